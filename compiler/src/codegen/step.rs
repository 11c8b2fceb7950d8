//! Situations compiled to code: what a visit of a situation does, as Rust
//! calls on the runtime's [`Cx`](sitlog_runtime::machine::Cx), with no
//! instance built and no arc copied.
//!
//! A situation is compiled when its id and type are atoms and its DM's head
//! parameters are distinct variables (so selecting it is comparing atoms and
//! its head needs no unification); any other situation is instantiated by
//! the machine as the interpreter does. Compiled code keeps the
//! interpreter's order of steps; what it saves is the work whose result is
//! known when the program is compiled:
//! - constants (ground terms L leaves unchanged) are built once, at start;
//! - an arc's variables are fresh variables, and the situation's variables
//!   it shares are imported by one joint copy only when a value is not
//!   atomic (D-11);
//! - variable updates are saved and restored around the expectations only
//!   when an expectation can make one (D-12);
//! - `get`/`set`/`inc`, conditionals (arithmetic conditions inline) and
//!   compounds of plain functors are evaluated in place; anything else goes
//!   to the runtime's evaluator;
//! - a constant next situation is resolved to its index (D-21), so the
//!   machine jumps to it without selecting.
//!
//! (One file over 800 lines: it is one lowering of a visit, step by step,
//! in the order the visit runs; split, the order would no longer read top
//! to bottom.)

use super::{none_marker, Gen};
use crate::ir::{IrDm, IrSituation};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::machine::Kind;
use sitlog_runtime::{eval, ArithCmp, Term, Value};
use sitlog_syntax::{atoms, Atom};
use std::collections::{HashMap, HashSet};

/// Field positions in a situation template (see `ir`).
const HEAD: usize = 0;
const ID: usize = 1;
const TYPE: usize = 2;
const IN_ARG: usize = 3;
const OUT_ARG: usize = 4;
const PROG: usize = 5;
const EMBEDDED_DM: usize = 6;
const DIAG_MOD: usize = 7;
const ARCS: usize = 8;

/// The code of one compiled situation.
pub(super) struct SituationCode {
    pub run: TokenStream,
    /// For a recursive situation: its exit arcs.
    pub exit: Option<TokenStream>,
}

/// Local names and fresh-name counter of one generated function.
struct Scope {
    vars: HashMap<u32, Ident>,
    /// Fresh variables not made yet: their first occurrence is the argument
    /// of a `get` or `inc`, whose value they take without being made.
    lazy: HashSet<u32>,
    next_tmp: usize,
}

impl Scope {
    fn tmp(&mut self) -> Ident {
        let t = format_ident!("t{}", self.next_tmp);
        self.next_tmp += 1;
        t
    }
}

impl Gen<'_> {
    /// The principal functor of the situation's id when it is compiled:
    /// an atom, or a compound whose arguments are distinct variables (not
    /// DM parameters) or atomic constants; its type an atom; its DM's head
    /// parameters distinct variables.
    pub(super) fn compiled_id(&self, dm: &IrDm, s: &IrSituation) -> Option<(Atom, usize)> {
        let f = self.store.args(s.template);
        self.store.atom_of(f[TYPE])?;
        if s.kind == Kind::Recursive && self.store.atom_of(f[EMBEDDED_DM]) == Some(none_marker()) {
            return None;
        }
        let mut seen = HashSet::new();
        for &a in self.store.args(dm.head) {
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

    /// The code of `select_compiled` for a compiled situation with a
    /// compound id: its constant arguments unified with `value`'s.
    pub(super) fn select_code(&self, s: &IrSituation) -> Option<TokenStream> {
        let id = self.store.args(s.template)[ID];
        let Value::Compound(_, args) = self.store.value(id) else {
            return None;
        };
        let mut checks = Vec::new();
        for (i, &arg) in args.iter().enumerate() {
            if matches!(self.store.value(arg), Value::Var(_)) {
                continue;
            }
            let c = self.build_into(arg, &HashMap::new(), false, &mut 0, &mut Vec::new());
            let i = Literal::usize_unsuffixed(i);
            checks.push(quote! {
                let x = store.args(value)[#i];
                if !store.unify(x, #c) {
                    return false;
                }
            });
        }
        if checks.is_empty() {
            return None;
        }
        Some(quote!(#(#checks)* true))
    }

    /// Where a constant next situation `name` goes: the index of the first
    /// situation whose id unifies with it, when that one is compiled.
    fn static_target(&self, dm: &IrDm, name: Atom) -> Option<u32> {
        for (i, s) in dm.situations.iter().enumerate() {
            let id = self.store.args(s.template)[ID];
            match self.store.value(id) {
                Value::Var(_) => return None,
                Value::Atom(a) if a == name => {
                    return self.compiled_id(dm, s).map(|_| i as u32);
                }
                Value::Compound(..) => {}
                _ => {}
            }
        }
        None
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

    pub(super) fn atom_expr(&self, a: Atom) -> TokenStream {
        let id = &self.atoms[self.atom_ix[&a]].1;
        quote!(a.#id)
    }

    pub(super) fn atom_term(&self, a: Atom) -> TokenStream {
        let id = &self.atoms[self.atom_ix[&a]].1;
        quote!(::sitlog_runtime::Term::atom(a.#id))
    }

    /// Statements building `t` (not evaluated) from the scope's variables.
    fn build_cx(&self, t: Term, scope: &mut Scope, out: &mut Vec<TokenStream>) -> TokenStream {
        let mut stmts = Vec::new();
        let value = self.build_into(t, &scope.vars, false, &mut scope.next_tmp, &mut stmts);
        for (tmp, e) in stmts {
            out.push(quote!(let #tmp = { let store = cx.store(); #e };));
        }
        value
    }

    /// Whether evaluating `t` gives `t` back with no effect: no construct of
    /// L in it and, when `vars_inert`, no variable (a bound one may hold one).
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

    /// Statements evaluating `t` in L; the expression of its value.
    fn eval_cx(
        &self,
        t: Term,
        arc: &TokenStream,
        scope: &mut Scope,
        out: &mut Vec<TokenStream>,
    ) -> TokenStream {
        match self.store.value(t) {
            Value::Var(v) => {
                let id = scope.vars[&v.index()].clone();
                let x = scope.tmp();
                out.push(quote!(let #x = cx.value(#id, #arc)?;));
                return quote!(#x);
            }
            Value::Compound(..) => {}
            _ => return self.build_cx(t, scope, out),
        }
        let Value::Compound(name, args) = self.store.value(t) else {
            unreachable!()
        };
        if self.store.is_ground(t) {
            let k = self.build_cx(t, scope, out);
            if self.inert(t, true) {
                return k;
            }
            let x = scope.tmp();
            out.push(quote!(let #x = cx.eval(#k, #arc)?;));
            return quote!(#x);
        }
        if let Some((cond, then, other)) = eval::conditional(self.store, t) {
            let c = self.condition_cx(cond, arc, scope, out);
            let mut then_stmts = Vec::new();
            let then_v = self.eval_cx(then, arc, scope, &mut then_stmts);
            let mut other_stmts = Vec::new();
            let other_v = self.eval_cx(other, arc, scope, &mut other_stmts);
            let x = scope.tmp();
            out.push(quote! {
                let #x = if #c { #(#then_stmts)* #then_v } else { #(#other_stmts)* #other_v };
            });
            return quote!(#x);
        }
        if args.len() == 2 && [atoms::GET, atoms::SET, atoms::INC].contains(&name) {
            if let (Some(var), Value::Var(v)) =
                (self.store.atom_of(args[0]), self.store.value(args[1]))
            {
                if scope.lazy.remove(&v.index()) {
                    let w = scope.vars[&v.index()].clone();
                    let (op, var) = (self.atom_expr(name), self.atom_expr(var));
                    out.push(quote!(let #w = cx.var_op_fresh(#op, #var, #arc)?;));
                    return quote!(#w);
                }
            }
            if let Some(var) = self.store.atom_of(args[0]) {
                let arg = self.build_cx(args[1], scope, out);
                let (op, var) = (self.atom_expr(name), self.atom_expr(var));
                let x = scope.tmp();
                out.push(quote!(let #x = cx.var_op(#op, #var, #arg, #arc)?;));
                return quote!(#x);
            }
        }
        if args.len() == 2 && name == atoms::IS {
            let expr = self.build_cx(args[1], scope, out);
            if let Value::Var(v) = self.store.value(args[0]) {
                if scope.lazy.remove(&v.index()) {
                    let w = scope.vars[&v.index()].clone();
                    out.push(quote!(let #w = cx.is(::std::option::Option::None, #expr, #arc)?;));
                    return quote!(#w);
                }
            }
            let lhs = self.build_cx(args[0], scope, out);
            let x = scope.tmp();
            out.push(quote!(let #x = cx.is(::std::option::Option::Some(#lhs), #expr, #arc)?;));
            return quote!(#x);
        }
        if eval::evaluates_arguments_only(name, args.len()) {
            let values: Vec<TokenStream> = args
                .iter()
                .map(|&a| self.eval_cx(a, arc, scope, out))
                .collect();
            let x = scope.tmp();
            if name == atoms::DOT && args.len() == 2 {
                out.push(quote!(let #x = cx.store().cons(#(#values),*);));
            } else {
                let f = self.atom_expr(name);
                out.push(quote!(let #x = cx.compound(#f, &[#(#values),*]);));
            }
            return quote!(#x);
        }
        let built = self.build_cx(t, scope, out);
        let x = scope.tmp();
        out.push(quote!(let #x = cx.eval(#built, #arc)?;));
        quote!(#x)
    }

    /// Statements running a conditional's condition; the `bool` expression.
    fn condition_cx(
        &self,
        cond: Term,
        arc: &TokenStream,
        scope: &mut Scope,
        out: &mut Vec<TokenStream>,
    ) -> TokenStream {
        if let Value::Compound(name, &[l, r]) = self.store.value(cond) {
            if let Some(op) = ArithCmp::from_atom(name) {
                let l = self.eval_cx(l, arc, scope, out);
                let r = self.eval_cx(r, arc, scope, out);
                let op = format_ident!("{}", format!("{op:?}"));
                let x = scope.tmp();
                out.push(quote! {
                    let #x = cx.arith_condition(::sitlog_runtime::ArithCmp::#op, #l, #r, #arc)?;
                });
                return quote!(#x);
            }
        }
        let built = self.build_cx(cond, scope, out);
        let x = scope.tmp();
        out.push(quote!(let #x = cx.condition(#built, #arc)?;));
        quote!(#x)
    }

    /// Statements evaluating a next situation; the expression of
    /// `(Term, Option<SitIx>)`: its value and, when known, its index.
    fn next_cx(
        &self,
        dm: &IrDm,
        t: Term,
        arc: &TokenStream,
        scope: &mut Scope,
        out: &mut Vec<TokenStream>,
    ) -> TokenStream {
        if let Some(name) = self.store.atom_of(t) {
            let v = self.atom_term(name);
            return match self.static_target(dm, name) {
                Some(ix) => {
                    let ix = Literal::u32_unsuffixed(ix);
                    quote!((#v, ::std::option::Option::Some(#ix)))
                }
                None => quote!((#v, ::std::option::Option::None)),
            };
        }
        if let Some((cond, then, other)) = eval::conditional(self.store, t) {
            let c = self.condition_cx(cond, arc, scope, out);
            let mut then_stmts = Vec::new();
            let then_v = self.next_cx(dm, then, arc, scope, &mut then_stmts);
            let mut other_stmts = Vec::new();
            let other_v = self.next_cx(dm, other, arc, scope, &mut other_stmts);
            let x = scope.tmp();
            out.push(quote! {
                let #x = if #c { #(#then_stmts)* #then_v } else { #(#other_stmts)* #other_v };
            });
            return quote!(#x);
        }
        let v = self.eval_cx(t, arc, scope, out);
        quote!((#v, ::std::option::Option::None))
    }

    /// The variables of `terms` (evaluated in this order) whose first
    /// occurrence is the argument of a `get` or `inc` outside any conditional.
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
        if let Some((c, a, b)) = eval::conditional(self.store, t) {
            for part in [c, a, b] {
                self.lazy_walk(part, depth + 1, seen, lazy);
            }
            return;
        }
        if args.len() == 2 && name == atoms::IS {
            // The expression is read first, then the variable is bound.
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

    /// The elements of a non-empty proper list written out in the source.
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

    /// Code of a compiled situation (`ix` in `dm`).
    pub(super) fn situation_code(
        &self,
        dm: &IrDm,
        ix: usize,
        run_name: &Ident,
        exit_name: &Ident,
    ) -> SituationCode {
        let s = &dm.situations[ix];
        let f = self.store.args(s.template);
        let mut scope = Scope {
            vars: HashMap::new(),
            lazy: HashSet::new(),
            next_tmp: 0,
        };
        // The situation's own variables (every field but the arcs).
        let mut inst_vars = Vec::new();
        for &t in &f[..ARCS] {
            self.term_vars(t, &mut inst_vars);
        }
        let head_vars: Vec<u32> = self
            .store
            .args(f[HEAD])
            .iter()
            .map(|&a| match self.store.value(a) {
                Value::Var(v) => v.index(),
                _ => unreachable!("compiled DMs have variable parameters"),
            })
            .collect();
        let in_arg = self.field(s, IN_ARG);
        let out_arg = self.field(s, OUT_ARG);
        let prog = self.field(s, PROG);
        let diag_mod = self.field(s, DIAG_MOD);
        let in_var = in_arg.and_then(|t| match self.store.value(t) {
            Value::Var(v) if !head_vars.contains(&v.index()) => Some(v.index()),
            _ => None,
        });
        let mut body = Vec::new();
        // A compound id: the value that selected the situation, else built
        // with fresh variables (initial situation); its variables are its arguments.
        let mut id_vars = Vec::new();
        if let Value::Compound(name, args) = self.store.value(f[ID]) {
            let mut fresh = Vec::new();
            let mut parts = Vec::new();
            for (i, &arg) in args.iter().enumerate() {
                if let Value::Var(v) = self.store.value(arg) {
                    id_vars.push((v.index(), i));
                    let x = format_ident!("x{}", i);
                    fresh.push(quote!(let #x = cx.var();));
                    parts.push(quote!(#x));
                } else {
                    parts.push(self.build_into(
                        arg,
                        &HashMap::new(),
                        false,
                        &mut 0,
                        &mut Vec::new(),
                    ));
                }
            }
            let f = self.atom_expr(name);
            body.push(quote! {
                let id = match cx.selected() {
                    ::std::option::Option::Some(value) => value,
                    ::std::option::Option::None => {
                        #(#fresh)*
                        let id = cx.compound(#f, &[#(#parts),*]);
                        cx.set_id(id);
                        id
                    }
                };
            });
        }
        for (n, &v) in inst_vars.iter().enumerate() {
            let id = format_ident!("v{}", n);
            let init = if let Some(&(_, i)) = id_vars.iter().find(|(x, _)| *x == v) {
                let i = Literal::usize_unsuffixed(i);
                quote!(cx.arg(id, #i))
            } else if let Some(i) = head_vars.iter().position(|&h| h == v) {
                let i = Literal::usize_unsuffixed(i);
                quote!(cx.head_arg(#i))
            } else if Some(v) == in_var {
                // A variable in_arg takes the pipe value (D-8).
                quote!(cx.pipe())
            } else {
                quote!(cx.var())
            };
            body.push(quote!(let #id = #init;));
            scope.vars.insert(v, id);
        }
        let mut links = Vec::new();
        if let Some(t) = in_arg {
            let pattern = self.build_cx(t, &mut scope, &mut body);
            if in_var.is_none() {
                body.push(quote!(cx.in_arg(#pattern)?;));
            }
            links.push(quote!(::std::option::Option::Some(#pattern)));
        }
        let out_built = if s.kind != Kind::Recursive {
            out_arg.map(|t| {
                let o = self.build_cx(t, &mut scope, &mut body);
                links.push(quote!(::std::option::Option::Some(#o)));
                o
            })
        } else {
            None
        };
        if let Some(p) = prog {
            // `prog` runs on a copy sharing only in_arg's (and out_arg's)
            // variables (D-10). When no other field has its variables, the
            // situation's fresh variables are that copy: evaluate in place.
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
                let none = quote!(::std::option::Option::None);
                // Its value is not used: a list's elements are evaluated, not gathered.
                let parts = self.list_literal(p).unwrap_or_else(|| vec![p]);
                for part in parts {
                    let value = self.eval_cx(part, &none, &mut scope, &mut body);
                    body.push(quote!(let _ = #value;));
                }
            } else {
                let p = self.build_cx(p, &mut scope, &mut body);
                body.push(quote!(cx.prog(#p, &[#(#links),*])?;));
            }
        }
        let rt = quote!(::sitlog_runtime);
        let sig = quote!(cx: &mut #rt::machine::Cx<'_, '_, super::Program>);
        let result = quote!(::std::result::Result<#rt::machine::Step, #rt::machine::RunError>);
        match s.kind {
            Kind::Final => {
                let out = match out_built {
                    Some(o) => quote!(::std::option::Option::Some(#o)),
                    None => quote!(::std::option::Option::None),
                };
                body.push(quote!(cx.final_out_arg(#out)?;));
                if let Some(d) = diag_mod {
                    let d = self.build_cx(d, &mut scope, &mut body);
                    body.push(quote!(cx.diag_mod(#d)?;));
                }
                let empty = quote!(#rt::Term::atom(#rt::atoms::EMPTY));
                body.push(quote!(cx.record(#empty, #empty, ::std::option::Option::None);));
                body.push(quote!(::std::result::Result::Ok(#rt::machine::Step::Final)));
                SituationCode {
                    run: wrap(
                        quote!(fn #run_name(p: &super::Program, #sig) -> #result),
                        body,
                    ),
                    exit: None,
                }
            }
            Kind::Perceptual => {
                self.arcs_code(dm, s, &mut scope, &mut body, false);
                SituationCode {
                    run: wrap(
                        quote!(fn #run_name(p: &super::Program, #sig) -> #result),
                        body,
                    ),
                    exit: None,
                }
            }
            Kind::Recursive => {
                let e = self.field(s, EMBEDDED_DM).expect("checked by compiled_id");
                if self.store.is_ground(e) && self.inert(e, true) {
                    // Evaluating a constant call changes nothing.
                    let e = self.build_cx(e, &mut scope, &mut body);
                    body.push(quote!(let call = #e;));
                } else {
                    let e = self.build_cx(e, &mut scope, &mut body);
                    body.push(quote!(let call = cx.embedded_dm(#e)?;));
                }
                // What the exit arcs need of the situation's variables.
                let mut needed = Vec::new();
                for t in [Some(f[ARCS]), out_arg, diag_mod].into_iter().flatten() {
                    self.term_vars(t, &mut needed);
                }
                let saved_vars: Vec<Ident> = inst_vars
                    .iter()
                    .enumerate()
                    .filter(|(_, v)| needed.contains(v))
                    .map(|(n, _)| format_ident!("v{}", n))
                    .collect();
                let saved = if saved_vars.is_empty() {
                    quote!(#rt::Term::NIL)
                } else {
                    quote!(cx.compound(#rt::atoms::DOT, &[#(#saved_vars),*]))
                };
                body.push(quote! {
                    let saved = #saved;
                    ::std::result::Result::Ok(#rt::machine::Step::Call { call, saved })
                });
                // The exit arcs: the situation's variables back from `saved`.
                let mut exit = Vec::new();
                for (n, v) in saved_vars.iter().enumerate() {
                    let n = Literal::usize_unsuffixed(n);
                    exit.push(quote!(let #v = cx.arg(saved, #n);));
                }
                let mut exit_scope = Scope {
                    vars: scope.vars.clone(),
                    lazy: HashSet::new(),
                    next_tmp: scope.next_tmp,
                };
                self.arcs_code(dm, s, &mut exit_scope, &mut exit, true);
                SituationCode {
                    run: wrap(
                        quote!(fn #run_name(p: &super::Program, #sig) -> #result),
                        body,
                    ),
                    exit: Some(wrap(
                        quote! {
                            fn #exit_name(
                                p: &super::Program,
                                saved: #rt::Term,
                                final_id: #rt::Term,
                                #sig,
                            ) -> #result
                        },
                        exit,
                    )),
                }
            }
        }
    }

    /// The arcs of a perceptual situation, or the exit arcs of a recursive
    /// one: copies (imports), expectations, the choice, then the chosen
    /// arc's action, next situation, out_arg, diag_mod and history entry.
    fn arcs_code(
        &self,
        dm: &IrDm,
        s: &IrSituation,
        scope: &mut Scope,
        body: &mut Vec<TokenStream>,
        exit: bool,
    ) {
        let rt = quote!(::sitlog_runtime);
        let f = self.store.args(s.template);
        let out_arg = self.field(s, OUT_ARG);
        let diag_mod = self.field(s, DIAG_MOD);
        let arcs: Vec<[Term; 3]> = self
            .store
            .list_iter(f[ARCS])
            .map(|arc| {
                let a = self.store.args(arc);
                [a[0], a[1], a[2]]
            })
            .collect();
        // Each arc's variables: imported copies of the situation's, fresh otherwise (D-11).
        let mut arc_scopes = Vec::new();
        for (i, arc) in arcs.iter().enumerate() {
            let mut vars = Vec::new();
            for &t in arc.iter().chain(out_arg.iter()) {
                self.term_vars(t, &mut vars);
            }
            // Expectations are evaluated apart (D-12): their variables are made first.
            let in_order: Vec<Term> = arc.iter().copied().chain(out_arg).collect();
            let mut in_expectation = Vec::new();
            self.term_vars(arc[0], &mut in_expectation);
            let lazy: HashSet<u32> = self
                .lazy_vars(&in_order)
                .into_iter()
                .filter(|v| !scope.vars.contains_key(v) && !in_expectation.contains(v))
                .collect();
            let mut arc_vars = HashMap::new();
            let mut imported = Vec::new();
            let mut import_from = Vec::new();
            for (n, &v) in vars.iter().enumerate() {
                let id = format_ident!("w{}_{}", i, n);
                if let Some(inst) = scope.vars.get(&v) {
                    imported.push(id.clone());
                    import_from.push(inst.clone());
                } else if !lazy.contains(&v) {
                    body.push(quote!(let #id = cx.var();));
                }
                arc_vars.insert(v, id);
            }
            if !imported.is_empty() {
                let tmp = format_ident!("imports{}", i);
                body.push(quote! {
                    let mut #tmp = [#(#import_from),*];
                    cx.import(&mut #tmp);
                    let [#(#imported),*] = #tmp;
                });
            }
            // Nothing to save when the expectation evaluates to itself and
            // has none of the situation's variables (whose values could).
            let pure = self.inert(arc[0], true)
                && in_expectation.iter().all(|v| !scope.vars.contains_key(v));
            arc_scopes.push((arc_vars, lazy, pure));
        }
        // Expectations, with variable updates discarded (D-12).
        let mut exp_stmts = Vec::new();
        let mut exps = Vec::new();
        let all_pure = arc_scopes.iter().all(|(_, _, p)| *p);
        for (i, arc) in arcs.iter().enumerate() {
            let mut sc = Scope {
                vars: arc_scopes[i].0.clone(),
                lazy: HashSet::new(),
                next_tmp: scope.next_tmp,
            };
            let arc_ix = Literal::usize_unsuffixed(i);
            let arc_t = quote!(::std::option::Option::Some(#arc_ix));
            let e = self.eval_cx(arc[0], &arc_t, &mut sc, &mut exp_stmts);
            scope.next_tmp = sc.next_tmp;
            let name = format_ident!("e{}", i);
            exp_stmts.push(quote!(let #name = #e;));
            exps.push(name);
        }
        if all_pure {
            body.extend(exp_stmts);
        } else {
            body.push(quote! {
                cx.save_vars();
                let expectations = (|| -> ::std::result::Result<_, #rt::machine::RunError> {
                    #(#exp_stmts)*
                    ::std::result::Result::Ok([#(#exps),*])
                })();
                cx.restore_vars();
                let [#(#exps),*] = expectations?;
            });
        }
        let neutral = self.store.atom_of(f[TYPE]) == Some(atoms::NEUTRAL);
        if !exit
            && neutral
            && arcs.len() == 1
            && self.store.atom_of(arcs[0][0]) == Some(atoms::EMPTY)
        {
            // The neutral rule on `[empty : A => N]` always takes the arc (D-14).
            body.push(quote!(let chosen = 0usize;));
        } else {
            body.push(quote!(cx.set_expectations(&[#(#exps),*]);));
        }
        if exit {
            body.push(quote!(let chosen = cx.choose_exit(final_id)?;));
        } else if !(neutral
            && arcs.len() == 1
            && self.store.atom_of(arcs[0][0]) == Some(atoms::EMPTY))
        {
            let ty = self.atom_term(self.store.atom_of(f[TYPE]).expect("an atom type"));
            body.push(quote! {
                let ::std::option::Option::Some(chosen) = cx.choose(#ty)? else {
                    return ::std::result::Result::Ok(#rt::machine::Step::Unmet { type_term: #ty });
                };
            });
        }
        let mut match_arms = Vec::new();
        for (i, arc) in arcs.iter().enumerate() {
            let mut sc = Scope {
                vars: arc_scopes[i].0.clone(),
                lazy: arc_scopes[i].1.clone(),
                next_tmp: scope.next_tmp,
            };
            let arc_ix = Literal::usize_unsuffixed(i);
            let arc_t = quote!(::std::option::Option::Some(#arc_ix));
            let mut stmts = Vec::new();
            match self.list_literal(arc[1]) {
                // A list of actions, written out: its elements evaluated and
                // performed in order; the list itself is built only for the
                // history.
                Some(items) if !self.inert(arc[1], true) || !self.store.is_ground(arc[1]) => {
                    let values: Vec<TokenStream> = items
                        .iter()
                        .map(|&x| self.eval_cx(x, &arc_t, &mut sc, &mut stmts))
                        .collect();
                    stmts.push(quote! {
                        cx.perform_each(&[#(#values),*], #arc_t)?;
                        let action = if cx.records() {
                            cx.store().list(&[#(#values),*])
                        } else {
                            #rt::Term::NIL
                        };
                    });
                }
                _ => {
                    let action = self.eval_cx(arc[1], &arc_t, &mut sc, &mut stmts);
                    stmts.push(quote!(let action = #action;));
                    stmts.push(quote!(cx.perform(action, #arc_t)?;));
                }
            }
            let next = self.next_cx(dm, arc[2], &arc_t, &mut sc, &mut stmts);
            stmts.push(quote!(let (next, target) = #next;));
            if let Some(o) = out_arg {
                let o = self.build_cx(o, &mut sc, &mut stmts);
                stmts.push(quote!(cx.out_arg(#o, #arc_t)?;));
            }
            if let Some(d) = diag_mod {
                // diag_mod belongs to the situation, not to the arc's copy.
                let mut inst = Scope {
                    vars: scope.vars.clone(),
                    lazy: HashSet::new(),
                    next_tmp: sc.next_tmp,
                };
                let d = self.build_cx(d, &mut inst, &mut stmts);
                sc.next_tmp = inst.next_tmp;
                stmts.push(quote!(cx.diag_mod(#d)?;));
            }
            let e = format_ident!("e{}", i);
            stmts.push(quote! {
                cx.record(#e, action, ::std::option::Option::Some(next));
                match target {
                    ::std::option::Option::Some(ix) => ::std::result::Result::Ok(#rt::machine::Step::GotoSit(ix)),
                    ::std::option::Option::None => cx.goto(next, #arc_t),
                }
            });
            scope.next_tmp = sc.next_tmp;
            match_arms.push(quote!(#arc_ix => { #(#stmts)* }));
        }
        body.push(quote! {
            match chosen {
                #(#match_arms)*
                _ => unreachable!("the machine chose an arc of this situation"),
            }
        });
    }
}

/// A function from its signature and body statements, with the `a`/`k`
/// bindings its body uses.
fn wrap(signature: TokenStream, body: Vec<TokenStream>) -> TokenStream {
    let body = quote!(#(#body)*);
    let prelude = Gen::prelude(&body);
    quote!(#signature { #prelude #body })
}
