//! The lowered program shared by the interpreter and the code generator.
//!
//! Built only from a [`Checked`] program; lowering cannot fail. Every
//! situation becomes one frozen template term
//! `'$sit'(Head, Id, Type, InArg, OutArg, Prog, EmbeddedDm, DiagMod, Arcs)`
//! (absent attributes are `'$none'`, arcs are `'$arc'(E, A, N)`), so that a
//! visit is one `copy_term` that shares every ground part: constants are
//! built once, at lowering. The IR never refers back to the AST; source
//! positions are kept as text in a side table.

use crate::ast::{FnValue, SituationKind};
use crate::check::Checked;
use sitlog_runtime::machine::Kind;
use sitlog_runtime::{Store, Term};
use sitlog_syntax::{Atom, Clause, TermId};
use std::collections::HashMap;

/// Index of a DM.
pub type DmIx = u32;

#[derive(Debug)]
pub struct Ir {
    /// The frozen store holding every template and constant.
    pub store: Store,
    pub dms: Vec<IrDm>,
    by_name: HashMap<Atom, DmIx>,
    /// Initial values of the global variables, in file order.
    pub globals: Vec<(Atom, Term)>,
    /// Names of the declared basic actions.
    pub basic_actions: Vec<Atom>,
    /// Names and arities of the Prolog user functions (heads of user_functions.pl).
    pub prolog_functions: Vec<(Atom, usize)>,
    /// Names and arities the host registers in Rust (`host_functions.pl`).
    pub host_functions: Vec<(Atom, usize)>,
    /// Whether every Prolog file the application consults was read
    /// (`prolog_functions` is then every function its Prolog defines; a
    /// file the loader could not read, `$SITLOG_HOME/..` or absolute, may
    /// define any).
    pub prolog_complete: bool,
    /// Recovery DM per situation type (D-42a).
    pub recovery: Vec<(Atom, Atom)>,
    /// The Prolog files (templates.pl, then user_functions.pl), consulted
    /// at start by the `prolog` feature.
    pub prolog_sources: Vec<PrologFile>,
    /// What each Prolog user function can return, as far as its clauses
    /// show it (for diagrams; see [`crate::ast::FunctionValues`]).
    pub function_values: Vec<IrFunctionValues>,
    /// The DM source files, for run-time errors shown on the source
    /// ([`IrSituation::source`]).
    pub sources: crate::source::SourceMap,
    /// The DMs the checker left out of this run for their errors
    /// ([`Checked::left_out`]): a call of one is a run-time error quoting
    /// its first error.
    pub left_out: Vec<crate::check::LeftOut>,
}

/// Where a situation and its expressions are written (run-time errors
/// point there).
#[derive(Debug, Clone)]
pub struct SituationSource {
    pub file: crate::source::FileId,
    pub span: sitlog_syntax::Span,
    /// Each arc's span, in order.
    pub arcs: Vec<sitlog_syntax::Span>,
    /// Its in_arg's span, when it has one.
    pub in_arg: Option<sitlog_syntax::Span>,
    /// The constructs of L written in the situation (`apply`, `get`, ...):
    /// those of the attributes that are not arcs, then each arc's, each in
    /// source order; which arc holds them (`None`: another attribute),
    /// their functor, their first argument's functor, their span.
    pub exprs: Vec<ExprSite>,
}

/// One construct of L in the source (see [`SituationSource::exprs`]).
#[derive(Debug, Clone, Copy)]
pub struct ExprSite {
    pub arc: Option<usize>,
    pub functor: (Atom, usize),
    pub inner: Option<(Atom, usize)>,
    pub span: sitlog_syntax::Span,
}

/// The constructs of L below `root` (see [`SituationSource::exprs`]).
fn expr_sites(
    terms: &sitlog_syntax::Terms,
    root: TermId,
    arc: Option<usize>,
    out: &mut Vec<ExprSite>,
) {
    let mut stack = vec![root];
    while let Some(t) = stack.pop() {
        if let Some((name, arity)) = terms.functor(t) {
            if arity > 0 && !sitlog_runtime::eval::evaluates_arguments_only(name, arity) {
                out.push(ExprSite {
                    arc,
                    functor: (name, arity),
                    inner: terms.args(t).first().and_then(|&a| terms.functor(a)),
                    span: terms.span(t),
                });
            }
        }
        stack.extend_from_slice(terms.args(t));
    }
}

/// The values a user function `name/arity` can give: `None` when some
/// clause gives a value that is not a constant nor an argument.
#[derive(Debug)]
pub struct IrFunctionValues {
    pub name: Atom,
    pub arity: usize,
    pub values: Option<Vec<IrFnValue>>,
}

/// One value a user function can give.
#[derive(Clone, Copy, Debug)]
pub enum IrFnValue {
    /// This term (may hold variables).
    Term(Term),
    /// The value of the call's argument at this index (0-based).
    Arg(usize),
}

/// A Prolog source file of the application.
#[derive(Clone, Debug)]
pub struct PrologFile {
    /// As shown in messages.
    pub name: String,
    pub path: std::path::PathBuf,
    pub text: String,
    /// The clauses of `text` as the loader read them (SWI-Prolog's
    /// operators), for the engine's load: `None` to read `text` again.
    pub clauses: Option<std::sync::Arc<Vec<sitlog_syntax::Clause>>>,
}

#[derive(Debug)]
pub struct IrDm {
    pub name: Atom,
    pub arity: usize,
    /// The head alone (for calls).
    pub head: Term,
    pub situations: Vec<IrSituation>,
    /// Local variables and their default values (templates).
    pub locals: Vec<(Atom, Term)>,
    /// `file:line:col` of the `diag_mod` clause.
    pub location: String,
    /// Source names of the template variables (for diagrams and messages).
    pub var_names: Vec<(Term, Box<str>)>,
    /// Source names of the clause's variables by store variable index
    /// (for the type listing).
    pub var_index_names: Vec<(u32, String)>,
}

#[derive(Debug)]
pub struct IrSituation {
    pub kind: Kind,
    pub template: Term,
    /// Principal functor of the id when it is not a variable (selection filter).
    pub id_functor: Option<(Atom, usize)>,
    /// `file:line:col` of the situation.
    pub location: String,
    /// `file:line:col` of its in_arg, when it has one.
    pub in_arg_location: Option<String>,
    /// `file:line:col` of each arc, in order.
    pub arc_locations: Vec<String>,
    /// Spans of the situation, its arcs and its constructs of L.
    pub source: SituationSource,
}

/// The marker of an absent attribute in a situation template.
pub fn none_marker() -> Atom {
    sitlog_runtime::machine::none_marker()
}

impl Ir {
    pub fn dm_by_name(&self, name: Atom) -> Option<DmIx> {
        self.by_name.get(&name).copied()
    }
}

/// Lowers a checked program.
pub fn lower(checked: &Checked) -> Ir {
    let program = checked.program();
    let mut store = Store::new();
    let none = Term::atom(none_marker());
    let sit_f = Atom::intern("$sit");
    let arc_f = Atom::intern("$arc");
    let mut dms = Vec::new();
    let mut by_name = HashMap::new();
    for dm in &program.dms {
        let clause: &Clause = &dm.clause;
        let file = program.sources.get(dm.file);
        // One variable table per DM clause: the head and all situations share it (D-7).
        let mut slots: Vec<Option<Term>> = vec![None; clause.vars.len()];
        let mut import = |store: &mut Store, t: TermId| store.import(&clause.terms, t, &mut slots);
        let head = import(&mut store, dm.head);
        let mut situations = Vec::new();
        for s in &dm.situations {
            let opt = |store: &mut Store,
                       t: Option<TermId>,
                       import: &mut dyn FnMut(&mut Store, TermId) -> Term| {
                t.map_or(none, |t| import(store, t))
            };
            let id = opt(&mut store, s.id, &mut import);
            let ty = opt(&mut store, s.kind_term, &mut import);
            let in_arg = opt(&mut store, s.in_arg, &mut import);
            let out_arg = opt(&mut store, s.out_arg, &mut import);
            let prog = opt(&mut store, s.prog, &mut import);
            let emb = opt(&mut store, s.embedded_dm, &mut import);
            let diag = opt(&mut store, s.diag_mod, &mut import);
            let mut arcs = Vec::new();
            let mut arc_locations = Vec::new();
            let mut exprs = Vec::new();
            for t in [s.prog, s.in_arg, s.out_arg, s.embedded_dm, s.diag_mod]
                .into_iter()
                .flatten()
            {
                expr_sites(&clause.terms, t, None, &mut exprs);
            }
            for (i, arc) in s.arcs.iter().flatten().enumerate() {
                for t in [arc.expectation, arc.action, arc.next] {
                    expr_sites(&clause.terms, t, Some(i), &mut exprs);
                }
            }
            // In the order the run-time error's look-up takes them
            // (`machine::places::blame`): other attributes', then each arc's.
            exprs.sort_by_key(|e| (e.arc.map_or(0, |a| a + 1), e.span));
            let source = SituationSource {
                file: dm.file,
                span: s.span,
                arcs: s.arcs.iter().flatten().map(|a| a.span).collect(),
                in_arg: s.in_arg.map(|t| clause.terms.span(t)),
                exprs,
            };
            for arc in s.arcs.iter().flatten() {
                let pos = file.line_col(arc.span.start);
                arc_locations.push(format!("{}:{}:{}", file.name, pos.line, pos.column));
                let e = import(&mut store, arc.expectation);
                let a = import(&mut store, arc.action);
                let n = import(&mut store, arc.next);
                arcs.push(store.compound(arc_f, &[e, a, n]));
            }
            let arcs = store.list(&arcs);
            let template = store.compound(
                sit_f,
                &[head, id, ty, in_arg, out_arg, prog, emb, diag, arcs],
            );
            let kind = match s.kind(clause) {
                SituationKind::Final => Kind::Final,
                SituationKind::Recursive => Kind::Recursive,
                SituationKind::Perceptual => Kind::Perceptual,
            };
            let id_functor = s.id.and_then(|id| clause.terms.functor(id));
            let pos = file.line_col(s.span.start);
            let in_arg_location = s.in_arg.map(|t| {
                let pos = file.line_col(clause.terms.span(t).start);
                format!("{}:{}:{}", file.name, pos.line, pos.column)
            });
            situations.push(IrSituation {
                kind,
                template,
                id_functor,
                location: format!("{}:{}:{}", file.name, pos.line, pos.column),
                in_arg_location,
                arc_locations,
                source,
            });
        }
        let locals = dm
            .locals
            .iter()
            .map(|l| (l.name, import(&mut store, l.value)))
            .collect();
        let var_names = slots
            .iter()
            .enumerate()
            .filter_map(|(i, t)| t.map(|t| (t, clause.vars[i].name.clone())))
            .collect();
        let var_index_names = slots
            .iter()
            .zip(&clause.vars)
            .filter_map(|(slot, info)| match store.value((*slot)?) {
                sitlog_runtime::Value::Var(v) => Some((v.index(), info.name.to_string())),
                _ => None,
            })
            .collect();
        let pos = file.line_col(clause.span.start);
        by_name.entry(dm.name).or_insert(dms.len() as DmIx);
        dms.push(IrDm {
            name: dm.name,
            arity: dm.arity,
            head,
            situations,
            locals,
            location: format!("{}:{}:{}", file.name, pos.line, pos.column),
            var_index_names,
            var_names,
        });
    }
    let mut globals: Vec<(Atom, Term)> = Vec::new();
    for g in &program.globals {
        if globals.iter().any(|(n, _)| *n == g.name) {
            continue; // the first declaration wins (checker warns)
        }
        let mut slots = vec![None; g.clause.vars.len()];
        let v = store.import(&g.clause.terms, g.value, &mut slots);
        globals.push((g.name, v));
    }
    let function_values = program
        .function_values
        .iter()
        .map(|f| IrFunctionValues {
            name: f.name,
            arity: f.arity,
            values: f.values.as_ref().map(|vs| {
                vs.iter()
                    .map(|v| match v {
                        FnValue::Arg(i) => IrFnValue::Arg(*i),
                        FnValue::Term(clause, t) => {
                            let mut slots = vec![None; clause.vars.len()];
                            IrFnValue::Term(store.import(&clause.terms, *t, &mut slots))
                        }
                    })
                    .collect()
            }),
        })
        .collect();
    store.freeze();
    Ir {
        left_out: checked.left_out().to_vec(),
        sources: program.sources.clone(),
        function_values,
        store,
        dms,
        by_name,
        globals,
        basic_actions: program.basic_actions.iter().map(|b| b.name).collect(),
        prolog_functions: program
            .functions
            .iter()
            .map(|f| (f.name, f.arity))
            .collect(),
        host_functions: program.host_functions.clone(),
        prolog_complete: program.unread_consults.is_empty(),
        recovery: program
            .recovery
            .iter()
            .map(|r| (r.situation_type, r.dm))
            .collect(),
        prolog_sources: program
            .prolog_files
            .iter()
            .enumerate()
            .map(|(i, &id)| {
                let f = program.sources.get(id);
                PrologFile {
                    name: f.name.clone(),
                    path: f.path.clone(),
                    text: f.text.clone(),
                    clauses: program.prolog_file_clauses.get(i).cloned().flatten(),
                }
            })
            .collect(),
    }
}
