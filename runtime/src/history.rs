//! The task history: what happened, in the original's structure. A DM's
//! history is a list of entries `DmId:(SitId, Expectation:Action)`; the whole
//! history of an embedded DM is one element of its caller's list, placed just
//! before the recursive situation's own entry.

use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::atoms;

/// One transition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Entry {
    pub dm: Term,
    pub situation: Term,
    pub expectation: Term,
    pub action: Term,
}

/// An element of a DM's history.
#[derive(Debug, PartialEq)]
pub enum Item {
    Entry(Entry),
    Nested(Vec<Item>),
}

/// Histories nest as deep as DM calls (100 000 levels and more): dropping
/// them must not recurse.
impl Drop for Item {
    fn drop(&mut self) {
        if let Item::Nested(items) = self {
            let mut stack = std::mem::take(items);
            while let Some(mut item) = stack.pop() {
                if let Item::Nested(inner) = &mut item {
                    stack.append(inner);
                }
            }
        }
    }
}

impl Entry {
    /// `DmId:(SitId, Expectation:Action)`.
    pub fn to_term(&self, store: &mut Store) -> Term {
        let ea = store.compound(atoms::COLON, &[self.expectation, self.action]);
        let pair = store.compound(atoms::COMMA, &[self.situation, ea]);
        store.compound(atoms::COLON, &[self.dm, pair])
    }
}

/// The history as a Prolog list term (nested lists for embedded DMs).
/// Nesting depth equals DM call depth, which can be large: the recursion
/// grows its stack through stacker.
pub fn to_term(items: &[Item], store: &mut Store) -> Term {
    build(items, store)
}

fn build(items: &[Item], store: &mut Store) -> Term {
    stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
        let mut terms = Vec::with_capacity(items.len());
        for item in items {
            terms.push(match item {
                Item::Entry(e) => e.to_term(store),
                Item::Nested(inner) => build(inner, store),
            });
        }
        store.list(&terms)
    })
}
