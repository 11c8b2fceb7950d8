//! Ground terms native code takes apart where they cross a boundary
//! (issue 37, the last hand-overs of the home butler): the MIR keeps a
//! ground term whole (`Build::Const`, `Ev::Eval(Build::Const)`), and three
//! places of the generator read only a compound of parts. Each is given
//! here the same term as the compound of its arguments, each a constant,
//! so the generator's own path for that compound makes the code:
//! - *a final's `diag_mod` that is constant* (`diag_mod ==> welcome([])`):
//!   [`Gen::diag_parts`] gives `welcome` of the constant `[]`, whose output
//!   slot ([`Gen::nat_output_slots`]) takes the value natively, so a native
//!   caller below that passed its output as `Ground::OUT` gets it in the
//!   frame's slot instead of the frames being handed over; the caller's
//!   exit arcs read the same parts (`call::slot_final`), so a final that
//!   comes back in its slots always has its arms there;
//! - *a ground next situation the evaluator computes*
//!   (`=> infer(apply(shop_place_here, []))`): where its functor evaluates
//!   its arguments only ([`sitlog_runtime::eval::evaluates_arguments_only`])
//!   the evaluation is that of its arguments, then the compound of their
//!   values (what the evaluator does), so [`Gen::ground_next_parts`] gives
//!   `infer` of the argument `Ev::Eval(apply(..))`, which the generator
//!   selects natively with the checked conversion (the machine given the
//!   value only where it does not convert); where the generator cannot
//!   select so (a situation whose argument has a narrower type than
//!   `ground`, `round(Rooms)` with `Rooms: list<atom>`), the whole term is
//!   the machine's as before;
//! - *a DM whose frames are always the base of the native stack*
//!   ([`Gen::only_at_base`]: no situation that runs as code calls it, so
//!   it is entered by the machine only): its finals have no native frame
//!   below to hand over (`nat_hand_over` would find none), so none is
//!   made.
//!
//! Invariant: the term given is the one the MIR holds (same functor, the
//! same arguments in order; an argument the evaluator computes is
//! evaluated as before), so the code made from it does what the code made
//! from the whole term did.

use super::Dm;
use crate::codegen::Gen;
use crate::mir::{Build, Ev, KindPlan};
use sitlog_runtime::{Store, Term, Value};
use sitlog_syntax::Atom;

/// [`Gen::diag_parts`], for the code that reads a callee's finals
/// (`call::slot_final`).
pub(super) fn diag_parts(store: &Store, d: &Dm, b: &Build) -> Option<Build> {
    let Build::Const(t) = b else {
        return None;
    };
    match store.value(*t) {
        Value::Compound(name, args) if name == d.dm.name && args.len() == d.dm.arity => Some(
            Build::Compound(name, args.iter().map(|&a| Build::Const(a)).collect()),
        ),
        _ => None,
    }
}

impl Gen<'_> {
    /// `b`, a final's `diag_mod`, as a compound of the DM's head (name and
    /// arity) when it is such a constant: each argument a constant
    /// ([`Build::Const`]); else `None` (the generator reads `b` as it is).
    pub(super) fn diag_parts(&self, d: &Dm, b: &Build) -> Option<Build> {
        diag_parts(self.store, d, b)
    }

    /// A ground next situation `e` the evaluator computes whole
    /// (`Ev::Eval(Build::Const(t))`) whose functor evaluates its arguments
    /// only, as that compound of its arguments: an argument whose value
    /// is itself ([`Self::inert_const`]) built, any other evaluated
    /// (`Ev::Eval`); `None` otherwise, or where no argument is evaluated
    /// (then the term is its own value and the MIR says so already).
    pub(super) fn ground_next_parts(&self, e: &Ev) -> Option<Ev> {
        let Ev::Eval(Build::Const(t)) = e else {
            return None;
        };
        let (name, args) = self.compound_of(*t)?;
        if !sitlog_runtime::eval::evaluates_arguments_only(name, args.len()) {
            return None;
        }
        let parts: Vec<Ev> = args
            .iter()
            .map(|&a| {
                if self.inert_const(a) {
                    Ev::Built(Build::Const(a))
                } else {
                    Ev::Eval(Build::Const(a))
                }
            })
            .collect();
        parts
            .iter()
            .any(|p| matches!(p, Ev::Eval(_)))
            .then(|| Ev::Compound(name, parts.into()))
    }

    /// Whether no situation that runs as code (a MIR plan) calls DM
    /// `name`, and no such call's DM is computed: its frames are then
    /// entered by the machine only, at the base of the native stack (a
    /// native frame is pushed above another only by a call a plan makes).
    pub(super) fn only_at_base(&self, name: Atom) -> bool {
        self.mir
            .dms
            .iter()
            .flatten()
            .flatten()
            .all(|p| match &p.kind {
                KindPlan::Recursive { call, .. } => {
                    let callee = match call {
                        Build::Const(t) => self
                            .store
                            .atom_of(*t)
                            .or_else(|| self.store.functor(*t).map(|f| f.0)),
                        Build::Compound(n, _) => Some(*n),
                        Build::Reg(_) => None,
                    };
                    callee.is_some_and(|c| c != name)
                }
                _ => true,
            })
    }

    /// Name and arguments of `t` when it is a compound.
    fn compound_of(&self, t: Term) -> Option<(Atom, Vec<Term>)> {
        match self.store.value(t) {
            Value::Compound(name, args) => Some((name, args.to_vec())),
            _ => None,
        }
    }

    /// Whether the ground term `t` evaluates to itself: every compound in
    /// it evaluates its arguments only (the MIR's `Planner::inert`).
    fn inert_const(&self, t: Term) -> bool {
        let mut stack = vec![t];
        while let Some(u) = stack.pop() {
            if let Value::Compound(name, args) = self.store.value(u) {
                if !sitlog_runtime::eval::evaluates_arguments_only(name, args.len()) {
                    return false;
                }
                stack.extend(args.iter());
            }
        }
        true
    }
}
