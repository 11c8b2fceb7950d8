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

const HELPER: &str = r#"diag_mod(helper(X),
  [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(X) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#;

const SHOP_FUNCTIONS: &str = r#"% the original's decision maker's way: grade, sort, take the highest
decide(_) :-
    open_kb(KB),
    findall(G-D, member(grade(G, D), KB), Graded),
    sort(Graded, Sorted), reverse(Sorted, [_-Best|_]),
    flatten([bring, Best], Words),
    assign_func_value(Words).
odd_op(_) :- open_kb([shop([Op=>>_])|_]), assign_func_value(Op).
"#;

/// The shop: the original's decision maker, cam2nav, SWI syntax in the
/// KB text, and a DM defined twice identically (W0203 under `--legacy`,
/// E0201 without).
fn shop_dm(name: &str) -> String {
    format!(
        r#"diag_mod({name},
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [say(['my decision is to', apply(decide(X), [x])]),
                          cam2nav([0.2, 2, 0.55], [-30, 0.1, -0.06], P),
                          say(P), say(apply(odd_op(Y), [y]))] => rs ] ],
    [ id ==> rs, type ==> recursive, embedded_dm ==> helper(done),
      arcs ==> [ fs : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#
    )
}

/// What the shop says, in order.
const SHOP_SAID: [&str; 4] = [
    // a list said as one sentence; SWI's order of 2 and 2.5
    "my decision is to [bring,coke,noodles]",
    // cam2nav's arithmetic (a list again: one sentence)
    "10.3049 0.559",
    // our reader read `'-'=>>loc`
    "-",
    "done",
];

const KB_FUNCTIONS: &str = r#"kb_talk(_) :-
    open_shop_kb(KB), object_property_value(coke, size, KB, Big),
    object_property_value(malz, size, KB, None),
    add_object_property(malz, size, small, KB, KB2), save_shop_kb(KB2),
    open_shop_kb(KB3), object_property_value(malz, size, KB3, Small),
    object_property_value(tea, size, KB3, Tea),
    individuals(KB3, N),
    findall(M, call(count_classes, KB3, M), [Classes]),
    Rule = (kb_count(K, C) :- count_inds(K, C)), assertz(Rule), kb_count(KB3, Inds),
    Rule2 = (kb_get(N2) :- open_shop_kb(K2), count_inds2(K2, N2)), assertz(Rule2), kb_get(Inds2),
    kb_len(KB3, Len), kb_walk(x, 1, Walk), assertz(kb_len(extra, 7)), kb_len([a|extra], Len2),
    assign_func_value([Big, None, Small, Tea, N, Classes, Inds, Inds2, Len, Walk, Len2]).
kb_out(_) :- open_shop_kb(KB), assign_func_value(KB).
kb_back(KB) :- length(KB, N), assign_func_value(N).
"#;

/// The KB layer: services, an update saved and read back, and predicates
/// of the layer that sitlog-kb does not serve, given the KB (a handle under
/// `--legacy-kb native`, a KB term for them) directly, through a meta-call
/// (`count_classes`) and through a rule asserted at run time (`kb_count`,
/// which calls `count_inds`, and through one whose body gets a KB itself,
/// `kb_get`: every predicate of the layer is wrapped from then on), and
/// recursions (`kb_len`, whose calls of itself go to its clauses directly
/// under `native`, until a clause is asserted for it; `kb_walk`, which
/// makes a handle before calling itself); a KB given to the DM is a KB term, as on the
/// original (`kb_out`, `kb_back`), never a handle.
fn kb_dm(name: &str) -> String {
    format!(
        r#"diag_mod({name},
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [say(apply(kb_talk(X), [x])),
                          say(apply(kb_back(K), [apply(kb_out(Y), [y])]))] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#
    )
}

const KB_SAID: [&str; 2] = ["big unknown small unknown 2 2 2 2 2 2 8.", "2"];

/// Test mode's situation types, as the original's test mode gives them.
fn wrap_dm(name: &str) -> String {
    format!(
        r#"diag_mod({name},
  [ [ id ==> body, type ==> detect_body(nearest),
      arcs ==> [ detected(B) : say(B) => ask ] ],
    [ id ==> ask, type ==> listening,
      arcs ==> [ yes : say(yes) => point ] ],
    [ id ==> point, type ==> see_pointing_follow,
      arcs ==> [ pointing_coords(X, Y, Z) : say([X, Y, Z]) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#
    )
}

const WRAP_SCRIPT: &str = "luis.\nyes.\n1.\n2.\n3.\n";
const WRAP_SAID: [&str; 3] = ["luis", "yes", "1 2 3."];

/// A DM call whose arguments have open tails.
fn tails_dm(name: &str) -> String {
    format!(
        r#"diag_mod({name},
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
"#
    )
}

/// in_arg patterns that do not match the pipe (semantics.md D-8): in a
/// neutral situation (a compound that matches partly, `f(A, b)` against
/// `f(1, c)`), a recursive one and a final one.
fn inarg_dm(name: &str) -> String {
    format!(
        r#"diag_mod({name},
  [ [ id ==> is, type ==> neutral, out_arg ==> f(1, c),
      arcs ==> [ empty : empty => s1 ] ],
    [ id ==> s1, type ==> neutral, in_arg ==> f(A, b),
      arcs ==> [ empty : say(seen(A)) => s2 ] ],
    [ id ==> s2, type ==> recursive, in_arg ==> g(B), embedded_dm ==> {name}_echo,
      arcs ==> [ fs : say(back(B)) => fs ] ],
    [ id ==> fs, type ==> final, in_arg ==> h(_) ] ],
  []).
diag_mod({name}_echo,
  [ [ id ==> is, type ==> neutral, in_arg ==> P,
      arcs ==> [ empty : say(got(P)) => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#
    )
}

/// `screen` of an unbound variable, with caption facts in the app.
fn caps_dm(name: &str) -> String {
    format!(
        r#"diag_mod({name},
  [ [ id ==> is, type ==> neutral,
      arcs ==> [ empty : [screen(X), screen(shown(X))] => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#
    )
}

const CAPTIONS: &str = "caption(greet, 'Welcome to the shop').\ncaption(bye, 'See you').\n";

/// The lines of `stderr` after `prefix` (`Golem says: `, ...).
fn lines<'a>(stderr: &'a str, prefix: &str) -> Vec<&'a str> {
    stderr
        .lines()
        .filter_map(|l| l.strip_prefix(prefix))
        .collect()
}

/// A tree like the original's: init.pl consults the interpreter (relative
/// names, which sitlog-rs replaces) and a KB layer from $SITLOG_HOME.
fn tree(name: &str) -> PathBuf {
    let root =
        crate::support::temp_root().join(format!("sitlogc-legacy-{name}-{}", std::process::id()));
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
count_classes(KB, N) :- length(KB, N).
count_inds(KB, N) :-
    findall(I, (member(class(_, _, _, _, Is), KB), member(I, Is)), L), length(L, N).
count_inds2(KB, N) :-
    findall(I, (member(class(_, _, _, _, Is), KB), member(I, Is)), L), length(L, N).
kb_len([], 0).
kb_len([_|T], N) :- kb_len(T, M), N is M + 1.
kb_walk(KB, 0, N) :- !, kb_len(KB, N).
kb_walk(_, K, N) :- K1 is K - 1, open_shop_kb(KB), kb_walk(KB, K1, N).
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
    for app in ["shop", "all"] {
        write(&root, &format!("apps/{app}/tools/helper.dm"), HELPER);
        write(&root, &format!("apps/{app}/tools/helper_copy.dm"), HELPER);
    }
    write(&root, "apps/shop/user_functions.pl", SHOP_FUNCTIONS);
    write(&root, "apps/shop/main.dm", &shop_dm("main"));
    write(&root, "apps/kb/models", "'main.dm'.\n");
    write(&root, "apps/kb/user_functions.pl", KB_FUNCTIONS);
    write(&root, "apps/kb/main.dm", &kb_dm("main"));
    // Every check of a successful `--legacy` run in one application (one
    // engine start serves them all: the Prolog layer loads in ~3 s of CPU in
    // a debug build): the shop, the KB layer, the situation types of test
    // mode, open tails and `screen` of a variable, each in a DM of its own
    // that `main` calls in turn; its functions also consult a sibling app's
    // file through `$SITLOG_HOME`.
    // ... and a DM that no task reaches by name, broken as the original
    // runs it (left out: W0232).
    write(
        &root,
        "apps/all/models",
        "'main.dm'.\n'tools/helper.dm'.\n'tools/helper_copy.dm'.\n'tools/broken.dm'.\n",
    );
    write(
        &root,
        "apps/all/tools/broken.dm",
        &TASK_B.replace("diag_mod(b,", "diag_mod(broken,"),
    );
    write(
        &root,
        "apps/all/user_functions.pl",
        &format!("{SHOP_FUNCTIONS}{KB_FUNCTIONS}:- consult('$SITLOG_HOME/apps/other/extra.pl').\n"),
    );
    write(&root, "apps/other/extra.pl", "extra_fact(yes).\n");
    write(&root, "apps/all/templates.pl", CAPTIONS);
    write(&root, "apps/all/in.txt", WRAP_SCRIPT);
    let mut main = String::from("diag_mod(main,\n  [ ");
    let parts = ["shop", "kb", "wrap", "tails", "caps", "inarg"];
    for (i, part) in parts.iter().enumerate() {
        let next = parts.get(i + 1).unwrap_or(&"fs");
        main.push_str(&format!(
            "[ id ==> {part}, type ==> recursive, embedded_dm ==> {part}_dm,\n      \
             arcs ==> [ fs : empty => {next} ] ],\n    "
        ));
    }
    main.push_str("[ id ==> fs, type ==> final ] ],\n  []).\n");
    for part in parts {
        let dm = match part {
            "shop" => shop_dm,
            "kb" => kb_dm,
            "wrap" => wrap_dm,
            "tails" => tails_dm,
            "inarg" => inarg_dm,
            _ => caps_dm,
        };
        main.push_str(&dm(&format!("{part}_dm")));
    }
    write(&root, "apps/all/main.dm", &main);
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

/// The original's applications run unmodified under `--legacy`: every
/// successful check in one application (`apps/all`, see [`tree`]), run
/// twice, so that two engine starts serve them all:
///
/// - from inside the tree, `SITLOG_HOME` found from the application's
///   directory, with the KB layer as it is (`--legacy-kb prolog`, the
///   default);
/// - from elsewhere with `--sitlog-home`, the KB layer served natively.
///
/// What each part checks: the shop (the original's decision maker, its
/// KB text in SWI syntax, cam2nav, a DM defined twice identically: W0203);
/// the KB layer (its services, an update saved and read back in a form the
/// layer reads, a predicate sitlog-kb does not serve); test mode's
/// situation types as the original gives them (`detect_body` gets the term
/// typed, `listening` the word, `see_pointing_follow` three numbers); a DM
/// call's open tails closed as the original's evaluator of lists closes
/// them; `screen(X)` of an unbound `X` showing the first caption (the
/// original's service clause for `screen([A|Rest])` and its message
/// formatter); the tree is the application: a consult of a sibling
/// app's file by a `$SITLOG_HOME` path needs no `--allow-os`; and a broken
/// DM that `main` does not reach is left out (W0232), as the original never
/// looks into it.
#[test]
fn runs_an_application_of_the_original_unmodified() {
    let root = tree("run");
    let script = root.join("apps/all/in.txt");
    let pristine = std::fs::read_to_string(root.join("knowledge_base/shop.kb")).unwrap();
    let prolog = sitlogc()
        .current_dir(&root)
        .args(["run", "apps/all", "--legacy", "--script", "apps/all/in.txt"])
        .env_remove("SITLOG_HOME")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&prolog.stderr);
    assert_eq!(prolog.status.code(), Some(0), "{stderr}");
    let said = lines(&stderr, "Golem says: ");
    assert_eq!(said.len(), 14, "{stderr}");
    assert_eq!(said[..4], SHOP_SAID, "{stderr}");
    assert_eq!(said[4..6], KB_SAID, "{stderr}");
    assert_eq!(said[6..9], WRAP_SAID, "{stderr}");
    // pick([First|Rest]) was called as pick([First]): no open tail, and the
    // caller's Rest is [] afterwards.
    assert!(
        said[9].contains("[[a]]") && !said[9].contains('|'),
        "{stderr}"
    );
    assert!(said[10].contains("[]"), "{stderr}");
    // in_arg patterns the pipe does not match are skipped as the original
    // skips them (D-8): `f(A, b)` against `f(1, c)` leaves `A` unbound (the
    // partial binding undone), the pipe goes on unchanged to the callee of
    // a recursive situation whose own in_arg did not match, and a final
    // situation's ends the DM.
    assert!(said[11].starts_with("seen(_"), "{stderr}");
    assert_eq!(said[12], "got(f(1,c))", "{stderr}");
    assert!(said[13].starts_with("back(_"), "{stderr}");
    assert_eq!(
        lines(&stderr, "Golem prints on screen: "),
        ["Welcome to the shop", "shown([caption(greet)])"],
        "{stderr}"
    );
    // The DM defined twice identically: a warning, the first is used.
    assert!(stderr.contains("W0203"), "{stderr}");
    // The broken DM no task reaches: left out, with a warning.
    assert!(
        stderr.contains("W0232") && stderr.contains("broken.dm:1:10"),
        "{stderr}"
    );
    // The update was saved by the layer's own clause (writeq, one line), in
    // a form the layer reads back.
    let kb = root.join("knowledge_base/shop.kb");
    let saved = std::fs::read_to_string(&kb).unwrap();
    assert!(
        saved.contains("small") && !saved.contains(",\nclass("),
        "{saved}"
    );
    // Again from another directory with --sitlog-home, the KB layer served
    // by sitlog-kb: the same words, the KB written by sitlog-kb (one class
    // a line).
    std::fs::write(&kb, &pristine).unwrap();
    let native = sitlogc()
        .args(["run", "--legacy", "--legacy-kb", "native", "--sitlog-home"])
        .arg(&root)
        .arg("--script")
        .arg(&script)
        .arg(root.join("apps/all"))
        .env_remove("SITLOG_HOME")
        .env("SITLOGC_CACHE_DIR", root.join("cache"))
        .output()
        .unwrap();
    let native_err = String::from_utf8_lossy(&native.stderr);
    assert_eq!(native.status.code(), Some(0), "{native_err}");
    // The KB-reach analysis was kept for the next task of this tree: one
    // file, its key in its first line.
    let cached: Vec<_> = std::fs::read_dir(root.join("cache/kb_reach"))
        .unwrap()
        .map(|e| std::fs::read_to_string(e.unwrap().path()).unwrap())
        .collect();
    assert!(
        cached.len() == 1 && cached[0].starts_with("sitlog-kb-reach-1 "),
        "{cached:?}"
    );
    assert!(native_err.contains("W0232"), "{native_err}");
    assert_eq!(lines(&native_err, "Golem says: "), said, "{native_err}");
    assert_eq!(
        lines(&native_err, "Golem prints on screen: "),
        lines(&stderr, "Golem prints on screen: ")
    );
    let saved = std::fs::read_to_string(&kb).unwrap();
    assert!(
        saved.contains("small") && saved.contains(",\nclass("),
        "{saved}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

/// Where `--legacy` differs, our own applications keep their semantics:
/// a DM defined twice is an error (E0201), `listening` gets `said(yes)`
/// and `detect_body` the term as typed (the task stops at its first
/// situation), a DM call keeps its open tails, `screen(X)` shows no
/// caption; an in_arg the pipe does not match is skipped as under
/// `--legacy` (D-8, the default since issue 39), with a warning on stderr
/// per situation, at the in_arg.
#[test]
fn without_legacy_the_same_applications_keep_our_semantics() {
    let root = tree("ours");
    let plain = sitlogc()
        .current_dir(&root)
        .args(["run", "apps/shop", "--allow-unresolved"])
        .output()
        .unwrap();
    assert_eq!(plain.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&plain.stderr).contains("E0201"));
    write(&root, "apps/wrap/main.dm", &wrap_dm("main"));
    write(&root, "apps/wrap/in.txt", WRAP_SCRIPT);
    write(&root, "apps/tails/main.dm", &tails_dm("main"));
    write(&root, "apps/caps/main.dm", &caps_dm("main"));
    write(&root, "apps/caps/templates.pl", CAPTIONS);
    write(&root, "apps/inarg/main.dm", &inarg_dm("main"));
    for app in ["wrap", "tails", "caps", "inarg"] {
        write(&root, &format!("apps/{app}/models"), "'main.dm'.\n");
    }
    let out = sitlogc()
        .current_dir(&root)
        .args(["run", "apps/wrap", "--script", "apps/wrap/in.txt"])
        .output()
        .unwrap();
    assert_ne!(out.status.code(), Some(0));
    let run = |app: &str, prefix: &str| {
        let out = sitlogc()
            .current_dir(&root)
            .args(["run", app])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(out.status.code(), Some(0), "{stderr}");
        lines(&stderr, prefix)
            .into_iter()
            .map(str::to_owned)
            .collect::<Vec<_>>()
    };
    let ours = run("apps/tails", "Golem says: ");
    assert!(ours[0].contains('|'), "{ours:?}");
    let ours = run("apps/caps", "Golem prints on screen: ");
    assert!(!ours.iter().any(|l| l.contains("Welcome")), "{ours:?}");
    let out = sitlogc()
        .current_dir(&root)
        .args(["run", "apps/inarg"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let said = lines(&stderr, "Golem says: ");
    assert_eq!(said.len(), 3, "{stderr}");
    assert!(said[0].starts_with("seen(_"), "{stderr}");
    assert_eq!(said[1], "got(f(1,c))", "{stderr}");
    assert!(said[2].starts_with("back(_"), "{stderr}");
    let warned = lines(&stderr, "warning: in DM `main`, situation ");
    assert_eq!(warned.len(), 3, "{stderr}");
    assert!(
        warned[0].starts_with("`s1` (")
            && warned[0].contains("main.dm:4:")
            && warned[0]
                .contains("in_arg `f(_G0,b)` does not match the incoming pipe value `f(1,c)`"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

/// The original's tree is found from the application's directory, named by
/// `--sitlog-home` or by `SITLOG_HOME` (the successful runs of the first two:
/// [`runs_an_application_of_the_original_unmodified`]); here, what is refused.
#[test]
fn sitlog_home_is_explicit_or_from_the_environment() {
    let root = tree("home");
    let app = root.join("apps/shop");
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
        crate::support::temp_root().join(format!("sitlogc-legacy-none-{}", std::process::id()));
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
        .env("SITLOGC_CACHE_DIR", root.join("cache"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert_eq!(lines(&stderr, "Golem says: "), KB_SAID, "{stderr}");
    // Saved by the layer's own clause (writeq, one line), `odd` kept.
    let saved = std::fs::read_to_string(root.join("knowledge_base/shop.kb")).unwrap();
    assert!(
        saved.contains("small") && saved.contains("[odd]") && !saved.contains(",\nclass("),
        "{saved}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

/// Under `--legacy` the original's tree is the application (a consult of a
/// sibling app's file by a `$SITLOG_HOME` path runs without `--allow-os`:
/// [`runs_an_application_of_the_original_unmodified`]), but a file outside
/// the tree is still refused.
#[test]
fn a_file_outside_the_original_tree_is_refused_under_legacy() {
    let root = tree("sibling");
    let functions = root.join("apps/shop/user_functions.pl");
    let elsewhere = crate::support::temp_root().join(format!(
        "sitlogc-legacy-elsewhere-{}.pl",
        std::process::id()
    ));
    std::fs::write(&elsewhere, "elsewhere_fact(yes).\n").unwrap();
    std::fs::write(
        &functions,
        format!("{SHOP_FUNCTIONS}\n:- consult('{}').\n", elsewhere.display()),
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

/// The dispatcher of the original's applications: `main` runs the task
/// typed (`res(T).`), a DM named at run time.
const DISPATCH: &str = r#"diag_mod(main,
  [ [ id ==> is, type ==> keyboard, arcs ==> [ res(T) : empty => go(T) ] ],
    [ id ==> go(T), type ==> recursive, embedded_dm ==> T, arcs ==> [ fs : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#;

const TASK_A: &str = "diag_mod(a, [ [ id ==> is, type ==> neutral, arcs ==> [ empty : say(done) => fs ] ],\n  [ id ==> fs, type ==> final ] ], []).\n";

/// Task `b`'s DM, broken as the original's loader does not see: a type
/// that is no type (E0230), arcs that are no list (E0104), a situation
/// without `id` (E0204).
const TASK_B: &str = r#"diag_mod(b,
  [ [ id ==> is, type ==> neutrall, arcs ==> [ empty : say(never) => more ] ],
    [ id ==> more, type ==> neutral, arcs ==> foo ],
    [ type ==> neutral, arcs ==> [ empty : empty => fs ] ],
    [ id ==> fs, type ==> final ] ],
  []).
"#;

/// Issue 39: the original reads every DM file at start (a syntax error in
/// any stops every task) but looks into a DM only when its run reaches it.
/// A run refuses only for errors in what it can reach by name from its main
/// DM; a broken DM it cannot reach is left out with a warning (W0232, at
/// the DM's head), and a call of it by a name computed at run time stops
/// the run there with its first error, located. (`apps/all` of [`tree`]
/// has such a DM too, under `--legacy`.)
#[test]
fn a_broken_dm_refuses_only_the_runs_that_reach_it() {
    let root =
        crate::support::temp_root().join(format!("sitlogc-legacy-tasks-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    write(&root, "tasks/models", "'main.dm'.\n'a.dm'.\n'b.dm'.\n");
    write(&root, "tasks/main.dm", DISPATCH);
    write(&root, "tasks/a.dm", TASK_A);
    write(&root, "tasks/b.dm", TASK_B);
    write(&root, "a.txt", "res(a).\n");
    write(&root, "b.txt", "res(b).\n");
    let run = |args: &[&str]| {
        let out = sitlogc()
            .current_dir(&root)
            .args(["run", "tasks"])
            .args(args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        (out.status.code(), stderr)
    };
    // Task a, named (`--main a`) or typed: runs to its end, b left out.
    for args in [&["--main", "a"][..], &["--script", "a.txt"]] {
        let (code, stderr) = run(args);
        assert_eq!(code, Some(0), "{args:?}: {stderr}");
        assert!(stderr.contains("Golem says: done"), "{stderr}");
        assert!(
            stderr.contains("[W0232] Warning") && stderr.contains("b.dm:1:10"),
            "{args:?}: {stderr}"
        );
        assert!(!stderr.contains("] Error"), "{args:?}: {stderr}");
    }
    // Task b named: refused with its errors, located.
    let (code, stderr) = run(&["--main", "b"]);
    assert_eq!(code, Some(1), "{stderr}");
    for located in ["E0230", "b.dm:2:27", "E0104", "b.dm:3:47", "E0204"] {
        assert!(stderr.contains(located), "{located}: {stderr}");
    }
    // A main DM that does not exist: every error is said.
    let (code, stderr) = run(&["--main", "c"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("E0230") && !stderr.contains("W0232"),
        "{stderr}"
    );
    // Task b typed: the call stops the run with b's first error, located.
    let (code, stderr) = run(&["--script", "b.txt"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("DM `b/0` was left out of this run")
            && stderr.contains("b.dm:2:27: error[E0230]"),
        "{stderr}"
    );
    assert!(!stderr.contains("Golem says: never"), "{stderr}");
    // A syntax error in b stops every task at start, as the original's
    // `read/1` of every DM file does.
    write(
        &root,
        "tasks/b.dm",
        &TASK_B.replace("final ] ],", "final ] ,"),
    );
    let (code, stderr) = run(&["--main", "a"]);
    assert_ne!(code, Some(0), "{stderr}");
    assert!(
        stderr.contains("E0001") && stderr.contains("b.dm:"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

/// The hunt's program 07 (`[First|Rest]` as an expectation) under
/// `--legacy`: the expectation's open tail is closed as the original's
/// evaluator closes it (`[First]`), so the input `[kitchen, hall]` never
/// meets it and the run reads until its input ends, as the original does
/// (`tests/conformance/hunt.sh`: `original: stops`); without `--legacy` it
/// meets it (`Rest = [hall]`).
#[test]
fn legacy_closes_an_expectations_open_tail() {
    let root = tree("expect-tail");
    let hunt = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/hunt/07_unbound_tail");
    for f in ["main.dm", "script.txt"] {
        write(
            &root,
            &format!("apps/tail/{f}"),
            &std::fs::read_to_string(hunt.join(f)).unwrap(),
        );
    }
    write(&root, "apps/tail/models", "'main.dm'.\n");
    let run = |legacy: bool| {
        let mut cmd = sitlogc();
        cmd.current_dir(&root)
            .args(["run", "apps/tail", "--script", "apps/tail/script.txt"])
            .args(["--format", "json"])
            .env_remove("SITLOG_HOME");
        if legacy {
            cmd.arg("--legacy");
        }
        let out = cmd.output().unwrap();
        let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        (report, String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (report, stderr) = run(true);
    assert_eq!(report["status"], "error", "{report} {stderr}");
    assert!(
        report["error"].as_str().unwrap().contains("end of input"),
        "{report}"
    );
    assert!(
        stderr.contains("the input `[kitchen,hall]` meets none of the expectations [[_G0]]"),
        "{stderr}"
    );
    let (report, stderr) = run(false);
    assert_eq!(report["status"], "ok", "{report} {stderr}");
    let _ = std::fs::remove_dir_all(&root);
}
