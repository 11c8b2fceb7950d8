//! Helper `ncall21` (issue 37): calls whose arguments are evaluated
//! (`tests/typed/ncall21`): `get` of a local, of a global the callee sets
//! before the frames become the machine's, `apply` of a function that
//! asserts and counts its calls, arithmetic (`_ is K * 2 + 1`), and values
//! that are not what the callee takes (unbound, not ground, an atom
//! added to, an overflow). The callees hand over while they run (`hand/1`
//! is not plain), so a waiting caller is made the machine's: the call it
//! made must be the one evaluated once (a global read before the callee
//! set it, one `tally/1` call), in the compiled task and the interpreter's
//! plans as in the interpreter (history, report, error, actions, observer,
//! with and without history).

use super::{agree_both, interpreter, run, with_engine};

mod dms {
    pub mod ncall21 {
        sitlog_macros::include_dm!("typed/ncall21");
    }
    /// The same program with evaluated calls pushed natively
    /// (`codegen::Options::held_calls`, off by default).
    pub mod held {
        sitlog_macros::include_dm!("typed/ncall21", held);
    }
}

/// Each task in the compiled task and the plans as in the interpreter,
/// the application's Prolog user functions loaded once, installed in
/// every run (each task starts with `reset/1`).
fn agree(mains: &[&str]) {
    let ir = interpreter("typed/ncall21");
    with_engine(&ir, || agree_both(dms::ncall21::program(), &ir, mains));
}

/// The compiled task's report (history kept), to check that what the
/// interpreter gives is the call evaluated once.
fn report(main: &str) -> String {
    let r = with_engine(&interpreter("typed/ncall21"), || {
        run(dms::ncall21::program(), main, "", true, false, false)
    });
    format!("{r:?}")
}

/// The cases, by what the call's arguments do.
const LOCAL: &[&str] = &["loc(1)", "loc(x)", "loc(_)"];
const GLOBAL: &[&str] = &["glob(a)", "glob(7)", "glob(f(_))", "glob(_)", "glob([a|_])"];
const APPLY: &[&str] = &["twice(s)", "twice(f(x))", "twice(_)"];
const ARITH: &[&str] = &[
    "arith(2)",
    "arith(-7)",
    "arith(a)",
    "arith(_)",
    "arith(1.5)",
    "arith(4611686018427387904)",
];
const BAD: &[&str] = &["bad(1)", "bad(a)", "bad(_)", "bad(f(_))"];

/// `echo(get(n, _))`, `slow(get(n, _))` after an `inc` of the local.
#[test]
fn ncall21_a_local_read_in_a_call_agrees() {
    agree(LOCAL);
}

/// `change(get(g, _))`: the callee sets `g`, then hands over; its
/// parameter and the caller's exit arc see the value read at the call.
#[test]
fn ncall21_a_global_the_callee_changes_agrees() {
    agree(GLOBAL);
    let r = report("glob(a)");
    assert!(r.contains("stop(a,1,changed)"), "{r}");
}

/// `slow(apply(tally(_), [S]))`: one call of `tally/1` (its fact asserted
/// once), whatever the hand-over in the callee.
#[test]
fn ncall21_an_apply_with_a_side_effect_agrees() {
    agree(APPLY);
    let r = report("twice(s)");
    assert!(r.contains("stop(s-1,2,2/[s,hand(s-1)])"), "{r}");
}

/// `slow(_ is K * 2 + 1)`: a value, a type error, unbound, an overflow.
#[test]
fn ncall21_arithmetic_in_a_call_agrees() {
    agree(ARITH);
}

/// `add(get(g, _))` whose callee adds one: an int, an atom, unbound.
#[test]
fn ncall21_bad_values_in_a_call_agree() {
    agree(BAD);
}

/// Every case above with evaluated calls pushed natively
/// (`codegen::Options::held_calls`): the calls are evaluated once by
/// native code, in the compiled task as in the interpreter.
#[test]
fn ncall21_held_calls_agree() {
    let ir = interpreter("typed/ncall21");
    with_engine(&ir, || {
        for mains in [LOCAL, GLOBAL, APPLY, ARITH, BAD] {
            agree_both(dms::held::program(), &ir, mains);
        }
    });
}
