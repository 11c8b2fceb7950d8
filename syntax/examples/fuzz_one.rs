//! Runs the fuzz target's check on files (reproduces fuzz artifacts on
//! stable): `cargo run --release -p sitlog-syntax --example fuzz_one -- FILE...`.
use sitlog_syntax::{read_clauses_bytes, read_term, writeq};
use std::time::Instant;

fn main() {
    for path in std::env::args().skip(1) {
        let data = std::fs::read(&path).expect("readable file");
        let t = Instant::now();
        let (clauses, errors) = read_clauses_bytes(&data);
        let read = t.elapsed();
        let t = Instant::now();
        for clause in &clauses {
            let printed = writeq(clause, clause.root);
            let again = read_term(&format!("{printed} ."))
                .unwrap_or_else(|e| panic!("{printed:?} does not read back: {e:?}"));
            assert!(
                clause.is_variant_of(&again),
                "round trip changed {printed:?}"
            );
        }
        eprintln!(
            "{path}: {} clauses, {} errors, read {read:?}, round trip {:?}",
            clauses.len(),
            errors.len(),
            t.elapsed()
        );
    }
}
