//! `sitlogc new NAME`: the new application checks, runs its script with the
//! golden output it ships, and an existing path is never overwritten.

use crate::support::sitlogc;
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
    assert_eq!(made.status.code(), Some(0), "{}", stderr(&made));
    let checked = run(&["check", "x"]);
    assert_eq!(checked.status.code(), Some(0), "{}", stderr(&checked));
    assert!(
        stderr(&checked).contains("0 error(s), 0 warning(s)"),
        "{}",
        stderr(&checked)
    );
    let ran = run(&["run", "x", "--script", "x/script.txt"]);
    assert_eq!(ran.status.code(), Some(0), "{}", stderr(&ran));
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
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(Path::new(&app.join("main.dm")).is_file());
    let out = sitlogc().arg("check").arg(&app).output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}
