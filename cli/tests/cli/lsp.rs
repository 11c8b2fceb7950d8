//! `sitlogc lsp`: a session as an editor runs it, over the process's
//! stdin/stdout: diagnostics on open and on change (and cleared when
//! fixed), go to definition, hover, unknown requests, shutdown and exit.

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::Duration;

use crate::support::sitlogc;

struct Session {
    child: Child,
    stdin: ChildStdin,
    rx: Receiver<Value>,
}

impl Session {
    fn start() -> Session {
        let mut child = sitlogc()
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .unwrap();
        let stdin = child.stdin.take().unwrap();
        let mut out = BufReader::new(child.stdout.take().unwrap());
        let (tx, rx) = channel();
        std::thread::spawn(move || loop {
            let mut len = None;
            loop {
                let mut line = String::new();
                if out.read_line(&mut line).unwrap_or(0) == 0 {
                    return;
                }
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
            if tx.send(serde_json::from_slice(&body).unwrap()).is_err() {
                return;
            }
        });
        Session { child, stdin, rx }
    }

    fn send(&mut self, msg: Value) {
        let body = msg.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).unwrap();
        self.stdin.flush().unwrap();
    }

    fn recv(&self) -> Value {
        self.rx
            .recv_timeout(Duration::from_secs(60))
            .expect("the server answers within a minute")
    }

    /// The next message that is not a notification other than `method`.
    fn next_of(&self, method: &str) -> Value {
        loop {
            let m = self.recv();
            if m["method"] == method {
                return m;
            }
        }
    }

    fn response(&self, id: i64) -> Value {
        loop {
            let m = self.recv();
            if m["id"] == id {
                return m;
            }
        }
    }
}

const BAD: &str = "% A greeting.\ndiag_mod(main,\n  [ [ id ==> is, type ==> neutral,\n      arcs ==> [ empty : say(hello) => fz ] ],\n    [ id ==> fs, type ==> final ] ],\n  []).\n";

#[test]
fn an_editor_session() {
    let dir = crate::support::temp_root().join(format!("sitlogc-lsp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("main.dm");
    std::fs::write(&file, BAD).unwrap();
    let uri = sitlog_lsp::path_to_uri(&file);

    let mut s = Session::start();
    s.send(
        json!({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {"capabilities": {}}}),
    );
    let init = s.response(1);
    assert_eq!(init["result"]["capabilities"]["definitionProvider"], true);
    s.send(json!({"jsonrpc": "2.0", "method": "initialized", "params": {}}));

    // Open: the unknown next situation `fz` (E0212) on line 4 (0-based 3).
    s.send(
        json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {
        "textDocument": {"uri": uri, "languageId": "sitlog", "version": 1, "text": BAD}}}),
    );
    let d = s.next_of("textDocument/publishDiagnostics");
    assert_eq!(d["params"]["uri"], uri.as_str());
    let diags = d["params"]["diagnostics"].as_array().unwrap();
    let e = diags.iter().find(|d| d["code"] == "E0212").expect("E0212");
    assert_eq!(e["severity"], 1);
    assert_eq!(e["range"]["start"]["line"], 3);
    assert_eq!(
        e["range"]["start"]["character"],
        BAD.lines().nth(3).unwrap().find("fz").unwrap()
    );

    // Change (unsaved): fixed, so the file's diagnostics are cleared.
    let fixed = BAD.replace("=> fz", "=> fs");
    s.send(
        json!({"jsonrpc": "2.0", "method": "textDocument/didChange", "params": {
        "textDocument": {"uri": uri, "version": 2},
        "contentChanges": [{"text": fixed}]}}),
    );
    let d = s.next_of("textDocument/publishDiagnostics");
    assert_eq!(d["params"]["diagnostics"], json!([]), "{d}");

    // Definition of the situation `fs` named in the arc.
    let line = fixed.lines().nth(3).unwrap();
    let col = line.find("fs").unwrap();
    s.send(
        json!({"jsonrpc": "2.0", "id": 2, "method": "textDocument/definition", "params": {
        "textDocument": {"uri": uri}, "position": {"line": 3, "character": col}}}),
    );
    let r = s.response(2);
    assert_eq!(r["result"]["uri"], uri.as_str());
    assert_eq!(r["result"]["range"]["start"]["line"], 4, "{r}");

    // Hover on the DM's name: its doc comment.
    s.send(
        json!({"jsonrpc": "2.0", "id": 3, "method": "textDocument/hover", "params": {
        "textDocument": {"uri": uri}, "position": {"line": 1, "character": 10}}}),
    );
    let r = s.response(3);
    let text = r["result"]["contents"]["value"].as_str().unwrap();
    assert!(text.contains("A greeting."), "{text}");
    assert!(text.contains("DM `main/0`"), "{text}");

    // A request it does not serve: an error, not a hang.
    s.send(json!({"jsonrpc": "2.0", "id": 4, "method": "textDocument/rename", "params": {}}));
    assert_eq!(s.response(4)["error"]["code"], -32601);

    s.send(json!({"jsonrpc": "2.0", "id": 5, "method": "shutdown"}));
    s.response(5);
    s.send(json!({"jsonrpc": "2.0", "method": "exit"}));
    let status = s.child.wait().unwrap();
    assert!(status.success());
    let _ = std::fs::remove_dir_all(&dir);
}

impl Session {
    /// `initialize` and `initialized`.
    fn handshake(&mut self) {
        self.send(
            json!({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {"capabilities": {}}}),
        );
        self.response(1);
        self.send(json!({"jsonrpc": "2.0", "method": "initialized", "params": {}}));
    }

    /// Opens `uri` with `text`; the diagnostics published for `uri`.
    fn open(&mut self, uri: &str, text: &str) -> Vec<Value> {
        self.send(
            json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {
            "textDocument": {"uri": uri, "languageId": "sitlog", "version": 1, "text": text}}}),
        );
        loop {
            let d = self.next_of("textDocument/publishDiagnostics");
            if d["params"]["uri"] == uri {
                return d["params"]["diagnostics"].as_array().unwrap().clone();
            }
        }
    }

    fn stop(mut self) {
        self.send(json!({"jsonrpc": "2.0", "id": 99, "method": "shutdown"}));
        self.response(99);
        self.send(json!({"jsonrpc": "2.0", "method": "exit"}));
        assert!(self.child.wait().unwrap().success());
    }
}

fn codes(diags: &[Value]) -> Vec<&str> {
    diags.iter().map(|d| d["code"].as_str().unwrap()).collect()
}

/// Issue 30: a file not saved yet gave E0004 "No such file or directory"
/// at 1:1, an `untitled:` document nothing. The text given is analysed,
/// with the side files of its directory when there is one.
#[test]
fn files_not_saved_yet() {
    let dir = crate::support::temp_root().join(format!("sitlogc-lsp-new-{}", std::process::id()));
    let lone = dir.join("lone");
    let app = dir.join("app");
    std::fs::create_dir_all(&lone).unwrap();
    std::fs::create_dir_all(&app).unwrap();
    // A directory with side files but no DM yet: `get(n, _)` is known.
    std::fs::write(lone.join("global_vars.pl"), "n ==> 1.\n").unwrap();
    // An application whose main DM calls a DM in a file not saved yet.
    std::fs::write(
        app.join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> recursive, embedded_dm ==> helper, arcs ==> [done : empty => fs]], [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();

    let mut s = Session::start();
    s.handshake();
    let text = BAD.replace("say(hello)", "say(get(n, _))");
    let diags = s.open(&sitlog_lsp::path_to_uri(&lone.join("new.dm")), &text);
    assert_eq!(codes(&diags), ["E0212", "W0214"], "{diags:?}");
    assert_eq!(diags[0]["range"]["start"]["line"], 3);

    let helper = "diag_mod(helper, [[id ==> is, type ==> neutral, arcs ==> [empty : empty => don]], [id ==> done, type ==> final]], []).\n";
    let diags = s.open(&sitlog_lsp::path_to_uri(&app.join("helper.dm")), helper);
    // `done` is taken as meant (did you mean): not "never reached" as well.
    assert_eq!(codes(&diags), ["E0212"], "{diags:?}");
    // main.dm, on disk, sees `helper`: no E0216.
    s.send(json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {
        "textDocument": {"uri": sitlog_lsp::path_to_uri(&app.join("main.dm")), "languageId": "sitlog", "version": 1,
        "text": std::fs::read_to_string(app.join("main.dm")).unwrap()}}}));
    let main_uri = sitlog_lsp::path_to_uri(&app.join("main.dm"));
    loop {
        let d = s.next_of("textDocument/publishDiagnostics");
        if d["params"]["uri"] == main_uri.as_str() {
            assert_eq!(d["params"]["diagnostics"], json!([]), "{d}");
            break;
        }
    }

    let diags = s.open("untitled:Untitled-1", BAD);
    assert_eq!(codes(&diags), ["E0212", "W0214"], "{diags:?}");
    s.stop();
    let _ = std::fs::remove_dir_all(&dir);
}

/// A `Content-Length` beyond the limit ends the session at once with an
/// error naming the length and the option (exit 2), before any allocation
/// of that size; a frame that breaks off does too.
#[test]
fn a_message_over_the_limit_is_refused() {
    for (header, expect) in [
        (
            "Content-Length: 1000000000000\r\n\r\n",
            "1000000000000 bytes",
        ),
        ("Content-Length: 3000000000\r\n\r\n", "--max-message-bytes"),
        (
            "Content-Length: 10\r\n\r\n{",
            "end of input after 1 of the 10 bytes",
        ),
    ] {
        let mut child = sitlogc()
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut stdin = child.stdin.take().unwrap();
        stdin.write_all(header.as_bytes()).unwrap();
        drop(stdin);
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(expect), "{err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}
