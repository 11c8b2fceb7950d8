//! An arc's action of effectors performed by native code without handing
//! its frames over (issue 37, helper `neff18`): `navigate(Place, Result)`,
//! `[say(['Attempting to grab the', Object]), grasp(Object, Hand,
//! Result)]`, `[say('Sorry.'), say(Question)]`, a constant action
//! (`say('I cannot find you.')`, `stop`, a constant list of `say`s), a
//! `say` of a list of native values.
//!
//! What the hand-over (`nat_hand_over`: the native frames below made the
//! machine's, the DM's locals written back) protects, read from the
//! runtime, and where each is kept:
//! - *the effector* sees none of it: `Actions::perform` is given the store
//!   and the action's term only (the simulated robot, the ROS bridge, the
//!   test mode's text, every `Actions` of the workspace), so it cannot
//!   read the DM stack, the locals, the situation entered or the history.
//!   It may bind a variable of the term (an output, `Result`): that grows
//!   the store and binds a fresh variable of this arc, made by
//!   `cx.vars()` before the hand-over in any case; no native value
//!   (ground) refers to it.
//! - *garbage collection*: none during an action; the machine collects
//!   only between situations, native code handing its frames over first
//!   (`Cx::gc_tick`, `machine::nat_goto`), so the frames' `Ground`/`Val`
//!   handles are not at stake.
//! - *the error report*: the machine's `RunError` names the running DM's
//!   call, the situation's id and its location from the machine's top
//!   frame, which is the native stack's bottom until the frames below are
//!   handed over; and the situation must be entered with its id. So where
//!   the effector fails, both are made first, then the error
//!   (`Cx::nat_perform`, out of line): the report is the interpreter's,
//!   the transitions before it counted, the failing one not.
//! - *the history and the observer* (`run.records`): the situation is
//!   entered with its id before the action, the frames handed over first,
//!   as before (the entry reads the machine's level); unchanged.
//! - *an evaluation in the action* (`apply(words(_), [..])`, `get`/`set`/
//!   `inc`, `is`, a conditional): the evaluator runs in the machine's
//!   running frame (`Cx::eval` materializes it; a user function may read or
//!   set its locals, `poke` in `tests/suite/typed.rs`), so an action with
//!   one keeps the hand-over before it (not here).
//! - *a value bound at the boundary that does not convert* (`Result` bound
//!   to a shape the next situation's field cannot hold): the arc's rest
//!   runs on terms (`nat_bound_at_boundary`'s fallback), which hands over
//!   first where the action did not.
//!
//! So an action whose items are built of values only (constants, native
//! values, fresh variables: `mir::Ev::Value`, `Built`, `Compound` of
//! them, no evaluation) is built from native values and performed by
//! `Cx::nat_perform`/`nat_perform_list`: unrecorded, neither the
//! hand-over nor the entry (the situation's id is a `Fill` or an atom the
//! call builds only where the effector fails); recorded, both first, as
//! before. A DM with locals (its own hand-over writes them back) keeps
//! the hand-over before the action.

use super::{atom_arg, fill_parts, runtime_hand, Dm, Gen, Regs, N};
use crate::mir::{Action, Build, Ev};
use proc_macro2::{Literal, TokenStream};
use quote::quote;
use sitlog_syntax::{atoms, Atom};

/// Whether `e` is built of values only: a constant, a register's value, a
/// compound of them (`mir::Ev::Compound`: evaluating it evaluates its
/// arguments only), nothing the evaluator computes.
fn built_of_values(e: &Ev) -> bool {
    match e {
        Ev::Value(_) | Ev::Built(_) => true,
        Ev::Compound(_, args) => args.iter().all(built_of_values),
        _ => false,
    }
}

impl Gen<'_> {
    /// Whether `Cx::perform` hands the value of `e` (built of values) to
    /// the effector as it is: a compound that is not a list.
    fn as_is(&self, e: &Ev) -> bool {
        match e {
            Ev::Built(Build::Const(t)) => self
                .store
                .functor(*t)
                .is_some_and(|(f, n)| n > 0 && f != atoms::DOT),
            Ev::Built(Build::Compound(f, _)) | Ev::Compound(f, _) => *f != atoms::DOT,
            _ => false,
        }
    }

    /// Whether arc actions `action` (`atom`: the action when it is a
    /// constant atom) of a situation of `d` are performed by
    /// [`Gen::nat_effect`]: a DM without locals, an action of effectors
    /// built of values only (not `empty`, which `Cx::nat_empty` performs).
    pub(super) fn nat_effect_ok(&self, d: &Dm, action: &Action, atom: Option<Atom>) -> bool {
        if !runtime_hand(&d.hand) {
            return false;
        }
        match (action, atom) {
            (_, Some(a)) => a != atoms::EMPTY,
            (Action::One(e), None) => built_of_values(e),
            (Action::List { items, .. }, None) => items.iter().all(built_of_values),
        }
    }

    /// The code performing arc `arc`'s action `action` of situation `ix`
    /// ([`Gen::nat_effect_ok`]), its items built from native values
    /// first: one `Cx::nat_perform` (`nat_perform_list`), which hands the
    /// frames over and enters the situation only where the run records
    /// (first) or the effector fails (then). Binds `act`, the action as the
    /// history records it (a constant atom's: bound by the caller). `None`: the situation's id is not an atom nor a
    /// filled pattern (the caller's way then).
    pub(super) fn nat_effect(
        &self,
        d: &Dm,
        ix: usize,
        action: &Action,
        atom: Option<Atom>,
        regs: &Regs,
    ) -> N<Option<TokenStream>> {
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let id = if id_stmts.is_empty() {
            atom_arg(&id)
        } else {
            match fill_parts(&id_stmts, &id) {
                // In the call (not a `let`, which would hold its borrows
                // of the fields: a field moved after would be cloned).
                Some((pattern, holes)) if holes.to_string() == quote!(&[]).to_string() => pattern,
                Some((pattern, holes)) => quote!(Fill(#pattern, #holes)),
                None => return Ok(None),
            }
        };
        let (cur, arc) = (Literal::u32_unsuffixed(ix as u32), quote!(arc_ix));
        let mut ts = Vec::new();
        let mut n = 0;
        let perform = match (action, atom) {
            // `act` bound by the caller.
            (_, Some(a)) => {
                let t = self.atom_term(a)?;
                quote!(cx.nat_perform(stack, &mut count, (#cur, #arc), #id, #t, run)?;)
            }
            (Action::One(e), None) => {
                let t = self.nat_ev_term(e, regs, &mut ts, &mut n)?;
                // What `Cx::perform` hands to the effector as it is (a
                // compound not a list): nothing looked at at run time.
                let f = if self.as_is(e) {
                    quote!(nat_perform)
                } else {
                    quote!(nat_perform_any)
                };
                quote! {
                    let act = #t;
                    cx.#f(stack, &mut count, (#cur, #arc), #id, act, run)?;
                }
            }
            (Action::List { items, .. }, None) => {
                let items = items
                    .iter()
                    .map(|e| self.nat_ev_term(e, regs, &mut ts, &mut n))
                    .collect::<N<Vec<_>>>()?;
                quote! {
                    let act_items = [#(#items),*];
                    let act = cx.nat_perform_list(stack, &mut count, (#cur, #arc), #id, &act_items, run)?;
                }
            }
        };
        Ok(Some(quote! {
            #(#ts)*
            #perform
        }))
    }
}
