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
    /// Run an application: on its simulated world, or in test mode.
    ///
    /// With a world (the application's `world.toml`, or --world FILE) the
    /// task runs on the simulated robot and user, and the conversation is
    /// printed as it happens. Without one it runs in test mode, like the
    /// original interpreter: each expectation of a perceptual situation is
    /// met by a term read from the script (one term per line, ending with
    /// `.`) or typed at a prompt on stdin. At the end the task history, the
    /// final out_arg and the global variables are printed. Exit status: 0
    /// when the main DM reached a final situation, 1 on a run-time error
    /// (the history so far is still printed), 2 on usage or I/O problems.
    Run {
        /// The application directory (or a single DM file).
        #[arg(value_name = "APP")]
        app: PathBuf,
        #[command(flatten)]
        run: sitlog_robot::cli::RunArgs,
        /// Run even if next situations, embedded DMs, exit arcs or SitLog
        /// variables do not resolve (E0212, E0216–E0219); taking such a path
        /// stops the task with a run-time error. For legacy applications.
        #[arg(long)]
        allow_unresolved: bool,
    },
    /// Compile an application to one executable.
    ///
    /// Generates a Cargo package under `target/sitlog-build/<app>/` that uses
    /// this workspace's runtime, builds it (cargo's progress on stderr; the
    /// build cache in `target/sitlog-build/target` is shared by every
    /// application) and copies the executable to FILE. The executable runs
    /// the task with the options of `sitlogc run` (`--main`, `--in-arg`,
    /// `--script`, `--format`, `--history`, `--trace`). With `--emit rust`
    /// the generated Rust is written to FILE (stdout without -o) instead.
    Build {
        /// The application directory (or a single DM file).
        #[arg(value_name = "APP")]
        app: PathBuf,
        /// Where to write the executable (default: the application's name).
        #[arg(short, long, value_name = "FILE")]
        output: Option<PathBuf>,
        /// Build with optimizations (the default: a shipped task is a
        /// release build; kept for compatibility).
        #[arg(long, conflicts_with = "debug")]
        release: bool,
        /// Build without optimizations (faster to build).
        #[arg(long)]
        debug: bool,
        /// `rust`: only write the generated code.
        #[arg(long, value_enum)]
        emit: Option<Emit>,
        /// Print what type inference found (which variables and situations
        /// run on native values, and why the others stay terms) and stop.
        #[arg(long)]
        explain_types: bool,
    },
    /// Ask a knowledge base one question (for people exploring a KB).
    ///
    /// QUERY is one service call with the original's name and argument
    /// order, leaving out the KB argument; the answer is the last argument,
    /// written as a variable, e.g. `object_property_value(pete, lives, X)`.
    /// Prints the answer (writeq style) or `false`. FILE is never modified.
    /// Exit status: 0 with an answer or `false`, 1 on a bad KB or query.
    Kb {
        /// The KB file (a Prolog list of `class(Id, Mother, Props, Rels, Individuals)`).
        #[arg(value_name = "FILE")]
        file: PathBuf,
        /// An update applied before the query (repeatable, in order),
        /// e.g. `--do 'add_object_property(mug1, misplaced, yes)'`.
        #[arg(long = "do", value_name = "UPDATE", allow_hyphen_values = true)]
        updates: Vec<String>,
        /// The service call.
        #[arg(value_name = "QUERY", allow_hyphen_values = true)]
        query: String,
    },
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum Emit {
    Rust,
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
        Command::Run {
            app,
            run,
            allow_unresolved,
        } => run_app(&app, &run, allow_unresolved),
        Command::Build {
            app,
            output,
            release: _,
            debug,
            emit,
            explain_types,
        } => {
            let release = !debug;
            if explain_types {
                explain_types_of(&app)
            } else {
                build_app(&app, output, release, emit)
            }
        }
        Command::Kb {
            file,
            updates,
            query,
        } => match sitlog_kb::cli(&file, &updates, &query) {
            Ok(line) => {
                println!("{line}");
                0
            }
            Err(e) => {
                eprintln!("{e}");
                1
            }
        },
    }
}

/// Loads and checks an application, printing its errors; `Err` is the exit status.
fn checked_ir(app: &std::path::Path) -> Result<sitlog_compiler::ir::Ir, u8> {
    checked_ir_with(app, false)
}

fn checked_ir_with(app: &std::path::Path, lenient: bool) -> Result<sitlog_compiler::ir::Ir, u8> {
    let loaded = if lenient {
        sitlog_compiler::check_path_lenient(app)
    } else {
        sitlog_compiler::check_path(app)
    };
    let (result, diags) = match loaded {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: cannot read {e}");
            return Err(2);
        }
    };
    let color = std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none();
    let program_sources = match &result {
        Ok(c) => &c.program().sources,
        Err(p) => &p.sources,
    };
    for d in diags.iter().filter(|d| d.is_error()) {
        eprint!("{}", diag::render_human(d, program_sources, color));
    }
    match result {
        Ok(c) => Ok(sitlog_compiler::ir::lower(&c)),
        Err(_) => {
            let n = diags.iter().filter(|d| d.is_error()).count();
            eprintln!("error: the application has {n} error(s); run `sitlogc check` for details");
            Err(1)
        }
    }
}

fn explain_types_of(app: &std::path::Path) -> u8 {
    match checked_ir(app) {
        Ok(ir) => {
            let types = sitlog_compiler::types::infer(&ir);
            print!("{}", sitlog_compiler::types::explain(&ir, &types));
            0
        }
        Err(code) => code,
    }
}

fn build_app(
    app: &std::path::Path,
    output: Option<PathBuf>,
    release: bool,
    emit: Option<Emit>,
) -> u8 {
    use sitlog_compiler::{build, package};
    if let Err(code) = checked_ir(app) {
        return code;
    }
    let compiled = match build::generate(app, &app.display().to_string()) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            return 1;
        }
    };
    if emit == Some(Emit::Rust) {
        let text = compiled.to_file_string();
        return match output {
            Some(path) => match build::write_if_changed(&path, &text) {
                Ok(_) => 0,
                Err(e) => {
                    eprintln!("error: cannot write {}: {e}", path.display());
                    2
                }
            },
            None => {
                print!("{text}");
                0
            }
        };
    }
    let output = output.unwrap_or_else(|| PathBuf::from(build::app_name(app)));
    let layout = package::Layout::workspace();
    let built = package::write_package(&compiled, app, &layout).and_then(|(dir, name)| {
        eprintln!("sitlogc: building {} in {}", name, dir.display());
        package::build_package(&dir, &name, &layout, release, &output)
    });
    match built {
        Ok(()) => {
            eprintln!("sitlogc: wrote {}", output.display());
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            2
        }
    }
}

fn run_app(app: &std::path::Path, args: &sitlog_robot::cli::RunArgs, allow_unresolved: bool) -> u8 {
    let ir = match checked_ir_with(app, allow_unresolved) {
        Ok(ir) => ir,
        Err(code) => return code,
    };
    let assets = match sitlog_robot::Assets::from_app(app) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("error: {e}");
            return 2;
        }
    };
    #[allow(unused_mut)]
    let mut functions = sitlog_runtime::Functions::standard();
    // The application's user_functions.pl and templates.pl (feature `prolog`).
    #[cfg(feature = "prolog")]
    if let Err(errors) =
        sitlog_compiler::run::install_prolog(&ir, &mut functions, Default::default())
    {
        for e in errors {
            eprintln!("error: {e}");
        }
        return 1;
    }
    sitlog_robot::execute(&ir, functions, args, &assets)
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
