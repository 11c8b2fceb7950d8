//! Conjunctions and disjunctions in a conditional's condition as native
//! code (`Cond::And`, `Cond::Or` of the MIR, `mir::lower`'s
//! `Planner::junction`): `((D == Target, K < Rounds) -> dispatch ;
//! otherwise -> halt)`. The evaluator evaluates the condition's arguments
//! before it calls it (D-35), so every operand is computed, left to right,
//! whatever the left one gave; native code does the same: each operand's
//! test is a `let` of its own, run in order (an operand that enters the
//! machine for its error enters it there, the left one's error first),
//! then the two `bool`s are combined. An operand native code cannot test
//! makes the whole condition not native ([`Gen::nat_cond_bind`] gives an
//! error, the caller's fallback then gives the whole condition to the
//! machine, `Cx::condition`, or keeps the situation on terms).

use super::call::Decide;
use super::{Dm, Regs, N};
use crate::codegen::Gen;
use crate::mir::{Build, Cond, Ev};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use sitlog_runtime::ArithCmp;

impl Gen<'_> {
    /// `c`, a [`Cond::And`] or [`Cond::Or`] of situation `cur`'s arc:
    /// statements pushed to `pre` (each operand's test, in order), and the
    /// combined test.
    pub(super) fn nat_junction(
        &self,
        d: &Dm,
        cur: usize,
        c: &Cond,
        regs: &mut Regs,
        pre: &mut Vec<TokenStream>,
    ) -> N<TokenStream> {
        let (Cond::And(l, r) | Cond::Or(l, r)) = c else {
            return Err("not a conjunction or a disjunction".into());
        };
        let side = |c: &Cond, regs: &mut Regs, pre: &mut Vec<TokenStream>| -> N<_> {
            let t = self.nat_junction_leaf(d, cur, c, regs, pre)?;
            let x = format_ident!("cj{}", pre.len());
            pre.push(quote!(let #x: bool = #t;));
            Ok(x)
        };
        let l = side(l, regs, pre)?;
        let r = side(r, regs, pre)?;
        Ok(if matches!(c, Cond::And(..)) {
            quote!((#l && #r))
        } else {
            quote!((#l || #r))
        })
    }

    /// An operand of [`Gen::nat_junction`]: a comparison of L (`A op B`,
    /// its value tested, the machine's `Cx::compare_condition` where the
    /// operands are not two numbers), `==`, `\==`, `member`/`not_member`
    /// of native values (their value is their test: native values are
    /// their own values), or another conjunction or disjunction.
    fn nat_junction_leaf(
        &self,
        d: &Dm,
        cur: usize,
        c: &Cond,
        regs: &mut Regs,
        pre: &mut Vec<TokenStream>,
    ) -> N<TokenStream> {
        match c {
            Cond::Cmp(op, l, r) => self.nat_cmp(d, cur, *op, (l, r), regs, Decide::Junction),
            Cond::Other(_) | Cond::And(..) | Cond::Or(..) => {
                self.nat_cond_bind(d, cur, c, regs, pre)
            }
            Cond::Arith(..) => Err("an arithmetic condition inside a conjunction".into()),
        }
    }

    /// A value comparison [`Cond::Cmp`] `l op r` (`when/3`'s condition,
    /// `how` [`Decide::Value`]; an operand of a conjunction,
    /// [`Decide::Junction`]): a side that is an expression of ints (`N +
    /// 1 > L`) computed in Rust as [`Gen::nat_arith_exprs`] computes an
    /// exit arc's; otherwise both sides native values compared
    /// ([`Gen::nat_arith_as`]). Where they are not numbers (or an
    /// expression overflows) the machine's comparison of the sides' terms
    /// decides (native values are their own values: the sides as written
    /// are their values).
    pub(super) fn nat_cmp(
        &self,
        d: &Dm,
        cur: usize,
        op: ArithCmp,
        (l, r): (&Build, &Build),
        regs: &Regs,
        how: Decide,
    ) -> N<TokenStream> {
        let (le, re) = (Ev::Built(l.clone()), Ev::Built(r.clone()));
        if let Some(t) = self.nat_arith_exprs_as(d, cur, op, (&le, &re), regs, how)? {
            return Ok(t);
        }
        let (l, r) = (self.nat_value(l, regs)?, self.nat_value(r, regs)?);
        match how {
            Decide::Junction => self.nat_arith_in_junction(d, cur, op, l, r),
            _ => self.nat_arith_as(d, cur, op, l, r, true),
        }
    }
}
