//! The machine's state: [`Machine`] (store, variables, functions, options,
//! the DM stack of [`Frame`]s and the frames typed code has not pushed yet
//! ([`LazyFrame`]s, never seen outside typed code), the history levels of
//! the DMs native code runs on its own stack with the history kept
//! ([`Level`]s, empty whenever the machine runs), the instances waiting
//! for embedded DMs and the buffers reused per transition) and how it is
//! made.

use super::options::Options;
use super::situation::{DmIx, Instance, SitIx};
use crate::functions::Functions;
use crate::history::Item;
use crate::store::Store;
use crate::term::Term;
use crate::vars::Vars;
use sitlog_syntax::Atom;

/// A recursive situation waiting for its embedded DM, or a failed
/// situation waiting for its recovery DM.
#[derive(Debug)]
pub(super) enum Pending {
    /// Its instance is on [`Machine::instances`] (kept out of the frame,
    /// which stays small to push and pop).
    Recursive {
        sit: SitIx,
    },
    Compiled {
        sit: SitIx,
        saved: Term,
        id: Term,
    },
    Recovery {
        id: Term,
    },
}

#[derive(Debug)]
pub(super) struct Frame {
    pub(super) dm: DmIx,
    /// The DM call term (the caller sees its bindings: parameters by reference).
    pub(super) dm_id: Term,
    pub(super) locals: Vars,
    pub(super) history: Vec<Item>,
    pub(super) pending: Option<Pending>,
}

/// A DM called by typed code whose frame is not on the stack yet (see
/// [`Machine::lazy`]): what [`Machine::materialize`] pushes.
#[derive(Debug)]
pub(super) struct LazyFrame {
    pub(super) dm: DmIx,
    pub(super) call: Term,
    /// What the caller's frame waits with.
    pub(super) caller: Pending,
}

/// The history of a DM native code called on its own stack while the
/// history is kept (see [`Machine::levels`]): its call term (the entries'
/// `dm`, the term its final's `diag_mod` binds) and its entries so far.
#[derive(Debug)]
pub(super) struct Level {
    pub(super) dm_id: Term,
    pub(super) history: Vec<Item>,
}

/// Where control goes next in the top frame.
pub(super) enum Goto {
    Initial,
    Situation(Term),
    /// A situation of the running DM chosen when the program was compiled.
    Index(SitIx),
}

/// The machine's state.
pub struct Machine<'p, P> {
    pub(super) program: &'p P,
    pub store: Store,
    pub globals: Vars,
    pub functions: Functions,
    pub options: Options,
    pub(super) frames: Vec<Frame>,
    /// Frames of DMs called by typed code that only typed code has run so
    /// far, innermost last, logically above `frames`: pushed
    /// ([`Machine::materialize`]) before anything reads the DM stack, so
    /// that nothing outside typed code ever sees them. Empty outside a
    /// typed run without history.
    pub(super) lazy: Vec<LazyFrame>,
    /// The histories of the DMs native code called on its own stack with
    /// the history kept, innermost last, logically above `frames`: an
    /// entry goes to the innermost; a DM's final closes its level, nested
    /// in the one below (or the top frame's history), as the machine's
    /// final pops a frame; where the native frames become the machine's
    /// (`Cx::wait_template`), each pushed frame takes its level, bottom
    /// first. Empty whenever the machine runs (so never a garbage-collection
    /// root), except on an error, whose unwinding nests them.
    pub(super) levels: std::collections::VecDeque<Level>,
    /// Instances of the recursive situations waiting for their embedded
    /// DMs (interpreted path), innermost last.
    pub(super) instances: Vec<Instance>,
    /// The `embedded_dm` native code evaluated (read-only) before it
    /// handed its recursive situation's visit to the template
    /// (`Cx::call_held`): the machine's call takes it instead of
    /// evaluating the template's again (`machine::held_call`). Set only
    /// between that hand-over and the call, which takes it (no collection
    /// in between).
    pub(super) held_call: Option<Term>,
    /// Reused buffers (no allocation per transition once warm).
    pub(super) scratch_locals: Vars,
    pub(super) scratch_globals: Vars,
    pub(super) arcs: Vec<[Term; 4]>,
    pub(super) expectations: Vec<Term>,
    pub(super) transitions: u64,
    pub(super) cells_after_gc: usize,
    /// Native code's checks between two situations left before one asks
    /// [`Cx::gc_due`](super::Cx::gc_due) ([`Cx::gc_tick`](super::Cx::gc_tick)).
    pub(super) gc_ticks: u32,
    /// Functor that pairs an arc with its out_arg for one joint copy (D-11);
    /// interned once, not per transition.
    pub(super) arc_functor: Atom,
    /// The perception answered [`Perceived::Again`](super::Perceived::Again): the situation is
    /// entered again without its recovery DM.
    pub(super) again: bool,
    /// Inputs read that met no expectation (D-15), not yet told to the
    /// observer: DM call, situation id, input, depth. Empty between two
    /// situations (so never a garbage-collection root).
    pub(super) unmatched: Vec<(Term, Term, Term, usize)>,
    /// The situation of the running DM and the arc (0-based) whose next
    /// situation is the one to select: where a next situation that matches
    /// no situation is written, for its error. No terms: nothing for the
    /// garbage collector.
    pub(super) chose: Option<(SitIx, Option<usize>)>,
    /// The pipe as native code set it, not made a term yet (the pipe's
    /// term is then [`HeldPipe::MARK`]): made one where anything reads the
    /// pipe as a term (`Cx::flush_pipe`), and when compiled code returns.
    /// Kept here, not in each `Cx`, so that a `Cx` costs nothing more to
    /// make and drop (the interpreter's plans make one per situation).
    pub(super) held: HeldPipe,
    /// The error of an arc's `empty` the effector refused
    /// (`Cx::empty_fails`), before its situation is entered: taken by the
    /// entry that follows (`Cx::enter_performed`, `Cx::nat_enter`), which
    /// reports it. Here, not in each `Cx`, as `held`.
    pub(super) empty_failed: Option<String>,
    /// The run's warnings so far ([`Outcome::warnings`](super::Outcome::warnings)).
    pub(super) warnings: Vec<super::RunWarning>,
    /// The situations that skipped their in_arg once (by DM and
    /// situation index): warned about, not again.
    pub(super) skipped_in_args: Vec<(DmIx, Option<SitIx>)>,
    /// The situations that warned of an input meeting no expectation
    /// ([`Perception::unmatched_is_news`](super::Perception::unmatched_is_news)).
    pub(super) unmatched_warned: Vec<(DmIx, Option<SitIx>)>,
    /// The situations whose arc ended their DM with a next situation
    /// without a value ([`Machine::end_unbound_next`]): warned about once.
    pub(super) unbound_next_warned: Vec<(DmIx, Option<SitIx>)>,
    /// The run's plain functions compiled into its program, resolved once
    /// (`Cx::nat_plain_rs`).
    pub(super) plain_slots: crate::plain::slots::PlainSlots,
}

/// How many arguments a pipe held as native values may have
/// ([`HeldPipe`]): a compound with more is made a term where it is set.
pub const HELD_MAX: usize = 3;

/// The pipe `name(args..)` as native code set it (an arc's out_arg of
/// native values, `Cx::hold_pipe`), while native code runs: no term built
/// for it and none taken apart where a native in_arg reads it
/// (`Cx::held_pipe`). Its arguments are canonical [`Val`](crate::native::Val)s
/// (no term inside), so a collection cannot move anything of it. While
/// it holds the pipe, the machine's pipe term is [`HeldPipe::MARK`] (a
/// header cell, never a handle given out); every reader of that term
/// makes it the term first (`Cx::flush_pipe`: the same term `build_of` of
/// the values makes), every writer replaces the mark. With `n == 0` the
/// pipe is the value `args[0]` itself (an out_arg `Acc` of a list or a
/// compound of native values, `Cx::hold_pipe_value`): its term is
/// `to_term` of it, and no pattern reads it held. A native in_arg that
/// reads the whole pipe into a register reads either where it is
/// (`Cx::pipe_as`, module `held_in`), the pipe left held.
pub struct HeldPipe {
    pub(super) name: Atom,
    pub(super) n: usize,
    pub(super) args: [crate::native::Val; HELD_MAX],
}

impl HeldPipe {
    /// The machine's pipe term while native values hold the pipe.
    pub const MARK: Term = Term(crate::term::Repr::Functor(sitlog_syntax::atoms::NIL, 0, 2));
}

impl Default for HeldPipe {
    fn default() -> HeldPipe {
        use crate::native::Val;
        HeldPipe {
            name: sitlog_syntax::atoms::NIL,
            n: 0,
            args: [Val::Int(0), Val::Int(0), Val::Int(0)],
        }
    }
}

impl<'p, P> Machine<'p, P> {
    pub fn new(
        program: &'p P,
        store: Store,
        globals: Vars,
        functions: Functions,
        options: Options,
    ) -> Self {
        Machine {
            program,
            store,
            globals,
            functions,
            options,
            frames: Vec::new(),
            lazy: Vec::new(),
            levels: std::collections::VecDeque::new(),
            instances: Vec::new(),
            held_call: None,
            scratch_locals: Vars::new(),
            scratch_globals: Vars::new(),
            arcs: Vec::new(),
            expectations: Vec::new(),
            transitions: 0,
            cells_after_gc: 0,
            gc_ticks: 0,
            arc_functor: Atom::intern("$arc"),
            again: false,
            unmatched: Vec::new(),
            chose: None,
            held: HeldPipe::default(),
            empty_failed: None,
            warnings: Vec::new(),
            skipped_in_args: Vec::new(),
            unmatched_warned: Vec::new(),
            unbound_next_warned: Vec::new(),
            plain_slots: Default::default(),
        }
    }

    /// Whether [`Options::stop`] is set.
    #[inline]
    pub(super) fn stop_requested(&self) -> bool {
        self.options
            .stop
            .as_ref()
            .is_some_and(|s| s.load(std::sync::atomic::Ordering::Relaxed))
    }
}
