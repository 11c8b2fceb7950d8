//! The legacy KB layer served natively: [`NativeKb`] says which of the
//! original's KB predicates the host serves; while the layer's sources are
//! prepared, each clause is kept or renamed, and the clauses that
//! call the host (or turn handles back into KB terms) are added at the end,
//! with the facts the prelude's checks of rules asserted at run time read
//! (`'$sitlog_kb_reach'/2`, `'$sitlog_kb_producer'/2`,
//! `'$sitlog_kb_unwrapped'/1`).
//!
//! Invariant: a predicate of the layer that a handle can reach when it is
//! called (`kb_reach`'s inputs; every one when the analysis gives up)
//! runs its clauses on KB terms, never on handles; the others (and the
//! application's own predicates, a layer predicate it redefines included)
//! run as written.

use super::kb_reach::{self, Clause, Numbering, Served, T};
use super::reach_cache;
use super::translate::{write_atom, Prepared};
use crate::store::Store;
use crate::term::{Term, Value, Var};
use sitlog_syntax::Atom;
use std::collections::{HashMap, HashSet};
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
/// - every other predicate that a handle can reach (`kb_reach`: a
///   data-flow analysis of the layer's and the application's clauses) gets
///   its handles turned back into KB terms (the host writes the KB) before
///   its own clauses run, so code of the layer that the host does not serve
///   still works; one that no handle can reach runs as written, unwrapped.
///   A wrapped predicate's calls of itself in its own clauses go to those
///   clauses directly where no handle can be (a recursion over a list
///   would go through the wrapper at each step), as long as no clause is
///   asserted for it at run time (`NativeState::direct_recursion`).
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
    /// Where the KB-reach analysis keeps its results, one file per input
    /// (`reach_cache`; [`reach_cache_dir`](super::reach_cache_dir) is the
    /// usual place): the tasks of one tree analyse it once. `None`: no cache.
    pub reach_cache: Option<std::path::PathBuf>,
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
    /// The layer's predicates kept under their own name, in order met: the
    /// candidates for a wrapper (those `kb_reach` finds reachable get one).
    wrapped: Vec<(Atom, usize)>,
    wrapped_set: HashSet<(Atom, usize)>,
    /// Served predicates the layer defines itself.
    defined_served: HashSet<(Atom, usize)>,
    queries: Vec<(String, usize)>,
    updates: Vec<(String, usize)>,
    /// Whether the file being read is part of the layer (else the
    /// application's: read for the analysis only).
    pub(super) in_layer: bool,
    /// Every clause and directive read, for the analysis.
    clauses: Vec<Clause>,
    /// Predicates the application's files define.
    app_defined: HashSet<(Atom, usize)>,
    /// The analysis' cache directory ([`NativeKb::reach_cache`]).
    reach_cache: Option<std::path::PathBuf>,
    /// A clause's text, as prepared, to the text it has if its predicate
    /// is wrapped: its calls of itself go to the layer's clauses directly
    /// ([`NativeState::direct_recursion`]).
    alts: HashMap<String, String>,
}

/// A predicate of the layer that a KB handle can reach, wrapped: its
/// clauses become `legacy`'s, `key`'s clause is `wrapper`. An engine that
/// asserted the layer ahead (under the predicates' own names) does this to
/// its waiting clauses (`engine::wrap_ahead`).
pub(super) struct Wrapped {
    pub(super) legacy: (Atom, usize),
    pub(super) key: (Atom, usize),
    pub(super) wrapper: String,
    /// Its clauses' texts that call it again, each with the text whose
    /// calls go to `legacy` directly when no handle can be there
    /// ([`NativeState::direct_recursion`]).
    pub(super) alts: Vec<(String, String)>,
    /// With `alts`: all its clauses as written, renamed to `legacy`'s,
    /// which replace `legacy`'s when a clause is asserted for it at run
    /// time (the prelude's `'$sitlog_lz_undirect'/1`, an engine's `D`
    /// request: the direct calls would not see that clause).
    pub(super) originals: Vec<String>,
}

/// The file name of the clauses the native KB layer adds.
pub(super) const NATIVE_FILE: &str = "<native KB layer>";

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
            in_layer: true,
            clauses: Vec::new(),
            app_defined: HashSet::new(),
            reach_cache: n.reach_cache.clone(),
            alts: HashMap::new(),
        }
    }

    /// Records a directive for the analysis.
    pub(super) fn directive(&mut self, store: &Store, goal: Term) {
        let mut vars = Numbering::default();
        let body = T::of(store, goal, &mut vars);
        self.clauses.push(Clause {
            key: None,
            head: Vec::new(),
            body: Some(body),
            vars: vars.count(),
        });
    }

    /// Records a clause of predicate `key` (as loaded) for the analysis.
    fn record(&mut self, store: &Store, key: (Atom, usize), head: Term, body: Option<Term>) {
        let mut vars = Numbering::default();
        let head = store
            .args(head)
            .to_vec()
            .into_iter()
            .map(|a| T::of(store, a, &mut vars))
            .collect();
        let body = body.map(|b| T::of(store, b, &mut vars));
        self.clauses.push(Clause {
            key: Some(key),
            head,
            body,
            vars: vars.count(),
        });
    }

    /// What becomes of a clause of `key` (head `head`, body `body`): kept,
    /// or renamed (the layer's, served or wrapped); recorded for the
    /// analysis.
    pub(super) fn clause(
        &mut self,
        store: &mut Store,
        key: (Atom, usize),
        head: Term,
        body: Option<Term>,
    ) -> ClauseFate {
        let fate = if self.in_layer {
            self.layer_clause(store, key, body)
        } else {
            self.app_defined.insert(key);
            ClauseFate::Keep
        };
        // A predicate that may be wrapped is analysed under its own name
        // (its callers call it so); a served one's clauses are the layer's
        // fallback, called by the host's clause only.
        let as_loaded = match &fate {
            ClauseFate::Rename(a) if !self.wrapped_set.contains(&key) => (*a, key.1),
            _ => key,
        };
        self.record(store, as_loaded, head, body);
        fate
    }

    fn layer_clause(
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
        // Kept under its own name: renamed at the end if it is wrapped.
        if self.wrapped_set.insert(key) {
            self.wrapped.push(key);
        }
        ClauseFate::Keep
    }

    /// Under [`finish`](Self::finish)'s wrapper (if `key` gets one), the
    /// clause of `key` (head `head`, body `body`, kept under its own name)
    /// with each call of `key` itself in its body (through conjunctions,
    /// disjunctions and if-then-else) going to the layer's clauses directly
    /// when none of its arguments can be a handle there, and through the
    /// wrapper only when one is: a wrapper costs a call, and a recursion
    /// over a list (the layer's `isElement/2`) would go through it at each
    /// element, two calls where the original makes one. An argument cannot
    /// be a handle (at run time, whatever the analysis says) when it is a
    /// term other than `'$kb'(_)`, a variable nothing bound yet (not in the
    /// head, in no goal before the call), or the variable that is the whole
    /// argument at the same position of a head with no variable twice and
    /// no goal before the call naming any variable of the head (the wrapper
    /// looked at it, or does not look there; two head variables may share a
    /// value); any other one is looked at inline, as the wrapper
    /// does. `None`: no such call, or not a predicate that may be wrapped.
    pub(super) fn direct_recursion(
        &self,
        store: &mut Store,
        key: (Atom, usize),
        head: Term,
        body: Option<Term>,
    ) -> Option<Term> {
        if !self.in_layer || key.1 == 0 || !self.wrapped_set.contains(&key) {
            return None;
        }
        let body = body?;
        let kb = Atom::intern("$kb");
        let mut occurrences: HashMap<Var, usize> = HashMap::new();
        let mut stack: Vec<Term> = store.args(head).to_vec();
        while let Some(t) = stack.pop() {
            match store.value(t) {
                Value::Var(v) => *occurrences.entry(v).or_insert(0) += 1,
                Value::Compound(f, a) => {
                    if f == kb && a.len() == 1 {
                        return None;
                    }
                    stack.extend(a.iter().copied());
                }
                _ => {}
            }
        }
        let linear = occurrences.values().all(|&n| n == 1);
        let mut whole: HashMap<Var, usize> = HashMap::new();
        if linear {
            for (i, &a) in store.args(head).iter().enumerate() {
                if let Value::Var(v) = store.value(a) {
                    whole.insert(v, i);
                }
            }
        }
        let mut cx = Direct {
            key,
            legacy: legacy_name(key.0),
            kb,
            in_head: occurrences.keys().copied().collect(),
            whole,
            seen: HashSet::new(),
            changed: false,
        };
        let new = cx.goal(store, body);
        if !cx.changed {
            return None;
        }
        Some(store.compound(Atom::intern(":-"), &[head, new]))
    }

    /// Keeps `alt` ([`direct_recursion`](Self::direct_recursion)'s clause
    /// as prepared) for the clause prepared as `text`.
    pub(super) fn alt(&mut self, text: String, alt: String) {
        self.alts.insert(text, alt);
    }

    /// The clauses that serve the layer's predicates and wrap the others.
    /// `give_up`: a file builds a call that changes clauses as data (every
    /// predicate of the layer is then wrapped). Gives the predicates left
    /// wrapped, their clauses in `out` renamed.
    pub(super) fn finish(self, out: &mut Vec<Prepared>, give_up: bool) -> Vec<Wrapped> {
        let vars = |n: usize| -> Vec<String> { (0..n).map(|i| format!("V{i}")).collect() };
        // Each clause with its predicate and whether it may be asserted at
        // the predicate's first call (`engine::lazify`): the served
        // services' clauses, the wrappers, the analysis' facts, as the
        // layer's own predicates (asserted at start, the served services'
        // 130 clauses were some 90 M instructions of every start, 6 % of a
        // small task).
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
            // The handles looked for inline, as a wrapper does: a service
            // of the layer may call others (or itself) by their served
            // name, so this may run at each of those calls once KB terms
            // are left to the layer.
            let any_handle: Vec<String> = all
                .iter()
                .map(|x| format!("nonvar({x}), {x} = '$kb'(_)"))
                .collect();
            format!(
                " ; ( {} ) -> '$sitlog_kb_terms'([{}], [{}]), {}({}) ; {}({})",
                any_handle.join(" ; "),
                all.join(","),
                w.join(","),
                legacy,
                w.join(","),
                legacy,
                all.join(",")
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
                true,
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
                true,
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
                        format!("('$sitlog_kb_set_off', {legacy}(KB))")
                    }
                ),
                (*p, 1),
                true,
            ));
        }
        // Which predicates a handle can reach. A file that builds a call
        // changing clauses as data (`give_up`) leaves it unknown.
        let mut served = Served::default();
        for (q, arity) in &self.queries {
            served.queries.insert((Atom::intern(q), arity + 1));
        }
        for (u, arity) in &self.updates {
            served.updates.insert((Atom::intern(u), arity + 2));
        }
        for (p, _, save) in &self.files {
            if *save {
                served.saves.insert((*p, 1));
            } else {
                served.loads.insert((*p, 1));
            }
        }
        let reach = if give_up {
            kb_reach::Reach {
                top: true,
                ..Default::default()
            }
        } else {
            let program = kb_reach::Program {
                clauses: &self.clauses,
                served: &served,
            };
            reach_cache::analyse(&program, self.reach_cache.as_deref())
        };
        let mut wrapped = Vec::new();
        let mut unwrapped = Vec::new();
        // The number of the next `'$sitlog_direct'/3` fact: the order of
        // the wrapped predicates with `alts`.
        let mut direct = 0usize;
        for &(p, arity) in &self.wrapped {
            // A predicate the application redefines has lost the layer's
            // clauses: its own are the application's, not wrapped.
            if arity == 0 || self.app_defined.contains(&(p, arity)) {
                continue;
            }
            let positions = reach.of((p, arity));
            if positions.is_empty() {
                unwrapped.push((p, arity));
                continue;
            }
            let legacy = (legacy_name(p), arity);
            // Its clauses whose calls of itself may go to the layer's
            // clauses directly; not when a file builds a call that changes
            // clauses as data (the prelude would not see a clause asserted
            // for it, `'$sitlog_lz_undirect'/1`).
            let mine = |c: &&Prepared| c.key == Some((p, arity));
            let alts: Vec<(String, String)> = if give_up {
                Vec::new()
            } else {
                out.iter()
                    .filter(mine)
                    .filter_map(|c| self.alts.get(&c.text).map(|a| (c.text.clone(), a.clone())))
                    .collect()
            };
            let mut originals = Vec::new();
            if !alts.is_empty() {
                let (mut old, mut new) = (String::new(), String::new());
                write_atom(&mut old, p);
                write_atom(&mut new, legacy.0);
                originals = out
                    .iter()
                    .filter(mine)
                    .map(|c| rename_head(&c.text, &old, &new))
                    .collect();
                for c in out.iter_mut().filter(|c| c.key == Some((p, arity))) {
                    if let Some(a) = self.alts.get(&c.text) {
                        c.text.clone_from(a);
                    }
                }
                let mut fact = String::from("'$sitlog_direct'(");
                write_atom(&mut fact, p);
                fact.push_str(&format!(",{arity},{})", direct));
                direct += 1;
                clauses.push((fact, (Atom::intern("$sitlog_direct"), 3), false));
            }
            rename_clauses(out, (p, arity), legacy);
            let text = wrapper_text(p, arity, &positions);
            wrapped.push(Wrapped {
                legacy,
                key: (p, arity),
                wrapper: format!("({text})"),
                alts,
                originals,
            });
            clauses.push((text, (p, arity), true));
        }
        // What the prelude's run-time checks of asserted rules need
        // (`'$sitlog_kb_rule'/2`); none when every predicate is wrapped.
        if !reach.top {
            clauses.push((
                "'$sitlog_kb_watch'".into(),
                (Atom::intern("$sitlog_kb_watch"), 0),
                false,
            ));
            let mut reached: Vec<(Atom, usize)> = reach
                .inputs
                .iter()
                .map(|&(n, a, _)| (n, a))
                .chain(reach.undefined.iter().copied())
                .collect::<HashSet<_>>()
                .into_iter()
                .collect();
            reached.sort_by(|a, b| (a.0.as_str(), a.1).cmp(&(b.0.as_str(), b.1)));
            // These facts are only called, by the prelude's checks of a
            // rule asserted at run time (dynamic there, never retracted
            // or looked at with `clause/2`): they wait for that first call
            // as the layer's predicates do (`engine::lazify`; asserted at
            // start they were 4 % of a small task's instructions).
            let fact = |f: &str, (n, a): (Atom, usize)| {
                let mut t = format!("'{f}'(");
                write_atom(&mut t, n);
                t.push_str(&format!(",{a})"));
                (t, (Atom::intern(f), 2), true)
            };
            for &k in &reached {
                clauses.push(fact("$sitlog_kb_reach", k));
            }
            let mut producers: Vec<(Atom, usize)> = reach
                .positions
                .iter()
                .map(|&(n, a, _)| (n, a))
                .chain(served.updates.iter().copied())
                .chain(served.loads.iter().copied())
                .collect::<HashSet<_>>()
                .into_iter()
                .collect();
            producers.sort_by(|a, b| (a.0.as_str(), a.1).cmp(&(b.0.as_str(), b.1)));
            for &k in &producers {
                clauses.push(fact("$sitlog_kb_producer", k));
            }
            let mut list = String::from("'$sitlog_kb_unwrapped'([");
            for (i, &(n, a)) in unwrapped.iter().enumerate() {
                if i > 0 {
                    list.push(',');
                }
                write_atom(&mut list, n);
                list.push_str(&format!("/{a}"));
            }
            list.push_str("])");
            clauses.push((list, (Atom::intern("$sitlog_kb_unwrapped"), 1), false));
        }
        for (text, key, lazy) in clauses {
            out.push(Prepared {
                text: format!("({text})"),
                directive: false,
                file: NATIVE_FILE.into(),
                line: 0,
                col: 0,
                key: Some(key),
                lazy,
            });
        }
        wrapped
    }
}

/// The clause wrapping `p/arity`: the handles at `positions` turned into
/// KB terms, then the layer's clauses (renamed) called. The handles are
/// looked for inline (no call per argument: a call costs one inference
/// more than the original's, not n + 2).
fn wrapper_text(p: Atom, arity: usize, positions: &[usize]) -> String {
    let v: Vec<String> = (0..arity).map(|i| format!("V{i}")).collect();
    let w: Vec<String> = (0..arity)
        .map(|i| {
            if positions.contains(&i) {
                format!("W{i}")
            } else {
                format!("V{i}")
            }
        })
        .collect();
    let from: Vec<String> = positions.iter().map(|&i| format!("V{i}")).collect();
    let to: Vec<String> = positions.iter().map(|&i| format!("W{i}")).collect();
    let mut name = String::new();
    write_atom(&mut name, p);
    let mut legacy = String::new();
    write_atom(&mut legacy, legacy_name(p));
    let any_handle: Vec<String> = from
        .iter()
        .map(|x| format!("nonvar({x}), {x} = '$kb'(_)"))
        .collect();
    format!(
        "{name}({}) :- ( ( {} ) -> '$sitlog_kb_terms'([{}], [{}]), {legacy}({}) ; {legacy}({}) )",
        v.join(","),
        any_handle.join(" ; "),
        from.join(","),
        to.join(","),
        w.join(","),
        v.join(",")
    )
}

/// The clauses of `out` read as `from` become `to`'s (the head renamed).
fn rename_clauses(out: &mut [Prepared], from: (Atom, usize), to: (Atom, usize)) {
    let (mut old, mut new) = (String::new(), String::new());
    write_atom(&mut old, from.0);
    write_atom(&mut new, to.0);
    for p in out.iter_mut().filter(|p| p.key == Some(from)) {
        p.text = rename_head(&p.text, &old, &new);
        p.key = Some(to);
    }
}

/// [`NativeState::direct_recursion`]'s walk of a body, left to right.
struct Direct {
    key: (Atom, usize),
    legacy: Atom,
    kb: Atom,
    /// The head's variables.
    in_head: HashSet<Var>,
    /// The head's variables that are a whole argument, by position (none
    /// when a variable is twice in the head).
    whole: HashMap<Var, usize>,
    /// The variables of the goals before.
    seen: HashSet<Var>,
    changed: bool,
}

impl Direct {
    fn goal(&mut self, store: &mut Store, g: Term) -> Term {
        let g = store.deref(g);
        let Some((f, n)) = store.functor(g) else {
            self.see(store, g);
            return g;
        };
        if n == 2 && matches!(f.as_str(), "," | ";" | "->" | "*->") {
            let args = store.args(g).to_vec();
            let l = self.goal(store, args[0]);
            let r = self.goal(store, args[1]);
            return store.compound(f, &[l, r]);
        }
        if (f, n) != self.key {
            self.see(store, g);
            return g;
        }
        let args = store.args(g).to_vec();
        let head_seen = self.seen.iter().any(|v| self.in_head.contains(v));
        let mut looked: Vec<Term> = Vec::new();
        for (j, &a) in args.iter().enumerate() {
            let a = store.deref(a);
            match store.value(a) {
                Value::Var(v) => {
                    let untouched = !self.seen.contains(&v);
                    // A head variable may share its value with another one
                    // (`p(X, X)` called with `p(A, B)`'s head): a goal that
                    // bound any of them may have bound this one too.
                    let safe = untouched
                        && (!self.in_head.contains(&v)
                            || (self.whole.get(&v) == Some(&j) && !head_seen));
                    if !safe {
                        looked.push(a);
                    }
                }
                Value::Compound(c, ca) if c == self.kb && ca.len() == 1 => {
                    self.see(store, g);
                    return g;
                }
                _ => {}
            }
        }
        self.see(store, g);
        self.changed = true;
        let direct = store.compound(self.legacy, &args);
        if looked.is_empty() {
            return direct;
        }
        // `( nonvar(A), A = '$kb'(_) ; .. ) -> P(..) ; '$legacy_P'(..)`
        let mut cond: Option<Term> = None;
        for &a in looked.iter().rev() {
            let nv = store.compound(Atom::intern("nonvar"), &[a]);
            let hv = store.new_var();
            let h = store.compound(self.kb, &[hv]);
            let eq = store.compound(Atom::intern("="), &[a, h]);
            let test = store.compound(Atom::intern(","), &[nv, eq]);
            cond = Some(match cond {
                None => test,
                Some(rest) => store.compound(Atom::intern(";"), &[test, rest]),
            });
        }
        let cond = cond.unwrap_or_else(|| Term::atom(Atom::intern("fail")));
        let then = store.compound(Atom::intern("->"), &[cond, g]);
        store.compound(Atom::intern(";"), &[then, direct])
    }

    fn see(&mut self, store: &Store, t: Term) {
        let mut stack = vec![t];
        while let Some(t) = stack.pop() {
            match store.value(t) {
                Value::Var(v) => {
                    self.seen.insert(v);
                }
                Value::Compound(_, a) => stack.extend(a.iter().copied()),
                _ => {}
            }
        }
    }
}

/// `text`, a clause as prepared (`':-'(Head,Body)` or `Head`), with its
/// head's name `old` (as written) replaced by `new`. The name is followed
/// by `(`, `,` (a fact of arity 0 as a rule's head) or nothing: a name
/// written bare (`foo`) is a prefix of others (`foobar(..)`).
pub(super) fn rename_head(text: &str, old: &str, new: &str) -> String {
    let named_at = |at: usize| {
        text[at..].starts_with(old)
            && matches!(
                text.as_bytes().get(at + old.len()),
                None | Some(b'(' | b',')
            )
    };
    let at = if named_at(0) {
        0
    } else if text.starts_with("':-'(") && named_at(5) {
        5
    } else {
        return text.to_owned();
    };
    format!("{}{}{}", &text[..at], new, &text[at + old.len()..])
}

pub(super) fn legacy_name(a: Atom) -> Atom {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prolog::translate::Writer;

    /// Each clause of `text` as `direct_recursion` gives it (written), or
    /// `None`.
    fn direct(text: &str) -> Vec<Option<String>> {
        let (clauses, errors) = sitlog_syntax::read_prolog_clauses(text);
        assert!(errors.is_empty(), "{errors:?}");
        let mut st = NativeState::new(&NativeKb {
            host: Arc::new(|_| String::new()),
            queries: Vec::new(),
            updates: Vec::new(),
            reach_cache: None,
        });
        clauses
            .iter()
            .map(|c| {
                let mut store = Store::new();
                let (t, _) = store.from_clause(c);
                let (head, body) = match store.compound_args(t, Atom::intern(":-"), 2) {
                    Some(a) => (a[0], Some(a[1])),
                    None => (t, None),
                };
                let key = store.functor(head).unwrap();
                assert!(matches!(
                    st.clause(&mut store, key, head, body),
                    ClauseFate::Keep
                ));
                st.direct_recursion(&mut store, key, head, body).map(|alt| {
                    let mut w = Writer::new(&store, true);
                    w.term(store.args(alt)[1]);
                    w.out
                })
            })
            .collect()
    }

    #[test]
    fn a_head_is_renamed_by_its_whole_name() {
        // Names are written bare (`write_atom`): `foo` is a prefix of
        // `foobar`, whose clauses keep their name.
        assert_eq!(rename_head("foo(1)", "foo", "'$x'"), "'$x'(1)");
        assert_eq!(rename_head("foo", "foo", "'$x'"), "'$x'");
        assert_eq!(
            rename_head("':-'(foo,true)", "foo", "'$x'"),
            "':-'('$x',true)"
        );
        assert_eq!(rename_head("foobar(1)", "foo", "'$x'"), "foobar(1)");
        assert_eq!(
            rename_head("':-'(foob(1),true)", "foo", "'$x'"),
            "':-'(foob(1),true)"
        );
    }

    #[test]
    fn a_recursion_calls_the_layers_clauses_unless_a_handle_may_be_there() {
        let got = direct(
            "member_of(X, [X|_]).\n\
             member_of(X, [_|T]) :- member_of(X, T).\n\
             walk(KB, 0, N) :- !, length(KB, N).\n\
             walk(_, K, N) :- K1 is K - 1, open_kb(KB2), walk(KB2, K1, N).\n\
             same(KB, [], KB).\n\
             same(KB, [_|T], R) :- same(KB, T, R), write(done).\n\
             twice(X, X) :- twice(X, y).\n\
             kb(X) :- kb('$kb'(1)), kb(X).\n\
             alias(A, B) :- open_kb(B), alias(A, z).\n",
        );
        let test = |v: &str, h: &str| format!("','(nonvar({v}),'='({v},'$kb'({h})))");
        assert_eq!(got[0], None);
        assert_eq!(got[2], None);
        assert_eq!(got[4], None);
        // X is the head's, untouched, at the same place: not looked at; T,
        // a part of the head's list, is.
        assert_eq!(
            got[1].as_deref().unwrap(),
            format!(
                "';'('->'({},member_of(_S0,_S2)),'$legacy_member_of'(_S0,_S2))",
                test("_S2", "_S3")
            )
        );
        // KB2 and K1, bound before the call, are looked at; so is N, the
        // head's, since a goal before names K, another variable of the head.
        assert_eq!(
            got[3].as_deref().unwrap(),
            format!(
                "','(is(_S3,'-'(_S1,1)),','(open_kb(_S4),';'('->'(';'({},';'({},{})),\
                 walk(_S4,_S3,_S2)),'$legacy_walk'(_S4,_S3,_S2))))",
                test("_S4", "_S7"),
                test("_S3", "_S6"),
                test("_S2", "_S5")
            )
        );
        // KB and the unbound R are not; T is.
        assert_eq!(
            got[5].as_deref().unwrap(),
            format!(
                "','(';'('->'({},same(_S0,_S2,_S3)),'$legacy_same'(_S0,_S2,_S3)),write(done))",
                test("_S2", "_S4")
            )
        );
        // A variable twice in the head is looked at.
        assert_eq!(
            got[6].as_deref().unwrap(),
            format!(
                "';'('->'({},twice(_S0,y)),'$legacy_twice'(_S0,y))",
                test("_S0", "_S1")
            )
        );
        // A call with a handle written in it is left as it is; the one
        // after, with nothing that may be a handle, goes directly.
        assert_eq!(
            got[7].as_deref().unwrap(),
            "','(kb('$kb'(1)),'$legacy_kb'(_S0))"
        );
        // A, the head's and untouched, is looked at when a goal before
        // names another variable of the head: the caller may have given
        // both one value (`alias(X, X)`), bound to a handle by `open_kb`.
        assert_eq!(
            got[8].as_deref().unwrap(),
            format!(
                "','(open_kb(_S1),';'('->'({},alias(_S0,z)),'$legacy_alias'(_S0,z)))",
                test("_S0", "_S2")
            )
        );
    }
}
