//! The `main` of a task compiled with `sitlogc build --debugger`: the
//! task's usual options ([`TaskCli`], those of
//! `sitlogc run`) plus `--commands FILE`, and the run under the debugger
//! exactly as `sitlogc debug APP` runs it.

use crate::command::CommandSource;
use sitlog_robot::cli::{parse_task_args, task_command, TaskCli};
use sitlog_robot::{on_big_stack, Assets, Streams};
use sitlog_runtime::app::App;
use sitlog_runtime::Functions;
use std::path::PathBuf;

/// The command line of a task compiled with `--debugger`.
#[derive(clap::Parser, Debug)]
struct DebugTaskCli {
    #[command(flatten)]
    task: TaskCli,
    /// Read the debugger's commands from FILE (each echoed after the
    /// prompt) instead of the terminal; when it ends, the run goes on
    /// without stopping.
    #[arg(long, value_name = "FILE")]
    commands: Option<PathBuf>,
}

/// What the compiled task's help adds to the usual description.
const ABOUT: &str = "\n\nBuilt with `sitlogc build --debugger`: the task runs under the step \
debugger, as `sitlogc debug APP` runs it (a REPL over the live run: `break`, `step`, `next`, \
`finish`, `continue`, `stack`, `pipe`, `vars`, `history`, `print TERM`, `world`, `input TERM`, \
`quit`; `help` lists them). The commands come from the terminal, or from --commands FILE. Exit \
status: the run's, 0 after `quit`, 2 for a bad line in the --commands file.";

/// The `main` of a task compiled with `sitlogc build --debugger`: parses
/// `std::env::args` (the options of a compiled task and `--commands
/// FILE`), runs the task under the debugger ([`crate::debug`]: commands
/// from the line editor, or from FILE) on a thread with a big stack, and
/// returns the exit status.
pub fn task_main<A: App>(app: &A, functions: Functions, assets: &Assets) -> std::process::ExitCode {
    let cli = match parse_task_args::<DebugTaskCli>(task_command::<DebugTaskCli>(assets, ABOUT)) {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    sitlog_syntax::decode::set_max_file_bytes(cli.task.max_file_bytes);
    on_big_stack(|| {
        let source = match &cli.commands {
            Some(path) => CommandSource::file(path),
            None => CommandSource::editor(),
        };
        let source = match source {
            Ok(s) => s,
            Err(e) => {
                sitlog_runtime::errln!("{e}");
                return 2;
            }
        };
        let run = cli.task.run_args();
        crate::debug(
            app,
            functions,
            &run,
            assets,
            Streams::process(),
            source,
            Box::new(std::io::stdout()),
            Box::new(std::io::stderr()),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[test]
    fn the_task_options_and_commands_parse() {
        let cli = DebugTaskCli::try_parse_from([
            "t",
            "--commands",
            "c.txt",
            "--script",
            "s.txt",
            "--allow-unresolved",
        ])
        .unwrap();
        assert_eq!(cli.commands, Some(PathBuf::from("c.txt")));
        assert_eq!(cli.task.run.script, Some(PathBuf::from("s.txt")));
        assert!(DebugTaskCli::try_parse_from(["t", "--commands"]).is_err());
        assert!(DebugTaskCli::try_parse_from(["t", "app"]).is_err());
    }
}
