//! Agreement: every application under `dms/` with a `script.txt` runs once
//! on the reference interpreter and once as generated Rust (compiled by
//! `tests/build.rs`); the JSON reports (history, out_arg, globals, status,
//! error) must be equal up to a consistent renaming of variables. Each runs
//! again on both without a history (`--history none`: native code keeps
//! its own stack of DM calls), and those reports must be equal too.

use sitlog_runtime::machine::Options;
use sitlog_tests::compiled::{canonical_vars, compiled, run_example_compiled_histories};
use sitlog_tests::{run_example_shared, workspace};
use std::path::PathBuf;

fn apps_with_scripts() -> Vec<PathBuf> {
    let apps = sitlog_compiler::load::discover(&workspace().join("dms")).unwrap();
    apps.into_iter()
        .filter(|a| a.join("script.txt").is_file())
        .collect()
}

#[test]
fn every_example_is_compiled() {
    let apps = apps_with_scripts();
    assert!(!apps.is_empty());
    for app in &apps {
        assert!(
            compiled(app).is_some(),
            "{} was not compiled",
            app.display()
        );
    }
}

#[test]
fn compiled_and_interpreted_runs_agree() {
    let mut failures = Vec::new();
    let apps = apps_with_scripts();
    let none = Options {
        keep_history: false,
        ..Options::default()
    };
    for app in &apps {
        // the interpreter's runs share one Prolog engine (the examples'
        // golden test, `examples.rs`, runs each on a fresh one)
        let (kept, without) = run_example_compiled_histories(app);
        for (how, options, generated) in [
            ("history kept", Options::default(), kept),
            ("--history none", none.clone(), without),
        ] {
            let interpreted = canonical_vars(&run_example_shared(app, options));
            let generated = canonical_vars(&generated);
            if interpreted != generated {
                failures.push(format!(
                    "{} ({how}):\n  interpreter {interpreted}\n  compiled    {generated}",
                    app.display()
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} applications disagree:\n{}",
        failures.len(),
        apps.len(),
        failures.join("\n")
    );
}
