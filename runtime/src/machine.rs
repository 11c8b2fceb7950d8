//! The DM machine: runs a SitLog program as a functional recursive
//! transition network. One loop, the DM stack on the heap (no Rust recursion
//! per embedded DM), the pipe, locals per DM execution, globals for the
//! program, and the task history, in the original's order of steps
//! (semantics notes D-7..D-27, with our fixes E1, E4, E5, E7–E16).
//!
//! The program itself is behind [`DmProgram`]: the reference interpreter
//! implements it over the compiler's IR, generated code implements it with
//! code. Both share every step below, so they cannot disagree on semantics.

use crate::eval::{self, EvalCtx, EvalError};
use crate::functions::Functions;
use crate::history::{Entry, Item};
use crate::store::Store;
use crate::term::Term;
use crate::vars::Vars;
use sitlog_syntax::{atoms, Atom};

/// Index of a DM in its program.
pub type DmIx = u32;
/// Index of a situation in its DM (0 is the initial situation).
pub type SitIx = u32;

/// What kind of situation, as its `type` says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Final,
    Recursive,
    /// Any other type: the name of a perceptual interpreter.
    Perceptual,
}

/// The fields of a situation instance, as [`DmProgram::instantiate`] returns
/// them: fresh terms sharing variables with a fresh copy of the DM head.
#[derive(Clone, Copy, Debug)]
pub struct Instance {
    pub head: Term,
    pub id: Term,
    pub type_term: Term,
    pub in_arg: Option<Term>,
    pub out_arg: Option<Term>,
    pub prog: Option<Term>,
    pub embedded_dm: Option<Term>,
    pub diag_mod: Option<Term>,
    /// The arcs as a list of `'$arc'(Expectation, Action, Next)`.
    pub arcs: Term,
}

/// A program the machine can run.
pub trait DmProgram {
    /// The first DM in load order with this name (D-3: arity is not compared).
    fn dm_by_name(&self, name: Atom) -> Option<DmIx>;
    fn dm_name(&self, dm: DmIx) -> Atom;
    fn situation_count(&self, dm: DmIx) -> usize;
    fn kind(&self, dm: DmIx, sit: SitIx) -> Kind;
    /// A fresh copy of the DM's head (its identifier term).
    fn fresh_head(&self, dm: DmIx, store: &mut Store) -> Term;
    /// A fresh instance of a situation (D-7), head included.
    fn instantiate(&self, dm: DmIx, sit: SitIx, store: &mut Store) -> Instance;
    /// Whether situation `sit`'s id could unify with `value` (a cheap filter
    /// before instantiating; `true` is always a correct answer).
    fn may_select(&self, dm: DmIx, sit: SitIx, value: Term, store: &Store) -> bool {
        let _ = (dm, sit, value, store);
        true
    }
    /// Fresh default values of the DM's local variables (D-5).
    fn locals(&self, dm: DmIx, store: &mut Store) -> Vars;
    /// Where a situation is written, for error messages (`file:line:col`).
    fn location(&self, dm: DmIx, sit: SitIx) -> Option<String> {
        let _ = (dm, sit);
        None
    }
    /// `Some((name, arity))` when situation `sit` runs as code
    /// ([`DmProgram::run_situation`] and, for a recursive one,
    /// [`DmProgram::run_exit`]) instead of being instantiated; its id is
    /// then the atom `name` (arity 0) or a compound `name(...)` whose
    /// arguments are distinct fresh variables or atomic constants.
    fn compiled_id(&self, dm: DmIx, sit: SitIx) -> Option<(Atom, usize)> {
        let _ = (dm, sit);
        None
    }
    /// Whether compiled situation `sit`, whose id has the principal functor
    /// of `value`, is selected by `value`: its constant id arguments unify
    /// with `value`'s (bindings are kept when it is, undone otherwise).
    fn select_compiled(&self, dm: DmIx, sit: SitIx, value: Term, store: &mut Store) -> bool {
        let _ = (dm, sit, value, store);
        true
    }
    /// Runs compiled situation `sit` of the running DM, up to the step the
    /// machine takes next.
    fn run_situation(
        &self,
        dm: DmIx,
        sit: SitIx,
        cx: &mut Cx<'_, '_, Self>,
    ) -> Result<Step, RunError>
    where
        Self: Sized,
    {
        let _ = (dm, sit);
        Err(cx.error("the situation has no compiled code", None))
    }
    /// Called between two transitions, before the machine enters the next
    /// situation: a program that can change while it runs (`sitlogc run
    /// --watch`) takes its new version here, and may add variables to the
    /// frames ([`Between`]). `Err` stops the run with that message.
    /// Does nothing unless overridden.
    fn between(&self, at: &mut Between<'_>) -> Result<(), String> {
        let _ = at;
        Ok(())
    }
    /// The exit arcs of compiled recursive situation `sit`, once its embedded
    /// DM ended in `final_id`; `saved` is what [`Step::Call`] kept.
    fn run_exit(
        &self,
        dm: DmIx,
        sit: SitIx,
        saved: Term,
        final_id: Term,
        cx: &mut Cx<'_, '_, Self>,
    ) -> Result<Step, RunError>
    where
        Self: Sized,
    {
        let _ = (dm, sit, saved, final_id);
        Err(cx.error("the situation has no compiled code", None))
    }
}

/// What the code of a compiled situation leaves to the machine.
#[derive(Clone, Copy, Debug)]
pub enum Step {
    /// Go to the situation this (evaluated) term names, selected as for any next situation.
    Goto(Term),
    /// Go to situation `SitIx` of the running DM: the one a constant next
    /// situation selects, resolved when the program was compiled.
    GotoSit(SitIx),
    /// Run the DM `call`; `saved` keeps what the exit arcs need (a GC root meanwhile).
    Call { call: Term, saved: Term },
    /// A final situation ended the running DM (its entry is recorded).
    Final,
    /// No expectation was met: the recovery DM of the type, or a new instance (D-15, D-42a).
    Unmet { type_term: Term },
}

/// What the perceptual interpreter of a situation type perceived.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Perceived {
    Input(Term),
    /// No more input (end of a test script).
    EndOfInput,
    /// Nothing perceived yet: enter the situation again, as a new instance,
    /// without its recovery DM (as when no expectation is met, D-15). A
    /// perception returns it when the program changed while it waited
    /// (hot reload), so that the new program's situation takes the input.
    Again,
}

/// Perceptual interpreters: given the situation type and the evaluated
/// expectations, perceive what happened (in test mode: read a term).
pub trait Perception {
    fn perceive(
        &mut self,
        store: &mut Store,
        situation_type: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String>;

    /// Where the next [`Perception::perceive`] is asked for: the running
    /// DM's call and the situation's id (for a prompt that names them).
    /// Called by the machine just before it. Does nothing unless overridden.
    fn waiting_at(&mut self, store: &Store, dm: Term, situation: Term) {
        let _ = (store, dm, situation);
    }
}

/// Basic actions: executed after an arc's action is evaluated.
pub trait Actions {
    /// Performs one action (an element of an action list, or the action).
    ///
    /// The store is mutable so that an action can report a result by
    /// binding an unbound argument (`navigate(kitchen, Status)` binds
    /// `Status`), as the original's robot services do: the arc's next
    /// situation, out_arg and the history entry then see the binding.
    fn perform(&mut self, store: &mut Store, action: Term) -> Result<(), String>;

    /// Whether performing a number does nothing (and succeeds), always: then
    /// typed code skips the calls for actions it knows are numbers (an
    /// `inc` in an action list). `false` is always a correct answer.
    fn ignores_numbers(&self) -> bool {
        false
    }
}

/// Notified of every transition as it happens (for `--trace`).
pub trait Observer {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>);

    /// Called after [`Observer::transition`] (the entry then in its DM's
    /// history), and once more when the run stops on an error (before the
    /// stack is unwound), with the machine as it is: a debugger blocks here.
    /// Does nothing unless overridden.
    fn inspect(&mut self, machine: &mut Inspection<'_>) {
        let _ = machine;
    }
}

/// What [`Observer::inspect`] sees of the machine between two transitions:
/// the DM stack (each frame's call term, locals and history, innermost
/// last), the pipe, the globals, and an evaluator that leaves them as they
/// were ([`Inspection::evaluate`]).
pub struct Inspection<'a> {
    pub store: &'a mut Store,
    pub globals: &'a mut Vars,
    pub functions: &'a Functions,
    /// The pipe's value.
    pub pipe: Term,
    /// The error that stopped the run, when it did (`None` after a transition).
    pub error: Option<&'a RunError>,
    frames: &'a mut [Frame],
    instances: &'a [Instance],
}

impl Inspection<'_> {
    /// DMs on the stack (the main DM is frame 0).
    pub fn depth(&self) -> usize {
        self.frames.len()
    }
    /// Frame `i`'s DM call term.
    pub fn dm_id(&self, i: usize) -> Term {
        self.frames[i].dm_id
    }
    /// Frame `i`'s local variables.
    pub fn locals(&self, i: usize) -> &Vars {
        &self.frames[i].locals
    }
    /// The id of the situation frame `i` waits in for frame `i + 1` (its
    /// recursive situation, or the failed one a recovery DM runs for);
    /// `None` for the innermost frame.
    pub fn waiting_in(&self, i: usize) -> Option<Term> {
        match self.frames.get(i)?.pending.as_ref()? {
            Pending::Recursive { .. } => {
                let n = self.frames[..=i]
                    .iter()
                    .filter(|f| matches!(f.pending, Some(Pending::Recursive { .. })))
                    .count();
                self.instances.get(n - 1).map(|inst| inst.id)
            }
            Pending::Compiled { id, .. } | Pending::Recovery { id } => Some(*id),
        }
    }
    /// Frame `i`'s history so far (empty when the history is not kept).
    pub fn history(&self, i: usize) -> &[Item] {
        &self.frames[i].history
    }
    /// Evaluates `t` (an L expression) in frame `i` and prints its value
    /// (`writeq`); bindings and variable updates are undone afterwards.
    pub fn evaluate(&mut self, i: usize, t: Term) -> Result<String, String> {
        let frame = &mut self.frames[i];
        let (locals, globals) = (frame.locals.clone(), self.globals.clone());
        let mark = self.store.mark();
        let mut cx = EvalCtx {
            store: &mut *self.store,
            locals: &mut frame.locals,
            globals: &mut *self.globals,
            history: &frame.history,
            functions: self.functions,
        };
        let result = eval::eval(&mut cx, t)
            .map(|v| self.store.writeq(v))
            .map_err(|e| e.message);
        self.store.undo_to(mark);
        frame.locals = locals;
        *self.globals = globals;
        result
    }
}

/// Where control goes next, as [`DmProgram::between`] sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Next {
    /// The initial situation of the running DM (just called).
    Initial,
    /// The situation this (evaluated) next-situation value selects.
    Situation(Term),
    /// Situation `SitIx` of the running DM (compiled code).
    Index(SitIx),
}

/// The machine between two transitions, for [`DmProgram::between`]: the DM
/// stack (frame 0 is the main DM, the running one is last), the situation
/// it enters next, the variables and the functions.
pub struct Between<'a> {
    pub store: &'a mut Store,
    pub globals: &'a mut Vars,
    pub functions: &'a mut Functions,
    pub next: Next,
    frames: &'a mut [Frame],
}

impl Between<'_> {
    /// DMs on the stack.
    pub fn depth(&self) -> usize {
        self.frames.len()
    }
    /// Frame `i`'s DM (the program's index) and call term.
    pub fn dm(&self, i: usize) -> (DmIx, Term) {
        (self.frames[i].dm, self.frames[i].dm_id)
    }
    /// Frame `i`'s local variables.
    pub fn locals_mut(&mut self, i: usize) -> &mut Vars {
        &mut self.frames[i].locals
    }
    /// The recursive situation of frame `i` that waits for the DM above it
    /// (interpreted programs), if any.
    pub fn waiting_situation(&self, i: usize) -> Option<SitIx> {
        match self.frames[i].pending {
            Some(Pending::Recursive { sit }) => Some(sit),
            _ => None,
        }
    }
    /// Renumbers the waiting recursive situation of frame `i` (its
    /// instance, already made, is kept), for a program that changed.
    pub fn set_waiting_situation(&mut self, i: usize, sit: SitIx) {
        if let Some(Pending::Recursive { sit: s }) = &mut self.frames[i].pending {
            *s = sit;
        }
    }
}

/// Options of a run.
#[derive(Clone, Debug)]
pub struct Options {
    /// Keep the task history (`--history keep`); without it, memory stays bounded.
    pub keep_history: bool,
    /// Deepest DM stack allowed before the run stops with an error.
    pub max_depth: usize,
    /// Recovery DM per situation type (D-42a): run when no expectation is met.
    pub recovery: Vec<(Atom, Atom)>,
    /// Collect garbage when the store has grown by this many cells since the last collection.
    pub gc_threshold: usize,
    /// Limits on terms from outside (`--in-arg`, `--main`; perception
    /// sources take theirs when they are made).
    pub input_limits: crate::testmode::InputLimits,
    /// When set (by a signal handler), the run stops before its next
    /// transition with an error and [`Outcome::interrupted`].
    pub stop: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            keep_history: true,
            max_depth: 10_000_000,
            recovery: Vec::new(),
            gc_threshold: 1 << 20,
            input_limits: Default::default(),
            stop: None,
        }
    }
}

/// A run-time error: where it happened and what.
#[derive(Clone, Debug, PartialEq)]
pub struct RunError {
    pub message: String,
    pub dm: Option<String>,
    pub situation: Option<String>,
    /// 1-based arc number.
    pub arc: Option<usize>,
    pub location: Option<String>,
    /// Where in the program, for a reporter that shows the source
    /// ([`crate::app::App::render_error`]); boxed to keep errors small.
    pub site: Option<Box<ErrorSite>>,
}

/// The running DM and situation of a [`RunError`], by index, and the
/// expression of L whose evaluation failed, when one did.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorSite {
    pub dm: DmIx,
    pub situation: SitIx,
    pub culprit: Option<eval::Culprit>,
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut place = Vec::new();
        if let Some(dm) = &self.dm {
            place.push(format!("DM `{dm}`"));
        }
        if let Some(s) = &self.situation {
            place.push(format!("situation `{s}`"));
        }
        if let Some(a) = self.arc {
            place.push(format!("arc {a}"));
        }
        if !place.is_empty() {
            write!(f, "in {}", place.join(", "))?;
            if let Some(loc) = &self.location {
                write!(f, " ({loc})")?;
            }
            write!(f, ": ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for RunError {}

/// How a run ended.
#[derive(Debug)]
pub struct Outcome {
    /// `Ok` when the main DM reached a final situation.
    pub result: Result<(), RunError>,
    /// The history (nested as the original's), empty with `keep_history: false`.
    pub history: Vec<Item>,
    /// The final pipe value.
    pub out_arg: Term,
    pub globals: Vars,
    /// The final situation reached by the main DM, if any.
    pub final_situation: Option<Term>,
    /// Transitions made (history entries appended, kept or not).
    pub transitions: u64,
    /// The run was stopped by [`Options::stop`] (the result is then an error
    /// saying so).
    pub interrupted: bool,
}

/// A recursive situation waiting for its embedded DM, or a failed
/// situation waiting for its recovery DM.
#[derive(Debug)]
enum Pending {
    /// Its instance is on [`Machine::instances`] (kept out of the frame,
    /// which stays small to push and pop).
    Recursive {
        sit: SitIx,
    },
    Compiled {
        sit: SitIx,
        saved: Term,
        id: Term,
    },
    Recovery {
        id: Term,
    },
}

#[derive(Debug)]
struct Frame {
    dm: DmIx,
    /// The DM call term (the caller sees its bindings: parameters by reference).
    dm_id: Term,
    locals: Vars,
    history: Vec<Item>,
    pending: Option<Pending>,
}

/// The situation [`Machine::select`] picked.
enum Selected {
    /// Instantiated (D-7), its id unified with the next situation's value.
    Instance(Instance),
    /// Compiled: `selected` is the next situation's value that selected it
    /// (then also its id), `None` when entered by index or as the initial one.
    /// `id` is the atom (or name, for code that builds its compound id).
    Compiled { id: Term, selected: Option<Term> },
}

/// Where control goes next in the top frame.
enum Goto {
    Initial,
    Situation(Term),
    /// A situation of the running DM chosen when the program was compiled.
    Index(SitIx),
}

/// The machine's state.
pub struct Machine<'p, P: DmProgram> {
    program: &'p P,
    pub store: Store,
    pub globals: Vars,
    pub functions: Functions,
    pub options: Options,
    frames: Vec<Frame>,
    /// Instances of the recursive situations waiting for their embedded
    /// DMs (interpreted path), innermost last.
    instances: Vec<Instance>,
    /// Reused buffers (no allocation per transition once warm).
    scratch_locals: Vars,
    scratch_globals: Vars,
    arcs: Vec<[Term; 4]>,
    expectations: Vec<Term>,
    transitions: u64,
    cells_after_gc: usize,
    /// Functor that pairs an arc with its out_arg for one joint copy (D-11);
    /// interned once, not per transition.
    arc_functor: Atom,
    /// The perception answered [`Perceived::Again`]: the situation is
    /// entered again without its recovery DM.
    again: bool,
}

/// What happened in one situation: the chosen arc's terms.
struct Chosen {
    arc: usize,
    expectation: Term,
    action: Term,
    next: Term,
    out_arg: Option<Term>,
}

impl<'p, P: DmProgram> Machine<'p, P> {
    pub fn new(
        program: &'p P,
        store: Store,
        globals: Vars,
        functions: Functions,
        options: Options,
    ) -> Self {
        Machine {
            program,
            store,
            globals,
            functions,
            options,
            frames: Vec::new(),
            instances: Vec::new(),
            scratch_locals: Vars::new(),
            scratch_globals: Vars::new(),
            arcs: Vec::new(),
            expectations: Vec::new(),
            transitions: 0,
            cells_after_gc: 0,
            arc_functor: Atom::intern("$arc"),
            again: false,
        }
    }

    fn err(
        &self,
        message: impl Into<String>,
        sit: Option<(SitIx, Term)>,
        arc: Option<usize>,
    ) -> RunError {
        let frame = self.frames.last();
        RunError {
            message: message.into(),
            dm: frame.map(|f| self.store.writeq(f.dm_id)),
            situation: sit.map(|(_, id)| self.store.writeq(id)),
            arc: arc.map(|a| a + 1),
            location: match (frame, sit) {
                (Some(f), Some((s, _))) => self.program.location(f.dm, s),
                _ => None,
            },
            site: match (frame, sit) {
                (Some(f), Some((s, _))) => Some(Box::new(ErrorSite {
                    dm: f.dm,
                    situation: s,
                    culprit: None,
                })),
                _ => None,
            },
        }
    }

    /// Runs `main` (a DM call term) with `in_arg` as the initial pipe;
    /// returns the outcome and the store its terms live in.
    pub fn run(
        mut self,
        main: Term,
        in_arg: Term,
        perception: &mut dyn Perception,
        actions: &mut dyn Actions,
        mut observer: Option<&mut dyn Observer>,
    ) -> (Outcome, Store) {
        let mut pipe = in_arg;
        let mut final_situation = None;
        let result = self.run_loop(
            main,
            &mut pipe,
            perception,
            actions,
            &mut observer,
            &mut final_situation,
        );
        if let (Err(e), Some(o)) = (&result, &mut observer) {
            self.inspect(pipe, Some(e), &mut **o);
        }
        // On error, the history so far: unwind the stack, nesting each
        // embedded DM's partial history into its caller's, as if it returned.
        let mut history = Vec::new();
        while let Some(frame) = self.frames.pop() {
            let mut h = frame.history;
            if !history.is_empty() {
                h.push(Item::Nested(std::mem::take(&mut history)));
            }
            history = h;
        }
        let interrupted = result.is_err() && self.stop_requested();
        let outcome = Outcome {
            interrupted,
            result,
            history,
            out_arg: pipe,
            globals: self.globals,
            final_situation,
            transitions: self.transitions,
        };
        (outcome, self.store)
    }

    /// Whether [`Options::stop`] is set.
    #[inline]
    fn stop_requested(&self) -> bool {
        self.options
            .stop
            .as_ref()
            .is_some_and(|s| s.load(std::sync::atomic::Ordering::Relaxed))
    }

    fn call_dm(&mut self, call: Term, sit: Option<(SitIx, Term)>) -> Result<(), RunError> {
        if self.frames.len() >= self.options.max_depth {
            return Err(self.err(
                format!(
                    "the DM stack exceeded {} nested DMs",
                    self.options.max_depth
                ),
                sit,
                None,
            ));
        }
        let call = self.store.deref(call);
        let Some((name, _)) = self.store.functor(call) else {
            return Err(self.err(
                format!("`{}` does not name a DM", self.store.writeq(call)),
                sit,
                None,
            ));
        };
        let Some(dm) = self.program.dm_by_name(name) else {
            return Err(self.err(format!("there is no DM named `{name}`"), sit, None));
        };
        let head = self.program.fresh_head(dm, &mut self.store);
        if !self.store.unify(head, call) {
            return Err(self.err(
                format!(
                    "the call `{}` does not match the DM's head `{}`",
                    self.store.writeq(call),
                    self.store.writeq(head)
                ),
                sit,
                None,
            ));
        }
        let locals = self.program.locals(dm, &mut self.store);
        self.frames.push(Frame {
            dm,
            dm_id: call,
            locals,
            history: Vec::new(),
            pending: None,
        });
        Ok(())
    }

    fn run_loop(
        &mut self,
        main: Term,
        pipe: &mut Term,
        perception: &mut dyn Perception,
        actions: &mut dyn Actions,
        observer: &mut Option<&mut dyn Observer>,
        final_situation: &mut Option<Term>,
    ) -> Result<(), RunError> {
        self.call_dm(main, None)?;
        let mut goto = Goto::Initial;
        let program = self.program;
        loop {
            if self.stop_requested() {
                return Err(self.err("interrupted (the run was stopped by a signal)", None, None));
            }
            self.maybe_gc(pipe, &mut goto);
            self.between(&mut goto)?;
            let (sit, inst) = self.select(&goto)?;
            let dm = self.frames.last().expect("a frame is running").dm;
            let inst = match inst {
                Selected::Instance(inst) => inst,
                Selected::Compiled { id, selected } => {
                    // Compiled code runs the situation; the machine takes the step it returns.
                    let mut cx = Cx {
                        m: self,
                        pipe,
                        perception,
                        actions,
                        observer: reborrow(observer),
                        sit,
                        id,
                        selected,
                    };
                    let step = program.run_situation(dm, sit, &mut cx)?;
                    // The code may have gone on to other situations of the DM.
                    let (sit, id) = (cx.sit, cx.id);
                    match self.take_step(step, sit, id, pipe, perception, actions, observer)? {
                        Some(next) => goto = next,
                        None => {
                            *final_situation = Some(id);
                            return Ok(());
                        }
                    }
                    continue;
                }
            };
            let here = Some((sit, inst.id));
            // in_arg is a pattern unified with the incoming pipe (D-8, E14).
            if let Some(pattern) = inst.in_arg {
                self.unify_in_arg(pattern, *pipe, here)?;
            }
            let step = match program.kind(dm, sit) {
                Kind::Final => {
                    self.run_prog(inst.prog, &[inst.in_arg, inst.out_arg], here)?;
                    self.final_out_arg(inst.out_arg, pipe, here)?;
                    self.bind_diag_mod(inst.diag_mod, here)?;
                    let empty = Term::atom(atoms::EMPTY);
                    self.record(inst.id, empty, empty, None, *pipe, observer);
                    Step::Final
                }
                Kind::Recursive => {
                    self.run_prog(inst.prog, &[inst.in_arg], here)?;
                    let Some(e) = inst.embedded_dm else {
                        return Err(self.err(
                            "recursive situation without `embedded_dm`",
                            here,
                            None,
                        ));
                    };
                    let call = self.eval_read_only(e, here)?;
                    self.frames.last_mut().expect("frame").pending =
                        Some(Pending::Recursive { sit });
                    self.instances.push(inst);
                    self.call_dm(call, here)?;
                    goto = Goto::Initial;
                    continue;
                }
                Kind::Perceptual => {
                    self.run_prog(inst.prog, &[inst.in_arg, inst.out_arg], here)?;
                    match self.choose_perceptual(sit, &inst, perception)? {
                        Some(chosen) => {
                            Step::Goto(self.conclude(&inst, here, chosen, pipe, actions, observer)?)
                        }
                        None => Step::Unmet {
                            type_term: inst.type_term,
                        },
                    }
                }
            };
            match self.take_step(step, sit, inst.id, pipe, perception, actions, observer)? {
                Some(next) => goto = next,
                None => {
                    *final_situation = Some(inst.id);
                    return Ok(());
                }
            }
        }
    }

    /// Where control goes after situation `sit` (id `id`) of the running DM
    /// took `step`; `None` when the main DM has ended.
    #[allow(clippy::too_many_arguments)]
    fn take_step(
        &mut self,
        mut step: Step,
        mut sit: SitIx,
        mut id: Term,
        pipe: &mut Term,
        perception: &mut dyn Perception,
        actions: &mut dyn Actions,
        observer: &mut Option<&mut dyn Observer>,
    ) -> Result<Option<Goto>, RunError> {
        let program = self.program;
        loop {
            let here = Some((sit, id));
            match step {
                Step::Goto(next) => return Ok(Some(Goto::Situation(next))),
                Step::GotoSit(next) => return Ok(Some(Goto::Index(next))),
                Step::Call { call, saved } => {
                    self.frames.last_mut().expect("frame").pending =
                        Some(Pending::Compiled { sit, saved, id });
                    self.call_dm(call, here)?;
                    return Ok(Some(Goto::Initial));
                }
                Step::Unmet { .. } if std::mem::take(&mut self.again) => {
                    // Asked to perceive again: a new instance, no recovery.
                    return Ok(Some(Goto::Situation(id)));
                }
                Step::Unmet { type_term } => {
                    // No expectation met (D-15 / D-42a): recovery DM, then a new instance.
                    let ty = self
                        .store
                        .atom_of(type_term)
                        .or_else(|| self.store.functor(type_term).map(|(n, _)| n));
                    let recovery = ty.and_then(|t| {
                        self.options
                            .recovery
                            .iter()
                            .find(|(k, _)| *k == t)
                            .map(|r| r.1)
                    });
                    return match recovery {
                        Some(dm_name) => {
                            self.frames.last_mut().expect("frame").pending =
                                Some(Pending::Recovery { id });
                            self.call_dm(Term::atom(dm_name), here)?;
                            Ok(Some(Goto::Initial))
                        }
                        None => Ok(Some(Goto::Situation(id))),
                    };
                }
                Step::Final => {
                    let frame = self.frames.pop().expect("a frame is running");
                    let Some(caller) = self.frames.last_mut() else {
                        self.frames.push(frame); // keep for the history
                        return Ok(None);
                    };
                    if self.options.keep_history {
                        caller.history.push(Item::Nested(frame.history));
                    }
                    match caller.pending.take() {
                        Some(Pending::Recursive { sit }) => {
                            let rinst = self.instances.pop().expect("a pending instance");
                            let next =
                                self.finish_recursive(sit, rinst, id, pipe, actions, observer)?;
                            return Ok(Some(Goto::Situation(next)));
                        }
                        Some(Pending::Recovery { id }) => return Ok(Some(Goto::Situation(id))),
                        Some(Pending::Compiled {
                            sit: rsit,
                            saved,
                            id: rid,
                        }) => {
                            let final_id = id;
                            let dm = self.frames.last().expect("caller").dm;
                            (sit, id) = (rsit, rid);
                            let mut cx = Cx {
                                m: self,
                                pipe,
                                perception,
                                actions,
                                observer: reborrow(observer),
                                sit,
                                id,
                                selected: Some(id),
                            };
                            step = program.run_exit(dm, sit, saved, final_id, &mut cx)?;
                        }
                        None => unreachable!("a caller frame always has a pending situation"),
                    }
                }
            }
        }
    }

    fn unify_in_arg(
        &mut self,
        pattern: Term,
        pipe: Term,
        here: Option<(SitIx, Term)>,
    ) -> Result<(), RunError> {
        if self.store.unify(pattern, pipe) {
            return Ok(());
        }
        Err(self.err(
            format!(
                "in_arg `{}` does not match the incoming pipe value `{}`",
                self.store.writeq(pattern),
                self.store.writeq(pipe)
            ),
            here,
            None,
        ))
    }

    /// A final situation's out_arg, evaluated, becomes the pipe unless it is a variable.
    fn final_out_arg(
        &mut self,
        out_arg: Option<Term>,
        pipe: &mut Term,
        here: Option<(SitIx, Term)>,
    ) -> Result<(), RunError> {
        let out = match out_arg {
            Some(o) => self.eval_in_frame(o, here, None)?,
            None => *pipe,
        };
        if !self.store.is_var(out) {
            *pipe = out;
        }
        Ok(())
    }

    /// Picks the situation to run (D-7, D-21), instantiated unless it is compiled.
    fn select(&mut self, goto: &Goto) -> Result<(SitIx, Selected), RunError> {
        let frame = self.frames.last().expect("a frame is running");
        let (dm, dm_id) = (frame.dm, frame.dm_id);
        match *goto {
            Goto::Initial => {
                if self.program.situation_count(dm) == 0 {
                    return Err(self.err("the DM has no situations", None, None));
                }
                if let Some((name, _)) = self.program.compiled_id(dm, 0) {
                    let id = Term::atom(name);
                    return Ok((0, Selected::Compiled { id, selected: None }));
                }
                let inst = self.program.instantiate(dm, 0, &mut self.store);
                if !self.store.unify(inst.head, dm_id) {
                    return Err(self.err(
                        format!(
                            "the call `{}` does not match the DM's head",
                            self.store.writeq(dm_id)
                        ),
                        None,
                        None,
                    ));
                }
                Ok((0, Selected::Instance(inst)))
            }
            Goto::Index(sit) => {
                if let Some((name, _)) = self.program.compiled_id(dm, sit) {
                    let id = Term::atom(name);
                    return Ok((sit, Selected::Compiled { id, selected: None }));
                }
                let inst = self.program.instantiate(dm, sit, &mut self.store);
                self.link_head(inst.head, dm_id);
                Ok((sit, Selected::Instance(inst)))
            }
            Goto::Situation(value) => {
                let value = self.store.deref(value);
                if self.store.functor(value).is_none() {
                    return Err(self.err(
                        format!(
                            "the next situation `{}` is not a situation name",
                            self.store.writeq(value)
                        ),
                        None,
                        None,
                    ));
                }
                let functor = self.store.functor(value);
                for sit in 0..self.program.situation_count(dm) as SitIx {
                    if let Some(id) = self.program.compiled_id(dm, sit) {
                        if functor != Some(id) {
                            continue;
                        }
                        if id.1 == 0 {
                            // An atom id unifies only with that atom.
                            let id = Term::atom(id.0);
                            return Ok((sit, Selected::Compiled { id, selected: None }));
                        }
                        let mark = self.store.mark();
                        if self
                            .program
                            .select_compiled(dm, sit, value, &mut self.store)
                        {
                            let selected = Some(value);
                            return Ok((
                                sit,
                                Selected::Compiled {
                                    id: value,
                                    selected,
                                },
                            ));
                        }
                        self.store.undo_to(mark);
                        continue;
                    }
                    if !self.program.may_select(dm, sit, value, &self.store) {
                        continue;
                    }
                    let mark = self.store.mark();
                    let inst = self.program.instantiate(dm, sit, &mut self.store);
                    if self.store.unify(inst.id, value) {
                        self.link_head(inst.head, dm_id);
                        return Ok((sit, Selected::Instance(inst)));
                    }
                    self.store.undo_to(mark);
                }
                Err(self.err(
                    format!(
                        "there is no situation `{}` in this DM",
                        self.store.writeq(value)
                    ),
                    None,
                    None,
                ))
            }
        }
    }

    /// Links a later situation's fresh head to the DM call, argument by
    /// argument where they unify (D-7).
    fn link_head(&mut self, head: Term, dm_id: Term) {
        let n = self.store.args(head).len();
        for i in 0..n {
            let (h, d) = (self.store.args(head)[i], self.store.arg(dm_id, i));
            if let Some(d) = d {
                let mark = self.store.mark();
                if !self.store.unify(h, d) {
                    self.store.undo_to(mark);
                }
            }
        }
    }

    /// `prog` on a renamed copy linked to in_arg/out_arg only (D-10):
    /// `links` are the terms whose variables stay shared.
    fn run_prog(
        &mut self,
        prog: Option<Term>,
        links: &[Option<Term>],
        here: Option<(SitIx, Term)>,
    ) -> Result<(), RunError> {
        let Some(prog) = prog else { return Ok(()) };
        let mut map = crate::copy::VarMap::new();
        for &linked in links.iter().flatten() {
            for v in self.store.term_vars(linked) {
                if let crate::term::Value::Var(var) = self.store.value(v) {
                    map.insert(var, v);
                }
            }
        }
        let copy = self.store.copy_term_with(prog, &mut map);
        self.eval_in_frame(copy, here, None).map(|_| ())
    }

    /// What the evaluator sees: the store, the running DM's locals and
    /// history, the globals and the functions.
    fn eval_ctx(&mut self) -> EvalCtx<'_> {
        let frame = self.frames.last_mut().expect("a frame is running");
        EvalCtx {
            store: &mut self.store,
            locals: &mut frame.locals,
            globals: &mut self.globals,
            history: &frame.history,
            functions: &self.functions,
        }
    }

    fn eval_in_frame(
        &mut self,
        t: Term,
        here: Option<(SitIx, Term)>,
        arc: Option<usize>,
    ) -> Result<Term, RunError> {
        match eval::eval(&mut self.eval_ctx(), t) {
            Ok(v) => Ok(v),
            Err(EvalError { message, culprit }) => {
                let mut e = self.err(message, here, arc);
                if let Some(site) = e.site.as_mut() {
                    site.culprit = culprit;
                }
                Err(e)
            }
        }
    }

    /// Evaluates with the variables read-only: updates are discarded
    /// (`embedded_dm` sees locals and globals; `diag_mod` too, E12).
    fn eval_read_only(&mut self, t: Term, here: Option<(SitIx, Term)>) -> Result<Term, RunError> {
        let frame = self.frames.last().expect("frame");
        self.scratch_locals.restore_from(&frame.locals);
        self.scratch_globals.restore_from(&self.globals);
        let r = self.eval_in_frame(t, here, None);
        let frame = self.frames.last_mut().expect("frame");
        frame.locals.restore_from(&self.scratch_locals);
        self.globals.restore_from(&self.scratch_globals);
        r
    }

    /// Copies every arc with its own out_arg (D-11) and evaluates the
    /// expectations in order, discarding variable updates (D-12).
    fn prepare_arcs(
        &mut self,
        inst: &Instance,
        here: Option<(SitIx, Term)>,
    ) -> Result<(), RunError> {
        self.arcs.clear();
        self.expectations.clear();
        let arc_functor = self.arc_functor;
        let out = inst.out_arg.unwrap_or(Term::atom(atoms::NONE));
        // Walk the list in place (no allocation per transition).
        let mut rest = inst.arcs;
        while let Some(&[arc, tail]) = self.store.compound_args(rest, atoms::DOT, 2) {
            let (e, a, n) = match self.store.args(arc) {
                &[e, a, n, ..] => (e, a, n),
                _ => break,
            };
            let both = self.store.compound(arc_functor, &[e, a, n, out]);
            let copy = self.store.copy_term(both);
            let c = self.store.args(copy);
            self.arcs.push([c[0], c[1], c[2], c[3]]);
            rest = tail;
        }
        let frame = self.frames.last().expect("frame");
        self.scratch_locals.restore_from(&frame.locals);
        self.scratch_globals.restore_from(&self.globals);
        let mut result = Ok(());
        for i in 0..self.arcs.len() {
            match self.eval_in_frame(self.arcs[i][0], here, Some(i)) {
                Ok(v) => self.expectations.push(v),
                Err(e) => {
                    result = Err(e);
                    break;
                }
            }
        }
        let frame = self.frames.last_mut().expect("frame");
        frame.locals.restore_from(&self.scratch_locals);
        self.globals.restore_from(&self.scratch_globals);
        result
    }

    /// Asks the perceptual interpreter which expectation is met (D-14, E2, E3).
    fn choose_perceptual(
        &mut self,
        sit: SitIx,
        inst: &Instance,
        perception: &mut dyn Perception,
    ) -> Result<Option<Chosen>, RunError> {
        let here = Some((sit, inst.id));
        self.prepare_arcs(inst, here)?;
        let Some(i) = self.choose_index(inst.type_term, here, perception)? else {
            return Ok(None);
        };
        Ok(Some(Chosen {
            arc: i,
            expectation: self.expectations[i],
            action: self.arcs[i][1],
            next: self.arcs[i][2],
            out_arg: inst.out_arg.map(|_| self.arcs[i][3]),
        }))
    }

    /// Which of the evaluated expectations (`self.expectations`, one per
    /// arc) is met: the neutral rule, else what the perceptual interpreter
    /// perceived, the last arc whose expectation unifies winning (D-14, E2, E3).
    fn choose_index(
        &mut self,
        type_term: Term,
        here: Option<(SitIx, Term)>,
        perception: &mut dyn Perception,
    ) -> Result<Option<usize>, RunError> {
        if self.expectations.is_empty() {
            return Err(self.err("the situation has no arcs", here, None));
        }
        if self.store.atom_of(type_term) == Some(atoms::NEUTRAL) {
            let e = self.store.deref(self.expectations[0]);
            if self.expectations.len() == 1
                && (self.store.atom_of(e) == Some(atoms::EMPTY) || self.store.is_var(e))
            {
                let _ = self.store.unify(e, Term::atom(atoms::EMPTY));
                self.expectations[0] = e;
                return Ok(Some(0));
            }
            return Err(self.err(
                "a `neutral` situation needs exactly one arc, with expectation `empty`",
                here,
                None,
            ));
        }
        let second_read_allowed = self.expectations.len() == 1 || {
            let first = self.store.deref(self.expectations[0]);
            self.store.list_to_vec(first).is_some()
                && self.store.functor(first).is_some_and(|f| f.0 == atoms::DOT)
        };
        if let (Some((_, id)), Some(frame)) = (here, self.frames.last()) {
            perception.waiting_at(&self.store, frame.dm_id, id);
        }
        for attempt in 0..2 {
            let exps = std::mem::take(&mut self.expectations);
            let perceived = perception.perceive(&mut self.store, type_term, &exps);
            self.expectations = exps;
            let input = match perceived {
                Ok(Perceived::Input(t)) => t,
                Ok(Perceived::Again) => {
                    self.again = true;
                    return Ok(None);
                }
                Ok(Perceived::EndOfInput) => {
                    return Err(self.err(
                        "end of input while the situation waits for an expectation",
                        here,
                        None,
                    ))
                }
                Err(e) => return Err(self.err(format!("perception failed: {e}"), here, None)),
            };
            // The last arc whose expectation unifies wins (D-14, E2).
            for i in (0..self.expectations.len()).rev() {
                let mark = self.store.mark();
                if self.store.unify(input, self.expectations[i]) {
                    return Ok(Some(i));
                }
                self.store.undo_to(mark);
            }
            if attempt == 0 && !second_read_allowed {
                break;
            }
        }
        Ok(None)
    }

    /// The first exit arc whose expectation unifies with the embedded DM's
    /// final situation (D-22), or an error.
    fn choose_exit_index(
        &mut self,
        final_id: Term,
        here: Option<(SitIx, Term)>,
    ) -> Result<usize, RunError> {
        for i in 0..self.expectations.len() {
            let mark = self.store.mark();
            if self.store.unify(self.expectations[i], final_id) {
                return Ok(i);
            }
            self.store.undo_to(mark);
        }
        Err(self.err(
            format!(
                "no exit arc for the embedded DM's final situation `{}`",
                self.store.writeq(final_id)
            ),
            here,
            None,
        ))
    }

    /// Action, next situation, pipe, diag_mod and history entry of a chosen arc (D-16..D-20).
    fn conclude(
        &mut self,
        inst: &Instance,
        here: Option<(SitIx, Term)>,
        chosen: Chosen,
        pipe: &mut Term,
        actions: &mut dyn Actions,
        observer: &mut Option<&mut dyn Observer>,
    ) -> Result<Term, RunError> {
        let arc = Some(chosen.arc);
        let action = self.eval_in_frame(chosen.action, here, arc)?;
        self.perform(action, actions, here, arc)?;
        let next = self.eval_in_frame(chosen.next, here, arc)?;
        if let Some(out) = chosen.out_arg {
            let value = self.eval_in_frame(out, here, arc)?;
            if !self.store.is_var(value) {
                *pipe = value;
            }
        }
        self.bind_diag_mod(inst.diag_mod, here)?;
        self.record(
            inst.id,
            chosen.expectation,
            action,
            Some(next),
            *pipe,
            observer,
        );
        let n = self.store.deref(next);
        if self.store.functor(n).is_none() {
            return Err(self.err(
                format!(
                    "the next situation evaluates to `{}`, which is not a situation name",
                    self.store.writeq(n)
                ),
                here,
                arc,
            ));
        }
        Ok(n)
    }

    fn perform(
        &mut self,
        action: Term,
        actions: &mut dyn Actions,
        here: Option<(SitIx, Term)>,
        arc: Option<usize>,
    ) -> Result<(), RunError> {
        let a = self.store.deref(action);
        // A proper list is executed element by element (checked and walked
        // in place: no allocation per transition).
        let is_list = self.store.functor(a).is_some_and(|f| f.0 == atoms::DOT) && {
            let mut it = self.store.list_iter(a);
            it.by_ref().for_each(drop);
            it.tail() == Term::NIL
        };
        let result = if is_list {
            // Walked by position: an action may bind variables (and so grow
            // the store) while the list is performed.
            let mut rest = a;
            let mut result = Ok(());
            while let Some(&[head, tail]) = self.store.compound_args(rest, atoms::DOT, 2) {
                result = actions.perform(&mut self.store, head);
                if result.is_err() {
                    break;
                }
                rest = tail;
            }
            result
        } else {
            actions.perform(&mut self.store, a)
        };
        result.map_err(|e| self.err(format!("action failed: {e}"), here, arc))
    }

    /// Evaluates `diag_mod` (read-only variables) and unifies it with the DM id (D-20, E9).
    fn bind_diag_mod(
        &mut self,
        diag_mod: Option<Term>,
        here: Option<(SitIx, Term)>,
    ) -> Result<(), RunError> {
        let Some(d) = diag_mod else {
            return Ok(());
        };
        let value = self.eval_read_only(d, here)?;
        let dm_id = self.frames.last().expect("frame").dm_id;
        if !self.store.unify(value, dm_id) {
            return Err(self.err(
                format!(
                    "diag_mod `{}` does not match the DM's identifier `{}`",
                    self.store.writeq(value),
                    self.store.writeq(dm_id)
                ),
                here,
                None,
            ));
        }
        Ok(())
    }

    /// Exit arc of a recursive situation whose embedded DM ended in `final_id` (D-22).
    fn finish_recursive(
        &mut self,
        sit: SitIx,
        inst: Instance,
        final_id: Term,
        pipe: &mut Term,
        actions: &mut dyn Actions,
        observer: &mut Option<&mut dyn Observer>,
    ) -> Result<Term, RunError> {
        let here = Some((sit, inst.id));
        self.prepare_arcs(&inst, here)?;
        let i = self.choose_exit_index(final_id, here)?;
        let chosen = Chosen {
            arc: i,
            expectation: self.expectations[i],
            action: self.arcs[i][1],
            next: self.arcs[i][2],
            out_arg: inst.out_arg.map(|_| self.arcs[i][3]),
        };
        self.conclude(&inst, here, chosen, pipe, actions, observer)
    }

    #[allow(clippy::too_many_arguments)]
    fn record(
        &mut self,
        situation: Term,
        expectation: Term,
        action: Term,
        next: Option<Term>,
        pipe: Term,
        observer: &mut Option<&mut dyn Observer>,
    ) {
        self.transitions += 1;
        let frame = self.frames.last_mut().expect("frame");
        let entry = Entry {
            dm: frame.dm_id,
            situation,
            expectation,
            action,
        };
        if let Some(o) = observer.as_deref_mut() {
            o.transition(&self.store, &entry, self.frames.len() - 1, next);
        }
        if self.options.keep_history {
            self.frames
                .last_mut()
                .expect("frame")
                .history
                .push(Item::Entry(entry));
        }
        if let Some(o) = observer.as_deref_mut() {
            self.inspect(pipe, None, o);
        }
    }

    /// Lets `observer` inspect the machine ([`Observer::inspect`]).
    fn inspect(&mut self, pipe: Term, error: Option<&RunError>, observer: &mut dyn Observer) {
        observer.inspect(&mut Inspection {
            store: &mut self.store,
            globals: &mut self.globals,
            functions: &self.functions,
            pipe,
            error,
            frames: &mut self.frames,
            instances: &self.instances,
        });
    }

    /// Lets the program look at the machine between two transitions
    /// ([`DmProgram::between`]).
    #[inline]
    fn between(&mut self, goto: &mut Goto) -> Result<(), RunError> {
        let next = match *goto {
            Goto::Initial => Next::Initial,
            Goto::Situation(t) => Next::Situation(t),
            Goto::Index(s) => Next::Index(s),
        };
        let mut at = Between {
            store: &mut self.store,
            globals: &mut self.globals,
            functions: &mut self.functions,
            next,
            frames: &mut self.frames,
        };
        match self.program.between(&mut at) {
            Ok(()) => Ok(()),
            Err(message) => Err(self.err(message, None, None)),
        }
    }

    /// Collects garbage when the store has grown enough; roots are everything
    /// the machine still refers to.
    fn maybe_gc(&mut self, pipe: &mut Term, goto: &mut Goto) {
        let cells = self.store.stats().cells + self.store.stats().vars;
        if cells < self.cells_after_gc + self.options.gc_threshold {
            return;
        }
        let mut roots: Vec<Term> = vec![*pipe];
        if let Goto::Situation(t) = goto {
            roots.push(*t);
        }
        roots.extend(self.globals.entries().iter().map(|e| e.1));
        for f in &self.frames {
            roots.push(f.dm_id);
            roots.extend(f.locals.entries().iter().map(|e| e.1));
            collect_history_roots(&f.history, &mut roots);
            if let Some(Pending::Recovery { id }) = &f.pending {
                roots.push(*id);
            }
            if let Some(Pending::Compiled { saved, id, .. }) = &f.pending {
                roots.push(*saved);
                roots.push(*id);
            }
        }
        for inst in &self.instances {
            roots.extend(instance_terms(inst));
        }
        self.store.gc(&mut roots);
        // Write the relocated roots back in the same order.
        let mut it = roots.into_iter();
        *pipe = it.next().expect("pipe root");
        if let Goto::Situation(t) = goto {
            *t = it.next().expect("goto root");
        }
        for v in self.globals.values_mut() {
            *v = it.next().expect("global root");
        }
        for f in &mut self.frames {
            f.dm_id = it.next().expect("dm root");
            for v in f.locals.values_mut() {
                *v = it.next().expect("local root");
            }
            restore_history_roots(&mut f.history, &mut it);
            if let Some(Pending::Recovery { id }) = &mut f.pending {
                *id = it.next().expect("recovery root");
            }
            if let Some(Pending::Compiled { saved, id, .. }) = &mut f.pending {
                *saved = it.next().expect("compiled situation root");
                *id = it.next().expect("compiled situation root");
            }
        }
        for inst in &mut self.instances {
            set_instance_terms(inst, &mut it);
        }
        self.cells_after_gc = self.store.stats().cells + self.store.stats().vars;
    }
}

/// What compiled code of a situation sees of the machine: one method per
/// semantic step, each the one the interpreted path takes, so generated code
/// decides only *which* steps a situation needs, never how they behave.
///
/// Terms built through it live in the run's store; they stay valid until the
/// situation returns its [`Step`] (garbage is collected only between situations).
pub struct Cx<'a, 'p, P: DmProgram> {
    m: &'a mut Machine<'p, P>,
    pipe: &'a mut Term,
    perception: &'a mut dyn Perception,
    actions: &'a mut dyn Actions,
    observer: Option<&'a mut dyn Observer>,
    sit: SitIx,
    id: Term,
    selected: Option<Term>,
}

impl<P: DmProgram> Cx<'_, '_, P> {
    fn here(&self) -> Option<(SitIx, Term)> {
        Some((self.sit, self.id))
    }

    /// A run-time error in this situation (`arc`: 0-based).
    pub fn error(&self, message: impl Into<String>, arc: Option<usize>) -> RunError {
        self.m.err(message, self.here(), arc)
    }

    /// A run-time error of `op(name, _)` (`get`, `set`, `inc`, ...) in this
    /// situation, blaming that construct as the machine's evaluator does.
    fn var_op_error(&self, message: String, op: Atom, name: Atom, arc: Option<usize>) -> RunError {
        let mut e = self.error(message, arc);
        if let Some(site) = e.site.as_mut() {
            site.culprit = Some(eval::Culprit {
                name: op,
                arity: 2,
                inner: Some((name, 0)),
            });
        }
        e
    }

    pub fn store(&mut self) -> &mut Store {
        &mut self.m.store
    }

    /// The value of the next situation that selected this one (its id
    /// then), or `None` when the situation was entered by index (an atom
    /// id) or as its DM's initial situation.
    #[inline]
    pub fn selected(&self) -> Option<Term> {
        self.selected
    }

    /// Sets the situation's id (a compound id built by the situation's code
    /// when it was not selected by a value).
    #[inline]
    pub fn set_id(&mut self, id: Term) {
        self.id = id;
    }

    /// Whether the machine wants control back before the next situation
    /// (the store has grown enough to be collected). Until then, code may go
    /// on to a compiled situation of the same DM by itself, after [`Cx::enter`].
    #[inline]
    pub fn gc_due(&self) -> bool {
        let stats = self.m.store.stats();
        stats.cells + stats.vars >= self.m.cells_after_gc + self.m.options.gc_threshold
            || self.m.stop_requested()
    }

    /// Goes on to compiled situation `sit` of the running DM, whose id is the atom `id`.
    #[inline]
    pub fn enter(&mut self, sit: SitIx, id: Atom) {
        self.sit = sit;
        self.id = Term::atom(id);
        self.selected = None;
    }

    /// A fresh variable.
    #[inline]
    pub fn var(&mut self) -> Term {
        self.m.store.new_var()
    }

    #[inline]
    pub fn compound(&mut self, name: Atom, args: &[Term]) -> Term {
        self.m.store.compound(name, args)
    }

    /// Argument `i` of compound `t` (as [`Step::Call`]'s `saved` keeps them).
    #[inline]
    pub fn arg(&self, t: Term, i: usize) -> Term {
        self.m.store.args(t)[i]
    }

    /// Argument `i` of the running DM's call: the value a head parameter
    /// written as a variable takes (D-7); a fresh variable if the call has
    /// no such argument.
    #[inline]
    pub fn head_arg(&mut self, i: usize) -> Term {
        let dm_id = self.m.frames.last().expect("a frame is running").dm_id;
        match self.m.store.arg(dm_id, i) {
            Some(a) => a,
            None => self.m.store.new_var(),
        }
    }

    /// The incoming pipe value.
    #[inline]
    pub fn pipe(&self) -> Term {
        *self.pipe
    }

    /// Unifies the situation's in_arg pattern with the incoming pipe (D-8, E14).
    pub fn in_arg(&mut self, pattern: Term) -> Result<(), RunError> {
        let here = self.here();
        self.m.unify_in_arg(pattern, *self.pipe, here)
    }

    /// Runs `prog` on a copy sharing only the variables of `links` (D-10).
    pub fn prog(&mut self, prog: Term, links: &[Option<Term>]) -> Result<(), RunError> {
        let here = self.here();
        self.m.run_prog(Some(prog), links, here)
    }

    /// What an arc sees of the situation's variables: each value copied with
    /// the arc (D-11), jointly, so shared unbound variables stay shared.
    /// Atomic values are their own copies (no work).
    pub fn import(&mut self, values: &mut [Term]) {
        let store = &mut self.m.store;
        let mut all_atomic = true;
        for v in values.iter_mut() {
            *v = store.deref(*v);
            all_atomic &= store.is_atomic(*v);
        }
        if all_atomic {
            return;
        }
        let both = store.compound(self.m.arc_functor, values);
        let copy = store.copy_term(both);
        values.copy_from_slice(store.args(copy));
    }

    /// Evaluates `t` in L (D-28..D-39).
    pub fn eval(&mut self, t: Term, arc: Option<usize>) -> Result<Term, RunError> {
        let here = self.here();
        self.m.eval_in_frame(t, here, arc)
    }

    /// The value of a variable occurrence in L: what [`Cx::eval`] gives,
    /// without a call when it is not bound to a compound.
    #[inline]
    pub fn value(&mut self, t: Term, arc: Option<usize>) -> Result<Term, RunError> {
        let t = self.m.store.deref(t);
        if self.m.store.is_compound(t) {
            return self.eval(t, arc);
        }
        Ok(t)
    }

    /// `op(name, arg)` for `op` in `get`, `set`, `inc` (D-38); `arg` as written.
    pub fn var_op(
        &mut self,
        op: Atom,
        name: Atom,
        arg: Term,
        arc: Option<usize>,
    ) -> Result<Term, RunError> {
        let r = eval::var_op_named(&mut self.m.eval_ctx(), op, name, arg);
        r.map_err(|e| self.var_op_error(e.message, op, name, arc))
    }

    /// `op(name, V)` for `op` in `get`, `inc`, where `V` is a variable that
    /// occurs nowhere else yet: the value `V` would be bound to, without
    /// making `V` (the caller uses the value in its place).
    pub fn var_op_fresh(
        &mut self,
        op: Atom,
        name: Atom,
        arc: Option<usize>,
    ) -> Result<Term, RunError> {
        let r = eval::var_op_fresh(&mut self.m.eval_ctx(), op, name);
        r.map_err(|e| self.var_op_error(e.message, op, name, arc))
    }

    /// `v is expr` (D-33), both as written (not evaluated); `v: None` for a
    /// variable that occurs nowhere else yet (the value is returned).
    #[inline]
    pub fn is(
        &mut self,
        v: Option<Term>,
        expr: Term,
        arc: Option<usize>,
    ) -> Result<Term, RunError> {
        eval::is(&mut self.m.store, v, expr, None).map_err(|e| self.error(e.message, arc))
    }

    /// A conditional's condition `a op b` with an arithmetic comparison, on evaluated operands.
    #[inline]
    pub fn arith_condition(
        &mut self,
        op: crate::arith::ArithCmp,
        a: Term,
        b: Term,
        arc: Option<usize>,
    ) -> Result<bool, RunError> {
        eval::arith_condition(&mut self.m.store, op, a, b).map_err(|e| self.error(e.message, arc))
    }

    /// Any other condition of a conditional (D-35).
    pub fn condition(&mut self, cond: Term, arc: Option<usize>) -> Result<bool, RunError> {
        let r = eval::condition(&mut self.m.eval_ctx(), cond);
        r.map_err(|e| self.error(e.message, arc))
    }

    /// Keeps the variables' values, to be put back by [`Cx::restore_vars`]:
    /// updates made while expectations are evaluated are discarded (D-12).
    pub fn save_vars(&mut self) {
        let frame = self.m.frames.last().expect("a frame is running");
        self.m.scratch_locals.restore_from(&frame.locals);
        self.m.scratch_globals.restore_from(&self.m.globals);
    }

    pub fn restore_vars(&mut self) {
        let frame = self.m.frames.last_mut().expect("a frame is running");
        frame.locals.restore_from(&self.m.scratch_locals);
        self.m.globals.restore_from(&self.m.scratch_globals);
    }

    /// The evaluated expectations of the situation's arcs, in arc order.
    pub fn set_expectations(&mut self, expectations: &[Term]) {
        self.m.expectations.clear();
        self.m.expectations.extend_from_slice(expectations);
    }

    /// The met expectation of arc `i`, after [`Cx::choose`] or [`Cx::choose_exit`].
    #[inline]
    pub fn expectation(&self, i: usize) -> Term {
        self.m.expectations[i]
    }

    /// Which arc's expectation is met (the neutral rule, else perception, D-14).
    pub fn choose(&mut self, type_term: Term) -> Result<Option<usize>, RunError> {
        let here = self.here();
        self.m.choose_index(type_term, here, &mut *self.perception)
    }

    /// Which exit arc takes the embedded DM's final situation `final_id` (D-22).
    pub fn choose_exit(&mut self, final_id: Term) -> Result<usize, RunError> {
        let here = self.here();
        self.m.choose_exit_index(final_id, here)
    }

    /// Performs an evaluated action (D-17).
    pub fn perform(&mut self, action: Term, arc: Option<usize>) -> Result<(), RunError> {
        let here = self.here();
        self.m.perform(action, &mut *self.actions, here, arc)
    }

    /// Performs the elements of an evaluated action that is a proper,
    /// non-empty list, one by one (what [`Cx::perform`] does with such a list).
    pub fn perform_each(&mut self, elements: &[Term], arc: Option<usize>) -> Result<(), RunError> {
        for &x in elements {
            if let Err(e) = self.actions.perform(&mut self.m.store, x) {
                return Err(self.error(format!("action failed: {e}"), arc));
            }
        }
        Ok(())
    }

    /// Whether history entries are observed (kept, or seen by an observer):
    /// when not, an entry's terms need not be built.
    #[inline]
    pub fn records(&self) -> bool {
        self.m.options.keep_history || self.observer.is_some()
    }

    /// An arc's out_arg: its value becomes the pipe unless it is a variable (D-18).
    pub fn out_arg(&mut self, out: Term, arc: Option<usize>) -> Result<(), RunError> {
        let value = self.eval(out, arc)?;
        if !self.m.store.is_var(value) {
            *self.pipe = value;
        }
        Ok(())
    }

    /// A final situation's out_arg (or the pipe unchanged when `None`).
    pub fn final_out_arg(&mut self, out: Option<Term>) -> Result<(), RunError> {
        let here = self.here();
        self.m.final_out_arg(out, self.pipe, here)
    }

    /// Evaluates `diag_mod` with read-only variables and unifies it with the DM's id (D-20).
    pub fn diag_mod(&mut self, d: Term) -> Result<(), RunError> {
        let here = self.here();
        self.m.bind_diag_mod(Some(d), here)
    }

    /// Evaluates `embedded_dm` with read-only variables: the DM call.
    pub fn embedded_dm(&mut self, e: Term) -> Result<Term, RunError> {
        let here = self.here();
        self.m.eval_read_only(e, here)
    }

    /// The value of the running DM's local variable `name` (dereferenced).
    pub fn local(&self, name: Atom) -> Option<Term> {
        let frame = self.m.frames.last().expect("a frame is running");
        frame.locals.get(name).map(|t| self.m.store.deref(t))
    }

    /// Sets the running DM's local variable `name` (typed code writing its
    /// frame back).
    pub fn set_local(&mut self, name: Atom, value: Term) {
        let frame = self.m.frames.last_mut().expect("a frame is running");
        frame.locals.set(name, value);
    }

    /// Argument `i` of the running DM's call, dereferenced, if it has one.
    pub fn param(&self, i: usize) -> Option<Term> {
        let dm_id = self.m.frames.last().expect("a frame is running").dm_id;
        self.m.store.arg(dm_id, i).map(|t| self.m.store.deref(t))
    }

    /// The integer a (dereferenced) term is, if it is one.
    #[inline]
    pub fn int_of(&self, t: Term) -> Option<i64> {
        match self.m.store.value(t) {
            crate::Value::Int(i) => Some(i),
            _ => None,
        }
    }

    /// The float a (dereferenced) term is, if it is one.
    #[inline]
    pub fn float_of(&self, t: Term) -> Option<f64> {
        match self.m.store.value(t) {
            crate::Value::Float(f) => Some(f),
            _ => None,
        }
    }

    /// Counts transitions typed code made without recording them (the
    /// history neither kept nor observed).
    #[inline]
    pub fn count_transitions(&mut self, n: u64) {
        self.m.transitions += n;
    }

    /// Whether the run's actions ignore numbers ([`Actions::ignores_numbers`]).
    #[inline]
    pub fn ignores_numbers(&self) -> bool {
        self.actions.ignores_numbers()
    }

    /// Appends the situation's history entry (and tells the observer).
    #[inline]
    pub fn record(&mut self, expectation: Term, action: Term, next: Option<Term>) {
        let id = self.id;
        let pipe = *self.pipe;
        self.m
            .record(id, expectation, action, next, pipe, &mut self.observer);
    }

    /// The step to an evaluated next situation, which must name one (D-19).
    pub fn goto(&mut self, next: Term, arc: Option<usize>) -> Result<Step, RunError> {
        let n = self.m.store.deref(next);
        if self.m.store.functor(n).is_none() {
            return Err(self.error(
                format!(
                    "the next situation evaluates to `{}`, which is not a situation name",
                    self.m.store.writeq(n)
                ),
                arc,
            ));
        }
        Ok(Step::Goto(n))
    }
}

/// A shorter-lived handle on the observer (the trait object's lifetime shrinks with it).
fn reborrow<'a>(observer: &'a mut Option<&mut dyn Observer>) -> Option<&'a mut dyn Observer> {
    match observer {
        Some(o) => Some(&mut **o),
        None => None,
    }
}

fn instance_terms(inst: &Instance) -> Vec<Term> {
    let opt = |t: Option<Term>| t.unwrap_or(Term::NIL);
    vec![
        inst.head,
        inst.id,
        inst.type_term,
        opt(inst.in_arg),
        opt(inst.out_arg),
        opt(inst.prog),
        opt(inst.embedded_dm),
        opt(inst.diag_mod),
        inst.arcs,
    ]
}

fn set_instance_terms(inst: &mut Instance, it: &mut impl Iterator<Item = Term>) {
    let mut next = || it.next().expect("instance root");
    inst.head = next();
    inst.id = next();
    inst.type_term = next();
    let opt = |o: &mut Option<Term>, v: Term| {
        if o.is_some() {
            *o = Some(v);
        }
    };
    let (a, b, c, d, e) = (next(), next(), next(), next(), next());
    opt(&mut inst.in_arg, a);
    opt(&mut inst.out_arg, b);
    opt(&mut inst.prog, c);
    opt(&mut inst.embedded_dm, d);
    opt(&mut inst.diag_mod, e);
    inst.arcs = next();
}

fn collect_history_roots(items: &[Item], roots: &mut Vec<Term>) {
    // Nesting depth equals DM call depth: grow the stack as needed.
    stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
        for item in items {
            match item {
                Item::Entry(e) => roots.extend([e.dm, e.situation, e.expectation, e.action]),
                Item::Nested(inner) => collect_history_roots(inner, roots),
            }
        }
    })
}

fn restore_history_roots(items: &mut [Item], it: &mut dyn Iterator<Item = Term>) {
    stacker::maybe_grow(64 * 1024, 1024 * 1024, || restore_history_level(items, it))
}

fn restore_history_level(items: &mut [Item], it: &mut dyn Iterator<Item = Term>) {
    for item in items {
        match item {
            Item::Entry(e) => {
                e.dm = it.next().expect("history root");
                e.situation = it.next().expect("history root");
                e.expectation = it.next().expect("history root");
                e.action = it.next().expect("history root");
            }
            Item::Nested(inner) => restore_history_roots(inner, it),
        }
    }
}
