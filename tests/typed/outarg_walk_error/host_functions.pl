% Functions the test registers in Rust (tests/tests/suite/typed.rs).
is_bed/1.
