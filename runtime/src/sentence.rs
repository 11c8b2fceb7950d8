//! The text of a message (`say(M)`, `screen(M)`, `msg_format/2`) written
//! into a caller's buffer (issue 37: a `say` at every step of a walk).
//!
//! What it owns: the one writer of the original's sentence rule
//! ([`crate::builtins::sentence`] documents it: the items separated by a
//! space, `pause` a full stop, a final `.` from three items on) and of
//! `write/1`'s text of a message that is not a list.
//!
//! Invariant: the text appended is byte for byte what `Store::write` of
//! each item, joined by the rule, gives. An atom is appended as its name
//! and a small integer as its digits with no writer in between (what
//! `write/1` gives them standing alone: it quotes nothing and an atom
//! standing alone is never put in parentheses); anything else (floats,
//! big integers, variables, compounds, lists) goes through the term
//! writer. No allocation for a message of atoms and integers but the
//! caller's buffer growing.
//!
//! The same text is written from a pattern and its holes without the term
//! filled ([`Holed`]: native code's `Fill`, an effector that only writes
//! text, `Actions::perform_filled`): a hole read where the term filled has
//! its value, so the text is the filled term's, byte for byte.
//!
//! Cost (issue 37, `r22_d_sweep_say`): a list cell's header is read once
//! for its name, arguments and mark (`Holed::cons`); an argument is
//! looked at as a hole only where its compound is marked (a pattern's
//! constant part holds none); an item is written as it was seen, not
//! resolved again; an atom's text is a read of the interner's published
//! table (`Atom::as_str`); an integer's digits are made in place.

use crate::term::{Repr, Term};
use crate::Store;
use sitlog_syntax::write::{write_term, TermSource, View, WriteOptions};
use sitlog_syntax::{atoms, Atom};

/// `pause`, interned once: the item the rule writes as a full stop.
pub(crate) fn pause_atom() -> Atom {
    static PAUSE: std::sync::OnceLock<Atom> = std::sync::OnceLock::new();
    *PAUSE.get_or_init(|| Atom::intern("pause"))
}

/// The terms of `store` as text sees them, a pattern's holes filled: a
/// program's constant with `'$hole'(i)` where value `holes[i]` goes
/// (`Cx::fill`'s pattern) read as the term filled, without building it
/// (an effector that only writes text, `Actions::perform_filled`). Every
/// hole must be atomic (an atom or a number: [`atomic`]), so that what is
/// seen through a hole holds no `'$hole'(_)` of its own; with no holes,
/// the store's terms as they are.
#[derive(Clone, Copy)]
pub struct Holed<'s> {
    store: &'s Store,
    holes: &'s [Term],
}

impl<'s> Holed<'s> {
    /// The store's terms as they are.
    pub fn plain(store: &'s Store) -> Self {
        Holed { store, holes: &[] }
    }

    /// Patterns of `store` with `holes` (each [`atomic`]), the patterns
    /// marked as a program's constants are (`machine::cx::mark_pattern`:
    /// a hole is seen where the mark says one is below).
    pub fn new(store: &'s Store, holes: &'s [Term]) -> Self {
        debug_assert!(holes.iter().all(|&h| atomic(store, h)));
        Holed { store, holes }
    }

    /// `t` dereferenced, a hole its value.
    #[inline]
    pub fn resolve(&self, t: Term) -> Term {
        let t = self.store.deref(t);
        if self.holes.is_empty() {
            return t;
        }
        self.hole_or(t)
    }

    /// `t` (dereferenced) an argument of a compound whose header said
    /// whether it is marked (`holed`), as seen: where the compound is not
    /// marked, nothing below it is a hole.
    #[inline(always)]
    fn see(&self, t: Term, holed: bool) -> Term {
        let t = self.store.deref(t);
        if holed && !self.holes.is_empty() {
            self.hole_or(t)
        } else {
            t
        }
    }

    /// `t` (dereferenced) its hole's value where it is a hole.
    #[inline]
    fn hole_or(&self, t: Term) -> Term {
        // A marked compound of one integer argument has no hole below it
        // but itself: it is `'$hole'(i)` (the mark is put on holes and the
        // compounds above them only).
        if let Some((_, [i])) = self.store.holed_parts(t) {
            let i = self.store.int_of(*i).and_then(|i| usize::try_from(i).ok());
            if let Some(&h) = i.and_then(|i| self.holes.get(i)) {
                return self.store.deref(h);
            }
        }
        t
    }

    /// The name and arguments of `t` (seen: dereferenced, a hole its
    /// value) where it is a compound, each argument seen: one read of its
    /// header.
    #[inline]
    pub fn parts(&self, t: Term) -> Option<(Atom, Parts<'_, 's>)> {
        let (name, args, holed) = self.store.parts_flagged(t)?;
        Some((
            name,
            Parts {
                src: self,
                args,
                holed,
            },
        ))
    }

    /// The head and tail of list cell `t` (seen), each seen.
    #[inline(always)]
    fn cons(&self, t: Term) -> Option<(Term, Term)> {
        match self.store.parts_flagged(t)? {
            (atoms::DOT, &[head, tail], holed) => {
                Some((self.see(head, holed), self.see(tail, holed)))
            }
            _ => None,
        }
    }

    /// The store.
    pub fn store(&self) -> &'s Store {
        self.store
    }
}

/// The arguments of a compound as a [`Holed`] sees them ([`Holed::parts`]).
#[derive(Clone, Copy)]
pub struct Parts<'a, 's> {
    src: &'a Holed<'s>,
    args: &'s [Term],
    holed: bool,
}

impl Parts<'_, '_> {
    /// Argument `i` (0-based), seen.
    #[inline]
    pub fn get(&self, i: usize) -> Option<Term> {
        self.args.get(i).map(|&t| self.src.see(t, self.holed))
    }

    /// How many arguments.
    #[inline]
    pub fn len(&self) -> usize {
        self.args.len()
    }

    /// Whether there are none.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.args.is_empty()
    }
}

impl TermSource for Holed<'_> {
    type Ref = Term;
    fn view(&self, t: Term) -> View<'_, Term> {
        self.store.view(self.resolve(t))
    }
}

/// Whether `t` is an atom or a number (dereferenced): a value that holds
/// no other term.
#[inline]
pub fn atomic(store: &Store, t: Term) -> bool {
    matches!(
        store.deref(t).0,
        Repr::Atom(_) | Repr::Int(_) | Repr::Float(_) | Repr::Big(_)
    )
}

/// Appends `t` as `write/1` writes it (`Store::write`).
#[inline]
pub fn write_into(store: &Store, t: Term, out: &mut String) {
    write_in(&Holed::plain(store), t, out);
}

/// [`write_into`] through `src`.
#[inline]
pub fn write_in(src: &Holed<'_>, t: Term, out: &mut String) {
    write_seen(src, src.resolve(t), out);
}

/// [`write_in`] of `t` seen already (dereferenced, a hole its value).
#[inline(always)]
pub fn write_seen(src: &Holed<'_>, t: Term, out: &mut String) {
    match t.0 {
        Repr::Atom(a) => out.push_str(a.as_str()),
        Repr::Int(i) => push_int(i, out),
        _ => write_other(src, t, out),
    }
}

/// [`write_seen`] of a term neither an atom nor a small integer: the term
/// writer's text.
#[inline(never)]
fn write_other(src: &Holed<'_>, t: Term, out: &mut String) {
    out.push_str(&write_term(src, t, WriteOptions::write()));
}

/// Appends the decimal digits of `i` (`write/1`'s text of a small
/// integer), no formatter.
#[inline(never)]
fn push_int(i: i64, out: &mut String) {
    let mut digits = [0u8; 20];
    let mut at = digits.len();
    let mut n = i.unsigned_abs();
    loop {
        at -= 1;
        digits[at] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    if i < 0 {
        out.push('-');
    }
    // ASCII digits: always text.
    out.push_str(std::str::from_utf8(&digits[at..]).unwrap_or_default());
}

/// Appends the sentence of `items` (the rule of [`crate::builtins::sentence`]).
pub fn sentence_into(store: &Store, items: &[Term], out: &mut String) {
    let src = Holed::plain(store);
    let mut items = items.iter().map(|&t| store.deref(t));
    match items.next() {
        Some(first) => sentence_of(&src, first, items, out),
        None => out.push_str("[]"),
    }
}

/// Appends the text of message `m`: a proper list with an item or more
/// as one sentence, anything else as `write/1` writes it (test mode's
/// `say(M)`, the robots' `say`, `screen` and `message`).
pub fn message_into(store: &Store, m: Term, out: &mut String) {
    message_in(&Holed::plain(store), m, out);
}

/// [`message_into`] through `src`: one pass over the list, what was
/// written of it taken back where it turns out not to be a proper list.
pub fn message_in(src: &Holed<'_>, m: Term, out: &mut String) {
    message_seen(src, src.resolve(m), out);
}

/// [`message_in`] of `m` seen already (dereferenced, a hole its value).
pub fn message_seen(src: &Holed<'_>, m: Term, out: &mut String) {
    let start = out.len();
    let mut items = Items { src, cur: m };
    let proper = match items.next() {
        None => false,
        Some(first) => {
            sentence_of(src, first, &mut items, out);
            items.cur == Term::NIL
        }
    };
    if !proper {
        out.truncate(start);
        write_seen(src, m, out);
    }
}

/// The text of message `m` ([`message_into`]).
pub fn message(store: &Store, m: Term) -> String {
    let mut out = String::new();
    message_into(store, m, &mut out);
    out
}

/// The items of a list seen through a [`Holed`], resolved; `cur`, the
/// rest (at the end, the tail).
struct Items<'a, 's> {
    src: &'a Holed<'s>,
    cur: Term,
}

impl Iterator for Items<'_, '_> {
    type Item = Term;
    #[inline(always)]
    fn next(&mut self) -> Option<Term> {
        let (head, tail) = self.src.cons(self.cur)?;
        self.cur = tail;
        Some(head)
    }
}

/// The rule on `first` and the items `items` yields (each resolved).
fn sentence_of(src: &Holed<'_>, first: Term, items: impl Iterator<Item = Term>, out: &mut String) {
    let pause = Term::atom(pause_atom());
    rule(
        first,
        items,
        |t| t == pause,
        |t, out: &mut String| write_seen(src, t, out),
        out,
    );
}

/// What the rule appends to: text, and (through `write`) the items.
pub(crate) trait Said {
    /// Appends `text`.
    fn text(&mut self, text: &str);
}

impl Said for String {
    #[inline]
    fn text(&mut self, text: &str) {
        self.push_str(text);
    }
}

/// The original's sentence rule ([`crate::builtins::sentence`]) on
/// `first` and the items `items` yields, of any kind: `is_pause` tells
/// the item written as a full stop, `write` appends one item (test
/// mode's plan of a pattern's line, `testmode::said`, writes a hole as a
/// place to fill).
#[inline]
pub(crate) fn rule<X: Copy, O: Said>(
    first: X,
    mut items: impl Iterator<Item = X>,
    is_pause: impl Fn(X) -> bool,
    mut write: impl FnMut(X, &mut O),
    out: &mut O,
) {
    let (a, b) = match items.next() {
        None => {
            write(first, out);
            return;
        }
        Some(b) => (first, b),
    };
    if is_pause(a) {
        out.text(". ");
        write(b, out);
    } else if is_pause(b) {
        write(a, out);
        out.text(" .");
    } else {
        write(a, out);
        out.text(" ");
        write(b, out);
    }
    let mut more = false;
    for x in items {
        more = true;
        if is_pause(x) {
            out.text(". ");
        } else {
            out.text(" ");
            write(x, out);
        }
    }
    if more {
        out.text(".");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rule as it was written before this module (each item by
    /// `Store::write`, joined with `format!`): what the writer must give.
    fn reference(store: &Store, items: &[Term]) -> String {
        let is_pause = |t: Term| store.atom_of(store.deref(t)).map(|a| a.as_str()) == Some("pause");
        let text = |t: Term| store.write(t);
        match items {
            [] => "[]".to_owned(),
            [one] => text(*one),
            [a, b, rest @ ..] => {
                let mut out = if is_pause(*a) {
                    format!(". {}", text(*b))
                } else if is_pause(*b) {
                    format!("{} .", text(*a))
                } else {
                    format!("{} {}", text(*a), text(*b))
                };
                if rest.is_empty() {
                    return out;
                }
                for &x in rest {
                    if is_pause(x) {
                        out.push_str(". ");
                    } else {
                        out.push(' ');
                        out.push_str(&text(x));
                    }
                }
                out.push('.');
                out
            }
        }
    }

    /// The message's text by the old way (`list_to_vec`, then the rule or
    /// `Store::write`).
    fn reference_message(store: &Store, m: Term) -> String {
        match store.list_to_vec(m).filter(|items| !items.is_empty()) {
            Some(items) => reference(store, &items),
            None => store.write(m),
        }
    }

    const MESSAGES: &[&str] = &[
        "[checking, p3]",
        "[checking]",
        "[]",
        "hello",
        "'Hello there'",
        "['Hello', 'Bob', pause, welcome]",
        "[pause, a]",
        "[a, pause]",
        "[pause, pause]",
        "[a, b, pause, c, pause]",
        "[a, b, c]",
        "['it''s', 'a\\nb', '', [], '[]', '{}', ',', '|', ';', '!', '.']",
        "[-, +, '==>', '-->', (:-), (dynamic), mod, is, (\\+)]",
        "[0, 1, -7, 123456789012, 99999999999999999999999, -99999999999999999999999]",
        "[1.0, -0.5, 1.0e22, 1.5e-7, 3.14159, 100000000000000.0]",
        "[[a, b], [the, 'living room'], [x|y], [1, [2, [3]]]]",
        "[f(x), f('A b', [c]), - 1, -(1), -(-(1)), a-b, 1+2*3, (a:-b, c), {x}, '$hole'(0)]",
        "[\"a string\", \"\", \"it's\"]",
        "[X, Y, _, X]",
        "[a|T]",
        "[a, b|c]",
        "f(X)",
        "'€uro', 中文, 'Ab'",
        "['€uro', 中文, 'Ab', 'hello world']",
        "7",
        "-2.5",
        "[pause]",
        "[say(hi), [pause], 'pause']",
    ];

    #[test]
    fn messages_are_written_as_before() {
        for text in MESSAGES {
            let mut store = Store::new();
            let (m, _) = store.parse(text).expect(text);
            let mut out = String::from(">");
            message_into(&store, m, &mut out);
            assert_eq!(out[1..], reference_message(&store, m), "{text}");
            assert_eq!(message(&store, m), reference_message(&store, m), "{text}");
            if let Some(items) = store.list_to_vec(m) {
                let mut out = String::new();
                sentence_into(&store, &items, &mut out);
                assert_eq!(out, reference(&store, &items), "{text}");
            }
        }
    }

    #[test]
    fn items_written_as_write_writes_them() {
        let mut store = Store::new();
        for text in MESSAGES {
            let (m, _) = store.parse(text).expect(text);
            for t in std::iter::once(m).chain(store.list_iter(m)) {
                let mut out = String::new();
                write_into(&store, t, &mut out);
                assert_eq!(out, store.write(t), "{text}");
            }
        }
        // Bound variables are followed.
        let v = store.new_var();
        store.bind(v, Term::atom(Atom::intern("Bound one")));
        let (l, _) = store.parse("[x, y]").unwrap();
        let items = [v, l, Term::int(-3), Term::float(0.1)];
        let mut out = String::new();
        sentence_into(&store, &items, &mut out);
        assert_eq!(out, "Bound one [x,y] -3 0.1.");
        assert_eq!(out, reference(&store, &items));
    }

    #[test]
    fn sentences_spelled_out() {
        let mut store = Store::new();
        let cases = [
            ("[checking, p3]", "checking p3"),
            ("[checking, 'Room 3', 4]", "checking Room 3 4."),
            ("['Hello', pause, 'Bob']", "Hello . Bob."),
            ("[pause, a]", ". a"),
            ("[a, pause]", "a ."),
            ("[x]", "x"),
            ("[[a,b]]", "[a,b]"),
            ("[a, 'b c'|d]", "[a,b c|d]"),
            ("'Don''t'", "Don't"),
        ];
        for (text, said) in cases {
            let (m, _) = store.parse(text).unwrap();
            assert_eq!(message(&store, m), said, "{text}");
        }
    }
}
