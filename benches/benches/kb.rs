//! Benchmarks of the KB service (`sitlog-kb`): property extension and
//! explanations over generated KBs of 10^2, 10^4 and 10^6 individuals in a
//! class tree of depth 8, and single-individual queries.
//!
//! Figures are for warm class caches (the first query after loading or an
//! update also computes the closure of each class once; that cold cost is
//! printed once per size).

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use sitlog_kb::{gen, Kb};
use std::time::{Duration, Instant};

fn query(kb: &Kb, q: &sitlog_syntax::Clause) -> usize {
    match kb.call(q) {
        Ok(sitlog_kb::Outcome::Answer(a)) => a.root().0 as usize,
        _ => 0,
    }
}

fn bench_kb(c: &mut Criterion) {
    let sizes = [100usize, 10_000, 1_000_000];
    let q = |s: &str| sitlog_syntax::read_term(s).expect("query parses");
    let prop_ext = q("property_extension(loc, X)");
    let expl_ext = q("explanation_extension(misplaced, X)");
    let one_value = q("object_property_value(o57, loc, X)");
    let one_general = q("object_property_value(o0, found_in, X)");
    let one_expl = q("explanation_of_individual(o2, X)");
    let one_props = q("properties_of_individual(o57, X)");
    // The benchmarks of each size, in this order.
    let queries = [
        ("property_extension", &prop_ext),
        ("explanation_extension", &expl_ext),
        ("object_property_value/cached", &one_value),
        ("object_property_value/own_closure", &one_general),
        ("explanation_of_individual", &one_expl),
        ("properties_of_individual", &one_props),
    ];

    let mut group = c.benchmark_group("kb");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    group.warm_up_time(Duration::from_millis(500));
    for &n in &sizes {
        let t = Instant::now();
        let kb = gen::generate(n, 8);
        let built = t.elapsed();
        let t = Instant::now();
        query(&kb, &prop_ext);
        let cold = t.elapsed();
        eprintln!("kb n={n}: generate {built:?}, first property_extension (cold caches) {cold:?}");
        for (name, clause) in &queries {
            group.bench_with_input(BenchmarkId::new(*name, n), &kb, |b, kb| {
                b.iter(|| black_box(query(kb, clause)))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench_kb);
criterion_main!(benches);
