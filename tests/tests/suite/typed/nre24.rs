//! Helper `nre24` (issue 37): walks whose every step calls a DM that
//! native code does not push (the exit arc's action is a user function),
//! then a situation that runs natively, so the walker's frame is entered
//! again from the machine at each place (`tests/typed/nre24`): its lists
//! (the parameter, the id's rest, what was seen so far built on the list
//! handed back) converted once and shared after (`native::memo`). Each run
//! with lists long enough to be remembered and short ones, bad inputs
//! (unbound elements, open and improper tails, `1` against `1.0`,
//! compounds, nested lists, an element L evaluates), on the compiled task
//! and on the interpreter's plans against the interpreter, with and
//! without history.

use super::{agree_both, interpreter, with_engine};
use sitlog_runtime::app;
use std::panic::{catch_unwind, AssertUnwindSafe};

mod dms {
    pub mod note_walk {
        sitlog_macros::include_dm!("typed/nre24/n24_d_note_walk");
    }
    pub mod tally {
        sitlog_macros::include_dm!("typed/nre24/n24_tally");
    }
}

/// [`agree_both`] on each main DM call of `mains`, every one even after
/// one disagrees (the failure names all that do), the DMs' Prolog loaded
/// once.
fn agree_all<A: app::App>(compiled: &A, dir: &str, mains: &[String]) {
    let ir = interpreter(dir);
    let bad: Vec<String> = with_engine(&ir, || {
        mains
            .iter()
            .filter_map(|main| {
                catch_unwind(AssertUnwindSafe(|| agree_both(compiled, &ir, &[main])))
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
            .collect()
    });
    assert!(
        bad.is_empty(),
        "{} disagree:\n{}",
        bad.len(),
        bad.join("\n\n")
    );
}

/// `p0, .., p<n-1>`, then `tail` (a list's text without its brackets).
fn places(n: usize, tail: &str) -> String {
    let mut items: Vec<String> = (0..n).map(|i| format!("p{i}")).collect();
    if !tail.is_empty() {
        items.push(tail.to_owned());
    }
    items.join(", ")
}

/// The lists each walk is run on: long (remembered) and short, found,
/// missing, empty, bad elements and tails.
fn lists() -> Vec<(String, &'static str)> {
    vec![
        (format!("[{}]", places(12, "")), "p9"),
        (format!("[{}]", places(12, "")), "none"),
        (format!("[{}]", places(3, "")), "p1"),
        ("[]".to_owned(), "p0"),
        (format!("[{}]", places(10, "X")), "p9"),
        (format!("[{}]", places(10, "X")), "zz"),
        (format!("[{}|T]", places(10, "")), "zz"),
        (format!("[{}|z]", places(10, "")), "zz"),
        ("[1, 2, 3, 4, 5, 6, 7, 8, 9, 1.0, 10]".to_owned(), "1.0"),
        ("[1, 2, 3, 4, 5, 6, 7, 8, 9, 1.0, 10]".to_owned(), "10"),
        (
            format!("[{}, f(a), g([b]), [c, d], []]", places(8, "")),
            "[c, d]",
        ),
        (format!("[{}, f(a), g([b])]", places(8, "")), "g([b])"),
        (format!("[[{}], [{}]]", places(9, ""), places(8, "")), "x"),
        (format!("[{}, f(X), get(x, _)]", places(8, "")), "zz"),
        (format!("[{}]", places(40, "")), "p39"),
    ]
}

/// The walk of the workload `n24_d_note_walk`: one round and two, on
/// every list.
#[test]
fn note_walk_agrees() {
    let mut mains = Vec::new();
    for (list, want) in lists() {
        mains.push(format!("survey(1, {list}, {want})"));
        mains.push(format!("survey(2, {list}, {want})"));
    }
    mains.push("survey(2, L, p1)".to_owned());
    mains.push("survey(1, x, p1)".to_owned());
    agree_all(
        dms::note_walk::program(),
        "typed/nre24/n24_d_note_walk",
        &mains,
    );
}

/// What was seen so far, built on the list the machine handed back and
/// handed back by the final; integers compared with a limit.
#[test]
fn tally_and_over_agree() {
    let mut mains = Vec::new();
    for (list, want) in lists() {
        mains.push(format!("report({list}, {want})"));
    }
    let ints: Vec<String> = (0..30).map(|i| i.to_string()).collect();
    let ints = ints.join(", ");
    for main in [
        format!("over([{ints}], 25)"),
        format!("over([{ints}], 99)"),
        format!("over([{ints}], 2.5)"),
        format!("over([{ints}, 3.5, 40], 29)"),
        format!("over([{ints}, a, 40], 29)"),
        format!("over([{ints}, X, 40], 29)"),
        format!("over([{ints}|T], 99)"),
        "over([1, 2, 30], 5)".to_owned(),
        "over([], 5)".to_owned(),
        format!("over([{ints}], L)"),
    ] {
        mains.push(main);
    }
    agree_all(dms::tally::program(), "typed/nre24/n24_tally", &mains);
}
