//! The KB crate's integration tests, in one binary (a test binary costs a
//! link: issue 30). Each module is one area; `tests/data/` holds
//! their KBs.
mod common;

mod errors;
mod never_panic;
mod office;
mod paper;
mod persist;
mod quirks;
mod updates;
