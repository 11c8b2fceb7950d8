//! Running a checked program in test mode: the glue between the IR, the
//! runtime machine and test-mode input/output, shared by `sitlogc run` and
//! the tests.

use crate::ir::Ir;
use crate::resolve::Resolved;
use sitlog_runtime::machine::{
    Actions, DmProgram, Machine, Observer, Options, Outcome, Perception,
};
use sitlog_runtime::{Functions, Store, Term};
use sitlog_syntax::atoms;

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
    run_program(ir, &resolved, config, perception, actions, observer)
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
    run_program(ir, ir, config, perception, actions, observer)
}

fn run_program<P: DmProgram>(
    ir: &Ir,
    program: &P,
    config: RunConfig,
    perception: &mut dyn Perception,
    actions: &mut dyn Actions,
    observer: Option<&mut dyn Observer>,
) -> Result<(Outcome, Store), ConfigError> {
    let (mut store, globals) = ir.initial_state();
    let main = store
        .parse(&config.main)
        .map_err(|e| ConfigError(format!("--main `{}`: {}", config.main, e.message)))?
        .0;
    let in_arg = match &config.in_arg {
        Some(text) => {
            store
                .parse(text)
                .map_err(|e| ConfigError(format!("--in-arg `{text}`: {}", e.message)))?
                .0
        }
        None => Term::atom(atoms::NONE),
    };
    if let Some((name, _)) = store.functor(main) {
        if ir.dm_by_name(name).is_none() {
            return Err(ConfigError(format!(
                "the application has no DM named `{name}`"
            )));
        }
    } else {
        return Err(ConfigError(format!(
            "--main `{}` is not a DM name",
            config.main
        )));
    }
    let mut options = config.options;
    if options.recovery.is_empty() {
        options.recovery = ir.recovery.clone();
    }
    let machine = Machine::new(program, store, globals, config.functions, options);
    let (outcome, store) = machine.run(main, in_arg, perception, actions, observer);
    Ok((outcome, store))
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
    use sitlog_runtime::prolog::{PrologFunctions, PrologSource};
    if ir.prolog_sources.is_empty() && before.is_empty() {
        return Ok(None);
    }
    let layer = before.len();
    let mut sources = before;
    let app: Vec<PrologSource> = ir
        .prolog_sources
        .iter()
        .map(|f| PrologSource {
            name: f.name.clone(),
            text: f.text.clone(),
            dir: f.path.parent().map(|d| d.to_path_buf()),
        })
        .collect();
    sources.extend(app);
    let prolog = PrologFunctions::load_with(&sources, options, layer, native)?;
    prolog.install(functions);
    Ok(Some(prolog))
}
