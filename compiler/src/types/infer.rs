//! The inference itself: per DM, the writes of each variable joined into
//! one type, then each situation given a typed plan ([`TSit`]) or a reason
//! to stay on terms.

use super::*;

/// Runs inference over a lowered program and its MIR (`mir::lower(ir)`,
/// built once by the caller and shared with the code generator).
pub fn infer(ir: &Ir, mir: &crate::mir::Mir) -> Types {
    let store = &ir.store;
    let mut dms = Vec::new();
    for dm in &ir.dms {
        dms.push(infer_dm(ir, dm));
    }
    typed_calls(mir, &mut dms);
    // Globals: initial values joined with the constant writes of every DM
    // where the name is not a local.
    let mut globals = Vec::new();
    for &(name, init) in &ir.globals {
        let mut ty = Ty::of_ground(store, init);
        let mut why = if ty == Ty::Term {
            format!("initial value `{}` is not ground", store.writeq(init))
        } else {
            format!("initial value `{}`", store.writeq(init))
        };
        for dm in &ir.dms {
            if dm.locals.iter().any(|(n, _)| *n == name) {
                continue;
            }
            let writes = writes_of(store, dm, name);
            (ty, why) = join_writes(store, dm, ty, why, &writes);
        }
        globals.push(VarTy {
            name: name.as_str().to_owned(),
            ty,
            why,
        });
    }
    Types { dms, globals }
}

/// Keeps a typed call only where it pays and is safe: the situation runs
/// as code (its exit arcs exist as code for when the callee ends through
/// the machine) and the callee's initial situation is typed. Demoting one
/// call may leave its DM with no typed situation but finals, and so demote
/// the calls into it: repeated until nothing changes.
fn typed_calls(mir: &crate::mir::Mir, dms: &mut [DmTypes]) {
    for (d, plans) in dms.iter_mut().zip(&mir.dms) {
        d.code = plans.iter().map(Option::is_some).collect();
        // Typed code runs from a situation's code: none without a plan.
        for (s, code) in d.situations.iter_mut().zip(&d.code) {
            if s.is_ok() && !code {
                *s = Err("it does not run as code".to_owned());
            }
        }
    }
    loop {
        let mut changed = false;
        for d in 0..dms.len() {
            for i in 0..dms[d].situations.len() {
                let Ok(TSit::Call {
                    callee: (callee, name),
                    ..
                }) = &dms[d].situations[i]
                else {
                    continue;
                };
                let why = if mir.dms[d][i].is_none() {
                    Some("it does not run as code".to_owned())
                } else if !dms[*callee].situations.first().is_some_and(|s| s.is_ok()) {
                    Some(format!("the initial situation of `{name}` runs on terms"))
                } else {
                    None
                };
                if let Some(why) = why {
                    dms[d].situations[i] = Err(why);
                    changed = true;
                }
            }
            let any = dms[d]
                .situations
                .iter()
                .any(|s| matches!(s, Ok(TSit::Perceptual { .. } | TSit::Call { .. })));
            if !any {
                for s in &mut dms[d].situations {
                    if s.is_ok() {
                        *s = Err("no other situation of the DM runs typed".to_owned());
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            return;
        }
    }
}

/// A write into a SitLog variable found in a DM's code.
pub(super) enum Write {
    Set(Term),
    Inc,
    /// `set`/`inc` whose variable name is not written out, or code that may
    /// write any variable (a user function, an unknown evaluation).
    Opaque(String),
}

pub(super) fn join_writes(
    store: &Store,
    dm: &IrDm,
    mut ty: Ty,
    mut why: String,
    writes: &[Write],
) -> (Ty, String) {
    for w in writes {
        if ty == Ty::Term {
            break;
        }
        match w {
            Write::Set(v) => {
                let t = Ty::of_ground(store, *v);
                let joined = ty.join(&t);
                if joined == Ty::Term {
                    why = format!(
                        "`set` to `{}` ({}) besides {why}",
                        show(store, dm, *v),
                        an(&t)
                    );
                } else if joined != ty {
                    why = format!("{why}, `set` to `{}`", show(store, dm, *v));
                }
                ty = joined;
            }
            Write::Inc => {
                if !matches!(ty, Ty::Int | Ty::Float) {
                    why = format!("`inc` of {} ({why})", an(&ty));
                    ty = Ty::Term;
                }
            }
            Write::Opaque(what) => {
                if !why.contains(what.as_str()) {
                    why = format!("{why}; {what}: checked on load");
                }
            }
        }
    }
    (ty, why)
}

/// Every write into `name` in the code of `dm` (any field of any situation).
pub(super) fn writes_of(store: &Store, dm: &IrDm, name: Atom) -> Vec<Write> {
    let mut out = Vec::new();
    for s in &dm.situations {
        let mut stack = vec![s.template];
        while let Some(t) = stack.pop() {
            if let Value::Compound(f, args) = store.value(t) {
                if args.len() == 2 && (f == atoms::SET || f == atoms::INC) {
                    match store.atom_of(args[0]) {
                        Some(n) if n == name => out.push(if f == atoms::SET {
                            Write::Set(args[1])
                        } else {
                            Write::Inc
                        }),
                        Some(_) => {}
                        None => out.push(Write::Opaque(format!(
                            "`{}` names its variable at run time",
                            show(store, dm, t)
                        ))),
                    }
                }
                stack.extend(args.iter());
            }
        }
    }
    out
}

pub(super) fn var_name(dm: &IrDm, v: u32) -> String {
    dm.var_index_names
        .iter()
        .find(|(i, _)| *i == v)
        .map_or_else(|| format!("_G{v}"), |(_, n)| n.clone())
}

pub(super) fn infer_dm(ir: &Ir, dm: &IrDm) -> DmTypes {
    let store = &ir.store;
    let locals: Vec<VarTy> = dm
        .locals
        .iter()
        .map(|&(name, init)| {
            let ty = Ty::of_ground(store, init);
            let why = if ty == Ty::Term {
                format!("default `{}` is not ground", store.writeq(init))
            } else {
                format!("default `{}`", store.writeq(init))
            };
            let writes = writes_of(store, dm, name);
            let (ty, why) = join_writes(store, dm, ty, why, &writes);
            let why = if writes.iter().any(|w| matches!(w, Write::Inc)) && ty != Ty::Term {
                format!("{why}; `inc` keeps it {}", an(&ty))
            } else {
                why
            };
            VarTy {
                name: name.as_str().to_owned(),
                ty,
                why,
            }
        })
        .collect();
    let head_vars: Vec<Option<u32>> = store
        .args(dm.head)
        .iter()
        .map(|&a| match store.value(a) {
            Value::Var(v) => Some(v.index()),
            _ => None,
        })
        .collect();
    let distinct_params = {
        let mut seen = Vec::new();
        head_vars
            .iter()
            .all(|v| v.is_some_and(|v| !seen.contains(&v) && (seen.push(v), true).1))
    };
    let mut cx = DmCx {
        ir,
        store,
        dm,
        locals: &locals,
        head_vars: &head_vars,
        params: vec![Ty::None; head_vars.len()],
        pipe: Ty::None,
        in_var: None,
    };
    let mut situations = Vec::new();
    for ix in 0..dm.situations.len() {
        let r = if distinct_params {
            cx.situation(ix)
        } else {
            Err("the DM's head has non-variable or repeated parameters".to_owned())
        };
        situations.push(r);
    }
    // A typed final situation alone gains nothing: the DM runs on terms.
    if !situations
        .iter()
        .any(|s| matches!(s, Ok(TSit::Perceptual { .. } | TSit::Call { .. })))
    {
        for s in &mut situations {
            if s.is_ok() {
                *s = Err("no other situation of the DM runs typed".to_owned());
            }
        }
    }
    // A parameter whose demanded types disagree: its situations stay untyped.
    let bad: Vec<usize> = (0..cx.params.len())
        .filter(|&i| cx.params[i] == Ty::Term)
        .collect();
    if !bad.is_empty() {
        for s in &mut situations {
            if let Ok(t) = s {
                let mut used = Vec::new();
                t.params_used(&mut used);
                if let Some(&i) = used.iter().find(|i| bad.contains(i)) {
                    *s = Err(format!(
                        "parameter `{}` is compared both as an int and as a float",
                        var_name(dm, head_vars[i].unwrap_or(0))
                    ));
                }
            }
        }
    }
    // The pipe compared both as an int and as a float: likewise.
    if cx.pipe == Ty::Term {
        for s in &mut situations {
            if s.as_ref().is_ok_and(|t| {
                t.uses(&|v| *v == TVal::Pipe) || matches!(t, TSit::Perceptual { out_arg: true, .. })
            }) {
                *s = Err("the pipe (in_arg) is compared both as an int and as a float".to_owned());
            }
        }
    }
    let pipe_used = situations
        .iter()
        .flatten()
        .any(|t| t.uses(&|v| *v == TVal::Pipe));
    let pipe = pipe_used.then(|| VarTy {
        name: "in_arg".to_owned(),
        ty: cx.pipe.clone(),
        why: format!(
            "compared with {} in typed code; checked on entry",
            an(&cx.pipe)
        ),
    });
    let params = head_vars
        .iter()
        .enumerate()
        .map(|(i, v)| {
            v.map(|v| {
                let (ty, why) = match &cx.params[i] {
                    Ty::None => (Ty::Term, "not used by typed code".to_owned()),
                    Ty::Term => (
                        Ty::Term,
                        "compared both as an int and as a float".to_owned(),
                    ),
                    t => (t.clone(), String::new()),
                };
                let why = match ty {
                    Ty::Term => why,
                    _ => format!("compared with {} in typed code; checked on entry", an(&ty)),
                };
                VarTy {
                    name: var_name(dm, v),
                    ty,
                    why,
                }
            })
        })
        .collect();
    DmTypes {
        params,
        pipe,
        locals,
        code: vec![false; situations.len()],
        situations,
    }
}

pub(super) struct DmCx<'a> {
    ir: &'a Ir,
    store: &'a Store,
    dm: &'a IrDm,
    locals: &'a [VarTy],
    head_vars: &'a [Option<u32>],
    /// Types the typed code demands of each parameter.
    params: Vec<Ty>,
    /// The type the typed code demands of the pipe.
    pipe: Ty,
    /// The variable in_arg of the situation being typed (the pipe).
    in_var: Option<u32>,
}

pub(super) const IN_ARG: usize = 3;
pub(super) const PROG: usize = 5;
pub(super) const EMBEDDED_DM: usize = 6;
pub(super) const DIAG_MOD: usize = 7;
pub(super) const OUT_ARG: usize = 4;

impl DmCx<'_> {
    fn present(&self, t: Term) -> bool {
        self.store.atom_of(t) != Some(none_marker())
    }

    fn situation(&mut self, ix: usize) -> Result<TSit, String> {
        let store = self.store;
        let s = &self.dm.situations[ix];
        let f = store.args(s.template);
        let Some(id) = store.atom_of(f[1]).filter(|&a| a != none_marker()) else {
            return Err(format!(
                "its id `{}` is not an atom",
                show(store, self.dm, f[1])
            ));
        };
        let Some(type_name) = store.atom_of(f[2]) else {
            return Err(format!(
                "its type `{}` is not an atom",
                show(store, self.dm, f[2])
            ));
        };
        // What the listing said of a perceptual situation with a `prog` or
        // an `out_arg` before they were typed (checked first, as then).
        let old_reason = [(OUT_ARG, "it has `out_arg`"), (PROG, "it has `prog`")]
            .into_iter()
            .find(|&(i, _)| self.present(f[i]))
            .map(|(_, why)| why.to_owned());
        let what = if s.kind == Kind::Perceptual {
            &[(EMBEDDED_DM, "embedded_dm"), (DIAG_MOD, "diag_mod")][..]
        } else if s.kind == Kind::Recursive {
            &[
                (OUT_ARG, "out_arg"),
                (PROG, "prog"),
                (IN_ARG, "in_arg"),
                (DIAG_MOD, "diag_mod"),
            ][..]
        } else {
            &[
                (OUT_ARG, "out_arg"),
                (PROG, "prog"),
                (EMBEDDED_DM, "embedded_dm"),
                (DIAG_MOD, "diag_mod"),
            ][..]
        };
        for &(i, what) in what {
            if self.present(f[i]) {
                return Err(old_reason.unwrap_or_else(|| format!("it has `{what}`")));
            }
        }
        // A variable in_arg names the pipe (D-8): typed like a parameter.
        self.in_var = None;
        if self.present(f[IN_ARG]) {
            match store.value(f[IN_ARG]) {
                _ if s.kind == Kind::Final => return Err("it has `in_arg`".to_owned()),
                Value::Var(v) if !self.head_vars.contains(&Some(v.index())) => {
                    self.in_var = Some(v.index());
                }
                _ => {
                    return Err(old_reason.unwrap_or_else(|| {
                        format!(
                            "its in_arg `{}` is not a variable",
                            show(store, self.dm, f[IN_ARG])
                        )
                    }))
                }
            }
        }
        match s.kind {
            Kind::Final => return Ok(TSit::Final { id }),
            Kind::Recursive => return self.call(id, f),
            Kind::Perceptual => {}
        }
        let raw: Vec<[Term; 3]> = store
            .list_iter(f[8])
            .map(|arc| {
                let a = store.args(arc);
                [a[0], a[1], a[2]]
            })
            .collect();
        // `prog ==> [V is E]` with `V` the out_arg: V an int the arcs may read.
        let mut bound: HashMap<u32, Ty> = HashMap::new();
        let prog = if self.present(f[PROG]) {
            let is = self.prog(f[PROG], f[OUT_ARG])?;
            bound.insert(is.var, Ty::Int);
            Some(is)
        } else if self.present(f[OUT_ARG]) {
            return Err("it has `out_arg`".to_owned());
        } else {
            None
        };
        let out_arg = prog.is_some();
        let always_first = type_name == atoms::NEUTRAL
            && raw.len() == 1
            && store.atom_of(raw[0][0]) == Some(atoms::EMPTY);
        let mut arcs = Vec::new();
        for (i, [e, a, n]) in raw.into_iter().enumerate() {
            let arc = self
                .arc(e, a, n, &bound)
                .map_err(|why| format!("arc {}: {why}", i + 1))?;
            arcs.push(arc);
        }
        if out_arg {
            // The pipe is written with an int.
            self.pipe = self.pipe.join(&Ty::Int);
        }
        Ok(TSit::Perceptual {
            id,
            type_name,
            always_first,
            prog,
            out_arg,
            arcs,
        })
    }

    /// A recursive situation as a typed call: `embedded_dm` an atom naming
    /// a DM without parameters, or a constant call (`count(2)`, arguments
    /// that evaluate to themselves) of a DM whose parameters are distinct
    /// variables; exit arcs with atom expectations that share no variable
    /// with the rest of the situation (nothing to save around the call).
    /// Whether the callee starts typed is decided once every DM is typed
    /// ([`infer`]).
    fn call(&mut self, id: Atom, f: &[Term]) -> Result<TSit, String> {
        let store = self.store;
        let e = f[EMBEDDED_DM];
        let Some((name, arity)) = store.functor(e) else {
            return Err(format!(
                "its embedded_dm `{}` is not an atom",
                show(store, self.dm, e)
            ));
        };
        if arity > 0 && !self.constant(e) {
            return Err(format!(
                "its embedded_dm `{}` passes arguments that are not constants",
                show(store, self.dm, e)
            ));
        }
        // The DM the machine calls: the first of that name.
        let Some(callee) = self
            .ir
            .dms
            .iter()
            .position(|d| d.name == name)
            .filter(|&d| self.ir.dms[d].arity == arity)
        else {
            return Err(format!(
                "its embedded_dm `{}` is not a DM of the program",
                show(store, self.dm, e)
            ));
        };
        let mut seen = Vec::new();
        for &a in store.args(self.ir.dms[callee].head) {
            match store.value(a) {
                Value::Var(v) if !seen.contains(&v.index()) => seen.push(v.index()),
                _ => {
                    return Err(format!(
                        "it calls `{name}`, whose parameters are not distinct variables"
                    ))
                }
            }
        }
        let mut shared = Vec::new();
        for &t in &f[..8] {
            shared.extend(store.term_vars(t));
        }
        let mut arcs = Vec::new();
        for (i, arc) in store.list_iter(f[8]).enumerate() {
            let a = store.args(arc);
            let (e, act, n) = (a[0], a[1], a[2]);
            if store.atom_of(e).is_none() {
                return Err(format!(
                    "exit arc {}: expectation `{}` is not an atom",
                    i + 1,
                    show(store, self.dm, e)
                ));
            }
            if store.term_vars(arc).iter().any(|v| shared.contains(v)) {
                return Err(format!(
                    "exit arc {} uses a variable of the situation",
                    i + 1
                ));
            }
            let arc = self
                .arc(e, act, n, &HashMap::new())
                .map_err(|why| format!("exit arc {}: {why}", i + 1))?;
            arcs.push(arc);
        }
        Ok(TSit::Call {
            id,
            callee: (callee, name),
            call: e,
            arcs,
        })
    }

    /// A typed `prog`: `V is E` (or `[V is E]`), `V` the out_arg variable,
    /// fresh, `E` an int expression.
    fn prog(&mut self, p: Term, out: Term) -> Result<TIs, String> {
        let store = self.store;
        // Any other shape: the reason the listing always gave.
        let other = || {
            Err(if self.present(out) {
                "it has `out_arg`".to_owned()
            } else {
                "it has `prog`".to_owned()
            })
        };
        let is = match list_literal(store, p) {
            Some(items) if items.len() == 1 => items[0],
            Some(_) => return other(),
            None => p,
        };
        let Value::Compound(op, &[v, e]) = store.value(is) else {
            return other();
        };
        let (Value::Var(var), Value::Var(o)) = (store.value(v), store.value(out)) else {
            return other();
        };
        if op.as_str() != "is"
            || var != o
            || self.head_vars.contains(&Some(var.index()))
            || self.in_var == Some(var.index())
            || store
                .term_vars(e)
                .iter()
                .any(|&x| matches!(store.value(x), Value::Var(w) if w == var))
        {
            return other();
        }
        let expr = self.expr(e, 0)?;
        Ok(TIs {
            var: var.index(),
            expr,
        })
    }

    /// An int expression of a typed `prog`.
    fn expr(&mut self, e: Term, depth: usize) -> Result<TExpr, String> {
        let store = self.store;
        if let Value::Compound(op, &[a, b]) = store.value(e) {
            let c = match op.as_str() {
                "+" => '+',
                "-" => '-',
                "*" => '*',
                _ => {
                    return Err(format!(
                        "prog expression `{}` is not `+`/`-`/`*` on ints",
                        show(store, self.dm, e)
                    ))
                }
            };
            if depth > 16 {
                return Err("its prog expression is too deep".to_owned());
            }
            let a = self.expr(a, depth + 1)?;
            let b = self.expr(b, depth + 1)?;
            return Ok(TExpr::Bin(c, Box::new(a), Box::new(b)));
        }
        let (v, ty) = self.val(e, &HashMap::new())?;
        match (&v, ty) {
            (TVal::Int(_), _) => {}
            (TVal::Param(i), Ty::None) => self.params[*i] = self.params[*i].join(&Ty::Int),
            (TVal::Pipe, Ty::None) => self.pipe = self.pipe.join(&Ty::Int),
            _ => {
                return Err(format!(
                    "prog operand `{}` is not an int",
                    show(store, self.dm, e)
                ))
            }
        }
        Ok(TExpr::Val(v))
    }

    fn constant(&self, t: Term) -> bool {
        self.store.is_ground(t) && inert(self.store, t)
    }

    fn local(&self, name: Atom) -> Result<usize, String> {
        let Some(i) = self.dm.locals.iter().position(|(n, _)| *n == name) else {
            return Err(format!(
                "`{name}` is not a local of the DM (globals stay terms)"
            ));
        };
        if !self.locals[i].ty.is_native() {
            return Err(format!("local `{name}` is {}", an(&self.locals[i].ty)));
        }
        Ok(i)
    }

    fn arc(
        &mut self,
        e: Term,
        a: Term,
        n: Term,
        prog_bound: &HashMap<u32, Ty>,
    ) -> Result<TArc, String> {
        let store = self.store;
        if !self.constant(e) {
            return Err(format!(
                "expectation `{}` is not a constant",
                show(store, self.dm, e)
            ));
        }
        // Arc variables bound so far (`prog`'s first), with their types.
        let mut bound: HashMap<u32, Ty> = prog_bound.clone();
        let action = match list_literal(store, a) {
            Some(items) if !self.constant(a) => {
                let mut out = Vec::new();
                for x in items {
                    out.push(self.item(x, &mut bound)?);
                }
                TAction::List(out)
            }
            _ if self.constant(a) => TAction::Const(a),
            _ => {
                return Err(format!(
                    "action `{}` is not a list of constants and `get`/`set`/`inc` of typed locals",
                    show(store, self.dm, a)
                ))
            }
        };
        let next = self.next(n, &bound)?;
        Ok(TArc {
            expectation: e,
            action,
            next,
        })
    }

    fn item(&self, x: Term, bound: &mut HashMap<u32, Ty>) -> Result<TItem, String> {
        let store = self.store;
        if self.constant(x) {
            return Ok(TItem::Const(x));
        }
        if let Value::Compound(op, &[var, arg]) = store.value(x) {
            if [atoms::GET, atoms::SET, atoms::INC].contains(&op) {
                let Some(name) = store.atom_of(var) else {
                    return Err(format!("`{}` names no variable", show(store, self.dm, x)));
                };
                let local = self.local(name)?;
                let ty = &self.locals[local].ty;
                if op == atoms::SET {
                    if !store.is_ground(arg) || Ty::of_ground(store, arg).join(ty) != *ty {
                        return Err(format!(
                            "`{}` sets a value not of type {ty}",
                            show(store, self.dm, x)
                        ));
                    }
                    return Ok(TItem::Set { local, value: arg });
                }
                if op == atoms::INC && !matches!(ty, Ty::Int | Ty::Float) {
                    return Err(format!("`inc` of {}", an(ty)));
                }
                let bind = match store.value(arg) {
                    Value::Var(v)
                        if self.head_vars.contains(&Some(v.index()))
                            || self.in_var == Some(v.index()) =>
                    {
                        return Err(format!(
                            "`{}` binds a DM parameter or the in_arg",
                            show(store, self.dm, x)
                        ))
                    }
                    Value::Var(v) if !bound.contains_key(&v.index()) => {
                        bound.insert(v.index(), ty.clone());
                        // `_` and other singletons are bound all the same.
                        Some(v.index())
                    }
                    _ => {
                        return Err(format!(
                            "`{}`: the variable is not fresh",
                            show(store, self.dm, x)
                        ))
                    }
                };
                return Ok(if op == atoms::INC {
                    TItem::Inc { local, bind }
                } else {
                    TItem::Get { local, bind }
                });
            }
        }
        Err(format!(
            "action element `{}` is not a constant or `get`/`set`/`inc` of a typed local",
            show(store, self.dm, x)
        ))
    }

    fn next(&mut self, n: Term, bound: &HashMap<u32, Ty>) -> Result<TNext, String> {
        let store = self.store;
        if let Some(name) = store.atom_of(n) {
            // The first situation whose id unifies with the atom (D-21).
            for (i, s) in self.dm.situations.iter().enumerate() {
                let id = store.args(s.template)[1];
                match store.value(id) {
                    Value::Var(_) => break,
                    Value::Atom(a) if a == name => return Ok(TNext::Sit(i as u32, name)),
                    _ => {}
                }
            }
            return Err(format!(
                "next situation `{name}` is not an atom id of the DM"
            ));
        }
        if let Some((cond, then, other)) = eval::conditional(store, n) {
            let Value::Compound(op, &[l, r]) = store.value(cond) else {
                return Err(format!(
                    "condition `{}` is not a comparison",
                    show(store, self.dm, cond)
                ));
            };
            let op = match ArithCmp::from_atom(op) {
                Some(op) => Cmp::Arith(op),
                None if op.as_str() == "==" => Cmp::Identical,
                None if op.as_str() == "\\==" => Cmp::NotIdentical,
                None => {
                    return Err(format!(
                        "condition `{}` is not an arithmetic comparison or `==`/`\\==`",
                        show(store, self.dm, cond)
                    ))
                }
            };
            let (a, ta) = self.val(l, bound)?;
            let (b, tb) = self.val(r, bound)?;
            if !matches!(op, Cmp::Arith(_)) {
                // Atoms of any two sets compare by identity.
                if !matches!(ta, Ty::Atoms(_)) || !matches!(tb, Ty::Atoms(_)) {
                    return Err(format!(
                        "`{}` compares {} with {} (typed `==` is on atoms)",
                        show(store, self.dm, cond),
                        an(&ta),
                        an(&tb)
                    ));
                }
                let then = Box::new(self.next(then, bound)?);
                let other = Box::new(self.next(other, bound)?);
                return Ok(TNext::If {
                    op,
                    float: false,
                    a,
                    b,
                    then,
                    other,
                });
            }
            let ty = match (&ta, &tb) {
                // Two values whose types are demanded (parameters, the
                // pipe): ints, checked when the frame is loaded (anything
                // else runs the untyped path).
                (Ty::None, Ty::None) => Ty::Int,
                (Ty::None, t) | (t, Ty::None) => t.clone(),
                (x, y) if x == y => x.clone(),
                _ => {
                    return Err(format!(
                        "`{}` compares {} with {}",
                        show(store, self.dm, cond),
                        an(&ta),
                        an(&tb)
                    ))
                }
            };
            if !matches!(ty, Ty::Int | Ty::Float) {
                return Err(format!(
                    "`{}` compares {ty} values",
                    show(store, self.dm, cond)
                ));
            }
            for v in [&a, &b] {
                match v {
                    TVal::Param(i) => self.params[*i] = self.params[*i].join(&ty),
                    TVal::Pipe => self.pipe = self.pipe.join(&ty),
                    _ => {}
                }
            }
            let then = Box::new(self.next(then, bound)?);
            let other = Box::new(self.next(other, bound)?);
            return Ok(TNext::If {
                op,
                float: ty == Ty::Float,
                a,
                b,
                then,
                other,
            });
        }
        Err(format!(
            "next situation `{}` is not an atom or a conditional on a comparison",
            show(store, self.dm, n)
        ))
    }

    /// A typed operand; `Ty::None` for a parameter (its type is demanded).
    fn val(&self, t: Term, bound: &HashMap<u32, Ty>) -> Result<(TVal, Ty), String> {
        let store = self.store;
        match store.value(t) {
            Value::Atom(a) => Ok((TVal::Atom(a), Ty::Atoms(vec![a]))),
            Value::Int(i) => Ok((TVal::Int(i), Ty::Int)),
            Value::Float(f) => Ok((TVal::Float(f), Ty::Float)),
            Value::Var(v) => {
                if let Some(ty) = bound.get(&v.index()) {
                    return Ok((TVal::Var(v.index()), ty.clone()));
                }
                if let Some(i) = self.head_vars.iter().position(|h| *h == Some(v.index())) {
                    return Ok((TVal::Param(i), Ty::None));
                }
                if self.in_var == Some(v.index()) {
                    return Ok((TVal::Pipe, Ty::None));
                }
                Err(format!(
                    "`{}` is not bound to a typed value",
                    var_name(self.dm, v.index())
                ))
            }
            // `get(n, _)`: the value of a typed local, read in place (the
            // fresh variable it would bind is used nowhere: a variable
            // used again is not bound in typed code, so its use leaves
            // the situation on terms).
            Value::Compound(get, &[name, var])
                if get.as_str() == "get"
                    && store.is_var(var)
                    && !bound.contains_key(&store.var_of(var).map_or(u32::MAX, |v| v.index())) =>
            {
                let Some(name) = store.atom_of(name) else {
                    return Err(format!(
                        "operand `{}` names its variable at run time",
                        show(store, self.dm, t)
                    ));
                };
                let i = self.local(name)?;
                Ok((TVal::Local(i), self.locals[i].ty.clone()))
            }
            _ => Err(format!(
                "operand `{}` is not a number or a typed variable",
                show(store, self.dm, t)
            )),
        }
    }
}

/// Whether evaluating `t` gives `t` back with no effect (no construct of L in it).
pub(super) fn inert(store: &Store, t: Term) -> bool {
    let mut stack = vec![t];
    while let Some(u) = stack.pop() {
        if let Value::Compound(name, args) = store.value(u) {
            if !eval::evaluates_arguments_only(name, args.len()) {
                return false;
            }
            stack.extend(args.iter());
        }
    }
    true
}

/// The elements of a non-empty proper list written out in the source.
pub(super) fn list_literal(store: &Store, t: Term) -> Option<Vec<Term>> {
    let mut items = Vec::new();
    let mut rest = t;
    loop {
        match store.value(rest) {
            Value::Compound(name, &[head, tail]) if name == atoms::DOT => {
                items.push(head);
                rest = tail;
            }
            Value::Atom(a) if a == atoms::NIL && !items.is_empty() => return Some(items),
            _ => return None,
        }
    }
}
