//! Helpers shared by the workspace integration tests in `tests/tests/`:
//! running an example application in test mode and comparing results.

pub mod alloc;
pub mod compiled;
#[path = "../gen/random_dm.rs"]
pub mod random_dm;
pub mod scenario;
pub mod world_functions;

use sitlog_compiler::run::{self, RunConfig};
use sitlog_runtime::machine::Options;
use sitlog_runtime::report;
use sitlog_runtime::testmode::{ScriptPerception, TextActions};
use sitlog_runtime::{atoms, Functions, Term};
use std::path::{Path, PathBuf};

/// The workspace root.
pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// The behaviour library as the repository holds it (`dms/behaviors/`,
/// named `behaviors/...`): what `sitlogc` embeds.
pub fn library() -> &'static sitlog_compiler::load::Library {
    use sitlog_compiler::load::{Library, LibraryFiles, LibraryRoot};
    static LIBRARY: std::sync::OnceLock<Library> = std::sync::OnceLock::new();
    LIBRARY.get_or_init(|| Library {
        roots: vec![LibraryRoot {
            what: "the repository's dms/".to_owned(),
            files: LibraryFiles::Dir(workspace().join("dms")),
        }],
    })
}

/// Loads and checks an application as `sitlogc` does: the simulated
/// robot's functions ([`sitlog_robot::WORLD_FUNCTIONS`]) and the behaviour
/// library ([`library`]) are known.
pub fn check_app(
    app: &Path,
) -> (
    Result<sitlog_compiler::check::Checked, sitlog_compiler::ast::Program>,
    Vec<sitlog_compiler::diag::Diagnostic>,
) {
    let options = sitlog_compiler::check::CheckOptions {
        world_functions: sitlog_robot::WORLD_FUNCTIONS,
        library: Some(library()),
        ..Default::default()
    };
    sitlog_compiler::check_path_opts(app, options)
        .unwrap_or_else(|e| panic!("{} is not readable: {e}", app.display()))
}

/// Rust versions of the Appendix A user functions `f`, `g` and `h`
/// (Listing A5), used until Prolog user functions run.
pub fn appendix_a_functions(functions: &mut Functions) {
    // f(X): `ok` if X is the local variable `day`, else `'not ok'`.
    functions.register("f", 1, |call, args| {
        let get = call.store.parse("get(day, Day)").map_err(|e| e.message)?.0;
        let day = call.var_op(get)?;
        let ok = call.store.identical(args[0], day);
        Ok(Term::atom(sitlog_runtime::Atom::intern(if ok {
            "ok"
        } else {
            "not ok"
        })))
    });
    // g(_): the last transition of the current DM.
    functions.register("g", 1, |call, _| {
        Ok(sitlog_runtime::functions::standard::last_transition(call))
    });
    // h(X, Y): `is` if X == Y, else `rs`.
    functions.register("h", 2, |call, args| {
        let same = call.store.identical(args[0], args[1]);
        Ok(Term::atom(sitlog_runtime::Atom::intern(if same {
            "is"
        } else {
            "rs"
        })))
    });
    let _ = atoms::NIL;
}

/// Options of an example run, read from the optional `run.args` file of the
/// application: lines `main=TERM`, `in_arg=TERM`, `functions=appendix_a`.
pub struct ExampleArgs {
    pub main: String,
    pub in_arg: Option<String>,
    pub appendix_a: bool,
}

pub fn example_args(app: &Path) -> ExampleArgs {
    let mut args = ExampleArgs {
        main: "main".into(),
        in_arg: None,
        appendix_a: app.file_name().is_some_and(|n| n == "appendix_a"),
    };
    if let Ok(text) = std::fs::read_to_string(app.join("run.args")) {
        for line in text.lines() {
            if let Some(v) = line.strip_prefix("main=") {
                args.main = v.trim().to_owned();
            } else if let Some(v) = line.strip_prefix("in_arg=") {
                args.in_arg = Some(v.trim().to_owned());
            }
        }
    }
    args
}

/// Runs an example application on its `script.txt`; returns the JSON report.
pub fn run_example(app: &Path) -> serde_json::Value {
    let (result, diags) = sitlog_compiler::check_path(app).expect("example is readable");
    let checked = match result {
        Ok(c) => c,
        Err(_) => panic!("{} does not check: {diags:#?}", app.display()),
    };
    let ir = sitlog_compiler::ir::lower(&checked);
    let mut functions = Functions::standard();
    // With the `prolog` feature the application's own user_functions.pl
    // runs; without it, Appendix A falls back to the Rust stand-ins.
    #[cfg(feature = "prolog")]
    if let Err(errors) = run::install_prolog(&ir, &mut functions, Default::default()) {
        panic!("{}: Prolog files do not load: {errors:?}", app.display());
    }
    #[cfg(not(feature = "prolog"))]
    if example_args(app).appendix_a {
        appendix_a_functions(&mut functions);
    }
    run_example_ir(app, &ir, functions, Options::default())
}

/// [`run_example`] with the machine's `options` (`keep_history: false` is
/// `--history none`), on the Prolog engine the test process shares for the
/// application's sources where that is sound
/// ([`scenario::shared_interpreter`]): runs of one example with other
/// options start no engine of their own.
pub fn run_example_shared(app: &Path, options: Options) -> serde_json::Value {
    let (ir, functions) = scenario::shared_interpreter(app);
    run_example_ir(app, &ir, functions, options)
}

/// The example's scripted input (`script.txt`; none: an empty script).
pub(crate) fn example_perception(app: &Path) -> ScriptPerception {
    let script = std::fs::read_to_string(app.join("script.txt")).unwrap_or_default();
    ScriptPerception::new("script.txt", script)
}

fn run_example_ir(
    app: &Path,
    ir: &sitlog_compiler::ir::Ir,
    functions: Functions,
    options: Options,
) -> serde_json::Value {
    let args = example_args(app);
    let mut perception = crate::example_perception(app);
    let mut actions = TextActions::new(std::io::sink(), ir.basic_actions.clone());
    let config = RunConfig {
        main: args.main,
        in_arg: args.in_arg,
        options,
        functions,
    };
    let (outcome, store) =
        run::run(ir, config, &mut perception, &mut actions, None).expect("valid run config");
    serde_json::from_str(&report::outcome_json(&store, &outcome)).expect("report is JSON")
}

/// Replaces every variable name (`_G12`, `_123`, `_`) in the TERM strings
/// of a report by `_`, so that reports compare regardless of numbering.
pub fn normalize(v: &serde_json::Value) -> serde_json::Value {
    use serde_json::Value;
    match v {
        Value::String(s) => Value::String(normalize_vars(s)),
        Value::Array(items) => Value::Array(items.iter().map(normalize).collect()),
        Value::Object(map) => {
            Value::Object(map.iter().map(|(k, v)| (k.clone(), normalize(v))).collect())
        }
        other => other.clone(),
    }
}

/// Every variable name of a term's text written `_` (see [`map_vars`]).
pub fn normalize_vars(s: &str) -> String {
    map_vars(s, |_| "_".to_owned())
}

/// Rewrites every variable name (`_G12`, `_123`, `_`) outside quoted atoms
/// and strings of a term's text (or of an error message quoting terms)
/// through `rename`.
pub fn map_vars(s: &str, mut rename: impl FnMut(&str) -> String) -> String {
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars().peekable();
    let mut in_quote: Option<char> = None;
    let mut prev_alnum = false;
    while let Some(c) = chars.next() {
        if let Some(q) = in_quote {
            out.push(c);
            if c == '\\' {
                if let Some(n) = chars.next() {
                    out.push(n);
                }
            } else if c == q {
                in_quote = None;
            }
            prev_alnum = false;
            continue;
        }
        // A quote right after a letter or digit opens nothing: Prolog
        // never writes one there, but prose does (`the DM's identifier`
        // in an error message).
        if (c == '\'' || c == '"') && !prev_alnum {
            in_quote = Some(c);
            out.push(c);
            prev_alnum = false;
            continue;
        }
        if c == '_' && !prev_alnum {
            let mut name = String::from("_");
            while let Some(&n) = chars.peek() {
                if n.is_alphanumeric() || n == '_' {
                    name.push(n);
                    chars.next();
                } else {
                    break;
                }
            }
            out.push_str(&rename(&name));
            prev_alnum = true;
            continue;
        }
        prev_alnum = c.is_alphanumeric() || c == '_';
        out.push(c);
    }
    out
}

/// Checks, lowers and runs in-memory sources (`name`, `text`) with a script;
/// returns the JSON report (as a JSON string when it nests deeper than
/// serde_json parses). Panics with the diagnostics if they do not check.
pub fn run_sources(
    files: &[(&str, &str)],
    script: &str,
    main: &str,
    in_arg: Option<&str>,
    options: Options,
) -> serde_json::Value {
    run_sources_with(files, script, main, in_arg, options, Functions::standard())
}

pub fn run_sources_with(
    files: &[(&str, &str)],
    script: &str,
    main: &str,
    in_arg: Option<&str>,
    options: Options,
    functions: Functions,
) -> serde_json::Value {
    let (mut program, diags) = sitlog_compiler::load::load_sources(files);
    // The functions registered here are the host's; names that resolve
    // nowhere are left to the machine (as `--allow-unresolved` does), whose
    // run-time errors these tests observe.
    program.host_functions.extend(functions.names());
    let (result, diags) = sitlog_compiler::check::check_with(program, diags, true);
    let checked = match result {
        Ok(c) => c,
        Err(p) => {
            let text: Vec<String> = diags
                .iter()
                .map(|d| sitlog_compiler::diag::render_short(d, &p.sources))
                .collect();
            panic!("sources do not check:\n{}", text.join("\n"));
        }
    };
    let ir = sitlog_compiler::ir::lower(&checked);
    let mut perception = ScriptPerception::new("script", script.to_owned());
    let mut actions = TextActions::new(std::io::sink(), ir.basic_actions.clone());
    let config = RunConfig {
        main: main.to_owned(),
        in_arg: in_arg.map(str::to_owned),
        options,
        functions,
    };
    let (outcome, store) =
        run::run(&ir, config, &mut perception, &mut actions, None).expect("valid run config");
    let text = report::outcome_json(&store, &outcome);
    serde_json::from_str(&text).unwrap_or(serde_json::Value::String(text))
}
