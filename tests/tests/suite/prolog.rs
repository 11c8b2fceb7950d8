//! Prolog user functions (feature `prolog`): applications run with their
//! own `user_functions.pl` in the embedded engine.
#![cfg(feature = "prolog")]

use sitlog_runtime::machine::Options;
use sitlog_runtime::Functions;
use sitlog_tests::{normalize, run_example, run_sources_with, workspace};

/// Appendix A with Listing A5's f, g and h written in Prolog gives the
/// golden history (D-46); no Rust stand-in is registered.
#[test]
fn appendix_a_runs_its_prolog_functions() {
    let app = workspace().join("dms/examples/appendix_a");
    let expected: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(app.join("expected.json")).unwrap()).unwrap();
    assert_eq!(normalize(&run_example(&app)), normalize(&expected));
}

fn run_with_prolog(dm: &str, functions_pl: &str, script: &str) -> serde_json::Value {
    let files = [("main.dm", dm), ("user_functions.pl", functions_pl)];
    let (program, diags) = sitlog_compiler::load::load_sources(&files);
    let (checked, _) = sitlog_compiler::check::check(program, diags);
    let ir = sitlog_compiler::ir::lower(&checked.unwrap_or_else(|_| panic!("checks")));
    let mut functions = Functions::standard();
    sitlog_compiler::run::install_prolog(&ir, &mut functions, Default::default())
        .expect("Prolog loads");
    run_sources_with(&files, script, "main", None, Options::default(), functions)
}

/// A failing function stops the task with an error naming DM, situation
/// and the call; the history so far is kept.
#[test]
fn failing_function_is_a_task_error() {
    let dm = "diag_mod(main, [[id ==> is, type ==> speech, \
              arcs ==> [x : apply(bad(A), [1]) => fs]], [id ==> fs, type ==> final]], []).";
    let report = run_with_prolog(dm, "bad(_) :- fail.\n", "x.\n");
    assert_eq!(report["status"], "error", "{report}");
    let err = report["error"].as_str().unwrap();
    assert!(
        err.contains("main") && err.contains("bad/1") && err.contains("failed"),
        "{err}"
    );
}

/// Variables set by a function are seen by the next situation; values
/// read from the history come back as terms.
#[test]
fn functions_set_variables_and_read_history() {
    let dm = "diag_mod(main, [\
        [id ==> is, type ==> speech, \
         arcs ==> [x : [apply(count(A), [_])] => s2]], \
        [id ==> s2, type ==> speech, \
         arcs ==> [y : [get(n, N), apply(last(B), [_])] => fs]], \
        [id ==> fs, type ==> final]], [n ==> 0]).";
    let pl = "count(_) :- var_op(inc(n, N)), assign_func_value(N).\n\
              last(_) :- get_history(H), get_last_transition(H, T), assign_func_value(T).\n";
    let report = run_with_prolog(dm, pl, "x.\ny.\n");
    assert_eq!(report["status"], "ok", "{report}");
    assert_eq!(report["history"][0]["action"], "[1]");
    assert_eq!(report["history"][1]["action"], "[1,x:[1]]");
}

#[test]
fn application_prolog_function_wins_over_a_standard_rust_one() {
    // The standard `when/3` is replaced by the application's own definition.
    let dm = "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : apply(when(I, T, E), [true, a, b]) => fs]],
        [id ==> fs, type ==> final]], []).";
    let uf = "when(_, _, _) :- assign_func_value(mine).\n";
    let v = run_with_prolog(dm, uf, "");
    assert_eq!(v["history"][0]["action"], "mine", "{v}");
}
