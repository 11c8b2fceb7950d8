//! The trust model (issue 31): the application's Prolog directives run only
//! when the run starts (not for `run --main nosuch`, a `debug` session that
//! quits at once, `run --view` before its page opens, nor ever for `check`,
//! `graph`, `lsp` and `build --emit rust`); shell, processes and sockets are
//! refused without `--allow-os`, with an error naming the predicate and the
//! flag; `check` warns (W0240) where the code reaches the operating system.

use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::Stdio;

use crate::support::{assert_ok, sitlogc};

const MAIN: &str = "diag_mod(main,\n  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(hello) => fs ] ],\n    [ id ==> fs, type ==> final ] ],\n  []).\n";

/// An application whose directive writes `marker` (inside the application:
/// allowed without the flag), and the marker's path.
fn app(name: &str, user_functions: impl Fn(&Path) -> String) -> (PathBuf, PathBuf) {
    let dir =
        crate::support::temp_root().join(format!("sitlogc-trust-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("main.dm"), MAIN).unwrap();
    std::fs::write(dir.join("script.txt"), "").unwrap();
    let marker = dir.join("marker");
    std::fs::write(dir.join("user_functions.pl"), user_functions(&marker)).unwrap();
    (dir, marker)
}

fn writes(marker: &Path) -> String {
    format!(
        ":- open('{}', write, S), write(S, ran), close(S).\n",
        marker.display()
    )
}

fn shell(marker: &Path) -> String {
    format!(
        ":- use_module(library(os)).\n:- atom_chars('touch {}', C), shell(C).\n",
        marker.display()
    )
}

/// Runs without `SHELL`, as CI and a task under systemd do: `--allow-os`
/// must still let `shell/1` run (the runtime defaults it to `/bin/sh`).
fn run(dir: &Path, extra: &[&str]) -> std::process::Output {
    sitlogc()
        .env_remove("SHELL")
        .arg("run")
        .arg(dir)
        .arg("--script")
        .arg(dir.join("script.txt"))
        .args(extra)
        .output()
        .unwrap()
}

#[test]
fn directives_run_only_when_the_run_starts() {
    let (dir, marker) = app("start", writes);
    // An option refused: exit 2, nothing ran.
    let out = run(&dir, &["--main", "nosuch"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!marker.exists(), "run --main nosuch ran a directive");
    // A debugger session that quits before the first step.
    let commands = dir.join("commands.txt");
    std::fs::write(&commands, "quit\n").unwrap();
    let out = sitlogc()
        .arg("debug")
        .arg(&dir)
        .arg("--script")
        .arg(dir.join("script.txt"))
        .arg("--commands")
        .arg(&commands)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert!(!marker.exists(), "debug + quit ran a directive");
    // Tools that only read the program.
    for args in [&["check"][..], &["graph"], &["build", "--emit", "rust"]] {
        let out = sitlogc().args(args).arg(&dir).output().unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(!marker.exists(), "{args:?} ran a directive");
    }
    lsp_opens(&dir.join("main.dm"));
    lsp_opens(&dir.join("user_functions.pl"));
    assert!(!marker.exists(), "lsp ran a directive");
    // The run itself.
    let out = run(&dir, &[]);
    assert_ok(&out);
    assert!(marker.exists(), "the run did not run the directive");
    let _ = std::fs::remove_dir_all(&dir);
}

/// An editor opens `file` in `sitlogc lsp` and gets its diagnostics.
fn lsp_opens(file: &Path) {
    let mut child = sitlogc()
        .arg("lsp")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let mut send = |msg: serde_json::Value| {
        let body = msg.to_string();
        write!(stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).unwrap();
        stdin.flush().unwrap();
    };
    let uri = sitlog_lsp::path_to_uri(file);
    let text = std::fs::read_to_string(file).unwrap();
    send(
        serde_json::json!({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {"capabilities": {}}}),
    );
    send(serde_json::json!({"jsonrpc": "2.0", "method": "initialized", "params": {}}));
    send(
        serde_json::json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {
        "textDocument": {"uri": uri, "languageId": "sitlog", "version": 1, "text": text}}}),
    );
    let mut out = BufReader::new(child.stdout.take().unwrap());
    // Read until the diagnostics are published.
    loop {
        let mut len = None;
        loop {
            let mut line = String::new();
            assert!(out.read_line(&mut line).unwrap() > 0, "lsp ended early");
            let line = line.trim_end();
            if line.is_empty() {
                break;
            }
            if let Some(n) = line.strip_prefix("Content-Length: ") {
                len = n.parse::<usize>().ok();
            }
        }
        let mut body = vec![0; len.unwrap()];
        out.read_exact(&mut body).unwrap();
        let msg: serde_json::Value = serde_json::from_slice(&body).unwrap();
        if msg["method"] == "textDocument/publishDiagnostics" {
            break;
        }
    }
    send(serde_json::json!({"jsonrpc": "2.0", "id": 2, "method": "shutdown", "params": null}));
    send(serde_json::json!({"jsonrpc": "2.0", "method": "exit", "params": null}));
    drop(stdin);
    let _ = child.wait();
}

#[test]
fn run_view_runs_no_directive_before_its_page_opens() {
    let (dir, marker) = app("view", writes);
    let mut child = sitlogc()
        .arg("run")
        .arg(&dir)
        .arg("--script")
        .arg(dir.join("script.txt"))
        .arg("--view")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    loop {
        line.clear();
        assert!(
            stderr.read_line(&mut line).unwrap() > 0,
            "no live view address"
        );
        if line.contains("http://127.0.0.1:") {
            break;
        }
    }
    std::thread::sleep(std::time::Duration::from_millis(500));
    let ran = marker.exists();
    let _ = child.kill();
    let _ = child.wait();
    assert!(!ran, "run --view ran a directive before its page opened");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_shell_is_off_without_allow_os() {
    let (dir, marker) = app("shell", shell);
    let out = run(&dir, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!marker.exists(), "the shell ran without --allow-os");
    assert!(
        stderr.contains("user_functions.pl:2:1")
            && stderr.contains("`shell/1`")
            && stderr.contains("--allow-os"),
        "{stderr}"
    );
    // check warns, at the call.
    let out = sitlogc().arg("check").arg(&dir).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("W0240")
            && stderr.contains("user_functions.pl:2:")
            && stderr.contains("`shell/1`"),
        "{stderr}"
    );
    // With the flag the shell runs.
    let out = run(&dir, &["--allow-os"]);
    assert_ok(&out);
    assert!(marker.exists(), "--allow-os did not let the shell run");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_user_function_reaching_the_os_is_a_located_error() {
    let (dir, marker) = app("function", |marker| {
        format!(
            ":- use_module(library(os)).\nf(_) :- atom_chars('touch {}', C), shell(C), assign_func_value(ok).\n",
            marker.display()
        )
    });
    std::fs::write(
        dir.join("main.dm"),
        MAIN.replace("say(hello)", "say(apply(f(X), [1]))"),
    )
    .unwrap();
    let out = run(&dir, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!marker.exists());
    assert!(
        stderr.contains("`f/1`") && stderr.contains("`shell/1`") && stderr.contains("--allow-os"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `check` warns (W0240) at module-qualified calls and closures of the
/// system's libraries (`call(os:shell, C)`, `process:process_create`,
/// `files:delete_file`) and at goals built by name from a table predicate
/// (`G =.. [shell, C]`), which the Prolog-level refusal does not see
/// (issue 38); not at other module-qualified calls.
#[test]
fn check_warns_at_module_qualified_and_name_built_os_calls() {
    let (dir, _) = app("qualified", |_| {
        ":- use_module(library(os)).\n\
         a(C) :- call(os:shell, C).\n\
         b(C) :- maplist(os:shell, [C]).\n\
         c(T, A) :- call(process:process_create, T, A, []).\n\
         d(T, A) :- process:process_create(T, A, []).\n\
         e(F) :- call(files:delete_file, F).\n\
         f(C) :- G =.. [shell, C], call(G).\n\
         g(A) :- call(sockets:socket_server_open, A, _).\n\
         h(L, X) :- lists:append(L, [x], X).\n"
            .to_owned()
    });
    let out = sitlogc().arg("check").arg(&dir).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    for (line, what) in [
        (2, "`os:shell`"),
        (3, "`os:shell`"),
        (4, "`process:process_create`"),
        (5, "`process:process_create`"),
        (6, "`files:delete_file`"),
        (7, "named `shell`"),
        (8, "`sockets:socket_server_open`"),
    ] {
        assert!(
            stderr.contains(&format!("user_functions.pl:{line}:")) && stderr.contains(what),
            "line {line}, {what}:\n{stderr}"
        );
    }
    assert_eq!(stderr.matches("[W0240]").count(), 7, "{stderr}");
    assert!(!stderr.contains("user_functions.pl:9:"), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}
