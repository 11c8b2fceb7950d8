//! Issue 37's check that typing comes from general rules: workloads of
//! shapes (c) (N calls of an embedded DM) and (d) (a list walked by a
//! called DM) written the way another engineer would
//! (`tests/typed/shapes/*`: the limit from a parameter, the pipe, a
//! global or a local; `<`, `=<`, `>`, `=:=`, `==`; the counter in the
//! callee; computed and constant out_args; calls with 0, 1, 3 arguments
//! and an output argument; lists of ints, atoms and pairs, one from the
//! pipe; a walk by `get`/`set` of a local; lists from a user function and
//! from the KB;
//! exit arcs `found(_)`, `found(P)`, a variable; a guard; nested calls;
//! a pair in the pipe; a final chosen by the in_arg; records matched by a
//! field; a recursive found situation; a list built by `append`).
//! Their `--explain-types` listings as one insta snapshot, through the
//! library (no `sitlogc`, no generated code compiled):
//! `docs/guide/performance.md` ("workloads that are not ours") has the table.

use sitlog_compiler::{check_path, codegen, ir};
use std::path::Path;

#[test]
fn other_engineers_shapes_explained() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/typed/shapes");
    let mut dirs: Vec<_> = std::fs::read_dir(&root)
        .expect("tests/typed/shapes")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    assert!(dirs.len() >= 10, "{dirs:?}");
    let mut all = String::new();
    for dir in dirs {
        let (checked, diags) = check_path(&dir).expect("readable");
        let checked = checked.unwrap_or_else(|_| panic!("{}: {diags:#?}", dir.display()));
        let ir = ir::lower(&checked);
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        all.push_str(&format!("== {name}\n{}", codegen::explain_types(&ir)));
    }
    insta::assert_snapshot!(all);
}
