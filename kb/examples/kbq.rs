//! `kbq KB [--do UPDATE]... QUERY`: the `sitlogc kb` convention as a small
//! stand-alone tool (the lead wires the same [`sitlog_kb::answer_line`] into
//! `sitlogc`). With `--cases FILE`, runs tab-separated lines
//! `KB<TAB>QUERY[<TAB>UPDATE]...` and prints one output line per case
//! (used for differential testing against the original). `--gen N DEPTH`
//! prints a generated KB.

use std::path::Path;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() == 3 && args[0] == "--gen" {
        let n = args[1].parse().unwrap_or(100);
        let depth = args[2].parse().unwrap_or(8);
        print!("{}", sitlog_kb::gen::generate_text(n, depth));
        return ExitCode::SUCCESS;
    }
    if args.len() == 2 && args[0] == "--cases" {
        let Ok(text) = std::fs::read_to_string(&args[1]) else {
            eprintln!("cannot read {}", args[1]);
            return ExitCode::FAILURE;
        };
        for line in text.lines() {
            let mut parts = line.split('\t');
            let (Some(kb), Some(q)) = (parts.next(), parts.next()) else {
                continue;
            };
            let dos: Vec<String> = parts.map(str::to_owned).collect();
            match sitlog_kb::answer_line(Path::new(kb), &dos, q) {
                Ok(out) => println!("{out}"),
                Err(e) => println!("error: {e}"),
            }
        }
        return ExitCode::SUCCESS;
    }
    let mut dos = Vec::new();
    let mut rest = Vec::new();
    let mut it = args.into_iter();
    while let Some(a) = it.next() {
        if a == "--do" {
            match it.next() {
                Some(d) => dos.push(d),
                None => {
                    eprintln!("--do needs an update");
                    return ExitCode::FAILURE;
                }
            }
        } else {
            rest.push(a);
        }
    }
    let [kb, query] = &rest[..] else {
        eprintln!("usage: kbq KB [--do UPDATE]... QUERY");
        return ExitCode::FAILURE;
    };
    match sitlog_kb::answer_line(Path::new(kb), &dos, query) {
        Ok(out) => {
            println!("{out}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}
