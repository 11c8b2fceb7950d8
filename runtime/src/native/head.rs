//! A DM's head argument written as a pattern (`key_of(K-_Qty)`) met by a
//! native value: whether a native caller's argument matches it (the call's
//! unification with the head, E13, decided where the callee's frame is
//! pushed) and the part of the frame's parameter a variable of the pattern
//! takes (`K`, at every visit, D-7).
//!
//! The pattern is a constant of the program with `'$hole'(i)` in place of
//! each of its variables (`codegen::native::head`), all distinct: a head
//! names each of its variables once (`mir::lower`'s rule), so a hole
//! matches anything and no two holes are compared.
//!
//! Invariant: [`head_matches`] is `true` only when unifying the value's
//! term with a fresh copy of the pattern succeeds (the value is ground:
//! nothing of the caller is bound); `false` where it fails *or* where it is
//! not decided here (a `Val::Term`, a big integer, a float in the
//! pattern): the caller then hands the call to the machine, whose
//! unification decides (and reports E13). Neither function allocates.

use super::val::Val;
use super::FromVal;
use crate::machine::hole_atom;
use crate::store::Store;
use crate::term::{Term, Value};
use sitlog_syntax::atoms;

/// Whether `v` matches `pattern` (see the module doc): `false` when it
/// does not or when that is the machine's to decide.
pub fn head_matches(store: &Store, pattern: Term, v: &Val) -> bool {
    match store.value(pattern) {
        Value::Compound(f, [_]) if f == hole_atom() => true,
        Value::Atom(a) if a == atoms::NIL => v.is_nil(),
        Value::Atom(a) => matches!(v, Val::Sym(b) if *b == a),
        Value::Int(i) => matches!(v, Val::Int(j) if *j == i),
        Value::Compound(f, [h, t]) if f == atoms::DOT => match v {
            Val::List(l) => match l.split_first() {
                Some((x, rest)) => {
                    head_matches(store, *h, x) && head_matches(store, *t, &Val::List(rest))
                }
                None => false,
            },
            Val::Tagged(c) if c.name() == atoms::DOT && c.args().len() == 2 => {
                head_matches(store, *h, &c.args()[0]) && head_matches(store, *t, &c.args()[1])
            }
            _ => false,
        },
        Value::Compound(f, args) => match v {
            Val::Tagged(c) if c.name() == f && c.args().len() == args.len() => args
                .iter()
                .zip(c.args())
                .all(|(&p, x)| head_matches(store, p, x)),
            _ => false,
        },
        // A variable (never in a pattern constant), a big integer, a float:
        // the machine's unification decides.
        _ => false,
    }
}

/// The part of `v` at `path` (argument positions; a list's head 0, its
/// tail 1) as a `T`; `None` when there is no such part or it is not a `T`
/// (never for a frame's parameter that matched the pattern, with the type
/// inference gave the part).
pub fn head_part<T: FromVal>(v: &Val, path: &[usize]) -> Option<T> {
    let Some((&k, rest)) = path.split_first() else {
        return T::from_val(v);
    };
    match v {
        Val::List(l) => {
            let (x, tail) = l.split_first()?;
            match k {
                0 => head_part(x, rest),
                1 => head_part(&Val::List(tail), rest),
                _ => None,
            }
        }
        Val::Tagged(c) => head_part(c.args().get(k)?, rest),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::native::{Ty, Val};

    fn val(store: &mut Store, text: &str) -> Val {
        let (t, _) = store.parse(text).expect("parses");
        Val::from_term(store, t, &Ty::Ground).expect("ground")
    }

    fn pattern(store: &mut Store, text: &str) -> Term {
        store.parse(text).expect("parses").0
    }

    #[test]
    fn a_pair_pattern_matches_pairs_only() {
        let mut s = Store::new();
        let p = pattern(&mut s, "'$hole'(0)-'$hole'(1)");
        let pair = val(&mut s, "a-1");
        assert!(head_matches(&s, p, &pair));
        for other in ["a", "f(a, 1)", "[a]", "1", "+(a, 1)"] {
            let v = val(&mut s, other);
            assert!(!head_matches(&s, p, &v), "{other}");
        }
        assert_eq!(head_part::<Atom>(&pair, &[0]), Some(Atom::intern("a")));
        assert_eq!(head_part::<i64>(&pair, &[1]), Some(1));
        assert_eq!(head_part::<i64>(&pair, &[2]), None);
    }

    #[test]
    fn list_and_constant_patterns() {
        let mut s = Store::new();
        let p = pattern(&mut s, "['$hole'(0)|'$hole'(1)]");
        let l = val(&mut s, "[x, y]");
        assert!(head_matches(&s, p, &l));
        let nil = val(&mut s, "[]");
        assert!(!head_matches(&s, p, &nil));
        assert_eq!(head_part::<Atom>(&l, &[0]), Some(Atom::intern("x")));
        let tail: Val = head_part(&l, &[1]).expect("a tail");
        assert_eq!(tail, val(&mut s, "[y]"));
        let q = pattern(&mut s, "p(yes, 3, [])");
        let v = val(&mut s, "p(yes, 3, [])");
        assert!(head_matches(&s, q, &v));
        let v = val(&mut s, "p(no, 3, [])");
        assert!(!head_matches(&s, q, &v));
        let v = val(&mut s, "p(yes, 4, [])");
        assert!(!head_matches(&s, q, &v));
        let v = val(&mut s, "p(yes, 3, [a])");
        assert!(!head_matches(&s, q, &v));
        // A float: the machine decides.
        let f = pattern(&mut s, "g(1.5)");
        let v = val(&mut s, "g(1.5)");
        assert!(!head_matches(&s, f, &v));
    }

    use sitlog_syntax::Atom;
}
