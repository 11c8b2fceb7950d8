//! Golden runs: every application under `dms/` with a `script.txt` and an
//! `expected.json` runs in test mode and must give exactly that history,
//! out_arg and globals (variable names compared as `_`).

use sitlog_tests::{normalize, run_example, workspace};
use std::path::PathBuf;

fn examples() -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![workspace().join("dms")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            }
        }
        if dir.join("expected.json").is_file() && dir.join("script.txt").is_file() {
            found.push(dir);
        }
    }
    found.sort();
    found
}

#[test]
fn examples_match_their_golden_results() {
    let mut failures = Vec::new();
    let apps = examples();
    for app in &apps {
        let expected: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(app.join("expected.json")).unwrap())
                .unwrap_or_else(|e| panic!("{}: bad expected.json: {e}", app.display()));
        let actual = run_example(app);
        if normalize(&actual) != normalize(&expected) {
            failures.push(format!(
                "{}:\n  expected {}\n  actual   {}",
                app.display(),
                normalize(&expected),
                normalize(&actual)
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} examples differ:\n{}",
        failures.len(),
        apps.len(),
        failures.join("\n")
    );
}
