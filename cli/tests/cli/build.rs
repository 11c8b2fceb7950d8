//! `sitlogc build`: an example application compiled to an executable (one
//! nested cargo build, offline when the dependencies are on the machine)
//! gives byte-identical output to `sitlogc run`; `--emit rust` prints the
//! generated code; the default output name, `build .`, failures that leave
//! nothing behind, and a sitlogc that works away from its checkout (the
//! runtime it compiles against is embedded and extracted into the cache);
//! `--debugger` builds that debug as `sitlogc debug` does.

use crate::support::{assert_ok, workspace};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The cache every test build shares (inside the target dir, so the tests
/// leave nothing in the user's cache and reuse one build cache).
fn cache() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("sitlogc-cache")
}

fn sitlogc() -> Command {
    let mut cmd = crate::support::sitlogc();
    cmd.env("SITLOGC_CACHE_DIR", cache());
    no_debug_info(&mut cmd);
    cmd
}

/// The nested cargo builds the generated package without debug info: its
/// workspace has no [profile], and full debug info only slows the tests
/// down (issue 30; nothing here reads it).
fn no_debug_info(cmd: &mut Command) -> &mut Command {
    cmd.env("CARGO_PROFILE_DEV_DEBUG", "false")
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A fresh copy of the example `name` in a new temporary directory.
fn copy_example(name: &str) -> (tempfile::TempDir, PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let from = workspace().join("dms/examples").join(name);
    let to = tmp.path().join(name);
    std::fs::create_dir(&to).unwrap();
    for entry in std::fs::read_dir(&from).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
    }
    (tmp, to)
}

/// What the tests of `sitlogc build` without a real build share: a copy of
/// an example in a temporary directory, a sitlogc cache of its own there,
/// and (on unix) a `cargo` that succeeds without building anything, so that
/// `sitlogc build` writes the package and then fails when it copies the
/// (missing) executable.
struct Scratch {
    tmp: tempfile::TempDir,
    app: PathBuf,
    cache: PathBuf,
}

impl Scratch {
    fn new(example: &str) -> Scratch {
        let (tmp, app) = copy_example(example);
        let cache = tmp.path().join("cache");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let cargo = tmp.path().join("fake-cargo");
            std::fs::write(&cargo, "#!/bin/sh\nexit 0\n").unwrap();
            std::fs::set_permissions(&cargo, std::fs::Permissions::from_mode(0o755)).unwrap();
        }
        Scratch { tmp, app, cache }
    }

    /// `sitlogc build` with this cache and the fake cargo.
    fn build(&self) -> Command {
        let mut cmd = sitlogc();
        cmd.env("SITLOGC_CACHE_DIR", &self.cache);
        #[cfg(unix)]
        cmd.env("CARGO", self.tmp.path().join("fake-cargo"));
        cmd.arg("build");
        cmd
    }

    /// A path in the temporary directory.
    fn path(&self, name: &str) -> PathBuf {
        self.tmp.path().join(name)
    }
}

#[test]
fn default_output_that_is_the_app_directory_is_refused_before_building() {
    let s = Scratch::new("countdown");
    let out = s
        .build()
        .arg("countdown")
        .current_dir(s.tmp.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("the default output `countdown` is a directory"),
        "{err}"
    );
    assert!(err.contains("-o countdown-task"), "{err}");
    // Refused before anything was extracted, generated or built.
    assert!(!s.cache.exists());
    // -o naming a directory is refused too.
    let out = s
        .build()
        .args(["countdown", "-o", "."])
        .current_dir(s.tmp.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("it is a directory"),
        "{}",
        stderr(&out)
    );
}

/// `build .` is named after the directory's real name, and a failed copy of
/// the executable leaves no temporary file.
#[cfg(unix)]
#[test]
fn build_dot_is_named_after_the_directory_and_failures_leave_nothing() {
    let s = Scratch::new("countdown");
    let app = &s.app;
    let out = s.build().arg(".").current_dir(app).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("cannot copy"), "{}", stderr(&out));
    assert!(s.cache.join("apps/countdown/Cargo.toml").is_file());
    // Nothing but the application's own files beside it.
    let mut names: Vec<String> = std::fs::read_dir(app)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "expected.json",
            "global_vars.pl",
            "main.dm",
            "models",
            "script.txt"
        ]
    );
    // cargo itself failing: the same.
    let out = s
        .build()
        .env("CARGO", "false")
        .args([".", "-o", "out/task"])
        .current_dir(app)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("cargo build failed"),
        "{}",
        stderr(&out)
    );
    assert!(!app.join("out").exists());
}

/// The generated package depends on the runtime extracted into the cache,
/// not on this checkout; the extracted copy is the workspace's sources.
#[cfg(unix)]
#[test]
fn generated_package_uses_the_embedded_runtime() {
    let s = Scratch::new("countdown");
    let (app, cache) = (&s.app, &s.cache);
    let out = s
        .build()
        .arg(app)
        .arg("-o")
        .arg(s.path("countdown-task"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let manifest = std::fs::read_to_string(cache.join("apps/countdown/Cargo.toml")).unwrap();
    let runtimes: Vec<_> = std::fs::read_dir(cache.join("runtime"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(runtimes.len(), 1, "{runtimes:?}");
    let runtime = &runtimes[0];
    assert!(
        manifest.contains(&format!("path = \"{}/runtime\"", runtime.display())),
        "{manifest}"
    );
    assert!(
        !manifest.contains(&workspace().display().to_string()),
        "{manifest}"
    );
    for file in [
        "runtime/src/lib.rs",
        "robot/src/cli.rs",
        "view/src/page.html",
        "debug/src/task.rs",
        "Cargo.lock",
    ] {
        assert_eq!(
            std::fs::read(runtime.join(file)).unwrap(),
            std::fs::read(workspace().join(file)).unwrap(),
            "{file}"
        );
    }
    let root = std::fs::read_to_string(runtime.join("Cargo.toml")).unwrap();
    assert!(
        root.contains("members = [\"syntax\", \"runtime\""),
        "{root}"
    );
    assert!(!root.contains("\"compiler\", \"graph\""), "{root}");
    assert!(!root.contains("[profile"), "{root}");
    // Extracted once: a second build reuses it, and leaves no temporary directory.
    let again = s
        .build()
        .arg(app)
        .arg("-o")
        .arg(s.path("t"))
        .output()
        .unwrap();
    assert_eq!(again.status.code(), Some(2));
    assert_eq!(std::fs::read_dir(cache.join("runtime")).unwrap().count(), 1);
    // The edit loop's profile (issue 40): no LTO, the task's crate
    // incremental, the runtime crates not (in `--debug` builds too);
    // `--lto` builds with the `lto` profile (fat LTO).
    for line in [
        "[profile.release]\nlto = \"off\"\ncodegen-units = 16\ndebug = false\n",
        "[profile.release.package.sitlog-app-countdown]\nincremental = true\n",
        "[profile.dev]\nincremental = false\n",
        "[profile.dev.package.sitlog-app-countdown]\nincremental = true\n",
        "[profile.lto]\ninherits = \"release\"\nlto = \"fat\"\ncodegen-units = 1\n",
    ] {
        assert!(manifest.contains(line), "{line}\n{manifest}");
    }
    // The Prolog engine's never-run dependencies are not optimised, only
    // where the engine is linked (an application with Prolog functions).
    assert!(
        !manifest.contains("[profile.release.package.crrl]"),
        "{manifest}"
    );
    let (_prolog_tmp, prolog_app) = copy_example("appendix_a");
    let out = s
        .build()
        .arg(&prolog_app)
        .arg("-o")
        .arg(s.path("t"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let prolog = std::fs::read_to_string(cache.join("apps/appendix_a/Cargo.toml")).unwrap();
    assert!(prolog.contains("features = [\"prolog\"]"), "{prolog}");
    assert!(
        prolog.contains("[profile.release.package.crrl]\nopt-level = 0\n"),
        "{prolog}"
    );
    let lto = s
        .build()
        .arg("--lto")
        .arg(app)
        .arg("-o")
        .arg(s.path("t"))
        .output()
        .unwrap();
    assert_eq!(lto.status.code(), Some(2));
    assert!(
        stderr(&lto).contains(&format!(
            "{}",
            Path::new("lto").join("sitlog-app-countdown").display()
        )),
        "{}",
        stderr(&lto)
    );
    // Only with --debugger does the task link the debugger and start in it.
    let main = std::fs::read_to_string(cache.join("apps/countdown/src/main.rs")).unwrap();
    assert!(!manifest.contains("sitlog-debug"), "{manifest}");
    assert!(main.contains("sitlog_robot::main("), "{main}");
    let debugger = s
        .build()
        .arg("--debugger")
        .arg(app)
        .arg("-o")
        .arg(s.path("t"))
        .output()
        .unwrap();
    assert_eq!(debugger.status.code(), Some(2));
    let manifest = std::fs::read_to_string(cache.join("apps/countdown/Cargo.toml")).unwrap();
    let main = std::fs::read_to_string(cache.join("apps/countdown/src/main.rs")).unwrap();
    assert!(
        manifest.contains(&format!(
            "sitlog-debug = {{ path = \"{}/debug\" }}",
            runtime.display()
        )),
        "{manifest}"
    );
    assert!(main.contains("sitlog_debug::task_main("), "{main}");
}

#[test]
fn emit_rust_prints_generated_code() {
    let out = sitlogc()
        .args(["build", "--emit", "rust"])
        .arg(workspace().join("dms/examples/countdown"))
        .output()
        .unwrap();
    assert_ok(&out);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("// This file is @generated by sitlog-compiler"));
    assert!(text.contains("pub mod dm_main"));
}

#[test]
fn build_rejects_a_bad_application() {
    let dir = crate::support::temp_root().join(format!("sitlogc-build-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> final]], [] .\n",
    )
    .unwrap();
    let out = sitlogc().arg("build").arg(&dir).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("main.dm"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn built_executable_runs_like_sitlogc_run() {
    let app = workspace().join("dms/examples/pipe");
    let dir = crate::support::temp_root().join(format!("sitlogc-build-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // As an installed sitlogc: a copy of the binary, run from elsewhere,
    // with the default output name (the app is not in the current directory).
    let installed = dir.join("bin/sitlogc");
    std::fs::create_dir_all(installed.parent().unwrap()).unwrap();
    std::fs::copy(crate::support::SITLOGC, &installed).unwrap();
    let exe = dir.join("pipe");
    let mut build = Command::new(&installed);
    no_debug_info(&mut build)
        .env("SITLOGC_CACHE_DIR", cache())
        .arg("build")
        .arg("--debug")
        .arg(&app)
        .current_dir(&dir);
    // Another test's thread forking while the copy was open for writing
    // keeps it open in that child until it execs: the copy is "busy" for
    // that moment (ETXTBSY); try again.
    let mut tries = 0;
    let status = loop {
        match build.status() {
            Err(e) if e.kind() == std::io::ErrorKind::ExecutableFileBusy && tries < 100 => {
                tries += 1;
                std::thread::sleep(std::time::Duration::from_millis(50));
            }
            other => break other.unwrap(),
        }
    };
    assert!(status.success());
    assert!(exe.is_file());
    let script = app.join("script.txt");
    for format in ["json", "text"] {
        let compiled = Command::new(&exe)
            .args(["--format", format, "--script"])
            .arg(&script)
            .output()
            .unwrap();
        let interpreted = sitlogc()
            .args(["run", "--format", format, "--script"])
            .arg(&script)
            .arg(&app)
            .output()
            .unwrap();
        assert_eq!(compiled.status.code(), Some(0));
        assert_eq!(
            String::from_utf8_lossy(&compiled.stdout),
            String::from_utf8_lossy(&interpreted.stdout)
        );
        assert_eq!(compiled.stderr, interpreted.stderr);
    }
    // Output that cannot be written is an error (issue 23), as for `sitlogc run`.
    #[cfg(target_os = "linux")]
    for format in ["json", "text"] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let out = Command::new(&exe)
            .args(["--format", format, "--script"])
            .arg(&script)
            .stdout(full)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{format}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("cannot write the report"));
    }
    // The options of `sitlogc run`: usage errors exit 2, --help exits 0.
    let bad = Command::new(&exe).arg("--format=xml").output().unwrap();
    assert_eq!(bad.status.code(), Some(2));
    let help = Command::new(&exe).arg("--help").output().unwrap();
    assert!(help.status.success());
    assert!(String::from_utf8_lossy(&help.stdout).contains("--in-arg"));
    assert!(String::from_utf8_lossy(&help.stdout).contains("--max-input-bytes"));
    assert!(String::from_utf8_lossy(&help.stdout).contains("--view"));
    // Named after the application, with run's KB options, and saying it does not reload.
    let help = String::from_utf8_lossy(&help.stdout).into_owned();
    assert!(help.contains("Usage: pipe [OPTIONS]"), "{help}");
    assert!(
        help.contains("--kb <FILE>") && help.contains("--kb-persist"),
        "{help}"
    );
    assert!(help.contains("no reloading"), "{help}");
    assert!(!help.contains("PROGRAM"), "{help}");
    // Compiled tasks do not reload (issue 21): their help says so.
    assert!(help.contains("does not reload"), "{help}");
    // Without --debugger, no debugger (see built_with_debugger_debugs_like_sitlogc_debug).
    assert!(!help.contains("--commands"), "{help}");
    // The live view works on the compiled task too: its diagram is embedded.
    let mut child = Command::new(&exe)
        .args(["--view", "--format", "json", "--script"])
        .arg(&script)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = std::io::BufReader::new(child.stderr.take().unwrap());
    let addr = loop {
        let mut line = String::new();
        use std::io::BufRead;
        assert!(
            stderr.read_line(&mut line).unwrap() > 0,
            "no live view address"
        );
        if let Some(at) = line.find("http://127.0.0.1:") {
            let rest = &line[at + "http://".len()..];
            break rest[..rest.find('/').unwrap()].to_owned();
        }
    };
    let mut stream = std::net::TcpStream::connect(&addr).unwrap();
    use std::io::{Read, Write};
    write!(stream, "GET /events HTTP/1.1\r\nHost: {addr}\r\n\r\n").unwrap();
    let mut events = String::new();
    stream.read_to_string(&mut events).unwrap();
    assert!(
        events.contains(r#"data: {"end":true,"message":"","status":"ok"}"#),
        "{events}"
    );
    assert!(events.contains(r#""node":"d0.s0""#), "{events}");
    assert!(child.wait().unwrap().success());
    let _ = std::fs::remove_dir_all(&dir);
}

/// `sitlogc build --debugger` (issue 21): the compiled task runs under the
/// step debugger, as `sitlogc debug` runs the sources. The same commands
/// file gives the same session. The one documented difference: fresh
/// variables that `print` shows (`_G5`) are numbered by each run's store,
/// so they are compared with their numbers left out.
#[test]
fn built_with_debugger_debugs_like_sitlogc_debug() {
    let app = workspace().join("tests/dms/debug_app");
    let dir = crate::support::temp_root().join(format!("sitlogc-build-dbg-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let exe = dir.join("debug_app");
    let out = sitlogc()
        .args(["build", "--debug", "--debugger", "-o"])
        .arg(&exe)
        .arg(&app)
        .output()
        .unwrap();
    assert_ok(&out);
    let commands = dir.join("commands.txt");
    std::fs::write(
        &commands,
        "break ask:is\ncontinue\nstack\nvars\npipe\nstep\nstep\nstack\nvars\n\
         print f(Color)\nhistory\nnext\ncontinue\n",
    )
    .unwrap();
    let script = app.join("script.txt");
    let compiled = Command::new(&exe)
        .arg("--script")
        .arg(&script)
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    let interpreted = sitlogc()
        .arg("debug")
        .arg(&app)
        .arg("--script")
        .arg(&script)
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    let fresh = |o: &std::process::Output| {
        let text = String::from_utf8_lossy(&o.stdout);
        let mut out = String::new();
        let mut chars = text.chars().peekable();
        while let Some(c) = chars.next() {
            out.push(c);
            if c == 'G' && out.ends_with("_G") {
                while chars.peek().is_some_and(|d| d.is_ascii_digit()) {
                    chars.next();
                }
            }
        }
        out
    };
    assert_ok(&compiled);
    assert_eq!(interpreted.status.code(), Some(0));
    let session = fresh(&compiled);
    assert_eq!(session, fresh(&interpreted));
    assert_eq!(compiled.stderr, interpreted.stderr);
    for seen in [
        "(sitlog) break ask:is\nbreakpoint 1: ask:is\n",
        "-- breakpoint 1 (ask:is)\n",
        "(sitlog) stack\n#1 ask(color)  after is\n#0 main  in ask1\n",
        "locals of #0 main:\n  color = red\n",
        "(sitlog) print f(Color)\nf(_G)\n",
        "(end of the commands: the run goes on without stopping)\n",
        "Out Arg: color\n",
    ] {
        assert!(session.contains(seen), "{seen:?} in\n{session}");
    }
    // A bad commands file: exit 2 naming FILE:LINE, as `sitlogc debug`.
    std::fs::write(&commands, "break ask:is\nfrobnicate\n").unwrap();
    let bad = Command::new(&exe)
        .arg("--script")
        .arg(&script)
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    assert!(stderr(&bad).contains("commands.txt:2"), "{}", stderr(&bad));
    // Its help: the task's options, --commands, and that it is a debugger build.
    let help = Command::new(&exe).arg("--help").output().unwrap();
    assert!(help.status.success());
    let help = String::from_utf8_lossy(&help.stdout).into_owned();
    assert!(help.contains("Usage: debug_app [OPTIONS]"), "{help}");
    assert!(help.contains("--commands <FILE>"), "{help}");
    assert!(help.contains("--script <FILE>"), "{help}");
    assert!(help.contains("sitlogc build --debugger"), "{help}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A compiled task stops at a transition boundary on SIGINT, with its
/// JSON object and exit status 130 (issue 23).
#[cfg(unix)]
#[test]
fn built_executable_stops_on_sigint() {
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let dir = crate::support::temp_root().join(format!("sitlogc-build-int-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let app = dir.join("spin");
    std::fs::create_dir_all(&app).unwrap();
    std::fs::write(
        app.join("main.dm"),
        "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : inc(n, _) => is]],
  [id ==> fs, type ==> final]
], [n ==> 0]).
",
    )
    .unwrap();
    // Into a directory that does not exist yet: it is made.
    let exe = dir.join("bin/spin-task");
    let status = sitlogc()
        .arg("build")
        .arg("--debug")
        .arg(&app)
        .arg("-o")
        .arg(&exe)
        .status()
        .unwrap();
    assert!(status.success());
    let trace = dir.join("t.jsonl");
    let child = Command::new(&exe)
        .args(["--format", "json", "--history", "none", "--trace"])
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
    crate::support::kill(child.id(), "INT");
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["status"], "interrupted");
    for line in std::fs::read_to_string(&trace).unwrap().lines() {
        let _: serde_json::Value = serde_json::from_str(line).unwrap();
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `build --allow-unresolved` compiles what `run --allow-unresolved` runs;
/// without it the unresolved names are errors.
#[test]
fn allow_unresolved_compiles_what_run_allows() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(
        tmp.path().join("main.dm"),
        "diag_mod(main, [
  [id ==> is, type ==> speech, arcs ==> [go : [] => fs, away : [] => nowhere]],
  [id ==> fs, type ==> final]
], []).
",
    )
    .unwrap();
    let build = |extra: &[&str]| {
        sitlogc()
            .args(["build", "--emit", "rust"])
            .args(extra)
            .arg(tmp.path())
            .output()
            .unwrap()
    };
    let strict = build(&[]);
    assert_eq!(strict.status.code(), Some(1));
    assert!(stderr(&strict).contains("nowhere"), "{}", stderr(&strict));
    let lenient = build(&["--allow-unresolved"]);
    assert_ok(&lenient);
    assert!(String::from_utf8_lossy(&lenient.stdout).contains("pub mod dm_main"));
}

/// E14 under `--deny-warnings` (issue 39): an in_arg the pipe does not
/// match is one error, the same bytes from `sitlogc run` and from a
/// compiled task (its own `--deny-warnings`), located at the in_arg as
/// the warning is (`file:line:column`), naming the pattern and the pipe
/// with their variables numbered alike (`_G0`, ..) in both back ends.
#[test]
fn a_denied_in_arg_is_the_same_located_error_run_or_compiled() {
    let tmp = tempfile::tempdir().unwrap();
    let app = tmp.path().join("inarg");
    std::fs::create_dir(&app).unwrap();
    std::fs::write(
        app.join("main.dm"),
        "diag_mod(main,
  [ [id ==> s0, type ==> recursive, embedded_dm ==> sub(_),
      arcs ==> [done : empty => fs]],
    [id ==> fs, type ==> final] ], []).

diag_mod(sub(_),
  [ [id ==> is, type ==> neutral, in_arg ==> f(X, b),
      arcs ==> [empty : say(X) => done]],
    [id ==> done, type ==> final] ], []).
",
    )
    .unwrap();
    let out = sitlogc()
        .args(["build", "--debug", "-o", "task", "inarg"])
        .current_dir(tmp.path())
        .output()
        .unwrap();
    assert_ok(&out);
    let args = ["--deny-warnings", "--in-arg", "f(1,c)", "--format"];
    let mut errors = Vec::new();
    for format in ["json", "text"] {
        let compiled = Command::new(tmp.path().join("task"))
            .args(args)
            .arg(format)
            .current_dir(tmp.path())
            .output()
            .unwrap();
        let interpreted = sitlogc()
            .args(["run", "inarg"])
            .args(args)
            .arg(format)
            .env("NO_COLOR", "1")
            .current_dir(tmp.path())
            .output()
            .unwrap();
        assert_eq!(compiled.status.code(), Some(1), "{}", stderr(&compiled));
        assert_eq!(
            interpreted.status.code(),
            Some(1),
            "{}",
            stderr(&interpreted)
        );
        assert_eq!(compiled.stdout, interpreted.stdout, "{format}");
        if format == "json" {
            let v: serde_json::Value = serde_json::from_slice(&compiled.stdout).unwrap();
            errors.push(v["error"].as_str().unwrap().to_owned());
        } else {
            // The compiled task prints the error's line, the interpreter
            // the same message at the in_arg in the source.
            errors.push(stderr(&compiled));
            let text = stderr(&interpreted);
            let trimmed: Vec<&str> = text.lines().map(str::trim_end).collect();
            errors.push(trimmed.join("\n"));
        }
    }
    insta::assert_snapshot!("denied_in_arg", errors.join("\n----\n"));
}
