//! The home butler (`dms/apps/home`) as a user runs it, and the two costs of
//! the simulated robot that such a run is made of:
//! - `home/interpreted` (`sitlogc run`'s interpreter: plans, the program
//!   checked and lowered in the run), `home/compiled`: one whole run on the app's world
//!   (Prolog engine start, KB, sim world built and settled, 260-odd
//!   transitions, the transcript written to a buffer);
//! - `home/prolog_start`: the Prolog engine with the app's files alone;
//!   `home/interpreted_run_only`, `home/compiled_run_only`: the run once
//!   the engine is there (and, interpreted, the program checked and lowered);
//! - `sim/new`: reading nothing, building the physics world of the home and
//!   settling every object on its shelf;
//! - `sim/see`: one look at the drinks shelf (a shape-intersection query and
//!   a ray per object);
//! - `sim/place`: putting a held object on a shelf and settling it.
//!
//! `cargo bench -p sitlog-benches --bench scenario`.

use criterion::{black_box, criterion_group, criterion_main, BatchSize, Criterion};
use sitlog_compiler::interp::Resolved;
use sitlog_sim::{Hand, Sim, World};
use sitlog_tests::compiled::generated::apps_home;
use sitlog_tests::scenario::{assets, execute, interpreter};
use std::path::{Path, PathBuf};
use std::time::Duration;

fn app() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../dms/apps/home")
}

fn home(c: &mut Criterion) {
    let world = std::fs::read_to_string(app().join("world.toml")).expect("the home world");
    let assets = assets(&app(), &world, None);
    let mut g = c.benchmark_group("home");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    g.bench_function("interpreted", |b| {
        b.iter(|| {
            let (ir, functions) = interpreter(&app());
            let run = execute(&Resolved::new(&ir), functions, &assets);
            assert_eq!(run.code, 0);
            black_box(run.transcript.len())
        })
    });
    g.bench_function("compiled", |b| {
        b.iter(|| {
            let functions = apps_home::functions().expect("Prolog loads");
            let run = execute(apps_home::program(), functions, &assets);
            assert_eq!(run.code, 0);
            black_box(run.transcript.len())
        })
    });
    // What a whole run is made of: the Prolog engine with the app's files,
    // and the run itself once the engine is there (the program checked
    // and lowered beforehand on the interpreter).
    g.bench_function("prolog_start", |b| {
        b.iter(|| black_box(apps_home::functions().expect("Prolog loads")))
    });
    g.bench_function("interpreted_run_only", |b| {
        b.iter_batched(
            || interpreter(&app()),
            |(ir, functions)| {
                let run = execute(&Resolved::new(&ir), functions, &assets);
                assert_eq!(run.code, 0);
                black_box(run.transcript.len())
            },
            BatchSize::PerIteration,
        )
    });
    g.bench_function("compiled_run_only", |b| {
        b.iter_batched(
            || apps_home::functions().expect("Prolog loads"),
            |functions| {
                let run = execute(apps_home::program(), functions, &assets);
                assert_eq!(run.code, 0);
                black_box(run.transcript.len())
            },
            BatchSize::PerIteration,
        )
    });
    g.finish();
}

fn sim(c: &mut Criterion) {
    let world = World::load(&app().join("world.toml")).expect("the home world");
    let mut g = c.benchmark_group("sim");
    g.bench_function("new", |b| b.iter(|| black_box(Sim::new(&world, 0))));
    let at_fridge = || {
        let mut s = Sim::new(&world, 0);
        s.navigate("shelf_drinks").expect("a route to the fridge");
        s
    };
    g.bench_function("see", |b| {
        b.iter_batched_ref(at_fridge, |s| black_box(s.see()), BatchSize::LargeInput)
    });
    let holding = || {
        let mut s = at_fridge();
        s.grasp("malz", Hand::Left).expect("malz is there");
        s
    };
    g.bench_function("place", |b| {
        b.iter_batched_ref(
            holding,
            |s| black_box(s.place(Hand::Left)).is_ok(),
            BatchSize::LargeInput,
        )
    });
    g.finish();
}

criterion_group!(benches, sim, home);
criterion_main!(benches);
