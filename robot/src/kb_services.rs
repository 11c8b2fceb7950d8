//! The knowledge base's services as SitLog user functions. The runtime does
//! not know the KB (it never depends on `kb`): whoever assembles a program
//! registers these. A query service `s(A1..An, Answer)` becomes the function
//! `s/n`: `apply(object_property_value(I, P), [pete, lives])` gives the
//! answer, or `false` where the original's call fails. An update
//! `u(A1..An)` becomes `u/n` and gives `true` or `false`; with a
//! persistence path, every successful update is written to disk atomically.
//! `open` finds the KB of a run (`--kb FILE`, `--kb-persist`, or the
//! application's `knowledge.kb`).

use crate::assets::TextFile;
use crate::console::SharedConsole;
use sitlog_kb::{Kb, Outcome, PersistLock, SERVICES, UPDATES};
use sitlog_runtime::functions::FnCall;
use sitlog_runtime::{Atom, Functions, Term};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// The KB of a run.
pub(crate) struct RunKb {
    pub(crate) kb: Kb,
    /// Where every successful update is written back (`--kb-persist`).
    pub(crate) persist: Option<PathBuf>,
    /// With `--kb-persist`: held for the whole run, so that no other
    /// persisting process writes the file meanwhile (and temporary files
    /// of killed runs are removed).
    pub(crate) lock: Option<PersistLock>,
}

/// The KB of a run: the file `file` (`--kb`), else the application's
/// `asset`; with `persist` (`--kb-persist`), `file` is locked and written
/// back. `Err` holds the exit status (1 for bad content, 2 for I/O or a
/// `--kb-persist` without a file) and the message.
pub(crate) fn open(
    file: Option<&Path>,
    persist: bool,
    asset: Option<&TextFile>,
) -> Result<Option<RunKb>, (u8, String)> {
    // A position means bad content (1); none, a file that cannot be read (2).
    let failed = |e: sitlog_kb::LoadError| (if e.pos.is_some() { 1 } else { 2 }, e.to_string());
    let found = match file {
        Some(path) if persist => {
            let (kb, lock) = Kb::open_persistent(path).map_err(failed)?;
            Some(RunKb {
                kb,
                // the real file, resolved once when locked
                persist: Some(lock.path().to_path_buf()),
                lock: Some(lock),
            })
        }
        Some(path) => Some(RunKb {
            kb: Kb::load(path).map_err(failed)?,
            persist: None,
            lock: None,
        }),
        None => match asset {
            Some(src) => Some(RunKb {
                kb: Kb::parse(&src.text, &src.name).map_err(|e| (1, e.to_string()))?,
                persist: None,
                lock: None,
            }),
            None => None,
        },
    };
    if persist && found.as_ref().is_none_or(|k| k.persist.is_none()) {
        return Err((
            2,
            "error: --kb-persist needs a KB file to write to: pass --kb FILE".to_owned(),
        ));
    }
    Ok(found)
}

/// A KB shared by the registered functions.
pub type SharedKb = Arc<Mutex<Kb>>;

fn call_text(call: &FnCall<'_>, name: &str, args: &[Term], answer: bool) -> String {
    let mut parts: Vec<String> = args.iter().map(|&a| call.store.writeq(a)).collect();
    if answer {
        parts.push("Answer".to_owned());
    }
    let mut f = String::new();
    sitlog_syntax::write::write_atom(&mut f, Atom::intern(name), true);
    format!("{f}({})", parts.join(","))
}

/// Registers every KB query and update service in `functions`.
pub fn register(functions: &mut Functions, kb: SharedKb, persist: Option<PathBuf>) {
    register_with(functions, kb, persist, None)
}

/// [`register`], narrating every update that changes the KB on `console`
/// (`KB: add_object_property(user,tired,yes)`).
pub fn register_with(
    functions: &mut Functions,
    kb: SharedKb,
    persist: Option<PathBuf>,
    console: Option<SharedConsole>,
) {
    for service in SERVICES {
        let kb = kb.clone();
        let name = service.name;
        functions.register(name, service.arity - 1, move |call, args| {
            let text = call_text(call, name, args, true);
            let kb = kb
                .lock()
                .map_err(|_| "the KB is unusable after an earlier panic".to_owned())?;
            let line = match kb.query(&text).map_err(|e| format!("{text}: {e}"))? {
                Outcome::Answer(a) => a.writeq(),
                Outcome::Fails => "false".to_owned(),
            };
            Ok(call.store.parse(&line).map_err(|e| e.message)?.0)
        });
    }
    for update in UPDATES {
        let kb = kb.clone();
        let persist = persist.clone();
        let name = update.name;
        let console = console.clone();
        functions.register(name, update.arity, move |call, args| {
            let text = call_text(call, name, args, false);
            let mut kb = kb
                .lock()
                .map_err(|_| "the KB is unusable after an earlier panic".to_owned())?;
            let clause =
                sitlog_syntax::read_term(&text).map_err(|e| format!("{text}: {}", e.message))?;
            let changed = match &persist {
                Some(path) => kb
                    .update_persist(&clause, path)
                    .map_err(|e| format!("{text}: {e}"))?
                    .map_err(|e| format!("{text}: {e}"))?,
                None => kb.update(&clause).map_err(|e| format!("{text}: {e}"))?,
            };
            if changed {
                if let Some(console) = &console {
                    if let Ok(mut c) = console.lock() {
                        c.narrate(&format!("KB: {text}"));
                    }
                }
            }
            Ok(Term::atom(if changed {
                sitlog_syntax::atoms::TRUE
            } else {
                sitlog_syntax::atoms::FALSE
            }))
        });
    }
}
