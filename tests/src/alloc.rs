//! The counting global allocator of the allocation test (`tests/alloc.rs`)
//! and the benchmarks (`benches/benches/compiled.rs`): [`Counting`]
//! forwards to the system allocator and, while counting is on, counts every
//! allocation and reallocation (frees are not counted) **made by the thread
//! that turned counting on**: another thread of the process (libtest's
//! main thread printing "has been running for over 60 seconds" on a loaded
//! machine, another test) is not the code measured, and counting it made
//! the allocation test fail now and then. One counter per process. A test
//! or bench binary installs it itself:
//!
//! ```ignore
//! #[global_allocator]
//! static GLOBAL: sitlog_tests::alloc::Counting = sitlog_tests::alloc::Counting;
//! ```
//!
//! (this library does not: every test binary linking it would get it).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

/// Counts heap allocations (and reallocations) while counting is on.
pub struct Counting;

static COUNTING: AtomicBool = AtomicBool::new(false);
static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// This thread turned counting on (const-initialised, no destructor:
    /// reading it never allocates, so the allocator may).
    static THIS_THREAD: Cell<bool> = const { Cell::new(false) };
}

/// Whether an allocation now is counted.
#[inline]
fn counted() -> bool {
    COUNTING.load(Ordering::Relaxed) && THIS_THREAD.try_with(Cell::get).unwrap_or(false)
}

unsafe impl GlobalAlloc for Counting {
    #[inline]
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if counted() {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        System.alloc(layout)
    }
    #[inline]
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    #[inline]
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if counted() {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        System.realloc(ptr, layout, new_size)
    }
}

/// Turns counting on or off for the calling thread (the count is kept).
pub fn set_counting(on: bool) {
    THIS_THREAD.with(|t| t.set(on));
    COUNTING.store(on, Ordering::SeqCst);
}

/// The allocations counted so far.
pub fn allocations() -> u64 {
    ALLOCATIONS.load(Ordering::SeqCst)
}

/// Runs `f` with counting on, from a count of zero: its result and the
/// allocations it made (with [`Counting`] installed; else 0).
pub fn count<T>(f: impl FnOnce() -> T) -> (T, u64) {
    ALLOCATIONS.store(0, Ordering::SeqCst);
    set_counting(true);
    let t = f();
    set_counting(false);
    (t, allocations())
}
