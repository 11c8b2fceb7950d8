//! The IR as a whole program for the runtime's runner
//! ([`sitlog_runtime::app::App`]): initial state, basic actions, recovery
//! protocols, and run-time errors rendered at the failing expression.

use crate::diag::{Diagnostic, Loc};
use crate::ir::{ExprSite, Ir};
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
    let arc = error.arc.map(|a| a - 1);
    let found = site.culprit.and_then(|c| {
        let exact = |e: &&ExprSite| e.functor == (c.name, c.arity) && e.inner == c.inner;
        let by_functor = |e: &&ExprSite| e.functor == (c.name, c.arity);
        let here = || src.exprs.iter().filter(|e| e.arc == arc);
        here()
            .find(exact)
            .or_else(|| here().find(by_functor))
            .or_else(|| src.exprs.iter().find(exact))
    });
    let in_arg = src.in_arg.filter(|_| site.in_arg);
    let (span, label) = match (found, arc.and_then(|a| src.arcs.get(a))) {
        _ if in_arg.is_some() => (
            in_arg.unwrap_or(src.span),
            "the pipe does not match this in_arg",
        ),
        (Some(e), _) => (e.span, "failed here"),
        (None, Some(&span)) => (span, "in this arc"),
        (None, None) => (src.span, "in this situation"),
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
    let message = if place.is_empty() {
        error.message.clone()
    } else {
        format!("{} (in {})", error.message, place.join(", "))
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
