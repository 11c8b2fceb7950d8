//! Perceptions chosen with the native frames kept (issue 37: "boundaries
//! converted once"). A perceptual situation (or a neutral one with several
//! arcs) builds its expectations as terms from native values and the
//! machine chooses the arc; this module generates that choice so that the
//! native frames below stay native on the path a perception takes when it
//! meets an expectation, and are handed over (`nat_hand_over`: made the
//! machine's frames, the locals written back) only on the cold paths.
//!
//! # What the hand-over protects before a perception
//! The machine's choice (`Machine::choose_index`, through `Cx::choose`)
//! reads the machine's frames, which below native code are not the
//! running DM's until the hand-over (the machine's top frame is the native
//! stack's bottom, the DM the machine entered):
//! - *the prompt*: before it reads, the perception is told where it waits
//!   (`Perception::waiting_at`: the top frame's DM call and the
//!   situation's id), which the interactive prompts show
//!   (`DM find(..), situation look(..) expects: ..`) and the watch and
//!   console wrappers forward;
//! - *an input that meets no expectation*: recorded with the top frame's
//!   DM call and the stack's depth for the report (`Observer::unmatched`,
//!   the report's unmatched inputs), and, for typed or scripted input
//!   (`Perception::unmatched_is_news`), the run's warning (once per DM and
//!   situation: the DM is `Machine::warning_dm`, the top frame's); the
//!   second read an action list's expectation allows comes after those;
//! - *errors*: the end of input, a perception that fails, a situation
//!   without arcs and a `neutral` type with several arcs are errors that
//!   name the running DM (`Machine::err`: the top frame's call);
//! - *no expectation met* (`Step::Unmet`, D-15) and `Perceived::Again`
//!   (a hot reload while waiting, `sitlogc watch`): the machine goes on
//!   with the situation as a new instance, from its template, and may
//!   call the recovery DM: from then on the machine runs the frames, so
//!   they must be its own (the locals written back);
//! - *garbage collection* is not among them: the machine collects only
//!   between visits (`Cx::gc_tick`, after a hand-over), never inside a
//!   perception, so the terms and `Ground` handles native code holds stay
//!   valid across it; nor is the test-mode script reader (it reads the
//!   next input whatever the stack; `ScriptPerception` ignores the
//!   expectations it is given) or the robot's senses (they answer the
//!   situation's type). The live debugger (`sitlog-debug`) shows the
//!   machine's state between steps, not during a read (its input prompt
//!   has the store only).
//!
//! So the hand-over before a perception protects what the machine reads of
//! its frames *after* an input meets nothing, or *instead of* an input, and
//! the prompt's "where". None of it is read when the input meets an
//! expectation of a perception that is not told where it waits.
//!
//! # The code
//! `machine::nat_choose(p, cx, stack, type_term)` (a DM with locals:
//! `cx.choose_kept(type_term, |cx| nat_hand_over(p, cx, stack, ..))`),
//! after `cx.set_expectations(&[e0, e1])`, asks `Machine::perceive_kept`: with arcs, a type
//! other than `neutral` and a perception whose `waiting_at` does nothing
//! (`Perception::uses_waiting_at` false: the test-mode script, the
//! simulated and the ROS robot's senses), it perceives and matches the
//! input against the expectations with the machine's matcher, the last
//! that unifies winning, exactly as `choose_index` does, on the terms
//! built (an input the perception hands over as `said(Input)` not built,
//! `Percept::Wrapped`, is unified with each expectation `said(E)`'s
//! argument in place: the same bindings as the compounds', no `said(..)`
//! made unless nothing is met); a met expectation returns its arc, nothing else done: the native
//! frames are kept. Otherwise (nothing read, or what was read: an input
//! that meets nothing, the end of input, an error, `Again`) the closure
//! hands the frames over and the machine's `choose_index` goes on from
//! what was read (`first`), so the unmatched input's record, warning,
//! second read, error and `Step::Unmet` are the interpreter's, byte for
//! byte. The variables a perception binds (`said(X)`, `objects(L)`,
//! `hands(_, free)`) are read natively in the chosen arc after the checked
//! conversion, once, where the arc's code reads them (as before).
//!
//! A situation whose id is filled from native values (`q([P|Ps])`: the
//! rest of a walked list converted, its length at every visit) is entered
//! with the id built only where it is read ([`lazy_id`]: the history, or
//! the cold path, where `Cx::choose_kept_at` builds it before the machine
//! reads it), when its arms take only steps that build from the id's parts.
//!
//! Kept only when building the expectations and the type term calls
//! nothing that reads the machine's state (`cx.build`, `cx.term`,
//! `cx.fill`, constants: [`builds_only`]); an expectation that evaluates
//! (`get(v, X)`, a user function) keeps the hand-over first, as before.

use proc_macro2::{Ident, TokenStream, TokenTree};
use quote::quote;

/// The `cx` calls that only build terms from native values and constants
/// (no evaluation, no read of the machine's frames, locals or globals).
const BUILDS: &[&str] = &["build", "build_of", "term", "fill", "store", "list"];

/// Whether `code` (the statements building the expectations and the type
/// term) only builds terms: every `cx.<method>` one of [`BUILDS`], no `?`
/// (nothing that can fail), no hand-over.
pub(super) fn builds_only(code: &TokenStream) -> bool {
    let toks: Vec<TokenTree> = code.clone().into_iter().collect();
    for (k, t) in toks.iter().enumerate() {
        match t {
            TokenTree::Group(g) if !builds_only(&g.stream()) => return false,
            TokenTree::Punct(p) if p.as_char() == '?' => return false,
            TokenTree::Ident(i) if i == "nat_hand_over" || i == "machine" => return false,
            TokenTree::Ident(i) if i == "cx" => {
                if let (Some(TokenTree::Punct(dot)), Some(TokenTree::Ident(m))) =
                    (toks.get(k + 1), toks.get(k + 2))
                {
                    if dot.as_char() == '.' && !BUILDS.iter().any(|b| m == b) {
                        return false;
                    }
                }
            }
            _ => {}
        }
    }
    true
}

/// The hand-over statement of a DM (`Dm::hand`: `super::nat_hand_over(p,
/// cx, stack)?;`, or the DM's own with its locals) as an expression of
/// its `Result` (the trailing `?;` taken off), for the closure
/// `Cx::choose_kept` calls on its cold path; `None` when it is not of that
/// form.
pub(super) fn hand_expr(hand: &TokenStream) -> Option<TokenStream> {
    let mut toks: Vec<TokenTree> = hand.clone().into_iter().collect();
    let semi = matches!(toks.pop()?, TokenTree::Punct(p) if p.as_char() == ';');
    let question = matches!(toks.pop()?, TokenTree::Punct(p) if p.as_char() == '?');
    (semi && question && !toks.is_empty()).then(|| toks.into_iter().collect())
}

/// The choice of a perceptual situation's arc with the native frames kept
/// (see the module doc): the situation entered (`enter`: its id built and
/// `cx.enter_counted`), the expectations `names` built by `exps` and set,
/// the type term built by `ty_stmts` and `ty`, then `Cx::choose_kept` (the
/// frames handed over by `hand` on its cold path; `machine::nat_choose`
/// for the runtime's hand-over, a DM without locals), `Step::Unmet` when
/// no expectation is met, else the `arms`. `None` when it cannot be kept
/// (building calls more than [`BUILDS`], a hand-over of another form):
/// the caller hands over first, as before.
/// With `lazy` ([`lazy_id`]), the situation is entered by it and its id
/// built on the cold path only (`Cx::choose_at`, `Cx::choose_kept_at`).
#[allow(clippy::too_many_arguments)]
pub(super) fn kept_choice(
    hand: &TokenStream,
    enter: &TokenStream,
    lazy: Option<(TokenStream, TokenStream)>,
    exps: &[TokenStream],
    names: &[Ident],
    ty_stmts: &[TokenStream],
    ty: &TokenStream,
    arms: &[TokenStream],
) -> Option<TokenStream> {
    let built = quote!(#(#exps)* #(#ty_stmts)* #ty);
    if !builds_only(&built) {
        return None;
    }
    let runtime = quote!(super::nat_hand_over(p, cx, stack)?;).to_string();
    let (enter, choose) = match (lazy, hand.to_string() == runtime) {
        (None, true) => (
            enter.clone(),
            quote!(machine::nat_choose(p, cx, stack, type_term)),
        ),
        (None, false) => {
            let hand = hand_expr(hand)?;
            (enter.clone(), quote!(cx.choose_kept(type_term, |cx| #hand)))
        }
        (Some((enter, id)), true) => (enter, quote!(cx.choose_at(stack, type_term, #id))),
        (Some((enter, id)), false) => {
            let hand = hand_expr(hand)?;
            (enter, quote!(cx.choose_kept_at(type_term, #id, |cx| #hand)))
        }
    };
    Some(quote! {
        #enter
        #(#exps)*
        cx.set_expectations(&[#(#names),*]);
        #(#ty_stmts)*
        let type_term = #ty;
        let Some(chosen) = #choose? else {
            return Ok(Some(Step::Unmet { type_term }));
        };
        match chosen {
            #(#arms)*
            _ => unreachable!("the machine chose an arc of this situation"),
        }
    })
}

/// The `cx` calls a chosen arm may make for its situation's id to be built
/// only where it is read ([`lazy_id`]): the entry of the next situation
/// from the id's parts (`nat_empty`), terms built, the hand-over and the
/// count before a `run.goto` (`count_and_enter`, which enters the
/// situation by its name where nothing records).
const ARM_STEPS: &[&str] = &[
    "nat_empty",
    "count_and_enter",
    "build",
    "build_of",
    "term",
    "fill",
    "store",
];

/// The entry of a perceptual situation whose id is filled from native
/// values (`let idN = cx.fill(..)`: a list part costs its length at every
/// visit) and read, where nothing records, by nothing but the choice's
/// cold path: `let idN = Fill(..); cx.enter_perceiving(&mut count, cur,
/// idN);` and `idN` for the choice (`Cx::choose_kept_at`). `None` (the id
/// built first, as before) for an id of another form or when an arm does
/// more than [`ARM_STEPS`] (anything else may read the id: an error names
/// it) or ends in `run.goto` without `count_and_enter` first.
pub(super) fn lazy_id(
    fill: Option<TokenStream>,
    id: &TokenStream,
    cur: &proc_macro2::Literal,
    arms: &[TokenStream],
) -> Option<(TokenStream, TokenStream)> {
    let fill = fill?;
    if !arms.iter().all(arm_steps_only) {
        return None;
    }
    Some((
        quote!(let #id = #fill; cx.enter_perceiving(&mut count, #cur, #id);),
        id.clone(),
    ))
}

/// Whether `code` calls no `cx` method but [`ARM_STEPS`] and no `run.goto`
/// before a `count_and_enter`.
fn arm_steps_only(code: &TokenStream) -> bool {
    fn walk(code: &TokenStream, entered: &mut bool) -> bool {
        let toks: Vec<TokenTree> = code.clone().into_iter().collect();
        for (k, t) in toks.iter().enumerate() {
            let method = |recv: &str| match (t, toks.get(k + 1), toks.get(k + 2)) {
                (TokenTree::Ident(i), Some(TokenTree::Punct(dot)), Some(TokenTree::Ident(m)))
                    if i == recv && dot.as_char() == '.' =>
                {
                    Some(m.to_string())
                }
                _ => None,
            };
            if let TokenTree::Group(g) = t {
                if !walk(&g.stream(), entered) {
                    return false;
                }
            } else if let Some(m) = method("cx") {
                if !ARM_STEPS.contains(&m.as_str()) {
                    return false;
                }
                *entered |= m == "count_and_enter";
            } else if (method("run").as_deref() == Some("goto") && !*entered)
                || matches!(t, TokenTree::Ident(i) if i == "machine")
            {
                return false;
            }
        }
        true
    }
    walk(code, &mut false)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builds_only_accepts_term_building() {
        let t = quote! {
            let e0 = cx.build(a.hands, &[fresh_r1, Term::atom(a.free)]);
            let e1 = { let b1 = cx.term(&r0); b1 };
        };
        assert!(builds_only(&t));
    }

    #[test]
    fn builds_only_refuses_evaluation_and_hand_over() {
        assert!(!builds_only(&quote!(let e0 = cx.eval(t, None)?;)));
        assert!(!builds_only(&quote!(let e0 = { cx.var_op(a, b)?; x };)));
        assert!(!builds_only(&quote!(super::nat_hand_over(p, cx, stack)?;)));
    }

    #[test]
    fn an_arms_steps_decide_whether_the_id_is_built_lazily() {
        let ok = quote! {
            0 => {
                if run.records || !run.quiet_empty {
                    cx.nat_empty(stack, &mut count, 2, 0, p.k[3], (&r3, r4))?;
                }
                run.tally(&mut count);
                super::nat_hand_over(p, cx, stack)?;
                cx.count_and_enter(count, run.records, 2, a.q);
                let rec_next = cx.build_of(a.q, &[v0]);
                return run.goto(cx, exp, act, rec_next, Some(1));
            }
        };
        assert!(arm_steps_only(&ok));
        assert!(!arm_steps_only(&quote!(0 => { cx.perform(t, Some(0))?; })));
        assert!(!arm_steps_only(
            &quote!(0 => { return run.goto(cx, exp, act, n, None); })
        ));
        assert!(!arm_steps_only(
            &quote!(0 => { machine::nat_template(p, cx, stack); })
        ));
        let id = quote!(id3);
        let cur = proc_macro2::Literal::usize_unsuffixed(2);
        let fill = Some(quote!(Fill(p.k[3], (&r3, r4))));
        let (enter, arg) = lazy_id(fill.clone(), &id, &cur, &[ok]).unwrap();
        assert_eq!(arg.to_string(), "id3");
        assert!(enter.to_string().contains("enter_perceiving"));
        assert!(lazy_id(None, &id, &cur, &[]).is_none());
        assert!(lazy_id(fill, &id, &cur, &[quote!(cx.eval(t, None)?;)]).is_none());
    }

    #[test]
    fn hand_expr_takes_off_the_question_mark() {
        let e = hand_expr(&quote!(super::nat_hand_over(p, cx, stack)?;)).unwrap();
        assert_eq!(
            e.to_string(),
            quote!(super::nat_hand_over(p, cx, stack)).to_string()
        );
        assert!(hand_expr(&quote!()).is_none());
        assert!(hand_expr(&quote!(f();)).is_none());
    }
}
