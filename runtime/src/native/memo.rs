//! Lists converted between terms and native values, remembered both ways
//! (issue 37, helper `nre24`): a native frame handed to the machine and
//! entered again (a situation run from its template, a hand-over, a held
//! call off) gives its lists back as terms and reads them again at the
//! next entry (`nat_entry`: `Cx::param_as`, `Cx::id_parts`). Without this
//! both are a walk of the whole list: a walk of `L` places whose every
//! visit goes through the machine costs O(L²).
//!
//! What is remembered: a proper list of at least [`MIN_LEN`] elements
//! held as one shared slice (`List`'s slice shape, `Rc<[T]>`), beside the
//! store cells of the term's spine, the `k`-th cell holding element
//! `base + k`. Made where a list term, ground and inert, is converted whole
//! (`list_from_term`), and where such a slice is made a term whole
//! (`list_to_term`). Then:
//! - converting a term that is one of those cells (the list or a tail of
//!   it) is the slice from that element on, shared: O(1); a term that
//!   reaches one after a few cells of its own (`[X|Seen]` built on it)
//!   converts those cells only;
//! - making a term of the slice or of a tail of it is that cell: O(1), no
//!   cell built; a list built by [`List::cons`] on top of one builds its own
//!   cells only.
//!
//! Invariant: an entry is valid for one store ([`Store`]'s `id`, a clone
//! has another) at one epoch (a collection moves cells and bumps it): its
//! spine's cells are never written again until then (cells are only
//! appended; a ground list's spine has no variable in it), so the term at
//! an entry's cell is the list it remembers; and the entry's elements are
//! what the conversion of its `kind` gives for that term (an entry made
//! from a term, or from a ground and inert term the elements' `to_term`
//! made, which that conversion reads back to equal values; `Val` elements
//! with a term inside are never remembered). So a remembered conversion
//! equals the walk it saves. At most [`ENTRIES`] entries, the oldest
//! dropped first; entries of other stores and epochs are dropped as a new
//! one comes.

use super::List;
use crate::term::Repr;
use crate::{Store, Term};
use sitlog_syntax::atoms;
use std::any::{Any, TypeId};
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

/// Lists shorter than this are converted by walking them (a walk that
/// short costs about what a look-up does).
pub(crate) const MIN_LEN: usize = 8;

/// Entries kept, per thread.
pub(crate) const ENTRIES: usize = 8;

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

thread_local! {
    static MEMO: RefCell<Vec<Entry>> = const { RefCell::new(Vec::new()) };
}

/// The cell index of a compound's handle.
#[inline]
fn cell_of(t: Term) -> Option<u32> {
    match t.0 {
        Repr::Struct(c) => Some(c),
        _ => None,
    }
}

/// The ranges of cells of the valid entries of `kind` (at most
/// [`ENTRIES`]; `n` of them), to test a walk's cells without a look-up.
struct Ranges {
    r: [(u32, u32); ENTRIES],
    n: usize,
}

impl Ranges {
    fn of(store: &Store, kind: TypeId) -> Ranges {
        let mut out = Ranges {
            r: [(1, 0); ENTRIES],
            n: 0,
        };
        MEMO.with(|m| {
            if let Ok(m) = m.try_borrow() {
                for e in m.iter().filter(|e| e.kind == kind && e.valid(store)) {
                    if out.n < ENTRIES {
                        out.r[out.n] = (e.lo, e.hi);
                        out.n += 1;
                    }
                }
            }
        });
        out
    }

    #[inline]
    fn may_hold(&self, c: u32) -> bool {
        self.r[..self.n].iter().any(|&(lo, hi)| lo <= c && c <= hi)
    }
}

/// The remembered list of `kind` term `t` (dereferenced) is, if any.
fn find<T: 'static>(store: &Store, kind: TypeId, t: Term) -> Option<List<T>> {
    let c = cell_of(t)?;
    MEMO.with(|m| {
        let m = m.try_borrow().ok()?;
        m.iter()
            .filter(|e| e.kind == kind && e.valid(store))
            .find_map(|e| {
                let i = e.index_of(c)?;
                let items = e.items.downcast_ref::<Rc<[T]>>()?;
                Some(List::from_rc(Rc::clone(items), i))
            })
    })
}

/// The term a slice-shaped `list` is, remembered (any kind), if any.
fn term_of<T: 'static>(store: &Store, list: &List<T>) -> Option<Term> {
    let (items, start) = list.slice_parts()?;
    let ptr = Rc::as_ptr(items) as *const T as usize;
    MEMO.with(|m| {
        let m = m.try_borrow().ok()?;
        m.iter()
            .filter(|e| e.ptr == ptr && e.valid(store) && e.items.is::<Rc<[T]>>())
            .find_map(|e| {
                let k = start.checked_sub(e.base)?;
                e.cells.get(k as usize).map(|&c| Term(Repr::Struct(c)))
            })
    })
}

/// Remembers that the spine `cells` holds `items[base..]`.
fn remember<T: 'static>(store: &Store, kind: TypeId, items: &Rc<[T]>, base: u32, cells: Vec<u32>) {
    let (Some(&first), Some(&second)) = (cells.first(), cells.get(1)) else {
        return;
    };
    let step = i64::from(second) - i64::from(first);
    let even = step != 0
        && cells
            .windows(2)
            .all(|w| i64::from(w[1]) - i64::from(w[0]) == step);
    let spine = if even {
        Spine::Stride { c0: first, step }
    } else {
        Spine::Map(
            cells
                .iter()
                .enumerate()
                .map(|(k, &c)| (c, k as u32))
                .collect(),
        )
    };
    let lo = cells.iter().copied().min().unwrap_or(0);
    let hi = cells.iter().copied().max().unwrap_or(0);
    let entry = Entry {
        store: store.id.0,
        epoch: store.epoch,
        kind,
        items: Box::new(Rc::clone(items)),
        ptr: Rc::as_ptr(items) as *const T as usize,
        base,
        cells: cells.into_boxed_slice(),
        spine,
        lo,
        hi,
    };
    MEMO.with(|m| {
        if let Ok(mut m) = m.try_borrow_mut() {
            m.retain(|e| e.valid(store));
            if m.len() >= ENTRIES {
                m.remove(0);
            }
            m.push(entry);
        }
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
        if ranges.may_hold(c) {
            if let Some(rest) = find::<T>(store, kind, cur) {
                return Some(
                    items
                        .into_iter()
                        .rev()
                        .fold(rest, |acc, x| List::cons(x, acc)),
                );
            }
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
/// them would build it (the same term, up to which cells): a slice
/// remembered (or a tail of one) is its cell; a list built by
/// [`List::cons`] on one builds its own cells on that cell; a slice made a
/// term whole, ground and inert, of [`MIN_LEN`] elements or more, is
/// remembered for `kind` (`keep`: its elements may be remembered, none
/// holding a term).
pub(crate) fn list_to_term<T: 'static>(
    store: &mut Store,
    kind: TypeId,
    list: &List<T>,
    term: impl Fn(&T, &mut Store) -> Term,
    keep: impl Fn(&T) -> bool,
) -> Term {
    // The cells built by `cons` on top, then what they end in.
    let mut prefix = 0usize;
    let mut rest = list;
    while let Some((_, tail)) = rest.cell_parts() {
        prefix += 1;
        rest = tail;
    }
    if let Some(tail) = term_of(store, rest) {
        return cons_on(store, list, prefix, tail, &term);
    }
    let t = super::val::list_term(store, list.iter(), list.len(), &term);
    if prefix == 0 && list.len() >= MIN_LEN && store.known_ground(t) && store.is_inert(t) {
        if let Some((items, start)) = list.slice_parts() {
            if items[start as usize..].iter().all(&keep) {
                let cells: Vec<u32> = spine_cells(store, t);
                let items = Rc::clone(items);
                remember(store, kind, &items, start, cells);
            }
        }
    }
    t
}

/// `prefix` elements of `list` made terms, then their cells on `tail`.
fn cons_on<T>(
    store: &mut Store,
    list: &List<T>,
    prefix: usize,
    tail: Term,
    term: &impl Fn(&T, &mut Store) -> Term,
) -> Term {
    const SHORT: usize = 16;
    let heads = list.iter().take(prefix);
    if prefix <= SHORT {
        let mut buf = [Term::NIL; SHORT];
        for (slot, v) in buf.iter_mut().zip(heads) {
            *slot = term(v, store);
        }
        store.list_with_tail(&buf[..prefix], tail)
    } else {
        let ts: Vec<Term> = heads.map(|v| term(v, store)).collect();
        store.list_with_tail(&ts, tail)
    }
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
    MEMO.with(|m| m.borrow_mut().clear());
}

#[cfg(test)]
mod tests;
