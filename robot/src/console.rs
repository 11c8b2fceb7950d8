//! Where a run's words for people go: the transcript (the conversation as
//! turns, `Golem: ...` / `Luis: ...`, and short narration lines for what the
//! robot does) and the progress indicator.
//!
//! Invariants: every write is checked, and the first failure is kept to be
//! reported when the run ends (a transcript that never reached its reader is
//! not a success), except a closed pipe (`| head`), which ends output
//! quietly; the progress indicator never writes between the characters of a
//! transcript line (lines are printed through it, test mode's actions too:
//! [`ConsoleStderr`]), and it is gone while the task waits for input typed
//! at the terminal ([`Console::pause`]), so the prompt and what is typed stay
//! readable.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{self, Write};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// The transcript and progress of one run.
pub struct Console {
    out: Box<dyn Write + Send>,
    progress: Option<ProgressBar>,
    /// While paused: the progress indicator's count and elapsed time.
    paused: Option<(u64, Duration)>,
    /// The next tick names where the task is (after a pause).
    rename: bool,
    /// Print narration lines (off with `--quiet`).
    narrate: bool,
    /// The first write that failed (other than a closed pipe).
    failed: Option<io::Error>,
    /// The reader went away (broken pipe): write nothing more.
    closed: bool,
    transitions: u64,
}

/// A console shared by the robot, the KB functions and the runner.
pub type SharedConsole = Arc<Mutex<Console>>;

impl Console {
    /// A console writing the transcript to `out`, with a progress indicator
    /// on stderr when `progress` is true.
    pub fn new(out: Box<dyn Write + Send>, progress: bool, narrate: bool) -> Console {
        let progress = progress.then(|| spinner(0, Duration::ZERO));
        Console {
            out,
            progress,
            paused: None,
            rename: false,
            narrate,
            failed: None,
            closed: false,
            transitions: 0,
        }
    }

    /// A console that keeps nothing (for runs without a transcript).
    pub fn sink() -> Console {
        Console::new(Box::new(io::sink()), false, false)
    }

    pub fn shared(self) -> SharedConsole {
        Arc::new(Mutex::new(self))
    }

    /// One line of the transcript, as it is.
    pub fn line(&mut self, text: &str) {
        if self.closed {
            return;
        }
        let out = &mut self.out;
        let write = |out: &mut Box<dyn Write + Send>| -> io::Result<()> {
            out.write_all(text.as_bytes())?;
            out.write_all(b"\n")?;
            out.flush()
        };
        let result = match &self.progress {
            Some(bar) => bar.suspend(|| write(out)),
            None => write(out),
        };
        self.note(result);
    }

    /// A turn of the conversation: `Who: text`.
    pub fn turn(&mut self, who: &str, text: &str) {
        self.line(&format!("{who}: {text}"));
    }

    /// A narration line (what the robot or the world did), unless quiet.
    pub fn narrate(&mut self, text: &str) {
        if self.narrate {
            self.line(&format!("  ({text})"));
        }
    }

    /// Counts a transition; `at` says where the task is now.
    pub fn tick(&mut self, at: impl FnOnce() -> String) {
        self.transitions += 1;
        if let Some(bar) = &self.progress {
            bar.set_position(self.transitions);
            if self.transitions % 16 == 1 || std::mem::take(&mut self.rename) {
                bar.set_message(at());
            }
        }
    }

    /// Whether a progress indicator is shown (or paused).
    pub fn shows_progress(&self) -> bool {
        self.progress.is_some() || self.paused.is_some()
    }

    /// Removes the progress indicator from the terminal while the task
    /// waits for typed input; [`Console::resume`] brings it back.
    pub fn pause(&mut self) {
        if let Some(bar) = self.progress.take() {
            self.paused = Some((bar.position(), bar.elapsed()));
            bar.finish_and_clear();
        }
    }

    /// Shows the progress indicator again after [`Console::pause`], with
    /// its count and time; the next transition names where the task is.
    pub fn resume(&mut self) {
        if let Some((position, elapsed)) = self.paused.take() {
            self.progress = Some(spinner(position, elapsed));
            self.rename = true;
        }
    }

    /// Runs `f` (which writes to the terminal) with the progress indicator
    /// out of the way.
    pub fn around_progress<R>(&self, f: impl FnOnce() -> R) -> R {
        match &self.progress {
            Some(bar) => bar.suspend(f),
            None => f(),
        }
    }

    /// Removes the progress indicator and flushes; the first write error, if any.
    pub fn finish(&mut self) -> Option<io::Error> {
        self.paused = None;
        if let Some(bar) = self.progress.take() {
            bar.finish_and_clear();
        }
        if !self.closed {
            let r = self.out.flush();
            self.note(r);
        }
        self.failed.take()
    }

    fn note(&mut self, result: io::Result<()>) {
        match result {
            Ok(()) => {}
            Err(e) if e.kind() == io::ErrorKind::BrokenPipe => self.closed = true,
            Err(e) => {
                self.closed = true;
                if self.failed.is_none() {
                    self.failed = Some(e);
                }
            }
        }
    }
}

/// The progress indicator on stderr, at `position` transitions after
/// `elapsed`.
fn spinner(position: u64, elapsed: Duration) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr())
        .with_position(position)
        .with_elapsed(elapsed);
    bar.set_style(
        ProgressStyle::with_template("{spinner} {elapsed} {pos} transitions  {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    bar.enable_steady_tick(Duration::from_millis(100));
    bar
}

/// Stderr written line by line around the console's progress indicator
/// (test mode's `Golem says: ...` lines): a line is never drawn over.
pub struct ConsoleStderr {
    console: SharedConsole,
    line: Vec<u8>,
}

impl ConsoleStderr {
    pub fn new(console: SharedConsole) -> ConsoleStderr {
        ConsoleStderr {
            console,
            line: Vec::new(),
        }
    }

    /// Writes the complete lines gathered so far (everything with `all`).
    fn write_lines(&mut self, all: bool) -> io::Result<()> {
        let end = match self.line.iter().rposition(|&b| b == b'\n') {
            Some(i) => i + 1,
            None if all => self.line.len(),
            None => return Ok(()),
        };
        if end == 0 {
            return Ok(());
        }
        let text: Vec<u8> = self.line.drain(..end).collect();
        let write = || {
            let mut err = io::stderr().lock();
            err.write_all(&text).and_then(|_| err.flush())
        };
        match self.console.lock() {
            Ok(c) => c.around_progress(write),
            Err(_) => write(),
        }
    }
}

impl Write for ConsoleStderr {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.line.extend_from_slice(buf);
        self.write_lines(false)?;
        Ok(buf.len())
    }
    /// Writes the complete lines (a part of a line waits for its end, so
    /// that the progress indicator is never drawn after it).
    fn flush(&mut self) -> io::Result<()> {
        self.write_lines(false)
    }
}

impl Drop for ConsoleStderr {
    fn drop(&mut self) {
        let _ = self.write_lines(true);
    }
}

/// A `Write` into a shared buffer (tests read what a run printed).
#[derive(Clone, Default)]
pub struct SharedBuf(pub Arc<Mutex<Vec<u8>>>);

impl SharedBuf {
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.0.lock().map(|b| b.clone()).unwrap_or_default()).into_owned()
    }
}

impl Write for SharedBuf {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0
            .lock()
            .map_err(|_| io::Error::other("poisoned"))?
            .extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// A `Write` shared by the transcript and the report that follows it on
/// the same stream (clones write to the one writer, in order).
#[derive(Clone)]
pub struct SharedWriter(Arc<Mutex<Box<dyn Write + Send>>>);

impl SharedWriter {
    pub fn new(w: Box<dyn Write + Send>) -> SharedWriter {
        SharedWriter(Arc::new(Mutex::new(w)))
    }
}

impl Write for SharedWriter {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0
            .lock()
            .map_err(|_| io::Error::other("poisoned"))?
            .write(buf)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.0
            .lock()
            .map_err(|_| io::Error::other("poisoned"))?
            .flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Full;
    impl Write for Full {
        fn write(&mut self, _: &[u8]) -> io::Result<usize> {
            Err(io::Error::from_raw_os_error(28))
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    struct Closed;
    impl Write for Closed {
        fn write(&mut self, _: &[u8]) -> io::Result<usize> {
            Err(io::ErrorKind::BrokenPipe.into())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn turns_and_narration() {
        let buf = SharedBuf::default();
        let mut c = Console::new(Box::new(buf.clone()), false, true);
        c.turn("Golem", "Hi Luis.");
        c.narrate("Golem goes to the kitchen");
        assert!(c.finish().is_none());
        assert_eq!(
            buf.text(),
            "Golem: Hi Luis.\n  (Golem goes to the kitchen)\n"
        );
        let buf = SharedBuf::default();
        let mut c = Console::new(Box::new(buf.clone()), false, false);
        c.narrate("hidden");
        c.turn("Luis", "yes");
        c.finish();
        assert_eq!(buf.text(), "Luis: yes\n");
    }

    #[test]
    fn a_failed_write_is_kept_a_closed_pipe_is_not() {
        let mut c = Console::new(Box::new(Full), false, true);
        c.turn("Golem", "lost");
        assert!(c.finish().is_some());
        let mut c = Console::new(Box::new(Closed), false, true);
        c.turn("Golem", "nobody reads this");
        assert!(c.finish().is_none());
    }
}
