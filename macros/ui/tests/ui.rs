//! `include_dm!` through the compiler: a good DM compiles and runs, bad
//! ones give `compile_error!`s naming the `.dm` file, line and column.
//! One trybuild run (one nested cargo build) for all cases.

#[test]
fn ui() {
    // trybuild's crate lives in the target dir: resolve the DM paths
    // against this crate (the nested cargo inherits the environment).
    std::env::set_var("SITLOG_DM_ROOT", env!("CARGO_MANIFEST_DIR"));
    // trybuild's project has no [profile]: without this its nested build
    // compiles the compiler and the runtime with full debug info, which only
    // slows the test down (issue 30; the messages compared do not change).
    std::env::set_var("CARGO_PROFILE_DEV_DEBUG", "false");
    let t = trybuild::TestCases::new();
    t.pass("tests/ui/good_dm.rs");
    t.compile_fail("tests/ui/bad_dm.rs");
    t.compile_fail("tests/ui/syntax_dm.rs");
    t.compile_fail("tests/ui/not_a_string.rs");
}
