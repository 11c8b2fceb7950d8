//! Synthetic KBs for benchmarks and scale tests: a class tree of a given
//! depth (two subclasses per class) with absolute properties, exceptions,
//! conditional defaults (backward and forward chaining, abduction rules) and
//! `n` individuals on the leaves, a few percent of them with entries that
//! defeat the per-class cache. Deterministic: same arguments, same KB.

use crate::entry::{new_entry, term_key, Entry, Known, ARROW, DEFAULT, NOT};
use crate::model::{Class, Ind, Kb};
use crate::store::{TId, TermStore};
use sitlog_syntax::Atom;

struct G<'a> {
    s: &'a mut TermStore,
    k: Known,
}

impl G<'_> {
    fn a(&mut self, name: &str) -> TId {
        self.s.atom(Atom::intern(name))
    }
    fn arrow(&mut self, p: &str, v: &str) -> TId {
        let (p, v) = (self.a(p), self.a(v));
        self.s.compound(ARROW, &[p, v])
    }
    fn not(&mut self, t: TId) -> TId {
        self.s.compound(NOT, &[t])
    }
    fn rule(&mut self, ant: TId, cons: TId) -> TId {
        self.s.compound(DEFAULT, &[ant, cons])
    }
    fn e(&mut self, term: TId, w: i64) -> Entry {
        let w = self.s.int(w);
        let k = self.k;
        // Every shape built here is valid; fall back to a plain fact otherwise.
        match new_entry(self.s, &k, term, w) {
            Ok(e) => e,
            Err(_) => {
                let zero = self.s.int(0);
                let pair = self.s.list(&[term, zero]);
                let key = term_key(self.s, term);
                Entry {
                    pair,
                    term,
                    weight: zero,
                    abs: true,
                    w: 0.0,
                    key,
                }
            }
        }
    }
}

/// Number of classes [`generate`] makes for `depth` (top included).
pub fn class_count(depth: usize) -> usize {
    (1usize << (depth.min(20) + 1)) - 1
}

/// A KB with `individuals` individuals in a class tree of `depth` levels
/// below `top` (two subclasses per class).
pub fn generate(individuals: usize, depth: usize) -> Kb {
    let depth = depth.clamp(1, 20);
    let (mut store, k) = Kb::empty_store();
    let mut g = G { s: &mut store, k };
    let mut classes: Vec<Class> = Vec::new();
    let top = g.a("top");
    let none = g.a("none");
    classes.push(Class {
        id: top,
        mother: none,
        props: vec![],
        rels: vec![],
        inds: vec![],
    });
    let mut prev: Vec<TId> = vec![top];
    let mut leaves: Vec<usize> = Vec::new();
    for d in 1..=depth {
        let mut level = Vec::new();
        for (j, &mother) in prev
            .iter()
            .enumerate()
            .flat_map(|(m, x)| [(2 * m, x), (2 * m + 1, x)])
        {
            let id = g.a(&format!("c{d}_{j}"));
            let mut props = Vec::new();
            let mut rels = Vec::new();
            let t = g.arrow(&format!("p{d}"), &format!("v{}", j % 3));
            props.push(g.e(t, 0));
            let swims = g.a("swims");
            if d % 2 == 0 {
                let n = g.not(swims);
                props.push(g.e(n, 0));
            } else if j % 2 == 1 {
                props.push(g.e(swims, 0));
            }
            let dash = g.k.dash;
            let shelf = g.arrow("loc", &format!("shelf{d}"));
            let r = g.rule(dash, shelf);
            props.push(g.e(r, d as i64 + 1));
            match d {
                1 => {
                    let ant = g.arrow("works_at", "-");
                    let cons = g.arrow("loc", "-");
                    let r = g.rule(ant, cons);
                    props.push(g.e(r, 1));
                    let likes = g.arrow("likes", "c2_0");
                    rels.push(g.e(likes, 0));
                }
                2 => {
                    let late = g.a("late");
                    let stressed = g.a("stressed");
                    let r1 = g.rule(late, stressed);
                    props.push(g.e(r1, 2));
                    let room = g.arrow("found_in", &format!("room{j}"));
                    let r2 = g.rule(stressed, room);
                    props.push(g.e(r2, 1));
                }
                3 => {
                    let misplaced = g.a("misplaced");
                    for (who, w) in [("kid", 1), ("cat", 2)] {
                        let ant = g.arrow("moved_by", who);
                        let r = g.rule(ant, misplaced);
                        props.push(g.e(r, w));
                    }
                }
                _ => {}
            }
            if d == depth {
                leaves.push(classes.len());
            }
            classes.push(Class {
                id,
                mother,
                props,
                rels,
                inds: vec![],
            });
            level.push(id);
        }
        prev = level;
    }
    let mut inds = Vec::with_capacity(individuals);
    for i in 0..individuals {
        // Contiguous blocks per leaf, as individuals are grouped in real files.
        let leaf = leaves[(i * leaves.len() / individuals.max(1)).min(leaves.len() - 1)];
        let id = g.a(&format!("o{i}"));
        let size = g.s.int((i % 10) as i64);
        let size_atom = g.a("size");
        let t = g.s.compound(ARROW, &[size_atom, size]);
        let mut props = vec![g.e(t, 0)];
        let mut rels = Vec::new();
        match i % 100 {
            0 => {
                let late = g.a("late");
                props.push(g.e(late, 0));
            }
            1 => {
                let t = g.arrow("works_at", &format!("lab{}", i % 7));
                props.push(g.e(t, 0));
            }
            2 => {
                let m = g.a("misplaced");
                props.push(g.e(m, 0));
                let t = g.arrow("moved_by", "cat");
                props.push(g.e(t, 0));
            }
            _ => {}
        }
        if i % 250 == 3 {
            let dash = g.k.dash;
            let desk = g.arrow("loc", "desk");
            let r = g.rule(dash, desk);
            props.push(g.e(r, 1));
        }
        if i % 10 == 0 && individuals > 1 {
            let t = g.arrow("owner", &format!("o{}", (i + 1) % individuals));
            rels.push(g.e(t, 0));
        }
        classes[leaf].inds.push(i as u32);
        inds.push(Ind {
            id,
            class: leaf as u32,
            props,
            rels,
            live: true,
        });
    }
    // The generator builds a valid tree, so this cannot fail; degrade to
    // the bare `top` rather than panic if it ever did.
    Kb::assemble(store, k, classes, inds, None).unwrap_or_else(|_| minimal())
}

fn minimal() -> Kb {
    let (store, k) = Kb::empty_store();
    let top = Class {
        id: k.top,
        mother: k.none,
        props: vec![],
        rels: vec![],
        inds: vec![],
    };
    let mut kb = Kb {
        store,
        k,
        classes: vec![top],
        class_ix: Default::default(),
        mother_ix: vec![None],
        children: vec![vec![]],
        inds: vec![],
        ind_ix: Default::default(),
        top: 0,
        caches: vec![],
        all_order: Default::default(),
        blooms: Default::default(),
        shortcuts: true,
    };
    let _ = kb.reindex();
    kb
}

/// [`generate`] in the file format (for round-trip and parser tests).
pub fn generate_text(individuals: usize, depth: usize) -> String {
    generate(individuals, depth).to_text()
}
