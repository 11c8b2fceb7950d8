//! [`Val`]: a register's value in native code, and its conversions to and
//! from terms, the one place a native value becomes a term or back
//! (history, observers, boundary calls).
//!
//! Invariants:
//! - A `Val` built by [`Val::from_term`] for a type `ty` has that type's
//!   shape (`Int` for `Ty::Int`, `List` for `Ty::List`, ...; `Term` only for
//!   `Ty::Term`), and `to_term` of it is `==` to the term it came from.
//! - Conversions never recurse per list element: a list is walked in a
//!   loop, and the recursion follows the nesting of lists and compounds
//!   (bounded by the type's depth, [`MAX_DEPTH`], in `from_term`; grown on
//!   the heap by `stacker` elsewhere). A cyclic list (made by binding a
//!   variable inside it) is not a proper list: `from_term` says `None`.
//! - Terms inside a `Val` are handles into one store and move with it: a
//!   holder of `Val`s hands them to [`gc`] (never to [`Store::gc`] alone),
//!   which rewrites every term inside, shared lists included.

use super::list::List;
use super::memo::GroundList;
use super::ty::{Ty, MAX_DEPTH};
use crate::store::Store;
use crate::term::{Term, Value};
use sitlog_syntax::{atoms, Atom};
use std::any::TypeId;
use std::cell::Cell;
use std::rc::Rc;

/// A SitLog value as native code holds it.
///
/// 24 bytes (checked by a test): the list's own tag leaves room for the
/// other variants, so `Val` needs no tag of its own. A compound is one
/// `Rc` slice holding its name and arguments ([`Compound`]): with the name
/// beside the slice `Val` would be 32 bytes.
///
/// `==` compares representations: numbers by bits (`0.0` and `-0.0`
/// differ, as in Prolog), lists and compounds element by element, `Term`s
/// by handle (the same term, not merely an equal one). Two values of one
/// type from [`Val::from_term`] are `==` exactly when their terms are `==`
/// in Prolog, except `Term` values: compare those with
/// [`Val::identical_to`].
#[derive(Debug)]
pub enum Val {
    Int(i64),
    Float(f64),
    /// An atom (`[]` too, when the type says atom).
    Sym(Atom),
    /// A proper list.
    List(List<Val>),
    /// `name(args..)` (with no arguments, the atom `name`); `'.'(H, T)`
    /// with `T` not a list is an improper list, built only by
    /// [`Val::cons`] (a conversion takes proper lists only).
    Tagged(Compound),
    /// Any term of the store, as it was given (it may be an unbound
    /// variable, bound later). In a `Cell` so that [`gc`] can move it
    /// in place inside shared lists.
    Term(Cell<Term>),
}

impl Clone for Val {
    /// An atom or an int copied where it is cloned (a list's head taken
    /// into a situation's field at each visit of a walk), the rest out of
    /// line.
    #[inline]
    fn clone(&self) -> Val {
        // One test of the variant each (a `match` decodes the niche of
        // the list's tag first: twice the instructions). The `matches!`
        // before each `if let` is deliberate: without it `list_search_8`
        // takes 148.5 instructions a transition instead of 144.4.
        if matches!(self, Val::Sym(_)) {
            if let Val::Sym(a) = self {
                return Val::Sym(*a);
            }
        }
        if matches!(self, Val::Int(_)) {
            if let Val::Int(i) = self {
                return Val::Int(*i);
            }
        }
        clone_slow(self)
    }
}

/// [`Val`]'s `clone` but for an atom or an int.
#[inline(never)]
fn clone_slow(v: &Val) -> Val {
    match v {
        Val::Int(i) => Val::Int(*i),
        Val::Float(f) => Val::Float(*f),
        Val::Sym(a) => Val::Sym(*a),
        Val::List(l) => Val::List(l.clone()),
        Val::Tagged(c) => Val::Tagged(c.clone()),
        Val::Term(t) => Val::Term(t.clone()),
    }
}

/// A compound's name and arguments in one shared allocation: `[name,
/// args..]`, the name a `Val::Sym` (the constructor keeps it so).
#[derive(Clone, Debug, PartialEq)]
pub struct Compound(Rc<[Val]>);

impl Compound {
    /// `name(args..)`.
    pub fn new(name: Atom, args: impl IntoIterator<Item = Val>) -> Compound {
        Compound(std::iter::once(Val::Sym(name)).chain(args).collect())
    }

    /// The name (inlined: a selection by a field's functor,
    /// `Val::args_of`, asks it at every visit).
    #[inline]
    pub fn name(&self) -> Atom {
        match self.0.first() {
            Some(Val::Sym(name)) => *name,
            _ => unreachable!("a compound starts with its name"),
        }
    }

    /// The arguments.
    #[inline]
    pub fn args(&self) -> &[Val] {
        &self.0[1..]
    }
}

impl PartialEq for Val {
    /// Atoms and ints compared where the comparison is (native code's
    /// `==` of a list's element with a target), the rest out of line.
    #[inline]
    fn eq(&self, other: &Val) -> bool {
        // One test of the variant each, as in `clone`.
        if let (Val::Sym(a), Val::Sym(b)) = (self, other) {
            return a == b;
        }
        if let (Val::Int(a), Val::Int(b)) = (self, other) {
            return a == b;
        }
        eq_slow(self, other)
    }
}

/// [`Val`]'s `==` but for two atoms or two ints.
#[inline(never)]
fn eq_slow(this: &Val, other: &Val) -> bool {
    match (this, other) {
        (Val::Int(a), Val::Int(b)) => a == b,
        (Val::Float(a), Val::Float(b)) => a.to_bits() == b.to_bits(),
        (Val::Sym(a), Val::Sym(b)) => a == b,
        (Val::List(a), Val::List(b)) => a == b,
        (Val::Tagged(a), Val::Tagged(b)) => a == b,
        (Val::Term(a), Val::Term(b)) => a.get() == b.get(),
        _ => false,
    }
}

impl From<Term> for Val {
    fn from(t: Term) -> Val {
        Val::Term(Cell::new(t))
    }
}

/// Grows the stack on the heap for a recursion on nesting.
fn nested<R>(f: impl FnOnce() -> R) -> R {
    stacker::maybe_grow(64 * 1024, 1024 * 1024, f)
}

impl Val {
    /// The term, if this is a `Term` value.
    pub fn as_term(&self) -> Option<Term> {
        match self {
            Val::Term(t) => Some(t.get()),
            _ => None,
        }
    }

    /// The value of type `ty` that `t` is, or `None` when `t` does not
    /// have that type: an unbound variable (unless `ty` is `Term`), a
    /// partial or cyclic list, an integer too big for `i64`, another
    /// shape, a type nested deeper than [`MAX_DEPTH`]. The caller then
    /// keeps the term.
    pub fn from_term(store: &Store, t: Term, ty: &Ty) -> Option<Val> {
        from_term_at(store, t, ty, 0)
    }

    /// The term this value is, built in `store` (compounds through
    /// [`Store::compound`], so their ground and inert flags are right).
    pub fn to_term(&self, store: &mut Store) -> Term {
        match self {
            Val::Int(i) => Term::int(*i),
            Val::Float(f) => Term::float(*f),
            Val::Sym(a) => Term::atom(*a),
            Val::Term(t) => t.get(),
            Val::List(items) => nested(|| {
                super::memo::list_to_term(
                    store,
                    TypeId::of::<GroundList>(),
                    items,
                    Val::to_term,
                    |v| !v.holds_terms(),
                )
            }),
            Val::Tagged(c) => {
                let terms = nested(|| to_terms(c.args().iter(), store));
                store.compound(c.name(), &terms)
            }
        }
    }

    /// Whether this value and `t` are the same term (Prolog's `==`),
    /// without building one.
    pub fn identical_to(&self, store: &Store, t: Term) -> bool {
        match self {
            Val::Int(i) => matches!(store.value(t), Value::Int(j) if j == *i),
            Val::Float(f) => store.float_of(t).map(f64::to_bits) == Some(f.to_bits()),
            Val::Sym(a) => store.atom_of(t) == Some(*a),
            Val::Term(u) => store.identical(u.get(), t),
            Val::List(items) => {
                let mut cur = t;
                for item in items {
                    let Some(&[head, tail]) = store.compound_args(cur, atoms::DOT, 2) else {
                        return false;
                    };
                    if !nested(|| item.identical_to(store, head)) {
                        return false;
                    }
                    cur = tail;
                }
                store.atom_of(cur) == Some(atoms::NIL)
            }
            Val::Tagged(c) if c.args().is_empty() => store.atom_of(t) == Some(c.name()),
            Val::Tagged(c) => match store.compound_args(t, c.name(), c.args().len()) {
                Some(ts) => c
                    .args()
                    .iter()
                    .zip(ts)
                    .all(|(a, &u)| nested(|| a.identical_to(store, u))),
                None => false,
            },
        }
    }

    /// Whether a term is anywhere inside.
    pub fn holds_terms(&self) -> bool {
        let mut any = false;
        self.each_term(&mut |_| any = true);
        any
    }

    /// Appends every term inside to `out`, in a fixed order: the first
    /// half of a collection by hand (the second is [`Val::pull_terms`]),
    /// for a holder whose roots are gathered from several places; [`gc`]
    /// does both.
    pub fn push_terms(&self, out: &mut Vec<Term>) {
        self.each_term(&mut |t| out.push(t.get()));
    }

    /// Puts back the terms [`Val::push_terms`] gave, moved by
    /// [`Store::gc`], taking them from `moved` in the same order (a value
    /// must not change between the two).
    pub fn pull_terms(&self, moved: &mut impl Iterator<Item = Term>) {
        self.each_term(&mut |t| {
            if let Some(m) = moved.next() {
                t.set(m);
            }
        });
    }

    /// Calls `f` on every term inside, in a fixed order (shared storage as
    /// often as it is reached).
    fn each_term(&self, f: &mut impl FnMut(&Cell<Term>)) {
        match self {
            Val::Int(_) | Val::Float(_) | Val::Sym(_) => {}
            Val::Term(t) => f(t),
            Val::List(items) => nested(|| items.iter().for_each(|v| v.each_term(f))),
            Val::Tagged(c) => nested(|| c.args().iter().for_each(|v| v.each_term(f))),
        }
    }
}

fn to_terms<'a>(items: impl Iterator<Item = &'a Val>, store: &mut Store) -> Vec<Term> {
    items.map(|v| v.to_term(store)).collect()
}

/// The store list of `len` items made terms in order by `term` (first to
/// last: `store.list` of them), in a buffer on the stack for a short list
/// (no vector allocated and freed where native code hands a list on as a
/// term: a pipe, an id, an action's argument).
pub(crate) fn list_term<'a, T: 'a>(
    store: &mut Store,
    items: impl Iterator<Item = &'a T>,
    len: usize,
    term: impl Fn(&T, &mut Store) -> Term,
) -> Term {
    const SHORT: usize = 16;
    if len <= SHORT {
        let mut buf = [Term::NIL; SHORT];
        let mut n = 0;
        for (slot, v) in buf.iter_mut().zip(items) {
            *slot = term(v, store);
            n += 1;
        }
        store.list(&buf[..n])
    } else {
        let terms: Vec<Term> = items.map(|v| term(v, store)).collect();
        store.list(&terms)
    }
}

fn from_term_at(store: &Store, t: Term, ty: &Ty, depth: usize) -> Option<Val> {
    if depth > MAX_DEPTH {
        return None;
    }
    match ty {
        Ty::Never => None,
        Ty::Int => store.int_of(t).map(Val::Int),
        Ty::Float => store.float_of(t).map(Val::Float),
        Ty::Sym => store.atom_of(t).map(Val::Sym),
        Ty::Term => Some(Val::from(t)),
        Ty::Ground => match store.value(t) {
            Value::Int(i) => Some(Val::Int(i)),
            Value::Float(_) => store.float_of(t).map(Val::Float),
            Value::Atom(a) if a == atoms::NIL => Some(Val::List(List::from_vec(Vec::new()))),
            Value::Atom(a) => Some(Val::Sym(a)),
            // A list read whole (a parameter, an id's part): remembered
            // (`native::memo`), so that a frame entered again shares it.
            Value::Compound(name, &[_, _]) if name == atoms::DOT && depth == 0 => {
                super::memo::list_from_term(store, TypeId::of::<GroundList>(), t, |item| {
                    from_term_at(store, item, &Ty::Ground, 1)
                })
                .map(Val::List)
            }
            Value::Compound(name, &[_, _]) if name == atoms::DOT => {
                from_term_at(store, t, &Ty::list(Ty::Ground), depth)
            }
            Value::Compound(name, args) => {
                let parts = std::iter::once(Some(Val::Sym(name)))
                    .chain(
                        args.iter()
                            .map(|&u| from_term_at(store, u, &Ty::Ground, depth + 1)),
                    )
                    .collect::<Option<Rc<[Val]>>>()?;
                Some(Val::Tagged(Compound(parts)))
            }
            Value::Var(_) | Value::BigInt(_) => None,
        },
        Ty::List(elem) => {
            // A proper list has at most one cell per three store cells;
            // more steps than that means the spine is cyclic.
            let most = store.cells.len() / 3;
            let mut items = Vec::new();
            let mut it = store.list_iter(t);
            for item in it.by_ref() {
                if items.len() >= most {
                    return None;
                }
                items.push(from_term_at(store, item, elem, depth + 1)?);
            }
            (it.tail() == Term::NIL).then(|| Val::List(List::from_vec(items)))
        }
        Ty::Tagged(name, args) if args.is_empty() => {
            (store.atom_of(t) == Some(*name)).then(|| Val::Tagged(Compound::new(*name, [])))
        }
        Ty::Tagged(name, args) => {
            let ts = store.compound_args(t, *name, args.len())?;
            let parts = std::iter::once(Some(Val::Sym(*name)))
                .chain(
                    ts.iter()
                        .zip(args.iter())
                        .map(|(&u, ty)| from_term_at(store, u, ty, depth + 1)),
                )
                .collect::<Option<Rc<[Val]>>>()?;
            Some(Val::Tagged(Compound(parts)))
        }
    }
}

/// Collects garbage in `store` keeping `roots` and every term inside
/// `vals`, and moves them all: the rule for any holder of native values
/// (a frame's registers, the pipe, a situation's fields). Every `Val`
/// still in use must be among `vals`: terms inside the others become
/// invalid, as handles do after [`Store::gc`]. A list shared by several
/// values is moved once per value that reaches it (each time to the same
/// place); lists of native values only are not touched.
pub fn gc<'v, I>(store: &mut Store, roots: &mut [Term], vals: I)
where
    I: IntoIterator<Item = &'v Val>,
    I::IntoIter: Clone,
{
    let vals = vals.into_iter();
    let mut all = roots.to_vec();
    for v in vals.clone() {
        v.push_terms(&mut all);
    }
    store.gc(&mut all);
    roots.copy_from_slice(&all[..roots.len()]);
    let mut moved = all[roots.len()..].iter().copied();
    for v in vals {
        v.pull_terms(&mut moved);
    }
}

#[cfg(test)]
mod tests;
