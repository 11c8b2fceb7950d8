//! One module per subcommand of `sitlogc`: each takes the parsed options
//! and returns the exit status (0 success, 1 the application or run failed,
//! 2 usage or I/O problems, 3 interrupted input; see each command's help).

pub mod build;
pub mod check;
pub mod graph;
pub mod library;
pub mod man;
pub mod new;
pub mod replay;
pub mod run;
#[cfg(feature = "ros2")]
pub mod sim;
pub mod test;
#[cfg(feature = "ros2")]
pub mod user;

pub use build::{build_app, explain_types_of};
pub use check::check;
pub use graph::graph;
pub use library::library;
pub use man::man;
pub use new::new_app;
pub use replay::replay;
pub use run::run_app;
#[cfg(feature = "ros2")]
pub use sim::sim;
pub use test::test_app;

/// How strict `run` and `build` are with a program's diagnostics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Strictness {
    /// `--allow-unresolved`: names that do not resolve are warnings.
    pub allow_unresolved: bool,
    /// `--deny-warnings` (or the application's `sitlog.toml`): warnings
    /// refuse the program.
    pub deny_warnings: bool,
}
#[cfg(feature = "ros2")]
pub use user::user;
