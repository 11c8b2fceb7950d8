//! A next situation selected by a shared selection written flat (issue 37:
//! fewer lines of the same code). A `'sel` block whose candidates are one
//! call of a DM's shared selection (`select_fn`) that may fall through,
//! followed by the arc's record and the visit's end,
//!
//! ```text
//! let next_at: Nat = 'sel: {
//!     let v0: &List<Val> = &r6;
//!     if let Some(next) = select_each(a, v0) {
//!         break 'sel next;
//!     }
//!     ..                                // the fall-through, ending in `return`
//! };
//! run.record_next(cx, exp, act, |s| next_at.id_term(p, s));
//! break 'visit next_at;                 // or `next_at`, the `'visit` block's value
//! ```
//!
//! becomes the same statements without the block: the `let`s, then `if let
//! Some(next_at) = select_each(a, v0) { run.record_next(..); break 'visit
//! next_at; }`, then the fall-through.
//!
//! Invariant: only that exact shape is rewritten (`let`s, the one `if let`,
//! a fall-through that mentions no `'sel` and ends in `return`), so the
//! code does what it did: the same calls in the same order, the `let`s'
//! values (and their temporaries) living to the end of the visit instead
//! of the block's, which no later statement reads.

use proc_macro2::{Delimiter, Group, TokenStream, TokenTree};
use quote::quote;

/// `items` with every such block written flat (module doc).
pub(super) fn flatten(items: TokenStream) -> TokenStream {
    walk(items, false)
}

/// `ts` rewritten; `visit`: `ts` is the body of a `'visit: { .. }` block
/// (a trailing `next_at` is its value).
fn walk(ts: TokenStream, visit: bool) -> TokenStream {
    let toks: Vec<TokenTree> = ts.into_iter().collect();
    let mut out: Vec<TokenTree> = Vec::new();
    let mut k = 0;
    while k < toks.len() {
        if let Some((flat, used)) = flat_at(&toks[k..], visit) {
            out.extend(flat);
            k += used;
            continue;
        }
        match &toks[k] {
            TokenTree::Group(g) => {
                // `'visit : { .. }`
                let labelled = k >= 3
                    && matches!(&toks[k - 1], TokenTree::Punct(p) if p.as_char() == ':')
                    && matches!(&toks[k - 2], TokenTree::Ident(i) if i == "visit")
                    && matches!(&toks[k - 3], TokenTree::Punct(p) if p.as_char() == '\'');
                let inner = labelled && g.delimiter() == Delimiter::Brace;
                let mut ng = Group::new(g.delimiter(), walk(g.stream(), inner));
                ng.set_span(g.span());
                out.push(TokenTree::Group(ng));
            }
            t => out.push(t.clone()),
        }
        k += 1;
    }
    out.into_iter().collect()
}

fn is_ident(t: Option<&TokenTree>, s: &str) -> bool {
    matches!(t, Some(TokenTree::Ident(i)) if i == s)
}

fn is_punct(t: Option<&TokenTree>, c: char) -> bool {
    matches!(t, Some(TokenTree::Punct(p)) if p.as_char() == c)
}

/// Whether `ts` mentions the label `'sel`.
fn mentions_sel(ts: &[TokenTree]) -> bool {
    ts.iter().enumerate().any(|(k, t)| match t {
        TokenTree::Group(g) => mentions_sel(&g.stream().into_iter().collect::<Vec<_>>()),
        TokenTree::Punct(p) if p.as_char() == '\'' => is_ident(ts.get(k + 1), "sel"),
        _ => false,
    })
}

/// The flat statements of the shape at the start of `toks` and how many
/// tokens they replace; `None` where `toks` does not start with it.
fn flat_at(toks: &[TokenTree], visit: bool) -> Option<(Vec<TokenTree>, usize)> {
    // let next_at : Nat = ' sel : { .. } ;
    let head = ["let", "next_at"];
    if !is_ident(toks.first(), head[0]) || !is_ident(toks.get(1), head[1]) {
        return None;
    }
    if !is_punct(toks.get(2), ':')
        || !is_ident(toks.get(3), "Nat")
        || !is_punct(toks.get(4), '=')
        || !is_punct(toks.get(5), '\'')
        || !is_ident(toks.get(6), "sel")
        || !is_punct(toks.get(7), ':')
        || !is_punct(toks.get(9), ';')
    {
        return None;
    }
    let Some(TokenTree::Group(block)) = toks.get(8) else {
        return None;
    };
    if block.delimiter() != Delimiter::Brace {
        return None;
    }
    // run . record_next ( .. ) ;
    let rec = toks.get(10..15)?;
    if !is_ident(rec.first(), "run")
        || !is_punct(rec.get(1), '.')
        || !is_ident(rec.get(2), "record_next")
        || !matches!(rec.get(3), Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Parenthesis)
        || !is_punct(rec.get(4), ';')
    {
        return None;
    }
    // break ' visit next_at ;   or the block's last token `next_at`
    let end = &toks[15..];
    let used = if is_ident(end.first(), "break")
        && is_punct(end.get(1), '\'')
        && is_ident(end.get(2), "visit")
        && is_ident(end.get(3), "next_at")
        && is_punct(end.get(4), ';')
    {
        15 + 5
    } else if visit && end.len() == 1 && is_ident(end.first(), "next_at") {
        15 + 1
    } else {
        return None;
    };
    let inner: Vec<TokenTree> = block.stream().into_iter().collect();
    let (lets, call, tail) = split_block(&inner)?;
    let rec: TokenStream = rec.iter().cloned().collect();
    let lets: TokenStream = lets.iter().cloned().collect();
    let call: TokenStream = call.iter().cloned().collect();
    let tail: TokenStream = tail.iter().cloned().collect();
    let flat = quote! {
        #lets
        if let Some(next_at) = #call {
            #rec
            break 'visit next_at;
        }
        #tail
    };
    Some((flat.into_iter().collect(), used))
}

/// The `'sel` block's statements split: its `let`s, the call of its one
/// `if let Some(next) = CALL { break 'sel next; }`, and the fall-through
/// after it (mentioning no `'sel`, ending in a `return` statement).
type Split<'a> = (&'a [TokenTree], &'a [TokenTree], &'a [TokenTree]);

fn split_block(toks: &[TokenTree]) -> Option<Split<'_>> {
    // The `let`s: each up to its `;`.
    let mut k = 0;
    while is_ident(toks.get(k), "let") {
        k += toks[k..].iter().position(|t| is_punct(Some(t), ';'))? + 1;
    }
    let lets = &toks[..k];
    // if let Some ( next ) = CALL { break ' sel next ; }
    if !is_ident(toks.get(k), "if")
        || !is_ident(toks.get(k + 1), "let")
        || !is_ident(toks.get(k + 2), "Some")
        || !matches!(toks.get(k + 3), Some(TokenTree::Group(g))
            if g.delimiter() == Delimiter::Parenthesis && g.stream().to_string() == "next")
        || !is_punct(toks.get(k + 4), '=')
    {
        return None;
    }
    let body = k
        + 5
        + toks[k + 5..]
            .iter()
            .position(|t| matches!(t, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace))?;
    let call = &toks[k + 5..body];
    let TokenTree::Group(b) = &toks[body] else {
        return None;
    };
    if b.stream().to_string() != quote!(break 'sel next;).to_string() || call.is_empty() {
        return None;
    }
    let tail = &toks[body + 1..];
    if mentions_sel(lets) || mentions_sel(call) || mentions_sel(tail) {
        return None;
    }
    // The fall-through's last statement a `return`.
    if !is_punct(tail.last(), ';') {
        return None;
    }
    let start = tail[..tail.len() - 1]
        .iter()
        .rposition(|t| {
            is_punct(Some(t), ';')
                || matches!(t, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace)
        })
        .map_or(0, |i| i + 1);
    if !is_ident(tail.get(start), "return") {
        return None;
    }
    Some((lets, call, tail))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shared_selection_is_written_flat() {
        let code = quote! {
            Nat::W1 { r1 } => 'visit: {
                match x {
                    S1 {} => {
                        let next_at: Nat = 'sel: {
                            let v0: &Val = &r1;
                            if let Some(next) = select_each(a, v0) {
                                break 'sel next;
                            }
                            super::nat_hand_over(p, cx, stack)?;
                            return run.goto(cx, exp, act, rec_next, Some(0));
                        };
                        run.record_next(cx, exp, act, |s| next_at.id_term(p, s));
                        break 'visit next_at;
                    }
                }
            }
        };
        let want = quote! {
            Nat::W1 { r1 } => 'visit: {
                match x {
                    S1 {} => {
                        let v0: &Val = &r1;
                        if let Some(next_at) = select_each(a, v0) {
                            run.record_next(cx, exp, act, |s| next_at.id_term(p, s));
                            break 'visit next_at;
                        }
                        super::nat_hand_over(p, cx, stack)?;
                        return run.goto(cx, exp, act, rec_next, Some(0));
                    }
                }
            }
        };
        assert_eq!(flatten(code).to_string(), want.to_string());
    }

    #[test]
    fn a_visits_value_is_written_flat_and_other_blocks_are_kept() {
        let code = quote! {
            Nat::S1 { r1 } => 'visit: {
                let next_at: Nat = 'sel: {
                    if let Some(next) = select_each(a, &r1) {
                        break 'sel next;
                    }
                    return run.goto(cx, exp, act, rec_next, Some(0));
                };
                run.record_next(cx, exp, act, |s| next_at.id_term(p, s));
                next_at
            }
        };
        let want = quote! {
            Nat::S1 { r1 } => 'visit: {
                if let Some(next_at) = select_each(a, &r1) {
                    run.record_next(cx, exp, act, |s| next_at.id_term(p, s));
                    break 'visit next_at;
                }
                return run.goto(cx, exp, act, rec_next, Some(0));
            }
        };
        assert_eq!(flatten(code).to_string(), want.to_string());
        // A candidate of its own, or a fall-through that gives a value: kept.
        let kept = quote! {
            'visit: {
                let next_at: Nat = 'sel: {
                    if v0.is_nil() {
                        break 'sel Nat::S1 {};
                    }
                    return run.goto(cx, exp, act, rec_next, Some(0));
                };
                run.record_next(cx, exp, act, |s| next_at.id_term(p, s));
                next_at
            }
        };
        assert_eq!(flatten(kept.clone()).to_string(), kept.to_string());
        let kept = quote! {
            'visit: {
                let next_at: Nat = 'sel: {
                    if let Some(next) = select_each(a, v0) {
                        break 'sel next;
                    }
                    Nat::S2 {}
                };
                run.record_next(cx, exp, act, |s| next_at.id_term(p, s));
                next_at
            }
        };
        assert_eq!(flatten(kept.clone()).to_string(), kept.to_string());
    }
}
