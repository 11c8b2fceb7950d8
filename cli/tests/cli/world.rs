//! `sitlogc run` on the simulated world: the README's main job ends well,
//! and a bad world file (the app's own or `--world FILE`) stops the run
//! before it starts with `file:line:col` and exit status 2.

use crate::support::sitlogc;
use std::path::{Path, PathBuf};
use std::process::Output;

fn home() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../dms/apps/home")
}

fn run_with_world(text: &str, tag: &str) -> Output {
    let dir =
        crate::support::temp_root().join(format!("sitlogc-world-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let world = dir.join("world.toml");
    std::fs::write(&world, text).unwrap();
    let out = sitlogc()
        .arg("run")
        .arg(home())
        .arg("--world")
        .arg(&world)
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    out
}

#[test]
fn the_main_job_runs_the_home_butler_to_the_end() {
    // Exit status 0 (checked there); the run is shared with the other tests
    // that compare a run of the home butler with it.
    let stdout = crate::support::home_run();
    // In text mode the conversation and then the report go to stdout.
    assert!(stdout.starts_with("Golem: Hi, Luis.\n"), "{stdout}");
    assert!(stdout.contains("Luis: bring me something to drink and biscuits\n"));
    assert!(stdout.contains("Golem: Goodbye.\n"));
    assert!(stdout.contains("Execution history:"), "{stdout}");
}

/// An error in the world file is one of the application's files: status
/// 1, as in its KB (issue 39; a file that cannot be read stays 2).
#[test]
fn bad_world_files_exit_one_with_their_position() {
    let base = std::fs::read_to_string(home().join("world.toml")).unwrap();
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "toml",
            "[robot\n".to_owned(),
            "world.toml:1:7: error: not valid TOML",
        ),
        (
            "unknown_key",
            base.replacen("[robot]\n", "[robot]\narms = 2\n", 1),
            "unknown key `arms` in [robot]",
        ),
        (
            "unknown_place",
            base.replacen("at = \"living_room\"", "at = \"garage\"", 1),
            "garage",
        ),
        (
            "empty",
            String::new(),
            "missing key `robot` in the world file",
        ),
    ];
    for (tag, text, wanted) in cases {
        let out = run_with_world(&text, tag);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{tag}: {stderr}");
        assert!(
            stderr.contains(wanted),
            "{tag}: wanted `{wanted}` in\n{stderr}"
        );
        assert!(
            stderr.contains("world.toml:"),
            "{tag}: no position in\n{stderr}"
        );
        assert!(
            !stderr.contains("Golem:"),
            "{tag}: the run started\n{stderr}"
        );
        assert!(!stderr.contains("panicked"), "{tag}: {stderr}");
    }
}

#[test]
fn a_missing_world_file_exits_two_naming_it() {
    let out = sitlogc()
        .arg("run")
        .arg(home())
        .args(["--world", "/nonexistent/world.toml"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("/nonexistent/world.toml"), "{stderr}");
}

/// The run's options and world file are checked before the Prolog engine
/// starts (issue 30): a run that cannot start says so at once, and a bad
/// world file is the error even when the engine would refuse a clause too.
#[test]
fn a_bad_world_file_is_reported_before_the_prolog_engine_starts() {
    let tmp = tempfile::tempdir().unwrap();
    let app = tmp.path().join("app");
    std::fs::create_dir_all(&app).unwrap();
    std::fs::write(
        app.join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : f(1) => fs]], [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    // The engine refuses a clause of one of its built-ins (exit status 1).
    std::fs::write(
        app.join("user_functions.pl"),
        "atom_length(_, 0).\nf(X) :- X = 1.\n",
    )
    .unwrap();
    let refused = sitlogc().arg("run").arg(&app).output().unwrap();
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("user_functions.pl:1:1"), "{stderr}");
    let world = tmp.path().join("world.toml");
    std::fs::write(&world, "[robot\n").unwrap();
    let out = sitlogc()
        .arg("run")
        .arg(&app)
        .arg("--world")
        .arg(&world)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("world.toml:1:7: error: not valid TOML"),
        "{stderr}"
    );
    assert!(!stderr.contains("user_functions.pl"), "{stderr}");
}
