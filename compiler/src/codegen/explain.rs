//! `sitlogc build --explain-types`: the typed MIR ([`crate::mir::ty`]) and
//! what the native code generator ([`super::native`]) does with it, per
//! DM and situation, as a user reads it; it ends with exactly two lines
//! for the application ([`summary`]).
//!
//! Invariant: every figure is read from the generator's own decisions
//! (the MIR built and typed once, the same `Gen` that `generate` uses),
//! so the listing says what the generated code does.

use super::native::{Held, NativeCode, Visit};
use super::Gen;
use crate::ir::{none_marker, Ir, IrDm};
use sitlog_runtime::machine::Kind;
use sitlog_runtime::Store;
use std::fmt::Write as _;

/// The `--explain-types` listing of a program: per DM its MIR types, its
/// native code and each situation; then the globals, the MIR inference's
/// summary, the native code's total, and last the two lines of
/// `summary`.
pub fn explain_types(ir: &Ir) -> String {
    let mut g = Gen::new(ir, super::Options::default());
    g.collect(ir);
    let Some(types) = g.mir_types.as_ref() else {
        unreachable!("a typed generator has types")
    };
    let store = &ir.store;
    let mut out = String::new();
    let mut totals = Totals::default();
    for (d, dm) in ir.dms.iter().enumerate() {
        let _ = writeln!(out, "DM {}/{}", dm.name.as_str(), dm.arity);
        let _ = writeln!(out, "{}", types.dm_line(ir, d));
        let native = g.native_code(dm, d, &types.dms[d]);
        // Emitted only with a native situation (see `emit_dm`).
        let native = native.and_then(|n| {
            if n.native_sits > 0 {
                Ok(n)
            } else {
                Err("no situation has native code".to_owned())
            }
        });
        match &native {
            Ok(n)
                if n.on_native_values == dm.situations.len()
                    && n.fixed_shapes == n.on_native_values =>
            {
                let _ = writeln!(
                    out,
                    "  native code: every situation, on Rust values of fixed shapes"
                );
            }
            Ok(n) if n.on_native_values == dm.situations.len() => {
                let _ = writeln!(out, "  native code: every situation, on Rust values");
            }
            Ok(n) => {
                let _ = writeln!(
                    out,
                    "  native code: {}/{} situations ({} on Rust values, {} of them only fixed shapes)",
                    n.native_sits,
                    dm.situations.len(),
                    n.on_native_values,
                    n.fixed_shapes
                );
            }
            Err(why) => {
                let _ = writeln!(out, "  native code: no ({why})");
            }
        }
        for (i, s) in dm.situations.iter().enumerate() {
            let id = show(store, dm, store.args(s.template)[crate::mir::ID]);
            let planned = g.mir.plan(d as u32, i as u32).is_some();
            let line = match (&native, planned) {
                (_, false) => format!(
                    "template (instantiated at run time: {})",
                    template_why(store, s)
                ),
                (Ok(n), true) if n.why[i].is_none() => {
                    let values = types.dms[d].sits[i]
                        .as_ref()
                        .is_some_and(|st| st.regs.iter().all(|r| r.ty.is_native()));
                    let on = if values {
                        "native code on Rust values"
                    } else {
                        "native code, holding ground terms as handles"
                    };
                    match n.visits.get(i).copied().flatten() {
                        Some(Visit::Template) => format!(
                            "{on}, but run from its template at every visit (on every path its \
                             code calls the machine's template: not on native values, not \
                             compiled as code)"
                        ),
                        Some(Visit::HandsOver) => format!(
                            "{on}, but handing the native frames over at every visit \
                             (`nat_hand_over`: the frames below made machine frames, their \
                             values terms: not on native values)"
                        ),
                        Some(Visit::Partly) => format!(
                            "{on}, but handing the native frames over or running the template \
                             on some paths (not a failed conversion, not the history's: terms \
                             there, not on native values)"
                        ),
                        _ => on.to_owned(),
                    }
                }
                (Ok(n), true) => format!(
                    "code on terms ({})",
                    n.why[i].as_deref().unwrap_or("no reason given")
                ),
                (Err(why), true) => format!("code on terms ({why})"),
            };
            let _ = writeln!(out, "  situation `{id}`: {line}");
            let _ = writeln!(out, "{}", types.sit_line(d, i));
        }
        if let Some(line) = totals.add(ir, d, types, native.as_ref().ok()) {
            let _ = writeln!(out, "{line}");
        }
    }
    if !types.globals.is_empty() {
        let gs: Vec<String> = types
            .globals
            .iter()
            .map(|(n, t)| format!("`{}`: {}", n.as_str(), t.ty))
            .collect();
        let _ = writeln!(
            out,
            "globals (MIR types; generated code keeps them as the machine's terms): {}",
            gs.join(", ")
        );
    }
    totals.vars += types.globals.len();
    let _ = writeln!(out, "{}", types.summary());
    let _ = writeln!(
        out,
        "native code: {}/{} situations ({} on Rust values, {} of them only fixed shapes)",
        totals.native, totals.sits, totals.values, totals.fixed
    );
    let names = |v: &[String]| {
        if v.is_empty() {
            String::new()
        } else {
            format!(" ({})", v.join(", "))
        }
    };
    let _ = writeln!(
        out,
        "situations run from the template at every visit: {}{}",
        totals.template.len(),
        names(&totals.template)
    );
    let _ = writeln!(
        out,
        "situations handing the native frames over at every visit: {}{}",
        totals.hands.len(),
        names(&totals.hands)
    );
    let _ = writeln!(
        out,
        "situations handing over or running the template on some paths: {}{}",
        totals.partly.len(),
        names(&totals.partly)
    );
    let _ = writeln!(out, "{}", summary(&totals));
    out
}

/// The application's figures, summed over its DMs.
#[derive(Default)]
struct Totals {
    /// Situations, those that run as code (a MIR plan), those with native
    /// code, those of them on Rust values, and of those the ones holding
    /// only fixed shapes.
    sits: usize,
    code: usize,
    native: usize,
    values: usize,
    fixed: usize,
    /// DM variables, and those generated code holds as Rust values.
    vars: usize,
    held: usize,
    /// The situations with native code whose every visit runs from the
    /// template, those whose every visit hands the native frames over,
    /// and those that do either on some paths only ([`Visit`]), as
    /// `dm/id`.
    template: Vec<String>,
    hands: Vec<String>,
    partly: Vec<String>,
}

impl Totals {
    /// Adds DM `d`'s figures; gives its line saying which of its
    /// variables generated code holds as Rust values (none when it has
    /// no variable).
    fn add(
        &mut self,
        ir: &Ir,
        d: usize,
        types: &crate::mir::ty::MirTypes,
        native: Option<&NativeCode>,
    ) -> Option<String> {
        let dm = &ir.dms[d];
        let t = &types.dms[d];
        self.sits += dm.situations.len();
        self.code += t.sits.iter().filter(|s| s.is_some()).count();
        if let Some(n) = native {
            self.native += n.native_sits;
            self.values += n.on_native_values;
            self.fixed += n.fixed_shapes;
            for (i, v) in n.visits.iter().enumerate() {
                let name = || {
                    let s = &dm.situations[i];
                    let id = ir.store.args(s.template)[crate::mir::ID];
                    format!("{}/{}", dm.name.as_str(), show(&ir.store, dm, id))
                };
                match v {
                    Some(Visit::Template) => {
                        // Planned, but no visit runs the plan.
                        self.code -= 1;
                        self.template.push(name());
                    }
                    Some(Visit::HandsOver) => self.hands.push(name()),
                    Some(Visit::Partly) => self.partly.push(name()),
                    _ => {}
                }
            }
        }
        let none = Held::default();
        let held = native.map_or(&none, |n| &n.held);
        let reads_pipe = t.sits.iter().flatten().any(|s| s.reads_pipe);
        // The variables `mir::ty` counts: parameters, the pipe when read,
        // locals (globals are added once, never held natively).
        let mut vars: Vec<(String, bool)> = Vec::new();
        for (i, &p) in ir.store.args(dm.head).iter().enumerate() {
            let name = format!("parameter {}", show(&ir.store, dm, p));
            vars.push((name, held.params.get(i).copied().unwrap_or(false)));
        }
        if reads_pipe {
            vars.push(("the pipe".to_owned(), held.pipe));
        }
        for (i, (name, _)) in dm.locals.iter().enumerate() {
            let name = format!("local {}", name.as_str());
            vars.push((name, held.locals.get(i).copied().unwrap_or(false)));
        }
        let n = vars.iter().filter(|v| v.1).count();
        self.vars += vars.len();
        self.held += n;
        if vars.is_empty() {
            return None;
        }
        let names = |h: bool| {
            vars.iter()
                .filter(|v| v.1 == h)
                .map(|v| v.0.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        };
        let mut line = format!("  variables held as Rust values: {n}/{}", vars.len());
        if n > 0 {
            line.push_str(&format!(" ({})", names(true)));
        }
        if n < vars.len() {
            line.push_str(&format!("; as terms: {}", names(false)));
        }
        Some(line)
    }
}

/// The listing's last two lines: exactly `situations on native values:
/// N/Y`, then `situations compiled as code: X/Y; variables typed: A/B`.
/// Of the application's Y situations, X run as generated code (a MIR
/// plan: no template instantiated; a situation whose native visit runs
/// its template on every path, [`Visit::Template`], is not), N have
/// native code whose registers all have a Rust type (no term, no ground
/// handle) and whose code neither hands the native frames over nor runs
/// the template on any path but a failed conversion's or the history's
/// ([`Visit::Native`]: every path of the visit and of its exit arm, read
/// as generated, `native::visit`). Of its B variables
/// (every DM parameter, the pipe of each DM an in_arg reads, every local,
/// every global), A are held by the generated code as native Rust values
/// (`i64`, `f64`, `Atom`, `List`, `Val`) in every situation of their DM
/// ([`Held`]): a DM with a situation on terms, a parameter native code
/// does not read, a global count as not typed.
fn summary(t: &Totals) -> String {
    format!(
        "situations on native values: {}/{}\n\
         situations compiled as code: {}/{}; variables typed: {}/{}",
        t.values, t.sits, t.code, t.sits, t.held, t.vars
    )
}

/// A term of a DM as written, its variables by their names.
fn show(store: &Store, dm: &IrDm, t: sitlog_runtime::Term) -> String {
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
                let name = dm
                    .var_index_names
                    .iter()
                    .find(|(i, _)| *i == v)
                    .map_or_else(|| format!("_G{v}"), |(_, n)| n.clone());
                out.push_str(&name);
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
        "its DM's head names a variable twice, or a term is too deep"
    }
}
