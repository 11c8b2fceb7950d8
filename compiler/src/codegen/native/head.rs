//! A DM whose head has an argument written as a pattern (`key_of(K-_Qty)`,
//! `first([X|_])`, `cell(p(A, B))`; issue 37, `nstock23`) in native code.
//!
//! The MIR gives each variable of such an argument [`Init::HeadPath`]: the
//! part of the DM call's argument at that path, which the call's
//! unification with the head (where the DM starts, E13) made it. Native
//! code holds the parameter as a `Val` (its type `ground` or a fixed-shape
//! compound) and takes the part apart at each visit (`native::head_part`,
//! no allocation). A native caller pushes such a callee's frame only where
//! its argument matches the pattern (`native::head_matches` of the
//! argument against the pattern, a constant of the program with
//! `'$hole'(i)` for each variable, [`Gen::head_guard`]); where it does
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
use sitlog_runtime::{Store, Term, Value};

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

/// The text of `t` with `'$hole'(n)` for its `n`-th variable (`None`
/// when it names `'$hole'`, or has a float or a big integer: not matched
/// natively).
fn pattern_text(store: &Store, t: Term) -> Option<String> {
    let mut scratch = Store::new();
    let mut n = 0;
    let copy = copy_holes(store, t, &mut scratch, &mut n)?;
    Some(scratch.writeq(copy))
}

fn copy_holes(store: &Store, t: Term, out: &mut Store, n: &mut i64) -> Option<Term> {
    let hole = sitlog_runtime::machine::hole_atom();
    Some(match store.value(t) {
        Value::Var(_) => {
            *n += 1;
            out.compound(hole, &[Term::int(*n - 1)])
        }
        Value::Atom(a) if a == hole => return None,
        Value::Atom(_) | Value::Int(_) => t,
        Value::Compound(f, args) => {
            if f == hole {
                return None;
            }
            let args = args.to_vec();
            let mut copied = Vec::with_capacity(args.len());
            for a in args {
                copied.push(copy_holes(store, a, out, n)?);
            }
            out.compound(f, &copied)
        }
        _ => return None,
    })
}

impl Gen<'_> {
    /// The condition under which a native caller pushes DM `j`'s frame
    /// with arguments `vs` (of types `tys`): each argument whose head
    /// argument is a pattern matches it (`&& native::head_matches(..)`,
    /// empty for a head of variables); an error where such an argument is
    /// not held as the callee's `Val` (the call is then the machine's).
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
            let text = pattern_text(self.store, a).ok_or("a head pattern not matched natively")?;
            let k = self
                .pattern_if(text)
                .map(Self::const_index)
                .ok_or("a head pattern not registered")?;
            conds.push(quote!(&& native::head_matches(cx.store(), p.k #k, &#x)));
        }
        Ok(quote!(#(#conds)*))
    }
}
