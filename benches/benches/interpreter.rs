//! Transitions per second of the reference interpreter for 10^3..10^6
//! transitions, on a neutral loop (local counter) and on a loop driven by
//! scripted input, with and without history. Cost per transition must stay
//! flat as N grows. `run::run` resolves the program into plans at each run
//! (included in the time); `templates` instantiates every situation from
//! its template (`run::run_unresolved`, the interpreter before the plans).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use sitlog_benches::{neutral_loop, scripted_loop};
use sitlog_compiler::ir::Ir;
use sitlog_compiler::run::{self, RunConfig};
use sitlog_runtime::machine::Options;
use sitlog_runtime::testmode::{ScriptPerception, TextActions};

fn lower(src: &str) -> Ir {
    let (program, diags) = sitlog_compiler::load::load_sources(&[("bench.dm", src)]);
    let (result, _) = sitlog_compiler::check::check(program, diags);
    sitlog_compiler::ir::lower(&result.expect("benchmark DM checks"))
}

fn run_once(ir: &Ir, script: &str, keep_history: bool) -> u64 {
    run_with(run::run, ir, script, keep_history)
}

type Runner =
    fn(
        &Ir,
        RunConfig,
        &mut dyn sitlog_runtime::machine::Perception,
        &mut dyn sitlog_runtime::machine::Actions,
        Option<&mut dyn sitlog_runtime::machine::Observer>,
    ) -> Result<(sitlog_runtime::machine::Outcome, sitlog_runtime::Store), run::ConfigError>;

fn run_with(runner: Runner, ir: &Ir, script: &str, keep_history: bool) -> u64 {
    let mut perception = ScriptPerception::new("script", script.to_owned());
    let mut actions = TextActions::new(std::io::sink(), Vec::new());
    let config = RunConfig {
        options: Options {
            keep_history,
            ..Options::default()
        },
        ..RunConfig::default()
    };
    let (outcome, _) = runner(ir, config, &mut perception, &mut actions, None).expect("runs");
    assert!(outcome.result.is_ok(), "{:?}", outcome.result);
    outcome.transitions
}

fn interpreter(c: &mut Criterion) {
    for (name, keep) in [("history_none", false), ("history_keep", true)] {
        let mut group = c.benchmark_group(format!("neutral_loop/{name}"));
        group.sample_size(10);
        for n in [1_000u64, 10_000, 100_000, 1_000_000] {
            let ir = lower(&neutral_loop(n));
            group.throughput(Throughput::Elements(n + 1));
            group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
                b.iter(|| run_once(&ir, "", keep))
            });
        }
        group.finish();
    }
    let mut group = c.benchmark_group("neutral_loop/templates/history_none");
    group.sample_size(10);
    for n in [1_000u64, 10_000] {
        let ir = lower(&neutral_loop(n));
        group.throughput(Throughput::Elements(n + 1));
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| run_with(run::run_unresolved, &ir, "", false))
        });
    }
    group.finish();
    let mut group = c.benchmark_group("scripted_loop/history_none");
    group.sample_size(10);
    for n in [1_000u64, 10_000, 100_000, 1_000_000] {
        let (dm, script) = scripted_loop(n);
        let ir = lower(&dm);
        group.throughput(Throughput::Elements(n + 2));
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| run_once(&ir, &script, false))
        });
    }
    group.finish();
}

criterion_group!(benches, interpreter);
criterion_main!(benches);
