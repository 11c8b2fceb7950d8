//! The output convention of `sitlogc kb FILE [--do UPDATE]... QUERY` (kb.md
//! section 6) as a function ([`answer_line`]): load the KB, check every
//! update and the query, apply the updates in order, run the query, and
//! give the exact answer line or the exact error line. No argument parsing
//! here: the command line is the caller's.

use crate::answer::CallError;
use crate::model::Kb;
use sitlog_syntax::{line_col, read_term};
use std::fmt;
use std::path::Path;

/// An [`answer_line`] error, already formatted as `WHERE:LINE:COL: error: message`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct QueryError(pub String);

impl fmt::Display for QueryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for QueryError {}

fn located(label: &str, src: &str, e: &CallError) -> QueryError {
    let (l, c) = line_col(src, e.span().start as usize);
    QueryError(format!("{label}:{l}:{c}: error: {e}"))
}

/// The answer line of `query` (one service call, the answer its last
/// argument) on `kb` as it is: what `sitlogc kb` prints for it (`false`
/// when the service fails). `label` names the query in errors
/// (`LABEL:LINE:COL: error: ...`, the position inside the query).
pub fn answer_in(kb: &Kb, label: &str, query: &str) -> Result<String, QueryError> {
    let q = read_term(query).map_err(|e| located(label, query, &CallError::Syntax(e)))?;
    Kb::check_query(&q).map_err(|e| located(label, query, &e))?;
    match kb.call(&q) {
        Ok(outcome) => Ok(outcome.to_line()),
        Err(e) => Err(located(label, query, &e)),
    }
}

/// The line `sitlogc kb KB_PATH [--do D]... QUERY` prints: `Ok` is the
/// answer line (without its newline), `Err` the error line.
pub fn answer_line(kb_path: &Path, dos: &[String], query: &str) -> Result<String, QueryError> {
    let mut kb = Kb::load(kb_path).map_err(|e| QueryError(e.to_string()))?;
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
