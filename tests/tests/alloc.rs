//! No heap allocation per transition in steady state: a ground DM compiled
//! with `include_dm!` runs with `keep_history: false`; a counting global
//! allocator attributes allocations to transitions, long after warm-up. The
//! only allocations left are the garbage collector's (a copying collection
//! allocates its new regions, and shrinks the store's vectors, which then
//! grow back in a few doublings): O(1) per collection, not per transition.
//! The same DM on the reference interpreter is measured too and printed
//! (`cargo test --test alloc -- --nocapture`).

use sitlog_runtime::app::{self, App};
use sitlog_runtime::machine::{Actions, Options, Perceived, Perception};
use sitlog_runtime::{Functions, Store, Term};
use sitlog_tests::alloc::{allocations, set_counting, Counting};

mod ground_loop {
    sitlog_macros::include_dm!("dms/ground_loop");
}
mod typed_counter {
    sitlog_macros::include_dm!("dms/typed_counter");
}
/// Issue 37's shape (c) written by another engineer (`nshape13`): the count
/// in the pipe and the caller's id, the callee's final chosen by its in_arg.
mod c_final_by_inarg {
    sitlog_macros::include_dm!("typed/shapes/c_final_by_inarg");
}

/// Shape (c) written without reading `tests/typed/shapes` (helper
/// `review17`, moved here from `alloc_review17.rs` by `nis17`: one test
/// binary less): a `when/3` next situation, a global three DMs deep, the
/// callee's final handing the pipe back, the pipe a pair counted by `is`
/// on `ground` values in an action list.
mod r17_charge {
    sitlog_macros::include_dm!("typed/review17/r17_c_charge_when");
}
mod r17_courier {
    sitlog_macros::include_dm!("typed/review17/r17_c_courier_global");
}
mod r17_odometer {
    sitlog_macros::include_dm!("typed/review17/r17_c_odometer");
}
mod r17_job_pair {
    sitlog_macros::include_dm!("typed/review17/r17_c_job_pair");
}

/// Shape (c) written without reading `tests/typed/shapes` or
/// `tests/typed/review17` (helper `review18`): three DMs deep, the limit
/// handed back by the deepest callee, a global counted in the middle DM and
/// handed up in its final's id; the callee choosing its final by a global.
mod r18_deep_limit {
    sitlog_macros::include_dm!("typed/review18/r18_c_deep_limit");
}
mod r18_clerk {
    sitlog_macros::include_dm!("typed/review18/r18_c_clerk_global");
}

/// Shape (c) written without reading the workloads above (helper
/// `review19`): a final carrying a compound the caller's exit arc
/// destructures (`done(K, tick)`); two DMs calling each other (`ping`,
/// `pong`), two levels deep.
mod r19_done_pair {
    sitlog_macros::include_dm!("typed/review19/r19_c_done_pair");
}
mod r19_ping_pong {
    sitlog_macros::include_dm!("typed/review19/r19_c_ping_pong");
}

/// Shape (c) written after sessions 19-20 (helper `review22`): the callee
/// in its own file and a global count; recursion through two situations;
/// the count and the limit in the pipe; the count in the id.
mod r22_stage_global {
    sitlog_macros::include_dm!("typed/review22/r22_c_stage_global");
}
mod r22_ferry_two {
    sitlog_macros::include_dm!("typed/review22/r22_c_ferry_two");
}
mod r22_lap_pipe {
    sitlog_macros::include_dm!("typed/review22/r22_c_lap_pipe");
}
mod r22_rung_id {
    sitlog_macros::include_dm!("typed/review22/r22_c_rung_id");
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
        let allocs = allocations();
        if self.n == WARM_UP {
            set_counting(true);
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
            set_counting(false);
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

/// Runs `app` from `main` without input until [`Ticks`] stops it.
fn measure<A: App>(app: &A) -> Ticks {
    measure_from(app, "main")
}

/// [`measure`] from the given main DM call.
fn measure_from<A: App>(app: &A, main: &str) -> Ticks {
    measure_with(app, main, None)
}

/// [`measure_from`] with the main DM's in_arg.
fn measure_piped<A: App>(app: &A, main: &str, in_arg: &str) -> Ticks {
    measure_with(app, main, Some(in_arg))
}

fn measure_with<A: App>(app: &A, main: &str, in_arg: Option<&str>) -> Ticks {
    let mut ticks = Ticks {
        n: 0,
        last_allocs: 0,
        last_cells: 0,
        steady: 0,
        collections: 0,
        gc_allocs: 0,
    };
    let (outcome, _store) = app::run(
        app,
        main,
        in_arg,
        options(),
        Functions::standard(),
        &mut NoInput,
        &mut ticks,
        None,
    )
    .unwrap();
    assert!(outcome.result.is_err());
    assert_eq!(ticks.n, WARM_UP + MEASURED);
    ticks
}

// All measurements in one test: the counter is global to the process.
#[test]
fn transitions_allocate_nothing_in_steady_state() {
    // Compiled code (what the generated `run` runs).
    let compiled = measure(ground_loop::program());
    // Typed code (issue 19): the counter is a native int, the store untouched.
    let typed = measure(typed_counter::program());
    // Shape (c) (issue 37): N calls, stopped long before the limit. The
    // ticks are its performed numbers (`J` of each exit arc, handed to the
    // effector without entering the machine since `nget14`) and the
    // callee's `empty` (this effector does not ignore it), handed to the
    // effector without handing the caller's native frame over since
    // `nalloc15` (performance.md, `nshape13`'s, `nget14`'s and
    // `nalloc15`'s sections).
    let calls = measure_from(c_final_by_inarg::program(), "relay(1000000000)");
    // review17's shape (c) workloads (`typed::review17_*`); `r17_c_job_pair`
    // (`L1 is L - 1` on a `ground` pipe value, then the list of numbers
    // performed) grew the store before `nis17`: 4 collections in 40 000
    // actions.
    let r17 = [
        (
            "r17_c_charge_when",
            measure_from(r17_charge::program(), "charger(1000000000)"),
        ),
        (
            "r17_c_courier_global",
            measure_from(r17_courier::program(), "mission(1000000000)"),
        ),
        (
            "r17_c_odometer",
            measure_from(r17_odometer::program(), "patrol(1000000000)"),
        ),
        (
            "r17_c_job_pair",
            measure_from(r17_job_pair::program(), "shift(1000000000)"),
        ),
        (
            "r18_c_deep_limit",
            measure_from(r18_deep_limit::program(), "top(1000000000)"),
        ),
        (
            "r18_c_clerk_global",
            measure_from(r18_clerk::program(), "boss(1000000000)"),
        ),
        (
            "r19_c_done_pair",
            measure_piped(r19_done_pair::program(), "relay", "1000000000"),
        ),
        (
            "r19_c_ping_pong",
            measure_from(r19_ping_pong::program(), "rally(1000000000, 2)"),
        ),
        (
            "r22_c_stage_global",
            measure_piped(r22_stage_global::program(), "launch", "1000000000"),
        ),
        (
            "r22_c_ferry_two",
            measure_piped(r22_ferry_two::program(), "shuttle", "1000000000"),
        ),
        (
            "r22_c_lap_pipe",
            measure_piped(r22_lap_pipe::program(), "track", "1000000000"),
        ),
        (
            "r22_c_rung_id",
            measure_piped(r22_rung_id::program(), "ladder", "1000000000"),
        ),
    ];
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("dms/ground_loop");
    let (checked, _) = sitlog_compiler::check_path(&dir).unwrap();
    let ir = sitlog_compiler::ir::lower(&checked.ok().unwrap());
    let interpreted = measure(&ir);
    for (name, t) in [
        ("compiled", &compiled),
        ("typed counter", &typed),
        ("shape (c) c_final_by_inarg", &calls),
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
    assert_eq!(
        (calls.steady, calls.collections),
        (0, 0),
        "shape (c) allocated in {MEASURED} transitions, `empty` performed"
    );
    let mut bad = Vec::new();
    for (name, t) in &r17 {
        println!(
            "{name}: {} allocations in {} actions without a collection; \
             {} collections made {} allocations",
            t.steady,
            MEASURED - t.collections,
            t.collections,
            t.gc_allocs
        );
        if (t.steady, t.collections) != (0, 0) {
            bad.push(format!(
                "{name}: {} steady, {} collections",
                t.steady, t.collections
            ));
        }
    }
    assert!(
        bad.is_empty(),
        "review17's, review18's, review19's and review22's shape (c) allocated: {bad:?}"
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
