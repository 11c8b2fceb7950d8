//! A global read's cold arm in a conditional's condition (issue 37,
//! `review19`'s finding 1). Native code reads a global as a value of its
//! MIR type (`Cx::global_as`); a frame on terms (a parameter that was not
//! ground where its frame started) may have stored a value that type does
//! not allow, such as an unbound variable (`set(goal, Goal)`, `Goal`
//! unbound). The interpreter then evaluates the condition on terms (`a ==
//! _G` is false) and goes on; native code must do the same, not stop with
//! an error. So where the machine can evaluate the condition
//! (`Cx::condition` through the situation's lazy id, as for a condition
//! native code cannot test at all), the native test is a labelled block
//! whose global read, on finding such a value, breaks out of it with
//! `None` (the native frames already handed over and the machine entered
//! by the read's cold arm), and the condition is evaluated on terms: the
//! branches chosen by the machine's answer, its error where it gives one.
//! In a DM with locals only where evaluating the condition changes none
//! ([`Gen::keeps_locals`], helper `ncold21`: native code goes on with the
//! frame's locals after it). A condition that binds a register for its
//! branches (`(get(h, D) == V -> .. D ..)`) is not made here: the whole
//! next situation goes on on terms (`cold_next`'s `Gen::nat_if_cold`).
//! The hot path (the global of its type) is unchanged.

use super::{Dm, Regs, N};
use crate::codegen::Gen;
use crate::mir::{Build, Cond, Ev};
use proc_macro2::{Group, Ident, TokenStream, TokenTree};
use quote::{format_ident, quote};
use sitlog_runtime::native::Ty;
use sitlog_syntax::atoms;

impl Gen<'_> {
    /// Condition `c` of situation `cur`'s conditional as native code
    /// ([`Gen::nat_cond_bind`]: `regs` the registers after it, `binds` its
    /// statements) whose global reads fall back to `on_terms` (the
    /// statements binding the machine's answer to the name given, `None`:
    /// the machine cannot evaluate it): the test and the statements before
    /// it, or `nat_cond_bind`'s error. A global read that has nowhere to go
    /// (no `on_terms`, or a test that binds registers for the branches,
    /// `get(v, D)`) is made as before, an error in its cold arm.
    pub(super) fn nat_cond_cold(
        &self,
        d: &Dm,
        cur: usize,
        c: &Cond,
        regs: &mut Regs,
        binds: &mut Vec<TokenStream>,
        on_terms: &dyn Fn(&Ident) -> N<Option<TokenStream>>,
    ) -> N<N<(TokenStream, TokenStream)>> {
        let name = format_ident!("cond_value");
        let before = regs.clone();
        let saved = self.global_cold.replace(Some(quote!(break 'nat_cold None)));
        let test = self.nat_cond_bind(d, cur, c, regs, binds);
        *self.global_cold.borrow_mut() = saved;
        let test = match test {
            Ok(t)
                if t.to_string().contains("nat_cold")
                    || binds.iter().any(|b| b.to_string().contains("nat_cold")) =>
            {
                t
            }
            Ok(t) => return Ok(Ok((t, quote!(#(#binds)*)))),
            Err(e) => return Ok(Err(e)),
        };
        let redo = match on_terms(&name)? {
            Some(redo) if binds.is_empty() => redo,
            // Made again, the read's cold arm an error.
            _ => {
                *regs = before;
                binds.clear();
                let t = self.nat_cond_bind(d, cur, c, regs, binds);
                return Ok(t.map(|t| (t, quote!(#(#binds)*))));
            }
        };
        // The fresh variables the evaluation reads (`get(goal, _)`'s `_`)
        // made in the cold arm, not at every visit (`fresh_vars`).
        let mut fresh = std::collections::BTreeSet::new();
        let redo = cold_fresh(redo, &mut fresh);
        let vars = (!fresh.is_empty()).then(|| {
            let fresh = fresh.iter();
            quote!(let [#(#fresh),*] = cx.vars();)
        });
        let pre = quote! {
            let native: Option<bool> = 'nat_cold: { Some(#test) };
            let #name: bool = match native {
                Some(v) => v,
                None => {
                    #vars
                    #redo
                    #name
                }
            };
        };
        Ok(Ok((quote!(#name), pre)))
    }
}

impl Gen<'_> {
    /// Whether the machine's evaluation of condition `c` (on the terms of
    /// `regs`' values) can change none of the DM's locals, so that native
    /// code goes on with the frame's after it (a global read's cold arm in
    /// a DM with locals): a comparison (`==`, `\\==`, `<`, .., `member/2`,
    /// `not_member/2`) or `(A, B)`/`(A ; B)` of them, whose parts have no
    /// `set`, `inc` or `apply` (a user function may change a local, D-37)
    /// and read no register whose value could be such a compound (a
    /// variable's value is evaluated: only numbers, atoms, lists of them
    /// and unbound variables).
    pub(super) fn keeps_locals(&self, c: &Cond, regs: &Regs) -> bool {
        self.cond_pure(c, Some(regs))
    }

    /// [`Gen::keeps_locals`]; with `regs` `None` any register's value is
    /// taken as one that only reads (`cold_next`'s rule for a value).
    pub(super) fn cond_pure(&self, c: &Cond, regs: Option<&Regs>) -> bool {
        match c {
            Cond::Arith(_, l, r) => self.ev_keeps(l, regs) && self.ev_keeps(r, regs),
            Cond::Cmp(_, l, r) => self.build_keeps(l, regs) && self.build_keeps(r, regs),
            Cond::And(a, b) | Cond::Or(a, b) => self.cond_pure(a, regs) && self.cond_pure(b, regs),
            Cond::Other(Build::Compound(f, args)) => {
                matches!(
                    f.as_str(),
                    "==" | "\\==" | "<" | ">" | "=<" | ">=" | "member" | "not_member"
                ) && args.iter().all(|a| self.build_keeps(a, regs))
            }
            Cond::Other(_) => false,
        }
    }

    fn ev_keeps(&self, e: &Ev, regs: Option<&Regs>) -> bool {
        match e {
            Ev::Value(r) => reg_keeps(*r, regs),
            Ev::Built(b) | Ev::Eval(b) => self.build_keeps(b, regs),
            Ev::If(c, a, b) | Ev::Pick(c, a, b) => {
                self.cond_pure(c, regs) && self.ev_keeps(a, regs) && self.ev_keeps(b, regs)
            }
            Ev::VarOpFresh { op, .. } => *op == atoms::GET,
            Ev::VarOp { op, arg, .. } => *op == atoms::GET && self.build_keeps(arg, regs),
            Ev::IsFresh { expr, .. } | Ev::BindFresh { expr, .. } => self.build_keeps(expr, regs),
            Ev::Is { lhs, expr } => self.build_keeps(lhs, regs) && self.build_keeps(expr, regs),
            Ev::Compound(f, args) => !changes(*f) && args.iter().all(|a| self.ev_keeps(a, regs)),
        }
    }

    fn build_keeps(&self, b: &Build, regs: Option<&Regs>) -> bool {
        match b {
            Build::Reg(r) => reg_keeps(*r, regs),
            Build::Const(t) => self.const_keeps(*t),
            Build::Compound(f, args) => {
                !changes(*f) && args.iter().all(|a| self.build_keeps(a, regs))
            }
        }
    }

    fn const_keeps(&self, t: sitlog_runtime::Term) -> bool {
        match self.store.value(t) {
            sitlog_runtime::Value::Compound(f, args) => {
                !changes(f) && args.iter().all(|a| self.const_keeps(*a))
            }
            _ => true,
        }
    }
}

/// `set`, `inc`, `apply`: evaluated, they may change a local (D-37, D-38).
fn changes(f: sitlog_syntax::Atom) -> bool {
    f == atoms::SET || f == atoms::INC || f == atoms::APPLY
}

/// Whether register `r`'s value is one the evaluator leaves as it is: an
/// unbound variable made at the visit, a number, an atom, a list of them.
fn reg_keeps(r: crate::mir::Reg, regs: Option<&Regs>) -> bool {
    let Some(regs) = regs else {
        return true;
    };
    fn atomic(t: &Ty) -> bool {
        match t {
            Ty::Int | Ty::Float | Ty::Sym | Ty::Never => true,
            Ty::List(e) => atomic(e),
            _ => false,
        }
    }
    regs.get(&r)
        .is_some_and(|(x, ty)| super::is_fresh(x) || atomic(ty))
}

/// `code` with each fresh variable `fresh_r<n>` renamed `cold_r<n>`, the
/// new names in `out`.
pub(super) fn cold_fresh(
    code: TokenStream,
    out: &mut std::collections::BTreeSet<Ident>,
) -> TokenStream {
    code.into_iter()
        .map(|t| match t {
            TokenTree::Ident(i) if super::is_fresh(&i) => {
                let n = i.to_string();
                let x = Ident::new(&n.replacen("fresh_r", "cold_r", 1), i.span());
                out.insert(x.clone());
                TokenTree::Ident(x)
            }
            TokenTree::Group(g) => {
                let mut h = Group::new(g.delimiter(), cold_fresh(g.stream(), out));
                h.set_span(g.span());
                TokenTree::Group(h)
            }
            t => t,
        })
        .collect()
}
