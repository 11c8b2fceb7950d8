//! Entries: the `[Entry, Weight]` items of property and relation lists,
//! checked for shape and keyed by the attribute they are about, and the
//! few term ids every KB interns. Below both the model (which holds
//! entries) and the closure (which reasons over them).

use crate::store::{SNode, TId, TermStore};
use sitlog_syntax::{atoms, Atom};

/// One `[Entry, Weight]` item of a property or relation list.
#[derive(Clone, Debug)]
pub(crate) struct Entry {
    /// The whole `[Entry, Weight]` term (what `class_properties(top, _)` shows).
    pub pair: TId,
    pub term: TId,
    pub weight: TId,
    /// Weight is the integer 0: an absolute fact, not a conditional default.
    pub abs: bool,
    /// Numeric weight, for ordering the defaults.
    pub w: f64,
    /// The attribute the entry is about (see `Ctx::key_t`).
    pub key: TId,
}

/// Ids of terms every KB needs, interned once.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Known {
    pub yes: TId,
    pub no: TId,
    pub unknown: TId,
    pub dash: TId,
    pub nil: TId,
    pub top: TId,
    pub none: TId,
}

pub(crate) const NOT: Atom = atoms::NOT;
pub(crate) const ARROW: Atom = atoms::ARROW;
pub(crate) const DEFAULT: Atom = atoms::DEFAULT_ARROW;

/// The attribute a term is about: `p` for `p=>v` and `not(p=>v)`, `a` for
/// `a` and `not(a)`.
pub(crate) fn term_key(s: &TermStore, mut t: TId) -> TId {
    loop {
        if let Some(inner) = s.unary(t, NOT) {
            t = inner;
        } else if let Some((p, _)) = s.binary(t, ARROW) {
            return p;
        } else {
            return t;
        }
    }
}

/// One bit per key hash: a set of keys that may have false positives.
pub(crate) fn key_bit(t: TId) -> u64 {
    1u64 << (t.0.wrapping_mul(0x9E37_79B1) >> 26)
}

/// Checks an entry's shape; `Err((0 = entry | 1 = weight, message))`.
pub(crate) fn make_entry(
    store: &mut TermStore,
    k: &Known,
    pair: TId,
    term: TId,
    weight: TId,
) -> Result<Entry, (usize, String)> {
    let _ = k;
    let w = store
        .number(weight)
        .ok_or((1, "the weight must be a number".to_owned()))?;
    let abs = matches!(store.node(weight), SNode::Int(0));
    let is_rule = store.binary(term, DEFAULT).is_some();
    if !abs && !is_rule {
        return Err((
            0,
            "an entry with a non-zero weight must be a conditional default Antecedent=>>Consequent"
                .to_owned(),
        ));
    }
    if abs && is_rule {
        return Err((
            0,
            "a conditional default Antecedent=>>Consequent needs a non-zero weight".to_owned(),
        ));
    }
    if store.number(term).is_some() {
        return Err((0, "an entry must be an atom or a compound term".to_owned()));
    }
    let key = term_key(store, term);
    Ok(Entry {
        pair,
        term,
        weight,
        abs,
        w,
        key,
    })
}

/// Builds an entry from a term and a weight term (interning the pair).
pub(crate) fn new_entry(
    store: &mut TermStore,
    k: &Known,
    term: TId,
    weight: TId,
) -> Result<Entry, String> {
    let pair = store.list(&[term, weight]);
    make_entry(store, k, pair, term, weight).map_err(|(_, m)| m)
}
