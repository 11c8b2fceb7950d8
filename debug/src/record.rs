//! One transition as the debugger shows, keeps and compares it: the
//! fields of a `--trace` line, as text; and an input that met no
//! expectation ([`Unmatched`], a trace line with `unmatched`), which is not
//! a transition (it has no number) but is listed and compared with them.
//! Live runs make them from the machine's terms (as `--trace` prints
//! them), replays read them from the trace, so both print and compare alike.

use std::fmt::Write as _;

/// One transition.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Record {
    pub dm: String,
    pub situation: String,
    pub expectation: String,
    pub action: String,
    /// DMs under this one on the stack (the main DM is at depth 0).
    pub depth: usize,
    /// The next situation; `None` when the DM ended.
    pub next: Option<String>,
}

impl Record {
    /// `main / ask  [said(yes) => say(ok)]  -> done`.
    pub fn line(&self) -> String {
        let next = self.next.as_deref().unwrap_or("(end of DM)");
        format!(
            "{} / {}  [{} => {}]  -> {}",
            self.dm, self.situation, self.expectation, self.action, next
        )
    }
}

/// An input that met no expectation of a situation: nothing entered the
/// history, the situation was entered again.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unmatched {
    pub dm: String,
    pub situation: String,
    pub input: String,
    pub depth: usize,
    /// The transitions made before it (it comes before transition
    /// `before + 1`).
    pub before: usize,
}

impl Unmatched {
    /// `main / ask  said(maybe) met no expectation`.
    pub fn line(&self) -> String {
        format!(
            "{} / {}  {} met no expectation",
            self.dm, self.situation, self.input
        )
    }

    /// Whether two inputs are the same event (where they came aside).
    pub fn same(&self, other: &Unmatched) -> bool {
        (&self.dm, &self.situation, &self.input, self.depth)
            == (&other.dm, &other.situation, &other.input, other.depth)
    }
}

/// An unmatched input as `history` lists it: no number, indented by depth.
pub fn unnumbered(u: &Unmatched) -> String {
    format!("      {}{}", "  ".repeat(u.depth.min(12)), u.line())
}

/// The name of a term's principal functor as `writeq` printed it: `ask`
/// for `ask`, `ask(X)` and `ask(1, 2)`.
pub fn name_of(text: &str) -> &str {
    text.split('(').next().unwrap_or(text).trim()
}

/// Whether `r` is where breakpoint `spec` stops, given the transitions
/// before it. A DM or situation is named by its name (`ask`) or by the
/// term as printed (`ask(color)`, spaces aside).
pub fn hits(spec: &crate::command::Spec, before: &[Record], r: &Record) -> bool {
    use crate::command::Spec;
    let names = |text: &str, name: &str| {
        name_of(text) == name || {
            let squeeze = |s: &str| s.chars().filter(|c| !c.is_whitespace()).collect::<String>();
            squeeze(text) == squeeze(name)
        }
    };
    match spec {
        Spec::Dm(dm) => names(&r.dm, dm) && first_of_call(before, r),
        Spec::Situation(dm, sit) => names(&r.dm, dm) && names(&r.situation, sit),
        Spec::Error => false,
    }
}

/// Why breakpoint `spec` can never stop in the program whose DMs and
/// situation names are `names` (a name that is not there, with the
/// closest one as "did you mean"); `None` when it can, or when `names`
/// is empty (the program did not say).
pub fn unknown_name(
    names: &[(String, Vec<String>)],
    spec: &crate::command::Spec,
) -> Option<String> {
    use crate::command::Spec;
    if names.is_empty() {
        return None;
    }
    let (dm, sit) = match spec {
        Spec::Dm(dm) => (dm, None),
        Spec::Situation(dm, sit) => (dm, Some(sit)),
        Spec::Error => return None,
    };
    let unquote = |s: &str| -> String {
        s.strip_prefix('\'')
            .and_then(|s| s.strip_suffix('\''))
            .unwrap_or(s)
            .to_owned()
    };
    let dm_name = unquote(name_of(dm));
    let dm_name = dm_name.as_str();
    let Some((_, situations)) = names.iter().find(|(n, _)| *n == dm_name) else {
        let hint = closest(dm_name, names.iter().map(|(n, _)| n.as_str()));
        return Some(format!("there is no DM `{dm_name}`{hint}"));
    };
    let sit = sit?;
    let sit_name = unquote(name_of(sit));
    let sit_name = sit_name.as_str();
    if situations.iter().any(|s| s == sit_name) {
        return None;
    }
    let hint = closest(sit_name, situations.iter().map(String::as_str));
    Some(format!(
        "DM `{dm_name}` has no situation `{sit_name}`{hint}"
    ))
}

/// ` (did you mean `NAME`?)` for the candidate closest to `target` when it
/// is close enough to be a typo (edit distance at most a third of the
/// length, or a shared start); empty otherwise.
fn closest<'a>(target: &str, candidates: impl Iterator<Item = &'a str>) -> String {
    let limit = (target.chars().count() / 3).max(1);
    let best = candidates
        .filter(|c| *c != target)
        .map(|c| (strsim::osa_distance(target, c), c))
        .filter(|(d, c)| *d <= limit || strsim::jaro_winkler(target, c) >= 0.9)
        .min_by_key(|(d, _)| *d);
    match best {
        Some((_, c)) => format!(" (did you mean `{c}`?)"),
        None => String::new(),
    }
}

/// Whether `r` is the first transition of a call of its DM, given the
/// transitions before it: going back, an earlier transition of the same
/// depth comes before any of a lower one only within the same call.
pub fn first_of_call(before: &[Record], r: &Record) -> bool {
    for p in before.iter().rev() {
        if p.depth == r.depth {
            return false;
        }
        if p.depth < r.depth {
            return true;
        }
    }
    true
}

/// Transition `n` (1-based) as `history` lists it, indented by depth.
pub fn numbered(n: usize, r: &Record) -> String {
    format!("#{n:<4} {}{}", "  ".repeat(r.depth.min(12)), r.line())
}

/// The last `count` of `records` (numbered from 1), one a line.
pub fn history(records: &[Record], count: usize) -> String {
    history_from(0, records, count)
}

/// [`history`] of records numbered from `first + 1`.
pub fn history_from(first: usize, records: &[Record], count: usize) -> String {
    history_with(first, records, &[], count)
}

/// [`history_from`] with the inputs that met no expectation among the
/// transitions listed, each where it came (`before` counts from 0, not
/// from `first`), the ones after the last transition at the end.
pub fn history_with(
    first: usize,
    records: &[Record],
    unmatched: &[Unmatched],
    count: usize,
) -> String {
    let mut out = String::new();
    let from = records.len().saturating_sub(count);
    let inputs = |out: &mut String, before: usize| {
        for u in unmatched.iter().filter(|u| u.before == before) {
            let _ = writeln!(out, "{}", unnumbered(u));
        }
    };
    if records.is_empty() {
        out.push_str("no transition yet\n");
    }
    for (i, r) in records.iter().enumerate().skip(from) {
        inputs(&mut out, first + i);
        let _ = writeln!(out, "{}", numbered(first + i + 1, r));
    }
    inputs(&mut out, first + records.len());
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(dm: &str, depth: usize) -> Record {
        Record {
            dm: dm.into(),
            situation: "s".into(),
            expectation: "e".into(),
            action: "a".into(),
            depth,
            next: None,
        }
    }

    #[test]
    fn first_of_a_call() {
        // main calls x twice (two recursive situations), x calls y.
        let rs = [r("y", 2), r("x", 1), r("x", 1), r("main", 0), r("x", 1)];
        assert!(first_of_call(&rs[..0], &rs[0]));
        assert!(first_of_call(&rs[..1], &rs[1]));
        assert!(!first_of_call(&rs[..2], &rs[2]));
        assert!(first_of_call(&rs[..4], &rs[4]));
        assert_eq!(name_of("ask(X, 1)"), "ask");
        use crate::command::Spec;
        let mut got = r("ask(color)", 1);
        got.situation = "got(red)".into();
        for (dm, sit, hit) in [
            ("ask", "got", true),
            ("ask(color)", "got(red)", true),
            ("ask( color )", "got( red)", true),
            ("ask(size)", "got", false),
            ("ask", "got(blue)", false),
            ("main", "got", false),
        ] {
            let spec = Spec::Situation(dm.into(), sit.into());
            assert_eq!(hits(&spec, &[], &got), hit, "{dm}:{sit}");
        }
        assert!(hits(&Spec::Dm("ask(color)".into()), &[], &got));
        assert!(!hits(&Spec::Error, &[], &got));
    }

    #[test]
    fn names_that_are_not_in_the_program_are_told_with_the_closest() {
        use crate::command::Spec;
        let names = vec![
            ("main".to_owned(), vec!["is".to_owned(), "ask".to_owned()]),
            ("greet".to_owned(), vec!["hello".to_owned()]),
        ];
        let dm = |d: &str| Spec::Dm(d.into());
        let sit = |d: &str, s: &str| Spec::Situation(d.into(), s.into());
        assert_eq!(unknown_name(&names, &dm("greet")), None);
        assert_eq!(unknown_name(&names, &dm("greet(x)")), None);
        assert_eq!(unknown_name(&names, &sit("main", "ask(1)")), None);
        assert_eq!(
            unknown_name(&names, &dm("gret")).as_deref(),
            Some("there is no DM `gret` (did you mean `greet`?)")
        );
        assert_eq!(
            unknown_name(&names, &sit("main", "aks")).as_deref(),
            Some("DM `main` has no situation `aks` (did you mean `ask`?)")
        );
        assert_eq!(
            unknown_name(&names, &dm("zzzzzz")).as_deref(),
            Some("there is no DM `zzzzzz`")
        );
        assert_eq!(unknown_name(&[], &dm("x")), None);
        let quoted = vec![("find it".to_owned(), vec!["look around".to_owned()])];
        assert_eq!(
            unknown_name(&quoted, &sit("'find it'", "'look around'")),
            None
        );
    }
}
