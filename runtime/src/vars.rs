//! SitLog variables: a DM instance's locals and the program's globals, each
//! an ordered list of `name ==> value` (order is kept, as in the original).

use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::{atoms, Atom};

/// An ordered list of SitLog variables.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Vars {
    entries: Vec<(Atom, Term)>,
}

impl Vars {
    pub fn new() -> Vars {
        Vars::default()
    }
    pub fn from_entries(entries: Vec<(Atom, Term)>) -> Vars {
        Vars { entries }
    }
    pub fn entries(&self) -> &[(Atom, Term)] {
        &self.entries
    }
    /// Inlined where it is called (native code reading a global,
    /// `Cx::global_as`, is on the hot path).
    #[inline]
    pub fn get(&self, name: Atom) -> Option<Term> {
        self.entries.iter().find(|(n, _)| *n == name).map(|e| e.1)
    }
    /// The value of an existing variable, to read and write in place
    /// (native code's `inc` of a global, `Cx::global_inc`: one search).
    #[inline]
    pub fn slot(&mut self, name: Atom) -> Option<&mut Term> {
        self.entries
            .iter_mut()
            .find(|(n, _)| *n == name)
            .map(|e| &mut e.1)
    }
    /// Sets an existing variable; `false` if there is none of that name.
    pub fn set(&mut self, name: Atom, value: Term) -> bool {
        match self.entries.iter_mut().find(|(n, _)| *n == name) {
            Some(e) => {
                e.1 = value;
                true
            }
            None => false,
        }
    }
    /// Adds a variable at the end (or sets it if it exists).
    pub fn define(&mut self, name: Atom, value: Term) {
        if !self.set(name, value) {
            self.entries.push((name, value));
        }
    }
    pub fn contains(&self, name: Atom) -> bool {
        self.entries.iter().any(|(n, _)| *n == name)
    }
    pub fn len(&self) -> usize {
        self.entries.len()
    }
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
    /// Copies `other` into `self` reusing `self`'s buffer (no allocation once warm).
    pub fn restore_from(&mut self, other: &Vars) {
        self.entries.clear();
        self.entries.extend_from_slice(&other.entries);
    }
    /// The list term `[name==>value, ...]`.
    pub fn to_term(&self, store: &mut Store) -> Term {
        let items: Vec<Term> = self
            .entries
            .iter()
            .map(|&(n, v)| store.compound(atoms::DOUBLE_ARROW, &[Term::atom(n), v]))
            .collect();
        store.list(&items)
    }
    /// Every value, for garbage collection roots.
    pub fn values_mut(&mut self) -> impl Iterator<Item = &mut Term> {
        self.entries.iter_mut().map(|e| &mut e.1)
    }
}
