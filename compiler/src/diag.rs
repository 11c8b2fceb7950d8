//! Diagnostics: one value (code, severity, message, spans, help) and its
//! renderers: human (ariadne, rustc-like), JSON lines for tools, and a short
//! one-line form for `compile_error!`.

use crate::source::{FileId, LineCol, SourceMap};
use sitlog_syntax::Span;

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    Error,
    Warning,
}

/// A position in a file of the source map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Loc {
    pub file: FileId,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub code: &'static str,
    pub severity: Severity,
    pub message: String,
    pub loc: Loc,
    /// Text under the primary caret.
    pub label: Option<String>,
    /// Secondary positions (e.g. the first definition of a duplicate).
    pub labels: Vec<(Loc, String)>,
    pub help: Option<String>,
}

impl Diagnostic {
    pub fn error(code: &'static str, loc: Loc, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            code,
            severity: Severity::Error,
            message: message.into(),
            loc,
            label: None,
            labels: Vec::new(),
            help: None,
        }
    }
    pub fn warning(code: &'static str, loc: Loc, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(code, loc, message)
        }
    }
    pub fn with_label(mut self, label: impl Into<String>) -> Diagnostic {
        self.label = Some(label.into());
        self
    }
    pub fn with_secondary(mut self, loc: Loc, label: impl Into<String>) -> Diagnostic {
        self.labels.push((loc, label.into()));
        self
    }
    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help = Some(help.into());
        self
    }
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

/// Sorts diagnostics by file and position (stable for equal positions).
pub fn sort(diags: &mut [Diagnostic]) {
    diags.sort_by_key(|d| (d.loc.file, d.loc.span.start, d.loc.span.end));
}

/// Renders a diagnostic for a terminal, rustc-like (ariadne).
pub fn render_human(diag: &Diagnostic, sources: &SourceMap, color: bool) -> String {
    use ariadne::{Config, IndexType, Label, Report, ReportKind};
    let file = sources.get(diag.loc.file);
    let kind = match diag.severity {
        Severity::Error => ReportKind::Error,
        Severity::Warning => ReportKind::Warning,
    };
    let range = clamp(diag.loc.span, &file.text);
    if let Some(text) = long_line(diag, sources, color) {
        return text;
    }
    let mut report = Report::build(kind, (file.name.clone(), range.clone())).with_config(
        Config::default()
            .with_index_type(IndexType::Byte)
            .with_color(color),
    );
    // Run-time errors have no code.
    if !diag.code.is_empty() {
        report = report.with_code(diag.code);
    }
    report = report.with_message(&diag.message);
    let mut primary = Label::new((file.name.clone(), range)).with_order(0);
    if let Some(text) = &diag.label {
        primary = primary.with_message(text);
    }
    report = report.with_label(primary);
    for (i, (loc, text)) in diag.labels.iter().enumerate() {
        let f = sources.get(loc.file);
        report = report.with_label(
            Label::new((f.name.clone(), clamp(loc.span, &f.text)))
                .with_message(text)
                .with_order(i as i32 + 1),
        );
    }
    if let Some(help) = &diag.help {
        report = report.with_help(help);
    }
    let mut files: Vec<(String, String)> = vec![(file.name.clone(), file.text.clone())];
    for (loc, _) in &diag.labels {
        let f = sources.get(loc.file);
        if !files.iter().any(|(n, _)| *n == f.name) {
            files.push((f.name.clone(), f.text.clone()));
        }
    }
    let mut out = Vec::new();
    if report
        .finish()
        .write(ariadne::sources(files), &mut out)
        .is_err()
    {
        return render_short(diag, sources) + "\n";
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Lines longer than this are not quoted (a generated 2 MB line would be
/// printed whole, with as many spaces under it).
const LONG_LINE: usize = 2000;

/// A diagnostic whose labelled lines include one over [`LONG_LINE`]
/// bytes, without the snippet: its header, place and help.
fn long_line(diag: &Diagnostic, sources: &SourceMap, color: bool) -> Option<String> {
    let line_len = |loc: &Loc| {
        let text = &sources.get(loc.file).text;
        let r = clamp(loc.span, text);
        let start = text[..r.start].rfind('\n').map_or(0, |i| i + 1);
        let end = text[r.end..].find('\n').map_or(text.len(), |i| r.end + i);
        // The longest line the span touches.
        text[start..end]
            .split('\n')
            .map(str::len)
            .max()
            .unwrap_or(0)
    };
    let longest = std::iter::once(&diag.loc)
        .chain(diag.labels.iter().map(|(l, _)| l))
        .map(line_len)
        .max()
        .unwrap_or(0);
    if longest <= LONG_LINE {
        return None;
    }
    let file = sources.get(diag.loc.file);
    let pos = file.line_col(diag.loc.span.start);
    let kind = match diag.severity {
        Severity::Error if color => "\x1b[31mError\x1b[0m",
        Severity::Error => "Error",
        Severity::Warning if color => "\x1b[33mWarning\x1b[0m",
        Severity::Warning => "Warning",
    };
    let code = if diag.code.is_empty() {
        String::new()
    } else {
        format!("[{}] ", diag.code)
    };
    let mut out = format!(
        "{code}{kind}: {}\n   ╭─[ {}:{}:{} ]\n   │ (a line of {longest} bytes: not quoted)\n",
        diag.message, file.name, pos.line, pos.column
    );
    if let Some(help) = &diag.help {
        out.push_str(&format!("   │ Help: {help}\n"));
    }
    out.push_str("───╯\n");
    Some(out)
}

/// A span as a byte range of `text` that the renderer can slice: clamped to
/// the text and widened to character boundaries (ariadne slices the text
/// with it and would panic inside a character).
fn clamp(span: Span, text: &str) -> std::ops::Range<usize> {
    let len = text.len();
    let mut start = (span.start as usize).min(len);
    while !text.is_char_boundary(start) {
        start -= 1;
    }
    let mut end = (span.end as usize).clamp(start, len);
    while !text.is_char_boundary(end) {
        end += 1;
    }
    start..end
}

/// One diagnostic as a JSON object (for editors and CI).
pub fn render_json(diag: &Diagnostic, sources: &SourceMap) -> serde_json::Value {
    let file = sources.get(diag.loc.file);
    let start: LineCol = file.line_col(diag.loc.span.start);
    let end: LineCol = file.line_col(diag.loc.span.end);
    let labels: Vec<serde_json::Value> = diag
        .labels
        .iter()
        .map(|(loc, text)| {
            let f = sources.get(loc.file);
            let p = f.line_col(loc.span.start);
            serde_json::json!({"file": f.name, "line": p.line, "column": p.column, "message": text})
        })
        .collect();
    serde_json::json!({
        "code": diag.code,
        "severity": diag.severity,
        "message": diag.message,
        "file": file.name,
        "line": start.line,
        "column": start.column,
        "end": {"line": end.line, "column": end.column},
        "label": diag.label,
        "labels": labels,
        "help": diag.help,
    })
}

/// `file:line:col: error[CODE]: message` plus the source line and a caret:
/// the text the proc-macro puts in `compile_error!`.
pub fn render_short(diag: &Diagnostic, sources: &SourceMap) -> String {
    let file = sources.get(diag.loc.file);
    let pos = file.line_col(diag.loc.span.start);
    let line_text = file
        .text
        .lines()
        .nth(pos.line as usize - 1)
        .unwrap_or("")
        .trim_end();
    let width = file
        .snippet(diag.loc.span)
        .lines()
        .next()
        .map_or(1, |s| s.chars().count().max(1));
    let mut s = format!(
        "{}:{}:{}: {}[{}]: {}\n  | {}\n  | {}{}",
        file.name,
        pos.line,
        pos.column,
        match diag.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        },
        diag.code,
        diag.message,
        line_text,
        " ".repeat(pos.column as usize - 1),
        "^".repeat(width)
    );
    if let Some(help) = &diag.help {
        s.push_str(&format!("\n  = help: {help}"));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::SourceMap;

    /// The renderers accept any span on any text: inside a character, past
    /// the end, reversed (issue 23: ariadne panicked inside a U+FFFD).
    #[test]
    fn any_span_renders() {
        let mut sources = SourceMap::new();
        let text = "dm(é, [\u{FFFD}\u{FFFD} x]).\n% caf\u{FFFD}";
        let file = sources.add(std::path::Path::new("a.dm"), text.to_owned());
        let n = text.len() as u32 + 2;
        for start in 0..n {
            for end in 0..n {
                let d = Diagnostic::error(
                    "E0002",
                    Loc {
                        file,
                        span: Span { start, end },
                    },
                    "m",
                )
                .with_label("l")
                .with_secondary(
                    Loc {
                        file,
                        span: Span {
                            start: end,
                            end: start,
                        },
                    },
                    "s",
                );
                assert!(render_human(&d, &sources, false).contains("E0002"));
                render_json(&d, &sources);
                render_short(&d, &sources);
            }
        }
    }
}
