//! Helper `review18` (issue 37): workloads of shapes (c) and (d) written
//! without reading `tests/typed/shapes` or `tests/typed/review17`
//! (`tests/typed/review18`), each run with bad inputs on the compiled task
//! and on the interpreter's plans against the interpreter (history,
//! report, error, actions, observer), with and without history.

use super::{agree, agree_app, agree_both, interpreter, with_engine};
use sitlog_compiler::interp::Resolved;

mod dms {
    pub mod deep_limit {
        sitlog_macros::include_dm!("typed/review18/r18_c_deep_limit");
    }
    pub mod clerk {
        sitlog_macros::include_dm!("typed/review18/r18_c_clerk_global");
    }
    pub mod item_qty {
        sitlog_macros::include_dm!("typed/review18/r18_d_item_qty");
    }
    pub mod room_of {
        sitlog_macros::include_dm!("typed/review18/r18_d_room_of");
    }
    pub mod fn_next {
        sitlog_macros::include_dm!("typed/review18/r18_d_fn_next");
    }
    pub mod callee_list {
        sitlog_macros::include_dm!("typed/review18/r18_d_callee_list");
    }
    pub mod yes_no {
        sitlog_macros::include_dm!("typed/review18/r18_d_yes_no");
    }
    pub mod lockstep {
        sitlog_macros::include_dm!("typed/review18/r18_d_lockstep");
    }
    pub mod lockstep_any {
        sitlog_macros::include_dm!("typed/review18/r18_d_lockstep_any");
    }
}

/// (c) three DMs deep, the limit in the pipe: a number, zero, a float, an
/// atom, an unbound variable and a compound where the count is compared.
#[test]
fn deep_limit_agrees() {
    agree_app(
        dms::deep_limit::program(),
        "typed/review18/r18_c_deep_limit",
        &[
            "top(3)",
            "top(0)",
            "top(2.5)",
            "top(abc)",
            "top(_)",
            "top(f(1))",
        ],
    );
}

/// (c) the callee choosing its final by a global compared with its
/// parameter: good limits, a float, an atom, unbound, a list.
#[test]
fn clerk_global_agrees() {
    agree_app(
        dms::clerk::program(),
        "typed/review18/r18_c_clerk_global",
        &[
            "boss(3)",
            "boss(1)",
            "boss(0)",
            "boss(1.5)",
            "boss(x)",
            "boss(_)",
            "boss([])",
        ],
    );
}

/// (d) `item(Name, Qty)` records: found, missing, an empty list, an
/// improper tail, a quantity that is not a number, an element that is not
/// an item, an unbound name sought, an unbound list, an item of another
/// arity, a float quantity, rounds not a number.
#[test]
fn item_qty_agrees() {
    agree_app(
        dms::item_qty::program(),
        "typed/review18/r18_d_item_qty",
        &[
            "stock(2, [item(a, 1), item(b, 2), item(c, 3)], c)",
            "stock(2, [item(a, 1), item(b, 2)], z)",
            "stock(2, [], c)",
            "stock(2, [item(a, 1)|t], z)",
            "stock(2, [item(a, x), item(b, 2)], b)",
            "stock(2, [a, item(b, 2)], b)",
            "stock(2, [item(a, 1), item(b, 2)], _)",
            "stock(2, _, b)",
            "stock(2, [item(a, 1, 2), item(b, 2)], b)",
            "stock(2, [item(a, 1.5), item(b, 2)], b)",
            "stock(x, [item(a, 1)], a)",
            "stock(1, [item(a, 9223372036854775807), item(b, 1), item(c, 1)], c)",
            "stock(1, [item(a, 1)|T], z)",
            "stock(1, [item(1, 1), item(1.0, 2)], 1.0)",
            "stock(1, [item(a, Q), item(b, 2)], b)",
        ],
    );
}

/// (d) `Room-Object` pairs, the object matched in the id (a repeated
/// variable): found at home, found elsewhere (`moved`), lost, an empty
/// list, an improper tail, an element not a pair, an unbound object (the
/// first pair's object matches it), an unbound home, rounds an atom; a
/// variable in the list that the id's match binds, `1` against `1.0`, an
/// unbound room, an open tail.
#[test]
fn room_of_agrees() {
    agree_app(
        dms::room_of::program(),
        "typed/review18/r18_d_room_of",
        &[
            "tidy(2, [k-cup, b-pen, l-box], pen, b)",
            "tidy(2, [k-cup, b-pen, l-box], pen, k)",
            "tidy(2, [k-cup, b-pen], sock, k)",
            "tidy(2, [], pen, k)",
            "tidy(2, [k-cup|b], pen, k)",
            "tidy(2, [cup, b-pen], pen, b)",
            "tidy(2, [k-cup, b-pen], _, k)",
            "tidy(2, [k-cup, b-pen], pen, _)",
            "tidy(2, [k-f(X), b-f(Y)], f(1), b)",
            "tidy(x, [k-cup], cup, k)",
            "tidy(1, [k-X, b-pen], pen, b)",
            "tidy(1, [k-1, b-1.0], 1.0, b)",
            "tidy(1, [k-1.0, b-1], 1, b)",
            "tidy(1, [R-cup], cup, k)",
            "tidy(1, [k-cup|T], pen, k)",
        ],
    );
}

/// (d) the next situation a Prolog user function's value: found, not
/// found, an empty list, an improper tail, an unbound target, a function
/// that fails (`boom`), a function giving no situation of the DM (`odd`).
#[test]
fn fn_next_agrees() {
    let ir = interpreter("typed/review18/r18_d_fn_next");
    // One engine for every run (`route/3` keeps no state): loading it per
    // run is minutes in a debug build.
    let mains = [
        "errand(2, [a, b, c], c)",
        "errand(2, [a, b], z)",
        "errand(2, [], c)",
        "errand(2, [a|b], z)",
        "errand(2, [a, b], _)",
        "errand(2, [a, boom, c], c)",
        "errand(2, [a, odd, c], c)",
        "errand(y, [a], a)",
        "errand(1, [a|T], z)",
        "errand(1, [1, 1.0], 1.0)",
    ];
    with_engine(&ir, || agree_both(dms::fn_next::program(), &ir, &mains));
}

/// (d) a callee's list walked by the caller: found, missing, no stops,
/// an improper tail, an unbound dock, an unbound list.
#[test]
fn callee_list_agrees() {
    agree_app(
        dms::callee_list::program(),
        "typed/review18/r18_d_callee_list",
        &[
            "courier(2, [a, b, c], a)",
            "courier(2, [a, b, c], z)",
            "courier(2, [], a)",
            "courier(2, [a, b|c], a)",
            "courier(2, [a, b], _)",
            "courier(2, _, a)",
            "courier(z, [a], a)",
            "courier(1, [1, 1.0], 1.0)",
            "courier(1, [a|T], z)",
            "courier(1, [X, b], b)",
        ],
    );
}

/// (d) a walk driven by a scripted user's `yes`/`no`: found, never, an
/// answer no arc expects, the script ending mid-walk, no places.
#[test]
fn yes_no_agrees() {
    let ir = interpreter("typed/review18/r18_d_yes_no");
    for (main, script) in [
        ("ask(2, [a, b, c])", "no.\nyes.\nno.\nno.\nyes.\n"),
        ("ask(1, [a, b])", "no.\nno.\n"),
        ("ask(1, [a, b])", "maybe.\nyes.\n"),
        ("ask(2, [a, b, c])", "no.\n"),
        ("ask(2, [])", ""),
        ("ask(1, [a|b])", "no.\n"),
    ] {
        agree(dms::yes_no::program(), &ir, main, script);
        agree(&Resolved::new(&ir), &ir, main, script);
    }
}

/// (d) two lists walked in step (`r18_d_lockstep`, `r18_d_lockstep_any`;
/// their generated Rust did not compile on main `0c8eab3`, E0505: fixed by
/// `nlock18`, see `sitlog-macros-ui`'s `review18_lockstep_compiles`): the
/// compiled task and the interpreter's plans against the interpreter, with
/// bad inputs (lists of different lengths either way, an improper tail in
/// the first or the second list, a non-number, an unbound threshold, an
/// overflow).
#[test]
fn lockstep_agrees() {
    let mains = [
        "gauge(2, [1, 2, 3], [4, 5, 6], 10)",
        "gauge(2, [1, 2, 3], [4, 5, 6], 100)",
        "gauge(2, [1, 2, 3], [4, 5], 10)",
        "gauge(2, [1, 2], [4, 5, 6], 10)",
        "gauge(2, [], [1], 0)",
        "gauge(2, [1], [], 0)",
        "gauge(2, [], [], 0)",
        "gauge(2, [1, a], [2, 3], 0)",
        "gauge(2, [1|x], [2|y], 0)",
        "gauge(2, [1, 2], [3|y], 0)",
        "gauge(2, [1, 2], [3, 4|y], 0)",
        "gauge(2, [1, 2|x], [3, 4], 0)",
        "gauge(2, [1, 2], [3, 4], _)",
        "gauge(1, [4611686018427387904], [2], 0)",
    ];
    agree_app(
        dms::lockstep::program(),
        "typed/review18/r18_d_lockstep",
        &mains,
    );
    agree_app(
        dms::lockstep_any::program(),
        "typed/review18/r18_d_lockstep_any",
        &mains,
    );
}
