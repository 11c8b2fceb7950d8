//! Reading the application's Prolog sources into clauses for the engine:
//! [`PrologSource`], [`PrologLoadError`]s with file:line:col (a clause that
//! does not read is skipped, as SWI-Prolog's consult skips it), and `consult/1` / `ensure_loaded/1` directives
//! resolved (an embedded source first, then `$SITLOG_HOME/...` and paths
//! relative to the consulting file, `.pl` added where needed); for the
//! `--legacy` profile, SWI-Prolog's rule that a file defining a predicate
//! again replaces what an earlier file defined ([`Redefinitions`]).

use super::legacy_kb::{ClauseFate, NativeState};
use super::translate::{Prepared, Writer};
use crate::paths::normalize;
use crate::plain::PlainScan;
use crate::store::Store;
use crate::term::{Term, Value};
use sitlog_syntax::{atoms, read_prolog_clauses, Atom};
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

/// One Prolog source file.
#[derive(Clone, Debug)]
pub struct PrologSource {
    /// Name used in messages (`file:line:col`).
    pub name: String,
    pub text: String,
    /// Directory relative to which `consult/1` directives are resolved
    /// (`None` for embedded sources: such directives are then errors).
    pub dir: Option<PathBuf>,
    /// The clauses of `text` already read by [`read_prolog_clauses`] (the
    /// checker's loader reads the application's files so): the load uses
    /// them instead of reading `text` again. `None`: read at load.
    pub clauses: Option<std::sync::Arc<Vec<sitlog_syntax::Clause>>>,
}

impl PrologSource {
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> PrologSource {
        PrologSource {
            name: name.into(),
            text: text.into(),
            dir: None,
            clauses: None,
        }
    }
    /// Reads `path`; text that is not UTF-8 is an `InvalidData` error naming
    /// the file, line and column of the first bad byte.
    pub fn from_path(path: &Path) -> std::io::Result<PrologSource> {
        let name = path.display().to_string();
        let bytes = sitlog_syntax::read_file(path)?;
        let text = sitlog_syntax::decode(&bytes)
            .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e.in_file(&name)))?
            .to_owned();
        Ok(PrologSource {
            name,
            text,
            dir: path.parent().map(Path::to_path_buf),
            clauses: None,
        })
    }
}

/// A problem while loading the Prolog sources: `file:line:col: message`.
#[derive(Clone, Debug, PartialEq)]
pub struct PrologLoadError {
    pub file: String,
    pub line: usize,
    pub col: usize,
    pub message: String,
}

impl std::fmt::Display for PrologLoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // An error of the engine itself has no place in the application.
        if self.line == 0 && self.file.starts_with('<') {
            return f.write_str(&self.message);
        }
        write!(
            f,
            "{}:{}:{}: {}",
            self.file, self.line, self.col, self.message
        )
    }
}

fn neck() -> Atom {
    Atom::intern(":-")
}

/// 1-based line and column (in characters) of byte offset `at` of `text`.
/// Line and column (in characters, from 1) of byte offsets of one text,
/// asked in increasing order (a file's clauses): each asks only for the
/// text since the last, so a file's positions cost time linear in it (a
/// scan from the start for each clause was quadratic: 6 % of a small
/// `--legacy` run's CPU on the original's 1,720 clauses).
pub(super) struct LineCursor {
    offset: usize,
    line: usize,
    line_start: usize,
}

impl LineCursor {
    pub(super) fn new() -> LineCursor {
        LineCursor {
            offset: 0,
            line: 1,
            line_start: 0,
        }
    }

    /// The position of byte `at` of `text` (the same text at each call).
    pub(super) fn line_col(&mut self, text: &str, at: usize) -> (usize, usize) {
        let mut at = at.min(text.len());
        while at > 0 && !text.is_char_boundary(at) {
            at -= 1;
        }
        if at < self.offset {
            *self = LineCursor::new();
        }
        for (i, _) in text[self.offset..at].match_indices('\n') {
            self.line += 1;
            self.line_start = self.offset + i + 1;
        }
        self.offset = at;
        (self.line, text[self.line_start..at].chars().count() + 1)
    }
}

/// Where [`prepare`] puts what it reads.
pub(super) struct Prep<'a> {
    pub(super) out: &'a mut Vec<Prepared>,
    pub(super) defined: &'a mut HashSet<(Atom, usize)>,
    pub(super) errors: &'a mut Vec<PrologLoadError>,
    pub(super) seen: &'a mut HashSet<PathBuf>,
    /// `consult/1` directives naming, by an absolute or `$SITLOG_HOME`
    /// path, a file outside the directories of `embedded` (refused at start
    /// without `--allow-os`; relative names are the application's own).
    pub(super) outside: &'a mut Vec<(PathBuf, PrologLoadError)>,
    /// Every source given: a file they consult is taken from them first
    /// (a compiled task embeds what its sources consult).
    pub(super) embedded: &'a [PrologSource],
    /// Set while reading the legacy KB layer served natively (and the
    /// application's files after it, for `kb_reach`'s analysis:
    /// `NativeState::in_layer` says which).
    pub(super) native: Option<&'a mut NativeState>,
    /// Set for the `--legacy` profile: SWI-Prolog's redefinition rule.
    pub(super) redefine: Option<&'a mut Redefinitions>,
    /// Set when a clause or directive names one of the calls that change
    /// or look at clauses as data (`Writer::touching_atom`).
    pub(super) touching: &'a mut bool,
    /// The plain functions' native forms being read (`plain`), outside
    /// the legacy profile.
    pub(super) plain: Option<&'a mut PlainScan>,
}

/// SWI-Prolog's `consult/1` rule, which the original's code relies on: the
/// clauses a file gives for a predicate replace those an earlier file gave
/// (SWI warns "Redefined static procedure"; dynamic ones too). Clauses of
/// one file are never dropped, whatever comes between them. (SWI's
/// exception, `multifile` predicates, does not arise: the engine refuses
/// the directive, and no file of the original's tree gives it.)
#[derive(Default)]
pub(super) struct Redefinitions {
    /// Each predicate's file and the indices (in `Prep::out`) of its clauses.
    owner: HashMap<(Atom, usize), (String, Vec<usize>)>,
    /// Indices of the clauses replaced by a later file.
    dropped: HashSet<usize>,
}

impl Redefinitions {
    fn clause(&mut self, key: (Atom, usize), file: &str, index: usize) {
        let entry = self
            .owner
            .entry(key)
            .or_insert_with(|| (file.to_owned(), Vec::new()));
        if entry.0 != file {
            self.dropped.extend(entry.1.drain(..));
            entry.0 = file.to_owned();
        }
        entry.1.push(index);
    }

    /// The indices of the clauses replaced by a later file so far.
    pub(super) fn dropped(&self) -> &HashSet<usize> {
        &self.dropped
    }

    /// `prepared` without the clauses replaced by a later file.
    pub(super) fn apply(&self, prepared: &mut Vec<Prepared>) {
        if self.dropped.is_empty() {
            return;
        }
        let mut i = 0;
        prepared.retain(|_| {
            i += 1;
            !self.dropped.contains(&(i - 1))
        });
    }
}

/// Prepares the clauses of `source` (recursively for consulted files).
/// The error of a clause nested `depth` levels deep, deeper than the
/// engine takes.
fn too_deep(depth: usize) -> String {
    format!(
        "this clause nests {depth} levels deep (a list counts a level per element); the Prolog engine takes at most {} (deeper, its reader would overflow its stack)",
        crate::functions::PROLOG_MAX_DEPTH
    )
}

pub(super) fn prepare(source: &PrologSource, cx: &mut Prep<'_>, depth: usize) {
    if !cx.seen.insert(normalize(Path::new(&source.name))) {
        return;
    }
    // A clause that does not read is skipped and the rest loaded, as
    // SWI-Prolog's consult does for the original (`sitlogc check` warns of
    // it, with its place).
    let read;
    let clauses: &[sitlog_syntax::Clause] = match &source.clauses {
        Some(clauses) => clauses,
        None => {
            read = read_prolog_clauses(&source.text).0;
            &read
        }
    };
    let mut positions = LineCursor::new();
    for clause in clauses {
        let (line, col) = positions.line_col(&source.text, clause.span.start as usize);
        let mut store = Store::new();
        let (t, _) = store.from_clause(clause);
        let err = |message: String| PrologLoadError {
            file: source.name.clone(),
            line,
            col,
            message,
        };
        // Directives.
        if let Some(args) = store.compound_args(t, neck(), 1) {
            let goal = args[0];
            if let Some(files) = consulted_files(&store, goal) {
                if depth > 32 {
                    cx.errors.push(err("consult/1 nested too deeply".into()));
                    continue;
                }
                for f in files {
                    // A file given with the sources (a compiled task embeds
                    // what its sources consult) is taken from them.
                    if let Some(s) = embedded_source(&f, source, cx.embedded) {
                        prepare(s, cx, depth + 1);
                        continue;
                    }
                    match resolve(&f, source.dir.as_deref()) {
                        // A relative name is part of the application (the
                        // checker reads it, a compiled task embeds it),
                        // unless a symbolic link takes it out (resolved
                        // before the test, issue 38).
                        Some(path)
                            if (f.starts_with('$')
                                || Path::new(&f).is_absolute()
                                || linked_out(&path, source.dir.as_deref()))
                                && !inside_sources(&path, cx.embedded) =>
                        {
                            cx.outside.push((
                                path.clone(),
                                err(format!(
                                    "consulting `{}` (outside the application) is refused: the operating system is off for application code unless the run is given {}",
                                    path.display(),
                                    crate::trust::ALLOW_OS
                                )),
                            ));
                            match PrologSource::from_path(&path) {
                                Ok(s) => prepare(&s, cx, depth + 1),
                                Err(e) => cx.errors.push(err(format!("cannot consult `{f}`: {e}"))),
                            }
                        }
                        Some(path) => match PrologSource::from_path(&path) {
                            Ok(s) => prepare(&s, cx, depth + 1),
                            Err(e) => cx.errors.push(err(format!("cannot consult `{f}`: {e}"))),
                        },
                        None => cx
                            .errors
                            .push(err(format!("cannot consult `{f}`: no such file"))),
                    }
                }
                continue;
            }
            let mut w = Writer::new(&store, true);
            w.touch = cx.redefine.is_some();
            w.term(goal);
            if w.too_deep() {
                cx.errors.push(err(too_deep(w.deepest)));
                continue;
            }
            if let Some(native) = cx.native.as_deref_mut() {
                native.directive(&store, goal);
            }
            if let Some(plain) = cx.plain.as_deref_mut() {
                plain.directive(&store, goal);
            }
            *cx.touching |= w.touching_atom;
            cx.out.push(Prepared {
                text: w.out,
                directive: true,
                file: source.name.clone(),
                line,
                col,
                key: None,
                lazy: false,
            });
            continue;
        }
        // Clauses.
        let (head, body) = match store.compound_args(t, neck(), 2) {
            Some(a) => (a[0], Some(a[1])),
            None => (t, None),
        };
        let key = match store.functor(head) {
            Some(key) => key,
            None => {
                cx.errors.push(err(format!(
                    "`{}` is not a clause head",
                    store.writeq(head)
                )));
                continue;
            }
        };
        cx.defined.insert(key);
        if let Some(plain) = cx.plain.as_deref_mut() {
            plain.clause(&store, key, head, body);
        }
        let mut t = t;
        // Under the native KB layer, the clause as it is if its predicate
        // is wrapped (its calls of itself going to the layer's clauses).
        let mut alt = None;
        if let Some(native) = cx.native.as_deref_mut() {
            match native.clause(&mut store, key, head, body) {
                ClauseFate::Keep => alt = native.direct_recursion(&mut store, key, head, body),
                ClauseFate::Rename(new) => {
                    let args = store.args(head).to_vec();
                    let h = store.compound(new, &args);
                    t = match body {
                        Some(b) => store.compound(neck(), &[h, b]),
                        None => h,
                    };
                }
            }
        }
        if let Some(r) = cx.redefine.as_deref_mut() {
            r.clause(key, &source.name, cx.out.len());
        }
        let mut w = Writer::new(&store, true);
        w.touch = cx.redefine.is_some();
        match store.compound_args(t, neck(), 2) {
            Some(a) => {
                w.out.push_str("':-'(");
                w.head(a[0]);
                w.out.push(',');
                w.term(a[1]);
                w.out.push(')');
            }
            None => w.head(t),
        }
        if w.too_deep() {
            cx.errors.push(err(too_deep(w.deepest)));
            continue;
        }
        *cx.touching |= w.touching_atom;
        if let (Some(alt), Some(native)) = (alt, cx.native.as_deref_mut()) {
            let mut a = Writer::new(&store, true);
            a.touch = cx.redefine.is_some();
            if let Some(x) = store.compound_args(alt, neck(), 2) {
                a.out.push_str("':-'(");
                a.head(x[0]);
                a.out.push(',');
                a.term(x[1]);
                a.out.push(')');
                if !a.too_deep() {
                    native.alt(w.out.clone(), a.out);
                }
            }
        }
        // The predicate as asserted (renamed by the native KB layer).
        let head = store.compound_args(t, neck(), 2).map_or(t, |a| a[0]);
        let key = store.functor(head);
        cx.out.push(Prepared {
            text: w.out,
            directive: false,
            file: source.name.clone(),
            line,
            col,
            key,
            lazy: cx.redefine.is_some() && body.is_none_or(|b| assertable(&store, b)),
        });
    }
}

/// Whether the engine asserts a clause with this body without an error:
/// no goal of its control structure (conjunctions, disjunctions,
/// if-then-else, negation) is a number. A clause of the legacy layer that
/// is not stays eager, so that the engine's refusal is a load error at its
/// place, as without lazy loading.
fn assertable(store: &Store, body: Term) -> bool {
    let mut stack = vec![body];
    while let Some(g) = stack.pop() {
        match store.value(store.deref(g)) {
            Value::Int(_) | Value::BigInt(_) | Value::Float(_) => return false,
            Value::Compound(f, a)
                if matches!(
                    (f.as_str(), a.len()),
                    (",", 2) | (";", 2) | ("->", 2) | ("*->", 2) | ("|", 2) | ("\\+", 1)
                ) =>
            {
                stack.extend(a.iter().copied());
            }
            _ => {}
        }
    }
    true
}

/// Whether `path`, named relative to `dir`, is a symbolic link (or lies
/// under one) that takes it out of `dir`.
fn linked_out(path: &Path, dir: Option<&Path>) -> bool {
    let Some(dir) = dir else {
        return false;
    };
    match (std::fs::canonicalize(path), std::fs::canonicalize(dir)) {
        (Ok(real), Ok(home)) => {
            let lexical =
                normalize(&std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf()));
            let lexical_home =
                normalize(&std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf()));
            lexical.starts_with(&lexical_home) && !real.starts_with(&home)
        }
        _ => false,
    }
}

/// Whether `path` lies inside the directory of one of `sources` (the
/// application's own Prolog files).
fn inside_sources(path: &Path, sources: &[PrologSource]) -> bool {
    let roots: Vec<PathBuf> = sources.iter().filter_map(|s| s.dir.clone()).collect();
    crate::trust::Trust::inside(path, &roots)
}

/// The files of a `consult/1`, `ensure_loaded/1` or `[F, ..]` directive.
fn consulted_files(store: &Store, goal: Term) -> Option<Vec<String>> {
    let arg = match store.value(goal) {
        Value::Compound(f, a)
            if a.len() == 1 && (f.as_str() == "consult" || f.as_str() == "ensure_loaded") =>
        {
            a[0]
        }
        Value::Compound(f, _) if f == atoms::DOT => goal,
        _ => return None,
    };
    let items = store.list_to_vec(arg).unwrap_or_else(|| vec![arg]);
    let mut files = Vec::new();
    for i in items {
        match store.atom_of(i) {
            Some(a) => files.push(a.as_str().to_owned()),
            None => return None,
        }
    }
    Some(files)
}

/// The source among `embedded` that `name`, consulted from `from`, names:
/// relative to the directory of `from`'s name, with or without `.pl`; else
/// one whose name ends with `name` (a library file the compiler's loader
/// found elsewhere, `library:/behaviors/language.pl` for
/// `'behaviors/language.pl'`).
fn embedded_source<'a>(
    name: &str,
    from: &PrologSource,
    embedded: &'a [PrologSource],
) -> Option<&'a PrologSource> {
    if name.starts_with('$') || Path::new(name).is_absolute() {
        return None;
    }
    let with_pl = format!("{name}.pl");
    let base = Path::new(&from.name).parent()?;
    let wanted = [normalize(&base.join(name)), normalize(&base.join(&with_pl))];
    let names = [normalize(Path::new(name)), normalize(Path::new(&with_pl))];
    let is_library_name = names[0]
        .components()
        .all(|c| matches!(c, std::path::Component::Normal(_)));
    embedded
        .iter()
        .find(|s| wanted.contains(&normalize(Path::new(&s.name))))
        .or_else(|| {
            embedded.iter().find(|s| {
                let path = normalize(Path::new(&s.name));
                is_library_name && names.iter().any(|n| path.ends_with(n))
            })
        })
}

/// Resolves a consulted file name: `$SITLOG_HOME/..` as described in the
/// module documentation, relative names against `dir`, `.pl` added when
/// the name has none and the file without it does not exist.
fn resolve(name: &str, dir: Option<&Path>) -> Option<PathBuf> {
    let with_ext = |p: PathBuf| -> Option<PathBuf> {
        if p.is_file() {
            return Some(p);
        }
        let mut q = p.into_os_string();
        q.push(".pl");
        let q = PathBuf::from(q);
        q.is_file().then_some(q)
    };
    if let Some(rest) = name.strip_prefix("$SITLOG_HOME/") {
        if let Some(home) = std::env::var_os("SITLOG_HOME") {
            return with_ext(Path::new(&home).join(rest));
        }
        let mut d = dir?.to_path_buf();
        loop {
            if let Some(p) = with_ext(d.join(rest)) {
                return Some(p);
            }
            if !d.pop() {
                return None;
            }
        }
    }
    let p = Path::new(name);
    if p.is_absolute() {
        with_ext(p.to_path_buf())
    } else {
        with_ext(dir?.join(p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The clauses `source` gives (text, line, column) as [`prepare`] reads them.
    fn prepared(source: &PrologSource) -> Vec<(String, usize, usize)> {
        let (mut out, mut defined, mut errors) = (Vec::new(), HashSet::new(), Vec::new());
        let (mut seen, mut outside, mut touching) = (HashSet::new(), Vec::new(), false);
        let mut cx = Prep {
            out: &mut out,
            defined: &mut defined,
            errors: &mut errors,
            seen: &mut seen,
            outside: &mut outside,
            embedded: std::slice::from_ref(source),
            native: None,
            redefine: None,
            touching: &mut touching,
            plain: None,
        };
        prepare(source, &mut cx, 0);
        assert!(errors.is_empty(), "{errors:?}");
        out.into_iter().map(|p| (p.text, p.line, p.col)).collect()
    }

    #[test]
    fn clauses_read_before_are_loaded_without_reading_the_text_again() {
        let text = "a(1).\n% note\n  b(X) :- a(X).\n";
        let plain = PrologSource::new("u.pl", text);
        let read = prepared(&plain);
        assert_eq!(read.len(), 2);
        assert_eq!((read[1].1, read[1].2), (3, 3));
        // The checker's clauses of the same text: the same load.
        let mut given = plain.clone();
        given.clauses = Some(std::sync::Arc::new(read_prolog_clauses(text).0));
        assert_eq!(prepared(&given), read);
        // They are what is loaded (the text only places them).
        given.clauses = Some(std::sync::Arc::new(
            read_prolog_clauses("a(2).\n% note\n  b(Y) :- a(Y).\n").0,
        ));
        let loaded = prepared(&given);
        assert_eq!(loaded[0].0, "a(2)");
        assert_eq!((loaded[1].1, loaded[1].2), (3, 3));
    }
}
