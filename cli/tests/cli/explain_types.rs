//! `sitlogc build --explain-types`: the typed MIR and what native code
//! does with it, as a user reads it (insta snapshots over the benchmark
//! DMs, the examples and the typed test DMs), each ending with its two
//! summary lines, after the MIR inference's summary (`mir::ty`) and the
//! native code's total.

use crate::support::{assert_ok, sitlogc, workspace};

fn explain(app: &str) -> String {
    let out = sitlogc()
        .args(["build", "--explain-types"])
        .arg(workspace().join(app))
        .output()
        .unwrap();
    assert_ok(&out);
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn explain_types_listing() {
    let mut all = String::new();
    for app in [
        "benches/dms/counter_loop",
        "benches/dms/counter_loop_in_arg",
        "benches/dms/echo_calls",
        "benches/dms/list_search",
        "benches/dms/pipe_calls",
        "benches/dms/scripted_loop",
        "tests/typed/loops",
        "tests/typed/mixed",
        "tests/typed/pipe",
        "dms/examples/appendix_a",
        "dms/examples/countdown",
        "dms/examples/retry_choice",
    ] {
        all.push_str(&format!("== {app}\n{}", explain(app)));
    }
    insta::assert_snapshot!(all);
}

/// The listing of each application ends with exactly one summary line;
/// the home butler and the supermarket meet issue 37's 80 % target for the
/// variables typed (the one for situations on native values they miss:
/// `docs/guide/performance.md`, issue 37's "what --explain-types counts"),
/// and the breakdown before the two lines adds up.
#[test]
fn explain_types_ends_with_one_summary_line() {
    for app in [
        "dms/apps/home",
        "dms/apps/supermarket",
        "dms/examples/tutorial",
    ] {
        let text = explain(app);
        let summaries: Vec<&str> = text
            .lines()
            .filter(|l| l.starts_with("situations compiled as code: "))
            .collect();
        assert_eq!(summaries.len(), 1, "{app}: {text}");
        let last = text.lines().last().unwrap();
        assert_eq!(last, summaries[0], "{app}");
        // Before the two lines: the MIR inference's line, then the native
        // code's total.
        let lines: Vec<&str> = text.lines().collect();
        let native = lines[lines.len() - 2];
        let (n, y) = native
            .strip_prefix("situations on native values: ")
            .and_then(|r| r.split_once('/'))
            .unwrap_or_else(|| panic!("{app}: {native}"));
        let (n, y): (usize, usize) = (n.parse().unwrap(), y.parse().unwrap());
        assert!(n <= y, "{app}: {native}");
        // The breakdown: situations whose native code runs the template,
        // or hands the frames over, on every path, or either on some
        // paths (not on native values, the first not compiled as code
        // either).
        let count = |line: &str, prefix: &str| -> usize {
            let rest = line
                .strip_prefix(prefix)
                .unwrap_or_else(|| panic!("{app}: {line}"));
            rest.split(' ').next().unwrap().parse().unwrap()
        };
        let template = count(
            lines[lines.len() - 5],
            "situations run from the template at every visit: ",
        );
        let hands = count(
            lines[lines.len() - 4],
            "situations handing the native frames over at every visit: ",
        );
        let partly = count(
            lines[lines.len() - 3],
            "situations handing over or running the template on some paths: ",
        );
        assert!(n + template + hands + partly <= y, "{app}: {text}");
        // Issue 37's target for the two applications: at least 80 % of the
        // variables typed (below); the 80 % of situations on native values
        // is printed, not asserted (unmet).
        let app_target = app.starts_with("dms/apps/");
        println!("{app}: {native} (80 % target: {})", 5 * n >= 4 * y);
        assert!(lines[lines.len() - 6].starts_with("native code: "));
        let mir = lines[lines.len() - 7];
        assert!(
            mir.starts_with("MIR registers typed: ")
                && mir.contains("; situations with no term register: ")
                && mir.ends_with("(MIR inference)"),
            "{app}: {mir}"
        );
        println!("{app}: {mir}");
        let (sits, vars) = last
            .strip_prefix("situations compiled as code: ")
            .and_then(|r| r.split_once("; variables typed: "))
            .unwrap_or_else(|| panic!("{app}: {last}"));
        for (ratio, target) in [(sits, false), (vars, app_target)] {
            let (x, y) = ratio.split_once('/').unwrap();
            let (x, y): (usize, usize) = (x.parse().unwrap(), y.parse().unwrap());
            assert!(x <= y && y > 0, "{app}: {last}");
            assert!(!target || 5 * x >= 4 * y, "{app}: {last}");
            if !target {
                assert!(x + template <= y, "{app}: {last}");
            }
        }
        println!("{app}: {last}");
    }
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
