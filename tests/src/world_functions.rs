//! The simulated robot's user functions by name and arity, as `tests/build.rs`
//! gives them to the checker when it compiles the applications under `dms/`.
//! The build script includes this file with `#[path]` instead of depending on
//! `sitlog-robot`: as a build dependency it compiled the simulator (rapier3d)
//! and, through the compiler's default feature, the Prolog engine a second
//! time for the host (issue 30: about a quarter of the test command's
//! compile time). Invariant: the list equals `sitlog_robot::WORLD_FUNCTIONS`
//! (`support::the_build_scripts_list_is_the_robots` in the `suite` test binary).

/// `sitlog_robot::WORLD_FUNCTIONS`, restated for the build script.
pub const WORLD_FUNCTIONS: &[(&str, usize)] = &[
    ("shop_shelves", 0),
    ("shop_shelf_here", 0),
    ("shop_place_here", 0),
    ("shop_diagnose", 4),
    ("shop_decide", 4),
];
