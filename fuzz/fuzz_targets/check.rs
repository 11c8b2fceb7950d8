//! Arbitrary bytes as a one-file application (`main.dm`), through load and
//! check; every diagnostic is rendered in the three forms (human, JSON,
//! short); a program that checks is lowered to the IR. Never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sitlog_compiler::{check, diag, ir, load};

fuzz_target!(|data: &[u8]| {
    let (program, diags) = load::load_source_bytes(&[("main.dm", data)]);
    let (result, diags) = check::check(program, diags);
    let sources = match &result {
        Ok(c) => &c.program().sources,
        Err(p) => &p.sources,
    };
    for d in &diags {
        diag::render_human(d, sources, false);
        diag::render_json(d, sources);
        diag::render_short(d, sources);
    }
    if let Ok(checked) = &result {
        ir::lower(checked);
    }
});
