//! Copying and inspecting terms as a whole: `copy_term/2` (with or without
//! a caller's variable map), `term_variables/2`, groundness, variants.
//!
//! Copies are post-order with an explicit work stack. A compound whose
//! arguments all come back unchanged is not rebuilt: ground subterms (most
//! of a program's text) are shared between the original and every copy,
//! which makes renaming a situation apart cost about its variables, not
//! its size. A compound the store knows to be ground
//! ([`Store::known_ground`]) is not even walked: copying the rest of a
//! list (`try(Ps)`) costs the same for 8 elements as for 256.
//!
//! Cyclic terms (made by `X = f(X)`): the inspections here terminate on
//! them ([`Store::is_acyclic`] detects them), but copying one does not, nor
//! does printing one; a caller that may meet them checks first.

use crate::store::Store;
use crate::term::{Repr, Term, Var};
use crate::unify::CycleGuard;
use sitlog_syntax::atoms;
use std::collections::{HashMap, HashSet};

/// Variable renaming for [`Store::copy_term_with`]: original variable ->
/// its image in the copy.
pub type VarMap = HashMap<Var, Term>;

/// Work-stack marker meaning "build the compound at this header from the
/// last `arity` results". Header cells never occur as terms to visit.
#[inline]
fn build_marker(p: u32) -> Term {
    Term(Repr::Functor(atoms::NIL, p, 0))
}

impl Store {
    /// `copy_term/2`: a copy of `t` with fresh variables, each distinct
    /// variable of `t` replaced by one fresh variable (sharing kept).
    /// Ground subterms are shared, not copied.
    pub fn copy_term(&mut self, t: Term) -> Term {
        self.copy_core(t, None)
    }

    /// Copies `t`, renaming each variable through `map`: a variable with an
    /// entry becomes that entry's term (map a variable to itself to keep it
    /// linked to the original), one without gets a fresh variable, which is
    /// added to `map` (so several copies can share a renaming).
    pub fn copy_term_with(&mut self, t: Term, map: &mut VarMap) -> Term {
        self.copy_core(t, Some(map))
    }

    fn copy_core(&mut self, t: Term, mut map: Option<&mut VarMap>) -> Term {
        // Without a map, each original variable is temporarily bound to its
        // fresh image (undone at the end): later occurrences dereference to
        // the image, recognisable as a variable created during this copy.
        let fresh_from = index_of(self.vars.len());
        let trail_start = self.trail.len();
        let mut work = std::mem::take(&mut self.work);
        let mut done = std::mem::take(&mut self.results);
        work.clear();
        done.clear();
        work.push(t);
        while let Some(item) = work.pop() {
            match item.0 {
                Repr::Functor(_, p, _) => {
                    let (name, n) = self.header_at(p);
                    let base = done.len() - n as usize;
                    let start = p as usize + 1;
                    let unchanged = done[base..] == self.cells[start..start + n as usize];
                    let built = if unchanged {
                        Term(Repr::Struct(p))
                    } else {
                        self.compound(name, &done[base..])
                    };
                    done.truncate(base);
                    done.push(built);
                }
                _ => {
                    let t = self.deref(item);
                    match t.0 {
                        Repr::Var(i) => {
                            let image = match map.as_deref_mut() {
                                Some(m) => match m.get(&Var(i)) {
                                    Some(&image) => image,
                                    None => {
                                        let v = self.new_var();
                                        m.insert(Var(i), v);
                                        v
                                    }
                                },
                                None if i >= fresh_from => t,
                                None => {
                                    let v = self.new_var();
                                    self.bind_raw(i, v);
                                    v
                                }
                            };
                            done.push(image);
                        }
                        // Ground: shared without a walk.
                        Repr::Struct(_) if self.known_ground(t) => done.push(t),
                        Repr::Struct(p) => {
                            work.push(build_marker(p));
                            let (_, args) = self.compound_at(p);
                            work.extend(args.iter().rev());
                        }
                        _ => done.push(t),
                    }
                }
            }
        }
        let result = done.pop().unwrap_or(t);
        if map.is_none() {
            while self.trail.len() > trail_start {
                if let Some(i) = self.trail.pop() {
                    self.vars[i as usize] = Term(Repr::Var(i));
                }
            }
        }
        work.clear();
        done.clear();
        self.work = work;
        self.results = done;
        result
    }

    /// `term_variables/2`: the distinct unbound variables of `t`, in
    /// depth-first, left-to-right order of first occurrence.
    pub fn term_vars(&self, t: Term) -> Vec<Term> {
        let mut seen = HashSet::new();
        let mut guard = CycleGuard::new();
        let mut out = Vec::new();
        let mut work = vec![t];
        while let Some(t) = work.pop() {
            let t = self.deref(t);
            match t.0 {
                Repr::Var(i) if seen.insert(i) => out.push(t),
                Repr::Struct(_) if self.known_ground(t) => {}
                Repr::Struct(p) if guard.first_visit(p) => {
                    work.extend(self.compound_at(p).1.iter().rev())
                }
                _ => {}
            }
        }
        out
    }

    /// Whether `t` is a finite tree (`acyclic_term/1`): false after
    /// unification without occurs check made it contain itself.
    pub fn is_acyclic(&self, t: Term) -> bool {
        let Repr::Struct(root) = self.deref(t).0 else {
            return true;
        };
        // Depth-first with an explicit path: meeting a compound that is on
        // the current path is a cycle; finished ones are not re-entered.
        const ON_PATH: bool = false;
        const DONE: bool = true;
        let mut state: HashMap<u32, bool> = HashMap::new();
        let mut path: Vec<(u32, usize)> = vec![(root, 0)];
        state.insert(root, ON_PATH);
        while let Some(&mut (p, ref mut next)) = path.last_mut() {
            let args = self.compound_at(p).1;
            let Some(&arg) = args.get(*next) else {
                state.insert(p, DONE);
                path.pop();
                continue;
            };
            *next += 1;
            if let Repr::Struct(q) = self.deref(arg).0 {
                match state.get(&q) {
                    Some(&ON_PATH) => return false,
                    Some(_) => {}
                    None => {
                        state.insert(q, ON_PATH);
                        path.push((q, 0));
                    }
                }
            }
        }
        true
    }

    /// Whether `t` contains no unbound variable.
    pub fn is_ground(&self, t: Term) -> bool {
        let mut work = Vec::new();
        let mut guard = CycleGuard::new();
        let mut t = t;
        loop {
            let d = self.deref(t);
            match d.0 {
                Repr::Var(_) => return false,
                Repr::Struct(_) if self.known_ground(d) => {}
                Repr::Struct(p) if guard.first_visit(p) => work.extend(self.compound_at(p).1),
                _ => {}
            }
            match work.pop() {
                Some(next) => t = next,
                None => return true,
            }
        }
    }

    /// `=@=/2`: `a` and `b` are equal up to a one-to-one renaming of
    /// variables.
    pub fn variant(&self, a: Term, b: Term) -> bool {
        let mut ab: HashMap<u32, u32> = HashMap::new();
        let mut ba: HashMap<u32, u32> = HashMap::new();
        let mut guard = CycleGuard::new();
        let mut work = vec![(a, b)];
        while let Some((a, b)) = work.pop() {
            let a = self.deref(a);
            let b = self.deref(b);
            match (a.0, b.0) {
                (Repr::Var(i), Repr::Var(j)) => {
                    if *ab.entry(i).or_insert(j) != j || *ba.entry(j).or_insert(i) != i {
                        return false;
                    }
                }
                (Repr::Struct(p), Repr::Struct(q)) => {
                    let (fa, xs) = self.compound_at(p);
                    let (fb, ys) = self.compound_at(q);
                    if fa != fb || xs.len() != ys.len() {
                        return false;
                    }
                    if !guard.first_visit((p, q)) {
                        continue;
                    }
                    work.extend(xs.iter().copied().zip(ys.iter().copied()));
                }
                _ => {
                    if !self.identical(a, b) {
                        return false;
                    }
                }
            }
        }
        true
    }
}

fn index_of(len: usize) -> u32 {
    crate::store::index(len)
}

#[cfg(test)]
mod tests {
    use super::*;
    use sitlog_syntax::Atom;

    fn a(s: &str) -> Term {
        Term::atom(Atom::intern(s))
    }

    #[test]
    fn known_ground_and_inert_are_decided_when_built() {
        let mut s = Store::new();
        let items: Vec<Term> = (0..300).map(|i| a(&format!("p{i}"))).collect();
        let list = s.list(&items);
        assert!(s.known_ground(list) && s.is_inert(list));
        // Copying or evaluating a ground list touches no cell.
        let cells = s.stats().cells;
        assert_eq!(s.copy_term(list), list);
        assert_eq!(s.stats().cells, cells);
        // Nor walks it inside a term with a variable (`try(Ps)` of issue
        // 37): the copy's work stack never holds more than a few terms.
        let v = s.new_var();
        let id = s.compound(Atom::intern("try"), &[v, list]);
        let c = s.copy_term(id);
        assert_eq!(s.arg(c, 1), Some(list));
        assert!(s.work.capacity() < 16, "walked: {}", s.work.capacity());
        // A variable handle, even bound, is not known ground (a binding may
        // be undone); the term is still ground when walked.
        let x = s.new_var();
        let tail = s.list(&items[1..]);
        let t = s.cons(items[0], x);
        assert!(s.unify(x, tail));
        assert!(!s.known_ground(t) && !s.is_inert(t));
        assert!(s.is_ground(t));
        // A construct of L is ground but not inert, and neither is what holds it.
        let get = s.compound(sitlog_syntax::atoms::GET, &[a("n"), Term::int(1)]);
        assert!(s.known_ground(get) && !s.is_inert(get));
        let l = s.list(&[a("x"), get]);
        assert!(s.known_ground(l) && !s.is_inert(l));
        // `get/3` is no construct of L.
        let get3 = s.compound(sitlog_syntax::atoms::GET, &[a("n"), a("m"), a("k")]);
        assert!(s.is_inert(get3));
    }

    #[test]
    fn copy_renames_and_keeps_sharing() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let x = s.new_var();
        let y = s.new_var();
        let inner = s.compound(f, &[a("k"), Term::int(2)]);
        let t = s.compound(f, &[x, y, x, inner]);
        let c = s.copy_term(t);
        assert!(s.variant(t, c));
        assert!(!s.identical(t, c));
        let cargs = s.args(c).to_vec();
        assert!(s.identical(cargs[0], cargs[2]));
        assert!(!s.identical(cargs[0], x) && !s.identical(cargs[1], y));
        // The ground subterm is shared, not copied.
        assert_eq!(cargs[3], inner);
        // Originals untouched (the binding trick is undone).
        assert!(s.is_var(x) && s.is_var(y));
        assert_eq!(s.stats().trail, 0);
        // Binding the copy does not bind the original.
        assert!(s.unify(cargs[0], a("z")));
        assert!(s.is_var(x));
        assert_eq!(s.writeq(c).matches('z').count(), 2);
    }

    #[test]
    fn copy_of_ground_term_is_the_term() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let g = s.compound(f, &[a("a"), Term::int(1)]);
        let t = s.list(&[g, g]);
        let before = s.stats().cells;
        assert_eq!(s.copy_term(t), t);
        assert_eq!(s.stats().cells, before);
        assert_eq!(s.copy_term(Term::int(3)), Term::int(3));
    }

    #[test]
    fn copy_sees_through_bindings() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let x = s.new_var();
        let y = s.new_var();
        let t = s.compound(f, &[x, y]);
        let m = s.mark();
        assert!(s.unify(x, a("bound")));
        let c = s.copy_term(t);
        assert_eq!(s.writeq(c).split(',').next(), Some("f(bound"));
        // Undoing the binding of the original does not change the copy.
        s.undo_to(m);
        assert!(s.is_var(x));
        assert!(s.writeq(c).starts_with("f(bound,_G"));
    }

    #[test]
    fn copy_with_map_keeps_linked_variables() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let keep = s.new_var();
        let other = s.new_var();
        let t = s.compound(f, &[keep, other]);
        let mut map = VarMap::new();
        map.insert(Var(keep_index(&s, keep)), keep);
        let c1 = s.copy_term_with(t, &mut map);
        let c2 = s.copy_term_with(other, &mut map);
        let cargs = s.args(c1).to_vec();
        assert!(s.identical(cargs[0], keep));
        assert!(!s.identical(cargs[1], other));
        assert!(s.identical(cargs[1], c2), "one renaming across copies");
        assert!(s.unify(keep, a("v")));
        assert_eq!(s.deref(cargs[0]), a("v"));
    }

    fn keep_index(s: &Store, t: Term) -> u32 {
        match s.value(t) {
            crate::Value::Var(v) => v.index(),
            _ => unreachable!("a variable"),
        }
    }

    #[test]
    fn vars_ground_variant() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let x = s.new_var();
        let y = s.new_var();
        let t = s.compound(f, &[y, x, y, Term::int(1)]);
        assert_eq!(s.term_vars(t), vec![y, x]);
        assert!(!s.is_ground(t));
        assert!(s.is_ground(Term::int(1)));
        let u = s.compound(f, &[x, y, x, Term::int(1)]);
        assert!(s.variant(t, u));
        let w = s.compound(f, &[x, x, x, Term::int(1)]);
        assert!(!s.variant(t, w));
        assert!(!s.variant(w, t));
        assert!(s.unify(x, Term::int(0)));
        assert!(s.unify(y, Term::int(0)));
        assert!(s.is_ground(t));
        assert!(s.term_vars(t).is_empty());
    }
}
