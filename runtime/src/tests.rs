//! Cross-module tests: reading and printing, arithmetic through the
//! reader, very deep terms on the default (2 MiB) test thread, and
//! properties of unify, copy and compare on random terms.

use crate::*;
use std::cmp::Ordering;

fn parse(s: &mut Store, src: &str) -> (Term, Bindings) {
    s.parse(src)
        .unwrap_or_else(|e| panic!("cannot read {src:?}: {e}"))
}

/// Reads `src` and writes it back with `writeq`.
fn rt(src: &str) -> String {
    let mut s = Store::new();
    let (t, _) = parse(&mut s, src);
    s.writeq(t)
}

/// Replaces `_G<n>` variable names by `_V<k>` in order of appearance, so
/// texts can be compared across renumbering.
fn normalize_vars(text: &str) -> String {
    let mut out = String::new();
    let mut seen: Vec<String> = Vec::new();
    let mut rest = text;
    while let Some(pos) = rest.find("_G") {
        out.push_str(&rest[..pos]);
        let digits: String = rest[pos + 2..]
            .chars()
            .take_while(|c| c.is_ascii_digit())
            .collect();
        let k = match seen.iter().position(|d| *d == digits) {
            Some(k) => k,
            None => {
                seen.push(digits.clone());
                seen.len() - 1
            }
        };
        out.push_str(&format!("_V{k}"));
        rest = &rest[pos + 2 + digits.len()..];
    }
    out.push_str(rest);
    out
}

// ------------------------------------------------------------- printing

#[test]
fn writeq_like_swi() {
    assert_eq!(rt("a:b"), "a:b");
    assert_eq!(rt("[a,b|T]"), "[a,b|_G0]");
    assert_eq!(rt("'hello world'"), "'hello world'");
    assert_eq!(rt("-1"), "-1");
    assert_eq!(rt("1 - -1"), "1- -1");
    assert_eq!(rt("1-(-1)"), "1- -1");
    assert_eq!(rt("f((a,b))"), "f((a,b))");
    assert_eq!(rt("x==>y"), "x==>y");
    assert_eq!(rt("e:a=>n"), "e:a=>n");
    assert_eq!(rt("[e:a=>n, x==>[1,2]]"), "[e:a=>n,x==>[1,2]]");
    assert_eq!(rt("\"ab\""), "[97,98]");
    assert_eq!(rt("`ab`"), "[97,98]");
    assert_eq!(rt("{a,b}"), "{a,b}");
    assert_eq!(rt("[]"), "[]");
    assert_eq!(rt("'don''t'"), "'don\\'t'");
    assert_eq!(rt("f(A,B,A)"), "f(_G0,_G1,_G0)");
    assert_eq!(rt("- a"), "-a");
    assert_eq!(rt("2.50"), "2.5");
    assert_eq!(
        rt("123456789012345678901234567890"),
        "123456789012345678901234567890"
    );
    assert_eq!(
        rt("-123456789012345678901234567890"),
        "-123456789012345678901234567890"
    );
}

#[test]
fn minus_one_versus_minus_of_one() {
    let mut s = Store::new();
    // The compound -(1) and the integer -1 print differently.
    let minus_one = s.compound(atoms::MINUS, &[Term::int(1)]);
    assert_eq!(s.writeq(minus_one), "- 1");
    assert_eq!(s.writeq(Term::int(-1)), "-1");
    let minus_minus = s.compound(atoms::MINUS, &[Term::int(-1)]);
    assert_eq!(s.writeq(minus_minus), "- -1");
    let sub = s.compound(atoms::MINUS, &[Term::int(1), minus_one]);
    assert_eq!(s.writeq(sub), "1- - 1");
    // Whatever `- 1` reads as, it prints back to itself.
    let (t, _) = parse(&mut s, "- 1");
    let text = s.writeq(t);
    assert!(text == "-1" || text == "- 1", "{text}");
    let (back, _) = parse(&mut s, &text);
    assert!(s.identical(t, back));
}

#[test]
fn write_unquoted() {
    let mut s = Store::new();
    let (t, _) = parse(&mut s, "f('hello world', \"x\", 'A')");
    assert_eq!(s.write(t), "f(hello world,[120],A)");
}

#[test]
fn bindings_by_name() {
    let mut s = Store::new();
    let (t, b) = parse(&mut s, "f(X, _, Y, _Z, X)");
    let names: Vec<&str> = b.iter().map(|(n, _)| &**n).collect();
    assert_eq!(names, ["X", "Y", "_Z"]);
    assert!(s.unify(b[0].1, Term::int(1)));
    assert!(s.unify(b[1].1, Atom::intern("y").into()));
    assert!(s.writeq(t).starts_with("f(1,_G"));
    assert!(s.writeq(t).ends_with(",y,_G3,1)"), "{}", s.writeq(t));
}

#[test]
fn read_print_round_trip() {
    let sources = [
        "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : screen('Hi') => fs]], [id ==> fs, type ==> final]], [])",
        "[day(X)] : [date(get(day, Y)), next_date(set(day, X))] => s2",
        "f(- 1, 1 - 2 - 3, 1 - (2 - 3), 2 ** -1, a = (\\+ b), [a|b], 'A'(x), - (-), f(;, '|', '[]'))",
        "(a :- b, c ; d -> e)",
        "f(1.0e10, -0.0, 1.5e-7, 0'a, 0x1F)",
    ];
    for src in sources {
        let mut s = Store::new();
        let (t, _) = parse(&mut s, src);
        let text = s.writeq(t);
        let (back, _) = parse(&mut s, &text);
        assert!(s.variant(t, back), "{src} -> {text} -> {}", s.writeq(back));
        assert_eq!(normalize_vars(&s.writeq(back)), normalize_vars(&text));
    }
}

// ----------------------------------------------------------- arithmetic

fn ev(src: &str) -> Result<Number, ArithError> {
    let mut s = Store::new();
    s.set_random_seed(7);
    let (t, _) = parse(&mut s, src);
    s.eval_arith(t)
}

fn int(src: &str) -> i64 {
    match ev(src) {
        Ok(Number::Int(i)) => i,
        other => panic!("{src}: {other:?}"),
    }
}

fn float(src: &str) -> f64 {
    match ev(src) {
        Ok(Number::Float(f)) => f,
        other => panic!("{src}: {other:?}"),
    }
}

#[test]
fn arithmetic_int_float() {
    assert_eq!(int("1 + 2 * 3"), 7);
    assert_eq!(int("6 / 2"), 3);
    assert_eq!(float("7 / 2"), 3.5);
    assert_eq!(float("7.0 / 2"), 3.5);
    assert_eq!(float("6.0 / 2"), 3.0);
    assert_eq!(int("-7 // 2"), -3);
    assert_eq!(int("-7 mod 2"), 1);
    assert_eq!(int("7 mod -2"), -1);
    assert_eq!(int("-7 rem 2"), -1);
    assert_eq!(int("div(-7, 2)"), -4);
    assert_eq!(int("div(7, 2)"), 3);
    assert_eq!(int("-9223372036854775808 mod -1"), 0);
    assert_eq!(float("1 + 0.5"), 1.5);
    assert_eq!(int("min(1, 2)"), 1);
    assert_eq!(float("max(1, 2.0)"), 2.0);
    assert_eq!(float("min(1, 1.0)"), 1.0);
    assert_eq!(int("max(1, 1.0)"), 1);
    assert_eq!(int("abs(-3)"), 3);
    assert_eq!(float("abs(-3.5)"), 3.5);
    assert_eq!(int("sign(-3)"), -1);
    assert_eq!(float("sign(-2.5)"), -1.0);
    assert_eq!(int("- (3)"), -3);
    assert_eq!(int("+ 3"), 3);
    assert_eq!(int("2 ** 3"), 8);
    assert_eq!(float("2 ** -1"), 0.5);
    assert_eq!(float("2 ** 3.0"), 8.0);
    assert_eq!(int("2 ^ 10"), 1024);
    assert_eq!(int("0 ^ 0"), 1);
    assert_eq!(int("1 ^ -3"), 1);
    assert_eq!(int("(-1) ^ -3"), -1);
    assert_eq!(int("(-1) ^ -2"), 1);
    assert_eq!(float("2.0 ^ 2"), 4.0);
    assert_eq!(float("sqrt(16)"), 4.0);
    assert_eq!(float("atan2(1, 1)"), std::f64::consts::FRAC_PI_4);
    assert_eq!(float("atan(1, 1)"), std::f64::consts::FRAC_PI_4);
    assert_eq!(float("exp(0)"), 1.0);
    assert_eq!(float("log(e)"), 1.0);
    assert_eq!(float("log(2, 8)"), 3.0);
    assert_eq!(float("float(3)"), 3.0);
    assert_eq!(int("integer(2.5)"), 3);
    assert_eq!(int("integer(-2.5)"), -3);
    assert_eq!(int("integer(7)"), 7);
    assert_eq!(float("float_integer_part(-2.5)"), -2.0);
    assert_eq!(float("float_fractional_part(2.75)"), 0.75);
    assert_eq!(int("truncate(-2.7)"), -2);
    assert_eq!(int("round(2.5)"), 3);
    assert_eq!(int("ceiling(2.1)"), 3);
    assert_eq!(int("floor(-2.1)"), -3);
    assert_eq!(int("5 >> 1"), 2);
    assert_eq!(int("-8 >> 1"), -4);
    assert_eq!(int("1 << 62"), 1 << 62);
    assert_eq!(int("-1 << 63"), i64::MIN);
    assert_eq!(int("1 << -1"), 0);
    assert_eq!(int("5 /\\ 3"), 1);
    assert_eq!(int("5 \\/ 3"), 7);
    assert_eq!(int("xor(5, 3)"), 6);
    assert_eq!(int("\\ 5"), -6);
    assert_eq!(int("msb(8)"), 3);
    assert_eq!(int("gcd(12, -18)"), 6);
    assert_eq!(float("pi"), std::f64::consts::PI);
    assert_eq!(float("e"), std::f64::consts::E);
    assert!(float("inf").is_infinite());
    assert!(float("nan").is_nan());
    assert_eq!(float("inf + 1"), f64::INFINITY);
    assert_eq!(int("max_tagged_integer"), (1 << 60) - 1);
    assert_eq!(int("\"a\""), 97);
    assert_eq!(int("[X]".replace('X', "3").as_str()), 3);
    assert!(int("realtime") > 1_600_000_000);
    assert!(float("cputime") >= 0.0);
}

#[test]
fn arithmetic_errors() {
    use ArithError::*;
    assert_eq!(ev("9223372036854775807 + 1"), Err(IntOverflow));
    assert_eq!(ev("-9223372036854775808 - 1"), Err(IntOverflow));
    assert_eq!(ev("4611686018427387904 * 2"), Err(IntOverflow));
    assert_eq!(ev("-(-9223372036854775808)"), Err(IntOverflow));
    assert_eq!(ev("abs(-9223372036854775808)"), Err(IntOverflow));
    assert_eq!(ev("-9223372036854775808 // -1"), Err(IntOverflow));
    assert_eq!(ev("-9223372036854775808 / -1"), Err(IntOverflow));
    assert_eq!(ev("2 ** 64"), Err(IntOverflow));
    assert_eq!(ev("2 ^ 63"), Err(IntOverflow));
    assert_eq!(ev("3 ^ 100000000000"), Err(IntOverflow));
    assert_eq!(ev("1 << 63"), Err(IntOverflow));
    assert_eq!(ev("integer(1.0e20)"), Err(IntOverflow));
    assert_eq!(ev("truncate(inf)"), Err(IntOverflow));
    assert_eq!(ev("round(nan)"), Err(Undefined));
    assert_eq!(ev("1 / 0"), Err(ZeroDivisor));
    assert_eq!(ev("1 / 0.0"), Err(ZeroDivisor));
    assert_eq!(ev("1.0 / 0"), Err(ZeroDivisor));
    assert_eq!(ev("0 / 0.0"), Err(Undefined));
    assert_eq!(ev("1 // 0"), Err(ZeroDivisor));
    assert_eq!(ev("1 mod 0"), Err(ZeroDivisor));
    assert_eq!(ev("1 rem 0"), Err(ZeroDivisor));
    assert_eq!(ev("div(1, 0)"), Err(ZeroDivisor));
    assert_eq!(ev("0 ^ -1"), Err(ZeroDivisor));
    assert_eq!(ev("0.0 ** -1"), Err(ZeroDivisor));
    assert!(matches!(ev("2 ^ -1"), Err(Type { .. })));
    assert_eq!(ev("sqrt(-1)"), Err(Undefined));
    assert_eq!(ev("log(0)"), Err(Undefined));
    assert_eq!(ev("asin(2)"), Err(Undefined));
    assert_eq!(ev("exp(1000)"), Err(FloatOverflow));
    assert_eq!(ev("1.0e308 * 10"), Err(FloatOverflow));
    assert_eq!(ev("X + 1"), Err(Instantiation));
    assert_eq!(ev("X"), Err(Instantiation));
    let foo = Atom::intern("foo");
    assert_eq!(
        ev("foo"),
        Err(NotEvaluable {
            name: foo,
            arity: 0
        })
    );
    assert_eq!(
        ev("1 + foo"),
        Err(NotEvaluable {
            name: foo,
            arity: 0
        })
    );
    assert_eq!(
        ev("foo(1, 2)"),
        Err(NotEvaluable {
            name: foo,
            arity: 2
        })
    );
    assert_eq!(
        ev("[]"),
        Err(NotEvaluable {
            name: atoms::NIL,
            arity: 0
        })
    );
    assert_eq!(
        ev("[1,2]"),
        Err(NotEvaluable {
            name: atoms::DOT,
            arity: 2
        })
    );
    assert_eq!(
        ev("2.5 // 1"),
        Err(Type {
            expected: "integer",
            culprit: "2.5".into()
        })
    );
    assert!(matches!(ev("1 << 1.0"), Err(Type { .. })));
    assert!(matches!(ev("msb(0)"), Err(Type { .. })));
    assert!(matches!(ev("random(0)"), Err(Type { .. })));
    assert!(matches!(
        ev("123456789012345678901234567890 + 1"),
        Err(BigInteger(_))
    ));
    // Messages name the culprit.
    assert_eq!(
        ev("foo").unwrap_err().to_string(),
        "Arithmetic: evaluable `foo/0' does not exist"
    );
    assert!(ev("'hello world'")
        .unwrap_err()
        .to_string()
        .contains("'hello world'/0"));
}

#[test]
fn arithmetic_random_is_seeded_and_in_range() {
    let mut s = Store::new();
    let (t, _) = parse(&mut s, "random(10)");
    let (u, _) = parse(&mut s, "random_float");
    s.set_random_seed(42);
    let first: Vec<Number> = (0..20).map(|_| s.eval_arith(t).unwrap()).collect();
    s.set_random_seed(42);
    let again: Vec<Number> = (0..20).map(|_| s.eval_arith(t).unwrap()).collect();
    assert_eq!(first, again);
    for _ in 0..1000 {
        match s.eval_arith(t) {
            Ok(Number::Int(i)) => assert!((0..10).contains(&i)),
            other => panic!("{other:?}"),
        }
        match s.eval_arith(u) {
            Ok(Number::Float(f)) => assert!(f > 0.0 && f < 1.0),
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn arithmetic_comparison() {
    let mut s = Store::new();
    let mut cmp = |op: &str, src: &str| {
        let (t, _) = parse(&mut s, src);
        let [a, b] = [s.arg(t, 0).unwrap(), s.arg(t, 1).unwrap()];
        s.arith_compare(ArithCmp::from_atom(Atom::intern(op)).unwrap(), a, b)
    };
    assert_eq!(cmp("=:=", "f(1, 1.0)"), Ok(true));
    assert_eq!(cmp("=\\=", "f(1, 1.0)"), Ok(false));
    assert_eq!(cmp("<", "f(1, 1.5)"), Ok(true));
    assert_eq!(cmp(">", "f(2, 1.5)"), Ok(true));
    assert_eq!(cmp("=<", "f(1+1, 2)"), Ok(true));
    assert_eq!(cmp(">=", "f(1, 2)"), Ok(false));
    assert_eq!(
        cmp("=:=", "f(9007199254740993, 9007199254740992.0)"),
        Ok(false)
    );
    assert_eq!(cmp("=:=", "f(nan, nan)"), Ok(false));
    assert_eq!(cmp("=\\=", "f(nan, nan)"), Ok(true));
    assert_eq!(cmp("<", "f(nan, 1)"), Ok(false));
    assert_eq!(cmp("<", "f(X, 1)"), Err(ArithError::Instantiation));
    assert_eq!(ArithCmp::from_atom(Atom::intern("==")), None);
}

#[test]
fn is_binds_through_unify() {
    let mut s = Store::new();
    let (t, b) = parse(&mut s, "X is 1 + 2");
    let [lhs, rhs] = [s.arg(t, 0).unwrap(), s.arg(t, 1).unwrap()];
    let v = s.eval_arith(rhs).unwrap();
    assert!(s.unify(lhs, v.into()));
    assert_eq!(s.int_of(b[0].1), Some(3));
}

// ----------------------------------------------------------- deep terms
//
// These run on the default test thread (2 MiB stack): nothing may recurse
// on depth.

const DEEP: usize = 100_000;

fn deep_term(s: &mut Store, leaf: Term) -> Term {
    let f = Atom::intern("f");
    let mut t = leaf;
    for _ in 0..DEEP {
        t = s.compound(f, &[t]);
    }
    t
}

#[test]
fn deep_terms_everything_iterative() {
    let mut s = Store::new();
    let x = s.new_var();
    let a = deep_term(&mut s, x);
    let b = deep_term(&mut s, Atom::intern("z").into());
    let c = deep_term(&mut s, Atom::intern("z").into());
    assert!(s.identical(b, c));
    assert_eq!(s.compare(b, c), Ordering::Equal);
    assert_eq!(s.compare(a, b), Ordering::Less);
    assert!(!s.is_ground(a));
    let copy = s.copy_term(a);
    assert!(s.variant(a, copy));
    assert_eq!(s.term_vars(copy).len(), 1);
    assert!(s.unify(a, b));
    assert_eq!(s.deref(x), Atom::intern("z").into());
    assert!(s.is_ground(a));
    assert!(s.identical(a, c));
    // The copy made before the binding is unaffected.
    assert!(!s.is_ground(copy));
    let text = s.writeq(a);
    assert_eq!(text.len(), DEEP * 3 + 1);
    assert!(text.starts_with("f(f(") && text.contains("(z))"));
    assert!(text.ends_with(&")".repeat(DEEP)));
    let mut roots = [a, copy];
    s.gc(&mut roots);
    assert_eq!(s.writeq(roots[0]), text);
    assert!(!s.is_ground(roots[1]));
    // Only the two roots survive: `a` (its variable short-cut to `z`) and
    // the copy, one header and one argument cell per level each.
    assert_eq!(s.stats().cells, 4 * DEEP);
    assert_eq!(s.stats().vars, 1);
    drop(s);
}

#[test]
fn deep_lists_and_operators() {
    let mut s = Store::new();
    let items: Vec<Term> = (0..DEEP as i64).map(Term::int).collect();
    let tail = s.new_var();
    let l1 = s.list_with_tail(&items, tail);
    let l2 = s.list(&items);
    assert!(s.unify(l1, l2));
    assert_eq!(s.list_to_vec(l1).map(|v| v.len()), Some(DEEP));
    assert_eq!(s.copy_term(l2), l2, "a ground list is shared, not copied");
    let copy = s.copy_term(l1);
    assert!(s.identical(copy, l2));
    let text = s.writeq(l1);
    assert!(text.starts_with("[0,1,2,") && text.ends_with(",99999]"));
    // 1+1+...+1, left-nested as the reader builds it.
    let plus = atoms::PLUS;
    let mut e = Term::int(1);
    for _ in 1..DEEP {
        e = s.compound(plus, &[e, Term::int(1)]);
    }
    assert_eq!(s.eval_arith(e), Ok(Number::Int(DEEP as i64)));
    let printed = s.writeq(e);
    assert_eq!(printed.len(), DEEP * 2 - 1);
    // Right-nested too.
    let mut r = Term::int(1);
    for _ in 1..DEEP {
        r = s.compound(plus, &[Term::int(1), r]);
    }
    assert_eq!(s.eval_arith(r), Ok(Number::Int(DEEP as i64)));
    assert!(s.writeq(r).starts_with("1+(1+(1+"));
    let mut roots = [e, r, l1];
    s.gc(&mut roots);
    assert_eq!(s.eval_arith(roots[0]), Ok(Number::Int(DEEP as i64)));
    assert_eq!(s.list_to_vec(roots[2]).map(|v| v.len()), Some(DEEP));
}

#[test]
fn deep_term_read_from_text() {
    let src = format!("{}z{}", "g(".repeat(DEEP), ")".repeat(DEEP));
    let mut s = Store::new();
    match s.parse(&src) {
        Ok((t, _)) => assert_eq!(s.writeq(t), src),
        // The reader may cap nesting; it must say so, not crash.
        Err(e) => assert!(!e.message.is_empty()),
    }
}

// ----------------------------------------------------------- properties

mod props {
    use super::*;
    use proptest::prelude::*;

    /// A term shape over a small alphabet, so random pairs often unify.
    #[derive(Clone, Debug)]
    pub(super) enum Shape {
        Var(u8),
        Atom(u8),
        Int(i8),
        Float(i8),
        Comp(u8, Vec<Shape>),
    }

    const ATOMS: [&str; 6] = ["a", "b", "[]", "hello world", "-", "==>"];
    const FUNCTORS: [&str; 5] = ["f", "g", "-", ":", "."];

    pub(super) fn shape() -> impl Strategy<Value = Shape> {
        let leaf = prop_oneof![
            (0u8..4).prop_map(Shape::Var),
            (0u8..ATOMS.len() as u8).prop_map(Shape::Atom),
            (-2i8..3).prop_map(Shape::Int),
            (-2i8..3).prop_map(Shape::Float),
        ];
        leaf.prop_recursive(4, 40, 3, |inner| {
            (
                0u8..FUNCTORS.len() as u8,
                prop::collection::vec(inner, 1..4),
            )
                .prop_map(|(f, args)| Shape::Comp(f, args))
        })
    }

    /// Builds a shape; variables `Var(k)` are shared through `vars`.
    pub(super) fn build(s: &mut Store, shape: &Shape, vars: &mut Vec<Term>) -> Term {
        match shape {
            Shape::Var(k) => {
                while vars.len() <= *k as usize {
                    let v = s.new_var();
                    vars.push(v);
                }
                vars[*k as usize]
            }
            Shape::Atom(k) => Atom::intern(ATOMS[*k as usize]).into(),
            Shape::Int(i) => Term::int(i64::from(*i)),
            Shape::Float(i) => Term::float(f64::from(*i) / 2.0),
            Shape::Comp(f, args) => {
                let args: Vec<Term> = args.iter().map(|a| build(s, a, vars)).collect();
                s.compound(Atom::intern(FUNCTORS[*f as usize]), &args)
            }
        }
    }

    fn cases() -> ProptestConfig {
        let cases = std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|c| c.parse().ok())
            .unwrap_or(256);
        ProptestConfig::with_cases(cases)
    }

    proptest! {
        #![proptest_config(cases())]

        #[test]
        fn unify_is_symmetric(x in shape(), y in shape()) {
            let mut s = Store::new();
            let mut vars = Vec::new();
            let a = build(&mut s, &x, &mut vars);
            let b = build(&mut s, &y, &mut vars);
            let mut all = vec![a, b];
            all.extend(vars.iter().copied());
            let snapshot = s.compound(Atom::intern("snap"), &all);
            let m = s.mark();
            let r1 = s.unify(a, b);
            if r1 && !s.is_acyclic(snapshot) {
                // No occurs check: a cyclic unifier. Both orders agree on
                // success; copies of cyclic terms are out of scope.
                s.undo_to(m);
                prop_assert!(s.unify(b, a));
                return Ok(());
            }
            let c1 = s.copy_term(snapshot);
            if r1 {
                prop_assert!(s.identical(a, b));
            } else {
                prop_assert_eq!(s.stats().trail, 0, "failed unify left bindings");
            }
            s.undo_to(m);
            let r2 = s.unify(b, a);
            let c2 = s.copy_term(snapshot);
            prop_assert_eq!(r1, r2);
            if r2 {
                prop_assert!(s.identical(a, b));
            }
            // Same most general unifier up to renaming.
            prop_assert!(s.variant(c1, c2), "{} vs {}", s.writeq(c1), s.writeq(c2));
            s.undo_to(m);
            prop_assert!(vars.iter().all(|&v| s.is_var(v)));
        }

        #[test]
        fn copy_term_gives_a_variant(x in shape()) {
            let mut s = Store::new();
            let mut vars = Vec::new();
            let a = build(&mut s, &x, &mut vars);
            let c = s.copy_term(a);
            prop_assert!(s.variant(a, c));
            let va = s.term_vars(a);
            let vc = s.term_vars(c);
            prop_assert_eq!(va.len(), vc.len());
            prop_assert!(vc.iter().all(|v| !va.contains(v)), "copy shares variables");
            prop_assert_eq!(s.is_ground(a), va.is_empty());
            // Binding the copy leaves the original alone.
            for &v in &vc {
                prop_assert!(s.unify(v, Term::int(0)));
            }
            prop_assert!(va.iter().all(|&v| s.is_var(v)));
        }

        #[test]
        fn compare_is_a_total_order_consistent_with_identical(
            x in shape(), y in shape(), z in shape()
        ) {
            let mut s = Store::new();
            let mut vars = Vec::new();
            let a = build(&mut s, &x, &mut vars);
            let b = build(&mut s, &y, &mut vars);
            let c = build(&mut s, &z, &mut vars);
            for (p, q) in [(a, b), (b, c), (a, c)] {
                let o = s.compare(p, q);
                prop_assert_eq!(o, s.compare(q, p).reverse());
                prop_assert_eq!(o == Ordering::Equal, s.identical(p, q));
            }
            prop_assert_eq!(s.compare(a, a), Ordering::Equal);
            let mut sorted = [a, b, c];
            sorted.sort_by(|&p, &q| s.compare(p, q));
            let [p, q, r] = sorted;
            prop_assert!(s.compare(p, q) != Ordering::Greater);
            prop_assert!(s.compare(q, r) != Ordering::Greater);
            prop_assert!(s.compare(p, r) != Ordering::Greater, "not transitive");
            // A copy of a ground term compares equal to it.
            let ca = s.copy_term(a);
            if s.is_ground(a) {
                prop_assert_eq!(s.compare(a, ca), Ordering::Equal);
            }
        }

        #[test]
        fn gc_preserves_reachable_terms(x in shape(), y in shape()) {
            let mut s = Store::new();
            let mut vars = Vec::new();
            let a = build(&mut s, &x, &mut vars);
            let b = build(&mut s, &y, &mut vars);
            let _ = s.unify(a, b);
            let pair = s.compound(Atom::intern("p"), &[a, b]);
            // Unification without occurs check may have made a cyclic term,
            // which copy_term and writeq do not handle (see `copy`).
            if !s.is_acyclic(pair) {
                return Ok(());
            }
            let garbage = build(&mut s, &y, &mut vars);
            let _ = s.copy_term(garbage);
            let before = normalize_vars(&s.writeq(pair));
            let mut roots = [pair, a];
            s.gc(&mut roots);
            prop_assert_eq!(normalize_vars(&s.writeq(roots[0])), before);
            let first = s.arg(roots[0], 0).unwrap();
            prop_assert!(s.identical(first, roots[1]), "sharing between roots lost");
        }

        #[test]
        fn writeq_reads_back(x in shape()) {
            let mut s = Store::new();
            let mut vars = Vec::new();
            let a = build(&mut s, &x, &mut vars);
            let text = s.writeq(a);
            let (back, _) = s.parse(&text).map_err(|e| {
                TestCaseError::fail(format!("{text}: {e}"))
            })?;
            prop_assert!(s.variant(a, back), "{} read back as {}", text, s.writeq(back));
        }
    }
}
