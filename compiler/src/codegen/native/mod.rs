//! Native code (phases 4 and 6 of `docs/design/typed-mir.md`): the
//! situations of a DM that can run natively do, on Rust values, and the
//! others run on the DM's term code; the two cross at a situation boundary
//! through the machine. In a native situation each MIR register is a Rust
//! local of its type (`i64`, `f64`, `Atom`, `List<T>`, and a canonical
//! [`Val`](sitlog_runtime::native::Val) for `ground` and fixed-shape
//! compounds, through [`sitlog_runtime::native::Native`]), each situation a
//! variant of the DM's `enum Nat` whose fields are its id's variables
//! (`S2 { r5: Atom, r6: List<Atom> }` for `try([P|Ps])`), a computed next
//! situation selected by a Rust `match`/`if let` on the value, in source
//! order, as the machine selects (D-21), and `==`/`\==` and integer
//! comparisons done in Rust.
//!
//! The boundaries, and why the run is the term path's, step for step:
//! - *entry*: `nat_entry(sit)` is tried whenever situation `sit` runs
//!   (by the program's `run_situation` for an all-native DM, else by the
//!   DM's `run_native(sit)`),
//!   with the history kept or not. The id's arguments (from the value
//!   that selected it) and the parameters the native situations read are
//!   converted with the checked conversion (`Native::from_term` through
//!   `Cx::id_parts`/`id_part_as`/`param_as`/`local_as`, in the DM's `nat_entry`; for a
//!   `Val`: ground, inert, proper lists, no big integer). A value that does
//!   not fit leaves the visit to the machine, nothing done: a situation with
//!   native code has no term code (`codegen::emit`), so `run_situation`
//!   returns `Step::Template` and the machine runs it from its template,
//!   as the interpreter does (correct, slower, rare). A situation whose
//!   visit runs its template on every path ([`Visit::Template`]) has no
//!   entry at all: converting its fields and the parameters only to build
//!   them back as terms made a walk on its template quadratic (issue 37,
//!   `nstock23`), so the machine runs it from its template, nothing
//!   converted. "Term code" below
//!   means, for such a situation, that path. Where native code needs a
//!   situation's id as a term (entering it, its history entry, a
//!   hand-over, a wait), it is filled from its pattern, a constant with a
//!   hole where each field goes (`Cx::fill`, module `fill`; the DM's
//!   `id_s<N>` builds it where no pattern reads back). Terms of two
//!   compounds or more built from native values (an action's, an evaluated
//!   call's) are filled from their patterns too.
//! - *values*: native values are ground and evaluate to themselves in L
//!   (atoms, numbers and lists of them are inert, D-28/D-36; a `Val` is
//!   converted from an inert term), so a condition `X == Y` is Rust's `==`
//!   on them (a `Val` is canonical: `[]` an empty list, so `==` is
//!   Prolog's), and a value matched against an id pattern binds exactly
//!   what unification would.
//! - *situations without native code*: a next situation that selects one
//!   (the first candidate in source order without native code, or a
//!   constant name) is built as a term and given to the machine
//!   ([`Cx::goto`]), which selects and runs its term code; so is a value no
//!   situation takes natively (the machine selects or reports the error),
//!   and the id of the situation reached when the machine wants control
//!   (garbage to collect, a stop asked), checked between two visits of
//!   the frame's loop by `Cx::gc_tick` (then `machine::nat_goto` in a DM
//!   without locals; `Cx::gc_due` asked once every
//!   `GC_TICKS` checks, so at most `GC_TICKS - 1` visits later; at every
//!   check for a GC threshold below `GC_TICKS_BELOW`).
//! - *effectors and the evaluator*: an action's term (`say(['Hi', Name])`,
//!   `navigate(P, S)`, a list of them) is built from native values where it
//!   is performed, as the term code would evaluate it; a part the evaluator
//!   computes (`apply(name_of(_), [user])`, `assign/2`) is handed to it as
//!   a term built from native values. A fresh variable of the action is a
//!   term made there; one the next situation reads (a status, a value a
//!   user function bound) is converted back with the checked conversion,
//!   and when that fails the rest of the arc (the next situation) runs on
//!   terms: the next situation as written, filled with the native values,
//!   evaluated whole as the machine evaluates an arc's next situation
//!   (`TypedRun::go_eval`, or `cx.eval` then `run.go` when the arc has an
//!   out_arg), or, with a condition, a `get`/`is` or a constant that is not
//!   atomic in it (or when it is a constant or a variable alone), by the
//!   term code's steps.
//! - *finals*: the final situation's id is built as a term, the machine
//!   entered in it, its (empty) out_arg, its `diag_mod` (a term built from
//!   native values: the DM's output arguments) and history entry taken as
//!   the term code takes them; the caller's exit arcs read that id.
//!   *Output parameters* (`DmTypes::outputs`: unbound when the DM is
//!   called, bound by every final's `diag_mod`) are output slots: the frame
//!   keeps the caller's term (an unbound variable, shown as the term path
//!   shows it in the DM's id), and a final computes the value it binds as
//!   a Rust local of the output type (`let o2: Atom = ..`), converted once
//!   where `diag_mod` hands it to the machine (`Gen::nat_output_slots`). A
//!   native caller that passed its fresh variable as no term
//!   (`Ground::OUT`, [`call`]) gets the value in the frame's output slot
//!   (`out<i>`) instead, nothing unified: the final's `diag_mod` is the
//!   head with every other argument the parameter itself.
//! - *the history*: where the term code records an entry (an arc: after
//!   its action, next situation and out_arg; a final), native code records
//!   the same one (`cx.record`: the situation entered with its id, the
//!   expectation the machine matched or one built from native values, the
//!   action performed, the next situation: the next `Nat`'s id or the
//!   value handed over), its terms built only when a history is kept or
//!   observed (`run.records`); otherwise it counts the transition, no term
//!   made. When observed (`run.records` without `run.nests`) every call is
//!   the machine's (the visit handed to the machine, which runs it from its
//!   template: the callee's entries nest in the caller's), so the native
//!   stack stays empty and `nat_hand_over` only writes the locals back.
//!   With the history kept and nothing observing (`run.nests`) a call whose
//!   exit arcs record natively is pushed, the callee's entries in a history
//!   level of their own (`Cx::open_level`/`close_level`, [`call`]), which a
//!   frame made the machine's takes (`Cx::wait_template`).
//! - *`term` registers* (a parameter or id part nothing reads, loaded from
//!   a place typed `term`): held as a
//!   [`Ground`](sitlog_runtime::native::Ground) handle, checked ground and
//!   inert where converted; the handles stay valid because the machine
//!   collects garbage only after native code has handed over.
//!
//! - *perceptions* ([`perceive`]): a perceptual situation (or a neutral
//!   one with several arcs) builds its expectations as terms from native
//!   values, and the machine chooses the arc (`Cx::choose_kept`,
//!   `machine::nat_choose`: the perception matched with the native frames
//!   below kept; handed over only where the machine reads them, an input
//!   that meets nothing, an error, a prompt; or `Step::Unmet` handed
//!   back); a variable the perception bound is read natively only after
//!   the checked conversion, as above.
//! - *locals, globals, `is`*: `get`/`set`/`inc` and `is` are the machine's
//!   own calls (`Cx::var_op`, `Cx::is`) on terms built from native values;
//!   what they bind is converted like a boundary's value. Except, when
//!   nothing is recorded, an arc whose action is only `inc`/`get` of the
//!   frame's locals or of globals (`Cx::global_inc`, `Cx::global_as`: the
//!   machine's globals read and written at each use, no copy kept; a name
//!   that is no local of the DM), `set(g, V)` of a global (`V` a value or
//!   a constant as written, `set(done, yes)`), `V is E` of ints into a fresh `int` variable
//!   (checked `i64`; an overflow is the machine's `is`), constants and
//!   values (`[inc(n, N)]`, `[J is I + 1]`): done on the frame's Rust
//!   locals and values, as an exit arc's; recorded, the same in a frame
//!   above the machine's (a callee pushed with the history kept, its entry
//!   built from the values: `Gen::nat_arc_rec_fast`), else the arc takes
//!   the machine's calls and makes its entry. An arc whose action binds a
//!   value at a boundary falls back to the term code's next situation and
//!   out_arg when that value does not convert. A fresh variable is made at
//!   the start of a visit only when code uses it before declaring it. In
//!   an expression (a comparison's operand, an out_arg), `get(v, _)` of a
//!   local held in the frame or of a global is the value read
//!   (`Gen::nat_var_get`), its `_` left unbound (nothing reads it). A
//!   condition's `get(v, D)` side (and an exit action's `get(v, X)`) is
//!   unified with its variable as the machine's `get` does: `D` bound to
//!   a register the code after it reads, or compared where it was bound
//!   before, the machine's error where they differ (`Gen::nat_get_unify`).
//!   `get(v, _)`/`inc(v, _)` of a local held in the frame (or `inc` of a
//!   global) in a next situation's arguments or an out_arg: computed once
//!   by native code in the machine's order (the next situation, then the
//!   out_arg), every fallback after it going on from the value computed
//!   (`Gen::nat_ev_effects`, `Gen::nat_next_out_after`).
//!
//! - *frames and calls* ([`frame`], [`call`]): each DM with native code
//!   has a `Frame` (parameters, locals, its `Nat`); the runtime's
//!   `machine::nat_drive` runs the program's `NatFrame`s on an explicit stack: a recursive situation
//!   with native code whose callee's initial situation has native code
//!   (and whose arguments fit the callee's frame) pushes the callee's
//!   frame (no Rust recursion, no term), the callee's final variant resumes
//!   the caller, whose exit arcs match it natively; every other call (the
//!   visit from its template, [`call`]: no exit arcs as term code), and
//!   every step that lets the machine see its state (an action performed,
//!   a situation handed over, `get`/`set`/`inc` through the machine), first
//!   makes the native frames machine frames and writes the locals back
//!   (`nat_hand_over`: the runtime's, or the DM's for a DM with locals),
//!   and reads the locals again after the machine's
//!   call; except, in a DM without locals, the evaluator's calls (a user
//!   function, the KB, a Prolog condition, `get`/`set`/`inc` of a
//!   global) and the performs after them, made where the frames are, the
//!   frames handed over only where one fails or before what gives the
//!   machine control ([`boundary`]). A call with an output argument is pushed so too when the
//!   callee hands it back in an output slot ([`call`]); other calls with a
//!   fresh variable are the machine's, the term built with the variable
//!   made for the visit.
//! - *the pipe* ([`pipe`]): read into a variable in_arg's register with a
//!   checked conversion, or matched against an in_arg that is a pattern
//!   (its variables registers; a pipe not taken natively is the machine's
//!   visit from the template), written back where an out_arg sets it; an
//!   out_arg `name(..)` of native values is held as those values
//!   (`Cx::hold_pipe`), which a native in_arg pattern reads where they are
//!   (`Cx::held_pipe`), a term only where something reads it as one.
//!
//! - *the evaluator's constructs*: an evaluated embedded DM call is built
//!   from native values and evaluated by `Cx::embedded_dm` (the machine's
//!   call); a conditional expression (`A -> B ; C`) as an action decides
//!   its condition in Rust (`==`/`\==` of native values) or as the term
//!   code does (`Cx::condition`, `Cx::arith_condition` on terms built from
//!   native values) and builds only the branch taken; so does a
//!   conditional next situation whose condition Rust cannot decide (the
//!   machine entered first; DMs without locals); a next situation the
//!   evaluator computes whole is evaluated and handed to the machine;
//!   compounds that evaluate to themselves (`take(O, S)`) and `[H|T]` of
//!   any native values are built as `Val`s (`Val::cons`). An error
//!   evaluating a next situation leaves its transition uncounted, as on
//!   the term path.
//! - *conjunctions and disjunctions* ([`cond`]): a condition `(A, B)` or
//!   `(A ; B)` the MIR lowered (`Cond::And`, `Cond::Or`) tests each operand
//!   in order, every one of them (the evaluator computes them all before
//!   calling the condition, D-35), then combines the `bool`s.
//!
//! What is not (yet) native keeps a situation on its term code: a `prog`
//! other than `V is E`, expectations that can
//! change a variable not held natively, a register read natively before it
//! is set, narrowing a `ground` value to a list or a compound, arithmetic
//! other than integer comparisons. (A `ground` value selecting a situation
//! whose id field is an atom or an int is narrowed with a check, `narrow`;
//! when it is another shape the machine selects. One whose id's list
//! pattern has a tail field typed `list<ground>`, `mir::ty`'s narrowing,
//! is split as a proper list, `Val::split_proper`, the tail a
//! `List<Val>`; an improper list goes to the machine.) `--explain-types`
//! says which and why, per situation.
//!
//! A register loaded from a frame's parameter or a callee's final field
//! that its visit reads only by reference (a comparison, a selected value)
//! is bound to it where it lies, not cloned (`by_ref_loads`).
//!
//! A situation (neither final nor recursive) whose id takes apart a list of
//! `Val`s by `[P|Ps]` holds the list itself, one field (`S2 { k5:
//! List<Val> }`, [`CellField`]): the visit reads `P` in place and makes `Ps`
//! (`List::head_tail`), a next situation `try(Ps)` moves `Ps` into the
//! variant after testing it non-empty (a `Val`: `Val::non_empty_list`, an
//! improper list handed to the machine as before); nothing is split at the
//! selection, no element cloned or dropped per visit. When the variant
//! holds the cell alone and the visit's next situation is its own with its
//! own tail (`try([P|Ps])` to `try(Ps)`), or holds other fields that this
//! next situation passes on as they are (`walk([P|Ps], T)` to `walk(Ps,
//! T)`, [`Gen::nat_cursor_passing`]: the fields cloned out for the visit),
//! the visit is a cursor
//! ([`Gen::nat_cursor`]): `P` cloned out, the list advanced in place
//! (`List::advance`), `Ps` the list itself by reference, and, unrecorded,
//! the variant left where it is (`break 'step`, no next variant built nor
//! moved; recorded, built as before for the entry's next id). A list of
//! atoms or ints is held that way only when its variant holds it alone
//! (a cursor): moved at each visit, holding it cost instructions.
//!
//! [`Cx::goto`]: sitlog_runtime::machine::Cx::goto

use super::Gen;

mod boundary;
mod call;
mod call_held;
mod cold;
mod cold_act;
mod cold_next;
mod cond;
mod effect;
mod fill;
mod float_expr;
mod frame;
mod ground_parts;
mod head;
mod next_is;
mod perceive;
mod pipe;
mod plain;
mod plain_rs;
mod sel_flat;
mod select_fn;
mod type_test;
mod visit;
use crate::ir::IrDm;
use crate::mir::ty::{DmTypes, SitTypes};
use crate::mir::{Action, ArcPlan, Build, Cond, Ev, Init, KindPlan, Next, Prog, Reg, SitPlan, ID};
pub(super) use plain_rs::PlainRs;
use proc_macro2::{Delimiter, Ident, Literal, TokenStream, TokenTree};
use quote::{format_ident, quote};
use sitlog_runtime::machine::Kind;
use sitlog_runtime::native::Ty;
use sitlog_runtime::{Term, Value};
use sitlog_syntax::{atoms, Atom};
use std::collections::{BTreeSet, HashMap};
use visit::visit_kind;
pub use visit::Visit;

/// Why a DM is not native (shown in the generated docs and
/// `--explain-types`).
type N<T> = Result<T, String>;

/// Per register of a visit, the Rust local holding its value and its type.
type Regs = HashMap<Reg, (Ident, Ty)>;

/// A native value in generated code: an expression of an owned Rust value
/// and its type.
#[derive(Clone)]
struct V {
    e: TokenStream,
    ty: Ty,
}

/// Whether native code holds a value of this type as a canonical
/// [`Val`](sitlog_runtime::native::Val): `ground` (a boundary's value
/// after the checked conversion, or the join of different shapes) and a
/// fixed-shape compound of native values.
fn held_as_val(ty: &Ty) -> bool {
    match ty {
        Ty::Ground => true,
        Ty::Tagged(..) => ty.is_native(),
        _ => false,
    }
}

/// Whether a value of this type is held with a `Val` somewhere in it (a
/// dynamic shape, counted apart in `--explain-types`).
fn holds_val(ty: &Ty) -> bool {
    match ty {
        Ty::List(e) => holds_val(e),
        t => held_as_val(t),
    }
}

/// Whether values of the two types have the same Rust representation.
fn same_rep(a: &Ty, b: &Ty) -> bool {
    match (a, b) {
        (Ty::List(x), Ty::List(y)) => same_rep(x, y),
        (x, y) => x == y || (held_as_val(x) && held_as_val(y)),
    }
}

/// The Rust type of a native type.
fn rust_ty(ty: &Ty) -> N<TokenStream> {
    Ok(match ty {
        Ty::Int => quote!(i64),
        Ty::Float => quote!(f64),
        Ty::Sym => quote!(Atom),
        Ty::Never => quote!(Never),
        Ty::List(e) => {
            let e = rust_ty(e)?;
            quote!(List<#e>)
        }
        t if held_as_val(t) => quote!(Val),
        // Known ground where native code holds it (see the module doc).
        Ty::Term => quote!(Ground),
        _ => return Err(format!("a value of type {ty} is not native yet")),
    })
}

/// A DM's types with every register, parameter or id argument that holds
/// no value (`never` since `mir::ty` types `_`) as `term`.
fn unread_as_term_dm(t: &DmTypes) -> DmTypes {
    let mut t = t.clone();
    // A parameter or id argument nothing reads holds no value (`never`):
    // native code still receives one there, a term.
    let unread = |x: &mut crate::mir::ty::Typed| {
        if x.ty == Ty::Never {
            x.ty = Ty::Term;
        }
    };
    t.params.iter_mut().for_each(unread);
    for st in t.sits.iter_mut().flatten() {
        st.id_args.iter_mut().for_each(unread);
    }
    t
}

/// The type of a register that holds no value for `mir::ty` (`_`: a
/// parameter, an id argument or a part of one that the situation does not
/// read): native code still loads it from where it starts, so it has the
/// type of that place (a fresh variable's is `term`).
fn unread_reg_ty(t: &DmTypes, st: &SitTypes, init: Option<&Init>) -> Ty {
    match init {
        Some(Init::HeadArg(i)) => t.params.get(*i).map_or(Ty::Term, |p| p.ty.clone()),
        Some(Init::IdArg(i)) => st.id_args.get(*i).map_or(Ty::Term, |a| a.ty.clone()),
        Some(Init::IdPath(path)) => {
            let Some((first, rest)) = path.split_first() else {
                return Ty::Term;
            };
            let mut ty = st.id_args.get(*first).map_or(Ty::Term, |a| a.ty.clone());
            for &k in rest {
                ty = match (&ty, k) {
                    (Ty::List(e), 0) => (**e).clone(),
                    (Ty::List(_), 1) => ty.clone(),
                    (Ty::Tagged(_, args), k) => args.get(k).cloned().unwrap_or(Ty::Term),
                    _ => Ty::Term,
                };
            }
            ty
        }
        Some(Init::Pipe) => st.pipe.ty.clone(),
        // A part of a head pattern nothing reads: never loaded.
        Some(Init::HeadPath(..)) | Some(Init::Fresh) | None => Ty::Term,
    }
}

/// Loads parameter `i` (the frame's field `p{i}`, a reference here) into
/// register `r` of type `ty`: a copy, converted when the parameter's type
/// is another (one rule for a visit and for a native call's caller).
fn load_head_arg(d: &Dm, r: Reg, i: usize, ty: Ty, regs: &mut Regs) -> N<TokenStream> {
    let p = format_ident!("p{}", i);
    let pv = V {
        e: quote!(#p.clone()),
        ty: d
            .params
            .get(i)
            .cloned()
            .ok_or("a head argument out of range")?,
    };
    let rr = reg(r);
    let e = if pv.ty == ty { pv.e } else { coerce(&pv, &ty)? };
    regs.insert(r, (rr.clone(), ty));
    Ok(quote!(let #rr = #e;))
}

/// Whether `code` may leave the visit before its end: a `return`, a `?`,
/// a `break` to a label outside it (any `'visit`, or a cursor's `'step`,
/// which stays in the situation without building a next variant: a tail
/// after `code` would not run, so the arc's count goes before it).
fn leaves(code: &TokenStream) -> bool {
    use proc_macro2::TokenTree;
    code.clone().into_iter().any(|t| match t {
        TokenTree::Ident(i) => i == "return" || i == "visit" || i == "step",
        TokenTree::Punct(p) => p.as_char() == '?',
        TokenTree::Group(g) => leaves(&g.stream()),
        TokenTree::Literal(_) => false,
    })
}

/// The history entry of an arc (`exp`, `act` and `rec_next` in
/// scope), when recorded: made as the term code makes it. The arc entered
/// its situation first (its id set, the locals written back: `Dm::hand`),
/// and what changed the locals since were the machine's own calls, so an
/// observer sees the frame the term path would have.
/// Whether `code` is one block whose last statement is a `return` (code
/// that hands over, never a value).
fn always_returns(code: &TokenStream) -> bool {
    use proc_macro2::{Delimiter, TokenTree};
    let mut it = code.clone().into_iter();
    let (Some(TokenTree::Group(g)), None) = (it.next(), it.next()) else {
        return false;
    };
    if g.delimiter() != Delimiter::Brace {
        return false;
    }
    let tokens: Vec<TokenTree> = g.stream().into_iter().collect();
    // A block of one block: look inside.
    if tokens.len() == 1 {
        return always_returns(&g.stream());
    }
    let Some(TokenTree::Punct(last)) = tokens.last() else {
        return false;
    };
    if last.as_char() != ';' {
        return false;
    }
    // The last statement starts with `return`: the last top-level `return`
    // (a `{ ... }` group is one token, so nested ones do not count) starts a
    // statement (after a `;` or a block) and no `;` follows it but the last.
    let Some(k) = tokens
        .iter()
        .rposition(|t| matches!(t, TokenTree::Ident(i) if i == "return"))
    else {
        return false;
    };
    let starts = k == 0
        || matches!(&tokens[k - 1], TokenTree::Punct(p) if p.as_char() == ';')
        || matches!(&tokens[k - 1], TokenTree::Group(g) if g.delimiter() == Delimiter::Brace);
    starts
        && !tokens[k..tokens.len() - 1]
            .iter()
            .any(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == ';'))
}

/// The value of `t` after the statements `ts` when they are none (`t`) or
/// one, `let t = E;` (`E`).
fn one_value(ts: &[TokenStream], t: &TokenStream) -> Option<TokenStream> {
    match ts {
        [] => Some(t.clone()),
        [s] => {
            let tokens: Vec<proc_macro2::TokenTree> = s.clone().into_iter().collect();
            match tokens.as_slice() {
                [proc_macro2::TokenTree::Ident(l), proc_macro2::TokenTree::Ident(x), proc_macro2::TokenTree::Punct(eq), rest @ .., proc_macro2::TokenTree::Punct(semi)]
                    if l == "let"
                        && *x == t.to_string()
                        && eq.as_char() == '='
                        && semi.as_char() == ';' =>
                {
                    Some(rest.iter().cloned().collect())
                }
                _ => None,
            }
        }
        _ => None,
    }
}

/// The fresh variables a visit uses, made first in one call (in order).
fn fresh_vars(used: &std::collections::BTreeSet<Ident>) -> TokenStream {
    if used.is_empty() {
        return quote!();
    }
    let used = used.iter();
    quote!(let [#(#used),*] = cx.vars();)
}

/// The end of an arc whose next situation is handed to the machine as the
/// term `rec_next`: its history entry (`rec`, empty where not recorded)
/// and the step.
fn goto_tail(rec: &TokenStream) -> TokenStream {
    if rec.is_empty() {
        quote!(return cx.goto(rec_next, arc_at).map(Some);)
    } else {
        quote!(return run.goto(cx, exp, act, rec_next, arc_at);)
    }
}

fn rec_entry() -> TokenStream {
    quote! {
        cx.record_if(run.records, exp, act, Some(rec_next));
    }
}

/// Whether `code` is a block that hands the native frames over
/// (`nat_hand_over`) in its own statements, not only on a path inside
/// them: code that always calls the machine (a Prolog condition), so not
/// a hot path.
fn hands_over_first(code: &TokenStream) -> bool {
    use proc_macro2::{Delimiter, TokenTree};
    let Some(TokenTree::Group(g)) = code
        .clone()
        .into_iter()
        .find(|t| matches!(t, TokenTree::Group(g) if g.delimiter() == Delimiter::Brace))
    else {
        return false;
    };
    g.stream()
        .into_iter()
        .any(|t| matches!(t, TokenTree::Ident(i) if i == "nat_hand_over"))
}

/// `code` with `arc_at` (the arc's index `i`, `Some(i)`) bound where it
/// reads it: nothing where it does not, the value itself where it reads it
/// once, else `let arc_at = Some(i);` first; `arc_ix` (the index itself,
/// `Cx::nat_empty`'s) is `i`.
pub(super) fn with_arc_at(code: &TokenStream, i: usize) -> TokenStream {
    use proc_macro2::{Group, TokenTree};
    fn count(ts: &TokenStream) -> usize {
        ts.clone()
            .into_iter()
            .map(|t| match t {
                TokenTree::Ident(x) => usize::from(x == "arc_at"),
                TokenTree::Group(g) => count(&g.stream()),
                _ => 0,
            })
            .sum()
    }
    fn put_as(ts: &TokenStream, name: &str, v: &TokenStream) -> TokenStream {
        ts.clone()
            .into_iter()
            .flat_map(|t| -> Vec<TokenTree> {
                match t {
                    TokenTree::Ident(x) if x == name => v.clone().into_iter().collect(),
                    TokenTree::Group(g) => {
                        let mut n = Group::new(g.delimiter(), put_as(&g.stream(), name, v));
                        n.set_span(g.span());
                        vec![TokenTree::Group(n)]
                    }
                    t => vec![t],
                }
            })
            .collect()
    }
    let put = |ts: &TokenStream, v: &TokenStream| put_as(ts, "arc_at", v);
    let (il, is) = (Literal::usize_unsuffixed(i), Literal::usize_suffixed(i));
    let code = &put_as(code, "arc_ix", &quote!(#il));
    match count(code) {
        0 => code.clone(),
        // Read once: an argument of `Cx`'s (`Option<usize>`).
        1 => put(code, &quote!(Some(#il))),
        _ => quote!(let arc_at = Some(#is); #code),
    }
}

/// The identifiers of generated code `ts`, at any depth.
fn idents(ts: &TokenStream, out: &mut std::collections::BTreeSet<String>) {
    for t in ts.clone() {
        match t {
            proc_macro2::TokenTree::Ident(i) => {
                out.insert(i.to_string());
            }
            proc_macro2::TokenTree::Group(g) => idents(&g.stream(), out),
            _ => {}
        }
    }
}

/// Whether `code` may move a variable that `reader` reads: one of
/// `reader`'s identifiers appears in `code` other than as `x.clone()`, a
/// field's name or a borrow `&x` (ended with `code`: the value it makes,
/// a `Nat`, holds no reference; any other use counts as a move).
fn moves_any(code: &TokenStream, reader: &TokenStream) -> bool {
    use proc_macro2::TokenTree;
    fn moves(ts: &TokenStream, read: &std::collections::BTreeSet<String>) -> bool {
        let toks: Vec<TokenTree> = ts.clone().into_iter().collect();
        toks.iter().enumerate().any(|(k, t)| match t {
            TokenTree::Ident(i) => {
                let cloned = matches!(toks.get(k + 1), Some(TokenTree::Punct(p)) if p.as_char() == '.')
                    && matches!(toks.get(k + 2), Some(TokenTree::Ident(c)) if c == "clone");
                // A field's name (`r1: ..`), not `r1::`.
                let field = matches!(toks.get(k + 1), Some(TokenTree::Punct(p))
                    if p.as_char() == ':' && p.spacing() == proc_macro2::Spacing::Alone);
                // Borrowed (`&r7`: a selected value, [`Gen::nat_select`]).
                let borrowed = k > 0
                    && matches!(&toks[k - 1], TokenTree::Punct(p) if p.as_char() == '&');
                read.contains(&i.to_string()) && !cloned && !field && !borrowed
            }
            TokenTree::Group(g) => moves(&g.stream(), read),
            _ => false,
        })
    }
    let mut read = std::collections::BTreeSet::new();
    idents(reader, &mut read);
    // Names that are not variables of the visit.
    for k in [
        "cx", "p", "a", "Term", "Nat", "let", "mut", "count", "exp", "act", "atoms",
    ] {
        read.remove(k);
    }
    moves(code, &read)
}

/// A visit's body `body` (its arm binds `names` by value) with the last
/// use of a field, `f: x.clone()` in a variant built at its end, moving
/// `x` instead (`f: x`, `x` where `f` is `x`): no clone of a value the
/// arm drops right after, and the variant often fits on one line. Only
/// where nothing reads `x` after it in the code's order, no loop can run
/// it again, and no `let` or `match` may hold a borrow of `x` (`x` in
/// its initializer, but for a call of `cx`: `let id = cx.fill(.., &[&x])`).
fn move_last_clones(body: &TokenStream, names: &[Ident]) -> TokenStream {
    use proc_macro2::{Group, TokenTree};
    use std::collections::{HashMap, HashSet};
    fn walk(
        ts: &TokenStream,
        at: &mut usize,
        last: &mut HashMap<String, usize>,
        held: &mut HashSet<String>,
        looped: &mut bool,
    ) {
        let toks: Vec<TokenTree> = ts.clone().into_iter().collect();
        for (k, t) in toks.iter().enumerate() {
            *at += 1;
            match t {
                TokenTree::Ident(i) => {
                    let s = i.to_string();
                    if s == "loop" || s == "while" || s == "for" {
                        *looped = true;
                    }
                    if s == "let" || s == "match" {
                        // `let P = E;` (`if let`, `let .. else`), `match E`:
                        // every identifier of `E` may be borrowed as long as
                        // `P` lives, but where `E` is a call of `cx` (its
                        // result a term, borrowing nothing).
                        let start = if s == "match" {
                            Some(k + 1)
                        } else {
                            toks[k..]
                                .iter()
                                .position(|t| {
                                    matches!(t, TokenTree::Punct(p) if p.as_char() == '='
                                        && p.spacing() == proc_macro2::Spacing::Alone)
                                })
                                .map(|e| k + e + 1)
                        };
                        let of_cx = start.is_some_and(|e| {
                            matches!(toks.get(e), Some(TokenTree::Ident(c)) if c == "cx")
                                && matches!(toks.get(e + 1), Some(TokenTree::Punct(p)) if p.as_char() == '.')
                        });
                        if let (Some(e), false) = (start, of_cx) {
                            let init = toks[e..].iter().take_while(
                                |t| !matches!(t, TokenTree::Punct(p) if p.as_char() == ';'),
                            );
                            // A block's own `let`s are looked at inside it.
                            let init = init.filter(|t| {
                                !matches!(t, TokenTree::Group(g) if g.delimiter() == proc_macro2::Delimiter::Brace)
                            });
                            for t in init {
                                let mut ids = std::collections::BTreeSet::new();
                                idents(&TokenStream::from(t.clone()), &mut ids);
                                held.extend(ids);
                            }
                        }
                    }
                    // A field's name (`f: ..`) is no mention of `f`.
                    let field = matches!(toks.get(k + 1), Some(TokenTree::Punct(p))
                        if p.as_char() == ':' && p.spacing() == proc_macro2::Spacing::Alone);
                    if !field {
                        last.insert(s, *at);
                    }
                }
                TokenTree::Group(g) => walk(&g.stream(), at, last, held, looped),
                _ => {}
            }
        }
    }
    fn rewrite(
        ts: &TokenStream,
        at: &mut usize,
        last: &HashMap<String, usize>,
        movable: &HashSet<String>,
    ) -> TokenStream {
        let toks: Vec<TokenTree> = ts.clone().into_iter().collect();
        let mut out: Vec<TokenTree> = Vec::new();
        let mut k = 0;
        while k < toks.len() {
            *at += 1;
            let t = &toks[k];
            if let TokenTree::Ident(x) = t {
                let s = x.to_string();
                // `f : x . clone ( )`, `x`'s last mention.
                let field = k >= 2
                    && matches!(&toks[k - 1], TokenTree::Punct(p) if p.as_char() == ':' && p.spacing() == proc_macro2::Spacing::Alone)
                    && matches!(&toks[k - 2], TokenTree::Ident(_));
                let clone = matches!(toks.get(k + 1), Some(TokenTree::Punct(p)) if p.as_char() == '.')
                    && matches!(toks.get(k + 2), Some(TokenTree::Ident(c)) if c == "clone")
                    && matches!(toks.get(k + 3), Some(TokenTree::Group(g)) if g.stream().is_empty());
                let ends = matches!(toks.get(k + 4), None | Some(TokenTree::Punct(_)))
                    && !matches!(toks.get(k + 4), Some(TokenTree::Punct(p)) if p.as_char() == '.');
                if field && clone && ends && movable.contains(&s) && last.get(&s) == Some(&*at) {
                    let same = matches!(&toks[k - 2], TokenTree::Ident(f) if *f == s);
                    if same {
                        out.truncate(out.len() - 2);
                    }
                    out.push(t.clone());
                    // `.`, `clone`, `()`: counted, dropped.
                    *at += 3;
                    k += 4;
                    continue;
                }
                out.push(t.clone());
            } else if let TokenTree::Group(g) = t {
                let mut ng = Group::new(g.delimiter(), rewrite(&g.stream(), at, last, movable));
                ng.set_span(g.span());
                out.push(TokenTree::Group(ng));
            } else {
                out.push(t.clone());
            }
            k += 1;
        }
        out.into_iter().collect()
    }
    let (mut at, mut last, mut held, mut looped) = (0, HashMap::new(), HashSet::new(), false);
    walk(body, &mut at, &mut last, &mut held, &mut looped);
    if looped {
        return body.clone();
    }
    let movable: HashSet<String> = names
        .iter()
        .map(|n| n.to_string())
        .filter(|n| !held.contains(n))
        .collect();
    let mut at = 0;
    rewrite(body, &mut at, &last, &movable)
}

/// An id `Term::atom(x)` given as the atom `x` to a call that takes
/// `impl Into<Term>` (`Cx::enter_empty`, `Cx::no_exit`): the call fits on
/// one line more often. Any other id as it is.
fn atom_arg(id: &TokenStream) -> TokenStream {
    match syn::parse2::<syn::ExprCall>(id.clone()) {
        Ok(c)
            if c.args.len() == 1 && {
                let f = &c.func;
                quote!(#f).to_string() == "Term :: atom"
            } =>
        {
            let x = &c.args[0];
            quote!(#x)
        }
        _ => id.clone(),
    }
}

/// Whether `hand` ([`Dm::hand`]) is the runtime's hand-over (a DM
/// without locals), which `Cx::nat_empty` makes itself.
fn runtime_hand(hand: &TokenStream) -> bool {
    hand.to_string() == quote!(super::nat_hand_over(p, cx, stack)?;).to_string()
}

/// The entry of situation `cur` by arc `arc` (tokens: a literal, or
/// `arc_ix`, [`with_arc_at`]'s index) whose action is `empty`, as one
/// `Cx::nat_empty` call (`empty` performed, the hand-over only where the
/// effector fails, the id filled, the entry, out of line), from the id's statements and value ([`Gen::nat_id_term`]): an
/// atom, or one `let idN = cx.fill(pattern, holes);`. `None` for another
/// id, or where the call would not fit on a line (60 columns, prettyplease's
/// least room: broken an argument a line it is longer than the statements
/// it replaces), for the caller's statements instead. `entered`: the
/// `Cx::nat_enter` call instead (`empty` performed before, a DM with
/// locals: `Cx::empty_fails`), of the same length.
fn empty_call(
    id_stmts: &[TokenStream],
    id: &TokenStream,
    cur: &Literal,
    arc: &TokenStream,
    entered: bool,
) -> Option<TokenStream> {
    let f = if entered {
        format_ident!("nat_enter")
    } else {
        format_ident!("nat_empty")
    };
    empty_call_with(
        id_stmts,
        id,
        arc,
        |pattern, holes| quote!(cx.#f(stack, &mut count, #cur, #arc, #pattern, #holes)?;),
    )
}

/// [`empty_call`] of `Cx::nat_empty` with its test: `TypedRun::empty`
/// (`gate` `empty`: where the run records or the actions do not ignore
/// `empty`, a neutral or perceptual arc's) or `TypedRun::exit_empty` (only
/// the latter: an exit arc's, whose entry is made after it), one call in
/// place of an `if` around the call.
fn gated_empty_call(
    id_stmts: &[TokenStream],
    id: &TokenStream,
    cur: &Literal,
    arc: &TokenStream,
    gate: &str,
) -> Option<TokenStream> {
    let f = format_ident!("{}", gate);
    empty_call_with(
        id_stmts,
        id,
        arc,
        |pattern, holes| quote!(run.#f(cx, stack, &mut count, #cur, #arc, #pattern, #holes)?;),
    )
}

/// The statements of [`empty_call`], the call made by `call` of the id's
/// pattern and holes.
fn empty_call_with(
    id_stmts: &[TokenStream],
    id: &TokenStream,
    arc: &TokenStream,
    call: impl Fn(&TokenStream, &TokenStream) -> TokenStream,
) -> Option<TokenStream> {
    // The holes a tuple (`fill::holes_tuple`): nothing built before the
    // call's test.
    let (pattern, holes) = match id_stmts {
        [] => {
            let x = atom_arg(id);
            if x.to_string() == id.to_string() {
                return None;
            }
            (x, quote!(()))
        }
        _ => {
            let (pattern, holes) = fill_parts(id_stmts, id)?;
            (pattern, fill::holes_tuple(&holes))
        }
    };
    // Measured with `arc_ix` a digit, as `with_arc_at` puts it in.
    let measure = |stmt: TokenStream| {
        if arc.to_string() == "arc_ix" {
            let s = stmt.to_string().replace("arc_ix", "0");
            s.parse::<TokenStream>().unwrap_or(stmt)
        } else {
            stmt
        }
    };
    let one = call(&pattern, &holes);
    if fits_at(&measure(one.clone()), None) {
        return Some(one);
    }
    // Else the id's pattern and holes as a `Fill` first (they borrow only
    // registers), which the call fills after the hand-over: two lines
    // where both fit.
    if id_stmts.is_empty() {
        return None;
    }
    let fill = quote!(let #id = Fill(#pattern, #holes););
    let two = call(id, &quote!(()));
    (fits_at(&fill, None) && fits_at(&measure(two.clone()), None)).then(|| {
        quote! {
            #fill
            #two
        }
    })
}

/// A statement `let x = cx.method(args..);` taken apart: `x`, the method's
/// name and its arguments. `None` for any other statement.
pub(super) fn cx_let(stmt: &TokenStream) -> Option<(String, String, Vec<TokenStream>)> {
    let syn::Stmt::Local(l) = syn::parse2::<syn::Stmt>(stmt.clone()).ok()? else {
        return None;
    };
    let syn::Pat::Ident(x) = &l.pat else {
        return None;
    };
    let syn::Expr::MethodCall(m) = &*l.init.as_ref()?.expr else {
        return None;
    };
    let recv = &m.receiver;
    if quote!(#recv).to_string() != "cx" {
        return None;
    }
    let args = m.args.iter().map(|a| quote!(#a)).collect();
    Some((x.ident.to_string(), m.method.to_string(), args))
}

/// The pattern and holes of an id made by one statement
/// `let id = cx.fill(pattern, holes);` (`stmts`, `id`).
fn fill_parts(stmts: &[TokenStream], id: &TokenStream) -> Option<(TokenStream, TokenStream)> {
    let [stmt] = stmts else { return None };
    let (x, method, args) = cx_let(stmt)?;
    let [pattern, holes] = args.as_slice() else {
        return None;
    };
    (x == id.to_string() && method == "fill").then(|| (pattern.clone(), holes.clone()))
}

/// `Fill(pattern, holes)` for an id made by one statement
/// `let id = cx.fill(pattern, holes);` ([`fill_parts`]): a call that takes
/// [`IdArg`](sitlog_runtime::machine::IdArg) fills it first.
fn fill_arg(stmts: &[TokenStream], id: &TokenStream) -> Option<TokenStream> {
    let (pattern, holes) = fill_parts(stmts, id)?;
    let holes = fill::holes_tuple(&holes);
    Some(quote!(Fill(#pattern, #holes)))
}

/// Whether statement `code` fits on one line at `indent` as prettyplease
/// writes it ([`fits_at`]).
fn fits(code: &TokenStream, indent: usize) -> bool {
    fits_at(code, Some(indent))
}

/// Whether statement `code` fits on one line as prettyplease writes it:
/// its length ([`printed_len`]) within the room prettyplease leaves at
/// `indent` (margin 89, never less than 60 columns), or within 60 at any
/// depth (`None`). The one estimate the generator makes of whether a call
/// is written on one line.
pub(super) fn fits_at(code: &TokenStream, indent: Option<usize>) -> bool {
    let room = indent.map_or(60, |i| 89usize.saturating_sub(i).max(60));
    printed_len(code) <= room
}

/// The length of `code` printed on one line, estimated from its tokens as
/// prettyplease spaces them: a space between two words (`&mut count`,
/// `return cx`), after a comma (none for a trailing one), after a `:` of a
/// type, around `=`, inside braces; none else.
fn printed_len(code: &TokenStream) -> usize {
    use proc_macro2::{Delimiter, Spacing, TokenTree};
    fn walk(ts: &TokenStream) -> usize {
        let toks: Vec<TokenTree> = ts.clone().into_iter().collect();
        let mut len = 0;
        let mut word = false;
        let mut joint = false;
        for (k, t) in toks.iter().enumerate() {
            let last = k + 1 == toks.len();
            match t {
                TokenTree::Ident(_) | TokenTree::Literal(_) => {
                    len += t.to_string().len() + usize::from(word);
                    word = true;
                    joint = false;
                }
                TokenTree::Punct(p) => {
                    len += match p.as_char() {
                        ',' if last => 0,
                        ',' => 2,
                        ':' | '=' if p.spacing() == Spacing::Alone && !joint => {
                            if p.as_char() == '=' {
                                3
                            } else {
                                2
                            }
                        }
                        _ => 1,
                    };
                    word = false;
                    joint = p.spacing() == Spacing::Joint;
                }
                TokenTree::Group(g) => {
                    let inner = walk(&g.stream());
                    len += match g.delimiter() {
                        Delimiter::Brace if inner > 0 => inner + 4,
                        Delimiter::None => inner,
                        _ => inner + 2,
                    };
                    word = false;
                    joint = false;
                }
            }
        }
        len
    }
    walk(code)
}

/// `code` as one expression: itself where it is one (a variant, a
/// `'sel` block, a block), else in a block.
fn as_expr(code: TokenStream) -> TokenStream {
    if syn::parse2::<syn::Expr>(code.clone()).is_ok() {
        code
    } else {
        quote!({ #code })
    }
}

/// Whether Rust's `==` on values of this type is Prolog's `==`.
fn eq_safe(ty: &Ty) -> bool {
    match ty {
        Ty::Int | Ty::Sym | Ty::Never => true,
        Ty::List(e) => eq_safe(e),
        // Canonical `Val`s: `==` is Prolog's (`sitlog_runtime::native`).
        t => held_as_val(t),
    }
}

/// Whether a local holds a fresh variable (a term) made for an arc.
/// Whether register `r` is read by `next` only in the conditions' terms
/// given whole to the machine (`Cond::Other`), not in a situation it goes to.
fn only_in_conditions(next: &Next, r: Reg) -> bool {
    fn targets(n: &Next, r: Reg) -> bool {
        match n {
            Next::Static(..) => false,
            Next::Eval(e) => crate::mir::ty::ev_mentions(e, r, 0),
            Next::If(c, a, b) => cond_mentions(c, r) || targets(a, r) || targets(b, r),
        }
    }
    fn cond_mentions(c: &Cond, r: Reg) -> bool {
        match c {
            Cond::Arith(_, a, b) => {
                crate::mir::ty::ev_mentions(a, r, 0) || crate::mir::ty::ev_mentions(b, r, 0)
            }
            Cond::Other(_) => false,
            Cond::Cmp(_, a, b) => {
                crate::mir::ty::build_mentions(a, r, 0) || crate::mir::ty::build_mentions(b, r, 0)
            }
            Cond::And(a, b) | Cond::Or(a, b) => cond_mentions(a, r) || cond_mentions(b, r),
        }
    }
    !targets(next, r)
}

/// Whether the arc's out_arg reads register `r`.
fn out_mentions(arc: &ArcPlan, r: Reg) -> bool {
    arc.out_arg
        .as_ref()
        .is_some_and(|o| crate::mir::ty::ev_mentions(o, r, 0))
}

/// Whether register `r` occurs once in situation `cur`'s plan (where it
/// is bound: nothing else reads it).
fn occurs_once(d: &Dm, cur: usize, r: Reg) -> bool {
    d.occ[cur].get(r as usize).is_some_and(|&n| n == 1)
}

/// Whether binding register `r` here has no other effect: not held, or a
/// fresh variable ([`is_fresh`]) that occurs nowhere else in the plan.
fn free_here(d: &Dm, cur: usize, r: Reg, regs: &Regs) -> bool {
    match regs.get(&r) {
        None => true,
        Some((x, _)) => is_fresh(x) && occurs_once(d, cur, r),
    }
}

fn is_fresh(x: &Ident) -> bool {
    // `fresh_r<n>` only: an atom's field (`a.fresh_water`) is not one.
    x.to_string()
        .strip_prefix("fresh_r")
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
}

/// An evaluated term as written (`None` where a part is not a term of
/// registers and constants: a condition, `get`/`inc`, `is`): what the
/// machine evaluates whole where the MIR evaluates it part by part.
fn as_written(e: &Ev) -> Option<Build> {
    Some(match e {
        Ev::Value(r) => Build::Reg(*r),
        Ev::Built(b) | Ev::Eval(b) => b.clone(),
        Ev::Compound(f, args) => Build::Compound(
            *f,
            args.iter().map(as_written).collect::<Option<Box<[_]>>>()?,
        ),
        _ => return None,
    })
}

/// The registers of an expression that evaluates to itself built from
/// them (`Value`, `Built`, compounds of those), pushed to `out`; `false`
/// when evaluating it does more.
fn built_regs(e: &Ev, out: &mut Vec<Reg>) -> bool {
    fn build(b: &Build, out: &mut Vec<Reg>) {
        match b {
            Build::Reg(r) => out.push(*r),
            Build::Const(_) => {}
            Build::Compound(_, args) => args.iter().for_each(|a| build(a, out)),
        }
    }
    match e {
        Ev::Value(r) => {
            out.push(*r);
            true
        }
        Ev::Built(b) => {
            build(b, out);
            true
        }
        Ev::Compound(_, args) => args.iter().all(|a| built_regs(a, out)),
        _ => false,
    }
}

/// Whether evaluating `e` does a `get` or an `inc` `op(v, ..)` for which
/// `which(op, v)` holds (at any depth of its compounds and conditionals).
fn has_var_op(e: &Ev, which: &dyn Fn(Atom, Atom) -> bool) -> bool {
    let cond = |c: &Cond| match c {
        Cond::Arith(_, a, b) => has_var_op(a, which) || has_var_op(b, which),
        // `when/3`'s comparison of built values: no `get`/`inc` in it.
        Cond::Cmp(..) | Cond::Other(_) | Cond::And(..) | Cond::Or(..) => false,
    };
    match e {
        Ev::VarOp { op, name, .. } | Ev::VarOpFresh { op, name, .. } => {
            (*op == atoms::GET || *op == atoms::INC) && which(*op, *name)
        }
        Ev::Compound(_, args) => args.iter().any(|a| has_var_op(a, which)),
        Ev::If(c, a, b) | Ev::Pick(c, a, b) => {
            cond(c) || has_var_op(a, which) || has_var_op(b, which)
        }
        _ => false,
    }
}

/// The registers an expression binds (`V is E`, `get(n, V)` of a `V` not
/// made yet), in evaluation order.
fn ev_binds(e: &Ev, out: &mut Vec<Reg>) {
    match e {
        Ev::VarOpFresh { dst, .. } | Ev::IsFresh { dst, .. } | Ev::BindFresh { dst, .. } => {
            out.push(*dst)
        }
        Ev::Compound(_, args) => args.iter().for_each(|a| ev_binds(a, out)),
        Ev::If(_, a, b) | Ev::Pick(_, a, b) => {
            ev_binds(a, out);
            ev_binds(b, out);
        }
        _ => {}
    }
}

/// The registers a next situation's expressions bind ([`ev_binds`]).
fn next_binds(n: &Next, out: &mut Vec<Reg>) {
    match n {
        Next::Eval(e) => ev_binds(e, out),
        Next::If(_, a, b) => {
            next_binds(a, out);
            next_binds(b, out);
        }
        Next::Static(..) => {}
    }
}

/// The fresh-variable locals (`fresh_rN`) `ts` uses before its own code
/// declares them (`let fresh_rN = cx.var_op_fresh(..);` in a branch that
/// runs only when recorded makes no variable on the other branch).
fn fresh_used(ts: &TokenStream, out: &mut std::collections::BTreeSet<Ident>) {
    fresh_used_in(ts, &mut Vec::new(), out);
}

fn fresh_used_in(
    ts: &TokenStream,
    declared: &mut Vec<Ident>,
    out: &mut std::collections::BTreeSet<Ident>,
) {
    let outer = declared.len();
    let mut pending = Vec::new();
    let mut after_let = false;
    for tt in ts.clone() {
        let is_let = matches!(&tt, proc_macro2::TokenTree::Ident(i) if i == "let");
        match tt {
            proc_macro2::TokenTree::Group(g) => fresh_used_in(&g.stream(), declared, out),
            proc_macro2::TokenTree::Ident(i) if after_let && is_fresh(&i) => pending.push(i),
            proc_macro2::TokenTree::Ident(i) if is_fresh(&i) && !declared.contains(&i) => {
                out.insert(i);
            }
            proc_macro2::TokenTree::Punct(p) if p.as_char() == ';' => {
                declared.append(&mut pending);
            }
            _ => {}
        }
        after_let = is_let;
    }
    declared.truncate(outer);
}

fn reg(r: Reg) -> Ident {
    format_ident!("r{}", r)
}

fn variant(ix: usize) -> Ident {
    format_ident!("S{}", ix)
}

/// One step of matching a value against an id pattern.
#[derive(Clone)]
enum MatchStep {
    /// A test.
    If(TokenStream),
    /// `[]` of a `List<T>`: `if v.is_empty()`.
    Empty(TokenStream),
    /// `let NAME = EXPR;`
    Let(Ident, TokenStream),
    /// `if let Some((h, t)) = v.split_first()`, the head cloned.
    Split(TokenStream, Ident, Ident),
    /// The arguments of a ground term `v` that is `name/arity`, each a
    /// ground term: `if let Some(&[x0, ..]) = store.compound_args(..)`.
    Args(TokenStream, TokenStream, Literal, Vec<Ident>),
    /// `[H|T]` of a `Val`: `if let Some((h, t)) = v.split_list()`.
    SplitVal(TokenStream, Ident, Ident),
    /// `[H|T]` of a `Val` whose `T` is a field typed `list<ground>`
    /// (`mir::ty`'s narrowing of a `ground` value by a list pattern):
    /// `if let Some((h, t)) = v.split_proper()`, the head a `Val`, the
    /// tail a `List<Val>`; an improper list (`[a|b]`: this candidate would take
    /// it on terms) is handed to the machine, never tried on a later
    /// candidate.
    SplitValList(TokenStream, Ident, Ident),
    /// The arguments of a `Val` that is `name/arity`, each a `Val`.
    ArgsVal(TokenStream, TokenStream, Literal, Vec<Ident>),
    /// `[P|Ps]` of a [`CellField`]: the list itself (`let x = take;`)
    /// when it is not empty, not split. `true`: a `Val` (a proper list,
    /// cloned; an improper one handed to the machine, as
    /// `SplitValList`).
    Cell(TokenStream, Ident, TokenStream, bool),
    /// `let Some(NAME) = EXPR else { the machine selects }`: a value held
    /// wider than the field it binds (`ground` into an `atom` field),
    /// narrowed with a check ([`narrow`]). The pattern variable takes any
    /// value, so when the check fails this candidate would still be the
    /// machine's choice: the value is handed to the machine, never tried
    /// on a later candidate.
    Narrow(Ident, TokenStream),
}

impl MatchStep {
    /// Whether the step's code mentions `x`.
    fn mentions(&self, x: &Ident) -> bool {
        match self {
            MatchStep::If(c) | MatchStep::Empty(c) => call::mentions(c, x),
            MatchStep::Let(_, e) | MatchStep::Narrow(_, e) => call::mentions(e, x),
            MatchStep::Split(v, ..)
            | MatchStep::SplitVal(v, ..)
            | MatchStep::SplitValList(v, ..)
            | MatchStep::Args(v, ..)
            | MatchStep::ArgsVal(v, ..)
            | MatchStep::Cell(v, ..) => call::mentions(v, x),
        }
    }
}

/// The DM's native code, for the module.
pub(super) struct NativeCode {
    /// `enum Nat`, `nat_step`, `nat_entry`, ...
    pub items: TokenStream,
    /// `run_native`, which a DM's `run_situation` calls for each situation
    /// with native code (an all-native DM has none: the program enters
    /// its frame).
    pub run_native: TokenStream,
    /// How many situations hold no ground handle (no register `term`) and
    /// whose code neither hands the frames over nor runs the template on
    /// any of its own paths ([`Visit::Native`]): the ones on native values.
    pub on_native_values: usize,
    /// How many of those hold no `Val` either (only fixed shapes: no
    /// register `ground` or a compound type).
    pub fixed_shapes: usize,
    /// How many situations have native code.
    pub native_sits: usize,
    /// Per situation with native code, what its visit does ([`Visit`]);
    /// `None`: it has none.
    pub visits: Vec<Option<Visit>>,
    /// Per situation, why it has no native code (`None`: it has).
    pub why: Vec<Option<String>>,
    /// Whether a call of the DM may push its frame on the native stack:
    /// its initial situation has native code and its locals are in the
    /// frame.
    pub callee_ok: bool,
    /// Which of the DM's variables native code holds as Rust values
    /// (`--explain-types`' `variables typed`).
    pub held: Held,
}

/// Which of a DM's variables its generated code holds as native Rust
/// values (`i64`, `f64`, `Atom`, `List`, `Val`: not a `Ground` handle, not
/// a term of the machine) in every situation of the DM: only when every
/// situation has native code; a parameter when native code reads it
/// (converted at entry; an unread one is a handle), a local when the
/// frame holds the locals, the pipe when every in_arg reading it is a
/// register of such a type. Globals stay the machine's terms.
#[derive(Clone, Debug, Default)]
pub struct Held {
    /// Per parameter.
    pub params: Vec<bool>,
    /// Per local, in the DM's order.
    pub locals: Vec<bool>,
    /// The pipe, as read by the DM's in_args.
    pub pipe: bool,
}

/// A situation's native code: its variant's fields, the visit, its id as
/// a term.
type SitCode = (Vec<(Reg, Ty)>, TokenStream, TokenStream, Option<call::Wait>);

struct Dm<'a> {
    dm: &'a IrDm,
    plans: Vec<&'a SitPlan>,
    types: Vec<SitTypes>,
    /// The parameters' types.
    params: Vec<Ty>,
    /// Per situation, whether it has native code (else a next situation
    /// that selects it is handed to the machine).
    native: Vec<bool>,
    /// The DM's locals' names and types (frame fields `l0..`).
    locals: Vec<(Atom, Ty)>,
    /// Whether the locals are held in the frame (each has a native type);
    /// else the DM is never a native callee.
    locals_ok: bool,
    /// Code run before native code hands over to the machine: the native
    /// stack below materialized, the locals written back (`frame`).
    hand: TokenStream,
    /// Calls made as if no callee were native (deciding native-ness).
    shallow: bool,
    /// The arc's out_arg, set where its next situation is handed over.
    out: std::cell::RefCell<TokenStream>,
    /// The situations whose id is built by the DM's `id_s<N>` function
    /// (one per situation, from its fields, where its pattern does not
    /// read back; [`Gen::nat_id_term`]).
    ids: std::cell::RefCell<std::collections::BTreeSet<usize>>,
    /// Names of the ids built (`id0`, `id1`, ...).
    id_n: std::cell::Cell<usize>,
    /// Per parameter, its type when the DM returns if it is an output
    /// (`DmTypes::outputs`) of a native type, else `None`.
    outputs: Vec<Option<Ty>>,
    /// Per parameter: an output that every final with native code binds
    /// from a Rust local of its output type (`Gen::nat_output_slots`).
    outs: std::cell::RefCell<Vec<bool>>,
    /// The arc's history entry where its next situation (`rec_next`, a
    /// term) is handed over: made when the history is kept or observed
    /// (`run.records`), as the term code makes it; empty in exit arcs
    /// (native only when no history is kept, see `call`).
    rec: std::cell::RefCell<TokenStream>,
    /// While a visit's own arcs are generated: the register its in_arg
    /// read the pipe into (the term read is `pipe_in`), so that an
    /// out_arg handing that register back sets the pipe to the term read
    /// instead of converting the value again ([`Gen::nat_next_out`]).
    pipe_in: std::cell::Cell<Option<Reg>>,
    /// While a visit is generated again because nothing of it reads the
    /// in_arg's register (the pipe only handed back as read, or not at
    /// all): the pipe's conversion is only checked, no value kept
    /// ([`Gen::nat_pipe_in`]).
    pipe_unread: std::cell::Cell<bool>,
    /// While a next situation is selected ([`Gen::nat_select`]): a
    /// selected value (`(* v0)`, as text) that is the visit's own cell
    /// tail (`Ps` of `[P|Ps]`, see [`CellField`]), moved (not cloned)
    /// into a candidate that holds it as its cell, and the register; with
    /// the visit's situation when it advances its list in place (a
    /// cursor, [`Gen::nat_cursor`]): then the tail is a reference to the
    /// held list, taken by reference by the visit's own situation and
    /// cloned into any other.
    movable: std::cell::RefCell<Option<(String, Ident, Option<usize>)>>,
    /// Per situation: how often each register occurs in its plan
    /// (`mir::ty::occurrences`), computed once for every question asked.
    occ: Vec<Vec<u32>>,
    /// The candidates of each `'sel` block generated, shared where they
    /// repeat ([`select_fn::share_selections`]).
    sels: std::cell::RefCell<Vec<select_fn::SelSite>>,
}

/// A situation whose id takes apart a list `[P|Ps]` (`P` and `Ps`
/// variables, each once in the id, `P` of the list's element type, one
/// held as a `Val`: `ground` or a compound) and
/// that is neither final nor recursive holds the list itself in its
/// variant, one field `k<Ps>` (never empty), not `P` and `Ps`: a visit
/// reads `P` in place (`&T`, [`List::head_tail`]) where it only compares,
/// selects on or clones it, and makes `Ps` (one `Rc` count, no element
/// copied); a next situation `try(Ps)` selecting it moves `Ps` in whole
/// (`Ps` tested non-empty, not split). Entered by the machine, the
/// field is `List::cons(P, Ps)` of the two converted parts.
///
/// [`List::head_tail`]: sitlog_runtime::native::List::head_tail
#[derive(Clone)]
struct CellField {
    head: Reg,
    tail: Reg,
    /// Where the list pattern is in the id.
    path: Vec<usize>,
    /// The list's type (the tail's).
    ty: Ty,
}

impl CellField {
    /// The variant's field.
    fn name(&self) -> Ident {
        format_ident!("k{}", self.tail)
    }
}

impl Dm<'_> {
    /// The frame's field holding local `name` (`l<i>`) and its type, where
    /// the frame holds it (`None`: a global, or a local not held natively).
    fn local_field(&self, name: Atom) -> Option<(Ident, Ty)> {
        let li = self.locals.iter().position(|(l, _)| *l == name)?;
        Some((format_ident!("l{}", li), self.locals[li].1.clone()))
    }
    /// Whether `name` is a local the DM declares (held in the frame or
    /// not): the machine's `var_op` looks at the running DM's locals
    /// first, a name that is none is a global (D-38).
    fn declares_local(&self, name: Atom) -> bool {
        self.dm.locals.iter().any(|(l, _)| *l == name)
    }
    /// The parameters the situations with native code read (and those of
    /// a native type a native first situation's id is linked with: its
    /// fields are their values, `first(N)` in `bump(N)`; the inference's
    /// filter, `mir::ty`). A first situation linked with a `term`
    /// parameter (`q(A)` in `ask(A)` called as `ask(_)`) is not native
    /// ([`Gen::nat_dm_fix`]), so none is read for it; the filter keeps a
    /// `term` parameter out of the checked conversion all the same.
    fn read_params(&self) -> std::collections::BTreeSet<usize> {
        let start = match (self.plans.first(), self.native.first()) {
            (Some(p0), Some(true)) => crate::mir::ty::start_links(p0)
                .into_iter()
                .filter(|&(_, j)| self.params.get(j).is_some_and(Ty::is_native))
                .collect(),
            _ => Vec::new(),
        };
        (0..self.plans.len())
            .filter(|&ix| self.native[ix])
            .flat_map(|ix| {
                let st = &self.types[ix];
                self.plans[ix]
                    .inits
                    .iter()
                    .filter_map(move |(r, i)| match i {
                        Init::HeadArg(p)
                            if !st.unbound.get(*r as usize).copied().unwrap_or(false) =>
                        {
                            Some(*p)
                        }
                        // A pattern's parameter: its parts read natively.
                        Init::HeadPath(p, _) => Some(*p),
                        _ => None,
                    })
            })
            .chain(start.into_iter().map(|(_, j)| j))
            .collect()
    }
}

impl Gen<'_> {
    /// The native code of DM `dm_ix`, or why it has none.
    pub(super) fn native_code(&self, dm: &IrDm, dm_ix: usize, t: &DmTypes) -> N<NativeCode> {
        self.native_code_with(dm, dm_ix, t, false)
    }

    /// [`Gen::native_code`]; `shallow`: every DM call handed to the machine
    /// (whether a DM is native does not depend on its callees).
    fn native_code_with(
        &self,
        dm: &IrDm,
        dm_ix: usize,
        t: &DmTypes,
        shallow: bool,
    ) -> N<NativeCode> {
        // `ground` is held as a `Val`, converted where it enters (a
        // parameter at entry); `term` as a ground handle.
        let t = &unread_as_term_dm(t);
        let (d, why, code) = self.nat_dm_fix(dm, dm_ix, t, shallow)?;
        let visits: Vec<Option<Visit>> = code
            .iter()
            .map(|c| {
                c.as_ref()
                    .map(|(_, body, _, wait)| visit_kind(body, wait.as_ref().map(|w| &w.exit_arm)))
            })
            .collect();
        // With no situation native, `items` is never emitted (the caller
        // looks at `native_sits`); `why` says why for each.
        // Parameters, converted at entry (those native situations read),
        // the others held as the machine's terms (see `nat_dm_fix`): the
        // frame's fields, made in order where it is made.
        let mut loads = Vec::new();
        let read = d.read_params();
        for (i, p) in d.params.iter().enumerate() {
            let name = format_ident!("p{}", i);
            let ix = Literal::usize_unsuffixed(i);
            if !read.contains(&i) {
                loads.push(quote!(#name: cx.param(#ix).map(Ground)?));
                continue;
            }
            let ty = rust_ty(p)?;
            loads.push(quote!(#name: cx.param_as::<#ty>(#ix)?));
        }
        // Locals, read from the machine's frame at entry.
        for (i, (name, ty)) in d.locals.iter().enumerate() {
            let ty = rust_ty(ty)?;
            let l = format_ident!("l{}", i);
            let a = self.atom_native(*name)?;
            loads.push(quote!(#l: cx.local_as::<#ty>(#a)?));
        }
        let mut variants = Vec::new();
        let mut arms = Vec::new();
        let mut id_arms = Vec::new();
        let mut entries = Vec::new();
        let mut exit_arms = Vec::new();
        let mut wait_arms = Vec::new();
        let mut waits_arms = Vec::new();
        let mut wait_pattern = false;
        let mut held_arms = Vec::new();
        let mut any_cursor = false;
        // The variant a frame holds while it runs (`nat_step` takes its own
        // out of the frame): the first without fields, else `Moved`.
        let mut placeholder: Option<Ident> = None;
        for (ix, c) in code.iter().enumerate() {
            let Some((fields, body, id, wait)) = c else {
                continue;
            };
            let v = variant(ix);
            // The variant's fields: the id's variables, `P` and `Ps` of a
            // cell one field (the list).
            let cell = self.nat_cell(&d, ix);
            let vfields: Vec<(Ident, Ty)> = fields
                .iter()
                .filter_map(|(r, ty)| match &cell {
                    Some(c) if *r == c.head => None,
                    Some(c) if *r == c.tail => Some((c.name(), c.ty.clone())),
                    _ => Some((reg(*r), ty.clone())),
                })
                .collect();
            let decls = vfields
                .iter()
                .map(|(r, ty)| {
                    let ty = rust_ty(ty)?;
                    Ok(quote!(#r: #ty))
                })
                .collect::<N<Vec<_>>>()?;
            let names: Vec<Ident> = vfields.iter().map(|(r, _)| r.clone()).collect();
            // A cell's `P` (a reference into the list) and `Ps`, for the
            // id's arm and the visit.
            // A cursor's visit (its own candidate took its tail in place,
            // [`Gen::nat_cursor`]): `P` cloned out, the list advanced, `Ps`
            // the list itself (by reference where the visit only reads it).
            let cursor = cell.is_some() && body.to_string().contains("break 'step");
            let (id_pre, body) = match &cell {
                Some(c) if cursor => {
                    let (h, t, k) = (reg(c.head), reg(c.tail), c.name());
                    let head = if pipe::mentions(body, &h) > 0 {
                        quote!(let #h = #k.head().clone();)
                    } else {
                        quote!()
                    };
                    let body = match cell_head(body, &t) {
                        Some(body) => quote!(let #t = &*#k; #body),
                        None => quote!(let #t = (*#k).clone(); #body),
                    };
                    // The variant's other fields (passed on unchanged by
                    // the visit's own next situation, `walk(Ps, T)`): their
                    // values, the variant left holding them; read where
                    // they lie where the visit only borrows or clones them
                    // ([`only_refs`]: no clone and drop a step).
                    let mut body = body;
                    let mut others = Vec::new();
                    for x in names.iter().filter(|x| **x != k) {
                        let toks: Vec<TokenTree> = body.clone().into_iter().collect();
                        if only_refs(&toks, x) {
                            others.push(quote!(let #x = &*#x;));
                            body = refs_read_through(&toks, x);
                        } else {
                            others.push(quote!(let #x = (*#x).clone();));
                        }
                    }
                    (
                        Some(quote!(let (#h, #t) = #k.head_tail(); let #t = &#t;)),
                        quote!(#(#others)* #head #k.advance(); #body),
                    )
                }
                Some(c) => {
                    let (h, t, k) = (reg(c.head), reg(c.tail), c.name());
                    let body = match cell_head(body, &h) {
                        Some(body) => body,
                        None => quote!(let #h = #h.clone(); #body),
                    };
                    (
                        Some(quote!(let (#h, #t) = #k.head_tail(); let #t = &#t;)),
                        quote!(let (#h, #t) = #k.head_tail(); #body),
                    )
                }
                None => (None, body.clone()),
            };
            let body = &body;
            let id = &match id_pre {
                Some(pre) => quote!({ #pre #id }),
                None => id.clone(),
            };
            let s = &d.dm.situations[ix];
            let doc = format!(
                " `{}` ({}, type `{}`)",
                self.store.writeq(self.nat_id_of(&d, ix)),
                s.location,
                self.store.writeq(self.store.args(s.template)[2])
            );
            if decls.is_empty() && placeholder.is_none() {
                placeholder = Some(v.clone());
            }
            variants.push(quote!(#[doc = #doc] #v { #(#decls),* },));
            // The waiting variant's id is the situation's (the same
            // fields, the same code): one arm for both.
            let wv = format_ident!("W{}", ix);
            // A variant holding its evaluated call has one field more
            // (`call_held`): `..` in its pattern.
            let rest = match &wait {
                Some(w) if !w.held_arm.is_empty() => quote!(..),
                _ => quote!(),
            };
            let w_pat = if rest.is_empty() {
                quote!(Nat::#wv { #(#names),* })
            } else {
                quote!(Nat::#wv { #(#names,)* #rest })
            };
            let w_arm = quote!(#w_pat => #id,).to_string();
            let same_id = wait.as_ref().is_some_and(|w| w.id_arm.to_string() == w_arm);
            id_arms.push(if same_id {
                quote!(Nat::#v { #(#names),* } | #w_pat => #id,)
            } else {
                quote!(Nat::#v { #(#names),* } => #id,)
            });
            arms.push(if cursor {
                any_cursor = true;
                quote!(Nat::#v { #(ref mut #names),* } => 'visit: { #body })
            } else {
                let body = move_last_clones(body, &names);
                quote!(Nat::#v { #(#names),* } => 'visit: { #body })
            });
            if let Some(w) = wait {
                variants.push(w.variant.clone());
                if !same_id {
                    id_arms.push(w.id_arm.clone());
                }
                exit_arms.push(w.exit_arm.clone());
                wait_arms.push(w.wait_arm.clone());
                waits_arms.push(w.waits_arm.clone());
                wait_pattern |= w.pattern;
                held_arms.push(w.held_arm.clone());
            }
            // A visit that runs the situation's template on every path
            // is not entered natively (issue 37, `nstock23`): its entry
            // would convert the id's fields and the parameters only to
            // hand them back as terms (a walk `try([P|Ps])` on its
            // template converted `Ps` and the parameters at every visit:
            // quadratic). The machine runs it from its template, as it
            // does for a value that does not convert (`_ => return None`).
            if visits[ix] == Some(Visit::Template) {
                continue;
            }
            // Entered by the machine: the fields from the value that
            // selected it, converted (else the term code runs it).
            let ixl = Literal::u32_unsuffixed(ix as u32);
            let mut conv = Vec::new();
            let mut paths = Vec::new();
            for (r, ty) in fields {
                let path: Vec<usize> = match d.plans[ix].inits.iter().find(|(x, _)| x == r) {
                    Some((_, Init::IdArg(a))) => vec![*a],
                    Some((_, Init::IdPath(p))) => p.to_vec(),
                    _ => return Err("an id field has no place in the id".into()),
                };
                let rr = reg(*r);
                let ty = rust_ty(ty)?;
                let path: Vec<Literal> =
                    path.iter().map(|&k| Literal::usize_unsuffixed(k)).collect();
                let text: Vec<String> = path.iter().map(|k| k.to_string()).collect();
                paths.push((quote!(&[#(#path),*]), format!("&[{}]", text.join(", "))));
                conv.push(quote! {
                    let #rr = cx.id_part_as::<#ty>(id, &[#(#path),*])?;
                });
            }
            // The pipe read there converts, else the term code runs it.
            let pipe = self.nat_pipe_entry(&d, ix)?;
            // The fields read in one call where it is one line (the
            // variant's field types say what each converts to).
            let path_ts = paths.iter().map(|(t, _)| t);
            let path_ts2 = path_ts.clone();
            let regs: Vec<Ident> = fields.iter().map(|(r, _)| reg(*r)).collect();
            let (tuple, text) = match regs.as_slice() {
                [one] => (quote!((#one,)), format!("({one},)")),
                _ => {
                    let text: Vec<String> = regs.iter().map(|n| n.to_string()).collect();
                    (quote!((#(#regs),*)), format!("({})", text.join(", ")))
                }
            };
            let parts = quote!(let #tuple = cx.id_parts(&[#(#path_ts),*])?;);
            let path_text: Vec<&str> = paths.iter().map(|(_, t)| t.as_str()).collect();
            // One line or two (prettyplease breaks before `.id_parts` first):
            // its margin is 89, the arm's statements are indented by 16.
            let call = format!(".id_parts(&[{}])?;", path_text.join(", "));
            let in_one_call = (1..=8).contains(&fields.len())
                && 16 + format!("let {text} = cx").len() <= 89
                && 20 + call.len() <= 89;
            let built = match &cell {
                Some(c) => {
                    let inits = fields.iter().filter(|(r, _)| *r != c.head).map(|(r, _)| {
                        let rr = reg(*r);
                        if *r == c.tail {
                            let (k, h) = (c.name(), reg(c.head));
                            quote!(#k: List::cons(#h, #rr))
                        } else {
                            quote!(#rr)
                        }
                    });
                    quote!(Nat::#v { #(#inits),* })
                }
                None => quote!(Nat::#v { #(#names),* }),
            };
            // The whole arm on one line where it fits (the arms are
            // indented by 12): the variant made from the converted parts.
            let names_text: Vec<String> = names.iter().map(|n| n.to_string()).collect();
            let one_line = format!(
                "{ix} => cx.id_parts(&[{}]).map(|{text}| Nat::{v} {{ {} }})?,",
                path_text.join(", "),
                names_text.join(", ")
            );
            entries.push(if fields.is_empty() {
                quote!(#ixl => { #pipe Nat::#v {} })
            } else if cell.is_none() && in_one_call && pipe.is_empty() && 12 + one_line.len() <= 89
            {
                quote!(#ixl => cx.id_parts(&[#(#path_ts2),*]).map(|#tuple| #built)?,)
            } else if in_one_call {
                quote!(#ixl => {
                    #parts
                    #pipe
                    #built
                })
            } else {
                quote!(#ixl => {
                    let id = cx.selected()?;
                    #(#conv)*
                    #pipe
                    #built
                })
            });
        }
        // Where a waiting variant waits (`NatAt::waits`; the frame made the
        // machine's by `NatAt::nat_wait`), unless the DM has locals to
        // write back first: its own `nat_wait` then.
        // A waiting situation with an in_arg pattern builds the pipe value
        // from its fields (`Wait::pattern`): its own `nat_wait` too.
        let own_wait = !wait_arms.is_empty() && (!d.locals.is_empty() || wait_pattern);
        let waits_fn = if own_wait || waits_arms.is_empty() {
            quote!()
        } else {
            quote! {
                fn waits(&self) -> Option<(SitIx, Option<&dyn machine::AsTerm>)> {
                    match self {
                        #(#waits_arms)*
                        _ => None,
                    }
                }
            }
        };
        // The calls the waiting variants hold (`NatAt::held`, read by
        // `NatAt::nat_wait`; a DM's own `nat_wait` reads its fields).
        let held_fn = if own_wait || held_arms.iter().all(|a| a.is_empty()) {
            quote!()
        } else {
            quote! {
                fn held(&self) -> Option<Term> {
                    match self {
                        #(#held_arms)*
                        _ => None,
                    }
                }
            }
        };
        let wait_arms = if own_wait { wait_arms } else { Vec::new() };
        let frame = self.nat_frame_items(&d, &wait_arms)?;
        let field_names = frame.names.clone();
        let out_names = frame.outs.clone();
        let variant_d = format_ident!("D{}", dm_ix);
        let hand = &d.hand;
        // The machine wants control (garbage, a stop asked): the situation
        // reached is handed over as its id.
        let gc = if d.locals.is_empty() {
            // The runtime's hand-over then `step_goto`, one call.
            quote! {
                if cx.gc_tick() {
                    return machine::nat_goto(p, cx, stack, count, &at);
                }
            }
        } else {
            quote! {
                if cx.gc_tick() {
                    #hand
                    return cx.step_goto(count, |s| at.id_term(p, s));
                }
            }
        };
        let arms = by_ref_loads(quote!(#(#arms)*));
        // A cursor's visit that stays (`break 'step`) leaves `at` as it is.
        let step = quote! {
            at = match at {
                #arms
                _ => return Err(cx.fault(Fault::Visited)),
            };
        };
        let step = if any_cursor {
            quote!('step: { #step })
        } else {
            step
        };
        // Resumed after a call returned: the waiting situation's exit arcs,
        // then the same checks as after a visit (before the loop: in the
        // loop's `match`, `echo_calls` measured 8.7 instructions a
        // transition more, all in the caller's `nat_step`, with
        // `Val::converts` inlined: performance.md, `nsize12b`'s section).
        // A DM with no situation that waits (most) does not read `ret`:
        // the driver gives it only to a frame that called.
        let resume = if exit_arms.iter().all(|a| a.is_empty()) {
            quote!()
        } else {
            let exit_arms = by_ref_loads(quote!(#(#exit_arms)*));
            quote! {
                if let Some(ret) = ret {
                    at = match at {
                        #exit_arms
                        _ => return Err(cx.fault(Fault::NotWaiting)),
                    };
                    #gc
                }
            }
        };
        // The frame made of its fields converted in place where that is
        // fewer lines than a `let` each beside a shorthand literal (which
        // prettyplease keeps on one line for a few fields).
        let field_names = &field_names;
        let in_place = quote!(Some(Frame { #(#loads,)* #(#out_names: None,)* at }));
        let lets = loads.iter().zip(field_names).map(|(l, n)| {
            let mut ts = l.clone().into_iter().skip(2);
            let e: TokenStream = ts.by_ref().collect();
            quote!(let #n = #e;)
        });
        let by_lets = quote! {
            #(#lets)*
            Some(Frame { #(#field_names,)* #(#out_names: None,)* at })
        };
        let made = if lines_in_dm(&in_place) <= lines_in_dm(&by_lets) {
            in_place
        } else {
            by_lets
        };
        // `a` bound only where the entries or loads name an atom.
        let entry_body = quote! {
            let at = match sit {
                #(#entries)*
                _ => return None,
            };
            cx.materialize_frames();
            #made
        };
        let entry_prelude = Gen::prelude(&entry_body);
        let entry_body = quote!(#entry_prelude #entry_body);
        let frame_items = frame.items;
        let doc = " Runs the DM natively from `sit`; `None`, nothing done, when it cannot.";
        // The situations' ids, each built by one function.
        let ids: Vec<usize> = d.ids.borrow().iter().copied().collect();
        let id_fns = ids
            .into_iter()
            .map(|ix| self.nat_id_fn(&d, ix))
            .collect::<N<Vec<_>>>()?;
        // Never read while it is there: a step that returns writes its
        // variant back, a fault ends the run.
        let (moved, moved_arm, held_at) = match &placeholder {
            Some(v) => (quote!(), quote!(), quote!(Nat::#v {})),
            None => (
                quote!(Moved {},),
                quote!(Nat::Moved {} => Term::NIL,),
                quote!(Nat::Moved {}),
            ),
        };
        let items = quote! {
            #(#id_fns)*

            #[derive(Clone, Debug)]
            pub enum Nat {
                #(#variants)*
                #moved
            }

            impl NatAt<Program> for Nat {
                fn id_term(&self, p: &Program, store: &mut Store) -> Term {
                    let a = &p.atoms;
                    match self {
                        #(#id_arms)*
                        #moved_arm
                    }
                }
                #waits_fn
                #held_fn
            }

            #frame_items

            // Documented once, in the program's doc (`codegen::emit`).
            #[inline(never)]
            pub(crate) fn nat_step(
                p: &Program,
                cx: &mut Ctx,
                frame: &mut Frame,
                ret: Option<&mut super::NatFrame>,
                stack: &mut super::NatBelow<'_>,
                call: &mut Option<super::NatFrame>,
                run: &TypedRun,
            ) -> NatResult {
                let a = &p.atoms;
                let Frame { #(#field_names,)* #(#out_names,)* at: slot } = frame;
                // Transitions done, not yet given to the machine.
                let mut count: u64 = 0;
                // A final reached below the base, or a call made, writes
                // its variant to `slot` and returns at once.
                let mut at = ::std::mem::replace(slot, #held_at);
                #resume
                loop {
                    #step
                    #gc
                }
            }

            /// The frame entered at `sit`, its values converted (`None`: one does not).
            pub(crate) fn nat_entry(p: &Program, cx: &mut Ctx, sit: SitIx) -> Option<Frame> {
                #entry_body
            }
        };
        // Only for a DM with term code too (`codegen::emit`): an all-native
        // DM's frame is entered by the program's `run_situation`.
        let run_native = quote! {
            #[doc = #doc]
            pub fn run_native(p: &Program, cx: &mut Ctx, sit: SitIx) -> NatResult {
                let run = cx.typed_run();
                let Some(frame) = nat_entry(p, cx, sit) else {
                    return Ok(None);
                };
                machine::nat_drive(p, cx, super::NatFrame::#variant_d(frame), &run).map(Some)
            }
        };
        // Counted on inference's types: a register that holds no value
        // (`never`: `_`, a parameter or id part nothing reads) is native
        // there although native code may carry a term in its place.
        // And on what the situation's code does (`Visit`): one that hands
        // the frames over or runs the template on a path of its own (not
        // a failed conversion's, not the history's) is not.
        let native: Vec<&SitTypes> = t
            .sits
            .iter()
            .flatten()
            .zip(&d.native)
            .zip(&visits)
            .filter(|((st, &n), v)| {
                n && **v == Some(Visit::Native) && st.regs.iter().all(|r| r.ty.is_native())
            })
            .map(|((st, _), _)| st)
            .collect();
        let fixed_shapes = native
            .iter()
            .filter(|st| !st.regs.iter().any(|r| holds_val(&r.ty)))
            .count();
        let items = select_fn::share_selections(items, &d.sels.borrow());
        let items = sel_flat::flatten(items);
        let held = Self::nat_held(&d);
        Ok(NativeCode {
            held,
            items,
            run_native,
            callee_ok: d.native.first().copied().unwrap_or(false) && d.locals_ok,
            on_native_values: native.len(),
            fixed_shapes,
            native_sits: d.native.iter().filter(|&&n| n).count(),
            visits,
            why,
        })
    }

    /// [`NativeCode::held`]: what native code holds as Rust values, read
    /// from the frame's and the registers' types it decided.
    fn nat_held(d: &Dm) -> Held {
        let all = !d.native.is_empty() && d.native.iter().all(|&n| n);
        let native = |ty: &Ty| *ty != Ty::Term && rust_ty(ty).is_ok();
        // An output parameter is held in its output slot, bound at the
        // final from a Rust value of its output type.
        let outs = d.outs.borrow();
        let params = d
            .params
            .iter()
            .enumerate()
            .map(|(i, ty)| {
                let out = d.outputs.get(i).is_some_and(Option::is_some)
                    && outs.get(i).copied().unwrap_or(false);
                all && (native(ty) || out)
            })
            .collect();
        let locals =
            d.dm.locals
                .iter()
                .map(|(name, _)| {
                    all && d.locals_ok && d.locals.iter().any(|(n, ty)| n == name && native(ty))
                })
                .collect();
        let pipe = all
            && d.plans.iter().zip(&d.types).all(|(plan, st)| {
                plan.inits.iter().all(|(r, init)| {
                    !matches!(init, Init::Pipe) || native(&st.regs[*r as usize].ty)
                })
            });
        Held {
            params,
            locals,
            pipe,
        }
    }

    /// The plans and types native code of DM `dm_ix` works from (`t` with
    /// unread registers as `term`), which situations have native code and
    /// their code, or why the DM has none; why each other situation has
    /// none.
    #[allow(clippy::type_complexity)]
    fn nat_dm_fix<'a>(
        &'a self,
        dm: &'a IrDm,
        dm_ix: usize,
        t: &DmTypes,
        shallow: bool,
    ) -> N<(Dm<'a>, Vec<Option<String>>, Vec<Option<SitCode>>)> {
        let mut plans = Vec::new();
        let mut types = Vec::new();
        // Per situation, why it has no native code (`None`: it may).
        let mut why: Vec<Option<String>> = Vec::new();
        for i in 0..dm.situations.len() {
            let plan = self
                .mir
                .plan(dm_ix as u32, i as u32)
                .ok_or("a situation is instantiated from its template")?;
            let st = t.sits[i].as_ref().ok_or("a situation has no types")?;
            let mut st = st.clone();
            for r in 0..st.regs.len() {
                if st.unbound.get(r).copied().unwrap_or(false) {
                    let init = plan
                        .inits
                        .iter()
                        .find(|(x, _)| *x as usize == r)
                        .map(|(_, i)| i);
                    st.regs[r].ty = unread_reg_ty(t, &st, init);
                }
            }
            let mut w = None;
            if let Some(r) = st.regs.iter().position(|r| rust_ty(&r.ty).is_err()) {
                let reason = st.regs[r].why.as_deref().unwrap_or("no reason given");
                w = Some(format!("register r{r} typed {}: {reason}", st.regs[r].ty));
            }
            // A parameter it reads must be native too.
            for (_, init) in &plan.inits {
                if let Init::HeadArg(p) = init {
                    let ty = t.params.get(*p).map_or(Ty::Term, |p| p.ty.clone());
                    if w.is_none() && rust_ty(&ty).is_err() {
                        w = Some(format!("parameter {} is typed {ty}", p + 1));
                    }
                }
                // A head pattern's parameter is taken apart as a `Val`.
                if let Init::HeadPath(p, _) = init {
                    let ty = t.params.get(*p).map_or(Ty::Term, |p| p.ty.clone());
                    if w.is_none() && !held_as_val(&ty) {
                        w = Some(format!(
                            "parameter {} (a pattern of the head) is typed {ty}",
                            p + 1
                        ));
                    }
                }
            }
            // An id argument linked with a parameter (D-7): no code when
            // both are values (they bind nothing); else the term code's link.
            for &(r, p) in &plan.links {
                let param = t.params.get(p).map_or(Ty::Term, |p| p.ty.clone());
                let own = &st.regs[r as usize].ty;
                if w.is_none() && !(param.is_native() && own.is_native()) {
                    w = Some(format!(
                        "its id's argument r{r} is parameter {} too, linked (D-7) where not both are values",
                        p + 1
                    ));
                }
            }
            why.push(w);
            plans.push(plan);
            types.push(st);
        }
        // The locals, held in the frame when each has a native type.
        let (locals, locals_ok) = match self.nat_locals(dm, t) {
            Ok(l) => (l, true),
            Err(_) => (Vec::new(), false),
        };
        let outputs: Vec<Option<Ty>> = t
            .outputs
            .iter()
            .map(|o| {
                o.as_ref()
                    .map(|o| o.ty.clone())
                    .filter(|ty| *ty != Ty::Term && ty.is_native() && rust_ty(ty).is_ok())
            })
            .collect();
        let occ = plans
            .iter()
            .map(|p| crate::mir::ty::occurrences(p))
            .collect();
        let mut d = Dm {
            dm,
            plans,
            types,
            params: t.params.iter().map(|p| p.ty.clone()).collect(),
            native: why.iter().map(Option::is_none).collect(),
            locals,
            locals_ok,
            hand: quote!(),
            shallow,
            out: std::cell::RefCell::new(quote!()),
            rec: std::cell::RefCell::new(quote!()),
            ids: Default::default(),
            id_n: Default::default(),
            outputs: outputs.clone(),
            outs: std::cell::RefCell::new(outputs.iter().map(Option::is_some).collect()),
            pipe_in: std::cell::Cell::new(None),
            pipe_unread: std::cell::Cell::new(false),
            movable: Default::default(),
            occ,
            sels: Default::default(),
        };
        d.hand = self.nat_hand(&d)?;
        // Each situation's code, given which others have native code (a
        // next situation without is handed to the machine): a fixpoint,
        // since a situation that fails only makes others hand over more.
        let mut code: Vec<Option<SitCode>>;
        loop {
            code = vec![None; d.plans.len()];
            d.ids.borrow_mut().clear();
            let mut changed = false;
            for ix in 0..d.plans.len() {
                if !d.native[ix] {
                    continue;
                }
                let c = self.nat_fields(&d, ix).and_then(|fields| {
                    let body = self.native_visit(&d, ix, &fields)?;
                    let id = self.nat_id_value(&d, ix, quote!(store))?;
                    // A recursive situation waiting for its callee: its own
                    // variant.
                    let wait = self.nat_wait_variant(&d, ix)?;
                    Ok((fields, body, id, wait))
                });
                match c {
                    Ok(c) => code[ix] = Some(c),
                    Err(e) => {
                        why[ix] = Some(e);
                        d.native[ix] = false;
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        // The frame's parameters: those native situations read, of their
        // type (converted at entry); the others held as the machine's
        // terms (`Ground`, unchecked: read only to rebuild the call term of
        // a native callee, whose arguments are native values).
        let read = d.read_params();
        for (i, ty) in d.params.iter_mut().enumerate() {
            if !read.contains(&i) || rust_ty(ty).is_err() {
                *ty = Ty::Term;
            }
        }
        Ok((d, why, code))
    }

    fn nat_id_of(&self, d: &Dm, ix: usize) -> Term {
        self.store.args(d.dm.situations[ix].template)[ID]
    }

    /// The variant's fields: the registers its id's variables start in.
    fn nat_fields(&self, d: &Dm, ix: usize) -> N<Vec<(Reg, Ty)>> {
        Ok(d.plans[ix]
            .inits
            .iter()
            .filter(|(_, i)| matches!(i, Init::IdArg(_) | Init::IdPath(_)))
            .map(|&(r, _)| (r, d.types[ix].regs[r as usize].ty.clone()))
            .collect())
    }

    /// The register a variable of situation `ix`'s id at `path` starts in.
    fn nat_id_reg(d: &Dm, ix: usize, path: &[usize]) -> Option<Reg> {
        d.plans[ix].inits.iter().find_map(|(r, i)| match i {
            Init::IdArg(a) if path == [*a] => Some(*r),
            Init::IdPath(p) if **p == *path => Some(*r),
            _ => None,
        })
    }

    /// Situation `ix`'s [`CellField`], if it has one (the first list
    /// pattern of its id that qualifies).
    fn nat_cell(&self, d: &Dm, ix: usize) -> Option<CellField> {
        if matches!(d.dm.situations[ix].kind, Kind::Final | Kind::Recursive) {
            return None;
        }
        let id = self.nat_id_of(d, ix);
        let mut vars = Vec::new();
        let mut cells = Vec::new();
        let mut path = Vec::new();
        for (i, &a) in self.store.args(id).iter().enumerate() {
            path.push(i);
            self.nat_cells_in(a, &mut path, &mut vars, &mut cells);
            path.pop();
        }
        let once = |v: u32| vars.iter().filter(|&&x| x == v).count() == 1;
        cells.into_iter().find_map(|(path, h, t)| {
            if h == t || !once(h) || !once(t) {
                return None;
            }
            let reg_at = |k: usize| {
                let mut p = path.clone();
                p.push(k);
                Self::nat_id_reg(d, ix, &p)
            };
            let (head, tail) = (reg_at(0)?, reg_at(1)?);
            let regs = &d.types[ix].regs;
            let ty = regs.get(tail as usize)?.ty.clone();
            // An element copied for nothing (an atom, an int) gains nothing
            // held this way when the variant moves at each visit: measured,
            // `list<atom>` lost 14 instructions a visit (`performance.md`,
            // `nperf8`). Held alone (a cursor, [`Gen::nat_cursor`]), the
            // variant stays where it is, which the clock pays for whatever
            // the element (`nperf9`; the lead's ninth-session run).
            match &ty {
                Ty::List(e)
                    if regs.get(head as usize)?.ty == **e
                        && (held_as_val(e) || self.nat_holds_only(d, ix, head, tail)) => {}
                _ => return None,
            }
            rust_ty(&ty).ok()?;
            Some(CellField {
                head,
                tail,
                path,
                ty,
            })
        })
    }

    /// Whether situation `ix`'s visit may advance its [`CellField`] in
    /// place (a cursor): the variant holds the cell alone (no other
    /// field to move in or out). Such a visit, when its next situation
    /// is its own with its own tail (`try([P|Ps])` to `try(Ps)`), makes
    /// the held list its tail in place (`List::advance`: a slice's start
    /// index moved, no `Rc` count touched; a cons cell replaced by its
    /// tail) and, unrecorded, leaves the variant where it is (`break
    /// 'step`; recorded, the variant is built again for the entry's next
    /// id). The list is advanced at the visit's start, whichever arc is
    /// taken: `P` is cloned out before (a `Val`: an atom copied, a
    /// compound's `Rc` counted) and `Ps` is the advanced list, so every
    /// other path (an id built, a hand-over, another next situation) reads
    /// the values it read before. `break 'step` leaves the arc's code
    /// after the selection unrun: what must happen for the transition
    /// (its count) has to come before it. Moving the variant
    /// instead (the next one built, then moved into the loop's `at`)
    /// cost more by the clock than its instructions say (stores read
    /// back by wider loads: `performance.md`, `nperf9`).
    fn nat_cursor(&self, d: &Dm, ix: usize) -> bool {
        self.nat_cell(d, ix)
            .is_some_and(|c| self.nat_holds_only(d, ix, c.head, c.tail))
    }

    /// [`Gen::nat_cursor`], or a variant holding other fields beside its
    /// cell (`walk([P|Ps], T)`) whose own next situation, the tail at
    /// argument `i`, passes every other id argument on as it is, each a
    /// variable of the id held in a field (`walk(Ps, T)`): advanced in
    /// place, the variant keeps them (the arm clones them out for the
    /// visit, as the next variant's fields were cloned).
    fn nat_cursor_passing(&self, d: &Dm, ix: usize, i: usize, args: &[V]) -> bool {
        if self.nat_cursor(d, ix) {
            return true;
        }
        let Some(c) = self.nat_cell(d, ix) else {
            return false;
        };
        let Ok(fields) = self.nat_fields(d, ix) else {
            return false;
        };
        let mut passed = 0;
        for (k, a) in args.iter().enumerate() {
            if k == i {
                continue;
            }
            match Self::nat_id_reg(d, ix, &[k]) {
                Some(r) if reg(r) == moved(a).to_string() => passed += 1,
                _ => return false,
            }
        }
        // Every field is the cell's or one of those passed on.
        fields.len() == passed + 2 && fields.iter().any(|(r, _)| *r == c.tail)
    }

    /// Whether situation `ix`'s variant holds no field but the cell's
    /// `head` and `tail` registers (the cursor's condition).
    fn nat_holds_only(&self, d: &Dm, ix: usize, head: Reg, tail: Reg) -> bool {
        self.nat_fields(d, ix)
            .is_ok_and(|fs| fs.iter().all(|(r, _)| *r == head || *r == tail))
    }

    /// The variables of `t` (each occurrence) and its list patterns of two
    /// variables `[H|T]` (path, `H`, `T`), for [`Gen::nat_cell`].
    fn nat_cells_in(
        &self,
        t: Term,
        path: &mut Vec<usize>,
        vars: &mut Vec<u32>,
        cells: &mut Vec<(Vec<usize>, u32, u32)>,
    ) {
        match self.store.value(t) {
            Value::Var(v) => vars.push(v.index()),
            Value::Compound(name, args) => {
                let args = args.to_vec();
                if let (true, [h, tl]) = (name == atoms::DOT, args.as_slice()) {
                    if let (Value::Var(h), Value::Var(tl)) =
                        (self.store.value(*h), self.store.value(*tl))
                    {
                        cells.push((path.clone(), h.index(), tl.index()));
                    }
                }
                for (k, a) in args.into_iter().enumerate() {
                    path.push(k);
                    self.nat_cells_in(a, path, vars, cells);
                    path.pop();
                }
            }
            _ => {}
        }
    }

    /// The term of atom `a` (`Term::EMPTY` for `empty`, `Term::NIL` for `[]`).
    fn atom_term(&self, a: Atom) -> N<TokenStream> {
        if a == atoms::EMPTY {
            return Ok(quote!(Term::EMPTY));
        }
        if a == atoms::NIL {
            return Ok(quote!(Term::NIL));
        }
        let a = self.atom_native(a)?;
        Ok(quote!(Term::atom(#a)))
    }

    fn atom_native(&self, a: Atom) -> N<TokenStream> {
        if a == atoms::NIL {
            return Ok(quote!(atoms::NIL));
        }
        if a == atoms::EMPTY {
            return Ok(quote!(atoms::EMPTY));
        }
        match self.atom_ix.get(&a) {
            Some(&i) => {
                let id = &self.atoms[i].1;
                Ok(quote!(a.#id))
            }
            None => Err(format!(
                "atom `{}` is not a constant of the program",
                a.as_str()
            )),
        }
    }

    /// The id of situation `ix` as a term, from its fields (`store`: the
    /// store expression): statements and the value; where the fields have
    /// Rust types, its pattern filled (`Cx::fill`/`machine::fill`,
    /// `Gen::nat_id_fill`), or a call of the DM's `id_s<ix>`
    /// ([`Gen::nat_id_fn`]) where the pattern does not read back.
    fn nat_id_term(
        &self,
        d: &Dm,
        ix: usize,
        store: TokenStream,
    ) -> N<(Vec<TokenStream>, TokenStream)> {
        self.nat_id_term_of(d, ix, store, false)
    }

    /// [`Gen::nat_id_term`] from fields that are references (`refs`: a
    /// frame matched by reference) or owned locals.
    fn nat_id_term_of(
        &self,
        d: &Dm,
        ix: usize,
        store: TokenStream,
        refs: bool,
    ) -> N<(Vec<TokenStream>, TokenStream)> {
        let (stmts, v) = self.nat_id_inline(d, ix, store.clone())?;
        if stmts.is_empty() {
            return Ok((stmts, v));
        }
        match self.nat_id_params(d, ix) {
            Ok(params) => {
                let names: Vec<Ident> = params.iter().map(|(r, _)| r.clone()).collect();
                // Its pattern filled, or the DM's `id_s<ix>`.
                let e = match self.nat_id_fill(d, ix, &names, &store, refs) {
                    Some(e) => e,
                    None => {
                        d.ids.borrow_mut().insert(ix);
                        let f = format_ident!("id_s{}", ix);
                        let args = params.iter().map(|(r, _)| quote!(&#r));
                        quote!(#f(p, #store, #(#args),*))
                    }
                };
                // A statement: the id is often an argument of a `cx` call.
                let n = d.id_n.get();
                d.id_n.set(n + 1);
                let x = format_ident!("id{}", n);
                Ok((vec![quote!(let #x = #e;)], quote!(#x)))
            }
            Err(_) => Ok((stmts, v)),
        }
    }

    /// [`Gen::nat_id_term`] as one expression (the pattern filled, or the
    /// `id_s<ix>` call itself where there is one), for `Nat::id_term`'s arms.
    fn nat_id_value(&self, d: &Dm, ix: usize, store: TokenStream) -> N<TokenStream> {
        let (stmts, v) = self.nat_id_inline(d, ix, store.clone())?;
        if stmts.is_empty() {
            return Ok(v);
        }
        match self.nat_id_params(d, ix) {
            Ok(params) => {
                let names: Vec<Ident> = params.iter().map(|(r, _)| r.clone()).collect();
                if let Some(e) = self.nat_id_fill(d, ix, &names, &store, true) {
                    return Ok(e);
                }
                d.ids.borrow_mut().insert(ix);
                let f = format_ident!("id_s{}", ix);
                let args = params.iter().map(|(r, _)| quote!(&#r));
                Ok(quote!(#f(p, #store, #(#args),*)))
            }
            Err(_) => Ok(quote!({ #(#stmts)* #v })),
        }
    }

    /// The fields situation `ix`'s id is built from, with their Rust types.
    fn nat_id_params(&self, d: &Dm, ix: usize) -> N<Vec<(Ident, TokenStream)>> {
        let (stmts, v) = self.nat_id_inline(d, ix, quote!(store))?;
        let used = super::step::registers(&quote!(#(#stmts)* #v));
        self.nat_fields(d, ix)?
            .into_iter()
            .filter(|(r, _)| used.contains(r))
            .map(|(r, ty)| Ok((reg(r), rust_ty(&ty)?)))
            .collect()
    }

    /// `fn id_s<ix>`: situation `ix`'s id as a term, from its fields (made
    /// only where its pattern does not read back, `Gen::nat_id_fill`): a
    /// `machine::build_of` per
    /// compound of the id, the fields (references) and constants its
    /// arguments.
    fn nat_id_fn(&self, d: &Dm, ix: usize) -> N<TokenStream> {
        let mut stmts = Vec::new();
        let mut n = 0;
        let id = self.nat_id_of(d, ix);
        let (v, _) = self.nat_id_part(d, ix, id, &mut Vec::new(), &mut stmts, &mut n, true)?;
        let params = self.nat_id_params(d, ix)?;
        let params = params.iter().map(|(r, ty)| quote!(#r: &#ty));
        let f = format_ident!("id_s{}", ix);
        let doc = format!(
            " The id `{}` from its variables.",
            self.store.writeq(self.nat_id_of(d, ix))
        );
        let body = quote!(#(#stmts)* #v);
        let prelude = super::Gen::prelude(&body);
        Ok(quote! {
            #[doc = #doc]
            fn #f(p: &Program, store: &mut Store, #(#params),*) -> Term {
                #prelude
                #body
            }
        })
    }

    /// Part `t` (at `path`) of situation `ix`'s id, for [`Gen::nat_id_fn`]:
    /// the expression and whether it is a reference already (a field); a
    /// compound is a statement unless it is the whole id (`top`).
    #[allow(clippy::too_many_arguments)]
    fn nat_id_part(
        &self,
        d: &Dm,
        ix: usize,
        t: Term,
        path: &mut Vec<usize>,
        stmts: &mut Vec<TokenStream>,
        n: &mut usize,
        top: bool,
    ) -> N<(TokenStream, bool)> {
        Ok(match self.store.value(t) {
            Value::Var(_) => {
                // A repeated variable: its first occurrence's field.
                let r = match Self::nat_id_reg(d, ix, path) {
                    Some(r) => r,
                    None => self.nat_first_reg(d, ix, t)?,
                };
                let rr = reg(r);
                (quote!(#rr), true)
            }
            Value::Atom(a) if a == atoms::NIL => (quote!(Term::NIL), false),
            Value::Atom(a) => {
                let a = self.atom_native(a)?;
                (quote!(Term::atom(#a)), false)
            }
            Value::Int(i) => {
                let i = Literal::i64_suffixed(i);
                (quote!(Term::int(#i)), false)
            }
            Value::Compound(name, args) => {
                let args = args.to_vec();
                let mut parts = Vec::new();
                for (i, &a) in args.iter().enumerate() {
                    path.push(i);
                    let (e, by_ref) = self.nat_id_part(d, ix, a, path, stmts, n, false)?;
                    path.pop();
                    parts.push(if by_ref { e } else { quote!(&#e) });
                }
                let f = if name == atoms::DOT {
                    quote!(atoms::DOT)
                } else {
                    self.atom_native(name)?
                };
                let e = quote!(machine::build_of(store, #f, &[#(#parts),*]));
                if top {
                    return Ok((e, false));
                }
                let x = format_ident!("t{}", *n);
                *n += 1;
                stmts.push(quote!(let #x = #e;));
                (quote!(#x), false)
            }
            _ => return Err("an id holds a constant that is not native".into()),
        })
    }

    /// The register of the first occurrence (pre-order, left to right) of
    /// id variable `t` of situation `ix`.
    fn nat_first_reg(&self, d: &Dm, ix: usize, t: Term) -> N<Reg> {
        fn find(store: &sitlog_runtime::Store, at: Term, var: Term, path: &mut Vec<usize>) -> bool {
            if store.deref(at) == var {
                return true;
            }
            if let Value::Compound(_, args) = store.value(at) {
                for (i, &a) in args.iter().enumerate() {
                    path.push(i);
                    if find(store, a, var, path) {
                        return true;
                    }
                    path.pop();
                }
            }
            false
        }
        let mut path = Vec::new();
        let var = self.store.deref(t);
        if !find(self.store, self.nat_id_of(d, ix), var, &mut path) {
            return Err("an id variable has no register".into());
        }
        Self::nat_id_reg(d, ix, &path).ok_or_else(|| "an id variable has no register".into())
    }

    /// [`Gen::nat_id_term`] built inline.
    fn nat_id_inline(
        &self,
        d: &Dm,
        ix: usize,
        store: TokenStream,
    ) -> N<(Vec<TokenStream>, TokenStream)> {
        let mut stmts = Vec::new();
        let mut vars = HashMap::new();
        let mut n = 0;
        let id = self.nat_id_of(d, ix);
        let v = self.nat_term_of(
            d,
            ix,
            id,
            &mut Vec::new(),
            &mut vars,
            &mut stmts,
            &mut n,
            &store,
        )?;
        Ok((stmts, v))
    }

    #[allow(clippy::too_many_arguments)]
    fn nat_term_of(
        &self,
        d: &Dm,
        ix: usize,
        t: Term,
        path: &mut Vec<usize>,
        vars: &mut HashMap<u32, Ident>,
        stmts: &mut Vec<TokenStream>,
        n: &mut usize,
        store: &TokenStream,
    ) -> N<TokenStream> {
        Ok(match self.store.value(t) {
            Value::Var(v) => {
                if let Some(r) = vars.get(&v.index()) {
                    let r = r.clone();
                    quote!(#r)
                } else {
                    let r =
                        Self::nat_id_reg(d, ix, path).ok_or("an id variable has no register")?;
                    let x = format_ident!("t{}", *n);
                    *n += 1;
                    let rr = reg(r);
                    stmts.push(quote! {
                        let #x = #rr.to_term(#store);
                    });
                    vars.insert(v.index(), x.clone());
                    quote!(#x)
                }
            }
            Value::Atom(a) if a == atoms::NIL => quote!(Term::NIL),
            Value::Atom(a) => {
                let a = self.atom_native(a)?;
                quote!(Term::atom(#a))
            }
            Value::Int(i) => {
                let i = Literal::i64_suffixed(i);
                quote!(Term::int(#i))
            }
            Value::Compound(name, args) => {
                let args = args.to_vec();
                let mut parts = Vec::new();
                for (i, &a) in args.iter().enumerate() {
                    path.push(i);
                    parts.push(self.nat_term_of(d, ix, a, path, vars, stmts, n, store)?);
                    path.pop();
                }
                let f = if name == atoms::DOT {
                    quote!(atoms::DOT)
                } else {
                    self.atom_native(name)?
                };
                let x = format_ident!("t{}", *n);
                *n += 1;
                stmts.push(quote!(let #x = native::compound(#store, #f, &[#(#parts),*]);));
                quote!(#x)
            }
            _ => return Err("an id holds a constant that is not native".into()),
        })
    }

    /// The code of one visit of situation `ix` (its fields bound): returns
    /// from `nat_step` or gives the next `Nat`.
    /// A visit whose code never reads the register the in_arg read the
    /// pipe into (`in_arg ==> X, out_arg ==> X`, or `X` unused) is made
    /// again with the pipe's conversion only checked ([`Gen::nat_pipe_in`]).
    fn native_visit(&self, d: &Dm, ix: usize, fields: &[(Reg, Ty)]) -> N<TokenStream> {
        let id_n = d.id_n.get();
        d.pipe_in.set(None);
        let code = self.native_visit_arcs(d, ix, fields);
        let pipe = d.pipe_in.take();
        let code = match (code, pipe) {
            (Ok(code), Some(r)) if pipe::mentions(&code, &reg(r)) == 1 => {
                d.id_n.set(id_n);
                d.pipe_unread.set(true);
                let again = self.native_visit_arcs(d, ix, fields);
                d.pipe_unread.set(false);
                again
            }
            (code, _) => code,
        };
        d.pipe_in.set(None);
        code
    }

    /// [`Gen::native_visit`], with [`Dm::pipe_in`] set once the pipe is read.
    fn native_visit_arcs(&self, d: &Dm, ix: usize, fields: &[(Reg, Ty)]) -> N<TokenStream> {
        let plan = d.plans[ix];
        let st = &d.types[ix];
        // Where each register's value lives: a field, a parameter, a local.
        let mut regs: Regs = fields
            .iter()
            .map(|(r, ty)| (*r, (reg(*r), ty.clone())))
            .collect();
        let mut stmts = Vec::new();
        for (r, init) in &plan.inits {
            match init {
                // A parameter nothing reads here is not loaded.
                Init::HeadArg(_) if st.unbound.get(*r as usize).copied().unwrap_or(false) => {}
                Init::HeadArg(i) => {
                    let ty = st.regs[*r as usize].ty.clone();
                    stmts.push(load_head_arg(d, *r, *i, ty, &mut regs)?);
                }
                Init::HeadPath(..) if st.unbound.get(*r as usize).copied().unwrap_or(false) => {}
                Init::HeadPath(i, path) => {
                    let ty = st.regs[*r as usize].ty.clone();
                    stmts.push(head::load_head_path(d, *r, *i, path, ty, &mut regs)?);
                }
                Init::Pipe => {
                    let ty = st.regs[*r as usize].ty.clone();
                    stmts.push(self.nat_pipe_in(d, ix, *r, &ty)?);
                    regs.insert(*r, (reg(*r), ty));
                    d.pipe_in.set(Some(*r));
                }
                Init::Fresh | Init::IdArg(_) | Init::IdPath(_) => {}
            }
        }
        // A variable in_arg: its register holds the pipe's value.
        if let Some((Build::Reg(src), false, r)) = &plan.in_arg {
            if let Some(at) = regs.get(src).cloned() {
                regs.insert(*r, at);
            }
        }
        // An in_arg that is a pattern: matched against the pipe natively.
        // In a recursive situation its variables the exit arcs or the call
        // read are fields of the waiting variant, from which a frame made
        // the machine's builds the pipe value its instance unifies
        // (`call::nat_in_arg_term`).
        if let Some((pat, true, _)) = &plan.in_arg {
            stmts.push(self.nat_pipe_match(d, ix, pat, &mut regs)?);
        }
        if let Some(prog) = &plan.prog {
            stmts.push(self.nat_prog(d, ix, prog, &mut regs)?);
        }
        let cur = Literal::u32_unsuffixed(ix as u32);
        let kind = d.dm.situations[ix].kind;
        match (&plan.kind, kind) {
            (KindPlan::Final { diag_mod }, Kind::Final) => {
                let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
                // `diag_mod`: the DM's head bound (its output arguments),
                // a term built from native values at that boundary.
                // A native caller that passed its outputs as `Ground::OUT`
                // gets them in the frame's output slots (`call::slot_final`).
                let mut slot_below = None;
                let diag = match diag_mod {
                    Some(b) => {
                        // A constant `welcome([])`: its parts give the
                        // slots (`ground_parts`), the term is the constant.
                        let parts = self.diag_parts(d, b);
                        let whole = b;
                        let b = parts.as_ref().unwrap_or(b);
                        let outs = self.nat_output_slots(d, b, &regs);
                        slot_below = self.nat_slot_below(d, ix, b, &outs);
                        let mut ts: Vec<TokenStream> = outs
                            .iter()
                            .flatten()
                            .map(|(o, rt, e)| quote!(let #o: #rt = #e;))
                            .collect();
                        let slots: Vec<Option<Ident>> =
                            outs.into_iter().map(|s| s.map(|(o, _, _)| o)).collect();
                        let mut n = 0;
                        let t = match b {
                            _ if parts.is_some() => {
                                ts.clear();
                                self.nat_build_term(whole, &regs, &mut ts, &mut n)
                                    .map_err(|e| format!("its diag_mod: {e}"))?
                            }
                            // Every argument a slot or a register: one
                            // `build_of` of the values.
                            Build::Compound(f, args)
                                if slots.iter().any(Option::is_some)
                                    && args.iter().zip(&slots).all(|(a, slot)| {
                                        slot.is_some()
                                            || matches!(a, Build::Reg(r) if regs.contains_key(r))
                                    }) =>
                            {
                                let parts =
                                    args.iter().zip(&slots).map(|(a, slot)| match (a, slot) {
                                        (_, Some(o)) => quote!(&#o),
                                        (Build::Reg(r), None) => {
                                            let v = &regs[r].0;
                                            quote!(&#v)
                                        }
                                        _ => quote!(),
                                    });
                                let f = self.functor_native(*f)?;
                                ts.push(quote!(let diag_t = cx.build_of(#f, &[#(#parts),*]);));
                                quote!(diag_t)
                            }
                            Build::Compound(f, args) if slots.iter().any(Option::is_some) => {
                                let mut parts = Vec::new();
                                for (a, slot) in args.iter().zip(&slots) {
                                    parts.push(match slot {
                                        Some(o) => {
                                            let x = format_ident!("{}_t", o);
                                            ts.push(quote!(let #x = cx.term(&#o);));
                                            quote!(#x)
                                        }
                                        None => self
                                            .nat_build_term(a, &regs, &mut ts, &mut n)
                                            .map_err(|e| format!("its diag_mod: {e}"))?,
                                    });
                                }
                                let f = self.functor_native(*f)?;
                                ts.push(quote!(let diag_t = cx.build(#f, &[#(#parts),*]);));
                                quote!(diag_t)
                            }
                            b => self
                                .nat_build_term(b, &regs, &mut ts, &mut n)
                                .map_err(|e| format!("its diag_mod: {e}"))?,
                        };
                        quote!(#(#ts)* cx.diag_mod(#t)?;)
                    }
                    // No output bound here: each is left as the caller
                    // gave it (a slot stays `None`; the MIR's outputs
                    // allow such a final, `DmTypes::outputs`, and the
                    // caller's exit arcs taking it do not read it,
                    // `call::nat_exit`).
                    None => quote!(),
                };
                let v = variant(ix);
                let names: Vec<Ident> = fields.iter().map(|(r, _)| reg(*r)).collect();
                // out_arg: the pipe's new value; a variable nothing binds
                // passes the pipe on (`mir::OutPass`, D-18): none.
                let final_out = match plan.final_out_pass() {
                    crate::mir::OutPass::Unchanged => None,
                    crate::mir::OutPass::Value => plan.out_arg.as_ref(),
                };
                let (out_set, out_final) = match final_out {
                    Some((b, _)) => {
                        let v = self.nat_value(b, &regs)?.e;
                        (
                            quote! {
                                let out = cx.term(&#v);
                                cx.set_pipe(out);
                            },
                            quote! {
                                let out = cx.term(&#v);
                                cx.final_out_arg(Some(out))?;
                            },
                        )
                    }
                    None => (quote!(), quote!()),
                };
                // Below the base the caller's exit arcs read the variant
                // (with a `diag_mod`, the machine takes the final).
                let hand = &d.hand;
                // Recorded (the history kept: the DM's entries in a level
                // of its own): its outputs bound in its call term, its
                // entry made, its level closed (`Cx::close_level`).
                // The id an atom, or filled by the call (`Fill`) where the
                // call still fits on a line (at the depth of a final's
                // `if run.recorded() { .. }`), else its `let` first.
                let close = |outs: TokenStream| {
                    let atom = atom_arg(&id);
                    let (lets, id) = match fill_arg(&id_stmts, &id) {
                        Some(f) if fits(&quote!(cx.close_level(#f, &#outs)?;), 28) => (quote!(), f),
                        _ if id_stmts.is_empty() => (quote!(), atom),
                        _ => (quote!(#(#id_stmts)*), id.clone()),
                    };
                    quote! {
                        if run.recorded() {
                            #lets
                            cx.close_level(#id, &#outs)?;
                            return cx.step_done(count, slot, Nat::#v { #(#names),* });
                        }
                    }
                };
                let below = match (diag_mod, slot_below) {
                    // An atom id, no output: the level closed when recorded
                    // by one call (`TypedRun::close_level`), which gives the
                    // count to hand over (the final's own transition in it
                    // when nothing is recorded).
                    (None, _)
                        if id_stmts.is_empty() && atom_arg(&id).to_string() != id.to_string() =>
                    {
                        let id = atom_arg(&id);
                        quote! {
                            if !stack.is_empty() {
                                #out_set
                                let count = run.close_level(cx, count, #id, &[])?;
                                return cx.step_done(count, slot, Nat::#v { #(#names),* });
                            }
                        }
                    }
                    // A `Fill` id bound first (nothing filled where
                    // nothing is recorded), the same one call.
                    (None, _) if fill_arg(&id_stmts, &id).is_some() => {
                        let fill = fill_arg(&id_stmts, &id);
                        quote! {
                            if !stack.is_empty() {
                                #out_set
                                let #id = #fill;
                                let count = run.close_level(cx, count, #id, &[])?;
                                return cx.step_done(count, slot, Nat::#v { #(#names),* });
                            }
                        }
                    }
                    (None, _) => {
                        let close = close(quote!([]));
                        quote! {
                            if !stack.is_empty() {
                                #out_set
                                #close
                                return cx.step_done(count + 1, slot, Nat::#v { #(#names),* });
                            }
                        }
                    }
                    (Some(_), Some((cond, set, outs)))
                        if fill_arg(&id_stmts, &id).is_some()
                            || (id_stmts.is_empty()
                                && atom_arg(&id).to_string() != id.to_string()) =>
                    {
                        let (id_let, id_arg) = match fill_arg(&id_stmts, &id) {
                            Some(fill) => (quote!(let #id = #fill;), id.clone()),
                            None => (quote!(), atom_arg(&id)),
                        };
                        quote! {
                            if !stack.is_empty() && #cond {
                                #set
                                #out_set
                                #id_let
                                let count = run.close_level(cx, count, #id_arg, &#outs)?;
                                return cx.step_done(count, slot, Nat::#v { #(#names),* });
                            }
                            #hand
                        }
                    }
                    (Some(_), Some((cond, set, outs))) => {
                        let close = close(outs);
                        quote! {
                            if !stack.is_empty() && #cond {
                                #set
                                #out_set
                                #close
                                return cx.step_done(count + 1, slot, Nat::#v { #(#names),* });
                            }
                            #hand
                        }
                    }
                    // No native frame below ever (`ground_parts`): none
                    // to hand over.
                    (Some(_), None) if runtime_hand(hand) && self.only_at_base(d.dm.name) => {
                        quote!()
                    }
                    (Some(_), None) => quote!(#hand),
                };
                // Without an out_arg, the entry and the pipe kept as the
                // final's output by one call (`Cx::enter_final`).
                let enter = if final_out.is_some() {
                    quote!(cx.enter_counted(&mut count, #cur, #id); #out_final)
                } else {
                    quote!(cx.enter_final(&mut count, #cur, #id)?;)
                };
                Ok(quote! {
                    #(#stmts)*
                    #below
                    #(#id_stmts)*
                    #enter
                    #diag
                    return cx.step_final();
                })
            }
            (KindPlan::Perceptual(arcs), kind) => {
                let single = kind == Kind::Perceptual && arcs.always_first && arcs.arcs.len() == 1;
                if !single && !arcs.pure && !self.nat_pure_arcs(arcs, &regs) {
                    return Err("its expectations can change variables".into());
                }
                let mut regs = regs.clone();
                for arc in &arcs.arcs {
                    if arc.diag_mod.is_some() {
                        return Err("its arc has a diag_mod".into());
                    }
                    for (k, from) in arc.import_from.iter().enumerate() {
                        // An imported copy of a ground value is the value.
                        if let Some(at) = regs.get(from).cloned() {
                            regs.insert(arc.import_at + k as Reg, at);
                        }
                    }
                }
                // A fresh variable (`_`, one a perception or a boundary binds:
                // `said(X)`, `apply(name_of(_), [user])`) is a term, made at
                // the start of the visit when the code uses it (as the term
                // code makes it), read natively only after a checked
                // conversion.
                let inits = plan
                    .inits
                    .iter()
                    .filter_map(|(r, i)| matches!(i, Init::Fresh).then_some(r));
                // What an action's `is`/`get` binds (`[X is M * M]`) too.
                let mut bound = Vec::new();
                for arc in &arcs.arcs {
                    match &arc.action {
                        Action::One(e) => ev_binds(e, &mut bound),
                        Action::List { items, .. } => {
                            items.iter().for_each(|e| ev_binds(e, &mut bound))
                        }
                    }
                }
                let arc_fresh = arcs.arcs.iter().flat_map(|a| a.fresh.iter());
                for r in inits.chain(arc_fresh).chain(bound.iter()) {
                    if !regs.contains_key(r) {
                        regs.insert(*r, (format_ident!("fresh_r{}", r), Ty::Term));
                    }
                }
                // An arc's copy of the situation's fresh variable (a `_` of
                // a situation-level out_arg, `apply(f(_), [X])`) is that
                // variable.
                for arc in &arcs.arcs {
                    for (k, from) in arc.import_from.iter().enumerate() {
                        let to = arc.import_at + k as Reg;
                        if let (false, Some(at)) = (regs.contains_key(&to), regs.get(from).cloned())
                        {
                            regs.insert(to, at);
                        }
                    }
                }
                let mut bodies = Vec::new();
                for (i, arc) in arcs.arcs.iter().enumerate() {
                    // The expectation the history records: the one the
                    // machine matched (`e<i>`), or built when recorded.
                    let exp = (!single).then(|| format_ident!("e{}", i));
                    bodies.push(self.nat_arc(d, ix, arc, &regs, exp)?);
                }
                let body = if single {
                    // `arc_at` only where the code reads it.
                    with_arc_at(&bodies[0], 0)
                } else {
                    // The machine chooses the arc (a perception matched
                    // against the expectations, built from native values).
                    let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
                    let mut exps = Vec::new();
                    let mut names = Vec::new();
                    for (i, arc) in arcs.arcs.iter().enumerate() {
                        let mut ts = Vec::new();
                        let mut n = 0;
                        let t = self
                            .nat_ev_term(&arc.expectation, &regs, &mut ts, &mut n)
                            .map_err(|e| format!("its expectation {}: {e}", i + 1))?;
                        let x = format_ident!("e{}", i);
                        let il = Literal::usize_unsuffixed(i);
                        // `arc_at` bound only where its code names it; one
                        // statement building the value is the value.
                        let at = ts.iter().any(|s| s.to_string().contains("arc_at"));
                        exps.push(match (at, one_value(&ts, &t)) {
                            (false, Some(e)) => quote!(let #x = #e;),
                            (false, None) => quote!(let #x = { #(#ts)* #t };),
                            (true, _) => quote! {
                                let #x = {
                                    let arc_at = Some(#il);
                                    #(#ts)*
                                    #t
                                };
                            },
                        });
                        names.push(x);
                    }
                    let mut ts = Vec::new();
                    let mut n = 0;
                    let ty = self
                        .nat_build_term(&arcs.type_term, &regs, &mut ts, &mut n)
                        .map_err(|e| format!("its type: {e}"))?;
                    let arms = bodies.iter().enumerate().map(|(i, b)| {
                        let il = Literal::usize_unsuffixed(i);
                        let b = with_arc_at(b, i);
                        quote!(#il => { #b })
                    });
                    let hand = &d.hand;
                    // The native frames kept unless the input meets nothing
                    // (module `perceive`), else handed over first.
                    let arms: Vec<_> = arms.collect();
                    let enter = quote!(#(#id_stmts)* cx.enter_counted(&mut count, #cur, #id););
                    let lazy = perceive::lazy_id(fill_arg(&id_stmts, &id), &id, &cur, &arms);
                    let kept =
                        perceive::kept_choice(hand, &enter, lazy, &exps, &names, &ts, &ty, &arms);
                    let handed = quote! {
                        #hand
                        #(#id_stmts)*
                        cx.enter_counted(&mut count, #cur, #id);
                        #(#exps)*
                        cx.set_expectations(&[#(#names),*]);
                        #(#ts)*
                        let type_term = #ty;
                        let Some(chosen) = cx.choose(type_term)? else {
                            return Ok(Some(
                                Step::Unmet { type_term },
                            ));
                        };
                        match chosen {
                            #(#arms)*
                            _ => unreachable!("the machine chose an arc of this situation"),
                        }
                    };
                    kept.unwrap_or(handed)
                };
                // The fresh variables the code uses, made first.
                let mut used = std::collections::BTreeSet::new();
                fresh_used(&body, &mut used);
                let fresh = fresh_vars(&used);
                Ok(quote! { #(#stmts)* #fresh #body })
            }
            (KindPlan::Final { .. }, _) => Err("a final situation with diag_mod".into()),
            (KindPlan::Recursive { .. }, Kind::Recursive) => {
                // A fresh variable (an output argument, `_`) is a term made
                // at the start of the visit when the code uses it, as the
                // term code makes it; such a call is the machine's.
                let mut regs = regs.clone();
                for (r, i) in &plan.inits {
                    if matches!(i, Init::Fresh) && !regs.contains_key(r) {
                        regs.insert(*r, (format_ident!("fresh_r{}", r), Ty::Term));
                    }
                }
                let call = self.nat_recursive(d, ix, &regs)?;
                let mut used = std::collections::BTreeSet::new();
                fresh_used(&call, &mut used);
                let fresh = fresh_vars(&used);
                Ok(quote! { #(#stmts)* #fresh #call })
            }
            (KindPlan::Recursive { .. }, _) => Err("a recursive plan of another kind".into()),
        }
    }

    /// Whether matching the arcs' expectations can bind only the arcs' own
    /// fresh variables, although the MIR says they may change the
    /// situation's (`Arcs::pure` false: `hands(_, Object)` names the
    /// situation's `Object`): each expectation is built (nothing
    /// evaluated) and every situation variable in it is held natively
    /// here, a value, so ground: unifying cannot bind it.
    fn nat_pure_arcs(&self, arcs: &crate::mir::Arcs, regs: &Regs) -> bool {
        arcs.arcs.iter().all(|arc| {
            let mut used = Vec::new();
            if !built_regs(&arc.expectation, &mut used) {
                return false;
            }
            used.iter().all(|r| {
                let Some(k) = r.checked_sub(arc.import_at) else {
                    return true;
                };
                let Some(from) = arc.import_from.get(k as usize) else {
                    return true; // the arc's own variable
                };
                regs.get(from).is_some_and(|(x, ty)| {
                    !is_fresh(x) && *ty != Ty::Term && ty.is_native() && rust_ty(ty).is_ok()
                })
            })
        })
    }

    /// A `prog` of `set(l, V)` and `inc(l, _)` of the frame's locals and `V is E` elements
    /// (`V` not set yet, `E` integer `+`, `-`,
    /// `*` over registers and integer constants, or float arithmetic as an
    /// arc's action computes it, `float_expr`): computed in Rust with
    /// checked operations; when an operand is not a number of its kind, an
    /// operation overflows or a float result is not finite, the element is
    /// evaluated on terms where the term code
    /// evaluates it (the machine entered in the situation: its value or
    /// its error), and its value converted to `V`'s type.
    fn nat_prog(&self, d: &Dm, ix: usize, prog: &Prog, regs: &mut Regs) -> N<TokenStream> {
        let Prog::InPlace(parts) = prog else {
            return Err("its prog shares variables with a copy (D-10)".into());
        };
        let cur = Literal::u32_unsuffixed(ix as u32);
        let hand = &d.hand;
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        // A register that starts unbound in this visit (not a parameter,
        // an id part or the pipe, which may hold a value).
        let fresh = |r: Reg| {
            d.plans[ix]
                .inits
                .iter()
                .all(|(x, i)| *x != r || matches!(i, Init::Fresh))
        };
        let mut out = Vec::new();
        for (k, part) in parts.iter().enumerate() {
            // `set(l, V)` of a local the frame holds (`set(rooms, [hall,
            // kitchen])`, a ground `V` or a native value): the field
            // written with `V` as written (D-38), as an exit arc's action
            // writes it; a prog performs nothing. A value of another type
            // than the local's is not native (`Gen::nat_local_set`).
            let set = match part {
                Ev::VarOp { op, name, arg } if *op == atoms::SET && d.declares_local(*name) => {
                    Some((*name, arg.clone()))
                }
                Ev::Eval(Build::Const(t)) => match self.store.value(*t) {
                    Value::Compound(f, args) if f == atoms::SET && args.len() == 2 => self
                        .store
                        .atom_of(args[0])
                        .filter(|l| d.declares_local(*l))
                        .map(|l| (l, Build::Const(args[1]))),
                    _ => None,
                },
                _ => None,
            };
            // `inc(l, _)` of an int local the frame holds: checked `i64`
            // addition, the field written; an overflow is the machine's
            // `inc` (its error), the situation entered as for `is`.
            // (`inc(l, V)` with `V` not set yet: the same, `V` bound.)
            let inc = match part {
                Ev::VarOpFresh { op, name, dst } => Some((op, name, dst)),
                Ev::VarOp {
                    op,
                    name,
                    arg: Build::Reg(dst),
                } if !regs.contains_key(dst) && fresh(*dst) => Some((op, name, dst)),
                _ => None,
            };
            if let Some((op, name, dst)) = inc {
                if *op == atoms::INC && d.declares_local(*name) {
                    let (l, lty) = d
                        .local_field(*name)
                        .ok_or("its prog's `inc` of a local the frame does not hold")?;
                    if lty != Ty::Int {
                        return Err("its prog's `inc` of a local that is not an int".into());
                    }
                    let (opa, namea) = (self.atom_native(*op)?, self.atom_native(*name)?);
                    let x = format_ident!("prog{}", k);
                    out.push(quote! {
                        let #x: i64 = match #l.checked_add(1) {
                            Some(v) => {
                                *#l = v;
                                v
                            }
                            None => {
                                #hand
                                #(#id_stmts)*
                                cx.enter_counted(&mut count, #cur, #id);
                                return match cx.var_op_fresh(#opa, #namea, None) {
                                    Err(e) => Err(e),
                                    Ok(_) => Err(cx.error(
                                        "`inc` overflowed in native code only",
                                        None,
                                    )),
                                };
                            }
                        };
                    });
                    let dty = d.types[ix].regs[*dst as usize].ty.clone();
                    let r = reg(*dst);
                    match &dty {
                        Ty::Int => {
                            out.push(quote!(let #r = #x;));
                            regs.insert(*dst, (r, dty));
                        }
                        t if held_as_val(t) => {
                            out.push(quote!(let #r = Val::Int(#x);));
                            regs.insert(*dst, (r, dty));
                        }
                        // Read nowhere as a value native code holds.
                        _ => out.push(quote!(let _ = #x;)),
                    }
                    continue;
                }
            }
            if let Some((name, arg)) = set {
                let v = self.nat_value(&arg, regs)?;
                let x = format_ident!("prog{}", k);
                let mut stmts = Vec::new();
                self.nat_local_set(d, name, &x, v, None, &mut stmts, &mut None)?;
                out.extend(stmts);
                continue;
            }
            // `V is E` with `V` not set yet (fresh, or the out_arg's variable).
            let (expr, dst) =
                match part {
                    Ev::IsFresh { expr, dst } => (expr, dst),
                    Ev::Is {
                        lhs: Build::Reg(dst),
                        expr,
                    } if !regs.contains_key(dst) && fresh(*dst) => (expr, dst),
                    _ => return Err(
                        "its prog is not `V is E` of integer arithmetic, `set` or `inc` of a local"
                            .into(),
                    ),
                };
            let ty = d.types[ix].regs[*dst as usize].ty.clone();
            let rty = rust_ty(&ty)?;
            let x = reg(*dst);
            // Float arithmetic (`K is N * 0.5`) as an arc's action does it
            // (`float_expr`): `None` (no number, an overflow, a result not
            // finite) takes the machine's evaluation below.
            let (e, num, native) = if self.float_typed(expr, regs) {
                let native = match &ty {
                    Ty::Float => quote!(v),
                    t if held_as_val(t) => quote!(Val::Float(v)),
                    _ => return Err(format!("its prog's `is` gives a value of type {ty}")),
                };
                (self.nat_float_expr(expr, regs)?, quote!(f64), native)
            } else {
                let native = match &ty {
                    Ty::Int => quote!(v),
                    t if held_as_val(t) => quote!(Val::Int(v)),
                    _ => return Err(format!("its prog's `is` gives a value of type {ty}")),
                };
                (self.nat_int_expr(expr, regs)?, quote!(i64), native)
            };
            let mut ts = Vec::new();
            let mut n = 0;
            let t = self.nat_build_term(expr, regs, &mut ts, &mut n)?;
            out.push(quote! {
                let prog_v: Option<#num> = #e;
                let #x: #rty = match prog_v {
                    Some(v) => #native,
                    None => {
                        // Not ints, or an overflow: the term code's evaluation.
                        #hand
                        #(#id_stmts)*
                        cx.enter_counted(&mut count, #cur, #id);
                        #(#ts)*
                        let v = cx.is(None, #t, None)?;
                        let v = cx.store_ref().deref(v);
                        match cx.to_native::<#rty>(v) {
                            Some(v) => v,
                            None => {
                                return Err(cx.error(
                                    "`is` in a prog gave a value native code cannot hold",
                                    None,
                                ))
                            }
                        }
                    }
                };
            });
            regs.insert(*dst, (x, ty));
        }
        Ok(quote!(#(#out)*))
    }

    /// An integer expression (`+`, `-`, `*`, unary `-` over registers
    /// holding ints and integer constants) as a Rust expression of an
    /// `Option<i64>`: `None` when an operand is not an int or an operation
    /// overflows.
    pub(super) fn nat_int_expr(&self, b: &Build, regs: &Regs) -> N<TokenStream> {
        let some = quote!(Some);
        Ok(match b {
            Build::Reg(r) => {
                let (x, ty) = regs
                    .get(r)
                    .ok_or_else(|| format!("register r{r} is read before it is set"))?;
                match ty {
                    Ty::Int => quote!(#some(#x)),
                    t if held_as_val(t) => quote!(#x.int()),
                    _ => return Err(format!("an arithmetic operand of type {ty}")),
                }
            }
            Build::Const(t) => match self.store.value(*t) {
                Value::Int(i) => {
                    let i = Literal::i64_suffixed(i);
                    quote!(#some(#i))
                }
                _ => return Err("an arithmetic operand that is not an int".into()),
            },
            Build::Compound(op, args) => {
                let args = args
                    .iter()
                    .map(|a| self.nat_int_expr(a, regs))
                    .collect::<N<Vec<_>>>()?;
                match (op.as_str(), args.as_slice()) {
                    ("+", [a, b]) => quote!(#a.and_then(|a| #b.and_then(|b| a.checked_add(b)))),
                    ("-", [a, b]) => quote!(#a.and_then(|a| #b.and_then(|b| a.checked_sub(b)))),
                    ("*", [a, b]) => quote!(#a.and_then(|a| #b.and_then(|b| a.checked_mul(b)))),
                    ("-", [a]) => quote!(#a.and_then(|a| a.checked_neg())),
                    _ => return Err(format!("arithmetic `{}` is not native yet", op.as_str())),
                }
            }
        })
    }

    /// The code of arc `arc` of situation `ix` once chosen (its action,
    /// the values a boundary bound converted, its next situation), with
    /// `arc_at` its index.
    ///
    /// When the history is kept or observed (`run.records`) the arc's
    /// entry is recorded as the term code records it (after the action,
    /// the next situation and the out_arg; `exp`: the expectation's term
    /// when the machine chose the arc, else built here), the situation's
    /// id entered first: on the next `Nat`'s id where native code goes on,
    /// on the value handed over where it hands over ([`Dm::rec`]).
    fn nat_arc(
        &self,
        d: &Dm,
        ix: usize,
        arc: &ArcPlan,
        regs: &Regs,
        exp: Option<Ident>,
    ) -> N<TokenStream> {
        let plan = d.plans[ix];
        let st = &d.types[ix];
        let cur = Literal::u32_unsuffixed(ix as u32);
        let mut regs = regs.clone();
        let mut stmts = Vec::new();
        let atom = match &arc.action {
            Action::One(Ev::Built(Build::Const(t))) => self.store.atom_of(*t),
            _ => None,
        };
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store()))?;
        let hand = &d.hand;
        let enter = quote! {
            #hand
            #(#id_stmts)*
            cx.enter_counted(&mut count, #cur, #id);
        };
        // An action of `inc`/`get` of the frame's locals, constants and
        // values (`[inc(n, N)]`): done natively, as an exit arc's is; the
        // machine sees only what is performed.
        let arc_ix = match &plan.kind {
            KindPlan::Perceptual(arcs) => arcs.arcs.iter().position(|a| std::ptr::eq(a, arc)),
            _ => None,
        };
        // Only when nothing is recorded: recorded, the arc takes the
        // general way below (the machine's `inc`/`get`, the entry made).
        let mut fast = None;
        let mut rec_fast = None;
        // An effector's compound action (`note(S)`): the general way
        // below performs it without entering the machine.
        // A constant compound among a list's items too (`[say('Hi.'),
        // say(N)]`): the general way, as before exit arcs performed them.
        let effector = match &arc.action {
            Action::One(e) => {
                self.const_compound(e) || call::pure_compound(e).is_some_and(|f| f != atoms::DOT)
            }
            Action::List { items, .. } => items.iter().any(|e| self.const_compound(e)),
        };
        if let (None, Some(k), false) = (atom, arc_ix, effector) {
            let mut nregs = regs.clone();
            if let Ok(act) = self.nat_exit_action(d, ix, k, arc, &mut nregs) {
                let name = self.atom_native(plan.id.0)?;
                let next =
                    self.nat_next_out(d, ix, &arc.next, pipe::arc_out(arc), &nregs, &name)?;
                fast = Some(quote! { #act count += 1; #next });
                // Recorded above the machine's frames (a level of its
                // own): the same, the entry made of the values.
                rec_fast = self.nat_arc_rec_fast(d, ix, arc, &act, exp.as_ref(), &regs, &nregs);
            }
        }
        // A fresh variable the action binds (a boundary's value) and the
        // next situation reads is converted with the checked conversion;
        // when that fails, or when a local the machine's calls changed no
        // longer fits the frame, the rest of the arc runs on terms (live
        // native values as terms): the next situation as written, evaluated
        // whole as `Machine::conclude` does, or the term code's steps.
        let reloads = atom.is_none() && !d.locals.is_empty();
        // An action of effectors built of values (`navigate(P, R)`, a
        // list of `say`s): performed without the hand-over (`effect`).
        let effect = if self.nat_effect_ok(d, &arc.action, atom, &regs) {
            self.nat_effect(d, ix, &arc.action, atom, &regs)
                .ok()
                .flatten()
        } else {
            None
        };
        // After an `empty` action (performed without handing the frames
        // below over, `Cx::empty_fails`) the native frames below
        // are handed over first: else the machine would be entered in the
        // caller's frame (`ngen12`'s `d_compare_fn`); so after an action
        // `effect` performs. Any other action handed over where it was
        // performed.
        let enter_id = if atom == Some(atoms::EMPTY) || effect.is_some() {
            quote!(#hand #(#id_stmts)* cx.enter_with_id(#cur, #id);)
        } else {
            quote!(#(#id_stmts)* cx.enter_with_id(#cur, #id);)
        };
        let conv = self.nat_bound_at_boundary(
            st,
            &arc.next,
            pipe::arc_out(arc),
            &regs,
            reloads,
            &enter_id,
        )?;
        // The expectation's term for the history, built only when recorded.
        let mut exp_leaf = true;
        let rec_exp = match exp {
            Some(e) => quote!(#e),
            None => {
                let mut ts = Vec::new();
                let mut n = 0;
                let t = self
                    .nat_ev_term(&arc.expectation, &regs, &mut ts, &mut n)
                    .map_err(|e| format!("its expectation: {e}"))?;
                if ts.is_empty() {
                    // A leaf: nothing built.
                    quote!(#t)
                } else {
                    exp_leaf = false;
                    quote!(if run.records { #(#ts)* #t } else { Term::NIL })
                }
            }
        };
        // A constant action's term beside an expectation that is a leaf
        // (both built in any case).
        let act_paired = atom.is_some() && exp_leaf;
        match atom {
            Some(action) if act_paired => {
                let act = self.atom_term(action)?;
                stmts.push(quote!(let (exp, act) = (#rec_exp, #act);));
            }
            _ => stmts.push(quote!(let exp: Term = #rec_exp;)),
        }
        match atom {
            Some(action) => {
                let act = self.atom_term(action)?;
                // Entered first, performed as an entered situation's
                // action (`effect`, `Cx::nat_perform`).
                let call = self.nat_perform_call(
                    &quote!(arc_at),
                    &arc.action,
                    atom,
                    &regs,
                    &mut vec![],
                    &mut 0,
                )?;
                let perform = quote! {
                    #enter
                    #call
                };
                // `empty` performed where the actions do not ignore it,
                // handed to the effector without handing the native frames
                // over (`Cx::empty_fails`); handed over only where the
                // effector fails, for the error the entry reports
                // (`Cx::enter_performed`).
                let id_arg = atom_arg(&id);
                let enter = if hand.is_empty() {
                    quote! {
                        let performs = !run.quiet_empty || stack.is_empty();
                        cx.enter_empty(&mut count, #cur, #id_arg, performs, arc_at)?;
                    }
                } else {
                    quote!(cx.enter_performed(&mut count, #cur, #id_arg, arc_at)?;)
                };
                // One call where it fits (after `empty` performed, a DM's
                // own hand-over where it fails, which writes its locals
                // back: then none is below).
                let one = empty_call(&id_stmts, &id, &cur, &quote!(arc_ix), !runtime_hand(hand))
                    .filter(|_| action == atoms::EMPTY && !hand.is_empty());
                let own_hand_if = if runtime_hand(hand) {
                    quote!()
                } else {
                    quote!(if cx.empty_fails(run) { #hand })
                };
                // The test in the call (`TypedRun::empty`) with the
                // runtime's hand-over.
                let gated = gated_empty_call(&id_stmts, &id, &cur, &quote!(arc_ix), "empty")
                    .filter(|_| action == atoms::EMPTY && runtime_hand(hand));
                stmts.push(if let Some(call) = gated {
                    call
                } else if let Some(call) = one {
                    quote! {
                        if run.records || !run.quiet_empty {
                            #own_hand_if
                            #call
                        }
                    }
                } else if action == atoms::EMPTY && !hand.is_empty() {
                    // `empty` performed where the actions do not ignore it;
                    // the situation entered (its id built) where the run
                    // records or the effector refused it, and handed over
                    // first only then.
                    quote! {
                        if cx.empty_fails(run) || run.records {
                            if cx.empty_refused() { #hand }
                            #(#id_stmts)*
                            #enter
                        }
                    }
                } else if action == atoms::EMPTY {
                    // Recorded: the situation entered (its id in the entry);
                    // above the machine's frames (a level of its own).
                    quote! {
                        if run.records || !run.quiet_empty {
                            #(#id_stmts)*
                            #enter
                        }
                    }
                } else if let Some(effect) = &effect {
                    effect.clone()
                } else {
                    perform
                });
                if !act_paired {
                    stmts.push(quote!(let act = #act;));
                }
            }
            None => {
                // An effector's action (`say([.., Name])`): its term
                // built from native values where it is performed.
                let why = |e: String| format!("its action {}: {e}", self.action_shape(&arc.action));
                let mut ts = Vec::new();
                let mut n = 0;
                let perform = match &arc.action {
                    // Built of values (`note(S)`, `navigate(P, R)`, a list
                    // of `say`s): performed without handing the frames over
                    // or entering the situation where the run does not
                    // record (`effect`, `Cx::nat_perform`).
                    _ if effect.is_some() => {
                        stmts.extend(effect.clone());
                        None
                    }
                    // Else entered first, then performed as an entered
                    // situation's action (`effect`, `Cx::nat_perform`):
                    // the one call of both.
                    _ => Some(
                        self.nat_perform_call(
                            &quote!(arc_at),
                            &arc.action,
                            None,
                            &regs,
                            &mut ts,
                            &mut n,
                        )
                        .map_err(why)?,
                    ),
                };
                if let Some(perform) = perform {
                    stmts.push(quote! {
                        #enter
                        #(#ts)*
                        #perform
                    });
                }
            }
        }
        // Recorded, the entry counts the transition. With nothing converted
        // after the action, counted at the arc's end instead (below, where
        // the next situation cannot leave the visit).
        let tally = quote!(run.tally(&mut count););
        let tally_apart = conv.is_some();
        if tally_apart {
            stmts.push(tally.clone());
        }
        // What the machine's calls changed of the locals, read again, and
        // the values bound at the boundary, converted: all checked in one
        // `let .. else`, the fallback written once.
        if let Some((fallback, conv)) = conv {
            let occ = &d.occ[ix];
            let mut checks = Vec::new();
            if atom.is_none() {
                checks = self.nat_local_checks(d)?;
            }
            for (r, ty) in conv {
                let (x, _) = regs[&r].clone();
                // A fresh variable a constant action leaves unbound and
                // only a condition's term reads (`same_place(_, _)` in
                // `apply(same_place(_, _), [P, T]) == yes`): never converts,
                // so passed as the unbound term it is, the arc kept native
                // (else every visit went to the term code, converting the
                // id's list to a term: quadratic, `ngen12b`).
                if atom.is_some() && only_in_conditions(&arc.next, r) && !out_mentions(arc, r) {
                    regs.insert(r, (x, Ty::Term));
                    continue;
                }
                // A fresh variable met only once in the plan, in the next
                // situation (the `_` of `C < get(limit, _)`): nothing before
                // binds it, so it is unbound here and converting it could
                // only fail; the evaluation there binds it
                // (`Gen::nat_var_get`).
                // The same in an out_arg the evaluator computes whole (the
                // `_`s of `apply(when(_, _, _), [..])`): a variable of the
                // term it is given, unbound as on the term path (D-18's
                // "pipe not set for a variable" is about the value,
                // `Cx::out_value`).
                let in_eval_out = matches!(arc.out_arg, Some(Ev::Eval(_)));
                if occ.get(r as usize) == Some(&1) && (in_eval_out || !out_mentions(arc, r)) {
                    regs.insert(r, (x, Ty::Term));
                    continue;
                }
                let rr = reg(r);
                let rty = rust_ty(&ty)?;
                checks.push((rr.clone(), quote!(cx.to_native::<#rty>(#x)), quote!()));
                regs.insert(r, (rr, ty));
            }
            stmts.push(checked(checks, &fallback));
        }
        let name = self.atom_native(plan.id.0)?;
        *d.rec.borrow_mut() = rec_entry();
        let next = self.nat_next_out(d, ix, &arc.next, pipe::arc_out(arc), &regs, &name);
        *d.rec.borrow_mut() = quote!();
        let next = next?;
        // One expression (most: a variant, a `'sel` block) is the
        // initializer itself, no block around it.
        let init_of = |next: TokenStream| {
            if syn::parse2::<syn::Expr>(next.clone()).is_ok() {
                next
            } else {
                quote!({ #next })
            }
        };
        let general = if always_returns(&next) {
            // Handed over (recorded there): no next variant.
            let tally = if tally_apart { quote!() } else { tally };
            quote! {
                #(#stmts)*
                #tally
                #next
            }
        } else if !tally_apart && !leaves(&next) {
            // The next situation neither returns nor fails: the arc's end
            // counts it or records its entry (`TypedRun::end_at`).
            let init = init_of(next);
            // A variant without fields is named in the call itself.
            let bare = matches!(init.clone().into_iter().last(),
                Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Brace && g.stream().is_empty());
            if bare {
                quote! {
                    #(#stmts)*
                    run.end_at(p, cx, &mut count, exp, act, #init)
                }
            } else {
                quote! {
                    #(#stmts)*
                    let next_at: Nat = #init;
                    run.end_at(p, cx, &mut count, exp, act, next_at)
                }
            }
        } else {
            let tally = if tally_apart { quote!() } else { tally };
            stmts.push(tally);
            let init = init_of(next);
            quote! {
                #(#stmts)*
                let next_at: Nat = #init;
                run.record_next(cx, exp, act, |s| next_at.id_term(p, s));
                next_at
            }
        };
        // A user function or a Prolog condition called at its boundary,
        // the frames below left native ([`boundary`]).
        let general = boundary::at_boundary(hand, general);
        Ok(match (fast, rec_fast) {
            (Some(fast), Some(rec)) => quote! {
                if !run.records { #fast } else if !stack.is_empty() { #rec } else { #general }
            },
            (Some(fast), None) => quote! {
                if !run.records { #fast } else { #general }
            },
            _ => general,
        })
    }

    /// The recorded way of arc `arc` of situation `ix` whose action
    /// native code runs (`act`: its values `act<n>`), for a frame above the
    /// machine's: the entry's expectation and action as terms of the
    /// values, the situation's id entered, the next situation computed
    /// (recording where it hands over) and its entry recorded. `None` when
    /// a term of them cannot be built.
    #[allow(clippy::too_many_arguments)]
    fn nat_arc_rec_fast(
        &self,
        d: &Dm,
        ix: usize,
        arc: &ArcPlan,
        act: &TokenStream,
        exp: Option<&Ident>,
        regs: &Regs,
        nregs: &Regs,
    ) -> Option<TokenStream> {
        let mut ts = Vec::new();
        let mut n = 0;
        let exp = match exp {
            Some(e) => quote!(#e),
            None => self
                .nat_ev_term(&arc.expectation, regs, &mut ts, &mut n)
                .ok()?,
        };
        let (items, list) = match &arc.action {
            Action::List { items, .. } => (items.len(), true),
            Action::One(_) => (1, false),
        };
        let acts: Vec<Ident> = (0..items).map(|k| format_ident!("act{}", k)).collect();
        let act_t = if list {
            quote! {
                let act_items = [#(cx.term(&#acts)),*];
                let act = cx.store().list(&act_items);
            }
        } else {
            quote!(let act = cx.term(&act0);)
        };
        let (id_stmts, id) = self.nat_id_term(d, ix, quote!(cx.store())).ok()?;
        let cur = Literal::u32_unsuffixed(ix as u32);
        let name = self.atom_native(d.plans[ix].id.0).ok()?;
        *d.rec.borrow_mut() = rec_entry();
        let next = self.nat_next_out(d, ix, &arc.next, pipe::arc_out(arc), nregs, &name);
        *d.rec.borrow_mut() = quote!();
        let next = next.ok()?;
        Some(quote! {
            #act
            #(#ts)*
            let exp: Term = #exp;
            #act_t
            #(#id_stmts)*
            cx.enter_counted(&mut count, #cur, #id);
            let next_at: Nat = { #next };
            cx.record_next(exp, act, |s| next_at.id_term(p, s));
            next_at
        })
    }

    /// The frame's locals read again from the machine's frame after its
    /// calls (`get`/`set`/`inc`, the evaluator) may have changed them, as
    /// checks for [`checked`] (one that no longer converts: the fallback,
    /// the term code's way on).
    fn nat_local_checks(&self, d: &Dm) -> N<Vec<Check>> {
        let mut out = Vec::new();
        for (i, (name, ty)) in d.locals.iter().enumerate() {
            let l = format_ident!("l{}", i);
            let v = format_ident!("new_l{}", i);
            let a = self.atom_native(*name)?;
            let ty = rust_ty(ty)?;
            out.push((v.clone(), quote!(cx.local_as::<#ty>(#a)), quote!(*#l = #v;)));
        }
        Ok(out)
    }

    /// A final's hand-back through the frame's output slots, when its
    /// `diag_mod` `b` is the DM's head with every output computed natively
    /// (`slots`, [`Gen::nat_output_slots`]'s) and every other
    /// argument the parameter itself (`call::slot_final`): the condition
    /// (each output parameter `Ground::OUT`, so the caller made no term
    /// for it) and the statements setting the slots (`*out2 = Some(..);`,
    /// each slot's expression).
    fn nat_slot_below(
        &self,
        d: &Dm,
        ix: usize,
        b: &Build,
        slots: &[Option<(Ident, TokenStream, TokenStream)>],
    ) -> Option<(TokenStream, TokenStream, TokenStream)> {
        let Build::Compound(name, args) = b else {
            return None;
        };
        if *name != d.dm.name || args.len() != d.dm.arity || slots.len() != args.len() {
            return None;
        }
        let plan = &d.plans[ix];
        let mut conds = Vec::new();
        let mut sets = Vec::new();
        let mut outs = Vec::new();
        for (i, a) in args.iter().enumerate() {
            if d.outputs.get(i).is_some_and(Option::is_some) {
                let (_, _, e) = slots[i].as_ref()?;
                if d.params[i] != Ty::Term {
                    return None;
                }
                let (p, out) = (format_ident!("p{}", i), format_ident!("out{}", i));
                conds.push(quote!(#p.is_out()));
                sets.push(quote!(*#out = Some(#e);));
                let il = Literal::usize_unsuffixed(i);
                // The slot itself (`&mut Option<T>`, a `&dyn OutSlot`):
                // `Cx::close_level` makes it a term.
                outs.push(quote!((#il, #out)));
            } else if !matches!(a, Build::Reg(r) if plan.inits.iter().any(|(x, init)| x == r && matches!(init, Init::HeadArg(p) if *p == i)))
            {
                return None;
            }
        }
        if conds.is_empty() {
            return None;
        }
        Some((
            quote!(#(#conds)&&*),
            quote!(#(#sets)*),
            quote!([#(#outs),*]),
        ))
    }

    /// A final's output slots: for each output parameter of the DM
    /// (`DmTypes::outputs`: unbound when called, bound by every final's
    /// `diag_mod`) whose output type is native, the value this final binds
    /// it to as a Rust expression of that type (its local's name `o2`, the
    /// type, the expression: `let o2: Atom = ..;` where the `diag_mod` term
    /// takes it, `Native::to_term`, the one conversion, at the boundary;
    /// `*out2 = Some(..);` where a native caller's slot takes it, module
    /// `call`), computed from the visit's native values.
    /// An output this final cannot compute so (a value of another shape, a
    /// fresh variable) is built as before and marks the parameter not held
    /// (`Dm::outs`).
    #[allow(clippy::type_complexity)]
    fn nat_output_slots(
        &self,
        d: &Dm,
        b: &Build,
        regs: &Regs,
    ) -> Vec<Option<(Ident, TokenStream, TokenStream)>> {
        let args: &[Build] = match b {
            Build::Compound(name, args) if *name == d.dm.name && args.len() == d.dm.arity => args,
            _ => {
                d.outs.borrow_mut().iter_mut().for_each(|o| *o = false);
                return Vec::new();
            }
        };
        let mut slots = vec![None; args.len()];
        let mut outs = d.outs.borrow_mut();
        for (i, a) in args.iter().enumerate() {
            let Some(Some(ty)) = d.outputs.get(i) else {
                continue;
            };
            let slot = self.nat_value(a, regs).and_then(|v| {
                let e = coerce(&v, ty)?;
                Ok((e, rust_ty(ty)?))
            });
            match slot {
                Ok((e, rt)) => slots[i] = Some((format_ident!("o{}", i), rt, e)),
                Err(_) => outs[i] = false,
            }
        }
        slots
    }

    /// The term of `b` built from native values (a boundary: an effector's
    /// action, `diag_mod`): statements pushed to `ts`, the term's
    /// expression returned.
    pub(super) fn nat_build_term(
        &self,
        b: &Build,
        regs: &Regs,
        ts: &mut Vec<TokenStream>,
        n: &mut usize,
    ) -> N<TokenStream> {
        let x = format_ident!("b{}", *n);
        *n += 1;
        let e = match b {
            // A fresh variable, made where the action's terms are built.
            Build::Reg(r) if regs.get(r).is_some_and(|(v, _)| is_fresh(v)) => {
                let (v, _) = &regs[r];
                return Ok(quote!(#v));
            }
            Build::Reg(r) => {
                let (v, _) = regs.get(r).ok_or(format!("register r{r} is read unset"))?;
                quote!(cx.term(&#v))
            }
            Build::Const(t) => return self.nat_const_term(*t, ts, n),
            Build::Compound(f, args) => {
                // Two compounds or more: one `cx.fill` where a pattern
                // fits (module `fill`), its local the next one.
                let mut m = *n - 1;
                if let Some(x) = self.nat_fill_build(b, regs, ts, &mut m)? {
                    *n = m;
                    return Ok(x);
                }
                let args = args
                    .iter()
                    .map(|a| self.nat_build_term(a, regs, ts, n))
                    .collect::<N<Vec<_>>>()?;
                let f = self.functor_native(*f)?;
                quote!(cx.build(#f, &[#(#args),*]))
            }
        };
        ts.push(quote!(let #x = #e;));
        Ok(quote!(#x))
    }

    /// The term of `e` evaluated, when evaluating builds it from native
    /// values (they evaluate to themselves: native values are inert).
    fn nat_ev_term(
        &self,
        e: &Ev,
        regs: &Regs,
        ts: &mut Vec<TokenStream>,
        n: &mut usize,
    ) -> N<TokenStream> {
        match e {
            Ev::Value(r) => self.nat_build_term(&Build::Reg(*r), regs, ts, n),
            Ev::Built(b) => self.nat_build_term(b, regs, ts, n),
            Ev::Compound(f, args) => {
                if let Some(x) = self.nat_fill_ev(e, regs, ts, n)? {
                    return Ok(x);
                }
                let args = args
                    .iter()
                    .map(|a| self.nat_ev_term(a, regs, ts, n))
                    .collect::<N<Vec<_>>>()?;
                let f = self.functor_native(*f)?;
                let x = format_ident!("b{}", *n);
                *n += 1;
                ts.push(quote!(let #x = cx.build(#f, &[#(#args),*]);));
                Ok(quote!(#x))
            }
            // A user function, the KB, `assign`...: the evaluator, on the
            // term built from native values (a boundary); its value is a
            // term, performed as it is.
            Ev::Eval(b) => {
                let t = self.nat_build_term(b, regs, ts, n)?;
                let x = format_ident!("b{}", *n);
                *n += 1;
                ts.push(quote!(let #x = cx.eval(#t, arc_at)?;));
                Ok(quote!(#x))
            }
            // `get`/`set`/`inc` of a local or global, `is`: the machine's
            // own calls, on terms built from native values; a variable
            // they bind is a fresh variable's local (a term), read
            // natively only after a checked conversion.
            Ev::VarOp { op, name, arg } => {
                let t = self.nat_build_term(arg, regs, ts, n)?;
                let (op, name) = (self.atom_native(*op)?, self.atom_native(*name)?);
                let x = format_ident!("b{}", *n);
                *n += 1;
                ts.push(quote!(let #x = cx.var_op(#op, #name, #t, arc_at)?;));
                Ok(quote!(#x))
            }
            Ev::VarOpFresh { op, name, dst } => {
                let x = match regs.get(dst) {
                    Some((x, _)) if is_fresh(x) => x.clone(),
                    _ => return Err(format!("register r{dst} is set twice")),
                };
                let (op, name) = (self.atom_native(*op)?, self.atom_native(*name)?);
                ts.push(quote!(let #x = cx.var_op_fresh(#op, #name, arc_at)?;));
                Ok(quote!(#x))
            }
            Ev::IsFresh { expr, dst } => {
                let x = match regs.get(dst) {
                    Some((x, _)) if is_fresh(x) => x.clone(),
                    _ => return Err(format!("register r{dst} is set twice")),
                };
                let t = self.nat_build_term(expr, regs, ts, n)?;
                ts.push(quote!(let #x = cx.is(None, #t, arc_at)?;));
                Ok(quote!(#x))
            }
            // `V = E` (D-30): `V` is `E`'s term as built.
            Ev::BindFresh { expr, dst } => {
                let x = match regs.get(dst) {
                    Some((x, _)) if is_fresh(x) => x.clone(),
                    _ => return Err(format!("register r{dst} is set twice")),
                };
                let t = self.nat_build_term(expr, regs, ts, n)?;
                ts.push(quote!(let #x = #t;));
                Ok(quote!(#x))
            }
            Ev::Is { lhs, expr } => {
                let e = self.nat_build_term(expr, regs, ts, n)?;
                let l = self.nat_build_term(lhs, regs, ts, n)?;
                let x = format_ident!("b{}", *n);
                *n += 1;
                ts.push(quote!(let #x = cx.is(Some(#l), #e, arc_at)?;));
                Ok(quote!(#x))
            }
            // `(C -> A ; otherwise -> B)` as a value: `C` decided here
            // (`==`/`\==`, [`Gen::nat_cond_term`]), then only the branch
            // taken is built and evaluated, in the evaluator's order.
            Ev::If(c, a, b) => {
                let mut binds = Vec::new();
                ev_binds(a, &mut binds);
                ev_binds(b, &mut binds);
                if !binds.is_empty() {
                    return Err("a conditional expression binds a variable".into());
                }
                let c = self.nat_cond_term(c, regs, ts, n)?;
                let (mut ta, mut tb) = (Vec::new(), Vec::new());
                let ea = self.nat_ev_term(a, regs, &mut ta, n)?;
                let eb = self.nat_ev_term(b, regs, &mut tb, n)?;
                let x = format_ident!("b{}", *n);
                *n += 1;
                ts.push(quote!(let #x = if #c { #(#ta)* #ea } else { #(#tb)* #eb };));
                Ok(quote!(#x))
            }
            // `when/3`: the condition, then both branches, in this order.
            Ev::Pick(c, a, b) => {
                let c = self.nat_cond_term(c, regs, ts, n)?;
                let ea = self.nat_ev_term(a, regs, ts, n)?;
                let eb = self.nat_ev_term(b, regs, ts, n)?;
                let x = format_ident!("b{}", *n);
                *n += 1;
                ts.push(quote!(let #x = if #c { #ea } else { #eb };));
                Ok(quote!(#x))
            }
        }
    }

    /// The condition of a conditional expression where an action or a
    /// next situation is evaluated (the machine entered, `arc_at` in
    /// scope): a `bool` expression, statements pushed to `ts`. `==`/`\==`
    /// of native values compare in Rust ([`identical`]); any other
    /// condition is decided as the term code decides it
    /// (`codegen::step`): an arithmetic comparison on its sides evaluated
    /// (`Cx::arith_condition`), anything else by `Cx::condition` on the
    /// term built from native values (`member(P, [O, unknown])`,
    /// `apply(f(_), [X]) == yes`; a fresh variable an earlier element bound
    /// stands for its value).
    fn nat_cond_term(
        &self,
        c: &Cond,
        regs: &Regs,
        ts: &mut Vec<TokenStream>,
        n: &mut usize,
    ) -> N<TokenStream> {
        let x = format_ident!("b{}", *n);
        *n += 1;
        match c {
            Cond::Other(b) => {
                // A type test of a native value (`type_test`).
                if self.is_type_test(b) {
                    if let Ok(t) = self.nat_type_test(b, regs) {
                        return Ok(t);
                    }
                }
                if let Build::Compound(op, args) = b {
                    if args.len() == 2 && matches!(op.as_str(), "==" | "\\==") {
                        let l = self.nat_value(&args[0], regs);
                        let r = self.nat_value(&args[1], regs);
                        if let Some(same) = l.ok().zip(r.ok()).and_then(|(l, r)| identical(&l, &r))
                        {
                            return Ok(if op.as_str() == "==" {
                                same
                            } else {
                                quote!((!#same))
                            });
                        }
                    }
                }
                let t = self.nat_build_term(b, regs, ts, n)?;
                ts.push(quote!(let #x = cx.condition(#t, arc_at)?;));
            }
            Cond::Arith(op, l, r) => {
                let l = self.nat_ev_term(l, regs, ts, n)?;
                let r = self.nat_ev_term(r, regs, ts, n)?;
                let op = format_ident!("{}", format!("{op:?}"));
                ts.push(quote! {
                    let #x = cx.arith_condition(::sitlog_runtime::ArithCmp::#op, #l, #r, arc_at)?;
                });
            }
            // `when/3`'s comparison: native values are their own values.
            Cond::Cmp(op, l, r) => {
                let l = self.nat_build_term(l, regs, ts, n)?;
                let r = self.nat_build_term(r, regs, ts, n)?;
                let op = format_ident!("{}", format!("{op:?}"));
                ts.push(quote! {
                    let #x = cx.compare_value(::sitlog_runtime::ArithCmp::#op, [#l, #r], [#l, #r], arc_at)?;
                });
            }
            // A conjunction or disjunction: the machine's, whole.
            Cond::And(..) | Cond::Or(..) => {
                let b = c.written().ok_or("a conjunction's operand")?;
                let t = self.nat_build_term(&b, regs, ts, n)?;
                ts.push(quote!(let #x = cx.condition(#t, arc_at)?;));
            }
        }
        Ok(quote!(#x))
    }

    /// A constant term (atoms, numbers, compounds of them), built.
    fn nat_const_term(&self, t: Term, ts: &mut Vec<TokenStream>, n: &mut usize) -> N<TokenStream> {
        match self.store.value(t) {
            Value::Atom(a) if a == atoms::NIL => Ok(quote!(Term::NIL)),
            Value::Atom(a) if a == atoms::EMPTY => Ok(quote!(Term::EMPTY)),
            Value::Atom(a) => {
                let a = self.functor_native(a)?;
                Ok(quote!(Term::atom(#a)))
            }
            Value::Int(i) => {
                let i = Literal::i64_suffixed(i);
                Ok(quote!(Term::int(#i)))
            }
            Value::Float(f) if f.is_finite() => {
                let f = Literal::f64_suffixed(f);
                Ok(quote!(Term::float(#f)))
            }
            // A ground compound the program built once (the term code's
            // `k[N]`).
            Value::Compound(..) if self.const_ix.contains_key(&self.store.writeq(t)) => {
                let ix = Self::const_index(self.const_ix[&self.store.writeq(t)]);
                Ok(quote!(p.k #ix))
            }
            Value::Compound(f, args) => {
                let args = args.to_vec();
                let args = args
                    .into_iter()
                    .map(|a| self.nat_const_term(a, ts, n))
                    .collect::<N<Vec<_>>>()?;
                let f = self.functor_native(f)?;
                let x = format_ident!("b{}", *n);
                *n += 1;
                ts.push(quote!(let #x = cx.build(#f, &[#(#args),*]);));
                Ok(quote!(#x))
            }
            _ => Err(format!(
                "constant `{}` is not native yet",
                self.store.writeq(t)
            )),
        }
    }

    /// An atom as a functor or constant in generated code.
    fn functor_native(&self, a: Atom) -> N<TokenStream> {
        if a == atoms::DOT {
            Ok(quote!(atoms::DOT))
        } else {
            self.atom_native(a)
        }
    }

    /// The fresh variables an action bound (made as terms for it) that
    /// `next` or the arc's out_arg `out` reads, with their types, and the
    /// code that runs the rest of the arc on terms: the next situation (as
    /// written, evaluated whole as `Machine::conclude` does, or by the term
    /// code's steps), then the out_arg (evaluated, `Cx::out_value`, before the entry is
    /// recorded and the transition counted, as `step::arc_code` orders
    /// them) (`None`: neither reads one and `always` is false).
    #[allow(clippy::type_complexity, clippy::too_many_arguments)]
    fn nat_bound_at_boundary(
        &self,
        st: &SitTypes,
        next: &Next,
        out: Option<&Ev>,
        regs: &Regs,
        always: bool,
        enter: &TokenStream,
    ) -> N<Option<(TokenStream, Vec<(Reg, Ty)>)>> {
        let at = quote!(arc_at);
        let out_b = out;
        let mut b = super::step::Body::new();
        let v = self.next_code(next, &at, &mut b);
        let out = out.map(|o| {
            let o = self.ev_code(o, &at, &mut b);
            quote!(cx.out_value(#o);)
        });
        let stmts = b.stmts;
        let body = quote!(#(#stmts)* #v #out);
        let used = super::step::registers(&body);
        let conv: Vec<(Reg, Ty)> = used
            .iter()
            .filter(|r| regs.get(r).is_some_and(|(x, _)| is_fresh(x)))
            .map(|&r| (r, st.regs[r as usize].ty.clone()))
            .collect();
        if conv.is_empty() && !always {
            return Ok(None);
        }
        // The next situation as written (an evaluated compound): filled from
        // its pattern with the registers' values and evaluated whole, as the
        // machine evaluates an arc's next situation
        // (`Machine::conclude`); the term code's steps compute the same value
        // part by part (the MIR's `Ev` says what `eval` does with each part).
        let written = match next {
            Next::Eval(e) => as_written(e),
            _ => None,
        };
        let mut filled = Vec::new();
        let filled_x = match &written {
            Some(w) => match self.nat_fill_build(w, regs, &mut filled, &mut 0)? {
                Some(x) => Some(x),
                // One compound: built of its parts (`Cx::build_of`).
                None => self.nat_build_of_parts(w, regs, &mut filled)?,
            },
            None => None,
        };
        let mut eval_go = None;
        let (stmts, v, used, out, k_of) = match filled_x {
            Some(x) if out_b.is_none() => {
                // Evaluated by `TypedRun::go_eval`.
                eval_go = Some(x);
                (filled, quote!(), BTreeSet::new(), None, quote!())
            }
            Some(x) => {
                let mut b = super::step::Body::new();
                let out = out_b.map(|o| {
                    let o = self.ev_code(o, &at, &mut b);
                    quote!(cx.out_value(#o);)
                });
                let mut stmts = filled;
                stmts.push(quote!(let t = cx.eval(#x, #at)?;));
                let rest = b.stmts;
                let rest = quote!(#(#rest)*);
                let used = super::step::registers(&quote!(#rest #out));
                let k_of = quote!(#rest #out);
                stmts.push(rest);
                (stmts, quote!((t, None)), used, out, k_of)
            }
            None => (stmts, v, used, out, body),
        };
        // What the next situation and the out_arg bind (`t(inc(n, _))`):
        // set by the term code's steps.
        let mut binds = Vec::new();
        next_binds(next, &mut binds);
        if let Some(o) = out_b {
            ev_binds(o, &mut binds);
        }
        let mut lets = Vec::new();
        for r in &used {
            let rr = reg(*r);
            match regs.get(r) {
                Some((x, _)) if is_fresh(x) => lets.push(quote!(let #rr: Term = #x;)),
                Some((x, _)) => lets.push(quote! {
                    let #rr: Term = cx.term(&#x);
                }),
                None if binds.contains(r) => lets.push(quote!(let mut #rr = Term::NIL;)),
                None => return Err(format!("register r{r} is read unset")),
            }
        }
        // `a` is `nat_step`'s.
        let k = Self::uses(&k_of).1.then(|| quote!(let k = &p.k;));
        // The arc's transition (counted in `count` when nothing is
        // recorded) counts once its next situation is computed, as on the
        // term path: an error evaluating it leaves it out. The machine is
        // in the situation then (an empty action performed nothing).
        // The next situation computed before the out_arg.
        let go = match (out, eval_go) {
            (None, Some(x)) => quote!(return run.go_eval(cx, this, exp, act, #x, #at);),
            (None, None) => quote!(return run.go(cx, this, exp, act, #v, #at);),
            (Some(out), _) => quote! {
                let next = #v;
                #out
                return run.go(cx, this, exp, act, next, #at);
            },
        };
        let fallback = quote! {{
            let this = run.count_but_this(cx, count);
            #enter
            #k
            #(#lets)*
            #(#stmts)*
            #go
        }};
        Ok(Some((fallback, conv)))
    }

    /// `let b0 = cx.build_of(f, &[..]);` of a compound whose arguments are
    /// registers and constants, pushed to `ts`; `None` for another term.
    fn nat_build_of_parts(
        &self,
        b: &Build,
        regs: &Regs,
        ts: &mut Vec<TokenStream>,
    ) -> N<Option<TokenStream>> {
        let Build::Compound(f, args) = b else {
            return Ok(None);
        };
        let mut parts = Vec::new();
        let mut n = 0;
        for a in args.iter() {
            match a {
                Build::Reg(r) => {
                    let (v, _) = regs.get(r).ok_or(format!("register r{r} is read unset"))?;
                    parts.push(quote!(&#v));
                }
                Build::Const(t) => {
                    let mut pre = Vec::new();
                    // A constant native code cannot write (or needs statements
                    // first) keeps the term code's steps: never worse than those.
                    match self.nat_const_term(*t, &mut pre, &mut n) {
                        Ok(c) if pre.is_empty() => parts.push(quote!(&#c)),
                        _ => return Ok(None),
                    }
                }
                Build::Compound(..) => return Ok(None),
            }
        }
        let f = self.functor_native(*f)?;
        ts.push(quote!(let b0 = cx.build_of(#f, &[#(#parts),*]);));
        Ok(Some(quote!(b0)))
    }

    /// What an action is, for `--explain-types`: `say/1`, a list of them.
    fn action_shape(&self, a: &Action) -> String {
        let ev = |e: &Ev| -> String {
            let b = match e {
                Ev::Built(b) | Ev::Eval(b) => b,
                Ev::Compound(name, args) => return format!("`{}/{}`", name.as_str(), args.len()),
                Ev::Value(_) => return "a variable".into(),
                _ => return "an expression".into(),
            };
            match b {
                Build::Const(t) => match self.store.functor(*t) {
                    Some((f, n)) => format!("`{}/{n}`", f.as_str()),
                    None => "a constant".into(),
                },
                Build::Reg(_) => "a variable".into(),
                Build::Compound(f, args) => format!("`{}/{}`", f.as_str(), args.len()),
            }
        };
        match a {
            Action::One(e) => ev(e),
            Action::List { items, .. } => {
                let mut shapes: Vec<String> = items.iter().map(ev).collect();
                shapes.dedup();
                format!("a list of {}", shapes.join(", "))
            }
        }
    }

    /// The value of a register or constant.
    fn nat_value(&self, b: &Build, regs: &Regs) -> N<V> {
        match b {
            Build::Reg(r) => {
                let (x, ty) = regs.get(r).ok_or(format!("register r{r} is read unset"))?;
                if is_fresh(x) {
                    return Err(format!(
                        "register r{r} is a fresh variable, bound at a boundary"
                    ));
                }
                Ok(V {
                    e: quote!(#x.clone()),
                    ty: ty.clone(),
                })
            }
            Build::Const(t) => match self.store.value(*t) {
                Value::Atom(a) if a == atoms::NIL => Ok(V {
                    e: quote!(List::<Never>::nil()),
                    ty: Ty::list(Ty::Never),
                }),
                Value::Atom(a) => Ok(V {
                    e: self.atom_native(a)?,
                    ty: Ty::Sym,
                }),
                Value::Int(i) => {
                    let i = Literal::i64_suffixed(i);
                    Ok(V {
                        e: quote!(#i),
                        ty: Ty::Int,
                    })
                }
                Value::Float(f) if f.is_finite() => {
                    let f = Literal::f64_suffixed(f);
                    Ok(V {
                        e: quote!(#f),
                        ty: Ty::Float,
                    })
                }
                // A constant list of atoms or of ints, built natively.
                Value::Compound(..) => self.nat_const_list(*t),
                _ => Err(format!(
                    "constant `{}` is not native yet",
                    self.store.writeq(*t)
                )),
            },
            Build::Compound(name, args) if *name == atoms::DOT && args.len() == 2 => {
                let h = self.nat_value(&args[0], regs)?;
                let t = self.nat_value(&args[1], regs)?;
                cons(h, t)
            }
            Build::Compound(name, args) => {
                let parts = args
                    .iter()
                    .map(|a| self.nat_value(a, regs))
                    .collect::<N<Vec<_>>>()?;
                self.nat_compound(*name, parts)
            }
        }
    }

    /// `name(parts..)` of native values (not a list cell): a fixed-shape
    /// compound, a canonical `Val` (`Val::Tagged`, its arguments `Val`s),
    /// typed `name(T1, ..)` (or `ground` past the depth limit).
    fn nat_compound(&self, name: Atom, parts: Vec<V>) -> N<V> {
        if parts.iter().any(|p| p.ty == Ty::Term || !p.ty.is_native()) {
            return Err("a compound value holds a term".into());
        }
        // Only a compound that evaluates to itself (`take(O, S)`, not
        // `N + 1` or `get(n, _)`, which a condition evaluates).
        if !sitlog_runtime::eval::evaluates_arguments_only(name, parts.len()) {
            return Err(format!(
                "`{}/{}` is evaluated, not a value",
                name.as_str(),
                parts.len()
            ));
        }
        let f = self.atom_native(name)?;
        let es = parts.iter().map(|p| {
            let e = &p.e;
            quote!(IntoVal::into_val(#e))
        });
        Ok(V {
            e: quote!(Val::Tagged(native::Compound::new(#f, [#(#es),*]))),
            ty: Ty::tagged(name, parts.iter().map(|p| p.ty.clone()).collect()),
        })
    }

    /// A ground list of atoms or of ints (`[x, y]`, `[1, 2]`) as a native list.
    /// Built once per thread and shared (`Rc`): no allocation per use.
    fn nat_const_list(&self, t: Term) -> N<V> {
        let v = self.nat_const_list_in(t)?;
        let (e, rty) = (v.e, rust_ty(&v.ty)?);
        Ok(V {
            e: quote!({
                ::std::thread_local! { static K: #rty = #e; }
                K.with(|k| k.clone())
            }),
            ty: v.ty,
        })
    }

    /// The list's value, its atoms interned by name (no `Program` in scope).
    fn nat_const_list_in(&self, t: Term) -> N<V> {
        let not = || format!("constant `{}` is not native yet", self.store.writeq(t));
        let items = self.store.list_to_vec(t).ok_or_else(not)?;
        let mut vals = Vec::new();
        for &x in &items {
            match self.store.value(x) {
                Value::Atom(a) if a != atoms::NIL => {
                    let lit = Literal::string(a.as_str());
                    vals.push(V {
                        e: quote!(Atom::intern(#lit)),
                        ty: Ty::Sym,
                    })
                }
                Value::Atom(_) => vals.push(self.nat_value(&Build::Const(x), &Regs::new())?),
                Value::Int(i) => {
                    let i = Literal::i64_suffixed(i);
                    vals.push(V {
                        e: quote!(#i),
                        ty: Ty::Int,
                    })
                }
                Value::Compound(..) => vals.push(self.nat_const_list_in(x)?),
                _ => return Err(not()),
            }
        }
        // The elements' type: the first that is not `[]`'s.
        let ty = vals
            .iter()
            .map(|v| v.ty.clone())
            .find(|t| *t != Ty::list(Ty::Never))
            .or_else(|| vals.first().map(|v| v.ty.clone()))
            .ok_or_else(not)?;
        let es = vals
            .iter()
            .map(|v| coerce(v, &ty).map_err(|_| not()))
            .collect::<N<Vec<_>>>()?;
        let rty = rust_ty(&ty)?;
        Ok(V {
            e: quote!(List::<#rty>::from_vec(vec![#(#es),*])),
            ty: Ty::list(ty),
        })
    }

    /// The value of an evaluated expression of situation `cur`'s arc, by
    /// native code: a register, a value as written, a compound that
    /// evaluates its arguments only, and `get(v, _)` of a local held in
    /// the frame or of a global ([`Gen::nat_var_get`]).
    fn nat_ev_value(&self, d: &Dm, cur: usize, e: &Ev, regs: &Regs) -> N<V> {
        match e {
            Ev::Value(r) => self.nat_value(&Build::Reg(*r), regs),
            Ev::Built(b) => self.nat_value(b, regs),
            Ev::Compound(name, args) if *name == atoms::DOT && args.len() == 2 => {
                let h = self.nat_ev_value(d, cur, &args[0], regs)?;
                let t = self.nat_ev_value(d, cur, &args[1], regs)?;
                cons(h, t)
            }
            // A compound that evaluates its arguments only, of native values.
            Ev::Compound(name, args) => {
                let parts = args
                    .iter()
                    .map(|a| self.nat_ev_value(d, cur, a, regs))
                    .collect::<N<Vec<_>>>()?;
                self.nat_compound(*name, parts)
            }
            Ev::VarOp {
                op,
                name,
                arg: Build::Reg(r),
            } if *op == atoms::GET => self
                .nat_var_get(d, cur, *name, *r, regs)?
                .ok_or_else(|| "a `get` native code does not read".into()),
            _ => Err("an expression is not native yet".into()),
        }
    }

    /// Whether evaluating `e` only builds it from registers of types whose
    /// values are their own values (ints, floats, atoms, lists and
    /// compounds of them with no construct of L as functor, `ground`
    /// values, inert by their conversion) and constants:
    /// evaluating it or not does nothing else (a branch of `when/3` not
    /// chosen, [`Ev::Pick`]).
    fn nat_inert(e: &Ev, regs: &Regs) -> bool {
        fn inert(ty: &Ty) -> bool {
            match ty {
                Ty::Never | Ty::Int | Ty::Float | Ty::Sym => true,
                Ty::List(e) => inert(e),
                Ty::Tagged(name, args) => {
                    sitlog_runtime::eval::evaluates_arguments_only(*name, args.len())
                        && args.iter().all(inert)
                }
                // A `Val`: an inert ground term (`sitlog_runtime::native`).
                Ty::Ground => true,
                Ty::Term => false,
            }
        }
        let mut rs = Vec::new();
        built_regs(e, &mut rs)
            && rs
                .iter()
                .all(|r| regs.get(r).is_some_and(|(x, ty)| !is_fresh(x) && inert(ty)))
    }

    /// `get(v, R)` evaluated inside an expression (`C < get(limit, _)`),
    /// `R` not bound before (the machine's `get` binds it to the value):
    /// a register native code does not hold (as for a condition's side
    /// `get(g, D)`, `Gen::nat_global_get`, a later read of it finds no
    /// register and that code stays the machine's) or a fresh variable
    /// occurring nowhere else in the plan (`_`): the value of `v`, read
    /// now, nothing written. A local of the DM held in
    /// the frame: its field (what `Gen::nat_local_get` reads for a call's
    /// argument; the frame's locals are the DM's while its native code
    /// runs). Else a global ([`Gen::nat_global_read`]). `None`: not such
    /// a `get` (a local the frame does not hold, `R` bound or read again,
    /// a global of no native type): the code stays the machine's.
    fn nat_var_get(&self, d: &Dm, cur: usize, name: Atom, r: Reg, regs: &Regs) -> N<Option<V>> {
        // Not held, or a fresh variable (made at the visit's start where
        // the code uses it) that occurs nowhere else in the plan: binding
        // it has no other effect.
        let free = free_here(d, cur, r, regs);
        if !free {
            return Ok(None);
        }
        self.nat_var_read(d, cur, name)
    }

    /// The value of variable `name` read now by native code in situation
    /// `cur`'s arc, nothing written: a local of the DM held in the frame
    /// (its field), else a global ([`Gen::nat_global_read`]). `None`: a
    /// local the frame does not hold, a global of no native type.
    fn nat_var_read(&self, d: &Dm, cur: usize, name: Atom) -> N<Option<V>> {
        if d.declares_local(name) {
            if !d.locals_ok {
                return Ok(None);
            }
            let Some((l, lty)) = d.local_field(name) else {
                return Ok(None);
            };
            // `l.clone()`: read in place where the value is only read
            // (`place`), a comparison's operand.
            return Ok(Some(V {
                e: quote!(#l.clone()),
                ty: lty,
            }));
        }
        self.nat_global_read(d, cur, name)
    }

    /// `get(v, _)` or `inc(v, _)` (the `_` taking the value) computed by
    /// native code in situation `cur`'s arc, as the machine's `var_op`
    /// computes it (D-38): a `get` reads ([`Gen::nat_var_read`]); an `inc`
    /// of a local held in the frame as an int or a float adds 1 to the
    /// field and gives the new value; an int that would overflow enters the
    /// machine (the native frames handed over, the locals written back,
    /// as for an evaluation, [`Gen::nat_enter_to_evaluate`]) whose
    /// `var_op` reports its error. An `inc` of a global of type int or
    /// float: `Cx::global_inc`, the machine's `var_op` where the value is
    /// no number of that type. The code has an effect: it is run once, in
    /// the evaluator's order ([`Gen::nat_ev_effects`]). `None`: not
    /// native (a local the frame does not hold, of another type).
    fn nat_var_op_value(&self, d: &Dm, cur: usize, op: Atom, name: Atom) -> N<Option<V>> {
        if op == atoms::GET {
            return self.nat_var_read(d, cur, name);
        }
        if op != atoms::INC {
            return Ok(None);
        }
        let (opa, namea) = (self.atom_native(op)?, self.atom_native(name)?);
        let enter = self.nat_enter_to_evaluate(d, cur)?;
        if d.declares_local(name) {
            let Some((l, lty)) = d.local_field(name).filter(|_| d.locals_ok) else {
                return Ok(None);
            };
            let e = match lty {
                Ty::Int => quote! {
                    match #l.checked_add(1) {
                        Some(v) => {
                            *#l = v;
                            v
                        }
                        None => {
                            #enter
                            cx.var_op_fresh(#opa, #namea, arc_at)?;
                            return Err(cx.error("`inc` overflowed in native code only", arc_at));
                        }
                    }
                },
                Ty::Float => quote!({
                    *#l += 1.0;
                    *#l
                }),
                _ => return Ok(None),
            };
            return Ok(Some(V { e, ty: lty }));
        }
        let Some(gty) = self
            .mir_types
            .as_ref()
            .and_then(|t| t.globals.iter().find(|(n, _)| *n == name))
            .map(|(_, t)| t.ty.clone())
            .filter(|t| matches!(t, Ty::Int | Ty::Float))
        else {
            return Ok(None);
        };
        let rt = rust_ty(&gty)?;
        Ok(Some(V {
            e: global_op(quote!(global_inc), &rt, &namea, &opa, &enter, None),
            ty: gty,
        }))
    }

    /// `e` (a next situation's argument, an out_arg) as a native value
    /// where its `get(v, _)`/`inc(v, _)` ([`Gen::nat_var_op_value`]; `_`
    /// a variable met nowhere else in the plan, or one native code does
    /// not hold, as [`Gen::nat_var_get`] takes it) are computed by native
    /// code: each once, in the evaluator's order (left to right, depth
    /// first, D-39), into `let <pfx><k> = ..;` pushed to `pre`, the
    /// value read from there. Any other part as [`Gen::nat_ev_value`]
    /// makes it (it has no effect). An error: some part is not native.
    fn nat_ev_effects(
        &self,
        d: &Dm,
        cur: usize,
        e: &Ev,
        regs: &Regs,
        pre: &mut Vec<TokenStream>,
        pfx: &str,
    ) -> N<V> {
        let (op, name) = match e {
            Ev::VarOpFresh { op, name, dst } => {
                let once = occurs_once(d, cur, *dst);
                if !once {
                    return Err("a `get`/`inc` whose variable is read again".into());
                }
                (*op, *name)
            }
            Ev::VarOp {
                op,
                name,
                arg: Build::Reg(r),
            } if *op == atoms::GET || *op == atoms::INC => {
                let free = free_here(d, cur, *r, regs);
                if !free {
                    return Err("a `get`/`inc` into a variable bound before".into());
                }
                (*op, *name)
            }
            Ev::Compound(f, args) => {
                let parts = args
                    .iter()
                    .map(|a| self.nat_ev_effects(d, cur, a, regs, pre, pfx))
                    .collect::<N<Vec<_>>>()?;
                return if *f == atoms::DOT && parts.len() == 2 {
                    let mut parts = parts.into_iter();
                    match (parts.next(), parts.next()) {
                        (Some(h), Some(t)) => cons(h, t),
                        _ => Err("a list cell".into()),
                    }
                } else {
                    self.nat_compound(*f, parts)
                };
            }
            e => return self.nat_ev_value(d, cur, e, regs),
        };
        let v = self
            .nat_var_op_value(d, cur, op, name)?
            .ok_or("a `get`/`inc` native code does not compute")?;
        let x = format_ident!("{}{}", pfx, pre.len());
        let (ve, rt) = (&v.e, rust_ty(&v.ty)?);
        pre.push(quote!(let #x: #rt = #ve;));
        Ok(V {
            e: quote!(#x.clone()),
            ty: v.ty,
        })
    }

    fn nat_cond(&self, d: &Dm, cur: usize, c: &Cond, regs: &Regs) -> N<TokenStream> {
        let mut regs = regs.clone();
        let mut pre = Vec::new();
        let c = self.nat_cond_bind(d, cur, c, &mut regs, &mut pre)?;
        Ok(if pre.is_empty() {
            c
        } else {
            quote!({ #(#pre)* #c })
        })
    }

    /// A condition of situation `cur`'s arc as native code: the statements
    /// `pre` (run first) and the test. A side `get(v, R)` (`get(done, D)
    /// == yes`, `C < get(limit, L)`) is the value of `v` read now
    /// ([`Gen::nat_var_read`]), unified with `R` as the machine evaluates
    /// it, left to right ([`Gen::nat_get_unify`]): `R` not bound before is
    /// bound to it, a register added to `regs` that the code after the
    /// condition reads (its branches); `R` bound (`get(left, D) ==
    /// get(right, D)`, the second side) compares, the machine's error
    /// where the values differ.
    fn nat_cond_bind(
        &self,
        d: &Dm,
        cur: usize,
        c: &Cond,
        regs: &mut Regs,
        pre: &mut Vec<TokenStream>,
    ) -> N<TokenStream> {
        match c {
            Cond::Arith(op, l, r) => {
                // A side an arithmetic expression of ints (`N + 1 > L`).
                if let Some(t) = self.nat_arith_exprs(d, cur, *op, (l, r), regs)? {
                    return Ok(t);
                }
                let side = |e: &Ev, regs: &mut Regs, pre: &mut Vec<TokenStream>| match e {
                    Ev::VarOp {
                        op,
                        name,
                        arg: Build::Reg(r),
                    } if *op == atoms::GET => self.nat_cond_get(d, cur, *name, *r, regs, pre),
                    e => self.nat_ev_value(d, cur, e, regs),
                };
                let l = side(l, regs, pre)?;
                let before = pre.len();
                let r = side(r, regs, pre)?;
                // The machine evaluates the left side first: where the
                // right side's `get` runs first (`pre`, it binds or
                // compares) and the left side's code may fail (enter the
                // machine for an error), the left side is read first too.
                let l = if pre.len() > before && may_leave(&l.e) {
                    let (le, lt) = (&l.e, rust_ty(&l.ty)?);
                    pre.insert(before, quote!(let lhs: #lt = #le;));
                    V {
                        e: quote!(lhs.clone()),
                        ty: l.ty,
                    }
                } else {
                    l
                };
                self.nat_arith(d, cur, *op, l, r)
            }
            // `when/3`'s comparison: its operands as written (a register,
            // a constant), its error the evaluator's.
            Cond::Cmp(op, l, r) => self.nat_cmp(d, cur, *op, (l, r), regs, call::Decide::Value),
            Cond::Other(Build::Compound(op, args))
                if args.len() == 2 && matches!(op.as_str(), "==" | "\\==") =>
            {
                // A side `get(v, D)`: evaluated (D-35); any other side is
                // a value as written.
                let mut side = |b: &Build, regs: &mut Regs| match b {
                    Build::Compound(f, a) if *f == atoms::GET && a.len() == 2 => {
                        match (&a[0], &a[1], self.nat_build_atom(&a[0])) {
                            (Build::Const(_), Build::Reg(r), Some(name)) => {
                                self.nat_cond_get(d, cur, name, *r, regs, pre)
                            }
                            _ => Err("a `get` that is not `get(v, V)`".into()),
                        }
                    }
                    b => self.nat_value(b, regs),
                };
                let l = side(&args[0], regs)?;
                let r = side(&args[1], regs)?;
                let same = identical(&l, &r)
                    .ok_or_else(|| format!("`{}` on {} and {}", op.as_str(), l.ty, r.ty))?;
                Ok(if op.as_str() == "==" {
                    same
                } else {
                    quote!((!#same))
                })
            }
            // `member(X, L)`, `not_member(X, L)` of native values (D-33).
            Cond::Other(Build::Compound(op, args))
                if args.len() == 2 && (*op == atoms::MEMBER || *op == atoms::NOT_MEMBER) =>
            {
                let x = self.nat_value(&args[0], regs)?;
                let l = self.nat_value(&args[1], regs)?;
                let found = member_test(&x, &l)
                    .ok_or_else(|| format!("`{}` on {} and {}", op.as_str(), x.ty, l.ty))?;
                Ok(if *op == atoms::MEMBER {
                    found
                } else {
                    quote!((!#found))
                })
            }
            // `number(X)`, `\+ atom(X)`, .. of a native value (`type_test`).
            Cond::Other(b) if self.is_type_test(b) => self.nat_type_test(b, regs),
            // `(A, B)`, `(A ; B)` (`cond.rs`).
            Cond::And(..) | Cond::Or(..) => self.nat_junction(d, cur, c, regs, pre),
            _ => Err("a condition is not `==`, `\\==`, `member` or an int comparison".into()),
        }
    }

    /// The atom a constant is, if it is one.
    fn nat_build_atom(&self, b: &Build) -> Option<Atom> {
        match b {
            Build::Const(t) => self.store.atom_of(*t),
            _ => None,
        }
    }

    /// A condition's side `get(v, R)` in situation `cur`'s arc (evaluated
    /// by the machine's condition, D-35): `v`'s value read now
    /// ([`Gen::nat_var_read`]: a local held in the frame, a global of a
    /// native type, read with `Cx::global_as`, no typed copy kept; where
    /// it is not of the global's MIR type the machine is entered and its
    /// `get` gives the value or its error), unified with `R`
    /// ([`Gen::nat_get_unify`]).
    fn nat_cond_get(
        &self,
        d: &Dm,
        cur: usize,
        name: Atom,
        r: Reg,
        regs: &mut Regs,
        pre: &mut Vec<TokenStream>,
    ) -> N<V> {
        let got = self
            .nat_var_read(d, cur, name)?
            .ok_or("a `get` native code does not read")?;
        let enter = self.nat_enter_to_evaluate(d, cur)?;
        self.nat_get_unify(d, cur, name, r, got, regs, pre, &enter, &quote!(arc_at))
    }

    /// `get(v, R)` in situation `cur`'s arc whose value `got` native code
    /// has read: the machine's `get` unifies it with `R` (D-38), and so
    /// does this. `R` not held (an arc's variable no code bound before):
    /// bound, `let r<R> = got;` in `pre`, the register (of `R`'s type)
    /// added to `regs` for what reads `R` later (a comparison's other
    /// side, a branch, an action, the next situation). `R` a fresh
    /// variable occurring nowhere else in the plan (`_`): the value, `R`
    /// left unbound (nothing reads it). `R` held as a native value:
    /// compared (ground values unify where they are identical); where they
    /// differ the machine is entered (`enter`) and its `get` reports its
    /// error (`arc`: the arc's index for it). `R` a term native code has
    /// not converted (a perception's value): not native.
    #[allow(clippy::too_many_arguments)]
    fn nat_get_unify(
        &self,
        d: &Dm,
        cur: usize,
        name: Atom,
        r: Reg,
        got: V,
        regs: &mut Regs,
        pre: &mut Vec<TokenStream>,
        enter: &TokenStream,
        arc: &TokenStream,
    ) -> N<V> {
        let g = format_ident!("got_r{}", r);
        let ge = &got.e;
        // Met only here: nothing reads what it is bound to. Not a value
        // held before (a parameter met only here is bound: compared).
        let once = occurs_once(d, cur, r) && regs.get(&r).is_none_or(|(x, _)| is_fresh(x));
        match regs.get(&r).cloned() {
            _ if once => Ok(got),
            None => {
                let dty = d.types[cur].regs[r as usize].ty.clone();
                let e = coerce(
                    &V {
                        e: quote!(#g),
                        ty: got.ty.clone(),
                    },
                    &dty,
                )?;
                let rr = reg(r);
                pre.push(quote!(let #g = #ge; let #rr = #e;));
                regs.insert(r, (rr.clone(), dty.clone()));
                Ok(V {
                    e: quote!(#rr.clone()),
                    ty: dty,
                })
            }
            Some((x, _)) if is_fresh(&x) => {
                Err("`get` into a variable that may be bound, a term".into())
            }
            Some((x, ty)) => {
                if !ty.is_native() {
                    return Err("`get` into a variable that is a term".into());
                }
                let held = V {
                    e: quote!(#x.clone()),
                    ty,
                };
                // A value read where it is held (a local's field) is
                // compared there, by reference: no copy (a list's count
                // changed and changed back) to compare it.
                let (bind, got_v) = if moved_place(&got).is_some() {
                    (quote!(), got.clone())
                } else {
                    let v = V {
                        e: quote!(#g.clone()),
                        ty: got.ty.clone(),
                    };
                    (quote!(let #g = #ge;), v)
                };
                let same = identical(&got_v, &held)
                    .ok_or("`get` of a value of another type than its variable's")?;
                let (opa, namea) = (self.atom_native(atoms::GET)?, self.atom_native(name)?);
                // `identical` is exact on ground native values (canonical
                // `Val`s: `==` is Prolog's), so values it calls different
                // never unify in the machine, whose `get` then fails with its
                // own error; the last line is unreachable unless that breaks.
                pre.push(quote! {
                    #bind
                    if !#same {
                        #enter
                        let t = cx.term(&#x);
                        cx.var_op(#opa, #namea, t, #arc)?;
                        return Err(cx.error("`get` unified in the machine only", #arc));
                    }
                });
                Ok(held)
            }
        }
    }

    /// The value of global `name` (no local of DM `d`) read by native code
    /// in situation `cur`'s arc (`Cx::global_as`, no typed copy kept), of
    /// the global's MIR type; where it is not of that type (only if the
    /// inference were wrong) the machine is entered and its `get` gives
    /// the value or its error. `None`: a global of no native type.
    fn nat_global_read(&self, d: &Dm, cur: usize, name: Atom) -> N<Option<V>> {
        let Some(gty) = self
            .mir_types
            .as_ref()
            .and_then(|t| t.globals.iter().find(|(n, _)| *n == name))
            .map(|(_, t)| t.ty.clone())
        else {
            return Ok(None);
        };
        if matches!(gty, Ty::Term | Ty::Never) || !gty.is_native() {
            return Ok(None);
        }
        let rt = rust_ty(&gty)?;
        let (opa, namea) = (self.atom_native(atoms::GET)?, self.atom_native(name)?);
        let enter = self.nat_enter_to_evaluate(d, cur)?;
        Ok(Some(V {
            e: {
                let cold = self.global_cold.borrow().clone();
                let read = global_op(quote!(global_as), &rt, &namea, &opa, &enter, cold);
                quote!((#read))
            },
            ty: gty,
        }))
    }

    /// Before the evaluator computes (part of) a next situation: the native
    /// stack handed over, the transitions counted so far given to the
    /// machine except this one, which counts once its next situation is
    /// computed (an error evaluating it leaves it out, as on the term path),
    /// and the machine entered in situation `cur` with its id.
    fn nat_enter_to_evaluate(&self, d: &Dm, cur: usize) -> N<TokenStream> {
        let (hand_count, id_stmts, id, curl) = self.nat_before_evaluating(d, cur)?;
        Ok(quote! {
            #hand_count
            #(#id_stmts)*
            cx.enter_with_id(#curl, #id);
        })
    }

    /// What [`Gen::nat_enter_to_evaluate`] and [`Gen::nat_eval_lazy_id`]
    /// share: the hand-over and the count (this transition counts once the
    /// evaluation is done: an error leaves it out, as on the term path),
    /// the statements and expression of situation `cur`'s id, `cur`.
    fn nat_before_evaluating(
        &self,
        d: &Dm,
        cur: usize,
    ) -> N<(TokenStream, Vec<TokenStream>, TokenStream, Literal)> {
        let (id_stmts, id) = self.nat_id_term(d, cur, quote!(cx.store()))?;
        let hand = &d.hand;
        let hand_count = quote! {
            #hand
            count = run.count_but_this(cx, count);
        };
        Ok((
            hand_count,
            id_stmts,
            id,
            Literal::u32_unsuffixed(cur as u32),
        ))
    }

    /// [`Gen::nat_enter_to_evaluate`] for an evaluation whose only reader
    /// of the situation's id is an error (a condition), with the id built
    /// only where it is read: statements entering the machine (the id
    /// built when the run records: the history reads it; else
    /// `Cx::enter_unbuilt`), then `let <name>: <ty>` of `eval`
    /// (statements ending in a `Result` expression, the machine's calls in
    /// them with `?`) run so that an error gets the id, built then
    /// (`Cx::with_id`). A list walk's id (`try(Ps)`, the rest a native
    /// list) costs O(length) to build: built at every visit, a walk whose
    /// condition the machine evaluates was quadratic (`d_compare_fn`).
    fn nat_eval_lazy_id(
        &self,
        d: &Dm,
        cur: usize,
        name: &Ident,
        eval: TokenStream,
        ty: TokenStream,
    ) -> N<TokenStream> {
        let (hand_count, id_stmts, id, curl) = self.nat_before_evaluating(d, cur)?;
        Ok(quote! {
            #hand_count
            if run.records {
                #(#id_stmts)*
                cx.enter_with_id(#curl, #id);
            } else {
                cx.enter_unbuilt(#curl);
            }
            let evaluated = (|cx: &mut Ctx| -> Result<#ty, RunError> { #eval })(cx);
            let #name: #ty = match evaluated {
                Ok(v) => v,
                Err(e) => {
                    #(#id_stmts)*
                    let id = #id;
                    return Err(cx.with_id(e, id));
                }
            };
        })
    }

    /// The next `Nat` of situation `cur` (named `cur_name`), or a return
    /// handing the value to the machine.
    fn nat_next(
        &self,
        d: &Dm,
        cur: usize,
        n: &Next,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<TokenStream> {
        let curl = Literal::u32_unsuffixed(cur as u32);
        // A global read whose value native code cannot hold: the machine's
        // (`cold_next`).
        if let Some(code) = self.nat_next_cold(d, cur, n, regs, cur_name)? {
            return Ok(code);
        }
        // A `get(v, _)`/`inc(v, _)` in the value (`t(inc(n, _))`, `u(X,
        // get(n, _))`) of the frame's local or a global: computed by native
        // code once, first (the evaluator's order), the value selected as
        // any other; a value no situation takes natively is handed to the
        // machine as that value (never evaluated again). Else, as below
        // (the evaluator's part).
        // (A `get` of a global alone stays the evaluator's: it has no
        // effect to keep in order.)
        if let Next::Eval(e @ Ev::Compound(name, args)) = n {
            if has_var_op(e, &|op, v| op == atoms::INC || d.declares_local(v)) {
                let mut pre = Vec::new();
                // A global read beside an `inc`: its cold arm the
                // machine's from there (`cold_next`).
                let cold = self.cold_effects(d, e);
                let saved =
                    cold.then(|| self.global_cold.replace(Some(quote!(break 'nat_cold_next))));
                let vals = args
                    .iter()
                    .map(|a| self.nat_ev_effects(d, cur, a, regs, &mut pre, "op"))
                    .collect::<N<Vec<_>>>();
                let vals = match saved {
                    Some(saved) => {
                        *self.global_cold.borrow_mut() = saved;
                        match self.nat_effects_cold(d, e, regs, std::mem::take(&mut pre), "op") {
                            Ok(cold) => {
                                pre = cold;
                                vals
                            }
                            // Made again, the reads' cold arms errors.
                            Err(_) => args
                                .iter()
                                .map(|a| self.nat_ev_effects(d, cur, a, regs, &mut pre, "op"))
                                .collect::<N<Vec<_>>>(),
                        }
                    }
                    None => vals,
                };
                if let Ok(sel) = vals.and_then(|v| self.nat_select(d, cur, *name, v, cur_name)) {
                    return Ok(quote!({ #(#pre)* #sel }));
                }
            }
        }
        // `infer(apply(here, []))` whole: as `infer` of its evaluated part
        // where that selects natively (else as below).
        if let Some(e) = match n {
            Next::Eval(e) => self.ground_next_parts(e),
            _ => None,
        } {
            if let Ok(code) = self.nat_next(d, cur, &Next::Eval(e), regs, cur_name) {
                return Ok(code);
            }
        }
        match n {
            Next::Static(t, ix)
                if self.store.atom_of(*t).is_some()
                    && ix.is_none_or(|ix| !d.native[ix as usize]) =>
            {
                // A situation without native code, or no situation of this
                // name (the machine says so): the machine enters it.
                let a = self.atom_native(self.store.atom_of(*t).unwrap_or(atoms::NIL))?;
                let hand = &d.hand;
                let out = d.out.borrow().clone();
                let tail = goto_tail(&d.rec.borrow());
                Ok(quote! {{
                    #hand
                    // Recorded, the situation was entered with its id.
                    cx.count_and_enter(count, run.records, #curl, #cur_name);
                    #out
                    let rec_next = Term::atom(#a);
                    #tail
                }})
            }
            Next::Static(t, Some(ix)) if self.store.atom_of(*t).is_some() => {
                let v = variant(*ix as usize);
                if d.plans[*ix as usize].id.1 != 0 {
                    return Err("a constant next situation selects a compound id".into());
                }
                Ok(quote!(Nat::#v {}))
            }
            Next::Static(t, _) | Next::Eval(Ev::Built(Build::Const(t)))
                if self.store.functor(*t).is_some_and(|(_, n)| n > 0) =>
            {
                let (name, _) = self.store.functor(*t).ok_or("no functor")?;
                let vals = self
                    .store
                    .args(*t)
                    .to_vec()
                    .into_iter()
                    .map(|a| self.nat_value(&Build::Const(a), regs))
                    .collect::<N<Vec<_>>>()?;
                self.nat_select(d, cur, name, vals, cur_name)
            }
            Next::If(c, a, b) => {
                // A plain call's test in a DM with locals (`plain`).
                if let Some(code) = self.nat_plain_if_locals(d, cur, n, regs, cur_name)? {
                    return Ok(code);
                }
                // A `get(v, D)` of the condition binds `D` for the branches.
                let mut bregs = regs.clone();
                let mut binds = Vec::new();
                // A condition the evaluator computes a side of
                // (`apply(member_of(_, _), [O, L]) == yes`): the
                // machine entered in the situation, as for a next
                // situation's evaluated part; only in a DM without
                // locals (the evaluator cannot change the frame's).
                let on_terms_if = |name: &Ident, locals_kept: bool| -> N<Option<TokenStream>> {
                    let mut ts = Vec::new();
                    let mut n = 0;
                    match self.nat_cond_term(c, regs, &mut ts, &mut n) {
                        Ok(cond)
                            if locals_kept || (d.locals.is_empty() && d.dm.locals.is_empty()) =>
                        {
                            // The id built only where an error reads it.
                            let pre = self.nat_eval_lazy_id(
                                d,
                                cur,
                                name,
                                quote!(#(#ts)* Ok(#cond)),
                                quote!(bool),
                            )?;
                            Ok(Some(pre))
                        }
                        _ => Ok(None),
                    }
                };
                let on_terms = |name: &Ident| on_terms_if(name, false);
                // A global read's cold arm (`cold`): also in a DM with
                // locals where evaluating the condition changes none.
                let on_terms_cold = |name: &Ident| on_terms_if(name, self.keeps_locals(c, regs));
                let name = format_ident!("cond_value");
                // `apply(f(..), [..]) == k` of a plain function (`plain`).
                if let Some(pre) = self.nat_plain_cond(d, c, regs, &name, || on_terms(&name))? {
                    let a = self.nat_next(d, cur, a, regs, cur_name)?;
                    let b = self.nat_next(d, cur, b, regs, cur_name)?;
                    return Ok(quote!({ #pre if #name { #a } else { #b } }));
                }
                let cond = self.nat_cond_cold(d, cur, c, &mut bregs, &mut binds, &on_terms_cold)?;
                let (c, pre) = match cond {
                    Ok(c) => c,
                    Err(e) => {
                        let Some(pre) = on_terms(&name)? else {
                            return Err(e);
                        };
                        bregs = regs.clone();
                        (quote!(#name), pre)
                    }
                };
                let a = self.nat_next(d, cur, a, &bregs, cur_name)?;
                let b = self.nat_next(d, cur, b, &bregs, cur_name)?;
                Ok(quote!({ #pre if #c { #a } else { #b } }))
            }
            Next::Eval(Ev::Compound(name, args))
                if args.iter().any(|a| {
                    matches!(a, Ev::Eval(_) | Ev::VarOp { .. } | Ev::VarOpFresh { .. })
                }) =>
            {
                // A part the evaluator computes (`confirm(apply(f(_),
                // [X]))`): given to it as a term built from native values,
                // its value converted with the checked conversion; when
                // that fails, the whole value goes to the machine as a term.
                let mut pre = vec![self.nat_enter_to_evaluate(d, cur)?];
                let mut n = 0;
                let mut parts = Vec::new();
                // A `get(g, _)` part (a local's or global's value read by
                // the machine, `review`'s `each(get(taken, _))`): the
                // fresh variable it takes is a term made there.
                let mut regs = regs.clone();
                for a in args.iter() {
                    if let Ev::VarOpFresh { dst, .. } = a {
                        regs.insert(*dst, (format_ident!("fresh_r{}", dst), Ty::Term));
                    }
                }
                let regs = &regs;
                for a in args.iter() {
                    match a {
                        Ev::Eval(_) | Ev::VarOp { .. } | Ev::VarOpFresh { .. } => {
                            let t = self.nat_ev_term(a, regs, &mut pre, &mut n)?;
                            parts.push(Err(t));
                        }
                        a => parts.push(Ok(self.nat_ev_value(d, cur, a, regs)?)),
                    }
                }
                let terms: Vec<TokenStream> = parts
                    .iter()
                    .map(|p| match p {
                        Ok(v) => {
                            let e = &v.e;
                            quote!(cx.term(&#e))
                        }
                        Err(t) => quote!(#t),
                    })
                    .collect();
                let f = self.functor_native(*name)?;
                let out = d.out.borrow().clone();
                let tail = goto_tail(&d.rec.borrow());
                let fallback = quote! {{
                    cx.count_transitions(count);
                    let ts = [#(#terms),*];
                    let rec_next = cx.build(#f, &ts);
                    #out
                    #tail
                }};
                let mut vals = Vec::new();
                let mut checks = Vec::new();
                for (k, p) in parts.into_iter().enumerate() {
                    match p {
                        Ok(v) => vals.push(v),
                        Err(t) => {
                            let x = format_ident!("x{}", k);
                            checks.push((x.clone(), quote!(cx.to_native::<Val>(#t)), quote!()));
                            vals.push(V {
                                e: quote!(#x.clone()),
                                ty: Ty::Ground,
                            });
                        }
                    }
                }
                // What the evaluator changed of the locals, read again.
                checks.extend(self.nat_local_checks(d)?);
                pre.push(checked(checks, &fallback));
                let sel = self.nat_select(d, cur, *name, vals, cur_name)?;
                Ok(quote!({ #(#pre)* #sel }))
            }
            // A next situation the evaluator computes whole
            // (`infer(apply(here, []))`, ground): evaluated where the term
            // code evaluates it, the machine entered in the situation, and
            // its value handed to the machine, which selects.
            Next::Eval(Ev::Eval(b)) => {
                let enter = self.nat_enter_to_evaluate(d, cur)?;
                let mut ts = Vec::new();
                let mut n = 0;
                let t = self.nat_build_term(b, regs, &mut ts, &mut n)?;
                let out = d.out.borrow().clone();
                let tail = goto_tail(&d.rec.borrow());
                let evaluated = quote! {{
                    #enter
                    #(#ts)*
                    let rec_next = cx.eval(#t, arc_at)?;
                    cx.count_transitions(count);
                    #out
                    #tail
                }};
                // A plain user function's value selected natively (`plain`).
                if let Some(code) =
                    self.nat_plain_next(d, cur, b, regs, cur_name, evaluated.clone())?
                {
                    return Ok(code);
                }
                Ok(evaluated)
            }
            Next::Eval(Ev::Compound(name, args))
                if args
                    .iter()
                    .any(|a| next_is::fresh_is(d, cur, a, regs).is_some()) =>
            {
                self.nat_next_is(d, cur, *name, args, regs, cur_name)
            }
            Next::Eval(Ev::Compound(name, args)) => {
                let vals = args
                    .iter()
                    .map(|a| self.nat_ev_value(d, cur, a, regs))
                    .collect::<N<Vec<_>>>()?;
                self.nat_select(d, cur, *name, vals, cur_name)
            }
            Next::Eval(Ev::Built(Build::Compound(name, args))) => {
                let vals = args
                    .iter()
                    .map(|a| self.nat_value(a, regs))
                    .collect::<N<Vec<_>>>()?;
                self.nat_select(d, cur, *name, vals, cur_name)
            }
            // `when/3` whose branches only build native values
            // (`apply(when(_, _, _), [D == Want, at(D), probe(Rest)])`):
            // evaluating the branch not chosen too changes nothing and
            // cannot fail, so it is the conditional `(C -> A ; otherwise
            // -> B)` of [`Next::If`], the condition's error the
            // evaluator's (`Cond::Cmp`, [`Gen::nat_cond_bind`]).
            Next::Eval(Ev::Pick(c, a, b))
                if Self::nat_inert(a, regs) && Self::nat_inert(b, regs) =>
            {
                let mut bregs = regs.clone();
                let mut binds = Vec::new();
                let c = self.nat_cond_bind(d, cur, c, &mut bregs, &mut binds)?;
                let a = self.nat_pick_next(d, cur, a, &bregs, cur_name)?;
                let b = self.nat_pick_next(d, cur, b, &bregs, cur_name)?;
                Ok(quote!({ #(#binds)* if #c { #a } else { #b } }))
            }
            _ => Err(format!(
                "situation {}: its next situation is not native yet",
                cur + 1
            )),
        }
    }

    /// A branch of a next situation's `when/3` ([`Ev::Pick`] in
    /// [`Gen::nat_next`]), a value that only builds native values: the
    /// situation it selects, as for that value written as the next
    /// situation.
    fn nat_pick_next(
        &self,
        d: &Dm,
        cur: usize,
        e: &Ev,
        regs: &Regs,
        cur_name: &TokenStream,
    ) -> N<TokenStream> {
        match e {
            Ev::Built(Build::Const(t)) => match self.store.atom_of(*t) {
                Some(name) => self.nat_select(d, cur, name, Vec::new(), cur_name),
                None => self.nat_next(d, cur, &Next::Static(*t, None), regs, cur_name),
            },
            Ev::Built(Build::Compound(name, args)) => {
                let vals = args
                    .iter()
                    .map(|a| self.nat_value(a, regs))
                    .collect::<N<Vec<_>>>()?;
                self.nat_select(d, cur, *name, vals, cur_name)
            }
            Ev::Compound(name, args) => {
                let vals = args
                    .iter()
                    .map(|a| self.nat_ev_value(d, cur, a, regs))
                    .collect::<N<Vec<_>>>()?;
                self.nat_select(d, cur, *name, vals, cur_name)
            }
            _ => Err("a `when/3` branch of a next situation is not native".into()),
        }
    }

    /// Selects the situation `name(args)` takes, in source order (D-21),
    /// else hands the value to the machine.
    fn nat_select(
        &self,
        d: &Dm,
        cur: usize,
        name: Atom,
        args: Vec<V>,
        cur_name: &TokenStream,
    ) -> N<TokenStream> {
        let curl = Literal::u32_unsuffixed(cur as u32);
        let arg_names: Vec<Ident> = (0..args.len()).map(|i| format_ident!("v{}", i)).collect();
        // Each value selected by reference where it lies (a register or
        // a frame field, not a clone): the candidates read it as `(*v<i>)`.
        // A register or field `x` (read as `x.clone()`) is borrowed as
        // `let v<i>: &T = &x;` (the value or, `x` a reference, the deref
        // coercion's: what `place`'s `Borrow` gives, in fewer columns).
        let lets: Vec<TokenStream> = args
            .iter()
            .zip(&arg_names)
            .map(|(v, n)| match (moved_place(v), rust_ty(&v.ty)) {
                (Some(x), Ok(t)) => quote!(let #n: &#t = &#x;),
                _ => {
                    let e = place(v);
                    quote!(let #n = &#e;)
                }
            })
            .collect();
        // The visit's own cell tail selected once: moved into a cell (or,
        // a cursor, the list advanced in place when it selects the visit's
        // own situation).
        let mut movable = None;
        if let Some(c) = self.nat_cell(d, cur) {
            let t = reg(c.tail);
            let of = |a: &V| pipe::mentions(&a.e, &t);
            let own: Vec<usize> = (0..args.len())
                .filter(|&i| t == moved(&args[i]).to_string())
                .collect();
            if let [i] = own[..] {
                if args.iter().map(of).sum::<usize>() == 1 {
                    let x = &arg_names[i];
                    // Not with an out_arg to set after the next situation.
                    let cursor = (d.plans[cur].id == (name, args.len())
                        && c.path == [i]
                        && d.out.borrow().is_empty()
                        && self.nat_cursor_passing(d, cur, i, &args))
                    .then_some(cur);
                    movable = Some((quote!((*#x)).to_string(), t, cursor));
                }
            }
        }
        *d.movable.borrow_mut() = movable;
        let mut candidates = Vec::new();
        // A candidate took every value: the hand-over below is not reached.
        let mut taken = false;
        for j in 0..d.plans.len() {
            if d.plans[j].id != (name, args.len()) {
                continue;
            }
            if !d.native[j] {
                // The machine selects from here on (D-21: source order).
                break;
            }
            let id = self.nat_id_of(d, j);
            let id_args = self.store.args(id).to_vec();
            let mut steps = Vec::new();
            let mut vars: HashMap<u32, (Ident, Ty)> = HashMap::new();
            let mut ok = true;
            let mut n = 0;
            for (i, (&pat, v)) in id_args.iter().zip(&args).enumerate() {
                let arg = V {
                    e: {
                        let x = &arg_names[i];
                        quote!((*#x))
                    },
                    ty: v.ty.clone(),
                };
                if !self.native_match(
                    d,
                    j,
                    pat,
                    &arg,
                    &mut vec![i],
                    &mut vars,
                    &mut steps,
                    &mut n,
                )? {
                    ok = false;
                    break;
                }
            }
            if !ok {
                continue; // cannot match a value of this type
            }
            if let Some((_, r, None)) = d.movable.borrow().as_ref() {
                defer_move(&mut steps, r);
            }
            // A field bound by a `let` that no test reads is computed
            // where the variant is built (no block per field, no clone
            // when an earlier test fails).
            let mut inline: HashMap<Ident, TokenStream> = HashMap::new();
            for (k, s) in steps.iter().enumerate() {
                if let MatchStep::Let(x, e) = s {
                    if !steps[k + 1..].iter().any(|t| t.mentions(x)) {
                        inline.insert(x.clone(), e.clone());
                    }
                }
            }
            let fields = self.nat_fields(d, j)?;
            let mut inits = Vec::new();
            let mut values = HashMap::new();
            // A cell selected whole (`fk<r>`, [`MatchStep::Cell`]).
            let cell = self.nat_cell(d, j);
            let whole = cell.as_ref().map(|c| format_ident!("f{}", c.name()));
            let whole = whole.filter(|w| vars.values().any(|(x, _)| x == w));
            for (r, _) in &fields {
                if let (Some(c), Some(w)) = (&cell, &whole) {
                    if *r == c.head || *r == c.tail {
                        values.insert(*r, quote!(#w));
                        inits.push((*r, quote!()));
                        continue;
                    }
                }
                let x = vars
                    .values()
                    .find(|(x, _)| *x == format_ident!("f{}", r))
                    .map(|(x, _)| x.clone())
                    .ok_or("an id field is not bound by its pattern")?;
                let rr = reg(*r);
                let e = match inline.get(&x) {
                    Some(e) => e.clone(),
                    None => quote!(#x),
                };
                values.insert(*r, e.clone());
                inits.push((*r, quote!(#rr: #e)));
            }
            // A cell's list: as selected (`fk<r>`, [`MatchStep::Cell`]), or
            // made again of its parts where they were taken apart.
            let inits: Vec<TokenStream> = match cell {
                Some(c) => {
                    let k = c.name();
                    let list = if let Some(w) = &whole {
                        quote!(#w)
                    } else {
                        let (h, t) = (&values[&c.head], &values[&c.tail]);
                        quote!(List::cons(#h, #t))
                    };
                    inits
                        .into_iter()
                        .filter_map(|(r, i)| match r {
                            r if r == c.head => None,
                            r if r == c.tail => Some(quote!(#k: #list)),
                            _ => Some(i),
                        })
                        .collect()
                }
                None => inits.into_iter().map(|(_, i)| i).collect(),
            };
            let v = variant(j);
            // The visit's own situation taking its own tail (a cursor): the
            // list was advanced in place, the variant stays where it is (the
            // visit ends there, `break 'step`, [`Gen::nat_cursor`]);
            // recorded, the variant is made again for the entry's next id.
            let own_cursor = d.movable.borrow().as_ref().and_then(|(_, t, c)| {
                let take = quote!(&#t).to_string();
                let took = steps
                    .iter()
                    .any(|s| matches!(s, MatchStep::Cell(_, _, x, _) if x.to_string() == take));
                (*c == Some(j) && took).then_some(())
            });
            if let (Some(()), Some(c), Some(w)) = (own_cursor, self.nat_cell(d, j), &whole) {
                let k = c.name();
                // Fields passed on as they are ([`Gen::nat_cursor_passing`]).
                let others = fields
                    .iter()
                    .filter(|(r, _)| *r != c.head && *r != c.tail)
                    .map(|(r, _)| {
                        let (rr, e) = (reg(*r), &values[r]);
                        quote!(#rr: #e)
                    });
                let stay = quote! {
                    if !run.records {
                        break 'step;
                    }
                    break 'sel Nat::#v { #k: #w.clone() #(, #others)* };
                };
                let code = wrap_steps(steps, &inline, stay);
                candidates.push((code, Shape::Other));
                continue;
            }
            // Only `let`s: this candidate takes every value that reaches
            // it, so no later one is tried.
            let lets = |ss: &[MatchStep]| ss.iter().all(|s| matches!(s, MatchStep::Let(..)));
            let takes_all = lets(&steps);
            // The first candidate, its id distinct variables: the variant
            // is the selection, each field the value itself (read once,
            // no `'sel` block and no reference to clone from).
            if takes_all
                && candidates.is_empty()
                && id_args
                    .iter()
                    .all(|&p| matches!(self.store.value(p), Value::Var(_)))
            {
                let direct = self.nat_select_direct(d, j, &id_args, &args, &fields);
                *d.movable.borrow_mut() = None;
                return direct;
            }
            // `[]` or `[H|T]` of one list, and `let`s (see below).
            let shape = match steps.split_first() {
                Some((MatchStep::Empty(l), rest)) if lets(rest) => {
                    let code = wrap_steps(
                        rest.to_vec(),
                        &inline,
                        quote!(break 'sel Nat::#v { #(#inits),* };),
                    );
                    Shape::Empty(l.to_string(), code)
                }
                Some((MatchStep::Split(l, ..), rest)) if lets(rest) => Shape::Split(l.to_string()),
                // `[P|Ps]` of a list taken whole: as exhaustive with `[]`.
                Some((MatchStep::Cell(l, _, _, false), rest)) if lets(rest) => {
                    Shape::Split(l.to_string())
                }
                _ => Shape::Other,
            };
            let code = wrap_steps(steps, &inline, quote!(break 'sel Nat::#v { #(#inits),* };));
            candidates.push((code, shape));
            if takes_all {
                taken = true;
                break;
            }
        }
        *d.movable.borrow_mut() = None;
        // `[]` and `[H|T]` of the same list (two adjacent candidates, the
        // rest of each only `let`s): every list is one or the other, so the
        // empty list is what the split leaves (the two are disjoint: their
        // order does not matter), and no later candidate is tried.
        let mut codes = Vec::new();
        let mut k = 0;
        while k < candidates.len() {
            let pair = match (&candidates[k], candidates.get(k + 1)) {
                ((_, Shape::Empty(l, empty)), Some((split, Shape::Split(m))))
                | ((split, Shape::Split(m)), Some((_, Shape::Empty(l, empty)))) => {
                    (l == m).then_some((split, empty))
                }
                _ => None,
            };
            if let Some((split, empty)) = pair {
                codes.push(split.clone());
                codes.push(empty.clone());
                taken = true;
                break;
            }
            codes.push(candidates[k].0.clone());
            k += 1;
        }
        let candidates = codes;
        let f = self.atom_native(name)?;
        let hand = &d.hand;
        let out = d.out.borrow().clone();
        let tail = goto_tail(&d.rec.borrow());
        // The `'hand` block only where a candidate leaves it (a value
        // that no later candidate may take either): every candidate
        // otherwise ends in `break 'sel` or falls through.
        let candidates: Vec<TokenStream> = candidates.iter().map(deref_receivers).collect();
        let candidates = if taken {
            candidates
        } else {
            drop_dead_hands(candidates)
        };
        let leaves = candidates.iter().any(|c| c.to_string().contains("'hand"));
        let candidates = if leaves {
            quote!('hand: { #(#candidates)* })
        } else {
            quote!(#(#candidates)*)
        };
        d.sels.borrow_mut().push(select_fn::SelSite {
            lets: quote!(#(#lets)*).to_string(),
            types: args
                .iter()
                .map(|v| rust_ty(&v.ty).ok().map(|t| quote!(&#t)))
                .collect(),
            text: candidates.to_string(),
            len: candidates.clone().into_iter().count(),
            name: name.to_string(),
        });
        if taken && !leaves {
            // Decided here: every value is taken natively.
            return Ok(quote! {
                'sel: {
                    #(#lets)*
                    #candidates
                }
            });
        }
        Ok(quote! {
            'sel: {
                #(#lets)*
                #candidates
                // No situation takes it here: the machine selects (or says
                // that none does).
                #hand
                // Recorded, the situation was entered with its id.
                cx.count_and_enter(count, run.records, #curl, #cur_name);
                let rec_next = cx.build_of(#f, &[#(#arg_names),*]);
                #out
                #tail
            }
        })
    }

    /// The variant of situation `j` whose id is distinct variables
    /// `id_args`, built of `args` (each read once: its own expression,
    /// converted to its field's type).
    fn nat_select_direct(
        &self,
        d: &Dm,
        j: usize,
        id_args: &[Term],
        args: &[V],
        fields: &[(Reg, Ty)],
    ) -> N<TokenStream> {
        let mut steps = Vec::new();
        let mut vars: HashMap<u32, (Ident, Ty)> = HashMap::new();
        let mut n = 0;
        for (i, (&pat, v)) in id_args.iter().zip(args).enumerate() {
            let matched =
                self.native_match(d, j, pat, v, &mut vec![i], &mut vars, &mut steps, &mut n)?;
            if !matched {
                return Err("an id variable does not take its value".into());
            }
        }
        let mut inits = Vec::new();
        for (r, _) in fields {
            let x = format_ident!("f{}", r);
            let e = steps
                .iter()
                .find_map(|s| match s {
                    MatchStep::Let(y, e) if *y == x => Some(e),
                    _ => None,
                })
                .ok_or("an id field is not bound by its pattern")?;
            let rr = reg(*r);
            inits.push(quote!(#rr: #e));
        }
        let v = variant(j);
        Ok(quote!(Nat::#v { #(#inits),* }))
    }

    /// Matching `v` against the id pattern `pat` of situation `j` at `path`:
    /// steps pushed; `false` when no value of `v`'s type can match.
    #[allow(clippy::too_many_arguments)]
    fn native_match(
        &self,
        d: &Dm,
        j: usize,
        pat: Term,
        v: &V,
        path: &mut Vec<usize>,
        vars: &mut HashMap<u32, (Ident, Ty)>,
        steps: &mut Vec<MatchStep>,
        n: &mut usize,
    ) -> N<bool> {
        let e = &v.e;
        match self.store.value(pat) {
            Value::Var(var) => {
                if let Some((x, ty)) = vars.get(&var.index()) {
                    let prev = V {
                        e: quote!(#x),
                        ty: ty.clone(),
                    };
                    let same = identical(&prev, v)
                        .ok_or("a repeated id variable on values of another type")?;
                    steps.push(MatchStep::If(same));
                    return Ok(true);
                }
                let r = Self::nat_id_reg(d, j, path).ok_or("an id variable has no register")?;
                let ty = d.types[j].regs[r as usize].ty.clone();
                let x = format_ident!("f{}", r);
                // A part taken apart for this candidate (`h0`, `l0`,
                // `g0_1`: its own value, read once) moves into the field;
                // the selected value itself (`v0`) is read again by later
                // candidates and the fallback, so it is cloned.
                let from = V {
                    e: if is_selected_value(e) {
                        quote!(#e.clone())
                    } else {
                        quote!(#e)
                    },
                    ty: v.ty.clone(),
                };
                match coerce(&from, &ty) {
                    Ok(val) => steps.push(MatchStep::Let(x.clone(), val)),
                    Err(e) => match narrow(&from, &ty) {
                        Some(val) => steps.push(MatchStep::Narrow(x.clone(), val)),
                        None => return Err(e),
                    },
                }
                vars.insert(var.index(), (x, ty));
                Ok(true)
            }
            // A canonical `Val`: read by its variant.
            _ if held_as_val(&v.ty) => self.val_match(d, j, pat, v, path, vars, steps, n),
            // A ground term: read in the store.
            Value::Atom(a) if v.ty == Ty::Term => {
                let a = self.atom_native(a)?;
                steps.push(MatchStep::If(quote!(
                    cx.store_ref().atom_of(#e.0) == Some(#a)
                )));
                Ok(true)
            }
            Value::Int(i) if v.ty == Ty::Term => {
                let i = Literal::i64_suffixed(i);
                steps.push(MatchStep::If(quote!(
                    cx.store_ref().int_of(#e.0) == Some(#i)
                )));
                Ok(true)
            }
            Value::Compound(name, args) if v.ty == Ty::Term => {
                let args = args.to_vec();
                let f = if name == atoms::DOT {
                    quote!(atoms::DOT)
                } else {
                    self.atom_native(name)?
                };
                let xs = arg_idents(n, args.len());
                let arity = Literal::usize_unsuffixed(args.len());
                steps.push(MatchStep::Args(quote!(#e), f, arity, xs.clone()));
                let parts = args.iter().zip(&xs).map(|(&a, x)| {
                    (
                        a,
                        V {
                            e: quote!(#x),
                            ty: Ty::Term,
                        },
                    )
                });
                self.match_parts(d, j, parts, path, vars, steps, n)
            }
            Value::Atom(a) if a == atoms::NIL => match &v.ty {
                Ty::List(_) => {
                    steps.push(MatchStep::Empty(quote!(#e)));
                    Ok(true)
                }
                Ty::Sym => {
                    steps.push(MatchStep::If(quote!(#e == atoms::NIL)));
                    Ok(true)
                }
                _ => Ok(false),
            },
            Value::Atom(a) => match &v.ty {
                Ty::Sym => {
                    let a = self.atom_native(a)?;
                    steps.push(MatchStep::If(quote!(#e == #a)));
                    Ok(true)
                }
                _ => Ok(false),
            },
            Value::Int(i) => match &v.ty {
                Ty::Int => {
                    let i = Literal::i64_suffixed(i);
                    steps.push(MatchStep::If(quote!(#e == #i)));
                    Ok(true)
                }
                Ty::Float => Err("an int pattern on a float".into()),
                _ => Ok(false),
            },
            Value::Compound(name, args) if name == atoms::DOT && args.len() == 2 => {
                let (h, t) = (args[0], args[1]);
                match &v.ty {
                    Ty::List(elem) if **elem == Ty::Never => Ok(false),
                    Ty::List(_) if self.nat_cell_at(d, j, path, &v.ty) => {
                        let x = self.nat_cell_step(d, j, v, false, steps);
                        self.nat_cell_vars(h, t, x, &v.ty, vars);
                        Ok(true)
                    }
                    Ty::List(elem) => {
                        let hx = format_ident!("h{}", *n);
                        let tx = format_ident!("l{}", *n);
                        *n += 1;
                        steps.push(MatchStep::Split(quote!(#e), hx.clone(), tx.clone()));
                        let hv = V {
                            e: quote!(#hx),
                            ty: (**elem).clone(),
                        };
                        let tv = V {
                            e: quote!(#tx),
                            ty: v.ty.clone(),
                        };
                        self.match_parts(d, j, [(h, hv), (t, tv)], path, vars, steps, n)
                    }
                    Ty::Sym | Ty::Int => Ok(false),
                    _ => Err("a list pattern on a value that is not native".into()),
                }
            }
            Value::Compound(..) => match &v.ty {
                Ty::Sym | Ty::Int | Ty::List(_) => Ok(false),
                _ => Err("a compound pattern is not native yet".into()),
            },
            _ => Err("an id pattern holds a constant that is not native".into()),
        }
    }
}

impl Gen<'_> {
    /// Whether the list pattern at `path` of situation `j`'s id is its
    /// [`CellField`], for a list of type `ty`.
    fn nat_cell_at(&self, d: &Dm, j: usize, path: &[usize], ty: &Ty) -> bool {
        self.nat_cell(d, j)
            .is_some_and(|c| c.path == path && c.ty == *ty)
    }

    /// [`MatchStep::Cell`] of `v` for situation `j`: its variable.
    fn nat_cell_step(
        &self,
        d: &Dm,
        j: usize,
        v: &V,
        val: bool,
        steps: &mut Vec<MatchStep>,
    ) -> Ident {
        let k = self
            .nat_cell(d, j)
            .map_or_else(|| format_ident!("k"), |c| c.name());
        let x = format_ident!("f{}", k);
        let e = &v.e;
        let movable = d.movable.borrow();
        let take = match movable.as_ref() {
            Some((text, r, Some(c))) if *text == e.to_string() => {
                if *c == j {
                    quote!(&#r)
                } else {
                    quote!(#r.clone())
                }
            }
            Some((text, r, None)) if *text == e.to_string() => quote!(#r),
            _ if is_selected_value(e) => quote!(#e.clone()),
            _ => quote!(#e),
        };
        steps.push(MatchStep::Cell(quote!(#e), x.clone(), take, val));
        x
    }
}

/// The visit's own cell tail `r` taken by move (`let fk = r;`, a
/// [`MatchStep::Cell`]) only where nothing after it in the candidate can
/// fail: a later test that fails (another list of the id walked in step,
/// `step([X|Xs], [Y|Ys], Acc)`) falls through to the next candidate or the
/// hand-over, which read `r` again. The step goes after the candidate's
/// last test (the tests are pure, their order is not observable; the step
/// tests only that the list is not empty and binds its variable), so the
/// move is on the path that builds the variant only; where a test after it
/// reads its variable, the register is cloned instead.
fn defer_move(steps: &mut Vec<MatchStep>, r: &Ident) {
    let take = quote!(#r).to_string();
    let Some(k) = steps
        .iter()
        .position(|s| matches!(s, MatchStep::Cell(_, _, t, false) if t.to_string() == take))
    else {
        return;
    };
    let Some(last) = steps
        .iter()
        .rposition(|s| !matches!(s, MatchStep::Let(..)))
        .filter(|&last| last > k)
    else {
        return;
    };
    let MatchStep::Cell(_, x, ..) = &steps[k] else {
        return;
    };
    if steps[k + 1..=last].iter().any(|s| s.mentions(x)) {
        if let MatchStep::Cell(_, _, t, _) = &mut steps[k] {
            *t = quote!(#r.clone());
        }
    } else {
        let s = steps.remove(k);
        steps.insert(last, s);
    }
}

impl Gen<'_> {
    /// The variables of a cell's pattern `[H|T]`: `T` the list (`x`), `H`
    /// bound with it (read in place by the visit, no value here).
    fn nat_cell_vars(
        &self,
        h: Term,
        t: Term,
        x: Ident,
        ty: &Ty,
        vars: &mut HashMap<u32, (Ident, Ty)>,
    ) {
        for (p, name) in [(h, format_ident!("{}_head", x)), (t, x)] {
            if let Value::Var(var) = self.store.value(p) {
                vars.insert(var.index(), (name, ty.clone()));
            }
        }
    }

    /// [`Gen::native_match`] of each part `k` (pattern, value) at `path`
    /// extended by `k`, in order; `false` as soon as one cannot match.
    #[allow(clippy::too_many_arguments)]
    fn match_parts(
        &self,
        d: &Dm,
        j: usize,
        parts: impl IntoIterator<Item = (Term, V)>,
        path: &mut Vec<usize>,
        vars: &mut HashMap<u32, (Ident, Ty)>,
        steps: &mut Vec<MatchStep>,
        n: &mut usize,
    ) -> N<bool> {
        for (k, (p, v)) in parts.into_iter().enumerate() {
            path.push(k);
            let ok = self.native_match(d, j, p, &v, path, vars, steps, n)?;
            path.pop();
            if !ok {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// [`Gen::native_match`] on a value held as a canonical `Val` (type
    /// `ground` or a fixed-shape compound): the pattern is not a variable.
    #[allow(clippy::too_many_arguments)]
    fn val_match(
        &self,
        d: &Dm,
        j: usize,
        pat: Term,
        v: &V,
        path: &mut Vec<usize>,
        vars: &mut HashMap<u32, (Ident, Ty)>,
        steps: &mut Vec<MatchStep>,
        n: &mut usize,
    ) -> N<bool> {
        let e = &v.e;
        let some = quote!(Some);
        let tagged = match &v.ty {
            Ty::Tagged(name, args) => Some((*name, args.len())),
            _ => None,
        };
        match self.store.value(pat) {
            Value::Atom(a) if a == atoms::NIL => {
                steps.push(MatchStep::If(quote!(#e.is_nil())));
                Ok(true)
            }
            Value::Atom(a) => {
                let a = self.atom_native(a)?;
                steps.push(MatchStep::If(quote!((#e.sym() == #some(#a)))));
                Ok(true)
            }
            Value::Int(i) => {
                let i = Literal::i64_suffixed(i);
                steps.push(MatchStep::If(quote!((#e.int() == #some(#i)))));
                Ok(true)
            }
            Value::Compound(name, args) if name == atoms::DOT && args.len() == 2 => {
                if tagged.is_some() {
                    return Ok(false);
                }
                let (h, t) = (args[0], args[1]);
                let hx = format_ident!("h{}", *n);
                let tx = format_ident!("l{}", *n);
                *n += 1;
                // A tail the situation holds as a list (`Ps` of `[P|Ps]`,
                // narrowed by `mir::ty`): split as a proper list.
                let tail_list = matches!(self.store.value(t), Value::Var(_)) && {
                    path.push(1);
                    let r = Self::nat_id_reg(d, j, path);
                    path.pop();
                    r.and_then(|r| d.types[j].regs.get(r as usize))
                        .is_some_and(|x| x.ty == Ty::list(Ty::Ground))
                };
                let list = Ty::list(Ty::Ground);
                if tail_list && self.nat_cell_at(d, j, path, &list) {
                    let x = self.nat_cell_step(d, j, v, true, steps);
                    self.nat_cell_vars(h, t, x, &list, vars);
                    return Ok(true);
                }
                let tail_ty = if tail_list {
                    steps.push(MatchStep::SplitValList(quote!(#e), hx.clone(), tx.clone()));
                    Ty::list(Ty::Ground)
                } else {
                    steps.push(MatchStep::SplitVal(quote!(#e), hx.clone(), tx.clone()));
                    Ty::Ground
                };
                let parts = [(h, hx, Ty::Ground), (t, tx, tail_ty)]
                    .map(|(p, x, ty)| (p, V { e: quote!(#x), ty }));
                self.match_parts(d, j, parts, path, vars, steps, n)
            }
            Value::Compound(name, args) => {
                if tagged.is_some_and(|t| t != (name, args.len())) {
                    return Ok(false);
                }
                let args = args.to_vec();
                let f = self.atom_native(name)?;
                let xs = arg_idents(n, args.len());
                let arity = Literal::usize_unsuffixed(args.len());
                steps.push(MatchStep::ArgsVal(quote!(#e), f, arity, xs.clone()));
                // Held as `Val`s inside the compound, whatever the type.
                let parts = args.iter().zip(&xs).map(|(&a, x)| {
                    (
                        a,
                        V {
                            e: quote!(#x),
                            ty: Ty::Ground,
                        },
                    )
                });
                self.match_parts(d, j, parts, path, vars, steps, n)
            }
            _ => Err("an id pattern holds a constant that is not native".into()),
        }
    }
}

/// A candidate's code: `code` (its `break 'sel`) inside its match steps,
/// the first outermost; a `let` in `inline` is written where it is read.
fn wrap_steps(
    steps: Vec<MatchStep>,
    inline: &HashMap<Ident, TokenStream>,
    mut code: TokenStream,
) -> TokenStream {
    for s in steps.into_iter().rev() {
        code = match s {
            MatchStep::If(c) => quote!(if #c { #code }),
            MatchStep::Empty(l) => quote!(if #l.is_empty() { #code }),
            MatchStep::Let(x, _) if inline.contains_key(&x) => code,
            MatchStep::Let(x, e) => quote!({ let #x = #e; #code }),
            MatchStep::Narrow(x, e) => quote! {{
                let Some(#x) = #e else { break 'hand; };
                #code
            }},
            MatchStep::Args(v, f, arity, xs) => quote! {
                if let Some(&[#(#xs),*]) =
                    cx.store_ref().compound_args(#v.0, #f, #arity)
                {
                    #(let #xs = Ground(#xs);)*
                    #code
                }
            },
            MatchStep::SplitVal(l, h, t) => quote! {
                if let Some((#h, #t)) = #l.split_list() {
                    #code
                }
            },
            MatchStep::SplitValList(l, h, t) => quote! {
                if let Some((#h, #t)) = #l.split_proper() {
                    #code
                } else if #l.is_cell() {
                    break 'hand;
                }
            },
            MatchStep::ArgsVal(v, f, arity, xs) => {
                // Each argument cloned where a field takes it, read in
                // place where only tests read it (no `let` a line).
                let mut lets = Vec::new();
                for x in &xs {
                    match read_in_place(&code, x) {
                        Some(c) => code = c,
                        None => lets.push(quote!(let #x = #x.clone();)),
                    }
                }
                quote! {
                    if let Some([#(#xs),*]) = #v.args_of(#f, #arity) {
                        #(#lets)*
                        #code
                    }
                }
            }
            MatchStep::Split(l, h, t) => match read_in_place(&code, &h) {
                Some(code) => quote! {
                    if let Some((#h, #t)) = #l.split_first() {
                        #code
                    }
                },
                None => quote! {
                    if let Some((#h, #t)) = #l.split_first() {
                        let #h = #h.clone();
                        #code
                    }
                },
            },
            MatchStep::Cell(l, x, take, false) => quote! {
                if !#l.is_empty() {
                    let #x = #take;
                    #code
                }
            },
            MatchStep::Cell(l, x, _, true) => quote! {
                if let Some(#x) = #l.non_empty_list() {
                    let #x = #x.clone();
                    #code
                } else if #l.is_cell() {
                    break 'hand;
                }
            },
        };
    }
    code
}

/// `code` reading `x`, a reference to a candidate's part (a list's head,
/// a compound's argument), without binding a clone of it first: `x` only
/// a receiver of `args_of` (a test that reads it in place), or mentioned
/// once as a field's value (`f: x`, then `f: x.clone()`, the clone made
/// only where the variant is built). `None`: `code` reads it otherwise.
fn read_in_place(code: &TokenStream, x: &Ident) -> Option<TokenStream> {
    use proc_macro2::TokenTree as T;
    fn receivers(toks: &[T], x: &Ident) -> bool {
        toks.iter().enumerate().all(|(k, t)| match t {
            T::Ident(i) if i == x => matches!(
                &toks[k + 1..],
                [T::Punct(dot), T::Ident(m), ..] if dot.as_char() == '.' && m == "args_of"
            ),
            T::Group(g) => receivers(&g.stream().into_iter().collect::<Vec<_>>(), x),
            _ => true,
        })
    }
    let toks: Vec<T> = code.clone().into_iter().collect();
    if receivers(&toks, x) {
        return Some(code.clone());
    }
    subst_at_field(code, x, &quote!(#x.clone()))
}

/// `code` with its one mention of `x`, a field's value (`f: x`), made `e`
/// (`None`: `x` is mentioned otherwise, or more than once).
fn subst_at_field(code: &TokenStream, x: &Ident, e: &TokenStream) -> Option<TokenStream> {
    use proc_macro2::{Group, Spacing, TokenTree as T};
    fn at_field(toks: Vec<T>, x: &Ident, e: &TokenStream, done: &mut bool) -> TokenStream {
        let mut out = TokenStream::new();
        for (k, t) in toks.iter().enumerate() {
            match t {
                T::Ident(i) if i == x => {
                    let colon = k > 0
                        && matches!(&toks[k - 1], T::Punct(c) if c.as_char() == ':' && c.spacing() == Spacing::Alone)
                        && !(k > 1 && matches!(&toks[k - 2], T::Punct(c) if c.as_char() == ':'));
                    let last = toks.get(k + 1).is_none()
                        || matches!(toks.get(k + 1), Some(T::Punct(c)) if c.as_char() == ',');
                    if colon && last {
                        *done = true;
                        out.extend(e.clone());
                    } else {
                        out.extend([t.clone()]);
                    }
                }
                T::Group(g) => {
                    let inner = at_field(g.stream().into_iter().collect(), x, e, done);
                    let mut ng = Group::new(g.delimiter(), inner);
                    ng.set_span(g.span());
                    out.extend([T::Group(ng)]);
                }
                _ => out.extend([t.clone()]),
            }
        }
        out
    }
    if pipe::mentions(code, x) != 1 {
        return None;
    }
    let mut done = false;
    let out = at_field(code.clone().into_iter().collect(), x, e, &mut done);
    done.then_some(out)
}

/// A `'sel` block's candidates (no candidate taking every value) without
/// the `else if v.is_cell() { break 'hand; }` that go where falling
/// through goes: after the last candidate the block's end is the
/// machine's selection, where `'hand` leads, so the last candidate's are
/// dropped; a candidate's outermost one is dropped where it and every later
/// candidate first split the same value (`v.split_proper()`,
/// `v.non_empty_list()`), which fails for an improper cell (`[a|b]`): none
/// of them can take it, so it falls through to the machine too.
fn drop_dead_hands(candidates: Vec<TokenStream>) -> Vec<TokenStream> {
    let firsts: Vec<Option<String>> = candidates.iter().map(first_split).collect();
    let last = candidates.len().saturating_sub(1);
    candidates
        .into_iter()
        .enumerate()
        .map(|(k, c)| match &firsts[k] {
            _ if k == last => strip_hand(c, None),
            Some(v) if firsts[k + 1..].iter().all(|f| f.as_ref() == Some(v)) => {
                strip_hand(c, Some(v))
            }
            _ => c,
        })
        .collect()
}

/// The value a candidate first splits, `v` of its outermost
/// `if let Some(..) = v.split_proper() { .. }` or
/// `if let Some(..) = v.non_empty_list() { .. }`.
fn first_split(c: &TokenStream) -> Option<String> {
    use proc_macro2::{Delimiter, TokenTree as T};
    let toks: Vec<T> = c.clone().into_iter().collect();
    let word = |k: usize, w: &str| matches!(toks.get(k), Some(T::Ident(i)) if i == w);
    if !(word(0, "if") && word(1, "let") && word(2, "Some")) {
        return None;
    }
    if !matches!(toks.get(4), Some(T::Punct(p)) if p.as_char() == '=') {
        return None;
    }
    let m = (5..toks.len()).find(|&k| word(k, "split_proper") || word(k, "non_empty_list"))?;
    if m <= 6 {
        // No receiver before the method (`toks[5..m - 1]` would be empty or reversed).
        return None;
    }
    let dot = matches!(&toks[m - 1], T::Punct(p) if p.as_char() == '.');
    let empty_call = matches!(toks.get(m + 1),
        Some(T::Group(g)) if g.delimiter() == Delimiter::Parenthesis && g.stream().is_empty());
    let body = matches!(toks.get(m + 2), Some(T::Group(g)) if g.delimiter() == Delimiter::Brace);
    let recv = &toks[5..m - 1];
    let plain = recv
        .iter()
        .all(|t| !matches!(t, T::Group(g) if g.delimiter() == Delimiter::Brace));
    (dot && empty_call && body && plain)
        .then(|| recv.iter().cloned().collect::<TokenStream>().to_string())
}

/// `c` without its `else if v.is_cell() { break 'hand; }`: every one, at
/// any depth (`None`), or only the outermost one, of value `v`.
fn strip_hand(c: TokenStream, only: Option<&String>) -> TokenStream {
    use proc_macro2::{Delimiter, Group, TokenTree as T};
    let toks: Vec<T> = c.into_iter().collect();
    let word = |k: usize, w: &str| matches!(toks.get(k), Some(T::Ident(i)) if i == w);
    let mut out = Vec::new();
    let mut k = 0;
    while k < toks.len() {
        if word(k, "else") && word(k + 1, "if") {
            let end = (k + 2..toks.len())
                .find(|&j| matches!(&toks[j], T::Group(g) if g.delimiter() == Delimiter::Brace));
            if let Some(j) = end {
                let test = &toks[k + 2..j];
                let breaks = matches!(&toks[j], T::Group(g)
                    if g.stream().to_string().replace(' ', "") == "break'hand;");
                let n = test.len();
                let is_cell = n >= 4
                    && matches!(&test[n - 3], T::Punct(p) if p.as_char() == '.')
                    && matches!(&test[n - 2], T::Ident(i) if i == "is_cell")
                    && matches!(&test[n - 1], T::Group(g) if g.stream().is_empty());
                let recv: TokenStream = test[..n.saturating_sub(3)].iter().cloned().collect();
                let of = only.is_none_or(|v| recv.to_string() == *v);
                if breaks && is_cell && of {
                    k = j + 1;
                    continue;
                }
            }
        }
        match &toks[k] {
            T::Group(g) if only.is_none() => {
                let mut h = Group::new(g.delimiter(), strip_hand(g.stream(), None));
                h.set_span(g.span());
                out.push(T::Group(h));
            }
            t => out.push(t.clone()),
        }
        k += 1;
    }
    out.into_iter().collect()
}

/// A selected value read by a method of its own type, `(*v<i>).m(..)`
/// ([`Gen::nat_select`]: `v<i>` a reference), as `v<i>.m(..)`: the
/// method found through the reference (inherent methods of `Val`,
/// `List`, and `clone`, which gives the value, not the reference).
fn deref_receivers(ts: &TokenStream) -> TokenStream {
    use proc_macro2::{Delimiter, Group, TokenTree as T};
    const METHODS: &[&str] = &[
        "clone",
        "is_empty",
        "split_first",
        "non_empty_list",
        "is_nil",
        "split_list",
        "split_proper",
        "is_cell",
        "args_of",
    ];
    let toks: Vec<T> = ts.clone().into_iter().collect();
    let mut out = TokenStream::new();
    for (k, t) in toks.iter().enumerate() {
        match t {
            T::Group(g) => {
                let inner: Vec<T> = g.stream().into_iter().collect();
                let receiver = g.delimiter() == Delimiter::Parenthesis
                    && matches!(inner.as_slice(), [T::Punct(star), T::Ident(v)]
                        if star.as_char() == '*' && is_selected_value(&quote!(#v)))
                    && matches!(&toks[k + 1..], [T::Punct(dot), T::Ident(m), ..]
                        if dot.as_char() == '.' && METHODS.iter().any(|x| m == x));
                if receiver {
                    out.extend([inner[1].clone()]);
                } else {
                    let mut ng = Group::new(g.delimiter(), deref_receivers(&g.stream()));
                    ng.set_span(g.span());
                    out.extend([T::Group(ng)]);
                }
            }
            _ => out.extend([t.clone()]),
        }
    }
    out
}

/// What a candidate of [`Gen::nat_select`] tests, for the pair `[]`,
/// `[H|T]` of one list (the place's text).
enum Shape {
    /// `[]` and `let`s; its code without the test.
    Empty(String, TokenStream),
    /// `[H|T]` and `let`s.
    Split(String),
    Other,
}

/// Fresh names `g{n}_{k}` for the `len` arguments of a compound matched
/// natively (`n` counts the matches of a situation).
/// Whether `e` is one of [`Gen::nat_select`]'s selected values `(*v<i>)`
/// (read by reference, shared by every candidate), not a part one candidate's steps took
/// apart (`h<n>`, `l<n>`, `g<n>_<k>`: owned by that candidate alone).
fn is_selected_value(e: &TokenStream) -> bool {
    let s = e.to_string();
    let s = s
        .strip_prefix("(* ")
        .and_then(|s| s.strip_suffix(')'))
        .unwrap_or(&s);
    s.strip_prefix('v')
        .is_some_and(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
}

fn arg_idents(n: &mut usize, len: usize) -> Vec<Ident> {
    let xs = (0..len).map(|k| format_ident!("g{}_{}", *n, k)).collect();
    *n += 1;
    xs
}

/// Prolog's `==` on two native values, when their types allow it in Rust
/// (ground terms compared in the store).
fn identical(l: &V, r: &V) -> Option<TokenStream> {
    let (le, re) = (&l.e, &r.e);
    // Compared where they are: no clone (a `Val`'s list or compound
    // count changed and changed back) to compare.
    let (lp, rp) = (place(l), place(r));
    let some = quote!(Some);
    match (&l.ty, &r.ty) {
        (a, b) if a == b && eq_safe(a) => Some(quote!((#lp == #rp))),
        // Canonical `Val`s and other native values as `Val`s.
        (a, b) if held_as_val(a) && held_as_val(b) => Some(quote!((#lp == #rp))),
        (Ty::Term, b) if held_as_val(b) => Some(quote!(#rp.identical_to(cx.store_ref(), #le.0))),
        (a, Ty::Term) if held_as_val(a) => Some(quote!(#lp.identical_to(cx.store_ref(), #re.0))),
        (a, b) if held_as_val(a) && b.is_native() && *b != Ty::Float => {
            let rv = coerce(r, &Ty::Ground).ok()?;
            Some(quote!((#le == #rv)))
        }
        (a, b) if held_as_val(b) && a.is_native() && *a != Ty::Float => {
            let lv = coerce(l, &Ty::Ground).ok()?;
            Some(quote!((#lv == #re)))
        }
        // Lists of different element types (`list<ground>`, a list a
        // pattern narrowed, against `[]` or `list<atom>`): as `Val`s.
        (Ty::List(_), Ty::List(_)) if l.ty.is_native() && r.ty.is_native() => {
            let lv = coerce(l, &Ty::Ground).ok()?;
            let rv = coerce(r, &Ty::Ground).ok()?;
            Some(quote!((#lv == #rv)))
        }
        (Ty::Term, Ty::Term) => Some(quote!(cx.store_ref().identical(#le.0, #re.0))),
        (Ty::Term, Ty::Sym) => Some(quote!((cx.store_ref().atom_of(#le.0) == #some(#re)))),
        (Ty::Sym, Ty::Term) => Some(quote!((cx.store_ref().atom_of(#re.0) == #some(#le)))),
        (Ty::Term, Ty::Int) => Some(quote!((cx.store_ref().int_of(#le.0) == #some(#re)))),
        (Ty::Int, Ty::Term) => Some(quote!((cx.store_ref().int_of(#re.0) == #some(#le)))),
        _ => None,
    }
}

/// `member(X, L)` (D-33) on two native values, when their types allow
/// it in Rust: whether `X` is an element of the proper list `L`. Native
/// values are ground, so unifying `X` with an element
/// (`builtins::member_unify`) is being identical to it
/// (`builtins::member_identical`, `not_member`'s test), as [`identical`]
/// compares; a `ground` value that is not a proper list (an improper
/// list, an atom) has no element, as `list_to_vec` finds none. A float
/// `X` or a term is left to the machine.
fn member_test(x: &V, l: &V) -> Option<TokenStream> {
    if !x.ty.is_native() || matches!(x.ty, Ty::Float | Ty::Term | Ty::Never) {
        return None;
    }
    let (xp, lp) = (place(x), place(l));
    match &l.ty {
        Ty::List(e) if **e == Ty::Never => Some(quote!(false)),
        Ty::List(e) if **e == x.ty && eq_safe(e) => Some(quote!(#lp.iter().any(|y| *y == #xp))),
        Ty::List(e) if held_as_val(e) => {
            let xv = coerce(x, &Ty::Ground).ok()?;
            Some(quote!({
                let member_x: Val = #xv;
                #lp.iter().any(|y| *y == member_x)
            }))
        }
        t if held_as_val(t) => {
            let xv = coerce(x, &Ty::Ground).ok()?;
            Some(quote!({
                let member_x: Val = #xv;
                matches!(#lp, Val::List(ref items) if items.iter().any(|y| *y == member_x))
            }))
        }
        _ => None,
    }
}

/// Whether code `ts` may leave before giving its value (a `return`, a
/// `?`): a read that enters the machine for its value or its error.
fn may_leave(ts: &TokenStream) -> bool {
    ts.clone().into_iter().any(|t| match t {
        proc_macro2::TokenTree::Ident(i) => i == "return",
        proc_macro2::TokenTree::Punct(p) => p.as_char() == '?',
        proc_macro2::TokenTree::Group(g) => may_leave(&g.stream()),
        _ => false,
    })
}

/// The place a value is read from, for reading it by reference: a
/// register or frame field `x` read as `x.clone()` is `x` itself (through
/// `Borrow`, whether the binding is the value or a reference to it), any
/// other value the expression's temporary.
fn place(v: &V) -> TokenStream {
    if let (Some(x), Ok(t)) = (moved_place(v), rust_ty(&v.ty)) {
        return quote!((*::std::borrow::Borrow::<#t>::borrow(&#x)));
    }
    let e = &v.e;
    quote!((#e))
}

/// The register or field `x` of a value read as `x.clone()` (as [`place`]
/// reads it by reference).
fn moved_place(v: &V) -> Option<Ident> {
    let ts: Vec<proc_macro2::TokenTree> = v.e.clone().into_iter().collect();
    if let [proc_macro2::TokenTree::Ident(x), proc_macro2::TokenTree::Punct(dot), proc_macro2::TokenTree::Ident(clone), proc_macro2::TokenTree::Group(g)] =
        ts.as_slice()
    {
        if dot.as_char() == '.'
            && clone == "clone"
            && g.delimiter() == proc_macro2::Delimiter::Parenthesis
            && g.stream().is_empty()
        {
            return Some(x.clone());
        }
    }
    None
}

/// A value read as `r<n>.clone()`, a register of the visit (an owned Rust
/// local), as a move of that local: for a use that is the visit's last.
fn moved(v: &V) -> TokenStream {
    let ts: Vec<proc_macro2::TokenTree> = v.e.clone().into_iter().collect();
    if let [proc_macro2::TokenTree::Ident(x), proc_macro2::TokenTree::Punct(dot), proc_macro2::TokenTree::Ident(clone), proc_macro2::TokenTree::Group(g)] =
        ts.as_slice()
    {
        let s = x.to_string();
        let is_reg = s
            .strip_prefix('r')
            .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()));
        if is_reg
            && dot.as_char() == '.'
            && clone == "clone"
            && g.delimiter() == proc_macro2::Delimiter::Parenthesis
            && g.stream().is_empty()
        {
            return quote!(#x);
        }
    }
    v.e.clone()
}

/// A register loaded from a frame's parameter or a callee's final field
/// (`let r3 = p1.clone();`) that the rest of its block reads only by
/// reference (`Borrow::<T>::borrow(&r3)`, as [`place`] prints it: a
/// comparison, a selected value) or clones (`r3.clone()`: a call's
/// argument) is bound to the value where it lies (`let r3 = &*p1;`,
/// `Borrow` and `clone` read through the reference): no clone and no drop
/// per visit. Parameters and a final's fields are not written while
/// a visit reads them.
/// How many lines prettyplease gives `stmts` as the body of a DM
/// module's function (indented as `nat_entry`'s).
fn lines_in_dm(stmts: &TokenStream) -> usize {
    let file = quote!(mod m { fn f() { #stmts } });
    match syn::parse2::<syn::File>(file) {
        Ok(f) => prettyplease::unparse(&f).lines().count(),
        Err(_) => usize::MAX,
    }
}

fn by_ref_loads(ts: TokenStream) -> TokenStream {
    use proc_macro2::{Group, TokenTree as T};
    let toks: Vec<T> = ts.into_iter().collect();
    let mut out = TokenStream::new();
    let mut i = 0;
    while i < toks.len() {
        // `let rN = X . clone ( ) ;`, X a parameter `p<n>` or a field `c<n>`.
        if let [T::Ident(l), T::Ident(r), T::Punct(eq), T::Ident(x), T::Punct(dot), T::Ident(clone), T::Group(g), T::Punct(semi), ..] =
            &toks[i..]
        {
            let numbered = |x: &Ident, pre: &[char]| {
                let s = x.to_string();
                s.strip_prefix(pre)
                    .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
            };
            let load = l == "let"
                && numbered(r, &['r'])
                && eq.as_char() == '='
                && numbered(x, &['p', 'c'])
                && dot.as_char() == '.'
                && clone == "clone"
                && g.delimiter() == proc_macro2::Delimiter::Parenthesis
                && g.stream().is_empty()
                && semi.as_char() == ';';
            if load && only_borrowed(&toks[i + 8..], r) {
                out.extend(quote!(let #r = &*#x;));
                i += 8;
                continue;
            }
            // Else where the rest reads it also as `&r` elsewhere (any use:
            // a reference is what it was, a hole, a term made of it): bound
            // so too, each such `&r` made `r` ([`refs_read_through`]).
            if load && only_refs(&toks[i + 8..], r) {
                out.extend(quote!(let #r = &*#x;));
                out.extend(by_ref_loads(refs_read_through(&toks[i + 8..], r)));
                return out;
            }
        }
        match &toks[i] {
            T::Group(g) => {
                let mut ng = Group::new(g.delimiter(), by_ref_loads(g.stream()));
                ng.set_span(g.span());
                out.extend([T::Group(ng)]);
            }
            t => out.extend([t.clone()]),
        }
        i += 1;
    }
    out
}

/// Whether every mention of `r` in `toks` is `borrow(&r)`, a selected
/// value's `let v<i>: &T = &r;` or `r.clone()` (through a reference, the
/// value it points at cloned); a field named
/// like it, `S3 { r3: .. }`, is not a mention.
fn only_borrowed(toks: &[proc_macro2::TokenTree], r: &Ident) -> bool {
    use proc_macro2::{Spacing, TokenTree as T};
    toks.iter().enumerate().all(|(k, t)| match t {
        T::Ident(x) if x == r => {
            let field = matches!(toks.get(k + 1), Some(T::Punct(c)) if c.as_char() == ':' && c.spacing() == Spacing::Alone)
                && !matches!(k.checked_sub(1).map(|j| &toks[j]), Some(T::Ident(l)) if l == "let");
            field || cloned_at(toks, k) || selected_at(toks, k)
        }
        T::Ident(_) => true,
        T::Group(g) => {
            let inner: Vec<T> = g.stream().into_iter().collect();
            let borrowed = matches!(inner.as_slice(), [T::Punct(amp), T::Ident(x)] if amp.as_char() == '&' && x == r)
                && k > 0
                && matches!(&toks[k - 1], T::Ident(b) if b == "borrow");
            borrowed || only_borrowed(&inner, r)
        }
        _ => true,
    })
}

/// [`only_borrowed`], or `&r` alone anywhere else (not `&&r`, `&mut r`,
/// `&r.f`): a place that takes a reference, which `r` bound by
/// reference is.
fn only_refs(toks: &[proc_macro2::TokenTree], r: &Ident) -> bool {
    use proc_macro2::{Spacing, TokenTree as T};
    toks.iter().enumerate().all(|(k, t)| match t {
        T::Ident(x) if x == r => {
            let field = matches!(toks.get(k + 1), Some(T::Punct(c)) if c.as_char() == ':' && c.spacing() == Spacing::Alone)
                && !matches!(k.checked_sub(1).map(|j| &toks[j]), Some(T::Ident(l)) if l == "let");
            field || cloned_at(toks, k) || selected_at(toks, k) || amp_alone(toks, k)
        }
        T::Group(g) => only_refs(&g.stream().into_iter().collect::<Vec<_>>(), r),
        _ => true,
    })
}

/// Whether the identifier at `toks[k]` is borrowed alone, `&x` (not
/// `&&x`, not `&x.f`).
fn amp_alone(toks: &[proc_macro2::TokenTree], k: usize) -> bool {
    use proc_macro2::TokenTree as T;
    let amp =
        |j: Option<usize>| matches!(j.map(|j| &toks[j]), Some(T::Punct(a)) if a.as_char() == '&');
    amp(k.checked_sub(1))
        && !amp(k.checked_sub(2))
        && !matches!(toks.get(k + 1), Some(T::Punct(d)) if d.as_char() == '.')
}

/// `toks` (which [`only_refs`] accepts for `r`) with `r` bound by
/// reference: each `&r` made `r`, but where [`only_borrowed`] reads it as
/// it is (`borrow(&r)`, a selected value's `let v<i>: &T = &r;`, whose
/// text the shared selections match: `select_fn`).
fn refs_read_through(toks: &[proc_macro2::TokenTree], r: &Ident) -> TokenStream {
    use proc_macro2::{Group, TokenTree as T};
    let mut out: Vec<T> = Vec::new();
    for (k, t) in toks.iter().enumerate() {
        match t {
            T::Ident(x) if x == r && amp_alone(toks, k) && !selected_at(toks, k) => {
                out.pop();
                out.push(t.clone());
            }
            T::Group(g) => {
                let inner: Vec<T> = g.stream().into_iter().collect();
                let borrowed = matches!(inner.as_slice(), [T::Punct(amp), T::Ident(x)] if amp.as_char() == '&' && x == r)
                    && matches!(k.checked_sub(1).map(|j| &toks[j]), Some(T::Ident(b)) if b == "borrow");
                if borrowed {
                    out.push(t.clone());
                } else {
                    let mut ng = Group::new(g.delimiter(), refs_read_through(&inner, r));
                    ng.set_span(g.span());
                    out.push(T::Group(ng));
                }
            }
            t => out.push(t.clone()),
        }
    }
    out.into_iter().collect()
}

/// The identifier at `toks[k]` borrowed as a selected value, `let v<i>:
/// &T = &x;` ([`Gen::nat_select`]; the type written, so a reference `x`
/// is read through by deref coercion).
fn selected_at(toks: &[proc_macro2::TokenTree], k: usize) -> bool {
    use proc_macro2::TokenTree as T;
    let punct = |j: usize, c: char| matches!(toks.get(j), Some(T::Punct(p)) if p.as_char() == c);
    if k < 2 || !punct(k - 1, '&') || !punct(k - 2, '=') || !punct(k + 1, ';') {
        return false;
    }
    // The statement's start: `let v<i> : & ..`.
    let Some(l) = toks[..k]
        .iter()
        .rposition(|t| matches!(t, T::Ident(i) if i == "let"))
    else {
        return false;
    };
    matches!(&toks[l + 1..k - 2], [T::Ident(v), T::Punct(c), T::Punct(a), ..]
        if c.as_char() == ':' && a.as_char() == '&' && is_selected_value(&quote!(#v)))
}

/// The identifier at `toks[k]` cloned there, `x.clone()` (not a field
/// `.x.clone()`).
fn cloned_at(toks: &[proc_macro2::TokenTree], k: usize) -> bool {
    use proc_macro2::TokenTree as T;
    matches!(
        &toks[k + 1..],
        [T::Punct(dot), T::Ident(c), T::Group(g), ..]
            if dot.as_char() == '.'
                && c == "clone"
                && g.delimiter() == proc_macro2::Delimiter::Parenthesis
                && g.stream().is_empty()
    ) && !matches!(k.checked_sub(1).map(|j| &toks[j]), Some(T::Punct(p)) if p.as_char() == '.')
}

/// A visit's code with a cell's head `h` (see [`CellField`]) read in
/// place: `None` when the code takes it by value (then it is cloned),
/// else the code with each `&h` made `h` (a reference already; `borrow`,
/// `clone` and `&dyn AsTerm` read through it).
fn cell_head(ts: &TokenStream, h: &Ident) -> Option<TokenStream> {
    use proc_macro2::{Group, TokenTree as T};
    fn ok(toks: &[T], h: &Ident) -> bool {
        toks.iter().enumerate().all(|(k, t)| match t {
            T::Ident(x) if x == h => {
                let prev = k.checked_sub(1).map(|j| &toks[j]);
                let field = matches!(toks.get(k + 1), Some(T::Punct(c)) if c.as_char() == ':' && c.spacing() == proc_macro2::Spacing::Alone)
                    && !matches!(prev, Some(T::Ident(l)) if l == "let");
                let by_ref = borrowed(toks, k);
                field || by_ref || cloned_at(toks, k)
            }
            T::Group(g) => ok(&g.stream().into_iter().collect::<Vec<_>>(), h),
            _ => true,
        })
    }
    /// `&h` alone (not `&&h`, not `&h.f`).
    fn borrowed(toks: &[T], k: usize) -> bool {
        let amp = |j: Option<usize>| matches!(j.map(|j| &toks[j]), Some(T::Punct(a)) if a.as_char() == '&');
        amp(k.checked_sub(1))
            && !amp(k.checked_sub(2))
            && !matches!(toks.get(k + 1), Some(T::Punct(d)) if d.as_char() == '.')
    }
    fn rewrite(toks: Vec<T>, h: &Ident) -> TokenStream {
        let mut out = Vec::new();
        for (k, t) in toks.iter().enumerate() {
            match t.clone() {
                T::Ident(x) if x == *h => {
                    if borrowed(&toks, k) {
                        out.pop();
                    }
                    out.push(T::Ident(x));
                }
                T::Group(g) => {
                    let mut ng =
                        Group::new(g.delimiter(), rewrite(g.stream().into_iter().collect(), h));
                    ng.set_span(g.span());
                    out.push(T::Group(ng));
                }
                t => out.push(t),
            }
        }
        out.into_iter().collect()
    }
    let toks: Vec<T> = ts.clone().into_iter().collect();
    ok(&toks, h).then(|| rewrite(toks, h))
}

/// `[h|t]` of native values.
fn cons(h: V, t: V) -> N<V> {
    let ty = match &t.ty {
        Ty::List(e) if **e == Ty::Never => Ty::list(h.ty.clone()),
        Ty::List(e) if **e == h.ty => t.ty.clone(),
        // Values of different shapes, each held as a `Val` or with a Rust
        // type of its own: a list of `Val`s (`[take(O, S), deliver(O)]`).
        Ty::List(e) if e.is_native() && h.ty.is_native() && **e != Ty::Term && h.ty != Ty::Term => {
            let ty = Ty::list(Ty::Ground);
            let head = coerce(&h, &Ty::Ground)?;
            let tail = coerce(&t, &ty)?;
            let r = rust_ty(&ty)?;
            return Ok(V {
                e: quote!(<#r>::cons(#head, #tail)),
                ty,
            });
        }
        // An atom or int among ground terms: its term.
        Ty::List(e) if **e == Ty::Term && matches!(h.ty, Ty::Sym | Ty::Int) => {
            let head = coerce(&h, &Ty::Term)?;
            return cons(
                V {
                    e: head,
                    ty: Ty::Term,
                },
                t,
            );
        }
        // A ground tail (`[O|Os]`, `Os` the rest of a `ground` value): a
        // list, or an improper one (`Val::cons`).
        Ty::Ground if h.ty.is_native() && h.ty != Ty::Term => {
            let head = coerce(&h, &Ty::Ground)?;
            let tail = t.e;
            return Ok(V {
                e: quote!(Val::cons(#head, #tail)),
                ty: Ty::Ground,
            });
        }
        _ => return Err(format!("`[_|_]` of {} and {}", h.ty, t.ty)),
    };
    let rt = ty.clone();
    let r = rust_ty(&rt)?;
    let tail = coerce(&t, &ty)?;
    let head = h.e;
    Ok(V {
        e: quote!(<#r>::cons(#head, #tail)),
        ty,
    })
}

/// `v`, held with a wider type, as a value of the narrower native type
/// `to` when it is one (an `Option` expression): a `Val` (`ground`) read
/// as an atom or an integer by its variant, a ground handle (`term`)
/// converted with the checked conversion. `None` when no check narrows
/// these types.
fn narrow(v: &V, to: &Ty) -> Option<TokenStream> {
    let e = &v.e;
    match (&v.ty, to) {
        (Ty::Ground, Ty::Sym) => Some(quote!((#e).sym())),
        (Ty::Ground, Ty::Int) => Some(quote!((#e).int())),
        (Ty::Ground, Ty::List(x)) if **x == Ty::Ground => Some(quote!((#e).into_list())),
        (Ty::Term, to) if to.is_native() && *to != Ty::Never => {
            let ty = rust_ty(to).ok()?;
            Some(quote!(<#ty as Native>::from_term(cx.store_ref(), (#e).0)))
        }
        _ => None,
    }
}

/// `v` as a value of type `to`.
fn coerce(v: &V, to: &Ty) -> N<TokenStream> {
    if v.ty == *to || same_rep(&v.ty, to) {
        return Ok(v.e.clone());
    }
    match (&v.ty, to) {
        (Ty::Never, _) => {
            let e = &v.e;
            Ok(quote!(match #e {}))
        }
        // A list of `Val`s is a `Val` as it is (shared, no copy).
        (Ty::List(e), Ty::Ground) if **e == Ty::Ground => {
            let e = &v.e;
            Ok(quote!(Val::List(#e)))
        }
        // A native value entering a `ground` register.
        (from, Ty::Ground) if from.is_native() => {
            let e = &v.e;
            Ok(quote!(IntoVal::into_val(#e)))
        }
        // Lists of native values as lists of `Val`s.
        (Ty::List(a), Ty::List(b)) if a.is_native() && held_as_val(b) && **b == Ty::Ground => {
            let e = &v.e;
            Ok(quote!(#e.to_vals()))
        }
        // A `Val` where a ground term is held: built in the store (inert:
        // it came from an inert term or from native values).
        (from, Ty::Term)
            if holds_val(from)
                || (from.is_native() && !matches!(from, Ty::Sym | Ty::Int | Ty::List(_))) =>
        {
            let ty = rust_ty(from)?;
            let e = &v.e;
            Ok(quote!(Ground(<#ty as Native>::to_term(&#e, cx.store()))))
        }
        // An empty list is an empty list of anything.
        (Ty::List(e), Ty::List(_)) if **e == Ty::Never => {
            let ty = rust_ty(to)?;
            let e = &v.e;
            if reads_only(e) {
                // Nothing to evaluate: a copy of a selected value or `[]`.
                return Ok(quote!(<#ty>::nil()));
            }
            Ok(quote!({ let _ = #e; <#ty>::nil() }))
        }
        // An immediate term of a native scalar, or `[]`.
        (Ty::Sym, Ty::Term) => {
            let e = &v.e;
            Ok(quote!(Ground(Term::atom(#e))))
        }
        (Ty::Int, Ty::Term) => {
            let e = &v.e;
            Ok(quote!(Ground(Term::int(#e))))
        }
        (Ty::List(e), Ty::Term) if **e == Ty::Never => {
            let e = &v.e;
            Ok(quote!({ let _ = #e; Ground(Term::NIL) }))
        }
        _ => Err(format!("a value of type {} where {} is expected", v.ty, to)),
    }
}

/// Whether expression `e` only reads: a name, a `clone()` of one, a
/// reference to one, `List::<Never>::nil()` (no call of `cx`, no `?`).
fn reads_only(e: &TokenStream) -> bool {
    use proc_macro2::{Delimiter, TokenTree as T};
    let mut after_name = false;
    e.clone().into_iter().all(|t| {
        let ok = match &t {
            T::Ident(i) => !matches!(i.to_string().as_str(), "cx" | "run" | "stack" | "p"),
            T::Punct(p) => matches!(p.as_char(), '.' | ':' | '<' | '>' | '&' | '*'),
            // A call with arguments (`f(x)`, `v.take(x)`) may do anything.
            T::Group(g) if g.delimiter() == Delimiter::Parenthesis && after_name => {
                g.stream().is_empty()
            }
            T::Group(g) => g.stream().is_empty() || reads_only(&g.stream()),
            T::Literal(_) => false,
        };
        after_name = matches!(&t, T::Ident(_)) || matches!(&t, T::Punct(p) if p.as_char() == '>');
        ok
    }) && {
        let text = e.to_string().replace(' ', "");
        let calls = text.matches("()").count();
        calls == text.matches(".clone()").count() + text.matches("::nil()").count()
    }
}

/// A checked conversion: the name it binds, the `Option` expression, what
/// is done with the value once all have converted.
type Check = (Ident, TokenStream, TokenStream);

/// The checked conversions `checks` in one `let .. else`, the `fallback`
/// (a block that returns) written once; then the stores.
fn checked(checks: Vec<Check>, fallback: &TokenStream) -> TokenStream {
    let names: Vec<&Ident> = checks.iter().map(|c| &c.0).collect();
    let exprs: Vec<&TokenStream> = checks.iter().map(|c| &c.1).collect();
    let stores: Vec<&TokenStream> = checks.iter().map(|c| &c.2).collect();
    match checks.len() {
        0 => quote!(),
        1 => quote! {
            let Some(#(#names)*) = #(#exprs)* else #fallback;
            #(#stores)*
        },
        _ => quote! {
            let (#(Some(#names)),*) = (#(#exprs),*) else #fallback;
            #(#stores)*
        },
    }
}

/// A global's `get` (`Cx::global_as`) or `inc` (`Cx::global_inc`) done by
/// native code, of Rust type `rt`; where the global does not hold such a
/// value the machine is entered (`enter`) and its `var_op` gives the value
/// or its error. A value native code cannot hold (a frame on terms stored
/// one the MIR's type does not allow: an unbound variable) ends in `cold`
/// where the code around can redo its work on terms (a condition the
/// machine evaluates, [`Gen::nat_next`]), else in an error.
fn global_op(
    method: TokenStream,
    rt: &TokenStream,
    namea: &TokenStream,
    opa: &TokenStream,
    enter: &TokenStream,
    cold: Option<TokenStream>,
) -> TokenStream {
    let cold = cold.unwrap_or_else(|| {
        quote! {
            return Err(cx.error(
                "a global's value native code cannot hold",
                arc_at,
            ))
        }
    });
    quote! {
        match cx.#method::<#rt>(#namea) {
            Some(v) => v,
            None => {
                #enter
                let t = cx.var_op_fresh(#opa, #namea, arc_at)?;
                match cx.to_native::<#rt>(t) {
                    Some(v) => v,
                    None => {
                        #cold
                    }
                }
            }
        }
    }
}
