//! The trust model in the engine: loading runs no directive, and without
//! `--allow-os` the guards refuse the shell, sockets, writes outside the
//! application and consults of files outside it; with it they let them be.

use super::{PrologFunctions, PrologOptions, PrologSource};
use crate::eval::{eval, EvalCtx};
use crate::functions::Functions;
use crate::store::Store;
use crate::trust::Trust;
use crate::vars::Vars;
use std::path::{Path, PathBuf};

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("sitlog-perm-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("app")).unwrap();
    d
}

fn source(dir: &Path, text: String) -> PrologSource {
    PrologSource {
        name: dir.join("app/user_functions.pl").display().to_string(),
        text,
        dir: Some(dir.join("app")),
        clauses: None,
    }
}

fn quoted(p: &Path) -> String {
    format!("'{}'", p.display())
}

fn call(engine: &PrologFunctions, trust: Trust, src: &str) -> Result<String, String> {
    let mut functions = Functions::standard();
    engine.install(&mut functions);
    functions.set_trust(trust);
    let mut store = Store::new();
    let (t, _) = store.parse(src).unwrap();
    let (mut locals, mut globals) = (Vars::default(), Vars::default());
    let mut ctx = EvalCtx {
        store: &mut store,
        locals: &mut locals,
        globals: &mut globals,
        history: &[],
        functions: &functions,
    };
    let v = eval(&mut ctx, t).map_err(|e| e.message)?;
    Ok(store.writeq(v))
}

#[test]
fn nothing_runs_before_start_and_the_os_is_off_without_the_flag() {
    let d = temp("off");
    let made = d.join("app/made");
    let pwned = d.join("pwned");
    let outside = d.join("outside.txt");
    let touch = quoted(Path::new(&format!("touch {}", pwned.display())));
    let directives = format!(
        ":- use_module(library(os)).\n\
         :- open({made}, write, S), close(S).\n\
         :- atom_chars({touch}, C), shell(C).\n",
        made = quoted(&made),
    );
    let load = |text: String| {
        PrologFunctions::load_with(&[source(&d, text)], PrologOptions::default(), 0, None)
            .expect("loads")
    };
    let engine = load(directives);
    assert!(!made.exists(), "a directive ran while loading");
    let errors = engine.start(&Trust::default()).unwrap_err();
    // The write inside the application ran; the shell was refused, at its line.
    assert!(made.exists());
    assert!(!pwned.exists());
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert_eq!(errors[0].line, 3, "{errors:?}");
    assert!(
        errors[0].message.contains("`shell/1`") && errors[0].message.contains("--allow-os"),
        "{errors:?}"
    );
    let functions = format!(
        ":- use_module(library(os)).\n\
         sh(_) :- atom_chars({touch}, C), shell(C), assign_func_value(ran).\n\
         wr(_) :- open({outside}, write, S), close(S), assign_func_value(wrote).\n\
         rd(_) :- open({made}, read, S), close(S), assign_func_value(read).\n\
         net(_) :- socket_client_open('127.0.0.1':9, S, []), close(S), assign_func_value(net).\n\
         dyn(_) :- G = shell(x), call(G), assign_func_value(dyn).\n\
         :- op(700, xfx, ===>).\n\
         :- op(1200, xfx, :-).\n\
         opx(_) :- X = '===>'(a, b), assign_func_value(X).\n\
         hl(_) :- halt.\n",
        made = quoted(&made),
        outside = quoted(&outside),
    );
    let engine = load(functions);
    let e = call(&engine, Trust::default(), "apply(sh(X), [1])").unwrap_err();
    assert!(
        e.contains("`sh/1`") && e.contains("`shell/1`") && e.contains("--allow-os"),
        "{e}"
    );
    assert!(!pwned.exists());
    let e = call(&engine, Trust::default(), "apply(wr(X), [1])").unwrap_err();
    assert!(
        e.contains("writing") && e.contains("outside.txt") && e.contains("--allow-os"),
        "{e}"
    );
    assert!(!outside.exists());
    assert_eq!(
        call(&engine, Trust::default(), "apply(rd(X), [1])").unwrap(),
        "read"
    );
    let e = call(&engine, Trust::default(), "apply(net(X), [1])").unwrap_err();
    assert!(
        e.contains("socket_client_open/3") && e.contains("--allow-os"),
        "{e}"
    );
    let e = call(&engine, Trust::default(), "apply(dyn(X), [1])").unwrap_err();
    assert!(e.contains("`shell/1`") && e.contains("--allow-os"), "{e}");
    // Issue 38's last rows: `op/3` directives leave the calls' canonical
    // text as it was; `halt` ends the call with an error, not the process.
    assert_eq!(
        call(&engine, Trust::default(), "apply(opx(X), [1])").unwrap(),
        "===>(a,b)"
    );
    let e = call(&engine, Trust::default(), "apply(hl(X), [1])").unwrap_err();
    assert!(e.contains("`hl/1`") && e.contains("did not answer"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn the_flag_lets_the_os_be_and_consults_outside_need_it() {
    let d = temp("on");
    let pwned = d.join("pwned");
    std::fs::write(d.join("lib.pl"), "from_outside(yes).\n").unwrap();
    let text = format!(
        ":- use_module(library(os)).\n\
         :- consult({lib}).\n\
         :- atom_chars({touch}, C), shell(C).\n",
        lib = quoted(&d.join("lib.pl")),
        touch = quoted(Path::new(&format!("touch {}", pwned.display()))),
    );
    let load = || {
        PrologFunctions::load_with(
            &[source(&d, text.clone())],
            PrologOptions::default(),
            0,
            None,
        )
        .expect("loads")
    };
    let errors = load().start(&Trust::default()).unwrap_err();
    assert!(!pwned.exists());
    assert!(
        errors[0].line == 2
            && errors[0].message.contains("lib.pl")
            && errors[0].message.contains("--allow-os"),
        "{errors:?}"
    );
    let trust = Trust {
        allow_os: true,
        ..Trust::default()
    };
    load().start(&trust).expect("starts");
    assert!(pwned.exists());
    let _ = std::fs::remove_dir_all(&d);
}
