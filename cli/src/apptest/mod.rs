//! `sitlogc test APP`: an application's own tests, in cargo's and pytest's
//! habits. Each `tests/*.toml` of the application is one test ([`case`]:
//! the world or script it runs on and what must hold afterwards); [`run`]
//! runs them in parallel on the interpreter and checks them; [`report`]
//! prints the results (one line per test, the failures with a diff, the
//! summary; JSON lines or JUnit XML for CI); [`coverage`] counts the
//! situations and arcs the runs took on the program's diagram.
//!
//! Invariant: the output does not depend on the order in which the
//! parallel runs finish (tests are reported in the order of their file
//! names), and a bad test file is an error at its `file:line:col` before
//! anything runs.

pub mod case;
pub mod coverage;
pub mod report;
pub mod run;

use std::path::{Path, PathBuf};

/// The directory of an application's tests.
pub const TESTS_DIR: &str = "tests";

/// A text file, refused when it is not UTF-8 (the message says why).
pub fn read_text(path: &Path) -> Result<String, String> {
    let bytes = sitlog_syntax::read_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
    sitlog_syntax::decode_owned(bytes).map_err(|e| {
        format!(
            "{}:{}:{}: error: {}",
            path.display(),
            e.line,
            e.column,
            e.message
        )
    })
}

/// The test files of `app` (`tests/*.toml`, by name).
pub fn test_files(app: &Path) -> Result<Vec<PathBuf>, String> {
    let dir = app.join(TESTS_DIR);
    let entries = std::fs::read_dir(&dir).map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound {
            format!(
                "{} has no tests: put test files in {} (one TOML file per test; `sitlogc new NAME --robot` makes an example)",
                app.display(),
                dir.display()
            )
        } else {
            format!("cannot read {}: {e}", dir.display())
        }
    })?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml") && p.is_file())
        .collect();
    files.sort();
    Ok(files)
}
