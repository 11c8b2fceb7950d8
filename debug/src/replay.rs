//! `sitlogc replay`: a `--trace` recording (one JSON object per transition:
//! `dm`, `situation`, `expectation`, `action`, `depth`, `next`; one per
//! input that met no expectation: `dm`, `situation`, `unmatched`, `depth`)
//! walked forwards and backwards with the debugger's commands, without
//! running anything; and the first difference of two recordings, inputs
//! that met no expectation included.

use crate::command::{self, Command, CommandSource, Line, Spec, PROMPT};
use crate::record::{self, Record, Unmatched};
use std::fmt::Write as _;
use std::io::Write;
use std::path::Path;

/// A recording, read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Trace {
    /// The file's name, for messages.
    pub name: String,
    pub records: Vec<Record>,
    /// The file's line of each record (1-based).
    pub lines: Vec<usize>,
    /// The inputs that met no expectation, in order.
    pub unmatched: Vec<Unmatched>,
    /// The file's line of each of them.
    pub unmatched_lines: Vec<usize>,
}

impl Trace {
    /// Reads a trace file; `Err` is `FILE:LINE[:COL]: error: ...`.
    pub fn read(path: &Path) -> Result<Trace, String> {
        let name = path.display().to_string();
        let bytes = sitlog_syntax::read_file(path)
            .map_err(|e| format!("error: cannot read trace {name}: {e}"))?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let at = e.utf8_error().valid_up_to();
            let before = &e.as_bytes()[..at];
            let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
            let col = at
                - before
                    .iter()
                    .rposition(|&b| b == b'\n')
                    .map_or(0, |p| p + 1)
                + 1;
            format!("{name}:{line}:{col}: error: the trace is not UTF-8 text")
        })?;
        Trace::parse(&name, &text)
    }

    /// Reads a trace's text; `name` names it in errors.
    pub fn parse(name: &str, text: &str) -> Result<Trace, String> {
        let mut trace = Trace {
            name: name.to_owned(),
            records: Vec::new(),
            lines: Vec::new(),
            unmatched: Vec::new(),
            unmatched_lines: Vec::new(),
        };
        for (i, line) in text.lines().enumerate() {
            let n = i + 1;
            if line.trim().is_empty() {
                continue;
            }
            let value: serde_json::Value = serde_json::from_str(line).map_err(|e| {
                // serde's message without its own " at line 1 column C".
                let message = e.to_string();
                let message = match message.rfind(" at line ") {
                    Some(i) => message[..i].to_owned(),
                    None => message,
                };
                format!(
                    "{name}:{n}:{}: error: not a JSON object: {message}",
                    e.column().max(1)
                )
            })?;
            let Some(object) = value.as_object() else {
                return Err(format!(
                    "{name}:{n}: error: a trace line is one JSON object, not `{}`",
                    short(line)
                ));
            };
            let text = |key: &str| -> Result<String, String> {
                match object.get(key) {
                    Some(serde_json::Value::String(s)) => Ok(s.clone()),
                    Some(other) => Err(format!(
                        "{name}:{n}: error: \"{key}\" must be a string, not `{}`",
                        short(&other.to_string())
                    )),
                    None => Err(format!(
                        "{name}:{n}: error: a trace entry needs \"{key}\" (a string)"
                    )),
                }
            };
            let depth = match object.get("depth") {
                Some(d) => d.as_u64().ok_or_else(|| {
                    format!(
                        "{name}:{n}: error: \"depth\" must be a whole number, not `{}`",
                        short(&d.to_string())
                    )
                })?,
                None => {
                    return Err(format!(
                        "{name}:{n}: error: a trace entry needs \"depth\" (a whole number)"
                    ))
                }
            };
            if object.contains_key("unmatched") {
                trace.unmatched.push(Unmatched {
                    dm: text("dm")?,
                    situation: text("situation")?,
                    input: text("unmatched")?,
                    depth: usize::try_from(depth).unwrap_or(usize::MAX),
                    before: trace.records.len(),
                });
                trace.unmatched_lines.push(n);
                continue;
            }
            let next = match object.get("next") {
                None | Some(serde_json::Value::Null) => None,
                Some(serde_json::Value::String(s)) => Some(s.clone()),
                Some(other) => {
                    return Err(format!(
                        "{name}:{n}: error: \"next\" must be a string or null, not `{}`",
                        short(&other.to_string())
                    ))
                }
            };
            trace.records.push(Record {
                dm: text("dm")?,
                situation: text("situation")?,
                expectation: text("expectation")?,
                action: text("action")?,
                depth: usize::try_from(depth).unwrap_or(usize::MAX),
                next,
            });
            trace.lines.push(n);
        }
        Ok(trace)
    }

    /// The DM stack after transition `at` (1-based), innermost first: each
    /// frame's DM and what it is doing. Callers are read from the
    /// recording's later transitions (a recursive situation is recorded
    /// when its embedded DM has ended).
    pub fn stack(&self, at: usize) -> Vec<String> {
        let Some(r) = at.checked_sub(1).and_then(|i| self.records.get(i)) else {
            return Vec::new();
        };
        let mut frames = vec![format!("#{} {}  after {}", r.depth, r.dm, r.situation)];
        for k in (0..r.depth).rev() {
            if frames.len() == STACK_SHOWN {
                frames.push(format!("... {} frames more, down to #0", k + 1));
                break;
            }
            let later = self.records[at..].iter().find(|p| p.depth <= k);
            let frame = match later {
                Some(p) if p.depth == k => format!("#{k} {}  in {}", p.dm, p.situation),
                _ => match self.records[..at - 1].iter().rev().find(|p| p.depth == k) {
                    Some(p) => format!("#{k} {}  after {}", p.dm, p.situation),
                    None => format!("#{k} (not in the recording)"),
                },
            };
            frames.push(frame);
        }
        frames
    }
}

/// Frames `stack` lists at most (a deep recursion has millions).
pub const STACK_SHOWN: usize = 100;

fn short(text: &str) -> String {
    let mut s: String = text.chars().take(60).collect();
    if s.len() < text.len() {
        s.push_str("...");
    }
    s
}

/// One line of a recording: a transition (its index) or an input that
/// met no expectation (its index), in the file's order.
#[derive(Clone, Copy)]
enum Event {
    Transition(usize),
    Input(usize),
}

impl Trace {
    fn events(&self) -> Vec<Event> {
        let mut out = Vec::with_capacity(self.records.len() + self.unmatched.len());
        let mut inputs = self.unmatched.iter().enumerate().peekable();
        for i in 0..=self.records.len() {
            while let Some((j, _)) = inputs.next_if(|(_, u)| u.before == i) {
                out.push(Event::Input(j));
            }
            if i < self.records.len() {
                out.push(Event::Transition(i));
            }
        }
        out
    }

    fn same_event(&self, x: Event, other: &Trace, y: Event) -> bool {
        match (x, y) {
            (Event::Transition(i), Event::Transition(j)) => self.records[i] == other.records[j],
            (Event::Input(i), Event::Input(j)) => self.unmatched[i].same(&other.unmatched[j]),
            _ => false,
        }
    }
}

/// The first difference of two recordings, with context; `None` when they
/// are the same. An input that met no expectation in one and not the
/// other is a difference, before the transition that follows it.
pub fn diff(a: &Trace, b: &Trace) -> Option<String> {
    let (ea, eb) = (a.events(), b.events());
    let k = ea
        .iter()
        .zip(&eb)
        .take_while(|(&x, &y)| a.same_event(x, b, y))
        .count();
    if k == ea.len() && k == eb.len() {
        return None;
    }
    let same = ea[..k]
        .iter()
        .filter(|e| matches!(e, Event::Transition(_)))
        .count();
    let input_differs = [ea.get(k), eb.get(k)]
        .iter()
        .any(|e| matches!(e, Some(Event::Input(_))));
    let mut out = String::new();
    if input_differs {
        let _ = writeln!(
            out,
            "the recordings differ before transition #{}: an input met no expectation (the {same} transitions before are the same)",
            same + 1
        );
    } else {
        let _ = writeln!(
            out,
            "the recordings differ at transition #{} (the {same} before are the same)",
            same + 1
        );
    }
    let from = same.saturating_sub(3);
    for (i, r) in a.records.iter().enumerate().take(same).skip(from) {
        let _ = writeln!(out, "  {}", record::numbered(i + 1, r));
    }
    for (t, e) in [(a, ea.get(k)), (b, eb.get(k))] {
        match e {
            Some(&Event::Transition(i)) => {
                let _ = writeln!(
                    out,
                    "{}:{}:\n  {}",
                    t.name,
                    t.lines[i],
                    record::numbered(i + 1, &t.records[i])
                );
            }
            Some(&Event::Input(j)) => {
                let _ = writeln!(
                    out,
                    "{}:{}:\n  {}",
                    t.name,
                    t.unmatched_lines[j],
                    record::unnumbered(&t.unmatched[j])
                );
            }
            None => {
                let _ = writeln!(
                    out,
                    "{}: ends after {} transitions",
                    t.name,
                    t.records.len()
                );
            }
        }
    }
    Some(out)
}

/// A replay session: a position in the recording (0: before the first
/// transition; N: after transition N).
struct Replay<'a> {
    trace: &'a Trace,
    at: usize,
    breaks: Vec<(usize, Spec)>,
    next_break: usize,
    out: &'a mut dyn Write,
}

macro_rules! say {
    ($r:expr, $($arg:tt)*) => {{
        let _ = writeln!($r.out, $($arg)*);
    }};
}

impl Replay<'_> {
    fn show(&mut self) {
        match self.at {
            0 => say!(self, "at the start (no transition yet)"),
            n => {
                // The inputs that met no expectation on the way here.
                for u in self.trace.unmatched.iter().filter(|u| u.before == n - 1) {
                    say!(self, "{}", record::unnumbered(u));
                }
                let line = record::numbered(n, &self.trace.records[n - 1]);
                say!(self, "{line}");
            }
        }
        if self.at == self.trace.records.len() {
            for u in self.trace.unmatched.iter().filter(|u| u.before == self.at) {
                say!(self, "{}", record::unnumbered(u));
            }
        }
    }

    /// The inputs that met no expectation up to the current position.
    fn inputs_so_far(&self) -> &[Unmatched] {
        let u = &self.trace.unmatched;
        if self.at == self.trace.records.len() {
            u
        } else {
            &u[..u.partition_point(|u| u.before < self.at)]
        }
    }

    /// Moves forwards to the first transition after the current one for
    /// which `stop` holds (or a breakpoint), else to the end.
    fn forward(&mut self, stop: impl Fn(&Record) -> bool) {
        let records = &self.trace.records;
        if self.at >= records.len() {
            say!(
                self,
                "at the end of the recording ({} transitions)",
                records.len()
            );
            return;
        }
        let mut i = self.at;
        while i < records.len() {
            let r = &records[i];
            i += 1;
            if let Some(n) = self.hit(i) {
                self.at = i;
                let spec = self.breaks.iter().find(|b| b.0 == n).map(|b| b.1.clone());
                if let Some(spec) = spec {
                    say!(self, "-- breakpoint {n} ({spec})");
                }
                self.show();
                return;
            }
            if stop(r) {
                self.at = i;
                self.show();
                return;
            }
        }
        self.at = records.len();
        self.show();
        say!(
            self,
            "-- end of the recording ({} transitions)",
            records.len()
        );
    }

    /// The breakpoint transition `n` (1-based) hits.
    fn hit(&self, n: usize) -> Option<usize> {
        let records = &self.trace.records;
        let r = &records[n - 1];
        self.breaks.iter().find_map(|(id, spec)| {
            let hit = record::hits(spec, &records[..n - 1], r);
            hit.then_some(*id)
        })
    }

    fn depth(&self) -> Option<usize> {
        self.at.checked_sub(1).map(|i| self.trace.records[i].depth)
    }

    /// Runs one command; `false` after `quit`.
    fn run(&mut self, command: Command) -> bool {
        match command {
            Command::Step => self.forward(|_| true),
            Command::Next => match self.depth() {
                Some(d) => self.forward(|r| r.depth <= d),
                None => self.forward(|_| true),
            },
            Command::Finish => match self.depth() {
                Some(d) => self.forward(|r| r.depth < d),
                None => self.forward(|_| true),
            },
            Command::Continue => self.forward(|_| false),
            Command::Back => {
                if self.at == 0 {
                    say!(self, "at the start already");
                } else {
                    self.at -= 1;
                    self.show();
                }
            }
            Command::Goto(n) if n <= self.trace.records.len() => {
                self.at = n;
                self.show();
            }
            Command::Goto(n) => say!(
                self,
                "there is no transition {n}: the recording has {}",
                self.trace.records.len()
            ),
            Command::Stack => {
                let frames = self.trace.stack(self.at);
                if frames.is_empty() {
                    say!(self, "no DM has made a transition yet");
                }
                for f in frames {
                    say!(self, "{f}");
                }
            }
            Command::History(n) => {
                let text = record::history_with(
                    0,
                    &self.trace.records[..self.at],
                    self.inputs_so_far(),
                    n.unwrap_or(10),
                );
                let _ = write!(self.out, "{text}");
            }
            Command::Break(None) => {
                if self.breaks.is_empty() {
                    say!(self, "no breakpoints");
                }
                for (n, spec) in &self.breaks {
                    let _ = writeln!(self.out, "{n}: {spec}");
                }
            }
            Command::Break(Some(Spec::Error)) => {
                say!(
                    self,
                    "a recording has no errors to stop at: the last transition is where the run stopped"
                )
            }
            Command::Break(Some(spec)) => {
                // the names the recording has: a breakpoint elsewhere never stops
                let mut names: Vec<(String, Vec<String>)> = Vec::new();
                for r in &self.trace.records {
                    let dm = crate::record::name_of(&r.dm).to_owned();
                    let i = match names.iter().position(|(n, _)| *n == dm) {
                        Some(i) => i,
                        None => {
                            names.push((dm, Vec::new()));
                            names.len() - 1
                        }
                    };
                    let sit = crate::record::name_of(&r.situation).to_owned();
                    if !names[i].1.contains(&sit) {
                        names[i].1.push(sit);
                    }
                }
                if let Some(problem) = crate::record::unknown_name(&names, &spec) {
                    say!(self, "{problem} in this recording: no breakpoint set");
                    return true;
                }
                self.next_break += 1;
                say!(self, "breakpoint {}: {spec}", self.next_break);
                self.breaks.push((self.next_break, spec));
            }
            Command::Delete(n) => match self.breaks.iter().position(|b| b.0 == n) {
                Some(i) => {
                    let (_, spec) = self.breaks.remove(i);
                    say!(self, "deleted breakpoint {n}: {spec}");
                }
                None => say!(self, "there is no breakpoint {n}"),
            },
            Command::Diff(path) => match Trace::read(&path) {
                Ok(other) => {
                    let text = diff(self.trace, &other).unwrap_or_else(|| {
                        format!(
                            "the recordings are the same ({} transitions)\n",
                            self.trace.records.len()
                        )
                    });
                    let _ = write!(self.out, "{text}");
                }
                Err(e) => say!(self, "{e}"),
            },
            Command::Pipe | Command::Vars(_) | Command::Print(_) => say!(
                self,
                "a trace records transitions only (no pipe or variables): use `sitlogc debug` for them"
            ),
            Command::Input(_) => say!(self, "a replay takes no input"),
            Command::World => say!(self, "a trace does not record the world"),
            Command::Help => {
                let _ = write!(self.out, "{}", command::HELP);
            }
            Command::Quit => return false,
        }
        true
    }
}

/// `sitlogc replay TRACE`: the REPL over `trace`, reading `commands`.
/// The exit status: 0, or 2 for a bad line in a commands file (reported on `err`).
pub fn replay(
    trace: &Trace,
    mut commands: CommandSource,
    out: &mut dyn Write,
    err: &mut dyn Write,
) -> u8 {
    let _ = writeln!(
        out,
        "replay of {}: {} transitions (`help` lists the commands)",
        trace.name,
        trace.records.len()
    );
    let mut replay = Replay {
        trace,
        at: 0,
        breaks: Vec::new(),
        next_break: 0,
        out,
    };
    loop {
        let (text, line) = match commands.read(PROMPT, replay.out) {
            Line::Text(t, n) => (t, n),
            Line::End => return 0,
        };
        match command::parse(&text) {
            Ok(Some(c)) => {
                if !replay.run(c) {
                    return 0;
                }
            }
            Ok(None) => {}
            Err(e) => match (commands.file_name(), line) {
                (Some(name), Some(n)) => {
                    let _ = writeln!(err, "{name}:{n}: error: {e}");
                    return 2;
                }
                _ => say!(replay, "error: {e}"),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: &str = r#"{"dm":"main","situation":"s","expectation":"x","action":"empty","depth":0,"next":"t"}
{"dm":"main","situation":"t","expectation":"empty","action":"empty","depth":0,"next":null}
"#;

    #[test]
    fn reads_and_rejects() {
        let t = Trace::parse("t.jsonl", T).unwrap();
        assert_eq!(t.records.len(), 2);
        assert_eq!(t.records[1].next, None);
        let e = Trace::parse("t.jsonl", "\n{\"dm\": 1").unwrap_err();
        assert!(e.starts_with("t.jsonl:2:"), "{e}");
        let e = Trace::parse("t.jsonl", "[1]").unwrap_err();
        assert!(
            e.contains("t.jsonl:1: error: a trace line is one JSON object"),
            "{e}"
        );
        let e = Trace::parse(
            "t.jsonl",
            r#"{"dm":"m","situation":"s","expectation":"x","action":"a","depth":-1}"#,
        )
        .unwrap_err();
        assert!(e.contains("\"depth\" must be a whole number"), "{e}");
    }

    #[test]
    fn a_deep_stack_is_cut() {
        let t = Trace::parse(
            "t.jsonl",
            r#"{"dm":"m","situation":"s","expectation":"x","action":"a","depth":18446744073709551615,"next":null}"#,
        )
        .unwrap();
        let frames = t.stack(1);
        assert_eq!(frames.len(), STACK_SHOWN + 1);
        assert!(frames[STACK_SHOWN].starts_with("... "), "{frames:?}");
    }

    #[test]
    fn diff_finds_the_first_difference() {
        let a = Trace::parse("a", T).unwrap();
        assert_eq!(diff(&a, &a), None);
        let b = Trace::parse("b", &T.replace("\"x\"", "\"y\"")).unwrap();
        let d = diff(&a, &b).unwrap();
        assert!(
            d.starts_with("the recordings differ at transition #1"),
            "{d}"
        );
        let c = Trace::parse("c", T.lines().next().unwrap()).unwrap();
        assert!(diff(&a, &c)
            .unwrap()
            .contains("c: ends after 1 transitions"));
    }
}

#[cfg(test)]
mod props {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Any text is a trace or an error naming the file and a line: never a panic.
        #[test]
        fn any_text_reads_or_names_a_line(text in "\\PC{0,200}") {
            if let Err(e) = Trace::parse("t.jsonl", &text) {
                prop_assert!(e.starts_with("t.jsonl:"), "{}", e);
            }
        }

        /// JSON-like lines with fields missing or of the wrong kind.
        #[test]
        fn trace_like_lines(
            fields in prop::collection::vec(
                (prop::sample::select(vec!["dm", "situation", "expectation", "action", "depth", "next"]),
                 prop::sample::select(vec!["\"a\"", "0", "-1", "null", "[1]", "1.5", "{}"])),
                0..7),
        ) {
            let body: Vec<String> = fields.iter().map(|(k, v)| format!("\"{k}\":{v}")).collect();
            let line = format!("{{{}}}", body.join(","));
            match Trace::parse("t.jsonl", &line) {
                Ok(t) => prop_assert_eq!(t.records.len(), 1),
                Err(e) => prop_assert!(e.starts_with("t.jsonl:1"), "{}", e),
            }
        }
    }
}
