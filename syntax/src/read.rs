//! The reader: tokens from [`crate::lexer`], terms by precedence climbing over
//! the operator table. The parser is iterative (an explicit stack of pending
//! levels), so deep terms never touch the native stack; a depth limit turns
//! absurd nesting into an error instead of exhausting memory.

use crate::atom::{atoms, Atom};
use crate::lexer::{Lexer, TokKind, Token};
use crate::ops::OpTable;
use crate::term::{Clause, Node, Span, TermId, Terms, VarId, VarInfo};
use std::collections::HashMap;

/// Deepest nesting of terms the reader accepts.
pub const MAX_DEPTH: usize = 1_000_000;

/// The start of the message of a depth-limit error ([`SyntaxError::is_too_deep`]).
const TOO_DEEP: &str = "term nested too deeply";

/// A syntax error with its position and, where useful, related positions.
#[derive(Clone, Debug, PartialEq)]
pub struct SyntaxError {
    pub span: Span,
    pub message: String,
    /// Secondary labels, e.g. the unclosed bracket.
    pub labels: Vec<(Span, String)>,
    pub help: Option<String>,
    /// The input ended inside a term: more text could complete it.
    pub incomplete: bool,
}

impl SyntaxError {
    pub fn new(span: Span, message: String) -> SyntaxError {
        SyntaxError {
            span,
            message,
            labels: Vec::new(),
            help: None,
            incomplete: false,
        }
    }
    fn with_help(mut self, help: &str) -> SyntaxError {
        self.help = Some(help.to_owned());
        self
    }
}

impl SyntaxError {
    /// Whether this is the error of a depth limit ([`MAX_DEPTH`], or the one
    /// given to [`read_term_limited`] or [`ClauseReader::with_max_depth`]).
    pub fn is_too_deep(&self) -> bool {
        self.message.starts_with(TOO_DEEP)
    }

    /// 1-based line and column (in characters) of the start of the error in `src`.
    pub fn line_col(&self, src: &str) -> (usize, usize) {
        line_col(src, self.span.start as usize)
    }

    /// [`SyntaxError::line_col`] for raw bytes (invalid UTF-8 counts one column per byte).
    pub fn line_col_bytes(&self, src: &[u8]) -> (usize, usize) {
        let at = (self.span.start as usize).min(src.len());
        let before = &src[..at];
        let line_start = before
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1);
        let line = 1 + before.iter().filter(|&&b| b == b'\n').count();
        let col = 1 + String::from_utf8_lossy(&before[line_start..])
            .chars()
            .count();
        (line, col)
    }
}

/// 1-based line and column (in characters) of byte `offset` of `src`.
/// Offsets past the end or inside a character are clamped.
pub fn line_col(src: &str, offset: usize) -> (usize, usize) {
    let mut at = offset.min(src.len());
    while !src.is_char_boundary(at) {
        at -= 1;
    }
    let before = &src[..at];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line = 1 + before.bytes().filter(|&b| b == b'\n').count();
    (line, 1 + before[line_start..].chars().count())
}

/// Checks that `bytes` are UTF-8 (the reader works on `&str`), through
/// [`crate::decode::decode`]: a leading BOM is skipped (spans of what is read
/// are then relative to the text after it). The error points at the first
/// invalid byte and gives its offset.
pub fn source_from_bytes(bytes: &[u8]) -> Result<&str, SyntaxError> {
    crate::decode::decode(bytes).map_err(|e| {
        let at = e.offset.min(bytes.len());
        let len = if e.utf16 { 2 } else { 1 };
        let mut err = SyntaxError::new(
            Span::new(at, (at + len).min(bytes.len())),
            format!("byte offset {at}: {}", e.message),
        );
        err.help = Some("convert the file to UTF-8 (e.g. with iconv)".into());
        err
    })
}

/// [`read_clauses`] for raw bytes: text that is not UTF-8 gives one error at
/// the first invalid byte and no clauses.
pub fn read_clauses_bytes(bytes: &[u8]) -> (Vec<Clause>, Vec<SyntaxError>) {
    read_clauses_bytes_with(bytes, OpTable::sitlog_shared())
}

/// [`read_clauses_bytes`] with another operator table.
pub fn read_clauses_bytes_with(bytes: &[u8], ops: &OpTable) -> (Vec<Clause>, Vec<SyntaxError>) {
    match source_from_bytes(bytes) {
        Ok(src) => read_clauses_with(src, ops),
        Err(e) => (Vec::new(), vec![e]),
    }
}

impl std::fmt::Display for SyntaxError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for SyntaxError {}

/// Number of tokens in `src` (layout and comments excluded, end tokens
/// included): for benchmarks of the lexer.
#[doc(hidden)]
pub fn count_tokens(src: &str) -> Result<usize, SyntaxError> {
    let mut lexer = Lexer::new(src, 0);
    let mut n = 0;
    loop {
        let tok = lexer.next_token()?;
        if tok.kind == TokKind::Eof {
            return Ok(n);
        }
        n += 1;
    }
}

/// Reads all clauses of `src` with SitLog's operator table. After a syntax
/// error, reading resumes after the next end token, like Prolog's `read/1`.
pub fn read_clauses(src: &str) -> (Vec<Clause>, Vec<SyntaxError>) {
    read_clauses_with(src, OpTable::sitlog_shared())
}

/// [`read_clauses`] with another operator table.
pub fn read_clauses_with(src: &str, ops: &OpTable) -> (Vec<Clause>, Vec<SyntaxError>) {
    let mut clauses = Vec::new();
    let mut errors = Vec::new();
    let mut reader = ClauseReader::new(src, ops);
    while let Some(result) = reader.next_clause() {
        match result {
            Ok(c) => clauses.push(c),
            Err(e) => errors.push(e),
        }
    }
    (clauses, errors)
}

/// Reads exactly one term from `src`; the final `.` is optional.
pub fn read_term(src: &str) -> Result<Clause, SyntaxError> {
    read_term_with(src, OpTable::sitlog_shared())
}

/// [`read_term`] with another operator table.
pub fn read_term_with(src: &str, ops: &OpTable) -> Result<Clause, SyntaxError> {
    read_term_limited(src, ops, MAX_DEPTH)
}

/// [`read_term_with`] that refuses terms nested more than `max_depth`
/// levels (for input from outside, which gets tighter limits than source
/// files): the error is [`SyntaxError::is_too_deep`].
pub fn read_term_limited(
    src: &str,
    ops: &OpTable,
    max_depth: usize,
) -> Result<Clause, SyntaxError> {
    let mut parser = Parser::new(src, 0, ops).map_err(|e| *e)?;
    parser.max_depth = max_depth.clamp(1, MAX_DEPTH);
    if parser.tok.kind == TokKind::Eof {
        return Err(SyntaxError {
            incomplete: true,
            ..SyntaxError::new(
                parser.tok.span,
                "expected a term, found end of input".into(),
            )
        });
    }
    let clause = parser.clause(true).map_err(|e| *e)?;
    if parser.tok.kind != TokKind::Eof {
        return Err(SyntaxError::new(
            parser.tok.span,
            "unexpected text after the term".into(),
        ));
    }
    Ok(clause)
}

/// Reads clauses one at a time (for scripts and interactive input).
pub struct ClauseReader<'s, 'o> {
    src: &'s str,
    ops: &'o OpTable,
    pos: usize,
    done: bool,
    max_depth: usize,
}

impl<'s, 'o> ClauseReader<'s, 'o> {
    pub fn new(src: &'s str, ops: &'o OpTable) -> ClauseReader<'s, 'o> {
        ClauseReader {
            src,
            ops,
            pos: 0,
            done: false,
            max_depth: MAX_DEPTH,
        }
    }

    /// Refuses clauses nested more than `max_depth` levels (at most
    /// [`MAX_DEPTH`]): the error is [`SyntaxError::is_too_deep`].
    pub fn with_max_depth(mut self, max_depth: usize) -> Self {
        self.max_depth = max_depth.clamp(1, MAX_DEPTH);
        self
    }

    /// Byte offset where the next clause starts.
    pub fn position(&self) -> usize {
        self.pos
    }

    /// The next clause, `None` at end of input.
    pub fn next_clause(&mut self) -> Option<Result<Clause, SyntaxError>> {
        if self.done {
            return None;
        }
        let mut parser = match Parser::new(self.src, self.pos, self.ops) {
            Ok(p) => p,
            Err(e) => {
                self.recover(e.span.end as usize);
                return Some(Err(*e));
            }
        };
        parser.max_depth = self.max_depth;
        if parser.tok.kind == TokKind::Eof {
            self.done = true;
            return None;
        }
        match parser.clause(false) {
            Ok(clause) => {
                self.pos = clause.span.end as usize;
                Some(Ok(clause))
            }
            Err(mut e) => {
                let from = parser.tok.span.start.max(e.span.start) as usize;
                let unclosed = e.labels.iter().find(|(_, l)| l.starts_with("unclosed"));
                if let Some(&(open, _)) = unclosed {
                    let (pos, at) = (self.pos, e.span.start as usize);
                    if let Some(hint) = indentation_hint(self.src, pos, open.start as usize, at) {
                        e.labels.push(hint);
                    }
                }
                self.recover(from);
                Some(Err(*e))
            }
        }
    }

    /// Skips to just after the next end token at or after `from`.
    fn recover(&mut self, from: usize) {
        let mut lexer = Lexer::new(self.src, from.min(self.src.len()));
        loop {
            match lexer.next_token() {
                Ok(Token {
                    kind: TokKind::End,
                    span,
                    ..
                }) => {
                    self.pos = span.end as usize;
                    return;
                }
                Ok(Token {
                    kind: TokKind::Eof, ..
                }) => {
                    self.pos = self.src.len();
                    self.done = true;
                    return;
                }
                Ok(_) => {}
                Err(e) if e.incomplete => {
                    self.pos = self.src.len();
                    self.done = true;
                    return;
                }
                Err(_) => lexer.skip_char(),
            }
        }
    }
}

/// Width of the indentation of the line holding byte `at` (a tab counts 8).
fn indent_of_line(src: &str, at: usize) -> usize {
    let start = src[..at].rfind('\n').map_or(0, |i| i + 1);
    src[start..]
        .chars()
        .take_while(|c| *c == ' ' || *c == '\t')
        .map(|c| if c == '\t' { 8 } else { 1 })
        .sum()
}

/// Whether only blanks precede byte `at` on its line.
fn first_on_line(src: &str, at: usize) -> bool {
    let start = src[..at].rfind('\n').map_or(0, |i| i + 1);
    src[start..at]
        .chars()
        .all(|c| c == ' ' || c == '\t' || c == '\r')
}

/// For unbalanced brackets: the first closing bracket between the unclosed
/// bracket at `unclosed` and the error at `to` that starts its line indented
/// less than the line of the bracket it closes: a likely place for a
/// forgotten closing bracket (the clause starts at `from`).
fn indentation_hint(src: &str, from: usize, unclosed: usize, to: usize) -> Option<(Span, String)> {
    let mut lexer = Lexer::new(src, from);
    let mut stack: Vec<(Span, usize)> = Vec::new();
    loop {
        let tok = lexer.next_token().ok()?;
        if tok.span.start as usize >= to || matches!(tok.kind, TokKind::Eof | TokKind::End) {
            return None;
        }
        match tok.kind {
            TokKind::Punct('(' | '[' | '{') | TokKind::OpenCt => {
                stack.push((tok.span, indent_of_line(src, tok.span.start as usize)));
            }
            TokKind::Punct(c @ (')' | ']' | '}')) => {
                let (open, indent) = stack.pop()?;
                let at = tok.span.start as usize;
                if at > unclosed && first_on_line(src, at) && indent_of_line(src, at) < indent {
                    let (line, _) = line_col(src, open.start as usize);
                    return Some((
                        tok.span,
                        format!(
                            "this `{c}` closes the bracket of line {line} but is indented less than that line: \
                             is a closing bracket missing before it?"
                        ),
                    ));
                }
            }
            _ => {}
        }
    }
}

struct Parser<'s, 'o> {
    lexer: Lexer<'s>,
    ops: &'o OpTable,
    tok: Token,
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
    max_depth: usize,
}

/// Errors are boxed inside the parser so that its recursive frames stay small.
type PResult<T> = Result<T, Box<SyntaxError>>;

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
    fn new(src: &'s str, pos: usize, ops: &'o OpTable) -> PResult<Parser<'s, 'o>> {
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
    fn clause(&mut self, end_optional: bool) -> PResult<Clause> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::write::writeq;

    fn rt(src: &str) -> String {
        let c = read_term(src).unwrap_or_else(|e| panic!("{src}: {e:?}"));
        writeq(&c, c.root)
    }

    fn err(src: &str) -> SyntaxError {
        read_term(src).expect_err(src)
    }

    #[test]
    fn basic_terms() {
        assert_eq!(rt("foo"), "foo");
        assert_eq!(rt("foo(X, bar, 'Baz q')"), "foo(X,bar,'Baz q')");
        assert_eq!(rt("[1,2|T]"), "[1,2|T]");
        assert_eq!(rt("[ ]"), "[]");
        assert_eq!(rt("{a,b}"), "{a,b}");
        assert_eq!(rt("-30.0"), "-30.0");
        assert_eq!(rt("- 1"), "- 1");
        assert_eq!(rt("-(1)"), "- 1");
        assert_eq!(rt("-(-(1))"), "- - 1");
        assert_eq!(rt("a- (-1)"), "a- -1");
        assert_eq!(rt("-(1)^2"), "(- 1)^2");
        assert_eq!(rt("-(2^1)"), "- 2^1");
        assert_eq!(rt("- {a}"), "- {a}");
        assert_eq!(rt("1.0e10"), "10000000000.0");
        assert_eq!(rt("1.0e15"), "1.0e+15");
        assert_eq!(rt("1.0Inf"), "1.0Inf");
        assert_eq!(rt("1 000"), "1000");
        assert_eq!(rt("1_000_ 000"), "1000000");
        assert_eq!(rt("'\\e\\0\\'"), "'\\u001B\\u0000'");
        assert_eq!(rt("'\\u00e9\\U0001F600'"), "'é😀'");
        // SWI-Prolog's `\c` skips the layout after it (the original's init.pl).
        assert_eq!(rt("'ab\\c\n    cd'"), "abcd");
        assert_eq!(rt("[](a)"), "[](a)");
        assert_eq!(rt("{}(a)"), "{a}");
        // Found by proptest: an atom starting with `/*` must be quoted.
        assert_eq!(rt("'/*'(X)"), "'/*'(X)");
        assert_eq!(rt("[+/*, a/**/+b]"), "[+/*,a+b]");
        assert_eq!(rt("a - -1"), "a- -1");
        assert_eq!(rt("f(x)-50"), "f(x)-50");
        assert_eq!(rt("0'a"), "97");
        assert_eq!(rt("0x1F"), "31");
        assert_eq!(rt("'it''s'"), "'it\\'s'");
        assert_eq!(rt("'a\\nb'"), "'a\\nb'");
        assert_eq!(rt("\"ab\""), "\"ab\"");
        assert_eq!(rt("foo()"), "foo()");
    }

    #[test]
    fn sitlog_operators() {
        assert_eq!(rt("[e : a => n]"), "[e:a=>n]");
        let c = read_term("e : a => n").unwrap();
        assert_eq!(c.terms.functor(c.root), Some((Atom::intern("=>"), 2)));
        assert_eq!(rt("id ==> is"), "id==>(is)");
        assert_eq!(rt("k ==> e : a => n"), "k==>e:a=>n");
        assert_eq!(rt("(a :- b, c ; d -> e)"), "a:-b,c;d->e");
        assert_eq!(rt("X is 1 + 2 * 3"), "X is 1+2*3");
        assert_eq!(rt("(1-2)-3"), "1-2-3");
        assert_eq!(rt("1-(2-3)"), "1-(2-3)");
        assert_eq!(rt("(c -> a | otherwise -> b)"), "c->a|otherwise->b");
        assert_eq!(rt("\\+ a"), "\\+a");
        assert_eq!(rt("- - a"), "- -a");
        assert_eq!(rt("f(-)"), "f(-)");
        assert_eq!(rt("- (1)"), "- 1");
        assert_eq!(rt("[(c -> a | b)]"), "[(c->a|b)]");
        assert_eq!(rt("f(a :- b, c)"), "f((a:-b),c)");
        assert_eq!(rt("[a -> b|T]"), "[(a->b)|T]");
        assert_eq!(rt("f(a | b)"), "f((a|b))");
        assert_eq!(rt("f(:-, -)"), "f(:-,-)");
        assert_eq!(rt("- (-)"), "- (-)");
        assert_eq!(rt("a = \\+"), "a=(\\+)");
        assert_eq!(rt("- * a"), "(-)*a");
        assert_eq!(rt("((:-) :- (:-))"), "(:-):-(:-)");
        assert_eq!(rt("[-]"), "[-]");
        assert_eq!(rt("f((a,b))"), "f((a,b))");
        assert_eq!(rt("f((a:-b))"), "f((a:-b))");
    }

    #[test]
    fn priority_clashes() {
        for src in [
            "a : b : c",
            "a => b => c",
            "a ==> b ==> c",
            "x : y => z => w",
            "a = b = c",
            "- \\+ a",
            "a = \\+ b",
            "\\+ * a",
        ] {
            let e = err(src);
            assert!(e.message.contains("priority clash"), "{src}: {e:?}");
        }
    }

    #[test]
    fn forgotten_bracket_is_located_by_indentation() {
        let src = "d(x,\n[\n  [\n    a ==> [\n      b\n  ],\n  [\n    c\n  ]\n]\n).\n";
        let (_, errors) = read_clauses(src);
        assert_eq!(errors.len(), 1, "{errors:?}");
        let e = &errors[0];
        assert!(e.message.contains("mismatched brackets"), "{e:?}");
        let hint = e.labels.iter().find(|(_, l)| l.contains("indented less"));
        let (span, _) = hint.expect("an indentation hint");
        assert_eq!(line_col(src, span.start as usize), (6, 3));
    }

    #[test]
    fn list_tail_errors() {
        for src in ["[a|b|c]", "[a|b,c]"] {
            let e = err(src);
            assert!(e.message.contains("after the list tail"), "{src}: {e:?}");
            assert_eq!(e.span, Span::new(4, 5));
            assert_eq!(e.labels.len(), 1);
        }
    }

    #[test]
    fn errors_are_positioned() {
        let e = err("[a, b,]");
        assert_eq!(e.span, Span::new(6, 7));
        assert_eq!(e.help.as_deref(), Some("remove the trailing `,`"));
        let e = err("'abc");
        assert!(e.message.contains("unterminated quoted atom"));
        assert!(e.incomplete);
        let e = err("f(a");
        assert!(e.incomplete);
        assert_eq!(e.labels.len(), 1);
        let e = err("/* abc");
        assert!(e.message.contains("unterminated block comment"), "{e:?}");
        let e = err("[id ==> a type ==> b]");
        assert!(e.message.contains("expected `,` or `]`"), "{e:?}");
        let (clauses, errors) = read_clauses("a. b(. c.\nd");
        assert_eq!(clauses.len(), 2);
        assert_eq!(errors.len(), 2);
        assert!(errors[1].message.contains("missing `.`"));
    }

    #[test]
    fn clauses_and_comments() {
        let src = "% comment\nfoo(X, Y) :- bar(X), /* c */ baz(Y).\n'x'.%end\nlast.";
        let (clauses, errors) = read_clauses(src);
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(clauses.len(), 3);
        assert_eq!(clauses[0].vars.len(), 2);
        assert_eq!(clauses[0].vars[0].occurrences, 2);
    }

    #[test]
    fn anonymous_variables_are_distinct() {
        let c = read_term("f(_, _, X, X)").unwrap();
        assert_eq!(c.vars.len(), 3);
    }

    #[test]
    fn deep_nesting_does_not_overflow() {
        let n = 100_000;
        let src = format!("{}a{}", "f(".repeat(n), ")".repeat(n));
        let c = read_term(&src).unwrap();
        let printed = writeq(&c, c.root);
        assert_eq!(printed.len(), src.len());
        let src = format!("{}a{}", "[".repeat(n), "]".repeat(n));
        assert!(read_term(&src).is_ok());
        let src = format!("{}a{}", "(".repeat(n), ")".repeat(n));
        assert!(read_term(&src).is_ok());
        let src = format!("{}a", "- ".repeat(n));
        assert!(read_term(&src).is_ok());
        let src = vec!["a"; n].join(",");
        assert!(read_term(&src).is_ok());
    }
}
