//! How the machine names a program's parts: DM and situation indices,
//! the [`Kind`] of a situation, and the fields of a situation [`Instance`].

use crate::term::Term;

/// Index of a DM in its program.
pub type DmIx = u32;
/// Index of a situation in its DM (0 is the initial situation).
pub type SitIx = u32;

/// What kind of situation, as its `type` says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Final,
    Recursive,
    /// Any other type: the name of a perceptual interpreter.
    Perceptual,
}

/// The fields of a situation instance, as [`DmProgram::instantiate`](super::DmProgram::instantiate) returns
/// them: fresh terms sharing variables with a fresh copy of the DM head.
#[derive(Clone, Copy, Debug)]
pub struct Instance {
    pub head: Term,
    pub id: Term,
    pub type_term: Term,
    pub in_arg: Option<Term>,
    pub out_arg: Option<Term>,
    pub prog: Option<Term>,
    pub embedded_dm: Option<Term>,
    pub diag_mod: Option<Term>,
    /// The arcs as a list of `'$arc'(Expectation, Action, Next)`.
    pub arcs: Term,
}
