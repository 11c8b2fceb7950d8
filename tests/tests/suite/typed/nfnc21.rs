//! Helper `nfnc21` (issue 37): plain Prolog user functions called by
//! native code on its values (`Cx::nat_plain`, `tests/typed/nfnc21`), the
//! `apply`'s declared variables made only on the term path, an out_arg's
//! value set as the pipe without the native frames handed over: a walk
//! whose next situation is `step/3`'s value (several clauses, guards, a
//! list head pattern), a condition whose declared variable the next
//! situation names (`find/2`), arithmetic and a list as the value
//! (`score/2`), an out_arg by `grow/1` (a failure, no value, an atom then
//! a type error, a float, an overflow), and out_args by functions that are
//! not plain (`wrap/1` calls `atom/1`; `hole/1` gives an unbound value:
//! the pipe unchanged). The compiled task and the interpreter's plans, plain
//! forms native, give what the interpreter gives with every call a query
//! of the engine; the compiled task what the interpreter gives without
//! history.

use super::{agree_plain, PLAIN_VS};

mod dms {
    pub mod nfnc21 {
        sitlog_macros::include_dm!("typed/nfnc21");
    }
}

const MAINS: &[&str] = &[
    "walk([a, b, c], c)",
    "walk([a, a, b], z)",
    "walk([a, boom], z)",
    "walk([skip, b], b)",
    "walk([], a)",
    "walk([a, f(1), [x]], [x])",
    "walk([a, 1.5], z)",
    "walk([a, _], z)",
    "walk([a|b], z)",
    "find([a, b], b)",
    "find([a, b], z)",
    "find([boom], z)",
    "find([a, 1.5], z)",
    "count(1, 2)",
    "count(1, 3)",
    "count(200, 1)",
    "count(a, 1)",
    "count(9223372036854775807, 2)",
    "pump(0)",
    "pump(3)",
    "pump(6)",
    "pump(7)",
    "pump(8)",
    "pump(9)",
    "pump(a)",
    "pump(1.5)",
    "pump(9223372036854775806)",
    "pump([1])",
    "pump_w(1)",
    "pump_w(a)",
    "pump_h(1)",
    "pump_h(200)",
];

#[test]
fn nfnc21_plain_calls_and_out_args_agree() {
    agree_plain(
        dms::nfnc21::program(),
        "typed/nfnc21",
        "grow/1 same/2 score/2 step/3",
        MAINS,
        PLAIN_VS,
    );
}
