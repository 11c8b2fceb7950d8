//! What one run can reach (issue 39): the DM a run starts from, the DMs
//! named by a constant `embedded_dm` from it (transitively) and the DMs of
//! the recovery protocols. The original looks into a DM only when its run
//! reaches it, so a run leaves out a DM with errors that it cannot reach by
//! name ([`leave_out`]): its errors become warnings, one warning W0232 names
//! it, and it is not lowered; a call of it by a name computed at run time
//! is a located run-time error ([`LeftOut`], through the IR).
//! Invariant: only DMs without errors stay in the program.

use super::*;

/// A DM left out of a run for its errors: calling it is a run-time error
/// that quotes the first of them.
#[derive(Debug, Clone)]
pub struct LeftOut {
    pub name: Atom,
    pub arity: usize,
    /// Why, in one line: the first error (`file:line:col: error[E0230]: ...`).
    pub error: String,
}

/// The indices of the DMs of `program` that a run of the DM named `task`
/// can reach by name.
fn reachable(program: &Program, task: Atom) -> HashSet<usize> {
    let mut reached = HashSet::new();
    let mut work: Vec<usize> = Vec::new();
    let named = |name: Atom, work: &mut Vec<usize>, reached: &mut HashSet<usize>| {
        for (i, dm) in program.dms.iter().enumerate() {
            if dm.name == name && reached.insert(i) {
                work.push(i);
            }
        }
    };
    named(task, &mut work, &mut reached);
    for r in &program.recovery {
        named(r.dm, &mut work, &mut reached);
    }
    while let Some(i) = work.pop() {
        let dm = &program.dms[i];
        for s in &dm.situations {
            let Some(callee) = s.embedded_dm else {
                continue;
            };
            // A name computed at run time (`M`, `get(dm, M)`) names no DM
            // here: a DM left out is then an error when the call reaches it.
            match dm.clause.terms.functor(callee) {
                Some((name, arity)) if !EVALUATED.contains(&(name.as_str(), arity)) => {
                    named(name, &mut work, &mut reached)
                }
                _ => {}
            }
        }
    }
    reached
}

/// The DM of `program` whose clause holds `loc`.
fn owner(program: &Program, loc: crate::diag::Loc) -> Option<usize> {
    program.dms.iter().position(|dm| {
        dm.file == loc.file
            && dm.clause.span.start <= loc.span.start
            && loc.span.end <= dm.clause.span.end
    })
}

/// Leaves out of `program` each DM with an error that a run of `task`
/// cannot reach by name: its errors become warnings, a warning W0232 at its
/// head names it, and it is returned with its first error.
pub(super) fn leave_out(
    program: &mut Program,
    diags: &mut Vec<Diagnostic>,
    task: Atom,
) -> Vec<LeftOut> {
    // Without errors there is nothing to leave out; without a DM of that
    // name the run cannot start, and every error is said.
    if !diags.iter().any(Diagnostic::is_error) || !program.dms.iter().any(|d| d.name == task) {
        return Vec::new();
    }
    let reached = reachable(program, task);
    // Each DM out of reach with its errors (indices into `diags`).
    let mut out: Vec<(usize, Vec<usize>)> = Vec::new();
    for (k, d) in diags.iter().enumerate().filter(|(_, d)| d.is_error()) {
        match owner(program, d.loc) {
            Some(i) if !reached.contains(&i) => match out.iter_mut().find(|(j, _)| *j == i) {
                Some((_, errors)) => errors.push(k),
                None => out.push((i, vec![k])),
            },
            _ => {}
        }
    }
    if out.is_empty() {
        return Vec::new();
    }
    let mut left = Vec::new();
    for (i, errors) in &out {
        let dm = &program.dms[*i];
        // The first in the file (the loader's errors come before the checker's).
        let first = errors
            .iter()
            .map(|&k| &diags[k])
            .min_by_key(|d| d.loc.span.start)
            .unwrap_or(&diags[errors[0]]);
        let error = crate::diag::render_short(first, &program.sources)
            .lines()
            .next()
            .unwrap_or_default()
            .to_owned();
        let warning = Diagnostic::warning(
            codes::LEFT_OUT,
            dm.loc(dm.span_of(dm.head)),
            format!(
                "DM `{}/{}` has {} error(s) and is left out of this run: `{task}` does not name it, and a run that reaches it stops there",
                dm.name,
                dm.arity,
                errors.len()
            ),
        )
        .with_label("left out")
        .with_help(format!("the first error: {error}"));
        left.push((
            warning,
            LeftOut {
                name: dm.name,
                arity: dm.arity,
                error,
            },
        ));
    }
    for (_, errors) in &out {
        for &k in errors {
            diags[k].severity = crate::diag::Severity::Warning;
        }
    }
    let mut removed: Vec<usize> = out.iter().map(|(i, _)| *i).collect();
    removed.sort_unstable();
    for i in removed.into_iter().rev() {
        program.dms.remove(i);
    }
    left.into_iter()
        .map(|(warning, l)| {
            diags.push(warning);
            l
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::check::{check_opts, codes, CheckOptions};
    use crate::load::load_sources;
    use sitlog_syntax::Atom;

    /// `main` calls `a(1)`, which calls `c`; `b` is named by nothing.
    const MAIN: &str = "diag_mod(main, [[id ==> is, type ==> recursive, embedded_dm ==> a(1), arcs ==> [fs : empty => fs]], [id ==> fs, type ==> final]], []).\n";
    const A: &str = "diag_mod(a(_), [[id ==> is, type ==> recursive, embedded_dm ==> c, arcs ==> [fs : empty => fs]], [id ==> fs, type ==> final]], []).\n";
    const GOOD: &str = "diag_mod(NAME, [[id ==> is, type ==> neutral, arcs ==> [empty : empty => fs]], [id ==> fs, type ==> final]], []).\n";
    const BROKEN: &str = "diag_mod(NAME, [[id ==> is, type ==> neutrall, arcs ==> [empty : empty => fs]], [id ==> fs, type ==> final]], []).\n";

    fn run_check(main: &str, b: &str, c: &str) -> (Vec<String>, Vec<String>, bool) {
        let (b, c) = (b.replace("NAME", "b"), c.replace("NAME", "c"));
        let files = [
            ("main.dm", main),
            ("a.dm", A),
            ("b.dm", b.as_str()),
            ("c.dm", c.as_str()),
        ];
        let (program, diags) = load_sources(&files);
        let options = CheckOptions {
            task: Some(Atom::intern("main")),
            ..CheckOptions::default()
        };
        let (result, diags) = check_opts(program, diags, options);
        let errors = diags
            .iter()
            .filter(|d| d.is_error())
            .map(|d| d.code.to_owned())
            .collect();
        let left = diags
            .iter()
            .filter(|d| d.code == codes::LEFT_OUT)
            .map(|d| d.message.clone())
            .collect();
        (errors, left, result.is_ok())
    }

    #[test]
    fn only_what_the_task_reaches_by_name_refuses_it() {
        // c is reached through a(1): its error refuses the run.
        let (errors, left, ok) = run_check(MAIN, GOOD, BROKEN);
        assert_eq!(
            (errors, left.len(), ok),
            (vec!["E0230".to_owned()], 0, false)
        );
        // b is named by nothing: left out, the rest checked.
        let (errors, left, ok) = run_check(MAIN, BROKEN, GOOD);
        assert!(errors.is_empty() && ok, "{errors:?}");
        assert_eq!(left.len(), 1);
        assert!(left[0].starts_with("DM `b/0` has 1 error(s)"), "{left:?}");
        // A name computed at run time reaches no DM here: c is left out too.
        let computed = MAIN.replace("embedded_dm ==> a(1)", "embedded_dm ==> M, in_arg ==> M");
        let (errors, left, ok) = run_check(&computed, BROKEN, BROKEN);
        assert!(errors.is_empty() && ok, "{errors:?}");
        assert_eq!(left.len(), 2, "{left:?}");
    }
}
