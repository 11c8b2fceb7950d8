//! `sitlogc`: the SitLog command-line tool. Argument parsing, exit codes and
//! the choice of output format only; the work is done by the library.

use clap::{CommandFactory, Parser, Subcommand, ValueEnum};
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
    /// When diagnostics are coloured: `auto` when stderr is a terminal and
    /// NO_COLOR is unset or empty; `always`; `never`.
    #[arg(long, global = true, value_enum, value_name = "WHEN", default_value_t = ColorWhen::Auto)]
    color: ColorWhen,
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq, Debug)]
enum ColorWhen {
    Auto,
    Always,
    Never,
}

/// The `--color` of this run (set once in `run`).
static COLOR: std::sync::OnceLock<ColorWhen> = std::sync::OnceLock::new();

/// Whether diagnostics on stderr are coloured: `--color`, else (`auto`)
/// when stderr is a terminal and NO_COLOR is unset or empty
/// (<https://no-color.org>).
fn color_stderr() -> bool {
    match COLOR.get().copied().unwrap_or(ColorWhen::Auto) {
        ColorWhen::Always => true,
        ColorWhen::Never => false,
        ColorWhen::Auto => {
            std::io::stderr().is_terminal()
                && std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty())
        }
    }
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
        /// The original's rules, as `run --legacy` applies them: a DM
        /// defined twice identically is a warning (W0203), not an error.
        #[arg(long)]
        legacy: bool,
    },
    /// Run an application: on its simulated world, or in test mode.
    ///
    /// With a world (the application's `world.toml`, or --world FILE) the
    /// task runs on the simulated robot and user, and the conversation is
    /// printed as it happens. Without one it runs in test mode, like the
    /// original interpreter: each expectation of a perceptual situation is
    /// met by a term read from the script (one term per line, ending with
    /// `.`) or typed at a prompt on stdin. At the end the task history, the
    /// final out_arg and the global variables are printed. At the prompt,
    /// Ctrl-D (the end of stdin) ends the task where it waits. Exit status: 0
    /// when the main DM reached a final situation, 1 on a run-time error
    /// (the history so far is still printed), 2 on usage or I/O problems,
    /// 3 when the typed input ended before the task did, 130 / 143 when
    /// stopped by SIGINT / SIGTERM.
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
        /// Run an application written for the original interpreter
        /// unmodified, from the original's tree: load the Prolog files its
        /// `src/init.pl` consults from `$SITLOG_HOME` (KB services, parser,
        /// cognitive model, diagnosis, decision, planning) before the
        /// application's own; a DM defined twice identically is a warning
        /// (the first is used); implies --allow-unresolved.
        #[arg(long)]
        legacy: bool,
        /// The original's tree for --legacy (default: $SITLOG_HOME, else
        /// the nearest directory above APP that has src/init.pl).
        #[arg(long, value_name = "DIR", requires = "legacy")]
        sitlog_home: Option<PathBuf>,
        /// With --legacy: `prolog` runs the original's KB layer as it is;
        /// `native` serves its KB services, updates, loads and saves from
        /// our KB (sitlog-kb), the KB being a handle.
        #[arg(long, value_enum, value_name = "HOW", requires = "legacy", default_value_t = LegacyKb::Prolog)]
        legacy_kb: LegacyKb,
        /// Hot reload: when a file of the application changes (a DM file,
        /// `models`, global_vars.pl, basic_actions.pl, the Prolog user
        /// functions), read and check the program again; if it checks, the
        /// run goes on in the new program between two transitions, at the
        /// same DM and situation, keeping its stack, pipe, variables and
        /// history (a situation waiting for input takes it in the new
        /// program); if not, the diagnostics are printed and the old program
        /// goes on. A change that removes the situation the run is at, or a
        /// DM on its stack, stops the run (exit status 1). Not with --legacy.
        #[arg(long, conflicts_with = "legacy")]
        watch: bool,
    },
    /// Run an application under the step debugger (interpreted).
    ///
    /// A REPL over the live run: breakpoints (`break DM[:SITUATION]`,
    /// `break on error`), `step`, `next`, `finish`, `continue`, and at a
    /// stop `stack`, `pipe`, `vars`, `history`, `print TERM`, `world`; in
    /// test mode `input TERM` answers a perceptual situation the script has
    /// no input for. `help` lists the commands. The run's options are
    /// those of `sitlogc run`. Exit status: the run's, 0 after `quit`, 2 for
    /// a bad line in the --commands file. A compiled task gets the same
    /// debugger with `sitlogc build --debugger`.
    Debug {
        /// The application directory (or a single DM file).
        #[arg(value_name = "APP")]
        app: PathBuf,
        #[command(flatten)]
        run: sitlog_robot::cli::RunArgs,
        /// Read the commands from FILE (each echoed after the prompt)
        /// instead of the terminal; when it ends, the run goes on without
        /// stopping.
        #[arg(long, value_name = "FILE")]
        commands: Option<PathBuf>,
    },
    /// Replay a recorded run (`sitlogc run --trace FILE`) without running it.
    ///
    /// The debugger's commands over the recording, forwards and backwards:
    /// `step`, `back`, `goto N`, `next`, `finish`, `continue`, `break`,
    /// `stack`, `history`, `diff TRACE2`. With --diff, prints the first
    /// transition where the two recordings differ and exits (status 0 when
    /// they are the same, 1 when they differ). A bad trace is an error
    /// naming FILE:LINE (exit 2).
    Replay {
        /// The recording (JSON lines, as --trace writes them).
        #[arg(value_name = "TRACE")]
        trace: PathBuf,
        /// Compare with this recording and exit.
        #[arg(long, value_name = "TRACE2")]
        diff: Option<PathBuf>,
        /// Read the commands from FILE (each echoed after the prompt)
        /// instead of the terminal.
        #[arg(long, value_name = "FILE", conflicts_with = "diff")]
        commands: Option<PathBuf>,
    },
    /// Compile an application to one executable.
    ///
    /// Generates a Cargo package that uses the runtime shipped inside
    /// sitlogc, builds it with cargo (progress on stderr) and copies the
    /// executable to FILE, by default a file named after the application in
    /// the current directory (refused when a directory has that name: give
    /// -o then). Needs cargo, not the sitlog-rs sources: the runtime, the
    /// generated packages and the shared build cache live in the user's
    /// cache directory ($SITLOGC_CACHE_DIR, else $XDG_CACHE_HOME/sitlogc,
    /// else ~/.cache/sitlogc). The executable runs the task with the
    /// options of `sitlogc run`. With `--emit rust` the generated Rust is
    /// written to FILE (stdout without -o) instead. Exit status: 0 when
    /// written, 1 when the application has errors, 2 on usage, I/O or cargo
    /// problems. A compiled task does not reload when its sources change
    /// (that is `sitlogc run APP --watch`).
    Build {
        /// The application directory (or a single DM file).
        #[arg(value_name = "APP")]
        app: PathBuf,
        /// Where to write the executable (default: the application's name,
        /// in the current directory).
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
        /// Compile even if next situations, embedded DMs, exit arcs or
        /// SitLog variables do not resolve (E0212, E0216–E0219), as `run
        /// --allow-unresolved` runs them: taking such a path stops the task
        /// with a run-time error.
        #[arg(long)]
        allow_unresolved: bool,
        /// Link the step debugger: the executable runs the task under the
        /// debugger, as `sitlogc debug APP` runs the sources (commands from
        /// the terminal, or from its --commands FILE). Opt-in: a normal
        /// compiled task stays smaller.
        #[arg(long, conflicts_with = "emit")]
        debugger: bool,
    },
    /// Draw an application in the notation of the SitLog papers.
    ///
    /// Each DM is a dotted oval; situations are circles with their id and
    /// type; arcs are labelled `expectation : action`; a next situation
    /// given by a function is a bold dot labelled with it, with one exit
    /// per value the compiler can tell (dashed when it cannot); several
    /// instances of one situation id are reached through a `∨` circle;
    /// recursive situations hold one return dot per final situation of
    /// their embedded DM; bold arrows are the pipe between DMs and the
    /// task's out_arg. Every element's SVG `<title>` starts with the
    /// `file:line:col` where it is written. An application with errors
    /// gives its diagnostics, not a picture (exit status 1).
    Graph {
        /// The application directory (or a single DM file).
        #[arg(value_name = "APP")]
        app: PathBuf,
        /// Where to write the diagram (default: stdout).
        #[arg(short, long, value_name = "FILE")]
        output: Option<PathBuf>,
        /// Draw only this DM (by name).
        #[arg(long, value_name = "NAME")]
        dm: Option<String>,
        /// The main DM, whose out_arg leaves the task (default `main`).
        #[arg(long, value_name = "NAME")]
        main: Option<String>,
        /// `svg` (laid out here), `dot` (for Graphviz), `json` (nodes,
        /// edges, labels and source locations, for other tools).
        #[arg(long, value_enum, default_value_t = GraphFormat::Svg)]
        format: GraphFormat,
        /// Colour a recorded run (`sitlogc run --trace FILE`): visited
        /// situations and arcs taken, with how often.
        #[arg(long, value_name = "FILE")]
        trace: Option<PathBuf>,
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
    /// A language server (LSP, JSON-RPC on stdin/stdout) for editors: the
    /// diagnostics of `check` as you type, go to the definition of a DM,
    /// situation, global, basic action or user function, and hovers.
    /// Point your editor's LSP client at `sitlogc lsp` for `*.dm` files.
    Lsp,
    /// Print a completion script for SHELL on stdout.
    ///
    /// For example `sitlogc completions bash > ~/.local/share/bash-completion/completions/sitlogc`,
    /// `sitlogc completions zsh > ~/.zfunc/_sitlogc` (with `~/.zfunc` in
    /// `fpath`), or `sitlogc completions fish > ~/.config/fish/completions/sitlogc.fish`.
    Completions {
        /// The shell.
        #[arg(value_enum)]
        shell: clap_complete::Shell,
    },
    /// Write the manual page (roff) of sitlogc.
    ///
    /// Without --dir, the page `sitlogc(1)` goes to stdout (try `sitlogc man
    /// | man -l -`); with --dir, `sitlogc.1` and one page per subcommand
    /// (`sitlogc-run.1`, ...) are written into DIR.
    Man {
        /// Write every page into this directory (made if missing).
        #[arg(long, value_name = "DIR")]
        dir: Option<PathBuf>,
    },
    /// Make a new application that checks and runs at once.
    ///
    /// Creates the directory NAME (it must not exist) with a DM `main` (a
    /// speech situation and a recursive situation calling the DM
    /// `ask_name`), global_vars.pl, basic_actions.pl, user_functions.pl, a
    /// `models` file, a test-mode script, the golden output of running it
    /// (`expected.txt`) and a README. Exit status: 0 when made, 2 when NAME
    /// exists or cannot be written (nothing is changed then).
    New {
        /// The application directory to make; its last component names the application.
        #[arg(value_name = "NAME")]
        name: PathBuf,
    },
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum LegacyKb {
    Prolog,
    Native,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum Emit {
    Rust,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum GraphFormat {
    Svg,
    Dot,
    Json,
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
    let _ = COLOR.set(cli.color);
    match cli.command {
        Command::Completions { shell } => {
            let mut out = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "sitlogc", &mut out);
            write_stdout(&String::from_utf8_lossy(&out), "the completion script")
        }
        Command::Man { dir } => man(dir.as_deref()),
        Command::Check {
            paths,
            format,
            deny_warnings,
            quiet,
            legacy,
        } => check(&paths, format, deny_warnings, quiet, legacy),
        Command::Run {
            app,
            run,
            allow_unresolved,
            legacy,
            sitlog_home,
            legacy_kb,
            watch,
        } => {
            let legacy = legacy.then_some(sitlog_home);
            run_app(
                &app,
                &run,
                allow_unresolved,
                legacy.as_ref().map(|h| h.as_deref()),
                legacy_kb == LegacyKb::Native,
                None,
                watch,
            )
        }
        Command::Debug { app, run, commands } => run_app(
            &app,
            &run,
            false,
            None,
            false,
            Some(commands.as_deref()),
            false,
        ),
        Command::Replay {
            trace,
            diff,
            commands,
        } => replay(&trace, diff.as_deref(), commands.as_deref()),
        Command::Build {
            app,
            output,
            release: _,
            debug,
            emit,
            explain_types,
            allow_unresolved,
            debugger,
        } => {
            let release = !debug;
            if explain_types {
                explain_types_of(&app)
            } else {
                build_app(&app, output, release, emit, allow_unresolved, debugger)
            }
        }
        Command::Lsp => match sitlog_lsp::run_stdio(&sitlog_compiler::analysis::Analysis) {
            Ok(()) => 0,
            Err(e) => {
                eprintln!("error: sitlogc lsp: {e}");
                2
            }
        },
        Command::Graph {
            app,
            output,
            dm,
            main,
            format,
            trace,
        } => graph(&app, output, dm, main, format, trace),
        Command::New { name } => new_app(&name),
        Command::Kb {
            file,
            updates,
            query,
        } => match sitlog_kb::cli(&file, &updates, &query) {
            Ok(line) => write_stdout(&format!("{line}\n"), "the answer"),
            Err(e) => {
                eprintln!("{e}");
                1
            }
        },
    }
}

/// `sitlogc man [--dir DIR]`.
fn man(dir: Option<&std::path::Path>) -> u8 {
    let command = Cli::command();
    match dir {
        None => {
            let mut out = Vec::new();
            match clap_mangen::Man::new(command).render(&mut out) {
                Ok(()) => write_stdout(&String::from_utf8_lossy(&out), "the manual page"),
                Err(e) => {
                    eprintln!("error: cannot render the manual page: {e}");
                    2
                }
            }
        }
        Some(dir) => {
            let written =
                std::fs::create_dir_all(dir).and_then(|_| clap_mangen::generate_to(command, dir));
            match written {
                Ok(()) => {
                    eprintln!("sitlogc: wrote the manual pages into {}", dir.display());
                    0
                }
                Err(e) => {
                    eprintln!(
                        "error: cannot write the manual pages into {}: {e}",
                        dir.display()
                    );
                    2
                }
            }
        }
    }
}

/// `sitlogc new NAME`.
fn new_app(dir: &std::path::Path) -> u8 {
    match sitlog_compiler::scaffold::create(dir) {
        Ok(files) => {
            let d = dir.display();
            eprintln!("sitlogc: made the application {d} ({} files)", files.len());
            eprintln!("  check it:  sitlogc check {d}");
            eprintln!("  run it:    sitlogc run {d} --script {d}/script.txt");
            eprintln!("  talk to it: sitlogc run {d}");
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            2
        }
    }
}

/// Writes `text` to stdout: 0, or 2 with a message naming `what` when it
/// cannot be written (a closed pipe, as `| head` makes, is quiet: 0).
fn write_stdout(text: &str, what: &str) -> u8 {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Ok(()) => 0,
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => 0,
        Err(e) => {
            eprintln!("error: cannot write {what} to stdout: {e}");
            2
        }
    }
}

/// Loads and checks an application, printing its errors; `Err` is the exit status.
fn checked_ir(app: &std::path::Path) -> Result<sitlog_compiler::ir::Ir, u8> {
    checked_ir_with(app, false)
}

fn checked_ir_with(app: &std::path::Path, lenient: bool) -> Result<sitlog_compiler::ir::Ir, u8> {
    checked_ir_opts(
        app,
        sitlog_compiler::check::CheckOptions {
            unresolved_as_warnings: lenient,
            ..Default::default()
        },
    )
}

fn checked_ir_opts(
    app: &std::path::Path,
    options: sitlog_compiler::check::CheckOptions,
) -> Result<sitlog_compiler::ir::Ir, u8> {
    let loaded = sitlog_compiler::check_path_opts(app, options);
    let (result, diags) = match loaded {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: cannot read {e}");
            return Err(2);
        }
    };
    let color = color_stderr();
    let program_sources = match &result {
        Ok(c) => &c.program().sources,
        Err(p) => &p.sources,
    };
    for d in diags.iter().filter(|d| {
        d.is_error()
            || (options.legacy && d.code == sitlog_compiler::check::codes::DUPLICATE_DM_IDENTICAL)
    }) {
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

fn graph(
    app: &std::path::Path,
    output: Option<PathBuf>,
    dm: Option<String>,
    main: Option<String>,
    format: GraphFormat,
    trace: Option<PathBuf>,
) -> u8 {
    let ir = match checked_ir(app) {
        Ok(ir) => ir,
        Err(code) => return code,
    };
    let options = sitlog_compiler::diagram::Options {
        dm,
        main,
        title: sitlog_compiler::build::app_name(app),
    };
    let diagram = match sitlog_compiler::diagram::diagram(&ir, &options) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: {e}");
            return 2;
        }
    };
    let overlay = match &trace {
        None => None,
        Some(path) => {
            let text = match std::fs::read_to_string(path) {
                Ok(t) => t,
                Err(e) => {
                    eprintln!("error: cannot read trace {}: {e}", path.display());
                    return 2;
                }
            };
            match sitlog_graph::trace::read(&diagram, &text) {
                Ok(o) => {
                    if o.unmatched > 0 {
                        eprintln!(
                            "note: {} of {} transitions of {} are not in this diagram",
                            o.unmatched,
                            o.transitions,
                            path.display()
                        );
                    }
                    Some(o)
                }
                Err(e) => {
                    eprintln!("error: {}: {e}", path.display());
                    return 2;
                }
            }
        }
    };
    let text = match format {
        GraphFormat::Dot => sitlog_graph::dot::render(&diagram),
        GraphFormat::Json => diagram.to_json(),
        GraphFormat::Svg => {
            let layout = sitlog_graph::layout::layout(&diagram);
            for n in &layout.notes {
                eprintln!("note: {n}");
            }
            sitlog_graph::svg::render(&diagram, &layout, overlay.as_ref())
        }
    };
    if trace.is_some() && format != GraphFormat::Svg {
        eprintln!("note: --trace colours the SVG only");
    }
    match output {
        Some(path) => match std::fs::write(&path, text) {
            Ok(()) => 0,
            Err(e) => {
                eprintln!("error: cannot write {}: {e}", path.display());
                2
            }
        },
        None => {
            let mut out = std::io::stdout().lock();
            match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
                Ok(()) => 0,
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => 0,
                Err(e) => {
                    eprintln!("error: cannot write the diagram: {e}");
                    2
                }
            }
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
    allow_unresolved: bool,
    debugger: bool,
) -> u8 {
    use sitlog_compiler::{build, package};
    let options = sitlog_compiler::check::CheckOptions {
        unresolved_as_warnings: allow_unresolved,
        ..Default::default()
    };
    if let Err(code) = checked_ir_opts(app, options) {
        return code;
    }
    let compiled =
        match build::generate_checked(app, &app.display().to_string(), Default::default(), options)
        {
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
            None => write_stdout(&text, "the generated code"),
        };
    }
    let output = match output_file(app, output) {
        Ok(o) => o,
        Err(message) => {
            eprintln!("error: {message}");
            return 2;
        }
    };
    let layout = match package::Layout::user() {
        Ok(l) => l,
        Err(e) => {
            eprintln!("error: {e}");
            return 2;
        }
    };
    let built =
        package::write_package(&compiled, app, &layout, debugger).and_then(|(dir, name)| {
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

/// Where `build` writes the executable: `-o FILE`, else a file named after
/// the application (its directory's real name, or the DM file's stem) in
/// the current directory. A directory there (the application itself when
/// building from beside it) is refused before anything is built, as
/// `go build` does, rather than writing somewhere the user did not ask.
fn output_file(app: &std::path::Path, output: Option<PathBuf>) -> Result<PathBuf, String> {
    let given = output.is_some();
    let output = output.unwrap_or_else(|| PathBuf::from(sitlog_robot::app_name(app)));
    if output.is_dir() {
        let o = output.display();
        return Err(if given {
            format!("cannot write the executable to `{o}`: it is a directory; give a file name with -o FILE")
        } else {
            format!(
                "the default output `{o}` is a directory (the application itself, when you build from beside it); \
                 name the executable with -o FILE, e.g. `sitlogc build {} -o {o}-task`",
                app.display()
            )
        });
    }
    Ok(output)
}

/// `legacy`: `Some(--sitlog-home)` under `--legacy`.
fn run_app(
    app: &std::path::Path,
    args: &sitlog_robot::cli::RunArgs,
    allow_unresolved: bool,
    legacy: Option<Option<&std::path::Path>>,
    native_kb: bool,
    debug: Option<Option<&std::path::Path>>,
    watch: bool,
) -> u8 {
    // The legacy profile: the original's Prolog layer from SITLOG_HOME.
    #[cfg(feature = "prolog")]
    let mut before: Vec<sitlog_runtime::prolog::PrologSource> = Vec::new();
    if let Some(explicit) = legacy {
        use sitlog_compiler::legacy;
        let files = legacy::find_home(app, explicit)
            .and_then(|home| legacy::init_consults(&home).map(|f| (home, f)));
        let (home, files) = match files {
            Ok(x) => x,
            Err(e) => {
                eprintln!("error: {e}");
                return 2;
            }
        };
        #[cfg(feature = "prolog")]
        {
            use sitlog_runtime::prolog::PrologSource;
            // getenv('SITLOG_HOME', H) as the original's launchers set it
            // (with a trailing `/`).
            let value = std::env::var("SITLOG_HOME")
                .ok()
                .filter(|v| !v.is_empty())
                .unwrap_or_else(|| format!("{}/", home.display()));
            let mut fact = String::from("'$sitlog_env'('SITLOG_HOME', ");
            sitlog_syntax::write::write_atom(&mut fact, sitlog_syntax::Atom::intern(&value), true);
            fact.push_str(").\n");
            before.push(PrologSource::new("<legacy environment>", fact));
            for f in &files {
                match PrologSource::from_path(f) {
                    Ok(s) => before.push(s),
                    Err(e) => {
                        eprintln!("error: --legacy: cannot read {}: {e}", f.display());
                        return 2;
                    }
                }
            }
        }
        #[cfg(not(feature = "prolog"))]
        {
            let _ = (home, files);
            eprintln!("error: --legacy needs the Prolog engine (feature `prolog`)");
            return 2;
        }
    }
    let check_options = sitlog_compiler::check::CheckOptions {
        unresolved_as_warnings: allow_unresolved || legacy.is_some(),
        legacy: legacy.is_some(),
        ..Default::default()
    };
    let ir = match checked_ir_opts(app, check_options) {
        Ok(ir) => ir,
        Err(code) => return code,
    };
    let mut assets = match sitlog_robot::Assets::from_app(app) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("{e}");
            return e.status;
        }
    };
    #[allow(unused_mut)]
    let mut functions = sitlog_runtime::Functions::standard();
    // The application's user_functions.pl and templates.pl (feature `prolog`).
    #[cfg(feature = "prolog")]
    if let Err(errors) = sitlog_compiler::run::install_prolog_with(
        &ir,
        &mut functions,
        Default::default(),
        before,
        native_kb.then(sitlog_compiler::legacy::native_kb),
    ) {
        for e in errors {
            eprintln!("error: {e}");
        }
        return 1;
    }
    if args.view {
        // the live view draws the program as `sitlogc graph` does
        let options = sitlog_compiler::diagram::Options {
            dm: None,
            main: Some(args.main.split('(').next().unwrap_or("").trim().to_owned()),
            title: sitlog_compiler::build::app_name(app),
        };
        match sitlog_compiler::diagram::diagram(&ir, &options) {
            Ok(d) => assets.diagram = Some(d.to_json()),
            Err(e) => {
                eprintln!("error: {e}");
                return 2;
            }
        }
    }
    if watch {
        return run_watched(app, ir, functions, args, &assets, check_options);
    }
    match debug {
        // Situations run from their plans where they can (resolved once, here).
        None => {
            let resolved = sitlog_compiler::resolve::Resolved::new(&ir);
            sitlog_robot::Runner::process().run(&resolved, functions, args, &assets)
        }
        Some(commands) => {
            let source = match commands {
                Some(path) => sitlog_debug::CommandSource::file(path),
                None => sitlog_debug::CommandSource::editor(),
            };
            let source = match source {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("{e}");
                    return 2;
                }
            };
            // Plans, back to the machine's loop after each situation, so the
            // debugger sees every one.
            let resolved = sitlog_compiler::resolve::Resolved::new(&ir).one_situation_per_step();
            sitlog_debug::debug(
                &resolved,
                functions,
                args,
                &assets,
                sitlog_robot::Streams::process(),
                source,
                Box::new(std::io::stdout()),
                Box::new(std::io::stderr()),
            )
        }
    }
}

/// `sitlogc replay`.
fn replay(
    trace: &std::path::Path,
    diff: Option<&std::path::Path>,
    commands: Option<&std::path::Path>,
) -> u8 {
    let read = |path| match sitlog_debug::Trace::read(path) {
        Ok(t) => Ok(t),
        Err(e) => {
            eprintln!("{e}");
            Err(2)
        }
    };
    let trace = match read(trace) {
        Ok(t) => t,
        Err(code) => return code,
    };
    if let Some(other) = diff {
        let other = match read(other) {
            Ok(t) => t,
            Err(code) => return code,
        };
        return match sitlog_debug::diff(&trace, &other) {
            None => {
                println!(
                    "the recordings are the same ({} transitions)",
                    trace.records.len()
                );
                0
            }
            Some(text) => {
                print!("{text}");
                1
            }
        };
    }
    let source = match commands {
        Some(path) => sitlog_debug::CommandSource::file(path),
        None => sitlog_debug::CommandSource::editor(),
    };
    match source {
        Ok(source) => sitlog_debug::replay(
            &trace,
            source,
            &mut std::io::stdout(),
            &mut std::io::stderr(),
        ),
        Err(e) => {
            eprintln!("{e}");
            2
        }
    }
}

/// `sitlogc run --watch`: the run over a program that reloads itself.
fn run_watched(
    app: &std::path::Path,
    ir: sitlog_compiler::ir::Ir,
    functions: sitlog_runtime::Functions,
    args: &sitlog_robot::cli::RunArgs,
    assets: &sitlog_robot::Assets,
    options: sitlog_compiler::check::CheckOptions,
) -> u8 {
    use sitlog_compiler::watch::{ReloadAware, Watched};
    let files: Vec<PathBuf> = match sitlog_compiler::load::load(app) {
        Ok((program, _)) => program
            .sources
            .files()
            .map(|(_, f)| f.path.clone())
            .collect(),
        Err(e) => {
            eprintln!("error: cannot read {e}");
            return 2;
        }
    };
    let color = std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none();
    let messages: sitlog_compiler::watch::Messages =
        std::sync::Arc::new(std::sync::Mutex::new(Box::new(std::io::stderr())));
    let watched = Watched::new(ir, messages);
    if let Err(e) = watched.watch(app, &files, options, color) {
        eprintln!("error: --watch: {e}");
        return 2;
    }
    eprintln!(
        "watch: watching {} ({} file(s)); edits take effect between transitions",
        app.display(),
        files.len()
    );
    let ready = watched.ready_flag();
    let wrap: sitlog_robot::PerceptionWrap =
        Box::new(move |inner| Box::new(ReloadAware::new(inner, ready)));
    sitlog_robot::Runner::process()
        .wrap_perception(wrap)
        .run(&watched, functions, args, assets)
}

fn check(paths: &[PathBuf], format: Format, deny_warnings: bool, quiet: bool, legacy: bool) -> u8 {
    let color = color_stderr();
    let mut errors = 0usize;
    let mut warnings = 0usize;
    let mut io_failed = false;
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let mut programs = Vec::new();
    for path in paths {
        match sitlog_compiler::load::discover(path) {
            // Nothing to check is a usage error (exit 2, like a missing
            // path): a check that passes on nothing would hide a wrong path.
            Ok(found) if found.is_empty() => {
                eprintln!(
                    "error: no application or DM file found in {} (an application is a directory with a `models` file or `*.dm` files)",
                    path.display()
                );
                io_failed = true;
            }
            Ok(found) => programs.extend(found),
            Err(e) => {
                eprintln!("error: cannot read {e}");
                io_failed = true;
            }
        }
    }
    for path in &programs {
        let options = sitlog_compiler::check::CheckOptions {
            legacy,
            ..Default::default()
        };
        let (result, diags) = match sitlog_compiler::check_path_opts(path, options) {
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
                    if let Err(e) = writeln!(out, "{}", diag::render_json(d, &program.sources)) {
                        if e.kind() != std::io::ErrorKind::BrokenPipe && !io_failed {
                            eprintln!("error: cannot write the diagnostics to stdout: {e}");
                        }
                        io_failed |= e.kind() != std::io::ErrorKind::BrokenPipe;
                    }
                }
            }
        }
    }
    if let Err(e) = out.flush() {
        if e.kind() != std::io::ErrorKind::BrokenPipe {
            eprintln!("error: cannot write the diagnostics to stdout: {e}");
            io_failed = true;
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
