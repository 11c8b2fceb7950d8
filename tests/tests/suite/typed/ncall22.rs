//! Helper `ncall22` (issue 37): calls whose arguments are evaluated, pushed
//! natively by DMs without locals (`tests/typed/ncall22`): the call
//! evaluated once, read-only, its arguments converted to the callee's
//! frame, the waiting variant holding the evaluated call. `get` of a
//! global the callee changes, `apply` of a function with a side effect
//! (one call, also where its value does not convert and the machine makes
//! the call), arithmetic that fails, an output argument, two held calls in
//! a row. The callees hand over while they run (`hand/1` is not plain),
//! so the waiting caller becomes the machine's (`Cx::wait_held`). Each task
//! agrees with the interpreter in the compiled task and the plans (history,
//! report, error, actions, observer, with and without history).

use super::{agree_both, interpreter, run, ENGINE};
use sitlog_runtime::Functions;

mod dms {
    pub mod ncall22 {
        sitlog_macros::include_dm!("typed/ncall22", held);
    }
}

/// The application's Prolog user functions loaded once, installed in
/// every run of this thread (each task starts with `reset/1`).
fn engine(ir: &sitlog_compiler::ir::Ir) {
    let mut f = Functions::standard();
    let p = sitlog_compiler::run::install_prolog(ir, &mut f, Default::default())
        .expect("the Prolog files load")
        .expect("an engine");
    ENGINE.with(|e| *e.borrow_mut() = Some((p, false)));
}

/// Each task in the compiled task and the plans as in the interpreter.
fn agree(mains: &[&str]) {
    let ir = interpreter("typed/ncall22");
    engine(&ir);
    agree_both(dms::ncall22::program(), &ir, mains);
    ENGINE.with(|e| *e.borrow_mut() = None);
}

/// The compiled task's report (history kept: its final situation).
fn report(main: &str) -> String {
    engine(&interpreter("typed/ncall22"));
    let r = run(dms::ncall22::program(), main, "", true, false, false);
    ENGINE.with(|e| *e.borrow_mut() = None);
    format!("{r:?}")
}

/// `up(get(g, _))`: the callee sets `g` and hands over; it adds one to
/// the value read at the call; the exit arc reads `g` as the callee left it.
#[test]
fn ncall22_a_global_the_callee_changes_agrees() {
    agree(&[
        "tint(5)",
        "tint(-1)",
        "tint(a)",
        "tint(_)",
        "tint(f(_))",
        "tint(1.5)",
    ]);
    let r = report("tint(5)");
    assert!(r.contains("stop(6,1,up)"), "{r}");
}

/// `len(get(g, _), x)`, `yn(get(g, _), W)` (an output argument the exit
/// arc reads): lists, atoms, values the callee does not take.
#[test]
fn ncall22_lists_atoms_and_outputs_agree() {
    agree(&[
        "tlist([a,b,c])",
        "tlist([])",
        "tlist(a)",
        "tlist([a|_])",
        "tlist(_)",
    ]);
    agree(&[
        "tatom(yes)",
        "tatom(no)",
        "tatom(3)",
        "tatom(f(_))",
        "tatom(_)",
    ]);
}

/// `up(apply(same(_), [S]))`: `same/1` called once, whatever the
/// hand-over in the callee; `keep(apply(tally(_), [S]))` where the value
/// is not ground (it does not convert: the machine's call with the
/// evaluated term, `tally/1` not called again).
#[test]
fn ncall22_an_apply_with_a_side_effect_is_called_once() {
    agree(&[
        "side(3)",
        "side(a)",
        "side(_)",
        "loose(s)",
        "loose(_)",
        "loose(f(_))",
    ]);
    let r = report("side(3)");
    assert!(r.contains("stop(4,2,2/[3,hand(3)])"), "{r}");
    let r = report("loose(_)");
    assert!(r.contains(",2,2/["), "{r}");
}

/// `up(_ is K * 3)`: a value, an atom, unbound, an overflow (errors the
/// machine's call reports, the frames handed over first).
#[test]
fn ncall22_an_evaluation_that_fails_agrees() {
    agree(&[
        "fails(2)",
        "fails(a)",
        "fails(_)",
        "fails(4611686018427387904)",
    ]);
}

/// Two held calls in a row, the second reading the global the first's
/// exit arc set.
#[test]
fn ncall22_two_held_calls_agree() {
    agree(&["chain(1)", "chain(a)", "chain(_)"]);
    let r = report("chain(1)");
    assert!(r.contains("stop(3,2,up)"), "{r}");
}
