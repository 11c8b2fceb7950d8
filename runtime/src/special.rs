//! The functors the language L gives a meaning of its own (D-29..D-38): a
//! compound with any other functor evaluates its arguments only and is
//! rebuilt from their values (D-36).
//!
//! Invariant: [`evaluates_arguments_only`] is the one answer to "does
//! evaluating `name/arity` do anything but evaluate the arguments"; the
//! evaluator dispatches on the same names, the store uses it to mark a
//! compound *inert* (its evaluation is itself, see `Store::is_inert`) when
//! it is built, and the compiler uses it to evaluate terms in place. The
//! check is a bit test on the atom's index, cheap enough for every
//! compound the store builds.

use sitlog_syntax::{atoms, Atom};
use std::sync::OnceLock;

/// The original's list operators and robot built-ins that L evaluates as
/// functions (D-32), with their arity (`None`: any arity).
const LIST_OPERATORS: &[(&str, Option<usize>)] = &[
    ("append", Some(3)),
    ("reverse", Some(2)),
    ("length_list", Some(2)),
    ("first", Some(2)),
    ("rest", Some(2)),
    ("last", Some(2)),
    ("rotate_list", Some(2)),
    ("push", Some(3)),
    ("pop", Some(2)),
    ("filter_element", Some(3)),
    ("filter_duplicates", Some(3)),
    ("idx_object", Some(3)),
    ("get_options", Some(4)),
    ("get_random_element", Some(2)),
    ("empty_list", Some(1)),
    ("print_list", Some(1)),
    ("msg_format", Some(2)),
    ("statistics", Some(2)),
    ("cam2nav", None),
    ("cam2arm", None),
    ("timeOver", None),
    ("arrived_posit", None),
];

/// The comparisons of L (D-34): arguments evaluated, then compared.
pub(crate) const COMPARISONS: [Atom; 6] = [
    atoms::EQ_EQ,
    atoms::NOT_EQ_EQ,
    atoms::GREATER,
    atoms::LESS,
    atoms::GREATER_EQ,
    atoms::LESS_EQ,
];

/// The binary constructs of L (D-29..D-38): conditionals, `apply`,
/// `get`/`set`/`inc`, unification, arithmetic, membership, comparisons.
const BINARY: [Atom; 17] = [
    atoms::ASSIGN,
    atoms::EQUALS,
    atoms::IS,
    atoms::MEMBER,
    atoms::NOT_MEMBER,
    atoms::SEMICOLON,
    atoms::BAR,
    atoms::APPLY,
    atoms::GET,
    atoms::SET,
    atoms::INC,
    COMPARISONS[0],
    COMPARISONS[1],
    COMPARISONS[2],
    COMPARISONS[3],
    COMPARISONS[4],
    COMPARISONS[5],
];

struct Table {
    /// Bit `i` set: the atom of index `i` names a construct of L at some
    /// arity (a superset: the arity is checked after).
    names: Vec<u64>,
    /// The list operators by atom, with their arity.
    list_ops: Vec<(Atom, Option<usize>)>,
}

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        let list_ops: Vec<(Atom, Option<usize>)> = LIST_OPERATORS
            .iter()
            .map(|&(name, arity)| (Atom::intern(name), arity))
            .collect();
        let all = BINARY
            .iter()
            .copied()
            .chain(list_ops.iter().map(|&(a, _)| a));
        let mut names = Vec::new();
        for a in all {
            let i = a.index() as usize;
            if names.len() <= i / 64 {
                names.resize(i / 64 + 1, 0u64);
            }
            names[i / 64] |= 1 << (i % 64);
        }
        Table { names, list_ops }
    })
}

/// Whether `name` names a construct of L at some arity (a cheap superset
/// of `!evaluates_arguments_only(name, _)`).
#[inline]
pub fn may_be_special(name: Atom) -> bool {
    let i = name.index() as usize;
    let names = &table().names;
    names.get(i / 64).is_some_and(|w| w & (1 << (i % 64)) != 0)
}

/// Whether `name/arity` is one of the original's list operators (D-32) or
/// its robot built-ins, which L evaluates as functions.
pub fn is_list_operator(name: Atom, arity: usize) -> bool {
    may_be_special(name)
        && table()
            .list_ops
            .iter()
            .any(|&(a, n)| a == name && n.is_none_or(|n| n == arity))
}

/// Whether evaluating a compound `name/arity` only evaluates its arguments
/// and rebuilds it (D-36): no construct of L has this functor. `;` and `|`
/// answer `false` because whether they are a conditional depends on their
/// arguments.
pub fn evaluates_arguments_only(name: Atom, arity: usize) -> bool {
    if !may_be_special(name) {
        return true;
    }
    if arity == 2 && BINARY.contains(&name) {
        return false;
    }
    !is_list_operator(name, arity)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_constructs_of_l_are_special() {
        assert!(!evaluates_arguments_only(atoms::GET, 2));
        assert!(evaluates_arguments_only(atoms::GET, 3));
        assert!(!evaluates_arguments_only(Atom::intern("append"), 3));
        assert!(evaluates_arguments_only(Atom::intern("append"), 2));
        assert!(!evaluates_arguments_only(Atom::intern("cam2nav"), 5));
        assert!(evaluates_arguments_only(atoms::DOT, 2));
        assert!(evaluates_arguments_only(Atom::intern("try"), 1));
        assert!(is_list_operator(Atom::intern("timeOver"), 1));
        assert!(!is_list_operator(Atom::intern("pop"), 3));
    }
}
