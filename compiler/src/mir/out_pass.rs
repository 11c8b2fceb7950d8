//! Whether an out_arg sets the pipe (issue 37, helper `ngauge25`): D-18
//! says the outgoing pipe is the incoming one when the out_arg's copy is
//! an unbound variable. Decided here, on the MIR, once for both back ends:
//!
//! - an arc's out_arg that is a variable of the arc's own (a fresh
//!   register of [`ArcPlan::fresh`]: renamed apart with the arc, D-11, not
//!   the situation's, nor made by a `get`/`inc`/`is` of the arc) that
//!   nothing of the arc names besides (not its expectation, which
//!   matching binds; not its action, whose evaluation, a boundary or the
//!   robot may bind it; not its next situation, whose selection unifies
//!   the value with the id of the situation it names, D-21) is unbound
//!   on every path: the pipe passes on unchanged, as without an out_arg
//!   ([`OutPass::Unchanged`]);
//! - a final's out_arg that is a variable no part of the situation other
//!   than `diag_mod` names (a fresh variable of the visit: not the id's,
//!   a parameter, the in_arg's, nor one its `prog` binds) is the same
//!   (`diag_mod` is unified after the pipe is set, D-20).
//!
//! Anything else is [`OutPass::Value`]: the value is computed (a back end
//! that holds the variable as a term decides at run time, `Cx::out_value`:
//! an unbound one passes the pipe on). Invariant: `Unchanged` only where
//! no evaluation order of the situation can bind the variable before the
//! out_arg is read.

use super::ty::{build_mentions, cond_mentions, ev_mentions};
use super::{Action, ArcPlan, Build, Ev, Init, Next, Prog, SitPlan};

/// What an out_arg does to the pipe.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutPass {
    /// Its value (computed as written) becomes the pipe, unless it is a
    /// variable at run time (D-18).
    Value,
    /// A variable nothing binds: the pipe passes on unchanged.
    Unchanged,
}

impl ArcPlan {
    /// What this arc's out_arg does to the pipe (the module doc); `Value`
    /// when it has none.
    pub fn out_pass(&self) -> OutPass {
        let Some(Ev::Value(r)) = &self.out_arg else {
            return OutPass::Value;
        };
        let r = *r;
        if !self.fresh.contains(&r) {
            return OutPass::Value;
        }
        let items: &[Ev] = match &self.action {
            Action::List { items, .. } => items,
            Action::One(e) => std::slice::from_ref(e),
        };
        let named = ev_mentions(&self.expectation, r, 0)
            || items.iter().any(|e| ev_mentions(e, r, 0))
            || next_mentions(&self.next, r, 0)
            || self
                .diag_mod
                .as_ref()
                .is_some_and(|b| build_mentions(b, r, 0));
        if named {
            OutPass::Value
        } else {
            OutPass::Unchanged
        }
    }
}

impl SitPlan {
    /// What a final situation's out_arg ([`SitPlan::out_arg`]) does to the
    /// pipe (the module doc); `Value` when it has none.
    pub fn final_out_pass(&self) -> OutPass {
        let Some((Build::Reg(r), _)) = &self.out_arg else {
            return OutPass::Value;
        };
        let r = *r;
        let fresh = self
            .inits
            .iter()
            .any(|(x, i)| *x == r && matches!(i, Init::Fresh));
        if !fresh {
            return OutPass::Value;
        }
        let in_arg = self
            .in_arg
            .as_ref()
            .is_some_and(|(b, _, _)| build_mentions(b, r, 0));
        let prog = match &self.prog {
            None => false,
            Some(Prog::InPlace(evs)) => evs.iter().any(|e| ev_mentions(e, r, 0)),
            Some(Prog::Copy(b)) => build_mentions(b, r, 0),
        };
        if in_arg || prog {
            OutPass::Value
        } else {
            OutPass::Unchanged
        }
    }
}

/// Whether next situation `n` names register `r`.
fn next_mentions(n: &Next, r: super::Reg, depth: usize) -> bool {
    if depth > super::MAX_DEPTH {
        return true;
    }
    match n {
        Next::Static(..) => false,
        Next::If(c, a, b) => {
            cond_mentions(c, r, depth + 1)
                || next_mentions(a, r, depth + 1)
                || next_mentions(b, r, depth + 1)
        }
        Next::Eval(e) => ev_mentions(e, r, depth + 1),
    }
}
