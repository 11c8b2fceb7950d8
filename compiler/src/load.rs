//! Loading an application: the only module of the library that touches the
//! file system. An application is a directory: the DM files its `models`
//! file lists (in order, paths relative to the directory), or, without a
//! `models` file, every `*.dm` below it (sorted by path); plus the side files
//! beside them (`global_vars.pl`, `basic_actions.pl`, `expectation_types.pl`,
//! `user_functions.pl`, `templates.pl`). A single file is a program of one
//! DM file.

use crate::ast::{self, Program};
use crate::diag::{Diagnostic, Loc};
use crate::source::FileId;
use sitlog_syntax::{read_clauses, Clause, Span, SyntaxError};
use std::io;
use std::path::{Path, PathBuf};

/// Diagnostic codes of loading and reading.
pub mod codes {
    pub const SYNTAX: &str = "E0001";
    pub const NOT_UTF8: &str = "E0002";
    pub const MODELS_ENTRY: &str = "E0003";
    pub const MISSING_FILE: &str = "E0004";
}

/// An I/O problem that stops loading (exit status 2 in the CLI).
#[derive(Debug)]
pub struct LoadError {
    pub path: PathBuf,
    pub error: io::Error,
}

impl std::fmt::Display for LoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.error)
    }
}

impl std::error::Error for LoadError {}

/// The side files read beside the DMs, by role.
const GLOBALS: &str = "global_vars.pl";
const BASIC_ACTIONS: &str = "basic_actions.pl";
const EXPECTATION_TYPES: &str = "expectation_types.pl";
const RECOVERY: &str = "recovery_protocols.pl";
const PROLOG_FILES: [&str; 2] = ["templates.pl", "user_functions.pl"];

/// The programs below `path`: a file is one program; a directory with a
/// `models` file or a `*.dm` file directly in it is one application; any
/// other directory is a collection whose subdirectories are searched (sorted).
pub fn discover(path: &Path) -> Result<Vec<PathBuf>, LoadError> {
    let err = |error| LoadError {
        path: path.to_path_buf(),
        error,
    };
    let meta = std::fs::metadata(path).map_err(err)?;
    if !meta.is_dir() || is_application(path).map_err(err)? {
        return Ok(vec![path.to_path_buf()]);
    }
    let mut subdirs: Vec<PathBuf> = std::fs::read_dir(path)
        .map_err(err)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    subdirs.sort();
    let mut apps = Vec::new();
    for dir in subdirs {
        apps.extend(discover(&dir)?);
    }
    Ok(apps)
}

fn is_application(dir: &Path) -> io::Result<bool> {
    if dir.join("models").is_file() {
        return Ok(true);
    }
    for entry in std::fs::read_dir(dir)? {
        let p = entry?.path();
        if p.is_file() && p.extension().is_some_and(|e| e == "dm") {
            return Ok(true);
        }
    }
    Ok(false)
}

/// Loads an application directory or a single DM file into one program.
pub fn load(path: &Path) -> Result<(Program, Vec<Diagnostic>), LoadError> {
    let mut program = Program::default();
    let mut diags = Vec::new();
    let meta = std::fs::metadata(path).map_err(|error| LoadError {
        path: path.to_path_buf(),
        error,
    })?;
    if meta.is_dir() {
        load_dir(path, &mut program, &mut diags)?;
    } else {
        load_dm_file(path, &mut program, &mut diags)?;
    }
    Ok((program, diags))
}

/// Loads a program from in-memory DM sources (for tests and tools).
pub fn load_sources(files: &[(&str, &str)]) -> (Program, Vec<Diagnostic>) {
    let mut program = Program::default();
    let mut diags = Vec::new();
    for (name, text) in files {
        let file =
            program
                .sources
                .add_named(PathBuf::from(name), name.to_string(), text.to_string());
        let clauses = read_file_clauses(&program, file, &mut diags);
        let name = Path::new(name)
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("");
        add_file_by_role(&mut program, file, name, clauses, &mut diags);
    }
    (program, diags)
}

/// [`load_sources`] for raw bytes, decoded as files are (text that is not
/// UTF-8 is a diagnostic at its first bad byte): for fuzzing and tools.
pub fn load_source_bytes(files: &[(&str, &[u8])]) -> (Program, Vec<Diagnostic>) {
    let mut program = Program::default();
    let mut diags = Vec::new();
    for (name, bytes) in files {
        let file = add_bytes(Path::new(name), bytes.to_vec(), &mut program, &mut diags);
        let clauses = read_file_clauses(&program, file, &mut diags);
        let name = Path::new(name)
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("");
        add_file_by_role(&mut program, file, name, clauses, &mut diags);
    }
    (program, diags)
}

fn add_file_by_role(
    program: &mut Program,
    file: FileId,
    name: &str,
    clauses: Vec<Clause>,
    diags: &mut Vec<Diagnostic>,
) {
    match name {
        GLOBALS => {
            program.has_globals_file = true;
            ast::build_globals(file, clauses, &mut program.globals, diags);
        }
        BASIC_ACTIONS => ast::build_basic_actions(file, clauses, &mut program.basic_actions, diags),
        EXPECTATION_TYPES => {
            ast::build_expectation_types(file, clauses, &mut program.expectation_types, diags)
        }
        RECOVERY => ast::build_recovery(file, clauses, &mut program.recovery, diags),
        n if PROLOG_FILES.contains(&n) => {
            ast::build_function_heads(file, &clauses, &mut program.functions);
            program.prolog_files.push(file);
        }
        _ => ast::build_dms(file, clauses, &mut program.dms, diags),
    }
}

fn read_text(
    path: &Path,
    program: &mut Program,
    diags: &mut Vec<Diagnostic>,
) -> Result<FileId, LoadError> {
    let bytes = std::fs::read(path).map_err(|error| LoadError {
        path: path.to_path_buf(),
        error,
    })?;
    Ok(add_bytes(path, bytes, program, diags))
}

fn add_bytes(
    path: &Path,
    bytes: Vec<u8>,
    program: &mut Program,
    diags: &mut Vec<Diagnostic>,
) -> FileId {
    match sitlog_syntax::decode(&bytes) {
        Ok(text) => program.sources.add(path, text.to_owned()),
        Err(e) => {
            // The file is shown with U+FFFD for what is not UTF-8; the span
            // covers the first replacement (a char boundary of that text).
            let (text, at) = sitlog_syntax::decode::lossy_with_offset(&bytes, e.offset);
            let text = text.into_owned();
            let width = text[at..].chars().next().map_or(0, char::len_utf8);
            let file = program.sources.add(path, text);
            let span = Span::new(at, at + width);
            let (label, help) = if e.utf16 {
                ("UTF-16 text", "save the file as UTF-8")
            } else {
                ("not UTF-8", "save the file as UTF-8 (e.g. iconv -t UTF-8)")
            };
            diags.push(
                Diagnostic::error(
                    codes::NOT_UTF8,
                    Loc { file, span },
                    format!("{} (at byte offset {})", e.message, e.offset),
                )
                .with_label(label)
                .with_help(help),
            );
            file
        }
    }
}

/// Reads the clauses of a file, turning syntax errors into diagnostics.
fn read_file_clauses(program: &Program, file: FileId, diags: &mut Vec<Diagnostic>) -> Vec<Clause> {
    if diags
        .iter()
        .any(|d| d.loc.file == file && d.code == codes::NOT_UTF8)
    {
        return Vec::new();
    }
    let (clauses, errors) = read_clauses(&program.sources.get(file).text);
    diags.extend(errors.into_iter().map(|e| syntax_diagnostic(file, e)));
    clauses
}

/// A reader error as a diagnostic.
pub fn syntax_diagnostic(file: FileId, e: SyntaxError) -> Diagnostic {
    let label = if e.incomplete {
        "input ends here"
    } else {
        "here"
    };
    let mut d =
        Diagnostic::error(codes::SYNTAX, Loc { file, span: e.span }, e.message).with_label(label);
    d.help = e.help;
    for (span, text) in e.labels {
        d = d.with_secondary(Loc { file, span }, text);
    }
    d
}

fn load_dm_file(
    path: &Path,
    program: &mut Program,
    diags: &mut Vec<Diagnostic>,
) -> Result<(), LoadError> {
    let file = read_text(path, program, diags)?;
    let clauses = read_file_clauses(program, file, diags);
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
    add_file_by_role(program, file, name, clauses, diags);
    Ok(())
}

fn load_dir(
    dir: &Path,
    program: &mut Program,
    diags: &mut Vec<Diagnostic>,
) -> Result<(), LoadError> {
    let models = dir.join("models");
    if models.is_file() {
        let file = read_text(&models, program, diags)?;
        let clauses = read_file_clauses(program, file, diags);
        for clause in clauses {
            let loc = Loc {
                file,
                span: clause.span,
            };
            let Some(name) = clause.terms.atom(clause.root) else {
                diags.push(
                    Diagnostic::error(
                        codes::MODELS_ENTRY,
                        loc,
                        "a `models` entry must be a quoted file name",
                    )
                    .with_help("e.g. `'main.dm'.`"),
                );
                continue;
            };
            let path = dir.join(name.as_str());
            match std::fs::read(&path) {
                Ok(bytes) => {
                    let f = add_bytes(&path, bytes, program, diags);
                    let clauses = read_file_clauses(program, f, diags);
                    ast::build_dms(f, clauses, &mut program.dms, diags);
                }
                Err(e) => diags.push(
                    Diagnostic::error(
                        codes::MISSING_FILE,
                        loc,
                        format!("cannot read DM file `{}`: {e}", path.display()),
                    )
                    .with_label("listed here"),
                ),
            }
        }
    } else {
        let mut dm_files = Vec::new();
        collect_dm_files(dir, &mut dm_files).map_err(|error| LoadError {
            path: dir.to_path_buf(),
            error,
        })?;
        dm_files.sort();
        for path in dm_files {
            load_dm_file(&path, program, diags)?;
        }
    }
    for side in [GLOBALS, BASIC_ACTIONS, EXPECTATION_TYPES, RECOVERY]
        .into_iter()
        .chain(PROLOG_FILES)
    {
        let path = dir.join(side);
        if path.is_file() {
            let file = read_text(&path, program, diags)?;
            let clauses = read_file_clauses(program, file, diags);
            add_file_by_role(program, file, side, clauses, diags);
        }
    }
    Ok(())
}

fn collect_dm_files(dir: &Path, out: &mut Vec<PathBuf>) -> io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let path = entry.path();
        let ty = entry.file_type()?;
        if ty.is_dir() {
            collect_dm_files(&path, out)?;
        } else if path.extension().is_some_and(|e| e == "dm") && path.is_file() {
            out.push(path);
        }
    }
    Ok(())
}
