//! Running a program from the command line in test mode: the part of
//! `sitlogc run` that compiled programs share (generated `main`s call
//! [`main`]; `sitlogc run` parses its options with clap and calls
//! [`execute`]). The option set and output contract are the notes'
//! "Our convention for `sitlogc run` output".

use crate::functions::Functions;
use crate::machine::{Actions, DmProgram, Machine, Observer, Options, Outcome, Perception};
use crate::report;
use crate::store::Store;
use crate::term::Term;
use crate::testmode::{PromptPerception, ScriptPerception, TextActions};
use crate::vars::Vars;
use sitlog_syntax::{atoms, Atom};
use std::io::Write;
use std::path::PathBuf;

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
    let main_term = store
        .parse(main)
        .map_err(|e| format!("--main `{main}`: {}", e.message))?
        .0;
    let in_arg = match in_arg {
        Some(text) => {
            store
                .parse(text)
                .map_err(|e| format!("--in-arg `{text}`: {}", e.message))?
                .0
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

/// Output format of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// The papers' history listing, then `Out Arg:` and `Out Global Vars:`.
    Text,
    /// One JSON object on stdout.
    Json,
}

/// The options of `sitlogc run` (after the application).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunArgs {
    /// The DM to start, as a term (default `main`).
    pub main: String,
    /// The initial pipe value, as a term (default: the atom `none`).
    pub in_arg: Option<String>,
    /// Test-mode inputs; stdin (with prompts) when absent.
    pub script: Option<PathBuf>,
    pub format: Format,
    /// `--history keep` (default) or `none`.
    pub keep_history: bool,
    /// Write one JSON object per transition to this file.
    pub trace: Option<PathBuf>,
}

impl Default for RunArgs {
    fn default() -> RunArgs {
        RunArgs {
            main: "main".to_owned(),
            in_arg: None,
            script: None,
            format: Format::Text,
            keep_history: true,
            trace: None,
        }
    }
}

/// The usage text of a compiled program.
pub const USAGE: &str = "\
Runs the compiled SitLog task in test mode.

Usage: PROGRAM [OPTIONS]

Options:
      --main <DM>        The DM to start, as a term (it may have arguments) [default: main]
      --in-arg <TERM>    The initial pipe value, as a term (default: the atom `none`)
      --script <FILE>    Read the inputs of test mode from FILE instead of stdin
      --format <FORMAT>  text: the papers' history listing; json: one JSON object on stdout
                         [default: text] [possible values: text, json]
      --history <MODE>   none keeps no history [default: keep] [possible values: keep, none]
      --trace <FILE>     Write one JSON object per transition to FILE as it happens
  -h, --help             Print help
";

/// What the command line asked for.
#[derive(Debug, PartialEq, Eq)]
pub enum Parsed {
    Run(RunArgs),
    Help,
}

impl RunArgs {
    /// Parses the options (without the program name); `Err` is a usage
    /// error message. Accepts `--opt value` and `--opt=value`.
    pub fn parse<I: IntoIterator<Item = String>>(args: I) -> Result<Parsed, String> {
        let mut out = RunArgs::default();
        let mut it = args.into_iter();
        while let Some(arg) = it.next() {
            if arg == "-h" || arg == "--help" {
                return Ok(Parsed::Help);
            }
            let (name, inline) = match arg.split_once('=') {
                Some((n, v)) if n.starts_with("--") => (n.to_owned(), Some(v.to_owned())),
                _ => (arg.clone(), None),
            };
            let known = [
                "--main",
                "--in-arg",
                "--script",
                "--format",
                "--history",
                "--trace",
            ];
            if !known.contains(&name.as_str()) {
                return Err(format!("unexpected argument `{arg}`"));
            }
            let value = match inline {
                Some(v) => v,
                None => it
                    .next()
                    .ok_or_else(|| format!("a value is required for `{name}`"))?,
            };
            match name.as_str() {
                "--main" => out.main = value,
                "--in-arg" => out.in_arg = Some(value),
                "--script" => out.script = Some(PathBuf::from(value)),
                "--trace" => out.trace = Some(PathBuf::from(value)),
                "--format" => {
                    out.format = match value.as_str() {
                        "text" => Format::Text,
                        "json" => Format::Json,
                        _ => {
                            return Err(format!(
                                "invalid value `{value}` for `--format` (text, json)"
                            ))
                        }
                    }
                }
                "--history" => {
                    out.keep_history = match value.as_str() {
                        "keep" => true,
                        "none" => false,
                        _ => {
                            return Err(format!(
                                "invalid value `{value}` for `--history` (keep, none)"
                            ))
                        }
                    }
                }
                _ => unreachable!("checked above"),
            }
        }
        Ok(Parsed::Run(out))
    }
}

/// Runs `app` as `sitlogc run` does: script or prompt input, actions on
/// stderr, the report on stdout; returns the exit status (0 ok, 1 run-time
/// error, 2 usage or I/O problem).
pub fn execute<A: App>(app: &A, functions: Functions, args: &RunArgs) -> u8 {
    let mut perception: Box<dyn Perception> = match &args.script {
        Some(path) => match std::fs::read_to_string(path) {
            Ok(text) => Box::new(ScriptPerception::new(path.display().to_string(), text)),
            Err(e) => {
                eprintln!("error: cannot read script {}: {e}", path.display());
                return 2;
            }
        },
        None => Box::new(PromptPerception::new(std::io::stdin().lock())),
    };
    let mut trace = match &args.trace {
        Some(path) => match std::fs::File::create(path) {
            Ok(f) => Some(report::JsonTrace::new(std::io::BufWriter::new(f))),
            Err(e) => {
                eprintln!("error: cannot create trace file {}: {e}", path.display());
                return 2;
            }
        },
        None => None,
    };
    let mut actions = TextActions::new(std::io::stderr(), app.basic_actions());
    let options = Options {
        keep_history: args.keep_history,
        ..Options::default()
    };
    let observer = trace.as_mut().map(|t| t as &mut dyn Observer);
    let (outcome, mut store) = match run(
        app,
        &args.main,
        args.in_arg.as_deref(),
        options,
        functions,
        perception.as_mut(),
        &mut actions,
        observer,
    ) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return 2;
        }
    };
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    match args.format {
        Format::Json => {
            let _ = writeln!(out, "{}", report::outcome_json(&store, &outcome));
        }
        Format::Text => {
            let _ = write!(out, "{}", report::outcome_text(&mut store, &outcome));
        }
    }
    if let Err(e) = &outcome.result {
        eprintln!("error: {e}");
        1
    } else {
        0
    }
}

/// The `main` of a compiled program: parses `std::env::args`, runs on a
/// thread with a big stack (as `sitlogc` does), returns the exit status.
pub fn main<A: App>(app: &A, functions: Functions) -> std::process::ExitCode {
    let args = match RunArgs::parse(std::env::args().skip(1)) {
        Ok(Parsed::Run(a)) => a,
        Ok(Parsed::Help) => {
            print!("{USAGE}");
            return std::process::ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("error: {e}\n\n{USAGE}");
            return std::process::ExitCode::from(2);
        }
    };
    let code = std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(256 * 1024 * 1024)
            .spawn_scoped(s, || execute(app, functions, &args))
            .map(|h| h.join().unwrap_or(101))
            .unwrap_or(101)
    });
    std::process::ExitCode::from(code)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<Parsed, String> {
        RunArgs::parse(args.iter().map(|s| s.to_string()))
    }

    #[test]
    fn options_parse() {
        let Ok(Parsed::Run(a)) = parse(&[
            "--main",
            "m(1)",
            "--in-arg=-3",
            "--format",
            "json",
            "--history",
            "none",
            "--script",
            "s.txt",
        ]) else {
            panic!()
        };
        assert_eq!(a.main, "m(1)");
        assert_eq!(a.in_arg.as_deref(), Some("-3"));
        assert_eq!(a.format, Format::Json);
        assert!(!a.keep_history);
        assert_eq!(a.script, Some(PathBuf::from("s.txt")));
        assert_eq!(parse(&["--help"]), Ok(Parsed::Help));
        assert!(parse(&["--format", "xml"]).is_err());
        assert!(parse(&["--main"]).is_err());
        assert!(parse(&["app"]).is_err());
    }
}
