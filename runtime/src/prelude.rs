//! The names generated code imports (`use ::sitlog_runtime::prelude::*;` at
//! the top of a generated file and of each DM module in it), so the code
//! says `Term::atom(a.x)`, `Step::Final`, `r5.to_term(cx.store())` instead
//! of full paths. Invariant: only re-exports, nothing defined here; a glob
//! import of it is shadowed by any item of the same name where the code is
//! included, and the generated code names functions (`native::compound`)
//! through their module, so no local name can shadow them.

pub use crate::machine::{
    AnyShape, Cx, DmIx, DmRow, Due, Fault, Fill, Instance, Kind, NatAt, NatFrames, Of, RunError,
    SitIx, SitRow, SitTable, Step, TypedRun, Visit,
};
pub use crate::native::{FromVal, Ground, IntoVal, List, Native, Never, Val};
pub use crate::type_test::TypeTest;
pub use crate::{atoms, machine, native, Atom, Store, Term, Vars};
