//! `include_dm!`'s compile tests (`tests/ui.rs`): a good DM compiles and
//! runs, bad ones give `compile_error!`s naming the `.dm` file, line and
//! column (each bad case one `rustc` run against the proc macro the
//! workspace build made; until issue 40 a trybuild project, whose nested
//! cargo build compiled the compiler and the runtime again).
//!
//! They live in this empty crate, not in `sitlog-macros`: the proc-macro
//! crate's own tests would need the runtime as a dependency of the macro's
//! crate, and this crate's tests see only what a user of `include_dm!` sees.
//! Invariant: this crate's dependencies are what the test programs use.
