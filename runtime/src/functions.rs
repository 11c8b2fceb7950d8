//! User functions: Rust functions registered by name and arity, called from
//! SitLog by `apply(f(X1..Xn), [E1..En])`. A function sees the caller's
//! SitLog variables (read and write, like the original's `var_op/1`) and the
//! task history (read only, like `get_history/1`).

use crate::history::{self, Item};
use crate::native::Val;
use crate::store::Store;
use crate::term::Term;
use crate::trust::Trust;
use crate::vars::Vars;
use sitlog_syntax::{atoms, Atom};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

mod compiled;
pub use compiled::CompiledFn;

/// What a user function gets besides its arguments.
pub struct FnCall<'a> {
    pub store: &'a mut Store,
    pub locals: &'a mut Vars,
    pub globals: &'a mut Vars,
    pub history: &'a [Item],
    pub functions: &'a Functions,
}

impl FnCall<'_> {
    // `var_op` (evaluating L against the caller's variables) is defined by
    // the evaluator, in `eval`, which is above this module.

    /// `get_history(H)`: the history of the current DM so far, as a term.
    pub fn history_term(&mut self) -> Term {
        history::to_term(self.history, self.store)
    }
}

/// A user function: arguments in, value out; an `Err` stops the task with
/// that message.
pub type UserFn = dyn Fn(&mut FnCall<'_>, &[Term]) -> Result<Term, String> + Send + Sync;

/// Calls functions that have no Rust entry (e.g. Prolog user functions):
/// `None` means "not mine".
pub type FallbackFn =
    dyn Fn(&mut FnCall<'_>, Atom, &[Term]) -> Option<Result<Term, String>> + Send + Sync;

/// Runs a function that has no Rust entry on native values where it can
/// (a plain Prolog function: `crate::plain`), given the registry, the
/// store and the caller's globals; `None` means the term path
/// ([`Functions::call`]) decides, with the same answer or error it always
/// gives. Only code whose DM has no locals calls it (the caller's locals
/// are then empty, as a query would send them).
pub type NativeFn = dyn Fn(&Functions, &Store, &Vars, Atom, &[Val]) -> Option<Val> + Send + Sync;

/// Run once when a run starts (its first transition), given the registry
/// (the run's [`Trust`], call limits and stop flag): an engine's own code (Prolog directives)
/// runs here, never while a program or its options are being checked.
pub type StartFn = dyn Fn(&Functions) -> Result<(), String> + Send + Sync;

/// The deepest term handed to the Prolog engine: a clause of the
/// application's Prolog files, or the arguments, variables and history
/// of a call (a list counts one level per element: the engine reads a
/// list as nested cells). The engine's reader and compiler recurse on the
/// engine's thread; deeper, they would overflow its stack and abort the
/// process, so a deeper clause is an error at its place (`sitlogc check`
/// too) and a deeper call an error naming the function.
pub const PROLOG_MAX_DEPTH: usize = 100_000;

/// Bounds on one call of a user function that runs outside Rust (Prolog):
/// set by a run's options (`--prolog-inferences`, `--prolog-time-limit`,
/// `--prolog-heap-limit`) and read by the engine at each call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CallLimits {
    /// Inferences (runaway recursion).
    pub inferences: u64,
    /// Wall-clock time of one call.
    pub time: std::time::Duration,
    /// Memory the process may grow by during one call, in bytes.
    pub heap_bytes: u64,
}

impl CallLimits {
    pub const INFERENCES: u64 = 10_000_000;
    pub const TIME: std::time::Duration = std::time::Duration::from_secs(10);
    pub const HEAP_BYTES: u64 = 512 << 20;
}

impl Default for CallLimits {
    fn default() -> CallLimits {
        CallLimits {
            inferences: CallLimits::INFERENCES,
            time: CallLimits::TIME,
            heap_bytes: CallLimits::HEAP_BYTES,
        }
    }
}

/// A map by function key (an atom's index and an arity), looked up at
/// every call (a plain function on native values, `Functions::call_native`,
/// too): hashed by [`crate::hash::AtomKeyHasher`].
pub(crate) type KeyMap<V> = crate::hash::AtomKeyMap<(Atom, usize), V>;

/// The registry of user functions.
#[derive(Clone, Default)]
pub struct Functions {
    map: KeyMap<Arc<UserFn>>,
    fallback: Option<Arc<FallbackFn>>,
    /// The fallback's run on native values ([`NativeFn`]); set with it,
    /// dropped when another fallback is set.
    native: Option<Arc<NativeFn>>,
    /// Which plain functions compiled into a program run as compiled
    /// ([`CompiledFn`], `compiled`); set with the fallback, dropped with it.
    compiled: Option<Arc<CompiledFn>>,
    /// The registry's contents as far as a compiled plain function's
    /// resolution reads them (`compiled`): a new one at each change.
    stamp: u64,
    limits: Option<CallLimits>,
    start: Option<Arc<StartFn>>,
    trust: Trust,
    stop: Option<Arc<AtomicBool>>,
    input: Option<crate::input::SharedInput>,
    /// The entries that are still the runtime's own ([`standard`]): one
    /// registered or removed again leaves the set.
    standard: std::collections::HashSet<(Atom, usize)>,
}

impl std::fmt::Debug for Functions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Functions")
            .field("count", &self.map.len())
            .finish()
    }
}

impl Functions {
    /// An empty registry.
    pub fn new() -> Functions {
        Functions::default()
    }

    /// The functions shipped with the runtime (see [`standard`]).
    pub fn standard() -> Functions {
        let mut f = Functions::new();
        standard::register(&mut f);
        f
    }

    /// Registers `name/arity`, replacing an earlier one.
    pub fn register(
        &mut self,
        name: &str,
        arity: usize,
        f: impl Fn(&mut FnCall<'_>, &[Term]) -> Result<Term, String> + Send + Sync + 'static,
    ) {
        let key = (Atom::intern(name), arity);
        self.standard.remove(&key);
        self.map.insert(key, Arc::new(f));
        self.stamp = compiled::new_stamp();
    }

    /// Whether `name/arity` is the runtime's own function ([`standard`]),
    /// not replaced by a later [`Functions::register`] nor removed. A
    /// program whose plans run the runtime's `when/3` as the conditional
    /// it equals relies on it (`DmProgram::lowers_runtime_when`).
    pub fn is_standard(&self, name: Atom, arity: usize) -> bool {
        self.standard.contains(&(name, arity))
    }

    /// Sets the handler for functions without a Rust entry.
    pub fn set_fallback(
        &mut self,
        f: impl Fn(&mut FnCall<'_>, Atom, &[Term]) -> Option<Result<Term, String>>
            + Send
            + Sync
            + 'static,
    ) {
        self.fallback = Some(Arc::new(f));
        self.native = None;
        self.compiled = None;
        self.stamp = compiled::new_stamp();
    }

    /// Sets the fallback's run on native values (see [`NativeFn`]): after
    /// [`Functions::set_fallback`], which drops it.
    pub fn set_native(
        &mut self,
        f: impl Fn(&Functions, &Store, &Vars, Atom, &[Val]) -> Option<Val> + Send + Sync + 'static,
    ) {
        self.native = Some(Arc::new(f));
        self.stamp = compiled::new_stamp();
    }

    /// The value of `name(args..)` run on native values by the fallback, if
    /// it runs so (see [`NativeFn`]): never for a function registered in
    /// Rust, which [`Functions::call`] runs instead of the fallback.
    #[inline]
    pub fn call_native(
        &self,
        store: &Store,
        globals: &Vars,
        name: Atom,
        args: &[Val],
    ) -> Option<Val> {
        let f = self.native.as_ref()?;
        if self.map.contains_key(&(name, args.len())) {
            return None;
        }
        f(self, store, globals, name, args)
    }

    /// Sets the bounds of each call of a function run outside Rust
    /// (otherwise each engine uses its own defaults).
    pub fn set_call_limits(&mut self, limits: CallLimits) {
        self.limits = Some(limits);
        self.stamp = compiled::new_stamp();
    }

    /// The bounds set by [`Functions::set_call_limits`].
    pub fn call_limits(&self) -> Option<CallLimits> {
        self.limits
    }

    /// Sets what runs when a run starts (see [`StartFn`]), replacing an
    /// earlier one.
    pub fn set_start(
        &mut self,
        f: impl Fn(&Functions) -> Result<(), String> + Send + Sync + 'static,
    ) {
        self.start = Some(Arc::new(f));
    }

    /// Sets the run's stop flag (SIGINT, SIGTERM: the machine's
    /// `Options::stop`): a call running outside Rust (a Prolog directive or
    /// user function) is abandoned when it is set, so the first signal ends
    /// the run even while such a call runs.
    pub fn set_stop(&mut self, stop: Option<Arc<AtomicBool>>) {
        self.stop = stop;
    }

    /// The flag set by [`Functions::set_stop`].
    pub fn stop(&self) -> Option<&AtomicBool> {
        self.stop.as_deref()
    }

    /// Runs the start hook set by [`Functions::set_start`] with this
    /// registry (its trust, limits and stop flag); the machine calls it at a run's first transition.
    pub fn start(&self) -> Result<(), String> {
        match &self.start {
            Some(f) => f(self),
            None => Ok(()),
        }
    }

    /// Sets what code run outside Rust may reach (a run's `--allow-os`).
    pub fn set_trust(&mut self, trust: Trust) {
        self.trust = trust;
    }

    /// What code run outside Rust may reach (nothing of the operating
    /// system unless set).
    pub fn trust(&self) -> &Trust {
        &self.trust
    }

    /// Sets the run's input that code run outside Rust reads terms from
    /// (Prolog's `read/1`): the perception's own reader (issue 39).
    pub fn set_input(&mut self, input: Option<crate::input::SharedInput>) {
        self.input = input;
    }

    /// The run's input set by [`Functions::set_input`].
    pub fn input(&self) -> Option<&crate::input::SharedInput> {
        self.input.as_ref()
    }

    /// Removes `name/arity`; `true` if it was registered.
    pub fn remove(&mut self, name: Atom, arity: usize) -> bool {
        self.standard.remove(&(name, arity));
        self.stamp = compiled::new_stamp();
        self.map.remove(&(name, arity)).is_some()
    }

    pub fn contains(&self, name: Atom, arity: usize) -> bool {
        self.map.contains_key(&(name, arity))
    }

    /// Names and arities of the registered functions.
    pub fn names(&self) -> impl Iterator<Item = (Atom, usize)> + '_ {
        self.map.keys().copied()
    }

    /// Calls `name/args.len()`; `None` if no such function exists.
    pub fn call(
        &self,
        call: &mut FnCall<'_>,
        name: Atom,
        args: &[Term],
    ) -> Option<Result<Term, String>> {
        if let Some(f) = self.map.get(&(name, args.len())) {
            return Some(f(call, args));
        }
        self.fallback.as_ref().and_then(|f| f(call, name, args))
    }
}

/// Functions shipped with the runtime: `when/3` and history access.
pub mod standard {
    use super::*;

    pub fn register(f: &mut Functions) {
        // when(If, Then, Else): Then if If holds, else Else. If is called
        // as a goal, as by the `when/3` that the original's applications
        // define in Prolog (`(If -> .. | otherwise -> ..)`): `X == Y` has
        // been evaluated to `true`/`false` already; `X =:= Y`, `X @< Y`,
        // `(A, B)` are decided here; a value that is no goal is an error.
        f.register("when", 3, |call, args| {
            let holds = crate::goal::goal_holds(call.store, args[0]).map_err(|e| e.message)?;
            Ok(if holds { args[1] } else { args[2] })
        });
        // get_history(H): the current DM's history as a term.
        f.register("get_history", 1, |call, _| Ok(call.history_term()));
        // last_transition(_): `Expectation:Action` of the last entry of the
        // current DM's history (`none` when it is empty), like the original's
        // get_last_transition/2 helper.
        f.register("last_transition", 1, |call, _| Ok(last_transition(call)));
        f.register("last_transition", 0, |call, _| Ok(last_transition(call)));
        let own = [
            ("when", 3),
            ("get_history", 1),
            ("last_transition", 1),
            ("last_transition", 0),
        ];
        for (name, arity) in own {
            f.standard.insert((Atom::intern(name), arity));
        }
    }

    /// The original's `get_last_transition/2`: the last entry of the
    /// current DM level, as `Expectation:Action`; `none` without one.
    pub fn last_transition(call: &mut FnCall<'_>) -> Term {
        let last = call.history.iter().rev().find_map(|item| match item {
            Item::Entry(e) => Some(*e),
            Item::Nested(_) => None,
        });
        match last {
            Some(e) => call
                .store
                .compound(atoms::COLON, &[e.expectation, e.action]),
            None => Term::atom(atoms::NONE),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The runtime's own entries stay standard until registered again or
    /// removed (what the machine checks for a program that lowered `when/3`).
    #[test]
    fn a_registered_or_removed_function_is_no_longer_standard() {
        let when = Atom::intern("when");
        let mut f = Functions::standard();
        assert!(f.is_standard(when, 3));
        assert!(f.is_standard(Atom::intern("last_transition"), 0));
        assert!(!Functions::new().is_standard(when, 3));
        f.register("when", 3, |_, args| Ok(args[2]));
        assert!(f.contains(when, 3) && !f.is_standard(when, 3));
        let mut g = Functions::standard();
        assert!(g.remove(when, 3));
        assert!(!g.is_standard(when, 3));
        let h = Functions::standard();
        assert!(h.clone().is_standard(when, 3));
    }
}
