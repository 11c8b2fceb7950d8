//! The `main` of a compiled task ([`main`]): its command line
//! ([`crate::cli`]) parsed, the task run by [`Runner::process`] on a
//! thread with a big stack ([`on_big_stack`], as `sitlogc` runs).

use crate::assets::Assets;
use crate::cli::{parse_task_args, task_command, TaskCli};
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
    let args = match parse_task_args::<TaskCli>(task_command::<TaskCli>(assets, "")) {
        Ok(cli) => {
            sitlog_syntax::decode::set_max_file_bytes(cli.max_file_bytes);
            cli.run
        }
        Err(code) => return code,
    };
    on_big_stack(|| Runner::process().run(app, functions, &args, assets))
}
