//! The update services: effects and quirks as measured against the
//! original (SWI-Prolog), and failing updates leaving the KB unchanged.
//! Each test names the update and the query service it uses.
use crate::common;
use common::ask;
use sitlog_kb::Kb;

const KB: &str = include_str!("../data/updates.kb");

#[test]
fn rm_object_cancels_relations_and_flattens_lists_object_relations() {
    assert_eq!(
        ask(KB, &["rm_object(pc1)"], "object_relations(i, X)"),
        "[uses=>pc2]"
    );
    // A one-element list value becomes plain; an empty one goes (quirk).
    assert_eq!(ask(KB, &["rm_object(pc1)"], "class_relations(c, X)"), "[]");
    assert_eq!(
        ask(KB, &["rm_object(pc1)"], "class_extension(top, X)"),
        "[i,pc2,j]"
    );
    // Even for a missing individual the relation lists are normalised.
    assert_eq!(
        ask(KB, &["rm_object(nobody)"], "object_relations(i, X)"),
        "[uses=>[pc1,pc2],owner=>pc1,not(sees=>pc1)]"
    );
}

#[test]
fn change_object_name_renames_relations_not_list_items_object_relations() {
    assert_eq!(
        ask(
            KB,
            &["change_object_name(pc1, laptop)"],
            "object_relations(i, X)"
        ),
        "[uses=>[pc1,pc2],owner=>laptop,not(sees=>laptop),spare=>[]]"
    );
    assert_eq!(
        ask(
            KB,
            &["change_object_name(pc1, laptop)"],
            "object_relations(pc2, X)"
        ),
        "[near=>laptop,uses=>[pc1]]"
    );
    // Renaming onto an existing individual fails.
    assert_eq!(
        ask(
            KB,
            &["change_object_name(pc1, pc2)"],
            "object_relations(pc2, X)"
        ),
        "false"
    );
}

#[test]
fn change_weight_moves_the_default_to_the_end_object_property_value() {
    // Equal weights: the later-declared default wins ...
    assert_eq!(ask(KB, &[], "object_property_value(j, loc, X)"), "b");
    // ... and re-adding `a` with the same weight makes it the later one.
    assert_eq!(
        ask(
            KB,
            &["change_weight_class_property_preference(c, '-'=>>loc=>a, 2)"],
            "object_property_value(j, loc, X)"
        ),
        "a"
    );
}

#[test]
fn change_value_object_relation_needs_existing_objects() {
    assert_eq!(
        ask(
            KB,
            &["change_value_object_relation(i, owner, pc2)"],
            "object_relations(i, X)"
        ),
        "[uses=>[pc1,pc2],not(sees=>pc1),spare=>[],owner=>pc2]"
    );
    assert_eq!(
        ask(
            KB,
            &["change_value_object_relation(i, owner, nothing)"],
            "object_relations(i, X)"
        ),
        "false"
    );
    assert_eq!(
        ask(
            KB,
            &["change_value_object_relation(i, owner, [pc1,pc2])"],
            "object_relations(i, X)"
        ),
        "[uses=>[pc1,pc2],not(sees=>pc1),spare=>[],owner=>[pc1,pc2]]"
    );
}

#[test]
fn property_updates_object_properties() {
    assert_eq!(
        ask(
            KB,
            &["rm_object_property(i, colour)"],
            "object_properties(i, X)"
        ),
        "[loc=>b]"
    );
    assert_eq!(
        ask(
            KB,
            &["change_value_object_property(i, colour, blue)"],
            "object_properties(i, X)"
        ),
        "[colour=>blue,loc=>b]"
    );
    assert_eq!(
        ask(
            KB,
            &[
                "add_object_property(i, fast, yes)",
                "add_object_property(i, big, no)"
            ],
            "object_properties(i, X)"
        ),
        "[colour=>red,not(colour),fast,not(big),loc=>b]"
    );
    // A missing individual: nothing changes, the update does not fail.
    assert_eq!(
        ask(
            KB,
            &["add_object_property(ghost, a, b)"],
            "object_properties(i, X)"
        ),
        "[colour=>red,not(colour),loc=>b]"
    );
}

#[test]
fn relation_updates_object_relations() {
    assert_eq!(
        ask(
            KB,
            &["rm_object_relation(i, not(sees))"],
            "object_relations(i, X)"
        ),
        "[uses=>[pc1,pc2],owner=>pc1,spare=>[]]"
    );
    assert_eq!(
        ask(
            KB,
            &["rm_object_relation(i, uses)"],
            "object_relation_value(i, uses, X)"
        ),
        "[pc1]"
    );
    assert_eq!(
        ask(
            KB,
            &["add_object_relation(i, likes, pc2)"],
            "object_relation_value(i, likes, X)"
        ),
        "pc2"
    );
}

#[test]
fn class_updates_class_extension() {
    assert_eq!(ask(KB, &["rm_class(c)"], "class_extension(top, X)"), "[j]");
    assert_eq!(
        ask(KB, &["rm_class(c)"], "descendants_of_a_class(top, X)"),
        "[d]"
    );
    assert_eq!(
        ask(
            KB,
            &["change_object_class(j, c)"],
            "class_extension(top, X)"
        ),
        "[j,i,pc1,pc2]"
    );
    assert_eq!(
        ask(
            KB,
            &["change_class_name(c, machine)"],
            "class_ancestors(d, X)"
        ),
        "[machine,top]"
    );
    assert_eq!(
        ask(KB, &["add_object(pc3, c)"], "class_extension(c, X)"),
        "[i,pc1,pc2,pc3,j]"
    );
    assert_eq!(
        ask(KB, &["add_class(e, c)"], "sons_of_class(c, X)"),
        "[d,e]"
    );
    assert_eq!(
        ask(
            KB,
            &[
                "add_class(e, c)",
                "add_class_property(e, shiny, yes)",
                "add_object(x, e)"
            ],
            "object_property_value(x, shiny, X)"
        ),
        "yes"
    );
}

#[test]
fn updates_that_would_corrupt_the_kb_fail() {
    for bad in [
        "add_class(zz, nomother)",
        "add_class(c, top)",
        "add_object(i, c)",
        "rm_class(top)",
        "change_class_name(c, d)",
        "change_object_class(i, nowhere)",
        "change_object_class(ghost, c)",
        "add_class_property_preference(c, '-'=>>a, 0)",
        "add_object_property_preference(i, notarule, 3)",
    ] {
        let mut kb = Kb::parse(KB, "kb").unwrap();
        let before = kb.to_text();
        assert!(!kb.apply(bad).unwrap(), "{bad}");
        assert_eq!(kb.to_text(), before, "{bad} changed the KB");
    }
}

#[test]
fn answer_line_stops_at_a_failing_update() {
    let path = common::data("updates.kb");
    let out = sitlog_kb::answer_line(
        &path,
        &["add_class(zz, nomother)".into(), "add_object(q, c)".into()],
        "class_extension(c, X)",
    );
    assert_eq!(out.unwrap(), "false");
}
