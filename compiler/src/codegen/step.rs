//! Situations that run as code, printed as Rust: each [`SitPlan`] of the
//! [MIR](crate::mir) turned into calls on the runtime's
//! [`Cx`](sitlog_runtime::machine::Cx), step for step what the interpreter
//! does when it runs the same plan (`crate::interp`'s `run`), with no
//! instance built and no arc copied.
//!
//! Which situations run as code, which variables are lazy and where a
//! constant next situation goes are the MIR's decisions, not this
//! module's: here a register of the plan becomes a Rust local `rN`, a
//! frozen constant an element `k[i]` of the program's constants, an atom a field of
//! its `Atoms`, and each step the `Cx` call that performs it. Semantics
//! stay in the runtime.

use super::Gen;
use crate::mir::{Action, ArcPlan, Arcs, Build, Cond, Ev, IdPart, Init, KindPlan, Next, Prog, Reg};
use crate::mir::{Mir, SitPlan};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::{Term, Value};
use sitlog_syntax::{atoms, Atom};
use std::collections::BTreeSet;

/// The code of one situation that runs as code.
pub(super) struct SituationCode {
    pub run: TokenStream,
    /// For a recursive situation: its exit arcs.
    pub exit: Option<TokenStream>,
}

fn reg(r: Reg) -> Ident {
    format_ident!("r{}", r)
}

/// Statements being written for one generated function, and its
/// temporaries' counter.
pub(super) struct Body {
    pub(super) stmts: Vec<TokenStream>,
    next_tmp: usize,
}

impl Body {
    pub(super) fn new() -> Body {
        Body {
            stmts: Vec::new(),
            next_tmp: 0,
        }
    }

    fn tmp(&mut self) -> Ident {
        let t = format_ident!("t{}", self.next_tmp);
        self.next_tmp += 1;
        t
    }

    /// A nested block of statements sharing the counter.
    fn nested<T>(&mut self, f: impl FnOnce(&mut Body) -> T) -> (Vec<TokenStream>, T) {
        let mut inner = Body {
            stmts: Vec::new(),
            next_tmp: self.next_tmp,
        };
        let v = f(&mut inner);
        self.next_tmp = inner.next_tmp;
        (inner.stmts, v)
    }
}

impl Gen<'_> {
    /// Registers the frozen terms the plans use on their own as constants
    /// (ground compounds, big integers), so that code refers to them.
    pub(super) fn collect_plans(&mut self, mir: &Mir) {
        let mut terms = Vec::new();
        for plan in mir.dms.iter().flatten().flatten() {
            plan.constants(&mut terms);
        }
        for t in terms {
            if matches!(self.store.value(t), Value::Compound(..) | Value::BigInt(_)) {
                self.constant(t);
            } else if let Some(a) = self.store.atom_of(t) {
                self.atom(a);
            }
        }
    }

    pub(super) fn atom_expr(&self, a: Atom) -> TokenStream {
        if a == atoms::DOT {
            return quote!(atoms::DOT);
        }
        let id = &self.atoms[self.atom_ix[&a]].1;
        quote!(a.#id)
    }

    /// A frozen term: an immediate, a constant of the program, or (a
    /// compound the program did not register) built here.
    fn frozen(&self, t: Term, b: &mut Body) -> TokenStream {
        if let Some(e) = self.leaf(t, &Default::default(), false) {
            return e;
        }
        let mut stmts = Vec::new();
        let value = self.build_into(t, &Default::default(), false, &mut b.next_tmp, &mut stmts);
        for (tmp, e) in stmts {
            b.stmts
                .push(quote!(let #tmp = { let store = cx.store(); #e };));
        }
        value
    }

    /// The term `x` builds (not evaluated).
    pub(super) fn build_code(&self, x: &Build, b: &mut Body) -> TokenStream {
        match x {
            Build::Const(t) => self.frozen(*t, b),
            Build::Reg(r) => {
                let r = reg(*r);
                quote!(#r)
            }
            Build::Compound(name, args) => {
                let args: Vec<TokenStream> = args.iter().map(|a| self.build_code(a, b)).collect();
                let f = self.atom_expr(*name);
                let x = b.tmp();
                b.stmts
                    .push(quote!(let #x = cx.compound(#f, &[#(#args),*]);));
                quote!(#x)
            }
        }
    }

    /// The value of `e` evaluated in L.
    pub(super) fn ev_code(&self, e: &Ev, arc: &TokenStream, b: &mut Body) -> TokenStream {
        match e {
            Ev::Value(r) => {
                let r = reg(*r);
                let x = b.tmp();
                b.stmts.push(quote!(let #x = cx.value(#r, #arc)?;));
                quote!(#x)
            }
            Ev::Built(t) => self.build_code(t, b),
            Ev::Eval(t) => {
                let t = self.build_code(t, b);
                let x = b.tmp();
                b.stmts.push(quote!(let #x = cx.eval(#t, #arc)?;));
                quote!(#x)
            }
            Ev::If(c, then, other) => {
                let c = self.cond_code(c, arc, b);
                let (then_stmts, then_v) = b.nested(|b| self.ev_code(then, arc, b));
                let (other_stmts, other_v) = b.nested(|b| self.ev_code(other, arc, b));
                let x = b.tmp();
                b.stmts.push(quote! {
                    let #x = if #c { #(#then_stmts)* #then_v } else { #(#other_stmts)* #other_v };
                });
                quote!(#x)
            }
            // `when/3`: both branches evaluated, in order, after the test.
            Ev::Pick(c, then, other) => {
                let c = self.cond_code(c, arc, b);
                let then = self.ev_code(then, arc, b);
                let other = self.ev_code(other, arc, b);
                let x = b.tmp();
                b.stmts
                    .push(quote!(let #x = if #c { #then } else { #other };));
                quote!(#x)
            }
            Ev::VarOpFresh { op, name, dst } => {
                let (op, name, dst) = (self.atom_expr(*op), self.atom_expr(*name), reg(*dst));
                b.stmts
                    .push(quote!(#dst = cx.var_op_fresh(#op, #name, #arc)?;));
                quote!(#dst)
            }
            Ev::VarOp { op, name, arg } => {
                let arg = self.build_code(arg, b);
                let (op, name) = (self.atom_expr(*op), self.atom_expr(*name));
                let x = b.tmp();
                b.stmts
                    .push(quote!(let #x = cx.var_op(#op, #name, #arg, #arc)?;));
                quote!(#x)
            }
            Ev::IsFresh { expr, dst } => {
                let expr = self.build_code(expr, b);
                let dst = reg(*dst);
                b.stmts.push(quote!(#dst = cx.is(None, #expr, #arc)?;));
                quote!(#dst)
            }
            Ev::BindFresh { expr, dst } => {
                let expr = self.build_code(expr, b);
                let dst = reg(*dst);
                b.stmts.push(quote!(#dst = #expr;));
                quote!(#dst)
            }
            Ev::Is { lhs, expr } => {
                let expr = self.build_code(expr, b);
                let lhs = self.build_code(lhs, b);
                let x = b.tmp();
                b.stmts
                    .push(quote!(let #x = cx.is(Some(#lhs), #expr, #arc)?;));
                quote!(#x)
            }
            Ev::Compound(name, args) => {
                let values: Vec<TokenStream> =
                    args.iter().map(|a| self.ev_code(a, arc, b)).collect();
                let f = self.atom_expr(*name);
                let x = b.tmp();
                b.stmts
                    .push(quote!(let #x = cx.compound(#f, &[#(#values),*]);));
                quote!(#x)
            }
        }
    }

    /// The `bool` of a conditional's condition.
    fn cond_code(&self, c: &Cond, arc: &TokenStream, b: &mut Body) -> TokenStream {
        let x = match c {
            Cond::Arith(op, l, r) => {
                let l = self.ev_code(l, arc, b);
                let r = self.ev_code(r, arc, b);
                let op = format_ident!("{}", format!("{op:?}"));
                let x = b.tmp();
                b.stmts.push(quote! {
                    let #x = cx.arith_condition(::sitlog_runtime::ArithCmp::#op, #l, #r, #arc)?;
                });
                x
            }
            Cond::Other(t) => {
                let t = self.build_code(t, b);
                let x = b.tmp();
                b.stmts.push(quote!(let #x = cx.condition(#t, #arc)?;));
                x
            }
            Cond::Cmp(op, l, r) => {
                let lw = self.build_code(l, b);
                let rw = self.build_code(r, b);
                let (l, r, x) = (b.tmp(), b.tmp(), b.tmp());
                let op = format_ident!("{}", format!("{op:?}"));
                b.stmts.push(quote! {
                    let #l = cx.value(#lw, #arc)?;
                    let #r = cx.value(#rw, #arc)?;
                    let #x = cx.compare_value(::sitlog_runtime::ArithCmp::#op, [#lw, #rw], [#l, #r], #arc)?;
                });
                x
            }
            Cond::And(l, r) | Cond::Or(l, r) => {
                // Both operands computed, left first (D-35), then combined.
                let l = self.junction_leaf_code(l, arc, b);
                let r = self.junction_leaf_code(r, arc, b);
                let x = b.tmp();
                b.stmts.push(if matches!(c, Cond::And(..)) {
                    quote!(let #x = #l && #r;)
                } else {
                    quote!(let #x = #l || #r;)
                });
                x
            }
        };
        quote!(#x)
    }

    /// An operand of [`Cond::And`]/[`Cond::Or`] (`mir::lower`): whether
    /// its value is `true` (`Cx::value_holds` on it as written), its error
    /// the condition's; a type test called as a goal (`Cx::condition`).
    fn junction_leaf_code(&self, c: &Cond, arc: &TokenStream, b: &mut Body) -> TokenStream {
        match c.written() {
            // A type test holds where its goal does (`mir::is_type_test`).
            _ if matches!(c, Cond::Other(t) if crate::mir::is_type_test(t)) => {
                self.cond_code(c, arc, b)
            }
            Some(w) if !matches!(c, Cond::And(..) | Cond::Or(..)) => {
                let t = self.build_code(&w, b);
                let x = b.tmp();
                b.stmts.push(quote!(let #x = cx.value_holds(#t, #arc)?;));
                quote!(#x)
            }
            _ => self.cond_code(c, arc, b),
        }
    }

    /// `(Term, Option<SitIx>)`: a next situation's value and, when known,
    /// its index.
    pub(super) fn next_code(&self, n: &Next, arc: &TokenStream, b: &mut Body) -> TokenStream {
        match n {
            Next::Static(t, ix) => {
                let v = self.frozen(*t, b);
                match ix {
                    Some(ix) => {
                        let ix = Literal::u32_unsuffixed(*ix);
                        quote!((#v, Some(#ix)))
                    }
                    None => quote!((#v, None)),
                }
            }
            Next::If(c, then, other) => {
                let c = self.cond_code(c, arc, b);
                let (then_stmts, then_v) = b.nested(|b| self.next_code(then, arc, b));
                let (other_stmts, other_v) = b.nested(|b| self.next_code(other, arc, b));
                let x = b.tmp();
                b.stmts.push(quote! {
                    let #x = if #c { #(#then_stmts)* #then_v } else { #(#other_stmts)* #other_v };
                });
                quote!(#x)
            }
            Next::Eval(e) => {
                let v = self.ev_code(e, arc, b);
                quote!((#v, None))
            }
        }
    }

    /// The code of `select_compiled` for a situation with a compound id:
    /// its constant arguments unified with `value`'s.
    pub(super) fn select_code(&self, plan: &SitPlan) -> Option<TokenStream> {
        if let Some(pat) = &plan.pattern {
            if self.linear(pat.term) {
                // Matched natively, argument by argument; a variable of the
                // value where the pattern has structure is bound to a fresh
                // copy of that part, as unifying with a copy would.
                let mut n = 0;
                let body = self.match_pattern(pat.term, quote!(value), &mut n);
                let k = Self::uses(&body).1.then(|| quote!(let k = &p.k;));
                return Some(quote!(#k #body true));
            }
            // As an instance's id: a fresh copy of the pattern unified with the value.
            let (fresh, vars) = self.fresh_vars(&[pat.term]);
            let built = self.build(pat.term, &vars, false, &mut 0);
            let stmts = built.stmts.iter().map(|(n, e)| quote!(let #n = #e;));
            let v = built.value;
            let body = quote! {
                #(#fresh)*
                #(#stmts)*
                store.unify(value, #v)
            };
            let k = Self::uses(&body).1.then(|| quote!(let k = &p.k;));
            return Some(quote!(#k #body));
        }
        if plan.select.is_empty() {
            return None;
        }
        let checks = plan.select.iter().map(|&(i, c)| {
            let c = self.build_into(c, &Default::default(), false, &mut 0, &mut Vec::new());
            let i = Literal::usize_unsuffixed(i);
            quote! {
                let x = store.args(value)[#i];
                if !store.unify(x, #c) {
                    return false;
                }
            }
        });
        Some(quote!(#(#checks)* true))
    }

    /// Whether no variable occurs twice in `t`.
    fn linear(&self, t: Term) -> bool {
        let mut seen = std::collections::HashSet::new();
        let mut stack = vec![t];
        while let Some(u) = stack.pop() {
            match self.store.value(u) {
                Value::Var(v) if !seen.insert(v.index()) => return false,
                Value::Compound(_, args) => stack.extend(args.iter().copied()),
                _ => {}
            }
        }
        true
    }

    /// Statements matching the value `x` against the linear pattern `pat`
    /// (`return false` when it cannot unify), each part as unifying with a
    /// fresh copy of the pattern would: a variable of the pattern takes
    /// anything, a ground part is unified, a compound part is taken apart
    /// when the value has that functor and arity, and bound to a fresh copy
    /// of itself when the value is a variable.
    fn match_pattern(&self, pat: Term, x: TokenStream, n: &mut usize) -> TokenStream {
        match self.store.value(pat) {
            Value::Var(_) => quote!(),
            _ if self.store.is_ground(pat) => {
                let c = self.build_into(pat, &Default::default(), false, &mut 0, &mut Vec::new());
                quote! {
                    if !store.unify(#x, #c) {
                        return false;
                    }
                }
            }
            Value::Compound(name, args) => {
                let y = format_ident!("y{}", *n);
                *n += 1;
                let (fresh, vars) = self.fresh_vars(&[pat]);
                let built = self.build(pat, &vars, false, &mut 0);
                let stmts = built.stmts.iter().map(|(n, e)| quote!(let #n = #e;));
                let copy = built.value;
                let f = self.atom_expr(name);
                let arity = Literal::usize_unsuffixed(args.len());
                let parts: Vec<Ident> = (0..args.len())
                    .map(|_| {
                        let p = format_ident!("y{}", *n);
                        *n += 1;
                        p
                    })
                    .collect();
                let ixs = (0..args.len()).map(Literal::usize_unsuffixed);
                let inner: Vec<TokenStream> = args
                    .iter()
                    .zip(&parts)
                    .map(|(&a, p)| self.match_pattern(a, quote!(#p), n))
                    .collect();
                quote! {
                    let #y = store.deref(#x);
                    if store.is_var(#y) {
                        #(#fresh)*
                        #(#stmts)*
                        let _ = store.unify(#y, #copy);
                    } else {
                        let Some(args) = store.compound_args(#y, #f, #arity) else {
                            return false;
                        };
                        let [#(#parts),*] = [#(args[#ixs]),*];
                        #(#inner)*
                    }
                }
            }
            _ => unreachable!("atomic terms are ground"),
        }
    }

    /// The code of a situation's plan: a visit, and for a recursive one its
    /// exit arcs.
    pub(super) fn situation_code(
        &self,
        plan: &SitPlan,
        run_name: &Ident,
        exit_name: &Ident,
    ) -> SituationCode {
        let none = quote!(None);
        let mut b = Body::new();
        // A compound id: the value that selected the situation, else built
        // with fresh variables (initial situation).
        if let Some(parts) = &plan.compound_id {
            let mut fresh = Vec::new();
            let mut values = Vec::new();
            for part in parts {
                match part {
                    IdPart::Fresh(r) => {
                        let r = reg(*r);
                        fresh.push(quote!(#r = cx.var();));
                        values.push(quote!(#r));
                    }
                    IdPart::Const(t) => values.push(self.frozen(*t, &mut b)),
                }
            }
            let f = self.atom_expr(plan.id.0);
            b.stmts.push(quote! {
                let id = match cx.selected() {
                    Some(value) => value,
                    None => {
                        #(#fresh)*
                        let id = cx.compound(#f, &[#(#values),*]);
                        cx.set_id(id);
                        id
                    }
                };
            });
        }
        if let Some(pat) = &plan.pattern {
            let fresh = pat.fresh.iter().map(|&r| {
                let r = reg(r);
                quote!(#r = cx.var();)
            });
            let (stmts, v) = b.nested(|b| self.build_code(&pat.build, b));
            b.stmts.push(quote! {
                let id = match cx.selected() {
                    Some(value) => value,
                    None => {
                        #(#fresh)*
                        #(#stmts)*
                        let id = #v;
                        cx.set_id(id);
                        id
                    }
                };
            });
        }
        for (r, init) in &plan.inits {
            let r = reg(*r);
            let init = match init {
                Init::IdArg(i) => {
                    let i = Literal::usize_unsuffixed(*i);
                    quote!(cx.arg(id, #i))
                }
                Init::IdPath(path) => {
                    let mut t = quote!(id);
                    for &i in path.iter() {
                        let i = Literal::usize_unsuffixed(i);
                        t = quote!(cx.arg(#t, #i));
                    }
                    t
                }
                Init::HeadArg(i) => {
                    let i = Literal::usize_unsuffixed(*i);
                    quote!(cx.head_arg(#i))
                }
                Init::HeadPath(i, path) => {
                    let i = Literal::usize_unsuffixed(*i);
                    let path = path.iter().map(|&k| Literal::usize_unsuffixed(k));
                    quote!(cx.head_part(#i, &[#(#path),*]))
                }
                // A variable in_arg takes the pipe value (D-8).
                Init::Pipe => quote!(cx.pipe()),
                Init::Fresh => quote!(cx.var()),
            };
            b.stmts.push(quote!(#r = #init;));
        }
        for &(r, i) in &plan.links {
            let (r, i) = (reg(r), Literal::usize_unsuffixed(i));
            b.stmts.push(quote!(cx.link_head_arg(#r, #i);));
        }
        let mut links = Vec::new();
        if let Some((pattern, unify, r)) = &plan.in_arg {
            let pattern = self.build_code(pattern, &mut b);
            let r = reg(*r);
            b.stmts.push(quote!(#r = #pattern;));
            if *unify {
                b.stmts.push(quote!(cx.in_arg(#r)?;));
            }
            links.push(quote!(Some(#r)));
        }
        if let Some((o, r)) = &plan.out_arg {
            let o = self.build_code(o, &mut b);
            let r = reg(*r);
            b.stmts.push(quote!(#r = #o;));
            links.push(quote!(Some(#r)));
        }
        match &plan.prog {
            None => {}
            // Its value is not used: a list's elements are evaluated, not gathered.
            Some(Prog::InPlace(parts)) => {
                for part in parts {
                    let v = self.ev_code(part, &none, &mut b);
                    b.stmts.push(quote!(let _ = #v;));
                }
            }
            Some(Prog::Copy(p)) => {
                let p = self.build_code(p, &mut b);
                b.stmts.push(quote!(cx.prog(#p, &[#(#links),*])?;));
            }
        }
        let sig = quote!(cx: &mut Cx<'_, '_, super::Program>);
        let result = quote!(Result<Step, RunError>);
        let mut exit = None;
        match &plan.kind {
            KindPlan::Final { diag_mod } => {
                let out = match &plan.out_arg {
                    Some((_, r)) => {
                        let r = reg(*r);
                        quote!(Some(#r))
                    }
                    None => none.clone(),
                };
                b.stmts.push(quote!(cx.final_out_arg(#out)?;));
                if let Some(d) = diag_mod {
                    let d = self.build_code(d, &mut b);
                    b.stmts.push(quote!(cx.diag_mod(#d)?;));
                }
                let empty = quote!(Term::atom(atoms::EMPTY));
                b.stmts.push(quote!(cx.record(#empty, #empty, None);));
                b.stmts.push(quote!(Ok(Step::Final)));
            }
            KindPlan::Perceptual(arcs) => self.arcs_code(arcs, false, &mut b),
            KindPlan::Recursive {
                call,
                eval_call,
                saved,
                exit: exit_arcs,
            } => {
                let e = self.build_code(call, &mut b);
                if *eval_call {
                    b.stmts.push(quote!(let call = cx.embedded_dm(#e)?;));
                } else {
                    // Evaluating a constant call changes nothing.
                    b.stmts.push(quote!(let call = #e;));
                }
                let saved_regs: Vec<Ident> = saved.iter().map(|&r| reg(r)).collect();
                let saved_value = if saved.is_empty() {
                    quote!(Term::NIL)
                } else {
                    quote!(cx.compound(atoms::DOT, &[#(#saved_regs),*]))
                };
                b.stmts.push(quote! {
                    let saved = #saved_value;
                    Ok(Step::Call { call, saved })
                });
                // The exit arcs: the situation's variables back from `saved`.
                let mut e = Body::new();
                for (n, r) in saved_regs.iter().enumerate() {
                    let n = Literal::usize_unsuffixed(n);
                    e.stmts.push(quote!(#r = cx.arg(saved, #n);));
                }
                self.arcs_code(exit_arcs, true, &mut e);
                exit = Some(wrap(
                    quote! {
                        fn #exit_name(
                            p: &super::Program,
                            saved: Term,
                            final_id: Term,
                            #sig,
                        ) -> #result
                    },
                    e.stmts,
                ));
            }
        }
        SituationCode {
            run: wrap(
                quote!(fn #run_name(p: &super::Program, #sig) -> #result),
                b.stmts,
            ),
            exit,
        }
    }

    /// The arcs of a perceptual situation, or the exit arcs of a recursive
    /// one: fresh and imported variables, expectations, the choice, then
    /// the chosen arc's action, next situation, out_arg, diag_mod and
    /// history entry.
    fn arcs_code(&self, a: &Arcs, exit: bool, b: &mut Body) {
        // Each arc's variables: imported copies of the situation's, fresh otherwise (D-11).
        for (i, arc) in a.arcs.iter().enumerate() {
            for &r in &arc.fresh {
                let r = reg(r);
                b.stmts.push(quote!(#r = cx.var();));
            }
            if !arc.import_from.is_empty() {
                let from: Vec<Ident> = arc.import_from.iter().map(|&r| reg(r)).collect();
                let to: Vec<Ident> = (0..arc.import_from.len())
                    .map(|n| reg(arc.import_at + n as Reg))
                    .collect();
                let tmp = format_ident!("imports{}", i);
                b.stmts.push(quote! {
                    let mut #tmp = [#(#from),*];
                    cx.import(&mut #tmp);
                    [#(#to),*] = #tmp;
                });
            }
        }
        // Expectations, with variable updates discarded (D-12) unless none can make one.
        let exps: Vec<Ident> = (0..a.arcs.len()).map(|i| reg(a.exps + i as Reg)).collect();
        let (exp_stmts, values) = b.nested(|b| {
            a.arcs
                .iter()
                .enumerate()
                .map(|(i, arc)| {
                    let ix = Literal::usize_unsuffixed(i);
                    self.ev_code(&arc.expectation, &quote!(Some(#ix)), b)
                })
                .collect::<Vec<_>>()
        });
        if a.pure {
            b.stmts.extend(exp_stmts);
            for (r, v) in exps.iter().zip(&values) {
                b.stmts.push(quote!(#r = #v;));
            }
        } else {
            b.stmts.push(quote! {
                cx.save_vars();
                let expectations = (|| -> Result<_, RunError> {
                    #(#exp_stmts)*
                    Ok([#(#values),*])
                })();
                cx.restore_vars();
                [#(#exps),*] = expectations?;
            });
        }
        if a.always_first {
            // The neutral rule on `[empty : A => N]` always takes the arc (D-14).
            b.stmts.push(quote!(let chosen = 0usize;));
        } else {
            b.stmts.push(quote!(cx.set_expectations(&[#(#exps),*]);));
            if exit {
                b.stmts
                    .push(quote!(let chosen = cx.choose_exit(final_id)?;));
            } else {
                let ty = self.build_code(&a.type_term, b);
                b.stmts.push(quote! {
                    let Some(chosen) = cx.choose(#ty)? else {
                        return Ok(Step::Unmet { type_term: #ty });
                    };
                });
            }
        }
        let mut match_arms = Vec::new();
        for (i, arc) in a.arcs.iter().enumerate() {
            let (stmts, ()) = b.nested(|b| self.arc_code(arc, i, &exps[i], b));
            let ix = Literal::usize_unsuffixed(i);
            match_arms.push(quote!(#ix => { #(#stmts)* }));
        }
        b.stmts.push(quote! {
            match chosen {
                #(#match_arms)*
                _ => unreachable!("the machine chose an arc of this situation"),
            }
        });
    }

    /// The chosen arc `i`: its action, next situation, out_arg, diag_mod,
    /// history entry, and where the machine goes.
    fn arc_code(&self, arc: &ArcPlan, i: usize, expectation: &Ident, b: &mut Body) {
        let ix = Literal::usize_unsuffixed(i);
        let at = quote!(Some(#ix));
        match &arc.action {
            // A list of actions, written out: its elements evaluated and
            // performed in order; the list itself is built only for the history.
            Action::List { items, regs } => {
                let values: Vec<Ident> = (0..items.len()).map(|n| reg(*regs + n as Reg)).collect();
                for (item, r) in items.iter().zip(&values) {
                    let v = self.ev_code(item, &at, b);
                    b.stmts.push(quote!(#r = #v;));
                }
                b.stmts.push(quote! {
                    cx.perform_each(&[#(#values),*], #at)?;
                    let action = if cx.records() {
                        cx.store().list(&[#(#values),*])
                    } else {
                        Term::NIL
                    };
                });
            }
            Action::One(e) => {
                let v = self.ev_code(e, &at, b);
                b.stmts.push(quote!(let action = #v;));
                b.stmts.push(quote!(cx.perform(action, #at)?;));
            }
        }
        let next = self.next_code(&arc.next, &at, b);
        b.stmts.push(quote!(let (next, target) = #next;));
        if let Some(o) = &arc.out_arg {
            let o = self.ev_code(o, &at, b);
            b.stmts.push(quote!(cx.out_value(#o);));
        }
        if let Some(d) = &arc.diag_mod {
            let d = self.build_code(d, b);
            b.stmts.push(quote!(cx.diag_mod(#d)?;));
        }
        b.stmts.push(quote! {
            cx.record(#expectation, action, Some(next));
            cx.go(next, target, #at)
        });
    }
}

/// The registers a body uses (`r0`, `r1`, ...), in order.
pub(super) fn registers(body: &TokenStream) -> BTreeSet<u32> {
    fn walk(ts: TokenStream, out: &mut BTreeSet<u32>) {
        for tt in ts {
            match tt {
                proc_macro2::TokenTree::Group(g) => walk(g.stream(), out),
                proc_macro2::TokenTree::Ident(i) => {
                    let s = i.to_string();
                    if let Some(n) = s.strip_prefix('r').and_then(|d| d.parse().ok()) {
                        out.insert(n);
                    }
                }
                _ => {}
            }
        }
    }
    let mut out = BTreeSet::new();
    walk(body.clone(), &mut out);
    out
}

/// A function from its signature and body statements, with the `a`/`k`
/// bindings and the registers its body uses.
fn wrap(signature: TokenStream, body: Vec<TokenStream>) -> TokenStream {
    let body = quote!(#(#body)*);
    let prelude = Gen::prelude(&body);
    let (body, first) = declared_at_first_set(body);
    let regs = registers(&body)
        .into_iter()
        .filter(|r| !first.contains(r))
        .map(reg);
    quote!(#signature {
        #prelude
        #(let mut #regs = Term::NIL;)*
        #body
    })
}

/// `body` with each register whose first mention is a statement of its
/// own at the top of the body, `rN = EXPR;`, declared there (`let mut rN =
/// EXPR;`), and those registers; the others are declared before the body
/// (set in branches, or read first).
fn declared_at_first_set(body: TokenStream) -> (TokenStream, BTreeSet<u32>) {
    use proc_macro2::{Spacing, TokenTree};
    let reg_of = |tt: &TokenTree| match tt {
        TokenTree::Ident(i) => i
            .to_string()
            .strip_prefix('r')
            .and_then(|d| d.parse::<u32>().ok()),
        _ => None,
    };
    // The top-level statements, each up to and with its `;` (a statement
    // without one, a block, is part of the next).
    let mut stmts: Vec<Vec<TokenTree>> = vec![Vec::new()];
    for tt in body {
        let end = matches!(&tt, TokenTree::Punct(p) if p.as_char() == ';');
        stmts.last_mut().expect("one statement at least").push(tt);
        if end {
            stmts.push(Vec::new());
        }
    }
    let mut seen = BTreeSet::new();
    let mut first = BTreeSet::new();
    let mut out = TokenStream::new();
    for st in stmts {
        let used = registers(&st.iter().cloned().collect());
        let set = match st.as_slice() {
            [r, TokenTree::Punct(eq), rest @ .., TokenTree::Punct(semi)]
                if eq.as_char() == '='
                    && eq.spacing() == Spacing::Alone
                    && semi.as_char() == ';'
                    && !rest.is_empty() =>
            {
                reg_of(r).filter(|n| {
                    !seen.contains(n) && !registers(&rest.iter().cloned().collect()).contains(n)
                })
            }
            _ => None,
        };
        if let Some(n) = set {
            first.insert(n);
            let rest: TokenStream = st[2..].iter().cloned().collect();
            out.extend(quote!(let mut));
            out.extend(std::iter::once(st[0].clone()));
            out.extend(quote!(=));
            out.extend(rest);
        } else {
            out.extend(st);
        }
        seen.extend(used);
    }
    (out, first)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_register_is_declared_where_first_set_only_at_the_top_and_before_any_read() {
        let body = quote! {
            r1 = cx.var();
            cx.f(r2);
            r2 = r1;
            if c { r3 = x; }
            r3 = y;
            r4 = cx.g(r4);
            r1 = z;
        };
        let (out, first) = declared_at_first_set(body);
        assert_eq!(first.into_iter().collect::<Vec<_>>(), vec![1]);
        let want = quote! {
            let mut r1 = cx.var();
            cx.f(r2);
            r2 = r1;
            if c { r3 = x; }
            r3 = y;
            r4 = cx.g(r4);
            r1 = z;
        };
        assert_eq!(out.to_string(), want.to_string());
    }
}
