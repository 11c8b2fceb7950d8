//! `sitlogc run --legacy`: an application written for the original
//! interpreter, run unmodified from a tree laid out like the original's
//! (`SITLOG_HOME` with `src/init.pl` and a Prolog layer under
//! `knowledge_base/`). The tree here is a small one of our own, written for
//! this test: it exercises what the paper's demos need (tests/conformance/
//! legacy_demos.sh runs those against the original itself).

use std::path::{Path, PathBuf};

use crate::support::sitlogc;

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
:- consult('$SITLOG_HOME/knowledge_base/kb_layer.pl').
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
    // A KB layer of the original's shape (services and updates take the KB
    // term; open/save read and write a file), for --legacy-kb.
    write(
        &root,
        "knowledge_base/kb_layer.pl",
        r#"open_shop_kb(KB) :-
    getenv('SITLOG_HOME', Home),
    atomic_concat(Home, '/knowledge_base/shop.kb', Path),
    open(Path, read, S), get0(S, C), codes(C, S, Cs), close(S),
    atom_chars(A, Cs), atom_to_chars(A, Text), append(Text, ".", All),
    read_from_chars(All, KB).
save_shop_kb(KB) :-
    getenv('SITLOG_HOME', Home),
    atomic_concat(Home, '/knowledge_base/shop.kb', Path),
    open(Path, write, S), writeq(S, KB), close(S).
object_property_value(O, P, KB, V) :-
    member(class(_, _, _, _, Inds), KB), member([id=>O, Props, _], Inds),
    member([P=>V, _], Props), !.
object_property_value(_, _, _, unknown).
add_object_property(O, P, V, KB, New) :- maplist(add_p(O, P, V), KB, New).
add_p(O, P, V, class(C, M, Ps, Rs, Is), class(C, M, Ps, Rs, Is2)) :- maplist(add_i(O, P, V), Is, Is2).
add_i(O, P, V, [id=>O, Props, Rels], [id=>O, Props2, Rels]) :- !, append(Props, [[P=>V, 0]], Props2).
add_i(_, _, _, I, I).
% not a service of sitlog-kb: gets the KB term
individuals(KB, N) :-
    findall(I, (member(class(_, _, _, _, Is), KB), member(I, Is)), L), length(L, N).
"#,
    );
    write(
        &root,
        "knowledge_base/shop.kb",
        "[class(top,none,[],[],[]),\nclass(drink,top,[],[],[[id=>coke,[[size=>big,0]],[]],[id=>malz,[],[]]])]\n",
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
    write(&root, "apps/kb/models", "'main.dm'.\n");
    write(
        &root,
        "apps/kb/user_functions.pl",
        r#"kb_talk(_) :-
    open_shop_kb(KB), object_property_value(coke, size, KB, Big),
    object_property_value(malz, size, KB, None),
    add_object_property(malz, size, small, KB, KB2), save_shop_kb(KB2),
    open_shop_kb(KB3), object_property_value(malz, size, KB3, Small),
    object_property_value(tea, size, KB3, Tea),
    individuals(KB3, N),
    assign_func_value([Big, None, Small, Tea, N]).
"#,
    );
    write(
        &root,
        "apps/kb/main.dm",
        r#"diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [say(apply(kb_talk(X), [x]))] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
    );
    root
}

fn run(root: &Path, extra: &[&str], home_env: Option<&Path>) -> std::process::Output {
    let mut cmd = sitlogc();
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
    let plain = sitlogc()
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
    let out = sitlogc()
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
    // `sitlogc build --legacy` places the application in its tree the same
    // way, and checks it under the original's rules (the DM defined twice
    // identically: W0203, not E0201); its Prolog layer is read when the
    // task starts (the compiled task itself: legacy_demos.sh).
    for command in ["run", "build"] {
        let out = sitlogc()
            .args([command, "--legacy"])
            .arg(&elsewhere)
            .env_remove("SITLOG_HOME")
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{command}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.contains("cannot find the original's tree"),
            "{command}: {stderr}"
        );
    }
    let out = sitlogc()
        .current_dir(&root)
        .args(["build", "apps/shop", "--legacy", "--emit", "rust"])
        .env_remove("SITLOG_HOME")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("W0203"), "{stderr}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("pub fn program()"));
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
    let out = sitlogc()
        .args(["run", "--sitlog-home"])
        .arg(&root)
        .arg(&app)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&root);
    let _ = std::fs::remove_dir_all(&elsewhere);
}

#[test]
fn the_kb_layer_served_natively_answers_as_the_original_layer() {
    for mode in ["prolog", "native"] {
        let root = tree(mode);
        let out = sitlogc()
            .current_dir(&root)
            .args(["run", "apps/kb", "--legacy", "--legacy-kb", mode])
            .env_remove("SITLOG_HOME")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{mode}: {stderr}");
        let said: Vec<&str> = stderr
            .lines()
            .filter_map(|l| l.strip_prefix("Golem says: "))
            .collect();
        assert_eq!(said, ["big unknown small unknown 2."], "{mode}: {stderr}");
        // The update was saved, in a form the layer reads back.
        let saved = std::fs::read_to_string(root.join("knowledge_base/shop.kb")).unwrap();
        assert!(saved.contains("small"), "{mode}: {saved}");
        // Written by sitlog-kb (one class a line) only when served natively.
        assert_eq!(
            saved.contains(",\nclass("),
            mode == "native",
            "{mode}: {saved}"
        );
        let _ = std::fs::remove_dir_all(&root);
    }
}

#[test]
fn a_kb_that_sitlog_kb_cannot_read_is_served_by_the_layer() {
    // A KB sitlog-kb refuses (a property not `[Entry, Weight]`): the layer's own clauses load,
    // query, update and save it, as with --legacy-kb prolog.
    let root = tree("native-fallback");
    write(
        &root,
        "knowledge_base/shop.kb",
        "[class(top,none,[odd],[],[]),\nclass(drink,top,[],[],[[id=>coke,[[size=>big,0]],[]],[id=>malz,[],[]]])]\n",
    );
    let out = sitlogc()
        .current_dir(&root)
        .args(["run", "apps/kb", "--legacy", "--legacy-kb", "native"])
        .env_remove("SITLOG_HOME")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let said: Vec<&str> = stderr
        .lines()
        .filter_map(|l| l.strip_prefix("Golem says: "))
        .collect();
    assert_eq!(said, ["big unknown small unknown 2."], "{stderr}");
    // Saved by the layer's own clause (writeq, one line), `odd` kept.
    let saved = std::fs::read_to_string(root.join("knowledge_base/shop.kb")).unwrap();
    assert!(
        saved.contains("small") && saved.contains("[odd]") && !saved.contains(",\nclass("),
        "{saved}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn test_mode_gives_each_situation_type_what_the_original_gives() {
    let root = tree("wrap");
    write(&root, "apps/wrap/models", "'main.dm'.\n");
    write(
        &root,
        "apps/wrap/main.dm",
        r#"diag_mod(main,
  [ [ id ==> body, type ==> detect_body(nearest),
      arcs ==> [ detected(B) : say(B) => ask ] ],
    [ id ==> ask, type ==> listening,
      arcs ==> [ yes : say(yes) => point ] ],
    [ id ==> point, type ==> see_pointing_follow,
      arcs ==> [ pointing_coords(X, Y, Z) : say([X, Y, Z]) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
    );
    write(&root, "apps/wrap/in.txt", "luis.\nyes.\n1.\n2.\n3.\n");
    let out = sitlogc()
        .current_dir(&root)
        .args([
            "run",
            "apps/wrap",
            "--legacy",
            "--script",
            "apps/wrap/in.txt",
        ])
        .env_remove("SITLOG_HOME")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let said: Vec<&str> = stderr
        .lines()
        .filter_map(|l| l.strip_prefix("Golem says: "))
        .collect();
    assert_eq!(said, ["luis", "yes", "1 2 3."], "{stderr}");
    // Without --legacy, `listening` gets said(yes) and detect_body the
    // term as typed: the task stops at its first situation.
    let out = sitlogc()
        .current_dir(&root)
        .args(["run", "apps/wrap", "--script", "apps/wrap/in.txt"])
        .output()
        .unwrap();
    assert_ne!(out.status.code(), Some(0));
    let _ = std::fs::remove_dir_all(&root);
}

/// Under `--legacy` the original's tree is the application: an app's
/// Prolog consulting another app's file by a `$SITLOG_HOME` path runs
/// without `--allow-os` (the original's own apps do), while a file outside
/// the tree is still refused.
#[test]
fn the_original_tree_is_the_application_under_legacy() {
    let root = tree("sibling");
    write(&root, "apps/other/extra.pl", "extra_fact(yes).\n");
    let functions = root.join("apps/shop/user_functions.pl");
    let text = std::fs::read_to_string(&functions).unwrap();
    std::fs::write(
        &functions,
        format!("{text}\n:- consult('$SITLOG_HOME/apps/other/extra.pl').\n"),
    )
    .unwrap();
    let out = run(&root, &[], None);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    // A file outside the tree: refused, naming --allow-os.
    let elsewhere = std::env::temp_dir().join(format!(
        "sitlogc-legacy-elsewhere-{}.pl",
        std::process::id()
    ));
    std::fs::write(&elsewhere, "elsewhere_fact(yes).\n").unwrap();
    std::fs::write(
        &functions,
        format!("{text}\n:- consult('{}').\n", elsewhere.display()),
    )
    .unwrap();
    let out = run(&root, &[], None);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("outside the application") && stderr.contains("--allow-os"),
        "{stderr}"
    );
    let _ = std::fs::remove_file(&elsewhere);
    let _ = std::fs::remove_dir_all(&root);
}

/// The original evaluates a DM call's arguments, and its evaluator of lists
/// closes a list whose tail is unbound: `pick([First|Rest])` calls
/// `pick([First])` and the caller's `Rest` is `[]` afterwards. `--legacy`
/// does the same; our own applications keep the open tail.
#[test]
fn a_dm_call_closes_its_lists_open_tails_under_legacy() {
    let root = tree("tails");
    write(&root, "apps/tails/models", "'main.dm'.\n");
    write(
        &root,
        "apps/tails/main.dm",
        r#"diag_mod(main,
  [ [ id ==> is, type ==> recursive,
      embedded_dm ==> pick(box(Kind, [First|Rest]), [[a|Inner]]),
      arcs ==> [ fs : say(after(Rest, Inner)) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
diag_mod(pick(B, L),
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : say(got(B, L)) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
    );
    let said = |legacy: bool| {
        let mut cmd = sitlogc();
        cmd.current_dir(&root)
            .args(["run", "apps/tails"])
            .env_remove("SITLOG_HOME");
        if legacy {
            cmd.arg("--legacy");
        }
        let out = cmd.output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(out.status.code(), Some(0), "{stderr}");
        stderr
            .lines()
            .filter_map(|l| l.strip_prefix("Golem says: "))
            .map(str::to_owned)
            .collect::<Vec<_>>()
    };
    let legacy = said(true);
    assert_eq!(legacy.len(), 2, "{legacy:?}");
    assert!(
        legacy[0].contains("[[a]]") && !legacy[0].contains('|'),
        "{legacy:?}"
    );
    assert!(legacy[1].contains("[]"), "{legacy:?}");
    let ours = said(false);
    assert!(ours[0].contains('|'), "{ours:?}");
    let _ = std::fs::remove_dir_all(&root);
}

/// The original's `screen(X)` with `X` unbound: its service's clause for
/// `screen([A|Rest])` matches and its message formatter takes the first
/// `caption(Id, Text)` fact, so `X` is `[caption(Id)]` afterwards and the
/// caption's text is shown. `--legacy` does the same.
#[test]
fn screen_of_an_unbound_variable_shows_the_first_caption_under_legacy() {
    let root = tree("screen");
    write(&root, "apps/caps/models", "'main.dm'.\n");
    write(
        &root,
        "apps/caps/templates.pl",
        "caption(greet, 'Welcome to the shop').\ncaption(bye, 'See you').\n",
    );
    write(
        &root,
        "apps/caps/main.dm",
        r#"diag_mod(main,
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [screen(X), screen(shown(X))] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#,
    );
    let run = |legacy: bool| {
        let mut cmd = sitlogc();
        cmd.current_dir(&root)
            .args(["run", "apps/caps"])
            .env_remove("SITLOG_HOME");
        if legacy {
            cmd.arg("--legacy");
        }
        let out = cmd.output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(out.status.code(), Some(0), "{stderr}");
        stderr
            .lines()
            .filter_map(|l| l.strip_prefix("Golem prints on screen: "))
            .map(str::to_owned)
            .collect::<Vec<_>>()
    };
    assert_eq!(
        run(true),
        ["Welcome to the shop", "shown([caption(greet)])"]
    );
    let ours = run(false);
    assert!(!ours.iter().any(|l| l.contains("Welcome")), "{ours:?}");
    let _ = std::fs::remove_dir_all(&root);
}
