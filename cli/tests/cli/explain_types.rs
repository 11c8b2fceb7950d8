//! `sitlogc build --explain-types`: what type inference found, as a user
//! reads it (insta snapshots over the benchmark DMs, the examples and the
//! typed test DMs).

use crate::support::{sitlogc, workspace};

fn explain(app: &str) -> String {
    let out = sitlogc()
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
    let out = sitlogc()
        .args(["build", "--explain-types"])
        .arg(workspace().join("no/such/app"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(!String::from_utf8_lossy(&out.stderr).is_empty());
}
