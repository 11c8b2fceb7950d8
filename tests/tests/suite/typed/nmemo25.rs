//! Helper `nmemo25` (issue 37): lists remembered beside their terms
//! (`native::memo`) across collections and a cell at a time, both ways.
//! Accumulators (`[S|Seen]`) handed between native code and the machine at
//! every place (`typed/nmemo25/n25_d_tally_walk`), two lists built on one
//! tail, an accumulator whose last cell is a variable bound later
//! (`typed/nmemo25/n25_acc`), a global list grown a step (helper
//! `nglob24`'s `typed/nglob24`); long lists and short ones, bad ones, a
//! collection in the middle of a walk (a GC threshold of one cell: the
//! machine collects at every check), on the compiled task and on the
//! interpreter's plans against the interpreter, with and without history.

use super::{agree_both, interpreter, run_with, with_engine, Options};
use sitlog_runtime::app;

mod dms {
    pub mod tally_walk {
        sitlog_macros::include_dm!("typed/nmemo25/n25_d_tally_walk");
    }
    pub mod acc {
        sitlog_macros::include_dm!("typed/nmemo25/n25_acc");
    }
    pub mod grow_list {
        sitlog_macros::include_dm!("typed/nglob24/g24_d_grow_list");
    }
    pub mod two_writers {
        sitlog_macros::include_dm!("typed/nglob24/g24_d_two_writers");
    }
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
        (
            format!("[{}, f(a), g([b]), [c, d], []]", places(8, "")),
            "[c, d]",
        ),
        (format!("[{}, f(X), get(x, _)]", places(8, "")), "zz"),
        (format!("[{}]", places(60, "")), "p59"),
    ]
}

/// Each of `mains` on the compiled task and on the interpreter's plans
/// against the interpreter with a GC threshold of `threshold` cells, the
/// history kept and not (`prolog`: the DMs have user functions, loaded
/// once).
fn agree_collecting<A: app::App>(
    compiled: &A,
    dir: &str,
    mains: &[String],
    threshold: usize,
    prolog: bool,
) {
    let ir = interpreter(dir);
    let all = || {
        for main in mains {
            for keep_history in [false, true] {
                let options = || Options {
                    keep_history,
                    gc_threshold: threshold,
                    ..Options::default()
                };
                let i = run_with(&ir, main, None, "", options(), false, false);
                let c = run_with(compiled, main, None, "", options(), false, false);
                assert_eq!(
                    c, i,
                    "{main}, GC threshold {threshold}, history {keep_history}"
                );
                let r = sitlog_compiler::interp::Resolved::new(&ir);
                let p = run_with(&r, main, None, "", options(), false, false);
                assert_eq!(
                    p, i,
                    "{main} (plans), GC threshold {threshold}, history {keep_history}"
                );
            }
        }
    };
    if prolog {
        with_engine(&ir, all);
    } else {
        all();
    }
}

/// The accumulator walk of the workload `n25_d_tally_walk`: one round and
/// two, on every list; then long walks collected in the middle.
#[test]
fn tally_walk_agrees() {
    let dir = "typed/nmemo25/n25_d_tally_walk";
    let mut mains = Vec::new();
    for (list, want) in lists() {
        mains.push(format!("survey(1, {list}, {want})"));
        mains.push(format!("survey(2, {list}, {want})"));
    }
    mains.push("survey(2, L, p1)".to_owned());
    mains.push("survey(1, x, p1)".to_owned());
    let ir = interpreter(dir);
    with_engine(&ir, || {
        let mains: Vec<&str> = mains.iter().map(String::as_str).collect();
        agree_both(dms::tally_walk::program(), &ir, &mains);
    });
    let long = vec![
        format!("survey(2, [{}], p149)", places(150, "")),
        format!("survey(2, [{}], zz)", places(40, "")),
    ];
    for threshold in [1, 3000] {
        agree_collecting(dms::tally_walk::program(), dir, &long, threshold, true);
    }
}

/// Two lists on one tail, and an accumulator over a variable bound later,
/// on every list, then collected in the middle.
#[test]
fn accumulators_agree() {
    let dir = "typed/nmemo25/n25_acc";
    let mut mains = Vec::new();
    for (list, want) in lists() {
        mains.push(format!("pair({list}, {want})"));
        mains.push(format!("bound({list}, {want})"));
    }
    let ir = interpreter(dir);
    with_engine(&ir, || {
        let ms: Vec<&str> = mains.iter().map(String::as_str).collect();
        agree_both(dms::acc::program(), &ir, &ms);
    });
    let long = vec![
        format!("pair([{}], p119)", places(120, "")),
        format!("pair([{}], zz)", places(30, "")),
        format!("bound([{}], p3)", places(120, "")),
        format!("bound([{}], zz)", places(30, "")),
    ];
    for threshold in [1, 3000] {
        agree_collecting(dms::acc::program(), dir, &long, threshold, true);
    }
}

/// Helper `nglob24`'s global list grown a step and read at each step:
/// 1, 2, 9 and 300 steps, a budget that is no number, a float budget;
/// collected in the middle.
#[test]
fn grow_list_agrees() {
    let dir = "typed/nglob24/g24_d_grow_list";
    let ir = interpreter(dir);
    agree_both(
        dms::grow_list::program(),
        &ir,
        &[
            "gather(1)",
            "gather(2)",
            "gather(9)",
            "gather(300)",
            "gather(0)",
            "gather(x)",
            "gather(2.5)",
            "gather(_)",
        ],
    );
    let long = vec!["gather(400)".to_owned(), "gather(20)".to_owned()];
    for threshold in [1, 600] {
        agree_collecting(dms::grow_list::program(), dir, &long, threshold, false);
    }
}

/// The machine's `set` between two native reads of the same global: each
/// native read sees the machine's list.
#[test]
fn two_writers_agree() {
    let dir = "typed/nglob24/g24_d_two_writers";
    let ir = interpreter(dir);
    agree_both(
        dms::two_writers::program(),
        &ir,
        &[
            "mix(1)", "mix(2)", "mix(7)", "mix(x)", "mix(1.5)", "mix(200)",
        ],
    );
    agree_collecting(
        dms::two_writers::program(),
        dir,
        &["mix(300)".to_owned()],
        1,
        false,
    );
}
