//! The functional language L: how SitLog evaluates expectations, actions,
//! next situations, `prog`, `out_arg`, `embedded_dm` and `diag_mod`
//! (semantics notes D-28..D-39, in the original's rule order).
//!
//! Evaluation is deterministic: every construct has exactly one value or an
//! error (the original's backtracking into earlier choices is not copied).

use crate::arith::ArithCmp;
use crate::builtins;
pub use crate::eval_error::{Culprit, EvalError};
use crate::functions::{FnCall, Functions};
use crate::history::Item;
use crate::store::Store;
use crate::term::{Term, Value};
use crate::vars::Vars;
use sitlog_syntax::{atoms, Atom};
use std::sync::OnceLock;

/// The environment of an evaluation.
pub struct EvalCtx<'a> {
    pub store: &'a mut Store,
    pub locals: &'a mut Vars,
    pub globals: &'a mut Vars,
    /// The current DM's history, for functions that read it.
    pub history: &'a [Item],
    pub functions: &'a Functions,
}

impl FnCall<'_> {
    /// `var_op(Op)`: evaluates a SitLog expression (typically `get`/`set`/`inc`)
    /// against the caller's variables, keeping the updates. (A method of
    /// [`FnCall`] defined here, with the evaluator it calls, so that
    /// `functions` stays below `eval`.)
    pub fn var_op(&mut self, term: Term) -> Result<Term, String> {
        let mut ctx = EvalCtx {
            store: self.store,
            locals: self.locals,
            globals: self.globals,
            history: self.history,
            functions: self.functions,
        };
        eval(&mut ctx, term).map_err(|e| e.message)
    }
}

impl EvalError {
    /// Blames `t` (a construct of L being evaluated) unless an inner
    /// expression is already blamed.
    fn blame(mut self, store: &Store, t: Term) -> EvalError {
        if self.culprit.is_none() {
            if let Some((name, arity)) = store.functor(t) {
                if !evaluates_arguments_only(name, arity) {
                    let inner = store
                        .args(t)
                        .first()
                        .and_then(|&a| store.functor(store.deref(a)));
                    self.culprit = Some(Culprit { name, arity, inner });
                }
            }
        }
        self
    }
}

pub(crate) struct Names {
    pub apply: Atom,
    pub assign: Atom,
    pub equals: Atom,
    pub is: Atom,
    pub if_then: Atom,
    pub otherwise: Atom,
    pub comparisons: [Atom; 6],
    pub member: Atom,
    pub not_member: Atom,
}

pub(crate) fn names() -> &'static Names {
    static NAMES: OnceLock<Names> = OnceLock::new();
    NAMES.get_or_init(|| Names {
        apply: atoms::APPLY,
        assign: atoms::ASSIGN,
        equals: atoms::EQUALS,
        is: atoms::IS,
        if_then: atoms::IF_THEN,
        otherwise: atoms::OTHERWISE,
        comparisons: crate::special::COMPARISONS,
        member: atoms::MEMBER,
        not_member: atoms::NOT_MEMBER,
    })
}

fn show(store: &Store, t: Term) -> String {
    crate::eval_error::shown(store, t)
}

/// Evaluates `t` (D-28..D-39).
pub fn eval(ctx: &mut EvalCtx<'_>, t: Term) -> Result<Term, EvalError> {
    stacker::maybe_grow(64 * 1024, 1024 * 1024, || {
        eval_inner(ctx, t).map_err(|e| {
            let t = ctx.store.deref(t);
            e.blame(ctx.store, t)
        })
    })
}

fn eval_inner(ctx: &mut EvalCtx<'_>, t: Term) -> Result<Term, EvalError> {
    let t = ctx.store.deref(t);
    // A compound built from inert parts with no construct of L as its
    // functor is its own value (D-36): a list of atoms is not walked.
    if ctx.store.is_inert(t) {
        return Ok(t);
    }
    let (name, arity) = match ctx.store.value(t) {
        Value::Compound(name, args) => (name, args.len()),
        // Variables, numbers and atoms evaluate to themselves (D-28).
        _ => return Ok(t),
    };
    let n = names();
    // Lists are evaluated element by element (D-36).
    if name == atoms::DOT && arity == 2 {
        return eval_args(ctx, t);
    }
    if arity == 2 && name == n.assign {
        let [var, body] = two(ctx.store, t);
        if !ctx.store.is_var(var) {
            return Err(EvalError::new(format!(
                "assign: `{}` is not an unbound variable",
                show(ctx.store, var)
            )));
        }
        let value = eval(ctx, body)?;
        ctx.store.bind(var, value);
        return Ok(value);
    }
    if arity == 2 && name == n.equals {
        let [x, y] = two(ctx.store, t);
        let mark = ctx.store.mark();
        if !ctx.store.unify(x, y) {
            return Err(EvalError::new(format!(
                "`{}` does not unify with `{}`",
                show(ctx.store, x),
                show(ctx.store, y)
            )));
        }
        // A cyclic term could not be copied or printed: refuse to make one
        // (the original would; SitLog programs have no use for them).
        if !ctx.store.is_acyclic(x) {
            ctx.store.undo_to(mark);
            return Err(EvalError::new(format!(
                "`{} = {}` would make a cyclic term (a variable inside its own value)",
                show(ctx.store, x),
                show(ctx.store, y)
            )));
        }
        return Ok(x);
    }
    if arity == 2 && name == n.is {
        let [v, expr] = two(ctx.store, t);
        return is(ctx.store, Some(v), expr, Some(t));
    }
    if let Some(result) = builtins::list_operator(ctx.store, name, t) {
        return result;
    }
    if arity == 2 && (name == n.member || name == n.not_member) {
        let [x, list] = two(ctx.store, t);
        let found = builtins::member_unify(ctx.store, x, list);
        let holds = if name == n.member {
            found
        } else {
            !builtins::member_identical(ctx.store, x, list)
        };
        return Ok(bool_atom(holds));
    }
    if arity == 2 && n.comparisons.contains(&name) {
        let [a, b] = two(ctx.store, t);
        let a = eval(ctx, a)?;
        let b = eval(ctx, b)?;
        let holds = compare(ctx.store, name, a, b)
            .map_err(|e| EvalError::new(format!("in `{}`: {e}", show(ctx.store, t))))?;
        return Ok(bool_atom(holds));
    }
    if let Some((cond, then, other)) = conditional(ctx.store, t) {
        let cond = eval_args(ctx, cond)?;
        return if call_goal(ctx, cond)? {
            eval(ctx, then)
        } else {
            eval(ctx, other)
        };
    }
    if arity == 2 && name == n.apply {
        let [f, args] = two(ctx.store, t);
        return apply(ctx, f, args);
    }
    if arity == 2 && (name == atoms::GET || name == atoms::SET || name == atoms::INC) {
        return var_op(ctx, name, t);
    }
    eval_args(ctx, t)
}

pub use crate::special::evaluates_arguments_only;

/// `get`, `set` or `inc` (`op`) of the variable `name` with argument `arg`
/// (not evaluated), as `op(name, arg)` evaluates (D-38).
pub fn var_op_named(
    ctx: &mut EvalCtx<'_>,
    op: Atom,
    name: Atom,
    arg: Term,
) -> Result<Term, EvalError> {
    var_op_parts(ctx, op, name, Some(arg), None)
}

/// `op(name, V)` for `op` in `get`, `inc` with `V` a fresh variable: the
/// value `V` would be bound to (the same updates and errors; `V` is made only
/// for an error message).
pub fn var_op_fresh(ctx: &mut EvalCtx<'_>, op: Atom, name: Atom) -> Result<Term, EvalError> {
    debug_assert!(op == atoms::GET || op == atoms::INC);
    var_op_parts(ctx, op, name, None, None)
}

/// `V is Expr` (D-33): `Expr` evaluated arithmetically, unified with `V`;
/// the value is `V`. `whole` is the term `V is Expr` if there is one (it is
/// built only for an error message otherwise).
/// `v: None` stands for a fresh variable: the value is returned instead.
pub fn is(
    store: &mut Store,
    v: Option<Term>,
    expr: Term,
    whole: Option<Term>,
) -> Result<Term, EvalError> {
    let whole = |store: &mut Store| {
        whole.unwrap_or_else(|| {
            let v = v.unwrap_or_else(|| store.new_var());
            store.compound(atoms::IS, &[v, expr])
        })
    };
    let value: Term = match store.eval_arith(expr) {
        Ok(n) => n.into(),
        Err(e) => {
            let t = whole(store);
            return Err(EvalError::new(format!("in `{}`: {e}", show(store, t))));
        }
    };
    let Some(v) = v else { return Ok(value) };
    if !store.unify(v, value) {
        let t = whole(store);
        return Err(EvalError::new(format!(
            "`{}` fails: `{}` is not {}",
            show(store, t),
            show(store, v),
            show(store, value)
        )));
    }
    Ok(v)
}

/// The condition of a conditional, as `(C -> A ; otherwise -> B)` runs it:
/// its arguments evaluated, then called as a goal (D-35).
pub fn condition(ctx: &mut EvalCtx<'_>, cond: Term) -> Result<bool, EvalError> {
    let cond = eval_args(ctx, cond)?;
    call_goal(ctx, cond)
}

/// The condition `A op B` of a conditional when `op` is an arithmetic
/// comparison, on the already evaluated `a` and `b`: what [`condition`]
/// does on such a term, without building it (except for an error message).
pub fn arith_condition(
    store: &mut Store,
    op: ArithCmp,
    a: Term,
    b: Term,
) -> Result<bool, EvalError> {
    match store.arith_compare(op, a, b) {
        Ok(holds) => Ok(holds),
        Err(e) => {
            let goal = store.compound(op.atom(), &[a, b]);
            Err(EvalError::new(format!("in `{}`: {e}", show(store, goal))))
        }
    }
}

/// The value of the comparison `A op B` (D-34, `op` an arithmetic one) is
/// `true`: `written` are `A` and `B` as written (a variable's value not
/// evaluated), `values` their values. What evaluating the term `A op B`
/// gives (its error message and the construct it blames, `op/2`), without
/// building the term except for an error.
pub fn compare_value(
    store: &mut Store,
    op: ArithCmp,
    written: [Term; 2],
    values: [Term; 2],
) -> Result<bool, EvalError> {
    match store.arith_compare(op, values[0], values[1]) {
        Ok(holds) => Ok(holds),
        Err(e) => {
            let t = store.compound(op.atom(), &written);
            let e = EvalError::new(format!("in `{}`: {e}", show(store, t)));
            Err(e.blame(store, t))
        }
    }
}

fn bool_atom(b: bool) -> Term {
    Term::atom(if b { atoms::TRUE } else { atoms::FALSE })
}

fn two(store: &Store, t: Term) -> [Term; 2] {
    let a = store.args(t);
    [a[0], a[1]]
}

/// `(C -> A ; otherwise -> B)`, also written with `|` (E6): `(C, A, B)`.
pub fn conditional(store: &Store, t: Term) -> Option<(Term, Term, Term)> {
    let n = names();
    let (cond, then, other) = crate::goal::if_then_else(store, t)?;
    let other = store.compound_args(other, n.if_then, 2)?;
    if store.atom_of(other[0]) != Some(n.otherwise) {
        return None;
    }
    Some((cond, then, other[1]))
}

/// Evaluates the arguments of a compound left to right and rebuilds it;
/// an unchanged compound is returned as is (no allocation).
fn eval_args(ctx: &mut EvalCtx<'_>, t: Term) -> Result<Term, EvalError> {
    let (name, arity) = match ctx.store.functor(t) {
        Some((name, arity)) if arity > 0 => (name, arity),
        _ => return Ok(t),
    };
    // Long lists: iterate along the spine instead of recursing on the tail.
    if name == atoms::DOT && arity == 2 {
        return eval_list(ctx, t);
    }
    let mut values: smallvec_like::Buf = smallvec_like::Buf::new();
    let mut changed = false;
    for i in 0..arity {
        let a = ctx.store.args(t)[i];
        let v = eval(ctx, a)?;
        changed |= v != a;
        values.push(v);
    }
    if !changed {
        return Ok(t);
    }
    Ok(ctx.store.compound(name, values.as_slice()))
}

fn eval_list(ctx: &mut EvalCtx<'_>, t: Term) -> Result<Term, EvalError> {
    let mut items = Vec::new();
    let mut changed = false;
    let mut cur = t;
    loop {
        let c = ctx.store.deref(cur);
        match ctx.store.compound_args(c, atoms::DOT, 2) {
            Some(&[head, tail]) => {
                let v = eval(ctx, head)?;
                changed |= v != head;
                items.push(v);
                cur = tail;
            }
            _ => {
                let tail = eval(ctx, c)?;
                changed |= tail != c;
                if !changed {
                    return Ok(t);
                }
                return Ok(ctx.store.list_with_tail(&items, tail));
            }
        }
    }
}

/// A small inline buffer for argument values (most compounds have few args).
mod smallvec_like {
    use crate::term::Term;
    pub struct Buf {
        inline: [Term; 8],
        len: usize,
        spill: Vec<Term>,
    }
    impl Buf {
        pub fn new() -> Buf {
            Buf {
                inline: [Term::NIL; 8],
                len: 0,
                spill: Vec::new(),
            }
        }
        pub fn push(&mut self, t: Term) {
            if self.len < 8 && self.spill.is_empty() {
                self.inline[self.len] = t;
                self.len += 1;
            } else {
                if self.spill.is_empty() {
                    self.spill.extend_from_slice(&self.inline[..self.len]);
                }
                self.spill.push(t);
            }
        }
        pub fn as_slice(&self) -> &[Term] {
            if self.spill.is_empty() {
                &self.inline[..self.len]
            } else {
                &self.spill
            }
        }
    }
}

/// `get`, `set`, `inc` on the locals, then the globals (D-38).
fn var_op(ctx: &mut EvalCtx<'_>, op: Atom, t: Term) -> Result<Term, EvalError> {
    let [name_t, arg] = two(ctx.store, t);
    let Some(name) = ctx.store.atom_of(name_t) else {
        return Err(EvalError::new(format!(
            "`{}`: the variable name must be an atom",
            show(ctx.store, t)
        )));
    };
    var_op_parts(ctx, op, name, Some(arg), Some(t))
}

/// `whole` is the term `op(name, arg)` when there is one; it is built only
/// for an error message otherwise. `arg: None` stands for a fresh variable
/// (which unifies with anything: no unification is made).
fn var_op_parts(
    ctx: &mut EvalCtx<'_>,
    op: Atom,
    name: Atom,
    arg: Option<Term>,
    whole: Option<Term>,
) -> Result<Term, EvalError> {
    let whole = |store: &mut Store| {
        whole.unwrap_or_else(|| {
            let arg = arg.unwrap_or_else(|| store.new_var());
            store.compound(op, &[Term::atom(name), arg])
        })
    };
    let in_locals = ctx.locals.contains(name);
    let current = if in_locals {
        ctx.locals.get(name)
    } else {
        ctx.globals.get(name)
    };
    let Some(current) = current else {
        // The original prints `Error: Variable "name" is not defined.`, then
        // `Press Ctrl. C and abort` and reads a term, and goes on with the
        // value unbound (its `arg` left as it was): so do we, noting it for
        // a warning (the machine's `Outcome::warnings`). Where that value is
        // performed as an action, the run stops as the original does
        // (`machine::io::perform_one`).
        ctx.store.note_undefined(op, name);
        return Ok(ctx.store.new_var());
    };
    let new = if op == atoms::GET {
        if let Some(arg) = arg.filter(|&arg| !ctx.store.unify(arg, current)) {
            return Err(EvalError::new(format!(
                "`{}`: the value `{}` does not unify with `{}`",
                {
                    let t = whole(ctx.store);
                    show(ctx.store, t)
                },
                show(ctx.store, current),
                show(ctx.store, arg)
            )));
        }
        return Ok(current);
    } else if op == atoms::SET {
        // The second argument is stored as written, not evaluated (D-38).
        let arg = arg.unwrap_or_else(|| ctx.store.new_var());
        ctx.store.deref(arg)
    } else {
        let cur = ctx.store.deref(current);
        let next = match ctx.store.value(cur) {
            Value::Int(i) => match i.checked_add(1) {
                Some(n) => Term::int(n),
                None => {
                    return Err(EvalError::new(format!(
                        "`inc` of `{name}`: integer overflow"
                    )))
                }
            },
            Value::Float(f) => Term::float(f + 1.0),
            _ => {
                return Err(EvalError::new(format!(
                    "`inc` of `{name}`: its value `{}` is not a number",
                    show(ctx.store, cur)
                )))
            }
        };
        if let Some(arg) = arg.filter(|&arg| !ctx.store.unify(arg, next)) {
            return Err(EvalError::new(format!(
                "`{}`: the new value `{}` does not unify with `{}`",
                {
                    let t = whole(ctx.store);
                    show(ctx.store, t)
                },
                show(ctx.store, next),
                show(ctx.store, arg)
            )));
        }
        next
    };
    if in_locals {
        ctx.locals.set(name, new);
    } else {
        ctx.globals.set(name, new);
    }
    Ok(new)
}

/// `apply(F, Args)` (D-37): evaluates Args, calls the user function named by F.
fn apply(ctx: &mut EvalCtx<'_>, f: Term, args: Term) -> Result<Term, EvalError> {
    let values = eval(ctx, args)?;
    let Some(values) = ctx.store.list_to_vec(values) else {
        return Err(EvalError::new(format!(
            "apply: the arguments `{}` are not a list",
            show(ctx.store, values)
        )));
    };
    let f = ctx.store.deref(f);
    let Some((name, arity)) = ctx.store.functor(f) else {
        return Err(EvalError::new(format!(
            "apply: `{}` does not name a function",
            show(ctx.store, f)
        )));
    };
    // Each argument of F that is a variable takes the next value, positionally;
    // other arguments are passed as written (the caller's variables stay unbound).
    // With more or fewer values than arguments none is bound: the original
    // binds them only when the counts agree, else prints `Ilegal list of
    // terms` and calls the function with its arguments unbound (W0251).
    let counts_agree = values.len() == arity;
    let declared: Vec<Term> = ctx.store.args(f).to_vec();
    let mut call_args = Vec::with_capacity(arity);
    for (i, &a) in declared.iter().enumerate() {
        let a = ctx.store.deref(a);
        call_args.push(if ctx.store.is_var(a) {
            match values.get(i) {
                Some(&v) if counts_agree => v,
                _ => ctx.store.new_var(),
            }
        } else {
            a
        });
    }
    let unbound = |e: String| {
        if counts_agree {
            e
        } else {
            format!(
                "{e} (called with its arguments unbound: {} value(s) for {arity} argument(s), which the original SitLog does not bind either)",
                values.len()
            )
        }
    };
    let mut call = FnCall {
        store: ctx.store,
        locals: ctx.locals,
        globals: ctx.globals,
        history: ctx.history,
        functions: ctx.functions,
    };
    match ctx.functions.call(&mut call, name, &call_args) {
        Some(Ok(v)) => Ok(v),
        Some(Err(e)) => Err(EvalError::new(unbound(format!(
            "user function `{name}/{arity}` failed: {e}"
        )))),
        None => Err(EvalError::new(format!(
            "no user function `{name}/{arity}` (called as `{}`)",
            show(ctx.store, f)
        ))),
    }
}

/// `==, \==, >, <, >=, =<` on evaluated arguments (D-34).
fn compare(store: &mut Store, op: Atom, a: Term, b: Term) -> Result<bool, String> {
    if op == atoms::EQ_EQ {
        return Ok(store.identical(a, b));
    }
    if op == atoms::NOT_EQ_EQ {
        return Ok(!store.identical(a, b));
    }
    let cmp = ArithCmp::from_atom(op).ok_or_else(|| format!("`{op}` is not a comparison"))?;
    store.arith_compare(cmp, a, b).map_err(|e| e.to_string())
}

/// Runs `goal` as a Prolog condition (the `C` of a conditional, D-35).
pub fn call_goal(ctx: &mut EvalCtx<'_>, goal: Term) -> Result<bool, EvalError> {
    crate::goal::goal_holds(ctx.store, goal)
}
