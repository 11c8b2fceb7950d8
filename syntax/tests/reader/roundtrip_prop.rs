//! Property tests: generated terms print (writeq) to text that reads back as
//! the same term (spans ignored, variables up to renaming), with SitLog's
//! operator table; and arbitrary token soup never makes the reader panic.
//! CI caps the cases with PROPTEST_CASES=64.

use proptest::prelude::*;
use sitlog_syntax::{
    read_clauses, read_term, writeq, Atom, Clause, Node, Span, TermId, Terms, VarInfo,
};

/// A generated term, built into a clause arena afterwards.
#[derive(Clone, Debug)]
enum T {
    Var(u8),
    Anon,
    Atom(String),
    Int(i64),
    Big(String),
    Float(f64),
    Str(String),
    Compound(String, Vec<T>),
    List(Vec<T>, Option<Box<T>>),
}

/// Names that exercise quoting and operators (as atoms and as functors).
const NAMES: &[&str] = &[
    "a",
    "foo",
    "b_1",
    "é",
    "hello world",
    "A",
    "_x",
    "",
    "'",
    "\"",
    "\\",
    "[]",
    "{}",
    ",",
    "|",
    "||",
    "!",
    ";",
    ".",
    "a.b",
    "-",
    "+",
    "*",
    "**",
    "^",
    "\\+",
    "\\",
    ":-",
    "?-",
    "-->",
    "->",
    ":",
    "=>",
    "==>",
    "=>>",
    "=",
    "\\=",
    "==",
    "=..",
    "is",
    "mod",
    "rem",
    "<",
    ">=",
    "@<",
    "$",
    "dynamic",
    "table",
    "end_of_file",
    "1a",
    "a\nb",
    "tab\there",
    "\u{7}\u{0}",
    "x\u{A0}y",
    "ω",
    "Ωmega",
    "/*",
    "%",
    "%a",
    "0'",
    "e+1",
];

fn name() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => prop::sample::select(NAMES).prop_map(str::to_owned),
        1 => "[a-z][a-zA-Z0-9_]{0,6}",
        1 => "[ -~]{0,5}",
        1 => "[#$&*+./:<=>?@^~\\\\-]{1,3}",
    ]
}

fn float() -> impl Strategy<Value = f64> {
    prop_oneof![
        prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO,
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(f64::NAN),
        Just(-0.0),
        Just(1e15),
        Just(1e-5),
        Just(0.22999999999999998),
    ]
}

fn leaf() -> impl Strategy<Value = T> {
    prop_oneof![
        2 => (0u8..4).prop_map(T::Var),
        1 => Just(T::Anon),
        4 => name().prop_map(T::Atom),
        2 => any::<i64>().prop_map(T::Int),
        1 => prop::sample::select(&[-3i64, -1, 0, 1, 2][..]).prop_map(T::Int),
        1 => "-?[1-9][0-9]{19,30}".prop_map(T::Big),
        2 => float().prop_map(T::Float),
        1 => "[ -~\n\t\u{e9}]{0,6}".prop_map(T::Str),
    ]
}

fn term() -> impl Strategy<Value = T> {
    leaf().prop_recursive(6, 64, 4, |inner| {
        prop_oneof![
            // Operators of every type, by arity: binary (infix), unary (prefix).
            3 => (name(), inner.clone(), inner.clone()).prop_map(|(f, a, b)| T::Compound(f, vec![a, b])),
            3 => (name(), inner.clone()).prop_map(|(f, a)| T::Compound(f, vec![a])),
            1 => (name(), prop::collection::vec(inner.clone(), 0..4)).prop_map(|(f, a)| T::Compound(f, a)),
            1 => inner.clone().prop_map(|a| T::Compound("{}".into(), vec![a])),
            2 => (
                prop::collection::vec(inner.clone(), 1..4),
                prop::option::of(inner.clone().prop_map(Box::new))
            )
                .prop_map(|(items, tail)| T::List(items, tail)),
        ]
    })
}

struct Builder {
    terms: Terms,
    vars: Vec<VarInfo>,
    named: [Option<u32>; 4],
}

impl Builder {
    fn var(&mut self, name: &str, slot: Option<usize>) -> Node {
        if let Some(i) = slot {
            if let Some(id) = self.named[i] {
                return Node::Var(sitlog_syntax::VarId(id));
            }
        }
        let id = self.vars.len() as u32;
        self.vars.push(VarInfo {
            name: name.into(),
            first: Span::default(),
            occurrences: 1,
        });
        if let Some(i) = slot {
            self.named[i] = Some(id);
        }
        Node::Var(sitlog_syntax::VarId(id))
    }

    fn build(&mut self, t: &T) -> TermId {
        let s = Span::default();
        let node = match t {
            T::Var(i) => {
                let names = ["X", "Y", "_Z", "Abc_1"];
                self.var(names[*i as usize], Some(*i as usize))
            }
            T::Anon => self.var("_", None),
            T::Atom(a) => Node::Atom(Atom::intern(a)),
            T::Int(i) => Node::Int(*i),
            T::Big(b) => Node::BigInt(b.as_str().into()),
            T::Float(f) => Node::Float(*f),
            T::Str(x) => Node::Str(x.as_str().into()),
            T::Compound(f, args) => {
                let ids: Vec<TermId> = args.iter().map(|a| self.build(a)).collect();
                return self.terms.push_compound(Atom::intern(f), &ids, s);
            }
            T::List(items, tail) => {
                let mut list = match tail {
                    Some(t) => self.build(t),
                    None => self.terms.push(Node::Atom(sitlog_syntax::atoms::NIL), s),
                };
                let ids: Vec<TermId> = items.iter().map(|a| self.build(a)).collect();
                for id in ids.into_iter().rev() {
                    list = self
                        .terms
                        .push_compound(sitlog_syntax::atoms::DOT, &[id, list], s);
                }
                return list;
            }
        };
        self.terms.push(node, s)
    }
}

fn clause_of(t: &T) -> Clause {
    let mut b = Builder {
        terms: Terms::new(),
        vars: Vec::new(),
        named: [None; 4],
    };
    let root = b.build(t);
    Clause {
        terms: b.terms,
        root,
        vars: b.vars,
        span: Span::default(),
    }
}

fn config() -> ProptestConfig {
    // PROPTEST_CASES (CI: 64) overrides the default of 256.
    ProptestConfig {
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn print_then_read_gives_the_same_term(t in term()) {
        let clause = clause_of(&t);
        let printed = writeq(&clause, clause.root);
        let again = read_term(&format!("{printed} ."));
        prop_assert!(again.is_ok(), "{printed:?} does not read back: {again:?}");
        let again = again.unwrap();
        prop_assert!(
            clause.is_variant_of(&again),
            "{printed:?} reads back as {:?}",
            writeq(&again, again.root)
        );
        // Printing is stable.
        prop_assert_eq!(writeq(&again, again.root), printed);
    }

    #[test]
    fn token_soup_never_panics_and_what_reads_round_trips(
        parts in prop::collection::vec(prop::sample::select(&[
            "a", "X", "_", "f(", "(", ")", "[", "]", "{", "}", ",", "|", ".", " ", "\n", "- ", "-",
            "1", "2.5", "0'a", "'q w'", "\"s\"", ":", "=>", "==>", ":-", "\\+", "is", ";", "->",
            "%c\n", "/*c*/", "e", "*", "0x1F", "1.0e10", "1.0Inf", "é", "'", "0'", "\\",
        ][..]), 0..40)
    ) {
        let src: String = parts.concat();
        let (clauses, _errors) = read_clauses(&src);
        for clause in &clauses {
            let printed = writeq(clause, clause.root);
            let again = read_term(&format!("{printed} ."));
            prop_assert!(again.is_ok(), "{src:?}: {printed:?} does not read back: {again:?}");
            prop_assert!(clause.is_variant_of(&again.unwrap()), "{src:?}: {printed:?}");
        }
    }
}
