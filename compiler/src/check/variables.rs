//! The checks of SitLog variables in a DM: declared before use (local,
//! global, parameter), singletons, locals shadowing globals.

use super::*;

impl<'p> Checker<'p> {
    /// `get`/`set`/`inc` name a local or global variable.
    pub(super) fn variables(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        for (i, l) in dm.locals.iter().enumerate() {
            if dm.locals[..i].iter().any(|p| p.name == l.name) {
                self.diags.push(Diagnostic::warning(
                    codes::DUPLICATE_LOCAL,
                    dm.loc(l.span),
                    format!(
                        "local variable `{}` is declared twice; the first is used",
                        l.name
                    ),
                ));
            }
        }
        let known = |name: Atom| {
            dm.locals.iter().any(|l| l.name == name)
                || self.program.globals.iter().any(|g| g.name == name)
        };
        let mut found = Vec::new();
        // For E0242: the `inc`s, the names `set` anywhere, and whether a
        // user function (which may `var_op(set(..))` the caller's locals)
        // is applied.
        let mut incs = Vec::new();
        // The names `set` anywhere, with the first value stored when every
        // `set` of the name stores a value that is never a number.
        let mut set: HashMap<Atom, Option<Option<TermId>>> = HashMap::new();
        let mut applies = false;
        for s in &dm.situations {
            let roots = [s.id, s.prog, s.in_arg, s.out_arg, s.embedded_dm, s.diag_mod];
            let mut stack: Vec<TermId> = roots.into_iter().flatten().collect();
            for arc in s.arcs.iter().flatten() {
                stack.extend([arc.expectation, arc.action, arc.next]);
            }
            while let Some(t) = stack.pop() {
                if let Some((f, 2)) = terms.functor(t) {
                    if f == atoms::GET || f == atoms::SET || f == atoms::INC {
                        if let Some(name) = terms.atom(terms.args(t)[0]) {
                            if !known(name) {
                                found.push((f, name, terms.args(t)[0], t));
                            } else if f == atoms::INC {
                                incs.push((name, terms.args(t)[0]));
                            } else if f == atoms::SET {
                                // `set` stores its value as written (D-38):
                                // a compound or an atom is never a number.
                                let v = terms.args(t)[1];
                                let number = matches!(
                                    terms.node(v),
                                    Node::Var(_) | Node::Int(_) | Node::BigInt(_) | Node::Float(_)
                                );
                                let stored = set.entry(name).or_insert(None);
                                *stored = match *stored {
                                    None if !number => Some(Some(v)),
                                    Some(Some(first)) if !number => Some(Some(first)),
                                    _ => Some(None),
                                };
                            }
                        }
                    }
                    applies |= f == atoms::APPLY;
                }
                stack.extend_from_slice(terms.args(t));
            }
        }
        found.sort_by_key(|&(_, _, t, _)| terms.span(t));
        let runs_on = data_arguments(dm);
        for (f, name, t, whole) in found {
            let mut d = if runs_on.contains(&whole) {
                Diagnostic::warning(
                    codes::UNKNOWN_VARIABLE_NESTED,
                    dm.loc(terms.span(t)),
                    format!("`{f}` of `{name}`, which is neither a local variable of DM `{}` nor a global variable: its value is unbound here (the original SitLog says the variable is not defined and runs on)", dm.name),
                )
            } else {
                Diagnostic::error(
                    codes::UNKNOWN_VARIABLE,
                    dm.loc(terms.span(t)),
                    format!("`{f}` of `{name}`, which is neither a local variable of DM `{}` nor a global variable", dm.name),
                )
            }
            .with_label("unknown SitLog variable");
            let names = dm
                .locals
                .iter()
                .map(|l| l.name.as_str())
                .chain(self.program.globals.iter().map(|g| g.name.as_str()));
            d = if let Some(similar) = did_you_mean(name.as_str(), names) {
                d.with_help(format!("did you mean `{similar}`?"))
            } else if self.program.has_globals_file {
                d.with_help(format!("declare it in the DM's local variables (`{name} ==> Value`) or in global_vars.pl"))
            } else {
                d.with_help(format!("declare it in the DM's local variables (`{name} ==> Value`) or in a global_vars.pl beside the DMs"))
            };
            self.diags.push(d);
        }
        if !applies {
            self.inc_not_a_number(dm, &incs, &set);
        }
        self.var_op_arity(dm);
    }

    /// E0250: `get`, `set` or `inc` with one argument or more than two
    /// where the functional language evaluates it (`inc(visits)` for
    /// `inc(visits, _)`). Ours would take it for a compound (an unknown
    /// action, doing nothing); the original's evaluator has no rule for it
    /// and stops (`Ilegal list of terms: inc(visits)`, then an
    /// instantiation error), wherever it is evaluated.
    fn var_op_arity(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        let mut found = Vec::new();
        walk_evaluated(dm, |t| {
            if let Some((f, n)) = terms.functor(t) {
                if n != 2 && (f == atoms::GET || f == atoms::SET || f == atoms::INC) {
                    found.push((f, n, t));
                }
            }
        });
        found.sort_by_key(|&(_, _, t)| terms.span(t));
        for (f, n, t) in found {
            let args = terms.args(t);
            let example = match (args.first(), f == atoms::SET) {
                (Some(&name), false) => format!("{f}({}, _)", show(dm, name)),
                (Some(&name), true) => format!("{f}({}, Value)", show(dm, name)),
                (None, _) => format!("{f}(Name, _)"),
            };
            self.diags.push(
                Diagnostic::error(
                    codes::VAR_OP_ARITY,
                    dm.loc(terms.span(t)),
                    format!("`{f}` with {n} argument{}: `{f}` takes a variable's name and a value, so the run stops here (the original SitLog says `Ilegal list of terms` and stops)", if n == 1 { "" } else { "s" }),
                )
                .with_label(format!("`{f}/{n}`, not `{f}/2`"))
                .with_help(format!("write `{example}`")),
            );
        }
    }

    /// E0242: `inc` of a local variable whose value is always its default,
    /// and that default is not a number (`tries ==> none`): nothing in the
    /// DM `set`s it and no user function is applied, so the `inc` stops
    /// the run wherever it is reached, as it stops the original SitLog
    /// (`the variable "tries" is not numeric`).
    ///
    /// Also (first-week program 35): `inc` of a local that every `set` of
    /// the DM gives a value that is never a number (`set(count, C + 1)`
    /// stores the term `0+1`: `set` does not evaluate), where every way
    /// from the DM's first situation to the `inc` takes an arc that `set`s
    /// it (outside a conditional's branch), whatever its default.
    fn inc_not_a_number(
        &mut self,
        dm: &Dm,
        incs: &[(Atom, TermId)],
        set: &HashMap<Atom, Option<Option<TermId>>>,
    ) {
        let terms = &dm.clause.terms;
        let mut incs = incs.to_vec();
        incs.sort_by_key(|&(_, t)| terms.span(t));
        for &(name, t) in &incs {
            let Some(local) = dm.locals.iter().find(|l| l.name == name) else {
                continue;
            };
            let default_number = matches!(
                terms.node(local.value),
                Node::Var(_) | Node::Int(_) | Node::BigInt(_) | Node::Float(_)
            );
            match set.get(&name) {
                None if !default_number => {}
                Some(Some(Some(stored))) => {
                    if default_number && !always_set_before(dm, name, t) {
                        continue;
                    }
                    let value = show(dm, *stored);
                    self.diags.push(
                        Diagnostic::error(
                            codes::INC_NOT_A_NUMBER,
                            dm.loc(terms.span(t)),
                            format!("`inc` of `{name}`, whose value here is always what a `set` stored, such as `{value}`: not a number (`set` stores its value as written, it does not evaluate it), so the run stops here (the original SitLog says the variable is not numeric and stops)"),
                        )
                        .with_label("never a number here")
                        .with_secondary(dm.loc(terms.span(*stored)), format!("`{name}` is set to the term `{value}`, not to its value"))
                        .with_help(if arithmetic(terms, *stored) {
                            format!("compute the number first (`N is {value}, set({name}, N)`), or count with `inc({name}, _)` alone")
                        } else {
                            format!("`set` it to a number before the `inc` (`set({name}, 0)`)")
                        }),
                    );
                    continue;
                }
                _ => continue,
            }
            let value = show(dm, local.value);
            self.diags.push(
                Diagnostic::error(
                    codes::INC_NOT_A_NUMBER,
                    dm.loc(terms.span(t)),
                    format!("`inc` of `{name}`, whose value is always `{value}`: not a number, so the run stops here (the original SitLog says the variable is not numeric and stops)"),
                )
                .with_label("never a number")
                .with_secondary(dm.loc(local.span), format!("`{name}` starts as `{value}`, and nothing in DM `{}` sets it", dm.name))
                .with_help(format!("start it at a number (`{name} ==> 0`), or `set` it to one before")),
            );
        }
    }

    /// Variables that occur once (Prolog's singleton warning), except those
    /// already reported as used without a value (`unbound`).
    pub(super) fn singletons(&mut self, dm: &Dm, unbound: &HashSet<sitlog_syntax::VarId>) {
        for (i, v) in dm.clause.vars.iter().enumerate() {
            if v.occurrences == 1
                && !v.is_anonymous_style()
                && !unbound.contains(&sitlog_syntax::VarId(i as u32))
            {
                self.diags.push(
                    Diagnostic::warning(
                        codes::SINGLETON,
                        dm.loc(v.first),
                        format!("singleton variable `{}`", v.name),
                    )
                    .with_label("occurs only once in this DM")
                    .with_help(format!("if that is intended, write `_{}` or `_`", v.name)),
                );
            }
        }
    }

    /// A later situation with the same ground id as an earlier one is never selected.
    pub(super) fn shadowed(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        let mut first: HashMap<String, usize> = HashMap::new();
        for (i, s) in dm.situations.iter().enumerate() {
            let Some(id) = s.id else { continue };
            if !is_ground(terms, id) {
                continue;
            }
            let earlier = match first.entry(sitlog_syntax::writeq(&dm.clause, id)) {
                std::collections::hash_map::Entry::Occupied(e) => Some(&dm.situations[*e.get()]),
                std::collections::hash_map::Entry::Vacant(e) => {
                    e.insert(i);
                    None
                }
            };
            if let Some(p) = earlier {
                self.diags.push(
                    Diagnostic::warning(
                        codes::SHADOWED,
                        dm.loc(terms.span(id)),
                        format!(
                            "situation `{}` is defined twice; the first one is always selected",
                            show(dm, id)
                        ),
                    )
                    .with_secondary(dm.loc(p.span), "first definition"),
                );
            }
        }
    }
}

/// Every way from `dm`'s first situation to the arc holding `inc` (the
/// term `inc`) takes an arc that certainly `set`s `name` (in its action,
/// not in a branch of a conditional), and the `inc`'s own arc sets nothing:
/// known only when every next situation is known from its text.
fn always_set_before(dm: &Dm, name: Atom, inc: TermId) -> bool {
    let terms = &dm.clause.terms;
    let index = super::situations::SituationIndex::new(dm);
    let inc_span = terms.span(inc);
    let inside = |t: TermId| {
        let s = terms.span(t);
        s.start <= inc_span.start && inc_span.end <= s.end
    };
    let n = dm.situations.len();
    let mut edges: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut at = None;
    for (i, s) in dm.situations.iter().enumerate() {
        if [s.prog, s.in_arg, s.out_arg, s.embedded_dm, s.diag_mod]
            .into_iter()
            .flatten()
            .any(inside)
        {
            // An `inc` outside the arcs: where it runs is not followed here.
            return false;
        }
        for arc in s.arcs.iter().flatten() {
            let Some(values) = static_values(terms, arc.next) else {
                return false;
            };
            if [arc.expectation, arc.action, arc.next]
                .into_iter()
                .any(inside)
            {
                if sets_anywhere(terms, name, arc.expectation)
                    || sets_anywhere(terms, name, arc.action)
                    || sets_anywhere(terms, name, arc.next)
                {
                    return false;
                }
                at = Some(i);
            }
            if certainly_sets(terms, name, arc.action) {
                continue;
            }
            for v in values {
                edges[i].extend(index.targets(dm, v));
            }
        }
    }
    let Some(at) = at else { return false };
    let mut reached = vec![false; n];
    let mut stack = vec![0];
    if n > 0 {
        reached[0] = true;
    }
    while let Some(i) = stack.pop() {
        if i == at {
            return false;
        }
        for &j in &edges[i] {
            if !reached[j] {
                reached[j] = true;
                stack.push(j);
            }
        }
    }
    true
}

/// `set(name, _)` anywhere in `t`.
fn sets_anywhere(terms: &Terms, name: Atom, t: TermId) -> bool {
    let mut stack = vec![t];
    while let Some(x) = stack.pop() {
        if let Some(&[n, _]) = terms.compound(x, atoms::SET, 2) {
            if terms.atom(n) == Some(name) {
                return true;
            }
        }
        stack.extend_from_slice(terms.args(x));
    }
    false
}

/// The action `t` evaluates `set(name, _)` whenever it runs: the action
/// itself, or an element of its list (not a branch of a conditional).
fn certainly_sets(terms: &Terms, name: Atom, t: TermId) -> bool {
    let mut t = t;
    loop {
        if let Some(&[n, _]) = terms.compound(t, atoms::SET, 2) {
            return terms.atom(n) == Some(name);
        }
        let Some(&[head, tail]) = terms.compound(t, atoms::DOT, 2) else {
            return false;
        };
        if terms
            .compound(head, atoms::SET, 2)
            .is_some_and(|a| terms.atom(a[0]) == Some(name))
        {
            return true;
        }
        t = tail;
    }
}

/// `t` is an arithmetic expression that `is` would evaluate (`C + 1`).
fn arithmetic(terms: &Terms, t: TermId) -> bool {
    matches!(
        terms.functor(t),
        Some((f, 1 | 2)) if matches!(f.as_str(), "+" | "-" | "*" | "/" | "//" | "mod" | "rem" | "**" | "^" | "min" | "max" | "abs")
    )
}

/// The terms of `dm`'s situations whose value is data the original passes
/// on unbound and runs on (first-week program 36): an element of a list
/// (at any depth, through lists and compounds that are no construct of the
/// functional language) inside an argument of an action
/// (`say(['Battery at', get(battery, _)])`), an argument of a next
/// situation's compound (`next(get(battery, _))`), an `out_arg`, an element
/// of a `prog`, an argument of an `embedded_dm` call, and what such a
/// place holds the same way. A `get` of an unknown variable there gives
/// the original an unbound value and it runs on (in an `embedded_dm` call
/// silently: semantics E12); as an action itself, a direct argument of one
/// (`say(get(battery, _))`: the original's `say` stops on an unbound
/// value), or in an `is`, a comparison or a condition, it stops.
fn data_arguments(dm: &Dm) -> HashSet<TermId> {
    let terms = &dm.clause.terms;
    let plain = |t: TermId| {
        terms.functor(t).is_some_and(|(name, arity)| {
            let list = name == atoms::DOT && arity == 2;
            !(list || is_evaluated(name, arity)) && conditional(terms, t).is_none()
        })
    };
    let mut out = HashSet::new();
    // (term, in action position, below a data compound, passed on unbound)
    let mut stack: Vec<(TermId, bool, bool, bool)> = Vec::new();
    for s in &dm.situations {
        for arc in s.arcs.iter().flatten() {
            stack.push((arc.action, true, false, false));
            if plain(arc.next) {
                for &a in terms.args(arc.next) {
                    stack.push((a, false, true, true));
                }
            }
        }
        // The pipe a situation passes on, and the elements of its `prog`
        // (evaluated, their values dropped): data wherever they are.
        if let Some(o) = s.out_arg {
            stack.push((o, false, true, true));
        }
        let mut prog = s.prog;
        while let Some(&[head, tail]) = prog.and_then(|p| terms.compound(p, atoms::DOT, 2)) {
            stack.push((head, false, true, true));
            prog = Some(tail);
        }
        // The arguments of an embedded DM's call (not the call itself).
        if let Some(e) = s.embedded_dm.filter(|&e| plain(e)) {
            for &a in terms.args(e) {
                stack.push((a, false, true, true));
            }
        }
    }
    while let Some((t, action, data, warn)) = stack.pop() {
        if warn {
            out.insert(t);
        }
        if action {
            if let Some((then, other)) = conditional(terms, t) {
                stack.extend([(then, true, false, false), (other, true, false, false)]);
                continue;
            }
            if let Some(&[head, tail]) = terms.compound(t, atoms::DOT, 2) {
                stack.extend([(head, true, false, false), (tail, true, false, false)]);
                continue;
            }
        }
        let Some((name, arity)) = terms.functor(t) else {
            continue;
        };
        let list = name == atoms::DOT && arity == 2;
        if !list && !plain(t) {
            continue;
        }
        let warn = warn || (list && data);
        for &a in terms.args(t) {
            stack.push((a, false, true, warn));
        }
    }
    out
}
