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

use crate::{shorten, Diagram, DmGraph, Edge, NodeKind};
use layout::core::base::Orientation;
use layout::core::color::Color;
use layout::core::format::{ClipHandle, RenderBackend};
use layout::core::geometry::Point;
use layout::core::style::StyleAttr;
use layout::std_shapes::shapes::{Arrow, Element, LineEndKind, ShapeKind};
use layout::topo::layout::VisualGraph;
use std::collections::HashMap;

/// Time the engine may take for a whole diagram; a DM not laid out by then
/// gets the simple layered layout.
pub const ENGINE_BUDGET: std::time::Duration = std::time::Duration::from_secs(4);

/// Up to this [`engine_cost`] the engine reduces edge crossings.
pub const OPT_LIMIT: usize = 250;
/// Up to this [`engine_cost`] the engine lays the DM out (without crossing
/// reduction past [`OPT_LIMIT`]); past it, the simple layered layout.
pub const PLAIN_LIMIT: usize = 500;

/// Width of one character of label text, in the monospace font the SVG uses.
pub const CHAR_W: f64 = 7.0;
/// Longest edge label line, in characters.
pub const LABEL_MAX: usize = 40;
/// Longest situation label line, in characters.
pub const NODE_LABEL_MAX: usize = 26;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct P {
    pub x: f64,
    pub y: f64,
}

impl P {
    pub fn new(x: f64, y: f64) -> P {
        P { x, y }
    }
    pub fn plus(self, o: P) -> P {
        P::new(self.x + o.x, self.y + o.y)
    }
    pub fn minus(self, o: P) -> P {
        P::new(self.x - o.x, self.y - o.y)
    }
    pub fn scale(self, k: f64) -> P {
        P::new(self.x * k, self.y * k)
    }
    pub fn len(self) -> f64 {
        (self.x * self.x + self.y * self.y).sqrt()
    }
}

/// A placed node: centre and size.
#[derive(Clone, Debug)]
pub struct Placed {
    pub center: P,
    pub w: f64,
    pub h: f64,
}

/// A DM's oval.
#[derive(Clone, Debug)]
pub struct Oval {
    pub center: P,
    pub rx: f64,
    pub ry: f64,
}

/// One drawing command of a path.
#[derive(Clone, Debug)]
pub enum Cmd {
    M(P),
    L(P),
    C(P, P, P),
    S(P, P),
}

/// An edge's route and where its label goes.
#[derive(Clone, Debug, Default)]
pub struct Route {
    pub path: Vec<Cmd>,
    /// Centre of the label.
    pub label_at: Option<P>,
    /// The label's lines as drawn (shortened).
    pub label_lines: Vec<String>,
}

/// The layout of a whole diagram.
#[derive(Clone, Debug, Default)]
pub struct Layout {
    pub width: f64,
    pub height: f64,
    /// One per DM, in order.
    pub ovals: Vec<Oval>,
    /// Node id → placement.
    pub nodes: HashMap<String, Placed>,
    /// Return dot id → centre.
    pub dots: HashMap<String, P>,
    /// Edge id → route.
    pub routes: HashMap<String, Route>,
    /// What the layout had to simplify (shown by the CLI).
    pub notes: Vec<String>,
}

/// Lines of an edge label as drawn: `α : β` on one line when short,
/// else `α :` and `β` on two.
pub fn label_lines(label: &str) -> Vec<String> {
    if label.is_empty() {
        return Vec::new();
    }
    if label.chars().count() <= LABEL_MAX {
        return vec![label.to_owned()];
    }
    if let Some(i) = label.find(" : ") {
        let (a, b) = (&label[..i + 2], &label[i + 3..]);
        return vec![shorten(a, LABEL_MAX), shorten(b, LABEL_MAX)];
    }
    vec![shorten(label, LABEL_MAX)]
}

/// The lines written inside a node.
pub fn node_lines(n: &crate::Node) -> Vec<String> {
    match n.kind {
        NodeKind::Situation => {
            let mut v = vec![shorten(&n.label, NODE_LABEL_MAX)];
            if let Some(t) = &n.situation_type {
                v.push(shorten(t, NODE_LABEL_MAX));
            }
            v
        }
        NodeKind::ExternalDm | NodeKind::OutArg => vec![shorten(&n.label, LABEL_MAX)],
        NodeKind::Disjunction => vec!["∨".to_owned()],
        NodeKind::Computed => vec!["?".to_owned()],
        NodeKind::Function => Vec::new(),
    }
}

/// Size of a node's shape.
pub fn node_size(n: &crate::Node) -> (f64, f64) {
    let chars = node_lines(n)
        .iter()
        .map(|l| l.chars().count())
        .max()
        .unwrap_or(0) as f64;
    match n.kind {
        NodeKind::Situation => {
            let mut d = (chars * CHAR_W + 24.0).max(58.0);
            if !n.returns.is_empty() {
                d = d.max(18.0 * n.returns.len() as f64 + 40.0).max(74.0);
            }
            (d, d)
        }
        NodeKind::Function => (20.0, 20.0),
        NodeKind::Disjunction => (24.0, 24.0),
        NodeKind::Computed => (26.0, 26.0),
        NodeKind::ExternalDm | NodeKind::OutArg => (chars * CHAR_W + 20.0, 30.0),
    }
}

/// Where the return dots of a recursive situation go, relative to its centre.
pub fn return_dot_offsets(n: usize, diameter: f64) -> Vec<P> {
    let r = diameter / 2.0;
    let span = (n as f64 - 1.0) * 18.0;
    (0..n)
        .map(|k| P::new(-span / 2.0 + 18.0 * k as f64, r * 0.5))
        .collect()
}

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
            let pair = if e.kind == crate::EdgeKind::Control {
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

/// A DM laid out in its own coordinates.
struct Local {
    nodes: Vec<Placed>,
    routes: Vec<Route>,
    /// Return dot id → centre.
    dots: Vec<(String, P)>,
    min: P,
    max: P,
}

/// [`engine`] on a thread of its own, given up after `time` (the thread is
/// left to finish on its own) or when the engine fails.
fn engine_within(dm: &DmGraph, optimize: bool, time: std::time::Duration) -> Result<Local, String> {
    if time.is_zero() {
        return Err("out of layout time".to_owned());
    }
    let (tx, rx) = std::sync::mpsc::channel();
    let owned = dm.clone();
    let spawned = std::thread::Builder::new()
        .name("sitlog-graph-layout".to_owned())
        .spawn(move || {
            let r = std::panic::catch_unwind(|| engine(&owned, optimize));
            let _ = tx.send(r.ok().flatten());
        });
    if spawned.is_err() {
        return Err("no thread for the layout engine".to_owned());
    }
    match rx.recv_timeout(time) {
        Ok(Some(l)) => Ok(l),
        Ok(None) => Err("the layout engine could not place it".to_owned()),
        Err(_) => Err("the layout engine took too long".to_owned()),
    }
}

/// Records the arrows `layout-rs` draws (their properties are our edge indices).
#[derive(Default)]
struct Capture {
    arrows: Vec<Captured>,
}

/// Edge index, path, whether the engine turned the edge around.
type Captured = (usize, Vec<(Point, Point)>, bool);

impl RenderBackend for Capture {
    fn draw_rect(
        &mut self,
        _: Point,
        _: Point,
        _: &StyleAttr,
        _: Option<String>,
        _: Option<ClipHandle>,
    ) {
    }
    fn draw_line(&mut self, _: Point, _: Point, _: &StyleAttr, _: Option<String>) {}
    fn draw_circle(&mut self, _: Point, _: Point, _: &StyleAttr, _: Option<String>) {}
    fn draw_text(&mut self, _: Point, _: &str, _: &StyleAttr) {}
    fn draw_arrow(
        &mut self,
        path: &[(Point, Point)],
        _: bool,
        head: (bool, bool),
        _: &StyleAttr,
        properties: Option<String>,
        _: &str,
    ) {
        if let Some(i) = properties.and_then(|p| p.parse().ok()) {
            self.arrows.push((i, path.to_vec(), head.0 && !head.1));
        }
    }
    fn create_clip(&mut self, _: Point, _: Point, _: usize) -> ClipHandle {
        0
    }
}

fn p(pt: Point) -> P {
    P::new(pt.x, pt.y)
}

/// `layout-rs` on one DM; `None` when its output cannot be read back.
fn engine(dm: &DmGraph, optimize: bool) -> Option<Local> {
    let mut vg = VisualGraph::new(Orientation::TopToBottom);
    let look = StyleAttr::new(Color::new(0), 1, None, 0, 7);
    let mut handles = Vec::new();
    let mut index: HashMap<&str, usize> = HashMap::new();
    for (i, n) in dm.nodes.iter().enumerate() {
        let (w, h) = node_size(n);
        let el = Element::create(
            ShapeKind::Circle(String::new()),
            look.clone(),
            Orientation::TopToBottom,
            Point::new(w, h),
        );
        handles.push(vg.add_node(el));
        index.insert(n.id.as_str(), i);
    }
    let first = handles.len();
    for (i, e) in dm.edges.iter().enumerate() {
        let (Some(&a), Some(&b)) = (index.get(e.from.as_str()), index.get(e.to.as_str())) else {
            continue;
        };
        let text = label_lines(&e.label).join("\n");
        let mut arrow = Arrow::simple(&text);
        arrow.look = look.clone();
        arrow.properties = Some(i.to_string());
        arrow.end = LineEndKind::Arrow;
        vg.add_edge(arrow, handles[a], handles[b]);
    }
    let mut cap = Capture::default();
    vg.do_it(false, !optimize, false, &mut cap);
    let mut nodes = Vec::new();
    for (i, h) in handles.iter().enumerate() {
        let pos = vg.pos(*h);
        let (w, hh) = node_size(&dm.nodes[i]);
        nodes.push(Placed {
            center: p(pos.center()),
            w,
            h: hh,
        });
    }
    // Label connectors, in creation order.
    let mut connectors = Vec::new();
    for h in vg.iter_nodes() {
        if h.get_index() < first {
            continue;
        }
        if let ShapeKind::Connector(Some(t)) = &vg.element(h).shape {
            connectors.push((t.clone(), p(vg.pos(h).center())));
        }
    }
    let mut routes = vec![Route::default(); dm.edges.len()];
    for (i, path, reversed) in cap.arrows {
        if path.len() < 2 || i >= routes.len() {
            return None;
        }
        // As explicit cubic segments: start, then (c1, c2, end) each.
        let start = p(path[0].0);
        let mut segs = vec![(p(path[0].1), p(path[1].0), p(path[1].1))];
        for q in &path[2..] {
            let (_, c2, end) = *segs.last().unwrap_or(&(start, start, start));
            // `S` reflects the previous second control point
            let c1 = end.plus(end.minus(c2));
            segs.push((c1, p(q.0), p(q.1)));
        }
        let mut cmds = Vec::new();
        if reversed {
            let last = segs.last().map_or(start, |s| s.2);
            cmds.push(Cmd::M(last));
            for (k, &(c1, c2, _)) in segs.iter().enumerate().rev() {
                let to = if k == 0 { start } else { segs[k - 1].2 };
                cmds.push(Cmd::C(c2, c1, to));
            }
        } else {
            cmds.push(Cmd::M(start));
            cmds.extend(segs.iter().map(|&(a, b, c)| Cmd::C(a, b, c)));
        }
        routes[i].path = cmds;
    }
    // Each label sits on a connector the edge's curve passes through: the
    // nearest one with the same text.
    let mut used = vec![false; connectors.len()];
    for (i, e) in dm.edges.iter().enumerate() {
        routes[i].label_lines = label_lines(&e.label);
        if routes[i].path.is_empty() {
            return None;
        }
        let text = routes[i].label_lines.join("\n");
        if text.is_empty() {
            continue;
        }
        let points = route_points(&routes[i].path);
        let best = connectors
            .iter()
            .enumerate()
            .filter(|(k, (t, _))| !used[*k] && *t == text)
            .map(|(k, (_, at))| {
                let d = points
                    .iter()
                    .map(|q| q.minus(*at).len())
                    .fold(f64::MAX, f64::min);
                (k, d)
            })
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        let (k, _) = best?;
        used[k] = true;
        routes[i].label_at = Some(connectors[k].1);
    }
    Some(bounded(dm, nodes, routes))
}

fn route_points(path: &[Cmd]) -> Vec<P> {
    let mut v = Vec::new();
    for c in path {
        match c {
            Cmd::M(a) | Cmd::L(a) => v.push(*a),
            Cmd::C(a, b, q) => v.extend([*a, *b, *q]),
            Cmd::S(a, q) => v.extend([*a, *q]),
        }
    }
    v
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

fn bounded(dm: &DmGraph, nodes: Vec<Placed>, routes: Vec<Route>) -> Local {
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
fn layered(dm: &DmGraph) -> Local {
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

/// The point of `n`'s ellipse towards `to`.
fn boundary(n: &Placed, to: P) -> P {
    let d = to.minus(n.center);
    let len = d.len();
    if len < 1e-9 {
        return n.center;
    }
    let (a, b) = (n.w / 2.0, n.h / 2.0);
    let t = 1.0 / ((d.x / a).powi(2) + (d.y / b).powi(2)).sqrt();
    n.center.plus(d.scale(t))
}

/// Places boxes of the given sizes with `layout-rs` (edges: calls); falls
/// back to a row when it cannot.
fn place_boxes(boxes: &[(f64, f64)], pairs: &[(usize, usize)]) -> Vec<P> {
    if boxes.is_empty() {
        return Vec::new();
    }
    let run = || {
        let mut vg = VisualGraph::new(Orientation::TopToBottom);
        let look = StyleAttr::new(Color::new(0), 1, None, 0, 7);
        let handles: Vec<_> = boxes
            .iter()
            .map(|&(w, h)| {
                vg.add_node(Element::create(
                    ShapeKind::Box(String::new()),
                    look.clone(),
                    Orientation::TopToBottom,
                    Point::new(w, h),
                ))
            })
            .collect();
        for &(a, b) in pairs {
            vg.add_edge(Arrow::simple(""), handles[a], handles[b]);
        }
        vg.do_it(false, false, false, &mut Capture::default());
        handles
            .iter()
            .map(|h| p(vg.pos(*h).center()))
            .collect::<Vec<_>>()
    };
    let grid = || {
        // rows of about √n boxes
        let per_row = (boxes.len() as f64).sqrt().ceil() as usize;
        let (mut x, mut y, mut row_h) = (0.0, 0.0, 0.0f64);
        let mut v = Vec::new();
        for (i, &(w, h)) in boxes.iter().enumerate() {
            if i > 0 && i % per_row == 0 {
                y += row_h + 40.0;
                x = 0.0;
                row_h = 0.0;
            }
            v.push(P::new(x + w / 2.0, y + h / 2.0));
            x += w + 40.0;
            row_h = row_h.max(h);
        }
        v
    };
    if boxes.len() > 60 || pairs.len() > 150 {
        return grid();
    }
    std::panic::catch_unwind(run).unwrap_or_else(|_| grid())
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

/// SVG path data of a route (one decimal).
pub fn path_data(path: &[Cmd]) -> String {
    let f = |q: &P| format!("{:.1} {:.1}", q.x, q.y);
    let mut s = String::new();
    for c in path {
        if !s.is_empty() {
            s.push(' ');
        }
        match c {
            Cmd::M(a) => s.push_str(&format!("M {}", f(a))),
            Cmd::L(a) => s.push_str(&format!("L {}", f(a))),
            Cmd::C(a, b, q) => s.push_str(&format!("C {} {} {}", f(a), f(b), f(q))),
            Cmd::S(a, q) => s.push_str(&format!("S {} {}", f(a), f(q))),
        }
    }
    s
}
