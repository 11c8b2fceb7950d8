//! Where a run writes ([`Streams`]): the report on stdout, messages on
//! stderr, and whether each is a terminal (the progress indicator and
//! colours need both).

use std::io::{IsTerminal, Write};

/// Where a run writes: the report (stdout), messages (stderr), and whether
/// each is a terminal. With a world, the transcript goes to stdout before
/// a text report, to stderr with `--format json`. In test mode the actions
/// are rendered on the process's own stderr, not here.
pub struct Streams {
    pub stdout: Box<dyn Write + Send>,
    pub stderr: Box<dyn Write + Send>,
    pub stdout_is_terminal: bool,
    pub stderr_is_terminal: bool,
}

impl Streams {
    /// The process's own stdout and stderr.
    pub fn process() -> Streams {
        Streams {
            stdout_is_terminal: std::io::stdout().is_terminal(),
            stderr_is_terminal: std::io::stderr().is_terminal(),
            stdout: Box::new(std::io::stdout()),
            stderr: Box::new(std::io::stderr()),
        }
    }
}
