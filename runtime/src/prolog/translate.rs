//! Terms between our store and the engine: store terms written as
//! canonical text the engine reads back exactly ([`Writer`], with SWI-6's
//! reading of `'|'` and the [`SWI_RENAMED`](super::SWI_RENAMED) calls
//! renamed), engine terms read back into the store ([`from_prolog`]), text
//! read as a term by our reader for the engine ([`read_reply`]), and a
//! clause ready for the engine ([`Prepared`]). Both walks grow their stack
//! on the heap; an engine term is dropped without recursion
//! ([`drop_deep`]), and the [`Writer`] measures how deep what it writes
//! nests, the engine's reader being recursive (see [`PROLOG_MAX_DEPTH`]).

use super::permissions::guard_name;
use super::swi::{closure_extra, swi_renamed};
use crate::functions::PROLOG_MAX_DEPTH;
use crate::store::Store;
use crate::term::{Term, Value, Var};
use scryer_prolog::Term as PTerm;
use sitlog_syntax::{atoms, Atom};
use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;

/// A clause ready for the engine.
#[derive(Clone)]
pub(super) struct Prepared {
    /// Canonical text of the clause term (no final `.`).
    pub(super) text: String,
    pub(super) directive: bool,
    pub(super) file: String,
    pub(super) line: usize,
    pub(super) col: usize,
    /// A clause's predicate (name and arity of its head as written), if
    /// known.
    pub(super) key: Option<(Atom, usize)>,
    /// Under the legacy profile, a clause (of the original's layer or of
    /// the application) that may be asserted at its predicate's first call
    /// rather than at load (see `engine::lazify`): its body calls nothing
    /// the engine refuses at assert time.
    pub(super) lazy: bool,
}

/// Writes store terms as canonical Prolog text the engine reads back
/// exactly: every atom quoted but a plain name (`write_atom`), no
/// operators, lists in list notation,
/// variables `_S<index>`.
pub(super) struct Writer<'s> {
    store: &'s Store,
    pub(super) out: String,
    /// Distinct unbound variables met, in order.
    pub(super) vars: Vec<Var>,
    seen: HashSet<Var>,
    /// Application clauses: turn `'|'/2` into `;/2` (SWI-6 reading) and
    /// rename the calls of [`SWI_RENAMED`](super::SWI_RENAMED) built-ins,
    /// and those of the predicates reaching the operating system to their
    /// guards (see `permissions`).
    bar_is_or: bool,
    /// Off while a clause head is written (an application's own `shell/1`
    /// keeps its name).
    guard: bool,
    /// Nesting of the term being written (a list element counts one level
    /// per element before it: the engine reads a list as nested cells).
    depth: usize,
    /// The deepest nesting written.
    pub(super) deepest: usize,
    /// The legacy profile: the calls that change or look at a predicate's
    /// clauses ([`TOUCHING`]) are renamed to the prelude's versions that
    /// first load a predicate asserted lazily (see `engine::lazify`).
    pub(super) touch: bool,
    /// Set when an atom naming one of [`TOUCHING`] was written as data
    /// (a goal that may be built at run time, `G =.. [assertz, C]`): the
    /// legacy layer is then loaded whole.
    pub(super) touching_atom: bool,
}

/// The built-ins that change or look at the clauses of a predicate, by
/// name and arity: under the legacy profile, an application's and the
/// layer's calls of them are renamed to `'$sitlog_lz_NAME'`, which loads
/// the predicate first if it is still a stub (`engine::lazify`).
pub(super) const TOUCHING: &[(&str, usize)] = &[
    ("assert", 1),
    ("asserta", 1),
    ("assertz", 1),
    ("retract", 1),
    ("retractall", 1),
    ("abolish", 1),
    ("abolish", 2),
    ("clause", 2),
];

/// The name a call of `f/n` is renamed to under the legacy profile, if it
/// is one of [`TOUCHING`].
fn touch_renamed(f: Atom, n: usize) -> Option<Atom> {
    TOUCHING
        .iter()
        .any(|&(name, arity)| arity == n && name == f.as_str())
        .then(|| Atom::intern(&format!("$sitlog_lz_{}", f.as_str())))
}

impl<'s> Writer<'s> {
    pub(super) fn new(store: &'s Store, bar_is_or: bool) -> Writer<'s> {
        Writer {
            store,
            out: String::new(),
            vars: Vec::new(),
            seen: HashSet::new(),
            bar_is_or,
            guard: true,
            depth: 0,
            deepest: 0,
            touch: false,
            touching_atom: false,
        }
    }

    /// Whether what was written nests deeper than the engine takes
    /// ([`PROLOG_MAX_DEPTH`]).
    pub(super) fn too_deep(&self) -> bool {
        self.deepest > PROLOG_MAX_DEPTH
    }

    /// A clause head: written as [`term`](Self::term) does, except that its
    /// own name is not renamed to a guard.
    pub(super) fn head(&mut self, t: Term) {
        self.guard = false;
        match self.store.value(t) {
            Value::Compound(f, args) if f != atoms::DOT => {
                let args = args.to_vec();
                let f = if self.bar_is_or {
                    swi_renamed(f, args.len()).unwrap_or(f)
                } else {
                    f
                };
                self.guard = true;
                write_atom(&mut self.out, f);
                self.out.push('(');
                for (i, &a) in args.iter().enumerate() {
                    if i > 0 {
                        self.out.push(',');
                    }
                    self.term(a);
                }
                self.out.push(')');
            }
            _ => {
                self.guard = true;
                self.term(t)
            }
        }
    }

    /// The name a compound `f/n` of an application clause is written with.
    fn renamed(&self, f: Atom, n: usize) -> Atom {
        swi_renamed(f, n)
            .or_else(|| {
                if self.touch {
                    touch_renamed(f, n)
                } else {
                    None
                }
            })
            .or_else(|| if self.guard { guard_name(f, n) } else { None })
            .unwrap_or(f)
    }

    pub(super) fn term(&mut self, t: Term) {
        self.depth += 1;
        self.deepest = self.deepest.max(self.depth);
        stacker::maybe_grow(64 * 1024, 1024 * 1024, || self.term_inner(t));
        self.depth -= 1;
    }

    fn term_inner(&mut self, t: Term) {
        match self.store.value(t) {
            Value::Var(v) => {
                if self.seen.insert(v) {
                    self.vars.push(v);
                }
                let _ = write!(self.out, "_S{}", v.0);
            }
            Value::Atom(a) => {
                if self.touch && TOUCHING.iter().any(|&(n, _)| n == a.as_str()) {
                    self.touching_atom = true;
                }
                write_atom(&mut self.out, a)
            }
            Value::Int(i) => {
                let _ = write!(self.out, "{i}");
            }
            Value::BigInt(s) => self.out.push_str(s),
            Value::Float(f) => {
                if f.is_finite() {
                    self.out.push_str(&sitlog_syntax::write::format_float(f));
                } else if f.is_nan() {
                    self.out.push_str("nan");
                } else if f > 0.0 {
                    self.out.push_str("inf");
                } else {
                    self.out.push_str("'-inf'");
                }
            }
            Value::Compound(f, args) if f == atoms::DOT && args.len() == 2 => {
                self.out.push('[');
                let base = self.depth;
                let mut it = self.store.list_iter(t);
                let mut first = true;
                for item in it.by_ref() {
                    if !first {
                        self.out.push(',');
                    }
                    first = false;
                    self.term(item);
                    self.depth += 1;
                }
                let tail = it.tail();
                if tail != Term::NIL {
                    self.out.push('|');
                    self.term(tail);
                }
                self.depth = base;
                self.out.push(']');
            }
            Value::Compound(f, args) => {
                let args = args.to_vec();
                let f = if !self.bar_is_or {
                    f
                } else if f == atoms::BAR && args.len() == 2 {
                    atoms::SEMICOLON
                } else {
                    self.renamed(f, args.len())
                };
                // A closure naming a renamed built-in.
                let closure = if self.bar_is_or {
                    closure_extra(f.as_str(), args.len())
                } else {
                    None
                };
                write_atom(&mut self.out, f);
                self.out.push('(');
                for (i, &a) in args.iter().enumerate() {
                    if i > 0 {
                        self.out.push(',');
                    }
                    match closure {
                        Some(extra) if i == 0 => self.closure(a, extra),
                        _ => self.term(a),
                    }
                }
                self.out.push(')');
            }
        }
    }
}

impl Writer<'_> {
    /// A closure given `extra` more arguments by a meta-predicate.
    fn closure(&mut self, t: Term, extra: usize) {
        let t = self.store.deref(t);
        match self.store.value(t) {
            Value::Atom(a) => match self.renamed(a, extra) {
                r if r != a => write_atom(&mut self.out, r),
                _ => self.term(t),
            },
            Value::Compound(f, args) if f != atoms::DOT => {
                let n = args.len();
                match Some(self.renamed(f, n + extra)).filter(|&r| r != f) {
                    Some(r) => {
                        let args = args.to_vec();
                        write_atom(&mut self.out, r);
                        self.out.push('(');
                        for (i, &a) in args.iter().enumerate() {
                            if i > 0 {
                                self.out.push(',');
                            }
                            self.term(a);
                        }
                        self.out.push(')');
                    }
                    None => self.term(t),
                }
            }
            _ => self.term(t),
        }
    }
}

/// An atom: a name (a small letter, then letters, digits and `_`, ASCII)
/// as it is, `[]` and `{}` as they are, any other quoted (ISO escapes).
/// The engine's reader makes the same token of `abc` and `'abc'` (its
/// lexer, `name_token`: an operator is one either way), and reads a bare
/// name cheaper than a quoted one (issue 39: the texts the engine reads
/// are written here: queries, clauses, the host's replies).
pub(super) fn write_atom(out: &mut String, a: Atom) {
    let s = a.as_str();
    if s == "[]" || s == "{}" || is_plain_name(s) {
        out.push_str(s);
        return;
    }
    out.push('\'');
    for c in s.chars() {
        match c {
            '\'' => out.push_str("\\'"),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => {
                let _ = write!(out, "\\x{:x}\\", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('\'');
}

/// Whether `s` reads as itself unquoted: a small letter, then ASCII
/// letters, digits and `_`.
pub(super) fn is_plain_name(s: &str) -> bool {
    let mut cs = s.bytes();
    cs.next().is_some_and(|c| c.is_ascii_lowercase())
        && cs.all(|c| c.is_ascii_alphanumeric() || c == b'_')
}

/// A scryer term as a store term: a variable is `names[name]`, or a fresh
/// variable recorded there.
pub(super) fn from_prolog(store: &mut Store, t: &PTerm, names: &mut HashMap<String, Term>) -> Term {
    stacker::maybe_grow(64 * 1024, 1024 * 1024, || match t {
        PTerm::Integer(i) => match i64::try_from(i.clone()) {
            Ok(small) => Term::int(small),
            Err(_) => store
                .integer_from_text(&i.to_string())
                .unwrap_or(Term::atom(atoms::NIL)),
        },
        PTerm::Rational(r) => {
            let text = r.to_string();
            Term::atom(Atom::intern(&text))
        }
        PTerm::Float(f) => Term::float(*f),
        PTerm::Atom(a) => Term::atom(Atom::intern(a)),
        PTerm::String(s) => {
            let chars: Vec<Term> = s
                .chars()
                .map(|c| Term::atom(Atom::intern(c.encode_utf8(&mut [0; 4]))))
                .collect();
            store.list(&chars)
        }
        PTerm::List(items) => {
            let items: Vec<Term> = items.iter().map(|i| from_prolog(store, i, names)).collect();
            store.list(&items)
        }
        PTerm::Compound(f, args) => {
            let args: Vec<Term> = args.iter().map(|a| from_prolog(store, a, names)).collect();
            store.compound(Atom::intern(f), &args)
        }
        PTerm::Var(name) => {
            if let Some(&t) = names.get(name) {
                return t;
            }
            let t = store.new_var();
            names.insert(name.clone(), t);
            t
        }
        _ => Term::atom(Atom::intern("$unknown")),
    })
}

/// Drops an engine term without recursion (the derived drop of a term
/// nested 500 000 levels deep overflows the stack).
pub(super) fn drop_deep(t: PTerm) {
    let mut stack = vec![t];
    while let Some(t) = stack.pop() {
        match t {
            PTerm::List(items) | PTerm::Compound(_, items) => stack.extend(items),
            _ => {}
        }
    }
}

/// Reads `text` as one term with our reader (SWI-Prolog syntax, SitLog
/// operators) and answers in canonical form: `'$ok'(Term, ['Name'=Var,..]).`,
/// `'$error'(error(syntax_error(Message), context(Text, Line, Column))).` or,
/// for text with no term, `'$eof'.`
pub fn read_reply(text: &str) -> String {
    if text.trim().is_empty() {
        return "'$eof'.\n".to_owned();
    }
    let mut store = Store::new();
    match store.parse(text) {
        Ok((t, bindings)) => {
            let mut w = Writer::new(&store, false);
            w.out.push_str("'$ok'(");
            w.term(t);
            w.out.push_str(",[");
            for (i, (name, v)) in bindings.iter().enumerate() {
                if i > 0 {
                    w.out.push(',');
                }
                write_atom(&mut w.out, Atom::intern(name));
                w.out.push('=');
                w.term(*v);
            }
            w.out.push_str("]).\n");
            w.out
        }
        Err(e) => {
            let (line, col) = e.line_col(text);
            let mut out = String::from("'$error'(error(syntax_error(");
            write_atom(&mut out, Atom::intern(&e.message));
            out.push_str("),context(");
            write_atom(&mut out, Atom::intern(text));
            let _ = writeln!(out, ",{line},{col}))).");
            out
        }
    }
}
