//! An arc's action performed by native code without handing its frames
//! over first (issue 37): [`Cx::nat_perform`], the one runtime entry for
//! it, whether native code entered the situation before the action or not
//! (`neff18`, `nfun18`, made one by `nuni19`); the code generator's
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
//! with its id). So the hand-over is made only where the effector fails,
//! before the error is made, which is then the one [`Cx::perform`] gives
//! in the situation entered, the transitions native code made before
//! counted (the failing one not, as on the term path).
//!
//! Two cases, one call, the difference given as data ([`NatEntry`]):
//! - *not entered yet* ([`Due`]: an action built of values, nothing
//!   evaluated before it in the arc; `neff18`): the situation is entered
//!   (its id built, the transitions before it counted) where the run
//!   records, the frames handed over first, before the action (the entry
//!   the history keeps, as before); else only where the effector fails,
//!   both made then, before the error. What this protects: the error's
//!   site (the situation and its id) and the recorded entry.
//! - *entered* (`Option<usize>`, the arc's index as errors name it: an
//!   evaluation in the arc came first and entered the situation, or the
//!   DM's own hand-over was made; `nfun18`): only the hand-over is left,
//!   made where the effector fails (nothing where it was made before: the
//!   stack below is then empty). What this protects: the error's DM (the
//!   machine's top frame).
//!
//! The action, also as data ([`NatAction`]): a term the code generator
//! knows [`Cx::perform`] hands to the effector as it is (an atom other
//! than `empty`, a compound that is not a list), handed to it with
//! nothing looked at; [`AnyShape`], a term of any shape, what
//! [`Cx::perform`] does with it (`empty` skipped where the actions ignore
//! it, a proper list element by element); the items of a list written
//! out (`&[Term; N]`), one by one, the list built for the history only
//! where the run records; a compound of native values as its pattern and
//! holes ([`Fill`]), offered to the effector unfilled where nothing records
//! it and its holes are atoms or numbers (`Actions::perform_filled`: test
//! mode writes the line from the pattern), else filled.
//!
//! An action whose functor the effector ignores whatever its arguments
//! ([`Actions::ignores`](super::Actions::ignores): test mode's actions
//! neither shown nor declared) is not built nor handed over where the run
//! does not record ([`Cx::ignores_action`], asked by the generated code
//! first): performing it would do nothing, and nothing reads its term.
//!
//! Invariant: the effector is handed what [`Cx::perform`] would hand it,
//! in order, the first error ending it (but an action it ignores, where
//! the run does not record), and the error is
//! [`Cx::perform`]'s in the situation entered; the situation is entered
//! with its id before the action where the run records.

use super::native_stack::{nat_hand_over, NatBelow, NatFrames};
use super::outcome::RunError;
use super::program::{Cx, DmProgram, TypedRun};
use super::situation::SitIx;
use super::{Fill, Holes, IdArg};
use crate::term::Term;
use crate::Store;

/// Where the situation of an arc whose action native code performs
/// ([`Cx::nat_perform`]) stands (module doc): entered already
/// (`Option<usize>`, the arc's index as errors name it), or [`Due`].
pub trait NatEntry {
    /// The arc's index (0-based) as an error names it.
    fn arc(&self) -> Option<usize>;

    /// The situation entered where it is not yet: the native frames below
    /// handed over, the transitions before it counted, its id built.
    /// Nothing where it is entered.
    fn enter<P: DmProgram, F: NatFrames<P>>(
        self,
        cx: &mut Cx<'_, '_, P>,
        stack: &mut NatBelow<'_, F>,
    ) -> Result<(), RunError>;
}

/// Entered: the arc's index.
impl NatEntry for Option<usize> {
    #[inline]
    fn arc(&self) -> Option<usize> {
        *self
    }

    #[inline]
    fn enter<P: DmProgram, F: NatFrames<P>>(
        self,
        _: &mut Cx<'_, '_, P>,
        _: &mut NatBelow<'_, F>,
    ) -> Result<(), RunError> {
        Ok(())
    }
}

/// A situation native code has not entered yet: the transitions it made
/// since it last counted, the situation and the arc (0-based), and the
/// situation's id (an atom, a term or a [`Fill`](super::Fill), built only
/// where it is entered).
pub struct Due<'c, I>(pub &'c mut u64, pub (SitIx, usize), pub I);

impl<I: IdArg> NatEntry for Due<'_, I> {
    #[inline]
    fn arc(&self) -> Option<usize> {
        Some(self.1 .1)
    }

    #[cold]
    #[inline(never)]
    fn enter<P: DmProgram, F: NatFrames<P>>(
        self,
        cx: &mut Cx<'_, '_, P>,
        stack: &mut NatBelow<'_, F>,
    ) -> Result<(), RunError> {
        let Due(count, (sit, _), id) = self;
        let p = cx.m.program;
        nat_hand_over(p, cx, stack)?;
        let id = id.id_in(&mut cx.m.store);
        cx.enter_counted(count, sit, id);
        Ok(())
    }
}

/// An arc's action as native code hands it to [`Cx::nat_perform`] (module
/// doc): a [`Term`] handed to the effector as it is, an [`AnyShape`], or
/// the items of a list written out.
pub trait NatAction: Copy {
    /// Hands the action to the effector as [`Cx::perform`] does: the
    /// effector's message where it fails.
    fn perform_in<P: DmProgram>(self, cx: &mut Cx<'_, '_, P>) -> Result<(), String>;

    /// The action as the history records it where `records`, else
    /// anything (the history does not read it).
    fn recorded(self, store: &mut Store, records: bool) -> Term;

    /// [`NatAction::perform_in`], then [`NatAction::recorded`]: one call
    /// where the two share work ([`Fill`]).
    #[inline]
    fn perform_recorded<P: DmProgram>(
        self,
        cx: &mut Cx<'_, '_, P>,
        records: bool,
    ) -> Result<Term, String> {
        self.perform_in(cx)?;
        Ok(self.recorded(&mut cx.m.store, records))
    }
}

/// A compound action (not a list) of native values given as its pattern
/// and holes (`Fill(p.k[3], (&r4,))`, `Cx::fill`'s arguments): where the
/// run does not record, every hole is an atom or a number and the pattern
/// is marked (`mark_pattern`: a program's constant), offered to
/// the effector unfilled ([`Actions::perform_filled`](super::Actions::perform_filled):
/// test mode writes its line from the pattern, no term built); else, or
/// where the effector declines, filled and handed to it as it is (what
/// [`Cx::perform`] does with a compound that is not a list).
impl<H: Holes> NatAction for Fill<H> {
    #[inline]
    fn perform_in<P: DmProgram>(self, cx: &mut Cx<'_, '_, P>) -> Result<(), String> {
        self.perform_recorded(cx, false).map(|_| ())
    }

    #[inline]
    fn recorded(self, store: &mut Store, _: bool) -> Term {
        self.id_in(store)
    }

    fn perform_recorded<P: DmProgram>(
        self,
        cx: &mut Cx<'_, '_, P>,
        records: bool,
    ) -> Result<Term, String> {
        let Fill(pattern, holes) = self;
        let store = &mut cx.m.store;
        let actions = &mut *cx.actions;
        let mut done = None;
        let action = holes.with_terms(store, |store, ts| {
            if ts.len() <= 8
                && !records
                && ts.iter().all(|&t| crate::sentence::atomic(store, t))
                && store.is_holed(pattern)
            {
                done = actions.perform_filled(store, pattern, ts);
            }
            match done {
                Some(_) => Term::EMPTY,
                None => super::cx::fill_in(store, pattern, ts),
            }
        });
        if let Some(done) = done {
            return done.map(|()| Term::EMPTY);
        }
        super::io::perform_one(&mut *cx.actions, &mut cx.m.store, action)?;
        Ok(action)
    }
}

/// An action [`Cx::perform`] hands to the effector as it is (an atom
/// other than `empty`, a compound that is not a list): the code generator
/// knows its shape.
impl NatAction for Term {
    #[inline]
    fn perform_in<P: DmProgram>(self, cx: &mut Cx<'_, '_, P>) -> Result<(), String> {
        super::io::perform_one(&mut *cx.actions, &mut cx.m.store, self)
    }

    #[inline]
    fn recorded(self, _: &mut Store, _: bool) -> Term {
        self
    }
}

/// An action of any shape (an evaluated term): what [`Cx::perform`] does
/// with it, `empty` skipped where the actions ignore it, a proper list
/// element by element.
#[derive(Clone, Copy)]
pub struct AnyShape(pub Term);

impl NatAction for AnyShape {
    #[inline]
    fn perform_in<P: DmProgram>(self, cx: &mut Cx<'_, '_, P>) -> Result<(), String> {
        cx.m.perform_raw(self.0, &mut *cx.actions)
    }

    #[inline]
    fn recorded(self, _: &mut Store, _: bool) -> Term {
        self.0
    }
}

/// The items of a list action written out: each handed to the effector
/// (what [`Cx::perform`] does with a proper list), the list built only
/// where the history records it (else `[]`).
impl<const N: usize> NatAction for &[Term; N] {
    #[inline]
    fn perform_in<P: DmProgram>(self, cx: &mut Cx<'_, '_, P>) -> Result<(), String> {
        self.iter()
            .try_for_each(|&x| super::io::perform_one(&mut *cx.actions, &mut cx.m.store, x))
    }

    #[inline]
    fn recorded(self, store: &mut Store, records: bool) -> Term {
        if records {
            store.list(self)
        } else {
            Term::NIL
        }
    }
}

impl<P: DmProgram> Cx<'_, '_, P> {
    /// Whether the run's effector ignores every action `name(..)` of
    /// `arity` arguments ([`Actions::ignores`](super::Actions::ignores)):
    /// native code then neither builds nor performs such an action where
    /// the run does not record (what [`Cx::nat_perform`] would hand it does
    /// nothing, and the history does not read it).
    #[inline]
    pub fn ignores_action(&self, name: sitlog_syntax::Atom, arity: usize) -> bool {
        self.actions.ignores(super::ActionShape::Named(name, arity))
    }

    /// Performs an arc's action `action` by native code (module doc): the
    /// situation entered first where it is not (`at`, [`Due`]) and the run
    /// records, then the action handed to the effector; where the effector
    /// fails, the situation entered (where it was not) and the native
    /// frames below handed over, then [`Cx::perform`]'s error. The action
    /// as the history records it ([`NatAction::recorded`]).
    #[inline]
    pub fn nat_perform<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        at: impl NatEntry,
        action: impl NatAction,
        run: &TypedRun,
    ) -> Result<Term, RunError> {
        if run.records {
            // Entered first (the entry the history keeps): entered from
            // then on, the arc's index its entry.
            let arc = at.arc();
            at.enter(self, stack)?;
            return self.nat_perform_at(stack, arc, action, true);
        }
        self.nat_perform_at(stack, at, action, false)
    }

    #[inline]
    fn nat_perform_at<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        at: impl NatEntry,
        action: impl NatAction,
        records: bool,
    ) -> Result<Term, RunError> {
        match action.perform_recorded(self, records) {
            Ok(t) => Ok(t),
            Err(e) => Err(self.nat_action_failed(stack, at, e)),
        }
    }

    /// The effector's error `e`: the situation entered where it was not
    /// (`at`), the frames below handed over, then [`Cx::action_failed`].
    #[cold]
    #[inline(never)]
    fn nat_action_failed<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        at: impl NatEntry,
        e: String,
    ) -> RunError {
        let p = self.m.program;
        let arc = at.arc();
        if let Err(h) = at
            .enter(self, stack)
            .and_then(|()| nat_hand_over(p, self, stack))
        {
            return h;
        }
        self.action_failed(e, arc)
    }
}
