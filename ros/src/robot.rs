//! The task's side ([`RosRobot`]): the runtime's [`Perception`] and
//! [`Actions`] over the interface of [`crate::config`], and the
//! [`hook`] that `--robot ros2` runs.
//!
//! - `say(Text)` is published on the say topic and waited on until every
//!   reader has it (so the robot hears it before the next action);
//!   `screen/1` and `message/2` likewise on theirs.
//! - A run announces itself once, at its start: its id on the run topic
//!   (a robot that serves episodes, the simulator, starts a fresh one).
//! - A speech situation publishes `true` on the listening topic, waits for
//!   one message on the heard topic (`said(Text)`; an empty one: `nobody`),
//!   then publishes `false`. What arrives while nothing listens is dropped.
//!   A message on the abort topic (the robot cannot go on with this run)
//!   ends the listening with a run-time error, its text.
//! - A run ends with one call of the hands service (if the robot serves
//!   one), answered once the robot has taken everything the run published
//!   (see `impl Drop for Inner`).
//! - `navigate/2` sends the place's pose to NavigateToPose; `grasp/3`,
//!   `place/2`, `hand_over/2` their sitlog_msgs actions; `vision` and
//!   `hands` call services; `presence(S)` the WaitForPerson action.
//! - An action's status: `ok` when it succeeded; when aborted, the term in
//!   its result (`blocked(From, To)`, `grasp_failed`, ...) or
//!   `aborted(Code, Message)`; `canceled`; `rejected(Topic)`;
//!   `unavailable(Topic)` when no server appeared within
//!   `timeouts.discovery`; `timed_out(Topic)`; `no_answer(Topic)` when the
//!   server did not answer within `timeouts.answer`.
//!
//! Invariant: every wait is bounded or watches the run's stop flag; the
//! robot counts as gone (the run stops at its next transition boundary,
//! exit status 4) exactly when a message or request it had matched is not
//! acknowledged or answered within `timeouts.answer`.

use crate::config::Interface;
use crate::link::{wait_for, Link, Waited, Writer};
use crate::msgs::*;
use crate::terms::{goal_pose, hand_arg, lower_first, name_arg, number, report, status_term};
use futures::future::Either;
use ros2_client::action::GoalStatusEnum;
use ros2_client::{ActionClient, Client, Subscription};
use sitlog_robot::console::SharedConsole;
use sitlog_robot::interrupt::Interrupt;
use sitlog_robot::robot::sentence;
use sitlog_robot::{RobotHook, RobotParts, RobotSetup, SimAccess};
use sitlog_runtime::machine::{Actions, Perceived, Perception};
use sitlog_runtime::{Atom, Store, Term};
use sitlog_sim::{Sim, World};
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// A run's id on the run topic: this process and the time it started.
fn run_id() -> String {
    let t = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap_or_default();
    format!(
        "pid {} at {}.{:09}",
        std::process::id(),
        t.as_secs(),
        t.subsec_nanos()
    )
}

/// The connection a `--robot ros2` run makes.
pub fn hook() -> RobotHook {
    Box::new(|setup: RobotSetup<'_>| {
        let world = match setup.world {
            Some(f) => Some(World::parse(&f.name, &f.text).map_err(|errors| {
                let lines: Vec<String> = errors.iter().map(|e| e.to_string()).collect();
                (2, lines.join("\n"))
            })?),
            None => None,
        };
        let file = setup
            .assets
            .ros2
            .as_ref()
            .map(|f| (f.name.as_str(), f.text.as_str()));
        let iface = Interface::load(file, world.as_ref()).map_err(|e| (2, e))?;
        let robot = RosRobot::connect(iface, setup.console, setup.stop)?;
        if let Some(w) = &world {
            let seed = setup.args.seed.or(w.seed()).unwrap_or(0);
            robot.believe(w, seed, setup.functions);
        }
        Ok(robot.split())
    })
}

type Nav = ActionClient<NavigateToPoseGoal, NavigateToPoseResult, NavigateToPoseFeedback>;

/// The run's end: before the task's participant leaves the domain, one
/// round trip to the robot's hands service (it changes nothing), if the
/// robot serves one. An acknowledgement says that a message is in the
/// robot's reader, not that the robot has taken it; when a writer's
/// participant leaves, RustDDS forgets what a reliable reader had from it
/// and had not yet taken (a simulator that lost the run's last `say` that
/// way, under load). The simulator takes every message on its topics
/// before it answers a request that came after them, so once the answer is
/// here the robot has everything this run published. Bounded by
/// `timeouts.answer`; skipped once the robot is gone.
impl Drop for Inner {
    fn drop(&mut self) {
        if self.stop.robot_gone() || !self.link.remote_server(&self.iface.services.hands) {
            return;
        }
        let answer = Some(Interface::secs(self.iface.timeouts.answer));
        let never = AtomicBool::new(false);
        if let Waited::Done(()) =
            wait_for(self.hands.wait_for_service(&self.link.node), answer, &never)
        {
            let _ = wait_for(
                self.hands.async_call_service(Empty::default()),
                answer,
                &never,
            );
        }
    }
}

struct Inner {
    link: Link,
    iface: Interface,
    console: SharedConsole,
    stop: Interrupt,
    say: Writer<StdString>,
    listening: Writer<StdBool>,
    screen: Writer<StdString>,
    message: Writer<TextMessage>,
    heard: Subscription<StdString>,
    abort: Subscription<StdString>,
    /// The run's announcement, kept for as long as the run.
    _run: Writer<StdString>,
    navigate: Nav,
    grasp: ActionClient<GraspGoal, StatusResult, Empty>,
    place: ActionClient<HandGoal, StatusResult, Empty>,
    hand_over: ActionClient<HandGoal, StatusResult, Empty>,
    wait_for_person: ActionClient<WaitForPersonGoal, WaitForPersonResult, Empty>,
    detect: Client<DetectObjectsRequest, DetectObjectsResponse>,
    hands: Client<Empty, GetHandsResponse>,
    /// What the robot believes of the world (the world file's map, its own
    /// place and hands as its actions reported them), for the world's
    /// functions; `None` without a world.
    belief: Option<Arc<Mutex<Sim>>>,
}

/// A robot over ROS 2.
pub struct RosRobot {
    inner: Arc<Mutex<Inner>>,
}

/// How an action or service call ended.
enum Call<R> {
    Succeeded(R),
    Aborted(R),
    Canceled,
    /// The status to report as it is (`rejected(T)`, `unavailable(T)`, ...).
    Failed(&'static str),
    Stopped,
}

impl RosRobot {
    /// Joins the domain, makes the interface's endpoints and waits (at most
    /// `timeouts.discovery`) for the robot: a reader of the say topic. `Err`:
    /// exit status and message (4: no robot; 2: another task drives it).
    pub fn connect(
        iface: Interface,
        console: SharedConsole,
        stop: Interrupt,
    ) -> Result<RosRobot, (u8, String)> {
        let fail = |e: String| (2u8, e);
        let mut link = Link::open("task").map_err(fail)?;
        let t = &iface.topics;
        let q = &iface.qos;
        let a = &iface.actions;
        let s = &iface.services;
        let say = link
            .writer(&t.say, ("std_msgs", "String"), &q.say)
            .map_err(fail)?;
        let listening = link
            .writer(&t.listening, ("std_msgs", "Bool"), &q.listening)
            .map_err(fail)?;
        let screen = link
            .writer(&t.screen, ("std_msgs", "String"), &q.screen)
            .map_err(fail)?;
        let message = link
            .writer(&t.message, ("sitlog_msgs", "TextMessage"), &q.message)
            .map_err(fail)?;
        let heard = link
            .subscription(&t.heard, ("std_msgs", "String"), &q.heard)
            .map_err(fail)?;
        let run = link
            .writer(&t.run, ("std_msgs", "String"), &q.run)
            .map_err(fail)?;
        let abort = link
            .subscription(&t.abort, ("std_msgs", "String"), &q.abort)
            .map_err(fail)?;
        let navigate = link
            .action_client(&a.navigate, ("nav2_msgs", "NavigateToPose"))
            .map_err(fail)?;
        let grasp = link
            .action_client(&a.grasp, ("sitlog_msgs", "Grasp"))
            .map_err(fail)?;
        let place = link
            .action_client(&a.place, ("sitlog_msgs", "Place"))
            .map_err(fail)?;
        let hand_over = link
            .action_client(&a.hand_over, ("sitlog_msgs", "HandOver"))
            .map_err(fail)?;
        let wait_for_person = link
            .action_client(&a.wait_for_person, ("sitlog_msgs", "WaitForPerson"))
            .map_err(fail)?;
        let detect = link
            .client(&s.detect_objects, ("sitlog_msgs", "DetectObjects"))
            .map_err(fail)?;
        let hands = link
            .client(&s.hands, ("sitlog_msgs", "GetHands"))
            .map_err(fail)?;
        // The robot: something that hears what the task says (reliably: a
        // console that only watches, `sitlogc user`, is no robot).
        let start = Instant::now();
        let limit = Interface::secs(iface.timeouts.discovery);
        while link.remote_reliable_readers(&t.say) == 0 {
            if start.elapsed() >= limit || stop.requested() {
                return Err((
                    sitlog_robot::interrupt::EXIT_ROBOT_GONE,
                    format!(
                        "error: no robot on ROS 2 domain {}: nothing subscribes to {} (waited {:.1} s); start one (`sitlogc sim APP --ros2`) or check ROS_DOMAIN_ID",
                        link.domain, t.say, iface.timeouts.discovery
                    ),
                ));
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        // One task per robot: another writer on the listening topic is
        // another task (give discovery a moment to tell).
        std::thread::sleep(Duration::from_millis(300));
        let (tasks, foreign) = link.remote_writers(&t.listening, "std_msgs::msg::dds_::Bool_");
        // A node publishing another type there is not a task: logged and
        // ignored (issue 38), also under -q.
        for type_name in foreign {
            sitlog_runtime::errln!(
                "note: a node publishes {type_name} on {} (not a task's std_msgs/Bool): ignored",
                t.listening
            );
        }
        if tasks > 0 {
            return Err((
                2,
                format!(
                    "error: another task already drives the robot on ROS 2 domain {} (it publishes on {}); one task per robot",
                    link.domain, t.listening
                ),
            ));
        }
        // The run starts: announced once the robot's reader of the run topic
        // (if it has one: a robot that serves episodes) is matched, and
        // acknowledged before anything else is sent.
        if link.remote_readers(&t.run) > 0 {
            run.wait_matched(&link, Interface::secs(iface.timeouts.discovery), &stop.flag);
        }
        let answer = iface.timeouts.answer;
        match run.send(StdString { data: run_id() }, Some(Interface::secs(answer))) {
            Ok(true) => {}
            Ok(false) => {
                return Err((
                    sitlog_robot::interrupt::EXIT_ROBOT_GONE,
                    format!(
                        "error: the robot did not acknowledge the start of the run on {} within {answer:.1} s",
                        t.run
                    ),
                ))
            }
            Err(e) => return Err((2, format!("error: ROS 2: {e}"))),
        }
        let inner = Inner {
            link,
            iface,
            console,
            stop,
            say,
            listening,
            screen,
            message,
            heard,
            abort,
            _run: run,
            navigate,
            grasp,
            place,
            hand_over,
            wait_for_person,
            detect,
            hands,
            belief: None,
        };
        Ok(RosRobot {
            inner: Arc::new(Mutex::new(inner)),
        })
    }

    /// Keeps `world` as the robot's belief and registers the world's
    /// functions over it.
    pub fn believe(&self, world: &World, seed: u64, functions: &mut sitlog_runtime::Functions) {
        let belief = Arc::new(Mutex::new(Sim::new(world, seed)));
        if let Ok(mut inner) = self.inner.lock() {
            inner.belief = Some(belief.clone());
        }
        sitlog_robot::register_world_functions(functions, Belief(belief), seed);
    }

    /// The two views the machine takes.
    pub fn split(self) -> RobotParts {
        (
            Box::new(Senses {
                inner: self.inner.clone(),
            }),
            Box::new(Effectors { inner: self.inner }),
        )
    }
}

#[derive(Clone)]
struct Belief(Arc<Mutex<Sim>>);

impl SimAccess for Belief {
    fn with_sim<R>(&self, f: impl FnOnce(&Sim) -> R) -> Result<R, String> {
        let sim = self
            .0
            .lock()
            .map_err(|_| "the robot's belief of the world is unusable".to_owned())?;
        Ok(f(&sim))
    }
}

fn atom(name: &str) -> Term {
    Term::atom(Atom::intern(name))
}

fn lock(inner: &Arc<Mutex<Inner>>) -> Result<std::sync::MutexGuard<'_, Inner>, String> {
    inner
        .lock()
        .map_err(|_| "the ROS 2 robot is unusable after an earlier panic".to_owned())
}

impl Inner {
    fn narrate(&self, text: &str) {
        if let Ok(mut c) = self.console.lock() {
            c.narrate(text);
        }
    }

    fn flag(&self) -> &AtomicBool {
        &self.stop.flag
    }

    /// The robot is gone: say why on the transcript and stop the run.
    fn gone(&self, why: &str) {
        if !self.stop.requested() {
            self.narrate(&format!("the robot is gone: {why}"));
            sitlog_runtime::errln!("error: the robot is gone: {why}");
        }
        self.stop.request_robot_gone();
    }

    /// Publishes on a topic and waits until the robot has it; `false`
    /// (and the robot gone) when it does not acknowledge it in time.
    fn publish<M: serde::Serialize>(&self, w: &Writer<M>, m: M) -> bool {
        let answer = Interface::secs(self.iface.timeouts.answer);
        match w.send(m, Some(answer)) {
            Ok(true) => true,
            Ok(false) => {
                self.gone(&format!(
                    "nothing acknowledged a message on {} within {:.1} s",
                    w.name, self.iface.timeouts.answer
                ));
                false
            }
            Err(e) => {
                self.gone(&e);
                false
            }
        }
    }

    /// One goal of an action, to its end.
    fn action<G, R, F>(
        &self,
        client: &ActionClient<G, R, F>,
        topic: &str,
        goal: G,
        limit: Duration,
    ) -> Call<R>
    where
        G: ros2_client::Message + Clone + 'static,
        R: ros2_client::Message + Clone + 'static,
        F: ros2_client::Message + 'static,
    {
        let t = &self.iface.timeouts;
        let node = &self.link.node;
        let discovery = Some(Interface::secs(t.discovery));
        let both = futures::future::join(
            client.goal_client().wait_for_service(node),
            client.result_client().wait_for_service(node),
        );
        match wait_for(both, discovery, self.flag()) {
            Waited::Done(_) => {}
            Waited::TimedOut => return Call::Failed("unavailable"),
            Waited::Stopped => return Call::Stopped,
        }
        let answer = Some(Interface::secs(t.answer));
        let (goal_id, response) = match wait_for(client.async_send_goal(goal), answer, self.flag())
        {
            Waited::Done(Ok(r)) => r,
            Waited::Done(Err(e)) => {
                self.gone(&format!("sending a goal on {topic}: {e:?}"));
                return Call::Failed("no_answer");
            }
            Waited::TimedOut => {
                self.gone(&format!(
                    "no answer to a goal on {topic} within {:.1} s",
                    t.answer
                ));
                return Call::Failed("no_answer");
            }
            Waited::Stopped => return Call::Stopped,
        };
        if !response.accepted {
            return Call::Failed("rejected");
        }
        match wait_for(
            client.async_request_result(goal_id),
            Some(limit),
            self.flag(),
        ) {
            Waited::Done(Ok((status, result))) => match status {
                GoalStatusEnum::Succeeded => Call::Succeeded(result),
                GoalStatusEnum::Aborted => Call::Aborted(result),
                GoalStatusEnum::Canceled => Call::Canceled,
                _ => Call::Failed("unknown_status"),
            },
            Waited::Done(Err(e)) => {
                self.gone(&format!("the result of a goal on {topic}: {e:?}"));
                Call::Failed("no_answer")
            }
            Waited::TimedOut => {
                let _ = client.cancel_goal(goal_id);
                Call::Failed("timed_out")
            }
            Waited::Stopped => {
                let _ = client.cancel_goal(goal_id);
                Call::Stopped
            }
        }
    }

    /// One call of a service.
    fn service<Q, A>(&self, client: &Client<Q, A>, topic: &str, request: Q) -> Call<A>
    where
        Q: ros2_client::Message + Clone + 'static,
        A: ros2_client::Message + 'static,
    {
        let t = &self.iface.timeouts;
        match wait_for(
            client.wait_for_service(&self.link.node),
            Some(Interface::secs(t.discovery)),
            self.flag(),
        ) {
            Waited::Done(()) => {}
            Waited::TimedOut => return Call::Failed("unavailable"),
            Waited::Stopped => return Call::Stopped,
        }
        match wait_for(
            client.async_call_service(request),
            Some(Interface::secs(t.answer)),
            self.flag(),
        ) {
            Waited::Done(Ok(a)) => Call::Succeeded(a),
            Waited::Done(Err(e)) => {
                self.gone(&format!("calling {topic}: {e:?}"));
                Call::Failed("no_answer")
            }
            Waited::TimedOut => {
                self.gone(&format!("no answer on {topic} within {:.1} s", t.answer));
                Call::Failed("no_answer")
            }
            Waited::Stopped => Call::Stopped,
        }
    }

    /// The status term of a call that did not succeed.
    fn failure<R>(
        store: &mut Store,
        call: Call<R>,
        topic: &str,
        aborted: impl FnOnce(&mut Store, R) -> Term,
    ) -> Term {
        match call {
            Call::Succeeded(_) => atom("ok"),
            Call::Aborted(r) => aborted(store, r),
            Call::Canceled => atom("canceled"),
            Call::Failed(why) => store.compound(Atom::intern(why), &[atom(topic)]),
            Call::Stopped => atom("stopped"),
        }
    }

    /// A speech situation: what was heard.
    fn listen(&mut self) -> Heard {
        let topic = self.iface.topics.heard.clone();
        // What came while nothing listened is not heard.
        loop {
            match self.heard.take() {
                Ok(Some((m, _))) => {
                    self.narrate(&format!("not listening: dropped `{}` from {topic}", m.data))
                }
                Ok(None) => break,
                Err(e) => dropped(&topic, &e),
            }
        }
        if let Some(why) = self.aborted() {
            return Heard::Aborted(why);
        }
        if !self.publish(&self.listening, StdBool { data: true }) {
            return Heard::Gone;
        }
        let t = &self.iface.timeouts;
        let speech = (t.speech > 0.0).then(|| Interface::secs(t.speech));
        let probe = Interface::secs(t.answer.max(0.5));
        let start = Instant::now();
        let heard = loop {
            let limit = match speech {
                Some(l) => {
                    let left = l.saturating_sub(start.elapsed());
                    if left.is_zero() {
                        break Heard::Nobody;
                    }
                    left.min(probe)
                }
                None => probe,
            };
            let either = futures::future::select(
                Box::pin(self.heard.async_take()),
                Box::pin(self.abort.async_take()),
            );
            let took = wait_for(either, Some(limit), &self.stop.flag);
            match took {
                Waited::Done(Either::Left((Ok((m, _)), _))) => break Heard::Said(m.data),
                Waited::Done(Either::Left((Err(e), _))) => dropped(&topic, &e),
                Waited::Done(Either::Right((Ok((m, _)), _))) => break Heard::Aborted(m.data),
                Waited::Done(Either::Right((Err(e), _))) => dropped(&self.iface.topics.abort, &e),
                // Still listening? The robot must acknowledge it again.
                Waited::TimedOut => {
                    if !self.publish(&self.listening, StdBool { data: true }) {
                        break Heard::Gone;
                    }
                }
                Waited::Stopped => break Heard::Stopped,
            }
        };
        if matches!(heard, Heard::Said(_) | Heard::Nobody | Heard::Aborted(_)) {
            self.publish(&self.listening, StdBool { data: false });
        }
        heard
    }

    /// The text of a message on the abort topic, if one came.
    fn aborted(&self) -> Option<String> {
        loop {
            match self.abort.take() {
                Ok(Some((m, _))) => return Some(m.data),
                Ok(None) => return None,
                Err(e) => dropped(&self.iface.topics.abort, &e),
            }
        }
    }
}

/// A message dropped because its bytes are not its topic's type (a
/// wrong layout): one line on stderr, also under `-q` (issue 38: such
/// messages on the heard topic were heard as `nobody`, then said only on
/// the transcript).
fn dropped(topic: &str, e: &dyn std::fmt::Debug) {
    sitlog_runtime::errln!("note: dropped a malformed message on {topic}: {e:?}");
}

/// What a speech situation heard.
enum Heard {
    Said(String),
    Nobody,
    /// The robot ended the run (why).
    Aborted(String),
    Gone,
    Stopped,
}

/// The robot's senses.
struct Senses {
    inner: Arc<Mutex<Inner>>,
}

/// The robot's effectors.
struct Effectors {
    inner: Arc<Mutex<Inner>>,
}

impl Perception for Senses {
    fn perceive(
        &mut self,
        store: &mut Store,
        situation_type: Term,
        _expectations: &[Term],
    ) -> Result<Perceived, String> {
        let mut inner = lock(&self.inner)?;
        if inner.stop.requested() {
            return Ok(Perceived::EndOfInput);
        }
        let (name, arity) = store
            .functor(situation_type)
            .ok_or_else(|| "a situation type must be an atom or a compound".to_owned())?;
        let input = match name.as_str() {
            "speech" | "listening" | "keyboard" | "nkeyboard" => match inner.listen() {
                Heard::Said(text) if !text.trim().is_empty() => {
                    let user = inner.iface.user_name.clone();
                    if let Ok(mut c) = inner.console.lock() {
                        c.turn(&user, &text);
                    }
                    let t = atom(&text);
                    store.compound(Atom::intern("said"), &[t])
                }
                Heard::Said(_) | Heard::Nobody => atom("nobody"),
                Heard::Aborted(why) => return Err(why),
                Heard::Gone | Heard::Stopped => return Ok(Perceived::EndOfInput),
            },
            "vision" => {
                let topic = inner.iface.services.detect_objects.clone();
                let request = DetectObjectsRequest {
                    camera: inner.iface.frames.camera.clone(),
                };
                match inner.service(&inner.detect, &topic, request) {
                    Call::Succeeded(r) => {
                        let mut seen: Vec<(f64, String)> = r
                            .detections
                            .detections
                            .iter()
                            .map(|d| {
                                let class = d
                                    .results
                                    .first()
                                    .map(|h| h.hypothesis.class_id.clone())
                                    .unwrap_or_else(|| d.id.clone());
                                (d.bbox.center.position.x, class)
                            })
                            .collect();
                        seen.sort_by(|a, b| a.0.total_cmp(&b.0));
                        let items: Vec<Term> = seen.iter().map(|(_, o)| atom(o)).collect();
                        let l = store.list(&items);
                        store.compound(Atom::intern("objects"), &[l])
                    }
                    Call::Stopped => return Ok(Perceived::EndOfInput),
                    other => {
                        let status = Inner::failure(store, other, &topic, |_, _| atom("aborted"));
                        if inner.stop.requested() {
                            return Ok(Perceived::EndOfInput);
                        }
                        return Err(format!("vision over ROS 2: {}", store.writeq(status)));
                    }
                }
            }
            "hands" => {
                let topic = inner.iface.services.hands.clone();
                match inner.service(&inner.hands, &topic, Empty::default()) {
                    Call::Succeeded(r) => {
                        let hand = |h: &str| atom(if h.is_empty() { "free" } else { h });
                        let (l, r) = (hand(&r.left), hand(&r.right));
                        store.compound(Atom::intern("hands"), &[l, r])
                    }
                    Call::Stopped => return Ok(Perceived::EndOfInput),
                    other => {
                        let status = Inner::failure(store, other, &topic, |_, _| atom("aborted"));
                        if inner.stop.requested() {
                            return Ok(Perceived::EndOfInput);
                        }
                        return Err(format!("hands over ROS 2: {}", store.writeq(status)));
                    }
                }
            }
            "presence" => {
                let seconds = if arity == 0 {
                    0.0
                } else {
                    number(store, store.args(situation_type)[0])
                        .filter(|s| s.is_finite() && *s >= 0.0)
                        .ok_or_else(|| {
                            format!(
                                "`{}`: the time to wait must be a number of seconds, at least 0",
                                store.writeq(situation_type)
                            )
                        })?
                };
                let topic = inner.iface.actions.wait_for_person.clone();
                let limit = Interface::secs(inner.iface.timeouts.action + seconds.min(1.0e6));
                let goal = WaitForPersonGoal {
                    max_seconds: seconds,
                };
                match inner.action(&inner.wait_for_person, &topic, goal, limit) {
                    Call::Succeeded(r) if r.present => atom("user"),
                    Call::Succeeded(_) | Call::Aborted(_) | Call::Canceled => atom("nobody"),
                    Call::Stopped => return Ok(Perceived::EndOfInput),
                    Call::Failed(why) => {
                        if inner.stop.requested() {
                            return Ok(Perceived::EndOfInput);
                        }
                        return Err(format!("presence over ROS 2: {why}('{topic}')"));
                    }
                }
            }
            other => {
                return Err(format!(
                    "the robot over ROS 2 has no perceptual interpreter for situations of type `{other}` (it has speech, vision, hands and presence)"
                ))
            }
        };
        Ok(Perceived::Input(input))
    }

    /// The robot's senses are not told where the program waits.
    fn uses_waiting_at(&self) -> bool {
        false
    }
}

impl Actions for Effectors {
    fn perform(&mut self, store: &mut Store, action: Term) -> Result<(), String> {
        let mut guard = lock(&self.inner)?;
        let inner = &mut *guard;
        let Some((name, arity)) = store.functor(action) else {
            return Ok(());
        };
        let action = store.deref(action);
        let robot = inner.iface.robot_name.clone();
        // Once the robot is gone nothing more reaches it.
        let gone = inner.stop.robot_gone();
        let belief = inner.belief.clone();
        let believe = |f: &dyn Fn(&mut Sim)| {
            if let Some(b) = &belief {
                if let Ok(mut sim) = b.lock() {
                    f(&mut sim);
                }
            }
        };
        match (name.as_str(), arity) {
            ("say", 1) => {
                let text = sentence(store, store.args(action)[0]);
                if let Ok(mut c) = inner.console.lock() {
                    c.turn(&robot, &text);
                }
                if !gone {
                    inner.publish(&inner.say, StdString { data: text });
                }
            }
            ("screen", 1) => {
                let text = sentence(store, store.args(action)[0]);
                inner.narrate(&format!("{robot} shows on its screen: {text}"));
                if !gone {
                    inner.publish(&inner.screen, StdString { data: text });
                }
            }
            ("message", 2) => {
                let to = sentence(store, store.args(action)[0]);
                let text = sentence(store, store.args(action)[1]);
                inner.narrate(&format!("{robot} texts {}: {text}", lower_first(&to)));
                if !gone {
                    inner.publish(&inner.message, TextMessage { to, text });
                }
            }
            ("navigate", 2) => {
                let place = name_arg(store, action, 0, "place")?;
                let topic = inner.iface.actions.navigate.clone();
                let status = match goal_pose(&inner.iface, &place) {
                    None => atom("unknown_place"),
                    Some(_) if gone => store.compound(Atom::intern("no_answer"), &[atom(&topic)]),
                    Some(goal) => {
                        let limit = Interface::secs(inner.iface.timeouts.navigate);
                        let call = inner.action(&inner.navigate, &topic, goal, limit);
                        if let Call::Succeeded(_) = call {
                            believe(&|sim| {
                                let _ = sim.navigate(&place);
                            });
                        }
                        Inner::failure(store, call, &topic, |store, r| {
                            status_term(store, &r.error_msg).unwrap_or_else(|| {
                                let code = Term::int(i64::from(r.error_code));
                                let msg = atom(&r.error_msg);
                                store.compound(Atom::intern("aborted"), &[code, msg])
                            })
                        })
                    }
                };
                inner.narrate(&format!(
                    "{robot} navigates to {place} over {topic}: {}",
                    store.writeq(status)
                ));
                report(store, action, 1, status)?;
            }
            ("grasp", 3) | ("place", 2) | ("hand_over", 2) => {
                let (object, hand) = if arity == 3 {
                    (
                        Some(name_arg(store, action, 0, "object")?),
                        hand_arg(store, action, 1)?,
                    )
                } else {
                    (None, hand_arg(store, action, 0)?)
                };
                let topic = match name.as_str() {
                    "grasp" => inner.iface.actions.grasp.clone(),
                    "place" => inner.iface.actions.place.clone(),
                    _ => inner.iface.actions.hand_over.clone(),
                };
                let limit = Interface::secs(inner.iface.timeouts.action);
                let hand_name = hand.as_str().to_owned();
                let call = if gone {
                    Call::Failed("no_answer")
                } else if let Some(o) = &object {
                    let goal = GraspGoal {
                        object: o.clone(),
                        hand: hand_name.clone(),
                    };
                    inner.action(&inner.grasp, &topic, goal, limit)
                } else {
                    let goal = HandGoal {
                        hand: hand_name.clone(),
                    };
                    let client = if name.as_str() == "place" {
                        &inner.place
                    } else {
                        &inner.hand_over
                    };
                    inner.action(client, &topic, goal, limit)
                };
                if let Call::Succeeded(_) = &call {
                    let verb = name.as_str().to_owned();
                    believe(&|sim| match (verb.as_str(), &object) {
                        ("grasp", Some(o)) => {
                            let _ = sim.grasp(o, hand);
                        }
                        ("place", _) => {
                            let _ = sim.place(hand);
                        }
                        _ => {
                            let _ = sim.hand_over(hand);
                        }
                    });
                }
                let status = Inner::failure(store, call, &topic, |store, r| {
                    status_term(store, &r.status).unwrap_or_else(|| atom("aborted"))
                });
                let what = match &object {
                    Some(o) => format!("{name} {o} with the {hand_name} hand"),
                    None => format!("{name} with the {hand_name} hand"),
                };
                inner.narrate(&format!(
                    "{robot}: {what} over {topic}: {}",
                    store.writeq(status)
                ));
                report(store, action, arity - 1, status)?;
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
                inner.narrate(&format!("{robot} waits {seconds:.1} s"));
                let end = Instant::now() + Duration::from_secs_f64(seconds.min(1.0e6));
                while Instant::now() < end && !inner.stop.requested() {
                    std::thread::sleep(crate::link::TICK.min(end - Instant::now()));
                }
            }
            // Any other action does nothing, as in the original.
            _ => {}
        }
        Ok(())
    }
}
