//! `sitlog-cli`: the `sitlogc` command line, a shell over the compiler core
//! (`sitlog-compiler`), the runner and simulated robot (`sitlog-robot`), the
//! debugger (`sitlog-debug`), the language server (`sitlog-lsp`) and the KB
//! (`sitlog-kb`). Everything only the command line needs lives here and
//! nowhere below: argument parsing ([`args`]), one module per subcommand
//! ([`commands`]), an application's settings file ([`config`]), hot reload
//! ([`watch`]), packaging a compiled task ([`package`]), the behaviour
//! library built into `sitlogc` ([`library`]), new applications
//! ([`scaffold`]), an application's own tests ([`apptest`], `sitlogc
//! test`), the legacy profile's Prolog layer
//! ([`legacy`]) and the editor analysis ([`analysis`]).
//!
//! Invariant: this crate is the top of the dependency graph; no crate of the
//! workspace depends on it (the tests in `tests/` check the crate layers).
//! Its modules only read the file system, run cargo (`package`) and write
//! files the user named or the build cache; the semantics of SitLog are in
//! the crates below.

pub mod analysis;
pub mod apptest;
pub mod args;
pub mod commands;
pub mod config;
pub mod legacy;
pub mod library;
pub mod output;
pub mod package;
pub mod scaffold;
pub mod watch;
