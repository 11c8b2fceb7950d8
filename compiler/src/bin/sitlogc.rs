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
    /// Run an application in test mode, like the original interpreter.
    ///
    /// Each expectation of a perceptual situation is met by a term read from
    /// the script (one term per line, ending with `.`) or, without --script,
    /// typed at a prompt on stdin. At the end the task history, the final
    /// out_arg and the global variables are printed. Exit status: 0 when the
    /// main DM reached a final situation, 1 on a run-time error (the history
    /// so far is still printed), 2 on usage or I/O problems.
    Run {
        /// The application directory (or a single DM file).
        #[arg(value_name = "APP")]
        app: PathBuf,
        /// The DM to start, as a term (it may have arguments).
        #[arg(long, default_value = "main", value_name = "DM")]
        main: String,
        /// The initial pipe value, as a term (default: the atom `none`).
        #[arg(long, value_name = "TERM", allow_hyphen_values = true)]
        in_arg: Option<String>,
        /// Read the inputs of test mode from FILE instead of stdin.
        #[arg(long, value_name = "FILE")]
        script: Option<PathBuf>,
        /// `text`: the papers' history listing; `json`: one JSON object on stdout.
        #[arg(long, value_enum, default_value_t = RunFormat::Text)]
        format: RunFormat,
        /// `none` keeps no history, so that a long task runs in bounded memory.
        #[arg(long, value_enum, default_value_t = HistoryMode::Keep)]
        history: HistoryMode,
        /// Write one JSON object per transition to FILE as it happens.
        #[arg(long, value_name = "FILE")]
        trace: Option<PathBuf>,
    },
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum RunFormat {
    Text,
    Json,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum HistoryMode {
    Keep,
    None,
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
            main,
            in_arg,
            script,
            format,
            history,
            trace,
        } => run_app(RunArgs {
            app,
            main,
            in_arg,
            script,
            format,
            keep_history: history == HistoryMode::Keep,
            trace,
        }),
    }
}

struct RunArgs {
    app: PathBuf,
    main: String,
    in_arg: Option<String>,
    script: Option<PathBuf>,
    format: RunFormat,
    keep_history: bool,
    trace: Option<PathBuf>,
}

fn run_app(args: RunArgs) -> u8 {
    use sitlog_compiler::run::{self, RunConfig};
    use sitlog_runtime::machine::{Observer, Options, Perception};
    use sitlog_runtime::report;
    use sitlog_runtime::testmode::{PromptPerception, ScriptPerception, TextActions};

    let (result, diags) = match sitlog_compiler::check_path(&args.app) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: cannot read {e}");
            return 2;
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
    let checked = match result {
        Ok(c) => c,
        Err(_) => {
            let n = diags.iter().filter(|d| d.is_error()).count();
            eprintln!("error: the application has {n} error(s); run `sitlogc check` for details");
            return 1;
        }
    };
    let ir = sitlog_compiler::ir::lower(&checked);
    let mut perception: Box<dyn Perception> = match &args.script {
        Some(path) => match std::fs::read_to_string(path) {
            Ok(text) => Box::new(ScriptPerception::new(path.display().to_string(), text)),
            Err(e) => {
                eprintln!("error: cannot read script {}: {e}", path.display());
                return 2;
            }
        },
        None => Box::new(PromptPerception::new(std::io::stdin().lock())),
    };
    let mut trace = match &args.trace {
        Some(path) => match std::fs::File::create(path) {
            Ok(f) => Some(report::JsonTrace::new(std::io::BufWriter::new(f))),
            Err(e) => {
                eprintln!("error: cannot create trace file {}: {e}", path.display());
                return 2;
            }
        },
        None => None,
    };
    let mut actions = TextActions::new(std::io::stderr(), ir.basic_actions.clone());
    let config = RunConfig {
        main: args.main,
        in_arg: args.in_arg,
        options: Options {
            keep_history: args.keep_history,
            ..Options::default()
        },
        ..RunConfig::default()
    };
    let observer = trace.as_mut().map(|t| t as &mut dyn Observer);
    let (outcome, mut store) =
        match run::run(&ir, config, perception.as_mut(), &mut actions, observer) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("error: {e}");
                return 2;
            }
        };
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    match args.format {
        RunFormat::Json => {
            let _ = writeln!(out, "{}", report::outcome_json(&store, &outcome));
        }
        RunFormat::Text => {
            let _ = write!(out, "{}", report::outcome_text(&mut store, &outcome));
        }
    }
    if let Err(e) = &outcome.result {
        eprintln!("error: {e}");
        1
    } else {
        0
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
