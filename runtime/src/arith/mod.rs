//! Arithmetic: `is/2` evaluation and the comparisons `=:=`, `=\=`, `<`,
//! `>`, `=<`, `>=`, with SWI-Prolog's semantics (flags `iso=false`,
//! `prefer_rationals=false`, `float_overflow=error`,
//! `float_zero_div=error`, `float_undefined=error`).
//!
//! One deliberate difference: integers are 64-bit. Where SWI-Prolog would
//! promote to a big integer, evaluation fails cleanly with
//! [`ArithError::IntOverflow`]; big integer literals are only printable.
//! Evaluation is iterative (explicit stacks), so `1+1+...+1` of any depth
//! is fine, and no input makes it panic.
//!
//! Two submodules: `number` (the values, errors and comparison
//! operators) below `evaluator` (the op table and the evaluation).

mod evaluator;
mod number;

pub use number::{compare_numbers, ArithCmp, ArithError, Number};
