//! Worlds of any size made up for the tests and benchmarks of loading and
//! settling a world ([`grid`]).

use std::fmt::Write;

/// A world file of `n` places in a grid 300 wide, 3 m apart, a route chain
/// through them, a shelf at each place and an object on each shelf.
pub fn grid(n: usize) -> String {
    let mut out = String::with_capacity(n * 160);
    out.push_str("seed = 1\n[robot]\nname = \"R\"\nat = \"p0\"\n[user]\nname = \"U\"\nat = \"p0\"\nsays = []\n");
    for i in 0..n {
        let (x, y) = ((i % 300) as f64 * 3.0, (i / 300) as f64 * 3.0);
        let _ = writeln!(out, "[[place]]\nname = \"p{i}\"\nx = {x:.1}\ny = {y:.1}");
    }
    for i in 1..n {
        let _ = writeln!(out, "[[route]]\nfrom = \"p{}\"\nto = \"p{i}\"", i - 1);
    }
    for i in 0..n {
        let _ = writeln!(out, "[[shelf]]\nname = \"s{i}\"\nat = \"p{i}\"");
    }
    for i in 0..n {
        let _ = writeln!(out, "[[object]]\nname = \"o{i}\"\non = \"s{i}\"");
    }
    out
}
