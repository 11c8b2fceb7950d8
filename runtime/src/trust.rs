//! The trust model of application code (issue 31): what a task's Prolog
//! user functions and directives may reach of the operating system
//! ([`Trust`], set by a run's `--allow-os`) and the one table of the
//! predicates that reach it ([`OS_PREDICATES`]), read both by the engine
//! (which refuses them without the flag) and by `sitlogc check` (which
//! warns where they are called). Invariant: the flag is named
//! [`ALLOW_OS`] everywhere (`sitlogc run`, `sitlogc debug`, compiled tasks,
//! messages).

use std::path::{Path, PathBuf};

/// The option that lets application code reach the operating system.
pub const ALLOW_OS: &str = "--allow-os";

/// What a predicate of [`OS_PREDICATES`] reaches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OsAccess {
    /// Runs a shell command.
    Shell,
    /// Creates, waits for or signals a process.
    Process,
    /// Opens a network connection or listens on a port.
    Network,
    /// Loads native code.
    Foreign,
    /// Opens a file: refused for writing outside the application.
    Open,
    /// Loads Prolog code from a file: refused outside the application.
    Consult,
}

impl OsAccess {
    /// Words for messages (`a shell command`, ...).
    pub fn describe(self) -> &'static str {
        match self {
            OsAccess::Shell => "runs a shell command",
            OsAccess::Process => "creates or controls a process",
            OsAccess::Network => "opens a network socket",
            OsAccess::Foreign => "loads native code",
            OsAccess::Open => "opens a file (writing is refused outside the application)",
            OsAccess::Consult => "loads code from a file (refused outside the application)",
        }
    }

    /// Whether every call is refused without [`ALLOW_OS`] (shell,
    /// processes, sockets, native code), not only some (files).
    pub fn always_refused(self) -> bool {
        !matches!(self, OsAccess::Open | OsAccess::Consult)
    }
}

/// The predicates through which Prolog code reaches the operating system
/// (scryer-prolog 0.10's `library(os)`, `library(process)`,
/// `library(sockets)`, `library(http/...)`, `library(tls)`, `library(ffi)`,
/// and the engine's primitives behind them), with what they reach.
pub const OS_PREDICATES: &[(&str, usize, OsAccess)] = &[
    ("shell", 1, OsAccess::Shell),
    ("shell", 2, OsAccess::Shell),
    ("$shell", 2, OsAccess::Shell),
    ("process_create", 3, OsAccess::Process),
    ("process_wait", 2, OsAccess::Process),
    ("process_wait", 3, OsAccess::Process),
    ("process_kill", 1, OsAccess::Process),
    ("process_kill", 2, OsAccess::Process),
    ("$process_create", 8, OsAccess::Process),
    ("$process_kill", 1, OsAccess::Process),
    ("socket_client_open", 3, OsAccess::Network),
    ("socket_server_open", 2, OsAccess::Network),
    ("socket_server_accept", 4, OsAccess::Network),
    ("$socket_client_open", 7, OsAccess::Network),
    ("$socket_server_open", 3, OsAccess::Network),
    ("$socket_server_accept", 7, OsAccess::Network),
    ("http_open", 3, OsAccess::Network),
    ("$http_open", 7, OsAccess::Network),
    ("http_listen", 2, OsAccess::Network),
    ("http_listen", 3, OsAccess::Network),
    ("$http_listen", 5, OsAccess::Network),
    ("$tls_client_connect", 3, OsAccess::Network),
    ("$tls_accept_client", 4, OsAccess::Network),
    ("use_foreign_module", 2, OsAccess::Foreign),
    ("$load_foreign_lib", 2, OsAccess::Foreign),
    ("$foreign_call", 3, OsAccess::Foreign),
    ("open", 3, OsAccess::Open),
    ("open", 4, OsAccess::Open),
    ("consult", 1, OsAccess::Consult),
    ("ensure_loaded", 1, OsAccess::Consult),
    ("load_files", 2, OsAccess::Consult),
];

/// What `name/arity` reaches of the operating system, if anything.
pub fn os_access(name: &str, arity: usize) -> Option<OsAccess> {
    OS_PREDICATES
        .iter()
        .find(|&&(n, a, _)| a == arity && n == name)
        .map(|&(_, _, k)| k)
}

/// What application code may do in one run.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Trust {
    /// [`ALLOW_OS`]: shell, processes, sockets, native code, writes and
    /// consults anywhere.
    pub allow_os: bool,
    /// Directories code may write into and consult from without the flag,
    /// besides those of the application's own Prolog files.
    pub roots: Vec<PathBuf>,
    /// The operating system's sandbox for a thread that runs application
    /// code (set by the runner when the run is confined): the Prolog
    /// engine's thread calls it on itself before the first directive.
    pub confine: Option<Confine>,
}

/// Confines the calling thread to what a task may do (the OS sandbox of
/// `sitlog-robot`, which owns it): given the directories the thread's code
/// may also write into (the application's), an error says why it could
/// not. Landlock binds a thread and those it starts afterwards, so each
/// thread that runs application code and was started before the sandbox
/// calls it on itself.
#[derive(Clone)]
pub struct Confine(pub std::sync::Arc<ConfineFn>);

/// What a [`Confine`] runs.
pub type ConfineFn = dyn Fn(&[PathBuf]) -> Result<(), String> + Send + Sync;

impl Confine {
    /// Confines the calling thread, `writable` its code's own directories.
    pub fn apply(&self, writable: &[PathBuf]) -> Result<(), String> {
        (self.0)(writable)
    }
}

impl std::fmt::Debug for Confine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Confine(..)")
    }
}

impl PartialEq for Confine {
    fn eq(&self, other: &Confine) -> bool {
        std::sync::Arc::ptr_eq(&self.0, &other.0)
    }
}

impl Eq for Confine {}

impl Trust {
    /// Whether `path` (relative to the current directory) lies inside one
    /// of `roots`, once both are resolved (a file about to be created:
    /// through its directory). A path that cannot be resolved is outside.
    pub fn inside(path: &Path, roots: &[PathBuf]) -> bool {
        let resolved = resolve(path);
        let Some(resolved) = resolved else {
            return false;
        };
        roots
            .iter()
            .filter_map(|r| std::fs::canonicalize(r).ok())
            .any(|r| resolved.starts_with(&r))
    }
}

/// Gives the process `SHELL=/bin/sh` when it has no `SHELL`, once.
/// The engine's `shell/1,2` run `$SHELL -c` and simply fail without it,
/// and a robot's task started by systemd, cron or a container runtime
/// usually has none: with [`ALLOW_OS`] a shell command then runs as it
/// does from a terminal. The variable is set through `std::env`, whose
/// readers (the engine's included) hold the same lock.
pub fn default_shell() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    #[cfg(unix)]
    ONCE.call_once(|| {
        if std::env::var_os("SHELL").is_none_or(|s| s.is_empty()) {
            std::env::set_var("SHELL", "/bin/sh");
        }
    });
    #[cfg(not(unix))]
    ONCE.call_once(|| {});
}

/// `path` with its links and `..` resolved: the file itself when it
/// exists, else its directory's real path joined with its name.
fn resolve(path: &Path) -> Option<PathBuf> {
    if let Ok(p) = std::fs::canonicalize(path) {
        return Some(p);
    }
    let name = path.file_name()?;
    if name == ".." || name == "." {
        return None;
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    Some(std::fs::canonicalize(dir).ok()?.join(name))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_inside_roots() {
        let dir = std::env::temp_dir().join(format!("sitlog-trust-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("app")).unwrap();
        let roots = vec![dir.join("app")];
        assert!(Trust::inside(&dir.join("app/new.txt"), &roots));
        assert!(!Trust::inside(&dir.join("app/../x.txt"), &roots));
        assert!(!Trust::inside(&dir.join("elsewhere/x.txt"), &roots));
        assert!(!Trust::inside(Path::new("/tmp/x"), &roots));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn the_table_names_shell_and_sockets() {
        assert_eq!(os_access("shell", 1), Some(OsAccess::Shell));
        assert_eq!(os_access("socket_client_open", 3), Some(OsAccess::Network));
        assert_eq!(os_access("shell", 3), None);
    }
}
