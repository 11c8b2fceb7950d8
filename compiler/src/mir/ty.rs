//! Types on the MIR's registers (phase 1 of `docs/design/typed-mir.md`):
//! [`infer`] gives every register of every [`SitPlan`] a [`Ty`] of the
//! runtime's lattice, and so every DM parameter, every argument of a
//! compound situation id, every local and global, and the pipe where a
//! situation reads it; for each register left `Term` (or holding a term
//! inside, `list<term>`), a short reason.
//!
//! Invariant: inference reads the [`Ir`] and the [`Mir`] only, never
//! rejects a program and never panics; every type is an upper bound of
//! what the register can hold *where it is read*, under the rules below
//! (a register that may be unbound there is `Term`). Nothing uses these
//! types yet: the generated code and the interpreter run on terms (phases
//! 3 and 4 of the plan make them use them).
//!
//! The rules (a forward fixpoint over the plans, every fact joined, so it
//! ends: joins only grow and [`Ty`] is capped in depth):
//! - constants have their ground type (`[]` is `list<never>`, a proper
//!   list `list<T>`, another compound `f(T1..Tn)`, an integer outside
//!   `i64` `Term`); a compound built from registers is typed from them.
//! - **DM parameters**: the join over the call sites of the argument's
//!   type (the call evaluated as the machine does). The DM named `main`,
//!   a DM no situation calls (it can only be started from the command
//!   line), a recovery DM, a DM called from a situation without a plan and
//!   every DM when some call's DM is computed (not written as a name) are
//!   entered from outside ([`DmTypes::entry`]): their parameters and
//!   in_arg are `ground`, converted where the frame starts, under the
//!   boundary contract below (a failed check at entry runs the task on
//!   the term path from its start).
//! - **the pipe** is followed from situation to situation: what enters a
//!   situation is the join of what leaves its predecessors (an out_arg's
//!   value, else the pipe that came in; after a call, the callee's
//!   outgoing pipe); a DM's first situation receives the caller's pipe.
//! - **id arguments**: a compound id's argument is the join, over every
//!   next situation of the DM that can select it (same name and arity, or
//!   a value of unknown shape), of that value's argument; a variable met
//!   deeper in a pattern id is typed by matching structurally
//!   (`try([P|Ps])` selected by `list<T>` gives `P: T`, `Ps: list<T>`).
//!   A `ground` value selecting an id argument that is a list pattern
//!   (`[P|Ps]`, `[X, Y|T]`, `[X]`) gives it `list<ground>`, a checked
//!   narrowing (`ground` may be an improper list, `[a|b]`): a back end
//!   takes only a proper list into that situation and hands any other
//!   value to the machine, which selects as always; a situation the
//!   machine enters converts its id's parts with the checked conversion,
//!   which fails for such a value (the term path runs it). So the walk
//!   after it (`try(Ps)`) is over a typed list.
//!   The DM's first situation is entered by position with its id's
//!   variables unbound (D-4): its id arguments are `Term`, except one
//!   that is a parameter's variable too (`first(N)` in DM `bump(N)`),
//!   which the link (D-7) binds to the call's argument: the parameter's
//!   type when that is a value (`start_links`).
//! - **locals and globals**: the default's type joined with every write
//!   the DM's code makes (`set(n, E)`: E as written; `inc` keeps a number
//!   a number); a global is written by every DM where it is not a local.
//!   A Prolog user function may write a variable through `var_op`: the
//!   user functions' source is scanned, `var_op(set(name, ..))` makes
//!   `name` a `Term`, a `var_op` whose operation or name is not written
//!   there makes every local and global a `Term`; `var_op(get(..))` and
//!   `var_op(inc(..))` change no type. A function the host registers in
//!   Rust (`host_functions.pl`) may set any global: every global is a
//!   `Term` in a program that declares one (a local it sets is read back
//!   after the call). A situation without a plan writes
//!   what its template's `set(n, V)` terms say (V's type when ground).
//! - **fresh variables**: a variable not made from the id, the
//!   parameters or the pipe is typed by what binds it before its first
//!   read, in evaluation order (in_arg, prog, the call, then per arc the
//!   expectation, the action's elements in order, the next situation,
//!   out_arg): matching an exit arc's expectation against the callee's
//!   final ids (`found(P)` gives `P` the type of `found`'s argument; a
//!   final that cannot match adds nothing), an in_arg pattern (its
//!   variables the parts of the pipe's type there: a pipe it does not
//!   match is skipped by the machine, D-8, or its error, E14, under
//!   `--deny-warnings`; native code hands it any visit whose pattern
//!   it does not match), `get`/`inc`/`is` into a
//!   variable not made yet, the left side of `is` (an int or float when
//!   its operands are, else `ground`: the evaluator's number), a
//!   callee's final `diag_mod` (an output argument, below), or a boundary
//!   (below). One read before any of these leaves it `Term`. This is the
//!   question the checker's W0228 (`check/unbound.rs`) asks on the
//!   source; that analysis is coarser (anything inside an evaluated
//!   construct counts as bound, which is right for a warning and wrong for
//!   a type), so the order is followed here on the MIR, not shared.
//! - **no value** (`_`): a fresh variable that is not bound before it is
//!   read and occurs once in its plan (`_`, a name used once), and a
//!   parameter or id argument that nothing in the plan reads
//!   (`ask(.., _Answer, _Status)`, `understood(Answer, _)`), hold no
//!   value: the register stays `never` and is marked in
//!   [`SitTypes::unbound`] (shown `_`). Contract for the back ends: such a
//!   register holds nothing; the one term built from it (a call's
//!   argument, `apply(name_of(_), ..)`, `get(vocab, _)`) gets a fresh
//!   variable there. Where its value flows on (a DM parameter, a next
//!   situation's argument, the pipe, an arc's import) it counts as `Term`
//!   (maybe unbound), so no receiver is typed by it; but an out_arg that
//!   is such a variable nothing binds ([`super::OutPass::Unchanged`])
//!   passes the pipe on, which leaves with the incoming pipe's type.
//! - **output arguments** (D-20, D-23): a fresh variable given as an
//!   argument of a DM call, read nowhere before the call, is bound when
//!   the call returns by the callee's final `diag_mod` (`welcome(Items)`
//!   in DM `welcome(_Order)`): it takes the join of that argument over
//!   every final situation of the callee that binds it, when every final
//!   situation is planned and has a `diag_mod` of the DM's name and arity
//!   with a value there or has no `diag_mod` (it leaves the variable
//!   unbound: `spool(_Out)`'s `jammed`), one at least binding it, and no
//!   exit arc that may take a final leaving it (its expectation not a
//!   pattern no such final's id matches) mentions the variable (else it
//!   stays `Term`). The callee's parameter gets `Term` from it (unbound
//!   when the DM is called).
//! - **an expectation that is a pattern** (`said(Text)`, `success(X)`:
//!   constants and variables, nothing evaluated) is matched, not held:
//!   its expectation register stays `never`; a back end matches the
//!   perception or the callee's final id against the pattern and fills
//!   the pattern's registers (building the term only for a history or an
//!   observer, from the registers).
//! - **boundaries: `ground`, a checked conversion.** The value of a Prolog
//!   user function or of the evaluator (`apply(..)`, `assign(..)`, a goal
//!   the evaluator runs, a call argument it evaluates), what a perception
//!   binds (`said(X)`), and a fresh variable whose first occurrence is
//!   inside such a call or is an argument of an action of two or more
//!   arguments the robot performs (`navigate(Place, Result)`: a status)
//!   are [`Ty::Ground`]: any ground value, held natively (`Val` without
//!   its `Term` variant). `Ground` is also the join of different native
//!   shapes (`int ⊔ atom`). A user function whose clauses assign only
//!   ground terms or its arguments (`Ir::function_values`) gives the join
//!   of those instead (`atom`, `list<atom>`, ...): the target of the same
//!   checked conversion. A compound the evaluator rebuilds from its
//!   evaluated arguments (D-36) is typed from its arguments' values, each
//!   by these rules, whether written with variables or ground
//!   (`round(apply(rooms, []))`: `round(list<atom>)`, not `ground`). `is` over values not known to be numbers gives
//!   `ground` (the evaluator's number). **Contract** (the code generator
//!   and the interpreter follow it): the term is converted once, where it
//!   enters (after the call returns, the perception arrives, the action
//!   reports, the frame starts), with `Val::from_term(store, t, &ty)` to
//!   the register's type; when the check fails (the term is not ground: a
//!   user function returning an unbound variable, `said(_)` from a test
//!   script, a status the action left unbound; a big integer; a partial
//!   list; a value outside a user function's assigned shapes) the task
//!   does not go on natively: from that step on it runs on the term path
//!   (every live native value, registers, frames' parameters, locals,
//!   globals, the pipe, converted back with `Val::to_term`, as the
//!   instantiating path would hold them). So a typed register never holds
//!   a store term and no behaviour changes. A finer switch (that visit,
//!   that frame) is as sound only where every value flowing from the term
//!   path back into native code (a next situation's id, the pipe, locals
//!   and globals, a callee's final id and outputs) is converted with the
//!   same check, since the types below a failed check assumed it held.
//!   A back end that does not implement the guard must treat `ground` (and
//!   a boundary's narrower type) as `term`. Still `Term`: a DM computed at
//!   run time (its finals and pipe), a variable read before anything binds
//!   it, a value built from those.

use super::*;
use sitlog_runtime::native::Ty;

/// Whole-program iterations before giving up (every type `Term`): a
/// guard, the fixpoint ends long before.
const MAX_ROUNDS: usize = 1000;

/// A type and, when some part of it is `Term`, why.
#[derive(Clone, Debug, PartialEq)]
pub struct Typed {
    pub ty: Ty,
    pub why: Option<String>,
}

impl Typed {
    fn never() -> Typed {
        Typed {
            ty: Ty::Never,
            why: None,
        }
    }

    fn of(ty: Ty) -> Typed {
        Typed { ty, why: None }
    }

    fn term(why: impl Into<String>) -> Typed {
        Typed {
            ty: Ty::Term,
            why: Some(why.into()),
        }
    }

    /// Whether the value is held without a term anywhere in it.
    pub fn is_native(&self) -> bool {
        self.ty.is_native()
    }

    /// Joins `other` in; whether the type grew.
    fn absorb(&mut self, other: &Typed) -> bool {
        let joined = self.ty.join(&other.ty);
        if joined == self.ty {
            return false;
        }
        if !joined.is_native() && self.why.is_none() {
            self.why = other.why.clone().or_else(|| {
                Some(format!(
                    "{} and {} meet here",
                    show_ty(&self.ty),
                    show_ty(&other.ty)
                ))
            });
        }
        self.ty = joined;
        true
    }

    fn join(mut self, other: &Typed) -> Typed {
        self.absorb(other);
        self
    }
}

fn show_ty(t: &Ty) -> String {
    t.to_string()
}

/// The types of one situation that runs as code.
#[derive(Debug, Clone)]
pub struct SitTypes {
    /// Each register of the plan, by number.
    pub regs: Vec<Typed>,
    /// Each argument of a compound id (the values that can select it).
    pub id_args: Vec<Typed>,
    /// The pipe entering the situation.
    pub pipe: Typed,
    /// Whether the situation has an in_arg (reads the pipe).
    pub reads_pipe: bool,
    /// Per register: it holds no value (a variable met once and not
    /// bound before that use, `_`): its type stays `never`, the one place
    /// that builds a term from it makes a fresh variable there, and where
    /// that value flows (a call's argument, a next situation, the pipe) it
    /// is `term`, maybe unbound.
    pub unbound: Vec<bool>,
}

/// The types of one DM.
#[derive(Debug, Clone)]
pub struct DmTypes {
    /// Head arguments, by position.
    pub params: Vec<Typed>,
    /// The pipe the DM is started with.
    pub pipe_in: Typed,
    /// The pipe it hands back from its final situations.
    pub pipe_out: Typed,
    /// Its locals, in declaration order.
    pub locals: Vec<(Atom, Typed)>,
    /// Per situation, its types when it runs as code.
    pub sits: Vec<Option<SitTypes>>,
    /// Per parameter: when no situation of the DM reads it (every
    /// situation has a plan) and every final situation binds it through
    /// its `diag_mod` or has none (leaving it as the caller gave it,
    /// unbound for an output argument), one at least binding it, the type
    /// it has when a final that binds it returns (an output argument,
    /// `ask(.., _Answer, _Status)`); else `None`.
    pub outputs: Vec<Option<Typed>>,
    /// Why the DM can be started from outside the program's own calls
    /// (the command line, the machine, a computed call), if it can: its
    /// parameters and pipe are then converted where its frame starts.
    pub entry: Option<String>,
}

/// What [`infer`] found.
#[derive(Debug, Clone)]
pub struct MirTypes {
    pub dms: Vec<DmTypes>,
    pub globals: Vec<(Atom, Typed)>,
}

impl MirTypes {
    /// Registers typed natively (no term in their type) and all
    /// registers; situations with no register holding a term and all
    /// situations that run as code.
    pub fn counts(&self) -> (usize, usize, usize, usize) {
        let (mut typed, mut regs, mut clean, mut sits) = (0, 0, 0, 0);
        for s in self.dms.iter().flat_map(|d| d.sits.iter().flatten()) {
            sits += 1;
            regs += s.regs.len();
            let n = s.regs.iter().filter(|r| r.is_native()).count();
            typed += n;
            clean += usize::from(n == s.regs.len());
        }
        (typed, regs, clean, sits)
    }

    /// How the native registers are typed: with a shape (`int`, `atom`,
    /// `list<atom>`, `found(atom)`: no `ground` inside), holding `ground`
    /// somewhere (a boundary's checked value, a join of shapes), holding
    /// no value (`_`, unread, a matched pattern: `never`); and the
    /// situations whose registers all have a shape or no value.
    pub fn breakdown(&self) -> (usize, usize, usize, usize) {
        let (mut shaped, mut ground, mut none, mut sits) = (0, 0, 0, 0);
        for s in self.dms.iter().flat_map(|d| d.sits.iter().flatten()) {
            let mut all_shaped = true;
            for r in s.regs.iter().filter(|r| r.is_native()) {
                if r.ty == Ty::Never {
                    none += 1;
                } else if has_ground(&r.ty) {
                    ground += 1;
                    all_shaped = false;
                } else {
                    shaped += 1;
                }
            }
            all_shaped &= s.regs.iter().all(Typed::is_native);
            sits += usize::from(all_shaped);
        }
        (shaped, ground, none, sits)
    }

    /// Variables typed natively and all variables: every DM parameter,
    /// the pipe of every DM one of whose situations reads it (in_arg),
    /// every local, every global.
    pub fn var_counts(&self) -> (usize, usize) {
        let (mut typed, mut all) = (0, 0);
        let mut count = |t: &Typed| {
            all += 1;
            typed += usize::from(t.is_native());
        };
        for d in &self.dms {
            for (i, p) in d.params.iter().enumerate() {
                match d.outputs.get(i).and_then(Option::as_ref) {
                    Some(out) if !p.is_native() => count(out),
                    _ => count(p),
                }
            }
            if d.sits.iter().flatten().any(|s| s.reads_pipe) {
                count(&d.pipe_in);
            }
            d.locals.iter().for_each(|(_, t)| count(t));
        }
        self.globals.iter().for_each(|(_, t)| count(t));
        (typed, all)
    }

    /// The `--explain-types` summary line of this inference.
    pub fn summary(&self) -> String {
        let (typed, regs, clean, sits) = self.counts();
        let (vars_typed, vars) = self.var_counts();
        let (shaped, ground, none, shaped_sits) = self.breakdown();
        format!(
            "MIR registers typed: {typed}/{regs} ({shaped} with a shape, {ground} ground, {none} no value); \
             situations with no term register: {clean}/{sits} ({shaped_sits} without ground); \
             variables with a MIR type: {vars_typed}/{vars} (MIR inference)"
        )
    }

    /// The `--explain-types` line of DM `dm` (its parameters, pipe and
    /// locals as inferred on the MIR).
    pub fn dm_line(&self, ir: &Ir, dm: usize) -> String {
        let d = &self.dms[dm];
        let idm = &ir.dms[dm];
        let mut parts = Vec::new();
        let params: Vec<String> = d
            .params
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let name = ir
                    .store
                    .args(idm.head)
                    .get(i)
                    .map(|&t| var_text(ir, idm, t))
                    .unwrap_or_default();
                match d.outputs.get(i).and_then(Option::as_ref) {
                    Some(out) => format!(
                        "{name}: {} (an output: {} when it returns)",
                        with_why(p),
                        out.ty
                    ),
                    None => format!("{name}: {}", with_why(p)),
                }
            })
            .collect();
        if !params.is_empty() {
            parts.push(format!("parameters {}", params.join(", ")));
        }
        parts.push(format!("pipe in {}", with_why(&d.pipe_in)));
        parts.push(format!("pipe out {}", with_why(&d.pipe_out)));
        if !d.locals.is_empty() {
            let l: Vec<String> = d
                .locals
                .iter()
                .map(|(n, t)| format!("{}: {}", n.as_str(), with_why(t)))
                .collect();
            parts.push(format!("locals {}", l.join(", ")));
        }
        if let Some(why) = &d.entry {
            parts.push(format!(
                "entered from outside ({why}): parameters and pipe checked ground where the frame starts"
            ));
        }
        format!("  MIR types: {}", parts.join("; "))
    }

    /// The `--explain-types` line of situation `sit` of DM `dm`: its
    /// registers' types, how many hold a term and why.
    pub fn sit_line(&self, dm: usize, sit: usize) -> String {
        let Some(s) = &self.dms[dm].sits[sit] else {
            return "    MIR: no plan (instantiated from its template)".to_owned();
        };
        let tys: Vec<String> = s
            .regs
            .iter()
            .enumerate()
            .map(|(i, r)| {
                if s.unbound.get(i).copied().unwrap_or(false) && r.ty == Ty::Never {
                    format!("r{i} _")
                } else {
                    format!("r{i} {}", r.ty)
                }
            })
            .collect();
        let n = s.regs.len();
        let typed = s.regs.iter().filter(|r| r.is_native()).count();
        let mut line = format!("    MIR registers {typed}/{n} typed");
        if n > 0 {
            line.push_str(&format!(" [{}]", tys.join(", ")));
        }
        if !s.id_args.is_empty() {
            let a: Vec<String> = s.id_args.iter().map(|t| t.ty.to_string()).collect();
            line.push_str(&format!("; id arguments ({})", a.join(", ")));
        }
        if s.reads_pipe {
            line.push_str(&format!("; pipe in {}", s.pipe.ty));
        }
        // The reasons, grouped: `term: r3, r5 (why); r4 (why)`.
        let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
        for (i, r) in s.regs.iter().enumerate() {
            if r.is_native() {
                continue;
            }
            let why = r.why.clone().unwrap_or_else(|| "no reason kept".to_owned());
            match groups.iter_mut().find(|(w, _)| *w == why) {
                Some((_, regs)) => regs.push(i),
                None => groups.push((why, vec![i])),
            }
        }
        if !groups.is_empty() {
            let g: Vec<String> = groups
                .iter()
                .map(|(why, regs)| {
                    let rs: Vec<String> = regs.iter().map(|r| format!("r{r}")).collect();
                    format!("{} ({why})", rs.join(", "))
                })
                .collect();
            line.push_str(&format!("; term: {}", g.join("; ")));
        }
        line
    }
}

fn with_why(t: &Typed) -> String {
    match &t.why {
        Some(w) if !t.is_native() => format!("{} ({w})", t.ty),
        _ => t.ty.to_string(),
    }
}

fn var_text(ir: &Ir, dm: &IrDm, t: Term) -> String {
    match ir.store.value(t) {
        Value::Var(v) => dm
            .var_index_names
            .iter()
            .find(|(i, _)| *i == v.index())
            .map_or_else(|| format!("_G{}", v.index()), |(_, n)| n.clone()),
        _ => ir.store.writeq(t),
    }
}

/// Whether `ground` occurs in `t`.
fn has_ground(t: &Ty) -> bool {
    match t {
        Ty::Ground => true,
        Ty::List(e) => has_ground(e),
        Ty::Tagged(_, args) => args.iter().any(has_ground),
        _ => false,
    }
}

/// The type of a ground term of `store`.
pub fn of_ground(store: &Store, t: Term) -> Ty {
    of_ground_at(store, t, 0)
}

fn of_ground_at(store: &Store, t: Term, depth: usize) -> Ty {
    if depth > sitlog_runtime::native::MAX_DEPTH {
        return Ty::Term;
    }
    match store.value(t) {
        Value::Int(_) => Ty::Int,
        Value::Float(_) => Ty::Float,
        Value::Atom(a) if a == atoms::NIL => Ty::list(Ty::Never),
        Value::Atom(_) => Ty::Sym,
        Value::Compound(name, &[_, _]) if name == atoms::DOT => {
            // Along the spine without recursion (a list may be long).
            let mut elem = Ty::Never;
            let mut rest = t;
            loop {
                match store.value(rest) {
                    Value::Compound(name, &[h, tl]) if name == atoms::DOT => {
                        elem = elem.join(&of_ground_at(store, h, depth + 1));
                        rest = tl;
                    }
                    Value::Atom(a) if a == atoms::NIL => return Ty::list(elem),
                    _ => return Ty::Term,
                }
            }
        }
        Value::Compound(name, args) => Ty::tagged(
            name,
            args.iter()
                .map(|&a| of_ground_at(store, a, depth + 1))
                .collect(),
        ),
        Value::Var(_) | Value::BigInt(_) => Ty::Term,
    }
}

/// `f(args..)` as a type: a list cell is a list when its tail is one.
fn compound_ty(name: Atom, args: Vec<Typed>) -> Typed {
    if name == atoms::DOT && args.len() == 2 {
        return match &args[1].ty {
            Ty::List(e) => {
                let ty = Ty::list(args[0].ty.join(e));
                let why = args[0].why.clone().or_else(|| args[1].why.clone());
                Typed { ty, why }
            }
            Ty::Term => Typed::term(
                args[1]
                    .why
                    .clone()
                    .unwrap_or_else(|| "a list whose tail may not be a list".to_owned()),
            ),
            // No value reaches the tail (yet): none reaches the cell.
            Ty::Never => Typed::never(),
            // An improper list of ground values (`[a|b]`, or a tail that is
            // any ground value) is ground.
            _ if args[0].ty.is_native() && args[1].ty.is_native() => Typed::of(Ty::Ground),
            _ => Typed::term("a partial list (its tail is not a list)"),
        };
    }
    let why = args.iter().find_map(|a| a.why.clone());
    let ty = Ty::tagged(name, args.into_iter().map(|a| a.ty).collect());
    let why = if ty.is_native() { None } else { why };
    Typed {
        why: why.or_else(|| (!ty.is_native()).then(|| "a term nested too deep".to_owned())),
        ty,
    }
}

/// The argument types of a value of type `t` with functor `name/n`, or
/// `None` when no such value has that type.
fn args_of(t: &Typed, name: Atom, n: usize) -> Option<Vec<Typed>> {
    match &t.ty {
        Ty::Never => None,
        Ty::Term => Some(vec![t.clone(); n]),
        // A ground `[H|T]` may be an improper list (`[a|b]`): its tail is
        // any ground value, not a list.
        Ty::Ground => Some(vec![Typed::of(Ty::Ground); n]),
        Ty::List(e) if name == atoms::DOT && n == 2 => Some(vec![
            Typed {
                ty: (**e).clone(),
                why: t.why.clone(),
            },
            t.clone(),
        ]),
        Ty::Tagged(f, args) if *f == name && args.len() == n => Some(
            args.iter()
                .map(|a| Typed {
                    ty: a.clone(),
                    why: t.why.clone(),
                })
                .collect(),
        ),
        _ => None,
    }
}

/// A `ground` value that an id's list pattern takes apart (`[P|Ps]`,
/// `[X, Y|T]`, `[X]`: cells ending in a variable or `[]`) is a proper list
/// of ground values there, `list<ground>`: a checked narrowing. A back end
/// takes only a proper list into such a situation (a `ground` value that
/// is an improper list, `[a|b]`, is handed to the machine, which selects
/// as always, and a situation entered by the machine with one converts
/// its id's parts with the checked conversion, which fails: the term path
/// runs it). So the walk `try(Ps)` after it is over a typed list. Any
/// other value or pattern: the value's own type.
fn narrowed_by_list_pattern(store: &Store, v: &Typed, pat: Term) -> Typed {
    if v.ty != Ty::Ground {
        return v.clone();
    }
    let mut cur = pat;
    let mut cells = 0;
    while let Value::Compound(name, &[_, tail]) = store.value(cur) {
        if name != atoms::DOT {
            break;
        }
        cells += 1;
        cur = tail;
    }
    let ends_as_list = match store.value(cur) {
        Value::Var(_) => true,
        Value::Atom(a) => a == atoms::NIL,
        _ => false,
    };
    if cells > 0 && ends_as_list {
        Typed::of(Ty::list(Ty::Ground))
    } else {
        v.clone()
    }
}

/// Whether a value of type `t` can be the atom `a`.
fn can_be_atom(t: &Ty, a: Atom) -> bool {
    match t {
        Ty::Sym => a != atoms::NIL,
        Ty::List(_) => a == atoms::NIL,
        Ty::Term | Ty::Ground => true,
        _ => false,
    }
}

/// The arithmetic result of `expr` (`is`): an int, a float or a term.
fn arith_ty(expr: &Build, reg: &dyn Fn(Reg) -> Ty, store: &Store) -> Ty {
    fn go(e: &Build, reg: &dyn Fn(Reg) -> Ty, store: &Store, depth: usize) -> Ty {
        if depth > MAX_DEPTH {
            return Ty::Term;
        }
        match e {
            Build::Const(t) => match store.value(*t) {
                Value::Int(_) => Ty::Int,
                Value::Float(_) => Ty::Float,
                Value::Compound(..) => {
                    // A ground expression: its shape decides as below.
                    Ty::Term
                }
                _ => Ty::Term,
            },
            // No value yet (the fixpoint has not reached it): none either.
            Build::Reg(r) => match reg(*r) {
                t @ (Ty::Int | Ty::Float | Ty::Never) => t,
                _ => Ty::Term,
            },
            Build::Compound(op, args) => {
                let tys: Vec<Ty> = args.iter().map(|a| go(a, reg, store, depth + 1)).collect();
                if tys.contains(&Ty::Never) {
                    return Ty::Never;
                }
                let all_int = tys.iter().all(|t| *t == Ty::Int);
                let numeric = tys.iter().all(|t| matches!(t, Ty::Int | Ty::Float));
                match (op.as_str(), args.len()) {
                    ("+" | "-" | "*" | "min" | "max", 2) | ("-" | "+" | "abs" | "sign", 1) => {
                        if all_int {
                            Ty::Int
                        } else if numeric {
                            Ty::Float
                        } else {
                            Ty::Term
                        }
                    }
                    ("//" | "mod" | "rem", 2) if all_int => Ty::Int,
                    ("/", 2) if numeric && !all_int => Ty::Float,
                    _ => Ty::Term,
                }
            }
        }
    }
    go(expr, reg, store, 0)
}

/// The whole-program state of the fixpoint.
struct State<'a> {
    ir: &'a Ir,
    mir: &'a Mir,
    t: MirTypes,
    /// Whether the current round made a type grow.
    changed: bool,
    /// Names written by Prolog user functions through `var_op`
    /// (`None`: some name unknown, every variable).
    prolog_writes: Option<Vec<Atom>>,
    /// Per DM, per planned situation: how often each register occurs in
    /// its plan ([`occurrences`]).
    occ: Vec<Vec<Vec<u32>>>,
}

/// Runs inference over a lowered program and its MIR.
pub fn infer(ir: &Ir, mir: &Mir) -> MirTypes {
    let store = &ir.store;
    let dms = ir
        .dms
        .iter()
        .enumerate()
        .map(|(d, dm)| DmTypes {
            params: vec![Typed::never(); store.args(dm.head).len()],
            pipe_in: Typed::never(),
            pipe_out: Typed::never(),
            locals: dm
                .locals
                .iter()
                .map(|&(n, t)| (n, default_ty(store, t)))
                .collect(),
            outputs: vec![None; store.args(dm.head).len()],
            entry: None,
            sits: (0..dm.situations.len())
                .map(|s| {
                    mir.dms
                        .get(d)
                        .and_then(|p| p.get(s))
                        .and_then(Option::as_ref)
                        .map(|p| SitTypes {
                            regs: vec![Typed::never(); p.regs],
                            id_args: vec![Typed::never(); p.id.1],
                            pipe: Typed::never(),
                            reads_pipe: p.in_arg.is_some(),
                            unbound: vec![false; p.regs],
                        })
                })
                .collect(),
        })
        .collect();
    let globals = ir
        .globals
        .iter()
        .map(|&(n, t)| (n, default_ty(store, t)))
        .collect();
    let mut st = State {
        ir,
        mir,
        t: MirTypes { dms, globals },
        changed: false,
        prolog_writes: prolog_writes(ir),
        occ: mir
            .dms
            .iter()
            .map(|plans| {
                plans
                    .iter()
                    .map(|p| p.as_ref().map(occurrences).unwrap_or_default())
                    .collect()
            })
            .collect(),
    };
    st.entries();
    let mut rounds = 0;
    loop {
        st.changed = false;
        st.round();
        if !st.changed {
            break;
        }
        rounds += 1;
        if rounds >= MAX_ROUNDS {
            st.give_up();
            break;
        }
    }
    st.outputs();
    st.t
}

fn default_ty(store: &Store, t: Term) -> Typed {
    let ty = of_ground(store, t);
    if ty.is_native() {
        Typed::of(ty)
    } else {
        Typed {
            ty,
            why: Some(format!("default `{}`", store.writeq(t))),
        }
    }
}

/// What the Prolog user functions write through `var_op` (see the module doc).
fn prolog_writes(ir: &Ir) -> Option<Vec<Atom>> {
    prolog_writes_in(ir.prolog_sources.iter().map(|f| f.text.as_str()))
}

/// [`prolog_writes`] of these Prolog texts.
fn prolog_writes_in<'t>(texts: impl Iterator<Item = &'t str>) -> Option<Vec<Atom>> {
    let mut names = Vec::new();
    for text in texts {
        let mut rest = text;
        while let Some(i) = rest.find("var_op(") {
            rest = &rest[i + "var_op(".len()..];
            let op = rest.trim_start();
            if op.starts_with("get(") || op.starts_with("inc(") {
                continue;
            }
            let after = op.strip_prefix("set(")?;
            let after = after.trim_start();
            let name: String = after
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.starts_with(|c: char| c.is_ascii_lowercase()) {
                return None;
            }
            names.push(Atom::intern(&name));
        }
    }
    Some(names)
}

impl<'a> State<'a> {
    fn store(&self) -> &'a Store {
        &self.ir.store
    }

    /// Entry DMs get `Term` parameters and pipe; Prolog writes make their
    /// variables `Term`.
    fn entries(&mut self) {
        let ir = self.ir;
        let mut called = vec![false; ir.dms.len()];
        let mut computed = false;
        for plans in &self.mir.dms {
            for p in plans.iter().flatten() {
                if let KindPlan::Recursive { call, .. } = &p.kind {
                    match self.callee(call) {
                        Some(d) => called[d] = true,
                        None => computed = true,
                    }
                }
            }
        }
        // A recursive situation without a plan calls a DM we do not see.
        for (d, dm) in ir.dms.iter().enumerate() {
            for (s, sit) in dm.situations.iter().enumerate() {
                if sit.kind == Kind::Recursive && self.mir.plan(d as u32, s as SitIx).is_none() {
                    let e = self.store().args(sit.template)[EMBEDDED_DM];
                    match self.store().functor(e).and_then(|(n, _)| ir.dm_by_name(n)) {
                        Some(c) => {
                            called[c as usize] = true;
                            let why = "called from a situation instantiated from its template";
                            self.entry(c as usize, why);
                        }
                        None => computed = true,
                    }
                }
            }
        }
        let recovery: Vec<Atom> = ir.recovery.iter().map(|&(_, dm)| dm).collect();
        for (d, dm) in ir.dms.iter().enumerate() {
            let why = if computed {
                Some("some call's DM is computed at run time")
            } else if dm.name.as_str() == "main" {
                Some("the main DM: the command line gives it")
            } else if recovery.contains(&dm.name) {
                Some("a recovery DM: the machine starts it")
            } else if !called[d] {
                Some("no situation calls this DM: the command line starts it")
            } else {
                None
            };
            if let Some(why) = why {
                self.entry(d, why);
            }
        }
        // A function the host registers in Rust may set a global through
        // `var_op` to a value of any type, unseen here; a local it sets is
        // read back after the call, a global is read where it is used.
        if !self.ir.host_functions.is_empty() {
            let why =
                "a function the host registers (host_functions.pl) may set a global (`var_op`)";
            for (_, g) in &mut self.t.globals {
                g.absorb(&Typed::term(why));
            }
        }
        match self.prolog_writes.clone() {
            None => {
                let why = "a Prolog user function writes a variable named at run time (`var_op`)";
                for d in &mut self.t.dms {
                    for (_, l) in &mut d.locals {
                        l.absorb(&Typed::term(why));
                    }
                }
                for (_, g) in &mut self.t.globals {
                    g.absorb(&Typed::term(why));
                }
            }
            Some(names) => {
                for name in names {
                    let why = format!("a Prolog user function sets `{}` (`var_op`)", name.as_str());
                    for d in &mut self.t.dms {
                        for (n, l) in &mut d.locals {
                            if *n == name {
                                l.absorb(&Typed::term(why.clone()));
                            }
                        }
                    }
                    for (n, g) in &mut self.t.globals {
                        if *n == name {
                            g.absorb(&Typed::term(why.clone()));
                        }
                    }
                }
            }
        }
    }

    /// DM `d` can be started from outside the program's own calls: its
    /// parameters and pipe are converted where the frame starts (checked,
    /// `ground`; see the module doc).
    fn entry(&mut self, d: usize, why: &str) {
        let dm = &mut self.t.dms[d];
        for p in &mut dm.params {
            p.absorb(&Typed::of(Ty::Ground));
        }
        dm.pipe_in.absorb(&Typed::of(Ty::Ground));
        if dm.entry.is_none() {
            dm.entry = Some(why.to_owned());
        }
    }

    fn give_up(&mut self) {
        let why = Typed::term("inference did not settle");
        for d in &mut self.t.dms {
            for t in d
                .params
                .iter_mut()
                .chain([&mut d.pipe_in, &mut d.pipe_out])
                .chain(d.locals.iter_mut().map(|(_, t)| t))
            {
                t.absorb(&why);
            }
            for s in d.sits.iter_mut().flatten() {
                for t in s.regs.iter_mut().chain(&mut s.id_args).chain([&mut s.pipe]) {
                    t.absorb(&why);
                }
            }
        }
    }

    /// The DM a call names, when it is written as a name.
    fn callee(&self, call: &Build) -> Option<usize> {
        let name = match call {
            Build::Const(t) => self
                .store()
                .atom_of(*t)
                .or_else(|| self.store().functor(*t).map(|f| f.0))?,
            Build::Compound(name, _) => *name,
            Build::Reg(_) => return None,
        };
        self.ir.dm_by_name(name).map(|d| d as usize)
    }

    /// One pass over every plan; sets `changed` when a type grew.
    fn round(&mut self) {
        for d in 0..self.ir.dms.len() {
            // A DM's first situation receives its entry pipe.
            let pipe_in = self.t.dms[d].pipe_in.clone();
            // An id argument that is a parameter's variable (`first(N)`
            // in DM `count(N)`) is then linked with the call's argument
            // (D-7): bound to it, so of its type when that is a value.
            let linked = self
                .mir
                .plan(d as u32, 0)
                .map(start_links)
                .unwrap_or_default();
            let params = self.t.dms[d].params.clone();
            if let Some(s0) = self.t.dms[d].sits.first_mut().and_then(Option::as_mut) {
                self.changed |= s0.pipe.absorb(&pipe_in);
                let why =
                    Typed::term("the DM's first situation is entered with its id unbound (D-4)");
                for (i, a) in s0.id_args.iter_mut().enumerate() {
                    let param = linked
                        .iter()
                        .find(|(x, _)| *x == i)
                        .and_then(|&(_, j)| params.get(j))
                        .filter(|t| t.is_native());
                    self.changed |= a.absorb(param.unwrap_or(&why));
                }
            }
            let mir = self.mir;
            for s in 0..self.ir.dms[d].situations.len() {
                match mir.plan(d as u32, s as SitIx) {
                    Some(p) => self.situation(d, s, p),
                    None => self.unplanned(d, s),
                }
            }
        }
    }

    /// A situation instantiated from its template: what leaves it is unknown.
    fn unplanned(&mut self, d: usize, s: usize) {
        let why = Typed::term("a situation of the DM is instantiated from its template");
        let ir = self.ir;
        let sit = &ir.dms[d].situations[s];
        // Its writes: `set(n, V)` anywhere in it (V's type when ground).
        self.scan_const_writes(d, sit.template);
        if sit.kind == Kind::Final {
            self.changed |= self.t.dms[d].pipe_out.absorb(&why);
        }
        for t in self.t.dms[d].sits.iter_mut().flatten() {
            self.changed |= t.pipe.absorb(&why);
            for a in &mut t.id_args {
                self.changed |= a.absorb(&why);
            }
        }
    }

    /// The value of register `r` where it is read or flows on (a
    /// register that holds no value is an unbound variable there).
    fn reg(&self, d: usize, s: usize, r: Reg) -> Typed {
        let Some(t) = self.t.dms[d].sits[s].as_ref() else {
            return Typed::never();
        };
        if t.unbound.get(r as usize).copied().unwrap_or(false) {
            return Typed::term(UNBOUND_WHY);
        }
        t.regs.get(r as usize).cloned().unwrap_or_else(Typed::never)
    }

    /// Register `r` is fresh and not bound before it is read: it holds no
    /// value when it occurs once (`_`), else it is a term.
    fn unbound_or_term(&mut self, d: usize, s: usize, r: Reg, why: &Typed) {
        let once = self.occ[d][s].get(r as usize).is_some_and(|&n| n <= 1);
        if once {
            if let Some(slot) = self.t.dms[d].sits[s]
                .as_mut()
                .and_then(|x| x.unbound.get_mut(r as usize))
            {
                self.changed |= !*slot;
                *slot = true;
            }
        } else {
            self.def(d, s, r, why);
        }
    }

    fn def(&mut self, d: usize, s: usize, r: Reg, t: &Typed) {
        if let Some(slot) = self.t.dms[d].sits[s]
            .as_mut()
            .and_then(|x| x.regs.get_mut(r as usize))
        {
            self.changed |= slot.absorb(t);
        }
    }

    /// The local (or else global) variable `name` seen from DM `d`.
    fn var(&self, d: usize, name: Atom) -> Typed {
        if let Some((_, t)) = self.t.dms[d].locals.iter().find(|(n, _)| *n == name) {
            return t.clone();
        }
        if let Some((_, t)) = self.t.globals.iter().find(|(n, _)| *n == name) {
            return t.clone();
        }
        // An unknown name: its value is a fresh unbound variable (the
        // evaluator's `var_op_parts`, as the original runs on).
        Typed::term(
            "a `get`, `set` or `inc` of a variable neither local nor global (an unbound value)",
        )
    }

    fn write_var(&mut self, d: usize, name: Atom, t: &Typed) {
        let t = if t.is_native() {
            t.clone()
        } else {
            Typed {
                ty: t.ty.clone(),
                why: Some(format!(
                    "`set` to a term ({})",
                    t.why.as_deref().unwrap_or("no reason kept")
                )),
            }
        };
        if let Some((_, slot)) = self.t.dms[d].locals.iter_mut().find(|(n, _)| *n == name) {
            self.changed |= slot.absorb(&t);
        } else if let Some((_, slot)) = self.t.globals.iter_mut().find(|(n, _)| *n == name) {
            self.changed |= slot.absorb(&t);
        }
    }

    fn build_ty(&self, d: usize, s: usize, b: &Build) -> Typed {
        match b {
            Build::Const(t) => {
                let ty = of_ground(self.store(), *t);
                if ty.is_native() {
                    Typed::of(ty)
                } else {
                    Typed {
                        ty,
                        why: Some("a constant not ground or too deep".to_owned()),
                    }
                }
            }
            Build::Reg(r) => self.reg(d, s, *r),
            Build::Compound(name, args) => {
                compound_ty(*name, args.iter().map(|a| self.build_ty(d, s, a)).collect())
            }
        }
    }

    /// Writes hidden in a term the evaluator runs (`set(n, V)` in the
    /// arguments of `apply`, a conditional's goal).
    fn scan_writes(&mut self, d: usize, s: usize, b: &Build, depth: usize) {
        if depth > MAX_DEPTH {
            return;
        }
        match b {
            Build::Const(t) => self.scan_const_writes(d, *t),
            Build::Reg(_) => {}
            Build::Compound(name, args) => {
                if *name == atoms::SET && args.len() == 2 {
                    if let Build::Const(n) = &args[0] {
                        if let Some(n) = self.store().atom_of(*n) {
                            let t = self.build_ty(d, s, &args[1]);
                            self.write_var(d, n, &t);
                        }
                    }
                }
                for a in args.iter() {
                    self.scan_writes(d, s, a, depth + 1);
                }
            }
        }
    }

    fn scan_const_writes(&mut self, d: usize, t: Term) {
        let store = self.store();
        let mut stack = vec![(t, 0)];
        while let Some((u, depth)) = stack.pop() {
            if depth > MAX_DEPTH {
                continue;
            }
            if let Value::Compound(name, args) = store.value(u) {
                if name == atoms::SET && args.len() == 2 {
                    if let Some(n) = store.atom_of(args[0]) {
                        let ty = of_ground(store, args[1]);
                        let ty = if ty.is_native() {
                            Typed::of(ty)
                        } else {
                            Typed {
                                ty,
                                why: Some("a value not ground where it is written".to_owned()),
                            }
                        };
                        self.write_var(d, n, &ty);
                    }
                }
                stack.extend(args.iter().map(|&a| (a, depth + 1)));
            }
        }
    }

    /// The value of evaluating `e`; records what it binds and writes.
    fn ev(&mut self, d: usize, s: usize, e: &Ev) -> Typed {
        match e {
            Ev::Value(r) => self.reg(d, s, *r),
            Ev::Built(b) => self.build_ty(d, s, b),
            Ev::Eval(b) => {
                if let Some((op, name, arg)) = self.var_op_of(d, s, b) {
                    // `set(n, c)` written out: a variable operation.
                    return self.var_op_value(d, op, name, Some(arg));
                }
                self.scan_writes(d, s, b, 0);
                self.eval_build(d, s, b)
            }
            Ev::If(c, a, b) | Ev::Pick(c, a, b) => {
                self.cond(d, s, c);
                let a = self.ev(d, s, a);
                let b = self.ev(d, s, b);
                a.join(&b)
            }
            Ev::VarOpFresh { op, name, dst } => {
                let v = self.var_op_value(d, *op, *name, None);
                self.def(d, s, *dst, &v);
                v
            }
            Ev::VarOp { op, name, arg } => {
                let arg = self.build_ty(d, s, arg);
                self.var_op_value(d, *op, *name, Some(arg))
            }
            Ev::IsFresh { expr, dst } => {
                let v = self.is_ty(d, s, expr);
                self.def(d, s, *dst, &v);
                v
            }
            // `V = E`: `V` takes `E`'s term as built (D-30).
            Ev::BindFresh { expr, dst } => {
                let v = self.build_ty(d, s, expr);
                self.def(d, s, *dst, &v);
                v
            }
            Ev::Is { lhs, expr } => {
                let v = self.is_ty(d, s, expr);
                if let Build::Reg(r) = lhs {
                    // `V is E` binds a fresh V (or compares a bound one).
                    self.def(d, s, *r, &v);
                }
                v
            }
            Ev::Compound(name, args) => {
                let args = args.iter().map(|a| self.ev(d, s, a)).collect();
                compound_ty(*name, args)
            }
        }
    }

    /// The value of `apply(f(..), Args)` when every value user function
    /// `f`'s clauses assign is a ground term or one of its arguments
    /// (`Ir::function_values`) of a native type: the join of those (the
    /// target of the checked conversion where the value enters; a value
    /// of another type fails the check like a non-ground one).
    fn function_value(&self, d: usize, s: usize, b: &Build) -> Option<Typed> {
        let Build::Compound(apply, parts) = b else {
            return None;
        };
        if apply.as_str() != "apply" || parts.len() != 2 {
            return None;
        }
        let store = self.store();
        let (name, arity) = match &parts[0] {
            Build::Const(t) => store.functor(*t)?,
            Build::Compound(name, args) => (*name, args.len()),
            Build::Reg(_) => return None,
        };
        let values = self
            .ir
            .function_values
            .iter()
            .find(|f| f.name == name && f.arity == arity)?
            .values
            .as_ref()?;
        // The argument list, element by element.
        let mut args: Vec<Build> = Vec::new();
        let mut rest = clone_build(&parts[1]);
        loop {
            match rest {
                Build::Compound(dot, mut cell) if dot == atoms::DOT && cell.len() == 2 => {
                    let tail = std::mem::replace(&mut cell[1], Build::Const(Term::NIL));
                    args.push(std::mem::replace(&mut cell[0], Build::Const(Term::NIL)));
                    rest = tail;
                }
                Build::Const(t) => {
                    args.extend(store.list_to_vec(t)?.into_iter().map(Build::Const));
                    break;
                }
                _ => return None,
            }
        }
        let mut out = Typed::never();
        for v in values {
            let t = match *v {
                crate::ir::IrFnValue::Term(t) => Typed::of(of_ground(store, t)),
                crate::ir::IrFnValue::Arg(i) => self.eval_build(d, s, args.get(i)?),
            };
            out.absorb(&t);
        }
        (out.is_native() && out.ty != Ty::Never).then_some(out)
    }

    /// `get`/`set`/`inc` of a named variable, as a term the evaluator
    /// runs: the operation, the name and the argument's type.
    fn var_op_of(&self, d: usize, s: usize, b: &Build) -> Option<(Atom, Atom, Typed)> {
        let ops = [atoms::GET, atoms::SET, atoms::INC];
        match b {
            Build::Const(t) => match self.store().value(*t) {
                Value::Compound(op, &[n, arg]) if ops.contains(&op) => Some((
                    op,
                    self.store().atom_of(n)?,
                    Typed::of(of_ground(self.store(), arg)),
                )),
                _ => None,
            },
            Build::Compound(op, args) if args.len() == 2 && ops.contains(op) => match &args[0] {
                Build::Const(n) => Some((
                    *op,
                    self.store().atom_of(*n)?,
                    self.build_ty(d, s, &args[1]),
                )),
                _ => None,
            },
            _ => None,
        }
    }

    fn is_ty(&self, d: usize, s: usize, expr: &Build) -> Typed {
        let reg = |r: Reg| self.reg(d, s, r).ty;
        match arith_ty(expr, &reg, self.store()) {
            // The evaluator's arithmetic: a number (an int or a float, or a
            // big integer the checked conversion turns away).
            Ty::Term => Typed::of(Ty::Ground),
            Ty::Never => Typed::never(),
            t => Typed::of(t),
        }
    }

    /// `get`/`set`/`inc` of `name`: its value; a `set` writes.
    fn var_op_value(&mut self, d: usize, op: Atom, name: Atom, arg: Option<Typed>) -> Typed {
        let cur = self.var(d, name);
        let label = |t: Typed| match t.why {
            Some(w) => Typed {
                ty: t.ty,
                why: Some(format!("variable `{}` is a term: {w}", name.as_str())),
            },
            None => t,
        };
        if op == atoms::SET {
            let v = arg.unwrap_or_else(|| Typed::term("`set` to a fresh variable"));
            self.write_var(d, name, &v);
            return v;
        }
        if op == atoms::INC {
            return match cur.ty {
                Ty::Int | Ty::Float | Ty::Never => cur,
                _ => label(cur),
            };
        }
        label(cur)
    }

    fn cond(&mut self, d: usize, s: usize, c: &Cond) {
        match c {
            Cond::Arith(_, l, r) => {
                self.ev(d, s, l);
                self.ev(d, s, r);
            }
            Cond::Other(b) => self.scan_writes(d, s, b, 0),
            Cond::Cmp(_, l, r) => {
                self.build_ty(d, s, l);
                self.build_ty(d, s, r);
            }
            Cond::And(l, r) | Cond::Or(l, r) => {
                self.cond(d, s, l);
                self.cond(d, s, r);
            }
        }
    }

    /// Binds the fresh registers `fresh` of a pattern matched against a
    /// value of type `v`; `false` when no value of that type can match.
    fn bind(&mut self, d: usize, s: usize, pat: &Build, v: &Typed, fresh: &[Reg], depth: usize) {
        if depth > MAX_DEPTH {
            return;
        }
        match pat {
            Build::Reg(r) => {
                if fresh.contains(r) {
                    self.def(d, s, *r, v);
                }
            }
            Build::Const(_) => {}
            Build::Compound(name, args) => {
                if let Some(vs) = args_of(v, *name, args.len()) {
                    for (a, t) in args.iter().zip(&vs) {
                        self.bind(d, s, a, t, fresh, depth + 1);
                    }
                }
            }
        }
    }

    /// Whether a value of type `v` can match `pat`.
    fn can_match(&self, pat: &Build, v: &Ty, depth: usize) -> bool {
        if depth > MAX_DEPTH {
            return true;
        }
        match (pat, v) {
            (_, Ty::Term) => true,
            (_, Ty::Never) => false,
            (Build::Reg(_), _) => true,
            (Build::Const(t), v) => match self.store().value(*t) {
                Value::Atom(a) => can_be_atom(v, a),
                Value::Int(_) => matches!(v, Ty::Int | Ty::Ground),
                Value::Float(_) => matches!(v, Ty::Float | Ty::Ground),
                Value::Compound(name, args) => args_of(&Typed::of(v.clone()), name, args.len())
                    .is_some_and(|vs| {
                        args.iter()
                            .zip(&vs)
                            .all(|(&a, t)| self.can_match(&Build::Const(a), &t.ty, depth + 1))
                    }),
                _ => true,
            },
            (Build::Compound(name, args), v) => args_of(&Typed::of(v.clone()), *name, args.len())
                .is_some_and(|vs| {
                    args.iter()
                        .zip(&vs)
                        .all(|(a, t)| self.can_match(a, &t.ty, depth + 1))
                }),
        }
    }

    /// An expectation as a pattern (what it evaluates to, with its
    /// unbound variables as registers).
    fn pattern_of(e: &Ev) -> Option<Build> {
        match e {
            Ev::Value(r) => Some(Build::Reg(*r)),
            Ev::Built(b) => Some(clone_build(b)),
            Ev::Compound(name, args) => {
                let args = args
                    .iter()
                    .map(Self::pattern_of)
                    .collect::<Option<Vec<_>>>()?;
                Some(Build::Compound(*name, args.into()))
            }
            _ => None,
        }
    }

    /// The id value a situation hands back when it is final.
    fn final_value(&self, d: usize, s: usize, p: &SitPlan) -> Typed {
        if p.id.1 == 0 {
            return Typed::of(if p.id.0 == atoms::NIL {
                Ty::list(Ty::Never)
            } else {
                Ty::Sym
            });
        }
        let args = self.t.dms[d].sits[s]
            .as_ref()
            .map(|t| t.id_args.clone())
            .unwrap_or_default();
        compound_ty(p.id.0, args)
    }

    /// The situations of DM `d` a next-situation value of type `v` can
    /// select (the id unifies), with the argument types it gives them.
    fn select(&mut self, d: usize, v: &Typed, pipe: &Typed) {
        let ir = self.ir;
        let dm = &ir.dms[d];
        for s in 0..dm.situations.len() {
            let id = self.store().args(dm.situations[s].template)[ID];
            let hit = match self.store().value(id) {
                Value::Var(_) => true,
                Value::Atom(a) => can_be_atom(&v.ty, a),
                Value::Compound(name, args) => args_of(v, name, args.len()).is_some(),
                _ => matches!(v.ty, Ty::Term),
            };
            if !hit {
                continue;
            }
            self.enter(d, s, pipe);
            if let Value::Compound(name, args) = self.store().value(id) {
                if let Some(vs) = args_of(v, name, args.len()) {
                    let vs: Vec<Typed> = vs
                        .iter()
                        .zip(args)
                        .map(|(a, &pat)| narrowed_by_list_pattern(self.store(), a, pat))
                        .collect();
                    if let Some(t) = self.t.dms[d].sits[s].as_mut() {
                        for (slot, a) in t.id_args.iter_mut().zip(&vs) {
                            self.changed |= slot.absorb(a);
                        }
                    }
                }
            }
        }
    }

    /// The pipe `pipe` enters situation `s`.
    fn enter(&mut self, d: usize, s: usize, pipe: &Typed) {
        if let Some(t) = self.t.dms[d].sits[s].as_mut() {
            self.changed |= t.pipe.absorb(pipe);
        }
    }

    /// The first situation an atom next situation `name` selects.
    fn go_static(&mut self, d: usize, name: Atom, pipe: &Typed) {
        let dm = &self.ir.dms[d];
        for s in 0..dm.situations.len() {
            let id = self.store().args(dm.situations[s].template)[ID];
            match self.store().value(id) {
                Value::Var(_) => return self.enter(d, s, pipe),
                Value::Atom(a) if a == name => return self.enter(d, s, pipe),
                _ => {}
            }
        }
    }

    fn next(&mut self, d: usize, s: usize, n: &Next, pipe: &Typed) {
        match n {
            Next::Static(t, _) => {
                if let Some(name) = self.store().atom_of(*t) {
                    self.go_static(d, name, pipe);
                }
            }
            Next::If(c, a, b) => {
                self.cond(d, s, c);
                self.next(d, s, a, pipe);
                self.next(d, s, b, pipe);
            }
            Next::Eval(e) => {
                // Each branch of a conditional is its own value.
                let mut values = Vec::new();
                self.next_values(d, s, e, &mut values);
                for v in values {
                    self.select(d, &v, pipe);
                }
            }
        }
    }

    fn next_values(&mut self, d: usize, s: usize, e: &Ev, out: &mut Vec<Typed>) {
        if let Ev::If(c, a, b) = e {
            self.cond(d, s, c);
            self.next_values(d, s, a, out);
            self.next_values(d, s, b, out);
        } else {
            let v = self.ev(d, s, e);
            out.push(v);
        }
    }

    fn situation(&mut self, d: usize, s: usize, p: &SitPlan) {
        let fresh_why = Typed::term("a fresh variable: may be unbound where it is read");
        let built_why = Typed::term("the id's variables, unbound when the DM starts here (D-4)");
        let pipe = self.t.dms[d].sits[s]
            .as_ref()
            .map(|t| t.pipe.clone())
            .unwrap_or_else(Typed::never);
        // The id built when the DM starts here (unused otherwise); an
        // argument linked with a parameter that is a value takes its value.
        if s == 0 {
            let linked = start_links(p);
            for (i, part) in p.compound_id.iter().flatten().enumerate() {
                if let IdPart::Fresh(r) = part {
                    let param = linked
                        .iter()
                        .find(|(x, _)| *x == i)
                        .and_then(|&(_, j)| self.t.dms[d].params.get(j))
                        .filter(|t| t.is_native())
                        .cloned();
                    self.def(d, s, *r, param.as_ref().unwrap_or(&built_why));
                }
            }
            if let Some(pat) = &p.pattern {
                for &r in &pat.fresh {
                    self.def(d, s, r, &built_why);
                }
            }
        }
        // Registers bound before any read (in_arg pattern, prog `is`).
        let id_args = self.t.dms[d].sits[s]
            .as_ref()
            .map(|t| t.id_args.clone())
            .unwrap_or_default();
        let mut fresh = Vec::new();
        for (r, init) in &p.inits {
            // A parameter or id argument nothing in the plan reads
            // (`_Answer`, `understood(Answer, _)`): no value is needed.
            let unread = self.occ[d][s].get(*r as usize) == Some(&0);
            if unread
                && matches!(
                    init,
                    Init::HeadArg(_) | Init::HeadPath(..) | Init::IdArg(_) | Init::IdPath(_)
                )
            {
                self.unbound_or_term(d, s, *r, &fresh_why);
                continue;
            }
            let t = match init {
                Init::IdArg(i) => id_args.get(*i).cloned().unwrap_or_else(Typed::never),
                Init::IdPath(path) => self.id_path(p, &id_args, path),
                Init::HeadArg(i) => self.t.dms[d]
                    .params
                    .get(*i)
                    .cloned()
                    .unwrap_or_else(Typed::never),
                Init::HeadPath(i, path) => self.head_path(d, *i, path),
                Init::Pipe => pipe.clone(),
                Init::Fresh => {
                    fresh.push(*r);
                    continue;
                }
            };
            self.def(d, s, *r, &t);
        }
        // An id argument linked with a parameter (D-7): unified, so a
        // binding either way unless both are values.
        for &(r, i) in &p.links {
            let param = self.t.dms[d].params.get(i).cloned();
            let own = self.t.dms[d].sits[s]
                .as_ref()
                .and_then(|x| x.regs.get(r as usize))
                .cloned();
            let values = |t: &Option<Typed>| {
                t.as_ref()
                    .is_some_and(|t| t.ty == Ty::Never || t.is_native())
            };
            if !(values(&param) && values(&own)) {
                let why = format!(
                    "an id argument that is parameter {} too, unified with it (D-7), not both values",
                    i + 1
                );
                self.def(d, s, r, &Typed::term(why));
            }
        }
        let mut bound: Vec<Reg> = Vec::new();
        if let Some((b, unify, r)) = &p.in_arg {
            if *unify {
                // The pattern unified with the pipe binds its fresh
                // variables to the pipe's parts: where it does not unify
                // the run ends there under `--deny-warnings` (E14,
                // `Machine::unify_in_arg`), so past it they hold values of
                // the pipe's type, whatever the pattern's shape (constants,
                // nested compounds, a variable twice or shared with the id
                // or a parameter: those are compared, not bound). By
                // default (`Options::skip_unmatched_in_arg`, D-8) a mismatch
                // is skipped and the visit runs with these variables
                // unbound, which these types do not describe: native code
                // still agrees because it runs the typed visit only where
                // its own match of the pattern succeeds and hands any
                // other to the machine, nothing of it done
                // (`Gen::nat_pipe_match`), which skips it there. A
                // variable met only there (`_`) holds no value; a part of
                // the pipe not known yet (`never`, the fixpoint has not
                // reached it) binds nothing so far, nor does a pipe the
                // pattern can never match (nothing after it runs).
                let mut regs = Vec::new();
                pattern_regs(b, &mut regs, 0);
                let live: Vec<Reg> = regs
                    .into_iter()
                    .filter(|r| fresh.contains(r))
                    .filter(|r| self.occ[d][s].get(*r as usize).is_some_and(|&n| n > 1))
                    .collect();
                if self.can_match(b, &pipe.ty, 0) {
                    self.bind(d, s, b, &pipe, &live, 0);
                }
                bound.extend(live);
            }
            // Unified, the in_arg is the pipe's value.
            let t = if *unify {
                pipe.clone()
            } else {
                pipe.clone().join(&self.build_ty(d, s, b))
            };
            self.def(d, s, *r, &t);
        }
        // `is` in prog binds its variable before the arcs read it.
        if let Some(Prog::InPlace(evs)) = &p.prog {
            let in_arg = p.in_arg.as_ref().map(|(b, _, _)| b);
            let mut lhs = Vec::new();
            is_lhs(
                evs,
                |r| in_arg.is_some_and(|b| build_mentions(b, r, 0)),
                &mut lhs,
            );
            bound.extend(lhs.into_iter().filter(|r| fresh.contains(r)));
        }
        // Output arguments: a fresh variable given to a DM call, bound by
        // the callee's final `diag_mod` (D-20, D-23).
        let mut outs: Vec<Reg> = Vec::new();
        if let KindPlan::Recursive {
            call: call @ Build::Compound(_, args),
            ..
        } = &p.kind
        {
            let before = |r: Reg| {
                p.in_arg
                    .as_ref()
                    .is_some_and(|(b, _, _)| build_mentions(b, r, 0))
                    || match &p.prog {
                        Some(Prog::InPlace(evs)) => evs.iter().any(|e| ev_mentions(e, r, 0)),
                        Some(Prog::Copy(b)) => build_mentions(b, r, 0),
                        None => false,
                    }
            };
            if let Some(c) = self.callee(call) {
                for (i, a) in args.iter().enumerate() {
                    let Build::Reg(r) = a else { continue };
                    let once = args.iter().filter(|x| build_mentions(x, *r, 0)).count() == 1;
                    if fresh.contains(r) && !bound.contains(r) && once && !before(*r) {
                        // A final of the callee that has no `diag_mod`
                        // leaves the variable unbound: typed by the others
                        // only where no exit arc that may take such a
                        // final reads it (`leaving_read`).
                        let t = self.out_param(c, i).filter(|_| {
                            let KindPlan::Recursive { exit, .. } = &p.kind else {
                                return false;
                            };
                            !self.leaving_read(c, exit, *r)
                        });
                        if let Some(t) = t {
                            self.def(d, s, *r, &t);
                            outs.push(*r);
                        }
                    }
                }
            }
        }
        bound.extend(outs.iter().copied());
        for r in &fresh {
            if !bound.contains(r) {
                self.unbound_or_term(d, s, *r, &fresh_why);
            }
        }
        if let Some((b, r)) = &p.out_arg {
            let t = self.build_ty(d, s, b);
            self.def(d, s, *r, &t);
        }
        match &p.prog {
            Some(Prog::InPlace(evs)) => {
                for e in evs {
                    self.ev(d, s, e);
                }
            }
            Some(Prog::Copy(b)) => self.scan_writes(d, s, b, 0),
            None => {}
        }
        // The out_arg of a non-recursive situation, re-read after prog:
        // the pipe leaves with its value (evaluated, D-9), not the term
        // as written (`(X > 0 -> X ; otherwise -> 1)` leaves an int or
        // `X`, not a `;` compound).
        let out = p.out_arg.as_ref().map(|(b, _)| self.eval_build(d, s, b));
        match &p.kind {
            KindPlan::Final { diag_mod } => {
                if let Some(b) = diag_mod {
                    self.scan_writes(d, s, b, 0);
                }
                // An out_arg nothing binds passes the pipe on (`OutPass`).
                let leaves = match out {
                    Some(_) if p.final_out_pass() == super::OutPass::Unchanged => pipe.clone(),
                    Some(o) => o,
                    None => pipe.clone(),
                };
                self.changed |= self.t.dms[d].pipe_out.absorb(&leaves);
            }
            KindPlan::Perceptual(arcs) => self.arcs(d, s, arcs, None, &pipe, out.as_ref()),
            KindPlan::Recursive {
                call,
                eval_call,
                exit,
                ..
            } => {
                let callee = self.callee(call);
                let args: Option<Vec<Typed>> = match call {
                    Build::Compound(_, args) => Some(
                        args.iter()
                            .map(|a| {
                                if matches!(a, Build::Reg(r) if outs.contains(r)) {
                                    Typed::term("an output argument: unbound when the DM is called")
                                } else if *eval_call {
                                    self.eval_build(d, s, a)
                                } else {
                                    self.build_ty(d, s, a)
                                }
                            })
                            .collect(),
                    ),
                    Build::Const(t) => Some(
                        self.store()
                            .args(*t)
                            .iter()
                            .map(|&a| self.build_ty(d, s, &Build::Const(a)))
                            .collect(),
                    ),
                    Build::Reg(_) => None,
                };
                if *eval_call {
                    self.scan_writes(d, s, call, 0);
                }
                match callee {
                    Some(c) => {
                        if let Some(args) = args {
                            let params = &mut self.t.dms[c].params;
                            if params.len() == args.len() {
                                for (slot, a) in params.iter_mut().zip(&args) {
                                    self.changed |= slot.absorb(a);
                                }
                            }
                        }
                        self.changed |= self.t.dms[c].pipe_in.absorb(&pipe);
                        let finals = self.finals(c);
                        let back = self.t.dms[c].pipe_out.clone();
                        self.arcs(d, s, exit, Some(&finals), &back, None);
                    }
                    None => {
                        let finals = vec![Typed::term(
                            "the final situation of a DM computed at run time",
                        )];
                        let back = Typed::term("the pipe of a DM computed at run time");
                        self.arcs(d, s, exit, Some(&finals), &back, None);
                    }
                }
            }
        }
    }

    /// A call's argument as the machine evaluates it (arguments of a
    /// compound evaluated; a constant evaluated if it is not inert).
    fn eval_build(&self, d: usize, s: usize, b: &Build) -> Typed {
        if let Some((op, name, arg)) = self.var_op_of(d, s, b) {
            // `set` gives the value written, `get`/`inc` the variable's
            // (the write itself is found by `scan_writes`).
            if op == atoms::SET {
                return arg;
            }
            let cur = self.var(d, name);
            return match &cur.why {
                Some(w) if !cur.is_native() => Typed {
                    why: Some(format!("variable `{}` is a term: {w}", name.as_str())),
                    ty: cur.ty,
                },
                _ => cur,
            };
        }
        match b {
            Build::Reg(r) => self.reg(d, s, *r),
            Build::Const(t) => {
                let st = self.store();
                let inert = {
                    let mut stack = vec![*t];
                    let mut ok = true;
                    while let Some(u) = stack.pop() {
                        if let Value::Compound(n, a) = st.value(u) {
                            if !eval::evaluates_arguments_only(n, a.len()) {
                                ok = false;
                                break;
                            }
                            stack.extend(a.iter());
                        }
                    }
                    ok
                };
                if inert {
                    return self.build_ty(d, s, b);
                }
                // A ground compound with an evaluated part
                // (`round(apply(rooms, []))`): typed as its parts are,
                // each evaluated (the same rule as for a compound built
                // from registers, below).
                match st.value(*t) {
                    Value::Compound(name, args) => {
                        let parts =
                            Build::Compound(name, args.iter().map(|&a| Build::Const(a)).collect());
                        self.eval_build(d, s, &parts)
                    }
                    _ => Typed::of(Ty::Ground),
                }
            }
            Build::Compound(name, args) if eval::evaluates_arguments_only(*name, args.len()) => {
                compound_ty(
                    *name,
                    args.iter().map(|a| self.eval_build(d, s, a)).collect(),
                )
            }
            Build::Compound(..) => self
                .function_value(d, s, b)
                .unwrap_or_else(|| Typed::of(Ty::Ground)),
        }
    }

    /// [`DmTypes::outputs`], once the fixpoint is reached.
    fn outputs(&mut self) {
        for c in 0..self.ir.dms.len() {
            let plans = &self.mir.dms[c];
            if plans.iter().any(Option::is_none) {
                continue;
            }
            for i in 0..self.t.dms[c].params.len() {
                let read = plans.iter().enumerate().any(|(s, p)| {
                    let p = p.as_ref().expect("planned");
                    p.links.iter().any(|&(_, k)| k == i)
                        // A pattern is matched with the argument: read.
                        || p.inits.iter().any(|(_, init)| {
                            matches!(init, Init::HeadPath(k, _) if *k == i)
                        })
                        || p.inits.iter().any(|(r, init)| {
                            matches!(init, Init::HeadArg(k) if *k == i)
                                && self.occ[c][s].get(*r as usize) != Some(&0)
                        })
                });
                if !read {
                    self.t.dms[c].outputs[i] = self.out_param(c, i);
                }
            }
        }
    }

    /// The type argument `i` of a call of DM `c` has when the call
    /// returns, when every final situation of `c` binds it (its
    /// `diag_mod` is `c`'s head with a value there, D-20) or has no
    /// `diag_mod` (it leaves the argument as the caller gave it: a fresh
    /// variable stays unbound, `State::leaving_read`), and one binds it;
    /// else `None`.
    fn out_param(&self, c: usize, i: usize) -> Option<Typed> {
        let dm = &self.ir.dms[c];
        let arity = self.store().args(dm.head).len();
        let mut out = Typed::never();
        let mut any = false;
        for (s, sit) in dm.situations.iter().enumerate() {
            if sit.kind != Kind::Final {
                continue;
            }
            let p = self.mir.plan(c as u32, s as SitIx)?;
            let b = match &p.kind {
                KindPlan::Final { diag_mod: Some(b) } => b,
                KindPlan::Final { diag_mod: None } => continue,
                _ => return None,
            };
            let t = match b {
                Build::Compound(name, args)
                    if *name == dm.name && args.len() == arity && i < arity =>
                {
                    self.build_ty(c, s, &args[i])
                }
                Build::Const(k) => match self.store().value(*k) {
                    Value::Compound(name, args)
                        if name == dm.name && args.len() == arity && i < arity =>
                    {
                        self.build_ty(c, s, &Build::Const(args[i]))
                    }
                    _ => return None,
                },
                _ => return None,
            };
            if !t.is_native() {
                return None;
            }
            any = true;
            out.absorb(&t);
        }
        any.then_some(out)
    }

    /// Whether an exit arc of `exit` that may take a final situation of
    /// DM `c` with no `diag_mod` (one that leaves an output argument
    /// unbound) reads register `r`: its expectation is not a pattern
    /// that no such final's id can match.
    fn leaving_read(&self, c: usize, exit: &Arcs, r: Reg) -> bool {
        let dm = &self.ir.dms[c];
        let leaving: Vec<((Atom, usize), Typed)> = dm
            .situations
            .iter()
            .enumerate()
            .filter(|(_, sit)| sit.kind == Kind::Final)
            .filter_map(|(s, _)| {
                let p = self.mir.plan(c as u32, s as SitIx)?;
                matches!(p.kind, KindPlan::Final { diag_mod: None })
                    .then(|| (p.id, self.final_value(c, s, p)))
            })
            .collect();
        if leaving.is_empty() {
            return false;
        }
        // A pattern of another name or arity than the final's id never
        // matches it (`wound` is not `jammed`); else its types decide.
        let functor = |b: &Build| match b {
            Build::Compound(name, args) => Some((*name, args.len())),
            Build::Const(t) => match self.store().value(*t) {
                Value::Atom(a) => Some((a, 0)),
                Value::Compound(name, args) => Some((name, args.len())),
                _ => None,
            },
            Build::Reg(_) => None,
        };
        exit.arcs.iter().any(|arc| {
            let may_take = match Self::pattern_of(&arc.expectation) {
                Some(pat) => leaving.iter().any(|(id, f)| {
                    functor(&pat).is_none_or(|x| x == *id) && self.can_match(&pat, &f.ty, 0)
                }),
                None => true,
            };
            may_take && arc_mentions(arc, r)
        })
    }

    /// The id values DM `c`'s final situations hand back.
    fn finals(&self, c: usize) -> Vec<Typed> {
        let dm = &self.ir.dms[c];
        let mut out = Vec::new();
        for (s, sit) in dm.situations.iter().enumerate() {
            if sit.kind != Kind::Final {
                continue;
            }
            match self.mir.plan(c as u32, s as SitIx) {
                Some(p) => out.push(self.final_value(c, s, p)),
                None => out.push(Typed::term(
                    "a final situation instantiated from its template",
                )),
            }
        }
        out
    }

    /// The type of the part at `path` of parameter `i`, whose head
    /// argument is a pattern ([`Init::HeadPath`]): the parameter's type
    /// taken apart along the pattern (`never` where the type cannot match
    /// it: the call is an error there, E13).
    fn head_path(&self, d: usize, i: usize, path: &[usize]) -> Typed {
        let store = self.store();
        let off = || Typed::term("a head path off the head");
        let mut t = self.t.dms[d]
            .params
            .get(i)
            .cloned()
            .unwrap_or_else(Typed::never);
        let Some(mut sub) = store.arg(self.ir.dms[d].head, i) else {
            return off();
        };
        for &k in path {
            let Value::Compound(name, args) = store.value(sub) else {
                return off();
            };
            let Some(vs) = args_of(&t, name, args.len()) else {
                return Typed::never();
            };
            t = vs.get(k).cloned().unwrap_or_else(Typed::never);
            sub = args.get(k).copied().unwrap_or(sub);
        }
        t
    }

    fn id_path(&self, p: &SitPlan, id_args: &[Typed], path: &[usize]) -> Typed {
        let Some(pat) = &p.pattern else {
            return Typed::term("an id path without a pattern");
        };
        let store = self.store();
        let Some((&first, rest)) = path.split_first() else {
            return Typed::term("an empty id path");
        };
        let mut t = id_args.get(first).cloned().unwrap_or_else(Typed::never);
        let mut sub = match store.value(pat.term) {
            Value::Compound(_, args) if first < args.len() => args[first],
            _ => return Typed::term("an id path off the id"),
        };
        for &k in rest {
            let Value::Compound(name, args) = store.value(sub) else {
                return Typed::term("an id path off the id");
            };
            let Some(vs) = args_of(&t, name, args.len()) else {
                return Typed::never();
            };
            t = vs.get(k).cloned().unwrap_or_else(Typed::never);
            sub = args.get(k).copied().unwrap_or(sub);
        }
        t
    }

    /// Arcs of a perceptual situation (`finals: None`: a perception
    /// matches the expectations) or a recursive one's exit arcs (matched
    /// against the callee's final ids); `pipe`: the incoming pipe of the
    /// arcs; `out`: the situation's out_arg value, if any.
    fn arcs(
        &mut self,
        d: usize,
        s: usize,
        arcs: &Arcs,
        finals: Option<&[Typed]>,
        pipe: &Typed,
        out: Option<&Typed>,
    ) {
        for (k, arc) in arcs.arcs.iter().enumerate() {
            for (n, &from) in arc.import_from.iter().enumerate() {
                let t = self.reg(d, s, from);
                self.def(d, s, arc.import_at + n as Reg, &t);
            }
            let exp = self.ev(d, s, &arc.expectation);
            // An expectation that is a pattern is matched, not held: its
            // register stays `never` (see the module doc).
            if Self::pattern_of(&arc.expectation).is_none() {
                self.def(d, s, arcs.exps + k as Reg, &exp);
            }
            let mut bound = Vec::new();
            match (finals, Self::pattern_of(&arc.expectation)) {
                (Some(finals), Some(pat)) => {
                    let mut regs = Vec::new();
                    pattern_regs(&pat, &mut regs, 0);
                    for f in finals {
                        if self.can_match(&pat, &f.ty, 0) {
                            self.bind(d, s, &pat, f, &arc.fresh, 0);
                        }
                    }
                    bound.extend(regs.into_iter().filter(|r| arc.fresh.contains(r)));
                }
                (Some(_), None) => {}
                (None, pat) => {
                    if let Some(pat) = pat {
                        let mut regs = Vec::new();
                        pattern_regs(&pat, &mut regs, 0);
                        let why = Typed::of(Ty::Ground);
                        for r in regs.into_iter().filter(|r| arc.fresh.contains(r)) {
                            self.def(d, s, r, &why);
                            bound.push(r);
                        }
                    }
                }
            }
            let mut lhs = Vec::new();
            action_is_lhs(&arc.action, &arc.expectation, &mut lhs);
            let fresh_why = Typed::term("a fresh variable: may be unbound where it is read");
            for &r in &arc.fresh {
                if !bound.contains(&r) && !lhs.contains(&r) {
                    if arc_first_use(arc, r) == Use::Boundary {
                        // `assign(R, E)` first: E's value, else any ground value.
                        let t = match assign_of(arc, r) {
                            Some(e) => self.eval_build(d, s, e),
                            None => Typed::of(Ty::Ground),
                        };
                        let t = if t.is_native() && t.ty != Ty::Never {
                            t
                        } else {
                            Typed::of(Ty::Ground)
                        };
                        self.def(d, s, r, &t);
                    } else {
                        self.unbound_or_term(d, s, r, &fresh_why);
                    }
                }
            }
            match &arc.action {
                Action::List { items, regs } => {
                    for (i, e) in items.iter().enumerate() {
                        let t = self.ev(d, s, e);
                        self.def(d, s, regs + i as Reg, &t);
                    }
                }
                Action::One(e) => {
                    self.ev(d, s, e);
                }
            }
            let leaves = match (&arc.out_arg, out) {
                // A variable nothing binds: the pipe passes on (`OutPass`).
                (Some(_), _) if arc.out_pass() == super::OutPass::Unchanged => pipe.clone(),
                (Some(e), _) => self.ev(d, s, e),
                (None, Some(o)) => o.clone(),
                (None, None) => pipe.clone(),
            };
            self.next(d, s, &arc.next, &leaves);
            if let Some(b) = &arc.diag_mod {
                self.scan_writes(d, s, b, 0);
            }
        }
    }
}

/// The arguments of a DM's first situation's id (a compound of distinct
/// variables and atomic constants) that are a parameter's variable too,
/// with that parameter's position: `(id argument, parameter)`. When the
/// DM starts there the id's variables are unbound (D-4) and the link
/// binds each such one to the call's argument (D-7).
pub(crate) fn start_links(p: &SitPlan) -> Vec<(usize, usize)> {
    if p.compound_id.is_none() {
        return Vec::new();
    }
    p.inits
        .iter()
        .filter_map(|(r, init)| match init {
            Init::IdArg(i) => p.links.iter().find(|(x, _)| x == r).map(|&(_, j)| (*i, j)),
            _ => None,
        })
        .collect()
}

/// `E` when the first action element that mentions `r` is `assign(R, E)`
/// with `r` as `R` and not in `E`.
fn assign_of(arc: &ArcPlan, r: Reg) -> Option<&Build> {
    let items: &[Ev] = match &arc.action {
        Action::List { items, .. } => items,
        Action::One(e) => std::slice::from_ref(e),
    };
    let first = items.iter().find(|e| ev_mentions(e, r, 0))?;
    match first {
        Ev::Eval(Build::Compound(name, args)) if name.as_str() == "assign" && args.len() == 2 => {
            (matches!(&args[0], Build::Reg(x) if *x == r) && !build_mentions(&args[1], r, 0))
                .then_some(&args[1])
        }
        _ => None,
    }
}

/// Where a register is first met in evaluation order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Use {
    /// Not met.
    None,
    /// Inside a term a boundary runs (the evaluator, a user function,
    /// `get`), which may bind it.
    Boundary,
    /// Read as a value (or passed on unbound).
    Read,
}

/// The first use of `r` in an arc: expectation, action, next, out_arg.
fn arc_first_use(arc: &ArcPlan, r: Reg) -> Use {
    let items: &[Ev] = match &arc.action {
        Action::List { items, .. } => items,
        Action::One(e) => std::slice::from_ref(e),
    };
    match ev_first_use(&arc.expectation, r, 0) {
        Use::None => {}
        u => return u,
    }
    for e in items {
        if performed_with(e, r) {
            // An argument of an action the robot performs, met there
            // first: the robot may bind it (a status).
            return Use::Boundary;
        }
        match ev_first_use(e, r, 0) {
            Use::None => {}
            u => return u,
        }
    }
    match next_first_use(&arc.next, r, 0) {
        Use::None => {}
        u => return u,
    }
    match &arc.out_arg {
        Some(e) => ev_first_use(e, r, 0),
        None => Use::None,
    }
}

/// Whether action `e` is a compound of two or more arguments, performed
/// as it is built, with `r` as one of its arguments and nowhere else in
/// it (`navigate(P, R)`): the robot may bind it, as a status. A superset
/// of the checker's status arguments (`check/unbound.rs`: a declared
/// `status` argument, else the last of two or more): soundness rests on
/// the checked conversion after the action, not on which one it is.
fn performed_with(e: &Ev, r: Reg) -> bool {
    match e {
        Ev::Compound(_, args) if args.len() >= 2 => {
            args.iter().any(|a| matches!(a, Ev::Value(x) if *x == r))
                && args.iter().filter(|a| ev_mentions(a, r, 0)).count() == 1
        }
        Ev::Built(Build::Compound(_, args)) if args.len() >= 2 => {
            args.iter().any(|a| matches!(a, Build::Reg(x) if *x == r))
                && args.iter().filter(|a| build_mentions(a, r, 0)).count() == 1
        }
        _ => false,
    }
}

fn cond_first_use(c: &Cond, r: Reg, depth: usize) -> Use {
    match c {
        Cond::Arith(_, a, b) => match ev_first_use(a, r, depth + 1) {
            Use::None => ev_first_use(b, r, depth + 1),
            u => u,
        },
        Cond::Other(b) if build_mentions(b, r, depth + 1) => Use::Boundary,
        Cond::Other(_) => Use::None,
        Cond::Cmp(_, a, b)
            if build_mentions(a, r, depth + 1) || build_mentions(b, r, depth + 1) =>
        {
            Use::Read
        }
        Cond::Cmp(..) => Use::None,
        Cond::And(a, b) | Cond::Or(a, b) => match cond_first_use(a, r, depth + 1) {
            Use::None => cond_first_use(b, r, depth + 1),
            u => u,
        },
    }
}

fn ev_first_use(e: &Ev, r: Reg, depth: usize) -> Use {
    if depth > MAX_DEPTH {
        return Use::Read;
    }
    let met = |b: &Build, u: Use| {
        if build_mentions(b, r, depth + 1) {
            u
        } else {
            Use::None
        }
    };
    match e {
        Ev::Value(x) if *x == r => Use::Read,
        Ev::Value(_) => Use::None,
        Ev::Built(b) => met(b, Use::Read),
        Ev::Eval(b) | Ev::VarOp { arg: b, .. } => met(b, Use::Boundary),
        Ev::If(c, a, b) => match cond_first_use(c, r, depth + 1) {
            Use::None if ev_mentions(a, r, depth + 1) || ev_mentions(b, r, depth + 1) => {
                // One branch or the other: not certainly bound.
                Use::Read
            }
            u => u,
        },
        // Both branches evaluated, in order.
        Ev::Pick(c, a, b) => match cond_first_use(c, r, depth + 1) {
            Use::None => match ev_first_use(a, r, depth + 1) {
                Use::None => ev_first_use(b, r, depth + 1),
                u => u,
            },
            u => u,
        },
        Ev::VarOpFresh { dst, .. } if *dst == r => Use::Boundary,
        Ev::VarOpFresh { .. } => Use::None,
        Ev::IsFresh { expr, dst } | Ev::BindFresh { expr, dst } => match met(expr, Use::Read) {
            Use::None if *dst == r => Use::Boundary,
            u => u,
        },
        Ev::Is { lhs, expr } => match met(expr, Use::Read) {
            Use::None => met(lhs, Use::Read),
            u => u,
        },
        Ev::Compound(_, args) => args
            .iter()
            .map(|a| ev_first_use(a, r, depth + 1))
            .find(|u| *u != Use::None)
            .unwrap_or(Use::None),
    }
}

fn next_first_use(n: &Next, r: Reg, depth: usize) -> Use {
    if depth > MAX_DEPTH {
        return Use::Read;
    }
    match n {
        Next::Static(..) => Use::None,
        Next::If(c, a, b) => match cond_first_use(c, r, depth + 1) {
            Use::None => match (
                next_first_use(a, r, depth + 1),
                next_first_use(b, r, depth + 1),
            ) {
                (Use::None, Use::None) => Use::None,
                _ => Use::Read,
            },
            u => u,
        },
        Next::Eval(e) => ev_first_use(e, r, depth + 1),
    }
}

/// Why a register that holds no value is a term where it flows on.
const UNBOUND_WHY: &str = "an unbound variable (`_`, or a variable used once)";

/// How often each register occurs in plan `p`: in a term built or
/// evaluated, as a destination (`get`/`is` into it), as an arc's import
/// source, linked with a parameter; `inits` and fresh lists are not occurrences.
pub(crate) fn occurrences(p: &SitPlan) -> Vec<u32> {
    let mut n = vec![0u32; p.regs];
    let mut bump = |r: Reg| {
        if let Some(c) = n.get_mut(r as usize) {
            *c += 1;
        }
    };
    fn build(b: &Build, f: &mut dyn FnMut(Reg), depth: usize) {
        match b {
            Build::Const(_) => {}
            Build::Reg(r) => f(*r),
            Build::Compound(_, args) => {
                if depth <= MAX_DEPTH {
                    args.iter().for_each(|a| build(a, f, depth + 1));
                }
            }
        }
    }
    fn cond(c: &Cond, f: &mut dyn FnMut(Reg), depth: usize) {
        match c {
            Cond::Arith(_, a, b) => {
                ev(a, f, depth + 1);
                ev(b, f, depth + 1);
            }
            Cond::Other(b) => build(b, f, depth + 1),
            Cond::Cmp(_, a, b) => {
                build(a, f, depth + 1);
                build(b, f, depth + 1);
            }
            Cond::And(a, b) | Cond::Or(a, b) => {
                if depth <= MAX_DEPTH {
                    cond(a, f, depth + 1);
                    cond(b, f, depth + 1);
                }
            }
        }
    }
    fn ev(e: &Ev, f: &mut dyn FnMut(Reg), depth: usize) {
        if depth > MAX_DEPTH {
            return;
        }
        match e {
            Ev::Value(r) => f(*r),
            Ev::Built(b) | Ev::Eval(b) | Ev::VarOp { arg: b, .. } => build(b, f, depth + 1),
            Ev::If(c, a, b) | Ev::Pick(c, a, b) => {
                cond(c, f, depth + 1);
                ev(a, f, depth + 1);
                ev(b, f, depth + 1);
            }
            Ev::VarOpFresh { dst, .. } => f(*dst),
            Ev::IsFresh { expr, dst } | Ev::BindFresh { expr, dst } => {
                build(expr, f, depth + 1);
                f(*dst);
            }
            Ev::Is { lhs, expr } => {
                build(lhs, f, depth + 1);
                build(expr, f, depth + 1);
            }
            Ev::Compound(_, args) => args.iter().for_each(|a| ev(a, f, depth + 1)),
        }
    }
    fn next(x: &Next, f: &mut dyn FnMut(Reg), depth: usize) {
        if depth > MAX_DEPTH {
            return;
        }
        match x {
            Next::Static(..) => {}
            Next::If(c, a, b) => {
                cond(c, f, depth + 1);
                next(a, f, depth + 1);
                next(b, f, depth + 1);
            }
            Next::Eval(e) => ev(e, f, depth + 1),
        }
    }
    fn arcs(a: &Arcs, f: &mut dyn FnMut(Reg)) {
        build(&a.type_term, f, 0);
        for arc in &a.arcs {
            arc.import_from.iter().for_each(|&r| f(r));
            ev(&arc.expectation, f, 0);
            match &arc.action {
                Action::List { items, .. } => items.iter().for_each(|e| ev(e, f, 0)),
                Action::One(e) => ev(e, f, 0),
            }
            next(&arc.next, f, 0);
            if let Some(e) = &arc.out_arg {
                ev(e, f, 0);
            }
            if let Some(b) = &arc.diag_mod {
                build(b, f, 0);
            }
        }
    }
    let f: &mut dyn FnMut(Reg) = &mut bump;
    for &(r, _) in &p.links {
        f(r);
    }
    for part in p.compound_id.iter().flatten() {
        if let IdPart::Fresh(r) = part {
            f(*r);
        }
    }
    if let Some(pat) = &p.pattern {
        build(&pat.build, f, 0);
    }
    if let Some((b, _, _)) = &p.in_arg {
        build(b, f, 0);
    }
    if let Some((b, _)) = &p.out_arg {
        build(b, f, 0);
    }
    match &p.prog {
        Some(Prog::InPlace(evs)) => evs.iter().for_each(|e| ev(e, f, 0)),
        Some(Prog::Copy(b)) => build(b, f, 0),
        None => {}
    }
    match &p.kind {
        KindPlan::Final { diag_mod } => {
            if let Some(b) = diag_mod {
                build(b, f, 0);
            }
        }
        KindPlan::Perceptual(a) => arcs(a, f),
        KindPlan::Recursive { call, exit, .. } => {
            build(call, f, 0);
            arcs(exit, f);
        }
    }
    n
}

/// `V is E` at the top of an action list: V is bound there.
fn action_is_lhs(a: &Action, exp: &Ev, out: &mut Vec<Reg>) {
    let items: &[Ev] = match a {
        Action::List { items, .. } => items,
        Action::One(e) => std::slice::from_ref(e),
    };
    is_lhs(items, |r| ev_mentions(exp, r, 0), out);
}

/// The fresh variables bound by a `V is E` of `items` before anything
/// reads them: not in an earlier item, not in `E`, not where `before` says.
fn is_lhs(items: &[Ev], before: impl Fn(Reg) -> bool, out: &mut Vec<Reg>) {
    for (i, e) in items.iter().enumerate() {
        if let Ev::Is {
            lhs: Build::Reg(r),
            expr,
        } = e
        {
            let read = before(*r)
                || build_mentions(expr, *r, 0)
                || items[..i].iter().any(|x| ev_mentions(x, *r, 0));
            if !read {
                out.push(*r);
            }
        }
    }
}

/// Whether arc `arc` reads or binds register `r` anywhere (its imports,
/// expectation, action, next situation, out_arg, diag_mod).
pub(crate) fn arc_mentions(arc: &crate::mir::ArcPlan, r: Reg) -> bool {
    fn next(x: &Next, r: Reg, depth: usize) -> bool {
        match x {
            _ if depth > MAX_DEPTH => true,
            Next::Static(..) => false,
            Next::If(c, a, b) => {
                cond_mentions(c, r, depth + 1) || next(a, r, depth + 1) || next(b, r, depth + 1)
            }
            Next::Eval(e) => ev_mentions(e, r, depth + 1),
        }
    }
    let action = match &arc.action {
        Action::List { items, .. } => items.iter().any(|e| ev_mentions(e, r, 0)),
        Action::One(e) => ev_mentions(e, r, 0),
    };
    arc.import_from.contains(&r)
        || ev_mentions(&arc.expectation, r, 0)
        || action
        || next(&arc.next, r, 0)
        || arc.out_arg.as_ref().is_some_and(|e| ev_mentions(e, r, 0))
        || arc
            .diag_mod
            .as_ref()
            .is_some_and(|b| build_mentions(b, r, 0))
}

pub(crate) fn build_mentions(b: &Build, r: Reg, depth: usize) -> bool {
    match b {
        Build::Const(_) => false,
        Build::Reg(x) => *x == r,
        Build::Compound(_, args) => {
            depth > MAX_DEPTH || args.iter().any(|a| build_mentions(a, r, depth + 1))
        }
    }
}

/// Whether condition `c` reads register `r`.
pub(crate) fn cond_mentions(c: &Cond, r: Reg, depth: usize) -> bool {
    if depth > MAX_DEPTH {
        return true;
    }
    match c {
        Cond::Arith(_, a, b) => ev_mentions(a, r, depth + 1) || ev_mentions(b, r, depth + 1),
        Cond::Other(b) => build_mentions(b, r, depth + 1),
        Cond::Cmp(_, a, b) => build_mentions(a, r, depth + 1) || build_mentions(b, r, depth + 1),
        Cond::And(a, b) | Cond::Or(a, b) => {
            cond_mentions(a, r, depth + 1) || cond_mentions(b, r, depth + 1)
        }
    }
}

pub(crate) fn ev_mentions(e: &Ev, r: Reg, depth: usize) -> bool {
    if depth > MAX_DEPTH {
        return true;
    }
    let cond = |c: &Cond| cond_mentions(c, r, depth);
    match e {
        Ev::Value(x) => *x == r,
        Ev::Built(b)
        | Ev::Eval(b)
        | Ev::VarOp { arg: b, .. }
        | Ev::IsFresh { expr: b, .. }
        | Ev::BindFresh { expr: b, .. } => build_mentions(b, r, depth + 1),
        Ev::If(c, a, b) | Ev::Pick(c, a, b) => {
            cond(c) || ev_mentions(a, r, depth + 1) || ev_mentions(b, r, depth + 1)
        }
        Ev::VarOpFresh { dst, .. } => *dst == r,
        Ev::Is { lhs, expr } => {
            build_mentions(lhs, r, depth + 1) || build_mentions(expr, r, depth + 1)
        }
        Ev::Compound(_, args) => args.iter().any(|a| ev_mentions(a, r, depth + 1)),
    }
}

/// The registers of a pattern; `false` when it holds a constant.
fn pattern_regs(b: &Build, out: &mut Vec<Reg>, depth: usize) -> bool {
    if depth > MAX_DEPTH {
        return false;
    }
    match b {
        Build::Reg(r) => {
            out.push(*r);
            true
        }
        Build::Const(_) => false,
        Build::Compound(_, args) => {
            let mut all = true;
            for a in args.iter() {
                all &= pattern_regs(a, out, depth + 1);
            }
            all
        }
    }
}

fn clone_build(b: &Build) -> Build {
    match b {
        Build::Const(t) => Build::Const(*t),
        Build::Reg(r) => Build::Reg(*r),
        Build::Compound(n, args) => Build::Compound(*n, args.iter().map(clone_build).collect()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{check, ir, load};
    use proptest::prelude::*;

    fn ir_of(src: &str) -> Ir {
        let (program, diags) = load::load_sources(&[("t.dm", src)]);
        let (result, diags) = check::check(program, diags);
        let checked = result.unwrap_or_else(|_| {
            let errors: Vec<_> = diags.iter().filter(|d| d.is_error()).collect();
            panic!("does not check: {errors:#?}")
        });
        ir::lower(&checked)
    }

    fn types_of(src: &str) -> (Ir, Mir, MirTypes) {
        let ir = ir_of(src);
        let mir = crate::mir::lower(&ir);
        let t = infer(&ir, &mir);
        (ir, mir, t)
    }

    fn dm(ir: &Ir, name: &str) -> usize {
        ir.dm_by_name(Atom::intern(name)).unwrap() as usize
    }

    /// The situation at this position of the DM's list.
    fn sit(_: &Ir, _: usize, k: usize) -> usize {
        k
    }

    /// The type of the situation's register that the variable `var` starts in.
    fn var_ty(ir: &Ir, mir: &Mir, t: &MirTypes, d: usize, s: usize, var: &str) -> Ty {
        let p = mir.plan(d as u32, s as SitIx).expect("a plan");
        let dmv = &ir.dms[d];
        let index = dmv
            .var_index_names
            .iter()
            .find(|(_, n)| n == var)
            .unwrap_or_else(|| panic!("no variable {var}"))
            .0;
        // The variable's register: the init whose source term is the variable.
        let f = ir.store.args(dmv.situations[s].template);
        let mut vars = Vec::new();
        for &x in &f[..ARCS] {
            Planner::new(&ir.store, dmv).term_vars(x, &mut vars);
        }
        let k = vars
            .iter()
            .position(|&v| v == index)
            .expect("a situation variable");
        let r = p.inits[k].0;
        t.dms[d].sits[s].as_ref().unwrap().regs[r as usize]
            .ty
            .clone()
    }

    fn all_native(t: &MirTypes, d: usize, s: usize) -> bool {
        t.dms[d].sits[s]
            .as_ref()
            .unwrap()
            .regs
            .iter()
            .all(Typed::is_native)
    }

    /// Workload (d) of issue 37, the list given by a caller as a constant.
    const SEARCH: &str = r#"
diag_mod(main,
  [ [ id ==> round, type ==> recursive,
      embedded_dm ==> search([kitchen, hall, bedroom], bedroom),
      arcs ==> [ found(P) : say(P) => fs, not_found : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(search(Places, Target),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => try(Places) ] ],
    [ id ==> try([]), type ==> neutral, arcs ==> [ empty : empty => not_found ] ],
    [ id ==> try([P|Ps]), type ==> neutral,
      arcs ==> [ empty : empty => (P == Target -> found(P) ; otherwise -> try(Ps)) ] ],
    [ id ==> found(P), type ==> final ],
    [ id ==> not_found, type ==> final ] ],
  []).
"#;

    #[test]
    fn a_ground_list_cell_may_be_improper() {
        // `main`'s parameter is `ground` (the command line gives it): it
        // may be `[a|b]`, so the tail matched by `[X|Rest]` is
        // `list<ground>` only by a checked narrowing (a back end takes
        // only a proper list into `w([X|Rest])`); a cell built of ground
        // values whose tail is not a list is `ground`, not a partial-list
        // `term`.
        let (ir, mir, t) = types_of(
            r#"
diag_mod(main(Items),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => w(Items) ] ],
    [ id ==> w([]), type ==> final ],
    [ id ==> w([X|Rest]), type ==> neutral, arcs ==> [ empty : empty => pair([X|X], Rest) ] ],
    [ id ==> pair(P, R), type ==> neutral, arcs ==> [ empty : [say(P)] => w(R) ] ] ],
  []).
"#,
        );
        let m = dm(&ir, "main");
        let walk = sit(&ir, m, 2);
        assert_eq!(var_ty(&ir, &mir, &t, m, walk, "X"), Ty::Ground);
        let grounds = Ty::list(Ty::Ground);
        assert_eq!(var_ty(&ir, &mir, &t, m, walk, "Rest"), grounds);
        assert_eq!(t.dms[m].sits[walk].as_ref().unwrap().id_args[0].ty, grounds);
        let pair = sit(&ir, m, 3);
        assert_eq!(
            t.dms[m].sits[pair].as_ref().unwrap().id_args[0].ty,
            Ty::Ground
        );
    }

    #[test]
    fn only_a_list_pattern_narrows_a_ground_value() {
        // Cells ending in a variable or `[]` narrow; an improper pattern
        // or another compound does not.
        let (ir, _mir, t) = types_of(
            r#"
diag_mod(main(Items),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => w(Items) ] ],
    [ id ==> w([X|a]), type ==> neutral, arcs ==> [ empty : empty => v(X) ] ],
    [ id ==> w(f(Y)), type ==> neutral, arcs ==> [ empty : empty => v(Y) ] ],
    [ id ==> w([Z]), type ==> neutral, arcs ==> [ empty : empty => v(Z) ] ],
    [ id ==> v(_), type ==> final ] ],
  []).
"#,
        );
        let m = dm(&ir, "main");
        let arg = |k| {
            let s = sit(&ir, m, k);
            t.dms[m].sits[s].as_ref().unwrap().id_args[0].ty.clone()
        };
        assert_eq!(arg(1), Ty::Ground);
        assert_eq!(arg(2), Ty::Ground);
        assert_eq!(arg(3), Ty::list(Ty::Ground));
    }

    #[test]
    fn a_list_walk_by_compound_id_is_typed() {
        let (ir, mir, t) = types_of(SEARCH);
        let s = dm(&ir, "search");
        let syms = Ty::list(Ty::Sym);
        assert_eq!(t.dms[s].params[0].ty, syms);
        assert_eq!(t.dms[s].params[1].ty, Ty::Sym);
        let walk = sit(&ir, s, 2);
        assert_eq!(t.dms[s].sits[walk].as_ref().unwrap().id_args[0].ty, syms);
        assert_eq!(var_ty(&ir, &mir, &t, s, walk, "P"), Ty::Sym);
        assert_eq!(var_ty(&ir, &mir, &t, s, walk, "Ps"), syms);
        // The final hands its id back; its variable is read by nothing
        // in its plan: no value there.
        let found = sit(&ir, s, 3);
        assert_eq!(
            t.dms[s].sits[found].as_ref().unwrap().id_args[0].ty,
            Ty::Sym
        );
        assert_eq!(var_ty(&ir, &mir, &t, s, found, "P"), Ty::Never);
        for k in 0..ir.dms[s].situations.len() {
            assert!(all_native(&t, s, k), "{}", t.sit_line(s, k));
        }
        // The caller's exit arc `found(P)` gets the callee's atom.
        let m = dm(&ir, "main");
        let round = &t.dms[m].sits[0].as_ref().unwrap();
        assert!(
            round.regs.iter().all(Typed::is_native),
            "{}",
            t.sit_line(m, 0)
        );
        assert!(t.summary().starts_with("MIR registers typed: "));
    }

    /// Workload (c) of issue 37, the limit put in the pipe by the caller.
    #[test]
    fn the_pipe_is_followed_through_a_call_and_back() {
        let (ir, mir, t) = types_of(
            r#"
diag_mod(main,
  [ [ id ==> start, type ==> neutral, out_arg ==> 5, arcs ==> [ empty : empty => call ] ],
    [ id ==> call, type ==> recursive, in_arg ==> Limit, embedded_dm ==> echo,
      arcs ==> [ back : [inc(n, N)] => (N >= Limit -> fs ; otherwise -> call) ] ],
    [ id ==> fs, type ==> final ] ],
  [ n ==> 0 ]).
diag_mod(echo,
  [ [ id ==> is, type ==> neutral, in_arg ==> X, out_arg ==> X,
      arcs ==> [ empty : empty => back ] ],
    [ id ==> back, type ==> final ] ],
  []).
"#,
        );
        let m = dm(&ir, "main");
        let e = dm(&ir, "echo");
        // `start` receives the command line's in_arg (checked ground
        // where the frame starts), sends an int.
        assert_eq!(t.dms[m].sits[0].as_ref().unwrap().pipe.ty, Ty::Ground);
        let call = sit(&ir, m, 1);
        assert_eq!(var_ty(&ir, &mir, &t, m, call, "Limit"), Ty::Int);
        assert_eq!(t.dms[e].pipe_in.ty, Ty::Int);
        assert_eq!(t.dms[e].pipe_out.ty, Ty::Int);
        assert_eq!(var_ty(&ir, &mir, &t, e, 0, "X"), Ty::Int);
        assert!(all_native(&t, m, call), "{}", t.sit_line(m, call));
        assert_eq!(t.dms[m].locals[0].1.ty, Ty::Int);
        // The main DM's pipe is the command line's, converted at entry.
        let line = t.dm_line(&ir, m);
        assert!(line.contains("pipe in ground"), "{line}");
        assert!(line.contains("entered from outside (the main DM"), "{line}");
    }

    /// The pipe leaves with the out_arg's value (D-9): a conditional out_arg
    /// is not the `;` compound it is written as (it was typed so, and the
    /// caller's `V =< L` read the pipe as that compound), but the join of
    /// its branches' values.
    #[test]
    fn an_out_arg_leaves_with_its_value_not_its_text() {
        let (ir, mir, t) = types_of(
            r#"
diag_mod(main,
  [ [ id ==> call, type ==> recursive, embedded_dm ==> succ, arcs ==> [ next : empty => test ] ],
    [ id ==> test, type ==> neutral, in_arg ==> V,
      arcs ==> [ empty : [get(limit, L)] => (V =< L -> call ; otherwise -> done) ] ],
    [ id ==> done, type ==> final ] ],
  [ limit ==> 3 ]).
diag_mod(succ,
  [ [ id ==> add, type ==> neutral, in_arg ==> X,
      out_arg ==> (X > 0 -> 7 ; otherwise -> 1),
      arcs ==> [ empty : empty => next ] ],
    [ id ==> next, type ==> final ] ],
  []).
"#,
        );
        // Evaluated as the arc's `Ev` (`ngen12`): 7 or 1, an int.
        let s = dm(&ir, "succ");
        assert_eq!(t.dms[s].pipe_out.ty, Ty::Int);
        let m = dm(&ir, "main");
        let test = sit(&ir, m, 1);
        assert_eq!(var_ty(&ir, &mir, &t, m, test, "V"), Ty::Int);
    }

    #[test]
    fn a_countdown_through_an_id_argument_is_an_int() {
        let (ir, mir, t) = types_of(
            r#"
diag_mod(main,
  [ [ id ==> go, type ==> recursive, embedded_dm ==> down(3), arcs ==> [ done : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(down(Max),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => count(Max) ] ],
    [ id ==> count(N), type ==> neutral,
      arcs ==> [ empty : [M is N - 1] => (N > 0 -> count(M) ; otherwise -> done) ] ],
    [ id ==> done, type ==> final ] ],
  []).
"#,
        );
        let d = dm(&ir, "down");
        assert_eq!(t.dms[d].params[0].ty, Ty::Int);
        let count = sit(&ir, d, 1);
        assert_eq!(var_ty(&ir, &mir, &t, d, count, "N"), Ty::Int);
        assert!(all_native(&t, d, count), "{}", t.sit_line(d, count));
    }

    #[test]
    fn a_list_built_by_cons_keeps_its_element_type() {
        let (ir, mir, t) = types_of(
            r#"
diag_mod(main,
  [ [ id ==> go, type ==> recursive, embedded_dm ==> rev([a, b, c]), arcs ==> [ out(_) : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(rev(Items),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => acc([], Items) ] ],
    [ id ==> acc(Done, []), type ==> neutral, arcs ==> [ empty : empty => out(Done) ] ],
    [ id ==> acc(Done, [O|Os]), type ==> neutral,
      arcs ==> [ empty : empty => acc([O|Done], Os) ] ],
    [ id ==> out(R), type ==> final ] ],
  []).
"#,
        );
        let d = dm(&ir, "rev");
        let walk = sit(&ir, d, 2);
        assert_eq!(var_ty(&ir, &mir, &t, d, walk, "Done"), Ty::list(Ty::Sym));
        assert_eq!(var_ty(&ir, &mir, &t, d, walk, "O"), Ty::Sym);
        let out = sit(&ir, d, 3);
        let id = &t.dms[d].sits[out].as_ref().unwrap().id_args[0];
        assert_eq!(id.ty, Ty::list(Ty::Sym));
    }

    #[test]
    fn what_stays_a_term_says_why() {
        let (ir, mir, t) = types_of(
            r#"
diag_mod(main(Arg),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [set(mode, 1)] => c1 ] ],
    [ id ==> c1, type ==> recursive, embedded_dm ==> take(1, _),
      arcs ==> [ fs : empty => c2 ] ],
    [ id ==> c2, type ==> recursive, embedded_dm ==> take(x, Arg),
      arcs ==> [ fs : empty => listen ] ],
    [ id ==> listen, type ==> listening,
      arcs ==> [ said(W) : say(W) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ mode ==> idle ]).
diag_mod(take(A, B),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : [say(A), say(B)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
        );
        let m = dm(&ir, "main");
        let take = dm(&ir, "take");
        let why = |x: &Typed| x.why.clone().unwrap_or_default();
        assert_eq!(t.dms[m].params[0].ty, Ty::Ground);
        assert!(t.dms[m].entry.as_deref().unwrap().contains("main DM"));
        // int and atom meet: any ground value.
        let a = &t.dms[take].params[0];
        assert_eq!(a.ty, Ty::Ground);
        // An unbound argument, then the caller's term parameter.
        let b = &t.dms[take].params[1];
        assert!(why(b).contains("unbound variable"), "{b:?}");
        // `idle` then 1: any ground value.
        let mode = &t.dms[m].locals[0].1;
        assert_eq!(mode.ty, Ty::Ground);
        // What a perception binds: decoded where it enters (checked).
        let listen = sit(&ir, m, 3);
        let line = t.sit_line(m, listen);
        assert!(all_native(&t, m, listen), "{line}");
        assert!(line.contains("ground"), "{line}");
        let _ = var_ty(&ir, &mir, &t, m, 0, "Arg");
    }

    #[test]
    fn a_situation_without_a_plan_still_writes_its_locals() {
        let (ir, _, t) = types_of(
            r#"
diag_mod(main,
  [ [ id ==> go, type ==> recursive, embedded_dm ==> fixed(a, a), arcs ==> [ fs : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(fixed(X, X),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : set(k, b) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ k ==> 0 ]).
"#,
        );
        let f = dm(&ir, "fixed");
        assert!(t.dms[f].sits.iter().all(Option::is_none));
        assert_eq!(t.dms[f].locals[0].1.ty, Ty::Ground);
        assert!(t.dms[f]
            .pipe_out
            .why
            .as_deref()
            .unwrap_or("")
            .contains("template"));
    }

    #[test]
    fn a_variable_bound_by_is_in_an_action_is_a_number() {
        // (Reading it before its `is` is refused by the checker, E0228;
        // inference would leave it a term.)
        let (ir, _, t) = types_of(
            r#"
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [W is 2, say(W), X is W * 1.5, say(X)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
        );
        let m = dm(&ir, "main");
        let line = t.sit_line(m, 0);
        assert!(all_native(&t, m, 0), "{line}");
        assert!(line.contains("int") && line.contains("float"), "{line}");
    }

    #[test]
    fn a_variable_used_once_holds_no_value() {
        let (ir, mir, t) = types_of(
            r#"
diag_mod(main,
  [ [ id ==> go, type ==> recursive, embedded_dm ==> take(_),
      arcs ==> [ fs : say([hi, _]) => two ] ],
    [ id ==> two, type ==> neutral,
      arcs ==> [ empty : [say(X), say(X)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(take(A),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(A) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
        );
        let m = dm(&ir, "main");
        let go = t.dms[m].sits[0].as_ref().unwrap();
        // Both `_`: no value, `never`, flagged.
        let flagged: Vec<usize> = (0..go.regs.len()).filter(|&r| go.unbound[r]).collect();
        assert_eq!(flagged.len(), 2, "{}", t.sit_line(m, 0));
        for r in flagged {
            assert_eq!(go.regs[r].ty, Ty::Never);
        }
        // What it stands for where it flows: maybe unbound, a term.
        let take = dm(&ir, "take");
        assert_eq!(t.dms[take].params[0].ty, Ty::Term);
        assert!(t.dms[take].params[0]
            .why
            .as_deref()
            .unwrap()
            .contains("unbound variable"));
        // `X` read twice, unbound: the same variable both times, a term.
        let two = sit(&ir, m, 1);
        let line = t.sit_line(m, two);
        assert!(line.contains("(a fresh variable: may be unbound"), "{line}");
        let _ = (&mir, var_ty);
    }

    /// Output arguments, unread parameters, boundaries (a perception, the
    /// evaluator, an action's status) and pattern expectations.
    #[test]
    fn outputs_and_boundaries_are_typed() {
        let (ir, mir, t) = types_of(
            r#"
diag_mod(main,
  [ [ id ==> go, type ==> recursive, embedded_dm ==> sub(Out, _),
      arcs ==> [ done : say(Out) => look ] ],
    [ id ==> look, type ==> listening,
      arcs ==> [ said(W) : [assign(X, W), say(X), navigate(kitchen, St), say(St)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(sub(_R, _S),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : empty => done ] ],
    [ id ==> done, type ==> final, diag_mod ==> sub(ok, 1) ] ],
  []).
"#,
        );
        let m = dm(&ir, "main");
        let sub = dm(&ir, "sub");
        // `Out` is bound by the callee's final diag_mod.
        assert_eq!(var_ty(&ir, &mir, &t, m, 0, "Out"), Ty::Sym);
        assert!(all_native(&t, m, 0), "{}", t.sit_line(m, 0));
        // The callee's parameters: unbound when called, outputs when it returns.
        let outs: Vec<Option<Ty>> = t.dms[sub]
            .outputs
            .iter()
            .map(|o| o.as_ref().map(|o| o.ty.clone()))
            .collect();
        assert_eq!(outs, vec![Some(Ty::Sym), Some(Ty::Int)]);
        assert_eq!(t.dms[sub].params[0].ty, Ty::Term);
        assert!(t
            .dm_line(&ir, sub)
            .contains("an output: int when it returns"));
        assert_eq!(t.var_counts(), (2, 2));
        // A perception, `assign` and an action's status: ground, checked
        // where they enter; the pattern `said(W)` is matched, not held.
        let look = sit(&ir, m, 1);
        let line = t.sit_line(m, look);
        assert!(all_native(&t, m, look), "{line}");
        assert!(line.contains("ground"), "{line}");
        let KindPlan::Perceptual(arcs) = &mir.plan(m as u32, look as SitIx).unwrap().kind else {
            panic!("a perceptual plan")
        };
        let st = t.dms[m].sits[look].as_ref().unwrap();
        assert_eq!(st.regs[arcs.exps as usize].ty, Ty::Never);
        // The callee's unread parameters: no value (`_` given to the call
        // is an output too, bound to 1).
        assert!(t.sit_line(sub, 0).contains(" _"), "{}", t.sit_line(sub, 0));
    }

    /// A user function whose clauses assign atoms or its argument: the
    /// join of those, not `ground`; one that assigns a computed value:
    /// `ground`.
    #[test]
    fn a_user_function_gives_what_its_clauses_assign() {
        let (program, diags) = load::load_sources(&[
            (
                "t.dm",
                r#"
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [assign(A, apply(yes_no(_), [1])), say(A),
                          assign(B, apply(same(_), [x])), say(B),
                          assign(C, apply(len(_), [[a]])), say(C),
                          assign(D, apply(ans(_), [k])), say(D),
                          say(pair(apply(rooms, []), b))] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
            ),
            (
                "user_functions.pl",
                "yes_no(1) :- assign_func_value(yes).\n\
                 yes_no(_) :- assign_func_value(no).\n\
                 same(X) :- assign_func_value(X).\n\
                 len(L) :- length(L, N), assign_func_value(N).\n\
                 ans(K) :- (lookup(K, A) -> true ; A = none), assign_func_value(A).\n\
                 rooms :- assign_func_value([hall, bath]).\n",
            ),
        ]);
        let (result, _) = check::check(program, diags);
        let ir = ir::lower(&result.expect("checks"));
        let mir = crate::mir::lower(&ir);
        let t = infer(&ir, &mir);
        let line = t.sit_line(0, 0);
        let tys: Vec<String> = t.dms[0].sits[0]
            .as_ref()
            .unwrap()
            .regs
            .iter()
            .map(|r| r.ty.to_string())
            .collect();
        assert!(all_native(&t, 0, 0), "{line}");
        // yes/no and `x` (the argument) are atoms; the length is computed.
        assert!(tys.iter().filter(|t| *t == "atom").count() >= 2, "{line}");
        assert!(tys.iter().any(|t| t == "ground"), "{line}");
        // `ans`'s `A` is bound by `lookup` too, not only by `A = none`:
        // its value cannot be told (was `atom`).
        let said_ground = tys.iter().filter(|t| *t == "say(ground)").count();
        assert_eq!(said_ground, 2, "{line}");
        // A ground compound with an evaluated part: typed from its parts
        // (the function's list), not `ground`.
        assert!(
            tys.iter().any(|t| t == "say(pair(list<atom>, atom))"),
            "{line}"
        );
    }

    /// A variable read before what could bind it stays a term.
    #[test]
    fn a_read_before_the_binding_is_a_term() {
        let (ir, _, t) = types_of(
            r#"
diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [say(X), assign(X, 1), navigate(X, S), say(S)] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
        );
        let m = dm(&ir, "main");
        let line = t.sit_line(m, 0);
        assert!(line.contains("(a fresh variable: may be unbound"), "{line}");
        // `S`, met first as the status of `navigate`: ground.
        assert!(line.contains("ground"), "{line}");
    }

    #[test]
    fn prolog_writes_through_var_op() {
        let n = prolog_writes_in(["f(X) :- var_op(set(count, X)), var_op(get(k, _))."].into_iter());
        assert_eq!(n, Some(vec![Atom::intern("count")]));
        assert_eq!(
            prolog_writes_in(["g(N) :- var_op(set(N, 1))."].into_iter()),
            None
        );
        assert_eq!(prolog_writes_in(["h(O) :- var_op(O)."].into_iter()), None);
        assert_eq!(
            prolog_writes_in(["i :- var_op(inc(n, _))."].into_iter()),
            Some(vec![])
        );
    }

    #[test]
    fn constants_have_their_ground_type() {
        let mut store = Store::new();
        let mut ty = |s: &str| {
            let t = store.parse(s).unwrap().0;
            of_ground(&store, t).to_string()
        };
        assert_eq!(ty("[a, b]"), "list<atom>");
        assert_eq!(ty("[]"), "list<never>");
        assert_eq!(ty("[a, 1]"), "list<ground>");
        assert_eq!(ty("p(1, 2.0, x)"), "p(int, float, atom)");
        assert_eq!(ty("[a | b]"), "term");
        assert_eq!(ty("123456789012345678901234567890"), "term");
        assert_eq!(ty("p(X)"), "p(term)");
        let long = format!("[{}]", vec!["a"; 100_000].join(", "));
        assert_eq!(ty(&long), "list<atom>");
    }

    /// A small random DM over the shapes above: compound ids, lists,
    /// calls with arguments, the pipe, locals.
    fn random_dm() -> impl Strategy<Value = String> {
        let value = prop_oneof![
            Just("a"),
            Just("1"),
            Just("2.5"),
            Just("[]"),
            Just("[a, b]"),
            Just("f(a)"),
            Just("X"),
            Just("_"),
            Just("[X|Xs]"),
            Just("Xs"),
            Just("get(n, _)"),
        ];
        let next = prop_oneof![
            Just("s(V)".to_owned()),
            Just("s([V|Xs])".to_owned()),
            Just("t".to_owned()),
            Just("r(Xs)".to_owned()),
            Just("fs".to_owned()),
            Just("(V == a -> s(V) ; otherwise -> fs)".to_owned()),
        ];
        (
            proptest::collection::vec(value.clone(), 4),
            proptest::collection::vec(next, 3),
            any::<bool>(),
        )
            .prop_map(move |(v, n, pipe)| {
                let io = if pipe {
                    "in_arg ==> X, out_arg ==> V,"
                } else {
                    ""
                };
                format!(
                    r#"
diag_mod(main,
  [ [ id ==> go, type ==> recursive, embedded_dm ==> d({}, {}),
      arcs ==> [ r(R) : say(R) => fs, t : empty => go, fs : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  [ n ==> 0 ]).
diag_mod(d(X, Xs),
  [ [ id ==> is, type ==> neutral, {io} arcs ==> [ empty : [V is 1, set(n, {})] => {} ] ],
    [ id ==> s(V), type ==> neutral, arcs ==> [ empty : empty => {} ] ],
    [ id ==> s([V|W]), type ==> neutral, arcs ==> [ empty : set(n, W) => {} ] ],
    [ id ==> t, type ==> final ],
    [ id ==> r(Q), type ==> final, out_arg ==> Q ],
    [ id ==> fs, type ==> final, out_arg ==> {} ] ],
  [ n ==> 0 ]).
"#,
                    v[0].replace("X", "a").replace('_', "b"),
                    v[1].replace("X", "b").replace('_', "c"),
                    v[2],
                    n[0],
                    n[1],
                    n[2],
                    v[3],
                )
            })
    }

    #[test]
    fn the_random_dms_mostly_check() {
        use proptest::strategy::ValueTree;
        let mut runner = proptest::test_runner::TestRunner::deterministic();
        let mut ok = 0;
        let mut first_refused = String::new();
        for _ in 0..40 {
            let src = random_dm().new_tree(&mut runner).unwrap().current();
            let (program, diags) = load::load_sources(&[("t.dm", src.as_str())]);
            let (result, diags) = check::check(program, diags);
            if result.is_ok() {
                ok += 1;
            } else if first_refused.is_empty() {
                let errors: Vec<_> = diags
                    .iter()
                    .filter(|d| d.is_error())
                    .map(|d| &d.message)
                    .collect();
                first_refused = format!("{src}\n{errors:?}");
            }
        }
        assert!(
            ok >= 20,
            "{ok} of 40 random DMs check; the first refused:\n{first_refused}"
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn inference_never_fails(src in random_dm()) {
            let (program, diags) = load::load_sources(&[("t.dm", src.as_str())]);
            let (result, _) = check::check(program, diags);
            if let Ok(checked) = result {
                let ir = ir::lower(&checked);
                let mir = crate::mir::lower(&ir);
                let t = infer(&ir, &mir);
                let (typed, regs, clean, sits) = t.counts();
                prop_assert!(typed <= regs && clean <= sits);
                for (d, plans) in mir.dms.iter().enumerate() {
                    for (s, p) in plans.iter().enumerate() {
                        if let Some(p) = p {
                            let st = t.dms[d].sits[s].as_ref().unwrap();
                            prop_assert_eq!(st.regs.len(), p.regs);
                            // Every constant has its ground type.
                            let mut ks = Vec::new();
                            p.constants(&mut ks);
                            for k in ks {
                                prop_assert!(of_ground(&ir.store, k).depth() <= sitlog_runtime::native::MAX_DEPTH);
                            }
                            let _ = t.sit_line(d, s);
                        }
                    }
                    let _ = t.dm_line(&ir, d);
                }
            }
        }
    }
}
