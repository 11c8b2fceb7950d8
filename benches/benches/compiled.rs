//! Generated code vs the reference interpreter vs a hand-written Rust
//! `enum` + `match` machine doing the same work (the floor), per transition:
//! - `counter_loop`: a neutral loop with a local counter (`inc` + a
//!   conditional next situation), no history;
//! - `counter_loop_in_arg`: the same loop with its limit as in_arg (the
//!   pipe), no history;
//! - `pipe_calls`: N DM calls passing the pipe (`B is A + 1` in the callee),
//!   no history;
//! - `scripted_loop`: a speech situation driven by a script of `tick.`
//!   inputs (each read and parsed as a term), no history;
//! - `appendix_a`: the papers' Appendix A example on its script, with history;
//! - `echo_calls` (workload c of issue 37): N calls of an embedded DM, the
//!   limit the recursive situation's in_arg, the callee handing its pipe
//!   back through `out_arg ==> X`, no history;
//! - `list_search_8`, `list_search_256` (workload d of issue 37): rounds of
//!   a call `search(Places, Target)` walking a list by the compound id
//!   `try([P|Ps])`, ending in `found(P)` or `not_found`, no history; 8 and
//!   256 places, to see that a walk costs the same per transition;
//!   `list_search_const_8`, `list_search_const_256`: the same with the
//!   call's arguments constants, so that `search` runs as native code
//!   (`codegen::native`: its parameters typed by the MIR's inference).
//!
//! Each program is also compiled `untyped` (every value a term: the code
//! generator before typed code), so that one run compares both. Sizes 10⁴
//! and 10⁶ transitions; the counter loop also at 10⁸ (typed code and the
//! hand-written loop only).
//!
//! The interpreter runs situations from their plans
//! ([`sitlog_compiler::interp`], what `sitlogc run` does); at 10⁴ also
//! from their templates (`interpreter_templates`, every situation
//! instantiated, as before the plans).
//!
//! Before each group, one run of each variant under a counting global
//! allocator prints its heap allocations per transition; the scripted loop
//! also times reading its script alone (`scripted_loop_parse`: the term
//! reader's share of a transition).
//!
//! `cargo bench -p sitlog-benches --bench compiled`; the ratios in
//! docs/guide/performance.md come from one such run.

use criterion::measurement::WallTime;
use criterion::{
    black_box, criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion, Throughput,
};
use sitlog_compiler::interp::Resolved;
use sitlog_compiler::ir::Ir;
use sitlog_runtime::machine::{Options, Outcome};
use sitlog_runtime::testmode::{ScriptPerception, TextActions};
use sitlog_runtime::{app, Functions, Store, Term};
use sitlog_tests::alloc::{self, Counting};
use std::path::Path;
use std::time::Duration;

#[path = "../src/hand.rs"]
mod hand;
use hand::*;

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Runs `f` once (it returns its transitions) and prints its heap
/// allocations per transition, whole run included (start-up, the store's
/// growth, garbage collections).
fn allocations(label: &str, f: impl FnOnce() -> u64) {
    let (t, a) = alloc::count(f);
    println!(
        "allocations {label}: {a} in {t} transitions = {:.4} per transition",
        a as f64 / t.max(1) as f64
    );
}

/// A benchmark group of `samples` samples measured for `secs` seconds
/// after one second of warm-up.
fn group<'a>(
    c: &'a mut Criterion,
    name: &str,
    samples: usize,
    secs: u64,
) -> BenchmarkGroup<'a, WallTime> {
    let mut group = c.benchmark_group(name);
    group
        .sample_size(samples)
        .measurement_time(Duration::from_secs(secs));
    group.warm_up_time(Duration::from_secs(1));
    group
}

mod counter_loop {
    sitlog_macros::include_dm!("dms/counter_loop");
}
mod counter_loop_in_arg {
    sitlog_macros::include_dm!("dms/counter_loop_in_arg");
}
mod pipe_calls {
    sitlog_macros::include_dm!("dms/pipe_calls");
}
mod scripted_loop {
    sitlog_macros::include_dm!("dms/scripted_loop");
}
mod echo_calls {
    sitlog_macros::include_dm!("dms/echo_calls");
}
mod list_search {
    sitlog_macros::include_dm!("dms/list_search");
}
mod list_search_const_8 {
    sitlog_macros::include_dm!("dms/list_search_const_8");
}
mod list_search_const_256 {
    sitlog_macros::include_dm!("dms/list_search_const_256");
}
mod route_walk {
    sitlog_macros::include_dm!("dms/route_walk");
}
mod count_pipe {
    sitlog_macros::include_dm!("dms/count_pipe");
}
// The same programs with every value a term (the code generator before typed code).
mod counter_loop_untyped {
    sitlog_macros::include_dm!("dms/counter_loop", untyped);
}
mod counter_loop_in_arg_untyped {
    sitlog_macros::include_dm!("dms/counter_loop_in_arg", untyped);
}
mod pipe_calls_untyped {
    sitlog_macros::include_dm!("dms/pipe_calls", untyped);
}
mod scripted_loop_untyped {
    sitlog_macros::include_dm!("dms/scripted_loop", untyped);
}
mod echo_calls_untyped {
    sitlog_macros::include_dm!("dms/echo_calls", untyped);
}
mod list_search_untyped {
    sitlog_macros::include_dm!("dms/list_search", untyped);
}
mod list_search_const_8_untyped {
    sitlog_macros::include_dm!("dms/list_search_const_8", untyped);
}
mod list_search_const_256_untyped {
    sitlog_macros::include_dm!("dms/list_search_const_256", untyped);
}
mod route_walk_untyped {
    sitlog_macros::include_dm!("dms/route_walk", untyped);
}
mod count_pipe_untyped {
    sitlog_macros::include_dm!("dms/count_pipe", untyped);
}
mod appendix_a {
    sitlog_macros::include_dm!("../dms/examples/appendix_a");
}

fn interpreter(app: &Path) -> Ir {
    let (checked, _) = sitlog_compiler::check_path(app).expect("readable");
    sitlog_compiler::ir::lower(&checked.expect("checks"))
}

fn options(keep_history: bool) -> Options {
    Options {
        keep_history,
        ..Options::default()
    }
}

/// One run of a program: its main call, in_arg and script, and whether the
/// history is kept.
struct Workload<'a> {
    main: &'a str,
    in_arg: Option<&'a str>,
    script: &'a str,
    keep_history: bool,
}

impl Workload<'_> {
    /// A run without history and without script.
    fn plain(main: &str) -> Workload<'_> {
        Workload {
            main,
            in_arg: None,
            script: "",
            keep_history: false,
        }
    }

    /// Runs a program with the standard functions; its transitions.
    fn run<A: app::App>(&self, app: &A) -> u64 {
        self.run_with(app, Functions::standard())
    }

    /// Runs a program through the runtime's runner (both back ends share it).
    fn run_with<A: app::App>(&self, app: &A, functions: Functions) -> u64 {
        let mut perception = ScriptPerception::new("script", self.script.to_owned());
        let mut actions = TextActions::new(std::io::sink(), Vec::new());
        let (outcome, _store): (Outcome, Store) = app::run(
            app,
            self.main,
            self.in_arg,
            options(self.keep_history),
            functions,
            &mut perception,
            &mut actions,
            None,
        )
        .expect("runs");
        assert!(outcome.result.is_ok(), "{:?}", outcome.result);
        outcome.transitions
    }
}

/// Sums the numbers it is given (does not ignore them).
struct Summing(i64, u64);

impl sitlog_runtime::machine::Actions for Summing {
    fn perform(&mut self, store: &mut Store, action: Term) -> Result<(), String> {
        if let sitlog_runtime::Value::Int(i) = store.value(action) {
            self.0 = self.0.wrapping_add(i);
            self.1 += 1;
        }
        Ok(())
    }
}

/// Runs the counter loop with [`Summing`] actions: (sum, actions performed).
fn run_performing<A: app::App>(app: &A, main: &str) -> (i64, u64) {
    let mut perception = ScriptPerception::new("script", String::new());
    let mut actions = Summing(0, 0);
    let (outcome, _store): (Outcome, Store) = app::run(
        app,
        main,
        None,
        options(false),
        Functions::standard(),
        &mut perception,
        &mut actions,
        None,
    )
    .expect("runs");
    assert!(outcome.result.is_ok(), "{:?}", outcome.result);
    (actions.0, actions.1)
}

/// One workload of size `n` on the three runners: compiled code and the
/// interpreter on the same run (`w`, no history), and the hand-written
/// floor, which must make as many transitions.
#[allow(clippy::too_many_arguments)]
fn three_ways(
    c: &mut Criterion,
    name: &str,
    n: u64,
    compiled: &impl app::App,
    untyped: &impl app::App,
    interpreted: &Ir,
    w: &Workload,
    hand: impl Fn() -> u64,
) {
    let mut group = group(c, name, 10, 3);
    let t = w.run(compiled);
    assert_eq!(
        t,
        hand(),
        "{name}: the hand-written machine makes other transitions"
    );
    group.throughput(Throughput::Elements(t));
    let resolved = Resolved::new(interpreted);
    let variants: [(&str, &dyn Fn() -> u64); 5] = [
        ("compiled", &|| w.run(compiled)),
        ("compiled_untyped", &|| w.run(untyped)),
        ("interpreter", &|| w.run(&resolved)),
        ("interpreter_templates", &|| w.run(interpreted)),
        ("hand_written", &hand),
    ];
    for (variant, f) in variants {
        allocations(&format!("{name}/{variant}/{n}"), f);
    }
    assert_eq!(w.run(untyped), t);
    for (variant, f) in variants {
        if variant == "interpreter_templates" && n > 10_000 {
            continue;
        }
        group.bench_with_input(BenchmarkId::new(variant, n), &n, |b, _| b.iter(f));
    }
    group.finish();
}

/// Reads the scripted loop's script alone, term by term, as the
/// perception of a run does (a fresh store per run, as a run has): the term
/// reader's share of a scripted transition.
fn read_script(c: &mut Criterion, n: u64, script: &str) {
    use sitlog_runtime::machine::{Perceived, Perception};
    let read = || {
        let mut store = Store::new();
        let mut perception = ScriptPerception::new("script", script.to_owned());
        let ty = Term::atom(sitlog_runtime::Atom::intern("speech"));
        let mut terms = 0u64;
        while let Ok(Perceived::Input(_)) = perception.perceive(&mut store, ty, &[]) {
            terms += 1;
        }
        terms
    };
    assert_eq!(read(), n + 1);
    let mut group = group(c, "scripted_loop_parse", 10, 3);
    group.throughput(Throughput::Elements(n + 2));
    group.bench_with_input(BenchmarkId::new("read_script", n), &n, |b, _| b.iter(read));
    group.finish();
}

fn bench(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let counter_ir = interpreter(&root.join("dms/counter_loop"));
    let in_arg_ir = interpreter(&root.join("dms/counter_loop_in_arg"));
    let pipe_ir = interpreter(&root.join("dms/pipe_calls"));
    let scripted_ir = interpreter(&root.join("dms/scripted_loop"));
    for n in [10_000u64, 1_000_000] {
        let main = format!("main({n})");
        let max = n as i64;
        three_ways(
            c,
            "counter_loop",
            n,
            counter_loop::program(),
            counter_loop_untyped::program(),
            &counter_ir,
            &Workload::plain(&main),
            || hand_counter_loop(black_box(max)),
        );
        let limit = n.to_string();
        three_ways(
            c,
            "counter_loop_in_arg",
            n,
            counter_loop_in_arg::program(),
            counter_loop_in_arg_untyped::program(),
            &in_arg_ir,
            &Workload {
                in_arg: Some(&limit),
                ..Workload::plain("main")
            },
            || hand_counter_loop(black_box(max)),
        );
        three_ways(
            c,
            "pipe_calls",
            n,
            pipe_calls::program(),
            pipe_calls_untyped::program(),
            &pipe_ir,
            &Workload {
                in_arg: Some("0"),
                ..Workload::plain(&main)
            },
            || hand_pipe_calls(black_box(max)),
        );
        let (_, script) = sitlog_benches::scripted_loop(n);
        read_script(c, n, &script);
        three_ways(
            c,
            "scripted_loop",
            n,
            scripted_loop::program(),
            scripted_loop_untyped::program(),
            &scripted_ir,
            &Workload {
                script: &script,
                ..Workload::plain("main")
            },
            || hand_scripted_loop(black_box(&script)),
        );
    }

    // Workloads (c) and (d) of issue 37.
    let echo_ir = interpreter(&root.join("dms/echo_calls"));
    let search_ir = interpreter(&root.join("dms/list_search"));
    for n in [10_000u64, 1_000_000] {
        let limit = n.to_string();
        three_ways(
            c,
            "echo_calls",
            n,
            echo_calls::program(),
            echo_calls_untyped::program(),
            &echo_ir,
            &Workload {
                in_arg: Some(&limit),
                ..Workload::plain("main")
            },
            || hand_echo_calls(black_box(n as i64)),
        );
    }
    // Flat cost of (c): compiled and hand-written only, 10^4 to 10^7 calls
    // (the interpreter at 10^7 would take minutes per sample). Allocations
    // per run are printed as for the other groups.
    {
        let mut group = group(c, "echo_calls_flat", 10, 2);
        for n in [10_000u64, 100_000, 1_000_000, 10_000_000] {
            let limit = n.to_string();
            let w = Workload {
                in_arg: Some(&limit),
                ..Workload::plain("main")
            };
            let t = w.run(echo_calls::program());
            assert_eq!(t, hand_echo_calls(n as i64));
            allocations(&format!("echo_calls_flat/compiled/{n}"), || {
                w.run(echo_calls::program())
            });
            group.throughput(Throughput::Elements(t));
            group.bench_with_input(BenchmarkId::new("compiled", n), &n, |b, _| {
                b.iter(|| w.run(echo_calls::program()))
            });
            group.bench_with_input(BenchmarkId::new("hand_written", n), &n, |b, _| {
                b.iter(|| hand_echo_calls(black_box(n as i64)))
            });
        }
        group.finish();
    }
    for (rounds, len) in [
        (1_000u64, 8usize),
        (100_000, 8),
        (1_000, 256),
        (10_000, 256),
    ] {
        let names: Vec<String> = (0..len).map(|i| format!("p{i}")).collect();
        let main = format!("main({rounds}, [{}], p{})", names.join(","), len - 1);
        let syms: Vec<Sym> = (0..len as u32).map(Sym).collect();
        three_ways(
            c,
            &format!("list_search_{len}"),
            rounds,
            list_search::program(),
            list_search_untyped::program(),
            &search_ir,
            &Workload::plain(&main),
            || {
                hand_list_search(
                    black_box(rounds as i64),
                    black_box(&syms),
                    black_box(Sym(len as u32 - 1)),
                )
            },
        );
    }

    // Workloads of shapes (c) and (d) written for the caller side of native
    // DMs (other names, ints, an extra parameter, a nested call).
    let count_ir = interpreter(&root.join("dms/count_pipe"));
    for n in [10_000u64, 1_000_000] {
        let limit = n.to_string();
        three_ways(
            c,
            "count_pipe",
            n,
            count_pipe::program(),
            count_pipe_untyped::program(),
            &count_ir,
            &Workload {
                in_arg: Some(&limit),
                ..Workload::plain("main(3)")
            },
            || hand_count_pipe(black_box(n as i64), black_box(3)),
        );
    }
    let route_ir = interpreter(&root.join("dms/route_walk"));
    for (trips, len) in [(1_000u64, 8usize), (100_000, 8), (1_000, 256)] {
        let stops: Vec<String> = (0..len).map(|i| (i + 1).to_string()).collect();
        let main = format!("main({trips}, [{}], {len}, east)", stops.join(","));
        let ints: Vec<i64> = (1..=len as i64).collect();
        three_ways(
            c,
            &format!("route_walk_{len}"),
            trips,
            route_walk::program(),
            route_walk_untyped::program(),
            &route_ir,
            &Workload::plain(&main),
            || {
                hand_route_walk(
                    black_box(trips as i64),
                    black_box(&ints),
                    black_box(len as i64),
                    black_box(Sym(0)),
                )
            },
        );
    }

    // Workload (d) with the call's arguments constants: `search` runs as
    // native code (`codegen::native`).
    for (rounds, len) in [
        (1_000u64, 8usize),
        (100_000, 8),
        (1_000, 256),
        (10_000, 256),
    ] {
        let dir = format!("dms/list_search_const_{len}");
        let ir = interpreter(&root.join(&dir));
        let main = format!("main({rounds})");
        let syms: Vec<Sym> = (0..len as u32).map(Sym).collect();
        let hand = || {
            hand_list_search(
                black_box(rounds as i64),
                black_box(&syms),
                black_box(Sym(len as u32 - 1)),
            )
        };
        let name = format!("list_search_const_{len}");
        let w = Workload::plain(&main);
        if len == 8 {
            let (typed, untyped) = (
                list_search_const_8::program(),
                list_search_const_8_untyped::program(),
            );
            three_ways(c, &name, rounds, typed, untyped, &ir, &w, hand);
        } else {
            let (typed, untyped) = (
                list_search_const_256::program(),
                list_search_const_256_untyped::program(),
            );
            three_ways(c, &name, rounds, typed, untyped, &ir, &w, hand);
        }
    }

    // 10^8 transitions: typed code and the hand-written loop only (the
    // others would take minutes per sample).
    {
        let n = 100_000_000u64;
        let main = format!("main({n})");
        let w = Workload::plain(&main);
        let mut group = group(c, "counter_loop", 10, 5);
        group.throughput(Throughput::Elements(n + 1));
        group.bench_with_input(BenchmarkId::new("compiled", n), &n, |b, _| {
            b.iter(|| w.run(counter_loop::program()))
        });
        group.bench_with_input(BenchmarkId::new("hand_written", n), &n, |b, _| {
            b.iter(|| hand_counter_loop(black_box(n as i64)))
        });
        group.finish();
        // Untyped code and the interpreter: one timed run each (criterion's
        // ten samples would take minutes), with their allocations.
        if std::env::var_os("SITLOG_BENCH_SKIP_1E8").is_none() {
            let resolved = Resolved::new(&counter_ir);
            let once = |label: &str, f: &dyn Fn() -> u64| {
                let start = std::time::Instant::now();
                let t = f();
                let ns = start.elapsed().as_nanos() as f64 / t as f64;
                println!(
                    "counter_loop/{label}/{n}: one run, {t} transitions, {ns:.2} ns per transition"
                );
            };
            let untyped = || w.run(counter_loop_untyped::program());
            let interp = || w.run(&resolved);
            once("compiled_untyped", &untyped);
            once("interpreter", &interp);
            allocations(&format!("counter_loop/compiled_untyped/{n}"), untyped);
            allocations(&format!("counter_loop/interpreter/{n}"), interp);
        }
    }

    // The counter loop whose actions are performed: an `Actions` that does
    // not ignore numbers gets each `inc`'s value (one dynamic call per
    // transition, which also keeps the optimiser from folding the typed
    // loop); the hand-written loop calls a `dyn FnMut(i64)` the same way.
    for n in [10_000u64, 1_000_000] {
        let main = format!("main({n})");
        let mut group = group(c, "counter_loop_performed", 10, 3);
        group.throughput(Throughput::Elements(n + 1));
        let t = run_performing(counter_loop::program(), &main);
        assert_eq!(t.1, n);
        group.bench_with_input(BenchmarkId::new("compiled", n), &n, |b, _| {
            b.iter(|| run_performing(counter_loop::program(), &main))
        });
        group.bench_with_input(BenchmarkId::new("compiled_untyped", n), &n, |b, _| {
            b.iter(|| run_performing(counter_loop_untyped::program(), &main))
        });
        let resolved = Resolved::new(&counter_ir);
        group.bench_with_input(BenchmarkId::new("interpreter", n), &n, |b, _| {
            b.iter(|| run_performing(&resolved, &main))
        });
        group.bench_with_input(BenchmarkId::new("hand_written", n), &n, |b, _| {
            b.iter(|| {
                let mut sum = 0i64;
                let mut sink = |x: i64| sum = sum.wrapping_add(x);
                let sink: &mut dyn FnMut(i64) = black_box(&mut sink);
                let t = hand_counter_loop_performing(black_box(n as i64), sink);
                black_box(sum);
                t
            })
        });
        group.finish();
    }

    let app = root.join("../dms/examples/appendix_a");
    let appendix_ir = interpreter(&app);
    let script = std::fs::read_to_string(app.join("script.txt")).expect("script");
    let functions = || {
        let mut f = Functions::standard();
        sitlog_tests::appendix_a_functions(&mut f);
        f
    };
    let w = Workload {
        script: &script,
        keep_history: true,
        ..Workload::plain("main")
    };
    let mut group = group(c, "appendix_a", 20, 3);
    let t = w.run_with(appendix_a::program(), functions());
    group.throughput(Throughput::Elements(t));
    group.bench_function("compiled", |b| {
        b.iter(|| w.run_with(appendix_a::program(), functions()))
    });
    let appendix_resolved = Resolved::new(&appendix_ir);
    group.bench_function("interpreter", |b| {
        b.iter(|| w.run_with(&appendix_resolved, functions()))
    });
    group.bench_function("interpreter_templates", |b| {
        b.iter(|| w.run_with(&appendix_ir, functions()))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
