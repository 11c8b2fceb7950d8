//! A new user's own task: `sitlogc new NAME [--robot]` makes an application
//! that checks, runs with the golden output it ships, and never overwrites
//! an existing path; the behaviour library is built into `sitlogc` and named
//! without a path, so an application copied anywhere runs (issue 30), a
//! local copy of a library file wins, and `check --origins` says which.

use crate::support::{assert_ok, sitlogc, workspace};
use std::path::Path;

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn new_app_checks_and_runs_at_once() {
    let tmp = tempfile::tempdir().unwrap();
    // sitlogc new x && sitlogc check x && sitlogc run x --script x/script.txt
    let run = |args: &[&str]| {
        sitlogc()
            .args(args)
            .current_dir(tmp.path())
            .output()
            .unwrap()
    };
    let made = run(&["new", "x"]);
    assert_ok(&made);
    let checked = run(&["check", "x"]);
    assert_ok(&checked);
    assert!(
        stderr(&checked).contains("0 error(s), 0 warning(s)"),
        "{}",
        stderr(&checked)
    );
    let ran = run(&["run", "x", "--script", "x/script.txt"]);
    assert_ok(&ran);
    // The golden test the application ships passes.
    let expected = std::fs::read_to_string(tmp.path().join("x/expected.txt")).unwrap();
    assert_eq!(String::from_utf8_lossy(&ran.stdout), expected);
    assert!(
        stderr(&ran).contains("Golem says: Nice to meet you, ada"),
        "{}",
        stderr(&ran)
    );
    // The README names the application.
    let readme = std::fs::read_to_string(tmp.path().join("x/README.md")).unwrap();
    assert!(readme.contains("sitlogc run x --script x/script.txt"));
}

#[test]
fn new_refuses_an_existing_directory_or_file() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("mine");
    std::fs::create_dir(&dir).unwrap();
    std::fs::write(dir.join("main.dm"), "% my own work\n").unwrap();
    let file = tmp.path().join("notes.txt");
    std::fs::write(&file, "keep").unwrap();
    for path in [&dir, &file] {
        let out = sitlogc().arg("new").arg(path).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
        assert!(stderr(&out).contains("already exists"), "{}", stderr(&out));
    }
    // Untouched.
    assert_eq!(
        std::fs::read_to_string(dir.join("main.dm")).unwrap(),
        "% my own work\n"
    );
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep");
}

#[test]
fn new_makes_missing_parents() {
    let tmp = tempfile::tempdir().unwrap();
    let app = tmp.path().join("a/b/robot_task");
    let out = sitlogc().arg("new").arg(&app).output().unwrap();
    assert_ok(&out);
    assert!(Path::new(&app.join("main.dm")).is_file());
    let out = sitlogc().arg("check").arg(&app).output().unwrap();
    assert_ok(&out);
}

/// `sitlogc new x --robot && sitlogc check x && sitlogc run x`: the task on
/// the simulated robot checks without a warning, runs as its golden output
/// says, and shows the library's recovery protocols at work.
#[test]
fn new_robot_app_checks_and_runs_at_once() {
    let tmp = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        sitlogc()
            .args(args)
            .current_dir(tmp.path())
            .env_remove("SITLOG_LIBRARY")
            .output()
            .unwrap()
    };
    let made = run(&["new", "x", "--robot"]);
    assert_ok(&made);
    assert!(tmp.path().join("x/world.toml").is_file());
    assert!(tmp.path().join("x/knowledge.kb").is_file());
    let checked = run(&["check", "x"]);
    assert_ok(&checked);
    assert!(
        stderr(&checked).contains("0 error(s), 0 warning(s)"),
        "{}",
        stderr(&checked)
    );
    let ran = run(&["run", "x"]);
    assert_ok(&ran);
    let out = String::from_utf8_lossy(&ran.stdout);
    let expected = std::fs::read_to_string(tmp.path().join("x/expected.txt")).unwrap();
    assert_eq!(out, expected);
    for line in [
        // ask's recovery protocol (ask_again), then the answer understood
        "Golem: Sorry, I did not understand you.",
        "Ada: the juice please",
        // find: not where the KB says drinks are
        "Golem: The juice is not in the fridge.",
        // take's recovery protocol (regrasp) after the fault
        "Golem: I could not grasp the juice; I will try again.",
        "Golem: Here is the juice.",
    ] {
        assert!(out.contains(line), "no {line:?} in:\n{out}");
    }
    let readme = std::fs::read_to_string(tmp.path().join("x/README.md")).unwrap();
    assert!(readme.contains("sitlogc test x --coverage"), "{readme}");
}

/// Copies the files of `from` (one level, as the shipped apps are) into `to`.
fn copy_app(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let p = entry.unwrap().path();
        if p.is_file() {
            std::fs::copy(&p, to.join(p.file_name().unwrap())).unwrap();
        }
    }
}

/// The home butler copied out of the repository runs with the same
/// conversation: its library DMs and grammar come from `sitlogc` itself.
#[test]
fn a_copy_of_the_home_app_runs_anywhere() {
    let tmp = tempfile::tempdir().unwrap();
    let home = workspace().join("dms/apps/home");
    let copy = tmp.path().join("my_butler");
    copy_app(&home, &copy);
    let run = |app: &Path| {
        let out = sitlogc()
            .arg("run")
            .arg(app)
            .env_remove("SITLOG_LIBRARY")
            .output()
            .unwrap();
        assert_ok(&out);
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let theirs = crate::support::home_run();
    assert!(theirs.contains("Golem: Hi, Luis."), "{theirs}");
    assert_eq!(run(&copy), theirs);
}

/// A local copy of a library file wins over the library's; `check
/// --origins` says where each library file came from; a library name found
/// nowhere is E0004 with the places looked at; $SITLOG_LIBRARY comes first.
#[test]
fn library_files_local_copies_and_origins() {
    let tmp = tempfile::tempdir().unwrap();
    let app = tmp.path().join("x");
    let made = sitlogc()
        .arg("new")
        .arg(&app)
        .arg("--robot")
        .output()
        .unwrap();
    assert_ok(&made);
    let check = |app: &Path, library: Option<&Path>| {
        let mut cmd = sitlogc();
        cmd.args(["check", "--origins"]).arg(app);
        match library {
            Some(dir) => cmd.env("SITLOG_LIBRARY", dir),
            None => cmd.env_remove("SITLOG_LIBRARY"),
        };
        cmd.output().unwrap()
    };
    let out = check(&app, None);
    assert_ok(&out);
    let text = stderr(&out);
    let version = env!("CARGO_PKG_VERSION");
    assert!(
        text.contains(&format!(
            "uses behaviors/take.dm from the library built into sitlogc {version} (library:/behaviors/take.dm)"
        )),
        "{text}"
    );
    assert!(
        text.contains("uses behaviors/language.pl from the library built into sitlogc"),
        "{text}"
    );
    // A local copy that says something else wins.
    let take = std::fs::read_to_string(workspace().join("dms/behaviors/take.dm")).unwrap();
    std::fs::create_dir_all(app.join("behaviors")).unwrap();
    std::fs::write(
        app.join("behaviors/take.dm"),
        take.replace("'I took the'", "'Got the'"),
    )
    .unwrap();
    let out = check(&app, None);
    let text = stderr(&out);
    assert!(
        text.contains("uses behaviors/take.dm from its own copy")
            && text.contains(&format!(
                "(instead of the library built into sitlogc {version})"
            )),
        "{text}"
    );
    let ran = sitlogc().arg("run").arg(&app).output().unwrap();
    let said = String::from_utf8_lossy(&ran.stdout);
    assert!(said.contains("Golem: Got the juice."), "{said}");
    // $SITLOG_LIBRARY is searched before the built-in library.
    let lib = tmp.path().join("lib");
    std::fs::create_dir_all(lib.join("behaviors")).unwrap();
    std::fs::copy(
        workspace().join("dms/behaviors/ask.dm"),
        lib.join("behaviors/ask.dm"),
    )
    .unwrap();
    let text = stderr(&check(&app, Some(&lib)));
    assert!(
        text.contains(&format!(
            "uses behaviors/ask.dm from $SITLOG_LIBRARY directory {}",
            lib.display()
        )),
        "{text}"
    );
    // A name found nowhere.
    let models = std::fs::read_to_string(app.join("models")).unwrap();
    std::fs::write(app.join("models"), format!("{models}'behaviors/fly.dm'.\n")).unwrap();
    let out = check(&app, None);
    assert_eq!(out.status.code(), Some(1));
    let text = stderr(&out);
    assert!(text.contains("[E0004]"), "{text}");
    assert!(
        text.contains(
            "not in the application directory, nor in the library (the library built into sitlogc"
        ),
        "{text}"
    );
}
