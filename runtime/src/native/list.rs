//! [`List<T>`]: the persistent list native code holds for a SitLog list
//! (`docs/design/typed-mir.md`): shared, never copied on a visit.
//!
//! Two shapes behind one type. A list that arrives whole (a constant, a
//! term converted at a boundary, `collect`) is one `Rc<[T]>` and a start
//! index: its tail is the same allocation one index further. A list built
//! by `[X|Xs]` ([`List::cons`]) is a chain of `Rc` cells that may end in such
//! a slice. So `split_first`, `first`, `tail`, `cons`, `len` and `clone`
//! take constant time, and a tail never allocates nor copies an element;
//! `advance` makes a list its own tail in place (a cursor: a slice's start
//! index moved, no `Rc` count touched).
//!
//! Invariant: a slice shape is never empty (`start < items.len()`; the
//! empty list is `Nil`, which allocates nothing), a cell's `len` is its
//! list's length, and dropping a chain of cells of any length takes
//! constant stack (the cells' own module, [`cells`], frees a chain in a
//! loop, each block kept by a per-thread pool for the next `cons`).

mod cells;

use cells::{CellRef, Node};
use std::fmt;
use std::rc::Rc;

/// A persistent list of `T`; see the module documentation. `clone` shares.
pub struct List<T>(Shape<T>);

enum Shape<T> {
    Nil,
    /// `items[start..]`, never empty.
    Slice {
        items: Rc<[T]>,
        start: u32,
    },
    Cons(CellRef<T>),
}

impl<T> List<T> {
    /// The empty list (no allocation).
    pub const fn nil() -> List<T> {
        List(Shape::Nil)
    }

    /// The list of `items`, in one allocation.
    ///
    /// # Panics
    /// With 2³² elements or more (the term store itself has fewer cells).
    pub fn from_vec(items: Vec<T>) -> List<T> {
        if items.is_empty() {
            return List::nil();
        }
        assert!(
            u32::try_from(items.len()).is_ok(),
            "native list exceeds 2^32 elements"
        );
        List(Shape::Slice {
            items: Rc::from(items),
            start: 0,
        })
    }

    /// The list of `items`, cloned into one allocation.
    pub fn from_slice(items: &[T]) -> List<T>
    where
        T: Clone,
    {
        List::from_vec(items.to_vec())
    }

    /// `[head|tail]`: one cell, `tail` shared.
    pub fn cons(head: T, tail: List<T>) -> List<T> {
        let len = tail.len() + 1;
        List(Shape::Cons(CellRef::new(head, tail, len)))
    }

    /// Whether this is `[]`.
    pub fn is_empty(&self) -> bool {
        matches!(self.0, Shape::Nil)
    }

    /// The number of elements (constant time).
    pub fn len(&self) -> usize {
        match &self.0 {
            Shape::Nil => 0,
            Shape::Slice { items, start } => items.len() - *start as usize,
            Shape::Cons(cell) => cell.len,
        }
    }

    /// The first element.
    pub fn first(&self) -> Option<&T> {
        match &self.0 {
            Shape::Nil => None,
            Shape::Slice { items, start } => items.get(*start as usize),
            Shape::Cons(cell) => Some(&cell.head),
        }
    }

    /// The first element and the rest, which shares this list's storage
    /// (constant time, no allocation, no element copied): what selecting
    /// `try([P|Ps])` does.
    #[inline]
    pub fn split_first(&self) -> Option<(&T, List<T>)> {
        match &self.0 {
            Shape::Nil => None,
            Shape::Slice { items, start } => Some(slice_split(items, *start)),
            Shape::Cons(cell) => Some((&cell.head, cell.tail.clone())),
        }
    }

    /// [`List::split_first`] of a list its holder keeps non-empty: a
    /// situation's variant that holds the list `[P|Ps]` its id's pattern
    /// takes apart, `P` read in place and `Ps` made at each visit
    /// (`codegen::native`'s cell fields).
    ///
    /// # Panics
    /// On `[]` (the holder's invariant broken).
    #[inline(always)]
    pub fn head_tail(&self) -> (&T, List<T>) {
        match &self.0 {
            Shape::Slice { items, start } => slice_split(items, *start),
            Shape::Cons(cell) => (&cell.head, cell.tail.clone()),
            Shape::Nil => empty_cell(),
        }
    }

    /// The first element of a list its holder keeps non-empty (a cell
    /// field, as [`List::head_tail`]), read in place.
    ///
    /// # Panics
    /// On `[]` (the holder's invariant broken).
    #[inline(always)]
    pub fn head(&self) -> &T {
        match &self.0 {
            Shape::Slice { items, start } => &items[*start as usize],
            Shape::Cons(cell) => &cell.head,
            Shape::Nil => empty_cell(),
        }
    }

    /// Makes this list its own tail, in place: a cursor moved one element
    /// on. A list that arrived whole moves its start index (no `Rc` count
    /// touched, no value moved; at its end it becomes `[]`, its storage let
    /// go); a cell is replaced by its tail (shared). `[]` stays `[]`. What
    /// a visit of `try([P|Ps])` going on to `try(Ps)` does to the list its
    /// situation holds (`codegen::native`'s cell fields).
    #[inline(always)]
    pub fn advance(&mut self) {
        match &mut self.0 {
            Shape::Slice { items, start } => {
                if (*start as usize) + 1 < items.len() {
                    *start += 1;
                } else {
                    self.0 = Shape::Nil;
                }
            }
            Shape::Cons(cell) => {
                let tail = cell.tail.clone();
                *self = tail;
            }
            Shape::Nil => {}
        }
    }

    /// The list without its first element (shared), `None` for `[]`.
    pub fn tail(&self) -> Option<List<T>> {
        self.split_first().map(|(_, rest)| rest)
    }

    /// The elements, first to last.
    pub fn iter(&self) -> Iter<'_, T> {
        let mut it = Iter {
            cell: None,
            slice: [].iter(),
            left: self.len(),
        };
        it.enter(self);
        it
    }

    /// Whether `other` is this list or one of its tails, decided without a
    /// walk: a list that arrived whole and a part of it from the same start
    /// on, or the very same cell; `false` otherwise (also for `[]`, and
    /// for a tail that a walk along a chain of cells would find).
    pub fn has_tail(&self, other: &List<T>) -> bool {
        match (&self.0, &other.0) {
            (Shape::Slice { items: a, start: i }, Shape::Slice { items: b, start: j }) => {
                j >= i && Rc::ptr_eq(a, b)
            }
            (Shape::Cons(a), Shape::Cons(b)) => CellRef::ptr_eq(a, b),
            _ => false,
        }
    }

    /// Whether both lists are the very same storage (then they are equal
    /// without a walk): a tail shares its list's storage this way.
    pub fn same_storage(&self, other: &List<T>) -> bool {
        match (&self.0, &other.0) {
            (Shape::Nil, Shape::Nil) => true,
            (Shape::Slice { items: a, start: i }, Shape::Slice { items: b, start: j }) => {
                i == j && Rc::ptr_eq(a, b)
            }
            (Shape::Cons(a), Shape::Cons(b)) => CellRef::ptr_eq(a, b),
            _ => false,
        }
    }
}

impl<T> List<T> {
    /// The storage and start index of a list that arrived whole (the slice
    /// shape): what `native::memo` remembers a term for.
    #[inline]
    pub(crate) fn slice_parts(&self) -> Option<(&Rc<[T]>, u32)> {
        match &self.0 {
            Shape::Slice { items, start } => Some((items, *start)),
            _ => None,
        }
    }

    /// `items[start..]` sharing `items` (`[]` from its end on): a tail of a
    /// list `native::memo` remembers.
    #[inline]
    pub(crate) fn from_rc(items: Rc<[T]>, start: u32) -> List<T> {
        if (start as usize) < items.len() {
            List(Shape::Slice { items, start })
        } else {
            List::nil()
        }
    }

    /// The head and tail of a list built by [`List::cons`] (the cell
    /// shape), `None` for the others.
    #[inline]
    pub(crate) fn cell_parts(&self) -> Option<(&T, &List<T>)> {
        match &self.0 {
            Shape::Cons(cell) => Some((&cell.head, &cell.tail)),
            _ => None,
        }
    }

    /// The address of a cell-shaped list's cell (`native::memo`'s key for
    /// it), `None` for the others.
    #[inline]
    pub(crate) fn cell_addr(&self) -> Option<usize> {
        match &self.0 {
            Shape::Cons(cell) => Some(cell.addr()),
            _ => None,
        }
    }
}

impl<T: 'static> List<T> {
    /// A cell-shaped list's cell, shared, as `native::memo` keeps it.
    pub(crate) fn cell_any(&self) -> Option<Rc<dyn std::any::Any>> {
        match &self.0 {
            // The list itself, behind a type-erased `Rc`: it holds the
            // cell (one more holder), so the cell's address stays its own.
            Shape::Cons(_) => Some(Rc::new(self.clone()) as Rc<dyn std::any::Any>),
            _ => None,
        }
    }

    /// The list a cell [`List::cell_any`] gave starts (shared), `None` if
    /// it is a cell of another element type.
    pub(crate) fn from_cell_any(cell: &Rc<dyn std::any::Any>) -> Option<List<T>> {
        cell.downcast_ref::<List<T>>().cloned()
    }
}

/// The element at `start` of a shared slice and the rest after it (the
/// same storage, `[]` at its end): [`List::split_first`] and
/// [`List::head_tail`] of a slice list.
#[inline(always)]
fn slice_split<T>(items: &Rc<[T]>, start: u32) -> (&T, List<T>) {
    let i = start as usize;
    let rest = if i + 1 < items.len() {
        List(Shape::Slice {
            items: Rc::clone(items),
            start: start + 1,
        })
    } else {
        List::nil()
    };
    (&items[i], rest)
}

/// [`List::head_tail`] of `[]`: a holder's invariant broken.
#[cold]
#[inline(never)]
fn empty_cell() -> ! {
    unreachable!("a cell field holds a non-empty list")
}

impl<T> Clone for List<T> {
    fn clone(&self) -> List<T> {
        List(match &self.0 {
            Shape::Nil => Shape::Nil,
            Shape::Slice { items, start } => Shape::Slice {
                items: Rc::clone(items),
                start: *start,
            },
            Shape::Cons(cell) => Shape::Cons(cell.clone()),
        })
    }
}

impl<T> Default for List<T> {
    fn default() -> List<T> {
        List::nil()
    }
}

impl<T: PartialEq> PartialEq for List<T> {
    fn eq(&self, other: &List<T>) -> bool {
        self.same_storage(other)
            || (self.len() == other.len() && self.iter().zip(other.iter()).all(|(a, b)| a == b))
    }
}

impl<T: Eq> Eq for List<T> {}

impl<T: fmt::Debug> fmt::Debug for List<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl<T> FromIterator<T> for List<T> {
    fn from_iter<I: IntoIterator<Item = T>>(iter: I) -> List<T> {
        List::from_vec(iter.into_iter().collect())
    }
}

impl<T> From<Vec<T>> for List<T> {
    fn from(items: Vec<T>) -> List<T> {
        List::from_vec(items)
    }
}

impl<'a, T> IntoIterator for &'a List<T> {
    type Item = &'a T;
    type IntoIter = Iter<'a, T>;
    fn into_iter(self) -> Iter<'a, T> {
        self.iter()
    }
}

/// Iterator over a [`List`]'s elements: the chain of cells first, then the
/// slice it ends in.
pub struct Iter<'a, T> {
    cell: Option<&'a Node<T>>,
    slice: std::slice::Iter<'a, T>,
    left: usize,
}

impl<'a, T> Iter<'a, T> {
    fn enter(&mut self, list: &'a List<T>) {
        match &list.0 {
            Shape::Nil => {}
            Shape::Slice { items, start } => self.slice = items[*start as usize..].iter(),
            Shape::Cons(cell) => self.cell = Some(&**cell),
        }
    }
}

impl<'a, T> Iterator for Iter<'a, T> {
    type Item = &'a T;
    fn next(&mut self) -> Option<&'a T> {
        let item = match self.cell.take() {
            Some(cell) => {
                self.enter(&cell.tail);
                Some(&cell.head)
            }
            None => self.slice.next(),
        };
        if item.is_some() {
            self.left -= 1;
        }
        item
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl<T> ExactSizeIterator for Iter<'_, T> {}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell as Counter;

    /// Counts its clones, to check that walking copies no element.
    struct Counted(i64, Rc<Counter<usize>>);

    impl Clone for Counted {
        fn clone(&self) -> Counted {
            self.1.set(self.1.get() + 1);
            Counted(self.0, Rc::clone(&self.1))
        }
    }

    #[test]
    fn shapes_agree() {
        let whole = List::from_slice(&[1, 2, 3]);
        let built = List::cons(1, List::cons(2, List::cons(3, List::nil())));
        let mixed = List::cons(1, List::from_vec(vec![2, 3]));
        for l in [&whole, &built, &mixed] {
            assert_eq!(l.len(), 3);
            assert_eq!(l.iter().copied().collect::<Vec<_>>(), [1, 2, 3]);
            assert_eq!(l.iter().len(), 3);
            assert_eq!(l.first(), Some(&1));
            assert_eq!(*l, whole);
            let (h, t) = l.split_first().unwrap();
            assert_eq!((*h, t.len()), (1, 2));
            let (h2, t2) = l.head_tail();
            assert_eq!((*h2, &t2), (*h, &t));
            assert_eq!(t.tail().unwrap().tail().unwrap(), List::nil());
        }
        assert_ne!(whole, List::from_slice(&[1, 2]));
        assert_ne!(whole, List::from_slice(&[1, 2, 4]));
        assert!(List::<i32>::from_vec(vec![]).is_empty());
        assert_eq!(List::<i32>::nil().split_first().map(|(h, _)| *h), None);
        assert_eq!(format!("{mixed:?}"), "[1, 2, 3]");
        let collected: List<i32> = (1..=3).collect();
        assert_eq!(collected, built);
    }

    #[test]
    fn a_tail_shares_its_list() {
        let l = List::from_slice(&[1, 2, 3]);
        let t = l.tail().unwrap();
        assert!(t.same_storage(&l.tail().unwrap()));
        assert!(!t.same_storage(&l));
        let c = List::cons(0, l.clone());
        assert!(c.tail().unwrap().same_storage(&l));
    }

    /// `split_first` walks a list in O(n) in total: every step copies no
    /// element and allocates nothing, counted rather than timed.
    #[test]
    fn walking_copies_nothing() {
        const N: usize = 100_000;
        let clones = Rc::new(Counter::new(0));
        let items: Vec<Counted> = (0..N as i64)
            .map(|i| Counted(i, Rc::clone(&clones)))
            .collect();
        let whole = List::from_vec(items);
        let mut built = List::nil();
        for i in (0..N as i64).rev() {
            built = List::cons(Counted(i, Rc::clone(&clones)), built);
        }
        // Half built by cons on top of half that arrived whole.
        let mut mixed = whole.clone();
        for _ in 0..N / 2 {
            mixed = mixed.tail().unwrap();
        }
        for i in (0..(N / 2) as i64).rev() {
            mixed = List::cons(Counted(i, Rc::clone(&clones)), mixed);
        }
        for list in [whole, built, mixed] {
            let mut steps = 0;
            let mut sum = 0;
            let mut cur = list.clone();
            while let Some((head, rest)) = cur.split_first() {
                sum += head.0;
                assert_eq!(rest.len(), N - steps - 1);
                cur = rest;
                steps += 1;
            }
            assert_eq!(steps, N);
            assert_eq!(sum, (N as i64 - 1) * N as i64 / 2);
            assert_eq!(list.iter().count(), N);
        }
        assert_eq!(clones.get(), 0, "a walk copied elements");
    }

    #[test]
    fn a_long_chain_drops_in_constant_stack() {
        let mut l = List::nil();
        for i in 0..1_000_000 {
            l = List::cons(i, l);
        }
        let shared = l.tail().unwrap();
        drop(l);
        assert_eq!(shared.len(), 999_999);
        drop(shared);
    }

    proptest::proptest! {
        /// Any mix of shapes behaves as the vector it holds.
        #[test]
        fn behaves_as_a_vector(
            items in proptest::collection::vec(0i32..5, 0..12),
            cells in 0usize..13,
            drop_first in 0usize..13,
        ) {
            let cells = cells.min(items.len());
            let mut list = List::from_slice(&items[cells..]);
            for &x in items[..cells].iter().rev() {
                list = List::cons(x, list);
            }
            let whole = List::from_slice(&items);
            proptest::prop_assert_eq!(list.len(), items.len());
            proptest::prop_assert_eq!(list.iter().copied().collect::<Vec<_>>(), items.clone());
            proptest::prop_assert_eq!(&list, &whole);
            proptest::prop_assert_eq!(list.first(), items.first());
            let mut rest = list.clone();
            for _ in 0..drop_first.min(items.len()) {
                rest = rest.tail().unwrap();
            }
            let model = &items[drop_first.min(items.len())..];
            proptest::prop_assert_eq!(rest.len(), model.len());
            proptest::prop_assert_eq!(rest.iter().len(), model.len());
            proptest::prop_assert!(rest.iter().eq(model.iter()));
            proptest::prop_assert_eq!(rest == whole, model.len() == items.len());
            // A cursor moved as far, in place, is that rest; past the end, `[]`.
            let mut cursor = list.clone();
            for _ in 0..drop_first {
                if !cursor.is_empty() {
                    proptest::prop_assert_eq!(Some(cursor.head()), cursor.first());
                }
                cursor.advance();
            }
            proptest::prop_assert_eq!(&cursor, &rest);
            proptest::prop_assert_eq!(cursor.len(), model.len());
        }
    }

    #[test]
    fn small() {
        assert_eq!(std::mem::size_of::<List<u64>>(), 24);
    }
}
