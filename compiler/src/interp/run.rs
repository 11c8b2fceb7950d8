//! Running plans: a [`SitPlan`] executed over the runtime's `Cx` steps
//! (build, evaluate, test, choose the arc, go on to the next situation),
//! the same steps in the same order as the generated code.

use super::*;

pub(super) type Rcx<'c, 'a, 'p, 'ir> = &'c mut Cx<'a, 'p, Resolved<'ir>>;

/// Results inside a visit: the error boxed, so that the values passed up
/// the tree of steps stay small.
pub(super) type R<T> = Result<T, Box<RunError>>;

pub(super) fn build(cx: Rcx<'_, '_, '_, '_>, regs: &[Term], b: &Build) -> Term {
    match b {
        Build::Const(t) => *t,
        Build::Reg(r) => regs[*r as usize],
        Build::Compound(name, args) => {
            let mut buf = [Term::NIL; 8];
            if args.len() <= buf.len() {
                for (slot, a) in buf.iter_mut().zip(args.iter()) {
                    *slot = build(cx, regs, a);
                }
                cx.compound(*name, &buf[..args.len()])
            } else {
                let values: Vec<Term> = args.iter().map(|a| build(cx, regs, a)).collect();
                cx.compound(*name, &values)
            }
        }
    }
}

pub(super) fn ev(
    cx: Rcx<'_, '_, '_, '_>,
    regs: &mut [Term],
    e: &Ev,
    arc: Option<usize>,
) -> R<Term> {
    match e {
        Ev::Value(r) => {
            // What `Cx::value` does: a compound is evaluated, anything else
            // is its own value.
            let store = cx.store();
            let t = store.deref(regs[*r as usize]);
            if store.is_compound(t) {
                Ok(cx.eval(t, arc)?)
            } else {
                Ok(t)
            }
        }
        Ev::Built(b) => Ok(build(cx, regs, b)),
        Ev::Eval(b) => {
            let t = build(cx, regs, b);
            Ok(cx.eval(t, arc)?)
        }
        Ev::If(c, then, other) => {
            if cond(cx, regs, c, arc)? {
                ev(cx, regs, then, arc)
            } else {
                ev(cx, regs, other, arc)
            }
        }
        Ev::Pick(c, then, other) => {
            let holds = cond(cx, regs, c, arc)?;
            let a = ev(cx, regs, then, arc)?;
            let b = ev(cx, regs, other, arc)?;
            Ok(if holds { a } else { b })
        }
        Ev::VarOpFresh { op, name, dst } => {
            // `inc` of a local integer that does not overflow: what
            // `var_op_fresh` does, without its general path.
            if *op == atoms::INC {
                let next = cx
                    .local(*name)
                    .and_then(|cur| cx.int_of(cur))
                    .and_then(|i| i.checked_add(1));
                if let Some(n) = next {
                    let v = Term::int(n);
                    cx.set_local(*name, v);
                    regs[*dst as usize] = v;
                    return Ok(v);
                }
            }
            let v = cx.var_op_fresh(*op, *name, arc)?;
            regs[*dst as usize] = v;
            Ok(v)
        }
        Ev::VarOp { op, name, arg } => {
            let a = build(cx, regs, arg);
            Ok(cx.var_op(*op, *name, a, arc)?)
        }
        Ev::IsFresh { expr, dst } => {
            let x = build(cx, regs, expr);
            let v = cx.is(None, x, arc)?;
            regs[*dst as usize] = v;
            Ok(v)
        }
        Ev::BindFresh { expr, dst } => {
            let v = build(cx, regs, expr);
            regs[*dst as usize] = v;
            Ok(v)
        }
        Ev::Is { lhs, expr } => {
            let x = build(cx, regs, expr);
            let l = build(cx, regs, lhs);
            Ok(cx.is(Some(l), x, arc)?)
        }
        Ev::Compound(name, args) => {
            let mut buf = [Term::NIL; 8];
            if args.len() <= buf.len() {
                for (i, a) in args.iter().enumerate() {
                    buf[i] = ev(cx, regs, a, arc)?;
                }
                Ok(cx.compound(*name, &buf[..args.len()]))
            } else {
                let mut values = Vec::with_capacity(args.len());
                for a in args.iter() {
                    values.push(ev(cx, regs, a, arc)?);
                }
                Ok(cx.compound(*name, &values))
            }
        }
    }
}

pub(super) fn cond(
    cx: Rcx<'_, '_, '_, '_>,
    regs: &mut [Term],
    c: &Cond,
    arc: Option<usize>,
) -> R<bool> {
    match c {
        Cond::Arith(op, l, r) => {
            let l = ev(cx, regs, l, arc)?;
            let r = ev(cx, regs, r, arc)?;
            // Two integers compare as integers (what the runtime's
            // comparison does with them).
            if let (Some(a), Some(b)) = (cx.int_of(l), cx.int_of(r)) {
                return Ok(int_cmp(*op, a, b));
            }
            Ok(cx.arith_condition(*op, l, r, arc)?)
        }
        Cond::Other(b) => {
            let t = build(cx, regs, b);
            Ok(cx.condition(t, arc)?)
        }
        Cond::Cmp(op, l, r) => {
            // Each operand's value as a variable's occurrence has it (a
            // compound evaluated), then compared (`Cx::compare_value`).
            let (lw, rw) = (build(cx, regs, l), build(cx, regs, r));
            let l = ev_written(cx, lw, arc)?;
            let r = ev_written(cx, rw, arc)?;
            if let (Some(a), Some(b)) = (cx.int_of(l), cx.int_of(r)) {
                return Ok(int_cmp(*op, a, b));
            }
            Ok(cx.compare_value(*op, [lw, rw], [l, r], arc)?)
        }
        Cond::And(l, r) | Cond::Or(l, r) => {
            // Both operands computed, left first (D-35), then combined.
            let l = junction_leaf(cx, regs, l, arc)?;
            let r = junction_leaf(cx, regs, r, arc)?;
            Ok(if matches!(c, Cond::And(..)) {
                l && r
            } else {
                l || r
            })
        }
    }
}

/// An operand of [`Cond::And`]/[`Cond::Or`]: whether its value is
/// `true` (`Cx::value_holds` on the operand as written: the evaluator's
/// value, its error the condition's); a comparison of two registers or
/// constants holding ints compared here.
fn junction_leaf(
    cx: Rcx<'_, '_, '_, '_>,
    regs: &mut [Term],
    c: &Cond,
    arc: Option<usize>,
) -> R<bool> {
    // A type test holds where its goal does (`mir::is_type_test`).
    if let Cond::Other(b) = c {
        if crate::mir::is_type_test(b) {
            let t = build(cx, regs, b);
            return Ok(cx.condition(t, arc)?);
        }
    }
    if let Cond::Cmp(op, l, r) = c {
        let (l, r) = (build(cx, regs, l), build(cx, regs, r));
        if let (Some(a), Some(b)) = (cx.int_of(l), cx.int_of(r)) {
            return Ok(int_cmp(*op, a, b));
        }
    }
    match c.written() {
        Some(w) if !matches!(c, Cond::And(..) | Cond::Or(..)) => {
            let t = build(cx, regs, &w);
            Ok(cx.value_holds(t, arc)?)
        }
        _ => cond(cx, regs, c, arc),
    }
}

/// `a op b` on two integers (what the runtime's comparison does with them).
fn int_cmp(op: ArithCmp, a: i64, b: i64) -> bool {
    match op {
        ArithCmp::Eq => a == b,
        ArithCmp::Ne => a != b,
        ArithCmp::Lt => a < b,
        ArithCmp::Gt => a > b,
        ArithCmp::Le => a <= b,
        ArithCmp::Ge => a >= b,
    }
}

/// The value of a term as written where a variable occurs (`Ev::Value`).
fn ev_written(cx: Rcx<'_, '_, '_, '_>, t: Term, arc: Option<usize>) -> R<Term> {
    let store = cx.store();
    let t = store.deref(t);
    if store.is_compound(t) {
        Ok(cx.eval(t, arc)?)
    } else {
        Ok(t)
    }
}

pub(super) fn next(
    cx: Rcx<'_, '_, '_, '_>,
    regs: &mut [Term],
    n: &Next,
    arc: Option<usize>,
) -> R<(Term, Option<SitIx>)> {
    match n {
        Next::Static(t, ix) => Ok((*t, *ix)),
        Next::If(c, then, other) => {
            if cond(cx, regs, c, arc)? {
                next(cx, regs, then, arc)
            } else {
                next(cx, regs, other, arc)
            }
        }
        Next::Eval(e) => Ok((ev(cx, regs, e, arc)?, None)),
    }
}

/// Runs `f` with the registers of one visit (on the stack when few).
#[inline]
pub(super) fn with_regs<T>(n: usize, f: impl FnOnce(&mut [Term]) -> T) -> T {
    if n <= 8 {
        let mut regs = [Term::NIL; 8];
        f(&mut regs[..n])
    } else if n <= STACK_REGS {
        let mut regs = [Term::NIL; STACK_REGS];
        f(&mut regs[..n])
    } else {
        f(&mut vec![Term::NIL; n])
    }
}

pub(super) fn run_plan(p: &SitPlan, cx: Rcx<'_, '_, '_, '_>, regs: &mut [Term]) -> R<Step> {
    let mut id = Term::NIL;
    if let Some(parts) = &p.compound_id {
        id = match cx.selected() {
            Some(value) => value,
            None => {
                let mut values = Vec::with_capacity(parts.len());
                for part in parts {
                    values.push(match part {
                        IdPart::Fresh(r) => {
                            let v = cx.var();
                            regs[*r as usize] = v;
                            v
                        }
                        IdPart::Const(t) => *t,
                    });
                }
                let id = cx.compound(p.id.0, &values);
                cx.set_id(id);
                id
            }
        };
    }
    if let Some(pat) = &p.pattern {
        id = match cx.selected() {
            Some(value) => value,
            None => {
                for &r in &pat.fresh {
                    regs[r as usize] = cx.var();
                }
                let id = build(cx, regs, &pat.build);
                cx.set_id(id);
                id
            }
        };
    }
    for (r, init) in &p.inits {
        regs[*r as usize] = match init {
            Init::IdArg(i) => cx.arg(id, *i),
            Init::IdPath(path) => path.iter().fold(id, |t, &i| cx.arg(t, i)),
            Init::HeadArg(i) => cx.head_arg(*i),
            Init::HeadPath(i, path) => cx.head_part(*i, path),
            Init::Pipe => cx.pipe(),
            Init::Fresh => cx.var(),
        };
    }
    for &(r, i) in &p.links {
        cx.link_head_arg(regs[r as usize], i);
    }
    let mut links: [Option<Term>; 2] = [None, None];
    let mut n_links = 0;
    if let Some((b, unify, r)) = &p.in_arg {
        let pattern = build(cx, regs, b);
        regs[*r as usize] = pattern;
        if *unify {
            cx.in_arg(pattern)?;
        }
        links[n_links] = Some(pattern);
        n_links += 1;
    }
    if let Some((b, r)) = &p.out_arg {
        let o = build(cx, regs, b);
        regs[*r as usize] = o;
        links[n_links] = Some(o);
        n_links += 1;
    }
    match &p.prog {
        None => {}
        Some(Prog::InPlace(parts)) => {
            for part in parts {
                ev(cx, regs, part, None)?;
            }
        }
        Some(Prog::Copy(b)) => {
            let t = build(cx, regs, b);
            cx.prog(t, &links[..n_links])?;
        }
    }
    match &p.kind {
        KindPlan::Final { diag_mod } => {
            cx.final_out_arg(p.out_arg.as_ref().map(|(_, r)| regs[*r as usize]))?;
            if let Some(d) = diag_mod {
                let d = build(cx, regs, d);
                cx.diag_mod(d)?;
            }
            let empty = Term::atom(atoms::EMPTY);
            cx.record(empty, empty, None);
            Ok(Step::Final)
        }
        KindPlan::Perceptual(arcs) => run_arcs(arcs, cx, regs, None),
        KindPlan::Recursive {
            call,
            eval_call,
            saved,
            ..
        } => {
            let e = build(cx, regs, call);
            let call = if *eval_call { cx.embedded_dm(e)? } else { e };
            let saved = if saved.is_empty() {
                Term::NIL
            } else {
                let values: Vec<Term> = saved.iter().map(|&r| regs[r as usize]).collect();
                cx.compound(atoms::DOT, &values)
            };
            Ok(Step::Call { call, saved })
        }
    }
}

pub(super) fn run_arcs(
    a: &Arcs,
    cx: Rcx<'_, '_, '_, '_>,
    regs: &mut [Term],
    final_id: Option<Term>,
) -> R<Step> {
    for arc in &a.arcs {
        for &r in &arc.fresh {
            regs[r as usize] = cx.var();
        }
        if !arc.import_from.is_empty() {
            let at = arc.import_at as usize;
            for (n, &src) in arc.import_from.iter().enumerate() {
                regs[at + n] = regs[src as usize];
            }
            cx.import(&mut regs[at..at + arc.import_from.len()]);
        }
    }
    let exps = a.exps as usize;
    let n = a.arcs.len();
    if a.pure {
        for (i, arc) in a.arcs.iter().enumerate() {
            regs[exps + i] = ev(cx, regs, &arc.expectation, Some(i))?;
        }
    } else {
        cx.save_vars();
        let mut result = Ok(());
        for (i, arc) in a.arcs.iter().enumerate() {
            match ev(cx, regs, &arc.expectation, Some(i)) {
                Ok(v) => regs[exps + i] = v,
                Err(e) => {
                    result = Err(e);
                    break;
                }
            }
        }
        cx.restore_vars();
        result?;
    }
    let chosen = if a.always_first {
        0
    } else {
        cx.set_expectations(&regs[exps..exps + n]);
        match final_id {
            Some(final_id) => cx.choose_exit(final_id)?,
            None => {
                let type_term = build(cx, regs, &a.type_term);
                match cx.choose(type_term)? {
                    Some(i) => i,
                    None => return Ok(Step::Unmet { type_term }),
                }
            }
        }
    };
    let arc = &a.arcs[chosen];
    let at = Some(chosen);
    let action = match &arc.action {
        Action::List { items, regs: base } => {
            let base = *base as usize;
            for (i, item) in items.iter().enumerate() {
                regs[base + i] = ev(cx, regs, item, at)?;
            }
            let values = &regs[base..base + items.len()];
            if cx.ignores_numbers() {
                // Performing a number does nothing: only the others.
                for &x in values {
                    if cx.int_of(x).is_none() && cx.float_of(x).is_none() {
                        cx.perform_each(&[x], at)?;
                    }
                }
            } else {
                cx.perform_each(values, at)?;
            }
            if cx.records() {
                cx.store().list(values)
            } else {
                Term::NIL
            }
        }
        Action::One(e) => {
            let action = ev(cx, regs, e, at)?;
            // Performing a number does nothing when the actions ignore numbers.
            let number = cx.int_of(action).is_some() || cx.float_of(action).is_some();
            if !(number && cx.ignores_numbers()) {
                cx.perform(action, at)?;
            }
            action
        }
    };
    let (next_value, target) = next(cx, regs, &arc.next, at)?;
    if let Some(o) = &arc.out_arg {
        let o = ev(cx, regs, o, at)?;
        cx.out_value(o);
    }
    if let Some(d) = &arc.diag_mod {
        let d = build(cx, regs, d);
        cx.diag_mod(d)?;
    }
    cx.record(regs[exps + chosen], action, Some(next_value));
    match target {
        Some(ix) => Ok(Step::GotoSit(ix)),
        None => Ok(cx.goto(next_value, at)?),
    }
}
