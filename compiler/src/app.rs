//! The IR as a whole program for the runtime's CLI runner (`sitlogc run`
//! shares `sitlog_runtime::cli` with compiled programs).

use crate::ir::Ir;
use sitlog_runtime::{cli::App, Atom, Store, Vars};

impl App for Ir {
    fn initial_state(&self) -> (Store, Vars) {
        Ir::initial_state(self)
    }
    fn basic_actions(&self) -> Vec<Atom> {
        self.basic_actions.clone()
    }
    fn recovery(&self) -> Vec<(Atom, Atom)> {
        self.recovery.clone()
    }
}
