//! The program's overview: one box per DM, the DMs each calls and the
//! recovery DMs of its situation types (`sitlogc graph --overview`).

use super::{fields, is_none, recovery_of, Named, Options};
use crate::ir::Ir;
use sitlog_graph::{Diagram, Edge, EdgeKind, Node, NodeKind};
use sitlog_runtime::machine::Kind;
use sitlog_syntax::Atom;

/// The program's overview: one box per DM (`d0`, `d1`, ... in program
/// order, the main DM's border bold, its situations and file as detail),
/// an edge from each DM to each DM it calls (labelled `×N` for N
/// calls) and to the recovery DM of each situation type it
/// has one for. A DM calling itself says so in its detail.
pub fn overview(ir: &Ir, options: &Options) -> Diagram {
    let store = &ir.store;
    let main_name = options.main.as_deref().unwrap_or("main");
    let main_ix = ir
        .dms
        .iter()
        .position(|d| d.name.as_str() == main_name)
        .or(if ir.dms.is_empty() { None } else { Some(0) });
    let mut d = Diagram {
        title: options.title.clone(),
        ..Diagram::default()
    };
    let mut calls: Vec<(usize, usize, usize)> = Vec::new(); // caller, callee, count
    let mut recoveries: Vec<(usize, Atom, usize, String)> = Vec::new();
    for (di, dm) in ir.dms.iter().enumerate() {
        let mut itself = false;
        for s in &dm.situations {
            let f = fields(store, s.template);
            if s.kind == Kind::Recursive && !is_none(store, f.emb) {
                if let Some(ci) = store
                    .functor(f.emb)
                    .and_then(|(name, _)| ir.dm_by_name(name))
                {
                    let ci = ci as usize;
                    if ci == di {
                        itself = true;
                    } else if let Some(c) = calls.iter_mut().find(|c| (c.0, c.1) == (di, ci)) {
                        c.2 += 1;
                    } else {
                        calls.push((di, ci, 1));
                    }
                }
            }
            if let Some((ty, ri)) = recovery_of(ir, f.ty) {
                if ri != di && !recoveries.iter().any(|r| (r.0, r.1) == (di, ty)) {
                    recoveries.push((di, ty, ri, s.location.clone()));
                }
            }
        }
        let file = dm
            .location
            .rsplitn(3, ':')
            .nth(2)
            .map(|f| f.rsplit('/').next().unwrap_or(f))
            .unwrap_or("");
        let n = dm.situations.len();
        let mut detail = format!("{n} situation{}, {file}", if n == 1 { "" } else { "s" });
        if itself {
            detail.push_str(", calls itself");
        }
        d.externals.push(Node {
            id: format!("d{di}"),
            kind: NodeKind::Dm,
            label: Named::new(store, dm).text(dm.head),
            situation_type: None,
            situation_kind: None,
            initial: Some(di) == main_ix,
            functor: Some(format!("{}/{}", dm.name, dm.arity)),
            embedded_dm: None,
            returns: Vec::new(),
            detail: Some(detail),
            link: None,
            location: dm.location.clone(),
        });
    }
    for (a, b, count) in calls {
        d.links.push(Edge {
            id: format!("e:d{a}.calls.d{b}"),
            kind: EdgeKind::Call,
            from: format!("d{a}"),
            from_port: None,
            to: format!("d{b}"),
            to_port: None,
            label: if count > 1 {
                format!("×{count}")
            } else {
                String::new()
            },
            expectation: None,
            location: ir.dms[a].location.clone(),
        });
    }
    for (a, ty, r, location) in recoveries {
        d.links.push(Edge {
            id: format!("e:d{a}.recovery.{ty}"),
            kind: EdgeKind::Recovery,
            from: format!("d{a}"),
            from_port: None,
            to: format!("d{r}"),
            to_port: None,
            label: format!("recovery\n({ty})"),
            expectation: None,
            location,
        });
    }
    d
}
