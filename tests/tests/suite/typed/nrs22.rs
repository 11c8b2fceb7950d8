//! Helper `nrs22` (issue 37): plain Prolog user functions compiled to Rust
//! (`codegen::native::plain_rs`), called by native code through
//! `Cx::nat_plain_rs` (`tests/typed/nrs22`): several clauses, guards, a
//! cut then `fail`, a cut inside an if-then-else then a failure, `is`
//! with an overflow, a type error and a division by zero, list head
//! patterns, a value built of the rest, the last assignment winning, `=`
//! and `\==`, compound head patterns, a function that fails, one that is
//! not plain, an out_arg. The compiled task and the interpreter's plans,
//! plain forms native, give what the interpreter gives with every call a
//! query of the engine; the compiled task what the interpreter gives
//! without history. Run with an engine that holds other definitions
//! (`tests/typed/nrs22_other`: other plain forms, one not plain, one the
//! same), the compiled task takes the present path for every function
//! whose form differs and gives what the interpreter of those
//! definitions gives.

use super::{interpreter, run, unnumbered, ENGINE};
use sitlog_compiler::interp::Resolved;
use sitlog_runtime::{Atom, Functions};

mod dms {
    pub mod nrs22 {
        sitlog_macros::include_dm!("typed/nrs22");
    }
}

const MAINS: &[&str] = &[
    "cls(-5)",
    "cls(0)",
    "cls(5)",
    "cls(4)",
    "cls(13)",
    "cls(12)",
    "cls(21)",
    "cls(2000000)",
    "cls(4000000000)",
    "cls(9223372036854775807)",
    "cls(a)",
    "cls(1.5)",
    "scan([a, b, c], c)",
    "scan([a, c, b], c)",
    "scan([skip, b], z)",
    "scan([], a)",
    "scan([a, b], z)",
    "scan([f(1), [x]], [x])",
    "scan([a, 1.5], z)",
    "scan([a|b], z)",
    "scan([a, _], z)",
    "calc(3, 10)",
    "calc(-8, 2)",
    "calc(5, 5)",
    "calc(a, 1)",
    "calc(-9223372036854775807, 9223372036854775807)",
    "shape(rect(3, 4))",
    "shape(sq(4))",
    "shape(circle(1))",
    "shape(rect(a, 2))",
    "shape(sq(3037000500))",
    "ratio(9, 3)",
    "ratio(10, 3)",
    "ratio(-10, 3)",
    "ratio(1, 0)",
    "ratio(a, 1)",
    "never(1)",
    "wrap(hello)",
    "wrap(5)",
    "pump(1)",
    "pump(99)",
    "pump(a)",
];

/// Every main of [`MAINS`]: the compiled task against the interpreter of
/// `ir` (the engine `p`'s application), as `nfnc21`'s test compares them.
fn agree(ir: &sitlog_compiler::ir::Ir, p: &sitlog_runtime::prolog::PrologFunctions, what: &str) {
    let set = |engine_only: bool| ENGINE.with(|e| *e.borrow_mut() = Some((p.clone(), engine_only)));
    // The compiled task's places are `tests/typed/nrs22`'s.
    let same = |s: String| unnumbered(s).replace("typed/nrs22_other/", "typed/nrs22/");
    let resolved = Resolved::new(ir);
    let compiled = dms::nrs22::program();
    for main in MAINS {
        set(true);
        let by_engine = run(ir, main, "", true, true, false);
        set(false);
        let c = run(compiled, main, "", true, true, false);
        let i = run(&resolved, main, "", true, true, false);
        let by_engine = same(format!("{by_engine:?}"));
        assert_eq!(
            same(format!("{c:?}")),
            by_engine,
            "{what} {main}: compiled / engine only"
        );
        assert_eq!(
            same(format!("{i:?}")),
            by_engine,
            "{what} {main}: plans / engine only"
        );
        let c = run(compiled, main, "", false, false, false);
        let i = run(ir, main, "", false, false, false);
        assert_eq!(
            same(format!("{c:?}")),
            same(format!("{i:?}")),
            "{what} {main}: compiled / interpreter, no history"
        );
    }
    ENGINE.with(|e| *e.borrow_mut() = None);
}

/// Which compiled functions the engine `p` runs as compiled.
fn resolved(p: &sitlog_runtime::prolog::PrologFunctions) -> Vec<String> {
    use dms::nrs22::plain_rs as k;
    let mut f = Functions::standard();
    p.install(&mut f);
    [
        ("classify", 1, k::FORM0),
        ("pick", 2, k::FORM1),
        ("diff", 2, k::FORM2),
        ("area", 1, k::FORM3),
        ("quot", 2, k::FORM4),
        ("nope", 1, k::FORM5),
        ("step", 1, k::FORM6),
    ]
    .iter()
    .filter(|(n, a, form)| f.resolve_compiled(Atom::intern(n), *a, form).is_some())
    .map(|(n, a, _)| format!("{n}/{a}"))
    .collect()
}

#[test]
fn nrs22_compiled_plain_functions_agree() {
    let ir = interpreter("typed/nrs22");
    let mut f = Functions::standard();
    let p = sitlog_compiler::run::install_prolog(&ir, &mut f, Default::default())
        .expect("the Prolog files load")
        .expect("an engine");
    let names: Vec<String> = p
        .plain_functions()
        .iter()
        .map(|(n, a)| format!("{n}/{a}"))
        .collect();
    assert_eq!(
        names.join(" "),
        "area/1 classify/1 diff/2 nope/1 pick/2 quot/2 step/1"
    );
    assert_eq!(
        resolved(&p).join(" "),
        "classify/1 pick/2 diff/2 area/1 quot/2 nope/1 step/1"
    );
    agree(&ir, &p, "nrs22");
}

#[test]
fn nrs22_an_engine_of_other_definitions_takes_the_present_path() {
    let ir = interpreter("typed/nrs22_other");
    let mut f = Functions::standard();
    let p = sitlog_compiler::run::install_prolog(&ir, &mut f, Default::default())
        .expect("the Prolog files load")
        .expect("an engine");
    // `pick/2` is not plain there; `classify/1`, `area/1`, `nope/1` and
    // `step/1` are other forms: only `diff/2` and `quot/2` run as compiled.
    assert_eq!(resolved(&p).join(" "), "diff/2 quot/2");
    agree(&ir, &p, "nrs22_other");
    // Every call a query: nothing runs as compiled.
    let mut f = Functions::standard();
    p.install_with(&mut f, false);
    assert!(f
        .resolve_compiled(Atom::intern("diff"), 2, dms::nrs22::plain_rs::FORM2)
        .is_none());
}

/// Each compiled function called directly gives what the engine's plain
/// form gives on the same values (`Functions::call_native`: `Some` exactly
/// where it runs the call natively, the same value), refusals included.
#[test]
fn nrs22_each_compiled_function_is_its_plain_form() {
    use dms::nrs22::plain_rs as k;
    use sitlog_runtime::native::{Compound, List, Val};
    use sitlog_runtime::{Store, Vars};
    let ir = interpreter("typed/nrs22");
    let mut f = Functions::standard();
    sitlog_compiler::run::install_prolog(&ir, &mut f, Default::default())
        .expect("the Prolog files load")
        .expect("an engine");
    f.start().expect("the engine starts");
    let atoms = &dms::nrs22::program().atoms;
    let sym = |s: &str| Val::Sym(Atom::intern(s));
    let c = |s: &str, args: Vec<Val>| Val::Tagged(Compound::new(Atom::intern(s), args));
    let list = |xs: Vec<Val>| Val::List(List::from_vec(xs));
    let i = Val::Int;
    // Each called on its arguments by reference, a compound answered by
    // its parts built (`Ans<k>::val`).
    type Compiled = fn(&dms::nrs22::Atoms, &[Val]) -> Option<Val>;
    let cases: Vec<(&str, Compiled, Vec<Vec<Val>>)> = vec![
        (
            "classify",
            (|a, v| k::p0_classify_1(a, [&v[0]]).map(|x| x.val(a))) as Compiled,
            [
                i(-5),
                i(0),
                i(5),
                i(4),
                i(13),
                i(12),
                i(21),
                i(2_000_000),
                i(4_000_000_000),
                i(i64::MAX),
                sym("a"),
                Val::Float(1.5),
                list(vec![i(1)]),
                c("f", vec![i(1)]),
            ]
            .into_iter()
            .map(|v| vec![v])
            .collect(),
        ),
        (
            "pick",
            (|a, v| k::p1_pick_2(a, [&v[0], &v[1]]).map(|x| x.val(a))) as Compiled,
            vec![
                vec![list(vec![sym("a"), sym("b"), sym("c")]), sym("c")],
                vec![list(vec![sym("c"), sym("b")]), sym("c")],
                vec![list(vec![sym("a"), sym("c"), sym("b")]), sym("c")],
                vec![list(vec![sym("skip"), sym("b")]), sym("z")],
                vec![list(vec![]), sym("a")],
                vec![
                    list(vec![c("f", vec![i(1)]), list(vec![sym("x")])]),
                    list(vec![sym("x")]),
                ],
                vec![sym("a"), sym("a")],
                vec![list(vec![sym("a")]), i(1)],
                vec![list(vec![sym("a"), Val::Float(0.5)]), i(1)],
            ],
        ),
        (
            "diff",
            (|a, v| k::p2_diff_2(a, [&v[0], &v[1]]).map(|x| x.val(a))) as Compiled,
            vec![
                vec![i(3), i(10)],
                vec![i(-8), i(2)],
                vec![i(5), i(5)],
                vec![sym("a"), i(1)],
                vec![sym("a"), sym("a")],
                vec![i(i64::MIN + 1), i(i64::MAX)],
                vec![i(i64::MIN), i(0)],
            ],
        ),
        (
            "area",
            (|a, v| k::p3_area_1(a, [&v[0]])) as Compiled,
            [
                c("rect", vec![i(3), i(4)]),
                c("sq", vec![i(4)]),
                c("circle", vec![i(1)]),
                c("rect", vec![sym("a"), i(2)]),
                c("sq", vec![i(3_037_000_500)]),
                sym("sq"),
                c("rect", vec![i(1)]),
            ]
            .into_iter()
            .map(|v| vec![v])
            .collect(),
        ),
        (
            "quot",
            (|a, v| k::p4_quot_2(a, [&v[0], &v[1]])) as Compiled,
            vec![
                vec![i(9), i(3)],
                vec![i(10), i(3)],
                vec![i(-10), i(3)],
                vec![i(1), i(0)],
                vec![sym("a"), i(1)],
                vec![i(i64::MIN), i(-1)],
            ],
        ),
        (
            "nope",
            (|a, v| k::p5_nope_1(a, [&v[0]])) as Compiled,
            vec![vec![i(1)]],
        ),
        (
            "step",
            (|a, v| k::p6_step_1(a, [&v[0]])) as Compiled,
            [i(1), i(99), i(100), sym("a"), i(i64::MAX)]
                .into_iter()
                .map(|v| vec![v])
                .collect(),
        ),
    ];
    let (store, globals) = (Store::new(), Vars::default());
    let mut ran = 0;
    for (name, compiled, calls) in cases {
        for args in calls {
            let by_form = f.call_native(&store, &globals, Atom::intern(name), &args);
            // The compiled function runs on what the form takes (the
            // slot checks the arguments first: `plain::rt::args_sure`).
            let by_rust = if sitlog_runtime::plain::rt::args_sure(&args) {
                compiled(atoms, &args)
            } else {
                None
            };
            // A function compiled on integers answers `None` where a float
            // reaches its arithmetic; `Cx::nat_plain_rs` then asks the
            // form (helper `nfloat25`): the answer the call site sees.
            let floats = args.iter().any(|a| matches!(a, Val::Float(_)));
            let by_rust = if by_rust.is_none() && floats {
                by_form.clone()
            } else {
                by_rust
            };
            assert_eq!(
                format!("{by_rust:?}"),
                format!("{by_form:?}"),
                "{name}{args:?}"
            );
            ran += usize::from(by_rust.is_some());
        }
    }
    // 30: `classify(1.5)` runs on the form since floats are taken (nfloat25).
    assert_eq!(ran, 30, "calls with a value");
}
