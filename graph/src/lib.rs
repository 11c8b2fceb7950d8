//! `sitlog-graph`: SitLog programs drawn in the notation of the papers
//! (the 2021 paper's §4.3 and Figure 3; the 2015 paper's §4, Figures 1, 2
//! and 4).
//!
//! This crate owns the *diagram model* ([`Diagram`]: DMs, situations,
//! function dots, disjunctions, return dots, arcs, pipes, control and
//! recovery links; the overview's DM boxes and calls; each with its
//! `file:line:col`), label wrapping ([`wrap`]), its layout ([`layout`], on the pure-Rust
//! Graphviz-style engine `layout-rs`) and its renderings: SVG ([`svg`]),
//! DOT ([`dot`]) and JSON ([`Diagram::to_json`]), plus the colouring of a
//! recorded run ([`trace`]).
//!
//! **Invariant:** the model is built from the checked IR by the compiler
//! (`sitlog_compiler::diagram`), never from source text; this crate knows
//! nothing of terms or files (no sitlog crate among its dependencies). Every
//! output is a pure function of the model: same model, same bytes (no
//! hash-map order, fixed float formatting). What the layout engine may take
//! is counted in work, not time ([`layout::engine_work`]): a DM past the
//! work limits gets the simple layered layout, the same on any machine, and
//! a note in the layout says so.
//!
//! Modules, each using only the model (defined here) and those listed before it:
//! [`layout`], [`trace`], [`svg`], [`dot`].

pub mod dot;
pub mod layout;
pub mod svg;
pub mod trace;

use serde::{Deserialize, Serialize};

/// A whole program, or one DM of it.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Diagram {
    /// The application's name.
    pub title: String,
    pub dms: Vec<DmGraph>,
    /// Nodes outside every DM: called DMs that are not drawn (with `--dm`),
    /// and the task's `out_arg` leaving the main DM.
    pub externals: Vec<Node>,
    /// Edges between DMs (pipes, control links, the task's out_arg).
    pub links: Vec<Edge>,
}

/// One DM: its situations and the arcs between them, inside a dotted oval.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct DmGraph {
    /// Stable id (`d0`, `d1`, ... in program order).
    pub id: String,
    /// The DM's identifier as written (`main`, `find(Object, Shelves, ...)`).
    pub name: String,
    /// `file:line:col` of the `diag_mod` clause.
    pub location: String,
    pub nodes: Vec<Node>,
    pub edges: Vec<Edge>,
}

/// What a node stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NodeKind {
    /// A situation: a circle with its id and type.
    Situation,
    /// The large bold dot of a next situation given by a function (a user
    /// function or a conditional), labelled with the function.
    Function,
    /// The small circle with `∨` before several instances of one situation id.
    Disjunction,
    /// Where a next situation the compiler cannot enumerate goes.
    Computed,
    /// A called DM that is not drawn.
    ExternalDm,
    /// The task's out_arg leaving the main DM.
    OutArg,
    /// A whole DM, as a box of the program's overview (its `detail`: how
    /// many situations, and where).
    Dm,
}

/// The kind of situation (for situation nodes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SituationKind {
    Perceptual,
    Recursive,
    Final,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Node {
    /// Stable id, unique in the diagram (`d0.s2`, `d0.s2.a1.f`, ...).
    pub id: String,
    pub kind: NodeKind,
    /// The situation id, the function, `∨`, the called DM...
    pub label: String,
    /// The situation's type as written (situation nodes only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub situation_type: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub situation_kind: Option<SituationKind>,
    /// Whether this is the DM's initial situation (the first one).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub initial: bool,
    /// Principal functor `name/arity` of a situation id (for matching a run's trace).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub functor: Option<String>,
    /// The embedded DM of a recursive situation, as written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub embedded_dm: Option<String>,
    /// The return dots of a recursive situation: one per final situation
    /// of the embedded DM.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub returns: Vec<ReturnDot>,
    /// More about it (a function dot: the call as written; a DM of the
    /// overview: its situations and file).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub detail: Option<String>,
    /// A page the SVG links the node to (a DM's own page, `sitlogc graph
    /// --out-dir`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub link: Option<String>,
    /// `file:line:col` where it is written.
    pub location: String,
}

/// A control return point inside a recursive situation.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ReturnDot {
    /// Stable id (`<situation id>.r<k>`).
    pub id: String,
    /// The id of the embedded DM's final situation, as written there.
    pub final_id: String,
    /// `file:line:col` of that final situation.
    pub location: String,
}

/// What an edge stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EdgeKind {
    /// An arc `α:β`, from a situation (or one of its return dots) to the
    /// next situation, a function dot or a disjunction.
    Arc,
    /// One possible value out of a function dot or a disjunction,
    /// labelled with its condition.
    Exit,
    /// Dashed: a value the compiler cannot enumerate.
    Computed,
    /// Bold: the pipe from a recursive situation into the embedded DM's
    /// initial situation (out_arg of one feeding in_arg of the next).
    Pipe,
    /// From a final situation of an embedded DM to the return dot of the
    /// recursive situation that called it.
    Control,
    /// Bold: the task's out_arg leaving the main DM.
    OutArg,
    /// Dashed: from a situation whose type has a recovery protocol (or, in
    /// the overview, a DM with such situations) to the recovery DM, run
    /// when no expectation of the situation is met.
    Recovery,
    /// In the overview: a DM calls another (its recursive situations'
    /// `embedded_dm`, the calls as label).
    Call,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Edge {
    /// Stable id, unique in the diagram (`e:...`).
    pub id: String,
    pub kind: EdgeKind,
    pub from: String,
    /// The return dot the edge leaves from (arcs of recursive situations).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub from_port: Option<String>,
    pub to: String,
    /// The return dot the edge goes into (control links).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to_port: Option<String>,
    /// `α:β` for arcs, the condition or value for exits, ...
    pub label: String,
    /// The arc's expectation as written (arcs out of a situation only;
    /// to tell which arc a recorded transition took).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub expectation: Option<String>,
    pub location: String,
}

impl Diagram {
    /// Every node, DMs first (in order), then the externals.
    pub fn nodes(&self) -> impl Iterator<Item = &Node> {
        self.dms
            .iter()
            .flat_map(|d| d.nodes.iter())
            .chain(self.externals.iter())
    }

    /// Every edge: DM edges in order, then the links.
    pub fn edges(&self) -> impl Iterator<Item = &Edge> {
        self.dms
            .iter()
            .flat_map(|d| d.edges.iter())
            .chain(self.links.iter())
    }

    /// Reads the JSON form back.
    pub fn from_json(text: &str) -> Result<Diagram, String> {
        serde_json::from_str(text).map_err(|e| format!("not a diagram: {e}"))
    }

    /// The JSON form: `{"title", "dms": [{"id","name","location","nodes","edges"}],
    /// "externals", "links"}`, pretty-printed, with a final newline.
    pub fn to_json(&self) -> String {
        let mut s = serde_json::to_string_pretty(self).expect("a diagram always serializes");
        s.push('\n');
        s
    }

    /// Number of situations drawn.
    pub fn situation_count(&self) -> usize {
        self.nodes()
            .filter(|n| n.kind == NodeKind::Situation)
            .count()
    }
}

/// Lines a label wraps into: at most [`WRAP_LINES`]; past them the last
/// line ends with `…` (only a label of hundreds of characters is cut).
pub const WRAP_LINES: usize = 12;

/// `text` in lines of at most `width` characters, broken after a `,`, a
/// space, a `:` or an opening bracket where possible (inside a word only
/// where it has none), continuation lines without leading spaces.
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let width = width.max(4);
    let chars: Vec<char> = text.chars().collect();
    let mut lines = Vec::new();
    let mut start = 0;
    while start < chars.len() {
        if chars.len() - start <= width {
            lines.push(chars[start..].iter().collect::<String>());
            break;
        }
        // the last break opportunity within the width
        let end = start + width;
        let cut = (start + 1..=end)
            .rev()
            .find(|&i| matches!(chars[i - 1], ',' | ' ' | ':' | '(' | '[' | '|'))
            .filter(|&i| i > start + width / 3)
            .unwrap_or(end);
        lines.push(
            chars[start..cut]
                .iter()
                .collect::<String>()
                .trim_end()
                .to_owned(),
        );
        start = cut;
        while start < chars.len() && chars[start] == ' ' {
            start += 1;
        }
        if lines.len() == WRAP_LINES && start < chars.len() {
            let last = lines.pop().unwrap_or_default();
            lines.push(shorten(
                &format!("{last} {}", chars[start..].iter().collect::<String>()),
                width,
            ));
            break;
        }
    }
    if lines.is_empty() {
        lines.push(String::new());
    }
    lines
}

/// Shortens `text` to at most `max` characters, ending with `…` when cut.
pub fn shorten(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        return text.to_owned();
    }
    let mut s: String = text.chars().take(max.saturating_sub(1)).collect();
    s.push('…');
    s
}
