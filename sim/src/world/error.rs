//! Errors in a world file: [`WorldError`] (file, line, column, message), byte
//! offsets turned into lines and columns, and the collector every step of
//! reading reports to. Invariant: errors are kept as byte offsets while
//! reading and come out sorted by position, each once, whatever order they
//! were found in.

use std::fmt;

/// One problem in a world file: where it is and what is wrong.
///
/// `line` and `column` are 1-based (columns count characters). An error that
/// has no position in the text (the file cannot be read) has line and column
/// 0 and displays as `FILE: error: MESSAGE`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WorldError {
    pub file: String,
    pub line: usize,
    pub column: usize,
    pub message: String,
}

impl fmt::Display for WorldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}: error: {}", self.file, self.message)
        } else {
            write!(
                f,
                "{}:{}:{}: error: {}",
                self.file, self.line, self.column, self.message
            )
        }
    }
}

impl std::error::Error for WorldError {}

/// 1-based line and column (in characters) of byte offset `at` in `text`.
pub(crate) fn line_col(text: &str, at: usize) -> (usize, usize) {
    let mut at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map(|i| i + 1).unwrap_or(0);
    let column = before[start..].chars().count() + 1;
    (line, column)
}

/// The error collector.
pub(super) struct Cx<'t> {
    pub file: String,
    text: &'t str,
    /// Byte offset and message of each error found so far.
    pub errors: Vec<(usize, String)>,
}

impl<'t> Cx<'t> {
    pub fn new(file: &str, text: &'t str) -> Self {
        Cx {
            file: file.to_string(),
            text,
            errors: Vec::new(),
        }
    }

    pub fn err(&mut self, at: usize, message: String) {
        self.errors.push((at, message));
    }

    /// `LINE:COL` of byte offset `at`, for messages that point elsewhere.
    pub fn pos(&self, at: usize) -> String {
        let (l, c) = line_col(self.text, at);
        format!("{l}:{c}")
    }

    pub fn finish(mut self) -> Vec<WorldError> {
        self.errors.sort();
        self.errors.dedup();
        self.errors
            .into_iter()
            .map(|(at, message)| {
                let (line, column) = line_col(self.text, at);
                WorldError {
                    file: self.file.clone(),
                    line,
                    column,
                    message,
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_counts_characters() {
        let t = "ab\nçd\nxyz";
        assert_eq!(line_col(t, 0), (1, 1));
        assert_eq!(line_col(t, 3), (2, 1));
        assert_eq!(line_col(t, 5), (2, 2));
        assert_eq!(line_col(t, 4), (2, 1)); // inside ç: back to its start
        assert_eq!(line_col(t, 999), (3, 4));
    }
}
