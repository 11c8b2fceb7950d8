//! The test-mode prompt of `sitlogc run` (issue 17): it names the DM and
//! situation waiting and lists the expectations; the end of the input
//! (Ctrl-D, or the end of a pipe) ends the task cleanly with exit status 3;
//! on a terminal, lines are edited and remembered, and no progress line is
//! drawn while the prompt waits (issue 30; both tested on a pty).

use std::io::Write;
use std::path::PathBuf;
use std::process::{Output, Stdio};

use crate::support::sitlogc;

const MAIN: &str = "diag_mod(main, [
  [id ==> ask, type ==> listening,
   arcs ==> [said(go) : say(one) => ask, said(stop) : say(bye) => fs]],
  [id ==> fs, type ==> final]
], []).
";

fn app(name: &str) -> PathBuf {
    let dir =
        crate::support::temp_root().join(format!("sitlogc-prompt-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("main.dm"), MAIN).unwrap();
    dir
}

/// `sitlogc run DIR ARGS` with `input` on a pipe.
fn run_piped(dir: &PathBuf, args: &[&str], input: &str) -> Output {
    let mut child = sitlogc()
        .arg("run")
        .arg(dir)
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    child.wait_with_output().unwrap()
}

#[test]
fn the_prompt_names_the_dm_and_situation_and_lists_the_expectations() {
    let dir = app("text");
    let out = run_piped(&dir, &[], "go.\nstop.\n");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert_eq!(
        err,
        "DM main, situation ask (listening) expects: said(go) | said(stop)\n\
         |: Golem says: one\n\
         DM main, situation ask (listening) expects: said(go) | said(stop)\n\
         |: Golem says: bye\n"
    );
}

#[test]
fn the_end_of_the_input_ends_the_task_cleanly() {
    let dir = app("eof");
    let out = run_piped(&dir, &[], "go.\n");
    let err = String::from_utf8_lossy(&out.stderr);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(
        err.ends_with(
            "|: \nstopped: the input ended (Ctrl-D) while DM `main` waited in situation `ask`: the task did not finish (exit status 3)\n"
        ),
        "{err}"
    );
    assert!(!err.contains("error:"), "{err}");
    // The history so far.
    assert!(
        text.starts_with("Execution history:\nmain:(ask,said(go):say(one))\n"),
        "{text}"
    );
    // JSON: the run was stopped, not failed.
    let out = run_piped(&dir, &["--format", "json"], "");
    assert_eq!(out.status.code(), Some(3));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["status"], "interrupted");
    assert_eq!(v["history"], serde_json::json!([]));
    // The end of a script is still an error (E4).
    std::fs::write(dir.join("s.txt"), "go.\n").unwrap();
    let script = dir.join("s.txt").display().to_string();
    let out = run_piped(&dir, &["--script", &script], "");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("end of input while the situation waits for an expectation"),
        "{err}"
    );
    assert!(!err.contains("stopped:"), "{err}");
}

/// On a pseudo-terminal: line editing (a backspace), history (the up
/// arrow) and Ctrl-D.
#[cfg(target_os = "linux")]
#[test]
fn on_a_terminal_lines_are_edited_and_remembered() {
    use std::io::Read;
    use std::os::fd::{FromRawFd, OwnedFd};
    use std::sync::mpsc;
    use std::time::{Duration, Instant};

    let dir = app("pty");
    let (mut master, slave) = unsafe {
        let (mut m, mut s) = (0, 0);
        let r = libc::openpty(
            &mut m,
            &mut s,
            std::ptr::null_mut(),
            std::ptr::null(),
            std::ptr::null(),
        );
        if r != 0 {
            // A machine without pseudo-terminals: nothing to test here.
            eprintln!("skipped: openpty: {}", std::io::Error::last_os_error());
            return;
        }
        (std::fs::File::from_raw_fd(m), OwnedFd::from_raw_fd(s))
    };
    let mut cmd = sitlogc();
    // The pty becomes the child's controlling terminal (its /dev/tty), as
    // a shell's terminal is.
    unsafe {
        use std::os::unix::process::CommandExt;
        cmd.pre_exec(|| {
            if libc::setsid() < 0 || libc::ioctl(0, libc::TIOCSCTTY, 0) < 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    // A terminal the editor supports, whatever the environment says.
    cmd.env("TERM", "xterm");
    let mut child = cmd
        .arg("run")
        .arg(&dir)
        .stdin(Stdio::from(slave.try_clone().unwrap()))
        .stderr(Stdio::from(slave.try_clone().unwrap()))
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    drop(slave);
    // Everything the terminal shows, read on a thread.
    let (tx, rx) = mpsc::channel::<Vec<u8>>();
    let mut reader = master.try_clone().unwrap();
    std::thread::spawn(move || {
        let mut buf = [0u8; 4096];
        while let Ok(n) = reader.read(&mut buf) {
            if n == 0 || tx.send(buf[..n].to_vec()).is_err() {
                return;
            }
        }
    });
    let mut screen = String::new();
    // Waits until the terminal has shown `text` `count` times in all.
    fn wait(screen: &mut String, rx: &mpsc::Receiver<Vec<u8>>, text: &str, count: usize) {
        let start = Instant::now();
        while screen.matches(text).count() < count {
            let left = Duration::from_secs(120).saturating_sub(start.elapsed());
            match rx.recv_timeout(left) {
                Ok(bytes) => screen.push_str(&String::from_utf8_lossy(&bytes)),
                Err(_) => panic!("no {text:?} (x{count}) on the terminal:\n{screen}"),
            }
        }
    }
    const HEADER: &str = "DM main, situation ask (listening) expects: said(go) | said(stop)";
    // Waits for the `n`th prompt: its header, then the editor's `|: `
    // (drawn once the terminal is in raw mode, so keys sent after it are
    // the editor's).
    fn prompt(screen: &mut String, rx: &mpsc::Receiver<Vec<u8>>, n: usize) {
        wait(screen, rx, HEADER, n);
        let start = Instant::now();
        while !screen.rsplit(HEADER).next().unwrap_or("").contains("|: ") {
            let left = Duration::from_secs(120).saturating_sub(start.elapsed());
            match rx.recv_timeout(left) {
                Ok(bytes) => screen.push_str(&String::from_utf8_lossy(&bytes)),
                Err(_) => panic!("no prompt {n} on the terminal:\n{screen}"),
            }
        }
    }
    prompt(&mut screen, &rx, 1);
    // `gx`, backspace, `o.`: the line read is `go.`.
    master.write_all(b"gx\x7fo.\r").unwrap();
    wait(&mut screen, &rx, "Golem says: one", 1);
    prompt(&mut screen, &rx, 2);
    // The up arrow brings `go.` back.
    master.write_all(b"\x1b[A\r").unwrap();
    wait(&mut screen, &rx, "Golem says: one", 2);
    prompt(&mut screen, &rx, 3);
    // Ctrl-D on an empty line ends the task.
    master.write_all(b"\x04").unwrap();
    wait(&mut screen, &rx, "stopped: the input ended (Ctrl-D)", 1);
    let mut out = String::new();
    child
        .stdout
        .take()
        .unwrap()
        .read_to_string(&mut out)
        .unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(3), "{screen}");
    assert!(
        out.contains("main:(ask,said(go):say(one))\nmain:(ask,said(go):say(one))\n"),
        "{out}"
    );
}

/// On a pseudo-terminal for stdin, stdout and stderr (as a shell runs it,
/// where the progress indicator is on): while the prompt waits, nothing is
/// drawn after `|: ` (no spinner over what is typed); when the task runs on
/// its own (a long loop after the input), the progress line comes back and
/// names where the task is; at the next prompt it is gone again.
#[cfg(target_os = "linux")]
#[test]
fn no_progress_line_while_the_prompt_waits() {
    use std::io::Read;
    use std::os::fd::{FromRawFd, OwnedFd};
    use std::sync::mpsc;
    use std::time::{Duration, Instant};

    let dir = app("spinner");
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [
  [id ==> ask, type ==> listening,
   arcs ==> [said(go) : set(n, 0) => busy, said(stop) : say(bye) => fs]],
  [id ==> busy, type ==> neutral,
   arcs ==> [empty : inc(n, _) => (get(n, _) < 60000 -> busy ; otherwise -> ask)]],
  [id ==> fs, type ==> final]
], [n ==> 0]).
",
    )
    .unwrap();
    let (mut master, slave) = unsafe {
        let (mut m, mut s) = (0, 0);
        let r = libc::openpty(
            &mut m,
            &mut s,
            std::ptr::null_mut(),
            std::ptr::null(),
            std::ptr::null(),
        );
        if r != 0 {
            eprintln!("skipped: openpty: {}", std::io::Error::last_os_error());
            return;
        }
        (std::fs::File::from_raw_fd(m), OwnedFd::from_raw_fd(s))
    };
    let mut cmd = sitlogc();
    unsafe {
        use std::os::unix::process::CommandExt;
        cmd.pre_exec(|| {
            if libc::setsid() < 0 || libc::ioctl(0, libc::TIOCSCTTY, 0) < 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    cmd.env("TERM", "xterm");
    let mut child = cmd
        .arg("run")
        .arg(&dir)
        .args(["--history", "none"])
        .stdin(Stdio::from(slave.try_clone().unwrap()))
        .stdout(Stdio::from(slave.try_clone().unwrap()))
        .stderr(Stdio::from(slave.try_clone().unwrap()))
        .spawn()
        .unwrap();
    drop(slave);
    let (tx, rx) = mpsc::channel::<Vec<u8>>();
    let mut reader = master.try_clone().unwrap();
    std::thread::spawn(move || {
        let mut buf = [0u8; 4096];
        while let Ok(n) = reader.read(&mut buf) {
            if n == 0 || tx.send(buf[..n].to_vec()).is_err() {
                return;
            }
        }
    });
    let mut screen = String::new();
    // Reads what the terminal shows until `until` holds, or for `at_least`.
    let read = |screen: &mut String, until: &dyn Fn(&str) -> bool, at_least: Duration| {
        let start = Instant::now();
        loop {
            let done = until(screen) && start.elapsed() >= at_least;
            if done {
                return;
            }
            let left = Duration::from_secs(120).saturating_sub(start.elapsed());
            assert!(!left.is_zero(), "timed out; the terminal shows:\n{screen}");
            if let Ok(bytes) = rx.recv_timeout(Duration::from_millis(50).min(left)) {
                screen.push_str(&String::from_utf8_lossy(&bytes));
            }
        }
    };
    const HEADER: &str = "DM main, situation ask (listening) expects: said(go) | said(stop)";
    let prompts = |s: &str| s.matches(HEADER).count();
    let after_last_prompt = |s: &str| {
        s.rsplit(HEADER)
            .next()
            .unwrap_or("")
            .split_once("|: ")
            .map(|(_, r)| r.to_owned())
    };
    // The first prompt; then a second of waiting (the spinner ticks every
    // 100 ms): nothing is drawn after `|: `.
    read(
        &mut screen,
        &|s| after_last_prompt(s).is_some(),
        Duration::from_millis(1200),
    );
    let waiting = after_last_prompt(&screen).unwrap();
    assert!(
        !waiting.contains("transitions"),
        "a progress line was drawn at the prompt: {waiting:?}\n{screen}"
    );
    // The task runs on its own for a while: the progress line is back, and
    // names the situation the task is in.
    master.write_all(b"go.\r").unwrap();
    read(
        &mut screen,
        &|s| prompts(s) == 2 && after_last_prompt(s).is_some(),
        Duration::from_millis(1200),
    );
    let busy = screen.rsplit(HEADER).nth(1).unwrap_or("");
    assert!(
        busy.contains("transitions") && busy.contains("main / busy"),
        "no progress line while the task ran on its own:\n{screen}"
    );
    let waiting = after_last_prompt(&screen).unwrap();
    assert!(
        !waiting.contains("transitions"),
        "a progress line was drawn at the second prompt: {waiting:?}\n{screen}"
    );
    master.write_all(b"stop.\r").unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(0), "{screen}");
}

/// Standard input at the prompt is read under the input limits, in time
/// linear in it (issue 38): a line that never ends (`< /dev/zero`) is
/// refused at `--max-input-bytes`, naming the input and the limit, instead
/// of growing until the process aborts; a term over 20,000 lines is read
/// once, not once a line.
#[test]
fn typed_input_is_read_under_the_limits_in_linear_time() {
    use std::time::{Duration, Instant};
    let dir = app("limits");
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [
  [id ==> is, type ==> listening, arcs ==> [X : screen(got) => fs]],
  [id ==> fs, type ==> final]
], []).
",
    )
    .unwrap();
    let start = Instant::now();
    let out = sitlogc()
        .arg("run")
        .arg(&dir)
        .args(["--max-input-bytes", "100000"])
        .stdin(std::fs::File::open("/dev/zero").unwrap())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(
            "standard input:1:1: the input is longer than 100000 bytes (100001 bytes or more); the limit is set by --max-input-bytes"
        ),
        "{err}"
    );
    let lines = 20_000;
    let term = "[\n".to_owned() + &"a,\n".repeat(lines) + "b].\n";
    let out = run_piped(&dir, &[], &term);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    // quadratic reading took 74 s for 20,000 lines
    assert!(start.elapsed() < Duration::from_secs(30));
    // the same term over the limit, refused at the line where it starts
    let small = "[\n".to_owned() + &"a,\n".repeat(2_000) + "b].\n";
    let out = run_piped(&dir, &["--max-input-bytes", "1000"], &format!("\n{small}"));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("standard input:2:1: the input is longer than 1000 bytes"),
        "{err}"
    );
}

/// Prolog's `read/1` in a user function takes the run's next input, from
/// the script or typed, in order with the perceptions (issue 39, as the
/// original's test mode): one reader serves the runner's perception and
/// the engine's thread (each run starts an engine: a few seconds in a
/// debug build).
#[test]
fn read_in_a_user_function_takes_the_next_input() {
    let dir = app("read");
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [
  [id ==> is, type ==> listening,
   arcs ==> [said(X) : say(X) => ask(apply(answer, []))]],
  [id ==> ask(A), type ==> listening,
   arcs ==> [said(Y) : [say(A), say(Y)] => fs]],
  [id ==> fs, type ==> final]
], []).
",
    )
    .unwrap();
    std::fs::write(
        dir.join("user_functions.pl"),
        "answer :- read(X), assign_func_value(got(X)).\n",
    )
    .unwrap();
    let said = "Golem says: first\nGolem says: got(second(2))\nGolem says: third\n";
    std::fs::write(dir.join("s.txt"), "first.\nsecond(2).\nthird.\n").unwrap();
    let script = dir.join("s.txt").display().to_string();
    let out = run_piped(&dir, &["--script", &script], "");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert_eq!(err, said);
    // typed, a term over two lines
    let out = run_piped(&dir, &[], "first.\nsecond(\n2).\nthird.\n");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert_eq!(err.matches("Golem says").count(), 3, "{err}");
    assert!(err.contains("Golem says: got(second(2))\n"), "{err}");
}
