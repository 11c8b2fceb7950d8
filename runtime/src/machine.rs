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
}

/// What the perceptual interpreter of a situation type perceived.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Perceived {
    Input(Term),
    /// No more input (end of a test script).
    EndOfInput,
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
}

/// Basic actions: executed after an arc's action is evaluated.
pub trait Actions {
    /// Performs one action (an element of an action list, or the action).
    fn perform(&mut self, store: &Store, action: Term) -> Result<(), String>;
}

/// Notified of every transition as it happens (for `--trace`).
pub trait Observer {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>);
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
}

impl Default for Options {
    fn default() -> Options {
        Options {
            keep_history: true,
            max_depth: 10_000_000,
            recovery: Vec::new(),
            gc_threshold: 1 << 20,
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
}

/// A recursive situation waiting for its embedded DM, or a failed
/// situation waiting for its recovery DM.
#[derive(Debug)]
enum Pending {
    Recursive { sit: SitIx, inst: Instance },
    Recovery { id: Term },
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

/// Where control goes next in the top frame.
enum Goto {
    Initial,
    Situation(Term),
}

/// The machine's state.
pub struct Machine<'p, P: DmProgram> {
    program: &'p P,
    pub store: Store,
    pub globals: Vars,
    pub functions: Functions,
    pub options: Options,
    frames: Vec<Frame>,
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
            scratch_locals: Vars::new(),
            scratch_globals: Vars::new(),
            arcs: Vec::new(),
            expectations: Vec::new(),
            transitions: 0,
            cells_after_gc: 0,
            arc_functor: Atom::intern("$arc"),
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
        let outcome = Outcome {
            result,
            history,
            out_arg: pipe,
            globals: self.globals,
            final_situation,
            transitions: self.transitions,
        };
        (outcome, self.store)
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
        loop {
            self.maybe_gc(pipe, &mut goto);
            let (sit, inst) = self.select(&goto)?;
            let here = Some((sit, inst.id));
            let dm = self.frames.last().expect("a frame is running").dm;
            // in_arg is a pattern unified with the incoming pipe (D-8, E14).
            if let Some(pattern) = inst.in_arg {
                if !self.store.unify(pattern, *pipe) {
                    return Err(self.err(
                        format!(
                            "in_arg `{}` does not match the incoming pipe value `{}`",
                            self.store.writeq(pattern),
                            self.store.writeq(*pipe)
                        ),
                        here,
                        None,
                    ));
                }
            }
            match self.program.kind(dm, sit) {
                Kind::Final => {
                    self.run_prog(&inst, inst.out_arg, here)?;
                    let out = match inst.out_arg {
                        Some(o) => self.eval_in_frame(o, here, None)?,
                        None => *pipe,
                    };
                    if !self.store.is_var(out) {
                        *pipe = out;
                    }
                    self.bind_diag_mod(&inst, here)?;
                    let empty = Term::atom(atoms::EMPTY);
                    self.record(inst.id, empty, empty, None, observer);
                    let frame = self.frames.pop().expect("a frame is running");
                    match self.frames.last_mut() {
                        None => {
                            *final_situation = Some(inst.id);
                            self.frames.push(frame); // keep for the history
                            return Ok(());
                        }
                        Some(caller) => {
                            if self.options.keep_history {
                                caller.history.push(Item::Nested(frame.history));
                            }
                            match caller.pending.take() {
                                Some(Pending::Recursive { sit, inst: rinst }) => {
                                    goto = Goto::Situation(self.finish_recursive(
                                        sit, rinst, inst.id, pipe, actions, observer,
                                    )?);
                                }
                                Some(Pending::Recovery { id }) => goto = Goto::Situation(id),
                                None => {
                                    unreachable!("a caller frame always has a pending situation")
                                }
                            }
                        }
                    }
                }
                Kind::Recursive => {
                    self.run_prog(&inst, None, here)?;
                    let Some(e) = inst.embedded_dm else {
                        return Err(self.err(
                            "recursive situation without `embedded_dm`",
                            here,
                            None,
                        ));
                    };
                    let call = self.eval_read_only(e, here)?;
                    self.frames.last_mut().expect("frame").pending =
                        Some(Pending::Recursive { sit, inst });
                    self.call_dm(call, here)?;
                    goto = Goto::Initial;
                }
                Kind::Perceptual => {
                    self.run_prog(&inst, inst.out_arg, here)?;
                    match self.choose_perceptual(sit, &inst, perception)? {
                        Some(chosen) => {
                            let next =
                                self.conclude(&inst, here, chosen, pipe, actions, observer)?;
                            goto = Goto::Situation(next);
                        }
                        None => {
                            // No expectation met (D-15 / D-42a): recovery DM, then a new instance.
                            let ty = self
                                .store
                                .atom_of(inst.type_term)
                                .or_else(|| self.store.functor(inst.type_term).map(|(n, _)| n));
                            let recovery = ty.and_then(|t| {
                                self.options
                                    .recovery
                                    .iter()
                                    .find(|(k, _)| *k == t)
                                    .map(|r| r.1)
                            });
                            match recovery {
                                Some(dm_name) => {
                                    self.frames.last_mut().expect("frame").pending =
                                        Some(Pending::Recovery { id: inst.id });
                                    self.call_dm(Term::atom(dm_name), here)?;
                                    goto = Goto::Initial;
                                }
                                None => goto = Goto::Situation(inst.id),
                            }
                        }
                    }
                }
            }
        }
    }

    /// Picks and instantiates the situation to run (D-7, D-21).
    fn select(&mut self, goto: &Goto) -> Result<(SitIx, Instance), RunError> {
        let frame = self.frames.last().expect("a frame is running");
        let (dm, dm_id) = (frame.dm, frame.dm_id);
        match *goto {
            Goto::Initial => {
                if self.program.situation_count(dm) == 0 {
                    return Err(self.err("the DM has no situations", None, None));
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
                Ok((0, inst))
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
                for sit in 0..self.program.situation_count(dm) as SitIx {
                    if !self.program.may_select(dm, sit, value, &self.store) {
                        continue;
                    }
                    let mark = self.store.mark();
                    let inst = self.program.instantiate(dm, sit, &mut self.store);
                    if self.store.unify(inst.id, value) {
                        self.link_head(inst.head, dm_id);
                        return Ok((sit, inst));
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

    /// `prog` on a renamed copy linked to in_arg/out_arg only (D-10).
    fn run_prog(
        &mut self,
        inst: &Instance,
        out_arg: Option<Term>,
        here: Option<(SitIx, Term)>,
    ) -> Result<(), RunError> {
        let Some(prog) = inst.prog else { return Ok(()) };
        let mut map = crate::copy::VarMap::new();
        for linked in [inst.in_arg, out_arg].into_iter().flatten() {
            for v in self.store.term_vars(linked) {
                if let crate::term::Value::Var(var) = self.store.value(v) {
                    map.insert(var, v);
                }
            }
        }
        let copy = self.store.copy_term_with(prog, &mut map);
        self.eval_in_frame(copy, here, None).map(|_| ())
    }

    fn eval_in_frame(
        &mut self,
        t: Term,
        here: Option<(SitIx, Term)>,
        arc: Option<usize>,
    ) -> Result<Term, RunError> {
        let frame = self.frames.last_mut().expect("a frame is running");
        let mut ctx = EvalCtx {
            store: &mut self.store,
            locals: &mut frame.locals,
            globals: &mut self.globals,
            history: &frame.history,
            functions: &self.functions,
        };
        match eval::eval(&mut ctx, t) {
            Ok(v) => Ok(v),
            Err(EvalError { message }) => Err(self.err(message, here, arc)),
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
        if self.arcs.is_empty() {
            return Err(self.err("the situation has no arcs", here, None));
        }
        let out_of =
            |this: &Self, i: usize| -> Option<Term> { inst.out_arg.map(|_| this.arcs[i][3]) };
        if self.store.atom_of(inst.type_term) == Some(atoms::NEUTRAL) {
            let e = self.store.deref(self.expectations[0]);
            if self.arcs.len() == 1
                && (self.store.atom_of(e) == Some(atoms::EMPTY) || self.store.is_var(e))
            {
                let _ = self.store.unify(e, Term::atom(atoms::EMPTY));
                return Ok(Some(Chosen {
                    arc: 0,
                    expectation: e,
                    action: self.arcs[0][1],
                    next: self.arcs[0][2],
                    out_arg: out_of(self, 0),
                }));
            }
            return Err(self.err(
                "a `neutral` situation needs exactly one arc, with expectation `empty`",
                here,
                None,
            ));
        }
        let second_read_allowed = self.arcs.len() == 1 || {
            let first = self.store.deref(self.expectations[0]);
            self.store.list_to_vec(first).is_some()
                && self.store.functor(first).is_some_and(|f| f.0 == atoms::DOT)
        };
        for attempt in 0..2 {
            let exps = std::mem::take(&mut self.expectations);
            let perceived = perception.perceive(&mut self.store, inst.type_term, &exps);
            self.expectations = exps;
            let input = match perceived {
                Ok(Perceived::Input(t)) => t,
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
            for i in (0..self.arcs.len()).rev() {
                let mark = self.store.mark();
                if self.store.unify(input, self.expectations[i]) {
                    return Ok(Some(Chosen {
                        arc: i,
                        expectation: self.expectations[i],
                        action: self.arcs[i][1],
                        next: self.arcs[i][2],
                        out_arg: out_of(self, i),
                    }));
                }
                self.store.undo_to(mark);
            }
            if attempt == 0 && !second_read_allowed {
                break;
            }
        }
        Ok(None)
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
        self.bind_diag_mod(inst, here)?;
        self.record(inst.id, chosen.expectation, action, Some(next), observer);
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
            self.store
                .list_iter(a)
                .try_for_each(|x| actions.perform(&self.store, x))
        } else {
            actions.perform(&self.store, a)
        };
        result.map_err(|e| self.err(format!("action failed: {e}"), here, arc))
    }

    /// Evaluates `diag_mod` (read-only variables) and unifies it with the DM id (D-20, E9).
    fn bind_diag_mod(
        &mut self,
        inst: &Instance,
        here: Option<(SitIx, Term)>,
    ) -> Result<(), RunError> {
        let Some(d) = inst.diag_mod else {
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
        // The first arc whose expectation unifies with the final situation wins.
        for i in 0..self.arcs.len() {
            let mark = self.store.mark();
            if self.store.unify(self.expectations[i], final_id) {
                let chosen = Chosen {
                    arc: i,
                    expectation: self.expectations[i],
                    action: self.arcs[i][1],
                    next: self.arcs[i][2],
                    out_arg: inst.out_arg.map(|_| self.arcs[i][3]),
                };
                return self.conclude(&inst, here, chosen, pipe, actions, observer);
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

    fn record(
        &mut self,
        situation: Term,
        expectation: Term,
        action: Term,
        next: Option<Term>,
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
            if let Some(Pending::Recursive { inst, .. }) = &f.pending {
                roots.extend(instance_terms(inst));
            }
            if let Some(Pending::Recovery { id }) = &f.pending {
                roots.push(*id);
            }
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
            if let Some(Pending::Recursive { inst, .. }) = &mut f.pending {
                set_instance_terms(inst, &mut it);
            }
            if let Some(Pending::Recovery { id }) = &mut f.pending {
                *id = it.next().expect("recovery root");
            }
        }
        self.cells_after_gc = self.store.stats().cells + self.store.stats().vars;
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
