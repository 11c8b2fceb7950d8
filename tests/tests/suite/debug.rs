//! `sitlogc debug` and `sitlogc replay` (issue 21): scripted debugger
//! sessions (`--commands`) with golden transcripts, on the test application
//! `tests/dms/debug_app` (Appendix-A-like: an embedded DM, locals, a
//! global, the pipe) and on the home scenario on its world; replays
//! forwards and backwards against the recorded entries; the first
//! difference of two recordings; bad commands and trace files.

use sitlog_debug::record::{numbered, Record};
use sitlog_debug::{diff, replay, CommandSource, Trace};
use sitlog_robot::console::SharedBuf;
use sitlog_robot::{Assets, HistoryMode, RunArgs, Runner, Streams};
use sitlog_tests::scenario::shared_interpreter as interpreter;
use sitlog_tests::workspace;
use std::path::{Path, PathBuf};

fn app() -> PathBuf {
    workspace().join("tests/dms/debug_app")
}

fn streams(out: &SharedBuf, err: &SharedBuf) -> Streams {
    Streams {
        stdout: Box::new(out.clone()),
        stderr: Box::new(err.clone()),
        stdout_is_terminal: false,
        stderr_is_terminal: false,
    }
}

/// A debugger session on `app` reading `commands`: what it printed on
/// stdout (debugger and report), on stderr, and the exit status.
fn session(app: &Path, args: &RunArgs, commands: &str) -> (String, String, u8) {
    let (ir, functions) = interpreter(app);
    let assets = Assets::from_app(app).unwrap();
    let (out, err) = (SharedBuf::default(), SharedBuf::default());
    let code = sitlog_debug::debug(
        &ir,
        functions,
        args,
        &assets,
        streams(&out, &err),
        CommandSource::text("session.txt", commands),
        Box::new(out.clone()),
        Box::new(err.clone()),
    );
    (normal(&out.text()), err.text(), code)
}

/// Variable names (`_G123`) as `_G`: they number the run's variables,
/// which other changes to the interpreter may renumber.
fn normal(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find("_G") {
        out.push_str(&rest[..i + 2]);
        rest = rest[i + 2..].trim_start_matches(|c: char| c.is_ascii_digit());
    }
    out.push_str(rest);
    out
}

/// A script file of `lines`.
fn script(dir: &tempfile::TempDir, name: &str, lines: &str) -> PathBuf {
    let path = dir.path().join(name);
    std::fs::write(&path, lines).unwrap();
    path
}

fn test_mode(script: PathBuf) -> RunArgs {
    RunArgs {
        script: Some(script),
        ..RunArgs::default()
    }
}

const SCRIPT: &str = "hello.\nanswer(red).\nhello.\ndunno.\nbye.\n";

#[test]
fn breakpoints_step_next_finish_and_inspection() {
    let dir = tempfile::tempdir().unwrap();
    let args = test_mode(script(&dir, "s.txt", SCRIPT));
    let (out, err, code) = session(
        &app(),
        &args,
        "break ask:is\nbreak main:ask1\nbreak\ncontinue\nstack\nvars\nvars 0\nvars 7\npipe\n\
         print get(asked, N)\nprint apply(no_such_function, [])\nprint [set(asked, 99), inc(asked, M)]\nvars\nhistory\nnext\nstack\nfinish\n\
         delete 1\ndelete 9\ncontinue\nworld\nback\nstep\ncontinue\n",
    );
    assert_eq!((code, err.as_str()), (0, ""));
    insta::assert_snapshot!(out);
}

#[test]
fn a_dm_breakpoint_stops_at_each_call_only() {
    let dir = tempfile::tempdir().unwrap();
    let args = test_mode(script(&dir, "s.txt", SCRIPT));
    let (out, _, code) = session(&app(), &args, "break ask\ncontinue\ncontinue\ncontinue\n");
    assert_eq!(code, 0);
    insta::assert_snapshot!(out);
}

#[test]
fn input_answers_a_situation_the_script_has_no_input_for() {
    let dir = tempfile::tempdir().unwrap();
    let args = test_mode(script(&dir, "s.txt", "hello.\n"));
    let (out, _, code) = session(
        &app(),
        &args,
        "continue\nstack\nstep\ninput answer(\ninput answer(blue)\npipe\nvars 0\ncontinue\n\
         print 1\ninput hello\ncontinue\ninput dunno\ninput bye\n",
    );
    assert_eq!(code, 0);
    insta::assert_snapshot!(out);
}

#[test]
fn break_on_error_stops_before_the_stack_unwinds() {
    let dir = tempfile::tempdir().unwrap();
    let args = test_mode(script(
        &dir,
        "s.txt",
        "hello.\nanswer(red).\ngo(nowhere).\n",
    ));
    let (out, err, code) = session(
        &app(),
        &args,
        "break on error\ncontinue\nstack\nvars\npipe\nprint get(color, C)\ncontinue\n",
    );
    assert_eq!(code, 1);
    assert!(err.contains("there is no situation `nowhere`"), "{err}");
    // The error names the arc that chose `nowhere`, at its file:line:col
    // (issue 39); the path below the workspace.
    let out = out.replace(&format!("{}/", workspace().display()), "");
    insta::assert_snapshot!(out);
}

#[test]
fn quit_stops_the_run_and_exits_0() {
    let dir = tempfile::tempdir().unwrap();
    let args = RunArgs {
        history: HistoryMode::None,
        ..test_mode(script(&dir, "s.txt", SCRIPT))
    };
    let (out, _, code) = session(&app(), &args, "step\nquit\nstep\n");
    assert_eq!(code, 0);
    insta::assert_snapshot!(out);
    // Quit before the run: nothing runs.
    let (out, _, code) = session(&app(), &args, "quit\n");
    assert_eq!(code, 0);
    assert!(!out.contains("Execution history"), "{out}");
}

#[test]
fn the_end_of_the_commands_lets_the_run_go_on() {
    let dir = tempfile::tempdir().unwrap();
    let args = RunArgs {
        history: HistoryMode::None,
        ..test_mode(script(&dir, "s.txt", SCRIPT))
    };
    let (out, _, code) = session(&app(), &args, "step\n");
    assert_eq!(code, 0);
    insta::assert_snapshot!(out);
}

#[test]
fn a_bad_command_line_names_file_and_line_and_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let args = RunArgs {
        history: HistoryMode::None,
        ..test_mode(script(&dir, "s.txt", SCRIPT))
    };
    let (_, err, code) = session(&app(), &args, "step\n# fine\njump 3\n");
    assert_eq!(code, 2);
    // The run stops; only the bad line is reported.
    assert_eq!(
        err,
        "session.txt:3: error: unknown command `jump` (`help` lists them)\n"
    );
    let (_, err, code) = session(&app(), &args, "break :is\n");
    assert_eq!(code, 2);
    assert_eq!(
        err,
        "session.txt:1: error: `break :is`: write DM or DM:SITUATION\n"
    );
    // A commands file that is not there, or not text.
    let e = CommandSource::file(&dir.path().join("missing.txt"))
        .err()
        .unwrap();
    assert!(e.starts_with("error: cannot read commands file "), "{e}");
    let bad = script(&dir, "bad.txt", "step\n\u{0}");
    std::fs::write(&bad, b"step\nnext \xff\n").unwrap();
    let e = CommandSource::file(&bad).err().unwrap();
    assert!(
        e.ends_with("bad.txt:2:6: error: the commands file is not UTF-8 text"),
        "{e}"
    );
}

#[test]
fn home_on_its_world() {
    let home = workspace().join("dms/apps/home");
    let args = RunArgs {
        history: HistoryMode::None,
        quiet: true,
        ..RunArgs::default()
    };
    let (out, err, code) = session(
        &home,
        &args,
        "world\nbreak deliver\ncontinue\nstack\nworld\nvars 1\nfinish\nworld\nhistory 3\nquit\n",
    );
    assert_eq!((code, err.as_str()), (0, ""));
    insta::assert_snapshot!(out);
}

/// Records a run of the test application with `script` (`--trace`).
fn record(dir: &tempfile::TempDir, name: &str, script_text: &str) -> Trace {
    let trace = dir.path().join(format!("{name}.jsonl"));
    let args = RunArgs {
        trace: Some(trace.clone()),
        ..test_mode(script(dir, &format!("{name}.txt"), script_text))
    };
    let (ir, functions) = interpreter(&app());
    let assets = Assets::from_app(&app()).unwrap();
    let (out, err) = (SharedBuf::default(), SharedBuf::default());
    let code = Runner::new(streams(&out, &err)).run(&ir, functions, &args, &assets);
    assert_eq!(code, 0, "{}", err.text());
    let mut t = Trace::read(&trace).unwrap();
    t.name = format!("{name}.jsonl");
    t
}

/// A replay session over `trace`: what it printed and its exit status.
fn replay_session(trace: &Trace, commands: &str) -> (String, String, u8) {
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let code = replay(
        trace,
        CommandSource::text("replay.txt", commands),
        &mut out,
        &mut err,
    );
    (
        normal(&String::from_utf8(out).unwrap()),
        String::from_utf8(err).unwrap(),
        code,
    )
}

/// The lines a replay printed for its transitions, after `(sitlog) CMD`.
fn shown(out: &str) -> Vec<String> {
    out.lines()
        .filter(|l| l.starts_with('#'))
        .map(str::to_owned)
        .collect()
}

#[test]
fn replay_forwards_and_backwards_equals_the_recording() {
    let dir = tempfile::tempdir().unwrap();
    let trace = record(&dir, "a", SCRIPT);
    let n = trace.records.len();
    assert_eq!(n, 10);
    let expected: Vec<String> = trace
        .records
        .iter()
        .enumerate()
        .map(|(i, r)| numbered(i + 1, r))
        .collect();
    // Forwards, one step at a time.
    let (out, _, code) = replay_session(&trace, &"step\n".repeat(n));
    assert_eq!(code, 0);
    assert_eq!(shown(&out), expected);
    // Backwards from the end.
    let (out, _, _) = replay_session(&trace, &format!("goto {n}\n{}", "back\n".repeat(n - 1)));
    let mut backwards = expected.clone();
    backwards.reverse();
    assert_eq!(shown(&out), backwards);
    // Every goto.
    let commands: String = (1..=n).rev().map(|i| format!("goto {i}\n")).collect();
    let (out, _, _) = replay_session(&trace, &commands);
    assert_eq!(shown(&out), backwards);
    // The file's entries are the live run's: the records as written.
    let text = std::fs::read_to_string(dir.path().join("a.jsonl")).unwrap();
    let first: serde_json::Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    assert_eq!(
        trace.records[0],
        Record {
            dm: first["dm"].as_str().unwrap().into(),
            situation: first["situation"].as_str().unwrap().into(),
            expectation: first["expectation"].as_str().unwrap().into(),
            action: first["action"].as_str().unwrap().into(),
            depth: 0,
            next: Some("ask1".into()),
        }
    );
}

#[test]
fn replay_session_golden() {
    let dir = tempfile::tempdir().unwrap();
    let trace = record(&dir, "a", SCRIPT);
    let (out, err, code) = replay_session(
        &trace,
        "back\nstack\nbreak ask:got\ncontinue\nstack\nhistory 3\nfinish\nnext\nback\nback\n\
         goto 99\ngoto 0\nbreak on error\nbreak main\ndelete 1\ncontinue\ncontinue\nstep\nvars\nprint 1\n\
         input x\nworld\nquit\nstep\n",
    );
    assert_eq!((code, err.as_str()), (0, ""));
    insta::assert_snapshot!(out);
}

#[test]
fn diff_finds_the_first_divergence() {
    let dir = tempfile::tempdir().unwrap();
    let a = record(&dir, "a", SCRIPT);
    // The second answer changed: the runs part at transition 6.
    let b = record(&dir, "b", &SCRIPT.replace("dunno", "answer(blue)"));
    // One input less at the end: a prefix.
    let c = record(&dir, "c", "hello.\nanswer(red).\nbye.\n");
    assert_eq!(diff(&a, &a), None);
    let ab = diff(&a, &b).unwrap();
    assert!(
        ab.starts_with("the recordings differ at transition #6 "),
        "{ab}"
    );
    insta::assert_snapshot!("diff_a_b", ab);
    insta::assert_snapshot!("diff_a_c", diff(&a, &c).unwrap());
    // The `diff` command of a replay.
    let (out, _, _) = replay_session(
        &a,
        &format!(
            "diff {}\ndiff {}\ndiff {}\n",
            dir.path().join("b.jsonl").display(),
            dir.path().join("a.jsonl").display(),
            dir.path().join("missing.jsonl").display()
        ),
    );
    let out = out.replace(&dir.path().display().to_string(), "DIR");
    insta::assert_snapshot!("diff_command", out);
}

#[test]
fn diff_of_two_home_runs_on_different_worlds() {
    // The home scenario recorded twice: the user's first answer misheard
    // in the second world.
    let home = workspace().join("dms/apps/home");
    let dir = tempfile::tempdir().unwrap();
    let world = std::fs::read_to_string(home.join("world.toml")).unwrap();
    let run = |name: &str, world: &str| {
        let trace = dir.path().join(format!("{name}.jsonl"));
        let mut assets = Assets::from_app(&home).unwrap();
        assets.world = Some(sitlog_robot::TextFile {
            name: "world.toml".into(),
            text: world.to_owned(),
        });
        let args = RunArgs {
            trace: Some(trace.clone()),
            history: HistoryMode::None,
            quiet: true,
            ..RunArgs::default()
        };
        let (ir, functions) = interpreter(&home);
        let (out, err) = (SharedBuf::default(), SharedBuf::default());
        Runner::new(streams(&out, &err)).run(&ir, functions, &args, &assets);
        let mut t = Trace::read(&trace).unwrap();
        t.name = format!("{name}.jsonl");
        t
    };
    let a = run("a", &world);
    let changed = world.replacen("i like malz", "i like coke", 1);
    assert_ne!(changed, world, "the world's first answer is `i like malz`");
    let b = run("b", &changed);
    let d = diff(&a, &b).unwrap();
    insta::assert_snapshot!(normal(&d));
}

#[test]
fn bad_trace_files_name_file_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let good = r#"{"dm":"main","situation":"is","expectation":"hello","action":"[]","depth":0,"next":"fs"}"#;
    let cases = [
        ("not_json", format!("{good}\n{{\"dm\": \"main\",, }}\n")),
        ("not_object", format!("{good}\n\n[1, 2]\n")),
        ("no_dm", good.replace(r#""dm":"main","#, "")),
        ("dm_number", good.replace(r#""main""#, "3")),
        ("bad_depth", good.replace(r#""depth":0"#, r#""depth":-2"#)),
        ("no_depth", good.replace(r#","depth":0"#, "")),
        ("bad_next", good.replace(r#""fs""#, "[1]")),
    ];
    let mut report = String::new();
    for (name, text) in cases {
        let path = dir.path().join(format!("{name}.jsonl"));
        std::fs::write(&path, text).unwrap();
        let e = Trace::read(&path).unwrap_err();
        report.push_str(&e.replace(&dir.path().display().to_string(), "DIR"));
        report.push('\n');
    }
    let path = dir.path().join("latin1.jsonl");
    std::fs::write(&path, b"{\"dm\":\"caf\xe9\"}\n").unwrap();
    let e = Trace::read(&path).unwrap_err();
    report.push_str(&e.replace(&dir.path().display().to_string(), "DIR"));
    report.push('\n');
    let e = Trace::read(&dir.path().join("missing.jsonl")).unwrap_err();
    assert!(e.starts_with("error: cannot read trace "), "{e}");
    insta::assert_snapshot!(report);
    // An empty recording replays as one with no transitions.
    let t = Trace::parse("empty.jsonl", "\n").unwrap();
    let (out, _, code) = replay_session(&t, "step\nstack\nhistory\nback\n");
    assert_eq!(code, 0);
    insta::assert_snapshot!("empty_replay", out);
    // A bad replay commands line.
    let (_, err, code) = replay_session(&t, "step\ngoto x\n");
    assert_eq!(code, 2);
    assert_eq!(
        err,
        "replay.txt:2: error: `goto` needs a transition number, not `x`\n"
    );
}
