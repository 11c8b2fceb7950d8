//! The term handle: a 16-byte `Copy` value that is the whole term for atoms,
//! integers, floats and variables, and an index into the [`Store`] for
//! compounds and big integers.
//!
//! A handle means nothing without the store that made it (except the
//! store-free constants built by [`Term::atom`], [`Term::int`] and
//! [`Term::float`]). Handles may point at bound variables: every accessor of
//! the store dereferences first.
//!
//! [`Store`]: crate::Store

use sitlog_syntax::{atoms, Atom};

/// A term handle. `==` on handles is identity (same atom, same number bits,
/// same variable, same stored compound), not structural equality: use
/// [`Store::identical`](crate::Store::identical) for Prolog's `==/2`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct Term(pub(crate) Repr);

/// Private representation. `Functor` only ever appears as the header cell of
/// a compound inside the store; no handle given out is a `Functor`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub(crate) enum Repr {
    /// Variable cell index. Unbound when the cell holds this very handle.
    Var(u32),
    Atom(Atom),
    Int(i64),
    /// Bits, so that handles are `Eq`/`Hash` and `0.0`/`-0.0` stay distinct
    /// as in SWI-Prolog (`0.0 == -0.0` is false).
    Float(u64),
    /// Index of an integer too big for `i64`, kept as decimal text.
    Big(u32),
    /// Index of the header cell of a compound; the args follow it.
    Struct(u32),
    /// Header cell: name, arity and what holds of the whole compound
    /// (`store::GROUND`, `store::INERT`), decided when it is built; a
    /// pattern's `store::HOLED`, noted once as it is read.
    Functor(Atom, u32, u8),
}

impl Term {
    /// The empty list `[]`.
    pub const NIL: Term = Term(Repr::Atom(atoms::NIL));
    /// The atom `true`.
    pub const TRUE: Term = Term(Repr::Atom(atoms::TRUE));
    /// The atom `empty` (the empty expectation and action).
    pub const EMPTY: Term = Term(Repr::Atom(atoms::EMPTY));

    /// An atom (needs no store).
    pub const fn atom(a: Atom) -> Term {
        Term(Repr::Atom(a))
    }

    /// An integer (needs no store).
    pub const fn int(i: i64) -> Term {
        Term(Repr::Int(i))
    }

    /// A float (needs no store).
    pub fn float(f: f64) -> Term {
        Term(Repr::Float(f.to_bits()))
    }
}

impl From<Atom> for Term {
    fn from(a: Atom) -> Term {
        Term::atom(a)
    }
}

impl From<i64> for Term {
    fn from(i: i64) -> Term {
        Term::int(i)
    }
}

impl From<f64> for Term {
    fn from(f: f64) -> Term {
        Term::float(f)
    }
}

/// A variable of a store (its cell index). Valid until the next
/// [`Store::gc`](crate::Store::gc).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct Var(pub(crate) u32);

impl Var {
    /// The cell index; printed variables are `_G<index>`.
    pub fn index(self) -> u32 {
        self.0
    }
}

impl From<Var> for Term {
    fn from(v: Var) -> Term {
        Term(Repr::Var(v.0))
    }
}

/// One level of a dereferenced term, as returned by
/// [`Store::value`](crate::Store::value).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value<'a> {
    /// An unbound variable.
    Var(Var),
    Atom(Atom),
    Int(i64),
    /// An integer outside `i64`, as normalised decimal text (`-` sign, no
    /// leading zeros). Printable and comparable, not computable.
    BigInt(&'a str),
    Float(f64),
    /// Name and arguments (at least one; `f()` does not exist in SWI-6).
    Compound(Atom, &'a [Term]),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn handle_is_small_and_copy() {
        assert_eq!(std::mem::size_of::<Term>(), 16);
        let t = Term::int(3);
        let u = t;
        assert_eq!(t, u);
        assert_ne!(Term::float(0.0), Term::float(-0.0));
        assert_eq!(Term::atom(atoms::NIL), Term::NIL);
    }
}
