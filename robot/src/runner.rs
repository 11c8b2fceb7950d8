//! The one way to run a task, for `sitlogc run`, `sitlogc debug`, compiled
//! tasks and tests: a [`Runner`] says where the run writes, what stops it,
//! what wraps its perception and which debugger watches it;
//! [`Runner::run`] runs a program with the options of a command line
//! ([`RunArgs`]) and its [`Assets`], and returns the exit status (0 ok, 1
//! run-time error, 2 usage or I/O problem, 3 end of typed input, 130 / 143
//! interrupted by SIGINT / SIGTERM).
//!
//! What runs the task:
//! - with a world (the application's `world.toml`, `--world FILE`, or one
//!   embedded in a compiled task) and without `--no-world`: the simulated
//!   robot and user ([`crate::robot`]); the transcript (the conversation and
//!   narration) goes to stdout before the text report, to stderr with
//!   `--format json`;
//! - without one: test mode, as the original's: inputs from `--script` or
//!   typed at a prompt ([`crate::prompt`]), actions rendered on the
//!   process's stderr;
//! - with `--robot ros2`: the robot the run's [`RobotHook`] connects
//!   ([`Runner::robot`]; the world file, if any, is then not simulated);
//!   its transcript goes where a world's does. Without a hook the run
//!   fails with exit status 2. When that robot goes away the task stops
//!   at its next transition boundary, exit status 4.

use crate::assets::{Assets, TextFile};
use crate::cli::{Format, HistoryMode, RobotKind, RunArgs};
use crate::console::{Console, SharedWriter};
use crate::debug_hooks::DebugHooks;
use crate::interrupt::Interrupt;
use crate::kb_services;
use crate::live_view::LiveView;
use crate::observers::{Fanout, Progress, TraceFile};
use crate::robot_hook::{RobotHook, RobotSetup};
use crate::streams::Streams;
use sitlog_runtime::app::{run, App};
use sitlog_runtime::machine::{Actions, Observer, Options, Perception};
use sitlog_runtime::report;
use sitlog_runtime::testmode::{ScriptPerception, SharedPerception, TextActions};
use sitlog_runtime::Functions;
use std::io::Write;
use std::sync::{Arc, Mutex};

/// Wraps the perception a run makes (the simulated user's, the script's or
/// the prompt's) in another: `sitlogc run --watch` lets a situation waiting
/// for input take it in a program that changed meanwhile.
pub type PerceptionWrap = Box<dyn FnOnce(Box<dyn Perception>) -> Box<dyn Perception>>;

/// How a task runs, besides its options and assets: its [`Streams`], what
/// stops it, what wraps its perception, and a debugger's hooks.
pub struct Runner {
    streams: Streams,
    interrupt: Option<Interrupt>,
    wrap: Option<PerceptionWrap>,
    debugger: Option<DebugHooks>,
    robot: Option<RobotHook>,
    watch: Option<Box<dyn Observer + Send>>,
    actions_out: Option<Box<dyn Write + Send>>,
    kb_probe: Option<KbProbe>,
}

/// Given the run's KB, if it has one, before the task starts: whoever asked
/// (`sitlogc test`) reads it after the run ([`Runner::kb_probe`]).
pub type KbProbe = Box<dyn FnOnce(kb_services::SharedKb) + Send>;

impl Runner {
    /// A run on `streams`, which nothing stops but its end (and, at a
    /// prompt, the end of the typed input).
    pub fn new(streams: Streams) -> Runner {
        Runner {
            streams,
            interrupt: None,
            wrap: None,
            debugger: None,
            robot: None,
            watch: None,
            actions_out: None,
            kb_probe: None,
        }
    }

    /// A run as `sitlogc run` makes it: on the process's streams, stopped
    /// by SIGINT and SIGTERM ([`Interrupt::install`]).
    ///
    /// A signal stops the task at its next transition: the report (status
    /// `interrupted`) is still printed and the trace closed; the exit
    /// status is then 130 (SIGINT) or 143 (SIGTERM). A second signal ends
    /// the process at once, and so does the first before the task starts
    /// (while files open, a FIFO waits for its writer or the live view for
    /// its page). The end of typed input (Ctrl-D at the prompt)
    /// stops it the same way, with exit status 3 ([`crate::prompt`]).
    pub fn process() -> Runner {
        Runner::new(Streams::process()).interrupt(Interrupt::install_before_start())
    }

    /// Stops the run between transitions when `interrupt` is set.
    pub fn interrupt(mut self, interrupt: Interrupt) -> Runner {
        self.interrupt = Some(interrupt);
        self
    }

    /// Wraps the run's perception in `wrap` ([`PerceptionWrap`]).
    pub fn wrap_perception(mut self, wrap: PerceptionWrap) -> Runner {
        self.wrap = Some(wrap);
        self
    }

    /// Runs under a debugger: its observer, test-mode perception, look at
    /// the world and stop flag ([`DebugHooks`]).
    pub fn debugger(mut self, hooks: DebugHooks) -> Runner {
        self.debugger = Some(hooks);
        self
    }

    /// Tells `observer` of every transition too (after the trace and the
    /// debugger): `sitlogc test` records the arcs a test takes.
    pub fn observe(mut self, observer: Box<dyn Observer + Send>) -> Runner {
        self.watch = Some(observer);
        self
    }

    /// In test mode, renders the actions (`Golem says: ...`) on `out`
    /// instead of the process's stderr.
    pub fn actions_to(mut self, out: Box<dyn Write + Send>) -> Runner {
        self.actions_out = Some(out);
        self
    }

    /// Hands the run's KB (if it has one) to `probe` before the task starts.
    pub fn kb_probe(mut self, probe: KbProbe) -> Runner {
        self.kb_probe = Some(probe);
        self
    }

    /// Connects `--robot ros2` runs with `hook` ([`RobotHook`]).
    pub fn robot(mut self, hook: RobotHook) -> Runner {
        self.robot = Some(hook);
        self
    }

    /// The checks of a run that need only its options and files, as
    /// [`Runner::run`] makes them first: outputs that would destroy an
    /// input, options that exclude each other, the world file read and (with
    /// the simulator) parsed (an error in it: status 1). For a caller with costly set-up of its own
    /// (`sitlogc run` starts the Prolog engine), so that a run that cannot
    /// start says so at once: it runs with `args` and `assets` as given back
    /// (the world file, read once, moved into the assets: a FIFO is read
    /// only once). Make the runner first: its signal handling then covers
    /// a world file that blocks. The error is the exit status and message.
    pub fn preflight(args: &RunArgs, assets: &Assets) -> Result<(RunArgs, Assets), (u8, String)> {
        let world = run_world(args, assets)?;
        #[cfg(feature = "sim")]
        if let (Some(world), false) = (&world, args.robot == RobotKind::Ros2) {
            // An error in the world file's content: status 1, as one in
            // the KB or the DMs (2 is for usage and for a file that cannot
            // be read).
            crate::robot::parse_world(world).map_err(|e| (1, e))?;
        }
        let mut args = args.clone();
        let mut assets = assets.clone();
        args.world = None;
        assets.world = world;
        Ok((args, assets))
    }

    /// Runs `app` with `functions`, the options `args` and `assets`; the
    /// exit status (see the module documentation). With `--view` the live
    /// view is served first, and the task starts when its page is open.
    pub fn run<A: App>(
        mut self,
        app: &A,
        functions: Functions,
        args: &RunArgs,
        assets: &Assets,
    ) -> u8 {
        crate::interrupt::report_json_before_start(args.format == Format::Json);
        if !args.view {
            return self.run_task(app, functions, args, assets, None);
        }
        let view = match LiveView::start(args, assets, &mut self.streams.stderr) {
            Ok(view) => view,
            Err((code, message)) => {
                let _ = writeln!(self.streams.stderr, "{message}");
                if args.format == Format::Json {
                    let _ = self
                        .streams
                        .stdout
                        .write_all(report::stopped_json("error", &message).as_bytes())
                        .and_then(|_| self.streams.stdout.flush());
                }
                return code;
            }
        };
        let observer = view.observer(args.view_delay);
        let code = self.run_task(app, functions, args, assets, Some(observer));
        view.finish(code);
        code
    }

    /// The run itself, `view` (the live view's observer) already set up.
    fn run_task<A: App>(
        self,
        app: &A,
        mut functions: Functions,
        args: &RunArgs,
        assets: &Assets,
        mut view: Option<Box<dyn Observer + Send>>,
    ) -> u8 {
        let Runner {
            mut streams,
            interrupt,
            wrap,
            debugger,
            robot,
            mut watch,
            actions_out,
            kb_probe,
        } = self;
        let (mut debug_observer, mut debug_perception, mut debug_world, debug_stop) = match debugger
        {
            Some(h) => (
                Some(h.observer),
                Some(h.perception),
                Some(h.world),
                Some(h.stop),
            ),
            None => (None, None, None, None),
        };
        // Without the simulator there is no world to look at.
        #[cfg(not(feature = "sim"))]
        let _ = debug_world.take();
        let json = args.format == Format::Json;
        // Until the report is written, a run stopped by an error still
        // writes one with --format json (status `error`, the message).
        let mut reported = false;
        macro_rules! fail {
            ($code:expr, $($msg:tt)*) => {{
                let message = format!($($msg)*);
                let _ = writeln!(streams.stderr, "{message}");
                if json && !reported {
                    let _ = streams
                        .stdout
                        .write_all(report::stopped_json("error", &message).as_bytes())
                        .and_then(|_| streams.stdout.flush());
                }
                return $code;
            }};
        }
        let world = match run_world(args, assets) {
            Ok(world) => world,
            Err((code, message)) => fail!(code, "{message}"),
        };
        let other_robot = args.robot == RobotKind::Ros2;
        // The transcript: stdout before the text report, stderr with JSON.
        let with_world = world.is_some() || other_robot;
        let progress = !args.quiet && streams.stdout_is_terminal && streams.stderr_is_terminal;
        let transcript_out: Box<dyn Write + Send> = if !with_world {
            Box::new(std::io::sink())
        } else {
            let stream = if json {
                &mut streams.stderr
            } else {
                &mut streams.stdout
            };
            let shared = SharedWriter::new(std::mem::replace(stream, Box::new(std::io::sink())));
            *stream = Box::new(shared.clone());
            Box::new(shared)
        };
        let console = Console::new(transcript_out, progress, !args.quiet).shared();

        // The KB; a persisted one stays locked until the run ends.
        let kb_lock =
            match kb_services::open(args.kb.as_deref(), args.kb_persist, assets.kb.as_ref()) {
                Ok(Some(kb)) => {
                    let narrate = with_world.then(|| console.clone());
                    let shared = Arc::new(Mutex::new(kb.kb));
                    if let Some(probe) = kb_probe {
                        probe(shared.clone());
                    }
                    kb_services::register_with(&mut functions, shared, kb.persist, narrate);
                    kb.lock
                }
                Ok(None) => None,
                Err((code, message)) => fail!(code, "{message}"),
            };

        // Typed input (test mode without a script) ends the task cleanly at
        // its end (Ctrl-D): recorded in the run's interrupt (one of its own
        // when signals are not handled).
        let typed = world.is_none() && args.script.is_none() && !other_robot;
        let ended: Option<Interrupt> = interrupt
            .clone()
            .or_else(|| (typed || other_robot).then(Interrupt::new));
        // Perception and actions: another robot, the simulated robot, or test mode.
        let (perception, mut actions): (Box<dyn Perception>, Box<dyn Actions>) = match &world {
            _ if other_robot => {
                let Some(hook) = robot else {
                    fail!(
                        2,
                        "error: --robot ros2: this program was built without ROS 2 (sitlogc: its default feature `ros2`; a compiled task: `sitlogc build --ros2`)"
                    );
                };
                let setup = RobotSetup {
                    args,
                    assets,
                    world: world.as_ref(),
                    console: console.clone(),
                    functions: &mut functions,
                    stop: ended.clone().unwrap_or_default(),
                };
                match hook(setup) {
                    Ok(parts) => parts,
                    Err((code, message)) => fail!(code, "{message}"),
                }
            }
            #[cfg(feature = "sim")]
            Some(world) => {
                match crate::robot::SimRobot::from_file(world, args.seed, console.clone()) {
                    Ok(robot) => {
                        robot.register_inference(&mut functions, args.seed);
                        if let Some(give) = debug_world.take() {
                            give(crate::debug_hooks::WorldProbe::new(robot.probe()));
                        }
                        let (senses, effectors) = robot.split();
                        (Box::new(senses), Box::new(effectors))
                    }
                    // A world file that is not what the simulator reads: exit 1,
                    // an error of the application's files as in its KB, its
                    // DMs or bytes that are not UTF-8 (issue 23; it was 2
                    // until issue 39, as for a missing file, which stays 2).
                    Err(e) => fail!(1, "{e}"),
                }
            }
            #[cfg(not(feature = "sim"))]
            Some(world) => fail!(
                2,
                "error: {} is a world, but this task was built without the simulator (feature `sim` of sitlog-robot)",
                world.name
            ),
            None => {
                let limits = args.input_limits();
                let perception: Box<dyn Perception> = match (&args.script, debug_perception.take())
                {
                    (Some(path), debugger) => match read_script(path) {
                        Ok(script) => {
                            // one reader of the script for the perception and
                            // the Prolog engine's read/1 (issue 39)
                            let script = SharedPerception::new(script.with_limits(limits));
                            functions.set_input(Some(script.input()));
                            let script: Box<dyn Perception> = Box::new(script);
                            match debugger {
                                Some(make) => make(Some(script)),
                                None => script,
                            }
                        }
                        Err(e) => fail!(e.status, "{e}"),
                    },
                    (None, Some(make)) => make(None),
                    (None, None) => {
                        let (perception, input) = crate::prompt::typed_input(
                            limits,
                            interrupt.as_ref(),
                            ended.clone().unwrap_or_default(),
                            console.clone(),
                        );
                        functions.set_input(input);
                        perception
                    }
                };
                let actions: Box<dyn Actions> = match actions_out {
                    Some(out) => Box::new(
                        TextActions::new(out, app.basic_actions())
                            .with_unbound_screen(args.unbound_screen.clone()),
                    ),
                    None => Box::new(
                        TextActions::new(
                            crate::console::ConsoleStderr::new(console.clone()),
                            app.basic_actions(),
                        )
                        .with_unbound_screen(args.unbound_screen.clone()),
                    ),
                };
                (perception, actions)
            }
        };
        let mut perception = match wrap {
            Some(wrap) => wrap(perception),
            None => perception,
        };

        let mut trace = match &args.trace {
            Some(path) => match std::fs::File::create(path) {
                Ok(f) => Some(TraceFile::new(f)),
                Err(e) => fail!(2, "error: cannot create trace file {}: {e}", path.display()),
            },
            None => None,
        };
        let shows_progress = console.lock().map(|c| c.shows_progress()).unwrap_or(false);
        let mut progress_observer = Progress { console: &console };
        let mut observers: Vec<&mut dyn Observer> = Vec::new();
        if let Some(t) = trace.as_mut() {
            observers.push(t);
        }
        if let Some(d) = debug_observer.as_mut() {
            observers.push(d.as_mut());
        }
        if let Some(v) = view.as_mut() {
            observers.push(v.as_mut());
        }
        if let Some(w) = watch.as_mut() {
            observers.push(w.as_mut());
        }
        if shows_progress {
            observers.push(&mut progress_observer);
        }
        let mut fanout = Fanout(observers);
        let observer: Option<&mut dyn Observer> = match fanout.0.len() {
            0 => None,
            _ => Some(&mut fanout),
        };
        let options = Options {
            keep_history: args.history == HistoryMode::Keep,
            input_limits: args.input_limits(),
            stop: ended.as_ref().map(|i| i.flag.clone()).or(debug_stop),
            close_list_tails: args.close_list_tails,
            skip_unmatched_in_arg: args.skip_unmatched_in_arg,
            ..Options::default()
        };
        functions.set_call_limits(args.call_limits());
        // A signal also ends a Prolog directive or call under way (issue 38).
        functions.set_stop(options.stop.clone());
        // Every file is open: the operating system's sandbox closes the
        // rest, on this thread and (through the trust's hook) on the
        // Prolog engine's before the first directive (issue 38).
        // (A persisted KB is written by replacing its real file.)
        let persist = kb_lock.as_ref().map(|lock| lock.path());
        let confine = match crate::sandbox::enter(args, persist, &mut streams.stderr) {
            Ok(confine) => confine,
            Err((code, message)) => fail!(code, "{message}"),
        };
        // What the application's code may reach (Prolog directives run at
        // the first transition, with this).
        let mut trust = args.trust();
        trust.confine = confine;
        functions.set_trust(trust);

        // from here a signal stops the task between transitions
        if let Some(i) = &interrupt {
            i.started();
        }
        let result = run(
            app,
            &args.main,
            args.in_arg.as_deref(),
            options,
            functions,
            perception.as_mut(),
            actions.as_mut(),
            observer,
        );
        drop(fanout);
        // The trace is flushed and synced however the run ended.
        let trace_error = trace.and_then(|t| t.finish().err());
        let trace_name = || {
            args.trace
                .as_ref()
                .map(|p| p.display().to_string())
                .unwrap_or_default()
        };
        let (outcome, mut store) = match result {
            Ok(r) => r,
            Err(e) => {
                if let Ok(mut c) = console.lock() {
                    c.finish();
                }
                if let Some(te) = trace_error {
                    let _ = writeln!(
                        streams.stderr,
                        "error: cannot write the trace {}: {te}",
                        trace_name()
                    );
                }
                fail!(2, "error: {e}")
            }
        };
        let mut outcome = outcome;
        // The error names the failing expression's position, in every report.
        if let Err(e) = &mut outcome.result {
            if let Some(location) = app.error_location(e) {
                e.location = Some(location);
            }
        }
        let transcript_error = console.lock().ok().and_then(|mut c| c.finish());
        // What the run went on from as the original does (an in_arg
        // skipped), on stderr: the report on stdout keeps its format.
        for w in &outcome.warnings {
            let _ = writeln!(streams.stderr, "{w}");
        }
        let report = match args.format {
            Format::Json => format!("{}\n", report::outcome_json(&store, &outcome)),
            Format::Text => {
                report::outcome_text_with(&mut store, &outcome, args.history == HistoryMode::Keep)
            }
        };
        reported = true;
        let written = streams
            .stdout
            .write_all(report.as_bytes())
            .and_then(|_| streams.stdout.flush());
        match written {
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
            Err(e) => fail!(2, "error: cannot write the report: {e}"),
            Ok(()) => {}
        }
        if let Some(e) = transcript_error {
            fail!(2, "error: cannot write the transcript: {e}");
        }
        match trace_error {
            Some(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
                fail!(2, "error: cannot write the trace {}: {e}", trace_name())
            }
            _ => {}
        }
        if let Err(e) = &outcome.result {
            let by_input =
                outcome.interrupted && ended.as_ref().is_some_and(Interrupt::ended_by_input);
            let gone = outcome.interrupted && ended.as_ref().is_some_and(Interrupt::robot_gone);
            if gone {
                let _ = writeln!(
                    streams.stderr,
                    "stopped: the robot went away: the task did not finish (exit status {})",
                    crate::interrupt::EXIT_ROBOT_GONE
                );
            } else if by_input {
                let place = match (&e.dm, &e.situation) {
                    (Some(dm), Some(sit)) => {
                        format!(" while DM `{dm}` waited in situation `{sit}`")
                    }
                    _ => String::new(),
                };
                let _ = writeln!(
                    streams.stderr,
                    "stopped: the input ended (Ctrl-D){place}: the task did not finish (exit status {})",
                    crate::interrupt::EXIT_END_OF_INPUT
                );
            } else {
                // Reported once, here (the report on stdout does not repeat
                // it): on the source when the program keeps it.
                let color = streams.stderr_is_terminal && std::env::var_os("NO_COLOR").is_none();
                let _ = match app.render_error(e, color) {
                    Some(text) => write!(streams.stderr, "{text}"),
                    None => writeln!(streams.stderr, "error: {e}"),
                };
            }
            match ended.as_ref().and_then(Interrupt::exit_status) {
                Some(status) if outcome.interrupted => status,
                _ => 1,
            }
        } else {
            0
        }
    }
}

/// The script of `--script`: a regular file is read whole (so that text
/// that is not UTF-8 is refused before the run starts); a pipe or device
/// (`/dev/stdin`, a FIFO) is read as the task consumes it.
fn read_script(path: &std::path::Path) -> Result<ScriptPerception, crate::assets::FileError> {
    let regular = std::fs::metadata(path).map(|m| m.is_file()).unwrap_or(true);
    if regular {
        let s = TextFile::read(path, "script")?;
        return Ok(ScriptPerception::new(s.name, s.text));
    }
    let name = path.display().to_string();
    match std::fs::File::open(path) {
        Ok(f) => Ok(ScriptPerception::from_reader(
            name,
            Box::new(std::io::BufReader::new(f)),
        )),
        Err(e) => Err(crate::assets::FileError {
            status: 2,
            message: format!("error: cannot read script {name}: {e}"),
        }),
    }
}

/// The run's world file, if any, after the checks that need no more than
/// the options: outputs in conflict with inputs, `--script` with a world or
/// with a robot over ROS 2 (exit status 2), a world file that cannot be read.
fn run_world(args: &RunArgs, assets: &Assets) -> Result<Option<TextFile>, (u8, String)> {
    // An output that is also an input (or another output) would destroy
    // it: refused before anything is opened.
    if let Some(message) = args.files_in_conflict() {
        return Err((2, format!("error: {message}")));
    }
    // The world, if any.
    let world: Option<TextFile> = if args.no_world {
        None
    } else if let Some(path) = &args.world {
        Some(TextFile::read(path, "world").map_err(|e| (e.status, e.to_string()))?)
    } else {
        assets.world.clone()
    };
    if args.robot == RobotKind::Ros2 && args.script.is_some() {
        return Err((
            2,
            "error: --script gives test-mode inputs, but this run is on a robot over ROS 2 (--robot ros2)"
                .to_owned(),
        ));
    }
    if world.is_some() && args.script.is_some() {
        return Err((
            2,
            "error: --script gives test-mode inputs, but this run has a world; pass --no-world to run in test mode"
                .to_owned(),
        ));
    }
    Ok(world)
}
