//! The lattice of native value types (`docs/design/typed-mir.md`): what the
//! compiler's inference (`sitlog_compiler::mir::ty`) gives every MIR
//! register, and what the runtime's conversions between native values and
//! terms are told. One type, shared by the compiler, the interpreter and
//! generated code.
//!
//! Invariant: [`Ty::join`] is the least upper bound of the order
//! `Never < {Int, Float, Sym, List<T>, Tagged} < Term`, with `List` and
//! `Tagged` ordered pointwise and `Ground` above every type that holds no
//! `Term` (so `Int ⊔ Sym = Ground`, `List<Int> ⊔ List<Sym> = List<Ground>`,
//! `Ground ⊔ List<Term> = Term`); it is commutative, associative, idempotent,
//! and a type never grows past [`MAX_DEPTH`] levels (deeper joins are
//! `Term`), so every fixpoint over it terminates.

use sitlog_syntax::Atom;
use std::fmt;

/// The deepest nesting of `List`/`Tagged` kept; deeper is `Term`.
pub const MAX_DEPTH: usize = 6;

/// The type of a SitLog value, as native code holds it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Ty {
    /// No value reaches here (the bottom; an empty list's elements).
    Never,
    Int,
    Float,
    /// Any atom (an open set: KB, world and perception make atoms).
    Sym,
    /// A proper list whose elements have this type (`[]` is `List(Never)`).
    List(Box<Ty>),
    /// A compound of this name and arity whose arguments have these types
    /// (`found(P)`, `shelf-Objects`); never a list cell.
    Tagged(Atom, Box<[Ty]>),
    /// Any ground value, held natively (a [`Val`](super::Val) that is an
    /// int, a float, an atom, a proper list or a compound of ground
    /// values, never a term): the join of different native types, and
    /// what a boundary (a Prolog user function, the evaluator, a KB
    /// answer, a perception) gives after a checked conversion (the
    /// contract is in `sitlog_compiler::mir::ty`).
    Ground,
    /// Anything, a term of the store (the top: also a value that may be
    /// unbound where it is read).
    Term,
}

impl Ty {
    /// `List<elem>`.
    pub fn list(elem: Ty) -> Ty {
        Ty::List(Box::new(elem)).capped()
    }

    /// `name(args..)`.
    pub fn tagged(name: Atom, args: Vec<Ty>) -> Ty {
        Ty::Tagged(name, args.into_boxed_slice()).capped()
    }

    /// The least type holding both.
    pub fn join(&self, other: &Ty) -> Ty {
        match (self, other) {
            (Ty::Never, t) | (t, Ty::Never) => t.clone(),
            (Ty::Int, Ty::Int) => Ty::Int,
            (Ty::Float, Ty::Float) => Ty::Float,
            (Ty::Sym, Ty::Sym) => Ty::Sym,
            (Ty::List(a), Ty::List(b)) => Ty::list(a.join(b)),
            (Ty::Tagged(f, a), Ty::Tagged(g, b)) if f == g && a.len() == b.len() => {
                Ty::tagged(*f, a.iter().zip(b.iter()).map(|(x, y)| x.join(y)).collect())
            }
            // Two native values of different shapes: any ground value.
            (a, b) if a.is_native() && b.is_native() => Ty::Ground,
            _ => Ty::Term,
        }
    }

    /// Whether `self ⊑ other`.
    pub fn le(&self, other: &Ty) -> bool {
        self.join(other) == *other
    }

    /// Whether native code holds a value of this type without a term
    /// anywhere in it.
    pub fn is_native(&self) -> bool {
        match self {
            Ty::Never | Ty::Int | Ty::Float | Ty::Sym | Ty::Ground => true,
            Ty::List(e) => e.is_native(),
            Ty::Tagged(_, args) => args.iter().all(Ty::is_native),
            Ty::Term => false,
        }
    }

    /// Levels of `List`/`Tagged` nesting (0 for a scalar).
    pub fn depth(&self) -> usize {
        match self {
            Ty::List(e) => 1 + e.depth(),
            Ty::Tagged(_, args) => 1 + args.iter().map(Ty::depth).max().unwrap_or(0),
            _ => 0,
        }
    }

    /// `Term` in place of a type nested deeper than [`MAX_DEPTH`].
    fn capped(self) -> Ty {
        if self.depth() > MAX_DEPTH {
            Ty::Term
        } else {
            self
        }
    }
}

impl fmt::Display for Ty {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Ty::Never => f.write_str("never"),
            Ty::Int => f.write_str("int"),
            Ty::Float => f.write_str("float"),
            Ty::Sym => f.write_str("atom"),
            Ty::List(e) => write!(f, "list<{e}>"),
            Ty::Tagged(name, args) => {
                let mut text = String::new();
                sitlog_syntax::write::write_atom(&mut text, *name, true);
                write!(f, "{text}(")?;
                for (i, a) in args.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{a}")?;
                }
                f.write_str(")")
            }
            Ty::Ground => f.write_str("ground"),
            Ty::Term => f.write_str("term"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn arb_ty() -> impl Strategy<Value = Ty> {
        let leaf = prop_oneof![
            Just(Ty::Never),
            Just(Ty::Int),
            Just(Ty::Float),
            Just(Ty::Sym),
            Just(Ty::Ground),
            Just(Ty::Term),
        ];
        leaf.prop_recursive(8, 64, 3, |inner| {
            prop_oneof![
                inner.clone().prop_map(Ty::list),
                (
                    prop_oneof![Just("f"), Just("g")],
                    proptest::collection::vec(inner, 1..3)
                )
                    .prop_map(|(n, args)| Ty::tagged(Atom::intern(n), args)),
            ]
        })
    }

    proptest! {
        #[test]
        fn join_is_a_least_upper_bound(a in arb_ty(), b in arb_ty(), c in arb_ty()) {
            prop_assert_eq!(a.join(&b), b.join(&a));
            prop_assert_eq!(a.join(&b).join(&c), a.join(&b.join(&c)));
            prop_assert_eq!(a.join(&a), a.clone());
            prop_assert!(a.le(&a.join(&b)) && b.le(&a.join(&b)));
            prop_assert!(a.join(&b).depth() <= MAX_DEPTH);
        }
    }

    #[test]
    fn lists_join_their_elements() {
        let syms = Ty::list(Ty::Sym);
        assert_eq!(Ty::list(Ty::Never).join(&syms), syms);
        assert_eq!(syms.join(&Ty::list(Ty::Int)), Ty::list(Ty::Ground));
        // Different native shapes meet in `ground`; a term anywhere is `term`.
        assert_eq!(syms.join(&Ty::Sym), Ty::Ground);
        assert_eq!(Ty::Int.join(&Ty::Float).to_string(), "ground");
        assert_eq!(Ty::list(Ty::Term).join(&Ty::Sym), Ty::Term);
        assert_eq!(Ty::Ground.join(&Ty::list(Ty::Term)), Ty::Term);
        assert!(Ty::list(Ty::Ground).le(&Ty::Ground) && Ty::Ground.is_native());
        assert!(syms.is_native() && !Ty::list(Ty::Term).is_native());
        let found = Ty::tagged(Atom::intern("found"), vec![Ty::Sym]);
        assert_eq!(found.to_string(), "found(atom)");
        assert_eq!(syms.to_string(), "list<atom>");
    }
}
