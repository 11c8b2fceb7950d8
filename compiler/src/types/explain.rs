//! `sitlogc build --explain-types`: what inference found, per DM, variable
//! and situation, as a user reads it, ending with one summary line for the
//! application ([`summary`]).

use super::*;

/// The `--explain-types` listing: every DM's parameters, locals and
/// situations, typed or not and why; then the globals; last, exactly one
/// line [`summary`].
pub fn explain(ir: &Ir, types: &Types) -> String {
    explain_with(ir, types, None)
}

/// [`explain`] with, when given, what [`crate::mir::ty::infer`] found on
/// the MIR: a line per DM and per situation, and its summary line just
/// before this listing's two summary lines; and per DM whether the code
/// generator gives it native code (`crate::codegen::native_dms`, passed
/// in: inference does not reach up into the back end).
pub fn explain_with(
    ir: &Ir,
    types: &Types,
    mir: Option<(&crate::mir::ty::MirTypes, &[Result<NativeDm, String>])>,
) -> String {
    let store = &ir.store;
    let mut out = String::new();
    let (mir, native) = match mir {
        Some((m, n)) => (Some(m), Some(n)),
        None => (None, None),
    };
    for (d, (dm, t)) in ir.dms.iter().zip(&types.dms).enumerate() {
        let _ = writeln!(out, "DM {}/{}", dm.name.as_str(), dm.arity);
        if let Some(m) = mir {
            let _ = writeln!(out, "{}", m.dm_line(ir, d));
        }
        match native.as_ref().map(|n| &n[d]) {
            Some(Ok(n)) if n.values == dm.situations.len() && n.fixed == n.values => {
                let _ = writeln!(
                    out,
                    "  native code: every situation, on Rust values of fixed shapes"
                );
            }
            Some(Ok(n)) if n.values == dm.situations.len() => {
                let _ = writeln!(out, "  native code: every situation, on Rust values");
            }
            Some(Ok(n)) => {
                let _ = writeln!(
                    out,
                    "  native code: {}/{} situations ({} on Rust values, {} of them only fixed shapes)",
                    n.native,
                    dm.situations.len(),
                    n.values,
                    n.fixed
                );
                for (s, why) in dm.situations.iter().zip(&n.why) {
                    if let Some(why) = why {
                        let id = show(store, dm, store.args(s.template)[1]);
                        let _ = writeln!(out, "    no native code for `{id}`: {why}");
                    }
                }
            }
            Some(Err(why)) => {
                let _ = writeln!(out, "  native code: no ({why})");
            }
            None => {}
        }
        for (i, p) in t.params.iter().enumerate() {
            match p {
                Some(p) => {
                    let _ = writeln!(
                        out,
                        "  parameter {} `{}`: {} ({})",
                        i + 1,
                        p.name,
                        p.ty,
                        p.why
                    );
                }
                None => {
                    let _ = writeln!(out, "  parameter {}: not a variable", i + 1);
                }
            }
        }
        if let Some(p) = &t.pipe {
            let _ = writeln!(out, "  pipe (in_arg): {} ({})", p.ty, p.why);
        }
        for l in &t.locals {
            let _ = writeln!(out, "  local `{}`: {} ({})", l.name, l.ty, l.why);
        }
        for (n, (s, r)) in dm.situations.iter().zip(&t.situations).enumerate() {
            let id = show(store, dm, store.args(s.template)[1]);
            match r {
                Ok(plan) => {
                    let mut vars = Vec::new();
                    if let TSit::Call {
                        callee: (_, name), ..
                    } = plan
                    {
                        vars.push(format!("calls `{name}` on a typed frame"));
                    }
                    if let TSit::Perceptual { prog: Some(is), .. } = plan {
                        vars.push(format!("prog `{}`: int", var_name(dm, is.var)));
                    }
                    for (i, arc) in plan.arcs().iter().enumerate() {
                        if let TAction::List(items) = &arc.action {
                            for it in items {
                                if let TItem::Inc {
                                    local,
                                    bind: Some(v),
                                }
                                | TItem::Get {
                                    local,
                                    bind: Some(v),
                                } = it
                                {
                                    vars.push(format!(
                                        "arc {} `{}`: {}",
                                        i + 1,
                                        var_name(dm, *v),
                                        t.locals[*local].ty
                                    ));
                                }
                            }
                        }
                    }
                    if vars.is_empty() {
                        let _ = writeln!(out, "  situation `{id}`: typed");
                    } else {
                        let _ = writeln!(out, "  situation `{id}`: typed ({})", vars.join(", "));
                    }
                }
                Err(why) if t.code[n] => {
                    let _ = writeln!(out, "  situation `{id}`: code on terms ({why})");
                }
                Err(_) => {
                    let _ = writeln!(
                        out,
                        "  situation `{id}`: template (instantiated at run time: {})",
                        template_why(store, s)
                    );
                }
            }
            if let Some(m) = mir {
                let _ = writeln!(out, "{}", m.sit_line(d, n));
            }
        }
    }
    if !types.globals.is_empty() {
        let _ = writeln!(out, "globals (kept as terms by generated code)");
        for g in &types.globals {
            let _ = writeln!(out, "  `{}`: {} ({})", g.name, g.ty, g.why);
        }
    }
    if let Some(m) = mir {
        let _ = writeln!(out, "{}", m.summary());
    }
    let native_sits = native.map(|n| {
        n.iter()
            .map(|n| n.as_ref().map_or((0, 0), |n| (n.values, n.fixed)))
            .fold((0, 0), |(a, b), (x, y)| (a + x, b + y))
    });
    let _ = writeln!(out, "{}", summary_with(types, native_sits));
    out
}

/// Why the MIR gives situation `s` no plan (see [`crate::mir`]'s rule).
fn template_why(store: &Store, s: &crate::ir::IrSituation) -> &'static str {
    let f = store.args(s.template);
    let id = f[crate::mir::ID];
    if store.atom_of(id).is_none() && store.functor(id).is_none() {
        "its id is not a name"
    } else if s.kind == Kind::Recursive
        && store.atom_of(f[crate::mir::EMBEDDED_DM]) == Some(none_marker())
    {
        "a recursive situation without `embedded_dm`"
    } else {
        "its DM's parameters are not distinct variables, its id shares one, or a term is too deep"
    }
}

/// The listing's last two lines: `situations on native values: N/Y`, then
/// exactly `situations compiled as code: X/Y; variables typed: A/B`.
/// X of the application's Y situations run as generated code (a
/// [MIR](crate::mir) plan: no template instantiated, next situations
/// selected by the code), N of those on native values (a typed plan); A
/// of its B variables (DM parameters, pipes read by typed code, locals
/// and globals) have a type other than `term`.
pub fn summary(types: &Types) -> String {
    summary_with(types, None)
}

/// [`summary`] counting also `native` situations of DMs that run natively
/// (`crate::codegen::native`; none of them has a typed plan): how many,
/// and how many of those hold only fixed shapes (no `Val`: no register
/// typed `ground` or a compound), said after the count as `(M with only
/// fixed shapes)` (typed plans hold fixed shapes only).
pub fn summary_with(types: &Types, native: Option<(usize, usize)>) -> String {
    let (mut sits, mut code, mut typed_sits, mut vars, mut typed_vars) = (0, 0, 0, 0, 0);
    let mut count = |v: &VarTy| {
        vars += 1;
        if v.ty != Ty::Term {
            typed_vars += 1;
        }
    };
    for dm in &types.dms {
        dm.params.iter().flatten().for_each(&mut count);
        dm.pipe.iter().for_each(&mut count);
        dm.locals.iter().for_each(&mut count);
        sits += dm.situations.len();
        code += dm.code.iter().filter(|&&c| c).count();
        typed_sits += dm.situations.iter().filter(|s| s.is_ok()).count();
    }
    types.globals.iter().for_each(&mut count);
    let (n, fixed) = native.unwrap_or((0, 0));
    let shapes = match native {
        Some(_) => format!(" ({} with only fixed shapes)", typed_sits + fixed),
        None => String::new(),
    };
    let typed_sits = typed_sits + n;
    format!(
        "situations on native values: {typed_sits}/{sits}{shapes}\n\
         situations compiled as code: {code}/{sits}; variables typed: {typed_vars}/{vars}"
    )
}

/// What the code generator does with one DM's situations
/// (`crate::codegen::native_dms`).
#[derive(Clone, Debug)]
pub struct NativeDm {
    /// How many situations have native code.
    pub native: usize,
    /// How many of those hold no ground term (no register typed `term`):
    /// on native values.
    pub values: usize,
    /// How many of those hold no `Val` either (only fixed shapes).
    pub fixed: usize,
    /// Per situation, why it has no native code (`None`: it has).
    pub why: Vec<Option<String>>,
}
