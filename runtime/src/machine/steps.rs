//! The steps of one situation, shared by the loop and by compiled code
//! ([`Cx`](super::Cx)): in_arg, `prog`, the arcs' expectations, the choice
//! of the met one (perception, the neutral rule, exit arcs), action, next
//! situation, out_arg, diag_mod and the history entry (D-8..D-22).

use super::io::{Actions, Perceived, Percept, Perception};
use super::observe::Observer;
use super::outcome::RunError;
use super::program::DmProgram;
use super::situation::{Instance, SitIx};
use super::state::Machine;
use crate::eval::{self, EvalCtx, EvalError};
use crate::history::{Entry, Item};
use crate::term::Term;
use sitlog_syntax::atoms;

/// What happened in one situation: the chosen arc's terms.
pub(super) struct Chosen {
    pub(super) arc: usize,
    pub(super) expectation: Term,
    pub(super) action: Term,
    pub(super) next: Term,
    pub(super) out_arg: Option<Term>,
}

impl<'p, P: DmProgram> Machine<'p, P> {
    /// The in_arg `pattern` unified with the incoming `pipe` (D-8): a
    /// mismatch is skipped as the original skips it (a failed unify
    /// leaves the store as it was: the pattern's variables stay unbound,
    /// the pipe unchanged) with a [`RunWarning`](super::RunWarning) the
    /// first time the situation skips
    /// ([`Options::skip_unmatched_in_arg`](super::Options::skip_unmatched_in_arg),
    /// the default), else an error (E14; `--deny-warnings`).
    /// Every in_arg goes through here: the loop, compiled term code
    /// (`Cx::in_arg`), a frame native code hands over
    /// (`Cx::wait_template`) and a pattern native code does not match
    /// (handed to the machine, nothing of the visit done), so both back
    /// ends skip, warn and fail alike.
    pub(super) fn unify_in_arg(
        &mut self,
        pattern: Term,
        pipe: Term,
        here: Option<(SitIx, Term)>,
    ) -> Result<(), RunError> {
        if self.store.unify(pattern, pipe) {
            return Ok(());
        }
        if self.options.skip_unmatched_in_arg {
            self.warn_in_arg_skipped(pattern, pipe, here);
            return Ok(());
        }
        Err(self.in_arg_denied(pattern, pipe, here))
    }

    /// E14's error (`--deny-warnings`): the warning's text and place (the
    /// in_arg's `file:line:col`, its variables numbered `_G0`, ..), so
    /// that the interpreter and a compiled task say the same bytes and a
    /// reporter with the source points at the in_arg ([`ErrorSite::in_arg`](super::ErrorSite::in_arg)).
    #[cold]
    fn in_arg_denied(&self, pattern: Term, pipe: Term, here: Option<(SitIx, Term)>) -> RunError {
        let frame = match self.lazy.last() {
            Some(l) => Some((l.dm, l.call)),
            None => self.frames.last().map(|f| (f.dm, f.dm_id)),
        };
        let call = frame.map_or(Term::atom(atoms::NONE), |(_, c)| c);
        let id = here.map_or(Term::atom(atoms::NONE), |(_, id)| id);
        let [call, id, pattern, pipe] = writeq_renumbered(&self.store, [call, id, pattern, pipe]);
        let mut e = self.err(
            format!(
                "in_arg `{pattern}` does not match the incoming pipe value `{pipe}` (warnings are denied; without --deny-warnings the run skips this in_arg, as the original SitLog does)"
            ),
            here,
            None,
        );
        if let Some((dm, _)) = frame {
            e.dm = Some(call);
            if let Some((s, _)) = here {
                e.situation = Some(id);
                if let Some(at) = self.program.in_arg_location(dm, s) {
                    e.location = Some(at);
                }
            }
        }
        if let Some(site) = e.site.as_deref_mut() {
            site.in_arg = true;
        }
        e
    }

    /// The DM a warning is about: the lazy frame's or the top frame's, with
    /// its call (`None`: no DM runs).
    fn warning_dm(&self) -> Option<(super::DmIx, Term)> {
        match self.lazy.last() {
            Some(l) => Some((l.dm, l.call)),
            None => self.frames.last().map(|f| (f.dm, f.dm_id)),
        }
    }

    /// The warning of an in_arg skipped ([`Machine::unify_in_arg`]), the
    /// first time its situation skips one; located at the in_arg
    /// ([`DmProgram::in_arg_location`](super::DmProgram::in_arg_location)),
    /// else at the situation. Cold: the hot path is the unify that succeeds.
    #[cold]
    fn warn_in_arg_skipped(&mut self, pattern: Term, pipe: Term, here: Option<(SitIx, Term)>) {
        let Some((dm, call)) = self.warning_dm() else {
            return;
        };
        let key = (dm, here.map(|(s, _)| s));
        if self.skipped_in_args.contains(&key) {
            return;
        }
        self.skipped_in_args.push(key);
        let id = here.map_or(Term::atom(atoms::NONE), |(_, id)| id);
        let [call, id, pattern, pipe] = writeq_renumbered(&self.store, [call, id, pattern, pipe]);
        let location = here.and_then(|(s, _)| {
            self.program
                .in_arg_location(dm, s)
                .or_else(|| self.program.location(dm, s))
        });
        self.warnings.push(super::RunWarning {
            message: format!(
                "in_arg `{pattern}` does not match the incoming pipe value `{pipe}`: skipped, as the original SitLog does (the situation runs with the in_arg's variables unbound and the pipe unchanged; --deny-warnings makes it an error)"
            ),
            dm: call,
            situation: id,
            location,
        });
    }

    /// The warning of a typed or scripted input that met no expectation
    /// ([`Perception::unmatched_is_news`]), the first time its situation
    /// reads one: the input and the expectations, variables numbered as
    /// in the in_arg's warning, located at the situation. The run reads
    /// again, as the original does (D-15). Cold.
    #[cold]
    fn warn_unmatched_input(&mut self, input: Term, here: Option<(SitIx, Term)>) {
        let Some((dm, call)) = self.warning_dm() else {
            return;
        };
        let key = (dm, here.map(|(s, _)| s));
        if self.unmatched_warned.contains(&key) {
            return;
        }
        self.unmatched_warned.push(key);
        let id = here.map_or(Term::atom(atoms::NONE), |(_, id)| id);
        let expectations = self.store.list(&self.expectations);
        let [call, id, input, expectations] =
            writeq_renumbered(&self.store, [call, id, input, expectations]);
        let location = here.and_then(|(s, _)| self.program.location(dm, s));
        self.warnings.push(super::RunWarning {
            message: format!(
                "the input `{input}` meets none of the expectations {expectations}: read again, as the original SitLog does (it prints `No satisfied expected intention!`); a misspelt expectation or input line? (said once per situation)"
            ),
            dm: call,
            situation: id,
            location,
        });
    }

    /// A final situation's out_arg, evaluated, becomes the pipe unless it is a variable.
    pub(super) fn final_out_arg(
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

    /// `prog` on a renamed copy linked to in_arg/out_arg only (D-10):
    /// `links` are the terms whose variables stay shared.
    pub(super) fn run_prog(
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
    /// history, the globals and the functions (`#[inline]`: a constructor
    /// that `cx` calls too, from another codegen unit, and must not cost a
    /// call).
    #[inline]
    pub(super) fn eval_ctx(&mut self) -> EvalCtx<'_> {
        let frame = self.frames.last_mut().expect("a frame is running");
        EvalCtx {
            store: &mut self.store,
            locals: &mut frame.locals,
            globals: &mut self.globals,
            history: &frame.history,
            functions: &self.functions,
        }
    }

    pub(super) fn eval_in_frame(
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
    pub(super) fn eval_read_only(
        &mut self,
        t: Term,
        here: Option<(SitIx, Term)>,
    ) -> Result<Term, RunError> {
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
    pub(super) fn prepare_arcs(
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
                Ok(v) => {
                    if self.options.close_list_tails {
                        // `--legacy`: closed as the original's evaluator closes them.
                        super::run::close_list_tails(&mut self.store, v);
                    }
                    self.expectations.push(v)
                }
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

    /// Which of the evaluated expectations (`self.expectations`, one per
    /// arc) is met: the neutral rule, else what the perceptual interpreter
    /// perceived, the last arc whose expectation unifies winning (D-14, E2, E3).
    /// `first`: what was perceived for this situation already
    /// ([`Machine::perceive_kept`]), taken as the first read.
    pub(super) fn choose_index(
        &mut self,
        type_term: Term,
        here: Option<(SitIx, Term)>,
        perception: &mut dyn Perception,
        mut first: Option<Result<Perceived, String>>,
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
            let perceived = match first.take() {
                Some(p) => p,
                None => {
                    let exps = std::mem::take(&mut self.expectations);
                    let p = perception.perceive(&mut self.store, type_term, &exps);
                    self.expectations = exps;
                    p
                }
            };
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
                // Two compounds of constants (`said(yes)`, `said(no)`): no mark.
                match self.store.unify_flat(input, self.expectations[i]) {
                    Some(true) => return Ok(Some(i)),
                    Some(false) => continue,
                    None => {}
                }
                let mark = self.store.mark();
                if self.store.unify(input, self.expectations[i]) {
                    return Ok(Some(i));
                }
                self.store.undo_to(mark);
            }
            if let (Some((_, id)), Some(frame)) = (here, self.frames.last()) {
                let depth = self.frames.len() - 1;
                self.unmatched.push((frame.dm_id, id, input, depth));
            }
            if perception.unmatched_is_news() {
                self.warn_unmatched_input(input, here);
            }
            if attempt == 0 && !second_read_allowed {
                break;
            }
        }
        Ok(None)
    }

    /// [`Machine::choose_index`]'s first read, for native code that keeps
    /// its frames (`Cx::choose_kept`): `Ok(i)` when arc `i`'s expectation
    /// is met (the last that unifies, as there), with no effect but the
    /// perception's and the bindings (an input handed over as
    /// [`Percept::Wrapped`] matched in place, [`Machine::match_wrapped`]); else `Err(first)`, nothing but the
    /// read done, for `choose_index` to go on from it (`first`: what was
    /// read) once the frames are the machine's. Nothing here reads the
    /// machine's frames: the cases that do are left to `choose_index`
    /// unread (`Err(None)`): no arcs, a `neutral` type, a perception that
    /// is told where it waits (`Perception::uses_waiting_at`: the running
    /// DM's call), and everything after a read that meets no expectation
    /// (the unmatched input recorded with the DM and depth, the warning,
    /// a second read) or fails (its error names the running DM).
    pub(super) fn perceive_kept(
        &mut self,
        type_term: Term,
        perception: &mut dyn Perception,
    ) -> Result<usize, Option<Result<Perceived, String>>> {
        if self.expectations.is_empty()
            || self.store.atom_of(type_term) == Some(atoms::NEUTRAL)
            || perception.uses_waiting_at()
        {
            return Err(None);
        }
        let percept = perception.perceive_percept(&mut self.store, type_term, &self.expectations);
        let perceived = match percept {
            Ok(Percept::Wrapped(name, arg)) => return self.match_wrapped(name, arg),
            Ok(Percept::Whole(p)) => Ok(p),
            Err(e) => Err(e),
        };
        let Ok(Perceived::Input(input)) = perceived else {
            return Err(Some(perceived));
        };
        for i in (0..self.expectations.len()).rev() {
            // Two compounds of constants (`said(yes)`, `said(no)`): no mark.
            match self.store.unify_flat(input, self.expectations[i]) {
                Some(true) => return Ok(i),
                Some(false) => continue,
                None => {}
            }
            let mark = self.store.mark();
            if self.store.unify(input, self.expectations[i]) {
                return Ok(i);
            }
            self.store.undo_to(mark);
        }
        Err(Some(perceived))
    }

    /// [`Machine::perceive_kept`]'s match of the input `name(arg)`, not
    /// built ([`Percept::Wrapped`]), against the expectations, the last
    /// that unifies winning: an expectation `name(E)` unifies with it when
    /// `E` unifies with `arg` (the same bindings as unifying the
    /// compounds), one of another functor or a constant never does; an
    /// unbound expectation gets `name(arg)` built. `Err` with the input
    /// built when none is met, for `choose_index` to go on from.
    #[inline]
    fn match_wrapped(
        &mut self,
        name: sitlog_syntax::Atom,
        arg: Term,
    ) -> Result<usize, Option<Result<Perceived, String>>> {
        let mut whole = None;
        for i in (0..self.expectations.len()).rev() {
            let e = self.expectations[i];
            // A failed unification undoes its own bindings.
            match self.store.unify_wrapped(name, arg, e) {
                Some(true) => return Ok(i),
                Some(false) => {}
                None => {
                    let input = *whole.get_or_insert_with(|| self.store.compound(name, &[arg]));
                    if self.store.unify(input, e) {
                        return Ok(i);
                    }
                }
            }
        }
        let input = whole.unwrap_or_else(|| self.store.compound(name, &[arg]));
        Err(Some(Ok(Perceived::Input(input))))
    }

    /// The first exit arc whose expectation unifies with the embedded DM's
    /// final situation (D-22), or an error.
    pub(super) fn choose_exit_index(
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
    pub(super) fn conclude(
        &mut self,
        inst: &Instance,
        here: Option<(SitIx, Term)>,
        chosen: Chosen,
        pipe: &mut Term,
        actions: &mut dyn Actions,
        observer: &mut Option<&mut dyn Observer>,
    ) -> Result<Term, RunError> {
        let arc = Some(chosen.arc);
        self.chose = here.map(|(sit, _)| (sit, arc));
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
        // An unbound next situation ends the DM (the loop's `take_step`, docs/guide/language.md, "Next").
        if self.store.functor(n).is_none() && !self.store.is_var(n) {
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

    /// Where a warning about the next situation of the arc just taken goes,
    /// once per DM and situation (`unbound_next_warned`): the running DM's
    /// call, the arc named (`arc 2's `) if it was the one chosen here, and
    /// the situation's place; `None` when it was said already or no DM runs.
    fn next_warning_place(
        &mut self,
        here: Option<(SitIx, Term)>,
    ) -> Option<(Term, String, Option<String>)> {
        let (dm, call) = self.warning_dm()?;
        let key = (dm, here.map(|(s, _)| s));
        if self.unbound_next_warned.contains(&key) {
            return None;
        }
        self.unbound_next_warned.push(key);
        let arc = match self.chose {
            Some((s, Some(a))) if Some(s) == here.map(|(s, _)| s) => format!("arc {}'s ", a + 1),
            _ => String::new(),
        };
        let location = here.and_then(|(s, _)| self.program.location(dm, s));
        Some((call, arc, location))
    }

    /// The warning of an arc whose next situation has no value (docs/guide/language.md, "Next"),
    /// the first time its situation takes one: the running DM ends there,
    /// without a final situation, as the original's ends (its unbound next
    /// situation unifies with the `empty` that ends a DM); a caller takes
    /// its first exit arc. Located at the situation, the arc named. Cold.
    #[cold]
    pub(super) fn warn_unbound_next(&mut self, next: Term, here: Option<(SitIx, Term)>) {
        let Some((call, arc, location)) = self.next_warning_place(here) else {
            return;
        };
        let id = here.map_or(Term::atom(atoms::NONE), |(_, id)| id);
        let [call, id, next] = writeq_renumbered(&self.store, [call, id, next]);
        let whom = if self.frames.len() + self.lazy.len() > 1 {
            "its caller takes its first exit arc"
        } else {
            "the task ends"
        };
        self.warnings.push(super::RunWarning {
            message: format!(
                "{arc}next situation `{next}` has no value: the DM ends here without a final situation, as the original SitLog ends it (an unbound next situation is its `empty`), and {whom}; a variable the arc meant to bind? (said once per situation)"
            ),
            dm: call,
            situation: id,
            location,
        });
    }

    /// The warning of an arc whose next situation is `empty` in an
    /// embedded DM (docs/guide/language.md, "Next"), the first time its
    /// situation takes one: the DM ends there without a final situation,
    /// as the original's, and its caller takes its first exit arc. In
    /// the main DM, where it ends the task, nothing is said. Cold.
    #[cold]
    pub(super) fn warn_empty_next(&mut self, here: Option<(SitIx, Term)>) {
        if self.frames.len() + self.lazy.len() <= 1 {
            return;
        }
        let Some((call, arc, location)) = self.next_warning_place(here) else {
            return;
        };
        let id = here.map_or(Term::atom(atoms::NONE), |(_, id)| id);
        let [call, id] = writeq_renumbered(&self.store, [call, id]);
        self.warnings.push(super::RunWarning {
            message: format!(
                "{arc}next situation `empty` ends the DM here without a final situation, as the original SitLog ends it, and its caller takes its first exit arc, whatever its expectation (said once per situation)"
            ),
            dm: call,
            situation: id,
            location,
        });
    }

    pub(super) fn perform(
        &mut self,
        action: Term,
        actions: &mut dyn Actions,
        here: Option<(SitIx, Term)>,
        arc: Option<usize>,
    ) -> Result<(), RunError> {
        self.perform_raw(action, actions)
            .map_err(|e| self.err(format!("action failed: {e}"), here, arc))
    }

    /// [`Machine::perform`] without its error: the effector's message
    /// (`Cx::nat_perform` makes the error once the native frames are
    /// handed over).
    pub(super) fn perform_raw(
        &mut self,
        action: Term,
        actions: &mut dyn Actions,
    ) -> Result<(), String> {
        let a = self.store.deref(action);
        if a == Term::atom(atoms::EMPTY) && actions.ignores(super::ActionShape::EMPTY) {
            return Ok(());
        }
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
                result = super::io::perform_one(actions, &mut self.store, head);
                if result.is_err() {
                    break;
                }
                rest = tail;
            }
            result
        } else {
            super::io::perform_one(actions, &mut self.store, a)
        };
        result
    }

    /// Evaluates `diag_mod` (read-only variables) and unifies it with the DM id (D-20, E9).
    pub(super) fn bind_diag_mod(
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

    /// A history entry of the running situation `situation`: counted, and
    /// kept (when the history is kept or observed) in the innermost history
    /// level native code has open ([`Machine::levels`]), else in the top
    /// frame's history.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn record(
        &mut self,
        situation: Term,
        expectation: Term,
        action: Term,
        next: Option<Term>,
        pipe: Term,
        observer: &mut Option<&mut dyn Observer>,
    ) {
        if observer.is_none() && !self.options.keep_history {
            // Nothing sees the entry: count it (and forget the unmatched
            // inputs, as reporting them to no observer does).
            self.unmatched.clear();
            self.transitions += 1;
            return;
        }
        self.report_unmatched(observer);
        self.transitions += 1;
        if let Some(level) = self.levels.back_mut() {
            // A DM native code runs on its own stack (no observer then).
            let entry = Entry {
                dm: level.dm_id,
                situation,
                expectation,
                action,
            };
            level.history.push(Item::Entry(entry));
            return;
        }
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
}

/// `terms` as `writeq` writes them, their variables numbered in order of
/// first appearance across all of them (`_G0`, `_G1`, ..): the same text
/// whichever store holds them (a [`RunWarning`](super::RunWarning)'s).
fn writeq_renumbered<const N: usize>(store: &crate::Store, terms: [Term; N]) -> [String; N] {
    use crate::term::Value;
    use sitlog_syntax::write::{TermSource, VarLabel, View};
    struct Renumbered<'a> {
        store: &'a crate::Store,
        order: Vec<crate::term::Var>,
    }
    impl TermSource for Renumbered<'_> {
        type Ref = Term;
        fn view(&self, t: Term) -> View<'_, Term> {
            match self.store.value(t) {
                Value::Var(v) => {
                    let n = self
                        .order
                        .iter()
                        .position(|&w| w == v)
                        .unwrap_or(self.order.len());
                    View::Var(VarLabel::Numbered(n as u64))
                }
                _ => self.store.view(t),
            }
        }
    }
    let mut order = Vec::new();
    for &t in &terms {
        for v in store.term_vars(t) {
            if let Value::Var(var) = store.value(v) {
                if !order.contains(&var) {
                    order.push(var);
                }
            }
        }
    }
    let source = Renumbered { store, order };
    terms.map(|t| sitlog_syntax::write::writeq(&source, t))
}
