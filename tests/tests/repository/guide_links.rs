//! Every relative link of README.md and of the guide (`docs/guide/*.md`)
//! names a file of the repository, and every `#anchor` a heading of the
//! page it points to (GitHub's heading ids); nothing links outside the
//! repository. Pages another change is still writing may be linked before
//! they exist: they are listed in `COMING`.

use sitlog_tests::workspace;
use std::path::{Path, PathBuf};

/// Guide pages linked as "coming" before they are written.
const COMING: [&str; 6] = [
    "cli.md",
    "running.md",
    "debugging.md",
    "performance.md",
    "compiling.md",
    "diagnostics.md",
];

/// The Markdown files checked.
fn pages() -> Vec<PathBuf> {
    let root = workspace();
    let mut pages = vec![root.join("README.md")];
    let mut guide: Vec<PathBuf> = std::fs::read_dir(root.join("docs/guide"))
        .expect("docs/guide exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    guide.sort();
    pages.extend(guide);
    pages
}

/// The text outside fenced code blocks and inline code, line by line.
fn prose(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fenced = false;
    for (i, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // drop `inline code`
        let mut kept = String::new();
        let mut code = false;
        for c in line.chars() {
            if c == '`' {
                code = !code;
            } else if !code {
                kept.push(c);
            }
        }
        out.push((i + 1, kept));
    }
    out
}

/// The targets of `[text](target)` and `![alt](target)` links, with their lines.
fn links(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (line, prose) in prose(text) {
        let mut rest = prose.as_str();
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let end = after.find(')').unwrap_or(after.len());
            found.push((line, after[..end].trim().to_owned()));
            rest = &after[end..];
        }
    }
    found
}

/// GitHub's id of a heading: lower case, spaces to `-`, punctuation other
/// than `-` and `_` dropped.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

fn anchors(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut ids = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if !fenced && line.starts_with('#') {
            let base = slug(line.trim_start_matches('#'));
            // repeated headings get -1, -2, ...
            let n = ids
                .iter()
                .filter(|i: &&String| **i == base || i.starts_with(&format!("{base}-")))
                .count();
            ids.push(if n == 0 { base } else { format!("{base}-{n}") });
        }
        // explicit anchors: <a id="name"></a>
        if !fenced {
            let mut rest = line;
            while let Some(at) = rest.find("<a id=\"") {
                let after = &rest[at + 7..];
                let end = after.find('"').unwrap_or(after.len());
                ids.push(after[..end].to_owned());
                rest = &after[end..];
            }
        }
    }
    ids
}

fn check(page: &Path, problems: &mut Vec<String>) {
    let root = workspace();
    let text = std::fs::read_to_string(page).unwrap();
    let name = page.strip_prefix(&root).unwrap().display().to_string();
    for (line, target) in links(&text) {
        let at = format!("{name}:{line}: `{target}`");
        if target.contains("://") || target.starts_with("mailto:") {
            problems.push(format!("{at}: points outside the repository"));
            continue;
        }
        let (path, anchor) = match target.split_once('#') {
            Some((p, a)) => (p, Some(a)),
            None => (target.as_str(), None),
        };
        let file = if path.is_empty() {
            page.to_path_buf()
        } else {
            page.parent().unwrap().join(path)
        };
        if !file.exists() {
            let coming =
                page.parent() == Some(root.join("docs/guide").as_path()) && COMING.contains(&path);
            if !coming {
                problems.push(format!("{at}: no such file"));
            }
            continue;
        }
        if let Some(anchor) = anchor {
            if file.extension().is_some_and(|e| e == "md") {
                let ids = anchors(&std::fs::read_to_string(&file).unwrap());
                if !ids.iter().any(|i| i == anchor) {
                    problems.push(format!("{at}: no heading with this id"));
                }
            }
        }
    }
}

#[test]
fn the_guide_links_resolve_in_the_repository() {
    let mut problems = Vec::new();
    for page in pages() {
        check(&page, &mut problems);
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn every_guide_page_is_in_the_summary() {
    let root = workspace();
    let summary = std::fs::read_to_string(root.join("docs/guide/SUMMARY.md")).unwrap();
    let listed: Vec<String> = links(&summary).into_iter().map(|(_, t)| t).collect();
    for page in pages().into_iter().skip(1) {
        let file = page.file_name().unwrap().to_string_lossy().into_owned();
        if file != "SUMMARY.md" {
            assert!(
                listed.contains(&file),
                "{file} is not in docs/guide/SUMMARY.md"
            );
        }
    }
}

#[test]
fn slugs_follow_github() {
    assert_eq!(
        slug(" The home butler (`dms/apps/home/`)"),
        "the-home-butler-dmsappshome"
    );
    assert_eq!(slug("Typed code generation"), "typed-code-generation");
    assert_eq!(
        slug("In your editor: `sitlogc lsp`"),
        "in-your-editor-sitlogc-lsp"
    );
}

/// The Rust blocks of `docs/guide/robot.md` that show the worked example's
/// robot are the example's code (`robot/examples/channel_robot.rs`), which
/// `cargo test -p sitlog-robot` compiles.
#[test]
fn the_robot_page_shows_the_example_as_it_is() {
    let root = workspace();
    let page = std::fs::read_to_string(root.join("docs/guide/robot.md")).unwrap();
    let example = std::fs::read_to_string(root.join("robot/examples/channel_robot.rs")).unwrap();
    let task = std::fs::read_to_string(root.join("robot/examples/channel_robot/main.dm")).unwrap();
    let mut shown = 0;
    for block in page.split("```rust\n").skip(1) {
        let block = &block[..block.find("```").unwrap()];
        if block.contains("impl Perception for Senses") {
            assert!(
                example.contains(block),
                "robot.md shows a robot that is not the example's:\n{block}"
            );
            shown += 1;
        }
    }
    for block in page.split("```prolog\n").skip(1) {
        let block = &block[..block.find("```").unwrap()];
        if block.contains("navigate(kitchen, Status)") {
            assert!(
                task.contains(block),
                "robot.md shows a task that is not the example's:\n{block}"
            );
            shown += 1;
        }
    }
    assert_eq!(shown, 2);
}

/// The first Prolog block of `text` (after `after`) and the text block after it.
fn blocks_after<'a>(text: &'a str, after: &str) -> (&'a str, &'a str) {
    let from = text.find(after).expect("marker") + after.len();
    let rest = &text[from..];
    let dm_at = rest.find("```prolog\n").expect("a Prolog block") + 10;
    let dm = &rest[dm_at..dm_at + rest[dm_at..].find("```").unwrap()];
    let rest = &rest[dm_at + dm.len()..];
    let out_at = rest.find("```text\n").expect("a text block") + 8;
    let out = &rest[out_at..out_at + rest[out_at..].find("```").unwrap()];
    (dm, out)
}

/// README's ten-line DM checks without a warning and, answered `yes.`,
/// prints what README shows.
#[test]
fn the_readme_dm_runs_as_shown() {
    use sitlog_compiler::run::{self, RunConfig};
    use sitlog_robot::console::SharedBuf;
    use sitlog_runtime::testmode::{ScriptPerception, TextActions};

    let readme = std::fs::read_to_string(workspace().join("README.md")).unwrap();
    let (dm, shown) = blocks_after(&readme, "A DM that greets");
    let dir = std::env::temp_dir().join(format!("sitlog-readme-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("hello.dm");
    std::fs::write(&file, dm).unwrap();
    let (result, diags) = sitlog_compiler::check_path(&file).expect("readable");
    let _ = std::fs::remove_dir_all(&dir);
    let checked = result.unwrap_or_else(|_| panic!("README's DM does not check: {diags:?}"));
    assert!(diags.is_empty(), "{diags:?}");
    let ir = sitlog_compiler::ir::lower(&checked);
    let said = SharedBuf::default();
    let mut actions = TextActions::new(said.clone(), ir.basic_actions.clone());
    let mut perception = ScriptPerception::new("answers.txt", "yes.\n".to_owned());
    let (outcome, mut store) = run::run(
        &ir,
        RunConfig::default(),
        &mut perception,
        &mut actions,
        None,
    )
    .expect("runs");
    let report = sitlog_runtime::report::outcome_text(&mut store, &outcome);
    let history = report.split("\n\n").next().unwrap();
    let printed = format!("{}{history}\n", said.text());
    assert_eq!(shown, printed, "README shows another run than its DM makes");
}

/// The excerpt of the main job's output in README is in the home butler's
/// golden transcript (`suite__home__paper.snap`, checked by `tests/tests/suite/home.rs`).
#[test]
fn the_readme_excerpt_is_in_the_home_transcript() {
    let root = workspace();
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let golden =
        std::fs::read_to_string(root.join("tests/tests/suite/snapshots/suite__home__paper.snap"))
            .unwrap();
    let from = readme.find("Golem: Hi, Luis.").expect("the excerpt");
    let excerpt = &readme[from..from + readme[from..].find("```").unwrap()];
    for line in excerpt.lines().filter(|l| *l != "...") {
        assert!(
            golden.lines().any(|g| g == line),
            "not in the home transcript: {line}"
        );
    }
}
