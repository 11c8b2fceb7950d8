//! `--robot ros2`, `sitlogc sim --ros2` and `sitlogc user --ros2` (feature
//! `ros2`): the scenarios over DDS between two processes print the
//! in-process conversation and history, a world variant's recovery runs
//! over it, one simulator serves run after run on a fresh world, a person
//! plays the user (from a file and on a terminal), and each fault of the
//! guide behaves as documented (no server, the robot killed, a malformed
//! message, two tasks, no robot, a user with nothing more to say). Every test has its own
//! `ROS_DOMAIN_ID` and stays on loopback (`ROS_LOCALHOST_ONLY=1`); every
//! child is killed when its test ends, and every wait has a deadline.

use crate::support::{assert_ok, sitlogc, workspace};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::atomic::{AtomicU16, Ordering};
use std::time::{Duration, Instant};

/// A domain of this test alone.
fn domain() -> u16 {
    static NEXT: AtomicU16 = AtomicU16::new(0);
    120 + (std::process::id() % 10) as u16 * 10 + NEXT.fetch_add(1, Ordering::SeqCst)
}

fn on_domain(cmd: &mut Command, domain: u16) -> &mut Command {
    cmd.env("ROS_DOMAIN_ID", domain.to_string())
        .env("ROS_LOCALHOST_ONLY", "1")
        .env_remove("ROS_AUTOMATIC_DISCOVERY_RANGE")
}

/// A child process killed (TERM, then KILL) when dropped; its stdout and
/// stderr go to files.
struct Node {
    child: Child,
    out: PathBuf,
    err: PathBuf,
    _dir: tempfile::TempDir,
}

impl Node {
    fn spawn(cmd: Command) -> Node {
        Node::spawn_with(cmd, Stdio::null())
    }

    /// [`Node::spawn`] with `stdin`.
    fn spawn_with(mut cmd: Command, stdin: Stdio) -> Node {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let err = dir.path().join("err");
        let child = cmd
            .stdin(stdin)
            .stdout(std::fs::File::create(&out).unwrap())
            .stderr(std::fs::File::create(&err).unwrap())
            .spawn()
            .expect("sitlogc starts");
        Node {
            child,
            out,
            err,
            _dir: dir,
        }
    }

    fn stdout(&self) -> String {
        std::fs::read_to_string(&self.out).unwrap_or_default()
    }

    fn stderr(&self) -> String {
        std::fs::read_to_string(&self.err).unwrap_or_default()
    }

    /// Waits until stdout or stderr has `text`.
    fn wait_for(&mut self, text: &str, limit: Duration) {
        let start = Instant::now();
        while !(self.stdout().contains(text) || self.stderr().contains(text)) {
            if let Ok(Some(status)) = self.child.try_wait() {
                panic!(
                    "ended ({status}) before printing `{text}`:\n{}\n{}",
                    self.stdout(),
                    self.stderr()
                );
            }
            assert!(
                start.elapsed() < limit,
                "no `{text}` within {limit:?}:\n{}\n{}",
                self.stdout(),
                self.stderr()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// Waits for the end (at most `limit`): exit code, stdout, stderr.
    fn finish(mut self, limit: Duration) -> (Option<i32>, String, String) {
        let start = Instant::now();
        loop {
            if let Some(status) = self.child.try_wait().unwrap() {
                return (status.code(), self.stdout(), self.stderr());
            }
            if start.elapsed() > limit {
                let (out, err) = (self.stdout(), self.stderr());
                panic!("still running after {limit:?}:\n{out}\n{err}");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// Stops it with `signal` and waits for it.
    fn stop(&mut self, signal: &str) {
        crate::support::kill(self.child.id(), signal);
        let start = Instant::now();
        while self.child.try_wait().ok().flatten().is_none()
            && start.elapsed() < Duration::from_secs(10)
        {
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

impl Drop for Node {
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            let _ = Command::new("kill")
                .arg("-TERM")
                .arg(self.child.id().to_string())
                .status();
            let start = Instant::now();
            while start.elapsed() < Duration::from_secs(3) {
                if let Ok(Some(_)) = self.child.try_wait() {
                    return;
                }
                std::thread::sleep(Duration::from_millis(20));
            }
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

/// `sitlogc sim APP --ros2 ARGS` on `domain`, once it serves.
fn sim(app: &Path, domain: u16, args: &[&str]) -> Node {
    let mut cmd = sitlogc();
    cmd.arg("sim").arg(app).arg("--ros2").args(args);
    on_domain(&mut cmd, domain);
    let mut node = Node::spawn(cmd);
    node.wait_for("sitlogc sim: serving", Duration::from_secs(30));
    node
}

/// `sitlogc run APP --robot ros2 ARGS` on `domain`.
fn task(app: &Path, domain: u16, args: &[&str]) -> Node {
    let mut cmd = sitlogc();
    cmd.arg("run")
        .arg(app)
        .arg("--robot")
        .arg("ros2")
        .args(args);
    on_domain(&mut cmd, domain);
    Node::spawn(cmd)
}

fn in_process(app: &Path, args: &[&str]) -> String {
    let out: Output = sitlogc().arg("run").arg(app).args(args).output().unwrap();
    assert_ok(&out);
    String::from_utf8(out.stdout).unwrap()
}

/// Lines that are not narration (the conversation, then the report).
fn conversation_and_history(text: &str) -> Vec<&str> {
    text.lines().filter(|l| !l.starts_with("  (")).collect()
}

/// The world's transcript as the simulated robot prints it in-process:
/// without the KB's lines (the task prints those) and the report.
fn world_transcript(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        if line == "Execution history:" {
            break;
        }
        if !line.starts_with("  (KB: ") {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// The scenario `app` (with `args`, e.g. `--world FILE`) over DDS prints the
/// in-process conversation and history (task), and the in-process world
/// transcript (sim node): `want`, the in-process run's stdout.
fn same_over_dds(app: &Path, args: &[&str], want: &str) {
    let d = domain();
    let mut robot = sim(app, d, args);
    let (code, out, err) = task(app, d, args).finish(Duration::from_secs(180));
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(
        conversation_and_history(&out),
        conversation_and_history(want),
        "the task over DDS:\n{out}\nin-process:\n{want}"
    );
    robot.stop("TERM");
    assert_eq!(
        robot.stdout(),
        world_transcript(want),
        "the sim node's transcript"
    );
}

#[test]
fn home_over_dds_prints_the_in_process_conversation_and_history() {
    // The in-process run is the one `new::a_copy_of_the_home_app_runs_anywhere`
    // compares with: one engine start for both.
    same_over_dds(
        &workspace().join("dms/apps/home"),
        &[],
        crate::support::home_run(),
    );
}

#[test]
fn supermarket_over_dds_prints_the_in_process_conversation_and_history() {
    let app = workspace().join("dms/apps/supermarket");
    same_over_dds(&app, &[], &in_process(&app, &[]));
}

/// A blocked route: the navigation goal is aborted with `blocked(From, To)`,
/// and the recovery protocol `reroute` runs over DDS as in-process.
#[test]
fn an_aborted_goal_runs_the_recovery_protocol_as_in_process() {
    let home = workspace().join("dms/apps/home");
    let text = std::fs::read_to_string(home.join("world.toml")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let world = dir.path().join("blocked.toml");
    std::fs::write(
        &world,
        format!("{text}\n[[fault]]\nkind = \"route_blocked\"\nfrom = \"hall\"\nto = \"pantry\"\n"),
    )
    .unwrap();
    let w = world.to_str().unwrap();
    let want = in_process(&home, &["--world", w]);
    assert!(
        want.contains("blocked"),
        "the variant blocks a route:\n{want}"
    );
    same_over_dds(&home, &["--world", w], &want);
}

/// A small robot task on the home world (no Prolog: a run takes a fraction
/// of a second): it asks, says what it heard, goes to the living room
/// (where it is) and listens again. Beside it `one.toml`, the home world
/// whose user says one line.
fn small_app() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("main.dm"),
        "diag_mod(main,\n  [\n\
         [id ==> is, type ==> neutral, arcs ==> [empty : say('What shall I do?') => ask]],\n\
         [id ==> ask, type ==> speech,\n arcs ==> [said(T) : say(['You said', T]) => go, nobody : empty => ask]],\n\
         [id ==> go, type ==> neutral, arcs ==> [empty : navigate(living_room, S) => again(S)]],\n\
         [id ==> again(S), type ==> speech,\n arcs ==> [said(T) : say(['Here', S, T]) => fs, nobody : empty => fs]],\n\
         [id ==> fs, type ==> final]\n  ],\n  []).\n",
    )
    .unwrap();
    let home = std::fs::read_to_string(workspace().join("dms/apps/home/world.toml")).unwrap();
    std::fs::write(dir.path().join("world.toml"), &home).unwrap();
    // One utterance, and no moves after the later ones.
    let start = home.find("says = [").unwrap();
    let end = start + home[start..].find(']').unwrap();
    let mut one = format!("{}says = [\"hi golem\"{}", &home[..start], &home[end..]);
    while let Some(at) = one.find("[[user.moves]]") {
        let stop = one[at..].find("\n\n").map_or(one.len(), |n| at + n + 2);
        one.replace_range(at..stop, "");
    }
    std::fs::write(dir.path().join("one.toml"), one).unwrap();
    // The robot's acknowledgement of a run may take more than the default
    // 5 s on a loaded 2-core CI machine running the suite (seen once: the
    // second run of `a_user_with_nothing_more_to_say_...`); no test here
    // waits for that timeout to expire.
    std::fs::write(dir.path().join("ros2.toml"), "[timeouts]\nanswer = 30.0\n").unwrap();
    dir
}

/// Three task runs against one simulator: each starts a new episode on a
/// fresh world, so each prints the in-process conversation and history
/// (the user's first two lines each time), and the node prints the
/// in-process world transcript three times.
#[test]
fn the_simulator_serves_run_after_run_each_on_a_fresh_world() {
    let app = small_app();
    let want = in_process(app.path(), &[]);
    assert!(want.contains("Luis: i like noodles best"), "{want}");
    let d = domain();
    let mut robot = sim(app.path(), d, &[]);
    for run in 1..=3 {
        let (code, out, err) = task(app.path(), d, &[]).finish(Duration::from_secs(60));
        assert_eq!(code, Some(0), "run {run}:\n{out}\n{err}");
        assert_eq!(
            conversation_and_history(&out),
            conversation_and_history(&want),
            "run {run} over DDS:\n{out}\nin-process:\n{want}"
        );
    }
    robot.stop("TERM");
    assert_eq!(robot.stdout(), world_transcript(&want).repeat(3));
    let notes = robot.stderr();
    assert!(notes.contains("run 3 (pid "), "{notes}");
    assert_eq!(notes.matches(": a fresh world").count(), 2, "{notes}");
}

/// The world's user has nothing more to say: the task stops with the
/// in-process run-time error, the node says why and serves the next run.
#[test]
fn a_user_with_nothing_more_to_say_stops_the_run_on_both_sides() {
    let app = small_app();
    let one = app.path().join("one.toml");
    let one = ["--world", one.to_str().unwrap()];
    let out = sitlogc()
        .arg("run")
        .arg(app.path())
        .args(one)
        .output()
        .unwrap();
    let in_code = out.status.code();
    let in_err = String::from_utf8(out.stderr).unwrap();
    let why = "the user has nothing more to say: all 1 utterances";
    assert!(in_err.contains(why), "in-process: {in_err}");
    let d = domain();
    let mut robot = sim(app.path(), d, &one);
    for _ in 0..2 {
        let (code, out, err) = task(app.path(), d, &one).finish(Duration::from_secs(60));
        assert_eq!(code, in_code, "as in-process:\n{out}\n{err}");
        assert!(err.contains(why), "the task: {err}");
    }
    robot.stop("TERM");
    let notes = robot.stderr();
    assert_eq!(notes.matches(why).count(), 2, "the node: {notes}");
}

/// `sitlogc user --ros2` fed the user's lines on stdin plays the user for a
/// simulator with `--speech external`: the task prints the in-process
/// conversation and history; the console prints what the robot said, when
/// it listened and what it sent, and ends after its last line.
#[test]
fn the_user_console_plays_the_user_from_stdin() {
    let app = small_app();
    let want = in_process(app.path(), &[]);
    let d = domain();
    let _robot = sim(app.path(), d, &["--speech", "external"]);
    let lines = app.path().join("lines.txt");
    std::fs::write(&lines, "hi golem i like malz\n\ni like noodles best\n").unwrap();
    let mut cmd = sitlogc();
    cmd.arg("user").arg(app.path()).arg("--ros2");
    on_domain(&mut cmd, d);
    let mut user = Node::spawn_with(cmd, std::fs::File::open(&lines).unwrap().into());
    user.wait_for(
        "sitlogc user: Luis on ROS 2 domain",
        Duration::from_secs(30),
    );
    let (code, out, err) = task(app.path(), d, &[]).finish(Duration::from_secs(60));
    assert_eq!(code, Some(0), "{out}\n{err}\n{}", user.stderr());
    assert_eq!(
        conversation_and_history(&out),
        conversation_and_history(&want)
    );
    // It ends a moment after its last line was heard (what the task says
    // then may or may not be shown).
    let (code, shown, err) = user.finish(Duration::from_secs(30));
    assert_eq!(code, Some(0), "{shown}\n{err}");
    let turns: Vec<&str> = shown
        .lines()
        .filter(|l| !l.contains("a task starts a run"))
        .take(6)
        .collect();
    assert_eq!(
        turns,
        [
            "Golem: What shall I do?",
            "  (Golem listens)",
            "Luis: hi golem i like malz",
            "Golem: You said hi golem i like malz",
            "  (Golem listens)",
            "Luis: i like noodles best",
        ],
        "{shown}"
    );
}

/// `sitlogc user --ros2` on a terminal (a pty): each time the robot
/// listens, what is typed at the prompt, edited (a backspace) or taken from
/// the history (the up arrow), is what the task hears; Ctrl-C ends it.
/// A line goes in one write, as pasted.
#[cfg(target_os = "linux")]
#[test]
fn the_user_console_on_a_terminal_edits_and_remembers_lines() {
    use std::io::{Read, Write};
    use std::os::fd::{FromRawFd, OwnedFd};
    use std::sync::mpsc;

    let app = small_app();
    let d = domain();
    let _robot = sim(app.path(), d, &["--speech", "external"]);
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
    // The pty is the console's controlling terminal, as a shell's is.
    unsafe {
        use std::os::unix::process::CommandExt;
        cmd.pre_exec(|| {
            if libc::setsid() < 0 || libc::ioctl(0, libc::TIOCSCTTY, 0) < 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    cmd.env("TERM", "xterm")
        .arg("user")
        .arg(app.path())
        .arg("--ros2")
        .stdout(Stdio::from(slave.try_clone().unwrap()))
        .stderr(Stdio::from(slave.try_clone().unwrap()));
    on_domain(&mut cmd, d);
    /// Killed if the test fails before it ends.
    struct Killed(Child);
    impl Drop for Killed {
        fn drop(&mut self) {
            let _ = self.0.kill();
            let _ = self.0.wait();
        }
    }
    let mut user = Killed(
        cmd.stdin(Stdio::from(slave.try_clone().unwrap()))
            .spawn()
            .unwrap(),
    );
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
    let mut wait = |text: &str, count: usize| {
        let start = Instant::now();
        while screen.matches(text).count() < count {
            let left = Duration::from_secs(60).saturating_sub(start.elapsed());
            match rx.recv_timeout(left) {
                Ok(bytes) => screen.push_str(&String::from_utf8_lossy(&bytes)),
                Err(_) => panic!("no {text:?} (x{count}) on the terminal:\n{screen}"),
            }
        }
    };
    let mut type_keys = |keys: &[&[u8]]| {
        for k in keys {
            master.write_all(k).unwrap();
            std::thread::sleep(Duration::from_millis(15));
        }
    };
    wait("sitlogc user: Luis on ROS 2 domain", 1);
    let t = task(app.path(), d, &[]);
    wait("(Golem listens)", 1);
    wait("Luis> ", 1);
    type_keys(&[b"hi golem i like malx\x7fz\r"]);
    wait("Golem: You said hi golem i like malz", 1);
    wait("(Golem listens)", 2);
    wait("Luis> ", 2);
    type_keys(&[b"\x1b[A", b"\r"]);
    let (code, out, err) = t.finish(Duration::from_secs(60));
    assert_eq!(code, Some(0), "{out}\n{err}\n{screen}");
    assert!(
        out.contains("Luis: hi golem i like malz\nGolem: Here ok hi golem i like malz.\n"),
        "{out}"
    );
    // Ctrl-C (no prompt: the terminal makes it SIGINT).
    type_keys(&[b"\x03"]);
    let start = Instant::now();
    let status = loop {
        if let Some(s) = user.0.try_wait().unwrap() {
            break s;
        }
        assert!(start.elapsed() < Duration::from_secs(30), "{screen}");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert_eq!(status.code(), Some(130), "{screen}");
}

/// A robot's side with `ros2` as its `ros2.toml` (and the home world).
fn robot_dir(ros2: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let home = workspace().join("dms/apps/home");
    std::fs::copy(home.join("world.toml"), dir.path().join("world.toml")).unwrap();
    std::fs::write(dir.path().join("ros2.toml"), ros2).unwrap();
    dir
}

#[test]
fn no_server_for_an_action_gives_a_status_naming_it_and_the_run_ends() {
    let home = workspace().join("dms/apps/home");
    // The robot serves navigation under another name.
    let side = robot_dir("[actions]\nnavigate = \"/elsewhere/navigate_to_pose\"\n");
    let d = domain();
    let _robot = sim(side.path(), d, &[]);
    let (code, out, err) = task(&home, d, &[]).finish(Duration::from_secs(180));
    assert!(
        out.contains("unavailable('/navigate_to_pose')"),
        "status {code:?}\n{out}\n{err}"
    );
    assert!(code.is_some());
}

#[test]
fn the_robot_killed_mid_run_stops_the_task_with_its_history_and_report() {
    let home = workspace().join("dms/apps/home");
    let d = domain();
    // The user's words come from outside: the task waits at the first question.
    let mut robot = sim(&home, d, &["--speech", "external"]);
    let t = task(&home, d, &["--format", "json"]);
    robot.wait_for("Golem: Please tell me", Duration::from_secs(60));
    robot.stop("KILL");
    let (code, out, err) = t.finish(Duration::from_secs(60));
    assert_eq!(code, Some(4), "{out}\n{err}");
    assert!(err.contains("the robot is gone"), "{err}");
    assert!(err.contains("stopped: the robot went away"), "{err}");
    let report: serde_json::Value = serde_json::from_str(out.trim()).expect("one JSON report");
    let history = report["history"].as_array().expect("a history");
    assert!(!history.is_empty(), "{report}");
}

#[test]
fn a_malformed_message_is_logged_and_dropped() {
    let home = workspace().join("dms/apps/home");
    let d = domain();
    let _robot = sim(&home, d, &["--speech", "external"]);
    let mut t = task(&home, d, &["-q"]);
    t.wait_for("Golem: Please tell me", Duration::from_secs(60));
    // A peer on the heard topic whose bytes are no std_msgs/String.
    let link = sitlog_ros::link::Link::open_on("test_peer", d, true).unwrap();
    let qos = sitlog_ros::Interface::load(None, None).unwrap().qos.heard;
    let bad = link
        .writer::<u32>("/sitlog/heard", ("std_msgs", "String"), &qos)
        .unwrap();
    let good = link
        .writer::<sitlog_ros::msgs::StdString>("/sitlog/heard", ("std_msgs", "String"), &qos)
        .unwrap();
    std::thread::sleep(Duration::from_secs(2));
    bad.send(1000, Some(Duration::from_secs(5))).unwrap();
    good.send(
        sitlog_ros::msgs::StdString {
            data: "hi golem i like malz".into(),
        },
        Some(Duration::from_secs(5)),
    )
    .unwrap();
    t.wait_for("Luis: hi golem i like malz", Duration::from_secs(30));
    // Said on stderr, under -q too (issue 38).
    assert!(
        t.stderr()
            .contains("note: dropped a malformed message on /sitlog/heard"),
        "{}",
        t.stderr()
    );
}

#[test]
fn a_second_task_on_the_domain_is_refused() {
    let home = workspace().join("dms/apps/home");
    let d = domain();
    let _robot = sim(&home, d, &["--speech", "external"]);
    let mut first = task(&home, d, &[]);
    first.wait_for("Golem: Please tell me", Duration::from_secs(60));
    let (code, _, err) = task(&home, d, &[]).finish(Duration::from_secs(60));
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("another task already drives the robot"),
        "{err}"
    );
    assert!(
        first.child.try_wait().unwrap().is_none(),
        "the first task goes on"
    );
}

/// (A one-situation task that looks for its robot for 1 s instead of the
/// default 5 s: the wait is the test's whole cost.)
#[test]
fn without_a_robot_the_task_does_not_start() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> final]], []).\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("ros2.toml"), "[timeouts]\ndiscovery = 1\n").unwrap();
    let (code, out, err) = task(dir.path(), domain(), &[]).finish(Duration::from_secs(60));
    assert_eq!(code, Some(4), "{out}\n{err}");
    assert!(err.contains("no robot on ROS 2 domain"), "{err}");
    assert!(out.is_empty(), "{out}");
}

/// A ROS 2 node on another DDS implementation (Eclipse Cyclone DDS, from
/// Python) plays the user through `--speech external`: it publishes the
/// world's utterances on the heard topic whenever the task listens. Skipped
/// when Python's `cyclonedds` module is missing.
#[test]
fn a_cyclone_dds_node_plays_the_user() {
    let python = std::env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    let has = Command::new(&python)
        .args(["-c", "import cyclonedds"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !has {
        eprintln!("skipped: no Python module `cyclonedds` (pip install cyclonedds)");
        return;
    }
    let home = workspace().join("dms/apps/home");
    let want = in_process(&home, &[]);
    let d = domain();
    let _robot = sim(&home, d, &["--speech", "external"]);
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("user.py");
    std::fs::write(&script, USER_PY).unwrap();
    let config = dir.path().join("cyclone.xml");
    std::fs::write(&config, CYCLONE_XML).unwrap();
    let mut user = Command::new(&python);
    user.arg(&script)
        .arg(d.to_string())
        .env("CYCLONEDDS_URI", format!("file://{}", config.display()));
    for line in says(&home) {
        user.arg(line);
    }
    let _user = Node::spawn(user);
    let (code, out, err) = task(&home, d, &[]).finish(Duration::from_secs(180));
    assert_eq!(code, Some(0), "{out}\n{err}\n{}", _user.stderr());
    assert_eq!(
        conversation_and_history(&out),
        conversation_and_history(&want)
    );
}

/// The world file's `user.says`.
fn says(app: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(app.join("world.toml")).unwrap();
    let start = text.find("says = [").unwrap() + "says = [".len();
    let end = start + text[start..].find(']').unwrap();
    text[start..end]
        .split('"')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect()
}

/// Cyclone DDS on loopback only, finding peers by unicast.
const CYCLONE_XML: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<CycloneDDS>
  <Domain id="any">
    <General>
      <Interfaces><NetworkInterface address="127.0.0.1"/></Interfaces>
      <AllowMulticast>false</AllowMulticast>
    </General>
    <Discovery>
      <ParticipantIndex>auto</ParticipantIndex>
      <MaxAutoParticipantIndex>20</MaxAutoParticipantIndex>
      <Peers><Peer address="127.0.0.1"/></Peers>
    </Discovery>
  </Domain>
</CycloneDDS>
"#;

/// The user as a ROS 2 node on Cyclone DDS: on each `true` on
/// `/sitlog/listening`, the next utterance on `/sitlog/heard`.
const USER_PY: &str = r#"
import sys, time
from dataclasses import dataclass
from cyclonedds.domain import DomainParticipant
from cyclonedds.topic import Topic
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.core import Qos, Policy
from cyclonedds.idl import IdlStruct
from cyclonedds.util import duration

@dataclass
class String_(IdlStruct, typename="std_msgs::msg::dds_::String_"):
    data: str

@dataclass
class Bool_(IdlStruct, typename="std_msgs::msg::dds_::Bool_"):
    data: bool

domain = int(sys.argv[1])
says = sys.argv[2:]
dp = DomainParticipant(domain)
latched = Qos(Policy.Reliability.Reliable(duration(seconds=1)), Policy.Durability.TransientLocal, Policy.History.KeepLast(100))
reliable = Qos(Policy.Reliability.Reliable(duration(seconds=1)), Policy.Durability.Volatile, Policy.History.KeepLast(10))
listening = DataReader(dp, Topic(dp, "rt/sitlog/listening", Bool_), qos=latched)
heard = DataWriter(dp, Topic(dp, "rt/sitlog/heard", String_), qos=reliable)
deadline = time.time() + 170
while says and time.time() < deadline:
    for sample in listening.take(N=100):
        # Each `true` is a new listen (not a writer's dispose or unregister).
        if getattr(sample, "data", False) and says:
            heard.write(String_(data=says.pop(0)))
            print("said", flush=True)
    time.sleep(0.01)
time.sleep(2)
"#;

/// A node of another kind publishing another type on `/sitlog/listening`
/// does not stop the task from starting: it is logged and ignored (issue
/// 38; it was taken for another task, exit 2).
#[test]
fn a_foreign_publisher_on_the_listening_topic_is_logged_and_ignored() {
    let home = workspace().join("dms/apps/home");
    let d = domain();
    let foreign = sitlog_ros::link::Link::open_on("foreign", d, true).unwrap();
    let qos = sitlog_ros::config::Qos {
        reliability: "reliable".into(),
        durability: "volatile".into(),
        depth: 1,
    };
    let _writer = foreign
        .writer::<sitlog_ros::msgs::StdString>("/sitlog/listening", ("std_msgs", "String"), &qos)
        .unwrap();
    let _robot = sim(&home, d, &["--speech", "external"]);
    let mut t = task(&home, d, &["-q"]);
    t.wait_for("Golem: Please tell me", Duration::from_secs(60));
    assert!(
        t.stderr().contains("std_msgs::msg::dds_::String_") && t.stderr().contains("ignored"),
        "{}",
        t.stderr()
    );
}
