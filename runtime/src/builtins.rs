//! The original's built-in list operators (D-32): called as Prolog goals on
//! their *unevaluated* arguments; the value is the last argument after the
//! call. Written from their observable behaviour (`first([])` is `non`,
//! `pop([])` is `empty`, indices start at 0, ...).

use crate::eval_error::EvalError;
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

pub use crate::special::is_list_operator;

fn run(store: &mut Store, name: Atom, t: Term) -> Result<Term, EvalError> {
    let args: Vec<Term> = store.args(t).to_vec();
    let arity = args.len();
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
                crate::errln!("{}", store.write(x));
            }
            args[0]
        }
        "msg_format" => {
            let a = list(store, args[0], "the argument", t)?;
            match a.as_slice() {
                [] => return Err(fails(store, t)),
                [one] => *one,
                _ => Term::atom(Atom::intern(&sentence(store, &a))),
            }
        }
        "cam2nav" if arity == 3 => cam2nav(store, &args, t)?,
        "cam2arm" if arity == 6 => cam2arm(store, &args, t)?,
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

/// A message given as a list, as the original says it (its `msg_format/2`)
/// in test mode and on its robot alike, and so what test mode shows and
/// the simulated and ROS 2 robots say (issue 40): the elements written one
/// after the other, separated by a space; `pause` is a full stop (`". "`
/// between elements); a message of three or more elements ends with `.`.
/// `[A]` is `A`; two elements get no final stop. An element is written as
/// a term (a list among them as `[a,b]`, as the original prints it).
/// Written by [`crate::sentence`] (into a caller's buffer there).
pub fn sentence(store: &Store, items: &[Term]) -> String {
    let mut out = String::new();
    crate::sentence::sentence_into(store, items, &mut out);
    out
}

/// The original's value of the constant pi in its coordinate transforms
/// (five decimals: its results depend on it).
#[allow(clippy::approx_constant)]
const PI_APPROX: f64 = 3.14159;

/// Evaluates the arithmetic expression `expr` (SWI-Prolog's arithmetic:
/// `round` gives an integer, an exact integer quotient stays an integer)
/// with the named numbers bound.
fn arith(
    store: &mut Store,
    expr: &str,
    values: &[(&str, Term)],
    call: Term,
) -> Result<Term, EvalError> {
    let (e, bindings) = store
        .parse(expr)
        .map_err(|err| EvalError::new(format!("internal formula `{expr}`: {}", err.message)))?;
    for (name, var) in bindings {
        if let Some(&(_, v)) = values.iter().find(|(n, _)| **n == *name) {
            store.unify(var, v);
        }
    }
    match store.eval_arith(e) {
        Ok(n) => Ok(Term::from(n)),
        Err(err) => Err(EvalError::new(format!("`{}`: {err:?}", show(store, call)))),
    }
}

/// The three numbers of a point `[X, Y, Z]`.
fn point(store: &Store, t: Term, what: &str, call: Term) -> Result<[Term; 3], EvalError> {
    let items = list(store, t, what, call)?;
    let ok = items.len() == 3
        && items
            .iter()
            .all(|&x| matches!(store.value(store.deref(x)), Value::Int(_) | Value::Float(_)));
    if !ok {
        return Err(EvalError::new(format!(
            "`{}`: {what} `{}` is not a point [X, Y, Z] of numbers",
            show(store, call),
            show(store, t)
        )));
    }
    Ok([items[0], items[1], items[2]])
}

/// `cam2nav([X, Y, Z], Tilt, Nav)`: a point seen by the camera as the
/// navigation's `[Angle, Distance]` from the robot's base (the camera sits
/// 0.10 to the side of the base; angle in degrees, both rounded to 4
/// decimals). `Tilt` is not used (as in the original).
fn cam2nav(store: &mut Store, args: &[Term], call: Term) -> Result<Term, EvalError> {
    let [x, _, z] = point(store, args[0], "the camera point", call)?;
    let pi = Term::float(PI_APPROX);
    let xb = arith(store, "X - 0.10", &[("X", x)], call)?;
    let v = [("XB", xb), ("ZB", z), ("PI", pi)];
    let dist = arith(
        store,
        "round(sqrt(XB * XB + ZB * ZB) * 10000) / 10000",
        &v,
        call,
    )?;
    let angle = arith(
        store,
        "round((atan(XB / ZB) * (180 / PI)) * 10000) / 10000",
        &v,
        call,
    )?;
    Ok(store.list(&[angle, dist]))
}

/// `cam2arm(Arm, RobotHeight, [X, Y, Z], Tilt, [XArm, YArm, ZArm], Polar)`:
/// a point seen by the camera as the arm's `[Height, Angle, Distance]`
/// (the platform height for the robot's height plus 0.45, the angle in
/// degrees, the left arm's 12 degrees less; rounded to 4 decimals). `Tilt`
/// is not used (as in the original). Fails for an arm other than
/// `right`/`left`.
fn cam2arm(store: &mut Store, args: &[Term], call: Term) -> Result<Term, EvalError> {
    let arm = store
        .atom_of(store.deref(args[0]))
        .map(|a| a.as_str().to_owned());
    let offset = match arm.as_deref() {
        Some("right") => "",
        Some("left") => " - 12.0",
        _ => return Err(fails(store, call)),
    };
    let [x, y, z] = point(store, args[2], "the camera point", call)?;
    let [xa, ya, za] = point(store, args[4], "the arm's position", call)?;
    let h = store.deref(args[1]);
    if !matches!(store.value(h), Value::Int(_) | Value::Float(_)) {
        return Err(EvalError::new(format!(
            "`{}`: the robot's height `{}` is not a number",
            show(store, call),
            show(store, h)
        )));
    }
    let pi = Term::float(PI_APPROX);
    let xo = arith(store, "X - XA", &[("X", x), ("XA", xa)], call)?;
    let yo = arith(store, "Y - YA", &[("Y", y), ("YA", ya)], call)?;
    let zo = arith(store, "Z - ZA", &[("Z", z), ("ZA", za)], call)?;
    let v = [("XO", xo), ("YO", yo), ("ZO", zo), ("H", h), ("PI", pi)];
    let height = arith(store, "round((H + 0.45 - YO) * 10000) / 10000", &v, call)?;
    let dist = arith(
        store,
        "round(sqrt(XO * XO + ZO * ZO) * 10000) / 10000",
        &v,
        call,
    )?;
    let angle = arith(
        store,
        &format!("round((atan(XO / ZO) * (180 / PI)) * 10000) / 10000{offset}"),
        &v,
        call,
    )?;
    Ok(store.list(&[height, angle, dist]))
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

#[cfg(test)]
mod tests {
    use super::*;

    fn op(src: &str) -> Result<String, String> {
        let mut store = Store::new();
        let (t, _) = store.parse(src).expect("parses");
        let name = store.functor(t).expect("compound").0;
        match list_operator(&mut store, name, t) {
            Some(Ok(v)) => Ok(store.writeq(v)),
            Some(Err(e)) => Err(e.message),
            None => Err("not a list operator".into()),
        }
    }

    #[test]
    fn cam2nav_camera_to_base() {
        assert_eq!(
            op("cam2nav([0.2, 2, 0.55], [-30, 0.1, -0.06], P)").unwrap(),
            "[10.3049,0.559]"
        );
        // Exact quotients stay integers, as in SWI-Prolog.
        assert_eq!(op("cam2nav([0.1, 0, 2], [0, 0, 0], P)").unwrap(), "[0,2]");
        let e = op("cam2nav([a, 0, 2], [0, 0, 0], P)").unwrap_err();
        assert!(e.contains("not a point"), "{e}");
        let e = op("cam2nav([0.1, 0, 0], [0, 0, 0], P)").unwrap_err();
        assert!(e.contains("cam2nav"), "{e}");
    }

    #[test]
    fn cam2arm_camera_to_arm() {
        assert_eq!(
            op("cam2arm(right, 1.25, [1, 2, 1], [0, 0.1, 0.1], [0, 1, 0], P)").unwrap(),
            "[0.7,45,1.4142]"
        );
        assert_eq!(
            op("cam2arm(left, 1.25, [1, 2, 1], [0, 0.1, 0.1], [0, 1, 0], P)").unwrap(),
            "[0.7,33.0,1.4142]"
        );
        assert!(
            op("cam2arm(middle, 1.25, [1, 2, 1], [0, 0, 0], [0, 1, 0], P)")
                .unwrap_err()
                .contains("fails")
        );
        // The value is the last argument: a bound one must match.
        assert!(op("cam2arm(right, 1.25, [1, 2, 1], [0, 0, 0], [0, 1, 0], [1, 2, 3])").is_err());
    }

    #[test]
    fn messages_as_sentences() {
        assert_eq!(
            op("msg_format(['what do you like best', malz, or, coke, '?'], M)").unwrap(),
            "'what do you like best malz or coke ?.'"
        );
        assert_eq!(
            op("msg_format([hello, world], M)").unwrap(),
            "'hello world'"
        );
        assert_eq!(op("msg_format([f(x)], M)").unwrap(), "f(x)");
        assert_eq!(
            op("msg_format([hi, pause, 'the ', 3, pause], M)").unwrap(),
            "'hi . the  3. .'"
        );
        assert_eq!(op("msg_format([pause, b, c], M)").unwrap(), "'. b c.'");
    }
}
