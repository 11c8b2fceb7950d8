//! Speed of the lexer and reader on a generated DM text (40 000 lines by
//! default; invented content shaped like SitLog DMs: situations, arcs,
//! `==>` pairs, quoted speech, numbers, comments).
//!
//!     cargo run --release -p sitlog-syntax --example bench_read [LINES]

use sitlog_syntax::read_clauses;
use std::fmt::Write;
use std::time::Instant;

/// A DM-shaped text of about `lines` lines.
pub fn generate(lines: usize) -> String {
    let mut s = String::new();
    let mut n = 0;
    let mut dm = 0;
    while s.lines().count() < lines {
        dm += 1;
        let _ = writeln!(
            s,
            "% dialogue model number {dm}\ndiag_mod(task_{dm}(Obj, Place, Status),\n["
        );
        for sit in 0..20 {
            n += 1;
            let _ = write!(
                s,
                "\t[\n\t\tid ==> step_{sit}(N),\n\t\ttype ==> neutral,\n\t\tin_arg ==> [X, Y|_],\n\
                 \t\tembedded_dm ==> move(Place, _Result),\n\
                 \t\tarcs ==> [\n\
                 \t\t\tsuccess(R) : [say('I am at the place number {n}, hello there'), tilt(-30.0), set(tries, 0)] => step_{}(N),\n\
                 \t\t\terror : [apply(inc(T_), [tries]), pan(0.5 * 2)] => error, % retry later\n\
                 \t\t\tstatus(S) : (S == ok -> empty | otherwise -> say(fail)) => is\n\
                 \t\t]\n\t]",
                sit + 1
            );
            s.push_str(if sit < 19 { ",\n" } else { "\n" });
        }
        s.push_str("],\n[tries ==> 0, last ==> 'none', scale ==> 1.25]\n).\n\n");
    }
    s
}

fn main() {
    let lines: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(40_000);
    let src = generate(lines);
    let mut best_lex = f64::MAX;
    let mut best_read = f64::MAX;
    let mut tokens = 0;
    for _ in 0..5 {
        let t = Instant::now();
        tokens = sitlog_syntax::read::count_tokens(&src).expect("lexes");
        best_lex = best_lex.min(t.elapsed().as_secs_f64());
        let t = Instant::now();
        let (clauses, errors) = read_clauses(&src);
        best_read = best_read.min(t.elapsed().as_secs_f64());
        assert!(errors.is_empty(), "{errors:?}");
        assert!(!clauses.is_empty());
    }
    println!(
        "{} lines, {} bytes, {tokens} tokens: lex {:.1} ms ({:.2} Mtok/s, {:.0} ns/token), read {:.1} ms ({:.2} Mtok/s)",
        src.lines().count(),
        src.len(),
        best_lex * 1e3,
        tokens as f64 / best_lex / 1e6,
        best_lex * 1e9 / tokens as f64,
        best_read * 1e3,
        tokens as f64 / best_read / 1e6
    );
}
