//! The checks of a DM's situations: their attributes and types, next situations
//! (resolved through a per-DM index of situation ids), embedded DMs and
//! their exits, reachability, in_args the pipe can never match (W0235);
//! and what an unreadable file may have
//! declared ([`Broken`]), so that it is not reported missing.

use super::*;

/// The situation types of the perceptual interpreters SitLog programs use
/// (the original's speech, listening, keyboard and vision; the simulated
/// robot's hands and presence), besides `neutral`, `final`, `recursive` and
/// the types `recovery_protocols.pl` names: a `type` that is none of these
/// but close to one is a typo (E0230). Any other type is left alone: a
/// robot may have perceptual interpreters of its own.
pub(super) const PERCEPTION_TYPES: &[&str] = &[
    "speech",
    "listening",
    "keyboard",
    "nkeyboard",
    "vision",
    "hands",
    "presence",
];

impl<'p> Checker<'p> {
    pub(super) fn dm(&mut self, dm: &Dm, broken: &Broken, outputs: unbound::Outputs<'_>) {
        let terms = &dm.clause.terms;
        let loc = |t: TermId| dm.loc(terms.span(t));
        // Situation structure, with a type that is a typo of a known one
        // taken as meant (its error is E0230, not a missing part).
        let kinds = self.situation_types(dm);
        for (s, &kind) in dm.situations.iter().zip(&kinds) {
            let sloc = dm.loc(s.span);
            if s.id.is_none() {
                self.diags.push(
                    Diagnostic::error(codes::MISSING_ID, sloc, "situation has no `id`")
                        .with_label("this situation")
                        .with_help("add `id ==> Name`"),
                );
            }
            if s.kind_term.is_none() {
                self.diags.push(
                    Diagnostic::error(codes::MISSING_TYPE, sloc, "situation has no `type`")
                        .with_label("this situation")
                        .with_help(
                            "add `type ==> neutral` (or `final`, `recursive`, a perception type)",
                        ),
                );
            } else if kind != SituationKind::Final && s.arcs.is_none() {
                self.diags.push(
                    Diagnostic::error(
                        codes::MISSING_ARCS,
                        sloc,
                        "a situation that is not final must have `arcs`",
                    )
                    .with_label("no `arcs` here")
                    .with_help(
                        "add `arcs ==> [Expectation : Action => Next]` or make it `type ==> final`",
                    ),
                );
            }
            if kind == SituationKind::Final {
                if let Some(span) = s.arcs_span {
                    self.diags.push(
                        Diagnostic::warning(
                            codes::FINAL_WITH_ARCS,
                            dm.loc(span),
                            "a final situation's arcs are never followed",
                        )
                        .with_label("ignored"),
                    );
                }
            }
            if kind == SituationKind::Recursive && s.embedded_dm.is_none() {
                self.diags.push(
                    Diagnostic::error(
                        codes::MISSING_EMBEDDED_DM,
                        sloc,
                        "a recursive situation must name its `embedded_dm`",
                    )
                    .with_label("no `embedded_dm` here"),
                );
            }
            for &(name, _, span) in &s.others {
                self.diags.push(
                    Diagnostic::warning(
                        codes::UNKNOWN_ATTRIBUTE,
                        dm.loc(span),
                        format!("unknown situation attribute `{name}` (kept, but SitLog does not use it)"),
                    )
                    .with_help("known attributes: id, type, arcs, prog, in_arg, out_arg, embedded_dm, diag_mod"),
                );
            }
            if let Some(d) = s.diag_mod {
                self.diag_mod_mismatch(dm, d);
            }
            if s.kind_term.and_then(|t| terms.atom(t)) == Some(atoms::NEUTRAL) {
                if let Some(arcs) = &s.arcs {
                    let ok =
                        arcs.len() == 1 && terms.atom(arcs[0].expectation) == Some(atoms::EMPTY);
                    // Certain: not one arc, or one whose expectation is
                    // never `empty` (every value known, none `empty`); a
                    // variable or a computed expectation may be.
                    let never = arcs.len() != 1
                        || static_values(terms, arcs[0].expectation).is_some_and(|vs| {
                            vs.iter().all(|&v| terms.atom(v) != Some(atoms::EMPTY))
                        });
                    if never {
                        self.diags.push(
                            Diagnostic::error(
                                codes::NEUTRAL_NEVER_PROCEEDS,
                                dm.loc(s.arcs_span.unwrap_or(s.span)),
                                format!(
                                    "a `neutral` situation proceeds only with exactly one arc whose expectation is `empty`; this one has {}",
                                    match arcs.len() {
                                        1 => "an arc whose expectation is never `empty`".to_owned(),
                                        n => format!("{n} arcs"),
                                    }
                                ),
                            )
                            .with_label("the run stops here when the situation is reached")
                            .with_help("write `arcs ==> [empty : Action => Next]`, or give the situation a perception type (`speech`, ..) to choose among arcs"),
                        );
                    } else if !ok {
                        self.diags.push(
                            Diagnostic::warning(
                                codes::NEUTRAL_SHAPE,
                                dm.loc(s.arcs_span.unwrap_or(s.span)),
                                "a `neutral` situation proceeds only with exactly one arc whose expectation is `empty`",
                            )
                            .with_help("write `arcs ==> [empty : Action => Next]`"),
                        );
                    }
                }
            }
        }
        if !kinds.contains(&SituationKind::Final) {
            self.diags.push(
                Diagnostic::error(
                    codes::NO_FINAL,
                    dm.loc(dm.span_of(dm.head)),
                    format!("DM `{}` has no final situation", dm.name),
                )
                .with_label("this DM never ends")
                .with_help("add a situation `[id ==> fs, type ==> final]`"),
            );
        }
        self.next_situations(dm);
        self.in_args_never_matched(dm);
        self.embedded(dm, broken);
        if !broken.globals {
            self.variables(dm);
        }
        let unbound = self.unbound(dm, outputs);
        self.singletons(dm, &unbound);
        self.shadowed(dm);
        self.never_taken(dm);
        let _ = loc;
    }

    /// E0230 for a `type` that names no known situation type but is close
    /// to one (`fianl`); the kind of each situation, taking such a typo as
    /// the type meant.
    fn situation_types(&mut self, dm: &Dm) -> Vec<SituationKind> {
        let terms = &dm.clause.terms;
        let mut known: Vec<&str> = [atoms::NEUTRAL, atoms::FINAL, atoms::RECURSIVE]
            .iter()
            .map(|a| a.as_str())
            .chain(PERCEPTION_TYPES.iter().copied())
            .collect();
        known.extend(
            self.program
                .recovery
                .iter()
                .map(|r| r.situation_type.as_str()),
        );
        let mut kinds = Vec::with_capacity(dm.situations.len());
        for s in &dm.situations {
            let mut kind = s.kind(&dm.clause);
            let name = s.kind_term.and_then(|t| terms.functor(t).map(|f| (t, f.0)));
            if let Some((t, name)) = name {
                if !known.contains(&name.as_str()) {
                    if let Some(similar) = did_you_mean(name.as_str(), known.iter().copied()) {
                        if similar == atoms::FINAL.as_str() {
                            kind = SituationKind::Final;
                        } else if similar == atoms::RECURSIVE.as_str() {
                            kind = SituationKind::Recursive;
                        }
                        self.diags.push(
                            Diagnostic::error(
                                codes::UNKNOWN_SITUATION_TYPE,
                                dm.loc(terms.span(t)),
                                format!("unknown situation type `{name}`"),
                            )
                            .with_label("not a situation type")
                            .with_help(format!("did you mean `{similar}`?")),
                        );
                    }
                }
            }
            kinds.push(kind);
        }
        kinds
    }

    /// Ground next situations must name a situation; unreachable situations warn.
    /// Linear in the situations of the DM: each next-situation value is
    /// looked up in an index of the ids, not compared with every id.
    pub(super) fn next_situations(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        let n = dm.situations.len();
        let index = SituationIndex::new(dm);
        let mut edges: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut everything_reachable = false;
        for (i, s) in dm.situations.iter().enumerate() {
            for arc in s.arcs.iter().flatten() {
                let Some(values) = static_values(terms, arc.next) else {
                    everything_reachable = true;
                    self.unknown_next_functor(dm, &index, arc.next);
                    continue;
                };
                for v in values {
                    // `=> empty` ends the DM, whatever its situations are
                    // called (the original's first clause for a next
                    // situation; the machine's `take_step`): no edge.
                    if terms.atom(v) == Some(atoms::EMPTY) {
                        continue;
                    }
                    let mut targets = index.targets(dm, v);
                    // No situation's id unifies with it, whatever its
                    // variables become: the arc can never go on.
                    if targets.is_empty() {
                        let shown = show(dm, v);
                        let ids: Vec<(usize, String)> = dm
                            .situations
                            .iter()
                            .enumerate()
                            .filter_map(|(j, s)| s.id.map(|id| (j, show(dm, id))))
                            .collect();
                        let similar = suggest_term(
                            terms,
                            v,
                            &shown,
                            dm,
                            dm.situations
                                .iter()
                                .enumerate()
                                .filter_map(|(j, s)| s.id.map(|id| (j, id))),
                        );
                        let help = match similar {
                            Some((j, similar)) => {
                                // Taken as meant: no follow-on "unreachable".
                                targets.push(j);
                                format!("did you mean `{similar}`?")
                            }
                            None => format!(
                                "situations of this DM: {}{}",
                                ids.iter()
                                    .take(8)
                                    .map(|(_, s)| s.clone())
                                    .collect::<Vec<_>>()
                                    .join(", "),
                                if ids.len() > 8 { ", …" } else { "" }
                            ),
                        };
                        self.diags.push(
                            Diagnostic::error(
                                codes::UNKNOWN_NEXT,
                                dm.loc(terms.span(v)),
                                format!("no situation `{shown}` in DM `{}`", dm.name),
                            )
                            .with_label("next situation not found")
                            .with_help(help),
                        );
                    }
                    edges[i].extend(targets);
                }
            }
        }
        if everything_reachable || n == 0 {
            return;
        }
        let mut reached = vec![false; n];
        let mut stack = vec![0];
        reached[0] = true;
        while let Some(i) = stack.pop() {
            for &j in &edges[i] {
                if !reached[j] {
                    reached[j] = true;
                    stack.push(j);
                }
            }
        }
        for (i, s) in dm.situations.iter().enumerate() {
            if reached[i] {
                continue;
            }
            let name = s.id.map(|id| show(dm, id)).unwrap_or_else(|| "?".into());
            let (code, msg) = if s.kind(&dm.clause) == SituationKind::Final {
                (
                    codes::FINAL_UNREACHED,
                    format!("final situation `{name}` is never reached"),
                )
            } else {
                (
                    codes::UNREACHABLE,
                    format!("situation `{name}` is unreachable"),
                )
            };
            self.diags.push(
                Diagnostic::warning(code, dm.loc(s.id.map_or(s.span, |id| dm.span_of(id))), msg)
                    .with_label("no arc leads here from the initial situation"),
            );
        }
    }

    /// E0212 for a next situation whose value is computed in part
    /// (`serch(get(x, _))`, a `(C -> A ; B)` that is not a conditional):
    /// its principal functor is not evaluated, so whatever the arguments
    /// become, no situation of the DM has that name and arity (and none
    /// has a variable id). Each branch of a conditional alike; nothing
    /// when the functor itself is computed.
    fn unknown_next_functor(&mut self, dm: &Dm, index: &SituationIndex, next: TermId) {
        let terms = &dm.clause.terms;
        if !index.var.is_empty() {
            return;
        }
        for v in callees(terms, next).into_iter().flatten() {
            let Some(f) = terms.functor(v) else { continue };
            if index.all.contains_key(&f) || f == (atoms::EMPTY, 0) {
                continue;
            }
            let shown = show(dm, v);
            let ids = || {
                dm.situations
                    .iter()
                    .enumerate()
                    .filter_map(|(j, s)| s.id.map(|id| (j, id)))
            };
            let help = match suggest_term(terms, v, &shown, dm, ids()) {
                Some((_, similar)) => format!("did you mean `{similar}`?"),
                None => format!(
                    "situations of this DM: {}",
                    ids()
                        .take(8)
                        .map(|(_, id)| show(dm, id))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            };
            let what = if f.0 == atoms::SEMICOLON || f.0 == atoms::BAR {
                " (written like a conditional, it is not one: its value is this term)"
            } else {
                ""
            };
            self.diags.push(
                Diagnostic::error(
                    codes::UNKNOWN_NEXT,
                    dm.loc(terms.span(v)),
                    format!("no situation `{}/{}` in DM `{}`{what}", f.0, f.1, dm.name),
                )
                .with_label("whatever its arguments, no situation has this name")
                .with_help(help),
            );
        }
    }

    /// W0235: an in_arg pattern that no pipe its situation can be given
    /// matches, known without running anything ([`piped_values`]): the
    /// run skips it (D-8), as the original does. Only where certain: not
    /// for the DM's first situation (the caller's pipe), nor in a DM one
    /// of whose next situations is computed (it may lead anywhere).
    pub(super) fn in_args_never_matched(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        let n = dm.situations.len();
        let index = SituationIndex::new(dm);
        // Per situation, the situations with an arc that may lead to it.
        let mut before: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (i, s) in dm.situations.iter().enumerate() {
            for arc in s.arcs.iter().flatten() {
                let Some(values) = static_values(terms, arc.next) else {
                    return;
                };
                for v in values {
                    for j in index.targets(dm, v) {
                        if !before[j].contains(&i) {
                            before[j].push(i);
                        }
                    }
                }
            }
        }
        for (j, s) in dm.situations.iter().enumerate().skip(1) {
            let Some(pattern) = s.in_arg else { continue };
            let Some(values) = piped_values(dm, &before, j) else {
                continue;
            };
            let Some(&(from, first)) = values.first() else {
                continue;
            };
            if values
                .iter()
                .any(|&(_, v)| may_unify(terms, pattern, terms, v))
            {
                continue;
            }
            let mut shown: Vec<String> = Vec::new();
            for &(_, v) in &values {
                let v = show(dm, v);
                if !shown.contains(&v) {
                    shown.push(v);
                }
            }
            let pipes = shown
                .iter()
                .map(|v| format!("`{v}`"))
                .collect::<Vec<_>>()
                .join(", ");
            let setter = dm.situations[from].id.map_or_else(String::new, |id| {
                format!(" of situation `{}`", show(dm, id))
            });
            self.diags.push(
                Diagnostic::warning(
                    codes::IN_ARG_NEVER_MATCHES,
                    dm.loc(terms.span(pattern)),
                    format!(
                        "in_arg `{}` never matches the pipe it is given ({pipes})",
                        show(dm, pattern)
                    ),
                )
                .with_label("skipped at run time, as the original skips it: its variables stay unbound, the pipe goes on unchanged")
                .with_secondary(
                    dm.loc(terms.span(first)),
                    format!("the pipe is set here, by the out_arg{setter}"),
                )
                .with_help("write the in_arg to match the pipe's shape, or remove it (`--deny-warnings` makes the skip a run-time error)"),
            );
        }
    }

    /// `embedded_dm` names a DM of the right arity, and the exit arcs name its final situations.
    pub(super) fn embedded(&mut self, dm: &Dm, broken: &Broken) {
        let terms = &dm.clause.terms;
        for s in &dm.situations {
            let Some(e) = s.embedded_dm else { continue };
            // The DMs it may call: known by their name and arity even when
            // the arguments are computed (`ask(Q, get(vocab, _))`).
            let Some(values) = callees(terms, e) else {
                continue;
            };
            let mut resolved: Vec<&'p Dm> = Vec::new();
            for v in values {
                let Some((name, arity)) = terms.functor(v) else {
                    continue;
                };
                match self.find_dm(name) {
                    // A DM file that could not be read may define it: the
                    // syntax error is the error to fix, not this name.
                    None if broken.may_define_dm(name) => {}
                    None => {
                        let mut d = Diagnostic::error(
                            codes::UNKNOWN_DM,
                            dm.loc(terms.span(v)),
                            format!("no DM named `{name}`"),
                        )
                        .with_label("embedded DM not found");
                        if let Some(file) = self.library_file_defining(name) {
                            let has_models =
                                self.program.sources.files().any(|(_, f)| {
                                    f.path.file_name().is_some_and(|n| n == "models")
                                });
                            d = d.with_help(if has_models {
                                format!("DM `{name}` is in the library's `{file}`: add `'{file}'.` to `models`")
                            } else {
                                format!("DM `{name}` is in the library's `{file}`: list the application's DM files in a `models` file, with `'{file}'.`")
                            });
                        } else if let Some(similar) = self.similar_dm(name) {
                            d = d.with_help(format!("did you mean `{similar}`?"));
                        } else if self.program.single_file {
                            d = d.with_help(
                                "a DM file checked alone sees no other DM file: check its application directory instead",
                            );
                        } else {
                            d = d.with_help("add its file to the application (or to `models`)");
                        }
                        self.diags.push(d);
                    }
                    Some(target) if target.arity != arity => {
                        self.diags.push(
                            Diagnostic::error(
                                codes::DM_ARITY,
                                dm.loc(terms.span(v)),
                                format!(
                                    "DM `{name}` takes {} argument(s), but is called with {arity}",
                                    target.arity
                                ),
                            )
                            .with_label("wrong number of arguments")
                            .with_secondary(
                                target.loc(target.span_of(target.head)),
                                "defined here",
                            ),
                        );
                    }
                    Some(target) => match head_mismatch(terms, v, target) {
                        Some(k) => self.diags.push(self.head_mismatch_error(dm, v, target, k)),
                        None => resolved.push(target),
                    },
                }
            }
            if resolved.len() != 1 {
                continue;
            }
            let target = resolved[0];
            let finals: Vec<TermId> = target
                .situations
                .iter()
                .filter(|t| t.kind(&target.clause) == SituationKind::Final)
                .filter_map(|t| t.id)
                .collect();
            // Whether every final situation has an exit arc that may take
            // it (an arc whose expectation is not known takes any): then a
            // dead exit arc is only dead code, which the original runs
            // (W0231); else the callee ending there stops the run (E0218).
            let arcs = s.arcs.iter().flatten();
            let covered = |f: TermId| {
                arcs.clone()
                    .any(|arc| match static_values(terms, arc.expectation) {
                        None => true,
                        Some(values) => values
                            .iter()
                            .any(|&v| may_unify(terms, v, &target.clause.terms, f)),
                    })
            };
            let all_covered = !finals.is_empty() && finals.iter().all(|&f| covered(f));
            for arc in s.arcs.iter().flatten() {
                let Some(values) = static_values(terms, arc.expectation) else {
                    continue;
                };
                for v in values {
                    if !finals
                        .iter()
                        .any(|&f| may_unify(terms, v, &target.clause.terms, f))
                    {
                        let names: Vec<String> = finals.iter().map(|&f| show(target, f)).collect();
                        let shown = show(dm, v);
                        let help = if names.is_empty() {
                            format!(
                                "DM `{}` has no final situation: add `[id ==> {shown}, type ==> final]` to it",
                                target.name
                            )
                        } else if let Some((_, similar)) = suggest_term(
                            terms,
                            v,
                            &shown,
                            target,
                            finals.iter().copied().enumerate(),
                        ) {
                            format!("did you mean `{similar}`?")
                        } else {
                            format!(
                                "final situations of `{}`: {}",
                                target.name,
                                names.join(", ")
                            )
                        };
                        let (code, make): (_, fn(_, _, String) -> Diagnostic) = if all_covered {
                            (codes::DEAD_EXIT, Diagnostic::warning)
                        } else {
                            (codes::UNKNOWN_EXIT, Diagnostic::error)
                        };
                        self.diags.push(
                            make(
                                code,
                                dm.loc(terms.span(v)),
                                format!(
                                    "`{shown}` is not a final situation of DM `{}`",
                                    target.name
                                ),
                            )
                            .with_label("this exit arc can never be taken")
                            .with_secondary(
                                target.loc(target.span_of(target.head)),
                                format!("DM `{}` defined here", target.name),
                            )
                            .with_help(help),
                        );
                    }
                }
            }
        }
    }
}

impl Checker<'_> {
    /// E0237: a situation's `diag_mod` that never unifies with the DM's
    /// identifier (the call, an instance of its head): every value it can
    /// take is known ([`static_values`]) and none may unify with the
    /// head, or its principal functor is known ([`callees`]) and is not
    /// the DM's name and arity. The machine stops there whenever the
    /// situation is reached (the original blocks: semantics E9).
    fn diag_mod_mismatch(&mut self, dm: &Dm, d: TermId) {
        let terms = &dm.clause.terms;
        let never = match static_values(terms, d) {
            Some(vs) => !vs.iter().any(|&v| may_unify(terms, v, terms, dm.head)),
            None => callees(terms, d).is_some_and(|cs| {
                cs.iter()
                    .all(|&c| terms.functor(c) != Some((dm.name, dm.arity)))
            }),
        };
        if !never {
            return;
        }
        let head = show(dm, dm.head);
        let help = match terms.functor(d) {
            Some((name, arity)) if (name, arity) != (dm.name, dm.arity) => format!(
                "a situation's diag_mod is unified with its DM's identifier: write `{}(..)` with {} argument(s), as the head `{head}`",
                dm.name, dm.arity
            ),
            _ => format!("a situation's diag_mod is unified with its DM's identifier: give it values that match the head `{head}`"),
        };
        self.diags.push(
            Diagnostic::error(
                codes::DIAG_MOD_MISMATCH,
                dm.loc(terms.span(d)),
                format!(
                    "diag_mod `{}` never matches DM `{}`'s identifier `{head}`",
                    show(dm, d),
                    dm.name
                ),
            )
            .with_label("the run stops here when the situation is reached")
            .with_secondary(
                dm.loc(dm.span_of(dm.head)),
                format!("DM `{}` defined here", dm.name),
            )
            .with_help(help),
        );
    }

    /// E0234: the call `v` of `dm` never matches the head of `target`
    /// (argument `k` cannot unify with the head's, [`head_mismatch`]): the
    /// machine's unification of the call with the head fails whenever the
    /// situation is entered (E13; the original crashes there too).
    fn head_mismatch_error(&self, dm: &Dm, v: TermId, target: &Dm, k: usize) -> Diagnostic {
        let terms = &dm.clause.terms;
        let arg = terms.args(v)[k];
        let head_arg = target.clause.terms.args(target.head)[k];
        let head = show(target, target.head);
        Diagnostic::error(
            codes::DM_HEAD_MISMATCH,
            dm.loc(terms.span(v)),
            format!(
                "the call `{}` never matches DM `{}`'s head `{head}`",
                show(dm, v),
                target.name
            ),
        )
        .with_label(format!(
            "argument {} `{}` cannot be `{}`",
            k + 1,
            show(dm, arg),
            show(target, head_arg)
        ))
        .with_secondary(
            target.loc(target.span_of(target.head)),
            format!("DM `{}` defined here", target.name),
        )
        .with_help(format!(
            "call it with arguments that match `{head}`, or make the head's argument {} a variable to take any value",
            k + 1
        ))
    }
}

/// The first argument of the call `v` (of `terms`) that certainly cannot
/// unify with the same argument of `target`'s head: every value the
/// argument can take is known without running anything
/// ([`static_values`]: constants, compounds, lists, each branch of a
/// conditional) and none may unify with the head's argument, itself free
/// of evaluated functors. A variable anywhere is a wildcard, and an
/// argument that is computed (`get(..)`, `apply(..)`) or a variable is
/// never certain. The arities are equal (E0217 checks them first).
fn head_mismatch(terms: &Terms, v: TermId, target: &Dm) -> Option<usize> {
    let head_terms = &target.clause.terms;
    let head_args = head_terms.args(target.head);
    let args = terms.args(v);
    if args.len() != head_args.len() {
        return None;
    }
    args.iter().zip(head_args).position(|(&a, &h)| {
        static_values(head_terms, h).is_some_and(|hv| hv == [h])
            && static_values(terms, a)
                .is_some_and(|values| values.iter().all(|&x| !may_unify(terms, x, head_terms, h)))
    })
}

/// Every value the pipe can have when situation `j` of `dm` is entered
/// from an arc (`before`: per situation, those with an arc that may lead
/// to it), each with the situation whose `out_arg` sets it: an `out_arg`'s
/// values known without running anything ([`static_values`]), through
/// situations without one (the pipe passes them unchanged). `None` when
/// one is unknown: an `out_arg` computed or a variable, a recursive
/// situation without `out_arg` (its embedded DM's pipe comes back), or the
/// DM's first situation without one (the caller's pipe).
fn piped_values(dm: &Dm, before: &[Vec<usize>], j: usize) -> Option<Vec<(usize, TermId)>> {
    let terms = &dm.clause.terms;
    let mut out = Vec::new();
    let mut seen = vec![false; dm.situations.len()];
    seen[j] = true;
    let mut stack = vec![j];
    while let Some(x) = stack.pop() {
        for &r in &before[x] {
            let s = &dm.situations[r];
            match s.out_arg {
                Some(o) => out.extend(static_values(terms, o)?.into_iter().map(|v| (r, v))),
                None if r == 0 || s.kind(&dm.clause) == SituationKind::Recursive => return None,
                None => {
                    if !seen[r] {
                        seen[r] = true;
                        stack.push(r);
                    }
                }
            }
        }
    }
    Some(out)
}

/// The candidate (its index, its text) that `v` (a term of `terms`, shown
/// as `shown`) is a typo of, among terms of `dm`: the closest by its text,
/// else one with the same arity whose name is close to `v`'s
/// (`serch(Shelves)` → `search(S)`).
fn suggest_term(
    terms: &Terms,
    v: TermId,
    shown: &str,
    dm: &Dm,
    candidates: impl Iterator<Item = (usize, TermId)>,
) -> Option<(usize, String)> {
    let candidates: Vec<(usize, TermId, String)> =
        candidates.map(|(j, t)| (j, t, show(dm, t))).collect();
    if let Some(similar) = did_you_mean(shown, candidates.iter().map(|(_, _, s)| s.as_str())) {
        let (j, _, s) = candidates.iter().find(|(_, _, s)| s == similar)?;
        return Some((*j, s.clone()));
    }
    let (name, arity) = terms.functor(v)?;
    let same_arity: Vec<(usize, Atom, &String)> = candidates
        .iter()
        .filter_map(|(j, t, s)| match dm.clause.terms.functor(*t) {
            Some((n, a)) if a == arity => Some((*j, n, s)),
            _ => None,
        })
        .collect();
    let best = did_you_mean(name.as_str(), same_arity.iter().map(|(_, n, _)| n.as_str()))?;
    let (j, _, s) = same_arity.iter().find(|(_, n, _)| n.as_str() == best)?;
    Some((*j, (*s).clone()))
}

/// The situations of a DM by id, so that finding the situations a
/// next-situation value can select costs a hash lookup, not a scan.
pub(super) struct SituationIndex {
    /// Ground ids, by their text.
    pub(super) ground: HashMap<String, Vec<usize>>,
    /// Ids with variables, by principal functor.
    pub(super) open: HashMap<(Atom, usize), Vec<usize>>,
    /// Every id, by principal functor (for values with variables).
    pub(super) all: HashMap<(Atom, usize), Vec<usize>>,
    /// Ids that are a variable: any value selects them.
    pub(super) var: Vec<usize>,
}

impl SituationIndex {
    pub(super) fn new(dm: &Dm) -> SituationIndex {
        let terms = &dm.clause.terms;
        let mut index = SituationIndex {
            ground: HashMap::new(),
            open: HashMap::new(),
            all: HashMap::new(),
            var: Vec::new(),
        };
        for (j, s) in dm.situations.iter().enumerate() {
            let Some(id) = s.id else { continue };
            let Some(key) = terms.functor(id) else {
                if matches!(terms.node(id), Node::Var(_)) {
                    index.var.push(j);
                } else {
                    // numbers and other constants: compared by text
                    index
                        .ground
                        .entry(sitlog_syntax::writeq(&dm.clause, id))
                        .or_default()
                        .push(j);
                }
                continue;
            };
            index.all.entry(key).or_default().push(j);
            if is_ground(terms, id) {
                index
                    .ground
                    .entry(sitlog_syntax::writeq(&dm.clause, id))
                    .or_default()
                    .push(j);
            } else {
                index.open.entry(key).or_default().push(j);
            }
        }
        index
    }

    /// The situations whose id may unify with `v`.
    pub(super) fn targets(&self, dm: &Dm, v: TermId) -> Vec<usize> {
        let terms = &dm.clause.terms;
        let unifies = |&j: &usize| {
            dm.situations[j]
                .id
                .is_some_and(|id| may_unify(terms, id, terms, v))
        };
        let mut out: Vec<usize> = self.var.clone();
        match terms.functor(v) {
            Some(key) if is_ground(terms, v) => {
                if let Some(js) = self.ground.get(&sitlog_syntax::writeq(&dm.clause, v)) {
                    out.extend(js);
                }
                if let Some(js) = self.open.get(&key) {
                    out.extend(js.iter().filter(|j| unifies(j)));
                }
            }
            Some(key) => {
                if let Some(js) = self.all.get(&key) {
                    out.extend(js.iter().filter(|j| unifies(j)));
                }
            }
            None => {
                if let Some(js) = self.ground.get(&sitlog_syntax::writeq(&dm.clause, v)) {
                    out.extend(js);
                }
            }
        }
        out
    }
}

/// What files that could not be read (syntax errors, not UTF-8) may have
/// declared: names they may define are not reported as unknown (the
/// reading error is the one to fix, and it is reported).
pub(super) struct Broken {
    /// A DM file failed.
    pub(super) dm_file: bool,
    /// The DM names the failed DM files seem to define (`diag_mod(name`);
    /// `None` when one of them shows none: any name may be defined there.
    pub(super) dm_names: Option<HashSet<String>>,
    pub(super) globals: bool,
    pub(super) basic_actions: bool,
    pub(super) prolog: bool,
}

impl Broken {
    pub(super) fn of(program: &Program, diags: &[Diagnostic]) -> Broken {
        let mut files: Vec<FileId> = diags
            .iter()
            .filter(|d| {
                (d.is_error()
                    && (d.code == crate::load::codes::SYNTAX
                        || d.code == crate::load::codes::NOT_UTF8))
                    || d.code == crate::load::codes::PROLOG_SYNTAX
            })
            .map(|d| d.loc.file)
            .collect();
        files.sort();
        files.dedup();
        let mut broken = Broken {
            dm_file: false,
            dm_names: Some(HashSet::new()),
            globals: false,
            basic_actions: false,
            prolog: false,
        };
        for f in files {
            let source = program.sources.get(f);
            let name = source
                .path
                .file_name()
                .and_then(|n| n.to_str())
                .unwrap_or("");
            match name {
                "global_vars.pl" => broken.globals = true,
                "basic_actions.pl" => broken.basic_actions = true,
                "host_functions.pl" => broken.prolog = true,
                "models" | "expectation_types.pl" | "recovery_protocols.pl" => {}
                _ if program.prolog_files.contains(&f) => broken.prolog = true,
                _ => {
                    broken.dm_file = true;
                    let names = dm_names_in(&source.text);
                    match (&mut broken.dm_names, names.is_empty()) {
                        (Some(known), false) => known.extend(names),
                        (known, _) => *known = None,
                    }
                }
            }
        }
        broken
    }

    pub(super) fn may_define_dm(&self, name: Atom) -> bool {
        self.dm_file
            && self
                .dm_names
                .as_ref()
                .is_none_or(|names| names.contains(name.as_str()))
    }
}
