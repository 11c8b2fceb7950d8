//! The layout of the workspace, as docs/guide/internals.md draws it:
//!
//! - every dependency between the workspace's crates is one the table
//!   [`LAYERS`] allows (a new arrow is a deliberate edit here and in the
//!   guide), the graph has no cycle, and nothing depends on the command line;
//! - the compiler core reaches neither the robot, the simulator, the
//!   debugger, the language server nor the live view, directly or not;
//! - inside each crate, the `crate::` paths between its top-level modules
//!   form no circle (a module's unit tests, after `#[cfg(test)]`, are not
//!   counted).

use sitlog_tests::workspace;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Each crate and the workspace crates its `[dependencies]` may name.
const LAYERS: &[(&str, &[&str])] = &[
    // floor 0: no SitLog inside, or the reader only
    ("sitlog-syntax", &[]),
    ("sitlog-graph", &[]),
    ("sitlog-lsp", &[]),
    ("sitlog-infer", &[]),
    ("sitlog-sim", &[]),
    // floor 1: what a running task needs
    ("sitlog-runtime", &["sitlog-syntax"]),
    ("sitlog-kb", &["sitlog-syntax"]),
    ("sitlog-view", &["sitlog-graph", "sitlog-runtime"]),
    // floor 2: the compiler core, and what a task runs on
    (
        "sitlog-compiler",
        &[
            "sitlog-syntax",
            "sitlog-runtime",
            "sitlog-kb",
            "sitlog-graph",
        ],
    ),
    (
        "sitlog-robot",
        &[
            "sitlog-syntax",
            "sitlog-runtime",
            "sitlog-kb",
            "sitlog-sim",
            "sitlog-infer",
            "sitlog-view",
            "sitlog-graph",
        ],
    ),
    // floor 3: tools over them
    ("sitlog-macros", &["sitlog-compiler", "sitlog-runtime"]),
    // include_dm!'s trybuild tests: what a user of the macro depends on
    ("sitlog-macros-ui", &["sitlog-macros", "sitlog-runtime"]),
    (
        "sitlog-debug",
        &["sitlog-syntax", "sitlog-runtime", "sitlog-robot"],
    ),
    // a robot over ROS 2, and the simulator served as one
    (
        "sitlog-ros",
        &["sitlog-runtime", "sitlog-robot", "sitlog-sim"],
    ),
    // floor 4: the command line
    (
        "sitlog-cli",
        &[
            "sitlog-syntax",
            "sitlog-runtime",
            "sitlog-compiler",
            "sitlog-kb",
            "sitlog-graph",
            "sitlog-lsp",
            "sitlog-debug",
            "sitlog-robot",
            "sitlog-ros",
            "sitlog-sim",
        ],
    ),
];

/// What the compiler core must never reach.
const NOT_UNDER_THE_COMPILER: &[&str] = &[
    "sitlog-robot",
    "sitlog-ros",
    "sitlog-sim",
    "sitlog-debug",
    "sitlog-lsp",
    "sitlog-view",
    "sitlog-cli",
];

/// The workspace's member directories, from the root manifest.
fn members() -> Vec<PathBuf> {
    let root = workspace();
    let text = std::fs::read_to_string(root.join("Cargo.toml")).unwrap();
    let manifest: toml::Table = toml::from_str(&text).unwrap();
    manifest["workspace"]["members"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| root.join(m.as_str().unwrap()))
        .collect()
}

/// A member's package name and the `sitlog-*` crates of its `[dependencies]`.
fn dependencies(dir: &Path) -> (String, BTreeSet<String>) {
    let text = std::fs::read_to_string(dir.join("Cargo.toml")).unwrap();
    let manifest: toml::Table = toml::from_str(&text).unwrap();
    let name = manifest["package"]["name"].as_str().unwrap().to_owned();
    let mut deps = BTreeSet::new();
    let mut tables = vec![manifest.get("dependencies")];
    // target-specific dependencies count too
    if let Some(targets) = manifest.get("target").and_then(|t| t.as_table()) {
        for t in targets.values() {
            tables.push(t.get("dependencies"));
        }
    }
    for table in tables.into_iter().flatten() {
        for key in table.as_table().unwrap().keys() {
            if key.starts_with("sitlog-") {
                deps.insert(key.clone());
            }
        }
    }
    (name, deps)
}

#[test]
fn crates_depend_only_downwards() {
    let allowed: BTreeMap<&str, BTreeSet<&str>> = LAYERS
        .iter()
        .map(|(c, deps)| (*c, deps.iter().copied().collect()))
        .collect();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut problems = Vec::new();
    for dir in members() {
        let (name, deps) = dependencies(&dir);
        if matches!(name.as_str(), "sitlog-tests" | "sitlog-benches") {
            // the workspace's tests and benchmarks may use anything but the CLI crate's library
            continue;
        }
        match allowed.get(name.as_str()) {
            None => problems.push(format!(
                "{name} is not in LAYERS (tests/tests/repository/layout.rs)"
            )),
            Some(ok) => {
                for d in &deps {
                    if !ok.contains(d.as_str()) {
                        problems.push(format!(
                            "{name} depends on {d}, which LAYERS does not allow"
                        ));
                    }
                }
            }
        }
        graph.insert(name, deps);
    }
    for (name, deps) in &graph {
        if deps.contains("sitlog-cli") {
            problems.push(format!("{name} depends on the command line (sitlog-cli)"));
        }
    }
    // what the compiler reaches, directly or not
    let mut reached = BTreeSet::new();
    let mut todo = vec!["sitlog-compiler".to_owned()];
    while let Some(c) = todo.pop() {
        for d in graph.get(&c).into_iter().flatten() {
            if reached.insert(d.clone()) {
                todo.push(d.clone());
            }
        }
    }
    for bad in NOT_UNDER_THE_COMPILER {
        if reached.contains(*bad) {
            problems.push(format!("sitlog-compiler reaches {bad}"));
        }
    }
    if let Some(cycle) = find_cycle(&graph) {
        problems.push(format!("crate cycle: {}", cycle.join(" -> ")));
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// A cycle of `graph`, as the nodes along it, if there is one.
fn find_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    // 0 unvisited, 1 on the path, 2 done; iterative depth-first search
    let mut state: BTreeMap<&str, u8> = BTreeMap::new();
    for start in graph.keys() {
        if state.get(start.as_str()).copied().unwrap_or(0) != 0 {
            continue;
        }
        let mut path: Vec<(&str, Vec<&str>)> = Vec::new();
        let next = |n: &str| -> Vec<&str> {
            graph
                .get(n)
                .map(|s| {
                    s.iter()
                        .map(|x| x.as_str())
                        .filter(|x| graph.contains_key(*x))
                        .collect()
                })
                .unwrap_or_default()
        };
        state.insert(start, 1);
        path.push((start, next(start)));
        while let Some((node, pending)) = path.last_mut() {
            let node = *node;
            match pending.pop() {
                Some(n) => match state.get(n).copied().unwrap_or(0) {
                    0 => {
                        state.insert(n, 1);
                        let more = next(n);
                        path.push((n, more));
                    }
                    1 => {
                        let from = path.iter().position(|(p, _)| *p == n).unwrap();
                        let mut cycle: Vec<String> =
                            path[from..].iter().map(|(p, _)| p.to_string()).collect();
                        cycle.push(n.to_owned());
                        return Some(cycle);
                    }
                    _ => {}
                },
                None => {
                    state.insert(node, 2);
                    path.pop();
                }
            }
        }
    }
    None
}

/// The `.rs` files under `dir`, recursively.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The top-level module a file of `src` belongs to (`None` for the crate
/// root and binaries' roots).
fn top_module(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).ok()?;
    let first = rel.components().next()?.as_os_str().to_str()?.to_owned();
    match first.strip_suffix(".rs") {
        Some("lib" | "main") => None,
        Some(stem) => Some(stem.to_owned()),
        None if first == "bin" => None,
        None => Some(first),
    }
}

/// The top-level modules a file's code (before its `#[cfg(test)]` part)
/// names through `crate::` paths, or through `super::` from a top-level file.
fn named_modules(text: &str, top_level_file: bool) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    for line in text.lines() {
        let code = line.trim_start();
        if code.starts_with("#[cfg(test)]") {
            break;
        }
        if code.starts_with("//") {
            continue;
        }
        let mut prefixes = vec!["crate::"];
        if top_level_file {
            prefixes.push("super::");
        }
        for prefix in prefixes {
            let mut rest = code;
            while let Some(at) = rest.find(prefix) {
                let before = rest[..at].chars().next_back();
                let after = &rest[at + prefix.len()..];
                rest = after;
                if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                    continue;
                }
                // `crate::{a, b::c}` names each group member
                let group = if let Some(inner) = after.strip_prefix('{') {
                    let end = inner.find('}').unwrap_or(inner.len());
                    inner[..end]
                        .split(',')
                        .map(|s| s.trim().to_owned())
                        .collect::<Vec<_>>()
                } else {
                    vec![after.to_owned()]
                };
                for item in group {
                    let ident: String = item
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    if !ident.is_empty() {
                        names.insert(ident);
                    }
                }
            }
        }
    }
    names
}

#[test]
fn no_import_circle_inside_a_crate() {
    let mut problems = Vec::new();
    for dir in members() {
        let src = dir.join("src");
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        files.sort();
        let modules: BTreeSet<String> = files.iter().filter_map(|f| top_module(&src, f)).collect();
        let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for file in &files {
            let Some(module) = top_module(&src, file) else {
                continue;
            };
            let top_level_file = file.parent() == Some(src.as_path());
            let text = std::fs::read_to_string(file).unwrap();
            let entry = graph.entry(module.clone()).or_default();
            for named in named_modules(&text, top_level_file) {
                if named != module && modules.contains(&named) {
                    entry.insert(named);
                }
            }
        }
        if let Some(cycle) = find_cycle(&graph) {
            problems.push(format!(
                "{}: modules import each other: {}",
                dir.file_name().unwrap().to_string_lossy(),
                cycle.join(" -> ")
            ));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Every diagnostic write of the crates' code goes through
/// `sitlog_runtime::errln!`/`errprint!`, which never panic
/// (`runtime/src/stderr.rs`): no `eprintln!` or `eprint!` in any `src/`.
#[test]
fn no_panicking_stderr_writes() {
    let mut found = Vec::new();
    for member in members() {
        let mut files = Vec::new();
        rust_files(&member.join("src"), &mut files);
        for f in files {
            let text = std::fs::read_to_string(&f).unwrap();
            for (i, line) in text.lines().enumerate() {
                if line.contains("eprintln!(") || line.contains("eprint!(") {
                    found.push(format!("{}:{}: {}", f.display(), i + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "use sitlog_runtime::errln!/errprint! instead:\n{}",
        found.join("\n")
    );
}

/// Each member once in `default-members` (twice, `cargo run --bin sitlogc`
/// sees two executables and the README's main command fails), and every
/// default member a member.
#[test]
fn default_members_are_members_once() {
    let text = std::fs::read_to_string(workspace().join("Cargo.toml")).unwrap();
    let manifest: toml::Table = toml::from_str(&text).unwrap();
    let names = |key: &str| -> Vec<String> {
        manifest["workspace"][key]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| m.as_str().unwrap().to_owned())
            .collect()
    };
    let members = names("members");
    let defaults = names("default-members");
    let mut seen = BTreeSet::new();
    for d in &defaults {
        assert!(seen.insert(d.clone()), "{d} twice in default-members");
        assert!(members.contains(d), "{d} is not a member");
    }
}
