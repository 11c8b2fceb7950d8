//! The end-of-run report in our fixed formats: the history listing of the
//! papers (text) and the `sitlogc run --format json` object, plus the
//! JSON lines of `--trace` (one per transition, and one per input that met
//! no expectation). The JSON is written by
//! serde_json (compact, keys in the order of the notes' convention).

use crate::history::{Entry, Item};
use crate::machine::{Observer, Outcome};
use crate::store::Store;
use crate::term::Term;
use serde::ser::{Serialize, SerializeMap, SerializeSeq, SerializeStruct, Serializer};
use std::io::Write;

/// serde_json's compact output, except that backspace and form feed are
/// written `\u0008` and `\u000c` (not `\b`, `\f`): the bytes this report
/// has always had.
struct Compact;

impl serde_json::ser::Formatter for Compact {
    fn write_char_escape<W: ?Sized + Write>(
        &mut self,
        writer: &mut W,
        char_escape: serde_json::ser::CharEscape,
    ) -> std::io::Result<()> {
        use serde_json::ser::CharEscape;
        match char_escape {
            CharEscape::Backspace => writer.write_all(b"\\u0008"),
            CharEscape::FormFeed => writer.write_all(b"\\u000c"),
            other => serde_json::ser::CompactFormatter.write_char_escape(writer, other),
        }
    }
}

/// `value` as one line of JSON.
fn to_json<T: Serialize>(value: &T) -> String {
    let mut out = Vec::new();
    let mut ser = serde_json::Serializer::with_formatter(&mut out, Compact);
    value
        .serialize(&mut ser)
        .expect("serializing to memory does not fail");
    String::from_utf8(out).expect("serde_json writes UTF-8")
}

/// One history entry: `{"dm":…,"situation":…,"expectation":…,"action":…}`,
/// plus `depth` and `next` in a trace line.
struct EntryJson<'a> {
    store: &'a Store,
    entry: &'a Entry,
    trace: Option<(usize, Option<Term>)>,
}

impl Serialize for EntryJson<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (store, e) = (self.store, self.entry);
        let mut m = s.serialize_struct("Entry", if self.trace.is_some() { 6 } else { 4 })?;
        m.serialize_field("dm", &store.writeq(e.dm))?;
        m.serialize_field("situation", &store.writeq(e.situation))?;
        m.serialize_field("expectation", &store.writeq(e.expectation))?;
        m.serialize_field("action", &store.writeq(e.action))?;
        if let Some((depth, next)) = self.trace {
            m.serialize_field("depth", &depth)?;
            m.serialize_field("next", &next.map(|n| store.writeq(n)))?;
        }
        m.end()
    }
}

/// A history: an array of entries and (embedded DMs) nested arrays.
struct ItemsJson<'a> {
    store: &'a Store,
    items: &'a [Item],
}

impl Serialize for ItemsJson<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        // Deeply nested histories: grow the stack rather than overflow it.
        stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
            let mut seq = s.serialize_seq(Some(self.items.len()))?;
            for item in self.items {
                match item {
                    Item::Entry(entry) => seq.serialize_element(&EntryJson {
                        store: self.store,
                        entry,
                        trace: None,
                    })?,
                    Item::Nested(inner) => seq.serialize_element(&ItemsJson {
                        store: self.store,
                        items: inner,
                    })?,
                }
            }
            seq.end()
        })
    }
}

/// The global variables as an object, in their order.
struct GlobalsJson<'a> {
    store: &'a Store,
    outcome: &'a Outcome,
}

impl Serialize for GlobalsJson<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let entries = self.outcome.globals.entries();
        let mut m = s.serialize_map(Some(entries.len()))?;
        for &(name, value) in entries.iter() {
            m.serialize_entry(name.as_str(), &self.store.writeq(value))?;
        }
        m.end()
    }
}

/// The `--format json` object.
struct OutcomeJson<'a> {
    store: &'a Store,
    outcome: &'a Outcome,
}

impl Serialize for OutcomeJson<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (store, outcome) = (self.store, self.outcome);
        let (status, error) = match &outcome.result {
            Ok(()) => ("ok", None),
            Err(e) if outcome.interrupted => ("interrupted", Some(e.to_string())),
            Err(e) => ("error", Some(e.to_string())),
        };
        let mut m = s.serialize_struct("Outcome", 5)?;
        m.serialize_field("status", status)?;
        m.serialize_field("error", &error)?;
        m.serialize_field(
            "history",
            &ItemsJson {
                store,
                items: &outcome.history,
            },
        )?;
        m.serialize_field("out_arg", &store.writeq(outcome.out_arg))?;
        m.serialize_field("globals", &GlobalsJson { store, outcome })?;
        m.end()
    }
}

/// The `--format json` object of a run whose task did not run, or
/// stopped before it could report (the program refused by its check, a
/// file that cannot be opened, the sandbox required and missing, a signal
/// before the start): `status` (`"error"` or `"interrupted"`), the error's
/// message, an empty history, `out_arg` `null`, no globals. A caller
/// reading the report always finds one.
pub fn stopped_json(status: &str, message: &str) -> String {
    struct Stopped<'a>(&'a str, &'a str);
    impl Serialize for Stopped<'_> {
        fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            let mut m = s.serialize_struct("Outcome", 5)?;
            m.serialize_field("status", self.0)?;
            m.serialize_field("error", self.1)?;
            m.serialize_field("history", &[(); 0])?;
            m.serialize_field("out_arg", &None::<&str>)?;
            m.serialize_field("globals", &std::collections::BTreeMap::<&str, &str>::new())?;
            m.end()
        }
    }
    let message = message.trim_end();
    let message = message.strip_prefix("error: ").unwrap_or(message);
    format!("{}\n", to_json(&Stopped(status, message)))
}

/// The history as a JSON array (nested arrays for embedded DMs).
pub fn history_json(store: &Store, items: &[Item]) -> String {
    to_json(&ItemsJson { store, items })
}

/// The `--format json` object.
pub fn outcome_json(store: &Store, outcome: &Outcome) -> String {
    to_json(&OutcomeJson { store, outcome })
}

/// The `--format text` report: the history listing, then `Out Arg:` and
/// `Out Global Vars:` lines. A run-time error is not part of it: the
/// runner reports it once, on stderr, like every diagnostic.
pub fn outcome_text(store: &mut Store, outcome: &Outcome) -> String {
    outcome_text_with(store, outcome, true)
}

/// [`outcome_text`]; without `history` (a run with `--history none`, which
/// keeps none) the `Execution history:` listing is left out, and the report
/// is the `Out Arg:` and `Out Global Vars:` lines.
pub fn outcome_text_with(store: &mut Store, outcome: &Outcome, history: bool) -> String {
    let mut out = String::new();
    if history {
        out.push_str("Execution history:\n");
        write_text(store, &outcome.history, 0, &mut out);
        out.push('\n');
    }
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
        let line = to_json(&EntryJson {
            store,
            entry,
            trace: Some((depth, next)),
        });
        self.write_line(&line);
    }

    /// `{"dm":…,"situation":…,"unmatched":INPUT,"depth":N}`: an input that
    /// met no expectation (no `expectation`, `action` or `next`: it is not
    /// a transition).
    fn unmatched(&mut self, store: &Store, dm: Term, situation: Term, input: Term, depth: usize) {
        if self.error.is_some() {
            return;
        }
        let line = to_json(&UnmatchedJson {
            dm: store.writeq(dm),
            situation: store.writeq(situation),
            unmatched: store.writeq(input),
            depth,
        });
        self.write_line(&line);
    }
}

impl<W: Write> JsonTrace<W> {
    fn write_line(&mut self, line: &str) {
        let written = writeln!(self.out, "{line}").and_then(|_| self.out.flush());
        if let Err(e) = written {
            self.error = Some(e);
        }
    }
}

/// A trace line for an input that met no expectation.
#[derive(serde::Serialize)]
struct UnmatchedJson {
    dm: String,
    situation: String,
    unmatched: String,
    depth: usize,
}

#[cfg(test)]
mod json_tests {
    use super::to_json;

    /// The escapes the report has always written (every control character
    /// as `\uXXXX` except `\n`, `\r`, `\t`; DEL and non-ASCII as they are).
    #[test]
    fn string_escapes_are_the_reports_own() {
        let text = "a\u{8}b\u{c}c\u{1}\u{1f}\"\\/\n\t\r\u{7f}é€😀";
        assert_eq!(
            to_json(&text),
            "\"a\\u0008b\\u000cc\\u0001\\u001f\\\"\\\\/\\n\\t\\r\u{7f}é€😀\""
        );
        // Still JSON, and the same string back.
        let back: String = serde_json::from_str(&to_json(&text)).unwrap();
        assert_eq!(back, text);
    }
}
