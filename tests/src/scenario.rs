//! Running a scenario application (`dms/apps/*`) on its simulated world,
//! as `sitlogc run APP --format json` does, with the world and the KB given
//! as text (tests change them), on the interpreter or on generated code.
//! Shared by `tests/tests/{home,supermarket}.rs` and the scenario bench.
//! The tests share one Prolog engine per application and back end
//! ([`shared_interpreter`], [`compiled_functions`]); the bench builds one
//! per run ([`interpreter`]).

use sitlog_robot::console::SharedBuf;
use sitlog_robot::{Assets, Format, RunArgs, Runner, Streams, TextFile};
use sitlog_runtime::app::App;
use sitlog_runtime::prolog::{PrologFunctions, PrologSource};
use sitlog_runtime::Functions;
use std::collections::HashMap;
use std::path::Path;
use std::sync::{Arc, Mutex, OnceLock};

/// What a run printed and returned.
pub struct Run {
    /// The conversation and narration (stderr with `--format json`).
    pub transcript: String,
    /// The JSON report.
    pub report: serde_json::Value,
    pub code: u8,
}

/// The application's assets with `world` and, if given, `kb` in place of
/// its files.
pub fn assets(app: &Path, world: &str, kb: Option<&str>) -> Assets {
    let mut assets = Assets::from_app(app).expect("the app's world and KB are readable");
    assets.world = Some(TextFile {
        name: "world.toml".into(),
        text: world.to_owned(),
    });
    if let Some(kb) = kb {
        assets.kb = Some(TextFile {
            name: "knowledge.kb".into(),
            text: kb.to_owned(),
        });
    }
    assets
}

/// Runs `program` with `functions` on `assets`, JSON report.
pub fn execute<A: App>(program: &A, functions: Functions, assets: &Assets) -> Run {
    execute_with(program, functions, assets, true)
}

/// [`execute`], keeping the history or not (`--history none`).
pub fn execute_with<A: App>(
    program: &A,
    functions: Functions,
    assets: &Assets,
    history: bool,
) -> Run {
    let args = RunArgs {
        format: Format::Json,
        history: if history {
            sitlog_robot::cli::HistoryMode::Keep
        } else {
            sitlog_robot::cli::HistoryMode::None
        },
        ..RunArgs::default()
    };
    let (out, err) = (SharedBuf::default(), SharedBuf::default());
    let streams = Streams {
        stdout: Box::new(out.clone()),
        stderr: Box::new(err.clone()),
        stdout_is_terminal: false,
        stderr_is_terminal: false,
    };
    let code = Runner::new(streams).run(program, functions, &args, assets);
    let report = serde_json::from_str(out.text().trim())
        .unwrap_or_else(|e| panic!("not one JSON object ({e}): {}", out.text()));
    Run {
        transcript: err.text(),
        report,
        code,
    }
}

/// The checked IR of `app` and its standard and Prolog functions: what the
/// interpreter runs (a new Prolog engine).
pub fn interpreter(app: &Path) -> (sitlog_compiler::ir::Ir, Functions) {
    interpreter_with(app, false)
}

/// [`interpreter`], with the Prolog engine of `app` shared by the tests of
/// the process where that is sound (see `shared_engine`).
pub fn shared_interpreter(app: &Path) -> (sitlog_compiler::ir::Ir, Functions) {
    interpreter_with(app, true)
}

fn interpreter_with(app: &Path, shared: bool) -> (sitlog_compiler::ir::Ir, Functions) {
    let (result, diags) = crate::check_app(app);
    let checked = result.unwrap_or_else(|_| panic!("{} does not check: {diags:?}", app.display()));
    let ir = sitlog_compiler::ir::lower(&checked);
    let mut functions = Functions::standard();
    let engine = shared
        .then(|| shared_engine(&sitlog_compiler::run::prolog_sources(&ir)))
        .flatten();
    match engine {
        Some(engine) => engine.install(&mut functions),
        None => {
            sitlog_compiler::run::install_prolog(&ir, &mut functions, Default::default())
                .unwrap_or_else(|e| panic!("{e:?}"));
        }
    }
    (ir, functions)
}

/// What a compiled application's `functions()` gives (the standard
/// functions and its embedded Prolog `sources`), its engine shared as
/// [`interpreter`]'s is.
pub fn compiled_functions(sources: &[(&str, &str)]) -> Functions {
    let given: Vec<PrologSource> = sources
        .iter()
        .map(|(name, text)| PrologSource::new(*name, *text))
        .collect();
    let mut functions = Functions::standard();
    match shared_engine(&given) {
        Some(engine) => engine.install(&mut functions),
        None => sitlog_runtime::install_prolog_sources(&mut functions, sources)
            .unwrap_or_else(|e| panic!("{e}")),
    }
    functions
}

/// One engine per set of Prolog sources for the whole test process, built
/// on first use (issue 30: building one takes ~2.5 s in a debug build, and
/// the scenario tests ran two per test). Sound only for code that keeps no
/// state between calls and whose directives only load files: then a run on
/// a used engine is a run on a fresh one (runs of two test threads send
/// their calls to it in turn, each call one query). Other sources (see
/// [`stateless`]) get `None`: a fresh engine per run, as before.
fn shared_engine(sources: &[PrologSource]) -> Option<PrologFunctions> {
    type Key = Vec<(String, String, Option<std::path::PathBuf>)>;
    type Engines = Mutex<HashMap<Key, Arc<OnceLock<PrologFunctions>>>>;
    static ENGINES: OnceLock<Engines> = OnceLock::new();
    if sources.is_empty()
        || !sources
            .iter()
            .all(|s| stateless(&s.text, s.dir.as_deref(), sources, 0))
    {
        return None;
    }
    let key: Key = sources
        .iter()
        .map(|s| (s.name.clone(), s.text.clone(), s.dir.clone()))
        .collect();
    let cell = ENGINES
        .get_or_init(Default::default)
        .lock()
        .unwrap()
        .entry(key)
        .or_default()
        .clone();
    let engine = cell.get_or_init(|| {
        PrologFunctions::load_with(sources, Default::default(), 0, None)
            .unwrap_or_else(|e| panic!("{e:?}"))
    });
    Some(engine.clone())
}

/// Runs on both back ends (the interpreter, its Prolog engine shared as
/// [`shared_interpreter`]'s, and `compiled` with `functions`); they must
/// print the same transcript and report, and the run must end `ok`. The
/// transcript.
pub fn both<A: App>(
    app: &Path,
    compiled: &A,
    compiled_functions: Functions,
    world: &str,
    kb: Option<&str>,
) -> String {
    let assets = assets(app, world, kb);
    let (ir, functions) = shared_interpreter(app);
    let a = execute(&ir, functions, &assets);
    let again = compiled_functions.clone();
    let b = execute(compiled, compiled_functions, &assets);
    assert_eq!(
        a.transcript, b.transcript,
        "interpreted and compiled transcripts differ"
    );
    assert_eq!(
        crate::compiled::canonical_vars(&a.report),
        crate::compiled::canonical_vars(&b.report),
        "interpreted and compiled reports differ"
    );
    assert_eq!(
        a.report["status"], "ok",
        "{}\n{}",
        a.transcript, a.report["error"]
    );
    assert_eq!(a.code, 0);
    // The compiled task runs its native code with the history kept (the
    // default run, compared above) and without (issue 37), where native
    // DM calls stay on the native stack: the same transcript and outcome.
    let c = execute_with(compiled, again, &assets, false);
    assert_eq!(
        a.transcript, c.transcript,
        "compiled without history differs"
    );
    assert_eq!(a.report["status"], c.report["status"]);
    a.transcript
}

/// `text` with each `(from, to)` replaced once (each must be there).
pub fn edit(text: &str, edits: &[(&str, &str)]) -> String {
    let mut w = text.to_owned();
    for (from, to) in edits {
        assert!(w.contains(from), "no `{from}` to replace");
        w = w.replacen(from, to, 1);
    }
    w
}

/// Whether Prolog sources keep no state between calls (moved to the
/// compiler, where `sitlogc test` shares an engine by the same rule).
pub use sitlog_compiler::run::stateless;
