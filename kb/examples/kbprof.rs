//! Profiling helper: generates a KB and runs one query repeatedly
//! (`kbprof N QUERY REPEAT`), printing the time per run.

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n = args
        .first()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let q = args
        .get(1)
        .cloned()
        .unwrap_or_else(|| "property_extension(loc, X)".into());
    let reps: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(5);
    let kb = sitlog_kb::gen::generate(n, 8);
    let Ok(c) = sitlog_syntax::read_term(&q) else {
        eprintln!("bad query");
        return;
    };
    for _ in 0..reps {
        let t = std::time::Instant::now();
        let ok = kb.call(&c).is_ok();
        println!("{q}: {:?} ({ok})", t.elapsed());
    }
}
