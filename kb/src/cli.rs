//! The `sitlogc kb FILE [--do UPDATE]... QUERY` convention (kb.md section 6):
//! load, check every update and the query, apply the updates in order, run
//! the query, and produce the exact output line or the exact error line.

use crate::answer::CallError;
use crate::model::Kb;
use sitlog_syntax::read_term;
use std::fmt;
use std::path::Path;

/// A `sitlogc kb` error, already formatted as `WHERE:LINE:COL: error: message`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CliError(pub String);

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for CliError {}

/// 1-based line and column (in characters) of a byte offset.
pub fn line_col(src: &str, byte: usize) -> (usize, usize) {
    let mut byte = byte.min(src.len());
    while !src.is_char_boundary(byte) {
        byte -= 1;
    }
    let before = &src[..byte];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

fn located(label: &str, src: &str, e: &CallError) -> CliError {
    let (l, c) = line_col(src, e.span().start as usize);
    CliError(format!("{label}:{l}:{c}: error: {e}"))
}

/// Runs `sitlogc kb KB_PATH [--do D]... QUERY`; `Ok` is the stdout line.
pub fn cli(kb_path: &Path, dos: &[String], query: &str) -> Result<String, CliError> {
    let mut kb = Kb::load(kb_path).map_err(|e| CliError(e.to_string()))?;
    let mut updates = Vec::with_capacity(dos.len());
    for (n, d) in dos.iter().enumerate() {
        let label = format!("<do-{}>", n + 1);
        let c = read_term(d).map_err(|e| located(&label, d, &CallError::Syntax(e)))?;
        Kb::check_update(&c).map_err(|e| located(&label, d, &e))?;
        updates.push((label, c));
    }
    let q = read_term(query).map_err(|e| located("<query>", query, &CallError::Syntax(e)))?;
    Kb::check_query(&q).map_err(|e| located("<query>", query, &e))?;
    for (n, (label, c)) in updates.iter().enumerate() {
        match kb.update(c) {
            Ok(true) => {}
            Ok(false) => return Ok("false".to_owned()),
            Err(e) => return Err(located(label, &dos[n], &e)),
        }
    }
    match kb.call(&q) {
        Ok(outcome) => Ok(outcome.to_line()),
        Err(e) => Err(located("<query>", query, &e)),
    }
}
