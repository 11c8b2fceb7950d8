//! The diagram as Graphviz DOT, for people who have Graphviz: one dotted
//! cluster per DM; situations as circles (`id\ntype`), function dots as
//! filled points with an external label, disjunctions as `∨` circles;
//! return dots as points joined to their recursive situation; pipes and
//! the out_arg bold; every element's `tooltip` is its `file:line:col`
//! (Graphviz's SVG output turns it into a `<title>`).

use crate::{Diagram, Edge, EdgeKind, Node, NodeKind, SituationKind};
use std::fmt::Write;

/// A DOT string literal.
fn q(s: &str) -> String {
    let mut o = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            '\n' => o.push_str("\\n"),
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

/// Renders the diagram as DOT.
pub fn render(d: &Diagram) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "digraph {} {{", q(&d.title));
    s.push_str("  compound=true;\n  fontname=\"monospace\";\n");
    s.push_str("  node [fontname=\"monospace\", fontsize=11];\n");
    s.push_str("  edge [fontname=\"monospace\", fontsize=10];\n");
    for dm in &d.dms {
        let _ = writeln!(s, "  subgraph {} {{", q(&format!("cluster_{}", dm.id)));
        let _ = writeln!(
            s,
            "    label={}; style=\"dotted,rounded\"; penwidth=2; tooltip={};",
            q(&dm.name),
            q(&dm.location)
        );
        for n in &dm.nodes {
            node(&mut s, n);
        }
        for e in &dm.edges {
            edge(&mut s, e, d);
        }
        s.push_str("  }\n");
    }
    for n in &d.externals {
        node(&mut s, n);
    }
    for e in &d.links {
        edge(&mut s, e, d);
    }
    s.push_str("}\n");
    s
}

fn node(s: &mut String, n: &Node) {
    let attrs = match n.kind {
        NodeKind::Situation => {
            let label = format!("{}\n{}", n.label, n.situation_type.as_deref().unwrap_or(""));
            let shape = if n.situation_kind == Some(SituationKind::Final) {
                "doublecircle"
            } else {
                "circle"
            };
            let pen = if n.initial { ", penwidth=2" } else { "" };
            format!("shape={shape}, label={}{pen}", q(&label))
        }
        NodeKind::Function => format!(
            "shape=point, width=0.22, xlabel={}, fontname=\"monospace bold\"",
            q(&n.label)
        ),
        NodeKind::Disjunction => "shape=circle, width=0.3, fixedsize=true, label=\"∨\"".to_owned(),
        NodeKind::Computed => {
            "shape=circle, style=dashed, width=0.3, fixedsize=true, label=\"?\"".to_owned()
        }
        NodeKind::ExternalDm => {
            format!("shape=box, style=\"dotted,rounded\", label={}", q(&n.label))
        }
        NodeKind::OutArg => format!("shape=plaintext, label={}", q(&n.label)),
        NodeKind::Dm => {
            let label = match &n.detail {
                Some(d) => format!("{}\n{d}", n.label),
                None => n.label.clone(),
            };
            let pen = if n.initial { ", penwidth=2" } else { "" };
            let url = n
                .link
                .as_ref()
                .map(|l| format!(", URL={}", q(l)))
                .unwrap_or_default();
            format!(
                "shape=box, style=\"dotted,rounded\", label={}{pen}{url}",
                q(&label)
            )
        }
    };
    let _ = writeln!(s, "    {} [{attrs}, tooltip={}];", q(&n.id), q(&n.location));
    for r in &n.returns {
        let _ = writeln!(
            s,
            "    {} [shape=point, width=0.12, tooltip={}];",
            q(&r.id),
            q(&format!("{}\nreturn point of {}", r.location, r.final_id))
        );
        let _ = writeln!(
            s,
            "    {} -> {} [arrowhead=none, style=bold, tooltip={}];",
            q(&n.id),
            q(&r.id),
            q(&r.location)
        );
    }
}

fn edge(s: &mut String, e: &Edge, d: &Diagram) {
    let mut from = e.from_port.as_deref().unwrap_or(&e.from);
    // an edge leaving a whole DM leaves its cluster (from its first node)
    let mut tail = String::new();
    if let Some(dm) = d.dms.iter().find(|g| g.id == e.from) {
        let Some(first) = dm.nodes.first() else {
            return;
        };
        from = &first.id;
        tail = format!(", ltail={}", q(&format!("cluster_{}", dm.id)));
    }
    let to = e.to_port.as_deref().unwrap_or(&e.to);
    let style = match e.kind {
        EdgeKind::Arc => "",
        EdgeKind::Exit => ", fontname=\"monospace italic\"",
        EdgeKind::Computed => ", style=dashed",
        EdgeKind::Pipe | EdgeKind::OutArg => ", penwidth=3.5",
        EdgeKind::Control => ", style=dashed, penwidth=2, color=\"#777777\"",
        EdgeKind::Recovery => ", style=dashed, penwidth=2, color=\"#a64b00\"",
        EdgeKind::Call => ", penwidth=2",
    };
    let label = if e.label.is_empty() {
        String::new()
    } else {
        format!(", label={}", q(&e.label))
    };
    let _ = writeln!(
        s,
        "    {} -> {} [id={}{label}{style}{tail}, tooltip={}];",
        q(from),
        q(to),
        q(&e.id),
        q(&e.location)
    );
}
