//! What a debugger (`sitlogc debug`, sitlog-debug) plugs into a run
//! ([`DebugHooks`]): its observer, its test-mode perception, its look at
//! the simulated world ([`WorldProbe`]) and its stop flag.

use sitlog_runtime::machine::{Observer, Perception};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

/// Makes a run's test-mode perception from the script's, if any.
pub type MakePerception = Box<dyn FnOnce(Option<Box<dyn Perception>>) -> Box<dyn Perception>>;

/// What a debugger adds to a run ([`crate::Runner::debugger`]).
pub struct DebugHooks {
    /// Watches every transition and stops the run between them.
    pub observer: Box<dyn Observer + Send>,
    /// Makes the test-mode perception from the script's (`None` without
    /// `--script`); it replaces the prompt on stdin.
    pub perception: MakePerception,
    /// Given a look at the simulated world when the run has one.
    pub world: Box<dyn FnOnce(WorldProbe)>,
    /// When set, the run stops before its next transition (`quit`).
    pub stop: Arc<AtomicBool>,
}

/// A look at the simulated world of a run (the debugger's `world`).
#[derive(Clone)]
pub struct WorldProbe {
    #[cfg(feature = "sim")]
    robot: crate::robot::Probe,
}

impl WorldProbe {
    /// A look through the simulated robot's probe.
    #[cfg(feature = "sim")]
    pub(crate) fn new(robot: crate::robot::Probe) -> WorldProbe {
        WorldProbe { robot }
    }

    /// The world's state now, one fact a line.
    pub fn describe(&self) -> String {
        #[cfg(feature = "sim")]
        {
            self.robot.describe()
        }
        #[cfg(not(feature = "sim"))]
        String::new()
    }
}
