//! `include_dm!`: a thin proc-macro layer over `sitlog-compiler` (to come).
