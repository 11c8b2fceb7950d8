//! The five `sitlogc kb` examples of kb.md section 6, output for output.
use crate::common;
use common::ask_file;

#[test]
fn object_property_value_chains_defaults_forward() {
    assert_eq!(
        ask_file("office.kb", &[], "object_property_value(tom, found_in, X)"),
        "canteen"
    );
}

#[test]
fn property_extension_reports_yes_and_no() {
    assert_eq!(
        ask_file("office.kb", &[], "property_extension(stressed, X)"),
        "[tom:yes,ivy:no]"
    );
}

#[test]
fn explanation_of_individual_after_an_update() {
    assert_eq!(
        ask_file(
            "office.kb",
            &["add_object_property(ivy, late, yes)"],
            "explanation_of_individual(ivy, E)"
        ),
        "[(found_in=>canteen):stressed,stressed:late]"
    );
}

#[test]
fn properties_of_individual_after_an_update() {
    assert_eq!(
        ask_file(
            "office.kb",
            &["add_object_property(ivy, late, yes)"],
            "properties_of_individual(ivy, P)"
        ),
        "[not(stressed),late,found_in=>canteen]"
    );
}

#[test]
fn explanation_of_an_unknown_individual_fails() {
    assert_eq!(
        ask_file("office.kb", &[], "explanation_of_individual(bob, E)"),
        "false"
    );
}
