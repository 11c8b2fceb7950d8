//! Times reading, writing and re-reading deeply nested terms (a probe for
//! the robustness tests): `cargo run --release -p sitlog-syntax --example deep_probe`.
use sitlog_syntax::{read_term, writeq};
use std::time::Instant;
fn main() {
    let n = 100_000;
    let cases = [
        ("f(", format!("{}a{}", "f(".repeat(n), ")".repeat(n))),
        ("a,a", format!("({})", vec!["a"; n].join(","))),
        ("a-a", vec!["a"; n].join("-")),
        ("- - a", format!("{}a", "- ".repeat(n))),
        ("a:(", format!("{}a{}", "a : (".repeat(n), ")".repeat(n))),
    ];
    for (name, src) in cases {
        let t = Instant::now();
        let c = read_term(&src).unwrap();
        let read = t.elapsed();
        let t = Instant::now();
        let p = writeq(&c, c.root);
        let write = t.elapsed();
        let t = Instant::now();
        let c2 = read_term(&format!("{p} .")).unwrap();
        let reread = t.elapsed();
        assert!(c.is_variant_of(&c2));
        eprintln!("{name:8} read {read:?} write {write:?} reread {reread:?}");
    }
}
