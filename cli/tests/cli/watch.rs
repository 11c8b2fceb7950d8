//! `sitlogc run APP --watch` (issue 21): a run waiting on input from a pipe
//! while its DM file is edited. Every wait is for a line the run prints,
//! with a generous timeout (a loaded 2-core machine), never a sleep.

use std::io::{BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::support::sitlogc;

const TIMEOUT: Duration = Duration::from_secs(120);

const MAIN: &str = "diag_mod(main, [
  [id ==> ask, type ==> listening,
   arcs ==> [said(go) : say(one) => ask, said(stop) : say(bye) => fs]],
  [id ==> fs, type ==> final]
], []).
";

/// A fresh application directory with `main.dm`.
fn app(name: &str) -> PathBuf {
    let dir =
        crate::support::temp_root().join(format!("sitlogc-watch-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("main.dm"), MAIN).unwrap();
    dir
}

/// A watched run: its stdin, and its stderr line by line.
struct Run {
    child: Child,
    stdin: Option<ChildStdin>,
    lines: mpsc::Receiver<String>,
    /// Everything read from stderr so far.
    seen: String,
}

impl Run {
    fn start(dir: &Path) -> Run {
        let mut child = sitlogc()
            .args(["run", "--watch"])
            .arg(dir)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let stdin = child.stdin.take();
        let stderr = child.stderr.take().unwrap();
        let (tx, lines) = mpsc::channel();
        std::thread::spawn(move || {
            // The prompt `|: ` has no newline: split on it too.
            let mut r = BufReader::new(stderr);
            let mut buf = Vec::new();
            loop {
                let mut byte = [0u8; 1];
                match std::io::Read::read(&mut r, &mut byte) {
                    Ok(0) | Err(_) => {
                        if !buf.is_empty() {
                            let _ = tx.send(String::from_utf8_lossy(&buf).into_owned());
                        }
                        return;
                    }
                    Ok(_) => {
                        buf.push(byte[0]);
                        if byte[0] == b'\n' || buf.ends_with(b"|: ") {
                            let _ = tx.send(String::from_utf8_lossy(&buf).into_owned());
                            buf.clear();
                        }
                    }
                }
            }
        });
        Run {
            child,
            stdin,
            lines,
            seen: String::new(),
        }
    }

    /// Waits until stderr has a line containing `text` (after what earlier
    /// waits consumed); returns the lines read meanwhile.
    fn wait_for(&mut self, text: &str) -> String {
        let start = Instant::now();
        let mut got = String::new();
        loop {
            let left = TIMEOUT.saturating_sub(start.elapsed());
            match self.lines.recv_timeout(left) {
                Ok(line) => {
                    self.seen.push_str(&line);
                    got.push_str(&line);
                    if line.contains(text) {
                        return got;
                    }
                }
                Err(_) => panic!(
                    "no line with {text:?} within {TIMEOUT:?}; stderr so far:\n{}",
                    self.seen
                ),
            }
        }
    }

    fn send(&mut self, line: &str) {
        let stdin = self.stdin.as_mut().unwrap();
        stdin.write_all(line.as_bytes()).unwrap();
        stdin.write_all(b"\n").unwrap();
        stdin.flush().unwrap();
    }

    /// Closes stdin and waits for the end: exit status and stdout.
    fn finish(mut self) -> (Option<i32>, String, String) {
        drop(self.stdin.take());
        let mut out = String::new();
        if let Some(mut o) = self.child.stdout.take() {
            std::io::Read::read_to_string(&mut o, &mut out).unwrap();
        }
        let status = self.child.wait().unwrap();
        while let Ok(line) = self.lines.recv_timeout(Duration::from_secs(10)) {
            self.seen.push_str(&line);
        }
        (status.code(), out, self.seen)
    }
}

/// Rewrites `main.dm` of `dir` with `edit` applied.
fn edit(dir: &Path, edit: impl Fn(&str) -> String) {
    let path = dir.join("main.dm");
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, edit(&text)).unwrap();
}

#[test]
fn an_edited_action_is_taken_at_the_next_input() {
    let dir = app("edit");
    let mut run = Run::start(&dir);
    run.wait_for("|: ");
    run.send("go.");
    run.wait_for("Golem says: one");
    run.wait_for("|: ");
    edit(&dir, |t| t.replace("say(one)", "say(two)"));
    run.wait_for("the program checks");
    run.send("go.");
    let got = run.wait_for("Golem says:");
    assert!(
        got.contains("watch: reloaded (main.dm): the run goes on in the new program at DM `main`, situation `ask`"),
        "{got}"
    );
    assert!(got.contains("Golem says: two"), "{got}");
    run.wait_for("|: ");
    run.send("stop.");
    let (code, out, err) = run.finish();
    assert_eq!(code, Some(0), "{err}");
    // The history keeps the transitions of both programs.
    assert!(
        out.contains("main:(ask,said(go):say(one))\nmain:(ask,said(go):say(two))\nmain:(ask,said(stop):say(bye))"),
        "{out}"
    );
}

#[test]
fn an_edit_that_does_not_check_leaves_the_run_going() {
    let dir = app("broken");
    let mut run = Run::start(&dir);
    run.wait_for("|: ");
    // An arc to a situation that does not exist.
    edit(&dir, |t| {
        t.replace("say(one) => ask", "say(one) => nowhere")
    });
    let got = run.wait_for("does not check");
    assert!(
        got.contains("nowhere"),
        "the diagnostics are printed: {got}"
    );
    assert!(got.contains("main.dm:"), "{got}");
    run.send("go.");
    run.wait_for("Golem says: one");
    // A syntax error too.
    edit(&dir, |t| {
        t.replace("diag_mod(main, [", "diag_mod(main, [[[")
    });
    run.wait_for("does not check");
    run.send("stop.");
    let (code, out, err) = run.finish();
    assert_eq!(code, Some(0), "{err}");
    assert!(!err.contains("reloaded"), "{err}");
    assert!(out.contains("main:(ask,said(stop):say(bye))"), "{out}");
}

#[test]
fn removing_the_current_situation_stops_the_run() {
    let dir = app("removed");
    let mut run = Run::start(&dir);
    run.wait_for("|: ");
    run.send("go.");
    run.wait_for("Golem says: one");
    run.wait_for("|: ");
    edit(&dir, |t| t.replace("ask", "asked"));
    run.wait_for("the program checks");
    run.send("go.");
    let (code, out, err) = run.finish();
    assert_eq!(code, Some(1), "{err}");
    assert!(
        err.contains("situation `ask` of DM `main`, where the run is, is no longer in the program: the run cannot go on in the new program"),
        "{err}"
    );
    assert!(!err.contains("Golem says: two"), "{err}");
    // The history so far is printed.
    assert!(out.contains("main:(ask,said(go):say(one))"), "{out}");
}

#[test]
fn removing_a_dm_on_the_stack_stops_the_run() {
    let dir = app("removed-dm");
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [
  [id ==> is, type ==> recursive, embedded_dm ==> inner, arcs ==> [done : say(back) => fs]],
  [id ==> fs, type ==> final]
], []).
",
    )
    .unwrap();
    std::fs::write(
        dir.join("inner.dm"),
        "diag_mod(inner, [
  [id ==> ask, type ==> listening, arcs ==> [said(go) : say(in) => done]],
  [id ==> done, type ==> final]
], []).
",
    )
    .unwrap();
    let mut run = Run::start(&dir);
    run.wait_for("|: ");
    // The DM moves to a file of another name and is renamed.
    std::fs::write(
        dir.join("inner.dm"),
        "diag_mod(inner2, [[id ==> done, type ==> final]], []).\n",
    )
    .unwrap();
    edit(&dir, |t| {
        t.replace("embedded_dm ==> inner,", "embedded_dm ==> inner2,")
    });
    run.wait_for("the program checks");
    run.send("go.");
    let (code, _, err) = run.finish();
    assert_eq!(code, Some(1), "{err}");
    assert!(
        err.contains(
            "DM `inner`, on the DM stack (called as `inner`), is no longer in the program"
        ),
        "{err}"
    );
}

#[test]
fn variables_are_kept_and_new_ones_start_at_their_initial_values() {
    let dir = app("vars");
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [
  [id ==> ask, type ==> listening,
   arcs ==> [said(go) : [inc(n, N), say(N)] => ask, said(stop) : say(bye) => fs]],
  [id ==> fs, type ==> final]
], [n ==> 0]).
",
    )
    .unwrap();
    let mut run = Run::start(&dir);
    run.wait_for("|: ");
    run.send("go.");
    run.wait_for("Golem says: 1");
    run.send("go.");
    run.wait_for("Golem says: 2");
    run.wait_for("|: ");
    // The new program says the local's value with a new global's. Until
    // global_vars.pl declares it, the program does not check (E0219): only
    // the program with both changes is taken.
    edit(&dir, |t| {
        t.replace(
            "[inc(n, N), say(N)]",
            "[inc(n, N), get(m, M), say(sum(N, M))]",
        )
    });
    std::fs::write(dir.join("global_vars.pl"), "m ==> 40.\n").unwrap();
    run.wait_for("the program checks");
    run.send("go.");
    run.wait_for("Golem says: sum(3,40)");
    run.send("stop.");
    let (code, out, err) = run.finish();
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("Out Global Vars: [m==>40]"), "{out}");
}

#[test]
fn changed_prolog_user_functions_are_loaded_again() {
    let dir = app("prolog");
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [
  [id ==> ask, type ==> listening,
   arcs ==> [said(go) : say(apply(word(_), [x])) => ask, said(stop) : say(bye) => fs]],
  [id ==> fs, type ==> final]
], []).
",
    )
    .unwrap();
    std::fs::write(
        dir.join("user_functions.pl"),
        "word(_) :- assign_func_value(one).\n",
    )
    .unwrap();
    let mut run = Run::start(&dir);
    run.wait_for("|: ");
    run.send("go.");
    run.wait_for("Golem says: one");
    run.wait_for("|: ");
    std::fs::write(
        dir.join("user_functions.pl"),
        "word(_) :- assign_func_value(two).\n",
    )
    .unwrap();
    run.wait_for("user_functions.pl changed; the program checks");
    run.send("go.");
    run.wait_for("Golem says: two");
    run.send("stop.");
    let (code, _, err) = run.finish();
    assert_eq!(code, Some(0), "{err}");
}
