//! Reads arbitrary bytes as SitLog/Prolog text; every clause read must print
//! (writeq) to text that reads back as the same term (round trip). Never a
//! panic, whatever the input. Differential: on text that decodes, the
//! lexer's fast paths (`fast_token`, layout and one-character tokens in
//! Rust) give the same tokens, spans and errors as the grammar alone.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sitlog_syntax::{fast_path_disagreement, read_clauses_bytes, read_term, writeq};

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Some(diff) = fast_path_disagreement(text) {
            panic!("{diff}");
        }
    }
    let (clauses, _errors) = read_clauses_bytes(data);
    for clause in &clauses {
        let printed = writeq(clause, clause.root);
        let again = match read_term(&format!("{printed} .")) {
            Ok(c) => c,
            Err(e) => panic!("printed text does not read back: {printed:?}: {e:?}"),
        };
        assert!(
            clause.is_variant_of(&again),
            "round trip changed the term: {printed:?} -> {:?}",
            writeq(&again, again.root)
        );
    }
});
