//! The reader: tokens from [`crate::lexer`], terms by precedence climbing over
//! the operator table. Recursion on nesting goes through `stacker`, so deep
//! terms grow the stack on the heap instead of overflowing it; a depth limit
//! turns absurd nesting into an error instead of exhausting memory.

use crate::atom::{atoms, Atom};
use crate::lexer::{Lexer, TokKind, Token};
use crate::ops::OpTable;
use crate::term::{Clause, Node, Span, TermId, Terms, VarId, VarInfo};
use std::collections::HashMap;

/// Deepest nesting of terms the reader accepts.
pub const MAX_DEPTH: usize = 1_000_000;

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
        let col = 1 + String::from_utf8_lossy(&before[line_start..]).chars().count();
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

/// Checks that `bytes` are UTF-8 (the reader works on `&str`). The error
/// points at the first invalid byte and gives its offset.
pub fn source_from_bytes(bytes: &[u8]) -> Result<&str, SyntaxError> {
    std::str::from_utf8(bytes).map_err(|e| {
        let at = e.valid_up_to();
        let len = e.error_len().unwrap_or(bytes.len() - at).max(1);
        let mut err = SyntaxError::new(
            Span::new(at, (at + len).min(bytes.len())),
            format!(
                "invalid UTF-8 at byte offset {at} (byte 0x{:02X}): source text must be UTF-8",
                bytes[at]
            ),
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
    let mut parser = Parser::new(src, 0, ops)?;
    if parser.tok.kind == TokKind::Eof {
        return Err(SyntaxError {
            incomplete: true,
            ..SyntaxError::new(
                parser.tok.span,
                "expected a term, found end of input".into(),
            )
        });
    }
    let clause = parser.clause(true)?;
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
}

impl<'s, 'o> ClauseReader<'s, 'o> {
    pub fn new(src: &'s str, ops: &'o OpTable) -> ClauseReader<'s, 'o> {
        ClauseReader {
            src,
            ops,
            pos: 0,
            done: false,
        }
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
                return Some(Err(e));
            }
        };
        if parser.tok.kind == TokKind::Eof {
            self.done = true;
            return None;
        }
        match parser.clause(false) {
            Ok(clause) => {
                self.pos = clause.span.end as usize;
                Some(Ok(clause))
            }
            Err(e) => {
                let from = parser.tok.span.start.max(e.span.start) as usize;
                self.recover(from);
                Some(Err(e))
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

struct Parser<'s, 'o> {
    lexer: Lexer<'s>,
    ops: &'o OpTable,
    tok: Token,
    /// One token of lookahead beyond `tok`, filled on demand.
    peeked: Option<Token>,
    terms: Terms,
    vars: Vec<VarInfo>,
    var_ids: HashMap<Box<str>, VarId>,
    open: Vec<(Span, char)>,
    depth: usize,
    last_end: usize,
}

type PResult<T> = Result<T, SyntaxError>;

impl<'s, 'o> Parser<'s, 'o> {
    fn new(src: &'s str, pos: usize, ops: &'o OpTable) -> PResult<Parser<'s, 'o>> {
        if src.len() >= u32::MAX as usize {
            return Err(SyntaxError::new(
                Span::new(0, 0),
                "source text is larger than 4 GiB".into(),
            ));
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
            depth: 0,
            last_end: pos,
        })
    }

    fn advance(&mut self) -> PResult<Token> {
        let next = match self.peeked.take() {
            Some(t) => t,
            None => self.lexer.next_token()?,
        };
        self.last_end = self.tok.span.end as usize;
        Ok(std::mem::replace(&mut self.tok, next))
    }

    fn peek(&mut self) -> PResult<&Token> {
        if self.peeked.is_none() {
            self.peeked = Some(self.lexer.next_token()?);
        }
        Ok(self.peeked.as_ref().expect("just filled"))
    }

    /// Reads one term and its end token. `end_optional`: end of input may stand for `.`.
    fn clause(&mut self, end_optional: bool) -> PResult<Clause> {
        let start = self.tok.span.start;
        let root = self.parse(1200)?;
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
            _ => Err(self.after_term_error()),
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

    fn lexer_prev_was_comma(&self) -> bool {
        let src = self.lexer_src();
        src[..self.tok.span.start as usize]
            .trim_end()
            .ends_with(',')
    }

    fn lexer_src(&self) -> &'s str {
        self.lexer.source()
    }

    fn push(&mut self, node: Node, span: Span) -> TermId {
        self.terms.push(node, span)
    }

    fn parse(&mut self, max: u16) -> PResult<TermId> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(SyntaxError::new(
                self.tok.span,
                format!("term nested too deeply (more than {MAX_DEPTH} levels)"),
            ));
        }
        // pest itself refuses to run with less than 64 KiB of stack left: keep more.
        let result = stacker::maybe_grow(256 * 1024, 4 * 1024 * 1024, || self.parse_inner(max));
        self.depth -= 1;
        result.map(|(t, _)| t)
    }

    fn parse_inner(&mut self, max: u16) -> PResult<(TermId, u16)> {
        let (mut left, mut left_prio) = self.primary(max)?;
        loop {
            let (name, is_punct) = match &self.tok.kind {
                TokKind::Name { atom, .. } => (*atom, false),
                TokKind::Punct(',') => (atoms::COMMA, true),
                TokKind::Punct('|') => (atoms::BAR, true),
                _ => break,
            };
            if let Some(def) = self.ops.infix(name) {
                let (lmax, rmax) = def.arg_max();
                let (lmax, rmax) = (lmax.unwrap_or(0), rmax.unwrap_or(0));
                if def.priority <= max && left_prio <= lmax {
                    let op_tok = self.advance()?;
                    let _ = is_punct;
                    let right = self.parse(rmax)?;
                    let span = self.terms.span(left).to(self.terms.span(right));
                    let _ = op_tok;
                    left = self.terms.push_compound(name, &[left, right], span);
                    left_prio = def.priority;
                    continue;
                }
            }
            if let Some(def) = self.ops.postfix(name) {
                let (lmax, _) = def.arg_max();
                if def.priority <= max && left_prio <= lmax.unwrap_or(0) {
                    let op_tok = self.advance()?;
                    let span = self.terms.span(left).to(op_tok.span);
                    left = self.terms.push_compound(name, &[left], span);
                    left_prio = def.priority;
                    continue;
                }
            }
            break;
        }
        Ok((left, left_prio))
    }

    /// Whether the current token can start a term (used to decide whether a
    /// prefix operator has an operand).
    fn starts_term(&mut self, tok: &TokKind) -> bool {
        match tok {
            TokKind::Name { atom, .. } => {
                // An infix operator that is not also a prefix operator ends the term.
                !(self.ops.infix(*atom).is_some() && self.ops.prefix(*atom).is_none())
            }
            TokKind::Var(_)
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

    fn primary(&mut self, max: u16) -> PResult<(TermId, u16)> {
        let tok = self.advance()?;
        let span = tok.span;
        match tok.kind {
            TokKind::Int(i) => Ok((self.push(Node::Int(i), span), 0)),
            TokKind::BigInt(s) => Ok((self.push(Node::BigInt(s), span), 0)),
            TokKind::Float(f) => Ok((self.push(Node::Float(f), span), 0)),
            TokKind::Str(s) => Ok((self.push(Node::Str(s), span), 0)),
            TokKind::BackQuoted(s) => Ok((self.push(Node::BackQuoted(s), span), 0)),
            TokKind::Var(name) => {
                let id = self.var(name, span);
                Ok((self.push(Node::Var(id), span), 0))
            }
            TokKind::Punct('(') | TokKind::OpenCt => {
                self.open.push((span, '('));
                let inner = self.parse(1200)?;
                self.close(')')?;
                Ok((inner, 0))
            }
            TokKind::Punct('[') => {
                if self.tok.kind == TokKind::Punct(']') {
                    let end = self.advance()?.span;
                    let id = self.push(Node::Atom(atoms::NIL), span.to(end));
                    return self.maybe_functional(atoms::NIL, id, span.to(end));
                }
                self.open.push((span, '['));
                let mut items = Vec::new();
                loop {
                    items.push(self.parse(999)?);
                    if self.tok.kind == TokKind::Punct(',') {
                        self.advance()?;
                        continue;
                    }
                    break;
                }
                let tail = if self.tok.kind == TokKind::Punct('|') {
                    self.advance()?;
                    Some(self.parse(999)?)
                } else {
                    None
                };
                let end = self.tok.span;
                self.close(']')?;
                let full = span.to(end);
                let mut list = match tail {
                    Some(t) => t,
                    None => self.push(Node::Atom(atoms::NIL), end),
                };
                for &item in items.iter().rev() {
                    let s = Span {
                        start: self.terms.span(item).start,
                        end: full.end,
                    };
                    list = self.terms.push_compound(atoms::DOT, &[item, list], s);
                }
                // The outermost cell spans the whole list, brackets included.
                let _ = full;
                Ok((list, 0))
            }
            TokKind::Punct('{') => {
                if self.tok.kind == TokKind::Punct('}') {
                    let end = self.advance()?.span;
                    let id = self.push(Node::Atom(atoms::CURLY), span.to(end));
                    return self.maybe_functional(atoms::CURLY, id, span.to(end));
                }
                self.open.push((span, '{'));
                let inner = self.parse(1200)?;
                let end = self.tok.span;
                self.close('}')?;
                Ok((
                    self.terms
                        .push_compound(atoms::CURLY, &[inner], span.to(end)),
                    0,
                ))
            }
            TokKind::Name { atom, quoted } => self.name_primary(atom, quoted, span, max),
            _ => {
                // Put the token back for the error message.
                let cur = std::mem::replace(&mut self.tok, tok);
                self.peeked = Some(cur);
                Err(self.expected_term_error())
            }
        }
    }

    /// `[](..)`/`{}(..)`: SWI-7 functional notation on `[]` and `{}`.
    fn maybe_functional(&mut self, name: Atom, id: TermId, span: Span) -> PResult<(TermId, u16)> {
        if self.tok.kind == TokKind::OpenCt {
            return self.compound(name, span);
        }
        Ok((id, 0))
    }

    fn name_primary(
        &mut self,
        atom: Atom,
        quoted: bool,
        span: Span,
        max: u16,
    ) -> PResult<(TermId, u16)> {
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
                return Ok((self.push(node, span.to(num.span)), 0));
            }
        }
        if let Some(def) = self.ops.prefix(atom) {
            let next = self.tok.kind.clone();
            let mut has_operand = self.starts_term(&next);
            // `- (a)`: an operand in parentheses; `-(a)` was functional notation above.
            if let TokKind::Name { atom: n, .. } = &next {
                // `- =`: an infix-only operator after a prefix operator makes it an atom,
                // unless that name is followed by `(` (then it is a term: `- =(a,b)`).
                if self.ops.infix(*n).is_some() && self.ops.prefix(*n).is_none() {
                    has_operand = self.peek()?.kind == TokKind::OpenCt;
                }
            }
            if has_operand {
                let (_, rmax) = def.arg_max();
                let mut prio = def.priority;
                let mut rmax = rmax.unwrap_or(0);
                if prio > max {
                    // ISO: a prefix operator of higher priority than allowed here
                    // can still be read as an atom operand; otherwise clamp like SWI.
                    prio = max;
                    rmax = rmax.min(max);
                }
                let arg = self.parse(rmax)?;
                let s = span.to(self.terms.span(arg));
                return Ok((self.terms.push_compound(atom, &[arg], s), prio));
            }
        }
        let id = self.push(Node::Atom(atom), span);
        Ok((id, 0))
    }

    fn compound(&mut self, name: Atom, start: Span) -> PResult<(TermId, u16)> {
        let open = self.advance()?; // OpenCt
        self.open.push((open.span, '('));
        let mut args = Vec::new();
        if self.tok.kind == TokKind::Punct(')') {
            // `name()`: SWI-Prolog 7 zero-argument compound.
            let end = self.advance()?.span;
            self.open.pop();
            return Ok((self.terms.push_compound(name, &[], start.to(end)), 0));
        }
        loop {
            args.push(self.parse(999)?);
            if self.tok.kind == TokKind::Punct(',') {
                self.advance()?;
                continue;
            }
            break;
        }
        let end = self.tok.span;
        self.close(')')?;
        Ok((self.terms.push_compound(name, &args, start.to(end)), 0))
    }

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
            Err(e)
        }
    }

    fn var(&mut self, name: Box<str>, span: Span) -> VarId {
        if &*name != "_" {
            if let Some(&id) = self.var_ids.get(&name) {
                self.vars[id.0 as usize].occurrences += 1;
                return id;
            }
        }
        let id = VarId(self.vars.len() as u32);
        self.vars.push(VarInfo {
            name: name.clone(),
            first: span,
            occurrences: 1,
        });
        if &*name != "_" {
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
        assert_eq!(rt("- 1"), "-(1)");
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
        assert_eq!(
            rt("(c -> a | otherwise -> b)"),
            "'|'((c->a),(otherwise->b))"
        );
        assert_eq!(rt("\\+ a"), "\\+a");
        assert_eq!(rt("- - a"), "- -a");
        assert_eq!(rt("f(-)"), "f(-)");
        assert_eq!(rt("- (1)"), "-(1)");
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
        ] {
            let e = err(src);
            assert!(e.message.contains("priority clash"), "{src}: {e:?}");
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
