//! The operating system's sandbox (issue 38): each row of the table
//! of attacks, written as an application's `user_functions.pl` would write
//! it (module-qualified, as a closure, built by name with `=..`), leaves
//! its canary untouched, opens no socket and runs no command, where the
//! Prolog-level refusals alone let it through. Each test needs the kernel's
//! Landlock (ABI 4 or later, for TCP) and seccomp, and says so and returns
//! where they are missing (a container without them).

use std::path::{Path, PathBuf};

use crate::support::{assert_ok, sitlogc};

const MAIN: &str = "diag_mod(main,\n  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(apply(attack(X), [1])) => fs ] ],\n    [ id ==> fs, type ==> final ] ],\n  []).\n";

/// Wraps each attack so that the function goes on to the next one: `t(G)`
/// runs G and ignores its outcome.
const PRELUDE: &str = ":- use_module(library(os)).\n:- use_module(library(process)).\n:- use_module(library(sockets)).\n:- use_module(library(files)).\n:- use_module(library(pio)).\n:- use_module(library(lists)).\nt(G) :- catch((G -> true ; true), _, true).\n";

/// Whether this kernel can hold the task; else prints why the test skips.
fn kernel_confines(test: &str) -> bool {
    let (abi, seccomp) = sitlog_robot::sandbox::support();
    if abi < 4 || !seccomp {
        eprintln!(
            "skipping {test}: this kernel lacks the sandbox (Landlock ABI {abi}, 4 needed; seccomp {seccomp})"
        );
        return false;
    }
    true
}

/// A scratch directory with `app/` (main.dm, an empty script, the
/// `user_functions.pl` made by `attack` from the outside directory) and
/// `outside/` (where the canaries are), and its path.
struct Scratch {
    root: PathBuf,
}

impl Scratch {
    fn new(name: &str, attack: impl Fn(&str) -> String) -> Scratch {
        let root = crate::support::temp_root()
            .join(format!("sitlogc-sandbox-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(root.join("app")).unwrap();
        std::fs::create_dir_all(root.join("outside")).unwrap();
        let s = Scratch { root };
        std::fs::write(s.app().join("main.dm"), MAIN).unwrap();
        std::fs::write(s.app().join("script.txt"), "").unwrap();
        let outside = s.outside().display().to_string();
        let code = format!("{PRELUDE}{}", attack(&outside));
        std::fs::write(s.app().join("user_functions.pl"), code).unwrap();
        s
    }

    fn app(&self) -> PathBuf {
        self.root.join("app")
    }

    fn outside(&self) -> PathBuf {
        self.root.join("outside")
    }

    /// Creates `name` in the outside directory with `text`.
    fn canary(&self, name: &str) -> PathBuf {
        let p = self.outside().join(name);
        std::fs::write(&p, "canary").unwrap();
        p
    }

    /// Runs the application in test mode with `extra` options; the output.
    fn run(&self, extra: &[&str]) -> std::process::Output {
        let out = sitlogc()
            .env("SHELL", "/bin/sh")
            .arg("run")
            .arg(self.app())
            .arg("--script")
            .arg(self.app().join("script.txt"))
            .arg("-q")
            .args(extra)
            .output()
            .unwrap();
        // The attack may fail the function (exit 1); the process must end
        // by itself, never by a signal.
        assert!(
            matches!(out.status.code(), Some(0 | 1)),
            "{:?}: {}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
        out
    }

    /// The names in the outside directory, sorted.
    fn outside_names(&self) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(self.outside())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.root);
    }
}

/// `atom_chars` of a path in `dir` (for the predicates that take text).
fn chars(var: &str, path: &str) -> String {
    format!("atom_chars('{path}', {var})")
}

#[test]
fn a_shell_command_as_a_closure_does_not_run() {
    if !kernel_confines("a_shell_command_as_a_closure_does_not_run") {
        return;
    }
    let s = Scratch::new("shell", |o| {
        format!(
            "attack(_) :- {}, t(call(os:shell, C1)), {}, t(call(os:shell, C2, _)), {}, t(maplist(os:shell, [C3])), {}, t((G =.. [shell, C4], call(G))), assign_func_value(d).\n",
            chars("C1", &format!("touch {o}/p1")),
            chars("C2", &format!("touch {o}/p2")),
            chars("C3", &format!("touch {o}/p3")),
            chars("C4", &format!("touch {o}/p4")),
        )
    });
    s.run(&[]);
    assert_eq!(s.outside_names(), Vec::<String>::new(), "a command ran");
    // Under the debugger too (its engine thread is the same kind).
    let commands = s.app().join("commands.txt");
    std::fs::write(&commands, "continue\n").unwrap();
    let out = sitlogc()
        .env("SHELL", "/bin/sh")
        .arg("debug")
        .arg(s.app())
        .arg("--script")
        .arg(s.app().join("script.txt"))
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    assert!(
        matches!(out.status.code(), Some(0 | 1)),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        s.outside_names(),
        Vec::<String>::new(),
        "a command ran under the debugger"
    );
    // --allow-os lifts the sandbox with the refusals: the same code runs.
    s.run(&["--allow-os"]);
    assert_eq!(s.outside_names(), ["p1", "p2", "p3", "p4"]);
}

/// The attacks on processes, sockets and files outside the application, in
/// one function (one run, one Prolog engine start): no process is created
/// (`process_create` as a closure and built by name), no socket is opened
/// (a server on a free port, a client to a listener, by closure and by
/// name: the function says what it opened), no file is written (`tell`,
/// `phrase_to_file`, `open` by name and as a closure), and none is deleted,
/// renamed or created (`delete_file` plain, qualified and by name,
/// `rename_file`, `make_directory`). Inside the application, writing stays
/// allowed.
#[test]
fn processes_sockets_and_files_outside_are_out_of_reach() {
    if !kernel_confines("processes_sockets_and_files_outside_are_out_of_reach") {
        return;
    }
    // A listener the attack tries to reach, and a port it tries to open.
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    listener.set_nonblocking(true).unwrap();
    let port = listener.local_addr().unwrap().port();
    let free = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let free_port = free.local_addr().unwrap().port();
    drop(free);
    let s = Scratch::new("attacks", |o| {
        format!(
            "r(G, R) :- (catch(G, _, fail) -> R = opened ; R = refused).\n\
             attack(_) :- \
             {}, {}, t(call(process:process_create, T, [P1], [])), {}, t((G =.. [process_create, T, [P2], []], call(G))), \
             r(call(sockets:socket_server_open, '127.0.0.1':{free_port}, _), R1), \
             r(call(sockets:socket_client_open, '127.0.0.1':{port}, _, []), R2), \
             r((G2 =.. [socket_client_open, '127.0.0.1':{port}, _, []], call(G2)), R3), \
             t((tell('{o}/told'), write(x), told)), \
             t(phrase_to_file(\"x\", '{o}/phrase')), \
             t((G3 =.. [open, '{o}/named', write, S], call(G3), write(S, x), close(S))), \
             t((call(open, '{o}/closure', append, S2), write(S2, x), close(S2))), \
             {}, t(delete_file(C1)), t(call(files:delete_file, C1)), {}, {}, t(call(files:rename_file, C2, R)), {}, t(call(files:make_directory, M)), {}, t((G4 =.. [delete_file, C3], call(G4))), \
             assign_func_value([R1, R2, R3]).\n",
            chars("T", "/usr/bin/touch"),
            chars("P1", &format!("{o}/p1")),
            chars("P2", &format!("{o}/p2")),
            chars("C1", &format!("{o}/canary1")),
            chars("C2", &format!("{o}/canary2")),
            chars("R", &format!("{o}/renamed")),
            chars("M", &format!("{o}/made")),
            chars("C3", &format!("{o}/canary3")),
        )
    });
    for c in ["canary1", "canary2", "canary3"] {
        s.canary(c);
    }
    let out = s.run(&[]);
    // Nothing created (no process's p1/p2, no written file, nothing renamed
    // or made), nothing deleted.
    assert_eq!(s.outside_names(), ["canary1", "canary2", "canary3"]);
    for c in ["canary1", "canary2", "canary3"] {
        assert_eq!(
            std::fs::read_to_string(s.outside().join(c)).unwrap(),
            "canary"
        );
    }
    // The function says what it opened.
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("say([refused,refused,refused])"),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        matches!(listener.accept(), Err(e) if e.kind() == std::io::ErrorKind::WouldBlock),
        "the task connected"
    );
    // Inside the application, writing stays allowed.
    let inside = Scratch::new("write-inside", |_| {
        "attack(_) :- open('marker', write, S), write(S, x), close(S), assign_func_value(d).\n"
            .to_owned()
    });
    let marker = inside.app().join("marker");
    let out = sitlogc()
        .current_dir(inside.app())
        .args(["run", ".", "--script", "script.txt", "-q"])
        .output()
        .unwrap();
    assert_ok(&out);
    assert!(marker.exists());
}

#[test]
fn the_kb_directory_is_no_write_permission() {
    if !kernel_confines("the_kb_directory_is_no_write_permission") {
        return;
    }
    let s = Scratch::new("kb", |o| {
        format!(
            "attack(_) :- t((open('{o}/bashrc', write, S), write(S, x), close(S))), assign_func_value(d).\n"
        )
    });
    let kb = s.outside().join("x.kb");
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../kb/tests/data/office.kb"),
        &kb,
    )
    .unwrap();
    let kb_arg = kb.display().to_string();
    // The engine's refusal alone (the sandbox off): the guards no longer
    // count the KB's directory as the application's (Landlock holds it
    // too: files_are_not_written_anywhere).
    s.run(&["--kb", &kb_arg, "--sandbox", "off"]);
    assert_eq!(
        s.outside_names(),
        ["x.kb"],
        "the KB's directory was written"
    );
    // --kb-persist writes the KB (by replacing it), not other files.
    s.run(&["--kb", &kb_arg, "--kb-persist"]);
    let names = s.outside_names();
    assert!(!names.contains(&"bashrc".to_owned()), "{names:?}");
}

#[test]
fn sandbox_require_and_off() {
    // `require` runs here (the kernel has it); `off` keeps the Prolog-level
    // refusals only: the closure's shell command then runs.
    if !kernel_confines("sandbox_require_and_off") {
        return;
    }
    let s = Scratch::new("modes", |o| {
        format!(
            "attack(_) :- {}, t(call(os:shell, C)), assign_func_value(d).\n",
            chars("C", &format!("touch {o}/p"))
        )
    });
    let out = s.run(&["--sandbox", "require"]);
    assert!(
        !String::from_utf8_lossy(&out.stderr).contains("without the operating system's sandbox")
    );
    assert_eq!(s.outside_names(), Vec::<String>::new());
    s.run(&["--sandbox", "off"]);
    assert_eq!(s.outside_names(), ["p"]);
    // A kernel without Landlock (its system calls answer ENOSYS, as an old
    // kernel's do): `require` is an error before any application code
    // runs, exit 2, its JSON report written; `auto` says so once and runs
    // on the engine's refusals and seccomp.
    #[cfg(target_os = "linux")]
    without_landlock_require_and_auto(&s);
}

/// The end of [`sandbox_require_and_off`]: `--sandbox require` and `auto`
/// on a kernel without Landlock.
#[cfg(target_os = "linux")]
fn without_landlock_require_and_auto(s: &Scratch) {
    // An application without Prolog (no engine to start: cheap).
    let plain = s.root.join("plain");
    std::fs::create_dir_all(&plain).unwrap();
    std::fs::write(
        plain.join("main.dm"),
        MAIN.replace("apply(attack(X), [1])", "hello"),
    )
    .unwrap();
    std::fs::write(plain.join("script.txt"), "").unwrap();
    let without = |mode: &str| {
        let mut cmd = sitlogc();
        cmd.arg("run")
            .arg(&plain)
            .arg("--script")
            .arg(plain.join("script.txt"))
            .args(["-q", "--format", "json", "--sandbox", mode]);
        without_landlock(&mut cmd);
        cmd.output().unwrap()
    };
    let out = without("require");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a JSON report");
    assert_eq!(report["status"], "error", "{report}");
    assert!(
        report["error"]
            .as_str()
            .is_some_and(|e| e
                .starts_with("--sandbox require: this system cannot confine the task: Landlock")),
        "{report}"
    );
    let out = without("auto");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert_eq!(
        err.matches("note: the task runs without the operating system's sandbox (Landlock")
            .count(),
        1,
        "{err}"
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a JSON report");
    assert_eq!(report["status"], "ok", "{report}");
}

#[cfg(target_os = "linux")]
/// Makes `cmd`'s process see a kernel without Landlock: a seccomp filter,
/// installed before it starts, answers Landlock's system calls (444 to
/// 446 on every architecture) with ENOSYS and lets every other call
/// through.
fn without_landlock(cmd: &mut std::process::Command) {
    use std::os::unix::process::CommandExt;
    const LD_W_ABS: u16 = 0x20;
    const JMP_JGE_K: u16 = 0x35;
    const JMP_JGT_K: u16 = 0x25;
    const RET_K: u16 = 0x06;
    const RET_ERRNO: u32 = 0x0005_0000;
    const RET_ALLOW: u32 = 0x7fff_0000;
    let op = |code, jt, jf, k| libc::sock_filter { code, jt, jf, k };
    let program = [
        op(LD_W_ABS, 0, 0, 0),                            // the call's number
        op(JMP_JGE_K, 0, 2, 444),                         // below 444: allow
        op(JMP_JGT_K, 1, 0, 446),                         // above 446: allow
        op(RET_K, 0, 0, RET_ERRNO | libc::ENOSYS as u32), // Landlock's
        op(RET_K, 0, 0, RET_ALLOW),
    ];
    // SAFETY: between fork and exec the closure makes two prctl calls on a
    // filter that lives on this (copied) stack; nothing is allocated.
    unsafe {
        cmd.pre_exec(move || {
            let prog = libc::sock_fprog {
                len: program.len() as u16,
                filter: program.as_ptr() as *mut libc::sock_filter,
            };
            if libc::prctl(libc::PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0
                || libc::prctl(
                    libc::PR_SET_SECCOMP,
                    libc::SECCOMP_MODE_FILTER,
                    &prog as *const libc::sock_fprog,
                ) != 0
            {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
}

/// `:- consult('lnk.pl').` where `lnk.pl` is a symbolic link to a file
/// outside the application: refused at the start (its directive never
/// runs), as an outside path is; with `--allow-os` it loads.
#[cfg(unix)]
#[test]
fn a_consult_through_a_link_out_of_the_application_is_refused() {
    let s = Scratch::new("link", |_| {
        ":- consult('lnk.pl').\nattack(_) :- assign_func_value(d).\n".to_owned()
    });
    let evil = s.root.join("evil.pl");
    let ran = s.outside().join("ran");
    std::fs::write(
        &evil,
        format!(":- open('{}', write, S), close(S).\n", ran.display()),
    )
    .unwrap();
    std::os::unix::fs::symlink(&evil, s.app().join("lnk.pl")).unwrap();
    let out = s.run(&["--sandbox", "off"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("lnk.pl") && stderr.contains("--allow-os"),
        "{stderr}"
    );
    assert!(!ran.exists(), "the linked file's directive ran");
    s.run(&["--allow-os"]);
    assert!(ran.exists(), "--allow-os did not load the linked file");
}

/// A side file or DM file that is a symbolic link out of the application
/// (`global_vars.pl` to a secret) is refused before it is read, by `check`
/// and `run`: no message quotes it.
#[cfg(unix)]
#[test]
fn a_side_file_linked_out_of_the_application_is_refused_unread() {
    let s = Scratch::new("side", |_| {
        "attack(_) :- assign_func_value(d).\n".to_owned()
    });
    let secret = s.outside().join("secret");
    std::fs::write(&secret, "root:SECRETHASH:19000:0:99999:7:::\n").unwrap();
    for name in ["global_vars.pl", "other.dm"] {
        let link = s.app().join(name);
        std::os::unix::fs::symlink(&secret, &link).unwrap();
        for args in [
            vec!["check".to_owned(), s.app().display().to_string()],
            vec![
                "run".to_owned(),
                s.app().display().to_string(),
                "--script".to_owned(),
                s.app().join("script.txt").display().to_string(),
            ],
        ] {
            let out = sitlogc().args(&args).output().unwrap();
            let text = String::from_utf8_lossy(&out.stdout).into_owned()
                + &String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{name} {args:?}: {text}");
            assert!(
                text.contains(name) && text.contains("symbolic link") && !text.contains("SECRET"),
                "{name} {args:?}: {text}"
            );
        }
        std::fs::remove_file(&link).unwrap();
    }
}

/// `--trace` naming one of the application's own files (its DM, its
/// Prolog file, a hard link to one) is refused before anything runs and
/// leaves the file as it was (issue 38).
#[test]
fn a_trace_over_an_application_file_is_refused() {
    let s = Scratch::new("trace", |_| {
        "attack(_) :- assign_func_value(d).\n".to_owned()
    });
    let link = s.outside().join("hard.dm");
    std::fs::hard_link(s.app().join("main.dm"), &link).unwrap();
    for target in [
        s.app().join("main.dm"),
        s.app().join("user_functions.pl"),
        link.clone(),
    ] {
        let before = std::fs::read(&target).unwrap();
        let out = sitlogc()
            .arg("run")
            .arg(s.app())
            .arg("--script")
            .arg(s.app().join("script.txt"))
            .arg("--trace")
            .arg(&target)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{}: {stderr}", target.display());
        assert!(
            stderr.contains("--trace") && stderr.contains("overwrite"),
            "{stderr}"
        );
        assert_eq!(std::fs::read(&target).unwrap(), before);
    }
}
