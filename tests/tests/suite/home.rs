//! The home butler (`dms/apps/home`, the 2021 paper's Section 9) on the
//! simulated world: the paper's conversation on the application's own
//! world, and variants of that world that must make the robot act
//! differently, each a golden transcript (insta). Every run is made twice,
//! on the interpreter and on the code `tests/build.rs` generated, and the
//! two must print the same transcript and report.

use sitlog_tests::compiled::generated::apps_home;
use sitlog_tests::scenario::{both, edit};
use sitlog_tests::workspace;
use std::path::PathBuf;

fn app() -> PathBuf {
    workspace().join("dms/apps/home")
}

fn base_world() -> String {
    std::fs::read_to_string(app().join("world.toml")).unwrap()
}

/// Runs `world` on both back ends; they must agree; the run must end ok.
fn run(world: &str) -> String {
    both(
        &app(),
        apps_home::program(),
        sitlog_tests::scenario::compiled_functions(apps_home::PROLOG_SOURCES),
        world,
        None,
    )
}

fn robot_lines(transcript: &str) -> Vec<&str> {
    transcript
        .lines()
        .filter(|l| l.starts_with("Golem: "))
        .collect()
}

#[test]
fn the_papers_conversation() {
    let t = run(&base_world());
    insta::assert_snapshot!("paper", t);
    // The paper's 41 turns: 32 by Golem (some of ours are one turn said in
    // two sentences), 9 by Luis.
    assert_eq!(t.lines().filter(|l| l.starts_with("Luis: ")).count(), 9);
    let golem = robot_lines(&t);
    assert!(golem.contains(&"Golem: The noodles are not in the shelf of food."));
    assert!(golem.contains(&"Golem: I think that the explanation for this is that the coke was misplaced there by your child."));
}

#[test]
fn noodles_already_on_the_food_shelf() {
    let w = edit(
        &base_world(),
        &[(
            "name = \"noodles\"\non = \"shelf_snacks\"",
            "name = \"noodles\"\non = \"shelf_food\"",
        )],
    );
    let t = run(&w);
    insta::assert_snapshot!("noodles_on_food", t);
    assert!(!t.contains("not in the shelf of food"));
    assert!(!t.contains("preferred location"));
}

#[test]
fn coke_on_the_drinks_shelf() {
    let w = edit(
        &base_world(),
        &[(
            "name = \"coke\"\non = \"shelf_snacks\"",
            "name = \"coke\"\non = \"shelf_drinks\"",
        )],
    );
    let t = run(&w);
    insta::assert_snapshot!("coke_on_drinks", t);
    assert!(!t.contains("not in its right place"));
    assert!(t.contains("preferred location of noodles"));
}

#[test]
fn the_user_insists_on_biscuits() {
    let w = edit(
        &base_world(),
        &[("\"no golem noodles are ok\"", "\"yes the biscuits please\"")],
    );
    let t = run(&w);
    insta::assert_snapshot!("biscuits", t);
    assert!(t.contains("Golem: Ok. I will bring you the malz and the biscuits."));
    assert!(t.contains("Here are the biscuits."));
}

#[test]
fn a_grasp_fails_once() {
    let w = format!(
        "{}\n[[fault]]\nkind = \"grasp_fails\"\nobject = \"malz\"\ntimes = 1\n",
        base_world()
    );
    let t = run(&w);
    insta::assert_snapshot!("grasp_fails", t);
    assert!(t.contains("Golem: I could not grasp the malz; I will try again."));
    assert!(t.contains("Golem: I took the malz."));
}

#[test]
fn a_blocked_route_is_rerouted() {
    let w = format!(
        "{}\n[[fault]]\nkind = \"route_blocked\"\nfrom = \"hall\"\nto = \"pantry\"\n",
        base_world()
    );
    let t = run(&w);
    insta::assert_snapshot!("route_blocked", t);
    assert!(t.contains("is blocked; I will take another route."));
    assert!(t.contains("Golem: I took the malz."));
}

#[test]
fn an_utterance_not_understood_is_asked_again() {
    let w = format!(
        "{}\n[[fault]]\nkind = \"mishear\"\nutterance = 5\n",
        base_world()
    );
    let t = run(&w);
    insta::assert_snapshot!("mishear", t);
    assert!(t.contains("Golem: Sorry, I did not understand you."));
    assert!(t.contains("Golem: Ok. I will bring you the malz and the noodles."));
}

#[test]
fn a_good_day_sends_the_user_to_the_dining_room() {
    // After a good day the KB's defaults no longer say `tired`: the user is
    // looked for in the dining room first (asked_comestible), where he is.
    let w = edit(
        &base_world(),
        &[
            ("\"i had a bad day\"", "\"i had a good day\""),
            (
                "after_saying = 7\ndelay = 20.0\nto = \"living_room\"",
                "after_saying = 7\ndelay = 20.0\nto = \"dining_room\"",
            ),
        ],
    );
    let t = run(&w);
    insta::assert_snapshot!("good_day", t);
    assert!(t.contains("I am glad to hear that"));
    assert!(!t.contains("Sorry to hear that"));
}
