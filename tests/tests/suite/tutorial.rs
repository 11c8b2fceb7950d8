//! The tutorial's application (`dms/examples/tutorial`, walked through in
//! `docs/guide/tutorial.md`) checks without a warning and runs on its
//! script as `sitlogc run dms/examples/tutorial --script
//! dms/examples/tutorial/script.txt` does (and on `script_no_drink.txt`),
//! on the interpreter and on the generated code; what it prints is an insta
//! snapshot, and the guide must show exactly that output, so the tutorial
//! cannot rot. (Every other block of the page is checked against a run of
//! the `sitlogc` binary by `cli/tests/cli/tutorial.rs`.)

use sitlog_robot::console::SharedBuf;
use sitlog_robot::{Assets, RunArgs, Runner, Streams};
use sitlog_runtime::app::App;
use sitlog_runtime::machine::Options;
use sitlog_runtime::testmode::{ScriptPerception, TextActions};
use sitlog_runtime::Functions;
use sitlog_tests::compiled::generated::examples_tutorial;
use sitlog_tests::workspace;
use std::path::PathBuf;

fn app() -> PathBuf {
    workspace().join("dms/examples/tutorial")
}

/// What `sitlogc run APP --script FILE` prints: (stdout, stderr, status).
fn run<A: App>(program: &A, functions: Functions, script: &str) -> (String, String, u8) {
    // stdout (the report) as `sitlogc run` writes it
    let args = RunArgs {
        script: Some(app().join(script)),
        ..RunArgs::default()
    };
    let assets = Assets::from_app(&app()).expect("the tutorial's files are readable");
    let out = SharedBuf::default();
    let streams = Streams {
        stdout: Box::new(out.clone()),
        stderr: Box::new(std::io::sink()),
        stdout_is_terminal: false,
        stderr_is_terminal: false,
    };
    let code = Runner::new(streams).run(program, functions.clone(), &args, &assets);
    // stderr: test mode renders the actions there, as `TextActions` does
    let text = std::fs::read_to_string(app().join(script)).unwrap();
    let mut perception = ScriptPerception::new(script, text);
    let err = SharedBuf::default();
    let mut actions = TextActions::new(err.clone(), program.basic_actions());
    let (outcome, _) = sitlog_runtime::app::run(
        program,
        "main",
        None,
        Options::default(),
        functions,
        &mut perception,
        &mut actions,
        None,
    )
    .expect("the tutorial starts");
    assert!(outcome.result.is_ok());
    (out.text(), err.text(), code)
}

fn guide() -> String {
    std::fs::read_to_string(workspace().join("docs/guide/tutorial.md"))
        .expect("docs/guide/tutorial.md is readable")
}

#[test]
fn the_tutorial_app_checks_without_a_warning() {
    let (result, diags) = sitlog_compiler::check_path(&app()).expect("readable");
    assert!(result.is_ok(), "{diags:?}");
    assert!(diags.is_empty(), "{diags:?}");
}

#[test]
fn the_tutorial_app_runs_as_the_guide_shows() {
    let (ir, functions) = sitlog_tests::scenario::interpreter(&app());
    let (out, err, code) = run(&ir, functions, "script.txt");
    assert_eq!(code, 0, "{out}\n{err}");
    // the same on the code tests/build.rs generated
    let compiled = run(
        examples_tutorial::program(),
        Functions::standard(),
        "script.txt",
    );
    assert_eq!((&out, &err, code), (&compiled.0, &compiled.1, compiled.2));
    insta::assert_snapshot!("tutorial_history", out);
    insta::assert_snapshot!("tutorial_said", err);
    // The guide pastes both outputs as they are.
    let guide = guide();
    for (what, text) in [("history", &out), ("actions", &err)] {
        assert!(
            guide.contains(text.trim_end()),
            "docs/guide/tutorial.md does not show the run's {what} as it is now:\n{text}"
        );
    }
}

#[test]
fn the_tutorial_app_gives_up_after_three_questions() {
    let (ir, functions) = sitlog_tests::scenario::interpreter(&app());
    let (out, err, code) = run(&ir, functions, "script_no_drink.txt");
    assert_eq!(code, 0, "{out}\n{err}");
    // the same on the code tests/build.rs generated
    let compiled = run(
        examples_tutorial::program(),
        Functions::standard(),
        "script_no_drink.txt",
    );
    assert_eq!((&out, &err, code), (&compiled.0, &compiled.1, compiled.2));
    insta::assert_snapshot!("tutorial_gave_up", out);
    assert!(guide().contains(out.trim_end()));
}

/// Step 4 of the tutorial: a typo in a next situation, as `sitlogc check`
/// reports it (without colours).
#[test]
fn a_typo_is_reported_as_the_guide_shows() {
    use sitlog_compiler::diag::{self, Severity};
    let tmp = std::env::temp_dir().join(format!("sitlog-tutorial-{}", std::process::id()));
    let copy = tmp.join("dms/examples/tutorial");
    std::fs::create_dir_all(&copy).unwrap();
    for entry in std::fs::read_dir(app()).unwrap() {
        let p = entry.unwrap().path();
        std::fs::copy(&p, copy.join(p.file_name().unwrap())).unwrap();
    }
    let dm = std::fs::read_to_string(copy.join("ask_drink.dm")).unwrap();
    let typo = "Other : say(msg_format(['Sorry, we have no', Other], _)) => retry,";
    assert!(dm.contains(typo), "the tutorial's ask_drink.dm changed");
    std::fs::write(
        copy.join("ask_drink.dm"),
        dm.replace(typo, &typo.replace("=> retry", "=> rerty")),
    )
    .unwrap();
    let (result, diags) = sitlog_compiler::check_path(&copy).expect("readable");
    let program = match &result {
        Ok(checked) => checked.program(),
        Err(program) => program,
    };
    let mut text: String = diags
        .iter()
        .map(|d| diag::render_human(d, &program.sources, false))
        .collect();
    let errors = diags
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .count();
    text.push_str(&format!(
        "checked 1 program(s): {errors} error(s), {} warning(s)\n",
        diags.len() - errors
    ));
    let prefix = format!("{}/", tmp.display());
    let text = text.replace(&prefix, "");
    let _ = std::fs::remove_dir_all(&tmp);
    insta::assert_snapshot!("tutorial_typo", text);
    assert!(
        guide().contains(text.trim_end()),
        "docs/guide/tutorial.md does not show `check`'s report as it is now:\n{text}"
    );
}
