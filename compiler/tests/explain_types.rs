//! `sitlogc build --explain-types`: what type inference found, as a user
//! reads it (insta snapshots over the benchmark DMs, the examples and the
//! typed test DMs).

use std::path::{Path, PathBuf};
use std::process::Command;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

fn explain(app: &str) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_sitlogc"))
        .args(["build", "--explain-types"])
        .arg(workspace().join(app))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn explain_types_listing() {
    let mut all = String::new();
    for app in [
        "benches/dms/counter_loop",
        "benches/dms/pipe_calls",
        "benches/dms/scripted_loop",
        "tests/typed/loops",
        "tests/typed/mixed",
        "dms/examples/appendix_a",
        "dms/examples/countdown",
        "dms/examples/retry_choice",
    ] {
        all.push_str(&format!("== {app}\n{}", explain(app)));
    }
    insta::assert_snapshot!(all);
}

#[test]
fn explain_types_rejects_a_bad_application() {
    let out = Command::new(env!("CARGO_BIN_EXE_sitlogc"))
        .args(["build", "--explain-types"])
        .arg(workspace().join("no/such/app"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(!String::from_utf8_lossy(&out.stderr).is_empty());
}
