//! Syntax errors: [`SyntaxError`] (a span, a message, related labels and
//! help) and byte offsets turned into 1-based lines and columns. Below the
//! lexer and the reader, which both make them.

use crate::term::Span;

/// The start of the message of a depth-limit error ([`SyntaxError::is_too_deep`]).
pub(crate) const TOO_DEEP: &str = "term nested too deeply";

/// A syntax error with its position and, where useful, related positions.
#[derive(Clone, Debug, PartialEq)]
pub struct SyntaxError {
    pub span: Span,
    pub message: String,
    /// Secondary labels, e.g. the unclosed bracket.
    pub labels: Vec<(Span, String)>,
    pub help: Option<String>,
    /// The input ended inside a term: more text could complete it.
    pub incomplete: bool,
}

impl SyntaxError {
    pub fn new(span: Span, message: String) -> SyntaxError {
        SyntaxError {
            span,
            message,
            labels: Vec::new(),
            help: None,
            incomplete: false,
        }
    }
    pub(crate) fn with_help(mut self, help: &str) -> SyntaxError {
        self.help = Some(help.to_owned());
        self
    }
}

impl SyntaxError {
    /// Whether this is the error of a depth limit ([`MAX_DEPTH`](crate::read::MAX_DEPTH), or
    /// the one given to [`read_term_limited`](crate::read_term_limited) or
    /// [`ClauseReader::with_max_depth`](crate::ClauseReader::with_max_depth)).
    pub fn is_too_deep(&self) -> bool {
        self.message.starts_with(TOO_DEEP)
    }

    /// 1-based line and column (in characters) of the start of the error in `src`.
    pub fn line_col(&self, src: &str) -> (usize, usize) {
        line_col(src, self.span.start as usize)
    }

    /// [`SyntaxError::line_col`] for raw bytes (invalid UTF-8 counts one column per byte).
    pub fn line_col_bytes(&self, src: &[u8]) -> (usize, usize) {
        let at = (self.span.start as usize).min(src.len());
        let before = &src[..at];
        let line_start = before
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1);
        let line = 1 + before.iter().filter(|&&b| b == b'\n').count();
        let col = 1 + String::from_utf8_lossy(&before[line_start..])
            .chars()
            .count();
        (line, col)
    }
}

/// 1-based line and column (in characters) of byte `offset` of `src`.
/// Offsets past the end or inside a character are clamped.
pub fn line_col(src: &str, offset: usize) -> (usize, usize) {
    let mut at = offset.min(src.len());
    while !src.is_char_boundary(at) {
        at -= 1;
    }
    let before = &src[..at];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line = 1 + before.bytes().filter(|&b| b == b'\n').count();
    (line, 1 + before[line_start..].chars().count())
}

impl std::fmt::Display for SyntaxError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for SyntaxError {}
