//! Interrupts of a task run: SIGINT and SIGTERM stop the machine at its
//! next transition boundary (the run's [`Options::stop`] flag), so the
//! runner can still print the history, close the trace and exit with
//! 130 (SIGINT) or 143 (SIGTERM). A second SIGINT or SIGTERM ends the
//! process at once with that status. The same flag stops a run at the end
//! of its typed input (exit 3) and when another robot went away (exit 4,
//! [`EXIT_ROBOT_GONE`]).
//!
//! Invariant: the handler only sets atomics (signal-hook's iterator runs it
//! on a thread of its own, not in the signal handler); everything else is
//! done by the run's thread when it sees the flag.
//!
//! [`Options::stop`]: sitlog_runtime::machine::Options::stop

use std::io::{self, BufRead, Read};
use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};
use std::sync::mpsc;
use std::sync::Arc;
use std::time::Duration;

/// Exit status of a run stopped by SIGINT.
pub const EXIT_SIGINT: u8 = 130;
/// Exit status of a run stopped by SIGTERM.
pub const EXIT_SIGTERM: u8 = 143;
/// Exit status of a run whose typed input ended (Ctrl-D at the prompt, or
/// the end of a pipe on stdin) while a situation waited for it.
pub const EXIT_END_OF_INPUT: u8 = 3;

/// Exit status of a run on another robot ([`crate::RobotHook`], `--robot
/// ros2`) stopped because the robot went away (it stopped answering, or
/// left the network): the task stops at its next transition boundary
/// with its history and report.
pub const EXIT_ROBOT_GONE: u8 = 4;

/// Whether the run reports in JSON (`--format json`): a signal before the
/// task starts then writes the report (status `interrupted`) as it ends
/// the process ([`report_json_before_start`]).
static JSON_REPORT: AtomicBool = AtomicBool::new(false);

/// Says that this process's run reports in JSON, so that a signal ending
/// it before its task starts writes that report (status `interrupted`)
/// on stdout: a caller reading the report always finds one.
pub fn report_json_before_start(json: bool) {
    JSON_REPORT.store(json, Ordering::SeqCst);
}

/// What [`Interrupt::request_end_of_input`] records in place of a signal.
const END_OF_INPUT: i32 = -1;
/// What [`Interrupt::request_robot_gone`] records in place of a signal.
const ROBOT_GONE: i32 = -2;

/// The stop flag of a run and the signal that set it.
#[derive(Clone, Default)]
pub struct Interrupt {
    pub flag: Arc<AtomicBool>,
    signal: Arc<AtomicI32>,
    /// Set once the task's loop runs (it checks `flag` between
    /// transitions); before that, a signal ends the process at once.
    running: Arc<AtomicBool>,
}

impl Interrupt {
    /// A flag nothing sets (until [`Interrupt::request`]).
    pub fn new() -> Interrupt {
        Interrupt::default()
    }

    /// Watches SIGINT and SIGTERM for this process (unix); elsewhere, a flag
    /// nothing sets.
    pub fn install() -> Interrupt {
        let me = Interrupt::install_before_start();
        me.started();
        me
    }

    /// [`Interrupt::install`] for a run that has not started: until
    /// [`Interrupt::started`], the first signal ends the process at once
    /// with its status (a run opening a FIFO, or waiting for the live view's
    /// page, is blocked where no flag is looked at; nothing has run, so
    /// there is no history to print).
    pub fn install_before_start() -> Interrupt {
        let me = Interrupt::new();
        #[cfg(unix)]
        {
            use signal_hook::consts::{SIGINT, SIGTERM};
            if let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) {
                let watch = me.clone();
                let _ = std::thread::Builder::new()
                    .name("sitlog-signals".into())
                    .spawn(move || {
                        for sig in signals.forever() {
                            if !watch.running.load(Ordering::SeqCst) {
                                const MESSAGE: &str = "interrupted before the task started";
                                sitlog_runtime::errln!("{MESSAGE}");
                                if JSON_REPORT.load(Ordering::SeqCst) {
                                    use std::io::Write as _;
                                    let report = sitlog_runtime::report::stopped_json(
                                        "interrupted",
                                        MESSAGE,
                                    );
                                    let mut out = std::io::stdout();
                                    let _ =
                                        out.write_all(report.as_bytes()).and_then(|_| out.flush());
                                }
                                std::process::exit(i32::from(status_of(sig)));
                            }
                            if watch.flag.load(Ordering::SeqCst) {
                                // The second one: end now.
                                std::process::exit(i32::from(status_of(sig)));
                            }
                            watch.request(sig);
                        }
                    });
            }
        }
        me
    }

    /// The task's loop runs: from now on the first signal stops it at its
    /// next transition.
    pub fn started(&self) {
        self.running.store(true, Ordering::SeqCst);
    }

    /// Asks the run to stop, as signal `signal` would.
    pub fn request(&self, signal: i32) {
        self.signal.store(signal, Ordering::SeqCst);
        self.flag.store(true, Ordering::SeqCst);
    }

    /// Asks the run to stop because its typed input ended (Ctrl-D): the
    /// exit status is then [`EXIT_END_OF_INPUT`].
    pub fn request_end_of_input(&self) {
        self.request(END_OF_INPUT);
    }

    /// Asks the run to stop because the robot went away: the exit status is
    /// then [`EXIT_ROBOT_GONE`].
    pub fn request_robot_gone(&self) {
        if !self.requested() {
            self.request(ROBOT_GONE);
        }
    }

    /// Whether the run was stopped because the robot went away.
    pub fn robot_gone(&self) -> bool {
        self.requested() && self.signal.load(Ordering::SeqCst) == ROBOT_GONE
    }

    /// Whether the run was stopped by the end of its typed input.
    pub fn ended_by_input(&self) -> bool {
        self.requested() && self.signal.load(Ordering::SeqCst) == END_OF_INPUT
    }

    /// Whether a stop was asked for.
    pub fn requested(&self) -> bool {
        self.flag.load(Ordering::SeqCst)
    }

    /// The exit status for the signal that stopped the run (130 for
    /// SIGINT, 143 for SIGTERM), `None` if none did.
    pub fn exit_status(&self) -> Option<u8> {
        self.requested()
            .then(|| status_of(self.signal.load(Ordering::SeqCst)))
    }
}

/// 128 + the signal number, as shells report it (SIGINT 130, SIGTERM 143);
/// [`EXIT_END_OF_INPUT`] for the end of typed input.
fn status_of(signal: i32) -> u8 {
    if signal == END_OF_INPUT {
        return EXIT_END_OF_INPUT;
    }
    if signal == ROBOT_GONE {
        return EXIT_ROBOT_GONE;
    }
    u8::try_from(128 + signal.clamp(0, 127)).unwrap_or(EXIT_SIGINT)
}

/// Standard input read on a thread of its own, so that a reader blocked at
/// the prompt sees an interrupt: reading fails with the error "interrupted"
/// once the flag is set. The thread holds at most a few pieces of at most
/// one buffer (8 KiB) each.
pub struct InterruptibleStdin {
    rx: mpsc::Receiver<io::Result<Vec<u8>>>,
    buf: Vec<u8>,
    pos: usize,
    eof: bool,
    flag: Arc<AtomicBool>,
}

impl InterruptibleStdin {
    pub fn new(flag: Arc<AtomicBool>) -> InterruptibleStdin {
        let (tx, rx) = mpsc::sync_channel(1);
        let _ = std::thread::Builder::new()
            .name("sitlog-stdin".into())
            .spawn(move || {
                let stdin = io::stdin();
                let mut lock = stdin.lock();
                loop {
                    // What one read gave (at most a buffer): a line that
                    // never ends (`< /dev/zero`) is passed on in pieces,
                    // never gathered here, and many short lines go
                    // together (issue 38).
                    let piece = match lock.fill_buf() {
                        Ok([]) => {
                            let _ = tx.send(Ok(Vec::new()));
                            return;
                        }
                        Ok(buf) => {
                            let piece = buf.to_vec();
                            lock.consume(piece.len());
                            piece
                        }
                        Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                        Err(e) => {
                            let _ = tx.send(Err(e));
                            return;
                        }
                    };
                    if tx.send(Ok(piece)).is_err() {
                        return;
                    }
                }
            });
        InterruptibleStdin {
            rx,
            buf: Vec::new(),
            pos: 0,
            eof: false,
            flag,
        }
    }
}

impl Read for InterruptibleStdin {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let n = {
            let available = self.fill_buf()?;
            let n = available.len().min(out.len());
            out[..n].copy_from_slice(&available[..n]);
            n
        };
        self.consume(n);
        Ok(n)
    }
}

impl BufRead for InterruptibleStdin {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        while self.pos >= self.buf.len() && !self.eof {
            if self.flag.load(Ordering::SeqCst) {
                // Not `ErrorKind::Interrupted`: std's readers retry on that.
                return Err(io::Error::other("interrupted"));
            }
            match self.rx.recv_timeout(Duration::from_millis(50)) {
                Ok(Ok(line)) if line.is_empty() => self.eof = true,
                Ok(Ok(line)) => {
                    self.buf = line;
                    self.pos = 0;
                }
                Ok(Err(e)) => return Err(e),
                Err(mpsc::RecvTimeoutError::Timeout) => {}
                Err(mpsc::RecvTimeoutError::Disconnected) => self.eof = true,
            }
        }
        Ok(&self.buf[self.pos.min(self.buf.len())..])
    }

    fn consume(&mut self, n: usize) {
        self.pos = (self.pos + n).min(self.buf.len());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statuses() {
        let i = Interrupt::new();
        assert_eq!(i.exit_status(), None);
        i.request(2);
        assert_eq!(i.exit_status(), Some(EXIT_SIGINT));
        i.request(15);
        assert_eq!(i.exit_status(), Some(EXIT_SIGTERM));
        assert!(!i.ended_by_input());
        let i = Interrupt::new();
        i.request_end_of_input();
        assert!(i.ended_by_input());
        assert_eq!(i.exit_status(), Some(EXIT_END_OF_INPUT));
        let i = Interrupt::new();
        i.request_robot_gone();
        assert!(i.robot_gone());
        assert_eq!(i.exit_status(), Some(EXIT_ROBOT_GONE));
    }
}
