//! `--explain-types`' detector of what a situation's generated code does
//! (`codegen::native::visit`), on DMs whose recursive situation's call
//! native code does not push (an exit arc's action is a user function),
//! each reaching the template in one of the shapes the generator emits
//! (`tests/typed/tidy23/*`): after the in_arg's conversion check
//! (`if !cx.converts_to::<T>(..)`, review22's finding 1, which the
//! detector reading up to the first branch missed: `inarg_unread`,
//! `inarg_read`), after an in_arg pattern's `let .. else` (`inarg_pattern`),
//! after a DM's own hand-over of its locals (`locals`), and the runtime's
//! hand-over and template in one call (`no_locals`). The generated code
//! is read too, so that a change of the generator that makes one of
//! these native says so here, not a wrong listing.

use sitlog_compiler::{check_path, codegen, ir};
use std::path::Path;

/// `(directory, the situation as the listing names it, a piece of its
/// generated code before the template call)`.
const CASES: [(&str, &str, &str); 5] = [
    (
        "inarg_unread",
        "main/rung(I)",
        "if ! cx . pipe_converts :: < i64 >",
    ),
    (
        "inarg_read",
        "main/rung(I)",
        "if ! cx . pipe_converts :: < i64 >",
    ),
    (
        "inarg_pattern",
        "main/rung(I)",
        "let Some ((r2 ,)) = pipe_parts else",
    ),
    (
        "locals",
        "main/rung(I)",
        "nat_hand_over(p, cx, stack, &*l0)?",
    ),
    ("no_locals", "main/go", "return machine :: nat_template"),
];

#[test]
fn a_template_call_on_every_path_is_seen_whatever_comes_before_it() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/typed/tidy23");
    for (dir, sit, code) in CASES {
        let (checked, diags) = check_path(&root.join(dir)).expect("readable");
        let checked = checked.unwrap_or_else(|_| panic!("{dir}: {diags:#?}"));
        let ir = ir::lower(&checked);
        // Compared without spaces (how tokens print is not the point).
        let squeeze = |s: &str| s.split_whitespace().collect::<String>();
        let rust = squeeze(&codegen::generate(&ir, "test").to_string());
        assert!(
            rust.contains(&squeeze(code)),
            "{dir}: the generated code changed: {rust}"
        );
        let text = codegen::explain_types(&ir);
        let id = sit.split_once('/').unwrap().1;
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("  situation `{id}`: ")))
            .unwrap_or_else(|| panic!("{dir}: {text}"));
        assert!(
            line.ends_with("but run from its template at every visit (on every path its code calls the machine's template: not on native values, not compiled as code)"),
            "{dir}: {line}"
        );
        let lines: Vec<&str> = text.lines().collect();
        let n = lines.len();
        assert_eq!(
            lines[n - 5],
            format!("situations run from the template at every visit: 1 ({sit})"),
            "{dir}: {text}"
        );
        assert_eq!(
            lines[n - 3],
            "situations handing over or running the template on some paths: 0",
            "{dir}"
        );
        // The other situations are on native values but `base` of
        // `inarg_pattern` (its out_arg `lim(3)`, a constant on terms).
        let (on, all) = lines[n - 2]
            .strip_prefix("situations on native values: ")
            .and_then(|r| r.split_once('/'))
            .unwrap();
        let (on, all): (usize, usize) = (on.parse().unwrap(), all.parse().unwrap());
        let terms = usize::from(dir == "inarg_pattern");
        assert_eq!(on + 1 + terms, all, "{dir}: {text}");
    }
}
