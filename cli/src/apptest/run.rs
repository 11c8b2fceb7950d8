//! Running the tests of an application: each [`Case`] on the interpreter
//! through the runner of `sitlogc run` (`sitlog_robot::Runner`, on captured
//! streams), its transitions recorded, then its expectations checked
//! (`check`). [`run_all`] runs the cases on worker threads and gives the
//! results in the cases' order.
//!
//! A run never hangs a test: it stops after `expect.max_transitions`
//! transitions (a failure), or after [`DEFAULT_MAX_TRANSITIONS`].

use super::case::{Case, Input, Status};
use sitlog_robot::console::SharedBuf;
use sitlog_robot::interrupt::Interrupt;
use sitlog_robot::{Assets, Format, RunArgs, Runner, SandboxMode, Streams, TextFile};
use sitlog_runtime::history::Entry;
use sitlog_runtime::machine::Observer;
use sitlog_runtime::report::JsonTrace;
use sitlog_runtime::{Store, Term};
use std::path::Path;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Transitions after which a test without `expect.max_transitions` stops.
pub const DEFAULT_MAX_TRANSITIONS: u64 = 200_000;

/// What one test did.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub name: String,
    /// The test file, as named in messages.
    pub file: String,
    /// Why it failed (empty: it passed). Each names the expectation's
    /// `file:line:col` where it has one.
    pub failures: Vec<String>,
    /// Lines shown with a failure: the output with the expected lines
    /// marked, or a diff against the golden file.
    pub detail: String,
    /// What the run printed (stdout: the conversation and the report).
    pub stdout: String,
    /// Its messages and, in test mode, its rendered actions.
    pub stderr: String,
    /// The run's transitions (JSON lines, as `sitlogc run --trace` writes).
    pub trace: String,
    pub transitions: u64,
    pub elapsed: Duration,
}

impl Outcome {
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }
}

/// Records a run's transitions and stops it after `limit` of them.
struct Recorder {
    trace: JsonTrace<SharedBuf>,
    count: Arc<AtomicU64>,
    limit: u64,
    stop: Arc<std::sync::atomic::AtomicBool>,
}

impl Observer for Recorder {
    fn transition(&mut self, store: &Store, entry: &Entry, depth: usize, next: Option<Term>) {
        self.trace.transition(store, entry, depth, next);
        if self.count.fetch_add(1, Ordering::Relaxed) + 1 >= self.limit {
            self.stop.store(true, Ordering::SeqCst);
        }
    }

    fn unmatched(&mut self, store: &Store, dm: Term, situation: Term, input: Term, depth: usize) {
        self.trace.unmatched(store, dm, situation, input, depth);
    }
}

/// What every test of an application shares: the checked program, its
/// assets, and where it is.
pub struct Suite<'a> {
    pub app: &'a Path,
    pub ir: &'a sitlog_compiler::ir::Ir,
    pub assets: &'a Assets,
    /// One Prolog engine for every test, when the application's Prolog
    /// keeps no state between calls ([`shared_engine`]); else each test
    /// starts its own.
    pub engine: Option<sitlog_runtime::prolog::PrologFunctions>,
}

/// The engine the tests of `ir` may share: its Prolog sources loaded once,
/// when they keep no state between calls
/// (`sitlog_compiler::run::shareable`); `None` otherwise, or when they do
/// not load (each test then reports why).
pub fn shared_engine(
    ir: &sitlog_compiler::ir::Ir,
) -> Option<sitlog_runtime::prolog::PrologFunctions> {
    let sources = sitlog_compiler::run::prolog_sources(ir);
    if !sitlog_compiler::run::shareable(&sources) {
        return None;
    }
    sitlog_runtime::prolog::PrologFunctions::load_with(&sources, Default::default(), 0, None).ok()
}

/// Runs `case` (its file's text `case_text`) and checks it.
pub fn run_case(suite: &Suite<'_>, case: &Case, case_text: &str) -> Outcome {
    let started = Instant::now();
    let mut outcome = Outcome {
        name: case.name.clone(),
        file: case.path.display().to_string(),
        failures: Vec::new(),
        detail: String::new(),
        stdout: String::new(),
        stderr: String::new(),
        trace: String::new(),
        transitions: 0,
        elapsed: Duration::ZERO,
    };
    let mut assets = suite.assets.clone();
    let mut args = RunArgs {
        format: Format::Text,
        // each test's run is a task: confined as `sitlogc run` confines one
        sandbox: SandboxMode::Auto,
        ..RunArgs::default()
    };
    if let Some(main) = &case.main {
        args.main = main.clone();
    }
    args.in_arg = case.in_arg.clone();
    // a script is read from a file: kept until the run ends
    let mut _script_file = None;
    match &case.input {
        Input::World(spec) => {
            let base = match &spec.file {
                Some(path) => match super::read_text(path) {
                    Ok(text) => Some(TextFile {
                        name: path.display().to_string(),
                        text,
                    }),
                    Err(e) => {
                        outcome
                            .failures
                            .push(format!("cannot read the test's world: {e}"));
                        return finish(outcome, started);
                    }
                },
                None => assets.world.clone(),
            };
            let Some(base) = base else {
                outcome.failures.push(format!(
                    "{}: the test changes or needs a world, but {} has no world.toml (give `[world] file`, or `script` for test mode)",
                    case.path.display(),
                    suite.app.display()
                ));
                return finish(outcome, started);
            };
            let text = match super::case::world_text(
                spec, &base.name, &base.text, &case.path, case_text,
            ) {
                Ok(t) => t,
                Err(errors) => {
                    outcome
                        .failures
                        .extend(errors.iter().map(ToString::to_string));
                    return finish(outcome, started);
                }
            };
            let name = if spec == &Default::default() {
                base.name
            } else {
                format!("{} (as {} changes it)", base.name, case.path.display())
            };
            assets.world = Some(TextFile { name, text });
        }
        Input::Script { name, text } => {
            args.no_world = true;
            match tempfile::NamedTempFile::new().and_then(|mut f| {
                use std::io::Write;
                f.write_all(text.as_bytes())?;
                f.flush()?;
                Ok(f)
            }) {
                Ok(f) => {
                    args.script = Some(f.path().to_path_buf());
                    _script_file = Some(f);
                }
                Err(e) => {
                    outcome
                        .failures
                        .push(format!("cannot write the script of {name}: {e}"));
                    return finish(outcome, started);
                }
            }
        }
    }

    let mut functions = sitlog_runtime::Functions::standard();
    if let Some(engine) = &suite.engine {
        engine.install(&mut functions);
    } else if let Err(errors) = sitlog_compiler::run::install_prolog_with(
        suite.ir,
        &mut functions,
        Default::default(),
        Vec::new(),
        None,
    ) {
        outcome.failures.extend(
            errors
                .iter()
                .map(|e| format!("the application's Prolog files: {e}")),
        );
        return finish(outcome, started);
    }

    let (out, err, actions) = (
        SharedBuf::default(),
        SharedBuf::default(),
        SharedBuf::default(),
    );
    let streams = Streams {
        stdout: Box::new(out.clone()),
        stderr: Box::new(err.clone()),
        stdout_is_terminal: false,
        stderr_is_terminal: false,
    };
    let interrupt = Interrupt::new();
    let limit = case
        .expect
        .max_transitions
        .map(|n| n + 1)
        .unwrap_or(DEFAULT_MAX_TRANSITIONS);
    let count = Arc::new(AtomicU64::new(0));
    let trace = SharedBuf::default();
    let recorder = Recorder {
        trace: JsonTrace::new(trace.clone()),
        count: count.clone(),
        limit,
        stop: interrupt.flag.clone(),
    };
    let kb: Arc<Mutex<Option<sitlog_robot::kb_services::SharedKb>>> = Arc::default();
    let kb_slot = kb.clone();
    let resolved = sitlog_compiler::interp::Resolved::new(suite.ir);
    let actions_out = actions.clone();
    let run = move || {
        Runner::new(streams)
            .interrupt(interrupt)
            .observe(Box::new(recorder))
            .actions_to(Box::new(actions_out))
            .kb_probe(Box::new(move |k| {
                if let Ok(mut slot) = kb_slot.lock() {
                    *slot = Some(k);
                }
            }))
            .run(&resolved, functions, &args, &assets)
    };
    // The task runs on a thread of its own: the operating system's sandbox
    // (Landlock binds the thread that enters it and the threads it starts)
    // confines that run, not this worker, which goes on to write the next
    // test's files (issue 38).
    let code = std::thread::scope(|scope| {
        std::thread::Builder::new()
            .stack_size(256 * 1024 * 1024)
            .spawn_scoped(scope, run)
            .map(|h| h.join())
    });
    let code = match code {
        Ok(Ok(code)) => code,
        Ok(Err(panic)) => std::panic::resume_unwind(panic),
        Err(e) => {
            outcome
                .failures
                .push(format!("the test's run could not start a thread: {e}"));
            return finish(outcome, started);
        }
    };
    outcome.stdout = out.text();
    outcome.stderr = format!("{}{}", actions.text(), err.text());
    outcome.trace = trace.text();
    outcome.transitions = count.load(Ordering::Relaxed);
    let stopped = outcome.transitions >= limit;
    check(case, code, stopped, &kb, &mut outcome);
    finish(outcome, started)
}

fn finish(mut o: Outcome, started: Instant) -> Outcome {
    o.elapsed = started.elapsed();
    o
}

/// `a` and `b` equal but for spaces (`writeq` text as written in a test).
fn same_term(a: &str, b: &str) -> bool {
    let c = |s: &str| s.chars().filter(|c| !c.is_whitespace()).collect::<String>();
    c(a) == c(b)
}

/// Whether the term `expected` (it may have variables) fits `actual`.
fn fits(expected: &str, actual: &str) -> bool {
    let has_var = expected
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .any(|w| w.starts_with(|c: char| c.is_ascii_uppercase() || c == '_'));
    same_term(expected, actual) || (has_var && sitlog_graph::trace::may_match(expected, actual))
}

/// What is wrong when a value the run gave (`None`: it gave none) does not
/// fit the expected one: `expected WHAT `want`, GOT `got`` or `.., NONE`.
fn mismatch(
    want: &super::case::Located,
    got: Option<String>,
    what: &str,
    got_word: &str,
    none: &str,
) -> Option<String> {
    match got {
        Some(g) if fits(&want.text, &g) => None,
        Some(g) => Some(format!("expected {what} `{}`, {got_word} `{g}`", want.text)),
        None => Some(format!("expected {what} `{}`, {none}", want.text)),
    }
}

/// Checks the expectations of `case` on what its run did.
fn check(
    case: &Case,
    code: u8,
    stopped: bool,
    kb: &Mutex<Option<sitlog_robot::kb_services::SharedKb>>,
    o: &mut Outcome,
) {
    let e = &case.expect;
    let file = o.file.clone();
    let at = |l: &super::case::Located| format!("{file}:{}:{}", l.line, l.column);
    if stopped {
        let why = match e.max_transitions {
            Some(n) => format!("more than `expect.max_transitions = {n}`"),
            None => format!("{DEFAULT_MAX_TRANSITIONS}, the most a test without `expect.max_transitions` may make"),
        };
        o.failures.push(format!(
            "{file}: the run was stopped after {} transitions: {why}",
            o.transitions
        ));
        return;
    }
    let status = match code {
        0 => Some(Status::Ok),
        1 => Some(Status::Error),
        _ => None,
    };
    let error_text = o.stderr.trim_end().to_owned();
    match (status, e.status) {
        (None, _) => {
            o.failures.push(format!(
                "{file}: the run could not start or did not finish (exit status {code}): {error_text}"
            ));
            return;
        }
        (Some(Status::Error), Status::Ok) => o.failures.push(format!(
            "{file}: expected the task to end in a final situation (status ok), but it stopped with an error:\n{error_text}"
        )),
        (Some(Status::Ok), Status::Error) => o.failures.push(format!(
            "{file}: expected the task to stop with an error (`status = \"error\"`), but it ended ok"
        )),
        _ => {}
    }
    if let Some(want) = &e.error {
        if status == Some(Status::Error) && !o.stderr.contains(&want.text) {
            o.failures.push(format!(
                "{}: expected the error to contain `{}`; it was:\n{error_text}",
                at(want),
                want.text
            ));
        }
    }
    // the main DM's last situation: the last transition at depth 0
    if let Some(want) = &e.final_situation {
        let last = o
            .trace
            .lines()
            .rev()
            .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
            .find(|v| v.get("unmatched").is_none() && v["depth"] == 0)
            .and_then(|v| v["situation"].as_str().map(str::to_owned));
        let failure = mismatch(
            want,
            last,
            "the main DM to end in situation",
            "it ended in",
            "it made no transition",
        );
        o.failures
            .extend(failure.map(|f| format!("{}: {f}", at(want))));
    }
    if let Some(want) = &e.out_arg {
        let got = o
            .stdout
            .lines()
            .rev()
            .find_map(|l| l.strip_prefix("Out Arg: "))
            .map(str::to_owned);
        let failure = mismatch(want, got, "the out_arg", "it was", "the run printed none");
        o.failures
            .extend(failure.map(|f| format!("{}: {f}", at(want))));
    }
    if let Some(max) = e.max_transitions {
        if o.transitions > max {
            o.failures.push(format!(
                "{file}: {} transitions, more than `expect.max_transitions = {max}`",
                o.transitions
            ));
        }
    }
    // lines in order, and lines that must not be there
    let output = format!("{}{}", o.stdout, o.stderr);
    let lines: Vec<&str> = output.lines().collect();
    let mut pos = 0;
    let mut marks: Vec<(usize, String)> = Vec::new();
    let mut missing: Option<(usize, String)> = None;
    for want in &e.lines {
        match lines[pos..].iter().position(|l| l.contains(&want.text)) {
            Some(k) => {
                marks.push((pos + k, want.text.clone()));
                pos += k + 1;
            }
            None => {
                let after = if pos == 0 {
                    "in the output".to_owned()
                } else {
                    format!("after line {pos} of the output")
                };
                o.failures.push(format!(
                    "{}: expected a line containing `{}` {after}; there is none",
                    at(want),
                    want.text
                ));
                missing = Some((pos, format!("{} ({})", want.text, at(want))));
                break;
            }
        }
    }
    let mut present = Vec::new();
    for not in &e.absent {
        if let Some(k) = lines.iter().position(|l| l.contains(&not.text)) {
            o.failures.push(format!(
                "{}: expected no line containing `{}`; line {} has it",
                at(not),
                not.text,
                k + 1
            ));
            present.push(k);
        }
    }
    if missing.is_some() || !present.is_empty() {
        o.detail = marked(&lines, &marks, missing.as_ref(), &present);
    }
    // the KB afterwards
    if !e.kb.is_empty() {
        let handle = kb.lock().ok().and_then(|k| k.clone());
        match handle {
            None => o.failures.push(format!(
                "{}: `expect.kb` asks the KB, but this run has none",
                at(&e.kb[0].0)
            )),
            Some(handle) => {
                let kb = match handle.lock() {
                    Ok(kb) => kb,
                    Err(p) => p.into_inner(),
                };
                for (query, answer) in &e.kb {
                    match sitlog_kb::answer_in(&kb, &at(query), &query.text) {
                        Ok(got) if fits(&answer.text, &got) => {}
                        Ok(got) => o.failures.push(format!(
                            "{}: the KB answers `{}` with `{got}`, expected `{}`",
                            at(answer),
                            query.text,
                            answer.text
                        )),
                        Err(err) => o.failures.push(err.to_string()),
                    }
                }
            }
        }
    }
    if let Some((name, path)) = &e.golden {
        match super::read_text(path) {
            Ok(want) if want == o.stdout => {}
            Ok(want) => {
                o.failures.push(format!(
                    "{}: the output differs from {} (- expected, + actual)",
                    at(name),
                    path.display()
                ));
                o.detail.push_str(&diff(&want, &o.stdout));
            }
            Err(err) => o
                .failures
                .push(format!("{}: cannot read the golden file: {err}", at(name))),
        }
    }
}

/// The output with the lines that met `expect.lines` marked `=`, the first
/// expected line not found shown `-` where it was looked for, and lines
/// that must not be there marked `!`.
fn marked(
    lines: &[&str],
    marks: &[(usize, String)],
    missing: Option<&(usize, String)>,
    present: &[usize],
) -> String {
    let mut s = String::from(
        "output (`=` an expected line found, `-` the expected line not found, `!` a line that must not be there):\n",
    );
    for (i, l) in lines.iter().enumerate() {
        if let Some((at, text)) = missing {
            if *at == i {
                s.push_str(&format!("     - {text}\n"));
            }
        }
        let mark = if present.contains(&i) {
            '!'
        } else if marks.iter().any(|(k, _)| *k == i) {
            '='
        } else {
            ' '
        };
        s.push_str(&format!("{:4} {mark} {l}\n", i + 1));
    }
    if let Some((at, text)) = missing {
        if *at >= lines.len() {
            s.push_str(&format!("     - {text}\n"));
        }
    }
    s
}

/// A line diff of `want` and `got` (`-` only in `want`, `+` only in
/// `got`), with three lines of context around each change.
pub fn diff(want: &str, got: &str) -> String {
    let a: Vec<&str> = want.lines().collect();
    let b: Vec<&str> = got.lines().collect();
    // longest common subsequence, by dynamic programming from the ends
    let (n, m) = (a.len(), b.len());
    if n.saturating_mul(m) > 25_000_000 {
        return format!("(the outputs are too long to compare line by line: {n} and {m} lines)\n");
    }
    let mut lcs = vec![vec![0u32; m + 1]; n + 1];
    for i in (0..n).rev() {
        for j in (0..m).rev() {
            lcs[i][j] = if a[i] == b[j] {
                lcs[i + 1][j + 1] + 1
            } else {
                lcs[i + 1][j].max(lcs[i][j + 1])
            };
        }
    }
    let mut ops: Vec<(char, &str)> = Vec::new();
    let (mut i, mut j) = (0, 0);
    while i < n || j < m {
        if i < n && j < m && a[i] == b[j] {
            ops.push((' ', a[i]));
            i += 1;
            j += 1;
        } else if i < n && (j == m || lcs[i + 1][j] >= lcs[i][j + 1]) {
            ops.push(('-', a[i]));
            i += 1;
        } else {
            ops.push(('+', b[j]));
            j += 1;
        }
    }
    let near = |k: usize| {
        let lo = k.saturating_sub(3);
        let hi = (k + 4).min(ops.len());
        ops[lo..hi].iter().any(|(c, _)| *c != ' ')
    };
    let mut s = String::new();
    let mut skipped = false;
    for (k, (c, l)) in ops.iter().enumerate() {
        if near(k) {
            if skipped {
                s.push_str("  ...\n");
                skipped = false;
            }
            s.push_str(&format!("{c} {l}\n"));
        } else {
            skipped = true;
        }
    }
    if skipped && !s.is_empty() {
        s.push_str("  ...\n");
    }
    s
}

/// Runs `cases` (with their files' texts) on `jobs` threads; `done` hears
/// of each outcome in the cases' order, as soon as it and those before it
/// are there. The outcomes, in the cases' order.
pub fn run_all(
    suite: &Suite<'_>,
    cases: &[(Case, String)],
    jobs: usize,
    done: &mut dyn FnMut(&Outcome),
) -> Vec<Outcome> {
    let next = AtomicUsize::new(0);
    let results: Vec<Mutex<Option<Outcome>>> = cases.iter().map(|_| Mutex::new(None)).collect();
    let (tx, rx) = std::sync::mpsc::channel::<()>();
    let jobs = jobs.clamp(1, cases.len().max(1));
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            let tx = tx.clone();
            let (next, results) = (&next, &results);
            // A thread that cannot start leaves its tests to the others
            // (with none, every test reports that it did not run).
            let _ = std::thread::Builder::new()
                .stack_size(256 * 1024 * 1024)
                .spawn_scoped(scope, move || loop {
                    let i = next.fetch_add(1, Ordering::SeqCst);
                    let Some((case, text)) = cases.get(i) else {
                        break;
                    };
                    // A bug that panics fails its test, not the whole run.
                    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        run_case(suite, case, text)
                    }))
                    .unwrap_or_else(|_| Outcome {
                        failures: vec![format!(
                            "{}: sitlogc failed inside this test's run (an internal error; please report it)",
                            case.path.display()
                        )],
                        ..not_run(case)
                    });
                    if let Ok(mut slot) = results[i].lock() {
                        *slot = Some(outcome);
                    }
                    let _ = tx.send(());
                });
        }
        drop(tx);
        let mut reported = 0;
        while reported < cases.len() {
            let ready = results[reported]
                .lock()
                .map(|r| r.is_some())
                .unwrap_or(false);
            if ready {
                if let Some(o) = results[reported].lock().ok().and_then(|r| r.clone()) {
                    done(&o);
                }
                reported += 1;
            } else if rx.recv().is_err() {
                // every worker has ended: what is left did not run
                break;
            }
        }
    });
    results
        .into_iter()
        .zip(cases)
        .map(|(r, (case, _))| {
            r.into_inner()
                .ok()
                .flatten()
                .unwrap_or_else(|| not_run(case))
        })
        .collect()
}

/// The outcome of a test that did not run.
fn not_run(case: &Case) -> Outcome {
    Outcome {
        name: case.name.clone(),
        file: case.path.display().to_string(),
        failures: vec![format!(
            "{}: the test did not run (no thread could run it)",
            case.path.display()
        )],
        detail: String::new(),
        stdout: String::new(),
        stderr: String::new(),
        trace: String::new(),
        transitions: 0,
        elapsed: Duration::ZERO,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diff_shows_changes_with_context() {
        let d = diff("a\nb\nc\nd\ne\nf\ng\nh\ni\n", "a\nb\nc\nd\nX\nf\ng\nh\ni\n");
        assert_eq!(d, "  ...\n  b\n  c\n  d\n- e\n+ X\n  f\n  g\n  h\n  ...\n");
        assert_eq!(diff("a\n", "a\n"), "");
    }

    #[test]
    fn terms_fit_with_variables() {
        assert!(fits("error(E)", "error(not_found)"));
        assert!(fits("fetch( juice )", "fetch(juice)"));
        assert!(!fits("fs", "error(x)"));
        assert!(!fits("ok", "Ok2"));
    }
}
