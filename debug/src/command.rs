//! The debugger's command language, shared by `sitlogc debug` and
//! `sitlogc replay`, and where commands come from (a line editor, or a
//! `--commands` file whose lines are echoed).

use std::io::Write;
use std::path::{Path, PathBuf};

/// A breakpoint's condition.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Spec {
    /// The first transition of each call of the DM.
    Dm(String),
    /// Each transition of the situation (its id, or the name of its id) in the DM.
    Situation(String, String),
    /// A run-time error (`break on error`; live runs only).
    Error,
}

impl std::fmt::Display for Spec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Spec::Dm(dm) => write!(f, "{dm}"),
            Spec::Situation(dm, sit) => write!(f, "{dm}:{sit}"),
            Spec::Error => f.write_str("on error"),
        }
    }
}

/// One command.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Command {
    /// `break` alone lists the breakpoints.
    Break(Option<Spec>),
    Delete(usize),
    Step,
    Next,
    Finish,
    Continue,
    Back,
    Goto(usize),
    Stack,
    Pipe,
    /// Locals of frame N (default: the innermost) and the globals.
    Vars(Option<usize>),
    History(Option<usize>),
    Print(String),
    Input(String),
    World,
    Diff(PathBuf),
    Help,
    Quit,
}

/// The help text (`help`).
pub const HELP: &str = "\
commands (at a stop):
  break DM[:SITUATION]  stop at the first transition of each call of DM, or at each transition of SITUATION in DM
  break on error        stop when the run fails, before the stack is unwound (live runs)
  break                 list the breakpoints
  delete N              remove breakpoint N
  step                  one transition
  next                  the next transition in this DM or a caller (over embedded DMs)
  finish                the next transition of a caller (out of this DM)
  continue              to the next breakpoint (or the end)
  back | goto N         one transition back | to transition N (replay only)
  stack                 the DM stack, innermost first
  pipe                  the pipe's value (live runs)
  vars [N]              the locals of frame N (default: the innermost) and the globals (live runs)
  history [N]           the last N transitions (default 10)
  print TERM            evaluate an L expression in the current DM, changing nothing (live runs)
  input TERM            answer the perceptual situation waiting for input (live runs)
  world                 the simulated world's state (live runs on a world)
  diff TRACE            the first transition where this recording and TRACE differ (replay only)
  help                  this text
  quit                  stop
";

/// Reads one command line; `Ok(None)` for an empty line or a `#` comment.
pub fn parse(line: &str) -> Result<Option<Command>, String> {
    let line = line.trim();
    if line.is_empty() || line.starts_with('#') {
        return Ok(None);
    }
    let (word, rest) = match line.find(char::is_whitespace) {
        Some(i) => (&line[..i], line[i..].trim()),
        None => (line, ""),
    };
    let none = |c: Command| {
        if rest.is_empty() {
            Ok(Some(c))
        } else {
            Err(format!("`{word}` takes no argument (got `{rest}`)"))
        }
    };
    let number = |what: &str| -> Result<usize, String> {
        rest.parse::<usize>()
            .map_err(|_| format!("`{word}` needs {what}, not `{rest}`"))
    };
    let optional = |what: &str| -> Result<Option<usize>, String> {
        if rest.is_empty() {
            Ok(None)
        } else {
            number(what).map(Some)
        }
    };
    let term = |c: fn(String) -> Command| {
        if rest.is_empty() {
            Err(format!("`{word}` needs a term"))
        } else {
            Ok(Some(c(rest.to_owned())))
        }
    };
    match word {
        "break" | "b" => {
            if rest.is_empty() {
                return Ok(Some(Command::Break(None)));
            }
            if rest == "on error" {
                return Ok(Some(Command::Break(Some(Spec::Error))));
            }
            let spec = match rest.split_once(':') {
                Some((dm, sit)) if !dm.trim().is_empty() && !sit.trim().is_empty() => {
                    Spec::Situation(dm.trim().to_owned(), sit.trim().to_owned())
                }
                Some(_) => return Err(format!("`break {rest}`: write DM or DM:SITUATION")),
                None if rest.contains(char::is_whitespace) => {
                    return Err(format!(
                        "`break {rest}`: write DM, DM:SITUATION or `on error`"
                    ))
                }
                None => Spec::Dm(rest.to_owned()),
            };
            Ok(Some(Command::Break(Some(spec))))
        }
        "delete" | "d" => Ok(Some(Command::Delete(number("a breakpoint number")?))),
        "step" | "s" => none(Command::Step),
        "next" | "n" => none(Command::Next),
        "finish" | "f" => none(Command::Finish),
        "continue" | "c" => none(Command::Continue),
        "back" => none(Command::Back),
        "goto" => Ok(Some(Command::Goto(number("a transition number")?))),
        "stack" | "bt" => none(Command::Stack),
        "pipe" => none(Command::Pipe),
        "vars" => Ok(Some(Command::Vars(optional("a frame number")?))),
        "history" => Ok(Some(Command::History(optional("a number of transitions")?))),
        "print" | "p" => term(Command::Print),
        "input" => term(Command::Input),
        "world" => none(Command::World),
        "diff" if rest.is_empty() => Err("`diff` needs a trace file".to_owned()),
        "diff" => Ok(Some(Command::Diff(PathBuf::from(rest)))),
        "help" | "h" | "?" => none(Command::Help),
        "quit" | "q" | "exit" => none(Command::Quit),
        _ => Err(format!("unknown command `{word}` (`help` lists them)")),
    }
}

/// Where commands come from.
pub enum CommandSource {
    /// A `--commands` file: its lines, each echoed after the prompt.
    File {
        name: String,
        lines: Vec<String>,
        next: usize,
    },
    /// A line editor on the terminal (history of the session's lines).
    Editor(Box<rustyline::DefaultEditor>),
}

/// A command line read, or why there is none.
pub enum Line {
    /// The text, and its line number in a commands file.
    Text(String, Option<usize>),
    /// End of the file, or of input (Ctrl-D).
    End,
}

impl CommandSource {
    /// A commands file (UTF-8 text); `Err` says why it cannot be read.
    pub fn file(path: &Path) -> Result<CommandSource, String> {
        let name = path.display().to_string();
        let bytes = sitlog_syntax::read_file(path)
            .map_err(|e| format!("error: cannot read commands file {name}: {e}"))?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let at = e.utf8_error().valid_up_to();
            let before = &e.as_bytes()[..at];
            let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
            let col = at
                - before
                    .iter()
                    .rposition(|&b| b == b'\n')
                    .map_or(0, |p| p + 1)
                + 1;
            format!("{name}:{line}:{col}: error: the commands file is not UTF-8 text")
        })?;
        Ok(CommandSource::File {
            name,
            lines: text.lines().map(str::to_owned).collect(),
            next: 0,
        })
    }

    /// Commands given as text (`name` names them in errors), as from a file.
    pub fn text(name: &str, text: &str) -> CommandSource {
        CommandSource::File {
            name: name.to_owned(),
            lines: text.lines().map(str::to_owned).collect(),
            next: 0,
        }
    }

    /// The terminal's line editor.
    pub fn editor() -> Result<CommandSource, String> {
        rustyline::DefaultEditor::new()
            .map(|e| CommandSource::Editor(Box::new(e)))
            .map_err(|e| format!("error: cannot start the line editor: {e}"))
    }

    /// The name of a commands file, for messages.
    pub fn file_name(&self) -> Option<&str> {
        match self {
            CommandSource::File { name, .. } => Some(name),
            CommandSource::Editor(_) => None,
        }
    }

    /// The next line, after `prompt` (echoed to `out` from a file).
    pub fn read(&mut self, prompt: &str, out: &mut dyn Write) -> Line {
        match self {
            CommandSource::File { lines, next, .. } => {
                let Some(line) = lines.get(*next) else {
                    return Line::End;
                };
                *next += 1;
                let _ = writeln!(out, "{prompt}{line}");
                Line::Text(line.clone(), Some(*next))
            }
            CommandSource::Editor(editor) => {
                let _ = out.flush();
                loop {
                    match editor.readline(prompt) {
                        Ok(line) => {
                            if !line.trim().is_empty() {
                                let _ = editor.add_history_entry(line.as_str());
                            }
                            return Line::Text(line, None);
                        }
                        // Ctrl-C drops the line.
                        Err(rustyline::error::ReadlineError::Interrupted) => continue,
                        Err(_) => return Line::End,
                    }
                }
            }
        }
    }
}

/// The prompt.
pub const PROMPT: &str = "(sitlog) ";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_parse() {
        assert_eq!(
            parse("break main:ask"),
            Ok(Some(Command::Break(Some(Spec::Situation(
                "main".into(),
                "ask".into()
            )))))
        );
        assert_eq!(
            parse(" break greet "),
            Ok(Some(Command::Break(Some(Spec::Dm("greet".into())))))
        );
        assert_eq!(
            parse("break on error"),
            Ok(Some(Command::Break(Some(Spec::Error))))
        );
        assert_eq!(parse("history 3"), Ok(Some(Command::History(Some(3)))));
        assert_eq!(parse("vars"), Ok(Some(Command::Vars(None))));
        assert_eq!(
            parse("print apply(f(X), [1])"),
            Ok(Some(Command::Print("apply(f(X), [1])".into())))
        );
        assert_eq!(parse("# a comment"), Ok(None));
        assert_eq!(parse(""), Ok(None));
        assert!(parse("jump")
            .unwrap_err()
            .contains("unknown command `jump`"));
        assert!(parse("delete x").unwrap_err().contains("breakpoint number"));
        assert!(parse("step 2").unwrap_err().contains("takes no argument"));
        assert!(parse("print").unwrap_err().contains("needs a term"));
        assert!(parse("break :x").is_err());
    }
}

#[cfg(test)]
mod props {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Any line is a command, nothing, or an error: never a panic.
        #[test]
        fn any_line_parses_or_is_refused(line in "\\PC{0,40}") {
            let _ = parse(&line);
        }

        /// Commands made of the known words and any argument.
        #[test]
        fn known_words_with_any_argument(
            word in prop::sample::select(vec![
                "break", "delete", "step", "next", "finish", "continue", "back", "goto",
                "stack", "pipe", "vars", "history", "print", "input", "world", "diff", "help", "quit",
            ]),
            arg in "[ -~]{0,12}",
        ) {
            let _ = parse(&format!("{word} {arg}"));
        }
    }
}
