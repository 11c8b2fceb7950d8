//! Helper `nfn19` (issue 37): plain Prolog user functions that take and
//! return compounds and lists (`tests/typed/plain_compounds`). The compiled
//! task and the interpreter's plans, with the plain forms run natively,
//! give what the interpreter gives with every call a query of the engine:
//! values built of the arguments, head patterns, a next situation that is
//! the function's value (`found(P)`, `walk(Ps)`, a non-list, an improper
//! list), and what the engine decides (a function that fails, one that
//! throws, one with no value, an unbound part); with `assertz/1` named in
//! the program, nothing is plain and the runs are the same.
//!
//! Not here: a value that holds an improper list (`walk([x|y])`,
//! `w([a|b])`): the engine fails such a call (its conversion of the answer
//! panics on the engine's thread, which then stops the engine for the
//! runs after it); the native form leaves it to the engine
//! (`prolog::plain`'s unit tests).

use super::{agree_plain, engine_of, interpreter, run, unnumbered, use_engine, Vs};

mod dms {
    pub mod plain_compounds {
        sitlog_macros::include_dm!("typed/plain_compounds");
    }
}

const MAINS: &[&str] = &[
    "main([c(wrap, a), c(pair, f(1)), c(head, [q, r]), c(tail, [q, r]), c(at, at(k, cup)), \
     c(same, f(a, [1])), c(same, f(a, [2])), c(same, f(a, [1.0])), c(bind, a), c(bind, b), \
     c(cut, a), c(twice, z), c(nil, 1), c(tail, [q|r]), c(wrap, 1.5), \
     c(wrap, 99999999999999999999), c(pair, [x, y])])",
    "main([c(err, a)])",
    "main([c(err, 1.5)])",
    "main([c(novalue, a)])",
    "main([c(cut, boom)])",
    "main([c(head, [])])",
    "main([c(head, q)])",
    "main([c(wrap, f(_))])",
    "main([c(tail, [_, a])])",
    "trip([a, b, c], c)",
    "trip([a, b, c], z)",
    "trip([], c)",
    "trip([a, skip, jump, b, c, d], d)",
    "trip([a, jump], d)",
    "trip([a, bad], z)",
    "trip([a|b], z)",
    "trip([a, err], z)",
    "trip([a, boom], z)",
    "trip([a, _, c], c)",
    "trip([a, b], _)",
    "trip([1, 1.0], 1.0)",
    "trip([f(x), g(_)], z)",
];

#[test]
fn plain_compounds_agree_with_the_engine() {
    let (ir, p) = agree_plain(
        dms::plain_compounds::program(),
        "typed/plain_compounds",
        "shape/2 step/3",
        MAINS,
        &[
            Vs::CompiledEngine,
            Vs::PlansEngine,
            Vs::InterpreterEngine,
            Vs::NoHistory,
        ],
    );
    // `assertz/1` named anywhere: nothing plain, the same runs.
    let ir_a = interpreter("typed/plain_compounds_assert");
    let pa = engine_of(&ir_a);
    assert!(pa.plain_functions().is_empty());
    for main in MAINS {
        use_engine(Some(&p), true);
        let by_engine = run(&ir, main, "", true, true, false);
        use_engine(Some(&pa), false);
        let a = run(&ir_a, main, "", true, true, false);
        assert_eq!(
            unnumbered(format!("{a:?}")).replace("plain_compounds_assert/", "plain_compounds/"),
            unnumbered(format!("{by_engine:?}")),
            "{main}: with assertz named / engine only"
        );
    }
    use_engine(None, false);
}
