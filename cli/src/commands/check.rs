//! `sitlogc check`: every problem of applications and DM files (with what
//! `run` would stop on in their world, KB, ROS 2 interface and `sitlog.toml`
//! files, E0007),
//! as text on stderr or JSON lines on stdout; warnings denied by
//! `--deny-warnings` or the application's `sitlog.toml`; and (`--origins`)
//! where the files named by a library name came from.

use crate::args::Format;
use crate::output::color_stderr;
use sitlog_compiler::diag::{self, Diagnostic, Loc, Severity};
use sitlog_compiler::source::SourceMap;
use std::io::Write;
use std::path::{Path, PathBuf};

pub fn check(
    paths: &[PathBuf],
    format: Format,
    deny_warnings: bool,
    quiet: bool,
    legacy: bool,
    origins: bool,
) -> u8 {
    let color = color_stderr();
    let mut errors = 0usize;
    let mut warnings = 0usize;
    // Warnings of applications whose sitlog.toml denies them.
    let mut denied_warnings = 0usize;
    let mut io_failed = false;
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let mut programs = Vec::new();
    for path in paths {
        match sitlog_compiler::load::discover(path) {
            // Nothing to check is a usage error (exit 2, like a missing
            // path): a check that passes on nothing would hide a wrong path.
            Ok(found) if found.is_empty() => {
                sitlog_runtime::errln!(
                    "error: no application or DM file found in {} (an application is a directory with a `models` file or `*.dm` files)",
                    path.display()
                );
                io_failed = true;
            }
            Ok(found) => programs.extend(found),
            Err(e) => {
                sitlog_runtime::errln!("error: cannot read {e}");
                io_failed = true;
            }
        }
    }
    for path in &programs {
        // The application's sitlog.toml may deny its warnings (a bad one
        // is an error; the program is checked all the same).
        let mut config_error = None;
        let denied = match crate::config::read(path) {
            Ok(config) => config.deny_warnings,
            Err((1, message)) => {
                // Bad content: a diagnostic (E0007) at its place, below.
                config_error = Some(message);
                false
            }
            Err((_, message)) => {
                sitlog_runtime::errln!("{message}");
                io_failed = true;
                false
            }
        };
        let options = sitlog_compiler::check::CheckOptions {
            legacy,
            ..Default::default()
        };
        let (result, mut diags) = match crate::output::check_app(path, options) {
            Ok(r) => r,
            Err(e) => {
                sitlog_runtime::errln!("error: cannot read {e}");
                io_failed = true;
                continue;
            }
        };
        let program = match &result {
            Ok(checked) => checked.program(),
            Err(program) => program,
        };
        // The world, KB and ROS 2 interface files, as `run` reads them.
        let (mut asset_sources, mut asset_diags) = match asset_diagnostics(path) {
            Ok(found) => found,
            Err((status, message)) => {
                // Text that is not UTF-8 is an error of the file (1), as in
                // `run`; a file that cannot be read, an I/O problem (2).
                sitlog_runtime::errln!("{message}");
                if status == 1 {
                    errors += 1;
                } else {
                    io_failed = true;
                }
                (SourceMap::new(), Vec::new())
            }
        };
        diags.extend(world_names(path, program));
        if let Some(message) = config_error {
            config_diagnostic(path, message, &mut asset_sources, &mut asset_diags);
        }
        if origins {
            for line in origin_lines(path, program) {
                sitlog_runtime::errln!("{line}");
            }
        }
        let all = diags
            .iter()
            .map(|d| (d, &program.sources))
            .chain(asset_diags.iter().map(|d| (d, &asset_sources)));
        for (d, sources) in all {
            match d.severity {
                Severity::Error => errors += 1,
                Severity::Warning if denied => denied_warnings += 1,
                Severity::Warning => warnings += 1,
            }
            if quiet && d.severity == Severity::Warning && !denied {
                continue;
            }
            match format {
                Format::Human => {
                    sitlog_runtime::errprint!("{}", diag::render_human(d, sources, color))
                }
                Format::Json => {
                    if let Err(e) = writeln!(out, "{}", diag::render_json(d, sources)) {
                        if e.kind() != std::io::ErrorKind::BrokenPipe && !io_failed {
                            sitlog_runtime::errln!(
                                "error: cannot write the diagnostics to stdout: {e}"
                            );
                        }
                        io_failed |= e.kind() != std::io::ErrorKind::BrokenPipe;
                    }
                }
            }
        }
    }
    if let Err(e) = out.flush() {
        if e.kind() != std::io::ErrorKind::BrokenPipe {
            sitlog_runtime::errln!("error: cannot write the diagnostics to stdout: {e}");
            io_failed = true;
        }
    }
    if format == Format::Human {
        sitlog_runtime::errln!(
            "checked {} program(s): {} error(s), {} warning(s){}",
            programs.len(),
            errors,
            warnings + denied_warnings,
            if denied_warnings > 0 {
                format!(" ({denied_warnings} denied by {})", crate::config::FILE)
            } else {
                String::new()
            }
        );
    }
    if io_failed {
        2
    } else if errors > 0 || denied_warnings > 0 || (deny_warnings && warnings > 0) {
        1
    } else {
        0
    }
}

/// The errors a run of the application at `path` would stop on in its
/// `world.toml`, `knowledge.kb` and (with ROS 2) `ros2.toml`, as
/// diagnostics (E0007) over a source map of those files; `Err`: a file that
/// cannot be used, as `run` says it (exit status and message).
fn asset_diagnostics(path: &Path) -> Result<(SourceMap, Vec<Diagnostic>), (u8, String)> {
    let assets = sitlog_robot::Assets::from_app(path).map_err(|e| (e.status, e.message))?;
    Ok(diagnostics_of(&assets))
}

/// [`asset_diagnostics`] of files already read.
fn diagnostics_of(assets: &sitlog_robot::Assets) -> (SourceMap, Vec<Diagnostic>) {
    #[allow(unused_mut)]
    let mut problems = assets.problems();
    #[cfg(feature = "ros2")]
    if let Some(file) = &assets.ros2 {
        let world = assets
            .world
            .as_ref()
            .and_then(|w| sitlog_sim::World::parse(&w.name, &w.text).ok());
        if let Err(message) =
            sitlog_ros::Interface::load(Some((&file.name, &file.text)), world.as_ref())
        {
            // `FILE:LINE:COL: error: ...`, or `FILE: error: ...` without a place.
            let rest = message.strip_prefix(file.name.as_str()).unwrap_or(&message);
            let (line, column, message) = error_position(rest).unwrap_or((
                0,
                0,
                rest.strip_prefix(": error: ").unwrap_or(rest).to_owned(),
            ));
            problems.push(sitlog_robot::AssetError {
                file: file.name.clone(),
                line,
                column,
                message,
            });
        }
    }
    let mut sources = SourceMap::new();
    let mut diags = Vec::new();
    for p in problems {
        let text = [&assets.world, &assets.kb, &assets.ros2]
            .into_iter()
            .flatten()
            .find(|f| f.name == p.file)
            .map(|f| f.text.clone())
            .unwrap_or_default();
        let at = (p.line, p.column, &[',', ']', '}'][..]);
        diags.push(app_file_error(
            &mut sources,
            Path::new(&p.file),
            text,
            at,
            p.message,
        ));
    }
    (sources, diags)
}

/// W0243: the places given to `navigate(Place, Status)` or `move(Place,
/// Status)` by name that the application's `world.toml` does not have (as
/// a place or a shelf, what the simulated robot navigates to), with *did
/// you mean*. The run goes on (`navigate` answers `unknown_place`), so a
/// warning; nothing without a world file or when it has errors (E0007).
fn world_names(path: &Path, program: &sitlog_compiler::ast::Program) -> Vec<Diagnostic> {
    let Ok(assets) = sitlog_robot::Assets::from_app(path) else {
        return Vec::new();
    };
    let Some(world) = assets
        .world
        .as_ref()
        .and_then(|w| sitlog_sim::World::parse(&w.name, &w.text).ok())
    else {
        return Vec::new();
    };
    let known: Vec<&str> = world
        .place_names()
        .into_iter()
        .chain(world.shelf_names())
        .collect();
    let mut out = Vec::new();
    for dm in &program.dms {
        let terms = &dm.clause.terms;
        let mut stack = vec![dm.clause.root];
        while let Some(t) = stack.pop() {
            stack.extend_from_slice(terms.args(t));
            let Some((f, 2)) = terms.functor(t) else {
                continue;
            };
            if !matches!(f.as_str(), "navigate" | "move") {
                continue;
            }
            let place = terms.args(t)[0];
            let Some(name) = terms.atom(place) else {
                continue;
            };
            if known.contains(&name.as_str()) {
                continue;
            }
            let mut d = Diagnostic::warning(
                sitlog_compiler::check::codes::UNKNOWN_WORLD_NAME,
                dm.loc(terms.span(place)),
                format!(
                    "`{name}` is no place or shelf of {}: `{f}` will answer `unknown_place`",
                    world.file_name()
                ),
            )
            .with_label("not in the world");
            d = match sitlog_compiler::suggest::did_you_mean(name.as_str(), known.iter().copied()) {
                Some(similar) => d.with_help(format!("did you mean `{similar}`?")),
                None => d.with_help(format!(
                    "the world's places and shelves: {}",
                    known.join(", ")
                )),
            };
            out.push(d);
        }
    }
    out
}

/// The error of the application's `sitlog.toml` (`message`, as `run`
/// prints it) as a diagnostic E0007 at its place, like those of its world
/// and KB files; the file is added to `sources`.
fn config_diagnostic(
    app: &Path,
    message: String,
    sources: &mut SourceMap,
    diags: &mut Vec<Diagnostic>,
) {
    let path = crate::config::path_of(app);
    let text = sitlog_robot::TextFile::read(&path, "settings")
        .map(|f| f.text)
        .unwrap_or_default();
    let (place, message) = match crate::config::parse_located(&text) {
        Err((place, m)) => (place, m),
        // Not UTF-8 (TextFile's error): its message names the place.
        Ok(_) => (None, message),
    };
    let (line, column) = place.unwrap_or((0, 0));
    let at = (line, column, &['='][..]);
    diags.push(app_file_error(sources, &path, text, at, message));
}

/// Error E0007 in an application file (`text`, added to `sources` as
/// `path`) at `(line, column, stops)`: the span runs from there to the
/// first newline, space or one of `stops` (at least one character).
fn app_file_error(
    sources: &mut SourceMap,
    path: &Path,
    text: String,
    (line, column, stops): (usize, usize, &[char]),
    message: String,
) -> Diagnostic {
    let start = offset(&text, line, column);
    let end = text[start..]
        .find(|c: char| c == '\n' || c == ' ' || stops.contains(&c))
        .map_or(text.len(), |n| start + n.max(1).min(text.len() - start));
    let file = sources.add(path, text);
    let span = sitlog_syntax::Span {
        start: start as u32,
        end: end as u32,
    };
    Diagnostic::error(
        sitlog_compiler::load::codes::APP_FILE,
        Loc { file, span },
        message,
    )
    .with_label("here")
}

/// The line, column and message of `:LINE:COL: error: MESSAGE` (what
/// follows the file's name in sitlog-ros's errors).
#[cfg(feature = "ros2")]
fn error_position(rest: &str) -> Option<(usize, usize, String)> {
    let rest = rest.strip_prefix(':')?;
    let (line, rest) = rest.split_once(':')?;
    let (column, message) = rest.split_once(": error: ")?;
    Some((line.parse().ok()?, column.parse().ok()?, message.to_owned()))
}

/// The byte offset of 1-based `line` and `column` (characters) in `text`;
/// the start for line 0.
fn offset(text: &str, line: usize, column: usize) -> usize {
    if line == 0 {
        return 0;
    }
    let mut start = 0;
    for _ in 1..line {
        match text[start..].find('\n') {
            Some(n) => start += n + 1,
            None => return text.len(),
        }
    }
    text[start..]
        .char_indices()
        .nth(column.saturating_sub(1))
        .map_or(text.len(), |(i, _)| start + i)
}

/// `--origins`: one line per file of `program` named by a library name,
/// saying where it was read from.
fn origin_lines(path: &std::path::Path, program: &sitlog_compiler::ast::Program) -> Vec<String> {
    program
        .library_files
        .iter()
        .map(|f| {
            let shown = &program.sources.get(f.file).name;
            let from = match (&f.root, &f.overrides) {
                (Some(root), _) => format!("from {root} ({shown})"),
                (None, Some(instead)) => {
                    format!("from its own copy {shown} (instead of {instead})")
                }
                (None, None) => format!("from its own copy {shown}"),
            };
            format!("{} uses {} {from}", path.display(), f.name)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use sitlog_robot::{Assets, TextFile};

    /// Pieces shaped like a world file, a KB and a `ros2.toml`.
    const PIECES: &[&str] = &[
        "[robot]",
        "[[place]]",
        "[[shelf]]",
        "[[object]]",
        "[places.k]",
        "[timeouts]",
        "[qos.say]",
        "name",
        "at",
        "on",
        "x",
        "y",
        "answer",
        "depth",
        " = ",
        "\"kitchen\"",
        "\"fridge\"",
        "[1.0, 2.0]",
        "-1",
        "0",
        "3",
        "nan",
        "1e400",
        "class(",
        "objects",
        ",",
        "[",
        "]",
        ")",
        ").",
        "'",
        "\"",
        "#",
        "%",
        " ",
        "\n",
        "é",
        "\u{2028}",
        "\u{a0}",
    ];

    fn file(name: &str, text: Option<String>) -> Option<TextFile> {
        text.map(|text| TextFile {
            name: name.to_owned(),
            text,
        })
    }

    /// Every diagnostic of the three files: a span on character boundaries
    /// of its file, at the line and column `run` gives (when that is inside
    /// the text), rendered in the three forms without a panic.
    fn located(
        world: Option<String>,
        kb: Option<String>,
        ros2: Option<String>,
    ) -> Result<(), TestCaseError> {
        let assets = Assets {
            world: file("world.toml", world),
            kb: file("knowledge.kb", kb),
            ros2: file("ros2.toml", ros2),
            ..Assets::default()
        };
        let (sources, diags) = diagnostics_of(&assets);
        for d in &diags {
            let f = sources.get(d.loc.file);
            let (start, end) = (d.loc.span.start as usize, d.loc.span.end as usize);
            prop_assert!(start <= end && end <= f.text.len(), "{d:?} in {:?}", f.text);
            prop_assert!(
                f.text.is_char_boundary(start) && f.text.is_char_boundary(end),
                "{d:?}"
            );
            diag::render_human(d, &sources, false);
            diag::render_json(d, &sources);
            diag::render_short(d, &sources);
        }
        #[allow(unused_mut)]
        let mut problems = assets.problems();
        #[cfg(feature = "ros2")]
        if let Some(f) = &assets.ros2 {
            let world = assets
                .world
                .as_ref()
                .and_then(|w| sitlog_sim::World::parse(&w.name, &w.text).ok());
            if let Err(e) = sitlog_ros::Interface::load(Some((&f.name, &f.text)), world.as_ref()) {
                if let Some((line, column, message)) = error_position(&e["ros2.toml".len()..]) {
                    problems.push(sitlog_robot::AssetError {
                        file: f.name.clone(),
                        line,
                        column,
                        message,
                    });
                }
            }
        }
        for p in problems {
            let lines: Vec<&str> = [&assets.world, &assets.kb, &assets.ros2]
                .into_iter()
                .flatten()
                .find(|f| f.name == p.file)
                .map(|f| f.text.split('\n').collect())
                .unwrap_or_default();
            let inside = p.line >= 1
                && p.line <= lines.len()
                && p.column <= lines[p.line - 1].chars().count() + 1;
            if !inside {
                continue;
            }
            let at = diags.iter().any(|d| {
                let f = sources.get(d.loc.file);
                let lc = f.line_col(d.loc.span.start);
                f.name == p.file && (lc.line as usize, lc.column as usize) == (p.line, p.column)
            });
            prop_assert!(at, "{p:?} not at its place in {diags:?}");
        }
        Ok(())
    }

    fn text() -> impl Strategy<Value = Option<String>> {
        prop::option::of(prop_oneof![
            any::<String>(),
            prop::collection::vec(prop::sample::select(PIECES), 0..24).prop_map(|p| p.concat()),
        ])
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        #[test]
        fn asset_diagnostics_are_located_and_render(world in text(), kb in text(), ros2 in text()) {
            located(world, kb, ros2)?;
        }
    }
}
