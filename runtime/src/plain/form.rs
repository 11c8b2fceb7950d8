//! The plain forms as data for a back end outside this module (issue 37):
//! the compiler reads the forms of the application's plain functions
//! ([`plain_forms`], the same scan the engine makes as it loads them) and
//! writes each as a Rust function (`sitlog_compiler::codegen::native::plain_rs`),
//! with its [`PlainFn::fingerprint`]; a run compares that fingerprint with
//! the one of the form its engine loaded ([`PlainFns::compiled_matches`])
//! before it runs the compiled function.
//!
//! Invariant: two forms have the same fingerprint exactly when they are
//! the same form (every clause, head argument, goal, register and
//! constant; atoms by their names, not their interned indices, so a
//! fingerprint written into generated code compares with a run's in
//! another process), and the fingerprint says nothing else.

use super::{
    scan_files, Bin, Cmp, Opnd, PArg, PClause, PExpr, PGoal, PlainFn, PlainFns, Un, MIN_INFERENCES,
};
use crate::term::{Repr, Term};
use sitlog_syntax::Atom;
use std::fmt::Write;

/// The plain functions of `files` (as [`super::plain_names`] reads them)
/// with their forms, sorted by name and arity.
pub fn plain_forms(
    files: &[(&str, Option<&[sitlog_syntax::Clause]>)],
) -> Vec<((Atom, usize), PlainFn)> {
    let fns = scan_files(files);
    let mut forms: Vec<((Atom, usize), PlainFn)> =
        fns.map.iter().map(|(k, f)| (*k, f.clone())).collect();
    forms.sort_by(|a, b| (a.0 .0.as_str(), a.0 .1).cmp(&(b.0 .0.as_str(), b.0 .1)));
    forms
}

/// A constant of a plain clause (`PArg::Const`, `Opnd::Const`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Atomic {
    Atom(Atom),
    Int(i64),
}

/// What the constant `k` of a plain form is (an atom or an integer, as
/// the scan keeps them).
pub fn atomic(k: Term) -> Atomic {
    match k.0 {
        Repr::Atom(a) => Atomic::Atom(a),
        Repr::Int(i) => Atomic::Int(i),
        _ => unreachable!("a plain clause's constant is an atom or an integer"),
    }
}

impl PlainFn {
    /// The clauses, in the engine's order.
    pub fn clauses(&self) -> &[PClause] {
        &self.clauses
    }

    /// The form as text (see the module's invariant), made once.
    pub fn fingerprint(&self) -> &str {
        self.fingerprint.get_or_init(|| self.fingerprint_now())
    }

    fn fingerprint_now(&self) -> String {
        let mut s = String::new();
        let _ = write!(s, "n{}", self.inferences);
        for c in self.clauses.iter() {
            let _ = write!(s, "c{}(", c.vars);
            for a in c.head.iter() {
                arg(&mut s, a);
            }
            s.push(')');
            goals(&mut s, &c.body);
        }
        s
    }
}

impl PClause {
    /// How many variables (registers) the clause has.
    pub fn vars(&self) -> usize {
        self.vars
    }

    /// The head's arguments.
    pub fn head(&self) -> &[PArg] {
        &self.head
    }

    /// The body's goals, in order.
    pub fn body(&self) -> &[PGoal] {
        &self.body
    }
}

impl PlainFns {
    /// Whether `name/arity` is plain here with the form whose fingerprint is
    /// `fingerprint`, and a call of it runs natively under an inference
    /// limit of `limit` (the check `call_vals` makes at every call).
    pub(crate) fn compiled_matches(
        &self,
        name: Atom,
        arity: usize,
        fingerprint: &str,
        limit: u64,
    ) -> bool {
        self.map.get(&(name, arity)).is_some_and(|f| {
            limit >= MIN_INFERENCES.max(f.inferences) && f.fingerprint() == fingerprint
        })
    }
}

fn atom(s: &mut String, a: Atom) {
    let name = a.as_str();
    let _ = write!(s, "a{}:{}", name.len(), name);
}

fn constant(s: &mut String, k: Term) {
    match atomic(k) {
        Atomic::Atom(a) => atom(s, a),
        Atomic::Int(i) => {
            let _ = write!(s, "i{i};");
        }
    }
}

fn arg(s: &mut String, a: &PArg) {
    match a {
        PArg::Bind(i) => {
            let _ = write!(s, "b{i};");
        }
        PArg::Same(i) => {
            let _ = write!(s, "s{i};");
        }
        PArg::Skip => s.push('_'),
        PArg::Const(k) => constant(s, *k),
        PArg::Struct(f, ps) => {
            s.push('S');
            atom(s, *f);
            let _ = write!(s, "{}(", ps.len());
            ps.iter().for_each(|p| arg(s, p));
            s.push(')');
        }
    }
}

fn opnd(s: &mut String, o: &Opnd) {
    match o {
        Opnd::Var(i) => {
            let _ = write!(s, "v{i};");
        }
        Opnd::Const(k) => constant(s, *k),
        Opnd::Build(f, xs) => {
            s.push('B');
            atom(s, *f);
            let _ = write!(s, "{}(", xs.len());
            xs.iter().for_each(|x| opnd(s, x));
            s.push(')');
        }
    }
}

fn expr(s: &mut String, e: &PExpr) {
    match e {
        PExpr::Var(i) => {
            let _ = write!(s, "v{i};");
        }
        PExpr::Int(i) => {
            let _ = write!(s, "i{i};");
        }
        PExpr::Float(f) => {
            // Its bits: the same float exactly.
            let _ = write!(s, "f{:x};", f.to_bits());
        }
        PExpr::Un(op, x) => {
            let op = match op {
                Un::Neg => "neg",
                Un::Pos => "pos",
                Un::Abs => "abs",
            };
            let _ = write!(s, "u{op}(");
            expr(s, x);
            s.push(')');
        }
        PExpr::Bin(op, x, y) => {
            let op = match op {
                Bin::Add => "add",
                Bin::Sub => "sub",
                Bin::Mul => "mul",
                Bin::IntDiv => "div",
                Bin::Mod => "mod",
                Bin::Rem => "rem",
                Bin::Min => "min",
                Bin::Max => "max",
                Bin::Div => "fdiv",
            };
            let _ = write!(s, "x{op}(");
            expr(s, x);
            expr(s, y);
            s.push(')');
        }
    }
}

fn goals(s: &mut String, gs: &[PGoal]) {
    s.push('{');
    for g in gs {
        match g {
            PGoal::True => s.push('T'),
            PGoal::Fail => s.push('F'),
            PGoal::Cut => s.push('!'),
            PGoal::IsFresh(i, e) => {
                let _ = write!(s, "is{i}(");
                expr(s, e);
                s.push(')');
            }
            PGoal::IsBound(i, e) => {
                let _ = write!(s, "isb{i}(");
                expr(s, e);
                s.push(')');
            }
            PGoal::Cmp(op, x, y) => {
                let op = match op {
                    Cmp::Lt => "lt",
                    Cmp::Gt => "gt",
                    Cmp::Le => "le",
                    Cmp::Ge => "ge",
                    Cmp::Eq => "eq",
                    Cmp::Ne => "ne",
                };
                let _ = write!(s, "c{op}(");
                expr(s, x);
                expr(s, y);
                s.push(')');
            }
            PGoal::Ident(eq, x, y) => {
                s.push_str(if *eq { "id(" } else { "nid(" });
                opnd(s, x);
                opnd(s, y);
                s.push(')');
            }
            PGoal::Bind(i, o) => {
                let _ = write!(s, "bind{i}(");
                opnd(s, o);
                s.push(')');
            }
            PGoal::Assign(o) => {
                s.push_str("as(");
                opnd(s, o);
                s.push(')');
            }
            PGoal::Ite(c, t, e) => {
                s.push_str("ite");
                goals(s, c);
                goals(s, t);
                goals(s, e);
            }
        }
    }
    s.push('}');
}

#[cfg(test)]
mod tests {
    use super::*;

    fn forms(text: &str) -> Vec<(String, String)> {
        plain_forms(&[(text, None)])
            .into_iter()
            .map(|((n, a), f)| (format!("{n}/{a}"), f.fingerprint().to_owned()))
            .collect()
    }

    #[test]
    fn a_fingerprint_is_the_form() {
        let a = forms(
            "f(X, [Y|_]) :- X > 0, !, Z is X + Y, assign_func_value(p(Z)).\n\
             f(_, _) :- assign_func_value(none).\n\
             g(X) :- ( X == a -> Y = 1 ; Y = 2 ), assign_func_value(Y).\n\
             h(X) :- atom(X), assign_func_value(X).\n",
        );
        let names: Vec<&str> = a.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["f/2", "g/1"]);
        // The same clauses, other variable names and layout: the same.
        let b = forms(
            "f(A,[B|_]):-A>0,!,C is A+B,assign_func_value(p(C)).\n\
             f(_,_):-assign_func_value(none).\n\
             g(Q) :- ( Q == a -> R = 1 ; R = 2 ), assign_func_value(R).\n",
        );
        assert_eq!(a, b);
        // Each a difference: an atom, an integer, an operator, a clause.
        for other in [
            "f(X, [Y|_]) :- X > 0, !, Z is X + Y, assign_func_value(q(Z)).\n",
            "f(X, [Y|_]) :- X > 1, !, Z is X + Y, assign_func_value(p(Z)).\n",
            "f(X, [Y|_]) :- X >= 0, !, Z is X + Y, assign_func_value(p(Z)).\n",
            "f(X, [Y|_]) :- X > 0, Z is X + Y, assign_func_value(p(Z)).\n",
            "f(X, [Y|_]) :- X > 0, !, Z is Y + X, assign_func_value(p(Z)).\n",
            "f(X, [Y]) :- X > 0, !, Z is X + Y, assign_func_value(p(Z)).\n",
        ] {
            let c = forms(&format!("{other}f(_, _) :- assign_func_value(none).\n"));
            assert_ne!(c[0].1, a[0].1, "{other}");
        }
        // An atom's name, not its index: `ab` + `c` is not `a` + `bc`.
        let x = forms("k(ab, c) :- assign_func_value(x).\n");
        let y = forms("k(a, bc) :- assign_func_value(x).\n");
        assert_ne!(x[0].1, y[0].1);
    }
}
