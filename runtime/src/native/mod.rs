//! Native values: what typed code holds instead of terms
//! (`docs/design/typed-mir.md`): the lattice of their types ([`Ty`]),
//! shared by the compiler's inference over the MIR and the runtime's
//! conversions; the persistent list ([`List`]); the register value
//! ([`Val`]) and its conversions to and from terms; [`gc`], how a holder
//! of values keeps the terms inside them across a collection.
//!
//! Choices (phase 2 of the plan):
//! - `List<T>` has two shapes behind one type, an `Rc<[T]>` with a start
//!   index for a list that arrives whole and `Rc` cells for `[X|Xs]`, so a
//!   converted list is one allocation and a tail is never one.
//! - `Val` is 24 bytes (a test checks): `Int`, `Float`, `Sym`, `List`,
//!   `Tagged` (a [`Compound`]: name and arguments in one `Rc` slice; the
//!   name beside the slice would make `Val` 32 bytes) and `Term`, the top,
//!   a handle as given. A `Term` sits in a `Cell`, so the collector moves it
//!   in place even inside a shared list, without copying the list.
//!
//! - A list converted whole from a term, or made a term whole, is
//!   remembered beside that term's cells (`memo`), so a frame handed to
//!   the machine and entered again converts its lists in O(1).
//!
//! Invariant: nothing here reads or writes the store except the
//! conversions (`Val::from_term`, `Val::to_term`, `Val::identical_to`) and
//! [`gc`], the one place a native value becomes a term or back.

mod head;
mod list;
pub(crate) mod memo;
mod rust;
mod ty;
mod val;

pub use head::head_part;
pub use list::{Iter, List};
pub use rust::{compound, id_part, FromVal, Ground, IntoVal, Native, Never};
pub use ty::{Ty, MAX_DEPTH};
pub use val::{gc, Compound, Val};
