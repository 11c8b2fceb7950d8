//! `include_dm!` through the compiler: a good DM compiles and runs, bad
//! ones give `compile_error!`s naming the `.dm` file, line and column.
//!
//! The good DM is compiled with this test binary (no nested build). Each bad
//! case is one `rustc` run on its `tests/ui/*.rs` against the proc macro the
//! workspace build already made (beside this binary in `target/*/deps`),
//! with `--emit=metadata`: the macro fails before any code is generated, so a
//! case takes well under a second. rustc's whole message (the DM's
//! file:line:col and source line, and the span of the literal in the `.rs`)
//! is compared with `tests/ui/*.stderr`, the crate's directory written
//! `$DIR`, as trybuild did (it built a crate of its own with the compiler and
//! the runtime: 50 s of CPU in the test command, issue 40).

use std::path::{Path, PathBuf};
use std::process::Command;

mod app {
    sitlog_macros::include_dm!("tests/ui/good_dm");
}

#[test]
fn good_dm_compiles_and_runs() {
    use sitlog_runtime::machine::Options;
    use sitlog_runtime::testmode::{ScriptPerception, TextActions};
    let mut perception = ScriptPerception::new("script", String::new());
    let mut actions = TextActions::new(std::io::sink(), Vec::new());
    let (outcome, _store) = app::run(
        "main",
        None,
        Options::default(),
        sitlog_runtime::Functions::standard(),
        &mut perception,
        &mut actions,
        None,
    )
    .unwrap();
    assert!(outcome.result.is_ok());
    assert_eq!(outcome.history.len(), 2);
}

/// The proc macro's library that this binary's build made: the newest
/// `libsitlog_macros-*.so` (`.dylib`, `sitlog_macros-*.dll`) beside it.
fn proc_macro_lib() -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let deps = exe.parent().expect("the deps directory");
    let (prefix, suffix) = (std::env::consts::DLL_PREFIX, std::env::consts::DLL_SUFFIX);
    let name = format!("{prefix}sitlog_macros-");
    std::fs::read_dir(deps)
        .expect("read the deps directory")
        .filter_map(Result::ok)
        .filter(|e| {
            let n = e.file_name().to_string_lossy().into_owned();
            n.starts_with(&name) && n.ends_with(suffix)
        })
        .max_by_key(|e| e.metadata().and_then(|m| m.modified()).ok())
        .map(|e| e.path())
        .unwrap_or_else(|| panic!("no {name}*{suffix} in {}", deps.display()))
}

/// rustc's messages for `case` (a path under this crate), as trybuild
/// normalises them: the crate's directory as `$DIR`, without the closing
/// `aborting due to ...` summary.
fn compile_fail(case: &str, out: &Path) -> String {
    let dir = env!("CARGO_MANIFEST_DIR");
    let rustc = std::env::var_os("RUSTC").unwrap_or_else(|| "rustc".into());
    let lib = proc_macro_lib();
    let output = Command::new(rustc)
        .current_dir(dir)
        .env("SITLOG_DM_ROOT", dir)
        .args([
            "--edition",
            "2021",
            "--crate-type",
            "bin",
            "--emit=metadata",
        ])
        .args(["--color", "never", "--crate-name", "ui_case"])
        .arg("--extern")
        .arg(format!("sitlog_macros={}", lib.display()))
        .arg("--out-dir")
        .arg(out)
        .arg(case)
        .output()
        .expect("run rustc");
    assert!(!output.status.success(), "{case} compiled");
    let stderr = String::from_utf8_lossy(&output.stderr).replace(dir, "$DIR");
    let mut lines: Vec<&str> = stderr
        .lines()
        .take_while(|l| !l.starts_with("error: aborting due to"))
        .collect();
    while lines.last().is_some_and(|l| l.trim().is_empty()) {
        lines.pop();
    }
    lines.join("\n") + "\n"
}

#[test]
fn bad_dms_give_located_compile_errors() {
    let out = std::env::temp_dir().join(format!("sitlog-macros-ui-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    let mut failures = Vec::new();
    for case in ["bad_dm", "syntax_dm", "not_a_string"] {
        let got = compile_fail(&format!("tests/ui/{case}.rs"), &out);
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/ui/{case}.stderr"));
        let want = std::fs::read_to_string(&path).unwrap();
        if got != want {
            failures.push(format!("{case}: expected\n{want}\ngot\n{got}"));
        }
    }
    let _ = std::fs::remove_dir_all(&out);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The libraries beside this binary whose names start with `prefix` and
/// end with `suffix`, the newest first.
fn dep_libs(prefix: &str, suffix: &str) -> Vec<PathBuf> {
    let exe = std::env::current_exe().expect("the test binary's path");
    let deps = exe.parent().expect("the deps directory");
    let mut libs: Vec<(std::time::SystemTime, PathBuf)> = std::fs::read_dir(deps)
        .expect("read the deps directory")
        .filter_map(Result::ok)
        .filter(|e| {
            let n = e.file_name().to_string_lossy().into_owned();
            n.starts_with(prefix) && n.ends_with(suffix)
        })
        .filter_map(|e| Some((e.metadata().and_then(|m| m.modified()).ok()?, e.path())))
        .collect();
    libs.sort_by_key(|l| std::cmp::Reverse(l.0));
    assert!(
        !libs.is_empty(),
        "no {prefix}*{suffix} in {}",
        deps.display()
    );
    libs.into_iter().map(|(_, p)| p).collect()
}

/// Helper `review18` (issue 37): DMs that check and run on the interpreter
/// must give Rust that compiles (`tests/typed/review18/r18_d_lockstep*`:
/// two lists walked in step). One `rustc --emit=metadata` run (type and
/// borrow checks, no code generated) against the macro and a runtime this
/// workspace's builds made (each `libsitlog_runtime-*.rlib` beside this
/// binary, the newest first, until one compiles: the deps directory holds
/// the runtime of several feature sets).
#[test]
fn review18_lockstep_compiles() {
    let dir = env!("CARGO_MANIFEST_DIR");
    let out = std::env::temp_dir().join(format!("sitlog-macros-ui-r18-{}", std::process::id()));
    std::fs::create_dir_all(&out).unwrap();
    let rustc = std::env::var_os("RUSTC").unwrap_or_else(|| "rustc".into());
    let mut first_error = None;
    for runtime in dep_libs("libsitlog_runtime-", ".rlib") {
        let deps = runtime.parent().unwrap().to_owned();
        let output = Command::new(&rustc)
            .current_dir(dir)
            .env("SITLOG_DM_ROOT", dir)
            .args([
                "--edition",
                "2021",
                "--crate-type",
                "bin",
                "--emit=metadata",
            ])
            .args(["--color", "never", "--crate-name", "ui_review18"])
            .arg("--extern")
            .arg(format!("sitlog_macros={}", proc_macro_lib().display()))
            .arg("--extern")
            .arg(format!("sitlog_runtime={}", runtime.display()))
            .arg("-L")
            .arg(format!("dependency={}", deps.display()))
            .arg("--out-dir")
            .arg(&out)
            .arg("tests/ui/review18_lockstep.rs")
            .output()
            .expect("run rustc");
        if output.status.success() {
            let _ = std::fs::remove_dir_all(&out);
            return;
        }
        first_error.get_or_insert_with(|| String::from_utf8_lossy(&output.stderr).into_owned());
    }
    let _ = std::fs::remove_dir_all(&out);
    panic!(
        "the generated Rust does not compile:\n{}",
        first_error.unwrap_or_default()
    );
}
