//! W0240: Prolog code of the application that reaches the operating system
//! (the trust model, issue 31): directives and clauses of the application's
//! Prolog files whose bodies call a predicate of
//! [`sitlog_runtime::trust::OS_PREDICATES`] (the shell, processes, sockets,
//! native code, `open/3,4` for writing, loading code at run time or from an
//! absolute or `$SITLOG_HOME` path). A syntactic scan of the clauses, like
//! every check it runs nothing; a run refuses these calls unless it is
//! given `--allow-os`.

use super::*;
use crate::diag::Loc;
use sitlog_runtime::trust::{os_access, OsAccess, ALLOW_OS};
use std::path::Path;

impl Checker<'_> {
    /// Warns at each call that reaches the operating system in the
    /// application's Prolog files.
    pub(super) fn os_access(&mut self) {
        let program = self.program;
        let neck = Atom::intern(":-");
        for &file in &program.prolog_files {
            let (clauses, _) = sitlog_syntax::read_clauses(&program.sources.get(file).text);
            for c in &clauses {
                let t = &c.terms;
                let (who, body, directive) = if let Some(&[goal]) = t.compound(c.root, neck, 1) {
                    ("this directive".to_owned(), goal, true)
                } else if let Some(&[head, body]) = t.compound(c.root, neck, 2) {
                    let who = match t.functor(head) {
                        Some((f, n)) => format!("`{f}/{n}`"),
                        None => "this clause".to_owned(),
                    };
                    (who, body, false)
                } else {
                    continue;
                };
                for (call, access) in os_calls(t, body, directive) {
                    let (f, n) = t.functor(call).expect("a compound");
                    let loc = Loc {
                        file,
                        span: t.span(call),
                    };
                    self.diags.push(
                        Diagnostic::warning(
                            codes::OS_ACCESS,
                            loc,
                            match access {
                                OsAccess::Open => format!(
                                    "{who} calls `{f}/{n}` to write a file: a run refuses writes outside the application unless given {ALLOW_OS}"
                                ),
                                OsAccess::Consult => format!(
                                    "{who} calls `{f}/{n}`, which loads code: a run refuses files outside the application unless given {ALLOW_OS}"
                                ),
                                _ => format!(
                                    "{who} calls `{f}/{n}`, which {}: a run refuses it unless given {ALLOW_OS}",
                                    access.describe()
                                ),
                            },
                        )
                        .with_label("reaches the operating system")
                        .with_help(format!(
                            "if the application needs it, run with {ALLOW_OS} (see \"Trust model\" in docs/guide/reliability.md)"
                        )),
                    );
                }
            }
        }
    }
}

/// The calls in `goal` that reach the operating system. A directive's
/// `consult/1` of a relative name is the application's own (the loader
/// reads it); `open/3,4` in mode `read` only reads.
fn os_calls(t: &Terms, goal: TermId, directive: bool) -> Vec<(TermId, OsAccess)> {
    let mut out = Vec::new();
    let mut stack = vec![goal];
    while let Some(id) = stack.pop() {
        let Some((f, n)) = t.functor(id) else {
            continue;
        };
        let args = t.args(id);
        stack.extend(args.iter().rev().copied());
        let Some(access) = os_access(f.as_str(), n) else {
            continue;
        };
        let reported = match access {
            OsAccess::Open => t.atom(args[1]).is_none_or(|m| m.as_str() != "read"),
            OsAccess::Consult if directive => {
                let names = list_atoms(t, args[0]);
                names.is_empty()
                    || names
                        .iter()
                        .any(|n| n.starts_with('$') || Path::new(n).is_absolute())
            }
            _ => true,
        };
        if reported {
            out.push((id, access));
        }
    }
    out
}

/// The atoms of `t` (one atom, or a list of atoms).
fn list_atoms(t: &Terms, mut item: TermId) -> Vec<String> {
    let mut out = Vec::new();
    loop {
        if let Some(a) = t.atom(item) {
            if a.as_str() != "[]" {
                out.push(a.as_str().to_owned());
            }
            return out;
        }
        match t.functor(item) {
            Some((f, 2)) if f.as_str() == "." => {
                if let Some(a) = t.atom(t.args(item)[0]) {
                    out.push(a.as_str().to_owned());
                }
                item = t.args(item)[1];
            }
            _ => return out,
        }
    }
}
