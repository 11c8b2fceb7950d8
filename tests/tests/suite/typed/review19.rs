//! Helper `review19` (issue 37): workloads of shapes (c) and (d) written
//! without reading `tests/typed/shapes`, `tests/typed/review17` or
//! `tests/typed/review18` (`tests/typed/review19`), each run with bad
//! inputs (a non-number compared, an unbound variable, an empty list, an
//! improper tail, a callee ending in a final no exit arc matches, a
//! function that fails) on the compiled task and on the interpreter's
//! plans against the interpreter (history, report, error, actions,
//! observer), with and without history.

use super::{agree_both, agree_piped, interpreter, with_engine};
use sitlog_compiler::interp::Resolved;
use sitlog_compiler::ir::Ir;
use sitlog_runtime::app;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// [`agree_both`] on each of `mains`, every one run even after one
/// disagrees: the test fails naming all that disagree (a review's test
/// reports every finding at once).
fn agree_all<A: app::App>(compiled: &A, interpreted: &Ir, mains: &[&str]) {
    let bad: Vec<String> = mains
        .iter()
        .filter_map(|main| {
            catch_unwind(AssertUnwindSafe(|| {
                agree_both(compiled, interpreted, &[main]);
            }))
            .err()
            .map(|e| {
                let msg = e
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| e.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                    .unwrap_or_default();
                format!("{main}: {msg}")
            })
        })
        .collect();
    assert!(
        bad.is_empty(),
        "{} of {} disagree:\n{}",
        bad.len(),
        mains.len(),
        bad.join("\n\n")
    );
}

mod dms {
    pub mod shelves {
        sitlog_macros::include_dm!("typed/review19/r19_d_shelves");
    }
    pub mod collect_out {
        sitlog_macros::include_dm!("typed/review19/r19_d_collect_out");
    }
    pub mod done_pair {
        sitlog_macros::include_dm!("typed/review19/r19_c_done_pair");
    }
    pub mod done_nomatch {
        sitlog_macros::include_dm!("typed/review19/r19_v_done_nomatch");
    }
    pub mod global_goal {
        sitlog_macros::include_dm!("typed/review19/r19_d_global_goal");
    }
    pub mod ping_pong {
        sitlog_macros::include_dm!("typed/review19/r19_c_ping_pong");
    }
    pub mod chain3 {
        sitlog_macros::include_dm!("typed/review19/r19_d_chain3");
    }
    pub mod when_qty {
        sitlog_macros::include_dm!("typed/review19/r19_d_when_qty");
    }
    pub mod prolog_first {
        sitlog_macros::include_dm!("typed/review19/r19_d_prolog_first");
    }
}

/// (d) a list of lists: found, missing, no shelves, an empty shelf, an
/// improper tail of a shelf and of the shelves, a shelf not a list, an
/// unbound item sought, unbound shelves, an open tail, `1` against `1.0`,
/// rounds an atom.
#[test]
fn shelves_agree() {
    let ir = interpreter("typed/review19/r19_d_shelves");
    agree_all(
        dms::shelves::program(),
        &ir,
        &[
            "pick(2, [[a, b], [c, d], [e]], e)",
            "pick(2, [[a, b], [c]], z)",
            "pick(2, [], a)",
            "pick(2, [[], [a]], a)",
            "pick(2, [[a|x], [b]], b)",
            "pick(2, [[a], [b]|x], z)",
            "pick(2, [a, [b]], b)",
            "pick(2, [[a, b]], _)",
            "pick(2, _, a)",
            "pick(1, [[a]|T], z)",
            "pick(1, [[a|T]], z)",
            "pick(1, [[1], [1.0]], 1.0)",
            "pick(1, [[X], [b]], b)",
            "pick(x, [[a]], a)",
        ],
    );
}

/// (d) a result list built in the id and handed back by out_arg: some
/// kept, none kept, no readings, a reading not a number, an unbound
/// reading, an unbound or atom limit, floats, an improper tail, an open
/// tail.
#[test]
fn collect_out_agrees() {
    let ir = interpreter("typed/review19/r19_d_collect_out");
    agree_all(
        dms::collect_out::program(),
        &ir,
        &[
            "harvest(2, [5, 12, 3, 40], 10)",
            "harvest(2, [5, 3], 10)",
            "harvest(2, [], 10)",
            "harvest(2, [5, a, 40], 10)",
            "harvest(2, [5, _, 40], 10)",
            "harvest(2, [5, 12], _)",
            "harvest(2, [5, 12], a)",
            "harvest(2, [1.5, 20, 10.0], 10)",
            "harvest(2, [5, 12|x], 10)",
            "harvest(1, [20|T], 10)",
            "harvest(1, [f(1), 20], 10)",
            "harvest(x, [20], 10)",
        ],
    );
}

/// (c) a final carrying a compound that the caller's exit arc
/// destructures: limits 3, 1, 0, a float, an atom, an unbound pipe, a
/// compound; then the variant whose callee ends in `done(X, big)`, which no
/// exit arc matches.
#[test]
fn done_pair_agrees() {
    let ir = interpreter("typed/review19/r19_c_done_pair");
    let nomatch = interpreter("typed/review19/r19_v_done_nomatch");
    for in_arg in ["3", "1", "0", "2.5", "a", "_", "f(2)", "[1]"] {
        agree_piped(dms::done_pair::program(), &ir, "relay", Some(in_arg), "");
        agree_piped(&Resolved::new(&ir), &ir, "relay", Some(in_arg), "");
    }
    for in_arg in ["3", "200", "a", "_"] {
        agree_piped(
            dms::done_nomatch::program(),
            &nomatch,
            "relay",
            Some(in_arg),
            "",
        );
        agree_piped(
            &Resolved::new(&nomatch),
            &nomatch,
            "relay",
            Some(in_arg),
            "",
        );
    }
}

/// (d) each spot compared with a global read at each visit: found,
/// missing, no spots, an improper tail, an unbound goal, an unbound spot,
/// `1` against `1.0`, compounds, rounds an atom.
#[test]
fn global_goal_agrees() {
    let ir = interpreter("typed/review19/r19_d_global_goal");
    agree_all(
        dms::global_goal::program(),
        &ir,
        &[
            "seek(2, [a, b, c], c)",
            "seek(2, [a, b], z)",
            "seek(2, [], a)",
            "seek(2, [a|b], z)",
            "seek(2, [a, b], _)",
            "seek(2, [X, b], b)",
            "seek(1, [1, 1.0], 1.0)",
            "seek(1, [f(a), f(b)], f(b))",
            "seek(1, [a|T], z)",
            "seek(x, [a], a)",
        ],
    );
}

/// (c) two DMs calling each other: depths 2, 0, negative, a float, an
/// atom, unbound, a compound; rounds an atom.
#[test]
fn ping_pong_agrees() {
    let ir = interpreter("typed/review19/r19_c_ping_pong");
    agree_all(
        dms::ping_pong::program(),
        &ir,
        &[
            "rally(2, 2)",
            "rally(1, 0)",
            "rally(1, -3)",
            "rally(1, 1.5)",
            "rally(1, a)",
            "rally(1, _)",
            "rally(1, f(1))",
            "rally(x, 1)",
            "rally(1, -9223372036854775808)",
        ],
    );
}

/// (d) three situations an element: found, missing, no boxes, an improper
/// tail, an unbound label, an unbound box, `1` against `1.0`, compounds.
#[test]
fn chain3_agrees() {
    let ir = interpreter("typed/review19/r19_d_chain3");
    agree_all(
        dms::chain3::program(),
        &ir,
        &[
            "audit(2, [a, b, c], c)",
            "audit(2, [a, b], z)",
            "audit(2, [], a)",
            "audit(2, [a|b], z)",
            "audit(2, [a, b], _)",
            "audit(2, [X, b], b)",
            "audit(1, [1, 1.0], 1.0)",
            "audit(1, [f(X), f(1)], f(1))",
            "audit(1, [a|T], z)",
        ],
    );
}

/// (d) `when/3` on an integer field of `item(Name, Qty)`: enough, short,
/// no items, an improper tail, a quantity not a number, an unbound
/// quantity, an element not an item, an item of another arity, an unbound
/// or atom need, floats.
#[test]
fn when_qty_agrees() {
    let ir = interpreter("typed/review19/r19_d_when_qty");
    agree_all(
        dms::when_qty::program(),
        &ir,
        &[
            "order(2, [item(a, 1), item(b, 5)], 3)",
            "order(2, [item(a, 1), item(b, 2)], 3)",
            "order(2, [], 3)",
            "order(2, [item(a, 1)|x], 3)",
            "order(2, [item(a, x), item(b, 5)], 3)",
            "order(2, [item(a, _), item(b, 5)], 3)",
            "order(2, [a, item(b, 5)], 3)",
            "order(2, [item(a, 1, 2), item(b, 5)], 3)",
            "order(2, [item(a, 1)], _)",
            "order(2, [item(a, 1)], a)",
            "order(2, [item(a, 1.5), item(b, 3.0)], 3)",
            "order(1, [item(a, 1)|T], 3)",
        ],
    );
}

/// (d) the first crate a Prolog user function accepts: found, none, no
/// crates, an improper tail, a weight the function cannot compare (an
/// atom, unbound), a weight for which it fails (negative), a float.
#[test]
fn prolog_first_agrees() {
    let ir = interpreter("typed/review19/r19_d_prolog_first");
    let mains = [
        "weigh(2, [3, 1000, 5])",
        "weigh(2, [3, 5])",
        "weigh(2, [])",
        "weigh(2, [3|x])",
        "weigh(2, [3, a, 1000])",
        "weigh(2, [3, _, 1000])",
        "weigh(2, [3, -1, 1000])",
        "weigh(2, [1000.5])",
        "weigh(1, [3|T])",
        "weigh(x, [1000])",
    ];
    with_engine(&ir, || agree_all(dms::prolog_first::program(), &ir, &mains));
}
