//! SVG of a laid-out diagram, self-contained (no scripts, no external
//! fonts or links). Every DM, node, return dot and edge is a `<g>` with a
//! stable `id`, a `class` (`dm`, `node situation`, `edge arc`, ...) and a
//! `<title>` that starts with its `file:line:col`, so that hovering says
//! where it is written; the live view highlights by those ids.

use crate::layout::{function_lines, node_lines, node_text, path_data, Layout, LINE_H, P};
use crate::trace::Overlay;
use crate::{Diagram, Edge, EdgeKind, Node, NodeKind, SituationKind};
use std::fmt::Write;

const FONT: &str = "DejaVu Sans Mono, Menlo, Consolas, monospace";

/// Escapes text for XML content and attribute values.
pub fn esc(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&#39;"),
            c if (c as u32) < 0x20 && c != '\n' && c != '\t' => o.push(' '),
            c => o.push(c),
        }
    }
    o
}

fn num(x: f64) -> String {
    format!("{x:.1}")
}

/// Renders the diagram (laid out by `l`), with a recorded run's colours when given.
pub fn render(d: &Diagram, l: &Layout, overlay: Option<&Overlay>) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="{FONT}">"#,
        w = num(l.width),
        h = num(l.height)
    );
    let _ = writeln!(s, "<title>{}</title>", esc(&d.title));
    s.push_str(concat!(
        "<defs>\n",
        r##"<marker id="arrow-black" viewBox="0 0 10 10" refX="9" refY="5" markerUnits="userSpaceOnUse" markerWidth="9" markerHeight="9" orient="auto-start-reverse"><path d="M 0 0 L 10 5 L 0 10 z" fill="#222"/></marker>"##,
        "\n",
        r##"<marker id="arrow-bold" viewBox="0 0 10 10" refX="8" refY="5" markerUnits="userSpaceOnUse" markerWidth="14" markerHeight="14" orient="auto-start-reverse"><path d="M 0 0 L 10 5 L 0 10 z" fill="#000"/></marker>"##,
        "\n",
        r##"<marker id="arrow-taken" viewBox="0 0 10 10" refX="9" refY="5" markerUnits="userSpaceOnUse" markerWidth="10" markerHeight="10" orient="auto-start-reverse"><path d="M 0 0 L 10 5 L 0 10 z" fill="#1a7f37"/></marker>"##,
        "\n</defs>\n",
    ));
    if overlay.is_some_and(|o| o.coverage) {
        s.truncate(s.len() - "</defs>\n".len());
        s.push_str(concat!(
            r##"<marker id="arrow-untaken" viewBox="0 0 10 10" refX="9" refY="5" markerUnits="userSpaceOnUse" markerWidth="10" markerHeight="10" orient="auto-start-reverse"><path d="M 0 0 L 10 5 L 0 10 z" fill="#c62828"/></marker>"##,
            "\n</defs>\n"
        ));
    }
    if d.edges().any(|e| e.kind == EdgeKind::Recovery) {
        s.truncate(s.len() - "</defs>\n".len());
        s.push_str(concat!(
            r##"<marker id="arrow-recovery" viewBox="0 0 10 10" refX="9" refY="5" markerUnits="userSpaceOnUse" markerWidth="10" markerHeight="10" orient="auto-start-reverse"><path d="M 0 0 L 10 5 L 0 10 z" fill="#a64b00"/></marker>"##,
            "\n</defs>\n"
        ));
    }
    let _ = writeln!(
        s,
        r##"<rect x="0" y="0" width="{}" height="{}" fill="#ffffff"/>"##,
        num(l.width),
        num(l.height)
    );
    // links first: the circles they end in cover them up to their dots
    for e in &d.links {
        edge(&mut s, e, l, overlay);
    }
    for (dm, oval) in d.dms.iter().zip(&l.ovals) {
        let _ = writeln!(
            s,
            r#"<g class="dm" id="{}" data-name="{}">"#,
            esc(&dm.id),
            esc(&dm.name)
        );
        let _ = writeln!(
            s,
            "<title>{}\ndiag_mod {}</title>",
            esc(&dm.location),
            esc(&dm.name)
        );
        let _ = writeln!(
            s,
            r##"<ellipse cx="{}" cy="{}" rx="{}" ry="{}" fill="none" stroke="#444" stroke-width="2" stroke-dasharray="2 5" stroke-linecap="round"/>"##,
            num(oval.center.x),
            num(oval.center.y),
            num(oval.rx),
            num(oval.ry)
        );
        for (i, line) in crate::wrap(&dm.name, 60).iter().enumerate() {
            let _ = writeln!(
                s,
                r##"<text x="{}" y="{}" text-anchor="middle" font-size="15" font-weight="bold" fill="#333">{}</text>"##,
                num(oval.center.x),
                num(oval.center.y - oval.ry + 22.0 + 17.0 * i as f64),
                esc(line)
            );
        }
        // nodes first: arcs leaving a return dot start inside their circle
        for n in &dm.nodes {
            node(&mut s, n, l, overlay);
        }
        for e in &dm.edges {
            edge(&mut s, e, l, overlay);
        }
        s.push_str("</g>\n");
    }
    for n in &d.externals {
        node(&mut s, n, l, overlay);
    }
    s.push_str("</svg>\n");
    s
}

fn edge(s: &mut String, e: &Edge, l: &Layout, overlay: Option<&Overlay>) {
    let Some(r) = l.routes.get(&e.id) else {
        return;
    };
    let kind = match e.kind {
        EdgeKind::Arc => "arc",
        EdgeKind::Exit => "exit",
        EdgeKind::Computed => "computed",
        EdgeKind::Pipe => "pipe",
        EdgeKind::Control => "control",
        EdgeKind::OutArg => "out-arg",
        EdgeKind::Recovery => "recovery",
        EdgeKind::Call => "call",
    };
    let taken = overlay.map(|o| o.edge_count(&e.id));
    let is_link = matches!(
        e.kind,
        EdgeKind::Pipe | EdgeKind::Control | EdgeKind::OutArg | EdgeKind::Recovery | EdgeKind::Call
    );
    let coverage = overlay.is_some_and(|o| o.coverage);
    let _ = writeln!(
        s,
        r#"<g class="edge {kind}" id="{}" data-from="{}" data-to="{}">"#,
        esc(&e.id),
        esc(&e.from),
        esc(&e.to)
    );
    let what = match e.kind {
        EdgeKind::Arc => format!("arc {}", e.label),
        EdgeKind::Exit => format!("exit {}", e.label),
        EdgeKind::Computed => format!("computed next situation {}", e.label),
        EdgeKind::Pipe => format!("pipe into {}", e.label),
        EdgeKind::Control => format!("control returns through {}", e.label),
        EdgeKind::OutArg => "the task's out_arg".to_owned(),
        EdgeKind::Recovery => format!("recovery protocol: {}", e.label),
        EdgeKind::Call => format!("calls {}", e.label),
    };
    let count = match taken {
        Some(n) if n > 0 => format!("\ntaken {n} time(s)"),
        Some(0) if coverage && !is_link => "\nnever taken".to_owned(),
        _ => String::new(),
    };
    let _ = writeln!(
        s,
        "<title>{}\n{}{}</title>",
        esc(&e.location),
        esc(&what),
        count
    );
    let (mut stroke, mut width, mut dash, mut marker) = match e.kind {
        EdgeKind::Arc | EdgeKind::Exit => ("#222", 1.3, "", "arrow-black"),
        EdgeKind::Computed => ("#222", 1.3, "6 4", "arrow-black"),
        EdgeKind::Pipe | EdgeKind::OutArg => ("#000", 3.5, "", "arrow-bold"),
        EdgeKind::Control => ("#777", 2.0, "7 3", ""),
        EdgeKind::Recovery => ("#a64b00", 2.0, "8 4", "arrow-recovery"),
        EdgeKind::Call => ("#222", 2.0, "", "arrow-black"),
    };
    let mut opacity = 1.0;
    match taken {
        // Coverage: an arc no run took is drawn red and dashed.
        Some(0) if !is_link && coverage => {
            stroke = "#c62828";
            marker = "arrow-untaken";
            width = 1.8;
            dash = "5 4";
        }
        Some(0) if !is_link => opacity = 0.45,
        Some(0) => {}
        Some(n) => {
            if matches!(e.kind, EdgeKind::Arc | EdgeKind::Exit | EdgeKind::Computed) {
                stroke = "#1a7f37";
                marker = "arrow-taken";
                width = 1.5 + (n as f64 + 1.0).log2().min(4.0);
                dash = if e.kind == EdgeKind::Computed {
                    "6 4"
                } else {
                    ""
                };
            }
        }
        None => {}
    }
    let dash_attr = if dash.is_empty() {
        String::new()
    } else {
        format!(r#" stroke-dasharray="{dash}""#)
    };
    let marker = if marker.is_empty() {
        String::new()
    } else {
        format!(r#" marker-end="url(#{marker})""#)
    };
    let _ = writeln!(
        s,
        r#"<path d="{}" fill="none" stroke="{stroke}" stroke-width="{}"{dash_attr} opacity="{}"{marker}/>"#,
        path_data(&r.path),
        num(width),
        num(opacity)
    );
    if let Some(at) = r.label_at {
        let mut lines = r.label_lines.clone();
        if let Some(n) = taken.filter(|&n| n > 0) {
            lines.push(format!("×{n}"));
        }
        let italic = matches!(e.kind, EdgeKind::Exit | EdgeKind::Computed);
        text_block(s, at, &lines, 11.0, italic, opacity, true);
    }
    s.push_str("</g>\n");
}

/// Lines of text centred on `at`, with a white backing so lines running
/// through stay readable.
fn text_block(
    s: &mut String,
    at: P,
    lines: &[String],
    size: f64,
    italic: bool,
    opacity: f64,
    backing: bool,
) {
    if lines.is_empty() {
        return;
    }
    let lh = size + 2.0;
    let w = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0) as f64 * size * 0.61;
    let h = lines.len() as f64 * lh;
    if backing {
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#ffffff" fill-opacity="0.85"/>"##,
            num(at.x - w / 2.0 - 2.0),
            num(at.y - h / 2.0),
            num(w + 4.0),
            num(h)
        );
    }
    let style = if italic {
        r#" font-style="italic""#
    } else {
        ""
    };
    for (i, line) in lines.iter().enumerate() {
        let y = at.y - h / 2.0 + lh * (i as f64 + 0.5) + size * 0.35;
        let _ = writeln!(
            s,
            r##"<text x="{}" y="{}" text-anchor="middle" font-size="{}"{style} fill="#111" opacity="{}">{}</text>"##,
            num(at.x),
            num(y),
            num(size),
            num(opacity),
            esc(line)
        );
    }
}

fn node(s: &mut String, n: &Node, l: &Layout, overlay: Option<&Overlay>) {
    let Some(pl) = l.nodes.get(&n.id) else {
        return;
    };
    let c = pl.center;
    let visits = overlay.map(|o| o.node_count(&n.id));
    let coverage = overlay.is_some_and(|o| o.coverage);
    let kind = match n.kind {
        NodeKind::Situation => "situation",
        NodeKind::Function => "function",
        NodeKind::Disjunction => "disjunction",
        NodeKind::Computed => "computed",
        NodeKind::ExternalDm => "external",
        NodeKind::OutArg => "out-arg",
        NodeKind::Dm => "dm-box",
    };
    if let Some(href) = &n.link {
        let _ = writeln!(s, r#"<a href="{}">"#, esc(href));
    }
    let _ = writeln!(
        s,
        r#"<g class="node {kind}" id="{}" data-label="{}">"#,
        esc(&n.id),
        esc(&n.label)
    );
    let what = match n.kind {
        NodeKind::Situation => format!(
            "situation {} (type {}){}",
            n.label,
            n.situation_type.as_deref().unwrap_or("?"),
            n.embedded_dm
                .as_ref()
                .map(|d| format!(", embedded DM {d}"))
                .unwrap_or_default()
        ),
        NodeKind::Function => format!(
            "next situation given by {}",
            n.detail.as_deref().unwrap_or(&n.label)
        ),
        NodeKind::Disjunction => format!("one of several instances of {}", n.label),
        NodeKind::Computed => format!("next situation computed at run time: {}", n.label),
        NodeKind::ExternalDm => format!("DM {} (not drawn)", n.label),
        NodeKind::OutArg => "the task's out_arg".to_owned(),
        NodeKind::Dm => format!(
            "DM {}{}",
            n.label,
            n.detail
                .as_ref()
                .map(|d| format!(": {d}"))
                .unwrap_or_default()
        ),
    };
    let count = match visits {
        Some(k) if k > 0 => format!("\nvisited {k} time(s)"),
        Some(0) if coverage && n.kind == NodeKind::Situation => "\nnever visited".to_owned(),
        _ => String::new(),
    };
    let _ = writeln!(
        s,
        "<title>{}\n{}{}</title>",
        esc(&n.location),
        esc(&what),
        count
    );
    let opacity = match visits {
        Some(0) if coverage && n.kind == NodeKind::Situation => 1.0,
        Some(0) => 0.45,
        _ => 1.0,
    };
    // Coverage: a situation no run visited has a red, dashed outline.
    let outline = match visits {
        Some(0) if coverage => r##"#c62828" stroke-dasharray="5 4"##,
        _ => "#222",
    };
    let fill = match visits {
        Some(k) if k > 0 => "#d4f5d4",
        _ => "#ffffff",
    };
    match n.kind {
        NodeKind::Situation => {
            let r = pl.w / 2.0;
            let width = if n.initial { 2.6 } else { 1.6 };
            let _ = writeln!(
                s,
                r##"<circle cx="{}" cy="{}" r="{}" fill="{fill}" stroke="{outline}" stroke-width="{}" opacity="{}"/>"##,
                num(c.x),
                num(c.y),
                num(r),
                num(width),
                num(opacity)
            );
            if n.situation_kind == Some(SituationKind::Final) {
                let _ = writeln!(
                    s,
                    r##"<circle cx="{}" cy="{}" r="{}" fill="none" stroke="#222" stroke-width="1" opacity="{}"/>"##,
                    num(c.x),
                    num(c.y),
                    num(r - 4.0),
                    num(opacity)
                );
            }
            let (bold, italic) = node_text(n);
            let lines: Vec<(bool, &String)> = bold
                .iter()
                .map(|l| (true, l))
                .chain(italic.iter().map(|l| (false, l)))
                .collect();
            let lh = LINE_H;
            let at = if n.returns.is_empty() {
                c
            } else {
                // above the return dots (at half the radius below the centre)
                P {
                    x: c.x,
                    y: c.y - (lh * lines.len() as f64 / 2.0).max(r * 0.22),
                }
            };
            // id in bold, type in italic
            let top = at.y - lh * lines.len() as f64 / 2.0;
            for (i, (is_bold, line)) in lines.iter().enumerate() {
                let (weight, style) = if *is_bold {
                    (r#" font-weight="bold""#, "")
                } else {
                    ("", r#" font-style="italic""#)
                };
                let _ = writeln!(
                    s,
                    r##"<text x="{}" y="{}" text-anchor="middle" font-size="12"{weight}{style} fill="#111" opacity="{}">{}</text>"##,
                    num(c.x),
                    num(top + lh * (i as f64 + 0.5) + 4.0),
                    num(opacity),
                    esc(line)
                );
            }
            for dot in &n.returns {
                let Some(&q) = l.dots.get(&dot.id) else {
                    continue;
                };
                let _ = writeln!(
                    s,
                    r##"<g class="return" id="{}"><title>{}
return point of the embedded DM's final situation {}</title><circle cx="{}" cy="{}" r="5.5" fill="#000" opacity="{}"/></g>"##,
                    esc(&dot.id),
                    esc(&dot.location),
                    esc(&dot.final_id),
                    num(q.x),
                    num(q.y),
                    num(opacity)
                );
            }
            if let Some(k) = visits.filter(|&k| k > 0) {
                let _ = writeln!(
                    s,
                    r##"<text x="{}" y="{}" font-size="11" font-weight="bold" fill="#1a7f37">×{k}</text>"##,
                    num(c.x + r * 0.75),
                    num(c.y - r * 0.75)
                );
            }
        }
        NodeKind::Function => {
            let _ = writeln!(
                s,
                r##"<circle cx="{}" cy="{}" r="9" fill="#000" opacity="{}"/>"##,
                num(c.x),
                num(c.y),
                num(opacity)
            );
            let lines = function_lines(n);
            let tw =
                lines.iter().map(|l| l.chars().count()).max().unwrap_or(0) as f64 * 12.0 * 0.61;
            let _ = writeln!(
                s,
                r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#ffffff" fill-opacity="0.85"/>"##,
                num(c.x + 12.0),
                num(c.y - 19.0),
                num(tw + 4.0),
                num(15.0 * lines.len() as f64)
            );
            for (i, line) in lines.iter().enumerate() {
                let _ = writeln!(
                    s,
                    r##"<text x="{}" y="{}" font-size="12" font-weight="bold" font-style="italic" fill="#000" opacity="{}">{}</text>"##,
                    num(c.x + 14.0),
                    num(c.y - 8.0 + 15.0 * i as f64),
                    num(opacity),
                    esc(line)
                );
            }
        }
        NodeKind::Disjunction | NodeKind::Computed => {
            let dash = if n.kind == NodeKind::Computed {
                r#" stroke-dasharray="3 2""#
            } else {
                ""
            };
            let _ = writeln!(
                s,
                r##"<circle cx="{}" cy="{}" r="{}" fill="{fill}" stroke="#222" stroke-width="1.4"{dash} opacity="{}"/>"##,
                num(c.x),
                num(c.y),
                num(pl.w / 2.0),
                num(opacity)
            );
            let sym = if n.kind == NodeKind::Computed {
                "?"
            } else {
                "∨"
            };
            let _ = writeln!(
                s,
                r##"<text x="{}" y="{}" text-anchor="middle" font-size="14" font-weight="bold" fill="#111" opacity="{}">{sym}</text>"##,
                num(c.x),
                num(c.y + 5.0),
                num(opacity)
            );
        }
        NodeKind::ExternalDm | NodeKind::OutArg => {
            if n.kind == NodeKind::ExternalDm {
                let _ = writeln!(
                    s,
                    r##"<rect x="{}" y="{}" width="{}" height="{}" rx="12" fill="#ffffff" stroke="#444" stroke-width="1.5" stroke-dasharray="2 4"/>"##,
                    num(c.x - pl.w / 2.0),
                    num(c.y - pl.h / 2.0),
                    num(pl.w),
                    num(pl.h)
                );
            }
            text_block(s, c, &node_lines(n), 12.0, false, 1.0, false);
        }
        NodeKind::Dm => {
            let stroke = if n.initial { 3.0 } else { 1.6 };
            let _ = writeln!(
                s,
                r##"<rect x="{}" y="{}" width="{}" height="{}" rx="14" fill="#f7f7ff" stroke="#333" stroke-width="{}" stroke-dasharray="2 4" stroke-linecap="round"/>"##,
                num(c.x - pl.w / 2.0),
                num(c.y - pl.h / 2.0),
                num(pl.w),
                num(pl.h),
                num(stroke)
            );
            let (bold, plain) = node_text(n);
            let total = (bold.len() + plain.len()) as f64;
            let top = c.y - LINE_H * total / 2.0;
            for (i, (is_bold, line)) in bold
                .iter()
                .map(|l| (true, l))
                .chain(plain.iter().map(|l| (false, l)))
                .enumerate()
            {
                let (size, weight) = if is_bold {
                    (13.0, r#" font-weight="bold""#)
                } else {
                    (11.0, "")
                };
                let _ = writeln!(
                    s,
                    r##"<text x="{}" y="{}" text-anchor="middle" font-size="{}"{weight} fill="#111">{}</text>"##,
                    num(c.x),
                    num(top + LINE_H * (i as f64 + 0.5) + 4.0),
                    num(size),
                    esc(line)
                );
            }
        }
    }
    s.push_str("</g>\n");
    if n.link.is_some() {
        s.push_str("</a>\n");
    }
}
