//! `sitlog-compiler`: SitLog source to checked program, interpreter and generated Rust.
