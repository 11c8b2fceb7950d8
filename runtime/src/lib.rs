//! `sitlog-runtime`: everything a running SitLog task needs, shared by the
//! reference interpreter and by generated code.
//!
//! What holds for the whole crate:
//! - It never depends on the compiler, nor on `kb` (KB services are
//!   registered as user functions by whoever assembles a program): its only
//!   SitLog dependency is `sitlog-syntax` (read terms, operators, the reader).
//! - Every walk over a term is iterative or grows its stack on the heap
//!   (`stacker`), so terms of any depth are safe on a 2 MiB thread; nesting
//!   DMs costs heap too (the machine's DM stack is a `Vec`).
//! - Semantics live here once for terms: the interpreter and generated
//!   code on terms run on the same [`machine`] and its steps. Generated
//!   *native* code (native values, `sitlog_compiler::codegen::native`) does
//!   many steps itself, on Rust values: choosing a situation by its id's
//!   pattern (a `match` on the id's variant and fields), integer arithmetic
//!   and comparisons, `when/3`, conjunctions and disjunctions of conditions,
//!   `member`, list heads and tails, `get`/`set`/`inc` of globals and
//!   locals, the pipe and DM parameters (`in_arg`/`out_arg`), matching a
//!   callee's final situation against exit arcs, matching a perception
//!   against expectations with the frames kept (`Cx::choose_kept`; a
//!   perception's `said(Input)` matched in place, not built:
//!   `machine::Percept`), plain
//!   user functions (`plain`, run in Rust before they would become
//!   a query), and performing an action built of values (converted to a term
//!   only at the effector); its frames are typed (`machine::native_stack`
//!   drives them, generic over the program's frame type). Where a value does
//!   not convert, or at an error, it hands its frames over to the machine
//!   (`nat_hand_over`), which then runs the step on terms. There agreement
//!   is not by construction but by test, with the history kept and without
//!   (native code's own DM stack):
//!   the examples (`tests/tests/suite/agreement.rs`), every scenario and
//!   world variant (`home.rs`, `supermarket.rs`), the typed agreement cases
//!   (`typed.rs`) and the random-program agreement (`random_agreement.rs`)
//!   compare the two back ends' histories, reports and errors.
//! - The `use crate::` edges between its modules form a DAG (below); within
//!   `machine`, `prolog` and `arith` the submodules are ordered the same
//!   way (see their module docs).
//!
//! The modules by floor, each using only modules of lower floors:
//!
//! | floor | modules |
//! |---|---|
//! | 6 | [`app`], [`prelude`] (the names generated code imports), [`report`], [`testmode`] |
//! | 5 | [`machine`] (the DM machine) |
//! | 4 | [`eval`] (the language L), [`plain`] (plain Prolog user functions run natively, no engine needed), `prolog` (feature `prolog`: Prolog user functions) |
//! | 3 | `arith`, `copy`, [`functions`], [`native`] (native values: their types, `List`, `Val`, conversions to and from terms, gc of the terms inside) |
//! | 2 | `unify`, `gc`, `convert`, [`vars`], [`history`], [`builtins`] |
//! | 1 | `store` |
//! | 0 | `term`, `special` (the functors L gives a meaning), `hash` (the atom-keyed tables' hasher), `eval_error`, `input` (limits on terms from outside), [`paths`], [`trust`] |
//!
//! The term layer:
//! - [`Term`]: a `Copy` handle; atoms, integers, floats and variables need
//!   no allocation.
//! - [`Store`]: where compounds, variables and the trail live; building,
//!   access ([`Store::value`], [`Store::functor`], [`Store::args`],
//!   [`Store::list_iter`]), binding and undo ([`Store::unify`],
//!   [`Store::mark`], [`Store::undo_to`]), comparison ([`Store::compare`],
//!   [`Store::identical`]), copying ([`Store::copy_term`],
//!   [`Store::copy_term_with`]), conversion from read terms
//!   ([`Store::from_clause`], [`Store::parse`]), printing
//!   ([`Store::writeq`]), arithmetic ([`Store::eval_arith`]) and memory
//!   ([`Store::freeze`], [`Store::gc`]).

pub mod app;
mod arith;
pub mod builtins;
mod convert;
mod copy;
pub mod eval;
mod eval_error;
pub mod functions;
mod gc;
mod goal;
pub(crate) mod hash;
pub mod history;
mod input;
pub mod machine;
pub mod native;
pub mod paths;
// Plain Prolog user functions run natively (used by `prolog`; the scan of
// which functions are plain also without the engine, for a build).
#[cfg_attr(not(feature = "prolog"), allow(dead_code))]
pub mod plain;
pub mod prelude;
#[cfg(feature = "prolog")]
pub mod prolog;
pub mod report;
pub mod sentence;
mod special;
pub mod stderr;
mod store;
mod term;
pub mod testmode;
pub mod trust;
pub mod type_test;
mod unify;
pub mod vars;

pub use arith::{compare_numbers, ArithCmp, ArithError, Number};
pub use convert::Bindings;
pub use copy::VarMap;
pub use functions::Functions;
pub use sitlog_syntax as syntax;
pub use sitlog_syntax::{atoms, Atom};
pub use store::{ListIter, Mark, Store, StoreStats};
pub use term::{Term, Value, Var};
pub use vars::Vars;

#[cfg(test)]
mod tests;

/// Installs an application's Prolog user functions (`templates.pl` then
/// `user_functions.pl`, as `(name, text)` in load order) as the fallback of
/// `functions`, their directives left for the run's start; generated tasks
/// call this with the sources they embed.
/// Without sources nothing happens; with sources but without the `prolog`
/// feature it is an error that says so.
pub fn install_prolog_sources(
    functions: &mut Functions,
    sources: &[(&str, &str)],
) -> Result<(), String> {
    if sources.is_empty() {
        return Ok(());
    }
    #[cfg(feature = "prolog")]
    {
        let sources: Vec<prolog::PrologSource> = sources
            .iter()
            .map(|(name, text)| prolog::PrologSource::new(*name, *text))
            .collect();
        // Loading runs no application code: the directives run when the
        // task starts (the trust model, see `prolog`).
        let engine = prolog::PrologFunctions::load_with(&sources, Default::default(), 0, None)
            .map_err(|errors| {
                errors
                    .iter()
                    .map(|e| e.to_string())
                    .collect::<Vec<_>>()
                    .join("\n")
            })?;
        engine.install(functions);
        Ok(())
    }
    #[cfg(not(feature = "prolog"))]
    {
        let _ = functions;
        Err("this task has Prolog user functions, but sitlog-runtime was built without its `prolog` feature".to_owned())
    }
}
