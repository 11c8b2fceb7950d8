//! Native frames and the program's native driver (phase 5 of
//! `docs/design/typed-mir.md`, for native DMs): each native DM's `Frame`
//! (its parameters `p0..`, its locals `l0..`, an output slot `out<i>:
//! Option<T>` per output parameter a native caller may pass as
//! `Ground::OUT` (`super::call`), and the situation it is in, all native
//! values), and in the program's module `enum NatFrame` (a
//! variant per native DM), `nat_drive` (the explicit stack of native
//! frames, each run where it lies: a callee runs where the driver holds
//! it and, at a final reached without calling, its caller resumes at once
//! with a reference to it (a call and its return in one turn, nothing
//! pushed); a callee that calls in turn is pushed, and its final resumes
//! the caller with a reference to it, then pops it (or gives its slot to
//! the caller's next call, made at once: without drop code when the
//! finished callee's DM holds nothing to drop); the depth room read from
//! the machine once, again only once the frames below became its own; no
//! frame moved out and back per step, no Rust recursion per nested DM, no term
//! built) and
//! `nat_materialize` (the hand-over: every native frame below the running
//! one becomes a machine frame, waiting in its recursive situation as the
//! interpreter's would, `Cx::wait_template`).
//!
//! Invariant: the machine's DM stack is the native stack's bottom frame
//! (the DM the machine entered) and what is below it; native code reads or
//! writes the machine's frames (an action performed, an error, a value
//! handed over, a value evaluated on terms) only after `nat_materialize`
//! and after writing its locals back ([`Dm::hand`]), so the machine sees,
//! at each such point, the stack and the locals the term path would have.
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
use proc_macro2::{Ident, Literal, TokenStream};
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

    /// The call term of the running frame, from its parameters (bound as
    /// references `p0..`).
    fn nat_call_term(&self, d: &Dm) -> N<TokenStream> {
        let name = self.atom_native(d.dm.name)?;
        let ps: Vec<Ident> = (0..d.params.len())
            .map(|i| format_ident!("p{}", i))
            .collect();
        Ok(quote!(cx.build_of(#name, &[#(#ps),*])))
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
    /// see its state, the native frames below become machine frames and
    /// the locals are written back.
    pub(super) fn nat_hand(&self, d: &Dm) -> N<TokenStream> {
        let names = Self::nat_frame_names(d);
        if names.is_empty() {
            // The program's, for a DM without parameters or locals.
            let dm = Literal::u32_unsuffixed(d.ix as u32);
            return Ok(quote!(super::nat_hand_over(p, cx, stack, #dm)?;));
        }
        Ok(quote!(nat_hand_over(p, cx, stack, #(&*#names),*)?;))
    }

    /// The frame's fields but `at`: `p0.., l0..`.
    fn nat_frame_names(d: &Dm) -> Vec<Ident> {
        (0..d.params.len())
            .map(|i| format_ident!("p{}", i))
            .chain((0..d.locals.len()).map(|i| format_ident!("l{}", i)))
            .collect()
    }

    /// `nat_hand_over`, the code of [`Dm::hand`], out of line (none for
    /// a DM without parameters or locals: the program's serves it).
    fn nat_hand_fn(&self, d: &Dm) -> N<TokenStream> {
        let names = Self::nat_frame_names(d);
        if names.is_empty() {
            return Ok(quote!());
        }
        let call = self.nat_call_term(d)?;
        let dm = Literal::u32_unsuffixed(d.ix as u32);
        let locals = self.nat_write_locals(d)?;
        let tys = d
            .params
            .iter()
            .chain(d.locals.iter().map(|(_, t)| t))
            .map(rust_ty)
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
                if !stack.is_empty() {
                    let own_call = #call;
                    super::nat_materialize(p, cx, stack, own_call, #dm)?;
                }
                #locals
                Ok(())
            }
        })
    }

    /// `struct Frame`, `nat_call_term`, `nat_wait` of a native DM
    /// (`wait_arms`: per recursive situation, its waiting variant made a
    /// machine frame's pending situation; none: the program's
    /// `nat_wait_none`, re-exported).
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
        let call = self.nat_call_term(d)?;
        // The frame's fields the call term reads (none: no statement).
        let fields = (!names.is_empty()).then(|| quote!(let Frame { #(#names,)* .. } = frame;));
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
        // A DM without waiting situations: the program's `nat_wait_none`.
        let wait_fn = if wait_arms.is_empty() {
            quote!(
                pub(crate) use super::nat_wait_none as nat_wait;
            )
        } else {
            quote! {
                pub(crate) fn nat_wait(
                    p: &Program,
                    cx: &mut Ctx,
                    frame: &Frame,
                    callee: Term,
                    callee_dm: DmIx,
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

            pub(crate) fn nat_call_term(p: &Program, cx: &mut Ctx, frame: &Frame) -> Term {
                let a = &p.atoms;
                #fields
                #call
            }

            #wait_fn
        };
        Ok(FrameItems { items, names, outs })
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

    /// The program's native driver (see the module doc); nothing when no
    /// DM is native.
    pub(in crate::codegen) fn native_driver(&self, ir: &Ir, mods: &[Ident]) -> TokenStream {
        let native: Vec<usize> = (0..ir.dms.len()).filter(|&d| self.native_ok(d).0).collect();
        if native.is_empty() {
            return quote!();
        }
        let vs: Vec<Ident> = native.iter().map(|d| format_ident!("D{}", d)).collect();
        let ms: Vec<&Ident> = native.iter().map(|&d| &mods[d]).collect();
        let fs: Vec<Ident> = native.iter().map(|d| format_ident!("NatF{}", d)).collect();
        let ns: Vec<Ident> = native.iter().map(|d| format_ident!("NatN{}", d)).collect();
        let ixs: Vec<Literal> = native
            .iter()
            .map(|&d| Literal::u32_unsuffixed(d as u32))
            .collect();
        quote! {
            /// A frame of the native stack: one variant per native DM.
            #[allow(dead_code, clippy::all)]
            pub(crate) enum NatFrame { #(#vs(#ms::Frame),)* }

            #(
                #[allow(dead_code)]
                pub(crate) type #fs = #ms::Frame;
                #[allow(dead_code)]
                pub(crate) type #ns = #ms::Nat;
            )*

            #[allow(clippy::all)]
            impl NatFrame {
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
                    match self { #(NatFrame::#vs(f) => #ms::nat_call_term(p, cx, f),)* }
                }
                /// `*self = next`, `self` a frame that reached its final:
                /// no drop code for a DM whose frame holds nothing to drop.
                #[inline(always)]
                fn replace_done(&mut self, next: NatFrame) {
                    match self {
                        #(NatFrame::#vs(_) if !::std::mem::needs_drop::<#ms::Frame>() => {
                            ::std::mem::forget(::std::mem::replace(self, next))
                        })*
                        _ => *self = next,
                    }
                }
                fn dm(&self) -> DmIx {
                    match self { #(NatFrame::#vs(_) => #ixs,)* }
                }
                fn wait(
                    &self,
                    p: &Program,
                    cx: &mut Cx<'_, '_, Program>,
                    callee: Term,
                    callee_dm: DmIx,
                ) -> Result<(), RunError> {
                    match self { #(NatFrame::#vs(f) => #ms::nat_wait(p, cx, f, callee, callee_dm),)* }
                }
            }

            /// `nat_wait` of a DM without waiting situations: no frame of it
            /// waits for a callee.
            #[allow(dead_code, unused_variables)]
            pub(crate) fn nat_wait_none<F>(
                p: &Program,
                cx: &mut Cx<'_, '_, Program>,
                frame: &F,
                callee: Term,
                callee_dm: DmIx,
            ) -> Result<(), RunError> {
                Err(cx.fault(Fault::WaitsForNone))
            }

            /// The native frames below the running one, bottom first (the
            /// base frame, then the pushed ones); `gone` once they were made
            /// machine frames (`nat_materialize`): the running frame is the
            /// native stack's bottom from then on.
            pub(crate) struct NatBelow<'s> {
                base: Option<&'s NatFrame>,
                mid: &'s [NatFrame],
                gone: &'s mut bool,
                /// `Cx::depth_room` when the driver last looked (the
                /// machine's frames change only when the native ones become
                /// theirs, `gone`).
                room: usize,
            }

            #[allow(clippy::all)]
            impl NatBelow<'_> {
                /// How many native frames are below the running one.
                #[inline]
                pub(crate) fn len(&self) -> usize {
                    if *self.gone { 0 } else { usize::from(self.base.is_some()) + self.mid.len() }
                }
                /// Whether the running frame is the native stack's bottom.
                #[inline]
                pub(crate) fn is_empty(&self) -> bool {
                    self.len() == 0
                }
                /// Whether a callee's frame may go on the native stack: the
                /// frames below, the running one and the machine's stay
                /// within the depth limit (`Cx::depth_room` asked again
                /// once the frames below became the machine's).
                #[inline]
                pub(crate) fn has_room(&self, cx: &Cx<'_, '_, Program>) -> bool {
                    if *self.gone {
                        0 < cx.depth_room()
                    } else {
                        self.len() < self.room
                    }
                }
            }

            /// Runs native frames from `base` (the DM the machine entered)
            /// on an explicit stack until one hands over to the machine.
            /// Frames stay where they are while they run (`frames`, above
            /// `base`): a callee runs where the driver holds it, and when
            /// it reaches its final without calling, its caller's exit arcs
            /// read it there at once (a call and its return in one turn of
            /// the inner loop, no push, no pop); a callee that calls in turn
            /// (or below which the frames became the machine's) is pushed,
            /// and a pushed callee that reached its final is read in place
            /// by its caller's exit arcs, then popped. Never inlined (into the
            /// program's `run_situation`, its caller for an all-native DM:
            /// inlined there, its loop measured 2 instructions a call more).
            #[allow(clippy::all)]
            #[inline(never)]
            pub(crate) fn nat_drive(
                p: &Program,
                cx: &mut Cx<'_, '_, Program>,
                base: NatFrame,
                run: &TypedRun,
            ) -> Result<Step, RunError> {
                let mut base = base;
                let mut frames: Vec<NatFrame> = Vec::new();
                let mut call = None;
                // The top frame reached a final: its caller runs next.
                let mut returning = false;
                let mut gone = false;
                // The top frame already ran (a callee run where it is held,
                // below): only what it left is handled.
                let mut ran = false;
                let mut room = cx.depth_room();
                loop {
                    if !ran {
                        let n = frames.len();
                        let stepped = match (n, returning) {
                            (0, _) => {
                                let mut below = NatBelow { base: None, mid: &[], gone: &mut gone, room };
                                base.step(p, cx, None, &mut below, &mut call, run)
                            }
                            (1, true) => {
                                let mut below = NatBelow { base: None, mid: &[], gone: &mut gone, room };
                                base.step(p, cx, frames.last_mut(), &mut below, &mut call, run)
                            }
                            (_, true) => {
                                let (callee, rest) = frames.split_last_mut().unwrap();
                                let (top, mid) = rest.split_last_mut().unwrap();
                                let mut below = NatBelow { base: Some(&base), mid, gone: &mut gone, room };
                                top.step(p, cx, Some(callee), &mut below, &mut call, run)
                            }
                            (_, false) => {
                                let (top, mid) = frames.split_last_mut().unwrap();
                                let mut below = NatBelow { base: Some(&base), mid, gone: &mut gone, room };
                                top.step(p, cx, None, &mut below, &mut call, run)
                            }
                        };
                        if let Some(step) = stepped? {
                            return Ok(step);
                        }
                        if returning {
                            returning = false;
                            // The caller called again (a loop of calls): the
                            // new callee takes the finished one's place.
                            if !gone {
                                if let Some(callee) = call.take() {
                                    if let Some(top) = frames.last_mut() {
                                        *top = callee;
                                    }
                                    continue;
                                }
                            }
                            frames.pop();
                        }
                    }
                    ran = false;
                    if gone {
                        // The frames below the running one are the machine's now.
                        if let Some(top) = frames.pop() {
                            base = top;
                        }
                        frames.clear();
                        gone = false;
                        room = cx.depth_room();
                    }
                    let Some(mut callee) = call.take() else {
                        if frames.is_empty() {
                            return Err(cx.error(
                                "native code ended its base DM without handing over",
                                None,
                            ));
                        }
                        returning = true;
                        continue;
                    };
                    // The callee runs where it is held, not pushed: when it
                    // reaches its final without calling, its caller resumes
                    // reading it at once (one turn per call, no push, no pop).
                    loop {
                        let stepped = {
                            let mut below = NatBelow { base: Some(&base), mid: &frames, gone: &mut gone, room };
                            callee.step(p, cx, None, &mut below, &mut call, run)
                        };
                        if let Some(step) = stepped? {
                            return Ok(step);
                        }
                        if gone || call.is_some() {
                            // It called in turn, or the frames below are the
                            // machine's: it is the top frame that ran.
                            frames.push(callee);
                            break;
                        }
                        let stepped = match frames.split_last_mut() {
                            None => {
                                let mut below = NatBelow { base: None, mid: &[], gone: &mut gone, room };
                                base.step(p, cx, Some(&mut callee), &mut below, &mut call, run)
                            }
                            Some((top, mid)) => {
                                let mut below = NatBelow { base: Some(&base), mid, gone: &mut gone, room };
                                top.step(p, cx, Some(&mut callee), &mut below, &mut call, run)
                            }
                        };
                        if let Some(step) = stepped? {
                            return Ok(step);
                        }
                        if !gone {
                            if let Some(next) = call.take() {
                                // A loop of calls: the next callee is held
                                // where the finished one was.
                                callee.replace_done(next);
                                continue;
                            }
                        }
                        // The caller is the top frame that ran; its finished
                        // callee is dropped.
                        break;
                    }
                    ran = true;
                }
            }

            /// Before DM `dm` (no parameters, no locals) hands over: the
            /// frames below made the machine's.
            #[allow(unused)]
            #[cold]
            #[inline(never)]
            pub(crate) fn nat_hand_over(
                p: &Program,
                cx: &mut Cx<'_, '_, Program>,
                stack: &mut NatBelow<'_>,
                dm: DmIx,
            ) -> Result<(), RunError> {
                if !stack.is_empty() {
                    let own_call = cx.build_of(machine::DmProgram::dm_name(p, dm), &[]);
                    nat_materialize(p, cx, stack, own_call, dm)?;
                }
                Ok(())
            }

            /// Makes the native frames below the running one (called as
            /// `top`, DM `top_dm`) machine frames, bottom first.
            #[allow(clippy::all)]
            pub(crate) fn nat_materialize(
                p: &Program,
                cx: &mut Cx<'_, '_, Program>,
                stack: &mut NatBelow<'_>,
                top: Term,
                top_dm: DmIx,
            ) -> Result<(), RunError> {
                if *stack.gone {
                    return Ok(());
                }
                *stack.gone = true;
                let mut frames = stack.base.into_iter().chain(stack.mid.iter()).peekable();
                while let Some(f) = frames.next() {
                    let (callee, callee_dm) = match frames.peek() {
                        Some(next) => (next.call_term(p, cx), next.dm()),
                        None => (top, top_dm),
                    };
                    f.wait(p, cx, callee, callee_dm)?;
                }
                Ok(())
            }
        }
    }
}
