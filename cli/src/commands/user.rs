//! `sitlogc user --ros2` (feature `ros2`): a person plays the user of a
//! robot over ROS 2 ([`sitlog_ros::user_node`]). On a terminal, lines are
//! typed at a prompt with line editing and history (rustyline) while the
//! node prints what the robot says above it; otherwise stdin's lines are
//! said in turn, each echoed as a turn of the transcript when it goes out.

use rustyline::error::ReadlineError;
use rustyline::ExternalPrinter;
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
        if terminal { " (Ctrl-D ends)" } else { "" }
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

/// The prompt on the terminal, the node on a thread of its own printing
/// above it.
fn prompt(
    iface: &Interface,
    tx: mpsc::Sender<String>,
    rx: mpsc::Receiver<String>,
    interrupt: &Interrupt,
) -> Result<(), String> {
    use rustyline::config::{Behavior, Config};
    let config = Config::builder()
        .behavior(Behavior::PreferTerm)
        .auto_add_history(false)
        .build();
    let mut editor = rustyline::DefaultEditor::with_config(config)
        .map_err(|e| format!("error: the terminal: {e}"))?;
    let mut printer = editor
        .create_external_printer()
        .map_err(|e| format!("error: the terminal: {e}"))?;
    let node_iface = iface.clone();
    let flag = interrupt.flag.clone();
    let node = std::thread::Builder::new()
        .name("sitlogc-user-node".into())
        .spawn(move || {
            let mut show = |s: Shown| {
                // The typed line is on the screen already.
                if !matches!(s, Shown::Sent(_)) {
                    let _ = printer.print(format!("{}\n", s.text(&node_iface)));
                }
            };
            serve(&node_iface, rx, &mut show, &flag)
        })
        .map_err(|e| format!("error: a thread: {e}"))?;
    let prompt = format!("{}> ", iface.user_name);
    loop {
        if interrupt.requested() || node.is_finished() {
            break;
        }
        match editor.readline(&prompt) {
            Ok(line) => {
                if !line.trim().is_empty() {
                    let _ = editor.add_history_entry(line.as_str());
                }
                if tx.send(line).is_err() {
                    break;
                }
            }
            // Ctrl-D: the node ends now, a line not yet out with it.
            Err(ReadlineError::Eof) => {
                interrupt.request_end_of_input();
                break;
            }
            // Ctrl-C in raw mode is a key, not a signal: stop as SIGINT would.
            Err(ReadlineError::Interrupted) => {
                interrupt.request(i32::from(EXIT_SIGINT) - 128);
                break;
            }
            Err(e) => {
                interrupt.request(i32::from(EXIT_SIGINT) - 128);
                let _ = node.join();
                return Err(format!("error: the terminal: {e}"));
            }
        }
    }
    drop(tx);
    node.join()
        .unwrap_or_else(|_| Err("error: the node stopped".to_owned()))
}
