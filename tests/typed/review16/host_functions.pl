% Functions the test registers in Rust (tests/tests/suite/typed.rs).
pokef/1.
pokel/1.
