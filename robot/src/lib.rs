//! `sitlog-robot`: what a SitLog task runs on, outside the DM machine: the
//! robot (simulated, behind the runtime's [`Perception`] and [`Actions`]
//! traits), the knowledge base (its services as user functions), the user,
//! and the command line that `sitlogc run` and compiled tasks share.
//!
//! Invariants:
//! - The runtime never depends on this crate; this crate never depends on
//!   the compiler (a compiled task links the runtime and this crate only).
//! - The simulator (`sitlog-sim`, feature `sim`) knows nothing of SitLog:
//!   every SitLog term a robot perceives or acts on is made or read here.
//! - One runner ([`cli::execute`]) for the interpreter and compiled code,
//!   so both print the same transcript and report for the same run.
//!
//! [`Perception`]: sitlog_runtime::machine::Perception
//! [`Actions`]: sitlog_runtime::machine::Actions

pub mod cli;
pub mod console;
#[cfg(feature = "sim")]
mod infer;
pub mod interrupt;
pub mod kb;
pub mod prompt;
#[cfg(feature = "sim")]
pub mod robot;

pub use cli::{execute, main, Assets, FileError, Source};

/// The user functions the simulated robot registers when a task runs on a
/// world (`shop_diagnose/4`, ...), by name and arity: `sitlogc check`
/// passes them to the checker, which does not depend on this crate.
#[cfg(feature = "sim")]
pub const WORLD_FUNCTIONS: &[(&str, usize)] = infer::FUNCTIONS;
/// Without the simulator no world functions exist.
#[cfg(not(feature = "sim"))]
pub const WORLD_FUNCTIONS: &[(&str, usize)] = &[];
