//! What an observer (`--trace`, the debugger) is told of a run: each
//! transition and each input that met no expectation ([`Observer`]) and,
//! between two transitions, the machine itself ([`Inspection`]:
//! read-mostly, with an evaluator that undoes itself).

use super::outcome::RunError;
use super::situation::Instance;
use super::state::{Frame, Machine, Pending};
use crate::eval::{self, EvalCtx};
use crate::functions::Functions;
use crate::history::{Entry, Item};
use crate::store::Store;
use crate::term::Term;
use crate::vars::Vars;

/// Notified of every transition as it happens (for `--trace`).
pub trait Observer {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>);

    /// Called after [`Observer::transition`] (the entry then in its DM's
    /// history), and once more when the run stops on an error (before the
    /// stack is unwound), with the machine as it is: a debugger blocks here.
    /// Does nothing unless overridden.
    fn inspect(&mut self, machine: &mut Inspection<'_>) {
        let _ = machine;
    }

    /// An input that met no expectation of `situation` (D-15): nothing
    /// enters the history, and the situation is entered again (after its
    /// recovery DM, if there is one). Called once the machine knows it met
    /// nothing, before the transition or step that follows. Does nothing
    /// unless overridden.
    fn unmatched(&mut self, store: &Store, dm: Term, situation: Term, input: Term, depth: usize) {
        let _ = (store, dm, situation, input, depth);
    }
}

/// What [`Observer::inspect`] sees of the machine between two transitions:
/// the DM stack (each frame's call term, locals and history, innermost
/// last), the pipe, the globals, and an evaluator that leaves them as they
/// were ([`Inspection::evaluate`]).
pub struct Inspection<'a> {
    pub store: &'a mut Store,
    pub globals: &'a mut Vars,
    pub functions: &'a Functions,
    /// The pipe's value.
    pub pipe: Term,
    /// The error that stopped the run, when it did (`None` after a transition).
    pub error: Option<&'a RunError>,
    frames: &'a mut [Frame],
    instances: &'a [Instance],
}

impl Inspection<'_> {
    /// DMs on the stack (the main DM is frame 0).
    pub fn depth(&self) -> usize {
        self.frames.len()
    }
    /// Frame `i`'s DM call term.
    pub fn dm_id(&self, i: usize) -> Term {
        self.frames[i].dm_id
    }
    /// Frame `i`'s local variables.
    pub fn locals(&self, i: usize) -> &Vars {
        &self.frames[i].locals
    }
    /// The id of the situation frame `i` waits in for frame `i + 1` (its
    /// recursive situation, or the failed one a recovery DM runs for);
    /// `None` for the innermost frame.
    pub fn waiting_in(&self, i: usize) -> Option<Term> {
        match self.frames.get(i)?.pending.as_ref()? {
            Pending::Recursive { .. } => {
                let n = self.frames[..=i]
                    .iter()
                    .filter(|f| matches!(f.pending, Some(Pending::Recursive { .. })))
                    .count();
                self.instances.get(n - 1).map(|inst| inst.id)
            }
            Pending::Compiled { id, .. } | Pending::Recovery { id } => Some(*id),
        }
    }
    /// Frame `i`'s history so far (empty when the history is not kept).
    pub fn history(&self, i: usize) -> &[Item] {
        &self.frames[i].history
    }
    /// Evaluates `t` (an L expression) in frame `i` and prints its value
    /// (`writeq`); bindings and variable updates are undone afterwards.
    pub fn evaluate(&mut self, i: usize, t: Term) -> Result<String, String> {
        let frame = &mut self.frames[i];
        let (locals, globals) = (frame.locals.clone(), self.globals.clone());
        let mark = self.store.mark();
        let mut cx = EvalCtx {
            store: &mut *self.store,
            locals: &mut frame.locals,
            globals: &mut *self.globals,
            history: &frame.history,
            functions: self.functions,
        };
        let result = eval::eval(&mut cx, t)
            .map(|v| self.store.writeq(v))
            .map_err(|e| e.message);
        self.store.undo_to(mark);
        frame.locals = locals;
        *self.globals = globals;
        result
    }
}

impl<'p, P> Machine<'p, P> {
    /// Tells `observer` of the inputs that met no expectation since it was
    /// last told ([`Observer::unmatched`]), and forgets them.
    pub(super) fn report_unmatched(&mut self, observer: &mut Option<&mut dyn Observer>) {
        if self.unmatched.is_empty() {
            return;
        }
        let inputs = std::mem::take(&mut self.unmatched);
        if let Some(o) = observer.as_deref_mut() {
            for &(dm, situation, input, depth) in &inputs {
                o.unmatched(&self.store, dm, situation, input, depth);
            }
        }
    }

    /// Lets `observer` inspect the machine ([`Observer::inspect`]).
    pub(super) fn inspect(
        &mut self,
        pipe: Term,
        error: Option<&RunError>,
        observer: &mut dyn Observer,
    ) {
        observer.inspect(&mut Inspection {
            store: &mut self.store,
            globals: &mut self.globals,
            functions: &self.functions,
            pipe,
            error,
            frames: &mut self.frames,
            instances: &self.instances,
        });
    }
}
