//! The checker: names, arities, situation structure, reachability,
//! variables, user functions (`apply`) and basic actions, with "did you
//! mean" suggestions. It collects every diagnostic and never runs anything;
//! what a file that could not be read may have declared is not reported as
//! missing. Linear in the size of the program. A
//! program without errors becomes a [`Checked`] program: later stages accept
//! only that type, so an unchecked program cannot reach them.

use crate::ast::{Dm, Program, SituationKind};
use crate::diag::{Diagnostic, Severity};
use crate::source::FileId;
use sitlog_syntax::{atoms, Atom, Node, Span, TermId, Terms};
use std::collections::{HashMap, HashSet};

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
    pub const UNKNOWN_FUNCTION: &str = "E0224";
    pub const UNKNOWN_ACTION: &str = "E0225";
    pub const KB_SERVICE_WITHOUT_KB: &str = "W0226";
    pub const WORLD_FUNCTION_WITHOUT_WORLD: &str = "W0227";
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
    codes::UNKNOWN_FUNCTION,
    codes::UNKNOWN_ACTION,
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
            ..CheckOptions::default()
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
    /// User functions the host registers when the task runs on a world
    /// (the simulated robot's, `sitlog_robot::WORLD_FUNCTIONS`): the
    /// checker does not depend on the robot, whoever assembles the run
    /// passes them ([`crate::check_path`] does). Known when the program has
    /// a `world.toml` or [`CheckOptions::world`] says so.
    pub world_functions: &'static [(&'static str, usize)],
    /// User functions the host always registers besides the standard ones
    /// (a custom runner's Rust functions).
    pub host_functions: &'static [(&'static str, usize)],
    /// Whether the task runs on a world (`Some`), or as the application's
    /// files say (`None`: a `world.toml` beside the DMs).
    pub world: Option<bool>,
    /// Whether the KB services are functions of the run (`Some`), or as the
    /// application's files say (`None`: a `knowledge.kb` beside the DMs).
    pub kb: Option<bool>,
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
        options,
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
    options: CheckOptions,
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
        let broken = Broken::of(self.program, self.diags);
        self.duplicate_dms();
        self.duplicate_globals();
        let program: &'p Program = self.program;
        for r in &program.recovery {
            if self.find_dm(r.dm).is_none() && !broken.may_define_dm(r.dm) {
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
            self.dm(dm, &broken);
        }
        if !broken.prolog {
            self.functions();
        }
        if !broken.basic_actions && !program.basic_actions.is_empty() {
            self.actions();
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

    fn dm(&mut self, dm: &Dm, broken: &Broken) {
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
        self.embedded(dm, broken);
        if !broken.globals {
            self.variables(dm);
        }
        self.singletons(dm);
        self.shadowed(dm);
        let _ = loc;
    }

    /// Ground next situations must name a situation; unreachable situations warn.
    /// Linear in the situations of the DM: each next-situation value is
    /// looked up in an index of the ids, not compared with every id.
    fn next_situations(&mut self, dm: &Dm) {
        let terms = &dm.clause.terms;
        let n = dm.situations.len();
        let index = SituationIndex::new(dm);
        let mut edges: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut everything_reachable = false;
        for (i, s) in dm.situations.iter().enumerate() {
            for arc in s.arcs.iter().flatten() {
                let Some(values) = static_values(terms, arc.next) else {
                    everything_reachable = true;
                    continue;
                };
                for v in values {
                    let targets = index.targets(dm, v);
                    if targets.is_empty() && is_ground(terms, v) {
                        let shown = show(dm, v);
                        let ids: Vec<String> = dm
                            .situations
                            .iter()
                            .filter_map(|s| s.id.map(|id| show(dm, id)))
                            .collect();
                        let help = match did_you_mean(&shown, ids.iter().map(String::as_str)) {
                            Some(similar) => format!("did you mean `{similar}`?"),
                            None => format!(
                                "situations of this DM: {}{}",
                                ids.iter().take(8).cloned().collect::<Vec<_>>().join(", "),
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

    /// `embedded_dm` names a DM of the right arity, and the exit arcs name its final situations.
    fn embedded(&mut self, dm: &Dm, broken: &Broken) {
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
                        if let Some(similar) = self.similar_dm(name) {
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
                        let shown = show(dm, v);
                        let help = if names.is_empty() {
                            format!(
                                "DM `{}` has no final situation: add `[id ==> {shown}, type ==> final]` to it",
                                target.name
                            )
                        } else if let Some(similar) =
                            did_you_mean(&shown, names.iter().map(String::as_str))
                        {
                            format!("did you mean `{similar}`?")
                        } else {
                            format!(
                                "final situations of `{}`: {}",
                                target.name,
                                names.join(", ")
                            )
                        };
                        self.diags.push(
                            Diagnostic::error(
                                codes::UNKNOWN_EXIT,
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

    fn similar_dm(&self, name: Atom) -> Option<&'p str> {
        let program: &'p Program = self.program;
        did_you_mean(name.as_str(), program.dms.iter().map(|d| d.name.as_str()))
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

/// The candidate closest to `target`, if it is close enough to be a typo of
/// it: at most a third of the name's length apart by edit distance
/// (a transposition counts one; at least one edit allowed), or sharing
/// most of its start (Jaro-Winkler similarity 0.9 or more: `greet` for
/// `greeting`). Never the name itself, nothing for names shorter than 3
/// characters (any other short name is one edit away); the fewest edits win.
fn did_you_mean<'a>(
    target: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let len = target.chars().count();
    let limit = (len / 3).max(1);
    let mut best: Option<(usize, f64, &'a str)> = None;
    for c in candidates {
        if c == target {
            continue;
        }
        let d = strsim::osa_distance(target, c);
        let jw = strsim::jaro_winkler(target, c);
        let close = len >= 3 && (d <= limit || jw >= 0.9);
        let better = best.is_none_or(|(bd, bjw, _)| d < bd || (d == bd && jw > bjw));
        if close && better {
            best = Some((d, jw, c));
        }
    }
    best.map(|(_, _, c)| c)
}

/// The situations of a DM by id, so that finding the situations a
/// next-situation value can select costs a hash lookup, not a scan.
struct SituationIndex {
    /// Ground ids, by their text.
    ground: HashMap<String, Vec<usize>>,
    /// Ids with variables, by principal functor.
    open: HashMap<(Atom, usize), Vec<usize>>,
    /// Every id, by principal functor (for values with variables).
    all: HashMap<(Atom, usize), Vec<usize>>,
    /// Ids that are a variable: any value selects them.
    var: Vec<usize>,
}

impl SituationIndex {
    fn new(dm: &Dm) -> SituationIndex {
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
    fn targets(&self, dm: &Dm, v: TermId) -> Vec<usize> {
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
struct Broken {
    /// A DM file failed.
    dm_file: bool,
    /// The DM names the failed DM files seem to define (`diag_mod(name`);
    /// `None` when one of them shows none: any name may be defined there.
    dm_names: Option<HashSet<String>>,
    globals: bool,
    basic_actions: bool,
    prolog: bool,
}

impl Broken {
    fn of(program: &Program, diags: &[Diagnostic]) -> Broken {
        let mut files: Vec<FileId> = diags
            .iter()
            .filter(|d| {
                d.is_error()
                    && (d.code == crate::load::codes::SYNTAX
                        || d.code == crate::load::codes::NOT_UTF8)
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

    fn may_define_dm(&self, name: Atom) -> bool {
        self.dm_file
            && self
                .dm_names
                .as_ref()
                .is_none_or(|names| names.contains(name.as_str()))
    }
}

/// The names after `diag_mod(` in a text that could not be read as terms.
fn dm_names_in(text: &str) -> Vec<String> {
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
fn unevaluated_args(terms: &Terms, t: TermId) -> bool {
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
fn head_example(name: Atom, arity: usize) -> String {
    let mut f = String::new();
    sitlog_syntax::write::write_atom(&mut f, name, true);
    if arity > 0 {
        let args: Vec<String> = (1..=arity).map(|i| format!("X{i}")).collect();
        f.push_str(&format!("({})", args.join(", ")));
    }
    f
}

/// Where a function is called: `apply(F, Args)` with F's functor known.
struct Call {
    name: Atom,
    arity: usize,
    span: Span,
}

/// The `apply` calls in the evaluated parts of `dm`, in source order.
fn calls(dm: &Dm) -> Vec<Call> {
    let terms = &dm.clause.terms;
    let mut out = Vec::new();
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
        if let Some(&[f, args]) = terms.compound(t, atoms::APPLY, 2) {
            if let Some((name, arity)) = terms.functor(f) {
                out.push(Call {
                    name,
                    arity,
                    span: terms.span(t),
                });
            }
            stack.push(args);
            continue;
        }
        // `set(N, E)` stores E as written (D-38): nothing in it is called.
        if terms.compound(t, atoms::SET, 2).is_some() {
            continue;
        }
        if unevaluated_args(terms, t) {
            continue;
        }
        stack.extend_from_slice(terms.args(t));
    }
    out.sort_by_key(|c| c.span);
    out
}

/// The actions an arc's action term performs, as far as they are written
/// (an element of a list, either branch of a conditional): name and span.
/// Terms evaluated to something unknown (`get`, `apply`, ...) and `empty`
/// are left out.
fn actions_of(terms: &Terms, action: TermId, out: &mut Vec<(Atom, Span)>) {
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
        out.push((name, terms.span(t)));
    }
}

impl Checker<'_> {
    /// Every `apply(f(..), Args)` names a function the run will have: a
    /// standard one, a clause head of the application's Prolog files, a KB
    /// service when the KB is in use, or one the host registers.
    fn functions(&mut self) {
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

    /// With a `basic_actions.pl`, every action an arc performs is declared
    /// there (the original ignores the others silently: a typo does nothing).
    fn actions(&mut self) {
        let program = self.program;
        let declared: HashSet<Atom> = program.basic_actions.iter().map(|b| b.name).collect();
        for dm in &program.dms {
            let terms = &dm.clause.terms;
            let mut found = Vec::new();
            for s in &dm.situations {
                for arc in s.arcs.iter().flatten() {
                    actions_of(terms, arc.action, &mut found);
                }
            }
            found.sort_by_key(|&(_, span)| span);
            for (name, span) in found {
                if declared.contains(&name) {
                    continue;
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
                    Diagnostic::error(
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

#[cfg(test)]
mod tests {
    use super::{did_you_mean, is_ground, may_unify, static_values, SituationIndex};
    use proptest::prelude::*;

    const IDS: &[&str] = &[
        "a", "b", "s(1)", "s(X)", "s(a)", "s(1.0)", "t(X, Y)", "t(a, b)", "X", "1", "'s'",
    ];

    proptest! {
        /// The index finds exactly the situations a scan of every id finds.
        #[test]
        fn index_agrees_with_a_scan(
            ids in proptest::collection::vec(0..IDS.len(), 1..8),
            nexts in proptest::collection::vec(0..IDS.len(), 1..8),
        ) {
            let mut text = String::from("diag_mod(m, [");
            for (i, &id) in ids.iter().enumerate() {
                let next = IDS[nexts[i % nexts.len()]];
                text.push_str(&format!(
                    "[id ==> {}, type ==> neutral, arcs ==> [empty : empty => {next}]],",
                    IDS[id]
                ));
            }
            text.push_str("[id ==> fs, type ==> final]], []).");
            let (program, diags) = crate::load::load_sources(&[("m.dm", &text)]);
            prop_assert!(diags.is_empty(), "{diags:?}");
            let dm = &program.dms[0];
            let terms = &dm.clause.terms;
            let index = SituationIndex::new(dm);
            for s in &dm.situations {
                for arc in s.arcs.iter().flatten() {
                    for v in static_values(terms, arc.next).into_iter().flatten() {
                        let mut got = index.targets(dm, v);
                        got.sort_unstable();
                        let want: Vec<usize> = dm
                            .situations
                            .iter()
                            .enumerate()
                            .filter(|(_, t)| t.id.is_some_and(|id| may_unify(terms, id, terms, v)))
                            .map(|(j, _)| j)
                            .collect();
                        prop_assert_eq!(&got, &want, "value {} ground {}", sitlog_syntax::writeq(&dm.clause, v), is_ground(terms, v));
                    }
                }
            }
        }

        /// A suggestion is one of the candidates, never the name itself.
        #[test]
        fn suggestion_is_another_candidate(
            target in "\\PC{0,12}",
            candidates in proptest::collection::vec("\\PC{0,12}", 0..6),
        ) {
            if let Some(s) = did_you_mean(&target, candidates.iter().map(String::as_str)) {
                prop_assert!(s != target);
                prop_assert!(candidates.iter().any(|c| c == s));
            }
        }
    }

    #[test]
    fn suggestions() {
        let names = ["say", "navigate", "grasp", "place"];
        assert_eq!(did_you_mean("sya", names), Some("say"));
        assert_eq!(did_you_mean("navgate", names), Some("navigate"));
        assert_eq!(did_you_mean("xyz", names), None);
        assert_eq!(did_you_mean("say", names), None);
        assert_eq!(did_you_mean("a", ["b"]), None);
        assert_eq!(did_you_mean("pour", ["poor", "milk"]), Some("poor"));
        // equal edits: the longer common start wins
        assert_eq!(did_you_mean("pour", ["poor", "pout"]), Some("pout"));
        assert_eq!(
            did_you_mean("greet", ["is", "greeting", "fs"]),
            Some("greeting")
        );
        assert_eq!(did_you_mean("fs", ["is", "greeting"]), None);
    }
}
