//! W0240: Prolog code of the application that reaches the operating system
//! (the trust model, issue 31): directives and clauses of the application's
//! Prolog files whose bodies call a predicate of
//! [`sitlog_runtime::trust::OS_PREDICATES`] (the shell, processes, sockets,
//! native code, `open/3,4` for writing, loading code at run time or from an
//! absolute or `$SITLOG_HOME` path), and those the engine's renaming does
//! not see (issue 38): module-qualified goals and closures of the system's
//! libraries (`call(os:shell, C)`, `files:delete_file`) and goals built by
//! name (`G =.. [shell, C]`). A syntactic scan of the clauses, like every
//! check it runs nothing; a run refuses these calls unless it is given
//! `--allow-os` (the operating system's sandbox holding where the
//! Prolog-level refusal does not see them).

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
            let clauses = program.prolog_clauses(file);
            for c in clauses.iter() {
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
                    let loc = Loc {
                        file,
                        span: t.span(call),
                    };
                    let message = match access {
                        Reach::Call(f, n, OsAccess::Open) => format!(
                            "{who} calls `{f}/{n}` to write a file: a run refuses writes outside the application unless given {ALLOW_OS}"
                        ),
                        Reach::Call(f, n, OsAccess::Consult) => format!(
                            "{who} calls `{f}/{n}`, which loads code: a run refuses files outside the application unless given {ALLOW_OS}"
                        ),
                        Reach::Call(f, n, access) => format!(
                            "{who} calls `{f}/{n}`, which {}: a run refuses it unless given {ALLOW_OS}",
                            access.describe()
                        ),
                        Reach::Qualified(m, f, what) => format!(
                            "{who} calls `{m}:{f}`, which {what}: a run refuses it unless given {ALLOW_OS} (the operating system's sandbox holds where the Prolog-level refusal does not see a module-qualified call)"
                        ),
                        Reach::ByName(f, what) => format!(
                            "{who} builds a goal named `{f}`, which {what}: a run refuses it unless given {ALLOW_OS} (the operating system's sandbox holds where the Prolog-level refusal does not see a goal built by name)"
                        ),
                    };
                    self.diags.push(
                        Diagnostic::warning(codes::OS_ACCESS, loc, message)
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

/// How a goal reaches the operating system.
enum Reach {
    /// A call of a predicate of the table, by name and arity.
    Call(Atom, usize, OsAccess),
    /// `Module:Name` (a goal or a closure) of a system library's module,
    /// and what it reaches in words.
    Qualified(Atom, Atom, &'static str),
    /// `G =.. [Name|Args]` naming a predicate of the table, in words.
    ByName(Atom, &'static str),
}

/// The libraries whose predicates reach the operating system, by module,
/// and those of `files` that change the file system (not in the engine's
/// table: the sandbox alone holds them).
const SYSTEM_MODULES: &[&str] = &[
    "os",
    "process",
    "sockets",
    "ffi",
    "tls",
    "http_open",
    "http_server",
];
const FILES_WRITING: &[&str] = &[
    "delete_file",
    "rename_file",
    "make_directory",
    "make_directory_path",
    "delete_directory",
];

/// What `name` reaches if it names a predicate of the table (any arity).
fn named_access(name: &str) -> Option<OsAccess> {
    sitlog_runtime::trust::OS_PREDICATES
        .iter()
        .find(|&&(n, _, _)| n == name)
        .map(|&(_, _, k)| k)
}

/// `Module:Goal` of a system library (see [`SYSTEM_MODULES`]): the module,
/// the goal's name and what it reaches.
fn qualified(t: &Terms, m: TermId, goal: TermId) -> Option<(Atom, Atom, &'static str)> {
    let module = t.atom(m)?;
    let name = t.atom(goal).or_else(|| t.functor(goal).map(|(f, _)| f))?;
    let what = if module.as_str() == "files" {
        if !FILES_WRITING.contains(&name.as_str()) {
            return None;
        }
        "deletes, renames or creates files"
    } else if SYSTEM_MODULES.contains(&module.as_str()) {
        named_access(name.as_str())
            .filter(|a| a.always_refused())
            .map_or("reaches the operating system", OsAccess::describe)
    } else {
        return None;
    };
    Some((module, name, what))
}

/// The calls in `goal` that reach the operating system. A directive's
/// `consult/1` of a relative name is the application's own (the loader
/// reads it); `open/3,4` in mode `read` only reads.
fn os_calls(t: &Terms, goal: TermId, directive: bool) -> Vec<(TermId, Reach)> {
    let mut out = Vec::new();
    let mut stack = vec![goal];
    let colon = Atom::intern(":");
    let univ = Atom::intern("=..");
    while let Some(id) = stack.pop() {
        let Some((f, n)) = t.functor(id) else {
            continue;
        };
        let args = t.args(id);
        if f == colon && n == 2 {
            if let Some((m, name, what)) = qualified(t, args[0], args[1]) {
                out.push((id, Reach::Qualified(m, name, what)));
                // The goal's arguments may hold more calls; not the goal.
                stack.extend(t.args(args[1]).iter().rev().copied());
                continue;
            }
        }
        if f == univ && n == 2 {
            if let Some(name) = list_head_atom(t, args[1]) {
                if let Some(access) = named_access(name.as_str()).filter(|a| a.always_refused()) {
                    out.push((id, Reach::ByName(name, access.describe())));
                }
            }
        }
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
            out.push((id, Reach::Call(f, n, access)));
        }
    }
    out
}

/// The first element of `list` when it is an atom (`[shell, C]`).
fn list_head_atom(t: &Terms, list: TermId) -> Option<Atom> {
    match t.functor(list) {
        Some((f, 2)) if f.as_str() == "." => t.atom(t.args(list)[0]),
        _ => None,
    }
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
