//! What the command-line tests share: the `sitlogc` under test, the
//! workspace's paths, and running a child process with a signal.

use std::path::{Path, PathBuf};
use std::process::Command;

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
