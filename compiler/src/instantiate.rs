//! The IR run by instantiating its situation templates: [`DmProgram`] for
//! [`Ir`], the reference path that the interpreter's plans
//! ([`crate::interp`]) and the generated code are compared with, and the
//! fallback of both for situations they do not plan. Never parses, never
//! re-checks; every semantic step is the runtime's.

use crate::ir::Ir;
use sitlog_runtime::machine::{DmIx, DmProgram, Instance, Kind, SitIx};
use sitlog_runtime::{Store, Term, Vars};
use sitlog_syntax::Atom;

impl DmProgram for Ir {
    fn dm_by_name(&self, name: Atom) -> Option<DmIx> {
        Ir::dm_by_name(self, name)
    }
    fn left_out(&self, name: Atom) -> Option<String> {
        self.left_out.iter().find(|l| l.name == name).map(|l| {
            format!(
                "DM `{}/{}` was left out of this run for its errors; the first: {}",
                l.name, l.arity, l.error
            )
        })
    }
    fn dm_name(&self, dm: DmIx) -> Atom {
        self.dms[dm as usize].name
    }
    fn situation_count(&self, dm: DmIx) -> usize {
        self.dms[dm as usize].situations.len()
    }
    fn kind(&self, dm: DmIx, sit: SitIx) -> Kind {
        self.dms[dm as usize].situations[sit as usize].kind
    }
    fn fresh_head(&self, dm: DmIx, store: &mut Store) -> Term {
        store.copy_term(self.dms[dm as usize].head)
    }
    fn instantiate(&self, dm: DmIx, sit: SitIx, store: &mut Store) -> Option<Instance> {
        let template = self.dms[dm as usize].situations[sit as usize].template;
        Some(Instance::fresh(store, template))
    }
    fn may_select(&self, dm: DmIx, sit: SitIx, value: Term, store: &Store) -> bool {
        match self.dms[dm as usize].situations[sit as usize].id_functor {
            Some(f) => store.functor(value) == Some(f),
            None => true,
        }
    }
    fn locals(&self, dm: DmIx, store: &mut Store) -> Vars {
        let entries = self.dms[dm as usize]
            .locals
            .iter()
            .map(|&(n, v)| (n, store.copy_term(v)))
            .collect();
        Vars::from_entries(entries)
    }
    fn location(&self, dm: DmIx, sit: SitIx) -> Option<String> {
        Some(
            self.dms[dm as usize].situations[sit as usize]
                .location
                .clone(),
        )
    }
    fn in_arg_location(&self, dm: DmIx, sit: SitIx) -> Option<String> {
        self.dms[dm as usize].situations[sit as usize]
            .in_arg_location
            .clone()
    }
}

impl Ir {
    /// Fresh copies of the global variables' initial values, in a new store
    /// that starts from the IR's frozen one.
    pub fn initial_state(&self) -> (Store, Vars) {
        let mut store = self.store.clone();
        let entries = self
            .globals
            .iter()
            .map(|&(n, v)| (n, store.copy_term(v)))
            .collect();
        (store, Vars::from_entries(entries))
    }
}

/// The [`Instance`] of a fresh copy `t` of a situation template (its nine
/// fields in order; the `none` marker stands for an absent one).
pub fn instance_of(store: &Store, t: Term) -> Instance {
    Instance::of_template(store, t)
}
