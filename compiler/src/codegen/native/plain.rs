//! Plain user functions called on native values (issue 37): a next
//! situation `apply(f(_, ..), [A1, .., An])` and a condition
//! `apply(f(_, ..), [..]) == k` (`\==`, `k` an atom or an integer) whose
//! function the build takes for plain (`sitlog_runtime::plain::plain_names`
//! over the application's Prolog files) call `Cx::nat_plain` on the
//! values native code holds; the value it returns is selected natively
//! ([`Gen::nat_select`] per name and arity of the DM's situations, the
//! arguments as `ground` values) or compared with `k` in Rust. `None` (the
//! run's engine does not run the call natively: not plain there, an
//! argument or value the native form refuses, ...) takes the code this
//! replaced, the `apply` evaluated as a term, so every answer and error
//! stays the evaluator's. A function compiled to Rust (`plain_rs`) is
//! called on the values by reference (a `Val` held, without a copy); one
//! that answers a compound answers it by its parts (`plain_rs::Ans<k>`):
//! a situation of that name and arity is selected from them, the value
//! never built (built only where no situation takes it, for the machine,
//! and for an out_arg's term).
//!
//! Taken only where that is the same call: a DM without locals (the call
//! sees the globals only), every declared argument of `f` a distinct fresh
//! variable and as many values as arguments (each takes its value, D-37),
//! every value a register of a native type or an atom or integer constant
//! (they evaluate to themselves; the runtime refuses a value L would
//! evaluate otherwise).
//!
//! The fresh variables only the term path reads (the `apply`'s declared
//! `_`s) are made in its arm ([`cold_arm`]), not at every visit: the
//! value computed natively never reads them (D-37: the caller's declared
//! variables stay unbound), so a visit whose call runs natively makes no
//! variable.

use super::plain_rs::Answers;
use super::{coerce, Dm, Regs, N, V};
use crate::codegen::Gen;
use crate::mir::{Build, Cond, Next};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::native::Ty;
use sitlog_runtime::Value;
use sitlog_syntax::{atoms, Atom};
use std::collections::BTreeSet;

impl Gen<'_> {
    /// Whether the build takes `name/arity` for a plain function.
    fn knows_plain(&self, name: Atom, arity: usize) -> bool {
        self.plain_forms().iter().any(|(k, _)| *k == (name, arity))
    }

    /// `cx.nat_plain(f, &[..])` for `b` = `apply(f(_, ..), [A1..An])` as
    /// the module doc takes it, else `None`; with the answers' type of the
    /// compiled function it calls (`None`: a `Val`).
    pub(super) fn nat_plain_call(
        &self,
        d: &Dm,
        b: &Build,
        regs: &Regs,
        at: Option<usize>,
    ) -> N<Option<(TokenStream, Option<Answers>)>> {
        // A DM with locals: only where the term path hands the frames
        // over (`at`, the situation), the locals held natively, each an
        // int, a float or an atom (a query sends them; these are never
        // too deep for it) or a `Val` checked at the call
        // (`rt::local_sure`).
        let scalar = |ty: &Ty| matches!(ty, Ty::Int | Ty::Float | Ty::Sym);
        let locals = !(d.locals.is_empty() && d.dm.locals.is_empty());
        if locals
            && !(at.is_some()
                && d.locals_ok
                && d.locals.len() == d.dm.locals.len()
                && d.locals
                    .iter()
                    .all(|(_, ty)| scalar(ty) || super::held_as_val(ty)))
        {
            return Ok(None);
        }
        let local_checks: Vec<TokenStream> = d
            .locals
            .iter()
            .enumerate()
            .filter(|(_, (_, ty))| !scalar(ty))
            .map(|(i, _)| {
                let l = format_ident!("l{}", i);
                quote!(::sitlog_runtime::plain::rt::local_sure(&*#l))
            })
            .collect();
        let Build::Compound(apply, parts) = b else {
            return Ok(None);
        };
        let [Build::Compound(name, declared), list] = &parts[..] else {
            return Ok(None);
        };
        if *apply != atoms::APPLY {
            return Ok(None);
        }
        // Each declared argument a fresh variable of its own.
        let mut fresh = Vec::new();
        for a in declared.iter() {
            match a {
                Build::Reg(r)
                    if regs.get(r).is_some_and(|(x, _)| super::is_fresh(x))
                        && !fresh.contains(r) =>
                {
                    fresh.push(*r)
                }
                _ => return Ok(None),
            }
        }
        // The values: a proper list of native registers and atomic constants.
        let mut items = Vec::new();
        let mut cur = list;
        loop {
            match cur {
                Build::Compound(dot, ht) if *dot == atoms::DOT && ht.len() == 2 => {
                    items.push(&ht[0]);
                    cur = &ht[1];
                }
                Build::Const(t) if self.store.atom_of(*t) == Some(atoms::NIL) => break,
                // A constant list of values: not taken apart here.
                _ => return Ok(None),
            }
        }
        if items.len() != declared.len() || !self.knows_plain(*name, declared.len()) {
            return Ok(None);
        }
        let mut vals = Vec::new();
        // Each value a reference too, for the compiled function: a `Val`
        // held, by reference; another, converted in a temporary.
        let mut refs = Vec::new();
        for it in items {
            // `get(l, _)` of a local held natively: its value.
            if let Some((v, l)) = at.and_then(|ix| self.plain_local_get(d, ix, it, regs)) {
                let Ok(e) = coerce(&v, &Ty::Ground) else {
                    return Ok(None);
                };
                // A `Val` held, by reference, for the compiled function.
                refs.push(
                    super::held_as_val(&v.ty)
                        .then(|| quote!(::sitlog_runtime::plain::rt::arg(&*#l))),
                );
                vals.push(e);
                continue;
            }
            let v = match it {
                Build::Reg(r) => match regs.get(r) {
                    Some((x, ty)) if !super::is_fresh(x) && ty.is_native() => {
                        if super::held_as_val(ty) {
                            refs.push(Some(quote!(::sitlog_runtime::plain::rt::arg(&#x))));
                        } else {
                            refs.push(None);
                        }
                        V {
                            e: quote!(#x.clone()),
                            ty: ty.clone(),
                        }
                    }
                    _ => return Ok(None),
                },
                Build::Const(t)
                    if matches!(
                        self.store.value(*t),
                        Value::Atom(_) | Value::Int(_) | Value::Float(_)
                    ) =>
                {
                    refs.push(None);
                    self.nat_value(it, regs)?
                }
                _ => return Ok(None),
            };
            let Ok(e) = coerce(&v, &Ty::Ground) else {
                return Ok(None);
            };
            vals.push(e);
        }
        let f = self.atom_native(*name)?;
        // Compiled to Rust where the generator takes the form (`plain_rs`).
        let guard = |(call, ans): (TokenStream, Option<Answers>)| {
            if local_checks.is_empty() {
                return (call, ans);
            }
            (
                quote!((if #(#local_checks)&&* { #call } else { None })),
                ans,
            )
        };
        Ok(Some(guard(match self.plain_slot(*name, declared.len()) {
            Some(k) => {
                let (form, fun, ans) = self.plain_rs_call(k);
                let k = proc_macro2::Literal::usize_unsuffixed(k);
                let args = refs.into_iter().zip(vals).map(|(r, v)| match r {
                    Some(r) => r,
                    None => quote!(&(#v)),
                });
                (
                    quote!(cx.nat_plain_rs(#k, #f, #form, [#(#args),*], |args| #fun(a, args))),
                    ans,
                )
            }
            None => (quote!(cx.nat_plain(#f, &[#(#vals),*])), None),
        })))
    }

    /// `get(l, V)` as a plain call's value (`b`) in situation `ix`, `l` a
    /// local held in the frame: its value, read natively, where binding
    /// `V` has no other effect (`nat_local_get`'s `unbound`, or a fresh
    /// variable met only there: nothing reads it after).
    fn plain_local_get(&self, d: &Dm, ix: usize, b: &Build, regs: &Regs) -> Option<(V, Ident)> {
        let Build::Compound(op, args) = b else {
            return None;
        };
        let [Build::Const(n), Build::Reg(r)] = &args[..] else {
            return None;
        };
        if *op != atoms::GET || !d.locals_ok {
            return None;
        }
        let taken = self.nat_local_get(d, ix, b).is_some()
            || (regs.get(r).is_some_and(|(x, _)| super::is_fresh(x))
                && super::occurs_once(d, ix, *r));
        if !taken {
            return None;
        }
        let (l, ty) = d.local_field(self.store.atom_of(*n)?)?;
        Some((
            V {
                e: quote!((*#l).clone()),
                ty,
            },
            l,
        ))
    }

    /// A next situation evaluated whole (`b`), a plain call: its value
    /// selected natively, `evaluated` (the term path) where the call gives
    /// `None`. `None` where `b` is not such a call.
    pub(super) fn nat_plain_next(
        &self,
        d: &Dm,
        cur: usize,
        b: &Build,
        regs: &Regs,
        cur_name: &TokenStream,
        evaluated: TokenStream,
    ) -> N<Option<TokenStream>> {
        let Some((call, ans)) = self.nat_plain_call(d, b, regs, Some(cur))? else {
            return Ok(None);
        };
        // Each name and arity a situation of the DM has, once, in order;
        // not `empty`, which ends the DM whatever its situations are
        // called (the machine's `goto` of it, below).
        let mut ids: Vec<(Atom, usize)> = Vec::new();
        for p in d.plans.iter() {
            let cell = p.id == (atoms::DOT, 2);
            if !cell && !ids.contains(&p.id) && p.id != (atoms::EMPTY, 0) {
                ids.push(p.id);
            }
        }
        // A compound answered by its parts: selected from them, its value
        // not built (built where no situation takes it).
        let by_parts = match &ans {
            Some(ans) => {
                let mut arms = Vec::new();
                let mut built = false;
                for (j, &(name, arity)) in ans.shapes.iter().enumerate() {
                    if !ids.contains(&(name, arity)) {
                        built = true;
                        continue;
                    }
                    let v = format_ident!("V{}", j);
                    let (xs, vals) = part_vals(arity);
                    let sel = self.nat_select(d, cur, name, vals, cur_name)?;
                    let e = &ans.name;
                    arms.push(quote! {
                        super::plain_rs::#e::#v(#(#xs),*) => {
                            #(let #xs: &Val = &#xs;)*
                            let next = #sel;
                            break 'plain next;
                        }
                    });
                }
                let e = &ans.name;
                let other = built.then(|| quote!(other => other.val(a),));
                quote! {
                    let pv: Val = match pa {
                        super::plain_rs::#e::Val(pv) => pv,
                        #(#arms)*
                        #other
                    };
                }
            }
            None => quote!(let pv: Val = pa;),
        };
        let mut arms = Vec::new();
        for (name, arity) in ids {
            let a = self.atom_native(name)?;
            if arity == 0 {
                let sel = self.nat_select(d, cur, name, Vec::new(), cur_name)?;
                arms.push(quote!(if pv.sym() == Some(#a) { let next = #sel; break 'plain next; }));
                continue;
            }
            let (xs, vals) = part_vals(arity);
            let sel = self.nat_select(d, cur, name, vals, cur_name)?;
            let n = proc_macro2::Literal::usize_unsuffixed(arity);
            arms.push(quote! {
                if let Some([#(#xs),*]) = pv.args_of(#a, #n) {
                    let next = #sel;
                    break 'plain next;
                }
            });
        }
        // A value no situation's name takes: the machine says so.
        let hand = &d.hand;
        let out = d.out.borrow().clone();
        let tail = super::goto_tail(&d.rec.borrow());
        let curl = proc_macro2::Literal::u32_unsuffixed(cur as u32);
        let evaluated = cold_arm(evaluated);
        Ok(Some(quote! {
            match #call {
                Some(pa) => 'plain: {
                    #by_parts
                    #(#arms)*
                    #hand
                    cx.count_and_enter(count, run.records, #curl, #cur_name);
                    let rec_next = cx.term(&pv);
                    #out
                    #tail
                }
                None => { #evaluated }
            }
        }))
    }

    /// A condition `apply(f(_, ..), [..]) == k` (`\==`; either side), a
    /// plain call: the test of its value in Rust, `None` from the call
    /// deciding by `evaluated` (statements binding `name` on the term
    /// path). `None` where `c` is not such a condition.
    pub(super) fn nat_plain_cond(
        &self,
        d: &Dm,
        c: &Cond,
        regs: &Regs,
        name: &Ident,
        evaluated: impl FnOnce() -> N<Option<TokenStream>>,
    ) -> N<Option<TokenStream>> {
        let Some((call, test)) = self.plain_cond_parts(d, None, c, regs)? else {
            return Ok(None);
        };
        let Some(pre) = evaluated()? else {
            return Ok(None);
        };
        let pre = cold_arm(pre);
        Ok(Some(quote! {
            let #name: bool = match #call {
                Some(pa) => #test,
                None => {
                    #pre
                    #name
                }
            };
        }))
    }

    /// A conditional next situation `n` (`( C -> A ; otherwise -> B )`)
    /// in a DM with locals whose condition `C` is a plain call's test as
    /// [`Gen::nat_plain_cond`] takes it: the test in Rust and `A` or `B`
    /// natively; where the call gives `None`, the native frames handed
    /// over (the locals written back), the machine entered in situation
    /// `cur` and the whole next situation evaluated on terms
    /// (`cold_next`'s `cold_next_terms`), as the term path does: nothing
    /// was done before (the native call changes nothing). `None`: not
    /// such a situation (a DM without locals takes `nat_plain_cond`).
    pub(super) fn nat_plain_if_locals(
        &self,
        d: &Dm,
        cur: usize,
        n: &Next,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<Option<TokenStream>> {
        let Next::If(c, a, b) = n else {
            return Ok(None);
        };
        if d.locals.is_empty() && d.dm.locals.is_empty() {
            return Ok(None);
        }
        let Some((call, test)) = self.plain_cond_parts(d, Some(cur), c, regs)? else {
            return Ok(None);
        };
        let Ok((vars, redo)) = self.cold_next_terms(n, regs) else {
            return Ok(None);
        };
        let a = self.nat_next(d, cur, a, regs, cur_name)?;
        let b = self.nat_next(d, cur, b, regs, cur_name)?;
        let enter = self.nat_enter_to_evaluate(d, cur)?;
        let out = d.out.borrow().clone();
        let tail = super::goto_tail(&d.rec.borrow());
        Ok(Some(quote! {
            match #call {
                Some(pa) => {
                    let cond_value: bool = #test;
                    if cond_value { #a } else { #b }
                }
                None => {
                    #enter
                    #vars
                    #redo
                    cx.count_transitions(count);
                    #out
                    #tail
                }
            }
        }))
    }

    /// The call and the test (of `pa`, its answer) of a condition
    /// `apply(f(_, ..), [..]) == k` (`\==`; either side) whose call
    /// [`Gen::nat_plain_call`] takes (`at` as there).
    fn plain_cond_parts(
        &self,
        d: &Dm,
        at: Option<usize>,
        c: &Cond,
        regs: &Regs,
    ) -> N<Option<(TokenStream, TokenStream)>> {
        let Cond::Other(Build::Compound(op, sides)) = c else {
            return Ok(None);
        };
        let eq = match op.as_str() {
            "==" => true,
            "\\==" => false,
            _ => return Ok(None),
        };
        let [l, r] = &sides[..] else {
            return Ok(None);
        };
        let ((call, ans), k) = match (self.nat_plain_call(d, l, regs, at)?, r) {
            (Some(call), Build::Const(k)) => (call, *k),
            _ => match (l, self.nat_plain_call(d, r, regs, at)?) {
                (Build::Const(k), Some(call)) => (call, *k),
                _ => return Ok(None),
            },
        };
        let test = match self.store.value(k) {
            Value::Atom(a) => {
                let a = self.atom_native(a)?;
                quote!(pv.sym() == Some(#a))
            }
            Value::Int(i) => {
                let i = proc_macro2::Literal::i64_suffixed(i);
                quote!(pv.int() == Some(#i))
            }
            _ => return Ok(None),
        };
        let test = if eq { test } else { quote!(!(#test)) };
        // A compound answered by its parts is not the constant.
        let test = match ans {
            Some(ans) => {
                let e = &ans.name;
                let other = if eq { quote!(false) } else { quote!(true) };
                quote!(match pa {
                    super::plain_rs::#e::Val(pv) => #test,
                    _ => #other,
                })
            }
            None => quote!({
                let pv = pa;
                #test
            }),
        };
        Ok(Some((call, test)))
    }
}

/// The term path's arm `code` of a plain call with the fresh variables it
/// reads (`fresh_r<n>`, the `apply`'s declared `_`s, made at the visit's
/// start otherwise) made at its start instead, renamed `cold_r<n>`
/// (statements, then `code`'s: the caller's block holds them; a
/// use of the same variable elsewhere in the visit still makes its own at
/// the start: the term path's call does not bind it, D-37).
pub(super) fn cold_arm(code: TokenStream) -> TokenStream {
    let mut used = BTreeSet::new();
    super::fresh_used(&code, &mut used);
    let mut renamed = BTreeSet::new();
    let code = super::cold::cold_fresh(code, &mut renamed);
    if used.is_empty() {
        return code;
    }
    let mut cold = BTreeSet::new();
    let made = super::cold::cold_fresh(quote!(#(#used)*), &mut cold);
    let made = made.into_iter();
    quote! {
        let [#(#made),*] = cx.vars();
        #code
    }
}

/// The names `px0`, `px1`, .. of an answer's `arity` parts and their
/// values for a selection (each cloned where a variant takes it).
fn part_vals(arity: usize) -> (Vec<Ident>, Vec<V>) {
    let xs: Vec<Ident> = (0..arity).map(|i| format_ident!("px{}", i)).collect();
    let vals = xs
        .iter()
        .map(|x| V {
            e: quote!(#x.clone()),
            ty: Ty::Ground,
        })
        .collect();
    (xs, vals)
}
