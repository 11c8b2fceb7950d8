//! [`fill`] of a pattern marked as it is read ([`mark_pattern`]) against
//! the same pattern walked whole: the same term, the constant parts shared.

use super::*;

const PATTERNS: &[&str] = &[
    "say([checking,'$hole'(0)])",
    "say(['$hole'(0),is,at,'$hole'(1)])",
    "point(left,'$hole'(0))",
    "f(g(h(a,b),[1,2,3]),'$hole'(1),k('$hole'(0)),[x,y])",
    "try(['$hole'(0)|'$hole'(1)])",
    "f('$hole'(0),'$hole'(0))",
    "f('$hole'(7),a)",
    "f('$hole'(-1),a)",
    "f(a,b,c,d,e,f,g,h,i,'$hole'(0))",
    "'$hole'(0)",
    "f([a,b,c],[d])",
];

fn holes(store: &mut Store) -> Vec<Term> {
    let (c, _) = store.parse("c(1,[2])").unwrap();
    vec![Term::atom(Atom::intern("p3")), Term::int(-4), c]
}

#[test]
fn marked_patterns_fill_as_walked_ones() {
    for text in PATTERNS {
        let mut store = Store::new();
        let hs = holes(&mut store);
        let [marked] = crate::machine::situation::read_consts(&mut store, &[text]);
        let (walked, _) = store.parse(text).unwrap();
        // `'$hole'(-1)` is no hole (no index).
        let holed = text.contains("$hole") && !text.contains("(-1)");
        assert_eq!(store.is_holed(marked), holed, "{text}");
        assert!(!store.is_holed(walked));
        let a = fill_in(&mut store, marked, &hs);
        let b = fill_walk(&mut store, walked, &hs);
        assert_eq!(store.writeq(a), store.writeq(b), "{text}");
        assert!(store.identical(a, b), "{text}");
        // Marking changes no term: the pattern reads as it was.
        assert_eq!(store.writeq(marked), store.writeq(walked), "{text}");
        assert!(store.identical(marked, walked), "{text}");
    }
}

#[test]
fn constant_parts_are_shared_not_copied() {
    let mut store = Store::new();
    let hs = holes(&mut store);
    let [k] = crate::machine::situation::read_consts(
        &mut store,
        &["f(g(h(a,b),[1,2,3]),'$hole'(0),[x,y])"],
    );
    let filled = fill_in(&mut store, k, &hs);
    let (pk, fk) = (store.args(k).to_vec(), store.args(filled).to_vec());
    assert_eq!(pk[0], fk[0]);
    assert_eq!(pk[2], fk[2]);
    assert_eq!(fk[1], hs[0]);
    assert!(!store.is_holed(filled), "a filled term is no pattern");
    // Filled twice from the same pattern: the same text.
    let again = fill_in(&mut store, k, &hs);
    assert_eq!(store.writeq(again), "f(g(h(a,b),[1,2,3]),p3,[x,y])");
}
