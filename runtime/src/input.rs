//! Terms from outside the application (a perception read from a script or
//! typed, `--in-arg`, `--main`): [`InputLimits`], the bounds they are read
//! under, and the reading itself. Re-exported as
//! `sitlog_runtime::testmode::InputLimits`; the machine's options carry one.

use sitlog_syntax::OpTable;

/// Limits on one term that comes from outside the application (a
/// perception read from a script or typed, `--in-arg`, `--main`): much
/// tighter than those of source files, so that a hostile or broken message
/// costs a few MB at most.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InputLimits {
    /// Bytes of text of one term (`--max-input-bytes`).
    pub max_bytes: usize,
    /// Nesting depth of one term (`--max-input-depth`).
    pub max_depth: usize,
}

impl InputLimits {
    /// Default of [`InputLimits::max_bytes`]: 1 MiB.
    pub const MAX_BYTES: usize = 1 << 20;
    /// Default of [`InputLimits::max_depth`]: 10 000 levels.
    pub const MAX_DEPTH: usize = 10_000;

    /// The error for a term of `len` bytes or more, if that is over the limit;
    /// `what` names the input (`script s.txt:3:1: a perception`).
    pub fn size_error(&self, what: &str, len: usize) -> String {
        format!(
            "{what} is longer than {} bytes ({len} bytes or more); the limit is set by --max-input-bytes",
            self.max_bytes
        )
    }

    /// The error for a term nested too deeply.
    pub fn depth_error(&self, what: &str) -> String {
        format!(
            "{what} is nested more than {} levels deep; the limit is set by --max-input-depth",
            self.max_depth
        )
    }

    /// Reads one term of outside input under these limits; `what` names it
    /// in errors.
    pub fn read_term(&self, what: &str, text: &str) -> Result<sitlog_syntax::Clause, String> {
        if text.len() > self.max_bytes {
            return Err(self.size_error(what, text.len()));
        }
        sitlog_syntax::read_term_limited(text, OpTable::sitlog_shared(), self.max_depth).map_err(
            |e| {
                if e.is_too_deep() {
                    self.depth_error(what)
                } else {
                    format!("{what}: {}", e.message)
                }
            },
        )
    }
}

impl Default for InputLimits {
    fn default() -> InputLimits {
        InputLimits {
            max_bytes: InputLimits::MAX_BYTES,
            max_depth: InputLimits::MAX_DEPTH,
        }
    }
}

/// The run's input read term by term by code other than the perception
/// that owns it: Prolog's `read/1` in a user function takes the next term
/// of the script, or of standard input, as the original's test mode does
/// (issue 39). One reader serves both, in order.
pub trait TermInput: Send {
    /// The text of the next term of the input (its end token included or
    /// not), `None` at the end of the input; an error names the input and
    /// the position (or the limit) as the perception's errors do.
    fn next_term_text(&mut self) -> Result<Option<String>, String>;
}

/// A [`TermInput`] shared between the perception that owns it (on the
/// runner's thread) and the Prolog engine (on its own thread).
pub type SharedInput = std::sync::Arc<std::sync::Mutex<dyn TermInput>>;
