//! Terms native code builds in one call: a term of native values, fresh
//! variables and constants with two compounds or more (an action's
//! `say(apply(words(_), [[.., Name]]))`, an evaluated call's term) is a
//! constant of the program, its *pattern*, with `'$hole'(i)` where value
//! `i` goes, filled at run time by `Cx::fill` (one line) instead of one
//! `cx.build` statement per compound. The term built is the one the
//! statements built: each compound with a value below it made as
//! `Cx::build` makes it, the values made terms as `Cx::term` makes them,
//! the rest ground and shared with the constant. A situation's compound
//! id is filled so too, from a pattern with a hole per field
//! (`nat_id_fill`: `Cx::fill`, or `machine::fill` in `Nat::id_term`),
//! even with one compound. A pattern whose text does not read back as
//! itself, or whose constants name `'$hole'`, is not used (the
//! statements are generated as before; for an id, the DM's `id_s<N>`).

use super::{Dm, Regs, N};
use crate::codegen::Gen;
use crate::mir::{Build, Ev};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use sitlog_runtime::{Store, Term, Value};
use sitlog_syntax::{atoms, Atom};
use std::collections::HashMap;

/// A pattern: compounds of constants and holes.
enum Pat {
    Node(Atom, Vec<Pat>),
    Const(Term),
    Hole(usize),
}

/// What a pattern's holes are filled with: the expressions (`&r5`,
/// `&fresh_r2`, `&b7`), a register's once.
#[derive(Default)]
struct Holes {
    exprs: Vec<TokenStream>,
    by_text: HashMap<String, usize>,
}

impl Holes {
    fn hole(&mut self, e: TokenStream) -> Pat {
        let key = e.to_string();
        if let Some(&i) = self.by_text.get(&key) {
            return Pat::Hole(i);
        }
        self.by_text.insert(key, self.exprs.len());
        self.exprs.push(e);
        Pat::Hole(self.exprs.len() - 1)
    }
}

fn compounds(p: &Pat) -> usize {
    match p {
        Pat::Node(_, args) if !args.is_empty() => 1 + args.iter().map(compounds).sum::<usize>(),
        _ => 0,
    }
}

impl Gen<'_> {
    /// `b` (a compound) built by one `cx.fill` when it has two compounds
    /// or more: the statement pushed to `ts`, its local returned; `None`
    /// to build it as before.
    pub(super) fn nat_fill_build(
        &self,
        b: &Build,
        regs: &Regs,
        ts: &mut Vec<TokenStream>,
        n: &mut usize,
    ) -> N<Option<TokenStream>> {
        let mut holes = Holes::default();
        let pat = self.build_pat(b, regs, &mut holes)?;
        Ok(self.fill_stmt(&pat, holes, ts, n))
    }

    /// [`Gen::nat_fill_build`] of an evaluated compound (`Ev::Compound`):
    /// its parts that are not built (an evaluation, a `get`) computed
    /// first, in order, each a hole.
    pub(super) fn nat_fill_ev(
        &self,
        e: &Ev,
        regs: &Regs,
        ts: &mut Vec<TokenStream>,
        n: &mut usize,
    ) -> N<Option<TokenStream>> {
        // A trial on a copy of the statements: a pattern not used leaves
        // them as they were.
        let mut trial = ts.clone();
        let mut m = *n;
        let mut holes = Holes::default();
        let pat = self.ev_pat(e, regs, &mut holes, &mut trial, &mut m)?;
        if compounds(&pat) < 2 {
            return Ok(None);
        }
        let Some(x) = self.fill_stmt(&pat, holes, &mut trial, &mut m) else {
            return Ok(None);
        };
        *ts = trial;
        *n = m;
        Ok(Some(x))
    }

    fn build_pat(&self, b: &Build, regs: &Regs, holes: &mut Holes) -> N<Pat> {
        Ok(match b {
            Build::Const(t) => Pat::Const(*t),
            Build::Reg(r) => {
                let (v, _) = regs.get(r).ok_or(format!("register r{r} is read unset"))?;
                holes.hole(quote!(&#v))
            }
            Build::Compound(f, args) => Pat::Node(
                *f,
                args.iter()
                    .map(|a| self.build_pat(a, regs, holes))
                    .collect::<N<Vec<_>>>()?,
            ),
        })
    }

    fn ev_pat(
        &self,
        e: &Ev,
        regs: &Regs,
        holes: &mut Holes,
        ts: &mut Vec<TokenStream>,
        n: &mut usize,
    ) -> N<Pat> {
        match e {
            Ev::Value(r) => self.build_pat(&Build::Reg(*r), regs, holes),
            Ev::Built(b) => self.build_pat(b, regs, holes),
            Ev::Compound(f, args) => Ok(Pat::Node(
                *f,
                args.iter()
                    .map(|a| self.ev_pat(a, regs, holes, ts, n))
                    .collect::<N<Vec<_>>>()?,
            )),
            other => {
                let x = self.nat_ev_term(other, regs, ts, n)?;
                Ok(holes.hole(quote!(&#x)))
            }
        }
    }

    /// `let bN = cx.fill(p.k[I], &[..]);` of a pattern with two compounds
    /// or more whose text reads back as itself (registered as constant
    /// `I`), pushed to `ts`; `None` otherwise.
    fn fill_stmt(
        &self,
        pat: &Pat,
        holes: Holes,
        ts: &mut Vec<TokenStream>,
        n: &mut usize,
    ) -> Option<TokenStream> {
        if compounds(pat) < 2 {
            return None;
        }
        let k = self.pattern_const(pat)?;
        let x = format_ident!("b{}", *n);
        *n += 1;
        let hs = holes.exprs;
        ts.push(quote!(let #x = cx.fill(p.k #k, &[#(#hs),*]);));
        Some(quote!(#x))
    }

    /// The constant of a pattern (`[I]`, constant `I` of the program) when
    /// its text reads back as itself.
    fn pattern_const(&self, pat: &Pat) -> Option<TokenStream> {
        let mut text = String::new();
        if !self.pat_text(pat, &mut text) {
            return None;
        }
        let mut scratch = Store::new();
        let (back, _) = scratch.parse(&text).ok()?;
        if !self.pat_reads_back(pat, &scratch, back) {
            return None;
        }
        self.pattern_if(text).map(Self::const_index)
    }

    /// Situation `ix`'s id built by `machine::fill` from its pattern, the
    /// id's variables the holes (`params`, in order: the fields it is built
    /// from, references where `refs`, else owned); `None` when the pattern
    /// does not fit.
    pub(super) fn nat_id_fill(
        &self,
        d: &Dm,
        ix: usize,
        params: &[Ident],
        store: &TokenStream,
        refs: bool,
    ) -> Option<TokenStream> {
        let id = self.nat_id_of(d, ix);
        let pat = self.id_pat(d, ix, id, &mut Vec::new(), params)?;
        let k = self.pattern_const(&pat)?;
        let args = params
            .iter()
            .map(|r| if refs { quote!(#r) } else { quote!(&#r) });
        if store.to_string() == quote!(cx.store()).to_string() {
            return Some(quote!(cx.fill(p.k #k, &[#(#args),*])));
        }
        Some(quote!(machine::fill(#store, p.k #k, &[#(#args),*])))
    }

    fn id_pat(
        &self,
        d: &Dm,
        ix: usize,
        t: Term,
        path: &mut Vec<usize>,
        params: &[Ident],
    ) -> Option<Pat> {
        Some(match self.store.value(t) {
            Value::Var(_) => {
                // A repeated variable: its first occurrence's field.
                let r = match Self::nat_id_reg(d, ix, path) {
                    Some(r) => r,
                    None => self.nat_first_reg(d, ix, t).ok()?,
                };
                let r = super::reg(r);
                Pat::Hole(params.iter().position(|p| *p == r)?)
            }
            Value::Compound(f, args) => {
                let args = args.to_vec();
                let mut parts = Vec::new();
                for (i, a) in args.into_iter().enumerate() {
                    path.push(i);
                    parts.push(self.id_pat(d, ix, a, path, params)?);
                    path.pop();
                }
                Pat::Node(f, parts)
            }
            Value::Atom(_) | Value::Int(_) => Pat::Const(t),
            _ => return None,
        })
    }

    /// The pattern's `writeq`-style text (lists in list notation, a
    /// compound constant in parentheses); `false` when a constant in it
    /// names `'$hole'`.
    fn pat_text(&self, pat: &Pat, out: &mut String) -> bool {
        match pat {
            Pat::Node(f, args) if args.is_empty() => {
                out.push_str(&self.store.writeq(Term::atom(*f)))
            }
            Pat::Node(f, args) if *f == atoms::DOT && args.len() == 2 => {
                out.push('[');
                let mut cell = pat;
                let mut first = true;
                while let Pat::Node(f, args) = cell {
                    if *f != atoms::DOT || args.len() != 2 {
                        break;
                    }
                    if !first {
                        out.push(',');
                    }
                    first = false;
                    if !self.pat_text(&args[0], out) {
                        return false;
                    }
                    cell = &args[1];
                }
                let nil = match cell {
                    Pat::Const(t) => match self.store.value(*t) {
                        Value::Atom(a) => a == atoms::NIL,
                        // A constant list's elements go on the pattern's.
                        Value::Compound(f, _) if f == atoms::DOT => {
                            let s = self.store.writeq(*t);
                            if s.contains("$hole") || !s.starts_with('[') {
                                return false;
                            }
                            out.push(',');
                            out.push_str(&s[1..]);
                            return true;
                        }
                        _ => false,
                    },
                    Pat::Node(f, args) => *f == atoms::NIL && args.is_empty(),
                    Pat::Hole(_) => false,
                };
                if !nil {
                    out.push('|');
                    if !self.pat_text(cell, out) {
                        return false;
                    }
                }
                out.push(']');
            }
            Pat::Node(f, args) => {
                out.push_str(&self.store.writeq(Term::atom(*f)));
                out.push('(');
                for (i, a) in args.iter().enumerate() {
                    if i > 0 {
                        out.push(',');
                    }
                    if !self.pat_text(a, out) {
                        return false;
                    }
                }
                out.push(')');
            }
            Pat::Const(t) => {
                let s = self.store.writeq(*t);
                if s.contains("$hole") {
                    return false;
                }
                let bare =
                    !matches!(self.store.value(*t), Value::Compound(..)) || s.starts_with('[');
                if bare {
                    out.push_str(&s);
                } else {
                    out.push('(');
                    out.push_str(&s);
                    out.push(')');
                }
            }
            Pat::Hole(i) => out.push_str(&format!("'$hole'({i})")),
        }
        true
    }

    /// Whether `t` (the pattern's text read) is the pattern.
    fn pat_reads_back(&self, pat: &Pat, sc: &Store, t: Term) -> bool {
        match (pat, sc.value(t)) {
            (Pat::Node(f, args), Value::Atom(a)) if args.is_empty() => a == *f,
            (Pat::Node(f, args), Value::Compound(g, ts)) if g == *f && ts.len() == args.len() => {
                let ts = ts.to_vec();
                args.iter()
                    .zip(ts)
                    .all(|(a, t)| self.pat_reads_back(a, sc, t))
            }
            (Pat::Const(c), _) => {
                crate::codegen::same_term(self.store, *c, sc, t, &mut HashMap::new())
            }
            (Pat::Hole(i), Value::Compound(g, [x])) if g.as_str() == "$hole" => {
                sc.int_of(*x) == Some(*i as i64)
            }
            _ => false,
        }
    }
}

/// The holes `holes` of a `cx.fill`/`cx.build_of` call (`&[&r5, r6]`) as
/// a call that takes them lazily wants them (the runtime's `Holes`): a
/// tuple of references, `(&r5, r6)`, `(&r3,)` or `()`, which a gated call
/// keeps in registers where a slice of `&dyn AsTerm` is built in memory
/// before its test (issue 37); with more holes than a tuple takes, the
/// array with its first element cast (`&[&r1 as &dyn machine::AsTerm,
/// ..]`). Anything not an array reference is given back as it is.
pub(super) fn holes_tuple(holes: &TokenStream) -> TokenStream {
    let Ok(syn::Expr::Reference(r)) = syn::parse2::<syn::Expr>(holes.clone()) else {
        return holes.clone();
    };
    let syn::Expr::Array(arr) = &*r.expr else {
        return holes.clone();
    };
    let elems: Vec<&syn::Expr> = arr.elems.iter().collect();
    match elems.as_slice() {
        [] => quote!(()),
        [one] => quote!((#one,)),
        many if many.len() <= sitlog_runtime::machine::TUPLE_HOLES => quote!((#(#many),*)),
        [first, rest @ ..] => quote!(&[#first as &dyn machine::AsTerm, #(#rest),*]),
    }
}

#[cfg(test)]
mod holes_tests {
    use super::holes_tuple;
    use quote::quote;

    #[test]
    fn holes_become_a_tuple_of_references() {
        let t = |h: proc_macro2::TokenStream| holes_tuple(&h).to_string();
        assert_eq!(t(quote!(&[])), quote!(()).to_string());
        assert_eq!(t(quote!(&[&r3])), quote!((&r3,)).to_string());
        assert_eq!(
            t(quote!(&[&r5, r6, &r7])),
            quote!((&r5, r6, &r7)).to_string()
        );
        assert_eq!(t(quote!(holes)), quote!(holes).to_string());
        let many: Vec<_> = (0..13u32)
            .map(|i| quote::format_ident!("r{}", i.to_string()))
            .collect();
        let out = t(quote!(&[#(&#many),*]));
        let first = quote!(&r0 as &dyn machine::AsTerm).to_string();
        assert!(out.contains(&first) && out.starts_with('&') && out.ends_with(']'));
    }
}
