//! Arbitrary bytes as a DM file; a program that checks runs in test mode
//! on a fixed script, stopped after 2 000 transitions. Never a panic (a
//! run-time error is an outcome, not a failure). A run that ends by itself
//! (not stopped by the budget) runs twice, through the interpreter's plans
//! (`run::run`, what `sitlogc run` does) and with every situation from its
//! template (`run::run_unresolved`, the reference): both reports (JSON) and
//! both transcripts of the actions must be the same up to a consistent
//! renaming of variables (differential, as `tests/suite/random_agreement`).
//! With `SITLOG_FUZZ_RUN_LOG` set, each input says on stderr how far it got
//! (`checks`, `compared`): to count, with `-runs=0` over a corpus, how many
//! inputs the comparison sees.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sitlog_compiler::ir::Ir;
use sitlog_compiler::{check, ir, load, run};
use sitlog_runtime::history::Entry;
use sitlog_runtime::machine::{Observer, Options};
use sitlog_runtime::testmode::{ScriptPerception, TextActions};
use sitlog_runtime::{report, Store, Term};
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

const SCRIPT: &str = "hello.\nyes.\n3.\nf(a, [1, 2]).\nno.\ngoodbye.\n";

/// Stops the run after a number of transitions.
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

/// One run of `ir` from its plans (`plans`) or its templates: the JSON
/// report and the actions' transcript, `None` when the budget stopped it
/// (where a stop lands may differ between the two: plans go from one
/// situation to the next without the machine's loop) or the run did not
/// start.
fn one_run(ir: &Ir, plans: bool) -> Option<(String, String)> {
    let stop = Arc::new(AtomicBool::new(false));
    let config = run::RunConfig {
        options: Options {
            stop: Some(stop.clone()),
            max_depth: 10_000,
            gc_threshold: 1 << 12,
            ..Options::default()
        },
        ..run::RunConfig::default()
    };
    let mut perception = ScriptPerception::new("script", SCRIPT.to_owned());
    let mut said = Vec::new();
    let mut actions = TextActions::new(&mut said, ir.basic_actions.clone());
    let mut budget = Budget { left: 2_000, stop };
    let runner = if plans { run::run } else { run::run_unresolved };
    let (outcome, mut store) =
        runner(ir, config, &mut perception, &mut actions, Some(&mut budget)).ok()?;
    let json = report::outcome_json(&store, &outcome);
    report::outcome_text(&mut store, &outcome);
    drop(actions);
    if outcome.interrupted || budget.left == 0 {
        return None;
    }
    Some((json, String::from_utf8_lossy(&said).into_owned()))
}

/// Every variable (`_G12`, `_123`) of `text` renamed `_V0`, `_V1`, ... in
/// the order first seen through `names`.
fn canonical(text: &str, names: &mut HashMap<String, usize>) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let mut prev_alnum = false;
    while let Some(c) = chars.next() {
        if c == '_' && !prev_alnum {
            let mut name = String::from("_");
            while let Some(&n) = chars.peek() {
                if n.is_ascii_alphanumeric() || n == '_' {
                    name.push(n);
                    chars.next();
                } else {
                    break;
                }
            }
            let digits = name.strip_prefix("_G").unwrap_or(&name[1..]);
            if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
                let next = names.len();
                out.push_str(&format!("_V{}", *names.entry(name).or_insert(next)));
            } else {
                out.push_str(&name);
            }
            prev_alnum = true;
            continue;
        }
        prev_alnum = c.is_alphanumeric();
        out.push(c);
    }
    out
}

/// Whether `data` holds text a variable prints as (`_` then a digit, or
/// `_G` then a digit), e.g. in a quoted atom: [`canonical`] would rename
/// it as a variable, and a run's fresh variable of the same number would
/// then look like it (a false disagreement, session 22). Such inputs are
/// run but not compared.
fn names_like_variables(data: &[u8]) -> bool {
    data.windows(2)
        .any(|w| w[0] == b'_' && w[1].is_ascii_digit())
        || data
            .windows(3)
            .any(|w| w[0] == b'_' && w[1] == b'G' && w[2].is_ascii_digit())
}

/// Whether to say how far each input got (`SITLOG_FUZZ_RUN_LOG`).
fn log() -> bool {
    static LOG: OnceLock<bool> = OnceLock::new();
    *LOG.get_or_init(|| std::env::var_os("SITLOG_FUZZ_RUN_LOG").is_some())
}

fuzz_target!(|data: &[u8]| {
    let (program, diags) = load::load_source_bytes(&[("main.dm", data)]);
    let (result, _) = check::check(program, diags);
    let Ok(checked) = result else { return };
    if log() {
        eprintln!("run-log: checks");
    }
    let ir = ir::lower(&checked);
    let Some((json, said)) = one_run(&ir, true) else {
        return;
    };
    if names_like_variables(data) {
        return;
    }
    let Some((json_t, said_t)) = one_run(&ir, false) else {
        panic!("the plans' run ended by itself, the templates' did not\nplans: {json}");
    };
    let mut names = HashMap::new();
    let plans = (canonical(&json, &mut names), canonical(&said, &mut names));
    let mut names = HashMap::new();
    let templates = (
        canonical(&json_t, &mut names),
        canonical(&said_t, &mut names),
    );
    assert!(
        plans == templates,
        "plans and templates disagree\nplans:     {}\n{}\ntemplates: {}\n{}",
        plans.0,
        plans.1,
        templates.0,
        templates.1
    );
    if log() {
        eprintln!("run-log: compared");
    }
});
