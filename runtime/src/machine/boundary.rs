//! A user function, the KB or a Prolog condition called by native code at
//! its boundary (issue 37): the call evaluated where the native frames are,
//! without making the frames below the running one machine frames first
//! (`nat_hand_over`), for native code of a DM without locals.
//!
//! What the hand-over protects at such a call, and how it is kept here:
//! - *the running DM's variables*: an evaluation (and a user function, by
//!   [`FnCall`](crate::functions::FnCall): Rust functions by `var_op`,
//!   Prolog ones by the caller's variables sent with the query and the
//!   changes its answer brings back) reads and writes the locals of the
//!   machine's running frame and the globals. While native frames are
//!   above the machine's, the machine's running frame is the caller's, so
//!   the function would see the caller's locals. Here a DM without locals
//!   gets an empty set of locals, which is what its machine frame holds
//!   (`Vars::set` of a name that is not a local changes nothing, a `get`
//!   falls through to the globals, as in the machine), and the globals,
//!   which are the machine's whatever the frame. A DM with locals (held in
//!   Rust locals by native code, written back by its own hand-over) keeps
//!   the hand-over: the generated code does not call these.
//! - *the running DM's history* (`get_history/1`, `last_transition`): the
//!   history of the running frame. With native frames above the machine's
//!   it is the innermost history level native code keeps
//!   ([`Machine::levels`](super::Machine), a level per frame pushed with
//!   the history kept), and with no level open the history is not kept
//!   (frames are pushed natively only when nothing records, or with a
//!   level each), so the machine's frame would hold no entry either.
//! - *errors*: a run-time error names the running DM and its call (the
//!   machine's top frame, `Machine::err`). An evaluation that fails hands
//!   the frames over first (the cold path), then makes its error as the
//!   machine's would ([`Cx::eval`]: the culprit the evaluator blames;
//!   [`Cx::condition`]: none), in the situation native code entered.
//!   The function is not called again: what it did (a global set, a
//!   Prolog `assert`) is done once, as on the term path.
//! - *garbage collection*: none happens during an evaluation (the machine
//!   collects only between two situations it runs, after native code
//!   handed over, `Cx::gc_tick`), so the `Ground` handles native frames
//!   hold stay valid across the call, as across any native step.
//!
//! An action such an arc performs after its evaluations goes through the
//! one native perform path, [`Cx::nat_perform`] (`machine::effect`), as an
//! entered situation's.
//!
//! Invariant: [`Cx::nat_eval`], [`Cx::nat_condition`] and
//! [`Cx::nat_var_op`] (and [`Cx::nat_embedded_dm`], read-only, what
//! `Machine::eval_read_only` gives) give what [`Cx::eval`], [`Cx::condition`] and
//! [`Cx::var_op`] give after `nat_hand_over` in a DM without locals: the
//! same value, the same changes to the globals and the store, the same
//! error; only the frames below stay native on success.

use super::native_stack::{nat_hand_over, NatBelow, NatFrames};
use super::outcome::RunError;
use super::program::{Cx, DmProgram};
use crate::eval::{self, EvalCtx, EvalError};
use crate::term::Term;
use crate::vars::Vars;
use sitlog_syntax::Atom;

impl<P: DmProgram> Cx<'_, '_, P> {
    /// Runs `f` on the evaluation environment of the running native frame
    /// of a DM without locals: the machine's own when no native frame is
    /// below (the machine's top frame is the running one), else no locals,
    /// the globals and the innermost history level native code keeps
    /// (none: the history is not kept).
    fn nat_env<F: NatFrames<P>, R>(
        &mut self,
        stack: &NatBelow<'_, F>,
        f: impl FnOnce(&mut EvalCtx<'_>) -> R,
    ) -> R {
        self.m.materialize();
        if stack.is_empty() {
            return f(&mut self.m.eval_ctx());
        }
        let m = &mut *self.m;
        let mut locals = Vars::new();
        let history = match m.levels.back() {
            Some(level) => &level.history[..],
            None => &[],
        };
        f(&mut EvalCtx {
            store: &mut m.store,
            locals: &mut locals,
            globals: &mut m.globals,
            history,
            functions: &m.functions,
        })
    }

    /// The error of an evaluation by native code: the frames below handed
    /// over first (the machine's error names the running DM), then the
    /// error in the situation entered, its culprit kept (what [`Cx::eval`]
    /// gives), or, for a condition (`culprit` false), as
    /// [`Cx::condition`] gives it (the conditional blamed when the
    /// evaluator blamed nothing inside).
    #[cold]
    #[inline(never)]
    fn nat_eval_failed<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        e: EvalError,
        culprit: bool,
        arc: Option<usize>,
    ) -> RunError {
        let p = self.m.program;
        if let Err(h) = nat_hand_over(p, self, stack) {
            return h;
        }
        if !culprit {
            return self.condition_error(e, arc);
        }
        let mut r = self.error(e.message, arc);
        if let Some(site) = r.site.as_mut() {
            site.culprit = e.culprit;
        }
        r
    }

    /// [`Cx::eval`] of `t` by native code of a DM without locals, the
    /// native frames below left native (module doc); handed over only
    /// where the evaluation fails.
    #[inline]
    pub fn nat_eval<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        t: Term,
        arc: Option<usize>,
    ) -> Result<Term, RunError> {
        match self.nat_env(stack, |ctx| eval::eval(ctx, t)) {
            Ok(v) => Ok(v),
            Err(e) => Err(self.nat_eval_failed(stack, e, true, arc)),
        }
    }

    /// A recursive situation's `embedded_dm` `t` evaluated by native code
    /// of a DM without locals, read-only as the machine's call evaluates it
    /// (`Machine::eval_read_only`, D-20/E12: the globals, and the running
    /// frame's locals when it is the machine's, restored after), the
    /// frames below left native. The error is given back, nothing handed
    /// over: the caller hands over and reports it (`Cx::call_held`), the
    /// call not evaluated again.
    #[inline]
    pub fn nat_embedded_dm<F: NatFrames<P>>(
        &mut self,
        stack: &NatBelow<'_, F>,
        t: Term,
    ) -> Result<Term, EvalError> {
        // The frames typed code called lazily pushed first: the running
        // frame whose locals are kept is the one `nat_env` evaluates in.
        self.m.materialize();
        self.m.scratch_globals.restore_from(&self.m.globals);
        if stack.is_empty() {
            let frame = self.m.frames.last().expect("a frame is running");
            self.m.scratch_locals.restore_from(&frame.locals);
        }
        let r = self.nat_env(stack, |ctx| eval::eval(ctx, t));
        let m = &mut *self.m;
        m.globals.restore_from(&m.scratch_globals);
        if stack.is_empty() {
            let frame = m.frames.last_mut().expect("a frame is running");
            frame.locals.restore_from(&m.scratch_locals);
        }
        r
    }

    /// [`Cx::condition`] of `cond` by native code of a DM without locals,
    /// as [`Cx::nat_eval`].
    #[inline]
    pub fn nat_condition<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        cond: Term,
        arc: Option<usize>,
    ) -> Result<bool, RunError> {
        match self.nat_env(stack, |ctx| eval::condition(ctx, cond)) {
            Ok(v) => Ok(v),
            Err(e) => Err(self.nat_eval_failed(stack, e, false, arc)),
        }
    }

    /// [`Cx::arith_condition`] by native code (the store only): the
    /// frames below handed over only where it fails, for the error.
    #[inline]
    pub fn nat_arith_condition<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        op: crate::arith::ArithCmp,
        a: Term,
        b: Term,
        arc: Option<usize>,
    ) -> Result<bool, RunError> {
        match eval::arith_condition(&mut self.m.store, op, a, b) {
            Ok(v) => Ok(v),
            Err(e) => Err(self.nat_eval_failed(stack, e, false, arc)),
        }
    }

    /// [`Cx::is`] by native code (the store only), as
    /// [`Cx::nat_arith_condition`].
    #[inline]
    pub fn nat_is<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        v: Option<Term>,
        expr: Term,
        arc: Option<usize>,
    ) -> Result<Term, RunError> {
        match eval::is(&mut self.m.store, v, expr, None) {
            Ok(v) => Ok(v),
            Err(e) => {
                let culprit = super::places::is_culprit(&self.m.store, v);
                let e = EvalError {
                    culprit: Some(culprit),
                    ..e
                };
                Err(self.nat_eval_failed(stack, e, true, arc))
            }
        }
    }

    /// [`Cx::var_op`] (`get`/`set`/`inc` of a global, a DM without
    /// locals) by native code, as [`Cx::nat_eval`].
    #[inline]
    pub fn nat_var_op<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        op: Atom,
        name: Atom,
        arg: Term,
        arc: Option<usize>,
    ) -> Result<Term, RunError> {
        match self.nat_env(stack, |ctx| eval::var_op_named(ctx, op, name, arg)) {
            Ok(v) => Ok(v),
            Err(e) => Err(self.nat_var_op_failed(stack, e, op, name, arc)),
        }
    }

    /// [`Cx::var_op_fresh`] by native code, as [`Cx::nat_var_op`].
    #[inline]
    pub fn nat_var_op_fresh<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        op: Atom,
        name: Atom,
        arc: Option<usize>,
    ) -> Result<Term, RunError> {
        match self.nat_env(stack, |ctx| eval::var_op_fresh(ctx, op, name)) {
            Ok(v) => Ok(v),
            Err(e) => Err(self.nat_var_op_failed(stack, e, op, name, arc)),
        }
    }

    /// The error of a `get`/`set`/`inc` by native code: handed over first,
    /// then [`Cx::var_op`]'s error.
    #[cold]
    #[inline(never)]
    fn nat_var_op_failed<F: NatFrames<P>>(
        &mut self,
        stack: &mut NatBelow<'_, F>,
        e: EvalError,
        op: Atom,
        name: Atom,
        arc: Option<usize>,
    ) -> RunError {
        let p = self.m.program;
        if let Err(h) = nat_hand_over(p, self, stack) {
            return h;
        }
        self.var_op_error(e.message, op, name, arc)
    }
}
