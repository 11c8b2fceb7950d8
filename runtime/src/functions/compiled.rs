//! Plain functions compiled into a program (issue 37): whether the run's
//! registry lets a compiled plain function run as compiled
//! ([`Functions::resolve_compiled`]), asked once a run for each (the
//! machine keeps the answer until [`Functions::stamp`] changes).
//!
//! Invariant: a registry answers `Some` for `name/arity` only where its
//! fallback runs the call natively with the very form compiled (the
//! engine's [`CompiledFn`] compares fingerprints and the inference limit)
//! and no Rust function of that name and arity is registered (which
//! [`Functions::call`] would run instead); every change of what this
//! reads gives the registry a new stamp.

use super::Functions;
use sitlog_syntax::Atom;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;

/// Given the registry, a plain function's name and arity and the
/// fingerprint of the form compiled (`plain::PlainFn::fingerprint`): the
/// engine's flag that says whether a call may run natively now (started,
/// not abandoned), if the engine's form of that function is the one
/// compiled and a call of it runs natively under the registry's limits;
/// `None`: the call takes the path a function not compiled takes.
pub type CompiledFn =
    dyn Fn(&Functions, Atom, usize, &str) -> Option<Arc<AtomicBool>> + Send + Sync;

static STAMPS: AtomicU64 = AtomicU64::new(1);

/// A stamp no registry had (`0`: an empty registry's).
pub(super) fn new_stamp() -> u64 {
    STAMPS.fetch_add(1, Ordering::Relaxed)
}

impl Functions {
    /// Sets which compiled plain functions run as compiled (see
    /// [`CompiledFn`]): after [`Functions::set_fallback`], which drops it.
    pub fn set_compiled(
        &mut self,
        f: impl Fn(&Functions, Atom, usize, &str) -> Option<Arc<AtomicBool>> + Send + Sync + 'static,
    ) {
        self.compiled = Some(Arc::new(f));
        self.stamp = new_stamp();
    }

    /// The registry's stamp: equal stamps, the same answers of
    /// [`Functions::resolve_compiled`] (a clone keeps its original's).
    #[inline]
    pub fn stamp(&self) -> u64 {
        self.stamp
    }

    /// The engine's live flag if `name/arity`, compiled from the plain form
    /// whose fingerprint is `fingerprint`, runs as compiled (see the
    /// module's invariant); `None`: as a function not compiled.
    pub fn resolve_compiled(
        &self,
        name: Atom,
        arity: usize,
        fingerprint: &str,
    ) -> Option<Arc<AtomicBool>> {
        let f = self.compiled.as_ref()?;
        if self.map.contains_key(&(name, arity)) {
            return None;
        }
        f(self, name, arity, fingerprint)
    }
}
