//! From read terms (the syntax crate's per-clause arenas) to store terms.
//!
//! Follows SWI-Prolog 6, the original's target: a double-quoted string
//! becomes a list of character codes, and so does a back-quoted one.
//! Printing the other way goes through [`Store::writeq`].

use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::{read_term, Clause, Node, SyntaxError, TermId, Terms};

/// Variable bindings of a converted clause: source name -> term, in order
/// of first occurrence; anonymous `_` variables are not listed.
pub type Bindings = Vec<(Box<str>, Term)>;

impl Store {
    /// Converts term `root` of `terms`. `vars[i]` is the term for the
    /// clause's variable `VarId(i)`: `None` slots are filled with fresh
    /// variables, preset slots link the term to existing ones. A variable
    /// without a slot gets a fresh variable that is not recorded.
    /// Iterative: any depth.
    pub fn import(&mut self, terms: &Terms, root: TermId, vars: &mut [Option<Term>]) -> Term {
        let mut work: Vec<(TermId, bool)> = vec![(root, false)];
        let mut done: Vec<Term> = Vec::new();
        while let Some((id, expanded)) = work.pop() {
            let t = match terms.node(id) {
                Node::Compound { functor, .. } => {
                    let args = terms.args(id);
                    if expanded {
                        let base = done.len().saturating_sub(args.len());
                        let t = self.compound(*functor, &done[base..]);
                        done.truncate(base);
                        t
                    } else {
                        work.push((id, true));
                        work.extend(args.iter().rev().map(|&a| (a, false)));
                        continue;
                    }
                }
                Node::Var(v) => match vars.get_mut(v.0 as usize) {
                    Some(Some(t)) => *t,
                    Some(slot) => *slot.insert(self.new_var()),
                    None => self.new_var(),
                },
                Node::Atom(a) => Term::atom(*a),
                Node::Int(i) => Term::int(*i),
                Node::Float(f) => Term::float(*f),
                Node::BigInt(text) => self.integer_from_text(text).unwrap_or_else(|| {
                    // The reader only produces valid digits; keep the text
                    // as an atom rather than fail on a malformed arena.
                    Term::atom(sitlog_syntax::Atom::intern(text))
                }),
                Node::Str(s) | Node::BackQuoted(s) => self.codes(s),
            };
            done.push(t);
        }
        done.pop().unwrap_or(Term::NIL)
    }

    /// Converts a whole clause, returning its term and its named variables.
    pub fn from_clause(&mut self, clause: &Clause) -> (Term, Bindings) {
        let mut slots = vec![None; clause.vars.len()];
        let t = self.import(&clause.terms, clause.root, &mut slots);
        let bindings = clause
            .vars
            .iter()
            .zip(slots)
            .filter(|(info, _)| &*info.name != "_")
            .filter_map(|(info, slot)| slot.map(|t| (info.name.clone(), t)))
            .collect();
        (t, bindings)
    }

    /// Reads one term from `src` (SitLog operators; final `.` optional)
    /// and converts it.
    pub fn parse(&mut self, src: &str) -> Result<(Term, Bindings), SyntaxError> {
        let clause = read_term(src)?;
        Ok(self.from_clause(&clause))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sitlog_syntax::{atoms, Atom, Node, Span, VarId, VarInfo};

    fn clause_by_hand() -> Clause {
        // f(X, "ab", X, _, 123456789012345678901234567890)
        let mut terms = Terms::new();
        let sp = Span::default();
        let x1 = terms.push(Node::Var(VarId(0)), sp);
        let s = terms.push(Node::Str("ab".into()), sp);
        let x2 = terms.push(Node::Var(VarId(0)), sp);
        let anon = terms.push(Node::Var(VarId(1)), sp);
        let big = terms.push(Node::BigInt("123456789012345678901234567890".into()), sp);
        let root = terms.push_compound(Atom::intern("f"), &[x1, s, x2, anon, big], sp);
        let info = |name: &str| VarInfo {
            name: name.into(),
            first: sp,
            occurrences: 1,
        };
        Clause {
            terms,
            root,
            vars: vec![info("X"), info("_")],
            span: sp,
        }
    }

    #[test]
    fn clause_conversion() {
        let mut s = Store::new();
        let clause = clause_by_hand();
        let (t, bindings) = s.from_clause(&clause);
        assert_eq!(bindings.len(), 1);
        assert_eq!(&*bindings[0].0, "X");
        let args = s.args(t).to_vec();
        assert!(s.identical(args[0], bindings[0].1));
        assert!(s.identical(args[0], args[2]));
        assert!(!s.identical(args[0], args[3]));
        assert_eq!(
            s.list_to_vec(args[1]),
            Some(vec![Term::int(97), Term::int(98)])
        );
        assert_eq!(
            s.writeq(t),
            "f(_G0,[97,98],_G0,_G1,123456789012345678901234567890)"
        );
    }

    #[test]
    fn preset_slots_link_variables() {
        let mut s = Store::new();
        let clause = clause_by_hand();
        let shared = Term::atom(atoms::EMPTY);
        let mut slots = vec![Some(shared), None];
        let t = s.import(&clause.terms, clause.root, &mut slots);
        assert_eq!(s.arg(t, 0), Some(shared));
        assert!(slots[1].is_some());
        // Too few slots: variables still get fresh terms.
        let t2 = s.import(&clause.terms, clause.root, &mut []);
        assert!(s.is_var(s.arg(t2, 0).unwrap()));
    }

    #[test]
    fn deep_clause_imports_iteratively() {
        let mut terms = Terms::new();
        let sp = Span::default();
        let f = Atom::intern("f");
        let mut t = terms.push(Node::Atom(Atom::intern("z")), sp);
        for _ in 0..100_000 {
            t = terms.push_compound(f, &[t], sp);
        }
        let mut s = Store::new();
        let r = s.import(&terms, t, &mut []);
        let mut depth = 0;
        let mut cur = r;
        while let Some(a) = s.arg(cur, 0) {
            cur = a;
            depth += 1;
        }
        assert_eq!(depth, 100_000);
        assert_eq!(s.atom_of(cur), Some(Atom::intern("z")));
    }
}
