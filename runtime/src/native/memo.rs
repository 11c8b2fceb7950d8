//! Lists converted between terms and native values, remembered both ways
//! (issue 37, helpers `nre24`, `nmemo25`): a native frame handed to the
//! machine and entered again (a situation run from its template, a
//! hand-over, a held call off) gives its lists back as terms and reads
//! them again at the next entry (`nat_entry`: `Cx::param_as`,
//! `Cx::id_parts`). Without this both are a walk of the whole list: a walk
//! of `L` places whose every visit goes through the machine costs O(L²).
//!
//! What is remembered, per thread, for one store at a time:
//! - **slices**: a proper list of at least [`MIN_LEN`] elements held as one
//!   shared slice (`List`'s slice shape, `Rc<[T]>`), beside the store
//!   cells of the term's spine, the `k`-th cell holding element `base + k`.
//!   Made where a list term, ground and inert, is converted whole
//!   (`list_from_term`), and where such a slice is made a term whole
//!   (`list_to_term`). At most [`ENTRIES`].
//! - **cells**: a term's list cell `[H|T]` beside the `List::cons` cell
//!   (`Rc`) it was converted to or made from, both ways. Made for each cell
//!   a conversion builds above a remembered tail (a list built on a
//!   remembered one: `[S|Seen]`, an accumulator, either side). At most
//!   [`CELLS`], the oldest dropped first.
//!
//! Then converting a term that is a remembered cell, or a cell or tail of a
//! remembered slice, is that list, shared: O(1); a term that reaches one
//! after a few cells of its own converts those cells only (and remembers
//! them). Making a term of a remembered `Rc` cell, or of a remembered slice
//! or a tail of it, is that term cell: O(1), no cell built; a list built by
//! [`List::cons`] above one builds (and remembers) its own cells only.
//!
//! Invariant: an entry is valid for one store ([`Store`]'s `id`, a clone
//! has another) at one epoch. Its term cells, ground and inert, are never
//! written again (cells are only appended; a ground list's spine has no
//! variable in it), so the term at an entry's cell is the list it
//! remembers; and the entry's elements are what the conversion of its
//! `kind` gives for that term (an entry made from a term, or from a ground
//! and inert term the elements' `to_term` made, which that conversion reads
//! back to equal values; `Val` elements with a term inside are never
//! remembered from a `to_term`). A collection (`Store::gc`) moves cells and
//! bumps the epoch: it calls [`moved`] with where each cell went, which
//! re-maps the entries of that store whose elements hold no term (ints,
//! floats, atoms, `Val`s without a term: what a collection does not touch)
//! to the cells' new places and the new epoch, keeping the part of a slice
//! whose cells survived (a surviving cell keeps its tail alive, so that
//! part is a tail of the slice) and dropping the rest. So a remembered
//! conversion equals the walk it saves, before and after a collection.
//! Entries of other stores and epochs are dropped as a new one comes.

use super::List;
use crate::hash::AtomKeyMap;
use crate::term::Repr;
use crate::{Store, Term};
use sitlog_syntax::{atoms, Atom};
use std::any::{Any, TypeId};
use std::cell::RefCell;
use std::collections::{HashMap, VecDeque};
use std::rc::Rc;

/// Lists shorter than this are converted by walking them (a walk that
/// short costs about what a look-up does).
pub(crate) const MIN_LEN: usize = 8;

/// Slice entries kept, per thread.
pub(crate) const ENTRIES: usize = 8;

/// Cell entries kept, per thread.
pub(crate) const CELLS: usize = 1 << 12;

/// The conversion of a list of `ground` values read as one `Val`
/// (`Val::from_term` with `Ty::Ground`, no check per element that it is
/// inert): a kind of its own beside `List<Val>`'s (`Native::from_term`).
pub(crate) struct GroundList;

/// Where element `base + k` of an entry's slice is: the spine's `k`-th
/// cell.
enum Spine {
    /// Cells evenly spaced (`store.list` builds them back to front: a
    /// step of -3).
    Stride { c0: u32, step: i64 },
    /// Any other layout: each cell's element index.
    Map(HashMap<u32, u32>),
}

struct Entry {
    store: u64,
    epoch: u32,
    kind: TypeId,
    /// The `Rc<[T]>` of the slice (kept alive by the entry).
    items: Box<dyn Any>,
    /// Its address, for looking a slice up without knowing `T`.
    ptr: usize,
    /// Whether no element holds a term (the entry survives a collection).
    termless: bool,
    base: u32,
    /// The spine's cells, first to last (`cells[k]`: element `base + k`).
    cells: Box<[u32]>,
    spine: Spine,
    /// The least and greatest of `cells`.
    lo: u32,
    hi: u32,
}

impl Entry {
    fn valid(&self, store: &Store) -> bool {
        self.store == store.id.0 && self.epoch == store.epoch
    }

    /// The element index of the spine's cell `c`, if it is one.
    fn index_of(&self, c: u32) -> Option<u32> {
        if c < self.lo || c > self.hi {
            return None;
        }
        let k = match &self.spine {
            Spine::Stride { c0, step } => {
                let d = i64::from(c) - i64::from(*c0);
                if d % step != 0 {
                    return None;
                }
                u32::try_from(d / step).ok()?
            }
            Spine::Map(m) => *m.get(&c)?,
        };
        ((k as usize) < self.cells.len()).then_some(self.base + k)
    }
}

/// A term's list cell and the `List::cons` cell it converts to.
struct One {
    kind: TypeId,
    /// The `Rc<Cell<T>>` (kept alive by the entry).
    cell: Rc<dyn Any>,
    /// Its address.
    addr: usize,
    /// Whether its element holds no term (the entry survives a
    /// collection).
    termless: bool,
}

/// The cell entries of one store at one epoch.
#[derive(Default)]
struct Cells {
    store: u64,
    epoch: u32,
    /// Term cell → its entry.
    by_term: AtomKeyMap<u32, One>,
    /// An `Rc` cell's address → the term cell made of it or converted to
    /// it (an entry of `by_term` with that address).
    by_addr: AtomKeyMap<usize, u32>,
    /// The keys of `by_term`, oldest first (each once).
    order: VecDeque<u32>,
}

impl Cells {
    fn valid(&self, store: &Store) -> bool {
        !self.by_term.is_empty() && self.store == store.id.0 && self.epoch == store.epoch
    }

    fn clear(&mut self) {
        self.by_term.clear();
        self.by_addr.clear();
        self.order.clear();
    }

    fn insert(&mut self, c: u32, one: One) {
        let addr = one.addr;
        match self.by_term.insert(c, one) {
            Some(old) => {
                if old.addr != addr && self.by_addr.get(&old.addr) == Some(&c) {
                    self.by_addr.remove(&old.addr);
                }
            }
            None => {
                self.order.push_back(c);
                if self.order.len() > CELLS {
                    if let Some(gone) = self.order.pop_front() {
                        if let Some(old) = self.by_term.remove(&gone) {
                            if self.by_addr.get(&old.addr) == Some(&gone) {
                                self.by_addr.remove(&old.addr);
                            }
                        }
                    }
                }
            }
        }
        self.by_addr.insert(addr, c);
    }
}

#[derive(Default)]
struct Memo {
    slices: Vec<Entry>,
    cells: Cells,
}

thread_local! {
    static MEMO: RefCell<Option<Memo>> = const { RefCell::new(None) };
}

/// `f` on the memo, `None` if it is in use (a conversion inside a
/// conversion: a miss).
#[inline]
fn with_memo<R>(f: impl FnOnce(&mut Memo) -> Option<R>) -> Option<R> {
    MEMO.with(|m| {
        let mut m = m.try_borrow_mut().ok()?;
        f(m.get_or_insert_with(Memo::default))
    })
}

/// Whether elements of type `T` hold no term: ints, floats, atoms, and
/// `Val`s without one (a collection leaves them as they are).
fn termless<T: 'static>(items: &[T]) -> bool {
    let t = TypeId::of::<T>();
    if t == TypeId::of::<i64>() || t == TypeId::of::<f64>() || t == TypeId::of::<Atom>() {
        return true;
    }
    items.iter().all(|v| {
        (v as &dyn Any)
            .downcast_ref::<super::Val>()
            .is_some_and(|v| !v.holds_terms())
    })
}

/// The cell index of a compound's handle.
#[inline]
fn cell_of(t: Term) -> Option<u32> {
    match t.0 {
        Repr::Struct(c) => Some(c),
        _ => None,
    }
}

/// The ranges of cells of the valid slice entries of `kind` (at most
/// [`ENTRIES`]; `n` of them), and whether cell entries are valid, to test
/// a walk's cells without a look-up.
struct Ranges {
    r: [(u32, u32); ENTRIES],
    n: usize,
    cells: bool,
}

impl Ranges {
    fn of(store: &Store, kind: TypeId) -> Ranges {
        let mut out = Ranges {
            r: [(1, 0); ENTRIES],
            n: 0,
            cells: false,
        };
        with_memo(|m| {
            for e in m.slices.iter().filter(|e| e.kind == kind && e.valid(store)) {
                if out.n < ENTRIES {
                    out.r[out.n] = (e.lo, e.hi);
                    out.n += 1;
                }
            }
            out.cells = m.cells.valid(store);
            Some(())
        });
        out
    }

    #[inline]
    fn may_hold(&self, c: u32) -> bool {
        self.r[..self.n].iter().any(|&(lo, hi)| lo <= c && c <= hi)
    }
}

/// The remembered list of `kind` term cell `c` is, if any, and whether
/// none of its elements holds a term.
fn find<T: 'static>(
    store: &Store,
    kind: TypeId,
    c: u32,
    ranges: &Ranges,
) -> Option<(List<T>, bool)> {
    if !ranges.cells && !ranges.may_hold(c) {
        return None;
    }
    with_memo(|m| {
        if ranges.cells {
            if let Some(one) = m.cells.by_term.get(&c) {
                if one.kind == kind {
                    return List::from_cell_any(&one.cell).map(|l| (l, one.termless));
                }
            }
        }
        if !ranges.may_hold(c) {
            return None;
        }
        m.slices
            .iter()
            .filter(|e| e.kind == kind && e.valid(store))
            .find_map(|e| {
                let i = e.index_of(c)?;
                let items = e.items.downcast_ref::<Rc<[T]>>()?;
                Some((List::from_rc(Rc::clone(items), i), e.termless))
            })
    })
}

/// The term a slice-shaped `list` is, remembered (any kind), if any, and
/// whether none of its elements holds a term.
fn term_of<T: 'static>(store: &Store, list: &List<T>) -> Option<(Term, bool)> {
    let (items, start) = list.slice_parts()?;
    let ptr = Rc::as_ptr(items) as *const T as usize;
    with_memo(|m| {
        m.slices
            .iter()
            .filter(|e| e.ptr == ptr && e.valid(store) && e.items.is::<Rc<[T]>>())
            .find_map(|e| {
                let k = start.checked_sub(e.base)?;
                e.cells
                    .get(k as usize)
                    .map(|&c| (Term(Repr::Struct(c)), e.termless))
            })
    })
}

/// The term cell a cell-shaped list (its cell at `addr`) is, remembered,
/// and whether none of its elements holds a term.
#[inline]
fn term_of_cell(store: &Store, addr: usize) -> Option<(Term, bool)> {
    with_memo(|m| {
        if !m.cells.valid(store) {
            return None;
        }
        let &c = m.cells.by_addr.get(&addr)?;
        let termless = m.cells.by_term.get(&c).is_some_and(|one| one.termless);
        Some((Term(Repr::Struct(c)), termless))
    })
}

/// Remembers that term cell `c` (ground and inert) and `list`'s cell are
/// the same list (`termless`: none of its elements holds a term).
fn remember_cell<T: 'static>(store: &Store, kind: TypeId, c: u32, list: &List<T>, termless: bool) {
    let (Some(cell), Some(addr)) = (list.cell_any(), list.cell_addr()) else {
        return;
    };
    let one = One {
        kind,
        cell,
        addr,
        termless,
    };
    with_memo(|m| {
        let cells = &mut m.cells;
        if cells.store != store.id.0 || cells.epoch != store.epoch {
            cells.clear();
            cells.store = store.id.0;
            cells.epoch = store.epoch;
        }
        cells.insert(c, one);
        Some(())
    });
}

/// The spine layout of `cells`.
fn spine_of(cells: &[u32]) -> Spine {
    let (Some(&first), Some(&second)) = (cells.first(), cells.get(1)) else {
        return Spine::Stride {
            c0: cells.first().copied().unwrap_or(0),
            step: 1,
        };
    };
    let step = i64::from(second) - i64::from(first);
    let even = step != 0
        && cells
            .windows(2)
            .all(|w| i64::from(w[1]) - i64::from(w[0]) == step);
    if even {
        Spine::Stride { c0: first, step }
    } else {
        Spine::Map(
            cells
                .iter()
                .enumerate()
                .map(|(k, &c)| (c, k as u32))
                .collect(),
        )
    }
}

/// Remembers that the spine `cells` holds `items[base..]`.
fn remember<T: 'static>(store: &Store, kind: TypeId, items: &Rc<[T]>, base: u32, cells: Vec<u32>) {
    if cells.len() < 2 {
        return;
    }
    let spine = spine_of(&cells);
    let lo = cells.iter().copied().min().unwrap_or(0);
    let hi = cells.iter().copied().max().unwrap_or(0);
    let entry = Entry {
        store: store.id.0,
        epoch: store.epoch,
        kind,
        items: Box::new(Rc::clone(items)),
        ptr: Rc::as_ptr(items) as *const T as usize,
        termless: termless(&items[base as usize..]),
        base,
        cells: cells.into_boxed_slice(),
        spine,
        lo,
        hi,
    };
    with_memo(|m| {
        m.slices.retain(|e| e.valid(store));
        if m.slices.len() >= ENTRIES {
            m.slices.remove(0);
        }
        m.slices.push(entry);
        Some(())
    });
}

/// A collection of the store `store` at epoch `old` moved its cells (to
/// epoch `new`): a cell `c` at or above `frozen` went to `fwd[c - frozen]`
/// (`u32::MAX`: dropped), one below stayed. Re-maps this store's entries
/// whose elements hold no term; drops the others of that store.
pub(crate) fn moved(store: u64, old: u32, new: u32, frozen: u32, fwd: &[u32]) {
    let to = |c: u32| -> Option<u32> {
        if c < frozen {
            return Some(c);
        }
        let n = *fwd.get((c - frozen) as usize)?;
        (n != u32::MAX).then_some(n)
    };
    with_memo(|m| {
        let mut slices = std::mem::take(&mut m.slices);
        slices.retain_mut(|e| {
            if e.store != store {
                return true;
            }
            if e.epoch != old || !e.termless {
                return false;
            }
            // A cell that survived keeps the cells after it alive: what
            // survives is a tail of the spine.
            let moved: Vec<Option<u32>> = e.cells.iter().map(|&c| to(c)).collect();
            let first = moved.iter().rposition(Option::is_none).map_or(0, |d| d + 1);
            let cells: Vec<u32> = moved[first..].iter().flatten().copied().collect();
            if cells.len() < 2 {
                return false;
            }
            e.base += first as u32;
            e.spine = spine_of(&cells);
            e.lo = cells.iter().copied().min().unwrap_or(0);
            e.hi = cells.iter().copied().max().unwrap_or(0);
            e.cells = cells.into_boxed_slice();
            e.epoch = new;
            true
        });
        m.slices = slices;
        let cells = &mut m.cells;
        if cells.store != store {
            return Some(());
        }
        if cells.epoch != old {
            cells.clear();
            return Some(());
        }
        let by_term = std::mem::take(&mut cells.by_term);
        let order = std::mem::take(&mut cells.order);
        cells.by_addr.clear();
        for c in order {
            let Some(one) = by_term.get(&c) else { continue };
            if !one.termless {
                continue;
            }
            if let Some(n) = to(c) {
                cells.order.push_back(n);
            }
        }
        for (c, one) in by_term {
            if !one.termless {
                continue;
            }
            if let Some(n) = to(c) {
                cells.by_addr.insert(one.addr, n);
                cells.by_term.insert(n, one);
            }
        }
        cells.epoch = new;
        Some(())
    });
}

/// The proper list `t` is, its elements converted by `conv` (`None`: a
/// partial, cyclic or improper list, or an element that does not
/// convert), as a walk would give it: a term remembered for `kind` (or a
/// tail of one) shared at once; else walked, up to a remembered tail;
/// a list walked whole, ground and inert, of [`MIN_LEN`] elements or
/// more, remembered.
pub(crate) fn list_from_term<T: 'static>(
    store: &Store,
    kind: TypeId,
    t: Term,
    mut conv: impl FnMut(Term) -> Option<T>,
) -> Option<List<T>> {
    let t = store.deref(t);
    let ranges = Ranges::of(store, kind);
    // A proper list has at most one cell per three store cells; more steps
    // than that means the spine is cyclic.
    let most = store.cells.len() / 3;
    let mut items = Vec::new();
    // The spine's cells, needed only for a list long enough to remember:
    // the first [`MIN_LEN`] on the stack, the rest (and those) in `cells`
    // once it is that long, so a short list's conversion allocates no
    // second vector.
    let mut first = [0u32; MIN_LEN];
    let mut cells = Vec::new();
    let mut cur = t;
    while let Some(c) = cell_of(cur) {
        if let Some((rest, mut clean)) = find::<T>(store, kind, c, &ranges) {
            // The cells above the remembered tail, remembered too (those
            // ground and inert), each beside the `cons` cell made of it.
            let mut acc = rest;
            for (i, x) in items.into_iter().enumerate().rev() {
                clean = clean && termless(std::slice::from_ref(&x));
                acc = List::cons(x, acc);
                let c = if cells.is_empty() { first[i] } else { cells[i] };
                let ct = Term(Repr::Struct(c));
                if store.known_ground(ct) && store.is_inert(ct) {
                    remember_cell(store, kind, c, &acc, clean);
                }
            }
            return Some(acc);
        }
        let Some(&[head, tail]) = store.compound_args(cur, atoms::DOT, 2) else {
            break;
        };
        if items.len() >= most {
            return None;
        }
        let k = items.len();
        items.push(conv(head)?);
        if k < MIN_LEN {
            first[k] = c;
        } else {
            if k == MIN_LEN {
                cells.extend_from_slice(&first);
            }
            cells.push(c);
        }
        cur = store.deref(tail);
    }
    if cur != Term::NIL {
        return None;
    }
    if items.len() < MIN_LEN || !store.known_ground(t) || !store.is_inert(t) {
        return Some(List::from_vec(items));
    }
    if cells.is_empty() {
        cells.extend_from_slice(&first);
    }
    let items: Rc<[T]> = Rc::from(items);
    remember(store, kind, &items, 0, cells);
    Some(List::from_rc(items, 0))
}

/// The term of `list` as `term` makes each element, as `store.list` of
/// them would build it (the same term, up to which cells): a remembered
/// `cons` cell, or a remembered slice (or a tail of one), is its term
/// cell; a list built by [`List::cons`] above one builds its own cells on
/// that cell and remembers them; a slice made a term whole, ground and
/// inert, of [`MIN_LEN`] elements or more, is remembered for `kind`
/// (`keep`: an element may be remembered, holding no term).
pub(crate) fn list_to_term<T: 'static>(
    store: &mut Store,
    kind: TypeId,
    list: &List<T>,
    term: impl Fn(&T, &mut Store) -> Term,
    keep: impl Fn(&T) -> bool,
) -> Term {
    // The `cons` cells on top up to a remembered one (`hit`), else up to
    // what they end in (`rest`).
    const SHORT: usize = 16;
    let mut buf: [Option<&List<T>>; SHORT] = [None; SHORT];
    let mut more: Vec<&List<T>> = Vec::new();
    let mut prefix = 0usize;
    let mut rest = list;
    let mut hit = None;
    while let Some(addr) = rest.cell_addr() {
        if let Some(t) = term_of_cell(store, addr) {
            hit = Some(t);
            break;
        }
        if prefix < SHORT {
            buf[prefix] = Some(rest);
        } else {
            if prefix == SHORT {
                more.extend(buf.iter().flatten());
            }
            more.push(rest);
        }
        prefix += 1;
        let Some((_, tail)) = rest.cell_parts() else {
            break;
        };
        rest = tail;
    }
    if prefix == 0 {
        if let Some((t, _)) = hit {
            return t;
        }
    }
    let (tail, mut clean) = match hit {
        Some(t) => t,
        None => slice_term(store, kind, rest, &term, &keep),
    };
    // The cells on top, last first, each remembered beside its `cons`
    // cell.
    let mut acc = tail;
    for i in (0..prefix).rev() {
        let cell = if more.is_empty() {
            buf[i]
        } else {
            more.get(i).copied()
        };
        let Some((head, _)) = cell.and_then(List::cell_parts) else {
            continue;
        };
        let h = term(head, store);
        acc = store.cons(h, acc);
        clean = clean && termless(std::slice::from_ref(head));
        if let Some(c) = cell_of(acc) {
            if keep(head) && store.known_ground(acc) && store.is_inert(acc) {
                if let Some(cell) = cell {
                    remember_cell(store, kind, c, cell, clean);
                }
            }
        }
    }
    acc
}

/// The term of a slice-shaped list or `[]`: remembered, else built (and
/// remembered if long enough, ground and inert); and whether none of its
/// elements holds a term.
fn slice_term<T: 'static>(
    store: &mut Store,
    kind: TypeId,
    list: &List<T>,
    term: &impl Fn(&T, &mut Store) -> Term,
    keep: &impl Fn(&T) -> bool,
) -> (Term, bool) {
    if let Some(found) = term_of(store, list) {
        return found;
    }
    let clean = list
        .slice_parts()
        .is_none_or(|(items, start)| termless(&items[start as usize..]));
    let t = super::val::list_term(store, list.iter(), list.len(), term);
    if list.len() >= MIN_LEN && store.known_ground(t) && store.is_inert(t) {
        if let Some((items, start)) = list.slice_parts() {
            if items[start as usize..].iter().all(keep) {
                let cells: Vec<u32> = spine_cells(store, t);
                let items = Rc::clone(items);
                remember(store, kind, &items, start, cells);
            }
        }
    }
    (t, clean)
}

/// The cells of a proper list's spine, first to last.
fn spine_cells(store: &Store, t: Term) -> Vec<u32> {
    let mut out = Vec::new();
    let mut cur = store.deref(t);
    while let Some(c) = cell_of(cur) {
        let Some(&[_, tail]) = store.compound_args(cur, atoms::DOT, 2) else {
            break;
        };
        out.push(c);
        cur = store.deref(tail);
    }
    out
}

/// Forgets every entry (tests).
#[cfg(test)]
pub(crate) fn clear() {
    MEMO.with(|m| *m.borrow_mut() = None);
}

#[cfg(test)]
mod tests;
