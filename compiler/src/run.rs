//! Running a checked program: the IR (through the interpreter's plans, or
//! from its templates) handed to the one runner, `sitlog_runtime::app::run`,
//! with the run's configuration as one value; and the application's Prolog
//! user functions installed in the embedded engine. The command line's
//! runner (`sitlog_robot`) calls the same `app::run`.

use crate::interp::Resolved;
use crate::ir::Ir;
use sitlog_runtime::app::App;
use sitlog_runtime::machine::{Actions, Observer, Options, Outcome, Perception};
use sitlog_runtime::{Functions, Store};

/// What to run and how.
pub struct RunConfig {
    /// The main DM call, as a term (`main` by default; may have arguments).
    pub main: String,
    /// The initial pipe value as a term (`none` when absent).
    pub in_arg: Option<String>,
    pub options: Options,
    pub functions: Functions,
}

impl Default for RunConfig {
    fn default() -> Self {
        RunConfig {
            main: "main".to_owned(),
            in_arg: None,
            options: Options::default(),
            functions: Functions::standard(),
        }
    }
}

/// A problem with the run's arguments (exit status 2 in the CLI).
#[derive(Debug)]
pub struct ConfigError(pub String);

impl std::fmt::Display for ConfigError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// Runs `ir` from `config.main`; returns the outcome and the store its terms live in.
///
/// The situations [`Resolved`] can plan run from their plans, the others
/// from their templates ([`run_unresolved`] runs every one from its template).
pub fn run(
    ir: &Ir,
    config: RunConfig,
    perception: &mut dyn Perception,
    actions: &mut dyn Actions,
    observer: Option<&mut dyn Observer>,
) -> Result<(Outcome, Store), ConfigError> {
    let resolved = Resolved::new(ir);
    run_program(&resolved, config, perception, actions, observer)
}

/// [`run`], every situation instantiated from its template (the reference
/// path the plans are compared with).
pub fn run_unresolved(
    ir: &Ir,
    config: RunConfig,
    perception: &mut dyn Perception,
    actions: &mut dyn Actions,
    observer: Option<&mut dyn Observer>,
) -> Result<(Outcome, Store), ConfigError> {
    run_program(ir, config, perception, actions, observer)
}

fn run_program<P: App>(
    program: &P,
    config: RunConfig,
    perception: &mut dyn Perception,
    actions: &mut dyn Actions,
    observer: Option<&mut dyn Observer>,
) -> Result<(Outcome, Store), ConfigError> {
    sitlog_runtime::app::run(
        program,
        &config.main,
        config.in_arg.as_deref(),
        config.options,
        config.functions,
        perception,
        actions,
        observer,
    )
    .map_err(ConfigError)
}

/// Starts the embedded Prolog engine with the application's templates.pl
/// and user_functions.pl and installs it as the fallback of `functions`
/// (Rust functions keep precedence). `Ok(None)` when the application has
/// no Prolog file. Errors carry `file:line:col`.
#[cfg(feature = "prolog")]
pub fn install_prolog(
    ir: &Ir,
    functions: &mut Functions,
    options: sitlog_runtime::prolog::PrologOptions,
) -> Result<
    Option<sitlog_runtime::prolog::PrologFunctions>,
    Vec<sitlog_runtime::prolog::PrologLoadError>,
> {
    install_prolog_with(ir, functions, options, Vec::new(), None)
}

/// [`install_prolog`], with `before` loaded ahead of the application's
/// files (the `--legacy` profile's Prolog layer of the original), served by
/// `native` if given.
#[cfg(feature = "prolog")]
pub fn install_prolog_with(
    ir: &Ir,
    functions: &mut Functions,
    options: sitlog_runtime::prolog::PrologOptions,
    before: Vec<sitlog_runtime::prolog::PrologSource>,
    native: Option<sitlog_runtime::prolog::NativeKb>,
) -> Result<
    Option<sitlog_runtime::prolog::PrologFunctions>,
    Vec<sitlog_runtime::prolog::PrologLoadError>,
> {
    use sitlog_runtime::prolog::PrologFunctions;
    if ir.prolog_sources.is_empty() && before.is_empty() {
        return Ok(None);
    }
    let layer = before.len();
    let mut sources = before;
    sources.extend(prolog_sources(ir));
    let prolog = PrologFunctions::load_with(&sources, options, layer, native)?;
    prolog.install(functions);
    Ok(Some(prolog))
}

/// The application's Prolog files as the engine loads them (each with its
/// directory, for the files it consults by a relative name).
#[cfg(feature = "prolog")]
pub fn prolog_sources(ir: &Ir) -> Vec<sitlog_runtime::prolog::PrologSource> {
    ir.prolog_sources
        .iter()
        .map(|f| sitlog_runtime::prolog::PrologSource {
            name: f.name.clone(),
            text: f.text.clone(),
            dir: f.path.parent().map(|d| d.to_path_buf()),
            clauses: f.clauses.clone(),
        })
        .collect()
}

/// Whether an engine loaded from `sources` may serve several runs, one
/// after another or from several threads (each call one query): every
/// source is [`stateless`]. `sitlogc test` and the workspace's scenario
/// tests share one engine then.
#[cfg(feature = "prolog")]
pub fn shareable(sources: &[sitlog_runtime::prolog::PrologSource]) -> bool {
    !sources.is_empty()
        && sources
            .iter()
            .all(|s| stateless(&s.text, s.dir.as_deref(), sources, 0))
}

/// Whether Prolog `text` (and the files it consults: one of `given`, whose
/// text the caller checks, else found as the engine finds it, from `dir`
/// or its nearest ancestor that has the path) has no directive but
/// `consult/1` and `ensure_loaded/1` and no word that could keep state
/// between calls. Conservative: a file it cannot find, or such a word
/// anywhere (even in a comment), says no.
#[cfg(feature = "prolog")]
pub fn stateless(
    text: &str,
    dir: Option<&std::path::Path>,
    given: &[sitlog_runtime::prolog::PrologSource],
    depth: usize,
) -> bool {
    const STATEFUL: &[&str] = &[
        "assert",
        "asserta",
        "assertz",
        "retract",
        "retractall",
        "abolish",
        "b_setval",
        "nb_setval",
        "bb_put",
        "bb_b_put",
        "flag",
        "random",
        "random_between",
        "random_member",
        "set_random",
        "gensym",
        "recorda",
        "recordz",
        "erase",
        "set_prolog_flag",
        "op",
        "dynamic",
    ];
    let words = text
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty());
    if depth > 8 || words.clone().any(|w| STATEFUL.contains(&w)) {
        return false;
    }
    text.lines().all(|line| {
        let line = line.trim_start();
        if !line.starts_with(":-") {
            return true;
        }
        let Some(rest) = line
            .strip_prefix(":- consult('")
            .or_else(|| line.strip_prefix(":- ensure_loaded('"))
        else {
            return false;
        };
        let Some(name) = rest.split('\'').next() else {
            return false;
        };
        let with_pl = format!("{name}.pl");
        if given.iter().any(|s| {
            let path = std::path::Path::new(&s.name);
            path.ends_with(name) || path.ends_with(&with_pl)
        }) {
            return true;
        }
        let Some(dir) = dir else {
            return false;
        };
        let found = dir.ancestors().map(|d| d.join(name)).find(|p| p.is_file());
        match found.and_then(|p| std::fs::read_to_string(&p).ok().map(|t| (p, t))) {
            Some((path, text)) => stateless(&text, path.parent(), given, depth + 1),
            None => false,
        }
    })
}
