//! A whole program as a run needs it ([`App`]) and one run of it ([`run`]):
//! what the interpreter's IR and generated code both offer. The command
//! line around a run (options, world, KB, transcript, report) is
//! `sitlog-robot`'s, shared by `sitlogc run` and compiled tasks.

use crate::functions::Functions;
use crate::machine::{Actions, DmProgram, Machine, Observer, Options, Outcome, Perception};
use crate::store::Store;
use crate::term::Term;
use crate::vars::Vars;
use sitlog_syntax::{atoms, Atom};

/// A whole program as a run needs it: the DMs plus the initial state.
/// Implemented by the reference interpreter's IR and by generated code.
pub trait App: DmProgram + Sync {
    /// A store for one run (the program's constants in it) and fresh
    /// initial values of the global variables.
    fn initial_state(&self) -> (Store, Vars);
    /// The declared basic actions (`basic_actions.pl`).
    fn basic_actions(&self) -> Vec<Atom>;
    /// Recovery DM per situation type (D-42a), used when the run's options
    /// name none.
    fn recovery(&self) -> Vec<(Atom, Atom)> {
        Vec::new()
    }
    /// A run-time error as the user reads it, pointing at the failing
    /// expression in the source (`color`: ANSI colours); `None` when the
    /// program keeps no source (then the error's own text is shown).
    fn render_error(&self, error: &crate::machine::RunError, color: bool) -> Option<String> {
        let _ = (error, color);
        None
    }
    /// `file:line:col` of the failing expression of a run-time error (the
    /// runner puts it in the error's `location`, so that the JSON report
    /// names it too); `None` when the program keeps no source.
    fn error_location(&self, error: &crate::machine::RunError) -> Option<String> {
        let _ = error;
        None
    }
    /// The program's DMs by name, each with the names of its situations
    /// (the functor of each id), for tools that check a name a person
    /// typed (the debugger's `break`); empty when the program does not
    /// say.
    fn names(&self) -> Vec<(String, Vec<String>)> {
        Vec::new()
    }
}

/// Runs `app` from `main` (a DM call, as a term) with `in_arg` (a term; the
/// atom `none` when absent). `Err` is a problem with the arguments (exit
/// status 2 in a CLI), not a run-time error (those are in the outcome).
#[allow(clippy::too_many_arguments)]
pub fn run<A: App>(
    app: &A,
    main: &str,
    in_arg: Option<&str>,
    options: Options,
    functions: Functions,
    perception: &mut dyn Perception,
    actions: &mut dyn Actions,
    observer: Option<&mut dyn Observer>,
) -> Result<(Outcome, Store), String> {
    let (mut store, globals) = app.initial_state();
    let limits = options.input_limits;
    // The option and its text (when short) name the input in errors.
    let named = |option: &str, text: &str| match text.len() {
        0..=80 => format!("{option} `{text}`"),
        _ => option.to_owned(),
    };
    let main_term = limits.read_term(&named("--main", main), main)?;
    let main_term = store.from_clause(&main_term).0;
    let in_arg = match in_arg {
        Some(text) => {
            let clause = limits.read_term(&named("--in-arg", text), text)?;
            store.from_clause(&clause).0
        }
        None => Term::atom(atoms::NONE),
    };
    match store.functor(main_term) {
        Some((name, _)) if app.dm_by_name(name).is_none() => {
            return Err(format!("the application has no DM named `{name}`"))
        }
        Some(_) => {}
        None => return Err(format!("--main `{main}` is not a DM name")),
    }
    let mut options = options;
    if options.recovery.is_empty() {
        options.recovery = app.recovery();
    }
    let machine = Machine::new(app, store, globals, functions, options);
    Ok(machine.run(main_term, in_arg, perception, actions, observer))
}
