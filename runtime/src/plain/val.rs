//! Plain functions run on native values (issue 37): the clauses of
//! [`PlainFn`] run on [`Val`]s, for native code that holds a call's
//! arguments as values already (`Cx::nat_plain`), so that neither the
//! arguments nor the value become terms and back.
//!
//! Invariant: [`PlainFns::call_vals`] gives `Some(v)` exactly where
//! [`PlainFns::call`] on the arguments' terms would give a term `==` to
//! `v`'s, and the term evaluator would have passed those terms to the
//! function unchanged; everything else is `None` (the caller takes the
//! term path, whose answer and error are the engine's). So it refuses what
//! `call` refuses (a float that is not sure, `num::sure_float`, an unbound part, an improper list, a deeper
//! nesting than [`MAX_DEPTH`], a type error, an overflow, a function that
//! fails or assigns nothing) and, besides, an argument that L would not
//! take as its own value (a compound whose functor is a construct of L,
//! D-36) and any `Val::Term` (a store term: the term path decides). A
//! list already checked is not walked again: [`CHECKED`] remembers the
//! last list checked whole and accepts its tails (a list is immutable, and
//! one without a `Val::Term` stays so), so a walk that passes the rest of
//! its list at each visit checks it once.

use super::{num, Opnd, PArg, PClause, PExpr, PGoal, PlainFn, PlainFns, MAX_DEPTH, MIN_INFERENCES};
use crate::arith::Number;
use crate::native::{Compound, List, Val};
use crate::term::{Repr, Term};
use sitlog_syntax::{atoms, Atom};
use std::cell::RefCell;

thread_local! {
    /// The last list [`sure`] checked whole as an argument (kept alive here,
    /// so its storage is never reused while it is remembered).
    static CHECKED: RefCell<List<Val>> = const { RefCell::new(List::nil()) };
}

/// How a clause ran on values.
enum Outcome {
    Value(Val),
    Fail { cut: bool },
    NoValue,
    Unsure,
}

impl PlainFns {
    /// [`PlainFns::call`] on values: the value of `name(args..)` if it is a
    /// plain function the native form runs to a value under an inference
    /// limit of `limit`, the arguments being what L passes on unchanged;
    /// `None`: the term path decides (see the module's invariant).
    pub(crate) fn call_vals(&self, name: Atom, args: &[Val], limit: u64) -> Option<Val> {
        let f = self.map.get(&(name, args.len()))?;
        if limit < MIN_INFERENCES.max(f.inferences) {
            return None;
        }
        if !args.iter().all(sure_arg) {
            return None;
        }
        // One set of registers for the call, made once: a clause writes a
        // variable's register before it reads it (a variable read before
        // it is bound is not plain), so what an earlier clause left there
        // is never read.
        if f.vars <= SMALL / 2 {
            let mut regs: [Val; SMALL / 2] = std::array::from_fn(|_| Val::Int(0));
            run_clauses(f, args, &mut regs[..f.vars])
        } else if f.vars <= SMALL {
            let mut regs: [Val; SMALL] = std::array::from_fn(|_| Val::Int(0));
            run_clauses(f, args, &mut regs[..f.vars])
        } else {
            let mut regs = vec![Val::Int(0); f.vars];
            run_clauses(f, args, &mut regs)
        }
    }
}

/// The first clause's value, `None` where no clause gives one or the term
/// path decides.
fn run_clauses(f: &PlainFn, args: &[Val], regs: &mut [Val]) -> Option<Val> {
    for c in f.clauses.iter() {
        match run_clause(c, args, &mut regs[..c.vars]) {
            Outcome::Value(v) => return Some(v),
            Outcome::Fail { cut: false } => continue,
            Outcome::Fail { cut: true } | Outcome::NoValue | Outcome::Unsure => return None,
        }
    }
    None
}

/// Registers on the stack for a function of at most this many variables
/// in a clause.
const SMALL: usize = 8;

/// Whether a top-level argument is taken ([`sure`] at depth 0), a list
/// that is a tail of the last one checked without a walk.
pub(super) fn sure_arg(v: &Val) -> bool {
    match v {
        Val::Int(_) | Val::Sym(_) => true,
        Val::List(l) => {
            if CHECKED.with(|c| c.borrow().has_tail(l)) {
                return true;
            }
            let ok = sure(v, 0);
            if ok && !l.is_empty() {
                CHECKED.with(|c| *c.borrow_mut() = l.clone());
            }
            ok
        }
        _ => sure(v, 0),
    }
}

/// Whether `v`, at nesting `depth`, is what the term path takes as it is:
/// ground (no `Val::Term`), no float but a sure one (`num::sure_float`),
/// no improper list (a `'.'/2`
/// compound is one), no compound L evaluates otherwise than by its
/// arguments (D-36), nesting at most [`MAX_DEPTH`] levels counted as the
/// term's (a list a level per element).
fn sure(v: &Val, depth: usize) -> bool {
    if depth > MAX_DEPTH {
        return false;
    }
    match v {
        Val::Int(_) | Val::Sym(_) => true,
        Val::Float(f) => num::sure_float(*f),
        Val::Term(_) => false,
        Val::List(l) => {
            // The `[]` ending the list sits `len` levels down.
            if depth + l.len() > MAX_DEPTH {
                return false;
            }
            stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
                l.iter().enumerate().all(|(k, x)| sure(x, depth + k + 1))
            })
        }
        Val::Tagged(c) => {
            let n = c.args().len();
            !(c.name() == atoms::DOT && n == 2)
                && crate::special::evaluates_arguments_only(c.name(), n)
                && stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
                    c.args().iter().all(|x| sure(x, depth + 1))
                })
        }
    }
}

/// The atom `v` is (`[]` as an empty list too).
fn atom_of(v: &Val) -> Option<Atom> {
    match v {
        Val::Sym(a) => Some(*a),
        Val::List(l) if l.is_empty() => Some(atoms::NIL),
        Val::Tagged(c) if c.args().is_empty() => Some(c.name()),
        _ => None,
    }
}

/// The arguments of `v` as the compound `f/n` (`n` ≥ 1), a list's head and
/// tail for `'.'/2`.
pub enum Parts<'a> {
    Args(&'a [Val]),
    Cell(&'a Val, Val),
}

impl Parts<'_> {
    /// Argument `i` (`0`: a list's head, `1` its tail).
    #[inline]
    pub fn get(&self, i: usize) -> &Val {
        match self {
            Parts::Args(a) => &a[i],
            Parts::Cell(h, _) if i == 0 => h,
            Parts::Cell(_, t) => t,
        }
    }
}

pub(super) fn parts(v: &Val, f: Atom, n: usize) -> Option<Parts<'_>> {
    match v {
        Val::List(l) if f == atoms::DOT && n == 2 => {
            l.split_first().map(|(h, t)| Parts::Cell(h, Val::List(t)))
        }
        Val::Tagged(c) if c.name() == f && c.args().len() == n && n > 0 => {
            Some(Parts::Args(c.args()))
        }
        _ => None,
    }
}

/// Whether two values taken or built here are the same term (`==`).
pub(super) fn ident(x: &Val, y: &Val) -> bool {
    match (x, y) {
        (Val::Sym(a), Val::Sym(b)) => a == b,
        (Val::Int(a), Val::Int(b)) => a == b,
        // Sure floats (`num::sure_float`): identical by value.
        (Val::Float(a), Val::Float(b)) => a.to_bits() == b.to_bits(),
        (Val::List(a), Val::List(b)) => {
            a.same_storage(b)
                || (a.len() == b.len() && a.iter().zip(b.iter()).all(|(p, q)| ident(p, q)))
        }
        (Val::Tagged(a), Val::Tagged(b)) if !a.args().is_empty() => {
            a.name() == b.name()
                && a.args().len() == b.args().len()
                && stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
                    a.args().iter().zip(b.args()).all(|(p, q)| ident(p, q))
                })
        }
        _ => match (atom_of(x), atom_of(y)) {
            (Some(a), Some(b)) => a == b,
            _ => false,
        },
    }
}

/// A constant of a clause (an atom or an integer) as a value.
fn constant(k: Term) -> Val {
    match k.0 {
        Repr::Atom(a) if a == atoms::NIL => Val::List(List::nil()),
        Repr::Atom(a) => Val::Sym(a),
        Repr::Int(i) => Val::Int(i),
        _ => unreachable!("a plain clause's constant is an atom or an integer"),
    }
}

/// Whether the operand's value is `v` (`==`), without building it.
fn ident_ov(o: &Opnd, v: &Val, regs: &[Val]) -> bool {
    match o {
        Opnd::Var(i) => ident(&regs[*i as usize], v),
        Opnd::Const(k) => ident_k(v, *k),
        Opnd::Build(f, args) => match parts(v, *f, args.len()) {
            Some(p) => (0..args.len()).all(|i| ident_ov(&args[i], p.get(i), regs)),
            None => false,
        },
    }
}

/// Whether `v` is the constant `k` (`==`): an atom or an integer compared
/// where it is, the rest as [`ident`] of the constant's value.
#[inline]
pub(super) fn ident_k(v: &Val, k: Term) -> bool {
    match (v, k.0) {
        // `[]` is an atom both ways (`atom_of`).
        (Val::Sym(a), Repr::Atom(b)) => *a == b,
        (Val::Int(i), Repr::Int(j)) => *i == j,
        _ => ident(v, &constant(k)),
    }
}

/// Whether two operands' values are identical (`==`).
#[inline]
fn ident_oo(x: &Opnd, y: &Opnd, regs: &[Val]) -> bool {
    match (x, y) {
        (Opnd::Var(i), Opnd::Const(k)) | (Opnd::Const(k), Opnd::Var(i)) => {
            ident_k(&regs[*i as usize], *k)
        }
        (Opnd::Var(i), Opnd::Var(j)) => ident(&regs[*i as usize], &regs[*j as usize]),
        _ => ident_oo_slow(x, y, regs),
    }
}

/// [`ident_oo`] but for a variable against a constant or a variable.
fn ident_oo_slow(x: &Opnd, y: &Opnd, regs: &[Val]) -> bool {
    match (x, y) {
        (Opnd::Build(f, a), Opnd::Build(g, b)) => {
            f == g
                && a.len() == b.len()
                && a.iter().zip(b.iter()).all(|(p, q)| ident_oo(p, q, regs))
        }
        (Opnd::Var(i), o) | (o, Opnd::Var(i)) => ident_ov(o, &regs[*i as usize], regs),
        (Opnd::Const(k), o) | (o, Opnd::Const(k)) => ident_ov(o, &constant(*k), regs),
    }
}

/// The operand's value, built of the registers' values (shared). `None`
/// for a list cell whose tail is not a list (the term path's refusal).
fn value(o: &Opnd, regs: &[Val]) -> Option<Val> {
    match o {
        Opnd::Var(i) => Some(regs[*i as usize].clone()),
        Opnd::Const(k) => Some(constant(*k)),
        Opnd::Build(f, args) if *f == atoms::DOT && args.len() == 2 => {
            let h = value(&args[0], regs)?;
            match value(&args[1], regs)? {
                Val::List(t) => Some(Val::List(List::cons(h, t))),
                _ => None,
            }
        }
        // A small compound in one allocation (its slice), no vector first.
        Opnd::Build(f, args) => Some(Val::Tagged(match &args[..] {
            [a] => Compound::new(*f, [value(a, regs)?]),
            [a, b] => Compound::new(*f, [value(a, regs)?, value(b, regs)?]),
            [a, b, c] => Compound::new(*f, [value(a, regs)?, value(b, regs)?, value(c, regs)?]),
            _ => {
                let mut vs = Vec::with_capacity(args.len());
                for a in args.iter() {
                    vs.push(value(a, regs)?);
                }
                Compound::new(*f, vs)
            }
        })),
    }
}

/// The number `v` is (a sure float, `num::sure_float`), `Err` (not
/// decided here) for anything else.
#[inline]
pub(super) fn number(v: &Val) -> Result<Number, ()> {
    match v {
        Val::Int(i) => Ok(Number::Int(*i)),
        Val::Float(f) => num::of_float(*f).ok_or(()),
        _ => Err(()),
    }
}

fn eval(e: &PExpr, regs: &[Val]) -> Result<Number, ()> {
    Ok(match e {
        PExpr::Var(i) => number(&regs[*i as usize])?,
        PExpr::Int(i) => Number::Int(*i),
        PExpr::Float(f) => Number::Float(*f),
        PExpr::Un(op, x) => num::un(*op, eval(x, regs)?).ok_or(())?,
        PExpr::Bin(op, x, y) => num::bin(*op, eval(x, regs)?, eval(y, regs)?).ok_or(())?,
    })
}

/// A number as a value.
#[inline]
fn of_number(n: Number) -> Val {
    match n {
        Number::Int(i) => Val::Int(i),
        Number::Float(f) => Val::Float(f),
    }
}

/// Whether the argument `a` matches the head argument `p`, binding its
/// variables' first occurrences in `regs` (a compound's parts out of line).
#[inline]
fn head_matches(p: &PArg, a: &Val, regs: &mut [Val]) -> bool {
    match p {
        PArg::Bind(i) => {
            regs[*i as usize] = a.clone();
            true
        }
        PArg::Same(i) => ident(&regs[*i as usize], a),
        PArg::Skip => true,
        PArg::Const(k) => ident_k(a, *k),
        PArg::Struct(f, ps) => struct_matches(*f, ps, a, regs),
    }
}

/// [`head_matches`] of a compound (a list cell too).
fn struct_matches(f: Atom, ps: &[PArg], a: &Val, regs: &mut [Val]) -> bool {
    match parts(a, f, ps.len()) {
        Some(parts) => (0..ps.len()).all(|i| head_matches(&ps[i], parts.get(i), regs)),
        None => false,
    }
}

fn run_clause(c: &PClause, args: &[Val], regs: &mut [Val]) -> Outcome {
    for (p, a) in c.head.iter().zip(args) {
        if !head_matches(p, a, regs) {
            return Outcome::Fail { cut: false };
        }
    }
    let mut cut = false;
    let mut assigned = None;
    match run_goals(&c.body, regs, &mut cut, &mut assigned) {
        Err(()) => Outcome::Unsure,
        Ok(false) => Outcome::Fail { cut },
        Ok(true) => match assigned {
            Some(o) => value(o, regs).map_or(Outcome::Unsure, Outcome::Value),
            None => Outcome::NoValue,
        },
    }
}

/// `plain::run_goals` on values.
fn run_goals<'c>(
    goals: &'c [PGoal],
    regs: &mut [Val],
    cut: &mut bool,
    assigned: &mut Option<&'c Opnd>,
) -> Result<bool, ()> {
    for g in goals {
        let holds = match g {
            PGoal::True => true,
            PGoal::Fail => false,
            PGoal::Cut => {
                *cut = true;
                true
            }
            PGoal::IsFresh(i, e) => {
                regs[*i as usize] = of_number(eval(e, regs)?);
                true
            }
            PGoal::IsBound(i, e) => num::same(eval(e, regs)?, number(&regs[*i as usize])?),
            PGoal::Cmp(op, x, y) => num::compare(*op, eval(x, regs)?, eval(y, regs)?).ok_or(())?,
            PGoal::Ident(eq, x, y) => ident_oo(x, y, regs) == *eq,
            PGoal::Bind(i, o) => {
                regs[*i as usize] = value(o, regs).ok_or(())?;
                true
            }
            PGoal::Assign(o) => {
                *assigned = Some(o);
                true
            }
            PGoal::Ite(c, t, e) => {
                let (mut no_cut, mut none) = (false, None);
                let branch = if run_goals(c, regs, &mut no_cut, &mut none)? {
                    t
                } else {
                    e
                };
                run_goals(branch, regs, cut, assigned)?
            }
        };
        if !holds {
            return Ok(false);
        }
    }
    Ok(true)
}
