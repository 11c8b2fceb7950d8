//! Prolog user functions (feature `prolog`): the application's
//! `templates.pl` and `user_functions.pl` run in an embedded
//! [scryer-prolog](https://crates.io/crates/scryer-prolog) engine, so a task
//! stays one binary with no system library.
//!
//! Trust. Loading runs no application code: the directives run at
//! [`PrologFunctions::start`], a run's first transition (see `permissions`
//! and docs/guide/reliability.md, "Trust model").
//!
//! Loading. Our reader (SWI-Prolog 6 syntax, SitLog operators) reads the
//! files; each clause is sent to the engine in canonical form, with `'|'/2`
//! turned into `;/2` (SWI-6 reads `(C -> A | otherwise -> B)` as `;`) and
//! double-quoted strings as code lists (SWI-6's default). So the engine
//! never parses application text: a clause our reader cannot read is
//! skipped and the rest loaded, as SWI-Prolog's consult does for the
//! original (`sitlogc check` warns of it with its file:line:col), and the
//! engine only reports errors of its own (a clause
//! it refuses, a failing directive) by clause position. `consult/1` and
//! `ensure_loaded/1` directives load the named file the same way
//! (`$SITLOG_HOME/...` is the `SITLOG_HOME` environment variable, else the
//! nearest ancestor directory in which the rest of the path exists).
//! Under the legacy profile (the original's layer of 1,720 clauses, and an
//! application's own files) each predicate is a stub until its first call
//! or the first call that changes or looks at its clauses, which asserts
//! its clauses (`engine::lazify`).
//!
//! SWI-Prolog. Code written for the original expects SWI-Prolog: the
//! prelude provides its built-ins and library predicates the engine lacks
//! ([`SWI_PREDICATES`], each yielding to an application's own definition),
//! and the loader renames the application's calls of engine built-ins that
//! behave otherwise ([`SWI_RENAMED`]: `atom_chars/2` on codes, SWI's
//! standard order of mixed numbers in `compare/3`, `@<`, the sorts, and
//! reading text as terms). Text read as a term at run time
//! (`read_from_chars/2`, `term_to_atom/2`, ...) is read by our reader too:
//! the engine sends it to the host on its `user_error` stream and gets the
//! term back in canonical form on `user_input` ([`read_reply`]); the same
//! channel serves the legacy KB layer natively ([`NativeKb`]).
//!
//! Calling. `apply(f(X1..Xn), [E1..En])` becomes one query of the prelude
//! (`prolog/prelude.pl`) with the arguments, the caller's locals and
//! globals, the history and the caller's unbound variables written as
//! canonical text; the answer gives the value passed to
//! `assign_func_value/1`, the SitLog variables changed by `var_op/1` and
//! the bindings of the caller's variables. The engine is not `Send`: it
//! lives on a thread of its own and calls are messages to it. A call of a
//! *plain* function (`crate::plain`: integer arithmetic, comparisons, `==`, cut,
//! `assign_func_value/1`) is first run natively from the clauses the
//! engine loaded; where that does not give a value, the query decides.
//!
//! One job per submodule, bottom to top (each uses only those before it;
//! this file only re-exports, so every public item keeps its path
//! `sitlog_runtime::prolog::X`):
//! - `swi`: the prelude (`prelude.pl`, then `prelude_swi.pl`: SWI's
//!   strings as atoms, `format/1,2,3`, Edinburgh I/O, file names, time)
//!   and the SWI-Prolog compatibility tables;
//! - `permissions`: the trust model's guards (calls reaching the operating
//!   system renamed to them; refused without `--allow-os`);
//! - `translate`: store terms to canonical text and engine terms back;
//! - `kb_reach`: which argument positions of the Prolog code a KB handle
//!   can reach (a data-flow analysis over its clauses; it names the
//!   layer's renamed services by `legacy_kb::legacy_name`, the one use of
//!   a later module);
//! - `reach_cache`: that analysis' result kept once per input in the cache
//!   directory ([`reach_cache_dir`]);
//! - `legacy_kb`: the legacy KB layer served natively ([`NativeKb`]);
//! - `plain`: the plain user functions' native form, which runs a call
//!   in Rust where the engine would give the same value and leaves the
//!   rest to the engine;
//! - `consult`: sources, their clauses, and `consult/1` resolution;
//! - `engine`: the engine thread and the calling protocol
//!   ([`PrologFunctions`]);
//! - `quiet`: a panic inside the engine caught without a backtrace on
//!   stderr (the engine restarted, the panic the call's error).

mod consult;
mod engine;
mod kb_reach;
mod legacy_kb;
mod permissions;
mod quiet;
mod reach_cache;
mod swi;
mod translate;

pub use consult::{PrologLoadError, PrologSource};
pub use engine::{PrologFunctions, PrologOptions, NO_INFERENCE_LIMIT};
pub use legacy_kb::{KbHost, NativeKb};
pub use reach_cache::default_dir as reach_cache_dir;
pub use swi::{PRELUDE, SWI_PREDICATES, SWI_RENAMED};
pub use translate::read_reply;

#[cfg(test)]
mod tests;

#[cfg(test)]
mod swi_tests;

#[cfg(test)]
mod permissions_tests;
