//! Helper `review22` (issue 37): workloads of shapes (c) and (d) written
//! after sessions 19–20 (`tests/typed/review22`), varied as another person
//! would write them: the callee in its own file, a count in a global, a
//! local, the pipe or the id, recursion through two situations, three exit
//! arcs, a `say` per step, pairs compared by an exit arc's expectation,
//! integers by a plain Prolog function, the target in a local; each run
//! with bad inputs on the compiled task and on the interpreter's plans
//! against the interpreter (history, report, error, actions, observer),
//! with and without history.

use super::{agree_both, agree_piped, interpreter, ENGINE};
use sitlog_compiler::interp::Resolved;
use sitlog_compiler::ir::Ir;
use sitlog_runtime::app;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Runs `one` on each of `cases`, every one even after one disagrees: the
/// test fails naming all that disagree (a review's test reports every
/// finding at once).
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
    pub mod stage_global {
        sitlog_macros::include_dm!("typed/review22/r22_c_stage_global");
    }
    pub mod ferry_two {
        sitlog_macros::include_dm!("typed/review22/r22_c_ferry_two");
    }
    pub mod lap_pipe {
        sitlog_macros::include_dm!("typed/review22/r22_c_lap_pipe");
    }
    pub mod rung_id {
        sitlog_macros::include_dm!("typed/review22/r22_c_rung_id");
    }
    pub mod sweep_say {
        sitlog_macros::include_dm!("typed/review22/r22_d_sweep_say");
    }
    pub mod stock_expect {
        sitlog_macros::include_dm!("typed/review22/r22_d_stock_expect");
    }
    pub mod floor_fn {
        sitlog_macros::include_dm!("typed/review22/r22_d_floor_fn");
    }
    pub mod goal_local {
        sitlog_macros::include_dm!("typed/review22/r22_d_goal_local");
    }
}

/// (c) the callee in its own file, the count a global, three exit arcs:
/// budgets 3, 1, none left (a dud), negative, a float, an atom, unbound, a
/// compound, a list.
#[test]
fn stage_global_agrees() {
    let ir = interpreter("typed/review22/r22_c_stage_global");
    agree_pipes(
        dms::stage_global::program(),
        &ir,
        "launch",
        &["3", "1", "0", "-2", "2.5", "a", "_", "f(1)", "[1]"],
    );
}

/// (c) recursion through two situations, the limit also the callee's
/// argument, the count a local: 3, 1, 0, negative, a float, an atom,
/// unbound, a compound.
#[test]
fn ferry_two_agrees() {
    let ir = interpreter("typed/review22/r22_c_ferry_two");
    agree_pipes(
        dms::ferry_two::program(),
        &ir,
        "shuttle",
        &["3", "1", "0", "-1", "2.5", "a", "_", "f(2)"],
    );
}

/// (c) the count and the limit in the pipe, `lap(K, Max)`: 3, 1, 0, a
/// float, an atom, unbound, a compound.
#[test]
fn lap_pipe_agrees() {
    let ir = interpreter("typed/review22/r22_c_lap_pipe");
    agree_pipes(
        dms::lap_pipe::program(),
        &ir,
        "track",
        &["3", "1", "0", "2.5", "a", "_", "lap(1, 2)"],
    );
}

/// (c) the count in the id, `rung(_J is I + 1)`: 3, 1, 0, a float, an
/// atom, unbound, a compound.
#[test]
fn rung_id_agrees() {
    let ir = interpreter("typed/review22/r22_c_rung_id");
    agree_pipes(
        dms::rung_id::program(),
        &ir,
        "ladder",
        &["3", "1", "0", "2.5", "a", "_", "f(1)"],
    );
}

/// (d) a `say` per room, three exit arcs: found, missing, no rooms, an
/// improper tail, an unbound target, an unbound room, `1` against `1.0`,
/// compounds, pairs, an open tail, rounds an atom.
#[test]
fn sweep_say_agrees() {
    let ir = interpreter("typed/review22/r22_d_sweep_say");
    agree_all(
        dms::sweep_say::program(),
        &ir,
        &[
            "patrol(2, [a, b, c], b)",
            "patrol(2, [a, b], z)",
            "patrol(2, [], a)",
            "patrol(2, [a|b], z)",
            "patrol(2, [a, b], _)",
            "patrol(2, [X, b], b)",
            "patrol(1, [1, 1.0], 1.0)",
            "patrol(1, [f(a), f(b)], f(b))",
            "patrol(2, [a-1, b-2], b-2)",
            "patrol(1, [a|T], z)",
            "patrol(x, [a], a)",
        ],
    );
}

/// (d) pairs compared by an exit arc's expectation (`key(Want)` before
/// `key(_)`): found, missing, no stock, an element not a pair (the
/// callee's head does not match), an improper tail, an unbound target, an
/// unbound key, `1` against `1.0`, compound keys, an open tail, rounds an
/// atom.
#[test]
fn stock_expect_agrees() {
    let ir = interpreter("typed/review22/r22_d_stock_expect");
    agree_all(
        dms::stock_expect::program(),
        &ir,
        &[
            "inventory(2, [a-1, b-2, c-3], c)",
            "inventory(2, [a-1], z)",
            "inventory(2, [], a)",
            "inventory(2, [a-1, b], b)",
            "inventory(2, [a-1|x], z)",
            "inventory(2, [a-1, b-2], _)",
            "inventory(2, [X-1, b-2], b)",
            "inventory(1, [1-a, 1.0-b], 1.0)",
            "inventory(1, [f(a)-1], f(a))",
            "inventory(1, [a-1|T], z)",
            "inventory(x, [a-1], a)",
        ],
    );
}

/// (d) integers compared by a plain Prolog function: found, none, no
/// readings, an improper tail, an atom and an unbound reading (the
/// function's comparison raises), floats, an unbound or atom floor, an
/// open tail, rounds an atom.
#[test]
fn floor_fn_agrees() {
    let ir = interpreter("typed/review22/r22_d_floor_fn");
    let mut f = sitlog_runtime::Functions::standard();
    let engine = sitlog_compiler::run::install_prolog(&ir, &mut f, Default::default())
        .expect("the Prolog files load")
        .expect("an engine");
    ENGINE.with(|e| *e.borrow_mut() = Some((engine, false)));
    agree_all(
        dms::floor_fn::program(),
        &ir,
        &[
            "meter(2, [1, 5, 9], 5)",
            "meter(2, [1, 2], 5)",
            "meter(2, [], 5)",
            "meter(2, [1|x], 5)",
            "meter(2, [1, a, 9], 5)",
            "meter(2, [1, _, 9], 5)",
            "meter(2, [1.5, 7.0], 5)",
            "meter(2, [1], _)",
            "meter(2, [1], a)",
            "meter(1, [1|T], 5)",
            "meter(x, [9], 5)",
        ],
    );
    ENGINE.with(|e| *e.borrow_mut() = None);
}

/// (d) the walker in its own file, the target a local, two situations an
/// element, the rounds left in the pipe: found, missing, no spots, an
/// improper tail, an unbound goal, an unbound spot, `1` against `1.0`,
/// compounds, an open tail, rounds an atom, zero or a float.
#[test]
fn goal_local_agrees() {
    let ir = interpreter("typed/review22/r22_d_goal_local");
    agree_all(
        dms::goal_local::program(),
        &ir,
        &[
            "errands(2, [a, b, c], c)",
            "errands(2, [a, b], z)",
            "errands(2, [], a)",
            "errands(2, [a|b], z)",
            "errands(2, [a, b], _)",
            "errands(2, [X, b], b)",
            "errands(1, [1, 1.0], 1.0)",
            "errands(1, [f(X), f(1)], f(1))",
            "errands(1, [a|T], z)",
            "errands(x, [a], a)",
            "errands(0, [a], a)",
            "errands(2.0, [a], a)",
        ],
    );
}
