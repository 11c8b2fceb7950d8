//! The selection of a next situation shared per DM: a `'sel` block
//! ([`Gen::nat_select`]) whose candidates are the same code as another
//! block's of the same DM, but for the values they read (`v0`, `v1`, ...,
//! each a reference bound by the block's `let`s), becomes one function of
//! those values (`select_<name>`), called from each block.
//!
//! Invariant: a block is shared only when its code says what the function
//! needs: each `let v<i>` written with its type (the function's parameter
//! type), and candidates that read nothing of the visit but the `v<i>`
//! and the atoms `a` (no register, no `cx`, no label but `'sel` and
//! `'hand`); what falls through the candidates (the hand-over to the
//! machine, its history entry) stays at the block. A block that occurs
//! once in its DM is left as it was, token for token, so code with no
//! repeated selection is generated as before.
//!
//! [`Gen::nat_select`] registers each block's candidates
//! ([`SelSite`]); [`share_selections`] finds them in the DM's finished
//! items (a block generated and then dropped is not counted).

use proc_macro2::{Delimiter, Group, Ident, Spacing, TokenStream, TokenTree as T};
use quote::{format_ident, quote};
use std::collections::HashMap;

/// The candidates of a `'sel` block as generated: their text, how many
/// top-level tokens they are, and the situation they select.
#[derive(Clone)]
pub(super) struct SelSite {
    /// The block's `let`s as text, and each value's type where its
    /// `let` is not written with it (`None`: no native type).
    pub(super) lets: String,
    pub(super) types: Vec<Option<TokenStream>>,
    pub(super) text: String,
    pub(super) len: usize,
    pub(super) name: String,
}

/// A `'sel` block found in the items, split where the candidates begin
/// and end.
struct Found {
    key: String,
    /// The `let`s' tokens, the candidates', the rest (the fall-through).
    lets: Vec<T>,
    candidates: Vec<T>,
    rest: Vec<T>,
    /// Each `v<i>` the candidates read, with its type.
    params: Vec<(Ident, TokenStream)>,
    reads_atoms: bool,
    name: String,
}

/// `items` with each `'sel` block that occurs at least twice (the same
/// candidates, the same value types) calling one function, and those
/// functions.
pub(super) fn share_selections(items: TokenStream, sites: &[SelSite]) -> TokenStream {
    if sites.len() < 2 {
        return items;
    }
    let mut found: Vec<Found> = Vec::new();
    walk(&items, sites, &mut |f| found.push(f));
    let mut uses: HashMap<String, usize> = HashMap::new();
    for f in &found {
        *uses.entry(f.key.clone()).or_default() += 1;
    }
    // One function per shared key, named in order of first occurrence.
    let mut names: HashMap<String, Ident> = HashMap::new();
    let mut fns = Vec::new();
    let mut taken_names: HashMap<String, usize> = HashMap::new();
    for f in &found {
        if uses[&f.key] < 2 || names.contains_key(&f.key) {
            continue;
        }
        // Shared only where it is fewer lines: each block keeps a call of
        // three lines (one, a selection that takes every value), the
        // function costs its candidates and about seven (its
        // `#[inline(always)]`: the sharing saves lines, not instructions).
        let candidates: TokenStream = f.candidates.iter().cloned().collect();
        let lines = super::lines_in_dm(&quote!('sel: { #candidates })).saturating_sub(6);
        let call = if f.rest.is_empty() { 1 } else { 3 };
        if uses[&f.key] * lines.saturating_sub(call) <= lines + 7 {
            continue;
        }
        let base = if is_plain_name(&f.name) {
            format!("select_{}", f.name)
        } else {
            "select".to_string()
        };
        let n = taken_names.entry(base.clone()).or_default();
        *n += 1;
        let fname = if *n == 1 {
            format_ident!("{}", base)
        } else {
            format_ident!("{}_{}", base, *n)
        };
        names.insert(f.key.clone(), fname.clone());
        let atoms = f.reads_atoms.then(|| quote!(a: &super::Atoms,));
        let params = f.params.iter().map(|(v, t)| quote!(#v: #t));
        let doc = format!(
            " Selects situation `{}` (shared by the DM's selections of it).",
            f.name
        );
        fns.push(if f.rest.is_empty() {
            quote! {
                #[doc = #doc]
                #[inline(always)]
                fn #fname(#atoms #(#params),*) -> Nat {
                    'sel: { #candidates }
                }
            }
        } else {
            quote! {
                #[doc = #doc]
                #[inline(always)]
                fn #fname(#atoms #(#params),*) -> Option<Nat> {
                    Some('sel: {
                        #candidates
                        return None;
                    })
                }
            }
        });
    }
    if fns.is_empty() {
        return items;
    }
    let items = rewrite(items, sites, &names);
    quote!(#items #(#fns)*)
}

fn is_plain_name(s: &str) -> bool {
    s.chars().next().is_some_and(|c| c.is_ascii_lowercase())
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Calls `f` on each `'sel` block of `ts` that a site's candidates begin.
fn walk(ts: &TokenStream, sites: &[SelSite], f: &mut dyn FnMut(Found)) {
    let toks: Vec<T> = ts.clone().into_iter().collect();
    for (i, t) in toks.iter().enumerate() {
        if let T::Group(g) = t {
            if is_sel(&toks[..i]) && g.delimiter() == Delimiter::Brace {
                if let Some(found) = analyze(g, sites) {
                    f(found);
                    continue;
                }
            }
            walk(&g.stream(), sites, f);
        }
    }
}

/// `ts` with each shared block calling its function.
fn rewrite(ts: TokenStream, sites: &[SelSite], names: &HashMap<String, Ident>) -> TokenStream {
    let toks: Vec<T> = ts.into_iter().collect();
    let mut out = Vec::with_capacity(toks.len());
    for (i, t) in toks.iter().enumerate() {
        let T::Group(g) = t else {
            out.push(t.clone());
            continue;
        };
        if is_sel(&toks[..i]) && g.delimiter() == Delimiter::Brace {
            if let Some(found) = analyze(g, sites) {
                if let Some(fname) = names.get(&found.key) {
                    let lets: TokenStream = found.lets.iter().cloned().collect();
                    let rest: TokenStream = found.rest.iter().cloned().collect();
                    let atoms = found.reads_atoms.then(|| quote!(a,));
                    let args = found.params.iter().map(|(v, _)| v);
                    let call = quote!(#fname(#atoms #(#args),*));
                    let body = if found.rest.is_empty() {
                        quote!(#lets #call)
                    } else {
                        quote! {
                            #lets
                            if let Some(next) = #call {
                                break 'sel next;
                            }
                            #rest
                        }
                    };
                    let mut ng = Group::new(Delimiter::Brace, body);
                    ng.set_span(g.span());
                    out.push(T::Group(ng));
                    continue;
                }
                out.push(t.clone());
                continue;
            }
        }
        let mut ng = Group::new(g.delimiter(), rewrite(g.stream(), sites, names));
        ng.set_span(g.span());
        out.push(T::Group(ng));
    }
    out.into_iter().collect()
}

/// Whether `before` ends in `'sel :`.
fn is_sel(before: &[T]) -> bool {
    matches!(
        before,
        [.., T::Punct(q), T::Ident(l), T::Punct(c)]
            if q.as_char() == '\'' && q.spacing() == Spacing::Joint && l == "sel" && c.as_char() == ':'
    )
}

/// The block `g` split into its typed `let`s, a site's candidates and the
/// rest, when the candidates can be a function of the `let`s' values.
fn analyze(g: &Group, sites: &[SelSite]) -> Option<Found> {
    let toks: Vec<T> = g.stream().into_iter().collect();
    // `let v<i> : TYPE = EXPR ;`, or `let v<i> = EXPR ;` (its type the
    // site's).
    let mut k = 0;
    let mut vals: Vec<(Ident, Option<TokenStream>)> = Vec::new();
    while matches!(&toks.get(k), Some(T::Ident(l)) if l == "let") {
        let Some(T::Ident(v)) = toks.get(k + 1) else {
            return None;
        };
        if *v != format!("v{}", vals.len()) {
            break;
        }
        let eq = k
            + 2
            + toks[k + 2..]
                .iter()
                .position(|t| matches!(t, T::Punct(p) if p.as_char() == '='))?;
        let semi = eq
            + toks[eq..]
                .iter()
                .position(|t| matches!(t, T::Punct(p) if p.as_char() == ';'))?;
        let ty = match toks.get(k + 2) {
            Some(T::Punct(c)) if c.as_char() == ':' => {
                Some(toks[k + 3..eq].iter().cloned().collect())
            }
            _ => None,
        };
        vals.push((v.clone(), ty));
        k = semi + 1;
    }
    let lets: TokenStream = toks[..k].iter().cloned().collect();
    let lets_text = lets.to_string();
    let after = &toks[k..];
    let site = sites.iter().find(|s| {
        s.lets == lets_text && s.types.len() == vals.len() && s.len <= after.len() && {
            let c: TokenStream = after[..s.len].iter().cloned().collect();
            c.to_string() == s.text
        }
    })?;
    // An untyped `let`: its type as every site with the same code says.
    let same = |s: &&SelSite| s.lets == site.lets && s.text == site.text;
    let text = |s: &SelSite| -> Vec<Option<String>> {
        s.types
            .iter()
            .map(|t| t.as_ref().map(|t| t.to_string()))
            .collect()
    };
    if sites.iter().filter(same).any(|s| text(s) != text(site)) {
        return None;
    }
    let vals: Vec<(Ident, TokenStream)> = vals
        .into_iter()
        .zip(&site.types)
        .map(|((v, t), st)| Some((v, t.or_else(|| st.clone())?)))
        .collect::<Option<_>>()?;
    let candidates = after[..site.len].to_vec();
    let mut idents = Vec::new();
    let mut labels = Vec::new();
    names_in(
        &candidates.iter().cloned().collect(),
        &mut idents,
        &mut labels,
    );
    if labels.iter().any(|l| l != "sel" && l != "hand") || idents.iter().any(|i| of_visit(i)) {
        return None;
    }
    let params: Vec<(Ident, TokenStream)> = vals
        .into_iter()
        .filter(|(v, _)| idents.iter().any(|i| v == i))
        .collect();
    let reads_atoms = idents.iter().any(|i| i == "a");
    let types: Vec<String> = params.iter().map(|(v, t)| format!("{v}: {t}")).collect();
    let rest = after[site.len..].to_vec();
    Some(Found {
        key: format!("{} | {} | {}", types.join(", "), site.text, rest.is_empty()),
        lets: toks[..k].to_vec(),
        candidates,
        rest,
        params,
        reads_atoms,
        name: site.name.clone(),
    })
}

/// The identifiers read and the labels (`'x`, as `x`) in `ts`: not a
/// name before a single `:` (a field of the variant built, `r5: ..`).
fn names_in(ts: &TokenStream, idents: &mut Vec<String>, labels: &mut Vec<String>) {
    let mut quote_before = false;
    let toks: Vec<T> = ts.clone().into_iter().collect();
    for (k, t) in toks.iter().enumerate() {
        let field = matches!(toks.get(k + 1), Some(T::Punct(c))
            if c.as_char() == ':' && c.spacing() == Spacing::Alone)
            && !matches!(k.checked_sub(1).map(|j| &toks[j]), Some(T::Punct(c)) if c.as_char() == ':');
        match t {
            T::Ident(i) if quote_before => labels.push(i.to_string()),
            T::Ident(_) if field => {}
            T::Ident(i) => idents.push(i.to_string()),
            T::Group(g) => names_in(&g.stream(), idents, labels),
            _ => {}
        }
        quote_before = matches!(t, T::Punct(p) if p.as_char() == '\'');
    }
}

/// Whether `i` names something of the visit (the machine, the program, a
/// register or frame field) that a shared selection cannot read.
fn of_visit(i: &str) -> bool {
    const VISIT: [&str; 14] = [
        "cx", "p", "run", "stack", "count", "store", "frame", "ret", "call", "slot", "exp", "act",
        "arc_at", "self",
    ];
    if VISIT.contains(&i) {
        return true;
    }
    ["r", "fresh_r", "x", "b", "t", "id", "out", "p", "c"]
        .iter()
        .any(|pre| {
            i.strip_prefix(pre)
                .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn site(lets: TokenStream, c: &TokenStream) -> SelSite {
        let n = lets.to_string().matches("let").count();
        SelSite {
            lets: lets.to_string(),
            types: vec![None; n],
            text: c.to_string(),
            len: c.clone().into_iter().count(),
            name: "each".into(),
        }
    }

    /// Candidates long enough to be worth a function.
    fn candidates(reg: TokenStream) -> TokenStream {
        let mut c = TokenStream::new();
        for k in 1..6u32 {
            let v = format_ident!("S{}", k);
            c.extend(quote! {
                if let Some((h0, l0)) = v0.split_first() {
                    if let Some([g1_0]) = h0.args_of(a.class, 1) {
                        break 'sel Nat::#v { r5: g1_0.clone(), r6: l0, r7: #reg.clone() };
                    }
                }
            });
        }
        c
    }

    #[test]
    fn two_blocks_share_one_function() {
        let c = candidates(quote!(v1));
        let (l1, l2) = (
            quote!(let v0: &List<Val> = &r6; let v1 = &(List::cons(r5.clone(), r7.clone()));),
            quote!(let v0: &List<Val> = &r8; let v1: &List<Val> = &r9;),
        );
        let items = quote! {
            fn f() {
                let n: Nat = 'sel: { #l1 #c hand(); };
                let m: Nat = 'sel: { #l2 #c hand(); };
            }
        };
        let mut s1 = site(l1, &c);
        s1.types = vec![Some(quote!(&List<Val>)), Some(quote!(&List<Val>))];
        let out = share_selections(items, &[s1, site(l2, &c)]).to_string();
        assert_eq!(out.matches("fn select_each").count(), 1, "{out}");
        assert_eq!(out.matches("select_each (a , v0 , v1)").count(), 2, "{out}");
        assert_eq!(out.matches("hand ()").count(), 2, "{out}");
    }

    #[test]
    fn a_block_reading_a_register_or_untyped_stays() {
        let c = candidates(quote!(r7));
        let l = quote!(let v0: &List<Val> = &r6;);
        let items = quote! {
            fn f() {
                let n: Nat = 'sel: { #l #c hand(); };
                let m: Nat = 'sel: { #l #c hand(); };
            }
        };
        let out = share_selections(items.clone(), &[site(l.clone(), &c), site(l, &c)]);
        assert_eq!(out.to_string(), items.to_string());
        // `v1` untyped, no type given.
        let d = candidates(quote!(v1));
        let l = quote!(let v0: &List<Val> = &r6; let v1 = &(x()););
        let items = quote! {
            fn f() {
                let n: Nat = 'sel: { #l #d hand(); };
                let m: Nat = 'sel: { #l #d hand(); };
            }
        };
        let out = share_selections(items.clone(), &[site(l.clone(), &d), site(l, &d)]);
        assert_eq!(out.to_string(), items.to_string());
    }
}
