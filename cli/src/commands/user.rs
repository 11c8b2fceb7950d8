//! `sitlogc user --ros2` (feature `ros2`): a person plays the user of a
//! robot over ROS 2 ([`sitlog_ros::user_node`]). On a terminal, what the
//! robot says is printed, and each time it listens a line is read at a
//! prompt with line editing and history (rustyline); otherwise stdin's
//! lines are said in turn, each echoed as a turn of the transcript when it
//! goes out.

use rustyline::error::ReadlineError;
use sitlog_robot::interrupt::{Interrupt, EXIT_SIGINT};
use sitlog_robot::Assets;
use sitlog_ros::user_node::{serve, Shown};
use sitlog_ros::{link, Interface};
use std::io::{BufRead, IsTerminal, Write};
use std::path::Path;
use std::sync::mpsc;

/// The interface of `app` (its `ros2.toml`, its world's names), or the
/// defaults. `Err`: the message, already printed.
fn interface(app: Option<&Path>) -> Result<Interface, u8> {
    let Some(app) = app else {
        return Interface::load(None, None).map_err(|e| {
            sitlog_runtime::errln!("{e}");
            2
        });
    };
    let assets = Assets::from_app(app).map_err(|e| {
        sitlog_runtime::errln!("{e}");
        e.status
    })?;
    let world = match &assets.world {
        Some(f) => Some(
            sitlog_sim::World::parse(&f.name, &f.text).map_err(|errors| {
                for e in errors {
                    sitlog_runtime::errln!("{e}");
                }
                2u8
            })?,
        ),
        None => None,
    };
    let ros2 = assets
        .ros2
        .as_ref()
        .map(|f| (f.name.as_str(), f.text.as_str()));
    Interface::load(ros2, world.as_ref()).map_err(|e| {
        sitlog_runtime::errln!("{e}");
        2
    })
}

/// `sitlogc user`: the exit status (see its help).
pub fn user(app: Option<&Path>) -> u8 {
    let iface = match interface(app) {
        Ok(i) => i,
        Err(status) => return status,
    };
    let domain = match link::domain_id() {
        Ok(d) => d,
        Err(e) => {
            sitlog_runtime::errln!("{e}");
            return 2;
        }
    };
    let interrupt = Interrupt::install();
    let terminal = std::io::stdin().is_terminal() && std::io::stdout().is_terminal();
    sitlog_runtime::errln!(
        "sitlogc user: {} on ROS 2 domain {domain}{}: what {} says on {}, what you type on {} while {} listens{}",
        iface.user_name,
        if link::localhost_only() {
            ", this host only"
        } else {
            ""
        },
        iface.robot_name,
        iface.topics.say,
        iface.topics.heard,
        iface.robot_name,
        if terminal {
            " (Ctrl-C ends, or Ctrl-D at the prompt)"
        } else {
            ""
        }
    );
    let (tx, rx) = mpsc::channel::<String>();
    let result = if terminal {
        prompt(&iface, tx, rx, &interrupt)
    } else {
        // Lines as they come; the thread ends with stdin (or the process).
        let _ = std::thread::Builder::new()
            .name("sitlogc-user-stdin".into())
            .spawn(move || {
                for line in std::io::stdin().lock().lines() {
                    let Ok(line) = line else { break };
                    if tx.send(line).is_err() {
                        break;
                    }
                }
            });
        let mut out = std::io::stdout();
        let mut show = |s: Shown| {
            if !matches!(s, Shown::Held(_)) {
                let _ = writeln!(out, "{}", s.text(&iface));
                let _ = out.flush();
            }
        };
        serve(&iface, rx, &mut show, &interrupt.flag)
    };
    match result {
        Err(e) => {
            sitlog_runtime::errln!("{e}");
            2
        }
        Ok(()) if interrupt.ended_by_input() => 0,
        Ok(()) => interrupt.exit_status().unwrap_or(0),
    }
}

/// The prompt on the terminal: the node on a thread of its own hands
/// what to show to this one, which prints it and, each time the robot
/// listens, reads a line (line editing, history). Nothing is printed while
/// a line is read: a robot does not speak while it listens, and what comes
/// meanwhile (a new run) is printed after. (rustyline's external printer
/// would print during the read, but then keys that arrive together, as
/// under load, wait for the next key: its issue 976.)
fn prompt(
    iface: &Interface,
    tx: mpsc::Sender<String>,
    rx: mpsc::Receiver<String>,
    interrupt: &Interrupt,
) -> Result<(), String> {
    use rustyline::config::{Behavior, Config};
    // An editor only while a line is read: rustyline takes SIGINT while
    // one exists (without its `signal-hook` feature), and between two
    // reads Ctrl-C must stop the node. The history goes from one to the next.
    let editor = |history: &[String]| {
        let config = Config::builder()
            .behavior(Behavior::PreferTerm)
            .auto_add_history(false)
            .build();
        let mut editor = rustyline::DefaultEditor::with_config(config)
            .map_err(|e| format!("error: the terminal: {e}"))?;
        for line in history {
            let _ = editor.add_history_entry(line.as_str());
        }
        Ok::<_, String>(editor)
    };
    let mut history: Vec<String> = Vec::new();
    let (shown_tx, shown) = mpsc::channel::<Shown>();
    let node_iface = iface.clone();
    let flag = interrupt.flag.clone();
    let node = std::thread::Builder::new()
        .name("sitlogc-user-node".into())
        .spawn(move || {
            let mut show = |s: Shown| {
                let _ = shown_tx.send(s);
            };
            serve(&node_iface, rx, &mut show, &flag)
        })
        .map_err(|e| format!("error: a thread: {e}"))?;
    let prompt = format!("{}> ", iface.user_name);
    let mut out = std::io::stdout();
    let stop = |why: i32| interrupt.request(why);
    loop {
        let s = match shown.recv_timeout(std::time::Duration::from_millis(100)) {
            Ok(s) => s,
            Err(mpsc::RecvTimeoutError::Timeout) => continue,
            // The node has ended (stopped, or it could not start).
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
        };
        // The typed line is on the screen already; nothing is held here.
        if !matches!(s, Shown::Sent(_) | Shown::Held(_)) {
            let _ = writeln!(out, "{}", s.text(iface));
            let _ = out.flush();
        }
        if s != Shown::Listens {
            continue;
        }
        // A line for this listen (a blank one is not said: read again).
        let mut editor = editor(&history)?;
        let line = loop {
            match editor.readline(&prompt) {
                Ok(line) if line.trim().is_empty() => continue,
                Ok(line) => break Some(line),
                // Ctrl-D: the node ends now.
                Err(ReadlineError::Eof) => {
                    interrupt.request_end_of_input();
                    break None;
                }
                // Ctrl-C in raw mode is a key, not a signal: stop as SIGINT would.
                Err(ReadlineError::Interrupted) => {
                    stop(i32::from(EXIT_SIGINT) - 128);
                    break None;
                }
                Err(e) => {
                    stop(i32::from(EXIT_SIGINT) - 128);
                    let _ = node.join();
                    return Err(format!("error: the terminal: {e}"));
                }
            }
        };
        drop(editor);
        let Some(line) = line else { break };
        history.push(line.clone());
        if tx.send(line).is_err() {
            break;
        }
    }
    drop(tx);
    node.join()
        .unwrap_or_else(|_| Err("error: the node stopped".to_owned()))
}
