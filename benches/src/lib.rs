//! Generators of benchmark inputs shared by the criterion benches.
