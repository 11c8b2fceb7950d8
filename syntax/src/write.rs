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
    w.term(source, term, 1200, false);
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
    if starts_letter_name(first) {
        return !text.chars().all(is_alnum);
    }
    if is_symbol_char(first) {
        // `/*` would start a comment.
        return text == "." || text.starts_with("/*") || !text.chars().all(is_symbol_char);
    }
    true
}

/// Letters, digits, marks and `_`: the characters of names and variables
/// after their first (`alnum` in `token.pest`). Beyond ASCII the grammar's
/// own Unicode tables (pest's) decide, not `char`'s methods, whose Unicode
/// version may differ: what is written unquoted must read back.
pub fn is_alnum(c: char) -> bool {
    if c.is_ascii() {
        return c.is_ascii_alphanumeric() || c == '_';
    }
    use pest::unicode::{ALPHABETIC, MARK, NUMBER};
    ALPHABETIC(c) || NUMBER(c) || MARK(c)
}

/// Whether `c` starts a name written without quotes (`letter_name` in
/// `token.pest`): a letter that is not upper or title case nor a number
/// (`ⅰ`, a letter number, starts no name; `中` and `ª` do).
pub fn starts_letter_name(c: char) -> bool {
    if c.is_ascii() {
        return c.is_ascii_lowercase();
    }
    use pest::unicode::{ALPHABETIC, NUMBER, TITLECASE_LETTER, UPPERCASE_LETTER};
    ALPHABETIC(c) && !UPPERCASE_LETTER(c) && !TITLECASE_LETTER(c) && !NUMBER(c)
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
            c if c == quote => {
                out.push('\\');
                out.push(c);
            }
            c if needs_escape(c) => {
                let _ = if (c as u32) <= 0xFFFF {
                    write!(out, "\\u{:04X}", c as u32)
                } else {
                    write!(out, "\\U{:08X}", c as u32)
                };
            }
            c => out.push(c),
        }
    }
    out.push(quote);
}

/// Characters SWI-Prolog 9 writes as `\uXXXX` inside quotes: controls and
/// invisible (separator and format) characters other than the plain space.
fn needs_escape(c: char) -> bool {
    let u = c as u32;
    c.is_control()
        || (c.is_whitespace() && c != ' ')
        || matches!(
            u,
            0xAD | 0x600..=0x605
                | 0x61C
                | 0x6DD
                | 0x70F
                | 0x180E
                | 0x200B..=0x200F
                | 0x202A..=0x202E
                | 0x2060..=0x2064
                | 0x2066..=0x206F
                | 0xFEFF
                | 0xFFF9..=0xFFFB
                | 0xE000..=0xF8FF
                | 0xF0000..=0x10FFFF
        )
}

/// Formats a float the way SWI-Prolog 9 prints it: the shortest text that
/// reads back to the same value, always with a `.`; exponent form (`1.0e+22`,
/// `1.0e-5`) outside `1.0e-4 <= |f| < 1.0e15`.
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
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{mantissa}e{sign}{}", exp.unsigned_abs())
    }
}

/// How one term is written in a given context.
#[derive(Clone, Copy)]
enum Form {
    /// An operator atom in operand position: `(op)`.
    ParenAtom,
    Plain,
    List,
    Curly,
    Infix {
        priority: u16,
        lmax: u16,
        rmax: u16,
    },
    Prefix {
        priority: u16,
        rmax: u16,
    },
    Postfix {
        priority: u16,
        lmax: u16,
    },
    Canonical,
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
            if glues(prev, next) {
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

    /// How `t` is written with maximum priority `max`; `arg`: as an argument
    /// of a canonical compound or a list element (operator atoms stay bare).
    fn form<S: TermSource>(&self, view: &View<'_, S::Ref>, max: u16, arg: bool) -> Form {
        match *view {
            View::Atom(a) => {
                if !arg && max < 1200 && self.is_op(a) {
                    Form::ParenAtom
                } else {
                    Form::Plain
                }
            }
            View::Compound(f, args) => {
                if f == atoms::DOT && args.len() == 2 {
                    return Form::List;
                }
                if f == atoms::CURLY && args.len() == 1 {
                    return Form::Curly;
                }
                let Some(ops) = self.options.ops else {
                    return Form::Canonical;
                };
                if args.len() == 2 {
                    if let Some(def) = ops.infix(f) {
                        let (l, r) = def.arg_max();
                        return Form::Infix {
                            priority: def.priority,
                            lmax: l.unwrap_or(999),
                            rmax: r.unwrap_or(999),
                        };
                    }
                }
                if args.len() == 1 {
                    if let Some(def) = ops.prefix(f) {
                        return Form::Prefix {
                            priority: def.priority,
                            rmax: def.arg_max().1.unwrap_or(999),
                        };
                    }
                    if let Some(def) = ops.postfix(f) {
                        return Form::Postfix {
                            priority: def.priority,
                            lmax: def.arg_max().0.unwrap_or(999),
                        };
                    }
                }
                Form::Canonical
            }
            _ => Form::Plain,
        }
    }

    /// The first character `term` writes as at (`max`, `arg`), without writing
    /// it. Walks down the left spine of operator terms, iteratively.
    fn first_char<S: TermSource>(
        &self,
        src: &S,
        mut t: S::Ref,
        mut max: u16,
        mut arg: bool,
    ) -> char {
        loop {
            let view = src.view(t);
            match self.form::<S>(&view, max, arg) {
                Form::ParenAtom => return '(',
                Form::List => return '[',
                Form::Curly => return '{',
                Form::Infix { priority, lmax, .. } | Form::Postfix { priority, lmax } => {
                    if priority > max {
                        return '(';
                    }
                    if let View::Compound(_, args) = view {
                        t = args[0];
                        max = lmax;
                        arg = false;
                        continue;
                    }
                }
                Form::Prefix { priority, .. } => {
                    if priority > max {
                        return '(';
                    }
                }
                Form::Plain | Form::Canonical => {}
            }
            return match view {
                View::Var(VarLabel::Named(name)) => name.chars().next().unwrap_or('_'),
                View::Var(VarLabel::Numbered(_)) => '_',
                View::Int(i) => {
                    if i < 0 {
                        '-'
                    } else {
                        '0'
                    }
                }
                View::BigInt(s) => s.chars().next().unwrap_or('0'),
                View::Float(f) => {
                    if f.is_sign_negative() && !f.is_nan() {
                        '-'
                    } else {
                        '0'
                    }
                }
                View::Str(_) => {
                    if self.options.quoted {
                        '"'
                    } else {
                        'a'
                    }
                }
                View::BackQuoted(_) => '`',
                View::Atom(a) | View::Compound(a, _) => {
                    let text = a.as_str();
                    if self.options.quoted && atom_needs_quotes(text) {
                        '\''
                    } else {
                        text.chars().next().unwrap_or('a')
                    }
                }
            };
        }
    }

    fn term<S: TermSource>(&mut self, src: &S, t: S::Ref, max: u16, arg: bool) {
        stacker::maybe_grow(64 * 1024, 1024 * 1024, || self.term_inner(src, t, max, arg));
    }

    fn term_inner<S: TermSource>(&mut self, src: &S, t: S::Ref, max: u16, arg: bool) {
        let view = src.view(t);
        match view {
            View::Var(VarLabel::Named(name)) => self.token(name),
            View::Var(VarLabel::Numbered(n)) => self.token(&format!("_G{n}")),
            View::Atom(a) => {
                if let Form::ParenAtom = self.form::<S>(&view, max, arg) {
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
            View::Compound(f, args) => self.compound(src, &view, f, args, max, arg),
        }
    }

    fn compound<S: TermSource>(
        &mut self,
        src: &S,
        view: &View<'_, S::Ref>,
        f: Atom,
        args: &[S::Ref],
        max: u16,
        arg: bool,
    ) {
        match self.form::<S>(view, max, arg) {
            Form::List => self.list(src, args),
            Form::Curly => {
                self.token("{");
                self.term(src, args[0], 1200, false);
                self.out.push('}');
            }
            Form::Infix {
                priority,
                lmax,
                rmax,
            } => {
                let open = priority > max;
                if open {
                    self.token("(");
                }
                self.term(src, args[0], lmax, false);
                if f == atoms::COMMA {
                    self.out.push(',');
                } else if f == atoms::BAR {
                    self.out.push('|');
                } else if f.as_str().chars().all(is_alnum) {
                    self.out.push(' ');
                    self.atom_token(f);
                    self.out.push(' ');
                } else {
                    self.atom_token(f);
                }
                self.term(src, args[1], rmax, false);
                if open {
                    self.out.push(')');
                }
            }
            Form::Prefix { priority, rmax } => {
                let open = priority > max;
                if open {
                    self.token("(");
                }
                self.atom_token(f);
                let next = self.first_char(src, args[0], rmax, false);
                // `- 1` is -(1), `-1` the integer; `-(a)` would be functional
                // notation and SWI reads `-{a}` as a dict.
                if f.as_str().chars().all(is_alnum)
                    || matches!(next, '(' | '{')
                    || (f == atoms::MINUS && next.is_ascii_digit())
                {
                    self.out.push(' ');
                }
                self.term(src, args[0], rmax, false);
                if open {
                    self.out.push(')');
                }
            }
            Form::Postfix { priority, lmax } => {
                let open = priority > max;
                if open {
                    self.token("(");
                }
                self.term(src, args[0], lmax, false);
                self.atom_token(f);
                if open {
                    self.out.push(')');
                }
            }
            Form::ParenAtom | Form::Plain | Form::Canonical => {
                self.atom_token(f);
                self.out.push('(');
                for (i, &a) in args.iter().enumerate() {
                    if i > 0 {
                        self.out.push(',');
                    }
                    self.term(src, a, 999, true);
                }
                self.out.push(')');
            }
        }
    }

    fn list<S: TermSource>(&mut self, src: &S, cell: &[S::Ref]) {
        self.token("[");
        self.term(src, cell[0], 999, true);
        let mut tail = cell[1];
        loop {
            match src.view(tail) {
                View::Compound(f, args) if f == atoms::DOT && args.len() == 2 => {
                    self.out.push(',');
                    self.term(src, args[0], 999, true);
                    tail = args[1];
                }
                View::Atom(a) if a == atoms::NIL => break,
                _ => {
                    self.out.push('|');
                    self.term(src, tail, 999, true);
                    break;
                }
            }
        }
        self.out.push(']');
    }
}

/// Whether two characters written next to each other would read as one token.
fn glues(prev: char, next: char) -> bool {
    (is_symbol_char(prev) && is_symbol_char(next)) || (is_alnum(prev) && is_alnum(next))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoting() {
        assert!(!atom_needs_quotes("abc_1"));
        // The grammar's letters (pest's Unicode tables), not `char`'s.
        assert!(!atom_needs_quotes("中文"));
        assert!(!atom_needs_quotes("na\u{308}me"));
        assert!(atom_needs_quotes("\u{2170}"));
        assert!(atom_needs_quotes("\u{1c5}a"));
        assert!(atom_needs_quotes("Abc"));
        assert!(atom_needs_quotes("hello world"));
        assert!(!atom_needs_quotes("==>"));
        assert!(atom_needs_quotes("."));
        assert!(!atom_needs_quotes("[]"));
        assert!(atom_needs_quotes(""));
        assert!(atom_needs_quotes(","));
        assert!(atom_needs_quotes("|"));
        assert!(atom_needs_quotes("/*"));
        assert!(!atom_needs_quotes("+/*"));
    }

    #[test]
    fn floats() {
        assert_eq!(format_float(1.0), "1.0");
        assert_eq!(format_float(0.22999999999999998), "0.22999999999999998");
        assert_eq!(format_float(-30.0), "-30.0");
        assert_eq!(format_float(1e22), "1.0e+22");
        assert_eq!(format_float(1.5e-7), "1.5e-7");
        assert_eq!(format_float(1e15), "1.0e+15");
        assert_eq!(format_float(1e14), "100000000000000.0");
        assert_eq!(format_float(1e-4), "0.0001");
        assert_eq!(format_float(1.5e300), "1.5e+300");
    }
}
