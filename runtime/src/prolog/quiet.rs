//! Panics of the Prolog engine kept quiet: what [`quietly`] runs on the
//! engine's thread may panic inside scryer (its conversion of an answer
//! it does not expect); the caller catches the panic and restarts the
//! engine, and the message becomes the caller's error instead of a
//! backtrace on stderr ("never a panic" for the user).
//!
//! Invariant: the process-wide panic hook is replaced once, by a hook
//! that hands every panic to the hook it replaced except one raised on a
//! thread while that thread runs [`quietly`]: other threads, and this one
//! outside [`quietly`], panic as before.

use std::cell::{Cell, RefCell};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;

thread_local! {
    /// This thread runs [`quietly`].
    static QUIET: Cell<bool> = const { Cell::new(false) };
    /// The message of the panic [`quietly`] caught on this thread.
    static MESSAGE: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Runs `f`, a panic caught and not printed: `Err` with its message.
pub(super) fn quietly<R>(f: impl FnOnce() -> R) -> Result<R, String> {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if QUIET.with(Cell::get) {
                let text = info
                    .payload()
                    .downcast_ref::<&str>()
                    .map(|s| (*s).to_owned())
                    .or_else(|| info.payload().downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "a panic".to_owned());
                let at = info
                    .location()
                    .map(|l| format!(" at {}:{}", l.file(), l.line()))
                    .unwrap_or_default();
                MESSAGE.with(|m| *m.borrow_mut() = Some(format!("{text}{at}")));
            } else {
                previous(info);
            }
        }));
    });
    QUIET.with(|q| q.set(true));
    let r = catch_unwind(AssertUnwindSafe(f));
    QUIET.with(|q| q.set(false));
    r.map_err(|_| {
        MESSAGE
            .with(|m| m.borrow_mut().take())
            .unwrap_or_else(|| "a panic".to_owned())
    })
}

#[cfg(test)]
mod tests {
    use super::quietly;

    #[test]
    fn a_panic_inside_is_an_error_with_its_message() {
        assert_eq!(quietly(|| 1 + 1), Ok(2));
        let e = quietly(|| -> u8 { panic!("boom {}", 7) }).unwrap_err();
        assert!(e.starts_with("boom 7 at "), "{e}");
        // Outside, a panic is caught as usual (and printed by the hook
        // that was there before).
        assert!(std::panic::catch_unwind(|| panic!("loud")).is_err());
    }
}
