//! Plain Prolog user functions compiled to Rust (issue 37, way (b)): each
//! plain function native code calls ([`super::plain`]) is written as one
//! Rust function over `Val`s, its arguments by reference
//! (`plain_rs::p<k>_<name>_<arity>(a, [&Val; n])` in the program's module
//! `plain_rs`), from the very form the runtime's
//! evaluator runs (`sitlog_runtime::plain::plain_forms`: one analysis, two
//! back ends); a call site calls it through `Cx::nat_plain_rs` with its
//! slot `k` and the form's fingerprint (`FORM<k>`).
//!
//! Each clause is a labelled block, in order: the head's arguments
//! matched (a head variable a reference into the arguments, a list cell's
//! head and tail taken apart, a compound's functor compared), its goals as
//! statements (an integer register for a variable only `is` binds, a
//! `Val` for one `=` binds; `==` decided as the evaluator decides it, the
//! parts of a built operand compared where they are), its value built at
//! the end (the last assignment reached); a failing goal goes to the next
//! clause (`break`), or gives `None` after the clause's cut, as do a type
//! error, an overflow, a division by zero, an improper list built, and a
//! clause that succeeds without a value; `None` after the last clause.
//! The helpers it calls are the evaluator's (`sitlog_runtime::plain::rt`).
//!
//! A function some clause of which answers a compound (not a list cell)
//! answers an `Ans<k>` instead of a `Val`: the compound by its variant
//! (`V<j>`, one a name, arity and way its parts are held) and its parts,
//! a head variable a reference into the arguments, any other part a
//! value; every other value as `Ans<k>::Val`. Its call sites select the
//! next situation from the parts (the compound never built where a
//! situation takes it: `plain`), `Ans<k>::val` builds the value
//! (`Ans<k>::Val` also holds the value of the path not compiled).
//!
//! Invariant (the same clauses, ensured at run time): the compiled
//! function gives `Some(v)` (an answer whose `val` is `v`) exactly where
//! the evaluator's `PlainFns::call_vals` on the same form gives `Some(v)`,
//! else `None`, but for one case: a function without a float constant or
//! a `/` computes on `i64` and answers `None` where a float reaches its
//! arithmetic (`call_vals` may run it: `Cx::nat_plain_rs` then asks it);
//! a function with one computes on `rt::Num` as `call_vals` does
//! (`sitlog_runtime::plain::num`);
//! and it runs only where the run's engine loaded that same form (the
//! fingerprint, atoms by name, compared once a run: `Cx::nat_plain_rs`,
//! `sitlog_runtime::plain::slots`) and `call_vals` would run the call (the
//! arguments' and the globals' checks, the inference limit, the engine
//! live). A program whose engine holds another definition, or none that
//! is plain, takes `Cx::nat_plain`'s path, the present one.

use super::{Gen, N};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::plain::{
    atomic, Atomic, Bin, Cmp, Opnd, PArg, PClause, PExpr, PGoal, PlainFn, Un,
};
use sitlog_syntax::{atoms, Atom};

/// A compiled plain function: its slot's name and arity, its items and
/// its answers' type.
pub(in crate::codegen) struct PlainRs {
    key: (Atom, usize),
    items: Option<TokenStream>,
    ans: Option<Answers>,
}

/// The answers of a function whose clauses answer a compound (`Ans<k>`,
/// a variant a compound's name, arity and how its parts are held, its
/// parts not built into a value; `Ans<k>::Val` every other value).
#[derive(Clone)]
pub(super) struct Answers {
    /// The enum's name (`Ans<k>`).
    pub(super) name: Ident,
    /// Each variant's (`V<j>`) compound name and arity.
    pub(super) shapes: Vec<(Atom, usize)>,
}

/// A compound answer's variant: its name and each part's way, a
/// reference into the arguments (`true`) or a value.
#[derive(Clone, PartialEq)]
struct Shape {
    f: Atom,
    refs: Vec<bool>,
}

/// How a clause holds a variable.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    /// A head variable: a reference into the arguments.
    Ref,
    /// Bound by `is` only: an `i64` (a `rt::Num` in a function with
    /// floats, `Clause::floats`).
    Int,
    /// Bound by `=` (or both): an owned `Val`.
    Val,
}

impl Gen<'_> {
    /// The forms of the application's plain functions (read once).
    pub(super) fn plain_forms(&self) -> &[((Atom, usize), PlainFn)] {
        let Some(ir) = self.ir else {
            return &[];
        };
        self.plain_fns.get_or_init(|| {
            let files: Vec<(&str, Option<&[sitlog_syntax::Clause]>)> = ir
                .prolog_sources
                .iter()
                .map(|f| (f.text.as_str(), f.clauses.as_deref().map(|c| c.as_slice())))
                .collect();
            sitlog_runtime::plain::plain_forms(&files)
        })
    }

    /// Registers the atoms of the plain functions whose name the program
    /// names (the functions a call site may compile).
    pub(in crate::codegen) fn collect_plain(&mut self) {
        let forms: Vec<PlainFn> = self
            .plain_forms()
            .iter()
            .filter(|((name, _), _)| self.atom_ix.contains_key(name))
            .map(|(_, f)| f.clone())
            .collect();
        for f in &forms {
            let mut found = Vec::new();
            for c in f.clauses() {
                c.head().iter().for_each(|a| arg_atoms(a, &mut found));
                goal_atoms(c.body(), &mut found);
            }
            for a in found {
                if a != atoms::DOT {
                    self.atom(a);
                }
            }
        }
    }

    /// The slot of `name/arity`'s compiled function, compiled at its first
    /// call site; `None`: not compiled (the call site calls `nat_plain`).
    pub(super) fn plain_slot(&self, name: Atom, arity: usize) -> Option<usize> {
        let mut used = self.plain_rs.borrow_mut();
        if let Some(k) = used.iter().position(|p| p.key == (name, arity)) {
            return used[k].items.is_some().then_some(k);
        }
        let k = used.len();
        let made = self
            .plain_forms()
            .iter()
            .find(|(key, _)| *key == (name, arity))
            .and_then(|(_, f)| self.plain_fn(k, name, arity, f).ok());
        let ok = made.is_some();
        let (items, ans) = match made {
            Some((items, ans)) => (Some(items), ans),
            None => (None, None),
        };
        used.push(PlainRs {
            key: (name, arity),
            items,
            ans,
        });
        ok.then_some(k)
    }

    /// The module `plain_rs` of the compiled plain functions (nothing where
    /// no call site compiled one).
    pub(in crate::codegen) fn plain_rs_module(&self) -> TokenStream {
        let used = self.plain_rs.borrow();
        let items: Vec<&TokenStream> = used.iter().filter_map(|p| p.items.as_ref()).collect();
        if items.is_empty() {
            return quote!();
        }
        quote! {
            /// The plain Prolog user functions native code calls, compiled
            /// from their plain forms (`sitlog_compiler::codegen::native::plain_rs`):
            /// each `p<k>_..` runs where the run's engine holds the form
            /// whose fingerprint is `FORM<k>` (`Cx::nat_plain_rs`).
            #[allow(unused, unreachable_code, clippy::all)]
            pub mod plain_rs {
                use ::sitlog_runtime::prelude::*;
                use ::sitlog_runtime::plain::rt;
                use super::Atoms;
                #(#items)*
            }
        }
    }

    /// The call of slot `k`'s function as a call site writes it: the
    /// fingerprint and the function; its answers' type (`None`: a `Val`).
    pub(super) fn plain_rs_call(&self, k: usize) -> (TokenStream, TokenStream, Option<Answers>) {
        let used = self.plain_rs.borrow();
        let (name, arity) = used[k].key;
        let (f, form) = names(k, name, arity);
        (
            quote!(super::plain_rs::#form),
            quote!(super::plain_rs::#f),
            used[k].ans.clone(),
        )
    }

    /// The items of slot `k`'s function and its answers' type.
    fn plain_fn(
        &self,
        k: usize,
        name: Atom,
        arity: usize,
        f: &PlainFn,
    ) -> N<(TokenStream, Option<Answers>)> {
        let (fname, form) = names(k, name, arity);
        let fp = Literal::string(f.fingerprint());
        let args: Vec<Ident> = (0..arity).map(|i| format_ident!("a{}", i)).collect();
        // An answer type where a clause answers a compound.
        let mut compound = false;
        for c in f.clauses() {
            answers_compound(c.body(), &mut compound);
        }
        let ans = compound.then(|| format_ident!("Ans{}", k));
        let shapes = std::cell::RefCell::new(Vec::new());
        let floats = f.clauses().iter().any(|c| goals_float(c.body()));
        let mut clauses = Vec::new();
        for (n, c) in f.clauses().iter().enumerate() {
            clauses.push(self.plain_clause(n, c, &args, ans.as_ref(), &shapes, floats)?);
        }
        let doc = format!(" `{}/{}`, compiled.", name.as_str(), arity);
        let n = Literal::usize_unsuffixed(arity);
        let Some(ans) = ans else {
            return Ok((
                quote! {
                    /// The fingerprint of the form compiled below.
                    pub const #form: &str = #fp;
                    #[doc = #doc]
                    #[inline]
                    pub fn #fname(a: &Atoms, [#(#args),*]: [&Val; #n]) -> Option<Val> {
                        #(#clauses)*
                        None
                    }
                },
                None,
            ));
        };
        let shapes = shapes.into_inner();
        let long = shapes.iter().any(|s| s.refs.contains(&true));
        let lt = long.then(|| quote!(<'v>));
        let (mut variants, mut builds, mut names) = (Vec::new(), Vec::new(), Vec::new());
        for (j, s) in shapes.iter().enumerate() {
            let v = format_ident!("V{}", j);
            let fa = self.atom_native(s.f)?;
            let tys = s
                .refs
                .iter()
                .map(|r| if *r { quote!(&'v Val) } else { quote!(Val) });
            let xs: Vec<Ident> = (0..s.refs.len()).map(|i| format_ident!("x{}", i)).collect();
            let vals = xs
                .iter()
                .zip(&s.refs)
                .map(|(x, r)| if *r { quote!(#x.clone()) } else { quote!(#x) });
            let vdoc = format!(" `{}/{}`, by its parts.", s.f.as_str(), s.refs.len());
            variants.push(quote!(#[doc = #vdoc] #v(#(#tys),*),));
            builds.push(quote!(#ans::#v(#(#xs),*) => Val::Tagged(native::Compound::new(#fa, [#(#vals),*])),));
            names.push((s.f, s.refs.len()));
        }
        let edoc = format!(
            " What `{}/{}` answers: a compound by its parts (not built), any other value as it is.",
            name.as_str(),
            arity
        );
        let items = quote! {
            /// The fingerprint of the form compiled below.
            pub const #form: &str = #fp;
            #[doc = #edoc]
            pub enum #ans #lt {
                Val(Val),
                #(#variants)*
            }
            impl #lt rt::Answer for #ans #lt {
                #[inline(always)]
                fn of_val(v: Val) -> Self {
                    #ans::Val(v)
                }
            }
            impl #lt #ans #lt {
                /// The answer's value, built.
                pub fn val(self, a: &Atoms) -> Val {
                    match self {
                        #ans::Val(v) => v,
                        #(#builds)*
                    }
                }
            }
            #[doc = #doc]
            #[inline]
            pub fn #fname<'v>(a: &Atoms, [#(#args),*]: [&'v Val; #n]) -> Option<#ans #lt> {
                #(#clauses)*
                None
            }
        };
        Ok((
            items,
            Some(Answers {
                name: ans,
                shapes: names,
            }),
        ))
    }

    fn plain_clause(
        &self,
        n: usize,
        c: &PClause,
        args: &[Ident],
        ans: Option<&Ident>,
        shapes: &std::cell::RefCell<Vec<Shape>>,
        floats: bool,
    ) -> N<TokenStream> {
        let mut kinds = vec![None; c.vars()];
        for a in c.head() {
            head_kinds(a, &mut kinds);
        }
        body_kinds(c.body(), &mut kinds);
        // A variable nothing binds (a head's `_`): never read.
        let declared: Vec<bool> = kinds.iter().map(Option::is_some).collect();
        let kinds: Vec<Kind> = kinds.into_iter().map(|k| k.unwrap_or(Kind::Val)).collect();
        let single_assign = {
            let mut all = 0;
            count_assigns(c.body(), &mut all);
            let top = c
                .body()
                .iter()
                .filter(|g| matches!(g, PGoal::Assign(_)))
                .count();
            all == top && top <= 1
        };
        let mut cg = Clause {
            g: self,
            label: syn_label(&format!("c{n}")),
            kinds,
            tmp: 0,
            dynamic_cut: c.body().iter().any(cut_inside),
            cut: false,
            assigns: Vec::new(),
            dynamic_assign: !single_assign,
            long: vec![false; c.vars()],
            ans: ans.cloned(),
            shapes,
            floats,
        };
        let mut stmts = Vec::new();
        for (p, a) in c.head().iter().zip(args) {
            cg.head(p, quote!(#a), true, &mut stmts)?;
        }
        // The body's variables, each written once on a path before it is read.
        let mut decls = Vec::new();
        for (i, k) in cg.kinds.iter().enumerate() {
            let r = reg(i);
            match k {
                _ if !declared[i] => {}
                Kind::Ref => {}
                Kind::Int if cg.floats => decls.push(quote!(let #r: rt::Num;)),
                Kind::Int => decls.push(quote!(let #r: i64;)),
                Kind::Val => decls.push(quote!(let #r: Val;)),
            }
        }
        let mut body = Vec::new();
        // A clause whose goals always fail ends where they do.
        let diverges = cg.goals(c.body(), &mut body)?;
        let state = match (cg.dynamic_cut, single_assign) {
            (true, true) => quote!(let mut cut = false;),
            (true, false) => quote!(let mut cut = false; let mut assigned = 0usize;),
            (false, true) => quote!(),
            (false, false) => quote!(let mut assigned = 0usize;),
        };
        let end = if diverges {
            quote!()
        } else if cg.assigns.is_empty() {
            quote!(return None;)
        } else if single_assign {
            let o = cg.assigns[0].clone();
            let v = cg.answer(&o)?;
            quote!(return Some(#v);)
        } else {
            let mut arms = Vec::new();
            for (i, o) in cg.assigns.clone().iter().enumerate() {
                let v = cg.answer(o)?;
                let i = Literal::usize_unsuffixed(i + 1);
                arms.push(quote!(#i => #v,));
            }
            quote!(return Some(match assigned { #(#arms)* _ => return None });)
        };
        let label = &cg.label;
        Ok(quote! {
            #label: {
                #(#stmts)*
                #(#decls)*
                #state
                #(#body)*
                #end
            }
        })
    }
}

/// The names of slot `k`'s function and fingerprint.
fn names(k: usize, name: Atom, arity: usize) -> (Ident, Ident) {
    let base = crate::codegen::names::snake(name.as_str());
    (
        format_ident!("p{}_{}_{}", k, base, arity),
        format_ident!("FORM{}", k),
    )
}

fn syn_label(name: &str) -> TokenStream {
    let l = proc_macro2::Punct::new('\'', proc_macro2::Spacing::Joint);
    let id = format_ident!("{}", name);
    quote!(#l #id)
}

fn reg(i: usize) -> Ident {
    format_ident!("r{}", i)
}

fn int_lit(i: i64) -> TokenStream {
    if i == i64::MIN {
        quote!(i64::MIN)
    } else {
        let l = Literal::i64_suffixed(i);
        quote!(#l)
    }
}

fn arg_atoms(a: &PArg, out: &mut Vec<Atom>) {
    match a {
        PArg::Const(k) => {
            if let Atomic::Atom(x) = atomic(*k) {
                out.push(x)
            }
        }
        PArg::Struct(f, ps) => {
            out.push(*f);
            ps.iter().for_each(|p| arg_atoms(p, out));
        }
        _ => {}
    }
}

fn opnd_atoms(o: &Opnd, out: &mut Vec<Atom>) {
    match o {
        Opnd::Const(k) => {
            if let Atomic::Atom(x) = atomic(*k) {
                out.push(x)
            }
        }
        Opnd::Build(f, xs) => {
            out.push(*f);
            xs.iter().for_each(|x| opnd_atoms(x, out));
        }
        Opnd::Var(_) => {}
    }
}

fn goal_atoms(gs: &[PGoal], out: &mut Vec<Atom>) {
    for g in gs {
        match g {
            PGoal::Ident(_, x, y) => {
                opnd_atoms(x, out);
                opnd_atoms(y, out);
            }
            PGoal::Bind(_, o) | PGoal::Assign(o) => opnd_atoms(o, out),
            PGoal::Ite(c, t, e) => {
                goal_atoms(c, out);
                goal_atoms(t, out);
                goal_atoms(e, out);
            }
            _ => {}
        }
    }
}

/// Whether an expression of `gs` has a float constant or a `/` (the
/// function's arithmetic is then on `rt::Num`).
fn goals_float(gs: &[PGoal]) -> bool {
    fn expr(e: &PExpr) -> bool {
        match e {
            PExpr::Float(_) | PExpr::Bin(Bin::Div, ..) => true,
            PExpr::Var(_) | PExpr::Int(_) => false,
            PExpr::Un(_, x) => expr(x),
            PExpr::Bin(_, x, y) => expr(x) || expr(y),
        }
    }
    gs.iter().any(|g| match g {
        PGoal::IsFresh(_, e) | PGoal::IsBound(_, e) => expr(e),
        PGoal::Cmp(_, x, y) => expr(x) || expr(y),
        PGoal::Ite(c, t, e) => goals_float(c) || goals_float(t) || goals_float(e),
        _ => false,
    })
}

fn head_kinds(a: &PArg, kinds: &mut [Option<Kind>]) {
    match a {
        PArg::Bind(i) => kinds[*i as usize] = Some(Kind::Ref),
        PArg::Struct(_, ps) => ps.iter().for_each(|p| head_kinds(p, kinds)),
        _ => {}
    }
}

fn body_kinds(gs: &[PGoal], kinds: &mut [Option<Kind>]) {
    for g in gs {
        match g {
            PGoal::IsFresh(i, _) => {
                let k = &mut kinds[*i as usize];
                if k.is_none() {
                    *k = Some(Kind::Int);
                }
            }
            PGoal::Bind(i, _) => kinds[*i as usize] = Some(Kind::Val),
            PGoal::Ite(c, t, e) => {
                body_kinds(c, kinds);
                body_kinds(t, kinds);
                body_kinds(e, kinds);
            }
            _ => {}
        }
    }
}

/// Whether `o`, a value assigned, is a compound a function answers by its
/// parts (not a list cell).
fn compound_answer(o: &Opnd) -> bool {
    let cell = |f: Atom, n: usize| f == atoms::DOT && n == 2;
    matches!(o, Opnd::Build(f, args) if !args.is_empty() && !cell(*f, args.len()))
}

/// Whether a goal of `gs` assigns a compound answered by its parts.
fn answers_compound(gs: &[PGoal], found: &mut bool) {
    for g in gs {
        match g {
            PGoal::Assign(o) => *found |= compound_answer(o),
            PGoal::Ite(c, t, e) => {
                answers_compound(c, found);
                answers_compound(t, found);
                answers_compound(e, found);
            }
            _ => {}
        }
    }
}

/// Whether a cut is inside an if-then-else (the clause then keeps whether
/// it cut at run time).
fn cut_inside(g: &PGoal) -> bool {
    match g {
        PGoal::Ite(c, t, e) => [c, t, e]
            .iter()
            .any(|gs| gs.iter().any(|g| matches!(g, PGoal::Cut) || cut_inside(g))),
        _ => false,
    }
}

fn count_assigns(gs: &[PGoal], n: &mut usize) {
    for g in gs {
        match g {
            PGoal::Assign(_) => *n += 1,
            PGoal::Ite(c, t, e) => {
                count_assigns(c, n);
                count_assigns(t, n);
                count_assigns(e, n);
            }
            _ => {}
        }
    }
}

/// One clause being written.
struct Clause<'g, 's> {
    g: &'g Gen<'s>,
    label: TokenStream,
    kinds: Vec<Kind>,
    /// Temporaries' names so far.
    tmp: usize,
    /// Whether the clause keeps `cut` at run time; else `cut` says whether
    /// a cut was reached at the point written.
    dynamic_cut: bool,
    cut: bool,
    /// The assignments in the order written (`assigned` their number).
    assigns: Vec<Opnd>,
    /// Whether the clause keeps which assignment it reached last at run
    /// time (`assigned`); else it has at most one, at its top level.
    dynamic_assign: bool,
    /// Which head variables are references into the arguments (`&'v`).
    long: Vec<bool>,
    /// The function's answer type (`None`: it answers a `Val`) and its
    /// variants so far.
    ans: Option<Ident>,
    shapes: &'g std::cell::RefCell<Vec<Shape>>,
    /// The function has a float constant or a `/`: its arithmetic is on
    /// `rt::Num` (integers and floats, `sitlog_runtime::plain::num`),
    /// else on `i64`.
    floats: bool,
}

impl Clause<'_, '_> {
    fn tmp(&mut self, what: &str) -> Ident {
        self.tmp += 1;
        format_ident!("{}{}", what, self.tmp)
    }

    fn atom(&self, a: Atom) -> N<TokenStream> {
        if a == atoms::DOT {
            return Ok(quote!(atoms::DOT));
        }
        self.g.atom_native(a)
    }

    /// A statement that fails the clause where it stands.
    fn fail(&self) -> TokenStream {
        let label = &self.label;
        if self.dynamic_cut {
            quote!({
                if cut {
                    return None;
                }
                break #label;
            })
        } else if self.cut {
            quote!(return None;)
        } else {
            quote!(break #label;)
        }
    }

    /// The value of an assignment, as the function answers it: a compound
    /// (not a list cell) by its variant and parts where the function has
    /// an answer type, else the value.
    fn answer(&mut self, o: &Opnd) -> N<TokenStream> {
        let Some(ans) = self.ans.clone() else {
            return self.value(o);
        };
        match o {
            Opnd::Build(f, args) if compound_answer(o) => {
                let mut refs = Vec::new();
                let mut parts = Vec::new();
                for x in args.iter() {
                    match x {
                        Opnd::Var(i)
                            if self.kinds[*i as usize] == Kind::Ref && self.long[*i as usize] =>
                        {
                            let r = reg(*i as usize);
                            refs.push(true);
                            parts.push(quote!(#r));
                        }
                        _ => {
                            refs.push(false);
                            parts.push(self.value(x)?);
                        }
                    }
                }
                let shape = Shape { f: *f, refs };
                let mut shapes = self.shapes.borrow_mut();
                let j = match shapes.iter().position(|s| *s == shape) {
                    Some(j) => j,
                    None => {
                        shapes.push(shape);
                        shapes.len() - 1
                    }
                };
                let v = format_ident!("V{}", j);
                Ok(quote!(#ans::#v(#(#parts),*)))
            }
            _ => {
                let v = self.value(o)?;
                Ok(quote!(#ans::Val(#v)))
            }
        }
    }

    /// Register `i` as a `&Val` expression.
    fn reg_ref(&self, i: u16) -> TokenStream {
        let r = reg(i as usize);
        match self.kinds[i as usize] {
            Kind::Ref => quote!(#r),
            Kind::Int if self.floats => quote!(&rt::num_val(#r)),
            Kind::Int => quote!(&Val::Int(#r)),
            Kind::Val => quote!(&#r),
        }
    }

    /// Whether `v` (a `&Val`) is the constant `k` (`ident_k`).
    fn is_const(&self, v: TokenStream, k: sitlog_runtime::Term) -> N<TokenStream> {
        Ok(match atomic(k) {
            Atomic::Atom(x) => {
                let x = self.atom(x)?;
                quote!(rt::is_atom(#v, #x))
            }
            Atomic::Int(i) => {
                let i = int_lit(i);
                quote!(rt::is_int(#v, #i))
            }
        })
    }

    /// The head argument `p` matched against `v` (a `&Val`; `long`: a
    /// reference into the arguments, `&'v`).
    fn head(&mut self, p: &PArg, v: TokenStream, long: bool, out: &mut Vec<TokenStream>) -> N<()> {
        let label = self.label.clone();
        match p {
            PArg::Bind(i) => {
                let r = reg(*i as usize);
                self.long[*i as usize] = long;
                out.push(quote!(let #r: &Val = #v;));
            }
            PArg::Same(i) => {
                let r = self.reg_ref(*i);
                out.push(quote!(if !rt::ident(#r, #v) { break #label; }));
            }
            PArg::Skip => {}
            PArg::Const(k) => {
                let t = self.is_const(v, *k)?;
                out.push(quote!(if !#t { break #label; }));
            }
            PArg::Struct(f, ps) if *f == atoms::DOT && ps.len() == 2 => {
                let (l, h, t) = (self.tmp("l"), self.tmp("h"), self.tmp("t"));
                out.push(quote! {
                    let Val::List(#l) = #v else { break #label; };
                    let Some((#h, #t)) = #l.split_first() else { break #label; };
                    let #t = Val::List(#t);
                });
                self.head(&ps[0], quote!(#h), long, out)?;
                self.head(&ps[1], quote!(&#t), false, out)?;
            }
            PArg::Struct(_, ps) if ps.is_empty() => out.push(quote!(break #label;)),
            PArg::Struct(f, ps) => {
                let c = self.tmp("s");
                let fa = self.atom(*f)?;
                let n = Literal::usize_unsuffixed(ps.len());
                out.push(quote! {
                    let Val::Tagged(#c) = #v else { break #label; };
                    if #c.name() != #fa || #c.args().len() != #n { break #label; }
                });
                for (i, p) in ps.iter().enumerate() {
                    let i = Literal::usize_unsuffixed(i);
                    self.head(p, quote!(&#c.args()[#i]), long, out)?;
                }
            }
        }
        Ok(())
    }

    /// `x == y` as the evaluator's `ident_oo` decides it.
    fn ident_oo(&mut self, x: &Opnd, y: &Opnd) -> N<TokenStream> {
        Ok(match (x, y) {
            (Opnd::Var(i), Opnd::Const(k)) | (Opnd::Const(k), Opnd::Var(i)) => {
                let r = self.reg_ref(*i);
                self.is_const(r, *k)?
            }
            (Opnd::Var(i), Opnd::Var(j)) => {
                let (a, b) = (self.reg_ref(*i), self.reg_ref(*j));
                quote!(rt::ident(#a, #b))
            }
            (Opnd::Build(f, a), Opnd::Build(g, b)) => {
                if f != g || a.len() != b.len() {
                    quote!(false)
                } else {
                    let mut parts = Vec::new();
                    for (p, q) in a.iter().zip(b.iter()) {
                        parts.push(self.ident_oo(p, q)?);
                    }
                    quote!((true #(&& #parts)*))
                }
            }
            (Opnd::Var(i), o) | (o, Opnd::Var(i)) => {
                let r = self.reg_ref(*i);
                self.ident_ov(o, r)?
            }
            // Two constants: the same term; a constant and a compound: not.
            (Opnd::Const(k), Opnd::Const(l)) => {
                if k == l {
                    quote!(true)
                } else {
                    quote!(false)
                }
            }
            (Opnd::Const(_), _) | (_, Opnd::Const(_)) => quote!(false),
        })
    }

    /// Whether the operand's value is `v` (a `&Val`), as `ident_ov`.
    fn ident_ov(&mut self, o: &Opnd, v: TokenStream) -> N<TokenStream> {
        Ok(match o {
            Opnd::Var(i) => {
                let r = self.reg_ref(*i);
                quote!(rt::ident(#r, #v))
            }
            Opnd::Const(k) => self.is_const(v, *k)?,
            Opnd::Build(f, args) => {
                let pp = self.tmp("pp");
                let fa = self.atom(*f)?;
                let n = Literal::usize_unsuffixed(args.len());
                let mut parts = Vec::new();
                for (i, a) in args.iter().enumerate() {
                    let i = Literal::usize_unsuffixed(i);
                    parts.push(self.ident_ov(a, quote!(#pp.get(#i)))?);
                }
                quote!(match rt::parts(#v, #fa, #n) {
                    Some(#pp) => true #(&& #parts)*,
                    None => false,
                })
            }
        })
    }

    /// The operand's value (a `Val`; `?`: the term path decides).
    fn value(&mut self, o: &Opnd) -> N<TokenStream> {
        Ok(match o {
            Opnd::Var(i) => {
                let r = reg(*i as usize);
                match self.kinds[*i as usize] {
                    Kind::Int if self.floats => quote!(rt::num_val(#r)),
                    Kind::Int => quote!(Val::Int(#r)),
                    Kind::Ref | Kind::Val => quote!(#r.clone()),
                }
            }
            Opnd::Const(k) => match atomic(*k) {
                Atomic::Atom(a) if a == atoms::NIL => quote!(Val::List(List::nil())),
                Atomic::Atom(a) => {
                    let a = self.atom(a)?;
                    quote!(Val::Sym(#a))
                }
                Atomic::Int(i) => {
                    let i = int_lit(i);
                    quote!(Val::Int(#i))
                }
            },
            Opnd::Build(f, args) if *f == atoms::DOT && args.len() == 2 => {
                let h = self.value(&args[0])?;
                let t = self.value(&args[1])?;
                quote!(rt::cons(#h, #t)?)
            }
            Opnd::Build(_, args) if args.is_empty() => {
                return Err("a compound of no arguments".into())
            }
            Opnd::Build(f, args) => {
                let fa = self.atom(*f)?;
                let mut vs = Vec::new();
                for a in args.iter() {
                    vs.push(self.value(a)?);
                }
                quote!(Val::Tagged(native::Compound::new(#fa, [#(#vs),*])))
            }
        })
    }

    /// The expression's integer (`?`: the term path decides); a `rt::Num`
    /// in a function with floats.
    fn eval(&self, e: &PExpr) -> TokenStream {
        if self.floats {
            return self.eval_num(e);
        }
        match e {
            PExpr::Var(i) => {
                let r = reg(*i as usize);
                match self.kinds[*i as usize] {
                    Kind::Int => quote!(#r),
                    Kind::Ref => quote!(rt::int(#r)?),
                    Kind::Val => quote!(rt::int(&#r)?),
                }
            }
            PExpr::Int(i) => int_lit(*i),
            // Not in a function without floats (`Clause::floats`).
            PExpr::Float(_) => quote!(None?),
            PExpr::Un(op, x) => {
                let x = self.eval(x);
                match op {
                    Un::Neg => quote!((#x).checked_neg()?),
                    Un::Pos => quote!((#x)),
                    Un::Abs => quote!((#x).checked_abs()?),
                }
            }
            PExpr::Bin(op, x, y) => {
                let (x, y) = (self.eval(x), self.eval(y));
                match op {
                    Bin::Add => quote!((#x).checked_add(#y)?),
                    Bin::Sub => quote!((#x).checked_sub(#y)?),
                    Bin::Mul => quote!((#x).checked_mul(#y)?),
                    Bin::IntDiv => quote!((#x).checked_div(#y)?),
                    Bin::Rem => quote!((#x).checked_rem(#y)?),
                    Bin::Mod => quote!(rt::modulo(#x, #y)?),
                    Bin::Min => quote!((#x).min(#y)),
                    Bin::Max => quote!((#x).max(#y)),
                    Bin::Div => quote!(None?),
                }
            }
        }
    }

    /// [`Clause::eval`] on `rt::Num` (the evaluator's `plain::num`).
    fn eval_num(&self, e: &PExpr) -> TokenStream {
        match e {
            PExpr::Var(i) => {
                let r = reg(*i as usize);
                match self.kinds[*i as usize] {
                    Kind::Int => quote!(#r),
                    Kind::Ref => quote!(rt::num(#r)?),
                    Kind::Val => quote!(rt::num(&#r)?),
                }
            }
            PExpr::Int(i) => {
                let i = int_lit(*i);
                quote!(rt::Num::Int(#i))
            }
            PExpr::Float(f) => {
                let bits = Literal::u64_suffixed(f.to_bits());
                quote!(rt::Num::Float(f64::from_bits(#bits)))
            }
            PExpr::Un(op, x) => {
                let x = self.eval_num(x);
                let op = match op {
                    Un::Neg => quote!(Neg),
                    Un::Pos => quote!(Pos),
                    Un::Abs => quote!(Abs),
                };
                quote!(rt::un(rt::Un::#op, #x)?)
            }
            PExpr::Bin(op, x, y) => {
                let (x, y) = (self.eval_num(x), self.eval_num(y));
                let op = match op {
                    Bin::Add => quote!(Add),
                    Bin::Sub => quote!(Sub),
                    Bin::Mul => quote!(Mul),
                    Bin::IntDiv => quote!(IntDiv),
                    Bin::Rem => quote!(Rem),
                    Bin::Mod => quote!(Mod),
                    Bin::Min => quote!(Min),
                    Bin::Max => quote!(Max),
                    Bin::Div => quote!(Div),
                };
                quote!(rt::bin(rt::Bin::#op, #x, #y)?)
            }
        }
    }

    /// A test goal (`is_test`) as a `bool` expression; `None` for `true`.
    fn test(&mut self, g: &PGoal) -> N<Option<TokenStream>> {
        if self.floats {
            match g {
                PGoal::IsBound(i, e) => {
                    let e = self.eval_num(e);
                    let r = reg(*i as usize);
                    return Ok(Some(match self.kinds[*i as usize] {
                        Kind::Int => quote!(rt::same(#e, #r)),
                        Kind::Ref => quote!(rt::same(#e, rt::num(#r)?)),
                        Kind::Val => quote!(rt::same(#e, rt::num(&#r)?)),
                    }));
                }
                PGoal::Cmp(op, x, y) => {
                    let (x, y) = (self.eval_num(x), self.eval_num(y));
                    let op = match op {
                        Cmp::Lt => quote!(Lt),
                        Cmp::Gt => quote!(Gt),
                        Cmp::Le => quote!(Le),
                        Cmp::Ge => quote!(Ge),
                        Cmp::Eq => quote!(Eq),
                        Cmp::Ne => quote!(Ne),
                    };
                    return Ok(Some(quote!(rt::cmp(rt::Cmp::#op, #x, #y)?)));
                }
                _ => {}
            }
        }
        Ok(Some(match g {
            PGoal::True => return Ok(None),
            PGoal::Fail => quote!(false),
            PGoal::IsBound(i, e) => {
                let e = self.eval(e);
                let r = reg(*i as usize);
                match self.kinds[*i as usize] {
                    Kind::Int => quote!((#e) == #r),
                    Kind::Ref => quote!((#e) == rt::int(#r)?),
                    Kind::Val => quote!((#e) == rt::int(&#r)?),
                }
            }
            PGoal::Cmp(op, x, y) => {
                let (x, y) = (self.eval(x), self.eval(y));
                match op {
                    Cmp::Lt => quote!((#x) < (#y)),
                    Cmp::Gt => quote!((#x) > (#y)),
                    Cmp::Le => quote!((#x) <= (#y)),
                    Cmp::Ge => quote!((#x) >= (#y)),
                    Cmp::Eq => quote!((#x) == (#y)),
                    Cmp::Ne => quote!((#x) != (#y)),
                }
            }
            PGoal::Ident(eq, x, y) => {
                let t = self.ident_oo(x, y)?;
                if *eq {
                    t
                } else {
                    quote!(!(#t))
                }
            }
            _ => return Err("not a test".into()),
        }))
    }

    /// The goals as statements; `true` where they always fail (what
    /// follows a `fail` is not written).
    fn goals(&mut self, gs: &[PGoal], out: &mut Vec<TokenStream>) -> N<bool> {
        for g in gs {
            match g {
                PGoal::Fail => {
                    out.push(self.fail());
                    return Ok(true);
                }
                PGoal::Cut => {
                    if self.dynamic_cut {
                        out.push(quote!(cut = true;));
                    } else {
                        self.cut = true;
                    }
                }
                PGoal::IsFresh(i, e) => {
                    let r = reg(*i as usize);
                    let e = self.eval(e);
                    out.push(match self.kinds[*i as usize] {
                        Kind::Int => quote!(#r = #e;),
                        _ if self.floats => quote!(#r = rt::num_val(#e);),
                        _ => quote!(#r = Val::Int(#e);),
                    });
                }
                PGoal::Bind(i, o) => {
                    let r = reg(*i as usize);
                    let v = self.value(o)?;
                    out.push(quote!(#r = #v;));
                }
                PGoal::Assign(o) => {
                    self.assigns.push(o.clone());
                    if self.dynamic_assign {
                        let n = Literal::usize_unsuffixed(self.assigns.len());
                        out.push(quote!(assigned = #n;));
                    }
                }
                PGoal::Ite(c, t, e) => {
                    let l = syn_label(&format!("if{}", self.tmp));
                    self.tmp += 1;
                    let mut tests = Vec::new();
                    for g in c.iter() {
                        if let Some(t) = self.test(g)? {
                            tests.push(quote!(if !(#t) { break #l false; }));
                        }
                    }
                    let (mut ts, mut es) = (Vec::new(), Vec::new());
                    let t_fails = self.goals(t, &mut ts)?;
                    let e_fails = self.goals(e, &mut es)?;
                    let holds = self.tmp("cond");
                    out.push(quote! {
                        let #holds: bool = #l: { #(#tests)* true };
                        if #holds {
                            #(#ts)*
                        } else {
                            #(#es)*
                        }
                    });
                    if t_fails && e_fails {
                        return Ok(true);
                    }
                }
                _ => {
                    if let Some(t) = self.test(g)? {
                        let fail = self.fail();
                        out.push(quote!(if !(#t) { #fail }));
                    }
                }
            }
        }
        Ok(false)
    }
}
