//! The query services (kb.md section 3): the eight main services and the
//! value and structure services, with the original's names, argument order
//! and answers, plus the table that maps `name/arity` to each of them.

use crate::closure::{Budget, Ctx, Kind, Part, PE};
use crate::entry::{key_bit, Entry, ARROW, NOT};
use crate::model::Kb;
use crate::store::{Built, TId};
use std::sync::Arc;

/// A query argument, looked up in the KB's store (a term the store does not
/// hold equals no KB term, but its parts may still matter).
#[derive(Clone, Copy, Debug)]
pub struct Arg {
    /// The whole term, if the store has it.
    pub t: Option<TId>,
    /// The term as a closure entry (`p=>v` split), if its parts are known.
    pub(crate) pe: Option<PE>,
    /// For `not(X)`: `Some(X's id if known)`.
    pub not_inner: Option<Option<TId>>,
}

/// A service's implementation: `Ok(None)` when the original's call fails.
pub(crate) type Handler = fn(&Kb, &[Arg], &mut Built<'_>) -> Result<Option<TId>, Budget>;

/// A query service: `name(Args..., Answer)` without the KB argument.
pub struct Service {
    pub name: &'static str,
    /// Arguments including the answer (the original's arity minus the KB).
    pub arity: usize,
    pub(crate) run: Handler,
}

macro_rules! services {
    ($($name:ident / $arity:literal => $f:expr,)*) => {
        /// Every query service, by name and arity (answer included).
        pub static SERVICES: &[Service] = &[
            $(Service { name: stringify!($name), arity: $arity, run: $f },)*
        ];
    };
}

services! {
    class_extension / 2 => |kb, a, b| Ok(Some(kb.s_class_extension(a[0], b))),
    objects_of_a_class / 2 => |kb, a, b| Ok(Some(kb.s_class_extension(a[0], b))),
    property_extension / 2 => |kb, a, b| kb.s_property_extension(a[0], b).map(Some),
    relation_extension / 2 => |kb, a, b| kb.s_relation_extension(a[0], b).map(Some),
    explanation_extension / 2 => |kb, a, b| kb.s_explanation_extension(a[0], b).map(Some),
    classes_of_individual / 2 => |kb, a, b| Ok(Some(kb.s_classes_of_individual(a[0], b))),
    properties_of_individual / 2 => |kb, a, b| kb.s_object_list(a[0], Kind::Props, b).map(Some),
    object_properties / 2 => |kb, a, b| kb.s_object_list(a[0], Kind::Props, b).map(Some),
    object_relations / 2 => |kb, a, b| kb.s_object_list(a[0], Kind::Rels, b).map(Some),
    relations_of_individual / 2 => |kb, a, b| kb.s_relations_of_individual(a[0], b).map(Some),
    explanation_of_individual / 2 => |kb, a, b| kb.s_explanation_of_individual(a[0], b),
    object_property_value / 3 => |kb, a, b| kb.s_object_value(a[0], a[1], Kind::Props, b).map(Some),
    object_relation_value / 3 => |kb, a, b| kb.s_object_value(a[0], a[1], Kind::Rels, b).map(Some),
    object_property_list / 3 => |kb, a, b| kb.s_object_property_list(a[0], a[1], b).map(Some),
    object_property_preference_value / 3 => |kb, a, _| Ok(Some(kb.s_object_property_preference_value(a[0], a[1]))),
    class_property_value / 3 => |kb, a, b| kb.s_class_property_value(a[0], a[1], b),
    class_property_list / 3 => |kb, a, b| kb.s_class_property_list(a[0], a[1], b).map(Some),
    class_has_property / 3 => |kb, a, b| kb.s_class_has_property(a[0], a[1], b).map(Some),
    class_relation_value / 3 => |kb, a, b| kb.s_class_relation_value(a[0], a[1], b).map(Some),
    class_properties / 2 => |kb, a, b| kb.s_class_list(a[0], Kind::Props, b).map(Some),
    class_relations / 2 => |kb, a, b| kb.s_class_list(a[0], Kind::Rels, b).map(Some),
    there_is_class / 2 => |kb, a, _| Ok(Some(if kb.class_of(a[0]).is_some() { kb.k.yes } else { kb.k.unknown })),
    there_is_object / 2 => |kb, a, _| Ok(Some(if kb.ind_of(a[0]).is_some() { kb.k.yes } else { kb.k.unknown })),
    class_of_an_object / 2 => |kb, a, _| Ok(Some(kb.ind_of(a[0]).map_or(kb.k.unknown, |i| kb.classes[kb.inds[i as usize].class as usize].id))),
    mother_of_a_class / 2 => |kb, a, _| Ok(Some(kb.class_of(a[0]).map_or(kb.k.unknown, |c| kb.classes[c as usize].mother))),
    class_ancestors / 2 => |kb, a, b| Ok(Some(kb.s_class_ancestors(a[0], b))),
    sons_of_class / 2 => |kb, a, b| Ok(Some(match kb.class_of(a[0]) {
        Some(c) => b.list_from(kb.children[c as usize].iter().map(|&x| kb.classes[x as usize].id)),
        None => kb.k.unknown,
    })),
    descendants_of_a_class / 2 => |kb, a, b| Ok(Some(match kb.class_of(a[0]) {
        Some(c) => { let d = kb.descendants(c); b.list_from(d.iter().map(|&x| kb.classes[x as usize].id)) }
        None => kb.k.unknown,
    })),
}

/// Looks a service up by name and arity (answer included).
pub fn service(name: &str, arity: usize) -> Option<&'static Service> {
    SERVICES.iter().find(|s| s.name == name && s.arity == arity)
}

/// How an individual's closure is obtained.
pub(crate) enum IndPart {
    /// Its class's closure plus its own facts (no default can see them).
    Reuse,
    /// Its own facts change what the class's defaults derive: the list
    /// before step 4, computed with the class's ordered defaults.
    OwnFacts(Result<Vec<PE>, Budget>),
    /// It has defaults of its own: a closure of its own.
    Full(Part),
}

impl Kb {
    pub(crate) fn class_of(&self, a: Arg) -> Option<u32> {
        a.t.and_then(|t| self.class_ix.get(&t).copied())
    }

    pub(crate) fn ind_of(&self, a: Arg) -> Option<u32> {
        a.t.and_then(|t| self.ind_ix.get(&t).copied())
    }

    /// Breadth first, file order; the class itself not included.
    pub(crate) fn descendants(&self, c: u32) -> Vec<u32> {
        let mut out: Vec<u32> = self.children[c as usize].clone();
        let mut i = 0;
        while i < out.len() {
            let kids = &self.children[out[i] as usize];
            out.extend_from_slice(kids);
            i += 1;
            if out.len() > self.classes.len() {
                break;
            }
        }
        out
    }

    /// Individuals of `c` then of its descendants (the original's order).
    pub(crate) fn extension(&self, c: u32) -> Vec<u32> {
        if c == self.top {
            return self.all_inds().to_vec();
        }
        self.extension_uncached(c)
    }

    fn extension_uncached(&self, c: u32) -> Vec<u32> {
        let mut out: Vec<u32> = self.classes[c as usize].inds.clone();
        for d in self.descendants(c) {
            out.extend_from_slice(&self.classes[d as usize].inds);
        }
        out
    }

    pub(crate) fn blooms(&self) -> Arc<Vec<crate::model::Bloom>> {
        self.blooms
            .get_or_init(|| Arc::new(self.inds.iter().map(crate::model::Bloom::of).collect()))
            .clone()
    }

    pub(crate) fn all_inds(&self) -> Arc<Vec<u32>> {
        self.all_order
            .get_or_init(|| Arc::new(self.extension_uncached(self.top)))
            .clone()
    }

    fn s_class_extension(&self, c: Arg, b: &mut Built<'_>) -> TId {
        match self.class_of(c) {
            Some(c) => {
                let ext = self.extension(c);
                b.list_from(ext.iter().map(|&i| self.inds[i as usize].id))
            }
            None => self.k.unknown,
        }
    }

    fn s_classes_of_individual(&self, i: Arg, b: &mut Built<'_>) -> TId {
        match self.ind_of(i) {
            Some(i) => {
                let chain = self.chain(self.inds[i as usize].class);
                b.list_from(chain.iter().map(|&c| self.classes[c as usize].id))
            }
            None => self.k.unknown,
        }
    }

    fn s_class_ancestors(&self, c: Arg, b: &mut Built<'_>) -> TId {
        match self.class_of(c) {
            Some(c) => {
                let chain = self.chain(c);
                b.list_from(chain[1..].iter().map(|&c| self.classes[c as usize].id))
            }
            None => self.k.unknown,
        }
    }

    /// The part for an individual: the class's cached one when the
    /// individual's own entries cannot change it.
    fn ind_part(
        &self,
        ctx: &Ctx<'_>,
        i: u32,
        kind: Kind,
    ) -> (IndPart, Arc<crate::closure::ClassCache>) {
        let ind = &self.inds[i as usize];
        let cache = self.cache(ind.class);
        let own: Vec<&[Entry]> = match kind {
            Kind::Props => vec![&ind.props],
            Kind::Rels => vec![&ind.rels],
            Kind::Both => vec![&ind.props, &ind.rels],
        };
        let part = match kind {
            Kind::Props => &cache.props,
            Kind::Rels => &cache.rels,
            Kind::Both => &cache.all,
        };
        let keys = if kind == Kind::Both {
            &part.all_keys
        } else {
            &part.ant_keys
        };
        let reusable = self.shortcuts && own.iter().all(|o| part.reusable(o, keys));
        if reusable {
            return (IndPart::Reuse, cache);
        }
        let own_rules = own.iter().any(|o| o.iter().any(|e| !e.abs));
        if self.shortcuts && !own_rules {
            // Same defaults as the class: only the starting list differs.
            let result = part.closure.as_ref().map_err(|b| *b).and_then(|cl| {
                let mut abs: Vec<PE> = own
                    .iter()
                    .flat_map(|o| o.iter())
                    .map(|e| ctx.pe(e.term))
                    .collect();
                abs.extend_from_slice(&cl.hidden_abs);
                let mut p = ctx.hide(&abs);
                ctx.run(&part.rules, &mut p)?;
                Ok(p)
            });
            return (IndPart::OwnFacts(result), cache);
        }
        (
            IndPart::Full(self.build_part(ctx, &own, &cache.chain, kind)),
            cache,
        )
    }

    /// An individual's list before step 4 (hidden absolutes, then derived).
    pub(crate) fn ind_pre(&self, ctx: &Ctx<'_>, i: u32, kind: Kind) -> Result<Vec<PE>, Budget> {
        let (part, cache) = self.ind_part(ctx, i, kind);
        match part {
            IndPart::Full(p) => p.closure.map(|c| c.pre()),
            IndPart::OwnFacts(pre) => pre,
            IndPart::Reuse => {
                let class_part = match kind {
                    Kind::Props => &cache.props,
                    Kind::Rels => &cache.rels,
                    Kind::Both => &cache.all,
                };
                let cl = class_part.closure.as_ref().map_err(|b| *b)?;
                let ind = &self.inds[i as usize];
                let mut abs: Vec<PE> = Vec::new();
                let owns: Vec<&Vec<Entry>> = match kind {
                    Kind::Props => vec![&ind.props],
                    Kind::Rels => vec![&ind.rels],
                    Kind::Both => vec![&ind.props, &ind.rels],
                };
                for o in owns {
                    abs.extend(o.iter().filter(|e| e.abs).map(|e| ctx.pe(e.term)));
                }
                if abs.is_empty() {
                    return Ok(cl.pre());
                }
                abs.extend_from_slice(&cl.hidden_abs);
                let mut pre = ctx.hide(&abs);
                pre.extend_from_slice(&cl.derived);
                Ok(pre)
            }
        }
    }

    /// `find_value`: the first `P=>V` (V), `not(P)` (no) or `P` (yes).
    pub(crate) fn find_value(&self, list: &[PE], p: Arg) -> Option<TId> {
        let not_p = p.t.and_then(|t| self.store.find_compound(NOT, &[t]));
        for &e in list {
            if let (PE::Arrow(a, v), Some(t)) = (e, p.t) {
                if a == t {
                    return Some(v);
                }
            }
            if let (PE::T(x), Some(n)) = (e, not_p) {
                if x == n {
                    return Some(self.k.no);
                }
            }
            if Some(e) == p.pe {
                return Some(self.k.yes);
            }
        }
        None
    }

    /// `find_value_relation`: `not(R)` → first `not(R=>V)`'s V; else first `R=>V`'s V.
    pub(crate) fn find_relation(&self, ctx: &Ctx<'_>, list: &[PE], r: Arg) -> Option<TId> {
        match r.not_inner {
            Some(inner) => {
                let inner = inner?;
                list.iter().find_map(|&e| match e {
                    PE::T(t) => ctx
                        .s
                        .unary(t, NOT)
                        .and_then(|i| ctx.s.binary(i, ARROW))
                        .filter(|&(a, _)| a == inner)
                        .map(|(_, v)| v),
                    PE::Arrow(..) => None,
                })
            }
            None => {
                let r = r.t?;
                list.iter().find_map(|&e| match e {
                    PE::Arrow(a, v) if a == r => Some(v),
                    _ => None,
                })
            }
        }
    }

    /// The key under which the lookup of `a` is decided, when key filtering
    /// is exact for it.
    fn lookup_key(&self, ctx: &Ctx<'_>, a: Arg, kind: Kind) -> Option<TId> {
        match (kind, a.not_inner) {
            (Kind::Rels, Some(inner)) => inner.filter(|&t| ctx.simple(t)),
            _ => a.t.filter(|&t| ctx.simple(t)),
        }
    }

    /// Lookup of `a` in the final list (hide repeats of `pre`, then find).
    fn lookup(&self, ctx: &Ctx<'_>, pre: &[PE], a: Arg, kind: Kind) -> Option<TId> {
        let fin = match self.lookup_key(ctx, a, kind) {
            Some(key) => {
                let f: Vec<PE> = pre.iter().copied().filter(|&e| ctx.key(e) == key).collect();
                ctx.hide(&f)
            }
            None => ctx.hide(pre),
        };
        match kind {
            Kind::Rels => self.find_relation(ctx, &fin, a),
            _ => self.find_value(&fin, a),
        }
    }

    fn s_object_value(
        &self,
        i: Arg,
        p: Arg,
        kind: Kind,
        _b: &mut Built<'_>,
    ) -> Result<TId, Budget> {
        let Some(i) = self.ind_of(i) else {
            return Ok(self.k.unknown);
        };
        let ctx = self.ctx();
        let pre = self.ind_pre(&ctx, i, kind)?;
        Ok(self.lookup(&ctx, &pre, p, kind).unwrap_or(self.k.unknown))
    }

    fn pe_term(&self, b: &mut Built<'_>, e: PE) -> TId {
        match e {
            PE::T(t) => t,
            PE::Arrow(p, v) => b.compound(ARROW, &[p, v]),
        }
    }

    fn s_object_list(&self, i: Arg, kind: Kind, b: &mut Built<'_>) -> Result<TId, Budget> {
        let Some(i) = self.ind_of(i) else {
            return Ok(self.k.unknown);
        };
        let ctx = self.ctx();
        let fin = ctx.hide(&self.ind_pre(&ctx, i, kind)?);
        let items: Vec<TId> = fin.iter().map(|&e| self.pe_term(b, e)).collect();
        Ok(b.list(&items))
    }

    fn s_relations_of_individual(&self, i: Arg, b: &mut Built<'_>) -> Result<TId, Budget> {
        let Some(i) = self.ind_of(i) else {
            return Ok(self.k.unknown);
        };
        let ctx = self.ctx();
        let fin = ctx.hide(&self.ind_pre(&ctx, i, Kind::Rels)?);
        let mut items = Vec::with_capacity(fin.len());
        for e in fin {
            let expand = |b: &mut Built<'_>, v: TId| match self.class_ix.get(&v) {
                Some(&c) => {
                    let ext = self.extension(c);
                    b.list_from(ext.iter().map(|&x| self.inds[x as usize].id))
                }
                None => b.list(&[v]),
            };
            match e {
                PE::Arrow(r, v) => {
                    let objs = expand(b, v);
                    items.push(b.compound(ARROW, &[r, objs]));
                }
                PE::T(t) => match ctx.s.unary(t, NOT).and_then(|x| ctx.s.binary(x, ARROW)) {
                    Some((r, v)) => {
                        let objs = expand(b, v);
                        let inner = b.compound(ARROW, &[r, objs]);
                        items.push(b.compound(NOT, &[inner]));
                    }
                    None => return Ok(self.k.unknown),
                },
            }
        }
        Ok(b.list(&items))
    }

    fn explanations(&self, ctx: &Ctx<'_>, i: u32) -> Result<Arc<Vec<(PE, PE)>>, Budget> {
        let (part, cache) = self.ind_part(ctx, i, Kind::Both);
        match part {
            // Own entries about attributes no default mentions change nothing.
            IndPart::Reuse => cache.expl.clone(),
            IndPart::OwnFacts(pre) => Ok(Arc::new(ctx.abduce(&cache.all.rules, pre?))),
            IndPart::Full(p) => {
                let cl = p.closure.as_ref().map_err(|b| *b)?;
                Ok(Arc::new(ctx.abduce(&p.rules, cl.pre())))
            }
        }
    }

    fn s_explanation_of_individual(
        &self,
        i: Arg,
        b: &mut Built<'_>,
    ) -> Result<Option<TId>, Budget> {
        let Some(i) = self.ind_of(i) else {
            return Ok(None);
        };
        let ctx = self.ctx();
        let ex = self.explanations(&ctx, i)?;
        let items: Vec<TId> = ex
            .iter()
            .map(|&(c, why)| {
                let c = self.pe_term(b, c);
                let why = self.pe_term(b, why);
                b.fresh(sitlog_syntax::atoms::COLON, &[c, why])
            })
            .collect();
        Ok(Some(b.list(&items)))
    }

    fn s_explanation_extension(&self, c: Arg, b: &mut Built<'_>) -> Result<TId, Budget> {
        let ctx = self.ctx();
        let mut out = Vec::new();
        if let Some(target) = c.pe {
            for &i in self.all_inds().iter() {
                let ex = self.explanations(&ctx, i)?;
                if let Some(&(_, why)) = ex.iter().find(|(k, _)| *k == target) {
                    let why = self.pe_term(b, why);
                    out.push(b.compound(
                        sitlog_syntax::atoms::COLON,
                        &[self.inds[i as usize].id, why],
                    ));
                }
            }
        }
        Ok(b.list(&out))
    }

    fn s_property_extension(&self, p: Arg, b: &mut Built<'_>) -> Result<TId, Budget> {
        self.extension_of(p, Kind::Props, b)
    }

    fn s_relation_extension(&self, r: Arg, b: &mut Built<'_>) -> Result<TId, Budget> {
        self.extension_of(r, Kind::Rels, b)
    }

    /// Property/relation extension: per individual, the lookup; individuals
    /// that share their class's closure reuse one lookup per class.
    fn extension_of(&self, a: Arg, kind: Kind, b: &mut Built<'_>) -> Result<TId, Budget> {
        let ctx = self.ctx();
        let key = self.lookup_key(&ctx, a, kind);
        let mut per_class: Vec<Option<Option<TId>>> = vec![None; self.classes.len()];
        let mut caches: Vec<Option<Arc<crate::closure::ClassCache>>> =
            vec![None; self.classes.len()];
        let all = self.all_inds();
        let blooms = self.blooms();
        let mut pairs: Vec<(u32, TId)> = Vec::new();
        let mut direct: Vec<TId> = Vec::new();
        if kind != Kind::Rels {
            b.reserve(2 * all.len() + 1, 4 * all.len());
            direct.reserve(all.len());
        }
        for &i in all.iter() {
            let ind = &self.inds[i as usize];
            let bloom = blooms.get(i as usize).copied().unwrap_or_default();
            let (own_bloom, own_rules) = match kind {
                Kind::Rels => (bloom.rels, bloom.rel_rules),
                _ => (bloom.props, bloom.prop_rules),
            };
            let own = if kind == Kind::Rels {
                &ind.rels
            } else {
                &ind.props
            };
            let cache = &*caches[ind.class as usize].get_or_insert_with(|| self.cache(ind.class));
            let part = if kind == Kind::Rels {
                &cache.rels
            } else {
                &cache.props
            };
            // The summary answers most individuals without reading their entries.
            let reusable = self.shortcuts
                && !own_rules
                && (own_bloom & part.ant_bloom == 0 || part.reusable(own, &part.ant_keys));
            let value = match key {
                Some(key) if reusable => {
                    let cl = part.closure.as_ref().map_err(|b| *b)?;
                    let own_q: Vec<PE> = if own_bloom & key_bit(key) == 0 {
                        Vec::new()
                    } else {
                        own.iter()
                            .filter(|e| e.key == key)
                            .map(|e| ctx.pe(e.term))
                            .collect()
                    };
                    if own_q.is_empty() {
                        let slot = &mut per_class[ind.class as usize];
                        match slot {
                            Some(v) => *v,
                            None => {
                                let v = self.lookup(&ctx, &cl.pre(), a, kind);
                                *slot = Some(v);
                                v
                            }
                        }
                    } else {
                        let mut l = own_q;
                        l.extend(
                            cl.hidden_abs
                                .iter()
                                .chain(&cl.derived)
                                .filter(|&&e| ctx.key(e) == key),
                        );
                        self.lookup(&ctx, &l, a, kind)
                    }
                }
                _ => {
                    let pre = self.ind_pre(&ctx, i, kind)?;
                    self.lookup(&ctx, &pre, a, kind)
                }
            };
            match value {
                // Property values go straight into the answer; a value that is
                // the list [unknown] counts as unknown (as in the original).
                Some(v)
                    if kind != Kind::Rels
                        && self
                            .store
                            .proper_list(v)
                            .is_none_or(|l| l != [self.k.unknown]) =>
                {
                    direct.push(b.fresh(sitlog_syntax::atoms::COLON, &[ind.id, v]));
                }
                Some(_) if kind != Kind::Rels => {}
                Some(v) => pairs.push((i, v)),
                None => {}
            }
        }
        let unknown = self.k.unknown;
        // One `:` pair and one list cell per individual, two arguments each.
        b.reserve(2 * pairs.len() + 1, 4 * pairs.len());
        let mut items = Vec::with_capacity(pairs.len());
        for (i, v) in pairs {
            let id = self.inds[i as usize].id;
            let value = match kind {
                Kind::Rels => {
                    let objs = match self.store.proper_list(v) {
                        Some(l) if !l.is_empty() => l,
                        _ => vec![v],
                    };
                    if objs == [unknown] {
                        continue;
                    }
                    // Class objects expand after the rest of the list (the original's order).
                    let mut acc: Vec<TId> = Vec::new();
                    for &y in objs.iter().rev() {
                        match self.class_ix.get(&y) {
                            Some(&c) => acc.extend(
                                self.extension(c).iter().map(|&x| self.inds[x as usize].id),
                            ),
                            None => acc.insert(0, y),
                        }
                    }
                    b.list(&acc)
                }
                _ => {
                    if self.store.proper_list(v).is_some_and(|l| l == [unknown]) {
                        continue;
                    }
                    v
                }
            };
            items.push(b.fresh(sitlog_syntax::atoms::COLON, &[id, value]));
        }
        if kind != Kind::Rels {
            return Ok(b.list_from(direct.into_iter()));
        }
        Ok(b.list_from(items.into_iter()))
    }

    fn s_object_property_list(&self, i: Arg, p: Arg, b: &mut Built<'_>) -> Result<TId, Budget> {
        let Some(i) = self.ind_of(i) else {
            return Ok(self.k.nil);
        };
        let ctx = self.ctx();
        let pre = self.ind_pre(&ctx, i, Kind::Props)?;
        Ok(self.list_values(&pre, p, b))
    }

    fn list_values(&self, pre: &[PE], p: Arg, b: &mut Built<'_>) -> TId {
        let vals: Vec<TId> = match p.t {
            Some(t) => pre
                .iter()
                .filter_map(|e| match e {
                    PE::Arrow(a, v) if *a == t => Some(*v),
                    _ => None,
                })
                .collect(),
            None => Vec::new(),
        };
        b.list(&vals)
    }

    fn s_object_property_preference_value(&self, i: Arg, pref: Arg) -> TId {
        let (Some(i), Some(pref)) = (self.ind_of(i), pref.t) else {
            return self.k.unknown;
        };
        let ind = &self.inds[i as usize];
        let mut rules = Vec::new();
        crate::closure::level_rules(&self.store, &ind.props, &mut rules);
        if let Some(r) = rules.iter().find(|r| r.term == pref) {
            return r.weight;
        }
        let cache = self.cache(ind.class);
        cache
            .props
            .rules
            .iter()
            .find(|r| r.term == pref)
            .map_or(self.k.unknown, |r| r.weight)
    }

    /// `class_properties` / `class_relations`: `None` for an unknown class;
    /// for `top`, the raw `[Entry, Weight]` list (the original's quirk).
    fn class_final(&self, c: Arg, kind: Kind) -> Result<Option<Vec<PE>>, Budget> {
        let Some(c) = self.class_of(c) else {
            return Ok(None);
        };
        let cl = &self.classes[c as usize];
        if c == self.top {
            let raw = if kind == Kind::Rels {
                &cl.rels
            } else {
                &cl.props
            };
            return Ok(Some(raw.iter().map(|e| PE::T(e.pair)).collect()));
        }
        let cache = self.cache(c);
        let part = if kind == Kind::Rels {
            &cache.rels
        } else {
            &cache.props
        };
        let closure = part.closure.as_ref().map_err(|b| *b)?;
        Ok(Some(self.ctx().hide(&closure.pre())))
    }

    fn s_class_list(&self, c: Arg, kind: Kind, b: &mut Built<'_>) -> Result<TId, Budget> {
        Ok(match self.class_final(c, kind)? {
            Some(l) => {
                let items: Vec<TId> = l.iter().map(|&e| self.pe_term(b, e)).collect();
                b.list(&items)
            }
            None => self.k.unknown,
        })
    }

    fn s_class_property_value(
        &self,
        c: Arg,
        p: Arg,
        _b: &mut Built<'_>,
    ) -> Result<Option<TId>, Budget> {
        Ok(self
            .class_final(c, Kind::Props)?
            .map(|l| self.find_value(&l, p).unwrap_or(self.k.unknown)))
    }

    fn s_class_relation_value(&self, c: Arg, r: Arg, _b: &mut Built<'_>) -> Result<TId, Budget> {
        let ctx = self.ctx();
        Ok(self
            .class_final(c, Kind::Rels)?
            .and_then(|l| self.find_relation(&ctx, &l, r))
            .unwrap_or(self.k.unknown))
    }

    fn s_class_property_list(&self, c: Arg, p: Arg, b: &mut Built<'_>) -> Result<TId, Budget> {
        let Some(ci) = self.class_of(c) else {
            return Ok(self.k.unknown);
        };
        if ci == self.top {
            return Ok(self.k.nil);
        }
        let cache = self.cache(ci);
        let closure = cache.props.closure.as_ref().map_err(|b| *b)?;
        Ok(self.list_values(&closure.pre(), p, b))
    }

    fn s_class_has_property(&self, c: Arg, p: Arg, _b: &mut Built<'_>) -> Result<TId, Budget> {
        let k = self.k;
        let Some(list) = self.class_final(c, Kind::Props)? else {
            return Ok(k.unknown);
        };
        if list.is_empty() {
            return Ok(k.unknown);
        }
        if p.pe.is_some_and(|e| list.contains(&e)) {
            return Ok(k.yes);
        }
        if let Some(Some(q)) = p.not_inner {
            let ctx = self.ctx();
            if list.contains(&ctx.pe(q)) {
                return Ok(k.no);
            }
        }
        let not_p = p.t.and_then(|t| self.store.find_compound(NOT, &[t]));
        if not_p.is_some_and(|n| list.contains(&PE::T(n))) {
            return Ok(k.no);
        }
        Ok(k.unknown)
    }
}
