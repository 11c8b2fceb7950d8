//! The trust model in the engine (issue 31; the table and [`Trust`] are
//! [`crate::trust`]'s): the application's calls of the predicates that
//! reach the operating system are renamed by the loader to guards
//! ([`guard_name`], written out by [`guards`] with `permissions.pl`) that
//! refuse them unless the run was given `--allow-os`; the host answers the
//! guards' question "is this file inside the application or its KB?"
//! ([`inside_reply`]); and a refusal comes back as a message naming the
//! culprit and the flag ([`refusal`]). Invariant: no application code runs
//! before [`super::PrologFunctions::start`], which sets the permissions first.

use crate::trust::{os_access, OsAccess, Trust, OS_PREDICATES};
use scryer_prolog::Term as PTerm;
use sitlog_syntax::Atom;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The guards' common part (`permissions.pl`).
const PERMISSIONS_PL: &str = include_str!("permissions.pl");

/// The guard the loader renames a call of `name/arity` to, if the
/// predicate reaches the operating system.
pub(super) fn guard_name(name: Atom, arity: usize) -> Option<Atom> {
    os_access(name.as_str(), arity).map(|_| Atom::intern(&format!("$sitlog_os_{}", name.as_str())))
}

/// The text consulted into the engine before the application: the
/// common part and one guard per predicate of the table.
pub(super) fn guards() -> String {
    let mut out = String::from(PERMISSIONS_PL);
    out.push('\n');
    for &(name, arity, access) in OS_PREDICATES {
        let args: Vec<String> = (1..=arity).map(|i| format!("A{i}")).collect();
        let args = args.join(", ");
        let mut guard = String::new();
        sitlog_syntax::write::write_atom(
            &mut guard,
            Atom::intern(&format!("$sitlog_os_{name}")),
            true,
        );
        let mut callee = String::new();
        sitlog_syntax::write::write_atom(&mut callee, Atom::intern(name), true);
        let check = match access {
            OsAccess::Open => "'$sitlog_permit_open'(A1, A2)".to_owned(),
            OsAccess::Consult => "'$sitlog_permit_load'(A1)".to_owned(),
            _ => format!("'$sitlog_permit'({callee}/{arity})"),
        };
        let _ = writeln!(out, "{guard}({args}) :- {check}, {callee}({args}).");
    }
    out
}

/// The host's answer to a guard's `P<file>` request: `yes.` when `file`
/// lies inside one of `roots`.
pub(super) fn inside_reply(file: &str, roots: &[PathBuf]) -> String {
    if Trust::inside(Path::new(file), roots) {
        "yes.\n".to_owned()
    } else {
        "no.\n".to_owned()
    }
}

/// The message of a guard's refusal (`error(permission_error(Action,
/// sitlog_trust, Culprit), _)`), if `error` is one.
pub(super) fn refusal(error: &PTerm, show: impl Fn(&PTerm) -> String) -> Option<String> {
    let PTerm::Compound(f, a) = error else {
        return None;
    };
    if f != "error" || a.len() != 2 {
        return None;
    }
    let PTerm::Compound(p, pa) = &a[0] else {
        return None;
    };
    if p != "permission_error" || pa.len() != 3 {
        return None;
    }
    match &pa[1] {
        PTerm::Atom(t) if t == "sitlog_trust" => {}
        _ => return None,
    }
    let flag = crate::trust::ALLOW_OS;
    let culprit = show(&pa[2]);
    let what = match &pa[0] {
        PTerm::Atom(a) if a == "write" => {
            format!("writing `{culprit}` (outside the application)")
        }
        PTerm::Atom(a) if a == "consult" => {
            format!("loading `{culprit}` (outside the application)")
        }
        _ => {
            let how = match &pa[2] {
                PTerm::Compound(s, na) if s == "/" && na.len() == 2 => match (&na[0], &na[1]) {
                    (PTerm::Atom(n), PTerm::Integer(k)) => k
                        .to_string()
                        .parse::<usize>()
                        .ok()
                        .and_then(|k| os_access(n, k)),
                    _ => None,
                },
                _ => None,
            };
            match how {
                Some(access) => format!("calling `{culprit}` ({})", access.describe()),
                None => format!("calling `{culprit}`"),
            }
        }
    };
    Some(format!(
        "{what} is refused: the operating system is off for application code unless the run is given {flag}"
    ))
}

/// The directories code may write into and load from: those of the
/// application's Prolog files, and `trust`'s.
pub(super) fn roots(source_dirs: &[PathBuf], trust: &Trust) -> Vec<PathBuf> {
    let mut roots = source_dirs.to_vec();
    roots.extend(trust.roots.iter().cloned());
    roots
}
