//! Helper `neq25` (issue 37): `X = Y` in arcs' actions (D-30), which the
//! MIR lowers as a binding ([`Ev::BindFresh`]) where one side is a
//! variable not made yet that the other does not name, and leaves to the
//! evaluator's unification otherwise (`tests/typed/neq25`): fresh variables
//! bound to ints, atoms, lists, compounds with variables, an expression
//! left unevaluated; `=` between bound values that holds or fails (an
//! error, E7); in a neutral situation's arc, a recursive one's exit arc
//! (its out_arg) and the arc into a final one; compiled and on the
//! interpreter's plans against the interpreter, with history kept and not.
//!
//! [`Ev::BindFresh`]: sitlog_compiler::mir::Ev::BindFresh

use super::{agree_both, agree_piped, interpreter};
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

/// Each main DM call of `mains` started with the pipe `in_arg`, compiled
/// and on the interpreter's plans, against the interpreter.
fn agree_mains_piped<A: app::App>(compiled: &A, interpreted: &Ir, mains: &[(&str, &str)]) {
    let cases: Vec<String> = mains.iter().map(|(m, i)| format!("{m} <- {i}")).collect();
    each(&cases, |case| {
        let (main, in_arg) = case.split_once(" <- ").expect("a case");
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
    pub mod eq_actions {
        sitlog_macros::include_dm!("typed/neq25/eq_actions");
    }
}

/// Fresh variables bound by `=` (either side) to what `binds(A)`'s
/// argument is: an int (and `1`, which takes the other branch), an atom, a
/// compound with a variable, a variable, an open list, a float.
#[test]
fn binds_agree() {
    let ir = interpreter("typed/neq25/eq_actions");
    agree_all(
        dms::eq_actions::program(),
        &ir,
        &[
            "binds(1)",
            "binds(2)",
            "binds(foo)",
            "binds(f(X))",
            "binds(_)",
            "binds([a|T])",
            "binds(2.5)",
            "binds(\"ab\")",
        ],
    );
}

/// `X = A` binds, then `X = B` is the evaluator's unification of two
/// values: equal ints, `1` against `1.0` (fails: an error), atoms, other
/// atoms, compounds unifying by parts, compounds that differ, an unbound
/// side, lists, strings, an int against an atom.
#[test]
fn check_agree() {
    let ir = interpreter("typed/neq25/eq_actions");
    agree_all(
        dms::eq_actions::program(),
        &ir,
        &[
            "check(1, 1)",
            "check(1, 1.0)",
            "check(1.0, 1.0)",
            "check(a, a)",
            "check(a, b)",
            "check(f(1, X), f(Y, 2))",
            "check(f(1), f(2))",
            "check(_, 3)",
            "check([1, 2], [1, 2])",
            "check([1, 2], [1, 3])",
            "check(\"ab\", \"ab\")",
            "check(1, a)",
            "check(X, X)",
        ],
    );
}

/// `N1 = N` in a recursive situation's exit arc (its out_arg) and
/// `Y = X` in the callee's neutral arc (its out_arg): limits 3, 0, an
/// atom (the comparison raises); pipes 0, a float, unbound, an atom.
#[test]
fn loop_agrees() {
    let ir = interpreter("typed/neq25/eq_actions");
    agree_mains_piped(
        dms::eq_actions::program(),
        &ir,
        &[
            ("loop(3)", "0"),
            ("loop(0)", "0"),
            ("loop(a)", "0"),
            ("loop(3)", "1.5"),
            ("loop(2)", "_"),
            ("loop(2)", "a"),
            ("loop(2)", "[1]"),
        ],
    );
}

/// `=` in the arc into a final situation, its out_arg a compound of the
/// value bound: an int, an atom, a variable, a compound with a variable.
#[test]
fn wrap_agrees() {
    let ir = interpreter("typed/neq25/eq_actions");
    agree_mains_piped(
        dms::eq_actions::program(),
        &ir,
        &[
            ("wrap(5)", "0"),
            ("wrap(x)", "a"),
            ("wrap(_)", "_"),
            ("wrap(g(Y))", "0"),
        ],
    );
}
