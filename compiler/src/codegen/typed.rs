//! Typed code: the situations [`crate::types`] gave a typed plan run on a
//! native frame of their DM (`struct Frame`: the locals and parameters they
//! use, as `i64`, `f64` or an `enum` of the local's atoms), not on terms.
//!
//! `run_typed` is tried before the untyped code of a situation: it loads the
//! frame from the machine's variables (a check: code the compiler cannot
//! see, a user function or the command line, may have put any term there;
//! if a value does not fit, `None` and the untyped path runs, nothing
//! done), runs typed situations one after the other as a `match` on native
//! values, and writes the frame back when it leaves (a situation that is not
//! typed, a final one, input not met, an error, or garbage to collect).
//!
//! What a typed transition still does, in the interpreter's order: the
//! machine's perception (`choose`) for a perceptual situation that is not
//! the neutral rule, the actions (skipped for numbers when the run's
//! `Actions` ignore them), and the history entry, built from the native
//! values only when the history is kept or observed; otherwise it counts.
//! Run-time errors are the untyped path's, word for word (`inc` overflow).
//!
//! Typed DM calls ([`Gen::typed_driver`]): the caller's `Step::Call`, taken
//! by the program's driver, which keeps every DM's typed frame in one enum
//! on a fixed array and the machine's DM stack exactly as the machine would
//! (`Cx::call_typed`, `Cx::return_typed`), so that any other step hands
//! over to the machine as it is. Without history the callee's machine frame
//! is not pushed at all unless something reads the DM stack
//! (`Cx::call_typed_lazy`, its typed frame made from the locals' defaults
//! and the call's arguments, `Frame::fresh`); the driver pushes every such
//! frame (`Cx::materialize_frames`) before it hands over.

use super::Gen;
use crate::ir::IrDm;
use crate::types::{Cmp, DmTypes, TAction, TExpr, TItem, TNext, TSit, TVal, Ty};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use sitlog_syntax::Atom;
use std::collections::HashMap;

/// The typed items of one DM module (empty when no situation is typed).
pub(super) struct TypedCode {
    /// `struct Frame`, its enums, `run_typed` and its loop.
    pub items: TokenStream,
    /// Whether `typed_loop` exists.
    pub present: bool,
}

/// Whether a DM has typed code (a typed situation that is not final).
pub(super) fn has_typed_code(t: &DmTypes) -> bool {
    t.situations
        .iter()
        .any(|s| matches!(s, Ok(TSit::Perceptual { .. } | TSit::Call { .. })))
}

fn local_field(i: usize) -> Ident {
    format_ident!("l{}", i)
}
fn param_field(i: usize) -> Ident {
    format_ident!("p{}", i)
}
fn atoms_enum(i: usize) -> Ident {
    format_ident!("Local{}", i)
}

impl Gen<'_> {
    pub(super) fn typed_code(&self, dm: &IrDm, t: &DmTypes) -> TypedCode {
        let rt = quote!(::sitlog_runtime);
        if !has_typed_code(t) {
            return TypedCode {
                items: quote!(),
                present: false,
            };
        }
        let locals = t.frame_locals();
        let params = t.frame_params();
        // The frame's fields, load and store.
        let mut fields = Vec::new();
        let mut enums = Vec::new();
        let mut loads = Vec::new();
        // The frame of a call no frame was pushed for: the locals' defaults
        // and the call's arguments.
        let mut fresh = Vec::new();
        let mut inits = Vec::new();
        let mut stores = Vec::new();
        for &i in &locals {
            let f = local_field(i);
            let name = self.atom_expr(dm.locals[i].0);
            let doc = format!(" Local `{}`: {}.", t.locals[i].name, t.locals[i].ty);
            match &t.locals[i].ty {
                Ty::Int => {
                    fields.push(quote!(#[doc = #doc] pub #f: i64,));
                    loads.push(quote!(let #f = cx.int_of(cx.local(#name)?)?;));
                    stores.push(quote!(cx.set_local(#name, #rt::Term::int(self.#f));));
                }
                Ty::Float => {
                    fields.push(quote!(#[doc = #doc] pub #f: f64,));
                    loads.push(quote!(let #f = cx.float_of(cx.local(#name)?)?;));
                    stores.push(quote!(cx.set_local(#name, #rt::Term::float(self.#f));));
                }
                Ty::Atoms(atoms) => {
                    let e = atoms_enum(i);
                    let variants: Vec<Ident> =
                        (0..atoms.len()).map(|j| format_ident!("A{}", j)).collect();
                    let docs: Vec<String> =
                        atoms.iter().map(|a| format!(" `{}`", a.as_str())).collect();
                    let atom_exprs: Vec<TokenStream> =
                        atoms.iter().map(|&a| self.atom_expr(a)).collect();
                    let edoc = format!(" The values of local `{}`.", t.locals[i].name);
                    enums.push(quote! {
                        #[doc = #edoc]
                        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
                        pub enum #e { #(#[doc = #docs] #variants,)* }
                        impl #e {
                            fn of(p: &super::Program, t: #rt::Term) -> ::std::option::Option<#e> {
                                let a = &p.atoms;
                                let x = ::std::option::Option::Some(t);
                                #(if x == ::std::option::Option::Some(#rt::Term::atom(#atom_exprs)) { return ::std::option::Option::Some(#e::#variants); })*
                                ::std::option::Option::None
                            }
                            fn term(self, p: &super::Program) -> #rt::Term {
                                let a = &p.atoms;
                                match self { #(#e::#variants => #rt::Term::atom(#atom_exprs),)* }
                            }
                        }
                    });
                    fields.push(quote!(#[doc = #doc] pub #f: #e,));
                    loads.push(quote!(let #f = #e::of(p, cx.local(#name)?)?;));
                    stores.push(quote!(cx.set_local(#name, self.#f.term(p));));
                }
                _ => unreachable!("frame locals are native"),
            }
            let default = self.native_default(t, i, dm.locals[i].1);
            fresh.push(quote!(let #f = #default;));
            inits.push(quote!(#f,));
        }
        for &i in &params {
            let f = param_field(i);
            let doc = match &t.params[i] {
                Some(v) => format!(" Parameter `{}`: {}.", v.name, v.ty),
                None => String::new(),
            };
            let ix = Literal::usize_unsuffixed(i);
            match t.params[i].as_ref().map(|v| &v.ty) {
                Some(Ty::Float) => {
                    fields.push(quote!(#[doc = #doc] pub #f: f64,));
                    loads.push(quote!(let #f = cx.float_of(cx.param(#ix)?)?;));
                    fresh.push(quote!(let #f = cx.float_of(cx.arg(call, #ix))?;));
                }
                _ => {
                    fields.push(quote!(#[doc = #doc] pub #f: i64,));
                    loads.push(quote!(let #f = cx.int_of(cx.param(#ix)?)?;));
                    fresh.push(quote!(let #f = cx.int_of(cx.arg(call, #ix))?;));
                }
            }
            inits.push(quote!(#f,));
        }

        if t.frame_pipe() {
            let doc = format!(
                " The incoming pipe: {}.",
                t.pipe.as_ref().map_or(Ty::Int, |p| p.ty.clone())
            );
            match t.pipe.as_ref().map(|v| &v.ty) {
                Some(Ty::Float) => {
                    fields.push(quote!(#[doc = #doc] pub pipe: f64,));
                    loads.push(quote!(let pipe = cx.float_of(cx.pipe())?;));
                    fresh.push(quote!(let pipe = cx.float_of(cx.pipe())?;));
                }
                _ => {
                    fields.push(quote!(#[doc = #doc] pub pipe: i64,));
                    loads.push(quote!(let pipe = cx.int_of(cx.pipe())?;));
                    fresh.push(quote!(let pipe = cx.int_of(cx.pipe())?;));
                }
            }
            inits.push(quote!(pipe,));
        }

        // The typed situations.
        let typed_ix: Vec<Literal> = t
            .situations
            .iter()
            .enumerate()
            .filter(|(_, s)| s.is_ok())
            .map(|(i, _)| Literal::u32_unsuffixed(i as u32))
            .collect();
        let mut arms = Vec::new();
        for (i, s) in t.situations.iter().enumerate() {
            let Ok(plan) = s else { continue };
            let ix = Literal::u32_unsuffixed(i as u32);
            let id = self.atom_expr(plan.id());
            let here = quote!(cx.enter(#ix, #id););
            let body = match plan {
                TSit::Final { .. } => {
                    let empty = quote!(#rt::Term::atom(#rt::atoms::EMPTY));
                    // No out_arg: the pipe stays as it is (D-18).
                    quote! {
                        #here
                        if run.records {
                            cx.record(#empty, #empty, ::std::option::Option::None);
                        } else {
                            run.count += 1;
                        }
                        return ::std::result::Result::Ok(#rt::machine::Step::Final);
                    }
                }
                TSit::Call {
                    callee, call, arcs, ..
                } => self.typed_call(dm, t, i, plan.id(), (*callee, *call), arcs),
                TSit::Perceptual {
                    type_name,
                    always_first,
                    prog,
                    out_arg,
                    arcs,
                    ..
                } => {
                    // `prog`: `V is E`, checked; an overflow leaves the
                    // situation to the untyped path, which reports it.
                    let prog_code = match prog {
                        Some(is) => {
                            let bail = quote! {{
                                #here
                                run.untyped = true;
                                return ::std::result::Result::Ok(#rt::machine::Step::GotoSit(#ix));
                            }};
                            let w = format_ident!("w{}", is.var);
                            let e = self.typed_expr(&is.expr, &bail);
                            quote!(let #w: i64 = #e;)
                        }
                        None => quote!(),
                    };
                    let out_var = prog.as_ref().filter(|_| *out_arg).map(|is| is.var);
                    let exps: Vec<TokenStream> = arcs
                        .iter()
                        .map(|a| self.typed_const(a.expectation))
                        .collect();
                    let enames: Vec<Ident> =
                        (0..arcs.len()).map(|j| format_ident!("e{}", j)).collect();
                    let choose = if *always_first {
                        quote!(let chosen = 0usize;)
                    } else {
                        let ty = self.atom_term(*type_name);
                        quote! {
                            #here
                            cx.set_expectations(&[#(#enames),*]);
                            let ::std::option::Option::Some(chosen) = cx.choose(#ty)? else {
                                return ::std::result::Result::Ok(#rt::machine::Step::Unmet { type_term: #ty });
                            };
                        }
                    };
                    let mut match_arms = Vec::new();
                    for (j, arc) in arcs.iter().enumerate() {
                        let code = self.typed_arc(dm, t, i, plan.id(), j, arc, out_var);
                        let j = Literal::usize_unsuffixed(j);
                        match_arms.push(quote!(#j => { #code }));
                    }
                    quote! {
                        #prog_code
                        #(let #enames = #exps;)*
                        #choose
                        match chosen {
                            #(#match_arms)*
                            _ => unreachable!("the machine chose an arc of this situation"),
                        }
                    }
                }
            };
            arms.push(quote!(#ix => { #body }));
        }
        let loop_body = quote! {
            loop {
                match sit {
                    #(#arms)*
                    _ => return ::std::result::Result::Ok(#rt::machine::Step::GotoSit(sit)),
                }
            }
        };
        let loop_prelude = Self::prelude(&loop_body);
        // With typed calls the program's driver loads, runs and stores the
        // frames of every DM ([`Gen::typed_driver`]); else the DM's own
        // `run_typed` does.
        let run_typed = if self.typed_calls() {
            quote! {
                /// Whether situation `sit` has typed code.
                pub fn is_typed(sit: #rt::machine::SitIx) -> bool {
                    matches!(sit, #(#typed_ix)|*)
                }
            }
        } else {
            quote! {
                /// Runs typed situations from `sit` on the typed frame until the
                /// machine or untyped code is needed; `None` (nothing done) when
                /// `sit` is not typed or the frame does not load, or when typed
                /// code hands the situation it reached to the untyped path (a
                /// typed `prog` that overflows), written into `sit`.
                pub fn run_typed(
                    p: &super::Program,
                    sit: &mut #rt::machine::SitIx,
                    cx: &mut #rt::machine::Cx<'_, '_, super::Program>,
                ) -> ::std::result::Result<::std::option::Option<#rt::machine::Step>, #rt::machine::RunError> {
                    if !matches!(*sit, #(#typed_ix)|*) {
                        return ::std::result::Result::Ok(::std::option::Option::None);
                    }
                    let ::std::option::Option::Some(mut fr) = Frame::load(p, cx) else {
                        return ::std::result::Result::Ok(::std::option::Option::None);
                    };
                    let mut run = cx.typed_run();
                    let r = typed_loop(p, *sit, &mut fr, ::std::option::Option::None, &mut run, cx);
                    cx.count_transitions(run.count);
                    fr.store(p, cx);
                    match r {
                        ::std::result::Result::Ok(#rt::machine::Step::GotoSit(at)) if run.untyped => {
                            *sit = at;
                            ::std::result::Result::Ok(::std::option::Option::None)
                        }
                        r => r.map(::std::option::Option::Some),
                    }
                }
            }
        };
        // Under the driver, each DM's loop is called from one place.
        let inline = if self.typed_calls() {
            quote!(#[inline])
        } else {
            quote!()
        };
        let items = quote! {
            #(#enums)*

            /// The DM's typed frame: what its typed situations use of its
            /// locals and parameters, as native values.
            #[derive(Clone, Copy, Debug)]
            pub struct Frame { #(#fields)* }

            impl Frame {
                /// The frame, if every value it holds has its type.
                pub fn load(p: &super::Program, cx: &#rt::machine::Cx<'_, '_, super::Program>) -> ::std::option::Option<Frame> {
                    let a = &p.atoms;
                    #(#loads)*
                    ::std::option::Option::Some(Frame { #(#inits)* })
                }

                /// The frame of a call of the DM as `call` whose machine
                /// frame is not pushed yet: the locals' defaults, the
                /// arguments of `call`, if every value has its type.
                #[allow(unreachable_code)]
                pub fn fresh(p: &super::Program, call: #rt::Term, cx: &#rt::machine::Cx<'_, '_, super::Program>) -> ::std::option::Option<Frame> {
                    let a = &p.atoms;
                    #(#fresh)*
                    ::std::option::Option::Some(Frame { #(#inits)* })
                }

                /// Writes the locals back into the machine's variables.
                pub fn store(&self, p: &super::Program, cx: &mut #rt::machine::Cx<'_, '_, super::Program>) {
                    let a = &p.atoms;
                    #(#stores)*
                }
            }

            #run_typed

            /// Runs typed situations from `sit` on the frame until the
            /// machine, untyped code or another DM is needed (a typed call
            /// returns its `Step::Call`). `exit`: the final id of the DM
            /// that `sit`, a typed call, waited for; its exit arcs run first.
            /// `untyped` is set when the returned `GotoSit` situation must
            /// run untyped.
            #[allow(unreachable_code, clippy::never_loop, clippy::too_many_arguments)]
            #inline
            pub fn typed_loop(
                p: &super::Program,
                mut sit: #rt::machine::SitIx,
                fr: &mut Frame,
                mut exit: ::std::option::Option<#rt::Term>,
                run: &mut #rt::machine::TypedRun,
                cx: &mut #rt::machine::Cx<'_, '_, super::Program>,
            ) -> ::std::result::Result<#rt::machine::Step, #rt::machine::RunError> {
                #loop_prelude
                #loop_body
            }
        };
        TypedCode {
            items,
            present: true,
        }
    }

    /// Whether some situation of the program is a typed call (then the
    /// program-level driver runs every DM's typed code).
    pub(super) fn typed_calls(&self) -> bool {
        self.types.as_ref().is_some_and(|t| {
            t.dms
                .iter()
                .flat_map(|d| &d.situations)
                .any(|s| matches!(s, Ok(TSit::Call { .. })))
        })
    }

    /// A typed call: the first visit returns the machine's `Step::Call`
    /// (the driver pushes the callee's typed frame, or hands the call to the
    /// machine); when the callee has ended, `exit` holds its final id and
    /// the exit arcs run here: the first whose atom is that id, else the
    /// machine's own choice (which reports a missing exit). The pipe the
    /// callee left is read again into the frame; a value of another type
    /// sends the next situation to the untyped path.
    fn typed_call(
        &self,
        dm: &IrDm,
        t: &DmTypes,
        sit: usize,
        id: Atom,
        callee: ((usize, Atom), sitlog_runtime::Term),
        arcs: &[crate::types::TArc],
    ) -> TokenStream {
        let rt = quote!(::sitlog_runtime);
        let ix = Literal::u32_unsuffixed(sit as u32);
        let id_expr = self.atom_expr(id);
        let here = quote!(cx.enter(#ix, #id_expr););
        let ((callee_ix, _), call) = callee;
        let callee_ix = Literal::u32_unsuffixed(callee_ix as u32);
        let callee = self.typed_const(call);
        let exps: Vec<TokenStream> = arcs
            .iter()
            .map(|a| self.typed_const(a.expectation))
            .collect();
        let enames: Vec<Ident> = (0..arcs.len()).map(|j| format_ident!("e{}", j)).collect();
        let js: Vec<Literal> = (0..arcs.len()).map(Literal::usize_unsuffixed).collect();
        let reload = if t.frame_pipe() {
            let of = match t.pipe.as_ref().map(|v| &v.ty) {
                Some(Ty::Float) => quote!(float_of),
                _ => quote!(int_of),
            };
            quote! {
                match cx.#of(cx.pipe()) {
                    ::std::option::Option::Some(v) => fr.pipe = v,
                    ::std::option::Option::None => {
                        cx.enter(target, next);
                        run.untyped = true;
                        return ::std::result::Result::Ok(#rt::machine::Step::GotoSit(target));
                    }
                }
            }
        } else {
            quote!()
        };
        let mut match_arms = Vec::new();
        for (j, arc) in arcs.iter().enumerate() {
            let code = self.typed_arc(dm, t, sit, id, j, arc, None);
            let j = Literal::usize_unsuffixed(j);
            match_arms.push(quote!(#j => { #code #reload }));
        }
        quote! {
            match exit.take() {
                ::std::option::Option::Some(final_id) => {
                    #(let #enames = #exps;)*
                    let chosen = #(if final_id == #enames { #js } else)* {
                        #here
                        cx.set_expectations(&[#(#enames),*]);
                        cx.choose_exit(final_id)?
                    };
                    match chosen {
                        #(#match_arms)*
                        _ => unreachable!("the machine chose an arc of this situation"),
                    }
                }
                ::std::option::Option::None => {
                    #here
                    run.call = ::std::option::Option::Some(#callee_ix);
                    return ::std::result::Result::Ok(#rt::machine::Step::Call {
                        call: #callee,
                        saved: #rt::Term::NIL,
                    });
                }
            }
        }
    }

    /// The program's typed driver, when it has typed calls: every DM's
    /// typed frame as one `enum`, and `run_typed`, which runs typed code
    /// across DMs. A typed call stores the caller's frame, pushes the
    /// callee's machine frame (as the machine would) and its typed frame
    /// on a fixed array (no Rust recursion, no allocation; deeper calls go
    /// through the machine); a typed final pops both and runs the caller's
    /// exit arcs. Whatever else happens returns to the machine with its DM
    /// stack as it would be had the machine run every step, each frame's
    /// locals written back: the step is for the DM that runs then.
    pub(super) fn typed_driver(&self, mods: &[Ident]) -> TokenStream {
        let rt = quote!(::sitlog_runtime);
        let Some(types) = self.types.as_ref().filter(|_| self.typed_calls()) else {
            return quote!();
        };
        let mut variants = Vec::new();
        let mut loads = Vec::new();
        let mut freshes = Vec::new();
        let mut stores = Vec::new();
        let mut runs = Vec::new();
        for (d, t) in types.dms.iter().enumerate() {
            if !t
                .situations
                .iter()
                .any(|s| matches!(s, Ok(TSit::Perceptual { .. } | TSit::Call { .. })))
            {
                continue;
            }
            let v = format_ident!("Dm{}", d);
            let m = &mods[d];
            let ix = Literal::u32_unsuffixed(d as u32);
            variants.push(quote!(#v(#m::Frame),));
            loads.push(quote! {
                #ix if #m::is_typed(sit) => #m::Frame::load(p, cx).map(TypedFrame::#v),
            });
            freshes.push(quote! {
                #ix if #m::is_typed(0) => #m::Frame::fresh(p, call, cx).map(TypedFrame::#v),
            });
            stores.push(quote!(TypedFrame::#v(fr) => fr.store(p, cx),));
            runs.push(quote! {
                TypedFrame::#v(fr) => #m::typed_loop(p, sit, fr, exit, run, cx),
            });
        }
        quote! {
            /// Every DM's typed frame, for the typed DM stack of
            /// [`run_typed`].
            #[derive(Clone, Copy, Debug)]
            #[allow(dead_code, clippy::all)]
            enum TypedFrame { #(#variants)* }

            #[allow(dead_code, unused_variables, clippy::all)]
            impl TypedFrame {
                /// DM `dm`'s frame, if `sit` has typed code and the frame loads.
                fn load(p: &Program, dm: #rt::machine::DmIx, sit: #rt::machine::SitIx, cx: &#rt::machine::Cx<'_, '_, Program>) -> ::std::option::Option<TypedFrame> {
                    match dm {
                        #(#loads)*
                        _ => ::std::option::Option::None,
                    }
                }
                /// DM `dm`'s frame for a call as `call` whose machine frame
                /// is not pushed yet, if its initial situation has typed
                /// code and the frame loads.
                fn fresh(p: &Program, dm: #rt::machine::DmIx, call: #rt::Term, cx: &#rt::machine::Cx<'_, '_, Program>) -> ::std::option::Option<TypedFrame> {
                    match dm {
                        #(#freshes)*
                        _ => ::std::option::Option::None,
                    }
                }
                fn store(&self, p: &Program, cx: &mut #rt::machine::Cx<'_, '_, Program>) {
                    match self { #(#stores)* }
                }
                #[allow(clippy::too_many_arguments)]
                fn run(
                    &mut self,
                    p: &Program,
                    sit: #rt::machine::SitIx,
                    exit: ::std::option::Option<#rt::Term>,
                    run: &mut #rt::machine::TypedRun,
                    cx: &mut #rt::machine::Cx<'_, '_, Program>,
                ) -> ::std::result::Result<#rt::machine::Step, #rt::machine::RunError> {
                    match self { #(#runs)* }
                }
            }

            /// How deep typed calls nest on the typed stack before the
            /// machine takes the next one.
            const TYPED_DEPTH: usize = 32;

            /// Runs typed code from situation `sit` of DM `dm` (the running
            /// one), across typed calls. `None`: nothing done (`sit` not
            /// typed, the frame does not load, or typed code handed `sit`,
            /// written there, to the DM's untyped path). `Some((step,
            /// same))`: the step for the DM that runs now, `same` when that
            /// is still `dm`.
            #[allow(dead_code, clippy::all)]
            pub fn run_typed(
                p: &Program,
                dm: #rt::machine::DmIx,
                sit: &mut #rt::machine::SitIx,
                cx: &mut #rt::machine::Cx<'_, '_, Program>,
            ) -> ::std::result::Result<::std::option::Option<(#rt::machine::Step, bool)>, #rt::machine::RunError> {
                let ::std::option::Option::Some(mut frame) = TypedFrame::load(p, dm, *sit, cx) else {
                    return ::std::result::Result::Ok(::std::option::Option::None);
                };
                let mut run = cx.typed_run();
                let mut stack = [frame; TYPED_DEPTH];
                let mut depth = 0usize;
                let mut at = *sit;
                let mut exit = ::std::option::Option::None;
                let r = loop {
                    let r = frame.run(p, at, exit.take(), &mut run, cx);
                    // A typed call (its step is `Step::Call` with the
                    // callee's atom and nothing saved), read from `run`.
                    match (run.call.take(), &r) {
                        (::std::option::Option::Some(callee), ::std::result::Result::Ok(#rt::machine::Step::Call { call, .. }))
                            if depth < TYPED_DEPTH && !cx.stop_requested() =>
                        {
                            let call = *call;
                            frame.store(p, cx);
                            // Without history the callee's machine frame is
                            // pushed only if something reads the DM stack.
                            let lazy = !run.records;
                            let pushed = if lazy {
                                cx.call_typed_lazy(callee, call, #rt::Term::NIL)
                            } else {
                                cx.call_typed(callee, call, #rt::Term::NIL)
                            };
                            if let ::std::result::Result::Err(e) = pushed {
                                break ::std::result::Result::Err(e);
                            }
                            stack[depth] = frame;
                            depth += 1;
                            let callee_frame = if lazy {
                                TypedFrame::fresh(p, callee, call, cx)
                            } else {
                                TypedFrame::load(p, callee, 0, cx)
                            };
                            match callee_frame {
                                ::std::option::Option::Some(f) => {
                                    frame = f;
                                    at = 0;
                                }
                                ::std::option::Option::None => {
                                    // The callee starts untyped, from the machine.
                                    cx.materialize_frames();
                                    cx.count_transitions(run.count);
                                    return ::std::result::Result::Ok(::std::option::Option::Some((#rt::machine::Step::GotoSit(0), false)));
                                }
                            }
                            continue;
                        }
                        _ => {}
                    }
                    match r {
                        ::std::result::Result::Ok(#rt::machine::Step::Final) if depth > 0 => {
                            exit = ::std::option::Option::Some(cx.return_typed());
                            depth -= 1;
                            frame = stack[depth];
                            at = cx.situation();
                        }
                        r => break r,
                    }
                };
                // The DM stack as the machine would have it, then each
                // frame's locals where the machine keeps them.
                cx.materialize_frames();
                cx.count_transitions(run.count);
                frame.store(p, cx);
                let same = depth == 0;
                match r {
                    ::std::result::Result::Ok(#rt::machine::Step::GotoSit(to)) if run.untyped && same => {
                        *sit = to;
                        ::std::result::Result::Ok(::std::option::Option::None)
                    }
                    r => r.map(|step| ::std::option::Option::Some((step, same))),
                }
            }
        }
    }

    /// A constant term (expectation, action element): an immediate or a `k` constant.
    fn typed_const(&self, t: sitlog_runtime::Term) -> TokenStream {
        self.leaf(t, &HashMap::new(), false)
            .expect("constants are leaves or registered constants")
    }

    fn typed_val(&self, v: &TVal) -> TokenStream {
        match v {
            TVal::Local(i) => {
                let f = local_field(*i);
                quote!(fr.#f)
            }
            TVal::Param(i) => {
                let f = param_field(*i);
                quote!(fr.#f)
            }
            TVal::Pipe => quote!(fr.pipe),
            TVal::Var(v) => {
                let w = format_ident!("w{}", *v);
                quote!(#w)
            }
            TVal::Int(i) => {
                let lit = Literal::i64_suffixed(*i);
                quote!(#lit)
            }
            TVal::Float(f) => {
                let bits = Literal::u64_suffixed(f.to_bits());
                quote!(f64::from_bits(#bits))
            }
            TVal::Atom(a) => self.atom_term(*a),
        }
    }

    /// A typed atom operand as a `Term`.
    fn atom_operand(&self, v: &TVal) -> TokenStream {
        match v {
            TVal::Atom(a) => self.atom_term(*a),
            v => {
                let e = self.typed_val(v);
                quote!(#e.term(p))
            }
        }
    }

    /// The term of a native value of local `i`'s type.
    fn native_term(&self, t: &DmTypes, local: usize, e: TokenStream) -> TokenStream {
        let rt = quote!(::sitlog_runtime);
        match &t.locals[local].ty {
            Ty::Int => quote!(#rt::Term::int(#e)),
            Ty::Float => quote!(#rt::Term::float(#e)),
            _ => quote!(#e.term(p)),
        }
    }

    /// The native value of local `i`'s default (`default`, the IR's term),
    /// or code that gives up on the fresh frame when it is not a constant
    /// of the local's type (the machine then makes the frame).
    fn native_default(
        &self,
        t: &DmTypes,
        local: usize,
        default: sitlog_runtime::Term,
    ) -> TokenStream {
        let fits = match (&t.locals[local].ty, self.store.value(default)) {
            (Ty::Int, sitlog_runtime::Value::Int(_))
            | (Ty::Float, sitlog_runtime::Value::Float(_)) => true,
            (Ty::Atoms(atoms), sitlog_runtime::Value::Atom(a)) => atoms.contains(&a),
            _ => false,
        };
        if fits {
            self.native_const(t, local, default)
        } else {
            quote!(return ::std::option::Option::None)
        }
    }

    /// The native value of a constant of local `i`'s type.
    fn native_const(&self, t: &DmTypes, local: usize, c: sitlog_runtime::Term) -> TokenStream {
        match (&t.locals[local].ty, self.store.value(c)) {
            (Ty::Int, sitlog_runtime::Value::Int(i)) => {
                let lit = Literal::i64_suffixed(i);
                quote!(#lit)
            }
            (Ty::Float, sitlog_runtime::Value::Float(f)) => {
                let bits = Literal::u64_suffixed(f.to_bits());
                quote!(f64::from_bits(#bits))
            }
            (Ty::Atoms(atoms), sitlog_runtime::Value::Atom(a)) => {
                let e = atoms_enum(local);
                let j = atoms
                    .iter()
                    .position(|x| *x == a)
                    .expect("checked by inference");
                let v = format_ident!("A{}", j);
                quote!(#e::#v)
            }
            _ => unreachable!("checked by inference"),
        }
    }

    /// A typed `prog` expression: `i64`, each operation checked (`bail`
    /// when it overflows).
    fn typed_expr(&self, e: &TExpr, bail: &TokenStream) -> TokenStream {
        match e {
            TExpr::Val(v) => self.typed_val(v),
            TExpr::Bin(op, a, b) => {
                let (a, b) = (self.typed_expr(a, bail), self.typed_expr(b, bail));
                let f = match op {
                    '+' => format_ident!("checked_add"),
                    '-' => format_ident!("checked_sub"),
                    _ => format_ident!("checked_mul"),
                };
                quote! {
                    match (#a).#f(#b) {
                        ::std::option::Option::Some(v) => v,
                        ::std::option::Option::None => #bail,
                    }
                }
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn typed_arc(
        &self,
        dm: &IrDm,
        t: &DmTypes,
        sit: usize,
        sit_id: Atom,
        j: usize,
        arc: &crate::types::TArc,
        out_var: Option<u32>,
    ) -> TokenStream {
        let rt = quote!(::sitlog_runtime);
        let sit_ix = Literal::u32_unsuffixed(sit as u32);
        let id = self.atom_expr(sit_id);
        let here = quote!(cx.enter(#sit_ix, #id););
        let arc_ix = Literal::usize_unsuffixed(j);
        let arc_t = quote!(::std::option::Option::Some(#arc_ix));
        let e = format_ident!("e{}", j);
        let mut out = Vec::new();
        // The action.
        let action = match &arc.action {
            TAction::Const(c) => {
                let c = self.typed_const(*c);
                let numeric = matches!(
                    self.store.value(arc_const(arc)),
                    sitlog_runtime::Value::Int(_) | sitlog_runtime::Value::Float(_)
                );
                let perform = quote! { #here cx.perform(action, #arc_t)?; };
                out.push(quote!(let action = #c;));
                let empty = self.store.atom_of(arc_const(arc)) == Some(sitlog_syntax::atoms::EMPTY);
                out.push(if numeric {
                    quote!(if !run.quiet_numbers { #perform })
                } else if empty {
                    quote!(if !run.quiet_empty { #perform })
                } else {
                    perform
                });
                quote!(action)
            }
            TAction::List(items) => {
                let mut values = Vec::new();
                let mut numeric = true;
                for (n, it) in items.iter().enumerate() {
                    let x = format_ident!("x{}", n);
                    match it {
                        TItem::Inc { local, bind } | TItem::Get { local, bind } => {
                            let f = local_field(*local);
                            if let TItem::Inc { .. } = it {
                                let name = dm.locals[*local].0.as_str();
                                let msg = Literal::string(&format!(
                                    "`inc` of `{name}`: integer overflow"
                                ));
                                let next = match t.locals[*local].ty {
                                    Ty::Int => quote! {
                                        match fr.#f.checked_add(1) {
                                            ::std::option::Option::Some(v) => v,
                                            ::std::option::Option::None => {
                                                #here
                                                return ::std::result::Result::Err(cx.error(#msg, #arc_t));
                                            }
                                        }
                                    },
                                    _ => quote!(fr.#f + 1.0),
                                };
                                out.push(quote!(fr.#f = #next;));
                            }
                            let native = quote!(fr.#f);
                            if let Some(v) = bind {
                                let w = format_ident!("w{}", *v);
                                out.push(quote!(let #w = #native;));
                            }
                            numeric &= matches!(t.locals[*local].ty, Ty::Int | Ty::Float);
                            let term = self.native_term(t, *local, native);
                            out.push(quote!(let #x = #term;));
                        }
                        TItem::Set { local, value } => {
                            let f = local_field(*local);
                            let c = self.native_const(t, *local, *value);
                            out.push(quote!(fr.#f = #c;));
                            numeric &= matches!(t.locals[*local].ty, Ty::Int | Ty::Float);
                            let c = self.typed_const(*value);
                            out.push(quote!(let #x = #c;));
                        }
                        TItem::Const(c) => {
                            numeric &= matches!(
                                self.store.value(*c),
                                sitlog_runtime::Value::Int(_) | sitlog_runtime::Value::Float(_)
                            );
                            let c = self.typed_const(*c);
                            out.push(quote!(let #x = #c;));
                        }
                    }
                    values.push(x);
                }
                let perform = quote! { #here cx.perform_each(&[#(#values),*], #arc_t)?; };
                out.push(if numeric {
                    quote!(if !run.quiet_numbers { #perform })
                } else {
                    perform
                });
                quote!(cx.store().list(&[#(#values),*]))
            }
        };
        // The next situation.
        let next = self.typed_next(&arc.next);
        out.push(quote!(let (target, next) = #next;));
        // The out_arg: `prog`'s value becomes the pipe (D-18).
        if let Some(v) = out_var {
            let w = format_ident!("w{}", v);
            out.push(quote!(cx.set_pipe(#rt::Term::int(#w));));
            if t.frame_pipe() {
                out.push(quote!(fr.pipe = #w;));
            }
        }
        out.push(quote! {
            if run.records {
                #here
                let action = #action;
                cx.record(#e, action, ::std::option::Option::Some(#rt::Term::atom(next)));
                if cx.gc_due() {
                    return ::std::result::Result::Ok(#rt::machine::Step::GotoSit(target));
                }
            } else {
                run.count += 1;
            }
            sit = target;
        });
        quote!(#(#out)*)
    }

    /// `(index, atom)` of a typed next situation.
    fn typed_next(&self, n: &TNext) -> TokenStream {
        match n {
            TNext::Sit(ix, name) => {
                let ix = Literal::u32_unsuffixed(*ix);
                let a = self.atom_expr(*name);
                quote!((#ix, #a))
            }
            TNext::If {
                op,
                a,
                b,
                then,
                other,
                ..
            } => {
                let c = match op {
                    Cmp::Arith(op) => {
                        let (a, b) = (self.typed_val(a), self.typed_val(b));
                        match op {
                            sitlog_runtime::ArithCmp::Eq => quote!(#a == #b),
                            sitlog_runtime::ArithCmp::Ne => quote!(#a != #b),
                            sitlog_runtime::ArithCmp::Lt => quote!(#a < #b),
                            sitlog_runtime::ArithCmp::Gt => quote!(#a > #b),
                            sitlog_runtime::ArithCmp::Le => quote!(#a <= #b),
                            sitlog_runtime::ArithCmp::Ge => quote!(#a >= #b),
                        }
                    }
                    // Atoms compare as terms (an atom-set value as its atom).
                    Cmp::Identical | Cmp::NotIdentical => {
                        let (a, b) = (self.atom_operand(a), self.atom_operand(b));
                        if *op == Cmp::Identical {
                            quote!(#a == #b)
                        } else {
                            quote!(#a != #b)
                        }
                    }
                };
                let (then, other) = (self.typed_next(then), self.typed_next(other));
                quote!(if #c { #then } else { #other })
            }
        }
    }
}

fn arc_const(arc: &crate::types::TArc) -> sitlog_runtime::Term {
    match arc.action {
        TAction::Const(c) => c,
        TAction::List(_) => unreachable!(),
    }
}
