//! The interpreter's plans (`sitlog_compiler::interp`) on the shipped
//! applications: every situation of the two scenarios runs from a plan
//! (ids that are patterns, `try([P|Ps])`, and types that are not atoms,
//! `presence(Seconds)`, included), at least 90 % elsewhere, and a whole
//! run of each scenario instantiates no template; the counts are
//! printed (`cargo test -p sitlog-tests --test suite -- resolve --nocapture`) for
//! docs/guide/performance.md. That plans and templates agree is checked by
//! `random_agreement.rs` and the goldens (which run from plans).

use sitlog_compiler::interp::Resolved;
use std::path::Path;

fn counts(app: &str) -> (usize, usize) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(app);
    let (result, _) = sitlog_tests::check_app(&dir);
    let ir = sitlog_compiler::ir::lower(&result.expect("checks"));
    let (planned, all) = Resolved::new(&ir).counts();
    println!("{app}: {planned} of {all} situations run from plans");
    (planned, all)
}

#[test]
fn the_applications_run_mostly_from_plans() {
    for app in [
        "dms/apps/home",
        "dms/apps/supermarket",
        "dms/examples/appendix_a",
    ] {
        let (planned, all) = counts(app);
        assert!(
            all > 0 && planned * 10 >= all * 9,
            "{app}: {planned} of {all}"
        );
        if app.starts_with("dms/apps/") {
            assert_eq!(planned, all, "{app}");
        }
    }
}

/// A whole run of each scenario on its own world, on `sitlogc run`'s
/// interpreter, instantiates no situation from its template: every
/// situation it reaches runs from its plan (the code the generated task
/// runs too).
#[test]
fn the_scenarios_instantiate_no_template() {
    for app in ["dms/apps/home", "dms/apps/supermarket"] {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(app);
        let world = std::fs::read_to_string(dir.join("world.toml")).expect("the app's world");
        let assets = sitlog_tests::scenario::assets(&dir, &world, None);
        let (ir, functions) = sitlog_tests::scenario::shared_interpreter(&dir);
        let resolved = Resolved::new(&ir);
        let run = sitlog_tests::scenario::execute(&resolved, functions, &assets);
        assert_eq!(run.report["status"], "ok", "{app}: {}", run.transcript);
        let history = run.report["history"].as_array().map_or(0, Vec::len);
        assert!(history > 5, "{app}: {history} history entries");
        assert_eq!(resolved.templates_instantiated(), 0, "{app}");
    }
}
