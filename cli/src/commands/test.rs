//! `sitlogc test APP [FILTER]`: an application's tests ([`crate::apptest`]):
//! read every test file (a bad one stops everything, exit status 2), run
//! the chosen tests in parallel, print their lines and the summary, and
//! the coverage when asked for. Exit status 0 when every test passed, 1
//! when one failed or the application has errors, 2 on usage or I/O
//! problems or a bad test file.

use crate::apptest::{self, case, coverage::Coverage, report, run};
use crate::output::checked_ir;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The options of `sitlogc test`.
pub struct Options {
    pub filter: Option<String>,
    pub exact: bool,
    pub jobs: Option<usize>,
    pub json: bool,
    pub junit: Option<PathBuf>,
    pub coverage: bool,
    pub coverage_table: Option<PathBuf>,
    pub coverage_file: Option<PathBuf>,
}

fn out(text: &str) {
    let mut o = std::io::stdout().lock();
    let _ = o.write_all(text.as_bytes()).and_then(|_| o.flush());
}

fn write(path: &Path, text: &str, what: &str) -> bool {
    match std::fs::write(path, text) {
        Ok(()) => true,
        Err(e) => {
            sitlog_runtime::errln!("error: cannot write {what} {}: {e}", path.display());
            false
        }
    }
}

/// `sitlogc test APP`.
pub fn test_app(app: &Path, options: Options) -> u8 {
    let started = Instant::now();
    if !app.is_dir() {
        sitlog_runtime::errln!(
            "error: {} is not an application directory (its tests are in its tests/ directory)",
            app.display()
        );
        return 2;
    }
    let files = match apptest::test_files(app) {
        Ok(f) => f,
        Err(e) => {
            sitlog_runtime::errln!("error: {e}");
            return 2;
        }
    };
    // Every test file is read first: a bad one is reported, and nothing runs.
    let mut cases = Vec::new();
    let mut bad = 0;
    for path in &files {
        let text = match apptest::read_text(path) {
            Ok(t) => t,
            Err(e) => {
                sitlog_runtime::errln!("error: cannot read the test {e}");
                bad += 1;
                continue;
            }
        };
        match case::parse(path, &text) {
            Ok(c) => cases.push((c, text)),
            Err(errors) => {
                for e in errors {
                    sitlog_runtime::errln!("{e}");
                }
                bad += 1;
            }
        }
    }
    if bad > 0 {
        sitlog_runtime::errln!("error: {bad} test file(s) could not be read; no test ran");
        return 2;
    }
    let total = cases.len();
    if let Some(f) = &options.filter {
        cases.retain(|(c, _)| {
            if options.exact {
                c.name == *f
            } else {
                c.name.contains(f.as_str())
            }
        });
    }
    let filtered = total - cases.len();
    let ir = match checked_ir(app) {
        Ok(ir) => ir,
        Err(code) => return code,
    };
    let assets = match sitlog_robot::Assets::from_app(app) {
        Ok(a) => a,
        Err(e) => {
            sitlog_runtime::errln!("{e}");
            return 2;
        }
    };
    let jobs = options.jobs.unwrap_or_else(|| {
        std::thread::available_parallelism()
            .map(usize::from)
            .unwrap_or(1)
    });
    if !options.json {
        out(&format!(
            "\nrunning {} test{} ({})\n",
            cases.len(),
            if cases.len() == 1 { "" } else { "s" },
            app.join(apptest::TESTS_DIR).display()
        ));
    }
    let suite = run::Suite {
        app,
        ir: &ir,
        assets: &assets,
        engine: if cases.is_empty() {
            None
        } else {
            run::shared_engine(&ir)
        },
    };
    let json = options.json;
    let outcomes = run::run_all(&suite, &cases, jobs, &mut |o| {
        if json {
            out(&report::json_line(o));
        } else {
            out(&report::line(o));
        }
    });
    let elapsed = started.elapsed();

    let mut code = if outcomes.iter().all(run::Outcome::passed) {
        0
    } else {
        1
    };
    let coverage = if options.coverage || options.coverage_file.is_some() {
        match coverage_of(app, &ir, &outcomes) {
            Ok(c) => Some(c),
            Err(()) => return 2,
        }
    } else {
        None
    };
    if json {
        let c = coverage
            .as_ref()
            .filter(|_| options.coverage)
            .map(|c| c.to_json());
        out(&report::json_summary(&outcomes, filtered, elapsed, c));
    } else {
        out(&report::summary(&outcomes, filtered, elapsed));
    }
    if let Some(path) = &options.junit {
        let name = sitlog_robot::app_name(app);
        if !write(
            path,
            &report::junit(&name, &outcomes, elapsed),
            "the JUnit file",
        ) {
            code = 2;
        }
    }
    if let (Some(c), true) = (&coverage, options.coverage) {
        let table = format!(
            "coverage of {} by {} test{}:\n{}",
            app.display(),
            outcomes.len(),
            if outcomes.len() == 1 { "" } else { "s" },
            c.table()
        );
        match &options.coverage_table {
            Some(path) if !write(path, &table, "the coverage table") => code = 2,
            Some(_) => {}
            None if !json => out(&format!("\n{table}")),
            None => {}
        }
    }
    if let Some(path) = &options.coverage_file {
        let text: String = outcomes.iter().map(|o| o.trace.as_str()).collect();
        if !write(path, &text, "the coverage file") {
            code = 2;
        }
    }
    code
}

/// The coverage of the tests' runs on the whole program's diagram.
fn coverage_of(
    app: &Path,
    ir: &sitlog_compiler::ir::Ir,
    outcomes: &[run::Outcome],
) -> Result<Coverage, ()> {
    let options = sitlog_compiler::diagram::Options {
        dm: None,
        main: Some("main".to_owned()),
        title: sitlog_compiler::build::app_ident(app),
    };
    let diagram = sitlog_compiler::diagram::diagram(ir, &options).map_err(|e| {
        sitlog_runtime::errln!("error: the program's diagram, for the coverage: {e}");
    })?;
    let trace: String = outcomes.iter().map(|o| o.trace.as_str()).collect();
    let overlay = sitlog_graph::trace::read(&diagram, &trace).map_err(|e| {
        sitlog_runtime::errln!("error: the tests' transitions: {e}");
    })?;
    Ok(Coverage::of(&diagram, &overlay))
}
