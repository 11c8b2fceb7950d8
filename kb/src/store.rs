//! The KB's term store: every ground term of a KB (ids, entries, values,
//! weights) hash-consed once, so that comparing two terms is comparing two
//! `u32`s on the hot paths of the closure.
//!
//! Also owns [`Built`], the small arena in which answers are assembled on top
//! of the store (list cells, `Ind:Value` pairs, `p=>v` built at query time)
//! without mutating the shared store.

use sitlog_syntax::write::{TermSource, View};
use sitlog_syntax::{atoms, Atom, Clause, Node, Span, TermId};
use std::collections::HashMap;

/// A hash-consed ground term: equal terms have equal ids.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TId(pub u32);

#[derive(Clone, Debug, PartialEq)]
pub(crate) enum SNode {
    Atom(Atom),
    Int(i64),
    BigInt(Box<str>),
    Float(f64),
    Str(Box<str>),
    BackQuoted(Box<str>),
    Compound { f: Atom, first: u32, arity: u32 },
}

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum Key {
    Atom(Atom),
    Int(i64),
    BigInt(Box<str>),
    Float(u64),
    Str(Box<str>),
    BackQuoted(Box<str>),
    Compound(Atom, Box<[TId]>),
}

/// The hash-consing store (append only: ids stay valid for the store's life).
#[derive(Clone, Debug, Default)]
pub struct TermStore {
    nodes: Vec<SNode>,
    args: Vec<TId>,
    index: HashMap<Key, TId>,
    /// Compounds of arity 1 and 2 again, found without allocating a key
    /// (`not(X)`, `P=>V`, `[E, W]` cells are looked up on hot paths).
    small: HashMap<(Atom, u32, u32), TId>,
}

fn leaf_key(node: &Node) -> Option<Key> {
    Some(match node {
        Node::Atom(a) => Key::Atom(*a),
        Node::Int(i) => Key::Int(*i),
        Node::BigInt(s) => Key::BigInt(s.clone()),
        Node::Float(f) => Key::Float(f.to_bits()),
        Node::Str(s) => Key::Str(s.clone()),
        Node::BackQuoted(s) => Key::BackQuoted(s.clone()),
        Node::Var(_) | Node::Compound { .. } => return None,
    })
}

impl TermStore {
    pub fn new() -> TermStore {
        TermStore::default()
    }

    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    fn insert(&mut self, key: Key) -> TId {
        if let Some(&t) = self.index.get(&key) {
            return t;
        }
        let id = TId(self.nodes.len() as u32);
        let node = match &key {
            Key::Atom(a) => SNode::Atom(*a),
            Key::Int(i) => SNode::Int(*i),
            Key::BigInt(s) => SNode::BigInt(s.clone()),
            Key::Float(b) => SNode::Float(f64::from_bits(*b)),
            Key::Str(s) => SNode::Str(s.clone()),
            Key::BackQuoted(s) => SNode::BackQuoted(s.clone()),
            Key::Compound(f, args) => {
                let first = self.args.len() as u32;
                self.args.extend_from_slice(args);
                SNode::Compound {
                    f: *f,
                    first,
                    arity: args.len() as u32,
                }
            }
        };
        if let Key::Compound(f, args) = &key {
            match args[..] {
                [a] => {
                    self.small.insert((*f, a.0, u32::MAX), id);
                }
                [a, b] => {
                    self.small.insert((*f, a.0, b.0), id);
                }
                _ => {}
            }
        }
        self.nodes.push(node);
        self.index.insert(key, id);
        id
    }

    pub fn atom(&mut self, a: Atom) -> TId {
        self.insert(Key::Atom(a))
    }

    pub fn int(&mut self, i: i64) -> TId {
        self.insert(Key::Int(i))
    }

    pub fn compound(&mut self, f: Atom, args: &[TId]) -> TId {
        if args.is_empty() {
            return self.atom(f);
        }
        if let Some(t) = self.find_compound(f, args) {
            return t;
        }
        self.insert(Key::Compound(f, args.into()))
    }

    pub fn list(&mut self, items: &[TId]) -> TId {
        let mut tail = self.atom(atoms::NIL);
        for &item in items.iter().rev() {
            tail = self.compound(atoms::DOT, &[item, tail]);
        }
        tail
    }

    /// The id of an existing atom, if the store has it.
    pub fn find_atom(&self, a: Atom) -> Option<TId> {
        self.index.get(&Key::Atom(a)).copied()
    }

    /// The id of an existing compound, if the store has it.
    pub fn find_compound(&self, f: Atom, args: &[TId]) -> Option<TId> {
        match args {
            [] => self.find_atom(f),
            [a] => self.small.get(&(f, a.0, u32::MAX)).copied(),
            [a, b] => self.small.get(&(f, a.0, b.0)).copied(),
            _ => self.index.get(&Key::Compound(f, args.into())).copied(),
        }
    }

    pub(crate) fn node(&self, t: TId) -> &SNode {
        &self.nodes[t.0 as usize]
    }

    /// Name and arguments of an atom (no arguments) or compound.
    pub fn functor(&self, t: TId) -> Option<(Atom, &[TId])> {
        match self.node(t) {
            SNode::Atom(a) => Some((*a, &[])),
            SNode::Compound { f, first, arity } => {
                Some((*f, &self.args[*first as usize..(*first + *arity) as usize]))
            }
            _ => None,
        }
    }

    pub fn as_atom(&self, t: TId) -> Option<Atom> {
        match self.node(t) {
            SNode::Atom(a) => Some(*a),
            _ => None,
        }
    }

    /// The two arguments if `t` is `name(A, B)`.
    pub fn binary(&self, t: TId, name: Atom) -> Option<(TId, TId)> {
        match self.functor(t) {
            Some((f, [a, b])) if f == name => Some((*a, *b)),
            _ => None,
        }
    }

    /// The argument if `t` is `name(A)`.
    pub fn unary(&self, t: TId, name: Atom) -> Option<TId> {
        match self.functor(t) {
            Some((f, [a])) if f == name => Some(*a),
            _ => None,
        }
    }

    /// The items of a proper list.
    pub fn proper_list(&self, t: TId) -> Option<Vec<TId>> {
        let mut items = Vec::new();
        let mut cur = t;
        loop {
            match self.functor(cur) {
                Some((f, [h, tail])) if f == atoms::DOT => {
                    items.push(*h);
                    cur = *tail;
                }
                Some((f, [])) if f == atoms::NIL => return Some(items),
                _ => return None,
            }
        }
    }

    /// The numeric value of a number term.
    pub fn number(&self, t: TId) -> Option<f64> {
        match self.node(t) {
            SNode::Int(i) => Some(*i as f64),
            SNode::Float(f) => Some(*f),
            SNode::BigInt(s) => s.parse::<f64>().ok(),
            _ => None,
        }
    }

    /// Interns term `root` of `clause`; `Err(span)` at the first variable.
    /// Iterative, so deep terms are fine.
    pub fn intern(&mut self, clause: &Clause, root: TermId) -> Result<TId, Span> {
        self.walk(clause, root, &mut |s, key| Some(s.insert(key)))
            .map(|t| t.unwrap_or(TId(0)))
    }

    /// Finds term `root` of `clause` without interning: `Ok(None)` if the
    /// store does not hold it (then it equals no KB term).
    pub fn find(&self, clause: &Clause, root: TermId) -> Result<Option<TId>, Span> {
        let mut missing = false;
        let r = walk_ro(self, clause, root, &mut missing)?;
        Ok(if missing { None } else { r })
    }

    fn walk(
        &mut self,
        clause: &Clause,
        root: TermId,
        make: &mut dyn FnMut(&mut TermStore, Key) -> Option<TId>,
    ) -> Result<Option<TId>, Span> {
        let terms = &clause.terms;
        let mut done: Vec<TId> = Vec::new();
        let mut stack: Vec<(TermId, bool)> = vec![(root, false)];
        while let Some((t, expanded)) = stack.pop() {
            match terms.node(t) {
                Node::Var(_) => return Err(terms.span(t)),
                Node::Compound { functor, .. } => {
                    let args = terms.args(t);
                    if expanded {
                        let kids = done.split_off(done.len() - args.len());
                        match make(self, Key::Compound(*functor, kids.into())) {
                            Some(id) => done.push(id),
                            None => return Ok(None),
                        }
                    } else {
                        stack.push((t, true));
                        for &a in args.iter().rev() {
                            stack.push((a, false));
                        }
                    }
                }
                node => {
                    let key = leaf_key(node).ok_or(terms.span(t))?;
                    match make(self, key) {
                        Some(id) => done.push(id),
                        None => return Ok(None),
                    }
                }
            }
        }
        Ok(done.pop())
    }
}

fn walk_ro(
    store: &TermStore,
    clause: &Clause,
    root: TermId,
    missing: &mut bool,
) -> Result<Option<TId>, Span> {
    let terms = &clause.terms;
    let mut done: Vec<TId> = Vec::new();
    let mut stack: Vec<(TermId, bool)> = vec![(root, false)];
    while let Some((t, expanded)) = stack.pop() {
        match terms.node(t) {
            Node::Var(_) => return Err(terms.span(t)),
            Node::Compound { functor, .. } => {
                let args = terms.args(t);
                if expanded {
                    let kids = done.split_off(done.len() - args.len());
                    // Once something is missing, keep scanning only to report variables.
                    let id = if *missing {
                        TId(0)
                    } else if let Some(&id) = store.index.get(&Key::Compound(*functor, kids.into()))
                    {
                        id
                    } else {
                        *missing = true;
                        TId(0)
                    };
                    done.push(id);
                } else {
                    stack.push((t, true));
                    for &a in args.iter().rev() {
                        stack.push((a, false));
                    }
                }
            }
            node => {
                let key = leaf_key(node).ok_or(terms.span(t))?;
                match store.index.get(&key) {
                    Some(&id) => done.push(id),
                    None => {
                        *missing = true;
                        done.push(TId(0));
                    }
                }
            }
        }
    }
    Ok(done.pop())
}

fn view_node<'a>(node: &'a SNode, args: &'a [TId]) -> View<'a, TId> {
    match node {
        SNode::Atom(a) => View::Atom(*a),
        SNode::Int(i) => View::Int(*i),
        SNode::BigInt(s) => View::BigInt(s),
        SNode::Float(f) => View::Float(*f),
        SNode::Str(s) => View::Str(s),
        SNode::BackQuoted(s) => View::BackQuoted(s),
        SNode::Compound { f, first, arity } => {
            View::Compound(*f, &args[*first as usize..(*first + *arity) as usize])
        }
    }
}

impl TermSource for TermStore {
    type Ref = TId;
    fn view(&self, term: TId) -> View<'_, TId> {
        view_node(self.node(term), &self.args)
    }
}

/// Terms built on top of a store: ids below the store's length are the
/// store's, ids above are this arena's.
#[derive(Clone, Debug)]
pub struct Built<'s> {
    store: &'s TermStore,
    base: u32,
    nodes: Vec<SNode>,
    args: Vec<TId>,
}

impl<'s> Built<'s> {
    pub fn new(store: &'s TermStore) -> Built<'s> {
        Built {
            store,
            base: store.len() as u32,
            nodes: Vec::new(),
            args: Vec::new(),
        }
    }

    /// Room for `nodes` more nodes with `args` more arguments in all.
    pub fn reserve(&mut self, nodes: usize, args: usize) {
        self.nodes.reserve(nodes);
        self.args.reserve(args);
    }

    pub fn store(&self) -> &'s TermStore {
        self.store
    }

    fn push(&mut self, node: SNode) -> TId {
        let id = TId(self.base + self.nodes.len() as u32);
        self.nodes.push(node);
        id
    }

    pub fn atom(&mut self, a: Atom) -> TId {
        match self.store.find_atom(a) {
            Some(t) => t,
            None => self.push(SNode::Atom(a)),
        }
    }

    pub fn compound(&mut self, f: Atom, args: &[TId]) -> TId {
        if args.is_empty() {
            return self.atom(f);
        }
        if args.iter().all(|a| a.0 < self.base) {
            if let Some(t) = self.store.find_compound(f, args) {
                return t;
            }
        }
        let first = self.args.len() as u32;
        self.args.extend_from_slice(args);
        self.push(SNode::Compound {
            f,
            first,
            arity: args.len() as u32,
        })
    }

    pub fn list(&mut self, items: &[TId]) -> TId {
        self.list_from(items.iter().copied())
    }

    /// A new compound in this arena, without looking for it in the store
    /// (cheaper when the term is only printed or walked).
    pub fn fresh(&mut self, f: Atom, args: &[TId]) -> TId {
        if args.is_empty() {
            return self.atom(f);
        }
        let first = self.args.len() as u32;
        self.args.extend_from_slice(args);
        self.push(SNode::Compound {
            f,
            first,
            arity: args.len() as u32,
        })
    }

    /// A list built from an iterator of items without collecting them first.
    pub fn list_from(&mut self, items: impl DoubleEndedIterator<Item = TId>) -> TId {
        let mut tail = self.atom(atoms::NIL);
        for item in items.rev() {
            let first = self.args.len() as u32;
            self.args.push(item);
            self.args.push(tail);
            tail = self.push(SNode::Compound {
                f: atoms::DOT,
                first,
                arity: 2,
            });
        }
        tail
    }

    pub fn writeq(&self, t: TId) -> String {
        sitlog_syntax::writeq(self, t)
    }
}

impl TermSource for Built<'_> {
    type Ref = TId;
    fn view(&self, term: TId) -> View<'_, TId> {
        if term.0 < self.base {
            self.store.view(term)
        } else {
            view_node(&self.nodes[(term.0 - self.base) as usize], &self.args)
        }
    }
}
