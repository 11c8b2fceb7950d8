//! The KB's data model: classes, individuals and their weighted entries, the
//! indexes over them (id → class, id → individual, class → children), and
//! reading a KB term into that model with validation.
//!
//! Order is meaningful everywhere (file order of classes, individuals and
//! entries decides answers), so everything is kept in vectors in file order;
//! the hash maps are only indexes into them.

use crate::closure::ClassCache;
use crate::entry::{key_bit, make_entry, Entry, Known};
use crate::store::{TId, TermStore};
use sitlog_syntax::{atoms, Atom, Clause, Span, TermId};
use std::collections::HashMap;
use std::sync::{Arc, OnceLock};

#[derive(Clone, Debug)]
pub(crate) struct Class {
    pub id: TId,
    pub mother: TId,
    pub props: Vec<Entry>,
    pub rels: Vec<Entry>,
    /// Individuals of this class, file order (indexes into `Kb::inds`).
    pub inds: Vec<u32>,
}

#[derive(Clone, Debug)]
pub(crate) struct Ind {
    pub id: TId,
    pub class: u32,
    pub props: Vec<Entry>,
    pub rels: Vec<Entry>,
    /// False once removed (slots are not reused, so indexes stay stable).
    pub live: bool,
}

/// An individual's own entries in brief: the keys of its absolute
/// properties and relations, and whether it has defaults of its own.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Bloom {
    pub props: u64,
    pub rels: u64,
    pub prop_rules: bool,
    pub rel_rules: bool,
}

impl Bloom {
    pub fn of(ind: &Ind) -> Bloom {
        let keys = |l: &[Entry]| {
            l.iter()
                .filter(|e| e.abs)
                .fold(0, |b, e| b | key_bit(e.key))
        };
        Bloom {
            props: keys(&ind.props),
            rels: keys(&ind.rels),
            prop_rules: ind.props.iter().any(|e| !e.abs),
            rel_rules: ind.rels.iter().any(|e| !e.abs),
        }
    }
}

/// A KB that failed validation: where and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ModelError {
    pub span: Span,
    pub message: String,
}

/// The robot's non-monotonic knowledge base.
#[derive(Clone, Debug)]
pub struct Kb {
    pub(crate) store: TermStore,
    pub(crate) k: Known,
    pub(crate) classes: Vec<Class>,
    pub(crate) class_ix: HashMap<TId, u32>,
    /// Mother of each class as an index (`None` for `top`).
    pub(crate) mother_ix: Vec<Option<u32>>,
    pub(crate) children: Vec<Vec<u32>>,
    pub(crate) inds: Vec<Ind>,
    pub(crate) ind_ix: HashMap<TId, u32>,
    pub(crate) top: u32,
    pub(crate) caches: Vec<OnceLock<Arc<ClassCache>>>,
    /// `class_extension(top, _)` order, computed on first use.
    pub(crate) all_order: OnceLock<Arc<Vec<u32>>>,
    /// Per individual (by index), a summary of its own entries, computed on
    /// first use: extensions then skip reading the entries themselves.
    pub(crate) blooms: OnceLock<Arc<Vec<Bloom>>>,
    /// Reuse class closures for individuals (off only to test that reuse).
    pub(crate) shortcuts: bool,
}

fn err(span: Span, message: impl Into<String>) -> ModelError {
    ModelError {
        span,
        message: message.into(),
    }
}

impl Kb {
    pub(crate) fn empty_store() -> (TermStore, Known) {
        let mut s = TermStore::new();
        let k = Known {
            yes: s.atom(atoms::YES),
            no: s.atom(atoms::NO),
            unknown: s.atom(atoms::UNKNOWN),
            dash: s.atom(atoms::MINUS),
            nil: s.atom(atoms::NIL),
            top: s.atom(atoms::TOP),
            none: s.atom(atoms::NONE),
        };
        (s, k)
    }

    /// Builds a KB from parsed classes; checks the hierarchy.
    pub(crate) fn assemble(
        store: TermStore,
        k: Known,
        classes: Vec<Class>,
        inds: Vec<Ind>,
        spans: Option<&[(Span, Span)]>,
    ) -> Result<Kb, ModelError> {
        let mut kb = Kb {
            store,
            k,
            classes,
            class_ix: HashMap::new(),
            mother_ix: Vec::new(),
            children: Vec::new(),
            inds,
            ind_ix: HashMap::new(),
            top: 0,
            caches: Vec::new(),
            all_order: OnceLock::new(),
            blooms: OnceLock::new(),
            shortcuts: true,
        };
        kb.reindex().map_err(|(ci, msg, on_mother)| {
            let span = spans
                .and_then(|s| s.get(ci as usize))
                .map(|(class, mother)| if on_mother { *mother } else { *class })
                .unwrap_or_default();
            err(span, msg)
        })?;
        Ok(kb)
    }

    /// Recomputes every index from `classes` and `inds`. On error: the class
    /// at fault, the message, and whether the mother term is to blame.
    pub(crate) fn reindex(&mut self) -> Result<(), (u32, String, bool)> {
        let n = self.classes.len();
        self.class_ix.clear();
        self.class_ix.reserve(n);
        for (i, c) in self.classes.iter().enumerate() {
            if self.class_ix.insert(c.id, i as u32).is_some() {
                let msg = format!("duplicate class `{}`", self.show(c.id));
                return Err((i as u32, msg, false));
            }
        }
        let top = *self.class_ix.get(&self.k.top).ok_or((
            0,
            "the KB has no class `top`".to_owned(),
            false,
        ))?;
        self.top = top;
        self.mother_ix = vec![None; n];
        self.children = vec![Vec::new(); n];
        for (i, c) in self.classes.iter().enumerate() {
            if i as u32 == top {
                if c.mother != self.k.none {
                    return Err((i as u32, "the mother of `top` must be `none`".into(), true));
                }
                continue;
            }
            match self.class_ix.get(&c.mother) {
                Some(&m) => {
                    self.mother_ix[i] = Some(m);
                    self.children[m as usize].push(i as u32);
                }
                None => {
                    let msg = format!(
                        "unknown mother class `{}` of class `{}`",
                        self.show(c.mother),
                        self.show(c.id)
                    );
                    return Err((i as u32, msg, true));
                }
            }
        }
        // Every class must reach `top`: walk up with a step bound.
        let mut reaches = vec![false; n];
        reaches[top as usize] = true;
        for start in 0..n {
            let mut path = Vec::new();
            let mut cur = start as u32;
            while !reaches[cur as usize] {
                if path.len() > n {
                    let msg = format!(
                        "class `{}` is in a cycle of the class hierarchy",
                        self.show(self.classes[start].id)
                    );
                    return Err((start as u32, msg, true));
                }
                path.push(cur);
                match self.mother_ix[cur as usize] {
                    Some(m) => cur = m,
                    None => break,
                }
            }
            for p in path {
                reaches[p as usize] = true;
            }
        }
        self.ind_ix.clear();
        for (ci, c) in self.classes.iter().enumerate() {
            for &ii in &c.inds {
                let ind = &mut self.inds[ii as usize];
                ind.class = ci as u32;
                let id = ind.id;
                if self.ind_ix.insert(id, ii).is_some() {
                    let msg = format!("duplicate individual `{}`", self.show(id));
                    return Err((ci as u32, msg, false));
                }
            }
        }
        self.reset_caches();
        Ok(())
    }

    /// Turns the reuse of class closures for individuals on or off (for
    /// testing that the reuse never changes an answer).
    #[doc(hidden)]
    pub fn set_shortcuts(&mut self, on: bool) {
        self.shortcuts = on;
    }

    pub(crate) fn reset_caches(&mut self) {
        self.caches = (0..self.classes.len()).map(|_| OnceLock::new()).collect();
        self.all_order = OnceLock::new();
        self.blooms = OnceLock::new();
    }

    pub(crate) fn show(&self, t: TId) -> String {
        sitlog_syntax::writeq(&self.store, t)
    }

    /// Reads a KB term (a list of `class/5`) into a KB.
    pub fn from_clause(clause: &Clause) -> Result<Kb, ModelError> {
        let (mut store, k) = Kb::empty_store();
        let terms = &clause.terms;
        let items = terms.proper_list(clause.root).ok_or_else(|| {
            err(
                terms.span(clause.root),
                "a KB must be a list of class(Id, Mother, Properties, Relations, Individuals) terms",
            )
        })?;
        let class_atom = Atom::intern("class");
        let mut classes = Vec::with_capacity(items.len());
        let mut inds = Vec::new();
        let mut spans = Vec::with_capacity(items.len());
        let mut ind_seen: HashMap<TId, Span> = HashMap::new();
        let mut class_seen: HashMap<TId, Span> = HashMap::new();
        for item in items {
            let args = terms.compound(item, class_atom, 5).ok_or_else(|| {
                err(
                    terms.span(item),
                    "expected class(Id, Mother, Properties, Relations, Individuals)",
                )
            })?;
            let id = intern(&mut store, clause, args[0])?;
            if class_seen.contains_key(&id) {
                return Err(err(
                    terms.span(args[0]),
                    format!("duplicate class `{}`", sitlog_syntax::writeq(&store, id)),
                ));
            }
            class_seen.insert(id, terms.span(args[0]));
            let mother = intern(&mut store, clause, args[1])?;
            let props = entries(&mut store, &k, clause, args[2], "properties")?;
            let rels = entries(&mut store, &k, clause, args[3], "relations")?;
            let ind_items = terms.proper_list(args[4]).ok_or_else(|| {
                err(
                    terms.span(args[4]),
                    "the individuals of a class must be a list of [id=>Name, Properties, Relations]",
                )
            })?;
            let ci = classes.len() as u32;
            let mut mine = Vec::with_capacity(ind_items.len());
            for it in ind_items {
                let shape_err = || {
                    err(
                        terms.span(it),
                        "expected an individual [id=>Name, Properties, Relations]",
                    )
                };
                let parts = terms.proper_list(it).ok_or_else(shape_err)?;
                let [idt, p, r] = parts[..] else {
                    return Err(shape_err());
                };
                let name = terms
                    .compound(idt, atoms::ARROW, 2)
                    .filter(|a| terms.atom(a[0]) == Some(atoms::ID))
                    .ok_or_else(|| err(terms.span(idt), "expected id=>Name"))?[1];
                let name_id = intern(&mut store, clause, name)?;
                if ind_seen.insert(name_id, terms.span(name)).is_some() {
                    return Err(err(
                        terms.span(name),
                        format!(
                            "duplicate individual `{}`",
                            sitlog_syntax::writeq(&store, name_id)
                        ),
                    ));
                }
                let props = entries(&mut store, &k, clause, p, "properties")?;
                let rels = entries(&mut store, &k, clause, r, "relations")?;
                mine.push(inds.len() as u32);
                inds.push(Ind {
                    id: name_id,
                    class: ci,
                    props,
                    rels,
                    live: true,
                });
            }
            spans.push((terms.span(item), terms.span(args[1])));
            classes.push(Class {
                id,
                mother,
                props,
                rels,
                inds: mine,
            });
        }
        let root_span = clause.span;
        Kb::assemble(store, k, classes, inds, Some(&spans)).map_err(|e| {
            if e.message.contains("no class `top`") {
                err(root_span, e.message)
            } else {
                e
            }
        })
    }
}

fn intern(store: &mut TermStore, clause: &Clause, t: TermId) -> Result<TId, ModelError> {
    store
        .intern(clause, t)
        .map_err(|span| err(span, "variables are not allowed in a KB"))
}

/// Reads a list of `[Entry, Weight]`.
fn entries(
    store: &mut TermStore,
    k: &Known,
    clause: &Clause,
    list: TermId,
    what: &str,
) -> Result<Vec<Entry>, ModelError> {
    let terms = &clause.terms;
    let items = terms.proper_list(list).ok_or_else(|| {
        err(
            terms.span(list),
            format!("the {what} must be a list of [Entry, Weight] pairs"),
        )
    })?;
    let mut out = Vec::with_capacity(items.len());
    for it in items {
        let pair = intern(store, clause, it)?;
        let Some(parts) = store.proper_list(pair).filter(|p| p.len() == 2) else {
            return Err(err(terms.span(it), "expected [Entry, Weight]"));
        };
        let span_of = |i: usize| {
            terms
                .proper_list(it)
                .and_then(|p| p.get(i).copied())
                .map(|t| terms.span(t))
                .unwrap_or(terms.span(it))
        };
        let e =
            make_entry(store, k, pair, parts[0], parts[1]).map_err(|(i, m)| err(span_of(i), m))?;
        out.push(e);
    }
    Ok(out)
}
