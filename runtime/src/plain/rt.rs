//! What a plain function compiled to Rust calls (issue 37: the functions
//! `sitlog_compiler::codegen::native::plain_rs` writes from the forms of
//! [`super::plain_forms`]): the comparisons and checks of the evaluator on
//! values (`val`), the same functions, so a compiled clause compares,
//! takes apart and refuses exactly as [`PlainFns::call_vals`](super::PlainFns)
//! does.
//!
//! Invariant: each function here is the one `call_vals` runs for the same
//! step (no second implementation of `==`, of a head's compound, of `mod`
//! or of the arguments' check; an atom's or an integer's case decided
//! inline is the first case of the evaluator's own). [`Answer`]: what a
//! compiled function answers (a `Val`, or the generated `Ans<k>` of one
//! that answers compounds by their parts).

use super::val;
use crate::native::{List, Val};
use crate::term::Term;
use sitlog_syntax::Atom;

pub use super::val::Parts;

/// Whether every argument is one the plain form takes (ground, no float
/// but a sure one,
/// no improper list, no construct of L, at most `MAX_DEPTH` deep): the
/// check `call_vals` makes before it runs a clause.
#[inline]
pub fn args_sure(args: &[Val]) -> bool {
    args.iter().all(arg_sure)
}

/// [`args_sure`] of one argument (an atom or an integer without a call).
#[inline]
pub fn arg_sure(v: &Val) -> bool {
    matches!(v, Val::Int(_) | Val::Sym(_)) || val::sure_arg(v)
}

/// An argument as the reference a compiled function takes (`x` a `Val`
/// or a `&Val`).
#[inline(always)]
pub fn arg<B: std::borrow::Borrow<Val> + ?Sized>(x: &B) -> &Val {
    x.borrow()
}

/// What a compiled plain function answers: its value, or (a function
/// that answers a compound: the generated `Ans<k>`) which compound and
/// its parts, the value not built. [`Answer::of_val`]: a value the
/// function's path not compiled gave.
pub trait Answer {
    fn of_val(v: Val) -> Self;
}

impl Answer for Val {
    #[inline(always)]
    fn of_val(v: Val) -> Val {
        v
    }
}

/// `x == y` of two values a plain clause holds.
#[inline]
pub fn ident(x: &Val, y: &Val) -> bool {
    match (x, y) {
        (Val::Sym(a), Val::Sym(b)) => a == b,
        (Val::Int(a), Val::Int(b)) => a == b,
        _ => val::ident(x, y),
    }
}

/// `v == a` (the atom `a`; `[]` the empty list too).
#[inline]
pub fn is_atom(v: &Val, a: Atom) -> bool {
    match v {
        Val::Sym(b) => *b == a,
        _ => val::ident_k(v, Term::atom(a)),
    }
}

/// `v == i`.
#[inline]
pub fn is_int(v: &Val, i: i64) -> bool {
    matches!(v, Val::Int(j) if *j == i)
}

/// The arguments of `v` as the compound `f/n` (a list cell for `'.'/2`).
#[inline]
pub fn parts(v: &Val, f: Atom, n: usize) -> Option<Parts<'_>> {
    val::parts(v, f, n)
}

/// The integer `v` is (`None`: the term path decides, a type error).
#[inline]
pub fn int(v: &Val) -> Option<i64> {
    match v {
        Val::Int(i) => Some(*i),
        _ => None,
    }
}

/// `x mod y` (`None`: division by zero or an overflow).
#[inline]
pub fn modulo(x: i64, y: i64) -> Option<i64> {
    super::bin(super::Bin::Mod, x, y).ok()
}

/// The list cell `[h|t]` (`None`: `t` is not a list, the term path's).
#[inline]
pub fn cons(h: Val, t: Val) -> Option<Val> {
    match t {
        Val::List(t) => Some(Val::List(List::cons(h, t))),
        _ => None,
    }
}

pub use super::{Bin, Cmp, Un};
/// A number of a clause's arithmetic (a function with a float constant
/// or a `/` keeps its `is` variables as these).
pub use crate::arith::Number as Num;

/// The number `v` is (`None`: the term path decides: not a number, a
/// float the plain form does not take).
#[inline]
pub fn num(v: &Val) -> Option<Num> {
    match v {
        Val::Int(i) => Some(Num::Int(*i)),
        _ => val::number(v).ok(),
    }
}

/// A number as a value.
#[inline]
pub fn num_val(n: Num) -> Val {
    match n {
        Num::Int(i) => Val::Int(i),
        Num::Float(f) => Val::Float(f),
    }
}

/// `op x` (`super::num::un`).
#[inline]
pub fn un(op: Un, x: Num) -> Option<Num> {
    super::num::un(op, x)
}

/// `x op y` (`super::num::bin`).
#[inline]
pub fn bin(op: Bin, x: Num, y: Num) -> Option<Num> {
    super::num::bin(op, x, y)
}

/// Whether `x op y` holds (`super::num::compare`).
#[inline]
pub fn cmp(op: Cmp, x: Num, y: Num) -> Option<bool> {
    super::num::compare(op, x, y)
}

/// Whether `V is E` holds with `V` the number `v` (`super::num::same`).
#[inline]
pub fn same(e: Num, v: Num) -> bool {
    super::num::same(e, v)
}

/// Whether a local of the caller, sent with a query, is one the plain
/// form runs a call beside (the term path's check of the caller's
/// variables, `plain::sure` not strict: not too deep for the engine);
/// stricter here (a value `call_vals` takes as an argument), which
/// refuses more, never less.
#[inline]
pub fn local_sure(v: &Val) -> bool {
    matches!(v, Val::Int(_) | Val::Sym(_) | Val::Float(_)) || val::sure_arg(v)
}
