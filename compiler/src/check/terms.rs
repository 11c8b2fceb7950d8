//! What the checker reads off terms without the program around them:
//! evaluated functors, conditionals, the values a next situation can take,
//! whether two terms may unify, DM calls and the actions of an arc, names
//! in text that could not be read.

use super::*;

pub(super) fn is_evaluated(name: Atom, arity: usize) -> bool {
    EVALUATED
        .iter()
        .any(|&(n, a)| a == arity && n == name.as_str())
}

/// The branches of `(C -> A ; otherwise -> B)` (also with `|`), if `t` is one:
/// exactly this shape, as the evaluator reads it (D-35).
pub(super) fn conditional(terms: &Terms, t: TermId) -> Option<(TermId, TermId)> {
    let (then, other) = if_then_else(terms, t)?;
    let other = terms.compound(other, atoms::IF_THEN, 2)?;
    (terms.atom(other[0]) == Some(atoms::OTHERWISE)).then_some((then, other[1]))
}

/// `(C -> A ; R)` (also with `|`): the then-part `A` and the else part `R`.
fn if_then_else(terms: &Terms, t: TermId) -> Option<(TermId, TermId)> {
    let args = terms
        .compound(t, atoms::SEMICOLON, 2)
        .or_else(|| terms.compound(t, atoms::BAR, 2))?;
    let then = terms.compound(args[0], atoms::IF_THEN, 2)?;
    Some((then[1], args[1]))
}

/// The terms in the evaluated parts of `dm` that are written like a
/// conditional and are not one (W0233): `(C -> A ; R)` whose else part `R`
/// is not `otherwise -> B`. With each, whether `R` is itself an
/// if-then (a chain `(C1 -> A ; C2 -> B ; ..)`).
pub(super) fn false_conditionals(dm: &Dm) -> Vec<(Span, bool)> {
    let terms = &dm.clause.terms;
    let mut out = Vec::new();
    walk_evaluated(dm, |t| {
        if let Some((_, other)) = if_then_else(terms, t) {
            if conditional(terms, t).is_none() {
                let chain = terms.compound(other, atoms::IF_THEN, 2).is_some()
                    || if_then_else(terms, other).is_some();
                out.push((terms.span(t), chain));
            }
        }
    });
    out.sort_by_key(|&(span, _)| span);
    out
}

/// The values `t` can evaluate to, when they are known without running
/// anything (variables inside are wildcards); `None` when unknown.
pub(super) fn static_values(terms: &Terms, t: TermId) -> Option<Vec<TermId>> {
    if let Some((a, b)) = conditional(terms, t) {
        let mut v = static_values(terms, a)?;
        v.extend(static_values(terms, b)?);
        return Some(v);
    }
    if matches!(terms.node(t), Node::Var(_)) {
        return None;
    }
    // Any evaluated functor anywhere inside makes the value unknown.
    let mut stack = vec![t];
    while let Some(x) = stack.pop() {
        if let Some((name, arity)) = terms.functor(x) {
            if arity > 0 && (is_evaluated(name, arity) || conditional(terms, x).is_some()) {
                return None;
            }
        }
        stack.extend_from_slice(terms.args(x));
    }
    Some(vec![t])
}

/// The calls an `embedded_dm` value can be, as far as their DM is known:
/// each branch of a conditional, and a term whose principal functor is not
/// evaluated (its arguments may be: `ask(Q, get(vocab, _))` calls
/// `ask/2`); `None` when the DM itself is computed (a variable, `get(...)`,
/// `apply(...)`).
pub(super) fn callees(terms: &Terms, t: TermId) -> Option<Vec<TermId>> {
    if let Some((a, b)) = conditional(terms, t) {
        let mut v = callees(terms, a)?;
        v.extend(callees(terms, b)?);
        return Some(v);
    }
    match terms.functor(t) {
        Some((name, arity)) if !is_evaluated(name, arity) => Some(vec![t]),
        _ => None,
    }
}

/// Whether two terms could unify, treating every variable as a wildcard.
pub(super) fn may_unify(ta: &Terms, a: TermId, tb: &Terms, b: TermId) -> bool {
    let mut stack = vec![(a, b)];
    while let Some((x, y)) = stack.pop() {
        match (ta.node(x), tb.node(y)) {
            (Node::Var(_), _) | (_, Node::Var(_)) => {}
            (
                Node::Compound {
                    functor: f,
                    arity: n,
                    ..
                },
                Node::Compound {
                    functor: g,
                    arity: m,
                    ..
                },
            ) => {
                if f != g || n != m {
                    return false;
                }
                stack.extend(ta.args(x).iter().copied().zip(tb.args(y).iter().copied()));
            }
            (Node::Int(i), Node::Float(f)) | (Node::Float(f), Node::Int(i)) => {
                let _ = (i, f);
                return false;
            }
            (p, q) => {
                if p != q {
                    return false;
                }
            }
        }
    }
    true
}

pub(super) fn is_ground(terms: &Terms, t: TermId) -> bool {
    let mut stack = vec![t];
    while let Some(x) = stack.pop() {
        if matches!(terms.node(x), Node::Var(_)) {
            return false;
        }
        stack.extend_from_slice(terms.args(x));
    }
    true
}

pub(super) fn show(dm: &Dm, t: TermId) -> String {
    let s = sitlog_syntax::writeq(&dm.clause, t);
    if s.chars().count() > 60 {
        format!("{}…", s.chars().take(59).collect::<String>())
    } else {
        s
    }
}

/// The names after `diag_mod(` in a text that could not be read as terms.
pub(super) fn dm_names_in(text: &str) -> Vec<String> {
    text.match_indices("diag_mod(")
        .filter_map(|(i, m)| {
            let rest = text[i + m.len()..].trim_start();
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            (!name.is_empty()).then_some(name)
        })
        .collect()
}

/// Functors whose arguments the functional language does not evaluate
/// (D-30..D-33, D-38: `set` stores its value as written).
pub(super) fn unevaluated_args(terms: &Terms, t: TermId) -> bool {
    match terms.functor(t) {
        Some((name, 2)) if name == atoms::SET => false,
        Some((name, arity)) => {
            let n = name.as_str();
            (arity == 2 && matches!(n, "=" | "is" | "member" | "not_member"))
                || (is_evaluated(name, arity)
                    && !matches!(
                        n,
                        "apply"
                            | "assign"
                            | "get"
                            | "inc"
                            | "when"
                            | "=="
                            | "\\=="
                            | ">"
                            | "<"
                            | ">="
                            | "=<"
                    ))
        }
        None => false,
    }
}

/// `name(X1, .., Xn)` (`name` alone for arity 0), for help texts.
pub(super) fn head_example(name: Atom, arity: usize) -> String {
    let mut f = String::new();
    sitlog_syntax::write::write_atom(&mut f, name, true);
    if arity > 0 {
        let args: Vec<String> = (1..=arity).map(|i| format!("X{i}")).collect();
        f.push_str(&format!("({})", args.join(", ")));
    }
    f
}

/// Where a function is called: `apply(F, Args)` with F's functor known.
pub(super) struct Call {
    pub(super) name: Atom,
    pub(super) arity: usize,
    pub(super) span: Span,
}

/// The `apply` calls in the evaluated parts of `dm`, in source order.
pub(super) fn calls(dm: &Dm) -> Vec<Call> {
    let terms = &dm.clause.terms;
    let mut out = Vec::new();
    walk_evaluated(dm, |t| {
        if let Some(&[f, _]) = terms.compound(t, atoms::APPLY, 2) {
            if let Some((name, arity)) = terms.functor(f) {
                out.push(Call {
                    name,
                    arity,
                    span: terms.span(t),
                });
            }
        }
    });
    out.sort_by_key(|c| c.span);
    out
}

/// Visits every term the functional language evaluates in `dm` (D-30..D-38):
/// `prog`, `out_arg`, `embedded_dm`, `diag_mod`, each arc's expectation,
/// action and next situation, and inside them every argument that is
/// evaluated (not `apply`'s function, `set`'s stored value, `=`, `is`,
/// `member`, ..).
pub(super) fn walk_evaluated(dm: &Dm, mut visit: impl FnMut(TermId)) {
    let terms = &dm.clause.terms;
    let mut stack: Vec<TermId> = Vec::new();
    for s in &dm.situations {
        // id and in_arg are patterns, not evaluated
        stack.extend(
            [s.prog, s.out_arg, s.embedded_dm, s.diag_mod]
                .into_iter()
                .flatten(),
        );
        for arc in s.arcs.iter().flatten() {
            stack.extend([arc.expectation, arc.action, arc.next]);
        }
    }
    while let Some(t) = stack.pop() {
        visit(t);
        if let Some(&[_, args]) = terms.compound(t, atoms::APPLY, 2) {
            stack.push(args);
            continue;
        }
        // `set(N, E)` stores E as written (D-38): nothing in it is evaluated.
        if terms.compound(t, atoms::SET, 2).is_some() {
            continue;
        }
        if unevaluated_args(terms, t) {
            continue;
        }
        stack.extend_from_slice(terms.args(t));
    }
}

/// The actions an arc's action term performs, as far as they are written
/// (an element of a list, either branch of a conditional): name, arity and span.
/// Terms evaluated to something unknown (`get`, `apply`, ...) and `empty`
/// are left out.
pub(super) fn actions_of(terms: &Terms, action: TermId, out: &mut Vec<(Atom, usize, Span)>) {
    let mut stack = vec![action];
    while let Some(t) = stack.pop() {
        if let Some((then, other)) = conditional(terms, t) {
            stack.extend([then, other]);
            continue;
        }
        if let Some(&[head, tail]) = terms.compound(t, atoms::DOT, 2) {
            stack.extend([head, tail]);
            continue;
        }
        let Some((name, arity)) = terms.functor(t) else {
            continue;
        };
        let text = name.as_str();
        if is_evaluated(name, arity)
            || text == "empty"
            || text == "[]"
            || !text.starts_with(|c: char| c.is_alphabetic())
        {
            continue;
        }
        out.push((name, arity, terms.span(t)));
    }
}
