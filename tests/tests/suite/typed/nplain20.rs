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

use super::{agree_plain, PLAIN_VS};

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
    agree_plain(
        dms::nplain20::program(),
        "typed/nplain20",
        "bump/1 heavy/1 is_at/2 next_of/3",
        MAINS,
        PLAIN_VS,
    );
}
