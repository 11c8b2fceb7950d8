//! An application's settings for `sitlogc`: `sitlog.toml` beside its DMs
//! ([`AppConfig`]). One key for now, `deny-warnings = true`: `check`, `run`
//! and `build` of the application treat its warnings as errors, as
//! `--deny-warnings` does (like `rustc -D warnings`, for an application
//! that wants to stay free of them).
//!
//! Invariant: no file means the defaults; an unknown key, a value of the
//! wrong type or text that is not TOML is an error naming
//! `FILE:LINE:COL`, never ignored.

use std::path::{Path, PathBuf};

/// The settings file of an application directory.
pub const FILE: &str = "sitlog.toml";

/// What `sitlog.toml` sets.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
pub struct AppConfig {
    /// Warnings are errors (`--deny-warnings`).
    #[serde(default)]
    pub deny_warnings: bool,
}

/// The settings file of `app` (an application directory, or the directory
/// of a DM file).
pub fn path_of(app: &Path) -> PathBuf {
    let dir = if app.is_dir() {
        app.to_path_buf()
    } else {
        app.parent().map(Path::to_path_buf).unwrap_or_default()
    };
    dir.join(FILE)
}

/// The settings of `app`: its `sitlog.toml`, or the defaults without one.
/// `Err`: the message (`FILE:LINE:COL: error: ...`) and the exit status
/// (1 for bad content, 2 when the file cannot be read).
pub fn read(app: &Path) -> Result<AppConfig, (u8, String)> {
    let path = path_of(app);
    if !path.is_file() {
        return Ok(AppConfig::default());
    }
    let file =
        sitlog_robot::TextFile::read(&path, "settings").map_err(|e| (e.status, e.message))?;
    parse(&file.name, &file.text).map_err(|m| (1, m))
}

/// `text`, a `sitlog.toml` named `name`, read.
pub fn parse(name: &str, text: &str) -> Result<AppConfig, String> {
    parse_located(text).map_err(|(place, message)| match place {
        Some((line, column)) => format!("{name}:{line}:{column}: error: {message}"),
        None => format!("{name}: error: {message}"),
    })
}

/// [`parse`]'s error as its place (1-based line and column, when known)
/// and message: `sitlogc check` makes it a diagnostic (E0007).
pub fn parse_located(text: &str) -> Result<AppConfig, (Option<(usize, usize)>, String)> {
    toml::from_str(text).map_err(|e: toml::de::Error| {
        let message = e.message().trim().replace('\n', " ");
        let place = e
            .span()
            .map(|span| sitlog_syntax::line_col(text, span.start));
        (place, message)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn reads_the_key_and_refuses_others_with_their_place() {
        assert_eq!(parse("s.toml", ""), Ok(AppConfig::default()));
        assert_eq!(
            parse("s.toml", "deny-warnings = true\n"),
            Ok(AppConfig {
                deny_warnings: true
            })
        );
        let e = parse("s.toml", "# settings\ndeny-warning = true\n").unwrap_err();
        assert!(
            e.starts_with("s.toml:2:1: error: unknown field `deny-warning`"),
            "{e}"
        );
        let e = parse("s.toml", "deny-warnings = \"yes\"\n").unwrap_err();
        assert!(e.starts_with("s.toml:1:17: error: "), "{e}");
        let e = parse("s.toml", "deny-warnings = \n").unwrap_err();
        assert!(e.starts_with("s.toml:1:"), "{e}");
    }

    /// Pieces of text shaped like a `sitlog.toml` (and like what it must refuse).
    const PIECES: &[&str] = &[
        "deny-warnings",
        "deny_warnings",
        " = ",
        "=",
        "true",
        "false",
        "1",
        "1e400",
        "nan",
        "\"",
        "'",
        "\"\"\"",
        "[",
        "]",
        "[[",
        "]]",
        "{",
        "}",
        ",",
        ".",
        "#",
        " ",
        "\t",
        "\n",
        "\r\n",
        "\r",
        "é",
        "\u{a0}",
        "\u{2028}",
        "\u{feff}",
        "\\",
        "\\u{0}",
        "x",
        "table",
        "\u{0}",
    ];

    /// Checks the invariant on `text`: the settings, or one line
    /// `s.toml:LINE:COL: error: ...` whose place is in `text` (or
    /// `s.toml: error: ...` without one).
    fn located(text: &str) -> Result<(), TestCaseError> {
        let Err(e) = parse("s.toml", text) else {
            return Ok(());
        };
        prop_assert!(!e.contains('\n'), "{e:?}");
        let Some(rest) = e.strip_prefix("s.toml:") else {
            return Err(TestCaseError::fail(format!("no file name: {e:?}")));
        };
        if rest.starts_with(" error: ") {
            return Ok(());
        }
        let mut parts = rest.splitn(3, ':');
        let line: usize = parts
            .next()
            .unwrap_or("")
            .parse()
            .map_err(|_| TestCaseError::fail(format!("{e:?}")))?;
        let col: usize = parts
            .next()
            .unwrap_or("")
            .parse()
            .map_err(|_| TestCaseError::fail(format!("{e:?}")))?;
        prop_assert!(
            parts.next().is_some_and(|m| m.starts_with(" error: ")),
            "{e:?}"
        );
        let lines: Vec<&str> = text.split('\n').collect();
        prop_assert!(
            line >= 1 && line <= lines.len(),
            "line {line} of {}: {e:?}",
            lines.len()
        );
        let chars = lines[line - 1].chars().count();
        prop_assert!(
            col >= 1 && col <= chars + 1,
            "column {col} of {chars}: {e:?}"
        );
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn any_text_reads_or_is_a_located_error(text in any::<String>()) {
            located(&text)?;
        }

        #[test]
        fn settings_shaped_text_reads_or_is_a_located_error(
            parts in prop::collection::vec(prop::sample::select(PIECES), 0..24)
        ) {
            located(&parts.concat())?;
        }
    }
}
