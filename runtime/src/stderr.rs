//! Text for people on stderr (diagnostics, errors, notes) written so that
//! a failed write never ends the process: `eprintln!` panics when stderr is
//! closed or full (`2>&-`, `2>/dev/full`), and a panic there would turn a
//! clean exit status into 101. Invariant: [`errln!`](crate::errln) and
//! [`errprint!`](crate::errprint) never panic; a write that fails is
//! dropped (there is nowhere left to report it) and the exit status still
//! says how the command ended. Every diagnostic write of the workspace's
//! binaries goes through here.

use std::io::Write;

/// Writes `args` (and a newline when `newline`) to stderr; `false` when
/// the write failed.
pub fn write(args: std::fmt::Arguments<'_>, newline: bool) -> bool {
    let mut err = std::io::stderr().lock();
    let ok = err.write_fmt(args).is_ok();
    let ok = ok && (!newline || err.write_all(b"\n").is_ok());
    ok && err.flush().is_ok()
}

/// `eprintln!` that never panics (see [`crate::stderr`]).
#[macro_export]
macro_rules! errln {
    () => {{
        let _ = $crate::stderr::write(format_args!(""), true);
    }};
    ($($arg:tt)*) => {{
        let _ = $crate::stderr::write(format_args!($($arg)*), true);
    }};
}

/// `eprint!` that never panics (see [`crate::stderr`]).
#[macro_export]
macro_rules! errprint {
    ($($arg:tt)*) => {{
        let _ = $crate::stderr::write(format_args!($($arg)*), false);
    }};
}
