//! Reclaiming store space: a copying (Cheney) collector over the region
//! above the frozen one.
//!
//! Everything reachable from the caller's roots (and from bindings of
//! frozen variables) is copied, breadth-first, into a fresh region; the
//! rest is dropped. No recursion (the copied region itself is the queue),
//! sharing is preserved (forwarding tables), bound variables are short-cut
//! (a term refers to its value, not to the variable), and only unbound
//! variables survive. Cost is proportional to what survives plus the size
//! of the collected region for the forwarding tables.

use crate::store::{index, Store};
use crate::term::{Repr, Term};

/// Marks a slot of a forwarding table as not yet copied.
const UNMOVED: u32 = u32::MAX;

/// The old (from-space) region and the new (to-space) one being built.
struct Collector<'a> {
    frozen_cells: u32,
    frozen_vars: u32,
    frozen_bigs: u32,
    /// Bindings of frozen variables as they were before the collection
    /// (old references).
    frozen_var_cells: &'a [Term],
    old_cells: &'a [Term],
    old_vars: &'a [Term],
    old_bigs: Vec<Box<str>>,
    cell_fwd: &'a mut Vec<u32>,
    var_fwd: &'a mut Vec<u32>,
    big_fwd: Vec<u32>,
    new_cells: &'a mut Vec<Term>,
    new_vars: &'a mut Vec<Term>,
    new_bigs: Vec<Box<str>>,
}

impl Collector<'_> {
    fn deref_old(&self, mut t: Term) -> Term {
        while let Repr::Var(i) = t.0 {
            let b = if i < self.frozen_vars {
                self.frozen_var_cells[i as usize]
            } else {
                self.old_vars[(i - self.frozen_vars) as usize]
            };
            if b == t {
                break;
            }
            t = b;
        }
        t
    }

    /// The new-space equivalent of the old-space reference `t`, copying the
    /// top level of what it points to if not copied yet. Every old
    /// reference must be evacuated exactly once (new and old indices of
    /// the collected region overlap).
    fn evacuate(&mut self, t: Term) -> Term {
        let t = self.deref_old(t);
        match t.0 {
            Repr::Var(i) if i >= self.frozen_vars => {
                let k = (i - self.frozen_vars) as usize;
                if self.var_fwd[k] == UNMOVED {
                    let at = self.frozen_vars + index(self.new_vars.len());
                    self.new_vars.push(Term(Repr::Var(at)));
                    self.var_fwd[k] = at;
                }
                Term(Repr::Var(self.var_fwd[k]))
            }
            Repr::Struct(p) if p >= self.frozen_cells => {
                let k = (p - self.frozen_cells) as usize;
                if self.cell_fwd[k] == UNMOVED {
                    let n = match self.old_cells[k].0 {
                        Repr::Functor(_, n, _) => n as usize,
                        _ => 0,
                    };
                    let at = self.frozen_cells + index(self.new_cells.len());
                    self.new_cells
                        .extend_from_slice(&self.old_cells[k..k + 1 + n]);
                    self.cell_fwd[k] = at;
                }
                Term(Repr::Struct(self.cell_fwd[k]))
            }
            Repr::Big(b) if b >= self.frozen_bigs => {
                let k = (b - self.frozen_bigs) as usize;
                if self.big_fwd[k] == UNMOVED {
                    let at = self.frozen_bigs + index(self.new_bigs.len());
                    self.new_bigs.push(std::mem::take(&mut self.old_bigs[k]));
                    self.big_fwd[k] = at;
                }
                Term(Repr::Big(self.big_fwd[k]))
            }
            _ => t,
        }
    }

    /// Evacuates the arguments of every copied compound; copying grows
    /// `new_cells`, which this walks to the end (Cheney's scan).
    fn scan(&mut self) {
        let mut s = 0;
        while s < self.new_cells.len() {
            let cell = self.new_cells[s];
            if !matches!(cell.0, Repr::Functor(..)) {
                self.new_cells[s] = self.evacuate(cell);
            }
            s += 1;
        }
    }
}

impl Store {
    /// Collects garbage: keeps the frozen region and what `roots` reach,
    /// rewriting `roots` to the moved terms. Every other handle into the
    /// collected region becomes invalid, and so do all marks: bindings made
    /// so far are committed and the trail is emptied. Variables are
    /// renumbered (their standard order may change).
    pub fn gc(&mut self, roots: &mut [Term]) {
        let frozen = self.frozen;
        let old_bigs = self.bigs.split_off(frozen.bigs as usize);
        let mut scratch = std::mem::take(&mut self.gc_scratch);
        let (frozen_var_cells, old_vars) = self.vars.split_at(frozen.vars as usize);
        let old_cells = &self.cells[frozen.cells as usize..];
        // Reused tables: filling them touches memory already mapped.
        scratch.cell_fwd.clear();
        scratch.cell_fwd.resize(old_cells.len(), UNMOVED);
        scratch.var_fwd.clear();
        scratch.var_fwd.resize(old_vars.len(), UNMOVED);
        scratch.new_cells.clear();
        scratch.new_vars.clear();
        let mut c = Collector {
            frozen_cells: frozen.cells,
            frozen_vars: frozen.vars,
            frozen_bigs: frozen.bigs,
            frozen_var_cells,
            cell_fwd: &mut scratch.cell_fwd,
            var_fwd: &mut scratch.var_fwd,
            big_fwd: vec![UNMOVED; old_bigs.len()],
            old_cells,
            old_vars,
            old_bigs,
            new_cells: &mut scratch.new_cells,
            new_vars: &mut scratch.new_vars,
            new_bigs: Vec::new(),
        };
        for root in roots.iter_mut() {
            *root = c.evacuate(*root);
        }
        // Frozen variables bound since the freeze may point into the
        // collected region: their bindings are roots too.
        let mut frozen_bindings = Vec::new();
        for i in 0..frozen.vars {
            let b = c.frozen_var_cells[i as usize];
            if b != Term(Repr::Var(i)) {
                frozen_bindings.push((i, c.evacuate(b)));
            }
        }
        c.scan();
        let new_bigs = std::mem::take(&mut c.new_bigs);
        self.cells.truncate(frozen.cells as usize);
        self.cells.extend_from_slice(&scratch.new_cells);
        self.vars.truncate(frozen.vars as usize);
        self.vars.extend_from_slice(&scratch.new_vars);
        self.bigs.extend(new_bigs);
        for (i, b) in frozen_bindings {
            self.vars[i as usize] = b;
        }
        self.gc_scratch = scratch;
        self.trail.clear();
        let old_epoch = self.epoch;
        self.epoch = self.epoch.wrapping_add(1);
        // Lists remembered beside their terms follow their cells.
        crate::native::memo::moved(
            self.id.0,
            old_epoch,
            self.epoch,
            frozen.cells,
            &self.gc_scratch.cell_fwd,
        );
        // Give back memory after a burst, keeping room to grow.
        shrink(&mut self.cells);
        shrink(&mut self.vars);
        shrink(&mut self.trail);
        shrink(&mut self.gc_scratch.cell_fwd);
        shrink(&mut self.gc_scratch.var_fwd);
        for scratch in [&mut self.work, &mut self.results] {
            scratch.shrink_to(1 << 12);
        }
        self.pairs.shrink_to(1 << 12);
    }
}

/// Gives back memory after a burst, keeping room for the usual growth
/// between collections (so the next cycle does not reallocate).
fn shrink<T>(v: &mut Vec<T>) {
    const HEADROOM: usize = 1 << 20;
    if v.capacity() > 2 * (v.len() + HEADROOM) {
        v.shrink_to(v.len() + HEADROOM);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sitlog_syntax::Atom;

    #[test]
    fn gc_keeps_roots_and_drops_garbage() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let x = s.new_var();
        let shared = s.compound(f, &[x, Term::int(1)]);
        let keep = s.compound(f, &[shared, shared, x]);
        for i in 0..1000 {
            let g = s.new_var();
            s.compound(f, &[g, Term::int(i)]);
        }
        let big = s
            .integer_from_text("123456789012345678901234567890")
            .unwrap();
        let keep2 = s.list(&[big, Term::float(1.5)]);
        let before = s.writeq(keep);
        let mut roots = [keep, keep2];
        s.gc(&mut roots);
        let [keep, keep2] = roots;
        let st = s.stats();
        assert_eq!(st.vars, 1);
        // f/3 + f/2 (shared once) + two list cells.
        assert_eq!(st.cells, 4 + 3 + 3 + 3);
        assert_eq!(st.bigs, 1);
        assert_eq!(before, "f(f(_G0,1),f(_G0,1),_G0)");
        assert_eq!(s.writeq(keep), before);
        assert_eq!(s.writeq(keep2), "[123456789012345678901234567890,1.5]");
        // Sharing survived: both arguments are the same compound.
        let args = s.args(keep).to_vec();
        assert_eq!(args[0], args[1]);
        // The variable survived as one variable.
        let inner_x = s.arg(args[0], 0).unwrap();
        assert!(s.unify(inner_x, Term::int(9)));
        assert_eq!(s.writeq(keep), "f(f(9,1),f(9,1),9)");
    }

    #[test]
    fn gc_shortcuts_bound_variables() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let x = s.new_var();
        let y = s.new_var();
        let t = s.compound(f, &[x, y]);
        let v = s.compound(f, &[Term::int(1), Term::int(2)]);
        assert!(s.unify(x, v));
        let mut roots = [t, y];
        s.gc(&mut roots);
        assert_eq!(s.stats().vars, 1, "only the unbound variable survives");
        assert_eq!(s.stats().trail, 0);
        assert_eq!(s.writeq(roots[0]), "f(f(1,2),_G0)");
        assert!(s.identical(s.arg(roots[0], 1).unwrap(), roots[1]));
    }

    #[test]
    fn frozen_region_is_untouched_and_its_bindings_survive() {
        let mut s = Store::new();
        let f = Atom::intern("f");
        let fv = s.new_var();
        let program = s.compound(f, &[Atom::intern("const").into(), fv]);
        s.freeze();
        let cells = s.stats().cells;
        // Bind the frozen variable to a young term, then collect without
        // naming it as a root.
        let young = s.compound(f, &[Term::int(42), Term::int(43)]);
        for _ in 0..100 {
            s.compound(f, &[Term::int(0)]);
        }
        assert!(s.unify(fv, young));
        s.gc(&mut []);
        assert_eq!(s.stats().cells, cells + 3);
        assert_eq!(s.writeq(program), "f(const,f(42,43))");
        // Frozen handles stay valid with no rewriting.
        s.gc(&mut []);
        assert_eq!(s.writeq(program), "f(const,f(42,43))");
    }

    #[test]
    fn a_ground_list_stays_shared_and_known_ground() {
        // Issue 37: situation ids of a list walk share the rest of the list;
        // a collection keeps one copy of it, still known ground, so copying
        // an id after it still shares the list.
        let mut s = Store::new();
        let items: Vec<Term> = (0..300)
            .map(|i| Atom::intern(&format!("p{i}")).into())
            .collect();
        let list = s.list(&items);
        let at = |s: &Store, l: Term, k: usize| {
            let mut t = l;
            for _ in 0..k {
                t = s.arg(t, 1).unwrap();
            }
            t
        };
        let f = Atom::intern("try");
        let ids: Vec<Term> = (0..10).map(|k| s.compound(f, &[at(&s, list, k)])).collect();
        for _ in 0..1000 {
            s.compound(f, &[Term::int(0)]);
        }
        let mut roots = ids.clone();
        roots.push(list);
        s.gc(&mut roots);
        let list = roots[10];
        assert_eq!(s.stats().cells, 300 * 3 + 10 * 2, "the list once, ten ids");
        assert!(s.known_ground(list));
        for (k, &id) in roots[..10].iter().enumerate() {
            assert_eq!(s.arg(id, 0), Some(at(&s, list, k)), "shared, not copied");
        }
        let cells = s.stats().cells;
        let x = s.new_var();
        let t = s.compound(f, &[x, roots[9]]);
        let c = s.copy_term(t);
        assert_eq!(
            s.stats().cells,
            cells + 3 + 3,
            "the two compounds, not the list"
        );
        assert_eq!(s.arg(s.arg(c, 1).unwrap(), 0), Some(at(&s, list, 9)));
    }

    #[test]
    fn stale_marks_are_ignored() {
        let mut s = Store::new();
        let x = s.new_var();
        let m = s.mark();
        let mut roots = [x];
        s.gc(&mut roots);
        assert!(s.unify(roots[0], Term::int(1)));
        assert_ne!(m, s.mark());
        s.undo_to(m);
        assert_eq!(
            s.deref(roots[0]),
            Term::int(1),
            "a stale mark undoes nothing"
        );
    }

    #[test]
    fn garbage_loop_stays_bounded() {
        let mut s = Store::new();
        let f = Atom::intern("step");
        let program = {
            let v = s.new_var();
            let body = s.list(&[v, Atom::intern("constant").into(), v]);
            s.compound(f, &[v, body])
        };
        s.freeze();
        // A long-running task: each step renames the program apart, binds
        // it, keeps a small state and drops the rest.
        let mut state = Term::int(0);
        let mut peak = 0;
        for i in 0..20_000i64 {
            let copy = s.copy_term(program);
            let v = s.arg(copy, 0).unwrap();
            let junk: Vec<Term> = (0..20).map(Term::int).collect();
            let junk = s.list(&junk);
            let cell = s.compound(f, &[Term::int(i), junk]);
            assert!(s.unify(v, cell));
            state = s.compound(f, &[Term::int(i), s.arg(cell, 0).unwrap()]);
            if i % 500 == 0 {
                let mut roots = [state];
                s.gc(&mut roots);
                state = roots[0];
                let st = s.stats();
                peak = peak.max(st.cells);
                assert!(st.cells < 100, "cells after gc: {}", st.cells);
                assert!(st.vars < 10, "vars after gc: {}", st.vars);
                assert_eq!(st.trail, 0);
            }
        }
        assert!(peak < 100);
        assert!(
            s.cells.capacity() < 200_000,
            "capacity {}",
            s.cells.capacity()
        );
        assert_eq!(s.writeq(state), "step(19999,19999)");
    }
}
