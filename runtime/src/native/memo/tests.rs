use super::*;
use crate::native::{Native, Ty, Val};
use sitlog_syntax::Atom;

fn atoms_list(store: &mut Store, n: usize) -> (Vec<Atom>, Term) {
    let xs: Vec<Atom> = (0..n).map(|i| Atom::intern(&format!("p{i}"))).collect();
    let ts: Vec<Term> = xs.iter().map(|&a| Term::atom(a)).collect();
    (xs.clone(), store.list(&ts))
}

/// The `k`-th tail of list term `t`.
fn tail_at(store: &Store, t: Term, k: usize) -> Term {
    let mut cur = t;
    for _ in 0..k {
        cur = store.args(cur)[1];
    }
    cur
}

/// A list and each of its tails convert to what a walk gives, sharing one
/// storage; making a term of a tail gives back the very cell, no cell
/// built.
#[test]
fn tails_convert_and_come_back_shared() {
    clear();
    let mut s = Store::new();
    let (xs, t) = atoms_list(&mut s, 20);
    let whole = <List<Atom>>::from_term(&s, t).expect("a list");
    assert_eq!(whole.iter().copied().collect::<Vec<_>>(), xs);
    for k in 0..=20 {
        let tk = tail_at(&s, t, k);
        let l = <List<Atom>>::from_term(&s, tk).expect("a tail");
        assert_eq!(l.iter().copied().collect::<Vec<_>>(), xs[k..]);
        if k < 20 {
            assert!(whole.has_tail(&l), "tail {k} shares the storage");
        }
        let cells = s.stats().cells;
        let back = l.to_term(&mut s);
        assert!(s.identical(back, tk));
        if k < 20 {
            assert_eq!(back, tk, "the same cell");
            assert_eq!(s.stats().cells, cells, "no cell built");
        }
    }
    // `[X|Tail]` built natively on a remembered tail: its own cell only,
    // and read back up to the remembered tail.
    let x = Atom::intern("x");
    let tail = <List<Atom>>::from_term(&s, tail_at(&s, t, 5)).unwrap();
    let consed = List::cons(x, tail.clone());
    let cells = s.stats().cells;
    let ct = consed.to_term(&mut s);
    assert_eq!(s.stats().cells, cells + 3);
    let back = <List<Atom>>::from_term(&s, ct).unwrap();
    assert_eq!(back, consed);
    assert!(back.tail().unwrap().same_storage(&tail));
}

/// A slice made a term whole is remembered: the term and its tails read
/// back shared; another store, or the same after a collection, walks.
#[test]
fn made_terms_are_remembered_per_store_and_epoch() {
    clear();
    let mut s = Store::new();
    let l: List<i64> = (0..30).collect();
    let t = l.to_term(&mut s);
    let back = <List<i64>>::from_term(&s, tail_at(&s, t, 3)).unwrap();
    assert!(l.has_tail(&back) && back.len() == 27);
    // After a collection the cells moved, and the entry with them.
    let mut roots = [t];
    s.gc(&mut roots);
    let moved = <List<i64>>::from_term(&s, roots[0]).unwrap();
    assert_eq!(moved, l);
    assert!(moved.same_storage(&l));
    let cells = s.stats().cells;
    assert_eq!(l.to_term(&mut s), roots[0], "the moved cell");
    assert_eq!(s.stats().cells, cells, "no cell built");
    // Only a tail kept by the next collection: that tail stays remembered.
    let mut roots = [tail_at(&s, roots[0], 12)];
    s.gc(&mut roots);
    let tail = <List<i64>>::from_term(&s, roots[0]).unwrap();
    assert_eq!(tail.len(), 18);
    assert!(l.has_tail(&tail));
    assert_eq!(tail.to_term(&mut s), roots[0]);
    // The whole list's cells are gone: made a term again, built anew.
    let again = l.to_term(&mut s);
    assert_eq!(<List<i64>>::from_term(&s, again).unwrap(), l);
    // A clone of the store is another store: it walks (and agrees).
    let c = s.clone();
    let other = <List<i64>>::from_term(&c, again).unwrap();
    assert_eq!(other, l);
    assert!(!other.same_storage(&l));
}

/// A list built a cell at a time on a remembered one, each cell made a
/// term and read back (an accumulator `[S|Seen]` handed to the machine and
/// back at every visit): each step builds its own cell only and shares the
/// rest, both ways; a collection in the middle keeps it so.
#[test]
fn accumulators_convert_a_cell_a_step() {
    clear();
    let mut s = Store::new();
    let base: List<i64> = (0..10).collect();
    let mut seen = base.clone();
    let mut seen_t = seen.to_term(&mut s);
    for k in 0..100i64 {
        // The machine builds `[k|Seen]` on the term it was given.
        let cell = s.cons(Term::int(1000 + k), seen_t);
        let read = <List<i64>>::from_term(&s, cell).unwrap();
        assert_eq!(read.len(), seen.len() + 1);
        assert!(
            read.tail().unwrap().same_storage(&seen),
            "step {k}: tail shared"
        );
        // Handed back: the very cell, none built.
        let cells = s.stats().cells;
        assert_eq!(read.to_term(&mut s), cell, "step {k}");
        assert_eq!(s.stats().cells, cells);
        // Read again: the same list.
        assert!(<List<i64>>::from_term(&s, cell)
            .unwrap()
            .same_storage(&read));
        seen = read;
        seen_t = cell;
        if k == 50 {
            let mut roots = [seen_t];
            s.gc(&mut roots);
            seen_t = roots[0];
            assert!(<List<i64>>::from_term(&s, seen_t)
                .unwrap()
                .same_storage(&seen));
        }
    }
    let want: Vec<i64> = (1000..1100).rev().chain(0..10).collect();
    assert_eq!(seen.iter().copied().collect::<Vec<_>>(), want);
    // Built natively a cell at a time: each cell made a term once.
    let mut l = List::nil();
    let mut t = l.to_term(&mut s);
    for k in 0..50i64 {
        l = List::cons(k, l);
        let cells = s.stats().cells;
        let nt = l.to_term(&mut s);
        assert_eq!(s.stats().cells, cells + 3, "one cell, step {k}");
        assert_eq!(s.args(nt)[1], t);
        assert!(<List<i64>>::from_term(&s, nt).unwrap().same_storage(&l));
        t = nt;
    }
}

/// Lists that share a tail both convert above it only; a cell over a
/// variable bound later converts while bound and is not remembered.
#[test]
fn shared_tails_and_bound_cells() {
    clear();
    let mut s = Store::new();
    let base: List<Atom> = (0..12).map(|i| Atom::intern(&format!("q{i}"))).collect();
    let bt = base.to_term(&mut s);
    let a = s.cons(Term::atom(Atom::intern("a")), bt);
    let b = s.cons(Term::atom(Atom::intern("b")), bt);
    let la = <List<Atom>>::from_term(&s, a).unwrap();
    let lb = <List<Atom>>::from_term(&s, b).unwrap();
    assert!(la.tail().unwrap().same_storage(&base));
    assert!(lb.tail().unwrap().same_storage(&base));
    assert_eq!(la.to_term(&mut s), a);
    assert_eq!(lb.to_term(&mut s), b);
    let v = s.new_var();
    let over = s.cons(Term::atom(Atom::intern("c")), v);
    let m = s.mark();
    assert!(s.bind(v, a));
    let lo = <List<Atom>>::from_term(&s, over).unwrap();
    assert_eq!(lo.len(), 14);
    assert!(lo.tail().unwrap().same_storage(&la));
    s.undo_to(m);
    assert!(<List<Atom>>::from_term(&s, over).is_none());
    // Made a term, that list is built on `a`'s cell (not on `over`).
    let back = lo.to_term(&mut s);
    assert_ne!(back, over);
    assert_eq!(s.args(back)[1], a);
}

/// Lists whose elements hold terms (`Ground`) are not kept across a
/// collection (their terms moved); the others are.
#[test]
fn a_collection_drops_lists_holding_terms() {
    clear();
    let mut s = Store::new();
    let f = Atom::intern("f");
    let ts: Vec<Term> = (0..10).map(|i| s.compound(f, &[Term::int(i)])).collect();
    let t = s.list(&ts);
    let g = <List<crate::native::Ground>>::from_term(&s, t).unwrap();
    assert!(<List<crate::native::Ground>>::from_term(&s, t)
        .unwrap()
        .same_storage(&g));
    let mut roots = [t];
    s.gc(&mut roots);
    let after = <List<crate::native::Ground>>::from_term(&s, roots[0]).unwrap();
    assert!(!after.same_storage(&g));
    let back = after.to_term(&mut s);
    assert!(s.identical(back, roots[0]));
    // The same through a cell above it.
    let cell = s.cons(Term::int(7), roots[0]);
    let v = <List<crate::native::Ground>>::from_term(&s, cell).unwrap();
    assert!(v.tail().unwrap().same_storage(&after));
    let mut roots2 = [cell];
    s.gc(&mut roots2);
    let v2 = <List<crate::native::Ground>>::from_term(&s, roots2[0]).unwrap();
    assert!(!v2.same_storage(&v));
    assert_eq!(v2.len(), 11);
}

/// Only [`CELLS`] cell entries are kept, the oldest dropped; each list
/// still agrees with a walk.
#[test]
fn cells_are_bounded() {
    clear();
    let mut s = Store::new();
    let base: List<i64> = (0..10).collect();
    let mut t = base.to_term(&mut s);
    let mut terms = Vec::new();
    for k in 0..(CELLS as i64 + 20) {
        t = s.cons(Term::int(k), t);
        let _ = <List<i64>>::from_term(&s, t).unwrap();
        terms.push(t);
    }
    MEMO.with(|m| {
        let m = m.borrow();
        let c = &m.as_ref().unwrap().cells;
        assert_eq!(c.by_term.len(), CELLS);
        assert_eq!(c.order.len(), CELLS);
        assert!(c.by_addr.len() <= CELLS);
    });
    for (k, &t) in terms.iter().enumerate().step_by(97) {
        assert_eq!(<List<i64>>::from_term(&s, t).unwrap().len(), 11 + k);
    }
}

/// A list that does not convert is never remembered as one that does:
/// partial, improper, unbound elements, a list built over a bound
/// variable (not known ground), non-inert elements of `ground` lists.
#[test]
fn what_does_not_convert_stays_so() {
    clear();
    let mut s = Store::new();
    let (_, t) = atoms_list(&mut s, 12);
    let v = s.new_var();
    let items: Vec<Term> = (0..12).map(Term::int).collect();
    let partial = s.list_with_tail(&items, v);
    assert!(<List<i64>>::from_term(&s, partial).is_none());
    let improper = s.list_with_tail(&items, Term::atom(Atom::intern("b")));
    assert!(<List<i64>>::from_term(&s, improper).is_none());
    // Bound later: converts, not remembered (a binding can be undone).
    let m = s.mark();
    let over_var = s.list_with_tail(&items, v);
    assert!(s.bind(v, Term::NIL));
    let got = <List<i64>>::from_term(&s, over_var).unwrap();
    assert_eq!(got.len(), 12);
    s.undo_to(m);
    assert!(<List<i64>>::from_term(&s, over_var).is_none());
    // Atoms do not convert to integers, remembered or not.
    assert!(<List<i64>>::from_term(&s, t).is_none());
    assert!(<List<Atom>>::from_term(&s, t).is_some());
    assert!(<List<i64>>::from_term(&s, t).is_none());
    // A `ground` list with an element L evaluates (`get(a, a)`): not a value.
    let a = Term::atom(Atom::intern("a"));
    let sum = s.compound(atoms::GET, &[a, a]);
    let mut ts = items.clone();
    ts.push(sum);
    let evals = s.list(&ts);
    assert!(<Val as Native>::from_term(&s, evals).is_none());
    assert!(<List<Val>>::from_term(&s, evals).is_none());
}

/// `Val`'s conversion of a `ground` list shares a tail too, and agrees
/// with a walk; a nested list converts as before.
#[test]
fn ground_lists_share_their_tails() {
    clear();
    let mut s = Store::new();
    let f = Atom::intern("f");
    let ts: Vec<Term> = (0..16).map(|i| s.compound(f, &[Term::int(i)])).collect();
    let t = s.list(&ts);
    let v = <Val as Native>::from_term(&s, t).unwrap();
    let Val::List(whole) = &v else {
        panic!("a list")
    };
    let t5 = tail_at(&s, t, 5);
    let v5 = <Val as Native>::from_term(&s, t5).unwrap();
    let Val::List(l5) = &v5 else { panic!("a list") };
    assert!(whole.has_tail(l5));
    assert_eq!(Val::from_term(&s, t5, &Ty::Ground), Some(v5.clone()));
    let back = Native::to_term(&v5, &mut s);
    assert_eq!(back, t5);
    // Nested: a list of lists, the inner ones converted by a walk.
    let outer = s.list(&[t, t5]);
    let n = <Val as Native>::from_term(&s, outer).unwrap();
    let Val::List(items) = n else {
        panic!("a list")
    };
    assert_eq!(items.iter().cloned().collect::<Vec<_>>(), [v, v5]);
}

/// Only [`ENTRIES`] entries are kept, the oldest dropped; each still
/// agrees with a walk.
#[test]
fn entries_are_bounded() {
    clear();
    let mut s = Store::new();
    let lists: Vec<(List<i64>, Term)> = (0..(ENTRIES as i64 + 3))
        .map(|j| {
            let l: List<i64> = (0..10).map(|i| i + 100 * j).collect();
            let t = l.to_term(&mut s);
            (l, t)
        })
        .collect();
    MEMO.with(|m| assert_eq!(m.borrow().as_ref().unwrap().slices.len(), ENTRIES));
    for (l, t) in &lists {
        assert_eq!(&<List<i64>>::from_term(&s, *t).unwrap(), l);
    }
}

/// A cell made a term above a list whose elements hold terms is
/// remembered, but not across a collection (those terms moved).
#[test]
fn a_cell_above_terms_is_dropped_by_a_collection() {
    clear();
    let mut s = Store::new();
    let f = Atom::intern("f");
    let ft = s.compound(f, &[Term::int(1)]);
    let tail: List<Val> = List::from_vec(vec![Val::from(ft), Val::Int(2)]);
    let l = List::cons(Val::Int(0), tail);
    let t = l.to_term(&mut s);
    let back = <List<Val>>::from_term(&s, t).unwrap();
    assert!(back.same_storage(&l));
    MEMO.with(|m| {
        let m = m.borrow();
        let c = &m.as_ref().unwrap().cells;
        assert_eq!(c.by_term.len(), 1);
        assert!(c.by_term.values().all(|one| !one.termless));
    });
    let mut roots = [t];
    s.gc(&mut roots);
    MEMO.with(|m| assert!(m.borrow().as_ref().unwrap().cells.by_term.is_empty()));
    let again = <List<Val>>::from_term(&s, roots[0]).unwrap();
    assert!(!again.same_storage(&l));
    assert_eq!(again.len(), 3);
}
