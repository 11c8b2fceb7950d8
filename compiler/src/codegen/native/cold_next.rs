//! A global read's cold arm in a next situation's value and in an out_arg
//! computed after it (issue 37, helper `ncold20`; [`super::cold`] does the
//! same for a conditional's condition). Native code reads a global as a
//! value of its MIR type (`Cx::global_as`); a frame on terms (a parameter
//! that was not ground
//! where its frame started) may have stored a value that type does not
//! allow, such as an unbound variable (`set(goal, Goal)`, `Goal`
//! unbound), and the interpreter goes on with it: `show(wrap(get(goal,
//! _)))` is `show(wrap(_G))`. So where the value only reads variables
//! (values, constants, compounds of them, `get`s: nothing changes if it
//! is evaluated again), the native code computing it is a labelled block
//! whose global read, on finding such a value, breaks out of it (the
//! native frames already handed over and the machine entered in the
//! situation by the read's cold arm); the value is then evaluated on
//! terms as the term code does ([`Gen::nat_ev_term`]: its error the
//! evaluator's) and handed to the machine as the next situation, which
//! selects, as for a next situation the evaluator computes; an out_arg's
//! value is evaluated so (`Cx::out_value`) after the next situation
//! native code computed, which is handed to the machine as its id. A
//! value that also `inc`s (`show(inc(n, _), get(goal, _))`) cannot be
//! evaluated again: each read's cold arm goes on from there on its own
//! ([`Gen::nat_effects_cold`]; an out_arg so too,
//! [`Gen::nat_out_effects_cold`], helper `ncold21`). A conditional next
//! situation whose condition [`super::cold`] cannot give to the machine
//! (it binds a register for the branches) and that only reads is
//! evaluated whole on terms where a read breaks out
//! ([`Gen::nat_if_cold`], `ncold21`), for a global whose type may hold
//! such a value (`ground`, a list, a compound; a number's or an atom's
//! cannot, [`Gen::global_may_not_hold`]). The hot path (the global of its
//! type) is unchanged; a value with no such read is made as before, byte
//! for byte.

use super::{Dm, Regs, N};
use crate::codegen::Gen;
use crate::mir::{Build, Cond, Ev, Next, Reg};
use proc_macro2::{Group, TokenStream, TokenTree};
use quote::{format_ident, quote};
use sitlog_runtime::native::Ty;
use sitlog_syntax::atoms;

impl Gen<'_> {
    /// Next situation `n` of situation `cur` (named `cur_name`) as
    /// [`Gen::nat_next`] makes it, with its global reads' cold arms going
    /// to the machine as above. `None`: nothing to do here (no global
    /// read, a value with an effect, or inside such a block already): the
    /// caller makes it as before.
    pub(super) fn nat_next_cold(
        &self,
        d: &Dm,
        cur: usize,
        n: &Next,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<Option<TokenStream>> {
        let Next::Eval(e) = n else {
            return self.nat_if_cold(d, cur, n, regs, cur_name);
        };
        if !self.cold_reads(d, e, regs) {
            return Ok(None);
        }
        let (vars, redo) = self.cold_terms(e, regs, |t| quote!(let rec_next = #t;))?;
        let code = self.nat_next_breaking(d, cur, n, regs, cur_name)?;
        if !code.to_string().contains("nat_cold_next") {
            return Ok(Some(code));
        }
        Ok(Some(Self::cold_next_block(d, code, vars, redo)))
    }
}

impl Gen<'_> {
    /// Conditional next situation `n` of situation `cur` (`nat_next`'s
    /// arguments) whose global read in its condition [`super::cold`]
    /// cannot give to the machine (a condition that binds a register for
    /// the branches, `(get(h, D) == V -> .. D ..)`, or one the evaluator
    /// may change a local in), where nothing in it but reads (conditions
    /// and values without `set`, `inc`, `apply`): that read's cold arm,
    /// and any other's, breaks out, and the whole next situation is
    /// evaluated on terms (the condition by the machine, then the branch
    /// it picks) and handed to the machine, as [`Gen::nat_next_cold`]
    /// does for a value. `None`: made as before (where no read's arm is
    /// the error, it is that code).
    fn nat_if_cold(
        &self,
        d: &Dm,
        cur: usize,
        n: &Next,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<Option<TokenStream>> {
        if !matches!(n, Next::If(..))
            || self.if_cold_off.get()
            || self.global_cold.borrow().is_some()
            || !self.next_reads_only(n)
        {
            return Ok(None);
        }
        // Only a global that may hold such a value (`cold_act`).
        let mut names = Vec::new();
        self.next_gets(d, n, &mut names);
        if !names.into_iter().any(|g| self.global_may_not_hold(g)) {
            return Ok(None);
        }
        self.if_cold_off.set(true);
        let before = self.nat_next(d, cur, n, regs, cur_name);
        self.if_cold_off.set(false);
        let before = before?;
        if !before
            .to_string()
            .contains("a global's value native code cannot hold")
        {
            return Ok(Some(before));
        }
        let Ok((vars, redo)) = self.cold_next_terms(n, regs) else {
            return Ok(Some(before));
        };
        let code = self.nat_next_breaking(d, cur, n, regs, cur_name)?;
        Ok(Some(Self::cold_next_block(d, code, vars, redo)))
    }

    /// Whether evaluating next situation `n` only reads: its conditions
    /// change nothing ([`Gen::cond_pure`]), its values only read
    /// ([`reads_only`]).
    fn next_reads_only(&self, n: &Next) -> bool {
        match n {
            Next::Static(..) => true,
            Next::Eval(e) => reads_only(e),
            Next::If(c, a, b) => {
                self.cond_pure(c, None) && self.next_reads_only(a) && self.next_reads_only(b)
            }
        }
    }

    /// The globals next situation `n` reads with `get` (a name that is no
    /// local of DM `d`), in a value or a condition.
    fn next_gets(&self, d: &Dm, n: &Next, out: &mut Vec<sitlog_syntax::Atom>) {
        let mut builds = Vec::new();
        let mut evs = Vec::new();
        next_parts(n, &mut builds, &mut evs);
        for e in evs {
            if let Ev::VarOp { op, name, .. } | Ev::VarOpFresh { op, name, .. } = e {
                if *op == atoms::GET && !d.declares_local(*name) {
                    out.push(*name);
                }
            }
        }
        while let Some(b) = builds.pop() {
            if let Build::Compound(f, args) = b {
                if *f == atoms::GET && args.len() == 2 {
                    if let Build::Const(t) = &args[0] {
                        if let Some(g) = self.store.atom_of(*t).filter(|g| !d.declares_local(*g)) {
                            out.push(g);
                        }
                    }
                }
                builds.extend(args.iter());
            }
        }
    }

    /// Next situation `n` evaluated on terms (`super::cold_act`'s
    /// `next_term`; the value `rec_next`): the statements making the
    /// variables it reads unset (a register the condition binds, made
    /// there) and the evaluation.
    pub(super) fn cold_next_terms(
        &self,
        n: &Next,
        regs: &Regs,
    ) -> N<(Option<TokenStream>, TokenStream)> {
        let _no_new = super::cold_act::NoNewPatterns::set(&self.no_new_patterns);
        let mut mregs = regs.clone();
        let mut all = Vec::new();
        next_regs(n, &mut all);
        for r in &all {
            mregs
                .entry(*r)
                .or_insert_with(|| (format_ident!("fresh_r{}", r), Ty::Term));
        }
        let mut binds = Vec::new();
        super::next_binds(n, &mut binds);
        for r in &binds {
            mregs.insert(*r, (format_ident!("fresh_r{}", r), Ty::Term));
        }
        let mut ts = Vec::new();
        let mut k = 0;
        let t = self.next_term(n, &mregs, &mut ts, &mut k)?;
        let mut fresh = std::collections::BTreeSet::new();
        let redo = super::cold::cold_fresh(quote!(#(#ts)* let rec_next = #t;), &mut fresh);
        let bound: Vec<String> = binds.iter().map(|r| format!("cold_r{r}")).collect();
        fresh.retain(|x| !bound.contains(&x.to_string()));
        let vars = (!fresh.is_empty()).then(|| {
            let fresh = fresh.iter();
            quote!(let [#(#fresh),*] = cx.vars();)
        });
        Ok((vars, redo))
    }
}

impl Gen<'_> {
    /// Whether `e` reads a global and does nothing else than read
    /// ([`reads_only`]), outside a block of another cold arm, and is made
    /// on terms ([`Gen::cold_terms`]): its global reads' cold arms may go
    /// to the machine, which evaluates `e` again.
    pub(super) fn cold_reads(&self, d: &Dm, e: &Ev, regs: &Regs) -> bool {
        let global_get = |op: sitlog_syntax::Atom, v: sitlog_syntax::Atom| {
            op == atoms::GET && !d.declares_local(v)
        };
        self.global_cold.borrow().is_none()
            && super::has_var_op(e, &global_get)
            && reads_only(e)
            && self.cold_terms(e, regs, |_| quote!()).is_ok()
    }

    /// `e` evaluated on terms as the term code does ([`Gen::nat_ev_term`]),
    /// its value given to `then`: the statements making the fresh
    /// variables it reads (`cold_r<n>`, made there, not at every visit),
    /// and the evaluation.
    fn cold_terms(
        &self,
        e: &Ev,
        regs: &Regs,
        then: impl FnOnce(&TokenStream) -> TokenStream,
    ) -> N<(Option<TokenStream>, TokenStream)> {
        // A `get` into a fresh variable binds a term made there; any
        // other fresh variable it reads (`get(goal, _)`'s `_` where the
        // MIR gives it a register) is made here.
        let mut mregs = regs.clone();
        let mut binds = Vec::new();
        super::ev_binds(e, &mut binds);
        for r in &binds {
            mregs.insert(*r, (format_ident!("fresh_r{}", r), Ty::Term));
        }
        let mut ts = Vec::new();
        let mut n = 0;
        let t = self.nat_ev_term(e, &mregs, &mut ts, &mut n)?;
        let then = then(&t);
        let mut fresh = std::collections::BTreeSet::new();
        let redo = super::cold::cold_fresh(quote!(#(#ts)* #then), &mut fresh);
        let bound: Vec<String> = binds.iter().map(|r| format!("cold_r{r}")).collect();
        fresh.retain(|x| !bound.contains(&x.to_string()));
        let vars = (!fresh.is_empty()).then(|| {
            let fresh = fresh.iter();
            quote!(let [#(#fresh),*] = cx.vars();)
        });
        Ok((vars, redo))
    }

    /// An out_arg `e` computed after next situation `next_at` by `body`
    /// (its statements, the pipe set), whose global reads were made with
    /// `break 'nat_cold_out` as their cold arm ([`Gen::cold_reads`]): the
    /// `Nat` of `next_at`, or, where a read broke out (the machine
    /// entered in situation `cur`), the out_arg evaluated on terms and
    /// `next_at` handed to the machine as its id.
    pub(super) fn nat_out_cold(
        &self,
        d: &Dm,
        e: &Ev,
        regs: &Regs,
        body: TokenStream,
    ) -> N<TokenStream> {
        let (vars, redo) = self.cold_terms(e, regs, |t| quote!(cx.out_value(#t);))?;
        let tail = super::goto_tail(&d.rec.borrow());
        Ok(quote! {
            'nat_out: {
                'nat_cold_out: {
                    #body
                    break 'nat_out next_at;
                }
                // A global's value native code cannot hold: the machine's.
                #vars
                #redo
                cx.count_transitions(count);
                let rec_next = next_at.id_term(p, cx.store());
                #tail
            }
        })
    }
}

impl Gen<'_> {
    /// Whether next situation `e` (a value with an effect, an `inc`,
    /// beside a global read: `show(inc(n, _), get(goal, _))`) can have its
    /// global reads' cold arms made by [`Gen::nat_effects_cold`]: its
    /// variable operations are `get`s and `inc`s, nothing else evaluated.
    pub(super) fn cold_effects(&self, d: &Dm, e: &Ev) -> bool {
        let global_get = |op: sitlog_syntax::Atom, v: sitlog_syntax::Atom| {
            op == atoms::GET && !d.declares_local(v)
        };
        self.global_cold.borrow().is_none() && super::has_var_op(e, &global_get) && gets_and_incs(e)
    }

    /// The statements `pre` computing next situation `e`'s `get`s and
    /// `inc`s ([`Gen::nat_ev_effects`], prefix `pfx`: the `k`-th operation
    /// in the evaluator's order is `pre[k]`, binding `<pfx><k>`), made with
    /// `break 'nat_cold_next` as their global reads' cold arm
    /// ([`Gen::cold_effects`]): each such arm is made the machine's way on
    /// from there (the machine entered by the read's cold arm, its value
    /// `t`): `e` built as a term, the operations before the `k`-th their
    /// values (an `inc` done is not done again), the `k`-th `t`, the later
    /// ones the machine's, in that order; then handed to the machine as
    /// the next situation.
    pub(super) fn nat_effects_cold(
        &self,
        d: &Dm,
        e: &Ev,
        regs: &Regs,
        pre: Vec<TokenStream>,
        pfx: &str,
    ) -> N<Vec<TokenStream>> {
        let out = d.out.borrow().clone();
        let tail = super::goto_tail(&d.rec.borrow());
        let then = |t: &TokenStream| quote!(let rec_next = #t;);
        let after = quote! {
            cx.count_transitions(count);
            #out
            #tail
        };
        self.effects_cold(e, regs, pre, pfx, &then, &after)
    }

    /// An out_arg `e` computed after next situation `next_at` (a value
    /// with an effect beside a global read, [`Gen::cold_effects`]: `f(inc(n,
    /// _), get(goal, _))`) by the statements `pre` as
    /// [`Gen::nat_effects_cold`] takes them: each read's cold arm
    /// evaluates the out_arg the machine's way on from there
    /// (`Cx::out_value`) and hands `next_at` to the machine as its id, as
    /// [`Gen::nat_out_cold`] does.
    pub(super) fn nat_out_effects_cold(
        &self,
        d: &Dm,
        e: &Ev,
        regs: &Regs,
        pre: Vec<TokenStream>,
    ) -> N<Vec<TokenStream>> {
        let tail = super::goto_tail(&d.rec.borrow());
        let then = |t: &TokenStream| quote!(cx.out_value(#t););
        let after = quote! {
            cx.count_transitions(count);
            let rec_next = next_at.id_term(p, cx.store());
            #tail
        };
        self.effects_cold(e, regs, pre, "out", &then, &after)
    }

    /// [`Gen::nat_effects_cold`]'s statements, each cold arm ending with
    /// `then` of the value's term (its fresh variables made there) and
    /// `after`.
    fn effects_cold(
        &self,
        e: &Ev,
        regs: &Regs,
        pre: Vec<TokenStream>,
        pfx: &str,
        then: &dyn Fn(&TokenStream) -> TokenStream,
        after: &TokenStream,
    ) -> N<Vec<TokenStream>> {
        pre.into_iter()
            .enumerate()
            .map(|(k, stmt)| {
                if !stmt.to_string().contains("nat_cold_next") {
                    return Ok(stmt);
                }
                let mut ts = Vec::new();
                let (mut n, mut op) = (0, 0);
                let t = self.cold_op_term(e, regs, (k, pfx), &mut op, &mut ts, &mut n)?;
                let mut fresh = std::collections::BTreeSet::new();
                let then = then(&t);
                let redo = super::cold::cold_fresh(quote!(#(#ts)* #then), &mut fresh);
                let vars = (!fresh.is_empty()).then(|| {
                    let fresh = fresh.iter();
                    quote!(let [#(#fresh),*] = cx.vars();)
                });
                let cold = quote! {{
                    // A global's value native code cannot hold: the machine's.
                    #vars
                    #redo
                    #after
                }};
                Ok(replace_break(stmt, &cold))
            })
            .collect()
    }

    /// `e` as a term for [`Gen::nat_effects_cold`]'s `k`-th operation's
    /// cold arm (`op` counts the operations met, in the evaluator's order).
    fn cold_op_term(
        &self,
        e: &Ev,
        regs: &Regs,
        (k, pfx): (usize, &str),
        op: &mut usize,
        ts: &mut Vec<TokenStream>,
        n: &mut usize,
    ) -> N<TokenStream> {
        let made = match e {
            Ev::Compound(f, args) => {
                let args = args
                    .iter()
                    .map(|a| self.cold_op_term(a, regs, (k, pfx), op, ts, n))
                    .collect::<N<Vec<_>>>()?;
                let f = self.functor_native(*f)?;
                quote!(cx.build(#f, &[#(#args),*]))
            }
            Ev::VarOp { op: o, name, .. } | Ev::VarOpFresh { op: o, name, .. } => {
                let j = *op;
                *op += 1;
                if j == k {
                    return Ok(quote!(t));
                }
                if j < k {
                    let v = format_ident!("{}{}", pfx, j);
                    quote!(cx.term(&#v))
                } else {
                    let (o, name) = (self.atom_native(*o)?, self.atom_native(*name)?);
                    quote!(cx.var_op_fresh(#o, #name, arc_at)?)
                }
            }
            e => return self.nat_ev_term(e, regs, ts, n),
        };
        let x = format_ident!("b{}", *n);
        *n += 1;
        ts.push(quote!(let #x = #made;));
        Ok(quote!(#x))
    }
}

/// `code` with each `break 'nat_cold_next` replaced by `by`.
fn replace_break(code: TokenStream, by: &TokenStream) -> TokenStream {
    let mut out: Vec<TokenTree> = Vec::new();
    let mut it = code.into_iter().peekable();
    while let Some(t) = it.next() {
        match t {
            TokenTree::Ident(i) if i == "break" => {
                let mut look = it.clone();
                let is_label = matches!(look.next(), Some(TokenTree::Punct(p)) if p.as_char() == '\'')
                    && matches!(look.next(), Some(TokenTree::Ident(l)) if l == "nat_cold_next");
                if is_label {
                    it.next();
                    it.next();
                    out.extend(by.clone());
                } else {
                    out.push(TokenTree::Ident(i));
                }
            }
            TokenTree::Group(g) => {
                let mut h = Group::new(g.delimiter(), replace_break(g.stream(), by));
                h.set_span(g.span());
                out.push(TokenTree::Group(h));
            }
            t => out.push(t),
        }
    }
    out.into_iter().collect()
}

/// Whether `e`'s parts are values, constants, compounds of them, `get`s
/// and `inc`s.
fn gets_and_incs(e: &Ev) -> bool {
    match e {
        Ev::Value(_) | Ev::Built(_) => true,
        Ev::Compound(_, args) => args.iter().all(gets_and_incs),
        Ev::VarOp { op, .. } | Ev::VarOpFresh { op, .. } => *op == atoms::GET || *op == atoms::INC,
        _ => false,
    }
}

/// Whether evaluating `e` only reads: values, constants, compounds of
/// them and `get`s (evaluated again, nothing changes).
fn reads_only(e: &Ev) -> bool {
    match e {
        Ev::Value(_) | Ev::Built(_) => true,
        Ev::Compound(_, args) => args.iter().all(reads_only),
        Ev::VarOp { op, .. } | Ev::VarOpFresh { op, .. } => *op == atoms::GET,
        _ => false,
    }
}

/// The registers next situation `n` reads or binds.
fn next_regs(n: &Next, out: &mut Vec<Reg>) {
    match n {
        Next::Static(..) => {}
        Next::Eval(e) => ev_regs(e, out),
        Next::If(c, a, b) => {
            cond_regs(c, out);
            next_regs(a, out);
            next_regs(b, out);
        }
    }
}

fn cond_regs(c: &Cond, out: &mut Vec<Reg>) {
    match c {
        Cond::Arith(_, l, r) => {
            ev_regs(l, out);
            ev_regs(r, out);
        }
        Cond::Other(b) => build_regs(b, out),
        Cond::Cmp(_, l, r) => {
            build_regs(l, out);
            build_regs(r, out);
        }
        Cond::And(a, b) | Cond::Or(a, b) => {
            cond_regs(a, out);
            cond_regs(b, out);
        }
    }
}

fn ev_regs(e: &Ev, out: &mut Vec<Reg>) {
    match e {
        Ev::Value(r) => out.push(*r),
        Ev::Built(b) | Ev::Eval(b) => build_regs(b, out),
        Ev::If(c, a, b) | Ev::Pick(c, a, b) => {
            cond_regs(c, out);
            ev_regs(a, out);
            ev_regs(b, out);
        }
        Ev::VarOpFresh { dst, .. } => out.push(*dst),
        Ev::VarOp { arg, .. } => build_regs(arg, out),
        Ev::IsFresh { expr, dst } | Ev::BindFresh { expr, dst } => {
            build_regs(expr, out);
            out.push(*dst);
        }
        Ev::Is { lhs, expr } => {
            build_regs(lhs, out);
            build_regs(expr, out);
        }
        Ev::Compound(_, args) => args.iter().for_each(|a| ev_regs(a, out)),
    }
}

fn build_regs(b: &Build, out: &mut Vec<Reg>) {
    match b {
        Build::Reg(r) => out.push(*r),
        Build::Const(_) => {}
        Build::Compound(_, args) => args.iter().for_each(|a| build_regs(a, out)),
    }
}

/// Every build and every expression of next situation `n`, at any depth
/// of its conditions and values (not inside a build).
fn next_parts<'a>(n: &'a Next, builds: &mut Vec<&'a Build>, evs: &mut Vec<&'a Ev>) {
    fn cond<'a>(c: &'a Cond, builds: &mut Vec<&'a Build>, evs: &mut Vec<&'a Ev>) {
        match c {
            Cond::Arith(_, l, r) => {
                ev(l, builds, evs);
                ev(r, builds, evs);
            }
            Cond::Other(b) => builds.push(b),
            Cond::Cmp(_, l, r) => builds.extend([l, r]),
            Cond::And(a, b) | Cond::Or(a, b) => {
                cond(a, builds, evs);
                cond(b, builds, evs);
            }
        }
    }
    fn ev<'a>(e: &'a Ev, builds: &mut Vec<&'a Build>, evs: &mut Vec<&'a Ev>) {
        evs.push(e);
        match e {
            Ev::Built(b) | Ev::Eval(b) => builds.push(b),
            Ev::If(c, a, b) | Ev::Pick(c, a, b) => {
                cond(c, builds, evs);
                ev(a, builds, evs);
                ev(b, builds, evs);
            }
            Ev::VarOp { arg, .. } => builds.push(arg),
            Ev::IsFresh { expr, .. } | Ev::BindFresh { expr, .. } => builds.push(expr),
            Ev::Is { lhs, expr } => builds.extend([lhs, expr]),
            Ev::Compound(_, args) => args.iter().for_each(|a| ev(a, builds, evs)),
            Ev::Value(_) | Ev::VarOpFresh { .. } => {}
        }
    }
    match n {
        Next::Static(..) => {}
        Next::Eval(e) => ev(e, builds, evs),
        Next::If(c, a, b) => {
            cond(c, builds, evs);
            next_parts(a, builds, evs);
            next_parts(b, builds, evs);
        }
    }
}

impl Gen<'_> {
    /// Next situation `n` made with every global read's cold arm breaking
    /// out to `'nat_cold_next` ([`Gen::cold_next_block`]).
    fn nat_next_breaking(
        &self,
        d: &Dm,
        cur: usize,
        n: &Next,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<TokenStream> {
        let saved = self.global_cold.replace(Some(quote!(break 'nat_cold_next)));
        let code = self.nat_next(d, cur, n, regs, cur_name);
        *self.global_cold.borrow_mut() = saved;
        code
    }

    /// `code` ([`Gen::nat_next_breaking`]'s) in its block: where a read
    /// breaks out, the next situation evaluated on terms (`vars`, `redo`)
    /// and handed to the machine, with the transition counted.
    fn cold_next_block(
        d: &Dm,
        code: TokenStream,
        vars: impl quote::ToTokens,
        redo: impl quote::ToTokens,
    ) -> TokenStream {
        let out = d.out.borrow().clone();
        let tail = super::goto_tail(&d.rec.borrow());
        quote! {
            'nat_next: {
                'nat_cold_next: {
                    break 'nat_next #code;
                }
                // A global's value native code cannot hold: the machine's.
                #vars
                #redo
                cx.count_transitions(count);
                #out
                #tail
            }
        }
    }
}
