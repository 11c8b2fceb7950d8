//! The world side of the machine: what it asks ([`Perception`]) and what
//! it has done ([`Actions`]). A perception may also hand over what it read
//! with its wrapper not built ([`Percept`], [`Perception::perceive_percept`]);
//! every such percept means exactly the term [`Percept::into_perceived`]
//! builds, so matching it in place (`Machine::perceive_kept`) agrees with
//! matching that term.

use crate::store::Store;
use crate::term::Term;

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

/// What a perception perceived, as [`Perception::perceive_percept`] hands
/// it over: a [`Perceived`], or an input wrapped by a functor of one
/// argument (`said(Input)` for a `listening` situation, D-14) with the
/// wrapper not built, so that the machine can match the input against
/// each expectation `said(..)` in place, no compound made for an input
/// that meets one. It means the term [`Percept::into_perceived`] builds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Percept {
    /// [`Perceived::Input`], [`Perceived::EndOfInput`] or [`Perceived::Again`].
    Whole(Perceived),
    /// The input `name(arg)`, not built.
    Wrapped(sitlog_syntax::Atom, Term),
}

impl Percept {
    /// The [`Perceived`] this percept means: `name(arg)` built for a
    /// wrapped input.
    pub fn into_perceived(self, store: &mut Store) -> Perceived {
        match self {
            Percept::Whole(p) => p,
            Percept::Wrapped(name, arg) => Perceived::Input(store.compound(name, &[arg])),
        }
    }
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

    /// [`Perception::perceive`], an input wrapped by a functor of one
    /// argument (`said(X)`) possibly handed over unbuilt
    /// ([`Percept::Wrapped`]); it must mean (by
    /// [`Percept::into_perceived`]) exactly what `perceive` would have
    /// given, with the same effects (the input read, echoed). The
    /// default calls `perceive` ([`Percept::Whole`]), always correct.
    /// Asked where compiled code perceives with its frames kept
    /// (`Machine::perceive_kept`), which matches a wrapped input against
    /// the expectations in place. Wrappers that only forward `perceive`
    /// may forward it too.
    fn perceive_percept(
        &mut self,
        store: &mut Store,
        situation_type: Term,
        expectations: &[Term],
    ) -> Result<Percept, String> {
        self.perceive(store, situation_type, expectations)
            .map(Percept::Whole)
    }

    /// Where the next [`Perception::perceive`] is asked for: the running
    /// DM's call and the situation's id (for a prompt that names them).
    /// Called by the machine just before it. Does nothing unless overridden.
    fn waiting_at(&mut self, store: &Store, dm: Term, situation: Term) {
        let _ = (store, dm, situation);
    }

    /// Whether [`Perception::waiting_at`] uses what it is told (the running
    /// DM's call, for a prompt that names it). `true`, the default, is
    /// always correct; `false` (a perception whose `waiting_at` does
    /// nothing) lets compiled code perceive without first making its
    /// native frames the machine's (`Cx::choose_kept`). Wrappers forward it.
    fn uses_waiting_at(&self) -> bool {
        true
    }

    /// Whether an input that meets no expectation is news to the user:
    /// typed or scripted input (test mode), where it is a misspelt
    /// expectation or script line, and the machine warns the first time a
    /// situation reads one (the original prints `No satisfied expected
    /// intention!`); `false` (the default) for a robot's senses, which
    /// perceive what they perceive. Wrappers forward it.
    fn unmatched_is_news(&self) -> bool {
        false
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

    /// Whether performing any action of shape `shape` does nothing (and
    /// succeeds), always, whatever its arguments are (bound or not). One
    /// question the machine and compiled code ask of three shapes:
    ///
    /// - [`ActionShape::Number`]: typed code skips the calls for actions
    ///   it knows are numbers (an `inc` in an action list);
    /// - [`ActionShape::EMPTY`] (the atom `empty`, the action of an arc
    ///   that does nothing): the machine and compiled code do not call
    ///   [`Actions::perform`] with it;
    /// - [`ActionShape::Named`]`(name, arity)` (`0`: the atom `name`):
    ///   compiled code neither builds nor hands over such an action where
    ///   nothing records it (`Cx::ignores_action`).
    ///
    /// `false`, the default, is always a correct answer.
    fn ignores(&self, shape: ActionShape) -> bool {
        let _ = shape;
        false
    }

    /// Performs the action `pattern` filled with `holes` without the
    /// term built, where the effector can: `pattern` a program's constant
    /// with `'$hole'(i)` where `holes[i]` goes (`Cx::fill`'s, marked as
    /// it was read: `machine::cx::mark_pattern`), every hole
    /// an atom or a number ([`crate::sentence::atomic`]), the term filled
    /// a compound that is not a list. `None`: not performed (the caller
    /// then builds the term and calls [`Actions::perform`]); else what
    /// `perform` of the filled term does, the same effects in the same
    /// order (test mode writes the same line,
    /// [`crate::sentence::Holed`]). Asked by native code where nothing
    /// records the action. `None`, the default, is always a correct
    /// answer.
    fn perform_filled(
        &mut self,
        store: &mut Store,
        pattern: Term,
        holes: &[Term],
    ) -> Option<Result<(), String>> {
        let _ = (store, pattern, holes);
        None
    }
}

/// The shape of actions [`Actions::ignores`] is asked about: every
/// number, or every action `name(..)` of `arity` arguments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ActionShape {
    /// Any number.
    Number,
    /// Any action `name(A1, .., An)`, `n` = the arity (`0`: the atom).
    Named(sitlog_syntax::Atom, usize),
}

impl ActionShape {
    /// The atom `empty`, the action of an arc that does nothing.
    pub const EMPTY: ActionShape = ActionShape::Named(sitlog_syntax::atoms::EMPTY, 0);
}

/// Hands one action (an element of an action list, or the action) to the
/// effector, as every way the machine and native code perform one does,
/// except an unbound action once the evaluator has given a `get`, `set`
/// or `inc` of a variable neither local nor global an unbound value
/// ([`Store::note_undefined`]): the original SitLog goes on with that
/// value where it is data, and stops where it is performed (Prolog's
/// instantiation error in `=..`), so the run stops there too (`get(battery,
/// B)` as an element of an action list). Otherwise as before: an unbound
/// action is the effector's to judge.
#[inline]
pub(crate) fn perform_one<A: Actions + ?Sized>(
    actions: &mut A,
    store: &mut Store,
    action: Term,
) -> Result<(), String> {
    if !store.undefined_noted().is_empty() && store.is_var(action) {
        return Err(undefined_action(store));
    }
    actions.perform(store, action)
}

#[cold]
#[inline(never)]
fn undefined_action(store: &Store) -> String {
    let noted: Vec<String> = store
        .undefined_noted()
        .iter()
        .map(|(op, name)| format!("`{op}` of `{name}`"))
        .collect();
    format!(
        "the action has no value: {} (neither a local nor a global variable) gave an unbound value, and the original SitLog stops on an unbound action too (an instantiation error)",
        noted.join(", ")
    )
}
