//! Issue 23: any bytes as a DM file, as typed or scripted input, or as
//! `user_functions.pl` get a verdict, never a panic: load, check, the three
//! diagnostic renderers, lowering and a bounded run. The cargo-fuzz targets
//! `check`, `run`, `input` and `prolog` in fuzz/ run the same properties
//! for longer.

use proptest::prelude::*;
use sitlog_compiler::{check, diag, ir, load, run};
use sitlog_runtime::history::Entry;
use sitlog_runtime::machine::{Observer, Options};
use sitlog_runtime::testmode::{InputLimits, ScriptPerception, TextActions};
use sitlog_runtime::{report, Store, Term};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Stops a run after a number of transitions.
struct Budget {
    left: u32,
    stop: Arc<AtomicBool>,
}

impl Observer for Budget {
    fn transition(&mut self, _: &Store, _: &Entry, _: usize, _: Option<Term>) {
        self.left = self.left.saturating_sub(1);
        if self.left == 0 {
            self.stop.store(true, Ordering::Relaxed);
        }
    }
}

/// Check, render, lower and run (bounded) one DM file's bytes.
fn pipeline(bytes: &[u8], script: &[u8]) {
    let (program, diags) = load::load_source_bytes(&[("main.dm", bytes)]);
    let (result, diags) = check::check(program, diags);
    let sources = match &result {
        Ok(c) => &c.program().sources,
        Err(p) => &p.sources,
    };
    for d in &diags {
        diag::render_human(d, sources, false);
        diag::render_json(d, sources);
        diag::render_short(d, sources);
    }
    let Ok(checked) = result else { return };
    let ir = ir::lower(&checked);
    let Ok(perception) = ScriptPerception::from_bytes("script", script.to_vec()) else {
        return;
    };
    let mut perception = perception.with_limits(InputLimits {
        max_bytes: 256,
        max_depth: 16,
    });
    let stop = Arc::new(AtomicBool::new(false));
    let config = run::RunConfig {
        options: Options {
            stop: Some(stop.clone()),
            max_depth: 1000,
            gc_threshold: 1 << 10,
            ..Options::default()
        },
        ..run::RunConfig::default()
    };
    let mut actions = TextActions::new(std::io::sink(), ir.basic_actions.clone());
    let mut budget = Budget { left: 500, stop };
    if let Ok((outcome, mut store)) = run::run(
        &ir,
        config,
        &mut perception,
        &mut actions,
        Some(&mut budget),
    ) {
        report::outcome_json(&store, &outcome);
        report::outcome_text(&mut store, &outcome);
    }
}

const DM_PIECES: &[&str] = &[
    "diag_mod(",
    "main",
    ", [",
    "[id ==> ",
    "is",
    "fs",
    ", type ==> ",
    "neutral",
    "listening",
    "final",
    "recursive",
    ", arcs ==> [",
    "empty : ",
    "X : ",
    " => ",
    "screen(X)",
    "inc(n, N)",
    "get(n, N)",
    "set(n, X)",
    "apply(f(X), [1])",
    "embedded_dm ==> main",
    "]",
    "]]",
    "], [n ==> 0]).",
    ", ",
    "(N > 2 -> fs ; otherwise -> is)",
    "[]",
    ".",
    "\n",
    " ",
    "\u{e9}",
    "\u{fffd}",
    "'",
    "%",
    "/*",
    "*/",
    "\"s\"",
    "0'",
    "1",
    "-",
];

const VALID: &str = "diag_mod(main, [
  [id ==> is, type ==> listening, arcs ==> [stop : screen(bye) => fs, X : [inc(n, _), screen(X)] => is]],
  [id ==> fs, type ==> final]
], [n ==> 0]).
";

fn config(default: u32) -> ProptestConfig {
    ProptestConfig {
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|c| c.parse().ok())
            .unwrap_or(default),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn arbitrary_bytes_as_a_dm_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        pipeline(&bytes, b"hello.\n3.\n");
    }

    #[test]
    fn dm_shaped_text_never_panics(parts in prop::collection::vec(prop::sample::select(DM_PIECES), 0..50)) {
        pipeline(parts.concat().as_bytes(), b"hello.\nyes.\n3.\nstop.\n");
    }

    #[test]
    fn a_valid_dm_with_bytes_changed_never_panics(
        edits in prop::collection::vec((0..VALID.len(), any::<u8>()), 1..6)
    ) {
        let mut bytes = VALID.as_bytes().to_vec();
        for (at, b) in edits {
            bytes[at] = b;
        }
        pipeline(&bytes, b"hello.\nstop.\n");
    }

    #[test]
    fn arbitrary_bytes_as_input_never_panic(script in prop::collection::vec(any::<u8>(), 0..300)) {
        pipeline(VALID.as_bytes(), &script);
    }

    #[test]
    fn term_shaped_input_never_panics(parts in prop::collection::vec(prop::sample::select(&[
        "f(", ")", "[", "]", ",", "|", ".", " ", "\n", "a", "X", "1", "'q", "\"", "stop", "%", "\u{e9}",
    ][..]), 0..80)) {
        pipeline(VALID.as_bytes(), parts.concat().as_bytes());
    }
}

/// `text` with every variable `_G<n>` renamed `_V0`, `_V1`, ... in the
/// order first seen through `names`.
fn canonical(text: &str, names: &mut std::collections::HashMap<String, usize>) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find("_G") {
        out.push_str(&rest[..i]);
        let digits = rest[i + 2..]
            .find(|c: char| !c.is_ascii_digit())
            .unwrap_or(rest.len() - i - 2);
        if digits == 0 {
            out.push_str("_G");
        } else {
            let next = names.len();
            let n = *names
                .entry(rest[i..i + 2 + digits].to_owned())
                .or_insert(next);
            out.push_str(&format!("_V{n}"));
        }
        rest = &rest[i + 2 + digits..];
    }
    out.push_str(rest);
    out
}

/// One run of `text`'s DM `main` on no input, from the interpreter's plans
/// (`run::run`, what `sitlogc run` does) or from every situation's
/// template (`run::run_unresolved`): the JSON report and what was said
/// (variables renamed, [`canonical`]), and the run's warnings.
fn run_one(text: &str, main: &str, plans: bool) -> (String, String, Vec<String>) {
    let (program, diags) = load::load_sources(&[("main.dm", text)]);
    let checked = check::check(program, diags).0.expect("the program checks");
    let ir = ir::lower(&checked);
    let config = run::RunConfig {
        main: main.to_owned(),
        ..run::RunConfig::default()
    };
    let mut perception = ScriptPerception::new("script", String::new());
    let mut said = Vec::new();
    let mut actions = TextActions::new(&mut said, ir.basic_actions.clone());
    let runner = if plans { run::run } else { run::run_unresolved };
    let (outcome, store) =
        runner(&ir, config, &mut perception, &mut actions, None).expect("the run starts");
    let json = report::outcome_json(&store, &outcome);
    let warnings = outcome.warnings.iter().map(ToString::to_string).collect();
    drop(actions);
    let mut names = std::collections::HashMap::new();
    let json = canonical(&json, &mut names);
    let said = canonical(&String::from_utf8(said).expect("UTF-8"), &mut names);
    (json, said, warnings)
}

/// Found by the `run` fuzz target (session 22, plans against templates):
/// `get(nope, L)` of a name neither local nor global, `L` not made yet.
/// The original (and the evaluator, `var_op_parts`) gives a fresh unbound
/// value and leaves `L` as it was; the plans made `L` that value
/// (`Ev::VarOpFresh`, right only for a variable the DM sees), so `L`
/// and the value were one variable where the templates had two.
#[test]
fn a_get_of_an_undefined_name_leaves_its_variable_on_both_paths() {
    let text = "diag_mod(main, [
  [id ==> is, type ==> neutral,
   arcs ==> [empty : say([a, get(nope, L), L, inc(nada, M), M]) => s(L)]],
  [id ==> s(X), type ==> neutral, arcs ==> [empty : say([b, X]) => fs]],
  [id ==> fs, type ==> final]], []).
";
    let plans = run_one(text, "main", true);
    let templates = run_one(text, "main", false);
    assert_eq!(plans, templates, "plans / templates");
    assert!(
        plans.1.starts_with("Golem says: a _V0 _V1 _V2 _V3.\n"),
        "{}",
        plans.1
    );
}

/// Found by the `run` fuzz target (session 22, plans against templates):
/// the exit arc of a recursive situation whose next situation has no
/// value (`=> Next`) or is `empty` ended the DM on the plans, as any arc's
/// does (docs/guide/language.md, "Next"), but was an error ("the next
/// situation `_G0` is not a situation name", or no situation `empty`)
/// from the templates: the machine's loop took a recursive situation's
/// next situation as a name without the checks of every other arc's. Now
/// both end the DM (the main DM: the task; a callee: its caller takes its
/// first exit arc), with the warning at the recursive situation.
#[test]
fn a_recursive_exit_arc_without_a_next_situation_ends_the_dm_on_both_paths() {
    let text = "diag_mod(u, [
  [id ==> is, type ==> recursive, embedded_dm ==> sub, arcs ==> [done : say(back) => Next]],
  [id ==> fs, type ==> final]
], []).
diag_mod(e, [
  [id ==> is, type ==> recursive, embedded_dm ==> sub, arcs ==> [done : say(back) => empty]],
  [id ==> fs, type ==> final]
], []).
diag_mod(top_u, [
  [id ==> is, type ==> recursive, embedded_dm ==> u, arcs ==> [_ : say(top) => fs]],
  [id ==> fs, type ==> final]
], []).
diag_mod(top_e, [
  [id ==> is, type ==> recursive, embedded_dm ==> e, arcs ==> [_ : say(top) => fs]],
  [id ==> fs, type ==> final]
], []).
diag_mod(sub, [
  [id ==> s, type ==> neutral, arcs ==> [empty : say(sub) => done]],
  [id ==> done, type ==> final]
], []).
";
    for main in ["u", "e", "top_u", "top_e"] {
        let plans = run_one(text, main, true);
        let templates = run_one(text, main, false);
        assert_eq!(plans, templates, "{main}: plans / templates");
        assert!(plans.0.contains(r#""status":"ok""#), "{main}: {}", plans.0);
        if main.ends_with('u') {
            assert!(
                plans.2.len() == 1 && plans.2[0].contains("next situation `_G0` has no value"),
                "{main}: {:?}",
                plans.2
            );
        }
        let top = if main.starts_with("top") {
            "Golem says: top\n"
        } else {
            ""
        };
        assert_eq!(
            plans.1,
            format!("Golem says: sub\nGolem says: back\n{top}"),
            "{main}"
        );
    }
}

#[cfg(feature = "prolog")]
mod prolog {
    use super::*;
    use sitlog_runtime::functions::{CallLimits, FnCall};
    use sitlog_runtime::prolog::{PrologFunctions, PrologOptions, PrologSource};
    use sitlog_runtime::{Atom, Functions, Vars};
    use std::time::Duration;

    /// Loads `bytes` as user_functions.pl and calls what it defines.
    fn user_functions(bytes: &[u8]) {
        let Ok(text) = sitlog_syntax::decode(bytes) else {
            return;
        };
        let options = PrologOptions {
            inference_limit: 100_000,
            time_limit: Duration::from_secs(2),
            heap_limit: 256 << 20,
        };
        let Ok(engine) =
            PrologFunctions::load(&[PrologSource::new("user_functions.pl", text)], options)
        else {
            return;
        };
        let mut functions = Functions::standard();
        functions.set_call_limits(CallLimits {
            inferences: 100_000,
            time: Duration::from_secs(2),
            heap_bytes: 256 << 20,
        });
        engine.install(&mut functions);
        let mut store = Store::new();
        let (mut locals, mut globals) = (Vars::default(), Vars::default());
        for name in ["f", "g", "p"] {
            for arity in 0..3 {
                let name = Atom::intern(name);
                if !engine.defines(name, arity) {
                    continue;
                }
                let args: Vec<Term> = (0..arity).map(|_| Term::atom(Atom::intern("x"))).collect();
                let mut call = FnCall {
                    store: &mut store,
                    locals: &mut locals,
                    globals: &mut globals,
                    history: &[],
                    functions: &functions,
                };
                let _ = engine.call(&mut call, name, &args);
            }
        }
    }

    /// Prolog-shaped text as user_functions.pl never panics the load or a
    /// call. Each case starts an engine (about 2.5 s in a debug build): four
    /// cases in the stable suite; `fuzz/fuzz_targets/prolog.rs` goes deep,
    /// `PROLOG_PROPTEST_CASES` raises the count here. Not a `proptest!`:
    /// its runner takes `PROPTEST_CASES` over any count the test sets, and
    /// `.ci/run` sets that to 64 (to shorten the 256-case properties), which
    /// made this test 64 engine starts, 150 s of CPU.
    #[test]
    fn prolog_shaped_text_never_panics() {
        use proptest::test_runner::{Config, TestRunner};
        let cases = std::env::var("PROLOG_PROPTEST_CASES")
            .ok()
            .and_then(|c| c.parse().ok())
            .unwrap_or(4);
        let parts = prop::collection::vec(
            prop::sample::select(
                &[
                    "f(X)",
                    "g",
                    "p(A, B)",
                    " :- ",
                    "assign_func_value(",
                    ")",
                    "X",
                    ", ",
                    ".\n",
                    "(",
                    "fail",
                    "!",
                    "[",
                    "]",
                    "|",
                    "1",
                    "is",
                    "+",
                    ";",
                    "->",
                    "\\+",
                    "length(L, 3)",
                    "var_op(get(n, V))",
                    "\u{e9}",
                    "'",
                    "%",
                    "\u{ff}",
                ][..],
            ),
            0..30,
        );
        let mut runner = TestRunner::new(Config {
            cases,
            ..Config::default()
        });
        if let Err(e) = runner.run(&parts, |parts| {
            user_functions(parts.concat().as_bytes());
            Ok(())
        }) {
            panic!("{e}");
        }
    }
}
