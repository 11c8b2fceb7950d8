//! `sitlogc debug` and `sitlogc replay` from the command line: exit codes
//! and where messages go (the sessions themselves are golden-tested in
//! tests/tests/suite/debug.rs).

use crate::support::{assert_ok, sitlogc};
use std::path::{Path, PathBuf};

fn app() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/dms/debug_app")
}

fn temp(name: &str) -> PathBuf {
    let dir = crate::support::temp_root().join(format!("sitlogc-cli-debug-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Records a run of the test application with `script` to `trace`.
fn record(trace: &Path, script: &str) {
    let script_file = trace.with_extension("txt");
    std::fs::write(&script_file, script).unwrap();
    let out = sitlogc()
        .arg("run")
        .arg(app())
        .arg("--script")
        .arg(&script_file)
        .arg("--trace")
        .arg(trace)
        .output()
        .unwrap();
    assert_ok(&out);
}

#[test]
fn debug_session_from_a_commands_file() {
    let commands = temp("session.txt");
    std::fs::write(&commands, "break ask:is\ncontinue\nstack\nquit\n").unwrap();
    let out = sitlogc()
        .arg("debug")
        .arg(app())
        .arg("--script")
        .arg(app().join("script.txt"))
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout
            .contains("(sitlog) stack\n#1 ask(color)  after is\n#0 main  in ask1\n(sitlog) quit\n"),
        "{stdout}"
    );
    assert!(!stdout.contains("Execution history"), "{stdout}");
    // A missing commands file, a bad line.
    let out = sitlogc()
        .arg("debug")
        .arg(app())
        .arg("--commands")
        .arg(temp("missing.txt"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).starts_with("error: cannot read commands file "));
    std::fs::write(&commands, "step\nfly\n").unwrap();
    let out = sitlogc()
        .arg("debug")
        .arg(app())
        .arg("--script")
        .arg(app().join("script.txt"))
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.ends_with("session.txt:2: error: unknown command `fly` (`help` lists them)\n"),
        "{stderr}"
    );
}

#[test]
fn replay_and_diff_exit_codes() {
    let (a, b) = (temp("a.jsonl"), temp("b.jsonl"));
    record(&a, "hello.\nanswer(red).\nbye.\n");
    record(&b, "hello.\nanswer(blue).\nbye.\n");
    let diff = |x: &Path, y: &Path| {
        sitlogc()
            .arg("replay")
            .arg(x)
            .arg("--diff")
            .arg(y)
            .output()
            .unwrap()
    };
    let same = diff(&a, &a);
    assert_eq!(same.status.code(), Some(0));
    assert_eq!(
        String::from_utf8(same.stdout).unwrap(),
        "the recordings are the same (6 transitions)\n"
    );
    let differ = diff(&a, &b);
    assert_eq!(differ.status.code(), Some(1));
    assert!(String::from_utf8(differ.stdout)
        .unwrap()
        .starts_with("the recordings differ at transition #2 "));
    // Replay with commands.
    let commands = temp("replay.txt");
    std::fs::write(&commands, "goto 3\nstack\nback\n").unwrap();
    let out = sitlogc()
        .arg("replay")
        .arg(&a)
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.contains("(sitlog) stack\n#1 ask(color)  after got(red)\n#0 main  in ask1\n"),
        "{stdout}"
    );
    // A bad trace: FILE:LINE:COL, exit 2, for replay and for either side of --diff.
    let bad = temp("bad.jsonl");
    std::fs::write(&bad, "{\"dm\":\"main\"\n").unwrap();
    for out in [
        sitlogc().arg("replay").arg(&bad).output().unwrap(),
        diff(&a, &bad),
        diff(&bad, &a),
    ] {
        assert_eq!(out.status.code(), Some(2));
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(
            stderr.contains(
                "bad.jsonl:1:12: error: not a JSON object: EOF while parsing an object\n"
            ),
            "{stderr}"
        );
    }
    let out = sitlogc()
        .arg("replay")
        .arg(temp("none.jsonl"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).starts_with("error: cannot read trace "));
}

/// Issue 30: an input that met no expectation left no trace, so `--diff`
/// of two runs pointed at a later transition. It is a line of the trace
/// (not a transition: no `expectation`, `action` or `next`), shown by the
/// debugger and by `replay`, and the first difference `--diff` finds.
#[test]
fn unmatched_inputs_are_traced_shown_and_compared() {
    let (a, b) = (temp("u_a.jsonl"), temp("u_b.jsonl"));
    record(&a, "hello.\nanswer(red).\nbye.\n");
    record(&b, "hello.\nmaybe.\nanswer(red).\nbye.\n");
    let text = std::fs::read_to_string(&b).unwrap();
    let line: serde_json::Value = serde_json::from_str(text.lines().nth(1).unwrap()).unwrap();
    assert_eq!(
        line,
        serde_json::json!({"dm": "ask(color)", "situation": "is", "unmatched": "maybe", "depth": 1})
    );
    let out = sitlogc()
        .arg("replay")
        .arg(&a)
        .arg("--diff")
        .arg(&b)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.starts_with(
            "the recordings differ before transition #2: an input met no expectation (the 1 transitions before are the same)\n"
        ),
        "{stdout}"
    );
    assert!(
        stdout.ends_with("u_b.jsonl:2:\n          ask(color) / is  maybe met no expectation\n"),
        "{stdout}"
    );
    // The debugger shows it as it happens and in `history`; so does replay.
    let commands = temp("u_commands.txt");
    std::fs::write(&commands, "step\nstep\nhistory 2\nquit\n").unwrap();
    let out = sitlogc()
        .arg("debug")
        .arg(app())
        .arg("--script")
        .arg(b.with_extension("txt"))
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8(out.stdout).unwrap();
    let shown = "        ask(color) / is  maybe met no expectation\n";
    assert_eq!(stdout.matches(shown).count(), 2, "{stdout}");
    std::fs::write(&commands, "step\nstep\nhistory 2\nquit\n").unwrap();
    let out = sitlogc()
        .arg("replay")
        .arg(&b)
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(stdout.matches(shown).count(), 2, "{stdout}");
}

/// `break` on a DM or situation the program does not have says so, with
/// the closest name, and sets nothing.
#[test]
fn a_breakpoint_on_a_name_not_in_the_program_is_refused() {
    let commands = temp("unknown.txt");
    std::fs::write(
        &commands,
        "break aks\nbreak ask:iz\nbreak ask:is\nbreak\nquit\n",
    )
    .unwrap();
    let out = sitlogc()
        .arg("debug")
        .arg(app())
        .arg("--script")
        .arg(app().join("script.txt"))
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.contains("there is no DM `aks` (did you mean `ask`?): no breakpoint set"),
        "{stdout}"
    );
    assert!(
        stdout.contains("DM `ask` has no situation `iz` (did you mean `is`?): no breakpoint set"),
        "{stdout}"
    );
    assert!(stdout.contains("breakpoint 1: ask:is"), "{stdout}");
    assert!(!stdout.contains("breakpoint 2"), "{stdout}");
}

/// In a replay, a breakpoint on a name the recording never shows is
/// refused the same way.
#[test]
fn a_replay_breakpoint_on_a_name_not_recorded_is_refused() {
    let trace = temp("names.jsonl");
    record(
        &trace,
        &std::fs::read_to_string(app().join("script.txt")).unwrap(),
    );
    let commands = temp("names.txt");
    std::fs::write(&commands, "break aks\nbreak ask\n").unwrap();
    let out = sitlogc()
        .arg("replay")
        .arg(&trace)
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.contains(
            "there is no DM `aks` (did you mean `ask`?) in this recording: no breakpoint set"
        ),
        "{stdout}"
    );
    assert!(stdout.contains("breakpoint 1: ask"), "{stdout}");
}
