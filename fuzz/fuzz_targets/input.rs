//! Arbitrary bytes as the perceptions of a fixed task (a script: one term
//! per clause), under tight input limits; the task takes every input in a
//! loop until the script ends. Never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sitlog_compiler::{check, ir, load, run};
use sitlog_runtime::machine::Options;
use sitlog_runtime::testmode::{InputLimits, ScriptPerception, TextActions};
use std::sync::OnceLock;

const TASK: &str = "diag_mod(main, [
  [id ==> is, type ==> listening,
   arcs ==> [stop : say(bye) => fs, X : [inc(n, _), screen(X)] => is]],
  [id ==> fs, type ==> final]
], [n ==> 0]).
";

fn task() -> &'static ir::Ir {
    static IR: OnceLock<ir::Ir> = OnceLock::new();
    IR.get_or_init(|| {
        let (program, diags) = load::load_sources(&[("main.dm", TASK)]);
        let checked = check::check(program, diags).0.expect("the fixed task checks");
        ir::lower(&checked)
    })
}

fuzz_target!(|data: &[u8]| {
    let ir = task();
    let Ok(perception) = ScriptPerception::from_bytes("input", data.to_vec()) else {
        return;
    };
    let mut perception = perception.with_limits(InputLimits {
        max_bytes: 4096,
        max_depth: 64,
    });
    let mut actions = TextActions::new(std::io::sink(), Vec::new());
    let config = run::RunConfig {
        options: Options {
            keep_history: false,
            ..Options::default()
        },
        ..run::RunConfig::default()
    };
    let _ = run::run(ir, config, &mut perception, &mut actions, None);
});
