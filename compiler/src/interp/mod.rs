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

mod plan;
mod run;

use plan::*;
use run::*;

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
    fn names(&self) -> Vec<(String, Vec<String>)> {
        self.ir.names()
    }
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
        let mut list = String::from("_X");
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
