//! Everything that drives `layout-rs`: the work it would do on one DM,
//! counted before it runs ([`engine_work`]), one DM laid out by the engine
//! (on a thread of its own, given up after a panic or a hang) and read back
//! from the arrows it draws, and the boxes of the program's call graph
//! placed by it (a grid when it cannot).

use super::dm::{bounded, Local};
use super::geometry::{label_lines, node_size, route_points, Cmd, Placed, Route, P};
use crate::{DmGraph, NodeKind};
use layout::adt::dag::NodeHandle;
use layout::core::base::Orientation;
use layout::core::color::Color;
use layout::core::format::{ClipHandle, RenderBackend};
use layout::core::geometry::Point;
use layout::core::style::StyleAttr;
use layout::std_shapes::shapes::{Arrow, Element, LineEndKind, ShapeKind};
use layout::topo::layout::VisualGraph;
use std::collections::HashMap;

/// [`engine`] on a thread of its own, given up after `time` (a guard
/// against a hang of the engine; the thread is left to finish on its own)
/// or when the engine fails.
pub(super) fn engine_within(
    dm: &DmGraph,
    optimize: bool,
    across: bool,
    time: std::time::Duration,
) -> Result<Local, String> {
    let (tx, rx) = std::sync::mpsc::channel();
    let owned = dm.clone();
    let spawned = std::thread::Builder::new()
        .name("sitlog-graph-layout".to_owned())
        .spawn(move || {
            let r = std::panic::catch_unwind(|| engine(&owned, optimize, across));
            let _ = tx.send(r.ok().flatten());
        });
    if spawned.is_err() {
        return Err("no thread for the layout engine".to_owned());
    }
    match rx.recv_timeout(time) {
        Ok(Some(l)) => Ok(l),
        Ok(None) => Err("the layout engine could not place it".to_owned()),
        Err(_) => Err("the layout engine did not finish (hung)".to_owned()),
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

/// An arc label as `layout-rs` is given it: the engine reserves 7 px a
/// character and 7 px a line (its font size), and the SVG draws lines 13 px
/// apart, so each line is followed by an empty one to reserve its height.
fn engine_label(lines: &[String]) -> String {
    if lines.is_empty() {
        return String::new();
    }
    let mut text = lines.join("\n\n");
    text.push_str("\n ");
    text
}

/// The graph `layout-rs` is given for one DM (ranks top to bottom, or left
/// to right `across`): a node per node, an edge per edge whose ends are
/// there (its properties its index), and the first handle that is not a
/// node (label connectors come after the nodes).
fn visual_graph(dm: &DmGraph, across: bool) -> (VisualGraph, Vec<NodeHandle>) {
    let orientation = if across {
        Orientation::LeftToRight
    } else {
        Orientation::TopToBottom
    };
    let mut vg = VisualGraph::new(orientation);
    let look = StyleAttr::new(Color::new(0), 1, None, 0, 7);
    let mut handles = Vec::new();
    let mut index: HashMap<&str, usize> = HashMap::new();
    for (i, n) in dm.nodes.iter().enumerate() {
        let (w, h) = node_size(n);
        // boxes are clipped as boxes, so that arrows end at their edge
        let shape = if matches!(
            n.kind,
            NodeKind::Dm | NodeKind::ExternalDm | NodeKind::OutArg
        ) {
            ShapeKind::Box(String::new())
        } else {
            ShapeKind::Circle(String::new())
        };
        let el = Element::create(shape, look.clone(), orientation, Point::new(w, h));
        handles.push(vg.add_node(el));
        index.insert(n.id.as_str(), i);
    }
    for (i, e) in dm.edges.iter().enumerate() {
        let (Some(&a), Some(&b)) = (index.get(e.from.as_str()), index.get(e.to.as_str())) else {
            continue;
        };
        let text = engine_label(&label_lines(&e.label));
        let mut arrow = Arrow::simple(&text);
        arrow.look = look.clone();
        arrow.properties = Some(i.to_string());
        arrow.end = LineEndKind::Arrow;
        vg.add_edge(arrow, handles[a], handles[b]);
    }
    (vg, handles)
}

/// The work `layout-rs` would do on one DM, counted, not timed. The DM's
/// graph is lowered as the engine lowers it, on a copy: back edges turned
/// round, a connector for each label, ranks by longest path; the dummy
/// nodes a long edge needs (one for each rank it crosses) are counted, not
/// made, and the engine's rank sinking, which only removes dummy nodes, is
/// left out, so this never counts less than the engine has. On those ranks
/// it counts the engine's passes: the placement schedules every node
/// against every other, four times; the crossing reduction (`optimize`)
/// compares each pair of a rank with each node of the next rank, 50 times,
/// each comparison a scan of both nodes' edges (counted as 8 steps; so
/// measured, a step of either pass takes about the same time, 10–25 ns in
/// a debug build). The same on any machine: this, not a clock, decides
/// what the engine lays out.
///
/// `None` when the engine's lowering fails on the DM (a panic of the
/// engine, caught): the engine could not place it either.
pub fn engine_work(dm: &DmGraph, optimize: bool, across: bool) -> Option<u64> {
    std::panic::catch_unwind(|| count_work(dm, optimize, across)).ok()
}

fn count_work(dm: &DmGraph, optimize: bool, across: bool) -> u64 {
    let (mut vg, _) = visual_graph(dm, across);
    if vg.num_nodes() == 0 {
        return 0;
    }
    // the engine's own checks of its DAG after each edge: not needed to count
    vg.dag.set_validate(false);
    vg.to_valid_dag();
    vg.split_text_edges();
    vg.dag.recompute_node_ranks();
    let dag = &vg.dag;
    let levels = dag.num_levels();
    // nodes in each rank, then the dummy nodes of the edges crossing it
    let mut width = vec![0u64; levels];
    let mut crossing = vec![0i64; levels + 1];
    for a in dag.iter() {
        let la = dag.level(a);
        width[la] += 1;
        for &b in dag.successors(a) {
            let lb = dag.level(b);
            if lb > la + 1 {
                crossing[la + 1] += 1;
                crossing[lb] -= 1;
            }
        }
    }
    let mut through = 0i64;
    for (w, c) in width.iter_mut().zip(&crossing) {
        through += c;
        *w += through.max(0) as u64;
    }
    // a self edge becomes a connector beside its node
    let loops = dm.edges.iter().filter(|e| e.from == e.to).count() as u64;
    let nodes = width.iter().sum::<u64>() + loops;
    let mut work = nodes.saturating_mul(nodes).saturating_mul(4);
    if optimize {
        for pair in width.windows(2) {
            let (w, next) = (pair[0], pair[1]);
            let pairs = w.saturating_mul(w).saturating_mul(next) / 2;
            let step = pairs.saturating_add(w.saturating_mul(next));
            work = work.saturating_add(step.saturating_mul(50 * 8));
        }
    }
    work
}

/// `layout-rs` on one DM (ranks top to bottom, or left to right
/// `across`); `None` when its output cannot be read back.
fn engine(dm: &DmGraph, optimize: bool, across: bool) -> Option<Local> {
    let (mut vg, handles) = visual_graph(dm, across);
    let first = handles.len();
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
        // The edge passes through the connector's `center` (the bottom of
        // its box, top to bottom); the engine reserved the box above it,
        // round its `middle`, for the text.
        if let ShapeKind::Connector(Some(t)) = &vg.element(h).shape {
            let pos = vg.pos(h);
            connectors.push((t.clone(), p(pos.center()), p(pos.middle())));
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
        let text = engine_label(&routes[i].label_lines);
        if text.is_empty() {
            continue;
        }
        let points = route_points(&routes[i].path);
        let best = connectors
            .iter()
            .enumerate()
            .filter(|(k, (t, _, _))| !used[*k] && *t == text)
            .map(|(k, (_, at, _))| {
                let d = points
                    .iter()
                    .map(|q| q.minus(*at).len())
                    .fold(f64::MAX, f64::min);
                (k, d)
            })
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        let (k, _) = best?;
        used[k] = true;
        routes[i].label_at = Some(connectors[k].2);
    }
    Some(bounded(dm, nodes, routes))
}

/// Places boxes of the given sizes with `layout-rs` (edges: calls); falls
/// back to a grid when it cannot.
pub(super) fn place_boxes(boxes: &[(f64, f64)], pairs: &[(usize, usize)]) -> Vec<P> {
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
