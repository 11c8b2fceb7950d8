//! [`Native`]: the Rust types generated code holds a typed register in
//! (`i64` for `int`, `f64` for `float`, [`Atom`] for `sym`, [`List<T>`]
//! for `list<T>`, [`Never`] for the elements of a list that is always
//! empty, [`Val`] for `ground` and fixed-shape compounds, [`Ground`] for a
//! `term` known to be ground), and their checked conversions from and to
//! terms, the one place such a value meets the store; [`IntoVal`], a
//! typed value as a `Val` (no store involved).
//!
//! Invariant: `T::from_term(store, t)` is `Some` exactly when
//! [`Val::from_term`](super::Val::from_term) with the matching [`Ty`](super::Ty)
//! is (an unbound variable, a partial or cyclic list, a big integer or
//! another shape give `None`, never a panic), for `Ground` exactly when
//! `t` is ground and inert (evaluates to itself), for `Val` exactly when
//! `t` is inert and `Val::from_term(.., &Ty::Ground)` is `Some`;
//! `to_term` builds the term that conversion reads back (compounds through
//! the store's constructors, so ground/inert flags are right), except for
//! [`Ground::OUT`], an output argument's place that no conversion makes:
//! its `to_term` is a fresh variable, the one the term path passes.
//! Equality (`==` of the Rust values) is Prolog's `==` on those terms for
//! every type but `f64` (generated code compares floats by bits, as
//! [`Val`](super::Val) does) and `Ground` (compared in the store).
//!
//! A `Val` held by generated code is *canonical*: no `Term` inside, `[]`
//! an empty `List` (never `Sym([])`), no compound without arguments or
//! named `'.'/2`. [`Native::from_term`] and [`IntoVal`] make only those,
//! so Rust's `==` on two of them is Prolog's `==` on their terms.

use super::{List, Ty, Val};
use crate::{Store, Term};
use sitlog_syntax::{atoms, Atom};
use std::any::TypeId;

/// A type no value has: the elements of `list<never>` (`[]`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Never {}

/// A register typed `term` whose value native code knows to be ground: a
/// handle of the store, valid while native code runs (it hands over to the
/// machine before any collection). Compared with [`Store::identical`], not
/// `==` (the derived `PartialEq` compares handles).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ground(pub Term);

impl Ground {
    /// An output argument a native caller passed without making a term for
    /// it (its fresh variable, `J` in `add(I, 1, J)`): the callee's final
    /// hands the value back in its frame's output slot. Never a store
    /// handle (a compound's header cell is never given out), never made by
    /// [`Native::from_term`]; [`Native::to_term`] makes the variable the
    /// term path would have passed, where the frame becomes the machine's.
    pub const OUT: Ground = Ground(Term(crate::term::Repr::Functor(atoms::NIL, 0, 0)));

    /// Whether this is [`Ground::OUT`].
    #[inline]
    pub fn is_out(&self) -> bool {
        *self == Ground::OUT
    }
}

/// A Rust type generated code holds a typed register in.
pub trait Native: Clone + PartialEq + Sized + 'static {
    /// The value `t` (dereferenced) is, when it has this type.
    fn from_term(store: &Store, t: Term) -> Option<Self>;
    /// The term of this value.
    fn to_term(&self, store: &mut Store) -> Term;
    /// Whether `t` converts ([`Native::from_term`] is `Some`), no value
    /// kept: native code that reads the pipe only to check it.
    #[inline]
    fn converts(store: &Store, t: Term) -> bool {
        Self::from_term(store, t).is_some()
    }
    /// The value a canonical [`Val`]'s term converts to, read from the
    /// value itself (the pipe native code holds whole, `Cx::pipe_as`):
    /// `Some(x)` only where `from_term` of `v.to_term(..)` is `Some(x)`;
    /// `None` where that is not known without the term (the caller then
    /// makes the term and converts it). Only the types [`FromVal`]
    /// reads, and lists of them, say more than `None`.
    #[inline]
    fn from_held(_v: &Val) -> Option<Self> {
        None
    }
}

impl Native for i64 {
    #[inline]
    fn from_held(v: &Val) -> Option<i64> {
        <i64 as FromVal>::from_val(v)
    }
    #[inline]
    fn from_term(store: &Store, t: Term) -> Option<i64> {
        store.int_of(t)
    }
    #[inline]
    fn to_term(&self, _: &mut Store) -> Term {
        Term::int(*self)
    }
}

impl Native for f64 {
    #[inline]
    fn from_held(v: &Val) -> Option<f64> {
        <f64 as FromVal>::from_val(v)
    }
    #[inline]
    fn from_term(store: &Store, t: Term) -> Option<f64> {
        store.float_of(t)
    }
    #[inline]
    fn to_term(&self, _: &mut Store) -> Term {
        Term::float(*self)
    }
}

impl Native for Atom {
    #[inline]
    fn from_held(v: &Val) -> Option<Atom> {
        <Atom as FromVal>::from_val(v)
    }
    #[inline]
    fn from_term(store: &Store, t: Term) -> Option<Atom> {
        store.atom_of(t)
    }
    #[inline]
    fn to_term(&self, _: &mut Store) -> Term {
        Term::atom(*self)
    }
}

impl Native for Never {
    fn from_term(_: &Store, _: Term) -> Option<Never> {
        None
    }
    fn to_term(&self, _: &mut Store) -> Term {
        match *self {}
    }
}

impl Native for Ground {
    /// `None` for a term with an unbound variable in it, or one that is not
    /// known to evaluate to itself in L ([`Store::is_inert`]): native code
    /// reads, compares and passes it on where the term path evaluates it
    /// (a condition's arguments, a next situation's).
    fn from_term(store: &Store, t: Term) -> Option<Ground> {
        let t = store.deref(t);
        (store.is_inert(t) && (store.known_ground(t) || store.is_ground(t))).then_some(Ground(t))
    }
    /// [`Ground::OUT`]: a fresh variable, made once where its frame
    /// becomes the machine's.
    #[inline]
    fn to_term(&self, store: &mut Store) -> Term {
        if self.is_out() {
            store.new_var()
        } else {
            self.0
        }
    }
}

impl Native for Val {
    /// The value itself (canonical, inert: [`FromVal`]).
    #[inline]
    fn from_held(v: &Val) -> Option<Val> {
        <Val as FromVal>::from_val(v)
    }
    /// A `ground` register's value (or a fixed-shape compound's), the
    /// checked conversion of a boundary: `None` for a term that is not
    /// ground, not inert (the term path would evaluate it: `1 + 1`), a
    /// partial list, a big integer.
    #[inline]
    fn from_term(store: &Store, t: Term) -> Option<Val> {
        let t = store.deref(t);
        // An int, a float or an atom other than `[]` (atomic, so inert):
        // what `Val::from_term(.., &Ty::Ground)` gives, without its walk
        // (the pipe read at every in_arg, whatever number it holds).
        match t.0 {
            crate::term::Repr::Int(i) => Some(Val::Int(i)),
            crate::term::Repr::Float(bits) => Some(Val::Float(f64::from_bits(bits))),
            crate::term::Repr::Atom(a) if a != atoms::NIL => Some(Val::Sym(a)),
            _ => ground_val(store, t),
        }
    }
    /// An int, a float or an atom other than `[]` without building the
    /// value; the rest out of line (`ground_val`). Always inlined: native
    /// code checks the pipe with it at every in_arg, and a program with
    /// many call sites had it called out of line (`nglob13`: +8
    /// instructions a transition of `echo_calls` in a harness with two
    /// more workloads).
    #[inline(always)]
    fn converts(store: &Store, t: Term) -> bool {
        let t = store.deref(t);
        match t.0 {
            crate::term::Repr::Int(_) | crate::term::Repr::Float(_) => true,
            crate::term::Repr::Atom(a) if a != atoms::NIL => true,
            _ => ground_val(store, t).is_some(),
        }
    }
    #[inline]
    fn to_term(&self, store: &mut Store) -> Term {
        match self {
            Val::Int(i) => Term::int(*i),
            Val::Float(f) => Term::float(*f),
            Val::Sym(a) => Term::atom(*a),
            v => Val::to_term(v, store),
        }
    }
}

/// `Native for Val`'s general case, out of line so that the int and atom
/// case inlines where it is read (the pipe at every in_arg).
#[inline(never)]
fn ground_val(store: &Store, t: Term) -> Option<Val> {
    if !store.is_inert(t) {
        return None;
    }
    Val::from_term(store, t, &Ty::Ground)
}

/// A [`Native`] type read from a canonical [`Val`] (an argument of the
/// pipe native code holds, `Cx::held_pipe`): `Some` exactly when
/// [`Native::from_term`] of the value's term is (`Val::to_term` then
/// `from_term` give back an equal value).
pub trait FromVal: Sized {
    fn from_val(v: &Val) -> Option<Self>;
}

impl FromVal for i64 {
    #[inline]
    fn from_val(v: &Val) -> Option<i64> {
        v.int()
    }
}

impl FromVal for f64 {
    #[inline]
    fn from_val(v: &Val) -> Option<f64> {
        match v {
            Val::Float(f) => Some(*f),
            _ => None,
        }
    }
}

impl FromVal for Atom {
    #[inline]
    fn from_val(v: &Val) -> Option<Atom> {
        v.sym()
    }
}

impl FromVal for Val {
    #[inline]
    fn from_val(v: &Val) -> Option<Val> {
        Some(v.clone())
    }
}

/// A typed native value as a canonical [`Val`] (`[]` an empty list): a
/// value entering a register typed `ground`.
pub trait IntoVal {
    fn into_val(self) -> Val;
}

impl IntoVal for i64 {
    #[inline]
    fn into_val(self) -> Val {
        Val::Int(self)
    }
}

impl IntoVal for f64 {
    #[inline]
    fn into_val(self) -> Val {
        Val::Float(self)
    }
}

impl IntoVal for Atom {
    #[inline]
    fn into_val(self) -> Val {
        if self == atoms::NIL {
            Val::List(List::nil())
        } else {
            Val::Sym(self)
        }
    }
}

impl IntoVal for Never {
    fn into_val(self) -> Val {
        match self {}
    }
}

impl IntoVal for Val {
    #[inline]
    fn into_val(self) -> Val {
        self
    }
}

impl<T: IntoVal + Clone> IntoVal for List<T> {
    fn into_val(self) -> Val {
        Val::List(self.to_vals())
    }
}

impl<T: IntoVal + Clone> List<T> {
    /// The list of its elements as `Val`s (a list of native values entering
    /// a `list<ground>` register): what `into_val` of a `List<T>` holds.
    #[inline]
    pub fn to_vals(&self) -> List<Val> {
        self.iter().cloned().map(IntoVal::into_val).collect()
    }
}

/// Reading a canonical [`Val`] as generated code matches it against an id
/// pattern.
impl Val {
    /// Whether this is `[]`.
    #[inline]
    pub fn is_nil(&self) -> bool {
        match self {
            Val::List(l) => l.is_empty(),
            Val::Sym(a) => *a == atoms::NIL,
            _ => false,
        }
    }

    /// The atom this is (`[]` too).
    #[inline]
    pub fn sym(&self) -> Option<Atom> {
        match self {
            Val::Sym(a) => Some(*a),
            v if v.is_nil() => Some(atoms::NIL),
            _ => None,
        }
    }

    /// The integer this is.
    #[inline]
    pub fn int(&self) -> Option<i64> {
        match self {
            Val::Int(i) => Some(*i),
            _ => None,
        }
    }

    /// `[H|T]` of a non-empty list: the head and the rest (sharing this
    /// list's storage).
    #[inline]
    pub fn split_list(&self) -> Option<(Val, Val)> {
        match self {
            Val::List(l) => l.split_first().map(|(h, t)| (h.clone(), Val::List(t))),
            _ => self.split_cell(),
        }
    }

    /// `[H|T]` of a non-empty proper list: the head (cloned) and the rest
    /// as a list (sharing this list's storage), inline: the walk of a
    /// `ground` value an id's list pattern narrowed to `list<ground>`.
    /// `None` for anything else, an improper list too ([`Val::is_cell`]).
    #[inline]
    pub fn split_proper(&self) -> Option<(Val, List<Val>)> {
        match self {
            Val::List(l) => l.split_first().map(|(h, t)| (h.clone(), t)),
            _ => None,
        }
    }

    /// The non-empty proper list this is (shared, not copied), `None`
    /// for anything else: a `ground` value selecting an id whose list
    /// pattern `[P|Ps]` is held as the list itself (`codegen::native`'s
    /// cell fields), as [`Val::split_proper`] would split it.
    #[inline]
    pub fn non_empty_list(&self) -> Option<&List<Val>> {
        match self {
            Val::List(l) if !l.is_empty() => Some(l),
            _ => None,
        }
    }

    /// Whether this is a cell whose tail is not a list (`[a|b]`, built by
    /// [`Val::cons`]): what [`Val::split_list`] splits and
    /// [`Val::split_proper`] does not.
    #[inline]
    pub fn is_cell(&self) -> bool {
        matches!(self, Val::Tagged(c) if c.name() == atoms::DOT && c.args().len() == 2)
    }

    /// The proper list this is (`[]` too), `None` for anything else: a
    /// `ground` value narrowed to `list<ground>`.
    #[inline]
    pub fn into_list(self) -> Option<List<Val>> {
        match self {
            Val::List(l) => Some(l),
            _ => None,
        }
    }

    /// [`Val::split_list`] of anything but a list, out of line (the
    /// list's case inlines where `[P|Ps]` is selected).
    #[inline(never)]
    fn split_cell(&self) -> Option<(Val, Val)> {
        match self {
            // A cell whose tail is not a list ([`Val::cons`]).
            Val::Tagged(c) if c.name() == atoms::DOT && c.args().len() == 2 => {
                Some((c.args()[0].clone(), c.args()[1].clone()))
            }
            _ => None,
        }
    }

    /// `[head|tail]` of ground values, canonical: a list when `tail` is one
    /// (sharing it), else the cell `'.'(head, tail)` as a compound (an
    /// improper list such as `[a|b]`, which a conversion never gives:
    /// `from_term` takes only proper lists, so only this builds one, and
    /// two equal terms built so are `==`). [`Val::split_list`] reads both.
    #[inline]
    pub fn cons(head: Val, tail: Val) -> Val {
        match tail {
            Val::List(l) => Val::List(List::cons(head, l)),
            Val::Sym(a) if a == atoms::NIL => Val::List(List::cons(head, List::nil())),
            t => Val::Tagged(super::Compound::new(atoms::DOT, [head, t])),
        }
    }

    /// The arguments of a compound `name/arity` (arity ≥ 1, not a list).
    #[inline]
    pub fn args_of(&self, name: Atom, arity: usize) -> Option<&[Val]> {
        match self {
            Val::Tagged(c) if c.name() == name && c.args().len() == arity => Some(c.args()),
            _ => None,
        }
    }
}

impl<T: Native> Native for List<T> {
    /// A held list of `Val`s read as a `List<Val>`: its `Rc` shared; of
    /// another element type, each element read by `T::from_held` (a new
    /// list, as `from_term` makes); `[]` the empty list. Anything else
    /// (an improper list, a compound): `None`, the term decides.
    fn from_held(v: &Val) -> Option<List<T>> {
        match v {
            Val::List(l) => {
                if let Some(l) = (l as &dyn std::any::Any).downcast_ref::<List<T>>() {
                    return Some(l.clone());
                }
                l.iter().map(T::from_held).collect()
            }
            v if v.is_nil() => Some(List::nil()),
            _ => None,
        }
    }
    /// A walk of the list, each element converted; a list remembered
    /// (`native::memo`: the same term converted before, or made of this
    /// list) shared at once.
    fn from_term(store: &Store, t: Term) -> Option<List<T>> {
        // Nesting follows the type, at most `MAX_DEPTH` levels.
        super::memo::list_from_term(store, TypeId::of::<T>(), t, |item| {
            T::from_term(store, item)
        })
    }

    fn to_term(&self, store: &mut Store) -> Term {
        super::memo::list_to_term(store, TypeId::of::<T>(), self, T::to_term, |v| {
            (v as &dyn std::any::Any)
                .downcast_ref::<Val>()
                .is_none_or(|v| !v.holds_terms())
        })
    }
}

/// The part of a (selected) situation id at `path` (argument indices,
/// outermost first), dereferenced; `None` when the id has no such part.
pub fn id_part(store: &Store, id: Term, path: &[usize]) -> Option<Term> {
    let mut t = store.deref(id);
    for &k in path {
        t = store.deref(store.arg(t, k)?);
    }
    Some(t)
}

/// `name(args..)` built from native values (a compound situation id or
/// next situation handed to the machine).
pub fn compound(store: &mut Store, name: Atom, args: &[Term]) -> Term {
    if args.is_empty() {
        Term::atom(name)
    } else if name == atoms::DOT && args.len() == 2 {
        store.cons(args[0], args[1])
    } else {
        store.compound(name, args)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::native::{Ty, Val};

    fn agrees<T: Native + std::fmt::Debug>(store: &mut Store, t: Term, ty: &Ty) {
        let ours = T::from_term(store, t);
        let val = Val::from_term(store, t, ty);
        assert_eq!(ours.is_some(), val.is_some(), "{}", store.writeq(t));
        if let Some(v) = ours {
            let back = v.to_term(store);
            assert!(store.identical(back, t), "{}", store.writeq(t));
        }
    }

    #[test]
    fn conversions_agree_with_val() {
        let mut s = Store::new();
        let a = Atom::intern("a");
        let b = Atom::intern("b");
        let ab = s.list(&[Term::atom(a), Term::atom(b)]);
        let ints = s.list(&[Term::int(1), Term::int(2)]);
        let v = s.new_var();
        let partial = s.list_with_tail(&[Term::atom(a)], v);
        let nested = s.list(&[ab, Term::NIL]);
        for t in [
            ab,
            ints,
            partial,
            nested,
            Term::NIL,
            Term::atom(a),
            Term::int(3),
            v,
        ] {
            agrees::<List<Atom>>(&mut s, t, &Ty::list(Ty::Sym));
            agrees::<List<i64>>(&mut s, t, &Ty::list(Ty::Int));
            agrees::<List<List<Atom>>>(&mut s, t, &Ty::list(Ty::list(Ty::Sym)));
            agrees::<List<Never>>(&mut s, t, &Ty::list(Ty::Never));
            agrees::<Atom>(&mut s, t, &Ty::Sym);
            agrees::<i64>(&mut s, t, &Ty::Int);
        }
        let f = Atom::intern("f");
        // `ground` values: inert ground terms only, canonical.
        let fa = s.compound(f, &[Term::atom(a), ints]);
        for t in [ab, ints, nested, Term::NIL, Term::atom(a), fa] {
            let v = <Val as Native>::from_term(&s, t).expect("converts");
            let back = Native::to_term(&v, &mut s);
            assert!(s.identical(back, t));
        }
        for t in [partial, v] {
            assert!(<Val as Native>::from_term(&s, t).is_none());
        }
        let plus = s.compound(atoms::GET, &[Term::atom(a), Term::atom(b)]);
        assert!(<Val as Native>::from_term(&s, plus).is_none(), "not inert");
        // `Ground::OUT`: never converted to, a fresh variable each time it
        // becomes a term.
        for t in [ab, Term::NIL, Term::atom(a), Term::int(3), fa] {
            assert!(!Ground::from_term(&s, t).expect("ground").is_out());
        }
        let (x, y) = (Ground::OUT.to_term(&mut s), Ground::OUT.to_term(&mut s));
        assert!(s.is_var(x) && s.is_var(y) && !s.identical(x, y));
        let nil = <Val as Native>::from_term(&s, Term::NIL).expect("[]");
        assert_eq!(atoms::NIL.into_val(), nil);
        assert!(nil.is_nil() && nil.sym() == Some(atoms::NIL));
        let l = <Val as Native>::from_term(&s, ab).expect("list");
        let (h, t) = l.split_list().expect("a cell");
        assert_eq!(h, a.into_val());
        assert_eq!(t, List::from_vec(vec![b]).into_val());
        // The same as a proper list; an improper one is a cell, not a list.
        let (h2, t2) = l.split_proper().expect("a proper list");
        assert_eq!((h2, Val::List(t2)), (h, t));
        assert!(!l.is_cell() && l.clone().into_list().is_some());
        let ab_cell = Val::cons(a.into_val(), b.into_val());
        assert!(ab_cell.is_cell() && ab_cell.split_proper().is_none());
        assert!(ab_cell.non_empty_list().is_none() && nil.non_empty_list().is_none());
        assert!(ab_cell.split_list().is_some() && ab_cell.into_list().is_none());
        assert!(nil.split_proper().is_none() && !nil.is_cell());
        let c = <Val as Native>::from_term(&s, fa).expect("f(a, [1, 2])");
        assert_eq!(c.args_of(f, 2).map(|x| x[0].clone()), Some(Val::Sym(a)));
        assert!(c.args_of(f, 1).is_none() && c.sym().is_none());
        let id = compound(&mut s, f, &[Term::atom(a)]);
        assert_eq!(s.writeq(id), "f(a)");
        assert_eq!(compound(&mut s, f, &[]), Term::atom(f));
    }

    /// `from_held` of a canonical value gives what `from_term` of its
    /// term gives, where it says anything (`Cx::pipe_as`).
    #[test]
    fn from_held_agrees_with_the_term() {
        fn check<T: Native + std::fmt::Debug>(s: &mut Store, v: &Val) {
            if let Some(x) = T::from_held(v) {
                let t = v.to_term(s);
                assert_eq!(Some(x), T::from_term(s, t), "{v:?}");
            }
        }
        let mut s = Store::new();
        let a = Atom::intern("a");
        let f = Atom::intern("f");
        let fa = Val::Tagged(super::super::Compound::new(f, [Val::Sym(a), Val::Int(1)]));
        let atoms: List<Val> = [Val::Sym(a), Val::Sym(f)].into_iter().collect();
        let ints: List<Val> = [Val::Int(1), Val::Int(2)].into_iter().collect();
        let mixed: List<Val> = [fa.clone(), Val::Float(1.5), Val::List(ints.clone())]
            .into_iter()
            .collect();
        for v in [
            Val::List(atoms),
            Val::List(ints),
            Val::List(mixed),
            Val::List(List::nil()),
            fa,
            Val::Int(3),
            Val::Float(2.5),
            Val::Sym(a),
        ] {
            check::<Val>(&mut s, &v);
            check::<List<Val>>(&mut s, &v);
            check::<List<Atom>>(&mut s, &v);
            check::<List<i64>>(&mut s, &v);
            check::<List<Never>>(&mut s, &v);
            check::<i64>(&mut s, &v);
            check::<f64>(&mut s, &v);
            check::<Atom>(&mut s, &v);
            assert!(<Val as Native>::from_held(&v).is_some());
        }
        let l: List<Val> = [Val::Int(1)].into_iter().collect();
        assert_eq!(
            <List<i64> as Native>::from_held(&Val::List(l)),
            Some([1].into_iter().collect())
        );
    }
}
