//! A world's size against the time to load it (`World::parse`: the file
//! read, checked and its objects laid out) and to build its physics and
//! settle every object (`Sim::new`), from 10³ to 3·10⁴ shelves with an
//! object each (issue 31: 100 000 took 79 s, a scan of every object per
//! shelf; now near-linear: the ratio between sizes is what to read).
//!
//! `cargo bench -p sitlog-benches --bench world`.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use sitlog_sim::{Sim, World};
use std::time::Duration;

fn world(c: &mut Criterion) {
    let mut g = c.benchmark_group("world");
    g.sample_size(10).measurement_time(Duration::from_secs(10));
    for n in [1_000, 10_000, 30_000] {
        let text = sitlog_sim::world::example::grid(n);
        g.bench_with_input(BenchmarkId::new("parse", n), &text, |b, text| {
            b.iter(|| black_box(World::parse("big.toml", text).expect("the world checks")))
        });
        let w = World::parse("big.toml", &text).expect("the world checks");
        g.bench_with_input(BenchmarkId::new("sim_new", n), &w, |b, w| {
            b.iter(|| black_box(Sim::new(w, 1)))
        });
    }
    g.finish();
}

criterion_group!(benches, world);
criterion_main!(benches);
