//! `sitlog-compiler`: SitLog source to checked program, and from there to the
//! reference interpreter and generated Rust.
//!
//! Stages run one way: [`load`] (files → read terms) → [`ast`] (SitLog layer)
//! → [`check`] (diagnostics; produces [`check::Checked`]) → IR → interpret |
//! generate. Only [`load`] touches the file system; rendering of diagnostics
//! lives in [`diag`].

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
pub mod package;
pub mod resolve;
pub mod run;
pub mod source;
pub mod types;

use std::path::Path;

/// Loads and checks an application directory or DM file.
pub fn check_path(
    path: &Path,
) -> Result<(Result<check::Checked, ast::Program>, Vec<diag::Diagnostic>), load::LoadError> {
    let (program, diags) = load::load(path)?;
    Ok(check::check(program, diags))
}

/// [`check_path`], with unresolved names as warnings (see [`check::check_with`]).
pub fn check_path_lenient(
    path: &Path,
) -> Result<(Result<check::Checked, ast::Program>, Vec<diag::Diagnostic>), load::LoadError> {
    let (program, diags) = load::load(path)?;
    Ok(check::check_with(program, diags, true))
}

/// [`check_path`] with [`check::CheckOptions`].
pub fn check_path_opts(
    path: &Path,
    options: check::CheckOptions,
) -> Result<(Result<check::Checked, ast::Program>, Vec<diag::Diagnostic>), load::LoadError> {
    let (program, diags) = load::load(path)?;
    Ok(check::check_opts(program, diags, options))
}
