//! Test mode, as the original's: expectations are met by terms read from a
//! script (one term per clause, ending with `.`) or typed at a prompt, and
//! actions are rendered as text on stderr. Input is data: it is read as a
//! term and never executed.
//!
//! Our own applications get the typed term as it is, except a situation of
//! type `listening` or `nkeyboard` (any arity), which gets `said(Term)`
//! (D-14). Under `sitlogc run --legacy`, [`original`] gives each situation
//! type what the original's test mode gives it instead (`detected(T)`,
//! `doas(T)`, `speaker(T)`, several terms read...).

pub use crate::input::{InputLimits, SharedInput, TermInput};
use crate::machine::{ActionShape, Actions, Perceived, Percept, Perception};
use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::{Atom, ClauseReader, OpTable};
use std::io::{BufRead, Read, Write};

pub mod original;
mod said;
pub use original::OriginalTestMode;
mod prompt;
pub use prompt::PromptPerception;

/// `said`, `nkeyboard` and `listening`, interned once (an input is
/// delivered at every perception: its type compared as atoms, not text).
fn said_atoms() -> &'static [Atom; 3] {
    static ATOMS: std::sync::OnceLock<[Atom; 3]> = std::sync::OnceLock::new();
    ATOMS.get_or_init(|| ["said", "nkeyboard", "listening"].map(Atom::intern))
}

/// Types whose perceptual interpreter wraps the input as `said(Term)` (D-14).
pub(crate) fn wraps_said(store: &Store, ty: Term) -> bool {
    let [_, nkeyboard, listening] = *said_atoms();
    store
        .functor(ty)
        .is_some_and(|(n, _)| n == nkeyboard || n == listening)
}

/// An input typed or read for a situation of type `ty`, as the perceptual
/// interpreter delivers it (`said(Input)` for `listening` and `nkeyboard`).
pub fn deliver_typed(store: &mut Store, ty: Term, input: Term) -> Perceived {
    deliver(store, ty, input)
}

fn deliver(store: &mut Store, ty: Term, input: Term) -> Perceived {
    deliver_percept(store, ty, input).into_perceived(store)
}

/// [`deliver`]'s input, `said(Input)` not built ([`Percept::Wrapped`]).
fn deliver_percept(store: &Store, ty: Term, input: Term) -> Percept {
    if wraps_said(store, ty) {
        Percept::Wrapped(said_atoms()[0], input)
    } else {
        Percept::Whole(Perceived::Input(input))
    }
}

/// Inputs from a script text.
pub struct ScriptPerception {
    text: String,
    pos: usize,
    /// Name of the script for error messages.
    name: String,
    /// Echo each input read to stderr.
    pub echo: bool,
    limits: InputLimits,
    /// Reads a plain atom input (`tick.`) without the term reader (see
    /// [`plain_atom`]); off only to compare both ways in tests.
    atoms_fast: bool,
    /// Where more of the script comes from, for a script read as the task
    /// consumes it (a pipe, a device: [`ScriptPerception::from_reader`]);
    /// `None` once it ended or for a script given whole.
    source: Option<Box<dyn BufRead + Send>>,
    /// Lines read so far (for positions of text that is not UTF-8).
    lines: usize,
    /// Lines dropped from the front of `text` once consumed.
    dropped_lines: usize,
    /// The plain atoms read last ([`RecentAtoms`]): a script repeats a
    /// few words.
    recent: RecentAtoms,
}

/// The last few plain atoms of at most 8 bytes a script gave, by their
/// text packed in a `u64` (zero-padded: a plain atom has no zero byte),
/// each one not an operator: such a word read again (`no.` at each place
/// of a walk) costs a comparison, not the interner's look-up nor the
/// operator table's. Any other word goes the way [`plain_atom`] goes.
#[derive(Default)]
struct RecentAtoms {
    keys: [u64; 4],
    atoms: [Option<Atom>; 4],
    next: usize,
}

impl RecentAtoms {
    /// [`plain_atom`]'s atom of the plain atom `name` (its text), `None`
    /// for an operator (the operator table asked only for a word not
    /// kept).
    /// The word is `text[start..end]`.
    #[inline]
    fn atom(&mut self, text: &str, start: usize, end: usize) -> Option<Atom> {
        let name = &text[start..end];
        let bytes = name.as_bytes();
        let ops = OpTable::sitlog_shared;
        if bytes.len() > 8 {
            return not_op(Atom::intern(name), ops());
        }
        // Packed from the eight bytes at `start` where the text has them
        // (one load, the bytes past the word masked off), else copied.
        let key = match text.as_bytes().get(start..start + 8) {
            Some(eight) => {
                let word = u64::from_le_bytes(eight.try_into().expect("eight bytes"));
                match bytes.len() {
                    8 => word,
                    n => word & ((1u64 << (8 * n)) - 1),
                }
            }
            None => {
                let mut packed = [0u8; 8];
                packed[..bytes.len()].copy_from_slice(bytes);
                u64::from_le_bytes(packed)
            }
        };
        if let Some(i) = self.keys.iter().position(|&k| k == key) {
            return self.atoms[i];
        }
        let atom = not_op(Atom::intern(name), ops())?;
        let i = self.next;
        self.keys[i] = key;
        self.atoms[i] = Some(atom);
        self.next = (i + 1) % self.keys.len();
        Some(atom)
    }
}

/// `atom`, unless it is an operator (not a plain atom: the term reader's).
fn not_op(atom: Atom, ops: &OpTable) -> Option<Atom> {
    (!ops.is_op(atom)).then_some(atom)
}

impl ScriptPerception {
    pub fn new(name: impl Into<String>, text: String) -> ScriptPerception {
        ScriptPerception {
            text,
            pos: 0,
            name: name.into(),
            echo: false,
            limits: InputLimits::default(),
            atoms_fast: true,
            source: None,
            lines: 0,
            dropped_lines: 0,
            recent: RecentAtoms::default(),
        }
    }

    /// A script read from `reader` as the task consumes it: whole lines, no
    /// more than one input ahead (so `yes 'quit.' | sitlogc run --script
    /// /dev/stdin` ends at once); each input still under the limits.
    pub fn from_reader(
        name: impl Into<String>,
        reader: Box<dyn BufRead + Send>,
    ) -> ScriptPerception {
        let mut script = ScriptPerception::new(name, String::new());
        script.source = Some(reader);
        script
    }

    /// For a script read as it is consumed: reads whole lines until the
    /// unread text holds a complete input (or a syntax error more text
    /// cannot mend, or more than one input may be long), or the source ends.
    /// Each read at least doubles the unread text, so an input spread over
    /// many lines costs linear time.
    fn fill(&mut self) -> Result<(), String> {
        let ops = OpTable::sitlog_shared();
        while self.source.is_some() {
            // what the task consumed is dropped (whole lines: columns stay)
            if self.pos >= 1 << 16 {
                if let Some(cut) = self.text[..self.pos].rfind('\n').map(|i| i + 1) {
                    self.dropped_lines += self.text[..cut].matches('\n').count();
                    self.text.drain(..cut);
                    self.pos -= cut;
                }
            }
            let rest = &self.text[self.pos..];
            // past max_bytes + 1: the input is refused as too long below
            if rest.len() > self.limits.max_bytes + 1 {
                return Ok(());
            }
            if plain_atom(rest, ops).is_some() {
                return Ok(());
            }
            let mut reader = ClauseReader::new(rest, ops).with_max_depth(self.limits.max_depth);
            match reader.next_clause() {
                Some(Ok(_)) => return Ok(()),
                Some(Err(e))
                    if !e.incomplete && !e.is_too_deep() && reader.position() < rest.len() =>
                {
                    return Ok(())
                }
                _ => {}
            }
            // one line at least (a pipe feeding inputs one by one is never
            // waited on for more), as many bytes as the unread text at most
            let want = rest.len().max(1);
            let room = (self.limits.max_bytes + 2 - rest.len()) as u64;
            let Some(source) = self.source.as_mut() else {
                break;
            };
            let mut bytes = Vec::new();
            let mut ended = false;
            while bytes.len() < want && (bytes.len() as u64) < room {
                let left = room - bytes.len() as u64;
                let n = source
                    .as_mut()
                    .take(left)
                    .read_until(b'\n', &mut bytes)
                    .map_err(|e| format!("error: cannot read script {}: {e}", self.name))?;
                if n == 0 {
                    ended = true;
                    break;
                }
            }
            // a byte order mark is skipped at the start of the script only
            let text = if self.lines == 0 && self.dropped_lines == 0 && self.text.is_empty() {
                sitlog_syntax::decode_owned(bytes)
            } else {
                String::from_utf8(bytes).map_err(|e| {
                    let bytes = e.into_bytes();
                    let mut at = bytes.clone();
                    // decode names the first bad byte (a leading BOM kept)
                    at.splice(0..0, b"x".iter().copied());
                    match sitlog_syntax::decode(&at) {
                        Err(mut d) => {
                            if d.line == 1 {
                                d.column -= 1;
                            }
                            d
                        }
                        Ok(_) => sitlog_syntax::DecodeError {
                            offset: 0,
                            line: 1,
                            column: 1,
                            message: "invalid UTF-8".to_owned(),
                            utf16: false,
                        },
                    }
                })
            };
            let text = text.map_err(|e| {
                format!(
                    "{}:{}:{}: error: {}",
                    self.name,
                    self.lines + e.line,
                    e.column,
                    e.message
                )
            })?;
            self.lines += text.matches('\n').count();
            self.text.push_str(&text);
            if ended {
                self.source = None;
            }
        }
        Ok(())
    }

    /// The script of `bytes`: an error naming `name`, line and column when
    /// they are not UTF-8 (a UTF-8 BOM is skipped).
    pub fn from_bytes(name: impl Into<String>, bytes: Vec<u8>) -> Result<ScriptPerception, String> {
        let name = name.into();
        match sitlog_syntax::decode_owned(bytes) {
            Ok(text) => Ok(ScriptPerception::new(name, text)),
            Err(e) => Err(format!("script {}", e.in_file(&name))),
        }
    }

    /// Reads each input under `limits` (default: [`InputLimits::default`]).
    pub fn with_limits(mut self, limits: InputLimits) -> Self {
        self.limits = limits;
        self
    }
}

/// Bytes of white space and `%` comments at the start of `text`.
fn leading_layout(text: &str) -> usize {
    let mut rest = text;
    loop {
        let trimmed = rest.trim_start();
        if let Some(comment) = trimmed.strip_prefix('%') {
            rest = comment.find('\n').map_or("", |i| &comment[i..]);
        } else {
            return text.len() - trimmed.len();
        }
    }
}

/// When `text` starts with white space (no comment) then a plain atom
/// (`[a-z][A-Za-z0-9_]*`, not an operator) and an end token (`.` then
/// white space or the end of the text): the atom and the offset where the
/// term reader's clause ends. Such an input is most of a scripted run; the
/// term reader gives the same atom (tested against it below).
fn plain_atom(text: &str, ops: &OpTable) -> Option<(Atom, usize)> {
    let (start, end) = plain_atom_at(text)?;
    Some((not_op(Atom::intern(&text[start..end]), ops)?, end + 1))
}

/// Where [`plain_atom`]'s atom is in `text` (its first byte and the byte
/// after it, the end token's `.`), its operator not checked.
#[inline]
fn plain_atom_at(text: &str) -> Option<(usize, usize)> {
    let bytes = text.as_bytes();
    let start = bytes.iter().position(|b| !b.is_ascii_whitespace())?;
    if !bytes[start].is_ascii_lowercase() {
        return None;
    }
    let len = bytes[start..]
        .iter()
        .position(|b| !(b.is_ascii_alphanumeric() || *b == b'_'))?;
    let end = start + len;
    if bytes[end] != b'.' || !bytes.get(end + 1).is_none_or(|b| b.is_ascii_whitespace()) {
        return None;
    }
    Some((start, end))
}

/// One input of a script: a plain atom (read without the term reader) or
/// a clause.
enum ScriptInput {
    Atom(Atom),
    Clause(sitlog_syntax::Clause),
}

impl ScriptPerception {
    /// [`ScriptPerception::next_input`]'s plain atom, read past, where the
    /// script is given whole (nothing more to read into `text`): the same
    /// atom and position, without the clause-sized result; `None`
    /// (nothing read) for anything else.
    #[inline]
    fn next_plain_atom(&mut self) -> Option<Atom> {
        if self.source.is_some() || !self.atoms_fast {
            return None;
        }
        let rest = &self.text[self.pos..];
        let (start, end) = plain_atom_at(rest)?;
        if end + 1 > self.limits.max_bytes {
            return None;
        }
        let atom = self.recent.atom(rest, start, end)?;
        self.pos += end + 1;
        Some(atom)
    }

    /// The next input and the offsets in `text` of its text (`None` at
    /// the end of the script); past it once read.
    fn next_input(&mut self) -> Result<Option<(ScriptInput, usize, usize)>, String> {
        self.fill()?;
        let ops = OpTable::sitlog_shared();
        let rest = &self.text[self.pos..];
        if self.atoms_fast {
            // `plain_atom`, a word read lately looked up in `recent`.
            let plain = plain_atom_at(rest)
                .and_then(|(start, end)| Some((self.recent.atom(rest, start, end)?, end + 1)));
            if let Some((name, end)) = plain {
                if end <= self.limits.max_bytes {
                    let start = self.pos;
                    self.pos += end;
                    return Ok(Some((ScriptInput::Atom(name), start, self.pos)));
                }
            }
        }
        // One input is read from at most max_bytes (+1 to tell a clause
        // that ends exactly there): a longer one is incomplete, then refused.
        let mut cut = rest.len().min(self.limits.max_bytes.saturating_add(1));
        while !rest.is_char_boundary(cut) {
            cut -= 1;
        }
        let truncated = cut < rest.len();
        let mut reader = ClauseReader::new(&rest[..cut], ops).with_max_depth(self.limits.max_depth);
        let what = || {
            let (line, col) = sitlog_syntax::line_col(&self.text, self.pos + leading_layout(rest));
            let line = line + self.dropped_lines;
            format!("{}:{line}:{col}: the input", self.name)
        };
        match reader.next_clause() {
            None if truncated => Err(self.limits.size_error(&what(), cut)),
            None => Ok(None),
            Some(Err(e)) if truncated && (e.incomplete || reader.position() >= cut) => {
                Err(self.limits.size_error(&what(), cut))
            }
            Some(Err(e)) if e.is_too_deep() => Err(self.limits.depth_error(&what())),
            Some(Ok(clause)) => {
                let start = self.pos + leading_layout(rest);
                self.pos += reader.position();
                Ok(Some((ScriptInput::Clause(clause), start, self.pos)))
            }
            Some(Err(e)) => {
                let (line, col) =
                    sitlog_syntax::line_col(&self.text, self.pos + e.span.start as usize);
                let line = line + self.dropped_lines;
                Err(format!(
                    "{}:{line}:{col}: syntax error in input: {}",
                    self.name, e.message
                ))
            }
        }
    }
}

impl Perception for ScriptPerception {
    fn perceive(
        &mut self,
        store: &mut Store,
        ty: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        let percept = self.perceive_percept(store, ty, expectations)?;
        Ok(percept.into_perceived(store))
    }

    /// The script's next input, `said(Input)` (D-14) not built.
    fn perceive_percept(
        &mut self,
        store: &mut Store,
        ty: Term,
        _expectations: &[Term],
    ) -> Result<Percept, String> {
        let t = match self.next_plain_atom() {
            Some(a) => Term::atom(a),
            None => match self.next_input()? {
                None => return Ok(Percept::Whole(Perceived::EndOfInput)),
                Some((ScriptInput::Atom(a), _, _)) => Term::atom(a),
                Some((ScriptInput::Clause(clause), _, _)) => store.from_clause(&clause).0,
            },
        };
        if self.echo {
            crate::errln!("input: {}", store.writeq(t));
        }
        Ok(deliver_percept(store, ty, t))
    }

    /// A script line that meets no expectation is worth a warning.
    fn unmatched_is_news(&self) -> bool {
        true
    }

    /// A script is not told where it is read.
    fn uses_waiting_at(&self) -> bool {
        false
    }
}

/// Prolog's `read/1` takes the script's next input (issue 39).
impl TermInput for ScriptPerception {
    fn next_term_text(&mut self) -> Result<Option<String>, String> {
        let Some((_, start, end)) = self.next_input()? else {
            return Ok(None);
        };
        let text = self.text[start..end].to_owned();
        if self.echo {
            crate::errln!("input: {}", text.trim().trim_end_matches('.'));
        }
        Ok(Some(text))
    }
}

/// Prolog's `read/1` takes the next term typed (issue 39).
impl<R: BufRead + Send> TermInput for PromptPerception<R> {
    fn next_term_text(&mut self) -> Result<Option<String>, String> {
        self.read_term_text()
    }
}

/// A perception shared with the run's Prolog engine: the perception
/// perceives through it, and [`SharedPerception::input`] gives the engine
/// the same reader (one input, read in order by both).
pub struct SharedPerception<P: Perception + TermInput + 'static> {
    inner: std::sync::Arc<std::sync::Mutex<P>>,
}

impl<P: Perception + TermInput + 'static> SharedPerception<P> {
    pub fn new(perception: P) -> Self {
        SharedPerception {
            inner: std::sync::Arc::new(std::sync::Mutex::new(perception)),
        }
    }

    /// The reader the engine's `read/1` takes terms from.
    pub fn input(&self) -> SharedInput {
        self.inner.clone()
    }
}

impl<P: Perception + TermInput + 'static> Perception for SharedPerception<P> {
    fn perceive(
        &mut self,
        store: &mut Store,
        ty: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        match self.inner.lock() {
            Ok(mut p) => p.perceive(store, ty, expectations),
            Err(_) => Err("the input's reader failed earlier (poisoned)".to_owned()),
        }
    }

    fn perceive_percept(
        &mut self,
        store: &mut Store,
        ty: Term,
        expectations: &[Term],
    ) -> Result<Percept, String> {
        match self.inner.lock() {
            Ok(mut p) => p.perceive_percept(store, ty, expectations),
            Err(_) => Err("the input's reader failed earlier (poisoned)".to_owned()),
        }
    }

    fn waiting_at(&mut self, store: &Store, dm: Term, situation: Term) {
        if let Ok(mut p) = self.inner.lock() {
            p.waiting_at(store, dm, situation);
        }
    }

    fn unmatched_is_news(&self) -> bool {
        self.inner.lock().is_ok_and(|p| p.unmatched_is_news())
    }

    fn uses_waiting_at(&self) -> bool {
        self.inner.lock().map_or(true, |p| p.uses_waiting_at())
    }
}

/// The line a prompt shows before it reads: the DM and situation waiting
/// (when known), the situation's type and its expectations, e.g.
/// `DM main, situation ask (listening) expects: said(go) | said(stop)`.
pub fn prompt_header(
    store: &Store,
    at: Option<&(String, String)>,
    ty: Term,
    expectations: &[Term],
) -> String {
    let list: Vec<String> = expectations.iter().map(|&e| store.writeq(e)).collect();
    let ty = store.writeq(ty);
    match at {
        Some((dm, situation)) => format!(
            "DM {dm}, situation {situation} ({ty}) expects: {}",
            list.join(" | ")
        ),
        None => format!("[{ty}] expectations: {}", list.join(" | ")),
    }
}

/// What [`Perception::waiting_at`] tells a prompt: the DM's name (its call
/// term's functor) and the situation's id, as text.
pub fn waiting_text(store: &Store, dm: Term, situation: Term) -> (String, String) {
    let dm = match store.functor(dm) {
        Some((name, _)) => {
            let mut text = String::new();
            sitlog_syntax::write::write_atom(&mut text, name, true);
            text
        }
        None => store.writeq(dm),
    };
    (dm, store.writeq(situation))
}

/// Renders actions as text, like the original's test mode: `screen(M)` and
/// `say(M)` are shown, other declared basic actions are listed, and unknown
/// actions do nothing (as in the original).
pub struct TextActions<W: Write> {
    out: W,
    declared: Vec<Atom>,
    unbound_screen: Option<(Atom, String)>,
    /// `say` and `screen`, interned once: an action's name is compared as
    /// an atom (its text is a thread-local table look-up, twice an action).
    say: Atom,
    screen: Atom,
    /// The line written, reused from action to action (no allocation
    /// once it is as long as the longest line).
    line: String,
    /// The lines of `say` patterns, planned once (`said`).
    plans: said::Plans,
}

impl<W: Write> TextActions<W> {
    pub fn new(out: W, declared: Vec<Atom>) -> Self {
        TextActions {
            out,
            declared,
            unbound_screen: None,
            say: Atom::intern("say"),
            screen: Atom::intern("screen"),
            line: String::new(),
            plans: said::Plans::default(),
        }
    }

    /// `screen(X)` with `X` unbound as the original performs it (`sitlogc
    /// run --legacy`): its `screen([A|Rest])` service clause matches, and
    /// its message formatter takes the application's first `caption(Id,
    /// Text)` fact, so `X` becomes `[caption(Id)]` and `Text` is shown.
    /// `caption` is that fact's `(Id, Text)`; `None` leaves `X` unbound.
    pub fn with_unbound_screen(mut self, caption: Option<(String, String)>) -> Self {
        self.unbound_screen = caption.map(|(id, text)| (Atom::intern(&id), text));
        self
    }

    /// Writes the line of action `a` (`name/1` `say` or `screen`, or
    /// another), seen through `src`, where it is shown: built in one
    /// reused buffer, written at once.
    fn show(
        &mut self,
        src: &crate::sentence::Holed<'_>,
        a: Term,
        name: Atom,
        say: bool,
        screen: bool,
    ) {
        let line = &mut self.line;
        line.clear();
        // The argument of `say/1` or `screen/1`, seen (a hole its value).
        let arg = || src.parts(a).and_then(|(_, args)| args.get(0));
        match (say, screen) {
            (_, true) => {
                line.push_str("Golem prints on screen: ");
                if let Some(m) = arg() {
                    crate::sentence::write_seen(src, m, line);
                }
            }
            (true, _) => {
                // A message given as a list is said as one sentence (the
                // original's msg_format/2).
                line.push_str("Golem says: ");
                if let Some(m) = arg() {
                    crate::sentence::message_seen(src, m, line);
                }
            }
            _ if self.declared.contains(&name) => {
                line.push_str("Golem does: ");
                let options = sitlog_syntax::write::WriteOptions::writeq();
                line.push_str(&sitlog_syntax::write::write_term(src, a, options));
            }
            _ => return,
        }
        line.push('\n');
        let _ = self.out.write_all(line.as_bytes());
    }
}

impl<W: Write> Actions for TextActions<W> {
    fn perform(&mut self, store: &mut Store, action: Term) -> Result<(), String> {
        let a = store.deref(action);
        let Some((name, arity)) = store.functor(a) else {
            return Ok(());
        };
        let (say, screen) = (
            name == self.say && arity == 1,
            name == self.screen && arity == 1,
        );
        if let (true, Some((id, text))) = (screen, &self.unbound_screen) {
            let x = store.args(a)[0];
            if store.is_var(x) {
                let caption = store.compound(Atom::intern("caption"), &[Term::atom(*id)]);
                let list = store.compound(sitlog_syntax::atoms::DOT, &[caption, Term::NIL]);
                store.bind(x, list);
                let _ = writeln!(self.out, "Golem prints on screen: {text}");
                return Ok(());
            }
        }
        self.show(&crate::sentence::Holed::plain(store), a, name, say, screen);
        Ok(())
    }

    /// The same line as [`TextActions::perform`] of the term filled, from
    /// the pattern and its holes (`Holed`); `None` where `perform` would
    /// bind a variable (an unbound `screen(X)` shown by its caption).
    fn perform_filled(
        &mut self,
        store: &mut Store,
        pattern: Term,
        holes: &[Term],
    ) -> Option<Result<(), String>> {
        if !store.is_holed(pattern) {
            // Not a pattern read as a program's constant is.
            return None;
        }
        let src = crate::sentence::Holed::new(store, holes);
        // A compound marked; an action that is a hole itself (its value
        // an atom or a number) is left to `perform`.
        let a = store.deref(pattern);
        let (name, args) = src.parts(a)?;
        if name == crate::machine::hole_atom() && args.len() == 1 {
            return None;
        }
        let (say, screen) = (
            name == self.say && args.len() == 1,
            name == self.screen && args.len() == 1,
        );
        if screen && self.unbound_screen.is_some() && args.get(0).is_some_and(|x| store.is_var(x)) {
            return None;
        }
        if say {
            self.line.clear();
            if self.plans.write(store, a, holes, &mut self.line) {
                let _ = self.out.write_all(self.line.as_bytes());
                return Some(Ok(()));
            }
        }
        self.show(&src, a, name, say, screen);
        Some(Ok(()))
    }

    /// What [`TextActions::perform`] shows: `say/1`, `screen/1` and the
    /// declared basic actions (any arity; `empty` too, when declared); the
    /// rest does nothing. A number has no functor: nothing to show.
    fn ignores(&self, shape: ActionShape) -> bool {
        match shape {
            ActionShape::Number => true,
            ActionShape::Named(name, arity) => {
                let shown = arity == 1 && (name == self.say || name == self.screen);
                !shown && !self.declared.contains(&name)
            }
        }
    }
}

#[cfg(test)]
mod tests;
