//! Another robot than the simulated one (`--robot ros2`): what a run hands
//! the code that connects it ([`RobotSetup`]) and the hook that does it
//! ([`RobotHook`], given to [`crate::Runner::robot`]). This crate knows no
//! such robot itself: sitlog-ros makes the hook, and `sitlogc` and compiled
//! tasks built with it pass it on.

use crate::assets::{Assets, TextFile};
use crate::cli::RunArgs;
use crate::console::SharedConsole;
use crate::interrupt::Interrupt;
use sitlog_runtime::machine::{Actions, Perception};
use sitlog_runtime::Functions;

/// What a run gives another robot to set itself up.
pub struct RobotSetup<'a> {
    /// The options of the run.
    pub args: &'a RunArgs,
    /// The application's files (its `ros2.toml` among them).
    pub assets: &'a Assets,
    /// The run's world file, if any (`--world`, or the application's): not
    /// simulated, but its names and map may serve the robot.
    pub world: Option<&'a TextFile>,
    /// Where the transcript goes (turns and narration, as on the simulator).
    pub console: SharedConsole,
    /// The run's user functions, to register the robot's own.
    pub functions: &'a mut Functions,
    /// The run's stop flag: [`Interrupt::request_robot_gone`] stops the task
    /// at its next transition boundary, exit status
    /// [`EXIT_ROBOT_GONE`](crate::interrupt::EXIT_ROBOT_GONE).
    pub stop: Interrupt,
}

/// The robot's senses and effectors.
pub type RobotParts = (Box<dyn Perception>, Box<dyn Actions>);

/// Connects another robot: its parts, or the exit status and message of why
/// it cannot run.
pub type RobotHook = Box<dyn FnOnce(RobotSetup<'_>) -> Result<RobotParts, (u8, String)>>;
