//! The operating system's sandbox of a task (issue 38): once a run has
//! opened everything it names (the application's files, the KB, the
//! trace, the script, the world, the robot's DDS sockets, the live view's
//! listening socket), [`enter`] confines the process so that application
//! code that slips past the Prolog-level refusals
//! (`sitlog_runtime::trust`) still cannot reach the system.
//!
//! On Linux:
//! - **seccomp** (`seccompiler`), on every thread of the process at once
//!   (`SECCOMP_FILTER_FLAG_TSYNC`): no program runs (`execve`,
//!   `execveat`), no process is created (`fork`, `vfork`, `clone` without
//!   `CLONE_THREAD`; `clone3`, whose flags a filter cannot read, answers
//!   "not implemented" so that the C library starts threads with `clone`),
//!   and nothing a task never needs (`ptrace`, mounts, modules, `bpf`,
//!   `io_uring`, namespaces, keys, ...) fails with `EPERM`. Without a robot
//!   over ROS 2, no new internet or packet socket either (`socket` of
//!   `AF_INET`, `AF_INET6`, `AF_PACKET`).
//! - **Landlock** (`landlock`, ABI 7 asked, best effort below), on the
//!   thread that runs the task and on each thread that runs application
//!   code ([`Confine`], which the Prolog engine's thread applies to itself
//!   before the first directive): files may be written, created, renamed,
//!   truncated or deleted only beneath the directories of the run's
//!   outputs that are written by replacing the file (a persisted KB's
//!   directory) and, on the engine's thread, the application's own
//!   directories (where the Prolog level lets code write); files opened
//!   before the sandbox (the trace, the KB's lock) stay writable as
//!   opened. No program is executed from any file, no TCP port is bound or
//!   connected to (UDP, which DDS speaks, is not Landlock's to restrict;
//!   the live view's server accepts on the socket it bound before), and no
//!   signal reaches a process outside the sandbox.
//!
//! Reads stay allowed everywhere: the Prolog level allows reading any file
//! (an application reads its data where it lies), the engine, the C
//! library and the DDS stack read system files whose list is not ours to
//! keep, and what is read can leave only through the task's own outputs,
//! since writing elsewhere, connecting, spawning and (without ROS 2)
//! sending datagrams are closed.
//!
//! Invariants: `--allow-os` and `--sandbox off` confine nothing; where the
//! kernel lacks a part, the run says so once on stderr and goes on (the
//! Prolog-level refusals still hold), and `--sandbox require` makes it an
//! error (exit 2) before any application code runs.

use crate::cli::{RobotKind, RunArgs, SandboxMode};
use sitlog_runtime::trust::Confine;
use std::path::{Path, PathBuf};

/// What the sandbox enforces on this machine, for messages and tests.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Enforced {
    /// Landlock confines file writes and TCP (fully: at the ABI asked).
    pub landlock: Option<bool>,
    /// The seccomp filter is installed.
    pub seccomp: bool,
    /// Why a part is missing, in words.
    pub missing: Vec<String>,
}

/// Confines the process for the run of `args` (see the module
/// documentation): `persist` is the KB file written by replacing it
/// (`--kb-persist`), whose directory stays writable. Returns the hook for
/// threads that run application code ([`Confine`], `None` when nothing is
/// confined), or the exit status and message with `--sandbox require` on a
/// kernel that cannot confine. Where it cannot under `auto`, one line says
/// so on `stderr`.
pub fn enter(
    args: &RunArgs,
    persist: Option<&Path>,
    stderr: &mut dyn std::io::Write,
) -> Result<Option<Confine>, (u8, String)> {
    if args.allow_os || args.sandbox == SandboxMode::Off {
        return Ok(None);
    }
    let mut writable: Vec<PathBuf> = Vec::new();
    if let Some(dir) = persist.and_then(Path::parent) {
        writable.push(if dir.as_os_str().is_empty() {
            PathBuf::from(".")
        } else {
            dir.to_path_buf()
        });
    }
    let sockets = args.robot == RobotKind::Ros2;
    let enforced = os::confine_process(sockets, &writable);
    if !enforced.missing.is_empty() {
        let what = enforced.missing.join("; ");
        if args.sandbox == SandboxMode::Require {
            return Err((
                2,
                format!("error: --sandbox require: this system cannot confine the task: {what}"),
            ));
        }
        say_once(stderr, &what);
    }
    if enforced.landlock.is_none() {
        return Ok(None);
    }
    let confine = move |own: &[PathBuf]| {
        let mut dirs = writable.clone();
        dirs.extend(own.iter().cloned());
        match os::landlock_thread(&dirs) {
            Ok(_) => Ok(()),
            Err(e) => Err(format!(
                "the sandbox could not confine the Prolog engine: {e}"
            )),
        }
    };
    Ok(Some(Confine(std::sync::Arc::new(confine))))
}

/// The note of a sandbox that is incomplete, once per process.
fn say_once(stderr: &mut dyn std::io::Write, what: &str) {
    static SAID: std::sync::Once = std::sync::Once::new();
    SAID.call_once(|| {
        let _ = writeln!(
            stderr,
            "note: the task runs without the operating system's sandbox ({what}); the Prolog-level refusals still hold (--sandbox require makes this an error)"
        );
    });
}

/// What this kernel can enforce, without enforcing anything: Landlock's ABI
/// (0 without it) and whether seccomp filters can be installed. For tests
/// that need the kernel's features, and for messages.
pub fn support() -> (i32, bool) {
    os::support()
}

#[cfg(target_os = "linux")]
mod os {
    use super::Enforced;
    use landlock::{
        Access, AccessFs, AccessNet, CompatLevel, Compatible, PathBeneath, PathFd, Ruleset,
        RulesetAttr, RulesetCreatedAttr, RulesetStatus, Scope, ABI,
    };
    use seccompiler::{
        SeccompAction, SeccompCmpArgLen, SeccompCmpOp, SeccompCondition, SeccompFilter, SeccompRule,
    };
    use std::collections::BTreeMap;
    use std::path::PathBuf;

    /// The Landlock ABI asked for (the kernel's features up to it are used).
    const ABI_ASKED: ABI = ABI::V7;

    /// seccomp on every thread, Landlock on this one.
    pub(super) fn confine_process(sockets: bool, writable: &[PathBuf]) -> Enforced {
        let mut enforced = Enforced::default();
        match seccomp(sockets) {
            Ok(()) => enforced.seccomp = true,
            Err(e) => enforced.missing.push(format!("seccomp: {e}")),
        }
        match landlock_thread(writable) {
            Ok(Some(full)) => {
                enforced.landlock = Some(full);
                if !full {
                    enforced.missing.push(format!(
                        "Landlock: only partly (the kernel's ABI {} is below {}: TCP or truncation may stay open)",
                        abi(),
                        ABI_ASKED as i32
                    ));
                }
            }
            Ok(None) => enforced
                .missing
                .push("Landlock: not supported or not enabled by this kernel".to_owned()),
            Err(e) => enforced.missing.push(format!("Landlock: {e}")),
        }
        enforced
    }

    /// The kernel's Landlock ABI (0: none).
    fn abi() -> i32 {
        // SAFETY: landlock_create_ruleset with a null attribute, size 0 and
        // LANDLOCK_CREATE_RULESET_VERSION only returns the ABI version.
        let v = unsafe {
            libc::syscall(
                libc::SYS_landlock_create_ruleset,
                std::ptr::null::<libc::c_void>(),
                0usize,
                1u32,
            )
        };
        i32::try_from(v).unwrap_or(0).max(0)
    }

    pub(super) fn support() -> (i32, bool) {
        // SAFETY: prctl(PR_GET_SECCOMP) reads the calling thread's mode.
        let seccomp = unsafe { libc::prctl(libc::PR_GET_SECCOMP, 0, 0, 0, 0) } >= 0;
        (abi(), seccomp)
    }

    /// Confines the calling thread (and those it starts): writes only
    /// beneath `writable` (and to `/dev/null`), no execution, no TCP, no
    /// signal out. `Some(true)` fully enforced, `Some(false)` partly,
    /// `None` not at all (no Landlock).
    pub(super) fn landlock_thread(writable: &[PathBuf]) -> Result<Option<bool>, String> {
        let write = AccessFs::from_write(ABI_ASKED);
        let handled = write | AccessFs::Execute;
        let mut ruleset = Ruleset::default()
            .set_compatibility(CompatLevel::BestEffort)
            .handle_access(handled)
            .map_err(|e| e.to_string())?
            .handle_access(AccessNet::from_all(ABI_ASKED))
            .map_err(|e| e.to_string())?
            .scope(Scope::from_all(ABI_ASKED))
            .map_err(|e| e.to_string())?
            .create()
            .map_err(|e| e.to_string())?;
        for dir in writable {
            // A directory that does not exist holds nothing to write.
            if let Ok(fd) = PathFd::new(dir) {
                ruleset = ruleset
                    .add_rule(PathBeneath::new(fd, write))
                    .map_err(|e| e.to_string())?;
            }
        }
        if let Ok(fd) = PathFd::new("/dev/null") {
            ruleset = ruleset
                .add_rule(PathBeneath::new(
                    fd,
                    AccessFs::WriteFile | AccessFs::Truncate,
                ))
                .map_err(|e| e.to_string())?;
        }
        let status = ruleset.restrict_self().map_err(|e| e.to_string())?;
        Ok(match status.ruleset {
            RulesetStatus::FullyEnforced => Some(true),
            RulesetStatus::PartiallyEnforced => Some(false),
            RulesetStatus::NotEnforced => None,
        })
    }

    /// The syscalls refused (EPERM) whatever their arguments.
    fn refused() -> Vec<i64> {
        let mut v = vec![
            libc::SYS_execve,
            libc::SYS_execveat,
            libc::SYS_ptrace,
            libc::SYS_process_vm_readv,
            libc::SYS_process_vm_writev,
            libc::SYS_mount,
            libc::SYS_umount2,
            libc::SYS_pivot_root,
            libc::SYS_chroot,
            libc::SYS_swapon,
            libc::SYS_swapoff,
            libc::SYS_reboot,
            libc::SYS_kexec_load,
            libc::SYS_kexec_file_load,
            libc::SYS_init_module,
            libc::SYS_finit_module,
            libc::SYS_delete_module,
            libc::SYS_bpf,
            libc::SYS_perf_event_open,
            libc::SYS_unshare,
            libc::SYS_setns,
            libc::SYS_keyctl,
            libc::SYS_add_key,
            libc::SYS_request_key,
            libc::SYS_userfaultfd,
            libc::SYS_acct,
            libc::SYS_settimeofday,
            libc::SYS_clock_settime,
            libc::SYS_adjtimex,
            libc::SYS_sethostname,
            libc::SYS_setdomainname,
            libc::SYS_open_by_handle_at,
            libc::SYS_name_to_handle_at,
            libc::SYS_fanotify_init,
            libc::SYS_io_uring_setup,
            libc::SYS_io_uring_enter,
            libc::SYS_io_uring_register,
            libc::SYS_move_mount,
            libc::SYS_open_tree,
            libc::SYS_fsopen,
            libc::SYS_fsconfig,
            libc::SYS_fsmount,
            libc::SYS_fspick,
            libc::SYS_mount_setattr,
            libc::SYS_pidfd_getfd,
            libc::SYS_quotactl,
        ];
        #[cfg(target_arch = "x86_64")]
        v.extend([
            libc::SYS_fork,
            libc::SYS_vfork,
            libc::SYS_iopl,
            libc::SYS_ioperm,
        ]);
        v
    }

    /// Installs the filters on every thread of the process.
    fn seccomp(sockets: bool) -> Result<(), String> {
        let arch = std::env::consts::ARCH
            .try_into()
            .map_err(|e: seccompiler::BackendError| e.to_string())?;
        let cond = |arg: u8, op: SeccompCmpOp, value: u64| {
            SeccompCondition::new(arg, SeccompCmpArgLen::Qword, op, value)
                .map_err(|e| e.to_string())
        };
        let rule = |c: Vec<SeccompCondition>| SeccompRule::new(c).map_err(|e| e.to_string());
        let mut rules: BTreeMap<i64, Vec<SeccompRule>> =
            refused().into_iter().map(|n| (n, Vec::new())).collect();
        // clone without CLONE_THREAD: a process.
        let thread = libc::CLONE_THREAD as u64;
        rules.insert(
            libc::SYS_clone,
            vec![rule(vec![cond(0, SeccompCmpOp::MaskedEq(thread), 0)?])?],
        );
        if !sockets {
            let mut by_family = Vec::new();
            for family in [libc::AF_INET, libc::AF_INET6, libc::AF_PACKET] {
                by_family.push(rule(vec![cond(
                    0,
                    SeccompCmpOp::Eq,
                    u64::try_from(family).unwrap_or(u64::MAX),
                )?])?);
            }
            rules.insert(libc::SYS_socket, by_family);
        }
        let refuse = SeccompFilter::new(
            rules,
            SeccompAction::Allow,
            SeccompAction::Errno(libc::EPERM as u32),
            arch,
        )
        .map_err(|e| e.to_string())?;
        // clone3: "not implemented", so that threads start with clone.
        let clone3 = SeccompFilter::new(
            [(libc::SYS_clone3, Vec::new())].into_iter().collect(),
            SeccompAction::Allow,
            SeccompAction::Errno(libc::ENOSYS as u32),
            arch,
        )
        .map_err(|e| e.to_string())?;
        for filter in [refuse, clone3] {
            let program: seccompiler::BpfProgram = filter
                .try_into()
                .map_err(|e: seccompiler::BackendError| e.to_string())?;
            seccompiler::apply_filter_all_threads(&program).map_err(|e| e.to_string())?;
        }
        Ok(())
    }
}

#[cfg(not(target_os = "linux"))]
mod os {
    use super::Enforced;
    use std::path::PathBuf;

    pub(super) fn confine_process(_sockets: bool, _writable: &[PathBuf]) -> Enforced {
        Enforced {
            landlock: None,
            seccomp: false,
            missing: vec!["the sandbox is built on Linux only (Landlock and seccomp)".to_owned()],
        }
    }

    pub(super) fn landlock_thread(_writable: &[PathBuf]) -> Result<Option<bool>, String> {
        Ok(None)
    }

    pub(super) fn support() -> (i32, bool) {
        (0, false)
    }
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;

    /// Runs this test binary again on `test` with `SITLOG_SANDBOX_CHILD`
    /// set: the sandbox binds the whole process, so each case confines a
    /// child of its own. `None` when the kernel lacks the sandbox.
    fn in_child(test: &str) -> Option<std::process::Output> {
        if std::env::var_os("SITLOG_SANDBOX_CHILD").is_some() {
            return None;
        }
        let (abi, seccomp) = support();
        if abi < 4 || !seccomp {
            sitlog_runtime::errln!(
                "skipping {test}: no sandbox here (Landlock ABI {abi}, seccomp {seccomp})"
            );
            return None;
        }
        let dir = scratch("child");
        let out = std::process::Command::new(std::env::current_exe().unwrap())
            .args([test, "--exact", "--nocapture", "--test-threads=1"])
            .env("SITLOG_SANDBOX_CHILD", "1")
            .env("SITLOG_SANDBOX_DIR", &dir)
            .output()
            .unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        Some(out)
    }

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("sitlog-sandbox-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("own")).unwrap();
        d
    }

    /// In the confined process: threads start (from the confined thread
    /// and from one started before), no process does, files are written
    /// only where allowed, a thread started before the sandbox is bound
    /// once it applies the hook, and no TCP socket is bound.
    #[test]
    fn threads_work_and_every_thread_is_held() {
        if let Some(out) = in_child("sandbox::tests::threads_work_and_every_thread_is_held") {
            let text = String::from_utf8_lossy(&out.stdout).into_owned()
                + &String::from_utf8_lossy(&out.stderr);
            assert!(out.status.success(), "{text}");
            assert!(text.contains("child checked"), "{text}");
            return;
        }
        if std::env::var_os("SITLOG_SANDBOX_CHILD").is_none() {
            return;
        }
        let dir = PathBuf::from(
            std::env::var("SITLOG_SANDBOX_DIR")
                .unwrap_or_else(|_| scratch("child").display().to_string()),
        );
        std::fs::create_dir_all(dir.join("own")).unwrap();
        // A thread started before the sandbox, as the Prolog engine's is.
        let (tx, rx) = std::sync::mpsc::channel::<Confine>();
        let (done_tx, done_rx) = std::sync::mpsc::channel::<Result<(), String>>();
        let d2 = dir.clone();
        let early = std::thread::spawn(move || {
            let confine = rx.recv().unwrap();
            let own = vec![d2.join("own")];
            let r = confine.apply(&own).and_then(|()| {
                std::fs::write(d2.join("own/ok"), "x").map_err(|e| format!("own dir: {e}"))?;
                match std::fs::write(d2.join("outside"), "x") {
                    Ok(()) => Err("the early thread wrote outside".to_owned()),
                    Err(_) => Ok(()),
                }
            });
            done_tx.send(r).unwrap();
        });
        let args = RunArgs {
            sandbox: SandboxMode::Require,
            ..RunArgs::default()
        };
        let mut err = Vec::new();
        let confine = enter(&args, None, &mut err)
            .expect("the sandbox is entered")
            .expect("a hook for the engine's thread");
        // Threads still start, from this thread.
        let h = std::thread::spawn(|| 40 + 2);
        assert_eq!(h.join().unwrap(), 42);
        // No process.
        assert!(std::process::Command::new("/bin/true").status().is_err());
        // This thread writes nowhere but /dev/null.
        assert!(std::fs::write(dir.join("main"), "x").is_err());
        std::fs::write("/dev/null", "x").expect("/dev/null stays writable");
        // No TCP, no internet socket.
        assert!(std::net::TcpListener::bind("127.0.0.1:0").is_err());
        assert!(std::net::UdpSocket::bind("127.0.0.1:0").is_err());
        tx.send(confine).unwrap();
        done_rx.recv().unwrap().unwrap();
        early.join().unwrap();
        assert!(dir.join("own/ok").exists());
        println!("child checked");
    }
}
