//! The knowledge base's services as SitLog user functions. The runtime does
//! not know the KB (it never depends on `kb`): whoever assembles a program
//! registers these. A query service `s(A1..An, Answer)` becomes the function
//! `s/n`: `apply(object_property_value(I, P), [pete, lives])` gives the
//! answer, or `false` where the original's call fails. An update
//! `u(A1..An)` becomes `u/n` and gives `true` or `false`; with a
//! persistence path, every successful update is written to disk atomically.

use crate::console::SharedConsole;
use sitlog_kb::{Kb, Outcome, SERVICES, UPDATES};
use sitlog_runtime::functions::FnCall;
use sitlog_runtime::{Atom, Functions, Term};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

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
