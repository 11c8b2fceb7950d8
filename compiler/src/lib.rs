//! `sitlog-compiler`: SitLog source to checked program, and from there to the
//! reference interpreter and generated Rust.
//!
//! Stages run one way: [`load`] (files → read terms) → [`ast`] (SitLog layer)
//! → [`check`] (diagnostics; produces [`check::Checked`]) → IR → interpret |
//! generate. Only [`load`] touches the file system; rendering of diagnostics
//! lives in [`diag`].

#[cfg(feature = "cli")]
pub mod analysis;
mod app;
pub mod ast;
pub mod build;
pub mod check;
pub mod codegen;
pub mod diag;
pub mod diagram;
pub mod interp;
pub mod ir;
pub mod legacy;
pub mod load;
#[cfg(feature = "cli")]
pub mod package;
pub mod resolve;
pub mod run;
pub mod scaffold;
pub mod source;
pub mod types;
#[cfg(feature = "cli")]
pub mod watch;

use std::path::Path;

/// Loads and checks an application directory or DM file.
///
/// The functions of the simulated robot ([`sitlog_robot::WORLD_FUNCTIONS`])
/// are known to the checker when the application runs on a world.
pub fn check_path(
    path: &Path,
) -> Result<(Result<check::Checked, ast::Program>, Vec<diag::Diagnostic>), load::LoadError> {
    check_path_opts(path, check::CheckOptions::default())
}

/// [`check_path`], with unresolved names as warnings (see [`check::check_with`]).
pub fn check_path_lenient(
    path: &Path,
) -> Result<(Result<check::Checked, ast::Program>, Vec<diag::Diagnostic>), load::LoadError> {
    check_path_opts(
        path,
        check::CheckOptions {
            unresolved_as_warnings: true,
            ..Default::default()
        },
    )
}

/// [`check_path`] with [`check::CheckOptions`] (the simulated robot's
/// functions are added to `world_functions` if it is empty).
pub fn check_path_opts(
    path: &Path,
    #[cfg_attr(not(feature = "cli"), allow(unused_mut))] mut options: check::CheckOptions,
) -> Result<(Result<check::Checked, ast::Program>, Vec<diag::Diagnostic>), load::LoadError> {
    let (program, diags) = load::load(path)?;
    #[cfg(feature = "cli")]
    if options.world_functions.is_empty() {
        options.world_functions = sitlog_robot::WORLD_FUNCTIONS;
    }
    Ok(check::check_opts(program, diags, options))
}
