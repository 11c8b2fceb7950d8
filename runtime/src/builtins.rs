//! The original's built-in list operators (D-32): called as Prolog goals on
//! their *unevaluated* arguments; the value is the last argument after the
//! call. Written from their observable behaviour (`first([])` is `non`,
//! `pop([])` is `empty`, indices start at 0, ...).

use crate::eval::EvalError;
use crate::store::Store;
use crate::term::{Term, Value};
use sitlog_syntax::Atom;

fn show(store: &Store, t: Term) -> String {
    store.writeq(t)
}

fn list(store: &Store, t: Term, what: &str, call: Term) -> Result<Vec<Term>, EvalError> {
    store.list_to_vec(t).ok_or_else(|| {
        EvalError::new(format!(
            "`{}`: {what} `{}` is not a list",
            show(store, call),
            show(store, t)
        ))
    })
}

fn fails(store: &Store, call: Term) -> EvalError {
    EvalError::new(format!("`{}` fails", show(store, call)))
}

/// Evaluates `t` if its functor is one of the original's list operators.
pub fn list_operator(store: &mut Store, name: Atom, t: Term) -> Option<Result<Term, EvalError>> {
    let arity = store.args(t).len();
    if !is_list_operator(name, arity) {
        return None;
    }
    Some(run(store, name, t))
}

/// Whether `name/arity` is one of the original's list operators (D-39) or
/// its robot built-ins, which L evaluates as functions.
pub fn is_list_operator(name: Atom, arity: usize) -> bool {
    matches!(
        (name.as_str(), arity),
        ("append", 3)
            | ("reverse", 2)
            | ("length_list", 2)
            | ("first", 2)
            | ("rest", 2)
            | ("last", 2)
            | ("rotate_list", 2)
            | ("push", 3)
            | ("pop", 2)
            | ("filter_element", 3)
            | ("filter_duplicates", 3)
            | ("idx_object", 3)
            | ("get_options", 4)
            | ("get_random_element", 2)
            | ("empty_list", 1)
            | ("print_list", 1)
            | ("msg_format", 2)
            | ("statistics", 2)
            | ("cam2nav", _)
            | ("cam2arm", _)
            | ("timeOver", _)
            | ("arrived_posit", _)
    )
}

fn run(store: &mut Store, name: Atom, t: Term) -> Result<Term, EvalError> {
    let args: Vec<Term> = store.args(t).to_vec();
    let result: Term = match name.as_str() {
        "append" => {
            let mut a = list(store, args[0], "the first argument", t)?;
            let tail = store.deref(args[1]);
            if a.is_empty() {
                tail
            } else {
                let b = store.list_to_vec(tail);
                match b {
                    Some(b) => {
                        a.extend(b);
                        store.list(&a)
                    }
                    None => store.list_with_tail(&a, tail),
                }
            }
        }
        "reverse" => {
            let mut a = list(store, args[0], "the argument", t)?;
            a.reverse();
            store.list(&a)
        }
        "length_list" => {
            let a = list(store, args[0], "the argument", t)?;
            Term::int(a.len() as i64)
        }
        "first" | "rest" | "pop" => {
            let a = list(store, args[0], "the argument", t)?;
            match (name.as_str(), a.split_first()) {
                ("first", None) => Term::atom(Atom::intern("non")),
                ("pop", None) => Term::atom(Atom::intern("empty")),
                (_, None) => Term::NIL,
                ("first" | "pop", Some((h, _))) => *h,
                (_, Some((_, rest))) => store.list(rest),
            }
        }
        "last" => {
            let a = list(store, args[0], "the argument", t)?;
            *a.last().ok_or_else(|| fails(store, t))?
        }
        "rotate_list" => {
            let mut a = list(store, args[0], "the argument", t)?;
            if a.is_empty() {
                return Err(fails(store, t));
            }
            a.rotate_left(1);
            store.list(&a)
        }
        "push" => {
            let s = store.deref(args[1]);
            store.cons(args[0], s)
        }
        "filter_element" => {
            // Removes the first element that unifies with the first argument.
            let a = list(store, args[1], "the second argument", t)?;
            let mut out = Vec::with_capacity(a.len());
            let mut removed = false;
            for &x in &a {
                if !removed && store.unify(args[0], x) {
                    removed = true;
                } else {
                    out.push(x);
                }
            }
            store.list(&out)
        }
        "filter_duplicates" => {
            // filter_duplicates(List, Acc, Out): Acc (reversed) then the new elements of List.
            let a = list(store, args[0], "the first argument", t)?;
            let mut acc = list(store, args[1], "the second argument", t)?;
            acc.reverse();
            for &x in &a {
                if !acc.iter().any(|&y| store.identical(x, y)) {
                    acc.insert(0, x);
                }
            }
            acc.reverse();
            store.list(&acc)
        }
        "idx_object" => {
            let a = list(store, args[1], "the second argument", t)?;
            let i = store.int_of(args[0]).ok_or_else(|| fails(store, t))?;
            *usize::try_from(i)
                .ok()
                .and_then(|i| a.get(i))
                .ok_or_else(|| fails(store, t))?
        }
        "get_options" => {
            let found = member_unify(store, args[2], args[0]);
            Term::atom(Atom::intern(if found { "ok" } else { "no" }))
        }
        "get_random_element" => {
            let a = list(store, args[0], "the argument", t)?;
            if a.is_empty() {
                return Err(fails(store, t));
            }
            let n = Term::int(a.len() as i64);
            let r = store.compound(Atom::intern("random"), &[n]);
            let i = store
                .eval_arith(r)
                .ok()
                .and_then(|v| store.int_of(Term::from(v)))
                .unwrap_or(0);
            a[(i.max(0) as usize).min(a.len() - 1)]
        }
        "empty_list" => {
            let a = list(store, args[0], "the argument", t)?;
            if !a.is_empty() {
                return Err(fails(store, t));
            }
            args[0]
        }
        "print_list" => {
            let a = list(store, args[0], "the argument", t)?;
            for x in a {
                eprintln!("{}", store.write(x));
            }
            args[0]
        }
        "msg_format" => {
            let a = list(store, args[0], "the argument", t)?;
            let mut text = String::new();
            for (i, &x) in a.iter().enumerate() {
                let x = store.deref(x);
                let piece = match store.value(x) {
                    Value::Atom(p) if p.as_str() == "pause" => {
                        text.push_str(if i == 0 { ". " } else { " ." });
                        continue;
                    }
                    _ => store.write(x),
                };
                if !text.is_empty() && !text.ends_with(' ') {
                    text.push(' ');
                }
                text.push_str(&piece);
            }
            Term::atom(Atom::intern(&text))
        }
        "statistics" => {
            // statistics(Key, [Total, SinceLast]) in milliseconds; only the
            // wall clock is meaningful outside the robot.
            let ms = std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_millis() as i64);
            store.list(&[Term::int(ms), Term::int(0)])
        }
        other => {
            return Err(EvalError::new(format!(
                "the robot built-in `{other}` is not available in this runtime (in `{}`)",
                show(store, t)
            )))
        }
    };
    let last = *args.last().expect("list operators have arguments");
    if store.unify(last, result) {
        Ok(store.deref(last))
    } else {
        Err(fails(store, t))
    }
}

/// `member(X, L)`: unifies `x` with the first element that unifies.
pub fn member_unify(store: &mut Store, x: Term, list: Term) -> bool {
    let items = match store.list_to_vec(list) {
        Some(items) => items,
        None => return false,
    };
    items.into_iter().any(|item| store.unify(x, item))
}

/// Whether `x` is identical (`==`) to an element of `list`.
pub fn member_identical(store: &Store, x: Term, list: Term) -> bool {
    store
        .list_to_vec(list)
        .is_some_and(|items| items.into_iter().any(|item| store.identical(x, item)))
}
