% Functions the test registers in Rust (tests/tests/typed.rs).
poke/1.
