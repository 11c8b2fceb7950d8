//! Which argument positions of the Prolog code's predicates a KB handle
//! can reach (`--legacy-kb native`, see [`NativeKb`](super::NativeKb)): a
//! data-flow analysis (abstract interpretation) over the clauses and
//! directives of the original's layer and of the application's files, so
//! that only the layer's predicates a handle can reach are wrapped to turn
//! handles back into KB terms.
//!
//! The domain: a position `P/n:i` is *reached* when its argument may hold a
//! handle anywhere inside it, at the call or on success (one notion for
//! input and output, an over-approximation). Handles enter where the host
//! makes them (a KB load's argument, an update's new KB) and flow by
//! unification (structure-insensitive: a term holding a reached variable is
//! reached) and by calls (a service's call also reaches the layer's own
//! clauses it may fall back to, all its arguments but the KB). A built-in
//! or a predicate defined by no file (asserted at run time) passes a
//! reached argument to all its arguments, except the built-ins that give
//! no part of an argument to another (`opaque`: type tests, arithmetic,
//! comparison, text, output), which stop it, and `=..`, `arg/3`,
//! `functor/3`, which share it only between a term and its arguments; an
//! argument of a built-in that names a predicate of the files is taken as
//! a goal it may call (a library's meta-predicate), as are the closures of
//! `call/N`, `maplist/N`, `foldl/N`, `include/3`, `exclude/3`,
//! `partition/4`, `apply/2`; the database and global variables
//! (`bb_get/2`, `recorded/3`, `clause/2`, `retract/1`, the catcher of
//! `catch/3`) give reached values.
//! Giving the outside a handle (`assert/1`, `bb_put/2`, `nb_setval/2`,
//! `recorda/3`, `throw/1` of a reached term) or calling an unknown goal (a
//! variable, `call/N` of one) with a reached argument at that point of its
//! clause (left to right: a goal called before its argument is bound
//! cannot see what is bound later, unless the code uses coroutines) makes
//! the result [`Reach::top`]: every predicate may be reached.
//!
//! Calls are followed through each predicate's *summary*, whatever its
//! callers give it (a first fixpoint over every clause, flow-insensitive):
//! which of its argument positions it may make share (unify any part of
//! one with any part of another) and which may hold a handle it makes
//! itself (a producer, an unknown goal, a callee's). At a call, the
//! arguments of positions that may share are unified and those it makes a
//! handle in are reached; so a predicate that only passes handles through
//! (a list utility given a KB by one caller and a character list by
//! another) does not carry one caller's handle to the other's arguments.
//!
//! Two results: the *inputs*, positions that may hold a handle when the
//! predicate is called, found left to right as above (all at once where
//! the files use coroutines), and the positions reached (at the call or on
//! success: an input, one the predicate makes, or one that may share with
//! an input); a wrapper looks only at the inputs. The second fixpoint looks
//! again only at the clauses a handle can start in (a producer, an unknown
//! goal, a call of a predicate that makes one) or of a predicate called
//! with one.
//!
//! `predsort/3` calls its closure on the list's elements, and `M:G` is
//! the goal `G`. Not covered (a hole, found in review): a handle's text
//! read back as a term (a handle is `'$kb'(N)`: `format(atom(A), "~q",
//! [KB])` is opaque, and `term_to_atom(T, A)` or `read/1` of what was
//! written makes a handle no position holds); a closure given to a
//! meta-predicate of a library not in the list above is a plain
//! built-in's argument.
//!
//! What the analysis assumes of the run, kept by the engine: the host never
//! holds a handle (a call's answer has its handles turned into KB terms,
//! `engine::unhandle`), so a call from the host gives none; a rule asserted
//! at run time for a predicate that may be called with a handle converts
//! its head's handles first, and one whose body may get a handle from a
//! producer or an unknown goal wraps every predicate then (the prelude's
//! `'$sitlog_kb_rule'/2`).

use crate::store::Store;
use crate::term::{Term, Value, Var};
use sitlog_syntax::Atom;
use std::collections::{HashMap, HashSet};

/// A clause term as the analysis sees it: its variables numbered.
#[derive(Clone, Debug)]
pub(super) enum T {
    Var(u32),
    Atom(Atom),
    /// A number or a string.
    Other,
    Comp(Atom, Vec<T>),
    /// A part too deep to keep: only its variables.
    Vars(Vec<u32>),
}

/// How deep a clause term is kept as it is (deeper: [`T::Vars`]).
const KEEP_DEPTH: usize = 64;

/// Numbers the variables of one clause.
#[derive(Default)]
pub(super) struct Numbering(HashMap<Var, u32>);

impl Numbering {
    fn var(&mut self, v: Var) -> u32 {
        let n = self.0.len() as u32;
        *self.0.entry(v).or_insert(n)
    }
    pub(super) fn count(&self) -> usize {
        self.0.len()
    }
}

impl T {
    pub(super) fn of(store: &Store, t: Term, vars: &mut Numbering) -> T {
        T::at(store, t, vars, 0)
    }

    fn at(store: &Store, t: Term, vars: &mut Numbering, depth: usize) -> T {
        match store.value(t) {
            Value::Var(v) => T::Var(vars.var(v)),
            Value::Atom(a) => T::Atom(a),
            Value::Compound(f, args) => {
                if depth >= KEEP_DEPTH {
                    let mut out = Vec::new();
                    let mut stack = vec![t];
                    while let Some(t) = stack.pop() {
                        match store.value(t) {
                            Value::Var(v) => out.push(vars.var(v)),
                            Value::Compound(_, a) => stack.extend(a.iter().copied()),
                            _ => {}
                        }
                    }
                    return T::Vars(out);
                }
                let args = args.to_vec();
                T::Comp(
                    f,
                    args.into_iter()
                        .map(|a| T::at(store, a, vars, depth + 1))
                        .collect(),
                )
            }
            _ => T::Other,
        }
    }

    fn vars(&self, out: &mut Vec<u32>) {
        match self {
            T::Var(v) => out.push(*v),
            T::Comp(_, a) => a.iter().for_each(|t| t.vars(out)),
            T::Vars(v) => out.extend(v),
            T::Atom(_) | T::Other => {}
        }
    }

    pub(super) fn all_vars(&self) -> Vec<u32> {
        let mut out = Vec::new();
        self.vars(&mut out);
        out
    }
}

/// One clause (a directive has no head), its predicate as loaded.
pub(super) struct Clause {
    pub(super) key: Option<(Atom, usize)>,
    pub(super) head: Vec<T>,
    pub(super) body: Option<T>,
    pub(super) vars: usize,
}

/// What the analysis knows of the predicates the host serves.
#[derive(Default)]
pub(super) struct Served {
    /// Query services (their answer holds no handle).
    pub(super) queries: HashSet<(Atom, usize)>,
    /// Updates (their last argument is a new handle).
    pub(super) updates: HashSet<(Atom, usize)>,
    /// KB loads (their argument is a handle).
    pub(super) loads: HashSet<(Atom, usize)>,
    /// KB saves.
    pub(super) saves: HashSet<(Atom, usize)>,
}

/// The analysis' result.
#[derive(Debug, Default)]
pub(super) struct Reach {
    /// Every position may be reached (the analysis gave up).
    pub(super) top: bool,
    /// The reached positions `(name, arity, index)`: may hold a handle at
    /// the call or on success.
    pub(super) positions: HashSet<(Atom, usize, usize)>,
    /// The positions that may hold a handle when the predicate is called
    /// (those a wrapper looks at).
    pub(super) inputs: HashSet<(Atom, usize, usize)>,
    /// Predicates defined by no file called with a reached argument.
    pub(super) undefined: HashSet<(Atom, usize)>,
}

impl Reach {
    /// The positions of `key` that may hold a handle when it is called
    /// (all under [`top`](Self::top)).
    pub(super) fn of(&self, key: (Atom, usize)) -> Vec<usize> {
        (0..key.1)
            .filter(|&i| self.top || self.inputs.contains(&(key.0, key.1, i)))
            .collect()
    }
}

/// A goal of a clause body, flattened in order.
enum Goal {
    /// Unifies its variables (a built-in, `=/2`, a predicate with no file).
    Unify(Vec<u32>, Option<(Atom, usize)>),
    /// A built-in that looks at its arguments and binds none to a part of
    /// another ([`opaque`]).
    Look(Vec<u32>, (Atom, usize)),
    /// A call of a predicate defined by a file: each argument's variables.
    Call((Atom, usize), Vec<Vec<u32>>),
    /// Binds its variables to what may hold a handle.
    Source(Vec<u32>),
    /// A goal unknown until run time, with its variables.
    Unknown(Vec<u32>),
    /// Gives its variables to the outside (the database, a global, a ball).
    Escape(Vec<u32>),
}

/// Union-find over a clause's variables, each class reached or not.
struct Classes {
    parent: Vec<u32>,
    reached: Vec<bool>,
}

impl Classes {
    fn new(n: usize) -> Classes {
        Classes {
            parent: (0..n as u32).collect(),
            reached: vec![false; n],
        }
    }
    fn find(&mut self, mut v: u32) -> u32 {
        while self.parent[v as usize] != v {
            let p = self.parent[v as usize];
            self.parent[v as usize] = self.parent[p as usize];
            v = p;
        }
        v
    }
    fn union(&mut self, vs: &[u32]) {
        let Some(&first) = vs.first() else { return };
        let root = self.find(first);
        for &v in &vs[1..] {
            let r = self.find(v);
            if r != root {
                self.parent[r as usize] = root;
                let both = self.reached[r as usize] || self.reached[root as usize];
                self.reached[root as usize] = both;
            }
        }
    }
    fn reach(&mut self, vs: &[u32]) {
        for &v in vs {
            let r = self.find(v);
            self.reached[r as usize] = true;
        }
    }
    fn any(&mut self, vs: &[u32]) -> bool {
        vs.iter().any(|&v| {
            let r = self.find(v);
            self.reached[r as usize]
        })
    }
}

/// The program to analyse.
pub(super) struct Program<'a> {
    pub(super) clauses: &'a [Clause],
    pub(super) served: &'a Served,
}

struct Flattener<'a> {
    defined: &'a HashSet<(Atom, usize)>,
    arities: &'a HashMap<Atom, Vec<usize>>,
    served: &'a Served,
    coroutines: bool,
}

/// The engine's built-ins (and the prelude's SWI ones) that never bind an
/// argument to (a term holding) a part of another: type tests, arithmetic,
/// comparison, text of atomic values, output. A handle given to them goes
/// no further.
fn opaque(f: Atom, n: usize) -> bool {
    matches!(
        (f.as_str(), n),
        (
            "var" | "nonvar" | "atom" | "number" | "integer" | "float" | "atomic",
            1
        ) | ("compound" | "callable" | "is_list" | "ground" | "string", 1)
            | ("==" | "\\==" | "@<" | "@>" | "@=<" | "@>=", 2)
            | ("is" | "=:=" | "=\\=" | "<" | ">" | "=<" | ">=" | "succ", 2)
            | ("compare" | "plus", 3)
            | (
                "length" | "atom_length" | "atom_codes" | "atom_chars" | "char_code",
                2
            )
            | (
                "atom_number" | "number_codes" | "number_chars" | "atom_string",
                2
            )
            | (
                "upcase_atom" | "downcase_atom" | "string_chars" | "string_codes",
                2
            )
            | (
                "string_to_atom" | "string_length" | "number_string" | "atom_to_chars",
                2
            )
            | (
                "atom_concat" | "atomic_concat" | "atomic_list_concat" | "string_concat",
                3
            )
            | ("atomic_list_concat", 2)
            | ("sub_atom" | "sub_string", 5)
            | (
                "write" | "writeq" | "print" | "write_canonical" | "nl" | "tab",
                1 | 2
            )
            | ("write_term", 2 | 3)
            | ("format", 1..=3)
            | (
                "nl" | "true" | "fail" | "false" | "!" | "halt" | "listing",
                0
            )
            | (
                "put_char" | "put_code" | "flush_output" | "close" | "halt" | "sleep",
                1
            )
            | ("put_char" | "put_code" | "close", 2)
            | (
                "get_char" | "get_code" | "get0" | "peek_char" | "peek_code",
                1 | 2
            )
            | ("open", 3 | 4)
            | ("between", 3)
            | ("get_time" | "random" | "listing", 1)
            | ("stamp_date_time", 3)
    )
}

fn is(f: Atom, name: &str) -> bool {
    f.as_str() == name
}

impl Flattener<'_> {
    /// `goal` called with `extra` more arguments (their variables).
    fn goal(&mut self, goal: &T, extra: &[Vec<u32>], out: &mut Vec<Goal>) {
        let extra_vars = || extra.iter().flatten().copied().collect::<Vec<u32>>();
        let (f, args): (Atom, &[T]) = match goal {
            T::Var(v) => {
                let mut vs = vec![*v];
                vs.extend(extra_vars());
                out.push(Goal::Unknown(vs));
                return;
            }
            T::Vars(v) => {
                let mut vs = v.clone();
                vs.extend(extra_vars());
                out.push(Goal::Unknown(vs));
                return;
            }
            T::Other => return,
            T::Atom(a) => (*a, &[]),
            T::Comp(f, a) => (*f, a.as_slice()),
        };
        // `M:G` calls `G` (with the same added arguments).
        if is(f, ":") && args.len() == 2 {
            self.goal(&args[1], extra, out);
            return;
        }
        let n = args.len() + extra.len();
        let key = (f, n);
        let vars_of = |i: usize| args[i].all_vars();
        if extra.is_empty() {
            match (f.as_str(), n) {
                (",", 2) | (";", 2) | ("->", 2) | ("*->", 2) | ("|", 2) | ("forall", 2) => {
                    self.goal(&args[0], &[], out);
                    self.goal(&args[1], &[], out);
                    return;
                }
                ("\\+", 1) | ("call", 1) | ("once", 1) | ("ignore", 1) | ("not", 1) => {
                    self.goal(&args[0], &[], out);
                    return;
                }
                ("findall", 3)
                | ("findall", 4)
                | ("bagof", 3)
                | ("setof", 3)
                | ("aggregate_all", 3)
                | ("aggregate_all", 4) => {
                    let mut vs = vars_of(0);
                    for i in 2..n {
                        vs.extend(vars_of(i));
                    }
                    out.push(Goal::Unify(vs, None));
                    let mut g = &args[1];
                    while let T::Comp(c, a) = g {
                        if is(*c, "^") && a.len() == 2 {
                            g = &a[1];
                        } else {
                            break;
                        }
                    }
                    self.goal(g, &[], out);
                    return;
                }
                ("catch", 3) => {
                    self.goal(&args[0], &[], out);
                    out.push(Goal::Source(vars_of(1)));
                    self.goal(&args[2], &[], out);
                    return;
                }
                ("setup_call_cleanup", 3) | ("call_cleanup", 2) => {
                    for a in args {
                        self.goal(a, &[], out);
                    }
                    return;
                }
                ("with_output_to", 2) | ("time", 1) => {
                    self.goal(&args[n - 1], &[], out);
                    return;
                }
                ("freeze", 2) | ("when", 2) => {
                    self.coroutines = true;
                    self.goal(&args[1], &[], out);
                    return;
                }
                ("dif", 2) | ("put_attr", 3) | ("put_atts", 2) => {
                    self.coroutines = true;
                }
                ("assert", 1) | ("asserta", 1) | ("assertz", 1) | ("throw", 1) => {
                    out.push(Goal::Escape(vars_of(0)));
                    return;
                }
                ("retract", 1)
                | ("clause", 2)
                | ("bb_get", 2)
                | ("b_getval", 2)
                | ("nb_getval", 2)
                | ("nb_current", 2)
                | ("recorded", 2)
                | ("recorded", 3) => {
                    out.push(Goal::Source(goal.all_vars()));
                    return;
                }
                ("bb_put", 2)
                | ("bb_b_put", 2)
                | ("b_setval", 2)
                | ("nb_setval", 2)
                | ("recorda", 2)
                | ("recordz", 2)
                | ("recorda", 3)
                | ("recordz", 3)
                | ("setarg", 3)
                | ("nb_setarg", 3) => {
                    out.push(Goal::Escape(goal.all_vars()));
                    return;
                }
                _ => {}
            }
        }
        // The closure-taking ones: `call/N`, `maplist/N`, `foldl/N`...
        if extra.is_empty() && !args.is_empty() && !self.defined.contains(&key) {
            let closure = match (f.as_str(), n) {
                ("call", _) | ("maplist", 2..=7) | ("foldl", 4..=7) | ("apply", 2) => true,
                ("include", 3) | ("exclude", 3) | ("partition", 4) => {
                    out.push(Goal::Unify(goal.all_vars(), None));
                    true
                }
                // `predsort(P, List, Sorted)` calls `P(Order, E1, E2)` on
                // the elements: each added argument may be any of them.
                ("predsort", 3) => {
                    out.push(Goal::Unify(goal.all_vars(), None));
                    let elems = [args[1].all_vars(), args[2].all_vars()].concat();
                    self.goal(&args[0], &[elems.clone(), elems.clone(), elems], out);
                    return;
                }
                _ => false,
            };
            if closure {
                let rest: Vec<Vec<u32>> = args[1..].iter().map(T::all_vars).collect();
                // `apply(G, Args)` adds as many arguments as Args has.
                if is(f, "apply") {
                    out.push(Goal::Unknown(goal.all_vars()));
                    return;
                }
                self.goal(&args[0], &rest, out);
                return;
            }
        }
        let mut per_arg: Vec<Vec<u32>> = args.iter().map(T::all_vars).collect();
        per_arg.extend(extra.iter().cloned());
        // A service called with arguments the host does not take runs the
        // layer's own clauses (`$legacy_S`) on them, the KB (the
        // next-to-last) turned into a term.
        if self.served.queries.contains(&key) || self.served.updates.contains(&key) {
            let legacy = (super::legacy_kb::legacy_name(f), n);
            if self.defined.contains(&legacy) && n >= 2 {
                let mut given = per_arg.clone();
                given[n - 2].clear();
                out.push(Goal::Call(legacy, given));
            }
        }
        if self.served.queries.contains(&key) || self.served.saves.contains(&key) {
            return;
        }
        if self.served.updates.contains(&key) || self.served.loads.contains(&key) {
            if let Some(last) = per_arg.last() {
                out.push(Goal::Source(last.clone()));
            }
            return;
        }
        if self.defined.contains(&key) {
            out.push(Goal::Call(key, per_arg));
            return;
        }
        // A built-in, or a predicate asserted at run time.
        if extra.is_empty() && !self.defined.contains(&key) {
            // The name and numbers these take or give are atomic: only
            // the term and its arguments share a handle.
            let shared = match (f.as_str(), n) {
                ("=..", 2) => match &args[1] {
                    T::Comp(dot, l) if l.len() == 2 && is(*dot, ".") => {
                        let mut vs = vars_of(0);
                        l[1].vars(&mut vs);
                        Some(vs)
                    }
                    _ => None,
                },
                ("arg", 3) => {
                    let mut vs = vars_of(1);
                    vs.extend(vars_of(2));
                    Some(vs)
                }
                ("functor", 3) => Some(Vec::new()),
                _ => None,
            };
            if let Some(vs) = shared {
                out.push(Goal::Look(goal.all_vars(), key));
                out.push(Goal::Unify(vs, None));
                return;
            }
        }
        if opaque(f, n) {
            out.push(Goal::Look(per_arg.concat(), key));
            return;
        }
        out.push(Goal::Unify(per_arg.concat(), Some(key)));
        // An argument naming a predicate of the files may be a goal it
        // calls (a meta-predicate of the engine's libraries).
        for (i, a) in args.iter().enumerate() {
            let (g, k) = match a {
                T::Atom(g) => (*g, 0),
                T::Comp(g, ga) => (*g, ga.len()),
                _ => continue,
            };
            let Some(arities) = self.arities.get(&g) else {
                continue;
            };
            let others: Vec<u32> = per_arg
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .flat_map(|(_, v)| v.iter().copied())
                .collect();
            for &m in arities {
                if m >= k && m - k <= 8 {
                    let extra = vec![others.clone(); m - k];
                    self.goal(a, &extra, out);
                }
            }
        }
    }
}

/// Runs the analysis; `top` from the start when the caller knows better
/// (a file builds a call that changes clauses as data).
pub(super) fn analyse(program: &Program<'_>) -> Reach {
    let mut defined: HashSet<(Atom, usize)> = HashSet::new();
    let mut arities: HashMap<Atom, Vec<usize>> = HashMap::new();
    for c in program.clauses {
        if let Some(k) = c.key {
            if defined.insert(k) {
                arities.entry(k.0).or_default().push(k.1);
            }
        }
    }
    let mut fl = Flattener {
        defined: &defined,
        arities: &arities,
        served: program.served,
        coroutines: false,
    };
    let flat: Vec<Vec<Goal>> = program
        .clauses
        .iter()
        .map(|c| {
            let mut out = Vec::new();
            if let Some(b) = &c.body {
                fl.goal(b, &[], &mut out);
            }
            out
        })
        .collect();
    let coroutines = fl.coroutines;
    // Each predicate's summary (what a call of it does to its arguments,
    // whatever the caller gives): which argument positions it may unify
    // with one another (structure-insensitive: sharing any part), and
    // which may hold a handle it makes itself (a producer, an unknown
    // goal, a callee's). A fixpoint over every clause: a predicate that
    // only passes handles through (a list utility called on a KB by one
    // caller and on a character list by another) does not mix its callers.
    let mut sums: HashMap<(Atom, usize), Summary> = HashMap::new();
    let heads: Vec<Vec<Vec<u32>>> = program
        .clauses
        .iter()
        .map(|c| c.head.iter().map(T::all_vars).collect())
        .collect();
    loop {
        let mut changed = false;
        for (n, (c, goals)) in program.clauses.iter().zip(&flat).enumerate() {
            let mut cl = Classes::new(c.vars);
            apply_all(&mut cl, goals, &sums);
            let Some(k) = c.key else { continue };
            let head = &heads[n];
            let s = sums.entry(k).or_insert_with(|| Summary::new(k.1));
            for i in 0..head.len() {
                if !s.gen[i] && cl.any(&head[i]) {
                    s.gen[i] = true;
                    changed = true;
                }
                for j in 0..i {
                    if s.same(i, j) {
                        continue;
                    }
                    let shared = head[i].iter().any(|&a| {
                        let ra = cl.find(a);
                        head[j].iter().any(|&b| cl.find(b) == ra)
                    });
                    if shared {
                        s.join(i, j);
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
    let gives = |k: &(Atom, usize)| sums.get(k).is_some_and(|s| s.gen.iter().any(|&g| g));
    // Per clause: the predicates it names, whether a handle can start in
    // it (a producer, an unknown goal, a callee that makes one). A clause
    // with no start and no predicate called with a handle yet has nothing
    // to give (most of them).
    let names: Vec<Vec<(Atom, usize)>> = program
        .clauses
        .iter()
        .map(|c| c.key.into_iter().collect())
        .collect();
    let starts: Vec<bool> = flat
        .iter()
        .map(|goals| {
            goals.iter().any(|g| match g {
                Goal::Source(_) | Goal::Unknown(_) => true,
                Goal::Call(k, _) => gives(k),
                _ => false,
            })
        })
        .collect();
    let mut live: HashSet<(Atom, usize)> = HashSet::new();
    let mut reach = Reach::default();
    loop {
        let mut changed = false;
        for (n, (c, goals)) in program.clauses.iter().zip(&flat).enumerate() {
            if !starts[n] && !names[n].iter().any(|k| live.contains(k)) {
                continue;
            }
            let head = &heads[n];
            // With coroutines, a goal may run after a later binding: every
            // binding of the clause at once.
            let mut all = Classes::new(c.vars);
            if coroutines {
                apply_all(&mut all, goals, &sums);
                if let Some(k) = c.key {
                    for (i, vs) in head.iter().enumerate() {
                        if reach.inputs.contains(&(k.0, k.1, i)) {
                            all.reach(vs);
                        }
                    }
                }
            }
            // Left to right: what is bound when a goal is called (a goal
            // called before a variable is bound to a handle does not see
            // it, unless a coroutine runs it later: then all at once).
            let mut seq = Classes::new(c.vars);
            if let Some(k) = c.key {
                for (i, vs) in head.iter().enumerate() {
                    if reach.inputs.contains(&(k.0, k.1, i)) {
                        seq.reach(vs);
                    }
                }
            }
            let cl = if coroutines { &mut all } else { &mut seq };
            for g in goals {
                match g {
                    Goal::Unify(vs, key) => {
                        if let Some(k) = key {
                            if cl.any(vs) && reach.undefined.insert(*k) {
                                changed = true;
                            }
                        }
                        cl.union(vs);
                    }
                    Goal::Look(vs, k) => {
                        if cl.any(vs) && reach.undefined.insert(*k) {
                            changed = true;
                        }
                    }
                    Goal::Escape(vs) => {
                        if cl.any(vs) {
                            reach.top = true;
                        }
                        cl.union(vs);
                    }
                    Goal::Source(vs) => cl.reach(vs),
                    Goal::Call(k, args) => {
                        for (i, vs) in args.iter().enumerate() {
                            if cl.any(vs) && reach.inputs.insert((k.0, k.1, i)) {
                                changed = true;
                            }
                        }
                        apply_call(cl, k, args, &sums);
                    }
                    Goal::Unknown(vs) => {
                        if cl.any(vs) {
                            reach.top = true;
                        }
                        cl.union(vs);
                        cl.reach(vs);
                    }
                }
            }
            if reach.top {
                return reach;
            }
        }
        if !changed {
            break;
        }
        live = reach.inputs.iter().map(|&(n, a, _)| (n, a)).collect();
    }
    // The positions that may hold a handle at the call or on success: an
    // input, one the predicate makes, or one that shares with an input.
    for (k, s) in &sums {
        for i in 0..k.1 {
            let held =
                s.gen[i] || (0..k.1).any(|j| s.same(i, j) && reach.inputs.contains(&(k.0, k.1, j)));
            if held {
                reach.positions.insert((k.0, k.1, i));
            }
        }
    }
    for &(n, a, i) in &reach.inputs {
        reach.positions.insert((n, a, i));
    }
    reach
}

/// What a call of a predicate does to its arguments (see [`analyse`]).
struct Summary {
    /// Union-find over the argument positions: those that may share.
    parent: Vec<usize>,
    /// Positions that may hold a handle the predicate makes.
    gen: Vec<bool>,
}

impl Summary {
    fn new(arity: usize) -> Summary {
        Summary {
            parent: (0..arity).collect(),
            gen: vec![false; arity],
        }
    }
    fn root(&self, mut i: usize) -> usize {
        while self.parent[i] != i {
            i = self.parent[i];
        }
        i
    }
    fn same(&self, i: usize, j: usize) -> bool {
        self.root(i) == self.root(j)
    }
    fn join(&mut self, i: usize, j: usize) {
        let (a, b) = (self.root(i), self.root(j));
        if a != b {
            self.parent[a] = b;
        }
    }
}

/// A call of `k` with `args` (each argument's variables): the arguments it
/// may make share are unified, those it may give a handle are reached.
fn apply_call(
    cl: &mut Classes,
    k: &(Atom, usize),
    args: &[Vec<u32>],
    sums: &HashMap<(Atom, usize), Summary>,
) {
    let Some(s) = sums.get(k) else { return };
    for i in 0..args.len().min(s.gen.len()) {
        if s.gen[i] {
            cl.reach(&args[i]);
        }
        let r = s.root(i);
        if r != i && r < args.len() {
            let mut both = args[i].clone();
            both.extend(&args[r]);
            cl.union(&both);
        }
    }
}

/// Every binding of a clause's body at once (flow-insensitive).
fn apply_all(cl: &mut Classes, goals: &[Goal], sums: &HashMap<(Atom, usize), Summary>) {
    for g in goals {
        match g {
            Goal::Unify(vs, _) | Goal::Escape(vs) => cl.union(vs),
            Goal::Unknown(vs) => {
                cl.union(vs);
                cl.reach(vs);
            }
            Goal::Source(vs) => cl.reach(vs),
            Goal::Look(..) => {}
            Goal::Call(k, args) => apply_call(cl, k, args, sums),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn program(text: &str) -> Vec<Clause> {
        let (clauses, errors) = sitlog_syntax::read_prolog_clauses(text);
        assert!(errors.is_empty(), "{errors:?}");
        clauses
            .iter()
            .map(|c| {
                let mut store = Store::new();
                let (t, _) = store.from_clause(c);
                let neck = Atom::intern(":-");
                let mut vars = Numbering::default();
                let (head, body) = match store.compound_args(t, neck, 2) {
                    Some(a) => (Some(a[0]), Some(a[1])),
                    None => match store.compound_args(t, neck, 1) {
                        Some(a) => (None, Some(a[0])),
                        None => (Some(t), None),
                    },
                };
                let key = head.and_then(|h| store.functor(h));
                let head = head
                    .map(|h| {
                        store
                            .args(h)
                            .to_vec()
                            .into_iter()
                            .map(|a| T::of(&store, a, &mut vars))
                            .collect()
                    })
                    .unwrap_or_default();
                let body = body.map(|b| T::of(&store, b, &mut vars));
                Clause {
                    key,
                    head,
                    body,
                    vars: vars.count(),
                }
            })
            .collect()
    }

    fn served() -> Served {
        let k = |n: &str, a| (Atom::intern(n), a);
        Served {
            queries: [k("objects_of_a_class", 3)].into(),
            updates: [k("add_object", 4)].into(),
            loads: [k("open_kb", 1)].into(),
            saves: [k("save_kb", 1)].into(),
        }
    }

    fn reached(text: &str) -> Reach {
        let clauses = program(text);
        let served = served();
        analyse(&Program {
            clauses: &clauses,
            served: &served,
        })
    }

    fn at(r: &Reach, name: &str, arity: usize) -> Vec<usize> {
        r.of((Atom::intern(name), arity))
    }

    #[test]
    fn a_handle_reaches_only_what_it_flows_to() {
        let r = reached(
            "load :- open_kb(KB), objects_of_a_class(human, KB, L), add_items(L), show(KB, x).\n\
             add_items([]).\nadd_items([H|T]) :- atom_length(H, _), add_items(T).\n\
             show(KB, Y) :- inner(KB), other(Y).\ninner(K) :- write(K).\nother(_).\n\
             new(N) :- open_kb(K), add_object(a, b, K, N).\nuse :- new(X), keep(X).\nkeep(_).\n\
             read_all(S, W) :- get_char(S, C), rest(C, S, W).\nrest(_, _, []).\n",
        );
        assert!(!r.top);
        assert_eq!(at(&r, "add_items", 1), Vec::<usize>::new());
        assert_eq!(at(&r, "show", 2), vec![0]);
        assert_eq!(at(&r, "inner", 1), vec![0]);
        assert_eq!(at(&r, "other", 1), Vec::<usize>::new());
        // Out of a predicate (no handle at its call: not wrapped), then
        // into another.
        assert_eq!(at(&r, "new", 1), Vec::<usize>::new());
        assert!(r.positions.contains(&(Atom::intern("new"), 1, 0)));
        assert_eq!(at(&r, "keep", 1), vec![0]);
        assert_eq!(at(&r, "rest", 3), Vec::<usize>::new());
        // A built-in passes it on.
        assert!(r.undefined.contains(&(Atom::intern("write"), 1)));
    }

    #[test]
    fn a_predicate_that_passes_a_handle_through_does_not_mix_its_callers() {
        // `app/3` gets a KB from one caller and characters from another
        // (the original's `append/3` in its KB updates and in its reader):
        // the reader is not reached, the KB user's callee is.
        let r = reached(
            "upd(L) :- open_kb(KB), app(KB, [x], New), show(New, L).\nshow(_, _).\n\
             app([], L, L).\napp([H|T], L, [H|R]) :- app(T, L, R).\n\
             conv(A, T) :- atom_chars(A, Cs), app(Cs, ['.'], Cs1), parse(Cs1, T).\nparse(_, _).\n\
             rd(S, T) :- get_char(S, C), conv(C, T).\n",
        );
        assert!(!r.top);
        assert_eq!(at(&r, "app", 3), vec![0]);
        assert_eq!(at(&r, "show", 2), vec![0]);
        assert_eq!(at(&r, "parse", 2), Vec::<usize>::new());
        assert_eq!(at(&r, "conv", 2), Vec::<usize>::new());
        assert_eq!(at(&r, "rd", 2), Vec::<usize>::new());
        // `pair/2` makes its arguments share: a handle bound into one
        // after the call reaches what the other is given to.
        let r = reached(
            "pair(X, Y) :- X = f(Z), Y = g(Z).\nshow(_).\n\
             late :- pair(A, B), open_kb(KB), A = f(KB), show(B).\n",
        );
        assert_eq!(at(&r, "show", 1), vec![0]);
    }

    #[test]
    fn meta_calls_are_followed_or_give_up() {
        // A known goal in a meta-call is followed, with call/N's arguments.
        let r = reached(
            "a :- open_kb(KB), call(p, KB), findall(X, q(KB, X), _), maplist(r, [KB]).\n\
             p(_).\nq(_, _).\nr(_).\ns(_).\n",
        );
        assert!(!r.top);
        assert_eq!(at(&r, "p", 1), vec![0]);
        assert_eq!(at(&r, "q", 2), vec![0]);
        assert_eq!(at(&r, "r", 1), vec![0]);
        assert_eq!(at(&r, "s", 1), Vec::<usize>::new());
        // An unknown goal given a handle: anything may be reached.
        let r = reached("a(G) :- open_kb(KB), call(G, KB).\np(_).\n");
        assert!(r.top);
        assert_eq!(at(&r, "p", 1), vec![0]);
        let r = reached("a(G) :- open_kb(KB), X =.. [G, KB], call(X).\n");
        assert!(r.top);
        // An unknown goal called before a handle exists does not.
        let r = reached("a(G) :- call(G, X), open_kb(X).\np(_).\n");
        assert!(!r.top);
        assert_eq!(at(&r, "p", 1), Vec::<usize>::new());
        // ... unless coroutines may run it later.
        let r = reached("a(G) :- freeze(Y, true), call(G, X), open_kb(X).\n");
        assert!(r.top);
        // A handle given to the database or thrown.
        assert!(reached("a :- open_kb(KB), assertz(kb(KB)).\n").top);
        assert!(reached("a :- open_kb(KB), throw(kb(KB)).\n").top);
        assert!(!reached("a :- open_kb(_), assertz(kb(x)).\n").top);
        // What the database gives back may hold one.
        let r = reached("a :- bb_get(k, X), p(X).\np(_).\n");
        assert_eq!(at(&r, "p", 1), vec![0]);
        // A goal built with =.. from a list's elements: the name is an atom,
        // the element given back may be a handle, the name stays none.
        let r = reached(
            "inc(_, [], A, A).\ninc(P, [X|R], A, N) :- G =.. [P, X], G, inc(P, R, [X|A], N).\n\
             f(L, N) :- inc(ok, L, [], N).\n",
        );
        assert!(!r.top);
        assert_eq!(at(&r, "inc", 4), vec![2]);
        // `predsort/3` calls its closure on the elements; `M:G` is `G`.
        let r = reached(
            "a :- open_kb(KB), predsort(cmp, [KB, x], _).\ncmp(_, A, B) :- p(A), q(B).\n\
             p(_).\nq(_).\n",
        );
        assert!(!r.top);
        assert_eq!(at(&r, "p", 1), vec![0]);
        assert_eq!(at(&r, "q", 1), vec![0]);
        assert!(reached("a(P) :- open_kb(KB), predsort(P, [KB], _).\n").top);
        let r = reached("a :- open_kb(KB), user:p(KB), call(user:q, KB).\np(_).\nq(_).\n");
        assert_eq!(at(&r, "p", 1), vec![0]);
        assert_eq!(at(&r, "q", 1), vec![0]);
        assert!(reached("a(G) :- open_kb(KB), findall(X, user:G, _), call(user:G, KB).\n").top);
        // Type tests, arithmetic and text give no handle on.
        let r =
            reached("a :- open_kb(KB), length(KB, N), atom_length(KB, M), p(N, M).\np(_, _).\n");
        assert_eq!(at(&r, "p", 2), Vec::<usize>::new());
    }
}
