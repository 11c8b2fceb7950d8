//! The goals a condition may call (D-35): `true`, comparisons, unification,
//! `member`, `\+`, conjunction, disjunction, if-then-else, type tests. A
//! conditional's condition and the runtime's `when/3` are decided here, as the
//! original calls them, as Prolog goals on their evaluated arguments.
//!
//! Invariant: a goal is decided on the store alone (no variables, history or
//! functions), and a goal that fails leaves the store as it found it; a goal
//! this module does not know is an error naming it, never a silent `false`.

use crate::arith::ArithCmp;
use crate::builtins;
use crate::eval_error::{shown as show, EvalError};
use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::atoms;

/// Whether `goal` (its arguments already evaluated) holds, called as the
/// original calls a condition, a Prolog goal: the one decider of the
/// conditionals' conditions (`eval::call_goal`) and of the runtime's `when/3`.
pub fn goal_holds(store: &mut Store, goal: Term) -> Result<bool, EvalError> {
    stacker::maybe_grow(64 * 1024, 1024 * 1024, || goal_holds_inner(store, goal))
}

fn goal_holds_inner(store: &mut Store, goal: Term) -> Result<bool, EvalError> {
    let goal = store.deref(goal);
    let Some((name, arity)) = store.functor(goal) else {
        return Err(EvalError::new(format!(
            "`{}` cannot be called as a condition",
            show(store, goal)
        )));
    };
    // Every goal handled here has at most two arguments (no allocation per call).
    let mut args = [Term::NIL; 2];
    for (slot, &a) in args.iter_mut().zip(store.args(goal)) {
        *slot = a;
    }
    let text = name.as_str();
    // Type tests: one decider for terms and native values (`type_test`).
    if let Some(k) = crate::type_test::TypeTest::of(text, arity) {
        return Ok(crate::type_test::term_is(k, store, args[0]));
    }
    let holds = match (text, arity) {
        ("true", 0) | ("otherwise", 0) => true,
        ("fail", 0) | ("false", 0) => false,
        ("==", 2) => store.identical(args[0], args[1]),
        ("\\==", 2) => !store.identical(args[0], args[1]),
        // With occurs check: a cyclic term could not be copied or printed.
        ("=", 2) => {
            let mark = store.mark();
            let u = store.unify(args[0], args[1]) && store.is_acyclic(args[0]);
            if !u {
                store.undo_to(mark);
            }
            u
        }
        ("\\=", 2) => {
            let mark = store.mark();
            let u = store.unify(args[0], args[1]);
            store.undo_to(mark);
            !u
        }
        ("<" | ">" | "=<" | ">=" | "=:=" | "=\\=", 2) => {
            let cmp = ArithCmp::from_atom(name).expect("an arithmetic comparison");
            store
                .arith_compare(cmp, args[0], args[1])
                .map_err(|e| EvalError::new(format!("in `{}`: {e}", show(store, goal))))?
        }
        ("@<" | "@>" | "@=<" | "@>=", 2) => {
            let ord = store.compare(args[0], args[1]);
            match text {
                "@<" => ord.is_lt(),
                "@>" => ord.is_gt(),
                "@=<" => ord.is_le(),
                _ => ord.is_ge(),
            }
        }
        ("is", 2) => {
            let v: Term = store
                .eval_arith(args[1])
                .map_err(|e| EvalError::new(format!("in `{}`: {e}", show(store, goal))))?
                .into();
            store.unify(args[0], v)
        }
        ("member" | "memberchk", 2) => builtins::member_unify(store, args[0], args[1]),
        ("not_member", 2) => !builtins::member_identical(store, args[0], args[1]),
        ("\\+", 1) => {
            let mark = store.mark();
            let r = goal_holds(store, args[0])?;
            store.undo_to(mark);
            !r
        }
        (",", 2) => goal_holds(store, args[0])? && goal_holds(store, args[1])?,
        (";" | "|", 2) => {
            if let Some((c, a, b)) = if_then_else(store, goal) {
                if goal_holds(store, c)? {
                    goal_holds(store, a)?
                } else {
                    goal_holds(store, b)?
                }
            } else {
                let mark = store.mark();
                if goal_holds(store, args[0])? {
                    true
                } else {
                    store.undo_to(mark);
                    goal_holds(store, args[1])?
                }
            }
        }
        ("->", 2) => goal_holds(store, args[0])? && goal_holds(store, args[1])?,
        _ => {
            return Err(EvalError::new(format!(
                "`{text}/{arity}` cannot be called as a condition here (in `{}`)",
                show(store, goal)
            )))
        }
    };
    Ok(holds)
}

/// `(C -> A ; B)` as a goal.
pub(crate) fn if_then_else(store: &Store, t: Term) -> Option<(Term, Term, Term)> {
    let args = store
        .compound_args(t, atoms::SEMICOLON, 2)
        .or_else(|| store.compound_args(t, atoms::BAR, 2))?;
    let (then, other) = (args[0], args[1]);
    let then = store.compound_args(then, atoms::IF_THEN, 2)?;
    Some((then[0], then[1], other))
}
