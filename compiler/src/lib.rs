//! `sitlog-compiler`, the compiler core: SitLog source to a checked
//! program, and from there to the interpreter's plans, generated Rust and
//! diagrams. No command line, no robot: the `sitlogc` shell is `sitlog-cli`,
//! which sits on top of this crate (as Gleam's CLI on its `compiler-core`).
//!
//! Stages run one way, one module each:
//! [`load`] (files → read terms, with [`source`] positions) → [`ast`] (the
//! SitLog layer) → [`check`] (diagnostics, rendered by [`diag`]; produces
//! [`check::Checked`], the only input later stages accept; [`codes`] lists
//! every diagnostic code, [`suggest`] gives their "did you mean") → [`ir::lower`]
//! → [`mir::lower`] (plans over registers, typed by [`mir::ty::infer`];
//! built and typed once per program by the code generator, which also
//! gives `--explain-types` ([`codegen::explain_types`]))
//! → the back ends: [`interp`] (plans the runtime's machine runs, with
//! [`instantiate`] the reference path from templates; [`run`] hands them to
//! the one runner, `sitlog_runtime::app::run`), [`codegen`] (Rust for
//! `include_dm!`, build scripts ([`build`]) and `sitlogc build`: term code
//! from the MIR's plans, native code from its types),
//! [`diagram`] (the papers' notation, drawn by `sitlog-graph`).
//!
//! Invariants: no stage reaches back to an earlier one; this crate never
//! depends on the robot, simulator, debugger, language server, live view or
//! command line (`tests/tests/repository/layout.rs` checks the crate graph);
//! it reads files only in [`load`] and writes only in [`build`] (the
//! generated file a build script asks for, as decisions.md §8 places that
//! helper here); semantics live in the runtime, so every back end runs the
//! same steps.

mod app;
pub mod ast;
pub mod build;
pub mod check;
pub mod codegen;
pub mod codes;
pub mod diag;
pub mod diagram;
pub mod instantiate;
pub mod interp;
pub mod ir;
pub mod load;
pub mod mir;
pub mod run;
pub mod source;
pub mod suggest;

use std::path::Path;

/// Loads and checks an application directory or DM file. Functions a host
/// registers (the simulated robot's, `sitlog_robot::WORLD_FUNCTIONS`) are
/// known to the checker only when [`check::CheckOptions::world_functions`]
/// names them ([`check_path_opts`]).
pub fn check_path(
    path: &Path,
) -> Result<(Result<check::Checked, ast::Program>, Vec<diag::Diagnostic>), load::LoadError> {
    check_path_opts(path, check::CheckOptions::default())
}

/// [`check_path`] with [`check::CheckOptions`].
pub fn check_path_opts(
    path: &Path,
    options: check::CheckOptions,
) -> Result<(Result<check::Checked, ast::Program>, Vec<diag::Diagnostic>), load::LoadError> {
    let library = options.library.unwrap_or(load::Library::none());
    let (program, diags) = load::load_with(path, library)?;
    Ok(check::check_opts(program, diags, options))
}
