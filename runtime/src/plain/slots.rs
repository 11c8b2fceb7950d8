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
//! ([`rt::arg_sure`](super::rt::arg_sure), the arguments by reference: none
//! is copied for the call), every global no deeper than
//! the engine takes ([`super::sure`]: globals whose terms cannot change
//! since they were found so are not walked again); the inference limit was checked at
//! the resolution (the stamp changes with the limits). A slot that did
//! not resolve takes the path of a function not compiled
//! (`Functions::call_native`, the plain form interpreted or the term path).

use crate::functions::Functions;
use crate::native::Val;
use crate::store::Store;
use crate::term::{Repr, Term};
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
    checked: Checked,
}

/// The globals' terms last found no deeper than the engine takes, in the
/// store's epoch `epoch`, each atomic or a compound the store knows ground
/// (it cannot change until a collection, which changes the epoch): the
/// same handles need no walk.
#[derive(Default)]
struct Checked {
    terms: Vec<Term>,
    epoch: u32,
}

impl Default for PlainSlots {
    fn default() -> PlainSlots {
        PlainSlots {
            // No registry has it: the first call resolves.
            stamp: u64::MAX,
            slots: Vec::new(),
            checked: Checked::default(),
        }
    }
}

impl PlainSlots {
    /// The answer of the compiled function `f` of slot `k` (`name/N`
    /// compiled from the form whose fingerprint is `form`) on `args`,
    /// each passed by reference: `Some(answer)` where the slot runs as
    /// compiled (`answer` `None`: the term path decides), `None` where it
    /// runs as a function not compiled.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub fn run<'v, const N: usize, R>(
        &mut self,
        k: usize,
        functions: &Functions,
        store: &Store,
        globals: &Vars,
        name: Atom,
        form: &str,
        args: [&'v Val; N],
        f: impl FnOnce([&'v Val; N]) -> Option<R>,
    ) -> Option<Option<R>> {
        if self.stamp != functions.stamp() || k >= self.slots.len() {
            self.renew(k, functions);
        }
        if let Slot::Unknown = self.slots[k] {
            self.resolve(k, functions, name, N, form);
        }
        let Slot::Compiled(live) = &self.slots[k] else {
            return None;
        };
        if !live.load(Ordering::Acquire) || !args.iter().all(|v| super::rt::arg_sure(v)) {
            return Some(None);
        }
        if !self.checked.shallow(store, globals.entries()) {
            return Some(None);
        }
        let v = f(args);
        // Abandoned meanwhile (by another run sharing the engine): its
        // calls are errors.
        Some(v.filter(|_| matches!(&self.slots[k], Slot::Compiled(l) if l.load(Ordering::Acquire))))
    }

    /// Slot `k` resolved (asked once a stamp).
    #[cold]
    fn resolve(&mut self, k: usize, functions: &Functions, name: Atom, arity: usize, form: &str) {
        self.slots[k] = match functions.resolve_compiled(name, arity, form) {
            Some(live) => Slot::Compiled(live),
            None => Slot::Other,
        };
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

impl Checked {
    /// Whether every global is no deeper than the engine takes
    /// ([`super::sure`]): the same terms as last time without a walk.
    #[inline]
    fn shallow(&mut self, store: &Store, entries: &[(Atom, Term)]) -> bool {
        (self.epoch == store.epoch
            && self.terms.len() == entries.len()
            && entries.iter().zip(&self.terms).all(|(&(_, v), &t)| v == t))
            || self.walk(store, entries)
    }

    #[cold]
    fn walk(&mut self, store: &Store, entries: &[(Atom, Term)]) -> bool {
        if !entries.iter().all(|&(_, v)| super::sure(store, v, false)) {
            return false;
        }
        let fixed = |t: Term| match t.0 {
            Repr::Var(_) => false,
            Repr::Struct(_) => store.known_ground(t),
            _ => true,
        };
        self.terms.clear();
        if entries.iter().all(|&(_, v)| fixed(v)) {
            self.terms.extend(entries.iter().map(|&(_, v)| v));
            self.epoch = store.epoch;
        } else {
            self.epoch = store.epoch.wrapping_add(1);
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A registry whose `f/1` resolves to `live` where the fingerprint is
    /// `"form"`; `asked` counts the resolutions.
    fn registry(live: &Arc<AtomicBool>, asked: &Arc<std::sync::atomic::AtomicUsize>) -> Functions {
        let mut f = Functions::new();
        let (live, asked) = (live.clone(), asked.clone());
        f.set_compiled(move |_, name, arity, form| {
            asked.fetch_add(1, Ordering::Relaxed);
            (name.as_str() == "f" && arity == 1 && form == "form").then(|| live.clone())
        });
        f
    }

    #[test]
    fn a_slot_resolves_once_a_stamp_and_runs_only_while_live() {
        let live = Arc::new(AtomicBool::new(true));
        let asked = Arc::new(std::sync::atomic::AtomicUsize::new(0));
        let mut functions = registry(&live, &asked);
        let (store, globals) = (Store::new(), Vars::default());
        let f = Atom::intern("f");
        let mut slots = PlainSlots::default();
        let one = |_: [&Val; 1]| Some(Val::Int(1));
        let arg = Val::Int(0);
        let args = [&arg];
        for _ in 0..3 {
            let v = slots.run(0, &functions, &store, &globals, f, "form", args, one);
            assert!(matches!(v, Some(Some(Val::Int(1)))));
        }
        assert_eq!(asked.load(Ordering::Relaxed), 1);
        // Another fingerprint: the present path (`None`), asked once.
        for _ in 0..2 {
            let v = slots.run(1, &functions, &store, &globals, f, "other", args, one);
            assert!(v.is_none());
        }
        assert_eq!(asked.load(Ordering::Relaxed), 2);
        // A refused argument, the engine not live: the term path.
        let v = slots.run(
            0,
            &functions,
            &store,
            &globals,
            f,
            "form",
            [&Val::Float(-0.0)],
            one,
        );
        assert!(matches!(v, Some(None)));
        live.store(false, Ordering::Relaxed);
        let v = slots.run(0, &functions, &store, &globals, f, "form", args, one);
        assert!(matches!(v, Some(None)));
        live.store(true, Ordering::Relaxed);
        // A Rust function of the name registered: a new stamp, not compiled.
        functions.register("f", 1, |_, _| Ok(crate::Term::int(2)));
        let v = slots.run(0, &functions, &store, &globals, f, "form", args, one);
        assert!(v.is_none());
        functions.remove(f, 1);
        let v = slots.run(0, &functions, &store, &globals, f, "form", args, one);
        assert!(matches!(v, Some(Some(_))));
        // A new fallback drops the resolution's hook.
        functions.set_fallback(|_, _, _| None);
        let v = slots.run(0, &functions, &store, &globals, f, "form", args, one);
        assert!(v.is_none());
    }

    #[test]
    fn globals_too_deep_refuse_and_fixed_ones_are_not_walked_again() {
        let live = Arc::new(AtomicBool::new(true));
        let asked = Arc::new(std::sync::atomic::AtomicUsize::new(0));
        let functions = registry(&live, &asked);
        let mut store = Store::new();
        let f = Atom::intern("f");
        let one = |_: [&Val; 1]| Some(Val::Int(1));
        let mut deep = Term::atom(Atom::intern("a"));
        let s = Atom::intern("s");
        for _ in 0..=super::super::MAX_DEPTH {
            deep = store.compound(s, &[deep]);
        }
        let list = store.parse("[a, b]").unwrap().0;
        let mut globals = Vars::from_entries(vec![(Atom::intern("g"), list)]);
        let mut slots = PlainSlots::default();
        let v = slots.run(
            0,
            &functions,
            &store,
            &globals,
            f,
            "form",
            [&Val::Int(0)],
            one,
        );
        assert!(matches!(v, Some(Some(_))));
        assert_eq!(slots.checked.terms, vec![list]);
        globals = Vars::from_entries(vec![(Atom::intern("g"), deep)]);
        let v = slots.run(
            0,
            &functions,
            &store,
            &globals,
            f,
            "form",
            [&Val::Int(0)],
            one,
        );
        assert!(matches!(v, Some(None)));
        // A variable: walked at every call, bound later to the deep term.
        let x = store.new_var();
        globals = Vars::from_entries(vec![(Atom::intern("g"), x)]);
        let v = slots.run(
            0,
            &functions,
            &store,
            &globals,
            f,
            "form",
            [&Val::Int(0)],
            one,
        );
        assert!(matches!(v, Some(Some(_))));
        assert!(slots.checked.terms.is_empty());
        store.bind(x, deep);
        let v = slots.run(
            0,
            &functions,
            &store,
            &globals,
            f,
            "form",
            [&Val::Int(0)],
            one,
        );
        assert!(matches!(v, Some(None)));
    }
}
