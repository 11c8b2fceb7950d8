//! What watches a run's transitions besides the debugger and the live view:
//! the progress indicator ([`Progress`]), the `--trace` file
//! ([`TraceFile`]), and several observers as one ([`Fanout`]).

use crate::console::SharedConsole;
use sitlog_runtime::history::Entry;
use sitlog_runtime::machine::{Inspection, Observer};
use sitlog_runtime::report;
use sitlog_runtime::{Store, Term};

/// Counts transitions on the console (the progress indicator).
pub(crate) struct Progress<'a> {
    pub(crate) console: &'a SharedConsole,
}

impl Observer for Progress<'_> {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, _next: Option<Term>) {
        if let Ok(mut c) = self.console.lock() {
            c.tick(|| {
                format!(
                    "{}{} / {}",
                    "  ".repeat(depth.min(8)),
                    store.writeq(entry.dm),
                    store.writeq(entry.situation)
                )
            });
        }
    }
}

/// Several observers as one, in order.
pub(crate) struct Fanout<'a>(pub(crate) Vec<&'a mut dyn Observer>);

impl Observer for Fanout<'_> {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>) {
        for o in &mut self.0 {
            o.transition(store, entry, depth, next);
        }
    }

    fn inspect(&mut self, machine: &mut Inspection<'_>) {
        for o in &mut self.0 {
            o.inspect(machine);
        }
    }

    fn unmatched(&mut self, store: &Store, dm: Term, situation: Term, input: Term, depth: usize) {
        for o in &mut self.0 {
            o.unmatched(store, dm, situation, input, depth);
        }
    }
}

/// The trace file of `--trace`: every write checked (the first error is
/// kept), flushed after each transition, synced to disk at the end.
pub(crate) struct TraceFile {
    inner: report::JsonTrace<std::io::BufWriter<std::fs::File>>,
}

impl Observer for TraceFile {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>) {
        self.inner.transition(store, entry, depth, next);
    }

    fn unmatched(&mut self, store: &Store, dm: Term, situation: Term, input: Term, depth: usize) {
        self.inner.unmatched(store, dm, situation, input, depth);
    }
}

impl TraceFile {
    /// A trace written to `file`.
    pub(crate) fn new(file: std::fs::File) -> TraceFile {
        TraceFile {
            inner: report::JsonTrace::new(std::io::BufWriter::new(file)),
        }
    }

    /// Flushes and syncs; the first write error, if any.
    pub(crate) fn finish(self) -> std::io::Result<()> {
        let file = self
            .inner
            .finish()?
            .into_inner()
            .map_err(|e| e.into_error())?;
        match file.sync_all() {
            // Devices and pipes cannot be synced: nothing was lost.
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::InvalidInput | std::io::ErrorKind::Unsupported
                ) =>
            {
                Ok(())
            }
            r => r,
        }
    }
}
