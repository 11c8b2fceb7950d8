//! A person plays the user over ROS 2 ([`serve`], `sitlogc user --ros2`):
//! a node that shows what the robot says (the say topic) and when it
//! listens (the listening topic), and sends the lines the person types on
//! the heard topic, as a speech recogniser would.
//!
//! A line goes out only while the robot listens, one line per listen: a
//! line typed while it does not is held, in order, until it next listens
//! (so a file of lines on stdin plays a whole conversation). A new run of
//! the task (the run topic) drops the state of the old one's listening.
//! The node reads with best effort, so that the task never waits for it:
//! closing it mid-run does not stop the run.
//!
//! Invariant: nothing here waits without looking at the stop flag at
//! least every [`POLL`]; a line is sent at most once.

use crate::config::Interface;
use crate::link::{Link, Writer};
use crate::msgs::{StdBool, StdString};
use ros2_client::Subscription;
use std::collections::VecDeque;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, TryRecvError};
use std::time::{Duration, Instant};

/// How often the node looks at its topics, its lines and the stop flag.
pub const POLL: Duration = Duration::from_millis(20);

/// How long the node stays once its lines are out and no task runs.
const LINGER: Duration = Duration::from_millis(500);

/// What [`serve`] prints, a line at a time, as the transcript does.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Shown {
    /// The robot said it (`Golem: text`).
    Said(String),
    /// The robot listens (`(Golem listens)`).
    Listens,
    /// A line went out on the heard topic (`Luis: text`; a terminal shows
    /// the typed line already).
    Sent(String),
    /// A line typed while the robot does not listen, held until it does.
    Held(String),
    /// A task started a run (its id).
    NewRun(String),
}

impl Shown {
    /// The line as printed, with the robot's and the user's names.
    pub fn text(&self, iface: &Interface) -> String {
        let (robot, user) = (&iface.robot_name, &iface.user_name);
        match self {
            Shown::Said(t) => format!("{robot}: {t}"),
            Shown::Listens => format!("  ({robot} listens)"),
            Shown::Sent(t) => format!("{user}: {t}"),
            Shown::Held(_) => format!("  (held until {robot} listens)"),
            Shown::NewRun(id) => format!("  (a task starts a run: {id})"),
        }
    }
}

/// Serves until `stop` is set, or `lines` has ended (its sender dropped)
/// and every line it gave has gone out, and either the task took the last
/// (a second ago) or no task runs. Each line of `lines` is what the
/// user says (blank lines are skipped); `show` gets what to print. `Err`:
/// the node could not start, or a line could not be published.
pub fn serve(
    iface: &Interface,
    lines: Receiver<String>,
    show: &mut dyn FnMut(Shown),
    stop: &AtomicBool,
) -> Result<(), String> {
    let mut link = Link::open("user")?;
    let t = &iface.topics;
    let q = &iface.qos;
    // Best effort: the task never waits for this node (a console closed
    // mid-run is no robot gone), which then misses what was said before it
    // started; a listening task says so again every `timeouts.answer`.
    // Keep every message until taken: a `false` then a `true` are two listens.
    let watch = crate::config::Qos {
        reliability: "best_effort".into(),
        durability: "volatile".into(),
        depth: 1000,
    };
    let say: Subscription<StdString> = link.subscription(&t.say, ("std_msgs", "String"), &watch)?;
    let listening: Subscription<StdBool> =
        link.subscription(&t.listening, ("std_msgs", "Bool"), &watch)?;
    let run: Subscription<StdString> = link.subscription(&t.run, ("std_msgs", "String"), &watch)?;
    let heard: Writer<StdString> = link.writer(&t.heard, ("std_msgs", "String"), &q.heard)?;
    let answer = Interface::secs(iface.timeouts.answer);
    let discovery = Interface::secs(iface.timeouts.discovery);

    let mut held: VecDeque<String> = VecDeque::new();
    let mut ended = false;
    let mut listens = false;
    let mut sent = false;
    let mut done: Option<Instant> = None;
    // When the task last took a line (its listening ended after it).
    let mut taken: Option<Instant> = None;
    loop {
        if stop.load(Ordering::SeqCst) {
            return Ok(());
        }
        loop {
            match lines.try_recv() {
                Ok(line) if line.trim().is_empty() => {}
                Ok(line) => {
                    if !(listens && !sent && held.is_empty()) {
                        show(Shown::Held(line.clone()));
                    }
                    held.push_back(line);
                }
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => {
                    ended = true;
                    break;
                }
            }
        }
        // The task's messages, in the order it published them.
        let mut inputs: Vec<(Option<ros2_client::ROSTime>, u8, Input)> = Vec::new();
        take(&run, 0, &mut inputs, Input::Run);
        take(&say, 1, &mut inputs, Input::Say);
        take(&listening, 2, &mut inputs, |b: StdBool| {
            Input::Listening(b.data)
        });
        inputs.sort_by_key(|a| (a.0, a.1));
        for (_, _, input) in inputs {
            match input {
                Input::Run(m) => {
                    listens = false;
                    sent = false;
                    show(Shown::NewRun(m.data));
                }
                Input::Say(m) => show(Shown::Said(m.data)),
                // The task says again that it listens while it waits.
                Input::Listening(true) if listens && !sent => {}
                // A new listen (after a line went out to the last one: its
                // `false` may be lost, this node reading with best effort).
                Input::Listening(true) => {
                    if sent {
                        taken = Some(Instant::now());
                    }
                    listens = true;
                    sent = false;
                    show(Shown::Listens);
                }
                Input::Listening(false) => {
                    if sent {
                        taken = Some(Instant::now());
                    }
                    listens = false;
                    sent = false;
                }
            }
        }
        if listens && !sent {
            if let Some(line) = held.pop_front() {
                // The task's reader of the heard topic, matched (the
                // message is volatile: a reader not yet matched misses it).
                heard.wait_matched(&link, discovery, stop);
                heard.send(
                    StdString {
                        data: line.trim().to_owned(),
                    },
                    Some(answer),
                )?;
                sent = true;
                show(Shown::Sent(line.trim().to_owned()));
            }
        }
        // Every line out and heard, or every line out and no task runs (its
        // listening writer is gone) for a moment: what it said last may come
        // after discovery tells. (A task's end may go unannounced: then
        // discovery tells only when its lease ends, a minute later.)
        if ended && held.is_empty() {
            if link
                .remote_writers(&t.listening, "std_msgs::msg::dds_::Bool_")
                .0
                == 0
            {
                let since = *done.get_or_insert_with(Instant::now);
                if since.elapsed() >= LINGER {
                    return Ok(());
                }
            } else {
                done = None;
            }
            if !sent && taken.is_some_and(|at| at.elapsed() >= LINGER * 2) {
                return Ok(());
            }
        }
        std::thread::sleep(POLL);
    }
}

/// A message of the task.
enum Input {
    Run(StdString),
    Say(StdString),
    Listening(bool),
}

/// Takes what `sub` has, with the publisher's timestamps (a malformed
/// message is dropped).
fn take<M: 'static + serde::de::DeserializeOwned>(
    sub: &Subscription<M>,
    rank: u8,
    into: &mut Vec<(Option<ros2_client::ROSTime>, u8, Input)>,
    make: impl Fn(M) -> Input,
) {
    loop {
        match sub.take() {
            Ok(Some((m, info))) => into.push((info.source_timestamp(), rank, make(m))),
            Ok(None) => break,
            Err(_) => continue,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_as_printed() {
        let mut i = Interface::load(None, None).unwrap();
        i.robot_name = "Golem".into();
        i.user_name = "Luis".into();
        assert_eq!(Shown::Said("Hi.".into()).text(&i), "Golem: Hi.");
        assert_eq!(Shown::Listens.text(&i), "  (Golem listens)");
        assert_eq!(Shown::Sent("malz".into()).text(&i), "Luis: malz");
        assert_eq!(
            Shown::Held("x".into()).text(&i),
            "  (held until Golem listens)"
        );
    }
}
