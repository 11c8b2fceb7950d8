//! What every command shares on its way out: whether stderr is coloured
//! (`--color`, `NO_COLOR`), writing to stdout (a closed pipe is quiet), and
//! loading and checking an application with its errors printed.

use crate::args::ColorWhen;
use sitlog_compiler::ast::Program;
use sitlog_compiler::check::{CheckOptions, Checked};
use sitlog_compiler::diag::{self, Diagnostic};
use sitlog_compiler::load::LoadError;
use std::io::{IsTerminal, Write};
use std::path::Path;

/// The `--color` of this run (set once in `run`).
pub static COLOR: std::sync::OnceLock<ColorWhen> = std::sync::OnceLock::new();

/// Whether diagnostics on stderr are coloured: `--color`, else (`auto`)
/// when stderr is a terminal and NO_COLOR is unset or empty
/// (<https://no-color.org>).
pub fn color_stderr() -> bool {
    match COLOR.get().copied().unwrap_or(ColorWhen::Auto) {
        ColorWhen::Always => true,
        ColorWhen::Never => false,
        ColorWhen::Auto => {
            std::io::stderr().is_terminal()
                && std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty())
        }
    }
}

/// Writes `text` to stdout: 0, or 2 with a message naming `what` when it
/// cannot be written (a closed pipe, as `| head` makes, is quiet: 0).
pub fn write_stdout(text: &str, what: &str) -> u8 {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Ok(()) => 0,
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => 0,
        Err(e) => {
            sitlog_runtime::errln!("error: cannot write {what} to stdout: {e}");
            2
        }
    }
}

/// Loads and checks an application or DM file as every command does: the
/// functions the simulated robot registers ([`sitlog_robot::WORLD_FUNCTIONS`])
/// are known to the checker unless `options` names others.
pub fn check_app(
    path: &Path,
    options: CheckOptions,
) -> Result<(Result<Checked, Program>, Vec<Diagnostic>), LoadError> {
    sitlog_compiler::check_path_opts(path, with_world(options))
}

/// `options` with the simulated robot's functions when it names none, and
/// the behaviour library ([`crate::library`]) when it names none.
pub fn with_world(mut options: CheckOptions) -> CheckOptions {
    if options.world_functions.is_empty() {
        options.world_functions = sitlog_robot::WORLD_FUNCTIONS;
    }
    if options.library.is_none() {
        options.library = Some(crate::library::library());
    }
    options
}

/// Loads and checks an application, printing its errors; `Err` is the exit status.
pub fn checked_ir(app: &Path) -> Result<sitlog_compiler::ir::Ir, u8> {
    checked_ir_opts(app, CheckOptions::default())
}

/// [`checked_ir`] with [`CheckOptions`] (under `legacy`, the identical
/// duplicate DMs' warnings are printed too).
pub fn checked_ir_opts(
    app: &std::path::Path,
    options: sitlog_compiler::check::CheckOptions,
) -> Result<sitlog_compiler::ir::Ir, u8> {
    checked_ir_strict(app, options, false)
}

/// Whether warnings are errors for `app`: `flag` (`--deny-warnings`) or its
/// `sitlog.toml` says so. `Err`: the exit status, the settings file's error
/// printed.
pub fn deny_warnings(app: &Path, flag: bool) -> Result<bool, u8> {
    deny_warnings_said(app, flag).map_err(|(code, _)| code)
}

/// [`deny_warnings`]; `Err` also holds the message printed.
pub fn deny_warnings_said(app: &Path, flag: bool) -> Result<bool, (u8, String)> {
    match crate::config::read(app) {
        Ok(config) => Ok(flag || config.deny_warnings),
        Err((code, message)) => {
            sitlog_runtime::errln!("{message}");
            Err((code, message))
        }
    }
}

/// [`checked_ir_opts`]; with `deny_warnings` the warnings are printed too
/// and any of them refuses the program, as an error does.
pub fn checked_ir_strict(
    app: &std::path::Path,
    options: sitlog_compiler::check::CheckOptions,
    deny_warnings: bool,
) -> Result<sitlog_compiler::ir::Ir, u8> {
    checked_ir_said(app, options, deny_warnings).map_err(|(code, _)| code)
}

/// [`checked_ir_strict`]; `Err` also holds what refused the program in
/// one line: the first error's `file:line:col: error[CODE]: message` (for
/// `run --format json`'s report).
pub fn checked_ir_said(
    app: &std::path::Path,
    options: sitlog_compiler::check::CheckOptions,
    deny_warnings: bool,
) -> Result<sitlog_compiler::ir::Ir, (u8, String)> {
    let loaded = check_app(app, options);
    let (result, diags) = match loaded {
        Ok(r) => r,
        Err(e) => {
            let message = format!("error: cannot read {e}");
            sitlog_runtime::errln!("{message}");
            return Err((2, message));
        }
    };
    let color = color_stderr();
    let program_sources = match &result {
        Ok(c) => &c.program().sources,
        Err(p) => &p.sources,
    };
    for d in diags.iter().filter(|d| {
        d.is_error()
            || deny_warnings
            || (options.legacy && d.code == sitlog_compiler::check::codes::DUPLICATE_DM_IDENTICAL)
            || d.code == sitlog_compiler::check::codes::LEFT_OUT
    }) {
        sitlog_runtime::errprint!("{}", diag::render_human(d, program_sources, color));
    }
    let errors = diags.iter().filter(|d| d.is_error()).count();
    let warnings = diags.len() - errors;
    // The first diagnostic that refuses the program, in one line.
    let first = diags
        .iter()
        .find(|d| d.is_error())
        .or_else(|| diags.iter().find(|_| deny_warnings))
        .map(|d| {
            let short = diag::render_short(d, program_sources);
            short.lines().next().unwrap_or_default().to_owned()
        })
        .unwrap_or_default();
    match result {
        Ok(_) if deny_warnings && warnings > 0 => {
            let message = format!(
                "error: the application has {warnings} warning(s), and warnings are denied (--deny-warnings, or `deny-warnings = true` in {})",
                crate::config::FILE
            );
            sitlog_runtime::errln!("{message}");
            Err((1, format!("{message}; the first: {first}")))
        }
        Ok(c) => Ok(sitlog_compiler::ir::lower(&c)),
        Err(_) => {
            sitlog_runtime::errln!(
                "error: the application has {errors} error(s); run `sitlogc check` for details"
            );
            Err((1, first))
        }
    }
}
