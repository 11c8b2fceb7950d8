//! Native frames and the program's native stack (phase 5 of
//! `docs/design/typed-mir.md`, for native DMs): each native DM's `Frame`
//! (its parameters `p0..`, its locals `l0..`, an output slot `out<i>:
//! Option<T>` per output parameter a native caller may pass as
//! `Ground::OUT` (`super::call`), and the situation it is in, all native
//! values), its `nat_wait` and `nat_hand_over` (only a DM with locals,
//! written back there: the others use `machine::NatAt::nat_wait` and
//! `machine::nat_hand_over`), and in
//! the program's module `enum NatFrame` (a variant per native DM) with its
//! `machine::NatFrames` impl: a dispatch to each DM's module (a frame's call
//! term built there from its DM's name and parameters, for a history level
//! opened at a push). The stack
//! itself is the runtime's (`sitlog_runtime::machine::nat_drive`, generic
//! over the frame type: an explicit stack of native frames, each run where
//! it lies, no Rust recursion per nested DM, no term built), and so is the
//! hand-over (`machine::nat_materialize`: every native frame below the
//! running one becomes a machine frame, waiting in its recursive situation
//! as the interpreter's would, `Cx::wait_template`, its callee's frame
//! pushed with the call its `embedded_dm` makes).
//!
//! Invariant: the machine's DM stack is the native stack's bottom frame
//! (the DM the machine entered) and what is below it; native code reads or
//! writes the machine's frames (an action the machine performs, an error, a value
//! handed over, a value evaluated on terms) only after `nat_materialize`
//! and after writing its locals back ([`Dm::hand`]), so the machine sees,
//! at each such point, the stack and the locals the term path would have
//! (an effector native code hands an action to sees none of them: module
//! `effect`).
//! With the history kept (`run.nests`) each native frame above the bottom
//! one has a history level (`Machine::levels`, opened at its push, closed
//! at its final); `nat_materialize` pushes each of them as a machine frame
//! with its level as its history (`Cx::wait_template`), bottom first, so
//! no level is left when the machine runs (nor for its garbage collector,
//! which does not scan levels).

use super::Gen;
use super::{rust_ty, Dm, N};
use crate::ir::{Ir, IrDm};
use crate::mir::ty::DmTypes;
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::native::Ty;
use sitlog_syntax::Atom;

/// A native DM's `Frame` and the functions the driver calls on it.
pub(super) struct FrameItems {
    pub items: TokenStream,
    /// The frame's fields but `at`: `p0.., l0..`.
    pub names: Vec<Ident>,
    /// The output slots `out<i>` (one per output parameter, `Dm::outputs`).
    pub outs: Vec<Ident>,
}

impl Gen<'_> {
    /// The DM's locals with their types, as native code holds them.
    pub(super) fn nat_locals(&self, dm: &IrDm, t: &DmTypes) -> N<Vec<(Atom, Ty)>> {
        dm.locals
            .iter()
            .map(|(name, _)| {
                let ty = t
                    .locals
                    .iter()
                    .find(|(n, _)| n == name)
                    .map_or(Ty::Term, |(_, x)| x.ty.clone());
                let ty = if ty == Ty::Never { Ty::Term } else { ty };
                rust_ty(&ty).map_err(|e| format!("local `{}`: {e}", name.as_str()))?;
                Ok((*name, ty))
            })
            .collect()
    }

    /// The locals written back to the machine's frame of this DM.
    fn nat_write_locals(&self, d: &Dm) -> N<TokenStream> {
        let mut out = Vec::new();
        for (i, (name, _)) in d.locals.iter().enumerate() {
            let a = self.atom_native(*name)?;
            let l = format_ident!("l{}", i);
            out.push(quote! {
                let lt = cx.term(&*#l);
                cx.set_local(#a, lt);
            });
        }
        Ok(quote!(#(#out)*))
    }

    /// [`Dm::hand`]: before native code hands over or lets the machine
    /// see its state, the native frames below become machine frames (the
    /// runtime's `nat_hand_over`) and the locals are written
    /// back (a DM with locals: its own `nat_hand_over`).
    pub(super) fn nat_hand(&self, d: &Dm) -> N<TokenStream> {
        let locals = Self::nat_local_names(d);
        if locals.is_empty() {
            return Ok(quote!(super::nat_hand_over(p, cx, stack)?;));
        }
        Ok(quote!(nat_hand_over(p, cx, stack, #(&*#locals),*)?;))
    }

    /// The frame's locals: `l0..`.
    fn nat_local_names(d: &Dm) -> Vec<Ident> {
        (0..d.locals.len())
            .map(|i| format_ident!("l{}", i))
            .collect()
    }

    /// `nat_hand_over` of a DM with locals, the code of [`Dm::hand`], out
    /// of line: the runtime's `machine::nat_hand_over`, then the locals
    /// written back (none for a DM without locals: the runtime's serves
    /// it).
    fn nat_hand_fn(&self, d: &Dm) -> N<TokenStream> {
        let names = Self::nat_local_names(d);
        if names.is_empty() {
            return Ok(quote!());
        }
        let locals = self.nat_write_locals(d)?;
        let tys = d
            .locals
            .iter()
            .map(|(_, t)| rust_ty(t))
            .collect::<N<Vec<_>>>()?;
        Ok(quote! {
            #[cold]
            #[inline(never)]
            fn nat_hand_over(
                p: &Program,
                cx: &mut Ctx,
                stack: &mut super::NatBelow<'_>,
                #(#names: &#tys,)*
            ) -> Result<(), RunError> {
                let a = &p.atoms;
                machine::nat_hand_over(p, cx, stack)?;
                #locals
                Ok(())
            }
        })
    }

    /// `struct Frame`, `nat_hand_over`, `nat_wait` of a native DM
    /// (`wait_arms`: per recursive situation, its waiting variant made a
    /// machine frame's pending situation, given only for a DM with locals;
    /// none: no `nat_wait`, the program's dispatch calls the runtime's
    /// `NatAt::nat_wait` on the frame's `Nat`).
    pub(super) fn nat_frame_items(&self, d: &Dm, wait_arms: &[TokenStream]) -> N<FrameItems> {
        let mut names = Vec::new();
        let mut decls = Vec::new();
        for (i, ty) in d.params.iter().enumerate() {
            let n = format_ident!("p{}", i);
            let ty = rust_ty(ty)?;
            decls.push(quote!(pub #n: #ty));
            names.push(n);
        }
        for (i, (_, ty)) in d.locals.iter().enumerate() {
            let n = format_ident!("l{}", i);
            let ty = rust_ty(ty)?;
            decls.push(quote!(pub #n: #ty));
            names.push(n);
        }
        // An output parameter's slot: the value a final hands back to a
        // native caller that passed `Ground::OUT` there (`native::call`).
        let mut outs = Vec::new();
        for (i, ty) in d.outputs.iter().enumerate() {
            if let Some(ty) = ty {
                let n = format_ident!("out{}", i);
                let ty = rust_ty(ty)?;
                decls.push(quote!(pub #n: Option<#ty>));
                outs.push(n);
            }
        }
        let rest = if outs.is_empty() {
            quote!()
        } else {
            quote!(..)
        };
        let locals = self.nat_write_locals(d)?;
        let hand_fn = self.nat_hand_fn(d)?;
        // `nat_wait` binds what its arms read (the atoms, the fields).
        let wait_body = quote!(#locals #(#wait_arms)*);
        let wait_a = if super::call::mentions(&wait_body, &format_ident!("a")) {
            quote!(let a = &p.atoms;)
        } else {
            quote!()
        };
        let wait_names = names
            .iter()
            .filter(|x| super::call::mentions(&wait_body, x))
            .collect::<Vec<_>>();
        let rest = if wait_names.len() < names.len() {
            quote!(..)
        } else {
            rest
        };
        // A DM without locals or without waiting situations: `NatAt::nat_wait`
        // on its `Nat` (the program's dispatch calls it).
        let wait_fn = if wait_arms.is_empty() {
            quote!()
        } else {
            quote! {
                pub(crate) fn nat_wait(
                    p: &Program,
                    cx: &mut Ctx,
                    frame: &Frame,
                ) -> Result<(), RunError> {
                    #wait_a
                    let Frame { #(#wait_names,)* at, #rest } = frame;
                    #locals
                    match at {
                        #(#wait_arms)*
                        _ => Err(cx.fault(Fault::WaitsForNone)),
                    }
                }
            }
        };
        let items = quote! {
            #hand_fn

            pub struct Frame { #(#decls,)* pub at: Nat }

            #wait_fn
        };
        Ok(FrameItems { items, names, outs })
    }

    /// Whether DM `dm`'s head is an atom (no parameters: its call term is
    /// the atom, made by the program's `NatFrames::call_term`).
    fn head_is_atom(&self, dm: &IrDm) -> bool {
        matches!(self.store.value(dm.head), sitlog_runtime::Value::Atom(_))
    }

    /// Whether DM `d` has native code (a `Frame`), and whether a call of
    /// it may push its frame on the native stack (see
    /// [`NativeCode::callee_ok`](super::NativeCode)); decided with every
    /// call handed to the machine, memoized.
    pub(super) fn native_ok(&self, d: usize) -> (bool, bool) {
        if let Some(&ok) = self.native_ok.borrow().get(&d) {
            return ok;
        }
        let ok = match (self.ir, &self.mir_types) {
            (Some(ir), Some(t)) => match self.native_code_with(&ir.dms[d], d, &t.dms[d], true) {
                Ok(n) if n.native_sits > 0 => (true, n.callee_ok),
                _ => (false, false),
            },
            _ => (false, false),
        };
        self.native_ok.borrow_mut().insert(d, ok);
        ok
    }

    /// The native DM `j`'s plans and types, as its own code sees them,
    /// when a call of it may push its frame.
    pub(super) fn nat_dm_of(&self, j: usize) -> Option<Dm<'_>> {
        let (ir, t) = (self.ir?, self.mir_types.as_ref()?);
        if !self.native_ok(j).1 {
            return None;
        }
        let t = super::unread_as_term_dm(&t.dms[j]);
        self.nat_dm_fix(&ir.dms[j], j, &t, true)
            .ok()
            .map(|(d, _, _)| d)
    }

    /// The program's native frames (see the module doc): `enum NatFrame`,
    /// its `machine::NatFrames` dispatch to each DM's module, and the
    /// names the DMs' code gives the runtime's native stack; nothing when
    /// no DM is native. `modules`: the DMs' code, whose `NatF<d>`/`NatN<d>`
    /// aliases (a native DM's `Frame` and `Nat` named from another DM)
    /// are the only ones written.
    pub(in crate::codegen) fn native_driver(
        &self,
        ir: &Ir,
        mods: &[Ident],
        modules: &[TokenStream],
    ) -> TokenStream {
        let native: Vec<usize> = (0..ir.dms.len()).filter(|&d| self.native_ok(d).0).collect();
        if native.is_empty() {
            return quote!();
        }
        let mut used = std::collections::HashSet::new();
        for m in modules {
            super::super::emit::idents_in(m, &mut used);
        }
        // A DM with its own `nat_wait` (locals written back first), else
        // `NatAt::nat_wait` of the frame's situation.
        let wait_arms: Vec<TokenStream> = native
            .iter()
            .map(|&d| {
                let (v, m) = (format_ident!("D{}", d), &mods[d]);
                let mut own = std::collections::HashSet::new();
                super::super::emit::idents_in(&modules[d], &mut own);
                if own.contains("nat_wait") {
                    quote!(NatFrame::#v(f) => #m::nat_wait(p, cx, f),)
                } else {
                    quote!(NatFrame::#v(f) => f.at.nat_wait(p, cx),)
                }
            })
            .collect();
        let vs: Vec<Ident> = native.iter().map(|d| format_ident!("D{}", d)).collect();
        let ms: Vec<&Ident> = native.iter().map(|&d| &mods[d]).collect();
        let mut aliases = Vec::new();
        for &d in &native {
            let m = &mods[d];
            let f = format_ident!("NatF{}", d);
            if used.contains(&f.to_string()) {
                aliases.push(quote!(pub(crate) type #f = #m::Frame;));
            }
            let n = format_ident!("NatN{}", d);
            if used.contains(&n.to_string()) {
                aliases.push(quote!(pub(crate) type #n = #m::Nat;));
            }
        }
        // The call term of a frame: its DM's name and parameters (read in
        // place; an atom for a DM whose head is an atom).
        let call_arms: Vec<TokenStream> = native
            .iter()
            .map(|&d| {
                let v = format_ident!("D{}", d);
                let a = &self.atoms[self.atom_ix[&ir.dms[d].name]].1;
                if self.head_is_atom(&ir.dms[d]) {
                    quote!(NatFrame::#v(_) => cx.build_of(p.atoms.#a, &[]),)
                } else {
                    let n = self.store.args(ir.dms[d].head).len();
                    let ps = (0..n).map(|i| format_ident!("p{}", i));
                    quote!(NatFrame::#v(f) => cx.build_of(p.atoms.#a, &[#(&f.#ps),*]),)
                }
            })
            .collect();
        quote! {
            /// A frame of the native stack: one variant per native DM.
            #[allow(dead_code, clippy::all)]
            pub(crate) enum NatFrame { #(#vs(#ms::Frame),)* }

            #(#aliases)*

            /// The native frames below the running one, as its code sees
            /// them (`machine::NatBelow`).
            pub(crate) type NatBelow<'s> = machine::NatBelow<'s, NatFrame>;

            /// The hand-over of a DM without locals.
            #[allow(unused_imports)]
            pub(crate) use ::sitlog_runtime::machine::nat_hand_over;

            /// What the runtime's native stack (`machine::nat_drive`) asks of
            /// a frame, each a dispatch to the frame's DM.
            #[allow(clippy::all)]
            impl machine::NatFrames<Program> for NatFrame {
                fn step(
                    &mut self,
                    p: &Program,
                    cx: &mut Cx<'_, '_, Program>,
                    ret: Option<&mut NatFrame>,
                    stack: &mut NatBelow<'_>,
                    call: &mut Option<NatFrame>,
                    run: &TypedRun,
                ) -> Result<Option<Step>, RunError> {
                    match self { #(NatFrame::#vs(f) => #ms::nat_step(p, cx, f, ret, stack, call, run),)* }
                }
                fn call_term(&self, p: &Program, cx: &mut Cx<'_, '_, Program>) -> Term {
                    match self { #(#call_arms)* }
                }
                /// `*self = next`, `self` a frame that reached its final:
                /// no drop code for a DM whose frame holds nothing to drop.
                #[inline(always)]
                fn replace_done(&mut self, next: NatFrame) {
                    let plain = match self { #(NatFrame::#vs(f) => machine::nat_plain(f),)* };
                    machine::nat_replace_done(self, next, plain)
                }
                fn wait(&self, p: &Program, cx: &mut Cx<'_, '_, Program>) -> Result<(), RunError> {
                    match self { #(#wait_arms)* }
                }
            }
        }
    }
}
