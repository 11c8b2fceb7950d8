//! Issue 39, the holes a new user found: what `check` passed and `run`
//! then failed on, in an application made by `sitlogc new NAME --robot`
//! and changed as the issue says. Each test fails on the checker before
//! the issue: a misspelt exit arc of a call with computed arguments, a
//! misspelt next situation with arguments (and its run-time error without
//! a place), a misspelt shelf in the world file, a library DM missing from
//! `models` or misspelt there, a misspelt variable.

use crate::support::sitlogc;
use std::path::{Path, PathBuf};

/// A fresh `sitlogc new b --robot` in a temporary directory (kept alive
/// by the returned guard), each edit (file, text, replacement) applied.
fn robot_app(edits: &[(&str, &str, &str)]) -> (tempfile::TempDir, PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let out = sitlogc()
        .args(["new", "b", "--robot"])
        .current_dir(tmp.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let app = tmp.path().join("b");
    for (file, from, to) in edits {
        let path = app.join(file);
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text.matches(from).count(), 1, "{file}: `{from}` once");
        std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
    }
    (tmp, app)
}

/// `sitlogc check --format json APP`: exit status and the diagnostics.
fn check(app: &Path) -> (i32, Vec<serde_json::Value>) {
    let out = sitlogc()
        .args(["check", "--format", "json"])
        .arg(app)
        .output()
        .unwrap();
    let diags = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    (out.status.code().unwrap(), diags)
}

fn errors(diags: &[serde_json::Value]) -> Vec<(String, String, String)> {
    diags
        .iter()
        .filter(|d| d["severity"] == "error")
        .map(|d| {
            (
                d["code"].as_str().unwrap().to_owned(),
                d["message"].as_str().unwrap().to_owned(),
                d["help"].as_str().unwrap_or("").to_owned(),
            )
        })
        .collect()
}

#[test]
fn the_robot_template_checks_clean() {
    let (_tmp, app) = robot_app(&[]);
    assert_eq!(check(&app), (0, vec![]));
}

/// The template's own `ask(...)` call has `get(...)` and `apply(...)`
/// arguments: its callee, arity and final situations are still known.
#[test]
fn exit_arc_of_a_call_with_computed_arguments() {
    let (_tmp, app) = robot_app(&[("main.dm", "success(Object) :", "sucess(Object) :")]);
    let (code, diags) = check(&app);
    assert_eq!(code, 1);
    assert_eq!(
        errors(&diags),
        [(
            "E0218".to_owned(),
            "`sucess(Object)` is not a final situation of DM `ask`".to_owned(),
            "did you mean `success(Answer)`?".to_owned()
        )]
    );
    // A dead arc beside one for each final situation: only a warning
    // (the original runs it, never taking the arc).
    let (_tmp, app) = robot_app(&[(
        "main.dm",
        "success(Object) : empty => fetch(Object),",
        "success(Object) : empty => fetch(Object),\n        sucess(Object) : empty => fetch(Object),",
    )]);
    let (code, diags) = check(&app);
    assert_eq!(code, 0);
    let codes: Vec<&str> = diags.iter().map(|d| d["code"].as_str().unwrap()).collect();
    assert_eq!(codes, ["W0231"]);
    // The arity too.
    let (_tmp, app) = robot_app(&[("main.dm", "get(vocab, _), _, _)", "get(vocab, _), _)")]);
    let (code, diags) = check(&app);
    assert_eq!(code, 1);
    assert_eq!(errors(&diags)[0].0, "E0217");
}

/// `=> serch(Shelves)`: E0212 with "did you mean" whatever its arguments,
/// and no "unreachable" warning for `search(Shelves)`, taken as meant; the
/// run (`--allow-unresolved`) stops at the arc, with its file, line and
/// column.
#[test]
fn next_situation_typo_with_arguments() {
    let (_tmp, app) = robot_app(&[(
        "fetch.dm",
        "                => search(Shelves)",
        "                => serch(Shelves)",
    )]);
    let (code, diags) = check(&app);
    assert_eq!(code, 1);
    assert_eq!(
        errors(&diags),
        [(
            "E0212".to_owned(),
            "no situation `serch(Shelves)` in DM `fetch`".to_owned(),
            "did you mean `search(Shelves)`?".to_owned()
        )]
    );
    assert_eq!(diags.len(), 1, "{diags:?}");
    let out = sitlogc()
        .args(["run", "--allow-unresolved", "--format", "json"])
        .arg(&app)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let error = report["error"].as_str().unwrap();
    assert!(
        error.contains("situation `is`, arc 1 (")
            && error.contains("fetch.dm:14:9): there is no situation `serch(["),
        "{error}"
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("fetch.dm:14:9"), "{stderr}");
}

/// `on = "fridg"` in world.toml: `check` reports what `run` stops on, at
/// the same line and column (E0007); a bad KB and ros2.toml too.
#[test]
fn check_reads_the_world_kb_and_ros2_files() {
    let (_tmp, app) = robot_app(&[("world.toml", "on = \"fridge\"", "on = \"fridg\"")]);
    let (code, diags) = check(&app);
    assert_eq!(code, 1);
    let message = "object `milk` is on shelf `fridg`, which is not defined; did you mean `fridge`?";
    assert_eq!(
        errors(&diags),
        [("E0007".to_owned(), message.to_owned(), String::new())]
    );
    let at = (&diags[0]["line"], &diags[0]["column"]);
    // An error of the application's files: `run` exits 1 for the world as
    // for the KB (session 17; the world's was 2, as for a missing file).
    let run = sitlogc().arg("run").arg(&app).output().unwrap();
    assert_eq!(run.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains(&format!("world.toml:{}:{}: error: {message}", at.0, at.1)),
        "{stderr}"
    );
    let (_kb_tmp, kb_app) = robot_app(&[]);
    let kb = std::fs::read_to_string(kb_app.join("knowledge.kb")).unwrap();
    std::fs::write(kb_app.join("knowledge.kb"), format!("{kb}\narity(\n")).unwrap();
    let run = sitlogc().arg("run").arg(&kb_app).output().unwrap();
    assert_eq!(run.status.code(), Some(1), "{run:?}");
    std::fs::write(app.join("ros2.toml"), "qos = 3\n").unwrap();
    let kb = std::fs::read_to_string(app.join("knowledge.kb")).unwrap();
    std::fs::write(app.join("knowledge.kb"), format!("{kb}\narity(\n")).unwrap();
    let (code, diags) = check(&app);
    assert_eq!(code, 1);
    let files: Vec<&str> = diags
        .iter()
        .map(|d| d["file"].as_str().unwrap().rsplit('/').next().unwrap())
        .collect();
    let expected: &[&str] = if cfg!(feature = "ros2") {
        &["world.toml", "knowledge.kb", "ros2.toml"]
    } else {
        &["world.toml", "knowledge.kb"]
    };
    assert_eq!(files, expected, "{diags:?}");
    if cfg!(feature = "ros2") {
        // At the value that is wrong (`3`, not a table), not at the file's start.
        assert_eq!(
            (&diags[2]["line"], &diags[2]["column"]),
            (&1.into(), &7.into()),
            "{diags:?}"
        );
        std::fs::write(app.join("ros2.toml"), "[timeouts]\nanswer = -1.0\n").unwrap();
        let (_, diags) = check(&app);
        let ros2 = diags
            .iter()
            .find(|d| d["file"].as_str().unwrap().ends_with("ros2.toml"));
        let ros2 = ros2.expect("an error of ros2.toml");
        assert_eq!(
            (&ros2["line"], &ros2["column"]),
            (&2.into(), &10.into()),
            "{ros2:?}"
        );
        assert!(
            ros2["message"]
                .as_str()
                .unwrap()
                .starts_with("timeouts.answer must be"),
            "{ros2:?}"
        );
    }
}

/// A library DM missing from `models` names the entry to add; a misspelt
/// entry gets "did you mean".
#[test]
fn library_dms_and_models_entries_get_a_help() {
    let (_tmp, app) = robot_app(&[("models", "'behaviors/find.dm'.\n", "")]);
    let (code, diags) = check(&app);
    assert_eq!(code, 1);
    assert_eq!(
        errors(&diags),
        [(
            "E0216".to_owned(),
            "no DM named `find`".to_owned(),
            "DM `find` is in the library's `behaviors/find.dm`: add `'behaviors/find.dm'.` to `models`"
                .to_owned()
        )]
    );
    let (_tmp, app) = robot_app(&[("models", "'behaviors/find.dm'.", "'behaviors/fnd.dm'.")]);
    let (code, diags) = check(&app);
    assert_eq!(code, 1);
    let e = errors(&diags);
    assert_eq!(e[0].0, "E0004");
    assert!(
        e[0].2.ends_with(": did you mean `'behaviors/find.dm'.`?"),
        "{}",
        e[0].2
    );
}

/// `Drnk` where `Drink` has a value: W0228 says "did you mean `Drink`?".
#[test]
fn misspelt_variable_gets_did_you_mean() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(
        tmp.path().join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> speech, arcs ==> [said(Drink) : say(['One', Drnk]) => fs]], [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    let (code, diags) = check(tmp.path());
    assert_eq!(code, 0);
    let w: Vec<_> = diags.iter().filter(|d| d["code"] == "W0228").collect();
    assert_eq!(w.len(), 1, "{diags:?}");
    assert_eq!(w[0]["help"], "did you mean `Drink`?");
}

/// A clause of `user_functions.pl` that does not read (marcopolo's
/// `parse/2`, whose body starts with `|`) is skipped, as SWI-Prolog's
/// consult skips it: W0008, and the run uses the rest of the file. A
/// clause that reads with SWI-Prolog's operators (`:- dynamic seen/1.`)
/// is not skipped.
#[test]
fn a_prolog_clause_that_does_not_read_is_skipped() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(
        tmp.path().join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : say(apply(hi(_), [x])) => fs]], [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    std::fs::write(
        tmp.path().join("user_functions.pl"),
        "parse(In, Out) :-\n  % the interpreter\n|  ( In = Out -> true | otherwise -> fail ).\nhi(_) :- assign_func_value(hello).\n:- dynamic seen/1, other/2.\n",
    )
    .unwrap();
    let (code, diags) = check(tmp.path());
    assert_eq!(code, 0, "{diags:?}");
    assert_eq!(diags.len(), 1, "{diags:?}");
    assert_eq!(diags[0]["code"], "W0008");
    assert_eq!(
        (&diags[0]["line"], &diags[0]["column"]),
        (&3.into(), &1.into())
    );
    let out = sitlogc().arg("run").arg(tmp.path()).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("Golem says: hello"), "{stderr}");
}

/// W0243: a place given by name to `move` (or `navigate`) that the world
/// file does not have: the run goes on (`unknown_place`), so a warning,
/// with *did you mean*.
#[test]
fn a_place_not_in_the_world_gets_did_you_mean() {
    let (_tmp, app) = robot_app(&[("fetch.dm", "move(living_room, _)", "move(livng_room, _)")]);
    let (code, diags) = check(&app);
    assert_eq!(code, 0, "{diags:?}");
    assert_eq!(diags.len(), 1, "{diags:?}");
    assert_eq!(diags[0]["code"], "W0243");
    assert_eq!(diags[0]["help"], "did you mean `living_room`?");
    assert!(diags[0]["file"].as_str().unwrap().ends_with("fetch.dm"));
}
