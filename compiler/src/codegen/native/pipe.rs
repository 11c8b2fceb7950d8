//! The pipe in native code: the machine keeps the pipe as a term (it is
//! the one value every DM of the stack shares); native code reads it into
//! a register of the type `mir::ty` gives the in_arg's variable (a checked
//! conversion; an int or an atom costs no allocation) and writes an
//! out_arg's value back as a term, where the term code does (an arc's
//! out_arg after its next situation is evaluated, a final's out_arg). An
//! arc's out_arg that hands back the in_arg's own value in the visit that
//! read it (`in_arg ==> X, out_arg ==> X`) sets the pipe to the term read,
//! dereferenced (what the term code's evaluated `X` is), not to the value
//! converted back: `Cx::pipe_deref`, the pipe dereferenced where it is
//! (nothing sets it between a visit's in_arg and its out_arg); a visit whose code reads the in_arg's
//! register nowhere else only checks that the pipe converts (the same
//! hand-over), keeping no value.
//!
//! An arc's out_arg is evaluated (`mir::ArcPlan::out_arg`, an `Ev`): a
//! conditional `(X > 0 -> X ; otherwise -> 1)` of native branches is a
//! Rust `if` computed before the next situation (`Gen::nat_out_value`);
//! one the evaluator computes (`apply(f(_), [X])`, `get(g, _)` of a
//! global) is built from native values and evaluated after the next
//! situation, the machine entered (`Gen::nat_next_out_eval`); one with a
//! `get(v, _)`/`inc(v, _)` of the frame's local or a global is computed
//! by native code after the next situation, and by the machine where the
//! next situation is handed over: once on every way
//! (`Gen::nat_next_out_after`).
//!
//! An arc's out_arg that is a variable of the arc nothing binds
//! (`mir::OutPass::Unchanged`: `out_arg ==> R1` with an exit arc
//! `error(E) : say(..) => rest` that leaves `R1` unbound) is no out_arg
//! here ([`arc_out`]): the pipe passes on unchanged (D-18), in a recursive
//! situation the one its embedded DM handed back (D-22); a final's the
//! same (`SitPlan::final_out_pass`). Without this such an arc failed to
//! generate (its register read unset) and its situation ran from its
//! template at every visit (`r24_d_gauge_guard`).
//!
//! An in_arg that is a pattern (`N-L`, `f(A, [B|C])`) is matched where the
//! pipe's term is (`Gen::nat_pipe_match`): its variables become registers
//! of the visit, and a pipe it does not take natively hands the visit to
//! the machine, nothing done, which runs it from the template (a mismatch
//! is skipped there with a warning, D-8, `Options::skip_unmatched_in_arg`,
//! or the machine's error under `--deny-warnings`, E14). In a recursive
//! situation the pattern's variables the exit arcs or the call read are
//! fields of its waiting variant; a waiting frame made the machine's
//! gives its instance the pattern built from them (`nat_in_arg_term`,
//! module `call`), which unifies as the pipe did.
//!
//! The pipe held as native values (`npipe15`): an out_arg `name(A, ..)`
//! of at most `HELD_MAX` arguments, each an int, a float, an atom or a
//! `ground` value, is not made a term: `Cx::hold_pipe` keeps the values
//! (`Gen::nat_out_held`), the machine's pipe term a mark meanwhile. A
//! pattern `name(..)` of variables and atom or int constants reads them
//! there (`Cx::held_pipe`, `Gen::nat_held_match`), as the term path reads
//! the parts; any other reader makes the term first (`Cx::pipe_in`,
//! `Cx::flush_pipe`), and so does the machine when compiled code returns
//! (a hand-over, the end of the run, an error): the term is the one
//! `build_of` of the values makes, so the machine, its history and its
//! report see what they saw when the pipe was built at once.
//!
//! An out_arg that is one value of a list of `Val`s or a `Val` held as it
//! is (`out_arg ==> Acc`, the list a walk accumulated: `held_whole`) is
//! held whole (`Cx::hold_pipe_value`, the `Rc` shared): the term, a cell
//! per element, made only where something reads the pipe as one (the
//! final that takes the last round's list), not at every call.
//!
//! An in_arg that reads the whole pipe into a register (`in_arg ==> L`)
//! reads a held pipe where it is (`Cx::pipe_as`, `Cx::pipe_converts`,
//! `npipe25`): the value held whole or the compound of the held values,
//! converted by `Native::from_held` (a list of `Val`s shared), no term
//! made and none converted back; the pipe stays held. Where `from_held`
//! cannot tell, the term is made and converted as before.
//!
//! A pipe value that does not convert hands the situation over to the
//! machine before anything of its visit is done (its term code runs it);
//! where the machine enters native code, `nat_entry` checks the
//! conversion first and leaves that situation to its term code, so a
//! hand-over never comes back to native code that would hand over again.

use super::{reg, Dm, Gen, Regs, N, V};
use crate::mir::{Build, Cond, Ev, Init, Next, Reg};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::native::Ty;
use sitlog_syntax::atoms;

impl Gen<'_> {
    /// `let r<r> = <the pipe as ty>;`, else the situation handed over.
    /// In a visit that never reads `r<r>` ([`Dm::pipe_unread`]: the pipe
    /// only handed back as read, `pipe_in`, or not used) the conversion
    /// is only checked, no value kept: the same hand-over for a pipe that
    /// does not convert (not ground, or one the term code would evaluate,
    /// `1 + 1`), no value built, moved or dropped.
    pub(super) fn nat_pipe_in(&self, d: &Dm, ix: usize, r: Reg, ty: &Ty) -> N<TokenStream> {
        let rty = super::rust_ty(ty)?;
        let rr = reg(r);
        let hand = &d.hand;
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let _ = Literal::u32_unsuffixed(ix as u32);
        if d.pipe_unread.get() {
            return Ok(quote! {
                if !cx.pipe_converts::<#rty>() {
                    // Not of the in_arg's type: the term code runs the visit.
                    #hand
                    cx.count_transitions(count);
                    #(#id_stmts)*
                    return Ok(Some(
                        Step::Goto(#id),
                    ));
                }
            });
        }
        Ok(quote! {
            let pipe_value = cx.pipe_as::<#rty>();
            let Some(#rr) = pipe_value else {
                // Not of the in_arg's type: the term code runs the visit.
                #hand
                cx.count_transitions(count);
                #(#id_stmts)*
                return Ok(Some(
                    Step::Goto(#id),
                ));
            };
        })
    }

    /// An in_arg that is a pattern (`in_arg ==> N-L`, `f(A, [B|C])`)
    /// unified with the pipe, natively: the pipe's term taken apart where
    /// it is (`Store::compound_args`, no value built for the whole), each
    /// variable met first converted to its register's type (`mir::ty`
    /// types it by the pipe's type there), a constant, a variable met
    /// again or one the visit already holds (the id's, a parameter's)
    /// compared with `==` (Prolog's `==` on ground values, which is their
    /// unification), a variable met only here (`_`) not read. Anything
    /// else (another shape, a part not of its type or not ground) hands
    /// the visit to the machine before anything of it is done: it runs it
    /// from the situation's template, unifying as the interpreter does,
    /// and a pipe the pattern does not match is skipped there (D-8) or,
    /// under `--deny-warnings`, its error (E14). The pattern's
    /// variables are registers of the visit.
    pub(super) fn nat_pipe_match(
        &self,
        d: &Dm,
        ix: usize,
        pat: &Build,
        regs: &mut Regs,
    ) -> N<TokenStream> {
        let mut body = Vec::new();
        let mut bound = Vec::new();
        let mut n = 0;
        self.nat_match_part(
            d,
            ix,
            pat,
            quote!(pipe_in),
            regs,
            &mut bound,
            &mut body,
            &mut n,
            0,
        )?;
        let names: Vec<_> = bound.iter().map(|(r, _)| reg(*r)).collect();
        let held = self.nat_held_match(pat, regs, &bound)?;
        for (r, ty) in bound {
            regs.insert(r, (reg(r), ty));
        }
        let to_template = self.nat_to_template(d, ix)?;
        let by_term = quote! {
            let pipe_in = cx.pipe_in();
            (|| {
                let s = cx.store_ref();
                #(#body)*
                Some((#(#names,)*))
            })()
        };
        let parts = match held {
            // The pipe native code holds as `name(..)` of this arity: its
            // values read where they are, no term.
            Some((f, len, held)) => quote! {
                match cx.held_pipe::<#len>(#f) {
                    Some(h) => (|| {
                        #(#held)*
                        Some((#(#names,)*))
                    })(),
                    None => { #by_term }
                }
            },
            None => quote!({ #by_term }),
        };
        Ok(quote! {
            let pipe_parts = #parts;
            let Some((#(#names,)*)) = pipe_parts else {
                // Not matched natively: the machine runs the visit.
                #to_template
            };
        })
    }

    /// [`Gen::nat_pipe_match`] against the pipe native code holds
    /// (`Cx::held_pipe`): for a pattern `name(..)` of at most `HELD_MAX`
    /// arguments, each a variable of a type a `Val` gives back
    /// (`FromVal`: an int, a float, an atom, a `ground` value) or an atom
    /// or int constant, the statements that read the held values `h[i]`
    /// as the term path reads the parts (binding `bound`, in its order),
    /// with the functor and arity; `None` for any other pattern (read from
    /// the pipe's term only).
    fn nat_held_match(
        &self,
        pat: &Build,
        regs: &Regs,
        bound: &[(Reg, Ty)],
    ) -> N<Option<(TokenStream, Literal, Vec<TokenStream>)>> {
        let Build::Compound(f, args) = pat else {
            return Ok(None);
        };
        if args.is_empty() || args.len() > sitlog_runtime::machine::HELD_MAX {
            return Ok(None);
        }
        let mut body = Vec::new();
        let mut met: Vec<Reg> = Vec::new();
        for (i, a) in args.iter().enumerate() {
            let i = Literal::usize_unsuffixed(i);
            let v = quote!((&h[#i]));
            match a {
                Build::Reg(r) => {
                    // Bound by the term path's order, met here so far.
                    let so_far = bound.iter().filter(|(x, _)| met.contains(x));
                    match held_reg(regs, so_far, *r) {
                        Some((x, ty)) => {
                            if !held_part(&ty) {
                                return Ok(None);
                            }
                            let rty = super::rust_ty(&ty)?;
                            let held = quote!((*::std::borrow::Borrow::<#rty>::borrow(&#x)));
                            body.push(if ty == Ty::Float {
                                quote! {
                                    if <f64 as FromVal>::from_val(#v)?.to_bits() != #held.to_bits() {
                                        return None;
                                    }
                                }
                            } else {
                                quote! {
                                    if <#rty as FromVal>::from_val(#v)? != #held {
                                        return None;
                                    }
                                }
                            });
                        }
                        // Met first here (one met only here, `_`, is not read).
                        None => {
                            if let Some((_, ty)) = bound.iter().find(|(x, _)| x == r) {
                                if !held_part(ty) {
                                    return Ok(None);
                                }
                                let rty = super::rust_ty(ty)?;
                                let x = reg(*r);
                                body.push(quote!(let #x = <#rty as FromVal>::from_val(#v)?;));
                                met.push(*r);
                            }
                        }
                    }
                }
                Build::Const(c) => match self.store.value(*c) {
                    sitlog_runtime::Value::Atom(a) => {
                        let a = self.atom_native(a)?;
                        body.push(quote! {
                            if #v.sym() != Some(#a) {
                                return None;
                            }
                        });
                    }
                    sitlog_runtime::Value::Int(n) => {
                        let n = Literal::i64_suffixed(n);
                        body.push(quote! {
                            if #v.int() != Some(#n) {
                                return None;
                            }
                        });
                    }
                    _ => return Ok(None),
                },
                Build::Compound(..) => return Ok(None),
            }
        }
        if met != bound.iter().map(|(r, _)| *r).collect::<Vec<_>>() {
            return Ok(None);
        }
        let fname = self.functor_native(*f)?;
        Ok(Some((fname, Literal::usize_unsuffixed(args.len()), body)))
    }

    /// [`Gen::nat_pipe_match`] of the part `pat` of the pattern against
    /// the term `t` (an identifier of the closure that matches): its
    /// statements in `body` (`return None` where it does not match), the
    /// registers it binds in `bound`.
    #[allow(clippy::too_many_arguments)]
    fn nat_match_part(
        &self,
        d: &Dm,
        ix: usize,
        pat: &Build,
        t: TokenStream,
        regs: &Regs,
        bound: &mut Vec<(Reg, Ty)>,
        body: &mut Vec<TokenStream>,
        n: &mut usize,
        depth: usize,
    ) -> N<()> {
        if depth > crate::mir::MAX_DEPTH {
            return Err("an in_arg pattern too deep".into());
        }
        match pat {
            Build::Reg(r) => {
                let held = held_reg(regs, bound.iter(), *r);
                let init = d.plans[ix]
                    .inits
                    .iter()
                    .find(|(x, _)| x == r)
                    .map(|(_, i)| i);
                match held {
                    // Held already: compared (unified, both ground).
                    Some((x, ty)) => {
                        let rty = super::rust_ty(&ty)?;
                        let held = quote!((*::std::borrow::Borrow::<#rty>::borrow(&#x)));
                        body.push(match ty {
                            Ty::Float => quote! {
                                if cx.to_native::<f64>(#t)?.to_bits() != #held.to_bits() {
                                    return None;
                                }
                            },
                            Ty::Int | Ty::Sym | Ty::List(_) => quote! {
                                if cx.to_native::<#rty>(#t)? != #held {
                                    return None;
                                }
                            },
                            t2 if super::held_as_val(&t2) => quote! {
                                if cx.to_native::<#rty>(#t)? != #held {
                                    return None;
                                }
                            },
                            _ => return Err("an in_arg pattern's variable held as a term".into()),
                        });
                    }
                    None if !matches!(init, Some(Init::Fresh)) => {
                        return Err("an in_arg pattern's variable is not held".into());
                    }
                    // Met only here (`_`): matches anything, not read.
                    None if d.types[ix]
                        .unbound
                        .get(*r as usize)
                        .copied()
                        .unwrap_or(false) => {}
                    None => {
                        let ty = d.types[ix].regs[*r as usize].ty.clone();
                        let rty = super::rust_ty(&ty)?;
                        let x = reg(*r);
                        body.push(quote!(let #x = cx.to_native::<#rty>(#t)?;));
                        bound.push((*r, ty));
                    }
                }
            }
            Build::Const(c) => match self.store.value(*c) {
                sitlog_runtime::Value::Atom(a) => {
                    let a = self.atom_native(a)?;
                    body.push(quote! {
                        if s.atom_of(#t) != Some(#a) {
                            return None;
                        }
                    });
                }
                sitlog_runtime::Value::Int(i) => {
                    let i = Literal::i64_suffixed(i);
                    body.push(quote! {
                        if s.int_of(#t) != Some(#i) {
                            return None;
                        }
                    });
                }
                _ => return Err("an in_arg pattern's constant is not native".into()),
            },
            Build::Compound(f, args) => {
                let parts: Vec<_> = (0..args.len())
                    .map(|k| format_ident!("m{}", *n + k))
                    .collect();
                *n += args.len();
                let fname = self.functor_native(*f)?;
                let len = Literal::usize_unsuffixed(args.len());
                body.push(quote! {
                    let &[#(#parts),*] = s.compound_args(#t, #fname, #len)? else {
                        return None;
                    };
                });
                for (a, part) in args.iter().zip(parts) {
                    self.nat_match_part(d, ix, a, quote!(#part), regs, bound, body, n, depth + 1)?;
                }
            }
        }
        Ok(())
    }

    /// In `nat_entry`: the in_arg of situation `ix` (where the machine
    /// enters native code) converts, else the situation runs on terms.
    pub(super) fn nat_pipe_entry(&self, d: &Dm, ix: usize) -> N<TokenStream> {
        let Some(plan) = d.plans.get(ix) else {
            return Ok(quote!());
        };
        let mut checks = Vec::new();
        for (r, init) in &plan.inits {
            if let Init::Pipe = init {
                let ty = super::rust_ty(&d.types[ix].regs[*r as usize].ty)?;
                checks.push(quote! {
                    if !cx.pipe_converts::<#ty>() {
                        return None;
                    }
                });
            }
        }
        Ok(quote!(#(#checks)*))
    }

    /// The next situation of an arc whose out_arg is `out`: the pipe set
    /// after the next value is evaluated, before any hand-over.
    pub(super) fn nat_next_out(
        &self,
        d: &Dm,
        cur: usize,
        next: &Next,
        out: Option<&Ev>,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<TokenStream> {
        let Some(e) = out else {
            return self.nat_next(d, cur, next, regs, cur_name);
        };
        // A `get`/`inc` in it (`inc(calls, _)`): after the next situation.
        if super::has_var_op(e, &|_, _| true) {
            return self.nat_next_out_after(d, cur, next, e, regs, cur_name);
        }
        // The value read where it is (no clone of a `Val`), made a term
        // once: an int or an atom costs nothing. The in_arg's value handed
        // back in the visit that read it (`out_arg ==> X`, `X` the in_arg)
        // is the term read, not converted again.
        let same = match (e, d.pipe_in.get()) {
            (Ev::Value(x), Some(pr)) => regs.get(x).is_some_and(|(e, _)| *e == super::reg(pr)),
            _ => false,
        };
        // The in_arg's term handed back: the pipe, unchanged since it was
        // read, only dereferenced (no term kept across the visit).
        let (pipe_out, set) = if same {
            (quote!(), quote!(cx.pipe_deref();))
        } else if let Ev::Eval(b) = e {
            // A user function, the KB, `get` of a global: the evaluator's.
            return self.nat_next_out_eval(d, cur, next, b, regs, cur_name);
        } else {
            let v = self.nat_out_value(d, cur, e, next, regs)?;
            let parts = self.nat_out_parts(d, cur, e, regs)?;
            let held = match &parts {
                Some((name, parts)) => self.nat_out_held(*name, parts)?,
                None => None,
            };
            if let Some((vals, f)) = held {
                // Held as native values (`Cx::hold_pipe`): a term only
                // where something reads it as one.
                let pipe_out = quote!(let pipe_out = [#(#vals),*];);
                let set = quote!(cx.hold_pipe(#f, pipe_out););
                *d.out.borrow_mut() = set.clone();
                let n = self.nat_next(d, cur, next, regs, cur_name);
                *d.out.borrow_mut() = quote!();
                let n = n?;
                return Ok(quote! {{
                    #pipe_out
                    let next_at = #n;
                    #set
                    next_at
                }});
            }
            // A conditional's value first (its condition may use `cx`).
            let choice = match e {
                Ev::Pick(..) => self.nat_out_choice_term(d, cur, e, next, regs)?,
                _ => None,
            };
            let pipe_out = if let Some(t) = choice {
                quote!(let pipe_out = #t;)
            } else if matches!(e, Ev::If(..) | Ev::Pick(..)) {
                let e = &v.e;
                quote!(let out_value = #e; let pipe_out = cx.term(&out_value);)
            } else if let Some((name, parts)) = &parts {
                let t = self.nat_out_term(*name, parts)?;
                quote!(let pipe_out = #t;)
            } else if let Some(held) = held_whole(&v) {
                // A list or compound held as it is (`Cx::hold_pipe_value`):
                // a term only where something reads the pipe as one.
                let set = quote!(cx.hold_pipe_value(pipe_out););
                *d.out.borrow_mut() = set.clone();
                let n = self.nat_next(d, cur, next, regs, cur_name);
                *d.out.borrow_mut() = quote!();
                let n = n?;
                return Ok(quote! {{
                    let pipe_out = #held;
                    let next_at = #n;
                    #set
                    next_at
                }});
            } else {
                let v = super::place(&v);
                quote!(let pipe_out = cx.term(&#v);)
            };
            // A value held as a term may be an unbound variable (a fresh
            // one the arc may or may not have bound): decided at run time,
            // the pipe passed on then (D-18, `Cx::out_value`).
            let set = if v.ty == Ty::Term {
                quote!(cx.out_value(pipe_out);)
            } else {
                quote!(cx.set_pipe(pipe_out);)
            };
            (pipe_out, set)
        };
        *d.out.borrow_mut() = set.clone();
        let n = self.nat_next(d, cur, next, regs, cur_name);
        *d.out.borrow_mut() = quote!();
        let n = n?;
        Ok(quote! {{
            #pipe_out
            let next_at = #n;
            #set
            next_at
        }})
    }
}

impl Gen<'_> {
    /// An arc's out_arg `name(A, B, ..)` (not a list cell, evaluating its
    /// arguments only) of native values read in place: its functor and
    /// parts, which [`Gen::nat_out_term`] makes a term of at once and
    /// [`Gen::nat_out_held`] holds as values. `None`: another out_arg, or
    /// a part that reads `cx`.
    fn nat_out_parts(
        &self,
        d: &Dm,
        cur: usize,
        e: &Ev,
        regs: &Regs,
    ) -> N<Option<(sitlog_syntax::Atom, Vec<V>)>> {
        let (name, parts) = match e {
            Ev::Compound(name, args) if *name != atoms::DOT => (
                *name,
                args.iter()
                    .map(|a| self.nat_ev_value(d, cur, a, regs))
                    .collect::<N<Vec<_>>>()?,
            ),
            Ev::Built(Build::Compound(name, args)) if *name != atoms::DOT => (
                *name,
                args.iter()
                    .map(|a| self.nat_value(a, regs))
                    .collect::<N<Vec<_>>>()?,
            ),
            _ => return Ok(None),
        };
        let cx = proc_macro2::Ident::new("cx", proc_macro2::Span::call_site());
        if parts.iter().any(|p| mentions(&p.e, &cx) > 0)
            || !sitlog_runtime::eval::evaluates_arguments_only(name, parts.len())
        {
            return Ok(None);
        }
        Ok(Some((name, parts)))
    }

    /// An arc's out_arg of [`Gen::nat_out_parts`] made a term at once from
    /// them (`Cx::build_of`), not a `Val` first (`M-L` of an int and a
    /// `Val`: no `Rc` allocated and dropped per visit); the same term.
    fn nat_out_term(&self, name: sitlog_syntax::Atom, parts: &[V]) -> N<TokenStream> {
        let f = self.functor_native(name)?;
        let ps = parts.iter().map(|p| {
            let x = super::place(p);
            quote!(&#x)
        });
        Ok(quote!(cx.build_of(#f, &[#(#ps),*])))
    }

    /// An arc's out_arg of [`Gen::nat_out_parts`] with at most `HELD_MAX`
    /// arguments each an int, a float, an atom or a `ground` value: the
    /// values as `Val`s (cloned: a `Val` an `Rc` count at most) and the
    /// functor, for `Cx::hold_pipe` (the pipe held as those values).
    /// `None`: another out_arg.
    fn nat_out_held(
        &self,
        name: sitlog_syntax::Atom,
        parts: &[V],
    ) -> N<Option<(Vec<TokenStream>, TokenStream)>> {
        if parts.is_empty()
            || parts.len() > sitlog_runtime::machine::HELD_MAX
            || !parts.iter().all(|p| held_part(&p.ty))
        {
            return Ok(None);
        }
        let vals = parts
            .iter()
            .map(|p| {
                let x = super::place(p);
                quote!(IntoVal::into_val(#x.clone()))
            })
            .collect();
        Ok(Some((vals, self.functor_native(name)?)))
    }

    /// [`Gen::nat_next_out`] for an out_arg the evaluator computes
    /// (`apply(f(X), [X])`, `get(g, _)` of a global): its term built from
    /// native values before the next situation (building has no effect),
    /// evaluated after it, the machine entered in situation `cur` (as for
    /// a next situation's evaluated part), the pipe set to the value
    /// unless it is a variable (`Cx::out_value`, D-18): the term code's
    /// order (`codegen::step`: next situation, then out_arg), on every way
    /// out (one that hands the next situation to the machine too). The
    /// situation's id is built only where it is read, as for a condition
    /// the machine evaluates ([`Gen::nat_eval_lazy_id`]): when the run
    /// records, and for an error of the evaluation; a list walk's id
    /// (`try(Ps)`) costs O(length), built at every visit the walk was
    /// quadratic (`d_outarg_when`). The id's fields the next situation
    /// may move (`Ps` into the next variant) are kept past it, a clone
    /// each (`keep_r<N>`: an `Rc` count for a list). In a DM with locals
    /// held in the frame, they are written back before the evaluation
    /// (which reads and may change the machine's frame) and read again
    /// after it, as for a next situation's evaluated part.
    fn nat_next_out_eval(
        &self,
        d: &Dm,
        cur: usize,
        next: &Next,
        b: &Build,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<TokenStream> {
        let mut ts = Vec::new();
        let mut n = 0;
        let t = self.nat_build_term(b, regs, &mut ts, &mut n)?;
        let (id_stmts, id) = self.nat_id_term(d, cur, quote!(cx.store()))?;
        // The id's registers, read after the next situation as kept.
        let fields: Vec<Ident> = crate::codegen::step::registers(&quote!(#(#id_stmts)* #id))
            .into_iter()
            .map(reg)
            .collect();
        let curl = Literal::u32_unsuffixed(cur as u32);
        // Where the next situation is handed to the machine (entered there
        // by name, or with its id when recorded): entered with its id,
        // built there.
        let eval = quote! {
            #(#id_stmts)*
            cx.enter_with_id(#curl, #id);
            let out_value = cx.eval(out_term, arc_at)?;
            cx.out_value(out_value);
        };
        *d.out.borrow_mut() = rename_kept(eval, &fields);
        let nx = self.nat_next(d, cur, next, regs, cur_name);
        *d.out.borrow_mut() = quote!();
        let nx = nx?;
        // What the evaluator changed of the locals (written back before
        // it, `Dm::hand`), read again, as after a next situation's
        // evaluated part; a local that no longer converts: the machine
        // goes on from the next situation (entered with this one's id,
        // the locals its own).
        let checks = self.nat_local_checks(d)?;
        let back = if checks.is_empty() {
            quote!()
        } else {
            let tail = super::goto_tail(&d.rec.borrow());
            let fallback = quote! {{
                cx.count_transitions(count);
                #(#id_stmts)*
                cx.enter_with_id(#curl, #id);
                let rec_next = next_at.id_term(p, cx.store());
                #tail
            }};
            super::checked(checks, &fallback)
        };
        // Kept: the fields the next situation's code may move.
        let moved: Vec<Ident> = fields
            .iter()
            .filter(|r| super::moves_any(&nx, &quote!(#r)))
            .cloned()
            .collect();
        let back = rename_kept(back, &moved);
        let unkept: Vec<Ident> = fields
            .iter()
            .filter(|r| !moved.contains(r))
            .cloned()
            .collect();
        let nx = unrename_kept(nx, &unkept);
        let name = format_ident!("out_value");
        let pre = self.nat_eval_lazy_id(
            d,
            cur,
            &name,
            quote!(cx.eval(out_term, arc_at)),
            quote!(Term),
        )?;
        // A plain user function's value, computed on native values
        // (`plain`), the `apply` built and evaluated where it gives none
        // (its term built there, after the next situation: building reads
        // registers only, the kept ones renamed below).
        let (built, pre) = match self.nat_plain_call(d, b, regs, None)? {
            Some((call, ans)) => {
                // A compound answered by its parts: built here.
                let val = match ans {
                    Some(_) => quote!(pa.val(a)),
                    None => quote!(pa),
                };
                let term_path = super::plain::cold_arm(quote! {
                    #(#ts)*
                    let out_term = #t;
                    #pre
                });
                (
                    quote!(),
                    quote! {
                        let #name: Term = match #call {
                            Some(pa) => cx.term(&#val),
                            None => {
                                #term_path
                                #name
                            }
                        };
                    },
                )
            }
            None => (quote!(#(#ts)* let out_term = #t;), pre),
        };
        let pre = rename_kept(pre, &moved);
        let kept = moved.iter().map(|r| {
            let k = kept_name(r);
            quote!(let #k = #r.clone();)
        });
        Ok(quote! {{
            #built
            #(#kept)*
            let next_at = #nx;
            #pre
            cx.out_value(#name);
            #back
            next_at
        }})
    }

    /// [`Gen::nat_next_out`] for an out_arg that does a `get(v, _)` or an
    /// `inc(v, _)` of the frame's local or a global (`inc(calls, _)`,
    /// `f(X, get(n, _))`): computed by native code after the next
    /// situation, as the machine evaluates it (`codegen::step`: next
    /// situation, then out_arg; the next situation may have changed `v`),
    /// each operation once ([`Gen::nat_ev_effects`]), the pipe set to the
    /// value. Where the next situation is handed to the machine (the
    /// native frames handed over, the locals written back: the machine's
    /// from there) the machine evaluates the out_arg instead, entered in
    /// situation `cur` with its id, as for an out_arg the evaluator
    /// computes ([`Gen::nat_next_out_eval`]): on every way out the
    /// out_arg is evaluated once, after the next situation. Not native
    /// where the next situation's code may move a value the out_arg or
    /// the situation's id reads.
    fn nat_next_out_after(
        &self,
        d: &Dm,
        cur: usize,
        next: &Next,
        e: &Ev,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<TokenStream> {
        let mut pre = Vec::new();
        // A global read whose value native code cannot hold: the
        // machine's (`cold_next`).
        let cold = self.cold_reads(d, e, regs);
        // Beside an `inc`: each read's cold arm its own (`cold_next`).
        let cold_inc = !cold && self.cold_effects(d, e);
        let saved = cold.then(|| self.global_cold.replace(Some(quote!(break 'nat_cold_out))));
        let saved_inc =
            cold_inc.then(|| self.global_cold.replace(Some(quote!(break 'nat_cold_next))));
        let v = self.nat_ev_effects(d, cur, e, regs, &mut pre, "out");
        if let Some(saved) = saved.or(saved_inc) {
            *self.global_cold.borrow_mut() = saved;
        }
        let mut v = v?;
        if cold_inc {
            match self.nat_out_effects_cold(d, e, regs, std::mem::take(&mut pre)) {
                Ok(cold) => pre = cold,
                // Made again, the reads' cold arms errors.
                Err(_) => v = self.nat_ev_effects(d, cur, e, regs, &mut pre, "out")?,
            }
        }
        // The machine's evaluation: a fresh variable it binds is a term
        // made there.
        let mut mregs = regs.clone();
        let mut binds = Vec::new();
        super::ev_binds(e, &mut binds);
        for r in binds {
            mregs.insert(r, (format_ident!("fresh_r{}", r), Ty::Term));
        }
        let mut ts = Vec::new();
        let mut n = 0;
        let t = self.nat_ev_term(e, &mregs, &mut ts, &mut n)?;
        let (id_stmts, id) = self.nat_id_term(d, cur, quote!(cx.store()))?;
        let curl = Literal::u32_unsuffixed(cur as u32);
        *d.out.borrow_mut() = quote! {
            #(#id_stmts)*
            cx.enter_with_id(#curl, #id);
            #(#ts)*
            cx.out_value(#t);
        };
        let nx = self.nat_next(d, cur, next, regs, cur_name);
        *d.out.borrow_mut() = quote!();
        let nx = nx?;
        let ve = &v.e;
        let read = crate::codegen::step::registers(&quote!(#(#id_stmts)* #id #ve));
        if read.into_iter().any(|r| {
            let r = reg(r);
            super::moves_any(&nx, &quote!(#r))
        }) {
            return Err("the next situation moves a value its out_arg reads".into());
        }
        let pv = super::place(&v);
        let body = quote! {
            #(#pre)*
            let pipe_out = cx.term(&#pv);
            cx.set_pipe(pipe_out);
        };
        if body.to_string().contains("nat_cold_out") {
            let out = self.nat_out_cold(d, e, regs, body)?;
            return Ok(quote!({ let next_at = #nx; #out }));
        }
        Ok(quote! {{
            let next_at = #nx;
            #body
            next_at
        }})
    }

    /// An arc's out_arg's value, computed before its next situation (the
    /// pipe is set on every way out of it): what [`Gen::nat_ev_value`]
    /// makes, and a conditional `(C -> A ; otherwise -> B)` of native
    /// branches, `if C { A } else { B }` in their join. A comparison of
    /// two ints (or floats) is plain Rust; one on a `Val` (a `ground`
    /// parameter or pipe) reads its number and, when it has none, lets the
    /// term code's comparison decide or fail (the machine entered in the
    /// situation, as for a next situation's condition): only where the
    /// next situation is a constant, which cannot fail, so an error is the
    /// one the term code reports (it evaluates the next situation first).
    pub(super) fn nat_out_value(
        &self,
        d: &Dm,
        cur: usize,
        e: &Ev,
        next: &Next,
        regs: &Regs,
    ) -> N<V> {
        let (c, a, b) = match e {
            Ev::If(c, a, b) => (c, a, b),
            // `when/3` whose branches do nothing but build native values:
            // evaluating the one not chosen too changes nothing.
            Ev::Pick(c, a, b) if Self::nat_inert(a, regs) && Self::nat_inert(b, regs) => (c, a, b),
            _ => return self.nat_ev_value(d, cur, e, regs),
        };
        let c = self.nat_out_cond(d, cur, c, next, regs)?;
        let a = self.nat_out_value(d, cur, a, next, regs)?;
        let b = self.nat_out_value(d, cur, b, next, regs)?;
        let ty = a.ty.join(&b.ty);
        if !ty.is_native() || ty == Ty::Term {
            return Err("an out_arg's branches join to a term".into());
        }
        let (ae, be) = (super::coerce(&a, &ty)?, super::coerce(&b, &ty)?);
        Ok(V {
            e: quote!((if #c { #ae } else { #be })),
            ty,
        })
    }

    /// The condition of an out_arg's choice ([`Gen::nat_out_value`]).
    fn nat_out_cond(
        &self,
        d: &Dm,
        cur: usize,
        c: &Cond,
        next: &Next,
        regs: &Regs,
    ) -> N<TokenStream> {
        Ok(match c {
            // `when/3`'s comparison: as an arithmetic condition, its
            // error the evaluator's; it may fail before the next
            // situation where that is a constant or only builds native
            // values (which cannot fail).
            Cond::Cmp(op, lb, rb) => {
                let (l, r) = (self.nat_value(lb, regs)?, self.nat_value(rb, regs)?);
                // A side that is an expression (`N + 1`) may overflow.
                let expr = [lb, rb].iter().any(|b| matches!(b, Build::Compound(..)));
                let plain = !expr
                    && ((l.ty == Ty::Int && r.ty == Ty::Int)
                        || (l.ty == Ty::Float && r.ty == Ty::Float));
                let safe = match next {
                    Next::Static(..) => true,
                    Next::Eval(e) => Self::nat_inert(e, regs),
                    Next::If(..) => false,
                };
                if !plain && !safe {
                    return Err("a `when`'s comparison may fail before its next situation".into());
                }
                self.nat_cmp(d, cur, *op, (lb, rb), regs, super::call::Decide::Value)?
            }
            Cond::Arith(op, l, r) => {
                // A side an arithmetic expression: it may enter the machine.
                if let Some(t) = self.nat_arith_exprs(d, cur, *op, (l, r), regs)? {
                    if !matches!(next, Next::Static(..)) {
                        return Err(
                            "an out_arg's comparison may fail before its next situation".into()
                        );
                    }
                    return Ok(t);
                }
                let (l, r) = (
                    self.nat_ev_value(d, cur, l, regs)?,
                    self.nat_ev_value(d, cur, r, regs)?,
                );
                let plain = (l.ty == Ty::Int && r.ty == Ty::Int)
                    || (l.ty == Ty::Float && r.ty == Ty::Float);
                if !plain && !matches!(next, Next::Static(..)) {
                    return Err("an out_arg's comparison may fail before its next situation".into());
                }
                self.nat_arith(d, cur, *op, l, r)?
            }
            Cond::Other(Build::Compound(op, _)) if matches!(op.as_str(), "==" | "\\==") => {
                self.nat_cond(d, cur, c, regs)?
            }
            // A conjunction's operand may enter the machine: only before a
            // constant next situation, as a comparison.
            Cond::And(..) | Cond::Or(..) if matches!(next, Next::Static(..)) => {
                self.nat_cond(d, cur, c, regs)?
            }
            _ => return Err("an out_arg's condition is not native".into()),
        })
    }

    /// The term of an out_arg that is `when/3`'s choice ([`Ev::Pick`]
    /// whose branches only build native values, and conditionals inside
    /// it): `if C { A } else { B }` with each branch's term built where it
    /// is chosen ([`Gen::nat_out_term`]), not a native value made and
    /// then converted. `None` where it is not such a choice.
    fn nat_out_choice_term(
        &self,
        d: &Dm,
        cur: usize,
        e: &Ev,
        next: &Next,
        regs: &Regs,
    ) -> N<Option<TokenStream>> {
        let (c, a, b) = match e {
            Ev::If(c, a, b) => (c, a, b),
            Ev::Pick(c, a, b) if Self::nat_inert(a, regs) && Self::nat_inert(b, regs) => (c, a, b),
            _ => return Ok(None),
        };
        let c = self.nat_out_cond(d, cur, c, next, regs)?;
        let branch = |x: &Ev| -> N<Option<TokenStream>> {
            if matches!(x, Ev::If(..) | Ev::Pick(..)) {
                return self.nat_out_choice_term(d, cur, x, next, regs);
            }
            if let Some((name, parts)) = self.nat_out_parts(d, cur, x, regs)? {
                return Ok(Some(self.nat_out_term(name, &parts)?));
            }
            let v = self.nat_ev_value(d, cur, x, regs)?;
            let p = super::place(&v);
            Ok(Some(quote!(cx.term(&#p))))
        };
        let (Some(ta), Some(tb)) = (branch(a)?, branch(b)?) else {
            return Ok(None);
        };
        Ok(Some(quote!((if #c { #ta } else { #tb }))))
    }
}

/// The out_arg an arc's native code evaluates: none where it passes the
/// pipe on unchanged ([`crate::mir::OutPass::Unchanged`]: a variable of
/// the arc nothing binds, D-18), which is then the arc without an
/// out_arg; else the arc's out_arg (a variable held as a term is decided
/// at run time, `Cx::out_value`).
pub(super) fn arc_out(arc: &crate::mir::ArcPlan) -> Option<&Ev> {
    match arc.out_pass() {
        crate::mir::OutPass::Unchanged => None,
        crate::mir::OutPass::Value => arc.out_arg.as_ref(),
    }
}

/// `keep_<r>`: register `r` kept past a next situation that may move it
/// ([`Gen::nat_next_out_eval`]).
fn kept_name(r: &Ident) -> Ident {
    format_ident!("keep_{}", r)
}

/// `code` with each identifier of `regs` made its kept name.
fn rename_kept(code: TokenStream, regs: &[Ident]) -> TokenStream {
    let map: Vec<(Ident, Ident)> = regs.iter().map(|r| (r.clone(), kept_name(r))).collect();
    rename_idents(code, &map)
}

/// `code` with each kept name of `regs` made the register again.
fn unrename_kept(code: TokenStream, regs: &[Ident]) -> TokenStream {
    let map: Vec<(Ident, Ident)> = regs.iter().map(|r| (kept_name(r), r.clone())).collect();
    rename_idents(code, &map)
}

fn rename_idents(code: TokenStream, map: &[(Ident, Ident)]) -> TokenStream {
    use proc_macro2::{Group, TokenTree as T};
    code.into_iter()
        .map(|t| match t {
            T::Ident(i) => match map.iter().find(|(from, _)| *from == i) {
                Some((_, to)) => T::Ident(to.clone()),
                None => T::Ident(i),
            },
            T::Group(g) => {
                let mut ng = Group::new(g.delimiter(), rename_idents(g.stream(), map));
                ng.set_span(g.span());
                T::Group(ng)
            }
            t => t,
        })
        .collect()
}

/// How many times the identifier `name` occurs in `code` (at any depth).
pub(super) fn mentions(code: &TokenStream, name: &proc_macro2::Ident) -> usize {
    mentions_of(code, std::slice::from_ref(name))
}

/// How many identifier tokens of `code` (at any depth) are one of `names`:
/// the one walk behind `mentions` here and `call::mentions`/`mentions_any`.
pub(super) fn mentions_of(code: &TokenStream, names: &[proc_macro2::Ident]) -> usize {
    code.clone()
        .into_iter()
        .map(|t| match t {
            proc_macro2::TokenTree::Ident(i) => usize::from(names.contains(&i)),
            proc_macro2::TokenTree::Group(g) => mentions_of(&g.stream(), names),
            _ => 0,
        })
        .sum()
}

/// Where an in_arg pattern's variable `r` is held already, and its type:
/// a register of the visit (`regs`: the id's field, a parameter) or one
/// the pattern bound before (`bound`); `None` where it is met first. The
/// one lookup of [`Gen::nat_match_part`] (the pipe's term) and
/// [`Gen::nat_held_match`] (the pipe held as values).
fn held_reg<'a>(
    regs: &Regs,
    mut bound: impl Iterator<Item = &'a (Reg, Ty)>,
    r: Reg,
) -> Option<(Ident, Ty)> {
    match regs.get(&r) {
        Some((x, ty)) => Some((x.clone(), ty.clone())),
        None => bound
            .find(|(x, _)| *x == r)
            .map(|(x, ty)| (reg(*x), ty.clone())),
    }
}

/// An out_arg's value the pipe holds whole as a canonical `Val`
/// (`Cx::hold_pipe_value`): a list of `Val`s (`list<ground>`, a list of
/// native compounds; its `Rc` shared, no element copied) or a value held
/// as a `Val` that is not atomic in every case (`ground`, a compound);
/// the expression of that `Val`. `None` for an int, a float or an atom
/// (their terms cost nothing to make) and for a list of ints or atoms
/// (whose `Val` would copy every element).
fn held_whole(v: &V) -> Option<TokenStream> {
    let x = super::place(v);
    match &v.ty {
        Ty::List(e) if super::held_as_val(e) => Some(quote!(Val::List(#x.clone()))),
        t if super::held_as_val(t) => Some(quote!(IntoVal::into_val(#x.clone()))),
        _ => None,
    }
}

/// Whether an argument of this type is held in the pipe as a native value
/// (`Cx::hold_pipe`): an int, a float, an atom or a value held as a `Val`.
fn held_part(ty: &Ty) -> bool {
    matches!(ty, Ty::Int | Ty::Float | Ty::Sym) || super::held_as_val(ty)
}
