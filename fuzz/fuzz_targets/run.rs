//! Arbitrary bytes as a DM file; a program that checks runs in test mode
//! on a fixed script, stopped after 2 000 transitions. Never a panic (a
//! run-time error is an outcome, not a failure).
#![no_main]

use libfuzzer_sys::fuzz_target;
use sitlog_compiler::{check, ir, load, run};
use sitlog_runtime::history::Entry;
use sitlog_runtime::machine::{Observer, Options};
use sitlog_runtime::testmode::{ScriptPerception, TextActions};
use sitlog_runtime::{report, Store, Term};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

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

fuzz_target!(|data: &[u8]| {
    let (program, diags) = load::load_source_bytes(&[("main.dm", data)]);
    let (result, _) = check::check(program, diags);
    let Ok(checked) = result else { return };
    let ir = ir::lower(&checked);
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
    let mut actions = TextActions::new(std::io::sink(), ir.basic_actions.clone());
    let mut budget = Budget { left: 2_000, stop };
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
});
