//! Arc coverage: which situations and arcs of each DM (the application's
//! and the behaviour library's) the recorded runs of `sitlogc test` took,
//! counted on the program's diagram ([`sitlog_graph::trace`] lays a
//! recorded run over it, as `sitlogc graph --trace` does). The counts are
//! those of the diagram: situations are its situation nodes; arcs are its
//! arcs out of situations and the exits of function dots and
//! disjunctions (each value a next situation may take).

use sitlog_graph::trace::Overlay;
use sitlog_graph::{Diagram, EdgeKind, NodeKind};

/// The coverage of one DM.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DmCoverage {
    pub name: String,
    /// `file:line:col` of its `diag_mod`.
    pub location: String,
    pub situations: (usize, usize),
    pub arcs: (usize, usize),
    /// Arcs never taken: (`file:line:col`, from situation, label).
    pub untaken: Vec<(String, String, String)>,
}

/// The coverage of a program.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Coverage {
    pub dms: Vec<DmCoverage>,
    /// Transitions read, and those not in the diagram.
    pub transitions: usize,
    pub unmatched: usize,
}

impl Coverage {
    /// Counts `overlay` (runs read against `d`) per DM.
    pub fn of(d: &Diagram, overlay: &Overlay) -> Coverage {
        let mut dms = Vec::new();
        for g in &d.dms {
            let label = |id: &str| {
                g.nodes
                    .iter()
                    .find(|n| n.id == id)
                    .map(|n| n.label.clone())
                    .unwrap_or_default()
            };
            let sits: Vec<_> = g
                .nodes
                .iter()
                .filter(|n| n.kind == NodeKind::Situation)
                .collect();
            let arcs: Vec<_> = g
                .edges
                .iter()
                .filter(|e| matches!(e.kind, EdgeKind::Arc | EdgeKind::Exit))
                .collect();
            let untaken = arcs
                .iter()
                .filter(|e| overlay.edge_count(&e.id) == 0)
                .map(|e| {
                    // an exit leaves a function dot: name the situation before it
                    let from = match g.nodes.iter().find(|n| n.id == e.from) {
                        Some(n) if n.kind == NodeKind::Situation => n.label.clone(),
                        Some(n) => g
                            .edges
                            .iter()
                            .find(|a| a.to == n.id)
                            .map(|a| label(&a.from))
                            .unwrap_or_else(|| n.label.clone()),
                        None => String::new(),
                    };
                    (e.location.clone(), from, e.label.clone())
                })
                .collect();
            dms.push(DmCoverage {
                name: g.name.clone(),
                location: g.location.clone(),
                situations: (
                    sits.iter().filter(|n| overlay.node_seen(&n.id)).count(),
                    sits.len(),
                ),
                arcs: (
                    arcs.iter()
                        .filter(|e| overlay.edge_count(&e.id) > 0)
                        .count(),
                    arcs.len(),
                ),
                untaken,
            });
        }
        Coverage {
            dms,
            transitions: overlay.transitions,
            unmatched: overlay.unmatched,
        }
    }

    /// Situations and arcs covered over all DMs.
    pub fn totals(&self) -> ((usize, usize), (usize, usize)) {
        let sum = |f: fn(&DmCoverage) -> (usize, usize)| {
            self.dms
                .iter()
                .map(f)
                .fold((0, 0), |(a, b), (c, d)| (a + c, b + d))
        };
        (sum(|d| d.situations), sum(|d| d.arcs))
    }

    /// The table `sitlogc test --coverage` prints: a line per DM, the
    /// totals, then every arc never taken with where it is written.
    pub fn table(&self) -> String {
        let pct = |(a, b): (usize, usize)| -> String {
            match b {
                0 => "  -".to_owned(),
                _ => format!("{:3}%", a * 100 / b),
            }
        };
        let cell = |(a, b): (usize, usize)| format!("{a:>3}/{b:<3} {}", pct((a, b)));
        let short = |name: &str| sitlog_graph::shorten(name, 40);
        let width = self
            .dms
            .iter()
            .map(|d| short(&d.name).chars().count())
            .max()
            .unwrap_or(2)
            .max("total".len());
        let mut s = format!(
            "{:<width$}  {:<13} {:<13} file\n",
            "DM", "situations", "arcs"
        );
        for d in &self.dms {
            let file = d
                .location
                .rsplitn(3, ':')
                .nth(2)
                .unwrap_or(&d.location)
                .to_owned();
            s.push_str(&format!(
                "{:<width$}  {:<13} {:<13} {file}\n",
                short(&d.name),
                cell(d.situations),
                cell(d.arcs)
            ));
        }
        let (sits, arcs) = self.totals();
        s.push_str(&format!(
            "{:<width$}  {:<13} {:<13}\n",
            "total",
            cell(sits),
            cell(arcs)
        ));
        let untaken: Vec<_> = self.dms.iter().flat_map(|d| &d.untaken).collect();
        if !untaken.is_empty() {
            s.push_str(&format!("\narcs never taken ({}):\n", untaken.len()));
            for (location, from, label) in untaken {
                s.push_str(&format!(
                    "  {location}  {from}: {}\n",
                    sitlog_graph::shorten(label, 70)
                ));
            }
        }
        if self.unmatched > 0 {
            s.push_str(&format!(
                "\nnote: {} of {} transitions are not in the program's diagram\n",
                self.unmatched, self.transitions
            ));
        }
        s
    }

    /// The JSON form (`--format json`): per DM its situations and arcs
    /// covered and the arcs never taken.
    pub fn to_json(&self) -> serde_json::Value {
        let pair = |(a, b): (usize, usize)| serde_json::json!({"covered": a, "total": b});
        let (sits, arcs) = self.totals();
        serde_json::json!({
            "dms": self.dms.iter().map(|d| serde_json::json!({
                "dm": d.name,
                "location": d.location,
                "situations": pair(d.situations),
                "arcs": pair(d.arcs),
                "untaken": d.untaken.iter().map(|(l, f, a)| serde_json::json!({
                    "location": l, "from": f, "arc": a
                })).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
            "situations": pair(sits),
            "arcs": pair(arcs),
        })
    }
}
