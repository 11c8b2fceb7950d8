//! The guide's table of the behaviour library's final situations
//! (`docs/guide/scenarios.md`, "The finals a caller's exit arcs match") is
//! what the library's DMs say: every final situation of every library DM,
//! and nothing else (issue 40). The DMs are read as the home application
//! loads them (it uses every file of the library).

use sitlog_tests::workspace;

fn compact(s: &str) -> String {
    s.chars().filter(|c| !c.is_whitespace()).collect()
}

/// `name/arity` of a DM head as written.
fn functor(head: &str) -> String {
    sitlog_graph::trace::functor_of(head).unwrap_or_else(|| head.to_owned())
}

#[test]
fn the_guide_lists_the_finals_of_every_library_dm() {
    let app = workspace().join("dms/apps/home");
    let (checked, diags) = sitlog_tests::check_app(&app);
    let checked = checked.unwrap_or_else(|_| panic!("home does not check: {diags:?}"));
    let ir = sitlog_compiler::ir::lower(&checked);
    let diagram = sitlog_compiler::diagram::diagram(
        &ir,
        &sitlog_compiler::diagram::Options {
            dm: None,
            main: Some("main".to_owned()),
            title: "home".to_owned(),
        },
    )
    .unwrap();
    let mut in_dms: Vec<(String, String, String)> = Vec::new();
    for g in &diagram.dms {
        let Some(at) = g.location.find("behaviors/") else {
            continue;
        };
        let file = g.location[at..].split(".dm").next().unwrap().to_owned() + ".dm";
        for n in &g.nodes {
            if n.situation_kind == Some(sitlog_graph::SituationKind::Final) {
                in_dms.push((file.clone(), functor(&g.name), compact(&n.label)));
            }
        }
    }
    let files = std::fs::read_dir(workspace().join("dms/behaviors"))
        .unwrap()
        .chain(std::fs::read_dir(workspace().join("dms/behaviors/recovery")).unwrap())
        .filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "dm"))
        })
        .count();
    let seen: std::collections::BTreeSet<&String> = in_dms.iter().map(|(f, _, _)| f).collect();
    assert_eq!(
        seen.len(),
        files,
        "home should load every DM file of the library"
    );

    let page = std::fs::read_to_string(workspace().join("docs/guide/scenarios.md")).unwrap();
    let section = page
        .split("### The finals a caller's exit arcs match")
        .nth(1)
        .expect("the section")
        .split("\n#")
        .next()
        .unwrap();
    let in_guide: Vec<(String, String, String)> = section
        .lines()
        .filter(|l| l.starts_with("| `"))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(|c| c.trim().trim_matches('`')).collect();
            (cells[1].to_owned(), functor(cells[2]), compact(cells[3]))
        })
        .collect();
    let missing: Vec<_> = in_dms.iter().filter(|r| !in_guide.contains(r)).collect();
    let extra: Vec<_> = in_guide.iter().filter(|r| !in_dms.contains(r)).collect();
    assert!(
        missing.is_empty() && extra.is_empty(),
        "docs/guide/scenarios.md misses the finals {missing:?} and lists finals no DM has: {extra:?}"
    );
}
