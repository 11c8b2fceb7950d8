//! Helper `review25` (issue 37): workloads of shapes (c) and (d) written
//! after session 23 (`tests/typed/review25`), varied as another person
//! would write them: the count in the pipe and the limit a parameter passed
//! on unchanged through two nested calls (`N1 = N` in an exit arc); a
//! counter in the pipe and a rotating list in the recursive situation's
//! id; records `obj(Name, Place, Weight)` taken apart in the id with a
//! guard on an atom then an integer and a local read by `get` and written
//! by `set`; a list that enters as a Prolog user function's answer, the
//! caller's exit arcs tried in order (`at(kitchen)` before `at(_)`); a
//! callee whose in_arg is a list and whose out_arg the list filtered;
//! strings (code lists) as elements; a walk by mutual recursion of two
//! DMs, one call a place. Each run with bad inputs on the compiled task
//! and on the interpreter's plans against the interpreter (history,
//! report, error, actions, observer), with and without history.

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
    pub mod pass_limit {
        sitlog_macros::include_dm!("typed/review25/r25_c_pass_limit");
    }
    pub mod rota_list {
        sitlog_macros::include_dm!("typed/review25/r25_c_rota_list");
    }
    pub mod obj_records {
        sitlog_macros::include_dm!("typed/review25/r25_d_obj_records");
    }
    pub mod prolog_route {
        sitlog_macros::include_dm!("typed/review25/r25_d_prolog_route");
    }
    pub mod filter_out {
        sitlog_macros::include_dm!("typed/review25/r25_d_filter_out");
    }
    pub mod strings {
        sitlog_macros::include_dm!("typed/review25/r25_d_strings");
    }
    pub mod mutual_walk {
        sitlog_macros::include_dm!("typed/review25/r25_d_mutual_walk");
    }
}

/// (c) the limit a parameter passed on twice, the count the pipe: limits
/// 3, 1, 0, negative, a float, an atom and unbound and a compound (the
/// comparison raises); pipes a float, an atom, unbound, a list.
#[test]
fn pass_limit_agrees() {
    let ir = interpreter("typed/review25/r25_c_pass_limit");
    agree_mains_piped(
        dms::pass_limit::program(),
        &ir,
        &[
            ("lap(3)", "0"),
            ("lap(1)", "0"),
            ("lap(0)", "0"),
            ("lap(-2)", "0"),
            ("lap(2.5)", "0"),
            ("lap(a)", "0"),
            ("lap(_)", "0"),
            ("lap(f(1))", "0"),
            ("lap(3)", "0.5"),
            ("lap(3)", "a"),
            ("lap(3)", "_"),
            ("lap(3)", "[1]"),
            ("lap(3)", "5"),
        ],
    );
}

/// (c) a counter in the pipe, a list in the id: two of the crew and `cy`,
/// one, nobody (the refill loops: a limit of 0 stops on the first shift
/// only if there is one, so the crew is never empty here), an improper
/// crew, an unbound member, an open crew, a float limit, an atom limit and
/// an atom pipe (the arithmetic raises), a crew that is not a list.
#[test]
fn rota_list_agrees() {
    let ir = interpreter("typed/review25/r25_c_rota_list");
    agree_mains_piped(
        dms::rota_list::program(),
        &ir,
        &[
            ("rota(5, [ann, bob, cy])", "0"),
            ("rota(3, [cy])", "0"),
            ("rota(0, [ann])", "0"),
            ("rota(3, [ann|bob])", "0"),
            ("rota(3, [X, cy])", "0"),
            ("rota(2, [ann|T])", "0"),
            ("rota(2.5, [ann, cy])", "0"),
            ("rota(a, [ann])", "0"),
            ("rota(3, [ann])", "a"),
            ("rota(3, [ann])", "_"),
            ("rota(3, [ann])", "1.5"),
            ("rota(3, crew)", "0"),
        ],
    );
}

/// (d) records in the id: found, none heavy enough, none in the kitchen,
/// no objects, an element not a record (no `look` situation matches), an
/// improper tail, an unbound place (`\==` of an unbound), an unbound or
/// atom weight (the comparison raises), an unbound limit, a float limit,
/// an open tail, rounds an atom or zero.
#[test]
fn obj_records_agrees() {
    let ir = interpreter("typed/review25/r25_d_obj_records");
    agree_all(
        dms::obj_records::program(),
        &ir,
        &[
            "haul(2, [obj(box, hall, 9), obj(pan, kitchen, 3), obj(pot, kitchen, 7)], 5)",
            "haul(2, [obj(pan, kitchen, 3)], 5)",
            "haul(2, [obj(box, hall, 9)], 5)",
            "haul(2, [], 5)",
            "haul(2, [obj(box, hall, 9), pot], 5)",
            "haul(2, [obj(box, hall, 9)|x], 5)",
            "haul(2, [obj(box, P, 9)], 5)",
            "haul(2, [obj(box, kitchen, W)], 5)",
            "haul(2, [obj(box, kitchen, heavy)], 5)",
            "haul(2, [obj(box, kitchen, 9)], _)",
            "haul(2, [obj(box, kitchen, 9)], 8.5)",
            "haul(1, [obj(box, hall, 9)|T], 5)",
            "haul(x, [obj(box, kitchen, 9)], 5)",
            "haul(0, [obj(box, kitchen, 9)], 5)",
        ],
    );
}

/// (d) the list a Prolog function's answer: the kitchen (the first exit
/// arc), another place (the second), missing, every stop `hall` (an empty
/// route), no stops, an improper list (the function fails: an error of
/// the call), an unbound stop (bound to `hall` by the function), an open
/// list, an unbound target, rounds an atom.
#[test]
fn prolog_route_agrees() {
    let ir = interpreter("typed/review25/r25_d_prolog_route");
    let mut f = sitlog_runtime::Functions::standard();
    let engine = sitlog_compiler::run::install_prolog(&ir, &mut f, Default::default())
        .expect("the Prolog files load")
        .expect("an engine");
    ENGINE.with(|e| *e.borrow_mut() = Some((engine, false)));
    agree_all(
        dms::prolog_route::program(),
        &ir,
        &[
            "errand(2, [hall, kitchen, den], kitchen)",
            "errand(2, [hall, kitchen, den], den)",
            "errand(2, [hall, kitchen], attic)",
            "errand(2, [hall, hall], hall)",
            "errand(2, [], den)",
            "errand(2, [den|x], den)",
            "errand(2, [X, den], den)",
            "errand(1, [den|T], den)",
            "errand(2, [den, kitchen], _)",
            "errand(x, [den], den)",
        ],
    );
    ENGINE.with(|e| *e.borrow_mut() = None);
}

/// (d) a list in by in_arg, the filtered list out by out_arg: some
/// dropped, none, all, an empty list, an improper tail, an unbound element
/// (`\==` of an unbound), an unbound drop, an open tail, compounds, a
/// list not a list, rounds an atom.
#[test]
fn filter_out_agrees() {
    let ir = interpreter("typed/review25/r25_d_filter_out");
    agree_all(
        dms::filter_out::program(),
        &ir,
        &[
            "sweep(2, [hall, kitchen, den, hall], hall)",
            "sweep(2, [kitchen, den], hall)",
            "sweep(2, [hall, hall], hall)",
            "sweep(2, [], hall)",
            "sweep(2, [den|x], hall)",
            "sweep(2, [X, den], hall)",
            "sweep(2, [den, hall], _)",
            "sweep(1, [den|T], hall)",
            "sweep(2, [f(a), f(b), 1, 1.0], f(a))",
            "sweep(2, rooms, hall)",
            "sweep(x, [den], hall)",
        ],
    );
}

/// (d) strings as elements: found, missing, no goods, `"tea"` against the
/// atom `tea`, an empty string, an improper tail, an unbound string
/// wanted, an unbound element, an open tail, a string with an unbound
/// code, rounds an atom; the DM that calls with literal strings.
#[test]
fn strings_agree() {
    let ir = interpreter("typed/review25/r25_d_strings");
    agree_all(
        dms::strings::program(),
        &ir,
        &[
            "shop(2, [\"tea\", \"milk\", \"bread\"], \"milk\")",
            "shop(2, [\"tea\"], \"milk\")",
            "shop(2, [], \"milk\")",
            "shop(2, [\"tea\"], tea)",
            "shop(2, [\"\", \"tea\"], [])",
            "shop(2, [\"tea\"|x], \"milk\")",
            "shop(2, [\"tea\"], _)",
            "shop(2, [X, \"tea\"], \"tea\")",
            "shop(1, [\"tea\"|T], \"milk\")",
            "shop(2, [[116, C, 97]], \"tea\")",
            "shop(x, [\"tea\"], \"tea\")",
            "groceries",
        ],
    );
}

/// (d) mutual recursion, one call a place: found at each depth, missing,
/// no places, an improper tail, an unbound target, an unbound place, an
/// open tail, rounds an atom.
#[test]
fn mutual_walk_agrees() {
    let ir = interpreter("typed/review25/r25_d_mutual_walk");
    agree_all(
        dms::mutual_walk::program(),
        &ir,
        &[
            "stroll(2, [a, b, c], c)",
            "stroll(2, [a, b, c], a)",
            "stroll(2, [a, b, c], b)",
            "stroll(2, [a, b], z)",
            "stroll(2, [], z)",
            "stroll(2, [a, b|x], z)",
            "stroll(2, [a, b], _)",
            "stroll(2, [X, b], b)",
            "stroll(1, [a|T], z)",
            "stroll(x, [a], a)",
        ],
    );
}
