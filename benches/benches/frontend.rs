//! Parsing and checking 40 000 lines of generated DMs (target: under 1 s on
//! one core in release).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use sitlog_benches::dm_program;

fn frontend(c: &mut Criterion) {
    let src = dm_program(40_000);
    let lines = src.lines().count();
    let mut group = c.benchmark_group("frontend");
    group.sample_size(10);
    group.throughput(Throughput::Elements(lines as u64));
    group.bench_function(format!("read_{lines}_lines"), |b| {
        b.iter(|| sitlog_syntax::read_clauses(&src))
    });
    group.bench_function(format!("read_and_check_{lines}_lines"), |b| {
        b.iter(|| {
            let (program, diags) = sitlog_compiler::load::load_sources(&[("gen.dm", &src)]);
            let (result, _) = sitlog_compiler::check::check(program, diags);
            assert!(result.is_ok());
        })
    });
    group.finish();
}

criterion_group!(benches, frontend);
criterion_main!(benches);
