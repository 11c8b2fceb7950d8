//! The cells' counts and the pool: every element dropped once, whatever
//! the order lists sharing cells are let go in; long chains freed in a
//! loop; blocks reused.

use super::super::List;
use proptest::prelude::*;
use std::cell::Cell as Counter;
use std::rc::Rc;

/// Counts its drops.
struct Dropped(Rc<Counter<usize>>);

impl Drop for Dropped {
    fn drop(&mut self) {
        self.0.set(self.0.get() + 1);
    }
}

fn cell_of<T>(l: &List<T>) -> &super::CellRef<T> {
    match &l.0 {
        super::Shape::Cons(c) => c,
        _ => panic!("not a cell"),
    }
}

#[test]
fn counts_follow_holders() {
    let drops = Rc::new(Counter::new(0));
    let a = List::cons(Dropped(drops.clone()), List::nil());
    let b = List::cons(Dropped(drops.clone()), a.clone());
    let c = List::cons(Dropped(drops.clone()), a.clone());
    assert_eq!(cell_of(&a).holders(), 3);
    drop(a);
    assert_eq!(
        cell_of(&b.tail().unwrap()).holders(),
        3,
        "a tail is a holder"
    );
    drop(b);
    assert_eq!(drops.get(), 1);
    drop(c);
    assert_eq!(drops.get(), 3);
}

/// A chain of 10^6 cells, each element a list itself, dropped from its
/// first cell and from a shared tail: no recursion along the chain, every
/// element dropped once.
#[test]
fn a_million_cells_drop_in_a_loop() {
    let drops = Rc::new(Counter::new(0));
    let mut l = List::nil();
    for _ in 0..1_000_000 {
        l = List::cons(List::cons(Dropped(drops.clone()), List::nil()), l);
    }
    let mut half = l.clone();
    for _ in 0..500_000 {
        half.advance();
    }
    drop(l);
    assert_eq!(drops.get(), 500_000);
    assert_eq!(half.len(), 500_000);
    drop(half);
    assert_eq!(drops.get(), 1_000_000);
}

/// Run on a thread of its own, with a small stack: a recursion along the
/// chain would overflow it.
#[test]
fn a_long_chain_drops_on_a_small_stack() {
    std::thread::Builder::new()
        .stack_size(64 * 1024)
        .spawn(|| {
            let mut l = List::nil();
            for i in 0..1_000_000u64 {
                l = List::cons(i, l);
            }
            assert_eq!(l.len(), 1_000_000);
            drop(l);
        })
        .expect("a thread")
        .join()
        .expect("no overflow");
}

#[test]
fn freed_blocks_are_reused_and_a_slice_tail_is_kept() {
    let base = List::from_vec(vec![7u64, 8, 9]);
    for round in 0..3u64 {
        let mut l = base.clone();
        for i in 0..2_000 {
            l = List::cons(i + round, l);
        }
        assert_eq!(l.len(), 2_003);
        assert_eq!(l.iter().copied().skip(2_000).collect::<Vec<_>>(), [7, 8, 9]);
    }
    assert_eq!(base.iter().copied().collect::<Vec<_>>(), [7, 8, 9]);
}

/// A type too big for the pool's classes: the allocator's own blocks.
#[test]
fn big_elements_bypass_the_pool() {
    let mut l = List::nil();
    for i in 0..100u64 {
        l = List::cons([i; 40], l);
    }
    assert_eq!(l.iter().map(|a| a[0]).sum::<u64>(), 4950);
}

proptest! {
    /// Lists built on each other's cells, then dropped in any order: each
    /// element is dropped exactly once, after its last holder.
    #[test]
    fn shared_lists_drop_in_any_order(
        build in proptest::collection::vec((0usize..8, any::<bool>()), 1..40),
        order in proptest::collection::vec(any::<proptest::sample::Index>(), 40),
    ) {
        let drops = Rc::new(Counter::new(0));
        let mut lists: Vec<List<Dropped>> = vec![List::nil()];
        for &(on, advance) in &build {
            let mut base = lists[on % lists.len()].clone();
            if advance {
                base.advance();
            }
            lists.push(List::cons(Dropped(drops.clone()), base));
        }
        let made = build.len();
        let mut order = order.into_iter();
        while !lists.is_empty() {
            let k = order.next().map_or(0, |i| i.index(lists.len()));
            drop(lists.swap_remove(k));
            prop_assert!(drops.get() <= made);
        }
        prop_assert_eq!(drops.get(), made);
    }
}
