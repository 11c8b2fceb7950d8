//! Compiling SitLog applications from a build script (the prost-build
//! pattern), and the shared front half of `include_dm!` and `sitlogc build`.
//!
//! ```no_run
//! // in build.rs's `main`:
//! sitlog_compiler::build::compile("dms/examples/countdown").unwrap();
//! // then in src/lib.rs:
//! // pub mod countdown { include!(concat!(env!("OUT_DIR"), "/countdown.rs")); }
//! ```
//!
//! The generated file is written only when its text changed (so unchanged
//! programs do not trigger rebuilds), and `cargo:rerun-if-changed` is printed
//! for every file read and for the application directory.

use crate::codegen;
use proc_macro2::TokenStream;
use std::path::{Path, PathBuf};

/// Why a program could not be compiled: I/O, or diagnostics of the DM
/// sources rendered as `file.dm:line:col: error[CODE]: message` plus the
/// source line (one string per error).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Error {
    pub messages: Vec<String>,
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.messages.join("\n"))
    }
}

impl std::error::Error for Error {}

/// A compiled program: its tokens and every file read to make them.
pub struct Compiled {
    pub tokens: TokenStream,
    /// Source files read (DM files, side files, the `models` file).
    pub files: Vec<PathBuf>,
    /// How the source was named (for the `@generated` header).
    pub source: String,
}

impl Compiled {
    /// The formatted file text with its `@generated` header.
    pub fn to_file_string(&self) -> String {
        codegen::format_file(self.tokens.clone(), &self.source)
    }
}

/// Loads, checks, lowers and generates the application at `path` (a
/// directory or a DM file). `source` names it in the header.
pub fn generate(path: &Path, source: &str) -> Result<Compiled, Error> {
    generate_with(path, source, codegen::Options::default())
}

/// [`generate`] with code generator options.
pub fn generate_with(
    path: &Path,
    source: &str,
    options: codegen::Options,
) -> Result<Compiled, Error> {
    generate_checked(path, source, options, crate::check::CheckOptions::default())
}

/// [`generate_with`] with checker options: with `unresolved_as_warnings`
/// a program whose next situations, embedded DMs or exit arcs do not all
/// resolve is compiled too (taking such a path is a run-time error, as in
/// `sitlogc run --allow-unresolved`).
pub fn generate_checked(
    path: &Path,
    source: &str,
    options: codegen::Options,
    check: crate::check::CheckOptions,
) -> Result<Compiled, Error> {
    let (result, diags) = crate::check_path_opts(path, check).map_err(|e| Error {
        messages: vec![format!("cannot read {e}")],
    })?;
    let sources = match &result {
        Ok(c) => &c.program().sources,
        Err(p) => &p.sources,
    };
    // The files read (for `cargo:rerun-if-changed` and `--watch`): not
    // those of a library held in memory.
    let mut files: Vec<PathBuf> = sources
        .files()
        .map(|(_, f)| f.path.clone())
        .filter(|p| !p.starts_with(crate::load::EMBEDDED))
        .collect();
    if path.is_dir() && path.join("models").is_file() {
        files.push(path.join("models"));
    }
    let checked = match result {
        Ok(c) => c,
        Err(p) => {
            let messages = diags
                .iter()
                .filter(|d| d.is_error())
                .map(|d| crate::diag::render_short(d, &p.sources))
                .collect();
            return Err(Error { messages });
        }
    };
    let ir = crate::ir::lower(&checked);
    Ok(Compiled {
        tokens: codegen::generate_with(&ir, source, options),
        files,
        source: source.to_owned(),
    })
}

/// Options of [`Config::compile`].
#[derive(Clone, Debug, Default)]
pub struct Config {
    out_dir: Option<PathBuf>,
    file_name: Option<String>,
    quiet: bool,
    world_functions: &'static [(&'static str, usize)],
    library: Option<&'static crate::load::Library>,
}

impl Config {
    pub fn new() -> Config {
        Config::default()
    }

    /// Where to write (default: the `OUT_DIR` Cargo gives build scripts).
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Config {
        self.out_dir = Some(dir.into());
        self
    }

    /// The output file name (default: `<application name>.rs`).
    pub fn file_name(mut self, name: impl Into<String>) -> Config {
        self.file_name = Some(name.into());
        self
    }

    /// Functions the host registers when the task runs on a world (e.g.
    /// `sitlog_robot::WORLD_FUNCTIONS`), known to the checker by name and
    /// arity (see [`crate::check::CheckOptions::world_functions`]).
    pub fn world_functions(mut self, functions: &'static [(&'static str, usize)]) -> Config {
        self.world_functions = functions;
        self
    }

    /// Where library names the application has no copy of are looked up
    /// (see [`crate::load::Library`]).
    pub fn library(mut self, library: &'static crate::load::Library) -> Config {
        self.library = Some(library);
        self
    }

    /// Do not print `cargo:` lines (outside build scripts).
    pub fn quiet(mut self, quiet: bool) -> Config {
        self.quiet = quiet;
        self
    }

    /// Compiles the application at `app` into the output directory; returns
    /// the path of the generated file.
    pub fn compile(&self, app: impl AsRef<Path>) -> Result<PathBuf, Error> {
        let app = app.as_ref();
        if !self.quiet {
            println!("cargo:rerun-if-changed={}", app.display());
        }
        let check = crate::check::CheckOptions {
            world_functions: self.world_functions,
            library: self.library,
            ..Default::default()
        };
        let compiled = generate_checked(app, &app.display().to_string(), Default::default(), check);
        if !self.quiet {
            let files = match &compiled {
                Ok(c) => c.files.clone(),
                Err(_) => Vec::new(),
            };
            for f in files {
                println!("cargo:rerun-if-changed={}", f.display());
            }
        }
        let compiled = compiled?;
        let out_dir = match &self.out_dir {
            Some(d) => d.clone(),
            None => PathBuf::from(std::env::var_os("OUT_DIR").ok_or_else(|| Error {
                messages: vec![
                    "OUT_DIR is not set: call from a build script or set Config::out_dir".into(),
                ],
            })?),
        };
        let name = match &self.file_name {
            Some(n) => n.clone(),
            None => format!("{}.rs", app_ident(app)),
        };
        let path = out_dir.join(name);
        write_if_changed(&path, &compiled.to_file_string()).map_err(|e| Error {
            messages: vec![format!("cannot write {}: {e}", path.display())],
        })?;
        Ok(path)
    }
}

/// Compiles the application at `app` into `OUT_DIR/<name>.rs` (from a
/// build script); see [`Config`] for options.
pub fn compile(app: impl AsRef<Path>) -> Result<PathBuf, Error> {
    Config::new().compile(app)
}

/// The application's name ([`sitlog_runtime::paths::app_name`]) as a Rust
/// identifier: lower case, `_` for anything not alphanumeric, `_` in front
/// of a leading digit. Names the generated file and the diagrams' title.
pub fn app_ident(app: &Path) -> String {
    let name = sitlog_runtime::paths::app_name(app);
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    s
}

/// Writes `text` to `path` unless the file already holds exactly it.
pub fn write_if_changed(path: &Path, text: &str) -> std::io::Result<bool> {
    if std::fs::read(path).is_ok_and(|old| old == text.as_bytes()) {
        return Ok(false);
    }
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(path, text)?;
    Ok(true)
}
