//! What the command-line tests share: the `sitlogc` under test, the
//! workspace's paths, asserting a run succeeded (`assert_ok`), running a
//! child process with a signal, the home butler's plain run (made once
//! for the binary), and the directory the tests write their files in
//! ([`temp_root`], removed when the binary exits).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// The `sitlogc` executable Cargo built for these tests.
pub const SITLOGC: &str = env!("CARGO_BIN_EXE_sitlogc");

/// A command running [`SITLOGC`].
pub fn sitlogc() -> Command {
    Command::new(SITLOGC)
}

/// The workspace root (the applications are under `dms/`).
pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// The stdout of `sitlogc run dms/apps/home` (no options, `SITLOG_LIBRARY`
/// unset), which must succeed: run once for the whole test binary, for the
/// tests that compare another run of the home butler with it (each run is
/// a Prolog engine start and the whole scenario: seconds of CPU in a debug
/// build).
pub fn home_run() -> &'static str {
    static RUN: OnceLock<String> = OnceLock::new();
    RUN.get_or_init(|| {
        let out = sitlogc()
            .arg("run")
            .arg(workspace().join("dms/apps/home"))
            .env_remove("SITLOG_LIBRARY")
            .output()
            .unwrap();
        assert_ok(&out);
        String::from_utf8(out.stdout).unwrap()
    })
}

/// Asserts that a finished `sitlogc` (or compiled task) exited with status
/// 0; else the test fails showing its stderr.
#[track_caller]
pub fn assert_ok(out: &std::process::Output) {
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Sends `signal` (`INT`, `TERM`, `KILL`, ...) to `pid` with unix `kill`.
#[cfg(unix)]
pub fn kill(pid: u32, signal: &str) {
    let ok = Command::new("kill")
        .arg(format!("-{signal}"))
        .arg(pid.to_string())
        .status()
        .expect("kill runs");
    assert!(ok.success(), "kill -{signal} {pid}");
}

/// This test binary's own directory under the system's temporary directory
/// (`sitlogc-tests-PID`), made at the first call; every test writes its
/// files under it, and it is removed, with all they wrote, when the binary
/// exits (the test harness leaves through `exit`, passing or failing, so
/// the `atexit` handler runs), so a run leaves nothing in `/tmp`.
pub fn temp_root() -> PathBuf {
    static ROOT: OnceLock<PathBuf> = OnceLock::new();
    extern "C" fn remove_root() {
        if let Some(root) = ROOT.get() {
            let _ = std::fs::remove_dir_all(root);
        }
    }
    ROOT.get_or_init(|| {
        let root = std::env::temp_dir().join(format!("sitlogc-tests-{}", std::process::id()));
        std::fs::create_dir_all(&root).unwrap();
        // SAFETY: `atexit` registers a plain function with no captured
        // state; it runs once, after `main` returns or `exit` is called.
        unsafe {
            libc::atexit(remove_root);
        }
        root
    })
    .clone()
}
