//! Type inference over the IR: which SitLog values are provably integers,
//! floats, atoms of a finite set or ground terms of a fixed shape, and which
//! situations can run on such native values (the *typed plan* the code
//! generator follows). Pure: reads the [`Ir`], never fails, never rejects a
//! program; whatever it cannot type stays a term (with the reason, for
//! `sitlogc build --explain-types`).
//!
//! What is typed:
//! - a **local variable** gets the join of its default value's type and of
//!   every value the DM's own code writes into it (`set(n, C)` with C a
//!   constant; `inc(n, _)` keeps an int an int and a float a float). Code
//!   the compiler cannot see (user functions through `var_op`, the
//!   evaluator on a constructed term) may still write anything, so typed
//!   code *loads* the frame with a check and falls back to the untyped path
//!   when a value does not fit: the type is a fact about the DM's own code
//!   and a guard at run time, never a rejection.
//! - a **DM parameter** (a variable of the head) gets the type its uses in
//!   typed situations demand (compared arithmetically with an int: int);
//!   any DM may be started from the command line with any argument, so this
//!   is always checked when the frame is loaded.
//! - an **arc variable** is typed when its first occurrence takes the value
//!   of a typed local (`inc(n, N)`, `get(n, N)`).
//! - a **situation** is typed when its id is an atom, it has no
//!   `in_arg`/`out_arg`/`prog`/`diag_mod`/`embedded_dm`, every expectation
//!   is a constant, every action a constant or a list of constants and
//!   `get`/`set`/`inc` of typed locals, and every next situation a constant
//!   situation of the DM or a conditional on an arithmetic comparison of
//!   typed numbers, or on `==`/`\==` of typed atoms. A run of typed situations executes on native values,
//!   touching no term unless the history is kept or observed.
//! - **globals** are typed like locals (for the listing); generated code
//!   keeps them as terms.

use crate::ir::{none_marker, Ir, IrDm};
use sitlog_runtime::machine::Kind;
use sitlog_runtime::{eval, ArithCmp, Store, Term, Value};
use sitlog_syntax::{atoms, Atom};
use std::collections::HashMap;
use std::fmt::Write as _;

/// Largest finite atom set kept as a type (beyond it: a term).
pub const MAX_ATOMS: usize = 64;
/// Deepest fixed shape kept as a type.
const MAX_DEPTH: usize = 8;

/// The type of a SitLog value.
#[derive(Clone, Debug, PartialEq)]
pub enum Ty {
    /// No value seen yet (the bottom of the lattice; never in a result).
    None,
    Int,
    Float,
    /// One of these atoms (sorted by text).
    Atoms(Vec<Atom>),
    /// A compound `name(T1, ..., Tn)` of this shape, ground.
    Shape(Atom, Vec<Ty>),
    /// Anything: stays a term.
    Term,
}

impl Ty {
    /// The least type holding both.
    pub fn join(&self, other: &Ty) -> Ty {
        match (self, other) {
            (Ty::None, t) | (t, Ty::None) => t.clone(),
            (Ty::Int, Ty::Int) => Ty::Int,
            (Ty::Float, Ty::Float) => Ty::Float,
            (Ty::Atoms(a), Ty::Atoms(b)) => {
                let mut all = a.clone();
                for x in b {
                    if !all.contains(x) {
                        all.push(*x);
                    }
                }
                if all.len() > MAX_ATOMS {
                    return Ty::Term;
                }
                all.sort_by(|x, y| x.as_str().cmp(y.as_str()));
                Ty::Atoms(all)
            }
            (Ty::Shape(f, a), Ty::Shape(g, b)) if f == g && a.len() == b.len() => {
                let args: Vec<Ty> = a.iter().zip(b).map(|(x, y)| x.join(y)).collect();
                if args.contains(&Ty::Term) {
                    Ty::Term
                } else {
                    Ty::Shape(*f, args)
                }
            }
            _ => Ty::Term,
        }
    }

    /// Whether generated code keeps a value of this type natively.
    pub fn is_native(&self) -> bool {
        matches!(self, Ty::Int | Ty::Float | Ty::Atoms(_))
    }

    /// The type of a ground term (`Term` for a non-ground one or a big integer).
    pub fn of_ground(store: &Store, t: Term) -> Ty {
        Self::of_ground_at(store, t, 0)
    }

    fn of_ground_at(store: &Store, t: Term, depth: usize) -> Ty {
        match store.value(t) {
            Value::Int(_) => Ty::Int,
            Value::Float(_) => Ty::Float,
            Value::Atom(a) => Ty::Atoms(vec![a]),
            Value::Compound(name, args) if depth < MAX_DEPTH => {
                let args: Vec<Ty> = args
                    .iter()
                    .map(|&a| Self::of_ground_at(store, a, depth + 1))
                    .collect();
                if args.contains(&Ty::Term) {
                    Ty::Term
                } else {
                    Ty::Shape(name, args)
                }
            }
            _ => Ty::Term,
        }
    }
}

impl std::fmt::Display for Ty {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Ty::None => f.write_str("none"),
            Ty::Int => f.write_str("int"),
            Ty::Float => f.write_str("float"),
            Ty::Term => f.write_str("term"),
            Ty::Atoms(atoms) => {
                f.write_str("{")?;
                for (i, a) in atoms.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    f.write_str(&quote_atom(a.as_str()))?;
                }
                f.write_str("}")
            }
            Ty::Shape(name, args) => {
                if *name == atoms::DOT && args.len() == 2 {
                    write!(f, "[{} | {}]", args[0], args[1])
                } else {
                    write!(f, "{}(", quote_atom(name.as_str()))?;
                    for (i, a) in args.iter().enumerate() {
                        if i > 0 {
                            f.write_str(", ")?;
                        }
                        write!(f, "{a}")?;
                    }
                    f.write_str(")")
                }
            }
        }
    }
}

/// `a float`, `an int`, `a term`, ...
fn an(ty: &Ty) -> String {
    match ty {
        Ty::Int => "an int".to_owned(),
        Ty::Atoms(_) => format!("an atom of {ty}"),
        _ => format!("a {ty}"),
    }
}

/// `writeq` of a term of `dm` with the source names of its variables.
fn show(store: &Store, dm: &IrDm, t: Term) -> String {
    let text = store.writeq(t);
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find("_G") {
        out.push_str(&rest[..i]);
        let digits: String = rest[i + 2..]
            .chars()
            .take_while(|c| c.is_ascii_digit())
            .collect();
        match digits.parse::<u32>() {
            Ok(v) if !digits.is_empty() => {
                out.push_str(&var_name(dm, v));
                rest = &rest[i + 2 + digits.len()..];
            }
            _ => {
                out.push_str("_G");
                rest = &rest[i + 2..];
            }
        }
    }
    out.push_str(rest);
    out
}

fn quote_atom(text: &str) -> String {
    let plain = text.chars().next().is_some_and(|c| c.is_ascii_lowercase())
        && text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if plain || text == "[]" {
        text.to_owned()
    } else {
        format!("'{}'", text.replace('\\', "\\\\").replace('\'', "\\'"))
    }
}

/// A variable's type and why.
#[derive(Clone, Debug, PartialEq)]
pub struct VarTy {
    pub name: String,
    pub ty: Ty,
    pub why: String,
}

/// The result of inference.
#[derive(Debug)]
pub struct Types {
    pub dms: Vec<DmTypes>,
    pub globals: Vec<VarTy>,
}

/// What inference found for one DM.
#[derive(Debug)]
pub struct DmTypes {
    /// Head parameters, by position (`None` for a non-variable argument).
    pub params: Vec<Option<VarTy>>,
    pub locals: Vec<VarTy>,
    /// Per situation, in order: its typed plan or why it has none.
    pub situations: Vec<Result<TSit, String>>,
}

impl DmTypes {
    /// Whether some situation runs typed.
    pub fn any_typed(&self) -> bool {
        self.situations.iter().any(|s| s.is_ok())
    }
    /// Locals the typed situations use (indices into `locals`), in order.
    pub fn frame_locals(&self) -> Vec<usize> {
        let mut used = Vec::new();
        for s in self.situations.iter().flatten() {
            s.locals_used(&mut used);
        }
        used.sort_unstable();
        used.dedup();
        used
    }
    /// Parameters the typed situations use, in order.
    pub fn frame_params(&self) -> Vec<usize> {
        let mut used = Vec::new();
        for s in self.situations.iter().flatten() {
            s.params_used(&mut used);
        }
        used.sort_unstable();
        used.dedup();
        used
    }
}

/// A typed value in a typed situation.
#[derive(Clone, Debug, PartialEq)]
pub enum TVal {
    /// The DM's local number `i` (in the frame).
    Local(usize),
    /// The DM's head parameter number `i` (in the frame).
    Param(usize),
    /// An arc variable bound by an earlier item (its store variable index).
    Var(u32),
    Int(i64),
    Float(f64),
    /// An atom (compared with `==`/`\==` against typed atoms).
    Atom(Atom),
}

/// A comparison in a typed conditional.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cmp {
    /// An arithmetic comparison of two numbers of one type.
    Arith(ArithCmp),
    /// `==` of two atoms.
    Identical,
    /// `\==` of two atoms.
    NotIdentical,
}

/// One element of a typed action list, or a typed action.
#[derive(Clone, Debug, PartialEq)]
pub enum TItem {
    /// `inc(n, V)`: the new value; `V` (fresh) takes it when `Some`.
    Inc { local: usize, bind: Option<u32> },
    /// `get(n, V)`: the value; `V` (fresh) takes it when `Some`.
    Get { local: usize, bind: Option<u32> },
    /// `set(n, C)`: C (a constant of the local's type) is the new value.
    Set { local: usize, value: Term },
    /// A constant (evaluates to itself).
    Const(Term),
}

/// What a typed arc does.
#[derive(Clone, Debug, PartialEq)]
pub enum TAction {
    /// A constant action (performed as one term).
    Const(Term),
    /// A written-out list: its elements evaluated and performed in order.
    List(Vec<TItem>),
}

/// A typed next situation.
#[derive(Clone, Debug, PartialEq)]
pub enum TNext {
    /// Situation `ix` of the DM, whose id is the atom.
    Sit(u32, Atom),
    /// `(A op B -> Then ; otherwise -> Else)` on typed numbers of one type,
    /// or `==`/`\==` on typed atoms.
    If {
        op: Cmp,
        float: bool,
        a: TVal,
        b: TVal,
        then: Box<TNext>,
        other: Box<TNext>,
    },
}

/// A typed arc.
#[derive(Clone, Debug, PartialEq)]
pub struct TArc {
    /// A constant expectation (no variables, evaluates to itself).
    pub expectation: Term,
    pub action: TAction,
    pub next: TNext,
}

/// A situation's typed plan.
#[derive(Clone, Debug, PartialEq)]
pub enum TSit {
    /// A final situation that leaves the pipe as it is.
    Final { id: Atom },
    /// A perceptual situation (`neutral` included).
    Perceptual {
        id: Atom,
        type_name: Atom,
        /// The neutral rule on one `empty` arc: always taken (D-14).
        always_first: bool,
        arcs: Vec<TArc>,
    },
}

impl TSit {
    pub fn id(&self) -> Atom {
        match self {
            TSit::Final { id } | TSit::Perceptual { id, .. } => *id,
        }
    }

    /// The constant terms the plan uses (expectations, actions, elements, set values).
    pub fn constants(&self, out: &mut Vec<Term>) {
        if let TSit::Perceptual { arcs, .. } = self {
            for arc in arcs {
                out.push(arc.expectation);
                match &arc.action {
                    TAction::Const(c) => out.push(*c),
                    TAction::List(items) => {
                        for it in items {
                            match it {
                                TItem::Const(c) | TItem::Set { value: c, .. } => out.push(*c),
                                _ => {}
                            }
                        }
                    }
                }
            }
        }
    }

    fn locals_used(&self, out: &mut Vec<usize>) {
        if let TSit::Perceptual { arcs, .. } = self {
            for arc in arcs {
                if let TAction::List(items) = &arc.action {
                    for it in items {
                        match it {
                            TItem::Inc { local, .. }
                            | TItem::Get { local, .. }
                            | TItem::Set { local, .. } => out.push(*local),
                            TItem::Const(_) => {}
                        }
                    }
                }
                arc.next.vals(&mut |v| {
                    if let TVal::Local(i) = v {
                        out.push(*i)
                    }
                });
            }
        }
    }

    fn params_used(&self, out: &mut Vec<usize>) {
        if let TSit::Perceptual { arcs, .. } = self {
            for arc in arcs {
                arc.next.vals(&mut |v| {
                    if let TVal::Param(i) = v {
                        out.push(*i)
                    }
                });
            }
        }
    }
}

impl TNext {
    fn vals(&self, f: &mut dyn FnMut(&TVal)) {
        if let TNext::If {
            a, b, then, other, ..
        } = self
        {
            f(a);
            f(b);
            then.vals(f);
            other.vals(f);
        }
    }
}

/// Runs inference over a lowered program.
pub fn infer(ir: &Ir) -> Types {
    let store = &ir.store;
    let mut dms = Vec::new();
    for dm in &ir.dms {
        dms.push(infer_dm(ir, dm));
    }
    // Globals: initial values joined with the constant writes of every DM
    // where the name is not a local.
    let mut globals = Vec::new();
    for &(name, init) in &ir.globals {
        let mut ty = Ty::of_ground(store, init);
        let mut why = if ty == Ty::Term {
            format!("initial value `{}` is not ground", store.writeq(init))
        } else {
            format!("initial value `{}`", store.writeq(init))
        };
        for dm in &ir.dms {
            if dm.locals.iter().any(|(n, _)| *n == name) {
                continue;
            }
            let writes = writes_of(store, dm, name);
            (ty, why) = join_writes(store, dm, ty, why, &writes);
        }
        globals.push(VarTy {
            name: name.as_str().to_owned(),
            ty,
            why,
        });
    }
    Types { dms, globals }
}

/// A write into a SitLog variable found in a DM's code.
enum Write {
    Set(Term),
    Inc,
    /// `set`/`inc` whose variable name is not written out, or code that may
    /// write any variable (a user function, an unknown evaluation).
    Opaque(String),
}

fn join_writes(
    store: &Store,
    dm: &IrDm,
    mut ty: Ty,
    mut why: String,
    writes: &[Write],
) -> (Ty, String) {
    for w in writes {
        if ty == Ty::Term {
            break;
        }
        match w {
            Write::Set(v) => {
                let t = Ty::of_ground(store, *v);
                let joined = ty.join(&t);
                if joined == Ty::Term {
                    why = format!(
                        "`set` to `{}` ({}) besides {why}",
                        show(store, dm, *v),
                        an(&t)
                    );
                } else if joined != ty {
                    why = format!("{why}, `set` to `{}`", show(store, dm, *v));
                }
                ty = joined;
            }
            Write::Inc => {
                if !matches!(ty, Ty::Int | Ty::Float) {
                    why = format!("`inc` of {} ({why})", an(&ty));
                    ty = Ty::Term;
                }
            }
            Write::Opaque(what) => {
                if !why.contains(what.as_str()) {
                    why = format!("{why}; {what}: checked on load");
                }
            }
        }
    }
    (ty, why)
}

/// Every write into `name` in the code of `dm` (any field of any situation).
fn writes_of(store: &Store, dm: &IrDm, name: Atom) -> Vec<Write> {
    let mut out = Vec::new();
    for s in &dm.situations {
        let mut stack = vec![s.template];
        while let Some(t) = stack.pop() {
            if let Value::Compound(f, args) = store.value(t) {
                if args.len() == 2 && (f == atoms::SET || f == atoms::INC) {
                    match store.atom_of(args[0]) {
                        Some(n) if n == name => out.push(if f == atoms::SET {
                            Write::Set(args[1])
                        } else {
                            Write::Inc
                        }),
                        Some(_) => {}
                        None => out.push(Write::Opaque(format!(
                            "`{}` names its variable at run time",
                            show(store, dm, t)
                        ))),
                    }
                }
                stack.extend(args.iter());
            }
        }
    }
    out
}

fn var_name(dm: &IrDm, v: u32) -> String {
    dm.var_index_names
        .iter()
        .find(|(i, _)| *i == v)
        .map_or_else(|| format!("_G{v}"), |(_, n)| n.clone())
}

fn infer_dm(ir: &Ir, dm: &IrDm) -> DmTypes {
    let store = &ir.store;
    let locals: Vec<VarTy> = dm
        .locals
        .iter()
        .map(|&(name, init)| {
            let ty = Ty::of_ground(store, init);
            let why = if ty == Ty::Term {
                format!("default `{}` is not ground", store.writeq(init))
            } else {
                format!("default `{}`", store.writeq(init))
            };
            let writes = writes_of(store, dm, name);
            let (ty, why) = join_writes(store, dm, ty, why, &writes);
            let why = if writes.iter().any(|w| matches!(w, Write::Inc)) && ty != Ty::Term {
                format!("{why}; `inc` keeps it {}", an(&ty))
            } else {
                why
            };
            VarTy {
                name: name.as_str().to_owned(),
                ty,
                why,
            }
        })
        .collect();
    let head_vars: Vec<Option<u32>> = store
        .args(dm.head)
        .iter()
        .map(|&a| match store.value(a) {
            Value::Var(v) => Some(v.index()),
            _ => None,
        })
        .collect();
    let distinct_params = {
        let mut seen = Vec::new();
        head_vars
            .iter()
            .all(|v| v.is_some_and(|v| !seen.contains(&v) && (seen.push(v), true).1))
    };
    let mut cx = DmCx {
        store,
        dm,
        locals: &locals,
        head_vars: &head_vars,
        params: vec![Ty::None; head_vars.len()],
    };
    let mut situations = Vec::new();
    for ix in 0..dm.situations.len() {
        let r = if distinct_params {
            cx.situation(ix)
        } else {
            Err("the DM's head has non-variable or repeated parameters".to_owned())
        };
        situations.push(r);
    }
    // A typed final situation alone gains nothing: the DM runs on terms.
    if !situations
        .iter()
        .any(|s| matches!(s, Ok(TSit::Perceptual { .. })))
    {
        for s in &mut situations {
            if s.is_ok() {
                *s = Err("no other situation of the DM runs typed".to_owned());
            }
        }
    }
    // A parameter whose demanded types disagree: its situations stay untyped.
    let bad: Vec<usize> = (0..cx.params.len())
        .filter(|&i| cx.params[i] == Ty::Term)
        .collect();
    if !bad.is_empty() {
        for s in &mut situations {
            if let Ok(t) = s {
                let mut used = Vec::new();
                t.params_used(&mut used);
                if let Some(&i) = used.iter().find(|i| bad.contains(i)) {
                    *s = Err(format!(
                        "parameter `{}` is compared both as an int and as a float",
                        var_name(dm, head_vars[i].unwrap_or(0))
                    ));
                }
            }
        }
    }
    let params = head_vars
        .iter()
        .enumerate()
        .map(|(i, v)| {
            v.map(|v| {
                let (ty, why) = match &cx.params[i] {
                    Ty::None => (Ty::Term, "not used by typed code".to_owned()),
                    Ty::Term => (
                        Ty::Term,
                        "compared both as an int and as a float".to_owned(),
                    ),
                    t => (t.clone(), String::new()),
                };
                let why = match ty {
                    Ty::Term => why,
                    _ => format!("compared with {} in typed code; checked on entry", an(&ty)),
                };
                VarTy {
                    name: var_name(dm, v),
                    ty,
                    why,
                }
            })
        })
        .collect();
    DmTypes {
        params,
        locals,
        situations,
    }
}

struct DmCx<'a> {
    store: &'a Store,
    dm: &'a IrDm,
    locals: &'a [VarTy],
    head_vars: &'a [Option<u32>],
    /// Types the typed code demands of each parameter.
    params: Vec<Ty>,
}

const IN_ARG: usize = 3;
const PROG: usize = 5;
const EMBEDDED_DM: usize = 6;
const DIAG_MOD: usize = 7;
const OUT_ARG: usize = 4;

impl DmCx<'_> {
    fn present(&self, t: Term) -> bool {
        self.store.atom_of(t) != Some(none_marker())
    }

    fn situation(&mut self, ix: usize) -> Result<TSit, String> {
        let store = self.store;
        let s = &self.dm.situations[ix];
        let f = store.args(s.template);
        let Some(id) = store.atom_of(f[1]).filter(|&a| a != none_marker()) else {
            return Err(format!(
                "its id `{}` is not an atom",
                show(store, self.dm, f[1])
            ));
        };
        let Some(type_name) = store.atom_of(f[2]) else {
            return Err(format!(
                "its type `{}` is not an atom",
                show(store, self.dm, f[2])
            ));
        };
        for (i, what) in [
            (IN_ARG, "in_arg"),
            (OUT_ARG, "out_arg"),
            (PROG, "prog"),
            (EMBEDDED_DM, "embedded_dm"),
            (DIAG_MOD, "diag_mod"),
        ] {
            if self.present(f[i]) {
                return Err(format!("it has `{what}`"));
            }
        }
        match s.kind {
            Kind::Final => return Ok(TSit::Final { id }),
            Kind::Recursive => return Err("it is recursive".to_owned()),
            Kind::Perceptual => {}
        }
        let raw: Vec<[Term; 3]> = store
            .list_iter(f[8])
            .map(|arc| {
                let a = store.args(arc);
                [a[0], a[1], a[2]]
            })
            .collect();
        let always_first = type_name == atoms::NEUTRAL
            && raw.len() == 1
            && store.atom_of(raw[0][0]) == Some(atoms::EMPTY);
        let mut arcs = Vec::new();
        for (i, [e, a, n]) in raw.into_iter().enumerate() {
            let arc = self
                .arc(e, a, n)
                .map_err(|why| format!("arc {}: {why}", i + 1))?;
            arcs.push(arc);
        }
        Ok(TSit::Perceptual {
            id,
            type_name,
            always_first,
            arcs,
        })
    }

    fn constant(&self, t: Term) -> bool {
        self.store.is_ground(t) && inert(self.store, t)
    }

    fn local(&self, name: Atom) -> Result<usize, String> {
        let Some(i) = self.dm.locals.iter().position(|(n, _)| *n == name) else {
            return Err(format!(
                "`{name}` is not a local of the DM (globals stay terms)"
            ));
        };
        if !self.locals[i].ty.is_native() {
            return Err(format!("local `{name}` is {}", an(&self.locals[i].ty)));
        }
        Ok(i)
    }

    fn arc(&mut self, e: Term, a: Term, n: Term) -> Result<TArc, String> {
        let store = self.store;
        if !self.constant(e) {
            return Err(format!(
                "expectation `{}` is not a constant",
                show(store, self.dm, e)
            ));
        }
        // Arc variables bound so far, with their types.
        let mut bound: HashMap<u32, Ty> = HashMap::new();
        let action = match list_literal(store, a) {
            Some(items) if !self.constant(a) => {
                let mut out = Vec::new();
                for x in items {
                    out.push(self.item(x, &mut bound)?);
                }
                TAction::List(out)
            }
            _ if self.constant(a) => TAction::Const(a),
            _ => {
                return Err(format!(
                    "action `{}` is not a list of constants and `get`/`set`/`inc` of typed locals",
                    show(store, self.dm, a)
                ))
            }
        };
        let next = self.next(n, &bound)?;
        Ok(TArc {
            expectation: e,
            action,
            next,
        })
    }

    fn item(&self, x: Term, bound: &mut HashMap<u32, Ty>) -> Result<TItem, String> {
        let store = self.store;
        if self.constant(x) {
            return Ok(TItem::Const(x));
        }
        if let Value::Compound(op, &[var, arg]) = store.value(x) {
            if [atoms::GET, atoms::SET, atoms::INC].contains(&op) {
                let Some(name) = store.atom_of(var) else {
                    return Err(format!("`{}` names no variable", show(store, self.dm, x)));
                };
                let local = self.local(name)?;
                let ty = &self.locals[local].ty;
                if op == atoms::SET {
                    if !store.is_ground(arg) || Ty::of_ground(store, arg).join(ty) != *ty {
                        return Err(format!(
                            "`{}` sets a value not of type {ty}",
                            show(store, self.dm, x)
                        ));
                    }
                    return Ok(TItem::Set { local, value: arg });
                }
                if op == atoms::INC && !matches!(ty, Ty::Int | Ty::Float) {
                    return Err(format!("`inc` of {}", an(ty)));
                }
                let bind = match store.value(arg) {
                    Value::Var(v) if self.head_vars.contains(&Some(v.index())) => {
                        return Err(format!(
                            "`{}` binds a DM parameter",
                            show(store, self.dm, x)
                        ))
                    }
                    Value::Var(v) if !bound.contains_key(&v.index()) => {
                        bound.insert(v.index(), ty.clone());
                        // `_` and other singletons are bound all the same.
                        Some(v.index())
                    }
                    _ => {
                        return Err(format!(
                            "`{}`: the variable is not fresh",
                            show(store, self.dm, x)
                        ))
                    }
                };
                return Ok(if op == atoms::INC {
                    TItem::Inc { local, bind }
                } else {
                    TItem::Get { local, bind }
                });
            }
        }
        Err(format!(
            "action element `{}` is not a constant or `get`/`set`/`inc` of a typed local",
            show(store, self.dm, x)
        ))
    }

    fn next(&mut self, n: Term, bound: &HashMap<u32, Ty>) -> Result<TNext, String> {
        let store = self.store;
        if let Some(name) = store.atom_of(n) {
            // The first situation whose id unifies with the atom (D-21).
            for (i, s) in self.dm.situations.iter().enumerate() {
                let id = store.args(s.template)[1];
                match store.value(id) {
                    Value::Var(_) => break,
                    Value::Atom(a) if a == name => return Ok(TNext::Sit(i as u32, name)),
                    _ => {}
                }
            }
            return Err(format!(
                "next situation `{name}` is not an atom id of the DM"
            ));
        }
        if let Some((cond, then, other)) = eval::conditional(store, n) {
            let Value::Compound(op, &[l, r]) = store.value(cond) else {
                return Err(format!(
                    "condition `{}` is not a comparison",
                    show(store, self.dm, cond)
                ));
            };
            let op = match ArithCmp::from_atom(op) {
                Some(op) => Cmp::Arith(op),
                None if op.as_str() == "==" => Cmp::Identical,
                None if op.as_str() == "\\==" => Cmp::NotIdentical,
                None => {
                    return Err(format!(
                        "condition `{}` is not an arithmetic comparison or `==`/`\\==`",
                        show(store, self.dm, cond)
                    ))
                }
            };
            let (a, ta) = self.val(l, bound)?;
            let (b, tb) = self.val(r, bound)?;
            if !matches!(op, Cmp::Arith(_)) {
                // Atoms of any two sets compare by identity.
                if !matches!(ta, Ty::Atoms(_)) || !matches!(tb, Ty::Atoms(_)) {
                    return Err(format!(
                        "`{}` compares {} with {} (typed `==` is on atoms)",
                        show(store, self.dm, cond),
                        an(&ta),
                        an(&tb)
                    ));
                }
                let then = Box::new(self.next(then, bound)?);
                let other = Box::new(self.next(other, bound)?);
                return Ok(TNext::If {
                    op,
                    float: false,
                    a,
                    b,
                    then,
                    other,
                });
            }
            let ty = match (&ta, &tb) {
                (Ty::None, Ty::None) => {
                    return Err("a comparison of two parameters".to_owned());
                }
                (Ty::None, t) | (t, Ty::None) => t.clone(),
                (x, y) if x == y => x.clone(),
                _ => {
                    return Err(format!(
                        "`{}` compares {} with {}",
                        show(store, self.dm, cond),
                        an(&ta),
                        an(&tb)
                    ))
                }
            };
            if !matches!(ty, Ty::Int | Ty::Float) {
                return Err(format!(
                    "`{}` compares {ty} values",
                    show(store, self.dm, cond)
                ));
            }
            for v in [&a, &b] {
                if let TVal::Param(i) = v {
                    self.params[*i] = self.params[*i].join(&ty);
                }
            }
            let then = Box::new(self.next(then, bound)?);
            let other = Box::new(self.next(other, bound)?);
            return Ok(TNext::If {
                op,
                float: ty == Ty::Float,
                a,
                b,
                then,
                other,
            });
        }
        Err(format!(
            "next situation `{}` is not an atom or a conditional on a comparison",
            show(store, self.dm, n)
        ))
    }

    /// A typed operand; `Ty::None` for a parameter (its type is demanded).
    fn val(&self, t: Term, bound: &HashMap<u32, Ty>) -> Result<(TVal, Ty), String> {
        let store = self.store;
        match store.value(t) {
            Value::Atom(a) => Ok((TVal::Atom(a), Ty::Atoms(vec![a]))),
            Value::Int(i) => Ok((TVal::Int(i), Ty::Int)),
            Value::Float(f) => Ok((TVal::Float(f), Ty::Float)),
            Value::Var(v) => {
                if let Some(ty) = bound.get(&v.index()) {
                    return Ok((TVal::Var(v.index()), ty.clone()));
                }
                if let Some(i) = self.head_vars.iter().position(|h| *h == Some(v.index())) {
                    return Ok((TVal::Param(i), Ty::None));
                }
                Err(format!(
                    "`{}` is not bound to a typed value",
                    var_name(self.dm, v.index())
                ))
            }
            _ => Err(format!(
                "operand `{}` is not a number or a typed variable",
                show(store, self.dm, t)
            )),
        }
    }
}

/// Whether evaluating `t` gives `t` back with no effect (no construct of L in it).
fn inert(store: &Store, t: Term) -> bool {
    let mut stack = vec![t];
    while let Some(u) = stack.pop() {
        if let Value::Compound(name, args) = store.value(u) {
            if !eval::evaluates_arguments_only(name, args.len()) {
                return false;
            }
            stack.extend(args.iter());
        }
    }
    true
}

/// The elements of a non-empty proper list written out in the source.
fn list_literal(store: &Store, t: Term) -> Option<Vec<Term>> {
    let mut items = Vec::new();
    let mut rest = t;
    loop {
        match store.value(rest) {
            Value::Compound(name, &[head, tail]) if name == atoms::DOT => {
                items.push(head);
                rest = tail;
            }
            Value::Atom(a) if a == atoms::NIL && !items.is_empty() => return Some(items),
            _ => return None,
        }
    }
}

/// The `--explain-types` listing: every DM's parameters, locals and
/// situations, typed or not and why; then the globals.
pub fn explain(ir: &Ir, types: &Types) -> String {
    let store = &ir.store;
    let mut out = String::new();
    for (dm, t) in ir.dms.iter().zip(&types.dms) {
        let _ = writeln!(out, "DM {}/{}", dm.name.as_str(), dm.arity);
        for (i, p) in t.params.iter().enumerate() {
            match p {
                Some(p) => {
                    let _ = writeln!(
                        out,
                        "  parameter {} `{}`: {} ({})",
                        i + 1,
                        p.name,
                        p.ty,
                        p.why
                    );
                }
                None => {
                    let _ = writeln!(out, "  parameter {}: not a variable", i + 1);
                }
            }
        }
        for l in &t.locals {
            let _ = writeln!(out, "  local `{}`: {} ({})", l.name, l.ty, l.why);
        }
        for (s, r) in dm.situations.iter().zip(&t.situations) {
            let id = show(store, dm, store.args(s.template)[1]);
            match r {
                Ok(plan) => {
                    let mut vars = Vec::new();
                    if let TSit::Perceptual { arcs, .. } = plan {
                        for (i, arc) in arcs.iter().enumerate() {
                            if let TAction::List(items) = &arc.action {
                                for it in items {
                                    if let TItem::Inc {
                                        local,
                                        bind: Some(v),
                                    }
                                    | TItem::Get {
                                        local,
                                        bind: Some(v),
                                    } = it
                                    {
                                        vars.push(format!(
                                            "arc {} `{}`: {}",
                                            i + 1,
                                            var_name(dm, *v),
                                            t.locals[*local].ty
                                        ));
                                    }
                                }
                            }
                        }
                    }
                    if vars.is_empty() {
                        let _ = writeln!(out, "  situation `{id}`: typed");
                    } else {
                        let _ = writeln!(out, "  situation `{id}`: typed ({})", vars.join(", "));
                    }
                }
                Err(why) => {
                    let _ = writeln!(out, "  situation `{id}`: terms ({why})");
                }
            }
        }
    }
    if !types.globals.is_empty() {
        let _ = writeln!(out, "globals (kept as terms by generated code)");
        for g in &types.globals {
            let _ = writeln!(out, "  `{}`: {} ({})", g.name, g.ty, g.why);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{check, ir, load};

    fn ir_of(src: &str) -> Ir {
        let (program, diags) = load::load_sources(&[("t.dm", src)]);
        let (result, diags) = check::check(program, diags);
        let checked = result.unwrap_or_else(|_| panic!("does not check: {diags:#?}"));
        ir::lower(&checked)
    }

    fn atoms(names: &[&str]) -> Ty {
        Ty::Atoms(names.iter().map(|n| Atom::intern(n)).collect())
    }

    #[test]
    fn the_lattice_joins() {
        assert_eq!(Ty::Int.join(&Ty::Int), Ty::Int);
        assert_eq!(Ty::None.join(&Ty::Float), Ty::Float);
        assert_eq!(Ty::Int.join(&Ty::Float), Ty::Term);
        assert_eq!(atoms(&["b"]).join(&atoms(&["a", "b"])), atoms(&["a", "b"]));
        assert_eq!(atoms(&["a"]).join(&Ty::Int), Ty::Term);
        let pos = |x: Ty| Ty::Shape(Atom::intern("pos"), vec![x, Ty::Float]);
        assert_eq!(
            pos(atoms(&["a"])).join(&pos(atoms(&["b"]))),
            pos(atoms(&["a", "b"]))
        );
        assert_eq!(pos(Ty::Int).join(&pos(Ty::Float)), Ty::Term);
        let many: Vec<Ty> = (0..=MAX_ATOMS)
            .map(|i| atoms(&[&format!("a{i}")]))
            .collect();
        let joined = many.iter().fold(Ty::None, |t, u| t.join(u));
        assert_eq!(joined, Ty::Term, "more atoms than MAX_ATOMS stay a term");
        assert_eq!(format!("{}", pos(atoms(&["b", "a"]))), "pos({b, a}, float)");
    }

    #[test]
    fn ground_terms_have_shapes() {
        let mut store = Store::new();
        let t = store.parse("p(1, 2.0, x, [a])").unwrap().0;
        assert_eq!(
            format!("{}", Ty::of_ground(&store, t)),
            "p(int, float, {x}, [{a} | {[]}])"
        );
        let v = store.parse("p(X)").unwrap().0;
        assert_eq!(Ty::of_ground(&store, v), Ty::Term);
        let big = store.parse("123456789012345678901234567890").unwrap().0;
        assert_eq!(Ty::of_ground(&store, big), Ty::Term);
    }

    const LOOP: &str = r#"
diag_mod(main(Max),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [inc(n, N), set(mode, busy)] => (N >= Max -> fs ; otherwise -> is) ] ],
    [ id ==> fs, type ==> final ] ],
  [ n ==> 0, mode ==> idle, f ==> 1.5, p ==> pos(1, 2), l ==> [], x ==> _ ]).
"#;

    #[test]
    fn locals_parameters_and_situations_are_typed() {
        let ir = ir_of(LOOP);
        let t = infer(&ir);
        let dm = &t.dms[0];
        let ty = |n: &str| &dm.locals.iter().find(|l| l.name == n).unwrap().ty;
        assert_eq!(*ty("n"), Ty::Int);
        assert_eq!(*ty("mode"), atoms(&["busy", "idle"]));
        assert_eq!(*ty("f"), Ty::Float);
        assert_eq!(format!("{}", ty("p")), "pos(int, int)");
        assert_eq!(*ty("x"), Ty::Term);
        assert_eq!(dm.params[0].as_ref().unwrap().ty, Ty::Int);
        assert_eq!(dm.params[0].as_ref().unwrap().name, "Max");
        let Ok(TSit::Perceptual {
            always_first, arcs, ..
        }) = &dm.situations[0]
        else {
            panic!("`is` is typed: {:?}", dm.situations[0]);
        };
        assert!(*always_first);
        assert!(matches!(
            &arcs[0].next,
            TNext::If {
                op: Cmp::Arith(ArithCmp::Ge),
                float: false,
                a: TVal::Var(_),
                b: TVal::Param(0),
                ..
            }
        ));
        assert!(matches!(dm.situations[1], Ok(TSit::Final { .. })));
        assert_eq!(dm.frame_locals(), vec![0, 1]);
        assert_eq!(dm.frame_params(), vec![0]);
    }

    #[test]
    fn what_stays_a_term_says_why() {
        let ir = ir_of(
            r#"
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [inc(n, _), set(n, done)] => is2 ] ],
    [ id ==> is2, type ==> neutral, in_arg ==> X,
      arcs ==> [ empty : [inc(k, _)] => s(X) ] ],
    [ id ==> s(_), type ==> neutral,
      arcs ==> [ empty : [inc(k, K)] => (K > 1.5 -> fs ; otherwise -> is2) ] ],
    [ id ==> fs, type ==> final ] ],
  [ n ==> 0, k ==> 0 ]).
"#,
        );
        let t = infer(&ir);
        let text = explain(&ir, &t);
        assert!(
            text.contains("local `n`: term (`set` to `done` (an atom of {done}) besides"),
            "{text}"
        );
        assert!(
            text.contains("situation `is`: terms (arc 1: local `n` is a term)"),
            "{text}"
        );
        assert!(
            text.contains("situation `is2`: terms (it has `in_arg`)"),
            "{text}"
        );
        assert!(
            text.contains("situation `s(_)`: terms (its id `s(_)` is not an atom)"),
            "{text}"
        );
        assert!(
            text.contains("situation `fs`: terms (no other situation of the DM runs typed)"),
            "{text}"
        );
    }

    #[test]
    fn mixed_comparisons_and_opaque_writes() {
        let ir = ir_of(
            r#"
diag_mod(main(P),
  [ [ id ==> a, type ==> neutral,
      arcs ==> [ empty : [inc(k, K)] => (K > 1.5 -> b ; otherwise -> a) ] ],
    [ id ==> b, type ==> neutral,
      arcs ==> [ empty : [get(k, K)] => (P > K -> c ; otherwise -> b) ] ],
    [ id ==> c, type ==> neutral,
      arcs ==> [ empty : [get(f, F)] => (P > F -> fs ; otherwise -> c) ] ],
    [ id ==> fs, type ==> final, prog ==> [set(V, 1)] ] ],
  [ k ==> 0, f ==> 0.5 ]).
"#,
        );
        let t = infer(&ir);
        let text = explain(&ir, &t);
        assert!(
            text.contains("situation `a`: terms (arc 1: `K>1.5` compares an int with a float)"),
            "{text}"
        );
        assert!(
            text.contains(
                "situation `b`: terms (parameter `P` is compared both as an int and as a float)"
            ),
            "{text}"
        );
        assert!(
            text.contains("`set(V,1)` names its variable at run time: checked on load"),
            "{text}"
        );
        assert_eq!(t.dms[0].params[0].as_ref().unwrap().ty, Ty::Term);
    }
}
