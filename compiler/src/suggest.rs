//! "Did you mean": the name a misspelt one was probably meant to be, for
//! the help lines of the loader's and the checker's diagnostics. Pure
//! string comparison; knows nothing of programs.

/// The candidate closest to `target`, if it is close enough to be a typo of
/// it: at most a third of the name's length apart by edit distance
/// (a transposition counts one; at least one edit allowed), or sharing
/// most of its start (Jaro-Winkler similarity 0.9 or more: `greet` for
/// `greeting`). Never the name itself, nothing for names shorter than 3
/// characters (any other short name is one edit away); the fewest edits win.
pub fn did_you_mean<'a>(
    target: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let len = target.chars().count();
    let limit = (len / 3).max(1);
    let mut best: Option<(usize, f64, &'a str)> = None;
    for c in candidates {
        if c == target {
            continue;
        }
        let d = strsim::osa_distance(target, c);
        let jw = strsim::jaro_winkler(target, c);
        let close = len >= 3 && (d <= limit || jw >= 0.9);
        let better = best.is_none_or(|(bd, bjw, _)| d < bd || (d == bd && jw > bjw));
        if close && better {
            best = Some((d, jw, c));
        }
    }
    best.map(|(_, _, c)| c)
}
