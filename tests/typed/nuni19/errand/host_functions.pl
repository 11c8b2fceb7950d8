% Functions the test registers in Rust (tests/tests/suite/typed.rs).
twice/1.
