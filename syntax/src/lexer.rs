//! The lexer: pest matches one token at a time (see `token.pest`); this module
//! turns the match into a [`Token`] and reports lexical errors precisely. The
//! common ASCII tokens (names, variables, symbol atoms, plain integers, quoted
//! atoms without escapes) are scanned without the grammar, to the same token
//! (`fast_token`; the grammar stays the reference and says every error): a
//! start of `sitlogc run --legacy` reads about a megabyte of DMs and Prolog, and
//! pest was a sixth of its instructions.
//!
//! **Invariant:** the fast paths change no token, span or error: on every text
//! the lexer gives what the grammar alone gives (its rule `next` from the end
//! of each token). [`fast_path_disagreement`] checks it, in proptests here, on
//! the fuzz regressions, and in the `read` fuzz target on arbitrary bytes.

use crate::atom::{atoms, Atom};
use crate::error::SyntaxError;
use crate::term::Span;
use pest::Parser;

#[derive(pest_derive::Parser)]
#[grammar = "token.pest"]
struct TokenGrammar;

/// What a token is.
#[derive(Clone, Debug, PartialEq)]
pub enum TokKind {
    /// A name: letter, symbol, solo or quoted atom.
    Name {
        atom: Atom,
        quoted: bool,
    },
    /// A variable; its name is the token's text.
    Var,
    Int(i64),
    BigInt(Box<str>),
    Float(f64),
    Str(Box<str>),
    BackQuoted(Box<str>),
    /// `(` directly after a name: functional notation.
    OpenCt,
    Punct(char),
    /// The end token `.` followed by layout or end of input.
    End,
    Eof,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    pub kind: TokKind,
    pub span: Span,
    /// Whether layout (spaces, comments) came before the token.
    pub layout_before: bool,
}

pub struct Lexer<'s> {
    src: &'s str,
    pos: usize,
    prev_was_name: bool,
    /// How much is done without the grammar; [`Mode::Fast`] except in the
    /// tests and the fuzz target that compare the three ways.
    mode: Mode,
}

/// How a [`Lexer`] finds its tokens. Every mode gives the same tokens and
/// errors on every text ([`fast_path_disagreement`] checks it).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    /// Layout, one-character tokens and characters that start no token in
    /// Rust, the common ASCII tokens by [`fast_token`], the rest by the
    /// grammar rule that the first character selects.
    Fast,
    /// As `Fast`, without [`fast_token`].
    Grammar,
    /// The grammar alone: every step is the rule `next` (layout then a
    /// token) from where the last token ended; driven by `tokens_in`, never
    /// by `next_token`.
    Pest,
}

impl<'s> Lexer<'s> {
    pub fn new(src: &'s str, pos: usize) -> Lexer<'s> {
        Lexer {
            src,
            pos,
            prev_was_name: false,
            mode: Mode::Fast,
        }
    }

    /// Skips one character after an error, so that reading can resume.
    pub fn skip_char(&mut self) {
        if let Some(c) = self.src[self.pos..].chars().next() {
            self.pos += c.len_utf8();
        }
    }

    #[inline(never)]
    pub fn next_token(&mut self) -> Result<Token, SyntaxError> {
        let begin = self.pos;
        let bytes = self.src.as_bytes();
        let mut i = self.pos;
        // Plain layout and comments, in Rust; pest only sees tokens.
        loop {
            match bytes.get(i) {
                Some(b' ' | b'\t' | b'\n' | b'\r' | 0x0B | 0x0C) => i += 1,
                Some(b'%') => {
                    i = bytes[i..]
                        .iter()
                        .position(|&b| b == b'\n')
                        .map_or(bytes.len(), |n| i + n);
                }
                Some(b'/') if bytes.get(i + 1) == Some(&b'*') => {
                    match find(&bytes[i + 2..], b"*/") {
                        Some(n) => i += 2 + n + 2,
                        None => break, // unterminated: reported by the token path
                    }
                }
                Some(&b) if b >= 0x80 => match self.src[i..].chars().next() {
                    Some(c) if is_unicode_layout(c) => i += c.len_utf8(),
                    _ => break,
                },
                _ => break,
            }
        }
        let layout_before = i > begin;
        self.pos = i;
        let base = i;
        let rest = &self.src[i..];
        let Some(&first) = bytes.get(i) else {
            return Ok(Token {
                kind: TokKind::Eof,
                span: Span::new(self.src.len(), self.src.len()),
                layout_before,
            });
        };
        // One-character tokens need no grammar.
        let single = match first {
            b'(' | b')' | b'[' | b']' | b'{' | b'}' | b',' | b'|' => {
                Some(if first == b'(' && !layout_before && self.prev_was_name {
                    TokKind::OpenCt
                } else {
                    TokKind::Punct(first as char)
                })
            }
            b'!' | b';' => Some(TokKind::Name {
                atom: if first == b'!' {
                    atoms::CUT
                } else {
                    atoms::SEMICOLON
                },
                quoted: false,
            }),
            b'.' if bytes
                .get(i + 1)
                .is_none_or(|&b| b == b'%' || starts_layout(&self.src[i + 1..])) =>
            {
                Some(TokKind::End)
            }
            _ => None,
        };
        if let Some(kind) = single {
            self.pos = i + 1;
            self.prev_was_name = matches!(
                kind,
                TokKind::Name { .. } | TokKind::Punct(']') | TokKind::Punct('}')
            );
            return Ok(Token {
                kind,
                span: Span::new(i, i + 1),
                layout_before,
            });
        }
        // A character that starts no token (a control character, or one
        // beyond ASCII that is neither layout nor a letter) is said here,
        // without the grammar: a failed pest parse costs the length of the
        // line, so a line of them cost its length squared. "A letter" is
        // the grammar's `ALPHABETIC`, by pest's Unicode tables: Rust's
        // `char::is_alphabetic` follows another Unicode version (U+058B).
        if !(0x20..0x7F).contains(&first) {
            let c = rest.chars().next().unwrap_or(' ');
            if c.is_control() || (!c.is_ascii() && !pest::unicode::ALPHABETIC(c)) {
                let what = if c.is_control() {
                    format!("unexpected control character U+{:04X}", c as u32)
                } else {
                    format!("unexpected character `{c}`")
                };
                return Err(SyntaxError::new(Span::new(i, i + c.len_utf8()), what));
            }
        }
        if self.mode == Mode::Fast {
            if let Some((kind, end)) = fast_token(bytes, i, first) {
                let span = Span::new(i, end);
                let kind = match kind {
                    Fast::Name => TokKind::Name {
                        atom: Atom::intern(&self.src[i..end]),
                        quoted: false,
                    },
                    Fast::Var => TokKind::Var,
                    Fast::Int(n) => TokKind::Int(n),
                    Fast::Quoted => TokKind::Name {
                        atom: Atom::intern(&unquote(&self.src[i..end], i)?),
                        quoted: true,
                    },
                };
                self.pos = end;
                self.prev_was_name = matches!(kind, TokKind::Name { .. });
                return Ok(Token {
                    kind,
                    span,
                    layout_before,
                });
            }
        }
        self.grammar_token(base, layout_before)
    }

    /// The token at `base` by the grammar: the rule that its first
    /// character selects, or `next` (layout, then a token) when that
    /// character selects none or in [`Mode::Pest`].
    fn grammar_token(&mut self, base: usize, layout_before: bool) -> Result<Token, SyntaxError> {
        let rest = &self.src[base..];
        let first = rest.as_bytes().first().copied().unwrap_or(b' ');
        let rule = match first {
            _ if self.mode == Mode::Pest => Rule::next,
            b'a'..=b'z' => Rule::letter_name,
            b'A'..=b'Z' | b'_' => Rule::variable,
            b'0'..=b'9' => Rule::number,
            b'\'' => Rule::quoted,
            b'"' => Rule::dq_string,
            b'`' => Rule::bq_string,
            b'#' | b'$' | b'&' | b'*' | b'+' | b'-' | b'.' | b'/' | b':' | b'<' | b'=' | b'>'
            | b'?' | b'@' | b'^' | b'~' | b'\\' => Rule::symbol_name,
            _ => Rule::next,
        };
        let pairs = match TokenGrammar::parse(rule, rest) {
            Ok(pairs) => pairs,
            Err(_) => return Err(self.lex_error(base)),
        };
        let mut pair = pairs
            .into_iter()
            .next()
            .expect("a token rule produced a pair");
        if rule == Rule::next {
            let mut token = None;
            for inner in pair.into_inner() {
                match inner.as_rule() {
                    Rule::layout | Rule::EOI => {}
                    _ => token = Some(inner),
                }
            }
            let Some(inner) = token else {
                // Only layout (or nothing) left. An unterminated block comment is not layout.
                let after = base + next_layout_end(rest);
                if self.src[after..].starts_with("/*") {
                    return Err(unterminated(after, "block comment", "`*/`"));
                }
                self.pos = self.src.len();
                return Ok(Token {
                    kind: TokKind::Eof,
                    span: Span::new(self.src.len(), self.src.len()),
                    layout_before: layout_before || after > base,
                });
            };
            pair = inner;
        }
        let start = base + pair.as_span().start();
        let end = base + pair.as_span().end();
        // Layout that the rule `next` skipped ([`Mode::Pest`]).
        let layout_before = layout_before || start > base;
        if pair.as_rule() == Rule::integer
            && pair.as_str() == "0"
            && self.src[start..].starts_with("0'")
        {
            return Err(SyntaxError {
                incomplete: self.src.len() - start == 2,
                ..SyntaxError::new(
                    Span::new(start, start + 2),
                    "incomplete character code `0'`".to_owned(),
                )
            });
        }
        let text = pair.as_str();
        let span = Span::new(start, end);
        let kind = match pair.as_rule() {
            Rule::float if text.ends_with("Inf") => TokKind::Float(f64::INFINITY),
            Rule::float if text.ends_with("NaN") => TokKind::Float(f64::NAN),
            Rule::float => match text.parse::<f64>() {
                Ok(f) if f.is_finite() => TokKind::Float(f),
                _ => {
                    return Err(SyntaxError::new(
                        span,
                        format!("float `{text}` is out of range"),
                    ))
                }
            },
            Rule::char_code => {
                let body = &text[2..];
                let code = if body == "''" {
                    '\'' as i64
                } else if let Some(esc) = body.strip_prefix('\\') {
                    let mut chars = String::new();
                    unescape_one(esc, start + 3, &mut chars)?;
                    chars.chars().next().map_or(0, |c| c as i64)
                } else {
                    body.chars().next().map_or(0, |c| c as i64)
                };
                TokKind::Int(code)
            }
            Rule::hex => radix(&text[2..], 16, span)?,
            Rule::octal => radix(&text[2..], 8, span)?,
            Rule::binary => radix(&text[2..], 2, span)?,
            Rule::integer => {
                let digits: String = text.chars().filter(char::is_ascii_digit).collect();
                match digits.parse::<i64>() {
                    Ok(i) => TokKind::Int(i),
                    Err(_) => TokKind::BigInt(digits.trim_start_matches('0').into()),
                }
            }
            Rule::variable => TokKind::Var,
            Rule::letter_name | Rule::solo => TokKind::Name {
                atom: Atom::intern(text),
                quoted: false,
            },
            Rule::end => TokKind::End,
            Rule::symbol_name => {
                // `/*` starts a comment only at the start of a token (as in
                // SWI-Prolog: `+/*` is one atom); a closed comment was layout.
                if text.starts_with("/*") {
                    return Err(unterminated(start, "block comment", "`*/`"));
                }
                TokKind::Name {
                    atom: Atom::intern(text),
                    quoted: false,
                }
            }
            Rule::quoted => TokKind::Name {
                atom: Atom::intern(&unquote(text, start)?),
                quoted: true,
            },
            Rule::dq_string => TokKind::Str(unquote(text, start)?.into()),
            Rule::bq_string => TokKind::BackQuoted(unquote(text, start)?.into()),
            Rule::punct => {
                let c = text.chars().next().expect("punct is one char");
                if c == '(' && !layout_before && self.prev_was_name {
                    TokKind::OpenCt
                } else {
                    TokKind::Punct(c)
                }
            }
            other => unreachable!("token rule {other:?} is not a token"),
        };
        self.pos = end;
        // `[](..)` and `{}(..)`: functional notation on `[]` and `{}` (SWI 7).
        self.prev_was_name = matches!(
            kind,
            TokKind::Name { .. } | TokKind::Punct(']') | TokKind::Punct('}')
        );
        Ok(Token {
            kind,
            span,
            layout_before,
        })
    }

    fn lex_error(&mut self, base: usize) -> SyntaxError {
        let rest = &self.src[base..];
        let at = base + next_layout_end(rest);
        let tail = &self.src[at..];
        let c = tail.chars().next().unwrap_or(' ');
        match c {
            '\'' => unterminated_or_bad_escape(self.src, at, '\'', "quoted atom"),
            '"' => unterminated_or_bad_escape(self.src, at, '"', "string"),
            '`' => unterminated_or_bad_escape(self.src, at, '`', "back-quoted string"),
            _ if tail.starts_with("0'") => SyntaxError::new(
                Span::new(at, at + 2),
                "incomplete character code `0'`".to_owned(),
            ),
            _ => {
                let what = if c.is_control() {
                    format!("unexpected control character U+{:04X}", c as u32)
                } else {
                    format!("unexpected character `{c}`")
                };
                SyntaxError::new(Span::new(at, at + c.len_utf8()), what)
            }
        }
    }
}

/// What [`fast_token`] found.
enum Fast {
    /// A letter or symbol name (not quoted).
    Name,
    Var,
    Int(i64),
    /// A quoted atom with no escape (its doubled quotes resolved by [`unquote`]).
    Quoted,
}

/// The token at `i` (first byte `first`, not layout) and its end, when it is
/// one of the common ASCII shapes that the grammar would match the same way:
/// a letter name or variable of ASCII letters, digits and `_` (not followed
/// by a character beyond ASCII, which may continue it), a run of symbol
/// characters (not starting a comment), a decimal integer that nothing may
/// continue (no `.`, `_`, `'`, letter or digit group after it) and fits in
/// 64 bits, a quoted atom with no `\`. Anything else (`None`) goes to the
/// grammar, which also says every error: what this accepts is exactly what
/// the grammar's rule for that first character accepts
/// ([`fast_path_disagreement`] compares them).
fn fast_token(bytes: &[u8], i: usize, first: u8) -> Option<(Fast, usize)> {
    let word = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    match first {
        b'a'..=b'z' | b'A'..=b'Z' | b'_' => {
            let mut j = i + 1;
            while j < bytes.len() && word(bytes[j]) {
                j += 1;
            }
            if bytes.get(j).is_some_and(|&b| b >= 0x80) {
                return None;
            }
            let kind = if first.is_ascii_lowercase() {
                Fast::Name
            } else {
                Fast::Var
            };
            Some((kind, j))
        }
        b if is_symbol_char(b) => {
            if first == b'/' && bytes.get(i + 1) == Some(&b'*') {
                return None;
            }
            let mut j = i + 1;
            while j < bytes.len() && is_symbol_char(bytes[j]) {
                j += 1;
            }
            Some((Fast::Name, j))
        }
        b'0'..=b'9' => {
            let mut j = i + 1;
            while j < bytes.len() && bytes[j].is_ascii_digit() {
                j += 1;
            }
            match bytes.get(j) {
                Some(b) if word(*b) || *b >= 0x80 || matches!(b, b'.' | b'\'') => return None,
                // `1 000` is one integer (a digit group).
                Some(b' ') if bytes.get(j + 1).is_some_and(u8::is_ascii_digit) => return None,
                _ => {}
            }
            let text = std::str::from_utf8(&bytes[i..j]).ok()?;
            let n = text.parse::<i64>().ok()?;
            Some((Fast::Int(n), j))
        }
        b'\'' => {
            let mut j = i + 1;
            loop {
                match bytes.get(j)? {
                    b'\\' => return None,
                    b'\'' if bytes.get(j + 1) == Some(&b'\'') => j += 2,
                    b'\'' => return Some((Fast::Quoted, j + 1)),
                    _ => j += 1,
                }
            }
        }
        _ => None,
    }
}

/// A symbol character (`symbol_char` of `token.pest`).
fn is_symbol_char(b: u8) -> bool {
    matches!(
        b,
        b'#' | b'$'
            | b'&'
            | b'*'
            | b'+'
            | b'-'
            | b'.'
            | b'/'
            | b':'
            | b'<'
            | b'='
            | b'>'
            | b'?'
            | b'@'
            | b'^'
            | b'~'
            | b'\\'
    )
}

/// Layout characters beyond ASCII white space (as in `token.pest`).
fn is_unicode_layout(c: char) -> bool {
    matches!(c, '\u{A0}' | '\u{FEFF}' | '\u{2028}' | '\u{2029}')
}

/// Whether `s` starts with a layout character or a `%` comment.
fn starts_layout(s: &str) -> bool {
    match s.chars().next() {
        Some(' ' | '\t' | '\n' | '\r' | '\u{0B}' | '\u{0C}' | '%') => true,
        Some(c) => is_unicode_layout(c),
        None => true,
    }
}

/// Offset of the first occurrence of `needle` in `hay`.
fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

/// Byte length of the layout (spaces and complete comments) at the start of `s`.
fn next_layout_end(s: &str) -> usize {
    match TokenGrammar::parse(Rule::layout, s) {
        Ok(mut pairs) => pairs.next().map_or(0, |p| p.as_span().end()),
        Err(_) => 0,
    }
}

fn unterminated(at: usize, what: &str, closer: &str) -> SyntaxError {
    let mut e = SyntaxError::new(
        Span::new(at, at + 2.min(1 + what.len())),
        format!("unterminated {what}"),
    );
    e.span = Span::new(at, at + if what == "block comment" { 2 } else { 1 });
    e.help = Some(format!("add the closing {closer}"));
    e.incomplete = true;
    e
}

fn unterminated_or_bad_escape(src: &str, at: usize, quote: char, what: &str) -> SyntaxError {
    // Find whether a closing quote exists: if so the problem is an escape.
    let body = &src[at + 1..];
    let mut chars = body.char_indices();
    while let Some((i, c)) = chars.next() {
        if c == '\\' {
            if let Some((j, e)) = chars.next() {
                if !"abcfnrtvxesuU0123456789\\'\"`\n".contains(e) {
                    let s = at + 1 + i;
                    let mut err = SyntaxError::new(
                        Span::new(s, at + 1 + j + e.len_utf8()),
                        format!("unknown escape sequence `\\{e}` in {what}"),
                    );
                    err.help = Some("write `\\\\` for a backslash".to_owned());
                    return err;
                }
            }
        } else if c == quote {
            if body[i + 1..].starts_with(quote) {
                chars.next();
                continue;
            }
            break;
        }
    }
    let mut e = unterminated(at, what, &format!("`{quote}`"));
    e.span = Span::new(at, at + 1);
    e
}

fn radix(digits: &str, base: u32, span: Span) -> Result<TokKind, SyntaxError> {
    match i64::from_str_radix(digits, base) {
        Ok(i) => Ok(TokKind::Int(i)),
        Err(_) => Err(SyntaxError::new(
            span,
            "integer literal is too large (more than 64 bits)".to_owned(),
        )),
    }
}

/// Resolves the quotes and escapes of a quoted token (`'..'`, `".."`, `` `..` ``).
fn unquote(text: &str, start: usize) -> Result<String, SyntaxError> {
    let quote = text.chars().next().expect("quoted token has a quote");
    let body = &text[1..text.len() - 1];
    let mut out = String::with_capacity(body.len());
    let mut i = 0;
    while i < body.len() {
        let c = body[i..].chars().next().expect("in bounds");
        if c == quote {
            // Doubled quote.
            out.push(quote);
            i += 2;
        } else if c == '\\' {
            i += 1 + unescape_one(&body[i + 1..], start + 1 + i + 1, &mut out)?;
        } else {
            out.push(c);
            i += c.len_utf8();
        }
    }
    Ok(out)
}

/// Resolves one escape (the text after `\`); returns the bytes consumed.
fn unescape_one(s: &str, at: usize, out: &mut String) -> Result<usize, SyntaxError> {
    let c = s.chars().next().unwrap_or('\\');
    let simple = match c {
        'a' => Some('\u{7}'),
        'b' => Some('\u{8}'),
        'f' => Some('\u{c}'),
        'n' => Some('\n'),
        'r' => Some('\r'),
        't' => Some('\t'),
        'v' => Some('\u{b}'),
        'e' => Some('\u{1b}'),
        's' => Some(' '),
        '\\' | '\'' | '"' | '`' => Some(c),
        _ => None,
    };
    if let Some(ch) = simple {
        out.push(ch);
        return Ok(1);
    }
    if c == '\n' {
        return Ok(1); // line continuation
    }
    if c == 'c' {
        // SWI-Prolog: `\c` skips the layout that follows it.
        let layout: usize = s[1..]
            .chars()
            .take_while(|c| c.is_whitespace())
            .map(char::len_utf8)
            .sum();
        return Ok(1 + layout);
    }
    if c == 'u' || c == 'U' {
        // SWI-Prolog: `\uXXXX` and `\UXXXXXXXX`.
        let n = if c == 'u' { 4 } else { 8 };
        let digits = s[1..]
            .get(..n)
            .filter(|d| d.chars().all(|c| c.is_ascii_hexdigit()));
        let ch = digits
            .and_then(|d| u32::from_str_radix(d, 16).ok())
            .and_then(char::from_u32);
        return match ch {
            Some(ch) => {
                out.push(ch);
                Ok(1 + n)
            }
            None => {
                // The `n` bytes after the letter, widened to the end of a
                // character they cut (`\ubbd` then a 2-byte character):
                // the span must stay on character boundaries (fuzzing).
                let mut end = (1 + n).min(s.len());
                while !s.is_char_boundary(end) {
                    end += 1;
                }
                Err(SyntaxError::new(
                    Span::new(at - 1, at + end),
                    format!(
                        "`\\{c}` must be followed by {n} hexadecimal digits of a valid character"
                    ),
                ))
            }
        };
    }
    let (digits, base, skip) = if c == 'x' {
        let d: String = s[1..]
            .chars()
            .take_while(|c| c.is_ascii_hexdigit())
            .collect();
        (d, 16, 1)
    } else if c.is_digit(8) {
        let d: String = s.chars().take_while(|c| c.is_digit(8)).collect();
        (d, 8, 0)
    } else {
        let mut e = SyntaxError::new(
            Span::new(at - 1, at + c.len_utf8()),
            format!("unknown escape sequence `\\{c}`"),
        );
        e.help = Some("write `\\\\` for a backslash".to_owned());
        return Err(e);
    };
    let mut used = skip + digits.len();
    if s[used..].starts_with('\\') {
        used += 1;
    }
    let code = u32::from_str_radix(&digits, base).ok();
    match code.and_then(char::from_u32) {
        Some(ch) => {
            out.push(ch);
            Ok(used)
        }
        None => Err(SyntaxError::new(
            Span::new(at - 1, at + used),
            "escape sequence is not a valid character code".to_owned(),
        )),
    }
}

impl<'s> Lexer<'s> {
    pub fn source(&self) -> &'s str {
        self.src
    }
}

/// Every token of `src` and every error in `mode`, as text: after an error,
/// lexing starts again at the error's end (as a reader that skips it would),
/// so that the rest of the text is compared too.
fn tokens_in(src: &str, mode: Mode) -> Vec<String> {
    let mut out = Vec::new();
    let mut lexer = Lexer::new(src, 0);
    lexer.mode = mode;
    loop {
        // `Mode::Pest` is driven from here, so that `next_token` (the
        // readers' path) does not test for it.
        let token = if mode == Mode::Pest {
            lexer.grammar_token(lexer.pos, false)
        } else {
            lexer.next_token()
        };
        match token {
            Ok(t) if t.kind == TokKind::Eof => {
                out.push(format!("{t:?}"));
                return out;
            }
            Ok(t) => out.push(format!("{t:?}")),
            Err(e) => {
                out.push(format!("{e:?}"));
                let (start, end) = (e.span.start as usize, e.span.end as usize);
                let mut at = end.max(lexer.pos);
                if at <= start {
                    at = start + src[start..].chars().next().map_or(1, char::len_utf8);
                }
                if at >= src.len() {
                    return out;
                }
                lexer = Lexer::new(src, at);
                lexer.mode = mode;
            }
        }
    }
}

/// Where the lexer's fast paths and the grammar alone disagree on `src`:
/// `None` when the three modes (fast path, grammar rule by first character,
/// the grammar's `next` rule only) give the same tokens, spans and errors;
/// otherwise the first difference. For the differential tests and the
/// `read` fuzz target; not an API.
#[doc(hidden)]
pub fn fast_path_disagreement(src: &str) -> Option<String> {
    let pest = tokens_in(src, Mode::Pest);
    for mode in [Mode::Fast, Mode::Grammar] {
        let other = tokens_in(src, mode);
        if other != pest {
            let k = other
                .iter()
                .zip(&pest)
                .position(|(a, b)| a != b)
                .unwrap_or(other.len().min(pest.len()));
            return Some(format!(
                "{mode:?} and the grammar alone differ on {src:?} at token {k}:\n  {mode:?}: {}\n  grammar: {}",
                other.get(k).map_or("(none)", String::as_str),
                pest.get(k).map_or("(none)", String::as_str),
            ));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn same(src: &str) {
        if let Some(diff) = fast_path_disagreement(src) {
            panic!("{diff}");
        }
    }

    #[test]
    fn fast_path_matches_the_grammar_on_chosen_text() {
        for src in [
            "foo(X, _Y, 'a''b', 'c\\n', 12, 1 000, 1_000, 0'a, 0x1F, 1.5, 1e3, 1.)",
            "a:-b,c;d->e. X =.. [F|A], '$x'(1) /* c */ % c\n +/* x",
            "9223372036854775808 007 0'' 0'\\n 'unterminated",
            "héllo hé Ünï _é 1é 'é' +é a\u{a0}b. x.% c",
            "[]([]) {}(a) f (x) f(x) \"s\" `b` 1 2 3.",
        ] {
            same(src);
        }
    }

    proptest! {
        #[test]
        fn fast_path_matches_the_grammar(src in "[a-zA-Z0-9_ '\"`.,()\\[\\]{}|%/*+=:\\\\#$&!;<>?@^~é\u{a0}\n-]{0,40}") {
            same(&src);
        }

        /// Characters beyond the strategy above: other layout, a control
        /// character, an upper-case and a title-case letter, a digit and a
        /// combining mark beyond ASCII, a character that starts no token.
        #[test]
        fn fast_path_matches_the_grammar_beyond_ascii(src in "[a-z0-9A-Z_ '\".(/*+\\\\\t\r\u{1}\u{7f}Üǅ²\u{301}\u{feff}\u{2028}€-]{0,30}") {
            same(&src);
        }
    }
}
