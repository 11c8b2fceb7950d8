//! The update services (kb.md section 3, "Updates"): the original's names
//! and argument order, applied in place. An update either applies (possibly
//! changing nothing, as the original does for a missing target) or fails,
//! and a failing update changes nothing.
//!
//! Measured against the original (SWI-Prolog): `rm_object`, `rm_class`,
//! `change_object_name` and `change_class_name` on a missing name still
//! rewrite the relations that mention it. Updates that would corrupt the
//! model fail instead of copying the original's corruption: `add_class`
//! with an unknown mother or an existing name, `add_object` of an existing
//! individual, renaming onto an existing name, `rm_class(top)`, and
//! `change_object_class` with a missing individual or class.

use crate::entry::{new_entry, Entry, ARROW, NOT};
use crate::model::{Class, Ind, Kb};
use crate::store::TId;

/// An update service: `name(Args...)` without the two KB arguments.
pub struct UpdateService {
    pub name: &'static str,
    pub arity: usize,
    pub(crate) run: fn(&mut Kb, &[TId]) -> bool,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Who {
    Class,
    Object,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum List {
    Props,
    Rels,
}

macro_rules! updates {
    ($($name:ident / $arity:literal => $f:expr,)*) => {
        /// Every update service, by name and arity (KB arguments left out).
        pub static UPDATES: &[UpdateService] = &[
            $(UpdateService { name: stringify!($name), arity: $arity, run: $f },)*
        ];
    };
}

updates! {
    add_class / 2 => |kb, a| kb.u_add_class(a[0], a[1]),
    add_class_property / 3 => |kb, a| kb.u_add_value(Who::Class, List::Props, a[0], a[1], a[2]),
    add_object_property / 3 => |kb, a| kb.u_add_value(Who::Object, List::Props, a[0], a[1], a[2]),
    add_class_relation / 3 => |kb, a| kb.u_add_value(Who::Class, List::Rels, a[0], a[1], a[2]),
    add_object_relation / 3 => |kb, a| kb.u_add_value(Who::Object, List::Rels, a[0], a[1], a[2]),
    add_class_property_preference / 3 => |kb, a| kb.u_add_pref(Who::Class, List::Props, a[0], a[1], a[2]),
    add_class_relation_preference / 3 => |kb, a| kb.u_add_pref(Who::Class, List::Rels, a[0], a[1], a[2]),
    add_object_property_preference / 3 => |kb, a| kb.u_add_pref(Who::Object, List::Props, a[0], a[1], a[2]),
    add_object_relation_preference / 3 => |kb, a| kb.u_add_pref(Who::Object, List::Rels, a[0], a[1], a[2]),
    add_object / 2 => |kb, a| kb.u_add_object(a[0], a[1]),
    rm_class_property / 2 => |kb, a| kb.u_rm(Who::Class, List::Props, a[0], |kb, l| kb.rm_property(l, a[1])),
    rm_object_property / 2 => |kb, a| kb.u_rm(Who::Object, List::Props, a[0], |kb, l| kb.rm_property(l, a[1])),
    rm_class_relation / 2 => |kb, a| kb.u_rm(Who::Class, List::Rels, a[0], |kb, l| kb.rm_relation(l, a[1])),
    rm_object_relation / 2 => |kb, a| kb.u_rm(Who::Object, List::Rels, a[0], |kb, l| kb.rm_relation(l, a[1])),
    rm_class_property_preference / 2 => |kb, a| kb.u_rm(Who::Class, List::Props, a[0], |_, l| rm_pref(l, a[1])),
    rm_class_relation_preference / 2 => |kb, a| kb.u_rm(Who::Class, List::Rels, a[0], |_, l| rm_pref(l, a[1])),
    rm_object_property_preference / 2 => |kb, a| kb.u_rm(Who::Object, List::Props, a[0], |_, l| rm_pref(l, a[1])),
    rm_object_relation_preference / 2 => |kb, a| kb.u_rm(Who::Object, List::Rels, a[0], |_, l| rm_pref(l, a[1])),
    rm_object / 1 => |kb, a| kb.u_rm_object(a[0]),
    rm_class / 1 => |kb, a| kb.u_rm_class(a[0]),
    change_value_object_property / 3 => |kb, a| kb.u_change_value(Who::Object, List::Props, a),
    change_value_class_property / 3 => |kb, a| kb.u_change_value(Who::Class, List::Props, a),
    change_value_object_relation / 3 => |kb, a| kb.u_change_value(Who::Object, List::Rels, a),
    change_value_class_relation / 3 => |kb, a| kb.u_change_value(Who::Class, List::Rels, a),
    change_weight_object_property_preference / 3 => |kb, a| kb.u_change_weight(Who::Object, List::Props, a),
    change_weight_object_relation_preference / 3 => |kb, a| kb.u_change_weight(Who::Object, List::Rels, a),
    change_weight_class_property_preference / 3 => |kb, a| kb.u_change_weight(Who::Class, List::Props, a),
    change_weight_class_relation_preference / 3 => |kb, a| kb.u_change_weight(Who::Class, List::Rels, a),
    change_object_name / 2 => |kb, a| kb.u_change_object_name(a[0], a[1]),
    change_class_name / 2 => |kb, a| kb.u_change_class_name(a[0], a[1]),
    change_object_class / 2 => |kb, a| kb.u_change_object_class(a[0], a[1]),
}

/// Looks an update up by name and arity (KB arguments left out).
pub fn update_service(name: &str, arity: usize) -> Option<&'static UpdateService> {
    UPDATES.iter().find(|s| s.name == name && s.arity == arity)
}

/// `deleteElement([Pref,_], L)`: the first match binds the weight, so only
/// entries with that same weight go.
fn rm_pref(list: &mut Vec<Entry>, pref: TId) {
    if let Some(w) = list.iter().find(|e| e.term == pref).map(|e| e.weight) {
        list.retain(|e| !(e.term == pref && e.weight == w));
    }
}

impl Kb {
    fn entries_mut(&mut self, who: Who, list: List, x: TId) -> Option<&mut Vec<Entry>> {
        match who {
            Who::Class => {
                let c = *self.class_ix.get(&x)?;
                let cl = &mut self.classes[c as usize];
                Some(if list == List::Props {
                    &mut cl.props
                } else {
                    &mut cl.rels
                })
            }
            Who::Object => {
                let i = *self.ind_ix.get(&x)?;
                let ind = &mut self.inds[i as usize];
                Some(if list == List::Props {
                    &mut ind.props
                } else {
                    &mut ind.rels
                })
            }
        }
    }

    fn exists(&self, who: Who, x: TId) -> bool {
        match who {
            Who::Class => self.class_ix.contains_key(&x),
            Who::Object => self.ind_ix.contains_key(&x),
        }
    }

    /// The entry a value update stores: `yes` → `P`, `no` → `not(P)`,
    /// otherwise `P=>V`; for relations `not(R)` → `not(R=>V)`.
    fn value_entry(&mut self, list: List, p: TId, v: TId) -> Option<Entry> {
        let term = match list {
            List::Props if v == self.k.yes => p,
            List::Props if v == self.k.no => self.store.compound(NOT, &[p]),
            List::Rels => match self.store.unary(p, NOT) {
                Some(r) => {
                    let inner = self.store.compound(ARROW, &[r, v]);
                    self.store.compound(NOT, &[inner])
                }
                None => self.store.compound(ARROW, &[p, v]),
            },
            List::Props => self.store.compound(ARROW, &[p, v]),
        };
        let zero = self.store.int(0);
        new_entry(&mut self.store, &self.k, term, zero).ok()
    }

    fn u_add_class(&mut self, c: TId, m: TId) -> bool {
        if self.class_ix.contains_key(&c) || !self.class_ix.contains_key(&m) {
            return false;
        }
        self.classes.push(Class {
            id: c,
            mother: m,
            props: Vec::new(),
            rels: Vec::new(),
            inds: Vec::new(),
        });
        self.reindex_or_panic_free()
    }

    /// Reindex after a structural change that was checked beforehand.
    fn reindex_or_panic_free(&mut self) -> bool {
        self.reindex().is_ok()
    }

    fn u_add_value(&mut self, who: Who, list: List, x: TId, p: TId, v: TId) -> bool {
        if !self.exists(who, x) {
            return true;
        }
        let Some(e) = self.value_entry(list, p, v) else {
            return false;
        };
        if let Some(l) = self.entries_mut(who, list, x) {
            l.push(e);
        }
        self.reset_caches();
        true
    }

    fn u_add_pref(&mut self, who: Who, list: List, x: TId, pref: TId, w: TId) -> bool {
        if !self.exists(who, x) {
            return true;
        }
        let Ok(e) = new_entry(&mut self.store, &self.k, pref, w) else {
            return false;
        };
        if let Some(l) = self.entries_mut(who, list, x) {
            l.push(e);
        }
        self.reset_caches();
        true
    }

    fn u_add_object(&mut self, i: TId, c: TId) -> bool {
        if self.ind_ix.contains_key(&i) {
            return false;
        }
        let Some(&ci) = self.class_ix.get(&c) else {
            return true;
        };
        let ii = self.inds.len() as u32;
        self.inds.push(Ind {
            id: i,
            class: ci,
            props: Vec::new(),
            rels: Vec::new(),
            live: true,
        });
        self.classes[ci as usize].inds.push(ii);
        self.ind_ix.insert(i, ii);
        self.reset_caches();
        true
    }

    fn u_rm(&mut self, who: Who, list: List, x: TId, f: impl FnOnce(&Kb, &mut Vec<Entry>)) -> bool {
        if !self.exists(who, x) {
            return true;
        }
        let mut l = self
            .entries_mut(who, list, x)
            .map(std::mem::take)
            .unwrap_or_default();
        f(self, &mut l);
        if let Some(slot) = self.entries_mut(who, list, x) {
            *slot = l;
        }
        self.reset_caches();
        true
    }

    /// Drops `P=>_` (any weight), then `not(P)` and `P` (each with the
    /// weight of its first occurrence, as `deleteElement` binds it).
    fn rm_property(&self, l: &mut Vec<Entry>, p: TId) {
        l.retain(|e| self.store.binary(e.term, ARROW).is_none_or(|(a, _)| a != p));
        if let Some(np) = self.store.find_compound(NOT, &[p]) {
            rm_pref(l, np);
        }
        rm_pref(l, p);
    }

    fn rm_relation(&self, l: &mut Vec<Entry>, r: TId) {
        match self.store.unary(r, NOT) {
            Some(x) => l.retain(|e| {
                self.store
                    .unary(e.term, NOT)
                    .and_then(|i| self.store.binary(i, ARROW))
                    .is_none_or(|(a, _)| a != x)
            }),
            None => l.retain(|e| self.store.binary(e.term, ARROW).is_none_or(|(a, _)| a != r)),
        }
    }

    /// The original's `cancel_relation` over every relation list: drops
    /// `_=>X` and `not(_=>X)`, removes `X` from list values, and (its quirk)
    /// rewrites every one-element list value as a plain value and drops
    /// empty list values.
    fn cancel_relations_to(&mut self, x: TId) {
        let mut lists: Vec<Vec<Entry>> = Vec::new();
        for c in &mut self.classes {
            lists.push(std::mem::take(&mut c.rels));
        }
        let n_classes = lists.len();
        for ind in self.inds.iter_mut().filter(|i| i.live) {
            lists.push(std::mem::take(&mut ind.rels));
        }
        for l in &mut lists {
            let old = std::mem::take(l);
            for e in old {
                if let Some((v, obj)) = self.store.binary(e.term, ARROW) {
                    if obj == x {
                        continue;
                    }
                    if let Some(items) = self.store.proper_list(obj) {
                        let kept: Vec<TId> = items.into_iter().filter(|&y| y != x).collect();
                        let value = match kept.len() {
                            0 => continue,
                            1 => kept[0],
                            _ => self.store.list(&kept),
                        };
                        let term = self.store.compound(ARROW, &[v, value]);
                        if let Ok(ne) = new_entry(&mut self.store, &self.k, term, e.weight) {
                            l.push(ne);
                        }
                        continue;
                    }
                }
                let negated = self
                    .store
                    .unary(e.term, NOT)
                    .and_then(|i| self.store.binary(i, ARROW))
                    .is_some_and(|(_, obj)| obj == x);
                if !negated {
                    l.push(e);
                }
            }
        }
        let mut it = lists.into_iter();
        for c in self.classes.iter_mut() {
            c.rels = it.next().unwrap_or_default();
        }
        debug_assert_eq!(self.classes.len(), n_classes);
        for ind in self.inds.iter_mut().filter(|i| i.live) {
            ind.rels = it.next().unwrap_or_default();
        }
    }

    fn u_rm_object(&mut self, i: TId) -> bool {
        let Some(ii) = self.ind_ix.remove(&i) else {
            // The original still cancels the relations to the missing name.
            self.cancel_relations_to(i);
            self.reset_caches();
            return true;
        };
        let ind = &mut self.inds[ii as usize];
        ind.live = false;
        let c = ind.class as usize;
        self.classes[c].inds.retain(|&x| x != ii);
        self.cancel_relations_to(i);
        self.reset_caches();
        true
    }

    fn u_rm_class(&mut self, c: TId) -> bool {
        let Some(&ci) = self.class_ix.get(&c) else {
            // The original still cancels the relations to the missing name.
            self.cancel_relations_to(c);
            self.reset_caches();
            return true;
        };
        if ci == self.top {
            return false;
        }
        let removed = self.classes.remove(ci as usize);
        for &ii in &removed.inds {
            let ind = &mut self.inds[ii as usize];
            ind.live = false;
            self.ind_ix.remove(&ind.id);
        }
        for cl in &mut self.classes {
            if cl.mother == c {
                cl.mother = removed.mother;
            }
        }
        if !self.reindex_or_panic_free() {
            return false;
        }
        self.cancel_relations_to(c);
        self.reset_caches();
        true
    }

    fn u_change_value(&mut self, who: Who, list: List, a: &[TId]) -> bool {
        let (x, p, v) = (a[0], a[1], a[2]);
        if list == List::Rels {
            let ok = |kb: &Kb, t: TId| kb.exists(who, t);
            let valid = ok(self, v)
                || self
                    .store
                    .proper_list(v)
                    .is_some_and(|items| items.iter().all(|&t| ok(self, t)));
            if !valid {
                return false;
            }
        }
        if !self.exists(who, x) {
            return true;
        }
        let Some(e) = self.value_entry(list, p, v) else {
            return false;
        };
        let mut l = self
            .entries_mut(who, list, x)
            .map(std::mem::take)
            .unwrap_or_default();
        match list {
            List::Props => self.rm_property(&mut l, p),
            List::Rels => self.rm_relation(&mut l, p),
        }
        l.push(e);
        if let Some(slot) = self.entries_mut(who, list, x) {
            *slot = l;
        }
        self.reset_caches();
        true
    }

    fn u_change_weight(&mut self, who: Who, list: List, a: &[TId]) -> bool {
        let (x, pref, w) = (a[0], a[1], a[2]);
        if !self.exists(who, x) {
            return true;
        }
        let Ok(e) = new_entry(&mut self.store, &self.k, pref, w) else {
            return false;
        };
        if let Some(l) = self.entries_mut(who, list, x) {
            rm_pref(l, pref);
            l.push(e);
        }
        self.reset_caches();
        true
    }

    /// `R=>Old` / `not(R=>Old)` become `R=>New` / `not(R=>New)` in every
    /// relation list (not inside list values, as in the original).
    fn rename_in_relations(&mut self, old: TId, new: TId) {
        let mut all: Vec<&mut Vec<Entry>> = Vec::new();
        let store = &mut self.store;
        for c in &mut self.classes {
            all.push(&mut c.rels);
        }
        for ind in self.inds.iter_mut().filter(|i| i.live) {
            all.push(&mut ind.rels);
        }
        for l in all {
            for e in l.iter_mut() {
                let term =
                    if let Some((r, v)) = store.binary(e.term, ARROW).filter(|&(_, v)| v == old) {
                        let _ = v;
                        Some(store.compound(ARROW, &[r, new]))
                    } else if let Some((r, _)) = store
                        .unary(e.term, NOT)
                        .and_then(|i| store.binary(i, ARROW))
                        .filter(|&(_, v)| v == old)
                    {
                        let inner = store.compound(ARROW, &[r, new]);
                        Some(store.compound(NOT, &[inner]))
                    } else {
                        None
                    };
                if let Some(t) = term {
                    e.term = t;
                    e.pair = store.list(&[t, e.weight]);
                }
            }
        }
    }

    fn u_change_object_name(&mut self, i: TId, new: TId) -> bool {
        let Some(&ii) = self.ind_ix.get(&i) else {
            // The original still renames the relations to the missing name.
            self.rename_in_relations(i, new);
            self.reset_caches();
            return true;
        };
        if i == new {
            return true;
        }
        if self.ind_ix.contains_key(&new) {
            return false;
        }
        self.ind_ix.remove(&i);
        self.ind_ix.insert(new, ii);
        self.inds[ii as usize].id = new;
        self.rename_in_relations(i, new);
        self.reset_caches();
        true
    }

    fn u_change_class_name(&mut self, c: TId, new: TId) -> bool {
        let Some(&ci) = self.class_ix.get(&c) else {
            // The original still renames the relations to the missing name.
            self.rename_in_relations(c, new);
            self.reset_caches();
            return true;
        };
        if c == new {
            return true;
        }
        if self.class_ix.contains_key(&new) || ci == self.top || new == self.k.top {
            return false;
        }
        self.classes[ci as usize].id = new;
        for cl in &mut self.classes {
            if cl.mother == c {
                cl.mother = new;
            }
        }
        if !self.reindex_or_panic_free() {
            return false;
        }
        self.rename_in_relations(c, new);
        self.reset_caches();
        true
    }

    fn u_change_object_class(&mut self, i: TId, c: TId) -> bool {
        let (Some(&ii), Some(&ci)) = (self.ind_ix.get(&i), self.class_ix.get(&c)) else {
            return false;
        };
        let old = self.inds[ii as usize].class as usize;
        self.classes[old].inds.retain(|&x| x != ii);
        self.classes[ci as usize].inds.insert(0, ii);
        self.inds[ii as usize].class = ci;
        self.reset_caches();
        true
    }
}
