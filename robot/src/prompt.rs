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
/// Off a terminal, the second part is the same reader for Prolog's
/// `read/1` (issue 39); on a terminal `read/1` gets `end_of_file`.
pub(crate) fn typed_input(
    limits: InputLimits,
    signals: Option<&Interrupt>,
    ended: Interrupt,
    console: SharedConsole,
) -> (Box<dyn Perception>, Option<SharedInput>) {
    let (prompt, input): (Box<dyn Perception>, _) = match edited_prompt(limits, &ended) {
        Some(p) => (p, None),
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
}

/// The prompt with line editing, when stdin and stderr are terminals (and
/// the `edit` feature is on).
#[cfg(feature = "edit")]
fn edited_prompt(limits: InputLimits, interrupt: &Interrupt) -> Option<Box<dyn Perception>> {
    use std::io::IsTerminal;
    if !(std::io::stdin().is_terminal() && std::io::stderr().is_terminal()) {
        return None;
    }
    EditedPrompt::new(limits, interrupt.clone()).map(|p| Box::new(p) as Box<dyn Perception>)
}

#[cfg(not(feature = "edit"))]
fn edited_prompt(_: InputLimits, _: &Interrupt) -> Option<Box<dyn Perception>> {
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
}

#[cfg(feature = "edit")]
pub use edit::EditedPrompt;

#[cfg(feature = "edit")]
mod edit {
    use crate::interrupt::Interrupt;
    use rustyline::config::{Behavior, Config};
    use rustyline::error::ReadlineError;
    use rustyline::DefaultEditor;
    use sitlog_runtime::machine::{Perceived, Perception};
    use sitlog_runtime::testmode::{prompt_header, waiting_text, InputLimits};
    use sitlog_runtime::{Store, Term};
    use sitlog_syntax::OpTable;
    use std::io::Write;

    /// The prompt with line editing and history, on the terminal.
    pub struct EditedPrompt {
        editor: DefaultEditor,
        limits: InputLimits,
        at: Option<(String, String)>,
        interrupt: Interrupt,
    }

    impl EditedPrompt {
        /// `None` when the terminal cannot be used for line editing.
        pub fn new(limits: InputLimits, interrupt: Interrupt) -> Option<EditedPrompt> {
            let config = Config::builder()
                .behavior(Behavior::PreferTerm)
                .auto_add_history(false)
                .build();
            let editor = DefaultEditor::with_config(config).ok()?;
            Some(EditedPrompt {
                editor,
                limits,
                at: None,
                interrupt,
            })
        }
    }

    impl Perception for EditedPrompt {
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
            let mut text = String::new();
            loop {
                let prompt = if text.is_empty() { "|: " } else { "|  " };
                let line = match self.editor.readline(prompt) {
                    Ok(line) => line,
                    Err(ReadlineError::Eof) if text.trim().is_empty() => {
                        return Ok(Perceived::EndOfInput)
                    }
                    Err(ReadlineError::Eof) => String::new(),
                    Err(ReadlineError::Interrupted) => {
                        // Ctrl-C in raw mode is a key, not a signal: stop as SIGINT would.
                        self.interrupt.request(2);
                        return Err("interrupted (Ctrl-C at the prompt)".to_owned());
                    }
                    Err(e) => return Err(format!("the terminal: {e}")),
                };
                if !line.trim().is_empty() {
                    let _ = self.editor.add_history_entry(line.as_str());
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
                    Ok(clause) => {
                        let (t, _) = store.from_clause(&clause);
                        return Ok(sitlog_runtime::testmode::deliver_typed(store, ty, t));
                    }
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

        fn waiting_at(&mut self, store: &Store, dm: Term, situation: Term) {
            self.at = Some(waiting_text(store, dm, situation));
        }
    }
}
