//! A recursive situation whose DM call is evaluated (`ask(Q, more,
//! get(vocab, _), _, _)`, `slow(apply(tally(_), [S]))`, `slow(_ is K * 2 +
//! 1)`) pushed on the native stack (issue 37): the call built from the
//! visit's values and evaluated once, read-only, where the native frames
//! are (`Cx::nat_embedded_dm`, D-20/E12: the globals as they were after),
//! each argument converted to the callee's frame type (`Cx::arg_as`), the
//! callee's frame pushed as for a call of values ([`Gen::nat_callee_frame`])
//! and the waiting variant `W<ix>` holding the evaluated call (`held`).
//!
//! The call is never evaluated twice (a global the callee sets, an `apply`
//! with side effects): where the push is not made for the history or the
//! depth limit the call is not evaluated at all (the machine's visit from
//! the template evaluates it, once); where it is evaluated and an argument
//! does not convert, or the evaluation failed, the frames are handed over
//! and `Cx::call_held` reports the error or gives the machine that call;
//! where the waiting frame becomes the machine's, `Cx::wait_held` pushes
//! the callee with it (`NatAt::held`). With the history kept, the callee's
//! level is opened with that call (`Cx::open_level`), the term a frame made
//! the machine's is checked against.
//!
//! With `codegen::Options::held_calls` (the default; `false` keeps these
//! situations on their templates).
//!
//! Which calls (`Gen::nat_held_args`): a DM without locals (the
//! evaluation's environment is then the machine's with no locals,
//! `machine::boundary`), a situation without `prog` and without an in_arg
//! pattern (the machine's call runs those before it evaluates), a call
//! named by a DM (not an L construct), each variable of it either a value
//! the visit holds, an output argument (a fresh variable, whole) or a
//! variable met only there (`SitTypes::unbound`): the template's own
//! variables are then only its arguments that are variables, which the
//! runtime links with the held call.
//!
//! Invariant: the code a held call generates evaluates the call at most
//! once per visit, and every path after the evaluation gives that term to
//! whoever makes the call (the native stack, `call_held`, `wait_held`).

use super::call::{build_regs, call_outputs, CallPlan};
use super::{is_fresh, Dm, Gen, Regs, N, V};
use crate::mir::{Build, KindPlan, Reg};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::native::Ty;
use sitlog_syntax::Atom;

impl Gen<'_> {
    /// The DM name and argument values of an evaluated call that native
    /// code evaluates itself (module doc: which calls): each argument the
    /// converted value `x<k>` of the callee's parameter type, an output
    /// argument `Ground::OUT`; `None` where the call is not one.
    pub(super) fn nat_held_args(
        &self,
        d: &Dm,
        ix: usize,
        regs: &Regs,
        outs: &[(usize, Reg)],
    ) -> Option<(Atom, Vec<V>)> {
        if !self.held_calls {
            return None;
        }
        let plan = &d.plans[ix];
        if d.shallow || !d.locals.is_empty() || plan.prog.is_some() {
            return None;
        }
        if matches!(plan.in_arg, Some((_, true, _))) {
            return None;
        }
        let KindPlan::Recursive {
            call: call @ Build::Compound(name, args),
            eval_call: true,
            ..
        } = &plan.kind
        else {
            return None;
        };
        if !sitlog_runtime::eval::evaluates_arguments_only(*name, args.len()) {
            return None;
        }
        self.held_fresh(d, ix, call, regs, outs)?;
        let ir = self.ir?;
        let j = ir.dms.iter().position(|x| x.name == *name)?;
        if ir.dms[j].arity != args.len() {
            return None;
        }
        let callee = self.nat_dm_of(j)?;
        let vals = callee
            .params
            .iter()
            .enumerate()
            .map(|(k, ty)| {
                if outs.iter().any(|&(o, _)| o == k) {
                    V {
                        e: quote!(Ground::OUT),
                        ty: Ty::Term,
                    }
                } else {
                    let x = format_ident!("x{}", k);
                    V {
                        e: quote!(#x),
                        ty: ty.clone(),
                    }
                }
            })
            .collect();
        Some((*name, vals))
    }

    /// The registers of call `call` the visit does not hold (`regs`), each
    /// an output argument or a variable met only there: made fresh
    /// variables where the call is built; `None` where one is not.
    fn held_fresh(
        &self,
        d: &Dm,
        ix: usize,
        call: &Build,
        regs: &Regs,
        outs: &[(usize, Reg)],
    ) -> Option<Vec<Reg>> {
        let mut rs = Vec::new();
        build_regs(call, &mut rs);
        rs.sort_unstable();
        rs.dedup();
        let mut fresh = Vec::new();
        for r in rs {
            if regs.get(&r).is_some_and(|(x, _)| !is_fresh(x)) {
                continue;
            }
            let out = outs.iter().any(|&(_, o)| o == r);
            if !out && d.types[ix].unbound.get(r as usize) != Some(&true) {
                return None;
            }
            fresh.push(r);
        }
        Some(fresh)
    }

    /// The visit of recursive situation `ix` whose call `plan` is held
    /// (module doc): within the depth limit and where the history allows
    /// the push, the call built, evaluated, converted and pushed; else the
    /// machine's visit from the template (nothing evaluated).
    pub(super) fn nat_held_visit(
        &self,
        d: &Dm,
        ix: usize,
        regs: &Regs,
        plan: &CallPlan,
    ) -> N<TokenStream> {
        let to_template = self.nat_to_template(d, ix)?;
        let KindPlan::Recursive { call, .. } = &d.plans[ix].kind else {
            return Err("not a recursive situation".into());
        };
        let outs = call_outputs(d, ix);
        let Some(fresh) = self.held_fresh(d, ix, call, regs, &outs) else {
            return Ok(to_template);
        };
        // The call's own variables: fresh variables of the visit (made
        // where it starts, with its others).
        let mut regs = regs.clone();
        for r in fresh {
            regs.insert(r, (format_ident!("fresh_r{}", r), Ty::Term));
        }
        let (mut ts, mut n) = (Vec::new(), 0);
        let t = self.nat_build_term(call, &regs, &mut ts, &mut n)?;
        // Each argument converted to the callee's parameter type (`v<k>`,
        // read at `[k]` of the call, `Cx::call_args`); an output argument
        // passes no term.
        let mut xs = Vec::new();
        let mut paths = Vec::new();
        let mut outs_let = Vec::new();
        let mut args = Vec::new();
        let vs: Vec<Ident> = (0..plan.callee.params.len())
            .map(|i| format_ident!("v{}", i))
            .collect();
        for (k, ty) in plan.callee.params.iter().enumerate() {
            let v = &vs[k];
            if outs.iter().any(|&(o, _)| o == k) {
                outs_let.push(v.clone());
                args.push(V {
                    e: quote!(#v),
                    ty: Ty::Term,
                });
                continue;
            }
            let kl = Literal::usize_unsuffixed(k);
            paths.push(quote!(&[#kl]));
            args.push(V {
                e: quote!(#v),
                ty: ty.clone(),
            });
            xs.push(v.clone());
        }
        if xs.len() > 8 {
            return Ok(to_template); // `FromIdParts`: eight at most
        }
        let cold = self.nat_held_cold(d, ix)?;
        // The first arguments: `Cx::first_args` (the paths its type's).
        let first = (0..xs.len())
            .map(|k| {
                let kl = Literal::usize_unsuffixed(k);
                quote!(&[#kl]).to_string()
            })
            .eq(paths.iter().map(|p| p.to_string()));
        let conv = if xs.is_empty() {
            quote!(let Ok(&held) = ev.as_ref() else { #cold };)
        } else if first {
            quote!(let Some((held, (#(#xs,)*))) = cx.first_args(&ev) else { #cold };)
        } else {
            quote!(let Some((held, (#(#xs,)*))) = cx.call_args(&ev, &[#(#paths),*]) else { #cold };)
        };
        let (frame, wf) = self.nat_callee_frame(d, ix, &regs, plan, &args, &vs)?;
        // An output argument passes no term: `Ground::OUT` in the frame.
        let frame = outs_let
            .iter()
            .fold(frame, |f, v| replace_ident(&f, v, &quote!(Ground::OUT)));
        let callee_v = format_ident!("D{}", plan.j);
        let wv = format_ident!("W{}", ix);
        let guard = if plan.rec_exit {
            quote!((!run.records || run.nests))
        } else {
            quote!(!run.records)
        };
        let visit = quote! {
            // The call evaluated once, read-only, then pushed natively
            // with the variant holding it (`call_held` where it is not).
            if #guard && stack.has_room(cx) {
                #(#ts)*
                let ev = cx.nat_embedded_dm(stack, #t);
                #conv
                let callee = #frame;
                cx.push_held(run, call, held, super::NatFrame::#callee_v(callee));
                return cx.step_done(count, slot, Nat::#wv { #(#wf,)* held });
            }
            #to_template
        };
        // The situation's id (a `Fill` both ways that hand over make) bound
        // once, first: a DM without locals, its registers not changed.
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        Ok(match super::fill_arg(&id_stmts, &id) {
            Some(fill) => match super::call::one_fill(&visit, &fill) {
                (Some(id_let), visit) => quote!(#id_let #visit),
                (None, visit) => visit,
            },
            None => visit,
        })
    }

    /// The frames handed over, then `Cx::call_held` with the evaluation
    /// `ev` (its error, or the machine's visit making that call).
    fn nat_held_cold(&self, d: &Dm, ix: usize) -> N<TokenStream> {
        let curl = Literal::u32_unsuffixed(ix as u32);
        let hand = &d.hand;
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        // The runtime's hand-over: both in one call (`NatBelow::call_held`),
        // the id an atom or a `Fill` bound first.
        let id_parts = match super::fill_arg(&id_stmts, &id) {
            Some(fill) => Some((quote!(let #id = #fill;), id.clone())),
            None if id_stmts.is_empty() => Some((quote!(), super::atom_arg(&id))),
            None => None,
        };
        if let (true, Some((id_let, id_arg))) = (super::runtime_hand(hand), id_parts) {
            return Ok(quote! {
                #id_let
                return stack.call_held(p, cx, count, #curl, #id_arg, ev);
            });
        }
        if let Some(fill) = super::fill_arg(&id_stmts, &id) {
            return Ok(quote!(#hand return cx.call_held(count, #curl, #fill, ev);));
        }
        if id_stmts.is_empty() {
            let id = super::atom_arg(&id);
            return Ok(quote!(#hand return cx.call_held(count, #curl, #id, ev);));
        }
        Ok(quote! {
            #hand
            #(#id_stmts)*
            return cx.call_held(count, #curl, #id, ev);
        })
    }
}

/// `ts` with every identifier `x` replaced by `by`.
pub(super) fn replace_ident(ts: &TokenStream, x: &Ident, by: &TokenStream) -> TokenStream {
    use proc_macro2::{Group, TokenTree};
    ts.clone()
        .into_iter()
        .flat_map(|t| -> Vec<TokenTree> {
            match t {
                TokenTree::Ident(i) if i == *x => by.clone().into_iter().collect(),
                TokenTree::Group(g) => {
                    let mut ng = Group::new(g.delimiter(), replace_ident(&g.stream(), x, by));
                    ng.set_span(g.span());
                    vec![TokenTree::Group(ng)]
                }
                t => vec![t],
            }
        })
        .collect()
}
