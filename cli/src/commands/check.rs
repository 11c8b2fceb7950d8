//! `sitlogc check`: every problem of applications and DM files, as text
//! on stderr or JSON lines on stdout, and (`--origins`) where the files
//! named by a library name came from.

use crate::args::Format;
use crate::output::color_stderr;
use sitlog_compiler::diag::{self, Severity};
use std::io::Write;
use std::path::PathBuf;

pub fn check(
    paths: &[PathBuf],
    format: Format,
    deny_warnings: bool,
    quiet: bool,
    legacy: bool,
    origins: bool,
) -> u8 {
    let color = color_stderr();
    let mut errors = 0usize;
    let mut warnings = 0usize;
    // Warnings of applications whose sitlog.toml denies them.
    let mut denied_warnings = 0usize;
    let mut io_failed = false;
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let mut programs = Vec::new();
    for path in paths {
        match sitlog_compiler::load::discover(path) {
            // Nothing to check is a usage error (exit 2, like a missing
            // path): a check that passes on nothing would hide a wrong path.
            Ok(found) if found.is_empty() => {
                sitlog_runtime::errln!(
                    "error: no application or DM file found in {} (an application is a directory with a `models` file or `*.dm` files)",
                    path.display()
                );
                io_failed = true;
            }
            Ok(found) => programs.extend(found),
            Err(e) => {
                sitlog_runtime::errln!("error: cannot read {e}");
                io_failed = true;
            }
        }
    }
    for path in &programs {
        // The application's sitlog.toml may deny its warnings (a bad one
        // is an error; the program is checked all the same).
        let denied = match crate::config::read(path) {
            Ok(config) => config.deny_warnings,
            Err((code, message)) => {
                sitlog_runtime::errln!("{message}");
                if code == 1 {
                    errors += 1;
                } else {
                    io_failed = true;
                }
                false
            }
        };
        let options = sitlog_compiler::check::CheckOptions {
            legacy,
            ..Default::default()
        };
        let (result, diags) = match crate::output::check_app(path, options) {
            Ok(r) => r,
            Err(e) => {
                sitlog_runtime::errln!("error: cannot read {e}");
                io_failed = true;
                continue;
            }
        };
        let program = match &result {
            Ok(checked) => checked.program(),
            Err(program) => program,
        };
        if origins {
            for line in origin_lines(path, program) {
                sitlog_runtime::errln!("{line}");
            }
        }
        for d in &diags {
            match d.severity {
                Severity::Error => errors += 1,
                Severity::Warning if denied => denied_warnings += 1,
                Severity::Warning => warnings += 1,
            }
            if quiet && d.severity == Severity::Warning && !denied {
                continue;
            }
            match format {
                Format::Human => {
                    sitlog_runtime::errprint!("{}", diag::render_human(d, &program.sources, color))
                }
                Format::Json => {
                    if let Err(e) = writeln!(out, "{}", diag::render_json(d, &program.sources)) {
                        if e.kind() != std::io::ErrorKind::BrokenPipe && !io_failed {
                            sitlog_runtime::errln!(
                                "error: cannot write the diagnostics to stdout: {e}"
                            );
                        }
                        io_failed |= e.kind() != std::io::ErrorKind::BrokenPipe;
                    }
                }
            }
        }
    }
    if let Err(e) = out.flush() {
        if e.kind() != std::io::ErrorKind::BrokenPipe {
            sitlog_runtime::errln!("error: cannot write the diagnostics to stdout: {e}");
            io_failed = true;
        }
    }
    if format == Format::Human {
        sitlog_runtime::errln!(
            "checked {} program(s): {} error(s), {} warning(s){}",
            programs.len(),
            errors,
            warnings + denied_warnings,
            if denied_warnings > 0 {
                format!(" ({denied_warnings} denied by {})", crate::config::FILE)
            } else {
                String::new()
            }
        );
    }
    if io_failed {
        2
    } else if errors > 0 || denied_warnings > 0 || (deny_warnings && warnings > 0) {
        1
    } else {
        0
    }
}

/// `--origins`: one line per file of `program` named by a library name,
/// saying where it was read from.
fn origin_lines(path: &std::path::Path, program: &sitlog_compiler::ast::Program) -> Vec<String> {
    program
        .library_files
        .iter()
        .map(|f| {
            let shown = &program.sources.get(f.file).name;
            let from = match (&f.root, &f.overrides) {
                (Some(root), _) => format!("from {root} ({shown})"),
                (None, Some(instead)) => {
                    format!("from its own copy {shown} (instead of {instead})")
                }
                (None, None) => format!("from its own copy {shown}"),
            };
            format!("{} uses {} {from}", path.display(), f.name)
        })
        .collect()
}
