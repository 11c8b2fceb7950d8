//! Hot reload for `sitlogc run APP --watch`: the application's files are
//! watched (the `notify` crate, debounced); on a change the program is read
//! and checked again on a thread of its own, and the run takes the new
//! program between two transitions, at the same DM and situation id,
//! keeping its stack, pipe, variables and history.
//!
//! Owns: [`Watched`], the running program that can change (a
//! [`DmProgram`] over the IR it started with, then over each new IR), the
//! watcher thread ([`Watched::watch`]) and [`ReloadAware`], the perception
//! that lets a situation waiting for input take it in the new program.
//!
//! Invariants:
//! - DM indices given to the machine are stable across reloads (one per DM
//!   name); a reload that removes a DM on the stack, or the situation the
//!   run is about to enter, stops the run with a message saying so.
//! - The run's store starts from the first IR's frozen store; every later
//!   IR keeps its own store, and its templates are copied into the run's
//!   store term by term ([`copy_across`]), so nothing of the run refers
//!   into an IR that may be dropped.
//! - A program that does not check never reaches the run: its diagnostics
//!   are printed and the old program goes on.

use sitlog_compiler::ir::Ir;
use sitlog_runtime::machine::{
    Between, DmIx, DmProgram, Instance, Kind, Next, Perceived, Perception, RunError, SitIx,
};
use sitlog_runtime::{app::App, Atom, Store, Term, Value, Var, Vars};
use std::collections::HashMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// How long the files must be quiet after a change before the program is
/// read again (editors write a file in several steps).
pub const DEBOUNCE: Duration = Duration::from_millis(200);

/// Where the messages of a watched run go (stderr in `sitlogc run`).
pub type Messages = Arc<Mutex<Box<dyn Write + Send>>>;

/// A new program, checked, waiting to be taken by the run.
struct Update {
    ir: Arc<Ir>,
    /// What changed, for the message (file names).
    changed: String,
}

/// The program of a watched run: the IR it started with, then each new one
/// that checks. See the module documentation.
pub struct Watched {
    state: Mutex<State>,
    /// Set while a checked new program waits to be taken.
    ready: Arc<AtomicBool>,
    messages: Messages,
}

struct State {
    /// The IR the run started with: its store is the base of the run's.
    base: Arc<Ir>,
    current: Arc<Ir>,
    /// DM names by stable index, and each one's index in `current`.
    names: Vec<Atom>,
    map: Vec<Option<u32>>,
    updates: mpsc::Receiver<Update>,
    sender: mpsc::Sender<Update>,
    /// The Prolog files of `current` (name, text), to tell when the Prolog
    /// user functions must be loaded again.
    prolog: Vec<(String, String)>,
}

impl State {
    fn cross(&self) -> bool {
        !Arc::ptr_eq(&self.base, &self.current)
    }

    /// `dm`'s index in the current IR. A DM given to the machine stays in
    /// the program while the machine can use it (see [`Watched::between`]).
    fn ix(&self, dm: DmIx) -> usize {
        self.map.get(dm as usize).copied().flatten().unwrap_or(0) as usize
    }

    fn copy(&self, t: Term, store: &mut Store, vars: &mut HashMap<Var, Term>) -> Term {
        if self.cross() {
            copy_across(&self.current.store, t, store, vars)
        } else {
            store.copy_term(t)
        }
    }

    fn instantiate(&self, ix: usize, sit: SitIx, store: &mut Store) -> Instance {
        let template = self.current.dms[ix].situations[sit as usize].template;
        let t = self.copy(template, store, &mut HashMap::new());
        sitlog_compiler::instantiate::instance_of(store, t)
    }
}

fn prolog_texts(ir: &Ir) -> Vec<(String, String)> {
    ir.prolog_sources
        .iter()
        .map(|f| (f.name.clone(), f.text.clone()))
        .collect()
}

impl Watched {
    /// The program `ir`, whose messages (reloads, diagnostics) go to `messages`.
    pub fn new(ir: Ir, messages: Messages) -> Watched {
        let ir = Arc::new(ir);
        let (sender, updates) = mpsc::channel();
        Watched {
            state: Mutex::new(State {
                base: ir.clone(),
                prolog: prolog_texts(&ir),
                current: ir,
                names: Vec::new(),
                map: Vec::new(),
                updates,
                sender,
            }),
            ready: Arc::new(AtomicBool::new(false)),
            messages,
        }
    }

    fn state(&self) -> std::sync::MutexGuard<'_, State> {
        // A panic elsewhere cannot leave the state half-changed: keep going.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn say(&self, text: &str) {
        let mut out = self.messages.lock().unwrap_or_else(|e| e.into_inner());
        let _ = writeln!(out, "{text}");
        let _ = out.flush();
    }

    /// Set while a checked new program waits to be taken (for [`ReloadAware`]).
    pub fn ready_flag(&self) -> Arc<AtomicBool> {
        self.ready.clone()
    }

    /// Hands a checked new program to the run (the watcher thread does
    /// this; tests may too). `changed` names what changed.
    pub fn offer(&self, ir: Ir, changed: &str) {
        offer(&self.state().sender, &self.ready, ir, changed);
    }

    /// Starts watching the files of the application at `app` (a directory
    /// or a DM file; `files` are its source files, some maybe outside it).
    /// On each change, after [`DEBOUNCE`], the application is read and
    /// checked with `options`; a program that checks is offered to the run,
    /// otherwise its diagnostics are printed. The watcher stops with the
    /// process. `Err` when the files cannot be watched.
    pub fn watch(
        &self,
        app: &Path,
        files: &[PathBuf],
        options: sitlog_compiler::check::CheckOptions,
        color: bool,
    ) -> Result<(), String> {
        use notify::{RecursiveMode, Watcher};
        let (tx, rx) = mpsc::channel();
        let mut watcher = notify::recommended_watcher(tx)
            .map_err(|e| format!("cannot watch {}: {e}", app.display()))?;
        let root = if app.is_dir() {
            app.to_path_buf()
        } else {
            app.parent()
                .map(Path::to_path_buf)
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or_else(|| PathBuf::from("."))
        };
        let mode = if app.is_dir() {
            RecursiveMode::Recursive
        } else {
            RecursiveMode::NonRecursive
        };
        watcher
            .watch(&root, mode)
            .map_err(|e| format!("cannot watch {}: {e}", root.display()))?;
        let root_abs = std::fs::canonicalize(&root).unwrap_or_else(|_| root.clone());
        // Files outside the application directory (`models` may name them):
        // their directories, not recursively.
        let mut dirs: Vec<PathBuf> = Vec::new();
        for f in files {
            let abs = std::fs::canonicalize(f).unwrap_or_else(|_| f.clone());
            if let Some(dir) = abs.parent() {
                if !dir.starts_with(&root_abs) && !dirs.iter().any(|d| d == dir) {
                    dirs.push(dir.to_path_buf());
                }
            }
        }
        for d in &dirs {
            let _ = watcher.watch(d, RecursiveMode::NonRecursive);
        }
        let sender = self.state().sender.clone();
        let ready = self.ready.clone();
        let messages = self.messages.clone();
        let app = app.to_path_buf();
        let sources: Vec<PathBuf> = files
            .iter()
            .map(|f| std::fs::canonicalize(f).unwrap_or_else(|_| f.clone()))
            .collect();
        std::thread::Builder::new()
            .name("sitlog-watch".into())
            .spawn(move || {
                // The watcher lives as long as this thread.
                let _watcher = watcher;
                let relevant = |p: &Path| {
                    let abs = std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
                    sources.contains(&abs) || is_source_name(p)
                };
                let say = |text: &str| {
                    let mut out = messages.lock().unwrap_or_else(|e| e.into_inner());
                    let _ = out.write_all(text.as_bytes());
                    let _ = out.flush();
                };
                loop {
                    // Wait for a change to a source file, then for quiet.
                    let mut changed: Vec<String> = Vec::new();
                    let note = |ev: notify::Result<notify::Event>, changed: &mut Vec<String>| {
                        if let Ok(ev) = ev {
                            if matches!(ev.kind, notify::EventKind::Access(_)) {
                                return;
                            }
                            for p in ev.paths.iter().filter(|p| relevant(p)) {
                                let name = p
                                    .file_name()
                                    .map(|n| n.to_string_lossy().into_owned())
                                    .unwrap_or_default();
                                if !changed.contains(&name) {
                                    changed.push(name);
                                }
                            }
                        }
                    };
                    match rx.recv() {
                        Ok(ev) => note(ev, &mut changed),
                        Err(_) => return,
                    }
                    if changed.is_empty() {
                        continue;
                    }
                    loop {
                        match rx.recv_timeout(DEBOUNCE) {
                            Ok(ev) => note(ev, &mut changed),
                            Err(mpsc::RecvTimeoutError::Timeout) => break,
                            Err(mpsc::RecvTimeoutError::Disconnected) => return,
                        }
                    }
                    let changed = changed.join(", ");
                    match reload(&app, options, color) {
                        Ok(ir) => {
                            // Offered before it is said, so that input
                            // typed after the message goes to the new program.
                            offer(&sender, &ready, ir, &changed);
                            say(&format!(
                                "watch: {changed} changed; the program checks: the run takes it at its next transition\n"
                            ));
                        }
                        Err(text) => say(&format!(
                            "{text}watch: {changed} changed, but the program does not check: the run goes on in the program it has\n"
                        )),
                    }
                }
            })
            .map_err(|e| format!("cannot start the watcher: {e}"))?;
        Ok(())
    }
}

fn offer(sender: &mpsc::Sender<Update>, ready: &AtomicBool, ir: Ir, changed: &str) {
    let update = Update {
        ir: Arc::new(ir),
        changed: changed.to_owned(),
    };
    if sender.send(update).is_ok() {
        ready.store(true, Ordering::SeqCst);
    }
}

/// Whether a file of this name is part of an application.
fn is_source_name(p: &Path) -> bool {
    let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
    let ext = p.extension().map(|e| e.to_string_lossy().into_owned());
    matches!(ext.as_deref(), Some("dm") | Some("pl")) || name.as_deref() == Some("models")
}

/// Reads and checks the application again: the IR, or the rendered
/// diagnostics (errors only).
fn reload(
    app: &Path,
    options: sitlog_compiler::check::CheckOptions,
    color: bool,
) -> Result<Ir, String> {
    let (result, diags) = match crate::output::check_app(app, options) {
        Ok(r) => r,
        Err(e) => return Err(format!("error: cannot read {e}\n")),
    };
    let sources = match &result {
        Ok(c) => &c.program().sources,
        Err(p) => &p.sources,
    };
    let mut text = String::new();
    for d in diags.iter().filter(|d| d.is_error()) {
        text.push_str(&sitlog_compiler::diag::render_human(d, sources, color));
    }
    match result {
        Ok(c) => Ok(sitlog_compiler::ir::lower(&c)),
        Err(_) => Err(text),
    }
}

/// A copy of `t`, a term of `from`, in `to`: every variable of `t` becomes
/// a fresh one of `to` (through `vars`, so that several copies can share
/// them). Iterative: deep terms need no stack.
pub fn copy_across(from: &Store, t: Term, to: &mut Store, vars: &mut HashMap<Var, Term>) -> Term {
    enum Work {
        Visit(Term),
        Build(Atom, usize),
    }
    let mut work = vec![Work::Visit(t)];
    let mut done: Vec<Term> = Vec::new();
    while let Some(w) = work.pop() {
        match w {
            Work::Build(name, n) => {
                let base = done.len() - n;
                let built = to.compound(name, &done[base..]);
                done.truncate(base);
                done.push(built);
            }
            Work::Visit(t) => match from.value(t) {
                Value::Var(v) => {
                    let image = *vars.entry(v).or_insert_with(|| to.new_var());
                    done.push(image);
                }
                Value::Atom(a) => done.push(Term::atom(a)),
                Value::Int(i) => done.push(Term::int(i)),
                Value::Float(f) => done.push(Term::float(f)),
                Value::BigInt(text) => done.push(
                    to.integer_from_text(text)
                        .unwrap_or_else(|| Term::atom(Atom::intern(text))),
                ),
                Value::Compound(name, args) => {
                    work.push(Work::Build(name, args.len()));
                    work.extend(args.iter().rev().map(|&a| Work::Visit(a)));
                }
            },
        }
    }
    done.pop().unwrap_or(t)
}

impl DmProgram for Watched {
    fn dm_by_name(&self, name: Atom) -> Option<DmIx> {
        let mut s = self.state();
        let ix = s.current.dm_by_name(name)?;
        let stable = match s.names.iter().position(|&n| n == name) {
            Some(i) => i,
            None => {
                s.names.push(name);
                s.map.push(Some(ix));
                s.names.len() - 1
            }
        };
        Some(stable as DmIx)
    }
    fn dm_name(&self, dm: DmIx) -> Atom {
        self.state().names[dm as usize]
    }
    fn situation_count(&self, dm: DmIx) -> usize {
        let s = self.state();
        s.current.dms[s.ix(dm)].situations.len()
    }
    fn kind(&self, dm: DmIx, sit: SitIx) -> Kind {
        let s = self.state();
        s.current.dms[s.ix(dm)].situations[sit as usize].kind
    }
    fn fresh_head(&self, dm: DmIx, store: &mut Store) -> Term {
        let s = self.state();
        let head = s.current.dms[s.ix(dm)].head;
        s.copy(head, store, &mut HashMap::new())
    }
    fn instantiate(&self, dm: DmIx, sit: SitIx, store: &mut Store) -> Option<Instance> {
        let s = self.state();
        Some(s.instantiate(s.ix(dm), sit, store))
    }
    fn may_select(&self, dm: DmIx, sit: SitIx, value: Term, store: &Store) -> bool {
        let s = self.state();
        match s.current.dms[s.ix(dm)].situations[sit as usize].id_functor {
            Some(f) => store.functor(value) == Some(f),
            None => true,
        }
    }
    fn locals(&self, dm: DmIx, store: &mut Store) -> Vars {
        let s = self.state();
        let locals = &s.current.dms[s.ix(dm)].locals;
        let entries = locals
            .iter()
            .map(|&(n, v)| (n, s.copy(v, store, &mut HashMap::new())))
            .collect();
        Vars::from_entries(entries)
    }
    fn location(&self, dm: DmIx, sit: SitIx) -> Option<String> {
        let s = self.state();
        let dm = s.current.dms.get(s.ix(dm))?;
        dm.situations.get(sit as usize).map(|x| x.location.clone())
    }
    fn in_arg_location(&self, dm: DmIx, sit: SitIx) -> Option<String> {
        let s = self.state();
        let dm = s.current.dms.get(s.ix(dm))?;
        dm.situations.get(sit as usize)?.in_arg_location.clone()
    }
    fn between(&self, at: &mut Between<'_>) -> Result<(), String> {
        if !self.ready.load(Ordering::Relaxed) {
            return Ok(());
        }
        // Cleared first: an offer made meanwhile sets it again.
        self.ready.store(false, Ordering::SeqCst);
        let mut s = self.state();
        // The newest offer wins.
        let mut update = None;
        while let Ok(u) = s.updates.try_recv() {
            update = Some(u);
        }
        let Some(update) = update else {
            return Ok(());
        };
        let new = update.ir;
        // Every DM on the stack must still be there.
        let mut new_ix = Vec::with_capacity(at.depth());
        for i in 0..at.depth() {
            let (dm, call) = at.dm(i);
            let name = s.names[dm as usize];
            match new.dm_by_name(name) {
                Some(ix) => new_ix.push(ix as usize),
                None => {
                    return Err(format!(
                        "{} changed and DM `{name}`, on the DM stack (called as `{}`), is no longer in the program: the run cannot go on in the new program",
                        update.changed,
                        at.store.writeq(call)
                    ))
                }
            }
        }
        let top = *new_ix.last().unwrap_or(&0);
        let top_dm = &new.dms[top];
        let cross_new = !Arc::ptr_eq(&s.base, &new);
        let template_id = |store: &mut Store, sit: usize| -> Term {
            let t = top_dm.situations[sit].template;
            let copy = if cross_new {
                copy_across(&new.store, t, store, &mut HashMap::new())
            } else {
                store.copy_term(t)
            };
            store.args(copy)[1]
        };
        // The situation the run enters next must still be there.
        let (where_, found) = match at.next {
            Next::Initial => (
                "its initial situation".to_owned(),
                !top_dm.situations.is_empty(),
            ),
            Next::Index(sit) => (
                format!("situation number {sit}"),
                (sit as usize) < top_dm.situations.len(),
            ),
            Next::Situation(value) => {
                let text = format!("situation `{}`", at.store.writeq(value));
                let value_f = at.store.functor(at.store.deref(value));
                let mut found = false;
                for (i, sit) in top_dm.situations.iter().enumerate() {
                    if sit.id_functor.is_some_and(|f| Some(f) != value_f) {
                        continue;
                    }
                    let mark = at.store.mark();
                    let id = template_id(at.store, i);
                    found = at.store.unify(id, value);
                    at.store.undo_to(mark);
                    if found {
                        break;
                    }
                }
                (text, found)
            }
        };
        let dm_name = top_dm.name;
        if !found {
            return Err(format!(
                "{} changed and {where_} of DM `{dm_name}`, where the run is, is no longer in the program: the run cannot go on in the new program",
                update.changed
            ));
        }
        // Recursive situations waiting for their embedded DM keep the
        // instance they have; their number follows the new program.
        for (i, &ix) in new_ix.iter().enumerate() {
            let Some(old_sit) = at.waiting_situation(i) else {
                continue;
            };
            let old_dm = &s.current.dms[s.ix(at.dm(i).0)];
            let old_id = old_dm.situations.get(old_sit as usize).map(|x| {
                let copy = s.copy(x.template, at.store, &mut HashMap::new());
                at.store.args(copy)[1]
            });
            let mut renumbered = SitIx::MAX;
            if let Some(old_id) = old_id {
                for (k, sit) in new.dms[ix].situations.iter().enumerate() {
                    let t = if cross_new {
                        copy_across(&new.store, sit.template, at.store, &mut HashMap::new())
                    } else {
                        at.store.copy_term(sit.template)
                    };
                    let id = at.store.args(t)[1];
                    if at.store.variant(id, old_id) {
                        renumbered = k as SitIx;
                        break;
                    }
                }
            }
            at.set_waiting_situation(i, renumbered);
        }
        // Take the new program.
        s.current = new.clone();
        let names = s.names.clone();
        s.map = names.iter().map(|&n| new.dm_by_name(n)).collect();
        // Variables the new program declares and the run does not have yet
        // get their initial values.
        for (i, &ix) in new_ix.iter().enumerate() {
            let dm = &new.dms[ix];
            for &(name, value) in &dm.locals {
                if !at.locals_mut(i).contains(name) {
                    let v = s.copy(value, at.store, &mut HashMap::new());
                    at.locals_mut(i).define(name, v);
                }
            }
        }
        for &(name, value) in &new.globals {
            if !at.globals.contains(name) {
                let v = s.copy(value, at.store, &mut HashMap::new());
                at.globals.define(name, v);
            }
        }
        // Prolog user functions that changed are loaded again.
        {
            let texts = prolog_texts(&new);
            if texts != s.prolog {
                s.prolog = texts;
                // The run has started: the new engine's directives run now.
                let installed =
                    sitlog_compiler::run::install_prolog(&new, at.functions, Default::default())
                        .and_then(|engine| match engine {
                            Some(engine) => engine.start(at.functions.trust()),
                            None => Ok(()),
                        });
                match installed {
                    Ok(()) => {}
                    Err(errors) => {
                        let text: Vec<String> = errors.iter().map(|e| e.to_string()).collect();
                        return Err(format!(
                            "{} changed and its Prolog user functions do not load: {}",
                            update.changed,
                            text.join("; ")
                        ));
                    }
                }
            }
        }
        let at_text = match at.next {
            Next::Situation(v) => format!("situation `{}`", at.store.writeq(v)),
            _ => where_,
        };
        drop(s);
        self.say(&format!(
            "watch: reloaded ({}): the run goes on in the new program at DM `{dm_name}`, {at_text}",
            update.changed
        ));
        Ok(())
    }
}

impl App for Watched {
    fn initial_state(&self) -> (Store, Vars) {
        // Only the first IR's store is the base of the run's store.
        let s = self.state();
        s.base.initial_state()
    }
    fn basic_actions(&self) -> Vec<Atom> {
        self.state().current.basic_actions.clone()
    }
    fn recovery(&self) -> Vec<(Atom, Atom)> {
        self.state().current.recovery.clone()
    }
    fn render_error(&self, error: &RunError, color: bool) -> Option<String> {
        let (ir, error) = self.in_current(error);
        ir.render_error(&error, color)
    }
    fn error_location(&self, error: &RunError) -> Option<String> {
        let (ir, error) = self.in_current(error);
        ir.error_location(&error)
    }
}

impl Watched {
    /// The current IR, and `error` with its DM numbered as in that IR.
    fn in_current(&self, error: &RunError) -> (Arc<Ir>, RunError) {
        let s = self.state();
        let mut error = error.clone();
        if let Some(site) = error.site.as_mut() {
            match s.map.get(site.dm as usize).copied().flatten() {
                Some(ix) => site.dm = ix,
                None => error.site = None,
            }
        }
        (s.current.clone(), error)
    }
}

/// The perception of a watched run: when a checked new program waits while
/// a situation reads its input, the input is kept and the machine is asked
/// to enter the situation again ([`Perceived::Again`]), so that the new
/// program's situation takes it. Without a new program it is `inner`.
pub struct ReloadAware {
    inner: Box<dyn Perception>,
    ready: Arc<AtomicBool>,
    /// The input read before the program changed, as text (a term handle
    /// would not survive a garbage collection).
    held: Option<String>,
}

impl ReloadAware {
    pub fn new(inner: Box<dyn Perception>, ready: Arc<AtomicBool>) -> ReloadAware {
        ReloadAware {
            inner,
            ready,
            held: None,
        }
    }
}

impl Perception for ReloadAware {
    fn perceive(
        &mut self,
        store: &mut Store,
        situation_type: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        if let Some(text) = self.held.take() {
            if let Ok((t, _)) = store.parse(&text) {
                return Ok(Perceived::Input(t));
            }
        }
        let perceived = self.inner.perceive(store, situation_type, expectations)?;
        match perceived {
            Perceived::Input(t) if self.ready.load(Ordering::SeqCst) => {
                self.held = Some(store.writeq(t));
                Ok(Perceived::Again)
            }
            p => Ok(p),
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn copies_across_stores_with_shared_variables() {
        let mut from = Store::new();
        let (t, _) = from
            .parse("f(X, g(X, Y), [1, 2.5, 123456789012345678901234567890], Y)")
            .unwrap();
        let mut to = Store::new();
        let _pad = to.parse("pad(A, B, c)").unwrap();
        let mut vars = HashMap::new();
        let c = copy_across(&from, t, &mut to, &mut vars);
        assert_eq!(vars.len(), 2);
        let text = to.writeq(c);
        assert!(
            text.starts_with("f(_G2,g(_G2,_G3),[1,2.5,123456789012345678901234567890],_G3)"),
            "{text}"
        );
        // Deep terms: no recursion.
        let mut deep = Term::NIL;
        for i in 0..200_000 {
            deep = from.cons(Term::int(i), deep);
        }
        let d = copy_across(&from, deep, &mut to, &mut HashMap::new());
        assert_eq!(to.list_to_vec(d).map(|v| v.len()), Some(200_000));
    }

    #[test]
    fn source_names() {
        assert!(is_source_name(Path::new("a/main.dm")));
        assert!(is_source_name(Path::new("global_vars.pl")));
        assert!(is_source_name(Path::new("x/models")));
        assert!(!is_source_name(Path::new("main.dm.swp")));
        assert!(!is_source_name(Path::new("world.toml")));
    }
}
