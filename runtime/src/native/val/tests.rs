use super::*;
use proptest::prelude::*;

fn atom(name: &str) -> Atom {
    Atom::intern(name)
}

/// Types with at least one value (`Never` only as a list's elements).
fn arb_ty() -> impl Strategy<Value = Ty> {
    let leaf = prop_oneof![
        Just(Ty::Int),
        Just(Ty::Float),
        Just(Ty::Sym),
        Just(Ty::Ground),
        Just(Ty::Term),
        Just(Ty::list(Ty::Never)),
    ];
    leaf.prop_recursive(8, 48, 3, |inner| {
        prop_oneof![
            inner.clone().prop_map(Ty::list),
            (
                prop_oneof![Just("f"), Just("g"), Just("-")],
                proptest::collection::vec(inner, 1..3)
            )
                .prop_map(|(n, args)| Ty::tagged(atom(n), args)),
        ]
    })
}

/// A term of the store, described (built by [`Seed::build`]).
#[derive(Clone, Debug)]
enum Seed {
    Var,
    Int(i64),
    Big,
    Float(f64),
    Atom(&'static str),
    /// Elements and what ends the list: `[]`, a variable or an atom.
    List(Vec<Seed>, u8),
    F(&'static str, Vec<Seed>),
}

impl Seed {
    fn build(&self, store: &mut Store) -> Term {
        match self {
            Seed::Var => store.new_var(),
            Seed::Int(i) => Term::int(*i),
            Seed::Big => store
                .integer_from_text("123456789012345678901234567890")
                .unwrap(),
            Seed::Float(f) => Term::float(*f),
            Seed::Atom(a) => Term::atom(atom(a)),
            Seed::List(items, end) => {
                let items: Vec<Term> = items.iter().map(|s| s.build(store)).collect();
                let tail = match end {
                    0 | 1 => Term::NIL,
                    2 => store.new_var(),
                    _ => Term::atom(atom("a")),
                };
                store.list_with_tail(&items, tail)
            }
            Seed::F(name, args) => {
                let args: Vec<Term> = args.iter().map(|s| s.build(store)).collect();
                store.compound(atom(name), &args)
            }
        }
    }
}

fn arb_seed() -> impl Strategy<Value = Seed> {
    let leaf = prop_oneof![
        Just(Seed::Var),
        any::<i64>().prop_map(Seed::Int),
        Just(Seed::Big),
        any::<f64>().prop_map(Seed::Float),
        prop_oneof![Just("a"), Just("b"), Just("[]"), Just("f")].prop_map(Seed::Atom),
    ];
    leaf.prop_recursive(5, 40, 4, |inner| {
        prop_oneof![
            (proptest::collection::vec(inner.clone(), 0..4), 0u8..4)
                .prop_map(|(items, end)| Seed::List(items, end)),
            (
                prop_oneof![Just("f"), Just("g"), Just("-")],
                proptest::collection::vec(inner, 1..3)
            )
                .prop_map(|(n, args)| Seed::F(n, args)),
        ]
    })
}

/// A value of a type, described (built by [`Spec::build`]).
#[derive(Clone, Debug)]
enum Spec {
    Int(i64),
    Float(f64),
    Sym(&'static str),
    /// Elements; the first `cons` of them are cells on a slice of the rest.
    List(Vec<Spec>, usize),
    Tagged(Atom, Vec<Spec>),
    Term(Seed),
}

impl Spec {
    fn build(&self, store: &mut Store) -> Val {
        match self {
            Spec::Int(i) => Val::Int(*i),
            Spec::Float(f) => Val::Float(*f),
            Spec::Sym(a) => Val::Sym(atom(a)),
            Spec::List(items, cons) => {
                let items: Vec<Val> = items.iter().map(|s| s.build(store)).collect();
                let cons = (*cons).min(items.len());
                let mut list = List::from_slice(&items[cons..]);
                for v in items[..cons].iter().rev() {
                    list = List::cons(v.clone(), list);
                }
                Val::List(list)
            }
            Spec::Tagged(name, args) => Val::Tagged(Compound::new(
                *name,
                args.iter().map(|s| s.build(store)).collect::<Vec<_>>(),
            )),
            Spec::Term(seed) => Val::from(seed.build(store)),
        }
    }
}

fn arb_spec(ty: &Ty) -> BoxedStrategy<Spec> {
    match ty {
        Ty::Never => unreachable!("no value has type never"),
        Ty::Int => any::<i64>().prop_map(Spec::Int).boxed(),
        Ty::Float => any::<f64>().prop_map(Spec::Float).boxed(),
        Ty::Sym => prop_oneof![Just("a"), Just("b"), Just("[]")]
            .prop_map(Spec::Sym)
            .boxed(),
        Ty::Term => arb_seed().prop_map(Spec::Term).boxed(),
        // (not `[]` as an atom: a ground `[]` is the empty list)
        Ty::Ground => prop_oneof![
            any::<i64>().prop_map(Spec::Int),
            prop_oneof![Just("a"), Just("b")].prop_map(Spec::Sym),
            (
                proptest::collection::vec(any::<i64>().prop_map(Spec::Int), 0..4),
                0usize..6
            )
                .prop_map(|(items, cons)| Spec::List(items, cons)),
        ]
        .boxed(),
        Ty::List(elem) if **elem == Ty::Never => Just(Spec::List(vec![], 0)).boxed(),
        Ty::List(elem) => (proptest::collection::vec(arb_spec(elem), 0..5), 0usize..6)
            .prop_map(|(items, cons)| Spec::List(items, cons))
            .boxed(),
        Ty::Tagged(name, args) => {
            let name = *name;
            args.iter()
                .map(arb_spec)
                .collect::<Vec<_>>()
                .prop_map(move |args| Spec::Tagged(name, args))
                .boxed()
        }
    }
}

/// Whether `t` has type `ty`, said plainly (the reference for `from_term`).
fn conforms(store: &Store, t: Term, ty: &Ty) -> bool {
    match ty {
        Ty::Never => false,
        Ty::Int => store.int_of(t).is_some(),
        Ty::Float => store.float_of(t).is_some(),
        Ty::Sym => store.atom_of(t).is_some(),
        Ty::Term => true,
        Ty::Ground => match store.value(t) {
            Value::Int(_) | Value::Float(_) | Value::Atom(_) => true,
            Value::Var(_) | Value::BigInt(_) => false,
            Value::Compound(name, &[_, _]) if name == sitlog_syntax::atoms::DOT => store
                .list_to_vec(t)
                .is_some_and(|items| items.iter().all(|&x| conforms(store, x, ty))),
            Value::Compound(_, args) => args.iter().all(|&u| conforms(store, u, ty)),
        },
        Ty::List(e) => store
            .list_to_vec(t)
            .is_some_and(|items| items.iter().all(|&x| conforms(store, x, e))),
        Ty::Tagged(name, args) if args.is_empty() => store.atom_of(t) == Some(*name),
        Ty::Tagged(name, args) => store.compound_args(t, *name, args.len()).is_some_and(|ts| {
            ts.iter()
                .zip(args.iter())
                .all(|(&u, a)| conforms(store, u, a))
        }),
    }
}

proptest! {
    #[test]
    fn to_term_then_from_term_is_the_same_value(
        (ty, spec) in arb_ty().prop_flat_map(|ty| (Just(ty.clone()), arb_spec(&ty)))
    ) {
        let mut store = Store::new();
        let v = spec.build(&mut store);
        let t = v.to_term(&mut store);
        prop_assert!(v.identical_to(&store, t));
        prop_assert!(conforms(&store, t, &ty));
        prop_assert_eq!(Val::from_term(&store, t, &ty), Some(v.clone()));
        // Built through `Store::compound`: a native value is a ground term.
        if ty.is_native() {
            prop_assert!(store.known_ground(t));
        }
        // Any wider type takes it too.
        prop_assert!(Val::from_term(&store, t, &Ty::Term).is_some());
        prop_assert!(Val::from_term(&store, t, &ty.join(&Ty::list(Ty::Int))).is_some());
    }

    #[test]
    fn from_term_takes_exactly_the_terms_of_its_type(seed in arb_seed(), ty in arb_ty()) {
        let mut store = Store::new();
        let t = seed.build(&mut store);
        let v = Val::from_term(&store, t, &ty);
        prop_assert_eq!(v.is_some(), conforms(&store, t, &ty));
        if let Some(v) = v {
            prop_assert!(v.identical_to(&store, t));
            let u = v.to_term(&mut store);
            prop_assert!(store.identical(t, u));
        }
    }

    #[test]
    fn identical_to_is_prologs_identity(
        (ty, spec) in arb_ty().prop_flat_map(|ty| (Just(ty.clone()), arb_spec(&ty))),
        seed in arb_seed(),
    ) {
        let mut store = Store::new();
        let v = spec.build(&mut store);
        let t = seed.build(&mut store);
        let u = v.to_term(&mut store);
        prop_assert_eq!(v.identical_to(&store, t), store.identical(u, t));
        let _ = ty;
    }
}

#[test]
fn what_is_not_of_the_type_stays_a_term() {
    let mut s = Store::new();
    let x = s.new_var();
    let partial = s.list_with_tail(&[Term::int(1)], x);
    let big = s.integer_from_text("99999999999999999999").unwrap();
    let ints = Ty::list(Ty::Int);
    assert_eq!(Val::from_term(&s, x, &Ty::Int), None);
    assert_eq!(Val::from_term(&s, x, &Ty::Term), Some(Val::from(x)));
    assert_eq!(Val::from_term(&s, partial, &ints), None);
    assert_eq!(Val::from_term(&s, big, &Ty::Int), None);
    assert_eq!(Val::from_term(&s, Term::int(1), &Ty::Float), None);
    assert_eq!(Val::from_term(&s, Term::int(1), &Ty::Never), None);
    // `[]` is an atom and the empty list.
    assert_eq!(
        Val::from_term(&s, Term::NIL, &Ty::Sym),
        Some(Val::Sym(atoms::NIL))
    );
    assert_eq!(
        Val::from_term(&s, Term::NIL, &ints),
        Some(Val::List(List::nil()))
    );
    // Bound variables are followed; a later binding is seen through `Term`.
    assert!(s.bind(x, Term::int(7)));
    assert_eq!(Val::from_term(&s, partial, &ints), None);
    assert_eq!(Val::from_term(&s, x, &Ty::Int), Some(Val::Int(7)));
}

#[test]
fn a_cyclic_list_is_not_a_list() {
    let mut s = Store::new();
    let x = s.new_var();
    let l = s.list_with_tail(&[Term::int(1), Term::int(2)], x);
    assert!(s.bind(x, l));
    assert_eq!(Val::from_term(&s, l, &Ty::list(Ty::Int)), None);
    assert!(Val::from_term(&s, l, &Ty::Term).is_some());
    let v = Val::List(List::from_slice(&[Val::Int(1), Val::Int(2)]));
    assert!(!v.identical_to(&s, l));
}

#[test]
fn pairs_and_their_flags() {
    let mut s = Store::new();
    let pair = Ty::tagged(atom("-"), vec![Ty::Sym, Ty::list(Ty::Sym)]);
    let t = s.parse("kitchen-[cup, book]").unwrap().0;
    let v = Val::from_term(&s, t, &pair).unwrap();
    let u = v.to_term(&mut s);
    assert_eq!(s.writeq(u), "kitchen-[cup,book]");
    assert!(s.is_inert(u) && s.known_ground(u));
    // A construct of L built natively is ground but not inert.
    let sum = Val::Tagged(Compound::new(
        atom("get"),
        [Val::Sym(atom("n")), Val::Int(2)],
    ));
    let u = sum.to_term(&mut s);
    assert!(s.known_ground(u) && !s.is_inert(u));
    // No arguments: the atom.
    let none = Val::Tagged(Compound::new(atom("stop"), []));
    assert_eq!(none.to_term(&mut s), Term::atom(atom("stop")));
    let stop = Ty::tagged(atom("stop"), vec![]);
    assert_eq!(
        Val::from_term(&s, Term::atom(atom("stop")), &stop),
        Some(none)
    );
}

/// 100 000 elements convert both ways, compare and drop without a
/// recursion per element.
#[test]
fn long_lists_convert_in_constant_stack() {
    const N: i64 = 100_000;
    let mut s = Store::new();
    let items: Vec<Term> = (0..N).map(Term::int).collect();
    let t = s.list(&items);
    let ints = Ty::list(Ty::Int);
    let v = Val::from_term(&s, t, &ints).unwrap();
    let Val::List(l) = &v else {
        panic!("not a list: {v:?}")
    };
    assert_eq!(l.len(), N as usize);
    assert!(v.identical_to(&s, t));
    let u = v.to_term(&mut s);
    assert!(s.identical(t, u));
    // Built by cons, of pairs, on a thread with a small stack.
    std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(move || {
            let mut s = Store::new();
            let mut l = List::nil();
            for i in (0..N).rev() {
                let pair = Val::Tagged(Compound::new(
                    atom("-"),
                    [Val::Int(i), Val::Sym(atoms::NIL)],
                ));
                l = List::cons(pair, l);
            }
            let v = Val::List(l);
            let t = v.to_term(&mut s);
            assert!(v.identical_to(&s, t));
            let ty = Ty::list(Ty::tagged(atom("-"), vec![Ty::Int, Ty::Sym]));
            assert_eq!(Val::from_term(&s, t, &ty).as_ref(), Some(&v));
            drop(v);
        })
        .unwrap()
        .join()
        .unwrap();
}

#[test]
fn gc_moves_the_terms_inside_values() {
    let mut s = Store::new();
    let f = atom("f");
    let x = s.new_var();
    let fx = s.compound(f, &[x]);
    let g = s.parse("g(a, [b])").unwrap().0;
    for i in 0..100 {
        s.compound(f, &[Term::int(i)]);
    }
    // A list of terms shared by two values, and a native list.
    let shared = List::from_slice(&[Val::from(fx), Val::from(g)]);
    let a = Val::List(shared.clone());
    let b = Val::List(List::cons(Val::from(x), shared.clone()));
    let native = Val::List(List::from_slice(&[Val::Int(1), Val::Sym(f)]));
    assert!(a.holds_terms() && !native.holds_terms());
    let before = (a.to_term(&mut s), b.to_term(&mut s));
    let text = (s.writeq(before.0), s.writeq(before.1));
    let mut roots = [before.0];
    let cells = s.stats().cells;
    gc(&mut s, &mut roots, [&a, &b, &native]);
    assert!(s.stats().cells < cells);
    let after = (a.to_term(&mut s), b.to_term(&mut s));
    assert_eq!((s.writeq(after.0), s.writeq(after.1)), text);
    assert!(s.identical(roots[0], after.0));
    // The variable is still one variable, shared by both values.
    let Val::List(l) = &b else { unreachable!() };
    let (Val::Term(moved_x), rest) = l.split_first().unwrap() else {
        unreachable!()
    };
    assert!(rest.same_storage(&shared));
    assert!(s.bind(moved_x.get(), Term::int(3)));
    let t = a.to_term(&mut s);
    assert_eq!(s.writeq(t), "[f(3),g(a,[b])]");
}

#[test]
fn terms_gathered_by_hand_move_too() {
    let mut s = Store::new();
    for i in 0..50 {
        s.compound(atom("junk"), &[Term::int(i)]);
    }
    let t = s.parse("p(X, [a])").unwrap().0;
    let v = Val::Tagged(Compound::new(atom("q"), [Val::from(t), Val::Int(1)]));
    let mut roots = Vec::new();
    v.push_terms(&mut roots);
    assert_eq!(roots, [t]);
    s.gc(&mut roots);
    v.pull_terms(&mut roots.iter().copied());
    assert_eq!(v.as_term(), None);
    let u = v.to_term(&mut s);
    assert_eq!(s.writeq(u), "q(p(_G0,[a]),1)");
}

#[test]
fn small() {
    assert_eq!(std::mem::size_of::<Val>(), 24);
    assert_eq!(std::mem::size_of::<List<Val>>(), 24);
}

#[test]
fn ground_takes_any_ground_term_and_no_other() {
    let mut store = Store::new();
    let mut conv = |s: &str| {
        let t = store.parse(s).unwrap().0;
        Val::from_term(&store, t, &Ty::Ground).map(|v| {
            let mut st = Store::new();
            let back = v.to_term(&mut st);
            st.writeq(back)
        })
    };
    assert_eq!(conv("[]").as_deref(), Some("[]"));
    assert_eq!(
        conv("f(a, [1, 2.5], g(b))").as_deref(),
        Some("f(a,[1,2.5],g(b))")
    );
    assert_eq!(conv("said(_)"), None);
    assert_eq!(conv("[a | b]"), None);
    assert_eq!(conv("123456789012345678901234567890"), None);
}

#[test]
fn cons_builds_a_list_or_an_improper_cell() {
    let mut s = Store::new();
    let (a, b) = (Val::Sym(atom("a")), Val::Sym(atom("b")));
    // A list tail: a list, sharing it.
    let l = Val::cons(
        a.clone(),
        Val::List(List::from_slice(std::slice::from_ref(&b))),
    );
    assert!(matches!(l, Val::List(_)));
    let t = l.to_term(&mut s);
    assert_eq!(s.writeq(t), "[a,b]");
    assert_eq!(Val::from_term(&s, t, &Ty::Ground), Some(l.clone()));
    assert_eq!(
        Val::cons(a.clone(), Val::Sym(atoms::NIL)),
        Val::cons(a.clone(), Val::List(List::nil()))
    );
    // Another tail: the improper cell, read back by `split_list`.
    let c = Val::cons(a.clone(), b.clone());
    let t = c.to_term(&mut s);
    assert_eq!(s.writeq(t), "[a|b]");
    assert!(c.identical_to(&s, t));
    assert_eq!(c.split_list(), Some((a.clone(), b.clone())));
    assert_eq!(Val::cons(a.clone(), b.clone()), c);
    // No conversion gives one.
    assert_eq!(Val::from_term(&s, t, &Ty::Ground), None);
}
