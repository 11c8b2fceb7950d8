//! The command line of `sitlogc` as clap reads it: the subcommands, their
//! options and help texts. Parsing only; [`crate::commands`] does the work.
//! The help and the manual page are generated from these definitions.

use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

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
pub struct Cli {
    /// When diagnostics are coloured: `auto` when stderr is a terminal and
    /// NO_COLOR is unset or empty; `always`; `never`.
    #[arg(long, global = true, value_enum, value_name = "WHEN", default_value_t = ColorWhen::Auto)]
    pub color: ColorWhen,
    /// Largest file read (a DM, side file, KB, world, script or trace, in
    /// bytes): a larger one is an error naming the file and this option.
    #[arg(long, global = true, value_name = "BYTES", default_value_t = sitlog_syntax::decode::DEFAULT_MAX_FILE_BYTES)]
    pub max_file_bytes: u64,
    #[command(subcommand)]
    pub command: Command,
}

/// Where `sitlogc sim`'s user's words come from.
#[derive(Clone, Copy, ValueEnum, PartialEq, Eq, Debug)]
pub enum Speech {
    Simulated,
    External,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq, Debug)]
pub enum ColorWhen {
    Auto,
    Always,
    Never,
}

#[derive(Subcommand)]
pub enum Command {
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
        /// Treat warnings as errors (exit status 1), as `rustc -D warnings`
        /// does; an application sets it for itself with `deny-warnings =
        /// true` in a `sitlog.toml` beside its DMs.
        #[arg(long)]
        deny_warnings: bool,
        /// Do not print warnings.
        #[arg(long, short)]
        quiet: bool,
        /// The original's rules, as `run --legacy` applies them: a DM
        /// defined twice identically is a warning (W0203), not an error.
        #[arg(long)]
        legacy: bool,
        /// Also say, on stderr, where each file named by a library name
        /// (`'behaviors/say.dm'` in `models`) was read from: the
        /// application's own copy, a directory of $SITLOG_LIBRARY, or the
        /// library built into sitlogc.
        #[arg(long)]
        origins: bool,
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
    /// (the history so far is still printed) or an error in the
    /// application's files (its DMs, world.toml, knowledge.kb, sitlog.toml:
    /// located, as `sitlogc check` reports them), 2 on usage or I/O
    /// problems (a file that cannot be read),
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
        /// Refuse to run a program with warnings, printing them (exit
        /// status 1), as `sitlogc check --deny-warnings` does, and make an
        /// in_arg that does not match the incoming pipe a run-time error
        /// (without it the run skips that in_arg, as the original SitLog
        /// does, with a warning on stderr); also set by `deny-warnings =
        /// true` in the application's `sitlog.toml`.
        #[arg(long)]
        deny_warnings: bool,
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
    /// Serve an application's simulated world as a robot over ROS 2.
    ///
    /// `sitlogc sim APP --ros2` runs the simulator of `sitlogc run` (the
    /// application's `world.toml`, or --world FILE) as a ROS 2 node on the
    /// interface of the guide's table (names from the application's
    /// `ros2.toml`), on the DDS domain ROS_DOMAIN_ID: a task in another
    /// process (`sitlogc run APP --robot ros2`, or a compiled task) runs on
    /// it. It prints the world's transcript and serves until it is stopped,
    /// run after run: each task run starts a new episode on a fresh world
    /// (the world file's, same seed). When the world's user has nothing more
    /// to say, the task is told (its run stops with that error, as
    /// in-process) and the node waits for the next run. Exit status: 0 when
    /// stopped by SIGINT or SIGTERM, 2 on usage, I/O or world file
    /// problems, or when ROS 2 cannot start.
    #[cfg(feature = "ros2")]
    Sim {
        /// The application directory (or a single DM file).
        #[arg(value_name = "APP")]
        app: PathBuf,
        /// Serve on ROS 2 (the only way `sitlogc sim` serves for now).
        #[arg(long, required = true)]
        ros2: bool,
        /// `simulated`: the user's words are the world file's `user.says`;
        /// `external`: they are what another node publishes on the heard
        /// topic while the task listens (a person with `ros2 topic pub`, a
        /// speech recogniser); the user's moves still follow the world file,
        /// counted on the utterances heard.
        #[arg(long, value_enum, default_value_t = Speech::Simulated)]
        speech: Speech,
        /// The world to serve (default: the application's `world.toml`).
        #[arg(long, value_name = "FILE")]
        world: Option<PathBuf>,
        /// The seed of the simulated world (default: the world file's `seed`, else 0).
        #[arg(long, value_name = "N")]
        seed: Option<u64>,
        /// No narration lines (the conversation stays).
        #[arg(long, short)]
        quiet: bool,
    },
    /// Play the user of a robot over ROS 2: read what it says, type what you say.
    ///
    /// `sitlogc user --ros2` is a ROS 2 node on the DDS domain
    /// ROS_DOMAIN_ID that prints what the robot says (the say topic) and,
    /// each time the robot listens (the listening topic), reads a line at a
    /// prompt (line editing, history) and sends it on the heard topic, as a
    /// speech recogniser would: with `sitlogc sim APP --ros2 --speech
    /// external`, or on a real robot whose recogniser is not running. When
    /// stdin is not a terminal, its lines are said in turn, one each time the
    /// robot listens (a line read before is held until it does), and the
    /// node ends a moment after the task has heard the last (or once no task
    /// runs). The node reads with best effort: a task never waits for it,
    /// and closing it does not stop a run. Exit status: 0 at the end of the
    /// input (Ctrl-D at the prompt), 130 / 143 on Ctrl-C, SIGINT or SIGTERM,
    /// 2 on usage or I/O problems, or when ROS 2 cannot start.
    #[cfg(feature = "ros2")]
    User {
        /// The application whose `ros2.toml` (topic names) and world file
        /// (the robot's and the user's names) to use (default: the
        /// interface's defaults).
        #[arg(value_name = "APP")]
        app: Option<PathBuf>,
        /// Over ROS 2 (the only way `sitlogc user` connects for now).
        #[arg(long, required = true)]
        ros2: bool,
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
        /// Whole-program optimisation (fat LTO, one codegen unit): the
        /// fastest code, but every build takes minutes (the default release
        /// build rebuilds only the task's own crate).
        #[arg(long, conflicts_with_all = ["debug", "release"])]
        lto: bool,
        /// `rust`: only write the generated code.
        #[arg(long, value_enum)]
        emit: Option<Emit>,
        /// Print which situations run as generated code (on native values
        /// or on terms) and which variables are typed, each with the reason
        /// when not, with the types inferred on the MIR's registers (not
        /// yet used by the generated code), and stop.
        #[arg(long)]
        explain_types: bool,
        /// Compile even if next situations, embedded DMs, exit arcs or
        /// SitLog variables do not resolve (E0212, E0216–E0219), as `run
        /// --allow-unresolved` runs them: taking such a path stops the task
        /// with a run-time error.
        #[arg(long)]
        allow_unresolved: bool,
        /// Refuse to compile a program with warnings (exit status 1); also
        /// set by `deny-warnings = true` in the application's `sitlog.toml`.
        /// The compiled task reads neither: its own `--deny-warnings` makes
        /// an in_arg that does not match the pipe a run-time error.
        #[arg(long)]
        deny_warnings: bool,
        /// Link the step debugger: the executable runs the task under the
        /// debugger, as `sitlogc debug APP` runs the sources (commands from
        /// the terminal, or from its --commands FILE). Opt-in: a normal
        /// compiled task stays smaller.
        #[arg(long, conflicts_with = "emit")]
        debugger: bool,
        /// Link the robot over ROS 2 (sitlog-ros): the executable also runs
        /// with `--robot ros2`. On when the application has a `ros2.toml`;
        /// opt-in otherwise (it adds build time and size, see the guide's
        /// "A robot over ROS 2"). Not with --debugger.
        #[arg(long, conflicts_with = "debugger")]
        ros2: bool,
        /// Compile an application written for the original interpreter, in
        /// the original's tree, as `run --legacy` runs it: the original's
        /// rules for its DMs (implies --allow-unresolved). The task loads,
        /// when it starts, the Prolog files the tree's src/init.pl consults
        /// (from its --sitlog-home DIR, else $SITLOG_HOME, else the nearest
        /// directory above the current one that has src/init.pl; not the
        /// tree it was built from) and takes `run --legacy`'s options
        /// (--sitlog-home, --legacy-kb). Not with --debugger or --ros2.
        #[arg(long, conflicts_with_all = ["debugger", "ros2", "explain_types"])]
        legacy: bool,
        /// The original's tree for --legacy at build time, where the
        /// application is placed (default: $SITLOG_HOME, else the nearest
        /// directory above APP that has src/init.pl).
        #[arg(long, value_name = "DIR", requires = "legacy")]
        sitlog_home: Option<PathBuf>,
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
    /// `file:line:col` where it is written. A program too large to read in
    /// one SVG (over 4000 px on a side) is drawn as its overview, one box
    /// per DM (`--all`: everything in one picture; `--out-dir`: the overview
    /// and a page per DM). An application with errors gives its
    /// diagnostics, not a picture (exit status 1).
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
        /// Draw the arc coverage of `sitlogc test APP --coverage-file FILE`
        /// (or of any trace): arcs never taken red and dashed, situations
        /// never visited with a red outline, the others coloured as with
        /// --trace.
        #[arg(long, value_name = "FILE", conflicts_with = "trace")]
        coverage: Option<PathBuf>,
        /// Draw the program's overview: one box per DM, an arrow to each DM
        /// it calls and to the recovery DM of each situation type it has one
        /// for.
        #[arg(long, conflicts_with_all = ["dm", "out_dir", "all"])]
        overview: bool,
        /// Write the overview and one page per DM into DIR: `index.svg`,
        /// `index.html` and `NAME.svg` for each DM (a box of the overview and
        /// a called DM on a page link to the DM's page).
        #[arg(long, value_name = "DIR", conflicts_with_all = ["dm", "output", "all"])]
        out_dir: Option<PathBuf>,
        /// Every DM in one SVG, however large (without it, a program too
        /// large to read in one picture is drawn as its overview).
        #[arg(long, conflicts_with = "dm")]
        all: bool,
    },
    /// Run an application's tests: each `tests/*.toml` of APP.
    ///
    /// A test file gives the world the task runs on (the application's
    /// `world.toml` with changes: objects missing or moved, the user's
    /// lines, faults, the seed; or another file), or test-mode inputs
    /// (`script`), and what must hold afterwards (`[expect]`: the status,
    /// the main DM's final situation, the out_arg, lines that must appear
    /// in order and lines that must not, KB answers, a bound on
    /// transitions, a golden output). The tests run in parallel; one line
    /// per test and a summary are printed in the order of their file names;
    /// a failure shows why, with the output marked or a diff. See the
    /// guide's "Testing an application". Exit status: 0 when every test
    /// passed, 1 when one failed or the application has errors (its
    /// diagnostics are printed, as by `check`), 2 on usage or I/O problems
    /// or a bad test file (at its file:line:col).
    Test {
        /// The application directory.
        #[arg(value_name = "APP")]
        app: PathBuf,
        /// Run only the tests whose name contains FILTER.
        #[arg(value_name = "FILTER")]
        filter: Option<String>,
        /// With FILTER: only the test named exactly FILTER.
        #[arg(long, requires = "filter")]
        exact: bool,
        /// Tests run at once (default: the number of CPUs).
        #[arg(long, short, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
        jobs: Option<u16>,
        /// `human`: cargo's lines; `json`: one JSON object per test and a
        /// summary, one per line.
        #[arg(long, value_enum, default_value_t = Format::Human)]
        format: Format,
        /// Also write the results as JUnit XML to FILE (for CI).
        #[arg(long, value_name = "FILE")]
        junit: Option<PathBuf>,
        /// Print the arc coverage after the summary: for each DM (the
        /// application's and the library's), the situations visited and
        /// the arcs taken by the tests, then every arc never taken.
        #[arg(long)]
        coverage: bool,
        /// Write the coverage table to FILE instead of stdout (implies
        /// --coverage).
        #[arg(long, value_name = "FILE")]
        coverage_table: Option<PathBuf>,
        /// Write every transition of the tests' runs to FILE (JSON lines,
        /// as `run --trace` writes them), for `sitlogc graph APP --coverage FILE`.
        #[arg(long, value_name = "FILE")]
        coverage_file: Option<PathBuf>,
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
    Lsp {
        /// Largest message read from the editor (bytes, its `Content-Length`);
        /// a longer one ends the session with an error (exit 2).
        #[arg(long, value_name = "BYTES", default_value_t = sitlog_lsp::transport::DEFAULT_MAX_MESSAGE_BYTES)]
        max_message_bytes: u64,
    },
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
    /// (`expected.txt`) and a README. With --robot, a task on the simulated
    /// robot instead: a world file (a small map, shelves, objects, a user),
    /// a KB, and DMs that fetch the object the user asks for with the
    /// behaviour library built into sitlogc, its recovery protocols at
    /// work; with the golden output of a run. Exit status: 0 when made, 2
    /// when NAME exists or cannot be written (nothing is changed then).
    New {
        /// The application directory to make; its last component names the application.
        #[arg(value_name = "NAME")]
        name: PathBuf,
        /// Make a task on the simulated robot (world, map, KB, the behaviour
        /// library) instead of a test-mode speech task.
        #[arg(long)]
        robot: bool,
    },
    /// List the behaviour library, or print one of its files.
    ///
    /// An application names the library's files without a path
    /// (`'behaviors/take.dm'.` in `models`, `:- consult('behaviors/language.pl').`):
    /// they are read from the application's own copy if it has one, else
    /// from the directories of $SITLOG_LIBRARY, else from the library built
    /// into sitlogc. Without NAME, every file of the built-in library and
    /// where it is read from; with NAME, the file's text on stdout (to make
    /// a copy of your own: `sitlogc library behaviors/take.dm >
    /// myapp/behaviors/take.dm`). Exit status: 0, or 2 when NAME is not in
    /// the library.
    Library {
        /// A library file (`behaviors/take.dm`).
        #[arg(value_name = "NAME")]
        name: Option<String>,
    },
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum LegacyKb {
    Prolog,
    Native,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum Emit {
    Rust,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum GraphFormat {
    Svg,
    Dot,
    Json,
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum Format {
    Human,
    Json,
}
