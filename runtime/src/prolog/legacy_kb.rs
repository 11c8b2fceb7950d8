//! The legacy KB layer served natively: [`NativeKb`] says which of the
//! original's KB predicates the host serves; while the layer's sources are
//! prepared, each clause is kept or renamed, and the clauses that
//! call the host (or turn handles back into KB terms) are added at the end.

use super::translate::{write_atom, Prepared};
use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::Atom;
use std::collections::HashSet;
use std::sync::Arc;

/// A host answering the KB requests of the engine (see [`NativeKb`]).
pub type KbHost = Arc<dyn Fn(&str) -> String + Send + Sync>;

/// The legacy KB layer served natively (`sitlogc run --legacy --legacy-kb
/// native`): the original's KB predicates, which pass the whole KB as a
/// term, run on the host's KB instead, the KB being a handle `'$kb'(N)`.
///
/// In the sources marked as the legacy layer (`load_with`'s `layer`, and
/// the files they consult):
/// - the clauses of a query service `S/n+1` of `queries` (`S(Args.., KB,
///   Answer)`) and of an update `U/m+2` of `updates` (`U(Args.., KB,
///   NewKB)`) are replaced by calls of the host;
/// - a predicate of arity 1 whose clause opens a file named by an
///   `atomic_concat(Home, '/dir/file.ext', Path)` for reading (writing) is a
///   KB load (save) of `$SITLOG_HOME/dir/file.ext` (the original's
///   `open_kb/1`, `save_kb/1`, `open_preferences_kb/1`...); a KB file the
///   host cannot read (a format of its own) is loaded by the layer's clause
///   as written, and KB terms are then served by the layer's own clauses
///   for the rest of the run (`'$sitlog_kb_native'/1` fails for them);
/// - every other predicate gets its handles turned back into KB terms (the
///   host writes the KB) before its own clauses run, so code of the layer
///   that the host does not serve still works.
///
/// Requests (canonical text): `open(Path)`, `save(KB, Path)`,
/// `query(KB, Goal)`, `update(KB, Goal)`, `term(KB)`, `handle(Term)`; the
/// host answers with [`read_reply`](super::read_reply) of its answer's text (`'$ok'(T, _).`),
/// `'$fail'.` or `'$error'(E).`.
#[derive(Clone)]
pub struct NativeKb {
    pub host: KbHost,
    /// Query services: name and arity without the KB (answer included).
    pub queries: Vec<(String, usize)>,
    /// Updates: name and arity without the two KBs.
    pub updates: Vec<(String, usize)>,
}

/// What becomes of a clause of the natively served legacy layer.
pub(super) enum ClauseFate {
    Keep,
    Rename(Atom),
}

/// The legacy layer's predicates as [`NativeKb`] serves them.
pub(super) struct NativeState {
    served: HashSet<(Atom, usize)>,
    /// KB loads and saves found: predicate name, file name, `true` for a save.
    files: Vec<(Atom, Atom, bool)>,
    /// Predicates wrapped to turn handles into terms, in order met.
    wrapped: Vec<(Atom, usize)>,
    wrapped_set: HashSet<(Atom, usize)>,
    /// Served predicates the layer defines itself.
    defined_served: HashSet<(Atom, usize)>,
    queries: Vec<(String, usize)>,
    updates: Vec<(String, usize)>,
}

impl NativeState {
    pub(super) fn new(n: &NativeKb) -> NativeState {
        let mut served = HashSet::new();
        for (name, arity) in &n.queries {
            served.insert((Atom::intern(name), arity + 1));
        }
        for (name, arity) in &n.updates {
            served.insert((Atom::intern(name), arity + 2));
        }
        NativeState {
            served,
            files: Vec::new(),
            wrapped: Vec::new(),
            wrapped_set: HashSet::new(),
            defined_served: HashSet::new(),
            queries: n.queries.clone(),
            updates: n.updates.clone(),
        }
    }

    pub(super) fn clause(
        &mut self,
        store: &mut Store,
        key: (Atom, usize),
        body: Option<Term>,
    ) -> ClauseFate {
        if key.1 == 0 {
            return ClauseFate::Keep;
        }
        // A KB load or save keeps its clauses, renamed, for a KB file the
        // host cannot read (another format): they then run as written.
        if self.files.iter().any(|f| f.0 == key.0 && key.1 == 1) {
            return ClauseFate::Rename(legacy_name(key.0));
        }
        if self.served.contains(&key) {
            // Kept for calls the host cannot serve (arguments not ground).
            self.defined_served.insert(key);
            return ClauseFate::Rename(legacy_name(key.0));
        }
        if key.1 == 1 {
            if let Some((file, save)) = body.and_then(|b| kb_file_access(store, b)) {
                self.files.push((key.0, file, save));
                return ClauseFate::Rename(legacy_name(key.0));
            }
        }
        if self.wrapped_set.insert(key) {
            self.wrapped.push(key);
        }
        ClauseFate::Rename(legacy_name(key.0))
    }

    /// The clauses that serve the layer's predicates and wrap the others.
    pub(super) fn finish(self, out: &mut Vec<Prepared>) {
        let vars = |n: usize| -> Vec<String> { (0..n).map(|i| format!("V{i}")).collect() };
        // Each clause with its predicate and whether it may be asserted at
        // the predicate's first call (the wrappers: one a predicate of the
        // layer, see `engine::lazify`).
        let mut clauses: Vec<(String, (Atom, usize), bool)> = Vec::new();
        let name = |a: &str| {
            let mut s = String::new();
            write_atom(&mut s, Atom::intern(a));
            s
        };
        // With arguments that are not ground (the original's services then
        // enumerate), or a KB term the host cannot read (another format),
        // the layer's own clauses run on the KB term.
        let native = |p: &str, arity: usize| -> &'static str {
            if self.defined_served.contains(&(Atom::intern(p), arity)) {
                ", '$sitlog_kb_native'(KB)"
            } else {
                ""
            }
        };
        let fallback = |p: &str, all: &[String]| -> String {
            let key = (Atom::intern(p), all.len());
            if !self.defined_served.contains(&key) {
                return String::new();
            }
            let w: Vec<String> = (0..all.len()).map(|i| format!("W{i}")).collect();
            let mut legacy = String::new();
            write_atom(&mut legacy, legacy_name(key.0));
            format!(
                " ; '$sitlog_kb_terms'([{}], [{}]), {}({})",
                all.join(","),
                w.join(","),
                legacy,
                w.join(",")
            )
        };
        for (q, arity) in &self.queries {
            let v = vars(arity - 1);
            let all = [v.clone(), vec!["KB".into(), "A".into()]].concat();
            clauses.push((
                format!(
                    "{}({}) :- ( ground([{}]){} -> '$sitlog_kb_query'({}, [{}], KB, A){} )",
                    name(q),
                    all.join(","),
                    v.join(","),
                    native(q, all.len()),
                    name(q),
                    v.join(","),
                    fallback(q, &all)
                ),
                (Atom::intern(q), all.len()),
                false,
            ));
        }
        for (u, arity) in &self.updates {
            let v = vars(*arity);
            let all = [v.clone(), vec!["KB".into(), "New".into()]].concat();
            clauses.push((
                format!(
                    "{}({}) :- ( ground([{}]){} -> '$sitlog_kb_update'({}, [{}], KB, New){} )",
                    name(u),
                    all.join(","),
                    v.join(","),
                    native(u, all.len()),
                    name(u),
                    v.join(","),
                    fallback(u, &all)
                ),
                (Atom::intern(u), all.len()),
                false,
            ));
        }
        for (p, file, save) in &self.files {
            let mut legacy = String::new();
            write_atom(&mut legacy, legacy_name(*p));
            clauses.push((
                format!(
                    "{}(KB) :- getenv('SITLOG_HOME', H), atomic_concat(H, {}, P), \
                 catch({}(P, KB), error(kb_error(_), native_kb), {})",
                    name(p.as_str()),
                    name(file.as_str()),
                    if *save {
                        "'$sitlog_kb_save'"
                    } else {
                        "'$sitlog_kb_open'"
                    },
                    if *save {
                        format!("('$sitlog_kb_terms'([KB], [T]), {legacy}(T))")
                    } else {
                        format!("(bb_put('$sitlog_kb_off', true), {legacy}(KB))")
                    }
                ),
                (*p, 1),
                false,
            ));
        }
        for (p, arity) in &self.wrapped {
            let v = vars(*arity);
            let w: Vec<String> = (0..*arity).map(|i| format!("W{i}")).collect();
            let mut legacy = String::new();
            write_atom(&mut legacy, legacy_name(*p));
            if *arity == 0 {
                continue;
            }
            // The handles are looked for inline (no call per argument: a
            // call of the layer's own predicates, recursion included, costs
            // one inference more than the original's, not n + 2).
            let any_handle: Vec<String> = v
                .iter()
                .map(|x| format!("nonvar({x}), {x} = '$kb'(_)"))
                .collect();
            clauses.push((
                format!(
                    "{}({}) :- ( ( {} ) -> '$sitlog_kb_terms'([{}], [{}]), {}({}) ; {}({}) )",
                    name(p.as_str()),
                    v.join(","),
                    any_handle.join(" ; "),
                    v.join(","),
                    w.join(","),
                    legacy,
                    w.join(","),
                    legacy,
                    v.join(",")
                ),
                (*p, *arity),
                true,
            ));
        }
        for (text, key, lazy) in clauses {
            out.push(Prepared {
                text: format!("({text})"),
                directive: false,
                file: "<native KB layer>".into(),
                line: 0,
                col: 0,
                key: Some(key),
                lazy,
            });
        }
    }
}

fn legacy_name(a: Atom) -> Atom {
    Atom::intern(&format!("$legacy_{}", a.as_str()))
}

/// Whether `body` opens a KB file as the original's `open_kb/1` and
/// `save_kb/1` do: `open(_, read|write, _)` of a path made by
/// `atomic_concat(_, '/….ext', _)`. Gives the file name and whether it is a
/// save.
fn kb_file_access(store: &Store, body: Term) -> Option<(Atom, bool)> {
    let mut stack = vec![body];
    let mut file = None;
    let mut mode = None;
    while let Some(t) = stack.pop() {
        let t = store.deref(t);
        let Some((f, n)) = store.functor(t) else {
            continue;
        };
        let args = store.args(t).to_vec();
        match (f.as_str(), n) {
            ("atomic_concat", 3) => {
                if let Some(a) = store.atom_of(store.deref(args[1])) {
                    let name = a.as_str().rsplit('/').next().unwrap_or("");
                    if a.as_str().starts_with('/') && name.contains('.') {
                        file = Some(a);
                    }
                }
            }
            ("open", 3) => {
                mode = store
                    .atom_of(store.deref(args[1]))
                    .map(|a| a.as_str() == "write");
            }
            (",", 2) => stack.extend(args),
            _ => {}
        }
    }
    Some((file?, mode?))
}
