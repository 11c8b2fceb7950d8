//! Planning (§8.3): our search against the authors' method (every
//! permutation of the basic actions, sorted by cost), from 4 to 14 basic
//! actions. The baseline is only run up to 10 actions (10! = 3.6 M orders;
//! 12 would take minutes per iteration).
//!
//! `cargo bench -p sitlog-benches --bench plan`.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use sitlog_infer::plan::{exhaustive, plan};
use std::time::Duration;

#[path = "../../infer/examples/plan_crossover/workload.rs"]
mod workload;
use workload::{problem, shop};

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
