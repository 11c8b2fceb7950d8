//! Type inference over the IR: which SitLog values are provably integers,
//! floats, atoms of a finite set or ground terms of a fixed shape, and which
//! situations can run on such native values (the *typed plan* the code
//! generator follows). Pure: reads the [`Ir`], never fails, never rejects a
//! program; whatever it cannot type stays a term (with the reason, for
//! `sitlogc build --explain-types`).
//!
//! What is typed:
//! - a **local variable** gets the join of its default value's type and of
//!   every value the DM's own code writes into it (`set(n, C)` with C a
//!   constant; `inc(n, _)` keeps an int an int and a float a float). Code
//!   the compiler cannot see (user functions through `var_op`, the
//!   evaluator on a constructed term) may still write anything, so typed
//!   code *loads* the frame with a check and falls back to the untyped path
//!   when a value does not fit: the type is a fact about the DM's own code
//!   and a guard at run time, never a rejection.
//! - a **DM parameter** (a variable of the head) gets the type its uses in
//!   typed situations demand (compared arithmetically with an int: int;
//!   with another parameter or the pipe: int too, the check on load
//!   sending any other value to the untyped path);
//!   any DM may be started from the command line with any argument, so this
//!   is always checked when the frame is loaded.
//! - an **arc variable** is typed when its first occurrence takes the value
//!   of a typed local (`inc(n, N)`, `get(n, N)`).
//! - the **pipe** read by a situation whose `in_arg` is a variable (not a
//!   parameter) gets the type its uses demand, like a parameter, and is
//!   checked when the frame is loaded (whoever called the DM may have put
//!   any term there).
//! - a **situation** is typed when its id is an atom, it has no
//!   `diag_mod`/`embedded_dm`, no `in_arg` but a variable (a final
//!   situation: no `in_arg` at all, no `prog`, no `out_arg`), no `prog` but
//!   `V is E` with `V` its out_arg variable (fresh; an int the arcs may
//!   read) and `E` `+`/`-`/`*` over ints, the pipe and parameters (an
//!   overflow runs the situation untyped, which reports it), and no
//!   `out_arg` but that `V`, every expectation
//!   is a constant, every action a constant or a list of constants and
//!   `get`/`set`/`inc` of typed locals, and every next situation a constant
//!   situation of the DM or a conditional on an arithmetic comparison of
//!   typed numbers (a typed local read in place, `get(n, _)`, included),
//!   or on `==`/`\==` of typed atoms. A run of typed situations executes on native values,
//!   touching no term unless the history is kept or observed.
//! - a **recursive situation** is a typed call when its id is an atom, it
//!   has no `in_arg`/`out_arg`/`prog`/`diag_mod`, its `embedded_dm` is an
//!   atom naming a DM without parameters or a constant call (`count(2)`:
//!   arguments that evaluate to themselves) of a DM whose parameters are
//!   distinct variables, the callee's initial situation typed,
//!   and its exit arcs have atom expectations, typed actions and next
//!   situations, and no variable shared with the rest of the situation;
//!   and when the situation runs as code (its MIR plan gives the untyped
//!   exit arcs, for a callee that ends through the machine).
//! - **globals** are typed like locals (for the listing); generated code
//!   keeps them as terms.

use crate::ir::{none_marker, Ir, IrDm};
use sitlog_runtime::machine::Kind;
use sitlog_runtime::{eval, ArithCmp, Store, Term, Value};
use sitlog_syntax::{atoms, Atom};
use std::collections::HashMap;
use std::fmt::Write as _;

mod explain;
mod infer;

pub use explain::{explain, explain_with, summary, NativeDm};
pub use infer::infer;
use infer::var_name;

/// Largest finite atom set kept as a type (beyond it: a term).
pub const MAX_ATOMS: usize = 64;
/// Deepest fixed shape kept as a type.
const MAX_DEPTH: usize = 8;

/// The type of a SitLog value.
#[derive(Clone, Debug, PartialEq)]
pub enum Ty {
    /// No value seen yet (the bottom of the lattice; never in a result).
    None,
    Int,
    Float,
    /// One of these atoms (sorted by text).
    Atoms(Vec<Atom>),
    /// A compound `name(T1, ..., Tn)` of this shape, ground.
    Shape(Atom, Vec<Ty>),
    /// Anything: stays a term.
    Term,
}

impl Ty {
    /// The least type holding both.
    pub fn join(&self, other: &Ty) -> Ty {
        match (self, other) {
            (Ty::None, t) | (t, Ty::None) => t.clone(),
            (Ty::Int, Ty::Int) => Ty::Int,
            (Ty::Float, Ty::Float) => Ty::Float,
            (Ty::Atoms(a), Ty::Atoms(b)) => {
                let mut all = a.clone();
                for x in b {
                    if !all.contains(x) {
                        all.push(*x);
                    }
                }
                if all.len() > MAX_ATOMS {
                    return Ty::Term;
                }
                all.sort_by(|x, y| x.as_str().cmp(y.as_str()));
                Ty::Atoms(all)
            }
            (Ty::Shape(f, a), Ty::Shape(g, b)) if f == g && a.len() == b.len() => {
                let args: Vec<Ty> = a.iter().zip(b).map(|(x, y)| x.join(y)).collect();
                if args.contains(&Ty::Term) {
                    Ty::Term
                } else {
                    Ty::Shape(*f, args)
                }
            }
            _ => Ty::Term,
        }
    }

    /// Whether generated code keeps a value of this type natively.
    pub fn is_native(&self) -> bool {
        matches!(self, Ty::Int | Ty::Float | Ty::Atoms(_))
    }

    /// The type of a ground term (`Term` for a non-ground one or a big integer).
    pub fn of_ground(store: &Store, t: Term) -> Ty {
        Self::of_ground_at(store, t, 0)
    }

    fn of_ground_at(store: &Store, t: Term, depth: usize) -> Ty {
        match store.value(t) {
            Value::Int(_) => Ty::Int,
            Value::Float(_) => Ty::Float,
            Value::Atom(a) => Ty::Atoms(vec![a]),
            Value::Compound(name, args) if depth < MAX_DEPTH => {
                let args: Vec<Ty> = args
                    .iter()
                    .map(|&a| Self::of_ground_at(store, a, depth + 1))
                    .collect();
                if args.contains(&Ty::Term) {
                    Ty::Term
                } else {
                    Ty::Shape(name, args)
                }
            }
            _ => Ty::Term,
        }
    }
}

impl std::fmt::Display for Ty {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Ty::None => f.write_str("none"),
            Ty::Int => f.write_str("int"),
            Ty::Float => f.write_str("float"),
            Ty::Term => f.write_str("term"),
            Ty::Atoms(atoms) => {
                f.write_str("{")?;
                for (i, a) in atoms.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    f.write_str(&quote_atom(a.as_str()))?;
                }
                f.write_str("}")
            }
            Ty::Shape(name, args) => {
                if *name == atoms::DOT && args.len() == 2 {
                    write!(f, "[{} | {}]", args[0], args[1])
                } else {
                    write!(f, "{}(", quote_atom(name.as_str()))?;
                    for (i, a) in args.iter().enumerate() {
                        if i > 0 {
                            f.write_str(", ")?;
                        }
                        write!(f, "{a}")?;
                    }
                    f.write_str(")")
                }
            }
        }
    }
}

/// `a float`, `an int`, `a term`, ...
fn an(ty: &Ty) -> String {
    match ty {
        Ty::Int => "an int".to_owned(),
        Ty::Atoms(_) => format!("an atom of {ty}"),
        _ => format!("a {ty}"),
    }
}

/// `writeq` of a term of `dm` with the source names of its variables.
fn show(store: &Store, dm: &IrDm, t: Term) -> String {
    let text = store.writeq(t);
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find("_G") {
        out.push_str(&rest[..i]);
        let digits: String = rest[i + 2..]
            .chars()
            .take_while(|c| c.is_ascii_digit())
            .collect();
        match digits.parse::<u32>() {
            Ok(v) if !digits.is_empty() => {
                out.push_str(&var_name(dm, v));
                rest = &rest[i + 2 + digits.len()..];
            }
            _ => {
                out.push_str("_G");
                rest = &rest[i + 2..];
            }
        }
    }
    out.push_str(rest);
    out
}

fn quote_atom(text: &str) -> String {
    let plain = text.chars().next().is_some_and(|c| c.is_ascii_lowercase())
        && text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if plain || text == "[]" {
        text.to_owned()
    } else {
        format!("'{}'", text.replace('\\', "\\\\").replace('\'', "\\'"))
    }
}

/// A variable's type and why.
#[derive(Clone, Debug, PartialEq)]
pub struct VarTy {
    pub name: String,
    pub ty: Ty,
    pub why: String,
}

/// The result of inference.
#[derive(Debug)]
pub struct Types {
    pub dms: Vec<DmTypes>,
    pub globals: Vec<VarTy>,
}

/// What inference found for one DM.
#[derive(Debug)]
pub struct DmTypes {
    /// Head parameters, by position (`None` for a non-variable argument).
    pub params: Vec<Option<VarTy>>,
    /// The incoming pipe, when typed situations read it (a variable in_arg).
    pub pipe: Option<VarTy>,
    pub locals: Vec<VarTy>,
    /// Per situation, in order: its typed plan or why it has none.
    pub situations: Vec<Result<TSit, String>>,
    /// Per situation, in order: whether it runs as generated code (it has
    /// a [MIR](crate::mir) plan), on native values when it also has a
    /// typed plan, on terms otherwise; else it is instantiated from its
    /// template at run time.
    pub code: Vec<bool>,
}

impl DmTypes {
    /// Whether some situation runs typed.
    pub fn any_typed(&self) -> bool {
        self.situations.iter().any(|s| s.is_ok())
    }
    /// Locals the typed situations use (indices into `locals`), in order.
    pub fn frame_locals(&self) -> Vec<usize> {
        let mut used = Vec::new();
        for s in self.situations.iter().flatten() {
            s.locals_used(&mut used);
        }
        used.sort_unstable();
        used.dedup();
        used
    }
    /// Whether a typed situation reads the pipe.
    pub fn frame_pipe(&self) -> bool {
        self.situations
            .iter()
            .flatten()
            .any(|s| s.uses(&|v| *v == TVal::Pipe))
    }
    /// Parameters the typed situations use, in order.
    pub fn frame_params(&self) -> Vec<usize> {
        let mut used = Vec::new();
        for s in self.situations.iter().flatten() {
            s.params_used(&mut used);
        }
        used.sort_unstable();
        used.dedup();
        used
    }
}

/// A typed value in a typed situation.
#[derive(Clone, Debug, PartialEq)]
pub enum TVal {
    /// The DM's local number `i` (in the frame).
    Local(usize),
    /// The DM's head parameter number `i` (in the frame).
    Param(usize),
    /// The incoming pipe, as the situation's variable in_arg (in the frame).
    Pipe,
    /// An arc variable bound by an earlier item (its store variable index).
    Var(u32),
    Int(i64),
    Float(f64),
    /// An atom (compared with `==`/`\==` against typed atoms).
    Atom(Atom),
}

/// A comparison in a typed conditional.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cmp {
    /// An arithmetic comparison of two numbers of one type.
    Arith(ArithCmp),
    /// `==` of two atoms.
    Identical,
    /// `\==` of two atoms.
    NotIdentical,
}

/// One element of a typed action list, or a typed action.
#[derive(Clone, Debug, PartialEq)]
pub enum TItem {
    /// `inc(n, V)`: the new value; `V` (fresh) takes it when `Some`.
    Inc { local: usize, bind: Option<u32> },
    /// `get(n, V)`: the value; `V` (fresh) takes it when `Some`.
    Get { local: usize, bind: Option<u32> },
    /// `set(n, C)`: C (a constant of the local's type) is the new value.
    Set { local: usize, value: Term },
    /// A constant (evaluates to itself).
    Const(Term),
}

/// What a typed arc does.
#[derive(Clone, Debug, PartialEq)]
pub enum TAction {
    /// A constant action (performed as one term).
    Const(Term),
    /// A written-out list: its elements evaluated and performed in order.
    List(Vec<TItem>),
}

/// An integer expression of a typed `prog` (`+`, `-`, `*` on ints, checked:
/// an overflow leaves the situation to the untyped path, which reports it).
#[derive(Clone, Debug, PartialEq)]
pub enum TExpr {
    /// An int operand (the pipe, a parameter, a constant).
    Val(TVal),
    /// `A op B`, `op` one of `+`, `-`, `*`.
    Bin(char, Box<TExpr>, Box<TExpr>),
}

impl TExpr {
    fn vals(&self, f: &mut dyn FnMut(&TVal)) {
        match self {
            TExpr::Val(v) => f(v),
            TExpr::Bin(_, a, b) => {
                a.vals(f);
                b.vals(f);
            }
        }
    }
}

/// A typed `prog`: `V is E` (alone or the only element of a list), `V` the
/// situation's out_arg variable, fresh, an int (arcs may read it), `E` an
/// int expression.
#[derive(Clone, Debug, PartialEq)]
pub struct TIs {
    /// `V`'s store variable index.
    pub var: u32,
    pub expr: TExpr,
}

/// A typed next situation.
#[derive(Clone, Debug, PartialEq)]
pub enum TNext {
    /// Situation `ix` of the DM, whose id is the atom.
    Sit(u32, Atom),
    /// `(A op B -> Then ; otherwise -> Else)` on typed numbers of one type,
    /// or `==`/`\==` on typed atoms.
    If {
        op: Cmp,
        float: bool,
        a: TVal,
        b: TVal,
        then: Box<TNext>,
        other: Box<TNext>,
    },
}

/// A typed arc.
#[derive(Clone, Debug, PartialEq)]
pub struct TArc {
    /// A constant expectation (no variables, evaluates to itself).
    pub expectation: Term,
    pub action: TAction,
    pub next: TNext,
}

/// A situation's typed plan.
#[derive(Clone, Debug, PartialEq)]
pub enum TSit {
    /// A final situation that leaves the pipe as it is.
    Final { id: Atom },
    /// A perceptual situation (`neutral` included).
    Perceptual {
        id: Atom,
        type_name: Atom,
        /// The neutral rule on one `empty` arc: always taken (D-14).
        always_first: bool,
        /// `prog ==> [V is E]`, run before the arc is chosen.
        prog: Option<TIs>,
        /// Whether the out_arg is `prog`'s `V` (the pipe after each arc).
        out_arg: bool,
        arcs: Vec<TArc>,
    },
    /// A recursive situation calling a DM by a constant `embedded_dm` (its
    /// name, or a call whose arguments evaluate to themselves), whose
    /// initial situation is typed: the callee's
    /// typed frame is pushed over the caller's (no Rust recursion), and the
    /// exit arcs (atom expectations, matched on the callee's final id) run
    /// on the caller's frame when it ends.
    Call {
        id: Atom,
        /// The callee's index in the program and its name.
        callee: (usize, Atom),
        /// The call: the callee's name, or a constant compound.
        call: Term,
        arcs: Vec<TArc>,
    },
}

impl TSit {
    pub fn id(&self) -> Atom {
        match self {
            TSit::Final { id } | TSit::Perceptual { id, .. } | TSit::Call { id, .. } => *id,
        }
    }

    /// The arcs of the plan (a call's exit arcs), none for a final situation.
    pub fn arcs(&self) -> &[TArc] {
        match self {
            TSit::Final { .. } => &[],
            TSit::Perceptual { arcs, .. } | TSit::Call { arcs, .. } => arcs,
        }
    }

    /// The constant terms the plan uses (expectations, actions, elements,
    /// set values, calls).
    pub fn constants(&self, out: &mut Vec<Term>) {
        if let TSit::Call { call, .. } = self {
            out.push(*call);
        }
        for arc in self.arcs() {
            out.push(arc.expectation);
            match &arc.action {
                TAction::Const(c) => out.push(*c),
                TAction::List(items) => {
                    for it in items {
                        match it {
                            TItem::Const(c) | TItem::Set { value: c, .. } => out.push(*c),
                            _ => {}
                        }
                    }
                }
            }
        }
    }

    fn locals_used(&self, out: &mut Vec<usize>) {
        for arc in self.arcs() {
            if let TAction::List(items) = &arc.action {
                for it in items {
                    match it {
                        TItem::Inc { local, .. }
                        | TItem::Get { local, .. }
                        | TItem::Set { local, .. } => out.push(*local),
                        TItem::Const(_) => {}
                    }
                }
            }
            arc.next.vals(&mut |v| {
                if let TVal::Local(i) = v {
                    out.push(*i)
                }
            });
        }
    }

    /// Whether an operand of the plan's conditionals satisfies `f`.
    pub(super) fn uses(&self, f: &dyn Fn(&TVal) -> bool) -> bool {
        let mut found = false;
        if let TSit::Perceptual { prog: Some(is), .. } = self {
            is.expr.vals(&mut |v| found |= f(v));
        }
        for arc in self.arcs() {
            arc.next.vals(&mut |v| found |= f(v));
        }
        found
    }

    fn params_used(&self, out: &mut Vec<usize>) {
        if let TSit::Perceptual { prog: Some(is), .. } = self {
            is.expr.vals(&mut |v| {
                if let TVal::Param(i) = v {
                    out.push(*i)
                }
            });
        }
        for arc in self.arcs() {
            arc.next.vals(&mut |v| {
                if let TVal::Param(i) = v {
                    out.push(*i)
                }
            });
        }
    }
}

impl TNext {
    fn vals(&self, f: &mut dyn FnMut(&TVal)) {
        if let TNext::If {
            a, b, then, other, ..
        } = self
        {
            f(a);
            f(b);
            then.vals(f);
            other.vals(f);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{check, ir, load};

    fn ir_of(src: &str) -> Ir {
        let (program, diags) = load::load_sources(&[("t.dm", src)]);
        let (result, diags) = check::check(program, diags);
        let checked = result.unwrap_or_else(|_| panic!("does not check: {diags:#?}"));
        ir::lower(&checked)
    }

    fn atoms(names: &[&str]) -> Ty {
        Ty::Atoms(names.iter().map(|n| Atom::intern(n)).collect())
    }

    #[test]
    fn the_lattice_joins() {
        assert_eq!(Ty::Int.join(&Ty::Int), Ty::Int);
        assert_eq!(Ty::None.join(&Ty::Float), Ty::Float);
        assert_eq!(Ty::Int.join(&Ty::Float), Ty::Term);
        assert_eq!(atoms(&["b"]).join(&atoms(&["a", "b"])), atoms(&["a", "b"]));
        assert_eq!(atoms(&["a"]).join(&Ty::Int), Ty::Term);
        let pos = |x: Ty| Ty::Shape(Atom::intern("pos"), vec![x, Ty::Float]);
        assert_eq!(
            pos(atoms(&["a"])).join(&pos(atoms(&["b"]))),
            pos(atoms(&["a", "b"]))
        );
        assert_eq!(pos(Ty::Int).join(&pos(Ty::Float)), Ty::Term);
        let many: Vec<Ty> = (0..=MAX_ATOMS)
            .map(|i| atoms(&[&format!("a{i}")]))
            .collect();
        let joined = many.iter().fold(Ty::None, |t, u| t.join(u));
        assert_eq!(joined, Ty::Term, "more atoms than MAX_ATOMS stay a term");
        assert_eq!(format!("{}", pos(atoms(&["b", "a"]))), "pos({b, a}, float)");
    }

    #[test]
    fn ground_terms_have_shapes() {
        let mut store = Store::new();
        let t = store.parse("p(1, 2.0, x, [a])").unwrap().0;
        assert_eq!(
            format!("{}", Ty::of_ground(&store, t)),
            "p(int, float, {x}, [{a} | {[]}])"
        );
        let v = store.parse("p(X)").unwrap().0;
        assert_eq!(Ty::of_ground(&store, v), Ty::Term);
        let big = store.parse("123456789012345678901234567890").unwrap().0;
        assert_eq!(Ty::of_ground(&store, big), Ty::Term);
    }

    const LOOP: &str = r#"
diag_mod(main(Max),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [inc(n, N), set(mode, busy)] => (N >= Max -> fs ; otherwise -> is) ] ],
    [ id ==> fs, type ==> final ] ],
  [ n ==> 0, mode ==> idle, f ==> 1.5, p ==> pos(1, 2), l ==> [], x ==> _ ]).
"#;

    #[test]
    fn locals_parameters_and_situations_are_typed() {
        let ir = ir_of(LOOP);
        let t = infer(&ir, &crate::mir::lower(&ir));
        let dm = &t.dms[0];
        let ty = |n: &str| &dm.locals.iter().find(|l| l.name == n).unwrap().ty;
        assert_eq!(*ty("n"), Ty::Int);
        assert_eq!(*ty("mode"), atoms(&["busy", "idle"]));
        assert_eq!(*ty("f"), Ty::Float);
        assert_eq!(format!("{}", ty("p")), "pos(int, int)");
        assert_eq!(*ty("x"), Ty::Term);
        assert_eq!(dm.params[0].as_ref().unwrap().ty, Ty::Int);
        assert_eq!(dm.params[0].as_ref().unwrap().name, "Max");
        let Ok(TSit::Perceptual {
            always_first, arcs, ..
        }) = &dm.situations[0]
        else {
            panic!("`is` is typed: {:?}", dm.situations[0]);
        };
        assert!(*always_first);
        assert!(matches!(
            &arcs[0].next,
            TNext::If {
                op: Cmp::Arith(ArithCmp::Ge),
                float: false,
                a: TVal::Var(_),
                b: TVal::Param(0),
                ..
            }
        ));
        assert!(matches!(dm.situations[1], Ok(TSit::Final { .. })));
        assert_eq!(dm.frame_locals(), vec![0, 1]);
        assert_eq!(dm.frame_params(), vec![0]);
    }

    #[test]
    fn what_stays_a_term_says_why() {
        let ir = ir_of(
            r#"
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [inc(n, _), set(n, done)] => is2 ] ],
    [ id ==> is2, type ==> neutral, in_arg ==> X,
      arcs ==> [ empty : [inc(k, _)] => s(X) ] ],
    [ id ==> s(_), type ==> neutral,
      arcs ==> [ empty : [inc(k, K)] => (K > 1.5 -> fs ; otherwise -> is2) ] ],
    [ id ==> fs, type ==> final ] ],
  [ n ==> 0, k ==> 0 ]).
"#,
        );
        let t = infer(&ir, &crate::mir::lower(&ir));
        let text = explain(&ir, &t);
        assert!(
            text.contains("local `n`: term (`set` to `done` (an atom of {done}) besides"),
            "{text}"
        );
        assert!(
            text.contains("situation `is`: code on terms (arc 1: local `n` is a term)"),
            "{text}"
        );
        // A variable in_arg is the pipe, typed like a parameter: what
        // leaves `is2` on terms is its next situation.
        assert!(
            text.contains(
                "situation `is2`: code on terms (arc 1: next situation `s(X)` is not an atom"
            ),
            "{text}"
        );
        assert!(
            text.contains("situation `s(_)`: code on terms (its id `s(_)` is not an atom)"),
            "{text}"
        );
        assert!(
            text.contains(
                "situation `fs`: code on terms (no other situation of the DM runs typed)"
            ),
            "{text}"
        );
    }

    #[test]
    fn the_summary_counts_code_and_native_values() {
        let ir = ir_of(
            r#"
diag_mod(main,
  [ [ id ==> is, type ==> recursive, embedded_dm ==> twice(a, a),
      arcs ==> [ fs : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(twice(X, X),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(X) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
        );
        let t = infer(&ir, &crate::mir::lower(&ir));
        let text = explain(&ir, &t);
        assert!(
            text.contains(
                "situation `is`: code on terms (it calls `twice`, whose parameters are not distinct variables)"
            ),
            "{text}"
        );
        assert!(
            text.contains(
                "situation `is`: template (instantiated at run time: its DM's parameters"
            ),
            "{text}"
        );
        assert!(
            text.ends_with(
                "situations on native values: 0/4\nsituations compiled as code: 2/4; variables typed: 0/2\n"
            ),
            "{text}"
        );
    }

    #[test]
    fn mixed_comparisons_and_opaque_writes() {
        let ir = ir_of(
            r#"
diag_mod(main(P),
  [ [ id ==> a, type ==> neutral,
      arcs ==> [ empty : [inc(k, K)] => (K > 1.5 -> b ; otherwise -> a) ] ],
    [ id ==> b, type ==> neutral,
      arcs ==> [ empty : [get(k, K)] => (P > K -> c ; otherwise -> b) ] ],
    [ id ==> c, type ==> neutral,
      arcs ==> [ empty : [get(f, F)] => (P > F -> fs ; otherwise -> c) ] ],
    [ id ==> fs, type ==> final, prog ==> [set(V, 1)] ] ],
  [ k ==> 0, f ==> 0.5 ]).
"#,
        );
        let t = infer(&ir, &crate::mir::lower(&ir));
        let text = explain(&ir, &t);
        assert!(
            text.contains(
                "situation `a`: code on terms (arc 1: `K>1.5` compares an int with a float)"
            ),
            "{text}"
        );
        assert!(
            text.contains(
                "situation `b`: code on terms (parameter `P` is compared both as an int and as a float)"
            ),
            "{text}"
        );
        assert!(
            text.contains("`set(V,1)` names its variable at run time: checked on load"),
            "{text}"
        );
        assert_eq!(t.dms[0].params[0].as_ref().unwrap().ty, Ty::Term);
    }
}
