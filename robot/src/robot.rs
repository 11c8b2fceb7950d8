//! The simulated robot (feature `sim`): a [`sitlog_sim::Sim`] behind the
//! runtime's [`Perception`] and [`Actions`] traits. This is the only place
//! where SitLog terms meet the simulator; the simulator knows nothing of
//! them.
//!
//! Perceptual interpreters, by situation type:
//! - `speech` (also `listening(_)`, `keyboard`, `nkeyboard`): the user's
//!   next utterance, `said(Text)` with Text an atom of what the robot heard
//!   (garbled when the world makes it mishear), or `nobody` when the user is
//!   in another room;
//! - `vision`: what the camera sees on the shelf in front, `objects([O..])`
//!   (left to right; `[]` with no shelf in front);
//! - `hands`: what the hands hold, `hands(Left, Right)`, each `free` or the
//!   object;
//! - `presence(Seconds)` (or `presence`, 0 s): waits at most Seconds of
//!   simulated time for the user to be at the robot's place: `user` or
//!   `nobody`.
//!
//! Basic actions (those of `basic_actions.pl` the robot has; any other
//! action does nothing, as in the original): `say(Text)` (an atom, or a
//! list of words said as one sentence: spaces between words, none before
//! punctuation, `_` said as a space, a capital first letter);
//! `navigate(Place, Status)` (Status: `ok`, `blocked(From, To)`,
//! `no_route`, `unknown_place`); `grasp(Object, Hand, Status)` (`ok`,
//! `not_in_view`, `hand_full`, `grasp_failed`, `unknown_object`);
//! `place(Hand, Status)` (on the shelf in front: `ok`; where there is no
//! shelf the object falls: `on_floor`; `empty_hand`);
//! `hand_over(Hand, Status)` (`ok`, `no_user`, `empty_hand`);
//! `wait(Seconds)`; `screen(Text)`. A Status argument is unified with the
//! result: a variable is bound, a different value is an error.
//!
//! Every event of the world goes to the console as it happens: what the
//! robot says and hears as turns of the conversation, the rest as
//! narration lines.

use crate::assets::TextFile;
use crate::console::SharedConsole;
use crate::shop_functions::{self, SimAccess};
use sitlog_runtime::machine::{Actions, Perceived, Perception};
use sitlog_runtime::{Atom, Store, Term, Value};
use sitlog_sim::{EventKind, Hand, Heard, Placed, Sim, World};
use std::sync::{Arc, Mutex};

struct Inner {
    sim: Sim,
    console: SharedConsole,
    /// Events of the world already printed.
    printed: usize,
    /// Utterances heard so far (for the message at the end of them).
    heard: usize,
}

impl Inner {
    /// Prints the events since the last call.
    fn flush(&mut self) {
        let events = self.sim.events();
        let Ok(mut console) = self.console.lock() else {
            return;
        };
        for event in &events[self.printed.min(events.len())..] {
            match &event.kind {
                EventKind::Said { text } => console.turn(&event.robot, text),
                EventKind::Heard { text } => console.turn(&event.user, text),
                EventKind::Misheard { text, .. } => {
                    console.turn(&event.user, text);
                    console.narrate(&event.to_string());
                }
                _ => console.narrate(&event.to_string()),
            }
        }
        self.printed = events.len();
    }
}

/// The simulated robot and user of one run.
pub struct SimRobot {
    inner: Arc<Mutex<Inner>>,
}

/// The robot's senses ([`Perception`]).
pub struct Senses {
    inner: Arc<Mutex<Inner>>,
}

/// The robot's effectors ([`Actions`]).
pub struct Effectors {
    inner: Arc<Mutex<Inner>>,
}

impl SimRobot {
    /// The robot in the world of the world file `file`, with `seed`
    /// (default: the world file's `seed`, else 0). `Err` holds every error
    /// of the world file, one per line, `FILE:LINE:COL: error: ...`.
    pub fn from_file(
        file: &TextFile,
        seed: Option<u64>,
        console: SharedConsole,
    ) -> Result<SimRobot, String> {
        let world = parse_world(file)?;
        Ok(SimRobot::new(&world, seed, console))
    }

    /// The robot in `world`.
    pub fn new(world: &World, seed: Option<u64>, console: SharedConsole) -> SimRobot {
        let seed = seed.or(world.seed()).unwrap_or(0);
        let mut inner = Inner {
            sim: Sim::new(world, seed),
            console,
            printed: 0,
            heard: 0,
        };
        inner.flush();
        SimRobot {
            inner: Arc::new(Mutex::new(inner)),
        }
    }

    /// Registers the inference cycle's user functions (`shop_diagnose`,
    /// `shop_decide`, `shop_shelves`), which read the robot's map.
    pub fn register_inference(&self, functions: &mut sitlog_runtime::Functions, seed: Option<u64>) {
        let seed = match self.inner.lock() {
            Ok(i) => seed.or(i.sim.world().seed()).unwrap_or(0),
            Err(_) => return,
        };
        shop_functions::register(functions, Shared(self.inner.clone()), seed);
    }

    /// A look at the world's state (the debugger's `world`).
    pub fn probe(&self) -> Probe {
        Probe {
            inner: self.inner.clone(),
        }
    }

    /// The two views the machine takes: senses and effectors.
    pub fn split(self) -> (Senses, Effectors) {
        (
            Senses {
                inner: self.inner.clone(),
            },
            Effectors { inner: self.inner },
        )
    }
}

/// A look at the simulated world's state, shared with the running robot.
#[derive(Clone)]
pub struct Probe {
    inner: Arc<Mutex<Inner>>,
}

impl Probe {
    /// Time, places, hands and the routes found blocked, one a line.
    pub fn describe(&self) -> String {
        let Ok(inner) = lock(&self.inner) else {
            return "the simulated world is unusable after an earlier panic\n".to_owned();
        };
        let sim = &inner.sim;
        let place = |p: &str| match sim.room_of(p) {
            Some(room) => format!("{p} (in {room})"),
            None => p.to_owned(),
        };
        let hand = |h: Hand| sim.holding(h).unwrap_or("free").to_owned();
        let mut out = format!("time: {:.1} s\n", sim.now());
        out.push_str(&format!("robot: at {}\n", place(sim.robot_at())));
        if let Some(shelf) = sim.shelf_at(sim.robot_at()) {
            out.push_str(&format!("in front of: {shelf}\n"));
        }
        out.push_str(&format!(
            "hands: left {}, right {}\n",
            hand(Hand::Left),
            hand(Hand::Right)
        ));
        out.push_str(&format!("user: at {}\n", place(sim.user_at())));
        let blocked = sim.known_blocked();
        if !blocked.is_empty() {
            let routes: Vec<String> = blocked.iter().map(|(a, b)| format!("{a}-{b}")).collect();
            out.push_str(&format!("known blocked: {}\n", routes.join(", ")));
        }
        out
    }
}

/// The robot's state as the shop functions read it.
#[derive(Clone)]
struct Shared(Arc<Mutex<Inner>>);

impl SimAccess for Shared {
    fn with_sim<R>(&self, f: impl FnOnce(&Sim) -> R) -> Result<R, String> {
        let inner = self
            .0
            .lock()
            .map_err(|_| "the simulated world is unusable".to_owned())?;
        Ok(f(&inner.sim))
    }
}

fn lock(inner: &Arc<Mutex<Inner>>) -> Result<std::sync::MutexGuard<'_, Inner>, String> {
    inner
        .lock()
        .map_err(|_| "the simulated world is unusable after an earlier panic".to_owned())
}

fn atom(store: &mut Store, name: &str) -> Term {
    let _ = store;
    Term::atom(Atom::intern(name))
}

fn list(store: &mut Store, items: &[Term]) -> Term {
    store.list(items)
}

impl Perception for Senses {
    fn perceive(
        &mut self,
        store: &mut Store,
        situation_type: Term,
        _expectations: &[Term],
    ) -> Result<Perceived, String> {
        let mut inner = lock(&self.inner)?;
        let (name, arity) = store
            .functor(situation_type)
            .ok_or_else(|| "a situation type must be an atom or a compound".to_owned())?;
        let input = match name.as_str() {
            "speech" | "listening" | "keyboard" | "nkeyboard" => match inner.sim.hear() {
                Heard::Said(text) | Heard::Misheard(text) => {
                    inner.heard += 1;
                    let t = Term::atom(Atom::intern(&text));
                    store.compound(Atom::intern("said"), &[t])
                }
                Heard::Nobody => atom(store, "nobody"),
                Heard::NothingMore => {
                    inner.flush();
                    return Err(format!(
                        "the user has nothing more to say: all {} utterances of the world's `user.says` have been heard",
                        inner.heard
                    ));
                }
            },
            "vision" => {
                let seen = inner.sim.see();
                let items: Vec<Term> = seen
                    .objects
                    .iter()
                    .map(|o| Term::atom(Atom::intern(o)))
                    .collect();
                let l = list(store, &items);
                store.compound(Atom::intern("objects"), &[l])
            }
            "hands" => {
                let hand = |h: Hand| match inner.sim.holding(h) {
                    Some(o) => Term::atom(Atom::intern(o)),
                    None => Term::atom(Atom::intern("free")),
                };
                let (l, r) = (hand(Hand::Left), hand(Hand::Right));
                store.compound(Atom::intern("hands"), &[l, r])
            }
            "presence" => {
                let seconds = if arity == 0 {
                    0.0
                } else {
                    number(store, store.args(situation_type)[0]).ok_or_else(|| {
                        format!(
                            "`{}`: the time to wait must be a number of seconds",
                            store.writeq(situation_type)
                        )
                    })?
                };
                if !(seconds.is_finite() && seconds >= 0.0) {
                    return Err(format!(
                        "`{}`: the time to wait must be a number of seconds, at least 0",
                        store.writeq(situation_type)
                    ));
                }
                if inner.sim.wait_for_user(seconds) {
                    atom(store, "user")
                } else {
                    atom(store, "nobody")
                }
            }
            other => {
                return Err(format!(
                    "the simulated robot has no perceptual interpreter for situations of type `{other}` (it has speech, vision, hands and presence)"
                ))
            }
        };
        inner.flush();
        Ok(Perceived::Input(input))
    }

    /// The robot's senses are not told where the program waits.
    fn uses_waiting_at(&self) -> bool {
        false
    }
}

fn number(store: &Store, t: Term) -> Option<f64> {
    match store.value(t) {
        Value::Int(i) => Some(i as f64),
        Value::Float(f) => Some(f),
        _ => None,
    }
}

/// The name an argument gives (an atom), or an error naming the action.
fn name_arg(store: &Store, action: Term, i: usize, what: &str) -> Result<String, String> {
    let a = store.args(action)[i];
    store
        .atom_of(a)
        .map(|n| n.as_str().to_owned())
        .ok_or_else(|| {
            format!(
                "`{}`: the {what} must be an atom, not `{}`",
                store.writeq(action),
                store.writeq(a)
            )
        })
}

fn hand_arg(store: &Store, action: Term, i: usize) -> Result<Hand, String> {
    let name = name_arg(store, action, i, "hand")?;
    name.parse::<Hand>()
        .map_err(|e| format!("`{}`: {e}", store.writeq(action)))
}

/// Unifies the status argument `i` of `action` with `status`.
fn report(store: &mut Store, action: Term, i: usize, status: Term) -> Result<(), String> {
    let arg = store.args(action)[i];
    if store.unify(arg, status) {
        Ok(())
    } else {
        Err(format!(
            "`{}`: the robot's answer `{}` does not match",
            store.writeq(action),
            store.writeq(status)
        ))
    }
}

/// What `say(Text)`, `screen(Text)` and `message(To, Text)` say: what
/// test mode shows, as the original says the same text in its test mode and
/// on its robot (issue 40): a list is one sentence made by the original's
/// rule ([`sitlog_runtime::builtins::sentence`]: words separated by a
/// space, a final `.` from three words on), anything else is written as it is.
pub fn sentence(store: &Store, text: Term) -> String {
    sitlog_runtime::sentence::message(store, text)
}

impl Actions for Effectors {
    fn perform(&mut self, store: &mut Store, action: Term) -> Result<(), String> {
        let mut inner = lock(&self.inner)?;
        let Some((name, arity)) = store.functor(action) else {
            return Ok(());
        };
        let action = store.deref(action);
        match (name.as_str(), arity) {
            ("say", 1) => {
                let text = sentence(store, store.args(action)[0]);
                inner.sim.say(&text);
            }
            ("screen", 1) => {
                let text = sentence(store, store.args(action)[0]);
                let robot = inner.sim.world().robot_name().to_owned();
                if let Ok(mut c) = inner.console.lock() {
                    c.narrate(&format!("{robot} shows on its screen: {text}"));
                }
            }
            // A text message to someone away (the shop's manager): a
            // line of the transcript.
            ("message", 2) => {
                let to = sentence(store, store.args(action)[0]);
                let text = sentence(store, store.args(action)[1]);
                let robot = inner.sim.world().robot_name().to_owned();
                if let Ok(mut c) = inner.console.lock() {
                    c.narrate(&format!("{robot} texts {}: {text}", lower_first(&to)));
                }
            }
            ("navigate", 2) => {
                let to = name_arg(store, action, 0, "place")?;
                let status = match inner.sim.navigate(&to) {
                    Ok(_) => atom(store, "ok"),
                    Err(sitlog_sim::NavError::Blocked { from, to, .. }) => {
                        let f = Term::atom(Atom::intern(&from));
                        let t = Term::atom(Atom::intern(&to));
                        store.compound(Atom::intern("blocked"), &[f, t])
                    }
                    Err(e) => atom(store, e.code()),
                };
                inner.flush();
                report(store, action, 1, status)?;
            }
            ("grasp", 3) => {
                let object = name_arg(store, action, 0, "object")?;
                let hand = hand_arg(store, action, 1)?;
                let status = match inner.sim.grasp(&object, hand) {
                    Ok(()) => "ok",
                    Err(e) => e.code(),
                };
                inner.flush();
                let status = atom(store, status);
                report(store, action, 2, status)?;
            }
            ("place", 2) => {
                let hand = hand_arg(store, action, 0)?;
                let status = match inner.sim.place(hand) {
                    Ok(Placed::OnShelf(_)) => "ok",
                    Ok(Placed::Floor { .. }) => "on_floor",
                    Err(e) => e.code(),
                };
                inner.flush();
                let status = atom(store, status);
                report(store, action, 1, status)?;
            }
            ("hand_over", 2) => {
                let hand = hand_arg(store, action, 0)?;
                let status = match inner.sim.hand_over(hand) {
                    Ok(_) => "ok",
                    Err(e) => e.code(),
                };
                inner.flush();
                let status = atom(store, status);
                report(store, action, 1, status)?;
            }
            ("wait", 1) => {
                let seconds = number(store, store.args(action)[0])
                    .filter(|s| s.is_finite() && *s >= 0.0)
                    .ok_or_else(|| {
                        format!(
                            "`{}`: the time to wait must be a number of seconds, at least 0",
                            store.writeq(action)
                        )
                    })?;
                inner.sim.wait(seconds);
            }
            // Any other action does nothing, as in the original.
            _ => {}
        }
        inner.flush();
        Ok(())
    }
}

/// `The manager` → `the manager` (a name said inside a sentence).
fn lower_first(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_lowercase().chain(c).collect(),
        None => String::new(),
    }
}

/// A world file parsed, or its errors as one message (a line each, with
/// their positions).
pub(crate) fn parse_world(file: &TextFile) -> Result<World, String> {
    World::parse(&file.name, &file.text).map_err(|errors| {
        errors
            .iter()
            .map(|e| e.to_string())
            .collect::<Vec<_>>()
            .join("\n")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sentences() {
        let mut store = Store::new();
        let t = store.parse("['I will get', the, malz]").unwrap().0;
        assert_eq!(sentence(&store, t), "I will get the malz.");
        let t = store.parse("['Hi,', 'Luis']").unwrap().0;
        assert_eq!(sentence(&store, t), "Hi, Luis");
        let t = store
            .parse("[here, is, [the, living_room], '?']")
            .unwrap()
            .0;
        assert_eq!(sentence(&store, t), "here is [the,living_room] ?.");
        let t = store.parse("'Goodbye.'").unwrap().0;
        assert_eq!(sentence(&store, t), "Goodbye.");
        let t = store.parse("[count, 3, f(x)]").unwrap().0;
        assert_eq!(sentence(&store, t), "count 3 f(x).");
    }

    /// The simulated (and ROS 2) robot says what test mode shows, the
    /// original's text in both its modes (issue 40): the same `say([...])`
    /// once printed `Hello Bob, welcome! I am Golem.` on the simulator and
    /// `Hello Bob , welcome! I am Golem..` in test mode.
    #[test]
    fn the_robot_says_what_test_mode_shows() {
        use sitlog_runtime::machine::Actions;
        for text in [
            "['Hello', 'Bob', ', welcome! I am Golem.']",
            "['I will get', the, malz]",
            "['Hi,', 'Luis']",
            "[a, pause, b, c]",
            "[one]",
            "[the, [malz, and, coke], please]",
            "'Goodbye.'",
            "hello_world",
        ] {
            let mut store = Store::new();
            let t = store.parse(&format!("say({text})")).unwrap().0;
            let mut shown = Vec::new();
            sitlog_runtime::testmode::TextActions::new(&mut shown, Vec::new())
                .perform(&mut store, t)
                .unwrap();
            let said = sentence(&store, store.args(t)[0]);
            assert_eq!(
                String::from_utf8(shown).unwrap(),
                format!("Golem says: {said}\n")
            );
        }
        let mut store = Store::new();
        let t = store
            .parse("['Hello', 'Bob', ', welcome! I am Golem.']")
            .unwrap()
            .0;
        assert_eq!(sentence(&store, t), "Hello Bob , welcome! I am Golem..");
    }

    /// [`shop_functions::FUNCTIONS`] lists exactly what a robot on a world
    /// registers.
    #[test]
    fn the_shop_functions_list_is_what_is_registered() {
        use crate::console::Console;
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../dms/apps/supermarket/world.toml"
        );
        let world = sitlog_sim::World::load(std::path::Path::new(path)).expect("world");
        let robot = SimRobot::new(&world, None, Console::sink().shared());
        let mut functions = sitlog_runtime::Functions::new();
        robot.register_inference(&mut functions, None);
        let mut got: Vec<(String, usize)> = functions
            .names()
            .map(|(n, a)| (n.as_str().to_owned(), a))
            .collect();
        got.sort();
        let mut want: Vec<(String, usize)> = shop_functions::FUNCTIONS
            .iter()
            .map(|&(n, a)| (n.to_owned(), a))
            .collect();
        want.sort();
        assert_eq!(got, want);
    }
}
