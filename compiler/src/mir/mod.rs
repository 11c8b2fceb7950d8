//! The mid-level representation (MIR) between the IR and the two back
//! ends: each situation that runs as code lowered once into a [`SitPlan`]
//! (its variables as registers, its steps as a small tree over the
//! runtime's `Cx` calls: build, evaluate, test, choose, go on), or left to
//! the instantiating path.
//!
//! Invariant: the rules of *which situations run as code* (an atom id, or
//! a compound id, whose variables shared with the DM's parameters are
//! [`SitPlan::links`]; any type, a
//! compound one built from the situation's variables; a DM whose head
//! names each of its variables once, an argument a variable or a pattern
//! ([`Init::HeadPath`]); no term deeper than [`MAX_DEPTH`]),
//! *which variables are lazy* (first occurring as the argument of
//! `get`/`inc`, the variable of `is`, or a side of `=` whose other side
//! does not name it), *where a constant next
//! situation goes* and *which out_arg passes the pipe on unchanged*
//! ([`OutPass`]) are decided here only. The interpreter
//! ([`crate::interp`]) runs the plans; the code generator
//! ([`crate::codegen`]) prints them as Rust; both therefore take the same
//! steps in the same order, which `tests/tests/suite/random_agreement.rs`
//! checks.

use crate::ir::{none_marker, Ir, IrDm, IrSituation};
use sitlog_runtime::machine::{Kind, SitIx};
use sitlog_runtime::{eval, ArithCmp, Atom, Store, Term, Value};
use sitlog_syntax::atoms;
use std::collections::{HashMap, HashSet};

mod lower;
mod out_pass;
pub(crate) use lower::is_type_test;
pub use out_pass::OutPass;
pub mod ty;

use lower::Planner;

/// Field positions in a situation template (see [`crate::ir`]).
pub(crate) const HEAD: usize = 0;
pub(crate) const ID: usize = 1;
pub(crate) const TYPE: usize = 2;
pub(crate) const IN_ARG: usize = 3;
pub(crate) const OUT_ARG: usize = 4;
pub(crate) const PROG: usize = 5;
pub(crate) const EMBEDDED_DM: usize = 6;
pub(crate) const DIAG_MOD: usize = 7;
pub(crate) const ARCS: usize = 8;

/// Deepest term the planner turns into a tree of steps; a deeper one keeps
/// its situation on the instantiating path (no deep recursion at run time).
pub const MAX_DEPTH: usize = 200;

/// Registers of one visit kept on the stack (more spill to the heap).
pub(crate) const STACK_REGS: usize = 32;

/// A register of one visit of a situation.
pub type Reg = u32;

/// Why the planner left a situation to the instantiating path (a variable
/// it does not know, a term too deep): never an error of the program.
#[derive(Debug)]
pub(crate) struct Unsupported;

pub(crate) type Plan<T> = Result<T, Unsupported>;

/// A term built from registers, not evaluated.
#[derive(Debug, Clone)]
pub enum Build {
    /// Atomic, or ground: a frozen term of the IR's store.
    Const(Term),
    Reg(Reg),
    Compound(Atom, Box<[Build]>),
}

/// A term evaluated in L, as the generated code evaluates it.
#[derive(Debug)]
pub enum Ev {
    /// A variable occurrence: its value ([`Cx::value`](sitlog_runtime::machine::Cx::value)).
    Value(Reg),
    /// Evaluating gives the term itself.
    Built(Build),
    /// Anything else: the runtime's evaluator.
    Eval(Build),
    If(Box<Cond>, Box<Ev>, Box<Ev>),
    /// The runtime's `when/3` (`Planner::when_call`): the condition
    /// decided, then both branches evaluated in this order (as `apply`
    /// evaluates its arguments, D-37), the value the condition picks.
    Pick(Box<Cond>, Box<Ev>, Box<Ev>),
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
    /// `V = E` or `E = V` for a variable `V` not made yet and not in `E`
    /// (D-30: unified, not evaluated): `V` takes `E`'s term as built, which
    /// is also the value. The unification cannot fail and makes no cycle.
    BindFresh {
        expr: Build,
        dst: Reg,
    },
    /// A compound whose evaluation evaluates its arguments only.
    Compound(Atom, Box<[Ev]>),
}

#[derive(Debug)]
pub enum Cond {
    Arith(ArithCmp, Ev, Ev),
    Other(Build),
    /// The value of `A op B` (`<`, `>`, `=<`, `>=`) is `true` (D-34), the
    /// condition of a `when/3` (`Planner::when_call`) or an operand of
    /// [`Cond::And`]: `A` and `B` (a register, a constant or an expression
    /// of them such as `N + 1`, as written) evaluated as a variable's
    /// occurrence is (a compound: the evaluator's value, D-36), then
    /// compared; an error is the evaluator's (`eval::compare_value`: the
    /// term as written, blaming `op/2`).
    Cmp(ArithCmp, Build, Build),
    /// `(A, B)` in a conditional's condition (`Planner::junction`): the
    /// condition's arguments are evaluated before it is called (D-35), so
    /// both operands are computed, left then right, each an error of its
    /// own (the left one's first), then both must hold. An operand is a
    /// leaf whose value is `true` or `false` (a comparison of L, D-34, as
    /// [`Cond::Cmp`]; `==`, `\==`, `member/2`, `not_member/2` as
    /// [`Cond::Other`], D-33), or another `And`/`Or`; an error is the
    /// condition's (`Cx::compare_condition`, `Cx::value_holds`: no culprit).
    And(Box<Cond>, Box<Cond>),
    /// `(A ; B)`: as [`Cond::And`] (both computed first), then either holds.
    Or(Box<Cond>, Box<Cond>),
}

/// A next situation: its value and, when known, its index.
#[derive(Debug)]
pub enum Next {
    Static(Term, Option<SitIx>),
    If(Box<Cond>, Box<Next>, Box<Next>),
    Eval(Ev),
}

/// How a situation variable starts a visit.
#[derive(Debug, Clone)]
pub enum Init {
    /// Argument `i` of the selecting value (a compound id).
    IdArg(usize),
    /// The subterm of the id at this path of argument positions (an id
    /// that is a pattern, [`IdPattern`]): where the variable first occurs.
    IdPath(Box<[usize]>),
    /// Argument `i` of the DM call.
    HeadArg(usize),
    /// The part at this path of argument positions of argument `i` of the
    /// DM call, whose head argument there is a pattern (`K` in
    /// `key_of(K-_Qty)`: `HeadPath(0, [0])`). The head is unified with the
    /// call where the DM starts (E13: an error where it does not unify), so
    /// the argument is an instance of the pattern and every later fresh
    /// head's unification with it (D-7) binds the variable to that part.
    HeadPath(usize, Box<[usize]>),
    /// A variable in_arg: the incoming pipe.
    Pipe,
    Fresh,
}

#[derive(Debug)]
pub enum IdPart {
    Fresh(Reg),
    Const(Term),
}

/// A compound id that is a pattern (an argument neither a fresh variable
/// nor atomic, or a variable twice: `try([P|Ps])`, `check(O, S, S, R)`):
/// selected by unifying the value with a fresh copy of `term`, as an
/// instance's id would be; built from `build` over the fresh registers
/// `fresh` when no value selected it (a DM's initial situation).
#[derive(Debug)]
pub struct IdPattern {
    /// The id as written (a term of the IR's store).
    pub term: Term,
    pub fresh: Vec<Reg>,
    pub build: Build,
}

#[derive(Debug)]
pub enum Prog {
    /// Evaluated in place, element by element.
    InPlace(Vec<Ev>),
    /// On a copy sharing in_arg's and out_arg's variables (D-10).
    Copy(Build),
}

#[derive(Debug)]
pub enum Action {
    /// A list written out: elements evaluated into `regs`, performed one by one.
    List {
        items: Vec<Ev>,
        regs: Reg,
    },
    One(Ev),
}

#[derive(Debug)]
pub struct ArcPlan {
    pub fresh: Vec<Reg>,
    /// Imported variables: sources, copied into `import_at..` and imported jointly.
    pub import_from: Vec<Reg>,
    pub import_at: Reg,
    pub expectation: Ev,
    pub action: Action,
    pub next: Next,
    /// The situation's out_arg, evaluated after the next situation (D-18):
    /// its value becomes the pipe unless it is a variable.
    pub out_arg: Option<Ev>,
    pub diag_mod: Option<Build>,
}

#[derive(Debug)]
pub struct Arcs {
    pub arcs: Vec<ArcPlan>,
    /// No expectation can change a variable: nothing saved around them.
    pub pure: bool,
    /// `neutral` with `[empty : A => N]`: the arc is taken (D-14).
    pub always_first: bool,
    /// The situation's type, built from the situation's registers when it
    /// is not an atom (`presence(Seconds)`).
    pub type_term: Build,
    /// The evaluated expectations: registers `exps..exps + arcs.len()`.
    pub exps: Reg,
}

#[derive(Debug)]
pub enum KindPlan {
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
pub struct SitPlan {
    pub id: (Atom, usize),
    /// Constant arguments of a compound id, unified when it is selected.
    pub select: Vec<(usize, Term)>,
    /// A compound id built when not selected by a value.
    pub compound_id: Option<Vec<IdPart>>,
    /// An id that is a pattern (then `select` is empty and `compound_id` `None`).
    pub pattern: Option<IdPattern>,
    pub inits: Vec<(Reg, Init)>,
    /// Id variables that are also DM parameters (`back(N)` in DM
    /// `mirror(N)`), in the head's order: the id is selected as if they
    /// were fresh, then each register (the id's value there) is unified
    /// with the DM call's argument, undone where it does not unify (D-7:
    /// an instance's fresh head linked argument by argument).
    pub links: Vec<(Reg, usize)>,
    /// in_arg: the pattern, unified with the pipe when `unify`; kept in `reg`.
    pub in_arg: Option<(Build, bool, Reg)>,
    /// out_arg of a non-recursive situation, built into `reg`.
    pub out_arg: Option<(Build, Reg)>,
    pub prog: Option<Prog>,
    pub kind: KindPlan,
    pub regs: usize,
}

/// The plans of a program: per DM, per situation, its plan or `None`
/// (instantiated from its template).
#[derive(Debug)]
pub struct Mir {
    pub dms: Vec<Vec<Option<SitPlan>>>,
    /// A plan runs a call of the runtime's own `when/3` as the conditional
    /// it equals (`Planner::when_call` in `mir::lower`): a run of the
    /// program needs the registry's `when/3` to be the runtime's
    /// (`DmProgram::lowers_runtime_when`, checked at the run's start).
    pub runtime_when: bool,
}

impl Mir {
    /// The plan of situation `sit` of DM `dm`, when it runs as code.
    pub fn plan(&self, dm: u32, sit: SitIx) -> Option<&SitPlan> {
        self.dms[dm as usize][sit as usize].as_ref()
    }

    /// How many situations run as code, of how many.
    pub fn counts(&self) -> (usize, usize) {
        let all = self.dms.iter().map(Vec::len).sum();
        let planned = self.dms.iter().flatten().filter(|p| p.is_some()).count();
        (planned, all)
    }
}

/// Lowers every situation of the IR that can run as code (see the module doc).
pub fn lower(ir: &Ir) -> Mir {
    let std_when = std_when(ir);
    let mut runtime_when = false;
    let dms = ir
        .dms
        .iter()
        .map(|dm| {
            (0..dm.situations.len())
                .map(|i| {
                    let mut planner = Planner::new(&ir.store, dm);
                    planner.std_when = std_when;
                    planner.globals = &ir.globals;
                    let lowered_when = planner.lowered_when.clone();
                    let plan = planner.situation(i).ok();
                    runtime_when |= plan.is_some() && lowered_when.get();
                    plan
                })
                .collect()
        })
        .collect();
    Mir { dms, runtime_when }
}

/// Whether `apply(when(..), ..)` calls the runtime's own `when/3`
/// (`functions::standard`): neither the application's Prolog (every file
/// it consults read: a `:- consult('$SITLOG_HOME/..')` the loader cannot
/// read may define it, as the original's applications do) nor the host
/// (`host_functions.pl`) defines `when/3`, which would replace it
/// (`Engine::install`). Only then does the planner lower it as a
/// conditional ([`Planner::when_call`](lower::Planner)).
fn std_when(ir: &Ir) -> bool {
    let when = (Atom::intern("when"), 3);
    ir.prolog_complete && !ir.prolog_functions.contains(&when) && !ir.host_functions.contains(&when)
}

impl Build {
    fn constants(&self, out: &mut Vec<Term>) {
        match self {
            Build::Const(t) => out.push(*t),
            Build::Reg(_) => {}
            Build::Compound(_, args) => args.iter().for_each(|a| a.constants(out)),
        }
    }
}

impl Ev {
    fn constants(&self, out: &mut Vec<Term>) {
        match self {
            Ev::Value(_) | Ev::VarOpFresh { .. } => {}
            Ev::Built(b)
            | Ev::Eval(b)
            | Ev::VarOp { arg: b, .. }
            | Ev::IsFresh { expr: b, .. }
            | Ev::BindFresh { expr: b, .. } => b.constants(out),
            Ev::If(c, a, b) | Ev::Pick(c, a, b) => {
                c.constants(out);
                a.constants(out);
                b.constants(out);
            }
            Ev::Is { lhs, expr } => {
                lhs.constants(out);
                expr.constants(out);
            }
            Ev::Compound(_, args) => args.iter().for_each(|a| a.constants(out)),
        }
    }
}

impl Cond {
    fn constants(&self, out: &mut Vec<Term>) {
        match self {
            Cond::Arith(_, l, r) => {
                l.constants(out);
                r.constants(out);
            }
            Cond::Other(b) => b.constants(out),
            Cond::Cmp(_, l, r) => {
                l.constants(out);
                r.constants(out);
            }
            Cond::And(l, r) | Cond::Or(l, r) => {
                l.constants(out);
                r.constants(out);
            }
        }
    }

    /// A leaf of [`Cond::And`]/[`Cond::Or`], or one of them, as written:
    /// the term the condition's evaluator would be given (`None` for
    /// [`Cond::Arith`], never such a leaf).
    pub fn written(&self) -> Option<Build> {
        Some(match self {
            Cond::Cmp(op, l, r) => Build::Compound(op.atom(), [l.clone(), r.clone()].into()),
            Cond::And(l, r) => Build::Compound(atoms::COMMA, [l.written()?, r.written()?].into()),
            Cond::Or(l, r) => {
                Build::Compound(atoms::SEMICOLON, [l.written()?, r.written()?].into())
            }
            Cond::Other(b) => b.clone(),
            Cond::Arith(..) => return None,
        })
    }
}

impl Next {
    fn constants(&self, out: &mut Vec<Term>) {
        match self {
            Next::Static(t, _) => out.push(*t),
            Next::If(c, a, b) => {
                c.constants(out);
                a.constants(out);
                b.constants(out);
            }
            Next::Eval(e) => e.constants(out),
        }
    }
}

impl Arcs {
    fn constants(&self, out: &mut Vec<Term>) {
        self.type_term.constants(out);
        for arc in &self.arcs {
            arc.expectation.constants(out);
            match &arc.action {
                Action::List { items, .. } => items.iter().for_each(|e| e.constants(out)),
                Action::One(e) => e.constants(out),
            }
            arc.next.constants(out);
            if let Some(e) = &arc.out_arg {
                e.constants(out);
            }
            if let Some(b) = &arc.diag_mod {
                b.constants(out);
            }
        }
    }
}

impl SitPlan {
    /// Every frozen term the plan uses on its own (a back end may make
    /// each a constant of its program).
    pub fn constants(&self, out: &mut Vec<Term>) {
        out.extend(self.select.iter().map(|&(_, t)| t));
        for part in self.compound_id.iter().flatten() {
            if let IdPart::Const(t) = part {
                out.push(*t);
            }
        }
        if let Some(p) = &self.pattern {
            p.build.constants(out);
        }
        if let Some((b, _, _)) = &self.in_arg {
            b.constants(out);
        }
        if let Some((b, _)) = &self.out_arg {
            b.constants(out);
        }
        match &self.prog {
            Some(Prog::InPlace(evs)) => evs.iter().for_each(|e| e.constants(out)),
            Some(Prog::Copy(b)) => b.constants(out),
            None => {}
        }
        match &self.kind {
            KindPlan::Final { diag_mod } => {
                if let Some(b) = diag_mod {
                    b.constants(out);
                }
            }
            KindPlan::Perceptual(arcs) => arcs.constants(out),
            KindPlan::Recursive { call, exit, .. } => {
                call.constants(out);
                exit.constants(out);
            }
        }
    }
}
