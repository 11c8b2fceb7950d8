//! Conformance with the paper's examples (section 6, Figure 5 / Listing 2;
//! section 9 and Appendix B, Figure 6 / Listing 3). Each test names the
//! service it calls; the KBs, and the repairs to the listings, are in
//! `tests/data/animals.kb` and `tests/data/preferences.kb`.
use crate::common;
use common::ask_file;

fn animals(q: &str) -> String {
    ask_file("animals.kb", &[], q)
}

// --- animals (section 6) ---

#[test]
fn do_birds_fly_yes_class_property_value() {
    assert_eq!(animals("class_property_value(birds, fly, A)"), "yes");
    assert_eq!(animals("class_has_property(birds, fly, A)"), "yes");
}

#[test]
fn do_birds_swim_no_class_property_value() {
    assert_eq!(animals("class_property_value(birds, swim, A)"), "no");
    assert_eq!(animals("class_has_property(birds, swim, A)"), "no");
}

#[test]
fn do_fish_swim_unknown_class_property_value() {
    assert_eq!(animals("class_property_value(fish, swim, A)"), "unknown");
}

#[test]
fn do_penguins_fly_no_class_property_value() {
    assert_eq!(animals("class_property_value(penguins, fly, A)"), "no");
    assert_eq!(animals("class_property_value(penguins, swim, A)"), "yes");
}

#[test]
fn does_arthur_swim_yes_object_property_value() {
    assert_eq!(animals("object_property_value(arthur, swim, A)"), "yes");
    assert_eq!(animals("object_property_value(arthur, fly, A)"), "no");
}

#[test]
fn do_eagles_eat_animals_yes_class_relation_value() {
    // The relation's object is the class `animals`: every eagle eats animals.
    assert_eq!(animals("class_relation_value(eagles, eat, A)"), "animals");
    // relation_extension reads a class object as all its individuals.
    assert_eq!(
        animals("relation_extension(eat, L)"),
        "[pete:[pete,arthur]]"
    );
}

#[test]
fn where_does_pete_live_mexico_object_relation_value() {
    // work=>mexico (weight 3) beats born=>argentina (weight 5).
    assert_eq!(animals("object_relation_value(pete, live, A)"), "mexico");
    assert_eq!(
        animals("relations_of_individual(pete, L)"),
        "[work=>[mexico],born=>[argentina],like=>[mexico],eat=>[pete,arthur],live=>[mexico]]"
    );
}

#[test]
fn why_does_pete_live_in_mexico_explanation_of_individual() {
    // The paper adds live=>mexico to Pete, then asks why: he works there.
    let dos = ["add_object_relation(pete, live, mexico)"];
    assert_eq!(
        ask_file("animals.kb", &dos, "explanation_of_individual(pete, E)"),
        "[(live=>mexico):(work=>mexico)]"
    );
    assert_eq!(
        ask_file("animals.kb", &dos, "explanation_extension(live=>mexico, L)"),
        "[pete:(work=>mexico)]"
    );
}

#[test]
fn class_extension_of_top_and_birds() {
    assert_eq!(animals("class_extension(top, L)"), "[pete,arthur]");
    assert_eq!(animals("class_extension(birds, L)"), "[pete,arthur]");
    assert_eq!(animals("class_extension(fish, L)"), "[]");
    assert_eq!(
        animals("classes_of_individual(pete, L)"),
        "[eagles,birds,animals,top]"
    );
}

// --- preferences (Appendix B) ---

#[test]
fn users_room_after_a_bad_day_back_from_work_object_property_value() {
    let dos = [
        "add_object_property(user, bad_day, yes)",
        "add_object_property(user, back_from_work, yes)",
    ];
    assert_eq!(
        ask_file(
            "preferences.kb",
            &dos,
            "object_property_value(user, found_in, R)"
        ),
        "living_room"
    );
    // Without being back from work, nothing places the user.
    assert_eq!(
        ask_file(
            "preferences.kb",
            &dos[..1],
            "object_property_value(user, found_in, R)"
        ),
        "unknown"
    );
    // Asking for a comestible sends the user to the dining room.
    assert_eq!(
        ask_file(
            "preferences.kb",
            &["add_object_property(user, asked_comestible, yes)"],
            "object_property_value(user, found_in, R)"
        ),
        "dining_room"
    );
}

#[test]
fn noodles_locations_before_and_after_last_seen_object_property_list() {
    assert_eq!(
        ask_file(
            "preferences.kb",
            &[],
            "object_property_list(noodles, loc, L)"
        ),
        "[shelf_food,shelf_snacks,shelf_drinks]"
    );
    let seen = ["change_value_object_property(noodles, last_seen, shelf_drinks)"];
    assert_eq!(
        ask_file(
            "preferences.kb",
            &seen,
            "object_property_list(noodles, loc, L)"
        ),
        "[shelf_drinks,shelf_food,shelf_snacks,shelf_drinks]"
    );
    assert_eq!(
        ask_file(
            "preferences.kb",
            &seen,
            "object_property_value(noodles, loc, L)"
        ),
        "shelf_drinks"
    );
    // B.1: the preferred shelf of a class.
    assert_eq!(
        ask_file("preferences.kb", &[], "class_property_list(drink, loc, L)"),
        "[shelf_drinks,shelf_snacks,shelf_food]"
    );
}

#[test]
fn misplaced_noodles_were_moved_by_the_child_explanation_of_individual() {
    let dos = [
        "change_value_object_property(noodles, last_seen, shelf_drinks)",
        "add_object_property(noodles, misplaced, yes)",
    ];
    assert_eq!(
        ask_file(
            "preferences.kb",
            &dos,
            "explanation_of_individual(noodles, E)"
        ),
        "[(loc=>shelf_drinks):(last_seen=>shelf_drinks),misplaced:(moved_by=>child)]"
    );
    assert_eq!(
        ask_file(
            "preferences.kb",
            &dos,
            "explanation_extension(misplaced, L)"
        ),
        "[noodles:(moved_by=>child)]"
    );
}

#[test]
fn users_choice_swaps_weights_change_weight_object_property_preference() {
    let dos = [
        "add_object_property_preference(noodles, '-'=>>loc=>shelf_snacks, 1)",
        "change_weight_object_property_preference(noodles, '-'=>>loc=>shelf_snacks, 5)",
    ];
    assert_eq!(
        ask_file(
            "preferences.kb",
            &dos,
            "object_property_preference_value(noodles, '-'=>>loc=>shelf_snacks, W)"
        ),
        "5"
    );
    assert_eq!(
        ask_file(
            "preferences.kb",
            &[],
            "object_property_preference_value(noodles, '-'=>>loc=>shelf_food, W)"
        ),
        "2"
    );
}
