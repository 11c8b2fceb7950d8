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

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
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
            write!(f, "in {}", place.join(", "))?;
            if let Some(loc) = &self.location {
                write!(f, " ({loc})")?;
            }
            write!(f, ": ")?;
        }
        f.write_str(&self.message)
    }
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
