//! A user function, the KB or a Prolog condition at its boundary (issue
//! 37): an arc of a DM without locals whose code hands the native frames
//! below over (`nat_hand_over`) only because it then evaluates a call of
//! the evaluator (`cx.eval` of `say(apply(words(_), [..]))`'s argument,
//! `cx.condition` of `apply(same_place(_, _), [P, T]) == yes`) calls it
//! where the frames are instead (`Cx::nat_eval`, `Cx::nat_condition`; the
//! action so computed is performed by `Cx::nat_perform` as the generator
//! wrote it, an entered situation's, `effect`), the frames handed over only
//! where that fails (the runtime's `machine::boundary`).
//!
//! What the hand-over protects before such a call, found by reading the
//! runtime (`eval`, `functions`, `prolog::engine`, `machine::steps`):
//! - *the running DM's variables*: the evaluator, and a user function
//!   through its `FnCall` (a Rust function's `var_op`, a Prolog function's
//!   query, which carries the caller's locals and globals and brings their
//!   changes back), reads and writes the locals of the machine's top
//!   frame. With native frames above it that frame is a caller's. So only
//!   a DM without locals calls at the boundary: its machine frame would
//!   hold no locals, which `Cx::nat_eval` gives it (a DM with locals holds
//!   them in Rust, written back by its own hand-over: kept as it is).
//! - *the running DM's history* (`get_history/1`, `last_transition`): the
//!   innermost history level native code keeps (the frames pushed with the
//!   history kept each have one), or none when the history is not kept.
//! - *errors*: they name the running DM (the machine's top frame): a call
//!   that fails hands over first, then makes the machine's error, the
//!   function not called again (an `assert` or a global it set is done
//!   once, as on the term path).
//! - *garbage*: the machine collects only between situations it runs,
//!   never during an evaluation, so the `Ground` handles of the native
//!   frames stay valid across the call.
//! - *anything else the arc does with the machine*: a next situation or
//!   an out_arg handed to the machine (`run.goto`, `run.go_eval`), a
//!   template, a `get`/`set`/`inc`, a perception, an error made in the
//!   situation: each needs the frames handed over before it. The arc
//!   calls at the boundary only when every such call in its code comes
//!   after a hand-over of its own in the same block ([`needs_hand`], read
//!   on the generated tokens: a conservative reading, a call it does not
//!   know keeps the hand-over).
//!
//! Invariant: an arc's code changed here does what it did with the
//! hand-over first (the runtime's `machine::boundary` invariant), its
//! frames below left native where nothing fails.

use proc_macro2::{Delimiter, Group, Ident, Punct, Spacing, Span, TokenStream, TokenTree};

/// The `cx` methods that read or change nothing of the machine's frames
/// (terms built from values, the situation entered, transitions counted,
/// history entries, which go to native code's levels, the driver's
/// step), or that hand the frames over themselves where they must (the
/// `nat_` calls, given `stack`).
const SAFE: &[&str] = &[
    "fill",
    "build",
    "build_of",
    "compound",
    "term",
    "vars",
    "store",
    "store_ref",
    "to_native",
    "id_parts",
    "id_part_as",
    "enter_counted",
    "enter_with_id",
    "enter_unbuilt",
    "enter_next",
    "count_transitions",
    "count_and_enter",
    "record_next",
    "with_id",
    "selected",
    "typed_run",
    "gc_tick",
    "step_done",
    "fault",
    "push_level",
    "close_level",
    "nat_empty",
    "nat_enter",
    "nat_eval",
    "nat_condition",
    "nat_perform",
    "nat_var_op",
    "nat_var_op_fresh",
    "nat_arith_condition",
    "nat_is",
    // A plain function on native values: reads the store and the globals
    // only (`machine::plain_fn`); compiled to Rust too (`plain_rs`: its
    // slot the machine's, no frame's).
    "nat_plain",
    "nat_plain_rs",
    // An out_arg's value set as the pipe: the run's pipe, no frame's
    // (`Cx::out_value`).
    "out_value",
    "perform_value",
    "global_as",
    "global_inc",
    "global_set",
];

/// The `run` (`TypedRun`) methods that give the machine control: after a
/// hand-over only.
const RUN_TO_MACHINE: &[&str] = &["go", "goto", "go_eval"];

/// The evaluator's calls moved to the boundary: `cx.<from>(args)` becomes
/// `cx.<to>(stack, args)`.
const MOVED: &[(&str, &str)] = &[
    ("eval", "nat_eval"),
    ("condition", "nat_condition"),
    ("var_op", "nat_var_op"),
    ("var_op_fresh", "nat_var_op_fresh"),
    ("arith_condition", "nat_arith_condition"),
    ("is", "nat_is"),
];

/// Arc code `code` of a DM whose hand-over is `hand`, with its calls of
/// the evaluator at the boundary (module doc): where `code` calls the
/// evaluator (`cx.eval`, `cx.condition`, `cx.var_op`) and its DM has no
/// locals, every hand-over of the runtime's dropped, the evaluator's calls
/// made the `nat_` calls, and a hand-over put back
/// before each statement that gives the machine anything ([`late`]: in
/// the block where it is, so a fallback's `run.goto` gets its own); else
/// `code`. `None` of [`late`] (a call where no statement can take a
/// hand-over before it) keeps `code`.
pub(super) fn at_boundary(hand: &TokenStream, code: TokenStream) -> TokenStream {
    if !super::runtime_hand(hand) || !calls(&code, &["eval", "condition", "var_op", "var_op_fresh"])
    {
        return code;
    }
    let mut dropped = false;
    let cand = drop_hands(&code, &mut dropped);
    if !dropped {
        return code;
    }
    let cand = moved(&cand);
    let toks: Vec<TokenTree> = cand.into_iter().collect();
    match late(&toks) {
        Some(out) => out.into_iter().collect(),
        None => code,
    }
}

/// Whether `code` calls `cx.<m>` for an `m` of `names`.
fn calls(code: &TokenStream, names: &[&str]) -> bool {
    let toks: Vec<TokenTree> = code.clone().into_iter().collect();
    toks.iter().enumerate().any(|(k, t)| match t {
        TokenTree::Group(g) => calls(&g.stream(), names),
        _ => method_at(&toks, k, "cx").is_some_and(|m| names.contains(&m.as_str())),
    })
}

/// The method name of `<recv>.<m>(` at `toks[k]` (`k` at `recv`).
fn method_at(toks: &[TokenTree], k: usize, recv: &str) -> Option<String> {
    match (&toks[k], toks.get(k + 1), toks.get(k + 2), toks.get(k + 3)) {
        (
            TokenTree::Ident(r),
            Some(TokenTree::Punct(dot)),
            Some(TokenTree::Ident(m)),
            Some(TokenTree::Group(g)),
        ) if r == recv && dot.as_char() == '.' && g.delimiter() == Delimiter::Parenthesis => {
            Some(m.to_string())
        }
        // `cx.step_done::<T>(..)`-like turbofish calls are not made here.
        _ => None,
    }
}

/// Whether `toks[k..]` starts with the runtime's hand-over statement
/// `super::nat_hand_over(p, cx, stack)?;`: its length.
fn hand_at(toks: &[TokenTree], k: usize) -> Option<usize> {
    let stmt: TokenStream = quote::quote!(super::nat_hand_over(p, cx, stack)?;);
    let want: Vec<String> = stmt.into_iter().map(|t| t.to_string()).collect();
    let n = want.len();
    (k + n <= toks.len()
        && toks[k..k + n]
            .iter()
            .zip(&want)
            .all(|(t, w)| t.to_string() == *w))
    .then_some(n)
}

/// `code` without the runtime's hand-over statements (`dropped` set
/// where there was one).
fn drop_hands(code: &TokenStream, dropped: &mut bool) -> TokenStream {
    let toks: Vec<TokenTree> = code.clone().into_iter().collect();
    let mut out = Vec::with_capacity(toks.len());
    let mut k = 0;
    while k < toks.len() {
        if let Some(n) = hand_at(&toks, k) {
            *dropped = true;
            k += n;
            continue;
        }
        match &toks[k] {
            TokenTree::Group(g) => out.push(regroup(g, drop_hands(&g.stream(), dropped))),
            t => out.push(t.clone()),
        }
        k += 1;
    }
    out.into_iter().collect()
}

fn regroup(g: &Group, stream: TokenStream) -> TokenTree {
    let mut n = Group::new(g.delimiter(), stream);
    n.set_span(g.span());
    TokenTree::Group(n)
}

/// Whether `toks[k]` is the `nat_hand_over` of a hand-over (the runtime's
/// or a DM's own).
fn is_hand(t: &TokenTree) -> bool {
    matches!(t, TokenTree::Ident(i) if i == "nat_hand_over")
}

/// `code` with each of [`MOVED`]'s calls made its boundary call (after
/// a hand-over, [`late`]'s, the boundary call finds no frame below and
/// is the machine's own).
fn moved(code: &TokenStream) -> TokenStream {
    let toks: Vec<TokenTree> = code.clone().into_iter().collect();
    let mut out = Vec::with_capacity(toks.len());
    let mut k = 0;
    while k < toks.len() {
        if let Some(m) = method_at(&toks, k, "cx") {
            if let Some((_, to)) = MOVED.iter().find(|(from, _)| *from == m) {
                let args = moved(&args_group(&toks[k + 3]).stream());
                let stack = Ident::new("stack", Span::call_site());
                let comma = Punct::new(',', Spacing::Alone);
                out.push(toks[k].clone());
                out.push(toks[k + 1].clone());
                out.push(TokenTree::Ident(Ident::new(to, Span::call_site())));
                out.push(regroup(
                    args_group(&toks[k + 3]),
                    quote::quote!(#stack #comma #args),
                ));
                k += 4;
                continue;
            }
        }
        match &toks[k] {
            TokenTree::Group(g) => out.push(regroup(g, moved(&g.stream()))),
            t => out.push(t.clone()),
        }
        k += 1;
    }
    out.into_iter().collect()
}

/// The statements of a block `toks` with the runtime's hand-over put
/// before each statement that gives the machine anything ([`needs_hand`])
/// and follows no hand-over in this block; a block inside (a `let ..
/// else`'s, an `if`'s, a block expression's) is one of its own. `None`
/// where such a call is in a `match`'s arms but not in a block of one.
fn late(toks: &[TokenTree]) -> Option<Vec<TokenTree>> {
    let hand: Vec<TokenTree> = quote::quote!(super::nat_hand_over(p, cx, stack)?;)
        .into_iter()
        .collect();
    let mut out: Vec<TokenTree> = Vec::with_capacity(toks.len());
    let mut start = 0;
    let mut handed = false;
    for (k, t) in toks.iter().enumerate() {
        if is_hand(t) {
            handed = true;
        }
        if !handed {
            let gives = match t {
                TokenTree::Group(g) if g.delimiter() == Delimiter::Brace && !arms(g) => {
                    let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                    out.push(regroup(g, late(&inner)?.into_iter().collect()));
                    continue;
                }
                TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => {
                    // A `match`'s arms: each arm's block is a block.
                    let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                    let mut arms_out = Vec::with_capacity(inner.len());
                    for a in &inner {
                        match a {
                            TokenTree::Group(b) if b.delimiter() == Delimiter::Brace => {
                                let body: Vec<TokenTree> = b.stream().into_iter().collect();
                                arms_out.push(regroup(b, late(&body)?.into_iter().collect()));
                            }
                            TokenTree::Group(b) if needs_hand(&b.stream(), false) => return None,
                            a => arms_out.push(a.clone()),
                        }
                    }
                    if gives_at(&inner, false) {
                        return None;
                    }
                    out.push(regroup(g, arms_out.into_iter().collect()));
                    continue;
                }
                TokenTree::Group(g) => needs_hand(&g.stream(), false) || gives_fn(toks, k),
                _ => gives_call(toks, k),
            };
            if gives {
                out.splice(start..start, hand.iter().cloned());
                handed = true;
            }
        }
        out.push(t.clone());
        if matches!(t, TokenTree::Punct(p) if p.as_char() == ';') {
            start = out.len();
        }
    }
    Some(out)
}

/// Whether a brace group is a `match`'s arms (`=>` in it).
fn arms(g: &Group) -> bool {
    let toks: Vec<TokenTree> = g.stream().into_iter().collect();
    toks.windows(2).any(|w| {
        matches!(
            (&w[0], &w[1]),
            (TokenTree::Punct(a), TokenTree::Punct(b))
                if a.as_char() == '=' && a.spacing() == Spacing::Joint && b.as_char() == '>'
        )
    })
}

/// Whether the tokens of a `match`'s arms give the machine anything
/// outside the arms' blocks (a call in an arm's pattern or expression).
fn gives_at(toks: &[TokenTree], _handed: bool) -> bool {
    toks.iter().enumerate().any(|(k, t)| match t {
        TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => false,
        TokenTree::Group(g) => needs_hand(&g.stream(), false) || gives_fn(toks, k),
        _ => gives_call(toks, k),
    })
}

fn args_group(t: &TokenTree) -> &Group {
    match t {
        TokenTree::Group(g) => g,
        _ => unreachable!("a call's arguments"),
    }
}

/// Whether `toks[k]` starts a call that gives the machine anything: a
/// `cx` method not in [`SAFE`], a `run` method of [`RUN_TO_MACHINE`].
fn gives_call(toks: &[TokenTree], k: usize) -> bool {
    method_at(toks, k, "cx").is_some_and(|m| !SAFE.contains(&m.as_str()))
        || method_at(toks, k, "run").is_some_and(|m| RUN_TO_MACHINE.contains(&m.as_str()))
}

/// Whether the group `toks[k]` is the arguments of a function given `cx`
/// (not a method of it) other than the driver's own, which hand over
/// themselves, `run`'s (read by [`gives_call`]) and a closure called at
/// once (`(|cx: &mut Ctx| ..)(cx)`, whose body is read with the rest).
fn gives_fn(toks: &[TokenTree], k: usize) -> bool {
    let TokenTree::Group(g) = &toks[k] else {
        return false;
    };
    if g.delimiter() != Delimiter::Parenthesis || !passes_cx(&g.stream()) {
        return false;
    }
    let before = k.checked_sub(1).map(|j| &toks[j]);
    let known = matches!(before, Some(TokenTree::Ident(i)) if [
        "nat_goto",
        "nat_template",
        "no_exit",
        "end",
        "end_at",
        "tally",
        "record_next",
        "count_but_this",
        "close_level",
        "recorded",
        // `machine::arm_calls`: `nat_empty` (given `stack`), an entry, a
        // push (`push_level`), a `ground` performed (handing over itself
        // where it must), and `NatBelow::call_held` (the same).
        "empty",
        "exit_empty",
        "entry",
        "exit_end",
        "push",
        "perform",
        "call_held",
    ]
    .contains(&&*i.to_string()));
    let closure =
        matches!(before, Some(TokenTree::Group(c)) if c.delimiter() == Delimiter::Parenthesis);
    !known && !closure
}

/// Whether `code` gives the machine anything ([`gives_call`],
/// [`gives_fn`]) before a hand-over in its block (`handed`: one came
/// before in an enclosing block).
fn needs_hand(code: &TokenStream, handed: bool) -> bool {
    let toks: Vec<TokenTree> = code.clone().into_iter().collect();
    let mut handed = handed;
    for (k, t) in toks.iter().enumerate() {
        if is_hand(t) {
            handed = true;
        }
        if handed {
            continue;
        }
        if gives_call(&toks, k) || gives_fn(&toks, k) {
            return true;
        }
        if let TokenTree::Group(g) = t {
            if needs_hand(&g.stream(), handed) {
                return true;
            }
        }
    }
    false
}

/// Whether a call's arguments `args` pass `cx` itself (an argument that
/// is `cx` alone).
fn passes_cx(args: &TokenStream) -> bool {
    let toks: Vec<TokenTree> = args.clone().into_iter().collect();
    toks.split(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == ','))
        .any(|a| matches!(a, [TokenTree::Ident(i)] if i == "cx"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    fn hand() -> TokenStream {
        quote!(super::nat_hand_over(p, cx, stack)?;)
    }

    #[test]
    fn an_evaluated_action_is_called_at_the_boundary() {
        let code = quote! {
            let exp: Term = Term::EMPTY;
            super::nat_hand_over(p, cx, stack)?;
            cx.enter_counted(&mut count, 2, id2);
            let b1 = cx.eval(b0, arc_at)?;
            let act = cx.nat_perform(stack, arc_at, cx.build(a.say, &[b1]), run)?;
            let next_at: Nat = Nat::S6 { r4: r5 };
            run.end(cx, &mut count, exp, act, |s| next_at.id_term(p, s));
            next_at
        };
        let got = at_boundary(&hand(), code).to_string();
        assert!(!got.contains("nat_hand_over"), "{got}");
        assert!(
            got.contains(&quote!(cx.nat_eval(stack, b0, arc_at)).to_string()),
            "{got}"
        );
        assert!(
            got.contains(
                &quote!(cx.nat_perform(stack, arc_at, cx.build(a.say, &[b1]), run)).to_string()
            ),
            "{got}"
        );
    }

    #[test]
    fn a_call_that_needs_the_machine_gets_a_hand_over_before_it() {
        // A perception chosen by the machine after the evaluation: handed
        // over before it, on every path.
        let code = quote! {
            super::nat_hand_over(p, cx, stack)?;
            let b1 = cx.eval(b0, arc_at)?;
            let Some(chosen) = cx.choose(type_term)? else {
                return Ok(None);
            };
        };
        let got = at_boundary(&hand(), code).to_string();
        let want = quote! {
            let b1 = cx.nat_eval(stack, b0, arc_at)?;
            super::nat_hand_over(p, cx, stack)?;
            let Some(chosen) = cx.choose(type_term)? else {
                return Ok(None);
            };
        };
        assert_eq!(got, want.to_string());
        // A next situation handed to the machine where a value does not
        // convert: handed over there only.
        let code = quote! {
            super::nat_hand_over(p, cx, stack)?;
            let b1 = cx.eval(b0, arc_at)?;
            let Some(r7) = cx.to_native::<Val>(b1) else {
                let this = run.count_but_this(cx, count);
                return run.go_eval(cx, this, exp, act, b0, arc_at);
            };
        };
        let want = quote! {
            let b1 = cx.nat_eval(stack, b0, arc_at)?;
            let Some(r7) = cx.to_native::<Val>(b1) else {
                let this = run.count_but_this(cx, count);
                super::nat_hand_over(p, cx, stack)?;
                return run.go_eval(cx, this, exp, act, b0, arc_at);
            };
        };
        assert_eq!(at_boundary(&hand(), code).to_string(), want.to_string());
        // A DM with locals: its own hand-over writes them back.
        let own = quote!(nat_hand_over(p, cx, stack, &*l0)?;);
        let code = quote! {
            nat_hand_over(p, cx, stack, &*l0)?;
            let b1 = cx.eval(b0, arc_at)?;
        };
        assert_eq!(
            at_boundary(&own, code.clone()).to_string(),
            code.to_string()
        );
        // A call in a `match` arm's expression: kept as it is.
        let code = quote! {
            super::nat_hand_over(p, cx, stack)?;
            let b1 = cx.eval(b0, arc_at)?;
            match x { 0 => cx.error("e", arc_at), _ => cx.error("f", arc_at) }
        };
        assert_eq!(
            at_boundary(&hand(), code.clone()).to_string(),
            code.to_string()
        );
    }

    #[test]
    fn a_later_hand_over_covers_what_follows_it_in_its_block() {
        let code = quote! {
            let next_at: Nat = {
                super::nat_hand_over(p, cx, stack)?;
                count = run.count_but_this(cx, count);
                cx.enter_unbuilt(2);
                let evaluated = (|cx: &mut Ctx| -> Result<bool, RunError> {
                    let b0 = cx.condition(b1, arc_at)?;
                    Ok(b0)
                })(cx);
                if cond { Nat::S3 {} } else {
                    super::nat_hand_over(p, cx, stack)?;
                    cx.count_and_enter(count, run.records, 2, a.r#try);
                    return run.goto(cx, exp, act, rec_next, arc_at);
                }
            };
        };
        let got = at_boundary(&hand(), code).to_string();
        assert!(
            got.contains(&quote!(cx.nat_condition(stack, b1, arc_at)).to_string()),
            "{got}"
        );
        assert_eq!(got.matches("nat_hand_over").count(), 1, "{got}");
    }
}
