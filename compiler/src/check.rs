//! The checker: names, arities, situation structure, reachability and
//! variables. It collects every diagnostic and never runs anything. A
//! program without errors becomes a [`Checked`] program: later stages accept
//! only that type, so an unchecked program cannot reach them.

use crate::ast::{Dm, Program, SituationKind};
use crate::diag::{Diagnostic, Loc};
use sitlog_syntax::{atoms, Atom, Node, TermId, Terms};
use std::collections::HashMap;

/// Diagnostic codes of the checker.
pub mod codes {
    pub const DUPLICATE_DM: &str = "E0201";
    pub const SAME_NAME_OTHER_ARITY: &str = "W0202";
    pub const DUPLICATE_DM_IDENTICAL: &str = "W0203";
    pub const MISSING_ID: &str = "E0204";
    pub const MISSING_TYPE: &str = "E0205";
    pub const MISSING_ARCS: &str = "E0206";
    pub const FINAL_WITH_ARCS: &str = "W0207";
    pub const MISSING_EMBEDDED_DM: &str = "E0208";
    pub const UNKNOWN_ATTRIBUTE: &str = "W0209";
    pub const NEUTRAL_SHAPE: &str = "W0210";
    pub const NO_FINAL: &str = "E0211";
    pub const UNKNOWN_NEXT: &str = "E0212";
    pub const UNREACHABLE: &str = "W0213";
    pub const FINAL_UNREACHED: &str = "W0214";
    pub const SHADOWED: &str = "W0215";
    pub const UNKNOWN_DM: &str = "E0216";
    pub const DM_ARITY: &str = "E0217";
    pub const UNKNOWN_EXIT: &str = "E0218";
    pub const UNKNOWN_VARIABLE: &str = "E0219";
    pub const SINGLETON: &str = "W0220";
    pub const DUPLICATE_GLOBAL: &str = "W0221";
    pub const DUPLICATE_LOCAL: &str = "W0222";
    pub const UNKNOWN_RECOVERY_DM: &str = "E0223";
}

/// A program the checker accepted (no errors; warnings allowed).
#[derive(Debug)]
pub struct Checked {
    program: Program,
}

impl Checked {
    pub fn program(&self) -> &Program {
        &self.program
    }
    pub fn into_program(self) -> Program {
        self.program
    }
}

/// Checks `program`; `diags` holds what loading reported. Returns the
/// checked program if no diagnostic is an error, and all diagnostics sorted.
pub fn check(
    program: Program,
    diags: Vec<Diagnostic>,
) -> (Result<Checked, Program>, Vec<Diagnostic>) {
    check_with(program, diags, false)
}

/// Errors about names that do not resolve (a next situation, an embedded DM
/// or its arity, an exit arc, a SitLog variable): the program's structure is
/// sound and, when run, the machine stops with a clean run-time error if and
/// only if the faulty path is taken, as the original would misbehave there.
pub const UNRESOLVED: &[&str] = &[
    codes::UNKNOWN_NEXT,
    codes::UNKNOWN_DM,
    codes::DM_ARITY,
    codes::UNKNOWN_EXIT,
    codes::UNKNOWN_VARIABLE,
];

/// [`check`]; with `unresolved_as_warnings`, the [`UNRESOLVED`] errors are
/// reported as warnings (`sitlogc run --allow-unresolved`, for legacy
/// applications whose dead paths name missing parts).
pub fn check_with(
    program: Program,
    diags: Vec<Diagnostic>,
    unresolved_as_warnings: bool,
) -> (Result<Checked, Program>, Vec<Diagnostic>) {
    check_opts(
        program,
        diags,
        CheckOptions {
            unresolved_as_warnings,
            legacy: false,
        },
    )
}

/// How lenient the checker is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CheckOptions {
    /// The [`UNRESOLVED`] errors are warnings (`--allow-unresolved`).
    pub unresolved_as_warnings: bool,
    /// The original's rules where it accepts what we refuse (`--legacy`):
    /// a DM defined twice *identically* is a warning (W0203) and the first
    /// definition is used, as the original does.
    pub legacy: bool,
}

/// [`check`] with [`CheckOptions`].
pub fn check_opts(
    program: Program,
    mut diags: Vec<Diagnostic>,
    options: CheckOptions,
) -> (Result<Checked, Program>, Vec<Diagnostic>) {
    let unresolved_as_warnings = options.unresolved_as_warnings;
    Checker {
        program: &program,
        diags: &mut diags,
        legacy: options.legacy,
    }
    .run();
    if unresolved_as_warnings {
        for d in diags.iter_mut().filter(|d| UNRESOLVED.contains(&d.code)) {
            d.severity = crate::diag::Severity::Warning;
        }
    }
    crate::diag::sort(&mut diags);
    if diags.iter().any(Diagnostic::is_error) {
        (Err(program), diags)
    } else {
        (Ok(Checked { program }), diags)
    }
}

struct Checker<'p> {
    program: &'p Program,
    diags: &'p mut Vec<Diagnostic>,
    legacy: bool,
}

/// Functors the functional language evaluates specially: a term with one of
/// these inside has no statically known value.
const EVALUATED: &[(&str, usize)] = &[
    ("apply", 2),
    ("assign", 2),
    ("=", 2),
    ("is", 2),
    ("get", 2),
    ("set", 2),
    ("inc", 2),
    ("when", 3),
    ("==", 2),
    ("\\==", 2),
    (">", 2),
    ("<", 2),
    (">=", 2),
    ("=<", 2),
    ("member", 2),
    ("not_member", 2),
    ("append", 3),
    ("reverse", 2),
    ("length_list", 2),
    ("first", 2),
    ("rest", 2),
    ("last", 2),
    ("rotate_list", 2),
    ("push", 3),
    ("pop", 2),
    ("filter_element", 3),
    ("filter_duplicates", 2),
    ("idx_object", 3),
    ("get_options", 3),
    ("get_random_element", 2),
    ("empty_list", 2),
    ("print_list", 2),
    ("msg_format", 3),
    ("cam2nav", 2),
    ("cam2arm", 2),
    ("timeOver", 2),
    ("statistics", 2),
    ("arrived_posit", 2),
];

fn is_evaluated(name: Atom, arity: usize) -> bool {
    EVALUATED
        .iter()
        .any(|&(n, a)| a == arity && n == name.as_str())
}

/// The branches of `(C -> A ; otherwise -> B)` (also with `|`), if `t` is one.
fn conditional(terms: &Terms, t: TermId) -> Option<(TermId, TermId)> {
    let args = terms
        .compound(t, atoms::SEMICOLON, 2)
        .or_else(|| terms.compound(t, atoms::BAR, 2))?;
    let then = terms.compound(args[0], atoms::IF_THEN, 2)?;
    let other = terms.compound(args[1], atoms::IF_THEN, 2)?;
    Some((then[1], other[1]))
}

/// The values `t` can evaluate to, when they are known without running
/// anything (variables inside are wildcards); `None` when unknown.
fn static_values(terms: &Terms, t: TermId) -> Option<Vec<TermId>> {
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

/// Whether two terms could unify, treating every variable as a wildcard.
fn may_unify(ta: &Terms, a: TermId, tb: &Terms, b: TermId) -> bool {
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

fn is_ground(terms: &Terms, t: TermId) -> bool {
    let mut stack = vec![t];
    while let Some(x) = stack.pop() {
        if matches!(terms.node(x), Node::Var(_)) {
            return false;
        }
        stack.extend_from_slice(terms.args(x));
    }
    true
}

fn show(dm: &Dm, t: TermId) -> String {
    let s = sitlog_syntax::writeq(&dm.clause, t);
    if s.chars().count() > 60 {
        format!("{}…", s.chars().take(59).collect::<String>())
    } else {
        s
    }
}

impl<'p> Checker<'p> {
    fn run(&mut self) {
        self.duplicate_dms();
        self.duplicate_globals();
        let program: &'p Program = self.program;
        for r in &program.recovery {
            if self.find_dm(r.dm).is_none() {
                self.diags.push(
                    Diagnostic::error(
                        codes::UNKNOWN_RECOVERY_DM,
                        r.loc,
                        format!(
                            "recovery protocol `{}` names no DM of the application",
                            r.dm
                        ),
                    )
                    .with_label("unknown DM"),
                );
            }
        }
        for dm in &program.dms {
            self.dm(dm);
        }
    }

    fn duplicate_dms(&mut self) {
        let mut first: HashMap<Atom, Vec<&Dm>> = HashMap::new();
        for dm in &self.program.dms {
            let seen = first.entry(dm.name).or_default();
            let head = dm.loc(dm.span_of(dm.head));
            if let Some(prev) = seen.iter().find(|p| p.arity == dm.arity) {
                let same = || {
                    sitlog_syntax::writeq(&prev.clause, prev.clause.root)
                        == sitlog_syntax::writeq(&dm.clause, dm.clause.root)
                };
                if self.legacy && same() {
                    self.diags.push(
                        Diagnostic::warning(
                            codes::DUPLICATE_DM_IDENTICAL,
                            head,
                            format!(
                                "DM `{}/{}` is defined twice, identically; the first definition is used",
                                dm.name, dm.arity
                            ),
                        )
                        .with_label("second definition")
                        .with_secondary(prev.loc(prev.span_of(prev.head)), "used"),
                    );
                    continue;
                }
                self.diags.push(
                    Diagnostic::error(
                        codes::DUPLICATE_DM,
                        head,
                        format!("DM `{}/{}` is defined twice", dm.name, dm.arity),
                    )
                    .with_label("second definition")
                    .with_secondary(prev.loc(prev.span_of(prev.head)), "first defined here")
                    .with_help("DMs are looked up by name: rename one of them"),
                );
            } else if let Some(prev) = seen.first() {
                self.diags.push(
                    Diagnostic::warning(
                        codes::SAME_NAME_OTHER_ARITY,
                        head,
                        format!(
                            "DM `{}/{}` has the same name as `{}/{}`; calls by name always reach the first",
                            dm.name, dm.arity, prev.name, prev.arity
                        ),
                    )
                    .with_secondary(prev.loc(prev.span_of(prev.head)), "defined first here"),
                );
            }
            seen.push(dm);
        }
    }

    fn duplicate_globals(&mut self) {
        let globals = &self.program.globals;
        for (i, g) in globals.iter().enumerate() {
            if let Some(prev) = globals[..i].iter().find(|p| p.name == g.name) {
                self.diags.push(
                    Diagnostic::warning(
                        codes::DUPLICATE_GLOBAL,
                        g.loc,
                        format!(
                            "global variable `{}` is declared twice; the first is used",
                            g.name
                        ),
                    )
                    .with_secondary(prev.loc, "first declared here"),
                );
            }
        }
    }

    fn find_dm(&self, name: Atom) -> Option<&'p Dm> {
        let program: &'p Program = self.program;
        program.dms.iter().find(|d| d.name == name)
    }

    fn dm(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        let loc = |t: TermId| dm.loc(terms.span(t));
        // Situation structure.
        for s in &dm.situations {
            let sloc = dm.loc(s.span);
            if s.id.is_none() {
                self.diags.push(
                    Diagnostic::error(codes::MISSING_ID, sloc, "situation has no `id`")
                        .with_label("this situation")
                        .with_help("add `id ==> Name`"),
                );
            }
            let kind = s.kind(&dm.clause);
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
            if s.kind_term.and_then(|t| terms.atom(t)) == Some(atoms::NEUTRAL) {
                if let Some(arcs) = &s.arcs {
                    let ok =
                        arcs.len() == 1 && terms.atom(arcs[0].expectation) == Some(atoms::EMPTY);
                    if !ok {
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
        if !dm
            .situations
            .iter()
            .any(|s| s.kind(&dm.clause) == SituationKind::Final)
        {
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
        self.embedded(dm);
        self.variables(dm);
        self.singletons(dm);
        self.shadowed(dm);
        let _ = loc;
    }

    /// Ground next situations must name a situation; unreachable situations warn.
    fn next_situations(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        let n = dm.situations.len();
        let mut edges: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut everything_reachable = false;
        for (i, s) in dm.situations.iter().enumerate() {
            for arc in s.arcs.iter().flatten() {
                let Some(values) = static_values(terms, arc.next) else {
                    everything_reachable = true;
                    continue;
                };
                for v in values {
                    let targets: Vec<usize> = dm
                        .situations
                        .iter()
                        .enumerate()
                        .filter(|(_, t)| t.id.is_some_and(|id| may_unify(terms, id, terms, v)))
                        .map(|(j, _)| j)
                        .collect();
                    if targets.is_empty() && is_ground(terms, v) {
                        let ids: Vec<String> = dm
                            .situations
                            .iter()
                            .filter_map(|s| s.id.map(|id| show(dm, id)))
                            .take(8)
                            .collect();
                        self.diags.push(
                            Diagnostic::error(
                                codes::UNKNOWN_NEXT,
                                dm.loc(terms.span(v)),
                                format!("no situation `{}` in DM `{}`", show(dm, v), dm.name),
                            )
                            .with_label("next situation not found")
                            .with_help(format!("situations of this DM: {}", ids.join(", "))),
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

    /// `embedded_dm` names a DM of the right arity, and the exit arcs name its final situations.
    fn embedded(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        for s in &dm.situations {
            let Some(e) = s.embedded_dm else { continue };
            let Some(values) = static_values(terms, e) else {
                continue;
            };
            let mut resolved: Vec<&'p Dm> = Vec::new();
            for v in values {
                let Some((name, arity)) = terms.functor(v) else {
                    continue;
                };
                match self.find_dm(name) {
                    None => {
                        let mut d = Diagnostic::error(
                            codes::UNKNOWN_DM,
                            dm.loc(terms.span(v)),
                            format!("no DM named `{name}`"),
                        )
                        .with_label("embedded DM not found");
                        if let Some(similar) = self.similar_dm(name) {
                            d = d.with_help(format!("did you mean `{similar}`?"));
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
                    Some(target) => resolved.push(target),
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
                        self.diags.push(
                            Diagnostic::error(
                                codes::UNKNOWN_EXIT,
                                dm.loc(terms.span(v)),
                                format!(
                                    "`{}` is not a final situation of DM `{}`",
                                    show(dm, v),
                                    target.name
                                ),
                            )
                            .with_label("this exit arc can never be taken")
                            .with_help(format!(
                                "final situations of `{}`: {}",
                                target.name,
                                names.join(", ")
                            )),
                        );
                    }
                }
            }
        }
    }

    fn similar_dm(&self, name: Atom) -> Option<Atom> {
        let target = name.as_str();
        self.program
            .dms
            .iter()
            .map(|d| (edit_distance(d.name.as_str(), target), d.name))
            .filter(|&(d, _)| d <= 2.max(target.len() / 4))
            .min_by_key(|&(d, _)| d)
            .map(|(_, n)| n)
    }

    /// `get`/`set`/`inc` name a local or global variable.
    fn variables(&mut self, dm: &Dm) {
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
                            }
                        }
                    }
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
            d = if self.program.has_globals_file {
                d.with_help(format!("declare it in the DM's local variables (`{name} ==> Value`) or in global_vars.pl"))
            } else {
                d.with_help(format!("declare it in the DM's local variables (`{name} ==> Value`) or in a global_vars.pl beside the DMs"))
            };
            self.diags.push(d);
        }
    }

    /// Variables that occur once (Prolog's singleton warning).
    fn singletons(&mut self, dm: &Dm) {
        for v in &dm.clause.vars {
            if v.occurrences == 1 && !v.is_anonymous_style() {
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
    fn shadowed(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        for (i, s) in dm.situations.iter().enumerate() {
            let Some(id) = s.id else { continue };
            if !is_ground(terms, id) {
                continue;
            }
            let earlier = dm.situations[..i].iter().find(|p| {
                p.id.is_some_and(|pid| {
                    is_ground(terms, pid)
                        && sitlog_syntax::writeq(&dm.clause, pid)
                            == sitlog_syntax::writeq(&dm.clause, id)
                })
            });
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

/// Levenshtein distance, for "did you mean" suggestions.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != cb))
                .min(prev[j + 1] + 1)
                .min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

#[allow(dead_code)]
fn loc_of(dm: &Dm, t: TermId) -> Loc {
    dm.loc(dm.span_of(t))
}
