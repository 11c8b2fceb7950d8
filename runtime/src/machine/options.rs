//! What a run is given besides its program: [`Options`].

use sitlog_syntax::Atom;

/// Options of a run.
#[derive(Clone, Debug)]
pub struct Options {
    /// Keep the task history (`--history keep`); without it, memory stays bounded.
    pub keep_history: bool,
    /// Deepest DM stack allowed before the run stops with an error.
    pub max_depth: usize,
    /// Recovery DM per situation type (D-42a): run when no expectation is met.
    pub recovery: Vec<(Atom, Atom)>,
    /// Collect garbage when the store has grown by this many cells since the last collection.
    pub gc_threshold: usize,
    /// Limits on terms from outside (`--in-arg`, `--main`; perception
    /// sources take theirs when they are made).
    pub input_limits: crate::input::InputLimits,
    /// When set (by a signal handler), the run stops before its next
    /// transition with an error and [`Outcome::interrupted`](super::Outcome::interrupted).
    pub stop: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    /// The original's evaluation of a DM call's arguments (`sitlogc run
    /// --legacy`): a list whose tail is an unbound variable is closed (the
    /// tail is bound to `[]`), as the original's evaluator of lists, whose
    /// first case is `[]`, does; `[First|Rest]` is called as `[First]`.
    pub close_list_tails: bool,
    /// The original's in_arg (semantics.md D-8; the default, issue 39):
    /// an in_arg pattern that does not unify with the incoming pipe is
    /// skipped, its partial bindings undone; the situation runs with the
    /// pattern's variables unbound and the pipe unchanged, and the run
    /// has a [`RunWarning`](super::RunWarning) the first time a situation
    /// skips. `false` (`sitlogc run --deny-warnings`, a compiled task's
    /// `--deny-warnings`) makes the mismatch an error (E14).
    pub skip_unmatched_in_arg: bool,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            keep_history: true,
            max_depth: 10_000_000,
            recovery: Vec::new(),
            gc_threshold: 1 << 20,
            input_limits: Default::default(),
            stop: None,
            close_list_tails: false,
            skip_unmatched_in_arg: true,
        }
    }
}
