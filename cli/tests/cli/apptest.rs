//! `sitlogc test APP` (issue 40): the scenario applications and a new robot
//! application pass their own tests, with the arc coverage shown and drawn;
//! a failing test says why (the output marked) and the run exits 1; a
//! filter, JSON lines and JUnit XML; a bad test file is an error at its
//! file:line:col before anything runs.

use crate::support::{assert_ok, sitlogc, workspace};
use std::path::Path;

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// `sitlogc test APP --coverage --junit --coverage-file`, in `dir`.
fn test_with_coverage(app: &Path, dir: &Path) -> (String, String, String) {
    let junit = dir.join("junit.xml");
    let cov = dir.join("coverage.jsonl");
    let out = sitlogc()
        .arg("test")
        .arg(app)
        .args(["--coverage", "--junit"])
        .arg(&junit)
        .arg("--coverage-file")
        .arg(&cov)
        .env_remove("SITLOG_LIBRARY")
        .output()
        .unwrap();
    let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
    assert_eq!(out.status.code(), Some(0), "{stdout}\n{stderr}");
    (
        stdout,
        std::fs::read_to_string(junit).unwrap(),
        cov.display().to_string(),
    )
}

#[test]
fn the_scenario_apps_pass_their_world_variant_tests() {
    let tmp = tempfile::tempdir().unwrap();
    for (app, tests, dm) in [("home", 3, "tidy"), ("supermarket", 3, "run_plan")] {
        let app = workspace().join("dms/apps").join(app);
        let (stdout, junit, cov) = test_with_coverage(&app, tmp.path());
        assert!(
            stdout.contains(&format!(
                "test result: ok. {tests} passed; 0 failed; 0 filtered out"
            )),
            "{stdout}"
        );
        // the coverage table: the app's DMs and the library's, then the
        // arcs never taken with where they are written
        assert!(stdout.contains("DM "), "{stdout}");
        assert!(stdout.contains("library:/behaviors/take.dm"), "{stdout}");
        assert!(stdout.contains("arcs never taken"), "{stdout}");
        let total = stdout.lines().find(|l| l.starts_with("total ")).unwrap();
        assert!(total.contains('%'), "{total}");
        assert_eq!(junit.matches("<testcase ").count(), tests, "{junit}");
        assert!(!junit.contains("<failure"), "{junit}");
        // the diagram of one DM with the coverage: arcs never taken red
        // and dashed, the taken ones green
        let out = sitlogc()
            .arg("graph")
            .arg(&app)
            .args(["--dm", dm, "--coverage", &cov])
            .output()
            .unwrap();
        assert_ok(&out);
        let svg = text(&out.stdout);
        assert!(svg.contains("never taken"), "{dm}");
        assert!(svg.contains("arrow-untaken"), "{dm}");
        assert!(svg.contains("arrow-taken"), "{dm}");
    }
}

#[test]
fn a_new_robot_app_tests_its_apology_and_a_failure_is_shown() {
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
    // One run serves the passing case, the failing one and the coverage
    // (each case starts a Prolog engine): a test expecting what the robot
    // does not say fails, with the output marked.
    let t = tmp.path().join("x/tests/juice_missing.toml");
    let changed = std::fs::read_to_string(&t).unwrap().replace(
        "\"Golem: Goodbye.\",",
        "\"Golem: Goodbye.\",\n  \"Golem: See you tomorrow.\",",
    );
    std::fs::write(&t, changed).unwrap();
    let failed = run(&["test", "x", "--coverage"]);
    let stdout = text(&failed.stdout);
    assert_eq!(
        failed.status.code(),
        Some(1),
        "{stdout}{}",
        text(&failed.stderr)
    );
    assert!(
        stdout.contains("test fetch_juice ... ok\ntest juice_missing ... FAILED"),
        "{stdout}"
    );
    assert!(
        stdout.contains("x/tests/juice_missing.toml:16:3: expected a line containing `Golem: See you tomorrow.` after line"),
        "{stdout}"
    );
    assert!(stdout.contains("= Golem: Goodbye."), "{stdout}");
    assert!(
        stdout.contains("     - Golem: See you tomorrow. (x/tests/juice_missing.toml:16:3)"),
        "{stdout}"
    );
    assert!(
        stdout.contains("test result: FAILED. 1 passed; 1 failed; 0 filtered out"),
        "{stdout}"
    );
    // the apology arc of main is taken (by juice_missing, which ran to its
    // end): only ask's error arc of main is left
    let never: Vec<&str> = stdout
        .lines()
        .filter(|l| l.trim_start().starts_with("x/main.dm:"))
        .collect();
    assert_eq!(never.len(), 1, "{stdout}");
    assert!(never[0].contains("ask: error(_)"), "{stdout}");

    // The filter (a part of the name) runs the failing case alone; JSON lines.
    let json = run(&["test", "x", "missing", "--format", "json"]);
    assert_eq!(json.status.code(), Some(1));
    let lines: Vec<serde_json::Value> = text(&json.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[0]["name"], "juice_missing");
    assert_eq!(lines[0]["status"], "failed");
    assert_eq!(lines[1]["type"], "summary");
    assert_eq!(lines[1]["failed"], 1);
    assert_eq!(lines[1]["filtered_out"], 1);
    // With --exact a part of the name is no name: nothing runs.
    let exact = run(&["test", "x", "missing", "--exact", "--format", "json"]);
    let lines: Vec<serde_json::Value> = text(&exact.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 1, "{}", text(&exact.stdout));
    assert_eq!(lines[0]["type"], "summary");
    assert_eq!(lines[0]["filtered_out"], 2);
}

#[test]
fn bad_test_files_are_errors_at_their_place_and_nothing_runs() {
    let tmp = tempfile::tempdir().unwrap();
    let app = tmp.path().join("x");
    let made = sitlogc()
        .arg("new")
        .arg(&app)
        .arg("--robot")
        .output()
        .unwrap();
    assert_eq!(made.status.code(), Some(0));
    let tests = app.join("tests");
    std::fs::write(
        tests.join("a_typo.toml"),
        "[world]\nmising = [\"juice\"]\n[expect]\nstatus = \"fine\"\nlines = \"Golem: hi\"\n",
    )
    .unwrap();
    std::fs::write(tests.join("b_not_toml.toml"), "[expect\nlines = [\n").unwrap();
    std::fs::write(
        tests.join("c_no_such_object.toml"),
        "[world]\nmissing = [\"cola\"]\n",
    )
    .unwrap();
    let out = sitlogc()
        .arg("test")
        .arg("x")
        .current_dir(tmp.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(text(&out.stdout), "");
    insta::assert_snapshot!("bad_test_files", text(&out.stderr));
    // A change naming what the world does not have fails that test, at
    // the change.
    std::fs::remove_file(tests.join("a_typo.toml")).unwrap();
    std::fs::remove_file(tests.join("b_not_toml.toml")).unwrap();
    let out = sitlogc()
        .args(["test", "x", "c_no"])
        .current_dir(tmp.path())
        .output()
        .unwrap();
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(
        stdout.contains("x/tests/c_no_such_object.toml:2:12: error: `world.missing`: no object `cola` in x/world.toml (its objects: apple, juice, milk)"),
        "{stdout}"
    );
}

#[test]
fn test_mode_tests_take_a_script_and_compare_a_golden_output() {
    let tmp = tempfile::tempdir().unwrap();
    let made = sitlogc()
        .args(["new", "hello"])
        .current_dir(tmp.path())
        .output()
        .unwrap();
    assert_eq!(made.status.code(), Some(0));
    let tests = tmp.path().join("hello/tests");
    std::fs::create_dir(&tests).unwrap();
    // the script file and the golden output `sitlogc new` made
    std::fs::write(
        tests.join("golden.toml"),
        "script = \"../script.txt\"\n[expect]\nfinal = \"done\"\nout_arg = \"none\"\ngolden = \"../expected.txt\"\nlines = [\"Golem says: Nice to meet you, ada\"]\n",
    )
    .unwrap();
    // an inline script that runs out: the task stops with an error
    std::fs::write(
        tests.join("too_short.toml"),
        "script = [\"hello.\"]\n[expect]\nstatus = \"error\"\nerror = \"end of input\"\n",
    )
    .unwrap();
    // a golden output that differs: a diff
    std::fs::write(
        tmp.path().join("hello/other.txt"),
        "Execution history:\nsomething else\n",
    )
    .unwrap();
    std::fs::write(
        tests.join("wrong_golden.toml"),
        "script = \"../script.txt\"\n[expect]\ngolden = \"../other.txt\"\n",
    )
    .unwrap();
    let out = sitlogc()
        .args(["test", "hello", "--jobs", "1"])
        .current_dir(tmp.path())
        .output()
        .unwrap();
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(
        stdout
            .contains("test golden ... ok\ntest too_short ... ok\ntest wrong_golden ... FAILED\n"),
        "{stdout}"
    );
    assert!(
        stdout.contains("hello/tests/wrong_golden.toml:3:10: the output differs from hello/tests/../other.txt (- expected, + actual)"),
        "{stdout}"
    );
    assert!(
        stdout.contains("  Execution history:\n- something else\n+ main:"),
        "{stdout}"
    );
}
