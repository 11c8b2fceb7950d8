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
#[cfg(feature = "ros2")]
pub use user::user;
