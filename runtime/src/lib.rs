//! `sitlog-runtime`: everything a running SitLog task needs, shared by the
//! reference interpreter and by generated code. Never depends on the compiler.
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
//!
//! Every walk over a term is iterative or grows its stack on the heap, so
//! terms of any depth are safe on a 2 MiB thread.

pub mod app;
mod arith;
pub mod builtins;
mod convert;
mod copy;
pub mod eval;
pub mod functions;
mod gc;
pub mod history;
pub mod machine;
pub mod paths;
#[cfg(feature = "prolog")]
pub mod prolog;
pub mod report;
mod store;
mod term;
pub mod testmode;
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
/// `functions`; generated tasks call this with the sources they embed.
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
        let engine =
            prolog::PrologFunctions::load(&sources, Default::default()).map_err(|errors| {
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
