//! Read terms: an arena of nodes with byte spans, one arena per clause.
//!
//! An arena (not a tree of boxes) so that dropping, cloning and comparing
//! a 100 000-deep term never recurses.

use crate::atom::{atoms, Atom};
use std::collections::HashMap;

/// A byte range in the source text.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Span {
    pub start: u32,
    pub end: u32,
}

impl Span {
    pub fn new(start: usize, end: usize) -> Span {
        Span {
            start: start as u32,
            end: end as u32,
        }
    }
    pub fn to(self, other: Span) -> Span {
        Span {
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }
    pub fn range(self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }
}

/// Index of a node in its [`Terms`] arena.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TermId(pub u32);

/// Index of a variable in its clause's [`Clause::vars`] table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct VarId(pub u32);

/// One node of a read term.
#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    Var(VarId),
    Atom(Atom),
    Int(i64),
    /// An integer that does not fit in `i64`, as decimal digits with optional `-`.
    BigInt(Box<str>),
    Float(f64),
    /// A double-quoted string (escapes resolved). Original SitLog reads it as a code list.
    Str(Box<str>),
    /// A back-quoted string (escapes resolved): a code list.
    BackQuoted(Box<str>),
    /// `functor(args...)`; lists are `'.'(Head, Tail)` ending in `[]`.
    Compound {
        functor: Atom,
        first_arg: u32,
        arity: u32,
    },
}

/// A term arena: nodes, their spans, and the argument lists of compounds.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Terms {
    nodes: Vec<Node>,
    spans: Vec<Span>,
    args: Vec<TermId>,
}

impl Terms {
    pub fn new() -> Terms {
        Terms::default()
    }
    pub fn node(&self, id: TermId) -> &Node {
        &self.nodes[id.0 as usize]
    }
    pub fn span(&self, id: TermId) -> Span {
        self.spans[id.0 as usize]
    }
    pub fn args(&self, id: TermId) -> &[TermId] {
        match self.nodes[id.0 as usize] {
            Node::Compound {
                first_arg, arity, ..
            } => &self.args[first_arg as usize..(first_arg + arity) as usize],
            _ => &[],
        }
    }
    pub fn len(&self) -> usize {
        self.nodes.len()
    }
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
    pub fn push(&mut self, node: Node, span: Span) -> TermId {
        let id = TermId(self.nodes.len() as u32);
        self.nodes.push(node);
        self.spans.push(span);
        id
    }
    pub fn push_compound(&mut self, functor: Atom, args: &[TermId], span: Span) -> TermId {
        let first_arg = self.args.len() as u32;
        self.args.extend_from_slice(args);
        self.push(
            Node::Compound {
                functor,
                first_arg,
                arity: args.len() as u32,
            },
            span,
        )
    }
    /// The atom if `id` is an atom.
    pub fn atom(&self, id: TermId) -> Option<Atom> {
        match self.node(id) {
            Node::Atom(a) => Some(*a),
            _ => None,
        }
    }
    /// Name and arity of an atom (arity 0) or compound; `None` for other nodes.
    pub fn functor(&self, id: TermId) -> Option<(Atom, usize)> {
        match self.node(id) {
            Node::Atom(a) => Some((*a, 0)),
            Node::Compound { functor, arity, .. } => Some((*functor, *arity as usize)),
            _ => None,
        }
    }
    /// The arguments if `id` is `name(..)` with exactly `arity` arguments.
    pub fn compound(&self, id: TermId, name: Atom, arity: usize) -> Option<&[TermId]> {
        match self.node(id) {
            Node::Compound {
                functor, arity: a, ..
            } if *functor == name && *a as usize == arity => Some(self.args(id)),
            _ => None,
        }
    }
    /// The elements of a proper or partial list and its tail (`[]` for a proper list).
    /// Iterative, so arbitrarily long lists are fine.
    pub fn list(&self, id: TermId) -> (Vec<TermId>, TermId) {
        let mut items = Vec::new();
        let mut cur = id;
        while let Some(args) = self.compound(cur, atoms::DOT, 2) {
            items.push(args[0]);
            cur = args[1];
        }
        (items, cur)
    }
    /// `Some(items)` if `id` is a proper list.
    pub fn proper_list(&self, id: TermId) -> Option<Vec<TermId>> {
        let (items, tail) = self.list(id);
        (self.atom(tail) == Some(atoms::NIL)).then_some(items)
    }
    /// Copies the term `id` of `other` into `self` (spans kept); iterative.
    pub fn import(&mut self, other: &Terms, id: TermId) -> TermId {
        // Post-order with an explicit stack: children first, then the parent.
        let mut done: Vec<TermId> = Vec::new();
        let mut stack: Vec<(TermId, bool)> = vec![(id, false)];
        while let Some((t, expanded)) = stack.pop() {
            match other.node(t) {
                Node::Compound { functor, .. } => {
                    if expanded {
                        let n = other.args(t).len();
                        let args = done.split_off(done.len() - n);
                        let new = self.push_compound(*functor, &args, other.span(t));
                        done.push(new);
                    } else {
                        stack.push((t, true));
                        for &a in other.args(t).iter().rev() {
                            stack.push((a, false));
                        }
                    }
                }
                node => {
                    let new = self.push(node.clone(), other.span(t));
                    done.push(new);
                }
            }
        }
        done.pop().expect("import produced a term")
    }
}

/// Facts about one variable of a clause.
#[derive(Clone, Debug, PartialEq)]
pub struct VarInfo {
    /// The name as written; `_` for each anonymous variable (each is distinct).
    pub name: Box<str>,
    /// Span of the first occurrence.
    pub first: Span,
    /// How many times it occurs in the clause.
    pub occurrences: u32,
}

impl VarInfo {
    /// `_` or `_Name`: Prolog does not warn about these being singletons.
    pub fn is_anonymous_style(&self) -> bool {
        self.name.starts_with('_')
    }
}

/// One clause (a term read up to its end `.`), with its variable table.
#[derive(Clone, Debug, PartialEq)]
pub struct Clause {
    pub terms: Terms,
    pub root: TermId,
    pub vars: Vec<VarInfo>,
    /// From the first token to the end `.` inclusive.
    pub span: Span,
}

impl Clause {
    pub fn var_name(&self, var: VarId) -> &str {
        &self.vars[var.0 as usize].name
    }

    /// Whether the two clauses hold the same term up to renaming of
    /// variables (spans and variable names ignored; floats compared by bits,
    /// so -0.0 differs from 0.0; any NaN equals any NaN). Iterative: any depth is fine.
    pub fn is_variant_of(&self, other: &Clause) -> bool {
        let mut map_a: HashMap<VarId, VarId> = HashMap::new();
        let mut map_b: HashMap<VarId, VarId> = HashMap::new();
        let mut stack = vec![(self.root, other.root)];
        while let Some((a, b)) = stack.pop() {
            let same = match (self.terms.node(a), other.terms.node(b)) {
                (Node::Var(x), Node::Var(y)) => {
                    *map_a.entry(*x).or_insert(*y) == *y && *map_b.entry(*y).or_insert(*x) == *x
                }
                (Node::Float(x), Node::Float(y)) => {
                    x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan())
                }
                (
                    Node::Compound {
                        functor: f,
                        arity: n,
                        ..
                    },
                    Node::Compound {
                        functor: g,
                        arity: m,
                        ..
                    },
                ) => {
                    if f == g && n == m {
                        let (xs, ys) = (self.terms.args(a), other.terms.args(b));
                        stack.extend(xs.iter().copied().zip(ys.iter().copied()));
                        true
                    } else {
                        false
                    }
                }
                (x, y) => x == y,
            };
            if !same {
                return false;
            }
        }
        true
    }
}
