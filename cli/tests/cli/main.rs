//! The command-line tests of `sitlogc`, one test binary (one link) with a
//! module per subcommand or concern; [`support`] holds what they share.

mod support;

mod apptest;
mod build;
mod check;
mod checks;
mod conventions;
mod debug;
mod diagram;
mod explain_types;
mod fidelity;
mod hunt;
mod kb;
mod legacy;
mod lsp;
mod new;
mod prompt;
mod reliability;
#[cfg(feature = "ros2")]
mod ros;
mod run;
mod sandbox;
mod trust;
mod tutorial;
mod view;
mod watch;
mod watch_reload;
mod world;
