//! An arc's action of effectors performed by native code without handing
//! its frames over (issue 37, `neff18`): [`Cx::nat_perform`],
//! [`Cx::nat_perform_any`] and [`Cx::nat_perform_list`], the code generator's
//! `codegen::native::effect`.
//!
//! An effector ([`Actions::perform`](super::Actions::perform)) is given the
//! store and the action's term and nothing else: it cannot see the DM
//! stack, the frames' locals or the situation entered, and it collects no
//! garbage (the machine collects only between situations, native code
//! handing its frames over first, `Cx::gc_tick`). What reads the machine's
//! frames around an effector is the machine's own: its error report (the
//! running DM's call, the situation's id and its location, from the
//! machine's top frame: the native frames below made machine frames
//! first, `nat_hand_over`) and the history entry (the situation entered
//! with its id). So the hand-over and the entry are made where the run
//! records (the entry first, as before), and elsewhere only where the
//! effector fails, before the error is made; the error is then the one
//! [`Cx::perform`] gives in the situation entered, the transitions native
//! code made before counted (the failing one not, as on the term path).
//!
//! Invariant: the effector is handed what [`Cx::perform`] would hand it
//! ([`Cx::nat_perform_any`]: the action, a proper list element by element;
//! [`Cx::nat_perform`]: the action as it is;
//! [`Cx::nat_perform_list`]: each item, as an element of a list written
//! out), in order, the first error ending it, and the error is
//! [`Cx::perform`]'s in the situation entered.

use super::native_stack::{nat_hand_over, NatBelow, NatFrames};
use super::outcome::RunError;
use super::program::{Cx, DmProgram, TypedRun};
use super::situation::SitIx;
use super::IdArg;
use crate::term::Term;
use sitlog_syntax::atoms;

impl<P: DmProgram> Cx<'_, '_, P> {
    /// Performs `action`, an arc's action evaluated (what [`Cx::perform`]
    /// does with it: `empty` skipped where the actions ignore it, a proper
    /// list element by element, anything else handed to the effector as
    /// it is), for arc `arc` of situation `sit` (its id `id`, built only
    /// where it is entered): where the run records
    /// ([`TypedRun::records`]), the native frames below handed over and
    /// the situation entered first ([`Cx::enter_counted`] of `count`),
    /// then [`Cx::perform`]; else without either, and where the effector
    /// fails, both made then and the error [`Cx::perform`]'s.
    #[inline]
    pub fn nat_perform_any<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        count: &mut u64,
        (sit, arc): (SitIx, usize),
        id: impl IdArg,
        action: Term,
        run: &TypedRun,
    ) -> Result<(), RunError> {
        if run.records {
            self.nat_enter_first(stack, count, sit, id)?;
            return self.perform(action, Some(arc));
        }
        match self.perform_unentered(action) {
            Ok(()) => Ok(()),
            Err(e) => Err(self.nat_action_failed(stack, count, (sit, arc), id, e)),
        }
    }

    /// [`Cx::nat_perform_any`] of an action the code generator knows
    /// [`Cx::perform`] hands to the effector as it is (an atom other than
    /// `empty`, a compound that is not a list): handed to it, nothing
    /// looked at first.
    #[inline]
    pub fn nat_perform<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        count: &mut u64,
        (sit, arc): (SitIx, usize),
        id: impl IdArg,
        action: Term,
        run: &TypedRun,
    ) -> Result<(), RunError> {
        self.nat_perform_items(stack, count, (sit, arc), id, &[action], run.records)
    }

    /// What `Machine::perform` does with `action`, the machine not entered:
    /// the effector's message where it fails.
    fn perform_unentered(&mut self, action: Term) -> Result<(), String> {
        let store = &mut self.m.store;
        let a = store.deref(action);
        if a == Term::EMPTY && self.actions.ignores_empty() {
            return Ok(());
        }
        let is_list = store.functor(a).is_some_and(|f| f.0 == atoms::DOT) && {
            let mut it = store.list_iter(a);
            it.by_ref().for_each(drop);
            it.tail() == Term::NIL
        };
        if !is_list {
            return self.actions.perform(store, a);
        }
        // Walked by position: an action may bind variables (and so grow
        // the store) while the list is performed.
        let mut rest = a;
        while let Some(&[head, tail]) = store.compound_args(rest, atoms::DOT, 2) {
            self.actions.perform(store, head)?;
            rest = tail;
        }
        Ok(())
    }

    /// [`Cx::nat_perform`] of the elements of an action list, one by one
    /// (what [`Cx::perform`] does with a proper list); the list itself, as
    /// the history records it, built only where the run records (else `[]`).
    #[inline]
    pub fn nat_perform_list<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        count: &mut u64,
        (sit, arc): (SitIx, usize),
        id: impl IdArg,
        items: &[Term],
        run: &TypedRun,
    ) -> Result<Term, RunError> {
        self.nat_perform_items(stack, count, (sit, arc), id, items, run.records)?;
        Ok(if run.records {
            self.m.store.list(items)
        } else {
            Term::NIL
        })
    }

    #[inline]
    fn nat_perform_items<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        count: &mut u64,
        (sit, arc): (SitIx, usize),
        id: impl IdArg,
        items: &[Term],
        records: bool,
    ) -> Result<(), RunError> {
        if records {
            self.nat_enter_first(stack, count, sit, id)?;
            return self.perform_each(items, Some(arc));
        }
        for &x in items {
            if let Err(e) = self.actions.perform(&mut self.m.store, x) {
                return Err(self.nat_action_failed(stack, count, (sit, arc), id, e));
            }
        }
        Ok(())
    }

    /// The frames below handed over, the situation entered with its id
    /// (the `count` transitions before it counted): before the action is
    /// performed where the run records, else where the effector fails.
    #[cold]
    #[inline(never)]
    fn nat_enter_first<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        count: &mut u64,
        sit: SitIx,
        id: impl IdArg,
    ) -> Result<(), RunError> {
        let p = self.m.program;
        nat_hand_over(p, self, stack)?;
        let id = id.id_in(&mut self.m.store);
        self.enter_counted(count, sit, id);
        Ok(())
    }

    /// The effector's error `e`, not recorded: the frames below handed
    /// over, the situation entered with its id (the `count` transitions
    /// before it counted), then [`Cx::action_failed`].
    #[cold]
    #[inline(never)]
    fn nat_action_failed<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        count: &mut u64,
        (sit, arc): (SitIx, usize),
        id: impl IdArg,
        e: String,
    ) -> RunError {
        if let Err(h) = self.nat_enter_first(stack, count, sit, id) {
            return h;
        }
        self.action_failed(e, Some(arc))
    }
}
