//! Checks that catch typos before running (issue 17): unknown user
//! functions and actions, "did you mean" for names, no follow-on errors
//! after a syntax error, what a single DM file and an empty directory give,
//! and a checker linear in the situations of a DM.
//!
//! Each application under `tests/checks/` is checked and its diagnostics,
//! rendered without colour, are compared with an insta snapshot.

use crate::support::sitlogc;
use sitlog_compiler::{check, diag, load};
use std::path::{Path, PathBuf};

fn cases() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/checks")
}

/// The diagnostics of `path` as the terminal shows them (no colour), paths
/// relative to `tests/checks`.
fn render(path: &Path) -> String {
    let (result, diags) =
        sitlog_cli::output::check_app(path, Default::default()).expect("readable");
    let program = match &result {
        Ok(c) => c.program(),
        Err(p) => p,
    };
    let mut out = String::new();
    for d in &diags {
        let text = diag::render_human(d, &program.sources, false);
        let text = text.replace(&format!("{}/", cases().display()), "");
        for line in text.lines() {
            out.push_str(line.trim_end());
            out.push('\n');
        }
    }
    out
}

#[test]
fn snapshots() {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(cases())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    assert!(dirs.len() >= 6);
    for dir in dirs {
        let name = dir.file_name().unwrap().to_str().unwrap().to_owned();
        insta::assert_snapshot!(name, render(&dir));
    }
}

/// `sitlogc check --format json PATH`: exit status and diagnostics.
fn check_json(path: &Path) -> (i32, Vec<serde_json::Value>, String) {
    let out = sitlogc()
        .args(["check", "--format", "json"])
        .arg(path)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "{stderr}");
    let diags = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    (out.status.code().unwrap(), diags, stderr)
}

fn codes(diags: &[serde_json::Value]) -> Vec<String> {
    diags
        .iter()
        .map(|d| d["code"].as_str().unwrap().to_owned())
        .collect()
}

/// The example: `apply(pour(D),[D])` passed; now an error at the call.
#[test]
fn unknown_function_is_an_error() {
    let (code, diags, _) = check_json(&cases().join("unknown_function"));
    assert_eq!(code, 1);
    assert_eq!(codes(&diags), ["E0224", "E0224"]);
    assert_eq!(diags[0]["message"], "no function `pour/1`");
    assert_eq!(
        (diags[0]["line"].as_u64(), diags[0]["column"].as_u64()),
        (Some(4), Some(27))
    );
    assert_eq!(diags[1]["help"], "did you mean `greeting`?");
}

/// `sya(hello)` with `say` declared in basic_actions.pl: a warning (the
/// original runs an undeclared action as doing nothing), an error with
/// `--deny-warnings`.
#[test]
fn undeclared_action_is_a_warning() {
    let (code, diags, _) = check_json(&cases().join("unknown_action"));
    assert_eq!(code, 0);
    assert_eq!(codes(&diags), ["W0225", "W0225"]);
    assert!(diags.iter().all(|d| d["severity"] == "warning"));
    let out = sitlogc()
        .args(["check", "--deny-warnings"])
        .arg(cases().join("unknown_action"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        diags[0]["message"],
        "action `sya` is not declared in basic_actions.pl"
    );
    assert_eq!(diags[0]["help"], "did you mean `say`?");
    assert!(diags[1]["message"].as_str().unwrap().contains("`beep`"));
}

#[test]
fn names_get_did_you_mean() {
    let (code, diags, _) = check_json(&cases().join("did_you_mean"));
    assert_eq!(code, 1);
    let helps: Vec<(&str, &str)> = diags
        .iter()
        .filter(|d| d["severity"] == "error")
        .map(|d| (d["code"].as_str().unwrap(), d["help"].as_str().unwrap()))
        .collect();
    assert_eq!(
        helps,
        [
            ("E0219", "did you mean `counter`?"),
            ("E0212", "did you mean `greeting`?"),
            ("E0216", "did you mean `ask_name`?"),
        ]
    );
}

/// Issue 30: a variable nothing binds, used once (`Guest`), twice (`Who`)
/// or bound only in another situation (`Drink`), is reported where it is
/// used; an action given the wrong number of arguments; `type ==> fianl`.
/// The first two are warnings (issue 39: the original runs them), the
/// typo of a type an error.
/// What does bind (an expectation, a status an earlier action reports, `=`,
/// a condition, a situation id's argument) gives nothing.
#[test]
fn unbound_variables_action_arity_and_situation_types() {
    let (code, diags, _) = check_json(&cases().join("unbound_variables"));
    assert_eq!(code, 1);
    assert_eq!(codes(&diags), ["W0228", "W0228", "W0229", "W0228", "E0230"]);
    let severities: Vec<&str> = diags
        .iter()
        .map(|d| d["severity"].as_str().unwrap())
        .collect();
    assert_eq!(
        severities,
        ["warning", "warning", "warning", "warning", "error"]
    );
    assert_eq!(
        diags[0]["message"],
        "variable `Guest` has no value here: nothing binds it before it is used"
    );
    assert_eq!(
        diags[3]["labels"].as_array().unwrap().len(),
        1,
        "{:?}",
        diags[3]
    );
    assert_eq!(
        diags[2]["message"],
        "action `say` takes 1 argument(s) (text), but is given 2"
    );
    assert_eq!(diags[4]["message"], "unknown situation type `fianl`");
    assert_eq!(diags[4]["help"], "did you mean `final`?");
    // No E0211 "no final situation" or E0206 "no arcs" after the typo,
    // no W0220 singleton for `Guest`.
}

/// An unbound variable is a warning (issue 39): the run goes on, as the
/// original's would, printing it as `_G..`; `--deny-warnings` refuses it.
#[test]
fn unbound_variable_is_a_warning_and_runs() {
    let dir = crate::support::temp_root().join(format!("sitlogc-unbound-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : say(['Welcome,', Guest]) => fs]], [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    let (code, diags, _) = check_json(&dir);
    assert_eq!((code, codes(&diags)), (0, vec!["W0228".to_owned()]));
    let out = sitlogc().arg("run").arg(&dir).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("Golem says: Welcome, _G"), "{stderr}");
    let out = sitlogc()
        .args(["run", "--deny-warnings"])
        .arg(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("[W0228] Warning"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// E0218 said "final situations of `sub`: " with nothing after it.
#[test]
fn exit_arc_of_a_dm_without_final_situation_has_a_help() {
    let (_, diags, _) = check_json(&cases().join("exit_without_final"));
    let e = diags.iter().find(|d| d["code"] == "E0218").expect("E0218");
    assert_eq!(
        e["help"],
        "DM `sub` has no final situation: add `[id ==> ok, type ==> final]` to it"
    );
}

/// A syntax error in `sub.dm` was followed by E0216 "no DM named `sub`
/// ... add its file to the application": its file is there.
#[test]
fn no_follow_on_error_after_a_syntax_error() {
    let (code, diags, _) = check_json(&cases().join("syntax_then_dm"));
    assert_eq!(code, 1);
    assert_eq!(codes(&diags), ["E0001"]);
}

/// A DM that can only have been in the broken file is not reported; one
/// that the broken file does not define still is.
#[test]
fn follow_on_errors_only_for_names_the_broken_file_may_define() {
    let (program, diags) = load::load_sources(&[
        (
            "main.dm",
            "diag_mod(main, [[id ==> is, type ==> recursive, embedded_dm ==> sub, arcs ==> [ok : empty => fs]], [id ==> is2, type ==> recursive, embedded_dm ==> other, arcs ==> [ok : empty => fs]], [id ==> fs, type ==> final]], []).\n",
        ),
        ("sub.dm", "diag_mod(sub, [[id ==> ok type ==> final]], []).\n"),
    ]);
    let (_, diags) = check::check(program, diags);
    let found: Vec<(&str, &str)> = diags
        .iter()
        .filter(|d| d.is_error())
        .map(|d| (d.code, d.message.as_str()))
        .collect();
    assert_eq!(found.len(), 2, "{found:?}");
    assert_eq!(found[0].0, "E0216");
    assert!(found[0].1.contains("`other`"));
    assert_eq!(found[1].0, "E0001");
}

/// A single DM file reads the side files beside it: its global variables,
/// actions and functions are known, as the help of E0219 says.
#[test]
fn single_file_reads_side_files_beside_it() {
    let dir = crate::support::temp_root().join(format!("sitlogc-single-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : [say(get(n, _)), apply(f, [])] => fs]], [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    std::fs::write(dir.join("global_vars.pl"), "n ==> 1.\n").unwrap();
    std::fs::write(
        dir.join("basic_actions.pl"),
        "[id ==> say, arity ==> [text], mod ==> speech, break ==> no].\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("user_functions.pl"),
        "f :- assign_func_value(1).\n",
    )
    .unwrap();
    let (code, diags, _) = check_json(&dir.join("main.dm"));
    assert_eq!((code, diags.len()), (0, 0), "{diags:?}");
    // Without the globals file, the help says where to put it.
    std::fs::remove_file(dir.join("global_vars.pl")).unwrap();
    let (code, diags, _) = check_json(&dir.join("main.dm"));
    assert_eq!(code, 1);
    assert_eq!(diags[0]["code"], "E0219");
    assert!(diags[0]["help"]
        .as_str()
        .unwrap()
        .contains("global_vars.pl beside the DMs"));
    // A DM of the application that is not in this file: check the directory.
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> recursive, embedded_dm ==> elsewhere, arcs ==> [fs : empty => fs]], [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    let (_, diags, _) = check_json(&dir.join("main.dm"));
    assert_eq!(diags[0]["code"], "E0216");
    assert!(diags[0]["help"]
        .as_str()
        .unwrap()
        .contains("check its application directory"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Nothing to check is a usage error (exit 2), not a pass.
#[test]
fn empty_directory_is_an_error() {
    let dir = crate::support::temp_root().join(format!("sitlogc-empty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (code, diags, stderr) = check_json(&dir);
    assert_eq!(code, 2, "{stderr}");
    assert!(diags.is_empty());
    assert!(
        stderr.contains("no application or DM file found"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every application of the repository checks clean (no error, no
/// warning), the behaviour library included.
#[test]
fn repository_applications_check_clean() {
    let dms = Path::new(env!("CARGO_MANIFEST_DIR")).join("../dms");
    let (code, diags, stderr) = check_json(&dms);
    assert!(diags.is_empty(), "{diags:#?}");
    assert_eq!(code, 0, "{stderr}");
}

/// A DM of `n` situations in a chain `s0 -> s1 -> ... -> fs`, each with an
/// unused local read, ids atoms or `s(N)` compounds.
fn chain_dm(n: usize, compound: bool) -> String {
    let id = |i: usize| {
        if compound {
            format!("s({i})")
        } else {
            format!("s{i}")
        }
    };
    let mut dm = String::from("diag_mod(big, [\n");
    for i in 0..n {
        let next = if i + 1 == n {
            "fs".to_owned()
        } else {
            id(i + 1)
        };
        dm.push_str(&format!(
            "  [id ==> {}, type ==> neutral, arcs ==> [empty : say(get(k, _)) => {next}]],\n",
            id(i)
        ));
    }
    dm.push_str("  [id ==> fs, type ==> final]\n], [k ==> 0]).\n");
    dm
}

/// 10 000 situations took 111 s in a debug build (every arc compared its
/// next situation with every id); now well under a second or two.
#[test]
fn ten_thousand_situations_check_in_linear_time() {
    for compound in [false, true] {
        let text = chain_dm(10_000, compound);
        let start = std::time::Instant::now();
        let (program, diags) = load::load_sources(&[("big.dm", &text)]);
        let (result, diags) = check::check(program, diags);
        let took = start.elapsed();
        assert!(result.is_ok(), "{:?}", &diags[..diags.len().min(3)]);
        assert!(diags.is_empty(), "{:?}", &diags[..3]);
        // Generous for a loaded debug machine; quadratic took minutes.
        assert!(took.as_secs() < 20, "took {took:?}");
        eprintln!("10 000 situations (compound ids: {compound}): {took:?}");
    }
}

/// `sitlogc run APP --allow-unresolved [--format json]` on `tests/run_errors/NAME`.
fn run_error(name: &str, json: bool) -> (i32, String, String) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/run_errors");
    let mut cmd = sitlogc();
    cmd.current_dir(&dir)
        .args(["run", name, "--allow-unresolved"])
        .env("NO_COLOR", "1");
    if json {
        cmd.args(["--format", "json"]);
    }
    let out = cmd.output().unwrap();
    (
        out.status.code().unwrap(),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

/// A run-time error points at the failing expression (file:line:col and a
/// snippet) and is printed once: on stderr, not in the report on stdout.
#[test]
fn run_time_errors_point_at_the_expression_once() {
    let (code, stdout, stderr) = run_error("arc", false);
    assert_eq!(code, 1);
    assert!(!stdout.contains("pour"), "{stdout}");
    assert!(stdout.starts_with("Execution history:"), "{stdout}");
    assert_eq!(stderr.matches("pour/1").count(), 1, "{stderr}");
    let trimmed: Vec<&str> = stderr.lines().map(str::trim_end).collect();
    insta::assert_snapshot!("run_error_arc", trimmed.join("\n"));
    let (code, stdout, stderr) = run_error("prog", false);
    assert_eq!(code, 1);
    assert!(stderr.contains("prog/main.dm:4:61"), "{stderr}");
    assert!(!stdout.contains("bob"), "{stdout}");
    let trimmed: Vec<&str> = stderr.lines().map(str::trim_end).collect();
    insta::assert_snapshot!("run_error_prog", trimmed.join("\n"));
    // With --format json, stdout holds exactly the JSON object.
    let (code, stdout, stderr) = run_error("arc", true);
    assert_eq!(code, 1);
    let v: serde_json::Value = serde_json::from_str(stdout.trim()).expect("one JSON object");
    assert_eq!(v["status"], "error");
    let error = v["error"].as_str().unwrap();
    assert!(error.contains("pour/1"), "{error}");
    // The message names the failing expression's position, not the situation's.
    assert!(error.contains("(arc/main.dm:4:39)"), "{error}");
    assert!(stderr.contains("arc/main.dm:4:39"), "{stderr}");
}

/// Issue 39: the shapes of the runs recorded on the original that `check`
/// and `run` refused (a variable bound only in `prog`, in another
/// situation, never) are warnings, and the run goes to its end, printing
/// the unbound variables as the original does (`_G..`).
#[test]
fn programs_the_original_runs_are_not_refused() {
    let app = cases().join("original_runs");
    let (code, diags, _) = check_json(&app);
    assert_eq!(code, 0, "{diags:?}");
    assert_eq!(codes(&diags), ["W0228"; 5]);
    let out = sitlogc()
        .args(["run", "--format", "json"])
        .arg(&app)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["status"], "ok", "{report}");
    let history = report["history"].to_string();
    assert!(history.contains("tick(_G"), "{history}");
    assert!(history.contains("round(_G"), "{history}");
}

/// `deny-warnings = true` in the application's `sitlog.toml` makes `check`
/// and `run` refuse its warnings, as `--deny-warnings` does; a misspelt key
/// is an error at its line and column.
#[test]
fn sitlog_toml_denies_warnings() {
    let dir = crate::support::temp_root().join(format!("sitlogc-deny-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : say(Who) => fs]], [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    let status = |args: &[&str]| {
        let out = sitlogc().args(args).arg(&dir).output().unwrap();
        (
            out.status.code().unwrap(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    assert_eq!(status(&["check"]).0, 0);
    assert_eq!(status(&["run"]).0, 0);
    std::fs::write(dir.join("sitlog.toml"), "deny-warnings = true\n").unwrap();
    let (code, stderr) = status(&["check"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains("1 warning(s) (1 denied by sitlog.toml)"),
        "{stderr}"
    );
    let (code, stderr) = status(&["run"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("[W0228] Warning"), "{stderr}");
    assert!(stderr.contains("warnings are denied"), "{stderr}");
    std::fs::write(dir.join("sitlog.toml"), "\ndeny-warning = true\n").unwrap();
    let (code, stderr) = status(&["run"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains("sitlog.toml:2:1: error: unknown field `deny-warning`"),
        "{stderr}"
    );
    // `check` gives it a code and a place like any other (E0007).
    let (code, stderr) = status(&["check"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains("[E0007] Error: unknown field `deny-warning`")
            && stderr.contains("sitlog.toml:2:1"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// W0235: an in_arg that the pipe it is given can never match, certain from
/// constants (`out_arg ==> now`, then `in_arg ==> foo`; and through a
/// situation without `out_arg`, which passes the pipe on), a warning at
/// the in_arg (the run skips it as the original does); none where the
/// pipe is not known: a DM's first situation (the caller's pipe), after a
/// recursive situation without `out_arg`, an in_arg that matches, a DM
/// with a computed next situation.
#[test]
fn an_in_arg_the_pipe_never_matches_is_a_warning_where_certain() {
    let dir = crate::support::temp_root().join(format!("sitlogc-w0235-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("main.dm"),
        "diag_mod(main,\n\
         \x20 [ [id ==> is, type ==> neutral, out_arg ==> now, arcs ==> [empty : empty => s1]],\n\
         \x20   [id ==> s1, type ==> neutral, in_arg ==> foo, arcs ==> [empty : empty => s2]],\n\
         \x20   [id ==> s2, type ==> neutral, in_arg ==> f(_), arcs ==> [empty : empty => s3]],\n\
         \x20   [id ==> s3, type ==> recursive, in_arg ==> now, embedded_dm ==> sub, arcs ==> [fs : empty => s4]],\n\
         \x20   [id ==> s4, type ==> neutral, in_arg ==> bar, arcs ==> [empty : empty => fs]],\n\
         \x20   [id ==> fs, type ==> final] ], []).\n\
         diag_mod(sub,\n\
         \x20 [ [id ==> is, type ==> neutral, in_arg ==> nothing, out_arg ==> now, arcs ==> [empty : empty => t]],\n\
         \x20   [id ==> t, type ==> neutral, in_arg ==> later, arcs ==> [empty : empty => get(next, _)]],\n\
         \x20   [id ==> fs, type ==> final] ], [next ==> fs]).\n",
    )
    .unwrap();
    let (code, diags, stderr) = check_json(&dir);
    assert_eq!(code, 0, "{stderr}");
    let found: Vec<(u64, u64, &str)> = diags
        .iter()
        .filter(|d| d["code"] == "W0235")
        .map(|d| {
            (
                d["line"].as_u64().unwrap(),
                d["column"].as_u64().unwrap(),
                d["message"].as_str().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        found,
        [
            (
                3,
                46,
                "in_arg `foo` never matches the pipe it is given (`now`)"
            ),
            (
                4,
                46,
                "in_arg `f(_)` never matches the pipe it is given (`now`)"
            ),
        ],
        "{diags:?}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
