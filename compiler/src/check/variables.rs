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
        let mut set = HashSet::new();
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
                                found.push((f, name, terms.args(t)[0]));
                            } else if f == atoms::INC {
                                incs.push((name, terms.args(t)[0]));
                            } else if f == atoms::SET {
                                set.insert(name);
                            }
                        }
                    }
                    applies |= f == atoms::APPLY;
                }
                stack.extend_from_slice(terms.args(t));
            }
        }
        found.sort_by_key(|&(_, _, t)| terms.span(t));
        for (f, name, t) in found {
            let mut d = Diagnostic::error(
                codes::UNKNOWN_VARIABLE,
                dm.loc(terms.span(t)),
                format!("`{f}` of `{name}`, which is neither a local variable of DM `{}` nor a global variable", dm.name),
            )
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
    fn inc_not_a_number(&mut self, dm: &Dm, incs: &[(Atom, TermId)], set: &HashSet<Atom>) {
        let terms = &dm.clause.terms;
        let mut incs = incs.to_vec();
        incs.sort_by_key(|&(_, t)| terms.span(t));
        for &(name, t) in &incs {
            let Some(local) = dm.locals.iter().find(|l| l.name == name) else {
                continue;
            };
            if set.contains(&name)
                || matches!(
                    terms.node(local.value),
                    Node::Var(_) | Node::Int(_) | Node::BigInt(_) | Node::Float(_)
                )
            {
                continue;
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
