//! A DM whose head has an argument written as a pattern (`key_of(K-_Qty)`,
//! `first([X|_])`, `cell(p(A, B))`; issue 37, `nstock23`) in native code.
//!
//! The MIR gives each variable of such an argument [`Init::HeadPath`]: the
//! part of the DM call's argument at that path, which the call's
//! unification with the head (where the DM starts, E13) made it. Native
//! code holds the parameter as a `Val` (its type `ground` or a fixed-shape
//! compound) and takes the part apart at each visit (`native::head_part`,
//! no allocation). A native caller pushes such a callee's frame only where
//! its argument matches the pattern (Rust tests on the `Val` generated
//! from the pattern, [`Gen::head_guard`]: `v0.args_of(a.minus, 2)
//! .is_some()` for `K-_Qty`, no store read); where it does
//! not, or where that is not decided natively, the call goes to the
//! machine, whose unification decides and reports a head that does not
//! unify exactly as the interpreter does (the same path as a call that is
//! not native). The machine entering the DM (`nat_entry`) finds the call
//! already unified with the head.
//!
//! Invariant: a frame of such a DM exists only with parameters that match
//! their patterns, so `head_part` finds its part (a fault otherwise,
//! `Fault::HeadPart`, never a wrong value).

use super::{held_as_val, reg, rust_ty, Dm, Regs, N};
use crate::codegen::Gen;
use crate::mir::Reg;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::native::Ty;
use sitlog_runtime::{Term, Value};
use sitlog_syntax::atoms;

/// `let rN: T = ..;` loading register `r` (of type `ty`) from the part at
/// `path` of parameter `i`, a pattern of the head.
pub(super) fn load_head_path(
    d: &Dm,
    r: Reg,
    i: usize,
    path: &[usize],
    ty: Ty,
    regs: &mut Regs,
) -> N<TokenStream> {
    let pty = d.params.get(i).ok_or("a head argument out of range")?;
    if !held_as_val(pty) {
        return Err(format!(
            "parameter {} (a pattern of the head) is typed {pty}",
            i + 1
        ));
    }
    let p = format_ident!("p{}", i);
    let rr = reg(r);
    let rty = rust_ty(&ty)?;
    if !matches!(ty, Ty::Int | Ty::Float | Ty::Sym) && !held_as_val(&ty) {
        return Err(format!(
            "a part of parameter {} (a pattern of the head) is typed {ty}",
            i + 1
        ));
    }
    let path = path.iter().map(|&k| Literal::usize_unsuffixed(k));
    regs.insert(r, (rr.clone(), ty));
    Ok(quote! {
        let #rr: #rty = native::head_part(&#p, &[#(#path),*])
            .ok_or_else(|| cx.fault(Fault::HeadPart))?;
    })
}

impl Gen<'_> {
    /// The condition under which a native caller pushes DM `j`'s frame
    /// with arguments `vs` (of types `tys`): each argument whose head
    /// argument is a pattern matches it (`&& ..`, Rust tests on the `Val`
    /// generated from the pattern, [`Gen::head_match`]; empty for a head of
    /// variables); an error where such an argument is not held as the
    /// callee's `Val` or the pattern has a float or a big integer (the call
    /// is then the machine's).
    pub(super) fn head_guard(
        &self,
        j: usize,
        vs: &[Ident],
        tys: &[Ty],
        params: &[Ty],
    ) -> N<TokenStream> {
        let ir = self.ir.ok_or("no IR")?;
        let head = ir.dms[j].head;
        let mut conds = Vec::new();
        let mut n = 0;
        for (i, &a) in self.store.args(head).iter().enumerate() {
            if matches!(self.store.value(a), Value::Var(_)) {
                continue;
            }
            let (Some(ty), Some(pty), Some(x)) = (tys.get(i), params.get(i), vs.get(i)) else {
                return Err("a head pattern without its argument".into());
            };
            if ty != pty || !held_as_val(pty) {
                return Err(format!(
                    "an argument of type {ty} for a head pattern (parameter typed {pty})"
                ));
            }
            if let Some(c) = self.head_match(a, quote!(#x), &mut n, 0)? {
                conds.push(quote!(&& #c));
            }
        }
        Ok(quote!(#(#conds)*))
    }

    /// Whether the `Val` `e` unifies with pattern `t` (a head argument whose
    /// variables are all distinct: each matches anything), as Rust tests;
    /// `None`: always (a variable).
    fn head_match(
        &self,
        t: Term,
        e: TokenStream,
        n: &mut usize,
        depth: usize,
    ) -> N<Option<TokenStream>> {
        if depth > crate::mir::MAX_DEPTH {
            return Err("a head pattern too deep".into());
        }
        Ok(match self.store.value(t) {
            Value::Var(_) => None,
            Value::Atom(a) if a == atoms::NIL => Some(quote!(#e.is_nil())),
            Value::Atom(a) => {
                let k = self.atom_native(a)?;
                Some(quote!(#e.sym() == Some(#k)))
            }
            Value::Int(i) => {
                let l = Literal::i64_unsuffixed(i);
                Some(quote!(#e.int() == Some(#l)))
            }
            Value::Compound(f, args) if f == atoms::DOT && args.len() == 2 => {
                let (h, tl) = (format_ident!("h{}", *n), format_ident!("t{}", *n));
                *n += 1;
                let (a0, a1) = (args[0], args[1]);
                let ch = self.head_match(a0, quote!(#h), n, depth + 1)?;
                let ct = self.head_match(a1, quote!(#tl), n, depth + 1)?;
                let conds: Vec<TokenStream> = ch.into_iter().chain(ct).collect();
                if conds.is_empty() {
                    Some(quote!(#e.split_list().is_some()))
                } else {
                    Some(quote!(#e.split_list().is_some_and(|(#h, #tl)| #(#conds)&&*)))
                }
            }
            Value::Compound(f, args) => {
                let k = self.atom_native(f)?;
                let arity = Literal::usize_unsuffixed(args.len());
                let xs = format_ident!("xs{}", *n);
                *n += 1;
                let args = args.to_vec();
                let mut conds = Vec::new();
                for (i, a) in args.into_iter().enumerate() {
                    let il = Literal::usize_unsuffixed(i);
                    if let Some(c) = self.head_match(a, quote!(#xs[#il]), n, depth + 1)? {
                        conds.push(c);
                    }
                }
                if conds.is_empty() {
                    Some(quote!(#e.args_of(#k, #arity).is_some()))
                } else {
                    Some(quote!(#e.args_of(#k, #arity).is_some_and(|#xs| #(#conds)&&*)))
                }
            }
            _ => return Err("a head pattern with a float or a big integer".into()),
        })
    }
}
