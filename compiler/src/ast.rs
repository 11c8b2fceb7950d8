//! The SitLog layer over read terms: DMs, situations, arcs, variable
//! declarations and side-file declarations, every node with its span.
//!
//! Building is shape checking only (is this a `diag_mod/3`, is a situation a
//! list of `attr ==> value`, is an arc `E : A => N`); names are resolved by
//! the checker. Terms stay in their clause's arena and are referred to by
//! [`TermId`].

use crate::diag::{Diagnostic, Loc};
use crate::source::{FileId, SourceMap};
use sitlog_syntax::{atoms, Atom, Clause, Node, Span, TermId};

/// A whole application (or a set of DM files checked together).
#[derive(Debug, Default)]
pub struct Program {
    pub sources: SourceMap,
    pub dms: Vec<Dm>,
    pub globals: Vec<GlobalVar>,
    pub basic_actions: Vec<BasicAction>,
    pub expectation_types: Vec<(Atom, Loc)>,
    /// Heads of the clauses of `user_functions.pl` / `templates.pl`.
    pub functions: Vec<FunctionHead>,
    /// What each of those functions can give as its value (for diagrams).
    pub function_values: Vec<FunctionValues>,
    /// Prolog files to consult at run time (user functions, templates), in load order.
    pub prolog_files: Vec<FileId>,
    /// The clauses of each of `prolog_files` (same index), read once by the
    /// loader with SWI-Prolog's operators: the checks and the engine's load
    /// use them instead of reading the file again. `None` where the loader
    /// read none from a text that is not blank (a file that is not UTF-8,
    /// whose text the loader does not read): read again where needed, as
    /// before. See [`Program::prolog_clauses`].
    pub prolog_file_clauses: Vec<Option<std::sync::Arc<Vec<Clause>>>>,
    /// Whether a `global_vars.pl` was read (if not, every `get`/`set` needs a local).
    pub has_globals_file: bool,
    /// Recovery protocols (`recovery_protocols.pl`): situation type name → DM to run
    /// when no expectation of a situation of that type is met.
    pub recovery: Vec<Recovery>,
    /// Files that Prolog files consult but the loader could not read
    /// (`$SITLOG_HOME/...`, absolute or missing paths), with the directive's
    /// position: their predicates are unknown to the checker.
    pub unread_consults: Vec<(String, Loc)>,
    /// Whether the application has a `knowledge.kb` (its KB services are functions).
    pub has_kb_file: bool,
    /// Whether the application has a `world.toml` (it runs on the simulated robot).
    pub has_world_file: bool,
    /// Whether the program is one DM file checked alone (other DMs of its
    /// directory are not part of it).
    pub single_file: bool,
    /// Functions the host registers in Rust, declared in `host_functions.pl`
    /// (`name/arity.` per clause) or by whoever assembles the program, so
    /// that the checker knows them.
    pub host_functions: Vec<(Atom, usize)>,
    /// The files named by a library name (`'behaviors/say.dm'` in `models`,
    /// `:- consult('behaviors/language.pl')`) and where each was read from.
    pub library_files: Vec<LibraryFile>,
}

impl Program {
    /// The clauses of Prolog file `file` (one of `prolog_files`), as the
    /// loader read them; read again only for a file the loader did not add.
    pub fn prolog_clauses(&self, file: FileId) -> std::sync::Arc<Vec<Clause>> {
        let known = self.prolog_files.iter().position(|&f| f == file);
        match known.and_then(|i| self.prolog_file_clauses.get(i)) {
            Some(Some(clauses)) => clauses.clone(),
            _ => std::sync::Arc::new(
                sitlog_syntax::read_prolog_clauses(&self.sources.get(file).text).0,
            ),
        }
    }
}

/// A file named by a library name, and where the loader found it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LibraryFile {
    /// The name as written (`behaviors/say.dm`).
    pub name: String,
    pub file: FileId,
    /// Where it came from: `None` for the application's own copy, else
    /// the library root's description (`the library built into sitlogc`).
    pub root: Option<String>,
    /// For the application's own copy, the root it stands in for.
    pub overrides: Option<String>,
}

/// `Type ==> dm.` in `recovery_protocols.pl`.
#[derive(Debug, Clone, Copy)]
pub struct Recovery {
    pub situation_type: Atom,
    pub dm: Atom,
    pub loc: Loc,
}

/// One `diag_mod(Id, Situations, LocalVars)`.
#[derive(Debug)]
pub struct Dm {
    pub file: FileId,
    pub clause: Clause,
    /// The `Id` term: an atom, or a compound whose arguments are the parameters.
    pub head: TermId,
    pub name: Atom,
    pub arity: usize,
    pub situations: Vec<Situation>,
    pub locals: Vec<LocalVar>,
}

impl Dm {
    pub fn loc(&self, span: Span) -> Loc {
        Loc {
            file: self.file,
            span,
        }
    }
    pub fn span_of(&self, t: TermId) -> Span {
        self.clause.terms.span(t)
    }
}

/// What kind of situation a `type` names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SituationKind {
    Final,
    Recursive,
    /// Any other type names a perceptual interpreter (`neutral`, `speech`, ...).
    Perceptual,
}

#[derive(Debug)]
pub struct Situation {
    pub span: Span,
    pub id: Option<TermId>,
    pub kind_term: Option<TermId>,
    pub arcs: Option<Vec<Arc>>,
    /// Span of the `arcs ==> [...]` pair.
    pub arcs_span: Option<Span>,
    pub prog: Option<TermId>,
    pub in_arg: Option<TermId>,
    pub out_arg: Option<TermId>,
    pub embedded_dm: Option<TermId>,
    pub diag_mod: Option<TermId>,
    /// Attributes SitLog does not know, kept as written.
    pub others: Vec<(Atom, TermId, Span)>,
}

impl Situation {
    pub fn kind(&self, clause: &Clause) -> SituationKind {
        match self.kind_term.and_then(|t| clause.terms.atom(t)) {
            Some(a) if a == atoms::FINAL => SituationKind::Final,
            Some(a) if a == atoms::RECURSIVE => SituationKind::Recursive,
            _ => SituationKind::Perceptual,
        }
    }
}

/// `Expectation : Action => Next`.
#[derive(Debug, Clone, Copy)]
pub struct Arc {
    pub span: Span,
    pub expectation: TermId,
    pub action: TermId,
    pub next: TermId,
}

/// `name ==> default` in a DM's local variable list.
#[derive(Debug, Clone, Copy)]
pub struct LocalVar {
    pub name: Atom,
    pub value: TermId,
    pub span: Span,
}

/// `name ==> value.` in `global_vars.pl`.
#[derive(Debug)]
pub struct GlobalVar {
    pub name: Atom,
    pub loc: Loc,
    pub clause: Clause,
    pub value: TermId,
}

/// One clause of `basic_actions.pl`: `[id ==> beep, arity ==> [], mod ==> sound, break ==> no]`.
#[derive(Debug)]
pub struct BasicAction {
    pub name: Atom,
    pub loc: Loc,
    pub clause: Clause,
}

/// The head of a user-function clause: `name/arity`.
#[derive(Debug, Clone, Copy)]
pub struct FunctionHead {
    pub name: Atom,
    pub arity: usize,
    pub loc: Loc,
}

/// Error codes of the SitLog layer.
pub mod codes {
    pub const NOT_A_DM: &str = "W0101";
    pub const MALFORMED_DM: &str = "E0102";
    pub const MALFORMED_SITUATION: &str = "E0103";
    pub const MALFORMED_ARC: &str = "E0104";
    pub const MALFORMED_VAR: &str = "E0105";
    pub const MALFORMED_SIDE_FILE: &str = "E0106";
    pub const MALFORMED_GLOBAL: &str = "W0106";
    pub const DUPLICATE_ATTRIBUTE: &str = "W0107";
}

fn dbl_arrow_pair(clause: &Clause, t: TermId) -> Option<(TermId, TermId)> {
    clause
        .terms
        .compound(t, atoms::DOUBLE_ARROW, 2)
        .map(|a| (a[0], a[1]))
}

/// Builds the DMs of one DM file's clauses.
pub fn build_dms(
    file: FileId,
    clauses: Vec<Clause>,
    out: &mut Vec<Dm>,
    diags: &mut Vec<Diagnostic>,
) {
    for clause in clauses {
        let loc = |span| Loc { file, span };
        let root = clause.root;
        let Some(args) = clause.terms.compound(root, atoms::DIAG_MOD, 3) else {
            diags.push(
                Diagnostic::warning(
                    codes::NOT_A_DM,
                    loc(clause.terms.span(root)),
                    "this clause is not a `diag_mod/3` and is ignored",
                )
                .with_help("a DM file holds `diag_mod(Id, Situations, LocalVars).`"),
            );
            continue;
        };
        let (head, sits, locals) = (args[0], args[1], args[2]);
        let (name, arity) = match clause.terms.functor(head) {
            Some(f) => f,
            None => {
                diags.push(
                    Diagnostic::error(
                        codes::MALFORMED_DM,
                        loc(clause.terms.span(head)),
                        "the DM identifier must be an atom or a compound term",
                    )
                    .with_label("not an atom or compound"),
                );
                continue;
            }
        };
        let mut situations = Vec::new();
        match clause.terms.proper_list(sits) {
            Some(items) => {
                for item in items {
                    if let Some(s) = build_situation(&clause, file, item, diags) {
                        situations.push(s);
                    }
                }
            }
            None => diags.push(
                Diagnostic::error(
                    codes::MALFORMED_DM,
                    loc(clause.terms.span(sits)),
                    "the situations of a DM must be a list",
                )
                .with_label("expected `[Situation, ...]`"),
            ),
        }
        let mut local_vars = Vec::new();
        match clause.terms.proper_list(locals) {
            Some(items) => {
                for item in items {
                    match dbl_arrow_pair(&clause, item)
                        .and_then(|(n, v)| clause.terms.atom(n).map(|n| (n, v)))
                    {
                        Some((name, value)) => local_vars.push(LocalVar {
                            name,
                            value,
                            span: clause.terms.span(item),
                        }),
                        None => diags.push(
                            Diagnostic::error(
                                codes::MALFORMED_VAR,
                                loc(clause.terms.span(item)),
                                "a local variable must be written `name ==> value`",
                            )
                            .with_label("not `name ==> value`"),
                        ),
                    }
                }
            }
            None => diags.push(
                Diagnostic::error(
                    codes::MALFORMED_DM,
                    loc(clause.terms.span(locals)),
                    "the local variables of a DM must be a list of `name ==> value`",
                )
                .with_label("expected a list"),
            ),
        }
        out.push(Dm {
            file,
            head,
            name,
            arity,
            situations,
            locals: local_vars,
            clause,
        });
    }
}

fn build_situation(
    clause: &Clause,
    file: FileId,
    item: TermId,
    diags: &mut Vec<Diagnostic>,
) -> Option<Situation> {
    let terms = &clause.terms;
    let loc = |span| Loc { file, span };
    let span = terms.span(item);
    let Some(attrs) = terms.proper_list(item) else {
        diags.push(
            Diagnostic::error(
                codes::MALFORMED_SITUATION,
                loc(span),
                "a situation must be a list of `attribute ==> value` pairs",
            )
            .with_label("not a list"),
        );
        return None;
    };
    let mut s = Situation {
        span,
        id: None,
        kind_term: None,
        arcs: None,
        arcs_span: None,
        prog: None,
        in_arg: None,
        out_arg: None,
        embedded_dm: None,
        diag_mod: None,
        others: Vec::new(),
    };
    let mut seen: Vec<(Atom, Span)> = Vec::new();
    for attr in attrs {
        let pair_span = terms.span(attr);
        let Some((name, value)) =
            dbl_arrow_pair(clause, attr).and_then(|(n, v)| terms.atom(n).map(|n| (n, v)))
        else {
            diags.push(
                Diagnostic::error(
                    codes::MALFORMED_SITUATION,
                    loc(pair_span),
                    "a situation attribute must be written `attribute ==> value`",
                )
                .with_label("not `attribute ==> value`"),
            );
            continue;
        };
        if let Some((_, first)) = seen.iter().find(|(n, _)| *n == name) {
            diags.push(
                Diagnostic::warning(
                    codes::DUPLICATE_ATTRIBUTE,
                    loc(pair_span),
                    format!("attribute `{name}` is given twice; the first one is used"),
                )
                .with_secondary(loc(*first), "first given here"),
            );
            continue;
        }
        seen.push((name, pair_span));
        let slot = match name.as_str() {
            "id" => &mut s.id,
            "type" => &mut s.kind_term,
            "prog" => &mut s.prog,
            "in_arg" => &mut s.in_arg,
            "out_arg" => &mut s.out_arg,
            "embedded_dm" => &mut s.embedded_dm,
            "diag_mod" => &mut s.diag_mod,
            "arcs" => {
                s.arcs_span = Some(pair_span);
                s.arcs = Some(build_arcs(clause, file, value, diags));
                continue;
            }
            _ => {
                s.others.push((name, value, pair_span));
                continue;
            }
        };
        *slot = Some(value);
    }
    Some(s)
}

fn build_arcs(
    clause: &Clause,
    file: FileId,
    value: TermId,
    diags: &mut Vec<Diagnostic>,
) -> Vec<Arc> {
    let terms = &clause.terms;
    let loc = |span| Loc { file, span };
    let Some(items) = terms.proper_list(value) else {
        diags.push(
            Diagnostic::error(
                codes::MALFORMED_ARC,
                loc(terms.span(value)),
                "`arcs` must be a list of `Expectation : Action => Next`",
            )
            .with_label("not a list"),
        );
        return Vec::new();
    };
    let mut arcs = Vec::new();
    for item in items {
        let shape = terms.compound(item, atoms::ARROW, 2).and_then(|a| {
            terms
                .compound(a[0], atoms::COLON, 2)
                .map(|ea| (ea[0], ea[1], a[1]))
        });
        match shape {
            Some((expectation, action, next)) => arcs.push(Arc {
                span: terms.span(item),
                expectation,
                action,
                next,
            }),
            None => diags.push(
                Diagnostic::error(
                    codes::MALFORMED_ARC,
                    loc(terms.span(item)),
                    "an arc must have the form `Expectation : Action => Next`",
                )
                .with_label("not an arc"),
            ),
        }
    }
    arcs
}

/// `name ==> value.` clauses of `global_vars.pl`.
pub fn build_globals(
    file: FileId,
    clauses: Vec<Clause>,
    out: &mut Vec<GlobalVar>,
    diags: &mut Vec<Diagnostic>,
) {
    for clause in clauses {
        let loc = Loc {
            file,
            span: clause.span,
        };
        match dbl_arrow_pair(&clause, clause.root)
            .and_then(|(n, v)| clause.terms.atom(n).map(|n| (n, v)))
        {
            Some((name, value)) => out.push(GlobalVar {
                name,
                loc,
                value,
                clause,
            }),
            // The original reads the clause into its list of globals, where
            // no `get`/`set`/`inc` finds it, and runs on (first-week program
            // 36, `battery => 100.`): a warning; a use of the name is E0219,
            // or W0219 where the original runs on.
            None => diags.push(
                Diagnostic::warning(
                    codes::MALFORMED_GLOBAL,
                    loc,
                    "a global variable must be written `name ==> value.`: this clause declares none",
                )
                .with_label("not `name ==> value`"),
            ),
        }
    }
}

/// Clauses of `basic_actions.pl`: attribute lists with an `id`.
pub fn build_basic_actions(
    file: FileId,
    clauses: Vec<Clause>,
    out: &mut Vec<BasicAction>,
    diags: &mut Vec<Diagnostic>,
) {
    for clause in clauses {
        let loc = Loc {
            file,
            span: clause.span,
        };
        let id = clause.terms.proper_list(clause.root).and_then(|items| {
            items.into_iter().find_map(|it| {
                dbl_arrow_pair(&clause, it)
                    .filter(|(n, _)| clause.terms.atom(*n) == Some(atoms::ID))
                    .and_then(|(_, v)| clause.terms.atom(v))
            })
        });
        match id {
            Some(name) => out.push(BasicAction { name, loc, clause }),
            None => diags.push(
                Diagnostic::error(
                    codes::MALFORMED_SIDE_FILE,
                    loc,
                    "a basic action must be a list of `attribute ==> value` with an atom `id`",
                )
                .with_help("e.g. `[id ==> beep, arity ==> [], mod ==> sound, break ==> no].`"),
            ),
        }
    }
}

/// `name/arity.` clauses of `host_functions.pl`: the user functions a
/// host registers in Rust (`Functions::register`), which no Prolog file of
/// the application defines.
pub fn build_host_functions(
    file: FileId,
    clauses: Vec<Clause>,
    out: &mut Vec<(Atom, usize)>,
    diags: &mut Vec<Diagnostic>,
) {
    let slash = Atom::intern("/");
    for clause in clauses {
        let loc = Loc {
            file,
            span: clause.span,
        };
        let terms = &clause.terms;
        let decl = terms.compound(clause.root, slash, 2).and_then(|a| {
            let name = terms.atom(a[0])?;
            match terms.node(a[1]) {
                Node::Int(n) if *n >= 0 => Some((name, *n as usize)),
                _ => None,
            }
        });
        match decl {
            Some(decl) => out.push(decl),
            None => diags.push(
                Diagnostic::error(
                    codes::MALFORMED_SIDE_FILE,
                    loc,
                    "a host function must be written `name/arity.`",
                )
                .with_help("e.g. `poke/1.`"),
            ),
        }
    }
}

/// `Type ==> dm.` clauses of `recovery_protocols.pl`.
pub fn build_recovery(
    file: FileId,
    clauses: Vec<Clause>,
    out: &mut Vec<Recovery>,
    diags: &mut Vec<Diagnostic>,
) {
    for clause in clauses {
        let loc = Loc {
            file,
            span: clause.span,
        };
        let pair = dbl_arrow_pair(&clause, clause.root).and_then(|(t, d)| {
            let ty = clause.terms.functor(t).map(|f| f.0)?;
            Some((ty, clause.terms.atom(d)?))
        });
        match pair {
            Some((situation_type, dm)) => out.push(Recovery {
                situation_type,
                dm,
                loc,
            }),
            None => diags.push(
                Diagnostic::error(
                    codes::MALFORMED_SIDE_FILE,
                    loc,
                    "a recovery protocol must be written `situation_type ==> dm_name.`",
                )
                .with_help("e.g. `speech ==> ask_again.`"),
            ),
        }
    }
}

/// Atoms of `expectation_types.pl`.
pub fn build_expectation_types(
    file: FileId,
    clauses: Vec<Clause>,
    out: &mut Vec<(Atom, Loc)>,
    diags: &mut Vec<Diagnostic>,
) {
    for clause in clauses {
        let loc = Loc {
            file,
            span: clause.span,
        };
        match clause.terms.atom(clause.root) {
            Some(a) => out.push((a, loc)),
            None => diags.push(Diagnostic::error(
                codes::MALFORMED_SIDE_FILE,
                loc,
                "an expectation type must be an atom",
            )),
        }
    }
}

/// The values a user function `name/arity` gives through
/// `assign_func_value/1`, as far as its clauses show them: `values` is
/// `None` when some clause gives something else than a term written in the
/// clause (directly or through `V = Term`, V bound by no other goal) or one
/// of its arguments.
#[derive(Debug, Clone)]
pub struct FunctionValues {
    pub name: Atom,
    pub arity: usize,
    pub values: Option<Vec<FnValue>>,
}

/// One value of a user function.
#[derive(Debug, Clone)]
pub enum FnValue {
    /// A term of this clause (it may hold variables).
    Term(Clause, TermId),
    /// The call's argument at this index (0-based).
    Arg(usize),
}

/// The `assign_func_value(V)` values of one clause: `None` if one of them
/// cannot be told; empty if the clause assigns nothing.
fn clause_values(clause: &Clause, head: TermId, body: Option<TermId>) -> Option<Vec<FnValue>> {
    let terms = &clause.terms;
    let Some(body) = body else {
        return Some(Vec::new());
    };
    // The goals of the body, through `,` `;` `->` `*->` `|`.
    let mut goals = Vec::new();
    let mut work = vec![body];
    while let Some(g) = work.pop() {
        match terms.node(g) {
            Node::Compound {
                functor, arity: 2, ..
            } if [",", ";", "->", "*->", "|"].contains(&functor.as_str()) => {
                let a = terms.args(g);
                work.push(a[1]);
                work.push(a[0]);
            }
            _ => goals.push(g),
        }
    }
    let var_of = |t: TermId| match terms.node(t) {
        Node::Var(v) if &*clause.vars[v.0 as usize].name != "_" => Some(*v),
        _ => None,
    };
    let head_args: &[TermId] = match terms.node(head) {
        Node::Compound { .. } => terms.args(head),
        _ => &[],
    };
    let arg_index = |v| head_args.iter().position(|&a| var_of(a) == Some(v));
    let assign = Atom::intern("assign_func_value");
    let eq = Atom::intern("=");
    let mut out = Vec::new();
    for &g in &goals {
        let Some(a) = terms.compound(g, assign, 1) else {
            continue;
        };
        let Some(v) = var_of(a[0]) else {
            out.push(FnValue::Term(clause.clone(), a[0]));
            continue;
        };
        if let Some(i) = arg_index(v) {
            out.push(FnValue::Arg(i));
            continue;
        }
        // Bound by another goal too (`(lang_answer(K, As, A) -> true ; A =
        // no)`): its values cannot be told from the `=` goals alone.
        let occurs = |t: TermId| {
            let mut work = vec![t];
            while let Some(x) = work.pop() {
                match terms.node(x) {
                    Node::Var(w) if *w == v => return true,
                    Node::Compound { .. } => work.extend(terms.args(x)),
                    _ => {}
                }
            }
            false
        };
        let binds_v = |u: TermId| {
            terms
                .compound(u, eq, 2)
                .is_some_and(|b| var_of(b[0]) == Some(v) || var_of(b[1]) == Some(v))
        };
        if goals
            .iter()
            .any(|&u| u != g && !binds_v(u) && terms.compound(u, assign, 1).is_none() && occurs(u))
        {
            return None;
        }
        let mut found = false;
        for &u in &goals {
            let Some(b) = terms.compound(u, eq, 2) else {
                continue;
            };
            let other = if var_of(b[0]) == Some(v) {
                b[1]
            } else if var_of(b[1]) == Some(v) {
                b[0]
            } else {
                continue;
            };
            match var_of(other) {
                Some(w) => match arg_index(w) {
                    Some(i) => out.push(FnValue::Arg(i)),
                    None => return None,
                },
                None => out.push(FnValue::Term(clause.clone(), other)),
            }
            found = true;
        }
        if !found {
            return None;
        }
    }
    Some(out)
}

/// Heads of Prolog clauses (`Head :- Body.`, facts); directives are skipped.
pub fn build_function_heads(
    file: FileId,
    clauses: &[Clause],
    out: &mut Vec<FunctionHead>,
    values: &mut Vec<FunctionValues>,
) {
    let neck = Atom::intern(":-");
    for clause in clauses {
        let terms = &clause.terms;
        let (head, body) = match terms.node(clause.root) {
            Node::Compound {
                functor, arity: 1, ..
            } if *functor == neck => continue,
            _ => terms
                .compound(clause.root, neck, 2)
                .map_or((clause.root, None), |a| (a[0], Some(a[1]))),
        };
        if let Some((name, arity)) = terms.functor(head) {
            let these = clause_values(clause, head, body);
            match values
                .iter_mut()
                .find(|f| f.name == name && f.arity == arity)
            {
                Some(f) => match (&mut f.values, these) {
                    (Some(vs), Some(more)) => vs.extend(more),
                    (vs, _) => *vs = None,
                },
                None => values.push(FunctionValues {
                    name,
                    arity,
                    values: these,
                }),
            }
            if !out.iter().any(|h| h.name == name && h.arity == arity) {
                out.push(FunctionHead {
                    name,
                    arity,
                    loc: Loc {
                        file,
                        span: terms.span(head),
                    },
                });
            }
        }
    }
}
