//! The command line of a task run, shared by `sitlogc run` (which adds the
//! application and its own options around [`RunArgs`]) and by compiled
//! tasks ([`main`]). The option set and the output contract are the notes'
//! "Our convention for `sitlogc run` output", plus the robot's options:
//! `--world`, `--no-world`, `--seed`, `--kb`, `--kb-persist`, `--quiet`.
//!
//! What runs the task:
//! - with a world (the application's `world.toml`, `--world FILE`, or one
//!   embedded in a compiled task) and without `--no-world`: the simulated
//!   robot and user ([`crate::robot`]); the transcript (the conversation and
//!   narration) goes to stdout before the text report, to stderr with
//!   `--format json`;
//! - without one: test mode, as the original's: inputs from `--script` or
//!   typed at a prompt, actions rendered on stderr.

use crate::console::{Console, SharedConsole, SharedWriter};
use crate::interrupt::{Interrupt, InterruptibleStdin};
use crate::kb;
use crate::prompt::EndOfInputStops;
use clap::{Args, CommandFactory, FromArgMatches, Parser, ValueEnum};
use sitlog_runtime::app::{run, App};
use sitlog_runtime::functions::CallLimits;
use sitlog_runtime::history::Entry;
use sitlog_runtime::machine::{Actions, Observer, Options, Perception};
use sitlog_runtime::report;
use sitlog_runtime::testmode::{InputLimits, PromptPerception, ScriptPerception, TextActions};
use sitlog_runtime::{Functions, Store, Term};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Output format of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// The papers' history listing, then `Out Arg:` and `Out Global Vars:`.
    Text,
    /// One JSON object on stdout.
    Json,
}

/// Whether the task history is kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum HistoryMode {
    Keep,
    None,
}

/// The options of a run (after the application).
#[derive(Args, Clone, Debug, PartialEq, Eq)]
pub struct RunArgs {
    /// The DM to start, as a term (it may have arguments).
    #[arg(long, default_value = "main", value_name = "DM")]
    pub main: String,
    /// The initial pipe value, as a term (default: the atom `none`).
    #[arg(long, value_name = "TERM", allow_hyphen_values = true)]
    pub in_arg: Option<String>,
    /// Test mode: read the inputs from FILE (one term per line, ending with
    /// `.`) instead of a prompt on stdin. Not with a world.
    #[arg(long, value_name = "FILE")]
    pub script: Option<PathBuf>,
    /// `text`: the papers' history listing; `json`: one JSON object on stdout.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
    /// `none` keeps no history, so that a long task runs in bounded memory.
    #[arg(long, value_enum, default_value_t = HistoryMode::Keep)]
    pub history: HistoryMode,
    /// Write one JSON object per transition to FILE as it happens.
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// A knowledge base whose services become user functions
    /// (`apply(object_property_value(I, P), [pete, lives])`); default: the
    /// application's `knowledge.kb`, if it has one.
    #[arg(long, value_name = "FILE")]
    pub kb: Option<PathBuf>,
    /// Write every successful KB update back to the --kb file (atomically).
    #[arg(long)]
    pub kb_persist: bool,
    /// Run on the simulated world of FILE (default: the application's
    /// `world.toml`, if it has one).
    #[arg(long, value_name = "FILE", conflicts_with = "no_world")]
    pub world: Option<PathBuf>,
    /// Run in test mode even if the application has a world.
    #[arg(long)]
    pub no_world: bool,
    /// The seed of the simulated world (default: the world file's `seed`, else 0).
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// No progress indicator and no narration lines (the conversation stays).
    #[arg(long, short)]
    pub quiet: bool,
    /// Longest term from outside (one perception read from --script or typed,
    /// --in-arg, --main), in bytes.
    #[arg(long, value_name = "BYTES", default_value_t = InputLimits::MAX_BYTES)]
    pub max_input_bytes: usize,
    /// Deepest nesting of a term from outside, in levels.
    #[arg(long, value_name = "LEVELS", default_value_t = InputLimits::MAX_DEPTH)]
    pub max_input_depth: usize,
    /// Inferences one Prolog user function call may make.
    #[arg(long, value_name = "N", default_value_t = CallLimits::INFERENCES)]
    pub prolog_inferences: u64,
    /// Wall-clock time one Prolog user function call may take, in seconds
    /// (decimals allowed).
    #[arg(long, value_name = "SECONDS", default_value = "10", value_parser = parse_seconds)]
    pub prolog_time_limit: Duration,
    /// Memory the process may grow by during one Prolog user function call, in MiB.
    #[arg(long, value_name = "MIB", default_value_t = CallLimits::HEAP_BYTES >> 20)]
    pub prolog_heap_limit: u64,
    /// Follow the run in a web page: the program's diagram (as `sitlogc
    /// graph` draws it) with the current situation, the arcs taken, the DM
    /// stack and the last transitions. Served on 127.0.0.1 only; the task
    /// starts when the page is open, and the server stops when it ends.
    #[arg(long)]
    pub view: bool,
    /// The live view's port (default: a free one, printed on stderr).
    #[arg(long, value_name = "PORT", default_value_t = 0, requires = "view")]
    pub view_port: u16,
    /// Wait this many milliseconds after each transition, so that a fast
    /// task can be followed in the live view.
    #[arg(long, value_name = "MS", default_value_t = 0, requires = "view")]
    pub view_delay: u64,
}

/// `--prolog-time-limit`: seconds, decimals allowed.
fn parse_seconds(text: &str) -> Result<Duration, String> {
    let s: f64 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a number of seconds"))?;
    Duration::try_from_secs_f64(s).map_err(|_| format!("`{text}` is not a duration in seconds"))
}

impl RunArgs {
    /// The limits on terms from outside.
    pub fn input_limits(&self) -> InputLimits {
        InputLimits {
            max_bytes: self.max_input_bytes,
            max_depth: self.max_input_depth,
        }
    }

    /// The limits of one Prolog user function call.
    pub fn call_limits(&self) -> CallLimits {
        CallLimits {
            inferences: self.prolog_inferences,
            time: self.prolog_time_limit,
            heap_bytes: self.prolog_heap_limit.saturating_mul(1 << 20),
        }
    }
}

impl Default for RunArgs {
    fn default() -> RunArgs {
        RunArgs {
            main: "main".to_owned(),
            in_arg: None,
            script: None,
            format: Format::Text,
            history: HistoryMode::Keep,
            trace: None,
            kb: None,
            kb_persist: false,
            world: None,
            no_world: false,
            seed: None,
            quiet: false,
            max_input_bytes: InputLimits::MAX_BYTES,
            max_input_depth: InputLimits::MAX_DEPTH,
            prolog_inferences: CallLimits::INFERENCES,
            prolog_time_limit: CallLimits::TIME,
            prolog_heap_limit: CallLimits::HEAP_BYTES >> 20,
            view: false,
            view_port: 0,
            view_delay: 0,
        }
    }
}

/// A file a task carries: its name (for messages) and its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Source {
    pub name: String,
    pub text: String,
}

/// A file of a run that could not be used: the exit status (1 for bad
/// content, e.g. text that is not UTF-8; 2 for I/O) and the message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileError {
    pub status: u8,
    pub message: String,
}

impl std::fmt::Display for FileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl Source {
    /// Reads a text file: `what` names it in errors ("world", "script").
    /// Text that is not UTF-8 is an error at its first bad byte (status 1).
    pub fn read(path: &Path, what: &str) -> Result<Source, FileError> {
        let name = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| FileError {
            status: 2,
            message: format!("error: cannot read {what} {name}: {e}"),
        })?;
        match sitlog_syntax::decode_owned(bytes) {
            Ok(text) => Ok(Source { name, text }),
            Err(e) => Err(FileError {
                status: 1,
                message: format!("{name}:{}:{}: error: {}", e.line, e.column, e.message),
            }),
        }
    }
}

/// What an application brings besides its DMs: its name, its world and its
/// KB. `sitlogc run` reads them from the application directory; a compiled
/// task embeds them.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Assets {
    pub app_name: String,
    /// `world.toml`.
    pub world: Option<Source>,
    /// `knowledge.kb`.
    pub kb: Option<Source>,
    /// The program's diagram as JSON (`sitlogc graph --format json`), for
    /// `--view`.
    pub diagram: Option<String>,
}

/// The world file of an application directory.
pub const WORLD_FILE: &str = "world.toml";
/// The KB file of an application directory.
pub const KB_FILE: &str = "knowledge.kb";

impl Assets {
    /// The assets of an application directory (or of the directory of a DM
    /// file): `world.toml` and `knowledge.kb` where present.
    pub fn from_app(app: &Path) -> Result<Assets, FileError> {
        let dir = if app.is_dir() {
            app.to_path_buf()
        } else {
            app.parent().map(Path::to_path_buf).unwrap_or_default()
        };
        let read = |file: &str, what: &str| -> Result<Option<Source>, FileError> {
            let path = dir.join(file);
            if !path.is_file() {
                return Ok(None);
            }
            Source::read(&path, what).map(Some)
        };
        Ok(Assets {
            app_name: app_name(app),
            world: read(WORLD_FILE, "world")?,
            kb: read(KB_FILE, "KB")?,
            diagram: None,
        })
    }
}

/// The name of an application: its directory's (real) name, or the DM
/// file's stem.
pub fn app_name(app: &Path) -> String {
    let app = std::fs::canonicalize(app).unwrap_or_else(|_| app.to_path_buf());
    let name = if app.is_dir() {
        app.file_name()
    } else {
        app.file_stem()
    };
    name.map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "app".to_owned())
}

/// Where a run writes: the report (stdout), messages and test-mode action
/// renderings (stderr), and whether each is a terminal; and who else
/// watches its transitions (the live view of `sitlogc run --view`).
pub struct Streams {
    pub stdout: Box<dyn Write + Send>,
    pub stderr: Box<dyn Write + Send>,
    pub stdout_is_terminal: bool,
    pub stderr_is_terminal: bool,
    pub observer: Option<Box<dyn Observer + Send>>,
}

impl Streams {
    /// The process's own stdout and stderr.
    pub fn process() -> Streams {
        Streams {
            stdout_is_terminal: std::io::stdout().is_terminal(),
            stderr_is_terminal: std::io::stderr().is_terminal(),
            stdout: Box::new(std::io::stdout()),
            stderr: Box::new(std::io::stderr()),
            observer: None,
        }
    }
}

/// Runs `app` as `sitlogc run` does on the process's streams; returns the
/// exit status (0 ok, 1 run-time error, 2 usage or I/O problem).
///
/// SIGINT and SIGTERM stop the task at its next transition: the report
/// (status `interrupted`) is still printed and the trace closed; the exit
/// status is then 130 (SIGINT) or 143 (SIGTERM). A second signal ends the
/// process at once. The end of typed input (Ctrl-D at the prompt) stops it
/// the same way, with exit status 3 ([`crate::prompt`]).
pub fn execute<A: App>(app: &A, functions: Functions, args: &RunArgs, assets: &Assets) -> u8 {
    let interrupt = Interrupt::install();
    execute_interruptible(
        app,
        functions,
        args,
        assets,
        Streams::process(),
        Some(interrupt),
    )
}

/// Wraps the perception a run makes (the simulated user's, the script's or
/// the prompt's) in another: `sitlogc run --watch` lets a situation waiting
/// for input take it in a program that changed meanwhile.
pub type PerceptionWrap = Box<dyn FnOnce(Box<dyn Perception>) -> Box<dyn Perception>>;

/// [`execute`], with the run's perception wrapped by `wrap`.
pub fn execute_wrapped<A: App>(
    app: &A,
    functions: Functions,
    args: &RunArgs,
    assets: &Assets,
    wrap: PerceptionWrap,
) -> u8 {
    let interrupt = Interrupt::install();
    let streams = Streams::process();
    if args.view {
        return with_view(
            app,
            functions,
            args,
            assets,
            streams,
            Some(interrupt),
            Some(wrap),
        );
    }
    run_task(
        app,
        functions,
        args,
        assets,
        streams,
        Some(interrupt),
        None,
        Some(wrap),
    )
}

/// Counts transitions on the console (the progress indicator).
struct Progress<'a> {
    console: &'a SharedConsole,
}

impl Observer for Progress<'_> {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, _next: Option<Term>) {
        if let Ok(mut c) = self.console.lock() {
            c.tick(|| {
                format!(
                    "{}{} / {}",
                    "  ".repeat(depth.min(8)),
                    store.writeq(entry.dm),
                    store.writeq(entry.situation)
                )
            });
        }
    }
}

/// Several observers as one.
struct Fanout<'a>(Vec<&'a mut dyn Observer>);

impl Observer for Fanout<'_> {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>) {
        for o in &mut self.0 {
            o.transition(store, entry, depth, next);
        }
    }

    fn inspect(&mut self, machine: &mut sitlog_runtime::machine::Inspection<'_>) {
        for o in &mut self.0 {
            o.inspect(machine);
        }
    }
}

/// Makes a run's test-mode perception from the script's, if any.
pub type MakePerception = Box<dyn FnOnce(Option<Box<dyn Perception>>) -> Box<dyn Perception>>;

/// What `sitlogc debug` (sitlog-debug) adds to a run besides its observer
/// (which comes in [`Streams::observer`]).
pub struct DebugHooks {
    /// Makes the test-mode perception from the script's (`None` without
    /// `--script`); it replaces the prompt on stdin.
    pub perception: MakePerception,
    /// Given a look at the simulated world when the run has one.
    pub world: Box<dyn FnOnce(WorldProbe)>,
    /// When set, the run stops before its next transition (`quit`).
    pub stop: Arc<std::sync::atomic::AtomicBool>,
}

/// A look at the simulated world of a run (the debugger's `world`).
#[derive(Clone)]
pub struct WorldProbe {
    #[cfg(feature = "sim")]
    robot: crate::robot::Probe,
}

impl WorldProbe {
    /// The world's state now, one fact a line.
    pub fn describe(&self) -> String {
        #[cfg(feature = "sim")]
        {
            self.robot.describe()
        }
        #[cfg(not(feature = "sim"))]
        String::new()
    }
}

/// Runs `app` as [`execute_with`] does, with a debugger's [`DebugHooks`].
pub fn execute_debug<A: App>(
    app: &A,
    functions: Functions,
    args: &RunArgs,
    assets: &Assets,
    streams: Streams,
    hooks: DebugHooks,
) -> u8 {
    run_task(
        app,
        functions,
        args,
        assets,
        streams,
        None,
        Some(hooks),
        None,
    )
}

/// [`execute`] on the given streams, without signal handling.
pub fn execute_with<A: App>(
    app: &A,
    functions: Functions,
    args: &RunArgs,
    assets: &Assets,
    streams: Streams,
) -> u8 {
    execute_interruptible(app, functions, args, assets, streams, None)
}

/// `--view`: serves the diagram, waits for the page, runs the task with
/// the page following it, then stops the server.
#[cfg(feature = "view")]
fn with_view<A: App>(
    app: &A,
    functions: Functions,
    args: &RunArgs,
    assets: &Assets,
    mut streams: Streams,
    interrupt: Option<Interrupt>,
    wrap: Option<PerceptionWrap>,
) -> u8 {
    let diagram = match assets
        .diagram
        .as_deref()
        .map(sitlog_graph::Diagram::from_json)
    {
        Some(Ok(d)) => d,
        Some(Err(e)) => {
            let _ = writeln!(streams.stderr, "error: the task's diagram: {e}");
            return 2;
        }
        None => {
            let _ = writeln!(
                streams.stderr,
                "error: --view needs the program's diagram, and this task has none"
            );
            return 2;
        }
    };
    let view = match sitlog_view::View::start(diagram, args.view_port) {
        Ok(v) => v,
        Err(e) => {
            let _ = writeln!(
                streams.stderr,
                "error: cannot serve the live view on 127.0.0.1:{}: {e}",
                args.view_port
            );
            return 2;
        }
    };
    let _ = writeln!(
        streams.stderr,
        "live view at {} (the task starts when the page is open)",
        view.url()
    );
    let _ = streams.stderr.flush();
    view.wait_for_viewer(None);
    streams.observer = Some(Box::new(
        view.observer(std::time::Duration::from_millis(args.view_delay)),
    ));
    let code = run_task(app, functions, args, assets, streams, interrupt, None, wrap);
    let status = match code {
        0 => "ok",
        1 => "error",
        _ => "stopped",
    };
    view.finish(status, "", std::time::Duration::from_secs(3));
    code
}

#[cfg(not(feature = "view"))]
fn with_view<A: App>(
    _: &A,
    _: Functions,
    _: &RunArgs,
    _: &Assets,
    mut streams: Streams,
    _: Option<Interrupt>,
    _: Option<PerceptionWrap>,
) -> u8 {
    let _ = writeln!(
        streams.stderr,
        "error: --view: this build has no live view (feature `view` of sitlog-robot)"
    );
    2
}

/// The trace file of `--trace`: every write checked (the first error is
/// kept), flushed after each transition, synced to disk at the end.
struct TraceFile {
    inner: report::JsonTrace<std::io::BufWriter<std::fs::File>>,
}

impl Observer for TraceFile {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>) {
        self.inner.transition(store, entry, depth, next);
    }
}

impl TraceFile {
    /// Flushes and syncs; the first write error, if any.
    fn finish(self) -> std::io::Result<()> {
        let file = self
            .inner
            .finish()?
            .into_inner()
            .map_err(|e| e.into_error())?;
        match file.sync_all() {
            // Devices and pipes cannot be synced: nothing was lost.
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::InvalidInput | std::io::ErrorKind::Unsupported
                ) =>
            {
                Ok(())
            }
            r => r,
        }
    }
}

/// [`execute_with`], stopping between transitions when `interrupt` is set.
pub fn execute_interruptible<A: App>(
    app: &A,
    functions: Functions,
    args: &RunArgs,
    assets: &Assets,
    streams: Streams,
    interrupt: Option<Interrupt>,
) -> u8 {
    if args.view {
        return with_view(app, functions, args, assets, streams, interrupt, None);
    }
    run_task(app, functions, args, assets, streams, interrupt, None, None)
}

/// The run itself (the live view, if any, already set up).
#[allow(clippy::too_many_arguments)]
fn run_task<A: App>(
    app: &A,
    mut functions: Functions,
    args: &RunArgs,
    assets: &Assets,
    mut streams: Streams,
    interrupt: Option<Interrupt>,
    hooks: Option<DebugHooks>,
    wrap: Option<PerceptionWrap>,
) -> u8 {
    let (mut debug_perception, mut debug_world, debug_stop) = match hooks {
        Some(h) => (Some(h.perception), Some(h.world), Some(h.stop)),
        None => (None, None, None),
    };
    // Without the simulator there is no world to look at.
    #[cfg(not(feature = "sim"))]
    let _ = debug_world.take();
    macro_rules! fail {
        ($code:expr, $($msg:tt)*) => {{
            let _ = writeln!(streams.stderr, $($msg)*);
            return $code;
        }};
    }
    // The world, if any.
    let world: Option<Source> = if args.no_world {
        None
    } else if let Some(path) = &args.world {
        match Source::read(path, "world") {
            Ok(source) => Some(source),
            Err(e) => fail!(e.status, "{e}"),
        }
    } else {
        assets.world.clone()
    };
    if world.is_some() && args.script.is_some() {
        fail!(
            2,
            "error: --script gives test-mode inputs, but this run has a world; pass --no-world to run in test mode"
        );
    }
    let json = args.format == Format::Json;
    // The transcript: stdout before the text report, stderr with JSON.
    let with_world = world.is_some();
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

    // The KB.
    // A persisted KB is locked against other persisting processes for the
    // whole run (and temporary files of killed runs are removed).
    let mut _kb_lock = None;
    let kb_source = match &args.kb {
        Some(path) if args.kb_persist => match sitlog_kb::Kb::open_persistent(path) {
            Ok((kb, lock)) => {
                _kb_lock = Some(lock);
                Some((kb, Some(path.clone())))
            }
            Err(e) => fail!(if e.pos.is_some() { 1 } else { 2 }, "{e}"),
        },
        Some(path) => match sitlog_kb::Kb::load(path) {
            Ok(kb) => Some((kb, Some(path.clone()))),
            // A position means bad content (1); none, a file that cannot be read (2).
            Err(e) => fail!(if e.pos.is_some() { 1 } else { 2 }, "{e}"),
        },
        None => match &assets.kb {
            Some(src) => match sitlog_kb::Kb::parse(&src.text, &src.name) {
                Ok(kb) => Some((kb, None)),
                Err(e) => fail!(1, "{e}"),
            },
            None => None,
        },
    };
    if args.kb_persist && kb_source.as_ref().is_none_or(|(_, p)| p.is_none()) {
        fail!(
            2,
            "error: --kb-persist needs a KB file to write to: pass --kb FILE"
        );
    }
    if let Some((kb_value, path)) = kb_source {
        let persist = if args.kb_persist { path } else { None };
        let narrate = with_world.then(|| console.clone());
        kb::register_with(
            &mut functions,
            Arc::new(Mutex::new(kb_value)),
            persist,
            narrate,
        );
    }

    // Typed input (test mode without a script) ends the task cleanly at its
    // end (Ctrl-D): recorded in the run's interrupt (one of its own when
    // signals are not handled).
    let typed = world.is_none() && args.script.is_none();
    let ended: Option<Interrupt> = interrupt.clone().or_else(|| typed.then(Interrupt::new));
    // Perception and actions: the simulated robot, or test mode.
    let mut io: (Box<dyn Perception>, Box<dyn Actions>) = match &world {
        #[cfg(feature = "sim")]
        Some(world) => {
            match crate::robot::SimRobot::from_source(world, args.seed, console.clone()) {
                Ok(robot) => {
                    robot.register_inference(&mut functions, args.seed);
                    if let Some(give) = debug_world.take() {
                        give(WorldProbe {
                            robot: robot.probe(),
                        });
                    }
                    let (senses, effectors) = robot.split();
                    (Box::new(senses), Box::new(effectors))
                }
                // A world file that is not what the simulator reads: exit 2
                // (issue 15), like a missing one; bytes that are not UTF-8
                // were refused above with exit 1 (issue 23).
                Err(e) => fail!(2, "{e}"),
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
            let perception: Box<dyn Perception> = match (&args.script, debug_perception.take()) {
                (Some(path), debugger) => match Source::read(path, "script") {
                    Ok(s) => {
                        let script =
                            Box::new(ScriptPerception::new(s.name, s.text).with_limits(limits));
                        match debugger {
                            Some(make) => make(Some(script)),
                            None => script,
                        }
                    }
                    Err(e) => fail!(e.status, "{e}"),
                },
                // Typed input: line editing on a terminal; else read on a
                // thread of its own when a signal can stop the run, so that
                // the prompt sees it.
                (None, Some(make)) => make(None),
                (None, None) => {
                    let ended = ended.clone().unwrap_or_default();
                    let prompt: Box<dyn Perception> = match edited_prompt(limits, &ended) {
                        Some(p) => p,
                        None => match &interrupt {
                            Some(i) => Box::new(
                                PromptPerception::new(InterruptibleStdin::new(i.flag.clone()))
                                    .with_limits(limits),
                            ),
                            None => Box::new(
                                PromptPerception::new(std::io::stdin().lock()).with_limits(limits),
                            ),
                        },
                    };
                    Box::new(EndOfInputStops::new(prompt, ended))
                }
            };
            let actions = Box::new(TextActions::new(std::io::stderr(), app.basic_actions()));
            (perception, actions)
        }
    };

    if let Some(wrap) = wrap {
        let (perception, actions) = io;
        io = (wrap(perception), actions);
    }

    let mut trace = match &args.trace {
        Some(path) => match std::fs::File::create(path) {
            Ok(f) => Some(TraceFile {
                inner: report::JsonTrace::new(std::io::BufWriter::new(f)),
            }),
            Err(e) => fail!(2, "error: cannot create trace file {}: {e}", path.display()),
        },
        None => None,
    };
    let shows_progress = console.lock().map(|c| c.shows_progress()).unwrap_or(false);
    let mut progress_observer = Progress { console: &console };
    let mut watcher = streams.observer.take();
    let mut observers: Vec<&mut dyn Observer> = Vec::new();
    if let Some(t) = trace.as_mut() {
        observers.push(t);
    }
    if let Some(w) = watcher.as_mut() {
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
        ..Options::default()
    };
    functions.set_call_limits(args.call_limits());

    let result = run(
        app,
        &args.main,
        args.in_arg.as_deref(),
        options,
        functions,
        io.0.as_mut(),
        io.1.as_mut(),
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
    let report = match args.format {
        Format::Json => format!("{}\n", report::outcome_json(&store, &outcome)),
        Format::Text => report::outcome_text(&mut store, &outcome),
    };
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
        let by_input = outcome.interrupted && ended.as_ref().is_some_and(Interrupt::ended_by_input);
        if by_input {
            let place = match (&e.dm, &e.situation) {
                (Some(dm), Some(sit)) => format!(" while DM `{dm}` waited in situation `{sit}`"),
                _ => String::new(),
            };
            let _ = writeln!(
                streams.stderr,
                "stopped: the input ended (Ctrl-D){place}: the task did not finish (exit status {})",
                crate::interrupt::EXIT_END_OF_INPUT
            );
        } else {
            // Reported once, here (the report on stdout does not repeat it):
            // on the source when the program keeps it.
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

/// The prompt with line editing, when stdin and stderr are terminals (and
/// the `edit` feature is on).
#[cfg(feature = "edit")]
fn edited_prompt(limits: InputLimits, interrupt: &Interrupt) -> Option<Box<dyn Perception>> {
    if !(std::io::stdin().is_terminal() && std::io::stderr().is_terminal()) {
        return None;
    }
    crate::prompt::EditedPrompt::new(limits, interrupt.clone())
        .map(|p| Box::new(p) as Box<dyn Perception>)
}

#[cfg(not(feature = "edit"))]
fn edited_prompt(_: InputLimits, _: &Interrupt) -> Option<Box<dyn Perception>> {
    None
}

/// The command line of a compiled task: the options of `sitlogc run`.
/// Public so that a task built with `sitlogc build --debugger`
/// (`sitlog_debug::task_main`) takes the same options, plus its own.
#[derive(Parser, Debug)]
pub struct TaskCli {
    #[command(flatten)]
    pub run: RunArgs,
    /// Accepted so that a `sitlogc run` command line works unchanged; it
    /// changes nothing here: unresolved names were allowed or refused when
    /// the task was compiled (`sitlogc build --allow-unresolved`).
    #[arg(long)]
    pub allow_unresolved: bool,
}

/// The clap command of a compiled task whose command line is `C` (e.g.
/// [`TaskCli`]), named after the application; `more` is appended to its
/// description.
pub fn task_command<C: CommandFactory>(assets: &Assets, more: &str) -> clap::Command {
    let name = if assets.app_name.is_empty() {
        "task".to_owned()
    } else {
        assets.app_name.clone()
    };
    let about = format!(
        "The SitLog task `{name}`, compiled. Runs it on its world when it has one, else in test mode.\n\
         A compiled task does not reload when its sources change: it runs the program it was \
         compiled from (no reloading); compile again with `sitlogc build`, or run the sources \
         with `sitlogc run APP --watch`.{more}"
    );
    C::command()
        .name(name.clone())
        .bin_name(name)
        .about(about)
        .version(env!("CARGO_PKG_VERSION"))
}

/// Parses `std::env::args` with `command` (see [`task_command`]); on
/// `--help`, `--version` or a usage error prints it and gives the exit
/// status (0, or 2).
pub fn parse_task_args<C: FromArgMatches>(
    command: clap::Command,
) -> Result<C, std::process::ExitCode> {
    match command
        .try_get_matches()
        .and_then(|m| C::from_arg_matches(&m))
    {
        Ok(cli) => Ok(cli),
        Err(e) => {
            let _ = e.print();
            Err(match e.kind() {
                clap::error::ErrorKind::DisplayHelp | clap::error::ErrorKind::DisplayVersion => {
                    std::process::ExitCode::SUCCESS
                }
                _ => std::process::ExitCode::from(2),
            })
        }
    }
}

/// Runs `f` on a thread with a big stack (as `sitlogc` does); its exit
/// status (101 when it panicked).
pub fn on_big_stack(f: impl FnOnce() -> u8 + Send) -> std::process::ExitCode {
    let code = std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(256 * 1024 * 1024)
            .spawn_scoped(s, f)
            .map(|h| h.join().unwrap_or(101))
            .unwrap_or(101)
    });
    std::process::ExitCode::from(code)
}

/// The `main` of a compiled task: parses `std::env::args` (clap, the
/// options of `sitlogc run`, named after the application), runs on a thread
/// with a big stack (as `sitlogc` does), returns the exit status.
pub fn main<A: App>(app: &A, functions: Functions, assets: &Assets) -> std::process::ExitCode {
    let args = match parse_task_args::<TaskCli>(task_command::<TaskCli>(assets, "")) {
        Ok(cli) => cli.run,
        Err(code) => return code,
    };
    on_big_stack(|| execute(app, functions, &args, assets))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_command_line_works_unchanged() {
        let cli =
            TaskCli::try_parse_from(["t", "--allow-unresolved", "--kb", "k.kb", "--kb-persist"])
                .unwrap();
        assert!(cli.allow_unresolved);
        assert_eq!(cli.run.kb.as_deref(), Some(Path::new("k.kb")));
        assert!(cli.run.kb_persist);
    }

    #[test]
    fn options_parse() {
        let cli = TaskCli::try_parse_from([
            "t",
            "--main",
            "m(1)",
            "--in-arg=-3",
            "--format",
            "json",
            "--history",
            "none",
            "--script",
            "s.txt",
        ])
        .unwrap();
        let a = cli.run;
        assert_eq!(a.main, "m(1)");
        assert_eq!(a.in_arg.as_deref(), Some("-3"));
        assert_eq!(a.format, Format::Json);
        assert_eq!(a.history, HistoryMode::None);
        assert_eq!(a.script, Some(PathBuf::from("s.txt")));
        assert!(TaskCli::try_parse_from(["t", "--format", "xml"]).is_err());
        assert!(TaskCli::try_parse_from(["t", "--main"]).is_err());
        assert!(TaskCli::try_parse_from(["t", "app"]).is_err());
        assert!(TaskCli::try_parse_from(["t", "--world", "w", "--no-world"]).is_err());
    }
}
