//! The interpreter's resolved program: the IR with the [MIR](crate::mir)'s
//! plans, which the machine runs without looking names up or copying
//! situation templates.
//!
//! A situation that runs as code (the rule is [`crate::mir`]'s, shared with
//! the code generator) is run from its *plan*: a small tree of steps over
//! the runtime's [`Cx`], the same steps, in the same order, as the
//! generated code of that situation takes. Variables live in registers of
//! one visit (no map from names), ground parts of the templates are the
//! IR's frozen terms (built once, at lowering), a constant next situation
//! is resolved to its index, and the machine's situations of one DM follow
//! each other without going back to the machine's loop. Every other
//! situation is instantiated from its template, as before: the plans only
//! skip work whose result is known before the run, so semantics are the
//! runtime's.
//!
//! Invariant: [`Resolved`] runs a program exactly as the IR alone does (the
//! same reports, histories and errors, up to the names of unbound
//! variables); `tests/tests/suite/random_agreement.rs` compares the two on random
//! programs and scripts, and both with the generated code.

use crate::ir::Ir;
use crate::mir::*;
use sitlog_runtime::machine::{Cx, DmIx, DmProgram, Instance, Kind, RunError, SitIx, Step};
use sitlog_runtime::{atoms, ArithCmp, Atom, Store, Term, Vars};

mod run;

use run::*;

/// The IR with plans for the situations it can resolve (see the module doc).
pub struct Resolved<'ir> {
    ir: &'ir Ir,
    plans: Mir,
    /// Go on to the next planned situation of a DM without returning to the
    /// machine's loop (as generated code does).
    chain: bool,
    /// Situations instantiated from their templates so far, by every run
    /// of this program (those without a plan).
    instantiated: std::sync::atomic::AtomicUsize,
}

impl<'ir> Resolved<'ir> {
    /// Plans every situation that can be resolved.
    pub fn new(ir: &'ir Ir) -> Resolved<'ir> {
        let plans = crate::mir::lower(ir);
        Resolved {
            ir,
            plans,
            chain: true,
            instantiated: std::sync::atomic::AtomicUsize::new(0),
        }
    }

    /// How many situations the runs of this program have instantiated from
    /// their templates (none when every situation they reached has a plan).
    pub fn templates_instantiated(&self) -> usize {
        self.instantiated.load(std::sync::atomic::Ordering::Relaxed)
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
        self.plans.counts()
    }

    fn plan(&self, dm: DmIx, sit: SitIx) -> Option<&SitPlan> {
        self.plans.plan(dm, sit)
    }
}

impl DmProgram for Resolved<'_> {
    fn dm_by_name(&self, name: Atom) -> Option<DmIx> {
        self.ir.dm_by_name(name)
    }
    fn left_out(&self, name: Atom) -> Option<String> {
        DmProgram::left_out(self.ir, name)
    }
    fn dm_name(&self, dm: DmIx) -> Atom {
        DmProgram::dm_name(self.ir, dm)
    }
    fn lowers_runtime_when(&self) -> bool {
        self.plans.runtime_when
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
    fn instantiate(&self, dm: DmIx, sit: SitIx, store: &mut Store) -> Option<Instance> {
        self.instantiated
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
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
    fn in_arg_location(&self, dm: DmIx, sit: SitIx) -> Option<String> {
        DmProgram::in_arg_location(self.ir, dm, sit)
    }
    fn compiled_id(&self, dm: DmIx, sit: SitIx) -> Option<(Atom, usize)> {
        self.plan(dm, sit).map(|p| p.id)
    }
    fn select_compiled(&self, dm: DmIx, sit: SitIx, value: Term, store: &mut Store) -> bool {
        let Some(p) = self.plan(dm, sit) else {
            return true;
        };
        if let Some(pat) = &p.pattern {
            // As an instance's id: a fresh copy of the pattern unified with the value.
            let c = store.copy_term(pat.term);
            return store.unify(value, c);
        }
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
                    // A compound id is built by the situation's plan.
                    Some(q) => {
                        cx.enter(next, q.id.0);
                        sit = next;
                    }
                    None => return Ok(step),
                },
                // A next situation computed at run time: selected here when
                // the machine would select a situation with a plan.
                Step::Goto(value) if self.chain && !cx.gc_due() => match cx.enter_selected(value) {
                    Some(next) => sit = next,
                    None => return Ok(step),
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
    fn ids_that_are_patterns_run_from_plans() {
        let src = "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : say(go) => walk([a, f(b), c|_])]],
  [id ==> walk([]), type ==> neutral, arcs ==> [empty : say(done) => check(x, y, y)]],
  [id ==> walk([f(X)|T]), type ==> neutral, arcs ==> [empty : say(f(X)) => walk(T)]],
  [id ==> walk([H|T]), type ==> neutral, in_arg ==> P, arcs ==> [empty : say(H-P) => walk(T)]],
  [id ==> check(A, B, B), type ==> neutral, arcs ==> [empty : say(A) => pipe(x)]],
  [id ==> pipe(Q), type ==> neutral, in_arg ==> Q, arcs ==> [empty : say(Q) => fs]],
  [id ==> fs, type ==> final]], []).\n";
        let ir = agree(src, "");
        assert_eq!(Resolved::new(&ir).counts(), (7, 7));
        // The first situation with a pattern id, and a variable in_arg
        // that is the id's: the pipe is unified with it (an error here).
        agree(
            "diag_mod(main, [
  [id ==> walk([H|T]), type ==> neutral, in_arg ==> H, arcs ==> [empty : say(H-T) => walk([])]],
  [id ==> walk([]), type ==> final]], []).\n",
            "",
        );
    }

    #[test]
    fn compound_types_run_from_plans() {
        // A type built from a parameter and from an id variable, as an
        // instance's would be; unmet input and recovery see the same term.
        let ir = agree(
            "diag_mod(main, [
  [id ==> is, type ==> recursive, embedded_dm ==> wait(speech), arcs ==> [done(W) : say(W) => fs]],
  [id ==> fs, type ==> final]], []).
diag_mod(wait(T), [
  [id ==> is, type ==> T, arcs ==> [go(X) : say(X) => at(T)]],
  [id ==> at(U), type ==> U, arcs ==> [stop : empty => done(U)]],
  [id ==> done(U), type ==> final]], []).\n",
            "go(a).\nnothing.\nstop.\n",
        );
        assert_eq!(Resolved::new(&ir).counts(), (5, 5));
    }

    #[test]
    fn computed_next_situations_are_selected_as_the_machine_would() {
        // `s(X)` shares the DM's parameter: left to its template, it may
        // take `s(..)` first, so the machine selects; `t(..)` is selected
        // by the plans' loop itself, `t([])` before `t([H|T])`, and a name
        // no situation has is the machine's error.
        for main in ["m(b)", "m(a)"] {
            let src = format!(
                "diag_mod(main, [
  [id ==> is, type ==> recursive, embedded_dm ==> {main}, arcs ==> [R : say(R) => fs]],
  [id ==> fs, type ==> final]], []).
diag_mod(m(X), [
  [id ==> is, type ==> neutral, arcs ==> [empty : say(go) => s(a)]],
  [id ==> s(X), type ==> neutral, arcs ==> [empty : say(param) => t([1, 2])]],
  [id ==> s(Y), type ==> neutral, arcs ==> [empty : say(Y) => t([3])]],
  [id ==> t([]), type ==> neutral, arcs ==> [empty : say(empty) => u(1)]],
  [id ==> t([H|T]), type ==> neutral, arcs ==> [empty : say(H) => t(T)]],
  [id ==> u(N), type ==> final]], []).\n"
            );
            agree(&src, "");
        }
        agree(
            "diag_mod(main, [
  [id ==> is, type ==> neutral, arcs ==> [empty : get(w, N) => N]],
  [id ==> fs, type ==> final]], [w ==> nowhere(1)]).\n",
            "",
        );
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

    /// Store cells and variables made by each visit of `try(..)` in a walk
    /// of `places` atoms (issue 37: a visit shares the rest of the list).
    fn growth_per_visit(ir: &Ir, places: usize, plans: bool, keep_history: bool) -> usize {
        struct Growth {
            last: Option<usize>,
            most: usize,
        }
        impl sitlog_runtime::machine::Observer for Growth {
            fn transition(
                &mut self,
                store: &Store,
                entry: &sitlog_runtime::history::Entry,
                _depth: usize,
                _next: Option<Term>,
            ) {
                let st = store.stats();
                let now = st.cells + st.vars;
                if store.writeq(entry.situation).starts_with("try([") {
                    if let Some(last) = self.last {
                        self.most = self.most.max(now.saturating_sub(last));
                    }
                    self.last = Some(now);
                }
            }
        }
        let names: Vec<String> = (0..places).map(|i| format!("p{i}")).collect();
        let mut perception = ScriptPerception::new("script", String::new());
        let mut actions = TextActions::new(std::io::sink(), Vec::new());
        let config = RunConfig {
            main: format!("main([{}], p{})", names.join(","), places - 1),
            options: Options {
                keep_history,
                // No collection: the store's size is what the visits made.
                gc_threshold: usize::MAX / 2,
                ..Options::default()
            },
            ..RunConfig::default()
        };
        let mut growth = Growth {
            last: None,
            most: 0,
        };
        let runner = if plans { run::run } else { run::run_unresolved };
        let (outcome, _) =
            runner(ir, config, &mut perception, &mut actions, Some(&mut growth)).expect("runs");
        assert!(outcome.result.is_ok(), "{:?}", outcome.result);
        growth.most
    }

    #[test]
    fn a_visit_of_a_list_walk_shares_the_rest_of_the_list() {
        // Workload (d) of issue 37, with the list also inside a nested
        // compound of the id and in a local (any ground argument is shared).
        let ir = agree(
            "diag_mod(main(Places, Target), [
  [id ==> is, type ==> recursive, embedded_dm ==> search(Places, Target),
   arcs ==> [found(P) : say(P) => fs, not_found : empty => fs]],
  [id ==> fs, type ==> final]], []).
diag_mod(search(Places, Target), [
  [id ==> is, type ==> neutral, arcs ==> [empty : empty => try(Places, st(Places, Target))]],
  [id ==> try([], _), type ==> neutral, arcs ==> [empty : empty => not_found]],
  [id ==> try([P|Ps], st(All, T)), type ==> neutral,
   arcs ==> [empty : [set(rest, Ps)] => (P == T -> found(P) ; otherwise -> try(Ps, st(All, T)))]],
  [id ==> found(P), type ==> final],
  [id ==> not_found, type ==> final]], [rest ==> []]).\n",
            "",
        );
        for plans in [true, false] {
            for keep in [true, false] {
                let short = growth_per_visit(&ir, 8, plans, keep);
                let long = growth_per_visit(&ir, 256, plans, keep);
                // A copy of the rest of the list would be 3 cells an element.
                assert!(
                    long <= short && long < 256,
                    "cells made per visit, 8 places: {short}, 256: {long} (plans: {plans}, history kept: {keep})"
                );
            }
        }
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
