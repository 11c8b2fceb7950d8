//! `sitlogc man`: the manual pages, from the clap definitions.

use crate::args::Cli;
use crate::output::write_stdout;
use clap::CommandFactory;

/// `sitlogc man [--dir DIR]`.
pub fn man(dir: Option<&std::path::Path>) -> u8 {
    let command = Cli::command();
    match dir {
        None => {
            let mut out = Vec::new();
            match clap_mangen::Man::new(command).render(&mut out) {
                Ok(()) => write_stdout(&String::from_utf8_lossy(&out), "the manual page"),
                Err(e) => {
                    sitlog_runtime::errln!("error: cannot render the manual page: {e}");
                    2
                }
            }
        }
        Some(dir) => {
            let written =
                std::fs::create_dir_all(dir).and_then(|_| clap_mangen::generate_to(command, dir));
            match written {
                Ok(()) => {
                    sitlog_runtime::errln!(
                        "sitlogc: wrote the manual pages into {}",
                        dir.display()
                    );
                    0
                }
                Err(e) => {
                    sitlog_runtime::errln!(
                        "error: cannot write the manual pages into {}: {e}",
                        dir.display()
                    );
                    2
                }
            }
        }
    }
}
