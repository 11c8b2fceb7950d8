//! The interpreter's resolved program: the IR turned, once before a run,
//! into plans the machine runs without looking names up or copying
//! situation templates.
//!
//! A situation the code generator would compile ([`codegen`](crate::codegen)'s
//! rule: its id and type are atoms, or its id a compound of fresh variables
//! and atomic constants, in a DM whose head parameters are distinct
//! variables) gets a *plan*: a small tree of steps over the runtime's
//! [`Cx`], the same steps, in the same order, as the generated code of that
//! situation takes. Variables live in registers of one visit (no map from
//! names), ground parts of the templates are the IR's frozen terms (built
//! once, at lowering), a constant next situation is resolved to its index,
//! and the machine's situations of one DM follow each other without going
//! back to the machine's loop. Every other situation (and any situation the
//! planner cannot resolve: see [`Unsupported`]) is instantiated from its
//! template, as before: the plans only skip work whose result is known
//! before the run, so semantics are the runtime's.
//!
//! Invariant: [`Resolved`] runs a program exactly as the IR alone does (the
//! same reports, histories and errors, up to the names of unbound
//! variables); `tests/tests/random_agreement.rs` compares the two on random
//! programs and scripts, and both with the generated code.

use crate::ir::{none_marker, Ir, IrDm, IrSituation};
use sitlog_runtime::machine::{Cx, DmIx, DmProgram, Instance, Kind, RunError, SitIx, Step};
use sitlog_runtime::{atoms, eval, ArithCmp, Atom, Store, Term, Value, Vars};
use std::collections::{HashMap, HashSet};

/// Field positions in a situation template (see [`crate::ir`]).
const HEAD: usize = 0;
const ID: usize = 1;
const TYPE: usize = 2;
const IN_ARG: usize = 3;
const OUT_ARG: usize = 4;
const PROG: usize = 5;
const EMBEDDED_DM: usize = 6;
const DIAG_MOD: usize = 7;
const ARCS: usize = 8;

/// Deepest term the planner turns into a tree of steps; a deeper one keeps
/// its situation on the instantiating path (no deep recursion at run time).
const MAX_DEPTH: usize = 200;

/// Registers of one visit kept on the stack (more spill to the heap).
const STACK_REGS: usize = 32;

/// A register of one visit of a situation.
type Reg = u32;

/// Why the planner left a situation to the instantiating path (a variable
/// it does not know, a term too deep): never an error of the program.
#[derive(Debug)]
struct Unsupported;

type Plan<T> = Result<T, Unsupported>;

/// A term built from registers, not evaluated.
#[derive(Debug)]
enum Build {
    /// Atomic, or ground: a frozen term of the IR's store.
    Const(Term),
    Reg(Reg),
    Compound(Atom, Box<[Build]>),
}

/// A term evaluated in L, as the generated code evaluates it.
#[derive(Debug)]
enum Ev {
    /// A variable occurrence: its value ([`Cx::value`]).
    Value(Reg),
    /// Evaluating gives the term itself.
    Built(Build),
    /// Anything else: the runtime's evaluator.
    Eval(Build),
    If(Box<Cond>, Box<Ev>, Box<Ev>),
    /// `get`/`inc` into a variable not made yet: it takes the value.
    VarOpFresh {
        op: Atom,
        name: Atom,
        dst: Reg,
    },
    VarOp {
        op: Atom,
        name: Atom,
        arg: Build,
    },
    /// `V is E` for a variable not made yet.
    IsFresh {
        expr: Build,
        dst: Reg,
    },
    Is {
        lhs: Build,
        expr: Build,
    },
    /// A compound whose evaluation evaluates its arguments only.
    Compound(Atom, Box<[Ev]>),
}

#[derive(Debug)]
enum Cond {
    Arith(ArithCmp, Ev, Ev),
    Other(Build),
}

/// A next situation: its value and, when known, its index.
#[derive(Debug)]
enum Next {
    Static(Term, Option<SitIx>),
    If(Box<Cond>, Box<Next>, Box<Next>),
    Eval(Ev),
}

/// How a situation variable starts a visit.
#[derive(Debug, Clone, Copy)]
enum Init {
    /// Argument `i` of the selecting value (a compound id).
    IdArg(usize),
    /// Argument `i` of the DM call.
    HeadArg(usize),
    /// A variable in_arg: the incoming pipe.
    Pipe,
    Fresh,
}

#[derive(Debug)]
enum IdPart {
    Fresh(Reg),
    Const(Term),
}

#[derive(Debug)]
enum Prog {
    /// Evaluated in place, element by element.
    InPlace(Vec<Ev>),
    /// On a copy sharing in_arg's and out_arg's variables (D-10).
    Copy(Build),
}

#[derive(Debug)]
enum Action {
    /// A list written out: elements evaluated into `regs`, performed one by one.
    List {
        items: Vec<Ev>,
        regs: Reg,
    },
    One(Ev),
}

#[derive(Debug)]
struct ArcPlan {
    fresh: Vec<Reg>,
    /// Imported variables: sources, copied into `import_at..` and imported jointly.
    import_from: Vec<Reg>,
    import_at: Reg,
    expectation: Ev,
    action: Action,
    next: Next,
    out_arg: Option<Build>,
    diag_mod: Option<Build>,
}

#[derive(Debug)]
struct Arcs {
    arcs: Vec<ArcPlan>,
    /// No expectation can change a variable: nothing saved around them.
    pure: bool,
    /// `neutral` with `[empty : A => N]`: the arc is taken (D-14).
    always_first: bool,
    type_term: Term,
    /// The evaluated expectations: registers `exps..exps + arcs.len()`.
    exps: Reg,
}

#[derive(Debug)]
enum KindPlan {
    Final {
        diag_mod: Option<Build>,
    },
    Perceptual(Arcs),
    Recursive {
        call: Build,
        eval_call: bool,
        saved: Vec<Reg>,
        exit: Arcs,
    },
}

/// The plan of one situation.
#[derive(Debug)]
struct SitPlan {
    id: (Atom, usize),
    /// Constant arguments of a compound id, unified when it is selected.
    select: Vec<(usize, Term)>,
    /// A compound id built when not selected by a value.
    compound_id: Option<Vec<IdPart>>,
    inits: Vec<(Reg, Init)>,
    /// in_arg: the pattern, unified with the pipe when `unify`; kept in `reg`.
    in_arg: Option<(Build, bool, Reg)>,
    /// out_arg of a non-recursive situation, built into `reg`.
    out_arg: Option<(Build, Reg)>,
    prog: Option<Prog>,
    kind: KindPlan,
    regs: usize,
}

/// The IR with plans for the situations it can resolve (see the module doc).
pub struct Resolved<'ir> {
    ir: &'ir Ir,
    plans: Vec<Vec<Option<SitPlan>>>,
    /// Go on to the next planned situation of a DM without returning to the
    /// machine's loop (as generated code does).
    chain: bool,
}

impl<'ir> Resolved<'ir> {
    /// Plans every situation that can be resolved.
    pub fn new(ir: &'ir Ir) -> Resolved<'ir> {
        let plans = ir
            .dms
            .iter()
            .map(|dm| {
                (0..dm.situations.len())
                    .map(|i| Planner::new(&ir.store, dm).situation(i).ok())
                    .collect()
            })
            .collect();
        Resolved {
            ir,
            plans,
            chain: true,
        }
    }

    /// Returns to the machine's loop after every situation, so that each
    /// one goes through [`Machine`](sitlog_runtime::machine::Machine)'s
    /// selection (for tools that act between situations, such as a
    /// debugger); a little slower, the same semantics.
    pub fn one_situation_per_step(mut self) -> Self {
        self.chain = false;
        self
    }

    /// The program without plans: every situation instantiated.
    pub fn ir(&self) -> &'ir Ir {
        self.ir
    }

    /// How many situations run from plans, of how many.
    pub fn counts(&self) -> (usize, usize) {
        let all = self.plans.iter().map(Vec::len).sum();
        let planned = self.plans.iter().flatten().filter(|p| p.is_some()).count();
        (planned, all)
    }

    fn plan(&self, dm: DmIx, sit: SitIx) -> Option<&SitPlan> {
        self.plans[dm as usize][sit as usize].as_ref()
    }
}

// ------------------------------------------------------------------ planning

/// Variables of one scope: their registers, and those not made yet.
#[derive(Clone, Default)]
struct Scope {
    vars: HashMap<u32, Reg>,
    lazy: HashSet<u32>,
}

struct Planner<'s> {
    store: &'s Store,
    dm: &'s IrDm,
    regs: Reg,
}

impl<'s> Planner<'s> {
    fn new(store: &'s Store, dm: &'s IrDm) -> Self {
        Planner { store, dm, regs: 0 }
    }

    fn reg(&mut self) -> Reg {
        self.regs += 1;
        self.regs - 1
    }

    fn regs(&mut self, n: usize) -> Reg {
        let r = self.regs;
        self.regs += n as Reg;
        r
    }

    fn field(&self, s: &IrSituation, i: usize) -> Option<Term> {
        let t = self.store.args(s.template)[i];
        (self.store.atom_of(t) != Some(none_marker())).then_some(t)
    }

    fn term_vars(&self, t: Term, out: &mut Vec<u32>) {
        let mut stack = vec![t];
        while let Some(u) = stack.pop() {
            match self.store.value(u) {
                Value::Var(v) if !out.contains(&v.index()) => out.push(v.index()),
                Value::Compound(_, args) => stack.extend(args.iter().rev()),
                _ => {}
            }
        }
    }

    /// The code generator's rule for a situation that runs as code.
    fn compiled_id(&self, s: &IrSituation) -> Option<(Atom, usize)> {
        let f = self.store.args(s.template);
        self.store.atom_of(f[TYPE])?;
        if s.kind == Kind::Recursive && self.store.atom_of(f[EMBEDDED_DM]) == Some(none_marker()) {
            return None;
        }
        let mut seen = HashSet::new();
        for &a in self.store.args(self.dm.head) {
            match self.store.value(a) {
                Value::Var(v) if seen.insert(v.index()) => {}
                _ => return None,
            }
        }
        match self.store.value(f[ID]) {
            Value::Atom(a) if a != none_marker() => Some((a, 0)),
            Value::Compound(name, args) => {
                for &arg in args {
                    match self.store.value(arg) {
                        Value::Var(v) if seen.insert(v.index()) => {}
                        Value::Atom(_) | Value::Int(_) | Value::Float(_) => {}
                        _ => return None,
                    }
                }
                Some((name, args.len()))
            }
            _ => None,
        }
    }

    /// The index of the first situation a constant next situation `name`
    /// selects, when that one runs from a plan.
    fn static_target(&self, name: Atom) -> Option<SitIx> {
        for (i, s) in self.dm.situations.iter().enumerate() {
            let id = self.store.args(s.template)[ID];
            match self.store.value(id) {
                Value::Var(_) => return None,
                Value::Atom(a) if a == name => {
                    return self.compiled_id(s).map(|_| i as SitIx);
                }
                _ => {}
            }
        }
        None
    }

    /// Whether evaluating `t` gives `t` back with no effect.
    fn inert(&self, t: Term, vars_inert: bool) -> bool {
        let mut stack = vec![t];
        while let Some(u) = stack.pop() {
            match self.store.value(u) {
                Value::Var(_) if !vars_inert => return false,
                Value::Compound(name, args) => {
                    if !eval::evaluates_arguments_only(name, args.len()) {
                        return false;
                    }
                    stack.extend(args.iter());
                }
                _ => {}
            }
        }
        true
    }

    fn build(&self, t: Term, vars: &HashMap<u32, Reg>, depth: usize) -> Plan<Build> {
        if depth > MAX_DEPTH {
            return Err(Unsupported);
        }
        match self.store.value(t) {
            Value::Var(v) => vars
                .get(&v.index())
                .map(|&r| Build::Reg(r))
                .ok_or(Unsupported),
            Value::Compound(name, args) if !self.store.is_ground(t) => {
                let args = args
                    .iter()
                    .map(|&a| self.build(a, vars, depth + 1))
                    .collect::<Plan<Vec<_>>>()?;
                Ok(Build::Compound(name, args.into()))
            }
            _ => Ok(Build::Const(t)),
        }
    }

    fn ev(&self, t: Term, scope: &mut Scope, depth: usize) -> Plan<Ev> {
        if depth > MAX_DEPTH {
            return Err(Unsupported);
        }
        let (name, args) = match self.store.value(t) {
            Value::Var(v) => {
                return scope
                    .vars
                    .get(&v.index())
                    .map(|&r| Ev::Value(r))
                    .ok_or(Unsupported)
            }
            Value::Compound(name, args) => (name, args),
            _ => return Ok(Ev::Built(Build::Const(t))),
        };
        if self.store.is_ground(t) {
            let k = Build::Const(t);
            return Ok(if self.inert(t, true) {
                Ev::Built(k)
            } else {
                Ev::Eval(k)
            });
        }
        if let Some((cond, then, other)) = eval::conditional(self.store, t) {
            let c = self.cond(cond, scope, depth + 1)?;
            let then = self.ev(then, scope, depth + 1)?;
            let other = self.ev(other, scope, depth + 1)?;
            return Ok(Ev::If(Box::new(c), Box::new(then), Box::new(other)));
        }
        if args.len() == 2 && [atoms::GET, atoms::SET, atoms::INC].contains(&name) {
            if let (Some(var), Value::Var(v)) =
                (self.store.atom_of(args[0]), self.store.value(args[1]))
            {
                if scope.lazy.remove(&v.index()) {
                    let dst = *scope.vars.get(&v.index()).ok_or(Unsupported)?;
                    return Ok(Ev::VarOpFresh {
                        op: name,
                        name: var,
                        dst,
                    });
                }
            }
            if let Some(var) = self.store.atom_of(args[0]) {
                let arg = self.build(args[1], &scope.vars, depth + 1)?;
                return Ok(Ev::VarOp {
                    op: name,
                    name: var,
                    arg,
                });
            }
        }
        if args.len() == 2 && name == atoms::IS {
            let expr = self.build(args[1], &scope.vars, depth + 1)?;
            if let Value::Var(v) = self.store.value(args[0]) {
                if scope.lazy.remove(&v.index()) {
                    let dst = *scope.vars.get(&v.index()).ok_or(Unsupported)?;
                    return Ok(Ev::IsFresh { expr, dst });
                }
            }
            let lhs = self.build(args[0], &scope.vars, depth + 1)?;
            return Ok(Ev::Is { lhs, expr });
        }
        if eval::evaluates_arguments_only(name, args.len()) {
            let values = args
                .iter()
                .map(|&a| self.ev(a, scope, depth + 1))
                .collect::<Plan<Vec<_>>>()?;
            return Ok(Ev::Compound(name, values.into()));
        }
        Ok(Ev::Eval(self.build(t, &scope.vars, depth + 1)?))
    }

    fn cond(&self, cond: Term, scope: &mut Scope, depth: usize) -> Plan<Cond> {
        if let Value::Compound(name, &[l, r]) = self.store.value(cond) {
            if let Some(op) = ArithCmp::from_atom(name) {
                let l = self.ev(l, scope, depth + 1)?;
                let r = self.ev(r, scope, depth + 1)?;
                return Ok(Cond::Arith(op, l, r));
            }
        }
        Ok(Cond::Other(self.build(cond, &scope.vars, depth + 1)?))
    }

    fn next(&self, t: Term, scope: &mut Scope, depth: usize) -> Plan<Next> {
        if depth > MAX_DEPTH {
            return Err(Unsupported);
        }
        if let Some(name) = self.store.atom_of(t) {
            return Ok(Next::Static(t, self.static_target(name)));
        }
        if let Some((cond, then, other)) = eval::conditional(self.store, t) {
            let c = self.cond(cond, scope, depth + 1)?;
            let then = self.next(then, scope, depth + 1)?;
            let other = self.next(other, scope, depth + 1)?;
            return Ok(Next::If(Box::new(c), Box::new(then), Box::new(other)));
        }
        Ok(Next::Eval(self.ev(t, scope, depth + 1)?))
    }

    /// Variables whose first occurrence is the argument of a `get`/`inc`
    /// (or the variable of an `is`) outside any conditional.
    fn lazy_vars(&self, terms: &[Term]) -> HashSet<u32> {
        let mut seen = HashSet::new();
        let mut lazy = HashSet::new();
        for &t in terms {
            self.lazy_walk(t, 0, &mut seen, &mut lazy);
        }
        lazy
    }

    fn lazy_walk(&self, t: Term, depth: usize, seen: &mut HashSet<u32>, lazy: &mut HashSet<u32>) {
        let Value::Compound(name, args) = self.store.value(t) else {
            if let Value::Var(v) = self.store.value(t) {
                seen.insert(v.index());
            }
            return;
        };
        if depth > MAX_DEPTH {
            // Planning fails on such a term anyway: mark its variables seen.
            let mut vars = Vec::new();
            self.term_vars(t, &mut vars);
            seen.extend(vars);
            return;
        }
        if let Some((c, a, b)) = eval::conditional(self.store, t) {
            for part in [c, a, b] {
                self.lazy_walk(part, depth + 1, seen, lazy);
            }
            return;
        }
        if args.len() == 2 && name == atoms::IS {
            let mut vars = Vec::new();
            self.term_vars(args[1], &mut vars);
            seen.extend(vars);
            if let Value::Var(v) = self.store.value(args[0]) {
                if depth == 0 && seen.insert(v.index()) {
                    lazy.insert(v.index());
                }
                return;
            }
            let mut vars = Vec::new();
            self.term_vars(args[0], &mut vars);
            seen.extend(vars);
            return;
        }
        if args.len() == 2 && (name == atoms::GET || name == atoms::INC) {
            if let (Some(_), Value::Var(v)) =
                (self.store.atom_of(args[0]), self.store.value(args[1]))
            {
                if depth == 0 && seen.insert(v.index()) {
                    lazy.insert(v.index());
                }
                return;
            }
        }
        if !self.store.is_ground(t) && eval::evaluates_arguments_only(name, args.len()) {
            for &a in args {
                self.lazy_walk(a, depth, seen, lazy);
            }
            return;
        }
        let mut vars = Vec::new();
        self.term_vars(t, &mut vars);
        seen.extend(vars);
    }

    fn list_literal(&self, t: Term) -> Option<Vec<Term>> {
        let mut items = Vec::new();
        let mut rest = t;
        loop {
            match self.store.value(rest) {
                Value::Compound(name, &[head, tail]) if name == atoms::DOT => {
                    items.push(head);
                    rest = tail;
                }
                Value::Atom(a) if a == atoms::NIL && !items.is_empty() => return Some(items),
                _ => return None,
            }
        }
    }

    /// The plan of situation `ix`.
    fn situation(mut self, ix: usize) -> Plan<SitPlan> {
        let s = &self.dm.situations[ix];
        let id = self.compiled_id(s).ok_or(Unsupported)?;
        let f = self.store.args(s.template).to_vec();
        let mut scope = Scope::default();
        let mut inst_vars = Vec::new();
        for &t in &f[..ARCS] {
            self.term_vars(t, &mut inst_vars);
        }
        let head_vars: Vec<u32> = self
            .store
            .args(f[HEAD])
            .iter()
            .map(|&a| match self.store.value(a) {
                Value::Var(v) => Ok(v.index()),
                _ => Err(Unsupported),
            })
            .collect::<Plan<_>>()?;
        let in_arg = self.field(s, IN_ARG);
        let out_arg = self.field(s, OUT_ARG);
        let prog = self.field(s, PROG);
        let diag_mod = self.field(s, DIAG_MOD);
        let in_var = in_arg.and_then(|t| match self.store.value(t) {
            Value::Var(v) if !head_vars.contains(&v.index()) => Some(v.index()),
            _ => None,
        });
        let mut select = Vec::new();
        let mut id_vars = Vec::new();
        let mut compound_id = None;
        if let Value::Compound(_, args) = self.store.value(f[ID]) {
            let mut parts = Vec::new();
            for (i, &arg) in args.iter().enumerate() {
                if let Value::Var(v) = self.store.value(arg) {
                    id_vars.push((v.index(), i));
                    parts.push(IdPart::Fresh(self.reg()));
                } else {
                    select.push((i, arg));
                    parts.push(IdPart::Const(arg));
                }
            }
            compound_id = Some(parts);
        }
        let mut inits = Vec::new();
        for &v in &inst_vars {
            let init = if let Some(&(_, i)) = id_vars.iter().find(|(x, _)| *x == v) {
                Init::IdArg(i)
            } else if let Some(i) = head_vars.iter().position(|&h| h == v) {
                Init::HeadArg(i)
            } else if Some(v) == in_var {
                Init::Pipe
            } else {
                Init::Fresh
            };
            let r = self.reg();
            inits.push((r, init));
            scope.vars.insert(v, r);
        }
        let in_plan = match in_arg {
            Some(t) => Some((self.build(t, &scope.vars, 0)?, in_var.is_none(), self.reg())),
            None => None,
        };
        let out_plan = match out_arg {
            Some(t) if s.kind != Kind::Recursive => {
                Some((self.build(t, &scope.vars, 0)?, self.reg()))
            }
            _ => None,
        };
        let prog_plan = match prog {
            None => None,
            Some(p) => {
                let mut linked = Vec::new();
                let mut elsewhere = Vec::new();
                for (i, &t) in f.iter().enumerate() {
                    let link = i == IN_ARG || (i == OUT_ARG && s.kind != Kind::Recursive);
                    match i {
                        PROG => {}
                        _ if link => self.term_vars(t, &mut linked),
                        _ => self.term_vars(t, &mut elsewhere),
                    }
                }
                let mut prog_vars = Vec::new();
                self.term_vars(p, &mut prog_vars);
                if prog_vars
                    .iter()
                    .all(|v| linked.contains(v) || !elsewhere.contains(v))
                {
                    let parts = self.list_literal(p).unwrap_or_else(|| vec![p]);
                    let evs = parts
                        .into_iter()
                        .map(|part| self.ev(part, &mut scope, 0))
                        .collect::<Plan<Vec<_>>>()?;
                    Some(Prog::InPlace(evs))
                } else {
                    Some(Prog::Copy(self.build(p, &scope.vars, 0)?))
                }
            }
        };
        let kind = match s.kind {
            Kind::Final => KindPlan::Final {
                diag_mod: match diag_mod {
                    Some(d) => Some(self.build(d, &scope.vars, 0)?),
                    None => None,
                },
            },
            Kind::Perceptual => KindPlan::Perceptual(self.arcs(s, &mut scope, false)?),
            Kind::Recursive => {
                let e = self.field(s, EMBEDDED_DM).ok_or(Unsupported)?;
                let eval_call = !(self.store.is_ground(e) && self.inert(e, true));
                let call = self.build(e, &scope.vars, 0)?;
                let mut needed = Vec::new();
                for t in [Some(f[ARCS]), out_arg, diag_mod].into_iter().flatten() {
                    self.term_vars(t, &mut needed);
                }
                let saved: Vec<Reg> = inst_vars
                    .iter()
                    .filter(|v| needed.contains(v))
                    .map(|v| scope.vars[v])
                    .collect();
                let mut exit_scope = Scope {
                    vars: scope.vars.clone(),
                    lazy: HashSet::new(),
                };
                let exit = self.arcs(s, &mut exit_scope, true)?;
                KindPlan::Recursive {
                    call,
                    eval_call,
                    saved,
                    exit,
                }
            }
        };
        Ok(SitPlan {
            id,
            select,
            compound_id,
            inits,
            in_arg: in_plan,
            out_arg: out_plan,
            prog: prog_plan,
            kind,
            regs: self.regs as usize,
        })
    }

    /// The arcs of a perceptual situation, or the exit arcs of a recursive one.
    fn arcs(&mut self, s: &IrSituation, scope: &mut Scope, exit: bool) -> Plan<Arcs> {
        let f = self.store.args(s.template);
        let out_arg = self.field(s, OUT_ARG);
        let diag_mod = self.field(s, DIAG_MOD);
        let type_term = f[TYPE];
        let arcs: Vec<[Term; 3]> = self
            .store
            .list_iter(f[ARCS])
            .map(|arc| {
                let a = self.store.args(arc);
                [a[0], a[1], a[2]]
            })
            .collect();
        let neutral = self.store.atom_of(type_term) == Some(atoms::NEUTRAL);
        let always_first = !exit
            && neutral
            && arcs.len() == 1
            && self.store.atom_of(arcs[0][0]) == Some(atoms::EMPTY);
        // Each arc's variables: imported copies of the situation's, fresh otherwise (D-11).
        let mut scopes = Vec::new();
        let mut parts = Vec::new();
        let mut pure = true;
        for arc in &arcs {
            let mut vars = Vec::new();
            for &t in arc.iter().chain(out_arg.iter()) {
                self.term_vars(t, &mut vars);
            }
            let in_order: Vec<Term> = arc.iter().copied().chain(out_arg).collect();
            let mut in_expectation = Vec::new();
            self.term_vars(arc[0], &mut in_expectation);
            let lazy: HashSet<u32> = self
                .lazy_vars(&in_order)
                .into_iter()
                .filter(|v| !scope.vars.contains_key(v) && !in_expectation.contains(v))
                .collect();
            let imported: Vec<u32> = vars
                .iter()
                .copied()
                .filter(|v| scope.vars.contains_key(v))
                .collect();
            let import_at = self.regs(imported.len());
            let import_from: Vec<Reg> = imported.iter().map(|v| scope.vars[v]).collect();
            let mut arc_vars = HashMap::new();
            let mut fresh = Vec::new();
            for (n, &v) in imported.iter().enumerate() {
                arc_vars.insert(v, import_at + n as Reg);
            }
            for &v in &vars {
                if arc_vars.contains_key(&v) {
                    continue;
                }
                let r = self.reg();
                if !lazy.contains(&v) {
                    fresh.push(r);
                }
                arc_vars.insert(v, r);
            }
            pure &= self.inert(arc[0], true)
                && in_expectation.iter().all(|v| !scope.vars.contains_key(v));
            scopes.push(Scope {
                vars: arc_vars,
                lazy,
            });
            parts.push((fresh, import_from, import_at));
        }
        let exps = self.regs(arcs.len());
        let mut plans = Vec::new();
        for ((arc, sc), (fresh, import_from, import_at)) in arcs.iter().zip(scopes).zip(parts) {
            let mut exp_scope = Scope {
                vars: sc.vars.clone(),
                lazy: HashSet::new(),
            };
            let expectation = self.ev(arc[0], &mut exp_scope, 0)?;
            let mut sc = sc;
            let action = match self.list_literal(arc[1]) {
                Some(items) if !self.inert(arc[1], true) || !self.store.is_ground(arc[1]) => {
                    let items = items
                        .into_iter()
                        .map(|x| self.ev(x, &mut sc, 0))
                        .collect::<Plan<Vec<_>>>()?;
                    let regs = self.regs(items.len());
                    Action::List { items, regs }
                }
                _ => Action::One(self.ev(arc[1], &mut sc, 0)?),
            };
            let next = self.next(arc[2], &mut sc, 0)?;
            let out_arg = match out_arg {
                Some(o) => Some(self.build(o, &sc.vars, 0)?),
                None => None,
            };
            let diag_mod = match diag_mod {
                Some(d) => Some(self.build(d, &scope.vars, 0)?),
                None => None,
            };
            plans.push(ArcPlan {
                fresh,
                import_from,
                import_at,
                expectation,
                action,
                next,
                out_arg,
                diag_mod,
            });
        }
        if !always_first {
            self.store.atom_of(type_term).ok_or(Unsupported)?;
        }
        Ok(Arcs {
            arcs: plans,
            pure,
            always_first,
            type_term,
            exps,
        })
    }
}

// ------------------------------------------------------------------ running

type Rcx<'c, 'a, 'p, 'ir> = &'c mut Cx<'a, 'p, Resolved<'ir>>;

/// Results inside a visit: the error boxed, so that the values passed up
/// the tree of steps stay small.
type R<T> = Result<T, Box<RunError>>;

fn build(cx: Rcx<'_, '_, '_, '_>, regs: &[Term], b: &Build) -> Term {
    match b {
        Build::Const(t) => *t,
        Build::Reg(r) => regs[*r as usize],
        Build::Compound(name, args) => {
            let mut buf = [Term::NIL; 8];
            if args.len() <= buf.len() {
                for (slot, a) in buf.iter_mut().zip(args.iter()) {
                    *slot = build(cx, regs, a);
                }
                cx.compound(*name, &buf[..args.len()])
            } else {
                let values: Vec<Term> = args.iter().map(|a| build(cx, regs, a)).collect();
                cx.compound(*name, &values)
            }
        }
    }
}

fn ev(cx: Rcx<'_, '_, '_, '_>, regs: &mut [Term], e: &Ev, arc: Option<usize>) -> R<Term> {
    match e {
        Ev::Value(r) => {
            // What `Cx::value` does: a compound is evaluated, anything else
            // is its own value.
            let store = cx.store();
            let t = store.deref(regs[*r as usize]);
            if store.is_compound(t) {
                Ok(cx.eval(t, arc)?)
            } else {
                Ok(t)
            }
        }
        Ev::Built(b) => Ok(build(cx, regs, b)),
        Ev::Eval(b) => {
            let t = build(cx, regs, b);
            Ok(cx.eval(t, arc)?)
        }
        Ev::If(c, then, other) => {
            if cond(cx, regs, c, arc)? {
                ev(cx, regs, then, arc)
            } else {
                ev(cx, regs, other, arc)
            }
        }
        Ev::VarOpFresh { op, name, dst } => {
            // `inc` of a local integer that does not overflow: what
            // `var_op_fresh` does, without its general path.
            if *op == atoms::INC {
                let next = cx
                    .local(*name)
                    .and_then(|cur| cx.int_of(cur))
                    .and_then(|i| i.checked_add(1));
                if let Some(n) = next {
                    let v = Term::int(n);
                    cx.set_local(*name, v);
                    regs[*dst as usize] = v;
                    return Ok(v);
                }
            }
            let v = cx.var_op_fresh(*op, *name, arc)?;
            regs[*dst as usize] = v;
            Ok(v)
        }
        Ev::VarOp { op, name, arg } => {
            let a = build(cx, regs, arg);
            Ok(cx.var_op(*op, *name, a, arc)?)
        }
        Ev::IsFresh { expr, dst } => {
            let x = build(cx, regs, expr);
            let v = cx.is(None, x, arc)?;
            regs[*dst as usize] = v;
            Ok(v)
        }
        Ev::Is { lhs, expr } => {
            let x = build(cx, regs, expr);
            let l = build(cx, regs, lhs);
            Ok(cx.is(Some(l), x, arc)?)
        }
        Ev::Compound(name, args) => {
            let mut buf = [Term::NIL; 8];
            if args.len() <= buf.len() {
                for (i, a) in args.iter().enumerate() {
                    buf[i] = ev(cx, regs, a, arc)?;
                }
                Ok(cx.compound(*name, &buf[..args.len()]))
            } else {
                let mut values = Vec::with_capacity(args.len());
                for a in args.iter() {
                    values.push(ev(cx, regs, a, arc)?);
                }
                Ok(cx.compound(*name, &values))
            }
        }
    }
}

fn cond(cx: Rcx<'_, '_, '_, '_>, regs: &mut [Term], c: &Cond, arc: Option<usize>) -> R<bool> {
    match c {
        Cond::Arith(op, l, r) => {
            let l = ev(cx, regs, l, arc)?;
            let r = ev(cx, regs, r, arc)?;
            // Two integers compare as integers (what the runtime's
            // comparison does with them).
            if let (Some(a), Some(b)) = (cx.int_of(l), cx.int_of(r)) {
                return Ok(match op {
                    ArithCmp::Eq => a == b,
                    ArithCmp::Ne => a != b,
                    ArithCmp::Lt => a < b,
                    ArithCmp::Gt => a > b,
                    ArithCmp::Le => a <= b,
                    ArithCmp::Ge => a >= b,
                });
            }
            Ok(cx.arith_condition(*op, l, r, arc)?)
        }
        Cond::Other(b) => {
            let t = build(cx, regs, b);
            Ok(cx.condition(t, arc)?)
        }
    }
}

fn next(
    cx: Rcx<'_, '_, '_, '_>,
    regs: &mut [Term],
    n: &Next,
    arc: Option<usize>,
) -> R<(Term, Option<SitIx>)> {
    match n {
        Next::Static(t, ix) => Ok((*t, *ix)),
        Next::If(c, then, other) => {
            if cond(cx, regs, c, arc)? {
                next(cx, regs, then, arc)
            } else {
                next(cx, regs, other, arc)
            }
        }
        Next::Eval(e) => Ok((ev(cx, regs, e, arc)?, None)),
    }
}

/// Runs `f` with the registers of one visit (on the stack when few).
fn with_regs<T>(n: usize, f: impl FnOnce(&mut [Term]) -> T) -> T {
    if n <= 8 {
        let mut regs = [Term::NIL; 8];
        f(&mut regs[..n])
    } else if n <= STACK_REGS {
        let mut regs = [Term::NIL; STACK_REGS];
        f(&mut regs[..n])
    } else {
        f(&mut vec![Term::NIL; n])
    }
}

fn run_plan(p: &SitPlan, cx: Rcx<'_, '_, '_, '_>, regs: &mut [Term]) -> R<Step> {
    let mut id = Term::NIL;
    if let Some(parts) = &p.compound_id {
        id = match cx.selected() {
            Some(value) => value,
            None => {
                let mut values = Vec::with_capacity(parts.len());
                for part in parts {
                    values.push(match part {
                        IdPart::Fresh(r) => {
                            let v = cx.var();
                            regs[*r as usize] = v;
                            v
                        }
                        IdPart::Const(t) => *t,
                    });
                }
                let id = cx.compound(p.id.0, &values);
                cx.set_id(id);
                id
            }
        };
    }
    for &(r, init) in &p.inits {
        regs[r as usize] = match init {
            Init::IdArg(i) => cx.arg(id, i),
            Init::HeadArg(i) => cx.head_arg(i),
            Init::Pipe => cx.pipe(),
            Init::Fresh => cx.var(),
        };
    }
    let mut links: [Option<Term>; 2] = [None, None];
    let mut n_links = 0;
    if let Some((b, unify, r)) = &p.in_arg {
        let pattern = build(cx, regs, b);
        regs[*r as usize] = pattern;
        if *unify {
            cx.in_arg(pattern)?;
        }
        links[n_links] = Some(pattern);
        n_links += 1;
    }
    if let Some((b, r)) = &p.out_arg {
        let o = build(cx, regs, b);
        regs[*r as usize] = o;
        links[n_links] = Some(o);
        n_links += 1;
    }
    match &p.prog {
        None => {}
        Some(Prog::InPlace(parts)) => {
            for part in parts {
                ev(cx, regs, part, None)?;
            }
        }
        Some(Prog::Copy(b)) => {
            let t = build(cx, regs, b);
            cx.prog(t, &links[..n_links])?;
        }
    }
    match &p.kind {
        KindPlan::Final { diag_mod } => {
            cx.final_out_arg(p.out_arg.as_ref().map(|(_, r)| regs[*r as usize]))?;
            if let Some(d) = diag_mod {
                let d = build(cx, regs, d);
                cx.diag_mod(d)?;
            }
            let empty = Term::atom(atoms::EMPTY);
            cx.record(empty, empty, None);
            Ok(Step::Final)
        }
        KindPlan::Perceptual(arcs) => run_arcs(arcs, cx, regs, None),
        KindPlan::Recursive {
            call,
            eval_call,
            saved,
            ..
        } => {
            let e = build(cx, regs, call);
            let call = if *eval_call { cx.embedded_dm(e)? } else { e };
            let saved = if saved.is_empty() {
                Term::NIL
            } else {
                let values: Vec<Term> = saved.iter().map(|&r| regs[r as usize]).collect();
                cx.compound(atoms::DOT, &values)
            };
            Ok(Step::Call { call, saved })
        }
    }
}

fn run_arcs(
    a: &Arcs,
    cx: Rcx<'_, '_, '_, '_>,
    regs: &mut [Term],
    final_id: Option<Term>,
) -> R<Step> {
    for arc in &a.arcs {
        for &r in &arc.fresh {
            regs[r as usize] = cx.var();
        }
        if !arc.import_from.is_empty() {
            let at = arc.import_at as usize;
            for (n, &src) in arc.import_from.iter().enumerate() {
                regs[at + n] = regs[src as usize];
            }
            cx.import(&mut regs[at..at + arc.import_from.len()]);
        }
    }
    let exps = a.exps as usize;
    let n = a.arcs.len();
    if a.pure {
        for (i, arc) in a.arcs.iter().enumerate() {
            regs[exps + i] = ev(cx, regs, &arc.expectation, Some(i))?;
        }
    } else {
        cx.save_vars();
        let mut result = Ok(());
        for (i, arc) in a.arcs.iter().enumerate() {
            match ev(cx, regs, &arc.expectation, Some(i)) {
                Ok(v) => regs[exps + i] = v,
                Err(e) => {
                    result = Err(e);
                    break;
                }
            }
        }
        cx.restore_vars();
        result?;
    }
    let chosen = if a.always_first {
        0
    } else {
        cx.set_expectations(&regs[exps..exps + n]);
        match final_id {
            Some(final_id) => cx.choose_exit(final_id)?,
            None => match cx.choose(a.type_term)? {
                Some(i) => i,
                None => {
                    return Ok(Step::Unmet {
                        type_term: a.type_term,
                    })
                }
            },
        }
    };
    let arc = &a.arcs[chosen];
    let at = Some(chosen);
    let action = match &arc.action {
        Action::List { items, regs: base } => {
            let base = *base as usize;
            for (i, item) in items.iter().enumerate() {
                regs[base + i] = ev(cx, regs, item, at)?;
            }
            let values = &regs[base..base + items.len()];
            if cx.ignores_numbers() {
                // Performing a number does nothing: only the others.
                for &x in values {
                    if cx.int_of(x).is_none() && cx.float_of(x).is_none() {
                        cx.perform_each(&[x], at)?;
                    }
                }
            } else {
                cx.perform_each(values, at)?;
            }
            if cx.records() {
                cx.store().list(values)
            } else {
                Term::NIL
            }
        }
        Action::One(e) => {
            let action = ev(cx, regs, e, at)?;
            // Performing a number does nothing when the actions ignore numbers.
            let number = cx.int_of(action).is_some() || cx.float_of(action).is_some();
            if !(number && cx.ignores_numbers()) {
                cx.perform(action, at)?;
            }
            action
        }
    };
    let (next_value, target) = next(cx, regs, &arc.next, at)?;
    if let Some(o) = &arc.out_arg {
        let o = build(cx, regs, o);
        cx.out_arg(o, at)?;
    }
    if let Some(d) = &arc.diag_mod {
        let d = build(cx, regs, d);
        cx.diag_mod(d)?;
    }
    cx.record(regs[exps + chosen], action, Some(next_value));
    match target {
        Some(ix) => Ok(Step::GotoSit(ix)),
        None => Ok(cx.goto(next_value, at)?),
    }
}

impl DmProgram for Resolved<'_> {
    fn dm_by_name(&self, name: Atom) -> Option<DmIx> {
        self.ir.dm_by_name(name)
    }
    fn dm_name(&self, dm: DmIx) -> Atom {
        DmProgram::dm_name(self.ir, dm)
    }
    fn situation_count(&self, dm: DmIx) -> usize {
        DmProgram::situation_count(self.ir, dm)
    }
    fn kind(&self, dm: DmIx, sit: SitIx) -> Kind {
        DmProgram::kind(self.ir, dm, sit)
    }
    fn fresh_head(&self, dm: DmIx, store: &mut Store) -> Term {
        DmProgram::fresh_head(self.ir, dm, store)
    }
    fn instantiate(&self, dm: DmIx, sit: SitIx, store: &mut Store) -> Instance {
        DmProgram::instantiate(self.ir, dm, sit, store)
    }
    fn may_select(&self, dm: DmIx, sit: SitIx, value: Term, store: &Store) -> bool {
        DmProgram::may_select(self.ir, dm, sit, value, store)
    }
    fn locals(&self, dm: DmIx, store: &mut Store) -> Vars {
        DmProgram::locals(self.ir, dm, store)
    }
    fn location(&self, dm: DmIx, sit: SitIx) -> Option<String> {
        DmProgram::location(self.ir, dm, sit)
    }
    fn compiled_id(&self, dm: DmIx, sit: SitIx) -> Option<(Atom, usize)> {
        self.plan(dm, sit).map(|p| p.id)
    }
    fn select_compiled(&self, dm: DmIx, sit: SitIx, value: Term, store: &mut Store) -> bool {
        let Some(p) = self.plan(dm, sit) else {
            return true;
        };
        for &(i, c) in &p.select {
            let x = store.args(value)[i];
            if !store.unify(x, c) {
                return false;
            }
        }
        true
    }
    fn run_situation(
        &self,
        dm: DmIx,
        sit: SitIx,
        cx: &mut Cx<'_, '_, Self>,
    ) -> Result<Step, RunError> {
        let mut sit = sit;
        loop {
            let Some(p) = self.plan(dm, sit) else {
                return Err(cx.error("the situation has no plan", None));
            };
            let step = with_regs(p.regs, |regs| run_plan(p, cx, regs)).map_err(|e| *e)?;
            match step {
                // Go on to the next situation of the DM by itself, until
                // the machine is needed.
                Step::GotoSit(next) if self.chain && !cx.gc_due() => match self.plan(dm, next) {
                    Some(q) if q.id.1 == 0 => {
                        cx.enter(next, q.id.0);
                        sit = next;
                    }
                    _ => return Ok(step),
                },
                _ => return Ok(step),
            }
        }
    }
    fn run_exit(
        &self,
        dm: DmIx,
        sit: SitIx,
        saved: Term,
        final_id: Term,
        cx: &mut Cx<'_, '_, Self>,
    ) -> Result<Step, RunError> {
        let Some(p) = self.plan(dm, sit) else {
            return Err(cx.error("the situation has no plan", None));
        };
        let KindPlan::Recursive {
            saved: saved_regs,
            exit,
            ..
        } = &p.kind
        else {
            return Err(cx.error("the situation is not recursive", None));
        };
        with_regs(p.regs, |regs| {
            for (n, &r) in saved_regs.iter().enumerate() {
                regs[r as usize] = cx.arg(saved, n);
            }
            run_arcs(exit, cx, regs, Some(final_id))
        })
        .map_err(|e| *e)
    }
}

impl sitlog_runtime::app::App for Resolved<'_> {
    fn initial_state(&self) -> (Store, Vars) {
        self.ir.initial_state()
    }
    fn basic_actions(&self) -> Vec<Atom> {
        self.ir.basic_actions.clone()
    }
    fn recovery(&self) -> Vec<(Atom, Atom)> {
        self.ir.recovery.clone()
    }
    fn render_error(
        &self,
        error: &sitlog_runtime::machine::RunError,
        color: bool,
    ) -> Option<String> {
        self.ir.render_error(error, color)
    }
    fn error_location(&self, error: &sitlog_runtime::machine::RunError) -> Option<String> {
        self.ir.error_location(error)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::{self, RunConfig};
    use sitlog_runtime::machine::Options;
    use sitlog_runtime::report;
    use sitlog_runtime::testmode::{ScriptPerception, TextActions};

    fn lower(src: &str) -> Ir {
        let (program, diags) = crate::load::load_sources(&[("t.dm", src)]);
        let (result, diags) = crate::check::check(program, diags);
        let errors: Vec<_> = diags.iter().filter(|d| d.is_error()).collect();
        assert!(errors.is_empty(), "{errors:?}");
        crate::ir::lower(&result.expect("checks"))
    }

    /// The JSON report of a run, with or without plans, variables renamed away.
    fn report(ir: &Ir, script: &str, plans: bool, keep_history: bool) -> String {
        let mut perception = ScriptPerception::new("script", script.to_owned());
        let mut actions = TextActions::new(std::io::sink(), Vec::new());
        let config = RunConfig {
            options: Options {
                keep_history,
                ..Options::default()
            },
            ..RunConfig::default()
        };
        let runner = if plans { run::run } else { run::run_unresolved };
        let (outcome, store) =
            runner(ir, config, &mut perception, &mut actions, None).expect("runs");
        let text = report::outcome_json(&store, &outcome);
        // `_G12`, `_123`: numbering differs between the paths.
        let mut out = String::new();
        let mut chars = text.chars().peekable();
        while let Some(c) = chars.next() {
            out.push(c);
            if c == '_' {
                while chars
                    .peek()
                    .is_some_and(|d| d.is_ascii_digit() || *d == 'G')
                {
                    chars.next();
                }
            }
        }
        out
    }

    fn agree(src: &str, script: &str) -> Ir {
        let ir = lower(src);
        for keep in [true, false] {
            assert_eq!(
                report(&ir, script, true, keep),
                report(&ir, script, false, keep),
                "plans and templates disagree (history kept: {keep})"
            );
        }
        ir
    }

    #[test]
    fn one_situation_per_step_runs_the_same() {
        let ir = lower(
            "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : inc(n, N) => (N >= 5 -> fs ; otherwise -> is)]],
  [id ==> fs, type ==> final]], [n ==> 0]).\n",
        );
        let run = |resolved: &Resolved<'_>| {
            let mut perception = ScriptPerception::new("script", String::new());
            let mut actions = TextActions::new(std::io::sink(), Vec::new());
            let (store, globals) = ir.initial_state();
            let machine = sitlog_runtime::machine::Machine::new(
                resolved,
                store,
                globals,
                sitlog_runtime::Functions::standard(),
                Options::default(),
            );
            let (outcome, store) = machine.run(
                Term::atom(Atom::intern("main")),
                Term::atom(atoms::NONE),
                &mut perception,
                &mut actions,
                None,
            );
            report::outcome_json(&store, &outcome)
        };
        assert_eq!(
            run(&Resolved::new(&ir)),
            run(&Resolved::new(&ir).one_situation_per_step())
        );
    }

    #[test]
    fn a_counter_loop_runs_from_plans() {
        let ir = agree(
            "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : inc(n, N) => (N >= 5 -> fs ; otherwise -> is)]],
  [id ==> fs, type ==> final]], [n ==> 0]).\n",
            "",
        );
        assert_eq!(Resolved::new(&ir).counts(), (2, 2));
    }

    #[test]
    fn calls_pipes_scripts_and_compound_ids_agree() {
        let ir = agree(
            "diag_mod(main, [
  [id ==> is, type ==> speech, arcs ==> [
      tick : [inc(n, _), say(tick)] => is,
      go(X) : [set(last, X)] => step(X, 1),
      stop : [] => call]],
  [id ==> step(X, K), type ==> neutral, arcs ==> [empty : say(X) => (K > 0 -> is ; otherwise -> fs)]],
  [id ==> call, type ==> recursive, embedded_dm ==> add_one(get(n, _)), out_arg ==> Out,
   arcs ==> [done(R) : say(R) => fs]],
  [id ==> fs, type ==> final, out_arg ==> get(last, _)]],
  [n ==> 0, last ==> none]).
diag_mod(add_one(A), [
  [id ==> is, type ==> neutral, in_arg ==> P, out_arg ==> Q,
   arcs ==> [empty : (Q is A + 1) => done(Q)]],
  [id ==> done(R), type ==> final, diag_mod ==> add_one(_)]], []).\n",
            "tick.\ngo(a).\ntick.\nnothing.\nstop.\n",
        );
        let (planned, all) = Resolved::new(&ir).counts();
        assert!(planned >= 4 && planned <= all, "{planned} of {all}");
    }

    #[test]
    fn errors_agree() {
        agree(
            "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : inc(n, _) => (get(n, _) > a -> is ; otherwise -> fs)]],
  [id ==> fs, type ==> final]],
  [n ==> 0]).\n",
            "",
        );
    }

    #[test]
    fn a_deep_term_keeps_its_situation_on_templates() {
        let mut list = String::from("X");
        for i in 0..(MAX_DEPTH + 50) {
            list = format!("f{}({list})", i % 3);
        }
        let src = format!(
            "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : say({list}) => fs]],
  [id ==> fs, type ==> final]], []).\n"
        );
        let ir = agree(&src, "");
        assert_eq!(Resolved::new(&ir).counts(), (1, 2));
    }
}
