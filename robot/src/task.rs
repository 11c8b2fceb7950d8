//! The `main` of a compiled task ([`main`]): its command line
//! ([`crate::cli`]) parsed, the task run by [`Runner::process`] on a
//! thread with a big stack ([`on_big_stack`], as `sitlogc` runs).

use crate::assets::Assets;
use crate::cli::{
    parse_task_args, parse_task_args_from, task_command, LegacyTaskCli, RunArgs, TaskCli,
};
use crate::robot_hook::RobotHook;
use crate::runner::Runner;
use sitlog_runtime::app::App;
use sitlog_runtime::Functions;

/// Runs `f` on a thread with a big stack (as `sitlogc` does); its exit
/// status (101 when it panicked).
pub fn on_big_stack(f: impl FnOnce() -> u8 + Send) -> std::process::ExitCode {
    let code = std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(256 * 1024 * 1024)
            .spawn_scoped(s, f)
            .map(|h| h.join().unwrap_or(101))
            .unwrap_or(101)
    });
    std::process::ExitCode::from(code)
}

/// The `main` of a compiled task: parses `std::env::args` (clap, the
/// options of `sitlogc run`, named after the application), runs on a thread
/// with a big stack (as `sitlogc` does), returns the exit status.
pub fn main<A: App>(app: &A, functions: Functions, assets: &Assets) -> std::process::ExitCode {
    main_from(app, functions, assets, std::env::args_os())
}

/// [`main`] on the command line `args` (the program's name first) instead
/// of the process's: what a compiled task runs, callable in process (the
/// tests run a compiled program through it, the OS sandbox included).
pub fn main_from<A: App>(
    app: &A,
    functions: Functions,
    assets: &Assets,
    args: impl IntoIterator<Item = std::ffi::OsString>,
) -> std::process::ExitCode {
    let args = match parse_task_args_from::<TaskCli>(task_command::<TaskCli>(assets, ""), args) {
        Ok(cli) => {
            sitlog_syntax::decode::set_max_file_bytes(cli.max_file_bytes);
            cli.run_args()
        }
        Err(code) => return code,
    };
    on_big_stack(|| Runner::process().run(app, functions, &args, assets))
}

/// The `main` of a task compiled with `sitlogc build --legacy`: its
/// command line is [`LegacyTaskCli`] (`sitlogc run --legacy`'s options);
/// `setup` applies the legacy profile to the run's options and makes the
/// functions (the original's Prolog layer, read from its tree at start,
/// before the application's own), or says why not (exit status, the lines
/// for stderr and the message of the `--format json` report, as `sitlogc
/// run --legacy` gives them); in test mode
/// each situation type is given what the original's test mode gives it
/// ([`sitlog_runtime::testmode::OriginalTestMode`]), as under `sitlogc run
/// --legacy`.
pub fn main_legacy<A: App>(
    app: &A,
    assets: &Assets,
    setup: impl FnOnce(&LegacyTaskCli, &mut RunArgs) -> Result<Functions, (u8, Vec<String>, String)>,
) -> std::process::ExitCode {
    let about = "\nAn application of the original SitLog's tree (`sitlogc build --legacy`): \
                 at start it loads the Prolog files the tree's src/init.pl consults, from \
                 --sitlog-home DIR, else $SITLOG_HOME, else the nearest directory above the \
                 current one that has src/init.pl.";
    let cli = match parse_task_args::<LegacyTaskCli>(task_command::<LegacyTaskCli>(assets, about)) {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    sitlog_syntax::decode::set_max_file_bytes(cli.task.max_file_bytes);
    let mut args = cli.task.run.clone();
    let json = args.format == crate::cli::Format::Json;
    crate::interrupt::report_json_before_start(json);
    let functions = match setup(&cli, &mut args) {
        Ok(f) => {
            args.skip_unmatched_in_arg &= !cli.task.deny_warnings;
            f
        }
        Err((code, lines, message)) => {
            for line in &lines {
                sitlog_runtime::errln!("{line}");
            }
            return stopped(json, code, &message);
        }
    };
    on_big_stack(|| {
        let test_mode = args.no_world || (args.world.is_none() && assets.world.is_none());
        let mut runner = Runner::process();
        if test_mode {
            runner = runner.wrap_perception(Box::new(|inner| {
                Box::new(sitlog_runtime::testmode::OriginalTestMode::new(inner))
            }));
        }
        runner.run(app, functions, &args, assets)
    })
}

/// `code`, after the report of a run stopped before its task ran (with
/// `--format json`: status `error`, `message`) is written on stdout.
fn stopped(json: bool, code: u8, message: &str) -> std::process::ExitCode {
    if json {
        use std::io::Write as _;
        let mut out = std::io::stdout();
        let report = sitlog_runtime::report::stopped_json("error", message);
        if out
            .write_all(report.as_bytes())
            .and_then(|_| out.flush())
            .is_err()
        {
            return std::process::ExitCode::from(2);
        }
    }
    std::process::ExitCode::from(code)
}

/// The `main` of a compiled task whose functions could not be made
/// (`message`: its Prolog refused, e.g. a clause too deep for the engine):
/// the command line is parsed as [`main`] parses it (`--help` still
/// answers), the error goes to stderr and, with `--format json`, the
/// report (status `error`, the message) to stdout; exit status 1.
pub fn main_failed(assets: &Assets, message: &str) -> std::process::ExitCode {
    main_failed_from(assets, message, std::env::args_os())
}

/// [`main_failed`] on the command line `args` (the program's name first).
pub fn main_failed_from(
    assets: &Assets,
    message: &str,
    args: impl IntoIterator<Item = std::ffi::OsString>,
) -> std::process::ExitCode {
    let args = match parse_task_args_from::<TaskCli>(task_command::<TaskCli>(assets, ""), args) {
        Ok(cli) => cli.run,
        Err(code) => return code,
    };
    sitlog_runtime::errln!("error: {message}");
    stopped(args.format == crate::cli::Format::Json, 1, message)
}

/// [`main`] for a task that can also run on another robot (`--robot
/// ros2`): `robot` makes the hook ([`Runner::robot`]) when the run asks
/// for it.
pub fn main_with_robot<A: App>(
    app: &A,
    functions: Functions,
    assets: &Assets,
    robot: impl FnOnce() -> RobotHook + Send,
) -> std::process::ExitCode {
    let args = match parse_task_args::<TaskCli>(task_command::<TaskCli>(assets, "")) {
        Ok(cli) => {
            sitlog_syntax::decode::set_max_file_bytes(cli.max_file_bytes);
            cli.run_args()
        }
        Err(code) => return code,
    };
    on_big_stack(|| {
        Runner::process()
            .robot(robot())
            .run(app, functions, &args, assets)
    })
}
