//! Unit tests of the closure quirks (kb.md section 2) live in `tests/`;
//! this module checks internal invariants only.

use crate::gen::generate;

#[test]
fn generated_kb_has_the_requested_shape() {
    let kb = generate(1000, 8);
    assert_eq!(kb.classes.len(), crate::gen::class_count(8));
    assert_eq!(kb.ind_ix.len(), 1000);
}
