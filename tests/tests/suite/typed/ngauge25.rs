//! Helper `ngauge25` (issue 37): an out_arg whose variable an arc leaves
//! unbound passes the pipe on unchanged, decided on the MIR
//! (`mir::OutPass`) and native (`tests/typed/ngauge25/g25_out_unbound`:
//! bound on some exit arcs, on none, on all, read by an action, a
//! neutral situation, a final, bound later by a next situation on some
//! paths, the in_arg's own variable); a float `is` in a `prog`
//! (`g25_c_float_prog`) and as a next situation's argument
//! (`g25_d_float_next`), with bad inputs (no number, a float overflow, an
//! int, an unbound value); each compiled and on the interpreter's plans
//! against the interpreter, with and without history, observer and
//! numbers logged.

use super::{agree_both, agree_piped, interpreter};
use sitlog_compiler::interp::Resolved;
use sitlog_compiler::ir::Ir;
use sitlog_runtime::app;

/// Main DM `main` started with each pipe of `in_args`, compiled and on
/// the interpreter's plans, against the interpreter.
fn agree_pipes<A: app::App>(compiled: &A, interpreted: &Ir, main: &str, in_args: &[&str]) {
    for in_arg in in_args {
        agree_piped(compiled, interpreted, main, Some(in_arg), "");
        agree_piped(
            &Resolved::new(interpreted),
            interpreted,
            main,
            Some(in_arg),
            "",
        );
    }
}

mod dms {
    pub mod out_unbound {
        sitlog_macros::include_dm!("typed/ngauge25/g25_out_unbound");
    }
    pub mod float_prog {
        sitlog_macros::include_dm!("typed/ngauge25/g25_c_float_prog");
    }
    pub mod float_next {
        sitlog_macros::include_dm!("typed/ngauge25/g25_d_float_next");
    }
}

/// Each variant of an out_arg left unbound, with pipes that reach each
/// final of the callee (`a` above 5, `b` above 0, `c` else, which sets
/// the pipe), and pipes that are no number.
#[test]
fn out_unbound_agrees() {
    let ir = interpreter("typed/ngauge25/g25_out_unbound");
    let mut mains = Vec::new();
    for dm in [
        "rec_some",
        "rec_none",
        "rec_all",
        "rec_said",
        "neu_none",
        "neu_some",
        "neu_later",
        "fin_called",
    ] {
        for n in ["9", "3", "1", "0", "-2", "2.5", "a"] {
            mains.push(format!("{dm}({n})"));
        }
    }
    mains.push("fin_none(1)".into());
    mains.push("fin_none(0)".into());
    let mains: Vec<&str> = mains.iter().map(String::as_str).collect();
    agree_both(dms::out_unbound::program(), &ir, &mains);
}

/// The in_arg's own variable as the out_arg: a pipe the pattern matches,
/// one whose part is unbound, one it does not match, an unbound pipe.
#[test]
fn out_same_as_in_arg_agrees() {
    let ir = interpreter("typed/ngauge25/g25_out_unbound");
    agree_pipes(
        dms::out_unbound::program(),
        &ir,
        "same_var",
        &["f(1)", "f(_)", "g(1)", "_", "f(x)"],
    );
}

/// A float `is` in a prog: a float charge, an int one (an int operand),
/// a huge one (`L * 2.0` overflows: the machine's error), an atom (no
/// number), unbound, zero rounds; `spend`'s `(L + L) * 0.25` of an int,
/// a float, an int sum that overflows, a float one that does.
#[test]
fn float_prog_agrees() {
    let ir = interpreter("typed/ngauge25/g25_c_float_prog");
    agree_both(
        dms::float_prog::program(),
        &ir,
        &[
            "battery(3, 0.0)",
            "battery(3, 300.0)",
            "battery(2, 4)",
            "battery(2, 1.0e308)",
            "battery(2, a)",
            "battery(2, _)",
            "battery(0, 1.5)",
            "battery(2, -7.5)",
            "spend(3, 0.0)",
            "spend(3, 4)",
            "spend(2, 9223372036854775807)",
            "spend(2, 1.0e308)",
            "spend(2, a)",
            "spend(2, _)",
        ],
    );
}

/// A float `is` in a next situation's argument: int and float weights,
/// the cap passed, no weights, an atom and an unbound weight (no
/// number), a huge weight (a float overflow: the machine's error), an
/// int sum that overflows, an atom cap (the comparison raises).
#[test]
fn float_next_agrees() {
    let ir = interpreter("typed/ngauge25/g25_d_float_next");
    agree_both(
        dms::float_next::program(),
        &ir,
        &[
            "tally(2, [1, 2, 3, 4], 100)",
            "tally(2, [1, 2.5, 3, 4], 2)",
            "tally(2, [], 2)",
            "tally(2, [1, a], 100)",
            "tally(2, [1, X], 100)",
            "tally(2, [1.0e308, 1.0e308, 1.0e308], 1.0e308)",
            "tally(1, [9223372036854775807, 2], 1.0e300)",
            "tally(2, [1, 2], a)",
            "tally(2, [1|T], 100)",
        ],
    );
}
