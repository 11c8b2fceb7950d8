//! `include_dm!`'s compile tests (`tests/ui.rs`, trybuild): a good DM
//! compiles and runs, bad ones give `compile_error!`s naming the `.dm` file,
//! line and column.
//!
//! They live in this empty crate, not in `sitlog-macros`, because trybuild's
//! project depends on every dependency of the crate the test is in: from
//! `sitlog-macros` that made the test program depend on the compiler, `syn`
//! and the rest of the proc macro's own dependencies, so its nested cargo
//! build compiled them twice, for the host and for the target (issue 30).
//! Invariant: this crate's dependencies are what the test programs use.
