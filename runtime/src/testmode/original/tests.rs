//! The original's test mode by situation type: what each kind of type
//! reads and gives, and the table against the original's own clauses.

use super::*;
use crate::testmode::ScriptPerception;

/// What a situation of type `ty` with `expectations` is given from
/// `script`, and how much of the script is left.
fn given(ty: &str, expectations: &[&str], script: &str) -> Result<String, String> {
    let mut store = Store::new();
    let (ty, _) = store.parse(ty).unwrap();
    let exps: Vec<Term> = expectations
        .iter()
        .map(|e| store.parse(e).unwrap().0)
        .collect();
    let inner = ScriptPerception::new("s", script.to_owned());
    let mut p = OriginalTestMode::new(Box::new(inner));
    match p.perceive(&mut store, ty, &exps)? {
        Perceived::Input(t) => Ok(store.writeq(t)),
        other => Ok(format!("{other:?}")),
    }
}

#[test]
fn detection_types_give_detected_and_listening_types_said() {
    assert_eq!(
        given("detect_body(1)", &["detected(X)"], "p1.\n").unwrap(),
        "detected(p1)"
    );
    assert_eq!(
        given("analyzing_crowd(m)", &[], "[a,b].\n").unwrap(),
        "detected([a,b])"
    );
    assert_eq!(given("doas", &[], "[1,2].\n").unwrap(), "doas([1,2])");
    assert_eq!(given("speakerid", &[], "luis.\n").unwrap(), "speaker(luis)");
    assert_eq!(given("listening(lm)", &[], "hi.\n").unwrap(), "said(hi)");
    assert_eq!(
        given("memorize_body(a,b,c)", &[], "hi.\n").unwrap(),
        "said(hi)"
    );
    // `listening` without an argument and `keyboard` give the term as typed
    // (our own test mode wraps the first: the original does not).
    assert_eq!(given("listening", &[], "hi.\n").unwrap(), "hi");
    assert_eq!(given("keyboard", &[], "res(x).\n").unwrap(), "res(x)");
    assert_eq!(given("nkeyboard", &[], "hi.\n").unwrap(), "said(hi)");
}

#[test]
fn types_that_read_several_terms_or_use_the_expectations() {
    assert_eq!(
        given("see_pointing_follow", &[], "1.\n2.\n3.\n").unwrap(),
        "pointing_coords(1,2,3)"
    );
    assert_eq!(
        given("positionxyz", &["pos(X,Y,Z)"], "1.\n2.\n3.\n").unwrap(),
        "pos(1,2,3)"
    );
    assert!(given("positionxyz", &["pos(X,Y,Z)", "b"], "1.\n")
        .unwrap_err()
        .contains("a single expectation pos/3"));
    assert_eq!(
        given(
            "translating_nav",
            &["a", "cam_to_nav(1,2,3,4,5,6,R)"],
            "[0,5].\n"
        )
        .unwrap(),
        "cam_to_nav(1,2,3,4,5,6,[0,5])"
    );
    assert_eq!(
        given("calculate_distance", &["distance_to(door,D)"], "2.5.\n").unwrap(),
        "distance_to(door,2.5)"
    );
    assert_eq!(
        given("direction", &["direction(A)"], "1.25.\n").unwrap(),
        "direction(1.3)"
    );
    assert_eq!(
        given("direction", &["direction(A)"], "2.\n").unwrap(),
        "direction(2)"
    );
    assert!(given("direction", &["direction(A)"], "x.\n")
        .unwrap_err()
        .contains("not a number"));
    assert!(given("walking", &["a", "b"], "x.\n")
        .unwrap_err()
        .contains("at least 3"));
    assert_eq!(given("walking", &["a", "b", "c"], "x.\n").unwrap(), "x");
    assert_eq!(
        given("get_dms", &["cmds2dms(go,D)"], "x.\n").unwrap(),
        "cmds2dms(go,x)"
    );
}

#[test]
fn every_variable_of_what_is_given_is_read_next() {
    // turning reads nothing itself: its unbound result is read.
    assert_eq!(given("turning", &[], "done.\n").unwrap(), "done");
    // grasping_obj reads one term and drops it, then reads its result.
    assert_eq!(given("grasping_obj", &[], "x.\nok.\n").unwrap(), "ok");
    assert_eq!(
        given("keyboard", &[], "f(X,Y,X).\na.\nb.\n").unwrap(),
        "f(a,b,a)"
    );
    assert_eq!(given("gfOrders", &[], "go.\n").unwrap(), "gfOrder(go)");
}

#[test]
fn end_of_input_unknown_types_and_robot_services() {
    assert_eq!(given("detect_body(1)", &[], "").unwrap(), "EndOfInput");
    assert_eq!(
        given("see_pointing_follow", &[], "1.\n").unwrap(),
        "EndOfInput"
    );
    let e = given("translating_arm", &[], "x.\n").unwrap_err();
    assert!(e.contains("no clause of communication_int/3"), "{e}");
    let e = given("person_pose_op", &[], "x.\n").unwrap_err();
    assert!(e.contains("ROS service"), "{e}");
}

/// The table as `tests/conformance/original/wrapping.pl` prints the
/// original's: `NAME/ARITY READS GIVEN` with the terms read being 1.25,
/// 2.25, ... and the expectations the type's pattern.
fn our_table() -> Vec<String> {
    ORIGINAL_TYPES
        .iter()
        .map(|e| {
            let mut store = Store::new();
            let ty = pattern(&mut store, e.name, e.arity);
            let mut exps = match (e.needs, e.reading) {
                (Needs::AtLeast(k), _) => (0..k).map(|_| store.new_var()).collect(),
                (Needs::Single(f, a) | Needs::Member(f, a), _) => vec![pattern(&mut store, f, a)],
                (_, CamToNav) => vec![pattern(&mut store, "cam_to_nav", 7)],
                (_, Cmds2Dms) => vec![pattern(&mut store, "cmds2dms", 2)],
                _ => Vec::new(),
            };
            exps.shrink_to_fit();
            let mut reads = 0;
            let mut read = |_: &mut Store| -> Result<Term, Stop> {
                reads += 1;
                Ok(Term::float(reads as f64 + 0.25))
            };
            let head = format!("{}/{}", e.name, e.arity);
            match build(&mut store, ty, e, &exps, &mut read) {
                Ok(t) => {
                    let t = store.writeq(t);
                    format!("{head} {reads} {t}")
                }
                Err(Stop::Error(m)) if m.contains("ROS") => format!("{head} ros"),
                Err(Stop::Error(m)) => format!("{head} error {m}"),
                Err(Stop::Perceived(p)) => format!("{head} {p:?}"),
            }
        })
        .map(|l| normalise(&l))
        .collect()
}

/// Variables (`A`, `_G12`) as `_`.
fn normalise(line: &str) -> String {
    let mut out = String::new();
    let mut chars = line.chars().peekable();
    let mut prev_word = false;
    while let Some(c) = chars.next() {
        if !prev_word && (c.is_ascii_uppercase() || c == '_') {
            while chars
                .peek()
                .is_some_and(|c| c.is_alphanumeric() || *c == '_')
            {
                chars.next();
            }
            out.push('_');
            prev_word = true;
            continue;
        }
        prev_word = c.is_alphanumeric() || c == '_';
        out.push(c);
    }
    out
}

#[test]
fn the_table_is_the_originals() {
    // Needs the original and SWI-Prolog; skipped without them.
    let Some(home) = std::env::var_os("SITLOG_HOME").filter(|h| !h.is_empty()) else {
        crate::errln!("skipped: SITLOG_HOME not set");
        return;
    };
    let probe = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/conformance/original/wrapping.pl"
    );
    let out = match std::process::Command::new("swipl")
        .args(["-q", probe])
        .env("SITLOG_HOME", &home)
        .output()
    {
        Ok(o) if o.status.success() => String::from_utf8_lossy(&o.stdout).into_owned(),
        Ok(o) => panic!("wrapping.pl failed: {}", String::from_utf8_lossy(&o.stderr)),
        Err(_) => {
            crate::errln!("skipped: swipl not found");
            return;
        }
    };
    let theirs: Vec<String> = out
        .lines()
        // The machine runs neutral situations itself.
        .filter(|l| !l.starts_with("neutral/0 "))
        .map(normalise)
        .collect();
    assert_eq!(our_table(), theirs);
}

#[test]
fn normalise_makes_variables_alike() {
    assert_eq!(
        normalise("get_dms/0 0 cmds2dms(A,_G12)"),
        "get_dms/0 0 cmds2dms(_,_)"
    );
    assert_eq!(
        normalise("gfOrders/0 0 gfOrder(Xy)"),
        "gfOrders/0 0 gfOrder(_)"
    );
}
