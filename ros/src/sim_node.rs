//! The robot's side: a simulated world ([`sitlog_sim::Sim`], the simulator
//! of `sitlogc run`) served on the interface of [`crate::config`], so that
//! a task in another process (`--robot ros2`) runs on it as on the
//! simulated robot in-process ([`serve`]).
//!
//! The node prints the world's transcript (turns and narration) as the
//! simulated robot does in-process, and serves until it is stopped, run
//! after run: each task run announces itself on the run topic (its id),
//! and a new id starts a new episode on a fresh world (the world file's,
//! with the same seed), so every run sees what a run in-process sees. When
//! the world's user has nothing more to say, the node tells the task on the
//! abort topic (the task stops with that run-time error, as in-process)
//! and waits for the next run.
//! Messages on the task's topics are taken in the order the task published
//! them (by source timestamp: the task waits until each is acknowledged
//! before it publishes the next or sends a goal), then goals, results and
//! service calls; the simulator answers each at once. Goals and service
//! calls are received before the topics are read, so a message acknowledged
//! before a request was sent is taken before that request is answered: a
//! task ends its run with such a round trip (`crate::robot`), since the
//! messages a reader has not taken are lost when their writer leaves.
//!
//! With `speech_external` the user's words are not the world file's: they
//! are what some other node publishes on the heard topic while the task
//! listens (the simulator counts them for the user's moves).

use crate::config::Interface;
use crate::link::{Link, Writer};
use crate::msgs::*;
use ros2_client::action::{GoalId, GoalStatusEnum};
use ros2_client::dds::rustdds::mio1;
use ros2_client::{ActionServer, Server, Subscription};
use sitlog_robot::console::Console;
use sitlog_sim::{EventKind, Hand, Heard, NavError, Placed, Sim, World};
use std::collections::BTreeMap;
use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// What [`serve`] needs besides the world.
pub struct Options {
    /// The seed (default: the world file's, else 0).
    pub seed: Option<u64>,
    /// The user's words come from the heard topic, not the world file.
    pub speech_external: bool,
    /// Narration lines as well as the conversation.
    pub narrate: bool,
}

type Status = (GoalStatusEnum, bool);

/// One action's server and the results of its goals.
struct Served<G, R, F>
where
    G: ros2_client::Message + Clone,
    R: ros2_client::Message + Clone,
    F: ros2_client::Message,
{
    server: ActionServer<G, R, F>,
    results: BTreeMap<GoalId, (GoalStatusEnum, R)>,
}

impl<G, R, F> Served<G, R, F>
where
    G: ros2_client::Message + Clone + 'static,
    R: ros2_client::Message + Clone + Default + 'static,
    F: ros2_client::Message + 'static,
{
    fn new(server: ActionServer<G, R, F>) -> Self {
        Served {
            server,
            results: BTreeMap::new(),
        }
    }

    fn register(&mut self, registry: &mio1::Registry, token: usize) -> std::io::Result<()> {
        use mio1::event::Source;
        self.server.goal_server().register(
            registry,
            mio1::Token(token),
            mio1::Interest::READABLE,
        )?;
        self.server.result_server().register(
            registry,
            mio1::Token(token + 1),
            mio1::Interest::READABLE,
        )
    }

    /// Takes and accepts every goal that has come.
    fn receive(&mut self) -> Vec<(GoalId, G)> {
        let mut goals = Vec::new();
        loop {
            let (req, request) = match self.server.receive_goal() {
                Ok(Some(r)) => r,
                Ok(None) => break,
                Err(_) => continue,
            };
            let _ = self.server.send_goal_response(
                req,
                ros2_client::action::SendGoalResponse {
                    accepted: true,
                    stamp: ros2_client::builtin_interfaces::Time::now(),
                },
            );
            goals.push((request.goal_id, request.goal));
        }
        goals
    }

    /// Carries out `goals` (from [`Served::receive`]) at once with `run`,
    /// then answers the result requests.
    fn goals(&mut self, goals: Vec<(GoalId, G)>, mut run: impl FnMut(G) -> (Status, R)) {
        for (id, goal) in goals {
            let ((status, _), result) = run(goal);
            self.results.insert(id, (status, result));
        }
        loop {
            let (req, request) = match self.server.receive_result_request() {
                Ok(Some(r)) => r,
                Ok(None) => break,
                Err(_) => continue,
            };
            let (status, result) = self
                .results
                .remove(&request.goal_id)
                .unwrap_or((GoalStatusEnum::Unknown, R::default()));
            let _ = self.server.send_result(
                req,
                ros2_client::action::GetResultResponse { status, result },
            );
        }
    }
}

fn ok() -> Status {
    (GoalStatusEnum::Succeeded, true)
}

fn aborted() -> Status {
    (GoalStatusEnum::Aborted, false)
}

/// A name as a status term's argument: as it is when it is an atom
/// without quotes, else quoted.
fn quoted(name: &str) -> String {
    let plain = name.starts_with(|c: char| c.is_ascii_lowercase())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if plain {
        name.to_owned()
    } else {
        format!("'{}'", name.replace('\\', "\\\\").replace('\'', "\\'"))
    }
}

/// The node's simulated world and where its transcript goes.
struct World2 {
    sim: Sim,
    console: Console,
    printed: usize,
    heard: usize,
}

impl World2 {
    /// A new episode: the world as the world file gives it.
    fn fresh(&mut self, world: &World, seed: u64) {
        self.sim = Sim::new(world, seed);
        self.printed = 0;
        self.heard = 0;
    }

    /// Prints the events since the last call (as the simulated robot does).
    fn flush(&mut self) {
        let events = self.sim.events();
        for event in &events[self.printed.min(events.len())..] {
            match &event.kind {
                EventKind::Said { text } => self.console.turn(&event.robot, text),
                EventKind::Heard { text } => self.console.turn(&event.user, text),
                EventKind::Misheard { text, .. } => {
                    self.console.turn(&event.user, text);
                    self.console.narrate(&event.to_string());
                }
                _ => self.console.narrate(&event.to_string()),
            }
        }
        self.printed = events.len();
    }
}

/// What the node receives on a topic, with the task's timestamp.
enum Input {
    Say(String),
    Screen(String),
    Message(TextMessage),
    Listening(bool),
    Heard(String),
    Run(String),
}

/// Serves `world` on `iface` until `stop` is set, a fresh episode for
/// each task run; prints the transcript on `out`, and on `note` a line
/// when a run starts or is told to stop. `Err`: the node could not start.
pub fn serve(
    world: &World,
    iface: &Interface,
    options: &Options,
    out: Box<dyn Write + Send>,
    note: &mut dyn FnMut(&str),
    stop: &AtomicBool,
) -> Result<(), String> {
    let seed = options.seed.or(world.seed()).unwrap_or(0);
    let mut w = World2 {
        sim: Sim::new(world, seed),
        console: Console::new(out, false, options.narrate),
        printed: 0,
        heard: 0,
    };
    w.flush();
    let mut link = Link::open("sim")?;
    let t = &iface.topics;
    let a = &iface.actions;
    let s = &iface.services;
    // Keep every message until taken (a `false` then `true` on the listening
    // topic are two listens, even when both arrive before the node looks).
    let deep = |q: &crate::config::Qos| crate::config::Qos {
        depth: q.depth.max(1000),
        ..q.clone()
    };
    let q = &iface.qos;
    let mut say: Subscription<StdString> =
        link.subscription(&t.say, ("std_msgs", "String"), &deep(&q.say))?;
    let mut screen: Subscription<StdString> =
        link.subscription(&t.screen, ("std_msgs", "String"), &deep(&q.screen))?;
    let mut message: Subscription<TextMessage> = link.subscription(
        &t.message,
        ("sitlog_msgs", "TextMessage"),
        &deep(&q.message),
    )?;
    let mut listening: Subscription<StdBool> =
        link.subscription(&t.listening, ("std_msgs", "Bool"), &deep(&q.listening))?;
    let mut heard_in: Option<Subscription<StdString>> = if options.speech_external {
        Some(link.subscription(&t.heard, ("std_msgs", "String"), &deep(&q.heard))?)
    } else {
        None
    };
    let mut run: Subscription<StdString> =
        link.subscription(&t.run, ("std_msgs", "String"), &deep(&q.run))?;
    let abort: Writer<StdString> = link.writer(&t.abort, ("std_msgs", "String"), &q.abort)?;
    let heard_out: Option<Writer<StdString>> = if options.speech_external {
        None
    } else {
        Some(link.writer(&t.heard, ("std_msgs", "String"), &q.heard)?)
    };
    let mut navigate = Served::new(
        link.action_server::<NavigateToPoseGoal, NavigateToPoseResult, NavigateToPoseFeedback>(
            &a.navigate,
            ("nav2_msgs", "NavigateToPose"),
        )?,
    );
    let mut grasp = Served::new(
        link.action_server::<GraspGoal, StatusResult, Empty>(&a.grasp, ("sitlog_msgs", "Grasp"))?,
    );
    let mut place = Served::new(
        link.action_server::<HandGoal, StatusResult, Empty>(&a.place, ("sitlog_msgs", "Place"))?,
    );
    let mut hand_over = Served::new(link.action_server::<HandGoal, StatusResult, Empty>(
        &a.hand_over,
        ("sitlog_msgs", "HandOver"),
    )?);
    let mut wait_for_person = Served::new(
        link.action_server::<WaitForPersonGoal, WaitForPersonResult, Empty>(
            &a.wait_for_person,
            ("sitlog_msgs", "WaitForPerson"),
        )?,
    );
    let mut detect: Server<DetectObjectsRequest, DetectObjectsResponse> =
        link.server(&s.detect_objects, ("sitlog_msgs", "DetectObjects"))?;
    let mut hands: Server<Empty, GetHandsResponse> =
        link.server(&s.hands, ("sitlog_msgs", "GetHands"))?;

    let mut poll = mio1::Poll::new().map_err(|e| format!("error: poll: {e}"))?;
    {
        use mio1::event::Source;
        let r = poll.registry();
        let readable = mio1::Interest::READABLE;
        let reg = |res: std::io::Result<()>| res.map_err(|e| format!("error: poll: {e}"));
        reg(say.register(r, mio1::Token(1), readable))?;
        reg(screen.register(r, mio1::Token(2), readable))?;
        reg(message.register(r, mio1::Token(3), readable))?;
        reg(listening.register(r, mio1::Token(4), readable))?;
        if let Some(h) = heard_in.as_mut() {
            reg(h.register(r, mio1::Token(5), readable))?;
        }
        reg(run.register(r, mio1::Token(6), readable))?;
        reg(navigate.register(r, 10))?;
        reg(grasp.register(r, 12))?;
        reg(place.register(r, 14))?;
        reg(hand_over.register(r, 16))?;
        reg(wait_for_person.register(r, 18))?;
        reg(detect.register(r, mio1::Token(20), readable))?;
        reg(hands.register(r, mio1::Token(21), readable))?;
    }
    let robot = world.robot_name().to_owned();
    let mut events = mio1::Events::with_capacity(64);
    let mut is_listening = false;
    // The run being served (its id) and how many have started.
    let mut current: Option<String> = None;
    let mut runs = 0usize;
    let mut stopped: Option<std::time::Instant> = None;
    loop {
        // Stopped: a moment more through what comes (a task's last
        // message, acknowledged, is the robot's to print), then out.
        if stop.load(Ordering::SeqCst) && stopped.is_none() {
            stopped = Some(std::time::Instant::now());
        }
        let _ = poll.poll(&mut events, Some(Duration::from_millis(50)));
        // Requests first, then the topics: a message the task had
        // acknowledged before it sent a request is then taken before the
        // request is answered (the run's end waits on that, see
        // `crate::robot`), and said before a goal that came after it.
        let navigate_goals = navigate.receive();
        let grasp_goals = grasp.receive();
        let place_goals = place.receive();
        let hand_over_goals = hand_over.receive();
        let wait_goals = wait_for_person.receive();
        let mut detect_calls = Vec::new();
        while let Ok(Some((req, _))) = detect.receive_request() {
            detect_calls.push(req);
        }
        let mut hands_calls = Vec::new();
        while let Ok(Some((req, _))) = hands.receive_request() {
            hands_calls.push(req);
        }
        // The task's messages, in the order it published them.
        let mut inputs: Vec<(Option<ros2_client::ROSTime>, u8, Input)> = Vec::new();
        fn drain<M: 'static + serde::de::DeserializeOwned>(
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
        drain(&run, 0, &mut inputs, |m| Input::Run(m.data));
        drain(&say, 0, &mut inputs, |m| Input::Say(m.data));
        drain(&screen, 1, &mut inputs, |m| Input::Screen(m.data));
        drain(&message, 2, &mut inputs, Input::Message);
        drain(&listening, 3, &mut inputs, |m| Input::Listening(m.data));
        if let Some(h) = &heard_in {
            drain(h, 4, &mut inputs, |m| Input::Heard(m.data));
        }
        inputs.sort_by_key(|a| (a.0, a.1));
        for (_, _, input) in inputs {
            match input {
                Input::Run(id) if current.as_ref() == Some(&id) => {}
                Input::Run(id) => {
                    runs += 1;
                    if runs > 1 {
                        w.fresh(world, seed);
                        is_listening = false;
                    }
                    let fresh = if runs > 1 { ": a fresh world" } else { "" };
                    note(&format!("run {runs} ({id}){fresh}"));
                    current = Some(id);
                }
                Input::Say(text) => w.sim.say(&text),
                Input::Screen(text) => w
                    .console
                    .narrate(&format!("{robot} shows on its screen: {text}")),
                Input::Message(m) => {
                    let mut c = m.to.chars();
                    let to: String = match c.next() {
                        Some(f) => f.to_lowercase().chain(c).collect(),
                        None => String::new(),
                    };
                    w.console
                        .narrate(&format!("{robot} texts {to}: {}", m.text))
                }
                Input::Listening(false) => is_listening = false,
                Input::Listening(true) if is_listening => {}
                Input::Listening(true) => {
                    is_listening = true;
                    if let Some(out) = &heard_out {
                        let text = match w.sim.hear() {
                            Heard::Said(text) | Heard::Misheard(text) => {
                                w.heard += 1;
                                Some(text)
                            }
                            Heard::Nobody => Some(String::new()),
                            Heard::NothingMore => None,
                        };
                        w.flush();
                        match text {
                            Some(text) => {
                                let _ = out.send(StdString { data: text }, None);
                            }
                            // As in-process: a run-time error of the task.
                            None => {
                                let why = format!(
                                    "the user has nothing more to say: all {} utterances of the world's `user.says` have been heard",
                                    w.heard
                                );
                                note(&format!(
                                    "run {}: {why}: the task is told so on {}; waiting for the next run",
                                    runs.max(1),
                                    t.abort
                                ));
                                // (Volatile: to the task's reader, matched.)
                                let answer = Interface::secs(iface.timeouts.answer);
                                abort.wait_matched(&link, answer, stop);
                                let _ = abort.send(StdString { data: why }, Some(answer));
                            }
                        }
                    }
                }
                Input::Heard(text) => {
                    if is_listening && !text.trim().is_empty() {
                        w.sim.hear_from_outside(&text);
                        w.heard += 1;
                    } else if !text.trim().is_empty() {
                        // Not silent: the user's moves follow what is heard.
                        note(&format!(
                            "run {}: `{text}` arrived while the robot was not listening: not counted as heard",
                            runs.max(1)
                        ));
                    }
                }
            }
            w.flush();
        }
        // Goals, results and service calls.
        navigate.goals(navigate_goals, |goal| {
            let (x, y) = (goal.pose.pose.position.x, goal.pose.pose.position.y);
            let at = world.place_names().into_iter().find(|p| {
                world
                    .place_pose(p)
                    .is_some_and(|(_, px, py, _)| (px - x).abs() < 1e-3 && (py - y).abs() < 1e-3)
            });
            let failed = |msg: String| {
                (
                    aborted(),
                    NavigateToPoseResult {
                        error_code: NAV2_UNKNOWN,
                        error_msg: msg,
                    },
                )
            };
            let out = match at {
                None => failed("unknown_place".into()),
                Some(p) => match w.sim.navigate(p) {
                    Ok(_) => (ok(), NavigateToPoseResult::default()),
                    Err(NavError::Blocked { from, to, .. }) => {
                        failed(format!("blocked({},{})", quoted(&from), quoted(&to)))
                    }
                    Err(e) => failed(e.code().to_owned()),
                },
            };
            w.flush();
            out
        });
        let status_of = |r: Result<&'static str, &'static str>| match r {
            Ok(s) => (ok(), StatusResult { status: s.into() }),
            Err(s) => (aborted(), StatusResult { status: s.into() }),
        };
        grasp.goals(grasp_goals, |goal| {
            let r = match goal.hand.parse::<Hand>() {
                Err(_) => Err("unknown_hand"),
                Ok(h) => w
                    .sim
                    .grasp(&goal.object, h)
                    .map(|()| "ok")
                    .map_err(|e| e.code()),
            };
            w.flush();
            status_of(r)
        });
        place.goals(place_goals, |goal| {
            let r = match goal.hand.parse::<Hand>() {
                Err(_) => Err("unknown_hand"),
                Ok(h) => match w.sim.place(h) {
                    Ok(Placed::OnShelf(_)) => Ok("ok"),
                    Ok(Placed::Floor { .. }) => Err("on_floor"),
                    Err(e) => Err(e.code()),
                },
            };
            w.flush();
            status_of(r)
        });
        hand_over.goals(hand_over_goals, |goal| {
            let r = match goal.hand.parse::<Hand>() {
                Err(_) => Err("unknown_hand"),
                Ok(h) => w.sim.hand_over(h).map(|_| "ok").map_err(|e| e.code()),
            };
            w.flush();
            status_of(r)
        });
        wait_for_person.goals(wait_goals, |goal| {
            let present = w.sim.wait_for_user(goal.max_seconds);
            w.flush();
            (ok(), WaitForPersonResult { present })
        });
        for req in detect_calls {
            let seen = w.sim.see();
            w.flush();
            let detections = seen
                .objects
                .iter()
                .enumerate()
                .map(|(i, o)| Detection2D {
                    header: Header {
                        stamp: Time::now(),
                        frame_id: "camera".into(),
                    },
                    results: vec![ObjectHypothesisWithPose {
                        hypothesis: ObjectHypothesis {
                            class_id: o.clone(),
                            score: 1.0,
                        },
                        pose: PoseWithCovariance::default(),
                    }],
                    bbox: BoundingBox2D {
                        center: Pose2D {
                            position: Point2D {
                                x: 50.0 + 100.0 * i as f64,
                                y: 240.0,
                            },
                            theta: 0.0,
                        },
                        size_x: 80.0,
                        size_y: 160.0,
                    },
                    id: o.clone(),
                })
                .collect();
            let response = DetectObjectsResponse {
                detections: Detection2DArray {
                    header: Header {
                        stamp: Time::now(),
                        frame_id: "camera".into(),
                    },
                    detections,
                },
            };
            let _ = detect.send_response(req, response);
        }
        for req in hands_calls {
            let hand = |h: Hand| w.sim.holding(h).unwrap_or("").to_owned();
            let response = GetHandsResponse {
                left: hand(Hand::Left),
                right: hand(Hand::Right),
            };
            let _ = hands.send_response(req, response);
        }
        if stopped.is_some_and(|at| at.elapsed() >= Duration::from_millis(300)) {
            w.console.finish();
            return Ok(());
        }
    }
}
