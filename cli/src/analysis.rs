//! Editor analysis for `sitlogc lsp`: the diagnostics of the program a
//! file belongs to, where a name is defined, what it is. It runs the same
//! loader and checker as `sitlogc check` (with the editor's unsaved texts
//! standing in for files, [`sitlog_compiler::load::with_overlay`]), so an editor
//! shows exactly what `check` says. Positions are the protocol's: 0-based
//! lines, UTF-16 columns.

use sitlog_compiler::ast::Program;
use sitlog_compiler::diag::Severity;
use sitlog_compiler::load;
use sitlog_lsp::{offset_of, position_of, Analyzer, Diag, Overlay, Pos, Range};
use sitlog_syntax::Span;
use std::path::{Path, PathBuf};

/// The analyzer of `sitlogc lsp`.
pub struct Analysis;

/// The program a file belongs to: the nearest directory at or above it
/// that is an application (a `models` file or a `*.dm` in it, the file
/// itself counted even when it is not saved yet), else the file alone.
pub fn program_root(file: &Path) -> PathBuf {
    let is_dm = file.extension().is_some_and(|e| e == "dm");
    for dir in file.ancestors().skip(1) {
        if dir.as_os_str().is_empty() {
            break;
        }
        let own_dir = is_dm && Some(dir) == file.parent() && dir.is_dir();
        if own_dir || load::is_application(dir).unwrap_or(false) {
            return dir.to_path_buf();
        }
    }
    file.to_path_buf()
}

fn same(a: &Path, b: &Path) -> bool {
    let abs =
        |p: &Path| load::normalize(&std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf()));
    abs(a) == abs(b)
}

/// Loads and checks the program of `file`: the program (checked or not)
/// and its diagnostics. The editor's text counts whether or not the file
/// is on disk; an `untitled:` document is a DM file alone, with no
/// directory and so no side files.
fn analyse(
    file: &Path,
    overlay: &Overlay,
) -> Result<(Program, Vec<sitlog_compiler::diag::Diagnostic>), String> {
    let (program, diags) = if sitlog_lsp::is_untitled(file) {
        let text = overlay.get(file).map_or("", String::as_str);
        let name = file.to_string_lossy();
        let (mut program, diags) = load::load_sources(&[(&name, text)]);
        program.single_file = true;
        (program, diags)
    } else {
        let root = program_root(file);
        load::with_overlay(overlay, || {
            load::load_with(&root, crate::library::library())
        })
        .map_err(|e| e.to_string())?
    };
    let options = sitlog_compiler::check::CheckOptions {
        world_functions: sitlog_robot::WORLD_FUNCTIONS,
        ..Default::default()
    };
    let (result, diags) = sitlog_compiler::check::check_opts(program, diags, options);
    let program = match result {
        Ok(c) => c.into_program(),
        Err(p) => p,
    };
    Ok((program, diags))
}

fn range_of(text: &str, span: Span) -> Range {
    Range {
        start: position_of(text, span.start as usize),
        end: position_of(text, (span.end as usize).max(span.start as usize)),
    }
}

/// The atom-like word at a byte offset, with its span.
fn word_at(text: &str, offset: usize) -> Option<(String, usize)> {
    let is_word = |c: char| c.is_alphanumeric() || c == '_';
    let mut start = offset.min(text.len());
    while !text.is_char_boundary(start) {
        start -= 1;
    }
    // The cursor may sit just after the word.
    if !text[start..].starts_with(is_word) && start > 0 {
        let prev = text[..start].char_indices().last()?;
        if is_word(prev.1) {
            start = prev.0;
        }
    }
    while let Some((i, c)) = text[..start].char_indices().last() {
        if !is_word(c) {
            break;
        }
        start = i;
    }
    let end = text[start..]
        .char_indices()
        .find(|&(_, c)| !is_word(c))
        .map_or(text.len(), |(i, _)| start + i);
    let word = &text[start..end];
    word.starts_with(|c: char| c.is_lowercase())
        .then(|| (word.to_owned(), start))
}

enum Found {
    Dm(usize),
    Situation(usize, usize),
    Global(usize),
    Action(usize),
    Function(usize),
}

fn find(program: &Program, file: &Path, pos: Pos, overlay: &Overlay) -> Option<Found> {
    let fid = program
        .sources
        .files()
        .find(|(_, f)| same(&f.path, file))
        .map(|(id, _)| id)?;
    let text = &program.sources.get(fid).text;
    let _ = overlay;
    let offset = offset_of(text, pos);
    let (word, start) = word_at(text, offset)?;
    let after_embedded = text[..start].trim_end().ends_with("embedded_dm ==>");
    // A situation of the DM the cursor is in, unless the word follows
    // `embedded_dm ==>`.
    if !after_embedded {
        for (d, dm) in program.dms.iter().enumerate() {
            if dm.file != fid
                || !(dm.clause.span.start as usize..=dm.clause.span.end as usize).contains(&offset)
            {
                continue;
            }
            for (s, sit) in dm.situations.iter().enumerate() {
                let Some(id) = sit.id else { continue };
                if dm
                    .clause
                    .terms
                    .functor(id)
                    .is_some_and(|(f, _)| f.as_str() == word)
                {
                    return Some(Found::Situation(d, s));
                }
            }
        }
    }
    if let Some(d) = program.dms.iter().position(|dm| dm.name.as_str() == word) {
        return Some(Found::Dm(d));
    }
    if let Some(g) = program.globals.iter().position(|g| g.name.as_str() == word) {
        return Some(Found::Global(g));
    }
    if let Some(a) = program
        .basic_actions
        .iter()
        .position(|a| a.name.as_str() == word)
    {
        return Some(Found::Action(a));
    }
    program
        .functions
        .iter()
        .position(|f| f.name.as_str() == word)
        .map(Found::Function)
}

/// The `%` comment lines right above byte `offset`.
fn doc_above(text: &str, offset: usize) -> String {
    let mut lines: Vec<&str> = Vec::new();
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    for line in text[..line_start].lines().rev() {
        match line.trim_start().strip_prefix('%') {
            Some(c) => lines.push(c.strip_prefix(' ').unwrap_or(c)),
            None => break,
        }
    }
    lines.reverse();
    lines.join("\n")
}

impl Analyzer for Analysis {
    fn diagnostics(&self, file: &Path, overlay: &Overlay) -> Vec<(PathBuf, Vec<Diag>)> {
        let (program, diags) = match analyse(file, overlay) {
            Ok(r) => r,
            Err(message) => {
                let zero = Pos {
                    line: 0,
                    character: 0,
                };
                return vec![(
                    file.to_path_buf(),
                    vec![Diag {
                        range: Range {
                            start: zero,
                            end: zero,
                        },
                        severity: sitlog_lsp::Severity::Error,
                        code: "E0004".into(),
                        message,
                    }],
                )];
            }
        };
        let mut out: Vec<(PathBuf, Vec<Diag>)> = program
            .sources
            .files()
            .map(|(_, f)| (f.path.clone(), Vec::new()))
            .collect();
        for d in diags {
            let src = program.sources.get(d.loc.file);
            let mut message = d.message.clone();
            if let Some(help) = &d.help {
                message.push_str("\nhelp: ");
                message.push_str(help);
            }
            out[d.loc.file.0 as usize].1.push(Diag {
                range: range_of(&src.text, d.loc.span),
                severity: match d.severity {
                    Severity::Error => sitlog_lsp::Severity::Error,
                    _ => sitlog_lsp::Severity::Warning,
                },
                code: d.code.to_owned(),
                message,
            });
        }
        out
    }

    fn definition(&self, file: &Path, pos: Pos, overlay: &Overlay) -> Option<(PathBuf, Range)> {
        let (program, _) = analyse(file, overlay).ok()?;
        let at = |f: sitlog_compiler::source::FileId, span: Span| {
            let src = program.sources.get(f);
            (src.path.clone(), range_of(&src.text, span))
        };
        Some(match find(&program, file, pos, overlay)? {
            Found::Dm(d) => {
                let dm = &program.dms[d];
                at(dm.file, dm.span_of(dm.head))
            }
            Found::Situation(d, s) => {
                let dm = &program.dms[d];
                let id = program.dms[d].situations[s].id?;
                at(dm.file, dm.span_of(id))
            }
            Found::Global(g) => at(program.globals[g].loc.file, program.globals[g].loc.span),
            Found::Action(a) => at(
                program.basic_actions[a].loc.file,
                program.basic_actions[a].loc.span,
            ),
            Found::Function(f) => at(program.functions[f].loc.file, program.functions[f].loc.span),
        })
    }

    fn hover(&self, file: &Path, pos: Pos, overlay: &Overlay) -> Option<String> {
        let (program, _) = analyse(file, overlay).ok()?;
        let place = |f: sitlog_compiler::source::FileId, span: Span| {
            let src = program.sources.get(f);
            let lc = src.line_col(span.start);
            format!("{}:{}:{}", src.name, lc.line, lc.column)
        };
        Some(match find(&program, file, pos, overlay)? {
            Found::Dm(d) => {
                let dm = &program.dms[d];
                let src = program.sources.get(dm.file);
                let head = src.snippet(dm.span_of(dm.head));
                let doc = doc_above(&src.text, dm.clause.span.start as usize);
                format!(
                    "```prolog\ndiag_mod({head}, ...)\n```\nDM `{}/{}` with {} situations, defined at {}\n\n{doc}",
                    dm.name,
                    dm.arity,
                    dm.situations.len(),
                    place(dm.file, dm.span_of(dm.head))
                )
            }
            Found::Situation(d, s) => {
                let dm = &program.dms[d];
                let sit = &dm.situations[s];
                let src = program.sources.get(dm.file);
                let id = src.snippet(dm.span_of(sit.id?));
                let kind = sit
                    .kind_term
                    .map(|t| src.snippet(dm.span_of(t)))
                    .unwrap_or("?");
                let arcs = sit.arcs.as_ref().map_or(0, |a| a.len());
                format!(
                    "situation `{id}` of type `{kind}` in DM `{}`, {arcs} arc(s), at {}",
                    dm.name,
                    place(dm.file, dm.span_of(sit.id?))
                )
            }
            Found::Global(g) => {
                let gv = &program.globals[g];
                let src = program.sources.get(gv.loc.file);
                format!(
                    "global variable: `{}`, at {}",
                    src.snippet(gv.loc.span),
                    place(gv.loc.file, gv.loc.span)
                )
            }
            Found::Action(a) => {
                let ba = &program.basic_actions[a];
                format!(
                    "basic action `{}`, declared at {}",
                    ba.name,
                    place(ba.loc.file, ba.loc.span)
                )
            }
            Found::Function(f) => {
                let fh = &program.functions[f];
                let src = program.sources.get(fh.loc.file);
                let doc = doc_above(&src.text, fh.loc.span.start as usize);
                format!(
                    "user function `{}/{}` (Prolog), at {}\n\n{doc}",
                    fh.name,
                    fh.arity,
                    place(fh.loc.file, fh.loc.span)
                )
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words() {
        let t = "x ==> listen(N), y";
        assert_eq!(word_at(t, 8).unwrap().0, "listen");
        assert_eq!(word_at(t, 12).unwrap().0, "listen");
        assert_eq!(word_at(t, 13), None); // N: a variable
        assert_eq!(word_at("", 0), None);
        assert_eq!(word_at("é", 1).unwrap().0, "é");
        assert_eq!(word_at("Éx", 2), None);
    }

    #[test]
    fn docs_above() {
        let t = "% one\n% two\ndiag_mod(x, [], []).";
        assert_eq!(doc_above(t, t.find("diag").unwrap()), "one\ntwo");
    }
}
