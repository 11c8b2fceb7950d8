//! A recorded run (`sitlogc run --trace FILE`: one JSON object per
//! transition, with `dm`, `situation`, `expectation`, `depth` and `next`)
//! laid over a diagram: how often each situation was visited and each
//! arc taken.
//!
//! A trace names situations by their instantiated ids (`look([b],[])`):
//! a situation matches by its id as written, else by its principal functor
//! (the first such instance; with several instances of one id the count
//! goes to the first).

use crate::{Diagram, DmGraph, NodeKind};
use std::collections::HashMap;

/// Visit and use counts by node and edge id.
#[derive(Clone, Debug, Default)]
pub struct Overlay {
    nodes: HashMap<String, u64>,
    edges: HashMap<String, u64>,
    /// Transitions read.
    pub transitions: usize,
    /// Transitions whose DM or situation is not in the diagram.
    pub unmatched: usize,
}

impl Overlay {
    pub fn node_count(&self, id: &str) -> u64 {
        self.nodes.get(id).copied().unwrap_or(0)
    }
    pub fn edge_count(&self, id: &str) -> u64 {
        self.edges.get(id).copied().unwrap_or(0)
    }
}

/// `name/arity` of a term as written (`look([S|Ss],Seen)` → `look/2`);
/// `None` for a variable or number.
pub fn functor_of(text: &str) -> Option<String> {
    let text = text.trim();
    let first = text.chars().next()?;
    if first.is_ascii_uppercase() || first == '_' || first.is_ascii_digit() {
        return None;
    }
    let (name, rest) = if first == '\'' {
        let mut end = None;
        let mut chars = text.char_indices().skip(1).peekable();
        while let Some((i, c)) = chars.next() {
            if c == '\\' {
                chars.next();
            } else if c == '\'' {
                if matches!(chars.peek(), Some((_, '\''))) {
                    chars.next();
                } else {
                    end = Some(i);
                    break;
                }
            }
        }
        let end = end?;
        (&text[1..end], &text[end + 1..])
    } else {
        let end = text.find('(').unwrap_or(text.len());
        (&text[..end], &text[end..])
    };
    if !rest.starts_with('(') {
        return Some(format!("{name}/0"));
    }
    // count top-level commas
    let (mut depth, mut arity, mut quote) = (0usize, 1usize, false);
    let mut prev = ' ';
    for c in rest.chars() {
        if quote {
            if c == '\'' && prev != '\\' {
                quote = false;
            }
        } else {
            match c {
                '\'' => quote = true,
                '(' | '[' | '{' => depth += 1,
                ')' | ']' | '}' => depth = depth.saturating_sub(1),
                ',' if depth == 1 => arity += 1,
                _ => {}
            }
        }
        prev = c;
    }
    Some(format!("{name}/{arity}"))
}

/// The DM a trace names (by functor name).
pub fn find_dm<'d>(d: &'d Diagram, dm: &str) -> Option<&'d DmGraph> {
    let name =
        |s: &str| functor_of(s).map(|f| f.rsplit_once('/').map(|(n, _)| n.to_owned()).unwrap_or(f));
    let want = name(dm)?;
    d.dms
        .iter()
        .find(|g| name(&g.name).as_deref() == Some(want.as_str()))
}

/// The situation node of `dm` a trace's situation id names.
pub fn find_situation<'d>(dm: &'d DmGraph, id: &str) -> Option<&'d crate::Node> {
    let sits = dm.nodes.iter().filter(|n| n.kind == NodeKind::Situation);
    let compact = |s: &str| s.chars().filter(|c| !c.is_whitespace()).collect::<String>();
    let id_c = compact(id);
    if let Some(n) = sits.clone().find(|n| compact(&n.label) == id_c) {
        return Some(n);
    }
    let f = functor_of(id)?;
    sits.clone()
        .find(|n| n.functor.as_deref() == Some(f.as_str()))
}

/// The edges from situation `from` to situation `to`, through function dots
/// and disjunctions (the first such chain in edge order).
pub fn chain(dm: &DmGraph, from: &str, to: &str) -> Option<Vec<String>> {
    let kind: HashMap<&str, NodeKind> = dm.nodes.iter().map(|n| (n.id.as_str(), n.kind)).collect();
    let mut best: Option<Vec<String>> = None;
    let mut stack: Vec<(String, Vec<String>)> = vec![(from.to_owned(), Vec::new())];
    while let Some((at, path)) = stack.pop() {
        if path.len() > 8 {
            continue;
        }
        for e in dm.edges.iter().filter(|e| e.from == at).rev() {
            let mut p = path.clone();
            p.push(e.id.clone());
            if e.to == to {
                if best
                    .as_ref()
                    .is_none_or(|b| p.len() < b.len() || (p.len() == b.len() && p < *b))
                {
                    best = Some(p.clone());
                }
                continue;
            }
            if kind.get(e.to.as_str()) != Some(&NodeKind::Situation) && !p.contains(&e.to) {
                stack.push((e.to.clone(), p));
            }
        }
    }
    best.or_else(|| {
        // a computed next situation: count the way into the `?`
        let e = dm
            .edges
            .iter()
            .find(|e| e.from == from && kind.get(e.to.as_str()) != Some(&NodeKind::Situation))?;
        Some(vec![e.id.clone()])
    })
}

/// Reads a trace (JSON lines) against a diagram.
pub fn read(d: &Diagram, text: &str) -> Result<Overlay, String> {
    let mut o = Overlay::default();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let v: serde_json::Value = serde_json::from_str(line)
            .map_err(|e| format!("line {}: not a trace entry: {e}", i + 1))?;
        let field = |k: &str| v.get(k).and_then(|x| x.as_str());
        let (Some(dm), Some(sit)) = (field("dm"), field("situation")) else {
            return Err(format!(
                "line {}: a trace entry needs \"dm\" and \"situation\"",
                i + 1
            ));
        };
        o.transitions += 1;
        let Some(g) = find_dm(d, dm) else {
            o.unmatched += 1;
            continue;
        };
        let Some(n) = find_situation(g, sit) else {
            o.unmatched += 1;
            continue;
        };
        *o.nodes.entry(n.id.clone()).or_default() += 1;
        if let Some(next) = field("next") {
            if let Some(t) = find_situation(g, next) {
                if let Some(edges) = chain(g, &n.id, &t.id) {
                    for e in edges {
                        *o.edges.entry(e).or_default() += 1;
                    }
                }
            }
        }
    }
    Ok(o)
}
