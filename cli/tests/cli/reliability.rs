//! Issue 23, reliability, from the command line: bytes that are not UTF-8
//! in every reader, output that cannot be written, limits on input from
//! outside and on Prolog user functions, SIGINT and SIGTERM.

#[cfg(unix)]
use crate::support::kill;
use crate::support::{assert_ok, sitlogc};
use std::path::{Path, PathBuf};
use std::process::{Output, Stdio};
use std::time::{Duration, Instant};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../dms/examples")
        .join(name)
}

/// A fresh directory for one test.
fn temp(name: &str) -> PathBuf {
    let dir =
        crate::support::temp_root().join(format!("sitlogc-rel-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

const ECHO: &str = "diag_mod(main, [
  [id ==> is, type ==> listening, arcs ==> [X : screen(got) => fs]],
  [id ==> fs, type ==> final]
], []).
";

const LOOP: &str = "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : inc(n, _) => is]],
  [id ==> fs, type ==> final]
], [n ==> 0]).
";

/// An application directory with `files`.
fn app(name: &str, files: &[(&str, &[u8])]) -> PathBuf {
    let dir = temp(name);
    for (file, bytes) in files {
        std::fs::write(dir.join(file), bytes).unwrap();
    }
    dir
}

// ------------------------------------------------------------ not UTF-8

#[test]
fn a_dm_file_that_is_not_utf8_is_an_error_with_its_position() {
    let cases: &[(&[u8], &str)] = &[
        (
            b"diag_mod(main, [[id ==> is, \xff\xfe type ==> final]], []).\n",
            "main.dm:1:29",
        ),
        // A file ending inside a character.
        (
            b"diag_mod(main, [[id ==> is, type ==> final]], []).\n% caf\xc3",
            "main.dm:2:6",
        ),
        (b"\xff\xfed\0i\0a\0g\0", "main.dm:1:1"),
    ];
    for (bytes, at) in cases {
        let dir = app("utf8", &[("main.dm", bytes)]);
        for cmd in ["check", "run", "build"] {
            let out = sitlogc()
                .arg(cmd)
                .arg(&dir)
                .stdin(Stdio::null())
                .output()
                .unwrap();
            let err = stderr(&out);
            assert_eq!(out.status.code(), Some(1), "{cmd}: {err}");
            assert!(err.contains(at), "{cmd}: {err}");
            assert!(err.contains("E0002"), "{cmd}: {err}");
            assert!(!err.contains("panicked"), "{cmd}: {err}");
        }
    }
    // JSON diagnostics give the line and column of the first bad byte.
    let dir = app("utf8j", &[("main.dm", b"% \xc3\xa9\n  x \xff.\n")]);
    let out = sitlogc()
        .args(["check", "--format", "json"])
        .arg(&dir)
        .output()
        .unwrap();
    let v: serde_json::Value =
        serde_json::from_str(String::from_utf8_lossy(&out.stdout).lines().next().unwrap()).unwrap();
    assert_eq!(
        (v["line"].as_u64(), v["column"].as_u64()),
        (Some(2), Some(5))
    );
}

#[test]
fn a_utf8_bom_is_skipped() {
    let mut bytes = b"\xef\xbb\xbf".to_vec();
    bytes.extend_from_slice(ECHO.as_bytes());
    let dir = app(
        "bom",
        &[("main.dm", &bytes), ("s.txt", b"\xef\xbb\xbfhello.\n")],
    );
    let out = sitlogc()
        .arg("run")
        .arg(&dir)
        .arg("--script")
        .arg(dir.join("s.txt"))
        .output()
        .unwrap();
    assert_ok(&out);
}

#[test]
fn side_files_scripts_kbs_and_worlds_that_are_not_utf8_are_errors_with_positions() {
    let bad = b"x.\ny \xff.\n";
    // Side files of the application: diagnostics.
    for side in [
        "global_vars.pl",
        "basic_actions.pl",
        "user_functions.pl",
        "models",
    ] {
        let mut files: Vec<(&str, &[u8])> = vec![("main.dm", ECHO.as_bytes()), (side, bad)];
        if side == "models" {
            files[1] = ("models", b"'main.dm'.\n\xfe");
        }
        let dir = app("side", &files);
        let out = sitlogc().arg("check").arg(&dir).output().unwrap();
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{side}: {err}");
        let at = if side == "models" { "2:1" } else { "2:3" };
        assert!(err.contains(&format!("{side}:{at}")), "{side}: {err}");
    }
    // Files of a run: one line naming file:line:col, exit 1.
    let dir = app(
        "runfiles",
        &[
            ("main.dm", ECHO.as_bytes()),
            ("s.txt", bad),
            ("k.kb", bad),
            ("w.toml", bad),
        ],
    );
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--script", "s.txt"], "s.txt:2:3"),
        (vec!["--kb", "k.kb", "--script", "s.txt"], "k.kb:2:3"),
        (vec!["--world", "w.toml"], "w.toml:2:3"),
    ];
    for (args, at) in cases {
        let mut cmd = sitlogc();
        cmd.arg("run").arg(&dir).current_dir(&dir).args(&args);
        let out = cmd.stdin(Stdio::null()).output().unwrap();
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(at), "{args:?}: {err}");
    }
    // `sitlogc kb` on a KB file.
    let out = sitlogc()
        .arg("kb")
        .arg(dir.join("k.kb"))
        .arg("class_extension(top, X)")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("k.kb:2:3"), "{}", stderr(&out));
    // Typed input.
    let mut child = sitlogc()
        .arg("run")
        .arg(&dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"caf\xc3\xa9 \xff.\n")
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("standard input:1:6"),
        "{}",
        stderr(&out)
    );
}

// ------------------------------------------------------- lost output

#[cfg(target_os = "linux")]
fn dev_full() -> std::fs::File {
    std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap()
}

#[cfg(target_os = "linux")]
#[test]
fn output_that_cannot_be_written_is_an_error() {
    let app = example("countdown");
    let script = app.join("script.txt");
    for format in ["text", "json"] {
        let out = sitlogc()
            .args(["run", "--format", format, "--script"])
            .arg(&script)
            .arg(&app)
            .stdout(dev_full())
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{format}");
        assert!(stderr(&out).contains("cannot write the report"));
    }
    let out = sitlogc()
        .args(["run", "--trace", "/dev/full", "--script"])
        .arg(&script)
        .arg(&app)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("cannot write the trace /dev/full"),
        "{}",
        stderr(&out)
    );
    // The other commands that write to stdout.
    let kb = Path::new(env!("CARGO_MANIFEST_DIR")).join("../kb/tests/data/office.kb");
    let bad = self::app("full", &[("main.dm", b"diag_mod(main, [], []).\n")]);
    let commands: Vec<Vec<std::ffi::OsString>> = vec![
        vec!["check".into(), "--format".into(), "json".into(), bad.into()],
        vec![
            "kb".into(),
            kb.into(),
            "object_property_value(tom, found_in, X)".into(),
        ],
        vec![
            "build".into(),
            "--emit".into(),
            "rust".into(),
            app.clone().into(),
        ],
    ];
    for args in commands {
        let out = sitlogc().args(&args).stdout(dev_full()).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(!stderr(&out).contains("panicked"), "{}", stderr(&out));
    }
    // A closed pipe stays quiet.
    let mut child = sitlogc()
        .args(["run", "--script"])
        .arg(&script)
        .arg(&app)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_ok(&out);
}

// --------------------------------------------------- outside input

#[test]
fn a_deep_or_long_perception_is_refused_quickly_naming_the_limit() {
    let n = 900_000;
    let deep = format!("{}a{}.\n", "f(".repeat(n), ")".repeat(n));
    let dir = app(
        "deep",
        &[("main.dm", ECHO.as_bytes()), ("s.txt", deep.as_bytes())],
    );
    let start = Instant::now();
    let out = sitlogc()
        .args(["run", "--format", "json", "--script", "s.txt"])
        .arg(&dir)
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let error = v["error"].as_str().unwrap();
    assert!(error.contains("s.txt:1:1"), "{error}");
    assert!(error.contains("--max-input-bytes"), "{error}");
    assert!(start.elapsed() < Duration::from_secs(20));
    // Under the size limit, too deep.
    let n = 20_000;
    let deep = format!("{}a{}.\n", "f(".repeat(n), ")".repeat(n));
    std::fs::write(dir.join("s.txt"), &deep).unwrap();
    let out = sitlogc()
        .args(["run", "--script", "s.txt"])
        .arg(&dir)
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("nested more than 10000 levels deep")
            && stderr(&out).contains("--max-input-depth"),
        "{}",
        stderr(&out)
    );
    // The options raise the limits.
    let out = sitlogc()
        .args(["run", "--max-input-depth", "30000", "--script", "s.txt"])
        .arg(&dir)
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_ok(&out);
    // --in-arg has the same limits (a usage error).
    let out = sitlogc()
        .args(["run", "--script", "s.txt", "--max-input-bytes", "10"])
        .args(["--in-arg", "[1,2,3,4,5,6]"])
        .arg(&dir)
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("--in-arg `[1,2,3,4,5,6]` is longer than 10 bytes"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_prolog_function_building_a_huge_term_is_stopped_by_the_time_limit() {
    let dm = "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : apply(grow(_), [x]) => fs]],
  [id ==> fs, type ==> final]
], []).
";
    let dir = app(
        "grow",
        &[
            ("main.dm", dm.as_bytes()),
            (
                "user_functions.pl",
                b"grow(_) :- length(L, 100000000), assign_func_value(L).\n",
            ),
        ],
    );
    let start = Instant::now();
    let out = sitlogc()
        .args(["run", "--prolog-time-limit", "2"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("`grow/1` exceeded the time limit of 2s per call")
            || err.contains("`grow/1` exceeded the memory limit"),
        "{err}"
    );
    assert!(err.contains("--prolog-"), "{err}");
    // Engine start-up (debug build) plus the limit.
    assert!(start.elapsed() < Duration::from_secs(60));
}

// ------------------------------------------------------- interrupts

#[cfg(unix)]
#[test]
fn sigint_stops_a_task_between_transitions_with_its_report() {
    let dir = app("sigint", &[("main.dm", LOOP.as_bytes())]);
    let trace = dir.join("t.jsonl");
    for (signal, status) in [("INT", 130), ("TERM", 143)] {
        let _ = std::fs::remove_file(&trace);
        let child = sitlogc()
            .args(["run", "--format", "json", "--history", "none", "--trace"])
            .arg(&trace)
            .arg(&dir)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Wait until the task runs (the trace grows).
        let start = Instant::now();
        while std::fs::metadata(&trace).map_or(0, |m| m.len()) < 1000 {
            assert!(start.elapsed() < Duration::from_secs(60));
            std::thread::sleep(Duration::from_millis(20));
        }
        kill(child.id(), signal);
        let out = child.wait_with_output().unwrap();
        assert_eq!(out.status.code(), Some(status), "{}", stderr(&out));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["status"], "interrupted");
        let text = std::fs::read_to_string(&trace).unwrap();
        assert!(text.ends_with('\n'));
        for line in text.lines() {
            let _: serde_json::Value = serde_json::from_str(line).unwrap();
        }
    }
    // Text: the history so far.
    let _ = std::fs::remove_file(&trace);
    let child = sitlogc()
        .arg("run")
        .arg(&dir)
        .arg("--trace")
        .arg(&trace)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while std::fs::metadata(&trace).map_or(0, |m| m.len()) < 1000 {
        assert!(start.elapsed() < Duration::from_secs(60));
        std::thread::sleep(Duration::from_millis(20));
    }
    kill(child.id(), "INT");
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with("Execution history:\n"), "{text}");
    // The error is reported once, on stderr (not in the report on stdout).
    assert!(!text.contains("interrupted"), "{text}");
    assert!(stderr(&out).contains("interrupted"), "{}", stderr(&out));
}

#[cfg(unix)]
#[test]
fn sigint_stops_a_task_waiting_at_the_prompt() {
    let dir = app("prompt", &[("main.dm", ECHO.as_bytes())]);
    let mut child = sitlogc()
        .args(["run", "--format", "json"])
        .arg(&dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stdin = child.stdin.take();
    // The prompt is on stderr once the task waits for input (the signal
    // handler is installed before the run starts).
    let mut err = child.stderr.take().unwrap();
    let mut seen = Vec::new();
    let mut byte = [0u8; 1];
    use std::io::Read;
    while !String::from_utf8_lossy(&seen).contains("|: ") {
        assert_eq!(err.read(&mut byte).unwrap(), 1, "no prompt");
        seen.push(byte[0]);
    }
    kill(child.id(), "INT");
    let out = child.wait_with_output().unwrap();
    drop(stdin);
    assert_eq!(out.status.code(), Some(130));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["status"], "interrupted");
}

// ------------------------------------------------- KB persistence

const KB_LOOP: &str = "diag_mod(main, [
  [id ==> is, type ==> neutral,
   arcs ==> [empty : [inc(n, N), apply(add_object(X, Y), [N, top])] => is]],
  [id ==> fs, type ==> final]
], [n ==> 0]).
";

/// The integer ids of the objects of class `top` in the KB file.
fn kb_objects(path: &Path) -> Vec<i64> {
    let kb = sitlog_kb::Kb::load(path).unwrap_or_else(|e| panic!("the KB must load: {e}"));
    let line = kb.query("class_extension(top, X)").unwrap().to_line();
    let inner = line.trim_start_matches('[').trim_end_matches(']');
    let mut ids: Vec<i64> = inner
        .split(',')
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap_or_else(|_| panic!("{line}")))
        .collect();
    ids.sort_unstable();
    ids
}

fn temporaries(dir: &Path) -> usize {
    std::fs::read_dir(dir)
        .unwrap()
        .filter(|e| {
            let name = e.as_ref().unwrap().file_name();
            name.to_string_lossy().ends_with(".tmp")
        })
        .count()
}

/// Kills a run persisting its KB at 40 random points (from its start to
/// well into its persisting; 100 until issue 30): every time, the KB
/// loads and holds exactly the updates up to some point (objects 1..k, k
/// never going back); temporary files of killed runs are removed by the
/// next run; a second persisting run is refused while one runs.
#[cfg(unix)]
#[test]
fn kill_9_while_persisting_leaves_a_consistent_kb_and_no_litter() {
    let dir = app(
        "persist",
        &[
            ("main.dm", KB_LOOP.as_bytes()),
            ("k.kb", b"[class(top,none,[],[],[])].\n"),
        ],
    );
    let kb = dir.join("k.kb");
    let run = || {
        sitlogc()
            .args(["run", "--history", "none", "--kb-persist", "--kb"])
            .arg(&kb)
            .arg(&dir)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let mut seed = std::process::id() as u64 | 1;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    let mut last = 0usize;
    for round in 0..40 {
        let mut child = run();
        std::thread::sleep(Duration::from_millis(40 + next() % 200));
        if round == 20 {
            // A second persisting process is refused while this one runs.
            let second = run().wait_with_output().unwrap();
            let err = stderr(&second);
            if second.status.code() == Some(2) {
                assert!(
                    err.contains("another process is persisting this KB"),
                    "{err}"
                );
            } else {
                // The first one ended before (it cannot: it loops).
                panic!("second run: {:?} {err}", second.status);
            }
        }
        child.kill().unwrap();
        child.wait().unwrap();
        let ids = kb_objects(&kb);
        let k = ids.len();
        assert_eq!(ids, (1..=k as i64).collect::<Vec<_>>(), "round {round}");
        assert!(k >= last, "round {round}: {k} objects after {last}");
        last = k;
        assert!(temporaries(&dir) <= 1, "round {round}");
    }
    assert!(last > 0, "no update was ever persisted");
    // The next persisting open removes what the last kill left.
    let lock = sitlog_kb::lock_for_persist(&kb).unwrap();
    assert_eq!(temporaries(&dir), 0);
    drop(lock);
}

/// An output naming an input (issue 31): `--trace` over the script, or over
/// the KB a run persists, would destroy it; refused before anything is
/// opened, naming both options, the files untouched.
#[test]
fn an_output_naming_an_input_is_refused_naming_both_options() {
    let dir = app(
        "same_file",
        &[
            ("main.dm", KB_LOOP.as_bytes()),
            ("k.kb", b"[class(top,none,[],[],[])].\n"),
            ("s.txt", b"go.\n"),
        ],
    );
    let script = dir.join("s.txt");
    let out = sitlogc()
        .args(["run", "--script"])
        .arg(&script)
        .arg("--trace")
        // another spelling of the same file
        .arg(dir.join(".").join("s.txt"))
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("--script and --trace name the same file"),
        "{err}"
    );
    assert_eq!(std::fs::read(&script).unwrap(), b"go.\n");
    let kb = dir.join("k.kb");
    let out = sitlogc()
        .args(["run", "--kb-persist", "--kb"])
        .arg(&kb)
        .arg("--trace")
        .arg(&kb)
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("--kb and --trace name the same file"),
        "{}",
        stderr(&out)
    );
    assert_eq!(
        std::fs::read(&kb).unwrap(),
        b"[class(top,none,[],[],[])].\n"
    );
}

// ------------------------------------------------------------ file sizes

/// Every file read is capped (`--max-file-bytes`, 256 MiB by default): a
/// larger or endless one (`/dev/zero`) is refused at once naming the file
/// and the option, with the exit status of a file that cannot be read.
#[test]
fn files_over_the_limit_are_refused_naming_the_option() {
    let dir = app("sizes", &[("main.dm", ECHO.as_bytes())]);
    // small enough for the limit: its files are read, the run's are not
    let tiny = app(
        "sizes-tiny",
        &[(
            "main.dm",
            b"diag_mod(main, [[id ==> fs, type ==> final]], []).\n",
        )],
    );
    let kb = dir.join("k.kb");
    std::fs::write(&kb, "class(object, top, [], [], []).\n".repeat(100)).unwrap();
    // a script that is a regular file is read whole (a pipe or device is
    // read as the task consumes it)
    let big = dir.join("big.txt");
    std::fs::write(&big, "a.\n".repeat(100)).unwrap();
    let cases: Vec<(Vec<std::ffi::OsString>, &str)> = vec![
        (vec!["check".into(), dir.clone().into()], "main.dm"),
        (
            vec!["kb".into(), kb.clone().into(), "objects_of(object)".into()],
            "k.kb",
        ),
        (
            vec![
                "run".into(),
                tiny.clone().into(),
                "--script".into(),
                big.clone().into(),
            ],
            "big.txt",
        ),
        (
            vec![
                "run".into(),
                tiny.clone().into(),
                "--world".into(),
                "/dev/zero".into(),
            ],
            "/dev/zero",
        ),
        (vec!["replay".into(), "/dev/zero".into()], "/dev/zero"),
    ];
    for (args, file) in cases {
        let start = Instant::now();
        let out = sitlogc()
            .args(["--max-file-bytes", "100"])
            .args(&args)
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let err = stderr(&out);
        assert!(start.elapsed() < Duration::from_secs(60), "{args:?}");
        assert!(matches!(out.status.code(), Some(1 | 2)), "{args:?}: {err}");
        assert!(err.contains("--max-file-bytes"), "{args:?}: {err}");
        assert!(err.contains(file), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
    // under the default, the same files are read
    let out = sitlogc()
        .args(["kb"])
        .arg(&kb)
        .arg("objects_of(object)")
        .output()
        .unwrap();
    assert!(
        !stderr(&out).contains("--max-file-bytes"),
        "{}",
        stderr(&out)
    );
}

/// A script from a pipe is read as the task consumes it: an endless
/// `yes 'water.'` ends with the task, and the run prints what the same
/// script from a file does.
#[test]
fn a_piped_script_is_read_term_by_term() {
    use std::io::Write;
    let app = example("tutorial");
    let mut child = sitlogc()
        .arg("run")
        .arg(&app)
        .args(["--script", "/dev/stdin", "-q"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || {
        let chunk = "water.\n".repeat(1000);
        // ends when the run closes its end of the pipe
        while stdin.write_all(chunk.as_bytes()).is_ok() {}
    });
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("the run did not end with its task");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap();
    assert_ok(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("Out Arg: water"), "{text}");
}

/// Diagnostics to a stderr that cannot be written (full, closed) never
/// panic: each command still ends with its own exit status.
#[cfg(target_os = "linux")]
#[test]
fn a_stderr_that_cannot_be_written_changes_no_exit_status() {
    let bad = app(
        "errfull",
        &[("main.dm", b"diag_mod(main, [[id ==> is]], []).\n")],
    );
    let good = example("countdown");
    let cases: Vec<(Vec<std::ffi::OsString>, i32)> = vec![
        (vec!["check".into(), bad.clone().into()], 1),
        (vec!["run".into(), bad.clone().into()], 1),
        (vec!["run".into(), "/no/such/app".into()], 2),
        (
            vec![
                "run".into(),
                good.clone().into(),
                "--script".into(),
                good.join("script.txt").into(),
            ],
            0,
        ),
        (vec!["replay".into(), "/no/such/trace".into()], 2),
    ];
    for (args, code) in cases {
        for closed in [false, true] {
            let mut cmd = sitlogc();
            cmd.args(&args).stdout(Stdio::null());
            if closed {
                // the read end of a pipe dropped at once: writes fail (EPIPE)
                cmd.stderr(Stdio::piped());
                let mut child = cmd.spawn().unwrap();
                drop(child.stderr.take());
                let status = child.wait().unwrap();
                assert_eq!(status.code(), Some(code), "{args:?} closed");
            } else {
                let out = cmd.stderr(dev_full()).output().unwrap();
                assert_eq!(out.status.code(), Some(code), "{args:?} full");
            }
        }
    }
}

/// Whether process `pid` has a thread blocked opening a FIFO and its
/// signal thread running.
#[cfg(target_os = "linux")]
fn waits_on_a_fifo(pid: u32) -> bool {
    let Ok(tasks) = std::fs::read_dir(format!("/proc/{pid}/task")) else {
        return false;
    };
    let (mut fifo, mut signals) = (false, false);
    for t in tasks.flatten() {
        let read = |f: &str| std::fs::read_to_string(t.path().join(f)).unwrap_or_default();
        fifo |= read("wchan").contains("wait_for_partner");
        signals |= read("comm").starts_with("sitlog-signals");
    }
    fifo && signals
}

/// The first SIGTERM ends a run blocked before its task starts (a FIFO
/// with no writer for --kb, --script, --world or --trace; the live view
/// waiting for its page) with the documented status, and its JSON report
/// (status `interrupted`) written.
#[cfg(target_os = "linux")]
#[test]
fn the_first_signal_ends_a_run_that_has_not_started() {
    let app = example("tutorial");
    let dir = temp("fifo");
    let fifo = dir.join("f");
    assert!(std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    for opt in ["--kb", "--script", "--world", "--trace", "--view"] {
        let mut cmd = sitlogc();
        cmd.args(["run", "--format", "json"]).arg(&app).arg(opt);
        if opt == "--view" {
            cmd.args(["--view-port", "0"]);
        } else {
            cmd.arg(&fifo);
        }
        let mut child = cmd
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let start = Instant::now();
        let mut err = child.stderr.take().unwrap();
        if opt == "--view" {
            // the line that says where the page is comes once it waits
            use std::io::BufRead;
            let mut line = String::new();
            std::io::BufReader::new(&mut err)
                .read_line(&mut line)
                .unwrap();
            assert!(line.contains("live view at"), "{line}");
        } else {
            while !waits_on_a_fifo(child.id()) {
                assert!(
                    start.elapsed() < Duration::from_secs(60),
                    "{opt}: never blocked"
                );
                std::thread::sleep(Duration::from_millis(20));
            }
        }
        kill(child.id(), "TERM");
        while child.try_wait().unwrap().is_none() {
            if start.elapsed() > Duration::from_secs(60) {
                let _ = child.kill();
                panic!("{opt}: still running after SIGTERM");
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        assert_eq!(child.wait().unwrap().code(), Some(143), "{opt}");
        let mut report = String::new();
        std::io::Read::read_to_string(&mut child.stdout.take().unwrap(), &mut report).unwrap();
        assert!(
            report.starts_with(
                r#"{"status":"interrupted","error":"interrupted before the task started","history":[]"#
            ),
            "{opt}: {report}"
        );
    }
}

/// A `models` entry naming a file that is not a DM file is refused without
/// reading it (no message quotes it); one outside the application is a
/// warning.
#[test]
fn models_entries_outside_the_application_are_not_quoted() {
    let secret = temp("secret").join("secret");
    std::fs::write(&secret, "TOP SECRET LINE\n").unwrap();
    let outside = temp("outside-dm").join("other.dm");
    std::fs::write(
        &outside,
        "diag_mod(other, [[id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    let models = format!(
        "'main.dm'.\n'{}'.\n'/proc/self/environ'.\n'{}'.\n",
        secret.display(),
        outside.display()
    );
    let dir = app(
        "foreign",
        &[
            (
                "main.dm",
                b"diag_mod(main, [[id ==> fs, type ==> final]], []).\n",
            ),
            ("models", models.as_bytes()),
        ],
    );
    let out = sitlogc().arg("check").arg(&dir).output().unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.matches("E0005").count(), 2, "{err}");
    assert!(err.contains("W0006"), "{err}");
    assert!(!err.contains("TOP SECRET"), "{err}");
    assert!(!err.contains("PATH="), "{err}");
}

/// A directive that never ends (`:- loop.`) is stopped by
/// `--prolog-time-limit` like a user function, with a located error and
/// the JSON report (issue 38; it ran until a second signal before).
#[test]
fn a_looping_directive_is_stopped_by_the_time_limit() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("main.dm"),
        "diag_mod(main,\n  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(apply(f(X), [1])) => fs ] ],\n    [ id ==> fs, type ==> final ] ],\n  []).\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("user_functions.pl"),
        "loop :- loop.\n:- loop.\nf(_) :- assign_func_value(d).\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("script.txt"), "").unwrap();
    let start = std::time::Instant::now();
    let out = crate::support::sitlogc()
        .arg("run")
        .arg(dir.path())
        .arg("--script")
        .arg(dir.path().join("script.txt"))
        .args(["--prolog-time-limit", "0.5", "--format", "json"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(start.elapsed() < std::time::Duration::from_secs(120));
    assert!(
        stdout.contains(r#""status":"error""#) && stdout.contains("--prolog-time-limit"),
        "{stdout}"
    );
    assert!(
        stderr.contains("directives exceeded the time limit"),
        "{stderr}"
    );
}

/// A directive that never ends is stopped by `--prolog-inferences` too,
/// at its place in `user_functions.pl` (issue 38).
#[test]
fn a_looping_directive_is_stopped_by_the_inference_limit() {
    let dm = "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : say(apply(f(X), [1])) => fs]],
  [id ==> fs, type ==> final]
], []).
";
    let dir = app(
        "loop-inferences",
        &[
            ("main.dm", dm.as_bytes()),
            (
                "user_functions.pl",
                b"loop :- loop.\n:- loop.\nf(_) :- assign_func_value(d).\n",
            ),
            ("script.txt", b""),
        ],
    );
    let out = sitlogc()
        .arg("run")
        .arg(&dir)
        .arg("--script")
        .arg(dir.join("script.txt"))
        .args(["--prolog-inferences", "20000", "--format", "json"])
        .args(["--prolog-time-limit", "100"])
        .output()
        .unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["status"], "error");
    assert!(
        err.contains(
            "user_functions.pl:2:1: the directive exceeded the inference limit (20000; option --prolog-inferences)"
        ),
        "{err}"
    );
}

/// The first SIGTERM ends a run whose directive loops, with its status
/// and report (issue 38: a second signal was needed).
#[cfg(unix)]
#[test]
fn the_first_signal_ends_a_looping_directive() {
    let dm = "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : say(apply(f(X), [1])) => fs]],
  [id ==> fs, type ==> final]
], []).
";
    let dir = app(
        "loop-signal",
        &[
            ("main.dm", dm.as_bytes()),
            (
                "user_functions.pl",
                b"loop :- loop.\n:- open(started, write, S), close(S), loop.\nf(_) :- assign_func_value(d).\n",
            ),
            ("script.txt", b""),
        ],
    );
    let child = sitlogc()
        .arg("run")
        .arg(&dir)
        .arg("--script")
        .arg(dir.join("script.txt"))
        .args(["--format", "json", "--prolog-inferences", "100000000000"])
        .args(["--prolog-time-limit", "600"])
        .current_dir(&dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !dir.join("started").exists() {
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "the directive did not start"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    kill(child.id(), "TERM");
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(143), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["status"], "interrupted");
    assert!(
        stderr(&out).contains("stopped by a signal"),
        "{}",
        stderr(&out)
    );
}

/// A clause of `user_functions.pl` nested deeper than the Prolog engine
/// takes is an error of `check` (E0241, its long line not quoted) and of
/// `run`, which stops before the engine starts (issue 38: the engine's
/// reader overflowed its thread's stack, SIGABRT, no report).
#[test]
fn a_prolog_clause_too_deep_for_the_engine_is_an_error_not_an_abort() {
    let n = 150_000;
    let clause = format!("d({}a{}).\n", "s(".repeat(n), ")".repeat(n));
    let dir = app(
        "deep-clause",
        &[
            ("main.dm", ECHO.as_bytes()),
            ("user_functions.pl", clause.as_bytes()),
        ],
    );
    let out = sitlogc().arg("check").arg(&dir).output().unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("[E0241] Error: this clause nests 150002 levels deep"),
        "{err}"
    );
    assert!(err.contains("user_functions.pl:1:300003"), "{err}");
    assert!(
        err.len() < 10_000,
        "the line is not quoted: {} bytes",
        err.len()
    );
    let out = sitlogc()
        .args(["run", "--format", "json"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("E0241") || stderr(&out).contains("1 error"));
    // The JSON report is written all the same, the error located in it.
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON report");
    assert_eq!(report["status"], "error", "{report}");
    let error = report["error"].as_str().unwrap_or_default();
    assert!(
        error.contains("user_functions.pl:1:300003: error[E0241]: this clause nests"),
        "{report}"
    );
    assert_eq!(report["history"], serde_json::json!([]), "{report}");
}

/// Two runs persisting one KB through a hard link (issue 38: both ran and
/// split the link): each is refused (exit 2, naming the links) and the
/// link stays whole.
#[cfg(unix)]
#[test]
fn a_hard_linked_kb_is_not_persisted_and_its_link_never_split() {
    use std::os::unix::fs::MetadataExt;
    let dir = app(
        "hardlink",
        &[
            ("main.dm", KB_LOOP.as_bytes()),
            ("k.kb", b"[class(top,none,[],[],[])].\n"),
        ],
    );
    let kb = dir.join("k.kb");
    let elsewhere = temp("hardlink-other").join("same.kb");
    std::fs::hard_link(&kb, &elsewhere).unwrap();
    for name in [&kb, &elsewhere] {
        let out = sitlogc()
            .args(["run", "--history", "none", "--kb-persist", "--kb"])
            .arg(name)
            .arg(&dir)
            .output()
            .unwrap();
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains("has 2 hard links"), "{err}");
    }
    let (a, b) = (
        std::fs::metadata(&kb).unwrap(),
        std::fs::metadata(&elsewhere).unwrap(),
    );
    assert_eq!((a.ino(), a.nlink()), (b.ino(), 2));
    assert_eq!(
        std::fs::read(&kb).unwrap(),
        b"[class(top,none,[],[],[])].\n"
    );
}
