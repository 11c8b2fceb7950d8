//! Review17 (issue 37): "0 allocations per typed transition of (c)",
//! checked on workloads of shape (c) written without reading
//! `tests/typed/shapes` (`tests/typed/review17/r17_c_*`), counted as
//! `tests/alloc.rs` counts them (a counting global allocator, the
//! allocations between two performed actions attributed to that
//! transition, after a warm-up; collections counted apart). A test binary
//! of its own: the counter is global to the process.

use sitlog_runtime::app::{self, App};
use sitlog_runtime::machine::{Actions, Options, Perceived, Perception};
use sitlog_runtime::{Functions, Store, Term};
use sitlog_tests::alloc::{allocations, set_counting, Counting};

mod charge {
    sitlog_macros::include_dm!("typed/review17/r17_c_charge_when");
}
mod courier {
    sitlog_macros::include_dm!("typed/review17/r17_c_courier_global");
}
mod odometer {
    sitlog_macros::include_dm!("typed/review17/r17_c_odometer");
}
mod job_pair {
    sitlog_macros::include_dm!("typed/review17/r17_c_job_pair");
}

#[global_allocator]
static GLOBAL: Counting = Counting;

const WARM_UP: u64 = 20_000;
const MEASURED: u64 = 40_000;

/// As `tests/alloc.rs`'s `Ticks`: one tick per action performed.
struct Ticks {
    n: u64,
    last_allocs: u64,
    last_cells: usize,
    steady: u64,
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

fn measure<A: App>(app: &A, main: &str) -> Ticks {
    let mut ticks = Ticks {
        n: 0,
        last_allocs: 0,
        last_cells: 0,
        steady: 0,
        collections: 0,
        gc_allocs: 0,
    };
    let options = Options {
        keep_history: false,
        gc_threshold: 1 << 16,
        ..Options::default()
    };
    let (outcome, _store) = app::run(
        app,
        main,
        None,
        options,
        Functions::standard(),
        &mut NoInput,
        &mut ticks,
        None,
    )
    .unwrap();
    assert!(outcome.result.is_err(), "{main}: {:?}", outcome.result);
    assert_eq!(ticks.n, WARM_UP + MEASURED, "{main}");
    ticks
}

// All in one test: the counter is global to the process.
#[test]
fn review17_shape_c_transitions_allocate_nothing() {
    let runs = [
        (
            "r17_c_charge_when",
            measure(charge::program(), "charger(1000000000)"),
        ),
        (
            "r17_c_courier_global",
            measure(courier::program(), "mission(1000000000)"),
        ),
        (
            "r17_c_odometer",
            measure(odometer::program(), "patrol(1000000000)"),
        ),
        (
            "r17_c_job_pair",
            measure(job_pair::program(), "shift(1000000000)"),
        ),
    ];
    let mut bad = Vec::new();
    for (name, t) in &runs {
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
    assert!(bad.is_empty(), "shape (c) allocated: {bad:?}");
}
