//! Native code (phase 4 of `docs/design/typed-mir.md`): a DM whose
//! situations all run as code and whose MIR registers are all native by
//! [`crate::mir::ty`] runs, when it is entered, on Rust values: each
//! register a Rust local of its type (`i64`, `f64`, `Atom`, `List<T>`,
//! through [`sitlog_runtime::native::Native`]), each situation a variant
//! of the DM's `enum Nat` whose fields are its id's variables
//! (`S2 { r5: Atom, r6: List<Atom> }` for `try([P|Ps])`), a computed next
//! situation selected by a Rust `match`/`if let` on the value, in source
//! order, as the machine selects (D-21), and `==`/`\==` and integer
//! comparisons done in Rust.
//!
//! The boundaries, and why the run is the term path's, step for step:
//! - *entry*: `run_native` is tried when the DM's initial situation runs
//!   (its id an atom) and no history is kept or observed; each parameter
//!   is converted once with a checked conversion (`Native::from_term`). A
//!   value that does not fit (a term of another shape, unbound, a partial
//!   list) leaves the whole visit to the term code, nothing done.
//! - *values*: native values are ground and evaluate to themselves in L
//!   (atoms, numbers and lists of them are inert, D-28/D-36), so a
//!   condition `X == Y` is Rust's `==` on them, and a value matched
//!   against an id pattern binds exactly what unification would.
//! - *hand-over*: a next value no situation takes natively is built as a
//!   term and given to the machine ([`Cx::goto`]), which selects (or
//!   reports the error) itself; so is the id of the situation reached when
//!   the machine wants control (garbage to collect, a stop asked), checked
//!   after each visit (so each native run makes progress).
//! - *finals*: the final situation's id is built as a term, the machine
//!   entered in it, its (empty) out_arg and history entry taken as the term
//!   code takes them; the caller's exit arcs read that id.
//! - *effects*: an action other than an ignored `empty` is performed with
//!   the machine entered in the situation (its errors located there);
//!   transitions are counted and handed to the machine before it runs.
//!
//! - *ground terms*: a register typed `term` is held as a
//!   [`Ground`](sitlog_runtime::native::Ground) handle: every value a
//!   native run holds was converted at entry (a parameter: checked ground
//!   and inert, so evaluating it, as the term path does in a condition or a
//!   next situation, gives it back) or taken apart from one; the handles stay
//!   valid because the machine collects garbage only after native code has
//!   handed over. `==` on them is [`Store::identical`], a pattern is matched
//!   by reading the store; such a situation does not count as on native
//!   values in `--explain-types`.
//!
//! - *frames and calls* ([`frame`], [`call`]): each native DM has a
//!   `Frame` (parameters, locals, its `Nat`); the program's `nat_drive`
//!   runs them on an explicit stack: a recursive situation whose DM is
//!   native pushes the callee's frame (no Rust recursion, no term), the
//!   callee's final variant resumes the caller, whose exit arcs match it
//!   natively; every other call, and every step that needs the machine's
//!   state, first makes the native frames machine frames (`nat_hand_over`).
//! - *the pipe* ([`pipe`]): read into a variable in_arg's register with a
//!   checked conversion, written back where an out_arg sets it.
//!
//! What is not (yet) native keeps the DM on its term code: a register
//! read before it is set (a fresh variable), a fixed-shape compound type,
//! an in_arg that is a pattern, `prog`, perceptual situations other than
//! the neutral `empty` arc, actions other than atoms (and, in exit arcs,
//! `inc`/`get` of a local and values), expressions other than registers,
//! constants and lists of them.
//!
//! [`Cx::goto`]: sitlog_runtime::machine::Cx::goto
//! [`Store::identical`]: sitlog_runtime::Store::identical

use super::Gen;

mod call;
mod frame;
mod pipe;
use crate::ir::IrDm;
use crate::mir::ty::{DmTypes, SitTypes};
use crate::mir::{Action, Build, Cond, Ev, Init, KindPlan, Next, Reg, SitPlan, ID};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::machine::Kind;
use sitlog_runtime::native::Ty;
use sitlog_runtime::{Term, Value};
use sitlog_syntax::{atoms, Atom};
use std::collections::HashMap;

/// Why a DM is not native (shown in the generated docs and
/// `--explain-types`).
type N<T> = Result<T, String>;

/// Per register of a visit, the Rust local holding its value and its type.
type Regs = HashMap<Reg, (Ident, Ty)>;

/// A native value in generated code: an expression of an owned Rust value
/// and its type.
#[derive(Clone)]
struct V {
    e: TokenStream,
    ty: Ty,
}

/// The Rust type of a native type.
fn rust_ty(ty: &Ty) -> N<TokenStream> {
    let rt = quote!(::sitlog_runtime);
    Ok(match ty {
        Ty::Int => quote!(i64),
        Ty::Float => quote!(f64),
        Ty::Sym => quote!(#rt::Atom),
        Ty::Never => quote!(#rt::native::Never),
        Ty::List(e) => {
            let e = rust_ty(e)?;
            quote!(#rt::native::List<#e>)
        }
        // Known ground where native code holds it (see the module doc).
        Ty::Term | Ty::Ground => quote!(#rt::native::Ground),
        Ty::Tagged(..) => return Err(format!("a value of type {ty} is not native yet")),
    })
}

/// `ty` with every `ground` read as `term` (see [`Gen::native_code`]).
fn ground_as_term(ty: &Ty) -> Ty {
    match ty {
        Ty::Ground => Ty::Term,
        Ty::List(e) => Ty::list(ground_as_term(e)),
        Ty::Tagged(name, args) => Ty::Tagged(*name, args.iter().map(ground_as_term).collect()),
        other => other.clone(),
    }
}

/// A DM's types with every `ground` read as `term`, and every register,
/// parameter or id argument that holds no value (`never` since `mir::ty`
/// types `_`) as `term`.
fn ground_as_term_dm(t: &DmTypes) -> DmTypes {
    let mut t = t.clone();
    let fix = |x: &mut crate::mir::ty::Typed| x.ty = ground_as_term(&x.ty);
    // A parameter or id argument nothing reads holds no value (`never`):
    // native code still receives one there, a term.
    let unread = |x: &mut crate::mir::ty::Typed| {
        if x.ty == Ty::Never {
            x.ty = Ty::Term;
        }
    };
    t.params.iter_mut().for_each(fix);
    t.params.iter_mut().for_each(unread);
    for st in t.sits.iter_mut().flatten() {
        st.regs.iter_mut().for_each(fix);
        st.id_args.iter_mut().for_each(fix);
        st.id_args.iter_mut().for_each(unread);
        fix(&mut st.pipe);
    }
    t
}

/// The type of a register that holds no value for `mir::ty` (`_`: a
/// parameter, an id argument or a part of one that the situation does not
/// read): native code still loads it from where it starts, so it has the
/// type of that place (a fresh variable's is `term`).
fn unread_reg_ty(t: &DmTypes, st: &SitTypes, init: Option<&Init>) -> Ty {
    match init {
        Some(Init::HeadArg(i)) => t.params.get(*i).map_or(Ty::Term, |p| p.ty.clone()),
        Some(Init::IdArg(i)) => st.id_args.get(*i).map_or(Ty::Term, |a| a.ty.clone()),
        Some(Init::IdPath(path)) => {
            let Some((first, rest)) = path.split_first() else {
                return Ty::Term;
            };
            let mut ty = st.id_args.get(*first).map_or(Ty::Term, |a| a.ty.clone());
            for &k in rest {
                ty = match (&ty, k) {
                    (Ty::List(e), 0) => (**e).clone(),
                    (Ty::List(_), 1) => ty.clone(),
                    (Ty::Tagged(_, args), k) => args.get(k).cloned().unwrap_or(Ty::Term),
                    _ => Ty::Term,
                };
            }
            ty
        }
        Some(Init::Pipe) => st.pipe.ty.clone(),
        Some(Init::Fresh) | None => Ty::Term,
    }
}

/// Whether Rust's `==` on values of this type is Prolog's `==`.
fn eq_safe(ty: &Ty) -> bool {
    match ty {
        Ty::Int | Ty::Sym | Ty::Never => true,
        Ty::List(e) => eq_safe(e),
        _ => false,
    }
}

fn reg(r: Reg) -> Ident {
    format_ident!("r{}", r)
}

fn variant(ix: usize) -> Ident {
    format_ident!("S{}", ix)
}

/// One step of matching a value against an id pattern.
enum MatchStep {
    /// A test.
    If(TokenStream),
    /// `let NAME = EXPR;`
    Let(Ident, TokenStream),
    /// `if let Some((h, t)) = v.split_first()`, the head cloned.
    Split(TokenStream, Ident, Ident),
    /// The arguments of a ground term `v` that is `name/arity`, each a
    /// ground term: `if let Some(&[x0, ..]) = store.compound_args(..)`.
    Args(TokenStream, TokenStream, Literal, Vec<Ident>),
}

/// The DM's native code, for the module.
pub(super) struct NativeCode {
    /// `enum Nat`, `run_native`.
    pub items: TokenStream,
    /// The hook `run_situation` tries first.
    pub first: TokenStream,
    /// How many situations hold no ground handle (no register `term`, or
    /// `ground`, which native code holds as a handle too): the ones on
    /// native values.
    pub on_native_values: usize,
}

struct Dm<'a> {
    dm: &'a IrDm,
    plans: Vec<&'a SitPlan>,
    types: Vec<SitTypes>,
    /// The parameters' types.
    params: Vec<Ty>,
    /// The DM's index, its locals' names and types (frame fields `l0..`).
    ix: usize,
    locals: Vec<(Atom, Ty)>,
    /// Code run before native code hands over to the machine: the native
    /// stack below materialized, the locals written back (`frame`).
    hand: TokenStream,
    /// Calls made as if no callee were native (deciding native-ness).
    shallow: bool,
    /// The arc whose code is being generated (for errors located there).
    arc: std::cell::Cell<usize>,
    /// The arc's out_arg, set where its next situation is handed over.
    out: std::cell::RefCell<TokenStream>,
}

impl Gen<'_> {
    /// The native code of DM `dm_ix`, or why it has none.
    pub(super) fn native_code(&self, dm: &IrDm, dm_ix: usize, t: &DmTypes) -> N<NativeCode> {
        self.native_code_with(dm, dm_ix, t, false)
    }

    /// [`Gen::native_code`]; `shallow`: every DM call handed to the machine
    /// (whether a DM is native does not depend on its callees).
    fn native_code_with(
        &self,
        dm: &IrDm,
        dm_ix: usize,
        t: &DmTypes,
        shallow: bool,
    ) -> N<NativeCode> {
        let rt = quote!(::sitlog_runtime);
        let d = self.nat_dm(dm, dm_ix, t, shallow)?;
        // Parameters, converted at entry.
        let mut loads = Vec::new();
        for (i, p) in d.params.iter().enumerate() {
            let ty = rust_ty(p)?;
            let name = format_ident!("p{}", i);
            let ix = Literal::usize_unsuffixed(i);
            loads.push(quote! {
                let ::std::option::Option::Some(#name) = cx
                    .param(#ix)
                    .and_then(|t| <#ty as #rt::native::Native>::from_term(cx.store_ref(), t))
                else {
                    return ::std::result::Result::Ok(::std::option::Option::None);
                };
            });
        }
        // Locals, read from the machine's frame at entry.
        for (i, (name, ty)) in d.locals.iter().enumerate() {
            let ty = rust_ty(ty)?;
            let l = format_ident!("l{}", i);
            let a = self.atom_native(*name)?;
            loads.push(quote! {
                let ::std::option::Option::Some(#l) = cx
                    .local(#a)
                    .and_then(|t| <#ty as #rt::native::Native>::from_term(cx.store_ref(), t))
                else {
                    return ::std::result::Result::Ok(::std::option::Option::None);
                };
            });
        }
        let mut variants = Vec::new();
        let mut arms = Vec::new();
        let mut id_arms = Vec::new();
        let mut exit_arms = Vec::new();
        let mut wait_arms = Vec::new();
        for ix in 0..d.plans.len() {
            let v = variant(ix);
            let fields = self.nat_fields(&d, ix)?;
            let decls = fields
                .iter()
                .map(|(r, ty)| {
                    let (r, ty) = (reg(*r), rust_ty(ty)?);
                    Ok(quote!(#r: #ty))
                })
                .collect::<N<Vec<_>>>()?;
            let names: Vec<Ident> = fields.iter().map(|(r, _)| reg(*r)).collect();
            let doc = format!(" `{}`", self.store.writeq(self.nat_id_of(&d, ix)));
            variants.push(quote!(#[doc = #doc] #v { #(#decls),* },));
            let (id_stmts, id) = self.nat_id_term(&d, ix, quote!(store))?;
            id_arms.push(quote!(Nat::#v { #(#names),* } => { #(#id_stmts)* #id }));
            let body = self.native_visit(&d, ix, &fields)?;
            arms.push(quote!(Nat::#v { #(#names),* } => 'visit: { #body }));
            // A recursive situation waiting for its callee: its own variant.
            if let Some(w) = self.nat_wait_variant(&d, ix)? {
                variants.push(w.variant);
                id_arms.push(w.id_arm);
                exit_arms.push(w.exit_arm);
                wait_arms.push(w.wait_arm);
            }
        }
        let frame = self.nat_frame_items(&d, &wait_arms)?;
        let field_names = frame.names.clone();
        let ixl = Literal::usize_unsuffixed(dm_ix);
        let variant_d = format_ident!("D{}", dm_ix);
        let hand = &d.hand;
        // The machine wants control (garbage, a stop asked): the situation
        // reached is handed over as its id.
        let gc = quote! {
            if cx.gc_due() {
                #hand
                cx.count_transitions(count);
                let id = at.id_term(p, cx.store());
                return ::std::result::Result::Ok(::std::option::Option::Some(#rt::machine::Step::Goto(id)));
            }
        };
        let frame_items = frame.items;
        let pipe_check = self.nat_pipe_entry(&d)?;
        let doc = format!(
            " Runs DM `{}` natively from its initial situation (see \
             `sitlog_compiler::codegen::native`); `None`, nothing done, when a \
             history is kept or observed or a parameter or local does not convert.",
            dm.name.as_str()
        );
        let items = quote! {
            /// The DM's situations as native values: the fields are the id's variables.
            #[allow(dead_code, non_camel_case_types, clippy::all)]
            #[derive(Clone, Debug)]
            pub enum Nat { #(#variants)* }

            #[allow(unused_variables, unreachable_patterns, clippy::all)]
            impl Nat {
                /// The situation's id as a term.
                pub(crate) fn id_term(&self, p: &super::Program, store: &mut #rt::Store) -> #rt::Term {
                    let a = &p.atoms;
                    match self { #(#id_arms)* }
                }
            }

            #frame_items

            /// Runs the frame on top of the native stack until it calls a DM
            /// (`call` set), ends in a final situation below the base
            /// (`Ok(None)`), or hands over to the machine (`Ok(Some(step))`).
            #[allow(unused_variables, unused_mut, unused_parens, unreachable_code, unused_labels, irrefutable_let_patterns, unreachable_patterns, unused_braces, break_with_label_and_loop, clippy::all)]
            pub(crate) fn nat_step(
                p: &super::Program,
                cx: &mut #rt::machine::Cx<'_, '_, super::Program>,
                frame: &mut Frame,
                ret: ::std::option::Option<super::NatFrame>,
                stack: &mut ::std::vec::Vec<super::NatFrame>,
                call: &mut ::std::option::Option<super::NatFrame>,
                run: &#rt::machine::TypedRun,
            ) -> ::std::result::Result<::std::option::Option<#rt::machine::Step>, #rt::machine::RunError> {
                let a = &p.atoms;
                let Frame { #(#field_names,)* at: slot } = frame;
                // Transitions done, not yet given to the machine.
                let mut count: u64 = 0;
                // A final reached below the base, or a call made.
                let mut done = false;
                let mut at = ::std::mem::replace(slot, Nat::S0 {});
                if let ::std::option::Option::Some(ret) = ret {
                    at = match at {
                        #(#exit_arms)*
                        _ => return ::std::result::Result::Err(cx.error("native code resumed a situation that waits for no DM", ::std::option::Option::None)),
                    };
                    if done {
                        cx.count_transitions(count);
                        *slot = at;
                        return ::std::result::Result::Ok(::std::option::Option::None);
                    }
                    #gc
                }
                loop {
                    at = match at {
                        #(#arms)*
                        _ => return ::std::result::Result::Err(cx.error("native code visited a waiting situation", ::std::option::Option::None)),
                    };
                    if done {
                        cx.count_transitions(count);
                        *slot = at;
                        return ::std::result::Result::Ok(::std::option::Option::None);
                    }
                    #gc
                }
            }

            #[doc = #doc]
            #[allow(unused_variables, unused_mut, unused_parens, unreachable_code, clippy::all)]
            pub fn run_native(
                p: &super::Program,
                cx: &mut #rt::machine::Cx<'_, '_, super::Program>,
            ) -> ::std::result::Result<::std::option::Option<#rt::machine::Step>, #rt::machine::RunError> {
                let run = cx.typed_run();
                if run.records {
                    return ::std::result::Result::Ok(::std::option::Option::None);
                }
                cx.materialize_frames();
                let a = &p.atoms;
                #(#loads)*
                #pipe_check
                let frame = Frame { #(#field_names,)* at: Nat::S0 {} };
                let _ = #ixl;
                super::nat_drive(p, cx, super::NatFrame::#variant_d(frame), &run)
                    .map(::std::option::Option::Some)
            }
        };
        let first = quote! {
            // The DM runs natively from its initial situation when its
            // parameters convert and no history is kept or observed.
            if sit == 0 && cx.selected().is_none() {
                if let ::std::option::Option::Some(step) = run_native(p, cx)? {
                    return ::std::result::Result::Ok(step);
                }
            }
        };
        let on_native_values = d
            .types
            .iter()
            .filter(|st| st.regs.iter().all(|r| r.ty.is_native()))
            .count();
        Ok(NativeCode {
            items,
            first,
            on_native_values,
        })
    }

    /// The plans and types native code of DM `dm_ix` works from, or why
    /// it has none.
    fn nat_dm<'a>(&'a self, dm: &'a IrDm, dm_ix: usize, t: &DmTypes, shallow: bool) -> N<Dm<'a>> {
        // `ground` (a boundary's value after a checked conversion, or the
        // join of different shapes) is held as a ground handle here, as
        // `term` is: native code has no boundary conversion yet.
        let t = &ground_as_term_dm(t);
        let mut plans = Vec::new();
        let mut types = Vec::new();
        for i in 0..dm.situations.len() {
            let plan = self
                .mir
                .plan(dm_ix as u32, i as u32)
                .ok_or("a situation is instantiated from its template")?;
            let st = t.sits[i].as_ref().ok_or("a situation has no types")?;
            let mut st = st.clone();
            for r in 0..st.regs.len() {
                if st.unbound.get(r).copied().unwrap_or(false) {
                    let init = plan
                        .inits
                        .iter()
                        .find(|(x, _)| *x as usize == r)
                        .map(|(_, i)| i);
                    st.regs[r].ty = unread_reg_ty(t, &st, init);
                }
            }
            if let Some(r) = st.regs.iter().position(|r| rust_ty(&r.ty).is_err()) {
                let why = st.regs[r].why.as_deref().unwrap_or("no reason given");
                return Err(format!(
                    "situation {} has register r{r} typed {}: {why}",
                    i + 1,
                    st.regs[r].ty
                ));
            }
            plans.push(plan);
            types.push(st);
        }
        if plans.first().is_none_or(|p| p.id.1 != 0) {
            return Err("its initial situation's id is not an atom".into());
        }
        if let Some(p) = t.params.iter().position(|p| rust_ty(&p.ty).is_err()) {
            let why = t.params[p].why.as_deref().unwrap_or("no reason given");
            return Err(format!(
                "parameter {} is typed {}: {why}",
                p + 1,
                t.params[p].ty
            ));
        }
        let locals = self.nat_locals(dm, t)?;
        let mut d = Dm {
            dm,
            plans,
            types,
            params: t.params.iter().map(|p| p.ty.clone()).collect(),
            ix: dm_ix,
            locals,
            hand: quote!(),
            shallow,
            arc: std::cell::Cell::new(0),
            out: std::cell::RefCell::new(quote!()),
        };
        d.hand = self.nat_hand(&d)?;
        Ok(d)
    }

    fn nat_id_of(&self, d: &Dm, ix: usize) -> Term {
        self.store.args(d.dm.situations[ix].template)[ID]
    }

    /// The variant's fields: the registers its id's variables start in.
    fn nat_fields(&self, d: &Dm, ix: usize) -> N<Vec<(Reg, Ty)>> {
        Ok(d.plans[ix]
            .inits
            .iter()
            .filter(|(_, i)| matches!(i, Init::IdArg(_) | Init::IdPath(_)))
            .map(|&(r, _)| (r, d.types[ix].regs[r as usize].ty.clone()))
            .collect())
    }

    /// The register a variable of situation `ix`'s id at `path` starts in.
    fn nat_id_reg(d: &Dm, ix: usize, path: &[usize]) -> Option<Reg> {
        d.plans[ix].inits.iter().find_map(|(r, i)| match i {
            Init::IdArg(a) if path == [*a] => Some(*r),
            Init::IdPath(p) if **p == *path => Some(*r),
            _ => None,
        })
    }

    fn atom_native(&self, a: Atom) -> N<TokenStream> {
        if a == atoms::NIL {
            return Ok(quote!(::sitlog_runtime::atoms::NIL));
        }
        if a == atoms::EMPTY {
            return Ok(quote!(::sitlog_runtime::atoms::EMPTY));
        }
        match self.atom_ix.get(&a) {
            Some(&i) => {
                let id = &self.atoms[i].1;
                Ok(quote!(a.#id))
            }
            None => Err(format!(
                "atom `{}` is not a constant of the program",
                a.as_str()
            )),
        }
    }

    /// The id of situation `ix` as a term, from its fields (`store`: the
    /// store expression): statements and the value.
    fn nat_id_term(
        &self,
        d: &Dm,
        ix: usize,
        store: TokenStream,
    ) -> N<(Vec<TokenStream>, TokenStream)> {
        let mut stmts = Vec::new();
        let mut vars = HashMap::new();
        let mut n = 0;
        let id = self.nat_id_of(d, ix);
        let v = self.nat_term_of(
            d,
            ix,
            id,
            &mut Vec::new(),
            &mut vars,
            &mut stmts,
            &mut n,
            &store,
        )?;
        Ok((stmts, v))
    }

    #[allow(clippy::too_many_arguments)]
    fn nat_term_of(
        &self,
        d: &Dm,
        ix: usize,
        t: Term,
        path: &mut Vec<usize>,
        vars: &mut HashMap<u32, Ident>,
        stmts: &mut Vec<TokenStream>,
        n: &mut usize,
        store: &TokenStream,
    ) -> N<TokenStream> {
        let rt = quote!(::sitlog_runtime);
        Ok(match self.store.value(t) {
            Value::Var(v) => {
                if let Some(r) = vars.get(&v.index()) {
                    let r = r.clone();
                    quote!(#r)
                } else {
                    let r =
                        Self::nat_id_reg(d, ix, path).ok_or("an id variable has no register")?;
                    let x = format_ident!("t{}", *n);
                    *n += 1;
                    let rr = reg(r);
                    stmts.push(quote! {
                        let #x = {
                            use #rt::native::Native as _;
                            (&#rr).to_term(#store)
                        };
                    });
                    vars.insert(v.index(), x.clone());
                    quote!(#x)
                }
            }
            Value::Atom(a) => {
                let a = self.atom_native(a)?;
                quote!(#rt::Term::atom(#a))
            }
            Value::Int(i) => {
                let i = Literal::i64_suffixed(i);
                quote!(#rt::Term::int(#i))
            }
            Value::Compound(name, args) => {
                let args = args.to_vec();
                let mut parts = Vec::new();
                for (i, &a) in args.iter().enumerate() {
                    path.push(i);
                    parts.push(self.nat_term_of(d, ix, a, path, vars, stmts, n, store)?);
                    path.pop();
                }
                let f = if name == atoms::DOT {
                    quote!(#rt::atoms::DOT)
                } else {
                    self.atom_native(name)?
                };
                let x = format_ident!("t{}", *n);
                *n += 1;
                stmts.push(quote!(let #x = #rt::native::compound(#store, #f, &[#(#parts),*]);));
                quote!(#x)
            }
            _ => return Err("an id holds a constant that is not native".into()),
        })
    }

    /// The code of one visit of situation `ix` (its fields bound): returns
    /// from `run_native` or gives the next `Nat`.
    fn native_visit(&self, d: &Dm, ix: usize, fields: &[(Reg, Ty)]) -> N<TokenStream> {
        let rt = quote!(::sitlog_runtime);
        let plan = d.plans[ix];
        let st = &d.types[ix];
        if plan.prog.is_some() {
            return Err(format!("situation {} has prog", ix + 1));
        }
        if matches!(plan.in_arg, Some((_, true, _))) {
            return Err(format!("situation {}: its in_arg is a pattern", ix + 1));
        }
        // Where each register's value lives: a field, a parameter, a local.
        let mut regs: Regs = fields
            .iter()
            .map(|(r, ty)| (*r, (reg(*r), ty.clone())))
            .collect();
        let mut stmts = Vec::new();
        for (r, init) in &plan.inits {
            match init {
                Init::HeadArg(i) => {
                    let ty = st.regs[*r as usize].ty.clone();
                    let p = format_ident!("p{}", i);
                    let pv = V {
                        e: quote!(#p.clone()),
                        ty: d
                            .params
                            .get(*i)
                            .cloned()
                            .ok_or("a head argument out of range")?,
                    };
                    if pv.ty == ty {
                        regs.insert(*r, (p, ty));
                    } else {
                        let e = coerce(&pv, &ty)?;
                        let rr = reg(*r);
                        stmts.push(quote!(let #rr = #e;));
                        regs.insert(*r, (rr, ty));
                    }
                }
                Init::Pipe => {
                    let ty = st.regs[*r as usize].ty.clone();
                    stmts.push(self.nat_pipe_in(d, ix, *r, &ty)?);
                    regs.insert(*r, (reg(*r), ty));
                }
                Init::Fresh | Init::IdArg(_) | Init::IdPath(_) => {}
            }
        }
        // A variable in_arg: its register holds the pipe's value.
        if let Some((Build::Reg(src), false, r)) = &plan.in_arg {
            if let Some(at) = regs.get(src).cloned() {
                regs.insert(*r, at);
            }
        }
        let cur = Literal::u32_unsuffixed(ix as u32);
        let kind = d.dm.situations[ix].kind;
        match (&plan.kind, kind) {
            (KindPlan::Final { diag_mod: None }, Kind::Final) => {
                let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
                let empty = quote!(#rt::Term::atom(#rt::atoms::EMPTY));
                let v = variant(ix);
                let names = fields.iter().map(|(r, _)| reg(*r));
                // out_arg: the pipe's new value (never unbound here).
                let (out_set, out_final) = match &plan.out_arg {
                    Some((b, _)) => {
                        let v = self.nat_value(b, &regs)?.e;
                        (
                            quote! {
                                let out = #rt::native::Native::to_term(&#v, cx.store());
                                cx.set_pipe(out);
                            },
                            quote! {
                                let out = #rt::native::Native::to_term(&#v, cx.store());
                                cx.final_out_arg(::std::option::Option::Some(out))?;
                            },
                        )
                    }
                    None => (
                        quote!(),
                        quote!(cx.final_out_arg(::std::option::Option::None)?;),
                    ),
                };
                Ok(quote! {
                    #(#stmts)*
                    // Below the base: the caller's exit arcs read the variant.
                    if !stack.is_empty() {
                        #out_set
                        count += 1;
                        done = true;
                        break 'visit Nat::#v { #(#names),* };
                    }
                    cx.count_transitions(count);
                    #(#id_stmts)*
                    cx.enter_with_id(#cur, #id);
                    #out_final
                    cx.record(#empty, #empty, ::std::option::Option::None);
                    return ::std::result::Result::Ok(::std::option::Option::Some(#rt::machine::Step::Final));
                })
            }
            (KindPlan::Perceptual(arcs), Kind::Perceptual)
                if arcs.always_first && arcs.arcs.len() == 1 =>
            {
                let arc = &arcs.arcs[0];
                if arc.diag_mod.is_some() {
                    return Err(format!("situation {} has diag_mod", ix + 1));
                }
                for (k, from) in arc.import_from.iter().enumerate() {
                    // An imported copy of a ground value is the value.
                    if let Some(at) = regs.get(from).cloned() {
                        regs.insert(arc.import_at + k as Reg, at);
                    }
                }
                let action = match &arc.action {
                    Action::One(Ev::Built(Build::Const(t))) => self.store.atom_of(*t),
                    _ => None,
                }
                .ok_or(format!("situation {}: its action is not an atom", ix + 1))?;
                let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
                let act = self.atom_native(action)?;
                let hand = &d.hand;
                let perform = quote! {
                    #hand
                    cx.count_transitions(count);
                    count = 0;
                    #(#id_stmts)*
                    cx.enter_with_id(#cur, #id);
                    cx.perform(#rt::Term::atom(#act), ::std::option::Option::Some(0))?;
                };
                stmts.push(if action == atoms::EMPTY {
                    quote!(if !run.quiet_empty { #perform })
                } else {
                    perform
                });
                stmts.push(quote!(count += 1;));
                let name = self.atom_native(plan.id.0)?;
                d.arc.set(0);
                let next =
                    self.nat_next_out(d, ix, &arc.next, arc.out_arg.as_ref(), &regs, &name)?;
                Ok(quote! { #(#stmts)* #next })
            }
            (KindPlan::Recursive { .. }, Kind::Recursive) => {
                let call = self.nat_recursive(d, ix, &regs)?;
                Ok(quote! { #(#stmts)* #call })
            }
            _ => Err(format!(
                "situation {} is not a final, a neutral `empty` or a recursive situation",
                ix + 1
            )),
        }
    }

    /// The value of a register or constant.
    fn nat_value(&self, b: &Build, regs: &Regs) -> N<V> {
        let rt = quote!(::sitlog_runtime);
        match b {
            Build::Reg(r) => {
                let (x, ty) = regs.get(r).ok_or(format!("register r{r} is read unset"))?;
                Ok(V {
                    e: quote!(#x.clone()),
                    ty: ty.clone(),
                })
            }
            Build::Const(t) => match self.store.value(*t) {
                Value::Atom(a) if a == atoms::NIL => Ok(V {
                    e: quote!(#rt::native::List::<#rt::native::Never>::nil()),
                    ty: Ty::list(Ty::Never),
                }),
                Value::Atom(a) => Ok(V {
                    e: self.atom_native(a)?,
                    ty: Ty::Sym,
                }),
                Value::Int(i) => {
                    let i = Literal::i64_suffixed(i);
                    Ok(V {
                        e: quote!(#i),
                        ty: Ty::Int,
                    })
                }
                // A constant list of atoms or of ints, built natively.
                Value::Compound(..) => self.nat_const_list(*t),
                _ => Err(format!(
                    "constant `{}` is not native yet",
                    self.store.writeq(*t)
                )),
            },
            Build::Compound(name, args) if *name == atoms::DOT && args.len() == 2 => {
                let h = self.nat_value(&args[0], regs)?;
                let t = self.nat_value(&args[1], regs)?;
                cons(h, t)
            }
            Build::Compound(..) => Err("a compound value is not native yet".into()),
        }
    }

    /// A ground list of atoms or of ints (`[x, y]`, `[1, 2]`) as a native list.
    /// Built once per thread and shared (`Rc`): no allocation per use.
    fn nat_const_list(&self, t: Term) -> N<V> {
        let v = self.nat_const_list_in(t)?;
        let (e, rty) = (v.e, rust_ty(&v.ty)?);
        Ok(V {
            e: quote!({
                ::std::thread_local! { static K: #rty = #e; }
                K.with(|k| k.clone())
            }),
            ty: v.ty,
        })
    }

    /// The list's value, its atoms interned by name (no `Program` in scope).
    fn nat_const_list_in(&self, t: Term) -> N<V> {
        let rt = quote!(::sitlog_runtime);
        let not = || format!("constant `{}` is not native yet", self.store.writeq(t));
        let items = self.store.list_to_vec(t).ok_or_else(not)?;
        let mut vals = Vec::new();
        for &x in &items {
            match self.store.value(x) {
                Value::Atom(a) if a != atoms::NIL => {
                    let lit = Literal::string(a.as_str());
                    vals.push(V {
                        e: quote!(#rt::Atom::intern(#lit)),
                        ty: Ty::Sym,
                    })
                }
                Value::Atom(_) => vals.push(self.nat_value(&Build::Const(x), &Regs::new())?),
                Value::Int(i) => {
                    let i = Literal::i64_suffixed(i);
                    vals.push(V {
                        e: quote!(#i),
                        ty: Ty::Int,
                    })
                }
                Value::Compound(..) => vals.push(self.nat_const_list_in(x)?),
                _ => return Err(not()),
            }
        }
        // The elements' type: the first that is not `[]`'s.
        let ty = vals
            .iter()
            .map(|v| v.ty.clone())
            .find(|t| *t != Ty::list(Ty::Never))
            .or_else(|| vals.first().map(|v| v.ty.clone()))
            .ok_or_else(not)?;
        let es = vals
            .iter()
            .map(|v| coerce(v, &ty).map_err(|_| not()))
            .collect::<N<Vec<_>>>()?;
        let rty = rust_ty(&ty)?;
        Ok(V {
            e: quote!(#rt::native::List::<#rty>::from_vec(::std::vec![#(#es),*])),
            ty: Ty::list(ty),
        })
    }

    fn nat_ev_value(&self, e: &Ev, regs: &Regs) -> N<V> {
        match e {
            Ev::Value(r) => self.nat_value(&Build::Reg(*r), regs),
            Ev::Built(b) => self.nat_value(b, regs),
            Ev::Compound(name, args) if *name == atoms::DOT && args.len() == 2 => {
                let h = self.nat_ev_value(&args[0], regs)?;
                let t = self.nat_ev_value(&args[1], regs)?;
                cons(h, t)
            }
            _ => Err("an expression is not native yet".into()),
        }
    }

    fn nat_cond(&self, d: &Dm, cur: usize, c: &Cond, regs: &Regs) -> N<TokenStream> {
        match c {
            Cond::Arith(op, l, r) => {
                let (l, r) = (self.nat_ev_value(l, regs)?, self.nat_ev_value(r, regs)?);
                self.nat_arith(d, cur, *op, l, r)
            }
            Cond::Other(Build::Compound(op, args))
                if args.len() == 2 && matches!(op.as_str(), "==" | "\\==") =>
            {
                let (l, r) = (
                    self.nat_value(&args[0], regs)?,
                    self.nat_value(&args[1], regs)?,
                );
                let same = identical(&l, &r)
                    .ok_or_else(|| format!("`{}` on {} and {}", op.as_str(), l.ty, r.ty))?;
                Ok(if op.as_str() == "==" {
                    same
                } else {
                    quote!((!#same))
                })
            }
            _ => Err("a condition is not `==`, `\\==` or an int comparison".into()),
        }
    }

    /// The next `Nat` of situation `cur` (named `cur_name`), or a return
    /// handing the value to the machine.
    fn nat_next(
        &self,
        d: &Dm,
        cur: usize,
        n: &Next,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<TokenStream> {
        let rt = quote!(::sitlog_runtime);
        let curl = Literal::u32_unsuffixed(cur as u32);
        match n {
            Next::Static(t, Some(ix)) if self.store.atom_of(*t).is_some() => {
                let v = variant(*ix as usize);
                if d.plans[*ix as usize].id.1 != 0 {
                    return Err("a constant next situation selects a compound id".into());
                }
                Ok(quote!(Nat::#v {}))
            }
            Next::Static(t, None) if self.store.atom_of(*t).is_some() => {
                // No situation has this name: the machine says so.
                let a = self.atom_native(self.store.atom_of(*t).unwrap_or(atoms::NIL))?;
                let hand = &d.hand;
                let out = d.out.borrow().clone();
                Ok(quote! {{
                    #hand
                    cx.count_transitions(count);
                    cx.enter(#curl, #cur_name);
                    #out
                    return cx.goto(#rt::Term::atom(#a), ::std::option::Option::Some(0)).map(::std::option::Option::Some);
                }})
            }
            Next::Static(t, _) | Next::Eval(Ev::Built(Build::Const(t)))
                if self.store.functor(*t).is_some_and(|(_, n)| n > 0) =>
            {
                let (name, _) = self.store.functor(*t).ok_or("no functor")?;
                let vals = self
                    .store
                    .args(*t)
                    .to_vec()
                    .into_iter()
                    .map(|a| self.nat_value(&Build::Const(a), regs))
                    .collect::<N<Vec<_>>>()?;
                self.nat_select(d, cur, name, vals, cur_name)
            }
            Next::If(c, a, b) => {
                let c = self.nat_cond(d, cur, c, regs)?;
                let a = self.nat_next(d, cur, a, regs, cur_name)?;
                let b = self.nat_next(d, cur, b, regs, cur_name)?;
                Ok(quote!(if #c { #a } else { #b }))
            }
            Next::Eval(Ev::Compound(name, args)) => {
                let vals = args
                    .iter()
                    .map(|a| self.nat_ev_value(a, regs))
                    .collect::<N<Vec<_>>>()?;
                self.nat_select(d, cur, *name, vals, cur_name)
            }
            Next::Eval(Ev::Built(Build::Compound(name, args))) => {
                let vals = args
                    .iter()
                    .map(|a| self.nat_value(a, regs))
                    .collect::<N<Vec<_>>>()?;
                self.nat_select(d, cur, *name, vals, cur_name)
            }
            _ => Err(format!(
                "situation {}: its next situation is not native yet",
                cur + 1
            )),
        }
    }

    /// Selects the situation `name(args)` takes, in source order (D-21),
    /// else hands the value to the machine.
    fn nat_select(
        &self,
        d: &Dm,
        cur: usize,
        name: Atom,
        args: Vec<V>,
        cur_name: &TokenStream,
    ) -> N<TokenStream> {
        let rt = quote!(::sitlog_runtime);
        let curl = Literal::u32_unsuffixed(cur as u32);
        let arg_names: Vec<Ident> = (0..args.len()).map(|i| format_ident!("v{}", i)).collect();
        let lets: Vec<TokenStream> = args
            .iter()
            .zip(&arg_names)
            .map(|(v, n)| {
                let e = &v.e;
                quote!(let #n = #e;)
            })
            .collect();
        let mut candidates = Vec::new();
        for j in 0..d.plans.len() {
            if d.plans[j].id != (name, args.len()) {
                continue;
            }
            let id = self.nat_id_of(d, j);
            let id_args = self.store.args(id).to_vec();
            let mut steps = Vec::new();
            let mut vars: HashMap<u32, (Ident, Ty)> = HashMap::new();
            let mut ok = true;
            let mut n = 0;
            for (i, (&pat, v)) in id_args.iter().zip(&args).enumerate() {
                let arg = V {
                    e: {
                        let x = &arg_names[i];
                        quote!(#x)
                    },
                    ty: v.ty.clone(),
                };
                if !self.native_match(
                    d,
                    j,
                    pat,
                    &arg,
                    &mut vec![i],
                    &mut vars,
                    &mut steps,
                    &mut n,
                )? {
                    ok = false;
                    break;
                }
            }
            if !ok {
                continue; // cannot match a value of this type
            }
            let fields = self.nat_fields(d, j)?;
            let mut inits = Vec::new();
            for (r, _) in &fields {
                let x = vars
                    .values()
                    .find(|(x, _)| *x == format_ident!("f{}", r))
                    .map(|(x, _)| x.clone())
                    .ok_or("an id field is not bound by its pattern")?;
                let rr = reg(*r);
                inits.push(quote!(#rr: #x));
            }
            let v = variant(j);
            let mut code = quote!(break 'sel Nat::#v { #(#inits),* };);
            for s in steps.into_iter().rev() {
                code = match s {
                    MatchStep::If(c) => quote!(if #c { #code }),
                    MatchStep::Let(x, e) => quote!({ let #x = #e; #code }),
                    MatchStep::Args(v, f, arity, xs) => quote! {
                        if let ::std::option::Option::Some(&[#(#xs),*]) =
                            cx.store_ref().compound_args(#v.0, #f, #arity)
                        {
                            #(let #xs = ::sitlog_runtime::native::Ground(#xs);)*
                            #code
                        }
                    },
                    MatchStep::Split(l, h, t) => quote! {
                        if let ::std::option::Option::Some((#h, #t)) = #l.split_first() {
                            let #h = #h.clone();
                            #code
                        }
                    },
                };
            }
            candidates.push(code);
        }
        let f = self.atom_native(name)?;
        let hand = &d.hand;
        let out = d.out.borrow().clone();
        let arg_terms: Vec<Ident> = (0..args.len()).map(|i| format_ident!("w{}", i)).collect();
        Ok(quote! {
            'sel: {
                #(#lets)*
                #(#candidates)*
                // No situation takes it here: the machine selects (or says
                // that none does).
                #hand
                cx.count_transitions(count);
                cx.enter(#curl, #cur_name);
                #(let #arg_terms = #rt::native::Native::to_term(&#arg_names, cx.store());)*
                let value = #rt::native::compound(cx.store(), #f, &[#(#arg_terms),*]);
                #out
                return cx.goto(value, ::std::option::Option::Some(0)).map(::std::option::Option::Some);
            }
        })
    }

    /// Matching `v` against the id pattern `pat` of situation `j` at `path`:
    /// steps pushed; `false` when no value of `v`'s type can match.
    #[allow(clippy::too_many_arguments)]
    fn native_match(
        &self,
        d: &Dm,
        j: usize,
        pat: Term,
        v: &V,
        path: &mut Vec<usize>,
        vars: &mut HashMap<u32, (Ident, Ty)>,
        steps: &mut Vec<MatchStep>,
        n: &mut usize,
    ) -> N<bool> {
        let e = &v.e;
        match self.store.value(pat) {
            Value::Var(var) => {
                if let Some((x, ty)) = vars.get(&var.index()) {
                    let prev = V {
                        e: quote!(#x),
                        ty: ty.clone(),
                    };
                    let same = identical(&prev, v)
                        .ok_or("a repeated id variable on values of another type")?;
                    steps.push(MatchStep::If(same));
                    return Ok(true);
                }
                let r = Self::nat_id_reg(d, j, path).ok_or("an id variable has no register")?;
                let ty = d.types[j].regs[r as usize].ty.clone();
                let x = format_ident!("f{}", r);
                let val = coerce(
                    &V {
                        e: quote!(#e.clone()),
                        ty: v.ty.clone(),
                    },
                    &ty,
                )?;
                steps.push(MatchStep::Let(x.clone(), val));
                vars.insert(var.index(), (x, ty));
                Ok(true)
            }
            // A ground term: read in the store.
            Value::Atom(a) if v.ty == Ty::Term => {
                let a = self.atom_native(a)?;
                steps.push(MatchStep::If(quote!(
                    cx.store_ref().atom_of(#e.0) == ::std::option::Option::Some(#a)
                )));
                Ok(true)
            }
            Value::Int(i) if v.ty == Ty::Term => {
                let i = Literal::i64_suffixed(i);
                steps.push(MatchStep::If(quote!(
                    cx.store_ref().int_of(#e.0) == ::std::option::Option::Some(#i)
                )));
                Ok(true)
            }
            Value::Compound(name, args) if v.ty == Ty::Term => {
                let args = args.to_vec();
                let f = if name == atoms::DOT {
                    quote!(::sitlog_runtime::atoms::DOT)
                } else {
                    self.atom_native(name)?
                };
                let xs: Vec<Ident> = (0..args.len())
                    .map(|k| format_ident!("g{}_{}", *n, k))
                    .collect();
                *n += 1;
                let arity = Literal::usize_unsuffixed(args.len());
                steps.push(MatchStep::Args(quote!(#e), f, arity, xs.clone()));
                for (k, (&a, x)) in args.iter().zip(&xs).enumerate() {
                    let xv = V {
                        e: quote!(#x),
                        ty: Ty::Term,
                    };
                    path.push(k);
                    let ok = self.native_match(d, j, a, &xv, path, vars, steps, n)?;
                    path.pop();
                    if !ok {
                        return Ok(false);
                    }
                }
                Ok(true)
            }
            Value::Atom(a) if a == atoms::NIL => match &v.ty {
                Ty::List(_) => {
                    steps.push(MatchStep::If(quote!(#e.is_empty())));
                    Ok(true)
                }
                Ty::Sym => {
                    steps.push(MatchStep::If(quote!(#e == ::sitlog_runtime::atoms::NIL)));
                    Ok(true)
                }
                _ => Ok(false),
            },
            Value::Atom(a) => match &v.ty {
                Ty::Sym => {
                    let a = self.atom_native(a)?;
                    steps.push(MatchStep::If(quote!(#e == #a)));
                    Ok(true)
                }
                _ => Ok(false),
            },
            Value::Int(i) => match &v.ty {
                Ty::Int => {
                    let i = Literal::i64_suffixed(i);
                    steps.push(MatchStep::If(quote!(#e == #i)));
                    Ok(true)
                }
                Ty::Float => Err("an int pattern on a float".into()),
                _ => Ok(false),
            },
            Value::Compound(name, args) if name == atoms::DOT && args.len() == 2 => {
                let (h, t) = (args[0], args[1]);
                match &v.ty {
                    Ty::List(elem) if **elem == Ty::Never => Ok(false),
                    Ty::List(elem) => {
                        let hx = format_ident!("h{}", *n);
                        let tx = format_ident!("l{}", *n);
                        *n += 1;
                        steps.push(MatchStep::Split(quote!(#e), hx.clone(), tx.clone()));
                        let hv = V {
                            e: quote!(#hx),
                            ty: (**elem).clone(),
                        };
                        let tv = V {
                            e: quote!(#tx),
                            ty: v.ty.clone(),
                        };
                        path.push(0);
                        let ok = self.native_match(d, j, h, &hv, path, vars, steps, n)?;
                        path.pop();
                        if !ok {
                            return Ok(false);
                        }
                        path.push(1);
                        let ok = self.native_match(d, j, t, &tv, path, vars, steps, n)?;
                        path.pop();
                        Ok(ok)
                    }
                    Ty::Sym | Ty::Int => Ok(false),
                    _ => Err("a list pattern on a value that is not native".into()),
                }
            }
            Value::Compound(..) => match &v.ty {
                Ty::Sym | Ty::Int | Ty::List(_) => Ok(false),
                _ => Err("a compound pattern is not native yet".into()),
            },
            _ => Err("an id pattern holds a constant that is not native".into()),
        }
    }
}

/// Prolog's `==` on two native values, when their types allow it in Rust
/// (ground terms compared in the store).
fn identical(l: &V, r: &V) -> Option<TokenStream> {
    let (le, re) = (&l.e, &r.e);
    let some = quote!(::std::option::Option::Some);
    match (&l.ty, &r.ty) {
        (a, b) if a == b && eq_safe(a) => Some(quote!((#le == #re))),
        (Ty::Term, Ty::Term) => Some(quote!(cx.store_ref().identical(#le.0, #re.0))),
        (Ty::Term, Ty::Sym) => Some(quote!((cx.store_ref().atom_of(#le.0) == #some(#re)))),
        (Ty::Sym, Ty::Term) => Some(quote!((cx.store_ref().atom_of(#re.0) == #some(#le)))),
        (Ty::Term, Ty::Int) => Some(quote!((cx.store_ref().int_of(#le.0) == #some(#re)))),
        (Ty::Int, Ty::Term) => Some(quote!((cx.store_ref().int_of(#re.0) == #some(#le)))),
        _ => None,
    }
}

/// `[h|t]` of native values.
fn cons(h: V, t: V) -> N<V> {
    let ty = match &t.ty {
        Ty::List(e) if **e == Ty::Never => Ty::list(h.ty.clone()),
        Ty::List(e) if **e == h.ty => t.ty.clone(),
        // An atom or int among ground terms: its term.
        Ty::List(e) if **e == Ty::Term && matches!(h.ty, Ty::Sym | Ty::Int) => {
            let head = coerce(&h, &Ty::Term)?;
            return cons(
                V {
                    e: head,
                    ty: Ty::Term,
                },
                t,
            );
        }
        _ => return Err(format!("`[_|_]` of {} and {}", h.ty, t.ty)),
    };
    let rt = ty.clone();
    let r = rust_ty(&rt)?;
    let tail = coerce(&t, &ty)?;
    let head = h.e;
    Ok(V {
        e: quote!(<#r>::cons(#head, #tail)),
        ty,
    })
}

/// `v` as a value of type `to`.
fn coerce(v: &V, to: &Ty) -> N<TokenStream> {
    if v.ty == *to {
        return Ok(v.e.clone());
    }
    match (&v.ty, to) {
        // An empty list is an empty list of anything.
        (Ty::List(e), Ty::List(_)) if **e == Ty::Never => {
            let ty = rust_ty(to)?;
            let e = &v.e;
            Ok(quote!({ let _ = #e; <#ty>::nil() }))
        }
        (Ty::Never, _) => {
            let e = &v.e;
            Ok(quote!(match #e {}))
        }
        // An immediate term of a native scalar, or `[]`.
        (Ty::Sym, Ty::Term) => {
            let e = &v.e;
            Ok(quote!(::sitlog_runtime::native::Ground(::sitlog_runtime::Term::atom(#e))))
        }
        (Ty::Int, Ty::Term) => {
            let e = &v.e;
            Ok(quote!(::sitlog_runtime::native::Ground(::sitlog_runtime::Term::int(#e))))
        }
        (Ty::List(e), Ty::Term) if **e == Ty::Never => {
            let e = &v.e;
            Ok(
                quote!({ let _ = #e; ::sitlog_runtime::native::Ground(::sitlog_runtime::Term::NIL) }),
            )
        }
        _ => Err(format!("a value of type {} where {} is expected", v.ty, to)),
    }
}
