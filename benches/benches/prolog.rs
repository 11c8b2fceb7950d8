//! Prolog user functions: per-call overhead of a trivial function in the
//! embedded engine against the same function in Rust, and engine start-up.
//! `cargo bench -p sitlog-benches --bench prolog`.

use criterion::{criterion_group, criterion_main, Criterion};
use sitlog_runtime::eval::{eval, EvalCtx};
use sitlog_runtime::prolog::{PrologFunctions, PrologOptions, PrologSource};
use sitlog_runtime::{Functions, Store, Vars};

const PL: &str = "echo(X) :- assign_func_value(X).\n\
                  getday(_) :- var_op(get(day, D)), assign_func_value(D).\n";

fn call(c: &mut Criterion, group: &str, functions: &Functions) {
    let mut store = Store::new();
    let (expr, _) = store.parse("apply(echo(X), [hello])").unwrap();
    let (get, _) = store.parse("apply(getday(X), [_])").unwrap();
    store.freeze();
    let mut locals = Vars::from_entries(vec![(
        sitlog_runtime::Atom::intern("day"),
        sitlog_runtime::Term::atom(sitlog_runtime::Atom::intern("monday")),
    )]);
    let mut globals = Vars::new();
    let history = Vec::new();
    let mut g = c.benchmark_group(group);
    for (name, t) in [("echo", expr), ("var_op_get", get)] {
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut ctx = EvalCtx {
                    store: &mut store,
                    locals: &mut locals,
                    globals: &mut globals,
                    history: &history,
                    functions,
                };
                eval(&mut ctx, t).unwrap()
            })
        });
    }
    g.finish();
}

fn benches(c: &mut Criterion) {
    let mut rust = Functions::standard();
    rust.register("echo", 1, |_, args| Ok(args[0]));
    rust.register("getday", 1, |call, _| {
        let get = call.store.parse("get(day, D)").map_err(|e| e.message)?.0;
        call.var_op(get)
    });
    call(c, "user_function_rust", &rust);

    let prolog = PrologFunctions::load(&[PrologSource::new("uf.pl", PL)], PrologOptions::default())
        .expect("loads");
    let mut pf = Functions::standard();
    prolog.install(&mut pf);
    call(c, "user_function_prolog", &pf);

    let mut g = c.benchmark_group("prolog_startup");
    g.sample_size(10);
    g.bench_function("load_engine_and_prelude", |b| {
        b.iter(|| {
            PrologFunctions::load(&[PrologSource::new("uf.pl", PL)], PrologOptions::default())
                .unwrap()
        })
    });
    g.finish();
}

criterion_group!(prolog, benches);
criterion_main!(prolog);
