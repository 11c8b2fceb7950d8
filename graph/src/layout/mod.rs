//! Where everything goes: each DM is laid out on its own by `layout-rs`
//! (a pure-Rust Sugiyama-style layered layout, like Graphviz `dot`), then
//! the DMs' ovals and the external nodes are laid out the same way as
//! boxes of the program's call graph, and the links between DMs are drawn
//! as curves between the placed nodes.
//!
//! `layout-rs` draws no nested clusters, so the two levels are ours. The
//! engine's edge-crossing reduction grows much faster than linearly with
//! the DM (its nodes plus the dummy nodes of long edges, see
//! [`engine_cost`]): past [`OPT_LIMIT`] it is skipped, and a DM past
//! [`PLAIN_LIMIT`], or one the engine cannot lay out, is placed by a simple
//! layered layout of ours instead. A note says so each time.
//!
//! This module is the whole-diagram step; its parts, each using only those
//! before it: `geometry` (the layout's types, label lines and node sizes),
//! `dm` (one DM in its own coordinates, the simple layered layout),
//! `engine` (everything that drives `layout-rs`).

mod dm;
mod engine;
mod geometry;

pub use dm::engine_cost;
pub use geometry::{
    label_lines, node_lines, node_size, path_data, return_dot_offsets, Cmd, Layout, Oval, Placed,
    Route, CHAR_W, LABEL_MAX, NODE_LABEL_MAX, P,
};

use crate::{Diagram, Edge, EdgeKind};
use dm::layered;
use engine::{engine_within, place_boxes};
use geometry::boundary;
use std::collections::HashMap;

/// Time the engine may take for a whole diagram; a DM not laid out by then
/// gets the simple layered layout.
pub const ENGINE_BUDGET: std::time::Duration = std::time::Duration::from_secs(4);

/// Up to this [`engine_cost`] the engine reduces edge crossings.
pub const OPT_LIMIT: usize = 250;
/// Up to this [`engine_cost`] the engine lays the DM out (without crossing
/// reduction past [`OPT_LIMIT`]); past it, the simple layered layout.
pub const PLAIN_LIMIT: usize = 500;

/// Lays out the whole diagram.
pub fn layout(d: &Diagram) -> Layout {
    let mut out = Layout::default();
    let started = std::time::Instant::now();
    let budget = ENGINE_BUDGET;
    // 1. Each DM on its own, in local coordinates.
    let mut locals = Vec::new();
    for dm in &d.dms {
        let cost = engine_cost(dm);
        let local = if cost > PLAIN_LIMIT {
            out.notes.push(format!(
                "DM {} has {} nodes and {} edges: too many to lay out in a few seconds; drawn with the simple layered layout",
                dm.name,
                dm.nodes.len(),
                dm.edges.len()
            ));
            layered(dm)
        } else {
            if cost > OPT_LIMIT {
                out.notes.push(format!(
                    "DM {} is large: edge crossings are not reduced",
                    dm.name
                ));
            }
            let left = budget.saturating_sub(started.elapsed());
            match engine_within(dm, cost <= OPT_LIMIT, left) {
                Ok(l) => l,
                Err(why) => {
                    out.notes.push(format!(
                        "DM {}: {why}; drawn with the simple layered layout",
                        dm.name
                    ));
                    layered(dm)
                }
            }
        };
        locals.push(local);
    }
    // 2. The ovals and externals, as boxes of the call graph.
    let mut boxes: Vec<(f64, f64)> = Vec::new();
    for l in &locals {
        let (w, h) = (l.max.x - l.min.x, l.max.y - l.min.y);
        let rx = w / 2.0 * std::f64::consts::SQRT_2 + 16.0;
        let ry = h / 2.0 * std::f64::consts::SQRT_2 + 26.0;
        boxes.push((2.0 * rx + 30.0, 2.0 * ry + 30.0));
    }
    for n in &d.externals {
        let (w, h) = node_size(n);
        boxes.push((w + 20.0, h + 20.0));
    }
    let owner = owners(d);
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for e in &d.links {
        if let (Some(&a), Some(&b)) = (owner.get(e.from.as_str()), owner.get(e.to.as_str())) {
            let pair = if e.kind == EdgeKind::Control {
                (b, a)
            } else {
                (a, b)
            };
            if pair.0 != pair.1 && !pairs.contains(&pair) {
                pairs.push(pair);
            }
        }
    }
    let centers = place_boxes(&boxes, &pairs);
    // 3. Absolute coordinates.
    let (mut minx, mut miny, mut maxx, mut maxy) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for (i, c) in centers.iter().enumerate() {
        let (w, h) = boxes[i];
        minx = minx.min(c.x - w / 2.0);
        miny = miny.min(c.y - h / 2.0);
        maxx = maxx.max(c.x + w / 2.0);
        maxy = maxy.max(c.y + h / 2.0);
    }
    if centers.is_empty() {
        (minx, miny, maxx, maxy) = (0.0, 0.0, 100.0, 60.0);
    }
    let margin = 20.0;
    let shift = P::new(margin - minx, margin - miny);
    out.width = (maxx - minx + 2.0 * margin).ceil();
    out.height = (maxy - miny + 2.0 * margin).ceil();
    for (i, (dm, l)) in d.dms.iter().zip(&locals).enumerate() {
        let c = centers[i].plus(shift);
        let local_center = l.min.plus(l.max).scale(0.5);
        let t = c.minus(local_center);
        let (w, h) = (l.max.x - l.min.x, l.max.y - l.min.y);
        out.ovals.push(Oval {
            center: c,
            rx: w / 2.0 * std::f64::consts::SQRT_2 + 16.0,
            ry: h / 2.0 * std::f64::consts::SQRT_2 + 26.0,
        });
        for (n, p) in dm.nodes.iter().zip(&l.nodes) {
            let placed = Placed {
                center: p.center.plus(t),
                w: p.w,
                h: p.h,
            };
            out.nodes.insert(n.id.clone(), placed);
        }
        for (id, at) in &l.dots {
            out.dots.insert(id.clone(), at.plus(t));
        }
        for (e, r) in dm.edges.iter().zip(&l.routes) {
            let mut r = r.clone();
            for c in r.path.iter_mut() {
                translate(c, t);
            }
            r.label_at = r.label_at.map(|p| p.plus(t));
            out.routes.insert(e.id.clone(), r);
        }
    }
    for (k, n) in d.externals.iter().enumerate() {
        let c = centers[d.dms.len() + k].plus(shift);
        let (w, h) = node_size(n);
        out.nodes.insert(n.id.clone(), Placed { center: c, w, h });
    }
    // 4. Links between DMs: curves between the placed nodes.
    for e in &d.links {
        if let Some(r) = link_route(&out, d, e) {
            out.routes.insert(e.id.clone(), r);
        }
    }
    out
}

fn translate(c: &mut Cmd, t: P) {
    match c {
        Cmd::M(a) | Cmd::L(a) => *a = a.plus(t),
        Cmd::C(a, b, p) => {
            *a = a.plus(t);
            *b = b.plus(t);
            *p = p.plus(t);
        }
        Cmd::S(a, p) => {
            *a = a.plus(t);
            *p = p.plus(t);
        }
    }
}

/// Node id → index of its box (DMs, then externals).
fn owners(d: &Diagram) -> HashMap<&str, usize> {
    let mut m = HashMap::new();
    for (i, dm) in d.dms.iter().enumerate() {
        m.insert(dm.id.as_str(), i);
        for n in &dm.nodes {
            m.insert(n.id.as_str(), i);
        }
    }
    for (k, n) in d.externals.iter().enumerate() {
        m.insert(n.id.as_str(), d.dms.len() + k);
    }
    m
}

/// A curve between two placed nodes (or into a return dot).
fn link_route(l: &Layout, d: &Diagram, e: &Edge) -> Option<Route> {
    let end = |id: &str| -> Option<Placed> {
        if let Some(n) = l.nodes.get(id) {
            return Some(n.clone());
        }
        let i = d.dms.iter().position(|g| g.id == id)?;
        let o = l.ovals.get(i)?;
        Some(Placed {
            center: o.center,
            w: 2.0 * o.rx,
            h: 2.0 * o.ry,
        })
    };
    let a = &end(&e.from)?;
    let b = &end(&e.to)?;
    let target_dot = e.to_port.as_ref().and_then(|d| l.dots.get(d)).copied();
    let s = boundary(a, target_dot.unwrap_or(b.center));
    let t = match target_dot {
        Some(dot) => dot,
        None => boundary(b, a.center),
    };
    let d = t.minus(s);
    // bend to the right of the direction of travel, so that a pipe and the
    // control link coming back do not overlap
    let normal = P::new(-d.y, d.x).scale(0.18);
    let c1 = s.plus(d.scale(0.3)).plus(normal);
    let c2 = s.plus(d.scale(0.7)).plus(normal);
    let mid = s.plus(d.scale(0.5)).plus(normal.scale(0.75));
    Some(Route {
        path: vec![Cmd::M(s), Cmd::C(c1, c2, t)],
        label_at: if e.label.is_empty() { None } else { Some(mid) },
        label_lines: label_lines(&e.label),
    })
}
