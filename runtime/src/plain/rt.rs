//! What a plain function compiled to Rust calls (issue 37: the functions
//! `sitlog_compiler::codegen::native::plain_rs` writes from the forms of
//! [`super::plain_forms`]): the comparisons and checks of the evaluator on
//! values (`val`), the same functions, so a compiled clause compares,
//! takes apart and refuses exactly as [`PlainFns::call_vals`](super::PlainFns)
//! does.
//!
//! Invariant: each function here is the one `call_vals` runs for the same
//! step (no second implementation of `==`, of a head's compound, of `mod`
//! or of the arguments' check).

use super::val;
use crate::native::{List, Val};
use crate::term::Term;
use sitlog_syntax::Atom;

pub use super::val::Parts;

/// Whether every argument is one the plain form takes (ground, no float,
/// no improper list, no construct of L, at most `MAX_DEPTH` deep): the
/// check `call_vals` makes before it runs a clause.
#[inline]
pub fn args_sure(args: &[Val]) -> bool {
    args.iter().all(val::sure_arg)
}

/// `x == y` of two values a plain clause holds.
#[inline]
pub fn ident(x: &Val, y: &Val) -> bool {
    val::ident(x, y)
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
