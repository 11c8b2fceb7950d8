//! `sitlog-ros`: a SitLog task's actions and perceptions over ROS 2, and
//! the simulated robot as a ROS 2 node, on ros2-client (pure Rust over
//! RustDDS: no ROS installation to build, test or run).
//!
//! Modules: `config` (the interface: `ros2.toml` over the guide's
//! defaults), `msgs` (the messages as Rust types), `link` (the DDS
//! participant, node and waits), `robot` (the task's side: [`RosRobot`],
//! the runtime's `Perception` and `Actions` over the interface, and
//! [`hook`] for `--robot ros2`), `sim_node` (the robot's side:
//! [`sim_node::serve`], a simulated world served on the interface, an
//! episode per task run), `user_node` (a person playing the user:
//! [`user_node::serve`] shows what the robot says and sends what is typed
//! while it listens), and `terms` (the terms the robot reads and makes).
//!
//! Invariant: no SitLog syntax here beyond the terms a robot perceives and
//! acts on (as `sitlog-robot`'s simulated robot makes them); the
//! simulator never learns it is reached over DDS.

pub mod config;
pub mod link;
pub mod msgs;
mod robot;
pub mod sim_node;
mod terms;
pub mod user_node;

pub use config::Interface;
pub use robot::{hook, RosRobot};
