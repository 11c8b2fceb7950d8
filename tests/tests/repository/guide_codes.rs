//! The guide's tables of diagnostic codes follow the compiler's list
//! (`sitlog_compiler::codes::DIAGNOSTICS`): the table of
//! `docs/guide/checking.md` is that list, row for row (a failure prints the
//! table to paste); `docs/guide/diagnostics.md` describes every code; and
//! no page of the guide names a code that does not exist.

use sitlog_compiler::codes::{markdown_table, DIAGNOSTICS};
use sitlog_tests::workspace;

fn page(name: &str) -> String {
    std::fs::read_to_string(workspace().join("docs/guide").join(name))
        .unwrap_or_else(|e| panic!("docs/guide/{name}: {e}"))
}

/// The codes (`E0212`, `W0220`) written in `text`.
fn codes_in(text: &str) -> Vec<String> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    for i in 0..b.len().saturating_sub(4) {
        let word_start = i == 0 || !b[i - 1].is_ascii_alphanumeric();
        let word_end = b.get(i + 5).is_none_or(|c| !c.is_ascii_alphanumeric());
        if word_start
            && word_end
            && (b[i] == b'E' || b[i] == b'W')
            && b[i + 1..i + 5].iter().all(u8::is_ascii_digit)
        {
            out.push(text[i..i + 5].to_owned());
        }
    }
    out
}

#[test]
fn the_code_table_of_checking_md_is_the_compilers_list() {
    let table = markdown_table();
    assert!(
        page("checking.md").contains(&table),
        "docs/guide/checking.md must hold the table of codes as the compiler lists them \
         (compiler/src/codes.rs):\n\n{table}"
    );
}

#[test]
fn diagnostics_md_describes_every_code() {
    let text = page("diagnostics.md");
    let missing: Vec<&str> = DIAGNOSTICS
        .iter()
        .map(|(code, _)| *code)
        .filter(|code| {
            // A table row whose first cell names it, or a paragraph `**CODE`.
            let in_a_row = text.lines().any(|l| {
                l.strip_prefix('|')
                    .and_then(|r| r.split('|').next())
                    .is_some_and(|cell| codes_in(cell).iter().any(|c| c == code))
            });
            !(in_a_row || text.contains(&format!("**{code}")))
        })
        .collect();
    assert!(
        missing.is_empty(),
        "docs/guide/diagnostics.md has no row (first cell) or paragraph (`**CODE`) for {missing:?}"
    );
}

#[test]
fn the_guide_names_only_codes_that_exist() {
    let mut unknown = Vec::new();
    for entry in std::fs::read_dir(workspace().join("docs/guide")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        for code in codes_in(&text) {
            if !DIAGNOSTICS.iter().any(|(c, _)| *c == code) {
                unknown.push(format!("{}: {code}", path.display()));
            }
        }
    }
    assert!(
        unknown.is_empty(),
        "codes the compiler does not have: {unknown:?}"
    );
}
