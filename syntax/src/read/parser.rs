//! The parser behind every reader entry point: one clause (or term) by
//! precedence climbing over the operator table, on the tokens of
//! [`crate::lexer`]. It is iterative (an explicit stack of pending
//! [`Level`]s), so deep terms never touch the native stack; a depth limit
//! ([`MAX_DEPTH`] at most) turns absurd nesting into an error instead of
//! exhausting memory.

use crate::atom::{atoms, Atom};
use crate::error::{SyntaxError, TOO_DEEP};
use crate::lexer::{Lexer, TokKind, Token};
use crate::ops::OpTable;
use crate::term::{Clause, Node, Span, TermId, Terms, VarId, VarInfo};
use std::collections::HashMap;

/// Deepest nesting of terms the reader accepts.
pub const MAX_DEPTH: usize = 1_000_000;

pub(super) struct Parser<'s, 'o> {
    lexer: Lexer<'s>,
    ops: &'o OpTable,
    pub(super) tok: Token,
    /// One token of lookahead beyond `tok`, filled on demand.
    peeked: Option<Token>,
    terms: Terms,
    vars: Vec<VarInfo>,
    var_ids: HashMap<&'s str, VarId>,
    open: Vec<(Span, char)>,
    /// Elements and arguments read so far, for every open list and compound.
    scratch: Vec<TermId>,
    last_end: usize,
    /// Whether the token before `tok` was a `,` (for "trailing comma" help).
    comma_before_tok: bool,
    /// Deepest nesting allowed ([`MAX_DEPTH`] for source files).
    pub(super) max_depth: usize,
}

/// Errors are boxed inside the parser so that its recursive frames stay small.
pub(super) type PResult<T> = Result<T, Box<SyntaxError>>;

/// Where a term is read: at the top of a clause or inside brackets, as an
/// argument of a compound (`,` ends it), or as a list element (`,` and `|`
/// end it). SWI-Prolog 7+ reads arguments and elements at priority 1200,
/// so `f(a :- b)` and `[a -> b]` are accepted, as in SWI.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Ctx {
    Top,
    Arg,
    Elem,
}

/// What to do with the term a [`Level`] reads once it is complete.
#[derive(Clone, Copy, Debug)]
enum Cont {
    /// The term asked for by the caller of `parse`.
    Root,
    /// The right operand of `name`, whose left operand is `left`.
    InfixRight { left: TermId, name: Atom, prio: u16 },
    /// The operand of a prefix operator.
    PrefixArg { atom: Atom, span: Span, prio: u16 },
    /// The contents of `( )`.
    Paren,
    /// The contents of `{ }`.
    Curly { open: Span },
    /// A list element; the list's earlier elements are `scratch[items..]`.
    Elem { open: Span, items: usize },
    /// The tail after `|` in a list.
    Tail { open: Span, items: usize },
    /// An argument of `name(`; earlier arguments are `scratch[args..]`.
    Arg {
        name: Atom,
        start: Span,
        args: usize,
    },
}

/// One pending `parse(max, ctx)`.
#[derive(Clone, Copy, Debug)]
struct Level {
    max: u16,
    ctx: Ctx,
    cont: Cont,
}

/// The outcome of one step: a complete term with its priority, or a level
/// to read first.
enum Step {
    Done(TermId, u16),
    Push(u16, Ctx, Cont),
}

impl<'s, 'o> Parser<'s, 'o> {
    pub(super) fn new(src: &'s str, pos: usize, ops: &'o OpTable) -> PResult<Parser<'s, 'o>> {
        if src.len() >= u32::MAX as usize {
            return Err(Box::new(SyntaxError::new(
                Span::new(0, 0),
                "source text is larger than 4 GiB".into(),
            )));
        }
        let mut lexer = Lexer::new(src, pos);
        let tok = lexer.next_token()?;
        Ok(Parser {
            lexer,
            ops,
            tok,
            peeked: None,
            terms: Terms::new(),
            vars: Vec::new(),
            var_ids: HashMap::new(),
            open: Vec::new(),
            scratch: Vec::new(),
            last_end: pos,
            comma_before_tok: false,
            max_depth: MAX_DEPTH,
        })
    }

    #[inline(never)]
    fn advance(&mut self) -> PResult<Token> {
        let next = match self.peeked.take() {
            Some(t) => t,
            None => self.lexer.next_token()?,
        };
        self.last_end = self.tok.span.end as usize;
        self.comma_before_tok = self.tok.kind == TokKind::Punct(',');
        Ok(std::mem::replace(&mut self.tok, next))
    }

    #[inline(never)]
    fn peek(&mut self) -> PResult<&Token> {
        if self.peeked.is_none() {
            self.peeked = Some(self.lexer.next_token()?);
        }
        Ok(self.peeked.as_ref().expect("just filled"))
    }

    /// Reads one term and its end token. `end_optional`: end of input may stand for `.`.
    pub(super) fn clause(&mut self, end_optional: bool) -> PResult<Clause> {
        let start = self.tok.span.start;
        let root = self.parse(1200, Ctx::Top)?;
        match self.tok.kind {
            TokKind::End => {
                let end = self.tok.span.end;
                self.advance()?;
                Ok(self.finish(root, Span { start, end }))
            }
            TokKind::Eof if end_optional => {
                let end = self.last_end as u32;
                Ok(self.finish(root, Span { start, end }))
            }
            _ => Err(Box::new(self.after_term_error())),
        }
    }

    fn finish(&mut self, root: TermId, span: Span) -> Clause {
        Clause {
            terms: std::mem::take(&mut self.terms),
            root,
            vars: std::mem::take(&mut self.vars),
            span,
        }
    }

    /// The error for a token that cannot follow a complete term.
    #[inline(never)]
    fn after_term_error(&self) -> SyntaxError {
        let span = self.tok.span;
        let mut e = match &self.tok.kind {
            TokKind::Eof => {
                let at = Span::new(self.last_end, self.last_end);
                let mut e = SyntaxError::new(
                    at,
                    "missing `.` at the end of the clause (end of file reached)".into(),
                );
                e.incomplete = true;
                e.help = Some("end every clause with `.`".into());
                e
            }
            TokKind::Name { atom, .. }
                if self.ops.infix(*atom).is_some() || self.ops.postfix(*atom).is_some() =>
            {
                SyntaxError::new(
                    span,
                    format!("operator priority clash at `{}`", atom.as_str()),
                )
                .with_help("add parentheses to say how the operators group")
            }
            TokKind::Punct(',') | TokKind::Punct('|') => SyntaxError::new(
                span,
                "operator priority clash: a `,` or `|` cannot follow this term here".into(),
            )
            .with_help("add parentheses around the operator term"),
            TokKind::Punct(c @ (')' | ']' | '}')) => {
                let mut e = SyntaxError::new(span, format!("unexpected `{c}`"));
                if self.open.is_empty() {
                    e.help = Some("this closing bracket has no opening bracket".into());
                }
                e
            }
            TokKind::End => SyntaxError::new(span, "unexpected end of clause".into()),
            _ => SyntaxError::new(span, "operator expected".into())
                .with_help("is a `,` or an operator missing between two terms?"),
        };
        self.add_open_label(&mut e);
        e
    }

    fn add_open_label(&self, e: &mut SyntaxError) {
        if let Some(&(span, c)) = self.open.last() {
            let close = match c {
                '(' => ')',
                '[' => ']',
                _ => '}',
            };
            e.labels.push((
                span,
                format!("unclosed `{c}` opened here (expected `{close}`)"),
            ));
        }
    }

    #[inline(never)]
    fn expected_term_error(&self) -> SyntaxError {
        let span = self.tok.span;
        let mut e = match &self.tok.kind {
            TokKind::Eof => {
                let mut e = SyntaxError::new(
                    Span::new(self.last_end, self.last_end),
                    "unexpected end of file: expected a term".into(),
                );
                e.incomplete = true;
                e
            }
            TokKind::End => {
                SyntaxError::new(span, "unexpected end of clause: expected a term".into())
            }
            TokKind::Punct(c @ (']' | ')' | '}')) => {
                let mut e = SyntaxError::new(span, format!("unexpected `{c}`: expected a term"));
                if self.lexer_prev_was_comma() {
                    e.help = Some("remove the trailing `,`".into());
                }
                e
            }
            TokKind::Punct(c) => {
                SyntaxError::new(span, format!("unexpected `{c}`: expected a term"))
            }
            _ => SyntaxError::new(span, "expected a term".into()),
        };
        self.add_open_label(&mut e);
        e
    }

    fn too_deep(&self) -> SyntaxError {
        SyntaxError::new(
            self.tok.span,
            format!("{TOO_DEEP} (more than {} levels)", self.max_depth),
        )
    }

    fn lexer_prev_was_comma(&self) -> bool {
        self.comma_before_tok
    }

    fn push(&mut self, node: Node, span: Span) -> TermId {
        self.terms.push(node, span)
    }

    /// Reads one term of priority at most `max`. Iterative: nesting lives in
    /// an explicit stack of [`Level`]s, so any depth runs in constant native
    /// stack (a depth limit turns absurd nesting into an error).
    fn parse(&mut self, max: u16, ctx: Ctx) -> PResult<TermId> {
        let mut levels = vec![Level {
            max,
            ctx,
            cont: Cont::Root,
        }];
        let mut start = true;
        let (mut left, mut left_prio) = (TermId(0), 0u16);
        loop {
            let Level { max, ctx, .. } = *levels.last().expect("a level is open");
            if start {
                match self.primary(max, ctx)? {
                    Step::Done(t, p) => {
                        (left, left_prio) = (t, p);
                        start = false;
                    }
                    Step::Push(max, ctx, cont) => {
                        if levels.len() >= self.max_depth {
                            return Err(Box::new(self.too_deep()));
                        }
                        levels.push(Level { max, ctx, cont });
                        continue;
                    }
                }
            }
            // Infix and postfix operators after a complete left operand.
            if let Some(step) = self.operator(left, left_prio, max, ctx)? {
                match step {
                    Step::Done(t, p) => (left, left_prio) = (t, p),
                    Step::Push(max, ctx, cont) => {
                        if levels.len() >= self.max_depth {
                            return Err(Box::new(self.too_deep()));
                        }
                        levels.push(Level { max, ctx, cont });
                        start = true;
                    }
                }
                continue;
            }
            // This level is complete: hand `left` to the level that asked for it.
            let done = levels.pop().expect("a level is open");
            match done.cont {
                Cont::Root => return Ok(left),
                Cont::InfixRight {
                    left: l,
                    name,
                    prio,
                } => {
                    let span = self.terms.span(l).to(self.terms.span(left));
                    left = self.terms.push_compound(name, &[l, left], span);
                    left_prio = prio;
                }
                Cont::PrefixArg { atom, span, prio } => {
                    let span = span.to(self.terms.span(left));
                    left = self.terms.push_compound(atom, &[left], span);
                    left_prio = prio;
                }
                Cont::Paren => {
                    self.close(')')?;
                    left_prio = 0;
                }
                Cont::Curly { open } => {
                    let end = self.tok.span;
                    self.close('}')?;
                    left = self
                        .terms
                        .push_compound(atoms::CURLY, &[left], open.to(end));
                    left_prio = 0;
                }
                Cont::Elem { open, items } => {
                    self.scratch.push(left);
                    let next = match self.tok.kind {
                        TokKind::Punct(',') => Some(Cont::Elem { open, items }),
                        TokKind::Punct('|') => Some(Cont::Tail { open, items }),
                        _ => None,
                    };
                    if let Some(cont) = next {
                        self.advance()?;
                        levels.push(Level {
                            max: 1200,
                            ctx: Ctx::Elem,
                            cont,
                        });
                        start = true;
                        continue;
                    }
                    let end = self.tok.span;
                    self.close(']')?;
                    let nil = self.push(Node::Atom(atoms::NIL), end);
                    left = self.build_list(items, nil, open.to(end));
                    left_prio = 0;
                }
                Cont::Tail { open, items } => {
                    if let TokKind::Punct(c @ (',' | '|')) = self.tok.kind {
                        let mut e = SyntaxError::new(
                            self.tok.span,
                            format!("expected `]` after the list tail, found `{c}`"),
                        )
                        .with_help("a list has one tail after `|`: write `[a, b|T]`");
                        self.add_open_label(&mut e);
                        return Err(Box::new(e));
                    }
                    let end = self.tok.span;
                    self.close(']')?;
                    left = self.build_list(items, left, open.to(end));
                    left_prio = 0;
                }
                Cont::Arg {
                    name,
                    start: fstart,
                    args,
                } => {
                    self.scratch.push(left);
                    if self.tok.kind == TokKind::Punct(',') {
                        self.advance()?;
                        levels.push(Level {
                            max: 1200,
                            ctx: Ctx::Arg,
                            cont: Cont::Arg {
                                name,
                                start: fstart,
                                args,
                            },
                        });
                        start = true;
                        continue;
                    }
                    let end = self.tok.span;
                    self.close(')')?;
                    left = self
                        .terms
                        .push_compound(name, &self.scratch[args..], fstart.to(end));
                    self.scratch.truncate(args);
                    left_prio = 0;
                }
            }
        }
    }

    /// The list of `self.scratch[items..]` ending in `tail`.
    fn build_list(&mut self, items: usize, tail: TermId, full: Span) -> TermId {
        let mut list = tail;
        for i in (items..self.scratch.len()).rev() {
            let item = self.scratch[i];
            let s = Span {
                start: self.terms.span(item).start,
                end: full.end,
            };
            list = self.terms.push_compound(atoms::DOT, &[item, list], s);
        }
        self.scratch.truncate(items);
        list
    }

    /// An infix or postfix operator after `left`, if one applies here.
    fn operator(
        &mut self,
        left: TermId,
        left_prio: u16,
        max: u16,
        ctx: Ctx,
    ) -> PResult<Option<Step>> {
        let name = match &self.tok.kind {
            TokKind::Name { atom, .. } => *atom,
            TokKind::Punct(',') if ctx == Ctx::Top => atoms::COMMA,
            TokKind::Punct('|') if ctx != Ctx::Elem => atoms::BAR,
            _ => return Ok(None),
        };
        if let Some(def) = self.ops.infix(name) {
            let (lmax, rmax) = def.arg_max();
            if def.priority <= max && left_prio <= lmax.unwrap_or(0) {
                self.advance()?;
                return Ok(Some(Step::Push(
                    rmax.unwrap_or(0),
                    ctx,
                    Cont::InfixRight {
                        left,
                        name,
                        prio: def.priority,
                    },
                )));
            }
        }
        if let Some(def) = self.ops.postfix(name) {
            let (lmax, _) = def.arg_max();
            if def.priority <= max && left_prio <= lmax.unwrap_or(0) {
                let op_tok = self.advance()?;
                let span = self.terms.span(left).to(op_tok.span);
                let t = self.terms.push_compound(name, &[left], span);
                return Ok(Some(Step::Done(t, def.priority)));
            }
        }
        Ok(None)
    }

    /// Whether the current token can start a term (used to decide whether a
    /// prefix operator has an operand).
    fn starts_term(&self, tok: &TokKind) -> bool {
        match tok {
            TokKind::Name { atom, .. } => {
                // An infix operator that is not also a prefix operator ends the term.
                !(self.ops.infix(*atom).is_some() && self.ops.prefix(*atom).is_none())
            }
            TokKind::Var
            | TokKind::Int(_)
            | TokKind::BigInt(_)
            | TokKind::Float(_)
            | TokKind::Str(_)
            | TokKind::BackQuoted(_) => true,
            TokKind::Punct(c) => matches!(c, '(' | '[' | '{'),
            TokKind::OpenCt => true,
            TokKind::End | TokKind::Eof => false,
        }
    }

    /// The start of a term: a complete primary term, or the level to read
    /// for its contents.
    fn primary(&mut self, max: u16, ctx: Ctx) -> PResult<Step> {
        let comma_before = self.comma_before_tok;
        let tok = self.advance()?;
        let span = tok.span;
        match tok.kind {
            TokKind::Int(i) => Ok(Step::Done(self.push(Node::Int(i), span), 0)),
            TokKind::BigInt(s) => Ok(Step::Done(self.push(Node::BigInt(s), span), 0)),
            TokKind::Float(f) => Ok(Step::Done(self.push(Node::Float(f), span), 0)),
            TokKind::Str(s) => Ok(Step::Done(self.push(Node::Str(s), span), 0)),
            TokKind::BackQuoted(s) => Ok(Step::Done(self.push(Node::BackQuoted(s), span), 0)),
            TokKind::Var => {
                let id = self.var(span);
                Ok(Step::Done(self.push(Node::Var(id), span), 0))
            }
            TokKind::Punct('(') | TokKind::OpenCt => {
                self.open.push((span, '('));
                Ok(Step::Push(1200, Ctx::Top, Cont::Paren))
            }
            TokKind::Punct('[') => {
                if self.tok.kind == TokKind::Punct(']') {
                    let end = self.advance()?.span;
                    let id = self.push(Node::Atom(atoms::NIL), span.to(end));
                    return self.maybe_functional(atoms::NIL, id, span.to(end));
                }
                self.open.push((span, '['));
                let items = self.scratch.len();
                Ok(Step::Push(
                    1200,
                    Ctx::Elem,
                    Cont::Elem { open: span, items },
                ))
            }
            TokKind::Punct('{') => {
                if self.tok.kind == TokKind::Punct('}') {
                    let end = self.advance()?.span;
                    let id = self.push(Node::Atom(atoms::CURLY), span.to(end));
                    return self.maybe_functional(atoms::CURLY, id, span.to(end));
                }
                self.open.push((span, '{'));
                Ok(Step::Push(1200, Ctx::Top, Cont::Curly { open: span }))
            }
            TokKind::Name { atom, quoted } => self.name_primary(atom, quoted, span, max, ctx),
            _ => {
                // Put the token back for the error message.
                let cur = std::mem::replace(&mut self.tok, tok);
                self.peeked = Some(cur);
                self.comma_before_tok = comma_before;
                Err(Box::new(self.expected_term_error()))
            }
        }
    }

    /// `[](..)`/`{}(..)`: SWI-7 functional notation on `[]` and `{}`.
    fn maybe_functional(&mut self, name: Atom, id: TermId, span: Span) -> PResult<Step> {
        if self.tok.kind == TokKind::OpenCt {
            return self.compound(name, span);
        }
        Ok(Step::Done(id, 0))
    }

    fn name_primary(
        &mut self,
        atom: Atom,
        quoted: bool,
        span: Span,
        max: u16,
        ctx: Ctx,
    ) -> PResult<Step> {
        if self.tok.kind == TokKind::OpenCt {
            return self.compound(atom, span);
        }
        if atom == atoms::MINUS && !quoted && !self.tok.layout_before {
            let negated = match &self.tok.kind {
                TokKind::Int(i) => Some(match i.checked_neg() {
                    Some(n) => Node::Int(n),
                    None => Node::BigInt(format!("-{i}").into()),
                }),
                TokKind::BigInt(s) => Some(if &**s == "9223372036854775808" {
                    Node::Int(i64::MIN)
                } else {
                    Node::BigInt(format!("-{s}").into())
                }),
                TokKind::Float(f) => Some(Node::Float(-f)),
                _ => None,
            };
            if let Some(node) = negated {
                let num = self.advance()?;
                return Ok(Step::Done(self.push(node, span.to(num.span)), 0));
            }
        }
        if let Some(def) = self.ops.prefix(atom) {
            let next = &self.tok.kind;
            let mut has_operand = self.starts_term(next);
            // `- (a)`: an operand in parentheses; `-(a)` was functional notation above.
            if let TokKind::Name { atom: n, .. } = *next {
                // `- =`: an infix-only operator after a prefix operator makes it an atom,
                // unless that name is followed by `(` (then it is a term: `- =(a,b)`).
                if self.ops.infix(n).is_some() && self.ops.prefix(n).is_none() {
                    has_operand = self.peek()?.kind == TokKind::OpenCt;
                }
            }
            if has_operand {
                if def.priority > max {
                    // SWI-Prolog (and ISO): `- \+ a`, `a = \+ b` are clashes.
                    let mut e = SyntaxError::new(
                        span,
                        format!(
                            "operator priority clash: prefix operator `{}` ({}) cannot appear where at most priority {max} is allowed",
                            atom.as_str(),
                            def.priority
                        ),
                    )
                    .with_help("add parentheses around the operator term");
                    self.add_open_label(&mut e);
                    return Err(Box::new(e));
                }
                let rmax = def.arg_max().1.unwrap_or(0);
                return Ok(Step::Push(
                    rmax,
                    ctx,
                    Cont::PrefixArg {
                        atom,
                        span,
                        prio: def.priority,
                    },
                ));
            }
            // A prefix operator standing as an atom keeps its priority as a
            // left operand (SWI: `- * a` reads, `\+ * a` does not).
            let id = self.push(Node::Atom(atom), span);
            return Ok(Step::Done(id, def.priority));
        }
        let id = self.push(Node::Atom(atom), span);
        Ok(Step::Done(id, 0))
    }

    /// `name(`: functional notation; the arguments are read as levels.
    fn compound(&mut self, name: Atom, start: Span) -> PResult<Step> {
        let open = self.advance()?; // OpenCt
        self.open.push((open.span, '('));
        if self.tok.kind == TokKind::Punct(')') {
            // `name()`: SWI-Prolog 7 zero-argument compound.
            let end = self.advance()?.span;
            self.open.pop();
            let id = self.terms.push_compound(name, &[], start.to(end));
            return Ok(Step::Done(id, 0));
        }
        let args = self.scratch.len();
        Ok(Step::Push(1200, Ctx::Arg, Cont::Arg { name, start, args }))
    }

    #[inline(never)]
    fn close(&mut self, c: char) -> PResult<()> {
        if self.tok.kind == TokKind::Punct(c) {
            self.advance()?;
            self.open.pop();
            Ok(())
        } else {
            let mut e = self.after_term_error();
            if !matches!(self.tok.kind, TokKind::Eof)
                && !e.message.starts_with("operator priority clash")
            {
                e.message = match &self.tok.kind {
                    TokKind::Punct(found @ (')' | ']' | '}')) => {
                        format!("mismatched brackets: expected `{c}`, found `{found}`")
                    }
                    _ => format!("expected `,` or `{c}`"),
                };
            } else if matches!(self.tok.kind, TokKind::Eof) {
                e.message = format!("unexpected end of file: expected `{c}`");
            }
            if e.help.is_none() && !matches!(self.tok.kind, TokKind::Punct(_)) {
                e.help = Some("is a `,` missing?".into());
            }
            Err(Box::new(e))
        }
    }

    fn var(&mut self, span: Span) -> VarId {
        let name: &'s str = &self.lexer.source()[span.range()];
        if name != "_" {
            if let Some(&id) = self.var_ids.get(name) {
                self.vars[id.0 as usize].occurrences += 1;
                return id;
            }
        }
        let id = VarId(self.vars.len() as u32);
        self.vars.push(VarInfo {
            name: name.into(),
            first: span,
            occurrences: 1,
        });
        if name != "_" {
            self.var_ids.insert(name, id);
        }
        id
    }
}
