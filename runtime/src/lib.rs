//! `sitlog-runtime`: everything a running SitLog task needs, shared by the
//! reference interpreter and by generated code. Never depends on the compiler.

pub use sitlog_syntax as syntax;
pub use sitlog_syntax::{atoms, Atom};
