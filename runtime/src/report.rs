//! The end-of-run report in our fixed formats: the history listing of the
//! papers (text) and the `sitlogc run --format json` object, plus the
//! per-transition JSON lines of `--trace`.

use crate::history::{Entry, Item};
use crate::machine::{Observer, Outcome};
use crate::store::Store;
use crate::term::Term;
use std::io::Write;

fn json_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn entry_json(store: &Store, e: &Entry) -> String {
    format!(
        "{{\"dm\":{},\"situation\":{},\"expectation\":{},\"action\":{}}}",
        json_string(&store.writeq(e.dm)),
        json_string(&store.writeq(e.situation)),
        json_string(&store.writeq(e.expectation)),
        json_string(&store.writeq(e.action))
    )
}

/// The history as a JSON array (nested arrays for embedded DMs).
pub fn history_json(store: &Store, items: &[Item]) -> String {
    let mut out = String::new();
    write_items(store, items, &mut out);
    out
}

fn write_items(store: &Store, items: &[Item], out: &mut String) {
    stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
        out.push('[');
        for (i, item) in items.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            match item {
                Item::Entry(e) => out.push_str(&entry_json(store, e)),
                Item::Nested(inner) => write_items(store, inner, out),
            }
        }
        out.push(']');
    })
}

/// The `--format json` object.
pub fn outcome_json(store: &Store, outcome: &Outcome) -> String {
    let (status, error) = match &outcome.result {
        Ok(()) => ("ok", "null".to_owned()),
        Err(e) if outcome.interrupted => ("interrupted", json_string(&e.to_string())),
        Err(e) => ("error", json_string(&e.to_string())),
    };
    let globals: Vec<String> = outcome
        .globals
        .entries()
        .iter()
        .map(|&(n, v)| {
            format!(
                "{}:{}",
                json_string(n.as_str()),
                json_string(&store.writeq(v))
            )
        })
        .collect();
    format!(
        "{{\"status\":\"{status}\",\"error\":{error},\"history\":{},\"out_arg\":{},\"globals\":{{{}}}}}",
        history_json(store, &outcome.history),
        json_string(&store.writeq(outcome.out_arg)),
        globals.join(",")
    )
}

/// The `--format text` report: the history listing, then `Out Arg:` and
/// `Out Global Vars:` lines. A run-time error is not part of it: the
/// runner reports it once, on stderr, like every diagnostic.
pub fn outcome_text(store: &mut Store, outcome: &Outcome) -> String {
    let mut out = String::from("Execution history:\n");
    write_text(store, &outcome.history, 0, &mut out);
    out.push('\n');
    out.push_str(&format!("Out Arg: {}\n", store.writeq(outcome.out_arg)));
    let globals = outcome.globals.to_term(store);
    out.push_str(&format!("Out Global Vars: {}\n", store.writeq(globals)));
    out
}

fn write_text(store: &mut Store, items: &[Item], depth: usize, out: &mut String) {
    stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
        let indent = "  ".repeat(depth);
        for item in items {
            match item {
                Item::Entry(e) => {
                    let t = e.to_term(store);
                    out.push_str(&format!("{indent}{}\n", store.writeq(t)));
                }
                Item::Nested(inner) => {
                    out.push_str(&format!("{indent}[\n"));
                    write_text(store, inner, depth + 1, out);
                    out.push_str(&format!("{indent}]\n"));
                }
            }
        }
    })
}

/// `--trace FILE`: one JSON object per transition, flushed as it happens.
/// Every write is checked: after the first failure nothing more is written,
/// and [`JsonTrace::finish`] returns that error.
pub struct JsonTrace<W: Write> {
    out: W,
    error: Option<std::io::Error>,
}

impl<W: Write> JsonTrace<W> {
    pub fn new(out: W) -> Self {
        JsonTrace { out, error: None }
    }

    /// Flushes; the writer, or the first write error.
    pub fn finish(mut self) -> std::io::Result<W> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        self.out.flush()?;
        Ok(self.out)
    }
}

impl<W: Write> Observer for JsonTrace<W> {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>) {
        if self.error.is_some() {
            return;
        }
        let mut line = entry_json(store, entry);
        line.pop();
        let next = next.map_or("null".to_owned(), |n| json_string(&store.writeq(n)));
        let written = writeln!(self.out, "{line},\"depth\":{depth},\"next\":{next}}}")
            .and_then(|_| self.out.flush());
        if let Err(e) = written {
            self.error = Some(e);
        }
    }
}
