//! The legacy profile (`sitlogc run --legacy`): running applications written
//! for the original SitLog interpreter unmodified, from the original's tree
//! (`SITLOG_HOME`).
//!
//! What the original loads before an application: its `src/init.pl`
//! consults the interpreter (files of `src/`, which sitlog-rs replaces) and
//! the Prolog layer the applications call (`:- consult('$SITLOG_HOME/...')`:
//! the KB services, the parser, the cognitive model, diagnosis, decision
//! making and planning). This module finds `SITLOG_HOME` and lists the
//! files of those `$SITLOG_HOME` directives, in order, read from `init.pl`
//! itself; nothing of the original is part of sitlog-rs. The files are then
//! loaded like `user_functions.pl` (our reader, the embedded engine).
//!
//! One profile for both back ends: [`prepare`] applies it to a run
//! (`sitlogc run --legacy`), and a task compiled with `sitlogc build
//! --legacy` compiles this very file into itself (the package's `main.rs`
//! has it as a module: `crate::package`) and calls [`task_setup`] at start.
//! So this file uses only the crates a compiled task links (`sitlog_robot`,
//! `sitlog_runtime` with its `prolog` feature, `sitlog_syntax`,
//! `sitlog_kb`), never `crate::`.

use std::path::{Path, PathBuf};

/// Inferences one Prolog call may make under `--legacy` unless
/// `--prolog-inferences` says otherwise: no limit, as the original (its
/// `rips` task needs more than ten times our default; a runaway call is
/// stopped by the time and memory limits). Without a limit a call does not
/// go through `call_with_inference_limit/3`, whose count (a big-integer
/// compare and add) costs on every inference.
pub const LEGACY_INFERENCES: u64 = sitlog_runtime::prolog::NO_INFERENCE_LIMIT;

/// Wall-clock time of one Prolog call under `--legacy` unless
/// `--prolog-time-limit` says otherwise (the original has no limit).
pub const LEGACY_TIME: std::time::Duration = std::time::Duration::from_secs(300);

/// The limits of one Prolog call under `--legacy`: the original has no
/// limit, and its own applications need more than ours by default (`rips`
/// initialises its parser from a KB read code by code), so a default limit
/// becomes [`LEGACY_INFERENCES`] or [`LEGACY_TIME`]; a value given on the
/// command line other than the default is kept.
pub fn raise_call_limits(args: &mut sitlog_robot::cli::RunArgs) {
    use sitlog_runtime::functions::CallLimits;
    if args.prolog_inferences == CallLimits::INFERENCES {
        args.prolog_inferences = LEGACY_INFERENCES;
    }
    if args.prolog_time_limit == CallLimits::TIME {
        args.prolog_time_limit = LEGACY_TIME;
    }
}

/// The application's first `caption(Id, Text)` fact (its `templates.pl`,
/// then its `user_functions.pl`), both atoms: what the original's
/// `screen(X)` shows, and binds `X` to, when `X` is unbound
/// (`TextActions::with_unbound_screen`). `None` when there is none.
pub fn first_caption(app: &Path) -> Option<(String, String)> {
    use sitlog_syntax::{Atom, Node};
    let caption = Atom::intern("caption");
    for file in ["templates.pl", "user_functions.pl"] {
        let Ok(bytes) = std::fs::read(app.join(file)) else {
            continue;
        };
        let (clauses, _) = sitlog_syntax::read_clauses_bytes(&bytes);
        for c in &clauses {
            if let Some(&[id, text]) = c.terms.compound(c.root, caption, 2) {
                return match (c.terms.node(id), c.terms.node(text)) {
                    (Node::Atom(i), Node::Atom(t)) => {
                        Some((i.as_str().to_owned(), t.as_str().to_owned()))
                    }
                    _ => None,
                };
            }
        }
    }
    None
}

/// The original's start-up file, relative to `SITLOG_HOME`.
pub const INIT_FILE: &str = "src/init.pl";

/// `SITLOG_HOME`: `explicit` (`--sitlog-home`), else the environment
/// variable, else the nearest ancestor of `app` that has `src/init.pl`.
pub fn find_home(app: &Path, explicit: Option<&Path>) -> Result<PathBuf, String> {
    if let Some(dir) = explicit {
        return checked_home(dir, "--sitlog-home");
    }
    if let Some(dir) = std::env::var_os("SITLOG_HOME").filter(|d| !d.is_empty()) {
        return checked_home(Path::new(&dir), "SITLOG_HOME");
    }
    let start = std::fs::canonicalize(app).unwrap_or_else(|_| app.to_path_buf());
    let mut dir = Some(start.as_path());
    while let Some(d) = dir {
        if d.join(INIT_FILE).is_file() {
            return Ok(d.to_path_buf());
        }
        dir = d.parent();
    }
    Err(format!(
        "--legacy: cannot find the original's tree: set SITLOG_HOME or pass --sitlog-home DIR \
         (a directory with {INIT_FILE}); {} is not inside one",
        app.display()
    ))
}

fn checked_home(dir: &Path, what: &str) -> Result<PathBuf, String> {
    if dir.join(INIT_FILE).is_file() {
        Ok(dir.to_path_buf())
    } else {
        Err(format!(
            "--legacy: {what} `{}` is not the original's tree (it has no {INIT_FILE})",
            dir.display()
        ))
    }
}

/// The files `init.pl` consults from `$SITLOG_HOME`, in order.
pub fn init_consults(home: &Path) -> Result<Vec<PathBuf>, String> {
    let init = home.join(INIT_FILE);
    let text = sitlog_syntax::read_file(&init)
        .map_err(|e| e.to_string())
        .and_then(|b| sitlog_syntax::decode_owned(b).map_err(|e| e.to_string()))
        .map_err(|e| format!("--legacy: cannot read {}: {e}", init.display()))?;
    let (clauses, errors) = sitlog_syntax::read_clauses(&text);
    if let Some(e) = errors.first() {
        let (line, col) = e.line_col(&text);
        return Err(format!(
            "--legacy: {}:{line}:{col}: {}",
            init.display(),
            e.message
        ));
    }
    let mut files = Vec::new();
    for clause in &clauses {
        let terms = &clause.terms;
        let Some(d) = terms.compound(clause.root, sitlog_syntax::Atom::intern(":-"), 1) else {
            continue;
        };
        let goal = d[0];
        for name in ["consult", "ensure_loaded"] {
            let Some(a) = terms.compound(goal, sitlog_syntax::Atom::intern(name), 1) else {
                continue;
            };
            let items = match terms.proper_list(a[0]) {
                Some(items) => items,
                None => vec![a[0]],
            };
            for item in items {
                let Some(f) = terms.atom(item) else { continue };
                if let Some(rest) = f.as_str().strip_prefix("$SITLOG_HOME/") {
                    let p = home.join(rest);
                    let p = if p.is_file() {
                        p
                    } else {
                        let mut q = p.clone().into_os_string();
                        q.push(".pl");
                        PathBuf::from(q)
                    };
                    if !p.is_file() {
                        return Err(format!(
                            "--legacy: {} consults `{}`, which does not exist",
                            init.display(),
                            f.as_str()
                        ));
                    }
                    files.push(p);
                }
            }
        }
    }
    Ok(files)
}

/// The legacy profile applied to the options of a run whose application
/// is `app` (or, for a compiled task, the current directory: where the tree
/// is looked for when neither `explicit` (`--sitlog-home`) nor
/// `$SITLOG_HOME` names it): the tree becomes a trust root, list tails are
/// closed, an in_arg that does not match the pipe skipped (D-8), the call
/// limits raised, `screen(X)` with `X` unbound shows
/// `caption` (see [`first_caption`]). Returns the tree and the Prolog
/// sources to load before the application's: the `SITLOG_HOME` fact of
/// `getenv/2` (as the original's launchers set it, with a trailing `/`),
/// then the files `init.pl` consults. The error is a message without the
/// `error: ` prefix.
pub fn prepare(
    app: &Path,
    explicit: Option<&Path>,
    args: &mut sitlog_robot::cli::RunArgs,
    caption: Option<(String, String)>,
) -> Result<(PathBuf, Vec<sitlog_runtime::prolog::PrologSource>), String> {
    use sitlog_runtime::prolog::PrologSource;
    let home = find_home(app, explicit)?;
    let files = init_consults(&home)?;
    // The original's tree is the application: its apps consult one
    // another's files (without --allow-os as well).
    args.trust_roots.push(home.clone());
    args.close_list_tails = true;
    args.skip_unmatched_in_arg = true;
    raise_call_limits(args);
    args.unbound_screen = caption;
    let value = std::env::var("SITLOG_HOME")
        .ok()
        .filter(|v| !v.is_empty())
        .unwrap_or_else(|| format!("{}/", home.display()));
    let mut fact = String::from("'$sitlog_env'('SITLOG_HOME', ");
    sitlog_syntax::write::write_atom(&mut fact, sitlog_syntax::Atom::intern(&value), true);
    fact.push_str(").\n");
    let mut before = vec![PrologSource::new("<legacy environment>", fact)];
    for f in &files {
        match PrologSource::from_path(f) {
            Ok(s) => before.push(s),
            Err(e) => return Err(format!("--legacy: cannot read {}: {e}", f.display())),
        }
    }
    Ok((home, before))
}

/// What a task compiled with `sitlogc build --legacy` does at start
/// (`sitlog_robot::main_legacy`'s `setup`), as `sitlogc run --legacy` does
/// before it runs: [`prepare`] from the current directory, then the
/// functions: the standard ones, the original's Prolog layer read from the
/// tree now, and the application's embedded Prolog `sources` (as the
/// interpreter loads them: consults relative to the application's
/// directory, `app_in_home` inside the tree), its KB layer served by
/// [`native_kb`] under `--legacy-kb native`. The error: the exit status,
/// the lines for stderr and the message of the `--format json` report.
pub fn task_setup(
    cli: &sitlog_robot::cli::LegacyTaskCli,
    args: &mut sitlog_robot::cli::RunArgs,
    app_in_home: Option<&str>,
    caption: Option<(&str, &str)>,
    sources: &[(&str, &str)],
) -> Result<sitlog_runtime::Functions, (u8, Vec<String>, String)> {
    use sitlog_runtime::prolog::{PrologFunctions, PrologSource};
    let caption = caption.map(|(i, t)| (i.to_owned(), t.to_owned()));
    let (home, mut all) = prepare(Path::new("."), cli.sitlog_home.as_deref(), args, caption)
        .map_err(|e| {
            let message = format!("error: {e}");
            (2, vec![message.clone()], message)
        })?;
    let layer = all.len();
    let dir = app_in_home.map(|rel| home.join(rel));
    all.extend(sources.iter().map(|(name, text)| PrologSource {
        name: (*name).to_owned(),
        text: (*text).to_owned(),
        dir: dir.clone(),
        clauses: None,
    }));
    let native = (cli.legacy_kb == sitlog_robot::cli::LegacyKb::Native).then(native_kb);
    let mut functions = sitlog_runtime::Functions::standard();
    match PrologFunctions::load_with(&all, Default::default(), layer, native) {
        Ok(prolog) => {
            prolog.install(&mut functions);
            Ok(functions)
        }
        Err(errors) => {
            let first = errors.first().map(|e| e.to_string()).unwrap_or_default();
            let lines = errors.iter().map(|e| format!("error: {e}")).collect();
            Err((1, lines, first))
        }
    }
}

/// `--legacy-kb native`: the original's KB layer served by our KB
/// (`sitlog-kb`): the services and updates the KB crate has, and the KB
/// loads and saves of the layer (see `sitlog_runtime::prolog::NativeKb`);
/// the KB-reach analysis kept in the cache directory (`kb_reach/`).
pub fn native_kb() -> sitlog_runtime::prolog::NativeKb {
    use sitlog_kb::{SERVICES, UPDATES};
    use std::sync::{Arc, Mutex};
    let kbs: Mutex<Vec<sitlog_kb::Kb>> = Mutex::new(Vec::new());
    let host = move |request: &str| -> String {
        let mut kbs = match kbs.lock() {
            Ok(k) => k,
            Err(p) => p.into_inner(),
        };
        match kb_request(&mut kbs, request) {
            Ok(reply) => reply,
            Err(message) => {
                let mut out = String::from("'$error'(error(kb_error(");
                sitlog_syntax::write::write_atom(
                    &mut out,
                    sitlog_syntax::Atom::intern(&message),
                    true,
                );
                out.push_str("),native_kb)).\n");
                out
            }
        }
    };
    sitlog_runtime::prolog::NativeKb {
        host: Arc::new(host),
        queries: SERVICES
            .iter()
            .map(|s| (s.name.to_owned(), s.arity))
            .collect(),
        updates: UPDATES
            .iter()
            .map(|u| (u.name.to_owned(), u.arity))
            .collect(),
        reach_cache: sitlog_runtime::prolog::reach_cache_dir(),
    }
}

/// One request of the engine (canonical text): see `NativeKb`.
fn kb_request(kbs: &mut Vec<sitlog_kb::Kb>, request: &str) -> Result<String, String> {
    use sitlog_runtime::prolog::read_reply;
    use sitlog_runtime::{Store, Term};
    let mut store = Store::new();
    let (t, _) = store
        .parse(request)
        .map_err(|e| format!("bad request `{request}`: {}", e.message))?;
    let Some((name, _)) = store.functor(t) else {
        return Err(format!("bad request `{request}`"));
    };
    let args: Vec<Term> = store.args(t).to_vec();
    let handle = |store: &Store, kbs: &[sitlog_kb::Kb], t: Term| -> Result<usize, String> {
        let t = store.deref(t);
        store
            .compound_args(t, sitlog_syntax::Atom::intern("$kb"), 1)
            .and_then(|a| store.int_of(a[0]))
            .and_then(|n| usize::try_from(n).ok())
            .filter(|&n| n < kbs.len())
            .ok_or_else(|| format!("`{}` is not a KB", store.writeq(t)))
    };
    let atom = |store: &Store, t: Term| -> Result<String, String> {
        store
            .atom_of(store.deref(t))
            .map(|a| a.as_str().to_owned())
            .ok_or_else(|| format!("`{}` is not a file name", store.writeq(t)))
    };
    let new = |kbs: &mut Vec<sitlog_kb::Kb>, kb: sitlog_kb::Kb| -> String {
        kbs.push(kb);
        format!("'$ok'('$kb'({}),[]).\n", kbs.len() - 1)
    };
    match (name.as_str(), args.len()) {
        ("open", 1) => {
            let path = atom(&store, args[0])?;
            let kb = sitlog_kb::Kb::load(Path::new(&path)).map_err(|e| e.to_string())?;
            Ok(new(kbs, kb))
        }
        ("handle", 1) => {
            let text = store.writeq(args[0]);
            let kb = sitlog_kb::Kb::parse(&text, "<KB term>").map_err(|e| e.to_string())?;
            Ok(new(kbs, kb))
        }
        ("save", 2) => {
            let h = handle(&store, kbs, args[0])?;
            let path = atom(&store, args[1])?;
            kbs[h].save(Path::new(&path)).map_err(|e| e.to_string())?;
            Ok("'$ok'(true,[]).\n".to_owned())
        }
        ("term", 1) => {
            let h = handle(&store, kbs, args[0])?;
            Ok(read_reply(&kbs[h].to_text()))
        }
        ("query", 2) => {
            let h = handle(&store, kbs, args[0])?;
            let goal = store.writeq(args[1]);
            match kbs[h].query(&goal).map_err(|e| format!("{goal}: {e}"))? {
                sitlog_kb::Outcome::Answer(a) => Ok(read_reply(&a.writeq())),
                sitlog_kb::Outcome::Fails => Ok("'$fail'.\n".to_owned()),
            }
        }
        ("update", 2) => {
            let h = handle(&store, kbs, args[0])?;
            let goal = store.writeq(args[1]);
            let clause =
                sitlog_syntax::read_term(&goal).map_err(|e| format!("{goal}: {}", e.message))?;
            let mut next = kbs[h].clone();
            if next.update(&clause).map_err(|e| format!("{goal}: {e}"))? {
                Ok(new(kbs, next))
            } else {
                Ok(format!("'$ok'('$kb'({h}),[]).\n"))
            }
        }
        _ => Err(format!("unknown request `{request}`")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legacy_raises_the_default_call_limits_and_keeps_given_ones() {
        let mut args = sitlog_robot::cli::RunArgs::default();
        raise_call_limits(&mut args);
        // No inference limit, as the original.
        assert_eq!(
            args.prolog_inferences,
            sitlog_runtime::prolog::NO_INFERENCE_LIMIT
        );
        assert_eq!(args.prolog_time_limit, LEGACY_TIME);
        let mut args = sitlog_robot::cli::RunArgs {
            prolog_inferences: 5000,
            prolog_time_limit: std::time::Duration::from_secs(2),
            ..Default::default()
        };
        raise_call_limits(&mut args);
        assert_eq!(args.prolog_inferences, 5000);
        assert_eq!(args.prolog_time_limit, std::time::Duration::from_secs(2));
    }

    #[test]
    fn reads_the_home_consults_of_init_pl() {
        let dir = std::env::temp_dir().join(format!("sitlog-legacy-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("src")).unwrap();
        std::fs::create_dir_all(dir.join("kb")).unwrap();
        std::fs::write(
            dir.join(INIT_FILE),
            ":- op(800, xfx, '=>').\n:- consult(diag_manager).\n\
             :- consult('$SITLOG_HOME/kb/a.pl').\n:- consult('$SITLOG_HOME/kb/b').\nstart :- true.\n",
        )
        .unwrap();
        std::fs::write(dir.join("kb/a.pl"), "a.\n").unwrap();
        std::fs::write(dir.join("kb/b.pl"), "b.\n").unwrap();
        let files = init_consults(&dir).unwrap();
        assert_eq!(files, vec![dir.join("kb/a.pl"), dir.join("kb/b.pl")]);
        // Found from an application inside the tree.
        std::fs::create_dir_all(dir.join("apps/x")).unwrap();
        if std::env::var_os("SITLOG_HOME").is_none() {
            let home = find_home(&dir.join("apps/x"), None).unwrap();
            assert_eq!(home, std::fs::canonicalize(&dir).unwrap());
        }
        assert!(find_home(Path::new("/"), Some(Path::new("/nonexistent")))
            .unwrap_err()
            .contains("no src/init.pl"));
        // The profile of a run: the layer after the `getenv` fact, the tree
        // a trust root, the limits raised, list tails closed.
        let mut args = sitlog_robot::cli::RunArgs::default();
        let caption = Some(("c".to_owned(), "Hi".to_owned()));
        let (home, before) = prepare(&dir, Some(&dir), &mut args, caption.clone()).unwrap();
        assert_eq!(home, dir);
        let names: Vec<&str> = before.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names[0], "<legacy environment>");
        assert!(before[0].text.starts_with("'$sitlog_env'('SITLOG_HOME', "));
        assert_eq!(before.len(), 3);
        assert_eq!(before[2].text, "b.\n");
        assert_eq!(args.trust_roots, vec![dir.clone()]);
        assert!(args.close_list_tails);
        assert!(args.skip_unmatched_in_arg);
        assert_eq!(args.prolog_inferences, LEGACY_INFERENCES);
        assert_eq!(args.unbound_screen, caption);
        std::fs::write(dir.join(INIT_FILE), ":- consult('$SITLOG_HOME/kb/c').\n").unwrap();
        assert!(init_consults(&dir).unwrap_err().contains("kb/c"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
