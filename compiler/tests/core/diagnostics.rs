//! Golden diagnostics: every file in `tests/ui/` is checked and its
//! diagnostics, rendered without colour, are compared with an insta snapshot.

use sitlog_compiler::{check, diag, load};
use std::path::Path;

fn render(path: &Path) -> String {
    let (program, diags) = load::load(path).expect("ui file is readable");
    let (result, diags) = check::check(program, diags);
    let program = match &result {
        Ok(c) => c.program(),
        Err(p) => p,
    };
    let mut out = String::new();
    for d in &diags {
        let text = diag::render_human(d, &program.sources, false);
        // Paths differ between machines: keep the file name only.
        let text = text.replace(
            &path.display().to_string(),
            path.file_name().unwrap().to_str().unwrap(),
        );
        out.push_str(
            text.lines()
                .map(str::trim_end)
                .collect::<Vec<_>>()
                .join("\n")
                .as_str(),
        );
        out.push('\n');
    }
    out
}

#[test]
fn ui_diagnostics() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/ui");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "dm"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    for file in files {
        let name = file.file_stem().unwrap().to_str().unwrap().to_owned();
        insta::assert_snapshot!(name, render(&file));
    }
}

#[test]
fn json_diagnostic_has_position_fields() {
    let (program, diags) = load::load_sources(&[(
        "x.dm",
        "diag_mod(m, [[id ==> a, type ==> final]], []).\nfoo(",
    )]);
    let (result, diags) = check::check(program, diags);
    let program = result.expect_err("syntax error is an error");
    let v = diag::render_json(&diags[0], &program.sources);
    assert_eq!(v["code"], "E0001");
    assert_eq!(v["severity"], "error");
    assert_eq!(v["line"], 2);
    assert_eq!(v["file"], "x.dm");
    assert!(v["end"]["column"].is_number());
}
