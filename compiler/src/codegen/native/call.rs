//! The caller's side of native DMs: a recursive situation with native
//! code whose embedded DM's initial situation has native code (its locals
//! native, the arguments converting to its frame) pushes the callee's typed frame on the driver's native
//! stack ([`super::frame`]) and waits in its own variant `W<ix>` (the
//! situation's id variables and the registers its exit arcs read, as the
//! term code's `saved` keeps them); when the callee reaches a final, the
//! exit arcs are matched against the callee's final variant natively
//! (`found(P)` binds `P` from the variant's field), their action (`inc`
//! and `get` of a local, atoms, numbers) and next situation run natively.
//!
//! Hand-over, so behaviour stays the term path's:
//! - a call made while a history is kept or observed (`run.records`: the
//!   machine pushes the callee's frame, its entries nest in the caller's),
//!   a call whose DM is not native there, whose arguments do not fit the
//!   callee's frame (an output argument: a fresh variable, made as a term
//!   for the visit), or whose exit arcs are not native here, or that
//!   would reach the depth limit, is given to the machine as the term
//!   code gives it (`Step::Call` with the same `saved`): the machine runs
//!   the callee and the caller's term code takes the exit;
//! - anything that needs the machine's state (an action performed, an
//!   error, a comparison evaluated on terms) first materializes the native
//!   stack and writes the locals back ([`super::Dm::hand`]);
//! - no exit arc matching is an error the machine reports itself
//!   (`Cx::choose_exit` on the final's id, built then).
//!
//! Which situations of a DM have native code never depends on its callees
//! (a call that is not native here is handed over), so it is decided once
//! per DM.

use super::{coerce, identical, reg, rust_ty, Dm, Gen, Regs, N, V};
use crate::mir::{Action, Build, Ev, Init, KindPlan, Reg};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::machine::Kind;
use sitlog_runtime::native::Ty;
use sitlog_runtime::{ArithCmp, Term, Value};
use sitlog_syntax::atoms;
use std::collections::HashMap;

/// Why a call is not native: its DM call is evaluated (given to the
/// machine on terms, evaluated there by `Cx::embedded_dm`).
const EVALUATED: &str = "the embedded DM call is evaluated";

/// The waiting variant of a recursive situation and its uses.
#[derive(Clone)]
pub(super) struct Wait {
    pub variant: TokenStream,
    pub id_arm: TokenStream,
    /// Resumes with the callee's frame (`ret`): the exit arcs.
    pub exit_arm: TokenStream,
    /// In `nat_wait`: made a machine frame's pending situation.
    pub wait_arm: TokenStream,
}

/// A native call: the callee's index and native view, and the exit code.
struct CallPlan<'a> {
    j: usize,
    callee: Dm<'a>,
    exit: TokenStream,
}

fn wait_variant(ix: usize) -> Ident {
    format_ident!("W{}", ix)
}

impl Gen<'_> {
    /// The registers the waiting variant keeps: the id's variables, then
    /// the registers saved for the exit arcs.
    fn nat_wait_fields(&self, d: &Dm, ix: usize) -> N<Vec<(Reg, Ty)>> {
        let mut fields = self.nat_fields(d, ix)?;
        if let KindPlan::Recursive { saved, .. } = &d.plans[ix].kind {
            for &r in saved {
                if !fields.iter().any(|(x, _)| *x == r) {
                    fields.push((r, d.types[ix].regs[r as usize].ty.clone()));
                }
            }
        }
        Ok(fields)
    }

    /// The call's DM name and argument values (`None`: evaluating it is not
    /// giving it back, the DM stays on terms).
    fn nat_call_values(&self, d: &Dm, ix: usize, regs: &Regs) -> N<(sitlog_syntax::Atom, Vec<V>)> {
        let KindPlan::Recursive {
            call, eval_call, ..
        } = &d.plans[ix].kind
        else {
            return Err("not a recursive situation".into());
        };
        match call {
            Build::Const(t) => {
                if *eval_call {
                    return Err(EVALUATED.into());
                }
                match self.store.value(*t) {
                    Value::Atom(a) => Ok((a, Vec::new())),
                    Value::Compound(name, args) => {
                        let args = args.to_vec();
                        let vals = args
                            .into_iter()
                            .map(|a| self.nat_value(&Build::Const(a), regs))
                            .collect::<N<Vec<_>>>()?;
                        Ok((name, vals))
                    }
                    _ => Err("the embedded DM is not a call".into()),
                }
            }
            Build::Compound(name, args) => {
                if *eval_call && !inert(call) {
                    return Err(EVALUATED.into());
                }
                let vals = args
                    .iter()
                    .map(|a| self.nat_value(a, regs))
                    .collect::<N<Vec<_>>>()?;
                Ok((*name, vals))
            }
            Build::Reg(_) => Err("the embedded DM is a variable".into()),
        }
    }

    /// The registers of a visit that come from the frame's parameters:
    /// each register's local and the statement that loads it.
    fn nat_head_regs(&self, d: &Dm, ix: usize, regs: &mut Regs) -> N<Vec<(Ident, TokenStream)>> {
        let mut stmts = Vec::new();
        let unbound = |r: Reg| {
            d.types[ix]
                .unbound
                .get(r as usize)
                .copied()
                .unwrap_or(false)
        };
        for (r, init) in &d.plans[ix].inits {
            if let Init::HeadArg(i) = init {
                if unbound(*r) {
                    continue;
                }
                let ty = d.types[ix].regs[*r as usize].ty.clone();
                stmts.push((reg(*r), super::load_head_arg(d, *r, *i, ty, regs)?));
            }
        }
        Ok(stmts)
    }

    /// Whether the call of recursive situation `ix` runs natively, and how.
    fn nat_call_plan(&self, d: &Dm, ix: usize) -> Option<CallPlan<'_>> {
        if d.shallow {
            return None;
        }
        let ir = self.ir?;
        // Argument values of the right count, with no registers: the name.
        let mut regs = Regs::new();
        for (r, ty) in self.nat_wait_fields(d, ix).ok()? {
            regs.insert(r, (reg(r), ty));
        }
        self.nat_head_regs(d, ix, &mut regs).ok()?;
        let (name, args) = self.nat_call_values(d, ix, &regs).ok()?;
        // The machine's `dm_by_name`: the first DM of that name.
        let j = ir.dms.iter().position(|x| x.name == name)?;
        if ir.dms[j].arity != args.len() {
            return None;
        }
        let callee = self.nat_dm_of(j)?;
        for (v, ty) in args.iter().zip(&callee.params) {
            coerce(v, ty).ok()?;
        }
        for ((_, default), (_, ty)) in ir.dms[j].locals.iter().zip(&callee.locals) {
            let v = self.nat_value(&Build::Const(*default), &Regs::new()).ok()?;
            coerce(&v, ty).ok()?;
        }
        let exit = self.nat_exit(d, ix, &callee, j).ok()?;
        Some(CallPlan { j, callee, exit })
    }

    /// The visit of recursive situation `ix` (registers `regs` set).
    pub(super) fn nat_recursive(&self, d: &Dm, ix: usize, regs: &Regs) -> N<TokenStream> {
        let (name, args) = match self.nat_call_values(d, ix, regs) {
            Ok(x) => x,
            // An argument is a fresh variable (an output argument), or the
            // call is evaluated (`ask(apply(f(_), [X]), ..)`): the
            // machine's call, on terms.
            Err(e) if e.starts_with("register r") || e == EVALUATED => {
                return self.nat_call_on_terms(d, ix, regs)
            }
            Err(e) => return Err(e),
        };
        let KindPlan::Recursive { saved, .. } = &d.plans[ix].kind else {
            return Err("not a recursive situation".into());
        };
        let curl = Literal::u32_unsuffixed(ix as u32);
        let hand = &d.hand;
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let vs: Vec<Ident> = (0..args.len()).map(|i| format_ident!("v{}", i)).collect();
        let lets = args.iter().zip(&vs).map(|(v, x)| {
            let e = &v.e;
            quote!(let #x = #e;)
        });
        let f = self.atom_native(name)?;
        let mut saved_vals = Vec::new();
        for &r in saved.iter() {
            let v = self.nat_value(&Build::Reg(r), regs)?;
            saved_vals.push(super::place(&v));
        }
        let saved_value = if saved.is_empty() {
            quote!(Term::NIL)
        } else {
            quote!(cx.compound_of(atoms::DOT, &[#(&#saved_vals),*]))
        };
        // The call given to the machine, as the term code gives it.
        let hand_call = quote! {
            #hand
            cx.count_transitions(count);
            #(#id_stmts)*
            cx.enter_with_id(#curl, #id);
            let call = cx.build_of(#f, &[#(&#vs),*]);
            let saved = #saved_value;
            return Ok(Some(
                Step::Call { call, saved },
            ));
        };
        let Some(plan) = self.nat_call_plan(d, ix) else {
            return Ok(quote! {
                #(#lets)*
                #hand_call
            });
        };
        let callee_f = format_ident!("NatF{}", plan.j);
        let callee_n = format_ident!("NatN{}", plan.j);
        let callee_v = format_ident!("D{}", plan.j);
        let ir = self.ir.ok_or("no IR")?;
        let mut inits = Vec::new();
        for (i, (v, ty)) in args.iter().zip(&plan.callee.params).enumerate() {
            let p = format_ident!("p{}", i);
            let x = &vs[i];
            // The argument moves into the callee's frame: the branch that
            // pushes the frame ends the visit, and the machine's call
            // below (the other branch) reads `v<i>` itself.
            let e = coerce(
                &V {
                    e: quote!(#x),
                    ty: v.ty.clone(),
                },
                ty,
            )?;
            inits.push(quote!(#p: #e));
        }
        for (i, ((_, default), (_, ty))) in ir.dms[plan.j]
            .locals
            .iter()
            .zip(&plan.callee.locals)
            .enumerate()
        {
            let l = format_ident!("l{}", i);
            let v = self.nat_value(&Build::Const(*default), &Regs::new())?;
            let e = coerce(&v, ty)?;
            inits.push(quote!(#l: #e));
        }
        let wv = wait_variant(ix);
        let mut wf = Vec::new();
        for (r, _) in self.nat_wait_fields(d, ix)? {
            let v = self.nat_value(&Build::Reg(r), regs)?;
            // The visit ends here: its own registers move into the
            // waiting variant (not cloned and dropped).
            let (rr, e) = (reg(r), super::moved(&v));
            wf.push(quote!(#rr: #e));
        }
        Ok(quote! {
            #(#lets)*
            // The callee's frame on the native stack, within the depth
            // limit, when no history is kept or observed (else the machine
            // pushes it: the callee's entries nest in the caller's).
            if !run.records && stack.len() < cx.depth_room() {
                let callee = super::#callee_f { #(#inits,)* at: super::#callee_n::S0 {} };
                *call = Some(super::NatFrame::#callee_v(callee));
                done = true;
                break 'visit Nat::#wv { #(#wf),* };
            }
            #hand_call
        })
    }

    /// The call of recursive situation `ix` given to the machine as the
    /// term code gives it, its term built from native values and the
    /// fresh variables made for the visit (`fresh_r<r>`, terms).
    fn nat_call_on_terms(&self, d: &Dm, ix: usize, regs: &Regs) -> N<TokenStream> {
        let KindPlan::Recursive {
            call,
            eval_call,
            saved,
            ..
        } = &d.plans[ix].kind
        else {
            return Err("not a recursive situation".into());
        };
        // Evaluated as the term code evaluates it (`Cx::embedded_dm`: the
        // evaluator and user functions at this boundary, on the term built
        // from native values), in the situation entered.
        let evaluated = *eval_call && (matches!(call, Build::Const(_)) || !inert(call));
        let curl = Literal::u32_unsuffixed(ix as u32);
        let hand = &d.hand;
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let mut ts = Vec::new();
        let mut n = 0;
        let call_t = self.nat_build_term(call, regs, &mut ts, &mut n)?;
        let eval = if evaluated {
            quote!(let call = cx.embedded_dm(call)?;)
        } else {
            quote!()
        };
        let mut saved_vals = Vec::new();
        for &r in saved.iter() {
            match regs.get(&r) {
                Some((f, _)) if super::is_fresh(f) => saved_vals.push(quote!(#f)),
                _ => saved_vals.push(super::place(&self.nat_value(&Build::Reg(r), regs)?)),
            }
        }
        let saved_value = if saved.is_empty() {
            quote!(Term::NIL)
        } else {
            quote!(cx.compound_of(atoms::DOT, &[#(&#saved_vals),*]))
        };
        Ok(quote! {
            #hand
            cx.count_transitions(count);
            #(#id_stmts)*
            cx.enter_with_id(#curl, #id);
            #(#ts)*
            let call = #call_t;
            #eval
            let saved = #saved_value;
            return Ok(Some(
                Step::Call { call, saved },
            ));
        })
    }

    /// The waiting variant of situation `ix` when it is recursive.
    pub(super) fn nat_wait_variant(&self, d: &Dm, ix: usize) -> N<Option<Wait>> {
        let KindPlan::Recursive { saved, .. } = &d.plans[ix].kind else {
            return Ok(None);
        };
        let wv = wait_variant(ix);
        let fields = self.nat_wait_fields(d, ix)?;
        let decls = fields
            .iter()
            .map(|(r, ty)| {
                let (r, ty) = (reg(*r), rust_ty(ty)?);
                Ok(quote!(#r: #ty))
            })
            .collect::<N<Vec<_>>>()?;
        let names: Vec<Ident> = fields.iter().map(|(r, _)| reg(*r)).collect();
        let doc = format!(
            " `{}` waiting for its embedded DM",
            self.store.writeq(self.nat_id_of(d, ix))
        );
        let variant = quote!(#[doc = #doc] #wv { #(#decls),* },);
        let id = self.nat_id_value(d, ix, quote!(store))?;
        let id_arm = quote!(Nat::#wv { #(#names),* } => #id,);
        let exit_arm = match self.nat_call_plan(d, ix) {
            Some(plan) => {
                let exit = plan.exit;
                quote!(Nat::#wv { #(#names),* } => 'visit: { #exit })
            }
            None => quote!(),
        };
        // In `nat_wait` (fields are references there).
        let curl = Literal::u32_unsuffixed(ix as u32);
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let mut saved_vals = Vec::new();
        for &r in saved.iter() {
            let rr = reg(r);
            if names.contains(&rr) {
                saved_vals.push(quote!(#rr));
            } else {
                return Err("a saved register is not kept".into());
            }
        }
        let saved_value = if saved.is_empty() {
            quote!(Term::NIL)
        } else {
            quote!(cx.compound_of(atoms::DOT, &[#(#saved_vals),*]))
        };
        let wait_arm = quote! {
            Nat::#wv { #(#names),* } => {
                #(#id_stmts)*
                cx.enter_with_id(#curl, #id);
                let saved = #saved_value;
                cx.call_typed(callee_dm, callee, saved)
            }
        };
        Ok(Some(Wait {
            variant,
            id_arm,
            exit_arm,
            wait_arm,
        }))
    }

    /// The exit arcs of recursive situation `ix` on the final variant of
    /// callee `callee` (DM `j`) in `ret`: evaluates to the next `Nat` (or
    /// returns, handing over).
    fn nat_exit(&self, d: &Dm, ix: usize, callee: &Dm, j: usize) -> N<TokenStream> {
        let KindPlan::Recursive { exit, .. } = &d.plans[ix].kind else {
            return Err("not a recursive situation".into());
        };
        let mut regs = Regs::new();
        for (r, ty) in self.nat_wait_fields(d, ix)? {
            regs.insert(r, (reg(r), ty));
        }
        let head = self.nat_head_regs(d, ix, &mut regs)?;
        let hand = &d.hand;
        let curl = Literal::u32_unsuffixed(ix as u32);
        let cur_name = self.atom_native(d.plans[ix].id.0)?;
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let callee_v = format_ident!("D{}", j);
        let callee_n = format_ident!("NatN{}", j);
        let mut final_arms = Vec::new();
        for k in 0..callee.plans.len() {
            // Only a final situation the callee hands back as its `Nat`
            // variant reaches these arms: one without native code, or with
            // a `diag_mod` (the machine takes it, see `native_visit`), goes
            // to the machine, which returns to the caller's term code. Its
            // variant may not exist (an application of the original's
            // tree: `see_body`'s finals with `diag_mod`, issue 37).
            let diag_mod = matches!(&callee.plans[k].kind, KindPlan::Final { diag_mod: Some(_) });
            if callee.dm.situations[k].kind != Kind::Final || !callee.native[k] || diag_mod {
                continue;
            }
            let fields = self.nat_fields(callee, k)?;
            let cf: Vec<TokenStream> = fields
                .iter()
                .map(|(r, _)| {
                    let (rr, c) = (reg(*r), format_ident!("c{}", r));
                    quote!(#rr: #c)
                })
                .collect();
            let pat = self.nat_id_of(callee, k);
            let mut arcs_code = Vec::new();
            for (i, arc) in exit.arcs.iter().enumerate() {
                if arc.diag_mod.is_some() {
                    return Err("an exit arc has diag_mod".into());
                }
                let b = ev_as_build(&arc.expectation)
                    .ok_or("an exit arc's expectation is evaluated")?;
                let b = &b;
                let mut regs = regs.clone();
                for (n, from) in arc.import_from.iter().enumerate() {
                    if let Some(at) = regs.get(from).cloned() {
                        regs.insert(arc.import_at + n as Reg, at);
                    }
                }
                let mut tests = Vec::new();
                let mut lets = Vec::new();
                let mut vars = HashMap::new();
                let fresh: Vec<Reg> = arc.fresh.clone();
                if !self.nat_unify(
                    d,
                    ix,
                    callee,
                    k,
                    b,
                    pat,
                    &mut Vec::new(),
                    &fresh,
                    &mut regs,
                    &mut vars,
                    &mut tests,
                    &mut lets,
                )? {
                    continue; // never this arc for this final
                }
                let action = self.nat_exit_action(d, ix, i, &arc.action, &mut regs)?;
                // The callee ran since the pipe was read: an out_arg writes
                // the saved value back ([`Dm::pipe_in`] is the visit's).
                let pipe_in = d.pipe_in.take();
                let next =
                    self.nat_next_out(d, ix, &arc.next, arc.out_arg.as_ref(), &regs, &cur_name);
                d.pipe_in.set(pipe_in);
                let next = next?;
                let cond = if tests.is_empty() {
                    quote!(true)
                } else {
                    quote!(#(#tests)&&*)
                };
                let il = Literal::usize_unsuffixed(i);
                arcs_code.push(quote! {
                    if #cond {
                        let arc_at = Some(#il);
                        #(#lets)*
                        #action
                        count += 1;
                        let next_at = { #next };
                        break 'visit next_at;
                    }
                });
            }
            let sk = format_ident!("S{}", k);
            final_arms.push(quote! {
                super::#callee_n::#sk { #(#cf),* } => {
                    #(#arcs_code)*
                }
            });
        }
        let body = quote! {
            let super::NatFrame::#callee_v(done_frame) = ret else {
                return Err(cx.error(
                    "native code resumed a caller with another DM's frame",
                    None,
                ));
            };
            let final_at = &done_frame.at;
            match &final_at {
                #(#final_arms)*
                _ => {}
            }
            // No exit arc takes the final situation: the machine says so.
            #hand
            cx.count_transitions(count);
            #(#id_stmts)*
            cx.enter_with_id(#curl, #id);
            let final_id = final_at.id_term(p, cx.store());
            cx.set_expectations(&[]);
            return match cx.choose_exit(final_id) {
                Err(e) => Err(e),
                Ok(_) => Err(cx.error(
                    "native exit arcs disagree with the machine's",
                    None,
                )),
            };
        };
        // Only the parameters the exit arcs read are loaded (a load is a
        // clone: a list's count changed and changed back on every return).
        let head = head
            .into_iter()
            .filter(|(r, _)| mentions(&body, r))
            .map(|(_, stmt)| stmt);
        Ok(quote!(#(#head)* #body))
    }

    /// Unifies the expectation `b` (the caller's registers, fresh or set)
    /// with the callee's final id `pat` at `path` (its variables the
    /// variant's fields `c<r>`, references): tests and bindings pushed;
    /// `false` when they never unify.
    #[allow(clippy::too_many_arguments)]
    fn nat_unify(
        &self,
        d: &Dm,
        ix: usize,
        callee: &Dm,
        k: usize,
        b: &Build,
        pat: Term,
        path: &mut Vec<usize>,
        fresh: &[Reg],
        regs: &mut Regs,
        vars: &mut HashMap<u32, V>,
        tests: &mut Vec<TokenStream>,
        lets: &mut Vec<TokenStream>,
    ) -> N<bool> {
        // The callee's side as a value, when it is a variable or atomic.
        let side: Option<V> = match self.store.value(pat) {
            Value::Var(v) => Some(match vars.get(&v.index()) {
                Some(x) => x.clone(),
                None => {
                    let r = Self::nat_id_reg(callee, k, path)
                        .ok_or("a final's id variable has no register")?;
                    let c = format_ident!("c{}", r);
                    let x = V {
                        e: quote!(#c.clone()),
                        ty: callee.types[k].regs[r as usize].ty.clone(),
                    };
                    vars.insert(v.index(), x.clone());
                    x
                }
            }),
            Value::Atom(_) | Value::Int(_) => {
                Some(self.nat_value(&Build::Const(pat), &Regs::new())?)
            }
            _ => None,
        };
        match b {
            Build::Reg(r) if fresh.contains(r) && !regs.contains_key(r) => {
                // A fresh variable of the arc takes the value.
                let side = side.ok_or("an exit arc's variable takes a compound")?;
                let ty = d.types[ix].regs[*r as usize].ty.clone();
                let e = coerce(&side, &ty)?;
                let rr = reg(*r);
                lets.push(quote!(let #rr = #e;));
                regs.insert(*r, (rr, ty));
                Ok(true)
            }
            Build::Reg(r) => {
                let mine = self.nat_value(&Build::Reg(*r), regs)?;
                let side = side.ok_or("an exit arc's value against a compound")?;
                tests.push(identical(&mine, &side).ok_or("`==` of these types")?);
                Ok(true)
            }
            Build::Const(c) => match (self.store.value(*c), self.store.value(pat)) {
                (Value::Var(_), _) => Err("a variable constant".into()),
                (_, Value::Var(_)) => {
                    let mine = self.nat_value(&Build::Const(*c), regs)?;
                    let side = side.ok_or("no value")?;
                    tests.push(identical(&mine, &side).ok_or("`==` of these types")?);
                    Ok(true)
                }
                (Value::Compound(n1, a1), Value::Compound(n2, a2)) => {
                    if n1 != n2 || a1.len() != a2.len() {
                        return Ok(false);
                    }
                    let (a1, a2) = (a1.to_vec(), a2.to_vec());
                    for (i, (x, y)) in a1.into_iter().zip(a2).enumerate() {
                        path.push(i);
                        let ok = self.nat_unify(
                            d,
                            ix,
                            callee,
                            k,
                            &Build::Const(x),
                            y,
                            path,
                            fresh,
                            regs,
                            vars,
                            tests,
                            lets,
                        )?;
                        path.pop();
                        if !ok {
                            return Ok(false);
                        }
                    }
                    Ok(true)
                }
                (Value::Compound(..), _) | (_, Value::Compound(..)) => Ok(false),
                _ => Ok(self.store.identical(*c, pat)),
            },
            Build::Compound(name, args) => match self.store.value(pat) {
                Value::Compound(n2, a2) => {
                    if *name != n2 || args.len() != a2.len() {
                        return Ok(false);
                    }
                    let a2 = a2.to_vec();
                    for (i, (x, y)) in args.iter().zip(a2).enumerate() {
                        path.push(i);
                        let ok = self.nat_unify(
                            d, ix, callee, k, x, y, path, fresh, regs, vars, tests, lets,
                        )?;
                        path.pop();
                        if !ok {
                            return Ok(false);
                        }
                    }
                    Ok(true)
                }
                Value::Var(_) => Err("a compound expectation against a variable".into()),
                _ => Ok(false),
            },
        }
    }

    /// An exit arc's action (and a perceptual or neutral arc's, when it
    /// has only these): `inc`/`get` of a local into a fresh variable,
    /// `V is E` of ints into a fresh variable, atoms and numbers performed
    /// (skipped where the run's actions ignore them).
    pub(super) fn nat_exit_action(
        &self,
        d: &Dm,
        ix: usize,
        arc_ix: usize,
        action: &Action,
        regs: &mut Regs,
    ) -> N<TokenStream> {
        let hand = &d.hand;
        let curl = Literal::u32_unsuffixed(ix as u32);
        let arc = Literal::usize_unsuffixed(arc_ix);
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let enter = quote! {
            #hand
            #(#id_stmts)*
            cx.enter_counted(&mut count, #curl, #id);
        };
        let mut stmts = Vec::new();
        let mut performs = Vec::new();
        let items: Vec<&Ev> = match action {
            Action::List { items, .. } => items.iter().collect(),
            Action::One(e) => vec![e],
        };
        let list = matches!(action, Action::List { .. });
        for (n, item) in items.into_iter().enumerate() {
            let x = format_ident!("act{}", n);
            let ty = match item {
                Ev::VarOpFresh { op, name, dst } => {
                    let li = d
                        .locals
                        .iter()
                        .position(|(l, _)| l == name)
                        .ok_or("`inc`/`get` of a global")?;
                    let l = format_ident!("l{}", li);
                    let lty = d.locals[li].1.clone();
                    let dty = d.types[ix].regs[*dst as usize].ty.clone();
                    let opa = self.atom_native(*op)?;
                    let namea = self.atom_native(*name)?;
                    let value = if *op == atoms::INC && lty == Ty::Int {
                        quote! {
                            match #l.checked_add(1) {
                                Some(v) => { *#l = v; v }
                                None => {
                                    #enter
                                    return match cx.var_op_fresh(#opa, #namea, Some(#arc)) {
                                        Err(e) => Err(e),
                                        Ok(_) => Err(cx.error(
                                            "`inc` overflowed in native code only",
                                            None,
                                        )),
                                    };
                                }
                            }
                        }
                    } else if *op == atoms::GET {
                        quote!(#l.clone())
                    } else {
                        return Err("a variable operation is not native".into());
                    };
                    let e = coerce(
                        &V {
                            e: quote!(#x.clone()),
                            ty: lty.clone(),
                        },
                        &dty,
                    )?;
                    stmts.push(quote!(let #x = #value;));
                    let rr = reg(*dst);
                    stmts.push(quote!(let #rr = #e;));
                    regs.insert(*dst, (rr, dty));
                    lty
                }
                // `J is I + 1` into a fresh variable that inference types
                // `int` (so its operands are ints): checked `i64`
                // arithmetic as in a native `prog`; an overflow is the
                // machine's evaluation (its value, if native code can hold
                // it, else an error, as `nat_prog` does).
                Ev::IsFresh { expr, dst } if d.types[ix].regs[*dst as usize].ty == Ty::Int => {
                    let e = self.nat_int_expr(expr, regs)?;
                    let mut ts = Vec::new();
                    let mut n = 0;
                    let t = self.nat_build_term(expr, regs, &mut ts, &mut n)?;
                    stmts.push(quote! {
                        let #x: i64 = match #e {
                            Some(v) => v,
                            None => {
                                #enter
                                #(#ts)*
                                let v = cx.is(None, #t, Some(#arc))?;
                                let v = cx.store_ref().deref(v);
                                match cx.to_native::<i64>(v) {
                                    Some(v) => v,
                                    None => {
                                        return Err(cx.error(
                                            "`is` gave a value native code cannot hold",
                                            Some(#arc),
                                        ))
                                    }
                                }
                            }
                        };
                    });
                    let rr = reg(*dst);
                    stmts.push(quote!(let #rr = #x;));
                    regs.insert(*dst, (rr, Ty::Int));
                    Ty::Int
                }
                Ev::Built(Build::Const(t)) => {
                    let v = self.nat_value(&Build::Const(*t), regs)?;
                    let e = v.e;
                    stmts.push(quote!(let #x = #e;));
                    v.ty
                }
                Ev::Value(r) => {
                    let v = self.nat_value(&Build::Reg(*r), regs)?;
                    let e = v.e;
                    stmts.push(quote!(let #x = #e;));
                    v.ty
                }
                _ => return Err("an exit arc's action is not native".into()),
            };
            let perform = if list {
                quote! {
                    #enter
                    let t = cx.term(&#x);
                    cx.perform_each(&[t], Some(#arc))?;
                }
            } else {
                quote! {
                    #enter
                    let t = cx.term(&#x);
                    cx.perform(t, Some(#arc))?;
                }
            };
            performs.push(match ty {
                Ty::Int | Ty::Float => quote!(if !run.quiet_numbers { #perform }),
                Ty::Sym => quote! {
                    if !(run.quiet_empty && #x == atoms::EMPTY) { #perform }
                },
                Ty::Term | Ty::List(_) => perform,
                _ => return Err("an action of this type".into()),
            });
        }
        Ok(quote!(#(#stmts)* #(#performs)*))
    }

    /// `l op r` on numbers: in Rust when both are ints or both floats (a
    /// ground term or a `Val` read as one), else evaluated on terms as the
    /// term code does (the machine entered in situation `cur`: its result
    /// or its error; an int against a float goes there too).
    pub(super) fn nat_arith(&self, d: &Dm, cur: usize, op: ArithCmp, l: V, r: V) -> N<TokenStream> {
        let rt = quote!(::sitlog_runtime);
        let some = quote!(Some);
        let none = quote!(None::<i64>);
        // `cl`, `cr`: references to the operands where they are (no clone
        // of a `Val` to read an int from it).
        let as_int = |v: &V, x: &Ident| -> N<TokenStream> {
            Ok(match v.ty {
                Ty::Int => quote!(#some(*#x)),
                Ty::Float => none.clone(),
                Ty::Term => quote!(cx.store_ref().int_of(#x.0)),
                // A `Val` (`ground`: a parameter, the pipe) holding an int.
                ref t if super::held_as_val(t) => quote!(#x.int()),
                _ => return Err("an arithmetic comparison is not on numbers".into()),
            })
        };
        let nonef = quote!(None::<f64>);
        let as_float = |v: &V, x: &Ident| -> TokenStream {
            match v.ty {
                Ty::Float => quote!(#some(*#x)),
                Ty::Term => quote!(cx.store_ref().float_of(#x.0)),
                ref t if super::held_as_val(t) => quote! {
                    match #x { Val::Float(f) => #some(*f), _ => #nonef }
                },
                _ => nonef.clone(),
            }
        };
        let (lx, rx) = (format_ident!("cl"), format_ident!("cr"));
        if (l.ty == Ty::Int && r.ty == Ty::Int) || (l.ty == Ty::Float && r.ty == Ty::Float) {
            let (le, re) = (l.e, r.e);
            return Ok(cmp_tokens(op, quote!(#le), quote!(#re)));
        }
        let (li, ri) = (as_int(&l, &lx)?, as_int(&r, &rx)?);
        let (lf, rf) = (as_float(&l, &lx), as_float(&r, &rx));
        let cmp = cmp_tokens(op, quote!(x), quote!(y));
        let hand = &d.hand;
        let curl = Literal::u32_unsuffixed(cur as u32);
        let (id_stmts, id) = self.nat_id_term(d, cur, quote!(cx.store()))?;
        let opt = match op {
            ArithCmp::Eq => quote!(Eq),
            ArithCmp::Ne => quote!(Ne),
            ArithCmp::Lt => quote!(Lt),
            ArithCmp::Gt => quote!(Gt),
            ArithCmp::Le => quote!(Le),
            ArithCmp::Ge => quote!(Ge),
        };
        let (lp, rp) = (super::place(&l), super::place(&r));
        let (lt, rt_) = (rust_ty(&l.ty)?, rust_ty(&r.ty)?);
        Ok(quote! {{
            let #lx: &#lt = &#lp;
            let #rx: &#rt_ = &#rp;
            match (#li, #ri, #lf, #rf) {
                (#some(x), #some(y), _, _) => #cmp,
                (_, _, #some(x), #some(y)) => #cmp,
                _ => {
                    // Not two ints: the term code's evaluation decides. The
                    // arc's own transition (counted before its next
                    // situation when nothing is recorded; recorded, its
                    // entry counts it) is not the machine's until that
                    // succeeds.
                    #hand
                    let own = u64::from(!run.records);
                    cx.count_transitions(count.saturating_sub(own));
                    count = own.min(count);
                    #(#id_stmts)*
                    cx.enter_with_id(#curl, #id);
                    let lt = cx.term(#lx);
                    let rterm = cx.term(#rx);
                    cx.arith_condition(#rt::ArithCmp::#opt, lt, rterm, arc_at)?
                }
            }
        }})
    }
}

fn cmp_tokens(op: ArithCmp, l: TokenStream, r: TokenStream) -> TokenStream {
    match op {
        ArithCmp::Eq => quote!((#l == #r)),
        ArithCmp::Ne => quote!((#l != #r)),
        ArithCmp::Lt => quote!((#l < #r)),
        ArithCmp::Gt => quote!((#l > #r)),
        ArithCmp::Le => quote!((#l <= #r)),
        ArithCmp::Ge => quote!((#l >= #r)),
    }
}

/// An expectation that evaluates to itself (`found(P)`), as a term built
/// from registers; `None` when evaluating it may do more.
fn ev_as_build(e: &Ev) -> Option<Build> {
    fn copy(b: &Build) -> Build {
        match b {
            Build::Const(t) => Build::Const(*t),
            Build::Reg(r) => Build::Reg(*r),
            Build::Compound(n, args) => Build::Compound(*n, args.iter().map(copy).collect()),
        }
    }
    match e {
        Ev::Built(b) => Some(copy(b)),
        Ev::Value(r) => Some(Build::Reg(*r)),
        Ev::Compound(n, args) => Some(Build::Compound(
            *n,
            args.iter().map(ev_as_build).collect::<Option<_>>()?,
        )),
        _ => None,
    }
}

/// Whether generated code `ts` mentions the identifier `x`.
pub(super) fn mentions(ts: &TokenStream, x: &Ident) -> bool {
    ts.clone().into_iter().any(|t| match t {
        proc_macro2::TokenTree::Ident(i) => i == *x,
        proc_macro2::TokenTree::Group(g) => mentions(&g.stream(), x),
        _ => false,
    })
}

/// Whether evaluating the call term gives it back (built from values).
fn inert(b: &Build) -> bool {
    match b {
        Build::Const(_) | Build::Reg(_) => true,
        Build::Compound(name, args) => {
            sitlog_runtime::eval::evaluates_arguments_only(*name, args.len())
                && args.iter().all(inert)
        }
    }
}
