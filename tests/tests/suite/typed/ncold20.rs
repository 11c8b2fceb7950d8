//! Helper `ncold20` (issue 37): a global typed `ground` that a DM whose
//! frame runs on terms (started with an argument that is not ground) sets
//! to a value native code cannot hold (`_`, `f(_)`, `[a|_]`), then read
//! by native code below it elsewhere than a conditional's condition (a
//! next situation's value, beside an `inc` too, an out_arg, a call's
//! argument, `when/3`; helper `ncold21`: an action, a condition in a DM
//! with locals or binding a variable, an out_arg beside an `inc`): the
//! interpreter goes on with the value, and so
//! must the compiled task and the interpreter's plans (history, report,
//! error, actions, observer, with and without history).

use super::agree_app;

mod dms {
    pub mod globals {
        sitlog_macros::include_dm!("typed/ncold20/globals");
    }
}

/// Each DM started with a ground goal, an unbound one, a compound and a
/// partial list holding a variable.
fn mains(dm: &str) -> Vec<String> {
    ["a", "_", "f(_)", "[a|_]"]
        .iter()
        .map(|g| format!("{dm}({g})"))
        .collect()
}

fn agree(dm: &str) {
    let mains = mains(dm);
    let mains: Vec<&str> = mains.iter().map(String::as_str).collect();
    agree_app(dms::globals::program(), "typed/ncold20/globals", &mains);
}

/// `show(get(n, _), get(goal, _))`: a global read beside a local's, each
/// computed by native code (`Gen::nat_ev_effects`).
#[test]
fn a_global_read_beside_a_local_read_in_a_next_situation_agrees() {
    agree("pair");
}

/// `show(wrap(get(goal, _)))` and `show(get(goal, _))`: the machine's
/// already (a situation on terms, a part the evaluator computes).
#[test]
fn a_global_read_in_a_next_situation_agrees() {
    agree("nest");
    agree("top");
}

/// `out_arg ==> wrap(get(goal, _))`.
#[test]
fn a_global_read_in_an_out_arg_agrees() {
    agree("out");
}

/// `embedded_dm ==> arg_leaf(wrap(get(goal, _)))` and
/// `apply(when(_, _, _), [get(goal, _) == a, yes, no])` as a next
/// situation.
#[test]
fn a_global_read_in_a_call_and_in_when_agrees() {
    agree("arg");
    agree("pick");
}

/// `show(inc(n, _), get(goal, _))` and `show(get(goal, _), inc(n, _))`:
/// the `inc` before the read not done again, the one after it the
/// machine's.
#[test]
fn a_global_read_beside_an_inc_in_a_next_situation_agrees() {
    agree("inc");
    agree("inc2");
}

/// `[get(goal, G)]` in an exit arc's action (`act`) and a neutral arc's
/// (`acts`), `(get(goal, _) == a -> ..)` in a DM with a local (`loc`):
/// left by `ncold20`, the arc's rest on terms from the read (`cold_act`),
/// the condition the machine's where it changes no local (helper
/// `ncold21`).
#[test]
fn a_global_read_in_an_action_or_a_dm_with_locals_agrees() {
    for dm in ["act", "acts", "loc"] {
        agree(dm);
    }
}

/// `[inc(n, N), get(goal, G), inc(n, M)]` in an exit arc's action (the
/// first `inc` not done again, the second the machine's), `[inc(n, N),
/// get(goal, G), set(n, 7)]` in a neutral arc's with `get(n, _)` in the
/// next situation, an exit arc's read beside its situation's out_arg
/// (helper `ncold21`).
#[test]
fn a_global_read_beside_effects_in_an_action_agrees() {
    for dm in ["act2", "acts2", "act3"] {
        agree(dm);
    }
}

/// `out_arg ==> f(inc(n, _), get(goal, _))` and `g(get(goal, _), inc(n,
/// _))`: the `inc` before the read not done again, the one after it the
/// machine's (helper `ncold21`).
#[test]
fn a_global_read_beside_an_inc_in_an_out_arg_agrees() {
    agree("outinc");
}

/// `(get(goal, D) == a -> seen(yes, D) ; otherwise -> seen(no, wrap(D)))`
/// and `(get(goal, D) == get(other, D) -> ..)`: a condition that binds a
/// variable for its branches, the whole next situation on terms
/// (`Gen::nat_if_cold`, helper `ncold21`).
#[test]
fn a_global_read_in_a_condition_binding_a_variable_agrees() {
    agree("bind");
    agree("same");
}
