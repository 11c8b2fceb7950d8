//! The tests crate's own helpers (its library builds no unit-test binary of
//! its own: one compile and link of the generated applications fewer).

use sitlog_runtime::prolog::PrologSource;
use sitlog_tests::scenario::stateless;

#[test]
fn variables_normalise() {
    use sitlog_tests::normalize_vars;
    assert_eq!(normalize_vars("f(_G12,'_x',_)"), "f(_,'_x',_)");
    assert_eq!(normalize_vars("a_b(_123)"), "a_b(_)");
    assert_eq!(normalize_vars("'it''s _G1'(_G2)"), "'it''s _G1'(_)");
    // An apostrophe in prose opens no quoted atom.
    assert_eq!(
        normalize_vars("`s(_G1)` is not the DM's identifier `s(_G2)`"),
        "`s(_)` is not the DM's identifier `s(_)`"
    );
}

#[test]
fn renaming_is_consistent() {
    let mut names = Default::default();
    assert_eq!(
        sitlog_tests::compiled::rename("f(_G12,'_x',_G3,_G12)", &mut names),
        "f(_V0,'_x',_V1,_V0)"
    );
    assert_eq!(
        sitlog_tests::compiled::rename("g(_G3)", &mut names),
        "g(_V1)"
    );
}

/// `tests/build.rs` restates the simulated robot's function names.
#[test]
fn the_build_scripts_list_is_the_robots() {
    assert_eq!(
        sitlog_tests::world_functions::WORLD_FUNCTIONS,
        sitlog_robot::WORLD_FUNCTIONS
    );
}

/// The scenario applications share their engines (else each of their
/// tests builds two again); code that may keep state does not.
#[test]
fn the_scenario_apps_are_stateless_and_state_is_seen() {
    for app in ["dms/apps/home", "dms/apps/supermarket"] {
        let dir = sitlog_tests::workspace().join(app);
        let text = std::fs::read_to_string(dir.join("user_functions.pl")).unwrap();
        assert!(stateless(&text, Some(&dir), &[], 0), "{app}");
    }
    let dir = sitlog_tests::workspace().join("dms/apps/home");
    for text in [
        "f(X) :- assertz(seen(X)).\n",
        ":- initialization(main).\n",
        ":- consult('no/such/file.pl').\n",
        "f(X) :- nb_setval(k, X).\n",
    ] {
        assert!(!stateless(text, Some(&dir), &[], 0), "{text}");
    }
    assert!(stateless("f(X) :- drop(X), stop(X).\n", None, &[], 0));
    // Compiled, their consults are among the sources they embed.
    use sitlog_tests::compiled::generated::{apps_home, apps_supermarket};
    for embedded in [apps_home::PROLOG_SOURCES, apps_supermarket::PROLOG_SOURCES] {
        let given: Vec<PrologSource> = embedded
            .iter()
            .map(|(name, text)| PrologSource::new(*name, *text))
            .collect();
        assert!(given.iter().all(|s| stateless(&s.text, None, &given, 0)));
    }
}
