//! The values of arithmetic and what can go wrong: [`Number`],
//! [`ArithError`], the comparison operators [`ArithCmp`] and
//! [`compare_numbers`] (exact comparison of integers with floats).

use crate::term::Term;
use crate::unify::cmp_int_float;
use sitlog_syntax::write::format_float;
use sitlog_syntax::Atom;
use std::cmp::Ordering;
use std::fmt;

/// The value of an arithmetic expression.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Number {
    Int(i64),
    Float(f64),
}

impl Number {
    /// As a float (integers rounded to the nearest float).
    pub fn to_f64(self) -> f64 {
        match self {
            Number::Int(i) => i as f64,
            Number::Float(f) => f,
        }
    }
}

impl From<Number> for Term {
    fn from(n: Number) -> Term {
        match n {
            Number::Int(i) => Term::int(i),
            Number::Float(f) => Term::float(f),
        }
    }
}

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Number::Int(i) => write!(f, "{i}"),
            Number::Float(x) => f.write_str(&format_float(*x)),
        }
    }
}

/// Why an arithmetic evaluation failed (SWI-Prolog's error terms in
/// comments).
#[derive(Clone, Debug, PartialEq)]
pub enum ArithError {
    /// An unbound variable (`instantiation_error`).
    Instantiation,
    /// An atom or compound that is no arithmetic function
    /// (`type_error(evaluable, Name/Arity)`).
    NotEvaluable { name: Atom, arity: usize },
    /// A value of the wrong type (`type_error(Expected, Culprit)`), e.g. a
    /// float given to `//`; `culprit` is the value as written.
    Type {
        expected: &'static str,
        culprit: String,
    },
    /// Division by zero (`evaluation_error(zero_divisor)`).
    ZeroDivisor,
    /// No defined result, e.g. `sqrt(-1)`, `log(0)`
    /// (`evaluation_error(undefined)`).
    Undefined,
    /// The integer result does not fit 64 bits (SWI-Prolog would use a
    /// big integer).
    IntOverflow,
    /// A float result too large (`evaluation_error(float_overflow)`).
    FloatOverflow,
    /// A big integer literal used in arithmetic (only printable here).
    BigInteger(String),
}

impl fmt::Display for ArithError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ArithError::Instantiation => f.write_str("Arguments are not sufficiently instantiated"),
            ArithError::NotEvaluable { name, arity } => {
                let mut n = String::new();
                sitlog_syntax::write::write_atom(&mut n, *name, true);
                write!(f, "Arithmetic: evaluable `{n}/{arity}' does not exist")
            }
            ArithError::Type { expected, culprit } => {
                write!(f, "Type error: `{expected}' expected, found `{culprit}'")
            }
            ArithError::ZeroDivisor => f.write_str("Arithmetic: evaluation error: zero_divisor"),
            ArithError::Undefined => f.write_str("Arithmetic: evaluation error: undefined"),
            ArithError::IntOverflow => {
                f.write_str("Arithmetic: evaluation error: int_overflow (integers are 64-bit)")
            }
            ArithError::FloatOverflow => {
                f.write_str("Arithmetic: evaluation error: float_overflow")
            }
            ArithError::BigInteger(text) => write!(
                f,
                "Arithmetic: integer {text} does not fit 64 bits (big integers are not supported)"
            ),
        }
    }
}

impl std::error::Error for ArithError {}

/// An arithmetic comparison operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArithCmp {
    /// `=:=`
    Eq,
    /// `=\=`
    Ne,
    /// `<`
    Lt,
    /// `>`
    Gt,
    /// `=<`
    Le,
    /// `>=`
    Ge,
}

impl ArithCmp {
    /// The comparison named by `op` (`=:=`, `=\=`, `<`, `>`, `=<`, `>=`).
    pub fn from_atom(op: Atom) -> Option<ArithCmp> {
        Some(match op.as_str() {
            "=:=" => ArithCmp::Eq,
            "=\\=" => ArithCmp::Ne,
            "<" => ArithCmp::Lt,
            ">" => ArithCmp::Gt,
            "=<" => ArithCmp::Le,
            ">=" => ArithCmp::Ge,
            _ => return None,
        })
    }

    /// The operator's name.
    pub fn atom(self) -> Atom {
        Atom::intern(match self {
            ArithCmp::Eq => "=:=",
            ArithCmp::Ne => "=\\=",
            ArithCmp::Lt => "<",
            ArithCmp::Gt => ">",
            ArithCmp::Le => "=<",
            ArithCmp::Ge => ">=",
        })
    }
}

/// Numeric comparison: integers and floats by exact value; `None` when a
/// NaN is involved.
pub fn compare_numbers(a: Number, b: Number) -> Option<Ordering> {
    match (a, b) {
        (Number::Int(x), Number::Int(y)) => Some(x.cmp(&y)),
        (Number::Float(x), Number::Float(y)) => x.partial_cmp(&y),
        (Number::Int(x), Number::Float(y)) => (!y.is_nan()).then(|| cmp_int_float(x, y)),
        (Number::Float(x), Number::Int(y)) => (!x.is_nan()).then(|| cmp_int_float(y, x).reverse()),
    }
}
