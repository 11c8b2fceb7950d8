//! Planning (§8.3): our search against the authors' method (every
//! permutation of the basic actions, sorted by cost), from 4 to 14 basic
//! actions. The baseline is only run up to 10 actions (10! = 3.6 M orders;
//! 12 would take minutes per iteration).
//!
//! `cargo bench -p sitlog-benches --bench plan`.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use sitlog_infer::plan::{exhaustive, plan, Costs, Obligation, Problem, Target};
use sitlog_infer::Distances;
use std::time::Duration;

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

fn bench(c: &mut Criterion) {
    let d = shop();
    let mut g = c.benchmark_group("plan");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    for n in [4, 6, 8, 10, 12, 14] {
        let p = problem(n);
        let ours = plan(&p, &d).expect("a plan");
        if n <= 10 {
            let base = exhaustive(&p, &d).expect("a plan");
            assert!(
                (ours.cost - base.cost).abs() < 1e-9,
                "{n}: {ours:?} vs {base:?}"
            );
            g.bench_with_input(BenchmarkId::new("exhaustive", n), &p, |b, p| {
                b.iter(|| black_box(exhaustive(p, &d).unwrap().cost))
            });
        }
        g.bench_with_input(BenchmarkId::new("search", n), &p, |b, p| {
            b.iter(|| black_box(plan(p, &d).unwrap().cost))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
