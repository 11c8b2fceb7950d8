//! Reads arbitrary bytes as SitLog/Prolog text; every clause read must print
//! (writeq) to text that reads back as the same term (round trip). Never a
//! panic, whatever the input.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sitlog_syntax::{read_clauses_bytes, read_term, writeq};

fuzz_target!(|data: &[u8]| {
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
