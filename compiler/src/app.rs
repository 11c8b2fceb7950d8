//! The IR as a whole program for the runtime's runner
//! ([`sitlog_runtime::app::App`]): initial state, basic actions, recovery
//! protocols, and run-time errors rendered at the failing expression.

use crate::diag::{Diagnostic, Loc};
use crate::ir::Ir;
use sitlog_runtime::machine::places::{blame, Blame, Written};
use sitlog_runtime::machine::RunError;
use sitlog_runtime::{app::App, Atom, Store, Vars};

impl App for Ir {
    fn initial_state(&self) -> (Store, Vars) {
        Ir::initial_state(self)
    }
    fn basic_actions(&self) -> Vec<Atom> {
        self.basic_actions.clone()
    }
    fn recovery(&self) -> Vec<(Atom, Atom)> {
        self.recovery.clone()
    }
    fn render_error(&self, error: &RunError, color: bool) -> Option<String> {
        let d = run_error_diagnostic(self, error)?;
        Some(crate::diag::render_human(&d, &self.sources, color))
    }
    fn error_location(&self, error: &RunError) -> Option<String> {
        let d = run_error_diagnostic(self, error)?;
        let file = self.sources.get(d.loc.file);
        let pos = file.line_col(d.loc.span.start);
        Some(format!("{}:{}:{}", file.name, pos.line, pos.column))
    }
    fn names(&self) -> Vec<(String, Vec<String>)> {
        Ir::names(self)
    }
}

impl Ir {
    /// Each DM's name with the names of its situations (functors of the
    /// ids that are not variables).
    pub fn names(&self) -> Vec<(String, Vec<String>)> {
        self.dms
            .iter()
            .map(|dm| {
                let situations = dm
                    .situations
                    .iter()
                    .filter_map(|s| s.id_functor.map(|(name, _)| name.as_str().to_owned()))
                    .collect();
                (dm.name.as_str().to_owned(), situations)
            })
            .collect()
    }
}

/// A run-time error as a diagnostic at the failing expression: the
/// construct of L the evaluator blamed, looked up among those written in
/// the arc (or the other attributes) that failed; else the arc, else the
/// situation. `None` without a situation (e.g. an unknown main DM).
pub fn run_error_diagnostic(ir: &Ir, error: &RunError) -> Option<Diagnostic> {
    let site = error.site.as_deref()?;
    let src = &ir
        .dms
        .get(site.dm as usize)?
        .situations
        .get(site.situation as usize)?
        .source;
    let written = src.exprs.iter().map(|e| Written {
        arc: e.arc,
        functor: (e.functor.0.as_str(), e.functor.1),
        inner: e.inner.map(|(n, a)| (n.as_str(), a)),
    });
    // The look-up a compiled program makes on its places text too.
    let (span, label) = match blame(error, written, src.arcs.len(), src.in_arg.is_some()) {
        Blame::InArg => (
            src.in_arg.unwrap_or(src.span),
            "the pipe does not match this in_arg",
        ),
        Blame::Written(i) => (src.exprs[i].span, "failed here"),
        Blame::Arc(a) => (src.arcs[a], "in this arc"),
        Blame::Situation => (src.span, "in this situation"),
    };
    let mut place = Vec::new();
    if let Some(dm) = &error.dm {
        place.push(format!("DM `{dm}`"));
    }
    if let Some(s) = &error.situation {
        place.push(format!("situation `{s}`"));
    }
    if let Some(a) = error.arc {
        place.push(format!("arc {a}"));
    }
    // Variables numbered as `RunError`'s text numbers them (the place
    // first, then the message): the same in every back end.
    let place = place.join(", ");
    let text = sitlog_runtime::machine::renumber_vars_after(&place, &error.message);
    let message = if place.is_empty() {
        text
    } else {
        format!(
            "{text} (in {})",
            sitlog_runtime::machine::renumber_vars(&place)
        )
    };
    Some(
        Diagnostic::error(
            "",
            Loc {
                file: src.file,
                span,
            },
            message,
        )
        .with_label(label),
    )
}
