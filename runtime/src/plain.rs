//! Plain user functions run natively (issue 37): a function whose every
//! clause is *plain* is also kept, when the engine loads it, in a small
//! native form ([`PlainFn`]) that a call runs in Rust before it would
//! become a query; the engine runs everything else.
//!
//! Plain: a head whose arguments are variables, atoms, integers, or
//! compounds and lists of these (`[P|Ps]`, `at(R, O)`); a body
//! that is a conjunction of `true`, `fail`/`false`, `!`, `V is E` (`E`
//! over integers, floats and bound variables with `+ - * / // mod rem min
//! max abs`, unary `-` and `+`, computed as the engine computes them or
//! left to it: [`num`]), `< > =< >= =:= =\=` between such expressions,
//! `==`/`\==` and `=` between bound variables, atoms, integers and
//! compounds or lists built of these (`=` with a fresh variable on one
//! side binds it), and `assign_func_value/1` of such a value (`walk(Ps)`,
//! `found(P)`, `[P|Seen]`: built from the bound variables' terms, which
//! are shared, not copied; the last assignment wins, as the prelude's
//! `bb_b_put/2` does). A variable read before it is bound makes the clause
//! not plain.
//!
//! Invariant (fidelity): the native form gives a value only where the
//! engine gives the same one, and hands every other call to the engine,
//! whose result and error it then is by construction. It runs a call only
//! when every argument is ground with no big integer and no float but a
//! sure one ([`num::sure_float`]) in it, and
//! neither they nor the caller's variables (which a query sends) nest
//! deeper than [`MAX_DEPTH`], and
//! gives up (the engine runs the call) on an argument or a value of
//! another type than an operation takes (a type error, or an atom where
//! Prolog would fail), an overflow, a division by zero, a function that
//! fails (every clause failed, or a goal failed after a cut) and one that
//! succeeds without assigning a value. So it only ever takes the path on
//! which the engine succeeds with a value: the first clause whose head
//! matches and whose goals all hold, in order, its last assigned value.
//! Nothing is native in a program whose Prolog changes or looks at clauses
//! as data (`assert`, `retract`, `clause`, ... named anywhere), defines a
//! predicate the plain form relies on (`assign_func_value/1`), or runs
//! under the legacy profile (checked by [`PlainScan`]'s caller).
//!
//! The same clauses also run on native values (`val`: [`PlainFns::call_vals`],
//! what `Cx::nat_plain` reaches through the engine's handle), under the
//! same invariant and the same refusals; and a build reads which
//! functions are plain from the files' text ([`plain_names`], a guess the
//! run checks). This module needs no engine: `prolog` (feature `prolog`)
//! loads the forms, the compiler without it reads the names.

// The module doc names the private items that keep its invariant.
#![allow(rustdoc::private_intra_doc_links)]

use crate::arith::Number;
use crate::store::Store;
use crate::term::{Repr, Term, Value, Var};
use sitlog_syntax::{atoms, Atom};
use std::collections::{HashMap, HashSet};

mod form;
pub mod num;
pub mod rt;
pub mod slots;
mod val;

pub use form::{atomic, plain_forms, Atomic};

/// The names whose mention anywhere in the application's Prolog turns the
/// native form off: they change or look at clauses, or at the code, as
/// data, or redefine what a plain body calls.
const OFF: &[&str] = &[
    "assert",
    "asserta",
    "assertz",
    "retract",
    "retractall",
    "abolish",
    "clause",
    "term_expansion",
    "goal_expansion",
    "load_files",
    "consult",
    "ensure_loaded",
    "include",
    "module",
];

/// The fewest inferences a call's limit must allow for the native form to
/// run it (the engine's inference count of a plain call is a few per
/// goal: under a smaller limit the engine decides whether it is
/// exceeded).
const MIN_INFERENCES: u64 = 1000;

/// An argument of a plain clause's head.
#[derive(Clone, Debug)]
pub enum PArg {
    /// A variable's first occurrence: it takes the argument.
    Bind(u16),
    /// A variable again: the argument must be identical to it.
    Same(u16),
    /// A variable's first occurrence that nothing reads (`_`, a singleton):
    /// it takes any argument, and no register.
    Skip,
    Const(Term),
    /// A compound (a list cell too): the argument must be one of this
    /// name and arity whose arguments match these.
    Struct(Atom, Box<[PArg]>),
}

/// An operand of `==`, `\==`, `=` or `assign_func_value/1`.
#[derive(Clone, Debug)]
pub enum Opnd {
    Var(u16),
    Const(Term),
    /// `name(args..)` (arity at least 1) built of bound variables and
    /// constants.
    Build(Atom, Box<[Opnd]>),
}

/// How deep a head argument or an operand of a plain clause nests (deeper:
/// not plain), so that a value built from arguments at most [`MAX_DEPTH`]
/// deep stays far within the engine's `PROLOG_MAX_DEPTH`.
const MAX_PATTERN_DEPTH: usize = 64;

#[derive(Clone, Copy, Debug)]
pub enum Bin {
    Add,
    Sub,
    Mul,
    IntDiv,
    Mod,
    Rem,
    Min,
    Max,
    /// `/`: native only with a float operand ([`num`]).
    Div,
}

#[derive(Clone, Copy, Debug)]
pub enum Un {
    Neg,
    Pos,
    Abs,
}

#[derive(Clone, Debug)]
pub enum PExpr {
    Var(u16),
    Int(i64),
    /// A float constant ([`num::sure_float`]).
    Float(f64),
    Un(Un, Box<PExpr>),
    Bin(Bin, Box<PExpr>, Box<PExpr>),
}

#[derive(Clone, Copy, Debug)]
pub enum Cmp {
    Lt,
    Gt,
    Le,
    Ge,
    Eq,
    Ne,
}

#[derive(Clone, Debug)]
pub enum PGoal {
    True,
    Fail,
    Cut,
    /// `V is E`, `V` fresh.
    IsFresh(u16, PExpr),
    /// `V is E`, `V` bound: it must be the integer `E` gives.
    IsBound(u16, PExpr),
    Cmp(Cmp, PExpr, PExpr),
    /// `==` (`true`) or `\==` (`false`).
    Ident(bool, Opnd, Opnd),
    /// `V = X` with `V` fresh.
    Bind(u16, Opnd),
    Assign(Opnd),
    /// `( C -> T ; E )`: `C` tests only (it binds no variable, cuts
    /// nothing, assigns nothing), `T` and `E` plain conjunctions that bind
    /// the same variables (a cut in them cuts the clause, as in Prolog).
    Ite(Box<[PGoal]>, Box<[PGoal]>, Box<[PGoal]>),
}

impl PGoal {
    /// Whether the goal only tests (binds, cuts and assigns nothing).
    fn is_test(&self) -> bool {
        matches!(
            self,
            PGoal::True | PGoal::Fail | PGoal::IsBound(..) | PGoal::Cmp(..) | PGoal::Ident(..)
        )
    }

    /// The goals the engine counts for it.
    fn goals(&self) -> usize {
        match self {
            PGoal::Ite(c, t, e) => {
                1 + [c, t, e]
                    .iter()
                    .map(|g| g.iter().map(PGoal::goals).sum::<usize>())
                    .sum::<usize>()
            }
            _ => 1,
        }
    }
}

#[derive(Clone, Debug)]
pub struct PClause {
    vars: usize,
    head: Box<[PArg]>,
    body: Box<[PGoal]>,
}

/// A plain user function: its clauses in the engine's order.
#[derive(Clone, Debug)]
pub struct PlainFn {
    clauses: Box<[PClause]>,
    /// At least the inferences the engine counts for a call.
    inferences: u64,
    /// The most variables a clause has (the registers a call needs).
    vars: usize,
    /// [`PlainFn::fingerprint`], made at its first use (a run compares it
    /// once with a compiled function's).
    fingerprint: std::sync::OnceLock<String>,
}

/// The native forms of an application's plain functions.
#[derive(Clone, Debug, Default)]
pub(super) struct PlainFns {
    map: crate::functions::KeyMap<PlainFn>,
}

/// Reads the application's clauses and directives as the engine loads
/// them ([`super::consult::prepare`]) and keeps the plain functions.
#[derive(Default)]
pub(super) struct PlainScan {
    /// Each predicate's clauses so far, `None` once one is not plain.
    fns: HashMap<(Atom, usize), Option<Vec<PClause>>>,
    /// A clause or directive names one of [`OFF`].
    off: bool,
}

impl PlainScan {
    /// A directive: only looked at for the names of [`OFF`].
    pub(super) fn directive(&mut self, store: &Store, goal: Term) {
        if names_off(store, goal) {
            self.off = true;
        }
    }

    /// A clause of `key`, as the engine gets it.
    pub(super) fn clause(
        &mut self,
        store: &Store,
        key: (Atom, usize),
        head: Term,
        body: Option<Term>,
    ) {
        // A definition of `assign_func_value/1` replaces the prelude's.
        if key.0.as_str() == "assign_func_value"
            || names_off(store, head)
            || body.is_some_and(|b| names_off(store, b))
        {
            self.off = true;
        }
        let entry = self.fns.entry(key).or_insert_with(|| Some(Vec::new()));
        if let Some(clauses) = entry {
            match plain_clause(store, head, body) {
                Some(c) => clauses.push(c),
                None => *entry = None,
            }
        }
    }

    /// The plain functions (none if the application names one of [`OFF`]).
    pub(super) fn finish(self) -> PlainFns {
        if self.off {
            return PlainFns::default();
        }
        let map = self
            .fns
            .into_iter()
            .filter(|((name, _), _)| !name.as_str().starts_with('$'))
            .filter_map(|(key, clauses)| {
                let clauses = clauses?;
                let goals: usize = clauses
                    .iter()
                    .map(|c| c.body.iter().map(PGoal::goals).sum::<usize>() + 1)
                    .sum();
                let vars = clauses.iter().map(|c| c.vars).max().unwrap_or(0);
                Some((
                    key,
                    PlainFn {
                        clauses: clauses.into(),
                        inferences: (goals as u64 + 1).saturating_mul(4),
                        vars,
                        fingerprint: Default::default(),
                    },
                ))
            })
            .collect();
        PlainFns { map }
    }
}

/// The functions of the Prolog files `files` (each its text, and its
/// clauses if read already) that are plain as the files read (without the
/// files their directives consult): what a build may expect to run
/// natively. Only a guess for generated code, which asks at run time
/// (`PlainFns::call_vals` through the engine that loaded the run's
/// sources, `None` there taking the term path); the engine's own scan
/// (`PlainScan` as `prolog::consult::prepare` loads the files) decides.
pub fn plain_names(files: &[(&str, Option<&[sitlog_syntax::Clause]>)]) -> HashSet<(Atom, usize)> {
    scan_files(files).keys().collect()
}

/// The plain functions of `files` as [`plain_names`] reads them, their
/// forms too.
fn scan_files(files: &[(&str, Option<&[sitlog_syntax::Clause]>)]) -> PlainFns {
    let mut scan = PlainScan::default();
    let neck = Atom::intern(":-");
    for &(text, clauses) in files {
        let read;
        let clauses: &[sitlog_syntax::Clause] = match clauses {
            Some(clauses) => clauses,
            None => {
                read = sitlog_syntax::read_prolog_clauses(text).0;
                &read
            }
        };
        for c in clauses {
            let mut store = Store::new();
            let (t, _) = store.from_clause(c);
            if let Some(a) = store.compound_args(t, neck, 1) {
                let g = a[0];
                scan.directive(&store, g);
                continue;
            }
            let (head, body) = match store.compound_args(t, neck, 2) {
                Some(a) => (a[0], Some(a[1])),
                None => (t, None),
            };
            if let Some(key) = store.functor(head) {
                scan.clause(&store, key, head, body);
            }
        }
    }
    scan.finish()
}

impl PlainFns {
    /// The plain functions' names and arities.
    pub(super) fn keys(&self) -> impl Iterator<Item = (Atom, usize)> + '_ {
        self.map.keys().copied()
    }

    /// The value of `name(args..)` if it is a plain function that the
    /// native form runs to a value under an inference limit of `limit`;
    /// `None`: the engine runs the call (see the module's invariant).
    pub(super) fn call(
        &self,
        store: &mut Store,
        name: Atom,
        args: &[Term],
        limit: u64,
    ) -> Option<Term> {
        let f = self.map.get(&(name, args.len()))?;
        if limit < MIN_INFERENCES.max(f.inferences) {
            return None;
        }
        if !args.iter().all(|&a| sure(store, a, true)) {
            return None;
        }
        // Registers on the stack for the usual clause (no allocation).
        let mut small = [Term::EMPTY; 16];
        let mut big = Vec::new();
        for c in f.clauses.iter() {
            let regs: &mut [Term] = if c.vars <= small.len() {
                &mut small[..c.vars]
            } else {
                big.clear();
                big.resize(c.vars, Term::EMPTY);
                &mut big
            };
            match run_clause(store, c, args, regs) {
                Outcome::Value(v) => return Some(v),
                Outcome::Fail { cut: false } => continue,
                Outcome::Fail { cut: true } | Outcome::NoValue | Outcome::Unsure => return None,
            }
        }
        None
    }
}

/// The deepest term the native form takes, as an argument or in the
/// caller's variables (a list counts a level per element, as for the
/// engine): deeper, the engine decides (it refuses what nests deeper
/// than `PROLOG_MAX_DEPTH`, with an error naming the function).
const MAX_DEPTH: usize = 10_000;

/// The index of the list cell `t` is, if the store knows it ground.
fn ground_cell(store: &Store, t: Term) -> Option<u32> {
    match t.0 {
        Repr::Struct(i)
            if store.known_ground(t) && store.compound_args(t, atoms::DOT, 2).is_some() =>
        {
            Some(i)
        }
        _ => None,
    }
}

/// Whether `t` nests at most [`MAX_DEPTH`] levels and, if `strict`, is
/// ground with no float that is not sure ([`num::sure_float`]), big
/// integer or improper list (`[a|b]`) anywhere
/// in it: the engine cannot give back an answer that holds an improper
/// list (it fails the call: see [`value`]). A strict argument that is the
/// list `Store::plain_memo` remembers, or its tail, is taken without a walk.
pub(super) fn sure(store: &Store, t: Term, strict: bool) -> bool {
    let t = store.deref(t);
    match store.value(t) {
        Value::Atom(_) | Value::Int(_) => return true,
        Value::Float(f) => return !strict || num::sure_float(f),
        Value::Var(_) | Value::BigInt(_) => return !strict,
        Value::Compound(..) => {}
    }
    let cell = if strict { ground_cell(store, t) } else { None };
    if let Some(i) = cell {
        if let Some(m) = store.plain_memo.get(store.epoch) {
            let last = Term(Repr::Struct(m));
            if m == i || store.args(last)[1] == t {
                store.plain_memo.set(store.epoch, i);
                return true;
            }
        }
    }
    let ok = sure_walk(store, t, strict);
    if let (true, Some(i)) = (ok, cell) {
        store.plain_memo.set(store.epoch, i);
    }
    ok
}

/// [`sure`] of a compound, walked.
fn sure_walk(store: &Store, t: Term, strict: bool) -> bool {
    let mut stack = vec![(t, 0usize)];
    while let Some((t, depth)) = stack.pop() {
        if depth > MAX_DEPTH {
            return false;
        }
        match store.value(store.deref(t)) {
            Value::Atom(_) | Value::Int(_) => {}
            Value::Float(f) => {
                if strict && !num::sure_float(f) {
                    return false;
                }
            }
            Value::Var(_) | Value::BigInt(_) => {
                if strict {
                    return false;
                }
            }
            Value::Compound(f, args) => {
                if strict && f == atoms::DOT && args.len() == 2 && !list_tail(store, args[1]) {
                    return false;
                }
                stack.extend(args.iter().map(|&a| (a, depth + 1)))
            }
        }
    }
    true
}

/// Whether `t` is `[]` or a list cell: a cell with it as its tail is not
/// an improper list's last.
fn list_tail(store: &Store, t: Term) -> bool {
    let t = store.deref(t);
    store.atom_of(t) == Some(atoms::NIL) || store.compound_args(t, atoms::DOT, 2).is_some()
}

/// Whether `t` names one of [`OFF`] (as an atom or a functor) anywhere.
fn names_off(store: &Store, t: Term) -> bool {
    let mut stack = vec![t];
    while let Some(t) = stack.pop() {
        match store.value(store.deref(t)) {
            Value::Atom(a) if OFF.contains(&a.as_str()) => return true,
            Value::Compound(f, args) => {
                if OFF.contains(&f.as_str()) {
                    return true;
                }
                stack.extend_from_slice(args);
            }
            _ => {}
        }
    }
    false
}

/// The variables of a clause being read, numbered in order of first
/// occurrence, and which are bound at the point reached.
#[derive(Default)]
struct Scope {
    vars: Vec<Var>,
    bound: Vec<bool>,
}

impl Scope {
    /// The variable's number and whether it was bound already.
    fn var(&mut self, v: Var) -> Option<(u16, bool)> {
        if let Some(i) = self.vars.iter().position(|&w| w == v) {
            return Some((i as u16, self.bound[i]));
        }
        if self.vars.len() >= u16::MAX as usize {
            return None;
        }
        self.vars.push(v);
        self.bound.push(false);
        Some(((self.vars.len() - 1) as u16, false))
    }

    fn bind(&mut self, i: u16) {
        self.bound[i as usize] = true;
    }
}

/// An atom or an integer.
fn constant(store: &Store, t: Term) -> Option<Term> {
    match store.value(t) {
        Value::Atom(a) => Some(Term::atom(a)),
        Value::Int(i) => Some(Term::int(i)),
        _ => None,
    }
}

fn plain_clause(store: &Store, head: Term, body: Option<Term>) -> Option<PClause> {
    let mut scope = Scope::default();
    let mut args = Vec::new();
    for &a in store.args(head) {
        args.push(head_arg(store, a, &mut scope, 0)?);
    }
    let goals = match body {
        Some(b) => conj(store, b, &mut scope, 0)?,
        None => Vec::new(),
    };
    // A first occurrence in the head that nothing reads takes no register.
    let mut read = vec![false; scope.vars.len()];
    args.iter().for_each(|a| arg_reads(a, &mut read));
    goals_read(&goals, &mut read);
    for a in args.iter_mut() {
        skip_unread(a, &read);
    }
    Some(PClause {
        vars: scope.vars.len(),
        head: args.into(),
        body: goals.into(),
    })
}

/// `Bind(i)` of a variable `read` says nothing reads made [`PArg::Skip`].
fn skip_unread(a: &mut PArg, read: &[bool]) {
    match a {
        PArg::Bind(i) if !read[*i as usize] => *a = PArg::Skip,
        PArg::Struct(_, ps) => ps.iter_mut().for_each(|p| skip_unread(p, read)),
        _ => {}
    }
}

/// Marks the variables a head argument reads (a repeated one).
fn arg_reads(a: &PArg, read: &mut [bool]) {
    match a {
        PArg::Same(i) => read[*i as usize] = true,
        PArg::Struct(_, ps) => ps.iter().for_each(|p| arg_reads(p, read)),
        PArg::Bind(_) | PArg::Skip | PArg::Const(_) => {}
    }
}

fn opnd_reads(o: &Opnd, read: &mut [bool]) {
    match o {
        Opnd::Var(i) => read[*i as usize] = true,
        Opnd::Build(_, xs) => xs.iter().for_each(|x| opnd_reads(x, read)),
        Opnd::Const(_) => {}
    }
}

fn expr_reads(e: &PExpr, read: &mut [bool]) {
    match e {
        PExpr::Var(i) => read[*i as usize] = true,
        PExpr::Int(_) | PExpr::Float(_) => {}
        PExpr::Un(_, x) => expr_reads(x, read),
        PExpr::Bin(_, x, y) => {
            expr_reads(x, read);
            expr_reads(y, read);
        }
    }
}

/// Marks the variables the goals read.
fn goals_read(goals: &[PGoal], read: &mut [bool]) {
    for g in goals {
        match g {
            PGoal::True | PGoal::Fail | PGoal::Cut => {}
            PGoal::IsFresh(_, e) => expr_reads(e, read),
            PGoal::IsBound(i, e) => {
                read[*i as usize] = true;
                expr_reads(e, read);
            }
            PGoal::Cmp(_, x, y) => {
                expr_reads(x, read);
                expr_reads(y, read);
            }
            PGoal::Ident(_, x, y) => {
                opnd_reads(x, read);
                opnd_reads(y, read);
            }
            PGoal::Bind(_, o) | PGoal::Assign(o) => opnd_reads(o, read),
            PGoal::Ite(c, t, e) => {
                goals_read(c, read);
                goals_read(t, read);
                goals_read(e, read);
            }
        }
    }
}

/// The plain goals of the conjunction `b`, left to right (`depth`: how
/// deep in if-then-elses).
fn conj(store: &Store, b: Term, scope: &mut Scope, depth: usize) -> Option<Vec<PGoal>> {
    if depth > MAX_PATTERN_DEPTH {
        return None;
    }
    let mut stack = vec![b];
    let mut flat = Vec::new();
    while let Some(g) = stack.pop() {
        let g = store.deref(g);
        match store.value(g) {
            Value::Compound(f, a) if f.as_str() == "," && a.len() == 2 => {
                stack.push(a[1]);
                stack.push(a[0]);
            }
            _ => flat.push(g),
        }
    }
    let mut goals = Vec::with_capacity(flat.len());
    for g in flat {
        goals.push(plain_goal(store, g, scope, depth)?);
    }
    Some(goals)
}

/// `( C -> T ; E )` (`c_t` the `->`, `e` the else) as [`PGoal::Ite`], if
/// plain: the condition only tests, and the variables bound after it are
/// the same whichever branch ran.
fn if_then_else(
    store: &Store,
    c_t: Term,
    e: Term,
    scope: &mut Scope,
    depth: usize,
) -> Option<PGoal> {
    let [c, t] = match store.value(store.deref(c_t)) {
        Value::Compound(f, a) if f.as_str() == "->" && a.len() == 2 => [a[0], a[1]],
        _ => return None,
    };
    let before = scope.bound.clone();
    let cg = conj(store, c, scope, depth + 1)?;
    if !cg.iter().all(PGoal::is_test)
        || scope.bound.iter().filter(|&&b| b).count() != before.iter().filter(|&&b| b).count()
    {
        return None;
    }
    let tg = conj(store, t, scope, depth + 1)?;
    let after_t = scope.bound.clone();
    for (k, b) in scope.bound.iter_mut().enumerate() {
        *b = before.get(k).copied().unwrap_or(false);
    }
    let eg = conj(store, e, scope, depth + 1)?;
    let same =
        (0..scope.bound.len()).all(|k| scope.bound[k] == after_t.get(k).copied().unwrap_or(false));
    same.then(|| PGoal::Ite(cg.into(), tg.into(), eg.into()))
}

/// A head argument: a variable (its first occurrence binds it), a constant,
/// or a compound of these.
fn head_arg(store: &Store, t: Term, scope: &mut Scope, depth: usize) -> Option<PArg> {
    if depth > MAX_PATTERN_DEPTH {
        return None;
    }
    let t = store.deref(t);
    if let Some(v) = store.var_of(t) {
        let (i, bound) = scope.var(v)?;
        if bound {
            return Some(PArg::Same(i));
        }
        scope.bind(i);
        return Some(PArg::Bind(i));
    }
    if let Value::Compound(f, a) = store.value(t) {
        let mut args = Vec::with_capacity(a.len());
        for &x in a {
            args.push(head_arg(store, x, scope, depth + 1)?);
        }
        return Some(PArg::Struct(f, args.into()));
    }
    constant(store, t).map(PArg::Const)
}

/// A bound variable, a constant, or a compound built of these.
fn operand(store: &Store, t: Term, scope: &mut Scope) -> Option<Opnd> {
    operand_at(store, t, scope, 0)
}

fn operand_at(store: &Store, t: Term, scope: &mut Scope, depth: usize) -> Option<Opnd> {
    if depth > MAX_PATTERN_DEPTH {
        return None;
    }
    let t = store.deref(t);
    match store.var_of(t) {
        Some(v) => match scope.var(v)? {
            (i, true) => Some(Opnd::Var(i)),
            (_, false) => None,
        },
        None => match store.value(t) {
            Value::Compound(f, a) => {
                let mut args = Vec::with_capacity(a.len());
                for &x in a {
                    args.push(operand_at(store, x, scope, depth + 1)?);
                }
                Some(Opnd::Build(f, args.into()))
            }
            _ => constant(store, t).map(Opnd::Const),
        },
    }
}

fn expr(store: &Store, t: Term, scope: &mut Scope, depth: usize) -> Option<PExpr> {
    if depth > 64 {
        return None;
    }
    let t = store.deref(t);
    match store.value(t) {
        Value::Var(v) => match scope.var(v)? {
            (i, true) => Some(PExpr::Var(i)),
            (_, false) => None,
        },
        Value::Int(i) => Some(PExpr::Int(i)),
        Value::Float(f) if num::sure_float(f) => Some(PExpr::Float(f)),
        Value::Compound(f, a) if a.len() == 1 => {
            let op = match f.as_str() {
                "-" => Un::Neg,
                "+" => Un::Pos,
                "abs" => Un::Abs,
                _ => return None,
            };
            Some(PExpr::Un(
                op,
                Box::new(expr(store, a[0], scope, depth + 1)?),
            ))
        }
        Value::Compound(f, a) if a.len() == 2 => {
            let op = match f.as_str() {
                "+" => Bin::Add,
                "-" => Bin::Sub,
                "*" => Bin::Mul,
                "//" => Bin::IntDiv,
                "mod" => Bin::Mod,
                "rem" => Bin::Rem,
                "min" => Bin::Min,
                "max" => Bin::Max,
                "/" => Bin::Div,
                _ => return None,
            };
            let (x, y) = (a[0], a[1]);
            Some(PExpr::Bin(
                op,
                Box::new(expr(store, x, scope, depth + 1)?),
                Box::new(expr(store, y, scope, depth + 1)?),
            ))
        }
        _ => None,
    }
}

fn plain_goal(store: &Store, g: Term, scope: &mut Scope, depth: usize) -> Option<PGoal> {
    match store.value(g) {
        Value::Compound(f, a) if a.len() == 2 && f.as_str() == ";" => {
            if_then_else(store, a[0], a[1], scope, depth)
        }
        Value::Atom(a) => match a.as_str() {
            "true" => Some(PGoal::True),
            "fail" | "false" => Some(PGoal::Fail),
            "!" => Some(PGoal::Cut),
            _ => None,
        },
        Value::Compound(f, a) if a.len() == 1 && f.as_str() == "assign_func_value" => {
            Some(PGoal::Assign(operand(store, a[0], scope)?))
        }
        Value::Compound(f, a) if a.len() == 2 => {
            let (x, y) = (a[0], a[1]);
            let cmp = match f.as_str() {
                "<" => Some(Cmp::Lt),
                ">" => Some(Cmp::Gt),
                "=<" => Some(Cmp::Le),
                ">=" => Some(Cmp::Ge),
                "=:=" => Some(Cmp::Eq),
                "=\\=" => Some(Cmp::Ne),
                _ => None,
            };
            if let Some(c) = cmp {
                return Some(PGoal::Cmp(
                    c,
                    expr(store, x, scope, 0)?,
                    expr(store, y, scope, 0)?,
                ));
            }
            match f.as_str() {
                "is" => {
                    let e = expr(store, y, scope, 0)?;
                    let v = store.var_of(store.deref(x))?;
                    match scope.var(v)? {
                        (i, true) => Some(PGoal::IsBound(i, e)),
                        (i, false) => {
                            scope.bind(i);
                            Some(PGoal::IsFresh(i, e))
                        }
                    }
                }
                "==" | "\\==" => Some(PGoal::Ident(
                    f.as_str() == "==",
                    operand(store, x, scope)?,
                    operand(store, y, scope)?,
                )),
                "=" => {
                    // One side a fresh variable, the other bound or a constant.
                    let fresh = |t: Term, scope: &mut Scope| {
                        let v = store.var_of(store.deref(t))?;
                        match scope.var(v)? {
                            (i, false) => Some(i),
                            (_, true) => None,
                        }
                    };
                    if let Some(i) = fresh(x, scope) {
                        let o = operand(store, y, scope)?;
                        scope.bind(i);
                        return Some(PGoal::Bind(i, o));
                    }
                    if let Some(i) = fresh(y, scope) {
                        let o = operand(store, x, scope)?;
                        scope.bind(i);
                        return Some(PGoal::Bind(i, o));
                    }
                    // Both bound: ground values unify when identical.
                    Some(PGoal::Ident(
                        true,
                        operand(store, x, scope)?,
                        operand(store, y, scope)?,
                    ))
                }
                _ => None,
            }
        }
        _ => None,
    }
}

/// How a clause ran.
enum Outcome {
    Value(Term),
    /// A head argument or a goal failed (after the clause's cut: `cut`).
    Fail {
        cut: bool,
    },
    /// The clause succeeded without assigning a value.
    NoValue,
    /// Not decided here (a type the operation does not take, an overflow).
    Unsure,
}

/// `x op y` on integers, `Err` (not decided here) on an overflow or a
/// division by zero.
fn bin(op: Bin, x: i64, y: i64) -> Result<i64, ()> {
    Ok(match op {
        Bin::Add => x.checked_add(y).ok_or(())?,
        Bin::Sub => x.checked_sub(y).ok_or(())?,
        Bin::Mul => x.checked_mul(y).ok_or(())?,
        // Prolog's `//` truncates toward zero (the engine's
        // `integer_rounding_function`), as Rust's `/`.
        Bin::IntDiv => x.checked_div(y).ok_or(())?,
        Bin::Rem => x.checked_rem(y).ok_or(())?,
        // `mod`: the sign of the divisor.
        Bin::Mod => {
            let r = x.checked_rem(y).ok_or(())?;
            if r != 0 && ((r < 0) != (y < 0)) {
                r + y
            } else {
                r
            }
        }
        Bin::Min => x.min(y),
        Bin::Max => x.max(y),
        // Of two integers: the engine's float ([`num`]).
        Bin::Div => return Err(()),
    })
}

/// Whether `x op y` holds.
fn compare(op: Cmp, x: i64, y: i64) -> bool {
    match op {
        Cmp::Lt => x < y,
        Cmp::Gt => x > y,
        Cmp::Le => x <= y,
        Cmp::Ge => x >= y,
        Cmp::Eq => x == y,
        Cmp::Ne => x != y,
    }
}

/// The number `t` is (a sure float, [`num::sure_float`]), `Err` (not
/// decided here) for anything else.
fn number(store: &Store, t: Term) -> Result<Number, ()> {
    match store.value(store.deref(t)) {
        Value::Int(i) => Ok(Number::Int(i)),
        Value::Float(f) => num::of_float(f).ok_or(()),
        _ => Err(()),
    }
}

fn eval(store: &Store, e: &PExpr, regs: &[Term]) -> Result<Number, ()> {
    Ok(match e {
        PExpr::Var(i) => number(store, regs[*i as usize])?,
        PExpr::Int(i) => Number::Int(*i),
        PExpr::Float(f) => Number::Float(*f),
        PExpr::Un(op, x) => num::un(*op, eval(store, x, regs)?).ok_or(())?,
        PExpr::Bin(op, x, y) => {
            num::bin(*op, eval(store, x, regs)?, eval(store, y, regs)?).ok_or(())?
        }
    })
}

/// The operand's term: a compound built in `store`, its variables' terms
/// shared (a list argument is not copied). `None` for a list cell whose
/// tail is neither a cell nor `[]` (`[x|y]`, `[X|T]` with `T` an atom):
/// the engine fails a call whose answer holds an improper list (its
/// conversion of the answer panics on the engine's thread), so such a
/// value is the engine's to decide. The arguments hold none ([`sure`]).
fn value(store: &mut Store, o: &Opnd, regs: &[Term]) -> Option<Term> {
    match o {
        Opnd::Var(i) => Some(regs[*i as usize]),
        Opnd::Const(t) => Some(*t),
        Opnd::Build(f, args) => {
            let mut small = [Term::EMPTY; 8];
            let mut big = Vec::new();
            let ts: &mut [Term] = if args.len() <= small.len() {
                &mut small[..args.len()]
            } else {
                big.resize(args.len(), Term::EMPTY);
                &mut big
            };
            for (t, a) in ts.iter_mut().zip(args.iter()) {
                *t = value(store, a, regs)?;
            }
            if *f == atoms::DOT && ts.len() == 2 && !list_tail(store, ts[1]) {
                return None;
            }
            Some(store.compound(*f, ts))
        }
    }
}

/// The term of a variable or a constant (`None`: a compound to build).
fn leaf(o: &Opnd, regs: &[Term]) -> Option<Term> {
    match o {
        Opnd::Var(i) => Some(regs[*i as usize]),
        Opnd::Const(k) => Some(*k),
        Opnd::Build(..) => None,
    }
}

/// Whether the operand's value is identical (`==`) to the ground term `t`,
/// without building it.
fn ident_term(store: &Store, o: &Opnd, regs: &[Term], t: Term) -> bool {
    match o {
        Opnd::Build(f, args) => {
            store.compound_args(t, *f, args.len()).is_some()
                && (0..args.len()).all(|i| ident_term(store, &args[i], regs, store.args(t)[i]))
        }
        _ => leaf(o, regs).is_some_and(|k| store.identical(k, t)),
    }
}

/// Whether two operands' values are identical (`==`).
fn ident(store: &Store, x: &Opnd, y: &Opnd, regs: &[Term]) -> bool {
    match (leaf(x, regs), leaf(y, regs), x, y) {
        (Some(a), Some(b), ..) => store.identical(a, b),
        (Some(a), None, ..) => ident_term(store, y, regs, a),
        (None, Some(b), ..) => ident_term(store, x, regs, b),
        (None, None, Opnd::Build(f, a), Opnd::Build(g, b)) => {
            f == g
                && a.len() == b.len()
                && a.iter()
                    .zip(b.iter())
                    .all(|(x, y)| ident(store, x, y, regs))
        }
        (None, None, ..) => false,
    }
}

/// Whether the ground argument `a` matches the head argument `p`, binding
/// its variables' first occurrences in `regs`.
fn head_matches(store: &Store, p: &PArg, a: Term, regs: &mut [Term]) -> bool {
    match p {
        PArg::Bind(i) => {
            regs[*i as usize] = a;
            true
        }
        PArg::Same(i) => store.identical(regs[*i as usize], a),
        PArg::Skip => true,
        PArg::Const(k) => store.identical(*k, a),
        PArg::Struct(f, ps) => {
            if store.compound_args(a, *f, ps.len()).is_none() {
                return false;
            }
            (0..ps.len()).all(|i| {
                let ai = store.args(a)[i];
                head_matches(store, &ps[i], ai, regs)
            })
        }
    }
}

fn run_clause(store: &mut Store, c: &PClause, args: &[Term], regs: &mut [Term]) -> Outcome {
    for (p, &a) in c.head.iter().zip(args) {
        if !head_matches(store, p, a, regs) {
            return Outcome::Fail { cut: false };
        }
    }
    let mut cut = false;
    let mut assigned = None;
    match run_goals(store, &c.body, regs, &mut cut, &mut assigned) {
        Err(()) => Outcome::Unsure,
        Ok(false) => Outcome::Fail { cut },
        Ok(true) => match assigned {
            Some(o) => value(store, o, regs).map_or(Outcome::Unsure, Outcome::Value),
            None => Outcome::NoValue,
        },
    }
}

/// Runs `goals` in order: whether they all held (`cut` set by a cut
/// reached, `assigned` the last assignment reached), `Err` where the
/// native form does not decide.
fn run_goals<'c>(
    store: &mut Store,
    goals: &'c [PGoal],
    regs: &mut [Term],
    cut: &mut bool,
    assigned: &mut Option<&'c Opnd>,
) -> Result<bool, ()> {
    for g in goals {
        let holds = match g {
            PGoal::True => true,
            PGoal::Fail => false,
            PGoal::Cut => {
                *cut = true;
                true
            }
            PGoal::IsFresh(i, e) => {
                regs[*i as usize] = Term::from(eval(store, e, regs)?);
                true
            }
            PGoal::IsBound(i, e) => {
                num::same(eval(store, e, regs)?, number(store, regs[*i as usize])?)
            }
            PGoal::Cmp(op, x, y) => {
                num::compare(*op, eval(store, x, regs)?, eval(store, y, regs)?).ok_or(())?
            }
            PGoal::Ident(eq, x, y) => ident(store, x, y, regs) == *eq,
            PGoal::Bind(i, o) => {
                regs[*i as usize] = value(store, o, regs).ok_or(())?;
                true
            }
            PGoal::Assign(o) => {
                // Built when the clause has succeeded (a later assignment wins).
                *assigned = Some(o);
                true
            }
            PGoal::Ite(c, t, e) => {
                // The condition tests only: no cut, no assignment to keep.
                let (mut no_cut, mut none) = (false, None);
                let branch = if run_goals(store, c, regs, &mut no_cut, &mut none)? {
                    t
                } else {
                    e
                };
                run_goals(store, branch, regs, cut, assigned)?
            }
        };
        if !holds {
            return Ok(false);
        }
    }
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::native::{Compound, List, Ty, Val};

    fn scan(text: &str) -> PlainFns {
        let (clauses, _) = sitlog_syntax::read_prolog_clauses(text);
        let mut s = PlainScan::default();
        let neck = Atom::intern(":-");
        for c in &clauses {
            let mut store = Store::new();
            let (t, _) = store.from_clause(c);
            if let Some(a) = store.compound_args(t, neck, 1) {
                let g = a[0];
                s.directive(&store, g);
                continue;
            }
            let (head, body) = match store.compound_args(t, neck, 2) {
                Some(a) => (a[0], Some(a[1])),
                None => (t, None),
            };
            let key = store.functor(head).unwrap();
            s.clause(&store, key, head, body);
        }
        s.finish()
    }

    /// The call on terms; on values too (`val`) where every argument is a
    /// `ground` value, which must give the same.
    fn call(fns: &PlainFns, store: &mut Store, q: &str) -> Option<String> {
        let t = store.parse(q).unwrap().0;
        let (name, _) = store.functor(t).unwrap();
        let args = store.args(t).to_vec();
        let on_terms = fns
            .call(store, name, &args, 10_000_000)
            .map(|v| store.writeq(v));
        let vals: Option<Vec<Val>> = args
            .iter()
            .map(|&a| Val::from_term(store, a, &Ty::Ground))
            .collect();
        if let Some(vals) = vals {
            let on_vals = fns.call_vals(name, &vals, 10_000_000).map(|v| {
                let t = v.to_term(store);
                store.writeq(t)
            });
            assert_eq!(on_vals, on_terms, "{q} on values");
        }
        on_terms
    }

    #[test]
    fn plain_functions_and_what_they_leave_to_the_engine() {
        let fns = scan(
            "same(A, B) :- A == B, !, assign_func_value(yes).\n\
             same(_, _) :- assign_func_value(no).\n\
             succ_of(X) :- Y is X + 1, assign_func_value(Y).\n\
             m(X) :- Y is X mod -3, Z is X // 2, W is X rem 3, assign_func_value(Y), assign_func_value(W), Z > -100.\n\
             cf(X) :- X > 0, !, X > 5, assign_func_value(big).\n\
             cf(_) :- assign_func_value(small).\n\
             fa(X) :- assign_func_value(a), X > 5.\n\
             fa(_).\n\
             k(a, X) :- X = b, assign_func_value(X).\n\
             notplain(X) :- atom(X), assign_func_value(X).\n",
        );
        let mut keys: Vec<String> = fns.keys().map(|(n, a)| format!("{n}/{a}")).collect();
        keys.sort();
        assert_eq!(keys, ["cf/1", "fa/1", "k/2", "m/1", "same/2", "succ_of/1"]);
        let s = &mut Store::new();
        assert_eq!(call(&fns, s, "same(a, a)").as_deref(), Some("yes"));
        assert_eq!(call(&fns, s, "same(a, b)").as_deref(), Some("no"));
        assert_eq!(call(&fns, s, "same(f(x), f(x))").as_deref(), Some("yes"));
        assert_eq!(call(&fns, s, "same(1, 1.0)").as_deref(), Some("no")); // not identical
        assert_eq!(call(&fns, s, "same(1.5, 1.5)").as_deref(), Some("yes"));
        assert_eq!(call(&fns, s, "succ_of(1.5)").as_deref(), Some("2.5"));
        assert_eq!(call(&fns, s, "m(7.0)"), None); // `mod` of a float: a type error
        assert_eq!(call(&fns, s, "same(X, a)"), None); // unbound: the engine
        assert_eq!(call(&fns, s, "succ_of(41)").as_deref(), Some("42"));
        assert_eq!(call(&fns, s, "succ_of(abc)"), None); // a type error
        assert_eq!(call(&fns, s, "succ_of(9223372036854775807)"), None); // overflow
        assert_eq!(call(&fns, s, "m(-7)").as_deref(), Some("-1")); // rem: -1, mod -3: -1
        assert_eq!(call(&fns, s, "m(7)").as_deref(), Some("1"));
        assert_eq!(call(&fns, s, "cf(9)").as_deref(), Some("big"));
        assert_eq!(call(&fns, s, "cf(1)"), None); // fails after the cut
        assert_eq!(call(&fns, s, "cf(0)").as_deref(), Some("small"));
        assert_eq!(call(&fns, s, "fa(9)").as_deref(), Some("a"));
        assert_eq!(call(&fns, s, "fa(1)"), None); // no value
        assert_eq!(call(&fns, s, "k(a, z)").as_deref(), None); // X bound: `=` fails, then no clause
        let fns2 = scan("k2(a, X) :- Y = X, assign_func_value(Y).\n");
        assert_eq!(call(&fns2, s, "k2(a, z)").as_deref(), Some("z"));
        assert_eq!(call(&fns2, s, "k2(b, z)"), None);
    }

    #[test]
    fn floats_in_arithmetic_and_comparisons() {
        let fns = scan(
            "near(X, T) :- D is abs(X - T), D < 0.1, !, assign_func_value(close).\n\
             near(_, _) :- assign_func_value(far).\n\
             half(X) :- Y is X / 2, assign_func_value(Y).\n\
             halfi(X) :- Y is X / 2.0, assign_func_value(Y).\n\
             big(X) :- Y is max(X, 1.0), Z is min(Y, 10), assign_func_value(Z).\n\
             eq(X, Y) :- X =:= Y, !, assign_func_value(yes).\n\
             eq(_, _) :- assign_func_value(no).\n\
             is2(X) :- Y = 2, Y is X, !, assign_func_value(yes).\n\
             is2(_) :- assign_func_value(no).\n\
             neg(X) :- Y is -X, assign_func_value(Y).\n",
        );
        let s = &mut Store::new();
        assert_eq!(call(&fns, s, "near(1.0, 1.05)").as_deref(), Some("close"));
        assert_eq!(call(&fns, s, "near(1.0, 1.1)").as_deref(), Some("far"));
        assert_eq!(call(&fns, s, "near(1, 1)").as_deref(), Some("close"));
        assert_eq!(call(&fns, s, "near(a, 1.0)"), None); // a type error
        assert_eq!(call(&fns, s, "half(3.0)").as_deref(), Some("1.5"));
        assert_eq!(call(&fns, s, "half(3)"), None); // `/` of integers: the engine's
        assert_eq!(call(&fns, s, "half(0.0)").as_deref(), Some("0.0"));
        assert_eq!(call(&fns, s, "halfi(0)").as_deref(), Some("0.0"));
        assert_eq!(call(&fns, s, "halfi(1.0e308)").as_deref(), Some("5.0e+307"));
        assert_eq!(call(&fns, s, "big(0)").as_deref(), Some("1.0"));
        assert_eq!(call(&fns, s, "big(1)"), None); // a tie of 1 and 1.0
        assert_eq!(call(&fns, s, "big(12)").as_deref(), Some("10"));
        assert_eq!(call(&fns, s, "eq(1, 1.0)").as_deref(), Some("yes"));
        assert_eq!(
            call(&fns, s, "eq(0.1, 0.10000000000000002)").as_deref(),
            Some("no")
        );
        assert_eq!(call(&fns, s, "is2(2)").as_deref(), Some("yes"));
        assert_eq!(call(&fns, s, "is2(2.0)").as_deref(), Some("no")); // 2 = 2.0 fails
        assert_eq!(call(&fns, s, "neg(2.5)").as_deref(), Some("-2.5"));
        assert_eq!(call(&fns, s, "neg(0.0)"), None); // negative zero
    }

    #[test]
    fn compounds_and_lists_taken_and_returned() {
        let fns = scan(
            "route(P, _, _) :- P == boom, !, fail.\n\
             route(P, _, T) :- P == T, !, assign_func_value(found(P)).\n\
             route(_, Ps, _) :- assign_func_value(walk(Ps)).\n\
             first([X|_]) :- assign_func_value(X).\n\
             first([]) :- assign_func_value(none).\n\
             pair(at(R, O), R) :- assign_func_value(O-[R, 1|x]).\n\
             pair2(at(R, O)) :- T = [], assign_func_value([O, R|T]).\n\
             same_as(X) :- X == f(a, [1]), assign_func_value(yes).\n\
             same_as(X) :- Y = g(X), Y \\== g(b), assign_func_value(Y).\n\
             same_as(_) :- assign_func_value([]).\n\
             open(X) :- Y = f(Z), assign_func_value(Y-X-Z).\n\
             fl(X) :- assign_func_value(f(X, 1.5)).\n",
        );
        let mut keys: Vec<String> = fns.keys().map(|(n, a)| format!("{n}/{a}")).collect();
        keys.sort();
        assert_eq!(
            keys,
            ["first/1", "pair/2", "pair2/1", "route/3", "same_as/1"]
        );
        let s = &mut Store::new();
        assert_eq!(
            call(&fns, s, "route(a, [b, c], c)").as_deref(),
            Some("walk([b,c])")
        );
        assert_eq!(
            call(&fns, s, "route(c, [], c)").as_deref(),
            Some("found(c)")
        );
        assert_eq!(call(&fns, s, "route(boom, [], c)"), None); // fails after its cut
        assert_eq!(call(&fns, s, "route(a, [b|_], c)"), None); // an unbound part
        assert_eq!(
            call(&fns, s, "route(a, [b, 1.0], c)").as_deref(),
            Some("walk([b,1.0])")
        );
        assert_eq!(call(&fns, s, "route(a, [b|c], c)"), None); // an improper list
        assert_eq!(call(&fns, s, "first([q|r])"), None);
        assert_eq!(call(&fns, s, "first([q, r])").as_deref(), Some("q"));
        assert_eq!(call(&fns, s, "first([])").as_deref(), Some("none"));
        assert_eq!(call(&fns, s, "first(q)"), None); // no clause matches
        assert_eq!(call(&fns, s, "pair(at(k, cup), k)"), None); // builds `[k, 1|x]`
        assert_eq!(
            call(&fns, s, "pair2(at(k, cup))").as_deref(),
            Some("[cup,k]")
        );
        assert_eq!(call(&fns, s, "pair(at(k, cup), j)"), None);
        assert_eq!(call(&fns, s, "pair(on(k, cup), k)"), None);
        assert_eq!(call(&fns, s, "same_as(f(a, [1]))").as_deref(), Some("yes"));
        assert_eq!(
            call(&fns, s, "same_as(f(a, [2]))").as_deref(),
            Some("g(f(a,[2]))")
        );
        assert_eq!(call(&fns, s, "same_as(b)").as_deref(), Some("[]"));
        // The argument's list is shared by the value, not copied.
        let t = s.parse("route(a, [b, c], c)").unwrap().0;
        let args = s.args(t).to_vec();
        let v = fns.call(s, Atom::intern("route"), &args, u64::MAX).unwrap();
        assert_eq!(s.args(v)[0], args[1]);
    }

    #[test]
    fn naming_assert_anywhere_turns_it_off() {
        let fns = scan(
            "succ_of(X) :- Y is X + 1, assign_func_value(Y).\n\
             other :- assertz(seen(x)).\n",
        );
        assert_eq!(fns.keys().count(), 0);
        let fns = scan(":- dynamic(foo/1).\nsucc_of(X) :- Y is X + 1, assign_func_value(Y).\n");
        assert_eq!(fns.keys().count(), 1);
        let fns = scan(":- G = assert, true.\nsucc_of(X) :- Y is X + 1, assign_func_value(Y).\n");
        assert_eq!(fns.keys().count(), 0);
    }

    #[test]
    fn a_small_inference_limit_leaves_the_call_to_the_engine() {
        let fns = scan("succ_of(X) :- Y is X + 1, assign_func_value(Y).\n");
        let s = &mut Store::new();
        let name = Atom::intern("succ_of");
        assert!(fns.call(s, name, &[Term::int(1)], 999).is_none());
        assert!(fns.call(s, name, &[Term::int(1)], 1000).is_some());
    }

    #[test]
    fn a_deep_argument_or_an_assign_func_value_of_its_own_is_the_engines() {
        let fns = scan("echo(X) :- assign_func_value(X).\n");
        let s = &mut Store::new();
        let sf = Atom::intern("s");
        let mut t = Term::atom(Atom::intern("a"));
        for _ in 0..MAX_DEPTH {
            t = s.compound(sf, &[t]);
        }
        let echo = Atom::intern("echo");
        assert!(fns.call(s, echo, &[t], u64::MAX).is_some());
        let deeper = s.compound(sf, &[t]);
        assert!(fns.call(s, echo, &[deeper], u64::MAX).is_none());
        let fns = scan("echo(X) :- assign_func_value(X).\nassign_func_value(_).\n");
        assert_eq!(fns.keys().count(), 0);
    }

    #[test]
    fn if_then_else_with_a_test_for_condition() {
        let fns = scan(
            "heavy(W) :- W >= 0, ( W >= 1000 -> A = yes ; A = no ), assign_func_value(A).\n\
             cut(X) :- ( X > 0 -> !, X > 5 ; true ), assign_func_value(big).\n\
             cut(_) :- assign_func_value(small).\n\
             pick(X) :- ( X == a -> assign_func_value(first) ; assign_func_value(other) ).\n\
             nested(X) :- ( X > 0 -> ( X > 9 -> Y = 2 ; Y = 1 ) ; Y = 0 ), assign_func_value(Y).\n\
             notest(X) :- ( Y = X -> A = Y ; A = no ), assign_func_value(A).\n\
             onlyone(X) :- ( X > 0 -> A = yes ; true ), assign_func_value(X).\n\
             nothen(X) :- ( X > 0 -> A = yes ), assign_func_value(A).\n\
             either(X) :- ( X > 0 ; X < -5 ), assign_func_value(X).\n",
        );
        let mut keys: Vec<String> = fns.keys().map(|(n, a)| format!("{n}/{a}")).collect();
        keys.sort();
        assert_eq!(keys, ["cut/1", "heavy/1", "nested/1", "pick/1"]);
        let s = &mut Store::new();
        assert_eq!(call(&fns, s, "heavy(1500)").as_deref(), Some("yes"));
        assert_eq!(call(&fns, s, "heavy(5)").as_deref(), Some("no"));
        assert_eq!(call(&fns, s, "heavy(-1)"), None); // fails: the engine
        assert_eq!(call(&fns, s, "heavy(a)"), None); // a type error
        assert_eq!(call(&fns, s, "cut(9)").as_deref(), Some("big"));
        assert_eq!(call(&fns, s, "cut(2)"), None); // fails after the cut
        assert_eq!(call(&fns, s, "cut(0)").as_deref(), Some("big"));
        assert_eq!(call(&fns, s, "pick(a)").as_deref(), Some("first"));
        assert_eq!(call(&fns, s, "pick(f(a))").as_deref(), Some("other"));
        assert_eq!(call(&fns, s, "nested(10)").as_deref(), Some("2"));
        assert_eq!(call(&fns, s, "nested(3)").as_deref(), Some("1"));
        assert_eq!(call(&fns, s, "nested(-3)").as_deref(), Some("0"));
    }

    #[test]
    fn a_list_taken_whole_is_remembered_with_its_tails() {
        let s = &mut Store::new();
        let l = s.parse("[a, b, c]").unwrap().0;
        assert!(sure(s, l, true));
        let tail = s.args(l)[1];
        assert_eq!(s.plain_memo.get(s.epoch), ground_cell(s, l));
        assert!(sure(s, tail, true));
        assert_eq!(s.plain_memo.get(s.epoch), ground_cell(s, tail));
        // Another list is walked: a float is still refused.
        let f = s.list(&[Term::atom(Atom::intern("a")), Term::float(-0.0)]);
        assert!(!sure(s, f, true));
        // A list over a variable bound later is not remembered.
        let x = s.new_var();
        let one = s.list(&[x]);
        s.bind(x, Term::atom(Atom::intern("q")));
        assert!(sure(s, one, true));
        assert_eq!(s.plain_memo.get(s.epoch), ground_cell(s, tail));
        // A collection forgets it.
        let mut roots = [l];
        s.gc(&mut roots);
        assert_eq!(s.plain_memo.get(s.epoch), None);
        assert!(sure(s, roots[0], true));
    }

    #[test]
    fn a_head_variable_nothing_reads_takes_no_register() {
        let fns = scan(
            "f(X, _, X) :- assign_func_value(same).\n\
             f([_|T], Y, _) :- Y == b, !, assign_func_value(T).\n\
             f(_, Y, Z) :- W is Z + 1, assign_func_value(p(Y, W)).\n",
        );
        let form = format!("{:?}", fns.map.get(&(Atom::intern("f"), 3)).unwrap());
        // Each `_` skipped (one, two, one); `X` (repeated), `T`, `Y`, `Z`
        // (read): bound.
        assert_eq!(form.matches("Skip").count(), 4, "{form}");
        let s = &mut Store::new();
        assert_eq!(call(&fns, s, "f(a, b, a)").as_deref(), Some("same"));
        assert_eq!(call(&fns, s, "f([1, 2], b, c)").as_deref(), Some("[2]"));
        assert_eq!(call(&fns, s, "f([1, 2], c, 4)").as_deref(), Some("p(c,5)"));
        assert_eq!(call(&fns, s, "f(a, b, c)"), None); // a type error
    }

    #[test]
    fn on_values_the_same_refusals() {
        let fns = scan(
            "echo(X) :- assign_func_value(X).\n\
             walk([_|Ps]) :- assign_func_value(walk(Ps)).\n",
        );
        let echo = Atom::intern("echo");
        let sf = Atom::intern("s");
        let mut v = Val::Sym(Atom::intern("a"));
        for _ in 0..MAX_DEPTH {
            v = Val::Tagged(Compound::new(sf, [v]));
        }
        assert!(fns.call_vals(echo, &[v.clone()], u64::MAX).is_some());
        let deeper = Val::Tagged(Compound::new(sf, [v]));
        assert!(fns.call_vals(echo, &[deeper], u64::MAX).is_none());
        // A list counts a level per element, as a term does.
        let long = |n: usize| Val::List((0..n as i64).map(Val::Int).collect::<List<Val>>());
        assert!(fns.call_vals(echo, &[long(MAX_DEPTH)], u64::MAX).is_some());
        assert!(fns
            .call_vals(echo, &[long(MAX_DEPTH + 1)], u64::MAX)
            .is_none());
        // Not ground, a float not sure (negative zero, NaN, infinite), a compound L evaluates: the term path's.
        let store = &mut Store::new();
        let x = store.new_var();
        for refused in [
            Val::from(x),
            Val::Float(-0.0),
            Val::Float(f64::NAN),
            Val::Tagged(Compound::new(
                Atom::intern("apply"),
                [Val::Int(1), Val::Int(2)],
            )),
            Val::Tagged(Compound::new(atoms::DOT, [Val::Int(1), Val::Int(2)])),
            Val::List(
                [Val::Int(1), Val::Float(f64::INFINITY)]
                    .into_iter()
                    .collect(),
            ),
        ] {
            assert!(fns.call_vals(echo, &[refused], u64::MAX).is_none());
        }
        // The rest of a walk's list, shared, not copied.
        let walk = Atom::intern("walk");
        let l: List<Val> = (0..5).map(Val::Int).collect();
        let mut arg = Val::List(l.clone());
        for _ in 0..5 {
            let out = fns.call_vals(walk, &[arg.clone()], u64::MAX).unwrap();
            let Val::Tagged(c) = &out else {
                panic!("walk(_) expected");
            };
            let (Val::List(rest), Val::List(now)) = (&c.args()[0], &arg) else {
                panic!("a list expected");
            };
            assert!(now.tail().unwrap().same_storage(rest));
            arg = c.args()[0].clone();
        }
        assert!(fns.call_vals(walk, &[arg], u64::MAX).is_none()); // `[]`: no clause
    }
}
