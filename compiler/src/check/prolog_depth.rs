//! E0241: a clause of the application's Prolog files nested deeper than
//! the Prolog engine takes ([`PROLOG_MAX_DEPTH`], a list counting a level
//! per element). The engine's reader recurses and would overflow its
//! stack, so a run refuses such a clause at its place; `check` says so
//! first. The walk is iterative (the reader takes terms 10⁶ deep).

use super::*;
use crate::diag::Loc;
use sitlog_runtime::functions::PROLOG_MAX_DEPTH;
use sitlog_syntax::{Node, TermId, Terms};

impl Checker<'_> {
    /// An error at each clause of the application's Prolog files that
    /// nests deeper than the engine takes.
    pub(super) fn prolog_depth(&mut self) {
        let program = self.program;
        for &file in &program.prolog_files {
            let clauses = program.prolog_clauses(file);
            for c in clauses.iter() {
                let (depth, deepest) = nesting(&c.terms, c.root);
                if depth <= PROLOG_MAX_DEPTH {
                    continue;
                }
                let loc = Loc {
                    file,
                    span: c.terms.span(deepest),
                };
                self.diags.push(
                    Diagnostic::error(
                        codes::PROLOG_TOO_DEEP,
                        loc,
                        format!(
                            "this clause nests {depth} levels deep (a list counts a level per element); the Prolog engine takes at most {PROLOG_MAX_DEPTH}: a run refuses it"
                        ),
                    )
                    .with_label("the deepest point")
                    .with_help(
                        "keep deep data out of the clause (build it at run time, or split a long list)",
                    ),
                );
            }
        }
    }
}

/// How deep `root` nests, as the engine reads it (a list's element `i`
/// one level below element `i - 1`; a string a level per character), and
/// the deepest node.
fn nesting(terms: &Terms, root: TermId) -> (usize, TermId) {
    let mut best = (0, root);
    let mut stack = vec![(root, 1usize)];
    while let Some((t, d)) = stack.pop() {
        let here = match terms.node(t) {
            Node::Str(s) | Node::BackQuoted(s) => d + s.chars().count(),
            _ => d,
        };
        if here > best.0 {
            best = (here, t);
        }
        for &a in terms.args(t) {
            stack.push((a, d + 1));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_count_a_level_per_element_and_nesting_a_level_per_compound() {
        let depth = |text: &str| {
            let c = sitlog_syntax::read_term(text).unwrap();
            nesting(&c.terms, c.root).0
        };
        assert_eq!(depth("a"), 1);
        assert_eq!(depth("f(g(a))"), 3);
        assert_eq!(depth("[1,2,3]"), 4);
        assert_eq!(depth("f(\"abc\")"), 5);
        let deep = format!("{}a{}", "s(".repeat(300_000), ")".repeat(300_000));
        assert_eq!(depth(&deep), 300_001);
    }
}
