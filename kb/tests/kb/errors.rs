//! Malformed KBs, queries and updates: exact `sitlogc kb` error lines.
use crate::common;
use sitlog_kb::{answer_line, Kb};
use std::path::PathBuf;

fn load_err(text: &str) -> String {
    Kb::parse(text, "f.kb")
        .err()
        .map(|e| e.to_string())
        .unwrap_or_else(|| "loaded".into())
}

#[test]
fn kb_shape_errors_have_positions() {
    assert_eq!(load_err("foo"), "f.kb:1:1: error: a KB must be a list of class(Id, Mother, Properties, Relations, Individuals) terms");
    assert_eq!(
        load_err("[class(top,none,[],[],[]),\n  klass(a)]"),
        "f.kb:2:3: error: expected class(Id, Mother, Properties, Relations, Individuals)"
    );
    assert_eq!(
        load_err("[class(a,none,[],[],[])]"),
        "f.kb:1:1: error: the KB has no class `top`"
    );
    assert_eq!(
        load_err("[class(top,none,[],[],[]),\nclass(a,nowhere,[],[],[])]"),
        "f.kb:2:9: error: unknown mother class `nowhere` of class `a`"
    );
    assert_eq!(
        load_err("[class(top,none,[],[],[]),class(a,b,[],[],[]),class(b,a,[],[],[])]"),
        "f.kb:1:35: error: class `a` is in a cycle of the class hierarchy"
    );
    assert_eq!(
        load_err("[class(top,none,[],[],[]),class(a,top,[],[],[]),class(a,top,[],[],[])]"),
        "f.kb:1:55: error: duplicate class `a`"
    );
    assert_eq!(
        load_err("[class(top,none,[],[],[]),class(a,top,[],[],[[id=>x,[],[]]]),class(b,top,[],[],[[id=>x,[],[]]])]"),
        "f.kb:1:86: error: duplicate individual `x`"
    );
    assert_eq!(
        load_err("[class(top,none,[[fly,yes]],[],[])]"),
        "f.kb:1:23: error: the weight must be a number"
    );
    assert_eq!(
        load_err("[class(top,none,[[fly,1]],[],[])]"),
        "f.kb:1:19: error: an entry with a non-zero weight must be a conditional default Antecedent=>>Consequent"
    );
    assert_eq!(
        load_err("[class(top,none,[fly],[],[])]"),
        "f.kb:1:18: error: expected [Entry, Weight]"
    );
    assert_eq!(
        load_err("[class(top,none,[[X,0]],[],[])]"),
        "f.kb:1:19: error: variables are not allowed in a KB"
    );
    assert_eq!(
        load_err("[class(top,none,[],[],[[name=>x,[],[]]])]"),
        "f.kb:1:25: error: expected id=>Name"
    );
    assert!(load_err("[class(top,none,[],[],[])").starts_with("f.kb:1:"));
    // Both forms load: with and without the final full stop.
    assert_eq!(load_err("[class(top,none,[],[],[])]."), "loaded");
    assert_eq!(load_err("% comment\n[class(top,none,[],[],[])]"), "loaded");
}

fn office() -> PathBuf {
    common::data("office.kb")
}

#[test]
fn query_errors() {
    let q = |s: &str| answer_line(&office(), &[], s).unwrap_err().to_string();
    assert_eq!(
        q("object_property_value(tom, found_in)"),
        "<query>:1:1: error: unknown KB service object_property_value/2"
    );
    assert_eq!(
        q("no_such(tom, X)"),
        "<query>:1:1: error: unknown KB service no_such/2"
    );
    assert_eq!(
        q("object_property_value(tom, found_in, canteen)"),
        "<query>:1:38: error: the answer (last argument) must be a variable"
    );
    assert_eq!(
        q("object_property_value(T, found_in, X)"),
        "<query>:1:23: error: arguments other than the answer must not contain variables"
    );
    assert!(q("object_property_value(tom, ").starts_with("<query>:1:"));
    assert_eq!(q("42"), "<query>:1:1: error: expected a service call such as object_property_value(ana, found_in, X)");
}

#[test]
fn update_errors() {
    let d = |dos: &[&str]| {
        let dos: Vec<String> = dos.iter().map(|s| s.to_string()).collect();
        answer_line(&office(), &dos, "property_extension(late, X)")
            .unwrap_err()
            .to_string()
    };
    assert_eq!(
        d(&["add_object_property(ivy, late)"]),
        "<do-1>:1:1: error: unknown KB service add_object_property/2"
    );
    assert_eq!(
        d(&["add_object(x, staff)", "add_object(Y, staff)"]),
        "<do-2>:1:12: error: arguments other than the answer must not contain variables"
    );
    assert!(d(&["add_object(x, staff"]).starts_with("<do-1>:1:"));
    let missing = answer_line(
        &PathBuf::from("/nonexistent/kb.kb"),
        &[],
        "class_extension(top, X)",
    )
    .unwrap_err()
    .to_string();
    assert!(
        missing.starts_with("/nonexistent/kb.kb: error: cannot read the KB"),
        "{missing}"
    );
}

#[test]
fn columns_count_characters() {
    assert_eq!(
        load_err("% ñandú\n[class(top,none,[],[],[]),\n  ñ(a)]"),
        "f.kb:3:3: error: expected class(Id, Mother, Properties, Relations, Individuals)"
    );
}
