//! Helper `nstock25` (issue 37): per-step costs of walks (shape d), run
//! natively and against the interpreter with bad inputs, with and without
//! history: a waiting variant that keeps no copy of the parameters its
//! exit arcs read (the frame's read after the call, one of them bound by
//! the callee meanwhile), and lists built cell by cell shared across
//! rounds (`tests/typed/nstock25`).

use super::{agree_both, interpreter};
use sitlog_runtime::app;
use std::panic::{catch_unwind, AssertUnwindSafe};

mod dms {
    pub mod wait_params {
        sitlog_macros::include_dm!("typed/nstock25/n25_wait_params");
    }
    pub mod bound_param {
        sitlog_macros::include_dm!("typed/nstock25/n25_bound_param");
    }
    pub mod passed_lists {
        sitlog_macros::include_dm!("typed/nstock25/n25_passed_lists");
    }
}

/// [`agree_both`] on each main DM call of `mains`, every one even after
/// one disagrees (the failure names all that do).
fn agree_all<A: app::App>(compiled: &A, ir: &sitlog_compiler::ir::Ir, mains: &[&str]) {
    let bad: Vec<String> = mains
        .iter()
        .filter_map(|main| {
            catch_unwind(AssertUnwindSafe(|| agree_both(compiled, ir, &[main])))
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
        "{} disagree:\n{}",
        bad.len(),
        bad.join("\n\n")
    );
}

/// Parameters read by the exit arcs after the call: found, under the
/// limit, missing, no stock, a tag of each shape (atom, number, list,
/// compound, unbound), an unbound target (bound by the first
/// expectation), an unbound limit (the comparison's error), an improper
/// stock, rounds an atom.
#[test]
fn wait_params_agrees() {
    let ir = interpreter("typed/nstock25/n25_wait_params");
    agree_all(
        dms::wait_params::program(),
        &ir,
        &[
            "shelf(2, [a-1, b-5, c-3], b, t, 2)",
            "shelf(2, [a-1, b-1, b-4], b, 7, 3)",
            "shelf(2, [a-1, b-5], z, [x, y], 0)",
            "shelf(2, [], a, f(g), 1)",
            "shelf(2, [a-1, b-5], b, T, 2)",
            "shelf(2, [a-1, b-5], W, t, 2)",
            "shelf(2, [a-1, b-5], W, t, 0)",
            "shelf(1, [a-1, b-5], b, t, _)",
            "shelf(1, [a-1|x], z, t, 0)",
            "shelf(1, [a-1, b], b, t, 0)",
            "shelf(1, [1-2, 1.0-3], 1.0, t, 0)",
            "shelf(x, [a-1], a, t, 0)",
        ],
    );
}

/// A parameter unbound at the walker's start and bound by its callee
/// while it waits: found first, later, never, no items, an unbound item,
/// compounds, an improper list, rounds an atom.
#[test]
fn bound_param_agrees() {
    let ir = interpreter("typed/nstock25/n25_bound_param");
    agree_all(
        dms::bound_param::program(),
        &ir,
        &[
            "fetch(2, [b, a])",
            "fetch(2, [a, c, b])",
            "fetch(2, [a, c])",
            "fetch(1, [])",
            "fetch(1, [X, b])",
            "fetch(1, [f(b), b])",
            "fetch(1, [a|b])",
            "fetch(x, [b])",
        ],
    );
}

/// Lists built cell by cell and shared between rounds: kept (each round
/// on the last one's cells), hit, no items, one item, numbers,
/// compounds, an unbound target, an improper list, rounds an atom.
#[test]
fn passed_lists_agrees() {
    let ir = interpreter("typed/nstock25/n25_passed_lists");
    agree_all(
        dms::passed_lists::program(),
        &ir,
        &[
            "rounds(3, [a, b, c], z)",
            "rounds(3, [a, b, c], b)",
            "rounds(2, [], a)",
            "rounds(4, [a], a)",
            "rounds(3, [1, 2, 3], 2.0)",
            "rounds(2, [f(a), g(b)], g(b))",
            "rounds(2, [a, b], _)",
            "rounds(2, [a|b], z)",
            "rounds(x, [a], a)",
        ],
    );
}
