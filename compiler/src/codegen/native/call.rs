//! The caller's side of native DMs: a recursive situation with native
//! code whose embedded DM's initial situation has native code (its locals
//! native, the arguments converting to its frame) pushes the callee's
//! typed frame on the driver's native stack ([`super::frame`]), the
//! arguments moved into it (a first situation whose id names parameters,
//! `first(N)` in `bump(N)`, takes them as its fields: the link of D-7 at
//! the start, `Gen::nat_start_fields`), and waits in its own variant `W<ix>` (the
//! situation's id variables and the registers its exit arcs read); when
//! the callee reaches a final, the exit arcs are matched against the
//! callee's final variant natively (`found(P)` binds `P` from the
//! variant's field), their action (`inc` and `get` of a local, `inc`,
//! `get` and `set` of a global read and written in the machine's globals
//! at each use (`Gen::nat_global_op`), atoms, numbers) and next situation
//! run natively. A call whose exit arcs
//! native code does not run (`say('..')`, `apply(..)` in the action) is
//! not pushed: the machine's, as below. The call's arguments are values
//! or, evaluated (D-20, read-only), `get(l, _)` of a local held in the
//! frame, its variable met only there (`search(get(places, _), T)`: the
//! local's value, `Gen::nat_local_get`); where the frames become the
//! machine's, `Cx::wait_template` evaluates the template's `embedded_dm`
//! before matching it with the call. The exit arms' tail where no arc
//! takes the final, in a DM without locals, is one call of
//! `NatBelow::no_exit` (the hand-over and the machine's error).
//!
//! *Output arguments* (`add(I, 1, J)`, `J` a fresh variable of the
//! situation written once, as a whole argument: `call_outputs`) given to
//! an output parameter of the callee (`DmTypes::outputs`: no situation
//! reads it, every final binds it in its `diag_mod`) are passed as no term
//! (`Ground::OUT` in the callee's frame); a final whose `diag_mod` is the
//! head with the outputs computed natively and every other argument the
//! parameter itself (`slot_final`) writes them to the frame's output slots
//! (`out<i>: Option<T>`) instead of unifying, and the caller's exit arcs
//! read them from there (`W<ix>` keeps no output register). That is the
//! term path's unification exactly: the caller's variable is fresh and
//! appears nowhere else, the other arguments unify with themselves. Where
//! the frames become the machine's while the callee runs
//! (`nat_materialize`), the callee's frame is pushed with the call the
//! caller's `embedded_dm` makes (`Cx::wait_template`, below): the variable
//! is the caller's instance's, so the machine's `diag_mod` binds it for the
//! caller's exit arcs. A variable given twice or inside an
//! argument, an output the callee may leave unbound, an output of a type
//! the caller's register does not take: the machine's call, as below.
//!
//! *With the history kept* (`run.nests`: kept, nothing observing) a call
//! whose exit arcs record their entries natively (their expectation a term
//! of the registers, their action of the values computed:
//! `nat_exit_record`) is pushed too: the callee's call term (`call_term`,
//! an output argument a fresh variable) opens a history level of its own
//! (`Cx::open_level`) that takes its entries; its final below the base binds
//! the outputs in that term, records its entry and closes the level, nested
//! in the caller's (`Cx::close_level`); the exit arc then records the
//! caller's entry (one copy of the exit arms: each arc's tail enters the
//! situation and builds the entry's terms where `TypedRun::recorded`, a
//! cold branch, and counts the transition otherwise; the next situation is
//! the same code either way, its hand-overs recording through `run.goto`).
//! The callee's frame is built once for both pushes, the level opened only
//! when recorded. Where the frames become the machine's, each pushed frame
//! takes its level (`Cx::wait_template`). A callee's visit records natively
//! where its action is `empty` or one native code runs (`inc`, `is`, values:
//! `Gen::nat_arc_rec_fast`); any other records on the machine's frames
//! (the native stack materialized first).
//!
//! Hand-over, so behaviour stays the term path's:
//! - a call made while the run is observed (`run.records` without
//!   `run.nests`: the machine pushes the callee's frame, its entries nest in
//!   the caller's), or with the history kept when its exit arcs do not
//!   record natively, a call whose DM is not native there, whose arguments do not fit the
//!   callee's frame (a fresh variable other than an output argument above),
//!   whose exit arcs native code does not run, or that would reach the
//!   depth limit: the visit is handed to the machine, nothing of it done
//!   (`Cx::to_template`), which runs it from the situation's template as
//!   the interpreter does (the call, the callee's entries nested, the exit
//!   arcs); so a situation with native code has no exit arcs as term code
//!   (`exit_*`, issue 37);
//! - a waiting frame made the machine's (`nat_wait`, when the frames below
//!   the running one are materialized) waits as the interpreter's instance
//!   would (`Cx::wait_template`: the situation's template with its id, the
//!   in_arg the visit read (an in_arg pattern built from the variant's
//!   fields, `nat_in_arg_term`), the callee's frame pushed with the call its
//!   `embedded_dm` makes), and the machine runs its exit arcs at the callee's
//!   final;
//! - anything that needs the machine's state (an action performed, an
//!   error, a comparison evaluated on terms) first materializes the native
//!   stack and writes the locals back ([`super::Dm::hand`]);
//! - no exit arc matching is an error the machine reports itself
//!   (`Cx::no_exit`: `Cx::choose_exit` on the final's id, built then).
//!
//! Which situations of a DM have native code never depends on its callees
//! (a call that is not native here is handed over), so it is decided once
//! per DM.

use super::{coerce, identical, leaves, reg, rust_ty, Dm, Gen, Regs, N, V};
use crate::mir::{Action, Build, Ev, Init, KindPlan, Reg};
use proc_macro2::{Ident, Literal, TokenStream, TokenTree};
use quote::{format_ident, quote};
use sitlog_runtime::machine::Kind;
use sitlog_runtime::native::Ty;
use sitlog_runtime::{ArithCmp, Store, Term, Value};
use sitlog_syntax::atoms;
use std::collections::HashMap;

/// Why a call is not native: its DM call is evaluated (given to the
/// machine on terms, evaluated there by `Cx::embedded_dm`).
const EVALUATED: &str = "the embedded DM call is evaluated";

/// The waiting variant of a recursive situation and its uses.
#[derive(Clone)]
pub(super) struct Wait {
    pub variant: TokenStream,
    pub id_arm: TokenStream,
    /// Resumes with the callee's frame (`ret`): the exit arcs (recording
    /// their entries when `run.records`, where the call is pushed then).
    pub exit_arm: TokenStream,
    /// In `nat_wait` (a DM with locals): made a machine frame's pending
    /// situation.
    pub wait_arm: TokenStream,
    /// In `NatAt::waits` (a DM without locals): the situation it waits in
    /// and the pipe value it keeps.
    pub waits_arm: TokenStream,
    /// Its in_arg is a pattern: the pipe value is built from the fields,
    /// in the DM's own `nat_wait` (not `NatAt::waits`).
    pub pattern: bool,
    /// In `NatAt::held`: the call the variant holds, where its native call
    /// evaluated it (`CallPlan::held`); else empty.
    pub held_arm: TokenStream,
}

/// The functor of an action item that is a compound built of values
/// only (`note(S)`, `say([hello, Name])`: no evaluation, no variable
/// operation), whose term native code can build where it is performed.
pub(super) fn pure_compound(e: &Ev) -> Option<sitlog_syntax::Atom> {
    fn pure(e: &Ev) -> bool {
        match e {
            Ev::Value(_) | Ev::Built(_) => true,
            Ev::Compound(_, args) => args.iter().all(pure),
            _ => false,
        }
    }
    match e {
        Ev::Built(Build::Compound(f, _)) => Some(*f),
        Ev::Compound(f, args) if args.iter().all(pure) => Some(*f),
        _ => None,
    }
}

/// Whether every register `e` reads holds a value made before (not a
/// fresh variable, `fresh_rN`, that the effector may bind).
pub(super) fn made_values(e: &Ev, regs: &Regs) -> bool {
    fn build(b: &Build, regs: &Regs) -> bool {
        match b {
            Build::Const(_) => true,
            Build::Reg(r) => regs
                .get(r)
                .is_some_and(|(x, _)| !x.to_string().starts_with("fresh_r")),
            Build::Compound(_, args) => args.iter().all(|a| build(a, regs)),
        }
    }
    match e {
        Ev::Value(r) => build(&Build::Reg(*r), regs),
        Ev::Built(b) => build(b, regs),
        Ev::Compound(_, args) => args.iter().all(|a| made_values(a, regs)),
        _ => false,
    }
}

/// A native call: the callee's index and native view, and the exit code.
pub(super) struct CallPlan<'a> {
    pub(super) j: usize,
    pub(super) callee: Dm<'a>,
    exit: TokenStream,
    /// The exit arcs record their entries natively (`run.records`): the
    /// call may then be pushed on the native stack with the history kept.
    pub(super) rec_exit: bool,
    /// The call is evaluated by native code, once ([`Gen::nat_held_visit`]):
    /// the waiting variant holds that call (`held`).
    held: bool,
}

fn wait_variant(ix: usize) -> Ident {
    format_ident!("W{}", ix)
}

impl Gen<'_> {
    /// The registers the waiting variant keeps: the id's variables, then
    /// the registers saved for the exit arcs.
    fn nat_wait_fields(&self, d: &Dm, ix: usize) -> N<Vec<(Reg, Ty)>> {
        let mut fields = self.nat_fields(d, ix)?;
        let outs = call_outputs(d, ix);
        if let KindPlan::Recursive { saved, .. } = &d.plans[ix].kind {
            for &r in saved {
                // An output argument has no value while the callee runs:
                // it comes back in the callee's output slot.
                if outs.iter().any(|&(_, o)| o == r) {
                    continue;
                }
                // A parameter held as it is (`lookup(Stock, Want)`'s
                // `Want`): the exit arcs read it from the frame
                // (`Gen::nat_exit` loads it, by reference where it is only
                // read), no copy kept in the variant.
                if self.nat_param_reg(d, ix, r) {
                    continue;
                }
                if !fields.iter().any(|(x, _)| *x == r) {
                    fields.push((r, d.types[ix].regs[r as usize].ty.clone()));
                }
            }
            // An in_arg's variable the call reads, of a pattern (`in_arg
            // ==> N-L, embedded_dm ==> count(N)`) or the in_arg itself
            // (`in_arg ==> N, embedded_dm ==> count(N)`): the call's
            // argument where it is pushed natively, and a frame made the
            // machine's evaluates the template's call with the variable
            // bound by the pipe value built from the fields
            // (`nat_in_arg_term`) or kept whole (`Cx::wait_template`).
            if let (Some((pat, _, _)), KindPlan::Recursive { call, .. }) =
                (&d.plans[ix].in_arg, &d.plans[ix].kind)
            {
                let (mut in_pat, mut in_call) = (Vec::new(), Vec::new());
                build_regs(pat, &mut in_pat);
                build_regs(call, &mut in_call);
                for r in in_pat {
                    let unbound = d.types[ix].unbound.get(r as usize).copied();
                    if in_call.contains(&r)
                        && unbound == Some(false)
                        && !fields.iter().any(|(x, _)| *x == r)
                    {
                        fields.push((r, d.types[ix].regs[r as usize].ty.clone()));
                    }
                }
            }
        }
        Ok(fields)
    }

    /// Whether register `r` of situation `ix` is a parameter of the DM
    /// read whole, of the parameter's own type (its load is `pN.clone()`,
    /// `load_head_arg`): the frame holds that value for as long as the
    /// situation waits, and never writes it (a variable bound by the callee
    /// is bound in the store, the same term either way), so reading it
    /// after the call reads what a copy made before it would hold.
    fn nat_param_reg(&self, d: &Dm, ix: usize, r: Reg) -> bool {
        let Some(i) = d.plans[ix].inits.iter().find_map(|(x, init)| match init {
            Init::HeadArg(i) if *x == r => Some(*i),
            _ => None,
        }) else {
            return false;
        };
        let unbound = d.types[ix].unbound.get(r as usize).copied();
        unbound == Some(false) && d.params.get(i) == Some(&d.types[ix].regs[r as usize].ty)
    }

    /// The call's DM name and argument values (`None`: evaluating it is not
    /// giving it back, the DM stays on terms).
    fn nat_call_values(
        &self,
        d: &Dm,
        ix: usize,
        regs: &Regs,
        outs: &[(usize, Reg)],
    ) -> N<(sitlog_syntax::Atom, Vec<V>)> {
        let KindPlan::Recursive {
            call, eval_call, ..
        } = &d.plans[ix].kind
        else {
            return Err("not a recursive situation".into());
        };
        match call {
            Build::Const(t) => {
                if *eval_call {
                    return Err(EVALUATED.into());
                }
                match self.store.value(*t) {
                    Value::Atom(a) => Ok((a, Vec::new())),
                    Value::Compound(name, args) => {
                        let args = args.to_vec();
                        let vals = args
                            .into_iter()
                            .map(|a| self.nat_value(&Build::Const(a), regs))
                            .collect::<N<Vec<_>>>()?;
                        Ok((name, vals))
                    }
                    _ => Err("the embedded DM is not a call".into()),
                }
            }
            Build::Compound(name, args) => {
                // Evaluated only for `get(l, _)` of locals held natively:
                // their values (a read, nothing written or bound). The
                // call's own name must not be an L construct (`last/2`,
                // `append/3`, ...): evaluated, it would not name the DM.
                if *eval_call
                    && !inert(call)
                    && !(sitlog_runtime::eval::evaluates_arguments_only(*name, args.len())
                        && args
                            .iter()
                            .all(|a| inert(a) || self.nat_local_get(d, ix, a).is_some()))
                {
                    return Err(EVALUATED.into());
                }
                let vals = args
                    .iter()
                    .enumerate()
                    .map(|(i, a)| {
                        if outs.iter().any(|&(k, _)| k == i) {
                            // No term for the caller's fresh variable.
                            Ok(V {
                                e: quote!(Ground::OUT),
                                ty: Ty::Term,
                            })
                        } else if let Some(v) = self.nat_local_get(d, ix, a).filter(|_| *eval_call)
                        {
                            Ok(v)
                        } else {
                            self.nat_value(a, regs)
                        }
                    })
                    .collect::<N<Vec<_>>>()?;
                Ok((*name, vals))
            }
            Build::Reg(_) => Err("the embedded DM is a variable".into()),
        }
    }

    /// `get(l, V)` as an argument of a DM call (evaluated with read-only
    /// variables, D-20), `l` a local held in the frame and `V` a variable
    /// met only there (`SitTypes::unbound`: binding it has no other
    /// effect): the local's value, read natively (`search(get(places, _),
    /// T)`).
    pub(super) fn nat_local_get(&self, d: &Dm, ix: usize, b: &Build) -> Option<V> {
        let Build::Compound(op, args) = b else {
            return None;
        };
        let [Build::Const(n), Build::Reg(r)] = &args[..] else {
            return None;
        };
        if *op != atoms::GET || !d.locals_ok || !*d.types[ix].unbound.get(*r as usize)? {
            return None;
        }
        let n = self.store.atom_of(*n)?;
        let (l, ty) = d.local_field(n)?;
        Some(V {
            e: quote!((*#l).clone()),
            ty,
        })
    }

    /// The registers of a visit that come from the frame's parameters:
    /// each register's local and the statement that loads it.
    fn nat_head_regs(&self, d: &Dm, ix: usize, regs: &mut Regs) -> N<Vec<(Ident, TokenStream)>> {
        let mut stmts = Vec::new();
        let unbound = |r: Reg| {
            d.types[ix]
                .unbound
                .get(r as usize)
                .copied()
                .unwrap_or(false)
        };
        for (r, init) in &d.plans[ix].inits {
            if let Init::HeadArg(i) = init {
                if unbound(*r) {
                    continue;
                }
                let ty = d.types[ix].regs[*r as usize].ty.clone();
                stmts.push((reg(*r), super::load_head_arg(d, *r, *i, ty, regs)?));
            }
            if let Init::HeadPath(i, path) = init {
                if unbound(*r) {
                    continue;
                }
                let ty = d.types[ix].regs[*r as usize].ty.clone();
                let load = super::head::load_head_path(d, *r, *i, path, ty, regs)?;
                stmts.push((reg(*r), load));
            }
        }
        Ok(stmts)
    }

    /// Whether the call of recursive situation `ix` runs natively, and how.
    fn nat_call_plan(&self, d: &Dm, ix: usize) -> Option<CallPlan<'_>> {
        if d.shallow {
            return None;
        }
        let ir = self.ir?;
        // Argument values of the right count, with no registers: the name.
        let mut regs = Regs::new();
        for (r, ty) in self.nat_wait_fields(d, ix).ok()? {
            regs.insert(r, (reg(r), ty));
        }
        self.nat_head_regs(d, ix, &mut regs).ok()?;
        let outs = call_outputs(d, ix);
        let (name, args, held) = match self.nat_call_values(d, ix, &regs, &outs) {
            Ok((name, args)) => (name, args, false),
            Err(e) if e == EVALUATED => {
                let (name, args) = self.nat_held_args(d, ix, &regs, &outs)?;
                (name, args, true)
            }
            Err(_) => return None,
        };
        // The machine's `dm_by_name`: the first DM of that name.
        let j = ir.dms.iter().position(|x| x.name == name)?;
        if ir.dms[j].arity != args.len() {
            return None;
        }
        let callee = self.nat_dm_of(j)?;
        for (v, ty) in args.iter().zip(&callee.params) {
            coerce(v, ty).ok()?;
        }
        // A callee whose head has a pattern: pushed where the argument
        // matches it (`Gen::head_guard`), not as a held call.
        let tys: Vec<Ty> = args.iter().map(|v| v.ty.clone()).collect();
        let vs: Vec<Ident> = (0..args.len()).map(|i| format_ident!("v{}", i)).collect();
        let guard = self.head_guard(j, &vs, &tys, &callee.params).ok()?;
        if held && !guard.is_empty() {
            return None;
        }
        // Each output argument: an output parameter of the callee (no
        // situation reads it, every final binds it) held in a slot of a
        // type the caller's register takes, where the exit arcs read it
        // (`saved`; else nothing reads the slot: `find(O, S, _, _, _)`).
        let KindPlan::Recursive { saved, .. } = &d.plans[ix].kind else {
            return None;
        };
        for &(k, r) in &outs {
            let oty = callee.outputs.get(k)?.as_ref()?;
            if callee.params[k] != Ty::Term || !callee.outs.borrow()[k] {
                return None;
            }
            if !saved.contains(&r) {
                continue;
            }
            let v = V {
                e: quote!(v),
                ty: oty.clone(),
            };
            coerce(&v, &d.types[ix].regs[r as usize].ty).ok()?;
        }
        for ((_, default), (_, ty)) in ir.dms[j].locals.iter().zip(&callee.locals) {
            let v = self.nat_value(&Build::Const(*default), &Regs::new()).ok()?;
            coerce(&v, ty).ok()?;
        }
        // The callee's first situation's fields: its id's variables that
        // are parameters too (`first(N)` in `bump(N)`), bound to the
        // arguments by the link (D-7); any other is unbound there (D-4).
        let start = Self::nat_start_fields(&callee).ok()?;
        for &(_, k, ref ty) in &start {
            coerce(args.get(k)?, ty).ok()?;
        }
        // Exit arcs native code does not run (an action or next situation
        // it does not know): the call is the machine's, from the template.
        let (exit, rec_exit) = self.nat_exit(d, ix, &callee, j).ok()?;
        Some(CallPlan {
            j,
            callee,
            exit,
            rec_exit,
            held,
        })
    }

    /// The fields of DM `callee`'s first situation, `(register, argument,
    /// type)`: each a variable of its id that is a parameter too, the
    /// call's argument once linked (D-7); an error when one is not.
    fn nat_start_fields(callee: &Dm) -> N<Vec<(Reg, usize, Ty)>> {
        let Some(p0) = callee.plans.first() else {
            return Ok(Vec::new());
        };
        let links = crate::mir::ty::start_links(p0);
        let mut out = Vec::new();
        for (r, init) in &p0.inits {
            let Init::IdArg(i) = init else {
                if matches!(init, Init::IdPath(_)) {
                    return Err("the first situation's id is a pattern".into());
                }
                continue;
            };
            let &(_, k) = links
                .iter()
                .find(|(x, _)| x == i)
                .ok_or("the first situation's id has a variable of its own (D-4)")?;
            out.push((*r, k, callee.types[0].regs[*r as usize].ty.clone()));
        }
        Ok(out)
    }

    /// The visit of recursive situation `ix` (registers `regs` set).
    pub(super) fn nat_recursive(&self, d: &Dm, ix: usize, regs: &Regs) -> N<TokenStream> {
        let outs = call_outputs(d, ix);
        if !outs.is_empty() {
            return self.nat_recursive_outputs(d, ix, regs, &outs);
        }
        let args = match self.nat_call_values(d, ix, regs, &[]) {
            Ok((_, args)) => args,
            // An argument is a fresh variable (an output argument), or the
            // call is evaluated (`ask(apply(f(_), [X]), ..)`): the
            // machine's visit, from the template.
            Err(e) if e == EVALUATED => {
                return match self.nat_call_plan(d, ix) {
                    Some(plan) if plan.held => self.nat_held_visit(d, ix, regs, &plan),
                    _ => self.nat_to_template(d, ix),
                }
            }
            Err(e) if e.starts_with("register r") => return self.nat_to_template(d, ix),
            Err(e) => return Err(e),
        };
        let to_template = self.nat_to_template(d, ix)?;
        let Some(plan) = self.nat_call_plan(d, ix) else {
            return Ok(to_template);
        };
        self.nat_push_else(d, ix, regs, &plan, &args, to_template)
    }

    /// A call with output arguments (`add(I, 1, J)`, `J` a fresh variable
    /// of the caller, `call_outputs`): pushed natively where
    /// [`Gen::nat_call_plan`] says so, the callee's frame getting
    /// `Ground::OUT` for each output parameter (no term made: its final
    /// hands the value back in the frame's output slot, which the exit
    /// arcs read) and the waiting variant keeping no output register; else,
    /// and when the push is not made, the machine's visit from the
    /// template ([`Gen::nat_to_template`]).
    fn nat_recursive_outputs(
        &self,
        d: &Dm,
        ix: usize,
        regs: &Regs,
        outs: &[(usize, Reg)],
    ) -> N<TokenStream> {
        let to_template = self.nat_to_template(d, ix)?;
        let Some(plan) = self.nat_call_plan(d, ix) else {
            return Ok(to_template);
        };
        if plan.held {
            return self.nat_held_visit(d, ix, regs, &plan);
        }
        let (_, args) = self.nat_call_values(d, ix, regs, outs)?;
        self.nat_push_else(d, ix, regs, &plan, &args, to_template)
    }

    /// The call's arguments bound as `v0`, `v1`, .. and pushed by
    /// [`Gen::nat_push`]; `to_template` where the push is not made.
    fn nat_push_else(
        &self,
        d: &Dm,
        ix: usize,
        regs: &Regs,
        plan: &CallPlan,
        args: &[V],
        to_template: TokenStream,
    ) -> N<TokenStream> {
        let vs: Vec<Ident> = (0..args.len()).map(|i| format_ident!("v{}", i)).collect();
        // An output argument (no term) written `Ground::OUT` where it is
        // used, not bound first.
        let out = quote!(Ground::OUT).to_string();
        // The frame made by one closure for both pushes where nothing after
        // them reads the arguments (the closure takes them).
        let reads_args = mentions_any(&to_template, &vs);
        let mut push = self.nat_push(d, ix, regs, plan, args, &vs, !reads_args)?;
        // A register's clone read once by the push, and by nothing after
        // it, written where the frame takes it (made only when pushed; one
        // line less).
        let mut inlined = Vec::new();
        if !reads_args {
            for (v, x) in args.iter().zip(&vs) {
                if is_clone_of_reg(&v.e) && super::pipe::mentions(&push, x) == 1 {
                    push = super::call_held::replace_ident(&push, x, &v.e);
                    inlined.push(x.clone());
                }
            }
        }
        let lets = args
            .iter()
            .zip(&vs)
            .filter(|(v, x)| v.e.to_string() != out && !inlined.contains(x))
            .map(|(v, x)| {
                let e = &v.e;
                quote!(let #x = #e;)
            });
        let outs: Vec<&Ident> = args
            .iter()
            .zip(&vs)
            .filter(|(v, _)| v.e.to_string() == out)
            .map(|(_, x)| x)
            .collect();
        let (push, to_template) = outs.iter().fold((push, to_template), |(p, t), x| {
            (
                super::call_held::replace_ident(&p, x, &quote!(Ground::OUT)),
                super::call_held::replace_ident(&t, x, &quote!(Ground::OUT)),
            )
        });
        Ok(quote! {
            #(#lets)*
            #push
            #to_template
        })
    }

    /// The callee's frame pushed on the native stack (arguments `vs`, of
    /// values `args`), the caller waiting in its variant `W<ix>`: within
    /// the depth limit, when no history is kept or observed (else the
    /// machine pushes it: the callee's entries nest in the caller's).
    #[allow(clippy::too_many_arguments)]
    fn nat_push(
        &self,
        d: &Dm,
        ix: usize,
        regs: &Regs,
        plan: &CallPlan,
        args: &[V],
        vs: &[Ident],
        shared: bool,
    ) -> N<TokenStream> {
        let callee_v = format_ident!("D{}", plan.j);
        let wv = wait_variant(ix);
        let (frame, wf) = self.nat_callee_frame(d, ix, regs, plan, args, vs)?;
        // A callee's head pattern matched by the arguments (empty for a
        // head of variables; read before the frame takes them).
        let tys: Vec<Ty> = args.iter().map(|v| v.ty.clone()).collect();
        let guard = self.head_guard(plan.j, vs, &tys, &plan.callee.params)?;
        let shared = shared && guard.is_empty();
        // Recorded (the history kept, nothing observing) where the exit
        // arcs record natively: the callee's entries in a level of their
        // own (`Cx::push_level`). A branch of its own: the push without a
        // history tests `run.records` once and builds the frame in place
        // (one frame built before both cost `echo_calls` 3 instructions a
        // transition).
        // Both pushes (with a history level and without) build the frame
        // by one closure, `callee()`, where it reads nothing of `cx`: the
        // frame built in place where the branch calls it, as before.
        if plan.rec_exit && shared && !mentions_any(&frame, &[format_ident!("cx")]) {
            // Both tests and pushes one call (`NatBelow::push`, inlined).
            return Ok(quote! {
                let callee = || #frame;
                if stack.push(p, cx, run, call, super::NatFrame::#callee_v, callee) {
                    return cx.step_done(count, slot, Nat::#wv { #(#wf),* });
                }
            });
        }
        let rec = if plan.rec_exit {
            quote! {
                else if run.nests && stack.has_room(cx) #guard {
                    let callee = super::NatFrame::#callee_v(#frame);
                    cx.push_level(p, call, callee);
                    return cx.step_done(count, slot, Nat::#wv { #(#wf),* });
                }
            }
        } else {
            quote!()
        };
        Ok(quote! {
            // The callee's frame on the native stack, within the depth
            // limit, when no history is kept or observed (else the machine
            // pushes it: the callee's entries nest in the caller's).
            if !run.records && stack.has_room(cx) #guard {
                let callee = #frame;
                *call = Some(super::NatFrame::#callee_v(callee));
                // Written where the frame keeps it (not through `at`).
                return cx.step_done(count, slot, Nat::#wv { #(#wf),* });
            } #rec
        })
    }

    /// The callee's frame of a native call (its parameters the arguments
    /// `vs`, of values `args`, its locals' defaults, its first situation)
    /// and the waiting variant's fields, the visit's registers moved in.
    pub(super) fn nat_callee_frame(
        &self,
        d: &Dm,
        ix: usize,
        regs: &Regs,
        plan: &CallPlan,
        args: &[V],
        vs: &[Ident],
    ) -> N<(TokenStream, Vec<TokenStream>)> {
        let callee_f = format_ident!("NatF{}", plan.j);
        let callee_n = format_ident!("NatN{}", plan.j);
        let ir = self.ir.ok_or("no IR")?;
        let mut inits = Vec::new();
        for (i, (v, ty)) in args.iter().zip(&plan.callee.params).enumerate() {
            let p = format_ident!("p{}", i);
            let x = &vs[i];
            // The argument moves into the callee's frame: the branch that
            // pushes the frame ends the visit, and the machine's call
            // below (the other branch) reads `v<i>` itself
            // (`nat_recursive`) or builds its term from the registers
            // again (`nat_recursive_outputs`: `v<i>` unused there).
            let e = coerce(
                &V {
                    e: quote!(#x),
                    ty: v.ty.clone(),
                },
                ty,
            )?;
            inits.push(quote!(#p: #e));
        }
        for (i, ((_, default), (_, ty))) in ir.dms[plan.j]
            .locals
            .iter()
            .zip(&plan.callee.locals)
            .enumerate()
        {
            let l = format_ident!("l{}", i);
            let v = self.nat_value(&Build::Const(*default), &Regs::new())?;
            let e = coerce(&v, ty)?;
            inits.push(quote!(#l: #e));
        }
        inits.extend(out_slots_none(&plan.callee));
        // The first situation's fields: the arguments its id's
        // parameters are linked with (cloned: each also moves into the frame).
        let mut s0 = Vec::new();
        for (r, k, ty) in Self::nat_start_fields(&plan.callee)? {
            let x = &vs[k];
            let e = coerce(
                &V {
                    e: quote!(#x.clone()),
                    ty: args[k].ty.clone(),
                },
                &ty,
            )?;
            let rr = reg(r);
            s0.push(quote!(#rr: #e));
        }
        // `at` first where it clones an argument that `inits` moves.
        let fields = if s0.is_empty() {
            quote!({ #(#inits,)* at: super::#callee_n::S0 {} })
        } else {
            quote!({ at: super::#callee_n::S0 { #(#s0),* }, #(#inits,)* })
        };
        let mut wf = Vec::new();
        for (r, _) in self.nat_wait_fields(d, ix)? {
            let v = self.nat_value(&Build::Reg(r), regs)?;
            // The visit ends here: its own registers move into the
            // waiting variant (not cloned and dropped).
            let (rr, e) = (reg(r), super::moved(&v));
            // `r5` for `r5: r5` (the shorthand: one line where it fits).
            if rr == e.to_string() {
                wf.push(quote!(#rr));
            } else {
                wf.push(quote!(#rr: #e));
            }
        }
        Ok((quote!(super::#callee_f #fields), wf))
    }

    /// The visit of situation `ix` handed to the machine, nothing of it
    /// done (a recursive situation's call not pushed on the native stack: a
    /// history kept or observed, a call that is not native, the depth
    /// limit; an in_arg pattern not matched natively): the
    /// frames below made the machine's, the locals written back, the
    /// machine runs the visit from the situation's template as the
    /// interpreter does (its call, the callee's entries nested in the DM's
    /// history, its exit arcs: no term code of them, `exit_*`, is made).
    pub(super) fn nat_to_template(&self, d: &Dm, ix: usize) -> N<TokenStream> {
        let curl = Literal::u32_unsuffixed(ix as u32);
        let hand = &d.hand;
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        // A DM without locals: the runtime's hand-over and the template in
        // one call (`machine::nat_template`) where it fits on a line.
        if d.locals.is_empty() {
            let arg = match super::fill_arg(&id_stmts, &id) {
                Some(fill) => Some(fill),
                None if id_stmts.is_empty() => Some(super::atom_arg(&id)),
                None => None,
            };
            if let Some(arg) = arg {
                let ret = quote!(return machine::nat_template(p, cx, stack, count, #curl, #arg););
                if super::fits(&ret, 24) {
                    return Ok(ret);
                }
            }
            // A `Fill` bound first (filled after the hand-over, by the call).
            if let Some(fill) = super::fill_arg(&id_stmts, &id) {
                let ret = quote!(return machine::nat_template(p, cx, stack, count, #curl, #id););
                let fill = quote!(let #id = #fill;);
                if super::fits(&ret, 24) && super::fits(&fill, 24) {
                    return Ok(quote!(#fill #ret));
                }
            }
        }
        // The id's pattern filled by the call (`Fill`) where the call
        // still fits on a line, else its `let` first.
        if let Some(fill) = super::fill_arg(&id_stmts, &id) {
            let ret = quote!(return cx.counted_template(count, #curl, #fill););
            if super::fits(&ret, 24) {
                return Ok(quote!(#hand #ret));
            }
        }
        Ok(quote! {
            #hand
            #(#id_stmts)*
            return cx.counted_template(count, #curl, #id);
        })
    }

    /// The waiting variant of situation `ix` when it is recursive.
    pub(super) fn nat_wait_variant(&self, d: &Dm, ix: usize) -> N<Option<Wait>> {
        if !matches!(d.plans[ix].kind, KindPlan::Recursive { .. }) {
            return Ok(None);
        }
        let wv = wait_variant(ix);
        let fields = self.nat_wait_fields(d, ix)?;
        let decls = fields
            .iter()
            .map(|(r, ty)| {
                let (r, ty) = (reg(*r), rust_ty(ty)?);
                Ok(quote!(#r: #ty))
            })
            .collect::<N<Vec<_>>>()?;
        let names: Vec<Ident> = fields.iter().map(|(r, _)| reg(*r)).collect();
        let doc = format!(
            " `{}` waiting for its embedded DM",
            self.store.writeq(self.nat_id_of(d, ix))
        );
        // A call never pushed on the native stack: no waiting variant (the
        // machine's visit from the template waits).
        let plan = self.nat_call_plan(d, ix);
        // The call evaluated by native code: held by the variant (a handle
        // of the store, as a `Ground`: no collection while native code
        // runs), its fields' patterns then `..`.
        let held = plan.as_ref().is_some_and(|p| p.held);
        let (held_decl, rest) = if held {
            (quote!(held: Term), quote!(..))
        } else {
            (quote!(), quote!())
        };
        let decls: Vec<TokenStream> = decls.into_iter().chain(held.then_some(held_decl)).collect();
        let variant = quote!(#[doc = #doc] #wv { #(#decls),* },);
        let id = self.nat_id_value(d, ix, quote!(store))?;
        let pat = if held {
            quote!(Nat::#wv { #(#names,)* #rest })
        } else {
            quote!(Nat::#wv { #(#names),* })
        };
        let id_arm = quote!(#pat => #id,);
        let exit_arm = match &plan {
            Some(plan) => {
                let exit = super::move_last_clones(&plan.exit, &names);
                quote!(#pat => 'visit: { #exit })
            }
            None => quote!(),
        };
        // In `nat_wait` (fields are references there).
        let curl = Literal::u32_unsuffixed(ix as u32);
        let (id_stmts, id) = self.nat_id_term_of(d, ix, quote!(cx.store()), true)?;
        // The pipe value the visit read, when the waiting variant keeps it
        // (the exit arcs read it): the template instance's in_arg.
        let in_arg = d.plans[ix]
            .inits
            .iter()
            .find(|(_, init)| matches!(init, Init::Pipe))
            .map(|(r, _)| reg(*r))
            .filter(|r| names.contains(r));
        let pattern = match &d.plans[ix].in_arg {
            Some((pat, true, _)) => Some(pat),
            _ => None,
        };
        let (in_stmt, in_arg, waits_arm) = match (pattern, in_arg) {
            // An in_arg pattern: the pipe value built from the fields
            // (a DM's own `nat_wait`, `Wait::pattern`).
            (Some(pat), _) => {
                let mut ts = Vec::new();
                let t = self.nat_in_arg_term(pat, &names, &mut ts, &mut Vec::new(), &mut 0)?;
                (
                    quote!(#(#ts)* let in_arg = #t;),
                    quote!(Some(in_arg)),
                    quote!(),
                )
            }
            (None, Some(r)) => (
                quote!(let in_arg = cx.term(#r);),
                quote!(Some(in_arg)),
                quote!(Nat::#wv { #r, .. } => Some((#curl, Some(#r))),),
            ),
            (None, None) => (
                quote!(),
                quote!(None),
                quote!(Nat::#wv { .. } => Some((#curl, None)),),
            ),
        };
        let wait_arm = if held {
            quote! {
                Nat::#wv { #(#names,)* held } => {
                    #in_stmt
                    #(#id_stmts)*
                    cx.wait_held(#curl, #id, #in_arg, Some(*held))
                }
            }
        } else {
            quote! {
                Nat::#wv { #(#names),* } => {
                    #in_stmt
                    #(#id_stmts)*
                    cx.wait_template(#curl, #id, #in_arg)
                }
            }
        };
        let held_arm = if held {
            quote!(Nat::#wv { held, .. } => Some(*held),)
        } else {
            quote!()
        };
        if plan.is_none() {
            return Ok(None);
        }
        Ok(Some(Wait {
            variant,
            id_arm,
            exit_arm,
            wait_arm,
            waits_arm,
            pattern: pattern.is_some(),
            held_arm,
        }))
    }

    /// The pipe value a waiting variant of a situation with an in_arg
    /// pattern gives its template instance (`Cx::wait_template`): the
    /// pattern built with each variable the variant keeps (`names`, a
    /// reference each) made a term, any other (`_`, one nothing after the
    /// call reads) a fresh variable, the same one where it is met again.
    /// The pipe matched the pattern natively, so this unifies with it as
    /// the pipe did and binds the instance's variables to the same values.
    fn nat_in_arg_term(
        &self,
        pat: &Build,
        names: &[Ident],
        ts: &mut Vec<TokenStream>,
        fresh: &mut Vec<(Reg, Ident)>,
        n: &mut usize,
    ) -> N<TokenStream> {
        let x = format_ident!("b{}", *n);
        *n += 1;
        let e = match pat {
            Build::Reg(r) if names.contains(&reg(*r)) => {
                let v = reg(*r);
                quote!(cx.term(#v))
            }
            Build::Reg(r) => match fresh.iter().find(|(f, _)| f == r) {
                Some((_, v)) => return Ok(quote!(#v)),
                None => {
                    fresh.push((*r, x.clone()));
                    quote!(cx.var())
                }
            },
            Build::Const(t) => return self.nat_const_term(*t, ts, n),
            Build::Compound(f, args) => {
                let args = args
                    .iter()
                    .map(|a| self.nat_in_arg_term(a, names, ts, fresh, n))
                    .collect::<N<Vec<_>>>()?;
                let f = self.functor_native(*f)?;
                quote!(cx.build(#f, &[#(#args),*]))
            }
        };
        ts.push(quote!(let #x = #e;));
        Ok(quote!(#x))
    }

    /// The exit arcs of recursive situation `ix` on the final variant of
    /// callee `callee` (DM `j`) in `ret`: evaluates to the next `Nat` (or
    /// returns, handing over). With `true` when every arc records its
    /// entry natively: each arm then records it where `run.records` (one
    /// copy of the arms; the recorded way enters the situation where the
    /// other counts the transition, and the next situation's hand-over
    /// records with `run.goto`, a no-op record otherwise).
    fn nat_exit(&self, d: &Dm, ix: usize, callee: &Dm, j: usize) -> N<(TokenStream, bool)> {
        let KindPlan::Recursive { exit, .. } = &d.plans[ix].kind else {
            return Err("not a recursive situation".into());
        };
        let mut regs = Regs::new();
        let fields = self.nat_wait_fields(d, ix)?;
        for (r, ty) in &fields {
            regs.insert(*r, (reg(*r), ty.clone()));
        }
        let head = self.nat_head_regs(d, ix, &mut regs)?;
        // A parameter the waiting variant keeps is read there, not loaded.
        let head: Vec<_> = head
            .into_iter()
            .filter(|(r, _)| !fields.iter().any(|(f, _)| reg(*f) == *r))
            .collect();
        // The output arguments, from the callee's output slots (set by a
        // final that hands them back there, `Gen::nat_output_slots`).
        let outs = call_outputs(d, ix);
        let mut out_loads = Vec::new();
        let KindPlan::Recursive { saved, .. } = &d.plans[ix].kind else {
            return Err("not a recursive situation".into());
        };
        for &(k, r) in &outs {
            if !saved.contains(&r) {
                continue; // the exit arcs do not read it
            }
            let oty = output_ty(callee, k)?;
            let rty = d.types[ix].regs[r as usize].ty.clone();
            let o = format_ident!("out{}", k);
            let rr = reg(r);
            let e = coerce(
                &V {
                    e: quote!(v),
                    ty: oty,
                },
                &rty,
            )?;
            let rt = rust_ty(&rty)?;
            // The output taken (`Cx::callee_out`: an error when the callee
            // left it unset), converted where its types differ.
            let take = quote!(cx.callee_out(done_frame.#o.take())?);
            out_loads.push((
                rr.clone(),
                if e.to_string() == "v" {
                    quote!(let #rr: #rt = #take;)
                } else {
                    quote! {
                        let v = #take;
                        let #rr: #rt = #e;
                    }
                },
            ));
            regs.insert(r, (rr, rty));
        }
        let cur_name = self.atom_native(d.plans[ix].id.0)?;
        let callee_n = format_ident!("NatN{}", j);
        // Per final: its pattern, and per arc its test, its code before
        // the entry, its plain tail and its recorded tail.
        type ArcCode = (
            TokenStream,
            (usize, TokenStream),
            TokenStream,
            Option<ExitRecord>,
        );
        let mut finals: Vec<(TokenStream, Vec<ArcCode>, bool)> = Vec::new();
        // A final with no `diag_mod` leaves the output arguments unbound
        // (`DmTypes::outputs`): its arcs see no output register (one that
        // reads it is not native), and the outputs are loaded in the arms
        // of the finals that bind them, not before the `match`.
        let leaves_outs = |k: usize| {
            !out_loads.is_empty()
                && matches!(&callee.plans[k].kind, KindPlan::Final { diag_mod: None })
        };
        let out_regs: Vec<Ident> = out_loads.iter().map(|(r, _)| r.clone()).collect();
        let regs_leave: Regs = regs
            .iter()
            .filter(|(_, (v, _))| !out_regs.contains(v))
            .map(|(r, v)| (*r, v.clone()))
            .collect();
        let mut any_leaves = false;
        // Every arc's entry built natively (its expectation a term of the
        // registers, its action of the values it computed).
        let mut rec_all = true;
        for k in 0..callee.plans.len() {
            // Only a final situation the callee hands back as its `Nat`
            // variant reaches these arms: one without native code, or with
            // a `diag_mod` (the machine takes it, see `native_visit`), goes
            // to the machine, which returns to the caller's term code. Its
            // variant may not exist (an application of the original's
            // tree: `see_body`'s finals with `diag_mod`, issue 37).
            // A final with `diag_mod` comes back here only when it hands
            // the call's outputs back in its slots (`slot_final`).
            let diag_mod = matches!(&callee.plans[k].kind, KindPlan::Final { diag_mod: Some(_) });
            let slotted = !outs.is_empty() && slot_final(self.store, callee, k);
            if callee.dm.situations[k].kind != Kind::Final
                || !callee.native[k]
                || (diag_mod && !slotted)
            {
                continue;
            }
            let fields = self.nat_fields(callee, k)?;
            let cf: Vec<TokenStream> = fields
                .iter()
                .map(|(r, _)| {
                    let (rr, c) = (reg(*r), format_ident!("c{}", r));
                    quote!(#rr: #c)
                })
                .collect();
            let pat = self.nat_id_of(callee, k);
            let mut arcs_code = Vec::new();
            let leaving = leaves_outs(k);
            any_leaves |= leaving;
            let regs = if leaving { &regs_leave } else { &regs };
            for (i, arc) in exit.arcs.iter().enumerate() {
                if arc.diag_mod.is_some() {
                    return Err("an exit arc has diag_mod".into());
                }
                let b = ev_as_build(&arc.expectation)
                    .ok_or("an exit arc's expectation is evaluated")?;
                let b = &b;
                let mut regs = regs.clone();
                for (n, from) in arc.import_from.iter().enumerate() {
                    if let Some(at) = regs.get(from).cloned() {
                        regs.insert(arc.import_at + n as Reg, at);
                    }
                }
                let mut tests = Vec::new();
                let mut lets = Vec::new();
                let mut vars = HashMap::new();
                let fresh: Vec<Reg> = arc.fresh.clone();
                if !self.nat_unify(
                    d,
                    ix,
                    callee,
                    k,
                    b,
                    pat,
                    &mut Vec::new(),
                    &fresh,
                    &mut regs,
                    &mut vars,
                    &mut tests,
                    &mut lets,
                )? {
                    continue; // never this arc for this final
                }
                // An arc taking a final that leaves the outputs unbound
                // reads none of them (the MIR typed them so, `mir::ty`).
                if leaving
                    && outs
                        .iter()
                        .any(|&(_, r)| crate::mir::ty::arc_mentions(arc, r))
                {
                    return Err(
                        "an exit arc reads an output argument a final leaves unbound".into(),
                    );
                }
                let action = self.nat_exit_action(d, ix, i, arc, &mut regs)?;
                // The callee ran since the pipe was read: an out_arg writes
                // the saved value back ([`Dm::pipe_in`] is the visit's).
                let pipe_in = d.pipe_in.take();
                let next = self.nat_next_out(
                    d,
                    ix,
                    &arc.next,
                    super::pipe::arc_out(arc),
                    &regs,
                    &cur_name,
                );
                d.pipe_in.set(pipe_in);
                // One expression (a variant, a `'sel` block) as it is; else
                // a block.
                let next = super::as_expr(next?);
                // Recorded: the entry as the machine's `conclude` makes it
                // (the expectation unified with the final's id, the action's
                // values), the next situation handing over records it there.
                let rec = self.nat_exit_record(d, ix, arc, &regs, &cur_name).ok();
                rec_all &= rec.is_some();
                let cond = quote!(#(#tests)&&*);
                let head = quote! {
                    #(#lets)*
                    #action
                };
                let plain = quote! {
                    count += 1;
                    let next_at = #next;
                    break 'visit next_at;
                };
                arcs_code.push((cond, (i, head), plain, rec));
            }
            let sk = format_ident!("S{}", k);
            finals.push((
                quote!(super::#callee_n::#sk { #(#cf),* }),
                arcs_code,
                leaving,
            ));
        }
        let curl = Literal::u32_unsuffixed(ix as u32);
        let arms = finals.into_iter().map(|(pat, arcs, leaving)| {
            // An arc whose test always holds takes every final that
            // reaches it: the arcs after it are never tried.
            let taken = arcs.iter().position(|(c, ..)| c.is_empty());
            let arcs = arcs.into_iter().take(taken.map_or(usize::MAX, |k| k + 1));
            let arcs = arcs.map(|(cond, (i, head), plain, rec)| {
                let uses_entry = |next: &TokenStream| {
                    mentions(next, &format_ident!("exp")) || mentions(next, &format_ident!("act"))
                };
                let tail = match rec {
                    // A next situation that is a value made of the
                    // registers (no call of `cx`, leaving nothing, moving
                    // nothing the entry reads): made first, once, then the
                    // transition counted (`run.tally`) or the entry recorded
                    // (the order of the store's terms is the entry's alone).
                    Some((entry, next, one, lazy))
                        if rec_all
                            && !leaves(&next)
                            && !mentions(&next, &format_ident!("cx"))
                            && !super::moves_any(&next, &entry) =>
                    {
                        // The entry and its record one `TypedRun` call
                        // where its terms can be made there (the id bound
                        // before the next situation is not reused: a move
                        // there would end its borrow).
                        let lazy = lazy.and_then(|l| {
                            l.stmts(&quote!(), |id| {
                                quote!(run.exit_end(cx, &mut count, #curl, #id, ea, &next_at);)
                            })
                        });
                        // Else the entry and its record one call where it fits.
                        let rec = one.unwrap_or_else(|| {
                            quote! {
                                #entry
                                cx.record_next(exp, act, |s| next_at.id_term(p, s));
                            }
                        });
                        // The count in `TypedRun::exit_end` too.
                        let rec = match lazy {
                            Some(l) => l,
                            None => quote!(run.tally(&mut count); if run.recorded() { #rec }),
                        };
                        quote! {
                            let next_at: Nat = #next;
                            #rec
                            break 'visit next_at;
                        }
                    }
                    // A next situation that does not hand over (no entry
                    // read there): the recorded way apart, the other as it
                    // is without a history (nothing kept alive across it).
                    // A next situation that hands over before anything
                    // else (a Prolog condition: a cold path) is written once,
                    // below, not once a way.
                    Some((entry, next, _, _))
                        if rec_all && !uses_entry(&next) && !super::hands_over_first(&next) =>
                    {
                        quote! {
                            if run.recorded() {
                                #entry
                                let next_at: Nat = #next;
                                cx.record_next(exp, act, |s| next_at.id_term(p, s));
                                break 'visit next_at;
                            }
                            #plain
                        }
                    }
                    // The entry one call (`TypedRun::entry`) where its
                    // terms can be made there.
                    Some((_, next, _, Some(lazy)))
                        if rec_all && lazy.stmts(&head, |_| quote!()).is_some() =>
                    {
                        let entry = lazy
                            .stmts(&head, |id| {
                                quote!(let (exp, act) = run.entry(cx, &mut count, #curl, #id, ea);)
                            })
                            .unwrap_or_default();
                        quote! {
                            #entry
                            let next_at: Nat = #next;
                            run.record_next(cx, exp, act, |s| next_at.id_term(p, s));
                            break 'visit next_at;
                        }
                    }
                    Some((entry, next, _, _)) if rec_all => quote! {
                        let (exp, act) = if run.recorded() {
                            #entry
                            (exp, act)
                        } else {
                            count += 1;
                            (Term::NIL, Term::NIL)
                        };
                        let next_at: Nat = #next;
                        run.record_next(cx, exp, act, |s| next_at.id_term(p, s));
                        break 'visit next_at;
                    },
                    _ => plain,
                };
                // `arc_at` only where the code reads it.
                let body = drop_unread_let(quote!(#head #tail), "act0");
                let body = super::with_arc_at(&body, i);
                if cond.is_empty() {
                    body
                } else {
                    quote!(if #cond { #body })
                }
            });
            let arcs = quote!(#(#arcs)*);
            // Where a final leaves the outputs, each binding final's arm
            // loads those its arcs read.
            let loads = out_loads
                .iter()
                .filter(|(r, _)| any_leaves && !leaving && mentions(&arcs, r))
                .map(|(_, stmt)| stmt);
            quote!(#pat => { #(#loads)* #arcs })
        });
        let arms: Vec<TokenStream> = arms.collect();
        let top: &[(Ident, TokenStream)] = if any_leaves { &[] } else { &out_loads };
        let body = self.nat_exit_body(d, ix, j, quote!(#(#arms)*), top, &head)?;
        Ok((body, rec_all))
    }

    /// The body of the exit arcs' arm: the callee's frame taken, the
    /// outputs the arms `arms` read loaded, the arms, and the machine's
    /// error when none takes the final.
    fn nat_exit_body(
        &self,
        d: &Dm,
        ix: usize,
        j: usize,
        arms: TokenStream,
        out_loads: &[(Ident, TokenStream)],
        head: &[(Ident, TokenStream)],
    ) -> N<TokenStream> {
        let hand = &d.hand;
        let curl = Literal::u32_unsuffixed(ix as u32);
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let id_arg = super::atom_arg(&id);
        let callee_v = format_ident!("D{}", j);
        let out_loads = out_loads
            .iter()
            .filter(|(r, _)| mentions(&arms, r))
            .map(|(_, stmt)| stmt);
        // No exit arc takes the final situation: the machine says so (in
        // a DM without locals the runtime's hand-over and the error in one
        // call, `NatBelow::no_exit`, the id filled after the hand-over:
        // an atom, or a `Fill` made before where the call would not fit
        // on a line; the arm's statements are indented by 20).
        let no_exit = |id: &TokenStream| quote!(return stack.no_exit(p, cx, count, #curl, #id, &done_frame.at););
        let fill = super::fill_arg(&id_stmts, &id);
        let no_exit = match (&fill, id_stmts.is_empty()) {
            _ if !super::runtime_hand(hand) => None,
            (Some(fill), _) if super::fits(&no_exit(fill), 20) => Some(no_exit(fill)),
            (Some(fill), _) if super::fits(&no_exit(&id), 20) => {
                let ret = no_exit(&id);
                Some(quote!(let #id = #fill; #ret))
            }
            (None, true) if super::fits(&no_exit(&id_arg), 20) => Some(no_exit(&id_arg)),
            _ => None,
        };
        let no_exit = no_exit.unwrap_or_else(|| {
            quote! {
                #hand
                #(#id_stmts)*
                return cx.no_exit(count, #curl, #id_arg, |s| done_frame.at.id_term(p, s));
            }
        });
        let body = quote! {
            match &done_frame.at {
                #arms
                _ => {}
            }
            #no_exit
        };
        // The waiting situation's id as one `Fill` made first where the arms
        // make it more than once (their `let`s of it dropped): where it
        // reads only the variant's fields (immutable: nothing changes them
        // while it lives).
        let fields: Vec<Ident> = self
            .nat_wait_fields(d, ix)?
            .iter()
            .map(|(r, _)| reg(*r))
            .collect();
        let (one_id, body) = match &fill {
            Some(fill) if reads_only(fill, &fields) => one_fill(&body, fill),
            _ => (None, body),
        };
        let body = quote! {
            let super::NatFrame::#callee_v(done_frame) = ret else {
                return Err(cx.fault(Fault::WrongFrame));
            };
            #(#out_loads)*
            #one_id
            #body
        };
        // Only the parameters the exit arcs read are loaded (a load is a
        // clone: a list's count changed and changed back on every return).
        let head = head
            .iter()
            .filter(|(r, _)| mentions(&body, r))
            .map(|(_, stmt)| stmt);
        Ok(quote!(#(#head)* #body))
    }

    /// The recorded way of exit arc `arc` of situation `ix` (its action's
    /// values `act<n>` computed): the entry's expectation and action as
    /// terms `exp` and `act`, the situation's id entered; and the next
    /// situation, recording where it hands over (`run.goto`).
    fn nat_exit_record(
        &self,
        d: &Dm,
        ix: usize,
        arc: &crate::mir::ArcPlan,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<ExitRecord> {
        let mut ts = Vec::new();
        let mut n = 0;
        let exp = self.nat_ev_term(&arc.expectation, regs, &mut ts, &mut n)?;
        let items = match &arc.action {
            Action::List { items, .. } => items.len(),
            Action::One(_) => 1,
        };
        let acts: Vec<Ident> = (0..items).map(|k| format_ident!("act{}", k)).collect();
        let act = match &arc.action {
            Action::List { .. } => quote! {
                let act_items = [#(cx.term(&#acts)),*];
                let act = cx.store().list(&act_items);
            },
            // A constant atom: its term (`act0` then often read nowhere),
            // beside the expectation's.
            Action::One(e) => match e {
                Ev::Built(Build::Const(t)) if self.store.atom_of(*t).is_some() => {
                    let t = self.atom_term(self.store.atom_of(*t).ok_or("an atom")?)?;
                    quote!(#t)
                }
                _ => quote!(let act = cx.term(&act0);),
            },
        };
        // The expectation's last statement, `let b = E;` with `b` its term,
        // is its `let` (`let exp: Term = E;`).
        let (ts, exp) = match ts.split_last() {
            Some((last, rest)) => match super::one_value(std::slice::from_ref(last), &exp) {
                Some(e) => (rest.to_vec(), e),
                None => (ts.clone(), exp),
            },
            None => (ts, exp),
        };
        // Its terms made by the call that builds it (`cx.build_of`), where
        // each is a native value's made just before, in order.
        let (ts, exp) = match built_of(&ts, &exp) {
            Some(e) => (Vec::new(), e),
            None => (ts, exp),
        };
        // A constant action beside a leaf expectation: one `let` of the
        // pair (a built one beside it would often break the line).
        let exp_act = if act.to_string().starts_with("let") {
            quote!(let exp: Term = #exp; #act)
        } else if ts.is_empty() && !exp.to_string().starts_with("cx") {
            quote!(let (exp, act) = (#exp, #act);)
        } else {
            quote!(let exp: Term = #exp; let act = #act;)
        };
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let curl = Literal::u32_unsuffixed(ix as u32);
        let pipe_in = d.pipe_in.take();
        *d.rec.borrow_mut() = super::rec_entry();
        let next = self.nat_next_out(d, ix, &arc.next, super::pipe::arc_out(arc), regs, cur_name);
        *d.rec.borrow_mut() = quote!();
        d.pipe_in.set(pipe_in);
        let next = super::as_expr(next?);
        // The entry and the record of a next situation made before it as
        // one call (`Cx::enter_next`) where it fits on a line (60 columns:
        // prettyplease's least room, at any depth).
        let id_arg = super::atom_arg(&id);
        let call = quote!(cx.enter_next(&mut count, #curl, #id_arg, exp, act, &next_at););
        let one = super::fits_at(&call, None).then(|| {
            quote! {
                #(#ts)*
                #exp_act
                #(#id_stmts)*
                #call
            }
        });
        let lazy = lazy_entry(&ts, &exp, &act, &id_stmts, &id);
        Ok((
            quote! {
                #(#ts)*
                #exp_act
                #(#id_stmts)*
                cx.enter_counted(&mut count, #curl, #id);
            },
            next,
            one,
            lazy,
        ))
    }

    /// Unifies the expectation `b` (the caller's registers, fresh or set)
    /// with the callee's final id `pat` at `path` (its variables the
    /// variant's fields `c<r>`, references): tests and bindings pushed;
    /// `false` when they never unify.
    #[allow(clippy::too_many_arguments)]
    fn nat_unify(
        &self,
        d: &Dm,
        ix: usize,
        callee: &Dm,
        k: usize,
        b: &Build,
        pat: Term,
        path: &mut Vec<usize>,
        fresh: &[Reg],
        regs: &mut Regs,
        vars: &mut HashMap<u32, V>,
        tests: &mut Vec<TokenStream>,
        lets: &mut Vec<TokenStream>,
    ) -> N<bool> {
        // The callee's side as a value, when it is a variable or atomic.
        let side: Option<V> = match self.store.value(pat) {
            Value::Var(v) => Some(match vars.get(&v.index()) {
                Some(x) => x.clone(),
                None => {
                    let r = Self::nat_id_reg(callee, k, path)
                        .ok_or("a final's id variable has no register")?;
                    let c = format_ident!("c{}", r);
                    let x = V {
                        e: quote!(#c.clone()),
                        ty: callee.types[k].regs[r as usize].ty.clone(),
                    };
                    vars.insert(v.index(), x.clone());
                    x
                }
            }),
            Value::Atom(_) | Value::Int(_) => {
                Some(self.nat_value(&Build::Const(pat), &Regs::new())?)
            }
            _ => None,
        };
        match b {
            Build::Reg(r) if fresh.contains(r) && !regs.contains_key(r) => {
                // A fresh variable of the arc takes the value. One that
                // takes a compound (`Result` against `got(P)`) is not held:
                // code that reads it fails to generate ("read unset"), and
                // the call is then the machine's.
                let Some(side) = side else {
                    return Ok(true);
                };
                let ty = d.types[ix].regs[*r as usize].ty.clone();
                let e = coerce(&side, &ty)?;
                let rr = reg(*r);
                lets.push(quote!(let #rr = #e;));
                regs.insert(*r, (rr, ty));
                Ok(true)
            }
            Build::Reg(r) => {
                let mine = self.nat_value(&Build::Reg(*r), regs)?;
                let side = side.ok_or("an exit arc's value against a compound")?;
                tests.push(identical(&mine, &side).ok_or("`==` of these types")?);
                Ok(true)
            }
            Build::Const(c) => match (self.store.value(*c), self.store.value(pat)) {
                (Value::Var(_), _) => Err("a variable constant".into()),
                (_, Value::Var(_)) => {
                    let mine = self.nat_value(&Build::Const(*c), regs)?;
                    let side = side.ok_or("no value")?;
                    tests.push(identical(&mine, &side).ok_or("`==` of these types")?);
                    Ok(true)
                }
                (Value::Compound(n1, a1), Value::Compound(n2, a2)) => {
                    if n1 != n2 || a1.len() != a2.len() {
                        return Ok(false);
                    }
                    let (a1, a2) = (a1.to_vec(), a2.to_vec());
                    for (i, (x, y)) in a1.into_iter().zip(a2).enumerate() {
                        path.push(i);
                        let ok = self.nat_unify(
                            d,
                            ix,
                            callee,
                            k,
                            &Build::Const(x),
                            y,
                            path,
                            fresh,
                            regs,
                            vars,
                            tests,
                            lets,
                        )?;
                        path.pop();
                        if !ok {
                            return Ok(false);
                        }
                    }
                    Ok(true)
                }
                (Value::Compound(..), _) | (_, Value::Compound(..)) => Ok(false),
                _ => Ok(self.store.identical(*c, pat)),
            },
            Build::Compound(name, args) => match self.store.value(pat) {
                Value::Compound(n2, a2) => {
                    if *name != n2 || args.len() != a2.len() {
                        return Ok(false);
                    }
                    let a2 = a2.to_vec();
                    for (i, (x, y)) in args.iter().zip(a2).enumerate() {
                        path.push(i);
                        let ok = self.nat_unify(
                            d, ix, callee, k, x, y, path, fresh, regs, vars, tests, lets,
                        )?;
                        path.pop();
                        if !ok {
                            return Ok(false);
                        }
                    }
                    Ok(true)
                }
                Value::Var(_) => Err("a compound expectation against a variable".into()),
                _ => Ok(false),
            },
        }
    }

    /// Whether `e` is a constant compound that is not a list
    /// (`say('Nothing here.')`): an effector's action performed as it is.
    pub(super) fn const_compound(&self, e: &Ev) -> bool {
        matches!(e, Ev::Built(Build::Const(t))
            if self.store.functor(*t).is_some_and(|(f, n)| n > 0 && f != atoms::DOT))
    }

    /// An exit arc's action (and a perceptual or neutral arc's, when it
    /// has only these): `inc`/`get` of a local into a fresh variable,
    /// `get(v, X)` with `X` made before (unified), `set` of a local the
    /// frame holds or of a global,
    /// `V is E` of ints into a fresh variable, atoms and numbers performed
    /// (skipped where the run's actions ignore them).
    pub(super) fn nat_exit_action(
        &self,
        d: &Dm,
        ix: usize,
        arc_ix: usize,
        arc_plan: &crate::mir::ArcPlan,
        regs: &mut Regs,
    ) -> N<TokenStream> {
        let action = &arc_plan.action;
        // The registers the expectation was made of (a cold arm's entry).
        let exp_regs = regs.clone();
        let hand = &d.hand;
        let curl = Literal::u32_unsuffixed(ix as u32);
        let arc = Literal::usize_unsuffixed(arc_ix);
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let enter = quote! {
            #hand
            #(#id_stmts)*
            cx.enter_counted(&mut count, #curl, #id);
        };
        // The id as a call takes it: an atom, or a `Fill` bound first.
        let ground_id = match super::fill_arg(&id_stmts, &id) {
            Some(fill) => Some((quote!(let #id = #fill;), id.clone())),
            None if id_stmts.is_empty() && super::atom_arg(&id).to_string() != id.to_string() => {
                Some((quote!(), super::atom_arg(&id)))
            }
            None => None,
        };
        let mut stmts = Vec::new();
        let mut performs = Vec::new();
        let items: Vec<&Ev> = match action {
            Action::List { items, .. } => items.iter().collect(),
            Action::One(e) => vec![e],
        };
        let list = matches!(action, Action::List { .. });
        // The terms of effectors' compound actions (`Ev` counter `b<n>`).
        let mut nb = 0;
        for (n, item) in items.into_iter().enumerate() {
            let x = format_ident!("act{}", n);
            // A constant atom: whether it is `empty` is known here.
            let mut const_atom = None;
            // An effector's compound action built of values (`note(S)`):
            // its term made from native values, handed to the effector
            // without entering the machine (below).
            // A constant compound (`say('Nothing here.')`) too.
            if (self.const_compound(item) || pure_compound(item).is_some_and(|f| f != atoms::DOT))
                && made_values(item, regs)
            {
                let mut ts = Vec::new();
                let t = self.nat_ev_term(item, regs, &mut ts, &mut nb)?;
                stmts.push(quote!(#(#ts)* let #x = Ground(#t);));
                // A compound (not `empty`, not a list): what the machine's
                // `perform` does with it is the effector's `perform`.
                performs.push(quote! {
                    if let Err(e) = cx.perform_value(#x.0) {
                        #enter
                        return Err(cx.action_failed(e, Some(#arc)));
                    }
                });
                continue;
            }
            // A global's `get`: where its value is one native code cannot
            // hold, the arc's rest on terms (`cold_act`), else an error.
            let cold = super::cold_act::is_global_get(d, item)
                .then(|| {
                    self.cold_action(d, arc_plan, arc_ix, n, regs, &exp_regs)
                        .ok()
                })
                .flatten();
            let _cold = super::cold_act::ColdArm::set(&self.global_cold, cold);
            let ty = match item {
                // `get`/`inc` of a global (a name that is no declared local
                // of this DM, held in the frame or not: the machine's
                // `var_op` looks at the running DM's locals first).
                Ev::VarOpFresh { op, name, dst } if !d.declares_local(*name) => {
                    let (gty, value) = self.nat_global_op(*op, *name, None, arc_ix, &enter)?;
                    let dty = d.types[ix].regs[*dst as usize].ty.clone();
                    bind_fresh(&mut stmts, regs, &x, value, &gty, *dst, dty)?;
                    gty
                }
                // `set(g, V)` of a global to a native value (stored as
                // written: a value evaluates to itself).
                Ev::VarOp { op, name, arg } if *op == atoms::SET && !d.declares_local(*name) => {
                    let v = self.nat_value(arg, regs)?;
                    let (_, value) = self.nat_global_op(*op, *name, Some(&v), arc_ix, &enter)?;
                    stmts.push(quote!(let #x = #value;));
                    if let Build::Const(t) = arg {
                        if let sitlog_runtime::Value::Atom(a) = self.store.value(*t) {
                            const_atom = Some(a);
                        }
                    }
                    v.ty
                }
                // A ground `set(g, k)` of a global (`set(done, yes)`,
                // `set(g, 5)`), which the MIR gives the evaluator as a
                // constant: the same as `set(g, V)` of a native value
                // (the value stored as written, D-38; `set` gives it).
                Ev::Eval(Build::Const(t)) if self.ground_global_set(d, *t).is_some() => {
                    let (name, k) = self.ground_global_set(d, *t).ok_or("not a `set`")?;
                    let v = self.nat_value(&Build::Const(k), regs)?;
                    let (_, value) =
                        self.nat_global_op(atoms::SET, name, Some(&v), arc_ix, &enter)?;
                    stmts.push(quote!(let #x = #value;));
                    if let sitlog_runtime::Value::Atom(a) = self.store.value(k) {
                        const_atom = Some(a);
                    }
                    v.ty
                }
                // `get(v, X)` with `X` made before (bound, or an arc's
                // variable the machine's `get` binds): `v`'s value unified
                // with `X` (`Gen::nat_get_unify`), a global's read as for
                // a fresh `X`, a local's in the frame.
                Ev::VarOp {
                    op,
                    name,
                    arg: Build::Reg(r),
                } if *op == atoms::GET => {
                    let got = if d.declares_local(*name) {
                        let (l, ty) = d
                            .local_field(*name)
                            .ok_or("`get` of a local the frame does not hold")?;
                        V {
                            e: quote!(#l.clone()),
                            ty,
                        }
                    } else {
                        let (gty, e) = self.nat_global_op(*op, *name, None, arc_ix, &enter)?;
                        V { e, ty: gty }
                    };
                    let at = quote!(Some(#arc));
                    let v =
                        self.nat_get_unify(d, ix, *name, *r, got, regs, &mut stmts, &enter, &at)?;
                    let e = v.e;
                    stmts.push(quote!(let #x = #e;));
                    v.ty
                }
                // `set(l, V)` of a local the frame holds, `V` a native value
                // of its type (stored as written, D-38: the field written;
                // `set` gives the value).
                Ev::VarOp { op, name, arg } if *op == atoms::SET => {
                    let v = self.nat_value(arg, regs)?;
                    let k = match arg {
                        Build::Const(t) => self.store.atom_of(*t),
                        _ => None,
                    };
                    self.nat_local_set(d, *name, &x, v, k, &mut stmts, &mut const_atom)?
                }
                // A ground `set(l, k)` of a local (`set(n, 0)`), a constant
                // the MIR gives the evaluator: the same.
                Ev::Eval(Build::Const(t))
                    if self
                        .ground_set(*t)
                        .is_some_and(|(l, _)| d.declares_local(l)) =>
                {
                    let (name, k) = self.ground_set(*t).ok_or("not a `set`")?;
                    let v = self.nat_value(&Build::Const(k), regs)?;
                    let a = self.store.atom_of(k);
                    self.nat_local_set(d, name, &x, v, a, &mut stmts, &mut const_atom)?
                }
                Ev::VarOpFresh { op, name, dst } => {
                    let (l, lty) = d.local_field(*name).ok_or("`inc`/`get` of a global")?;
                    let dty = d.types[ix].regs[*dst as usize].ty.clone();
                    let opa = self.atom_native(*op)?;
                    let namea = self.atom_native(*name)?;
                    let value = if *op == atoms::INC && lty == Ty::Int {
                        quote! {
                            match #l.checked_add(1) {
                                Some(v) => { *#l = v; v }
                                None => {
                                    #enter
                                    return match cx.var_op_fresh(#opa, #namea, Some(#arc)) {
                                        Err(e) => Err(e),
                                        Ok(_) => Err(cx.error(
                                            "`inc` overflowed in native code only",
                                            None,
                                        )),
                                    };
                                }
                            }
                        }
                    } else if *op == atoms::GET {
                        quote!(#l.clone())
                    } else {
                        return Err("a variable operation is not native".into());
                    };
                    bind_fresh(&mut stmts, regs, &x, value, &lty, *dst, dty)?;
                    lty
                }
                // `J is I + 1` into a fresh variable that inference types
                // `int` (so its operands are ints): checked `i64`
                // arithmetic as in a native `prog`; an overflow is the
                // machine's evaluation (its value, if native code can hold
                // it, else an error, as `nat_prog` does).
                // Into a fresh variable typed `ground` (`L1 is L - 1`, `L`
                // read from a `ground` pipe): the same, each `Val` operand
                // checked for an int at run time; a value that is not an
                // int (a float, a non-number: the machine's value or its
                // error) takes the machine's way as an overflow does.
                Ev::IsFresh { expr, dst }
                    if matches!(d.types[ix].regs[*dst as usize].ty, Ty::Int | Ty::Ground) =>
                {
                    let dty = d.types[ix].regs[*dst as usize].ty.clone();
                    let e = self.nat_int_expr(expr, regs)?;
                    let mut ts = Vec::new();
                    let mut n = 0;
                    let t = self.nat_build_term(expr, regs, &mut ts, &mut n)?;
                    let (rty, some) = if dty == Ty::Int {
                        (quote!(i64), quote!(v))
                    } else {
                        (quote!(Val), quote!(Val::Int(v)))
                    };
                    stmts.push(quote! {
                        let #x: #rty = match #e {
                            Some(v) => #some,
                            None => {
                                #enter
                                #(#ts)*
                                let v = cx.is(None, #t, Some(#arc))?;
                                let v = cx.store_ref().deref(v);
                                match cx.to_native::<#rty>(v) {
                                    Some(v) => v,
                                    None => {
                                        return Err(cx.error(
                                            "`is` gave a value native code cannot hold",
                                            Some(#arc),
                                        ))
                                    }
                                }
                            }
                        };
                    });
                    let rr = reg(*dst);
                    let copy = if dty == Ty::Int {
                        quote!(#x)
                    } else {
                        quote!(#x.clone())
                    };
                    stmts.push(quote!(let #rr = #copy;));
                    regs.insert(*dst, (rr, dty.clone()));
                    dty
                }
                // `K1 is K + 1.0` into a fresh variable typed `float`: the
                // evaluator's float arithmetic in Rust (`float_expr`); an
                // operand that is no number, an overflow or a result that
                // is not finite takes the machine's way as above.
                Ev::IsFresh { expr, dst } if d.types[ix].regs[*dst as usize].ty == Ty::Float => {
                    let e = self.nat_float_expr(expr, regs)?;
                    let mut ts = Vec::new();
                    let mut n = 0;
                    let t = self.nat_build_term(expr, regs, &mut ts, &mut n)?;
                    stmts.push(quote! {
                        let #x: f64 = match #e {
                            Some(v) => v,
                            None => {
                                #enter
                                #(#ts)*
                                let v = cx.is(None, #t, Some(#arc))?;
                                let v = cx.store_ref().deref(v);
                                match cx.to_native::<f64>(v) {
                                    Some(v) => v,
                                    None => {
                                        return Err(cx.error(
                                            "`is` gave a value native code cannot hold",
                                            Some(#arc),
                                        ))
                                    }
                                }
                            }
                        };
                    });
                    let rr = reg(*dst);
                    stmts.push(quote!(let #rr = #x;));
                    regs.insert(*dst, (rr, Ty::Float));
                    Ty::Float
                }
                // `V = E` (D-30) into a fresh variable: `E`'s native
                // value, as built, held in `V`'s register (no unification
                // is needed: `V` is not made yet and `E` does not name it).
                Ev::BindFresh { expr, dst } => {
                    let v = self.nat_value(expr, regs)?;
                    if let Build::Const(t) = expr {
                        if let sitlog_runtime::Value::Atom(a) = self.store.value(*t) {
                            const_atom = Some(a);
                        }
                    }
                    let dty = d.types[ix].regs[*dst as usize].ty.clone();
                    bind_fresh(&mut stmts, regs, &x, v.e, &v.ty, *dst, dty)?;
                    v.ty
                }
                Ev::Built(Build::Const(t)) => {
                    let v = self.nat_value(&Build::Const(*t), regs)?;
                    let e = v.e;
                    stmts.push(quote!(let #x = #e;));
                    if let sitlog_runtime::Value::Atom(a) = self.store.value(*t) {
                        const_atom = Some(a);
                    }
                    v.ty
                }
                Ev::Value(r) => {
                    let v = self.nat_value(&Build::Reg(*r), regs)?;
                    let e = v.e;
                    stmts.push(quote!(let #x = #e;));
                    v.ty
                }
                _ => return Err("an exit arc's action is not native".into()),
            };
            let perform = if list {
                quote! {
                    #enter
                    let t = cx.term(&#x);
                    cx.perform_each(&[t], Some(#arc))?;
                }
            } else {
                quote! {
                    #enter
                    let t = cx.term(&#x);
                    cx.perform(t, Some(#arc))?;
                }
            };
            // A number or a constant atom other than `empty` (never a
            // list): handed to the effector without entering the machine
            // (`Cx::perform_value`); the situation entered (its id built)
            // only where the effector fails, for its error.
            let perform_value = quote! {
                let t = cx.term(&#x);
                if let Err(e) = cx.perform_value(t) {
                    #enter
                    return Err(cx.action_failed(e, Some(#arc)));
                }
            };
            performs.push(match ty {
                Ty::Int | Ty::Float => quote!(if !run.quiet_numbers { #perform_value }),
                Ty::Sym if const_atom == Some(atoms::EMPTY) && !list => {
                    let id_arg = super::atom_arg(&id);
                    // One call where it fits in a DM without locals
                    // (`Cx::nat_empty` performs `empty`, handing over only
                    // where the effector fails). Else `empty` handed to the
                    // effector (`Cx::empty_fails`) and, only where it fails,
                    // the hand-over (a DM's own writes its locals back) and
                    // the entry that reports the error.
                    let arc_t = quote!(#arc);
                    let gated = super::runtime_hand(hand)
                        .then(|| {
                            super::gated_empty_call(&id_stmts, &id, &curl, &arc_t, "exit_empty")
                        })
                        .flatten();
                    match super::empty_call(&id_stmts, &id, &curl, &arc_t, false) {
                        _ if gated.is_some() => gated.unwrap_or_default(),
                        Some(call) if super::runtime_hand(hand) => {
                            quote!(if !run.quiet_empty { #call })
                        }
                        _ if !hand.is_empty() => quote! {
                            if cx.empty_fails(run) {
                                #hand
                                #(#id_stmts)*
                                cx.enter_performed(&mut count, #curl, #id_arg, Some(#arc))?;
                            }
                        },
                        _ => quote! {
                            if !run.quiet_empty {
                                #hand
                                #(#id_stmts)*
                                cx.enter_empty(&mut count, #curl, #id_arg, true, Some(#arc))?;
                            }
                        },
                    }
                }
                Ty::Sym if const_atom == Some(atoms::EMPTY) => {
                    quote!(if !run.quiet_empty { #perform })
                }
                Ty::Sym if const_atom.is_some() => perform_value,
                // An atom other than `empty` handed to the effector as a
                // constant one is (`Cx::perform_value`: what the machine's
                // `perform` does with it, no hand-over; `set(goal, G)`'s
                // value, helper `review22`).
                Ty::Sym => quote! {
                    if #x != atoms::EMPTY { #perform_value }
                    else if !run.quiet_empty { #perform }
                },
                Ty::Term | Ty::List(_) => perform,
                // A `ground` value (`set(m, W)`, `W` a parameter's value):
                // a number or `empty` skipped where the run's actions
                // ignore it, as for a value of those types; a number or
                // an atom other than `empty` performed, handed to the
                // effector as an `int`'s is (`Cx::perform_value`, no
                // hand-over).
                // The same in one call (`NatBelow::perform`) where the
                // hand-over is the runtime's and the id an atom or a `Fill`.
                Ty::Ground if super::runtime_hand(hand) && !list && ground_id.is_some() => {
                    let (id_let, id_arg) = ground_id.clone().unwrap_or_default();
                    quote! {
                        #id_let
                        stack.perform(cx, run, &mut count, #curl, #arc, #id_arg, &#x)?;
                    }
                }
                Ty::Ground => quote! {
                    match &#x {
                        Val::Int(_) | Val::Float(_) => {
                            if !run.quiet_numbers { #perform_value }
                        }
                        Val::Sym(s) if run.quiet_empty && *s == atoms::EMPTY => {}
                        Val::Sym(s) if *s != atoms::EMPTY => { #perform_value }
                        _ => { #perform }
                    }
                },
                _ => return Err("an action of this type".into()),
            });
        }
        Ok(quote!(#(#stmts)* #(#performs)*))
    }

    /// `set(l, V)` of local `name` of DM `d` held in the frame, `v` the
    /// native value `V` (`k`: the atom it is, if a constant one): the field
    /// written with `v` converted to the local's type (not native where it
    /// does not convert: a value the local's type does not hold), `x`
    /// the action's value (`set` gives `V`); its type.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn nat_local_set(
        &self,
        d: &Dm,
        name: sitlog_syntax::Atom,
        x: &Ident,
        v: V,
        k: Option<sitlog_syntax::Atom>,
        stmts: &mut Vec<TokenStream>,
        const_atom: &mut Option<sitlog_syntax::Atom>,
    ) -> N<Ty> {
        let (l, lty) = d
            .local_field(name)
            .ok_or("`set` of a local the frame does not hold")?;
        let e = &v.e;
        let to = coerce(
            &V {
                e: quote!(#x.clone()),
                ty: v.ty.clone(),
            },
            &lty,
        )?;
        stmts.push(quote! {
            let #x = #e;
            *#l = #to;
        });
        *const_atom = k;
        Ok(v.ty)
    }

    /// `set(g, k)` as written (a ground constant), `g` no declared local of
    /// DM `d` and `k` an atom or a number: `g` and `k`.
    fn ground_global_set(&self, d: &Dm, t: Term) -> Option<(sitlog_syntax::Atom, Term)> {
        self.ground_set(t).filter(|(g, _)| !d.declares_local(*g))
    }

    /// `set(v, k)` as written (a ground constant), `k` an atom or a
    /// number: `v` and `k`.
    fn ground_set(&self, t: Term) -> Option<(sitlog_syntax::Atom, Term)> {
        let (name, args) = match self.store.value(t) {
            sitlog_runtime::Value::Compound(name, args) if args.len() == 2 => (name, args),
            _ => return None,
        };
        let (g, k) = (args[0], args[1]);
        let g = self.store.atom_of(g)?;
        if name != atoms::SET {
            return None;
        }
        match self.store.value(k) {
            sitlog_runtime::Value::Atom(a) if a != atoms::NIL => Some((g, k)),
            sitlog_runtime::Value::Int(_) => Some((g, k)),
            sitlog_runtime::Value::Float(f) if f.is_finite() => Some((g, k)),
            _ => None,
        }
    }

    /// `get`/`inc` (`set: None`) or `set` (`set: Some(v)`, the native
    /// value written) of global `name` in arc `arc` by native code, the
    /// machine not entered (`Cx::global_as`, `Cx::global_inc`,
    /// `Cx::global_set`: read or written in the machine's globals at each
    /// use, never a typed copy kept, since any DM, a user function or the
    /// machine's own code may set it). The value's type (the global's MIR
    /// type; `set`: the value's) and its expression. Where the fast way
    /// does not apply (no such global, a value that is not a number or not
    /// of the global's type, an overflow) the machine is entered (`enter`)
    /// and its `var_op` does the operation or reports its error, with its
    /// message and place; a value it gives that native code cannot hold
    /// (only if the inference were wrong) is an error there.
    fn nat_global_op(
        &self,
        op: sitlog_syntax::Atom,
        name: sitlog_syntax::Atom,
        set: Option<&V>,
        arc: usize,
        enter: &TokenStream,
    ) -> N<(Ty, TokenStream)> {
        let arc = Literal::usize_unsuffixed(arc);
        let (opa, namea) = (self.atom_native(op)?, self.atom_native(name)?);
        if let Some(v) = set {
            let e = &v.e;
            let value = quote! {{
                let v = #e;
                let t = cx.term(&v);
                if !cx.global_set(#namea, t) {
                    #enter
                    cx.var_op(#opa, #namea, t, Some(#arc))?;
                }
                v
            }};
            return Ok((v.ty.clone(), value));
        }
        let gty = self
            .mir_types
            .as_ref()
            .and_then(|t| t.globals.iter().find(|(n, _)| *n == name))
            .map(|(_, t)| t.ty.clone())
            .ok_or("not a declared global")?;
        // A global native code holds as a value (not `term`, not `_`).
        if matches!(gty, Ty::Term | Ty::Never) || !gty.is_native() {
            return Err(format!("a global of type {gty}"));
        }
        let rt = rust_ty(&gty)?;
        let fast = if op == atoms::INC {
            if !matches!(gty, Ty::Int | Ty::Float) {
                return Err("`inc` of a global that is not a number".into());
            }
            quote!(cx.global_inc::<#rt>(#namea))
        } else if op == atoms::GET {
            quote!(cx.global_as::<#rt>(#namea))
        } else {
            return Err("a variable operation is not native".into());
        };
        // A `get`'s value native code cannot hold: the arc's rest on terms
        // where the caller made it (`cold_act`), else an error.
        let cold = match self.global_cold.borrow().clone() {
            Some(cold) if op == atoms::GET => cold,
            _ => quote! {
                return Err(cx.error(
                    "a global's value native code cannot hold",
                    Some(#arc),
                ))
            },
        };
        let value = quote! {
            match #fast {
                Some(v) => v,
                None => {
                    #enter
                    let t = cx.var_op_fresh(#opa, #namea, Some(#arc))?;
                    match cx.to_native::<#rt>(t) {
                        Some(v) => v,
                        None => {
                            #cold
                        }
                    }
                }
            }
        };
        Ok((gty, value))
    }

    /// `l op r` on numbers: in Rust when both are ints or both floats (a
    /// ground term or a `Val` read as one), else evaluated on terms as the
    /// term code does (the machine entered in situation `cur`: its result
    /// or its error; an int against a float goes there too).
    pub(super) fn nat_arith(&self, d: &Dm, cur: usize, op: ArithCmp, l: V, r: V) -> N<TokenStream> {
        self.nat_arith_as(d, cur, op, l, r, false)
    }

    /// [`Gen::nat_arith`]; `value`: the comparison's value is tested
    /// (`when/3`'s condition, `Cond::Cmp`), whose error where the operands
    /// are not numbers is the evaluator's (`Cx::compare_value`), not a
    /// conditional's.
    pub(super) fn nat_arith_as(
        &self,
        d: &Dm,
        cur: usize,
        op: ArithCmp,
        l: V,
        r: V,
        value: bool,
    ) -> N<TokenStream> {
        let how = if value {
            Decide::Value
        } else {
            Decide::Condition
        };
        self.nat_arith_fast(d, cur, op, (l, None), (r, None), how)
    }

    /// [`Gen::nat_arith_as`] for a comparison that is an operand of a
    /// conditional's `(A, B)`/`(A ; B)` (`Cond::And`): its value tested,
    /// its error the condition's (`Cx::compare_condition`).
    pub(super) fn nat_arith_in_junction(
        &self,
        d: &Dm,
        cur: usize,
        op: ArithCmp,
        l: V,
        r: V,
    ) -> N<TokenStream> {
        self.nat_arith_fast(d, cur, op, (l, None), (r, None), Decide::Junction)
    }

    /// `l op r` where a side is an arithmetic expression (`N + 1 > L`,
    /// `N * 2 =< Max`, `L - 1 =:= K`: `+`, `-`, `*`, unary `-` over
    /// registers holding ints and int constants, [`Gen::nat_int_expr`]):
    /// that side computed as an int in Rust (checked), compared with the
    /// other as [`Gen::nat_arith`] compares (an int, a float, a `Val`
    /// read as one); where a side is no int or an operation overflows,
    /// the machine's comparison of the sides' terms as the term code
    /// evaluates them (`Cx::arith_condition`: Prolog's result, or its
    /// error), the expression's term built only there. `None`: neither
    /// side is such an expression (or one reads a value that is no int).
    pub(super) fn nat_arith_exprs(
        &self,
        d: &Dm,
        cur: usize,
        op: ArithCmp,
        (l, r): (&Ev, &Ev),
        regs: &Regs,
    ) -> N<Option<TokenStream>> {
        self.nat_arith_exprs_as(d, cur, op, (l, r), regs, Decide::Condition)
    }

    /// [`Gen::nat_arith_exprs`] with the machine's comparison `how`
    /// (`Cond::Cmp`'s sides as written, `Ev::Built`: the value of `A op
    /// B`, [`Decide::Value`], or an operand of a conjunction,
    /// [`Decide::Junction`]).
    pub(super) fn nat_arith_exprs_as(
        &self,
        d: &Dm,
        cur: usize,
        op: ArithCmp,
        (l, r): (&Ev, &Ev),
        regs: &Regs,
        how: Decide,
    ) -> N<Option<TokenStream>> {
        let arith = |e: &Ev| {
            ev_as_build(e).filter(|b| {
                matches!(b, Build::Compound(f, a)
                    if matches!((f.as_str(), a.len()), ("+" | "-" | "*", 2) | ("-", 1)))
            })
        };
        let (lb, rb) = (arith(l), arith(r));
        if lb.is_none() && rb.is_none() {
            return Ok(None);
        }
        let side = |e: &Ev, b: &Option<Build>| -> N<Option<(V, Option<TokenStream>)>> {
            let v = self.nat_ev_value(d, cur, e, regs)?;
            Ok(match b {
                Some(b) => self.nat_int_expr(b, regs).ok().map(|x| (v, Some(x))),
                None => Some((v, None)),
            })
        };
        let (Some(l), Some(r)) = (side(l, &lb)?, side(r, &rb)?) else {
            return Ok(None);
        };
        self.nat_arith_fast(d, cur, op, l, r, how).map(Some)
    }

    /// [`Gen::nat_arith_as`] with, per side, the Rust expression of its
    /// value as an `Option<i64>` where it is an arithmetic expression
    /// ([`Gen::nat_arith_exprs`]): then its `V` (the expression's term as
    /// a value) is built only where the machine decides.
    fn nat_arith_fast(
        &self,
        d: &Dm,
        cur: usize,
        op: ArithCmp,
        (l, lfast): (V, Option<TokenStream>),
        (r, rfast): (V, Option<TokenStream>),
        how: Decide,
    ) -> N<TokenStream> {
        let rt = quote!(::sitlog_runtime);
        let some = quote!(Some);
        let none = quote!(None::<i64>);
        // `cl`, `cr`: references to the operands where they are (no clone
        // of a `Val` to read an int from it).
        let as_int = |v: &V, x: &Ident| -> N<TokenStream> {
            Ok(match v.ty {
                Ty::Int => quote!(#some(*#x)),
                Ty::Float => none.clone(),
                Ty::Term => quote!(cx.store_ref().int_of(#x.0)),
                // A `Val` (`ground`: a parameter, the pipe) holding an int.
                ref t if super::held_as_val(t) => quote!(#x.int()),
                _ => return Err("an arithmetic comparison is not on numbers".into()),
            })
        };
        let nonef = quote!(None::<f64>);
        let as_float = |v: &V, x: &Ident| -> TokenStream {
            match v.ty {
                Ty::Float => quote!(#some(*#x)),
                Ty::Term => quote!(cx.store_ref().float_of(#x.0)),
                ref t if super::held_as_val(t) => quote! {
                    match #x { Val::Float(f) => #some(*f), _ => #nonef }
                },
                _ => nonef.clone(),
            }
        };
        let (lx, rx) = (format_ident!("cl"), format_ident!("cr"));
        let (lfa, rfa) = (lfast.is_some(), rfast.is_some());
        let exprs = lfa || rfa;
        if !exprs
            && ((l.ty == Ty::Int && r.ty == Ty::Int) || (l.ty == Ty::Float && r.ty == Ty::Float))
        {
            let (le, re) = (l.e, r.e);
            return Ok(cmp_tokens(op, quote!(#le), quote!(#re)));
        }
        // An expression's int: computed from the registers (`lfast`), no
        // float of it (an int expression that overflows is the machine's).
        let (li, lf) = match lfast {
            Some(x) => (x, nonef.clone()),
            None => (as_int(&l, &lx)?, as_float(&l, &lx)),
        };
        let (ri, rf) = match rfast {
            Some(x) => (x, nonef.clone()),
            None => (as_int(&r, &rx)?, as_float(&r, &rx)),
        };
        let cmp = cmp_tokens(op, quote!(x), quote!(y));
        let ord = |o: TokenStream| -> TokenStream {
            let eq = quote!(::std::cmp::Ordering::Equal);
            let lt = quote!(::std::cmp::Ordering::Less);
            let gt = quote!(::std::cmp::Ordering::Greater);
            match op {
                ArithCmp::Eq => quote!((#o == Some(#eq))),
                ArithCmp::Ne => quote!((#o != Some(#eq))),
                ArithCmp::Lt => quote!((#o == Some(#lt))),
                ArithCmp::Gt => quote!((#o == Some(#gt))),
                ArithCmp::Le => quote!(matches!(#o, Some(#lt | #eq))),
                ArithCmp::Ge => quote!(matches!(#o, Some(#gt | #eq))),
            }
        };
        let mixed_if =
            ord(quote!(#rt::compare_numbers(#rt::Number::Int(x), #rt::Number::Float(y))));
        let mixed_fi =
            ord(quote!(#rt::compare_numbers(#rt::Number::Float(x), #rt::Number::Int(y))));
        let (hand_count, id_stmts, id, curl) = self.nat_before_evaluating(d, cur)?;
        let opt = match op {
            ArithCmp::Eq => quote!(Eq),
            ArithCmp::Ne => quote!(Ne),
            ArithCmp::Lt => quote!(Lt),
            ArithCmp::Gt => quote!(Gt),
            ArithCmp::Le => quote!(Le),
            ArithCmp::Ge => quote!(Ge),
        };
        let (lp, rp) = (super::place(&l), super::place(&r));
        let (lt, rt_) = (rust_ty(&l.ty)?, rust_ty(&r.ty)?);
        let decide = match how {
            Decide::Value => {
                quote!(cx.compare_value(#rt::ArithCmp::#opt, [lt, rterm], [lt, rterm], arc_at)?)
            }
            Decide::Junction => quote!(cx.compare_condition(
                #rt::ArithCmp::#opt,
                [lt, rterm],
                [lt, rterm],
                arc_at
            )?),
            Decide::Condition => {
                quote!(cx.arith_condition(#rt::ArithCmp::#opt, lt, rterm, arc_at)?)
            }
        };
        // A side that is an expression is read in Rust from its registers;
        // its term (a `Val` compound) made only for the machine.
        let bind = |x: &Ident, t: &TokenStream, p: &TokenStream, fast: bool| {
            if fast {
                (quote!(), quote!(let #x: &#t = &#p;))
            } else {
                (quote!(let #x: &#t = &#p;), quote!())
            }
        };
        let (lbind, llate) = bind(&lx, &lt, &lp, lfa);
        let (rbind, rlate) = bind(&rx, &rt_, &rp, rfa);
        Ok(quote! {{
            #lbind
            #rbind
            match (#li, #ri, #lf, #rf) {
                (#some(x), #some(y), _, _) => #cmp,
                (_, _, #some(x), #some(y)) => #cmp,
                // An int and a float (`I < 300.0`): compared exactly, as
                // the machine compares them (`compare_numbers`).
                (#some(x), _, _, #some(y)) => #mixed_if,
                (_, #some(y), #some(x), _) => #mixed_fi,
                _ => {
                    // Not two ints: the term code's evaluation decides. The
                    // arc's own transition (counted before its next
                    // situation when nothing is recorded; recorded, its
                    // entry counts it) is not the machine's until that
                    // succeeds.
                    #hand_count
                    #(#id_stmts)*
                    cx.enter_with_id(#curl, #id);
                    #llate
                    #rlate
                    let lt = cx.term(#lx);
                    let rterm = cx.term(#rx);
                    #decide
                }
            }
        }})
    }
}

/// Which of the machine's comparisons decides where native code cannot
/// ([`Gen::nat_arith_fast`]).
#[derive(Clone, Copy)]
pub(super) enum Decide {
    /// A conditional's condition `A op B` (`Cx::arith_condition`).
    Condition,
    /// The value of `A op B` (`when/3`'s condition, `Cx::compare_value`).
    Value,
    /// An operand of a condition's `(A, B)`/`(A ; B)`
    /// (`Cx::compare_condition`).
    Junction,
}

fn cmp_tokens(op: ArithCmp, l: TokenStream, r: TokenStream) -> TokenStream {
    match op {
        ArithCmp::Eq => quote!((#l == #r)),
        ArithCmp::Ne => quote!((#l != #r)),
        ArithCmp::Lt => quote!((#l < #r)),
        ArithCmp::Gt => quote!((#l > #r)),
        ArithCmp::Le => quote!((#l <= #r)),
        ArithCmp::Ge => quote!((#l >= #r)),
    }
}

/// An expectation that evaluates to itself (`found(P)`), as a term built
/// from registers; `None` when evaluating it may do more.
fn ev_as_build(e: &Ev) -> Option<Build> {
    fn copy(b: &Build) -> Build {
        match b {
            Build::Const(t) => Build::Const(*t),
            Build::Reg(r) => Build::Reg(*r),
            Build::Compound(n, args) => Build::Compound(*n, args.iter().map(copy).collect()),
        }
    }
    match e {
        Ev::Built(b) => Some(copy(b)),
        Ev::Value(r) => Some(Build::Reg(*r)),
        Ev::Compound(n, args) => Some(Build::Compound(
            *n,
            args.iter().map(ev_as_build).collect::<Option<_>>()?,
        )),
        _ => None,
    }
}

/// Whether generated code `ts` mentions the identifier `x`.
pub(super) fn mentions(ts: &TokenStream, x: &Ident) -> bool {
    super::pipe::mentions(ts, x) > 0
}

/// Whether `e` is `r<k>.clone()`, a register's clone (no other effect).
fn is_clone_of_reg(e: &TokenStream) -> bool {
    let t: Vec<TokenTree> = e.clone().into_iter().collect();
    matches!(&t[..], [TokenTree::Ident(r), TokenTree::Punct(dot), TokenTree::Ident(c), TokenTree::Group(g)]
        if r.to_string().starts_with('r')
            && dot.as_char() == '.'
            && c == "clone"
            && g.delimiter() == proc_macro2::Delimiter::Parenthesis
            && g.stream().is_empty())
}

/// Whether evaluating the call term gives it back (built from values).
fn inert(b: &Build) -> bool {
    match b {
        Build::Const(_) | Build::Reg(_) => true,
        Build::Compound(name, args) => {
            sitlog_runtime::eval::evaluates_arguments_only(*name, args.len())
                && args.iter().all(inert)
        }
    }
}

/// The output arguments of recursive situation `ix`'s call: the arguments
/// (position, register) that are a fresh variable of the situation, each
/// written once in the call, as a whole argument (`J` in `add(I, 1, J)`),
/// and nothing of the visit sets before the call (no `prog`, not the
/// in_arg's register nor a variable of an in_arg pattern; an evaluated
/// call's, in a DM without locals). A fresh variable written twice (`f(J, J)`) or
/// inside an argument (`f(g(J))`) is none: such a call stays the
/// machine's (its arguments do not convert).
pub(super) fn call_outputs(d: &Dm, ix: usize) -> Vec<(usize, Reg)> {
    let plan = &d.plans[ix];
    let KindPlan::Recursive {
        call, eval_call, ..
    } = &plan.kind
    else {
        return Vec::new();
    };
    let Build::Compound(_, args) = call else {
        return Vec::new();
    };
    // An evaluated call: its outputs only where native code may evaluate
    // it itself (a DM without locals, `call_held`; the variable evaluates
    // to itself).
    if plan.prog.is_some() || (*eval_call && !inert(call) && !d.locals.is_empty()) {
        return Vec::new();
    }
    fn count(b: &Build, r: Reg) -> usize {
        match b {
            Build::Reg(x) => usize::from(*x == r),
            Build::Const(_) => 0,
            Build::Compound(_, args) => args.iter().map(|a| count(a, r)).sum(),
        }
    }
    let in_arg = plan.in_arg.as_ref().map(|(_, _, r)| *r);
    args.iter()
        .enumerate()
        .filter_map(|(k, a)| match a {
            Build::Reg(r)
                if plan
                    .inits
                    .iter()
                    .any(|(x, i)| x == r && matches!(i, Init::Fresh))
                    && in_arg != Some(*r)
                    && plan
                        .in_arg
                        .as_ref()
                        .is_none_or(|(b, _, _)| count(b, *r) == 0)
                    && args.iter().map(|b| count(b, *r)).sum::<usize>() == 1 =>
            {
                Some((k, *r))
            }
            _ => None,
        })
        .collect()
}

/// Whether final situation `k` of DM `d` hands the DM's outputs back in
/// its frame's output slots when its caller is native and passed them as
/// `Ground::OUT`: its `diag_mod` is the DM's head with, at each output
/// parameter, a value computed natively (`Dm::outs`), and at every other
/// position that parameter itself (so unifying it with the call binds the
/// outputs and nothing else, as the term path's `diag_mod` does).
pub(super) fn slot_final(store: &Store, d: &Dm, k: usize) -> bool {
    let plan = &d.plans[k];
    let KindPlan::Final { diag_mod: Some(b) } = &plan.kind else {
        return false;
    };
    // A constant `diag_mod` (`welcome([])`) by its parts (`ground_parts`).
    let parts = super::ground_parts::diag_parts(store, d, b);
    let Build::Compound(name, args) = parts.as_ref().unwrap_or(b) else {
        return false;
    };
    if *name != d.dm.name || args.len() != d.dm.arity {
        return false;
    }
    let outs = d.outs.borrow();
    let mut any = false;
    for (i, a) in args.iter().enumerate() {
        if d.outputs.get(i).is_some_and(Option::is_some) {
            if !outs.get(i).copied().unwrap_or(false) {
                return false;
            }
            any = true;
        } else {
            let own = matches!(a, Build::Reg(r) if plan.inits.iter().any(|(x, init)| x == r && matches!(init, Init::HeadArg(p) if *p == i)));
            if !own {
                return false;
            }
        }
    }
    any
}

/// The type of the callee's output parameter `k` (the slot `out<k>`).
fn output_ty(callee: &Dm, k: usize) -> N<Ty> {
    callee
        .outputs
        .get(k)
        .cloned()
        .flatten()
        .ok_or_else(|| "an output argument of a parameter that is not an output".to_string())
}

/// The output slots of a callee's frame, empty (`out<i>: None`).
fn out_slots_none(callee: &Dm) -> Vec<TokenStream> {
    callee
        .outputs
        .iter()
        .enumerate()
        .filter(|(_, o)| o.is_some())
        .map(|(i, _)| {
            let o = format_ident!("out{}", i);
            quote!(#o: None)
        })
        .collect()
}

/// `code` without its statement `let NAME = ..;` (at its top level) when
/// nothing else in it mentions `NAME`.
fn drop_unread_let(code: TokenStream, name: &str) -> TokenStream {
    use proc_macro2::TokenTree;
    let toks: Vec<TokenTree> = code.clone().into_iter().collect();
    let Some(k) = toks.windows(3).position(|w| {
        matches!(&w[0], TokenTree::Ident(l) if l == "let")
            && matches!(&w[1], TokenTree::Ident(x) if x == name)
            && matches!(&w[2], TokenTree::Punct(p) if p.as_char() == '=')
    }) else {
        return code;
    };
    let Some(end) = toks[k..]
        .iter()
        .position(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == ';'))
        .map(|e| k + e)
    else {
        return code;
    };
    let rest: TokenStream = toks[..k].iter().chain(&toks[end + 1..]).cloned().collect();
    if mentions(&rest, &format_ident!("{}", name)) {
        return code;
    }
    rest
}

/// Whether `ts` names one of `names` (an identifier token, at any depth).
fn mentions_any(ts: &TokenStream, names: &[Ident]) -> bool {
    super::pipe::mentions_of(ts, names) > 0
}

/// An action's value `x` (of type `ty`) taken by the fresh register `dst`
/// (of type `dty`, converted): `let x = value; let r<dst> = x;`, the
/// register then known in `regs`.
fn bind_fresh(
    stmts: &mut Vec<TokenStream>,
    regs: &mut Regs,
    x: &Ident,
    value: TokenStream,
    ty: &Ty,
    dst: Reg,
    dty: Ty,
) -> N<()> {
    let e = coerce(
        &V {
            e: quote!(#x.clone()),
            ty: ty.clone(),
        },
        &dty,
    )?;
    stmts.push(quote!(let #x = #value;));
    let rr = reg(dst);
    stmts.push(quote!(let #rr = #e;));
    regs.insert(dst, (rr, dty));
    Ok(())
}

/// Whether `fill` (a `Fill(p.k[i], &[..])`) reads no variable but
/// `fields`.
fn reads_only(fill: &TokenStream, fields: &[Ident]) -> bool {
    let mut ids = std::collections::BTreeSet::new();
    super::idents(fill, &mut ids);
    ids.iter()
        .all(|i| ["Fill", "p", "k"].contains(&i.as_str()) || fields.iter().any(|f| f == i))
}

/// `code` with its statements `let x = FILL;` (`fill`) dropped and every
/// such `x` named as the first: that name's `let` (to put before `code`)
/// and the code; where there are fewer than two, none and `code`.
pub(super) fn one_fill(
    code: &TokenStream,
    fill: &TokenStream,
) -> (Option<TokenStream>, TokenStream) {
    use proc_macro2::{Group, TokenTree};
    fn drop_lets(ts: &TokenStream, fill: &str, names: &mut Vec<Ident>) -> TokenStream {
        let toks: Vec<TokenTree> = ts.clone().into_iter().collect();
        let mut out = Vec::new();
        let mut k = 0;
        while k < toks.len() {
            if let (TokenTree::Ident(l), Some(TokenTree::Ident(x)), Some(TokenTree::Punct(eq))) =
                (&toks[k], toks.get(k + 1), toks.get(k + 2))
            {
                if l == "let" && eq.as_char() == '=' && eq.spacing() == proc_macro2::Spacing::Alone
                {
                    let end = toks[k + 3..]
                        .iter()
                        .position(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == ';'));
                    if let Some(end) = end {
                        let init: TokenStream = toks[k + 3..k + 3 + end].iter().cloned().collect();
                        if init.to_string() == fill {
                            names.push(x.clone());
                            k += 3 + end + 1;
                            continue;
                        }
                    }
                }
            }
            match &toks[k] {
                TokenTree::Group(g) => {
                    let mut ng = Group::new(g.delimiter(), drop_lets(&g.stream(), fill, names));
                    ng.set_span(g.span());
                    out.push(TokenTree::Group(ng));
                }
                t => out.push(t.clone()),
            }
            k += 1;
        }
        out.into_iter().collect()
    }
    fn rename(ts: &TokenStream, from: &[Ident], to: &Ident) -> TokenStream {
        ts.clone()
            .into_iter()
            .map(|t| match t {
                TokenTree::Ident(i) if from.contains(&i) => TokenTree::Ident(to.clone()),
                TokenTree::Group(g) => {
                    let mut ng = Group::new(g.delimiter(), rename(&g.stream(), from, to));
                    ng.set_span(g.span());
                    TokenTree::Group(ng)
                }
                t => t,
            })
            .collect()
    }
    let mut names = Vec::new();
    let dropped = drop_lets(code, &fill.to_string(), &mut names);
    match names.first() {
        Some(x) if names.len() >= 2 => {
            let x = x.clone();
            (Some(quote!(let #x = #fill;)), rename(&dropped, &names, &x))
        }
        _ => (None, code.clone()),
    }
}

/// An exit arc's recorded way ([`Gen::nat_exit_record`]): its entry's
/// statements, its next situation, the entry and record as one call where
/// it fits, and the entry's terms made where a `TypedRun` call needs them
/// ([`LazyEntry`]).
type ExitRecord = (
    TokenStream,
    TokenStream,
    Option<TokenStream>,
    Option<LazyEntry>,
);

/// An exit arc's entry whose terms a `TypedRun` call makes only where the
/// run records ([`lazy_entry`]): `let ea = (EXP, ACT);` (its expectation
/// an `Of` or a constant, its action a constant), and the id (an atom, or
/// a `Fill` bound first: its name and `let`).
struct LazyEntry {
    pair: TokenStream,
    id: TokenStream,
    id_let: Option<(Ident, TokenStream)>,
}

impl LazyEntry {
    /// `call` of the id and `ea` after the pair's `let` (and the id's,
    /// unless `head` binds the same `Fill` already: that name then);
    /// `None` where a statement would not fit on a line.
    fn stmts(
        &self,
        head: &TokenStream,
        call: impl Fn(&TokenStream) -> TokenStream,
    ) -> Option<TokenStream> {
        let pair = &self.pair;
        let pair = quote!(let ea = #pair;);
        let (id_let, id) = match &self.id_let {
            None => (None, self.id.clone()),
            Some((x, fill)) => match bound_as(head, fill) {
                Some(y) => (None, quote!(#y)),
                None => (Some(quote!(let #x = #fill;)), quote!(#x)),
            },
        };
        let call = call(&id);
        let all: Vec<&TokenStream> = id_let.iter().chain([&pair, &call]).collect();
        all.iter()
            .all(|t| super::fits_at(t, None))
            .then(|| quote!(#id_let #pair #call))
    }
}

/// The name `head` binds to `fill` (`let x = Fill(..);`, a statement of
/// its own at its top level), if any.
fn bound_as(head: &TokenStream, fill: &TokenStream) -> Option<Ident> {
    use proc_macro2::TokenTree;
    let toks: Vec<TokenTree> = head.clone().into_iter().collect();
    let want = fill.to_string();
    for k in 0..toks.len() {
        let (TokenTree::Ident(l), Some(TokenTree::Ident(x)), Some(TokenTree::Punct(eq))) =
            (&toks[k], toks.get(k + 1), toks.get(k + 2))
        else {
            continue;
        };
        if l != "let" || eq.as_char() != '=' {
            continue;
        }
        let end = toks[k + 3..]
            .iter()
            .position(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == ';'))?;
        let init: TokenStream = toks[k + 3..k + 3 + end].iter().cloned().collect();
        if init.to_string() == want {
            return Some(x.clone());
        }
    }
    None
}

/// [`LazyEntry`] of an exit arc's entry: where the expectation is a term
/// made by one `cx.build_of` (then an `Of`) or a constant (its statements
/// `ts` none), the action a constant, the id an atom or one `cx.fill`
/// (then a `Fill`). `None` for any other.
fn lazy_entry(
    ts: &[TokenStream],
    exp: &TokenStream,
    act: &TokenStream,
    id_stmts: &[TokenStream],
    id: &TokenStream,
) -> Option<LazyEntry> {
    if !ts.is_empty() {
        return None;
    }
    // `let act = cx.term(&act0);`: the value, made a term by the call.
    let act = match syn::parse2::<syn::Stmt>(act.clone()) {
        Ok(syn::Stmt::Local(l)) => match l.init.map(|i| *i.expr) {
            Some(syn::Expr::MethodCall(m))
                if m.method == "term" && m.args.len() == 1 && {
                    let r = &m.receiver;
                    quote!(#r).to_string() == "cx"
                } =>
            {
                let v = &m.args[0];
                quote!(#v)
            }
            _ => return None,
        },
        _ if act.to_string().starts_with("let") => return None,
        _ => act.clone(),
    };
    let exp = match syn::parse2::<syn::Expr>(exp.clone()).ok()? {
        syn::Expr::MethodCall(m)
            if m.method == "build_of" && {
                let r = &m.receiver;
                quote!(#r).to_string() == "cx"
            } =>
        {
            let name = m.args.first()?;
            let holes = m.args.get(1)?;
            let holes = super::fill::holes_tuple(&quote!(#holes));
            quote!(Of(#name, #holes))
        }
        e if !mentions(&quote!(#e), &format_ident!("cx")) => quote!(#e),
        _ => return None,
    };
    let (id_let, id) = if id_stmts.is_empty() {
        (None, super::atom_arg(id))
    } else {
        let fill = super::fill_arg(id_stmts, id)?;
        let x = syn::parse2::<Ident>(id.clone()).ok()?;
        (Some((x, fill)), id.clone())
    };
    Some(LazyEntry {
        pair: quote!((#exp, #act)),
        id,
        id_let,
    })
}

/// `exp`, a compound `cx.build(f, &[..])` whose arguments' terms `ts`
/// made just before (`let bN = cx.term(&x);`, each argument once, in
/// order), as one `cx.build_of(f, &[&x, ..])`: the same terms made in the
/// same order (`Cx::build_of` makes each argument's term in turn, a term
/// argument being itself). `None` for another shape, or an argument that
/// calls `cx`.
fn built_of(ts: &[TokenStream], exp: &TokenStream) -> Option<TokenStream> {
    let syn::Expr::MethodCall(m) = syn::parse2::<syn::Expr>(exp.clone()).ok()? else {
        return None;
    };
    let recv = &m.receiver;
    if m.method != "build" || quote!(#recv).to_string() != "cx" || m.args.len() != 2 {
        return None;
    }
    let syn::Expr::Reference(r) = &m.args[1] else {
        return None;
    };
    let syn::Expr::Array(args) = &*r.expr else {
        return None;
    };
    // The terms made before: `bN` and the value it is made of.
    let mut made = Vec::new();
    for t in ts {
        let (x, method, args) = super::cx_let(t)?;
        let [v] = args.as_slice() else {
            return None;
        };
        if method != "term" {
            return None;
        }
        made.push((x, v.clone()));
    }
    let cx = format_ident!("cx");
    let mut next = 0;
    let mut out = Vec::new();
    for a in &args.elems {
        let a = quote!(#a);
        if mentions(&a, &cx) {
            return None;
        }
        match made.iter().position(|(b, _)| *b == a.to_string()) {
            Some(k) if k == next => {
                out.push(made[k].1.clone());
                next += 1;
            }
            Some(_) => return None,
            None => out.push(quote!(&#a)),
        }
    }
    if next != made.len() {
        return None;
    }
    let f = &m.args[0];
    Some(quote!(cx.build_of(#f, &[#(#out),*])))
}

/// The registers of `b`, pushed to `out` (a register met twice, twice).
pub(super) fn build_regs(b: &Build, out: &mut Vec<Reg>) {
    super::built_regs(&Ev::Built(b.clone()), out);
}
