//! `sitlog-debug`: working on a task program from the command line.
//!
//! Owns the REPL engine of `sitlogc debug` ([`debug`]: a step debugger
//! over a live, interpreted run) and of `sitlogc replay` ([`replay()`]: a
//! `--trace` recording walked forwards and backwards, [`diff`] of two
//! recordings), their command language ([`command`]), where commands come
//! from ([`CommandSource`]: a line editor, or a `--commands` file, echoed,
//! for tests), and the `main` of a task compiled with `sitlogc build
//! --debugger` ([`task_main`]: the same debugger over the compiled
//! program).
//! `sitlogc` only parses the arguments.
//!
//! Invariants: the debugger never changes the run it watches except by
//! `input` (an answer the script or prompt would have given) and `quit`
//! (the run's stop flag); `print` evaluates with every binding and variable
//! update undone. It stops only at transition boundaries (after a
//! transition is recorded, or when the run fails, before the stack is
//! unwound) and when a perceptual situation has no input. A bad commands
//! or trace file is an error naming FILE:LINE (and column), never a panic.

pub mod command;
mod live;
pub mod record;
pub mod replay;
mod task;

pub use command::CommandSource;
pub use live::debug;
pub use replay::{diff, replay, Trace};
pub use task::task_main;
