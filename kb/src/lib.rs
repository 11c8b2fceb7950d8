//! `sitlog-kb`: the robot's non-monotonic knowledge base. Never knows about DMs.
//!
//! **Invariant:** of sitlog-rs it depends on `sitlog-syntax` only (terms and
//! the term reader), never on the compiler or the runtime; and no input makes
//! it panic: bad KBs, queries and updates are typed errors with positions.
//!
//! A KB is a list of `class(Id, Mother, Properties, Relations, Individuals)`
//! (kb.md section 1). [`Kb`] loads and validates it, answers the original
//! SitLog KB services with the original's answers and quirks (section 2-4),
//! applies the updates, and saves it back atomically. Services are called
//! with the `sitlogc kb` convention: a Prolog term without the KB argument,
//! the answer as the last argument ([`Kb::call`], [`Kb::update`], and
//! [`answer_line`] for the whole `sitlogc kb` output line).
//! The service tables ([`SERVICES`], [`UPDATES`]) let whoever assembles a
//! program register them as SitLog user functions.
//!
//! Modules, each using only those listed before it: `store` (the terms),
//! `entry` (weighted entries), `closure` (closures and explanations),
//! `model` ([`Kb`]), `class_cache`, `services`, `update`, `answer` (the
//! dispatcher), `persist` (files), `query` ([`answer_line`]); and [`gen`]
//! (synthetic KBs, for benchmarks).

mod answer;
mod class_cache;
mod closure;
mod entry;
pub mod gen;
mod model;
mod persist;
mod query;
mod services;
pub mod store;
mod update;

pub use answer::{Answer, CallError, Outcome};
pub use closure::Budget;
pub use model::{Kb, ModelError};
pub use persist::{lock_for_persist, real_path, LoadError, PersistError, PersistLock};
pub use query::{answer_in, answer_line, QueryError};
pub use services::{service, Arg, Service, SERVICES};
/// 1-based line and column (in characters) of a byte offset: the positions
/// of KB errors, as the term reader counts them.
pub use sitlog_syntax::line_col;
pub use update::{update_service, UpdateService, UPDATES};

#[cfg(test)]
mod tests;
