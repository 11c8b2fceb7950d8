//! Writing terms in Prolog syntax, `writeq` style (as SWI-Prolog prints them).
//!
//! The printer is generic over [`TermSource`] so the reader's arena terms and
//! the runtime's heap terms print through the same code.

use crate::atom::{atoms, Atom};
use crate::ops::OpTable;
use crate::term::{Clause, Node, TermId};
use std::fmt::Write as _;

/// How a variable prints.
#[derive(Clone, Copy, Debug)]
pub enum VarLabel<'a> {
    /// A source name (`X`, `_Foo`, `_`).
    Named(&'a str),
    /// A fresh variable: prints as `_G<n>`.
    Numbered(u64),
}

/// One level of a term, as seen by the printer.
#[derive(Clone, Copy, Debug)]
pub enum View<'a, R> {
    Var(VarLabel<'a>),
    Atom(Atom),
    Int(i64),
    BigInt(&'a str),
    Float(f64),
    Str(&'a str),
    BackQuoted(&'a str),
    Compound(Atom, &'a [R]),
}

/// Anything whose terms can be looked at one level at a time.
pub trait TermSource {
    type Ref: Copy;
    /// The (dereferenced) view of `term`.
    fn view(&self, term: Self::Ref) -> View<'_, Self::Ref>;
}

impl TermSource for Clause {
    type Ref = TermId;
    fn view(&self, term: TermId) -> View<'_, TermId> {
        match self.terms.node(term) {
            Node::Var(v) => View::Var(VarLabel::Named(self.var_name(*v))),
            Node::Atom(a) => View::Atom(*a),
            Node::Int(i) => View::Int(*i),
            Node::BigInt(s) => View::BigInt(s),
            Node::Float(f) => View::Float(*f),
            Node::Str(s) => View::Str(s),
            Node::BackQuoted(s) => View::BackQuoted(s),
            Node::Compound { functor, .. } => View::Compound(*functor, self.terms.args(term)),
        }
    }
}

/// Options of the writer.
#[derive(Clone, Copy, Debug)]
pub struct WriteOptions<'o> {
    /// Quote atoms and strings where needed to read them back (`writeq`).
    pub quoted: bool,
    /// Operators to write in operator form; `None` writes canonical form.
    pub ops: Option<&'o OpTable>,
}

impl WriteOptions<'static> {
    /// `writeq/1` with SitLog's operators.
    pub fn writeq() -> WriteOptions<'static> {
        WriteOptions {
            quoted: true,
            ops: Some(OpTable::sitlog_shared()),
        }
    }
    /// `print/1`/`write/1` style: operators, no quotes.
    pub fn write() -> WriteOptions<'static> {
        WriteOptions {
            quoted: false,
            ops: Some(OpTable::sitlog_shared()),
        }
    }
}

/// Writes `term` of `source` as `writeq` would.
pub fn writeq<S: TermSource>(source: &S, term: S::Ref) -> String {
    write_term(source, term, WriteOptions::writeq())
}

/// Writes `term` of `source` with `options`.
pub fn write_term<S: TermSource>(source: &S, term: S::Ref, options: WriteOptions<'_>) -> String {
    let mut w = Writer {
        out: String::new(),
        options,
    };
    w.term(source, term, 1200);
    w.out
}

/// Appends `atom` as `writeq` would write it standing alone.
pub fn write_atom(out: &mut String, atom: Atom, quoted: bool) {
    let text = atom.as_str();
    if quoted && atom_needs_quotes(text) {
        quote_into(out, text, '\'');
    } else {
        out.push_str(text);
    }
}

/// Whether an atom's text must be quoted to read back as the same atom.
pub fn atom_needs_quotes(text: &str) -> bool {
    if matches!(text, "[]" | "{}" | "!" | ";") {
        return false;
    }
    let mut chars = text.chars();
    let Some(first) = chars.next() else {
        return true;
    };
    if first.is_lowercase() {
        return !text.chars().all(is_alnum);
    }
    if is_symbol_char(first) {
        return text == "." || !text.chars().all(is_symbol_char);
    }
    true
}

/// Letters, digits and `_`: the characters of names and variables.
pub fn is_alnum(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// Characters of symbolic atoms such as `==>` and `\+`.
pub fn is_symbol_char(c: char) -> bool {
    matches!(
        c,
        '#' | '$'
            | '&'
            | '*'
            | '+'
            | '-'
            | '.'
            | '/'
            | ':'
            | '<'
            | '='
            | '>'
            | '?'
            | '@'
            | '^'
            | '~'
            | '\\'
    )
}

fn quote_into(out: &mut String, text: &str, quote: char) {
    out.push(quote);
    for c in text.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            '\u{7}' => out.push_str("\\a"),
            '\u{8}' => out.push_str("\\b"),
            '\u{b}' => out.push_str("\\v"),
            '\u{c}' => out.push_str("\\f"),
            '\0' => out.push_str("\\0\\"),
            c if c == quote => {
                out.push('\\');
                out.push(c);
            }
            c if (c as u32) < 0x20 || c as u32 == 0x7f => {
                let _ = write!(out, "\\x{:x}\\", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push(quote);
}

/// Formats a float the way SWI-Prolog prints it: shortest text that reads
/// back to the same value, always with a `.` or an exponent.
pub fn format_float(f: f64) -> String {
    if f.is_nan() {
        return "1.5NaN".to_owned();
    }
    if f.is_infinite() {
        return if f > 0.0 { "1.0Inf" } else { "-1.0Inf" }.to_owned();
    }
    let sci = format!("{f:e}"); // shortest round-trip digits, e.g. "1.2345e3", "-5e-7"
    let (mantissa, exp) = sci.split_once('e').expect("{:e} has an exponent");
    let exp: i32 = exp.parse().expect("{:e} exponent is an integer");
    if (-4..15).contains(&exp) {
        let mut s = format!("{f}");
        if !s.contains('.') {
            s.push_str(".0");
        }
        s
    } else {
        let mantissa = if mantissa.contains('.') {
            mantissa.to_owned()
        } else {
            format!("{mantissa}.0")
        };
        format!("{mantissa}e{exp}")
    }
}

struct Writer<'o> {
    out: String,
    options: WriteOptions<'o>,
}

impl Writer<'_> {
    /// Appends a token, inserting a space where it would otherwise glue to
    /// the previous one (two symbol-char runs or two alphanumeric runs).
    fn token(&mut self, text: &str) {
        if let (Some(prev), Some(next)) = (self.out.chars().next_back(), text.chars().next()) {
            let glue = (is_symbol_char(prev) && is_symbol_char(next))
                || (is_alnum(prev) && is_alnum(next));
            if glue {
                self.out.push(' ');
            }
        }
        self.out.push_str(text);
    }

    fn atom_token(&mut self, atom: Atom) {
        let mut s = String::new();
        write_atom(&mut s, atom, self.options.quoted);
        self.token(&s);
    }

    fn is_op(&self, atom: Atom) -> bool {
        self.options.ops.is_some_and(|ops| ops.is_op(atom))
    }

    fn term<S: TermSource>(&mut self, src: &S, t: S::Ref, max: u16) {
        stacker::maybe_grow(64 * 1024, 1024 * 1024, || self.term_inner(src, t, max));
    }

    /// Writes `t` as an operand of an operator: operator atoms get parentheses.
    fn operand<S: TermSource>(&mut self, src: &S, t: S::Ref, max: u16) {
        if let View::Atom(a) = src.view(t) {
            if self.is_op(a) && a != atoms::NIL && a != atoms::CURLY {
                self.token("(");
                self.atom_token(a);
                self.out.push(')');
                return;
            }
        }
        self.term(src, t, max);
    }

    fn term_inner<S: TermSource>(&mut self, src: &S, t: S::Ref, max: u16) {
        match src.view(t) {
            View::Var(VarLabel::Named(name)) => self.token(name),
            View::Var(VarLabel::Numbered(n)) => self.token(&format!("_G{n}")),
            View::Atom(a) => {
                let prio = self.options.ops.map_or(0, |ops| ops.max_priority(a));
                if prio > max {
                    self.token("(");
                    self.atom_token(a);
                    self.out.push(')');
                } else {
                    self.atom_token(a);
                }
            }
            View::Int(i) => self.token(&i.to_string()),
            View::BigInt(s) => self.token(s),
            View::Float(f) => self.token(&format_float(f)),
            View::Str(s) => {
                let mut q = String::new();
                if self.options.quoted {
                    quote_into(&mut q, s, '"');
                } else {
                    q.push_str(s);
                }
                self.token(&q);
            }
            View::BackQuoted(s) => {
                let mut q = String::new();
                quote_into(&mut q, s, '`');
                self.token(&q);
            }
            View::Compound(f, args) => self.compound(src, f, args, max),
        }
    }

    fn compound<S: TermSource>(&mut self, src: &S, f: Atom, args: &[S::Ref], max: u16) {
        if f == atoms::DOT && args.len() == 2 {
            return self.list(src, args);
        }
        if f == atoms::CURLY && args.len() == 1 {
            self.token("{");
            self.term(src, args[0], 1200);
            self.out.push('}');
            return;
        }
        if let Some(ops) = self.options.ops {
            // SWI writes the bar term canonically: `'|'(a,b)`.
            if args.len() == 2 && f != atoms::BAR {
                if let Some(def) = ops.infix(f) {
                    let (lmax, rmax) = def.arg_max();
                    let open = def.priority > max;
                    if open {
                        self.token("(");
                    }
                    self.operand(src, args[0], lmax.unwrap_or(999));
                    if f == atoms::COMMA {
                        self.out.push(',');
                    } else if f.as_str().chars().all(is_alnum) {
                        self.out.push(' ');
                        self.atom_token(f);
                        self.out.push(' ');
                    } else {
                        self.atom_token(f);
                    }
                    self.operand(src, args[1], rmax.unwrap_or(999));
                    if open {
                        self.out.push(')');
                    }
                    return;
                }
            }
            if args.len() == 1 {
                if let Some(def) = ops.prefix(f) {
                    let arg_is_number = matches!(
                        src.view(args[0]),
                        View::Int(_) | View::BigInt(_) | View::Float(_)
                    );
                    if !((f == atoms::MINUS || f == atoms::PLUS) && arg_is_number) {
                        let (_, rmax) = def.arg_max();
                        let open = def.priority > max;
                        if open {
                            self.token("(");
                        }
                        self.atom_token(f);
                        if f.as_str().chars().all(is_alnum) {
                            self.out.push(' ');
                        }
                        // An operand starting with `(` would read as functional notation.
                        let before = self.out.len();
                        self.operand(src, args[0], rmax.unwrap_or(999));
                        if self.out[before..].starts_with('(') {
                            self.out.insert(before, ' ');
                        }
                        if open {
                            self.out.push(')');
                        }
                        return;
                    }
                }
                if let Some(def) = ops.postfix(f) {
                    let (lmax, _) = def.arg_max();
                    let open = def.priority > max;
                    if open {
                        self.token("(");
                    }
                    self.operand(src, args[0], lmax.unwrap_or(999));
                    self.atom_token(f);
                    if open {
                        self.out.push(')');
                    }
                    return;
                }
            }
        }
        self.atom_token(f);
        self.out.push('(');
        for (i, &a) in args.iter().enumerate() {
            if i > 0 {
                self.out.push(',');
            }
            self.term(src, a, 999);
        }
        self.out.push(')');
    }

    fn list<S: TermSource>(&mut self, src: &S, cell: &[S::Ref]) {
        self.token("[");
        self.term(src, cell[0], 999);
        let mut tail = cell[1];
        loop {
            match src.view(tail) {
                View::Compound(f, args) if f == atoms::DOT && args.len() == 2 => {
                    self.out.push(',');
                    self.term(src, args[0], 999);
                    tail = args[1];
                }
                View::Atom(a) if a == atoms::NIL => break,
                _ => {
                    self.out.push('|');
                    self.term(src, tail, 999);
                    break;
                }
            }
        }
        self.out.push(']');
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoting() {
        assert!(!atom_needs_quotes("abc_1"));
        assert!(atom_needs_quotes("Abc"));
        assert!(atom_needs_quotes("hello world"));
        assert!(!atom_needs_quotes("==>"));
        assert!(atom_needs_quotes("."));
        assert!(!atom_needs_quotes("[]"));
        assert!(atom_needs_quotes(""));
        assert!(atom_needs_quotes(","));
        assert!(atom_needs_quotes("|"));
    }

    #[test]
    fn floats() {
        assert_eq!(format_float(1.0), "1.0");
        assert_eq!(format_float(0.22999999999999998), "0.22999999999999998");
        assert_eq!(format_float(-30.0), "-30.0");
        assert_eq!(format_float(1e22), "1.0e22");
        assert_eq!(format_float(1.5e-7), "1.5e-7");
    }
}
