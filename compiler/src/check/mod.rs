//! The checker: names, arities, situation structure and types,
//! reachability, SitLog variables and Prolog variables used without a
//! value, user functions (`apply`) and basic actions (names and arities),
//! with "did you mean" suggestions. It collects every diagnostic and never runs anything;
//! what a file that could not be read may have declared is not reported as
//! missing. Linear in the size of the program. A
//! program without errors becomes a [`Checked`] program: later stages accept
//! only that type, so an unchecked program cannot reach them. For a run
//! ([`CheckOptions::task`]), a DM with errors that the run cannot reach by
//! name is first left out of the program (module `task`, W0232), so a
//! [`Checked`] program still holds only DMs without errors.

use crate::ast::{Dm, Program, SituationKind};
use crate::diag::{Diagnostic, Severity};
use crate::source::FileId;
use crate::suggest::did_you_mean;
use sitlog_syntax::{atoms, Atom, Node, Span, TermId, Terms};
use std::collections::{HashMap, HashSet};

mod calls;
mod never_taken;
mod os_access;
mod prolog_depth;
mod situations;
mod task;
mod terms;
mod unbound;
mod variables;

use situations::Broken;
pub use task::LeftOut;
use terms::*;

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
    /// E0219 where the original runs on (its value an argument of data).
    pub const UNKNOWN_VARIABLE_NESTED: &str = "W0219";
    pub const SINGLETON: &str = "W0220";
    pub const DUPLICATE_GLOBAL: &str = "W0221";
    pub const DUPLICATE_LOCAL: &str = "W0222";
    pub const UNKNOWN_RECOVERY_DM: &str = "E0223";
    pub const UNKNOWN_FUNCTION: &str = "E0224";
    pub const UNKNOWN_ACTION: &str = "W0225";
    pub const KB_SERVICE_WITHOUT_KB: &str = "W0226";
    pub const WORLD_FUNCTION_WITHOUT_WORLD: &str = "W0227";
    pub const UNBOUND_VARIABLE: &str = "W0228";
    pub const ACTION_ARITY: &str = "W0229";
    pub const UNKNOWN_SITUATION_TYPE: &str = "E0230";
    pub const DEAD_EXIT: &str = "W0231";
    pub const LEFT_OUT: &str = "W0232";
    pub const NOT_A_CONDITIONAL: &str = "W0233";
    pub const DM_HEAD_MISMATCH: &str = "E0234";
    pub const IN_ARG_NEVER_MATCHES: &str = "W0235";
    pub const NEUTRAL_NEVER_PROCEEDS: &str = "E0236";
    pub const DIAG_MOD_MISMATCH: &str = "E0237";
    pub const ARITHMETIC_WITHOUT_VALUE: &str = "E0238";
    pub const ARC_NEVER_TAKEN: &str = "W0239";
    pub const OS_ACCESS: &str = "W0240";
    pub const PROLOG_TOO_DEEP: &str = "E0241";
    pub const INC_NOT_A_NUMBER: &str = "E0242";
    /// Given by `sitlogc check`, which reads the world file.
    pub const UNKNOWN_WORLD_NAME: &str = "W0243";
    pub const VAR_OP_ARITY: &str = "E0250";
    pub const APPLY_VALUE_COUNT: &str = "W0251";
}

/// A program the checker accepted (no errors; warnings allowed).
#[derive(Debug)]
pub struct Checked {
    program: Program,
    left_out: Vec<LeftOut>,
}

impl Checked {
    pub fn program(&self) -> &Program {
        &self.program
    }
    /// The DMs a run of [`CheckOptions::task`] left out for their errors
    /// (not in [`Checked::program`]).
    pub fn left_out(&self) -> &[LeftOut] {
        &self.left_out
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
/// or its arity, an exit arc, a SitLog variable, a function): the
/// program's structure is sound and, when run, the faulty path fails only
/// if it is taken (a clean run-time error: the original stops there too).
/// What the original runs on (an undeclared action or one given another
/// number of arguments does nothing, an unbound variable prints as `_G1`)
/// is a warning from the start (W0225, W0228, W0229).
pub const UNRESOLVED: &[&str] = &[
    codes::UNKNOWN_NEXT,
    codes::UNKNOWN_DM,
    codes::DM_ARITY,
    codes::DM_HEAD_MISMATCH,
    codes::DIAG_MOD_MISMATCH,
    codes::UNKNOWN_EXIT,
    codes::UNKNOWN_VARIABLE,
    codes::UNKNOWN_FUNCTION,
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
    /// Where [`crate::check_path_opts`] looks up library names the
    /// application has no copy of (`sitlogc` passes the behaviour library
    /// built into it); `None`: nowhere.
    pub library: Option<&'static crate::load::Library>,
    /// The DM a run starts from (`sitlogc run`'s `--main`): a DM with
    /// errors that it cannot reach by name is left out of the program
    /// (W0232, its errors warnings; [`Checked::left_out`]), as the original
    /// looks into a DM only when its run reaches it. `None` (`sitlogc
    /// check`, the editor): every DM's errors are errors.
    pub task: Option<Atom>,
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
    let mut program = program;
    let left_out = match options.task {
        Some(task) => task::leave_out(&mut program, &mut diags, task),
        None => Vec::new(),
    };
    crate::diag::sort(&mut diags);
    if diags.iter().any(Diagnostic::is_error) {
        (Err(program), diags)
    } else {
        (Ok(Checked { program, left_out }), diags)
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
        let declared = self.declared_actions();
        let outputs = |name: Atom, arity: usize, i: usize| match declared.get(&name) {
            Some(Some(names)) => names.get(i).is_some_and(|n| is_output_name(n.as_str())),
            _ => arity >= 2 && i == arity - 1,
        };
        for dm in &program.dms {
            self.dm(dm, &broken, &outputs);
        }
        if !broken.prolog {
            self.functions();
        }
        self.apply_value_counts();
        self.false_conditionals();
        self.os_access();
        self.prolog_depth();
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

    /// The library file (`behaviors/find.dm`) that defines a DM named
    /// `name`, when the checker was given a library.
    fn library_file_defining(&self, name: Atom) -> Option<String> {
        let library = self.options.library?;
        library
            .dm_files(true)
            .into_iter()
            .find(|(_, text)| dm_names_in(text).iter().any(|n| n == name.as_str()))
            .map(|(file, _)| file)
    }

    fn similar_dm(&self, name: Atom) -> Option<&'p str> {
        let program: &'p Program = self.program;
        did_you_mean(name.as_str(), program.dms.iter().map(|d| d.name.as_str()))
    }
}

/// Whether an argument an action's `arity` list names so is one the robot
/// binds: `status`, `result`, `out`, or a name with one of them in it
/// (`grasp_status`, `out_pose`).
fn is_output_name(name: &str) -> bool {
    name.contains("status") || name.contains("result") || name.starts_with("out")
}

#[cfg(test)]
mod tests {
    use super::situations::SituationIndex;
    use super::{did_you_mean, is_ground, may_unify, static_values};
    use proptest::prelude::*;

    /// A Prolog file is read once: the loader's clauses serve the checks
    /// (their diagnostics as before) and the engine's load (the IR).
    #[test]
    fn prolog_files_are_read_once_for_the_check_and_the_load() {
        let uf = "f(X) :- X = 1, assign_func_value(X).\ng :- shell(ls).\n";
        let (program, diags) = crate::load::load_sources(&[
            ("templates.pl", "% none\n"),
            ("user_functions.pl", uf),
            (
                "main.dm",
                "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : empty => fs]], [id ==> fs, type ==> final]], []).",
            ),
        ]);
        let read = sitlog_syntax::read_prolog_clauses(uf).0;
        let uf_file = program.prolog_files[1];
        assert_eq!(*program.prolog_clauses(uf_file), read);
        // A file without clauses is read again where needed (nothing).
        assert!(program.prolog_file_clauses[0].is_none());
        let (checked, diags) = super::check(program, diags);
        let codes: Vec<_> = diags.iter().map(|d| d.code).collect();
        assert_eq!(codes, [super::codes::OS_ACCESS], "{diags:?}");
        let ir = crate::ir::lower(&checked.expect("checks"));
        let uf = &ir.prolog_sources[1];
        assert_eq!(uf.clauses.as_deref(), Some(&read));
        assert!(ir.prolog_sources[0].clauses.is_none());
    }

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
