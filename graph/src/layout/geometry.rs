//! What a layout is made of and how big things are drawn: points, placed
//! nodes, DM ovals, paths and routes, the whole [`Layout`]; the lines of
//! node and edge labels and the sizes they give the shapes; SVG path data.
//! Pure geometry: no layout engine here.

use crate::{wrap, Node, NodeKind};
use std::collections::HashMap;

/// Width of one character of label text, in the monospace font the SVG uses.
pub const CHAR_W: f64 = 7.0;
/// Longest edge label line, in characters (longer labels wrap).
pub const LABEL_MAX: usize = 40;
/// Longest situation label line, in characters (longer ids wrap).
pub const NODE_LABEL_MAX: usize = 26;
/// Longest line in a DM's box of the overview, in characters.
pub const DM_LABEL_MAX: usize = 20;
/// Height of a line of node text.
pub const LINE_H: f64 = 14.0;

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
    /// The label's lines as drawn (wrapped).
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
/// else `α :` and `β` each wrapped to [`LABEL_MAX`] characters; a label
/// with line breaks of its own keeps them.
pub fn label_lines(label: &str) -> Vec<String> {
    if label.is_empty() {
        return Vec::new();
    }
    if label.contains('\n') {
        return label.lines().flat_map(|l| wrap(l, LABEL_MAX)).collect();
    }
    if label.chars().count() <= LABEL_MAX {
        return vec![label.to_owned()];
    }
    if let Some(i) = label.find(" : ") {
        let (a, b) = (&label[..i + 2], &label[i + 3..]);
        let mut lines = wrap(a, LABEL_MAX);
        lines.extend(wrap(b, LABEL_MAX));
        return lines;
    }
    wrap(label, LABEL_MAX)
}

/// The text inside a node: its bold lines (a situation's id, a DM's name)
/// and its plain or italic ones (a situation's type, a DM's summary).
pub fn node_text(n: &Node) -> (Vec<String>, Vec<String>) {
    match n.kind {
        NodeKind::Situation => (
            wrap(&n.label, NODE_LABEL_MAX),
            n.situation_type
                .as_deref()
                .map_or_else(Vec::new, |t| wrap(t, NODE_LABEL_MAX)),
        ),
        NodeKind::ExternalDm | NodeKind::OutArg => (Vec::new(), wrap(&n.label, LABEL_MAX)),
        NodeKind::Dm => (
            wrap(&n.label, DM_LABEL_MAX),
            n.detail
                .as_deref()
                .map_or_else(Vec::new, |t| wrap(t, DM_LABEL_MAX)),
        ),
        NodeKind::Disjunction => (Vec::new(), vec!["∨".to_owned()]),
        NodeKind::Computed => (Vec::new(), vec!["?".to_owned()]),
        NodeKind::Function => (Vec::new(), Vec::new()),
    }
}

/// The lines written inside a node ([`node_text`], bold lines first).
pub fn node_lines(n: &Node) -> Vec<String> {
    let (mut a, b) = node_text(n);
    a.extend(b);
    a
}

/// The lines of a function dot's label (beside the dot).
pub fn function_lines(n: &Node) -> Vec<String> {
    wrap(&n.label, LABEL_MAX)
}

/// Size of a node's shape.
pub fn node_size(n: &Node) -> (f64, f64) {
    let lines = node_lines(n);
    let chars = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0) as f64;
    let text_h = lines.len() as f64 * LINE_H;
    match n.kind {
        NodeKind::Situation => {
            // a circle round the text's box
            let (w, h) = (chars * CHAR_W + 16.0, text_h + 8.0);
            let mut d = (w * w + h * h).sqrt().max(58.0);
            if !n.returns.is_empty() {
                d = d.max(18.0 * n.returns.len() as f64 + 40.0).max(74.0);
                // the text sits above the return dots
                d = d.max(2.4 * text_h + 30.0);
            }
            (d.round(), d.round())
        }
        NodeKind::Function => (20.0, 20.0),
        NodeKind::Disjunction => (24.0, 24.0),
        NodeKind::Computed => (26.0, 26.0),
        NodeKind::ExternalDm | NodeKind::OutArg => (chars * CHAR_W + 20.0, text_h + 16.0),
        NodeKind::Dm => (chars * CHAR_W + 28.0, text_h + 22.0),
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

pub(super) fn route_points(path: &[Cmd]) -> Vec<P> {
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

/// The point of `n`'s ellipse towards `to`.
pub(super) fn boundary(n: &Placed, to: P) -> P {
    let d = to.minus(n.center);
    let len = d.len();
    if len < 1e-9 {
        return n.center;
    }
    let (a, b) = (n.w / 2.0, n.h / 2.0);
    let t = 1.0 / ((d.x / a).powi(2) + (d.y / b).powi(2)).sqrt();
    n.center.plus(d.scale(t))
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
