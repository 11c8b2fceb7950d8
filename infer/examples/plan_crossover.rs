//! A quick look at the planner against every permutation (the same
//! problems as `benches/benches/plan.rs`, which is the criterion bench):
//! `cargo run --release -p sitlog-infer --example plan_crossover`.
//! Prints, per size, the best of 5 runs of each, in one process.

use sitlog_infer::plan::{exhaustive, plan, Costs, Obligation, Problem, Target};
use sitlog_infer::Distances;
use std::time::{Duration, Instant};

const SHELVES: [(&str, f64, f64); 6] = [
    ("entrance", 0.0, 0.0),
    ("shelf_drinks", 6.0, 0.0),
    ("shelf_food", 6.0, 5.0),
    ("shelf_bread", 0.0, 5.0),
    ("shelf_snacks", 3.0, 8.0),
    ("shelf_fruit", 9.0, 8.0),
];

fn shop() -> Distances {
    let mut d = Distances::new();
    for (a, ax, ay) in SHELVES {
        for (b, bx, by) in SHELVES {
            d.set(a, b, ((ax - bx) * (ax - bx) + (ay - by) * (ay - by)).sqrt());
        }
    }
    d
}

/// A problem of `n` basic actions (4 per object to fetch, 2 per object in
/// a hand): the customer's object first, then misplaced ones.
fn problem(n: usize) -> Problem {
    let fetch = n / 4;
    let held = (n % 4) / 2;
    let mut obligations = Vec::new();
    for i in 0..fetch {
        let from = SHELVES[1 + (i * 2) % 5].0;
        obligations.push(Obligation {
            object: format!("o{i}"),
            from: Some(from.into()),
            to: if i == 0 {
                Target::User
            } else {
                Target::Shelf(SHELVES[1 + (i * 2 + 1) % 5].0.into())
            },
        });
    }
    let mut right = None;
    if held == 1 {
        obligations.push(Obligation {
            object: "h".into(),
            from: None,
            to: Target::Shelf("shelf_fruit".into()),
        });
        right = Some("h".into());
    }
    Problem {
        at: "shelf_drinks".into(),
        left: None,
        right,
        user_at: "entrance".into(),
        obligations,
        costs: Costs::default(),
    }
}

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
