//! The type tests a condition may call (D-35: `var/1`, `nonvar/1`,
//! `ground/1`, `atom/1`, `number/1`, `integer/1`, `float/1`, `atomic/1`,
//! `compound/1`, `is_list/1`), decided on a term of the store ([`term_is`],
//! what `goal::goal_holds` calls) and on a native value ([`val_is`], what
//! generated code calls on a register held as a [`Val`]).
//!
//! Invariant: for every value `v` and its term `t` (`Val::to_term`),
//! `val_is(k, v, store) == term_is(k, store, t)`: the native test answers as
//! the machine's goal does (a unit test checks each kind on values of every
//! shape). Neither writes the store.

use crate::native::Val;
use crate::store::Store;
use crate::term::{Term, Value};
use sitlog_syntax::atoms;

/// A type test of a condition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TypeTest {
    Var,
    Nonvar,
    Ground,
    Atom,
    Number,
    Integer,
    Float,
    Atomic,
    Compound,
    IsList,
}

impl TypeTest {
    /// Every type test, in the order of [`TypeTest::name`].
    pub const ALL: [TypeTest; 10] = [
        TypeTest::Var,
        TypeTest::Nonvar,
        TypeTest::Ground,
        TypeTest::Atom,
        TypeTest::Number,
        TypeTest::Integer,
        TypeTest::Float,
        TypeTest::Atomic,
        TypeTest::Compound,
        TypeTest::IsList,
    ];

    /// The test a goal `name/arity` is, if it is one.
    pub fn of(name: &str, arity: usize) -> Option<TypeTest> {
        if arity != 1 {
            return None;
        }
        TypeTest::ALL.into_iter().find(|t| t.name() == name)
    }

    /// [`val_is`] (the form generated code calls).
    #[inline]
    pub fn of_val(self, v: &Val, store: &Store) -> bool {
        val_is(self, v, store)
    }

    /// [`term_is`] (the form generated code calls).
    #[inline]
    pub fn of_term(self, store: &Store, t: Term) -> bool {
        term_is(self, store, t)
    }

    /// Its predicate's name.
    pub fn name(self) -> &'static str {
        match self {
            TypeTest::Var => "var",
            TypeTest::Nonvar => "nonvar",
            TypeTest::Ground => "ground",
            TypeTest::Atom => "atom",
            TypeTest::Number => "number",
            TypeTest::Integer => "integer",
            TypeTest::Float => "float",
            TypeTest::Atomic => "atomic",
            TypeTest::Compound => "compound",
            TypeTest::IsList => "is_list",
        }
    }
}

/// Whether the term `t` passes test `k` (the goal `k(t)` holds).
pub fn term_is(k: TypeTest, store: &Store, t: Term) -> bool {
    let v = store.deref(t);
    match k {
        TypeTest::Var => store.is_var(v),
        TypeTest::Nonvar => !store.is_var(v),
        TypeTest::Ground => store.is_ground(v),
        TypeTest::Atom => store.atom_of(v).is_some(),
        TypeTest::IsList => store.list_to_vec(v).is_some(),
        _ => matches!(
            (k, store.value(v)),
            (
                TypeTest::Number,
                Value::Int(_) | Value::BigInt(_) | Value::Float(_)
            ) | (TypeTest::Integer, Value::Int(_) | Value::BigInt(_))
                | (TypeTest::Float, Value::Float(_))
                | (
                    TypeTest::Atomic,
                    Value::Atom(_) | Value::Int(_) | Value::BigInt(_) | Value::Float(_)
                )
                | (TypeTest::Compound, Value::Compound(..))
        ),
    }
}

/// Whether the native value `v` passes test `k`, as its term would
/// ([`term_is`]); the store is read only for a value held as a term
/// (`Val::Term`, possibly unbound).
pub fn val_is(k: TypeTest, v: &Val, store: &Store) -> bool {
    match v {
        Val::Int(_) => matches!(
            k,
            TypeTest::Nonvar
                | TypeTest::Ground
                | TypeTest::Number
                | TypeTest::Integer
                | TypeTest::Atomic
        ),
        Val::Float(_) => matches!(
            k,
            TypeTest::Nonvar
                | TypeTest::Ground
                | TypeTest::Number
                | TypeTest::Float
                | TypeTest::Atomic
        ),
        Val::Sym(a) => atom_is(k, *a),
        Val::List(l) if l.is_empty() => atom_is(k, atoms::NIL),
        Val::List(l) => match k {
            TypeTest::Nonvar | TypeTest::Compound => true,
            TypeTest::Ground => l.iter().all(|x| val_is(k, x, store)),
            // A `List` is proper: its elements are any values.
            TypeTest::IsList => true,
            _ => false,
        },
        Val::Tagged(c) if c.args().is_empty() => atom_is(k, c.name()),
        Val::Tagged(c) => match k {
            TypeTest::Nonvar | TypeTest::Compound => true,
            TypeTest::Ground => c.args().iter().all(|x| val_is(k, x, store)),
            TypeTest::IsList => tagged_list(c.name(), c.args(), store),
            _ => false,
        },
        Val::Term(t) => term_is(k, store, t.get()),
    }
}

/// An atom's answers (`[]` a list too).
fn atom_is(k: TypeTest, a: sitlog_syntax::Atom) -> bool {
    match k {
        TypeTest::Nonvar | TypeTest::Ground | TypeTest::Atom | TypeTest::Atomic => true,
        TypeTest::IsList => a == atoms::NIL,
        _ => false,
    }
}

/// `is_list/1` of `name(args..)`: a cell `'.'(H, T)` whose tail is a
/// proper list (followed along the spine, no recursion).
fn tagged_list(name: sitlog_syntax::Atom, args: &[Val], store: &Store) -> bool {
    let (mut name, mut args) = (name, args);
    loop {
        if name != atoms::DOT || args.len() != 2 {
            return false;
        }
        match &args[1] {
            Val::List(_) => return true,
            Val::Sym(a) => return *a == atoms::NIL,
            Val::Term(t) => return term_is(TypeTest::IsList, store, t.get()),
            Val::Tagged(c) if c.args().is_empty() => return c.name() == atoms::NIL,
            Val::Tagged(c) => {
                name = c.name();
                args = c.args();
            }
            Val::Int(_) | Val::Float(_) => return false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::native::{Compound, List};

    /// Values of every shape, each against its term, for every test.
    #[test]
    fn native_answers_as_the_goal() {
        let mut store = Store::new();
        let a = sitlog_syntax::Atom::intern("hello world");
        let f = sitlog_syntax::Atom::intern("f");
        let unbound = store.new_var();
        let vals = vec![
            Val::Int(3),
            Val::Int(-7),
            Val::Float(2.5),
            Val::Sym(a),
            Val::Sym(atoms::NIL),
            Val::List(List::from_vec(vec![])),
            Val::List(List::from_vec(vec![Val::Int(1), Val::Sym(a)])),
            Val::List(List::from_vec(vec![Val::Term(std::cell::Cell::new(
                unbound,
            ))])),
            Val::Tagged(Compound::new(f, [Val::Int(1)])),
            Val::Tagged(Compound::new(f, [])),
            Val::Tagged(Compound::new(atoms::DOT, [Val::Int(1), Val::Int(2)])),
            Val::Tagged(Compound::new(
                atoms::DOT,
                [Val::Int(1), Val::List(List::from_vec(vec![Val::Int(2)]))],
            )),
            Val::Tagged(Compound::new(f, [Val::Term(std::cell::Cell::new(unbound))])),
            Val::Term(std::cell::Cell::new(unbound)),
            Val::Term(std::cell::Cell::new(Term::int(4))),
        ];
        for v in &vals {
            let t = v.to_term(&mut store);
            for k in TypeTest::ALL {
                assert_eq!(
                    val_is(k, v, &store),
                    term_is(k, &store, t),
                    "{}({v:?})",
                    k.name()
                );
            }
        }
    }

    #[test]
    fn names_round_trip() {
        for k in TypeTest::ALL {
            assert_eq!(TypeTest::of(k.name(), 1), Some(k));
            assert_eq!(TypeTest::of(k.name(), 2), None);
        }
        assert_eq!(TypeTest::of("callable", 1), None);
    }
}
