//! A robot of your own under a SitLog task: the worked example of
//! `docs/guide/robot.md`.
//!
//! `Senses` implements the runtime's `Perception`: it takes what the robot
//! perceives from a channel, as text (on a real robot, the speech and vision
//! nodes would send into it). `Effectors` implements `Actions`: it prints each
//! action and binds the status argument of `navigate/2`. The task
//! (`examples/channel_robot/main.dm`) is compiled into this program by
//! `include_dm!`, and `describe/1` is a user function written in Rust.
//!
//! ```sh
//! cargo run -p sitlog-robot --example channel_robot
//! ```

use sitlog_runtime::machine::{Actions, Options, Perceived, Perception};
use sitlog_runtime::{report, Atom, Functions, Store, Term};
use std::sync::mpsc::{channel, Receiver};

mod task {
    sitlog_macros::include_dm!("examples/channel_robot");
}

/// What the robot perceives, one term (as text) per perception.
struct Senses {
    inbox: Receiver<String>,
}

impl Perception for Senses {
    fn perceive(
        &mut self,
        store: &mut Store,
        situation_type: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        let expected: Vec<String> = expectations.iter().map(|&e| store.writeq(e)).collect();
        println!(
            "robot: waiting in a `{}` situation for one of: {}",
            store.writeq(situation_type),
            expected.join(" | ")
        );
        // A closed channel: nothing more will be perceived.
        let Ok(text) = self.inbox.recv() else {
            return Ok(Perceived::EndOfInput);
        };
        let (term, _) = store
            .parse(&text)
            .map_err(|e| format!("cannot read the perception `{text}`: {}", e.message))?;
        println!("robot: perceived {}", store.writeq(term));
        Ok(Perceived::Input(term))
    }
}

/// What the robot does.
struct Effectors;

impl Actions for Effectors {
    fn perform(&mut self, store: &mut Store, action: Term) -> Result<(), String> {
        let action = store.deref(action);
        match store.functor(action) {
            Some((name, 2)) if name.as_str() == "navigate" => {
                let place = store.writeq(store.args(action)[0]);
                println!("robot: driving to {place}");
                // The status goes back to the task by unification: the
                // arc's next situation, `arrived(Status)`, sees it.
                let status = store.args(action)[1];
                let ok = Term::atom(Atom::intern("ok"));
                if !store.unify(status, ok) {
                    return Err(format!(
                        "navigate: status already `{}`",
                        store.writeq(status)
                    ));
                }
            }
            Some((name, 1)) if name.as_str() == "say" => {
                println!("robot: says \"{}\"", store.write(store.args(action)[0]));
            }
            // Anything else (numbers from `inc`, actions this robot lacks).
            _ => println!("robot: ignores {}", store.writeq(action)),
        }
        Ok(())
    }
}

/// describe(Objects): a sentence naming what was seen.
fn describe(functions: &mut Functions) {
    functions.register("describe", 1, |call, args| {
        let seen = call
            .store
            .list_to_vec(args[0])
            .ok_or_else(|| "describe/1 expects a list of objects".to_owned())?;
        let names: Vec<String> = seen.iter().map(|&o| call.store.write(o)).collect();
        let text = match names.len() {
            0 => "I see nothing here.".to_owned(),
            n => format!("I see {n} objects: {}.", names.join(", ")),
        };
        Ok(Term::atom(Atom::intern(&text)))
    });
}

fn main() -> std::process::ExitCode {
    let (tx, rx) = channel();
    // Here a thread plays the camera; on a robot, your perception nodes.
    std::thread::spawn(move || {
        tx.send("objects([cup, plate]).".to_owned()).ok();
    });
    let mut functions = Functions::standard();
    describe(&mut functions);
    let result = task::run(
        "main",
        None,
        Options::default(),
        functions,
        &mut Senses { inbox: rx },
        &mut Effectors,
        None,
    );
    let (outcome, mut store) = match result {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return std::process::ExitCode::from(2);
        }
    };
    print!("{}", report::outcome_text(&mut store, &outcome));
    match outcome.result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(_) => std::process::ExitCode::FAILURE,
    }
}
