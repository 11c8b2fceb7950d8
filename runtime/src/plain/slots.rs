//! A run's plain functions compiled into its program (issue 37): each
//! generated call site names its function by a slot (an index the
//! generated code fixes) and the fingerprint of the form it was compiled
//! from; the slot is resolved once ([`Functions::resolve_compiled`]: the
//! run's engine holds that very form and runs a call of it natively) and
//! kept while the registry's [`Functions::stamp`] stays the same, so a
//! call looks nothing up in the registry or the engine's map.
//!
//! Invariant: a compiled function runs only where the slot resolved to
//! the engine's live flag, and then only where `call_vals` would run the
//! same form on the same arguments: the flag set (the engine started and
//! not abandoned) before and after, every argument taken
//! ([`rt::args_sure`](super::rt::args_sure)), every global no deeper than
//! the engine takes ([`super::sure`]); the inference limit was checked at
//! the resolution (the stamp changes with the limits). A slot that did
//! not resolve takes the path of a function not compiled
//! (`Functions::call_native`, the plain form interpreted or the term path).

use crate::functions::Functions;
use crate::native::Val;
use crate::store::Store;
use crate::vars::Vars;
use sitlog_syntax::Atom;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// One compiled function's resolution.
enum Slot {
    /// Not asked yet.
    Unknown,
    /// Runs as a function not compiled.
    Other,
    /// Runs as compiled while the engine's flag is set.
    Compiled(Arc<AtomicBool>),
}

/// The resolutions of a run's compiled plain functions, by slot.
pub struct PlainSlots {
    /// The registry's stamp they were resolved under.
    stamp: u64,
    slots: Vec<Slot>,
}

impl Default for PlainSlots {
    fn default() -> PlainSlots {
        PlainSlots {
            // No registry has it: the first call resolves.
            stamp: u64::MAX,
            slots: Vec::new(),
        }
    }
}

impl PlainSlots {
    /// The value of the compiled function `f` of slot `k` (`name/args.len()`
    /// compiled from the form whose fingerprint is `form`) on `args`:
    /// `Some(answer)` where the slot runs as compiled (`answer` `None`: the
    /// term path decides), `None` where it runs as a function not compiled.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub fn run(
        &mut self,
        k: usize,
        functions: &Functions,
        store: &Store,
        globals: &Vars,
        name: Atom,
        form: &str,
        args: &[Val],
        f: impl FnOnce(&[Val]) -> Option<Val>,
    ) -> Option<Option<Val>> {
        if self.stamp != functions.stamp() || k >= self.slots.len() {
            self.renew(k, functions);
        }
        if let Slot::Unknown = self.slots[k] {
            self.slots[k] = match functions.resolve_compiled(name, args.len(), form) {
                Some(live) => Slot::Compiled(live),
                None => Slot::Other,
            };
        }
        let Slot::Compiled(live) = &self.slots[k] else {
            return None;
        };
        if !live.load(Ordering::Acquire)
            || !super::rt::args_sure(args)
            || !globals
                .entries()
                .iter()
                .all(|&(_, v)| super::sure(store, v, false))
        {
            return Some(None);
        }
        let v = f(args);
        // Abandoned meanwhile (by another run sharing the engine): its
        // calls are errors.
        Some(v.filter(|_| live.load(Ordering::Acquire)))
    }

    /// Forgets every resolution made under another stamp, and makes room
    /// for slot `k`.
    #[cold]
    fn renew(&mut self, k: usize, functions: &Functions) {
        if self.stamp != functions.stamp() {
            self.slots.clear();
            self.stamp = functions.stamp();
        }
        if k >= self.slots.len() {
            self.slots.resize_with(k + 1, || Slot::Unknown);
        }
    }
}
