//! Loading an application: the only module of the library that touches the
//! file system. An application is a directory: the DM files its `models`
//! file lists (in order, paths relative to the directory), or, without a
//! `models` file, every `*.dm` below it (sorted by path); plus the side files
//! beside them (`global_vars.pl`, `basic_actions.pl`, `expectation_types.pl`,
//! `user_functions.pl`, `templates.pl`, `recovery_protocols.pl`,
//! `host_functions.pl`). A single file is a program of one
//! DM file.
//!
//! Library names: a `models` entry or a consulted Prolog file named by a
//! relative path without `..` (`'behaviors/say.dm'`) is read from the
//! application's directory when it is there (a local copy wins), else from
//! the first root of the [`Library`] the caller gives that has it (the
//! `sitlogc` binary passes `$SITLOG_LIBRARY`'s directories, then the
//! behaviour library built into it). Files of an embedded root are shown as
//! `library:/NAME`; [`Program::library_files`] says where each came from.

use crate::ast::{self, Program};
use crate::diag::{Diagnostic, Loc};
use crate::source::FileId;
use sitlog_syntax::{read_clauses_with, Clause, OpTable, Span, SyntaxError};
use std::io;
use std::path::{Path, PathBuf};

/// Diagnostic codes of loading and reading.
pub mod codes {
    pub const SYNTAX: &str = "E0001";
    pub const NOT_UTF8: &str = "E0002";
    pub const MODELS_ENTRY: &str = "E0003";
    pub const MISSING_FILE: &str = "E0004";
    pub const NOT_A_DM_FILE: &str = "E0005";
    pub const OUTSIDE_APP: &str = "W0006";
    /// Not the loader's: the command line reads the application's world,
    /// KB and ROS 2 interface files (`sitlogc check`) and reports their
    /// errors with this code.
    pub const APP_FILE: &str = "E0007";
    /// A clause of a consulted Prolog file that does not read (skipped).
    pub const PROLOG_SYNTAX: &str = "W0008";
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
const HOST_FUNCTIONS: &str = "host_functions.pl";
const PROLOG_FILES: [&str; 2] = ["templates.pl", "user_functions.pl"];
/// The application's knowledge base and simulated world (not read here).
const KB_FILE: &str = "knowledge.kb";
const WORLD_FILE: &str = "world.toml";

/// Where library names are looked up after the application's directory,
/// in order (see the module documentation).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Library {
    pub roots: Vec<LibraryRoot>,
}

/// One place library files are read from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LibraryRoot {
    /// What it is, as `sitlogc check --origins` says it (`the library built
    /// into sitlogc 0.1.0`, `$SITLOG_LIBRARY directory /opt/lib`).
    pub what: String,
    pub files: LibraryFiles,
}

/// The files of a [`LibraryRoot`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LibraryFiles {
    /// A directory: a name is a path below it.
    Dir(PathBuf),
    /// Files held in memory (shipped inside a program), by name
    /// (`behaviors/say.dm`); shown as [`EMBEDDED`]`/NAME`.
    Embedded(&'static [(&'static str, &'static [u8])]),
}

/// The directory embedded library files appear in (their paths and names).
pub const EMBEDDED: &str = "library:";

/// No library: names are read from the application's directory only.
static NO_LIBRARY: Library = Library { roots: Vec::new() };

impl Library {
    /// No library: names are read from the application's directory only.
    pub fn none() -> &'static Library {
        &NO_LIBRARY
    }

    /// The file a library name names: the root's index, its path (for an
    /// embedded root, below [`EMBEDDED`]) and its bytes.
    pub fn find(&self, name: &str) -> Option<(usize, PathBuf, Vec<u8>)> {
        if !is_library_name(name) {
            return None;
        }
        let wanted = normalize(Path::new(name));
        self.roots
            .iter()
            .enumerate()
            .find_map(|(i, root)| match &root.files {
                LibraryFiles::Dir(dir) => {
                    let path = dir.join(&wanted);
                    let bytes = path.is_file().then(|| read_bytes(&path).ok()).flatten()?;
                    Some((i, path, bytes))
                }
                LibraryFiles::Embedded(files) => files
                    .iter()
                    .find(|(n, _)| Path::new(n) == wanted)
                    .map(|(n, b)| (i, Path::new(EMBEDDED).join(n), b.to_vec())),
            })
    }

    /// The bytes of the file `name` of the first embedded root that has it.
    fn embedded(&self, name: &Path) -> Option<&'static [u8]> {
        self.roots.iter().find_map(|root| match &root.files {
            LibraryFiles::Embedded(files) => files
                .iter()
                .find(|(n, _)| Path::new(n) == name)
                .map(|(_, b)| *b),
            LibraryFiles::Dir(_) => None,
        })
    }

    /// The names of the library's DM files (`behaviors/find.dm`), each
    /// once (the first root that has it), sorted; with `text`, their text
    /// too. For help lines: read only when a diagnostic needs them.
    pub fn dm_files(&self, text: bool) -> Vec<(String, String)> {
        let mut out: Vec<(String, String)> = Vec::new();
        for root in &self.roots {
            let mut found: Vec<(String, String)> = Vec::new();
            match &root.files {
                LibraryFiles::Dir(dir) => {
                    let mut files = Vec::new();
                    if collect_dm_files(dir, &mut files).is_err() {
                        continue;
                    }
                    for f in files {
                        let Ok(rel) = f.strip_prefix(dir) else {
                            continue;
                        };
                        let name = rel
                            .components()
                            .map(|c| c.as_os_str().to_string_lossy())
                            .collect::<Vec<_>>()
                            .join("/");
                        let body = if text {
                            read_bytes(&f)
                                .map(|b| String::from_utf8_lossy(&b).into_owned())
                                .unwrap_or_default()
                        } else {
                            String::new()
                        };
                        found.push((name, body));
                    }
                }
                LibraryFiles::Embedded(files) => {
                    for (n, b) in files.iter().filter(|(n, _)| n.ends_with(".dm")) {
                        let body = if text {
                            String::from_utf8_lossy(b).into_owned()
                        } else {
                            String::new()
                        };
                        found.push(((*n).to_owned(), body));
                    }
                }
            }
            for f in found {
                if !out.iter().any(|(n, _)| *n == f.0) {
                    out.push(f);
                }
            }
        }
        out.sort();
        out
    }

    /// Where the library was looked for, for a help line.
    fn places(&self) -> String {
        self.roots
            .iter()
            .map(|r| r.what.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Whether `name` may name a library file: a relative path of plain
/// components (no `..`, no root).
pub fn is_library_name(name: &str) -> bool {
    let p = Path::new(name);
    !name.is_empty()
        && p.components()
            .all(|c| matches!(c, std::path::Component::Normal(_)))
}

/// The name of an embedded library file below [`EMBEDDED`], if `path` is one.
fn embedded_name(path: &Path) -> Option<PathBuf> {
    normalize(path)
        .strip_prefix(EMBEDDED)
        .ok()
        .map(Path::to_path_buf)
}

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

pub fn is_application(dir: &Path) -> io::Result<bool> {
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

/// Loads an application directory or a single DM file into one program,
/// without a library ([`load_with`]).
pub fn load(path: &Path) -> Result<(Program, Vec<Diagnostic>), LoadError> {
    load_with(path, Library::none())
}

/// Loads an application directory or a single DM file into one program,
/// library names looked up in `library` when the application has no copy.
pub fn load_with(path: &Path, library: &Library) -> Result<(Program, Vec<Diagnostic>), LoadError> {
    let cx = Cx { library };
    let mut program = Program::default();
    let mut diags = Vec::new();
    // A file only in the overlay (an editor's unsaved buffer) is a DM file.
    let is_dir = match std::fs::metadata(path) {
        Ok(meta) => meta.is_dir(),
        Err(_) if in_overlay(path) => false,
        Err(error) => {
            return Err(LoadError {
                path: path.to_path_buf(),
                error,
            })
        }
    };
    let dir = if is_dir {
        load_dir(cx, path, &mut program, &mut diags)?;
        Some(path.to_path_buf())
    } else {
        load_dm_file(cx, path, &mut program, &mut diags)?;
        program.single_file = true;
        // A DM file checked alone still sees the side files beside it (its
        // globals, actions, functions): what the help of its diagnostics
        // tells the user to edit is what is read.
        let dir = path.parent().map(|p| {
            if p.as_os_str().is_empty() {
                Path::new(".")
            } else {
                p
            }
        });
        if path.extension().is_some_and(|e| e == "dm") {
            if let Some(dir) = dir {
                load_side_files(cx, dir, &mut program, &mut diags)?;
            }
        }
        dir.map(Path::to_path_buf)
    };
    if let Some(dir) = dir {
        program.has_kb_file = dir.join(KB_FILE).is_file();
        program.has_world_file = dir.join(WORLD_FILE).is_file();
    }
    skipped_prolog_clauses(&program, &mut diags);
    Ok((program, diags))
}

/// A syntax error in a Prolog file that is consulted (`user_functions.pl`,
/// `templates.pl` and what they consult) skips that clause, as SWI-Prolog's
/// consult does for the original, and the engine loads the rest: a warning
/// (W0008), not an error. The side files the original reads with `read/1`
/// (global variables, actions, ...) and the DM files stay errors (E0001).
fn skipped_prolog_clauses(program: &Program, diags: &mut [Diagnostic]) {
    for d in diags.iter_mut() {
        if d.code == codes::SYNTAX && program.prolog_files.contains(&d.loc.file) {
            d.code = codes::PROLOG_SYNTAX;
            d.severity = crate::diag::Severity::Warning;
            d.message = format!("{} (this clause is skipped)", d.message);
            if d.help.is_none() {
                d.help = Some(
                    "SWI-Prolog skips a clause it cannot read and loads the rest of the file, and so does the run: the functions it defines are missing".to_owned(),
                );
            }
        }
    }
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
        let name = Path::new(name)
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("");
        let clauses = if PROLOG_FILES.contains(&name) {
            read_prolog_file_clauses(&program, file, &mut diags)
        } else {
            read_file_clauses(&program, file, &mut diags)
        };
        add_file_by_role(Cx::NONE, &mut program, file, name, clauses, &mut diags);
    }
    skipped_prolog_clauses(&program, &mut diags);
    (program, diags)
}

/// [`load_sources`] for raw bytes, decoded as files are (text that is not
/// UTF-8 is a diagnostic at its first bad byte): for fuzzing and tools.
pub fn load_source_bytes(files: &[(&str, &[u8])]) -> (Program, Vec<Diagnostic>) {
    let mut program = Program::default();
    let mut diags = Vec::new();
    for (name, bytes) in files {
        let file = add_bytes(Path::new(name), bytes.to_vec(), &mut program, &mut diags);
        let name = Path::new(name)
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("");
        let clauses = if PROLOG_FILES.contains(&name) {
            read_prolog_file_clauses(&program, file, &mut diags)
        } else {
            read_file_clauses(&program, file, &mut diags)
        };
        add_file_by_role(Cx::NONE, &mut program, file, name, clauses, &mut diags);
    }
    skipped_prolog_clauses(&program, &mut diags);
    (program, diags)
}

/// What loading one program needs besides the files: the library.
#[derive(Clone, Copy)]
struct Cx<'a> {
    library: &'a Library,
}

impl Cx<'static> {
    const NONE: Cx<'static> = Cx {
        library: &NO_LIBRARY,
    };
}

impl Cx<'_> {
    /// Whether `path` names a file: one of an embedded library root, or
    /// one on disk.
    fn exists(&self, path: &Path) -> bool {
        match embedded_name(path) {
            Some(name) => self.library.embedded(&name).is_some(),
            None => path.is_file(),
        }
    }

    /// The bytes of `path`: an embedded library file, or a file on disk
    /// (or the overlay standing in for it).
    fn read(&self, path: &Path) -> io::Result<Vec<u8>> {
        match embedded_name(path) {
            Some(name) => self
                .library
                .embedded(&name)
                .map(<[u8]>::to_vec)
                .ok_or_else(|| io::ErrorKind::NotFound.into()),
            None => read_bytes(path),
        }
    }
}

fn add_file_by_role(
    cx: Cx<'_>,
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
        HOST_FUNCTIONS => {
            ast::build_host_functions(file, clauses, &mut program.host_functions, diags)
        }
        n if PROLOG_FILES.contains(&n) => add_prolog_file(cx, program, file, clauses, diags, 0),
        _ => ast::build_dms(file, clauses, &mut program.dms, diags),
    }
}

/// Adds a Prolog file and, before it, the files it consults by relative
/// name (`:- consult(F)`, `:- ensure_loaded(F)`, `:- [F, ...]`), so that the
/// checker knows their predicates and a compiled task embeds them: one
/// binary, no file read at run time. A consulted file that is missing, or
/// named through `$SITLOG_HOME`, is left to the Prolog loader, which
/// reports it with its position.
fn add_prolog_file(
    cx: Cx<'_>,
    program: &mut Program,
    file: FileId,
    clauses: Vec<Clause>,
    diags: &mut Vec<Diagnostic>,
    depth: usize,
) {
    let dir = program
        .sources
        .get(file)
        .path
        .parent()
        .map(Path::to_path_buf);
    if let Some(dir) = dir.filter(|_| depth < 32) {
        for (name, span) in consulted(&clauses) {
            let unread = (name.clone(), Loc { file, span });
            if name.starts_with('$') || Path::new(&name).is_absolute() {
                program.unread_consults.push(unread);
                continue;
            }
            let with_pl = format!("{name}.pl");
            // Beside the consulting file (a file of an embedded library:
            // beside it in the library), with or without `.pl`.
            let beside = [&name, &with_pl]
                .into_iter()
                .map(|n| normalize(&dir.join(n)))
                .find(|p| cx.exists(p));
            let (path, bytes, library) = match beside {
                Some(path) => {
                    let library = [&name, &with_pl]
                        .into_iter()
                        .find_map(|n| cx.library.find(n).map(|found| (n, found)))
                        .map(|(n, (root, _, _))| {
                            let what = cx.library.roots[root].what.clone();
                            match embedded_name(&path) {
                                Some(_) => (n.clone(), Some(what), None),
                                None => (n.clone(), None, Some(what)),
                            }
                        });
                    (path, None, library)
                }
                // A library name the application has no copy of.
                None => match [&name, &with_pl]
                    .into_iter()
                    .find_map(|n| cx.library.find(n).map(|found| (n, found)))
                {
                    Some((n, (root, path, bytes))) => {
                        let what = cx.library.roots[root].what.clone();
                        (
                            normalize(&path),
                            Some(bytes),
                            Some((n.clone(), Some(what), None)),
                        )
                    }
                    None => {
                        program.unread_consults.push(unread);
                        continue;
                    }
                },
            };
            // A symbolic link out of the application is not read (the run
            // refuses to consult it without --allow-os).
            if bytes.is_none() && linked_outside(&dir, &path).is_some() {
                program.unread_consults.push(unread);
                continue;
            }
            let known = program
                .prolog_files
                .iter()
                .any(|&f| normalize(&program.sources.get(f).path) == path);
            if known {
                continue;
            }
            let read = match bytes {
                Some(bytes) => Ok(add_bytes(&path, bytes, program, diags)),
                None => read_text(cx, &path, program, diags),
            };
            if let Ok(id) = read {
                if let Some((name, root, overrides)) = library {
                    program.library_files.push(ast::LibraryFile {
                        name,
                        file: id,
                        root,
                        overrides,
                    });
                }
                let clauses = read_prolog_file_clauses(program, id, diags);
                add_prolog_file(cx, program, id, clauses, diags, depth + 1);
            }
        }
    }
    ast::build_function_heads(
        file,
        &clauses,
        &mut program.functions,
        &mut program.function_values,
    );
    program.prolog_files.push(file);
    // No clause from a text that is not blank: maybe a file the loader
    // did not read (not UTF-8); whoever needs its clauses reads it.
    let read = !clauses.is_empty() || program.sources.get(file).text.trim().is_empty();
    program
        .prolog_file_clauses
        .push(read.then(|| std::sync::Arc::new(clauses)));
}

/// The file names of the consult directives among `clauses`, each with
/// the span of its directive.
fn consulted(clauses: &[Clause]) -> Vec<(String, Span)> {
    let neck = sitlog_syntax::Atom::intern(":-");
    let mut out = Vec::new();
    for c in clauses {
        let t = &c.terms;
        let Some(&[goal]) = t.compound(c.root, neck, 1) else {
            continue;
        };
        let list = match t.functor(goal) {
            Some((f, 1)) if f.as_str() == "consult" || f.as_str() == "ensure_loaded" => {
                t.args(goal)[0]
            }
            Some((f, 2)) if f.as_str() == "." => goal,
            _ => continue,
        };
        let mut item = list;
        loop {
            if let Some(a) = t.atom(item) {
                if a.as_str() != "[]" {
                    out.push((a.as_str().to_owned(), c.span));
                }
                break;
            }
            match t.functor(item) {
                Some((f, 2)) if f.as_str() == "." => {
                    if let Some(a) = t.atom(t.args(item)[0]) {
                        out.push((a.as_str().to_owned(), c.span));
                    }
                    item = t.args(item)[1];
                }
                _ => break,
            }
        }
    }
    out
}

pub use sitlog_runtime::paths::normalize;

thread_local! {
    /// Texts that stand in for files on this thread (an editor's unsaved
    /// buffers, see [`with_overlay`]), by normalized path.
    static OVERLAY: std::cell::RefCell<std::collections::HashMap<PathBuf, String>> =
        Default::default();
}

/// Runs `f` with `overlay` standing in for the files it names: loading
/// reads those texts instead of the disk (the language server's unsaved
/// buffers), whether or not the file exists. Directories are listed from
/// disk, plus the overlay's `*.dm` files below them that are not on disk.
pub fn with_overlay<R>(
    overlay: &std::collections::HashMap<PathBuf, String>,
    f: impl FnOnce() -> R,
) -> R {
    OVERLAY.with(|o| {
        *o.borrow_mut() = overlay
            .iter()
            .map(|(p, t)| (normalize(&absolute(p)), t.clone()))
            .collect()
    });
    let r = f();
    OVERLAY.with(|o| o.borrow_mut().clear());
    r
}

fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

/// Whether the overlay holds `path`.
fn in_overlay(path: &Path) -> bool {
    OVERLAY.with(|o| {
        let o = o.borrow();
        !o.is_empty() && o.contains_key(&normalize(&absolute(path)))
    })
}

/// The overlay's `*.dm` files below `dir` that are not on disk (a DM file
/// an editor has not saved yet), as paths under `dir`.
fn overlay_dm_files(dir: &Path) -> Vec<PathBuf> {
    let base = normalize(&absolute(dir));
    OVERLAY.with(|o| {
        o.borrow()
            .keys()
            .filter(|p| p.extension().is_some_and(|e| e == "dm") && !p.is_file())
            .filter_map(|p| p.strip_prefix(&base).ok().map(|rel| dir.join(rel)))
            .collect()
    })
}

/// A file's bytes: from the overlay if it holds the file, else the disk.
fn read_bytes(path: &Path) -> io::Result<Vec<u8>> {
    let over = OVERLAY.with(|o| {
        let o = o.borrow();
        if o.is_empty() {
            None
        } else {
            o.get(&normalize(&absolute(path))).cloned()
        }
    });
    match over {
        Some(text) => Ok(text.into_bytes()),
        None => sitlog_syntax::read_file(path),
    }
}

fn read_text(
    cx: Cx<'_>,
    path: &Path,
    program: &mut Program,
    diags: &mut Vec<Diagnostic>,
) -> Result<FileId, LoadError> {
    let bytes = cx.read(path).map_err(|error| LoadError {
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
    read_file_clauses_with(program, file, diags, OpTable::sitlog_shared())
}

/// [`read_file_clauses`] with the operator table `ops`.
fn read_file_clauses_with(
    program: &Program,
    file: FileId,
    diags: &mut Vec<Diagnostic>,
    ops: &OpTable,
) -> Vec<Clause> {
    if diags
        .iter()
        .any(|d| d.loc.file == file && d.code == codes::NOT_UTF8)
    {
        return Vec::new();
    }
    let (clauses, errors) = read_clauses_with(&program.sources.get(file).text, ops);
    diags.extend(errors.into_iter().map(|e| syntax_diagnostic(file, e)));
    clauses
}

/// Reads the clauses of a Prolog source file (`user_functions.pl`,
/// `templates.pl`, what they consult) with SWI-Prolog's operators
/// ([`sitlog_syntax::read_prolog_clauses`]).
fn read_prolog_file_clauses(
    program: &Program,
    file: FileId,
    diags: &mut Vec<Diagnostic>,
) -> Vec<Clause> {
    read_file_clauses_with(program, file, diags, OpTable::swi_shared())
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
    cx: Cx<'_>,
    path: &Path,
    program: &mut Program,
    diags: &mut Vec<Diagnostic>,
) -> Result<(), LoadError> {
    let file = read_text(cx, path, program, diags)?;
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
    // A Prolog file read as the engine reads it (its clauses are the ones
    // the engine loads: `Program::prolog_file_clauses`).
    let clauses = if PROLOG_FILES.contains(&name) {
        read_prolog_file_clauses(program, file, diags)
    } else {
        read_file_clauses(program, file, diags)
    };
    add_file_by_role(cx, program, file, name, clauses, diags);
    Ok(())
}

fn load_dir(
    cx: Cx<'_>,
    dir: &Path,
    program: &mut Program,
    diags: &mut Vec<Diagnostic>,
) -> Result<(), LoadError> {
    let models = dir.join("models");
    if models.is_file() {
        let file = read_text(cx, &models, program, diags)?;
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
            let name = name.as_str();
            let path = dir.join(name);
            match foreign_entry(dir, &path, loc) {
                Some(d) if d.is_error() => {
                    diags.push(d);
                    continue;
                }
                Some(d) => diags.push(d),
                None => {}
            }
            // The application's own file (a local copy of a library file
            // wins), else the library's.
            let (path, read, root) = match read_bytes(&path) {
                Err(e) if e.kind() == io::ErrorKind::NotFound => match cx.library.find(name) {
                    Some((root, path, bytes)) => (path, Ok(bytes), Some(root)),
                    None => (path, Err(e), None),
                },
                read => (path, read, None),
            };
            match read {
                Ok(bytes) => {
                    let f = add_bytes(&path, bytes, program, diags);
                    let what = |root: usize| cx.library.roots[root].what.clone();
                    let library = match root {
                        Some(root) => Some((Some(what(root)), None)),
                        None => cx
                            .library
                            .find(name)
                            .map(|(root, _, _)| (None, Some(what(root)))),
                    };
                    if let Some((root, overrides)) = library {
                        program.library_files.push(ast::LibraryFile {
                            name: name.to_owned(),
                            file: f,
                            root,
                            overrides,
                        });
                    }
                    let clauses = read_file_clauses(program, f, diags);
                    ast::build_dms(f, clauses, &mut program.dms, diags);
                }
                Err(e) => {
                    let mut d = Diagnostic::error(
                        codes::MISSING_FILE,
                        loc,
                        format!("cannot read DM file `{}`: {e}", path.display()),
                    )
                    .with_label("listed here");
                    if e.kind() == io::ErrorKind::NotFound && is_library_name(name) {
                        // A typo of a library file, or of one of the application's own.
                        let mut known: Vec<String> = cx
                            .library
                            .dm_files(false)
                            .into_iter()
                            .map(|(n, _)| n)
                            .collect();
                        let mut own = Vec::new();
                        if collect_dm_files(dir, &mut own).is_ok() {
                            known.extend(own.iter().filter_map(|f| {
                                let rel = f.strip_prefix(dir).ok()?;
                                Some(
                                    rel.components()
                                        .map(|c| c.as_os_str().to_string_lossy())
                                        .collect::<Vec<_>>()
                                        .join("/"),
                                )
                            }));
                        }
                        let mut help = if cx.library.roots.is_empty() {
                            "the path is relative to the application directory".to_owned()
                        } else {
                            format!(
                                "not in the application directory, nor in the library ({})",
                                cx.library.places()
                            )
                        };
                        if let Some(similar) = similar_file(name, &known) {
                            help.push_str(&format!(": did you mean `'{similar}'.`?"));
                        }
                        d = d.with_help(help);
                    }
                    diags.push(d);
                }
            }
        }
    } else {
        let mut dm_files = Vec::new();
        collect_dm_files(dir, &mut dm_files).map_err(|error| LoadError {
            path: dir.to_path_buf(),
            error,
        })?;
        dm_files.extend(overlay_dm_files(dir));
        dm_files.sort();
        for path in dm_files {
            refuse_linked_outside(dir, &path)?;
            load_dm_file(cx, &path, program, diags)?;
        }
    }
    load_side_files(cx, dir, program, diags)
}

/// What is wrong with a `models` entry naming `path` before it is read:
/// a file that is not SitLog/Prolog text by its name (not `.dm` or `.pl`:
/// `/etc/shadow`, `/proc/self/environ`, a device) is refused without being
/// read, so no diagnostic ever quotes it; a file outside the application's
/// directory is a warning (the behaviour library is named without a path).
fn foreign_entry(dir: &Path, path: &Path, loc: Loc) -> Option<Diagnostic> {
    let ext = path.extension().and_then(|e| e.to_str());
    if !matches!(ext, Some("dm" | "pl")) {
        return Some(
            Diagnostic::error(
                codes::NOT_A_DM_FILE,
                loc,
                format!(
                    "`{}` is not a DM file: `models` lists `.dm` (or `.pl`) files only; it was not read",
                    path.display()
                ),
            )
            .with_label("listed here"),
        );
    }
    let real = std::fs::canonicalize(path).ok()?;
    let home = std::fs::canonicalize(dir).ok()?;
    if real.starts_with(&home) {
        return None;
    }
    Some(
        Diagnostic::warning(
            codes::OUTSIDE_APP,
            loc,
            format!(
                "`{}` is outside the application directory",
                path.display()
            ),
        )
        .with_label("listed here")
        .with_help(
            "copy it into the application, or name a library file without a path (`'behaviors/say.dm'`)",
        ),
    )
}

/// Where `path`, a file of the application in `dir` by its name, really is
/// when a symbolic link takes it out of `dir` (issue 38: `global_vars.pl`
/// linked to `/etc/shadow`). Files only in the LSP's overlay, and those
/// that cannot be resolved, are not links out.
fn linked_outside(dir: &Path, path: &Path) -> Option<PathBuf> {
    if in_overlay(path) {
        return None;
    }
    let real = std::fs::canonicalize(path).ok()?;
    let home = std::fs::canonicalize(dir).ok()?;
    (!real.starts_with(&home)).then_some(real)
}

/// Refuses, before reading it, a file of the application that a symbolic
/// link takes out of `dir`: no diagnostic ever quotes what it holds.
fn refuse_linked_outside(dir: &Path, path: &Path) -> Result<(), LoadError> {
    match linked_outside(dir, path) {
        None => Ok(()),
        Some(real) => Err(LoadError {
            path: path.to_path_buf(),
            error: io::Error::new(
                io::ErrorKind::PermissionDenied,
                format!(
                    "a symbolic link to {}, outside the application: refused, not read (copy the file into the application)",
                    real.display()
                ),
            ),
        }),
    }
}

/// The side files of the application in `dir` (those that exist).
fn load_side_files(
    cx: Cx<'_>,
    dir: &Path,
    program: &mut Program,
    diags: &mut Vec<Diagnostic>,
) -> Result<(), LoadError> {
    for side in [
        GLOBALS,
        BASIC_ACTIONS,
        EXPECTATION_TYPES,
        RECOVERY,
        HOST_FUNCTIONS,
    ]
    .into_iter()
    .chain(PROLOG_FILES)
    {
        let path = dir.join(side);
        if path.is_file() {
            refuse_linked_outside(dir, &path)?;
            let file = read_text(cx, &path, program, diags)?;
            let clauses = if PROLOG_FILES.contains(&side) {
                read_prolog_file_clauses(program, file, diags)
            } else {
                read_file_clauses(program, file, diags)
            };
            add_file_by_role(cx, program, file, side, clauses, diags);
        }
    }
    Ok(())
}

/// The file of `known` (names with `/`) that `name` is a typo of: one in
/// the same directory whose file name is close (`behaviors/fnd.dm` →
/// `behaviors/find.dm`), else one whose whole name is close.
fn similar_file<'a>(name: &str, known: &'a [String]) -> Option<&'a str> {
    let split = |n: &'a str| n.rsplit_once('/').unwrap_or(("", n));
    let (dir, base) = name.rsplit_once('/').unwrap_or(("", name));
    let same_dir: Vec<&str> = known
        .iter()
        .map(|k| split(k))
        .filter(|(d, _)| *d == dir)
        .map(|(_, b)| b)
        .collect();
    if let Some(b) = crate::suggest::did_you_mean(base, same_dir.iter().copied()) {
        return known
            .iter()
            .map(String::as_str)
            .find(|k| split(k) == (dir, b));
    }
    crate::suggest::did_you_mean(name, known.iter().map(String::as_str))
        .filter(|k| split(k).0 != dir)
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
