//! Test mode, as the original's: expectations are met by terms read from a
//! script (one term per clause, ending with `.`) or typed at a prompt, and
//! actions are rendered as text on stderr. Input is data: it is read as a
//! term and never executed.

use crate::machine::{Actions, Perceived, Perception};
use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::{Atom, ClauseReader, OpTable};
use std::io::{BufRead, Write};

/// Types whose perceptual interpreter wraps the input as `said(Term)` (D-14).
fn wraps_said(store: &Store, ty: Term) -> bool {
    let name = store.functor(ty).map(|(n, _)| n.as_str());
    matches!(name, Some("nkeyboard") | Some("listening"))
}

fn deliver(store: &mut Store, ty: Term, input: Term) -> Perceived {
    if wraps_said(store, ty) {
        Perceived::Input(store.compound(Atom::intern("said"), &[input]))
    } else {
        Perceived::Input(input)
    }
}

/// Inputs from a script text.
pub struct ScriptPerception {
    text: String,
    pos: usize,
    /// Name of the script for error messages.
    name: String,
    /// Echo each input read to stderr.
    pub echo: bool,
}

impl ScriptPerception {
    pub fn new(name: impl Into<String>, text: String) -> ScriptPerception {
        ScriptPerception {
            text,
            pos: 0,
            name: name.into(),
            echo: false,
        }
    }
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

impl Perception for ScriptPerception {
    fn perceive(
        &mut self,
        store: &mut Store,
        ty: Term,
        _expectations: &[Term],
    ) -> Result<Perceived, String> {
        let ops = OpTable::sitlog_shared();
        let rest = &self.text[self.pos..];
        let mut reader = ClauseReader::new(rest, ops);
        match reader.next_clause() {
            None => Ok(Perceived::EndOfInput),
            Some(Ok(clause)) => {
                let base = self.pos;
                self.pos = base + reader.position();
                let (t, _) = store.from_clause(&clause);
                if self.echo {
                    eprintln!("input: {}", store.writeq(t));
                }
                Ok(deliver(store, ty, t))
            }
            Some(Err(e)) => {
                let (line, col) = line_col(&self.text, self.pos + e.span.start as usize);
                Err(format!(
                    "{}:{line}:{col}: syntax error in input: {}",
                    self.name, e.message
                ))
            }
        }
    }
}

/// Inputs typed at a prompt (stdin), with the expectations listed on stderr.
pub struct PromptPerception<R: BufRead> {
    input: R,
}

impl<R: BufRead> PromptPerception<R> {
    pub fn new(input: R) -> Self {
        PromptPerception { input }
    }
}

impl<R: BufRead> Perception for PromptPerception<R> {
    fn perceive(
        &mut self,
        store: &mut Store,
        ty: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        let list: Vec<String> = expectations.iter().map(|&e| store.writeq(e)).collect();
        let mut err = std::io::stderr();
        let _ = writeln!(
            err,
            "[{}] expectations: {}",
            store.writeq(ty),
            list.join(" | ")
        );
        let mut text = String::new();
        loop {
            let _ = write!(err, "{}", if text.is_empty() { "|: " } else { "|  " });
            let _ = err.flush();
            let mut line = String::new();
            let n = self.input.read_line(&mut line).map_err(|e| e.to_string())?;
            if n == 0 {
                if text.trim().is_empty() {
                    return Ok(Perceived::EndOfInput);
                }
                text.push('\n');
            }
            text.push_str(&line);
            if text.trim().is_empty() {
                text.clear();
                continue;
            }
            match sitlog_syntax::read_term(text.trim()) {
                Ok(clause) => {
                    let (t, _) = store.from_clause(&clause);
                    return Ok(deliver(store, ty, t));
                }
                Err(e) if e.incomplete && n > 0 => continue,
                Err(e) => {
                    let _ = writeln!(
                        err,
                        "syntax error: {} (type a term ending with `.`)",
                        e.message
                    );
                    text.clear();
                    if n == 0 {
                        return Ok(Perceived::EndOfInput);
                    }
                }
            }
        }
    }
}

/// Renders actions as text, like the original's test mode: `screen(M)` and
/// `say(M)` are shown, other declared basic actions are listed, and unknown
/// actions do nothing (as in the original).
pub struct TextActions<W: Write> {
    out: W,
    declared: Vec<Atom>,
}

impl<W: Write> TextActions<W> {
    pub fn new(out: W, declared: Vec<Atom>) -> Self {
        TextActions { out, declared }
    }
}

impl<W: Write> Actions for TextActions<W> {
    fn perform(&mut self, store: &mut Store, action: Term) -> Result<(), String> {
        let a = store.deref(action);
        let Some((name, arity)) = store.functor(a) else {
            return Ok(());
        };
        let arg = |i: usize| store.write(store.args(a)[i]);
        let line = match (name.as_str(), arity) {
            ("screen", 1) => format!("Golem prints on screen: {}", arg(0)),
            ("say", 1) => format!("Golem says: {}", arg(0)),
            _ if self.declared.contains(&name) => format!("Golem does: {}", store.writeq(a)),
            _ => return Ok(()),
        };
        let _ = writeln!(self.out, "{line}");
        Ok(())
    }

    /// A number has no functor: nothing to show.
    fn ignores_numbers(&self) -> bool {
        true
    }
}
