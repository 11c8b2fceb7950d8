//! The steps [`Cx`] offers the code of a compiled situation (generated
//! Rust, or an interpreter's plan): one method per semantic step, each
//! the one the interpreted path takes. Beside them, what native code
//! needs and the term path does not: terms built from native values
//! ([`fill`] of a pattern, [`build_of`], [`FromIdParts`] reading an id's
//! parts), the end of a native step ([`Cx::step_done`],
//! [`Cx::step_goto`], [`Cx::step_final`], [`Cx::to_template`]), the
//! history of a DM native code calls on its own stack ([`Cx::open_level`],
//! [`Cx::close_level`], [`Cx::wait_template`] where its caller's frame
//! becomes the machine's), its faults ([`Fault`]) and its check of whether
//! the machine wants control ([`Cx::gc_tick`]). None of them changes
//! what a run does (`gc_tick` only when the machine collects or stops:
//! at most `GC_TICKS - 1` situations later than `gc_due` would; at every
//! check below `GC_TICKS_BELOW`).

use super::holes::Holes;
use super::outcome::RunError;
use super::program::{Cx, DmProgram, Step, Visit};
use super::situation::{DmIx, SitIx};
use super::state::{HeldPipe, Machine};
use crate::eval;
use crate::native::{self, Native};
use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::Atom;

/// How often [`Cx::gc_tick`] asks [`Cx::gc_due`]: once every this many
/// checks.
pub const GC_TICKS: u32 = 16;

/// A [`super::Options::gc_threshold`] below this many cells (a run that
/// asks to collect often: the tests' tiny thresholds) makes
/// [`Cx::gc_tick`] ask [`Cx::gc_due`] at every check: garbage may then
/// come between any two visits, as tests of the hand-over want.
pub const GC_TICKS_BELOW: usize = 1 << 12;

impl<P: DmProgram> Cx<'_, '_, P> {
    /// A run-time error of `op(name, _)` (`get`, `set`, `inc`, ...) in this
    /// situation, blaming that construct as the machine's evaluator does.
    pub(super) fn var_op_error(
        &self,
        message: String,
        op: Atom,
        name: Atom,
        arc: Option<usize>,
    ) -> RunError {
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

    /// The run's store, read only (native code converting a term).
    #[inline]
    pub fn store_ref(&self) -> &Store {
        &self.m.store
    }

    /// Goes on to situation `sit` of the running DM with the id `id` (a
    /// term: native code handing a compound situation to the machine).
    #[inline]
    pub fn enter_with_id(&mut self, sit: SitIx, id: Term) {
        self.sit = sit;
        self.id = id;
        self.selected = None;
    }

    /// Native code entering situation `sit` to evaluate part of an arc
    /// (a condition, an out_arg) without building its id, which only an
    /// error of that evaluation reads (the evaluator does not see it):
    /// `[]` stands for it until [`Cx::with_id`] puts the id, built then,
    /// into the error. Recorded, native code enters with the id (the
    /// history reads it).
    #[inline]
    pub fn enter_unbuilt(&mut self, sit: SitIx) {
        self.enter_with_id(sit, Term::NIL);
    }

    /// Error `e` of an evaluation run after [`Cx::enter_unbuilt`],
    /// located at the situation's id `id`: what [`Cx::error`] would have
    /// given with the id entered.
    #[cold]
    pub fn with_id(&mut self, mut e: RunError, id: Term) -> RunError {
        let here = e.site.as_ref().map(|s| s.situation);
        if self.id == Term::NIL && e.situation.is_some() && here.is_none_or(|s| s == self.sit) {
            e.situation = Some(self.m.store.writeq(id));
        }
        self.id = id;
        e
    }

    /// Native code entering situation `sit` with its id `id` (built from
    /// its fields), after counting the `count` transitions it made since
    /// it last counted (then zero): the sequence an arc's native run ends
    /// with before the machine sees the situation, as one call.
    #[inline]
    pub fn enter_counted(&mut self, count: &mut u64, sit: SitIx, id: Term) {
        self.count_transitions(std::mem::take(count));
        self.enter_with_id(sit, id);
    }

    /// [`Cx::enter_counted`] of a perceptual situation whose choice native
    /// code keeps ([`Cx::choose_at`], [`Cx::choose_kept_at`]): the id `id` (a [`Fill`] of
    /// native values, which costs a list part's length) built now when the
    /// run records (the history reads it), else the situation entered
    /// unbuilt ([`Cx::enter_unbuilt`]) and the id built by the choice's
    /// cold path, the only other reader before the chosen arc's code
    /// (which the generator gives only steps that take the id's parts).
    #[inline]
    pub fn enter_perceiving(&mut self, count: &mut u64, sit: SitIx, id: impl IdArg) {
        self.count_transitions(std::mem::take(count));
        if self.records() {
            let id = id.id_in(&mut self.m.store);
            self.enter_with_id(sit, id);
        } else {
            self.enter_unbuilt(sit);
        }
    }

    /// [`Cx::enter_counted`] in a final the machine takes (the base's, or
    /// one with a `diag_mod`), then its out_arg the pipe unchanged
    /// ([`Cx::final_out_arg`] of `None`): the two calls of a final without
    /// an out_arg, as one.
    #[inline]
    pub fn enter_final(&mut self, count: &mut u64, sit: SitIx, id: Term) -> Result<(), RunError> {
        self.enter_counted(count, sit, id);
        self.final_out_arg(None)
    }

    /// [`Cx::enter_counted`] for an arc whose action is `empty`, then
    /// the action performed where `performs` (the run's actions do not
    /// ignore `empty`, or no native frame is above the machine's: native
    /// code handed over first).
    #[inline]
    pub fn enter_empty(
        &mut self,
        count: &mut u64,
        sit: SitIx,
        id: impl Into<Term>,
        performs: bool,
        arc: Option<usize>,
    ) -> Result<(), RunError> {
        self.enter_counted(count, sit, id.into());
        if performs {
            self.perform(Term::atom(sitlog_syntax::atoms::EMPTY), arc)?;
        }
        Ok(())
    }

    /// An arc's `empty` performed by native code before its situation is
    /// entered, where the run's actions do not ignore it (`run`'s
    /// `quiet_empty`): handed to the effector, which sees the atom and
    /// nothing else, as from the machine's `perform`, without the native
    /// frames below handed over nor the situation's id built. `true`:
    /// the effector failed; native code then hands over (the frames below
    /// and a DM's locals: what the machine's error sees) and enters the
    /// situation, whose entry ([`Cx::enter_performed`], [`Cx::nat_enter`])
    /// reports the error [`Cx::perform`] gives (kept for it until then).
    #[inline]
    pub fn empty_fails(&mut self, run: &super::TypedRun) -> bool {
        !run.quiet_empty && self.perform_empty()
    }

    /// [`Cx::empty_fails`] where `empty` is performed (the run's actions do
    /// not ignore it: every such arc, so not cold).
    #[inline(never)]
    fn perform_empty(&mut self) -> bool {
        self.m.empty_failed = self.perform_value(Term::EMPTY).err();
        self.m.empty_failed.is_some()
    }

    /// [`Cx::enter_counted`] for an arc whose action is `empty`, after
    /// [`Cx::empty_fails`]: the effector's error, if it failed, reported
    /// in the situation entered (what [`Cx::perform`] gives).
    #[inline]
    pub fn enter_performed(
        &mut self,
        count: &mut u64,
        sit: SitIx,
        id: impl Into<Term>,
        arc: Option<usize>,
    ) -> Result<(), RunError> {
        self.enter_counted(count, sit, id.into());
        match self.m.empty_failed.take() {
            Some(e) => Err(self.action_failed(e, arc)),
            None => Ok(()),
        }
    }

    /// The entry of situation `sit` by arc `arc`, whose action is
    /// `empty`, as one call, out of native code's hot path (its caller
    /// tests `run.records || !run.quiet_empty`, or `!run.quiet_empty` in
    /// an exit arc): `empty` handed to the effector where the actions do
    /// not ignore it ([`Cx::perform_value`]: the effector sees the atom
    /// and nothing else, as from the machine's `perform`), without
    /// handing the native frames below over; then [`Cx::nat_enter`]
    /// (`pattern` an [`IdArg`], so a [`Fill`] the generated code made
    /// beside, with no holes then).
    #[cold]
    #[inline(never)]
    pub fn nat_empty<F: super::NatFrames<P>>(
        &mut self,
        stack: &mut super::NatBelow<'_, F>,
        count: &mut u64,
        sit: SitIx,
        arc: usize,
        pattern: impl IdArg,
        holes: impl Holes,
    ) -> Result<(), RunError> {
        if !self.actions.ignores(super::ActionShape::EMPTY) {
            self.perform_empty();
        }
        self.nat_enter(stack, count, sit, arc, pattern, holes)
    }

    /// The entry of situation `sit` by arc `arc`, whose action `empty`
    /// was performed ([`Cx::nat_empty`], or [`Cx::empty_fails`] in a DM
    /// with locals, which hands over with its own where it fails), as one
    /// call: the situation's id filled (`pattern` and `holes`,
    /// [`Cx::fill`]) and entered where the run records (its entry reads
    /// it; else nothing reads it, and native code counts the transition
    /// as where `empty` is not performed). Where the effector failed, the
    /// native frames below are handed over first (the runtime's
    /// [`nat_hand_over`](super::nat_hand_over); none is below after a
    /// DM's own), the id filled after it (the store's order) and
    /// entered, and the error is [`Cx::perform`]'s.
    #[cold]
    #[inline(never)]
    pub fn nat_enter<F: super::NatFrames<P>>(
        &mut self,
        stack: &mut super::NatBelow<'_, F>,
        count: &mut u64,
        sit: SitIx,
        arc: usize,
        pattern: impl IdArg,
        holes: impl Holes,
    ) -> Result<(), RunError> {
        if let Some(e) = self.m.empty_failed.take() {
            let p = self.m.program;
            super::nat_hand_over(p, self, stack)?;
            let id = self.nat_id(pattern, holes);
            self.enter_counted(count, sit, id);
            return Err(self.action_failed(e, Some(arc)));
        }
        if self.records() {
            let id = self.nat_id(pattern, holes);
            self.enter_counted(count, sit, id);
        }
        Ok(())
    }

    /// A situation's id from its pattern and holes ([`Cx::fill`]), the
    /// pattern an [`IdArg`] (a [`Fill`] is filled first, its holes its own).
    #[inline]
    fn nat_id(&mut self, pattern: impl IdArg, holes: impl Holes) -> Term {
        let pattern = pattern.id_in(&mut self.m.store);
        holes.with_terms(&mut self.m.store, |store, ts| {
            if ts.is_empty() {
                pattern
            } else {
                fill_in(store, pattern, ts)
            }
        })
    }

    /// Whether the effector refused the `empty` of [`Cx::empty_fails`],
    /// whose error the entry that follows reports: native code hands over
    /// first.
    #[inline]
    pub fn empty_refused(&self) -> bool {
        self.m.empty_failed.is_some()
    }

    /// Native code handing a value to the machine: counts the `count`
    /// transitions it made, and enters situation `sit` by its name `name`
    /// unless `recorded` (then it was entered with its id).
    #[inline]
    pub fn count_and_enter(&mut self, count: u64, recorded: bool, sit: SitIx, name: Atom) {
        self.count_transitions(count);
        if !recorded {
            self.enter(sit, name);
        }
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

    /// [`Cx::gc_due`], asked once every `GC_TICKS` (16) calls: native code's
    /// check between two situations of its own loop (a decrement and a
    /// test, not the store's sizes and the stop flag each time). The
    /// collection or the stop comes at most `GC_TICKS - 1` situations
    /// later than with [`Cx::gc_due`]; what runs is the same. With a GC
    /// threshold below `GC_TICKS_BELOW` (4,096 cells) it asks every time.
    #[inline]
    pub fn gc_tick(&mut self) -> bool {
        if self.m.gc_ticks > 0 {
            self.m.gc_ticks -= 1;
            return false;
        }
        if self.m.options.gc_threshold >= GC_TICKS_BELOW {
            self.m.gc_ticks = GC_TICKS - 1;
        }
        self.gc_due()
    }

    /// Where an arc of compiled code goes: compiled situation `target` of
    /// the running DM when the code resolved it (a constant next
    /// situation), else the situation the evaluated `next` selects
    /// ([`Cx::goto`]; `arc`: 0-based, for errors).
    #[inline]
    pub fn go(
        &mut self,
        next: Term,
        target: Option<SitIx>,
        arc: Option<usize>,
    ) -> Result<Step, RunError> {
        match target {
            Some(ix) => Ok(Step::GotoSit(ix)),
            None => self.goto(next, arc),
        }
    }

    /// Runs compiled situation `sit` of the running DM (number `dm`) with
    /// `visit`, and the compiled situations it goes to (by index, or
    /// selected by the value of its next situation), until the machine is
    /// needed (another kind of step, a situation instantiated from its
    /// template, or garbage to collect) or `visit` stops ([`Visit::Stop`]).
    /// The loop of every DM's `run_situation` in generated code.
    pub fn run_compiled(
        &mut self,
        dm: DmIx,
        mut sit: SitIx,
        mut visit: impl FnMut(&mut Self, SitIx) -> Result<Visit, RunError>,
    ) -> Result<Step, RunError> {
        loop {
            let step = match visit(self, sit)? {
                Visit::Go(step) => step,
                Visit::Stop(step) => return Ok(step),
            };
            match step {
                Step::GotoSit(next) if !self.gc_due() => {
                    let Some((id, _)) = self.m.program.compiled_id(dm, next) else {
                        return Ok(step);
                    };
                    self.enter(next, id);
                    sit = next;
                }
                Step::Goto(value) if !self.gc_due() => {
                    let Some(next) = self.enter_selected(value) else {
                        return Ok(step);
                    };
                    sit = next;
                }
                _ => return Ok(step),
            }
        }
    }

    /// Goes on to compiled situation `sit` of the running DM, whose id is the atom `id`.
    #[inline]
    pub fn enter(&mut self, sit: SitIx, id: Atom) {
        self.sit = sit;
        self.id = Term::atom(id);
        self.selected = None;
    }

    /// Goes on to the situation of the running DM that the evaluated next
    /// situation `next` (a [`Step::Goto`]'s) selects, when it is compiled
    /// and selected as the machine would (D-21): its index, after which its
    /// code runs as if the machine had entered it. `None`, nothing done,
    /// when the machine must select (a situation instantiated from its
    /// template may take it, or none does). Code that goes on by itself
    /// asks [`Cx::gc_due`] first.
    #[inline]
    pub fn enter_selected(&mut self, next: Term) -> Option<SitIx> {
        self.m.materialize();
        let dm = self.m.frames.last().expect("a frame is running").dm;
        let next = self.m.store.deref(next);
        let (sit, id, selected) = self.m.select_compiled_first(dm, next)?;
        self.sit = sit;
        self.id = id;
        self.selected = selected;
        Some(sit)
    }

    /// What typed code keeps while it runs typed situations one after the
    /// other without the machine: the run's settings read once, the
    /// transitions it counted (given back with [`Cx::count_transitions`]).
    #[inline]
    pub fn typed_run(&self) -> super::TypedRun {
        super::TypedRun {
            records: self.records(),
            nests: self.m.options.keep_history && self.observer.is_none(),
            quiet_numbers: self.ignores_numbers(),
            quiet_empty: self.actions.ignores(super::ActionShape::EMPTY),
            count: 0,
            untyped: false,
            call: None,
        }
    }

    /// The situation running now (after [`Cx::return_typed`]: the caller's
    /// recursive situation).
    #[inline]
    pub fn situation(&self) -> SitIx {
        self.sit
    }

    /// Whether the run was asked to stop (a signal): code that goes on
    /// without the machine's loop checks it at each DM call.
    #[inline]
    pub fn stop_requested(&self) -> bool {
        self.m.stop_requested()
    }

    /// A DM call made by typed code, which goes on running the callee
    /// itself: what the machine does for [`Step::Call`] (the recursive
    /// situation `sit`/`id` waits with `saved`, the callee's frame is
    /// pushed, the depth limit checked), for `dm` called as `call`: its
    /// name, or a call whose head the machine would unify for sure (the
    /// caller's code knows: the DM's parameters are distinct variables and
    /// the arguments as many). The callee starts at its initial situation.
    pub fn call_typed(&mut self, dm: super::DmIx, call: Term, saved: Term) -> Result<(), RunError> {
        self.m.materialize();
        self.m.check_depth(self.here())?;
        self.m
            .frames
            .last_mut()
            .expect("a frame is running")
            .pending = Some(super::state::Pending::Compiled {
            sit: self.sit,
            saved,
            id: self.id,
        });
        self.m.push_frame(dm, call);
        self.sit = 0;
        self.selected = None;
        Ok(())
    }

    /// Native code handing the visit of situation `sit` of the running DM
    /// (its id `id`, built from native values) to the machine, nothing of
    /// it done: the machine runs it from its template, as the interpreter
    /// does (a recursive situation whose call is not pushed on the native
    /// stack: the machine makes the call, nests the callee's entries in the
    /// DM's history and runs the exit arcs).
    #[cold]
    #[inline(never)]
    pub fn to_template(&mut self, sit: SitIx, id: Term) -> Step {
        self.sit = sit;
        self.id = id;
        self.selected = Some(id);
        Step::Template
    }

    /// [`Cx::to_template`] after counting the `count` transitions native
    /// code made, as the visit's code returns it.
    /// The id is a term, or [`Fill`]: a pattern and its holes, filled
    /// first ([`Cx::fill`]), as a `let` before the call would fill it.
    #[cold]
    #[inline(never)]
    pub fn counted_template(
        &mut self,
        count: u64,
        sit: SitIx,
        id: impl IdArg,
    ) -> Result<Option<Step>, RunError> {
        let id = id.id_in(&mut self.m.store);
        self.count_transitions(count);
        Ok(Some(self.to_template(sit, id)))
    }

    /// A native frame waiting in recursive situation `sit` (id `id`) for
    /// its native callee, made the machine's: the situation's instance
    /// from its template as the interpreter holds it while the callee runs
    /// (its id `id`; its in_arg the pipe value the visit read, `in_arg`,
    /// when the exit arcs read it; its `embedded_dm`, evaluated read-only
    /// as at the call), the callee's frame pushed with that evaluation as
    /// its call term by the machine's own call (`Machine::callee`: the
    /// depth limit, the DM it names, its head unified with the call, E13;
    /// the call's variables, an output argument's, are
    /// the instance's, which the callee's `diag_mod` binds): the machine
    /// runs the exit arcs at the callee's final. (`prog` is not run again:
    /// native code ran it, and its variables are renamed apart from the
    /// exit arcs', D-10.) The callee's history level, when native code kept
    /// one, becomes its frame's history and its call term (built by native
    /// code at the push) the frame's, checked against the evaluation. The
    /// running situation is left as it was.
    pub fn wait_template(
        &mut self,
        sit: SitIx,
        id: Term,
        in_arg: Option<Term>,
    ) -> Result<(), RunError> {
        self.wait_held(sit, id, in_arg, None)
    }

    /// [`Cx::wait_template`] of a frame whose native call evaluated its
    /// `embedded_dm` (`held`, `Cx::nat_embedded_dm`): that call, not the
    /// template's evaluated again (a global the callee set since, a
    /// function's side effects twice), linked with the instance's
    /// variables (`Machine::held_or_eval`).
    pub fn wait_held(
        &mut self,
        sit: SitIx,
        id: Term,
        in_arg: Option<Term>,
        held: Option<Term>,
    ) -> Result<(), RunError> {
        self.m.materialize();
        // The running frame's situation, as native code entered it (its
        // history entry may come after the hand-over), given back below.
        let running = (self.sit, self.id, self.selected);
        self.enter_with_id(sit, id);
        let here = Some((sit, id));
        let dm = self.m.frames.last().expect("a frame is running").dm;
        let inst = self.m.template_instance(dm, sit, Some(id))?;
        if let (Some(pattern), Some(value)) = (inst.in_arg, in_arg) {
            self.m.unify_in_arg(pattern, value, here)?;
        }
        // The template's `embedded_dm` evaluated (read-only, as at the
        // call): native code pushes calls whose evaluation reads only
        // locals (`search(get(places, _), T)`) or gives the term itself;
        // or the call native code evaluated and held (`held`), taken as
        // it is (`machine::held_call`).
        let Some(e) = inst.embedded_dm else {
            return Err(self.fault(Fault::NotTheCall));
        };
        self.m.held_call = held;
        let e = self.m.held_or_eval(e, here)?;
        // The callee's history so far when native code kept it (its level,
        // the bottom one left: frames are made the machine's bottom first),
        // with the call term its entries name, which must be the call. The
        // level is taken only once the call is checked: on an error it is
        // still there for the unwinding to nest (`Machine::run`).
        let callee = match self.m.levels.front() {
            Some(level) => {
                let callee = level.dm_id;
                if !self.m.store.unify(e, callee) {
                    return Err(self.fault(Fault::NotTheCall));
                }
                callee
            }
            None => e,
        };
        // The DM it names, its head unified with the call, by the
        // machine's own call (one function: a head that does not unify is
        // the same error, E13, whoever made the call).
        let (callee_dm, callee) = self.m.callee(callee, here)?;
        let history = self
            .m
            .levels
            .pop_front()
            .map_or_else(Vec::new, |level| level.history);
        self.m
            .frames
            .last_mut()
            .expect("a frame is running")
            .pending = Some(super::state::Pending::Recursive { sit });
        self.m.instances.push(inst);
        self.m.push_frame_with(callee_dm, callee, history);
        (self.sit, self.id, self.selected) = running;
        Ok(())
    }

    /// A DM call native code pushes on its own stack while the history is
    /// kept ([`TypedRun::nests`](super::TypedRun::nests)): the callee's
    /// entries go to a level of their own (its call term `call`, the
    /// entries' `dm`) until its final closes it ([`Cx::close_level`]) or
    /// its frame becomes the machine's ([`Cx::wait_template`]).
    #[inline]
    pub fn open_level(&mut self, call: Term) {
        self.m.levels.push_back(super::state::Level {
            dm_id: call,
            history: Vec::new(),
        });
    }

    /// The callee's frame `callee` pushed by native code with the history
    /// kept: its level opened ([`Cx::open_level`], its call term the
    /// frame's), the frame put in `call` for the driver to push.
    #[inline]
    pub fn push_level<F: super::NatFrames<P>>(&mut self, p: &P, call: &mut Option<F>, callee: F) {
        let t = callee.call_term(p, self);
        self.open_level(t);
        *call = Some(callee);
    }

    /// The final situation `id` of the DM whose level is the innermost,
    /// reached on the native stack: its output arguments bound (each
    /// `(i, value)`: argument `i` of the call term, a variable the call
    /// made, takes `value`, as the machine's `diag_mod` binds it), its
    /// entry recorded, its history nested in its caller's (the level below,
    /// or the machine's top frame), as the machine's final pops a frame.
    ///
    /// `id` an [`IdArg`] (a [`Fill`] filled first), each output a slot
    /// of the native frame ([`OutSlot`]: `[]` where empty) made a term in
    /// order after it.
    pub fn close_level(
        &mut self,
        id: impl IdArg,
        outs: &[(usize, &dyn OutSlot)],
    ) -> Result<(), RunError> {
        let id = id.id_in(&mut self.m.store);
        let Some(dm_id) = self.m.levels.back().map(|l| l.dm_id) else {
            return Err(self.fault(Fault::NoLevel));
        };
        for &(i, slot) in outs {
            let value = slot.out_term(&mut self.m.store);
            let bound = self
                .m
                .store
                .arg(self.m.store.deref(dm_id), i)
                .is_some_and(|arg| self.m.store.unify(arg, value));
            if !bound {
                return Err(self.fault(Fault::NoLevel));
            }
        }
        let empty = Term::atom(sitlog_syntax::atoms::EMPTY);
        self.id = id;
        self.flush_pipe();
        self.m.record(id, empty, empty, None, *self.pipe, &mut None);
        let level = self.m.levels.pop_back().expect("a level");
        let nested = crate::history::Item::Nested(level.history);
        match self.m.levels.back_mut() {
            Some(below) => below.history.push(nested),
            None => self
                .m
                .frames
                .last_mut()
                .expect("a frame is running")
                .history
                .push(nested),
        }
        Ok(())
    }

    /// [`Cx::call_typed`] without pushing the callee's frame, for typed
    /// code that keeps no history: the frame is pushed, with every one
    /// below it, only when something reads the DM stack (any step of this
    /// `Cx` that does, an error, or [`Cx::materialize_frames`]), so a call
    /// that typed code runs to its end costs no frame. The depth limit is
    /// checked as by `call_typed`.
    pub fn call_typed_lazy(
        &mut self,
        dm: super::DmIx,
        call: Term,
        saved: Term,
    ) -> Result<(), RunError> {
        // Counts the lazy frames; its error names the running DM, pushed or not.
        self.m.check_depth(self.here())?;
        self.m.lazy.push(super::state::LazyFrame {
            dm,
            call,
            caller: super::state::Pending::Compiled {
                sit: self.sit,
                saved,
                id: self.id,
            },
        });
        self.sit = 0;
        self.selected = None;
        Ok(())
    }

    /// How many more DMs may be called before the depth limit
    /// ([`Options::max_depth`](super::Options::max_depth)): native code
    /// keeping callee frames of its own hands a call over to the machine
    /// (which reports the error) when its stack would reach it.
    #[inline]
    pub fn depth_room(&self) -> usize {
        self.m
            .options
            .max_depth
            .saturating_sub(self.m.frames.len() + self.m.lazy.len())
    }

    /// Pushes the frames of the DMs [`Cx::call_typed_lazy`] called: the DM
    /// stack as the machine would have it. Typed code calls it before it
    /// hands over.
    #[inline]
    pub fn materialize_frames(&mut self) {
        self.m.materialize();
    }

    /// The end of a DM entered by [`Cx::call_typed`] or
    /// [`Cx::call_typed_lazy`], after its final
    /// situation: what the machine does for [`Step::Final`] (the frame
    /// popped, its history nested in the caller's), the caller's waiting
    /// situation becoming the running one. Returns the final situation's id.
    pub fn return_typed(&mut self) -> Term {
        let final_id = self.id;
        if let Some(l) = self.m.lazy.pop() {
            // A frame never pushed: nothing to pop, no history to nest.
            let super::state::Pending::Compiled { sit, id, .. } = l.caller else {
                unreachable!("a typed call left its caller waiting")
            };
            self.sit = sit;
            self.id = id;
            self.selected = Some(id);
            return final_id;
        }
        match self.m.pop_frame() {
            Some(Some(super::state::Pending::Compiled { sit, id, .. })) => {
                self.sit = sit;
                self.id = id;
                self.selected = Some(id);
            }
            _ => unreachable!("a typed call left its caller waiting"),
        }
        final_id
    }

    /// The error of native code finding its own frames not as it made
    /// them (a compiler bug, reported as a run-time error naming it).
    #[cold]
    pub fn fault(&self, fault: Fault) -> RunError {
        let message = match fault {
            Fault::NotWaiting => "native code resumed a situation that waits for no DM",
            Fault::WrongFrame => "native code resumed a caller with another DM's frame",
            Fault::WaitsForNone => "native code handed over a frame that waits for no DM",
            Fault::Visited => "native code visited a waiting situation or a running frame",
            Fault::Exits => "native exit arcs disagree with the machine's",
            Fault::NoLevel => "native code closed a history level it did not open",
            Fault::HeadPart => "native code read a part its DM's head pattern does not have",
            Fault::NotTheCall => {
                "native code called a DM its situation's embedded_dm does not call"
            }
        };
        self.error(message, None)
    }

    /// The end of a native step without the machine (a call made, a final
    /// reached below the base): its transitions counted, the frame's
    /// situation put back in its `slot`.
    #[inline(always)]
    pub fn step_done<T>(
        &mut self,
        count: u64,
        slot: &mut T,
        at: T,
    ) -> Result<Option<Step>, RunError> {
        self.count_transitions(count);
        *slot = at;
        Ok(None)
    }

    /// The end of a native step in a final situation (the machine entered
    /// in it, its out_arg and `diag_mod` taken): its history entry, as the
    /// term path records a final's, and the step.
    #[inline]
    pub fn step_final(&mut self) -> Result<Option<Step>, RunError> {
        let empty = Term::atom(crate::atoms::EMPTY);
        self.record(empty, empty, None);
        Ok(Some(Step::Final))
    }

    /// The end of a native step that gives the machine control (garbage to
    /// collect, a stop asked): its transitions counted, the situation
    /// reached handed over as its id.
    #[cold]
    pub fn step_goto(
        &mut self,
        count: u64,
        id: impl FnOnce(&mut Store) -> Term,
    ) -> Result<Option<Step>, RunError> {
        self.count_transitions(count);
        let id = id(&mut self.m.store);
        Ok(Some(Step::Goto(id)))
    }

    /// A fresh variable.
    #[inline]
    pub fn var(&mut self) -> Term {
        self.m.store.new_var()
    }

    /// `N` fresh variables, made in order (a visit's fresh variables).
    #[inline]
    pub fn vars<const N: usize>(&mut self) -> [Term; N] {
        std::array::from_fn(|_| self.m.store.new_var())
    }

    #[inline]
    pub fn compound(&mut self, name: Atom, args: &[Term]) -> Term {
        self.m.store.compound(name, args)
    }

    /// A native value as a term ([`Native::to_term`] in the store).
    #[inline]
    pub fn term<T: Native>(&mut self, v: &T) -> Term {
        v.to_term(&mut self.m.store)
    }

    /// A term built by native code ([`native::compound`]: an atom for no
    /// arguments, a list cell for `'.'/2`).
    #[inline]
    pub fn build(&mut self, name: Atom, args: &[Term]) -> Term {
        native::compound(&mut self.m.store, name, args)
    }

    /// [`Cx::build`] of values, each made a term in order
    /// ([`Native::to_term`]): a next situation or call term native code
    /// hands to the machine.
    pub fn build_of(&mut self, name: Atom, args: &[&dyn AsTerm]) -> Term {
        build_of(&mut self.m.store, name, args)
    }

    /// The term `pattern` (a constant of the program, [`hole_atom`]`(i)`
    /// where a value goes) with `holes[i]` made a term in its place, the
    /// holes in order: a term native code builds from native values in one
    /// call. Each compound with a hole below it is built as [`Cx::build`]
    /// builds it; a part without one is the constant's.
    pub fn fill(&mut self, pattern: Term, holes: &[&dyn AsTerm]) -> Term {
        fill(&mut self.m.store, pattern, holes)
    }

    /// [`Cx::compound`] of values, each made a term in order: the
    /// registers a [`Step::Call`](super::Step::Call) keeps (`saved`).
    pub fn compound_of(&mut self, name: Atom, args: &[&dyn AsTerm]) -> Term {
        with_terms(&mut self.m.store, args, |store, ts| {
            store.compound(name, ts)
        })
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
        self.m.materialize();
        let dm_id = self.m.frames.last().expect("a frame is running").dm_id;
        match self.m.store.arg(dm_id, i) {
            Some(a) => a,
            None => self.m.store.new_var(),
        }
    }

    /// The part at `path` (argument positions) of argument `i` of the
    /// running DM's call: the value a variable of a head argument written
    /// as a pattern takes (`K` in `key_of(K-_Qty)`; D-7: the call unified
    /// with the head where the DM started, so the part is there); a fresh
    /// variable where the call has no such part.
    pub fn head_part(&mut self, i: usize, path: &[usize]) -> Term {
        let mut t = self.head_arg(i);
        for &k in path {
            match self.m.store.arg(t, k) {
                Some(a) => t = a,
                None => return self.m.store.new_var(),
            }
        }
        t
    }

    /// Links `x`, the selected id's value of a variable that is also head
    /// parameter `i`, to the running DM's call: unified with argument `i`,
    /// undone where they do not unify (D-7: a later situation's fresh head
    /// is linked argument by argument, where possible).
    pub fn link_head_arg(&mut self, x: Term, i: usize) {
        self.m.materialize();
        let dm_id = self.m.frames.last().expect("a frame is running").dm_id;
        if let Some(a) = self.m.store.arg(dm_id, i) {
            let mark = self.m.store.mark();
            if !self.m.store.unify(x, a) {
                self.m.store.undo_to(mark);
            }
        }
    }

    /// The incoming pipe value (made a term first if native code holds
    /// it, [`Cx::flush_pipe`]).
    #[inline]
    pub fn pipe(&mut self) -> Term {
        self.flush_pipe();
        *self.pipe
    }

    /// [`Cx::pipe`] dereferenced: what native code's in_arg reads.
    #[inline]
    pub fn pipe_in(&mut self) -> Term {
        let t = self.pipe();
        self.m.store.deref(t)
    }

    /// The pipe held as native values made a term, if native code holds
    /// it ([`HeldPipe`]): before anything reads the pipe's term (the
    /// machine when compiled code returns, on an error too).
    #[inline]
    pub fn flush_pipe(&mut self) {
        // Any header cell is the mark (no handle given out is one).
        if let crate::term::Repr::Functor(..) = self.pipe.0 {
            self.unhold_pipe();
        }
    }

    #[cold]
    #[inline(never)]
    fn unhold_pipe(&mut self) {
        debug_assert!(*self.pipe == HeldPipe::MARK, "a header cell as the pipe");
        // What `build_of` of the values makes (an argument's term built
        // before the compound, in order), without allocating.
        let Machine { held: h, store, .. } = &mut *self.m;
        if h.n == 0 {
            // A value held whole: its term, the value let go.
            let v = std::mem::replace(&mut h.args[0], native::Val::Int(0));
            *self.pipe = v.to_term(store);
            return;
        }
        let mut ts = [Term::NIL; super::HELD_MAX];
        for (t, v) in ts.iter_mut().zip(&h.args[..h.n]) {
            *t = v.to_term(store);
        }
        *self.pipe = native::compound(store, h.name, &ts[..h.n]);
    }

    /// Sets the pipe to `name(args..)` (an arc's out_arg of native values,
    /// at most [`HELD_MAX`](super::HELD_MAX) arguments, each canonical),
    /// held as those values ([`HeldPipe`]): the term `build_of` would make,
    /// made only where something reads it as a term.
    #[inline]
    pub fn hold_pipe<const N: usize>(&mut self, name: Atom, args: [native::Val; N]) {
        const { assert!(0 < N && N <= super::HELD_MAX) };
        self.m.held.name = name;
        self.m.held.n = N;
        for (slot, v) in self.m.held.args.iter_mut().zip(args) {
            *slot = v;
        }
        *self.pipe = HeldPipe::MARK;
    }

    /// Sets the pipe to the value `v` (an arc's out_arg `Acc` of a
    /// canonical value that is not atomic: a list, a compound), held as
    /// it is ([`HeldPipe`] with no name): its term, which [`Cx::term`] of
    /// the value would make at once (a walk's whole accumulated list, at
    /// each call), made only where something reads the pipe as a term.
    #[inline]
    pub fn hold_pipe_value(&mut self, v: native::Val) {
        // An atomic value is its term at once (a `ground` value may be).
        let t = match v {
            native::Val::Int(i) => Term::int(i),
            native::Val::Float(f) => Term::float(f),
            native::Val::Sym(a) => Term::atom(a),
            v => {
                self.m.held.n = 0;
                self.m.held.args[0] = v;
                HeldPipe::MARK
            }
        };
        *self.pipe = t;
    }

    /// The pipe's `N` arguments when native code holds it as
    /// `name(args..)` of `N` arguments ([`Cx::hold_pipe`]), else `None`
    /// (the pipe's term then reads it: [`Cx::pipe_in`]).
    #[inline]
    pub fn held_pipe<const N: usize>(&self, name: Atom) -> Option<&[native::Val; N]> {
        if matches!(self.pipe.0, crate::term::Repr::Functor(..))
            && self.m.held.n == N
            && self.m.held.name == name
        {
            self.m.held.args.first_chunk::<N>()
        } else {
            None
        }
    }

    /// Unifies the situation's in_arg pattern with the incoming pipe (D-8, E14).
    pub fn in_arg(&mut self, pattern: Term) -> Result<(), RunError> {
        self.m.materialize();
        self.flush_pipe();
        let here = self.here();
        self.m.unify_in_arg(pattern, *self.pipe, here)
    }

    /// Runs `prog` on a copy sharing only the variables of `links` (D-10).
    pub fn prog(&mut self, prog: Term, links: &[Option<Term>]) -> Result<(), RunError> {
        self.m.materialize();
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
        self.m.materialize();
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
        self.m.materialize();
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
        self.m.materialize();
        let r = eval::var_op_fresh(&mut self.m.eval_ctx(), op, name);
        r.map_err(|e| self.var_op_error(e.message, op, name, arc))
    }

    /// `get(name, V)` of a global by native code, the machine not entered:
    /// its value as a `T`, read now (never a copy kept). `None` when there
    /// is no global `name` or its value is not a `T`: nothing is changed,
    /// and native code enters the machine for [`Cx::var_op_fresh`], which
    /// gives the value or reports the error. Only for a name that is no
    /// local of the DM whose code runs (the compiler knows that statically;
    /// the machine's `var_op` looks at the running frame's locals first,
    /// and the machine's running frame may not be that DM's while native
    /// frames run).
    #[inline]
    pub fn global_as<T: Native>(&self, name: Atom) -> Option<T> {
        let t = self.m.globals.get(name)?;
        T::from_term(&self.m.store, self.m.store.deref(t))
    }

    /// `inc(name, V)` of a global by native code, as [`Cx::global_as`]:
    /// the new value as a `T`, set. `None` (nothing changed) when there is
    /// no global `name`, its value is not a number, the int overflows or
    /// the new value is not a `T`: the machine's [`Cx::var_op_fresh`] then
    /// does it or reports its error.
    #[inline]
    pub fn global_inc<T: Native>(&mut self, name: Atom) -> Option<T> {
        let m = &mut *self.m;
        let slot = m.globals.slot(name)?;
        let cur = m.store.deref(*slot);
        let next = if let Some(i) = m.store.int_of(cur) {
            Term::int(i.checked_add(1)?)
        } else {
            Term::float(m.store.float_of(cur)? + 1.0)
        };
        let v = T::from_term(&m.store, next)?;
        *slot = next;
        Some(v)
    }

    /// `set(name, value)` of a global by native code, `value` the term
    /// of a native value (as written: a value evaluates to itself), as
    /// [`Cx::global_as`]: `false` (nothing changed) when there is no
    /// global `name` (the machine's [`Cx::var_op`] then reports it).
    #[inline]
    pub fn global_set(&mut self, name: Atom, value: Term) -> bool {
        let value = self.m.store.deref(value);
        self.m.globals.set(name, value)
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
        eval::is(&mut self.m.store, v, expr, None).map_err(|e| self.is_error(e, v, arc))
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
        eval::arith_condition(&mut self.m.store, op, a, b).map_err(|e| self.condition_error(e, arc))
    }

    /// Whether the value of `A op B` (an arithmetic comparison) is `true`,
    /// `lw`/`rw` its operands as written, `l`/`r` their values: the
    /// evaluator's error (`eval::compare_value`), blaming `op/2` as it does.
    pub fn compare_value(
        &mut self,
        op: crate::arith::ArithCmp,
        written: [Term; 2],
        values: [Term; 2],
        arc: Option<usize>,
    ) -> Result<bool, RunError> {
        eval::compare_value(&mut self.m.store, op, written, values).map_err(|e| {
            let mut err = self.error(e.message, arc);
            if let Some(site) = err.site.as_mut() {
                site.culprit = e.culprit;
            }
            err
        })
    }

    /// [`Cx::compare_value`] for a comparison that is an operand of a
    /// conditional's `(A, B)` or `(A ; B)` (D-35: the condition's
    /// arguments are evaluated as values, then it is called): the same
    /// value, its error as [`Cx::condition`] gives it (blaming `op/2`).
    pub fn compare_condition(
        &mut self,
        op: crate::arith::ArithCmp,
        written: [Term; 2],
        values: [Term; 2],
        arc: Option<usize>,
    ) -> Result<bool, RunError> {
        eval::compare_value(&mut self.m.store, op, written, values)
            .map_err(|e| self.condition_error(e, arc))
    }

    /// Whether the value of `t`, an operand of a conditional's `(A, B)` or
    /// `(A ; B)` whose value is `true` or `false` (`A == B`, `member(X,
    /// L)`, D-33, D-34), is `true`: what the condition computes of it
    /// before calling it (D-35), its error as [`Cx::condition`] gives it.
    pub fn value_holds(&mut self, t: Term, arc: Option<usize>) -> Result<bool, RunError> {
        self.m.materialize();
        let r = eval::eval(&mut self.m.eval_ctx(), t);
        match r {
            Ok(v) => Ok(self.m.store.atom_of(v) == Some(sitlog_syntax::atoms::TRUE)),
            Err(e) => Err(self.condition_error(e, arc)),
        }
    }

    /// Any other condition of a conditional (D-35).
    pub fn condition(&mut self, cond: Term, arc: Option<usize>) -> Result<bool, RunError> {
        self.m.materialize();
        let r = eval::condition(&mut self.m.eval_ctx(), cond);
        r.map_err(|e| self.condition_error(e, arc))
    }

    /// Keeps the variables' values, to be put back by [`Cx::restore_vars`]:
    /// updates made while expectations are evaluated are discarded (D-12).
    pub fn save_vars(&mut self) {
        self.m.materialize();
        let frame = self.m.frames.last().expect("a frame is running");
        self.m.scratch_locals.restore_from(&frame.locals);
        self.m.scratch_globals.restore_from(&self.m.globals);
    }

    pub fn restore_vars(&mut self) {
        self.m.materialize();
        let frame = self.m.frames.last_mut().expect("a frame is running");
        frame.locals.restore_from(&self.m.scratch_locals);
        self.m.globals.restore_from(&self.m.scratch_globals);
    }

    /// The evaluated expectations of the situation's arcs, in arc order.
    pub fn set_expectations(&mut self, expectations: &[Term]) {
        self.m.expectations.clear();
        self.m.expectations.extend_from_slice(expectations);
        if self.m.options.close_list_tails {
            self.close_expectations();
        }
    }

    /// `--legacy` ([`Options::close_list_tails`](super::Options::close_list_tails)):
    /// the expectations' list tails closed, as the original's evaluator
    /// closes them (`[First|Rest]` expects `[First]`), as the machine's
    /// own evaluation of them does. Cold: off outside `--legacy`.
    #[cold]
    #[inline(never)]
    fn close_expectations(&mut self) {
        for &e in &self.m.expectations {
            super::run::close_list_tails(&mut self.m.store, e);
        }
    }

    /// The met expectation of arc `i`, after [`Cx::choose`] or [`Cx::choose_exit`].
    #[inline]
    pub fn expectation(&self, i: usize) -> Term {
        self.m.expectations[i]
    }

    /// Which arc's expectation is met (the neutral rule, else perception, D-14).
    pub fn choose(&mut self, type_term: Term) -> Result<Option<usize>, RunError> {
        self.m.materialize();
        let here = self.here();
        self.m
            .choose_index(type_term, here, &mut *self.perception, None)
    }

    /// [`Cx::choose`] after [`Cx::set_expectations`], for native code that
    /// keeps its frames below (module `perceive` of the code generator;
    /// `machine::nat_choose` for a DM without locals):
    /// the perception read and matched without the machine's frames
    /// (`Machine::perceive_kept`); only where the machine's frames are read
    /// (the running DM's call for a prompt, an input that meets no
    /// expectation, an error, `neutral`) `hand` makes the native frames
    /// the machine's first (`nat_hand_over`), and the machine goes on from
    /// what was read, as [`Cx::choose`] would.
    #[inline]
    pub fn choose_kept(
        &mut self,
        type_term: Term,
        hand: impl FnOnce(&mut Self) -> Result<(), RunError>,
    ) -> Result<Option<usize>, RunError> {
        match self.m.perceive_kept(type_term, &mut *self.perception) {
            Ok(i) => Ok(Some(i)),
            Err(first) => self.choose_cold(type_term, first, hand),
        }
    }

    /// [`Cx::choose_kept`] after [`Cx::enter_perceiving`]: on the cold
    /// path the situation's id `id` is built first if it was not (the
    /// machine's choice, a prompt, an error and `Step::Unmet` read it).
    #[inline]
    pub fn choose_kept_at(
        &mut self,
        type_term: Term,
        id: impl IdArg,
        hand: impl FnOnce(&mut Self) -> Result<(), RunError>,
    ) -> Result<Option<usize>, RunError> {
        match self.m.perceive_kept(type_term, &mut *self.perception) {
            Ok(i) => Ok(Some(i)),
            Err(first) => {
                if self.id == Term::NIL {
                    self.id = id.id_in(&mut self.m.store);
                }
                self.choose_cold(type_term, first, hand)
            }
        }
    }

    /// [`Cx::choose_kept_at`] in a DM without locals, the frames below
    /// handed over by the runtime's [`nat_hand_over`](super::nat_hand_over)
    /// on the cold path (`machine::nat_choose`'s, with the id).
    #[inline]
    pub fn choose_at<F: super::NatFrames<P>>(
        &mut self,
        stack: &mut super::NatBelow<'_, F>,
        type_term: Term,
        id: impl IdArg,
    ) -> Result<Option<usize>, RunError> {
        let p = self.m.program;
        self.choose_kept_at(type_term, id, |cx| super::nat_hand_over(p, cx, stack))
    }

    /// [`Cx::choose_kept`]'s cold path: the frames handed over, then the
    /// machine's choice going on from `first`.
    #[cold]
    #[inline(never)]
    fn choose_cold(
        &mut self,
        type_term: Term,
        first: Option<Result<super::Perceived, String>>,
        hand: impl FnOnce(&mut Self) -> Result<(), RunError>,
    ) -> Result<Option<usize>, RunError> {
        hand(self)?;
        self.m.materialize();
        let here = self.here();
        self.m
            .choose_index(type_term, here, &mut *self.perception, first)
    }

    /// Which exit arc takes the embedded DM's final situation `final_id` (D-22).
    pub fn choose_exit(&mut self, final_id: Term) -> Result<usize, RunError> {
        self.m.materialize();
        let here = self.here();
        self.m.choose_exit_index(final_id, here)
    }

    /// No exit arc of native code's waiting situation `sit` (id `id`) takes
    /// the embedded DM's final situation (`final_id` builds its id): the
    /// error the machine gives for it ([`Cx::choose_exit`]), the `count`
    /// transitions native code made counted first (always `Err`). One cold
    /// call for the tail every native exit `match` ends with.
    #[cold]
    #[inline(never)]
    pub fn no_exit<T>(
        &mut self,
        count: u64,
        sit: SitIx,
        id: impl Into<Term>,
        final_id: impl FnOnce(&mut Store) -> Term,
    ) -> Result<T, RunError> {
        self.count_transitions(count);
        self.enter_with_id(sit, id.into());
        let final_id = final_id(self.store());
        self.set_expectations(&[]);
        Err(match self.choose_exit(final_id) {
            Err(e) => e,
            Ok(_) => self.fault(Fault::Exits),
        })
    }

    /// The output `out` a native callee's frame hands back to its caller's
    /// exit arcs (taken from the frame), or the error when the callee
    /// returned without it.
    #[inline(always)]
    pub fn callee_out<T>(&self, out: Option<T>) -> Result<T, RunError> {
        match out {
            Some(v) => Ok(v),
            None => Err(self.no_callee_out()),
        }
    }

    #[cold]
    #[inline(never)]
    fn no_callee_out(&self) -> RunError {
        self.error("a native callee returned without its output", None)
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
            if let Err(e) = super::io::perform_one(&mut *self.actions, &mut self.m.store, x) {
                return Err(self.error(format!("action failed: {e}"), arc));
            }
        }
        Ok(())
    }

    /// [`Cx::perform_each`], then the action as the history records it
    /// where `records` (the list of the elements, built only then), else
    /// `[]`: a list action of native code as one call.
    #[inline]
    pub fn perform_list(
        &mut self,
        elements: &[Term],
        records: bool,
        arc: Option<usize>,
    ) -> Result<Term, RunError> {
        self.perform_each(elements, arc)?;
        Ok(if records {
            self.m.store.list(elements)
        } else {
            Term::NIL
        })
    }

    /// Performs `action`, a value native code computed that is neither a
    /// list nor `empty` (a number, another atom), as [`Cx::perform`] does,
    /// without entering the machine: the effector is handed the value and
    /// nothing else, so native code need not build the situation's id nor
    /// hand its frames over. `Err`: the effector's message; native code
    /// then enters the situation and reports it ([`Cx::action_failed`]),
    /// the error [`Cx::perform`] would have given.
    #[inline]
    pub fn perform_value(&mut self, action: Term) -> Result<(), String> {
        super::io::perform_one(&mut *self.actions, &mut self.m.store, action)
    }

    /// The error of an action [`Cx::perform_value`] did not perform, once
    /// native code has entered its situation: what [`Cx::perform`] gives.
    #[cold]
    pub fn action_failed(&mut self, e: String, arc: Option<usize>) -> RunError {
        self.error(format!("action failed: {e}"), arc)
    }

    /// Whether history entries are observed (kept, or seen by an observer):
    /// when not, an entry's terms need not be built.
    #[inline]
    pub fn records(&self) -> bool {
        self.m.options.keep_history || self.observer.is_some()
    }

    /// Sets the pipe to a value typed code computed (an arc's out_arg, D-18).
    #[inline]
    pub fn set_pipe(&mut self, value: Term) {
        *self.pipe = value;
    }

    /// An arc's out_arg that hands back the in_arg's value read in the same
    /// visit (`in_arg ==> X, out_arg ==> X`, the pipe not set in between):
    /// the pipe set to its own term dereferenced, what [`Cx::set_pipe`] of
    /// the term read writes, without native code keeping that term across
    /// the visit.
    #[inline]
    pub fn pipe_deref(&mut self) {
        // Held as native values: a compound, nothing to dereference.
        let t = *self.pipe;
        if let crate::term::Repr::Var(_) = t.0 {
            *self.pipe = self.m.store.deref(t);
        }
    }

    /// An arc's out_arg already evaluated (the plans and the generated code
    /// evaluate it as they evaluate a next situation, after it): the value
    /// becomes the pipe unless it is a variable (D-18).
    #[inline]
    pub fn out_value(&mut self, value: Term) {
        if !self.m.store.is_var(value) {
            *self.pipe = value;
        }
    }

    /// A final situation's out_arg (or the pipe unchanged when `None`).
    pub fn final_out_arg(&mut self, out: Option<Term>) -> Result<(), RunError> {
        self.m.materialize();
        self.flush_pipe();
        let here = self.here();
        self.m.final_out_arg(out, self.pipe, here)
    }

    /// Evaluates `diag_mod` with read-only variables and unifies it with the DM's id (D-20).
    pub fn diag_mod(&mut self, d: Term) -> Result<(), RunError> {
        self.m.materialize();
        let here = self.here();
        self.m.bind_diag_mod(Some(d), here)
    }

    /// Evaluates `embedded_dm` with read-only variables: the DM call.
    pub fn embedded_dm(&mut self, e: Term) -> Result<Term, RunError> {
        self.m.materialize();
        let here = self.here();
        self.m.eval_read_only(e, here)
    }

    /// The value of the running DM's local variable `name` (dereferenced).
    pub fn local(&self, name: Atom) -> Option<Term> {
        debug_assert!(self.m.lazy.is_empty(), "locals read under a lazy frame");
        let frame = self.m.frames.last().expect("a frame is running");
        frame.locals.get(name).map(|t| self.m.store.deref(t))
    }

    /// Sets the running DM's local variable `name` (typed code writing its
    /// frame back).
    pub fn set_local(&mut self, name: Atom, value: Term) {
        self.m.materialize();
        let frame = self.m.frames.last_mut().expect("a frame is running");
        frame.locals.set(name, value);
    }

    /// Argument `i` of the running DM's call, dereferenced, if it has one.
    pub fn param(&self, i: usize) -> Option<Term> {
        debug_assert!(self.m.lazy.is_empty(), "parameters read under a lazy frame");
        let dm_id = self.m.frames.last().expect("a frame is running").dm_id;
        self.m.store.arg(dm_id, i).map(|t| self.m.store.deref(t))
    }

    /// The native value of type `T` term `t` is (`None`: it has not that
    /// type).
    pub fn to_native<T: Native>(&self, t: Term) -> Option<T> {
        T::from_term(&self.m.store, t)
    }

    /// Whether `t` converts to a `T` ([`Native::converts`]), no value kept.
    #[inline]
    pub fn converts_to<T: Native>(&self, t: Term) -> bool {
        T::converts(&self.m.store, t)
    }

    /// [`Cx::param`] as a native value (`None`: none, or it does not
    /// convert), for native code entering a DM.
    pub fn param_as<T: Native>(&self, i: usize) -> Option<T> {
        self.param(i).and_then(|t| T::from_term(&self.m.store, t))
    }

    /// [`Cx::local`] as a native value (`None`: none, or it does not
    /// convert).
    pub fn local_as<T: Native>(&self, name: Atom) -> Option<T> {
        self.local(name)
            .and_then(|t| T::from_term(&self.m.store, t))
    }

    /// The part of situation id `id` at `path` ([`native::id_part`]) as a
    /// native value (`None`: no such part, or it does not convert).
    pub fn id_part_as<T: Native>(&self, id: Term, path: &[usize]) -> Option<T> {
        native::id_part(&self.m.store, id, path).and_then(|t| T::from_term(&self.m.store, t))
    }

    /// The parts of the selected situation id at `paths`, each as a native
    /// value, in order ([`Cx::id_part_as`] of each; `None`: no id selected,
    /// or a part missing or not converting): the fields a situation is
    /// entered with.
    pub fn id_parts<T: FromIdParts>(&self, paths: &[&[usize]]) -> Option<T> {
        T::from_id_parts(&self.m.store, self.selected()?, paths)
    }

    /// The integer a (dereferenced) term is, if it is one.
    #[inline]
    pub fn int_of(&self, t: Term) -> Option<i64> {
        self.m.store.int_of(t)
    }

    /// The float a (dereferenced) term is, if it is one.
    #[inline]
    pub fn float_of(&self, t: Term) -> Option<f64> {
        self.m.store.float_of(t)
    }

    /// Counts transitions typed code made without recording them (the
    /// history neither kept nor observed).
    #[inline]
    pub fn count_transitions(&mut self, n: u64) {
        self.m.transitions += n;
    }

    /// Whether the run's actions ignore numbers ([`Actions::ignores`](super::Actions::ignores)
    /// of [`ActionShape::Number`](super::ActionShape::Number)).
    #[inline]
    pub fn ignores_numbers(&self) -> bool {
        self.actions.ignores(super::ActionShape::Number)
    }

    /// Appends the situation's history entry (and tells the observer).
    #[inline]
    pub fn record(&mut self, expectation: Term, action: Term, next: Option<Term>) {
        self.m.materialize();
        let id = self.id;
        self.flush_pipe();
        let pipe = *self.pipe;
        self.m
            .record(id, expectation, action, next, pipe, &mut self.observer);
    }

    /// [`Cx::record`] when `recorded` (native code's `run.records`).
    #[inline]
    pub fn record_if(
        &mut self,
        recorded: bool,
        expectation: Term,
        action: Term,
        next: Option<Term>,
    ) {
        if recorded {
            self.record(expectation, action, next);
        }
    }

    /// A recorded exit arc's entry as one call, out of native code's hot
    /// path: [`Cx::enter_counted`] of situation `sit` with its id `id`
    /// (an [`IdArg`]), then [`Cx::record_next`] of the expectation and
    /// action with the id of `next` (the frame's next variant,
    /// [`NatAt::id_term`](super::NatAt::id_term)) built only then.
    #[cold]
    #[inline(never)]
    pub fn enter_next(
        &mut self,
        count: &mut u64,
        sit: SitIx,
        id: impl IdArg,
        expectation: Term,
        action: Term,
        next: &dyn super::NatAt<P>,
    ) {
        let id = id.id_in(&mut self.m.store);
        self.enter_counted(count, sit, id);
        let p = self.m.program;
        self.record_next(expectation, action, |s| next.id_term(p, s));
    }

    /// [`Cx::record`] of an arc whose next situation native code computed:
    /// its id built (`next`, in the store) only here, when recorded.
    #[inline]
    pub fn record_next(
        &mut self,
        expectation: Term,
        action: Term,
        next: impl FnOnce(&mut Store) -> Term,
    ) {
        let next = next(&mut self.m.store);
        self.record(expectation, action, Some(next));
    }

    /// The step to an evaluated next situation, which must name one (D-19).
    pub fn goto(&mut self, next: Term, arc: Option<usize>) -> Result<Step, RunError> {
        self.m.chose = Some((self.sit, arc));
        let n = self.m.store.deref(next);
        // An unbound one ends the DM (the machine's `take_step`, docs/guide/language.md, "Next").
        if self.m.store.functor(n).is_none() && !self.m.store.is_var(n) {
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

/// What native code found wrong with its own frames ([`Cx::fault`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fault {
    /// A frame resumed after a call, in a situation that made none.
    NotWaiting,
    /// A caller resumed with a callee of another DM than it called.
    WrongFrame,
    /// A frame made the machine's as waiting, in a situation that made no call.
    WaitsForNone,
    /// A waiting situation visited as if it were running, or a frame
    /// visited while it runs (its situation moved out).
    Visited,
    /// No native exit arc took the callee's final, but the machine's did.
    Exits,
    /// A native callee's call term that its caller's `embedded_dm` does not take.
    NotTheCall,
    /// A native final closing a history level none opened, or whose call
    /// term does not take its outputs.
    NoLevel,
    /// A native frame's parameter without the part its DM's head pattern
    /// names (the push checked the match: `native::head_matches`).
    HeadPart,
}

/// A value native code makes a term of, of any native type (a term is
/// itself): the arguments of [`Cx::build_of`] and [`Cx::compound_of`].
pub trait AsTerm {
    fn as_term(&self, store: &mut Store) -> Term;
}

impl<T: Native> AsTerm for T {
    #[inline]
    fn as_term(&self, store: &mut Store) -> Term {
        self.to_term(store)
    }
}

impl AsTerm for Term {
    #[inline]
    fn as_term(&self, _: &mut Store) -> Term {
        *self
    }
}

/// An output slot of a native frame (`Option<T>` of a native value),
/// made a term where [`Cx::close_level`] binds it ([`Cx::term`] of the
/// value), `[]` where empty.
pub trait OutSlot {
    fn out_term(&self, store: &mut Store) -> Term;
}

impl<T: Native> OutSlot for Option<T> {
    #[inline]
    fn out_term(&self, store: &mut Store) -> Term {
        match self {
            Some(v) => v.to_term(store),
            None => Term::NIL,
        }
    }
}

/// A tuple of native values read from the parts of a situation id, one
/// path per element, converted in order ([`Cx::id_parts`]).
pub trait FromIdParts: Sized {
    fn from_id_parts(store: &Store, id: Term, paths: &[&[usize]]) -> Option<Self>;
}

macro_rules! from_id_parts {
    ($($t:ident $i:tt),+) => {
        impl<$($t: Native),+> FromIdParts for ($($t,)+) {
            fn from_id_parts(store: &Store, id: Term, paths: &[&[usize]]) -> Option<Self> {
                Some(($(
                    native::id_part(store, id, paths.get($i)?)
                        .and_then(|t| $t::from_term(store, t))?,
                )+))
            }
        }
    };
}

from_id_parts!(A 0);
from_id_parts!(A 0, B 1);
from_id_parts!(A 0, B 1, C 2);
from_id_parts!(A 0, B 1, C 2, D 3);
from_id_parts!(A 0, B 1, C 2, D 3, E 4);
from_id_parts!(A 0, B 1, C 2, D 3, E 4, F 5);
from_id_parts!(A 0, B 1, C 2, D 3, E 4, F 5, G 6);
from_id_parts!(A 0, B 1, C 2, D 3, E 4, F 5, G 6, H 7);

/// [`native::compound`] of values, each made a term in order: how native
/// code builds a DM's call term, a compound of one level, or a situation's
/// id where its pattern does not read back (the DM's `id_s<N>`; else
/// [`fill`]).
pub fn build_of(store: &mut Store, name: Atom, args: &[&dyn AsTerm]) -> Term {
    with_terms(store, args, |store, ts| native::compound(store, name, ts))
}

/// The functor of a hole, `'$hole'(i)`, in a pattern [`Cx::fill`] fills
/// (the compiler makes no pattern with a constant that names it).
pub fn hole_atom() -> Atom {
    static HOLE: std::sync::OnceLock<Atom> = std::sync::OnceLock::new();
    *HOLE.get_or_init(|| Atom::intern("$hole"))
}

/// A situation's id as a cold call of native code takes it
/// ([`Cx::counted_template`]): a term, an atom, or a [`Fill`] the call
/// fills.
pub trait IdArg {
    /// The id, built in `store` where it is a [`Fill`].
    fn id_in(self, store: &mut Store) -> Term;
}

impl IdArg for Term {
    #[inline]
    fn id_in(self, _: &mut Store) -> Term {
        self
    }
}

impl IdArg for Atom {
    #[inline]
    fn id_in(self, _: &mut Store) -> Term {
        Term::atom(self)
    }
}

/// A pattern and its holes ([`Cx::fill`]'s arguments) given to a call
/// that fills them first: `Fill(p.k[29], (&r1,))`, where a `let` of the
/// filled id would come just before the call. The holes a tuple of
/// references ([`Holes`]), so a call that fills only on a gated path
/// does no work for them on the other.
#[derive(Clone, Copy)]
pub struct Fill<H>(pub Term, pub H);

impl<H: Holes> IdArg for Fill<H> {
    #[inline]
    fn id_in(self, store: &mut Store) -> Term {
        let pattern = self.0;
        self.1
            .with_terms(store, |store, ts| fill_in(store, pattern, ts))
    }
}

/// [`Cx::fill`] in `store`: how native code builds a term of native values
/// from its pattern (an action's term, a situation's id).
pub fn fill(store: &mut Store, pattern: Term, holes: &[&dyn AsTerm]) -> Term {
    with_terms(store, holes, |store, ts| fill_in(store, pattern, ts))
}

/// [`fill`] of `t` with the holes' terms (no allocation for compounds of up
/// to eight arguments): a pattern marked as it was read ([`mark_pattern`])
/// walked along its holes only, its constant parts neither walked nor
/// copied; any other, walked whole.
pub(super) fn fill_in(store: &mut Store, t: Term, holes: &[Term]) -> Term {
    if store.is_holed(t) {
        fill_holed(store, t, holes)
    } else {
        fill_walk(store, t, holes)
    }
}

/// Whether `t` is `'$hole'(i)`: `Some(i)`.
#[inline]
fn hole_index(store: &Store, name: Atom, args: &[Term]) -> Option<usize> {
    match args {
        [i] if name == hole_atom() => store.int_of(*i).and_then(|i| usize::try_from(i).ok()),
        _ => None,
    }
}

/// [`fill_in`] of a compound flagged `HOLED`: only its flagged arguments
/// have holes below them.
fn fill_holed(store: &mut Store, t: Term, holes: &[Term]) -> Term {
    if let crate::term::Value::Compound(name, args) = store.value(t) {
        if let Some(i) = hole_index(store, name, args) {
            return holes.get(i).copied().unwrap_or(t);
        }
    }
    let mut buf = [Term::NIL; 8];
    let mut spill = Vec::new();
    let Some((name, args)) = args_copy(store, t, &mut buf, &mut spill) else {
        return t;
    };
    for a in args.iter_mut() {
        if store.is_holed(*a) {
            *a = fill_holed(store, *a, holes);
        }
    }
    native::compound(store, name, args)
}

/// Compound `t`'s name and a copy of its arguments, in `buf` up to 8 of
/// them (no allocation), else in `spill`; `None` for any other term.
fn args_copy<'b>(
    store: &Store,
    t: Term,
    buf: &'b mut [Term; 8],
    spill: &'b mut Vec<Term>,
) -> Option<(Atom, &'b mut [Term])> {
    let crate::term::Value::Compound(name, args) = store.value(t) else {
        return None;
    };
    let n = args.len();
    match buf.get_mut(..n) {
        Some(b) => {
            b.copy_from_slice(args);
            Some((name, &mut buf[..n]))
        }
        None => {
            spill.extend_from_slice(args);
            Some((name, &mut spill[..]))
        }
    }
}

/// [`fill_in`] of a pattern not marked: walked whole.
fn fill_walk(store: &mut Store, t: Term, holes: &[Term]) -> Term {
    let mut buf = [Term::NIL; 8];
    let mut spill = Vec::new();
    let Some((name, args)) = args_copy(store, t, &mut buf, &mut spill) else {
        return t;
    };
    if let Some(&h) = hole_index(store, name, args).and_then(|i| holes.get(i)) {
        return h;
    }
    let mut changed = false;
    for a in args.iter_mut() {
        let f = fill_walk(store, *a, holes);
        changed |= f != *a;
        *a = f;
    }
    if !changed {
        return t;
    }
    native::compound(store, name, args)
}

/// Marks pattern `t` for [`fill`] (once, as a program's constant is read,
/// `read_consts`): each compound with a hole `'$hole'(i)` below it, the
/// hole included, flagged, so that filling walks those only. Whether `t`
/// has a hole.
pub fn mark_pattern(store: &mut Store, t: Term) -> bool {
    stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
        let (name, args) = match store.value(t) {
            crate::term::Value::Compound(name, args) => (name, args.to_vec()),
            _ => return false,
        };
        let mut holed = hole_index(store, name, &args).is_some();
        if !holed {
            for a in args {
                holed |= mark_pattern(store, a);
            }
        }
        if holed {
            store.set_holed(t);
        }
        holed
    })
}

/// `f` of `args` made terms (no allocation up to eight).
fn with_terms(
    store: &mut Store,
    args: &[&dyn AsTerm],
    f: impl FnOnce(&mut Store, &[Term]) -> Term,
) -> Term {
    args.with_terms(store, f)
}

#[cfg(test)]
#[path = "fill_tests.rs"]
mod fill_tests;
