//! A global read's cold arm in an arc's action (issue 37, helper
//! `ncold21`; [`super::cold`] and [`super::cold_next`] do the same for a
//! conditional's condition and a next situation). Native code reads a
//! global as a value of its MIR type (`Cx::global_as`); a frame on terms
//! (a parameter that was not ground where its frame started) may have
//! stored a value that type does not allow, such as an unbound variable
//! (`set(goal, Goal)`, `Goal` unbound), and the interpreter goes on with
//! it: `done : [get(goal, G)] => seen(G)` performs `[_G]` and goes to
//! `seen(_G)`. An exit arc's action, or a neutral or perceptual arc's that
//! native code computes item by item ([`Gen::nat_exit_action`]), reads a
//! global by `get`; where that read finds such a value (the native frames
//! already handed over and the machine entered in the situation by the
//! read's cold arm), the rest of the arc goes on on terms from that item,
//! as `Machine::conclude` does it: the items before it are the values
//! native code computed (their effects done once, not again), that item
//! and the later ones are evaluated on terms as the term code does
//! ([`Gen::nat_ev_term`]: a `get` again, which changes nothing), the
//! action performed by the machine (`Cx::perform`, whole), the next
//! situation and the out_arg evaluated on terms, the history entry made
//! when recorded and the next situation handed to the machine as a term
//! (`TypedRun::goto`), the transition counted once its next situation is
//! computed. The hot path (the global of its type) is unchanged; an
//! action with no such read is made as before, byte for byte.

use super::{Dm, Regs, N};
use crate::codegen::Gen;
use crate::mir::{Action, ArcPlan, Ev, Next};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::native::Ty;
use sitlog_syntax::atoms;
use std::cell::RefCell;

impl Gen<'_> {
    /// The cold arm of item `k` of arc `arc`'s action (arc number
    /// `arc_ix`) where that item is a `get` of a global native code read
    /// and found a value it cannot hold: the statements of the arc's rest
    /// on terms, ending in the machine's step (above). `regs`: the
    /// registers after the items before `k` (their values `act<j>`);
    /// `exp_regs`: those the expectation was made of. `Err` where a part
    /// is not made on terms (the read's arm stays the error).
    pub(super) fn cold_action(
        &self,
        d: &Dm,
        arc: &ArcPlan,
        arc_ix: usize,
        k: usize,
        regs: &Regs,
        exp_regs: &Regs,
    ) -> N<TokenStream> {
        let (items, list): (Vec<&Ev>, bool) = match &arc.action {
            Action::List { items, .. } => (items.iter().collect(), true),
            Action::One(e) => (vec![e], false),
        };
        let item = items.get(k).ok_or("no such item")?;
        let (Ev::VarOpFresh { name, .. } | Ev::VarOp { name, .. }) = item else {
            return Err("not a global's `get`".into());
        };
        if !is_global_get(d, item) || !self.global_may_not_hold(*name) {
            return Err("not a global's `get` that may find such a value".into());
        }
        // No pattern registered for code that may be dropped.
        let _no_new = NoNewPatterns::set(&self.no_new_patterns);
        // What the rest binds (`get(goal, G)`'s `G`): a term made there.
        let mut binds = Vec::new();
        for item in &items[k..] {
            super::ev_binds(item, &mut binds);
        }
        super::next_binds(&arc.next, &mut binds);
        if let Some(o) = super::pipe::arc_out(arc) {
            super::ev_binds(o, &mut binds);
        }
        let mut mregs = regs.clone();
        for r in &binds {
            mregs.insert(*r, (format_ident!("fresh_r{}", r), Ty::Term));
        }
        let mut ts = Vec::new();
        let mut n = 0;
        // The items before `k`: their values; from `k` on: on terms.
        let mut terms = Vec::new();
        for (j, item) in items.iter().enumerate() {
            if j < k {
                let x = format_ident!("act{}", j);
                terms.push(quote!(cx.term(&#x)));
            } else {
                terms.push(self.nat_ev_term(item, &mregs, &mut ts, &mut n)?);
            }
        }
        let act = if list {
            quote! {
                let act_items = [#(#terms),*];
                let act = cx.store().list(&act_items);
            }
        } else {
            quote!(let act = #(#terms)*;)
        };
        let mut next_ts = Vec::new();
        let next = self.next_term(&arc.next, &mregs, &mut next_ts, &mut n)?;
        let out = match super::pipe::arc_out(arc) {
            Some(o) => {
                let mut out_ts = Vec::new();
                let t = self.nat_ev_term(o, &mregs, &mut out_ts, &mut n)?;
                quote!(#(#out_ts)* cx.out_value(#t);)
            }
            None => quote!(),
        };
        // The expectation's term made again: only one evaluating nothing.
        if !built_only(&arc.expectation) {
            return Err("an evaluated expectation".into());
        }
        let mut exp_ts = Vec::new();
        let exp = self.nat_ev_term(&arc.expectation, exp_regs, &mut exp_ts, &mut n)?;
        let arc_l = Literal::usize_unsuffixed(arc_ix);
        Ok(quote! {{
            // A global's value native code cannot hold: the arc's rest on
            // terms, the machine's.
            let arc_at = Some(#arc_l);
            #(#ts)*
            #act
            cx.perform(act, arc_at)?;
            #(#next_ts)*
            let rec_next = #next;
            #out
            #(#exp_ts)*
            let exp: Term = #exp;
            cx.count_transitions(u64::from(!run.records));
            return run.goto(cx, exp, act, rec_next, arc_at);
        }})
    }

    /// Next situation `n` as a term evaluated on terms as the term code
    /// does (a constant as it is, a value by [`Gen::nat_ev_term`], a
    /// conditional's condition by the machine, then the branch it picks).
    pub(super) fn next_term(
        &self,
        n: &Next,
        regs: &Regs,
        ts: &mut Vec<TokenStream>,
        k: &mut usize,
    ) -> N<TokenStream> {
        match n {
            Next::Eval(e) => self.nat_ev_term(e, regs, ts, k),
            Next::Static(t, _) => self.nat_const_term(*t, ts, k),
            Next::If(c, a, b) => {
                let c = self.nat_cond_term(c, regs, ts, k)?;
                let (mut ta, mut tb) = (Vec::new(), Vec::new());
                let xa = self.next_term(a, regs, &mut ta, k)?;
                let xb = self.next_term(b, regs, &mut tb, k)?;
                let x = format_ident!("b{}", *k);
                *k += 1;
                ts.push(quote! {
                    let #x = if #c { #(#ta)* #xa } else { #(#tb)* #xb };
                });
                Ok(quote!(#x))
            }
        }
    }
}

impl Gen<'_> {
    /// Whether global `name` may hold a value of its MIR type native code
    /// cannot hold (stored by a frame on terms: an unbound variable,
    /// `f(_)`): a `ground` one, a list, a compound. A number's or an
    /// atom's cannot (its type joins every value written to it, and a
    /// frame on terms writes a `ground` one): its cold arm stays the
    /// error, never reached.
    pub(super) fn global_may_not_hold(&self, name: sitlog_syntax::Atom) -> bool {
        let ty = self
            .mir_types
            .as_ref()
            .and_then(|t| t.globals.iter().find(|(n, _)| *n == name))
            .map(|(_, t)| t.ty.clone());
        !matches!(ty, Some(Ty::Int | Ty::Float | Ty::Sym))
    }
}

/// Whether `e` is made without evaluating anything: values, constants,
/// compounds of them.
fn built_only(e: &Ev) -> bool {
    match e {
        Ev::Value(_) | Ev::Built(_) => true,
        Ev::Compound(_, args) => args.iter().all(built_only),
        _ => false,
    }
}

/// Whether `e` is a `get` of a global (a name that is no declared local
/// of DM `d`): evaluated again, it changes nothing.
pub(super) fn is_global_get(d: &Dm, e: &Ev) -> bool {
    match e {
        Ev::VarOpFresh { op, name, .. } | Ev::VarOp { op, name, .. } => {
            *op == atoms::GET && !d.declares_local(*name)
        }
        _ => false,
    }
}

/// While alive, the cold arm native code gives a global's `get`
/// (`Gen::global_cold`, read by `Gen::nat_global_op`); the one before
/// it back when dropped.
pub(super) struct ColdArm<'a> {
    cell: &'a RefCell<Option<TokenStream>>,
    saved: Option<TokenStream>,
}

impl<'a> ColdArm<'a> {
    pub(super) fn set(cell: &'a RefCell<Option<TokenStream>>, cold: Option<TokenStream>) -> Self {
        let saved = cell.replace(cold);
        ColdArm { cell, saved }
    }
}

impl Drop for ColdArm<'_> {
    fn drop(&mut self) {
        *self.cell.borrow_mut() = self.saved.take();
    }
}

/// While alive, no new `cx.fill` pattern is registered
/// (`Gen::no_new_patterns`); the flag as it was back when dropped.
pub(super) struct NoNewPatterns<'a> {
    cell: &'a std::cell::Cell<bool>,
    saved: bool,
}

impl<'a> NoNewPatterns<'a> {
    pub(super) fn set(cell: &'a std::cell::Cell<bool>) -> Self {
        let saved = cell.replace(true);
        NoNewPatterns { cell, saved }
    }
}

impl Drop for NoNewPatterns<'_> {
    fn drop(&mut self) {
        self.cell.set(self.saved);
    }
}
