% Functions the test registers in Rust (tests/tests/suite/typed.rs).
poke/1.
