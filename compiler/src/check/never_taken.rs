//! Arcs that are never taken (W0239): in a perceptual situation the
//! *last* arc whose expectation matches the input is taken (semantics
//! D-14, E2), in a recursive one the *first* whose expectation matches the
//! embedded DM's final situation (D-22). So an arc is dead when an arc that
//! wins over it has an expectation that matches everything its own
//! matches: `confirm(R, R)` before `confirm(_, _)` in a `speech`
//! situation, the catch-all written last as in a Prolog `case`. Only
//! expectations known without running anything are compared, and only a
//! winning expectation whose variables are the arc's own (a variable of
//! the situation's id, `in_arg`, `out_arg`, `prog` or the DM's head may have
//! a value when the arc is tried, which makes the expectation narrower).
//! Two expectations equal up to their variables' names (`p(X)`, `p(Y)`)
//! are not reported: that is how a program shows which arc wins.

use super::*;
use sitlog_syntax::VarId;

impl Checker<'_> {
    /// W0239 for every arc of `dm` that another arc always wins over.
    pub(super) fn never_taken(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        let mut outer = HashSet::new();
        collect(terms, dm.head, &mut outer);
        for l in &dm.locals {
            collect(terms, l.value, &mut outer);
        }
        for s in &dm.situations {
            let Some(arcs) = &s.arcs else { continue };
            let kind = s.kind(&dm.clause);
            let last_wins = match kind {
                SituationKind::Final => continue,
                SituationKind::Recursive => false,
                SituationKind::Perceptual => {
                    if s.kind_term.and_then(|t| terms.atom(t)) == Some(atoms::NEUTRAL) {
                        continue;
                    }
                    true
                }
            };
            let mut fixed = outer.clone();
            for t in [s.id, s.in_arg, s.out_arg, s.prog].into_iter().flatten() {
                collect(terms, t, &mut fixed);
            }
            let known: Vec<bool> = arcs
                .iter()
                .map(|a| static_pattern(terms, a.expectation))
                .collect();
            for (i, arc) in arcs.iter().enumerate() {
                if !known[i] {
                    continue;
                }
                // The arcs that win over arc `i` when both match.
                let winners: Vec<usize> = if last_wins {
                    (i + 1..arcs.len()).collect()
                } else {
                    (0..i).collect()
                };
                let Some(w) = winners.into_iter().find(|&j| {
                    known[j]
                        && own_variables(terms, arcs[j].expectation, &fixed)
                        && subsumes(terms, arcs[j].expectation, arc.expectation)
                        // two variants (`p(X)`, `p(Y)`) are a choice written
                        // on purpose (dms/examples/retry_choice shows E2)
                        && !subsumes(terms, arc.expectation, arcs[j].expectation)
                }) else {
                    continue;
                };
                let winner = show(dm, arcs[w].expectation);
                let (rule, help) = if last_wins {
                    (
                        "of the arcs whose expectation matches the input, the last is taken",
                        "put the more general arc before the more specific ones (the last matching arc wins, as in the original SitLog), or make the expectations exclusive",
                    )
                } else {
                    (
                        "of the exit arcs whose expectation matches the final situation, the first is taken",
                        "put the more specific exit arc first",
                    )
                };
                self.diags.push(
                    Diagnostic::warning(
                        codes::ARC_NEVER_TAKEN,
                        dm.loc(terms.span(arc.expectation)),
                        format!(
                            "this arc is never taken: the arc `{winner}` matches everything `{}` matches, and {rule}",
                            show(dm, arc.expectation)
                        ),
                    )
                    .with_label("never taken")
                    .with_secondary(
                        dm.loc(terms.span(arcs[w].expectation)),
                        "this arc is taken instead",
                    )
                    .with_help(help),
                );
            }
        }
    }
}

fn collect(terms: &Terms, t: TermId, set: &mut HashSet<VarId>) {
    let mut stack = vec![t];
    while let Some(x) = stack.pop() {
        if let Node::Var(v) = terms.node(x) {
            set.insert(*v);
        }
        stack.extend_from_slice(terms.args(x));
    }
}

/// An expectation known without running anything: no evaluated functor
/// inside, not a list (a list expectation is matched element by element in
/// the original, E3), not a bare variable shared with nothing (kept: it
/// matches every input, so it is compared like any other pattern).
fn static_pattern(terms: &Terms, t: TermId) -> bool {
    if terms.compound(t, atoms::DOT, 2).is_some() || terms.atom(t) == Some(atoms::NIL) {
        return false;
    }
    let mut stack = vec![t];
    while let Some(x) = stack.pop() {
        if let Some((name, arity)) = terms.functor(x) {
            if arity > 0
                && (is_evaluated(name, arity)
                    || !sitlog_runtime::eval::evaluates_arguments_only(name, arity))
            {
                return false;
            }
        }
        stack.extend_from_slice(terms.args(x));
    }
    true
}

/// Whether every variable of `t` is the arc's own (none in `fixed`).
fn own_variables(terms: &Terms, t: TermId, fixed: &HashSet<VarId>) -> bool {
    let mut vars = HashSet::new();
    collect(terms, t, &mut vars);
    vars.is_disjoint(fixed)
}

/// Whether `general` matches every term `specific` matches: a substitution
/// of `general`'s variables makes it `specific` (whose variables are taken
/// as they are). The two are of one DM, renamed apart by the run (D-11).
fn subsumes(terms: &Terms, general: TermId, specific: TermId) -> bool {
    let mut map: HashMap<VarId, TermId> = HashMap::new();
    let mut stack = vec![(general, specific)];
    while let Some((g, s)) = stack.pop() {
        match terms.node(g) {
            Node::Var(v) => match map.get(v) {
                Some(&earlier) => {
                    if !same(terms, earlier, s) {
                        return false;
                    }
                }
                None => {
                    map.insert(*v, s);
                }
            },
            Node::Compound { .. } => {
                if terms.functor(g) != terms.functor(s) {
                    return false;
                }
                stack.extend(
                    terms
                        .args(g)
                        .iter()
                        .copied()
                        .zip(terms.args(s).iter().copied()),
                );
            }
            other => {
                if other != terms.node(s) {
                    return false;
                }
            }
        }
    }
    true
}

/// Structural identity (a variable is only itself).
fn same(terms: &Terms, a: TermId, b: TermId) -> bool {
    let mut stack = vec![(a, b)];
    while let Some((x, y)) = stack.pop() {
        match (terms.node(x), terms.node(y)) {
            (Node::Compound { .. }, Node::Compound { .. }) => {
                if terms.functor(x) != terms.functor(y) {
                    return false;
                }
                stack.extend(
                    terms
                        .args(x)
                        .iter()
                        .copied()
                        .zip(terms.args(y).iter().copied()),
                );
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
