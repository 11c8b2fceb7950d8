//! The command line of a task run: the options of `sitlogc run`
//! ([`RunArgs`], which `sitlogc run` and `sitlogc debug` flatten after the
//! application) and the command line of a compiled task ([`TaskCli`],
//! [`task_command`], [`parse_task_args`]). The option set and the output
//! contract are the notes' "Our convention for `sitlogc run` output", plus
//! the robot's options: `--world`, `--no-world`, `--seed`, `--robot`, `--kb`,
//! `--kb-persist`, `--quiet`, and the trust model's `--allow-os` and
//! `--sandbox`. What a run does with them is
//! [`crate::Runner`]'s.

use crate::assets::Assets;
use clap::{Args, CommandFactory, FromArgMatches, Parser, ValueEnum};
use sitlog_runtime::functions::CallLimits;
use sitlog_runtime::testmode::InputLimits;
use sitlog_runtime::trust::Trust;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Output format of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// The papers' history listing, then `Out Arg:` and `Out Global Vars:`.
    Text,
    /// One JSON object on stdout.
    Json,
}

/// What a run's actions and perceptions reach.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum RobotKind {
    /// The simulated robot of the world file (test mode without one).
    #[default]
    Sim,
    /// A robot over ROS 2: the topics and actions of the guide's interface
    /// table (names in the application's `ros2.toml`), on the DDS domain
    /// `ROS_DOMAIN_ID`.
    Ros2,
}

/// `--sandbox`: whether the operating system confines the task
/// ([`crate::sandbox`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum SandboxMode {
    /// Confine where the kernel can; say once where it cannot.
    #[default]
    Auto,
    /// Confine, or refuse to run (exit 2) where the kernel cannot.
    Require,
    /// Only the Prolog-level refusals.
    Off,
}

/// Whether the task history is kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum HistoryMode {
    Keep,
    None,
}

/// The options of a run (after the application).
#[derive(Args, Clone, Debug, PartialEq, Eq)]
pub struct RunArgs {
    /// The DM to start, as a term (it may have arguments).
    #[arg(long, default_value = "main", value_name = "DM")]
    pub main: String,
    /// The initial pipe value, as a term (default: the atom `none`).
    #[arg(long, value_name = "TERM", allow_hyphen_values = true)]
    pub in_arg: Option<String>,
    /// Test mode: read the inputs from FILE (one term per line, ending with
    /// `.`) instead of a prompt on stdin. Not with a world.
    #[arg(long, value_name = "FILE")]
    pub script: Option<PathBuf>,
    /// `text`: the papers' history listing; `json`: one JSON object on stdout.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub format: Format,
    /// `none` keeps no history, so that a long task runs in bounded memory.
    #[arg(long, value_enum, default_value_t = HistoryMode::Keep)]
    pub history: HistoryMode,
    /// Write one JSON object per transition to FILE as it happens.
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// A knowledge base whose services become user functions
    /// (`apply(object_property_value(I, P), [pete, lives])`); default: the
    /// application's `knowledge.kb`, if it has one.
    #[arg(long, value_name = "FILE")]
    pub kb: Option<PathBuf>,
    /// Write every successful KB update back to the --kb file (atomically).
    #[arg(long)]
    pub kb_persist: bool,
    /// Run on the simulated world of FILE (default: the application's
    /// `world.toml`, if it has one).
    #[arg(long, value_name = "FILE", conflicts_with = "no_world")]
    pub world: Option<PathBuf>,
    /// Run in test mode even if the application has a world.
    #[arg(long)]
    pub no_world: bool,
    /// The seed of the simulated world (default: the world file's `seed`, else 0).
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// The robot: `sim`, the simulated one of the world file (test mode
    /// without one); `ros2`, a robot over ROS 2 (`sitlogc sim APP --ros2`, or
    /// a real one; see the guide's "Connecting a robot").
    #[arg(long, value_enum, default_value_t = RobotKind::Sim, value_name = "ROBOT")]
    pub robot: RobotKind,
    /// No progress indicator and no narration lines (the conversation stays).
    #[arg(long, short)]
    pub quiet: bool,
    /// Longest term from outside (one perception read from --script or typed,
    /// --in-arg, --main), in bytes.
    #[arg(long, value_name = "BYTES", default_value_t = InputLimits::MAX_BYTES)]
    pub max_input_bytes: usize,
    /// Deepest nesting of a term from outside, in levels.
    #[arg(long, value_name = "LEVELS", default_value_t = InputLimits::MAX_DEPTH)]
    pub max_input_depth: usize,
    /// Inferences one Prolog user function call may make.
    #[arg(long, value_name = "N", default_value_t = CallLimits::INFERENCES)]
    pub prolog_inferences: u64,
    /// Wall-clock time one Prolog user function call may take, in seconds
    /// (decimals allowed).
    #[arg(long, value_name = "SECONDS", default_value = "10", value_parser = parse_seconds)]
    pub prolog_time_limit: Duration,
    /// Memory the process may grow by during one Prolog user function call, in MiB.
    #[arg(long, value_name = "MIB", default_value_t = CallLimits::HEAP_BYTES >> 20)]
    pub prolog_heap_limit: u64,
    /// Let the application's Prolog code reach the operating system: run
    /// shell commands and processes, open sockets, write files outside the
    /// application, consult files outside the application. Without it
    /// these are refused with an error naming this option, and the
    /// operating system's sandbox holds the task (see --sandbox).
    #[arg(long)]
    pub allow_os: bool,
    /// The operating system's sandbox of the task (Linux: Landlock and
    /// seccomp), set once every file of the run is open: `auto` confines
    /// the task where the kernel can and says once where it cannot,
    /// `require` makes a kernel that cannot an error (exit 2), `off` leaves
    /// only the Prolog-level refusals. --allow-os lifts it.
    #[arg(long, value_enum, value_name = "MODE", default_value_t = SandboxMode::Auto)]
    pub sandbox: SandboxMode,
    /// Directories the application's code may also write into and consult
    /// from without `--allow-os` (not an option: `sitlogc run --legacy`
    /// gives the original's tree, whose apps consult one another's files).
    #[arg(skip)]
    pub trust_roots: Vec<PathBuf>,
    /// The original's evaluation of DM calls (not an option: set by
    /// `sitlogc run --legacy`): see `Options::close_list_tails`.
    #[arg(skip)]
    pub close_list_tails: bool,
    /// The original's in_arg, the default (not an option: `sitlogc run
    /// --deny-warnings`, the application's `sitlog.toml` or a compiled
    /// task's `--deny-warnings` clear it): see `Options::skip_unmatched_in_arg`.
    #[arg(skip = true)]
    pub skip_unmatched_in_arg: bool,
    /// What `screen(X)` with `X` unbound shows in test mode (not an
    /// option: `sitlogc run --legacy` gives the application's first
    /// `caption(Id, Text)`): see `TextActions::with_unbound_screen`.
    #[arg(skip)]
    pub unbound_screen: Option<(String, String)>,
    /// Follow the run in a web page: the program's diagram (as `sitlogc
    /// graph` draws it) with the current situation, the arcs taken, the DM
    /// stack and the last transitions. Served on 127.0.0.1 only; the task
    /// starts when the page is open, and the server stops when it ends.
    #[arg(long)]
    pub view: bool,
    /// The live view's port (default: a free one, printed on stderr).
    #[arg(long, value_name = "PORT", default_value_t = 0, requires = "view")]
    pub view_port: u16,
    /// Wait this many milliseconds after each transition, so that a fast
    /// task can be followed in the live view.
    #[arg(long, value_name = "MS", default_value_t = 0, requires = "view")]
    pub view_delay: u64,
}

/// Whether `a` and `b` name one file: the same file on disk when both
/// exist (through links, `..`, another spelling), else the same path once
/// the directory is resolved (a file `--trace` is about to create).
fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    if let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) {
        use std::os::unix::fs::MetadataExt;
        return ma.dev() == mb.dev() && ma.ino() == mb.ino();
    }
    let resolve = |p: &Path| -> PathBuf {
        if let Ok(real) = std::fs::canonicalize(p) {
            return real;
        }
        let dir = match p.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        match (std::fs::canonicalize(dir), p.file_name()) {
            (Ok(d), Some(name)) => d.join(name),
            _ => p.to_path_buf(),
        }
    };
    resolve(a) == resolve(b)
}

/// `--prolog-time-limit`: seconds, decimals allowed.
fn parse_seconds(text: &str) -> Result<Duration, String> {
    let s: f64 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a number of seconds"))?;
    Duration::try_from_secs_f64(s).map_err(|_| format!("`{text}` is not a duration in seconds"))
}

impl RunArgs {
    /// Two options naming the same file where one of them writes it
    /// (`--trace`, and `--kb` with `--kb-persist`) and the other reads or
    /// writes it too (`--script`, `--kb`, `--world`, `--trace`): `run
    /// --script s.txt --trace s.txt` would overwrite the script. The
    /// message names both options and the file.
    pub fn files_in_conflict(&self) -> Option<String> {
        let mut named: Vec<(&str, &Path, bool)> = Vec::new();
        if let Some(p) = &self.script {
            named.push(("--script", p, false));
        }
        if let Some(p) = &self.kb {
            named.push(("--kb", p, self.kb_persist));
        }
        if let Some(p) = &self.world {
            named.push(("--world", p, false));
        }
        if let Some(p) = &self.trace {
            named.push(("--trace", p, true));
        }
        for (i, &(a, pa, wa)) in named.iter().enumerate() {
            for &(b, pb, wb) in &named[i + 1..] {
                if (wa || wb) && same_file(pa, pb) {
                    let writer = if wb { b } else { a };
                    return Some(format!(
                        "{a} and {b} name the same file, {}: {writer} would overwrite it; give them different files",
                        pb.display()
                    ));
                }
            }
        }
        None
    }

    /// The limits on terms from outside.
    pub fn input_limits(&self) -> InputLimits {
        InputLimits {
            max_bytes: self.max_input_bytes,
            max_depth: self.max_input_depth,
        }
    }

    /// What the application's code may reach of the operating system
    /// (`--allow-os`; without it, writes stay inside the application: the
    /// KB's directory is no permission, issue 38). The runner adds the
    /// sandbox ([`Trust::confine`]).
    pub fn trust(&self) -> Trust {
        Trust {
            allow_os: self.allow_os,
            roots: self.trust_roots.clone(),
            confine: None,
        }
    }

    /// The limits of one Prolog user function call.
    pub fn call_limits(&self) -> CallLimits {
        CallLimits {
            inferences: self.prolog_inferences,
            time: self.prolog_time_limit,
            heap_bytes: self.prolog_heap_limit.saturating_mul(1 << 20),
        }
    }
}

/// The defaults of a program that embeds the runner (tests, benchmarks,
/// `sitlogc test`'s harness): as the command line's, except that the OS
/// sandbox is off (`SandboxMode::Off`): seccomp binds every thread of the
/// process, so an embedding program opts in for itself; the command line
/// (`sitlogc run`, `sitlogc debug`, a compiled task) defaults to `auto`.
impl Default for RunArgs {
    fn default() -> RunArgs {
        RunArgs {
            main: "main".to_owned(),
            in_arg: None,
            script: None,
            format: Format::Text,
            history: HistoryMode::Keep,
            trace: None,
            kb: None,
            kb_persist: false,
            world: None,
            no_world: false,
            seed: None,
            robot: RobotKind::Sim,
            quiet: false,
            max_input_bytes: InputLimits::MAX_BYTES,
            max_input_depth: InputLimits::MAX_DEPTH,
            prolog_inferences: CallLimits::INFERENCES,
            prolog_time_limit: CallLimits::TIME,
            prolog_heap_limit: CallLimits::HEAP_BYTES >> 20,
            allow_os: false,
            sandbox: SandboxMode::Off,
            trust_roots: Vec::new(),
            close_list_tails: false,
            skip_unmatched_in_arg: true,
            unbound_screen: None,
            view: false,
            view_port: 0,
            view_delay: 0,
        }
    }
}

/// The command line of a compiled task: the options of `sitlogc run`.
/// Public so that a task built with `sitlogc build --debugger`
/// (`sitlog_debug::task_main`) takes the same options, plus its own.
#[derive(Parser, Debug)]
pub struct TaskCli {
    #[command(flatten)]
    pub run: RunArgs,
    /// Accepted so that a `sitlogc run` command line works unchanged; it
    /// changes nothing here: unresolved names were allowed or refused when
    /// the task was compiled (`sitlogc build --allow-unresolved`).
    #[arg(long)]
    pub allow_unresolved: bool,
    /// Make the run's warnings errors: an in_arg that does not match the
    /// incoming pipe stops the task with a located error instead of being
    /// skipped (as the original skips it) with a warning on stderr.
    #[arg(long)]
    pub deny_warnings: bool,
    /// Largest file read (a KB, world, script or trace, in bytes): a larger
    /// one is an error naming the file and this option.
    #[arg(long, value_name = "BYTES", default_value_t = sitlog_syntax::decode::DEFAULT_MAX_FILE_BYTES)]
    pub max_file_bytes: u64,
}

impl TaskCli {
    /// The run's options: its `--deny-warnings` makes an in_arg that does
    /// not match the incoming pipe an error (E14) instead of skipped, as
    /// the original skips it, with a warning.
    pub fn run_args(&self) -> RunArgs {
        let mut run = self.run.clone();
        run.skip_unmatched_in_arg &= !self.deny_warnings;
        run
    }
}

/// `--legacy-kb`: how a task of the original's tree (`--legacy`) serves the
/// original's KB layer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum LegacyKb {
    /// The original's KB layer runs as it is (the KB a Prolog term).
    #[default]
    Prolog,
    /// Its services, updates, loads and saves are served by sitlog-kb (the
    /// KB a handle).
    Native,
}

/// The command line of a task compiled with `sitlogc build --legacy` (an
/// application of the original's tree): the options of `sitlogc run
/// --legacy`, so that its command line works unchanged.
#[derive(Parser, Debug)]
pub struct LegacyTaskCli {
    #[command(flatten)]
    pub task: TaskCli,
    /// Accepted so that a `sitlogc run --legacy` command line works
    /// unchanged: this task always runs under the original's rules.
    #[arg(long)]
    pub legacy: bool,
    /// The original's tree, whose `src/init.pl` names the Prolog layer
    /// loaded at start and whose files the application reads and writes
    /// (default: $SITLOG_HOME, else the nearest directory above the current
    /// one that has src/init.pl). Read when the task starts, not when it
    /// was built.
    #[arg(long, value_name = "DIR")]
    pub sitlog_home: Option<PathBuf>,
    /// `prolog` runs the original's KB layer as it is; `native` serves its
    /// KB services, updates, loads and saves from our KB (sitlog-kb), the
    /// KB being a handle.
    #[arg(long, value_enum, value_name = "HOW", default_value_t = LegacyKb::Prolog)]
    pub legacy_kb: LegacyKb,
}

/// The clap command of a compiled task whose command line is `C` (e.g.
/// [`TaskCli`]), named after the application; `more` is appended to its
/// description.
pub fn task_command<C: CommandFactory>(assets: &Assets, more: &str) -> clap::Command {
    let name = if assets.app_name.is_empty() {
        "task".to_owned()
    } else {
        assets.app_name.clone()
    };
    let about = format!(
        "The SitLog task `{name}`, compiled. Runs it on its world when it has one, else in test mode.\n\
         A compiled task does not reload when its sources change: it runs the program it was \
         compiled from (no reloading); compile again with `sitlogc build`, or run the sources \
         with `sitlogc run APP --watch`.{more}"
    );
    C::command()
        .name(name.clone())
        .bin_name(name)
        .about(about)
        .version(env!("CARGO_PKG_VERSION"))
}

/// Parses `std::env::args` with `command` (see [`task_command`]); on
/// `--help`, `--version` or a usage error prints it and gives the exit
/// status (0, or 2).
pub fn parse_task_args<C: FromArgMatches>(
    command: clap::Command,
) -> Result<C, std::process::ExitCode> {
    parse_task_args_from(command, std::env::args_os())
}

/// [`parse_task_args`] of the command line `args` (the program's name
/// first), for a task run in process (tests).
pub fn parse_task_args_from<C: FromArgMatches>(
    command: clap::Command,
    args: impl IntoIterator<Item = std::ffi::OsString>,
) -> Result<C, std::process::ExitCode> {
    match command
        .try_get_matches_from(args)
        .and_then(|m| C::from_arg_matches(&m))
    {
        Ok(cli) => Ok(cli),
        Err(e) => {
            let _ = e.print();
            Err(match e.kind() {
                clap::error::ErrorKind::DisplayHelp | clap::error::ErrorKind::DisplayVersion => {
                    std::process::ExitCode::SUCCESS
                }
                _ => std::process::ExitCode::from(2),
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn deny_warnings_makes_a_skipped_in_arg_an_error() {
        let cli = TaskCli::try_parse_from(["t"]).unwrap();
        assert!(cli.run_args().skip_unmatched_in_arg);
        assert!(RunArgs::default().skip_unmatched_in_arg);
        let cli = TaskCli::try_parse_from(["t", "--deny-warnings"]).unwrap();
        assert!(!cli.run_args().skip_unmatched_in_arg);
    }

    #[test]
    fn a_run_command_line_works_unchanged() {
        let cli =
            TaskCli::try_parse_from(["t", "--allow-unresolved", "--kb", "k.kb", "--kb-persist"])
                .unwrap();
        assert!(cli.allow_unresolved);
        assert_eq!(cli.run.kb.as_deref(), Some(Path::new("k.kb")));
        assert!(cli.run.kb_persist);
    }

    #[test]
    fn a_run_legacy_command_line_works_unchanged_on_a_legacy_task() {
        let cli = LegacyTaskCli::try_parse_from([
            "t",
            "--legacy",
            "--sitlog-home",
            "/tree",
            "--legacy-kb",
            "native",
            "--script",
            "in.txt",
            "--allow-unresolved",
        ])
        .unwrap();
        assert!(cli.legacy);
        assert_eq!(cli.sitlog_home.as_deref(), Some(Path::new("/tree")));
        assert_eq!(cli.legacy_kb, LegacyKb::Native);
        assert_eq!(cli.task.run.script, Some(PathBuf::from("in.txt")));
        let cli = LegacyTaskCli::try_parse_from(["t"]).unwrap();
        assert_eq!(cli.legacy_kb, LegacyKb::Prolog);
        assert!(LegacyTaskCli::try_parse_from(["t", "--legacy-kb", "sql"]).is_err());
    }

    #[test]
    fn options_parse() {
        let cli = TaskCli::try_parse_from([
            "t",
            "--main",
            "m(1)",
            "--in-arg=-3",
            "--format",
            "json",
            "--history",
            "none",
            "--script",
            "s.txt",
        ])
        .unwrap();
        let a = cli.run;
        assert_eq!(a.main, "m(1)");
        assert_eq!(a.in_arg.as_deref(), Some("-3"));
        assert_eq!(a.format, Format::Json);
        assert_eq!(a.history, HistoryMode::None);
        assert_eq!(a.script, Some(PathBuf::from("s.txt")));
        assert!(TaskCli::try_parse_from(["t", "--format", "xml"]).is_err());
        assert!(TaskCli::try_parse_from(["t", "--main"]).is_err());
        assert!(TaskCli::try_parse_from(["t", "app"]).is_err());
        assert!(TaskCli::try_parse_from(["t", "--world", "w", "--no-world"]).is_err());
    }
}
