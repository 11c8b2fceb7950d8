//! `sitlogc run`: the fixed output conventions (text, JSON, trace), exit codes.

use crate::support::{assert_ok, sitlogc};
use std::path::{Path, PathBuf};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../dms/examples")
        .join(name)
}

#[test]
fn json_report_is_one_object_on_stdout() {
    let app = example("countdown");
    let out = sitlogc()
        .args(["run", "--format", "json", "--script"])
        .arg(app.join("script.txt"))
        .arg(&app)
        .output()
        .unwrap();
    assert_ok(&out);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1);
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let expected: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(app.join("expected.json")).unwrap()).unwrap();
    assert_eq!(v, expected);
    // Rendered actions go to stderr, not stdout.
    assert!(String::from_utf8_lossy(&out.stderr).contains("Golem says: more"));
}

#[test]
fn text_report_lists_history_out_arg_and_globals() {
    let app = example("countdown");
    let out = sitlogc()
        .args(["run", "--script"])
        .arg(app.join("script.txt"))
        .arg(&app)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(stdout.starts_with("Execution history:\n"), "{stdout}");
    assert!(stdout.contains("main:(start,count(3):[3])"), "{stdout}");
    assert!(stdout.contains("\nOut Arg: "), "{stdout}");
    assert!(stdout.contains("\nOut Global Vars: ["), "{stdout}");
}

#[test]
fn runtime_error_exits_one_with_history_so_far() {
    let dir = crate::support::temp_root().join(format!("sitlogc-run-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> speech, arcs ==> [a : x => s2]],\n\
         [id ==> s2, type ==> speech, arcs ==> [b : y => fs]], [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    std::fs::write(dir.join("script.txt"), "a.\n").unwrap();
    let trace = dir.join("trace.jsonl");
    let out = sitlogc()
        .args(["run", "--format", "json", "--script"])
        .arg(dir.join("script.txt"))
        .arg("--trace")
        .arg(&trace)
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["status"], "error");
    assert!(
        v["error"].as_str().unwrap().contains("situation `s2`"),
        "{v}"
    );
    assert_eq!(v["history"].as_array().unwrap().len(), 1);
    // The trace has the transition, with depth and next situation.
    let line = std::fs::read_to_string(&trace).unwrap();
    let t: serde_json::Value = serde_json::from_str(line.lines().next().unwrap()).unwrap();
    assert_eq!(t["situation"], "is");
    assert_eq!(t["depth"], 0);
    assert_eq!(t["next"], "s2");
}

/// An in_arg pattern that the pipe does not match is skipped as the
/// original skips it (D-8, issue 39; the notes' own case: `in_arg ==>
/// foo`, pipe `now`): the situation runs, the pipe goes on unchanged, and
/// stderr has one warning located at the in_arg however often the
/// situation is entered; stdout is the report of the convention, nothing
/// added. `--deny-warnings`, or `deny-warnings = true` in the application's
/// `sitlog.toml`, makes it E14's error, located.
#[test]
fn an_in_arg_the_pipe_does_not_match_is_skipped_with_one_warning() {
    let dir = crate::support::temp_root().join(format!("sitlogc-run-inarg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main,\n  [ [id ==> is, type ==> neutral, in_arg ==> foo,\n\
         \x20     arcs ==> [empty : [inc(n, N), say(x)] => (N >= 3 -> fs ; otherwise -> is)]],\n\
         \x20   [id ==> fs, type ==> final] ], [n ==> 0]).\n",
    )
    .unwrap();
    let run = |extra: &[&str]| {
        let out = sitlogc()
            .args(["run", "--format", "json", "--in-arg", "now"])
            .args(extra)
            .arg(&dir)
            .output()
            .unwrap();
        let stdout = String::from_utf8(out.stdout).unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        (out.status.code(), stdout, stderr)
    };
    let (code, stdout, stderr) = run(&[]);
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    assert!(!stdout.contains("warning"), "{stdout}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["status"], "ok", "{v}");
    assert_eq!(v["out_arg"], "now", "{v}");
    assert_eq!(v["history"].as_array().unwrap().len(), 4, "{v}");
    assert_eq!(stderr.matches("Golem says: x").count(), 3, "{stderr}");
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(
        warnings[0].starts_with("warning: in DM `main`, situation `is` (")
            && warnings[0].contains("main.dm:2:46): in_arg `foo` does not match the incoming pipe value `now`: skipped, as the original SitLog does"),
        "{stderr}"
    );
    // Denied, by the option or by the application's sitlog.toml.
    for extra in [&["--deny-warnings"][..], &[]] {
        if extra.is_empty() {
            std::fs::write(dir.join("sitlog.toml"), "deny-warnings = true\n").unwrap();
        }
        let (code, stdout, stderr) = run(extra);
        assert_eq!(code, Some(1), "{stderr}");
        let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
        let e = v["error"].as_str().unwrap();
        assert!(
            e.contains("in_arg `foo` does not match the incoming pipe value `now`")
                && e.contains("main.dm:2:"),
            "{v}"
        );
        assert!(v["history"].as_array().unwrap().is_empty(), "{v}");
        assert!(!stderr.contains("Golem says"), "{stderr}");
        assert!(!stderr.contains("warning: in DM"), "{stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A script line that meets no expectation (a misspelt expectation or
/// input line, session 16's new user) is read again as the original does
/// (D-15), and no longer silently: one warning on stderr per situation,
/// located, with the input and the expectations; stdout unchanged.
#[test]
fn a_script_line_no_expectation_meets_is_a_warning() {
    let tmp = tempfile::tempdir().unwrap();
    let app = tmp.path().join("greet");
    std::fs::create_dir(&app).unwrap();
    std::fs::write(
        app.join("main.dm"),
        "diag_mod(main,\n  [ [id ==> start, type ==> speech,\n\
         \x20     arcs ==> [helo : say(hi) => start, bye : say(bye) => done]],\n\
         \x20   [id ==> done, type ==> final] ], []).\n",
    )
    .unwrap();
    std::fs::write(app.join("script.txt"), "hello.\nname(ada).\nbye.\n").unwrap();
    let out = sitlogc()
        .args(["run", "greet", "--script", "greet/script.txt"])
        .current_dir(tmp.path())
        .output()
        .unwrap();
    assert_ok(&out);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(stdout.contains("main:(start,bye:say(bye))"), "{stdout}");
    assert!(!stdout.contains("warning"), "{stdout}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .collect();
    insta::assert_snapshot!("unmatched_script_line", warnings.join("\n"));
}

#[test]
fn usage_errors_exit_two() {
    let out = sitlogc()
        .args(["run", "/nonexistent/app"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let app = example("countdown");
    let out = sitlogc()
        .args(["run", "--main", "nosuchdm"])
        .arg(&app)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no DM named `nosuchdm`"));
    let out = sitlogc()
        .args(["run", "--in-arg", "f(("])
        .arg(&app)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn history_none_keeps_no_history() {
    let app = example("countdown");
    let out = sitlogc()
        .args(["run", "--format", "json", "--history", "none", "--script"])
        .arg(app.join("script.txt"))
        .arg(&app)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["history"], serde_json::json!([]));
    assert_eq!(v["status"], "ok");
    // The text report has no `Execution history:` header then (issue 40).
    let out = sitlogc()
        .args(["run", "--history", "none", "--script"])
        .arg(app.join("script.txt"))
        .arg(&app)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with("Out Arg: "), "{text}");
    assert!(!text.contains("Execution history"), "{text}");
}

/// E0237 (a diag_mod that never matches its DM's identifier) fails only
/// where the run reaches it, as E0234: `--allow-unresolved` (and
/// `--legacy`, for the original's library DMs that have one) runs the
/// program, and reaching it is a located run-time error.
#[test]
fn allow_unresolved_runs_a_dead_path_with_a_diag_mod_that_never_matches() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(
        tmp.path().join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> speech, arcs ==> [go : [] => fs, broken : [] => odd]],\n\
         [id ==> fs, type ==> final], [id ==> odd, type ==> final, diag_mod ==> mian]], []).\n",
    )
    .unwrap();
    let run = |extra: &[&str], script: &str| {
        std::fs::write(tmp.path().join("script.txt"), script).unwrap();
        sitlogc()
            .args(["run", "--format", "json", "--script"])
            .arg(tmp.path().join("script.txt"))
            .args(extra)
            .arg(tmp.path())
            .output()
            .unwrap()
    };
    let strict = run(&[], "go.\n");
    assert_eq!(strict.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&strict.stdout).contains("E0237"));
    assert_eq!(run(&["--allow-unresolved"], "go.\n").status.code(), Some(0));
    let out = run(&["--allow-unresolved"], "broken.\n");
    assert_eq!(out.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let e = v["error"].as_str().unwrap();
    assert!(
        e.contains("diag_mod `mian`") && e.contains("main.dm:2:"),
        "{v}"
    );
}

#[test]
fn allow_unresolved_runs_legacy_programs_with_dead_paths() {
    let dir = crate::support::temp_root().join(format!("sitlogc-lenient-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> speech, arcs ==> [go : [] => fs, broken : [] => nowhere]],\n\
         [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    std::fs::write(dir.join("script.txt"), "go.\n").unwrap();
    let run = |extra: &[&str], script: &str| {
        std::fs::write(dir.join("script.txt"), script).unwrap();
        sitlogc()
            .args(["run", "--format", "json", "--script"])
            .arg(dir.join("script.txt"))
            .args(extra)
            .arg(&dir)
            .output()
            .unwrap()
    };
    assert_eq!(run(&[], "go.\n").status.code(), Some(1));
    assert_eq!(run(&["--allow-unresolved"], "go.\n").status.code(), Some(0));
    // Taking the dead path is a clean run-time error.
    let out = run(&["--allow-unresolved"], "broken.\n");
    assert_eq!(out.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(
        v["error"]
            .as_str()
            .unwrap()
            .contains("no situation `nowhere`"),
        "{v}"
    );
}
