//! The reader (work in progress).
use crate::ops::OpTable;
use crate::term::{Clause, Span};

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

/// Reads all clauses of `src` with SitLog's operator table.
pub fn read_clauses(src: &str) -> (Vec<Clause>, Vec<SyntaxError>) {
    read_clauses_with(src, OpTable::sitlog_shared())
}

pub fn read_clauses_with(src: &str, ops: &OpTable) -> (Vec<Clause>, Vec<SyntaxError>) {
    let _ = (src, ops);
    (Vec::new(), Vec::new())
}

pub fn read_term(src: &str) -> Result<Clause, SyntaxError> {
    read_term_with(src, OpTable::sitlog_shared())
}

pub fn read_term_with(src: &str, ops: &OpTable) -> Result<Clause, SyntaxError> {
    let _ = (src, ops);
    Err(SyntaxError {
        span: Span::default(),
        message: "not implemented".into(),
        labels: vec![],
        help: None,
        incomplete: false,
    })
}

pub struct ClauseReader;
