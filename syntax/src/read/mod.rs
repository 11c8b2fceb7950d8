//! The reader's entry points: all clauses of a text (resuming after an
//! error, like Prolog's `read/1`), one term, clauses one at a time
//! ([`ClauseReader`]), from text or from bytes; and, for an unclosed
//! bracket, a hint at the likely place from the indentation. The parsing
//! itself is in `parser` (precedence climbing, iterative, depth-limited).

mod parser;

pub use parser::MAX_DEPTH;

use crate::error::{line_col, SyntaxError};
use crate::lexer::{Lexer, TokKind, Token};
use crate::ops::OpTable;
use crate::term::{Clause, Span};
use parser::Parser;

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

/// Reads all clauses of a Prolog source file (an application's
/// `user_functions.pl`, `templates.pl` and what they consult) with
/// SWI-Prolog's operator table, as the original's SWI-Prolog consults
/// them: `:- dynamic foo/1.` and the other directive operators
/// (`discontiguous`, `initialization`, `multifile`, ...) read as prefix
/// operators. DMs and the other side files keep SitLog's table.
pub fn read_prolog_clauses(src: &str) -> (Vec<Clause>, Vec<SyntaxError>) {
    read_clauses_with(src, OpTable::swi_shared())
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

/// Where the lines of a text start, found as a walk moves forwards through
/// it: each byte is looked at once, however long the lines (looking back
/// from every bracket of a 400 000-bracket line took 15 s).
struct Lines<'s> {
    src: &'s str,
    /// Start of the line holding `seen`.
    start: usize,
    /// How far the text has been looked at.
    seen: usize,
}

impl<'s> Lines<'s> {
    fn new(src: &'s str, from: usize) -> Lines<'s> {
        let start = src[..from].rfind('\n').map_or(0, |i| i + 1);
        Lines {
            src,
            start,
            seen: from,
        }
    }

    /// Start of the line holding byte `at` (`at` never goes backwards).
    fn start_of(&mut self, at: usize) -> usize {
        if at > self.seen {
            if let Some(i) = self.src[self.seen..at].rfind('\n') {
                self.start = self.seen + i + 1;
            }
            self.seen = at;
        }
        self.start
    }

    /// Width of the indentation of the line holding byte `at` (a tab counts 8).
    fn indent_of_line(&mut self, at: usize) -> usize {
        let start = self.start_of(at);
        self.src[start..]
            .chars()
            .take_while(|c| *c == ' ' || *c == '\t')
            .map(|c| if c == '\t' { 8 } else { 1 })
            .sum()
    }

    /// Whether only blanks precede byte `at` on its line.
    fn first_on_line(&mut self, at: usize) -> bool {
        let start = self.start_of(at);
        self.src[start..at]
            .chars()
            .all(|c| c == ' ' || c == '\t' || c == '\r')
    }
}

/// For unbalanced brackets: the first closing bracket between the unclosed
/// bracket at `unclosed` and the error at `to` that starts its line indented
/// less than the line of the bracket it closes: a likely place for a
/// forgotten closing bracket (the clause starts at `from`).
fn indentation_hint(src: &str, from: usize, unclosed: usize, to: usize) -> Option<(Span, String)> {
    let mut lexer = Lexer::new(src, from);
    let mut lines = Lines::new(src, from);
    let mut stack: Vec<(Span, usize)> = Vec::new();
    loop {
        let tok = lexer.next_token().ok()?;
        if tok.span.start as usize >= to || matches!(tok.kind, TokKind::Eof | TokKind::End) {
            return None;
        }
        match tok.kind {
            TokKind::Punct('(' | '[' | '{') | TokKind::OpenCt => {
                stack.push((tok.span, lines.indent_of_line(tok.span.start as usize)));
            }
            TokKind::Punct(c @ (')' | ']' | '}')) => {
                let (open, indent) = stack.pop()?;
                let at = tok.span.start as usize;
                if at > unclosed && lines.first_on_line(at) && lines.indent_of_line(at) < indent {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atom::Atom;
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
