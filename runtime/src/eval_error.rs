//! Why an evaluation of L failed: [`EvalError`], and the [`Culprit`] it
//! blames. Below the evaluator and the built-ins, which both raise it;
//! re-exported as `sitlog_runtime::eval::{EvalError, Culprit}`.

use sitlog_syntax::Atom;

/// Why an evaluation failed.
#[derive(Clone, Debug, PartialEq)]
pub struct EvalError {
    pub message: String,
    /// The construct of L whose evaluation failed (the innermost one), so
    /// that a reporter can point at it in the source.
    pub culprit: Option<Culprit>,
}

/// The shape of a failing expression as written: its principal functor
/// and that of its first argument (`apply(pour(D), [D])` is `apply/2`
/// with `pour/1`; `get(count, N)` is `get/2` with `count/0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Culprit {
    pub name: Atom,
    pub arity: usize,
    pub inner: Option<(Atom, usize)>,
}

impl EvalError {
    pub fn new(message: impl Into<String>) -> EvalError {
        EvalError {
            message: message.into(),
            culprit: None,
        }
    }
}

impl std::fmt::Display for EvalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// `t` as written in an error message, cut at 200 characters.
pub(crate) fn shown(store: &crate::store::Store, t: crate::term::Term) -> String {
    let s = store.writeq(t);
    if s.chars().count() > 200 {
        format!("{}…", s.chars().take(199).collect::<String>())
    } else {
        s
    }
}
