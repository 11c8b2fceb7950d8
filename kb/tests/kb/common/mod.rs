#![allow(dead_code)]
use sitlog_kb::Kb;
use std::path::PathBuf;

pub fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// Runs updates then a query on KB text, giving the `sitlogc kb` line.
pub fn ask(kb: &str, dos: &[&str], query: &str) -> String {
    let mut kb = Kb::parse(kb, "<test>").unwrap_or_else(|e| panic!("{e}"));
    for d in dos {
        match kb.apply(d) {
            Ok(true) => {}
            Ok(false) => return "false".into(),
            Err(e) => panic!("{d}: {e}"),
        }
    }
    kb.query(query)
        .unwrap_or_else(|e| panic!("{query}: {e}"))
        .to_line()
}

pub fn ask_file(file: &str, dos: &[&str], query: &str) -> String {
    let dos: Vec<String> = dos.iter().map(|s| s.to_string()).collect();
    sitlog_kb::answer_line(&data(file), &dos, query).unwrap_or_else(|e| panic!("{e}"))
}
