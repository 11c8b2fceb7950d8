//! The machine's loop: calls and returns of DMs on a heap stack (no Rust
//! recursion per embedded DM), selection of the next situation, the step
//! each situation ends with, interpreted or compiled (D-7, D-15, D-21,
//! D-22, D-42a), and garbage collection between two situations, with
//! every term the machine refers to as a root.

use super::io::{Actions, Perception};
use super::observe::Observer;
use super::outcome::{Outcome, RunError};
use super::program::{Cx, DmProgram, Step};
use super::situation::{DmIx, Instance, Kind, SitIx};
use super::state::{Frame, Goto, Machine, Pending};
use super::steps::Chosen;
use crate::history::Item;
use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::{atoms, Atom};

/// The situation [`Machine::select`] picked.
enum Selected {
    /// Instantiated (D-7), its id unified with the next situation's value.
    Instance(Instance),
    /// Compiled: `selected` is the next situation's value that selected it
    /// (then also its id), `None` when entered by index or as the initial one.
    /// `id` is the atom (or name, for code that builds its compound id).
    Compiled { id: Term, selected: Option<Term> },
}

impl<'p, P: DmProgram> Machine<'p, P> {
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
        self.report_unmatched(&mut observer);
        if let (Err(e), Some(o)) = (&result, &mut observer) {
            self.inspect(pipe, Some(e), &mut **o);
        }
        // On error, the history so far: unwind the stack, nesting each
        // embedded DM's partial history into its caller's, as if it returned.
        let mut history = Vec::new();
        // Native code's levels first: the frames above the machine's.
        while let Some(level) = self.levels.pop_back() {
            let mut h = level.history;
            if !history.is_empty() {
                h.push(Item::Nested(std::mem::take(&mut history)));
            }
            history = h;
        }
        while let Some(frame) = self.frames.pop() {
            let mut h = frame.history;
            if !history.is_empty() {
                h.push(Item::Nested(std::mem::take(&mut history)));
            }
            history = h;
        }
        let interrupted = result.is_err() && self.stop_requested();
        // The evaluator's notes of variables neither local nor global
        // (`Store::note_undefined`), after the machine's own warnings.
        let mut warnings = self.warnings;
        warnings.extend(
            self.store
                .undefined_noted()
                .iter()
                .map(|&(op, name)| super::RunWarning::undefined_variable(op, name)),
        );
        let outcome = Outcome {
            interrupted,
            result,
            history,
            out_arg: pipe,
            globals: self.globals,
            final_situation,
            transitions: self.transitions,
            warnings,
        };
        (outcome, self.store)
    }

    fn call_dm(&mut self, call: Term, sit: Option<(SitIx, Term)>) -> Result<(), RunError> {
        let (dm, call) = self.callee(call, sit)?;
        self.push_frame(dm, call);
        Ok(())
    }

    /// The DM that `call` calls, as every call of the machine finds it (the
    /// loop's and a native frame's made the machine's, `Cx::wait_template`):
    /// the depth limit checked, list tails closed under
    /// [`Options::close_list_tails`](super::Options::close_list_tails), the
    /// first DM of its name (D-3), its fresh head unified with the call (a
    /// head that does not unify is an error, E13). Returns the DM and the
    /// call term (dereferenced) its frame takes; pushes nothing.
    pub(super) fn callee(
        &mut self,
        call: Term,
        sit: Option<(SitIx, Term)>,
    ) -> Result<(super::DmIx, Term), RunError> {
        self.check_depth(sit)?;
        let call = self.store.deref(call);
        if self.options.close_list_tails && sit.is_some() {
            close_list_tails(&mut self.store, call);
        }
        let Some((name, _)) = self.store.functor(call) else {
            return Err(self.err(
                format!("`{}` does not name a DM", self.store.writeq(call)),
                sit,
                None,
            ));
        };
        let Some(dm) = self.program.dm_by_name(name) else {
            let why = self.program.left_out(name);
            let message = why.unwrap_or_else(|| format!("there is no DM named `{name}`"));
            return Err(self.err(message, sit, None));
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
        Ok((dm, call))
    }

    /// The error of a call that would exceed [`Options::max_depth`](super::Options::max_depth).
    pub(super) fn check_depth(&self, sit: Option<(SitIx, Term)>) -> Result<(), RunError> {
        if self.frames.len() + self.lazy.len() >= self.options.max_depth {
            return Err(self.err(
                format!(
                    "the DM stack exceeded {} nested DMs",
                    self.options.max_depth
                ),
                sit,
                None,
            ));
        }
        Ok(())
    }

    /// Pushes the frames of the DMs typed code called without them
    /// ([`Machine::lazy`]), each caller waiting as it would; a no-op when
    /// there are none.
    #[inline]
    pub(super) fn materialize(&mut self) {
        if !self.lazy.is_empty() {
            self.materialize_all();
        }
    }

    #[cold]
    fn materialize_all(&mut self) {
        let mut lazy = std::mem::take(&mut self.lazy);
        for l in lazy.drain(..) {
            self.frames.last_mut().expect("a frame is running").pending = Some(l.caller);
            self.push_frame(l.dm, l.call);
        }
        // The buffer is kept: no allocation per call once warm.
        self.lazy = lazy;
    }

    /// Pushes a frame for DM `dm` called as `call` (checked by the caller:
    /// the depth limit, the head unified), with fresh locals.
    pub(super) fn push_frame(&mut self, dm: super::DmIx, call: Term) {
        self.push_frame_with(dm, call, Vec::new());
    }

    /// [`Machine::push_frame`] with the history the DM has so far.
    pub(super) fn push_frame_with(&mut self, dm: super::DmIx, call: Term, history: Vec<Item>) {
        let locals = self.program.locals(dm, &mut self.store);
        self.frames.push(Frame {
            dm,
            dm_id: call,
            locals,
            history,
            pending: None,
        });
    }

    /// The end of the running DM: its frame popped, its history nested in
    /// the caller's when kept; the caller's waiting situation taken. `None`
    /// when the main DM has ended (its frame stays, for the history).
    pub(super) fn pop_frame(&mut self) -> Option<Option<Pending>> {
        let frame = self.frames.pop().expect("a frame is running");
        let keep = self.options.keep_history;
        let Some(caller) = self.frames.last_mut() else {
            self.frames.push(frame);
            return None;
        };
        if keep {
            caller.history.push(Item::Nested(frame.history));
        } else if frame.history.capacity() == 0 {
            // Nothing allocated: skip the (out-of-line) drop of no entries.
            std::mem::forget(frame.history);
        }
        Some(caller.pending.take())
    }

    /// Why the run cannot start when the program runs the runtime's
    /// `when/3` as a conditional ([`DmProgram::lowers_runtime_when`]) and
    /// the host's registry no longer holds it (registered its own
    /// `when/3`, or removed it): the plans and native code would compute
    /// the runtime's `when` while the evaluator's path calls the host's, a
    /// silent disagreement. The fix is the declaration that makes the
    /// compiler keep every `when/3` call the evaluator's.
    fn replaced_runtime_when(&self) -> Option<String> {
        let when = Atom::intern("when");
        if !self.program.lowers_runtime_when() || self.functions.is_standard(when, 3) {
            return None;
        }
        let what = if self.functions.contains(when, 3) {
            "registers its own `when/3`"
        } else {
            "does not hold it (removed, e.g. by a Prolog `when/3` the program was not compiled with)"
        };
        Some(format!(
            "the program was compiled with the runtime's own `when/3` (its \
             calls run as conditionals) but the host's function registry \
             {what}: declare `when/3` in the application's \
             `host_functions.pl` (`when/3` is a host function) and compile \
             it again, or register the runtime's (`Functions::standard`)"
        ))
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
        let mut started = false;
        loop {
            if self.stop_requested() {
                return Err(self.err("interrupted (the run was stopped by a signal)", None, None));
            }
            self.maybe_gc(pipe, &mut goto);
            self.between(&mut goto)?;
            // The functions' own start (Prolog directives) at the first
            // transition: after the run's options were checked and after the
            // hooks between transitions (a debugger, a live view) had their say.
            if !started {
                started = true;
                if let Some(message) = self.replaced_runtime_when() {
                    return Err(self.err(message, None, None));
                }
                if let Err(message) = self.functions.start() {
                    return Err(self.err(message, None, None));
                }
            }
            let (mut sit, inst) = self.select(&goto)?;
            let mut dm = self.frames.last().expect("a frame is running").dm;
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
                    let step = program.run_situation(dm, sit, &mut cx);
                    // The pipe native code held, made a term before the
                    // machine (its report too, on an error) reads it.
                    cx.flush_pipe();
                    let step = step?;
                    // The code may have gone on to other situations of the DM.
                    let (at, id, selected) = (cx.sit, cx.id, cx.selected);
                    debug_assert!(self.lazy.is_empty(), "typed code left lazy frames");
                    debug_assert!(self.levels.is_empty(), "native code left history levels");
                    if let Step::Template = step {
                        // Nothing of the visit done: the situation from its
                        // template, in the running DM (native code may have
                        // made its callers' frames the machine's first).
                        sit = at;
                        dm = self.frames.last().expect("a frame is running").dm;
                        self.template_instance(dm, at, selected)?
                    } else {
                        let sit = at;
                        match self.take_step(
                            step,
                            sit,
                            id,
                            pipe,
                            perception,
                            actions,
                            observer,
                            final_situation,
                        )? {
                            Some(next) => goto = next,
                            None => {
                                final_situation.get_or_insert(id);
                                return Ok(());
                            }
                        }
                        continue;
                    }
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
                    let call = self.held_or_eval(e, here)?;
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
            match self.take_step(
                step,
                sit,
                inst.id,
                pipe,
                perception,
                actions,
                observer,
                final_situation,
            )? {
                Some(next) => goto = next,
                None => {
                    final_situation.get_or_insert(inst.id);
                    return Ok(());
                }
            }
        }
    }

    /// Where control goes after situation `sit` (id `id`) of the running DM
    /// took `step`; `None` when the main DM has ended (in `final_situation`).
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
        final_situation: &mut Option<Term>,
    ) -> Result<Option<Goto>, RunError> {
        let program = self.program;
        let mut unbound_end = false;
        loop {
            let here = Some((sit, id));
            match step {
                Step::Goto(next) if self.store.is_var(self.store.deref(next)) => {
                    // docs/guide/language.md, "Next": a next situation without a value ends the DM
                    // as a final situation would, but with no entry of its
                    // own and the variable as its final situation (a caller
                    // takes its first exit arc), as the original's `empty`.
                    self.warn_unbound_next(next, here);
                    unbound_end = true;
                    id = self.store.deref(next);
                    step = Step::Final;
                }
                Step::Goto(next) if self.store.deref(next) == Term::atom(atoms::EMPTY) => {
                    // `=> empty` ends the DM the same way, whatever its
                    // situations are called: the original's first clause
                    // for the next situation is `empty`'s (its final
                    // situation left unbound: a caller takes its first
                    // exit arc, with a warning).
                    self.warn_empty_next(here);
                    unbound_end = true;
                    id = self.store.new_var();
                    step = Step::Final;
                }
                Step::Goto(next) => return Ok(Some(Goto::Situation(next))),
                Step::GotoSit(next) => return Ok(Some(Goto::Index(next))),
                // Taken where the code returns it (the run loop).
                Step::Template => {
                    return Err(self.err(
                        "compiled code handed a situation to its template outside a visit",
                        here,
                        None,
                    ))
                }
                Step::Call { call, saved } => {
                    self.frames.last_mut().expect("frame").pending =
                        Some(Pending::Compiled { sit, saved, id });
                    self.call_dm(call, here)?;
                    return Ok(Some(Goto::Initial));
                }
                Step::Unmet { .. } if std::mem::take(&mut self.again) => {
                    // Asked to perceive again: a new instance, no recovery.
                    self.report_unmatched(observer);
                    return Ok(Some(Goto::Situation(id)));
                }
                Step::Unmet { type_term } => {
                    // No expectation met (D-15 / D-42a): recovery DM, then a new instance.
                    self.report_unmatched(observer);
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
                    let Some(pending) = self.pop_frame() else {
                        if unbound_end {
                            *final_situation = Some(id);
                        }
                        return Ok(None);
                    };
                    unbound_end = false;
                    match pending {
                        Some(Pending::Recursive { sit: rsit }) => {
                            let rinst = self.instances.pop().expect("a pending instance");
                            let rid = rinst.id;
                            let next =
                                self.finish_recursive(rsit, rinst, id, pipe, actions, observer)?;
                            // The exit arc's next situation is any arc's:
                            // unbound or `empty`, it ends the DM (the arms
                            // above), where the recursive situation is.
                            (sit, id) = (rsit, rid);
                            step = Step::Goto(next);
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
                            let exit = program.run_exit(dm, sit, saved, final_id, &mut cx);
                            cx.flush_pipe();
                            step = exit?;
                        }
                        None => unreachable!("a caller frame always has a pending situation"),
                    }
                }
            }
        }
    }

    /// A fresh instance of compiled situation `sit` whose code handed it
    /// over ([`Step::Template`]), as the machine's selection would have
    /// made it: its id unified with the value that selected it (`selected`;
    /// the code's selection said it unifies), its head linked to the call.
    pub(super) fn template_instance(
        &mut self,
        dm: DmIx,
        sit: SitIx,
        selected: Option<Term>,
    ) -> Result<Instance, RunError> {
        let inst = self.instance(dm, sit)?;
        if let Some(value) = selected {
            if !self.store.unify(inst.id, value) {
                return Err(self.err(
                    format!(
                        "the situation handed over does not take `{}`",
                        self.store.writeq(value)
                    ),
                    Some((sit, inst.id)),
                    None,
                ));
            }
        }
        let dm_id = self.frames.last().expect("a frame is running").dm_id;
        self.link_head(inst.head, dm_id);
        Ok(inst)
    }

    /// A fresh instance of a situation that does not run as code.
    fn instance(&mut self, dm: DmIx, sit: SitIx) -> Result<Instance, RunError> {
        match self.program.instantiate(dm, sit, &mut self.store) {
            Some(inst) => Ok(inst),
            None => Err(self.err(
                format!(
                    "the program has neither code nor an instance for situation {sit} of its DM"
                ),
                None,
                None,
            )),
        }
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
                let inst = self.instance(dm, 0)?;
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
                let inst = self.instance(dm, sit)?;
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
                        if let Some((id, selected)) =
                            self.select_compiled_one(dm, sit, id, functor, value)
                        {
                            return Ok((sit, Selected::Compiled { id, selected }));
                        }
                        continue;
                    }
                    if !self.program.may_select(dm, sit, value, &self.store) {
                        continue;
                    }
                    let mark = self.store.mark();
                    let inst = self.instance(dm, sit)?;
                    if self.store.unify(inst.id, value) {
                        self.link_head(inst.head, dm_id);
                        return Ok((sit, Selected::Instance(inst)));
                    }
                    self.store.undo_to(mark);
                }
                // Where the next situation was chosen: that situation and
                // arc (file:line:col of the arc), when it is known.
                let message = format!(
                    "there is no situation `{}` in this DM",
                    self.store.writeq(value)
                );
                let chose = self
                    .chose
                    .take()
                    .filter(|&(sit, _)| (sit as usize) < self.program.situation_count(dm));
                // The situation by its id's name, on both back ends (a
                // compiled situation builds no instance; an instance's fresh
                // variables would name it differently in each run).
                let id = chose.and_then(|(sit, _)| match self.program.compiled_id(dm, sit) {
                    Some((name, _)) => Some(Term::atom(name)),
                    None => {
                        let inst = self.program.instantiate(dm, sit, &mut self.store)?;
                        match self.store.functor(inst.id) {
                            Some((name, _)) => Some(Term::atom(name)),
                            None => Some(inst.id),
                        }
                    }
                });
                match (chose, id) {
                    (Some((sit, arc)), Some(id)) => Err(self.err(message, Some((sit, id)), arc)),
                    _ => Err(self.err(message, None, None)),
                }
            }
        }
    }

    /// Whether compiled situation `sit` (its id's name and arity `id`) of
    /// DM `dm` takes the next situation `value` (principal functor
    /// `functor`), D-21: its id and the value that selected it (`None` for
    /// an atom id), else nothing bound. One rule for the machine's
    /// selection and for code going on by itself ([`Machine::select_compiled_first`]).
    fn select_compiled_one(
        &mut self,
        dm: DmIx,
        sit: SitIx,
        id: (Atom, usize),
        functor: Option<(Atom, usize)>,
        value: Term,
    ) -> Option<(Term, Option<Term>)> {
        if functor != Some(id) {
            return None;
        }
        if id.1 == 0 {
            // An atom id unifies only with that atom.
            return Some((Term::atom(id.0), None));
        }
        let mark = self.store.mark();
        if self
            .program
            .select_compiled(dm, sit, value, &mut self.store)
        {
            return Some((value, Some(value)));
        }
        self.store.undo_to(mark);
        None
    }

    /// The situation of DM `dm` the next situation `value` (dereferenced,
    /// a name) selects, when the machine's selection would pick a compiled
    /// one: `None` (nothing bound) when a situation instantiated from its
    /// template may take it first, or none does (the machine then selects,
    /// and reports what it must).
    pub(super) fn select_compiled_first(
        &mut self,
        dm: DmIx,
        value: Term,
    ) -> Option<(SitIx, Term, Option<Term>)> {
        let functor = self.store.functor(value);
        // `empty` ends the DM whatever its situations are called: the
        // machine's `take_step` ends it.
        if functor? == (atoms::EMPTY, 0) {
            return None;
        }
        for sit in 0..self.program.situation_count(dm) as SitIx {
            match self.program.compiled_id(dm, sit) {
                Some(id) => {
                    if let Some((id, selected)) =
                        self.select_compiled_one(dm, sit, id, functor, value)
                    {
                        return Some((sit, id, selected));
                    }
                }
                None if self.program.may_select(dm, sit, value, &self.store) => return None,
                None => {}
            }
        }
        None
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

    /// Asks the perceptual interpreter which expectation is met (D-14, E2, E3).
    fn choose_perceptual(
        &mut self,
        sit: SitIx,
        inst: &Instance,
        perception: &mut dyn Perception,
    ) -> Result<Option<Chosen>, RunError> {
        let here = Some((sit, inst.id));
        self.prepare_arcs(inst, here)?;
        let Some(i) = self.choose_index(inst.type_term, here, perception, None)? else {
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

/// Most cells [`close_list_tails`] visits: a term bigger (or a cyclic one)
/// is left as it is beyond that.
const CLOSE_LIST_TAILS_BUDGET: usize = 1 << 22;

/// Binds to `[]` the unbound tail of every list in `t` (the original's
/// evaluation of a DM call's arguments, [`Options::close_list_tails`](super::options::Options::close_list_tails)):
/// `[a|T]` becomes `[a]`, in lists nested in lists and compounds too; an
/// unbound variable that is not a list's tail stays unbound.
pub(crate) fn close_list_tails(store: &mut Store, t: Term) {
    let mut stack = vec![(t, false)];
    let mut budget = CLOSE_LIST_TAILS_BUDGET;
    while let Some((t, is_tail)) = stack.pop() {
        if budget == 0 {
            return;
        }
        budget -= 1;
        let t = store.deref(t);
        if store.is_var(t) {
            if is_tail {
                store.bind(t, Term::NIL);
            }
            continue;
        }
        if let Some(&[head, tail]) = store.compound_args(t, atoms::DOT, 2) {
            stack.push((tail, true));
            stack.push((head, false));
            continue;
        }
        for &a in store.args(t).iter().rev() {
            stack.push((a, false));
        }
    }
}
