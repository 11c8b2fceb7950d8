//! The test-mode prompt of a run without `--script` (issue 17): typed
//! inputs, with the DM and situation waiting and their expectations shown
//! before each read.
//!
//! - On a terminal (stdin and stderr both terminals, feature `edit`), lines
//!   are read with line editing and history (`EditedPrompt`, rustyline,
//!   on the terminal itself); Ctrl-C stops the run as SIGINT does.
//! - Otherwise lines are read as they come ([`PromptPerception`] of the
//!   runtime), so scripts and pipes work as before.
//!
//! Either way the end of the input (Ctrl-D, or the end of a pipe) ends the
//! task cleanly ([`EndOfInputStops`]): the run stops with the history so
//! far and exit status [`EXIT_END_OF_INPUT`](crate::interrupt::EXIT_END_OF_INPUT),
//! not as a run-time error; and no progress indicator is on the terminal
//! while a situation waits for what is typed ([`PausesProgress`]): it comes
//! back when the task runs on its own.
//!
//! [`PromptPerception`]: sitlog_runtime::testmode::PromptPerception

use crate::console::SharedConsole;
use crate::interrupt::{Interrupt, InterruptibleStdin};
use sitlog_runtime::machine::{Perceived, Perception};
use sitlog_runtime::testmode::{InputLimits, PromptPerception, SharedInput, SharedPerception};
use sitlog_runtime::{Store, Term};

/// The perception of typed input: line editing on a terminal; else lines
/// read on a thread of their own when `signals` can stop the run (so that
/// the prompt sees them), or straight from stdin. The end of the input is
/// recorded in `ended`; `console`'s progress indicator is paused while
/// the prompt waits.
///
/// The second part is the same reader for Prolog's `read/1` (issue 39):
/// a user function's `read(X)` takes the next term typed, on a terminal
/// or not.
pub(crate) fn typed_input(
    limits: InputLimits,
    signals: Option<&Interrupt>,
    ended: Interrupt,
    console: SharedConsole,
) -> (Box<dyn Perception>, Option<SharedInput>) {
    let (prompt, input): (Box<dyn Perception>, _) = match edited_prompt(limits, &ended, &console) {
        Some((p, input)) => (p, Some(input)),
        None => match signals {
            Some(i) => {
                let p = SharedPerception::new(
                    PromptPerception::new(InterruptibleStdin::new(i.flag.clone()))
                        .with_limits(limits),
                );
                let input = p.input();
                (Box::new(p), Some(input))
            }
            None => {
                let stdin = std::io::BufReader::new(std::io::stdin());
                let p = SharedPerception::new(PromptPerception::new(stdin).with_limits(limits));
                let input = p.input();
                (Box::new(p), Some(input))
            }
        },
    };
    let perception = Box::new(PausesProgress {
        inner: Box::new(EndOfInputStops::new(prompt, ended)),
        console,
    });
    (perception, input)
}

/// Takes the progress indicator off the terminal while `inner` waits for
/// typed input, and brings it back when the input is read.
pub struct PausesProgress {
    inner: Box<dyn Perception>,
    console: SharedConsole,
}

impl Perception for PausesProgress {
    fn perceive(
        &mut self,
        store: &mut Store,
        situation_type: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        if let Ok(mut c) = self.console.lock() {
            c.pause();
        }
        let p = self.inner.perceive(store, situation_type, expectations);
        if let Ok(mut c) = self.console.lock() {
            c.resume();
        }
        p
    }

    fn waiting_at(&mut self, store: &Store, dm: Term, situation: Term) {
        self.inner.waiting_at(store, dm, situation);
    }

    fn uses_waiting_at(&self) -> bool {
        self.inner.uses_waiting_at()
    }

    fn unmatched_is_news(&self) -> bool {
        self.inner.unmatched_is_news()
    }
}

/// The prompt with line editing, when stdin and stderr are terminals (and
/// the `edit` feature is on), and the same reader for `read/1`.
#[cfg(feature = "edit")]
fn edited_prompt(
    limits: InputLimits,
    interrupt: &Interrupt,
    console: &SharedConsole,
) -> Option<(Box<dyn Perception>, SharedInput)> {
    use std::io::IsTerminal;
    if !(std::io::stdin().is_terminal() && std::io::stderr().is_terminal()) {
        return None;
    }
    let p = EditedPrompt::new(limits, interrupt.clone())?.with_console(console.clone());
    let p = SharedPerception::new(p);
    let input = p.input();
    Some((Box::new(p), input))
}

#[cfg(not(feature = "edit"))]
fn edited_prompt(
    _: InputLimits,
    _: &Interrupt,
    _: &SharedConsole,
) -> Option<(Box<dyn Perception>, SharedInput)> {
    None
}

/// Makes the end of a prompt's input stop the run cleanly: the run's
/// interrupt records it, so the machine's end-of-input error becomes an
/// interrupted outcome with exit status 3.
pub struct EndOfInputStops {
    inner: Box<dyn Perception>,
    interrupt: Interrupt,
}

impl EndOfInputStops {
    pub fn new(inner: Box<dyn Perception>, interrupt: Interrupt) -> EndOfInputStops {
        EndOfInputStops { inner, interrupt }
    }
}

impl Perception for EndOfInputStops {
    fn perceive(
        &mut self,
        store: &mut Store,
        situation_type: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        let p = self.inner.perceive(store, situation_type, expectations)?;
        if p == Perceived::EndOfInput && !self.interrupt.requested() {
            self.interrupt.request_end_of_input();
            // End the prompt's line.
            sitlog_runtime::errln!();
        }
        Ok(p)
    }

    fn waiting_at(&mut self, store: &Store, dm: Term, situation: Term) {
        self.inner.waiting_at(store, dm, situation);
    }

    fn uses_waiting_at(&self) -> bool {
        self.inner.uses_waiting_at()
    }

    fn unmatched_is_news(&self) -> bool {
        self.inner.unmatched_is_news()
    }
}

#[cfg(feature = "edit")]
pub use edit::{EditedPrompt, Lines};

#[cfg(feature = "edit")]
mod edit {
    use crate::console::SharedConsole;
    use crate::interrupt::Interrupt;
    use rustyline::config::{Behavior, Config};
    use rustyline::error::ReadlineError;
    use rustyline::DefaultEditor;
    use sitlog_runtime::machine::{Perceived, Perception};
    use sitlog_runtime::testmode::{prompt_header, waiting_text, InputLimits, TermInput};
    use sitlog_runtime::{Store, Term};
    use sitlog_syntax::{Clause, OpTable};
    use std::io::Write;

    /// Where an [`EditedPrompt`] gets its lines: the terminal's line
    /// editor, or lines given in a test.
    pub trait Lines: Send {
        /// The next line typed after `prompt` (without its line end).
        fn readline(&mut self, prompt: &str) -> Result<String, ReadlineError>;
        /// Keeps `line` in the history.
        fn add_history(&mut self, line: &str);
    }

    impl Lines for DefaultEditor {
        fn readline(&mut self, prompt: &str) -> Result<String, ReadlineError> {
            DefaultEditor::readline(self, prompt)
        }
        fn add_history(&mut self, line: &str) {
            let _ = self.add_history_entry(line);
        }
    }

    /// The prompt with line editing and history, on the terminal. It is
    /// also the reader of Prolog's `read/1` (issue 39): a user function's
    /// `read(X)` takes the next term typed, at SWI-Prolog's prompt `|: `,
    /// as the original's does.
    pub struct EditedPrompt<L: Lines = DefaultEditor> {
        lines: L,
        limits: InputLimits,
        at: Option<(String, String)>,
        interrupt: Interrupt,
        /// The progress indicator, taken off the terminal while `read/1`
        /// waits (the perception's caller pauses it for the situations).
        console: Option<SharedConsole>,
    }

    impl EditedPrompt {
        /// `None` when the terminal cannot be used for line editing.
        pub fn new(limits: InputLimits, interrupt: Interrupt) -> Option<EditedPrompt> {
            let config = Config::builder()
                .behavior(Behavior::PreferTerm)
                .auto_add_history(false)
                .build();
            let editor = DefaultEditor::with_config(config).ok()?;
            Some(EditedPrompt::with_lines(editor, limits, interrupt))
        }
    }

    impl<L: Lines> EditedPrompt<L> {
        /// The prompt reading its lines from `lines`.
        pub fn with_lines(lines: L, limits: InputLimits, interrupt: Interrupt) -> Self {
            EditedPrompt {
                lines,
                limits,
                at: None,
                interrupt,
                console: None,
            }
        }

        /// Pauses `console`'s progress indicator while `read/1` waits.
        pub fn with_console(mut self, console: SharedConsole) -> Self {
            self.console = Some(console);
            self
        }

        /// The next term typed and its text (trimmed); `None` at the end
        /// of the input (Ctrl-D). A syntax error is shown on `err` and the
        /// next term read.
        fn read_clause(&mut self, err: &mut dyn Write) -> Result<Option<(Clause, String)>, String> {
            let mut text = String::new();
            loop {
                let prompt = if text.is_empty() { "|: " } else { "|  " };
                let line = match self.lines.readline(prompt) {
                    Ok(line) => line,
                    Err(ReadlineError::Eof) if text.trim().is_empty() => return Ok(None),
                    Err(ReadlineError::Eof) => String::new(),
                    Err(ReadlineError::Interrupted) => {
                        // Ctrl-C in raw mode is a key, not a signal: stop as SIGINT would.
                        self.interrupt.request(2);
                        return Err("interrupted (Ctrl-C at the prompt)".to_owned());
                    }
                    Err(e) => return Err(format!("the terminal: {e}")),
                };
                if !line.trim().is_empty() {
                    self.lines.add_history(&line);
                }
                let ended = line.is_empty() && !text.is_empty();
                text.push_str(&line);
                text.push('\n');
                if text.trim().is_empty() {
                    text.clear();
                    continue;
                }
                let what = "the input";
                if text.len() > self.limits.max_bytes {
                    return Err(self.limits.size_error(what, text.len()));
                }
                match sitlog_syntax::read_term_limited(
                    text.trim(),
                    OpTable::sitlog_shared(),
                    self.limits.max_depth,
                ) {
                    Ok(clause) => return Ok(Some((clause, text.trim().to_owned()))),
                    Err(e) if e.is_too_deep() => return Err(self.limits.depth_error(what)),
                    Err(e) if e.incomplete && !ended => continue,
                    Err(e) => {
                        let _ = writeln!(
                            err,
                            "syntax error: {} (type a term ending with `.`)",
                            e.message
                        );
                        text.clear();
                    }
                }
            }
        }
    }

    impl<L: Lines> Perception for EditedPrompt<L> {
        fn perceive(
            &mut self,
            store: &mut Store,
            ty: Term,
            expectations: &[Term],
        ) -> Result<Perceived, String> {
            let header = prompt_header(store, self.at.as_ref(), ty, expectations);
            let mut err = std::io::stderr();
            let _ = writeln!(err, "{header}");
            let _ = err.flush();
            match self.read_clause(&mut err)? {
                Some((clause, _)) => {
                    let (t, _) = store.from_clause(&clause);
                    Ok(sitlog_runtime::testmode::deliver_typed(store, ty, t))
                }
                None => Ok(Perceived::EndOfInput),
            }
        }

        fn waiting_at(&mut self, store: &Store, dm: Term, situation: Term) {
            self.at = Some(waiting_text(store, dm, situation));
        }
    }

    /// Prolog's `read/1` in a user function takes the next term typed at
    /// the terminal (issue 39), as the original's does.
    impl<L: Lines> TermInput for EditedPrompt<L> {
        fn next_term_text(&mut self) -> Result<Option<String>, String> {
            if let Some(c) = &self.console {
                if let Ok(mut c) = c.lock() {
                    c.pause();
                }
            }
            let mut err = std::io::stderr();
            let text = self.read_clause(&mut err).map(|r| r.map(|(_, text)| text));
            if let Some(c) = &self.console {
                if let Ok(mut c) = c.lock() {
                    c.resume();
                }
            }
            text
        }
    }
}

#[cfg(all(test, feature = "edit"))]
mod tests {
    use super::*;
    use rustyline::error::ReadlineError;

    /// Lines "typed" at the terminal, then Ctrl-D.
    struct Typed(std::collections::VecDeque<&'static str>);

    impl Lines for Typed {
        fn readline(&mut self, _: &str) -> Result<String, ReadlineError> {
            self.0
                .pop_front()
                .map(str::to_owned)
                .ok_or(ReadlineError::Eof)
        }
        fn add_history(&mut self, _: &str) {}
    }

    /// At a terminal, the situations and a user function's `read/1` take
    /// the terms typed in order, one reader for both (issue 39): a term
    /// over two lines, a syntax error typed again, then Ctrl-D.
    #[test]
    fn read_at_the_terminal_takes_the_next_term_typed() {
        let typed = Typed(["ok.", "hello(", "world).", "", "bad).", "next."].into());
        let p = EditedPrompt::with_lines(typed, InputLimits::default(), Interrupt::new());
        let mut p = SharedPerception::new(p);
        let input = p.input();
        let mut store = Store::new();
        let ty = Term::atom(sitlog_syntax::Atom::intern("typed"));
        let first = p.perceive(&mut store, ty, &[]).unwrap();
        let Perceived::Input(t) = first else {
            panic!("{first:?}")
        };
        assert_eq!(store.writeq(t), "ok");
        let read = || input.lock().unwrap().next_term_text().unwrap();
        assert_eq!(read().as_deref(), Some("hello(\nworld)."));
        assert_eq!(read().as_deref(), Some("next."));
        assert_eq!(read(), None);
        assert_eq!(
            p.perceive(&mut store, ty, &[]).unwrap(),
            Perceived::EndOfInput
        );
    }
}
