//! Tests of the compiler core through its library API (no `sitlogc`
//! binary: those are in `cli/tests/cli/`), one test binary.

mod codegen;
mod diagnostics;
mod explain_visit;
mod never_panic;
mod shapes;
