//! Float arithmetic of native values (issue 37, helper `review24`): `V is
//! E` where inference types `V` a float (`K1 is K + 1.0`, `K` a float id
//! field) computed in Rust as the evaluator computes it
//! (`sitlog_runtime::arith`): a `+`, `-` or `*` with a float operand is
//! the two operands as `f64` (an int converted by `as`, as
//! `Number::to_f64` does) and the IEEE operation; a subexpression without
//! a float operand is integer arithmetic ([`Gen::nat_int_expr`], then
//! converted), as the evaluator makes it, one with a `Val` operand an
//! int or a float by the values at run time (`Gen::nat_num_expr`); unary
//! `-` negates. The Rust
//! expression is an `Option<f64>`: `None` where a `Val` operand is no
//! number, an int subexpression overflows, or a result is not finite (the
//! evaluator's `float_overflow`/`float_undefined` error, or an infinity
//! that came in): the caller then takes the machine's evaluation, whose
//! value or error is the evaluator's. Without this a float `is` in an
//! arc's action put the arc on terms, and a recursive situation with one
//! in an exit arc ran from its template at every visit
//! (`tests/typed/review24/r24_c_mill_nested`). The same arithmetic is
//! used for `V is E` in a `prog` (`Gen::nat_prog`) and as a next
//! situation's argument (`next_is`), with the same ways back to the
//! machine (helper `ngauge25`).

use super::{held_as_val, Regs, N};
use crate::codegen::Gen;
use crate::mir::Build;
use proc_macro2::{Literal, TokenStream};
use quote::quote;
use sitlog_runtime::native::Ty;
use sitlog_runtime::Value;

impl Gen<'_> {
    /// Whether `b` is a float by its static types: a register typed
    /// `float`, a float constant, or `+`/`-`/`*` (unary `-`) with such an
    /// operand.
    pub(super) fn float_typed(&self, b: &Build, regs: &Regs) -> bool {
        match b {
            Build::Reg(r) => regs.get(r).is_some_and(|(_, ty)| *ty == Ty::Float),
            Build::Const(t) => matches!(self.store.value(*t), Value::Float(f) if f.is_finite()),
            Build::Compound(op, args) => {
                matches!((op.as_str(), args.len()), ("+" | "-" | "*", 2) | ("-", 1))
                    && args.iter().any(|a| self.float_typed(a, regs))
            }
        }
    }

    /// `b`, a float by [`Gen::float_typed`], as a Rust `Option<f64>` (the
    /// module doc).
    pub(super) fn nat_float_expr(&self, b: &Build, regs: &Regs) -> N<TokenStream> {
        if !self.float_typed(b, regs) {
            return Err("an arithmetic expression that is not a float".into());
        }
        Ok(match b {
            Build::Reg(r) => {
                let (x, _) = regs
                    .get(r)
                    .ok_or_else(|| format!("register r{r} is read before it is set"))?;
                quote!(Some(#x))
            }
            Build::Const(t) => match self.store.value(*t) {
                Value::Float(f) => {
                    let f = Literal::f64_suffixed(f);
                    quote!(Some(#f))
                }
                _ => return Err("a float constant that is not one".into()),
            },
            Build::Compound(op, args) => {
                let parts = args
                    .iter()
                    .map(|a| self.nat_num_as_f64(a, regs))
                    .collect::<N<Vec<_>>>()?;
                let done = quote!(.filter(|v: &f64| v.is_finite()));
                match (op.as_str(), parts.as_slice()) {
                    ("+", [a, b]) => quote!(#a.and_then(|a| #b.map(|b| a + b))#done),
                    ("-", [a, b]) => quote!(#a.and_then(|a| #b.map(|b| a - b))#done),
                    ("*", [a, b]) => quote!(#a.and_then(|a| #b.map(|b| a * b))#done),
                    ("-", [a]) => quote!(#a.map(|a| -a)),
                    _ => return Err(format!("arithmetic `{}` is not native yet", op.as_str())),
                }
            }
        })
    }

    /// An operand of a float operation as an `Option<f64>`: a float
    /// expression, or an int one (a register, a constant, integer
    /// arithmetic) converted, or a `Val` that is a number.
    fn nat_num_as_f64(&self, b: &Build, regs: &Regs) -> N<TokenStream> {
        if self.float_typed(b, regs) {
            return self.nat_float_expr(b, regs);
        }
        if let Build::Reg(r) = b {
            if let Some((x, ty)) = regs.get(r) {
                if held_as_val(ty) {
                    return Ok(quote!(match &#x {
                        Val::Float(f) => Some(*f),
                        Val::Int(i) => Some(*i as f64),
                        _ => None::<f64>,
                    }));
                }
            }
        }
        // Arithmetic with a `Val` operand (`(L + L) * 0.25`, `L` the
        // pipe): an int or a float by the values, as the evaluator makes
        // it ([`Gen::nat_num_expr`]).
        if self.has_val_operand(b, regs) {
            let n = self.nat_num_expr(b, regs, 0)?;
            return Ok(quote!(#n.map(|n: ::sitlog_runtime::Number| n.to_f64())));
        }
        let i = self.nat_int_expr(b, regs)?;
        Ok(quote!(#i.map(|i: i64| i as f64)))
    }

    /// Whether `b` reads a register held as a `Val` (a number of either
    /// kind, known at run time only).
    fn has_val_operand(&self, b: &Build, regs: &Regs) -> bool {
        match b {
            Build::Reg(r) => regs.get(r).is_some_and(|(_, ty)| held_as_val(ty)),
            Build::Const(_) => false,
            Build::Compound(_, args) => args.iter().any(|a| self.has_val_operand(a, regs)),
        }
    }

    /// `b` (`+`, `-`, `*`, unary `-` over ints, floats and `Val`s) as a
    /// Rust `Option<Number>`: two ints by checked `i64`, else both as
    /// `f64` (as `sitlog_runtime::arith` does), `None` where a `Val` is no
    /// number, an int overflows or a float result is not finite (the
    /// machine's evaluation then, as for [`Gen::nat_float_expr`]).
    fn nat_num_expr(&self, b: &Build, regs: &Regs, depth: usize) -> N<TokenStream> {
        if depth > crate::mir::MAX_DEPTH {
            return Err("an arithmetic expression too deep".into());
        }
        let num = quote!(::sitlog_runtime::Number);
        Ok(match b {
            Build::Reg(r) => {
                let (x, ty) = regs
                    .get(r)
                    .ok_or_else(|| format!("register r{r} is read before it is set"))?;
                match ty {
                    Ty::Int => quote!(Some(#num::Int(#x))),
                    Ty::Float => quote!(Some(#num::Float(#x))),
                    t if held_as_val(t) => quote!(match &#x {
                        Val::Int(i) => Some(#num::Int(*i)),
                        Val::Float(f) => Some(#num::Float(*f)),
                        _ => None::<#num>,
                    }),
                    _ => return Err(format!("an arithmetic operand of type {ty}")),
                }
            }
            Build::Const(t) => match self.store.value(*t) {
                Value::Int(i) => {
                    let i = Literal::i64_suffixed(i);
                    quote!(Some(#num::Int(#i)))
                }
                Value::Float(f) if f.is_finite() => {
                    let f = Literal::f64_suffixed(f);
                    quote!(Some(#num::Float(#f)))
                }
                _ => return Err("an arithmetic operand that is not a number".into()),
            },
            Build::Compound(op, args) => {
                let parts = args
                    .iter()
                    .map(|a| self.nat_num_expr(a, regs, depth + 1))
                    .collect::<N<Vec<_>>>()?;
                let (int_op, float_op) = match (op.as_str(), parts.len()) {
                    ("+", 2) => (quote!(checked_add), quote!(+)),
                    ("-", 2) => (quote!(checked_sub), quote!(-)),
                    ("*", 2) => (quote!(checked_mul), quote!(*)),
                    ("-", 1) => {
                        let a = &parts[0];
                        return Ok(quote!(#a.and_then(|a: #num| match a {
                            #num::Int(x) => x.checked_neg().map(#num::Int),
                            #num::Float(x) => Some(#num::Float(-x)),
                        })));
                    }
                    _ => return Err(format!("arithmetic `{}` is not native yet", op.as_str())),
                };
                let (a, b) = (&parts[0], &parts[1]);
                quote!(#a.and_then(|a: #num| #b.and_then(|b: #num| match (a, b) {
                    (#num::Int(x), #num::Int(y)) => x.#int_op(y).map(#num::Int),
                    (x, y) => Some(x.to_f64() #float_op y.to_f64())
                        .filter(|v: &f64| v.is_finite())
                        .map(#num::Float),
                })))
            }
        })
    }
}
