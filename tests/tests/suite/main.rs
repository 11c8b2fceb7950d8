//! The workspace's end-to-end tests, one test binary (one link instead of
//! eleven): the scenarios, the agreement of the back ends, the debugger,
//! the examples and the tutorial, each a module. `alloc` stays a binary of
//! its own (its counting allocator is global) and `repository` checks the
//! repository's files.

mod agreement;
mod debug;
mod examples;
mod home;
mod machine;
mod prolog;
mod random_agreement;
mod resolve;
mod supermarket;
mod support;
mod tutorial;
mod typed;
