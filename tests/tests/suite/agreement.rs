//! Agreement: every application under `dms/` with a `script.txt` runs once
//! on the reference interpreter and once as generated Rust (compiled by
//! `tests/build.rs`); the JSON reports (history, out_arg, globals, status,
//! error) must be equal up to a consistent renaming of variables.

use sitlog_tests::compiled::{canonical_vars, compiled, run_example_compiled};
use sitlog_tests::{run_example, workspace};
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
    for app in &apps {
        let interpreted = canonical_vars(&run_example(app));
        let generated = canonical_vars(&run_example_compiled(app));
        if interpreted != generated {
            failures.push(format!(
                "{}:\n  interpreter {interpreted}\n  compiled    {generated}",
                app.display()
            ));
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
