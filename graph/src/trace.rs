//! A recorded run (`sitlogc run --trace FILE`: one JSON object per
//! transition, with `dm`, `situation`, `expectation`, `depth` and `next`)
//! laid over a diagram: how often each situation was visited and each
//! arc taken.
//!
//! A trace names situations by their instantiated ids (`look([b],[])`):
//! a situation matches by its id as written, else by its principal functor
//! (of several instances of one id, the first whose id as written the
//! recorded one may fit, else the first).

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
    /// Drawn as coverage (`sitlogc graph --coverage`): arcs never taken
    /// red and dashed, situations never visited with a red outline,
    /// instead of faded.
    pub coverage: bool,
}

impl Overlay {
    pub fn node_count(&self, id: &str) -> u64 {
        self.nodes.get(id).copied().unwrap_or(0)
    }
    pub fn edge_count(&self, id: &str) -> u64 {
        self.edges.get(id).copied().unwrap_or(0)
    }
    /// Whether node `id` was visited.
    pub fn node_seen(&self, id: &str) -> bool {
        self.node_count(id) > 0
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
    let mut same = sits.filter(|n| n.functor.as_deref() == Some(f.as_str()));
    let first = same.clone().next();
    // of several instances of one id, the first the recorded id may fit
    same.find(|n| may_match(&n.label, id)).or(first)
}

/// A term as written by `writeq`, enough to tell whether a recorded value
/// may have met an expectation.
#[derive(Debug, PartialEq)]
enum T {
    /// A variable, or something computed when the arc is taken.
    Any,
    Atom(String),
    Compound(String, Vec<T>),
}

struct Reader<'a> {
    s: &'a [u8],
    i: usize,
}

impl Reader<'_> {
    fn ws(&mut self) {
        while self.i < self.s.len() && self.s[self.i].is_ascii_whitespace() {
            self.i += 1;
        }
    }
    fn peek(&mut self) -> Option<u8> {
        self.ws();
        self.s.get(self.i).copied()
    }
    fn eat(&mut self, c: u8) -> Option<()> {
        (self.peek()? == c).then(|| self.i += 1)
    }
    fn name(&mut self) -> Option<String> {
        let c = self.peek()?;
        let start = self.i;
        if c == b'\'' {
            self.i += 1;
            while self.i < self.s.len() {
                match self.s[self.i] {
                    b'\\' => self.i += 2,
                    b'\'' if self.s.get(self.i + 1) == Some(&b'\'') => self.i += 2,
                    b'\'' => {
                        self.i += 1;
                        return Some(String::from_utf8_lossy(&self.s[start..self.i]).into_owned());
                    }
                    _ => self.i += 1,
                }
            }
            return None;
        }
        while self.i < self.s.len()
            && (self.s[self.i].is_ascii_alphanumeric()
                || self.s[self.i] == b'_'
                || self.s[self.i] == b'.'
                || self.s[self.i] >= 0x80)
        {
            self.i += 1;
        }
        (self.i > start).then(|| String::from_utf8_lossy(&self.s[start..self.i]).into_owned())
    }
    fn term(&mut self, depth: usize) -> Option<T> {
        if depth > 200 {
            return None;
        }
        match self.peek()? {
            b'[' => {
                self.i += 1;
                let mut items = Vec::new();
                let mut tail = T::Atom("[]".into());
                if self.eat(b']').is_none() {
                    loop {
                        items.push(self.term(depth + 1)?);
                        match self.peek()? {
                            b',' => self.i += 1,
                            b'|' => {
                                self.i += 1;
                                tail = self.term(depth + 1)?;
                                self.eat(b']')?;
                                break;
                            }
                            b']' => {
                                self.i += 1;
                                break;
                            }
                            _ => return None,
                        }
                    }
                }
                Some(
                    items
                        .into_iter()
                        .rev()
                        .fold(tail, |t, h| T::Compound("[|]".into(), vec![h, t])),
                )
            }
            c if c.is_ascii_uppercase() || c == b'_' => {
                self.name()?;
                Some(T::Any)
            }
            _ => {
                let name = self.name()?;
                if self.s.get(self.i) != Some(&b'(') {
                    return Some(T::Atom(name));
                }
                self.i += 1;
                let mut args = Vec::new();
                loop {
                    args.push(self.term(depth + 1)?);
                    match self.peek()? {
                        b',' => self.i += 1,
                        b')' => {
                            self.i += 1;
                            break;
                        }
                        _ => return None,
                    }
                }
                if matches!(name.as_str(), "apply" | "get" | "set" | "inc") && args.len() == 2 {
                    return Some(T::Any);
                }
                Some(T::Compound(name, args))
            }
        }
    }
}

fn read_term(text: &str) -> Option<T> {
    let mut r = Reader {
        s: text.as_bytes(),
        i: 0,
    };
    let t = r.term(0)?;
    r.ws();
    (r.i == r.s.len()).then_some(t)
}

fn matches(p: &T, v: &T) -> bool {
    match (p, v) {
        (T::Any, _) | (_, T::Any) => true,
        (T::Atom(a), T::Atom(b)) => a == b || a.trim_matches('\'') == b.trim_matches('\''),
        (T::Compound(f, xs), T::Compound(g, ys)) => {
            f == g && xs.len() == ys.len() && xs.iter().zip(ys).all(|(x, y)| matches(x, y))
        }
        _ => false,
    }
}

/// Whether a recorded `value` may have met the expectation `pattern`
/// (both as `writeq` writes them; variables and computed parts match
/// anything; text this reader does not follow, operators for instance,
/// matches too).
pub fn may_match(pattern: &str, value: &str) -> bool {
    match (read_term(pattern), read_term(value)) {
        (Some(p), Some(v)) => matches(&p, &v),
        _ => true,
    }
}

/// The edges from situation `from` to situation `to`, through function dots
/// and disjunctions: the shortest such chain whose arc's expectation may
/// have met `expectation` (any arc when none may have).
pub fn chain(dm: &DmGraph, from: &str, to: &str, expectation: Option<&str>) -> Option<Vec<String>> {
    let kind: HashMap<&str, NodeKind> = dm.nodes.iter().map(|n| (n.id.as_str(), n.kind)).collect();
    let first_ok = |e: &crate::Edge| match (&e.expectation, expectation) {
        (Some(p), Some(v)) => may_match(p, v),
        _ => true,
    };
    let any_ok = dm.edges.iter().any(|e| e.from == from && first_ok(e));
    let mut best: Option<Vec<String>> = None;
    let mut stack: Vec<(String, Vec<String>)> = vec![(from.to_owned(), Vec::new())];
    while let Some((at, path)) = stack.pop() {
        if path.len() > 8 {
            continue;
        }
        for e in dm.edges.iter().filter(|e| e.from == at).rev() {
            if path.is_empty() && any_ok && !first_ok(e) {
                continue;
            }
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
        let e = dm.edges.iter().find(|e| {
            e.from == from && kind.get(e.to.as_str()) != Some(&NodeKind::Situation) && first_ok(e)
        })?;
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
        // An input that met no expectation is not a transition.
        if v.get("unmatched").is_some() {
            continue;
        }
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
                if let Some(edges) = chain(g, &n.id, &t.id, field("expectation")) {
                    for id in edges {
                        // the dots and disjunctions passed through count as visited
                        if let Some(e) = g.edges.iter().find(|e| e.id == id) {
                            if e.to != t.id {
                                *o.nodes.entry(e.to.clone()).or_default() += 1;
                            }
                        }
                        *o.edges.entry(id).or_default() += 1;
                    }
                }
            }
        }
    }
    Ok(o)
}
