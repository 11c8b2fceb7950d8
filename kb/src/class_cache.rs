//! A Kb's per-class closures: the chain of a class up to `top`, and the
//! closures of its properties, its relations and both (with their
//! explanations), computed on first use and kept in the KB's cache slots
//! ([`ClassCache`], cleared whenever the KB changes); also the closure of an
//! individual's own entries in front of its class chain.

use crate::closure::{level_rules, ClassCache, Ctx, Kind, Part, Rule, PE};
use crate::entry::Entry;
use crate::model::Kb;

impl Kb {
    pub(crate) fn ctx(&self) -> Ctx<'_> {
        Ctx::new(&self.store, self.k)
    }

    pub(crate) fn chain(&self, c: u32) -> Vec<u32> {
        let mut v = vec![c];
        let mut cur = c;
        while let Some(m) = self.mother_ix.get(cur as usize).copied().flatten() {
            if v.len() > self.classes.len() {
                break;
            }
            v.push(m);
            cur = m;
        }
        v
    }

    pub(crate) fn cache(&self, c: u32) -> std::sync::Arc<ClassCache> {
        self.caches[c as usize]
            .get_or_init(|| std::sync::Arc::new(self.compute_cache(c)))
            .clone()
    }

    fn compute_cache(&self, c: u32) -> ClassCache {
        let ctx = self.ctx();
        let chain = self.chain(c);
        let props = self.build_part(&ctx, &[], &chain, Kind::Props);
        let rels = self.build_part(&ctx, &[], &chain, Kind::Rels);
        let all = self.build_part(&ctx, &[], &chain, Kind::Both);
        let expl = all
            .closure
            .as_ref()
            .map(|cl| std::sync::Arc::new(ctx.abduce(&all.rules, cl.pre())))
            .map_err(|b| *b);
        ClassCache {
            chain,
            props,
            rels,
            all,
            expl,
        }
    }

    /// The part of `kind` for an individual's own entries (may be empty)
    /// in front of a class chain.
    pub(crate) fn build_part(
        &self,
        ctx: &Ctx<'_>,
        own: &[&[Entry]],
        chain: &[u32],
        kind: Kind,
    ) -> Part {
        let s = &self.store;
        let mut abs = Vec::new();
        let mut rules = Vec::new();
        let level = |entries: &[&[Entry]], abs: &mut Vec<PE>, rules: &mut Vec<Rule>| {
            let both: Vec<Entry>;
            let flat: &[Entry] = if entries.len() == 1 {
                entries[0]
            } else {
                both = entries.iter().flat_map(|e| e.iter().cloned()).collect();
                &both
            };
            abs.extend(flat.iter().filter(|e| e.abs).map(|e| ctx.pe(e.term)));
            level_rules(s, flat, rules);
        };
        level(own, &mut abs, &mut rules);
        for &ci in chain {
            let cl = &self.classes[ci as usize];
            let entries: Vec<&[Entry]> = match kind {
                Kind::Props => vec![&cl.props],
                Kind::Rels => vec![&cl.rels],
                Kind::Both => vec![&cl.props, &cl.rels],
            };
            level(&entries, &mut abs, &mut rules);
        }
        Part::new(ctx, abs, rules)
    }
}
