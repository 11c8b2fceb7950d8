//! `sitlogc check` on bad input: clear errors, the right exit status, never a panic.

use crate::support::sitlogc;
use std::path::PathBuf;

fn temp_file(name: &str, bytes: &[u8]) -> PathBuf {
    let dir =
        crate::support::temp_root().join(format!("sitlogc-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Runs `sitlogc check --format json FILE`; returns exit code and the JSON diagnostics.
fn check(name: &str, bytes: &[u8]) -> (i32, Vec<serde_json::Value>) {
    let path = temp_file(name, bytes);
    let out = sitlogc()
        .args(["check", "--format", "json"])
        .arg(&path)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    let diags = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    (out.status.code().unwrap(), diags)
}

fn first_error(diags: &[serde_json::Value]) -> &serde_json::Value {
    diags
        .iter()
        .find(|d| d["severity"] == "error")
        .expect("an error")
}

const GOOD: &str = "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : [] => fs]], [id ==> fs, type ==> final]], []).\n";

#[test]
fn clean_file_exits_zero() {
    let (code, diags) = check("good.dm", GOOD.as_bytes());
    assert_eq!(code, 0, "{diags:?}");
    assert!(diags.is_empty());
}

#[test]
fn empty_file_is_a_program_without_dms() {
    let (code, diags) = check("empty.dm", b"");
    assert_eq!(code, 0, "{diags:?}");
}

#[test]
fn non_utf8_is_reported_with_its_offset() {
    let (code, diags) = check("bytes.dm", b"diag_mod(m, [], []).\n% caf\xe9\n");
    assert_eq!(code, 1);
    let e = first_error(&diags);
    assert_eq!(e["code"], "E0002");
    assert_eq!(e["line"], 2);
    assert!(e["message"].as_str().unwrap().contains("offset 26"));
}

#[test]
fn unterminated_quote_comment_and_missing_end() {
    for (src, line, what) in [
        (
            "diag_mod(m, [[id ==> 'abc]], []).\n",
            1,
            "unterminated quoted atom",
        ),
        ("a.\n/* never closed\n", 2, "unterminated block comment"),
        (GOOD.trim_end().trim_end_matches('.'), 1, "missing `.`"),
        ("x(a : b : c).\n", 1, "priority clash"),
    ] {
        let (code, diags) = check("bad.dm", src.as_bytes());
        assert_eq!(code, 1, "{src}");
        let e = first_error(&diags);
        assert_eq!(e["code"], "E0001");
        assert_eq!(e["line"], line, "{src}: {e}");
        assert!(e["message"].as_str().unwrap().contains(what), "{src}: {e}");
    }
}

#[test]
fn deep_nesting_is_parsed() {
    let n = 100_000;
    let src = format!("x({}a{}).\n", "f(".repeat(n), ")".repeat(n));
    let (code, diags) = check("deep.dm", src.as_bytes());
    // Not a DM: a warning only.
    assert_eq!(code, 0, "{diags:?}");
}

#[test]
fn usage_and_io_errors_exit_two() {
    let out = sitlogc()
        .args(["check", "/nonexistent/path/x.dm"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let out = sitlogc().args(["check"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let out = sitlogc().args(["frobnicate"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
}

/// Slow in a debug build (about two minutes): run it with
/// `cargo test --release -p sitlog-cli --test cli -- --ignored check::`.
#[test]
#[ignore]
fn fifty_megabytes_of_dms() {
    big_file(50 << 20);
}

#[test]
fn two_megabytes_of_dms() {
    big_file(2 << 20);
}

fn big_file(size: usize) {
    let one = GOOD.replace("main", "m0");
    let mut src = String::with_capacity(size + 1024);
    let mut i = 0;
    while src.len() < size {
        src.push_str(&one.replace("m0", &format!("m{i}")));
        i += 1;
    }
    let (code, diags) = check("big.dm", src.as_bytes());
    assert_eq!(code, 0, "{:?}", diags.first());
}

/// `sitlogc check` reports every DM's errors, a DM that the main DM does
/// not reach by name included (as `cargo check` reports an error in a
/// function nothing calls); `sitlogc run` leaves such a DM out (W0232,
/// legacy::a_broken_dm_refuses_only_the_runs_that_reach_it).
#[test]
fn errors_of_a_dm_that_main_does_not_reach_are_errors() {
    let dir =
        crate::support::temp_root().join(format!("sitlogc-cli-{}-unreached", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("main.dm"), GOOD).unwrap();
    std::fs::write(
        dir.join("other.dm"),
        "diag_mod(other, [[id ==> is, type ==> neutrall, arcs ==> [empty : [] => fs]], [id ==> fs, type ==> final]], []).\n",
    )
    .unwrap();
    let out = sitlogc()
        .args(["check", "--format", "json"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("\"E0230\"") && !stdout.contains("W0232"),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
