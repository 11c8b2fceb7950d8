//! The contract between the machine and a program: what the program
//! implements ([`DmProgram`]), what its compiled code is handed ([`Cx`],
//! whose steps are in `cx`) and returns ([`Step`]), what it sees between
//! two transitions ([`Between`]), and the program's part in a run-time
//! error (where the situation is written).

use super::io::{Actions, Perception};
use super::observe::Observer;
use super::outcome::{ErrorSite, RunError};
use super::situation::{DmIx, Instance, Kind, SitIx};
use super::state::{Frame, Goto, Machine, Pending};
use crate::functions::Functions;
use crate::store::Store;
use crate::term::Term;
use crate::vars::Vars;
use sitlog_syntax::Atom;

/// What one visit of compiled code gives [`Cx::run_compiled`]'s loop.
#[derive(Debug)]
pub enum Visit {
    /// A step the loop may go on from by itself (to a compiled situation).
    Go(Step),
    /// A step for the machine as it is (native code left the DM, or handed
    /// the situation to its template).
    Stop(Step),
}

/// A program the machine can run.
pub trait DmProgram {
    /// The first DM in load order with this name (D-3: arity is not compared).
    fn dm_by_name(&self, name: Atom) -> Option<DmIx>;
    /// Why no DM named `name` is in the program when one was left out of
    /// this run for its errors (a DM that the run's main DM does not reach
    /// by name: issue 39): a call of it is a run-time error that says so.
    fn left_out(&self, _name: Atom) -> Option<String> {
        None
    }
    fn dm_name(&self, dm: DmIx) -> Atom;
    /// Whether the program runs a call of the runtime's own `when/3`
    /// (`functions::standard`) as the conditional it equals (its plans or
    /// native code: the compiler's `Planner::when_call`), which is right
    /// only while the run's registry holds that `when/3`: the machine
    /// refuses to start a run whose registry replaced it
    /// ([`Functions::is_standard`](crate::Functions::is_standard)), where
    /// the evaluator's path would call the replacement and the plans not.
    fn lowers_runtime_when(&self) -> bool {
        false
    }
    fn situation_count(&self, dm: DmIx) -> usize;
    fn kind(&self, dm: DmIx, sit: SitIx) -> Kind;
    /// A fresh copy of the DM's head (its identifier term).
    fn fresh_head(&self, dm: DmIx, store: &mut Store) -> Term;
    /// A fresh instance of a situation (D-7), head included; `None` for a
    /// situation that runs as code ([`DmProgram::compiled_id`] is `Some`)
    /// and never hands a visit to its template ([`Step::Template`]): the
    /// machine never instantiates it (generated code has no builder for it).
    fn instantiate(&self, dm: DmIx, sit: SitIx, store: &mut Store) -> Option<Instance>;
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
    /// Where a situation's in_arg is written (`file:line:col`), for the
    /// warning of an in_arg skipped; `None`: the situation's
    /// [`DmProgram::location`] stands for it.
    fn in_arg_location(&self, dm: DmIx, sit: SitIx) -> Option<String> {
        let _ = (dm, sit);
        None
    }
    /// `Some((name, arity))` when situation `sit` runs as code
    /// ([`DmProgram::run_situation`] and, for a recursive one,
    /// [`DmProgram::run_exit`]) instead of being instantiated; its id is
    /// then the atom `name` (arity 0) or a compound `name(...)`, which
    /// [`DmProgram::select_compiled`] matches against a value.
    fn compiled_id(&self, dm: DmIx, sit: SitIx) -> Option<(Atom, usize)> {
        let _ = (dm, sit);
        None
    }
    /// Whether compiled situation `sit`, whose id has the principal functor
    /// of `value`, is selected by `value`: its id unifies with `value` as an
    /// instance's would (bindings are kept when it is, undone otherwise).
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
    /// The situation entered (the code's `Cx` situation, id and selecting
    /// value) of the running DM (the top frame: native code may have made
    /// its callers' frames the machine's first) runs from its template, as
    /// the interpreter runs it: the code handed it over before doing
    /// anything (native code whose values do not convert, in a situation
    /// the program has no term code for; a recursive situation whose call
    /// native code does not push, [`Cx::to_template`]).
    Template,
}

/// What compiled typed code keeps while it runs typed situations one after
/// the other on native frames ([`Cx::typed_run`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct TypedRun {
    /// History entries are kept or observed: build and record them.
    pub records: bool,
    /// The history is kept and nothing observes the run: native code may
    /// call DMs on its own stack, their entries in levels of their own
    /// ([`Cx::open_level`]).
    pub nests: bool,
    /// [`Actions::ignores`](super::Actions::ignores) of [`ActionShape::Number`](super::ActionShape::Number).
    pub quiet_numbers: bool,
    /// [`Actions::ignores`](super::Actions::ignores) of [`ActionShape::EMPTY`](super::ActionShape::EMPTY).
    pub quiet_empty: bool,
    /// Transitions done without a history entry, not yet counted.
    pub count: u64,
    /// Set with a `GotoSit` step: that situation must run untyped.
    pub untyped: bool,
    /// Set with the `Step::Call` of a typed call: the callee, for the
    /// program's typed driver (the call term is the step's).
    pub call: Option<super::DmIx>,
}

/// Marks the path that calls it unlikely (its caller's branch laid out
/// away from the hot one).
#[cold]
#[inline(never)]
fn unlikely() {}

impl TypedRun {
    /// [`TypedRun::records`] where native code's hot path is the one that
    /// does not record (with `--history none`): the recorded branch is
    /// laid out as a cold one.
    #[inline(always)]
    pub fn recorded(&self) -> bool {
        if self.records {
            unlikely();
            true
        } else {
            false
        }
    }

    /// An arc's transition, one more for native code to count (`count`,
    /// given to the machine later) unless recorded: then entering the
    /// situation counted it.
    #[inline(always)]
    pub fn tally(&self, count: &mut u64) {
        if !self.records {
            *count += 1;
        }
    }

    /// [`Cx::record_next`] when recorded: an arc's history entry, its next
    /// situation's id built only then.
    #[inline(always)]
    pub fn record_next<P: DmProgram>(
        &self,
        cx: &mut Cx<'_, '_, P>,
        expectation: Term,
        action: Term,
        next: impl FnOnce(&mut Store) -> Term,
    ) {
        if self.records {
            cx.record_next(expectation, action, next);
        }
    }

    /// An arc's end: recorded, its history entry ([`Cx::record_next`], the
    /// next situation's id built only then), else one more transition for
    /// native code to count ([`TypedRun::tally`] and
    /// [`TypedRun::record_next`] in one test).
    #[inline(always)]
    pub fn end<P: DmProgram>(
        &self,
        cx: &mut Cx<'_, '_, P>,
        count: &mut u64,
        expectation: Term,
        action: Term,
        next: impl FnOnce(&mut Store) -> Term,
    ) {
        if self.records {
            cx.record_next(expectation, action, next);
        } else {
            *count += 1;
        }
    }

    /// [`TypedRun::end`] of an arc whose next situation is the variant
    /// `next`, given back (the visit's value: one call where the code
    /// would record `next`'s id, then name it).
    #[inline(always)]
    pub fn end_at<P: DmProgram, N: super::NatAt<P>>(
        &self,
        p: &P,
        cx: &mut Cx<'_, '_, P>,
        count: &mut u64,
        expectation: Term,
        action: Term,
        next: N,
    ) -> N {
        self.end(cx, count, expectation, action, |s| next.id_term(p, s));
        next
    }

    /// A final reached above the native stack's bottom, its level closed
    /// when recorded ([`Cx::close_level`] of its id `id` and outputs
    /// `outs`): the transitions for the driver to count, `count`, and its
    /// own when nothing is recorded (else its entry counted it).
    #[inline(always)]
    pub fn close_level<P: DmProgram>(
        &self,
        cx: &mut Cx<'_, '_, P>,
        count: u64,
        id: impl super::IdArg,
        outs: &[(usize, &dyn super::OutSlot)],
    ) -> Result<u64, RunError> {
        if self.recorded() {
            cx.close_level(id, outs)?;
            return Ok(count);
        }
        Ok(count + 1)
    }

    /// Counts the `count` transitions native code made but the arc's own
    /// (its last, not yet counted when nothing is recorded), and gives that
    /// one (0 or 1): it counts once the arc's next situation is computed,
    /// as on the term path, where an error evaluating it leaves it out.
    #[inline]
    pub fn count_but_this<P: DmProgram>(&self, cx: &mut Cx<'_, '_, P>, count: u64) -> u64 {
        let this = u64::from(!self.records).min(count);
        cx.count_transitions(count - this);
        this
    }

    /// The end of an arc that native code finished on terms (a value it
    /// could not convert): its transition `this` counted
    /// ([`TypedRun::count_but_this`]), its history entry made when recorded
    /// ([`Cx::record_if`]), then [`Cx::go`] (`next` its next situation and
    /// target).
    #[inline]
    pub fn go<P: DmProgram>(
        &self,
        cx: &mut Cx<'_, '_, P>,
        this: u64,
        expectation: Term,
        action: Term,
        (next, target): (Term, Option<SitIx>),
        arc: Option<usize>,
    ) -> Result<Option<Step>, RunError> {
        cx.count_transitions(this);
        cx.record_if(self.records, expectation, action, Some(next));
        cx.go(next, target, arc).map(Some)
    }

    /// [`TypedRun::go`] of an arc's next situation as written (`next`, a
    /// term of values), evaluated first as the machine evaluates it
    /// ([`Cx::eval`]; an error leaves the transition uncounted).
    #[cold]
    #[inline(never)]
    pub fn go_eval<P: DmProgram>(
        &self,
        cx: &mut Cx<'_, '_, P>,
        this: u64,
        expectation: Term,
        action: Term,
        next: Term,
        arc: Option<usize>,
    ) -> Result<Option<Step>, RunError> {
        let next = cx.eval(next, arc)?;
        self.go(cx, this, expectation, action, (next, None), arc)
    }

    /// An arc's next situation handed to the machine as a term: its history
    /// entry made when recorded ([`Cx::record_if`]), then [`Cx::goto`].
    #[inline]
    pub fn goto<P: DmProgram>(
        &self,
        cx: &mut Cx<'_, '_, P>,
        expectation: Term,
        action: Term,
        next: Term,
        arc: Option<usize>,
    ) -> Result<Option<Step>, RunError> {
        cx.record_if(self.records, expectation, action, Some(next));
        cx.goto(next, arc).map(Some)
    }
}

/// What compiled code of a situation sees of the machine: one method per
/// semantic step, each the one the interpreted path takes, so generated code
/// decides only *which* steps a situation needs, never how they behave.
///
/// Terms built through it live in the run's store; they stay valid until the
/// situation returns its [`Step`] (garbage is collected only between situations).
pub struct Cx<'a, 'p, P: DmProgram> {
    pub(super) m: &'a mut Machine<'p, P>,
    pub(super) pipe: &'a mut Term,
    pub(super) perception: &'a mut dyn Perception,
    pub(super) actions: &'a mut dyn Actions,
    pub(super) observer: Option<&'a mut dyn Observer>,
    pub(super) sit: SitIx,
    pub(super) id: Term,
    pub(super) selected: Option<Term>,
}

impl<P: DmProgram> Cx<'_, '_, P> {
    pub(super) fn here(&self) -> Option<(SitIx, Term)> {
        Some((self.sit, self.id))
    }

    /// A run-time error in this situation (`arc`: 0-based).
    pub fn error(&self, message: impl Into<String>, arc: Option<usize>) -> RunError {
        self.m.err(message, self.here(), arc)
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

impl<'p, P: DmProgram> Machine<'p, P> {
    pub(super) fn err(
        &self,
        message: impl Into<String>,
        sit: Option<(SitIx, Term)>,
        arc: Option<usize>,
    ) -> RunError {
        // The running DM: the innermost one typed code called, if any.
        let frame = match self.lazy.last() {
            Some(l) => Some((l.dm, l.call)),
            None => self.frames.last().map(|f| (f.dm, f.dm_id)),
        };
        RunError {
            message: message.into(),
            dm: frame.map(|(_, call)| self.store.writeq(call)),
            situation: sit.map(|(_, id)| self.store.writeq(id)),
            arc: arc.map(|a| a + 1),
            location: match (frame, sit) {
                (Some((dm, _)), Some((s, _))) => self.program.location(dm, s),
                _ => None,
            },
            site: match (frame, sit) {
                (Some((dm, _)), Some((s, _))) => Some(Box::new(ErrorSite {
                    dm,
                    situation: s,
                    culprit: None,
                    in_arg: false,
                })),
                _ => None,
            },
        }
    }

    /// Lets the program look at the machine between two transitions
    /// ([`DmProgram::between`]).
    #[inline]
    pub(super) fn between(&mut self, goto: &mut Goto) -> Result<(), RunError> {
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
}
