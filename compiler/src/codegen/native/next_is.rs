//! `V is E` as an argument of a computed next situation (`=> hit(E is D -
//! 1)`, `review19`'s finding 2): its value, `E`'s, is the argument. Where
//! `E` is integer arithmetic of ints native code holds (`+`, `-`, `*`,
//! unary `-`: [`Gen::nat_int_expr`]) and `V` is read nowhere else, the
//! value is computed in Rust, first, in the evaluator's order (the other
//! arguments are native values that evaluate to themselves: nothing to
//! order them by); an overflow (the only way ints fail) is the cold path:
//! the native frames handed over, the machine entered in the situation,
//! `is` evaluated on terms as the evaluator does (its value, or its error
//! with its message), and the next situation handed to the machine as the
//! term it built ([`Gen::nat_next`]'s fallback for a part the evaluator
//! computes). Without this the situation stayed on terms, and a caller
//! whose callee has a situation on terms ran from its template at every
//! visit. The same where `V` is first met inside a conditional's branch
//! (`(I >= Top -> roof ; otherwise -> rung(_J is I + 1))`, helper
//! `review22`), which the MIR makes an [`Ev::Is`] of an unset register.
//! Float arithmetic (`add(Rest, _ is S + W * 0.5)`: `E` a float by
//! [`Gen::float_typed`], helper `ngauge25`) the same way, computed as an
//! arc's action computes it ([`Gen::nat_float_expr`]): an operand that is
//! no number, an int overflow inside or a result that is not finite takes
//! the cold path above, the machine's evaluation.

use super::{Dm, Regs, N, V};
use crate::codegen::Gen;
use crate::mir::{Build, Ev, Init, Reg};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use sitlog_runtime::native::Ty;
use sitlog_syntax::Atom;

/// `V is E` with `V` unbound where it is evaluated: [`Ev::IsFresh`], or
/// [`Ev::Is`] of a register that starts unbound in the visit (not a
/// parameter, an id part or the pipe) and that nothing set before (the MIR
/// makes `Is` of a variable first met inside a conditional's branch:
/// `(I >= Top -> roof ; otherwise -> rung(_J is I + 1))`; in a
/// perceptual situation such a variable is a fresh term `fresh_r<n>` the
/// visit would make, still unbound here); its expression and register.
pub(super) fn fresh_is<'e>(d: &Dm, cur: usize, e: &'e Ev, regs: &Regs) -> Option<(&'e Build, Reg)> {
    match e {
        Ev::IsFresh { expr, dst } => Some((expr, *dst)),
        Ev::Is {
            lhs: Build::Reg(dst),
            expr,
        } if regs.get(dst).is_none_or(|(x, _)| super::is_fresh(x))
            && d.plans[cur]
                .inits
                .iter()
                .all(|(x, i)| x != dst || matches!(i, Init::Fresh)) =>
        {
            Some((expr, *dst))
        }
        _ => None,
    }
}

impl Gen<'_> {
    /// Next situation `name(args..)` of situation `cur` (named `cur_name`)
    /// with at least one argument `V is E` ([`Ev::IsFresh`]): the selection
    /// of the native situation it names, or an error (not native: the
    /// caller keeps the situation on terms).
    pub(super) fn nat_next_is(
        &self,
        d: &Dm,
        cur: usize,
        name: Atom,
        args: &[Ev],
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<TokenStream> {
        let mut ints = Vec::new();
        let mut vals = Vec::new();
        let mut xs = Vec::new();
        let mut terms = Vec::new();
        let mut cold = Vec::new();
        let mut n = 0;
        for (k, a) in args.iter().enumerate() {
            match fresh_is(d, cur, a, regs) {
                Some((expr, dst)) => {
                    if !super::free_here(d, cur, dst, regs) {
                        return Err("`V is E` whose `V` is read again".into());
                    }
                    // Float arithmetic as an arc's action does it
                    // (`float_expr`); else integer arithmetic.
                    let (e, num, ty) = if self.float_typed(expr, regs) {
                        (self.nat_float_expr(expr, regs)?, quote!(f64), Ty::Float)
                    } else {
                        (self.nat_int_expr(expr, regs)?, quote!(i64), Ty::Int)
                    };
                    let x = format_ident!("is{}", k);
                    ints.push(quote!(let #x: Option<#num> = #e;));
                    let t = self.nat_build_term(expr, regs, &mut cold, &mut n)?;
                    let y = format_ident!("is_t{}", k);
                    cold.push(quote! {
                        let #y = match #x {
                            Some(v) => cx.term(&v),
                            None => cx.is(None, #t, arc_at)?,
                        };
                    });
                    terms.push(quote!(#y));
                    vals.push(V { e: quote!(#x), ty });
                    xs.push(x);
                }
                None => {
                    let v = self.nat_ev_value(d, cur, a, regs)?;
                    let e = &v.e;
                    terms.push(quote!(cx.term(&#e)));
                    vals.push(v);
                }
            }
        }
        let enter = self.nat_enter_to_evaluate(d, cur)?;
        let f = self.functor_native(name)?;
        let out = d.out.borrow().clone();
        let tail = super::goto_tail(&d.rec.borrow());
        let sel = self.nat_select(d, cur, name, vals, cur_name)?;
        let (pat, val) = match xs.as_slice() {
            [x] => (quote!(Some(#x)), quote!(#x)),
            _ => (quote!((#(Some(#xs)),*)), quote!((#(#xs),*))),
        };
        Ok(quote! {{
            #(#ints)*
            let #pat = #val else {
                // An overflow: `is` on terms, the next situation the machine's.
                #enter
                #(#cold)*
                let ts = [#(#terms),*];
                let rec_next = cx.build(#f, &ts);
                cx.count_transitions(count);
                #out
                #tail
            };
            #sel
        }})
    }
}
