//! The term store: compound cells, variable cells, big-integer texts and the
//! trail; term construction, access, binding, undo, and printing.
//!
//! Layout. A compound `f(A1..An)` is `n + 1` contiguous cells: a header
//! holding the name and arity, then the argument handles. Everything lives
//! in `Vec`s indexed by `u32`, so there are no pointers to chase on drop and
//! a 100 000-deep term drops in constant stack. Variables are cells in their
//! own vector: an unbound variable's cell holds its own handle, a bound one
//! holds its value (chains are followed by [`Store::deref`]).
//!
//! Lifetime of terms. Cells are never mutated once written; only variable
//! cells change (by binding, and back by undo). [`Store::freeze`] turns the
//! current contents into a permanent region (programs, constants), and
//! [`Store::gc`] reclaims everything above it that the caller's roots do not
//! reach.
//!
//! Besides terms, the store keeps one note for the evaluator: which `get`,
//! `set` or `inc` of a variable that is neither local nor global it has
//! evaluated ([`Store::note_undefined`]): names only, no terms, so a
//! collection leaves them alone.

use crate::term::{Repr, Term, Value, Var};
use sitlog_syntax::write::{write_term, TermSource, VarLabel, View, WriteOptions};
use sitlog_syntax::{atoms, Atom};
use std::sync::atomic::{AtomicU64, Ordering};

/// Header flag: the compound contains no variable handle (ground, and so
/// acyclic: cells are never changed once written).
pub(crate) const GROUND: u8 = 1;
/// Header flag: the compound is ground and evaluates to itself in L.
pub(crate) const INERT: u8 = 2;
/// Header flag: a compound of a pattern native code fills
/// (`machine::fill`) with a hole below it, the hole included; an argument
/// of it without the flag holds no hole. Set once, as the program's
/// constants are read, by [`Store::set_holed`]: a note beside the term,
/// which does not change what the term is (the one change to a cell once
/// written; nothing but `machine::fill` reads it).
pub(crate) const HOLED: u8 = 4;

/// A point in the trail to undo bindings back to (see [`Store::mark`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mark {
    trail: u32,
    epoch: u32,
}

/// Sizes of the store's regions, for monitoring memory.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StoreStats {
    /// Compound cells (headers and arguments), frozen ones included.
    pub cells: usize,
    /// Variable cells, frozen ones included.
    pub vars: usize,
    /// Big-integer texts.
    pub bigs: usize,
    /// Trail entries (bindings that [`Store::undo_to`] could undo).
    pub trail: usize,
    /// Cells in the frozen (never collected) region.
    pub frozen_cells: usize,
    /// Variable cells in the frozen region.
    pub frozen_vars: usize,
}

/// Boundary of the frozen region of each vector.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Frontier {
    pub(crate) cells: u32,
    pub(crate) vars: u32,
    pub(crate) bigs: u32,
}

/// The collector's buffers (see `Store::gc`), kept in the store between
/// collections; only the collector reads them.
#[derive(Clone, Debug, Default)]
pub(crate) struct GcScratch {
    pub(crate) cell_fwd: Vec<u32>,
    pub(crate) var_fwd: Vec<u32>,
    pub(crate) new_cells: Vec<Term>,
    pub(crate) new_vars: Vec<Term>,
}

/// The term store. See the module documentation.
#[derive(Debug, Clone)]
pub struct Store {
    pub(crate) cells: Vec<Term>,
    pub(crate) vars: Vec<Term>,
    pub(crate) bigs: Vec<Box<str>>,
    pub(crate) trail: Vec<u32>,
    pub(crate) frozen: Frontier,
    /// Bumped by every gc: marks taken before a gc are stale.
    pub(crate) epoch: u32,
    /// Scratch stack of term pairs reused by unify/compare/identical, so
    /// those allocate nothing in the steady state.
    pub(crate) pairs: Vec<(Term, Term)>,
    /// Scratch stacks of terms reused by copies and conversions.
    pub(crate) work: Vec<Term>,
    pub(crate) results: Vec<Term>,
    /// xorshift64* state for `random/1` and `random_float`.
    pub(crate) rng: u64,
    /// Buffers of the collector, kept between collections so that a
    /// collection allocates (and page-faults) nothing once warm.
    pub(crate) gc_scratch: GcScratch,
    /// The last list a plain function's call took whole (`crate::plain`).
    pub(crate) plain_memo: PlainMemo,
    /// `(op, name)` of each `get`/`set`/`inc` of a variable neither local
    /// nor global evaluated so far, each pair once ([`Store::note_undefined`]).
    pub(crate) undefined: Vec<(Atom, Atom)>,
    /// This store among the process's ([`StoreId`]): with [`Store::epoch`],
    /// what names its cells for `native::memo` (the lists converted from
    /// and to terms of this store, remembered) and for test mode's plan of
    /// a `say` pattern's line (`testmode::said`).
    pub(crate) id: StoreId,
}

/// A store's identity, unique in the process: drawn from a counter when
/// the store is made, a new one for a clone (its cells may differ from the
/// original's at the same places and epoch later).
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct StoreId(pub(crate) u64);

impl StoreId {
    fn fresh() -> StoreId {
        static NEXT: AtomicU64 = AtomicU64::new(1);
        StoreId(NEXT.fetch_add(1, Ordering::Relaxed))
    }
}

impl Clone for StoreId {
    fn clone(&self) -> StoreId {
        StoreId::fresh()
    }
}

impl Default for Store {
    fn default() -> Store {
        Store::new()
    }
}

/// Converts a vector length to a cell index. Exceeding 2^32 cells means
/// tens of gigabytes of terms: treated as memory exhaustion.
#[inline]
pub(crate) fn index(len: usize) -> u32 {
    u32::try_from(len).expect("term store exceeds 2^32 cells")
}

impl Store {
    /// An empty store.
    pub fn new() -> Store {
        let seed = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0x9E37_79B9_7F4A_7C15, |d| d.as_nanos() as u64);
        Store {
            cells: Vec::new(),
            vars: Vec::new(),
            bigs: Vec::new(),
            trail: Vec::new(),
            frozen: Frontier::default(),
            epoch: 0,
            pairs: Vec::new(),
            work: Vec::new(),
            results: Vec::new(),
            rng: seed | 1,
            gc_scratch: Default::default(),
            plain_memo: Default::default(),
            undefined: Vec::new(),
            id: StoreId::fresh(),
        }
    }

    /// Notes that the evaluator gave `op(name, _)` an unbound value because
    /// `name` is neither a local nor a global variable (the original SitLog
    /// says the variable is not defined and runs on): once per pair.
    #[cold]
    #[inline(never)]
    pub fn note_undefined(&mut self, op: Atom, name: Atom) {
        if !self.undefined.contains(&(op, name)) {
            self.undefined.push((op, name));
        }
    }

    /// The pairs [`Store::note_undefined`] noted, in order.
    #[inline]
    pub fn undefined_noted(&self) -> &[(Atom, Atom)] {
        &self.undefined
    }

    // ---------------------------------------------------------------- build

    /// A fresh unbound variable.
    pub fn new_var(&mut self) -> Term {
        let t = Term(Repr::Var(index(self.vars.len())));
        self.vars.push(t);
        t
    }

    /// `name(V1, .., VN)` of `N` fresh variables made in order (a DM's
    /// head in generated code).
    pub fn fresh_compound<const N: usize>(&mut self, name: Atom) -> Term {
        let vars: [Term; N] = std::array::from_fn(|_| self.new_var());
        self.compound(name, &vars)
    }

    /// The compound `name(args..)`; with no arguments, the atom `name`
    /// (SWI-6 has no zero-arity compounds).
    pub fn compound(&mut self, name: Atom, args: &[Term]) -> Term {
        if args.is_empty() {
            return Term::atom(name);
        }
        let mut flags = GROUND | INERT;
        for &a in args {
            flags &= self.flags_of(a);
        }
        if flags & INERT != 0 && !crate::special::evaluates_arguments_only(name, args.len()) {
            flags &= !INERT;
        }
        let at = index(self.cells.len());
        self.cells.reserve(args.len() + 1);
        self.cells
            .push(Term(Repr::Functor(name, index(args.len()), flags)));
        // A few arguments one push each (an action `note(S)` built at each
        // visit, issue 37): a `memcpy` call of unknown length costs more.
        if args.len() <= 4 {
            for &a in args {
                self.cells.push(a);
            }
        } else {
            self.cells.extend_from_slice(args);
        }
        Term(Repr::Struct(at))
    }

    /// What is known of `t` as a whole without walking it: [`GROUND`] and
    /// [`INERT`] for atomic terms, none for a variable handle (even a bound
    /// one: a binding may be undone), a compound's as decided when it was
    /// built.
    #[inline]
    fn flags_of(&self, t: Term) -> u8 {
        match t.0 {
            Repr::Var(_) => 0,
            Repr::Struct(p) => match self.cells[p as usize].0 {
                Repr::Functor(_, _, f) => f,
                _ => 0,
            },
            _ => GROUND | INERT,
        }
    }

    /// Flags compound `t` [`HOLED`] (a pattern's, `machine::cx::mark_pattern`).
    pub(crate) fn set_holed(&mut self, t: Term) {
        if let Repr::Struct(p) = t.0 {
            if let Repr::Functor(name, n, f) = self.cells[p as usize].0 {
                self.cells[p as usize] = Term(Repr::Functor(name, n, f | HOLED));
            }
        }
    }

    /// Whether `t` (not dereferenced) is a compound flagged [`HOLED`].
    #[inline]
    pub(crate) fn is_holed(&self, t: Term) -> bool {
        matches!(t.0, Repr::Struct(_)) && self.flags_of(t) & HOLED != 0
    }

    /// The name and arguments of `t` (not dereferenced) where it is a
    /// compound flagged [`HOLED`]: one read of its header.
    #[inline]
    pub(crate) fn holed_parts(&self, t: Term) -> Option<(Atom, &[Term])> {
        let Repr::Struct(p) = t.0 else { return None };
        let p = p as usize;
        match self.cells[p].0 {
            Repr::Functor(name, n, f) if f & HOLED != 0 => {
                Some((name, &self.cells[p + 1..p + 1 + n as usize]))
            }
            _ => None,
        }
    }

    /// The name and arguments of `t` (not dereferenced) where it is a
    /// compound, and whether it is flagged [`HOLED`]: one read of its
    /// header (`crate::sentence`'s walk of a pattern).
    #[inline]
    pub(crate) fn parts_flagged(&self, t: Term) -> Option<(Atom, &[Term], bool)> {
        let Repr::Struct(p) = t.0 else { return None };
        let p = p as usize;
        match self.cells[p].0 {
            Repr::Functor(name, n, f) => {
                Some((name, &self.cells[p + 1..p + 1 + n as usize], f & HOLED != 0))
            }
            _ => None,
        }
    }

    /// The index of compound `t` (not dereferenced) where it lies in the
    /// frozen region: its cells never change nor move again (only a
    /// pattern's `HOLED` flag is set, as it is read, before the freeze).
    #[inline]
    pub(crate) fn frozen_index(&self, t: Term) -> Option<u32> {
        match t.0 {
            Repr::Struct(p) if p < self.frozen.cells => Some(p),
            _ => None,
        }
    }

    /// Whether `t` is known to be ground without walking it: atomic, or a
    /// compound built from ground parts only (every argument atomic or
    /// itself such a compound; a compound built over variable handles is
    /// not known to be ground even when they are bound). Constant time.
    #[inline]
    pub fn known_ground(&self, t: Term) -> bool {
        self.flags_of(self.deref(t)) & GROUND != 0
    }

    /// Whether `t` is known to evaluate to itself in L (D-28, D-36) without
    /// walking it: atomic, or a compound built from inert parts whose
    /// functor is no construct of L (`crate::special`). Constant time; a
    /// list of atoms, numbers and inert compounds is inert.
    #[inline]
    pub fn is_inert(&self, t: Term) -> bool {
        let t = self.deref(t);
        !matches!(t.0, Repr::Var(_)) && self.flags_of(t) & INERT != 0
    }

    /// The list cell `'.'(head, tail)`: [`Store::compound`]'s cell, its
    /// three cells written at once (`'.'/2` evaluates its arguments only,
    /// D-36: ground and inert when both parts are).
    #[inline]
    pub fn cons(&mut self, head: Term, tail: Term) -> Term {
        let flags = (GROUND | INERT) & self.flags_of(head) & self.flags_of(tail);
        let at = index(self.cells.len());
        self.cells
            .extend_from_slice(&[Term(Repr::Functor(atoms::DOT, 2, flags)), head, tail]);
        Term(Repr::Struct(at))
    }

    /// The proper list `[items..]`.
    pub fn list(&mut self, items: &[Term]) -> Term {
        self.list_with_tail(items, Term::NIL)
    }

    /// The list `[items..|tail]`.
    pub fn list_with_tail(&mut self, items: &[Term], tail: Term) -> Term {
        items
            .iter()
            .rev()
            .fold(tail, |acc, &item| self.cons(item, acc))
    }

    /// The list of the character codes of `text` (how SWI-6 reads `"text"`).
    pub fn codes(&mut self, text: &str) -> Term {
        // Built back to front: one pass, no intermediate vector.
        let mut acc = Term::NIL;
        for c in text.chars().rev() {
            acc = self.cons(Term::int(i64::from(u32::from(c))), acc);
        }
        acc
    }

    /// An integer from decimal text (optional `-`/`+`, digits): a small
    /// integer if it fits `i64`, else a big integer. `None` if not a number.
    pub fn integer_from_text(&mut self, text: &str) -> Option<Term> {
        let (negative, digits) = match text.as_bytes().first()? {
            b'-' => (true, &text[1..]),
            b'+' => (false, &text[1..]),
            _ => (false, text),
        };
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let digits = digits.trim_start_matches('0');
        if digits.is_empty() {
            return Some(Term::int(0));
        }
        let normal = if negative {
            format!("-{digits}")
        } else {
            digits.to_owned()
        };
        if let Ok(i) = normal.parse::<i64>() {
            return Some(Term::int(i));
        }
        let at = index(self.bigs.len());
        self.bigs.push(normal.into_boxed_str());
        Some(Term(Repr::Big(at)))
    }

    // --------------------------------------------------------------- access

    /// Follows variable bindings: the result is not a bound variable.
    #[inline]
    pub fn deref(&self, mut t: Term) -> Term {
        while let Repr::Var(i) = t.0 {
            let b = self.vars[i as usize];
            if b == t {
                break;
            }
            t = b;
        }
        t
    }

    /// The float the dereferenced term is, if it is one.
    #[inline]
    pub fn float_of(&self, t: Term) -> Option<f64> {
        match self.deref(t).0 {
            Repr::Float(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    /// The dereferenced term, one level deep.
    pub fn value(&self, t: Term) -> Value<'_> {
        let t = self.deref(t);
        match t.0 {
            Repr::Var(i) => Value::Var(Var(i)),
            Repr::Atom(a) => Value::Atom(a),
            Repr::Int(i) => Value::Int(i),
            Repr::Float(bits) => Value::Float(f64::from_bits(bits)),
            Repr::Big(b) => Value::BigInt(&self.bigs[b as usize]),
            Repr::Struct(p) => {
                let (name, args) = self.compound_at(p);
                Value::Compound(name, args)
            }
            // A handle given out is never a header cell; treat one as an
            // atom rather than panic.
            Repr::Functor(name, ..) => Value::Atom(name),
        }
    }

    /// Name and arguments of the compound whose header is at `p`.
    #[inline]
    pub(crate) fn compound_at(&self, p: u32) -> (Atom, &[Term]) {
        let p = p as usize;
        match self.cells[p].0 {
            Repr::Functor(name, n, _) => (name, &self.cells[p + 1..p + 1 + n as usize]),
            _ => (atoms::NIL, &[]),
        }
    }

    /// The header of the compound at `p`.
    #[inline]
    pub(crate) fn header_at(&self, p: u32) -> (Atom, u32) {
        match self.cells[p as usize].0 {
            Repr::Functor(name, n, _) => (name, n),
            _ => (atoms::NIL, 0),
        }
    }

    /// Name and arity of an atom (arity 0) or compound.
    pub fn functor(&self, t: Term) -> Option<(Atom, usize)> {
        match self.deref(t).0 {
            Repr::Atom(a) => Some((a, 0)),
            Repr::Struct(p) => {
                let (name, n) = self.header_at(p);
                Some((name, n as usize))
            }
            _ => None,
        }
    }

    /// The arguments of a compound (not dereferenced); empty otherwise.
    pub fn args(&self, t: Term) -> &[Term] {
        match self.deref(t).0 {
            Repr::Struct(p) => self.compound_at(p).1,
            _ => &[],
        }
    }

    /// Argument `i` (0-based) of a compound.
    pub fn arg(&self, t: Term, i: usize) -> Option<Term> {
        self.args(t).get(i).copied()
    }

    /// The arguments if `t` is `name(..)` with exactly `arity` arguments.
    #[inline]
    pub fn compound_args(&self, t: Term, name: Atom, arity: usize) -> Option<&[Term]> {
        match self.deref(t).0 {
            Repr::Struct(p) => {
                let (n, args) = self.compound_at(p);
                (n == name && args.len() == arity).then_some(args)
            }
            _ => None,
        }
    }

    /// The atom, if `t` is one.
    #[inline]
    pub fn atom_of(&self, t: Term) -> Option<Atom> {
        match self.deref(t).0 {
            Repr::Atom(a) => Some(a),
            _ => None,
        }
    }

    /// The integer, if `t` is a small integer.
    #[inline]
    pub fn int_of(&self, t: Term) -> Option<i64> {
        match self.deref(t).0 {
            Repr::Int(i) => Some(i),
            _ => None,
        }
    }

    /// The variable, if `t` is an unbound one.
    pub fn var_of(&self, t: Term) -> Option<Var> {
        match self.deref(t).0 {
            Repr::Var(i) => Some(Var(i)),
            _ => None,
        }
    }

    /// Whether `t` is an unbound variable.
    #[inline]
    pub fn is_var(&self, t: Term) -> bool {
        matches!(self.deref(t).0, Repr::Var(_))
    }

    /// Whether `t` is (bound to) a compound.
    #[inline]
    pub fn is_compound(&self, t: Term) -> bool {
        matches!(self.deref(t).0, Repr::Struct(_))
    }

    /// Whether `t` is (bound to) an atom or a number.
    #[inline]
    pub fn is_atomic(&self, t: Term) -> bool {
        !matches!(self.deref(t).0, Repr::Var(_) | Repr::Struct(_))
    }

    /// Iterates over the elements of a (proper or partial) list; afterwards
    /// [`ListIter::tail`] is what ended it (`[]` for a proper list).
    pub fn list_iter(&self, t: Term) -> ListIter<'_> {
        ListIter {
            store: self,
            cur: t,
        }
    }

    /// The elements of a proper list; `None` for anything else.
    pub fn list_to_vec(&self, t: Term) -> Option<Vec<Term>> {
        let mut it = self.list_iter(t);
        let items: Vec<Term> = it.by_ref().collect();
        (it.tail() == Term::NIL).then_some(items)
    }

    // ------------------------------------------------------ binding, trail

    /// Binds `var` (dereferenced first) to `value`, recording it on the
    /// trail. Returns `false`, binding nothing, if `var` is not an unbound
    /// variable.
    pub fn bind(&mut self, var: Term, value: Term) -> bool {
        match self.deref(var).0 {
            Repr::Var(i) => {
                let value = self.deref(value);
                if value != Term(Repr::Var(i)) {
                    self.bind_raw(i, value);
                }
                true
            }
            _ => false,
        }
    }

    /// Binds the unbound variable cell `i`.
    #[inline]
    pub(crate) fn bind_raw(&mut self, i: u32, value: Term) {
        self.vars[i as usize] = value;
        self.trail.push(i);
    }

    /// The current trail position: [`Store::undo_to`] it to forget every
    /// binding made since. Marks are invalidated by [`Store::gc`].
    pub fn mark(&self) -> Mark {
        Mark {
            trail: index(self.trail.len()),
            epoch: self.epoch,
        }
    }

    /// Unbinds every variable bound since `mark`. A mark taken before the
    /// last [`Store::gc`] is stale and ignored (gc commits all bindings).
    pub fn undo_to(&mut self, mark: Mark) {
        if mark.epoch != self.epoch {
            return;
        }
        let keep = mark.trail as usize;
        while self.trail.len() > keep {
            if let Some(i) = self.trail.pop() {
                self.vars[i as usize] = Term(Repr::Var(i));
            }
        }
    }

    // ------------------------------------------------------ memory regions

    /// Makes everything currently in the store permanent: never moved or
    /// reclaimed by [`Store::gc`]. Build programs and constants, collect
    /// away the scaffolding, then freeze. Frozen compounds can be shared by
    /// any number of terms built later at no cost.
    pub fn freeze(&mut self) {
        self.frozen = Frontier {
            cells: index(self.cells.len()),
            vars: index(self.vars.len()),
            bigs: index(self.bigs.len()),
        };
    }

    /// Current sizes.
    pub fn stats(&self) -> StoreStats {
        StoreStats {
            cells: self.cells.len(),
            vars: self.vars.len(),
            bigs: self.bigs.len(),
            trail: self.trail.len(),
            frozen_cells: self.frozen.cells as usize,
            frozen_vars: self.frozen.vars as usize,
        }
    }

    // ------------------------------------------------------------- output

    /// `writeq/1` text of `t` (SitLog operators; variables as `_G<n>`).
    pub fn writeq(&self, t: Term) -> String {
        write_term(self, t, WriteOptions::writeq())
    }

    /// `write/1` text of `t` (operators, no quotes).
    pub fn write(&self, t: Term) -> String {
        write_term(self, t, WriteOptions::write())
    }

    /// Text of `t` with explicit writer options.
    pub fn write_with(&self, t: Term, options: WriteOptions<'_>) -> String {
        write_term(self, t, options)
    }
}

/// Runtime terms print through the syntax crate's writer.
impl TermSource for Store {
    type Ref = Term;
    fn view(&self, t: Term) -> View<'_, Term> {
        match self.value(t) {
            Value::Var(v) => View::Var(VarLabel::Numbered(u64::from(v.0))),
            Value::Atom(a) => View::Atom(a),
            Value::Int(i) => View::Int(i),
            Value::BigInt(s) => View::BigInt(s),
            Value::Float(f) => View::Float(f),
            Value::Compound(name, args) => View::Compound(name, args),
        }
    }
}

/// Iterator over list elements; see [`Store::list_iter`].
#[derive(Clone, Debug)]
pub struct ListIter<'s> {
    store: &'s Store,
    cur: Term,
}

impl ListIter<'_> {
    /// The dereferenced remainder: `[]` after a proper list, else the
    /// partial tail (a variable or a non-list term).
    pub fn tail(&self) -> Term {
        self.store.deref(self.cur)
    }
}

impl Iterator for ListIter<'_> {
    type Item = Term;
    fn next(&mut self) -> Option<Term> {
        let args = self.store.compound_args(self.cur, atoms::DOT, 2)?;
        let head = args[0];
        self.cur = args[1];
        Some(head)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn build_and_access() {
        let mut s = Store::new();
        let a = Term::atom(Atom::intern("a"));
        let x = s.new_var();
        let f = Atom::intern("f");
        let t = s.compound(f, &[a, x, Term::int(3)]);
        assert_eq!(s.functor(t), Some((f, 3)));
        assert_eq!(s.arg(t, 0), Some(a));
        assert_eq!(s.arg(t, 3), None);
        assert!(s.is_var(x));
        assert_eq!(s.var_of(x).map(Term::from), Some(x));
        assert_eq!(s.var_of(t), None);
        assert_eq!(s.compound(f, &[]), Term::atom(f));
        assert_eq!(s.functor(Term::int(1)), None);
        assert!(s.args(a).is_empty());
    }

    #[test]
    fn bind_deref_undo() {
        let mut s = Store::new();
        let x = s.new_var();
        let y = s.new_var();
        let m = s.mark();
        assert!(s.bind(x, y));
        assert!(s.bind(y, Term::int(5)));
        assert_eq!(s.deref(x), Term::int(5));
        assert!(!s.bind(x, Term::int(6)), "bound variables cannot be bound");
        s.undo_to(m);
        assert!(s.is_var(x) && s.is_var(y));
        assert_ne!(s.deref(x), s.deref(y));
        // Binding a variable to itself is a no-op.
        assert!(s.bind(x, x));
        assert!(s.is_var(x));
    }

    /// `cons` writes the cell `compound` of `'.'/2` writes, flags too.
    #[test]
    fn cons_is_the_compound_of_dot() {
        let mut s = Store::new();
        let x = s.new_var();
        let plus = s.compound(Atom::intern("+"), &[Term::int(1), Term::int(2)]);
        let f = s.compound(Atom::intern("f"), &[Term::int(1)]);
        let parts = [Term::int(1), Term::atom(atoms::NIL), x, plus, f];
        for &h in &parts {
            for &t in &parts {
                let a = s.cons(h, t);
                let b = s.compound(atoms::DOT, &[h, t]);
                let (Repr::Struct(p), Repr::Struct(q)) = (a.0, b.0) else {
                    panic!("two compounds");
                };
                let cell = |i: u32| s.cells[i as usize..i as usize + 3].to_vec();
                assert_eq!(cell(p), cell(q));
                assert_eq!(s.known_ground(a), s.known_ground(b));
                assert_eq!(s.is_inert(a), s.is_inert(b));
            }
        }
    }

    #[test]
    fn lists() {
        let mut s = Store::new();
        let items = [Term::int(1), Term::int(2), Term::int(3)];
        let l = s.list(&items);
        assert_eq!(s.list_to_vec(l), Some(items.to_vec()));
        let t = s.new_var();
        let p = s.list_with_tail(&items[..1], t);
        let mut it = s.list_iter(p);
        assert_eq!(it.next(), Some(Term::int(1)));
        assert_eq!(it.next(), None);
        assert_eq!(it.tail(), t);
        assert_eq!(s.list_to_vec(p), None);
        assert_eq!(s.list_to_vec(Term::NIL), Some(vec![]));
        let c = s.codes("hé");
        assert_eq!(s.list_to_vec(c), Some(vec![Term::int(104), Term::int(233)]));
        assert_eq!(s.writeq(c), "[104,233]");
    }

    #[test]
    fn integers_from_text() {
        let mut s = Store::new();
        assert_eq!(s.integer_from_text("-0042"), Some(Term::int(-42)));
        assert_eq!(s.integer_from_text("+7"), Some(Term::int(7)));
        assert_eq!(s.integer_from_text("000"), Some(Term::int(0)));
        assert_eq!(s.integer_from_text(""), None);
        assert_eq!(s.integer_from_text("-"), None);
        assert_eq!(s.integer_from_text("12a"), None);
        let big = s
            .integer_from_text("-000123456789012345678901234567890")
            .unwrap();
        assert_eq!(
            s.value(big),
            Value::BigInt("-123456789012345678901234567890")
        );
        assert_eq!(s.writeq(big), "-123456789012345678901234567890");
        assert_eq!(
            s.integer_from_text("9223372036854775807"),
            Some(Term::int(i64::MAX))
        );
        assert_eq!(
            s.integer_from_text("-9223372036854775808"),
            Some(Term::int(i64::MIN))
        );
    }
}

/// The last list cell `plain::sure` took whole as an argument, in its store
/// (`Store::plain_memo`): the store's epoch and the cell's index, so that a
/// walk that passes the rest of its list at each call checks the list
/// once (the arguments of the next call are then that list, or its tail).
/// Only a list the store knows ground is remembered: its cells never
/// change until a collection, which bumps the epoch (a clone of the store
/// holds the same cells, and the memo with them).
#[derive(Debug, Default)]
pub(crate) struct PlainMemo(AtomicU64);

impl Clone for PlainMemo {
    fn clone(&self) -> PlainMemo {
        PlainMemo(AtomicU64::new(self.0.load(Ordering::Relaxed)))
    }
}

impl PlainMemo {
    pub(crate) fn get(&self, epoch: u32) -> Option<u32> {
        let m = self.0.load(Ordering::Relaxed);
        (m as u32 != 0 && (m >> 32) as u32 == epoch).then(|| m as u32 - 1)
    }

    pub(crate) fn set(&self, epoch: u32, cell: u32) {
        if let Some(c) = cell.checked_add(1) {
            self.0
                .store(u64::from(epoch) << 32 | u64::from(c), Ordering::Relaxed);
        }
    }
}
