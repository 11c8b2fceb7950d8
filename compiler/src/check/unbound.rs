//! Prolog variables used without a value: a variable in an arc's action or
//! next situation that nothing can bind before it is used (W0228). The
//! places that can bind it, in the order a visit runs them: the DM's
//! parameters and local defaults, the situation's id, `in_arg`, the
//! `out_arg` variables that `prog` sets, the embedded DM call, the arc's
//! expectation, and, in the action and next situation, any evaluated
//! construct (`apply`, `assign`, `=`, `is`, `get`, a condition, ...) met
//! before the use. Situations and arcs are renamed apart on every visit
//! (semantics D-7, D-11), so a variable of the same name elsewhere in the
//! DM binds nothing here; the diagnostic points at it when there is one.
//! Conservative: a variable anywhere inside an evaluated construct counts
//! as bound (a user function may bind its arguments), so every error is a
//! variable that is certainly unbound when the arc runs.
//!
//! Arithmetic on such a variable is an error (E0238): the right side of
//! `is` or an operand of `<`, `>`, `=<`, `>=` (D-31, D-34) that is
//! certainly unbound, where the arc certainly evaluates it (not inside a
//! branch of a conditional that may not be taken) and the variable occurs
//! there first in the arc (an action before may be the robot's to bind):
//! both the original SitLog and the run stop there with Prolog's
//! instantiation error.

use super::*;
use sitlog_syntax::VarId;

impl Checker<'_> {
    /// W0228 for every arc of `dm`; returns the variables reported, so that
    /// the singleton warning is not given for them too.
    pub(super) fn unbound(&mut self, dm: &Dm, outputs: Outputs<'_>) -> HashSet<VarId> {
        let terms = &dm.clause.terms;
        let mut reported = HashSet::new();
        // Where each variable occurs in the DM, for "another variable" labels.
        let mut occurrences: HashMap<VarId, Vec<TermId>> = HashMap::new();
        collect_vars(terms, dm.clause.root, &mut |v, t| {
            occurrences.entry(v).or_default().push(t)
        });
        let mut dm_level = HashSet::new();
        add_vars(terms, dm.head, &mut dm_level);
        for l in &dm.locals {
            add_vars(terms, l.value, &mut dm_level);
        }
        // Each use: the variable, where, situation and arc, and the
        // variables bound in that arc (for "did you mean").
        let mut found: Vec<(VarId, TermId, usize, usize, Vec<VarId>)> = Vec::new();
        // Arithmetic on a variable without a value (E0238): the variable,
        // where, the arithmetic term, and the variables bound in the arc.
        let mut no_value: Vec<(VarId, TermId, TermId, Vec<VarId>)> = Vec::new();
        for (si, s) in dm.situations.iter().enumerate() {
            let Some(arcs) = &s.arcs else { continue };
            let mut situation = dm_level.clone();
            for t in [s.id, s.in_arg, s.embedded_dm].into_iter().flatten() {
                add_vars(terms, t, &mut situation);
            }
            if let (Some(prog), Some(out)) = (s.prog, s.out_arg) {
                // prog runs on a copy linked to the situation only through
                // in_arg and out_arg (D-10): it can bind out_arg's variables.
                let mut in_prog = HashSet::new();
                add_vars(terms, prog, &mut in_prog);
                let mut in_out = HashSet::new();
                add_vars(terms, out, &mut in_out);
                situation.extend(in_prog.intersection(&in_out).copied());
            }
            for (ai, arc) in arcs.iter().enumerate() {
                let mut bound = situation.clone();
                add_vars(terms, arc.expectation, &mut bound);
                let mut uses = Vec::new();
                let mut arith = Vec::new();
                walk(
                    terms, arc.action, true, outputs, &mut bound, &mut uses, &mut arith,
                );
                walk(
                    terms, arc.next, false, outputs, &mut bound, &mut uses, &mut arith,
                );
                if !arith.is_empty() {
                    // Only a variable whose first occurrence in the arc is
                    // this one: one written before in an action the robot
                    // may bind (a status it reports) is not certain.
                    let mut first: HashMap<VarId, u32> = HashMap::new();
                    for root in [arc.action, arc.next] {
                        collect_vars(terms, root, &mut |v, o| {
                            let at = terms.span(o).start;
                            let e = first.entry(v).or_insert(at);
                            *e = (*e).min(at);
                        });
                    }
                    for (v, t, op) in arith {
                        if first.get(&v) == Some(&terms.span(t).start) {
                            no_value.push((v, t, op, bound.iter().copied().collect()));
                        }
                    }
                }
                let mut seen = HashSet::new();
                let mut near: Option<Vec<VarId>> = None;
                for (v, t) in uses {
                    if seen.insert(v) && !dm.clause.vars[v.0 as usize].is_anonymous_style() {
                        let near = near.get_or_insert_with(|| {
                            let mut b: Vec<VarId> = bound.iter().copied().collect();
                            b.sort_by_key(|v| v.0);
                            b
                        });
                        found.push((v, t, si, ai, near.clone()));
                    }
                }
            }
        }
        self.arithmetic_without_value(dm, no_value, &mut reported);
        found.sort_by_key(|&(_, t, _, _, _)| terms.span(t));
        for (v, t, si, ai, near) in found {
            reported.insert(v);
            let s = &dm.situations[si];
            let name = dm.clause.var_name(v);
            let situation = s.id.map(|id| show(dm, id)).unwrap_or_else(|| "?".into());
            let mut places = Vec::new();
            if dm.arity > 0 {
                places.push(format!("the parameters of DM `{}`", dm.name));
            }
            if s.id.is_some_and(|id| !is_ground(terms, id)) {
                places.push(format!("the id of situation `{situation}`"));
            }
            if s.in_arg.is_some() {
                places.push("its `in_arg`".into());
            }
            if s.embedded_dm.is_some() {
                places.push("its `embedded_dm` call".into());
            }
            if s.prog.is_some() && s.out_arg.is_some() {
                places.push("the `out_arg` variables its `prog` sets".into());
            }
            places.push("this arc's expectation".into());
            places.push("the functions and actions before this use".into());
            let mut d = Diagnostic::warning(
                codes::UNBOUND_VARIABLE,
                dm.loc(terms.span(t)),
                format!("variable `{name}` has no value here: nothing binds it before it is used"),
            )
            .with_label("unbound when the arc runs");
            // A near miss of a variable that has a value here (`Drnk`).
            let similar = did_you_mean(
                name,
                near.iter()
                    .filter(|b| !dm.clause.vars[b.0 as usize].is_anonymous_style())
                    .map(|&b| dm.clause.var_name(b)),
            );
            d = d.with_help(match similar {
                Some(similar) => format!("did you mean `{similar}`?"),
                None => format!(
                    "looked for what binds `{name}` in {}; give it a value before this use (in the expectation, e.g. `said({name})`, or with `get`, `apply`, `=`), or write `_` if no value is meant",
                    join_places(&places)
                ),
            });
            // The same name outside this arc (and its out_arg copy) is
            // another variable on every visit.
            let own: Vec<Span> = [
                Some(s.arcs.as_ref().expect("arcs")[ai].span),
                s.out_arg.map(|o| terms.span(o)),
            ]
            .into_iter()
            .flatten()
            .collect();
            let elsewhere = occurrences.get(&v).and_then(|ts| {
                ts.iter()
                    .copied()
                    .filter(|&o| {
                        let sp = terms.span(o);
                        !own.iter().any(|w| w.start <= sp.start && sp.end <= w.end)
                    })
                    .min_by_key(|&o| terms.span(o))
            });
            if let Some(o) = elsewhere {
                d = d.with_secondary(
                    dm.loc(terms.span(o)),
                    format!("this `{name}` is another variable: each visit of a situation has fresh variables"),
                );
            }
            self.diags.push(d);
        }
        reported
    }
}

/// `a, b and c`.
fn join_places(places: &[String]) -> String {
    match places {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

/// Every variable occurrence under `t`, with the term where it occurs.
fn collect_vars(terms: &Terms, t: TermId, f: &mut impl FnMut(VarId, TermId)) {
    let mut stack = vec![t];
    while let Some(x) = stack.pop() {
        if let Node::Var(v) = terms.node(x) {
            f(*v, x);
        }
        stack.extend_from_slice(terms.args(x));
    }
}

fn add_vars(terms: &Terms, t: TermId, set: &mut HashSet<VarId>) {
    collect_vars(terms, t, &mut |v, _| {
        set.insert(v);
    });
}

/// Whether argument `i` of action `name/arity` is one the robot binds
/// (a status it reports): with `basic_actions.pl`, an argument the action's
/// `arity` list names `status` (or `result`, `out...`); for an action it
/// does not declare, the last of two or more arguments
/// (`navigate(Place, Status)`).
pub(super) type Outputs<'a> = &'a dyn Fn(Atom, usize, usize) -> bool;

/// Walks an action (`action`: true) or next situation in evaluation
/// order: variables inside an evaluated construct become bound, and so do
/// the status arguments of actions performed before; any other occurrence
/// of a variable not yet bound is a use without a value (`uses`, in order).
/// Arithmetic that the arc certainly evaluates (not in a branch of a
/// conditional) on a variable not yet bound goes to `arith`, with the
/// arithmetic term (E0238).
fn walk(
    terms: &Terms,
    t: TermId,
    action: bool,
    outputs: Outputs<'_>,
    bound: &mut HashSet<VarId>,
    uses: &mut Vec<(VarId, TermId)>,
    arith: &mut Vec<(VarId, TermId, TermId)>,
) {
    // Explicit stack, arguments pushed in reverse: visited left to right.
    // The flags say whether the term is performed as an action and whether
    // the arc certainly evaluates it.
    let mut stack = vec![(t, action, true)];
    while let Some((x, action, certain)) = stack.pop() {
        match terms.node(x) {
            Node::Var(v) if !bound.contains(v) => uses.push((*v, x)),
            Node::Compound { .. } => {
                let (name, arity) = terms.functor(x).expect("a compound");
                let args = terms.args(x);
                if arity == 2 && name == atoms::IF_THEN {
                    // the condition may bind; the branch is an action, run
                    // only when the condition holds
                    if certain {
                        arithmetic(terms, args[0], bound, arith);
                    }
                    add_vars(terms, args[0], bound);
                    stack.push((args[1], action, false));
                } else if arity == 2 && (name == atoms::SEMICOLON || name == atoms::BAR) {
                    // branches: the first is evaluated (a conditional's
                    // first condition, or an argument), the rest may not be
                    stack.push((args[1], action, false));
                    stack.push((args[0], action, certain));
                } else if is_evaluated(name, arity)
                    || (name != atoms::DOT
                        && !sitlog_runtime::eval::evaluates_arguments_only(name, arity))
                {
                    // (with the list operators of any arity the run
                    // evaluates, D-32: `cam2arm/6` binds its last argument)
                    if certain {
                        arithmetic(terms, x, bound, arith);
                    }
                    add_vars(terms, x, bound);
                } else if action && arity == 2 && name == atoms::DOT {
                    // elements of a list action: actions
                    stack.extend(args.iter().rev().map(|&a| (a, true, certain)));
                } else if action {
                    // a performed action: its status arguments are bound
                    // when it runs, after its arguments are evaluated
                    let mut statuses = Vec::new();
                    for (i, &a) in args.iter().enumerate() {
                        if matches!(terms.node(a), Node::Var(_)) && outputs(name, arity, i) {
                            statuses.push(a);
                        }
                    }
                    let rest = args.iter().rev().filter(|a| !statuses.contains(a));
                    stack.extend(rest.map(|&a| (a, false, certain)));
                    // (leniently bound at once: the same variable in another
                    // argument of this action counts as bound too)
                    for a in statuses {
                        add_vars(terms, a, bound);
                    }
                } else {
                    stack.extend(args.iter().rev().map(|&a| (a, false, certain)));
                }
            }
            _ => {}
        }
    }
}

/// If `t` is arithmetic (`V is E`, `A < B`, `A > B`, `A =< B`, `A >= B`),
/// the variables it needs that are not in `bound`: those of `E` (`is`
/// does arithmetic on the unevaluated term, D-31), the operands that are
/// variables (a comparison evaluates its operands first, D-34).
fn arithmetic(
    terms: &Terms,
    t: TermId,
    bound: &HashSet<VarId>,
    arith: &mut Vec<(VarId, TermId, TermId)>,
) {
    let Some((name, 2)) = terms.functor(t) else {
        return;
    };
    let args = terms.args(t);
    match name.as_str() {
        "is" => collect_vars(terms, args[1], &mut |v, o| {
            if !bound.contains(&v) {
                arith.push((v, o, t));
            }
        }),
        "<" | ">" | "=<" | ">=" => {
            for &a in args {
                if let Node::Var(v) = terms.node(a) {
                    if !bound.contains(v) {
                        arith.push((*v, a, t));
                    }
                }
            }
        }
        _ => {}
    }
}

impl Checker<'_> {
    /// E0238 for each arithmetic on a variable without a value (`no_value`,
    /// from [`walk`]); adds the variables to `reported`.
    fn arithmetic_without_value(
        &mut self,
        dm: &Dm,
        mut no_value: Vec<(VarId, TermId, TermId, Vec<VarId>)>,
        reported: &mut HashSet<VarId>,
    ) {
        let terms = &dm.clause.terms;
        no_value.sort_by_key(|&(_, t, _, _)| terms.span(t));
        let mut seen = HashSet::new();
        for (v, t, op, bound) in no_value {
            if !seen.insert((v, op)) {
                continue;
            }
            reported.insert(v);
            let name = dm.clause.var_name(v);
            let anonymous = dm.clause.vars[v.0 as usize].is_anonymous_style();
            let shown = show(dm, op);
            let mut d = Diagnostic::error(
                codes::ARITHMETIC_WITHOUT_VALUE,
                dm.loc(terms.span(t)),
                format!(
                    "arithmetic on `{name}`, which has no value here: `{shown}` stops the run (Prolog's instantiation error), as it stops the original SitLog"
                ),
            )
            .with_label("unbound when the arc runs");
            // A SitLog variable of (nearly) that name: its value is read
            // with `get`, not by naming it (`Level` for `level ==> 50`).
            let lower = name.trim_start_matches('_').to_lowercase();
            let sitlog_var = dm
                .locals
                .iter()
                .map(|l| l.name)
                .chain(self.program.globals.iter().map(|g| g.name))
                .find(|n| n.as_str() == lower);
            let near = did_you_mean(
                name,
                bound
                    .iter()
                    .filter(|b| !dm.clause.vars[b.0 as usize].is_anonymous_style())
                    .map(|&b| dm.clause.var_name(b)),
            );
            d = d.with_help(match (sitlog_var, near) {
                (Some(var), _) if !anonymous => format!(
                    "a variable is not the SitLog variable `{var}`: read its value first, `get({var}, {name})`"
                ),
                (_, Some(similar)) if !anonymous => format!("did you mean `{similar}`?"),
                _ => format!(
                    "give `{name}` a value before this use: in the expectation, with `get`, `apply` or `=`, or in an earlier `is`"
                ),
            });
            self.diags.push(d);
        }
    }
}
