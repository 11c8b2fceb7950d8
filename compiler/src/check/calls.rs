//! What a program calls outside its DMs: user functions (`apply`) against
//! the standard ones, the Prolog files' clause heads, KB services and the
//! host's functions; basic actions and their arities against
//! `basic_actions.pl`; and, among the expressions it evaluates, those
//! written like a conditional that are not one (W0233).

use super::*;

impl Checker<'_> {
    /// W0251: `apply(F, [V1, .., Vm])` whose list of values (written as a
    /// list) is longer or shorter than `F`'s arguments. The original binds
    /// values to arguments only when the counts agree; otherwise it prints
    /// `Ilegal list of terms`, waits for a line of input (`Press Ctrl. C
    /// and abort`) and calls the function with every argument unbound
    /// (observed: `apply(double(_X), [2, 3])` then stops on `is/2`, a
    /// function that does not use its argument returns its value). The run
    /// does the same (`eval::apply`): a warning, the function decides.
    pub(super) fn apply_value_counts(&mut self) {
        for dm in &self.program.dms {
            let terms = &dm.clause.terms;
            let mut found = Vec::new();
            walk_evaluated(dm, |t| {
                let Some(&[f, values]) = terms.compound(t, atoms::APPLY, 2) else {
                    return;
                };
                let Some((name, arity)) =
                    terms.functor(f).or_else(|| terms.atom(f).map(|a| (a, 0)))
                else {
                    return;
                };
                let Some(values) = terms.proper_list(values) else {
                    return;
                };
                if values.len() != arity {
                    found.push((t, f, name, arity, values.len()));
                }
            });
            found.sort_by_key(|&(t, ..)| terms.span(t));
            for (t, f, name, arity, n) in found {
                let plural =
                    |k: usize, w: &str| format!("{k} {w}{}", if k == 1 { "" } else { "s" });
                self.diags.push(
                    Diagnostic::warning(
                        codes::APPLY_VALUE_COUNT,
                        dm.loc(terms.span(t)),
                        format!(
                            "`apply` of `{name}/{arity}` with {}: the values are bound to the arguments only when there are as many, so `{}` is called with every argument unbound (the original SitLog prints `Ilegal list of terms` and does the same)",
                            plural(n, "value"),
                            show(dm, f),
                        ),
                    )
                    .with_label(format!("{} for {}", plural(n, "value"), plural(arity, "argument")))
                    .with_help(format!("give one value per argument: `apply({}, [..])` takes {}", show(dm, f), plural(arity, "value"))),
                );
            }
        }
    }

    /// Every `apply(f(..), Args)` names a function the run will have: a
    /// standard one, a clause head of the application's Prolog files, a KB
    /// service when the KB is in use, or one the host registers.
    pub(super) fn functions(&mut self) {
        let program = self.program;
        let mut known: HashSet<(Atom, usize)> =
            sitlog_runtime::Functions::standard().names().collect();
        known.extend(program.functions.iter().map(|f| (f.name, f.arity)));
        known.extend(program.host_functions.iter().copied());
        known.extend(
            self.options
                .host_functions
                .iter()
                .map(|&(n, a)| (Atom::intern(n), a)),
        );
        let kb: HashSet<(Atom, usize)> = sitlog_kb::SERVICES
            .iter()
            .map(|s| (Atom::intern(s.name), s.arity - 1))
            .chain(
                sitlog_kb::UPDATES
                    .iter()
                    .map(|u| (Atom::intern(u.name), u.arity)),
            )
            .collect();
        let world: HashSet<(Atom, usize)> = self
            .options
            .world_functions
            .iter()
            .map(|&(n, a)| (Atom::intern(n), a))
            .collect();
        let kb_in_use = self.options.kb.unwrap_or(program.has_kb_file);
        let on_world = self.options.world.unwrap_or(program.has_world_file);
        if kb_in_use {
            known.extend(kb.iter().copied());
        }
        if on_world {
            known.extend(world.iter().copied());
        }
        for dm in &program.dms {
            for call in calls(dm) {
                let key = (call.name, call.arity);
                if known.contains(&key) {
                    continue;
                }
                let loc = dm.loc(call.span);
                let sig = format!("{}/{}", call.name, call.arity);
                if kb.contains(&key) {
                    self.diags.push(
                        Diagnostic::warning(
                            codes::KB_SERVICE_WITHOUT_KB,
                            loc,
                            format!(
                                "`{sig}` is a KB service, but the application has no knowledge.kb"
                            ),
                        )
                        .with_label("needs a knowledge base")
                        .with_help("add a knowledge.kb beside the DMs, or run with `--kb FILE`"),
                    );
                    continue;
                }
                if world.contains(&key) {
                    self.diags.push(
                        Diagnostic::warning(
                            codes::WORLD_FUNCTION_WITHOUT_WORLD,
                            loc,
                            format!("`{sig}` is a function of the simulated robot, but the application has no world.toml"),
                        )
                        .with_label("needs a world")
                        .with_help("add a world.toml beside the DMs, or run with `--world FILE`"),
                    );
                    continue;
                }
                let same_name: Vec<usize> = known
                    .iter()
                    .chain(kb.iter())
                    .chain(world.iter())
                    .filter(|(n, _)| *n == call.name)
                    .map(|&(_, a)| a)
                    .collect();
                let mut d =
                    Diagnostic::error(codes::UNKNOWN_FUNCTION, loc, format!("no function `{sig}`"))
                        .with_label("unknown function");
                let names: Vec<(Atom, usize)> = known
                    .iter()
                    .chain(kb.iter())
                    .chain(world.iter())
                    .copied()
                    .collect();
                let mut texts: Vec<&str> = names.iter().map(|(n, _)| n.as_str()).collect();
                texts.sort_unstable();
                texts.dedup();
                let help = if let Some(mut arities) = (!same_name.is_empty()).then_some(same_name) {
                    arities.sort_unstable();
                    arities.dedup();
                    let list: Vec<String> = arities
                        .iter()
                        .map(|a| format!("`{}/{a}`", call.name))
                        .collect();
                    format!(
                        "`{}` exists with {} argument(s): {}",
                        call.name,
                        arities
                            .iter()
                            .map(usize::to_string)
                            .collect::<Vec<_>>()
                            .join(" or "),
                        list.join(", ")
                    )
                } else if let Some(similar) = did_you_mean(call.name.as_str(), texts) {
                    format!("did you mean `{similar}`?")
                } else if program.prolog_files.is_empty() {
                    format!(
                        "define it in a user_functions.pl beside the DMs: `{} :- ..., assign_func_value(Value).` (a function registered in Rust by the host is declared in host_functions.pl: `{sig}.`)",
                        head_example(call.name, call.arity)
                    )
                } else {
                    format!(
                        "define it in user_functions.pl: `{} :- ..., assign_func_value(Value).` (a function registered in Rust by the host is declared in host_functions.pl: `{sig}.`)",
                        head_example(call.name, call.arity)
                    )
                };
                d = d.with_help(help);
                if let Some((file, at)) = program.unread_consults.first() {
                    // It may be defined in a file the checker cannot read.
                    d.severity = Severity::Warning;
                    d = d.with_secondary(
                        *at,
                        format!("`{file}` is not read by the checker: it may define `{sig}`"),
                    );
                }
                self.diags.push(d);
            }
        }
    }

    /// The argument names of each action `basic_actions.pl` declares
    /// (`arity ==> [place, status]`); `None` where no such list is given.
    /// W0233: a term written like a conditional that is not one (D-35).
    /// The original evaluates it to a compound term like any other, so it
    /// runs; a next situation or an action made of it is then wrong.
    pub(super) fn false_conditionals(&mut self) {
        for dm in &self.program.dms {
            for (span, chain) in false_conditionals(dm) {
                let help = if chain {
                    "nest the chain: `(C1 -> A ; otherwise -> (C2 -> B ; otherwise -> D))`"
                } else {
                    "write the else part as `otherwise -> B`: `(C -> A ; otherwise -> B)`"
                };
                self.diags.push(
                    Diagnostic::warning(
                        codes::NOT_A_CONDITIONAL,
                        dm.loc(span),
                        "not a conditional: only `(C -> A ; otherwise -> B)` is one, this evaluates to the term as written",
                    )
                    .with_label("its else part is not `otherwise -> ..`")
                    .with_help(help),
                );
            }
        }
    }

    pub(super) fn declared_actions(&self) -> HashMap<Atom, Option<Vec<Atom>>> {
        let arrow = Atom::intern("==>");
        let arity = Atom::intern("arity");
        let mut out = HashMap::new();
        for b in &self.program.basic_actions {
            let terms = &b.clause.terms;
            let names = terms
                .proper_list(b.clause.root)
                .into_iter()
                .flatten()
                .filter_map(|item| terms.compound(item, arrow, 2))
                .find(|pair| terms.atom(pair[0]) == Some(arity))
                .and_then(|pair| terms.proper_list(pair[1]))
                .map(|items| {
                    items
                        .iter()
                        .map(|&i| terms.atom(i).unwrap_or(atoms::EMPTY))
                        .collect()
                });
            out.entry(b.name).or_insert(names);
        }
        out
    }

    /// With a `basic_actions.pl`, every action an arc performs is declared
    /// there (the original ignores the others silently: a typo does
    /// nothing), with as many arguments as its `arity` list names.
    pub(super) fn actions(&mut self) {
        let program = self.program;
        let declared = self.declared_actions();
        for dm in &program.dms {
            let terms = &dm.clause.terms;
            let mut found = Vec::new();
            for s in &dm.situations {
                for arc in s.arcs.iter().flatten() {
                    actions_of(terms, arc.action, &mut found);
                }
            }
            found.sort_by_key(|&(_, _, span)| span);
            for (name, arity, span) in found {
                match declared.get(&name) {
                    Some(Some(names)) if names.len() != arity => {
                        let decl = program
                            .basic_actions
                            .iter()
                            .find(|b| b.name == name)
                            .expect("declared");
                        let shown: Vec<&str> = names.iter().map(|n| n.as_str()).collect();
                        self.diags.push(
                            Diagnostic::warning(
                                codes::ACTION_ARITY,
                                dm.loc(span),
                                format!(
                                    "action `{name}` takes {} argument(s) ({}), but is given {arity}",
                                    names.len(),
                                    shown.join(", ")
                                ),
                            )
                            .with_label("wrong number of arguments")
                            .with_secondary(decl.loc, "declared here")
                            .with_help(if names.len() == 1 && arity > 1 {
                                format!("to give several parts, pass one list: `{name}([...])`")
                            } else {
                                format!("write `{}`", head_example(name, names.len()))
                            }),
                        );
                        continue;
                    }
                    Some(_) => continue,
                    None => {}
                }
                let help = match did_you_mean(
                    name.as_str(),
                    program.basic_actions.iter().map(|b| b.name.as_str()),
                ) {
                    Some(similar) => format!("did you mean `{similar}`?"),
                    None => format!(
                        "declare it in basic_actions.pl: `[id ==> {name}, arity ==> [...], mod ==> ..., break ==> no].`"
                    ),
                };
                self.diags.push(
                    Diagnostic::warning(
                        codes::UNKNOWN_ACTION,
                        dm.loc(span),
                        format!("action `{name}` is not declared in basic_actions.pl"),
                    )
                    .with_label("unknown action")
                    .with_help(help),
                );
            }
        }
    }
}
