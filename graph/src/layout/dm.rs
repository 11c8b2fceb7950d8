//! One DM in its own coordinates: the record a DM's layout comes back as
//! ([`Local`]: placed nodes, routes, return dots, bounding box), our simple
//! layered layout (the fallback for DMs the engine cannot or should not
//! take), and [`engine_cost`], the measure that chooses between the two.

use super::geometry::{
    boundary, label_lines, node_size, return_dot_offsets, Cmd, Placed, Route, CHAR_W, P,
};
use crate::DmGraph;
use std::collections::HashMap;

/// A DM laid out in its own coordinates.
pub(super) struct Local {
    pub nodes: Vec<Placed>,
    pub routes: Vec<Route>,
    /// Return dot id → centre.
    pub dots: Vec<(String, P)>,
    pub min: P,
    pub max: P,
}

/// Where the return dots of each recursive situation go (local
/// coordinates): a dot with an arc sits just inside the rim where that arc
/// leaves, so the arc starts at its dot; the others along the bottom.
fn place_ports(dm: &DmGraph, nodes: &[Placed], routes: &[Route]) -> Vec<(String, P)> {
    let mut out = Vec::new();
    for (i, n) in dm.nodes.iter().enumerate() {
        if n.returns.is_empty() {
            continue;
        }
        let offsets = return_dot_offsets(n.returns.len(), nodes[i].w);
        for (k, dot) in n.returns.iter().enumerate() {
            let start = dm
                .edges
                .iter()
                .zip(routes)
                .find(|(e, _)| e.from == n.id && e.from_port.as_ref() == Some(&dot.id))
                .and_then(|(_, r)| match r.path.first() {
                    Some(Cmd::M(a)) => Some(*a),
                    _ => None,
                });
            let at = match start {
                Some(a) => {
                    let c = nodes[i].center;
                    let d = a.minus(c);
                    let len = d.len().max(1e-9);
                    c.plus(d.scale((len - 7.0).max(0.0) / len))
                }
                None => nodes[i].center.plus(offsets[k]),
            };
            out.push((dot.id.clone(), at));
        }
    }
    out
}

pub(super) fn bounded(dm: &DmGraph, nodes: Vec<Placed>, routes: Vec<Route>) -> Local {
    let dots = place_ports(dm, &nodes, &routes);
    let (mut min, mut max) = (P::new(f64::MAX, f64::MAX), P::new(f64::MIN, f64::MIN));
    let mut grow = |q: P| {
        min = P::new(min.x.min(q.x), min.y.min(q.y));
        max = P::new(max.x.max(q.x), max.y.max(q.y));
    };
    for n in &nodes {
        grow(P::new(n.center.x - n.w / 2.0, n.center.y - n.h / 2.0));
        // function dots carry their label to the right
        grow(P::new(n.center.x + n.w / 2.0, n.center.y + n.h / 2.0));
    }
    for r in &routes {
        for c in &r.path {
            match c {
                Cmd::M(a) | Cmd::L(a) => grow(*a),
                Cmd::C(a, b, q) => {
                    grow(*a);
                    grow(*b);
                    grow(*q)
                }
                Cmd::S(a, q) => {
                    grow(*a);
                    grow(*q)
                }
            }
        }
        if let Some(at) = r.label_at {
            let w = r
                .label_lines
                .iter()
                .map(|l| l.chars().count())
                .max()
                .unwrap_or(0) as f64
                * CHAR_W;
            let h = r.label_lines.len() as f64 * 13.0;
            grow(P::new(at.x - w / 2.0, at.y - h / 2.0));
            grow(P::new(at.x + w / 2.0, at.y + h / 2.0));
        }
    }
    if nodes.is_empty() {
        min = P::new(0.0, 0.0);
        max = P::new(60.0, 40.0);
    }
    Local {
        nodes,
        routes,
        dots,
        min,
        max,
    }
}

/// Ranks by breadth-first search from the first node (then from each node
/// not reached yet).
fn ranks(dm: &DmGraph) -> (Vec<usize>, HashMap<&str, usize>, Vec<Vec<usize>>) {
    let n = dm.nodes.len();
    let index: HashMap<&str, usize> = dm
        .nodes
        .iter()
        .enumerate()
        .map(|(i, n)| (n.id.as_str(), i))
        .collect();
    let mut succ: Vec<Vec<usize>> = vec![Vec::new(); n];
    for e in &dm.edges {
        if let (Some(&a), Some(&b)) = (index.get(e.from.as_str()), index.get(e.to.as_str())) {
            succ[a].push(b);
        }
    }
    let mut rank = vec![usize::MAX; n];
    let mut next_root = 0;
    let mut queue = std::collections::VecDeque::new();
    let mut base = 0;
    while next_root < n {
        if rank[next_root] != usize::MAX {
            next_root += 1;
            continue;
        }
        rank[next_root] = base;
        queue.push_back(next_root);
        while let Some(a) = queue.pop_front() {
            for &b in &succ[a] {
                if rank[b] == usize::MAX {
                    rank[b] = rank[a] + 1;
                    base = base.max(rank[b] + 1);
                    queue.push_back(b);
                }
            }
        }
        base = base.max(rank[next_root] + 1);
    }
    (rank, index, succ)
}

/// How much work the engine has with a DM: its nodes plus the dummy
/// nodes long edges need (the sum of the edges' rank spans, with the
/// label connector each edge gets). The engine's crossing reduction grows
/// much faster than linearly in it.
pub fn engine_cost(dm: &DmGraph) -> usize {
    let (rank, _, succ) = ranks(dm);
    let mut cost = dm.nodes.len();
    for (a, bs) in succ.iter().enumerate() {
        for &b in bs {
            cost += 2 * rank[a].abs_diff(rank[b]).max(1);
        }
    }
    cost
}

/// The simple layered layout: ranks by breadth-first search from the
/// first node, rows left to right, straight edges.
pub(super) fn layered(dm: &DmGraph) -> Local {
    let n = dm.nodes.len();
    let (rank, index, _) = ranks(dm);
    // Rows, wrapped at a fixed width so that wide ranks stay readable.
    let max_row_w = 2400.0;
    let mut nodes = vec![
        Placed {
            center: P::new(0.0, 0.0),
            w: 0.0,
            h: 0.0
        };
        n
    ];
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&i| (rank[i], i));
    let (mut x, mut y, mut row_h) = (0.0f64, 0.0f64, 0.0f64);
    let mut cur_rank = None;
    for i in order {
        let (w, h) = node_size(&dm.nodes[i]);
        if (cur_rank.is_some() && cur_rank != Some(rank[i])) || x + w > max_row_w {
            y += row_h + 90.0;
            x = 0.0;
            row_h = 0.0;
        }
        cur_rank = Some(rank[i]);
        nodes[i] = Placed {
            center: P::new(x + w / 2.0, y + h / 2.0),
            w,
            h,
        };
        x += w + 60.0;
        row_h = row_h.max(h);
    }
    let mut routes = Vec::new();
    for e in &dm.edges {
        let mut r = Route {
            label_lines: label_lines(&e.label),
            ..Route::default()
        };
        if let (Some(&a), Some(&b)) = (index.get(e.from.as_str()), index.get(e.to.as_str())) {
            let (pa, pb) = (&nodes[a], &nodes[b]);
            if a == b {
                let c = pa.center;
                let s = c.plus(P::new(pa.w / 2.0, -8.0));
                let t = c.plus(P::new(pa.w / 2.0, 8.0));
                r.path = vec![
                    Cmd::M(s),
                    Cmd::C(s.plus(P::new(40.0, -30.0)), t.plus(P::new(40.0, 30.0)), t),
                ];
                r.label_at = Some(c.plus(P::new(pa.w / 2.0 + 40.0, 0.0)));
            } else {
                let s = boundary(pa, pb.center);
                let t = boundary(pb, pa.center);
                r.path = vec![Cmd::M(s), Cmd::L(t)];
                r.label_at = Some(s.plus(t).scale(0.5));
            }
        }
        routes.push(r);
    }
    bounded(dm, nodes, routes)
}
