//! Unification (`=/2`, no occurs check), structural equality (`==/2`) and
//! the standard order of terms (`compare/3`).
//!
//! All three walk pairs of terms with an explicit stack, never Rust
//! recursion, so depth is bounded by memory only. The stacks are reused
//! between calls (the store's scratch vector for `unify`, a thread-local
//! one for the `&self` comparisons) so the steady state allocates nothing.
//!
//! Terms made cyclic by unification without occurs check (`X = f(X)`):
//! these walks still terminate. After many steps they start remembering
//! the compound pairs they have entered and skip repeats (sound for `=` and
//! `==`: a repeated pair is being or has been handled; for `compare` the
//! order among cyclic terms is then merely some consistent answer). The same
//! guard keeps walks over heavily shared (DAG) terms linear.

use crate::store::Store;
use crate::term::{Repr, Term};
use sitlog_syntax::Atom;
use std::cell::Cell;
use std::cmp::Ordering;
use std::collections::HashSet;
use std::hash::Hash;

/// Steps a walk takes before it starts remembering what it has entered:
/// ordinary terms never pay for the set.
const GUARD_AFTER: usize = 1 << 20;

/// Termination guard for walks that may meet cyclic or shared structure.
pub(crate) struct CycleGuard<K> {
    steps: usize,
    seen: Option<HashSet<K>>,
}

impl<K: Hash + Eq> CycleGuard<K> {
    pub(crate) fn new() -> CycleGuard<K> {
        CycleGuard {
            steps: 0,
            seen: None,
        }
    }

    /// False if `key` was entered before (tracked only after
    /// [`GUARD_AFTER`] steps).
    #[inline]
    pub(crate) fn first_visit(&mut self, key: K) -> bool {
        self.steps += 1;
        if self.steps < GUARD_AFTER {
            return true;
        }
        self.seen.get_or_insert_with(HashSet::new).insert(key)
    }
}

thread_local! {
    static PAIRS: Cell<Vec<(Term, Term)>> = const { Cell::new(Vec::new()) };
}

/// Runs `f` with a cleared, thread-local pair stack (reentrant: a nested
/// call gets its own empty vector).
fn with_pairs<R>(f: impl FnOnce(&mut Vec<(Term, Term)>) -> R) -> R {
    PAIRS.with(|cell| {
        let mut stack = cell.take();
        stack.clear();
        let r = f(&mut stack);
        stack.clear();
        cell.set(stack);
        r
    })
}

impl Store {
    /// Unifies `a` and `b`. On success the bindings stay (and are on the
    /// trail); on failure every binding this call made is undone, so a
    /// failed unify leaves the store as it was.
    pub fn unify(&mut self, a: Term, b: Term) -> bool {
        let a = self.deref(a);
        let b = self.deref(b);
        if a == b {
            return true;
        }
        // Two different constants: no stack, no trail.
        if !matches!(a.0, Repr::Var(_) | Repr::Struct(_) | Repr::Big(_))
            && !matches!(b.0, Repr::Var(_) | Repr::Struct(_) | Repr::Big(_))
        {
            return false;
        }
        let start = self.trail.len();
        let mut stack = std::mem::take(&mut self.pairs);
        stack.clear();
        stack.push((a, b));
        let ok = self.unify_pairs(&mut stack);
        stack.clear();
        self.pairs = stack;
        if !ok {
            while self.trail.len() > start {
                if let Some(i) = self.trail.pop() {
                    self.vars[i as usize] = Term(Repr::Var(i));
                }
            }
        }
        ok
    }

    /// [`Store::unify`] of two compounds of constants (an input
    /// `said(yes)` against an expectation `said(no)`, at every perception):
    /// compared in place, no pair stack, no trail (two constants unify
    /// when they are equal); `None` for any other pair (then
    /// [`Store::unify`]). Apart from `unify` so that its other callers
    /// (the plans' ids and instances, which are seldom flat) pay nothing.
    #[inline]
    pub fn unify_flat(&self, a: Term, b: Term) -> Option<bool> {
        let (Repr::Struct(p), Repr::Struct(q)) = (self.deref(a).0, self.deref(b).0) else {
            return None;
        };
        let (fa, xs) = self.compound_at(p);
        let (fb, ys) = self.compound_at(q);
        if fa != fb || xs.len() != ys.len() {
            return Some(false);
        }
        let constant = |t: &Term| !matches!(t.0, Repr::Var(_) | Repr::Struct(_) | Repr::Big(_));
        xs.iter().chain(ys).all(constant).then(|| xs == ys)
    }

    /// [`Store::unify`] of the compound `name(arg)`, not built, with `e`
    /// (an input `said(yes)` a perception hands over unbuilt, against an
    /// expectation): `e` of another functor or arity, or not a compound,
    /// never unifies; `name(E)` unifies when `E` unifies with `arg`, with
    /// the bindings `unify` of the compounds makes (their one pair of
    /// arguments), two constants compared in place; `None` when `e` is
    /// unbound (the caller builds the compound to bind it).
    #[inline]
    pub fn unify_wrapped(&mut self, name: Atom, arg: Term, e: Term) -> Option<bool> {
        let p = match self.deref(e).0 {
            Repr::Struct(p) => p,
            Repr::Var(_) => return None,
            _ => return Some(false),
        };
        let (f, args) = self.compound_at(p);
        if f != name || args.len() != 1 {
            return Some(false);
        }
        let a = self.deref(arg);
        let b = self.deref(args[0]);
        if a == b {
            return Some(true);
        }
        let constant = |t: Term| !matches!(t.0, Repr::Var(_) | Repr::Struct(_) | Repr::Big(_));
        if constant(a) && constant(b) {
            return Some(false);
        }
        Some(self.unify(a, b))
    }

    fn unify_pairs(&mut self, stack: &mut Vec<(Term, Term)>) -> bool {
        let mut guard = CycleGuard::new();
        while let Some((a, b)) = stack.pop() {
            let a = self.deref(a);
            let b = self.deref(b);
            if a == b {
                continue;
            }
            match (a.0, b.0) {
                // Younger (higher index) points to older: short chains, and
                // variables of frozen programs are bound only when they must.
                (Repr::Var(i), Repr::Var(j)) => {
                    if i < j {
                        self.bind_raw(j, a);
                    } else {
                        self.bind_raw(i, b);
                    }
                }
                (Repr::Var(i), _) => self.bind_raw(i, b),
                (_, Repr::Var(j)) => self.bind_raw(j, a),
                (Repr::Struct(p), Repr::Struct(q)) => {
                    let (fa, xs) = self.compound_at(p);
                    let (fb, ys) = self.compound_at(q);
                    if fa != fb || xs.len() != ys.len() {
                        return false;
                    }
                    if !guard.first_visit((p, q)) {
                        continue;
                    }
                    // Reversed, so the first argument is unified first and
                    // a list's tail is the last thing pushed at each level.
                    stack.extend(xs.iter().copied().zip(ys.iter().copied()).rev());
                }
                (Repr::Big(x), Repr::Big(y)) => {
                    if self.bigs[x as usize] != self.bigs[y as usize] {
                        return false;
                    }
                }
                _ => return false,
            }
        }
        true
    }

    /// Structural equality, Prolog's `==/2`: same shape, same atoms and
    /// numbers (`1 \== 1.0`), same variables.
    pub fn identical(&self, a: Term, b: Term) -> bool {
        let a = self.deref(a);
        let b = self.deref(b);
        if a == b {
            return true;
        }
        match (a.0, b.0) {
            (Repr::Struct(_), Repr::Struct(_)) => {}
            (Repr::Big(x), Repr::Big(y)) => return self.bigs[x as usize] == self.bigs[y as usize],
            _ => return false,
        }
        with_pairs(|stack| {
            let mut guard = CycleGuard::new();
            stack.push((a, b));
            while let Some((a, b)) = stack.pop() {
                let a = self.deref(a);
                let b = self.deref(b);
                if a == b {
                    continue;
                }
                match (a.0, b.0) {
                    (Repr::Struct(p), Repr::Struct(q)) => {
                        let (fa, xs) = self.compound_at(p);
                        let (fb, ys) = self.compound_at(q);
                        if fa != fb || xs.len() != ys.len() {
                            return false;
                        }
                        if !guard.first_visit((p, q)) {
                            continue;
                        }
                        stack.extend(xs.iter().copied().zip(ys.iter().copied()).rev());
                    }
                    (Repr::Big(x), Repr::Big(y)) => {
                        if self.bigs[x as usize] != self.bigs[y as usize] {
                            return false;
                        }
                    }
                    _ => return false,
                }
            }
            true
        })
    }

    /// Standard order of terms (`compare/3`): Var < Number < Atom <
    /// Compound. Variables by age; numbers by value, and `Float < Int` when
    /// equal; atoms alphabetically; compounds by arity, then name, then
    /// arguments left to right.
    ///
    /// Variable order follows cell indices, which [`Store::gc`] renumbers.
    pub fn compare(&self, a: Term, b: Term) -> Ordering {
        let a = self.deref(a);
        let b = self.deref(b);
        if a == b {
            return Ordering::Equal;
        }
        if !matches!((a.0, b.0), (Repr::Struct(_), Repr::Struct(_))) {
            return self.compare_one(a, b);
        }
        with_pairs(|stack| {
            let mut guard = CycleGuard::new();
            stack.push((a, b));
            while let Some((a, b)) = stack.pop() {
                let a = self.deref(a);
                let b = self.deref(b);
                if a == b {
                    continue;
                }
                if let (Repr::Struct(p), Repr::Struct(q)) = (a.0, b.0) {
                    let (fa, xs) = self.compound_at(p);
                    let (fb, ys) = self.compound_at(q);
                    let o = xs.len().cmp(&ys.len()).then_with(|| fa.cmp(&fb));
                    if o != Ordering::Equal {
                        return o;
                    }
                    if !guard.first_visit((p, q)) {
                        continue;
                    }
                    stack.extend(xs.iter().copied().zip(ys.iter().copied()).rev());
                } else {
                    let o = self.compare_one(a, b);
                    if o != Ordering::Equal {
                        return o;
                    }
                }
            }
            Ordering::Equal
        })
    }

    /// Order of two dereferenced terms that are not both compounds.
    fn compare_one(&self, a: Term, b: Term) -> Ordering {
        let ra = rank(a);
        let rb = rank(b);
        if ra != rb {
            return ra.cmp(&rb);
        }
        match (a.0, b.0) {
            (Repr::Var(i), Repr::Var(j)) => i.cmp(&j),
            (Repr::Atom(x), Repr::Atom(y)) => x.cmp(&y),
            _ => self.compare_numbers(a, b),
        }
    }

    /// Standard order of two numbers: by value (exactly, also between
    /// integers and floats), then `Float < Int`; floats among themselves by
    /// IEEE total order (so `-0.0 @< 0.0`, and NaN has a fixed place).
    fn compare_numbers(&self, a: Term, b: Term) -> Ordering {
        match (a.0, b.0) {
            (Repr::Int(x), Repr::Int(y)) => x.cmp(&y),
            (Repr::Float(x), Repr::Float(y)) => f64::from_bits(x).total_cmp(&f64::from_bits(y)),
            (Repr::Int(x), Repr::Float(y)) => {
                cmp_int_float(x, f64::from_bits(y)).then(Ordering::Greater)
            }
            (Repr::Float(x), Repr::Int(y)) => cmp_int_float(y, f64::from_bits(x))
                .reverse()
                .then(Ordering::Less),
            (Repr::Big(x), Repr::Big(y)) => {
                cmp_big_texts(&self.bigs[x as usize], &self.bigs[y as usize])
            }
            // A big integer lies outside the i64 range: its sign decides.
            (Repr::Big(x), Repr::Int(_)) => big_sign(&self.bigs[x as usize]),
            (Repr::Int(_), Repr::Big(y)) => big_sign(&self.bigs[y as usize]).reverse(),
            (Repr::Big(x), Repr::Float(y)) => big_to_f64(&self.bigs[x as usize])
                .total_cmp(&f64::from_bits(y))
                .then(Ordering::Greater),
            (Repr::Float(x), Repr::Big(y)) => f64::from_bits(x)
                .total_cmp(&big_to_f64(&self.bigs[y as usize]))
                .then(Ordering::Less),
            _ => Ordering::Equal,
        }
    }
}

/// Class of a term in the standard order.
fn rank(t: Term) -> u8 {
    match t.0 {
        Repr::Var(_) => 0,
        Repr::Int(_) | Repr::Float(_) | Repr::Big(_) => 1,
        Repr::Atom(_) => 3,
        Repr::Struct(_) | Repr::Functor(..) => 4,
    }
}

/// Exact comparison of an integer with a float (no rounding of the
/// integer to a float, which would make distinct values compare equal).
/// NaN sorts by its sign bit: above every integer when positive.
pub(crate) fn cmp_int_float(i: i64, f: f64) -> Ordering {
    if f.is_nan() {
        return if f.is_sign_negative() {
            Ordering::Greater
        } else {
            Ordering::Less
        };
    }
    // 2^63 is exactly representable; every i64 is below it.
    const TWO_63: f64 = 9_223_372_036_854_775_808.0;
    if f >= TWO_63 {
        return Ordering::Less;
    }
    if f < -TWO_63 {
        return Ordering::Greater;
    }
    let whole = f.trunc();
    // In range, so the cast is exact.
    let w = whole as i64;
    match i.cmp(&w) {
        Ordering::Equal => {
            if f > whole {
                Ordering::Less
            } else if f < whole {
                Ordering::Greater
            } else {
                Ordering::Equal
            }
        }
        o => o,
    }
}

/// `Greater` for a positive big integer text, `Less` for a negative one.
fn big_sign(text: &str) -> Ordering {
    if text.starts_with('-') {
        Ordering::Less
    } else {
        Ordering::Greater
    }
}

/// Compares normalised decimal texts (`-` sign, no leading zeros).
fn cmp_big_texts(x: &str, y: &str) -> Ordering {
    match (x.strip_prefix('-'), y.strip_prefix('-')) {
        (None, None) => cmp_digits(x, y),
        (Some(a), Some(b)) => cmp_digits(a, b).reverse(),
        (Some(_), None) => Ordering::Less,
        (None, Some(_)) => Ordering::Greater,
    }
}

fn cmp_digits(a: &str, b: &str) -> Ordering {
    a.len().cmp(&b.len()).then_with(|| a.cmp(b))
}

pub(crate) fn big_to_f64(text: &str) -> f64 {
    text.parse::<f64>().unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;
    use sitlog_syntax::Atom;

    fn a(s: &str) -> Term {
        Term::atom(Atom::intern(s))
    }

    /// Compounds of constants compared in place (`unify_flat`) give what
    /// the walk gives.
    #[test]
    fn unify_flat_compounds() {
        let mut s = Store::new();
        let said = Atom::intern("said");
        let yes = s.compound(said, &[a("yes")]);
        let yes2 = s.compound(said, &[a("yes")]);
        let no = s.compound(said, &[a("no")]);
        assert!(s.unify(yes, yes2));
        assert!(!s.unify(yes, no));
        assert_eq!(s.unify_flat(yes, yes2), Some(true));
        assert_eq!(s.unify_flat(yes, no), Some(false));
        assert_eq!(s.unify_flat(yes, a("yes")), None);
        let f = Atom::intern("f");
        let x = s.compound(f, &[Term::int(1), Term::float(2.0)]);
        let y = s.compound(f, &[Term::int(1), Term::float(2.0)]);
        let z = s.compound(f, &[Term::int(1), Term::float(-2.0)]);
        assert!(s.unify(x, y) && !s.unify(x, z) && !s.unify(x, yes));
        assert_eq!(s.stats().trail, 0, "ground unification binds nothing");
        // A variable argument: the walk, which binds it.
        let v = s.new_var();
        let open = s.compound(said, &[v]);
        assert_eq!(s.unify_flat(open, no), None);
        assert!(s.unify(open, no));
        assert_eq!(s.deref(v), a("no"));
    }

    /// `unify_wrapped(name, arg, e)` (the input `name(arg)` not built)
    /// gives what `unify` of the built compound gives, with the same
    /// bindings, for every pair of an input and an expectation of a grid:
    /// constants, numbers, big integers, variables (fresh, shared,
    /// repeated), compounds, another functor or arity.
    #[test]
    fn unify_wrapped_agrees_with_the_compound() {
        let inputs = [
            "yes",
            "no",
            "1",
            "1.0",
            "123456789012345678901234567890",
            "_",
            "f(_)",
            "f(a)",
            "p(a, a)",
            "p(a, b)",
            "[x, y]",
            "said(x)",
        ];
        let exps = [
            "said(yes)",
            "said(no)",
            "said(1)",
            "said(1.0)",
            "said(123456789012345678901234567890)",
            "said(_)",
            "said(f(b))",
            "said(f(X))",
            "said(p(X, X))",
            "said(p(X, Y))",
            "said([H|T])",
            "said(said(Z))",
            "said(a, b)",
            "heard(yes)",
            "yes",
            "_",
        ];
        let said = Atom::intern("said");
        for input in inputs {
            for exp in exps {
                // Each way on its own store, the same terms read in order.
                let run = |wrapped: bool| {
                    let mut s = Store::new();
                    let (arg, _) = s.parse(input).unwrap();
                    let (e, _) = s.parse(exp).unwrap();
                    let met = if wrapped {
                        match s.unify_wrapped(said, arg, e) {
                            Some(met) => met,
                            None => {
                                let whole = s.compound(said, &[arg]);
                                s.unify(whole, e)
                            }
                        }
                    } else {
                        let whole = s.compound(said, &[arg]);
                        s.unify(whole, e)
                    };
                    let whole = s.compound(said, &[arg]);
                    (met, s.writeq(whole), s.writeq(e), s.stats().trail)
                };
                assert_eq!(run(true), run(false), "said({input}) against {exp}");
            }
        }
    }

    #[test]
    fn unify_atoms_and_numbers() {
        let mut s = Store::new();
        assert!(s.unify(a("x"), a("x")));
        assert!(!s.unify(a("x"), a("y")));
        assert!(s.unify(Term::int(1), Term::int(1)));
        assert!(!s.unify(Term::int(1), Term::float(1.0)));
        assert!(!s.unify(Term::float(0.0), Term::float(-0.0)));
        assert!(s.unify(Term::float(2.5), Term::float(2.5)));
        let b1 = s
            .integer_from_text("123456789012345678901234567890")
            .unwrap();
        let b2 = s
            .integer_from_text("123456789012345678901234567890")
            .unwrap();
        let b3 = s
            .integer_from_text("-123456789012345678901234567890")
            .unwrap();
        assert!(s.unify(b1, b2));
        assert!(!s.unify(b1, b3));
        assert!(!s.unify(b1, Term::int(1)));
        assert_eq!(s.stats().trail, 0, "ground unification binds nothing");
    }

    #[test]
    fn unify_binds_and_failure_undoes() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let x = s.new_var();
        let y = s.new_var();
        // f(X, b, X) = f(a, Y, c) fails on the third argument after binding
        // X and Y: both must be unbound again.
        let t1 = s.compound(f, &[x, a("b"), x]);
        let t2 = s.compound(f, &[a("a"), y, a("c")]);
        assert!(!s.unify(t1, t2));
        assert!(s.is_var(x) && s.is_var(y));
        // f(X, b, X) = f(a, Y, a) succeeds.
        let t3 = s.compound(f, &[a("a"), y, a("a")]);
        assert!(s.unify(t1, t3));
        assert_eq!(s.deref(x), a("a"));
        assert_eq!(s.deref(y), a("b"));
        assert_eq!(s.writeq(t1), "f(a,b,a)");
    }

    #[test]
    fn unify_var_var_and_sharing() {
        let mut s = Store::new();
        let g = Atom::intern("g");
        let x = s.new_var();
        let y = s.new_var();
        let z = s.new_var();
        // g(X, Y, Z) = g(Y, Z, X): all three aliased, then one binding
        // reaches all.
        let t1 = s.compound(g, &[x, y, z]);
        let t2 = s.compound(g, &[y, z, x]);
        assert!(s.unify(t1, t2));
        assert!(s.identical(x, z) && s.identical(x, y));
        assert!(s.unify(y, Term::int(7)));
        assert_eq!(s.deref(x), Term::int(7));
        assert_eq!(s.deref(z), Term::int(7));
        // A shared subterm unified against itself through two paths.
        let w = s.new_var();
        let shared = s.compound(g, &[w, w, w]);
        let pair1 = s.compound(g, &[shared, shared, w]);
        let v = s.new_var();
        let pair2 = s.compound(g, &[v, shared, a("k")]);
        assert!(s.unify(pair1, pair2));
        assert_eq!(s.writeq(pair1), "g(g(k,k,k),g(k,k,k),k)");
        assert!(s.identical(v, shared));
    }

    #[test]
    fn mark_and_undo_restore() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let x = s.new_var();
        let y = s.new_var();
        let t = s.compound(f, &[x, y]);
        let m = s.mark();
        let u = s.compound(f, &[a("p"), a("q")]);
        assert!(s.unify(t, u));
        assert_eq!(s.writeq(t), "f(p,q)");
        s.undo_to(m);
        assert!(s.is_var(x) && s.is_var(y));
        let m2 = s.mark();
        assert!(s.unify(x, y));
        let m3 = s.mark();
        assert!(s.unify(y, a("z")));
        s.undo_to(m3);
        assert!(s.is_var(x) && s.identical(x, y));
        s.undo_to(m2);
        assert!(!s.identical(x, y));
    }

    #[test]
    fn identical_is_structural() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let x = s.new_var();
        let y = s.new_var();
        let t1 = s.compound(f, &[x, Term::int(1)]);
        let t2 = s.compound(f, &[x, Term::int(1)]);
        let t3 = s.compound(f, &[y, Term::int(1)]);
        let t4 = s.compound(f, &[x, Term::float(1.0)]);
        assert!(s.identical(t1, t2));
        assert!(!s.identical(t1, t3));
        assert!(!s.identical(t1, t4));
        assert!(s.unify(x, y));
        assert!(s.identical(t1, t3));
    }

    #[test]
    fn standard_order() {
        let mut s = Store::new();
        let x = s.new_var();
        let y = s.new_var();
        let f = Atom::intern("f");
        let g = Atom::intern("g");
        let fa = s.compound(f, &[a("a")]);
        let fb = s.compound(f, &[a("b")]);
        let ga = s.compound(g, &[a("a")]);
        let faa = s.compound(f, &[a("a"), a("a")]);
        let big = s.integer_from_text("100000000000000000000").unwrap();
        let nbig = s.integer_from_text("-100000000000000000000").unwrap();
        // Ascending, per SWI-Prolog's standard order.
        let ascending = [
            x,
            y,
            Term::float(f64::NEG_INFINITY),
            nbig,
            Term::int(i64::MIN),
            Term::float(-1.5),
            Term::float(-0.0),
            Term::float(0.0),
            Term::int(0),
            Term::float(1.0),
            Term::int(1),
            Term::int(2),
            Term::float(9.2e18),
            Term::int(i64::MAX),
            Term::float(1e20),
            big,
            Term::float(f64::INFINITY),
            Term::NIL,
            a("a"),
            a("b"),
            a("z"),
            fa,
            fb,
            ga,
            faa,
        ];
        for (i, &p) in ascending.iter().enumerate() {
            for (j, &q) in ascending.iter().enumerate() {
                assert_eq!(
                    s.compare(p, q),
                    i.cmp(&j),
                    "{} vs {}",
                    s.writeq(p),
                    s.writeq(q)
                );
            }
        }
        let big2 = s.integer_from_text("100000000000000000000").unwrap();
        assert_eq!(s.compare(big, big2), Ordering::Equal);
        // Exact comparison: 2^53 + 1 is above the float 2^53.
        let two53 = 9_007_199_254_740_992_i64;
        assert_eq!(cmp_int_float(two53 + 1, two53 as f64), Ordering::Greater);
        assert_eq!(cmp_int_float(two53, two53 as f64), Ordering::Equal);
        assert_eq!(cmp_int_float(3, 2.5), Ordering::Greater);
        assert_eq!(cmp_int_float(-3, -2.5), Ordering::Less);
        assert_eq!(cmp_int_float(2, 2.5), Ordering::Less);
        assert_eq!(cmp_int_float(i64::MAX, f64::NAN), Ordering::Less);
    }

    #[test]
    fn cyclic_terms_terminate() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let g = Atom::intern("g");
        let x = s.new_var();
        let y = s.new_var();
        let fx = s.compound(f, &[x]);
        let fy = s.compound(f, &[y]);
        assert!(s.unify(x, fx));
        assert!(s.unify(y, fy));
        assert!(!s.is_acyclic(x));
        assert!(s.unify(x, y));
        assert!(s.identical(x, y));
        assert_eq!(s.compare(x, y), Ordering::Equal);
        assert!(s.is_ground(x));
        assert!(s.term_vars(x).is_empty());
        // f(A, B, A, B) = f(g(A), g(B), B, A): unifies two distinct cyclic
        // structures inside one call.
        let a1 = s.new_var();
        let b1 = s.new_var();
        let ga = s.compound(g, &[a1]);
        let gb = s.compound(g, &[b1]);
        let l = s.compound(f, &[a1, b1, a1, b1]);
        let r = s.compound(f, &[ga, gb, b1, a1]);
        assert!(s.unify(l, r));
        assert!(!s.is_acyclic(l));
        let one = s.compound(f, &[Term::int(1)]);
        assert!(!s.unify(x, one));
        assert!(s.variant(l, l));
    }

    #[test]
    fn shared_dag_walks_stay_linear() {
        // 2^60 paths through 60 shared levels: walks must not enumerate them.
        let mut s = Store::new();
        let f = Atom::intern("f");
        let mut t1 = s.new_var();
        let mut t2 = s.new_var();
        for _ in 0..60 {
            t1 = s.compound(f, &[t1, t1]);
            t2 = s.compound(f, &[t2, t2]);
        }
        assert!(s.unify(t1, t2));
        assert!(s.identical(t1, t2));
        assert_eq!(s.compare(t1, t2), Ordering::Equal);
        assert!(!s.is_ground(t1));
        assert_eq!(s.term_vars(t1).len(), 1);
        assert!(s.is_acyclic(t1));
    }

    #[test]
    fn list_compare_long() {
        let mut s = Store::new();
        let items: Vec<Term> = (0..10_000).map(Term::int).collect();
        let l1 = s.list(&items);
        let l2 = s.list(&items);
        assert_eq!(s.compare(l1, l2), Ordering::Equal);
        assert!(s.identical(l1, l2));
        let mut items3 = items.clone();
        items3[9_999] = Term::int(10_000);
        let l3 = s.list(&items3);
        assert_eq!(s.compare(l1, l3), Ordering::Less);
        assert!(!s.identical(l1, l3));
    }
}
