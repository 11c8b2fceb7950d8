//! Helper `nwinch25` (issue 37): a callee's output parameter bound by some
//! of its finals only (a final without `diag_mod` leaves the caller's
//! variable unbound), by all, by none, the caller's variable said,
//! compared and passed on after the call, and read unbound by the arcs of
//! a final that leaves it; type tests (`number/1`, `atom/1`, `is_list/1`,
//! ...) in conditions on native values of every kind, negated and in
//! combination with a comparison. Each compiled and on the interpreter's
//! plans against the interpreter, with and without history.

use super::{agree_both, agree_piped, interpreter};
use sitlog_compiler::interp::Resolved;

mod dms {
    pub mod outs {
        sitlog_macros::include_dm!("typed/nwinch25/outs");
    }
    pub mod kinds {
        sitlog_macros::include_dm!("typed/nwinch25/kinds");
    }
    pub mod typed {
        sitlog_macros::include_dm!("typed/nwinch25/typed");
    }
    pub mod tally_grade {
        sitlog_macros::include_dm!("typed/nwinch25/n25_c_tally_grade");
    }
}

/// The workload `n25_c_tally_grade` with pipes of each kind: ints (one,
/// several, zero and negative: `other`), a float, an atom, a string, a
/// list, a compound, unbound.
#[test]
fn tally_grade_agrees() {
    let ir = interpreter("typed/nwinch25/n25_c_tally_grade");
    for pipe in ["3", "1", "0", "-2", "2.5", "a", "\"s\"", "[1]", "f(1)", "_"] {
        agree_piped(dms::tally_grade::program(), &ir, "tally", Some(pipe), "");
        agree_piped(&Resolved::new(&ir), &ir, "tally", Some(pipe), "");
    }
}

/// Outputs bound by some finals, all, none; the variable said, compared
/// (`G > 10`), passed on (`two(Xs, G)`), read where it is unbound.
#[test]
fn outputs_some_finals_agree() {
    let ir = interpreter("typed/nwinch25/outs");
    agree_both(
        dms::outs::program(),
        &ir,
        &[
            "outs([3, 12, stop, x, 'hello world', 2.5, f(1), [a], []])",
            "outs([stop, stop])",
            "outs([1, _, stop])",
            "outs([])",
        ],
    );
}

/// A loop of shape (c) on `pick` (its `halt` leaves the output): limits,
/// pipes that are ints, an atom that halts, another atom, unbound.
#[test]
fn output_loop_agrees() {
    let ir = interpreter("typed/nwinch25/outs");
    for (main, pipe) in [
        ("loop(3)", "2"),
        ("loop(3)", "5"),
        ("loop(1)", "0"),
        ("loop(4)", "stop"),
        ("loop(4)", "x"),
        ("loop(4)", "_"),
        ("loop(2)", "1.5"),
        ("loop(a)", "1"),
    ] {
        agree_piped(dms::outs::program(), &ir, main, Some(pipe), "");
        agree_piped(&Resolved::new(&ir), &ir, main, Some(pipe), "");
    }
}

/// Every type test on a value of each kind: int, float, atom, quoted
/// atom, string, list, empty list, compound, unbound, partial list,
/// compound with a variable; `\+` of one, `\+ \+`.
#[test]
fn type_tests_agree() {
    let ir = interpreter("typed/nwinch25/kinds");
    let values = [
        "3",
        "-7",
        "2.5",
        "abc",
        "'hello world'",
        "\"str\"",
        "[1, 2]",
        "[]",
        "f(x)",
        "f(_)",
        "[a|_]",
        "_",
        "'[]'",
        "'.'(1, 2)",
    ];
    for v in values {
        let kinds = format!("kinds({v})");
        let both = format!("both({v})");
        let mixed = format!("mixed({v})");
        agree_both(dms::kinds::program(), &ir, &[&kinds, &both, &mixed]);
    }
}

/// Type tests the registers' types decide (int, float, lists, `[]`, an
/// atom) and those asked at run time of a typed register.
#[test]
fn typed_registers_agree() {
    let ir = interpreter("typed/nwinch25/typed");
    agree_both(dms::typed::program(), &ir, &["typed"]);
}
