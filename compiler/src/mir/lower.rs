//! Lowering: a situation of the IR turned into a [`SitPlan`] once
//! (registers for its variables, frozen ground parts, next situations
//! resolved to indices), or left to the instantiating path
//! ([`Unsupported`]). The one place that decides which situations run as
//! code and which variables are lazy.

use super::*;

/// Variables of one scope: their registers, and those not made yet.
#[derive(Clone, Default)]
pub(crate) struct Scope {
    vars: HashMap<u32, Reg>,
    lazy: HashSet<u32>,
}

pub(crate) struct Planner<'s> {
    store: &'s Store,
    dm: &'s IrDm,
    regs: Reg,
    /// `when/3` is the runtime's own ([`super::std_when`]).
    pub(crate) std_when: bool,
    /// The program's globals ([`Self::sees_var`]); none until set.
    pub(crate) globals: &'s [(Atom, Term)],
    /// The variables the situation being planned names once (its template,
    /// the DM's head included: the `_` idiom). Only these are unbound
    /// wherever they are evaluated.
    single: HashSet<u32>,
    /// A call of the runtime's `when/3` was lowered as a conditional
    /// ([`Self::when_call`]): the plan relies on the registry's `when/3`
    /// being the runtime's ([`super::Mir::runtime_when`]).
    pub(crate) lowered_when: std::rc::Rc<std::cell::Cell<bool>>,
}

impl<'s> Planner<'s> {
    pub(crate) fn new(store: &'s Store, dm: &'s IrDm) -> Self {
        Planner {
            store,
            dm,
            regs: 0,
            std_when: false,
            globals: &[],
            single: HashSet::new(),
            lowered_when: Default::default(),
        }
    }

    /// Whether a `get`/`inc` of `name` in this DM reads a variable (a
    /// local of the DM, or a global): only then does `get(name, V)` give
    /// `V` the value (`V` not made yet: [`Ev::VarOpFresh`]). Of any other
    /// name the value is a fresh unbound variable and `V` is left as it
    /// was (the evaluator's `var_op_parts`, as the original runs on), so
    /// `V` is made as any variable and the op is [`Ev::VarOp`].
    fn sees_var(&self, name: Atom) -> bool {
        self.dm.locals.iter().any(|(n, _)| *n == name)
            || self.globals.iter().any(|(n, _)| *n == name)
    }

    pub(crate) fn reg(&mut self) -> Reg {
        self.regs += 1;
        self.regs - 1
    }

    pub(crate) fn regs(&mut self, n: usize) -> Reg {
        let r = self.regs;
        self.regs += n as Reg;
        r
    }

    pub(crate) fn field(&self, s: &IrSituation, i: usize) -> Option<Term> {
        let t = self.store.args(s.template)[i];
        (self.store.atom_of(t) != Some(none_marker())).then_some(t)
    }

    /// The variables `t` names exactly once.
    fn named_once(&self, t: Term) -> HashSet<u32> {
        let mut seen = HashMap::new();
        let mut stack = vec![t];
        while let Some(u) = stack.pop() {
            match self.store.value(u) {
                Value::Var(v) => *seen.entry(v.index()).or_insert(0u32) += 1,
                Value::Compound(_, args) => stack.extend(args.iter()),
                _ => {}
            }
        }
        seen.into_iter()
            .filter(|&(_, n)| n == 1)
            .map(|(v, _)| v)
            .collect()
    }

    pub(crate) fn term_vars(&self, t: Term, out: &mut Vec<u32>) {
        let mut stack = vec![t];
        while let Some(u) = stack.pop() {
            match self.store.value(u) {
                Value::Var(v) if !out.contains(&v.index()) => out.push(v.index()),
                Value::Compound(_, args) => stack.extend(args.iter().rev()),
                _ => {}
            }
        }
    }

    /// The rule for a situation that runs as code (both back ends follow it).
    pub(crate) fn compiled_id(&self, s: &IrSituation) -> Option<(Atom, usize)> {
        let f = self.store.args(s.template);
        if s.kind == Kind::Recursive && self.store.atom_of(f[EMBEDDED_DM]) == Some(none_marker()) {
            return None;
        }
        // A head naming each variable once: an argument a variable or a
        // pattern (`key_of(K-_Qty)`, [`Init::HeadPath`]).
        if !self.linear_head() {
            return None;
        }
        match self.store.value(f[ID]) {
            Value::Atom(a) if a != none_marker() => Some((a, 0)),
            // Its variables shared with the DM's head are linked after
            // selection ([`SitPlan::links`]).
            Value::Compound(name, args) => Some((name, args.len())),
            _ => None,
        }
    }

    /// Whether the DM's head names each of its variables once, and no term
    /// in it is deeper than [`MAX_DEPTH`].
    pub(crate) fn linear_head(&self) -> bool {
        let mut seen = HashSet::new();
        let mut stack: Vec<(Term, usize)> = vec![(self.dm.head, 0)];
        while let Some((t, depth)) = stack.pop() {
            if depth > MAX_DEPTH {
                return false;
            }
            match self.store.value(t) {
                Value::Var(v) if !seen.insert(v.index()) => return false,
                Value::Compound(_, args) => stack.extend(args.iter().map(|&a| (a, depth + 1))),
                _ => {}
            }
        }
        true
    }

    /// Whether a compound id's arguments are distinct variables and atomic
    /// constants (selected by unifying the constants only); otherwise the
    /// id is a pattern ([`IdPattern`]).
    pub(crate) fn simple_id(&self, args: &[Term]) -> bool {
        let mut seen = HashSet::new();
        args.iter().all(|&arg| match self.store.value(arg) {
            Value::Var(v) => seen.insert(v.index()),
            Value::Atom(_) | Value::Int(_) | Value::Float(_) => true,
            _ => false,
        })
    }

    /// The path of argument positions to each variable's first occurrence
    /// in `t` (pre-order, left to right).
    pub(crate) fn var_paths(
        &self,
        t: Term,
        path: &mut Vec<usize>,
        out: &mut HashMap<u32, Box<[usize]>>,
    ) {
        match self.store.value(t) {
            Value::Var(v) => {
                out.entry(v.index()).or_insert_with(|| path.clone().into());
            }
            Value::Compound(_, args) => {
                for (i, &a) in args.iter().enumerate() {
                    path.push(i);
                    self.var_paths(a, path, out);
                    path.pop();
                }
            }
            _ => {}
        }
    }

    /// The index of the first situation a constant next situation `name`
    /// selects, when that one runs from a plan.
    pub(crate) fn static_target(&self, name: Atom) -> Option<SitIx> {
        // `empty` ends the DM whatever its situations are called (the
        // machine's `take_step`): never a situation's index.
        if name == atoms::EMPTY {
            return None;
        }
        for (i, s) in self.dm.situations.iter().enumerate() {
            let id = self.store.args(s.template)[ID];
            match self.store.value(id) {
                Value::Var(_) => return None,
                Value::Atom(a) if a == name => {
                    return self.compiled_id(s).map(|_| i as SitIx);
                }
                _ => {}
            }
        }
        None
    }

    /// Whether evaluating `t` gives `t` back with no effect.
    pub(crate) fn inert(&self, t: Term, vars_inert: bool) -> bool {
        let mut stack = vec![t];
        while let Some(u) = stack.pop() {
            match self.store.value(u) {
                Value::Var(_) if !vars_inert => return false,
                Value::Compound(name, args) => {
                    if !eval::evaluates_arguments_only(name, args.len()) {
                        return false;
                    }
                    stack.extend(args.iter());
                }
                _ => {}
            }
        }
        true
    }

    pub(crate) fn build(&self, t: Term, vars: &HashMap<u32, Reg>, depth: usize) -> Plan<Build> {
        if depth > MAX_DEPTH {
            return Err(Unsupported);
        }
        match self.store.value(t) {
            Value::Var(v) => vars
                .get(&v.index())
                .map(|&r| Build::Reg(r))
                .ok_or(Unsupported),
            Value::Compound(name, args) if !self.store.is_ground(t) => {
                let args = args
                    .iter()
                    .map(|&a| self.build(a, vars, depth + 1))
                    .collect::<Plan<Vec<_>>>()?;
                Ok(Build::Compound(name, args.into()))
            }
            _ => Ok(Build::Const(t)),
        }
    }

    pub(crate) fn ev(&self, t: Term, scope: &mut Scope, depth: usize) -> Plan<Ev> {
        if depth > MAX_DEPTH {
            return Err(Unsupported);
        }
        let (name, args) = match self.store.value(t) {
            Value::Var(v) => {
                return scope
                    .vars
                    .get(&v.index())
                    .map(|&r| Ev::Value(r))
                    .ok_or(Unsupported)
            }
            Value::Compound(name, args) => (name, args),
            _ => return Ok(Ev::Built(Build::Const(t))),
        };
        if self.store.is_ground(t) {
            let k = Build::Const(t);
            return Ok(if self.inert(t, true) {
                Ev::Built(k)
            } else {
                Ev::Eval(k)
            });
        }
        if let Some((cond, then, other)) = eval::conditional(self.store, t) {
            let c = self.cond(cond, scope, depth + 1)?;
            let then = self.ev(then, scope, depth + 1)?;
            let other = self.ev(other, scope, depth + 1)?;
            return Ok(Ev::If(Box::new(c), Box::new(then), Box::new(other)));
        }
        if args.len() == 2 && [atoms::GET, atoms::SET, atoms::INC].contains(&name) {
            if let (Some(var), Value::Var(v)) =
                (self.store.atom_of(args[0]), self.store.value(args[1]))
            {
                if self.sees_var(var) && scope.lazy.remove(&v.index()) {
                    let dst = *scope.vars.get(&v.index()).ok_or(Unsupported)?;
                    return Ok(Ev::VarOpFresh {
                        op: name,
                        name: var,
                        dst,
                    });
                }
            }
            if let Some(var) = self.store.atom_of(args[0]) {
                let arg = self.build(args[1], &scope.vars, depth + 1)?;
                return Ok(Ev::VarOp {
                    op: name,
                    name: var,
                    arg,
                });
            }
        }
        if args.len() == 2 && name == atoms::IS {
            let expr = self.build(args[1], &scope.vars, depth + 1)?;
            if let Value::Var(v) = self.store.value(args[0]) {
                if scope.lazy.remove(&v.index()) {
                    let dst = *scope.vars.get(&v.index()).ok_or(Unsupported)?;
                    return Ok(Ev::IsFresh { expr, dst });
                }
            }
            let lhs = self.build(args[0], &scope.vars, depth + 1)?;
            return Ok(Ev::Is { lhs, expr });
        }
        if args.len() == 2 && name == atoms::EQUALS {
            if let Some(e) = self.bind_fresh(args[0], args[1], scope, depth)? {
                return Ok(e);
            }
        }
        if let Some(e) = self.when_call(t, scope, depth) {
            return Ok(e);
        }
        if eval::evaluates_arguments_only(name, args.len()) {
            let values = args
                .iter()
                .map(|&a| self.ev(a, scope, depth + 1))
                .collect::<Plan<Vec<_>>>()?;
            return Ok(Ev::Compound(name, values.into()));
        }
        Ok(Ev::Eval(self.build(t, &scope.vars, depth + 1)?))
    }

    /// `X = Y` (D-30) where one side is a lazy variable (not made yet; the
    /// lazy walk made it lazy only if the other side does not name it):
    /// [`Ev::BindFresh`] of the other side's term, unevaluated. Anything
    /// else (`None`) stays the evaluator's unification.
    fn bind_fresh(&self, x: Term, y: Term, scope: &mut Scope, depth: usize) -> Plan<Option<Ev>> {
        for (v, e) in [(x, y), (y, x)] {
            if let Value::Var(v) = self.store.value(v) {
                if scope.lazy.contains(&v.index()) {
                    let expr = self.build(e, &scope.vars, depth + 1)?;
                    scope.lazy.remove(&v.index());
                    let dst = *scope.vars.get(&v.index()).ok_or(Unsupported)?;
                    return Ok(Some(Ev::BindFresh { expr, dst }));
                }
            }
        }
        Ok(None)
    }

    /// `apply(when(_, _, _), [C, T, E])` with the runtime's own `when/3`
    /// (`functions::standard`: `T` if `C`'s value is `true`, else `E`;
    /// `apply` evaluates `C`, `T` and `E` in this order first, D-37) as a
    /// choice that takes the same steps, where the two cannot differ:
    /// `when`'s three arguments are variables the situation names nowhere
    /// else (each takes its value, D-37) and `C` is a comparison whose
    /// value is `true` exactly when it holds ([`Self::when_cond`]). When
    /// `T` and `E` are terms whose evaluation gives themselves (constants:
    /// evaluating both, as `apply` does, or one is the same) it is the
    /// conditional `(C -> T ; otherwise -> E)` ([`Ev::If`]); otherwise both
    /// are evaluated, then the value chosen ([`Ev::Pick`]). Anything else
    /// stays the evaluator's call (`None`).
    pub(crate) fn when_call(&self, t: Term, scope: &mut Scope, depth: usize) -> Option<Ev> {
        let (c, then, other) = self.when_parts(t)?;
        // Nothing lowered (no scope changed) unless all three parts are.
        let mut trial = scope.clone();
        let c = self.when_cond(c, &trial, depth)?;
        let then = self.ev(then, &mut trial, depth + 1).ok()?;
        let other = self.ev(other, &mut trial, depth + 1).ok()?;
        *scope = trial;
        self.lowered_when.set(true);
        let (c, then, other) = (Box::new(c), Box::new(then), Box::new(other));
        Some(if self.when_lazy(t) {
            Ev::If(c, then, other)
        } else {
            Ev::Pick(c, then, other)
        })
    }

    /// Whether both branches of a `when` ([`Self::when_parts`]) are
    /// constants whose evaluation gives themselves (what `ev` makes
    /// `Ev::Built`): evaluating only the one chosen is the same.
    fn when_lazy(&self, t: Term) -> bool {
        let constant = |t: Term| self.store.is_ground(t) && self.inert(t, true);
        self.when_parts(t)
            .is_some_and(|(_, then, other)| constant(then) && constant(other))
    }

    /// `when`'s condition `C` as a [`Cond`] that holds exactly when `C`'s
    /// value is `true` (D-34), with the same steps and errors: `A == B`,
    /// `A \== B` (both evaluate `A` then `B` and compare them, never an
    /// error of their own, D-34/D-35), or `A op B` for `op` one of `<`,
    /// `>`, `=<`, `>=` with `A` and `B` each a variable, a constant whose
    /// evaluation gives itself or an expression of them (`N + 1`,
    /// [`Self::cmp_operand`]) ([`Cond::Cmp`]: the value comparison's own
    /// error, message and blame). Any other condition
    /// (`=:=`, `@<`, `(A, B)`, `\+ A`, an atom, a variable: the
    /// evaluator's value, never `true` but for the atom `true` or a
    /// variable bound to it) is `None`.
    fn when_cond(&self, c: Term, scope: &Scope, depth: usize) -> Option<Cond> {
        let (name, args) = match self.store.value(c) {
            Value::Compound(name, args) if args.len() == 2 => (name, args),
            _ => return None,
        };
        if name == atoms::EQ_EQ || name == atoms::NOT_EQ_EQ {
            return Some(Cond::Other(self.build(c, &scope.vars, depth + 1).ok()?));
        }
        self.order_cmp(name, args[0], args[1], scope)
    }

    /// `A > B`, `A < B`, `A >= B`, `A =< B` as a [`Cond::Cmp`] of two
    /// operands as written; `None` for another functor or an operand
    /// [`Self::cmp_operand`] does not take.
    fn order_cmp(&self, name: Atom, a: Term, b: Term, scope: &Scope) -> Option<Cond> {
        if ![
            atoms::GREATER,
            atoms::LESS,
            atoms::GREATER_EQ,
            atoms::LESS_EQ,
        ]
        .contains(&name)
        {
            return None;
        }
        let op = ArithCmp::from_atom(name)?;
        Some(Cond::Cmp(
            op,
            self.cmp_operand(a, scope)?,
            self.cmp_operand(b, scope)?,
        ))
    }

    /// `(C, T, E)` of `apply(when(V1, V2, V3), [C, T, E])` (`V`s variables
    /// the situation names nowhere else, the runtime's own `when/3`): see
    /// [`Self::when_call`].
    fn when_parts(&self, t: Term) -> Option<(Term, Term, Term)> {
        if !self.std_when {
            return None;
        }
        let [f, list] = *self.store.compound_args(t, atoms::APPLY, 2)? else {
            return None;
        };
        let f = self
            .store
            .compound_args(self.store.deref(f), Atom::intern("when"), 3)?;
        // Each `V` unbound where `when/3` is called: named nowhere else in
        // the situation (a `V` bound at run time, by the in_arg, the id, an
        // expectation or `C` itself, is passed to `when/3` as its value,
        // `eval::apply`, not the condition's).
        let single = |v: Term| matches!(self.store.value(v), Value::Var(x) if self.single.contains(&x.index()));
        if !f.iter().all(|&v| single(v)) {
            return None;
        }
        let items = self.list_literal(list)?;
        let &[c, then, other] = items.as_slice() else {
            return None;
        };
        Some((c, then, other))
    }

    pub(crate) fn cond(&self, cond: Term, scope: &mut Scope, depth: usize) -> Plan<Cond> {
        if let Value::Compound(name, &[l, r]) = self.store.value(cond) {
            if let Some(op) = ArithCmp::from_atom(name) {
                let l = self.ev(l, scope, depth + 1)?;
                let r = self.ev(r, scope, depth + 1)?;
                return Ok(Cond::Arith(op, l, r));
            }
        }
        if let Some(c) = self.junction(cond, scope, depth) {
            return Ok(c);
        }
        Ok(Cond::Other(self.build(cond, &scope.vars, depth + 1)?))
    }

    /// A conditional's condition `(A, B)` or `(A ; B)` whose operands are
    /// leaves with a value `true` or `false` ([`Cond::And`]): `A op B`
    /// (`<`, `>`, `=<`, `>=`, D-34) with each side a variable or a constant
    /// whose evaluation gives itself, as [`Cond::Cmp`]; `A == B`, `A \== B`,
    /// `member(X, L)`, `not_member(X, L)` (D-33) as [`Cond::Other`]; or
    /// another such conjunction or disjunction. The condition's arguments
    /// are evaluated before it is called (D-35): every leaf is computed,
    /// in order, then the goal of `true`s and `false`s is called. Any
    /// other operand (`=:=`, whose goal may fail or err where the
    /// disjunction does not reach it; `\+`, `->`, an atom) keeps the
    /// whole condition the evaluator's (`None`).
    fn junction(&self, c: Term, scope: &Scope, depth: usize) -> Option<Cond> {
        if depth > MAX_DEPTH {
            return None;
        }
        let Value::Compound(name, &[l, r]) = self.store.value(c) else {
            return None;
        };
        if name != atoms::COMMA && name != atoms::SEMICOLON {
            return None;
        }
        let l = self.junction_leaf(l, scope, depth + 1)?;
        let r = self.junction_leaf(r, scope, depth + 1)?;
        let (l, r) = (Box::new(l), Box::new(r));
        Some(if name == atoms::COMMA {
            Cond::And(l, r)
        } else {
            Cond::Or(l, r)
        })
    }

    /// An operand of [`Self::junction`].
    fn junction_leaf(&self, t: Term, scope: &Scope, depth: usize) -> Option<Cond> {
        if let Some(c) = self.junction(t, scope, depth) {
            return Some(c);
        }
        // A type test (`number(X)`, `\+ atom(X)`): it holds where the goal
        // of its evaluated arguments does (`is_type_test`).
        if let Ok(b) = self.build(t, &scope.vars, depth + 1) {
            if is_type_test(&b) {
                return Some(Cond::Other(b));
            }
        }
        let Value::Compound(name, &[a, b]) = self.store.value(t) else {
            return None;
        };
        if [
            atoms::EQ_EQ,
            atoms::NOT_EQ_EQ,
            atoms::MEMBER,
            atoms::NOT_MEMBER,
        ]
        .contains(&name)
        {
            return Some(Cond::Other(self.build(t, &scope.vars, depth + 1).ok()?));
        }
        self.order_cmp(name, a, b, scope)
    }

    /// An operand of a value comparison ([`Cond::Cmp`]), as written: a
    /// variable, a constant whose evaluation gives itself, or a compound
    /// whose functors only evaluate their arguments over variables and
    /// such constants (`N + 1`, `Max * 2`: its value is the compound of
    /// its arguments' values, D-36, which the comparison evaluates).
    fn cmp_operand(&self, a: Term, scope: &Scope) -> Option<Build> {
        match self.store.value(a) {
            Value::Var(v) => scope.vars.get(&v.index()).map(|&r| Build::Reg(r)),
            _ if self.store.is_ground(a) && self.inert(a, true) => Some(Build::Const(a)),
            Value::Compound(..) if self.inert(a, true) => self.build(a, &scope.vars, 0).ok(),
            _ => None,
        }
    }

    pub(crate) fn next(&self, t: Term, scope: &mut Scope, depth: usize) -> Plan<Next> {
        if depth > MAX_DEPTH {
            return Err(Unsupported);
        }
        if let Some(name) = self.store.atom_of(t) {
            return Ok(Next::Static(t, self.static_target(name)));
        }
        if let Some((cond, then, other)) = eval::conditional(self.store, t) {
            let c = self.cond(cond, scope, depth + 1)?;
            let then = self.next(then, scope, depth + 1)?;
            let other = self.next(other, scope, depth + 1)?;
            return Ok(Next::If(Box::new(c), Box::new(then), Box::new(other)));
        }
        // The runtime's `when/3` as the conditional it is the same as
        // (constant branches: each a next situation of its own).
        if self.when_lazy(t) {
            if let Some(Ev::If(c, ..)) = self.when_call(t, scope, depth) {
                if let Some((_, then, other)) = self.when_parts(t) {
                    let then = self.next(then, scope, depth + 1)?;
                    let other = self.next(other, scope, depth + 1)?;
                    return Ok(Next::If(c, Box::new(then), Box::new(other)));
                }
            }
        }
        Ok(Next::Eval(self.ev(t, scope, depth + 1)?))
    }

    /// Variables whose first occurrence is the argument of a `get`/`inc`
    /// (or the variable of an `is`, or a side of `=`) outside any
    /// conditional, none of them `known` (made before the arc). A side of
    /// `=` only where the other side names no variable the arc makes
    /// unbound (each `known` or itself lazy, so bound before): otherwise
    /// the value would have unbound parts, and the `=` stays the
    /// evaluator's unification.
    pub(crate) fn lazy_vars(&self, terms: &[Term], known: &dyn Fn(u32) -> bool) -> HashSet<u32> {
        let mut seen = HashSet::new();
        let mut lazy = HashSet::new();
        let mut binds = Vec::new();
        for &t in terms {
            self.lazy_walk(t, 0, &mut seen, &mut lazy, &mut binds);
        }
        lazy.retain(|&v| !known(v));
        loop {
            let before = lazy.len();
            for (v, others) in &binds {
                if lazy.contains(v) && others.iter().any(|w| !known(*w) && !lazy.contains(w)) {
                    lazy.remove(v);
                }
            }
            if lazy.len() == before {
                return lazy;
            }
        }
    }

    pub(crate) fn lazy_walk(
        &self,
        t: Term,
        depth: usize,
        seen: &mut HashSet<u32>,
        lazy: &mut HashSet<u32>,
        binds: &mut Vec<(u32, Vec<u32>)>,
    ) {
        let Value::Compound(name, args) = self.store.value(t) else {
            if let Value::Var(v) = self.store.value(t) {
                seen.insert(v.index());
            }
            return;
        };
        if depth > MAX_DEPTH {
            // Planning fails on such a term anyway: mark its variables seen.
            let mut vars = Vec::new();
            self.term_vars(t, &mut vars);
            seen.extend(vars);
            return;
        }
        if let Some((c, a, b)) = eval::conditional(self.store, t) {
            for part in [c, a, b] {
                self.lazy_walk(part, depth + 1, seen, lazy, binds);
            }
            return;
        }
        if args.len() == 2 && name == atoms::IS {
            let mut vars = Vec::new();
            self.term_vars(args[1], &mut vars);
            seen.extend(vars);
            if let Value::Var(v) = self.store.value(args[0]) {
                if depth == 0 && seen.insert(v.index()) {
                    lazy.insert(v.index());
                }
                return;
            }
            let mut vars = Vec::new();
            self.term_vars(args[0], &mut vars);
            seen.extend(vars);
            return;
        }
        if args.len() == 2 && name == atoms::EQUALS {
            // `V = E` / `E = V` with `V` first met here and not in `E`
            // ([`Self::bind_fresh`]); the left side is tried first.
            let mut vars = Vec::new();
            self.term_vars(t, &mut vars);
            let fresh = |side: Term, other: Term, seen: &HashSet<u32>| match self.store.value(side)
            {
                Value::Var(v) if !seen.contains(&v.index()) => {
                    let mut in_other = Vec::new();
                    self.term_vars(other, &mut in_other);
                    (!in_other.contains(&v.index())).then_some((v.index(), in_other))
                }
                _ => None,
            };
            if depth == 0 {
                if let Some((v, others)) =
                    fresh(args[0], args[1], seen).or_else(|| fresh(args[1], args[0], seen))
                {
                    lazy.insert(v);
                    binds.push((v, others));
                }
            }
            seen.extend(vars);
            return;
        }
        if args.len() == 2 && (name == atoms::GET || name == atoms::INC) {
            if let (Some(var), Value::Var(v)) =
                (self.store.atom_of(args[0]), self.store.value(args[1]))
            {
                if !self.sees_var(var) {
                    // Left as it was (`Self::sees_var`): made as any variable.
                    seen.insert(v.index());
                } else if depth == 0 && seen.insert(v.index()) {
                    lazy.insert(v.index());
                }
                return;
            }
        }
        if !self.store.is_ground(t) && eval::evaluates_arguments_only(name, args.len()) {
            for &a in args {
                self.lazy_walk(a, depth, seen, lazy, binds);
            }
            return;
        }
        let mut vars = Vec::new();
        self.term_vars(t, &mut vars);
        seen.extend(vars);
    }

    pub(crate) fn list_literal(&self, t: Term) -> Option<Vec<Term>> {
        let mut items = Vec::new();
        let mut rest = t;
        loop {
            match self.store.value(rest) {
                Value::Compound(name, &[head, tail]) if name == atoms::DOT => {
                    items.push(head);
                    rest = tail;
                }
                Value::Atom(a) if a == atoms::NIL && !items.is_empty() => return Some(items),
                _ => return None,
            }
        }
    }

    /// Whether a situation's `prog` runs on a renamed copy (D-10): it
    /// shares a variable with a part other than the in_arg and (but in a
    /// recursive situation) the out_arg; otherwise it runs in place.
    fn prog_on_copy(&self, f: &[Term], kind: Kind, prog: Option<Term>) -> bool {
        let Some(p) = prog else {
            return false;
        };
        let mut linked = Vec::new();
        let mut elsewhere = Vec::new();
        for (i, &t) in f.iter().enumerate() {
            let link = i == IN_ARG || (i == OUT_ARG && kind != Kind::Recursive);
            match i {
                PROG => {}
                _ if link => self.term_vars(t, &mut linked),
                _ => self.term_vars(t, &mut elsewhere),
            }
        }
        let mut prog_vars = Vec::new();
        self.term_vars(p, &mut prog_vars);
        !prog_vars
            .iter()
            .all(|v| linked.contains(v) || !elsewhere.contains(v))
    }

    /// The plan of situation `ix`.
    pub(crate) fn situation(mut self, ix: usize) -> Plan<SitPlan> {
        let s = &self.dm.situations[ix];
        let id = self.compiled_id(s).ok_or(Unsupported)?;
        self.single = self.named_once(s.template);
        let f = self.store.args(s.template).to_vec();
        let mut scope = Scope::default();
        let prog = self.field(s, PROG);
        let prog_on_copy = self.prog_on_copy(&f, s.kind, prog);
        // Each arc is renamed apart with its own copy of the out_arg
        // (D-11): a variable of the out_arg that no other part of the
        // situation names (`out_arg ==> M-L` with `[M is N + 1]` in the
        // arc) is the arc's own, fresh in each arc, and not the
        // instance's, unless the out_arg is built as written (a final, a
        // `prog` run on a copy, which links it: D-10).
        let out_own = s.kind != Kind::Final && !prog_on_copy;
        let mut elsewhere = Vec::new();
        if out_own {
            for (i, &t) in f[..ARCS].iter().enumerate() {
                if i != OUT_ARG {
                    self.term_vars(t, &mut elsewhere);
                }
            }
        }
        let mut inst_vars = Vec::new();
        for (i, &t) in f[..ARCS].iter().enumerate() {
            if i == OUT_ARG && out_own {
                let mut vars = Vec::new();
                self.term_vars(t, &mut vars);
                for v in vars {
                    if elsewhere.contains(&v) && !inst_vars.contains(&v) {
                        inst_vars.push(v);
                    }
                }
            } else {
                self.term_vars(t, &mut inst_vars);
            }
        }
        // A head argument that is a variable is the argument; the
        // variables of one that is a pattern are parts of it
        // ([`Init::HeadPath`]), each named once in the head (`compiled_id`).
        let mut head_vars: Vec<u32> = Vec::new();
        let mut head_paths: HashMap<u32, (usize, Box<[usize]>)> = HashMap::new();
        for (i, &a) in self.store.args(f[HEAD]).iter().enumerate() {
            match self.store.value(a) {
                Value::Var(v) => head_vars.push(v.index()),
                _ => {
                    // No variable there: never this index.
                    head_vars.push(u32::MAX);
                    let mut paths = HashMap::new();
                    self.var_paths(a, &mut Vec::new(), &mut paths);
                    for (v, path) in paths {
                        head_paths.insert(v, (i, path));
                    }
                }
            }
        }
        let in_arg = self.field(s, IN_ARG);
        let out_arg = self.field(s, OUT_ARG);
        let diag_mod = self.field(s, DIAG_MOD);
        let mut id_vars_all = Vec::new();
        self.term_vars(f[ID], &mut id_vars_all);
        // A variable in_arg takes the pipe unless it is a parameter or
        // the id's (then the pipe is unified with its value).
        let in_var = in_arg.and_then(|t| match self.store.value(t) {
            Value::Var(v)
                if !head_vars.contains(&v.index())
                    && !head_paths.contains_key(&v.index())
                    && !id_vars_all.contains(&v.index()) =>
            {
                Some(v.index())
            }
            _ => None,
        });
        let mut select = Vec::new();
        let mut id_vars = Vec::new();
        let mut id_paths = HashMap::new();
        let mut compound_id = None;
        let mut pattern = None;
        if let Value::Compound(_, args) = self.store.value(f[ID]) {
            if self.simple_id(args) {
                let mut parts = Vec::new();
                for (i, &arg) in args.iter().enumerate() {
                    if let Value::Var(v) = self.store.value(arg) {
                        id_vars.push((v.index(), i));
                        parts.push(IdPart::Fresh(self.reg()));
                    } else {
                        select.push((i, arg));
                        parts.push(IdPart::Const(arg));
                    }
                }
                compound_id = Some(parts);
            } else {
                let mut fresh_vars = HashMap::new();
                let mut fresh = Vec::new();
                for &v in &id_vars_all {
                    let r = self.reg();
                    fresh_vars.insert(v, r);
                    fresh.push(r);
                }
                let build = self.build(f[ID], &fresh_vars, 0)?;
                self.var_paths(f[ID], &mut Vec::new(), &mut id_paths);
                pattern = Some(IdPattern {
                    term: f[ID],
                    fresh,
                    build,
                });
            }
        }
        let mut inits = Vec::new();
        for &v in &inst_vars {
            let init = if let Some(&(_, i)) = id_vars.iter().find(|(x, _)| *x == v) {
                Init::IdArg(i)
            } else if let Some(path) = id_paths.get(&v) {
                Init::IdPath(Box::clone(path))
            } else if let Some(i) = head_vars.iter().position(|&h| h == v) {
                Init::HeadArg(i)
            } else if let Some((i, path)) = head_paths.get(&v) {
                Init::HeadPath(*i, Box::clone(path))
            } else if Some(v) == in_var {
                Init::Pipe
            } else {
                Init::Fresh
            };
            let r = self.reg();
            inits.push((r, init));
            scope.vars.insert(v, r);
        }
        // An id variable that is part of a head pattern: linked to the call
        // by the term path only (not planned).
        if id_vars_all.iter().any(|v| head_paths.contains_key(v)) {
            return Err(Unsupported);
        }
        // Id variables that are parameters: linked to the call after selection (D-7).
        let links: Vec<(Reg, usize)> = head_vars
            .iter()
            .enumerate()
            .filter(|(_, v)| id_vars_all.contains(v))
            .filter_map(|(i, v)| scope.vars.get(v).map(|&r| (r, i)))
            .collect();
        let in_plan = match in_arg {
            Some(t) => Some((self.build(t, &scope.vars, 0)?, in_var.is_none(), self.reg())),
            None => None,
        };
        // The term as written is needed by a final (evaluated when it
        // ends) and by a `prog` run on a copy (its variables linked);
        // otherwise each arc evaluates the out_arg itself
        // ([`ArcPlan::out_arg`]) and building it is wasted work.
        let out_plan = match out_arg {
            Some(t) if s.kind == Kind::Final || (s.kind != Kind::Recursive && prog_on_copy) => {
                Some((self.build(t, &scope.vars, 0)?, self.reg()))
            }
            _ => None,
        };
        let prog_plan = match prog {
            None => None,
            Some(p) => {
                if !prog_on_copy {
                    let parts = self.list_literal(p).unwrap_or_else(|| vec![p]);
                    let evs = parts
                        .into_iter()
                        .map(|part| self.ev(part, &mut scope, 0))
                        .collect::<Plan<Vec<_>>>()?;
                    Some(Prog::InPlace(evs))
                } else {
                    Some(Prog::Copy(self.build(p, &scope.vars, 0)?))
                }
            }
        };
        let kind = match s.kind {
            Kind::Final => KindPlan::Final {
                diag_mod: match diag_mod {
                    Some(d) => Some(self.build(d, &scope.vars, 0)?),
                    None => None,
                },
            },
            Kind::Perceptual => KindPlan::Perceptual(self.arcs(s, &mut scope, false)?),
            Kind::Recursive => {
                let e = self.field(s, EMBEDDED_DM).ok_or(Unsupported)?;
                let eval_call = !(self.store.is_ground(e) && self.inert(e, true));
                let call = self.build(e, &scope.vars, 0)?;
                let mut needed = Vec::new();
                for t in [Some(f[ARCS]), out_arg, diag_mod].into_iter().flatten() {
                    self.term_vars(t, &mut needed);
                }
                let saved: Vec<Reg> = inst_vars
                    .iter()
                    .filter(|v| needed.contains(v))
                    .map(|v| scope.vars[v])
                    .collect();
                let mut exit_scope = Scope {
                    vars: scope.vars.clone(),
                    lazy: HashSet::new(),
                };
                let exit = self.arcs(s, &mut exit_scope, true)?;
                KindPlan::Recursive {
                    call,
                    eval_call,
                    saved,
                    exit,
                }
            }
        };
        Ok(SitPlan {
            id,
            select,
            compound_id,
            pattern,
            inits,
            links,
            in_arg: in_plan,
            out_arg: out_plan,
            prog: prog_plan,
            kind,
            regs: self.regs as usize,
        })
    }

    /// The arcs of a perceptual situation, or the exit arcs of a recursive one.
    pub(crate) fn arcs(&mut self, s: &IrSituation, scope: &mut Scope, exit: bool) -> Plan<Arcs> {
        let f = self.store.args(s.template);
        let out_arg = self.field(s, OUT_ARG);
        let diag_mod = self.field(s, DIAG_MOD);
        let type_term = f[TYPE];
        let arcs: Vec<[Term; 3]> = self
            .store
            .list_iter(f[ARCS])
            .map(|arc| {
                let a = self.store.args(arc);
                [a[0], a[1], a[2]]
            })
            .collect();
        let neutral = self.store.atom_of(type_term) == Some(atoms::NEUTRAL);
        let always_first = !exit
            && neutral
            && arcs.len() == 1
            && self.store.atom_of(arcs[0][0]) == Some(atoms::EMPTY);
        // Each arc's variables: imported copies of the situation's, fresh otherwise (D-11).
        let mut scopes = Vec::new();
        let mut parts = Vec::new();
        let mut pure = true;
        for arc in &arcs {
            let mut vars = Vec::new();
            for &t in arc.iter().chain(out_arg.iter()) {
                self.term_vars(t, &mut vars);
            }
            let in_order: Vec<Term> = arc.iter().copied().chain(out_arg).collect();
            let mut in_expectation = Vec::new();
            self.term_vars(arc[0], &mut in_expectation);
            let lazy: HashSet<u32> = self.lazy_vars(&in_order, &|v| {
                scope.vars.contains_key(&v) || in_expectation.contains(&v)
            });
            let imported: Vec<u32> = vars
                .iter()
                .copied()
                .filter(|v| scope.vars.contains_key(v))
                .collect();
            let import_at = self.regs(imported.len());
            let import_from: Vec<Reg> = imported.iter().map(|v| scope.vars[v]).collect();
            let mut arc_vars = HashMap::new();
            let mut fresh = Vec::new();
            for (n, &v) in imported.iter().enumerate() {
                arc_vars.insert(v, import_at + n as Reg);
            }
            for &v in &vars {
                if arc_vars.contains_key(&v) {
                    continue;
                }
                let r = self.reg();
                if !lazy.contains(&v) {
                    fresh.push(r);
                }
                arc_vars.insert(v, r);
            }
            pure &= self.inert(arc[0], true)
                && in_expectation.iter().all(|v| !scope.vars.contains_key(v));
            scopes.push(Scope {
                vars: arc_vars,
                lazy,
            });
            parts.push((fresh, import_from, import_at));
        }
        let exps = self.regs(arcs.len());
        let mut plans = Vec::new();
        for ((arc, sc), (fresh, import_from, import_at)) in arcs.iter().zip(scopes).zip(parts) {
            let mut exp_scope = Scope {
                vars: sc.vars.clone(),
                lazy: HashSet::new(),
            };
            let expectation = self.ev(arc[0], &mut exp_scope, 0)?;
            let mut sc = sc;
            let action = match self.list_literal(arc[1]) {
                Some(items) if !self.inert(arc[1], true) || !self.store.is_ground(arc[1]) => {
                    let items = items
                        .into_iter()
                        .map(|x| self.ev(x, &mut sc, 0))
                        .collect::<Plan<Vec<_>>>()?;
                    let regs = self.regs(items.len());
                    Action::List { items, regs }
                }
                _ => Action::One(self.ev(arc[1], &mut sc, 0)?),
            };
            let next = self.next(arc[2], &mut sc, 0)?;
            // Evaluated, as the next situation is (a conditional, `get`,
            // `apply(..)`): its variables are the situation's, never lazy.
            let out_arg = match out_arg {
                Some(o) => Some(self.ev(o, &mut sc, 0)?),
                None => None,
            };
            let diag_mod = match diag_mod {
                Some(d) => Some(self.build(d, &scope.vars, 0)?),
                None => None,
            };
            plans.push(ArcPlan {
                fresh,
                import_from,
                import_at,
                expectation,
                action,
                next,
                out_arg,
                diag_mod,
            });
        }
        // A type that is not an atom is built from the situation's
        // variables, as an instance's would be.
        let type_term = self.build(type_term, &scope.vars, 0)?;
        Ok(Arcs {
            arcs: plans,
            pure,
            always_first,
            type_term,
            exps,
        })
    }
}

/// Whether `b` is a type test of a condition (`var/1`, `number/1`,
/// `is_list/1`, ... the runtime's `type_test`) or `\+` of one: in a
/// conjunction or disjunction ([`Cond::And`], [`Cond::Or`]) it holds where
/// the goal of its evaluated argument holds (its value is the compound,
/// not `true`: a back end calls it as a condition).
pub(crate) fn is_type_test(b: &Build) -> bool {
    match b {
        Build::Compound(op, args) if args.len() == 1 && op.as_str() == "\\+" => {
            is_type_test(&args[0])
        }
        Build::Compound(op, args) => {
            sitlog_runtime::type_test::TypeTest::of(op.as_str(), args.len()).is_some()
        }
        _ => false,
    }
}
