//! The test-mode prompt on a stream that is not a terminal ([`PromptPerception`]):
//! one term per input, typed or piped, over as many lines as it takes.
//!
//! Invariant: reading costs memory and time linear in what is read, and no
//! more than the input limits allow: a line is read at most
//! `max_bytes + 1` bytes at a time (so `< /dev/zero` is refused after
//! 1 MiB, not grown into gigabytes), and the text gathered so far is read
//! as a term only when a line brings something that may end it (an end
//! token, `.` then layout, outside quotes and comments: [`EndScan`]) or
//! when the text has doubled since it was last read, so a term spread over
//! many lines is read once, not once a line (issue 38).

use super::{deliver, prompt_header, waiting_text, InputLimits};
use crate::machine::{Perceived, Perception};
use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::{Clause, OpTable};
use std::io::{BufRead, Read, Write};

/// Inputs typed at a prompt (stdin), with the expectations listed on stderr.
pub struct PromptPerception<R: BufRead> {
    input: R,
    limits: InputLimits,
    /// Lines read so far (for positions in errors).
    line: usize,
    /// The DM and situation waiting, when the machine said.
    at: Option<(String, String)>,
}

/// A line read, or why there is none.
enum Line {
    Text(String),
    /// More than the bytes asked for, without a line end.
    TooLong(usize),
    End,
}

impl<R: BufRead> PromptPerception<R> {
    pub fn new(input: R) -> Self {
        PromptPerception {
            input,
            limits: InputLimits::default(),
            line: 0,
            at: None,
        }
    }

    /// Reads each input under `limits` (default: [`InputLimits::default`]).
    pub fn with_limits(mut self, limits: InputLimits) -> Self {
        self.limits = limits;
        self
    }

    /// One line of input (with its `\n`), at most `max` bytes kept: more
    /// is [`Line::TooLong`]; an error for text that is not UTF-8.
    fn read_line(&mut self, max: usize) -> Result<Line, String> {
        let mut bytes = Vec::new();
        let n = (&mut self.input)
            .take(max as u64 + 1)
            .read_until(b'\n', &mut bytes)
            .map_err(|e| format!("standard input: {e}"))?;
        if n == 0 {
            return Ok(Line::End);
        }
        if bytes.len() > max {
            return Ok(Line::TooLong(bytes.len()));
        }
        self.line += 1;
        match sitlog_syntax::decode_owned(bytes) {
            Ok(text) => Ok(Line::Text(text)),
            Err(e) => Err(format!(
                "standard input:{}:{}: {}",
                self.line, e.column, e.message
            )),
        }
    }

    /// The next term of the input and its text (trimmed), `prompt`s shown
    /// on `err` before each line (`|: `, then `|  ` inside a term);
    /// `Ok(None)` at the end of the input. A syntax error is shown on
    /// `err` and the next term read; a term over the limits is an error
    /// naming its line.
    pub(crate) fn read_clause(
        &mut self,
        err: &mut dyn Write,
    ) -> Result<Option<(Clause, String)>, String> {
        let mut text = String::new();
        let mut scan = EndScan::default();
        // the length of `text` when it was last read as a term
        let mut tried = 0usize;
        let mut start_line = self.line + 1;
        loop {
            let _ = write!(err, "{}", if text.is_empty() { "|: " } else { "|  " });
            let _ = err.flush();
            if text.is_empty() {
                start_line = self.line + 1;
            }
            let what = || format!("standard input:{start_line}:1: the input");
            let room = self.limits.max_bytes.saturating_sub(text.len());
            let line = match self.read_line(room)? {
                Line::Text(line) => line,
                Line::TooLong(n) => return Err(self.limits.size_error(&what(), text.len() + n)),
                Line::End => String::new(),
            };
            let n = line.len();
            if n == 0 {
                if text.trim().is_empty() {
                    return Ok(None);
                }
                text.push('\n');
            }
            let may_end = scan.feed(&line);
            text.push_str(&line);
            if text.trim().is_empty() {
                text.clear();
                continue;
            }
            if n > 0 && !may_end && text.len() < 2 * tried.max(64) {
                continue;
            }
            tried = text.len();
            let term = text.trim();
            match sitlog_syntax::read_term_limited(
                term,
                OpTable::sitlog_shared(),
                self.limits.max_depth,
            ) {
                Ok(clause) => return Ok(Some((clause, term.to_owned()))),
                Err(e) if e.is_too_deep() => return Err(self.limits.depth_error(&what())),
                Err(e) if e.incomplete && n > 0 => continue,
                Err(e) => {
                    let _ = writeln!(
                        err,
                        "syntax error: {} (type a term ending with `.`)",
                        e.message
                    );
                    text.clear();
                    scan = EndScan::default();
                    tried = 0;
                    if n == 0 {
                        return Ok(None);
                    }
                }
            }
        }
    }

    /// The next term's text for Prolog's `read/1` (the run's next input),
    /// with SWI-Prolog's prompt `|: ` on stderr; `None` at the end.
    pub fn read_term_text(&mut self) -> Result<Option<String>, String> {
        let mut err = std::io::stderr();
        Ok(self.read_clause(&mut err)?.map(|(_, text)| text))
    }
}

impl<R: BufRead> Perception for PromptPerception<R> {
    fn perceive(
        &mut self,
        store: &mut Store,
        ty: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        let mut err = std::io::stderr();
        let header = prompt_header(store, self.at.as_ref(), ty, expectations);
        let _ = writeln!(err, "{header}");
        match self.read_clause(&mut err)? {
            Some((clause, _)) => {
                let (t, _) = store.from_clause(&clause);
                Ok(deliver(store, ty, t))
            }
            None => Ok(Perceived::EndOfInput),
        }
    }

    fn waiting_at(&mut self, store: &Store, dm: Term, situation: Term) {
        self.at = Some(waiting_text(store, dm, situation));
    }
}

/// Where a scan of the lines of one input stands.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum ScanState {
    #[default]
    Code,
    /// Inside a quoted item opened by this quote.
    Quoted(u8),
    /// Inside `/* ... */`.
    Comment,
}

/// Finds, line by line and in time linear in the text, whether the text
/// may hold an end token (`.` then layout, `%` or the end of the line,
/// not after a symbol character) outside quotes and comments. It errs only
/// towards "may": the term reader decides.
#[derive(Debug, Default)]
pub(crate) struct EndScan {
    state: ScanState,
    /// The last two bytes seen (the latest last).
    prev: [u8; 2],
}

fn symbol_char(b: u8) -> bool {
    b"+-*/\\^<>=~:.?@#&$".contains(&b)
}

fn alnum(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

impl EndScan {
    /// Scans `line` (with its line end, if any): whether it holds a
    /// possible end token.
    pub(crate) fn feed(&mut self, line: &str) -> bool {
        let b = line.as_bytes();
        let mut found = false;
        let mut i = 0;
        while i < b.len() {
            let c = b[i];
            match self.state {
                ScanState::Quoted(q) => {
                    if c == b'\\' {
                        // the escaped byte (a line end continues the item)
                        i += 1;
                    } else if c == q {
                        self.state = ScanState::Code;
                    }
                }
                ScanState::Comment => {
                    if c == b'*' && b.get(i + 1) == Some(&b'/') {
                        self.state = ScanState::Code;
                        i += 1;
                    }
                }
                ScanState::Code => match c {
                    // the rest of the line is a comment
                    b'%' => break,
                    b'/' if b.get(i + 1) == Some(&b'*') => {
                        self.state = ScanState::Comment;
                        i += 1;
                    }
                    // 0'c is a character code
                    b'\'' if self.prev[1] == b'0' && !alnum(self.prev[0]) => match b.get(i + 1) {
                        Some(b'\\') => i += 2,
                        Some(b'\'') if b.get(i + 2) == Some(&b'\'') => i += 2,
                        Some(_) => i += 1,
                        None => {}
                    },
                    // N'digits is a radix number
                    b'\'' if self.prev[1].is_ascii_digit() => {}
                    b'\'' | b'"' | b'`' => self.state = ScanState::Quoted(c),
                    b'.' => {
                        let after = b.get(i + 1).copied();
                        if !symbol_char(self.prev[1])
                            && after.is_none_or(|a| a.is_ascii_whitespace() || a == b'%')
                        {
                            found = true;
                        }
                    }
                    _ => {}
                },
            }
            let last = b[i.min(b.len() - 1)];
            self.prev = [self.prev[1], last];
            i += 1;
        }
        // a line end separates tokens
        if self.state == ScanState::Code {
            self.prev = [b' ', b' '];
        }
        found
    }
}
