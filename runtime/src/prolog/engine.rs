//! The engine: [`PrologFunctions`] loads the prepared clauses into a
//! scryer-prolog machine on a thread of its own (the engine is not `Send`)
//! and calls user functions as queries sent to it, watched for their time
//! and memory limits ([`PrologOptions`]) and the run's stop flag (a
//! signal) from the calling thread; directives and calls run under the
//! inference limit inside the engine. A call's query holds its arguments
//! and the caller's variables; the task's history is written only when the
//! function's `get_history/1` asks the waiting caller for it
//! ([`Reply::History`]), in parts the engine's reader takes. Under the
//! legacy profile a predicate is loaded at its first call (a stub until
//! then, [`lazify`]), compiled static, and asserted (dynamic) instead once
//! a call changes or looks at its clauses; no call sees the difference.
//! Invariant (the trust model): loading only stores clauses; the
//! application's directives run at [`PrologFunctions::start`] (a run's
//! first transition, or the first call), after the run's permissions are
//! set in the engine.

use super::consult::{prepare, LineCursor, Prep, PrologLoadError, PrologSource, Redefinitions};
use super::legacy_kb::{rename_head, KbHost, NativeKb, NativeState, Wrapped, NATIVE_FILE};
use super::permissions;
use super::swi::{LIBRARIES, PRELUDE, PRELUDE_SWI, SWI_PREDICATES};
use super::translate::{drop_deep, from_prolog, read_reply, write_atom, Prepared, Writer};
use crate::functions::{CallLimits, FnCall, Functions, PROLOG_MAX_DEPTH};
use crate::plain::{self, PlainFns, PlainScan};
use crate::store::Store;
use crate::term::Term;
use crate::trust::{Confine, Trust};
use scryer_prolog::{
    InputStreamConfig, LeafAnswer, Machine, MachineBuilder, OutputStreamConfig, StreamConfig,
    Term as PTerm,
};
use sitlog_syntax::Atom;
use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};

/// Limits of one call (the defaults of an engine; a run's
/// [`Functions::set_call_limits`] overrides them).
///
/// The inference limit is the engine's own (`call_with_inference_limit/3`);
/// [`NO_INFERENCE_LIMIT`] is none (the original's rule, under `--legacy`).
/// Time and memory are watched from the calling thread, which waits for the
/// answer in short slices: a call that runs longer than `time_limit`, or
/// during which the process grows by more than `heap_limit` bytes (resident
/// memory, where the system tells it), is abandoned with an error naming the
/// limit. The engine thread is then left behind and every later call is an
/// error (the run ends on the first one anyway).
#[derive(Clone, Copy, Debug)]
pub struct PrologOptions {
    /// Inferences one function call may use before it is stopped with an
    /// error (runaway recursion).
    pub inference_limit: u64,
    /// Wall-clock time of one call.
    pub time_limit: std::time::Duration,
    /// Growth of the process's memory during one call, in bytes.
    pub heap_limit: u64,
}

impl Default for PrologOptions {
    fn default() -> Self {
        let d = CallLimits::default();
        PrologOptions {
            inference_limit: d.inferences,
            time_limit: d.time,
            heap_limit: d.heap_bytes,
        }
    }
}

impl From<CallLimits> for PrologOptions {
    fn from(l: CallLimits) -> PrologOptions {
        PrologOptions {
            inference_limit: l.inferences,
            time_limit: l.time,
            heap_limit: l.heap_bytes,
        }
    }
}

/// The inference limit that is none: a call runs without counting its
/// inferences against a limit (the engine still counts them, cheaper).
pub const NO_INFERENCE_LIMIT: u64 = u64::MAX;

/// Resident memory of this process in bytes, where the system tells it.
fn resident_bytes() -> Option<u64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: u64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    Some(pages * 4096)
}

/// What the engine thread is asked to do.
enum Request {
    /// Run the application's directives, code reaching the operating
    /// system allowed or not, under an inference limit, the thread first confined by the sandbox
    /// (with the directories the application may write into) if the run
    /// has one.
    Start(
        bool,
        u64,
        Option<(Confine, Vec<PathBuf>)>,
        mpsc::Sender<Vec<PrologLoadError>>,
    ),
    /// A query, with the run's input its `read/1` takes terms from; the
    /// engine answers on the channel, and asks there for the history while
    /// the query runs ([`Reply::History`]).
    Query(
        String,
        Option<crate::input::SharedInput>,
        mpsc::Sender<Reply>,
    ),
}

/// Directories the guards let code write into and load from (set at start).
type Roots = Arc<Mutex<Vec<PathBuf>>>;

/// The run's input that `read/1` takes terms from, as the running call's
/// [`Functions::input`] set it (none: `read/1` gives `end_of_file`).
type RunInput = Arc<Mutex<Option<crate::input::SharedInput>>>;

/// The KB host of the native KB layer, set when the application is loaded
/// (an engine built ahead has none yet).
type HostSlot = Arc<Mutex<Option<KbHost>>>;

/// An engine thread started ahead ([`PrologFunctions::prewarm`]): its
/// machine built with the prelude (and the legacy layer's clauses, if it
/// was given one), waiting for an application to load.
pub(super) struct Warm {
    setup: mpsc::Sender<Setup>,
    host: HostSlot,
    shared: Shared,
    layer: Option<WarmLayer>,
}

/// The query services and updates a [`NativeKb`] serves.
type Served = (Vec<(String, usize)>, Vec<(String, usize)>);

/// The legacy layer a warm engine prepares and asserts ahead
/// ([`PrologFunctions::prewarm_layer`]): a load whose first sources are
/// these, served the same way, continues from it.
struct WarmLayer {
    sources: Vec<PrologSource>,
    /// The natively served KB predicates (`None`: the layer as written).
    native: Option<Served>,
    /// The layer's sources read, sent before its clauses are asserted.
    prepped: mpsc::Receiver<Prepping>,
}

impl WarmLayer {
    fn serves(&self, layer: &[PrologSource], native: Option<&NativeKb>) -> bool {
        self.sources.len() == layer.len()
            && self
                .sources
                .iter()
                .zip(layer)
                .all(|(a, b)| a.name == b.name && a.dir == b.dir && a.text == b.text)
            && self.native == native.map(|n| (n.queries.clone(), n.updates.clone()))
    }
}

/// The sources read so far ([`prepare`]'s state): a warm engine reads the
/// legacy layer ahead, the load then reads the application's files after it.
struct Prepping {
    prepared: Vec<Prepared>,
    errors: Vec<PrologLoadError>,
    defined: HashSet<(Atom, usize)>,
    seen: HashSet<PathBuf>,
    outside: Vec<(PathBuf, PrologLoadError)>,
    native: Option<NativeState>,
    redefinitions: Option<Redefinitions>,
    /// A file names a call that changes clauses as data
    /// (`Prep::touching`): the layer is then loaded whole.
    touching: bool,
    /// The plain functions read so far (none under the legacy profile).
    plain: Option<PlainScan>,
}

impl Prepping {
    fn new(native: Option<&NativeKb>, legacy: bool) -> Prepping {
        Prepping {
            prepared: Vec::new(),
            errors: Vec::new(),
            defined: HashSet::new(),
            seen: HashSet::new(),
            outside: Vec::new(),
            native: native.map(NativeState::new),
            redefinitions: legacy.then(Redefinitions::default),
            touching: false,
            plain: (!legacy && native.is_none()).then(PlainScan::default),
        }
    }

    /// Reads `sources[from..]`, the first `layer` of them being the legacy
    /// layer (served natively if `native` was given).
    fn add(&mut self, sources: &[PrologSource], from: usize, layer: usize) {
        for (i, s) in sources.iter().enumerate().skip(from) {
            if let Some(n) = self.native.as_mut() {
                n.in_layer = i < layer;
            }
            let mut cx = Prep {
                out: &mut self.prepared,
                defined: &mut self.defined,
                errors: &mut self.errors,
                seen: &mut self.seen,
                outside: &mut self.outside,
                embedded: sources,
                native: self.native.as_mut(),
                redefine: self.redefinitions.as_mut(),
                touching: &mut self.touching,
                plain: self.plain.as_mut(),
            };
            prepare(s, &mut cx, 0);
        }
    }

    fn dropped(&self) -> HashSet<usize> {
        self.redefinitions
            .as_ref()
            .map(|r| r.dropped().clone())
            .unwrap_or_default()
    }
}

/// The legacy layer's clauses asserted ahead by a warm engine: their
/// texts and the engine's refusals, by index in the layer's prepared
/// clauses.
struct LayerLoaded {
    clauses: Vec<(usize, String)>,
    errors: Vec<(usize, PrologLoadError)>,
}

/// What of the application's prepared clauses a warm engine asserted
/// ahead: the first `kept` (the layer's, less those a later file
/// redefines), and the layer's clauses to retract (by index in the
/// layer's prepared clauses), redefined by the application's files.
struct Preloaded {
    kept: usize,
    drop: HashSet<usize>,
}

/// What a warm engine thread gets to load its application and serve it.
struct Setup {
    prepared: Vec<Prepared>,
    preloaded: Option<Preloaded>,
    /// The layer's predicates a KB handle can reach (`kb_reach`): asserted
    /// ahead under their own name, they are wrapped ([`wrap_ahead`]).
    wrapped: Vec<Wrapped>,
    /// The application's files name a call that changes clauses as data
    /// (`Prep::touching`): the layer's predicates still waiting for their
    /// first call are loaded before it starts.
    load_all: bool,
    rx: mpsc::Receiver<Request>,
    ready: mpsc::Sender<Vec<PrologLoadError>>,
}

/// The engine built ahead, if any; the next load takes it.
static WARM: Mutex<Option<Warm>> = Mutex::new(None);

/// The engine thread's stack: its reader and compiler recurse, so room for
/// terms `PROLOG_MAX_DEPTH` deep in a debug build (reserved, not used).
const ENGINE_STACK: usize = 512 << 20;

/// What the engine thread sends back for a query.
enum Reply {
    /// The query's answer.
    Answer(Result<Option<PTerm>, String>),
    /// `get_history/1` in the running query asks for the history from the
    /// element given on (the caller, waiting for the answer, writes that
    /// part and sends it back).
    History(usize, mpsc::Sender<String>),
}

/// Where the running query's `get_history/1` asks for the history: its
/// reply channel while it runs.
type HistoryLink = Arc<Mutex<Option<mpsc::Sender<Reply>>>>;

/// What the engine thread shares with the handle: the trust roots, the
/// run's input and the running query's history link.
#[derive(Clone)]
struct Shared {
    roots: Roots,
    input: RunInput,
    history: HistoryLink,
    lazy: LazyStore,
    statics: StaticStore,
    direct: DirectStore,
}

/// The clauses of the lazily loaded predicates compiled static, by their
/// number in the [`LazyStore`], kept for the engine to assert them if a
/// call changes or looks at them ([`unstatic_reply`]).
type StaticStore = Arc<Mutex<HashMap<usize, Vec<String>>>>;

/// The wrapped predicates of the native KB layer whose clauses call their
/// layer's clauses directly (`Wrapped::alts`), numbered as their
/// `'$sitlog_direct'/3` facts: the name and arity of those clauses'
/// predicate (`$legacy_P`) and its clauses as written, asked for by a `D`
/// request when a clause is asserted for the predicate at run time.
type DirectStore = Arc<Mutex<Vec<(Atom, usize, Vec<String>)>>>;

impl Shared {
    fn new(roots: Roots) -> Shared {
        Shared {
            roots,
            input: Arc::new(Mutex::new(None)),
            history: Arc::new(Mutex::new(None)),
            lazy: Arc::new(Mutex::new(Vec::new())),
            statics: Arc::new(Mutex::new(HashMap::new())),
            direct: Arc::new(Mutex::new(Vec::new())),
        }
    }
}

/// The legacy layer's predicates asserted at their first call
/// ([`lazify`]), by number: name, arity and clauses (canonical text, in
/// order), taken when the engine asks for them (`L` requests).
type LazyStore = Arc<Mutex<Vec<Option<LazyPred>>>>;

struct LazyPred {
    name: Atom,
    arity: usize,
    clauses: Vec<String>,
}

/// The application's Prolog user functions, running in an embedded engine.
/// Cheap to clone (a handle to the engine thread).
#[derive(Clone)]
pub struct PrologFunctions {
    inner: Arc<Inner>,
}

struct Inner {
    tx: Mutex<mpsc::Sender<Request>>,
    /// Why the engine was abandoned (a call over its time or memory limit).
    abandoned: Mutex<Option<String>>,
    /// Predicates defined by the application's clauses.
    defined: HashSet<(Atom, usize)>,
    options: PrologOptions,
    /// The outcome of [`PrologFunctions::start`], once it ran.
    started: Mutex<Option<Result<(), Vec<PrologLoadError>>>>,
    /// `consult/1` directives naming a file outside the application: the
    /// file and the refusal (unless the run's trust roots hold the file).
    outside: Vec<(PathBuf, PrologLoadError)>,
    /// Directories of the application's Prolog files.
    source_dirs: Vec<PathBuf>,
    roots: Roots,
    /// The native KB layer's host (`--legacy-kb native`): a call's answer
    /// never gives the caller a handle ([`unhandle`]).
    kb_host: Option<KbHost>,
    /// The application's plain functions, run natively where they can
    /// be (`plain`).
    plain: PlainFns,
    /// Started without an error and not abandoned since: what
    /// `plain_vals` reads instead of both locks (and a compiled plain
    /// function, given it by `set_compiled`).
    plain_live: Arc<AtomicBool>,
}

impl std::fmt::Debug for PrologFunctions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PrologFunctions")
            .field("defined", &self.inner.defined.len())
            .finish()
    }
}

impl PrologFunctions {
    /// Reads `sources` (in order: templates.pl, then user_functions.pl),
    /// starts the engine, loads the prelude and the clauses and runs the
    /// directives ([`load_with`](Self::load_with) then
    /// [`start`](Self::start) with nothing of the operating system
    /// allowed). Every problem is reported, with its position.
    pub fn load(
        sources: &[PrologSource],
        options: PrologOptions,
    ) -> Result<PrologFunctions, Vec<PrologLoadError>> {
        let warm = WARM.lock().ok().and_then(|mut w| w.take());
        let (engine, mut errors) = Self::spawn_from(warm, sources, options, 0, None)?;
        if let Err(e) = engine.start(&Trust::default()) {
            errors.extend(e);
        }
        if errors.is_empty() {
            Ok(engine)
        } else {
            errors.sort_by(|a, b| (&a.file, a.line, a.col).cmp(&(&b.file, b.line, b.col)));
            Err(errors)
        }
    }

    /// Reads `sources`, starts the engine and stores the clauses, the
    /// first `layer` sources being the legacy profile's Prolog layer of the
    /// original, its KB layer served by `native` if given (see
    /// [`NativeKb`]). With a layer, a file that defines a predicate again
    /// replaces what an earlier file defined, as SWI-Prolog's `consult/1`
    /// does (the original's apps rely on it). No application code runs:
    /// the directives wait for [`start`](Self::start).
    pub fn load_with(
        sources: &[PrologSource],
        options: PrologOptions,
        layer: usize,
        native: Option<NativeKb>,
    ) -> Result<PrologFunctions, Vec<PrologLoadError>> {
        let warm = WARM.lock().ok().and_then(|mut w| w.take());
        match Self::spawn_from(warm, sources, options, layer, native)? {
            (engine, errors) if errors.is_empty() => Ok(engine),
            (_, errors) => Err(errors),
        }
    }

    /// [`load_with`](Self::load_with) on `warm` (an engine built ahead, if
    /// it serves this load; else one built now), the clauses the engine
    /// refused given beside the engine.
    pub(super) fn spawn_from(
        mut warm: Option<Warm>,
        sources: &[PrologSource],
        options: PrologOptions,
        layer: usize,
        native: Option<NativeKb>,
    ) -> Result<(PrologFunctions, Vec<PrologLoadError>), Vec<PrologLoadError>> {
        // The engine built ahead's legacy layer, read (and being asserted) ahead, if this load's
        // first sources are that layer; an engine that holds another
        // layer's clauses is not used.
        let mut ahead = None;
        if let Some(l) = warm.as_mut().and_then(|w| w.layer.take()) {
            if layer <= sources.len() && l.serves(&sources[..layer], native.as_ref()) {
                ahead = l.prepped.recv().ok();
            }
            if ahead.is_none() {
                warm = None;
            }
        }
        let (mut st, from, base) = match ahead {
            Some(p) => {
                let base = (p.prepared.len(), p.dropped());
                (p, layer, Some(base))
            }
            None => (Prepping::new(native.as_ref(), layer > 0), 0, None),
        };
        st.add(sources, from, layer);
        // The layer's clauses asserted ahead that the application's files
        // redefine are retracted before its clauses are added.
        let preloaded = base.map(|(n, before)| {
            let all = st.dropped();
            Preloaded {
                kept: n - all.iter().filter(|&&i| i < n).count(),
                drop: all
                    .into_iter()
                    .filter(|i| *i < n && !before.contains(i))
                    .collect(),
            }
        });
        let Prepping {
            mut prepared,
            errors,
            defined,
            outside,
            native: native_state,
            redefinitions,
            touching,
            plain,
            ..
        } = st;
        let plain = match plain {
            Some(p) if layer == 0 && !touching => p.finish(),
            _ => PlainFns::default(),
        };
        if let Some(r) = &redefinitions {
            r.apply(&mut prepared);
        }
        let wrapped = match native_state {
            Some(st) => st.finish(&mut prepared, touching),
            None => Vec::new(),
        };
        if touching {
            for p in &mut prepared {
                p.lazy = false;
            }
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        let host = native.map(|n| n.host);
        let kb_host = host.clone();
        let source_dirs: Vec<PathBuf> = sources.iter().filter_map(|s| s.dir.clone()).collect();
        let (tx, rx) = mpsc::channel::<Request>();
        let (ready_tx, ready_rx) = mpsc::channel();
        let mut setup = Setup {
            prepared,
            preloaded,
            wrapped,
            load_all: touching,
            rx,
            ready: ready_tx,
        };
        let roots = 'engine: {
            if let Some(w) = warm {
                if let Ok(mut h) = w.host.lock() {
                    *h = host.clone();
                }
                if let Ok(mut r) = w.shared.roots.lock() {
                    r.clone_from(&source_dirs);
                }
                match w.setup.send(setup) {
                    Ok(()) => break 'engine w.shared.roots,
                    // its thread is gone: one built now, with every clause
                    Err(mpsc::SendError(back)) => setup = back,
                }
                setup.preloaded = None;
            }
            let roots: Roots = Arc::new(Mutex::new(source_dirs.clone()));
            let shared = Shared::new(roots.clone());
            let host: HostSlot = Arc::new(Mutex::new(host));
            spawn_engine(host, shared, || (), move |_, ()| Some((setup, None))).map_err(|e| {
                vec![PrologLoadError {
                    file: "<engine>".into(),
                    line: 0,
                    col: 0,
                    message: format!("cannot start the Prolog engine thread: {e}"),
                }]
            })?;
            roots
        };
        Ok(PrologFunctions::handle(
            roots,
            tx,
            ready_rx,
            defined,
            options,
            outside,
            source_dirs,
            kb_host,
            plain,
        ))
    }

    /// Starts, ahead of [`load_with`](Self::load_with), an engine thread
    /// that builds the machine every application's engine starts from (the
    /// engine's libraries and the prelude: most of its start-up), so that
    /// it runs while the caller reads and checks the application; the next
    /// load takes it. Does nothing when one is waiting already.
    pub fn prewarm() {
        Self::prewarm_with(None);
    }

    /// [`prewarm`](Self::prewarm), the engine also reading `layer` (the
    /// legacy profile's Prolog layer of the original, its KB layer served
    /// by `native` if given) and asserting its clauses (1,720 for the
    /// original's: most of a small `--legacy` run's start after the
    /// engine's own) while the caller checks the application. A
    /// [`load_with`](Self::load_with) whose first `layer` sources are these,
    /// served the same way, takes it and reads only the application's
    /// files; a file of the application that redefines a predicate of the
    /// layer then has the layer's clauses retracted before its own are
    /// added (SWI-Prolog's rule, as without this). Another load does not
    /// take it. No directive runs ahead.
    pub fn prewarm_layer(layer: Vec<PrologSource>, native: Option<NativeKb>) {
        Self::prewarm_with(Some((layer, native)));
    }

    fn prewarm_with(layer: Option<(Vec<PrologSource>, Option<NativeKb>)>) {
        let Ok(mut slot) = WARM.lock() else {
            return;
        };
        if slot.is_none() {
            *slot = Self::warm(layer);
        }
    }

    /// An engine thread started ahead ([`prewarm_with`](Self::prewarm_with)).
    pub(super) fn warm(layer: Option<(Vec<PrologSource>, Option<NativeKb>)>) -> Option<Warm> {
        let host: HostSlot = Arc::new(Mutex::new(None));
        let shared = Shared::new(Arc::new(Mutex::new(Vec::new())));
        let (tx, setup_rx) = mpsc::channel::<Setup>();
        let (prepped_tx, prepped) = mpsc::channel();
        let warm_layer = layer.as_ref().map(|(sources, native)| WarmLayer {
            sources: sources.clone(),
            native: native
                .as_ref()
                .map(|n| (n.queries.clone(), n.updates.clone())),
            prepped,
        });
        // The layer is read first (the load waits for what was read, not
        // for the machine), its clauses asserted once the machine is built.
        let read = move || {
            layer.map(|(sources, native)| read_layer(&sources, native.as_ref(), &prepped_tx))
        };
        let lazy = shared.lazy.clone();
        let spawned = spawn_engine(
            host.clone(),
            shared.clone(),
            read,
            move |machine, clauses| {
                let loaded = clauses.map(|c| assert_layer(machine, c, &lazy));
                setup_rx.recv().ok().map(|s| (s, loaded))
            },
        );
        spawned.ok().map(|_| Warm {
            setup: tx,
            host,
            shared,
            layer: warm_layer,
        })
    }

    /// The handle of an engine thread loading its application: waits for
    /// its load errors.
    #[allow(clippy::too_many_arguments)]
    fn handle(
        roots: Roots,
        tx: mpsc::Sender<Request>,
        ready_rx: mpsc::Receiver<Vec<PrologLoadError>>,
        defined: HashSet<(Atom, usize)>,
        options: PrologOptions,
        outside: Vec<(PathBuf, PrologLoadError)>,
        source_dirs: Vec<PathBuf>,
        kb_host: Option<KbHost>,
        plain: PlainFns,
    ) -> (PrologFunctions, Vec<PrologLoadError>) {
        let load_errors = ready_rx.recv().unwrap_or_else(|_| {
            vec![PrologLoadError {
                file: "<engine>".into(),
                line: 0,
                col: 0,
                message: "the Prolog engine stopped while loading".into(),
            }]
        });
        let engine = PrologFunctions {
            inner: Arc::new(Inner {
                tx: Mutex::new(tx),
                abandoned: Mutex::new(None),
                defined,
                options,
                started: Mutex::new(None),
                outside,
                source_dirs,
                roots,
                kb_host,
                plain,
                plain_live: Arc::new(AtomicBool::new(false)),
            }),
        };
        (engine, load_errors)
    }

    /// Runs the application's directives, once (later calls give the first
    /// outcome), with what `trust` allows of the operating system: without
    /// `--allow-os` a `consult/1` of a file outside the application is
    /// refused here, and the guards refuse shell, processes, sockets and
    /// writes outside the application. A refusal or a failing
    /// directive is an error at the directive's position.
    pub fn start(&self, trust: &Trust) -> Result<(), Vec<PrologLoadError>> {
        self.start_with(trust, None, None)
    }

    /// [`start`](Self::start) under `limits` (a run's call limits, else the
    /// engine's): the directives together run under the inference, time
    /// and memory limits of one call, and are abandoned when `stop` is set
    /// (issue 38: `:- loop.` is stopped, by its limits or the first signal).
    pub fn start_with(
        &self,
        trust: &Trust,
        limits: Option<CallLimits>,
        stop: Option<&AtomicBool>,
    ) -> Result<(), Vec<PrologLoadError>> {
        let mut started = self
            .inner
            .started
            .lock()
            .map_err(|_| vec![engine_error("the Prolog engine is poisoned")])?;
        if let Some(outcome) = &*started {
            return outcome.clone();
        }
        let options = limits.map_or(self.inner.options, PrologOptions::from);
        let outcome = self.start_now(trust, options, stop);
        *started = Some(outcome.clone());
        // Set under the lock: no call can be abandoned before it.
        let live = outcome.is_ok() && self.inner.abandoned.lock().is_ok_and(|a| a.is_none());
        self.inner.plain_live.store(live, Ordering::Release);
        outcome
    }

    /// [`start_with`](Self::start_with) with what a run's registry holds.
    fn start_from(&self, functions: &Functions) -> Result<(), Vec<PrologLoadError>> {
        self.start_with(functions.trust(), functions.call_limits(), functions.stop())
    }

    fn start_now(
        &self,
        trust: &Trust,
        options: PrologOptions,
        stop: Option<&AtomicBool>,
    ) -> Result<(), Vec<PrologLoadError>> {
        if !trust.allow_os {
            let refused: Vec<PrologLoadError> = self
                .inner
                .outside
                .iter()
                .filter(|(path, _)| !Trust::inside(path, &trust.roots))
                .map(|(_, e)| e.clone())
                .collect();
            if !refused.is_empty() {
                return Err(refused);
            }
        }
        let roots = permissions::roots(&self.inner.source_dirs, trust);
        if let Ok(mut r) = self.inner.roots.lock() {
            r.clone_from(&roots);
        }
        let confine = trust.confine.clone().map(|c| (c, roots));
        if trust.allow_os {
            crate::trust::default_shell();
        }
        let (tx, rx) = mpsc::channel();
        self.inner
            .tx
            .lock()
            .map_err(|_| vec![engine_error("the Prolog engine is poisoned")])?
            .send(Request::Start(
                trust.allow_os,
                options.inference_limit,
                confine,
                tx,
            ))
            .map_err(|_| vec![engine_error("the Prolog engine has stopped")])?;
        let errors = match self.watch(&rx, options, stop, "the application's directives") {
            Ok(errors) => errors,
            Err(message) => vec![engine_error(&message)],
        };
        if errors.is_empty() {
            Ok(())
        } else {
            Err(errors)
        }
    }

    /// Whether the application defines `name/arity` in Prolog.
    pub fn defines(&self, name: Atom, arity: usize) -> bool {
        self.inner.defined.contains(&(name, arity))
    }

    /// Installs these functions as the fallback of `functions`. Where the
    /// application defines a function in Prolog that is also registered in
    /// Rust (e.g. the standard `when/3`), the application's definition wins:
    /// it is what the author wrote and what the original runs. Names Prolog
    /// does not define stay as they are.
    ///
    /// A call of a plain function (`plain`) runs natively when it can (the
    /// engine runs the rest, so that results and errors are the engine's).
    pub fn install(&self, functions: &mut Functions) {
        self.install_with(functions, true)
    }

    /// [`install`](Self::install); with `plain` false every call is a query
    /// of the engine (the tests compare both paths).
    pub fn install_with(&self, functions: &mut Functions, plain: bool) {
        for &(name, arity) in &self.inner.defined {
            functions.remove(name, arity);
        }
        let me = self.clone();
        functions.set_fallback(move |call, name, args| {
            if !me.defines(name, args.len()) {
                return None;
            }
            // A call before the run's start (a debugger's evaluation) starts it.
            if let Err(errors) = me.start_from(call.functions) {
                return Some(Err(show_errors(&errors)));
            }
            if plain {
                if let Some(v) = me.plain_call(call, name, args) {
                    return Some(Ok(v));
                }
            }
            Some(me.call(call, name, args))
        });
        if plain && self.inner.plain.keys().next().is_some() {
            let me = self.clone();
            functions.set_native(move |functions, store, globals, name, args| {
                me.plain_vals(functions, store, globals, name, args)
            });
            // A function compiled from a plain form runs as compiled where
            // the form is this engine's (its fingerprint) and a call of it
            // runs natively under the run's inference limit.
            let me = self.clone();
            functions.set_compiled(move |functions, name, arity, fingerprint| {
                let limit = functions
                    .call_limits()
                    .map_or(me.inner.options.inference_limit, |l| l.inferences);
                me.inner
                    .plain
                    .compiled_matches(name, arity, fingerprint, limit)
                    .then(|| me.inner.plain_live.clone())
            });
        }
        let me = self.clone();
        functions.set_start(move |functions| me.start_from(functions).map_err(|e| show_errors(&e)));
    }

    /// The application's functions that run natively when they can
    /// (`plain`), by name and arity, sorted.
    pub fn plain_functions(&self) -> Vec<(Atom, usize)> {
        let mut keys: Vec<(Atom, usize)> = self.inner.plain.keys().collect();
        keys.sort_by(|a, b| (a.0.as_str(), a.1).cmp(&(b.0.as_str(), b.1)));
        keys
    }

    /// The value of a call of a plain function run natively, if it runs so
    /// (`None`: the engine runs it): never on an engine already abandoned
    /// (its calls are errors).
    fn plain_call(&self, call: &mut FnCall<'_>, name: Atom, args: &[Term]) -> Option<Term> {
        let limit = call
            .functions
            .call_limits()
            .map_or(self.inner.options.inference_limit, |l| l.inferences);
        let v = self.inner.plain.call(call.store, name, args, limit)?;
        // The caller's variables go with a query: one too deep for the
        // engine is its error (`call`), not the native form's to skip.
        let store: &Store = call.store;
        let shallow = [&*call.locals, &*call.globals].iter().all(|vars| {
            vars.entries()
                .iter()
                .all(|&(_, v)| plain::sure(store, v, false))
        });
        if !shallow {
            return None;
        }
        match self.inner.abandoned.lock() {
            Ok(a) if a.is_none() => Some(v),
            _ => None,
        }
    }

    /// [`plain_call`](Self::plain_call) on native values (`Cx::nat_plain`,
    /// through [`Functions::call_native`]): the value if the call runs
    /// natively, `None` for the term path (which starts the engine on a
    /// call before the run's start, and decides the rest). The same checks
    /// as the term path's: the registry (`call_native`), the inference
    /// limit, the caller's variables (the globals: the caller has no
    /// locals), the engine started and not abandoned (`plain_live`). A plain function is one the
    /// application defines (its clauses are the application's), so
    /// `defines` holds of it.
    fn plain_vals(
        &self,
        functions: &Functions,
        store: &Store,
        globals: &crate::vars::Vars,
        name: Atom,
        args: &[crate::native::Val],
    ) -> Option<crate::native::Val> {
        if !self.inner.plain_live.load(Ordering::Acquire) {
            return None;
        }
        let limit = functions
            .call_limits()
            .map_or(self.inner.options.inference_limit, |l| l.inferences);
        let v = self.inner.plain.call_vals(name, args, limit)?;
        let shallow = globals
            .entries()
            .iter()
            .all(|&(_, v)| plain::sure(store, v, false));
        // Abandoned meanwhile (by another run sharing the engine): its
        // calls are errors.
        (shallow && self.inner.plain_live.load(Ordering::Acquire)).then_some(v)
    }

    /// Runs a raw query (for tests and tools): the first answer's binding
    /// of `Result`, `None` on failure.
    pub fn query_raw(&self, query: &str) -> Result<Option<String>, String> {
        self.ask(query.to_owned(), self.inner.options, None, "the query")
            .map(|a| a.map(|t| format!("{t:?}")))
    }

    /// Sends `query` and waits for its answer within the time and memory
    /// limits of `options` (and until `stop` is set); `what` names the call
    /// in errors.
    pub(super) fn ask(
        &self,
        query: String,
        options: PrologOptions,
        stop: Option<&AtomicBool>,
        what: &str,
    ) -> Result<Option<PTerm>, String> {
        self.ask_with(query, None, options, stop, what, &mut |_| {
            NO_HISTORY.to_owned()
        })
    }

    /// [`ask`](Self::ask) with the input `read/1` takes terms from (set on
    /// the engine thread with the query, so runs sharing one engine each
    /// read their own), and `history` writing the part of the history from
    /// an element on that `get_history/1` asks for, if the query calls it
    /// ([`history_part`]).
    fn ask_with(
        &self,
        query: String,
        input: Option<crate::input::SharedInput>,
        options: PrologOptions,
        stop: Option<&AtomicBool>,
        what: &str,
        history: &mut dyn FnMut(usize) -> String,
    ) -> Result<Option<PTerm>, String> {
        if let Some(why) = self.inner.abandoned.lock().ok().and_then(|a| a.clone()) {
            return Err(format!("the Prolog engine is stopped: {why}"));
        }
        let (tx, rx) = mpsc::channel();
        self.inner
            .tx
            .lock()
            .map_err(|_| "the Prolog engine is poisoned".to_owned())?
            .send(Request::Query(query, input, tx))
            .map_err(|_| "the Prolog engine has stopped".to_owned())?;
        self.watch_with(&rx, options, stop, what, |reply| match reply {
            Reply::Answer(answer) => Some(answer),
            Reply::History(from, back) => {
                let _ = back.send(history(from));
                None
            }
        })?
    }

    /// Waits for the engine's answer on `rx` within the time and memory
    /// limits of `options`; over one, the engine is abandoned and the
    /// error names the limit (`what` the call). The same when `stop` is set
    /// (a signal: the run ends, reported as interrupted).
    fn watch<T>(
        &self,
        rx: &mpsc::Receiver<T>,
        options: PrologOptions,
        stop: Option<&AtomicBool>,
        what: &str,
    ) -> Result<T, String> {
        self.watch_with(rx, options, stop, what, Some)
    }

    /// [`watch`](Self::watch), each message given to `take`: `None` (a
    /// request it served) waits on, within the same limits.
    fn watch_with<T, R>(
        &self,
        rx: &mpsc::Receiver<T>,
        options: PrologOptions,
        stop: Option<&AtomicBool>,
        what: &str,
        mut take: impl FnMut(T) -> Option<R>,
    ) -> Result<R, String> {
        let start = std::time::Instant::now();
        let rss0 = resident_bytes();
        let slice = std::time::Duration::from_millis(10);
        loop {
            match rx.recv_timeout(slice) {
                Ok(message) => {
                    if let Some(answer) = take(message) {
                        return Ok(answer);
                    }
                }
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    return Err("the Prolog engine has stopped".to_owned())
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {}
            }
            let over = if stop.is_some_and(|s| s.load(Ordering::SeqCst)) {
                Some(format!(
                    "interrupted (the run was stopped by a signal during {what})"
                ))
            } else if start.elapsed() > options.time_limit {
                Some(format!(
                    "{what} exceeded the time limit of {:?} per call (option --prolog-time-limit)",
                    options.time_limit
                ))
            } else {
                match (rss0, resident_bytes()) {
                    (Some(a), Some(b)) if b.saturating_sub(a) > options.heap_limit => Some(format!(
                        "{what} exceeded the memory limit of {} MiB per call (option --prolog-heap-limit)",
                        options.heap_limit >> 20
                    )),
                    _ => None,
                }
            };
            if let Some(message) = over {
                self.inner.plain_live.store(false, Ordering::Release);
                if let Ok(mut a) = self.inner.abandoned.lock() {
                    *a = Some(message.clone());
                }
                return Err(message);
            }
        }
    }

    /// Calls `name(args..)` with the caller's environment.
    pub fn call(&self, call: &mut FnCall<'_>, name: Atom, args: &[Term]) -> Result<Term, String> {
        let options = match call.functions.call_limits() {
            Some(l) => PrologOptions::from(l),
            None => self.inner.options,
        };
        let store: &Store = call.store;
        let mut w = Writer::new(store, false);
        w.out.push_str("'$sitlog_call'(");
        write_atom(&mut w.out, name);
        if !args.is_empty() {
            w.out.push('(');
            for (i, &a) in args.iter().enumerate() {
                if i > 0 {
                    w.out.push(',');
                }
                w.term(a);
            }
            w.out.push(')');
        }
        // Vars come after everything else is written: reserve its place.
        let mut rest = String::new();
        std::mem::swap(&mut rest, &mut w.out);
        for (i, vars) in [&*call.locals, &*call.globals].into_iter().enumerate() {
            let _ = i;
            w.out.push(',');
            w.out.push('[');
            for (j, &(n, v)) in vars.entries().iter().enumerate() {
                if j > 0 {
                    w.out.push(',');
                }
                w.out.push_str("'-'(");
                write_atom(&mut w.out, n);
                w.out.push(',');
                w.term(v);
                w.out.push(')');
            }
            w.out.push(']');
        }
        // The history is not sent: `get_history/1` asks for it while the
        // call runs (issue 38: sent with every call, it cost time per call
        // and, past 100 000 entries, the engine's depth limit).
        let _ = write!(w.out, ",{},R).", limit_text(options.inference_limit));
        if w.too_deep() {
            return Err(format!(
                "`{name}/{}`: its arguments or the caller's variables nest {} levels deep (a list counts a level per element); the Prolog engine takes at most {PROLOG_MAX_DEPTH}",
                args.len(),
                w.deepest
            ));
        }
        let env = std::mem::take(&mut w.out);
        let mut query = rest;
        query.push_str(",[");
        for (i, v) in w.vars.iter().enumerate() {
            if i > 0 {
                query.push(',');
            }
            let _ = write!(query, "_S{}", v.0);
        }
        query.push(']');
        query.push_str(&env);
        let vars = w.vars.clone();
        let shown = || format!("{}/{}", name, args.len());
        // read/1 in this call takes the run's next input
        let input = call.functions.input().cloned();
        let (store, history) = (&mut *call.store, call.history);
        let answer = self.ask_with(
            query,
            input,
            options,
            call.functions.stop(),
            &format!("`{}`", shown()),
            &mut |from| history_part(store, history, from),
        )?;
        let Some(r) = answer else {
            return Err(format!("the Prolog call of `{}` did not answer", shown()));
        };
        let result = self.answer(call, &r, &vars, options, &shown);
        drop_deep(r);
        result
    }

    /// The value of a call's answer `r`, the caller's variables `vars`
    /// bound and its SitLog variables changed as the answer says.
    fn answer(
        &self,
        call: &mut FnCall<'_>,
        r: &PTerm,
        vars: &[crate::term::Var],
        options: PrologOptions,
        shown: &dyn Fn() -> String,
    ) -> Result<Term, String> {
        let mut names: HashMap<String, Term> = vars
            .iter()
            .map(|&v| (format!("_S{}", v.0), Term::from(v)))
            .collect();
        match r {
            PTerm::Compound(f, a) if f == "ok" && a.len() == 3 => {
                let host = self.inner.kb_host.as_ref();
                let value = from_prolog(call.store, &a[0], &mut names);
                let value = unhandle(call.store, value, host)?;
                if let PTerm::List(outs) = &a[1] {
                    for (&v, out) in vars.iter().zip(outs) {
                        let t = from_prolog(call.store, out, &mut names);
                        let t = unhandle(call.store, t, host)?;
                        let var = Term::from(v);
                        if call.store.deref(t) != call.store.deref(var) && !call.store.unify(var, t)
                        {
                            return Err(format!("`{}`: a binding does not unify back", shown()));
                        }
                    }
                }
                if let PTerm::List(changes) = &a[2] {
                    for c in changes {
                        if let PTerm::Compound(w, ca) = c {
                            if ca.len() == 2 {
                                if let PTerm::Atom(n) = &ca[0] {
                                    let v = from_prolog(call.store, &ca[1], &mut names);
                                    let v = unhandle(call.store, v, host)?;
                                    let n = Atom::intern(n);
                                    if w == "l" {
                                        call.locals.set(n, v);
                                    } else {
                                        call.globals.set(n, v);
                                    }
                                }
                            }
                        }
                    }
                }
                Ok(value)
            }
            PTerm::Atom(a) if a == "cyclic" => Err(format!(
                "`{}`: its value, a binding of the caller's variables or a SitLog variable it set is a cyclic term (a variable inside its own value), which the run cannot take",
                shown()
            )),
            PTerm::Compound(f, a) if f == "improper" && a.len() == 1 => Err(format!(
                "`{}`: its value (or what it set) `{}` holds a list whose tail is an atom other than `[]`, which the Prolog engine cannot hand over (end the list with `[]`, or make the tail a variable or a compound)",
                shown(),
                cut_text(match &a[0] {
                    PTerm::Atom(t) => t.clone(),
                    other => show_pterm(other),
                })
            )),
            PTerm::Atom(a) if a == "novalue" => Err(format!(
                "`{}` succeeded without calling assign_func_value/1",
                shown()
            )),
            PTerm::Atom(a) if a == "fail" => Err(format!("`{}` failed", shown())),
            PTerm::Atom(a) if a == "limit" => Err(format!(
                "`{}` exceeded the inference limit ({}; option --prolog-inferences)",
                shown(),
                options.inference_limit
            )),
            PTerm::Compound(f, a) if f == "error" && a.len() == 1 => {
                if let Some(m) = permissions::refusal(&a[0], show_pterm) {
                    return Err(m);
                }
                let mut names = HashMap::new();
                let e = from_prolog(call.store, &a[0], &mut names);
                let e = unhandle(call.store, e, self.inner.kb_host.as_ref())?;
                Err(format!("`{}` raised {}", shown(), call.store.writeq(e)))
            }
            other => Err(format!("`{}`: unexpected answer {other:?}", shown())),
        }
    }
}

/// Starts an engine thread: it builds the machine every application's
/// engine starts from, then takes its application from `setup` (none: the
/// thread ends) and serves it ([`engine_thread`]).
fn spawn_engine<X>(
    host: HostSlot,
    shared: Shared,
    first: impl FnOnce() -> X + Send + 'static,
    setup: impl FnOnce(&mut Machine, X) -> Option<(Setup, Option<LayerLoaded>)> + Send + 'static,
) -> std::io::Result<std::thread::JoinHandle<()>> {
    std::thread::Builder::new()
        .name("sitlog-prolog".into())
        // The engine's reader and compiler recurse: room for terms
        // PROLOG_MAX_DEPTH deep in a debug build (reserved, not used).
        .stack_size(ENGINE_STACK)
        .spawn(move || {
            let x = first();
            let (mut machine, errors) = base_machine(host.clone(), shared.clone());
            if let Some((setup, loaded)) = setup(&mut machine, x) {
                engine_thread(machine, errors, setup, loaded, host, shared);
            }
        })
}

/// The engine thread: loads the application into the machine built (with
/// `base_errors`, those of the prelude), then starts and answers queries.
fn engine_thread(
    mut machine: Machine,
    base_errors: Vec<PrologLoadError>,
    setup: Setup,
    loaded: Option<LayerLoaded>,
    host: HostSlot,
    shared: Shared,
) {
    let Setup {
        prepared,
        preloaded,
        wrapped,
        load_all,
        rx,
        ready,
    } = setup;
    let mut errors = base_errors;
    if let Ok(mut d) = shared.direct.lock() {
        *d = wrapped
            .iter()
            .filter(|w| !w.alts.is_empty())
            .map(|w| (w.legacy.0, w.legacy.1, w.originals.clone()))
            .collect();
    }
    match (preloaded, loaded) {
        (Some(pre), Some(loaded)) => {
            // The layer's clauses are in: those the application's files
            // redefine go, then the application's are added.
            for (i, text) in &loaded.clauses {
                if pre.drop.contains(i) {
                    let _ = first_answer(&mut machine, &format!("'$sitlog_drop'({text},R)."), "R");
                }
            }
            errors.extend(
                loaded
                    .errors
                    .into_iter()
                    .filter(|(i, _)| !pre.drop.contains(i))
                    .map(|(_, e)| e),
            );
            wrap_ahead(&mut machine, &shared.lazy, &wrapped, &mut errors);
            // Their wrappers are in the waiting clauses now.
            let keys: HashSet<Option<(Atom, usize)>> =
                wrapped.iter().map(|w| Some(w.key)).collect();
            let rest: Vec<Prepared> = prepared[pre.kept..]
                .iter()
                .filter(|p| !(p.file == NATIVE_FILE && keys.contains(&p.key)))
                .cloned()
                .collect();
            errors.extend(load_application(&mut machine, &rest, Some(&shared.lazy)));
        }
        _ => errors.extend(load_application(
            &mut machine,
            &prepared,
            Some(&shared.lazy),
        )),
    }
    if load_all {
        load_lazy(&mut machine, &shared.lazy);
    }
    let _ = ready.send(errors);
    // `Some((allow_os, inference limit))` once started.
    let mut started: Option<(bool, u64)> = None;
    while let Ok(request) = rx.recv() {
        let (q, reply) = match request {
            Request::Start(allow_os, limit, confine, reply) => {
                // The sandbox binds this thread before any application
                // code runs on it.
                if let Some((confine, writable)) = confine {
                    if let Err(e) = confine.apply(&writable) {
                        let _ = reply.send(vec![engine_error(&e)]);
                        continue;
                    }
                }
                started = Some((allow_os, limit));
                let _ = reply.send(run_directives(&mut machine, &prepared, allow_os, limit));
                continue;
            }
            Request::Query(q, input, reply) => {
                if let Ok(mut slot) = shared.input.lock() {
                    *slot = input;
                }
                if let Ok(mut slot) = shared.history.lock() {
                    *slot = Some(reply.clone());
                }
                (q, reply)
            }
        };
        // The prelude hands over no answer the engine's conversion panics
        // on that it knows of (a cyclic term, a list with an atom tail:
        // `'$sitlog_safe'/2`); any other panic is caught quietly.
        let r = super::quiet::quietly(|| first_answer(&mut machine, &q, "R"));
        let r = match r {
            Ok(r) => r,
            Err(message) => {
                // The engine may be in any state: start afresh.
                machine = build_machine(&prepared, host.clone(), shared.clone()).0;
                if let Some((allow_os, limit)) = started {
                    let _ = run_directives(&mut machine, &prepared, allow_os, limit);
                }
                Err(format!(
                    "the Prolog engine could not hand over its answer (an internal error of the engine: {message}; it was restarted)"
                ))
            }
        };
        if let Ok(mut slot) = shared.history.lock() {
            *slot = None;
        }
        // An answer nobody waits for any more (a call abandoned over a
        // limit) is dropped here, without recursion.
        if let Err(mpsc::SendError(Reply::Answer(Ok(Some(t))))) = reply.send(Reply::Answer(r)) {
            drop_deep(t);
        }
    }
}

/// The engine's streams: `user_output` is dropped (what functions print is
/// not part of the task's output); `user_error` carries the requests of
/// `'$sitlog_read_text'/3`, the native KB layer, `'$sitlog_system'/2` and
/// the guards' questions (framed by `\x01` and `\x02`, the first character
/// saying which), answered on `user_input` ([`read_reply`],
/// [`system_reply`], [`permissions::inside_reply`]); anything else written
/// there goes to stderr.
fn engine_streams(host: HostSlot, shared: Shared) -> StreamConfig {
    type StreamCallback = Box<dyn FnMut(&mut std::io::Cursor<Vec<u8>>)>;
    let (mut replies, input) = InputStreamConfig::channel();
    let mut pending: Vec<u8> = Vec::new();
    let on_error: StreamCallback = Box::new(move |buf: &mut std::io::Cursor<Vec<u8>>| {
        pending.extend(std::mem::take(buf.get_mut()));
        buf.set_position(0);
        loop {
            let Some(start) = pending.iter().position(|&b| b == 1) else {
                let _ = std::io::stderr().write_all(&pending);
                pending.clear();
                return;
            };
            if start > 0 {
                let _ = std::io::stderr().write_all(&pending[..start]);
                pending.drain(..start);
            }
            let Some(end) = pending.iter().position(|&b| b == 2) else {
                return;
            };
            let text = String::from_utf8_lossy(&pending[1..end]).into_owned();
            pending.drain(..=end);
            // The first character says what is asked: `R` read, `K` KB,
            // `S` the system (clock, sleep), `P` whether a file is inside
            // the application (the guards), `I` input, `H` the history,
            // `L` a waiting predicate's clauses (`M` the same, asserted,
            // never static; `C` those of one compiled static, to assert
            // in its place), `D` a wrapped predicate's clauses as written
            // (`direct_reply`).
            // A KB term or a term read may be long: the engine reads it in
            // one go after its length (`'$sitlog_read_long'/1`).
            let long = |text: String| format!("{}\n{text}", text.chars().count());
            let reply = if let Some(request) = text.strip_prefix('K') {
                let h = host.lock().ok().and_then(|h| h.clone());
                long(match h {
                    Some(h) => h(request),
                    None => "'$error'(error(existence_error(kb_host, sitlog), kb)).\n".to_owned(),
                })
            } else if let Some(request) = text.strip_prefix('R') {
                long(read_reply(request))
            } else if let Some(request) = text.strip_prefix('S') {
                system_reply(request)
            } else if let Some(file) = text.strip_prefix('P') {
                let roots = shared.roots.lock().map(|r| r.clone()).unwrap_or_default();
                permissions::inside_reply(file, &roots)
            } else if text.starts_with('I') {
                input_reply(&shared.input)
            } else if let Some(from) = text.strip_prefix('H') {
                history_reply(&shared.history, from)
            } else if let Some(id) = text.strip_prefix('L') {
                lazy_reply(&shared.lazy, &shared.statics, id, true)
            } else if let Some(id) = text.strip_prefix('M') {
                lazy_reply(&shared.lazy, &shared.statics, id, false)
            } else if let Some(id) = text.strip_prefix('C') {
                unstatic_reply(&shared.statics, id)
            } else if let Some(k) = text.strip_prefix('D') {
                direct_reply(&shared.lazy, &shared.direct, k)
            } else {
                read_reply(&text)
            };
            let _ = replies.write_all(reply.as_bytes());
        }
    });
    let on_output: StreamCallback = Box::new(|buf: &mut std::io::Cursor<Vec<u8>>| {
        buf.get_mut().clear();
        buf.set_position(0);
    });
    StreamConfig::in_memory()
        .with_user_input(input)
        .with_user_output(OutputStreamConfig::callback(on_output))
        .with_user_error(OutputStreamConfig::callback(on_error))
}

/// How many elements of the history one answer to `get_history/1` holds
/// (an answer is one term for the engine's reader, which recurses on a
/// list's cells: see [`PROLOG_MAX_DEPTH`]).
const HISTORY_PART: usize = if cfg!(test) { 2 } else { 1000 };

/// The history of a query that has none to give (a raw query).
const NO_HISTORY: &str = "'$ok'([],end).\n";

/// The answer to `get_history/1` (`H` request, `From` the first element
/// wanted): asked of the caller waiting for the running query
/// ([`Reply::History`]), and sent after a line giving its length in
/// characters, so that the engine takes it in one read (its
/// `get_line_to_chars/3` takes a character at a time: 70 µs each in a
/// debug build).
fn history_reply(link: &HistoryLink, from: &str) -> String {
    let text = history_text(link, from);
    format!("{}\n{text}", text.chars().count())
}

/// [`history_reply`]'s answer.
fn history_text(link: &HistoryLink, from: &str) -> String {
    let refused =
        || "'$error'(error(existence_error(history, sitlog), get_history/1)).\n".to_owned();
    let Ok(from) = from.trim().parse::<usize>() else {
        return refused();
    };
    let Some(caller) = link.lock().ok().and_then(|l| l.clone()) else {
        return NO_HISTORY.to_owned();
    };
    let (tx, rx) = mpsc::channel();
    if caller.send(Reply::History(from, tx)).is_err() {
        return refused();
    }
    rx.recv().unwrap_or_else(|_| refused())
}

/// The part of `history` (the current DM's, as `get_history/1` gives it)
/// from element `from` on, at most [`HISTORY_PART`] elements, as the
/// engine reads it: `'$ok'(Elements, Next)`, `Next` the next element's
/// index or `end`. An element too deep for the engine's reader (an
/// embedded DM's history over 100 000 entries) is an error naming the
/// limit. Its terms are built in `store` only when a function asks.
fn history_part(store: &mut Store, history: &[crate::history::Item], from: usize) -> String {
    use crate::history::Item;
    let from = from.min(history.len());
    let end = (from + HISTORY_PART).min(history.len());
    let terms: Vec<Term> = history[from..end]
        .iter()
        .map(|item| match item {
            Item::Entry(e) => e.to_term(store),
            Item::Nested(inner) => crate::history::to_term(inner, store),
        })
        .collect();
    let list = store.list(&terms);
    let mut w = Writer::new(store, false);
    w.out.push_str("'$ok'(");
    w.term(list);
    if w.too_deep() {
        return format!(
            "'$error'(error(representation_error(history_depth({PROLOG_MAX_DEPTH})), get_history/1)).\n"
        );
    }
    if end < history.len() {
        let _ = writeln!(w.out, ",{end}).");
    } else {
        w.out.push_str(",end).\n");
    }
    w.out
}

/// The answer to a `read/1` of the application (`I` request): the run's
/// next input, read as `read_from_chars/2` reads text ([`read_reply`]);
/// `'$eof'` at its end or without an input; an input error (over the
/// limits, not UTF-8) is thrown as `error(input_error(Message), read/1)`.
fn input_reply(input: &RunInput) -> String {
    let source = input.lock().ok().and_then(|i| i.clone());
    let Some(source) = source else {
        return "'$eof'.\n".to_owned();
    };
    let next = match source.lock() {
        Ok(mut s) => s.next_term_text(),
        Err(_) => Err("the input's reader failed earlier (poisoned)".to_owned()),
    };
    match next {
        Ok(Some(text)) => read_reply(&text),
        Ok(None) => "'$eof'.\n".to_owned(),
        Err(message) => {
            let mut out = String::from("'$error'(error(input_error(");
            write_atom(&mut out, Atom::intern(&message));
            out.push_str("),read/1)).\n");
            out
        }
    }
}

/// When the first engine was built: `statistics(walltime, _)` counts from
/// here, as SWI-Prolog's counts from its start.
static STARTED: std::sync::OnceLock<(std::time::Instant, f64)> = std::sync::OnceLock::new();

fn epoch_seconds() -> f64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}

fn started() -> (std::time::Instant, f64) {
    *STARTED.get_or_init(|| (std::time::Instant::now(), epoch_seconds()))
}

/// The CPU time of this process in seconds (user + system, from
/// `/proc/self/stat` at 100 ticks a second); elsewhere the time since the
/// engine started.
fn cpu_seconds() -> f64 {
    let ticks = std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // The fields after the command name (which may hold spaces).
            let rest = &s[s.rfind(')')? + 2..];
            let f: Vec<&str> = rest.split_whitespace().collect();
            Some(f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?)
        });
    match ticks {
        Some(t) => t as f64 / 100.0,
        None => started().0.elapsed().as_secs_f64(),
    }
}

/// The answer to a `'$sitlog_system'/2` request of the prelude: `time`
/// (seconds since the epoch), `cputime` (seconds), `walltime`
/// (milliseconds since the engine started), `epoch` (when it started),
/// `sleep(Seconds)` (sleeps, at most a day; answers 0).
fn system_reply(request: &str) -> String {
    let (since, epoch) = started();
    let request = request.trim();
    if let Some(secs) = request
        .strip_prefix("sleep(")
        .and_then(|r| r.strip_suffix(')'))
        .and_then(|r| r.trim().parse::<f64>().ok())
    {
        if secs.is_finite() && secs > 0.0 {
            std::thread::sleep(std::time::Duration::from_secs_f64(secs.min(86_400.0)));
        }
        return "'$ok'(0,[]).\n".to_owned();
    }
    match request {
        "time" => format!("'$ok'({:?},[]).\n", epoch_seconds()),
        "cputime" => format!("'$ok'({:?},[]).\n", cpu_seconds()),
        "walltime" => format!("'$ok'({},[]).\n", since.elapsed().as_millis()),
        "epoch" => format!("'$ok'({epoch:?},[]).\n"),
        other => {
            let mut out = String::from("'$error'(error(domain_error(system_request,");
            write_atom(&mut out, Atom::intern(other));
            out.push_str("),sitlog)).\n");
            out
        }
    }
}

/// The clauses and directives of `prelude_swi.pl` as canonical text (read
/// by our reader; no call renamed).
fn prelude_swi() -> Vec<Prepared> {
    let (clauses, _) = sitlog_syntax::read_clauses(PRELUDE_SWI);
    let mut positions = LineCursor::new();
    clauses
        .iter()
        .map(|clause| {
            let mut store = Store::new();
            let (t, _) = store.from_clause(clause);
            let directive = store.compound_args(t, Atom::intern(":-"), 1).map(|a| a[0]);
            let mut w = Writer::new(&store, false);
            w.term(directive.unwrap_or(t));
            let (line, col) = positions.line_col(PRELUDE_SWI, clause.span.start as usize);
            Prepared {
                text: w.out,
                directive: directive.is_some(),
                file: "prelude_swi.pl".to_owned(),
                line,
                col,
                key: None,
                lazy: false,
            }
        })
        .collect()
}

/// A machine with the prelude, the guards and the application's clauses
/// (no directive run: see [`run_directives`]).
fn build_machine(
    prepared: &[Prepared],
    host: HostSlot,
    shared: Shared,
) -> (Machine, Vec<PrologLoadError>) {
    let (mut machine, mut errors) = base_machine(host, shared);
    errors.extend(load_application(&mut machine, prepared, None));
    (machine, errors)
}

/// A machine with the prelude (both parts) and the guards: what every
/// application's engine starts from, built ahead of the application by
/// [`PrologFunctions::prewarm`]; the errors of the prelude's second part
/// (none but in development).
fn base_machine(host: HostSlot, shared: Shared) -> (Machine, Vec<PrologLoadError>) {
    started();
    let mut machine = MachineBuilder::default()
        .with_streams(engine_streams(host, shared))
        .with_toplevel(toplevel())
        .build();
    machine.consult_module_string("user", PRELUDE);
    machine.consult_module_string("user", permissions::guards());
    let mut errors = Vec::new();
    // The prelude's second part is asserted clause by clause, like the
    // application's (consulted in one string with the first part, the
    // engine loses its trail on the next query).
    for p in prelude_swi() {
        let q = if p.directive {
            format!("'$sitlog_directive'({},R).", p.text)
        } else {
            format!("'$sitlog_add'({},R).", p.text)
        };
        check_load(&mut machine, &q, &p, &mut errors);
    }
    (machine, errors)
}

/// On a warm engine: reads the legacy `layer` (served by `native` if given)
/// and sends what it read on `prepped`; gives the layer's clauses that no
/// later file of the layer redefines, by index (no directive).
fn read_layer(
    layer: &[PrologSource],
    native: Option<&NativeKb>,
    prepped: &mpsc::Sender<Prepping>,
) -> Vec<(usize, Prepared)> {
    let mut st = Prepping::new(native, true);
    st.add(layer, 0, layer.len());
    let dropped = st.dropped();
    let touching = st.touching;
    let clauses: Vec<(usize, Prepared)> = st
        .prepared
        .iter()
        .enumerate()
        .filter(|(i, p)| !p.directive && !dropped.contains(i))
        .map(|(i, p)| {
            let mut p = p.clone();
            p.lazy &= !touching;
            (i, p)
        })
        .collect();
    // The load reads the application's files meanwhile.
    let _ = prepped.send(st);
    clauses
}

/// On a warm engine: asserts the layer's `clauses` ([`read_layer`]), its
/// predicates that can wait as stubs ([`lazify`]).
fn assert_layer(
    machine: &mut Machine,
    clauses: Vec<(usize, Prepared)>,
    lazy: &LazyStore,
) -> LayerLoaded {
    let mut errors = Vec::new();
    lazify(machine, &clauses, lazy, |i, e| errors.push((i, e)));
    LayerLoaded {
        clauses: clauses.into_iter().map(|(i, p)| (i, p.text)).collect(),
        errors,
    }
}

/// Loads the application's clauses (`prepared`, no directive run) into a
/// [`base_machine`], then its libraries and the SWI-Prolog bridge.
fn load_application(
    machine: &mut Machine,
    prepared: &[Prepared],
    lazy: Option<&LazyStore>,
) -> Vec<PrologLoadError> {
    let mut errors = Vec::new();
    let clauses: Vec<(usize, &Prepared)> = prepared
        .iter()
        .filter(|p| !p.directive)
        .enumerate()
        .collect();
    match lazy {
        Some(lazy) => lazify(machine, &clauses, lazy, |_, e| errors.push(e)),
        None => add_clauses(machine, &clauses, |_, e| errors.push(e)),
    }
    for (lib, preds) in LIBRARIES {
        let q = format!("'$sitlog_import'({lib},[{}],R).", preds.join(","));
        let _ = first_answer(machine, &q, "R");
    }
    let q = format!(
        "'$sitlog_bridge'([{}],R).",
        SWI_PREDICATES
            .iter()
            .map(|p| {
                let (n, a) = p.rsplit_once('/').expect("name/arity");
                let mut q = String::new();
                write_atom(&mut q, Atom::intern(n));
                format!("{q}/{a}")
            })
            .collect::<Vec<_>>()
            .join(",")
    );
    let _ = first_answer(machine, &q, "R");
    errors
}

/// The engine's toplevel module without its interactive loop, which an
/// embedded engine never runs: the directives of scryer's own (the
/// libraries it loads, which every query then finds loaded, and the
/// dynamic predicates its loader looks at), one a line, then `repl/0`.
/// Building the machine compiles it: 0.2 s less than the whole toplevel
/// in a debug build (issue 30).
pub(super) fn toplevel() -> String {
    let mut text: String = scryer_prolog::default_toplevel()
        .lines()
        .filter(|l| l.starts_with(":-"))
        .map(|l| format!("{l}\n"))
        .collect();
    text.push_str("repl.\n");
    text
}

/// An inference limit as the prelude's `'$sitlog_run'/3` takes it:
/// [`NO_INFERENCE_LIMIT`] is `inf` (the goal is called without
/// `call_with_inference_limit/3`, whose count costs on every call).
fn limit_text(limit: u64) -> String {
    if limit == NO_INFERENCE_LIMIT {
        "inf".to_owned()
    } else {
        limit.to_string()
    }
}

/// Sets the permissions, then runs the application's directives in order,
/// each under the inference limit `limit` (`--prolog-inferences`).
fn run_directives(
    machine: &mut Machine,
    prepared: &[Prepared],
    allow_os: bool,
    limit: u64,
) -> Vec<PrologLoadError> {
    if allow_os {
        let _ = first_answer(machine, "assertz('$sitlog_allow_os'), R = ok.", "R");
    }
    let mut errors = Vec::new();
    for p in prepared.iter().filter(|p| p.directive) {
        let q = format!("'$sitlog_directive'({},{},R).", p.text, limit_text(limit));
        check_load(machine, &q, p, &mut errors);
    }
    errors
}

/// Clauses asserted per query by [`add_clauses`]: a query has a cost of
/// its own (the engine's query set-up, the answer read back), paid 1,720
/// times for the original's layer with a query per clause; a bounded batch
/// keeps a query's term small.
const ADD_BATCH: usize = 64;

/// Asserts `clauses` in order, [`ADD_BATCH`] a query; `refused` gets each
/// clause the engine refuses (by its number in `clauses`), with its error
/// at its position.
fn add_clauses<P: std::borrow::Borrow<Prepared>>(
    machine: &mut Machine,
    clauses: &[(usize, P)],
    mut refused: impl FnMut(usize, PrologLoadError),
) {
    for batch in clauses.chunks(ADD_BATCH) {
        let mut q = String::from("'$sitlog_add_all'(c(");
        for (k, (_, p)) in batch.iter().enumerate() {
            if k > 0 {
                q.push(',');
            }
            let _ = write!(q, "({})", p.borrow().text);
        }
        q.push_str("),R).");
        refusals(machine, &q, batch, &mut refused);
    }
}

/// Runs the query `q`, whose `R` is the list of `K-E` for each element
/// `K` (from 1) of `batch` the engine refused with the error `E`, and
/// gives each to `refused` with its error at its position.
fn refusals<P: std::borrow::Borrow<Prepared>>(
    machine: &mut Machine,
    q: &str,
    batch: &[(usize, P)],
    refused: &mut impl FnMut(usize, PrologLoadError),
) {
    match first_answer(machine, q, "R") {
        Ok(Some(PTerm::List(refusals))) => {
            for r in refusals {
                let (k, e) = match r {
                    PTerm::Compound(f, mut a) if f == "-" && a.len() == 2 => {
                        let e = a.pop();
                        (a.pop(), e)
                    }
                    other => (None, Some(other)),
                };
                // `K`: the clause's argument number in `c(...)`.
                let k = match k {
                    Some(PTerm::Integer(k)) => usize::try_from(&k).ok(),
                    _ => None,
                };
                let k = k.and_then(|k| k.checked_sub(1));
                let (i, p) = match k.and_then(|k| batch.get(k)) {
                    Some((i, p)) => (*i, p.borrow()),
                    None => (batch[0].0, batch[0].1.borrow()),
                };
                let answer = Ok(e.map(|e| PTerm::Compound("error".into(), vec![e])));
                let mut one = Vec::new();
                load_error(answer, p, &mut one);
                one.into_iter().for_each(|e| refused(i, e));
            }
        }
        Ok(Some(PTerm::Atom(a))) if a == "[]" => {}
        // The batch as a whole failed (not expected; some of its
        // clauses may be in): an error at its first clause.
        other => {
            let mut one = Vec::new();
            load_error(other, batch[0].1.borrow(), &mut one);
            one.into_iter().for_each(|e| refused(batch[0].0, e));
        }
    }
}

/// Stubs asserted by one query.
const STUB_BATCH: usize = 512;

/// Asserts the stub clause (`P(V..) :- '$sitlog_lazy'(Id, P, A), P(V..)`,
/// [`lazify`]) of each waiting predicate of
/// `preds` (its name and arity, its number in the [`LazyStore`]; its place
/// for errors: the [`Prepared`] at the same index of `stubs`), as
/// [`add_clauses`] would, but built by the prelude
/// (`'$sitlog_stubs'/2`) from `s(Name, Arity, Id)`: the engine reads a
/// few characters a predicate rather than a clause with its head twice
/// (reading them was a third of a stub's cost: `example` under `--legacy`,
/// 680 stubs, 60 M instructions less).
fn add_stubs(
    machine: &mut Machine,
    stubs: &[(usize, Prepared)],
    preds: &[((Atom, usize), usize)],
    mut refused: impl FnMut(usize, PrologLoadError),
) {
    for (batch, preds) in stubs.chunks(STUB_BATCH).zip(preds.chunks(STUB_BATCH)) {
        let mut q = String::from("'$sitlog_stubs'([");
        for (k, ((name, arity), id)) in preds.iter().enumerate() {
            if k > 0 {
                q.push(',');
            }
            q.push_str("s(");
            write_atom(&mut q, *name);
            let _ = write!(q, ",{arity},{id})");
        }
        q.push_str("],R).");
        refusals(machine, &q, batch, &mut refused);
    }
}

/// Asserts `clauses` ([`add_clauses`]), except that the predicates whose
/// clauses are all [`Prepared::lazy`] (the legacy profile's: the
/// original's layer and the application's files) get one stub clause
/// each, `P(V..) :- '$sitlog_lazy'(N, P, A), P(V..)`, their clauses kept
/// in `store` (number `N`): the stub's first call retracts it, asks the
/// host for the clauses (an `L` request) and compiles them as a consulted
/// file's, static ([`lazy_reply`]), then calls the predicate; a call that
/// changes or looks at the clauses asserts them instead (dynamic), before
/// or after. The original's layer has 1,720 clauses and
/// `apps/test_behaviors` 800, of which a task calls a few. Calls that
/// change or look at clauses (`TOUCHING`, renamed in the legacy profile's
/// clauses) load the predicate first, so that a stub is never seen,
/// retracted, or followed by clauses asserted before the predicate's own.
/// A stub the engine refuses (a predicate it does not let the application
/// define) has its clauses asserted now, each refusal an error at its
/// clause's place as without stubs.
fn lazify<P: std::borrow::Borrow<Prepared>>(
    machine: &mut Machine,
    clauses: &[(usize, P)],
    store: &LazyStore,
    mut refused: impl FnMut(usize, PrologLoadError),
) {
    // A predicate waits only if all its clauses may.
    let mut waits: HashMap<(Atom, usize), bool> = HashMap::new();
    for (_, p) in clauses {
        let p = p.borrow();
        if let Some(key) = p.key {
            *waits.entry(key).or_insert(true) &= p.lazy;
        }
    }
    let waits_key = |p: &Prepared| p.key.filter(|k| waits.get(k) == Some(&true));
    let eager: Vec<(usize, &Prepared)> = clauses
        .iter()
        .map(|(i, p)| (*i, p.borrow()))
        .filter(|(_, p)| waits_key(p).is_none())
        .collect();
    add_clauses(machine, &eager, &mut refused);
    // The waiting predicates in the order of their first clauses.
    let mut order: Vec<(Atom, usize)> = Vec::new();
    let mut members: HashMap<(Atom, usize), Vec<(usize, &Prepared)>> = HashMap::new();
    for (i, p) in clauses {
        let p = p.borrow();
        if let Some(key) = waits_key(p) {
            members
                .entry(key)
                .or_insert_with(|| {
                    order.push(key);
                    Vec::new()
                })
                .push((*i, p));
        }
    }
    if order.is_empty() {
        return;
    }
    let Ok(mut lazy) = store.lock() else {
        // Not expected: everything now.
        let rest: Vec<(usize, &Prepared)> = order.iter().flat_map(|k| members[k].clone()).collect();
        add_clauses(machine, &rest, &mut refused);
        return;
    };
    let mut stubs = Vec::with_capacity(order.len());
    let mut ids = Vec::with_capacity(order.len());
    for (k, key) in order.iter().enumerate() {
        let first = members[key][0].1;
        let id = lazy.len();
        lazy.push(Some(LazyPred {
            name: key.0,
            arity: key.1,
            clauses: members[key].iter().map(|(_, p)| p.text.clone()).collect(),
        }));
        ids.push((*key, id));
        stubs.push((
            k,
            Prepared {
                text: String::new(),
                directive: false,
                file: first.file.clone(),
                line: first.line,
                col: first.col,
                key: Some(*key),
                lazy: false,
            },
        ));
    }
    let base = lazy.len() - order.len();
    drop(lazy);
    let mut refused_stubs = Vec::new();
    add_stubs(machine, &stubs, &ids, |k, _| refused_stubs.push(k));
    if refused_stubs.is_empty() {
        return;
    }
    refused_stubs.dedup();
    let mut now = Vec::new();
    if let Ok(mut lazy) = store.lock() {
        for &k in &refused_stubs {
            lazy[base + k] = None;
            now.extend(members[&order[k]].iter().cloned());
        }
    }
    now.sort_by_key(|(i, _)| *i);
    add_clauses(machine, &now, &mut refused);
}

/// On an engine that asserted the legacy layer ahead (each predicate under
/// its own name): the predicates a KB handle can reach (`kb_reach`) are
/// wrapped. A waiting one's clauses become `$legacy_P`'s (a new waiting
/// predicate, its stub added) and its own waiting clause the wrapper; one
/// asserted already is wrapped by the prelude (`'$sitlog_kb_wrap'/2`).
fn wrap_ahead(
    machine: &mut Machine,
    lazy: &LazyStore,
    wrapped: &[Wrapped],
    errors: &mut Vec<PrologLoadError>,
) {
    if wrapped.is_empty() {
        return;
    }
    let mut stubs = Vec::new();
    let mut preds = Vec::new();
    let mut now = String::new();
    if let Ok(mut store) = lazy.lock() {
        let mut waiting: HashMap<(Atom, usize), usize> = HashMap::new();
        for (id, p) in store.iter().enumerate() {
            if let Some(p) = p {
                waiting.insert((p.name, p.arity), id);
            }
        }
        for w in wrapped {
            let Some(id) = waiting.get(&w.key).copied() else {
                let mut n = String::new();
                write_atom(&mut n, w.key.0);
                let _ = write!(now, "'$sitlog_kb_wrap'({n},{}),", w.key.1);
                continue;
            };
            let Some(p) = store[id].as_mut() else {
                continue;
            };
            let (mut old, mut new) = (String::new(), String::new());
            write_atom(&mut old, w.key.0);
            write_atom(&mut new, w.legacy.0);
            let clauses: Vec<String> = p
                .clauses
                .iter()
                .map(|c| {
                    let c = w.alts.iter().find(|(t, _)| t == c).map_or(c, |(_, a)| a);
                    rename_head(c, &old, &new)
                })
                .collect();
            p.clauses = vec![w.wrapper.clone()];
            let legacy_id = store.len();
            store.push(Some(LazyPred {
                name: w.legacy.0,
                arity: w.legacy.1,
                clauses,
            }));
            preds.push((w.legacy, legacy_id));
            stubs.push((
                stubs.len(),
                Prepared {
                    text: String::new(),
                    directive: false,
                    file: NATIVE_FILE.into(),
                    line: 0,
                    col: 0,
                    key: Some(w.legacy),
                    lazy: false,
                },
            ));
        }
    }
    add_stubs(machine, &stubs, &preds, |_, e| errors.push(e));
    if !now.is_empty() {
        now.push_str("R = ok.");
        let _ = first_answer(machine, &now, "R");
    }
}

/// `t` with every KB handle of the native KB layer (`'$kb'(N)`) replaced
/// by the KB term it stands for, asked of `host`: what a Prolog call gives
/// its caller (the original's DMs hold KB terms; a handle given to the
/// host could come back as an argument where `kb_reach` assumes none).
fn unhandle(store: &mut Store, t: Term, host: Option<&KbHost>) -> Result<Term, String> {
    let Some(host) = host else {
        return Ok(t);
    };
    // Most answers have none: looked for first, without building.
    let mut stack = vec![t];
    let mut found = false;
    while let Some(u) = stack.pop() {
        if handle_number(store, u).is_some() {
            found = true;
            break;
        }
        if let crate::term::Value::Compound(_, a) = store.value(u) {
            stack.extend(a.iter().copied());
        }
    }
    if !found {
        return Ok(t);
    }
    let mut terms: HashMap<i64, Term> = HashMap::new();
    rebuild(store, t, host, &mut terms, 0)
}

/// `N` if `t` is a handle `'$kb'(N)`.
fn handle_number(store: &Store, t: Term) -> Option<i64> {
    store
        .compound_args(store.deref(t), Atom::intern("$kb"), 1)
        .and_then(|a| store.int_of(a[0]))
}

/// [`unhandle`]'s copy of `t` (a term with a handle somewhere).
fn rebuild(
    store: &mut Store,
    t: Term,
    host: &KbHost,
    terms: &mut HashMap<i64, Term>,
    depth: usize,
) -> Result<Term, String> {
    if let Some(n) = handle_number(store, t) {
        if let Some(&k) = terms.get(&n) {
            return Ok(k);
        }
        let reply = host(&format!("term('$kb'({n}))"));
        let (r, _) = store
            .parse(&reply)
            .map_err(|e| format!("the KB of handle {n}: {}", e.message))?;
        let Some(k) = store.compound_args(r, Atom::intern("$ok"), 2).map(|a| a[0]) else {
            return Err(format!("the KB of handle {n}: {}", reply.trim()));
        };
        terms.insert(n, k);
        return Ok(k);
    }
    let crate::term::Value::Compound(f, a) = store.value(t) else {
        return Ok(t);
    };
    if depth > PROLOG_MAX_DEPTH {
        return Ok(t);
    }
    let args = a.to_vec();
    let mut new = Vec::with_capacity(args.len());
    for a in args {
        new.push(rebuild(store, a, host, terms, depth + 1)?);
    }
    Ok(store.compound(f, &new))
}

/// The answer to an `L` request (a waiting predicate's number; `fixed`)
/// or an `M` request (not `fixed`): its clauses as
/// `'$ok'([c(C1, ..), ..])`, at most [`ADD_BATCH`] a group (taken: a
/// second request gets none), after a line with the text's length in
/// characters, as [`history_reply`]. For an `L` request the answer is
/// `'$static'(..)` instead: the engine compiles the predicate as a
/// consulted one (static), and the clauses are kept in `statics` for a
/// `C` request ([`unstatic_reply`]) if a call changes or looks at them
/// later (the prelude's `'$sitlog_lz_touch'/2`).
fn lazy_reply(store: &LazyStore, statics: &StaticStore, id: &str, fixed: bool) -> String {
    let id = id.trim().parse::<usize>().ok();
    let pred = id.and_then(|id| {
        store
            .lock()
            .ok()
            .and_then(|mut s| s.get_mut(id).and_then(Option::take))
    });
    let fixed = fixed && pred.is_some();
    let mut text = String::from(if fixed { "'$static'([" } else { "'$ok'([" });
    if let Some(pred) = pred {
        write_groups(&mut text, &pred.clauses);
        if let (true, Some(id), Ok(mut s)) = (fixed, id, statics.lock()) {
            s.insert(id, pred.clauses);
        }
    }
    text.push_str("]).\n");
    format!("{}\n{text}", text.chars().count())
}

/// The answer to a `C` request (the number of a predicate compiled static
/// by an `L` request, [`lazy_reply`]): its clauses, taken, as
/// `'$ok'([c(C1, ..), ..])` for the engine to assert in place of its
/// static code (none if they were taken already).
fn unstatic_reply(statics: &StaticStore, id: &str) -> String {
    let clauses = id
        .trim()
        .parse::<usize>()
        .ok()
        .and_then(|id| statics.lock().ok().and_then(|mut s| s.remove(&id)));
    let mut text = String::from("'$ok'([");
    if let Some(clauses) = clauses {
        write_groups(&mut text, &clauses);
    }
    text.push_str("]).\n");
    format!("{}\n{text}", text.chars().count())
}

/// `clauses` as `c(C1, ..)` groups of at most [`ADD_BATCH`], comma
/// separated (`'$sitlog_lazy_add'/1`'s list).
fn write_groups(text: &mut String, clauses: &[String]) {
    for (g, group) in clauses.chunks(ADD_BATCH).enumerate() {
        if g > 0 {
            text.push(',');
        }
        text.push_str("c(");
        for (k, c) in group.iter().enumerate() {
            if k > 0 {
                text.push(',');
            }
            let _ = write!(text, "({c})");
        }
        text.push(')');
    }
}

/// The answer to a `D` request (a `'$sitlog_direct'/3` fact's number): the
/// clauses as written of that predicate of the layer, whose calls of itself
/// go through its wrapper again, for the engine to put in place of the
/// clauses it has: `'$ok'([c(C1, ..), ..])` as [`lazy_reply`]. While the
/// predicate still waits for its first call, its waiting clauses become
/// those instead, and the answer is `'$ok'([])`.
fn direct_reply(lazy: &LazyStore, direct: &DirectStore, k: &str) -> String {
    let found = k
        .trim()
        .parse::<usize>()
        .ok()
        .and_then(|k| direct.lock().ok().and_then(|d| d.get(k).cloned()));
    let mut text = String::from("'$ok'([");
    if let Some((name, arity, originals)) = found {
        let waiting = lazy.lock().ok().and_then(|mut s| {
            s.iter_mut()
                .flatten()
                .find(|p| p.name == name && p.arity == arity)
                .map(|p| p.clauses.clone_from(&originals))
        });
        if waiting.is_none() {
            write_groups(&mut text, &originals);
        }
    }
    text.push_str("]).\n");
    format!("{}\n{text}", text.chars().count())
}

/// Loads every predicate of the legacy layer still waiting for its first
/// call ([`lazify`]; one that a file of the application redefined has no
/// stub any more and stays out).
fn load_lazy(machine: &mut Machine, store: &LazyStore) {
    let waiting: Vec<(usize, Atom, usize)> = match store.lock() {
        Ok(s) => s
            .iter()
            .enumerate()
            .filter_map(|(id, p)| p.as_ref().map(|p| (id, p.name, p.arity)))
            .collect(),
        Err(_) => return,
    };
    for batch in waiting.chunks(ADD_BATCH) {
        let mut q = String::new();
        for (id, name, arity) in batch {
            q.push_str("'$sitlog_lazy'(");
            let _ = write!(q, "{id},");
            write_atom(&mut q, *name);
            // Asserted, never static: a call built as data may change
            // or look at its clauses without loading it first.
            let _ = write!(q, ",{arity},'M'),");
        }
        q.push_str("R = ok.");
        let _ = first_answer(machine, &q, "R");
    }
}

fn check_load(machine: &mut Machine, q: &str, p: &Prepared, errors: &mut Vec<PrologLoadError>) {
    load_error(first_answer(machine, q, "R"), p, errors);
}

/// The load error of `p` for its query's `answer` (none for `ok`).
fn load_error(
    answer: Result<Option<PTerm>, String>,
    p: &Prepared,
    errors: &mut Vec<PrologLoadError>,
) {
    let message = match &answer {
        Ok(Some(PTerm::Atom(a))) if a == "ok" => return,
        Ok(Some(PTerm::Atom(a))) if a == "fail" => "directive failed".to_owned(),
        Ok(Some(PTerm::Compound(f, a))) if f == "limit" && a.len() == 1 => format!(
            "the directive exceeded the inference limit ({}; option --prolog-inferences)",
            show_pterm(&a[0])
        ),
        Ok(Some(PTerm::Compound(f, a))) if f == "error" && a.len() == 1 => {
            match permissions::refusal(&a[0], show_pterm) {
                Some(m) => m,
                None => format!("the Prolog engine refused it: {}", show_pterm(&a[0])),
            }
        }
        Ok(Some(other)) => format!("the Prolog engine refused it: {}", show_pterm(other)),
        Ok(None) => "the Prolog engine refused it (no answer)".to_owned(),
        Err(e) => e.clone(),
    };
    if let Ok(Some(t)) = answer {
        drop_deep(t);
    }
    errors.push(PrologLoadError {
        file: p.file.clone(),
        line: p.line,
        col: p.col,
        message,
    });
}

/// `text` cut at 200 characters (a value written out in an error message:
/// an atom-tailed list may hold thousands of elements).
fn cut_text(text: String) -> String {
    if text.chars().count() > 200 {
        format!("{}…", text.chars().take(199).collect::<String>())
    } else {
        text
    }
}

/// A scryer term as Prolog-like text (for messages).
fn show_pterm(t: &PTerm) -> String {
    let mut store = Store::new();
    let mut names = HashMap::new();
    let t = from_prolog(&mut store, t, &mut names);
    store.writeq(t)
}

/// The binding of `var` in the first answer of `query`.
fn first_answer(machine: &mut Machine, query: &str, var: &str) -> Result<Option<PTerm>, String> {
    let mut answers = machine.run_query(query.to_owned());
    let first = answers.next();
    drop(answers);
    // Terms of any depth are taken, not copied, and dropped without
    // recursion (`drop_deep`).
    match first {
        None | Some(Ok(LeafAnswer::False)) => Ok(None),
        Some(Ok(LeafAnswer::True)) => Ok(Some(PTerm::Atom("true".into()))),
        Some(Ok(LeafAnswer::LeafAnswer { mut bindings, .. })) => {
            let value = bindings.remove(var);
            bindings.into_values().for_each(drop_deep);
            Ok(value)
        }
        Some(Ok(LeafAnswer::Exception(e))) | Some(Err(e)) => {
            let message = format!("Prolog exception: {}", show_pterm(&e));
            drop_deep(e);
            Err(message)
        }
    }
}

/// An error of the engine itself (no position in the application).
fn engine_error(message: &str) -> PrologLoadError {
    PrologLoadError {
        file: "<engine>".into(),
        line: 0,
        col: 0,
        message: message.to_owned(),
    }
}

/// Load errors as one message, one per line.
fn show_errors(errors: &[PrologLoadError]) -> String {
    errors
        .iter()
        .map(|e| e.to_string())
        .collect::<Vec<_>>()
        .join("\n")
}
