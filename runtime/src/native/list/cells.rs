//! The cells of a list built by `[X|Xs]` ([`List::cons`]): each a count
//! of its holders beside the cell, in a block that a per-thread pool keeps
//! once freed and hands out again (issue 37: a walk that builds a list
//! cell by cell and lets it go at the end of each round, `step(Is,
//! [I|Passed])`, paid the allocator twice a cell, and `free` of a round's
//! cells overflowed its own per-thread cache).
//!
//! Invariants:
//! - A [`CellRef`] points at a live node whose count is the number of
//!   `CellRef`s to it; the node is dropped and its block released exactly
//!   when that count reaches 0.
//! - Releasing a chain of nodes whose counts reach 0 one after another is
//!   a loop ([`free_chain`]): constant stack for a list of any length (its
//!   elements drop as usual, their own nesting bounded by their type's).
//! - A block of the pool has the size and alignment of its class
//!   ([`layout_of`]) whether it came from the pool or the allocator, so a
//!   block goes back to either; the pool keeps at most [`KEEP`] blocks a
//!   class and frees them when its thread ends. A `CellRef` is neither
//!   `Send` nor `Sync` (as `Rc`): a block is released on the thread whose
//!   pool it may have come from.

use super::{List, Shape};
use std::alloc::{alloc, dealloc, handle_alloc_error, Layout};
use std::cell::Cell;
use std::marker::PhantomData;
use std::mem::ManuallyDrop;
use std::ptr::{self, NonNull};

/// A cell and the number of its holders.
pub(super) struct Node<T> {
    count: Cell<usize>,
    pub(super) head: T,
    pub(super) tail: List<T>,
    /// Length of the list this cell starts.
    pub(super) len: usize,
}

/// A shared cell: `clone` counts one more holder, `drop` one less.
pub(super) struct CellRef<T> {
    ptr: NonNull<Node<T>>,
    _owns: PhantomData<Node<T>>,
}

impl<T> CellRef<T> {
    /// A new cell with one holder.
    #[inline]
    pub(super) fn new(head: T, tail: List<T>, len: usize) -> CellRef<T> {
        let ptr = block::<Node<T>>().cast::<Node<T>>();
        let node = Node {
            count: Cell::new(1),
            head,
            tail,
            len,
        };
        // SAFETY: a fresh block of `Node<T>`'s size and alignment at least.
        unsafe { ptr.as_ptr().write(node) };
        CellRef {
            ptr,
            _owns: PhantomData,
        }
    }

    /// Whether both are the very same cell.
    #[inline]
    pub(super) fn ptr_eq(a: &CellRef<T>, b: &CellRef<T>) -> bool {
        a.ptr == b.ptr
    }

    /// The cell's address: its identity while a holder lives
    /// (`native::memo`'s key for it).
    #[inline]
    pub(super) fn addr(&self) -> usize {
        self.ptr.as_ptr() as usize
    }

    /// The holders of this cell (for tests).
    #[cfg(test)]
    pub(super) fn holders(&self) -> usize {
        self.count.get()
    }
}

impl<T> std::ops::Deref for CellRef<T> {
    type Target = Node<T>;
    #[inline(always)]
    fn deref(&self) -> &Node<T> {
        // SAFETY: live while a holder is (the invariant).
        unsafe { self.ptr.as_ref() }
    }
}

impl<T> Clone for CellRef<T> {
    #[inline]
    fn clone(&self) -> CellRef<T> {
        let c = self.count.get();
        if c == usize::MAX {
            // As `Rc`: more holders than memory can hold is a broken count.
            std::process::abort();
        }
        self.count.set(c + 1);
        CellRef {
            ptr: self.ptr,
            _owns: PhantomData,
        }
    }
}

impl<T> Drop for CellRef<T> {
    #[inline]
    fn drop(&mut self) {
        let c = self.count.get() - 1;
        self.count.set(c);
        if c == 0 {
            // SAFETY: the last holder gone.
            unsafe { free_chain(self.ptr) }
        }
    }
}

/// Drops the node at `ptr` (its count 0) and releases its block, then so
/// for each next cell of its tail whose count that makes 0: a loop, not a
/// recursion along the tail.
///
/// # Safety
/// `ptr` is a live node whose count reached 0 (no holder left).
unsafe fn free_chain<T>(mut ptr: NonNull<Node<T>>) {
    loop {
        let node = ptr.as_ptr();
        // SAFETY: no holder left: the node is ours to take apart.
        let tail = unsafe {
            ptr::drop_in_place(ptr::addr_of_mut!((*node).head));
            let tail = ptr::read(ptr::addr_of!((*node).tail));
            release::<Node<T>>(node.cast());
            tail
        };
        let next = match tail.0 {
            Shape::Cons(next) => ManuallyDrop::new(next),
            // `[]` or a slice: dropped as usual.
            _ => return,
        };
        let c = next.count.get() - 1;
        next.count.set(c);
        if c != 0 {
            return;
        }
        ptr = next.ptr;
    }
}

/// The size step of the pool's classes, and their alignment.
const GRAIN: usize = 16;
/// Classes of 16, 32, .., 128 bytes (a cell of `Val`s is 64).
const CLASSES: usize = 8;
/// Blocks kept a class: the cells of a round of a walk of a few hundred
/// places, reused by the next round; more go back to the allocator.
const KEEP: usize = 1024;

/// Free blocks a class, each linked to the next by its first word.
struct Pool {
    free: [Cell<*mut u8>; CLASSES],
    kept: [Cell<usize>; CLASSES],
}

impl Drop for Pool {
    fn drop(&mut self) {
        for (c, head) in self.free.iter().enumerate() {
            let layout = class_layout(c);
            let mut p = head.replace(ptr::null_mut());
            while !p.is_null() {
                // SAFETY: a free block of class `c`, its first word the next.
                unsafe {
                    let next = p.cast::<*mut u8>().read();
                    dealloc(p, layout);
                    p = next;
                }
            }
            self.kept[c].set(0);
        }
    }
}

thread_local! {
    static POOL: Pool = const {
        Pool {
            free: [const { Cell::new(ptr::null_mut()) }; CLASSES],
            kept: [const { Cell::new(0) }; CLASSES],
        }
    };
}

/// The class of blocks for an `N`, `None` for one too big or too aligned
/// (then the allocator's own layout of `N`).
#[inline(always)]
const fn class_of<N>() -> Option<usize> {
    let size = std::mem::size_of::<N>();
    if std::mem::align_of::<N>() <= GRAIN && size <= GRAIN * CLASSES && size > 0 {
        Some(size.div_ceil(GRAIN) - 1)
    } else {
        None
    }
}

fn class_layout(c: usize) -> Layout {
    match Layout::from_size_align((c + 1) * GRAIN, GRAIN) {
        Ok(l) => l,
        Err(_) => unreachable!("a class's size is small and its alignment a power of two"),
    }
}

#[inline(always)]
fn layout_of<N>() -> Layout {
    match class_of::<N>() {
        Some(c) => class_layout(c),
        None => Layout::new::<N>(),
    }
}

/// A block for an `N`: from the pool where it has one, else the allocator.
#[inline]
fn block<N>() -> NonNull<u8> {
    if let Some(c) = class_of::<N>() {
        let kept = POOL.try_with(|pool| {
            let p = pool.free[c].get();
            if p.is_null() {
                return None;
            }
            // SAFETY: a free block of class `c`, its first word the next.
            pool.free[c].set(unsafe { p.cast::<*mut u8>().read() });
            pool.kept[c].set(pool.kept[c].get() - 1);
            NonNull::new(p)
        });
        if let Ok(Some(p)) = kept {
            return p;
        }
    }
    let layout = layout_of::<N>();
    // SAFETY: `layout` is not zero-sized (a node holds its count).
    let p = unsafe { alloc(layout) };
    NonNull::new(p).unwrap_or_else(|| handle_alloc_error(layout))
}

/// Gives back a block [`block`] gave for an `N` (its value dropped or
/// moved out): to the pool while it keeps fewer than [`KEEP`], else (or
/// while the thread ends) to the allocator.
///
/// # Safety
/// `p` came from `block::<N>()` on this thread and is not used again.
#[inline]
unsafe fn release<N>(p: *mut u8) {
    if let Some(c) = class_of::<N>() {
        let kept = POOL.try_with(|pool| {
            let n = pool.kept[c].get();
            if n >= KEEP {
                return false;
            }
            // SAFETY: the block is ours and at least a word long.
            unsafe { p.cast::<*mut u8>().write(pool.free[c].get()) };
            pool.free[c].set(p);
            pool.kept[c].set(n + 1);
            true
        });
        if kept == Ok(true) {
            return;
        }
    }
    // SAFETY: allocated with this layout (a pooled block too).
    unsafe { dealloc(p, layout_of::<N>()) }
}

#[cfg(test)]
mod tests;
