//! The evaluator: the table of evaluable functors, [`Store::eval_arith`]
//! (a fast path for an operation on numbers, else an explicit task stack),
//! [`Store::arith_compare`], and what each operation computes, with
//! SWI-Prolog's errors and 64-bit integers.

use super::number::{compare_numbers, ArithCmp, ArithError, Number};
use crate::store::Store;
use crate::term::{Repr, Term};
use sitlog_syntax::write::format_float;
use sitlog_syntax::{atoms, Atom};
use std::cmp::Ordering;
use std::sync::OnceLock;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Op {
    // nullary
    Pi,
    E,
    Inf,
    Nan,
    Epsilon,
    MaxTagged,
    MaxInt,
    MinInt,
    RandomFloat,
    Cputime,
    Realtime,
    // unary
    Neg,
    Pos,
    Abs,
    Sign,
    Sqrt,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Asinh,
    Acosh,
    Atanh,
    Exp,
    Log,
    Log2,
    ToFloat,
    Integer,
    FloatIntPart,
    FloatFracPart,
    Truncate,
    Round,
    Ceiling,
    Floor,
    BitNot,
    Msb,
    Random,
    Succ,
    // binary
    Add,
    Sub,
    Mul,
    Div,
    IntDiv,
    Mod,
    Rem,
    FloorDiv,
    Min,
    Max,
    StarStar,
    Caret,
    Atan2,
    LogBase,
    Shr,
    Shl,
    And,
    Or,
    Xor,
    Gcd,
    Copysign,
}

/// The operator table, looked up at every `is` ([`crate::hash::AtomKeyHasher`]).
type OpTable = crate::hash::AtomKeyMap<(Atom, u32), Op>;

fn op_table() -> &'static OpTable {
    static TABLE: OnceLock<OpTable> = OnceLock::new();
    TABLE.get_or_init(|| {
        use Op::*;
        let defs: &[(&str, u32, Op)] = &[
            ("pi", 0, Pi),
            ("e", 0, E),
            ("inf", 0, Inf),
            ("infinite", 0, Inf),
            ("nan", 0, Nan),
            ("epsilon", 0, Epsilon),
            ("max_tagged_integer", 0, MaxTagged),
            ("max_integer", 0, MaxInt),
            ("min_integer", 0, MinInt),
            ("random_float", 0, RandomFloat),
            ("cputime", 0, Cputime),
            ("realtime", 0, Realtime),
            ("-", 1, Neg),
            ("+", 1, Pos),
            ("abs", 1, Abs),
            ("sign", 1, Sign),
            ("sqrt", 1, Sqrt),
            ("sin", 1, Sin),
            ("cos", 1, Cos),
            ("tan", 1, Tan),
            ("asin", 1, Asin),
            ("acos", 1, Acos),
            ("atan", 1, Atan),
            ("sinh", 1, Sinh),
            ("cosh", 1, Cosh),
            ("tanh", 1, Tanh),
            ("asinh", 1, Asinh),
            ("acosh", 1, Acosh),
            ("atanh", 1, Atanh),
            ("exp", 1, Exp),
            ("log", 1, Log),
            ("log2", 1, Log2),
            ("float", 1, ToFloat),
            ("integer", 1, Integer),
            ("float_integer_part", 1, FloatIntPart),
            ("float_fractional_part", 1, FloatFracPart),
            ("truncate", 1, Truncate),
            ("round", 1, Round),
            ("ceiling", 1, Ceiling),
            ("floor", 1, Floor),
            ("\\", 1, BitNot),
            ("msb", 1, Msb),
            ("random", 1, Random),
            ("succ", 1, Succ),
            ("+", 2, Add),
            ("-", 2, Sub),
            ("*", 2, Mul),
            ("/", 2, Div),
            ("//", 2, IntDiv),
            ("mod", 2, Mod),
            ("rem", 2, Rem),
            ("div", 2, FloorDiv),
            ("min", 2, Min),
            ("max", 2, Max),
            ("**", 2, StarStar),
            ("^", 2, Caret),
            ("atan", 2, Atan2),
            ("atan2", 2, Atan2),
            ("log", 2, LogBase),
            (">>", 2, Shr),
            ("<<", 2, Shl),
            ("/\\", 2, And),
            ("\\/", 2, Or),
            ("xor", 2, Xor),
            ("gcd", 2, Gcd),
            ("copysign", 2, Copysign),
        ];
        defs.iter()
            .map(|&(name, arity, op)| ((Atom::intern(name), arity), op))
            .collect()
    })
}

/// Work item of the evaluator.
enum Task {
    Eval(Term),
    Apply(Op, usize),
}

impl Store {
    /// Evaluates an arithmetic expression (the right side of `is/2`).
    pub fn eval_arith(&mut self, t: Term) -> Result<Number, ArithError> {
        let t = self.deref(t);
        // Fast paths: a number, or an operation on numbers.
        match t.0 {
            Repr::Int(i) => return Ok(Number::Int(i)),
            Repr::Float(bits) => return Ok(Number::Float(f64::from_bits(bits))),
            Repr::Struct(p) => {
                let (name, args) = self.compound_at(p);
                if args.len() <= 2 {
                    let mut xs = [Number::Int(0); 2];
                    let mut all = true;
                    for (slot, &a) in xs.iter_mut().zip(args) {
                        match self.deref(a).0 {
                            Repr::Int(i) => *slot = Number::Int(i),
                            Repr::Float(b) => *slot = Number::Float(f64::from_bits(b)),
                            _ => all = false,
                        }
                    }
                    if all {
                        if let Some(&op) = op_table().get(&(name, args.len() as u32)) {
                            let n = args.len();
                            return self.apply(op, &xs[..n]);
                        }
                    }
                }
            }
            _ => {}
        }
        self.eval_general(t)
    }

    fn eval_general(&mut self, t: Term) -> Result<Number, ArithError> {
        let mut tasks = vec![Task::Eval(t)];
        let mut vals: Vec<Number> = Vec::new();
        while let Some(task) = tasks.pop() {
            match task {
                Task::Eval(t) => {
                    let t = self.deref(t);
                    match t.0 {
                        Repr::Int(i) => vals.push(Number::Int(i)),
                        Repr::Float(b) => vals.push(Number::Float(f64::from_bits(b))),
                        Repr::Var(_) => return Err(ArithError::Instantiation),
                        Repr::Big(b) => {
                            return Err(ArithError::BigInteger(self.bigs[b as usize].to_string()))
                        }
                        Repr::Atom(a) => match op_table().get(&(a, 0)) {
                            Some(&op) => vals.push(self.apply(op, &[])?),
                            None => return Err(ArithError::NotEvaluable { name: a, arity: 0 }),
                        },
                        Repr::Struct(p) => {
                            let (name, args) = self.compound_at(p);
                            // `[X]` evaluates X (so `"a"` is 97), as in SWI-Prolog.
                            if name == atoms::DOT
                                && args.len() == 2
                                && self.deref(args[1]) == Term::NIL
                            {
                                tasks.push(Task::Eval(args[0]));
                                continue;
                            }
                            let Some(&op) = op_table().get(&(name, args.len() as u32)) else {
                                return Err(ArithError::NotEvaluable {
                                    name,
                                    arity: args.len(),
                                });
                            };
                            tasks.push(Task::Apply(op, args.len()));
                            tasks.extend(args.iter().rev().map(|&a| Task::Eval(a)));
                        }
                        Repr::Functor(name, n, _) => {
                            return Err(ArithError::NotEvaluable {
                                name,
                                arity: n as usize,
                            })
                        }
                    }
                }
                Task::Apply(op, n) => {
                    let base = vals.len().saturating_sub(n);
                    let mut xs = [Number::Int(0); 2];
                    xs[..n].copy_from_slice(&vals[base..]);
                    vals.truncate(base);
                    let r = self.apply(op, &xs[..n])?;
                    vals.push(r);
                }
            }
        }
        vals.pop().ok_or(ArithError::Undefined)
    }

    /// Arithmetic comparison: both sides are evaluated, then compared by
    /// value (`1 =:= 1.0` is true). NaN compares unequal to everything.
    pub fn arith_compare(&mut self, op: ArithCmp, a: Term, b: Term) -> Result<bool, ArithError> {
        if let (Repr::Int(x), Repr::Int(y)) = (self.deref(a).0, self.deref(b).0) {
            return Ok(match op {
                ArithCmp::Eq => x == y,
                ArithCmp::Ne => x != y,
                ArithCmp::Lt => x < y,
                ArithCmp::Gt => x > y,
                ArithCmp::Le => x <= y,
                ArithCmp::Ge => x >= y,
            });
        }
        let x = self.eval_arith(a)?;
        let y = self.eval_arith(b)?;
        let o = compare_numbers(x, y);
        Ok(match op {
            ArithCmp::Eq => o == Some(Ordering::Equal),
            ArithCmp::Ne => o != Some(Ordering::Equal),
            ArithCmp::Lt => o == Some(Ordering::Less),
            ArithCmp::Gt => o == Some(Ordering::Greater),
            ArithCmp::Le => matches!(o, Some(Ordering::Less | Ordering::Equal)),
            ArithCmp::Ge => matches!(o, Some(Ordering::Greater | Ordering::Equal)),
        })
    }

    /// Seeds the generator behind `random/1` and `random_float`
    /// (reproducible runs).
    pub fn set_random_seed(&mut self, seed: u64) {
        // splitmix64 scrambles small seeds; xorshift needs a non-zero state.
        let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        self.rng = if z == 0 { 0x9E37_79B9_7F4A_7C15 } else { z };
    }

    fn next_random(&mut self) -> u64 {
        // xorshift64*
        let mut x = self.rng;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.rng = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn apply(&mut self, op: Op, x: &[Number]) -> Result<Number, ArithError> {
        use Number::{Float as F, Int as I};
        let a = x.first().copied().unwrap_or(I(0));
        let b = x.get(1).copied().unwrap_or(I(0));
        Ok(match op {
            Op::Pi => F(std::f64::consts::PI),
            Op::E => F(std::f64::consts::E),
            Op::Inf => F(f64::INFINITY),
            Op::Nan => F(f64::NAN),
            Op::Epsilon => F(f64::EPSILON),
            Op::MaxTagged => I((1 << 60) - 1),
            Op::MaxInt => I(i64::MAX),
            Op::MinInt => I(i64::MIN),
            Op::RandomFloat => {
                // Strictly inside (0, 1), as SWI-Prolog's random_float.
                F(((self.next_random() >> 11) as f64 + 0.5) / (1u64 << 53) as f64)
            }
            Op::Cputime => F(cpu_time()),
            Op::Realtime => I(std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_secs() as i64)),

            Op::Neg => match a {
                I(i) => I(i.checked_neg().ok_or(ArithError::IntOverflow)?),
                F(f) => F(-f),
            },
            Op::Pos => a,
            Op::Abs => match a {
                I(i) => I(i.checked_abs().ok_or(ArithError::IntOverflow)?),
                F(f) => F(f.abs()),
            },
            Op::Sign => match a {
                I(i) => I(i.signum()),
                F(f) if f > 0.0 => F(1.0),
                F(f) if f < 0.0 => F(-1.0),
                F(f) => F(f),
            },
            Op::Sqrt => float1(a, |f| (f >= 0.0 || f.is_nan()).then(|| f.sqrt()))?,
            Op::Sin => float1(a, |f| Some(f.sin()))?,
            Op::Cos => float1(a, |f| Some(f.cos()))?,
            Op::Tan => float1(a, |f| Some(f.tan()))?,
            Op::Asin => float1(a, |f| (f.abs() <= 1.0 || f.is_nan()).then(|| f.asin()))?,
            Op::Acos => float1(a, |f| (f.abs() <= 1.0 || f.is_nan()).then(|| f.acos()))?,
            Op::Atan => float1(a, |f| Some(f.atan()))?,
            Op::Sinh => float1(a, |f| Some(f.sinh()))?,
            Op::Cosh => float1(a, |f| Some(f.cosh()))?,
            Op::Tanh => float1(a, |f| Some(f.tanh()))?,
            Op::Asinh => float1(a, |f| Some(f.asinh()))?,
            Op::Acosh => float1(a, |f| (f >= 1.0 || f.is_nan()).then(|| f.acosh()))?,
            Op::Atanh => float1(a, |f| (f.abs() < 1.0 || f.is_nan()).then(|| f.atanh()))?,
            Op::Exp => float1(a, |f| Some(f.exp()))?,
            Op::Log => float1(a, |f| (f > 0.0 || f.is_nan()).then(|| f.ln()))?,
            Op::Log2 => float1(a, |f| (f > 0.0 || f.is_nan()).then(|| f.log2()))?,
            Op::LogBase => {
                let (base, v) = (a.to_f64(), b.to_f64());
                if base <= 0.0 || v <= 0.0 || base == 1.0 {
                    return Err(ArithError::Undefined);
                }
                check_float(v.ln() / base.ln(), &[base, v])?
            }
            Op::ToFloat => F(a.to_f64()),
            Op::Integer => match a {
                I(i) => I(i),
                F(f) => I(float_to_int(f.round())?),
            },
            Op::FloatIntPart => match a {
                I(i) => F(i as f64),
                F(f) => F(f.trunc()),
            },
            Op::FloatFracPart => match a {
                I(_) => I(0),
                F(f) => F(f.fract()),
            },
            Op::Truncate => round_with(a, f64::trunc)?,
            Op::Round => round_with(a, f64::round)?,
            Op::Ceiling => round_with(a, f64::ceil)?,
            Op::Floor => round_with(a, f64::floor)?,
            Op::BitNot => I(!int(a)?),
            Op::Msb => {
                let i = int(a)?;
                if i <= 0 {
                    return Err(ArithError::Type {
                        expected: "not_less_than_one",
                        culprit: i.to_string(),
                    });
                }
                I(63 - i64::from(i.leading_zeros()))
            }
            Op::Random => {
                let n = int(a)?;
                if n <= 0 {
                    return Err(ArithError::Type {
                        expected: "positive_integer",
                        culprit: n.to_string(),
                    });
                }
                // Multiply-shift: uniform enough, no modulo bias worth noting.
                let r = (u128::from(self.next_random()) * n as u128) >> 64;
                I(r as i64)
            }
            Op::Succ => {
                let i = int(a)?;
                if i < 0 {
                    return Err(ArithError::Type {
                        expected: "not_less_than_zero",
                        culprit: i.to_string(),
                    });
                }
                I(i.checked_add(1).ok_or(ArithError::IntOverflow)?)
            }

            Op::Add => match (a, b) {
                (I(x), I(y)) => I(x.checked_add(y).ok_or(ArithError::IntOverflow)?),
                _ => float2(a, b, |x, y| x + y)?,
            },
            Op::Sub => match (a, b) {
                (I(x), I(y)) => I(x.checked_sub(y).ok_or(ArithError::IntOverflow)?),
                _ => float2(a, b, |x, y| x - y)?,
            },
            Op::Mul => match (a, b) {
                (I(x), I(y)) => I(x.checked_mul(y).ok_or(ArithError::IntOverflow)?),
                _ => float2(a, b, |x, y| x * y)?,
            },
            Op::Div => match (a, b) {
                (I(_), I(0)) => return Err(ArithError::ZeroDivisor),
                (I(x), I(y)) => {
                    // Exact quotients stay integers (iso=false).
                    if x.checked_rem(y).unwrap_or(0) == 0 {
                        I(x.checked_div(y).ok_or(ArithError::IntOverflow)?)
                    } else {
                        F(x as f64 / y as f64)
                    }
                }
                _ => {
                    let (x, y) = (a.to_f64(), b.to_f64());
                    if y == 0.0 && !x.is_nan() {
                        return Err(if x == 0.0 {
                            ArithError::Undefined
                        } else {
                            ArithError::ZeroDivisor
                        });
                    }
                    check_float(x / y, &[x, y])?
                }
            },
            Op::IntDiv => {
                let (x, y) = (int(a)?, int(b)?);
                if y == 0 {
                    return Err(ArithError::ZeroDivisor);
                }
                I(x.checked_div(y).ok_or(ArithError::IntOverflow)?)
            }
            Op::Mod => {
                let (x, y) = (int(a)?, int(b)?);
                if y == 0 {
                    return Err(ArithError::ZeroDivisor);
                }
                // Sign of the divisor; MIN mod -1 is 0, not an overflow.
                let r = x.checked_rem(y).unwrap_or(0);
                I(if r != 0 && ((r < 0) != (y < 0)) {
                    r + y
                } else {
                    r
                })
            }
            Op::Rem => {
                let (x, y) = (int(a)?, int(b)?);
                if y == 0 {
                    return Err(ArithError::ZeroDivisor);
                }
                I(x.checked_rem(y).unwrap_or(0))
            }
            Op::FloorDiv => {
                let (x, y) = (int(a)?, int(b)?);
                if y == 0 {
                    return Err(ArithError::ZeroDivisor);
                }
                let q = x.checked_div(y).ok_or(ArithError::IntOverflow)?;
                I(if x % y != 0 && ((x < 0) != (y < 0)) {
                    q - 1
                } else {
                    q
                })
            }
            // As SWI-Prolog's ar_min/ar_max: on a tie (`1` vs `1.0`) min
            // gives the second argument and max the first; NaN is contagious.
            Op::Min => match compare_numbers(a, b) {
                None => F(f64::NAN),
                Some(Ordering::Less) => a,
                Some(_) => b,
            },
            Op::Max => match compare_numbers(a, b) {
                None => F(f64::NAN),
                Some(Ordering::Less) => b,
                Some(_) => a,
            },
            Op::StarStar => match (a, b) {
                (I(x), I(y)) if y >= 0 => I(int_pow(x, y)?),
                _ => float_pow(a, b)?,
            },
            Op::Caret => match (a, b) {
                (I(x), I(y)) if y >= 0 => I(int_pow(x, y)?),
                (I(x), I(y)) => match x {
                    1 => I(1),
                    -1 => I(if y % 2 == 0 { 1 } else { -1 }),
                    0 => return Err(ArithError::ZeroDivisor),
                    // ISO: an integer result cannot be negative-exponent.
                    _ => {
                        return Err(ArithError::Type {
                            expected: "float",
                            culprit: x.to_string(),
                        })
                    }
                },
                _ => float_pow(a, b)?,
            },
            Op::Atan2 => {
                let (y, x) = (a.to_f64(), b.to_f64());
                check_float(y.atan2(x), &[y, x])?
            }
            Op::Shr => I(shift_right(int(a)?, int(b)?)?),
            Op::Shl => I(shift_left(int(a)?, int(b)?)?),
            Op::And => I(int(a)? & int(b)?),
            Op::Or => I(int(a)? | int(b)?),
            Op::Xor => I(int(a)? ^ int(b)?),
            Op::Gcd => {
                let (mut x, mut y) = (int(a)?.unsigned_abs(), int(b)?.unsigned_abs());
                while y != 0 {
                    (x, y) = (y, x % y);
                }
                I(i64::try_from(x).map_err(|_| ArithError::IntOverflow)?)
            }
            Op::Copysign => F(a.to_f64().copysign(b.to_f64())),
        })
    }
}

/// The integer value, or a type error naming the float.
fn int(n: Number) -> Result<i64, ArithError> {
    match n {
        Number::Int(i) => Ok(i),
        Number::Float(f) => Err(ArithError::Type {
            expected: "integer",
            culprit: format_float(f),
        }),
    }
}

/// Applies a float function; `None` from `f` means outside its domain.
fn float1(a: Number, f: impl Fn(f64) -> Option<f64>) -> Result<Number, ArithError> {
    let x = a.to_f64();
    match f(x) {
        Some(r) => check_float(r, &[x]),
        None => Err(ArithError::Undefined),
    }
}

fn float2(a: Number, b: Number, f: impl Fn(f64, f64) -> f64) -> Result<Number, ArithError> {
    let (x, y) = (a.to_f64(), b.to_f64());
    check_float(f(x, y), &[x, y])
}

/// A non-finite result from finite inputs is an error (SWI-Prolog's
/// float_overflow/float_undefined flags default to `error`); infinities
/// and NaNs that came in may go out.
fn check_float(r: f64, inputs: &[f64]) -> Result<Number, ArithError> {
    if r.is_finite() || inputs.iter().any(|x| !x.is_finite()) {
        Ok(Number::Float(r))
    } else if r.is_nan() {
        Err(ArithError::Undefined)
    } else {
        Err(ArithError::FloatOverflow)
    }
}

fn float_pow(a: Number, b: Number) -> Result<Number, ArithError> {
    let (x, y) = (a.to_f64(), b.to_f64());
    if x == 0.0 && y < 0.0 {
        return Err(ArithError::ZeroDivisor);
    }
    check_float(x.powf(y), &[x, y])
}

fn int_pow(base: i64, exp: i64) -> Result<i64, ArithError> {
    match base {
        0 => Ok(if exp == 0 { 1 } else { 0 }),
        1 => Ok(1),
        -1 => Ok(if exp % 2 == 0 { 1 } else { -1 }),
        _ => {
            let e = u32::try_from(exp).map_err(|_| ArithError::IntOverflow)?;
            base.checked_pow(e).ok_or(ArithError::IntOverflow)
        }
    }
}

/// Exact conversion of an integral float to `i64`.
fn float_to_int(f: f64) -> Result<i64, ArithError> {
    if f.is_nan() {
        return Err(ArithError::Undefined);
    }
    // [-2^63, 2^63): every float in it converts exactly.
    if (-9_223_372_036_854_775_808.0..9_223_372_036_854_775_808.0).contains(&f) {
        Ok(f as i64)
    } else {
        Err(ArithError::IntOverflow)
    }
}

fn round_with(a: Number, f: fn(f64) -> f64) -> Result<Number, ArithError> {
    match a {
        Number::Int(i) => Ok(Number::Int(i)),
        Number::Float(x) => Ok(Number::Int(float_to_int(f(x))?)),
    }
}

fn shift_left(x: i64, s: i64) -> Result<i64, ArithError> {
    if s < 0 {
        return shift_right(x, s.checked_neg().ok_or(ArithError::IntOverflow)?);
    }
    if x == 0 {
        return Ok(0);
    }
    if s >= 64 {
        return Err(ArithError::IntOverflow);
    }
    let r = x << s;
    if r >> s == x {
        Ok(r)
    } else {
        Err(ArithError::IntOverflow)
    }
}

fn shift_right(x: i64, s: i64) -> Result<i64, ArithError> {
    if s < 0 {
        return shift_left(x, s.checked_neg().ok_or(ArithError::IntOverflow)?);
    }
    Ok(if s >= 64 {
        if x < 0 {
            -1
        } else {
            0
        }
    } else {
        x >> s
    })
}

/// Process CPU time in seconds.
#[cfg(unix)]
fn cpu_time() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime only writes the timespec it is given.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    if rc == 0 {
        ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
    } else {
        wall_time_since_start()
    }
}

#[cfg(not(unix))]
fn cpu_time() -> f64 {
    wall_time_since_start()
}

#[cfg_attr(unix, allow(dead_code))]
fn wall_time_since_start() -> f64 {
    static START: OnceLock<std::time::Instant> = OnceLock::new();
    START
        .get_or_init(std::time::Instant::now)
        .elapsed()
        .as_secs_f64()
}
