//! `sitlogc build --explain-types`: what inference found, per DM, variable
//! and situation, as a user reads it.

use super::*;

/// The `--explain-types` listing: every DM's parameters, locals and
/// situations, typed or not and why; then the globals.
pub fn explain(ir: &Ir, types: &Types) -> String {
    let store = &ir.store;
    let mut out = String::new();
    for (dm, t) in ir.dms.iter().zip(&types.dms) {
        let _ = writeln!(out, "DM {}/{}", dm.name.as_str(), dm.arity);
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
        for l in &t.locals {
            let _ = writeln!(out, "  local `{}`: {} ({})", l.name, l.ty, l.why);
        }
        for (s, r) in dm.situations.iter().zip(&t.situations) {
            let id = show(store, dm, store.args(s.template)[1]);
            match r {
                Ok(plan) => {
                    let mut vars = Vec::new();
                    if let TSit::Perceptual { arcs, .. } = plan {
                        for (i, arc) in arcs.iter().enumerate() {
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
                    }
                    if vars.is_empty() {
                        let _ = writeln!(out, "  situation `{id}`: typed");
                    } else {
                        let _ = writeln!(out, "  situation `{id}`: typed ({})", vars.join(", "));
                    }
                }
                Err(why) => {
                    let _ = writeln!(out, "  situation `{id}`: terms ({why})");
                }
            }
        }
    }
    if !types.globals.is_empty() {
        let _ = writeln!(out, "globals (kept as terms by generated code)");
        for g in &types.globals {
            let _ = writeln!(out, "  `{}`: {} ({})", g.name, g.ty, g.why);
        }
    }
    out
}
