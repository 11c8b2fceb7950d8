//! How a run ends: its [`Outcome`], the [`RunError`] that stops it
//! (with the [`ErrorSite`] a reporter points at) and the [`RunWarning`]s
//! of what it did on, as the original does, that a user may not expect.

use super::situation::{DmIx, SitIx};
use crate::eval;
use crate::history::Item;
use crate::term::Term;
use crate::vars::Vars;

/// A run-time error: where it happened and what.
#[derive(Clone, Debug, PartialEq)]
pub struct RunError {
    pub message: String,
    pub dm: Option<String>,
    pub situation: Option<String>,
    /// 1-based arc number.
    pub arc: Option<usize>,
    pub location: Option<String>,
    /// Where in the program, for a reporter that shows the source
    /// (an `App`'s `render_error`); boxed to keep errors small.
    pub site: Option<Box<ErrorSite>>,
}

/// The running DM and situation of a [`RunError`], by index, and the
/// expression of L whose evaluation failed, when one did.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorSite {
    pub dm: DmIx,
    pub situation: SitIx,
    pub culprit: Option<eval::Culprit>,
    /// The error is the situation's in_arg's (E14 under
    /// `--deny-warnings`): a reporter points at the in_arg.
    pub in_arg: bool,
}

/// The text of a [`RunError`]: where, then what.
///
/// Its unbound variables are numbered in order of first appearance in the
/// whole text (`_G0`, `_G1`, ..; [`renumber_vars`]): each back end's store
/// numbers its variables apart (the interpreter's `_G25` is the compiled
/// task's `_G33`), so the store's numbers would make the same error read
/// differently in `sitlogc run` and a compiled task. A variable that occurs
/// twice keeps one name; our convention compares every `_G..` alike with
/// the original's.
impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&renumber_vars(&self.unnumbered_text()))
    }
}

impl RunError {
    /// The text as the parts hold it, variables numbered by the store.
    fn unnumbered_text(&self) -> String {
        use std::fmt::Write;
        let mut f = String::new();
        let mut place = Vec::new();
        if let Some(dm) = &self.dm {
            place.push(format!("DM `{dm}`"));
        }
        if let Some(s) = &self.situation {
            place.push(format!("situation `{s}`"));
        }
        if let Some(a) = self.arc {
            place.push(format!("arc {a}"));
        }
        if !place.is_empty() {
            let _ = write!(f, "in {}", place.join(", "));
            if let Some(loc) = &self.location {
                let _ = write!(f, " ({loc})");
            }
            f.push_str(": ");
        }
        f.push_str(&self.message);
        f
    }
}

/// `text` with every variable name `_G<n>` that the writer made renamed
/// `_G<k>`, `k` its order of first appearance. A name the writer made is
/// `_G` and digits, not preceded by a letter (any non-ASCII character
/// counts as one), digit, `_` or a quote and not followed by a letter,
/// digit or `_` (a quoted atom `'_G5'` and a name such as `x_G5` or `_G5a`
/// stay as they are).
pub fn renumber_vars(text: &str) -> String {
    renumber_vars_after("", text)
}

/// [`renumber_vars`] of `text` as if it followed `before`: the names that
/// occur in `before` are numbered first, in their order there (a rendered
/// diagnostic that writes the message before the place it names numbers
/// them as [`RunError`]'s text, which writes the place first).
pub fn renumber_vars_after(before: &str, text: &str) -> String {
    let mut seen: Vec<&str> = Vec::new();
    renumber_into(before, &mut seen);
    renumber_into(text, &mut seen)
}

fn renumber_into<'t>(text: &'t str, seen: &mut Vec<&'t str>) -> String {
    rename_vars(text, |digits| {
        Some(seen.iter().position(|&d| d == digits).unwrap_or_else(|| {
            seen.push(digits);
            seen.len() - 1
        }))
    })
}

/// `text` with each variable name `_G<n>` that the writer made (as
/// [`renumber_vars`] finds them) renamed by `name`, given the digits `n`:
/// `Some(k)` writes `_G<k>`, `None` writes `_G` (the number dropped). The
/// one scan of the names behind [`renumber_vars`], a test harness's
/// renaming of said text and its comparisons modulo variables.
pub fn rename_vars<'t>(text: &'t str, mut name: impl FnMut(&'t str) -> Option<usize>) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut last = 0;
    let mut i = 0;
    while i + 2 < b.len() {
        let starts = b[i] == b'_'
            && b[i + 1] == b'G'
            && b[i + 2].is_ascii_digit()
            && (i == 0
                || !(b[i - 1].is_ascii_alphanumeric()
                    || b[i - 1] >= 0x80
                    || matches!(b[i - 1], b'_' | b'\'' | b'"')));
        if !starts {
            i += 1;
            continue;
        }
        let mut j = i + 2;
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        if j < b.len() && (b[j].is_ascii_alphanumeric() || b[j] >= 0x80 || b[j] == b'_') {
            i = j;
            continue;
        }
        out.push_str(&text[last..i]);
        out.push_str("_G");
        if let Some(k) = name(&text[i + 2..j]) {
            out.push_str(&k.to_string());
        }
        last = j;
        i = j;
    }
    out.push_str(&text[last..]);
    out
}

impl std::error::Error for RunError {}

/// Something the run went on from as the original SitLog does, silently
/// there: an in_arg pattern that does not unify with the incoming pipe,
/// skipped (semantics D-8; the error of E14 under
/// `Options::skip_unmatched_in_arg` false), and a scripted input that
/// meets no expectation, read again (D-15; only where
/// `Perception::unmatched_is_news`). One per situation and DM,
/// the first time (a loop does not repeat it). Its text
/// ([`Display`](std::fmt::Display)) names every term with its variables
/// numbered in order of appearance (`_G0`, `_G1`, ..), so that a compiled
/// task and the interpreter, whose stores number them apart, print the
/// same line.
#[derive(Clone, Debug, PartialEq)]
pub struct RunWarning {
    pub message: String,
    /// The running DM's call term.
    pub dm: String,
    /// The situation's id.
    pub situation: String,
    /// `file:line:col` of the construct (the in_arg), else of the
    /// situation; `None` when the program keeps no places.
    pub location: Option<String>,
}

impl RunWarning {
    /// `op(name, _)` evaluated where `name` is neither a local nor a global
    /// variable (`Store::note_undefined`): the value was unbound and the
    /// run went on, as the original's. Said once per variable and
    /// operation, at no place: generated code evaluates it without the
    /// machine knowing the DM (check's W0219 gives the place).
    pub fn undefined_variable(op: sitlog_syntax::Atom, name: sitlog_syntax::Atom) -> RunWarning {
        RunWarning {
            message: format!(
                "`{op}` of `{name}`, which is neither a local nor a global variable: its value was unbound and the run went on, as the original SitLog's does (it prints `Error: Variable \"{name}\" is not defined.`); a misspelt name? (said once per variable)"
            ),
            dm: String::new(),
            situation: String::new(),
            location: None,
        }
    }
}

impl std::fmt::Display for RunWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.dm.is_empty() {
            return write!(f, "warning: {}", self.message);
        }
        write!(
            f,
            "warning: in DM `{}`, situation `{}`",
            self.dm, self.situation
        )?;
        if let Some(loc) = &self.location {
            write!(f, " ({loc})")?;
        }
        write!(f, ": {}", self.message)
    }
}

/// How a run ended.
#[derive(Debug)]
pub struct Outcome {
    /// `Ok` when the main DM reached a final situation.
    pub result: Result<(), RunError>,
    /// The history (nested as the original's), empty with `keep_history: false`.
    pub history: Vec<Item>,
    /// The final pipe value.
    pub out_arg: Term,
    pub globals: Vars,
    /// The final situation reached by the main DM, if any.
    pub final_situation: Option<Term>,
    /// Transitions made (history entries appended, kept or not).
    pub transitions: u64,
    /// The run was stopped by [`Options::stop`](super::Options::stop) (the result is then an error
    /// saying so).
    pub interrupted: bool,
    /// What the run went on from as the original does ([`RunWarning`]),
    /// in the order it happened; a runner prints them on stderr, never
    /// in the report.
    pub warnings: Vec<RunWarning>,
}

#[cfg(test)]
mod renumber_tests {
    use super::renumber_vars;

    #[test]
    fn variables_are_numbered_in_order_of_appearance() {
        assert_eq!(
            renumber_vars("in DM `f(_G33,_G7)`: in `_G7 is _G33+_G12`"),
            "in DM `f(_G0,_G1)`: in `_G1 is _G0+_G2`"
        );
    }

    #[test]
    fn names_the_writer_did_not_make_stay() {
        for s in ["'_G5'", "x_G5", "_G5a", "_G", "_Gx", "\"_G3\"", "a_G_1"] {
            assert_eq!(renumber_vars(s), s);
        }
        assert_eq!(renumber_vars("_G9"), "_G0");
        assert_eq!(
            super::renumber_vars_after("g(_G4)", "f(_G9,_G4)"),
            "f(_G1,_G0)"
        );
        assert_eq!(renumber_vars("(_G9)"), "(_G0)");
        assert_eq!(renumber_vars("é_G9 _G4 _G9é"), "é_G9 _G0 _G9é");
    }

    /// The map decides: numbers kept apart in a map the caller owns, or
    /// dropped.
    #[test]
    fn rename_vars_takes_the_map() {
        use super::rename_vars;
        let mut names = std::collections::HashMap::new();
        let mut by = |d: &str| {
            let next = names.len();
            Some(*names.entry(d.to_owned()).or_insert(next))
        };
        assert_eq!(rename_vars("a _G7 b _G3", &mut by), "a _G0 b _G1");
        assert_eq!(rename_vars("_G3 '_G7'", &mut by), "_G1 '_G7'");
        assert_eq!(
            rename_vars("f(_G12, _G4, x_G4)", |_| None),
            "f(_G, _G, x_G4)"
        );
    }
}
