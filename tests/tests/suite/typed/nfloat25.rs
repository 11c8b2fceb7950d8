//! Helper `nfloat25` (issue 37): plain Prolog user functions on floats
//! (`sitlog_runtime::plain::num`) and a plain call in a DM with locals
//! (`tests/typed/nfloat25/n25_floats`). Each run, compiled, on the
//! interpreter and on the interpreter's plans with the plain functions
//! run natively, against the interpreter whose every call is a query of
//! the engine (the reference: the native form must give what the engine
//! gives, its errors included), with and without history, observer and
//! numbers logged.

use super::{interpreter, run_piped, ENGINE};
use sitlog_compiler::interp::Resolved;
use sitlog_runtime::Functions;

mod dms {
    pub mod floats {
        sitlog_macros::include_dm!("typed/nfloat25/n25_floats");
    }
    pub mod band {
        sitlog_macros::include_dm!("typed/nfloat25/n25_d_float_band");
    }
}

/// Each main DM call of `mains` on the three back ends with plain
/// functions native, against the interpreter with every call a query.
fn agree_with_engine(mains: &[&str]) {
    agree_app(dms::floats::program(), "typed/nfloat25/n25_floats", mains);
}

/// [`agree_with_engine`] of the compiled `app` of the DMs in `dir`.
fn agree_app<A: sitlog_runtime::app::App>(app: &A, dir: &str, mains: &[&str]) {
    let ir = interpreter(dir);
    let mut f = Functions::standard();
    let engine = sitlog_compiler::run::install_prolog(&ir, &mut f, Default::default())
        .expect("the Prolog files load")
        .expect("an engine");
    let resolved = Resolved::new(&ir);
    let mut bad = Vec::new();
    for main in mains {
        for keep in [false, true] {
            for (observe, numbers) in [(false, false), (true, true)] {
                ENGINE.with(|e| *e.borrow_mut() = Some((engine.clone(), true)));
                let want = run_piped(&ir, main, None, "", keep, observe, numbers);
                ENGINE.with(|e| *e.borrow_mut() = Some((engine.clone(), false)));
                let got = [
                    (
                        "compiled",
                        run_piped(app, main, None, "", keep, observe, numbers),
                    ),
                    (
                        "interpreter",
                        run_piped(&ir, main, None, "", keep, observe, numbers),
                    ),
                    (
                        "plans",
                        run_piped(&resolved, main, None, "", keep, observe, numbers),
                    ),
                ];
                for (way, g) in got {
                    if g != want {
                        bad.push(format!(
                            "{main} {way} (history {keep}, observer {observe}):\n  got  {g:?}\n  want {want:?}"
                        ));
                    }
                }
            }
        }
    }
    ENGINE.with(|e| *e.borrow_mut() = None);
    assert!(
        bad.is_empty(),
        "{} disagree:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// Floats compared and computed on: equal, a tenth apart, the sum of two
/// tenths, an int against a float, `/` of ints and of floats, `abs`,
/// `min`/`max` (a tie of `1` and `1.0`), large and small floats, big
/// ints beside a float; errors: an atom, a zero divisor (int and float),
/// a float overflow; a negative zero (the engine's).
#[test]
fn floats_agree_with_the_engine() {
    agree_with_engine(&[
        "fl([1.0-2.0, 0.1-0.1, 0.30000000000000004-0.3, 0.3-0.30000000000000004, 0.1-0.2])",
        "fl([1-1.0, 3-2, 7-2.0, 2.5-1, -1.5-(-2.5), 2-4.0, 1.0-1, 4-2])",
        "fl([1.0e300-1.0e-300])",
        "fl([1.0e-300-1.0e300, 1.0e15-3.0])",
        "fl([9007199254740993-1.0])",
        "fl([-0.0-0.0])",
        "fl([0.0-(-0.0)])",
        "fl([a-1.0])",
        "fl([1.0-b])",
        "fl([1.0-0.0])",
        "fl([1-0])",
        "fl([f(1)-1.0])",
        "fl([1.5-1.5, 2.5-0.5, 0.5-2.5])",
    ]);
}

/// `//`, `mod` (ints, a float: a type error, a zero divisor), `+ 0.1` of
/// an int and of a float.
#[test]
fn int_division_and_a_float_step_agree_with_the_engine() {
    agree_with_engine(&[
        "ints(7, 2)",
        "ints(-7, 2)",
        "ints(7.0, 2)",
        "ints(7, 2.0)",
        "ints(7, 0)",
        "ints(0.2, 1)",
    ]);
}

/// A DM with a local: each number compared with it (`get(lim, _)` in the
/// call's values), an atom naming the local passed as a value (`lim`
/// stays the atom), a float target, an int target, an unbound one, an
/// atom element (the comparison's error).
#[test]
fn a_dm_with_locals_agrees_with_the_engine() {
    agree_with_engine(&[
        "loc([0.1, 0.5, 0.7, lim, 2], 0.5)",
        "loc([0.4, 0.6, 1], 1)",
        "loc([a], 0.5)",
        "loc([0.3], T)",
        "loc([1.0, 0.0], 0.0)",
        "loc([lim], lim)",
        "loc([], 0.5)",
    ]);
}

/// The workload `n25_d_float_band` (shape d): in the band, none, the
/// floor an int, an atom reading (the engine's error), an empty sweep,
/// a reading on the band's edges (0.0 and 0.5 above the floor).
#[test]
fn float_band_agrees_with_the_engine() {
    agree_app(
        dms::band::program(),
        "typed/nfloat25/n25_d_float_band",
        &[
            "band(2, [0.5, 1.5, 2.5], 2.25)",
            "band(2, [0.5, 1.5], 2.25)",
            "band(1, [1, 2, 3], 2)",
            "band(1, [0.5, a], 2.25)",
            "band(2, [], 1.0)",
            "band(1, [1.0, 1.5], 1.0)",
            "band(1, [1.5000000000000002, 1.5], 1.0)",
        ],
    );
}
