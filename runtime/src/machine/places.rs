//! Where a run-time error happened in the source: the one look-up both
//! back ends use (issue 39). The interpreter keeps the source and looks
//! among its spans; a compiled program keeps no source, only each DM's
//! *places* (its `PLACES`, a text its generator writes, given to its
//! [`SitTable`] by [`SitTable::with_places`] and read here only when an
//! error is reported: nothing per transition), and gets the same answer
//! from the same look-up ([`SitTable::error_location`]), so `sitlogc run`
//! and a compiled task name the same `file:line:col`. Compiled code's
//! errors of an `is` or of a conditional's condition blame what the
//! evaluator blames ([`Cx`]'s `is_error`, `condition_error`).
//!
//! The place of a [`RunError`] ([`blame`]): the situation's in_arg for the
//! in_arg's error; else the construct of L the evaluator blamed (the
//! error's [`crate::eval::Culprit`]: its functor and its first
//! argument's), looked up among those written in the situation ([`Written`]:
//! those of the attributes that are not arcs, then each arc's, each in
//! source order): first one of the failing arc with the same functor and
//! first argument, then one of that arc with the same functor, then the
//! first anywhere in the situation with the same functor and first argument
//! (an out_arg evaluated after an arc was taken); else the failing arc;
//! else the situation.
//!
//! The places text of a DM (`PLACES` in generated code), one entry per
//! situation in order, separated by `#`; an entry is items separated by
//! `,`, in the order [`blame`] looks at them: first the constructs of L of
//! the attributes that are not arcs, then each arc, `@L:C` (its line and
//! column), followed by the constructs of L written in it. A construct is
//! `F I@L:C`: its functor `F` (with `/N` unless its arity is 2), its first
//! argument's `I` (with `/M` unless an atom; absent, with its space, when
//! the first argument is neither an atom nor a compound: `F@L:C`), and its
//! line and column. `I` is quoted (`'...'`, `''` for a quote) unless it is
//! a lower-case letter followed by letters, digits and `_`. So
//! `is@11:65,@13:18,apply never/1@13:30,@14:18` is a situation with an `is`
//! in another attribute and two arcs, the first holding an `apply` of
//! `never/1`.

use super::outcome::RunError;
use super::program::{Cx, DmProgram};
use super::situation::SitTable;
use crate::eval::{Culprit, EvalError};
use crate::term::Term;
use sitlog_syntax::atoms;

impl<P: DmProgram> Cx<'_, '_, P> {
    /// Error `e` of the condition of a conditional `(C -> A ; otherwise ->
    /// B)` that compiled code evaluates (`Cx::condition`, ..): blaming what
    /// the evaluator blamed inside the condition, else the conditional, as
    /// the interpreter's evaluator does (it evaluates the whole
    /// conditional).
    #[cold]
    pub(super) fn condition_error(&self, e: EvalError, arc: Option<usize>) -> RunError {
        let culprit = e.culprit.unwrap_or(Culprit {
            name: atoms::SEMICOLON,
            arity: 2,
            inner: Some((atoms::IF_THEN, 2)),
        });
        self.blamed(e.message, Some(culprit), arc)
    }

    /// Error `e` of `v is expr` (`v` as written, `None` for a variable that
    /// occurs nowhere else), blaming `is/2` as the evaluator does.
    #[cold]
    pub(super) fn is_error(&self, e: EvalError, v: Option<Term>, arc: Option<usize>) -> RunError {
        let culprit = is_culprit(self.store_ref(), v);
        self.blamed(e.message, Some(culprit), arc)
    }

    /// A run-time error in this situation blaming `culprit`.
    fn blamed(&self, message: String, culprit: Option<Culprit>, arc: Option<usize>) -> RunError {
        let mut e = self.error(message, arc);
        if let Some(site) = e.site.as_mut() {
            site.culprit = culprit;
        }
        e
    }
}

/// What the evaluator blames for an error of `v is expr` (`v` as written,
/// `None` for a variable that occurs nowhere else).
pub(super) fn is_culprit(store: &crate::store::Store, v: Option<Term>) -> Culprit {
    Culprit {
        name: atoms::IS,
        arity: 2,
        inner: v.and_then(|t| store.functor(store.deref(t))),
    }
}

impl SitTable {
    /// `file:line:col` of what run-time error `error` names ([`blame`]),
    /// from the program's places ([`SitTable::with_places`]):
    /// what the interpreter names from the source. `None` without a site.
    pub fn error_location(&self, error: &RunError) -> Option<String> {
        let site = error.site.as_deref()?;
        let (file, text) = self.file_and_places(site.dm)?;
        let (at, in_arg_at) = self.positions(site.dm, site.situation)?;
        let places = sit_places(text, site.situation as usize).unwrap_or_default();
        let written = places.written.iter().map(Place::written);
        let (line, col) = match blame(error, written, places.arcs.len(), in_arg_at.is_some()) {
            Blame::InArg => in_arg_at.unwrap_or(at),
            Blame::Written(i) => places.written[i].at,
            Blame::Arc(a) => places.arcs[a],
            Blame::Situation => at,
        };
        Some(format!("{file}:{line}:{col}"))
    }
}

/// A construct of L written in a situation, as [`blame`] compares it with
/// an error's culprit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Written<'a> {
    /// The arc holding it (0-based; `None`: another attribute).
    pub arc: Option<usize>,
    pub functor: (&'a str, usize),
    /// Its first argument's functor, when that is an atom or a compound.
    pub inner: Option<(&'a str, usize)>,
}

/// What a run-time error names in its situation ([`blame`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Blame {
    /// The situation's in_arg.
    InArg,
    /// The construct of L at this index of the situation's list.
    Written(usize),
    /// The arc at this index (0-based).
    Arc(usize),
    /// The situation itself.
    Situation,
}

/// The place `error` names in its situation, whose constructs of L are
/// `written` (in source order), `arcs` arcs and an in_arg when `in_arg`
/// (see the module doc).
pub fn blame<'a>(
    error: &RunError,
    written: impl Iterator<Item = Written<'a>> + Clone,
    arcs: usize,
    in_arg: bool,
) -> Blame {
    let site = error.site.as_deref();
    if in_arg && site.is_some_and(|s| s.in_arg) {
        return Blame::InArg;
    }
    let arc = error.arc.map(|a| a - 1);
    if let Some(c) = site.and_then(|s| s.culprit) {
        let name = c.name.as_str();
        let inner = c.inner.map(|(n, a)| (n.as_str(), a));
        let functor = |w: &Written<'_>| w.functor == (name, c.arity);
        let exact = |w: &Written<'_>| functor(w) && w.inner == inner;
        let here = || written.clone().enumerate().filter(|(_, w)| w.arc == arc);
        let found = here()
            .find(|(_, w)| exact(w))
            .or_else(|| here().find(|(_, w)| functor(w)))
            .or_else(|| written.clone().enumerate().find(|(_, w)| exact(w)));
        if let Some((i, _)) = found {
            return Blame::Written(i);
        }
    }
    match arc {
        Some(a) if a < arcs => Blame::Arc(a),
        _ => Blame::Situation,
    }
}

/// One situation's entry of a DM's places text (see the module doc).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SitPlaces {
    /// Each arc's line and column, in order.
    pub arcs: Vec<(u32, u32)>,
    /// Each construct of L with its line and column, in source order.
    pub written: Vec<Place>,
}

/// A construct of L of a [`SitPlaces`], its names read from the text.
#[derive(Clone, Debug, PartialEq)]
pub struct Place {
    pub arc: Option<usize>,
    pub functor: (String, usize),
    pub inner: Option<(String, usize)>,
    /// Its line and column.
    pub at: (u32, u32),
}

impl Place {
    /// As [`blame`] compares it.
    pub fn written(&self) -> Written<'_> {
        Written {
            arc: self.arc,
            functor: (&self.functor.0, self.functor.1),
            inner: self.inner.as_ref().map(|(n, a)| (n.as_str(), *a)),
        }
    }
}

/// Entry `sit` of a DM's places text `text` (`None` when it has none or
/// the text does not read: then the situation stands for every place).
pub fn sit_places(text: &str, sit: usize) -> Option<SitPlaces> {
    let entry = entry(text, sit)?;
    let mut out = SitPlaces::default();
    let mut rest = entry;
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix('@') {
            let (pos, r) = position(r)?;
            out.arcs.push(pos);
            rest = r;
        } else {
            let end = rest.find([' ', '@'])?;
            let functor = name_arity(&rest[..end], 2)?;
            let (inner, r) = match rest[end..].strip_prefix(' ') {
                Some(r) => {
                    let (name, r) = inner_name(r)?;
                    let at = r.find('@')?;
                    let arity = match &r[..at] {
                        "" => 0,
                        n => n.strip_prefix('/')?.parse().ok()?,
                    };
                    (Some((name, arity)), &r[at..])
                }
                None => (None, &rest[end..]),
            };
            let (pos, r) = position(r.strip_prefix('@')?)?;
            out.written.push(Place {
                arc: out.arcs.len().checked_sub(1),
                functor,
                inner,
                at: pos,
            });
            rest = r;
        }
        rest = match rest.strip_prefix(',') {
            Some(r) => r,
            None if rest.is_empty() => rest,
            None => return None,
        };
    }
    Some(out)
}

/// Entry `sit` of `text`: between the `#`s outside quotes.
fn entry(text: &str, sit: usize) -> Option<&str> {
    let mut quoted = false;
    let mut n = 0;
    let mut start = 0;
    for (i, c) in text.char_indices() {
        match c {
            '\'' => quoted = !quoted,
            '#' if !quoted => {
                if n == sit {
                    return Some(&text[start..i]);
                }
                n += 1;
                start = i + 1;
            }
            _ => {}
        }
    }
    (n == sit).then(|| &text[start..])
}

/// `L:C` at the start of `s`, and what follows.
fn position(s: &str) -> Option<((u32, u32), &str)> {
    let end = s.find([',', '#']).unwrap_or(s.len());
    let (line, col) = s[..end].split_once(':')?;
    Some(((line.parse().ok()?, col.parse().ok()?), &s[end..]))
}

/// `F/N` (`F` alone: arity `default`).
fn name_arity(s: &str, default: usize) -> Option<(String, usize)> {
    match s.rsplit_once('/') {
        Some((name, n)) if !name.is_empty() => Some((name.to_owned(), n.parse().ok()?)),
        _ => Some((s.to_owned(), default)),
    }
}

/// A first argument's name at the start of `s` (quoted or plain), and what
/// follows.
fn inner_name(s: &str) -> Option<(String, &str)> {
    let Some(q) = s.strip_prefix('\'') else {
        let end = s.find(['/', '@']).unwrap_or(s.len());
        return Some((s[..end].to_owned(), &s[end..]));
    };
    let mut name = String::new();
    let mut chars = q.char_indices();
    let end = loop {
        let (i, c) = chars.next()?;
        if c != '\'' {
            name.push(c);
        } else if q[i + 1..].starts_with('\'') {
            name.push('\'');
            chars.next();
        } else {
            break i + 1;
        }
    };
    Some((name, &q[end..]))
}

/// The places text of one situation (see the module doc): `arcs` its
/// arcs' positions, `written` its constructs of L with theirs, in the
/// order [`blame`] looks at them (those of other attributes first, then
/// each arc's; `arc` numbers from 0).
pub fn sit_places_text<'a>(
    arcs: &[(u32, u32)],
    written: impl IntoIterator<Item = (Written<'a>, (u32, u32))>,
) -> String {
    let mut items = Vec::new();
    let mut next_arc = 0;
    for (w, (l, c)) in written {
        while w.arc.is_some_and(|a| a >= next_arc) && next_arc < arcs.len() {
            let (l, c) = arcs[next_arc];
            items.push(format!("@{l}:{c}"));
            next_arc += 1;
        }
        let (f, n) = w.functor;
        let f = match n {
            2 => f.to_owned(),
            n => format!("{f}/{n}"),
        };
        let inner = match w.inner {
            Some((i, 0)) => format!(" {}", quoted(i)),
            Some((i, m)) => format!(" {}/{m}", quoted(i)),
            None => String::new(),
        };
        items.push(format!("{f}{inner}@{l}:{c}"));
    }
    for &(l, c) in &arcs[next_arc.min(arcs.len())..] {
        items.push(format!("@{l}:{c}"));
    }
    items.join(",")
}

/// `name` as the places text writes a first argument's name.
fn quoted(name: &str) -> String {
    let mut chars = name.chars();
    let plain = chars.next().is_some_and(|c| c.is_ascii_lowercase())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
    if plain {
        name.to_owned()
    } else {
        format!("'{}'", name.replace('\'', "''"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::Culprit;
    use crate::machine::ErrorSite;
    use sitlog_syntax::Atom;

    fn error(arc: Option<usize>, culprit: Option<Culprit>) -> RunError {
        RunError {
            message: String::new(),
            dm: None,
            situation: None,
            arc,
            location: None,
            site: Some(Box::new(ErrorSite {
                dm: 0,
                situation: 0,
                culprit,
                in_arg: false,
            })),
        }
    }

    fn culprit(name: &str, arity: usize, inner: Option<(&str, usize)>) -> Option<Culprit> {
        Some(Culprit {
            name: Atom::intern(name),
            arity,
            inner: inner.map(|(n, a)| (Atom::intern(n), a)),
        })
    }

    #[test]
    fn a_places_text_reads_back() {
        let w = |arc, f, n, inner| Written {
            arc,
            functor: (f, n),
            inner,
        };
        let written = vec![
            (w(None, "is", 2, None), (11, 65)),
            (w(None, "cam2nav", 3, Some(("a/b", 0))), (11, 70)),
            (w(Some(0), "apply", 2, Some(("never", 1))), (13, 30)),
            (w(Some(2), "get", 2, Some(("it's, #odd", 0))), (15, 2)),
            (w(Some(2), ";", 2, Some(("->", 2))), (15, 9)),
            (w(Some(2), "\\==", 2, Some(("x", 0))), (15, 12)),
        ];
        let arcs = [(13, 18), (14, 18), (15, 1), (16, 1)];
        let text = sit_places_text(&arcs, written.clone());
        assert_eq!(
            text,
            "is@11:65,cam2nav/3 'a/b'@11:70,@13:18,apply never/1@13:30,@14:18,@15:1,\
             get 'it''s, #odd'@15:2,; '->'/2@15:9,\\== x@15:12,@16:1"
        );
        let text = format!("#{text}#");
        assert_eq!(sit_places(&text, 0), Some(SitPlaces::default()));
        let read = sit_places(&text, 1).expect("reads");
        assert_eq!(read.arcs, arcs);
        let back: Vec<_> = read.written.iter().map(|p| (p.written(), p.at)).collect();
        assert_eq!(back, written);
        assert_eq!(sit_places(&text, 2), Some(SitPlaces::default()));
        assert_eq!(sit_places(&text, 3), None);
        assert_eq!(sit_places("@1", 0), None);
        assert_eq!(sit_places("apply@1:2,x", 0), None);
    }

    #[test]
    fn the_blamed_construct_is_found_as_the_interpreter_finds_it() {
        let w = |arc, f, inner| Written {
            arc,
            functor: (f, 2),
            inner,
        };
        let written = [
            w(None, "apply", Some(("f", 1))),
            w(Some(0), "apply", Some(("g", 1))),
            w(Some(0), "apply", Some(("f", 1))),
            w(Some(1), "inc", Some(("n", 0))),
        ];
        let at = |arc, c| blame(&error(arc, c), written.iter().copied(), 2, false);
        // In the arc, the same first argument first.
        assert_eq!(
            at(Some(1), culprit("apply", 2, Some(("f", 1)))),
            Blame::Written(2)
        );
        // In the arc, the functor alone.
        assert_eq!(
            at(Some(1), culprit("apply", 2, Some(("h", 1)))),
            Blame::Written(1)
        );
        // Anywhere, the same first argument (an out_arg after the arc).
        assert_eq!(
            at(Some(2), culprit("apply", 2, Some(("f", 1)))),
            Blame::Written(0)
        );
        // Not written: the arc, else the situation.
        assert_eq!(at(Some(2), culprit("is", 2, None)), Blame::Arc(1));
        assert_eq!(at(Some(3), None), Blame::Situation);
        assert_eq!(at(None, None), Blame::Situation);
        let mut e = error(Some(1), culprit("inc", 2, Some(("n", 0))));
        e.site.as_mut().unwrap().in_arg = true;
        assert_eq!(blame(&e, written.iter().copied(), 2, true), Blame::InArg);
        assert_eq!(
            blame(&e, written.iter().copied(), 2, false),
            Blame::Written(3)
        );
    }
}
