//! Steps generated code writes at many sites (issue 37), each one call
//! here instead of the same few lines at every site: the test of whether
//! `empty` is performed, the push of a callee's frame on the native stack
//! with or without a history level, an exit arc's entry and end where the
//! run records (its terms given lazily: [`Of`], a `Fill`, `&value`), a
//! `ground` action value performed. Each is inlined over the calls the
//! sites made before (the cold paths are the same out-of-line calls), so
//! behaviour stays that of the inline code; only the source is shorter.
//!
//! Invariant: each helper does exactly what the lines it replaces did, in
//! the same order (terms made in the store in the same order, the same
//! transitions counted).

use super::cx::IdArg;
use super::holes::Holes;
use super::native_stack::{NatBelow, NatFrames};
use super::outcome::RunError;
use super::program::{Cx, DmProgram, TypedRun};
use super::situation::SitIx;
use crate::native::Val;
use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::Atom;

/// A compound of native values named `name` ([`Cx::build_of`]'s
/// arguments, the values a tuple of references: [`Holes`]) built only
/// where a call needs it: an exit arc's expectation given to
/// [`TypedRun::entry`], built only when the run records.
#[derive(Clone, Copy)]
pub struct Of<H>(pub Atom, pub H);

impl<H: Holes> IdArg for Of<H> {
    #[inline]
    fn id_in(self, store: &mut Store) -> Term {
        let name = self.0;
        self.1
            .with_terms(store, |store, ts| crate::native::compound(store, name, ts))
    }
}

/// A native value (an exit arc's action's value, `&act0`) made a term only
/// where a call needs it ([`TypedRun::entry`]).
impl<T: crate::native::Native> IdArg for &T {
    #[inline]
    fn id_in(self, store: &mut Store) -> Term {
        self.to_term(store)
    }
}

impl TypedRun {
    /// An arc whose action is `empty`, in a DM without locals: where the
    /// run records or the actions do not ignore `empty`,
    /// [`Cx::nat_empty`] (`empty` performed, the situation `sit` entered
    /// by arc `arc`, its id `pattern` filled with `holes`).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn empty<P: DmProgram, F: NatFrames<P>>(
        &self,
        cx: &mut Cx<'_, '_, P>,
        stack: &mut NatBelow<'_, F>,
        count: &mut u64,
        sit: SitIx,
        arc: usize,
        pattern: impl IdArg,
        holes: impl Holes,
    ) -> Result<(), RunError> {
        if self.records || !self.quiet_empty {
            cx.nat_empty(stack, count, sit, arc, pattern, holes)?;
        }
        Ok(())
    }

    /// [`TypedRun::empty`] of an exit arc, whose entry is made after it
    /// where the run records ([`TypedRun::entry`]): only where the
    /// actions do not ignore `empty`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn exit_empty<P: DmProgram, F: NatFrames<P>>(
        &self,
        cx: &mut Cx<'_, '_, P>,
        stack: &mut NatBelow<'_, F>,
        count: &mut u64,
        sit: SitIx,
        arc: usize,
        pattern: impl IdArg,
        holes: impl Holes,
    ) -> Result<(), RunError> {
        if !self.quiet_empty {
            cx.nat_empty(stack, count, sit, arc, pattern, holes)?;
        }
        Ok(())
    }

    /// An exit arc's entry: where the run records, its expectation and
    /// action (`exp`, made terms in that order), situation `sit` entered
    /// with its id `id` ([`Cx::enter_counted`]), and the pair given back
    /// for the record after the next situation; else the transition
    /// counted and a pair nothing reads.
    #[inline(always)]
    pub fn entry<P: DmProgram>(
        &self,
        cx: &mut Cx<'_, '_, P>,
        count: &mut u64,
        sit: SitIx,
        id: impl IdArg,
        (exp, act): (impl IdArg, impl IdArg),
    ) -> (Term, Term) {
        if self.recorded() {
            let exp = exp.id_in(cx.store());
            let act = act.id_in(cx.store());
            let id = id.id_in(cx.store());
            cx.enter_counted(count, sit, id);
            (exp, act)
        } else {
            *count += 1;
            (Term::NIL, Term::NIL)
        }
    }

    /// An exit arc's end once its next situation `next` is made: where
    /// the run records, its expectation and action (`exp`, made terms in
    /// that order), then [`Cx::enter_next`] (the id `id` filled, the
    /// entry, the record with the next situation's id); else one more
    /// transition counted ([`TypedRun::tally`] and the entry in one test).
    #[inline(always)]
    pub fn exit_end<P: DmProgram>(
        &self,
        cx: &mut Cx<'_, '_, P>,
        count: &mut u64,
        sit: SitIx,
        id: impl IdArg,
        (exp, act): (impl IdArg, impl IdArg),
        next: &dyn super::NatAt<P>,
    ) {
        if self.recorded() {
            let exp = exp.id_in(cx.store());
            let act = act.id_in(cx.store());
            cx.enter_next(count, sit, id, exp, act, next);
        } else {
            *count += 1;
        }
    }
}

impl<F> NatBelow<'_, F> {
    /// A callee's frame (`wrap(callee())`, `wrap` the driver's frame
    /// variant of the callee's DM) pushed for the driver (`call`) within
    /// the depth limit, by a caller whose exit arcs record natively:
    /// without a history where none is kept or observed, in a history
    /// level of its own ([`Cx::push_level`]) where it is kept and nothing
    /// observes (`run.nests`); `false` where it is not pushed (the caller
    /// hands the visit to the machine).
    #[inline(always)]
    pub fn push<P: DmProgram, T>(
        &self,
        p: &P,
        cx: &mut Cx<'_, '_, P>,
        run: &TypedRun,
        call: &mut Option<F>,
        wrap: impl FnOnce(T) -> F,
        callee: impl FnOnce() -> T,
    ) -> bool
    where
        F: NatFrames<P>,
    {
        if !run.records && self.has_room(cx) {
            *call = Some(wrap(callee()));
            true
        } else if run.nests && self.has_room(cx) {
            cx.push_level(p, call, wrap(callee()));
            true
        } else {
            false
        }
    }

    /// An exit arc's action whose value `v` is a `ground` (`set(g, W)`,
    /// `W` a parameter's value), in a DM without locals: a number or
    /// `empty` skipped where the run's actions ignore it; a number or an
    /// atom other than `empty` handed to the effector without handing the
    /// frames over ([`Cx::perform_value`]; where it fails, the frames
    /// handed over, situation `sit` entered with its id `id` and the
    /// effector's error); anything else performed by the machine
    /// ([`Cx::perform`], the frames handed over and the situation entered
    /// first).
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub fn perform<P: DmProgram>(
        &mut self,
        cx: &mut Cx<'_, '_, P>,
        run: &TypedRun,
        count: &mut u64,
        sit: SitIx,
        arc: usize,
        id: impl IdArg,
        v: &Val,
    ) -> Result<(), RunError>
    where
        F: NatFrames<P>,
    {
        let as_value = match v {
            Val::Int(_) | Val::Float(_) => {
                if run.quiet_numbers {
                    return Ok(());
                }
                true
            }
            Val::Sym(s) if run.quiet_empty && *s == crate::atoms::EMPTY => return Ok(()),
            Val::Sym(s) => *s != crate::atoms::EMPTY,
            _ => false,
        };
        let p = cx.m.program;
        if as_value {
            let t = cx.term(v);
            if let Err(e) = cx.perform_value(t) {
                super::nat_hand_over(p, cx, self)?;
                let id = id.id_in(cx.store());
                cx.enter_counted(count, sit, id);
                return Err(cx.action_failed(e, Some(arc)));
            }
            return Ok(());
        }
        super::nat_hand_over(p, cx, self)?;
        let id = id.id_in(cx.store());
        cx.enter_counted(count, sit, id);
        let t = cx.term(v);
        cx.perform(t, Some(arc))
    }
}
