//! Helper `fid21` (issue 39): a run-time error that comes from a place in
//! the source names that place (file:line:column of the failing
//! expression, else of the arc, else of the situation) and the same text
//! in the compiled task, the interpreter's plans and the interpreter
//! (`tests/typed/fid21`): the runner's report with the location
//! `App::error_location` gives it.

use super::{functions, interpreter, ENGINE};
use sitlog_compiler::interp::Resolved;
use sitlog_runtime::machine::{Options, RunError};
use sitlog_runtime::testmode::{ScriptPerception, TextActions};
use sitlog_runtime::{app, Atom, Functions};

mod dms {
    pub mod fid21 {
        sitlog_macros::include_dm!("typed/fid21");
    }
}

/// One run of `main(case)`: its error as a runner reports it (with the
/// location the app gives, `App::error_location`, the workspace's path
/// cut), or `ok`.
fn error_of<A: app::App>(app: &A, case: &str, keep_history: bool) -> String {
    let mut perception = ScriptPerception::new("script", String::new());
    let mut text = Vec::new();
    let mut actions = TextActions::new(&mut text, vec![Atom::intern("say")]);
    let (outcome, _) = app::run(
        app,
        &format!("main({case})"),
        None,
        Options {
            keep_history,
            ..Options::default()
        },
        functions(),
        &mut perception,
        &mut actions,
        None,
    )
    .expect("runs");
    let Err(mut e): Result<(), RunError> = outcome.result else {
        return "ok".to_owned();
    };
    if let Some(at) = app.error_location(&e) {
        e.location = Some(at);
    }
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/");
    e.to_string().replace(root, "")
}

/// Each case's error, where the interpreter names it.
const WANT: &[(&str, &str)] = &[
    ("inc_atom", "in DM `main(inc_atom)`, situation `inc_atom`, arc 1 (typed/fid21/main.dm:8:39): `inc` of `name`: its value `bob` is not a number"),
    ("apply_fails", "in DM `main(apply_fails)`, situation `apply_fails`, arc 1 (typed/fid21/main.dm:10:30): user function `never/1` failed: `never/1` failed"),
    ("is_atom", "in DM `main(is_atom)`, situation `is_atom` (typed/fid21/main.dm:11:65): in `_G0 is bob+1`: Arithmetic: evaluable `bob/0' does not exist"),
    ("by_zero", "in DM `main(by_zero)`, situation `by_zero`, arc 1 (typed/fid21/main.dm:14:43): user function `ratio/2` failed: `ratio/2` raised error(evaluation_error(zero_divisor),(/)/2)"),
    ("no_situation", "in DM `main(no_situation)`, situation `no_situation`, arc 1 (typed/fid21/main.dm:16:18): there is no situation `[x,x]` in this DM"),
    ("unbound_action", "ok"),
    ("out_fails", "in DM `main(out_fails)`, situation `out_fails`, arc 1 (typed/fid21/main.dm:19:55): user function `never/1` failed: `never/1` failed"),
    ("call_fails", "in DM `main(call_fails)`, situation `call_fails` (typed/fid21/main.dm:21:68): user function `never/1` failed: `never/1` failed"),
    ("in_callee", "in DM `count(3)`, situation `step`, arc 1 (typed/fid21/main.dm:38:47): user function `ratio/2` failed: `ratio/2` raised error(evaluation_error(zero_divisor),(/)/2)"),
    ("overflow", "in DM `big`, situation `is`, arc 1 (typed/fid21/main.dm:45:26): `inc` of `n`: integer overflow"),
    ("compare_atom", "in DM `main(compare_atom)`, situation `compare_atom`, arc 1 (typed/fid21/main.dm:28:36): in `bob>2`: Arithmetic: evaluable `bob/0' does not exist"),
];

/// A run-time error that comes from a place in the source: the failing
/// expression (an `inc` of an atom, a user function that fails in an
/// action, an out_arg, a DM call's argument, a callee's native loop, an
/// `is` in a `prog`, an overflow, a comparison in a conditional), the arc
/// (a computed next situation that names none), each named at the same
/// `file:line:col` with the same text by the compiled task, the
/// interpreter's plans (`sitlogc run`) and the interpreter, history kept
/// and not.
#[test]
fn a_run_time_error_names_the_same_place_in_every_back_end() {
    let ir = interpreter("typed/fid21");
    // One engine for every run (the functions keep no state).
    let engine =
        sitlog_compiler::run::install_prolog(&ir, &mut Functions::standard(), Default::default())
            .expect("the Prolog files load")
            .expect("an engine");
    ENGINE.with(|e| *e.borrow_mut() = Some((engine, false)));
    let plans = Resolved::new(&ir);
    let mut bad = Vec::new();
    for &(case, want) in WANT {
        for keep in [false, true] {
            for (by, got) in [
                ("interpreter", error_of(&ir, case, keep)),
                ("plans", error_of(&plans, case, keep)),
                ("compiled", error_of(dms::fid21::program(), case, keep)),
            ] {
                if got != want {
                    bad.push(format!("{case} ({by}, history {keep}): {got}"));
                }
            }
        }
    }
    // One of them as a compiled task prints it (`error: ` and the text).
    let shown = format!(
        "error: {}",
        error_of(dms::fid21::program(), "in_callee", false)
    );
    ENGINE.with(|e| *e.borrow_mut() = None);
    assert!(bad.is_empty(), "{}", bad.join("\n"));
    insta::assert_snapshot!("fid21_compiled_error", shown);
}
