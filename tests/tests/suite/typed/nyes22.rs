//! Helper `nyes22` (issue 37): perceptions matched in place
//! (`tests/typed/nyes22`). Where compiled code perceives with its frames
//! kept (`Machine::perceive_kept`), the test-mode script hands the input of
//! a `listening` or `nkeyboard` situation over with `said(..)` not built
//! (`Percept::Wrapped`), and the machine unifies it with each expectation's
//! argument in place. The compiled task and the interpreter's plans must
//! agree with the interpreter (report, history, actions, observer, errors,
//! the "not understood" warning and the unmatched inputs), with the
//! history kept or not, on a script, on a script shared with the engine
//! (`SharedPerception`, as `sitlogc run` reads it) and typed at a prompt
//! (`PromptPerception`, which is told where it waits: the term path).

use super::{functions, interpreter, run_piped, unnumbered, Trace};
use sitlog_compiler::interp::Resolved;
use sitlog_runtime::machine::{Observer, Options, Perceived, Percept, Perception};
use sitlog_runtime::testmode::{PromptPerception, ScriptPerception, SharedPerception, TextActions};
use sitlog_runtime::{app, report, Atom};
use sitlog_tests::compiled::{canonical_vars, rename};

mod dms {
    pub mod nyes22 {
        sitlog_macros::include_dm!("typed/nyes22");
    }
}

/// Scripts for `main(Goal)`: yes/no with inputs that meet neither, words,
/// shapes of one functor (a repeated variable met and not, lists, numbers,
/// `1.0` against `1`, an input `said(x)` wrapped again, variables), the
/// keyboard and speech; and scripts that end early or meet nothing.
const SCRIPTS: [&str; 9] = [
    "yes.\nhi.\nstop.\ndone.\nk.\nsaid(z).\n",
    "maybe.\nno.\nyes.\nhello.\nhi.\nstop.\np(a, a).\np(a, b).\n[x, y].\n1.\n1.5.\n1.0.\nsaid(x).\nf(_).\ndone.\nk.\nsaid(z).\n",
    "no.\nno.\nsaid(yes).\nyes.\nhello.\nhi.\np(X, X).\np(_, _).\n[].\n[_|_].\ndone.\nesc.\nstop.\n",
    "_.\nX.\nhi.\nstop.\nq(1).\nyes.\n",
    "yes.\n[hi].\nstop.\ndone.\n",
    "maybe.\n",
    "",
    "yes.\nhi.\n",
    "yes.\nstop.\ndone.\nf(X, Y).\n[a].\n",
];

const MAINS: [&str; 3] = ["main(hi)", "main([hi])", "main(_)"];

/// The compiled task and the plans against the interpreter on every
/// script, history kept or not, observed or not (unbound variables
/// compared without their store numbers).
#[test]
fn nyes22_perceptions_matched_in_place_agree() {
    let ir = interpreter("typed/nyes22");
    let plans = Resolved::new(&ir);
    for main in MAINS {
        for script in SCRIPTS {
            for (keep, observe) in [(false, false), (true, false), (false, true), (true, true)] {
                let i = run_piped(&ir, main, None, script, keep, observe, false);
                let c = run_piped(
                    dms::nyes22::program(),
                    main,
                    None,
                    script,
                    keep,
                    observe,
                    false,
                );
                let r = run_piped(&plans, main, None, script, keep, observe, false);
                let what = format!("{main} on {script:?} (history {keep}, observer {observe})");
                assert_eq!(
                    unnumbered(format!("{c:?}")),
                    unnumbered(format!("{i:?}")),
                    "{what}"
                );
                assert_eq!(
                    unnumbered(format!("{r:?}")),
                    unnumbered(format!("{i:?}")),
                    "{what}"
                );
            }
        }
    }
}

/// The chosen arcs are the ones the DM says (not only the same in both):
/// the yes/no question asked again after `maybe.` (a warning), `hi` the
/// goal, the shapes of one functor.
#[test]
fn nyes22_perceptions_choose_the_last_expectation_met() {
    let (report, _, seen, trace) = run_piped(
        dms::nyes22::program(),
        "main(hi)",
        None,
        SCRIPTS[1],
        true,
        true,
        false,
    );
    let history = report.to_string();
    for said in [
        "say(no)",
        "say(yes)",
        "say(heard(hello))",
        "say(got(hi))",
        "say(pair(a))",
        "say(any(said(stop)))",
        "say(two(a,b))",
        "say(list(x,[y]))",
        "say(one)",
        "say(half)",
        "say(any(said(1.0)))",
        "say(any(said(said(x))))",
        "say(key(k))",
        "say(other(said(z)))",
    ] {
        assert!(history.contains(said), "{said} in {history}");
    }
    assert!(
        seen.iter()
            .any(|l| l.contains("No satisfied expected intention")
                || l.contains("meets no expectation")),
        "{seen:?}"
    );
    assert!(
        trace.iter().any(|l| l.contains("unmatched said(maybe)")),
        "{trace:?}"
    );
}

/// One run with `perception`: the report (variables renamed), the
/// transitions, what was said and warned, the observer's trace.
fn run_perceiving<A: app::App>(
    app: &A,
    main: &str,
    perception: &mut dyn Perception,
    keep_history: bool,
) -> (serde_json::Value, u64, Vec<String>, Vec<String>) {
    let mut text = Vec::new();
    let mut trace = Trace::default();
    let (outcome, store) = {
        let mut actions = TextActions::new(&mut text, vec![Atom::intern("beep")]);
        let observer: Option<&mut dyn Observer> = Some(&mut trace);
        app::run(
            app,
            main,
            None,
            Options {
                keep_history,
                ..Options::default()
            },
            functions(),
            perception,
            &mut actions,
            observer,
        )
        .expect("runs")
    };
    let report: serde_json::Value =
        serde_json::from_str(&report::outcome_json(&store, &outcome)).expect("JSON");
    let mut seen: Vec<String> = String::from_utf8(text)
        .unwrap()
        .lines()
        .map(str::to_owned)
        .collect();
    seen.extend(outcome.warnings.iter().map(ToString::to_string));
    let mut names = std::collections::HashMap::new();
    let trace = trace.0.iter().map(|l| rename(l, &mut names)).collect();
    (canonical_vars(&report), outcome.transitions, seen, trace)
}

/// A script shared with the engine (`sitlogc run`'s way, forwarding the
/// percept) gives what the plain script gives, on both back ends; the
/// same inputs typed at a prompt (no warning for an input that meets
/// nothing: the user saw the expectations) agree on both back ends.
#[test]
fn nyes22_shared_and_typed_inputs_agree() {
    let ir = interpreter("typed/nyes22");
    for main in MAINS {
        for script in SCRIPTS {
            for keep in [false, true] {
                let plain = |app: &dyn Fn(&mut dyn Perception) -> _| {
                    let mut p = ScriptPerception::new("script", script.to_owned());
                    app(&mut p)
                };
                let shared = |app: &dyn Fn(&mut dyn Perception) -> _| {
                    let mut p =
                        SharedPerception::new(ScriptPerception::new("script", script.to_owned()));
                    app(&mut p)
                };
                let typed = |app: &dyn Fn(&mut dyn Perception) -> _| {
                    let mut p = PromptPerception::new(std::io::Cursor::new(script.as_bytes()));
                    app(&mut p)
                };
                let interp = |p: &mut dyn Perception| run_perceiving(&ir, main, p, keep);
                let compiled =
                    |p: &mut dyn Perception| run_perceiving(dms::nyes22::program(), main, p, keep);
                let want = unnumbered(format!("{:?}", plain(&interp)));
                let what = format!("{main} on {script:?} (history {keep})");
                assert_eq!(
                    unnumbered(format!("{:?}", plain(&compiled))),
                    want,
                    "{what}"
                );
                assert_eq!(
                    unnumbered(format!("{:?}", shared(&compiled))),
                    want,
                    "{what}"
                );
                assert_eq!(unnumbered(format!("{:?}", shared(&interp))), want, "{what}");
                // Typed: the same inputs (a prompt shows its header on
                // stderr, not among the actions).
                assert_eq!(
                    unnumbered(format!("{:?}", typed(&compiled))),
                    unnumbered(format!("{:?}", typed(&interp))),
                    "{what}"
                );
            }
        }
    }
}

/// The script, counting the inputs it hands over unbuilt.
struct Counting {
    inner: ScriptPerception,
    wrapped: usize,
}

impl Perception for Counting {
    fn perceive(
        &mut self,
        store: &mut sitlog_runtime::Store,
        ty: sitlog_runtime::Term,
        expectations: &[sitlog_runtime::Term],
    ) -> Result<Perceived, String> {
        self.inner.perceive(store, ty, expectations)
    }

    fn perceive_percept(
        &mut self,
        store: &mut sitlog_runtime::Store,
        ty: sitlog_runtime::Term,
        expectations: &[sitlog_runtime::Term],
    ) -> Result<Percept, String> {
        let p = self.inner.perceive_percept(store, ty, expectations)?;
        self.wrapped += usize::from(matches!(p, Percept::Wrapped(..)));
        Ok(p)
    }

    fn unmatched_is_news(&self) -> bool {
        self.inner.unmatched_is_news()
    }

    fn uses_waiting_at(&self) -> bool {
        self.inner.uses_waiting_at()
    }
}

/// Compiled code takes the script's `said(..)` unbuilt (the `listening`
/// and `nkeyboard` inputs it reads with its frames kept: at most 16 of
/// the 17, the `speech` one whole), the interpreter never: both give the
/// plain script's run.
#[test]
fn nyes22_compiled_code_matches_inputs_unbuilt() {
    let ir = interpreter("typed/nyes22");
    let script = SCRIPTS[1];
    let counting = || Counting {
        inner: ScriptPerception::new("script", script.to_owned()),
        wrapped: 0,
    };
    let plain = |app: &dyn Fn(&mut dyn Perception) -> _| {
        let mut p = ScriptPerception::new("script", script.to_owned());
        app(&mut p)
    };
    for keep in [false, true] {
        let want = unnumbered(format!(
            "{:?}",
            plain(&|p: &mut dyn Perception| run_perceiving(&ir, "main(hi)", p, keep))
        ));
        let mut c = counting();
        let got = run_perceiving(dms::nyes22::program(), "main(hi)", &mut c, keep);
        assert_eq!(unnumbered(format!("{got:?}")), want, "history {keep}");
        assert!(
            (12..=16).contains(&c.wrapped),
            "history {keep}: {}",
            c.wrapped
        );
        let mut i = counting();
        let got = run_perceiving(&ir, "main(hi)", &mut i, keep);
        assert_eq!(unnumbered(format!("{got:?}")), want, "history {keep}");
        assert_eq!(i.wrapped, 0, "history {keep}");
    }
}
