//! `sitlog-robot`: what a SitLog task runs on, outside the DM machine: the
//! robot (simulated, behind the runtime's [`Perception`] and [`Actions`]
//! traits), the knowledge base (its services as user functions), the user,
//! and the runner and command line that `sitlogc run` and compiled tasks
//! share.
//!
//! Invariants:
//! - The library never depends on the compiler: a compiled task links the
//!   runtime and this crate only (the dev-dependency on sitlog-macros is
//!   for an example). The runtime never depends on this crate.
//! - One runner ([`Runner::run`]) for the interpreter and compiled code, so
//!   both print the same transcript and report for the same run.
//! - The simulator (`sitlog-sim`, feature `sim`) knows nothing of SitLog
//!   (it uses only sitlog-syntax's text decoding): every SitLog term a
//!   robot perceives or acts on is made or read here (the simulated robot,
//!   and the shop's functions over its world).
//!
//! The modules, each using only those before it: `assets` (what an
//! application brings: [`Assets`], [`TextFile`]), [`cli`] (the options of
//! a run, [`RunArgs`], and a compiled task's command line), `streams`
//! ([`Streams`]), [`console`], [`interrupt`], [`prompt`] (typed input),
//! [`kb_services`], `shop_functions` and the simulated robot (`robot`,
//! feature `sim`), `robot_hook` (another robot: [`RobotHook`]),
//! `debug_hooks` ([`DebugHooks`]), `observers` and
//! `live_view` (what watches a run), [`sandbox`] (the operating system's
//! confinement of a task), `runner` ([`Runner`]: the run), and
//! `task` (a compiled task's [`main`]). The public items of the private
//! modules are re-exported here.
//!
//! [`Perception`]: sitlog_runtime::machine::Perception
//! [`Actions`]: sitlog_runtime::machine::Actions

mod assets;
pub mod cli;
pub mod console;
mod debug_hooks;
pub mod interrupt;
pub mod kb_services;
mod live_view;
mod observers;
pub mod prompt;
#[cfg(feature = "sim")]
pub mod robot;
mod robot_hook;
mod runner;
pub mod sandbox;
#[cfg(feature = "sim")]
mod shop_functions;
mod streams;
mod task;

pub use assets::{
    app_name, AssetError, Assets, FileError, TextFile, KB_FILE, ROS2_FILE, WORLD_FILE,
};
pub use cli::{Format, HistoryMode, RobotKind, RunArgs, SandboxMode};
pub use debug_hooks::{DebugHooks, MakePerception, WorldProbe};
pub use robot_hook::{RobotHook, RobotParts, RobotSetup};
pub use runner::{KbProbe, PerceptionWrap, Runner};
pub use streams::Streams;
pub use task::{
    main, main_failed, main_failed_from, main_from, main_legacy, main_with_robot, on_big_stack,
};

/// The world's user functions (`shop_diagnose/4`, ...) over a simulator
/// that another robot keeps as its belief of the world (sitlog-ros).
#[cfg(feature = "sim")]
pub use shop_functions::{register as register_world_functions, SimAccess};

/// The user functions the simulated robot registers when a task runs on a
/// world (`shop_diagnose/4`, ...), by name and arity: `sitlogc check`
/// passes them to the checker, which does not depend on this crate.
#[cfg(feature = "sim")]
pub const WORLD_FUNCTIONS: &[(&str, usize)] = shop_functions::FUNCTIONS;
/// Without the simulator no world functions exist.
#[cfg(not(feature = "sim"))]
pub const WORLD_FUNCTIONS: &[(&str, usize)] = &[];
