//! An arc's action of effectors performed by native code without handing
//! its frames over (issue 37, helpers `neff18`, `nuni19`): `navigate(Place, Result)`,
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
//! them, no evaluation) is built from native values and performed before
//! the situation is entered: unrecorded, neither the hand-over nor the
//! entry (the situation's id is a `Fill` or an atom the call builds only
//! where the effector fails); recorded, both first, as before. A DM with
//! locals (its own hand-over writes them back) keeps the hand-over before
//! the action.
//!
//! One path performs every arc's action in native code
//! ([`Gen::nat_perform_call`], the runtime's one `Cx::nat_perform`), the
//! two cases (helpers `neff18` and `nfun18`, made one by `nuni19`) told
//! apart by the entry it is given, data:
//! - `Due(&mut count, (sit, arc), id)`: the action above, *before* the
//!   situation is entered ([`Gen::nat_effect`]). What is protected: the
//!   error's site (the situation entered with its id where the effector
//!   fails, the frames handed over first) and the recorded entry (made
//!   first where the run records).
//! - `arc_at` (the arc's index): *after* the arc's code entered the
//!   situation (`cx.enter_counted`), an action with an evaluation in it or
//!   of a DM with locals. In a DM without locals whose arc calls the
//!   evaluator, the boundary post-pass (`boundary::at_boundary`) drops the
//!   hand-over before the entry: `Cx::nat_perform` hands over only where
//!   the effector fails (what is protected: the error's DM, the machine's
//!   top frame). Else the hand-over is made before the entry and the call
//!   finds no native frame below (`Cx::perform`'s behaviour).
//!
//! An action performed before its situation is entered whose functor is
//! known (a compound not a list; not `say/1` nor `screen/1`, which every
//! effector performs) is built and performed only where the run records
//! or the effector does not ignore it (`Cx::ignores_action`, the
//! runtime's `Actions::ignores`): an action nothing shows costs a
//! question, not a term.
//!
//! The action, in both: a term `Cx::perform` hands to the effector as it
//! is where [`Gen::as_is`] (nothing looked at at run time; one filled
//! from its pattern given as `Fill(pattern, holes)`, which the effector
//! may perform unfilled where nothing records it), an
//! `AnyShape(..)` for any other value (a term evaluated whole: `empty` and
//! proper lists as `Cx::perform` treats them), or the items of a list
//! written out (`&act_items`, the list built for the history only where
//! the run records).

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

/// Whether entry `at` ([`Gen::nat_perform_call`]) is `arc_at`: the
/// situation entered.
fn entered(at: &TokenStream) -> bool {
    at.to_string() == "arc_at"
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
    /// built of values only (not `empty`, which `Cx::nat_empty` performs),
    /// or of conditionals on type tests native code decides on `regs`
    /// (`(number(X) -> n ; otherwise -> o)`, module `type_test`) choosing
    /// between such values.
    pub(super) fn nat_effect_ok(
        &self,
        d: &Dm,
        action: &Action,
        atom: Option<Atom>,
        regs: &Regs,
    ) -> bool {
        if !runtime_hand(&d.hand) {
            return false;
        }
        let ok = |e: &Ev| self.values_or_tests(e, regs, 0);
        match (action, atom) {
            (_, Some(a)) => a != atoms::EMPTY,
            (Action::One(e), None) => ok(e),
            (Action::List { items, .. }, None) => items.iter().all(ok),
        }
    }

    /// [`built_of_values`], or a conditional whose condition is a type
    /// test native code decides on `regs` and whose branches are such.
    fn values_or_tests(&self, e: &Ev, regs: &Regs, depth: usize) -> bool {
        match e {
            _ if built_of_values(e) => true,
            Ev::If(c, a, b) if depth < sitlog_runtime::native::MAX_DEPTH => {
                matches!(&**c, crate::mir::Cond::Other(t)
                    if self.is_type_test(t) && self.nat_type_test(t, regs).is_ok())
                    && self.values_or_tests(a, regs, depth + 1)
                    && self.values_or_tests(b, regs, depth + 1)
            }
            _ => false,
        }
    }

    /// The code performing arc `arc`'s action `action` of situation `ix`
    /// ([`Gen::nat_effect_ok`]) before the situation is entered, its items
    /// built from native values first: [`Gen::nat_perform_call`] with the
    /// entry `Due` (the situation entered where the run records, first, or
    /// the effector fails, then). Binds `act`, the action as the history
    /// records it (a constant atom's: bound by the caller). `None`: the
    /// situation's id is not an atom nor a filled pattern (the caller's
    /// way then).
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
                Some((pattern, holes)) => {
                    let holes = super::fill::holes_tuple(&holes);
                    quote!(Fill(#pattern, #holes))
                }
                None => return Ok(None),
            }
        };
        let cur = Literal::u32_unsuffixed(ix as u32);
        let at = quote!(Due(&mut count, (#cur, arc_ix), #id));
        let mut ts = Vec::new();
        let mut n = 0;
        let perform = self.nat_perform_call(&at, action, atom, regs, &mut ts, &mut n)?;
        // A compound the effector may ignore whatever its arguments
        // (`Actions::ignores`: an action test mode neither shows nor
        // declares): neither built nor handed over where nothing records.
        if let (Action::One(e), None) = (action, atom) {
            if let Some((f, arity)) = self.as_is_functor(e) {
                let f = self.functor_native(f)?;
                let arity = Literal::usize_unsuffixed(arity);
                return Ok(Some(quote! {
                    let act = if run.records || !cx.ignores_action(#f, #arity) {
                        #(#ts)*
                        #perform
                        act
                    } else {
                        Term::EMPTY
                    };
                }));
            }
        }
        Ok(Some(quote! {
            #(#ts)*
            #perform
        }))
    }

    /// The functor of an action [`Gen::as_is`] (a compound not a list)
    /// that an effector may ignore: not `say/1` nor `screen/1`, which every
    /// effector of the workspace performs (test mode shows them, the robot
    /// speaks and shows them), so the question would always be answered
    /// no; not asking is always correct, and keeps the program smaller.
    fn as_is_functor(&self, e: &Ev) -> Option<(Atom, usize)> {
        let (f, n) = match e {
            Ev::Built(Build::Const(t)) => self.store.functor(*t)?,
            Ev::Built(Build::Compound(f, args)) => (*f, args.len()),
            Ev::Compound(f, args) => (*f, args.len()),
            _ => return None,
        };
        let shown = n == 1 && (f == Atom::intern("say") || f == Atom::intern("screen"));
        (self.as_is(e) && n > 0 && !shown).then_some((f, n))
    }

    /// The one call performing arc action `action` (`atom`: the action
    /// when it is a constant atom other than `empty`) by native code,
    /// whether the situation is entered or not (`at`: `arc_at` where it is,
    /// `Due(..)` where it is not; the runtime's `machine::effect`): one
    /// `Cx::nat_perform`, the action a term performed as it is where
    /// [`Gen::as_is`], else an `AnyShape`, or a list's items written out.
    /// Its items' statements go to `ts`. Binds `act`, the action as the
    /// history records it (a constant atom's: bound by the caller).
    pub(super) fn nat_perform_call(
        &self,
        at: &TokenStream,
        action: &Action,
        atom: Option<Atom>,
        regs: &Regs,
        ts: &mut Vec<TokenStream>,
        n: &mut usize,
    ) -> N<TokenStream> {
        Ok(match (action, atom) {
            // `act` bound by the caller.
            (_, Some(a)) => {
                let t = self.atom_term(a)?;
                quote!(cx.nat_perform(stack, #at, #t, run)?;)
            }
            (Action::One(e), None) => {
                let t = self.nat_ev_term(e, regs, ts, n)?;
                // A compound filled from its pattern (`let b0 =
                // cx.fill(p.k[3], &[&r4]);`): handed over as the pattern
                // and its holes, `Fill`, which the effector may perform
                // unfilled (the runtime's `machine::effect`).
                if let Some((pattern, holes)) = ts
                    .last()
                    .filter(|_| self.as_is(e))
                    .and_then(|last| fill_parts(std::slice::from_ref(last), &t))
                {
                    ts.pop();
                    let holes = super::fill::holes_tuple(&holes);
                    return Ok(quote! {
                        let act = cx.nat_perform(stack, #at, Fill(#pattern, #holes), run)?;
                    });
                }
                // What `Cx::perform` hands to the effector as it is (a
                // compound not a list): nothing looked at at run time.
                let shape = |t: TokenStream| {
                    if self.as_is(e) {
                        t
                    } else {
                        quote!(AnyShape(#t))
                    }
                };
                if entered(at) {
                    let t = shape(t);
                    quote!(let act = cx.nat_perform(stack, #at, #t, run)?;)
                } else {
                    // The action bound first: a `Due`'s call is long.
                    let act = shape(quote!(act));
                    quote! {
                        let act = #t;
                        cx.nat_perform(stack, #at, #act, run)?;
                    }
                }
            }
            (Action::List { items, .. }, None) => {
                let items = items
                    .iter()
                    .map(|e| self.nat_ev_term(e, regs, ts, n))
                    .collect::<N<Vec<_>>>()?;
                quote! {
                    let act_items = [#(#items),*];
                    let act = cx.nat_perform(stack, #at, &act_items, run)?;
                }
            }
        })
    }
}
