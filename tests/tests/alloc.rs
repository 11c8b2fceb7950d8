//! No heap allocation per transition in steady state: a ground DM compiled
//! with `include_dm!` runs with `keep_history: false`; a counting global
//! allocator attributes allocations to transitions, long after warm-up. The
//! only allocations left are the garbage collector's (a copying collection
//! allocates its new regions, and shrinks the store's vectors, which then
//! grow back in a few doublings): O(1) per collection, not per transition.
//! The same DM on the reference interpreter is measured too and printed
//! (`cargo test --test alloc -- --nocapture`).

use sitlog_runtime::machine::{Actions, Options, Perceived, Perception};
use sitlog_runtime::{Functions, Store, Term};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

mod ground_loop {
    sitlog_macros::include_dm!("dms/ground_loop");
}
mod typed_counter {
    sitlog_macros::include_dm!("dms/typed_counter");
}

struct Counting;

static COUNTING: AtomicBool = AtomicBool::new(false);
static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

const WARM_UP: u64 = 50_000;
const MEASURED: u64 = 100_000;

/// Counts `tick`s; from tick WARM_UP on, attributes the allocations made
/// since the previous tick to that transition, separating the transitions
/// during which the garbage collector ran (the store shrank: a copying
/// collection allocates its new regions) from all the others. Stops the run
/// with an error after WARM_UP + MEASURED ticks.
struct Ticks {
    n: u64,
    last_allocs: u64,
    last_cells: usize,
    /// Allocations in transitions without a collection.
    steady: u64,
    /// Transitions with a collection, and their allocations.
    collections: u64,
    gc_allocs: u64,
}

impl Actions for Ticks {
    fn perform(&mut self, store: &mut Store, _action: Term) -> Result<(), String> {
        self.n += 1;
        let stats = store.stats();
        let cells = stats.cells + stats.vars;
        let allocs = ALLOCATIONS.load(Ordering::SeqCst);
        if self.n == WARM_UP {
            COUNTING.store(true, Ordering::SeqCst);
        } else if self.n > WARM_UP {
            let delta = allocs - self.last_allocs;
            if cells < self.last_cells {
                self.collections += 1;
                self.gc_allocs += delta;
            } else {
                self.steady += delta;
            }
        }
        self.last_allocs = allocs;
        self.last_cells = cells;
        if self.n == WARM_UP + MEASURED {
            COUNTING.store(false, Ordering::SeqCst);
            return Err("enough".into());
        }
        Ok(())
    }
}

struct NoInput;

impl Perception for NoInput {
    fn perceive(&mut self, _: &mut Store, _: Term, _: &[Term]) -> Result<Perceived, String> {
        Ok(Perceived::EndOfInput)
    }
}

fn options() -> Options {
    Options {
        keep_history: false,
        // Collect often, so the measured window includes collections.
        gc_threshold: 1 << 16,
        ..Options::default()
    }
}

fn measure(run: impl FnOnce(&mut Ticks)) -> Ticks {
    let mut ticks = Ticks {
        n: 0,
        last_allocs: 0,
        last_cells: 0,
        steady: 0,
        collections: 0,
        gc_allocs: 0,
    };
    run(&mut ticks);
    assert_eq!(ticks.n, WARM_UP + MEASURED);
    ticks
}

// Both measurements in one test: the counter is global to the process.
#[test]
fn transitions_allocate_nothing_in_steady_state() {
    let compiled = measure(|ticks| {
        let (outcome, _store) = ground_loop::run(
            "main",
            None,
            options(),
            Functions::standard(),
            &mut NoInput,
            ticks,
            None,
        )
        .unwrap();
        assert!(outcome.result.is_err());
    });
    // Typed code (issue 19): the counter is a native int, the store untouched.
    let typed = measure(|ticks| {
        let (outcome, _store) = typed_counter::run(
            "main",
            None,
            options(),
            Functions::standard(),
            &mut NoInput,
            ticks,
            None,
        )
        .unwrap();
        assert!(outcome.result.is_err());
    });
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("dms/ground_loop");
    let (checked, _) = sitlog_compiler::check_path(&dir).unwrap();
    let ir = sitlog_compiler::ir::lower(&checked.ok().unwrap());
    let interpreted = measure(|ticks| {
        let (outcome, _store) = sitlog_runtime::app::run(
            &ir,
            "main",
            None,
            options(),
            Functions::standard(),
            &mut NoInput,
            ticks,
            None,
        )
        .unwrap();
        assert!(outcome.result.is_err());
    });
    for (name, t) in [
        ("compiled", &compiled),
        ("typed counter", &typed),
        ("interpreter", &interpreted),
    ] {
        println!(
            "{name}: {} allocations in {} transitions without a collection; \
             {} collections made {} allocations",
            t.steady,
            MEASURED - t.collections,
            t.collections,
            t.gc_allocs
        );
    }
    // Compiled code on a ground DM does not even grow the store: no
    // allocation and nothing to collect.
    assert_eq!(
        (compiled.steady, compiled.collections),
        (0, 0),
        "compiled code allocated in {MEASURED} transitions"
    );
    assert_eq!(
        (typed.steady, typed.collections),
        (0, 0),
        "typed code allocated in {MEASURED} transitions"
    );
    // The interpreter builds each instance in the store; the window is long
    // enough to include collections. What remains outside them is the
    // store's vectors growing back after each collection (the collector
    // shrinks them): a few doublings per cycle, none per transition.
    assert!(interpreted.collections > 0);
    assert!(
        interpreted.steady <= 8 * (interpreted.collections + 1),
        "the interpreter allocated {} times in {} transitions",
        interpreted.steady,
        MEASURED
    );
}
