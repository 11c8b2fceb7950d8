//! The closure of a property or relation list (kb.md section 2) and the
//! abductive explanations (section 4), reproducing the original's clause
//! order: hiding of repeats, per-level ordering of defaults, backward and
//! forward chaining, and the abduction walk.
//!
//! Entries are kept as [`PE`]: `p=>v` split into its two ids so that a
//! consequent whose value is bound at query time (`q=>'-'`) needs no new term
//! in the shared store.
//!
//! Also defines the per-class cache record ([`ClassCache`]: the closure of a
//! class alone, reused for every individual whose own entries cannot change
//! it, see [`Part::reusable`]); `class_cache` fills it for a `Kb`. This
//! module knows entries and the term store, not the `Kb`.

use crate::entry::{key_bit, term_key, Entry, Known, ARROW, DEFAULT, NOT};
use crate::store::{TId, TermStore};
use std::cell::Cell;
use std::collections::HashMap;

/// One entry of a closure list: `p=>v`, or any other term.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum PE {
    Arrow(TId, TId),
    T(TId),
}

/// The closure needed more steps than allowed (the original's forward
/// chaining is exponential in the worst case).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budget;

/// The result of a search step: whether the continuation accepted.
type Step = Result<bool, Budget>;
/// A continuation over a complete solution list.
type Cont<'k> = &'k mut dyn FnMut(&[PE]) -> Step;
/// A continuation over one outcome of a default.
type Emit<'k> = &'k mut dyn FnMut(Option<PE>) -> Step;

/// Steps (firings tried) allowed for one closure.
pub(crate) const STEP_LIMIT: u64 = 5_000_000;

/// A conditional default `Ant=>>Cons`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rule {
    /// The whole `Ant=>>Cons` term.
    pub term: TId,
    pub ant: TId,
    pub cons: TId,
    /// The weight term, for the preference services.
    pub weight: TId,
    pub w: f64,
}

pub(crate) struct Ctx<'a> {
    pub s: &'a TermStore,
    pub k: Known,
    steps: Cell<u64>,
}

impl<'a> Ctx<'a> {
    pub fn new(s: &'a TermStore, k: Known) -> Ctx<'a> {
        Ctx {
            s,
            k,
            steps: Cell::new(0),
        }
    }

    pub fn pe(&self, t: TId) -> PE {
        match self.s.binary(t, ARROW) {
            Some((p, v)) => PE::Arrow(p, v),
            None => PE::T(t),
        }
    }

    /// The attribute an entry is about: hiding and lookups only ever relate
    /// entries with the same key.
    pub fn key_t(&self, t: TId) -> TId {
        term_key(self.s, t)
    }

    pub fn key(&self, e: PE) -> TId {
        match e {
            PE::Arrow(p, _) => p,
            PE::T(t) => self.key_t(t),
        }
    }

    /// A term for which key filtering is exact (not `not(_)`, not `_=>_`).
    pub fn simple(&self, t: TId) -> bool {
        self.s.unary(t, NOT).is_none() && self.s.binary(t, ARROW).is_none()
    }

    fn not_arrow(&self, e: PE) -> Option<(TId, TId)> {
        match e {
            PE::T(t) => self.s.unary(t, NOT).and_then(|i| self.s.binary(i, ARROW)),
            PE::Arrow(..) => None,
        }
    }

    fn not_inner(&self, e: PE) -> Option<TId> {
        match e {
            PE::T(t) => self
                .s
                .unary(t, NOT)
                .filter(|&i| self.s.binary(i, ARROW).is_none()),
            PE::Arrow(..) => None,
        }
    }

    /// Whether the kept entry `kept` hides a later `e` (step 1 of kb.md).
    fn hides(&self, kept: PE, e: PE) -> bool {
        match kept {
            PE::Arrow(p, v) => {
                matches!(e, PE::Arrow(q, _) if q == p) || self.not_arrow(e) == Some((p, v))
            }
            PE::T(t) => {
                if let Some((p, v)) = self.not_arrow(kept) {
                    self.not_arrow(e).is_some_and(|(q, _)| q == p) || e == PE::Arrow(p, v)
                } else if let Some(h) = self.not_inner(kept) {
                    e == kept || e == PE::T(h)
                } else {
                    e == kept || self.not_inner(e) == Some(t)
                }
            }
        }
    }

    /// Hide repeats: keep an entry unless an earlier kept entry hides it.
    pub fn hide(&self, list: &[PE]) -> Vec<PE> {
        let mut kept: Vec<PE> = Vec::with_capacity(list.len());
        if list.len() <= 24 {
            let mut keys: Vec<TId> = Vec::with_capacity(list.len());
            for &e in list {
                let ke = self.key(e);
                let hidden = kept
                    .iter()
                    .zip(&keys)
                    .any(|(&k, &kk)| kk == ke && self.hides(k, e));
                if !hidden {
                    kept.push(e);
                    keys.push(ke);
                }
            }
        } else {
            let mut by_key: HashMap<TId, Vec<PE>> = HashMap::new();
            for &e in list {
                let group = by_key.entry(self.key(e)).or_default();
                if !group.iter().any(|&k| self.hides(k, e)) {
                    group.push(e);
                    kept.push(e);
                }
            }
        }
        kept
    }

    /// The value of the first `p=>X` left after hiding repeats in `list`.
    pub fn first_kept_val(&self, list: &[PE], p: TId) -> Option<TId> {
        let mut first_not: Option<TId> = None;
        for &e in list {
            match e {
                // Hidden by an earlier kept not(p=>x).
                PE::Arrow(q, x) if q == p && first_not != Some(x) => return Some(x),
                PE::T(_) if first_not.is_none() => {
                    if let Some((q, v)) = self.not_arrow(e) {
                        if q == p {
                            first_not = Some(v);
                        }
                    }
                }
                _ => {}
            }
        }
        None
    }

    fn has_attr(list: &[PE], p: TId) -> bool {
        list.iter().any(|e| matches!(e, PE::Arrow(q, _) if *q == p))
    }

    fn tick(&self) -> Result<(), Budget> {
        let n = self.steps.get() + 1;
        self.steps.set(n);
        if n > STEP_LIMIT {
            Err(Budget)
        } else {
            Ok(())
        }
    }

    /// Runs the ordered defaults over `p` (the original's `prefer_handler`,
    /// first solution): each default adds its first outcome.
    pub fn run(&self, rules: &[Rule], p: &mut Vec<PE>) -> Result<(), Budget> {
        for i in 0..rules.len() {
            let mut first = None;
            self.outcomes(rules, i, p, &mut |o| {
                first = o;
                Ok(true)
            })?;
            if let Some(c) = first {
                p.push(c);
            }
        }
        Ok(())
    }

    fn concludes(&self, rest: &[Rule], what: impl Fn(PE) -> bool) -> bool {
        rest.iter().any(|r| what(self.pe(r.cons)))
    }

    /// Enumerates, in Prolog's order, the solutions of running `rules[i..]`
    /// over `p`, calling `k` on each final list until it accepts one (`true`).
    /// Forward chaining in the original backtracks through these solutions
    /// until its check holds; repeated outcomes are skipped, since their
    /// solutions were already rejected.
    fn solve(&self, rules: &[Rule], i: usize, p: &mut Vec<PE>, k: Cont<'_>) -> Step {
        stacker::maybe_grow(32 * 1024, 1024 * 1024, || {
            if i == rules.len() {
                return k(p);
            }
            let snapshot = p.clone();
            let mut seen: Vec<Option<PE>> = Vec::new();
            self.outcomes(rules, i, &snapshot, &mut |o| {
                if seen.contains(&o) {
                    return Ok(false);
                }
                seen.push(o);
                if let Some(x) = o {
                    p.push(x);
                }
                let r = self.solve(rules, i + 1, p, &mut *k);
                if o.is_some() {
                    p.pop();
                }
                r
            })
        })
    }

    /// The outcomes of default `i` over `p` (what it appends, or `None` for
    /// nothing), in the order of the original's clauses; stops when `emit`
    /// accepts one.
    fn outcomes(&self, rules: &[Rule], i: usize, p: &[PE], emit: Emit<'_>) -> Step {
        self.tick()?;
        let r = rules[i];
        let rest = &rules[i + 1..];
        let dash = self.k.dash;
        let ant = self.pe(r.ant);
        let cons = self.pe(r.cons);
        macro_rules! em {
            ($o:expr) => {
                if emit($o)? {
                    return Ok(true);
                }
            };
        }
        // Backward: the antecedent is already in the list.
        if let (PE::Arrow(pa, va), PE::Arrow(q, vc)) = (ant, cons) {
            if va == dash && vc == dash {
                if let Some(v) = self.first_kept_val(p, pa) {
                    em!(Some(PE::Arrow(q, v)));
                }
            }
            if va == dash && Self::has_attr(p, pa) {
                em!(Some(cons));
            }
            if self.first_kept_val(p, pa) == Some(va) {
                em!(Some(cons));
            }
        }
        if p.contains(&ant) {
            em!(Some(cons));
        }
        if let PE::Arrow(pa, va) = ant {
            if va == dash && Self::has_attr(p, pa) {
                em!(Some(cons));
            }
        }
        if r.ant == dash {
            em!(Some(cons));
        }
        // Forward: a later default concludes the antecedent; some solution of
        // the rest must contain it.
        if let (PE::Arrow(pa, va), PE::Arrow(q, vc)) = (ant, cons) {
            if va == dash
                && vc == dash
                && self.concludes(rest, |c| matches!(c, PE::Arrow(x, _) if x == pa))
            {
                let mut copy = p.to_vec();
                let stop = self.solve(rest, 0, &mut copy, &mut |fl| match self
                    .first_kept_val(fl, pa)
                {
                    Some(v) => emit(Some(PE::Arrow(q, v))),
                    None => Ok(false),
                })?;
                if stop {
                    return Ok(true);
                }
            }
            if self.concludes(rest, |c| c == ant) {
                let mut copy = p.to_vec();
                let stop = self.solve(rest, 0, &mut copy, &mut |fl| {
                    if self.first_kept_val(fl, pa) == Some(va) {
                        emit(Some(cons))
                    } else {
                        Ok(false)
                    }
                })?;
                if stop {
                    return Ok(true);
                }
            }
        }
        if self.concludes(rest, |c| c == ant) {
            let mut copy = p.to_vec();
            let stop = self.solve(rest, 0, &mut copy, &mut |fl| {
                if fl.contains(&ant) {
                    emit(Some(cons))
                } else {
                    Ok(false)
                }
            })?;
            if stop {
                return Ok(true);
            }
        }
        // A list of antecedents.
        if let Some(items) = self.s.proper_list(r.ant) {
            if let PE::Arrow(q, vc) = cons {
                if vc == dash {
                    // An empty list leaves the value unbound in the original.
                    let stop = self.list4(&items, 0, rest, p, None, &mut |v| {
                        emit(Some(PE::Arrow(q, v.unwrap_or(dash))))
                    })?;
                    if stop {
                        return Ok(true);
                    }
                }
                let stop = self.list4(&items, 0, rest, p, Some(vc), &mut |_| emit(Some(cons)))?;
                if stop {
                    return Ok(true);
                }
            }
            if self.list3(&items, rest, p)? {
                em!(Some(cons));
            }
        }
        em!(None);
        Ok(false)
    }

    /// Whether some solution of running `rest` over `p` satisfies `check`.
    fn some_solution(&self, rest: &[Rule], p: &[PE], check: impl Fn(&[PE]) -> bool) -> Step {
        let mut copy = p.to_vec();
        self.solve(rest, 0, &mut copy, &mut |fl| Ok(check(fl)))
    }

    /// The original's 3-argument list check: every item is in the list, or
    /// a later default concludes it in some solution of the rest.
    fn list3(&self, items: &[TId], rest: &[Rule], p: &[PE]) -> Step {
        for &item in items {
            let it = self.pe(item);
            if p.contains(&it) {
                continue;
            }
            if !(self.concludes(rest, |c| c == it)
                && self.some_solution(rest, p, |fl| fl.contains(&it))?)
            {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// The original's 4-argument list check: every item `p=>'-'` / `p=>v`
    /// holds with one shared value, in clause order with backtracking;
    /// `k` gets the binding.
    fn list4(
        &self,
        items: &[TId],
        idx: usize,
        rest: &[Rule],
        p: &[PE],
        val: Option<TId>,
        k: &mut dyn FnMut(Option<TId>) -> Step,
    ) -> Step {
        let Some(&item) = items.get(idx) else {
            return k(val);
        };
        self.tick()?;
        // One level of recursion per item: grow the stack for long lists.
        stacker::maybe_grow(32 * 1024, 1024 * 1024, || {
            self.list4_item(items, idx, item, rest, p, val, k)
        })
    }

    #[allow(clippy::too_many_arguments)]
    fn list4_item(
        &self,
        items: &[TId],
        idx: usize,
        item: TId,
        rest: &[Rule],
        p: &[PE],
        val: Option<TId>,
        k: &mut dyn FnMut(Option<TId>) -> Step,
    ) -> Step {
        let dash = self.k.dash;
        let Some((pa, va)) = self.s.binary(item, ARROW) else {
            return Ok(false);
        };
        let compat = |x: TId| val.is_none() || val == Some(x);
        if va == dash {
            // This clause ends in a cut: its first success is the only one.
            if let Some(x) = self.first_kept_val(p, pa).filter(|&x| compat(x)) {
                let mut first = None;
                self.list4(items, idx + 1, rest, p, Some(x), &mut |v| {
                    first = Some(v);
                    Ok(true)
                })?;
                if let Some(v) = first {
                    return k(v);
                }
            }
            if compat(dash)
                && self.first_kept_val(p, pa) == Some(dash)
                && self.list4(items, idx + 1, rest, p, Some(dash), k)?
            {
                return Ok(true);
            }
            if self.concludes(rest, |c| matches!(c, PE::Arrow(x, _) if x == pa)) {
                let mut copy = p.to_vec();
                let stop = self.solve(rest, 0, &mut copy, &mut |fl| match self
                    .first_kept_val(fl, pa)
                    .filter(|&x| compat(x))
                {
                    Some(x) => self.list4(items, idx + 1, rest, p, Some(x), &mut *k),
                    None => Ok(false),
                })?;
                if stop {
                    return Ok(true);
                }
            }
            if compat(dash) && self.concludes(rest, |c| c == PE::Arrow(pa, dash)) {
                let mut copy = p.to_vec();
                return self.solve(rest, 0, &mut copy, &mut |fl| {
                    if self.first_kept_val(fl, pa) == Some(dash) {
                        self.list4(items, idx + 1, rest, p, Some(dash), &mut *k)
                    } else {
                        Ok(false)
                    }
                });
            }
            Ok(false)
        } else {
            if !compat(va) {
                return Ok(false);
            }
            if self.first_kept_val(p, pa) == Some(va)
                && self.list4(items, idx + 1, rest, p, Some(va), k)?
            {
                return Ok(true);
            }
            if self.concludes(rest, |c| c == PE::Arrow(pa, va)) {
                let mut copy = p.to_vec();
                return self.solve(rest, 0, &mut copy, &mut |fl| {
                    if self.first_kept_val(fl, pa) == Some(va) {
                        self.list4(items, idx + 1, rest, p, Some(va), &mut *k)
                    } else {
                        Ok(false)
                    }
                });
            }
            Ok(false)
        }
    }

    /// The abduction walk over the ordered defaults (the original's
    /// `abductive_handler`), then one explanation per consequent.
    pub fn abduce(&self, rules: &[Rule], mut p: Vec<PE>) -> Vec<(PE, PE)> {
        let dash = self.k.dash;
        let mut out: Vec<(PE, PE)> = Vec::new();
        for r in rules {
            let ant = self.pe(r.ant);
            let cons = self.pe(r.cons);
            let first_val = |p: &[PE], q: TId| {
                p.iter().find_map(|e| match e {
                    PE::Arrow(x, v) if *x == q => Some(*v),
                    _ => None,
                })
            };
            if let (PE::Arrow(pa, va), PE::Arrow(q, vc)) = (ant, cons) {
                if va == dash && vc == dash {
                    if let Some(v) = first_val(&p, q) {
                        out.push((PE::Arrow(q, v), PE::Arrow(pa, v)));
                        p.push(PE::Arrow(pa, v));
                        continue;
                    }
                }
                if va == dash && p.contains(&cons) {
                    let why = PE::Arrow(pa, first_val(&p, pa).unwrap_or(dash));
                    out.push((cons, why));
                    p.push(PE::Arrow(pa, dash));
                    continue;
                }
            }
            if let PE::Arrow(q, vc) = cons {
                if vc == dash {
                    if let Some(v) = first_val(&p, q) {
                        out.push((PE::Arrow(q, v), ant));
                        p.push(ant);
                        continue;
                    }
                }
            }
            if p.contains(&cons) {
                out.push((cons, ant));
                p.push(ant);
            }
        }
        // Keep the first explanation per consequent (per attribute for q=>v).
        let mut kept: Vec<(PE, PE)> = Vec::with_capacity(out.len());
        for (c, why) in out {
            let dup = kept.iter().any(|(k, _)| match (k, c) {
                (PE::Arrow(a, _), PE::Arrow(b, _)) => *a == b,
                (k, c) => *k == c,
            });
            if !dup {
                kept.push((c, why));
            }
        }
        kept
    }
}

/// The defaults of one level in the original's order: reversed declaration
/// order, then a stable sort by weight.
pub(crate) fn level_rules(s: &TermStore, entries: &[Entry], out: &mut Vec<Rule>) {
    let start = out.len();
    for e in entries.iter().rev().filter(|e| !e.abs) {
        if let Some((ant, cons)) = s.binary(e.term, DEFAULT) {
            out.push(Rule {
                term: e.term,
                ant,
                cons,
                weight: e.weight,
                w: e.w,
            });
        }
    }
    // Stable: equal weights keep the reversed declaration order.
    out[start..].sort_by(|a, b| a.w.partial_cmp(&b.w).unwrap_or(std::cmp::Ordering::Equal));
}

/// The closure of a chain of levels: `hidden_abs ++ derived` is the list
/// before step 4.
#[derive(Clone, Debug, Default)]
pub(crate) struct Closure {
    pub hidden_abs: Vec<PE>,
    pub derived: Vec<PE>,
}

impl Closure {
    pub fn pre(&self) -> Vec<PE> {
        let mut v = self.hidden_abs.clone();
        v.extend_from_slice(&self.derived);
        v
    }
}

/// The properties (or relations, or both for explanations) of a class chain.
#[derive(Clone, Debug)]
pub(crate) struct Part {
    pub rules: Vec<Rule>,
    /// Keys of every antecedent (and antecedent list item): entries with
    /// other keys cannot change which defaults fire.
    pub ant_keys: Vec<TId>,
    /// `ant_keys` plus the consequents' keys (for explanations).
    pub all_keys: Vec<TId>,
    /// `ant_keys` as a bloom set (see `entry::key_bit`).
    pub ant_bloom: u64,
    pub closure: Result<Closure, Budget>,
}

impl Part {
    pub fn new(ctx: &Ctx<'_>, abs: Vec<PE>, rules: Vec<Rule>) -> Part {
        let mut ant_keys = Vec::new();
        let mut all_keys = Vec::new();
        for r in &rules {
            let items = ctx.s.proper_list(r.ant).unwrap_or_default();
            for t in std::iter::once(r.ant).chain(items) {
                ant_keys.push(ctx.key_t(t));
            }
            all_keys.push(ctx.key_t(r.cons));
        }
        ant_keys.sort();
        ant_keys.dedup();
        all_keys.extend_from_slice(&ant_keys);
        all_keys.sort();
        all_keys.dedup();
        let hidden_abs = ctx.hide(&abs);
        let mut p = hidden_abs.clone();
        let closure = ctx.run(&rules, &mut p).map(|()| Closure {
            derived: p[hidden_abs.len()..].to_vec(),
            hidden_abs,
        });
        let ant_bloom = ant_keys.iter().fold(0, |b, &k| b | key_bit(k));
        Part {
            ant_bloom,
            rules,
            ant_keys,
            all_keys,
            closure,
        }
    }

    /// Whether an individual with these own entries has this class closure
    /// (plus its own absolutes): no own defaults, and no own absolute about
    /// an attribute that some antecedent looks at.
    pub fn reusable(&self, own: &[Entry], keys: &[TId]) -> bool {
        own.iter()
            .all(|e| e.abs && keys.binary_search(&e.key).is_err())
    }
}

/// Per-class data computed on first use.
#[derive(Clone, Debug)]
pub(crate) struct ClassCache {
    /// The class and its ancestors up to `top`.
    pub chain: Vec<u32>,
    pub props: Part,
    pub rels: Part,
    /// Properties and relations together (explanations).
    pub all: Part,
    pub expl: Result<std::sync::Arc<Vec<(PE, PE)>>, Budget>,
}

/// Which lists a closure is over.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Props,
    Rels,
    /// Properties and relations together (explanations).
    Both,
}
