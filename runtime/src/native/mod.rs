//! Native values: what typed code holds instead of terms
//! (`docs/design/typed-mir.md`). For now the lattice of their types
//! ([`Ty`]), shared by the compiler's inference over the MIR and the
//! runtime's conversions; the values themselves (`List<T>`, `Val`) and the
//! conversions between them and terms come next.
//!
//! Invariant: nothing here reads or writes the store except the
//! conversions, the one place a native value becomes a term or back.

mod ty;

pub use ty::{Ty, MAX_DEPTH};
