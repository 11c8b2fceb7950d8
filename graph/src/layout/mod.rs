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
//! Invariant: the layout is a function of the diagram, never of the
//! machine's speed. What the engine may take is a *work* budget, counted by
//! [`engine_work`] before it runs (the engine's lowering done on a copy, its
//! passes counted on the ranks it gets), not a clock: a DM whose crossing
//! reduction would count more than [`DM_WORK_LIMIT`] is laid out without
//! it, one whose layout would still count more, or more than is left of
//! [`ENGINE_WORK_BUDGET`] for the whole diagram, gets the simple layered
//! layout. The one clock left is [`ENGINE_HANG_GUARD`], against a bug of the
//! engine (a loop that does not end): the work limits keep every DM it is
//! given far below it.
//!
//! This module is the whole-diagram step; its parts, each using only those
//! before it: `geometry` (the layout's types, label lines and node sizes),
//! `dm` (one DM in its own coordinates, the simple layered layout),
//! `engine` (everything that drives `layout-rs`), `route` (links routed
//! round the nodes in their way).

mod dm;
mod engine;
mod geometry;
mod route;

pub use dm::engine_cost;
pub use engine::engine_work;
pub use geometry::{
    function_lines, label_lines, node_lines, node_size, node_text, path_data, return_dot_offsets,
    Cmd, Layout, Oval, Placed, Route, CHAR_W, LABEL_MAX, LINE_H, NODE_LABEL_MAX, P,
};

use crate::{Diagram, Edge, EdgeKind};
use dm::layered;
use engine::{engine_within, place_boxes};
use geometry::boundary;
use std::collections::HashMap;

/// The [`engine_work`] the engine may do for a whole diagram; a DM for
/// which not enough is left gets the simple layered layout. About 1–2.5 s
/// of a debug build on a 2-core machine; the home butler's 28 DMs count
/// about 3 million.
pub const ENGINE_WORK_BUDGET: u64 = 100_000_000;

/// The [`engine_work`] the engine may do for one DM: past it, first the
/// crossing reduction is left out, then the engine. The largest DM of the
/// home butler counts 0.45 million; a synthetic DM of 20 situations with
/// an arc to a random one each, 14 million with crossing reduction (0.16 s
/// of a debug build); of 30, 72 million (1.1 s), 2.7 million without.
pub const DM_WORK_LIMIT: u64 = 20_000_000;

/// How long one run of the engine may take before it is given up as hung
/// (a bug of the engine, not a large DM: the work limits decide those).
/// The engine runs on a thread of its own, left to finish on its own.
pub const ENGINE_HANG_GUARD: std::time::Duration = std::time::Duration::from_secs(60);

/// Up to this [`engine_cost`] the engine reduces edge crossings.
pub const OPT_LIMIT: usize = 250;
/// Up to this [`engine_cost`] the engine lays the DM out (without crossing
/// reduction past [`OPT_LIMIT`]); past it, the simple layered layout.
pub const PLAIN_LIMIT: usize = 500;

/// For each external node, the DM it belongs with: the one whose nodes
/// all its links join (a DM called from one drawn DM, on a page of one
/// DM); it is laid out with that DM, so its links are routed as arcs.
fn attached(d: &Diagram) -> Vec<Option<usize>> {
    let mut node_dm: HashMap<&str, usize> = HashMap::new();
    for (i, dm) in d.dms.iter().enumerate() {
        for n in &dm.nodes {
            node_dm.insert(n.id.as_str(), i);
        }
    }
    d.externals
        .iter()
        .map(|x| {
            let mut dm = None;
            for e in &d.links {
                let other = if e.to == x.id {
                    &e.from
                } else if e.from == x.id {
                    &e.to
                } else {
                    continue;
                };
                match (node_dm.get(other.as_str()), dm) {
                    (Some(&i), None) => dm = Some(i),
                    (Some(&i), Some(j)) if i == j => {}
                    _ => return None,
                }
            }
            dm
        })
        .collect()
}

/// The overview (boxes and links, no DM drawn): laid out as one graph by
/// the engine, ranks left to right (call graphs are wide).
fn overview(d: &Diagram) -> Layout {
    let mut out = Layout::default();
    let g = crate::DmGraph {
        id: String::new(),
        name: d.title.clone(),
        location: String::new(),
        nodes: d.externals.clone(),
        edges: d.links.clone(),
    };
    let cost = engine_cost(&g);
    let local = if cost > PLAIN_LIMIT {
        out.notes.push(format!(
            "the overview has {} DMs and {} calls: drawn with the simple layered layout",
            g.nodes.len(),
            g.edges.len()
        ));
        layered(&g)
    } else {
        let mut left = ENGINE_WORK_BUDGET;
        match within_work(
            &g,
            cost <= OPT_LIMIT,
            true,
            "the overview",
            &mut left,
            &mut out.notes,
        ) {
            Ok(l) => l,
            Err(why) => {
                out.notes.push(format!(
                    "the overview: {why}; drawn with the simple layered layout"
                ));
                layered(&g)
            }
        }
    };
    let margin = 20.0;
    let t = P::new(margin - local.min.x, margin - local.min.y);
    out.width = (local.max.x - local.min.x + 2.0 * margin).ceil();
    out.height = (local.max.y - local.min.y + 2.0 * margin).ceil();
    for (n, p) in g.nodes.iter().zip(&local.nodes) {
        let placed = Placed {
            center: p.center.plus(t),
            w: p.w,
            h: p.h,
        };
        out.nodes.insert(n.id.clone(), placed);
    }
    for (e, r) in g.edges.iter().zip(&local.routes) {
        let mut r = r.clone();
        for c in r.path.iter_mut() {
            translate(c, t);
        }
        r.label_at = r.label_at.map(|p| p.plus(t));
        out.routes.insert(e.id.clone(), r);
    }
    out
}

/// Lays out the whole diagram.
pub fn layout(d: &Diagram) -> Layout {
    if d.dms.is_empty() && d.externals.iter().any(|n| n.kind == crate::NodeKind::Dm) {
        return overview(d);
    }
    let mut out = Layout::default();
    let mut left = ENGINE_WORK_BUDGET;
    let attached = attached(d);
    // 1. Each DM on its own, in local coordinates, with the external
    // nodes that belong with it and their links.
    let mut locals = Vec::new();
    let mut extra_links: Vec<Vec<&Edge>> = Vec::new();
    for (di, plain) in d.dms.iter().enumerate() {
        let mut dm = std::borrow::Cow::Borrowed(plain);
        let mine: Vec<&crate::Node> = d
            .externals
            .iter()
            .zip(&attached)
            .filter(|(_, a)| **a == Some(di))
            .map(|(n, _)| n)
            .collect();
        let links: Vec<&Edge> = d
            .links
            .iter()
            .filter(|e| mine.iter().any(|n| n.id == e.to || n.id == e.from))
            .collect();
        if !mine.is_empty() {
            let g = dm.to_mut();
            g.nodes.extend(mine.iter().map(|n| (*n).clone()));
            g.edges.extend(links.iter().map(|e| (*e).clone()));
        }
        extra_links.push(links);
        let dm = &*dm;
        let cost = engine_cost(dm);
        let local = if cost > PLAIN_LIMIT {
            out.notes.push(format!(
                "DM {} has {} nodes and {} edges: too many to lay out in a few seconds; drawn with the simple layered layout",
                dm.name,
                plain.nodes.len(),
                plain.edges.len()
            ));
            layered(dm)
        } else {
            if cost > OPT_LIMIT {
                out.notes.push(format!(
                    "DM {} is large: edge crossings are not reduced",
                    dm.name
                ));
            }
            let what = format!("DM {}", dm.name);
            match within_work(
                dm,
                cost <= OPT_LIMIT,
                false,
                &what,
                &mut left,
                &mut out.notes,
            ) {
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
    // 2. The ovals and the other externals, as boxes of the call graph.
    let mut boxes: Vec<(f64, f64)> = Vec::new();
    for l in &locals {
        let (w, h) = (l.max.x - l.min.x, l.max.y - l.min.y);
        let rx = w / 2.0 * std::f64::consts::SQRT_2 + 16.0;
        let ry = h / 2.0 * std::f64::consts::SQRT_2 + 26.0;
        boxes.push((2.0 * rx + 30.0, 2.0 * ry + 30.0));
    }
    let mut box_of_external = Vec::new();
    for (n, a) in d.externals.iter().zip(&attached) {
        match a {
            Some(di) => box_of_external.push(*di),
            None => {
                let (w, h) = node_size(n);
                box_of_external.push(boxes.len());
                boxes.push((w + 20.0, h + 20.0));
            }
        }
    }
    let owner = owners(d, &box_of_external);
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
    let mut routed: Vec<&str> = Vec::new();
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
        let ext_nodes = d
            .externals
            .iter()
            .zip(&attached)
            .filter(|(_, a)| **a == Some(i))
            .map(|(n, _)| n);
        for (n, p) in dm.nodes.iter().chain(ext_nodes).zip(&l.nodes) {
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
        let edges = dm.edges.iter().chain(extra_links[i].iter().copied());
        for (e, r) in edges.zip(&l.routes) {
            let mut r = r.clone();
            for c in r.path.iter_mut() {
                translate(c, t);
            }
            r.label_at = r.label_at.map(|p| p.plus(t));
            out.routes.insert(e.id.clone(), r);
        }
        routed.extend(extra_links[i].iter().map(|e| e.id.as_str()));
    }
    for (k, n) in d.externals.iter().enumerate() {
        if attached[k].is_some() {
            continue;
        }
        let c = centers[box_of_external[k]].plus(shift);
        let (w, h) = node_size(n);
        out.nodes.insert(n.id.clone(), Placed { center: c, w, h });
    }
    // 4. Links between DMs: curves between the placed nodes, routed round
    // the nodes in their way.
    let mut ids: Vec<&String> = out.nodes.keys().collect();
    ids.sort();
    let placed: Vec<(&str, route::Obstacle)> = ids
        .into_iter()
        .map(|id| (id.as_str(), route::Obstacle::of(&out.nodes[id])))
        .collect();
    for e in &d.links {
        if routed.contains(&e.id.as_str()) {
            continue;
        }
        if let Some(mut r) = link_route(&out, d, e) {
            let others: Vec<route::Obstacle> = placed
                .iter()
                .filter(|(id, _)| *id != e.from && *id != e.to)
                .map(|(_, o)| *o)
                .collect();
            if let Some((path, mid)) = route::around(&r.path, &others) {
                r.path = path;
                if r.label_at.is_some() {
                    r.label_at = Some(mid);
                }
            }
            out.routes.insert(e.id.clone(), r);
        }
    }
    out
}

/// The engine on `dm` (`what` in notes) if its [`engine_work`] fits: with crossing reduction
/// (`optimize`) if that fits [`DM_WORK_LIMIT`] (else a note, and without),
/// then if the layout fits both the limit and what is `left` of the
/// diagram's budget, which it takes from. `Err`: why not, for a note.
fn within_work(
    dm: &crate::DmGraph,
    optimize: bool,
    across: bool,
    what: &str,
    left: &mut u64,
    notes: &mut Vec<String>,
) -> Result<dm::Local, String> {
    let unplaced = || "the layout engine could not place it".to_owned();
    let mut optimize = optimize;
    let mut work = engine_work(dm, optimize, across).ok_or_else(unplaced)?;
    if optimize && work > DM_WORK_LIMIT {
        optimize = false;
        work = engine_work(dm, false, across).ok_or_else(unplaced)?;
        notes.push(format!(
            "{what}: edge crossings are not reduced (too much work for the layout engine)"
        ));
    }
    if work > DM_WORK_LIMIT {
        return Err(format!(
            "too much work for the layout engine ({work} steps, limit {DM_WORK_LIMIT})"
        ));
    }
    if work > *left {
        return Err(format!(
            "the diagram's layout work is spent ({work} steps needed, {} left of {ENGINE_WORK_BUDGET})",
            *left
        ));
    }
    *left -= work;
    engine_within(dm, optimize, across, ENGINE_HANG_GUARD)
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

/// Node id → index of its box (DMs, then the externals not laid out
/// with a DM: `box_of_external`).
fn owners<'d>(d: &'d Diagram, box_of_external: &[usize]) -> HashMap<&'d str, usize> {
    let mut m = HashMap::new();
    for (i, dm) in d.dms.iter().enumerate() {
        m.insert(dm.id.as_str(), i);
        for n in &dm.nodes {
            m.insert(n.id.as_str(), i);
        }
    }
    for (k, n) in d.externals.iter().enumerate() {
        m.insert(n.id.as_str(), box_of_external[k]);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{DmGraph, Node, NodeKind};

    fn chain(n: usize) -> DmGraph {
        let node = |i: usize| Node {
            id: format!("s{i}"),
            kind: NodeKind::Situation,
            label: format!("s{i}"),
            situation_type: None,
            situation_kind: None,
            initial: i == 0,
            functor: None,
            embedded_dm: None,
            returns: Vec::new(),
            detail: None,
            link: None,
            location: String::new(),
        };
        let edge = |i: usize| Edge {
            id: format!("e{i}"),
            kind: EdgeKind::Arc,
            from: format!("s{i}"),
            from_port: None,
            to: format!("s{}", i + 1),
            to_port: None,
            label: "a : empty".into(),
            expectation: None,
            location: String::new(),
        };
        DmGraph {
            id: "d".into(),
            name: "d".into(),
            location: String::new(),
            nodes: (0..n).map(node).collect(),
            edges: (0..n.saturating_sub(1)).map(edge).collect(),
        }
    }

    /// The diagram's budget is taken DM by DM: what needs more than is
    /// left is refused, with the counts, and takes nothing.
    #[test]
    fn the_work_budget_is_counted_down() {
        let dm = chain(4);
        // 4 nodes, 3 label connectors, in 7 ranks
        let work = engine_work(&dm, false, false).unwrap();
        assert_eq!(work, 4 * 7 * 7);
        assert_eq!(engine_work(&dm, true, false), Some(work + 6 * 400));
        let mut notes = Vec::new();
        let mut left = work;
        assert!(within_work(&dm, false, false, "DM d", &mut left, &mut notes).is_ok());
        assert_eq!(left, 0);
        let mut left = work - 1;
        let why = within_work(&dm, false, false, "DM d", &mut left, &mut notes)
            .err()
            .unwrap();
        assert_eq!(left, work - 1);
        assert_eq!(
            why,
            format!(
                "the diagram's layout work is spent ({work} steps needed, {} left of {ENGINE_WORK_BUDGET})",
                work - 1
            )
        );
        assert!(notes.is_empty());
    }
}
