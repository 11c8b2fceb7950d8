//! The example applications compiled to Rust by `tests/build.rs`, and how
//! to run them like [`crate::run_example`] runs the interpreter.

use crate::{appendix_a_functions, example_args, workspace};
use sitlog_runtime::machine::Options;
use sitlog_runtime::report;
use sitlog_runtime::testmode::TextActions;
use sitlog_runtime::Functions;
use std::path::Path;

/// The generated modules (one per application under `dms/`) and `APPS`.
#[allow(clippy::all, dead_code)]
pub mod generated {
    include!(concat!(env!("OUT_DIR"), "/generated_apps.rs"));
}

/// The compiled `run` of the application at `app`, if `tests/build.rs`
/// compiled it.
pub fn compiled(app: &Path) -> Option<(generated::RunFn, generated::FunctionsFn)> {
    let dms = workspace().join("dms");
    let rel = app.strip_prefix(&dms).ok()?;
    generated::APPS
        .iter()
        .find(|(p, _, _)| Path::new(p) == rel)
        .map(|e| (e.1, e.2))
}

/// Runs the compiled example on its `script.txt` (as
/// [`crate::run_example`] does with the interpreter); returns the JSON report.
pub fn run_example_compiled(app: &Path) -> serde_json::Value {
    let (run, functions) = compiled_and_functions(app);
    run_compiled(app, run, functions, Options::default())
}

/// [`run_example_compiled`] twice on one set of functions (one Prolog
/// engine; the examples' Prolog files keep no state between calls): with
/// the history kept, then without (`--history none`, where native code runs
/// DM calls on its own stack). Returns the two reports in that order.
pub fn run_example_compiled_histories(app: &Path) -> (serde_json::Value, serde_json::Value) {
    let (run, functions) = compiled_and_functions(app);
    let kept = run_compiled(app, run, functions.clone(), Options::default());
    let options = Options {
        keep_history: false,
        ..Options::default()
    };
    (kept, run_compiled(app, run, functions, options))
}

/// The compiled `run` of `app` and its functions: standard ones plus its
/// embedded Prolog sources (issue 10); Rust stand-ins only when Prolog is
/// compiled out.
fn compiled_and_functions(app: &Path) -> (generated::RunFn, Functions) {
    let (run, embedded_functions) =
        compiled(app).unwrap_or_else(|| panic!("{} was not compiled", app.display()));
    let mut functions = if cfg!(feature = "prolog") {
        embedded_functions().expect("embedded Prolog sources load")
    } else {
        Functions::standard()
    };
    if example_args(app).appendix_a && !cfg!(feature = "prolog") {
        appendix_a_functions(&mut functions);
    }
    (run, functions)
}

fn run_compiled(
    app: &Path,
    run: generated::RunFn,
    functions: Functions,
    options: Options,
) -> serde_json::Value {
    let args = example_args(app);
    let mut perception = crate::example_perception(app);
    let mut actions = TextActions::new(std::io::sink(), Vec::new());
    let (outcome, store) = run(
        &args.main,
        args.in_arg.as_deref(),
        options,
        functions,
        &mut perception,
        &mut actions,
        None,
    )
    .expect("valid run config");
    serde_json::from_str(&report::outcome_json(&store, &outcome)).expect("report is JSON")
}

/// Renames the variables of every TERM string of a report consistently, in
/// order of first appearance (`_G17` → `_V0`, ...), so that two reports
/// compare exactly up to a consistent renaming (a stronger check than
/// [`crate::normalize`], which maps every variable to `_`).
pub fn canonical_vars(v: &serde_json::Value) -> serde_json::Value {
    let mut names = std::collections::HashMap::new();
    canonical(v, &mut names)
}

fn canonical(
    v: &serde_json::Value,
    names: &mut std::collections::HashMap<String, usize>,
) -> serde_json::Value {
    use serde_json::Value;
    match v {
        Value::String(s) => Value::String(rename(s, names)),
        Value::Array(items) => Value::Array(items.iter().map(|i| canonical(i, names)).collect()),
        // serde_json's map is sorted by key: a deterministic order.
        Value::Object(map) => Value::Object(
            map.iter()
                .map(|(k, v)| (k.clone(), canonical(v, names)))
                .collect(),
        ),
        other => other.clone(),
    }
}

/// Each variable of a term's text renamed `_V0`, `_V1`, ... in the order
/// first seen through `names` (shared by the texts of one history).
pub fn rename(s: &str, names: &mut std::collections::HashMap<String, usize>) -> String {
    crate::map_vars(s, |name| {
        if name == "_" {
            return "_".to_owned();
        }
        let next = names.len();
        format!("_V{}", *names.entry(name.to_owned()).or_insert(next))
    })
}
