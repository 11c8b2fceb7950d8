//! Helper `npipe25` (issue 37): a native in_arg reading the whole pipe
//! where a native out_arg left it held (`Cx::pipe_as`,
//! `tests/typed/npipe25`): a list handed to a callee and back, of atoms,
//! compounds, floats, with an unbound cell, an improper or open tail,
//! empty; the pipe unchanged, boxed, made an int; an int or an atom as the
//! list; a compound held as its arguments read whole; the pipe read and
//! rewritten by the machine between, ground or not. Compiled and on the
//! interpreter's plans against the interpreter, history kept and none,
//! observed or not (`agree_both`).

use super::{agree_both, interpreter};

mod dms {
    sitlog_macros::include_dm!("typed/npipe25");
}

fn agree_all(mains: &[&str]) {
    let ir = interpreter("typed/npipe25");
    let mut bad = Vec::new();
    for main in mains {
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            agree_both(dms::program(), &ir, &[main])
        }));
        if r.is_err() {
            bad.push(*main);
        }
    }
    assert!(bad.is_empty(), "disagree: {bad:?}");
}

#[test]
fn lists_through_the_pipe_agree() {
    agree_all(&[
        "loop(3, [a, b, c], rev)",
        "loop(2, [f(1), g(a, [x]), []], rev)",
        "loop(2, [1.5, 2, \"ab\"], rev)",
        "loop(2, [a, X], rev)",
        "loop(2, [a|b], rev)",
        "loop(2, [a|T], rev)",
        "loop(2, [], rev)",
        "loop(1, [a, b], rev)",
        "loop(0, [a, b], rev)",
        "loop(2, [a, b], same)",
        "loop(2, [a, b], wrap)",
        "loop(2, [a, b], len)",
        "loop(2, 7, same)",
        "loop(2, atom, same)",
        "loop(2, 7, rev)",
        "loop(2, f(a), len)",
        "loop(2, [a], other)",
        "loop(2, [a], _)",
        "loop(x, [a, b], rev)",
    ]);
}

#[test]
fn held_compounds_and_the_machine_between_agree() {
    agree_all(&[
        "pairs(3, [a, b])",
        "pairs(2, f(x))",
        "pairs(2, [A])",
        "pairs(a, [])",
        "between(2, [a, b], x)",
        "between(3, [f(a), 1], g(b))",
        "between(2, [a, b], _)",
        "between(2, [], x)",
        "between(2, [a|t], x)",
    ]);
}
