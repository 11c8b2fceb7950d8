mod app {
    sitlog_macros::include_dm!("tests/ui/good_dm");
}

fn main() {
    use sitlog_runtime::machine::Options;
    use sitlog_runtime::testmode::{ScriptPerception, TextActions};
    let mut perception = ScriptPerception::new("script", String::new());
    let mut actions = TextActions::new(std::io::sink(), Vec::new());
    let (outcome, store) = app::run(
        "main",
        None,
        Options::default(),
        sitlog_runtime::Functions::standard(),
        &mut perception,
        &mut actions,
        None,
    )
    .unwrap();
    assert!(outcome.result.is_ok());
    assert_eq!(outcome.history.len(), 2);
    let _ = store;
}
