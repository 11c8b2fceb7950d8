//! What a situation's generated native code does with terms, read from
//! the code itself (`--explain-types`, issue 37's "on native values": a
//! situation's code uses no term except explicit conversions at a
//! boundary). Owns [`Visit`] and [`visit_kind`].
//!
//! Invariant: the verdict follows every path of the generated statements
//! (each arm of an `if`, an `else if`, a `match`, a labelled block's
//! `break`s, a loop's body), not a prefix of them, so a template call or a
//! hand-over after a conversion check, inside a block, a branch or a
//! labelled block is seen. These paths are not the situation's
//! own: a **failed conversion at a boundary** (the `else` of a `let ..
//! else`, the body of `if !cx.converts_to::<T>(..)` (or `pipe_converts`), the `None` or `_`
//! arm of a `match`: a value that is not of its inferred type, of no shape
//! the other arms take, or an overflow of checked arithmetic, handed to
//! the machine's term code; a selection's value that no variant takes, the end of a `'sel`
//! block: the machine selects), an **error** (`return Err(..)`, a
//! `no_exit`, an effector failing on `empty`, a `set` of a global that
//! does not exist: the run stops), a **boundary back to the machine** (a final whose caller is
//! the machine's, `stack.is_empty()`, or gave a bound output argument,
//! not `is_out()`; the depth limit, not `stack.has_room(cx)`), and a **history
//! path** (a condition that `run.records`, `run.recorded()` or
//! `cx.gc_tick()` decides, read as with `--history none` between two
//! collections). A closure's body is not run where it is written. A `?`'s
//! error path ends the run, not a branch.

use proc_macro2::{Delimiter, TokenStream, TokenTree};

/// What a situation's native code does on its paths (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Visit {
    /// No path hands the native frames over or runs the template.
    Native,
    /// Some paths hand the native frames over (`nat_hand_over`) or run the
    /// template, others do not: terms on those paths, so not on native
    /// values.
    Partly,
    /// Every path hands the native frames below over to the machine
    /// (`nat_hand_over`: each made a machine frame, its values converted
    /// to terms; the locals written back), then goes on natively.
    HandsOver,
    /// Every path runs the visit from the situation's template
    /// (`machine::nat_template`, `Cx::counted_template`): the frames
    /// handed over, an instance made.
    Template,
}

/// A path's state: what it did so far.
const CLEAN: u8 = 1;
const HANDED: u8 = 2;
const TEMPLATE: u8 = 4;

/// The states of the paths that leave a piece of code (`gone`: by
/// `return`; `breaks`: by a `break` to a label, with the label) and of
/// those that run on after it (`on`).
#[derive(Default, Clone)]
struct Flow {
    on: u8,
    gone: u8,
    breaks: Vec<(String, u8)>,
}

/// [`Visit`] of a situation's code: `body` its visit, `more` code that
/// runs after it on some path (a recursive situation's exit arm, run when
/// its callee is given back).
pub(super) fn visit_kind(body: &TokenStream, more: Option<&TokenStream>) -> Visit {
    let toks: Vec<TokenTree> = body.clone().into_iter().collect();
    let f = seq(&toks, CLEAN);
    let mut ends = f.on | f.gone;
    for (_, s) in &f.breaks {
        ends |= s;
    }
    let visit = verdict(ends);
    match (visit, more) {
        (Visit::Native, Some(m)) => {
            let toks: Vec<TokenTree> = m.clone().into_iter().collect();
            let f = seq(&toks, CLEAN);
            let mut ends = f.on | f.gone;
            for (_, s) in &f.breaks {
                ends |= s;
            }
            if ends & (HANDED | TEMPLATE) != 0 {
                Visit::Partly
            } else {
                Visit::Native
            }
        }
        (v, _) => v,
    }
}

fn verdict(ends: u8) -> Visit {
    if ends == 0 || ends & (HANDED | TEMPLATE) == 0 {
        Visit::Native
    } else if ends == TEMPLATE {
        Visit::Template
    } else if ends & CLEAN == 0 {
        Visit::HandsOver
    } else {
        Visit::Partly
    }
}

/// Each state of `s` with `bit` added (a template call is a hand-over
/// too, and more: it replaces the state).
fn mark(s: u8, bit: u8) -> u8 {
    if s == 0 {
        return 0;
    }
    if bit == TEMPLATE {
        return TEMPLATE;
    }
    let mut out = 0;
    if s & CLEAN != 0 || s & HANDED != 0 {
        out |= HANDED;
    }
    out | (s & TEMPLATE)
}

fn is_ident(t: Option<&TokenTree>, name: &str) -> bool {
    matches!(t, Some(TokenTree::Ident(i)) if i == name)
}

fn is_punct(t: Option<&TokenTree>, c: char) -> bool {
    matches!(t, Some(TokenTree::Punct(p)) if p.as_char() == c)
}

fn is_brace(t: Option<&TokenTree>) -> bool {
    matches!(t, Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Brace)
}

fn has_ident(toks: &[TokenTree], name: &str) -> bool {
    toks.iter().any(|t| match t {
        TokenTree::Ident(i) => i == name,
        TokenTree::Group(g) => has_ident(&g.stream().into_iter().collect::<Vec<_>>(), name),
        _ => false,
    })
}

/// The flow of a sequence of statements entered with the paths `s`.
fn seq(toks: &[TokenTree], s: u8) -> Flow {
    let mut f = Flow {
        on: s,
        ..Flow::default()
    };
    let mut k = 0;
    while k < toks.len() {
        if f.on == 0 {
            break;
        }
        match &toks[k] {
            TokenTree::Ident(i) if i == "if" => {
                k = if_chain(toks, k, &mut f);
                continue;
            }
            TokenTree::Ident(i) if i == "match" => {
                let Some(body) = (k + 1..toks.len()).find(|&j| is_brace(toks.get(j))) else {
                    break;
                };
                let scrutinee = &toks[k + 1..body];
                let s = straight(scrutinee, &mut f);
                let TokenTree::Group(g) = &toks[body] else {
                    unreachable!("a brace")
                };
                let arms = match_arms(&g.stream().into_iter().collect::<Vec<_>>());
                let mut on = 0;
                for (pat, arm) in arms {
                    // The value no other arm takes (a conversion that
                    // fails, an overflow, a shape native code does not
                    // handle): the machine's.
                    if pat.len() == 1
                        && (is_ident(pat.first(), "None") || is_ident(pat.first(), "_"))
                    {
                        continue;
                    }
                    let a = seq(&arm, s);
                    on |= a.on;
                    f.gone |= a.gone;
                    f.breaks.extend(a.breaks);
                }
                f.on = on;
                k = body + 1;
                continue;
            }
            TokenTree::Ident(i) if i == "else" => {
                // A `let .. else`'s block: a failed conversion.
                k += if is_brace(toks.get(k + 1)) { 2 } else { 1 };
                continue;
            }
            TokenTree::Ident(i) if i == "return" => {
                let end = stmt_end(toks, k + 1);
                let s = straight(&toks[k + 1..end], &mut f);
                // An error ends the run: not a path of the visit (nor
                // `no_exit`'s, always the machine's error).
                if !is_ident(toks.get(k + 1), "Err") && !has_ident(&toks[k + 1..end], "no_exit") {
                    f.gone |= s;
                }
                f.on = 0;
                k = end;
                continue;
            }
            TokenTree::Ident(i) if i == "break" => {
                let end = stmt_end(toks, k + 1);
                let label = match (toks.get(k + 1), toks.get(k + 2)) {
                    (Some(TokenTree::Punct(p)), Some(TokenTree::Ident(l)))
                        if p.as_char() == '\'' =>
                    {
                        Some(l.to_string())
                    }
                    _ => None,
                };
                let from = if label.is_some() { k + 3 } else { k + 1 };
                let s = straight(&toks[from.min(end)..end], &mut f);
                f.breaks.push((label.unwrap_or_default(), s));
                f.on = 0;
                k = end;
                continue;
            }
            TokenTree::Ident(i) if i == "continue" => {
                f.breaks.push((String::new(), f.on));
                f.on = 0;
                k = stmt_end(toks, k + 1);
                continue;
            }
            TokenTree::Ident(i) if ["loop", "while", "for"].contains(&&*i.to_string()) => {
                let Some(body) = (k + 1..toks.len()).find(|&j| is_brace(toks.get(j))) else {
                    break;
                };
                let s = straight(&toks[k + 1..body], &mut f);
                let TokenTree::Group(g) = &toks[body] else {
                    unreachable!("a brace")
                };
                let b = seq(&g.stream().into_iter().collect::<Vec<_>>(), s);
                f.gone |= b.gone;
                // Run none, one or more times; an unlabelled `break` or a
                // `continue` ends its round.
                let mut on = s | b.on;
                for (l, st) in b.breaks {
                    if l.is_empty() {
                        on |= st;
                    } else {
                        f.breaks.push((l, st));
                    }
                }
                f.on = on;
                k = body + 1;
                continue;
            }
            TokenTree::Ident(i) if i == "nat_template" || i == "counted_template" => {
                f.on = mark(f.on, TEMPLATE);
            }
            TokenTree::Ident(i) if i == "nat_hand_over" => f.on = mark(f.on, HANDED),
            // A labelled block (`'sel: { .. }`): its `break`s to the label
            // run on after it.
            TokenTree::Punct(p)
                if p.as_char() == '\''
                    && is_punct(toks.get(k + 2), ':')
                    && is_brace(toks.get(k + 3)) =>
            {
                let label = toks[k + 1].to_string();
                let TokenTree::Group(g) = &toks[k + 3] else {
                    unreachable!("a brace")
                };
                let b = seq(&g.stream().into_iter().collect::<Vec<_>>(), f.on);
                // A selection's block (`'sel`) where some value is taken
                // natively (a `break 'sel`): a value that no variant takes
                // (its paths that end or return in the block) is a failed
                // conversion, the machine's selection. One with no variant
                // to take hands every value to the machine: its paths are
                // the visit's.
                let sel = label == "sel" && b.breaks.iter().any(|(l, _)| *l == label);
                let mut on = if sel { 0 } else { b.on };
                for (l, st) in b.breaks {
                    if l == label {
                        on |= st;
                    } else {
                        f.breaks.push((l, st));
                    }
                }
                if !sel {
                    f.gone |= b.gone;
                }
                f.on = on;
                k += 4;
                continue;
            }
            // A closure's body is not run here.
            TokenTree::Punct(p) if p.as_char() == '|' => {
                k = closure_end(toks, k);
                continue;
            }
            TokenTree::Group(g) => {
                let b = seq(&g.stream().into_iter().collect::<Vec<_>>(), f.on);
                f.gone |= b.gone;
                f.breaks.extend(b.breaks);
                f.on = b.on;
            }
            _ => {}
        }
        k += 1;
    }
    f
}

/// The paths after `toks`, code without statements of its own (an `if`'s
/// condition, a `match`'s scrutinee, a `return`'s value), read as a
/// sequence; paths leaving inside it go to `f`.
fn straight(toks: &[TokenTree], f: &mut Flow) -> u8 {
    straight_from(toks, f.on, f)
}

/// [`straight`] entered with the paths `s`.
fn straight_from(toks: &[TokenTree], s: u8, f: &mut Flow) -> u8 {
    let b = seq(toks, s);
    f.gone |= b.gone;
    f.breaks.extend(b.breaks);
    b.on
}

/// The end of the statement starting at `from`: its `;` at this level, or
/// the sequence's end.
fn stmt_end(toks: &[TokenTree], from: usize) -> usize {
    (from..toks.len())
        .find(|&j| is_punct(toks.get(j), ';'))
        .map_or(toks.len(), |j| j + 1)
}

/// After a closure starting at the `|` at `k`: its parameters, then its
/// body (a block, or an expression up to a `,` or `;` at this level).
fn closure_end(toks: &[TokenTree], k: usize) -> usize {
    // `||`: one token `|` joint with the next, or two.
    let mut j = k + 1;
    if !is_punct(toks.get(j), '|') {
        while j < toks.len() && !is_punct(toks.get(j), '|') {
            j += 1;
        }
    }
    j += 1;
    if is_brace(toks.get(j)) {
        return j + 1;
    }
    while j < toks.len() && !is_punct(toks.get(j), ',') && !is_punct(toks.get(j), ';') {
        j += 1;
    }
    j
}

/// A condition's value on the paths read ([`seq`]'s module doc): `Some`
/// where the history decides it (`run.records`, `run.recorded()`,
/// `cx.gc_tick()`, negated or joined by `&&`, `||`), else `None`.
fn decided(cond: &[TokenTree]) -> Option<bool> {
    // Split at the top level's `||`, then `&&`.
    fn split(toks: &[TokenTree], op: char) -> Vec<&[TokenTree]> {
        let mut out = Vec::new();
        let mut start = 0;
        let mut j = 0;
        while j + 1 < toks.len() {
            if is_punct(toks.get(j), op) && is_punct(toks.get(j + 1), op) {
                out.push(&toks[start..j]);
                start = j + 2;
                j += 2;
                continue;
            }
            j += 1;
        }
        out.push(&toks[start..]);
        out
    }
    fn atom(toks: &[TokenTree]) -> Option<bool> {
        let text: String = toks.iter().map(|t| t.to_string()).collect();
        match text.as_str() {
            // `empty_fails`: the effector's error.
            "run.records"
            | "run.recorded()"
            | "cx.gc_tick()"
            | "stack.is_empty()"
            | "cx.empty_fails(run)" => Some(false),
            "stack.has_room(cx)" => Some(true),
            // `NatBelow::push`: `false` only where a history is recorded and
            // not nested, or at the depth limit (both not counted).
            _ if text.starts_with("stack.push(") => Some(true),
            // `false` only for a global that does not exist (the machine's
            // error follows).
            _ if text.starts_with("cx.global_set(") => Some(true),
            // An output parameter the native caller left unbound.
            _ if text.ends_with(".is_out()") => Some(true),
            _ => match toks.first() {
                Some(TokenTree::Punct(p)) if p.as_char() == '!' => atom(&toks[1..]).map(|v| !v),
                Some(TokenTree::Group(g))
                    if toks.len() == 1 && g.delimiter() == Delimiter::Parenthesis =>
                {
                    decided(&g.stream().into_iter().collect::<Vec<_>>())
                }
                _ => None,
            },
        }
    }
    let ors = split(cond, '|');
    let mut any_unknown = false;
    for o in &ors {
        let ands = split(o, '&');
        let mut v = Some(true);
        for a in ands {
            v = match (v, atom(a)) {
                (Some(false), _) | (_, Some(false)) => Some(false),
                (Some(true), Some(true)) => Some(true),
                _ => None,
            };
        }
        match v {
            Some(true) => return Some(true),
            None => any_unknown = true,
            Some(false) => {}
        }
    }
    if any_unknown {
        None
    } else {
        Some(false)
    }
}

/// An `if` (with its `else if`s and `else`) starting at `k`: its paths
/// added to `f`; the index after it.
fn if_chain(toks: &[TokenTree], mut k: usize, f: &mut Flow) -> usize {
    let mut s = f.on;
    let mut on = 0;
    loop {
        // `k` is at `if`.
        let Some(then) = (k + 1..toks.len()).find(|&j| is_brace(toks.get(j))) else {
            f.on = s;
            return toks.len();
        };
        let cond = &toks[k + 1..then];
        let after = straight_from(cond, s, f);
        let TokenTree::Group(g) = &toks[then] else {
            unreachable!("a brace")
        };
        let body: Vec<TokenTree> = g.stream().into_iter().collect();
        // `if !cx.converts_to::<T>(v)`: its body is a failed conversion.
        let failed = is_punct(cond.first(), '!')
            && (has_ident(cond, "converts_to") || has_ident(cond, "pipe_converts"));
        let value = if failed { Some(false) } else { decided(cond) };
        if value != Some(false) {
            let b = seq(&body, after);
            on |= b.on;
            f.gone |= b.gone;
            f.breaks.extend(b.breaks);
        }
        // The paths on which the condition is false.
        s = if value == Some(true) { 0 } else { after };
        k = then + 1;
        if !is_ident(toks.get(k), "else") {
            f.on = on | s;
            return k;
        }
        k += 1;
        if is_ident(toks.get(k), "if") {
            continue;
        }
        if let Some(TokenTree::Group(g)) = toks.get(k) {
            let b = seq(&g.stream().into_iter().collect::<Vec<_>>(), s);
            on |= b.on;
            f.gone |= b.gone;
            f.breaks.extend(b.breaks);
            k += 1;
        }
        f.on = on;
        return k;
    }
}

/// A `match`'s arms: each its pattern and its body.
fn match_arms(toks: &[TokenTree]) -> Vec<(Vec<TokenTree>, Vec<TokenTree>)> {
    let mut arms = Vec::new();
    let mut k = 0;
    while k < toks.len() {
        let start = k;
        while k + 1 < toks.len() && !(is_punct(toks.get(k), '=') && is_punct(toks.get(k + 1), '>'))
        {
            k += 1;
        }
        if k + 1 >= toks.len() {
            break;
        }
        let pat = toks[start..k].to_vec();
        k += 2;
        let body_start = k;
        if is_brace(toks.get(k)) {
            k += 1;
            let body = toks[body_start..k].to_vec();
            if is_punct(toks.get(k), ',') {
                k += 1;
            }
            arms.push((pat, body));
            continue;
        }
        while k < toks.len() && !is_punct(toks.get(k), ',') {
            k += 1;
        }
        arms.push((pat, toks[body_start..k].to_vec()));
        k += 1;
    }
    arms
}

#[cfg(test)]
mod tests {
    use super::{visit_kind, Visit};
    use quote::quote;

    fn kind(t: proc_macro2::TokenStream) -> Visit {
        visit_kind(&t, None)
    }

    #[test]
    fn every_path_or_some() {
        // The template, alone or after the hand-over.
        let t = quote!(return machine::nat_template(p, cx, stack, count, 2, a.welcome););
        assert_eq!(kind(t), Visit::Template);
        let t =
            quote!(super::nat_hand_over(p, cx, stack)?; return cx.counted_template(count, 1, id););
        assert_eq!(kind(t), Visit::Template);
        // A push where no history is kept: the template is the history's
        // path.
        let t = quote!(if !run.records { return cx.step_done(count, slot, at); } return machine::nat_template(p, cx, stack, count, 0, a.is););
        assert_eq!(kind(t), Visit::Native);
        let t = quote! {
            if !run.records {
                *call = Some(super::NatFrame::D1(callee()));
                return cx.step_done(count, slot, Nat::W0 {});
            } else if run.nests && stack.has_room(cx) {
                cx.push_level(p, call, super::NatFrame::D1(callee()));
                return cx.step_done(count, slot, Nat::W0 {});
            }
            super::nat_hand_over(p, cx, stack)?;
            return cx.counted_template(count, 1, Term::atom(a.preferences));
        };
        assert_eq!(kind(t), Visit::Native);
        // The hand-over first, or after an `if` that cannot leave, or in a
        // block statement.
        let t = quote!(let exp = Term::EMPTY; super::nat_hand_over(p, cx, stack)?; cx.perform(act, None)?;);
        assert_eq!(kind(t), Visit::HandsOver);
        let t = quote!(if run.records { cx.nat_empty(stack)?; } let next_at: Nat = { super::nat_hand_over(p, cx, stack)?; Nat::S1 {} }; next_at);
        assert_eq!(kind(t), Visit::HandsOver);
        // A failed conversion's `else`: not the situation's path.
        let t = quote!(let Some(x) = v else { super::nat_hand_over(p, cx, stack)?; return run.goto(); }; x);
        assert_eq!(kind(t), Visit::Native);
        // One arm of a match, or of an `if`: on some paths.
        let t = quote!(match chosen {
            0 => {
                super::nat_hand_over(p, cx, stack)?;
            }
            1 => {}
            _ => unreachable!(),
        });
        assert_eq!(kind(t), Visit::Partly);
        let t = quote!(let t13 = if t2 { super::nat_hand_over(p, cx, stack)?; (t7, None) } else { super::nat_hand_over(p, cx, stack)?; (t12, None) };);
        assert_eq!(kind(t), Visit::HandsOver);
        // A closure's body is not run there.
        let t = quote!(let f = || { super::nat_hand_over(p, cx, stack) }; Nat::S0 {});
        assert_eq!(kind(t), Visit::Native);
        let t = quote!(run.record_next(cx, exp, act, |s| machine::nat_template(s)); next_at);
        assert_eq!(kind(t), Visit::Native);
    }

    /// Review22's finding 1: the template after the in_arg's conversion
    /// check is the visit of every pipe that converts.
    #[test]
    fn a_template_after_a_conversion_check() {
        let t = quote! {
            let pipe_in = cx.pipe_in();
            if !cx.converts_to::<Val>(pipe_in) {
                super::nat_hand_over(p, cx, stack)?;
                cx.count_transitions(count);
                return Ok(Some(Step::Goto(id)));
            }
            super::nat_hand_over(p, cx, stack)?;
            return cx.counted_template(count, 1, Fill(p.k[3], (&r0,)));
        };
        assert_eq!(kind(t), Visit::Template);
        let t = quote! {
            let pipe_in = cx.pipe_in();
            let pipe_value = cx.to_native::<i64>(pipe_in);
            let Some(r1) = pipe_value else {
                cx.count_transitions(count);
                return Ok(Some(Step::Goto(id)));
            };
            return machine::nat_template(p, cx, stack, count, 1, a.rung);
        };
        assert_eq!(kind(t), Visit::Template);
        // The `None` arm of a conversion's match is its failure.
        let t = quote! {
            let r2 = match cx.to_native::<Atom>(t) {
                Some(v) => v,
                None => {
                    super::nat_hand_over(p, cx, stack)?;
                    return run.goto();
                }
            };
            return cx.counted_template(count, 2, id);
        };
        assert_eq!(kind(t), Visit::Template);
    }

    /// An error's path and an overflow's are not the visit's.
    #[test]
    fn errors_and_overflows() {
        let t = quote! {
            let act0: i64 = match Some(r6).and_then(|a| a.checked_add(1i64)) {
                Some(v) => v,
                None => {
                    super::nat_hand_over(p, cx, stack)?;
                    cx.is(None, b0, Some(0))?
                }
            };
            if let Err(e) = cx.perform_value(t) {
                super::nat_hand_over(p, cx, stack)?;
                return Err(cx.action_failed(e, Some(0)));
            }
            break 'visit Nat::S1 { r6: act0 };
        };
        assert_eq!(kind(t), Visit::Native);
        // A `_` arm: a value of a shape no other arm takes.
        let t = quote! {
            match &act0 {
                Val::Int(_) | Val::Float(_) => {}
                _ => {
                    nat_hand_over(p, cx, stack, &*l0)?;
                    cx.perform_each(&[t], Some(0))?;
                }
            }
        };
        assert_eq!(kind(t), Visit::Native);
        // Any other arm is a path.
        let t = quote! {
            match chosen {
                Some(0) => v,
                Some(_) => { super::nat_hand_over(p, cx, stack)?; return run.goto(); }
                None => v,
            }
        };
        assert_eq!(kind(t), Visit::Partly);
    }

    /// A labelled block's `break`s run on after it; its fall-through too.
    #[test]
    fn labelled_blocks() {
        let t = quote! {
            let next_at: Nat = 'sel: {
                if v0.is_empty() { break 'sel Nat::S1 {}; }
                break 'sel Nat::S2 {};
            };
            super::nat_hand_over(p, cx, stack)?;
            return cx.counted_template(count, 3, id);
        };
        assert_eq!(kind(t), Visit::Template);
        // A selection's value that no variant takes: the machine's.
        let t = quote! {
            let next_at: Nat = 'sel: {
                if v0.is_empty() { break 'sel Nat::S1 {}; }
                super::nat_hand_over(p, cx, stack)?;
                return run.goto(cx, exp, act, rec_next, arc_at);
            };
            next_at
        };
        assert_eq!(kind(t), Visit::Native);
        // No variant to take: every value the machine's.
        let t = quote! {
            let next_at: Nat = 'sel: {
                let v0: &Atom = &r1;
                super::nat_hand_over(p, cx, stack)?;
                return run.goto(cx, exp, act, rec_next, Some(0));
            };
            next_at
        };
        assert_eq!(kind(t), Visit::HandsOver);
        // Another label's block: its paths are the visit's.
        let t = quote! {
            let next_at: Nat = 'step: {
                if v0.is_empty() { break 'step Nat::S1 {}; }
                super::nat_hand_over(p, cx, stack)?;
                return run.goto(cx, exp, act, rec_next, arc_at);
            };
            next_at
        };
        assert_eq!(kind(t), Visit::Partly);
        // A final's native return; the machine's caller is a boundary.
        let t = quote! {
            if !stack.is_empty() && p3.is_out() {
                *out3 = Some(r6.clone());
                return cx.step_done(count + 1, slot, Nat::S5 { r6 });
            }
            super::nat_hand_over(p, cx, stack)?;
            return cx.step_final();
        };
        assert_eq!(kind(t), Visit::Native);
        // An exit arm that hands over on a path.
        let exit = quote!(if ok { break 'visit Nat::S2 {}; } super::nat_hand_over(p, cx, stack)?;);
        let t = quote!(if !run.records {
            return cx.step_done(count, slot, at);
        });
        assert_eq!(visit_kind(&t, Some(&exit)), Visit::Partly);
    }
}
