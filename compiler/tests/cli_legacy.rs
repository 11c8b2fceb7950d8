//! `sitlogc run --legacy`: an application written for the original
//! interpreter, run unmodified from a tree laid out like the original's
//! (`SITLOG_HOME` with `src/init.pl` and a Prolog layer under
//! `knowledge_base/`). The tree here is a small one of our own, written for
//! this test: it exercises what the paper's demos need (tests/conformance/
//! legacy_demos.sh runs those against the original itself).

use std::path::{Path, PathBuf};
use std::process::Command;

fn write(root: &Path, rel: &str, text: &str) {
    let p = root.join(rel);
    std::fs::create_dir_all(p.parent().unwrap()).unwrap();
    std::fs::write(p, text).unwrap();
}

/// A tree like the original's: init.pl consults the interpreter (relative
/// names, which sitlog-rs replaces) and a KB layer from $SITLOG_HOME.
fn tree(name: &str) -> PathBuf {
    let root = std::env::temp_dir().join(format!("sitlogc-legacy-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    write(
        &root,
        "src/init.pl",
        r#":- op(900, xfx, '==>').
:- consult(interpreter).
:- consult('$SITLOG_HOME/knowledge_base/layer.pl').
banner('a long line \c
        continued').
"#,
    );
    write(
        &root,
        "src/interpreter.pl",
        "this is not loaded by sitlogc.\n",
    );
    // The KB layer: reads the KB text code by code, SWI-Prolog style.
    write(
        &root,
        "knowledge_base/layer.pl",
        r#":- consult(helpers).
open_kb(KB) :-
    getenv('SITLOG_HOME', Home),
    atomic_concat(Home, '/knowledge_base/shop_kb.txt', Path),
    open(Path, read, S), get0(S, C), codes(C, S, Cs), close(S),
    atom_chars(A, Cs),
    atom_to_chars(A, Text), atom_to_chars('.', Stop), append(Text, Stop, All),
    read_from_chars(All, KB).
"#,
    );
    write(
        &root,
        "knowledge_base/helpers.pl",
        "codes(-1, _, []) :- !.\ncodes(C, S, [C|Cs]) :- get0(S, N), codes(N, S, Cs).\n",
    );
    // `'-'=>>loc` is SWI syntax; grades of mixed type decide the answer.
    write(
        &root,
        "knowledge_base/shop_kb.txt",
        "[shop(['-'=>>loc]), grade(2, [coke]), grade(2.5, [coke, noodles]), grade(1, [])]",
    );
    write(
        &root,
        "apps/shop/models",
        "'main.dm'.\n'tools/helper.dm'.\n'tools/helper_copy.dm'.\n",
    );
    let helper = r#"diag_mod(helper(X),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(X) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#;
    write(&root, "apps/shop/tools/helper.dm", helper);
    write(&root, "apps/shop/tools/helper_copy.dm", helper);
    write(
        &root,
        "apps/shop/user_functions.pl",
        r#"% the original's decision maker's way: grade, sort, take the highest
decide(_) :-
    open_kb(KB),
    findall(G-D, member(grade(G, D), KB), Graded),
    sort(Graded, Sorted), reverse(Sorted, [_-Best|_]),
    flatten([bring, Best], Words),
    assign_func_value(Words).
odd_op(_) :- open_kb([shop([Op=>>_])|_]), assign_func_value(Op).
"#,
    );
    write(
        &root,
        "apps/shop/main.dm",
        r#"diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [say(['my decision is to', apply(decide(X), [x])]),
                          cam2nav([0.2, 2, 0.55], [-30, 0.1, -0.06], P),
                          say(P), say(apply(odd_op(Y), [y]))] => rs ] ],
    [ id ==> rs, type ==> recursive, embedded_dm ==> helper(done),
      arcs ==> [ fs : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
    );
    root
}

fn run(root: &Path, extra: &[&str], home_env: Option<&Path>) -> std::process::Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_sitlogc"));
    cmd.current_dir(root)
        .args(["run", "apps/shop", "--legacy"])
        .args(extra)
        .env_remove("SITLOG_HOME");
    if let Some(h) = home_env {
        cmd.env("SITLOG_HOME", h);
    }
    cmd.output().unwrap()
}

#[test]
fn runs_an_application_of_the_original_unmodified() {
    let root = tree("run");
    // SITLOG_HOME found from the application's directory.
    let out = run(&root, &[], None);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let said: Vec<&str> = stderr
        .lines()
        .filter_map(|l| l.strip_prefix("Golem says: "))
        .collect();
    assert_eq!(
        said,
        [
            // a list said as one sentence; SWI's order of 2 and 2.5
            "my decision is to [bring,coke,noodles]",
            // cam2nav's arithmetic (a list again: one sentence)
            "10.3049 0.559",
            // our reader read `'-'=>>loc`
            "-",
            "done"
        ],
        "{stderr}"
    );
    // The DM defined twice identically: a warning, the first is used.
    assert!(stderr.contains("W0203"), "{stderr}");
    // Without --legacy the same application is refused (E0201).
    let plain = Command::new(env!("CARGO_BIN_EXE_sitlogc"))
        .current_dir(&root)
        .args(["run", "apps/shop", "--allow-unresolved"])
        .output()
        .unwrap();
    assert_eq!(plain.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&plain.stderr).contains("E0201"));
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn sitlog_home_is_explicit_or_from_the_environment() {
    let root = tree("home");
    let app = root.join("apps/shop");
    // --sitlog-home, from another directory.
    let out = Command::new(env!("CARGO_BIN_EXE_sitlogc"))
        .args(["run", "--legacy", "--sitlog-home"])
        .arg(&root)
        .arg(&app)
        .env_remove("SITLOG_HOME")
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // SITLOG_HOME naming a directory that is not the original's tree.
    let out = run(&root, &[], Some(&app));
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("SITLOG_HOME") && stderr.contains("src/init.pl"),
        "{stderr}"
    );
    // An application outside any tree.
    let elsewhere =
        std::env::temp_dir().join(format!("sitlogc-legacy-none-{}", std::process::id()));
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::fs::copy(app.join("main.dm"), elsewhere.join("main.dm")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_sitlogc"))
        .args(["run", "--legacy"])
        .arg(&elsewhere)
        .env_remove("SITLOG_HOME")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot find the original's tree"));
    // A consult of init.pl naming a missing file.
    write(
        &root,
        "src/init.pl",
        ":- consult('$SITLOG_HOME/knowledge_base/gone.pl').\n",
    );
    let out = run(&root, &[], None);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("gone.pl"));
    // --sitlog-home needs --legacy.
    let out = Command::new(env!("CARGO_BIN_EXE_sitlogc"))
        .args(["run", "--sitlog-home"])
        .arg(&root)
        .arg(&app)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&root);
    let _ = std::fs::remove_dir_all(&elsewhere);
}
