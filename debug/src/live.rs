//! `sitlogc debug`: the REPL over a live run. The run is `sitlogc run`'s
//! ([`sitlog_robot::Runner`] with the debugger's hooks); the debugger is its observer
//! (stopping at transition boundaries, in [`Observer::inspect`]) and, in
//! test mode, its perception (asking for `input TERM` when the script has
//! no more inputs, or there is no script).

use crate::command::{self, Command, CommandSource, Line, Spec, PROMPT};
use crate::record::{self, Record, Unmatched};
use sitlog_robot::{Assets, DebugHooks, RunArgs, Runner, Streams, WorldProbe};
use sitlog_runtime::app::App;
use sitlog_runtime::history::Entry;
use sitlog_runtime::machine::{Inspection, Observer, Perceived, Perception};
use sitlog_runtime::testmode::InputLimits;
use sitlog_runtime::{Functions, Store, Term};
use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

/// Transitions kept for `history` (memory stays bounded on long runs).
const KEEP: usize = 50_000;

/// Where the run goes until it stops again.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Step,
    /// Stop at a transition at this depth or less.
    Next(usize),
    /// Stop at a transition above this depth.
    Finish(usize),
    Continue,
}

#[derive(Clone, Debug, PartialEq, Eq)]
enum State {
    Running,
    /// The commands file ended: the run goes on without stopping.
    Free,
    Quit,
    /// A bad line in the commands file (its message): exit 2.
    Failed(String),
}

/// What the REPL is stopped on.
enum Ctx<'a, 'b> {
    /// Before the run.
    Start,
    Machine(&'a mut Inspection<'b>),
    /// A perceptual situation waiting for input.
    Input(&'a mut Store),
}

/// How the REPL was left.
enum Resume {
    Go,
    Input(Term),
    Stop,
}

struct Live {
    commands: CommandSource,
    out: Box<dyn Write + Send>,
    breaks: Vec<(usize, Spec)>,
    next_break: usize,
    mode: Mode,
    /// The last transitions (at most 2 × [`KEEP`]), for `history` and
    /// breakpoints; `dropped` older ones were let go.
    records: Vec<Record>,
    dropped: usize,
    /// The inputs that met no expectation since the oldest record kept.
    unmatched: Vec<Unmatched>,
    world: Option<WorldProbe>,
    stop: Arc<AtomicBool>,
    state: State,
    limits: InputLimits,
    /// Set by Ctrl-C (interactive sessions): stop at the next transition.
    interrupt: Option<Arc<AtomicBool>>,
    /// The program's DMs and their situations' names (empty: unknown).
    names: Vec<(String, Vec<String>)>,
}

macro_rules! say {
    ($live:expr, $($arg:tt)*) => {{
        let _ = writeln!($live.out, $($arg)*);
    }};
}

impl Live {
    fn depth(ctx: &Ctx) -> Option<usize> {
        match ctx {
            Ctx::Machine(m) => Some(m.depth().saturating_sub(1)),
            _ => None,
        }
    }

    /// Reads and runs commands until one resumes the run.
    fn repl(&mut self, ctx: &mut Ctx) -> Resume {
        loop {
            let (text, line) = match self.commands.read(PROMPT, &mut *self.out) {
                Line::Text(t, n) => (t, n),
                Line::End => {
                    if self.commands.file_name().is_some() {
                        say!(
                            self,
                            "(end of the commands: the run goes on without stopping)"
                        );
                        self.state = State::Free;
                        return Resume::Go;
                    }
                    self.quit();
                    return Resume::Stop;
                }
            };
            let command = match command::parse(&text) {
                Ok(Some(c)) => c,
                Ok(None) => continue,
                Err(e) => {
                    if let (Some(name), Some(n)) = (self.commands.file_name(), line) {
                        self.state = State::Failed(format!("{name}:{n}: error: {e}"));
                        self.stop.store(true, Ordering::Relaxed);
                        return Resume::Stop;
                    }
                    say!(self, "error: {e}");
                    continue;
                }
            };
            if let Some(resume) = self.run_command(command, ctx) {
                return resume;
            }
        }
    }

    fn quit(&mut self) {
        self.state = State::Quit;
        self.stop.store(true, Ordering::Relaxed);
    }

    /// Runs one command; `Some` when it resumes the run.
    fn run_command(&mut self, command: Command, ctx: &mut Ctx) -> Option<Resume> {
        let waiting = matches!(ctx, Ctx::Input(_));
        let resume = |live: &mut Live, mode: Mode| {
            if waiting {
                say!(
                    live,
                    "the situation waits for input: answer with `input TERM` (or `quit`)"
                );
                return None;
            }
            live.mode = mode;
            Some(Resume::Go)
        };
        match command {
            Command::Step => resume(self, Mode::Step),
            Command::Next => match Self::depth(ctx) {
                Some(d) => resume(self, Mode::Next(d)),
                None => resume(self, Mode::Step),
            },
            Command::Finish => match Self::depth(ctx) {
                Some(0) => resume(self, Mode::Continue),
                Some(d) => resume(self, Mode::Finish(d)),
                None => resume(self, Mode::Step),
            },
            Command::Continue => resume(self, Mode::Continue),
            Command::Quit => {
                self.quit();
                Some(Resume::Stop)
            }
            Command::Break(None) => {
                if self.breaks.is_empty() {
                    say!(self, "no breakpoints");
                }
                for (n, spec) in &self.breaks {
                    let _ = writeln!(self.out, "{n}: {spec}");
                }
                None
            }
            Command::Break(Some(spec)) => {
                if let Some(problem) = crate::record::unknown_name(&self.names, &spec) {
                    say!(self, "{problem}: no breakpoint set");
                    return None;
                }
                self.next_break += 1;
                say!(self, "breakpoint {}: {spec}", self.next_break);
                self.breaks.push((self.next_break, spec));
                None
            }
            Command::Delete(n) => {
                match self.breaks.iter().position(|b| b.0 == n) {
                    Some(i) => {
                        let (_, spec) = self.breaks.remove(i);
                        say!(self, "deleted breakpoint {n}: {spec}");
                    }
                    None => say!(self, "there is no breakpoint {n}"),
                }
                None
            }
            Command::History(n) => {
                let text = record::history_with(
                    self.dropped,
                    &self.records,
                    &self.unmatched,
                    n.unwrap_or(10),
                );
                let _ = write!(self.out, "{text}");
                None
            }
            Command::World => {
                match &self.world {
                    Some(w) => {
                        let text = w.describe();
                        let _ = write!(self.out, "{text}");
                    }
                    None if matches!(ctx, Ctx::Start) => {
                        say!(self, "the world (if any) is made when the run starts")
                    }
                    None => say!(self, "this run has no world (test mode)"),
                }
                None
            }
            Command::Help => {
                let _ = write!(self.out, "{}", command::HELP);
                None
            }
            Command::Back | Command::Goto(_) | Command::Diff(_) => {
                say!(
                    self,
                    "a live run goes forwards only: record it with --trace and use `sitlogc replay`"
                );
                None
            }
            Command::Input(text) => {
                let Ctx::Input(store) = ctx else {
                    say!(self, "no situation is waiting for input");
                    return None;
                };
                match self.limits.read_term("the input", &text) {
                    Ok(clause) => Some(Resume::Input(store.from_clause(&clause).0)),
                    Err(e) => {
                        say!(self, "error: {e}");
                        None
                    }
                }
            }
            Command::Stack | Command::Pipe | Command::Vars(_) | Command::Print(_) => {
                match ctx {
                    Ctx::Machine(m) => self.inspect_command(command, m),
                    Ctx::Start => say!(self, "the run has not started: `step` first"),
                    Ctx::Input(_) => say!(
                        self,
                        "the machine is inside a situation waiting for input: `input TERM` first"
                    ),
                }
                None
            }
        }
    }

    fn inspect_command(&mut self, command: Command, m: &mut Inspection) {
        let top = m.depth().saturating_sub(1);
        match command {
            Command::Stack => {
                for i in (0..m.depth()).rev() {
                    if m.depth() - i > crate::replay::STACK_SHOWN {
                        say!(self, "... {} frames more, down to #0", i + 1);
                        break;
                    }
                    let dm = m.store.writeq(m.dm_id(i));
                    let at = match (i == top, self.records.last(), m.waiting_in(i)) {
                        (true, Some(r), _) => format!("  after {}", r.situation),
                        (false, _, Some(id)) => format!("  in {}", m.store.writeq(id)),
                        _ => String::new(),
                    };
                    say!(self, "#{i} {dm}{at}");
                }
            }
            Command::Pipe => {
                let pipe = m.store.writeq(m.pipe);
                say!(self, "{pipe}");
            }
            Command::Vars(frame) => {
                let i = frame.unwrap_or(top);
                if i >= m.depth() {
                    say!(self, "there is no frame {i} (frames 0 to {top}: `stack`)");
                    return;
                }
                let dm = m.store.writeq(m.dm_id(i));
                say!(self, "locals of #{i} {dm}:");
                let locals: Vec<String> = m
                    .locals(i)
                    .entries()
                    .iter()
                    .map(|&(n, v)| format!("  {n} = {}", m.store.writeq(v)))
                    .collect();
                self.list(&locals);
                say!(self, "globals:");
                let globals: Vec<String> = m
                    .globals
                    .entries()
                    .iter()
                    .map(|&(n, v)| format!("  {n} = {}", m.store.writeq(v)))
                    .collect();
                self.list(&globals);
            }
            Command::Print(text) => {
                let value = self.limits.read_term("the term", &text).and_then(|clause| {
                    let t = m.store.from_clause(&clause).0;
                    m.evaluate(top, t)
                });
                match value {
                    Ok(v) => say!(self, "{v}"),
                    Err(e) => say!(self, "error: {e}"),
                }
            }
            _ => {}
        }
    }

    fn list(&mut self, lines: &[String]) {
        if lines.is_empty() {
            say!(self, "  (none)");
        }
        for l in lines {
            say!(self, "{l}");
        }
    }

    /// Why the run stops after the last transition, if it does.
    fn stops(&self) -> Option<String> {
        let r = self.records.last()?;
        if let Some(flag) = &self.interrupt {
            if flag.swap(false, Ordering::SeqCst) {
                return Some("-- interrupted (Ctrl-C)".to_owned());
            }
        }
        let before = &self.records[..self.records.len() - 1];
        for (n, spec) in &self.breaks {
            let hit = record::hits(spec, before, r);
            if hit {
                return Some(format!("-- breakpoint {n} ({spec})"));
            }
        }
        let here = match self.mode {
            Mode::Step => true,
            Mode::Next(d) => r.depth <= d,
            Mode::Finish(d) => r.depth < d,
            Mode::Continue => false,
        };
        here.then(String::new)
    }
}

/// The debugger as the run's observer.
struct Watch(Arc<Mutex<Live>>);

impl Observer for Watch {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>) {
        let Ok(mut live) = self.0.lock() else { return };
        if live.records.len() >= 2 * KEEP {
            live.records.drain(..KEEP);
            live.dropped += KEEP;
            let dropped = live.dropped;
            live.unmatched.retain(|u| u.before >= dropped);
        }
        live.records.push(Record {
            dm: store.writeq(entry.dm),
            situation: store.writeq(entry.situation),
            expectation: store.writeq(entry.expectation),
            action: store.writeq(entry.action),
            depth,
            next: next.map(|n| store.writeq(n)),
        });
    }

    /// Kept for `history` and shown at once while the debugger watches.
    fn unmatched(&mut self, store: &Store, dm: Term, situation: Term, input: Term, depth: usize) {
        let Ok(mut live) = self.0.lock() else { return };
        let u = Unmatched {
            dm: store.writeq(dm),
            situation: store.writeq(situation),
            input: store.writeq(input),
            depth,
            before: live.dropped + live.records.len(),
        };
        if live.state == State::Running {
            say!(live, "{}", record::unnumbered(&u));
        }
        if live.unmatched.len() >= 2 * KEEP {
            live.unmatched.drain(..KEEP);
        }
        live.unmatched.push(u);
    }

    fn inspect(&mut self, machine: &mut Inspection<'_>) {
        let Ok(mut live) = self.0.lock() else { return };
        if live.state != State::Running {
            return;
        }
        if let Some(e) = machine.error {
            let Some(n) = live.breaks.iter().find(|b| b.1 == Spec::Error).map(|b| b.0) else {
                return;
            };
            say!(live, "-- breakpoint {n} (on error)");
            say!(live, "error: {e}");
            live.repl(&mut Ctx::Machine(machine));
            return;
        }
        let Some(why) = live.stops() else { return };
        if !why.is_empty() {
            say!(live, "{why}");
        }
        let n = live.records.len();
        let line = record::numbered(live.dropped + n, &live.records[n - 1]);
        say!(live, "{line}");
        live.repl(&mut Ctx::Machine(machine));
    }
}

/// The test-mode perception: the script's inputs, then the debugger's `input`.
struct Ask {
    script: Option<Box<dyn Perception>>,
    live: Arc<Mutex<Live>>,
}

impl Perception for Ask {
    fn perceive(
        &mut self,
        store: &mut Store,
        situation_type: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        if let Some(script) = &mut self.script {
            if let Perceived::Input(t) = script.perceive(store, situation_type, expectations)? {
                return Ok(Perceived::Input(t));
            }
        }
        let Ok(mut live) = self.live.lock() else {
            return Ok(Perceived::EndOfInput);
        };
        if live.state != State::Running {
            return Ok(Perceived::EndOfInput);
        }
        let exps: Vec<String> = expectations.iter().map(|&e| store.writeq(e)).collect();
        say!(
            live,
            "-- waiting for input ({}); expectations: {}",
            store.writeq(situation_type),
            exps.join(", ")
        );
        match live.repl(&mut Ctx::Input(store)) {
            Resume::Input(t) => Ok(Perceived::Input(t)),
            Resume::Go | Resume::Stop => Ok(Perceived::EndOfInput),
        }
    }
}

/// A run's output stream that goes quiet once the session has quit (or
/// failed): the run's end, report and "interrupted" error are not printed.
struct Gate {
    inner: Box<dyn Write + Send>,
    closed: Arc<AtomicBool>,
}

impl Write for Gate {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.closed.load(Ordering::Relaxed) {
            return Ok(buf.len());
        }
        self.inner.write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// `sitlogc debug`: runs `app` as `sitlogc run` does with `args`, under
/// the REPL reading `commands`; the debugger writes to `out`, a bad
/// commands file is reported on `err`. The exit status is the run's, 0
/// after `quit`, 2 for a bad line in a commands file. After `quit` (or a
/// bad line) the run stops at its next transition and prints nothing more.
#[allow(clippy::too_many_arguments)]
pub fn debug<A: App>(
    app: &A,
    functions: Functions,
    args: &RunArgs,
    assets: &Assets,
    mut streams: Streams,
    commands: CommandSource,
    out: Box<dyn Write + Send>,
    mut err: Box<dyn Write + Send>,
) -> u8 {
    let stop = Arc::new(AtomicBool::new(false));
    // At the terminal, Ctrl-C during a run stops it at its next transition
    // (a second one, before that, ends the process).
    let interrupt = match commands {
        CommandSource::Editor(_) => Some(sitlog_robot::interrupt::Interrupt::install().flag),
        CommandSource::File { .. } => None,
    };
    let live = Arc::new(Mutex::new(Live {
        interrupt,
        commands,
        out,
        breaks: Vec::new(),
        next_break: 0,
        mode: Mode::Step,
        records: Vec::new(),
        unmatched: Vec::new(),
        dropped: 0,
        world: None,
        stop: stop.clone(),
        state: State::Running,
        limits: args.input_limits(),
        names: app.names(),
    }));
    // Before the run: breakpoints, then `step`, `continue`...
    let started = {
        let Ok(mut l) = live.lock() else { return 2 };
        say!(
            l,
            "sitlog debugger: `{}` from {} (`help` lists the commands; the run starts with `step` or `continue`)",
            args.main,
            assets.app_name
        );
        l.repl(&mut Ctx::Start)
    };
    let code = match started {
        Resume::Stop => 0,
        _ => {
            // No progress indicator: it would tick over the prompt.
            streams.stdout_is_terminal = false;
            for stream in [&mut streams.stdout, &mut streams.stderr] {
                let inner = std::mem::replace(stream, Box::new(std::io::sink()));
                *stream = Box::new(Gate {
                    inner,
                    closed: stop.clone(),
                });
            }
            let for_perception = live.clone();
            let for_world = live.clone();
            let hooks = DebugHooks {
                observer: Box::new(Watch(live.clone())),
                perception: Box::new(move |script| {
                    Box::new(Ask {
                        script,
                        live: for_perception,
                    })
                }),
                world: Box::new(move |probe| {
                    if let Ok(mut l) = for_world.lock() {
                        l.world = Some(probe);
                    }
                }),
                stop,
            };
            // The debugger is the run's only watcher: no live view under it.
            let args = RunArgs {
                view: false,
                ..args.clone()
            };
            Runner::new(streams)
                .debugger(hooks)
                .run(app, functions, &args, assets)
        }
    };
    let Ok(mut l) = live.lock() else { return 2 };
    let _ = l.out.flush();
    match &l.state {
        State::Failed(message) => {
            let _ = writeln!(err, "{message}");
            2
        }
        State::Quit => 0,
        _ => code,
    }
}
