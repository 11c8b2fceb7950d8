//! The DM machine: runs a SitLog program as a functional recursive
//! transition network. One loop, the DM stack on the heap (no Rust recursion
//! per embedded DM), the pipe, locals per DM execution, globals for the
//! program, and the task history, in the original's order of steps
//! (semantics notes D-7..D-27, with our fixes E1, E4, E5, E7–E16).
//!
//! The program itself is behind [`DmProgram`]: the reference interpreter
//! implements it over the compiler's IR, generated code implements it with
//! code. Both share every step below on terms; native code (values held as
//! Rust values) does integer arithmetic, list walks, exit matching and its
//! frames itself, and agrees with this machine by test (see the crate doc).
//! What a compiled program tells the machine about its situations is data,
//! read by generic code here: each DM's row (`DmRow`: name, file, head),
//! each situation's row (`SitTable`: kind, id
//! functor, whether it runs as code, where it is written) and its template
//! (`Templates`), on whose id a compiled situation is selected exactly as
//! the interpreter's plan selects it (constants of a simple id, else a
//! fresh copy unified), so selection agrees by construction.
//!
//! One job per submodule, bottom to top (each uses only those before it;
//! this file only re-exports, so every public item keeps its path
//! `sitlog_runtime::machine::X`):
//! - `situation`: indices, [`Kind`], [`Instance`]; `io`: [`Perception`],
//!   [`Percept`], [`Actions`]; `options`: [`Options`];
//! - `outcome`: [`Outcome`], [`RunError`], [`RunWarning`]; `places`: where
//!   a run-time error happened in the source ([`places::blame`]), for both
//!   back ends;
//! - `state`: the [`Machine`] and its DM stack;
//! - `observe`: [`Observer`] and the [`Inspection`] it is shown;
//! - `program`: [`DmProgram`], [`Step`], [`Cx`], [`Between`];
//! - `steps`: the semantic steps of one situation;
//! - `cx`: the steps as [`Cx`] offers them to compiled code;
//! - `holes`: the holes of a pattern native code fills, as a tuple of
//!   references a gated call takes without building anything ([`Holes`],
//!   beside `cx`'s [`AsTerm`], which each hole is);
//! - `native_stack`: the native stack of compiled code ([`nat_drive`],
//!   [`NatBelow`], [`NatFrames`]: what the program's frames must offer,
//!   [`NatAt`]: what a DM's situations must offer);
//! - `boundary`: a user function, the KB or a Prolog condition evaluated
//!   by native code without handing the native frames over
//!   ([`Cx::nat_eval`], [`Cx::nat_condition`]);
//! - `effect`: an arc's action performed by native code, entered or not
//!   ([`Cx::nat_perform`], [`NatEntry`], [`NatAction`]), its frames
//!   handed over only where it records unentered or the effector fails;
//! - `arm_calls`: steps generated code writes at many sites as one inlined
//!   call each ([`TypedRun::empty`], [`TypedRun::entry`],
//!   [`TypedRun::exit_end`], [`NatBelow::push`], [`NatBelow::perform`],
//!   [`Of`]);
//! - `run`: the loop (DM calls and returns, selection of situations, garbage
//!   collection between them).

mod arm_calls;
mod boundary;
mod cx;
mod effect;
mod held_call;
mod held_in;
mod holes;
mod io;
mod native_stack;
mod observe;
mod options;
mod outcome;
pub mod places;
mod plain_fn;
mod program;
mod run;
mod situation;
mod state;
mod steps;

pub use arm_calls::Of;
pub use cx::{build_of, fill, hole_atom, AsTerm, Fault, Fill, FromIdParts, IdArg, OutSlot};
pub use effect::{AnyShape, Due, NatAction, NatEntry};
pub use holes::{Holes, TUPLE_HOLES};
pub use io::{ActionShape, Actions, Perceived, Percept, Perception};
pub use native_stack::{
    nat_choose, nat_drive, nat_goto, nat_hand_over, nat_materialize, nat_plain, nat_replace_done,
    nat_template, NatAt, NatBelow, NatFrames,
};
pub use observe::{Inspection, Observer};
pub use options::Options;
pub use outcome::{
    rename_vars, renumber_vars, renumber_vars_after, ErrorSite, Outcome, RunError, RunWarning,
};
pub use program::{Between, Cx, DmProgram, Next, Step, TypedRun, Visit};
pub use situation::{
    none_marker, read_consts, read_dms, read_templates, DmIx, DmRow, Instance, Kind, SitIx, SitRow,
    SitTable, Templates,
};
pub use state::{HeldPipe, Machine, HELD_MAX};
