//! Helper `nnext23` (issue 37): a plain function compiled to Rust whose
//! clauses answer compounds answers them by their parts
//! (`plain_rs::Ans<k>`), and native code selects the next situation from
//! the parts without building the compound (`tests/typed/nnext23`): a
//! compound of one part and of two, parts that are arguments, list tails
//! taken apart in the head and values built, an atom, a failing clause,
//! an atom and a compound naming no situation of the DM, the last
//! assignment reached, a compound in a condition (never the constant) and
//! as an out_arg's value. The compiled task and the interpreter's plans
//! give what the interpreter gives with every call a query of the engine;
//! run with an engine of other definitions (`tests/typed/nnext23_other`)
//! the compiled task takes the path not compiled for every function whose
//! form differs and agrees with the interpreter of those definitions.

use super::{interpreter, run, unnumbered, ENGINE};
use sitlog_compiler::interp::Resolved;
use sitlog_runtime::{Atom, Functions};

mod dms {
    pub mod nnext23 {
        sitlog_macros::include_dm!("typed/nnext23");
    }
}

const MAINS: &[&str] = &[
    "walk([a, b, c], c)",
    "walk([a, b, c], z)",
    "walk([], z)",
    "walk([a, mark, c], z)",
    "walk([a, pair, c], z)",
    "walk([num, a, b], b)",
    "walk([num], b)",
    "walk([low, a], a)",
    "walk([a, stop, c], c)",
    "walk([a, odd, c], c)",
    "walk([a, zz, c], c)",
    "walk([a, f(b), c], f(b))",
    "walk([a, [x, y]], [x, y])",
    "walk([a, 1.5], z)",
    "walk([a|b], z)",
    "walk([a, _], z)",
    "scan([a, b, c], b)",
    "scan([a, b], z)",
    "scan([a, halt, b], b)",
    "scan([], a)",
    "scan([a|b], z)",
    "sort_of(3)",
    "sort_of(50)",
    "sort_of(500)",
    "sort_of(a)",
    "pack(7)",
    "pack(hi)",
];

/// Every main of [`MAINS`]: the compiled task against the interpreter of
/// `ir` (the engine `p`'s application), as `nrs22`'s test compares them.
fn agree(ir: &sitlog_compiler::ir::Ir, p: &sitlog_runtime::prolog::PrologFunctions, what: &str) {
    let set = |engine_only: bool| ENGINE.with(|e| *e.borrow_mut() = Some((p.clone(), engine_only)));
    // The compiled task's places are `tests/typed/nnext23`'s.
    let same = |s: String| unnumbered(s).replace("typed/nnext23_other/", "typed/nnext23/");
    let resolved = Resolved::new(ir);
    let compiled = dms::nnext23::program();
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

/// The engine of `app`'s Prolog files.
fn engine(
    app: &str,
) -> (
    sitlog_compiler::ir::Ir,
    sitlog_runtime::prolog::PrologFunctions,
) {
    let ir = interpreter(app);
    let mut f = Functions::standard();
    let p = sitlog_compiler::run::install_prolog(&ir, &mut f, Default::default())
        .expect("the Prolog files load")
        .expect("an engine");
    (ir, p)
}

/// Which compiled functions the engine `p` runs as compiled.
fn resolved(p: &sitlog_runtime::prolog::PrologFunctions) -> Vec<String> {
    use dms::nnext23::plain_rs as k;
    let mut f = Functions::standard();
    p.install(&mut f);
    [
        ("hop", 3, k::FORM0),
        ("next", 2, k::FORM1),
        ("kind", 1, k::FORM2),
        ("wrap", 1, k::FORM3),
    ]
    .iter()
    .filter(|(n, a, form)| f.resolve_compiled(Atom::intern(n), *a, form).is_some())
    .map(|(n, a, _)| format!("{n}/{a}"))
    .collect()
}

#[test]
fn nnext23_next_situations_from_answers_agree() {
    let (ir, p) = engine("typed/nnext23");
    assert_eq!(resolved(&p).join(" "), "hop/3 next/2 kind/1 wrap/1");
    agree(&ir, &p, "nnext23");
}

#[test]
fn nnext23_an_engine_of_other_definitions_takes_the_path_not_compiled() {
    let (ir, p) = engine("typed/nnext23_other");
    // `next/2` is not plain there; `hop/3` and `wrap/1` are other forms.
    assert_eq!(resolved(&p).join(" "), "kind/1");
    agree(&ir, &p, "nnext23_other");
}

/// Each compiled function called directly answers what the engine's
/// plain form gives on the same values (its compound by its parts, built
/// by `Ans<k>::val`), and a compound answer is not built: its variant
/// holds the argument itself.
#[test]
fn nnext23_answers_are_the_plain_forms_values() {
    use dms::nnext23::plain_rs as k;
    use sitlog_runtime::native::{List, Val};
    use sitlog_runtime::{Store, Vars};
    let (_, p) = engine("typed/nnext23");
    let mut f = Functions::standard();
    p.install(&mut f);
    f.start().expect("the engine starts");
    let atoms = &dms::nnext23::program().atoms;
    let sym = |s: &str| Val::Sym(Atom::intern(s));
    let list = |xs: Vec<Val>| Val::List(List::from_vec(xs));
    let rest = list(vec![sym("b"), sym("c")]);
    let (store, globals) = (Store::new(), Vars::default());
    let mut ran = 0;
    for x in ["a", "c", "stop", "odd", "zz", "mark", "pair", "num", "low"] {
        let args = [sym(x), rest.clone(), sym("c")];
        let by_form = f.call_native(&store, &globals, Atom::intern("hop"), &args);
        let by_rust = k::p0_hop_3(atoms, [&args[0], &args[1], &args[2]]);
        // `step(Xs)` and `at(X, Xs)`: the arguments themselves.
        match (&by_rust, x) {
            (Some(k::Ans0::V4(xs)), "a") => assert!(std::ptr::eq(*xs, &args[1])),
            (Some(k::Ans0::V1(h, xs)), "c") => {
                assert!(std::ptr::eq(*h, &args[0]) && std::ptr::eq(*xs, &args[1]))
            }
            _ => {}
        }
        let by_rust = by_rust.map(|v| v.val(atoms));
        assert_eq!(format!("{by_rust:?}"), format!("{by_form:?}"), "hop({x})");
        ran += usize::from(by_rust.is_some());
    }
    assert_eq!(ran, 8, "calls of hop/3 with a value");
    for (items, t) in [
        (vec![], "a"),
        (vec![sym("a"), sym("b")], "a"),
        (vec![sym("a"), sym("b")], "z"),
        (vec![sym("halt"), sym("b")], "z"),
    ] {
        let args = [list(items), sym(t)];
        let by_form = f.call_native(&store, &globals, Atom::intern("next"), &args);
        let by_rust = k::p1_next_2(atoms, [&args[0], &args[1]]).map(|v| v.val(atoms));
        assert_eq!(
            format!("{by_rust:?}"),
            format!("{by_form:?}"),
            "next{args:?}"
        );
        assert!(by_rust.is_some());
    }
    for x in [Val::Int(3), Val::Int(50), Val::Int(500), sym("a")] {
        let by_form = f.call_native(
            &store,
            &globals,
            Atom::intern("kind"),
            std::slice::from_ref(&x),
        );
        let by_rust = k::p2_kind_1(atoms, [&x]).map(|v| v.val(atoms));
        assert_eq!(
            format!("{by_rust:?}"),
            format!("{by_form:?}"),
            "kind({x:?})"
        );
    }
}
