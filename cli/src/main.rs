//! `sitlogc`: the SitLog command-line tool. Parses the arguments
//! ([`sitlog_cli::args`]), sets the colour of diagnostics, runs the chosen
//! command ([`sitlog_cli::commands`]) on a thread with a big stack and turns
//! its status into the exit code; the three commands of a few lines
//! (`completions`, `kb`, `lsp`) are dispatched here.

use clap::{CommandFactory, Parser};
use sitlog_cli::args::{Cli, Command, LegacyKb};
use sitlog_cli::commands::*;
use sitlog_cli::output::{write_stdout, COLOR};
use std::process::ExitCode;

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
            sitlog_runtime::errln!("sitlogc: internal error");
            ExitCode::from(101)
        }
    }
}

fn run(cli: Cli) -> u8 {
    let _ = COLOR.set(cli.color);
    sitlog_syntax::decode::set_max_file_bytes(cli.max_file_bytes);
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
            origins,
        } => check(&paths, format, deny_warnings, quiet, legacy, origins),
        Command::Run {
            app,
            run,
            allow_unresolved,
            deny_warnings,
            legacy,
            sitlog_home,
            legacy_kb,
            watch,
        } => {
            let legacy = legacy.then_some(sitlog_home);
            run_app(
                &app,
                &run,
                Strictness {
                    allow_unresolved,
                    deny_warnings,
                },
                legacy.as_ref().map(|h| h.as_deref()),
                legacy_kb == LegacyKb::Native,
                None,
                watch,
            )
        }
        #[cfg(feature = "ros2")]
        Command::Sim {
            app,
            ros2: _,
            speech,
            world,
            seed,
            quiet,
        } => sim(
            &app,
            world.as_deref(),
            seed,
            speech == sitlog_cli::args::Speech::External,
            quiet,
        ),
        #[cfg(feature = "ros2")]
        Command::User { app, ros2: _ } => user(app.as_deref()),
        Command::Debug { app, run, commands } => run_app(
            &app,
            &run,
            Strictness::default(),
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
            lto,
            emit,
            explain_types,
            allow_unresolved,
            deny_warnings,
            debugger,
            ros2,
            legacy,
            sitlog_home,
        } => {
            use sitlog_cli::package::Profile;
            let profile = match (debug, lto) {
                (true, _) => Profile::Debug,
                (false, true) => Profile::Lto,
                (false, false) => Profile::Release,
            };
            if explain_types {
                explain_types_of(&app)
            } else {
                build_app(
                    &app,
                    output,
                    profile,
                    emit,
                    Strictness {
                        allow_unresolved,
                        deny_warnings,
                    },
                    debugger,
                    ros2,
                    legacy.then_some(sitlog_home.as_deref()),
                )
            }
        }
        Command::Lsp { max_message_bytes } => {
            match sitlog_lsp::run_stdio(&sitlog_cli::analysis::Analysis, max_message_bytes) {
                Ok(()) => 0,
                Err(e) => {
                    sitlog_runtime::errln!("error: sitlogc lsp: {e}");
                    2
                }
            }
        }
        Command::Graph {
            app,
            output,
            dm,
            main,
            format,
            trace,
            coverage,
            overview,
            out_dir,
            all,
        } => graph(
            &app,
            sitlog_cli::commands::graph::What {
                output,
                dm,
                main,
                format,
                coverage: coverage.is_some(),
                trace: trace.or(coverage),
                overview,
                out_dir,
                all,
            },
        ),
        Command::Test {
            app,
            filter,
            exact,
            jobs,
            format,
            junit,
            coverage,
            coverage_table,
            coverage_file,
        } => test_app(
            &app,
            sitlog_cli::commands::test::Options {
                filter,
                exact,
                jobs: jobs.map(usize::from),
                json: format == sitlog_cli::args::Format::Json,
                junit,
                coverage: coverage || coverage_table.is_some(),
                coverage_table,
                coverage_file,
            },
        ),
        Command::New { name, robot } => new_app(&name, robot),
        Command::Library { name } => library(name.as_deref()),
        Command::Kb {
            file,
            updates,
            query,
        } => match sitlog_kb::answer_line(&file, &updates, &query) {
            Ok(line) => write_stdout(&format!("{line}\n"), "the answer"),
            Err(e) => {
                sitlog_runtime::errln!("{e}");
                1
            }
        },
    }
}
