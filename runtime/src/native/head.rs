//! A DM's head argument written as a pattern (`key_of(K-_Qty)`) in native
//! code: the part of the frame's parameter a variable of the pattern takes
//! (`K`, at every visit, D-7). Whether a native caller's argument matches
//! the pattern is tested by code generated from it
//! (`codegen::native::head`).
//!
//! Invariant: [`head_part`] reads, never allocates, and says `None` where
//! the value has no such part or it is not of the type asked.

use super::val::Val;
use super::FromVal;

/// The part of `v` at `path` (argument positions; a list's head 0, its
/// tail 1) as a `T`; `None` when there is no such part or it is not a `T`
/// (never for a frame's parameter that matched the pattern, with the type
/// inference gave the part).
///
/// Inlined: the steps into a compound's argument or a list's head are a
/// loop of reads in place (`key_of(K-_Qty)` takes `K` at every visit of
/// a walk); a step into a list's tail, which makes a list, is
/// `head_part_at`'s.
#[inline]
pub fn head_part<T: FromVal>(v: &Val, path: &[usize]) -> Option<T> {
    let mut cur = v;
    for (n, &k) in path.iter().enumerate() {
        cur = match cur {
            Val::Tagged(c) => c.args().get(k)?,
            Val::List(l) if k == 0 => l.first()?,
            _ => return head_part_at(cur, &path[n..]),
        };
    }
    T::from_val(cur)
}

/// [`head_part`] by recursion on the path, for a step into a list's tail.
fn head_part_at<T: FromVal>(v: &Val, path: &[usize]) -> Option<T> {
    let Some((&k, rest)) = path.split_first() else {
        return T::from_val(v);
    };
    match v {
        Val::List(l) => {
            let (x, tail) = l.split_first()?;
            match k {
                0 => head_part_at(x, rest),
                1 => head_part_at(&Val::List(tail), rest),
                _ => None,
            }
        }
        Val::Tagged(c) => head_part_at(c.args().get(k)?, rest),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::native::Ty;
    use crate::store::Store;
    use sitlog_syntax::Atom;

    fn val(store: &mut Store, text: &str) -> Val {
        let (t, _) = store.parse(text).expect("parses");
        Val::from_term(store, t, &Ty::Ground).expect("ground")
    }

    #[test]
    fn parts_of_pairs_lists_and_compounds() {
        let mut s = Store::new();
        let pair = val(&mut s, "a-1");
        assert_eq!(head_part::<Atom>(&pair, &[0]), Some(Atom::intern("a")));
        assert_eq!(head_part::<i64>(&pair, &[1]), Some(1));
        assert_eq!(head_part::<i64>(&pair, &[2]), None);
        assert_eq!(head_part::<i64>(&pair, &[0]), None);
        let l = val(&mut s, "[x, y]");
        assert_eq!(head_part::<Atom>(&l, &[0]), Some(Atom::intern("x")));
        let tail: Val = head_part(&l, &[1]).expect("a tail");
        assert_eq!(tail, val(&mut s, "[y]"));
        assert_eq!(head_part::<Atom>(&l, &[1, 0]), Some(Atom::intern("y")));
        let nested = val(&mut s, "p(q(1, [z]), b)");
        assert_eq!(
            head_part::<Atom>(&nested, &[0, 1, 0]),
            Some(Atom::intern("z"))
        );
        assert_eq!(head_part::<Atom>(&nested, &[1]), Some(Atom::intern("b")));
        let nil = val(&mut s, "[]");
        assert_eq!(head_part::<Val>(&nil, &[0]), None);
    }
}
