//! `sitlogc`: the SitLog command-line tool. Argument parsing, exit codes and
//! the choice of output format only; the work is done by the library.

use clap::{Parser, Subcommand, ValueEnum};
use sitlog_compiler::diag::{self, Severity};
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "sitlogc",
    version,
    about = "Check, run and compile SitLog task programs (dialogue models)",
    long_about = "Check, run and compile SitLog task programs (dialogue models).\n\n\
An application is a directory: the DM files listed in its `models` file (or every `*.dm` \
below it), plus global_vars.pl, basic_actions.pl, expectation_types.pl, user_functions.pl \
and templates.pl beside them."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Read and check applications or DM files, reporting every problem found.
    ///
    /// Each PATH is a DM file (a program of one file), an application
    /// directory (it has a `models` file or `*.dm` files directly in it), or
    /// a directory of applications (each checked on its own). Exit status: 0 without errors,
    /// 1 when an error was found, 2 on usage or I/O problems.
    Check {
        /// Application directories or DM files.
        #[arg(required = true, value_name = "PATH")]
        paths: Vec<PathBuf>,
        /// `human`: rustc-like text on stderr; `json`: one JSON object per
        /// diagnostic and line on stdout (code, severity, message, file, line,
        /// column, end, label, labels, help).
        #[arg(long, value_enum, default_value_t = Format::Human)]
        format: Format,
        /// Treat warnings as errors (exit status 1).
        #[arg(long)]
        deny_warnings: bool,
        /// Do not print warnings.
        #[arg(long, short)]
        quiet: bool,
    },
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum Format {
    Human,
    Json,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return match e.kind() {
                clap::error::ErrorKind::DisplayHelp | clap::error::ErrorKind::DisplayVersion => {
                    ExitCode::SUCCESS
                }
                _ => ExitCode::from(2),
            };
        }
    };
    // Deep terms are handled by stacker and explicit stacks; a big main stack
    // is a cheap extra margin for the rest.
    let child = std::thread::Builder::new()
        .stack_size(256 * 1024 * 1024)
        .spawn(move || run(cli));
    match child.map(|h| h.join()) {
        Ok(Ok(code)) => ExitCode::from(code),
        _ => {
            eprintln!("sitlogc: internal error");
            ExitCode::from(101)
        }
    }
}

fn run(cli: Cli) -> u8 {
    match cli.command {
        Command::Check {
            paths,
            format,
            deny_warnings,
            quiet,
        } => check(&paths, format, deny_warnings, quiet),
    }
}

fn check(paths: &[PathBuf], format: Format, deny_warnings: bool, quiet: bool) -> u8 {
    let color = std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none();
    let mut errors = 0usize;
    let mut warnings = 0usize;
    let mut io_failed = false;
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let mut programs = Vec::new();
    for path in paths {
        match sitlog_compiler::load::discover(path) {
            Ok(found) if found.is_empty() => {
                eprintln!(
                    "warning: no application or DM file found in {}",
                    path.display()
                )
            }
            Ok(found) => programs.extend(found),
            Err(e) => {
                eprintln!("error: cannot read {e}");
                io_failed = true;
            }
        }
    }
    for path in &programs {
        let (result, diags) = match sitlog_compiler::check_path(path) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("error: cannot read {e}");
                io_failed = true;
                continue;
            }
        };
        let program = match &result {
            Ok(checked) => checked.program(),
            Err(program) => program,
        };
        for d in &diags {
            match d.severity {
                Severity::Error => errors += 1,
                Severity::Warning => warnings += 1,
            }
            if quiet && d.severity == Severity::Warning {
                continue;
            }
            match format {
                Format::Human => eprint!("{}", diag::render_human(d, &program.sources, color)),
                Format::Json => {
                    let _ = writeln!(out, "{}", diag::render_json(d, &program.sources));
                }
            }
        }
    }
    if format == Format::Human {
        eprintln!(
            "checked {} program(s): {} error(s), {} warning(s)",
            programs.len(),
            errors,
            warnings
        );
    }
    if io_failed {
        2
    } else if errors > 0 || (deny_warnings && warnings > 0) {
        1
    } else {
        0
    }
}
