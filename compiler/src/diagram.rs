//! The papers' diagram of a program, built from the lowered IR (the same
//! one the interpreter and the code generator run; no second reading of the
//! text). Layout and rendering live in `sitlog-graph`.
//!
//! What the compiler can tell about next situations: a concrete term goes
//! to the situations whose id may unify with it (several: a `∨`
//! disjunction, each exit labelled with the instance's id); a conditional
//! `(C -> A ; otherwise -> B)` is a function dot labelled with `C` whose
//! exits are the branches; `apply(F, Args)` is a function dot labelled
//! with `F`'s name whose exits are the values F's clauses give through
//! `assign_func_value/1` (constants, or arguments of the call), plus a
//! dashed "computed" exit when they cannot all be told; anything else (a
//! variable bound by the expectation, `get/2`...) is a dashed arrow to `?`.
//! A situation whose type has a recovery protocol is linked to the
//! recovery DM. [`overview`] draws the program one box per DM, with its
//! calls and recovery protocols.

use crate::ir::{none_marker, Ir, IrDm, IrFnValue};
use sitlog_graph::{Diagram, DmGraph, Edge, EdgeKind, Node, NodeKind, ReturnDot, SituationKind};
use sitlog_runtime::machine::Kind;
use sitlog_runtime::{Store, Term, Value, Var};
use sitlog_syntax::write::{write_term, TermSource, VarLabel, View, WriteOptions};
use sitlog_syntax::Atom;
use std::collections::HashMap;

mod overview;
pub use overview::overview;

/// What to draw.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Only this DM (by name); `None`: the whole program.
    pub dm: Option<String>,
    /// The main DM's name (default `main`, else the first DM).
    pub main: Option<String>,
    /// The diagram's title (the application's name).
    pub title: String,
}

/// The store's terms with the DM's source variable names.
pub(crate) struct Named<'a> {
    store: &'a Store,
    names: HashMap<Var, &'a str>,
}

impl TermSource for Named<'_> {
    type Ref = Term;
    fn view(&self, t: Term) -> View<'_, Term> {
        match self.store.value(t) {
            Value::Var(v) => match self.names.get(&v) {
                Some(n) => View::Var(VarLabel::Named(n)),
                None => View::Var(VarLabel::Numbered(u64::from(v.index()))),
            },
            Value::Atom(a) => View::Atom(a),
            Value::Int(i) => View::Int(i),
            Value::BigInt(s) => View::BigInt(s),
            Value::Float(f) => View::Float(f),
            Value::Compound(name, args) => View::Compound(name, args),
        }
    }
}

impl<'a> Named<'a> {
    pub(crate) fn new(store: &'a Store, dm: &'a IrDm) -> Named<'a> {
        let names = dm
            .var_names
            .iter()
            .filter_map(|(t, n)| store.var_of(*t).map(|v| (v, &**n)))
            .collect();
        Named { store, names }
    }
    pub(crate) fn text(&self, t: Term) -> String {
        write_term(self, t, WriteOptions::writeq())
    }
}

/// The fields of a situation template.
pub(crate) struct Sit {
    id: Term,
    pub(crate) ty: Term,
    pub(crate) emb: Term,
    arcs: Vec<(Term, Term, Term)>,
}

pub(crate) fn fields(store: &Store, template: Term) -> Sit {
    let a = store.args(template).to_vec();
    let get = |i: usize| a.get(i).copied().unwrap_or(template);
    let arcs = store
        .list_to_vec(get(8))
        .unwrap_or_default()
        .into_iter()
        .map(|arc| {
            let x = store.args(arc);
            (x[0], x[1], x[2])
        })
        .collect();
    Sit {
        id: get(1),
        ty: get(2),
        emb: get(6),
        arcs,
    }
}

pub(crate) fn is_none(store: &Store, t: Term) -> bool {
    store.atom_of(t) == Some(none_marker())
}

/// Terms whose value is computed when the arc is taken.
fn is_evaluated(store: &Store, t: Term) -> bool {
    match store.functor(t) {
        Some((f, 2)) => matches!(
            f.as_str(),
            "apply" | "get" | "set" | "inc" | ";" | "|" | "->"
        ),
        _ => false,
    }
}

/// Whether `a` (a value, evaluated parts unknown) may unify with `b`.
fn may_unify(store: &Store, a: Term, b: Term) -> bool {
    let mut work = vec![(a, b)];
    while let Some((a, b)) = work.pop() {
        if store.is_var(a) || store.is_var(b) || is_evaluated(store, a) || is_evaluated(store, b) {
            continue;
        }
        match (store.value(a), store.value(b)) {
            (Value::Compound(f, xs), Value::Compound(g, ys)) => {
                if f != g || xs.len() != ys.len() {
                    return false;
                }
                work.extend(xs.iter().copied().zip(ys.iter().copied()));
            }
            (Value::Atom(x), Value::Atom(y)) if x == y => {}
            (Value::Int(x), Value::Int(y)) if x == y => {}
            (Value::Float(x), Value::Float(y)) if x.to_bits() == y.to_bits() => {}
            (Value::BigInt(x), Value::BigInt(y)) if x == y => {}
            _ => return false,
        }
    }
    true
}

/// Whether every value unifies with id pattern `b` (an atom, or distinct variables as arguments).
fn always_matches(store: &Store, b: Term) -> bool {
    if store.is_var(b) {
        return true;
    }
    let args = store.args(b);
    let mut seen = Vec::new();
    for &x in args {
        match store.var_of(x) {
            Some(v) if !seen.contains(&v) => seen.push(v),
            _ => return false,
        }
    }
    true
}

/// Where a next-situation term may lead.
enum Target {
    /// The situations (several: a disjunction) with their ids, and the term as written.
    Sits(Vec<(usize, String)>, String),
    Fun {
        label: String,
        what: String,
        exits: Vec<(String, Target)>,
        computed: bool,
    },
    Computed(String),
}

struct Cx<'a> {
    ir: &'a Ir,
    store: &'a Store,
    named: Named<'a>,
    sits: Vec<Sit>,
    /// Situations by the functor of their id.
    by_functor: HashMap<(Atom, usize), Vec<usize>>,
    /// Situations whose id is a variable.
    var_ids: Vec<usize>,
}

impl Cx<'_> {
    fn candidates(&self, n: Term) -> Vec<(usize, String)> {
        let mut out = Vec::new();
        // situations whose id has n's functor, or is a variable, in order
        let mut ixs: Vec<usize> = match self.store.functor(n) {
            Some(f) if !is_evaluated(self.store, n) => {
                self.by_functor.get(&f).cloned().unwrap_or_default()
            }
            _ => (0..self.sits.len()).collect(),
        };
        if !self.var_ids.is_empty() {
            ixs.extend(&self.var_ids);
            ixs.sort_unstable();
            ixs.dedup();
        }
        for i in ixs {
            let s = &self.sits[i];
            if is_none(self.store, s.id) {
                continue;
            }
            if may_unify(self.store, n, s.id) {
                out.push((i, self.named.text(s.id)));
                if always_matches(self.store, s.id) {
                    break;
                }
            }
        }
        out
    }

    fn target(&self, n: Term, depth: usize) -> Target {
        let store = self.store;
        if depth > 8 {
            return Target::Computed(self.named.text(n));
        }
        if store.is_var(n) {
            return Target::Computed(self.named.text(n));
        }
        if let Some((f, 2)) = store.functor(n) {
            let args = store.args(n);
            let cond = if f.as_str() == ";" || f.as_str() == "|" {
                store
                    .compound_args(args[0], Atom::intern("->"), 2)
                    .map(|c| (c, args[1]))
            } else {
                None
            };
            if let Some((c, rest)) = cond {
                let (guard, then) = (c[0], c[1]);
                let otherwise = store
                    .compound_args(rest, Atom::intern("->"), 2)
                    .map_or(rest, |o| o[1]);
                return Target::Fun {
                    label: self.named.text(guard),
                    what: "conditional".to_owned(),
                    exits: vec![
                        ("then".to_owned(), self.target(then, depth + 1)),
                        ("otherwise".to_owned(), self.target(otherwise, depth + 1)),
                    ],
                    computed: false,
                };
            }
            if f.as_str() == "apply" {
                let call = args[0];
                let call_args = store.list_to_vec(args[1]).unwrap_or_default();
                let label = store.functor(call).map_or_else(
                    || self.named.text(call),
                    |(name, _)| name.as_str().to_owned(),
                );
                let values = store.functor(call).and_then(|(name, arity)| {
                    self.ir
                        .function_values
                        .iter()
                        .find(|f| f.name == name && f.arity == arity)
                        .and_then(|f| f.values.as_ref())
                });
                let mut exits = Vec::new();
                let mut computed = true;
                if let Some(vs) = values.filter(|vs| !vs.is_empty()) {
                    computed = false;
                    for v in vs {
                        let t = match *v {
                            IrFnValue::Term(t) => Some(t),
                            IrFnValue::Arg(i) => call_args.get(i).copied(),
                        };
                        match t {
                            Some(t) => {
                                let text = write_term(store, t, WriteOptions::writeq());
                                let text = if matches!(v, IrFnValue::Arg(_)) {
                                    self.named.text(t)
                                } else {
                                    text
                                };
                                if !exits.iter().any(|(l, _)| *l == text) {
                                    exits.push((text, self.target(t, depth + 1)));
                                }
                            }
                            None => computed = true,
                        }
                    }
                }
                return Target::Fun {
                    label,
                    what: format!("user function {}", self.named.text(call)),
                    exits,
                    computed,
                };
            }
            if is_evaluated(store, n) {
                return Target::Computed(self.named.text(n));
            }
        }
        Target::Sits(self.candidates(n), self.named.text(n))
    }
}

/// Builds the diagram of `ir` (the whole program, or `options.dm`).
pub fn diagram(ir: &Ir, options: &Options) -> Result<Diagram, String> {
    let store = &ir.store;
    let main_name = options.main.as_deref().unwrap_or("main");
    let main_ix = ir
        .dms
        .iter()
        .position(|d| d.name.as_str() == main_name)
        .or(if ir.dms.is_empty() { None } else { Some(0) });
    let drawn: Vec<usize> = match &options.dm {
        Some(name) => {
            let i = ir
                .dms
                .iter()
                .position(|d| d.name.as_str() == name)
                .ok_or_else(|| {
                    let names: Vec<&str> = ir.dms.iter().map(|d| d.name.as_str()).collect();
                    format!("no DM named `{name}` (the DMs are: {})", names.join(", "))
                })?;
            vec![i]
        }
        None => (0..ir.dms.len()).collect(),
    };
    let mut d = Diagram {
        title: options.title.clone(),
        ..Diagram::default()
    };
    let sit_id = |dm: usize, s: usize| format!("d{dm}.s{s}");
    // Pipes and control links, made once every DM is drawn.
    let mut calls: Vec<(usize, usize, usize, String, String)> = Vec::new(); // (dm, sit, callee, call text, location)
    for &di in &drawn {
        let dm = &ir.dms[di];
        let named = Named::new(store, dm);
        let sits: Vec<Sit> = dm
            .situations
            .iter()
            .map(|s| fields(store, s.template))
            .collect();
        let mut by_functor: HashMap<(Atom, usize), Vec<usize>> = HashMap::new();
        let mut var_ids = Vec::new();
        for (i, s) in sits.iter().enumerate() {
            match store.functor(s.id) {
                Some(f) => by_functor.entry(f).or_default().push(i),
                None => var_ids.push(i),
            }
        }
        let cx = Cx {
            ir,
            store,
            named,
            sits,
            by_functor,
            var_ids,
        };
        let mut g = DmGraph {
            id: format!("d{di}"),
            name: cx.named.text(dm.head),
            location: dm.location.clone(),
            nodes: Vec::new(),
            edges: Vec::new(),
        };
        for (si, (s, irs)) in cx.sits.iter().zip(&dm.situations).enumerate() {
            let id = sit_id(di, si);
            let mut returns = Vec::new();
            let mut embedded = None;
            if irs.kind == Kind::Recursive && !is_none(store, s.emb) {
                embedded = Some(cx.named.text(s.emb));
                if let Some((name, _)) = store.functor(s.emb) {
                    if let Some(ci) = ir.dm_by_name(name) {
                        let ci = ci as usize;
                        let cdm = &ir.dms[ci];
                        let cnamed = Named::new(store, cdm);
                        for (k, fs) in cdm.situations.iter().enumerate() {
                            if fs.kind == Kind::Final {
                                let f = fields(store, fs.template);
                                returns.push((
                                    k,
                                    f.id,
                                    ReturnDot {
                                        id: format!("{id}.r{}", returns.len()),
                                        final_id: cnamed.text(f.id),
                                        location: fs.location.clone(),
                                    },
                                ));
                            }
                        }
                        calls.push((
                            di,
                            si,
                            ci,
                            embedded.clone().unwrap_or_default(),
                            irs.location.clone(),
                        ));
                    }
                }
            }
            // Which return dot each arc leaves from: for each final, the
            // first arc whose expectation may unify with its id.
            let mut port: Vec<Option<String>> = vec![None; s.arcs.len()];
            for (_, fid, dot) in &returns {
                if let Some(j) = s.arcs.iter().position(|a| may_unify(store, a.0, *fid)) {
                    if port[j].is_none() {
                        port[j] = Some(dot.id.clone());
                    }
                }
            }
            let kind = match irs.kind {
                Kind::Final => SituationKind::Final,
                Kind::Recursive => SituationKind::Recursive,
                Kind::Perceptual => SituationKind::Perceptual,
            };
            g.nodes.push(Node {
                id: id.clone(),
                kind: NodeKind::Situation,
                label: if is_none(store, s.id) {
                    "(no id)".to_owned()
                } else {
                    cx.named.text(s.id)
                },
                situation_type: (!is_none(store, s.ty)).then(|| cx.named.text(s.ty)),
                situation_kind: Some(kind),
                initial: si == 0,
                functor: store.functor(s.id).map(|(n, a)| {
                    format!(
                        "{}/{a}",
                        sitlog_syntax::write::writeq(&cx.named, Term::atom(n))
                    )
                }),
                embedded_dm: embedded,
                returns: returns.into_iter().map(|(_, _, r)| r).collect(),
                detail: None,
                link: None,
                location: irs.location.clone(),
            });
            for (j, &(e, a, n)) in s.arcs.iter().enumerate() {
                let loc = irs
                    .arc_locations
                    .get(j)
                    .cloned()
                    .unwrap_or_else(|| irs.location.clone());
                let label = format!("{} : {}", cx.named.text(e), cx.named.text(a));
                let base = format!("{id}.a{j}");
                let t = cx.target(n, 0);
                emit(
                    &mut g,
                    &t,
                    (&id, port[j].clone()),
                    label,
                    EdgeKind::Arc,
                    &base,
                    &loc,
                    di,
                    Some(cx.named.text(e)),
                );
            }
        }
        d.dms.push(g);
    }
    // Pipes into embedded DMs and control links back.
    let mut externals: Vec<(usize, String)> = Vec::new();
    for (di, si, ci, call, loc) in calls {
        let from = sit_id(di, si);
        let pipe_id = format!("e:{from}.pipe");
        if drawn.contains(&ci) && !ir.dms[ci].situations.is_empty() {
            d.links.push(Edge {
                id: pipe_id,
                kind: EdgeKind::Pipe,
                from: from.clone(),
                from_port: None,
                to: sit_id(ci, 0),
                to_port: None,
                label: call,
                expectation: None,
                location: loc.clone(),
            });
            let node = d.dms[drawn.iter().position(|&x| x == di).unwrap_or(0)]
                .nodes
                .iter()
                .find(|n| n.id == from)
                .cloned();
            let Some(node) = node else { continue };
            let finals: Vec<usize> = ir.dms[ci]
                .situations
                .iter()
                .enumerate()
                .filter(|(_, s)| s.kind == Kind::Final)
                .map(|(k, _)| k)
                .collect();
            for (r, k) in node.returns.iter().zip(finals) {
                d.links.push(Edge {
                    id: format!("e:{}.ctl", r.id),
                    kind: EdgeKind::Control,
                    from: sit_id(ci, k),
                    from_port: None,
                    to: from.clone(),
                    to_port: Some(r.id.clone()),
                    label: String::new(),
                    expectation: None,
                    location: r.location.clone(),
                });
            }
        } else {
            let xid = format!("x{ci}");
            if !externals.iter().any(|(c, _)| *c == ci) {
                externals.push((ci, xid.clone()));
                d.externals.push(external(store, &ir.dms[ci], xid.clone()));
            }
            d.links.push(Edge {
                id: pipe_id,
                kind: EdgeKind::Pipe,
                from,
                from_port: None,
                to: xid,
                to_port: None,
                label: call,
                expectation: None,
                location: loc,
            });
        }
    }
    // Recovery protocols: from each situation of a type that has one to
    // the recovery DM (its initial situation, or its box when not drawn).
    for &di in &drawn {
        let dm = &ir.dms[di];
        for (si, s) in dm.situations.iter().enumerate() {
            let Some(ri) = recovery_of(ir, fields(store, s.template).ty) else {
                continue;
            };
            let (ty, ri) = ri;
            let to = if drawn.contains(&ri) && !ir.dms[ri].situations.is_empty() {
                sit_id(ri, 0)
            } else {
                let xid = format!("x{ri}");
                if !externals.iter().any(|(c, _)| *c == ri) {
                    externals.push((ri, xid.clone()));
                    d.externals.push(external(store, &ir.dms[ri], xid.clone()));
                }
                xid
            };
            d.links.push(Edge {
                id: format!("e:{}.recovery", sit_id(di, si)),
                kind: EdgeKind::Recovery,
                from: sit_id(di, si),
                from_port: None,
                to,
                to_port: None,
                label: format!("recovery ({ty})"),
                expectation: None,
                location: s.location.clone(),
            });
        }
    }
    // The task's out_arg leaves the main DM.
    if let Some(mi) = main_ix.filter(|m| drawn.contains(m)) {
        d.externals.push(Node {
            id: "out_arg".to_owned(),
            kind: NodeKind::OutArg,
            label: "out_arg".to_owned(),
            situation_type: None,
            situation_kind: None,
            initial: false,
            functor: None,
            embedded_dm: None,
            returns: Vec::new(),
            detail: None,
            link: None,
            location: ir.dms[mi].location.clone(),
        });
        d.links.push(Edge {
            id: "e:out_arg".to_owned(),
            kind: EdgeKind::OutArg,
            from: format!("d{mi}"),
            from_port: None,
            to: "out_arg".to_owned(),
            to_port: None,
            label: String::new(),
            expectation: None,
            location: ir.dms[mi].location.clone(),
        });
    }
    Ok(d)
}

/// The box of a DM that is not drawn.
fn external(store: &Store, dm: &IrDm, id: String) -> Node {
    Node {
        id,
        kind: NodeKind::ExternalDm,
        label: Named::new(store, dm).text(dm.head),
        situation_type: None,
        situation_kind: None,
        initial: false,
        functor: None,
        embedded_dm: None,
        returns: Vec::new(),
        detail: None,
        link: None,
        location: dm.location.clone(),
    }
}

/// The recovery protocol of a situation type (`type ==> dm.` in
/// `recovery_protocols.pl`, by the type's name): the type and the DM's index.
pub(crate) fn recovery_of(ir: &Ir, ty: Term) -> Option<(Atom, usize)> {
    let (name, _) = ir.store.functor(ty)?;
    let (_, dm) = ir.recovery.iter().find(|(t, _)| *t == name)?;
    Some((name, ir.dm_by_name(*dm)? as usize))
}

/// Draws the way from `from` along `t`.
#[allow(clippy::too_many_arguments)]
fn emit(
    g: &mut DmGraph,
    t: &Target,
    from: (&str, Option<String>),
    label: String,
    kind: EdgeKind,
    base: &str,
    loc: &str,
    di: usize,
    expectation: Option<String>,
) {
    let edge = |g: &mut DmGraph, to: String, label: String, kind: EdgeKind, id: String| {
        g.edges.push(Edge {
            id: format!("e:{id}"),
            kind,
            from: from.0.to_owned(),
            from_port: from.1.clone(),
            to,
            to_port: None,
            label,
            expectation: expectation.clone(),
            location: loc.to_owned(),
        });
    };
    let plain = |kind: NodeKind, id: String, label: String| Node {
        id,
        kind,
        label,
        situation_type: None,
        situation_kind: None,
        initial: false,
        functor: None,
        embedded_dm: None,
        returns: Vec::new(),
        detail: None,
        link: None,
        location: loc.to_owned(),
    };
    match t {
        Target::Sits(ks, _) if ks.len() == 1 => {
            edge(
                g,
                format!("d{di}.s{}", ks[0].0),
                label,
                kind,
                base.to_owned(),
            );
        }
        Target::Sits(ks, text) if ks.is_empty() => {
            let cid = format!("{base}.c");
            g.nodes
                .push(plain(NodeKind::Computed, cid.clone(), text.clone()));
            edge(g, cid, label, EdgeKind::Computed, base.to_owned());
        }
        Target::Sits(ks, text) => {
            let vid = format!("{base}.v");
            g.nodes
                .push(plain(NodeKind::Disjunction, vid.clone(), text.clone()));
            edge(g, vid.clone(), label, kind, base.to_owned());
            for (k, cond) in ks {
                let cond = cond.clone();
                g.edges.push(Edge {
                    id: format!("e:{vid}.{k}"),
                    kind: EdgeKind::Exit,
                    from: vid.clone(),
                    from_port: None,
                    to: format!("d{di}.s{k}"),
                    to_port: None,
                    label: cond,
                    expectation: None,
                    location: loc.to_owned(),
                });
            }
        }
        Target::Fun {
            label: fun,
            what,
            exits,
            computed,
        } => {
            let fid = format!("{base}.f");
            let mut node = plain(NodeKind::Function, fid.clone(), fun.clone());
            node.detail = Some(what.clone());
            g.nodes.push(node);
            edge(g, fid.clone(), label, kind, base.to_owned());
            for (x, (cond, t)) in exits.iter().enumerate() {
                emit(
                    g,
                    t,
                    (&fid, None),
                    cond.clone(),
                    EdgeKind::Exit,
                    &format!("{fid}.x{x}"),
                    loc,
                    di,
                    None,
                );
            }
            if *computed {
                let cid = format!("{fid}.c");
                g.nodes
                    .push(plain(NodeKind::Computed, cid.clone(), fun.clone()));
                g.edges.push(Edge {
                    id: format!("e:{cid}"),
                    kind: EdgeKind::Computed,
                    from: fid.clone(),
                    from_port: None,
                    to: cid,
                    to_port: None,
                    label: "computed".to_owned(),
                    expectation: None,
                    location: loc.to_owned(),
                });
            }
        }
        Target::Computed(text) => {
            let cid = format!("{base}.c");
            g.nodes
                .push(plain(NodeKind::Computed, cid.clone(), text.clone()));
            edge(g, cid, label, EdgeKind::Computed, base.to_owned());
        }
    }
}
