//! Arbitrary bytes as `user_functions.pl`: read by our reader, loaded into
//! the embedded engine; every function it defines is called once with an
//! atom, under small limits. Never a panic (load errors and call errors are
//! outcomes). Slow: each input starts an engine.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sitlog_runtime::functions::{CallLimits, FnCall};
use sitlog_runtime::prolog::{PrologFunctions, PrologOptions, PrologSource};
use sitlog_runtime::{Atom, Functions, Store, Term, Vars};
use std::time::Duration;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = sitlog_syntax::decode(data) else {
        return;
    };
    let options = PrologOptions {
        inference_limit: 100_000,
        time_limit: Duration::from_millis(200),
        heap_limit: 64 << 20,
    };
    let Ok(engine) = PrologFunctions::load(&[PrologSource::new("user_functions.pl", text)], options)
    else {
        return;
    };
    let mut functions = Functions::standard();
    functions.set_call_limits(CallLimits {
        inferences: 100_000,
        time: Duration::from_millis(200),
        heap_bytes: 64 << 20,
    });
    engine.install(&mut functions);
    let mut store = Store::new();
    let (mut locals, mut globals) = (Vars::default(), Vars::default());
    for name in ["f", "g", "p", "a", "grow"] {
        for arity in 0..3 {
            let name = Atom::intern(name);
            if !engine.defines(name, arity) {
                continue;
            }
            let args: Vec<Term> = (0..arity).map(|_| Term::atom(Atom::intern("x"))).collect();
            let mut call = FnCall {
                store: &mut store,
                locals: &mut locals,
                globals: &mut globals,
                history: &[],
                functions: &functions,
            };
            let _ = engine.call(&mut call, name, &args);
        }
    }
});
