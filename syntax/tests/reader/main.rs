//! The reader's integration tests, in one binary (a test binary costs a
//! link: issue 30): bad and extreme input (`robustness`) and the print/read
//! round trip as properties (`roundtrip_prop`).
mod robustness;
mod roundtrip_prop;
