//! Every diagnostic code of the compiler with its one-line meaning, in
//! order: the list the guide's code tables are made from
//! (`tests/tests/repository/guide_codes.rs` checks `docs/guide/checking.md`
//! and `docs/guide/diagnostics.md` against it). Invariant: each code
//! constant of [`crate::load::codes`], [`crate::ast::codes`] and
//! [`crate::check::codes`] is here once (a unit test reads their sources).

use crate::ast::codes as shape;
use crate::check::codes as check;
use crate::load::codes as load;

/// (code, what it reports), in the order of the codes.
pub const DIAGNOSTICS: &[(&str, &str)] = &[
    (
        load::SYNTAX,
        "syntax error (with the unclosed bracket, if any)",
    ),
    (load::NOT_UTF8, "file is not UTF-8"),
    (
        load::MODELS_ENTRY,
        "a `models` entry is not a quoted file name",
    ),
    (
        load::MISSING_FILE,
        "a file listed in `models` cannot be read (in the application's directory, or in the library for a library name)",
    ),
    (
        load::NOT_A_DM_FILE,
        "a file listed in `models` is not a `.dm` or `.pl` file (not read)",
    ),
    (
        load::OUTSIDE_APP,
        "a file listed in `models` is outside the application directory",
    ),
    (
        load::APP_FILE,
        "the application's `world.toml`, `knowledge.kb`, `ros2.toml` or `sitlog.toml` has an error that `sitlogc run` stops on (its message and position; `run` exits 1 on each, 2 when a file cannot be read)",
    ),
    (
        load::PROLOG_SYNTAX,
        "a clause of a consulted Prolog file (`user_functions.pl`, `templates.pl` and what they consult) that does not read: skipped, as SWI-Prolog's consult skips it, and the rest is loaded",
    ),
    (
        shape::NOT_A_DM,
        "a clause of a DM file that is not a DM (ignored)",
    ),
    (shape::MALFORMED_DM, "malformed DM identifier"),
    (shape::MALFORMED_SITUATION, "malformed situation"),
    (shape::MALFORMED_ARC, "malformed arc"),
    (shape::MALFORMED_VAR, "malformed local variable"),
    (shape::MALFORMED_SIDE_FILE, "malformed side-file clause"),
    (
        shape::MALFORMED_GLOBAL,
        "a clause of `global_vars.pl` that is not `name ==> value` (`battery => 100.`): it declares no variable (the original keeps it in its list of globals, where no `get` finds it, and runs on)",
    ),
    (
        shape::DUPLICATE_ATTRIBUTE,
        "attribute given twice in a situation (the first is used)",
    ),
    (check::DUPLICATE_DM, "DM defined twice"),
    (
        check::SAME_NAME_OTHER_ARITY,
        "two DMs with the same name and other arities",
    ),
    (
        check::DUPLICATE_DM_IDENTICAL,
        "DM defined twice identically (only with `--legacy`, where the first is used, as the original does; otherwise E0201)",
    ),
    (check::MISSING_ID, "situation without `id`"),
    (check::MISSING_TYPE, "situation without `type`"),
    (
        check::MISSING_ARCS,
        "situation that is not final without `arcs`",
    ),
    (check::FINAL_WITH_ARCS, "final situation with arcs"),
    (
        check::MISSING_EMBEDDED_DM,
        "recursive situation without `embedded_dm`",
    ),
    (check::UNKNOWN_ATTRIBUTE, "unknown situation attribute"),
    (
        check::NEUTRAL_SHAPE,
        "`neutral` situation not of the form `[empty : A => N]`",
    ),
    (check::NO_FINAL, "DM without a final situation"),
    (
        check::UNKNOWN_NEXT,
        "next situation that names no situation of the DM",
    ),
    (check::UNREACHABLE, "unreachable situation"),
    (check::FINAL_UNREACHED, "final situation never reached"),
    (
        check::SHADOWED,
        "situation shadowed by an earlier one with the same id",
    ),
    (check::UNKNOWN_DM, "`embedded_dm` names no DM"),
    (
        check::DM_ARITY,
        "DM called with the wrong number of arguments",
    ),
    (
        check::UNKNOWN_EXIT,
        "exit arc that is not a final situation of the embedded DM",
    ),
    (
        check::UNKNOWN_VARIABLE,
        "`get`/`set`/`inc` of a variable neither local nor global",
    ),
    (
        check::UNKNOWN_VARIABLE_NESTED,
        "`get`/`set`/`inc` of a variable neither local nor global whose value is data passed on: an element of a list in an action's argument (`say(['Battery at', get(battery, _)])`), an argument of a next situation (`=> next(get(battery, _))`), an `out_arg`, an element of a `prog`, an argument of an `embedded_dm` call: the original prints that the variable is not defined and runs on with the value unbound, and so does the run (a warning once per variable on stderr, [language](language.md#variables-local-and-global))",
    ),
    (check::SINGLETON, "singleton variable (as Prolog warns)"),
    (check::DUPLICATE_GLOBAL, "global variable declared twice"),
    (check::DUPLICATE_LOCAL, "local variable declared twice"),
    (
        check::UNKNOWN_RECOVERY_DM,
        "a recovery protocol (`recovery_protocols.pl`) names no DM of the application",
    ),
    (
        check::UNKNOWN_FUNCTION,
        "`apply` of a function the run will not have",
    ),
    (
        check::UNKNOWN_ACTION,
        "action not declared in `basic_actions.pl`",
    ),
    (
        check::KB_SERVICE_WITHOUT_KB,
        "KB service called in an application without a KB",
    ),
    (
        check::WORLD_FUNCTION_WITHOUT_WORLD,
        "function of the simulated robot called in an application without a world",
    ),
    (
        check::UNBOUND_VARIABLE,
        "a variable used in an action or next situation that nothing binds before (names the places looked at)",
    ),
    (
        check::ACTION_ARITY,
        "an action given another number of arguments than its `arity` list in `basic_actions.pl`",
    ),
    (
        check::UNKNOWN_SITUATION_TYPE,
        "a situation `type` that is no known type but close to one (`fianl`: *did you mean `final`?*)",
    ),
    (
        check::DEAD_EXIT,
        "an exit arc that names no final situation of the embedded DM, while each of its final situations has another exit arc: never taken (E0218 when a final situation is left without one)",
    ),
    (
        check::LEFT_OUT,
        "(`sitlogc run`) a DM with errors that the run's main DM does not reach by name: left out of the run, its errors warnings; a run that reaches it (a name computed at run time) stops there with its first error",
    ),
    (
        check::NOT_A_CONDITIONAL,
        "a term written like a conditional that is not one: `(C -> A ; R)` whose else part is not `otherwise -> B` (an `if`-chain `(C1 -> A ; C2 -> B ; otherwise -> D)`, or `(C -> A ; B)`); the original evaluates it to a compound term like any other (D-35)",
    ),
    (
        check::DM_HEAD_MISMATCH,
        "an `embedded_dm` call whose arguments can never match the called DM's head: an argument whose every value is known without running anything (a constant, a compound, a list, each branch of a conditional; a variable inside matches anything) that cannot unify with the head's argument (`callee(1)` for `diag_mod(callee(2), ..)`, `at(kitchen)` for `to(Place)`, `[a]` for `[First, Second]`); a variable or a computed argument (`get(..)`, `apply(..)`) is never reported",
    ),
    (
        check::IN_ARG_NEVER_MATCHES,
        "an in_arg pattern that can never match the pipe its situation is given: every situation that can lead to it sets the pipe to a value known without running anything (its `out_arg` a constant, a compound, a list, each branch of a conditional; a variable inside matches anything), or passes on such a value, and none can unify with the pattern (`in_arg ==> foo` after `out_arg ==> now`); the run skips the in_arg, as the original does, its variables unbound (D-8; `--deny-warnings`: an error at run time). Not reported for a DM's first situation (its pipe is the caller's), after a recursive situation without `out_arg`, or where a computed next situation may lead",
    ),
    (
        check::NEUTRAL_NEVER_PROCEEDS,
        "a `neutral` situation that can never proceed: not exactly one arc, or one whose expectation is known and never `empty` (the run stops when it reaches it; the original re-enters it forever); a variable or computed expectation is only W0210",
    ),
    (
        check::DIAG_MOD_MISMATCH,
        "a situation's `diag_mod` that never matches its DM's identifier: every value known and none unifies with the head, or its principal functor is not the DM's name and arity (`fecth(Object, ok)` in DM `fetch/2`); the run stops when it reaches the situation (the original blocks, semantics E9)",
    ),
    (
        check::ARITHMETIC_WITHOUT_VALUE,
        "arithmetic on a variable that certainly has no value where the arc certainly evaluates it: the right side of `is` or an operand of `<`, `>`, `=<`, `>=` (`Next is Count + 1` with nothing binding `Count`; not inside a branch of a conditional); the original SitLog and the run both stop there with Prolog's instantiation error (*did you mean* `get(count, Count)` when a SitLog variable has that name)",
    ),
    (
        check::ARC_NEVER_TAKEN,
        "an arc that is never taken: an arc that wins over it has an expectation matching everything its own matches (in a perceptual situation the last matching arc wins, `confirm(R, R)` before `confirm(_, _)`; in a recursive one the first); only expectations known without running anything, and a winner whose variables are its own",
    ),
    (
        check::OS_ACCESS,
        "a directive or clause of the application's Prolog files reaches the operating system (shell, processes, sockets, native code, `open/3,4` for writing, loading code at run time or from an absolute or `$SITLOG_HOME` path): a run refuses it unless given `--allow-os` (the trust model, [reliability](reliability.md#trust-model))",
    ),
    (
        check::PROLOG_TOO_DEEP,
        "a clause of the application's Prolog files nests deeper than the Prolog engine takes (100 000 levels, a list counting a level per element): a run refuses it",
    ),
    (
        check::INC_NOT_A_NUMBER,
        "`inc` of a local variable whose value is never a number there: always a default that is not a number (`tries ==> none`; nothing in the DM `set`s it), or what a `set` stored as written (`set(count, C + 1)` stores the term `0+1`) when every `set` of it stores such a term and every way to the `inc` sets it; the DM applies no user function: the run stops at the `inc`, as the original does (`is not numeric`)",
    ),
    (
        check::UNKNOWN_WORLD_NAME,
        "(`sitlogc check` of an application with a `world.toml`) a place given by name to `navigate(Place, Status)` or `move(Place, Status)` that is no place or shelf of the world (*did you mean*): the run goes on, `navigate` answering `unknown_place`",
    ),
    (
        check::VAR_OP_ARITY,
        "`get`, `set` or `inc` with another number of arguments than two (`inc(visits)` for `inc(visits, _)`) where it is evaluated: the original stops there (`Ilegal list of terms`)",
    ),
    (
        check::APPLY_VALUE_COUNT,
        "`apply(F, Values)` with a list of values longer or shorter than `F`'s arguments (`apply(double(X), [2, 3])`): the original prints `Ilegal list of terms` and calls the function with every argument unbound, and so does the run (it stops if the function needs them)",
    ),
];

/// The meaning of `code`, if it is one.
pub fn meaning(code: &str) -> Option<&'static str> {
    DIAGNOSTICS
        .iter()
        .find(|(c, _)| *c == code)
        .map(|(_, m)| *m)
}

/// The guide's table of codes (`docs/guide/checking.md`): one row per code.
pub fn markdown_table() -> String {
    let mut out = String::from("| code | meaning |\n|---|---|\n");
    for (code, meaning) in DIAGNOSTICS {
        out.push_str(&format!("| {code} | {meaning} |\n"));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The codes defined as `pub const NAME: &str = "E0123";` in `source`.
    fn defined(source: &str) -> Vec<String> {
        source
            .lines()
            .filter_map(|l| {
                let l = l.trim();
                let rest = l.strip_prefix("pub const ")?;
                let (_, value) = rest.split_once(": &str = \"")?;
                let code = value.strip_suffix("\";")?;
                let c = code.as_bytes();
                (c.len() == 5 && (c[0] == b'E' || c[0] == b'W')).then(|| code.to_owned())
            })
            .collect()
    }

    #[test]
    fn every_code_is_listed_once_in_order() {
        let mut defined: Vec<String> = [
            include_str!("load.rs"),
            include_str!("ast.rs"),
            include_str!("check/mod.rs"),
        ]
        .iter()
        .flat_map(|s| defined(s))
        .collect();
        defined.sort_by(|a, b| a[1..].cmp(&b[1..]));
        let listed: Vec<String> = DIAGNOSTICS.iter().map(|(c, _)| c.to_string()).collect();
        assert_eq!(
            listed, defined,
            "compiler/src/codes.rs must list every code constant once, in order"
        );
        assert!(DIAGNOSTICS.iter().all(|(_, m)| !m.is_empty()));
        assert_eq!(
            meaning("E0212"),
            Some("next situation that names no situation of the DM")
        );
    }
}
