//! The machine and the functional language L on small DMs written for each
//! rule of the semantics notes (D-numbers in the test names' comments).

use serde_json::Value;
use sitlog_runtime::machine::Options;
use sitlog_tests::run_sources;

fn run(dm: &str, script: &str) -> Value {
    run_sources(&[("t.dm", dm)], script, "main", None, Options::default())
}

fn run_with_globals(dm: &str, globals: &str, script: &str) -> Value {
    run_sources(
        &[("t.dm", dm), ("global_vars.pl", globals)],
        script,
        "main",
        None,
        Options::default(),
    )
}

/// `situation expectation => action` for every top-level entry.
fn steps(v: &Value) -> Vec<String> {
    v["history"]
        .as_array()
        .unwrap()
        .iter()
        .map(|item| match item {
            Value::Array(inner) => format!("[{} entries]", inner.len()),
            e => format!(
                "{} {} => {}",
                e["situation"].as_str().unwrap(),
                e["expectation"].as_str().unwrap(),
                e["action"].as_str().unwrap()
            ),
        })
        .collect()
}

fn ok(v: &Value) {
    assert_eq!(v["status"], "ok", "{v}");
}

/// One neutral situation whose action is the expression under test.
fn eval_action(expr: &str, locals: &str) -> Value {
    let dm = format!(
        "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : {expr} => fs]], [id ==> fs, type ==> final]], [{locals}])."
    );
    run(&dm, "")
}

fn action_of(expr: &str, locals: &str) -> String {
    let v = eval_action(expr, locals);
    ok(&v);
    v["history"][0]["action"].as_str().unwrap().to_owned()
}

#[test]
fn l_atoms_numbers_variables_and_compounds() {
    // D-28, D-36: atoms, numbers and unknown functors evaluate to themselves.
    assert_eq!(
        action_of("[hello, 42, -1.5, 'a b']", ""),
        "[hello,42,-1.5,'a b']"
    );
    assert_eq!(action_of("unknown_fn(1+2)", ""), "unknown_fn(1+2)");
    assert_eq!(action_of("foo(get(cnt, K))", "cnt ==> 7"), "foo(7)");
}

#[test]
fn l_assign_equals_is() {
    // D-29, D-30, D-31.
    assert_eq!(action_of("[assign(X, get(n, _)), X]", "n ==> 3"), "[3,3]");
    let a = action_of("[Y = q(Z), Y]", "");
    assert!(a.starts_with("[q(_G") && a.ends_with(")]"), "{a}");
    assert_eq!(action_of("[X is 1 + 2 * 3, X]", ""), "[7,7]");
    assert_eq!(action_of("[X is 7 / 2]", ""), "[3.5]");
    let v = eval_action("[a = b]", "");
    assert_eq!(v["status"], "error");
    assert!(
        v["error"].as_str().unwrap().contains("does not unify"),
        "{v}"
    );
}

#[test]
fn l_comparisons_yield_true_or_false() {
    // D-34: arguments evaluated first, never failure.
    assert_eq!(
        action_of(
            "[get(cnt, C) == 7, 3 > 4, 2 =< 2, a \\== b, 1 < 2.5, 3 >= 4]",
            "cnt ==> 7"
        ),
        "[true,false,true,true,true,false]"
    );
}

#[test]
fn l_conditional() {
    // D-35, E6: both `;` and `|` spellings; without `otherwise` it is a plain term.
    assert_eq!(
        action_of("(get(n, N) == 1 -> one ; otherwise -> other)", "n ==> 1"),
        "one"
    );
    assert_eq!(
        action_of("(get(n, N) == 1 -> one | otherwise -> other)", "n ==> 2"),
        "other"
    );
    assert_eq!(action_of("((2 > 1) -> yes ; no)", ""), "true->yes;no");
}

#[test]
fn l_list_operators_and_predicates() {
    // D-32, D-33: called on unevaluated arguments; the value is the last argument.
    assert_eq!(action_of("append([a], [b], L)", ""), "[a,b]");
    assert_eq!(
        action_of(
            "[first([x, y], F), first([], G), rest([x, y], R), last([x, y], La)]",
            ""
        ),
        "[x,non,[y],y]"
    );
    assert_eq!(
        action_of("[push(e, [s], S), pop([h, t], P), pop([], Q)]", ""),
        "[[e,s],h,empty]"
    );
    assert_eq!(
        action_of(
            "[reverse([1, 2, 3], R), length_list([a, b], N), rotate_list([1, 2, 3], T)]",
            ""
        ),
        "[[3,2,1],2,[2,3,1]]"
    );
    assert_eq!(
        action_of(
            "[member(b, [a, b]), member(c, [a, b]), not_member(c, [a, b])]",
            ""
        ),
        "[true,false,true]"
    );
    assert_eq!(
        action_of(
            "[idx_object(1, [a, b, c], E), filter_element(b, [a, b, c, b], F)]",
            ""
        ),
        "[b,[a,c,b]]"
    );
}

#[test]
fn l_get_set_inc_locals_then_globals() {
    // D-38 (the observed example of the notes).
    let dm = "diag_mod(main, [
        [id ==> is, type ==> neutral, prog ==> [set(cnt, 5), inc(cnt, A)],
         arcs ==> [empty : [get(cnt, V), inc(cnt, W), set(glist, [x]), get(gcount, G)] => fs]],
        [id ==> fs, type ==> final]], [cnt ==> 0]).";
    let v = run_with_globals(dm, "glist ==> [].\ngcount ==> 11.\n", "");
    ok(&v);
    assert_eq!(v["history"][0]["action"], "[6,7,[x],11]");
    assert_eq!(v["globals"]["glist"], "[x]");
    // Set to an atom at run time: a default that is never a number is
    // refused by `check` (E0242), so the run-time error is reached this way.
    let v = eval_action("[set(name, bob), inc(name, X)]", "name ==> 0");
    assert_eq!(v["status"], "error");
    assert!(v["error"].as_str().unwrap().contains("not a number"), "{v}");
}

#[test]
fn l_apply_user_functions() {
    // D-37: `when/3` ships with the runtime; an unknown function is an error.
    assert_eq!(
        action_of("apply(when(If, T, F), [1 == 1, yes, no])", ""),
        "yes"
    );
    let v = eval_action("apply(nope(X), [1])", "");
    assert_eq!(v["status"], "error");
    assert!(
        v["error"]
            .as_str()
            .unwrap()
            .contains("no user function `nope/1`"),
        "{v}"
    );
}

#[test]
fn perceptual_last_matching_arc_wins_and_no_match_retries() {
    // D-14, E2: the last unifying arc wins; D-15: no match re-enters the situation.
    let dm = "diag_mod(main, [
        [id ==> is, type ==> speech, arcs ==> [p(X) : one(X) => fs, p(Y) : two(Y) => fs, q : three => fs]]],
        []).";
    let dm = dm.replace("]]],", "]], [id ==> fs, type ==> final]],");
    let v = run(&dm, "zz.\np(7).\n");
    ok(&v);
    assert_eq!(steps(&v), ["is p(7) => two(7)", "fs empty => empty"]);
}

#[test]
fn single_arc_no_match_reads_a_second_term() {
    // E3: with one arc, a non-matching input is followed by a second read.
    let dm = "diag_mod(main, [[id ==> is, type ==> speech, prog ==> [inc(n, _)], arcs ==> [ok : get(n, N) => fs]],
        [id ==> fs, type ==> final]], [n ==> 0]).";
    let v = run(dm, "a.\nb.\nc.\nok.\n");
    ok(&v);
    // a, b: one attempt (two reads); c, ok: second attempt; prog ran twice.
    assert_eq!(steps(&v)[0], "is ok => 2");
}

#[test]
fn end_of_script_is_an_error_with_history_kept() {
    // E4.
    let dm = "diag_mod(main, [[id ==> is, type ==> speech, arcs ==> [a : x => s2]],
        [id ==> s2, type ==> speech, arcs ==> [b : y => fs]], [id ==> fs, type ==> final]], []).";
    let v = run(dm, "a.\n");
    assert_eq!(v["status"], "error");
    assert!(v["error"].as_str().unwrap().contains("end of input"), "{v}");
    assert_eq!(steps(&v), ["is a => x"]);
}

#[test]
fn pipe_flows_and_out_arg_is_evaluated() {
    // D-8, D-9, D-18: in_arg binds the pipe; out_arg's value goes on; without out_arg the pipe flows.
    let dm = "diag_mod(main, [
        [id ==> is, type ==> neutral, in_arg ==> In, out_arg ==> got(In, get(n, _)), arcs ==> [empty : [] => s2]],
        [id ==> s2, type ==> neutral, arcs ==> [empty : [] => fs]],
        [id ==> fs, type ==> final]], [n ==> 3]).";
    let v = run_sources(
        &[("t.dm", dm)],
        "",
        "main",
        Some("start"),
        Options::default(),
    );
    ok(&v);
    assert_eq!(v["out_arg"], "got(start,3)");
}

#[test]
fn situations_with_arguments_select_by_unification() {
    // D-21: the first situation whose id unifies.
    let dm = "diag_mod(main, [
        [id ==> is, type ==> neutral, arcs ==> [empty : [] => s(3)]],
        [id ==> s(1), type ==> neutral, arcs ==> [empty : one => fs]],
        [id ==> s(N), type ==> neutral, arcs ==> [empty : other(N) => (N == 3 -> s(1) ; otherwise -> fs)]],
        [id ==> fs, type ==> final]], []).";
    let v = run(dm, "");
    ok(&v);
    assert_eq!(
        steps(&v),
        [
            "is empty => []",
            "s(3) empty => other(3)",
            "s(1) empty => one",
            "fs empty => empty"
        ]
    );
}

#[test]
fn parameters_by_reference_and_diag_mod() {
    // D-20, D-23: diag_mod binds the caller's variable; exit arcs see it.
    let dm = "diag_mod(main, [
        [id ==> is, type ==> recursive, embedded_dm ==> sub(R), arcs ==> [done : got(R) => fs]],
        [id ==> fs, type ==> final]], []).
      diag_mod(sub(_R), [
        [id ==> s1, type ==> neutral, arcs ==> [empty : work => done]],
        [id ==> done, type ==> final, diag_mod ==> sub(result_ok)]], []).";
    let v = run(dm, "");
    ok(&v);
    assert_eq!(
        steps(&v),
        [
            "[2 entries]",
            "is done => got(result_ok)",
            "fs empty => empty"
        ]
    );
    assert_eq!(v["history"][0][0]["dm"], "sub(result_ok)");
}

#[test]
fn recursive_exit_arc_is_the_first_that_unifies() {
    // D-22, E2; D-24: the embedded history is one element before the entry.
    let dm = "diag_mod(main, [
        [id ==> is, type ==> recursive, embedded_dm ==> sub, arcs ==> [X : first(X) => fs, fin : second => fs]],
        [id ==> fs, type ==> final]], []).
      diag_mod(sub, [[id ==> fin, type ==> final]], []).";
    let v = run(dm, "");
    ok(&v);
    assert_eq!(
        steps(&v),
        ["[1 entries]", "is fin => first(fin)", "fs empty => empty"]
    );
}

#[test]
fn next_situation_that_does_not_exist_is_an_error() {
    // E8: named in the message, history so far kept.
    let dm = "diag_mod(main, [[id ==> is, type ==> neutral, arcs ==> [empty : [] => apply(when(I, a, nowhere), [false, a, nowhere])]],
        [id ==> a, type ==> final]], []).";
    let v = run(dm, "");
    assert_eq!(v["status"], "error");
    let e = v["error"].as_str().unwrap();
    assert!(
        e.contains("no situation `nowhere`") && e.contains("DM `main`"),
        "{e}"
    );
    assert_eq!(steps(&v).len(), 1);
}

#[test]
fn in_arg_mismatch_and_diag_mod_mismatch_are_errors() {
    // E14 (denied: by default the in_arg is skipped as the original
    // skips it, D-8, with a warning: typed.rs), E9.
    let dm = "diag_mod(main, [[id ==> is, type ==> neutral, in_arg ==> foo, arcs ==> [empty : [] => fs]],
        [id ==> fs, type ==> final]], []).";
    let v = run_sources(&[("t.dm", dm)], "", "main", Some("now"), Options::default());
    assert_eq!(v["status"], "ok", "{v}");
    assert_eq!(v["out_arg"], "now", "{v}");
    let denied = Options {
        skip_unmatched_in_arg: false,
        ..Options::default()
    };
    let v = run_sources(&[("t.dm", dm)], "", "main", Some("now"), denied);
    assert!(
        v["error"]
            .as_str()
            .unwrap()
            .contains("in_arg `foo` does not match"),
        "{v}"
    );
    let dm = "diag_mod(main, [[id ==> fs, type ==> final, diag_mod ==> other]], []).";
    let v = run(dm, "");
    assert!(
        v["error"]
            .as_str()
            .unwrap()
            .contains("diag_mod `other` does not match"),
        "{v}"
    );
}

#[test]
fn deep_recursion_runs_on_the_heap() {
    // 100 000 nested DM calls: no Rust recursion per DM.
    let dm = "diag_mod(main, [
        [id ==> is, type ==> recursive, embedded_dm ==> down, arcs ==> [fs : [] => fs]],
        [id ==> fs, type ==> final]], []).
      diag_mod(down, [
        [id ==> is, type ==> neutral, arcs ==> [empty : inc(depth, D) => (D >= 100000 -> fs ; otherwise -> rec)]],
        [id ==> rec, type ==> recursive, embedded_dm ==> down, arcs ==> [fs : [] => fs]],
        [id ==> fs, type ==> final]], []).";
    // (The JSON of a 100 000-deep history is valid but deeper than serde_json
    // parses by default, so this run keeps no history.)
    let options = Options {
        keep_history: false,
        ..Options::default()
    };
    let v = run_sources(
        &[("t.dm", dm), ("global_vars.pl", "depth ==> 0.\n")],
        "",
        "main",
        None,
        options,
    );
    ok(&v);
    assert_eq!(v["globals"]["depth"], "100000");
    // With the history: 100 000 nested lists, printed and dropped without overflow.
    let v = run_sources(
        &[("t.dm", dm), ("global_vars.pl", "depth ==> 0.\n")],
        "",
        "main",
        None,
        Options::default(),
    );
    let text = v.as_str().expect("too deep for serde_json: kept as text");
    assert!(text.starts_with("{\"status\":\"ok\""), "{}", &text[..100]);
    assert_eq!(text.matches("\"dm\":\"down\"").count(), 3 * 100_000 - 1);
}

#[test]
fn long_loop_without_history() {
    // --history none: no history, same result.
    let dm = "diag_mod(main, [
        [id ==> is, type ==> neutral, arcs ==> [empty : inc(n, N) => (N >= 20000 -> fs ; otherwise -> is)]],
        [id ==> fs, type ==> final]], [n ==> 0]).";
    let options = Options {
        keep_history: false,
        gc_threshold: 4096,
        ..Options::default()
    };
    let v = run_sources(&[("t.dm", dm)], "", "main", None, options);
    ok(&v);
    assert_eq!(v["history"], serde_json::json!([]));
}

#[test]
fn recovery_protocol_runs_then_the_situation_again() {
    // D-42a: with `speech ==> ask_again` configured, a non-matching input runs
    // the recovery DM (nested history) and then a new instance of the situation.
    let dm = "diag_mod(main, [
        [id ==> is, type ==> speech, prog ==> [inc(tries, _)], arcs ==> [yes : got(get(tries, T)) => fs, no : [] => fs]],
        [id ==> fs, type ==> final]], [tries ==> 0]).
      diag_mod(ask_again, [
        [id ==> s1, type ==> neutral, arcs ==> [empty : say('Sorry, again?') => done]],
        [id ==> done, type ==> final]], []).";
    let v = run_sources(
        &[
            ("t.dm", dm),
            ("recovery_protocols.pl", "speech ==> ask_again.\n"),
        ],
        "maybe.\nyes.\n",
        "main",
        None,
        Options::default(),
    );
    ok(&v);
    assert_eq!(
        steps(&v),
        ["[2 entries]", "is yes => got(2)", "fs empty => empty"]
    );
    // Without recovery configured: the original's retry (D-15), nothing recorded.
    let v = run(dm, "maybe.\nyes.\n");
    ok(&v);
    assert_eq!(steps(&v), ["is yes => got(2)", "fs empty => empty"]);
}

#[test]
fn a_cyclic_term_is_an_error_not_a_hang() {
    // `X = f(X)` would make a term that no copy or print ends on; as a
    // condition it fails (occurs check), as an action it is an error.
    let dm = "diag_mod(main, [[id ==> is, type ==> neutral,
            arcs ==> [empty : [(Y = g(Y) -> no ; otherwise -> yes), X = f(X)] => fs]],
        [id ==> fs, type ==> final]], []).";
    let v = run(dm, "");
    assert_eq!(v["status"], "error");
    let e = v["error"].as_str().unwrap();
    assert!(e.contains("would make a cyclic term"), "{e}");
}
