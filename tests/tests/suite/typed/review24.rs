//! Helper `review24` (issue 37): workloads of shapes (c) and (d) written
//! after session 22 (`tests/typed/review24`), varied as another person
//! would write them: a callee giving two results (the pipe and a value
//! bound through its parameter by `diag_mod`), two nested embedded DMs
//! with a float count in the id, integers compared by `<` and `>` in a
//! nested guard against a global with three exits and the rounds in the
//! pipe, pairs searched by their first part with the place said once a
//! round, a recursive walker whose id holds two lists and calls a DM per
//! element on quoted atoms, floats compared by a plain Prolog function
//! with `\==`; each run with bad inputs on the compiled task and on the
//! interpreter's plans against the interpreter (history, report, error,
//! actions, observer), with and without history.

use super::{agree_both, agree_piped, interpreter, ENGINE};
use sitlog_compiler::interp::Resolved;
use sitlog_compiler::ir::Ir;
use sitlog_runtime::app;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Runs `one` on each of `cases`, every one even after one disagrees: the
/// test fails naming all that disagree.
fn each<T: std::fmt::Display>(cases: &[T], one: impl Fn(&T)) {
    let bad: Vec<String> = cases
        .iter()
        .filter_map(|case| {
            catch_unwind(AssertUnwindSafe(|| one(case))).err().map(|e| {
                let msg = e
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| e.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                    .unwrap_or_default();
                format!("{case}: {msg}")
            })
        })
        .collect();
    assert!(
        bad.is_empty(),
        "{} of {} disagree:\n{}",
        bad.len(),
        cases.len(),
        bad.join("\n\n")
    );
}

/// [`agree_both`] on each main DM call of `mains`.
fn agree_all<A: app::App>(compiled: &A, interpreted: &Ir, mains: &[&str]) {
    each(mains, |main| agree_both(compiled, interpreted, &[main]));
}

/// Main DM `main` started with each pipe of `in_args`, compiled and on
/// the interpreter's plans, against the interpreter.
fn agree_pipes<A: app::App>(compiled: &A, interpreted: &Ir, main: &str, in_args: &[&str]) {
    each(in_args, |in_arg| {
        agree_piped(compiled, interpreted, main, Some(in_arg), "");
        agree_piped(
            &Resolved::new(interpreted),
            interpreted,
            main,
            Some(in_arg),
            "",
        );
    });
}

mod dms {
    pub mod winch_param {
        sitlog_macros::include_dm!("typed/review24/r24_c_winch_param");
    }
    pub mod mill_nested {
        sitlog_macros::include_dm!("typed/review24/r24_c_mill_nested");
    }
    pub mod gauge_guard {
        sitlog_macros::include_dm!("typed/review24/r24_d_gauge_guard");
    }
    pub mod where_pairs {
        sitlog_macros::include_dm!("typed/review24/r24_d_where_pairs");
    }
    pub mod sift_two_lists {
        sitlog_macros::include_dm!("typed/review24/r24_d_sift_two_lists");
    }
    pub mod near_floats {
        sitlog_macros::include_dm!("typed/review24/r24_d_near_floats");
    }
    pub mod float_is {
        sitlog_macros::include_dm!("typed/review24/r24_float_is");
    }
}

/// Float arithmetic of an arc's action in Rust (`float_expr.rs`): a
/// value, a float overflow and an int overflow inside (the machine's
/// errors), an unbound selector.
#[test]
fn float_is_agrees() {
    let ir = interpreter("typed/review24/r24_float_is");
    agree_all(
        dms::float_is::program(),
        &ir,
        &["scale(ok)", "scale(big)", "scale(huge)", "scale(_)"],
    );
}

/// (c) two results, the pipe and the caller's variable bound by the
/// callee's `diag_mod`: limits 3, 1, 0, negative, a float, an atom and
/// unbound (the callee's `jammed`), a compound, a list.
#[test]
fn winch_param_agrees() {
    let ir = interpreter("typed/review24/r24_c_winch_param");
    agree_pipes(
        dms::winch_param::program(),
        &ir,
        "winch",
        &["3", "1", "0", "-2", "2.5", "a", "_", "f(1)", "[1]"],
    );
}

/// (c) two nested calls, a float count: budgets 2.5, 3, 1, 0, negative
/// (`worn`), an atom and unbound and a compound (the comparison raises).
#[test]
fn mill_nested_agrees() {
    let ir = interpreter("typed/review24/r24_c_mill_nested");
    agree_pipes(
        dms::mill_nested::program(),
        &ir,
        "works",
        &["2.5", "3", "1", "0", "-1.0", "a", "_", "f(1)"],
    );
}

/// (d) a nested guard, three exits, the rounds in the pipe: found, none,
/// no readings, a negative reading (`error(negative(X))`), an improper
/// tail, an atom and an unbound reading (the comparison raises), floats,
/// an unbound or atom cap, an open tail, rounds an atom or zero.
#[test]
fn gauge_guard_agrees() {
    let ir = interpreter("typed/review24/r24_d_gauge_guard");
    agree_all(
        dms::gauge_guard::program(),
        &ir,
        &[
            "gauge(2, [3, 9, 12], 8)",
            "gauge(2, [3, 4], 8)",
            "gauge(2, [], 8)",
            "gauge(2, [3, -1, 12], 8)",
            "gauge(2, [3|x], 8)",
            "gauge(2, [3, a], 8)",
            "gauge(2, [X, 9], 8)",
            "gauge(2, [1.5, 8.5], 8)",
            "gauge(2, [9], _)",
            "gauge(2, [9], a)",
            "gauge(1, [3|T], 8)",
            "gauge(x, [9], 8)",
            "gauge(0, [9], 8)",
        ],
    );
}

/// (d) pairs by their first part, the place said by the caller: found,
/// missing, nobody, an element not a pair (no `look` situation matches),
/// an improper tail, an unbound name wanted, an unbound name, `1` against
/// `1.0`, compound names, an open tail, rounds an atom, an unbound place
/// said.
#[test]
fn where_pairs_agrees() {
    let ir = interpreter("typed/review24/r24_d_where_pairs");
    agree_all(
        dms::where_pairs::program(),
        &ir,
        &[
            "where(2, [ann-kitchen, bob-hall], bob)",
            "where(2, [ann-kitchen], zed)",
            "where(2, [], ann)",
            "where(2, [ann-kitchen, bob], bob)",
            "where(2, [ann-kitchen|x], zed)",
            "where(2, [ann-kitchen], _)",
            "where(2, [X-hall], bob)",
            "where(1, [1-a, 1.0-b], 1.0)",
            "where(1, [f(a)-k], f(a))",
            "where(1, [ann-kitchen|T], zed)",
            "where(x, [ann-k], ann)",
            "where(2, [ann-P], ann)",
        ],
    );
}

/// (d) two lists in the recursive walker's id, a DM a comparison: found,
/// missing, no items, an improper tail, an unbound item wanted, an
/// unbound item, `1` against `1.0`, compounds, an open tail, rounds an
/// atom.
#[test]
fn sift_two_lists_agrees() {
    let ir = interpreter("typed/review24/r24_d_sift_two_lists");
    agree_all(
        dms::sift_two_lists::program(),
        &ir,
        &[
            "sort_room(2, ['red cup', 'blue box', 'old shoe'], 'blue box')",
            "sort_room(2, ['red cup'], x)",
            "sort_room(2, [], x)",
            "sort_room(2, [a|b], z)",
            "sort_room(2, [a, b], _)",
            "sort_room(2, [X, b], b)",
            "sort_room(1, [1, 1.0], 1.0)",
            "sort_room(1, [f(X), f(1)], f(1))",
            "sort_room(1, [a|T], z)",
            "sort_room(x, [a], a)",
        ],
    );
}

/// (d) floats by a plain Prolog function: found, none, no frequencies,
/// an improper tail, an atom (the function's arithmetic raises),
/// integers, an unbound target, an unbound frequency, an open tail,
/// rounds an atom.
#[test]
fn near_floats_agrees() {
    let ir = interpreter("typed/review24/r24_d_near_floats");
    let mut f = sitlog_runtime::Functions::standard();
    let engine = sitlog_compiler::run::install_prolog(&ir, &mut f, Default::default())
        .expect("the Prolog files load")
        .expect("an engine");
    ENGINE.with(|e| *e.borrow_mut() = Some((engine, false)));
    agree_all(
        dms::near_floats::program(),
        &ir,
        &[
            "tune(2, [1.0, 2.5, 3.04], 3.0)",
            "tune(2, [1.0, 2.5], 3.0)",
            "tune(2, [], 3.0)",
            "tune(2, [1.0|x], 3.0)",
            "tune(2, [1.0, a], 3.0)",
            "tune(2, [1, 3], 3)",
            "tune(2, [1.0], _)",
            "tune(2, [X, 3.0], 3.0)",
            "tune(1, [1.0|T], 3.0)",
            "tune(x, [3.0], 3.0)",
        ],
    );
    ENGINE.with(|e| *e.borrow_mut() = None);
}
