//! Helper `nplain20` (issue 37): plain Prolog user functions called by
//! native code on the values it holds (`Cx::nat_plain`,
//! `tests/typed/nplain20`): a next situation that is a function's value
//! (`hop/2`, `tick/1`), a condition `apply(..) == yes` (`check/2`,
//! `weigh/1`, whose function is an if-then-else). The
//! compiled task and the interpreter's plans, plain forms run natively,
//! give what the interpreter gives with every call a query of the engine;
//! the compiled task what the interpreter gives without history. The
//! calls the native form refuses go to the term path: an argument not
//! ground, a float, an improper list, a compound L evaluates
//! (`get(x, y)`), an overflow, a type error, a function that fails, one
//! that assigns nothing, a value no situation has.
//!
//! Not here: a value holding an improper list (`walk([[x|y], c])`): the
//! engine fails such a call and stops (`typed::plain_compounds`' doc).

use super::{interpreter, run, unnumbered, ENGINE};
use sitlog_compiler::interp::Resolved;
use sitlog_runtime::Functions;

mod dms {
    pub mod nplain20 {
        sitlog_macros::include_dm!("typed/nplain20");
    }
}

const MAINS: &[&str] = &[
    "hop([a, b, c], c)",
    "hop([a, b], z)",
    "hop([], c)",
    "hop([a, skip, c], c)",
    "hop([a, stop, c], c)",
    "hop([f(x), [1, 2], g(1)], g(1))",
    "hop([a, boom, c], c)",
    "hop([a, quiet], z)",
    "hop([a, lost], z)",
    "hop([a, _, c], c)",
    "hop([1, 1.0], 1.0)",
    "hop([a|b], z)",
    "hop([a, get(x, y), c], c)",
    "hop([a, b], _)",
    "check([a, b, c], c)",
    "check([a, b], z)",
    "check([num, b], b)",
    "check([a, boom], z)",
    "check([a, quiet], z)",
    "check([a, _, c], c)",
    "check([1.5, b], b)",
    "check([a, [x|y]], z)",
    "check([get(x, y)], z)",
    "tick(0)",
    "tick(9223372036854775806)",
    "tick(9223372036854775807)",
    "tick(a)",
    "tick(1.5)",
    "weigh([5, 1200, 7])",
    "weigh([5, 7])",
    "weigh([5, 13, 2000])",
    "weigh([5, -1])",
    "weigh([5, a])",
    "weigh([5, 1000.0])",
    "weigh([5, _])",
];

#[test]
fn nplain20_plain_functions_on_native_values_agree() {
    let set = |p: &sitlog_runtime::prolog::PrologFunctions, engine_only: bool| {
        ENGINE.with(|e| *e.borrow_mut() = Some((p.clone(), engine_only)))
    };
    let ir = interpreter("typed/nplain20");
    let resolved = Resolved::new(&ir);
    let mut f = Functions::standard();
    let p = sitlog_compiler::run::install_prolog(&ir, &mut f, Default::default())
        .expect("the Prolog files load")
        .expect("an engine");
    let names: Vec<String> = p
        .plain_functions()
        .iter()
        .map(|(n, a)| format!("{n}/{a}"))
        .collect();
    assert_eq!(names.join(" "), "bump/1 heavy/1 is_at/2 next_of/3");
    let compiled = dms::nplain20::program();
    for main in MAINS {
        set(&p, true);
        let by_engine = run(&ir, main, "", true, true, false);
        set(&p, false);
        let c = run(compiled, main, "", true, true, false);
        let i = run(&resolved, main, "", true, true, false);
        let by_engine = unnumbered(format!("{by_engine:?}"));
        assert_eq!(
            unnumbered(format!("{c:?}")),
            by_engine,
            "{main}: compiled / engine only"
        );
        assert_eq!(
            unnumbered(format!("{i:?}")),
            by_engine,
            "{main}: plans / engine only"
        );
        let c = run(compiled, main, "", false, false, false);
        let i = run(&ir, main, "", false, false, false);
        assert_eq!(
            unnumbered(format!("{c:?}")),
            unnumbered(format!("{i:?}")),
            "{main}: compiled / interpreter, no history"
        );
        let c = run(compiled, main, "", false, true, false);
        let i = run(&ir, main, "", false, true, false);
        assert_eq!(
            unnumbered(format!("{c:?}")),
            unnumbered(format!("{i:?}")),
            "{main}: compiled / interpreter, observed, no history"
        );
    }
    ENGINE.with(|e| *e.borrow_mut() = None);
}
