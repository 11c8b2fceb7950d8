//! A quick look at the planner against every permutation (the same
//! problems as `benches/benches/plan.rs`, which is the criterion bench):
//! `cargo run --release -p sitlog-infer --example plan_crossover`.
//! Prints, per size, the best of 5 runs of each, in one process.

use sitlog_infer::plan::{exhaustive, plan};
use std::time::{Duration, Instant};

mod workload;
use workload::{problem, shop};

fn best<T>(mut f: impl FnMut() -> T) -> Duration {
    (0..5)
        .map(|_| {
            let t = Instant::now();
            std::hint::black_box(f());
            t.elapsed()
        })
        .min()
        .unwrap()
}

fn main() {
    let d = shop();
    println!("actions  search        every permutation  ratio");
    for n in [4, 6, 8, 10, 12, 14] {
        let p = problem(n);
        let ours = plan(&p, &d).expect("a plan");
        let s = best(|| plan(&p, &d).unwrap().cost);
        if n <= 10 {
            let base = exhaustive(&p, &d).expect("a plan");
            assert!((ours.cost - base.cost).abs() < 1e-9);
            let e = best(|| exhaustive(&p, &d).unwrap().cost);
            println!(
                "{n:>7}  {s:>12.2?}  {e:>17.2?}  {:>5.1}x",
                e.as_secs_f64() / s.as_secs_f64()
            );
        } else {
            println!("{n:>7}  {s:>12.2?}  {:>17}", "(not run)");
        }
    }
}
