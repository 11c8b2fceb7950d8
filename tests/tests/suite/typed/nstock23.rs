//! Helper `nstock23` (issue 37): DMs whose head has a pattern argument
//! (`first_of([X|_Rest])`, `same(p(A, B, on))`, `price(_Item-Cost)`,
//! `tests/typed/nstock23`), run natively: the pattern's variables taken
//! from the frame's parameter, a native caller pushing the callee only
//! where its argument matches the pattern (else the machine's call and
//! its error, E13). Each run with bad inputs (an argument that does not
//! match, unbound parts, open and improper tails, `1` against `1.0`) on
//! the compiled task and on the interpreter's plans against the
//! interpreter, with and without history.

use super::{agree_both, interpreter};
use sitlog_runtime::app;
use std::panic::{catch_unwind, AssertUnwindSafe};

mod dms {
    pub mod row_first {
        sitlog_macros::include_dm!("typed/nstock23/n23_row_first");
    }
    pub mod pair_same {
        sitlog_macros::include_dm!("typed/nstock23/n23_pair_same");
    }
    pub mod two_callers {
        sitlog_macros::include_dm!("typed/nstock23/n23_two_callers");
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

/// A list pattern head whose variable the callee's final carries back:
/// found, missing, no rows, an empty row and an atom row (the head does
/// not match), an unbound first cell, open tails, a non-list, numbers,
/// compounds.
#[test]
fn row_first_agrees() {
    let ir = interpreter("typed/nstock23/n23_row_first");
    agree_all(
        dms::row_first::program(),
        &ir,
        &[
            "table([[a, b], [c, d]], c)",
            "table([[a], [b]], z)",
            "table([], a)",
            "table([[a, b], []], z)",
            "table([[a, b], x], z)",
            "table([[X, b], [c]], c)",
            "table([[a|T]], z)",
            "table([[a, b]|T], z)",
            "table([[a, b]|x], z)",
            "table(x, a)",
            "table([[1.0]], 1)",
            "table([[f(a)], [g]], f(a))",
            "table([[a, b]], _)",
        ],
    );
}

/// A compound pattern with a constant inside, its two variables compared
/// by the callee's condition: agreeing and not, none, a constant that
/// differs or an arity that differs (no match), unbound parts (the
/// machine's unification binds them), `1` against `1.0`, an atom, open
/// and improper tails.
#[test]
fn pair_same_agrees() {
    let ir = interpreter("typed/nstock23/n23_pair_same");
    agree_all(
        dms::pair_same::program(),
        &ir,
        &[
            "agree([p(a, a, on), p(a, b, on), p(1, 1, on)])",
            "agree([])",
            "agree([p(a, a, off)])",
            "agree([p(a, a, on), p(a, a)])",
            "agree([p(X, X, on)])",
            "agree([p(X, Y, on)])",
            "agree([p(a, a, X)])",
            "agree([p(1, 1.0, on)])",
            "agree([q])",
            "agree([p(a, a, on)|T])",
            "agree([p(a, a, on)|x])",
            "agree([p(f(a), f(a), on), p([1], [1], on)])",
            // The callee as the main DM: its head unified with the
            // command line's call (E13 where it does not).
            "same(p(a, a, on))",
            "same(p(a, b, on))",
            "same(p(a, a, off))",
            "same(x)",
            "same(_)",
        ],
    );
}

/// One callee called with the caller's parameter and with list elements:
/// found, not, none, a parameter or an element that is not a pair (E13),
/// unbound costs, `2` against `2.0`, an unbound parameter, an open tail.
#[test]
fn two_callers_agree() {
    let ir = interpreter("typed/nstock23/n23_two_callers");
    agree_all(
        dms::two_callers::program(),
        &ir,
        &[
            "basket(a-2, [b-1, c-2, d-2])",
            "basket(a-2, [b-1])",
            "basket(a-2, [])",
            "basket(x, [b-1])",
            "basket(a-2, [b-1, c])",
            "basket(a-X, [b-1, c-2])",
            "basket(a-2, [b-X])",
            "basket(a-2.0, [b-2])",
            "basket(_, [b-1])",
            "basket(a-2, [b-1|T])",
        ],
    );
}
