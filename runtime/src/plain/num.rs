//! The arithmetic of a plain clause on integers and floats (issue 37,
//! helper `nfloat25`): one implementation that the term path
//! (`plain::call`), the value path (`val`) and a compiled function
//! (`rt`) all run, so that `V is E` and the comparisons give what the
//! engine (scryer-prolog, which runs every Prolog user function) gives.
//!
//! Invariant (fidelity): every function here gives `Some` only where the
//! engine's `is/2` or comparison gives the same value or outcome, `None`
//! (the engine decides, whose value or error it then is) everywhere else.
//! What the engine does, read from its arithmetic (`scryer-prolog`
//! 0.10, `arithmetic.rs`, `machine/arithmetic_ops.rs`):
//! - integer `+ - * // mod rem min max abs`, unary `-` and `+`: checked
//!   `i64` (an overflow, which the engine turns into a big integer, is the
//!   engine's), as before floats were taken;
//! - `+ - *` with a float operand: both as `f64` (an integer by `as`), the
//!   IEEE operation, an infinite or NaN result the engine's error
//!   (`float_overflow`, `undefined`); `-` is `+` of the negation, the same
//!   IEEE value;
//! - `/`: with a float operand the `f64` quotient (a zero divisor the
//!   engine's error); of two integers the engine gives a float where
//!   SWI-Prolog gives an integer for an exact quotient: left to it;
//! - `//`, `mod`, `rem` of a float: the engine's type error;
//! - `min`/`max` with a float operand: compared as floats, the greater
//!   (smaller) operand as it is; a tie of an integer and a float (the
//!   engine answers the float) is the engine's;
//! - comparisons with a float operand: as floats (the engine converts the
//!   integer by `as`).
//!
//! Refused besides, wherever they occur (an argument, a constant, a
//! result): a float that is not *sure* ([`sure_float`]: not normal and not
//! `0.0`, i.e. negative zero, a subnormal, an infinity, a NaN: written as
//! text for a query, compared by `==` in the engine as ordered floats,
//! where `-0.0` and `0.0` are one), and an integer beyond ±2^53 meeting a
//! float (its conversion rounds; the engine's may differ). So a float a
//! clause holds is exactly the one the engine holds, and `==`, `is`'s
//! unification and the comparisons of two sure floats are those of
//! `f64`.

use super::{Bin, Cmp, Un};
use crate::arith::Number;

/// Whether the float is one the plain form takes (the module doc): a
/// normal float or `0.0`.
#[inline]
pub fn sure_float(f: f64) -> bool {
    f.is_normal() || f.to_bits() == 0
}

/// The largest integer magnitude converted to a float exactly.
const EXACT: i64 = 1 << 53;

/// `n` as the float the engine compares or computes with, `None` for an
/// integer beyond ±2^53.
#[inline]
fn as_f64(n: Number) -> Option<f64> {
    match n {
        Number::Int(i) if (-EXACT..=EXACT).contains(&i) => Some(i as f64),
        Number::Int(_) => None,
        Number::Float(f) => Some(f),
    }
}

/// A float result, `None` where it is not sure (an infinity or a NaN is
/// the engine's error; a negative zero or a subnormal, its value).
#[inline]
fn float(f: f64) -> Option<Number> {
    sure_float(f).then_some(Number::Float(f))
}

/// The float `f` as a number of a clause (`None`: not sure).
#[inline]
pub fn of_float(f: f64) -> Option<Number> {
    float(f)
}

/// `op x`.
#[inline]
pub fn un(op: Un, x: Number) -> Option<Number> {
    match (op, x) {
        (Un::Pos, x) => Some(x),
        (Un::Neg, Number::Int(i)) => i.checked_neg().map(Number::Int),
        (Un::Abs, Number::Int(i)) => i.checked_abs().map(Number::Int),
        (Un::Neg, Number::Float(f)) => float(-f),
        (Un::Abs, Number::Float(f)) => float(f.abs()),
    }
}

/// `x op y`.
#[inline]
pub fn bin(op: Bin, x: Number, y: Number) -> Option<Number> {
    match (x, y) {
        (Number::Int(a), Number::Int(b)) => match op {
            // Of two integers the engine's `/` is a float (the module doc).
            Bin::Div => None,
            _ => super::bin(op, a, b).ok().map(Number::Int),
        },
        _ => float_bin(op, x, y),
    }
}

/// [`bin`] with a float operand.
#[cold]
fn float_bin(op: Bin, x: Number, y: Number) -> Option<Number> {
    let (a, b) = (as_f64(x)?, as_f64(y)?);
    match op {
        Bin::Add => float(a + b),
        Bin::Sub => float(a - b),
        Bin::Mul => float(a * b),
        Bin::Div if b == 0.0 => None,
        Bin::Div => float(a / b),
        Bin::IntDiv | Bin::Mod | Bin::Rem => None,
        Bin::Min | Bin::Max => {
            if a == b {
                // A tie: the engine answers a float (of an integer too).
                return matches!((x, y), (Number::Float(_), Number::Float(_))).then_some(x);
            }
            Some(if (a < b) == matches!(op, Bin::Min) {
                x
            } else {
                y
            })
        }
    }
}

/// Whether `x op y` holds.
#[inline]
pub fn compare(op: Cmp, x: Number, y: Number) -> Option<bool> {
    match (x, y) {
        (Number::Int(a), Number::Int(b)) => Some(super::compare(op, a, b)),
        _ => {
            let (a, b) = (as_f64(x)?, as_f64(y)?);
            Some(match op {
                Cmp::Lt => a < b,
                Cmp::Gt => a > b,
                Cmp::Le => a <= b,
                Cmp::Ge => a >= b,
                Cmp::Eq => a == b,
                Cmp::Ne => a != b,
            })
        }
    }
}

/// Whether `V is E` holds with `V` bound to the number `v` and `E`'s value
/// `e`: they unify (an integer never with a float, `1` with `1.0` not).
#[inline]
pub fn same(e: Number, v: Number) -> bool {
    match (e, v) {
        (Number::Int(a), Number::Int(b)) => a == b,
        (Number::Float(a), Number::Float(b)) => a == b,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Number::{Float as F, Int as I};

    #[test]
    fn floats_as_the_engine_computes_them_or_refused() {
        assert_eq!(bin(Bin::Add, F(0.1), F(0.2)), Some(F(0.1 + 0.2)));
        assert_eq!(bin(Bin::Sub, I(3), F(0.5)), Some(F(2.5)));
        assert_eq!(bin(Bin::Div, I(7), I(2)), None); // the engine's float
        assert_eq!(bin(Bin::Div, F(7.0), I(2)), Some(F(3.5)));
        assert_eq!(bin(Bin::Div, F(7.0), I(0)), None); // zero divisor
        assert_eq!(bin(Bin::Mul, F(1e300), F(1e300)), None); // overflow
        assert_eq!(bin(Bin::Mul, F(1e-300), F(1e-300)), Some(F(0.0))); // underflow to zero
        assert_eq!(bin(Bin::Mul, F(1e-200), F(1e-120)), None); // a subnormal
        assert_eq!(bin(Bin::IntDiv, F(7.0), I(2)), None); // type error
        assert_eq!(bin(Bin::Mod, I(7), F(2.0)), None);
        assert_eq!(bin(Bin::Max, I(1), F(1.0)), None); // a tie of int and float
        assert_eq!(bin(Bin::Max, I(2), F(1.5)), Some(I(2)));
        assert_eq!(bin(Bin::Min, I(2), F(1.5)), Some(F(1.5)));
        assert_eq!(bin(Bin::Min, F(1.5), F(1.5)), Some(F(1.5)));
        assert_eq!(bin(Bin::Add, I(1 << 60), F(1.0)), None); // rounds
        assert_eq!(un(Un::Neg, F(0.0)), None); // negative zero
        assert_eq!(un(Un::Abs, F(-2.5)), Some(F(2.5)));
        assert_eq!(bin(Bin::Sub, F(0.5), F(0.5)), Some(F(0.0)));
        assert_eq!(compare(Cmp::Eq, I(1), F(1.0)), Some(true));
        assert_eq!(compare(Cmp::Lt, F(0.1), F(0.1)), Some(false));
        assert_eq!(compare(Cmp::Lt, I(EXACT + 1), F(1.0)), None);
        assert!(!same(I(1), F(1.0)));
        assert!(same(F(0.5), F(0.5)));
        assert!(!sure_float(-0.0) && !sure_float(f64::NAN) && !sure_float(f64::INFINITY));
        assert!(!sure_float(f64::MIN_POSITIVE / 2.0) && sure_float(0.0) && sure_float(-1e300));
    }
}
