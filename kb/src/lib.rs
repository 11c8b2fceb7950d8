//! `sitlog-kb`: the robot's non-monotonic knowledge base. Never knows about DMs.
//!
//! A KB is a list of `class(Id, Mother, Properties, Relations, Individuals)`
//! (kb.md section 1). [`Kb`] loads and validates it, answers the original
//! SitLog KB services with the original's answers and quirks (section 2-4),
//! applies the updates, and saves it back atomically. Services are called
//! with the `sitlogc kb` convention: a Prolog term without the KB argument,
//! the answer as the last argument ([`Kb::call`], [`Kb::update`], [`cli`]).
//! The service tables ([`SERVICES`], [`UPDATES`]) let whoever assembles a
//! program register them as SitLog user functions.

mod answer;
mod cli;
mod closure;
pub mod gen;
mod model;
mod persist;
mod services;
pub mod store;
mod update;

pub use answer::{Answer, CallError, Outcome};
pub use cli::{cli, line_col, CliError};
pub use closure::Budget;
pub use model::{Kb, ModelError};
pub use persist::{lock_for_persist, LoadError, PersistError, PersistLock};
pub use services::{service, Arg, Service, SERVICES};
pub use update::{update_service, UpdateService, UPDATES};

#[cfg(test)]
mod tests;
