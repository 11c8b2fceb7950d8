//! The engine's calling protocol, end to end: variables, history, bindings,
//! term round trips, failures and load errors.

use super::{PrologFunctions, PrologOptions, PrologSource};
use crate::eval::{eval, EvalCtx};
use crate::functions::Functions;
use crate::history::{Entry, Item};
use crate::store::Store;
use crate::term::Term;
use crate::vars::Vars;
use sitlog_syntax::Atom;

const FUNCTIONS: &str = r#"
% reads a local, answers with the SWI-6 conditional style
f(X) :- var_op(get(day, Day)), (X == Day -> A = ok | otherwise -> A = 'not ok'), assign_func_value(A).
g(_) :- get_history(H), get_last_transition(H, T), assign_func_value(T).
bump(V) :- var_op(inc(cnt, N)), var_op(set(glist, [V])), assign_func_value(N).
out(X, Y) :- X = bound(Y), Y = 42, assign_func_value(done).
fails(_) :- fail.
throws(_) :- throw(oops).
novalue(_) :- true.
loop(X) :- loop(X).
echo(X) :- assign_func_value(X).
hist(_) :- get_history(H), assign_func_value(H).
cur(_) :- get_history(H), get_current_DM(H, C), length(C, N), assign_func_value(N).
codes(X) :- X = "ab", assign_func_value(X).
sum(L) :- sum_list(L, S), assign_func_value(S).
member(x, _).
mem(X) :- (member(X, [a]) -> assign_func_value(yes) ; assign_func_value(no)).
tail_atom(_) :- findall(Y, member(Y, [c]), [T]), assign_func_value(f([ab,cd|T])).
tail_char(_) :- findall(Y, member(Y, [c]), [T]), assign_func_value(f([a,b|T])).
set_tail(_) :- findall(Y, member(Y, [y]), [T]), var_op(set(glist, [x|T])), assign_func_value(ok).
compound_tail(_) :- findall(Y, member(Y, [x]), [T]), assign_func_value([a|f(T)]).
cyclic(_) :- findall(Y, member(Y, [c]), [_]), X = f(X), assign_func_value(X).
mk(0, T, T) :- !.
mk(N, T, [N|R]) :- N1 is N - 1, mk(N1, T, R).
mkc(0, T, T) :- !.
mkc(N, T, [a|R]) :- N1 is N - 1, mkc(N1, T, R).
long_tail(_) :- mk(8000, z, L), assign_func_value(L).
long_chars(_) :- mkc(8000, z, L), assign_func_value(f(L)).
long_list(_) :- mk(25000, [], L), assign_func_value(L).
"#;

struct Env {
    /// Held while the test runs: see [`ALONE`].
    _shared: std::sync::RwLockReadGuard<'static, ()>,
    store: Store,
    locals: Vars,
    globals: Vars,
    history: Vec<Item>,
    functions: Functions,
}

/// One engine for all tests (building one takes a while in debug builds).
fn engine() -> &'static PrologFunctions {
    static ENGINE: std::sync::OnceLock<PrologFunctions> = std::sync::OnceLock::new();
    ENGINE.get_or_init(|| {
        PrologFunctions::load(
            &[PrologSource::new("user_functions.pl", FUNCTIONS)],
            PrologOptions {
                inference_limit: 200_000,
                ..Default::default()
            },
        )
        .expect("loads")
    })
}

/// Taken for writing by a test that grows the process by hundreds of MiB
/// (`deep_terms_never_overflow_a_stack`'s million-level term), and for
/// reading by every [`env`]: the engine's memory limit is the growth of the
/// whole process during a call, so an engine call of another test beside
/// such a growth would exceed it.
static ALONE: std::sync::RwLock<()> = std::sync::RwLock::new(());

fn env() -> Env {
    let shared = ALONE.read().unwrap_or_else(|e| e.into_inner());
    let p = engine();
    let mut functions = Functions::standard();
    p.install(&mut functions);
    let mut store = Store::new();
    let locals = Vars::from_entries(vec![
        (Atom::intern("day"), Term::atom(Atom::intern("monday"))),
        (Atom::intern("cnt"), Term::int(5)),
    ]);
    let globals = Vars::from_entries(vec![(Atom::intern("glist"), Term::NIL)]);
    let mut entry = |dm: &str, sit: &str, e: &str, a: &str| {
        let dm = Term::atom(Atom::intern(dm));
        let situation = Term::atom(Atom::intern(sit));
        let expectation = store.parse(e).unwrap().0;
        let action = store.parse(a).unwrap().0;
        Item::Entry(Entry {
            dm,
            situation,
            expectation,
            action,
        })
    };
    let history = vec![
        entry("main", "is", "[day(tuesday)]", "[date(monday)]"),
        Item::Nested(vec![entry("wait", "is", "loop", "[1]")]),
        entry("main", "rs", "fs2", "screen(x)"),
    ];
    Env {
        _shared: shared,
        store,
        locals,
        globals,
        history,
        functions,
    }
}

fn run(env: &mut Env, src: &str) -> Result<String, String> {
    let (t, _) = env.store.parse(src).unwrap();
    let mut ctx = EvalCtx {
        store: &mut env.store,
        locals: &mut env.locals,
        globals: &mut env.globals,
        history: &env.history,
        functions: &env.functions,
    };
    let v = eval(&mut ctx, t).map_err(|e| e.message)?;
    Ok(env.store.writeq(v))
}

#[test]
fn reads_variables_and_conditional_with_bar() {
    let mut e = env();
    assert_eq!(run(&mut e, "apply(f(X), [monday])").unwrap(), "ok");
    assert_eq!(run(&mut e, "apply(f(X), [sunday])").unwrap(), "'not ok'");
}

#[test]
fn history_helpers() {
    let mut e = env();
    assert_eq!(run(&mut e, "apply(g(X), [_])").unwrap(), "fs2:screen(x)");
    assert_eq!(run(&mut e, "apply(cur(X), [_])").unwrap(), "1");
    let h = run(&mut e, "apply(hist(X), [_])").unwrap();
    assert_eq!(
        h,
        "[main:((is),[day(tuesday)]:[date(monday)]),[wait:((is),loop:[1])],main:(rs,fs2:screen(x))]"
    );
    e.history.clear();
    assert_eq!(run(&mut e, "apply(g(X), [_])").unwrap(), "none");
}

#[test]
fn sets_and_increments_variables() {
    let mut e = env();
    assert_eq!(run(&mut e, "apply(bump(V), [z])").unwrap(), "6");
    assert_eq!(run(&mut e, "get(cnt, C)").unwrap(), "6");
    assert_eq!(run(&mut e, "get(glist, G)").unwrap(), "[z]");
    assert_eq!(
        run(&mut e, "[apply(bump(V), [w]), get(cnt, C)]").unwrap(),
        "[7,7]"
    );
}

#[test]
fn binds_output_variables() {
    let mut e = env();
    assert_eq!(
        run(&mut e, "[apply(out(A, B), [X, Y]), X, Y]").unwrap(),
        "[done,bound(42),42]"
    );
}

#[test]
fn terms_round_trip() {
    let mut e = env();
    for t in [
        "'hello world'",
        "'it''s'",
        "[]",
        "'[]'",
        "{a,b}",
        "123456789012345678901234567890",
        "-123456789012345678901234567890",
        "-7",
        "1.5e300",
        "-2.25",
        "f(- 1, -(1), a:b, (a:-b), (a,b), (a;b), '|'(a,b))",
        "[1,2|T]",
        "'\\n\\t\\\\'",
        "'ünï'",
        "f(X, Y, X)",
        // Names the engine is given bare (`write_atom`), operators among them.
        "f(mod, is, rem, xor, div, dynamic, table, abc_1X)",
        "[mod, is, dynamic, a]",
        "mod(is, rem)",
    ] {
        let src = format!("apply(echo(V), [{t}])");
        let expected = {
            let (v, _) = e.store.parse(t).unwrap();
            e.store.writeq(v)
        };
        let got = run(&mut e, &src).unwrap();
        assert_eq!(
            got.replace(|c: char| c.is_ascii_digit(), ""),
            expected.replace(|c: char| c.is_ascii_digit(), ""),
            "{t}"
        );
    }
    // Strings are SWI-6 code lists.
    assert_eq!(run(&mut e, "apply(codes(V), [_])").unwrap(), "[97,98]");
    // A caller's variable shared by arguments stays shared.
    assert_eq!(
        run(&mut e, "[apply(echo(V), [f(A, A)]), A]")
            .unwrap()
            .replace(|c: char| c.is_ascii_digit(), ""),
        "[f(_G,_G),_G]"
    );
}

#[test]
fn failures_are_errors_naming_the_call() {
    let mut e = env();
    let err = run(&mut e, "apply(fails(X), [1])").unwrap_err();
    assert!(err.contains("fails/1") && err.contains("failed"), "{err}");
    let err = run(&mut e, "apply(throws(X), [1])").unwrap_err();
    assert!(err.contains("throws/1") && err.contains("oops"), "{err}");
    let err = run(&mut e, "apply(novalue(X), [1])").unwrap_err();
    assert!(err.contains("assign_func_value"), "{err}");
    let err = run(&mut e, "apply(loop(X), [1])").unwrap_err();
    assert!(err.contains("inference limit"), "{err}");
    let err = run(&mut e, "apply(missing(X), [1])").unwrap_err();
    assert!(err.contains("no user function `missing/1`"), "{err}");
    // The engine is still fine afterwards.
    assert_eq!(run(&mut e, "apply(f(X), [monday])").unwrap(), "ok");
}

#[test]
fn libraries_yield_to_application_definitions() {
    let mut e = env();
    assert_eq!(run(&mut e, "apply(sum(X), [[1,2,3]])").unwrap(), "6");
    // The application's member/2 wins over library(lists).
    assert_eq!(run(&mut e, "apply(mem(X), [a])").unwrap(), "no");
    assert_eq!(run(&mut e, "apply(mem(X), [x])").unwrap(), "yes");
}

#[test]
fn load_errors_have_positions() {
    // A clause that does not read is skipped, the rest loaded, as
    // SWI-Prolog's consult does (issue 39; `check` warns, W0008).
    let loaded = PrologFunctions::load(
        &[PrologSource::new(
            "uf.pl",
            "bad(X :- .\nok(X) :- assign_func_value(X).\n",
        )],
        PrologOptions::default(),
    );
    assert!(loaded.is_ok(), "{:?}", loaded.err());
    let errs = PrologFunctions::load(
        &[PrologSource::new("uf.pl", "ok(1).\n:- consult(nowhere).\n")],
        PrologOptions::default(),
    )
    .unwrap_err();
    assert!(
        errs[0].line == 2 && errs[0].message.contains("nowhere"),
        "{errs:?}"
    );
    // Errors of the engine itself: a failing directive, a clause it refuses.
    let errs = PrologFunctions::load(
        &[PrologSource::new(
            "uf.pl",
            "ok(1).\n:- fail.\nassign_func_value(_).\nterm_expansion(x, y).\n",
        )],
        PrologOptions::default(),
    )
    .unwrap_err();
    // (a term_expansion/2 of the application is refused: issue 38)
    assert_eq!(errs.len(), 3, "{errs:?}");
    assert!(
        errs.iter()
            .any(|e| e.line == 4 && e.message.contains("term_expansion/2")),
        "{errs:?}"
    );
    assert!(
        errs.iter()
            .any(|e| e.line == 2 && e.message.contains("failed")),
        "{errs:?}"
    );
    assert!(errs.iter().any(|e| e.line == 3), "{errs:?}");
    // A directive runs under the call's memory limit (issue 38: `:- length(L,
    // 100000000).`, a builtin making no inferences, grew to 4.9 GB and
    // aborted); the list here stops growing at 5 M cells.
    let engine = PrologFunctions::load_with(
        &[PrologSource::new("uf.pl", ":- length(L, 5000000).\n")],
        PrologOptions::default(),
        0,
        None,
    )
    .expect("loads");
    let limits = crate::functions::CallLimits {
        heap_bytes: 8 << 20,
        ..Default::default()
    };
    let errs = engine
        .start_with(&crate::trust::Trust::default(), Some(limits), None)
        .unwrap_err();
    assert!(
        errs[0].message.contains(
            "directives exceeded the memory limit of 8 MiB per call (option --prolog-heap-limit)"
        ),
        "{errs:?}"
    );
}

/// Clause positions are found in one pass over a file (they were a scan
/// from its start per clause), the same as a scan gives: columns in
/// characters, a position asked again or earlier rescanned.
#[test]
fn clause_positions_in_one_pass() {
    let text = "a.\n\n  é(x). b.\nc.";
    let scan = |at: usize| {
        let before = &text[..at];
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        (line, col)
    };
    let mut cursor = super::consult::LineCursor::new();
    for at in [0, 4, 6, 12, 16, 16, 5, text.len(), 99] {
        assert_eq!(
            cursor.line_col(text, at),
            scan(at.min(text.len())),
            "at {at}"
        );
    }
}

/// A library file the compiler's loader found elsewhere (issue 30) is
/// consulted by its library name: the source whose name ends with it.
#[test]
fn a_consulted_library_name_is_taken_from_the_sources_given() {
    let library = PrologSource::new("library:/behaviors/lang.pl", "word(hello).\n");
    let app = PrologSource::new(
        "apps/mine/user_functions.pl",
        ":- consult('behaviors/lang.pl').\ngreet :- word(_).\n",
    );
    assert!(PrologFunctions::load(&[library, app.clone()], PrologOptions::default()).is_ok());
    let errs = PrologFunctions::load(&[app], PrologOptions::default()).unwrap_err();
    assert!(errs[0].message.contains("behaviors/lang.pl"), "{errs:?}");
}

#[test]
fn legacy_files_redefine_as_swi_consult() {
    let layer = PrologSource::new(
        "layer.pl",
        "p(a1).\np(a2).\nr(x).\ns(1).\ns(2).\nu(1).\nu(2).\nw(X) :- s(X).\n\
         t(1).\nt(2).\nk(1).\nk(2).\n",
    );
    let app = PrologSource::new(
        "user_functions.pl",
        "p(b).\nadd :- assertz(s(3)).\ncl(L) :- findall(X-B, clause(u(X), B), L).\n\
         rt :- retract(u(1)).\naddt :- assertz(t(3)).\n\
         clk(L) :- retract(k(1)), findall(X-B, clause(k(X), B), L).\n",
    );
    // `R` is the binding query_raw gives back: `yes` when p/1 and r/1
    // have the clauses `want`.
    let has = |p: &PrologFunctions, want: &str| {
        let q = format!(
            "( findall(X, p(X), P), findall(Z, r(Z), Q), [P, Q] == {want} -> R = yes ; R = no )."
        );
        p.query_raw(&q).unwrap().unwrap().contains("yes")
    };
    // The --legacy profile (a layer before the application's files): the
    // later file's clauses replace the earlier file's.
    let legacy = PrologFunctions::load_with(
        &[layer.clone(), app.clone()],
        PrologOptions::default(),
        1,
        None,
    )
    .expect("loads");
    assert!(has(&legacy, "[[b],[x]]"));
    // The layer's predicates are asserted at their first call (a stub
    // until then), or at the first call that changes or looks at their
    // clauses: clauses asserted before the first call come after the
    // layer's, `clause/2` and `retract/1` see the layer's clauses.
    let yes = |p: &PrologFunctions, q: &str| {
        let q = format!("( {q} -> R = yes ; R = no ).");
        p.query_raw(&q).unwrap().unwrap().contains("yes")
    };
    assert!(yes(&legacy, "add, findall(X, w(X), L), L == [1,2,3]"));
    assert!(yes(&legacy, "cl(L), L == [1-true,2-true]"));
    assert!(yes(&legacy, "rt, findall(X, u(X), L), L == [2]"));
    // Called first, a predicate is compiled static; a later call that
    // changes or looks at its clauses makes it dynamic with them
    // (issue 39: a static predicate runs faster).
    assert!(yes(
        &legacy,
        "findall(X, t(X), L), L == [1,2], \\+ predicate_property(t(_), dynamic)"
    ));
    assert!(yes(
        &legacy,
        "addt, findall(X, t(X), L), L == [1,2,3], predicate_property(t(_), dynamic)"
    ));
    assert!(yes(&legacy, "k(2), clk(L), L == [2-true]"));
    drop(legacy);
    // The same with the layer read and asserted ahead by an engine built
    // ahead (`sitlogc run --legacy`): its clauses that the application
    // redefines are retracted, those a later file of the layer redefines
    // never asserted.
    // (`v :- 2`: a clause of the layer the engine refuses is an error at
    // its place too, asserted at load, not at its first call.)
    let layer2 = PrologSource::new("layer2.pl", "r(y).\nv :- true.\nv :- 2.\n");
    let warm = PrologFunctions::warm(Some((vec![layer.clone(), layer2.clone()], None)));
    // A clause the engine refuses is an error at its place, the clauses
    // after it in its batch loaded.
    let app2 = PrologSource::new("user_functions.pl", "p(b).\nq :- 1.\np(c).\n");
    let (ahead, errors) = PrologFunctions::spawn_from(
        warm,
        &[layer.clone(), layer2, app2],
        PrologOptions::default(),
        2,
        None,
    )
    .expect("loads");
    assert_eq!(errors.len(), 2, "{errors:?}");
    assert_eq!((errors[0].file.as_str(), errors[0].line), ("layer2.pl", 3));
    assert_eq!(
        (errors[1].file.as_str(), errors[1].line),
        ("user_functions.pl", 2)
    );
    assert!(has(&ahead, "[[b,c],[y]]"));
    drop(ahead);
    // Our own applications keep every clause.
    let own = PrologFunctions::load(&[layer, app], PrologOptions::default()).expect("loads");
    assert!(has(&own, "[[a1,a2,b],[x]]"));
}

/// The engine's toplevel keeps scryer's directives whole (one a line), so
/// the same libraries are loaded as with scryer's own toplevel.
#[test]
fn the_toplevel_keeps_scryers_directives_whole() {
    let text = super::engine::toplevel();
    for line in text.lines() {
        assert!(
            line == "repl." || (line.starts_with(":- ") && line.ends_with(").")),
            "{line}"
        );
    }
    for library in ["lists", "format", "charsio", "'$atts'"] {
        assert!(
            text.contains(&format!(":- use_module(library({library})).")),
            "{library}"
        );
    }
    assert!(text.contains(":- dynamic(started/0)."));
}

/// Issue 39: a name is written bare when it reads as itself, any other
/// atom quoted.
#[test]
fn names_are_written_bare_other_atoms_quoted() {
    let w = |s: &str| {
        let mut out = String::new();
        super::translate::write_atom(&mut out, Atom::intern(s));
        out
    };
    for plain in ["a", "abc_1X", "mod", "is"] {
        assert_eq!(w(plain), plain);
    }
    assert_eq!(w("Abc"), "'Abc'");
    assert_eq!(w("_x"), "'_x'");
    assert_eq!(w("$x"), "'$x'");
    assert_eq!(w("a-b"), "'a-b'");
    assert_eq!(w("a b"), "'a b'");
    assert_eq!(w("\u{e9}t\u{e9}"), "'\u{e9}t\u{e9}'");
    assert_eq!(w(""), "''");
    assert_eq!(w("-"), "'-'");
    assert_eq!((w("[]"), w("{}")), ("[]".to_owned(), "{}".to_owned()));
}

/// Issue 38: terms of any depth cross between engine and store without
/// recursion on the engine's side (a 500 000-deep answer aborted the
/// process: its copy and drop recursed), and what the engine's reader
/// would overflow on is refused before it is sent, with an error.
#[test]
fn deep_terms_never_overflow_a_stack() {
    use super::translate::{drop_deep, from_prolog};
    use scryer_prolog::Term as PTerm;
    // An engine term a million levels deep: read into the store (stacker)
    // and dropped (iteratively), no other test's engine call beside it.
    let alone = ALONE.write().unwrap_or_else(|e| e.into_inner());
    let mut t = PTerm::Atom("a".into());
    for _ in 0..1_000_000 {
        t = PTerm::Compound("s".into(), vec![t]);
    }
    let mut store = Store::new();
    let mut names = std::collections::HashMap::new();
    let s = from_prolog(&mut store, &t, &mut names);
    drop_deep(t);
    assert!(store.compound_args(s, Atom::intern("s"), 1).is_some());
    drop(store);
    drop(alone);
    // A call whose argument nests deeper than the engine takes.
    let mut e = env();
    let depth = crate::functions::PROLOG_MAX_DEPTH + 1;
    let deep = format!("{}a{}", "s(".repeat(depth), ")".repeat(depth));
    let err = run(&mut e, &format!("apply(echo(X), [{deep}])")).unwrap_err();
    assert!(
        err.contains("`echo/1`") && err.contains("the Prolog engine takes at most 100000"),
        "{err}"
    );
    // A list counts a level per element.
    let long = format!("[{}]", vec!["1"; depth].join(","));
    let err = run(&mut e, &format!("apply(echo(X), [{long}])")).unwrap_err();
    assert!(err.contains("levels deep"), "{err}");
    // Just under the limit, the engine takes it.
    let list = format!("[{}]", vec!["1"; 50_000].join(","));
    assert_eq!(
        run(&mut e, &format!("apply(sum(X), [{list}])")).unwrap(),
        "50000"
    );
}

/// A clause nested deeper than the engine takes is an error at its place,
/// before any engine starts (it aborted the process before).
#[test]
fn a_clause_too_deep_for_the_engine_is_a_located_error() {
    let depth = crate::functions::PROLOG_MAX_DEPTH;
    let text = format!("ok(1).\nd({}a{}).\n", "s(".repeat(depth), ")".repeat(depth));
    let errors = PrologFunctions::load(
        &[PrologSource::new("user_functions.pl", &text)],
        PrologOptions::default(),
    )
    .unwrap_err();
    assert_eq!(errors.len(), 1);
    let shown = errors[0].to_string();
    assert!(
        shown.starts_with("user_functions.pl:2:1: this clause nests 100001 levels deep"),
        "{shown}"
    );
}

/// Issue 38: the history is not sent with every call (it cost time per
/// call, 0.18 s per 1 000 entries for the engine's reader in a debug
/// build, and past 100 000 entries it was deeper than the engine takes):
/// `get_history/1` asks for it, in parts, when a function reads it. A task
/// past 100 000 transitions keeps calling Prolog; what a function reads is
/// the history as it stands, assembled from parts (of two elements in a
/// test build: `history_helpers` reads three).
#[test]
fn a_history_past_the_engines_depth_is_given_on_demand() {
    let mut e = env();
    let n = crate::functions::PROLOG_MAX_DEPTH + 1_500;
    let (m, s, a) = (Atom::intern("m"), Atom::intern("s"), Atom::intern("a"));
    let mut history: Vec<Item> = (0..n)
        .map(|i| {
            Item::Entry(Entry {
                dm: Term::atom(m),
                situation: Term::atom(s),
                expectation: Term::int(i as i64),
                action: Term::atom(a),
            })
        })
        .collect();
    history.insert(1, e.history.swap_remove(1));
    e.history = history;
    // A function that does not read the history costs nothing per entry
    // (before: an error, the history too deep for the engine).
    assert_eq!(run(&mut e, "apply(echo(X), [ok])").unwrap(), "ok");
    // One that reads it gets it in parts (the last five entries here: the
    // engine's reader takes 0.18 s per 1 000 entries in a debug build).
    e.history.drain(..n - 4);
    assert_eq!(
        run(&mut e, "apply(g(X), [_])").unwrap(),
        format!("{}:a", n - 1)
    );
    assert_eq!(run(&mut e, "apply(cur(X), [_])").unwrap(), "5");
}

/// A value with a list whose tail is an atom (`[ab,cd|x]`: `member/2` is the application's here), which scryer's
/// conversion of an answer panicked on (the engine restarted, a
/// backtrace on stderr), and a cyclic value: each an error naming the
/// function and the value, the engine whole (it answers the next call);
/// `[a|f(x)]` is handed over as it is (helper fid20).
#[test]
fn atom_tails_and_cyclic_values_leave_the_engine_whole() {
    let mut e = env();
    let err = run(&mut e, "apply(tail_atom(X), [_])").unwrap_err();
    assert!(
        err.contains("`tail_atom/1`: its value (or what it set) `f([ab,cd|x])` holds a list whose tail is an atom"),
        "{err}"
    );
    // Of one-character atoms (a partial string in the engine).
    let err = run(&mut e, "apply(tail_char(X), [_])").unwrap_err();
    assert!(err.contains("`tail_char/1`: its value"), "{err}");
    let err = run(&mut e, "apply(set_tail(X), [_])").unwrap_err();
    assert!(
        err.contains("`set_tail/1`") && err.contains("g(glist,[x|x])"),
        "{err}"
    );
    let err = run(&mut e, "apply(cyclic(X), [_])").unwrap_err();
    assert!(
        err.contains("`cyclic/1`") && err.contains("cyclic term"),
        "{err}"
    );
    assert_eq!(
        run(&mut e, "apply(compound_tail(X), [_])").unwrap(),
        "[a|f(x)]"
    );
    assert_eq!(run(&mut e, "apply(echo(X), [b])").unwrap(), "b");
}

/// A long list with an atom tail (`[8000, .., 1|z]`, and of
/// one-character atoms, a partial string in the engine, whose whole
/// writing took longer than a call may): the same error as `[a|b]`'s,
/// naming the function, its value written to a depth (helper fid21). A
/// long proper list is handed over. Left: an atom tail past the 20 000
/// nodes the prelude walks is still the engine's internal error (caught
/// quietly, the engine restarted).
#[test]
fn a_long_atom_tailed_list_is_the_same_error() {
    let mut e = env();
    let err = run(&mut e, "apply(long_tail(X), [_])").unwrap_err();
    assert!(
        err.contains("`long_tail/1`: its value (or what it set) `[8000,7999,")
            && err.contains("holds a list whose tail is an atom")
            && err.len() < 600,
        "{err}"
    );
    let err = run(&mut e, "apply(long_chars(X), [_])").unwrap_err();
    assert!(
        err.contains("`long_chars/1`: its value")
            && err.contains("holds a list whose tail is an atom"),
        "{err}"
    );
    let ok = run(&mut e, "apply(long_list(X), [_])").unwrap();
    assert!(
        ok.starts_with("[25000,24999,") && ok.ends_with(",2,1]"),
        "{}",
        &ok[..40]
    );
    assert_eq!(run(&mut e, "apply(echo(X), [b])").unwrap(), "b");
}
