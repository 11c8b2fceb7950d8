//! A recursive situation's call that native code evaluated itself (issue
//! 37): its `embedded_dm` evaluated once, read-only, where the native
//! frames are ([`Cx::nat_embedded_dm`]), each argument converted to the
//! callee's frame type, the callee pushed on the native stack with the
//! waiting variant holding the evaluated call. Where that call must become
//! the machine's, it is the call made, never the template's evaluated
//! again (a global the callee set since, an `apply` with side effects
//! called twice would be a silent wrong answer):
//! - an argument that does not convert, or an evaluation that failed:
//!   [`Cx::call_held`] (after the hand-over) reports the error as the
//!   machine's call would, or gives the call to the machine's visit from
//!   the template, which calls it instead of evaluating
//!   (`Machine::held_call`, taken by [`Machine::held_or_eval`]);
//! - the waiting frame made the machine's ([`Cx::wait_held`]): the callee's
//!   frame pushed with that call.
//!
//! In both the template instance's own call variables (an output
//! argument, `_` in `ask(Q, K, get(vocab, _), _, _)`, which the callee's
//! `diag_mod` binds for the exit arcs) are linked with the evaluated call:
//! each argument of the template's `embedded_dm` that is a variable is
//! unified with the call's argument (evaluating a variable gives it).
//!
//! Invariant: the call the machine pushes is the term native code
//! evaluated, and an argument that is a variable of the template's call is
//! the instance's variable, as when the machine evaluates the call itself
//! (a link that fails is the run's error naming the call, never a silent
//! stop: not reachable, see `Machine::held_or_eval`).

use super::native_stack::NatFrames;
use super::outcome::RunError;
use super::program::TypedRun;
use super::program::{Cx, DmProgram, Step};
use super::situation::SitIx;
use super::state::Machine;
use super::{FromIdParts, IdArg};
use crate::eval::EvalError;
use crate::term::Term;

impl<P: DmProgram> Machine<'_, P> {
    /// The call of a recursive situation whose template instance's
    /// `embedded_dm` is `e`: the one native code evaluated and held
    /// ([`Cx::call_held`], [`Cx::wait_held`]), linked with the instance's
    /// variables (module doc), else `e` evaluated read-only.
    pub(super) fn held_or_eval(
        &mut self,
        e: Term,
        here: Option<(SitIx, Term)>,
    ) -> Result<Term, RunError> {
        let Some(call) = self.held_call.take() else {
            return self.eval_read_only(e, here);
        };
        let e = self.store.deref(e);
        let call = self.store.deref(call);
        let same = match (self.store.functor(e), self.store.functor(call)) {
            (Some(a), Some(b)) => a == b,
            _ => false,
        };
        if same {
            for k in 0..self.store.args(e).len() {
                let (x, y) = (self.store.args(e)[k], self.store.args(call)[k]);
                if !self.store.is_var(self.store.deref(x)) {
                    continue;
                }
                // Not reachable: `x` is an unbound variable of the
                // template's fresh instance, which the call native code
                // evaluated (from its own values) cannot contain, and an
                // unbound variable unifies with any other term (no occurs
                // check). Were it reached, the arguments linked before
                // would stay bound and the rest not: the run's error, never
                // a silent stop with the instance half linked.
                let linked = self.store.unify(x, y);
                debug_assert!(linked, "a held call's argument did not link");
                if !linked {
                    let message = format!(
                        "the call `{}` native code evaluated does not unify with the \
                         situation's `embedded_dm` `{}` at argument {}",
                        self.store.writeq(call),
                        self.store.writeq(e),
                        k + 1
                    );
                    return Err(self.err(message, here, None));
                }
            }
        }
        Ok(call)
    }
}

impl<P: DmProgram> Cx<'_, '_, P> {
    /// The call native code evaluated (`ev`, [`Cx::nat_embedded_dm`]'s
    /// answer) and its arguments at `paths` (`&[k]`: argument `k`) as
    /// native values of the callee's frame types (`None`: the evaluation
    /// failed, or one does not convert).
    #[inline]
    pub fn call_args<T: FromIdParts>(
        &self,
        ev: &Result<Term, EvalError>,
        paths: &[&[usize]],
    ) -> Option<(Term, T)> {
        let call = *ev.as_ref().ok()?;
        Some((call, T::from_id_parts(&self.m.store, call, paths)?))
    }

    /// [`Cx::call_args`] of the call's first arguments, as many as `T`
    /// has (`(v0, v1)`: arguments 0 and 1).
    #[inline]
    pub fn first_args<T: FromIdParts>(&self, ev: &Result<Term, EvalError>) -> Option<(Term, T)> {
        const FIRST: [&[usize]; 8] = [&[0], &[1], &[2], &[3], &[4], &[5], &[6], &[7]];
        self.call_args(ev, &FIRST)
    }

    /// The callee's frame `callee` of a held call (`held`) put in `call`
    /// for the driver to push; with the history kept its level opened
    /// with that call ([`Cx::open_level`]), the term a frame made the
    /// machine's is checked against.
    #[inline]
    pub fn push_held<F: NatFrames<P>>(
        &mut self,
        run: &TypedRun,
        call: &mut Option<F>,
        held: Term,
        callee: F,
    ) {
        if run.records {
            self.open_level(held);
        }
        *call = Some(callee);
    }

    /// A recursive situation `sit` (id `id`) whose call native code
    /// evaluated (`held`: [`Cx::nat_embedded_dm`]'s answer) but does not
    /// push, after the hand-over and the `count` transitions counted: the
    /// evaluation's error as the machine's call reports it (the culprit
    /// the evaluator blamed), or the visit handed to the machine from the
    /// template with that call, which it calls instead of evaluating the
    /// template's again (module doc).
    #[cold]
    #[inline(never)]
    pub fn call_held(
        &mut self,
        count: u64,
        sit: SitIx,
        id: impl IdArg,
        held: Result<Term, EvalError>,
    ) -> Result<Option<Step>, RunError> {
        let id = id.id_in(&mut self.m.store);
        self.count_transitions(count);
        match held {
            Ok(call) => {
                self.m.held_call = Some(call);
                Ok(Some(self.to_template(sit, id)))
            }
            Err(EvalError { message, culprit }) => {
                let mut e = self.m.err(message, Some((sit, id)), None);
                if let Some(site) = e.site.as_mut() {
                    site.culprit = culprit;
                }
                Err(e)
            }
        }
    }
}

impl<F> super::NatBelow<'_, F> {
    /// [`Cx::call_held`] in a DM without locals, the native frames below
    /// handed over first (the runtime's
    /// [`nat_hand_over`](super::nat_hand_over)): one cold call for a held
    /// call that native code does not push.
    #[cold]
    #[inline(never)]
    pub fn call_held<P: DmProgram>(
        &mut self,
        p: &P,
        cx: &mut Cx<'_, '_, P>,
        count: u64,
        sit: SitIx,
        id: impl IdArg,
        held: Result<Term, EvalError>,
    ) -> Result<Option<Step>, RunError>
    where
        F: NatFrames<P>,
    {
        super::nat_hand_over(p, cx, self)?;
        cx.call_held(count, sit, id, held)
    }
}
