//! `sitlogc sim APP --ros2` (feature `ros2`): the application's simulated
//! world served as a robot over ROS 2 ([`sitlog_ros::sim_node`]), its
//! transcript on stdout, an episode per task run (each announced on
//! stderr), until SIGINT or SIGTERM.

use sitlog_robot::interrupt::Interrupt;
use sitlog_robot::{Assets, TextFile};
use sitlog_ros::sim_node::{serve, Options};
use sitlog_ros::{link, Interface};
use std::path::Path;

/// `sitlogc sim`: the exit status (see its help).
pub fn sim(app: &Path, world: Option<&Path>, seed: Option<u64>, external: bool, quiet: bool) -> u8 {
    let assets = match Assets::from_app(app) {
        Ok(a) => a,
        Err(e) => {
            sitlog_runtime::errln!("{e}");
            return e.status;
        }
    };
    let file = match world {
        Some(path) => match TextFile::read(path, "world") {
            Ok(f) => f,
            Err(e) => {
                sitlog_runtime::errln!("{e}");
                return e.status;
            }
        },
        None => match assets.world.clone() {
            Some(f) => f,
            None => {
                sitlog_runtime::errln!(
                    "error: {} has no world file (world.toml): give one with --world FILE",
                    app.display()
                );
                return 2;
            }
        },
    };
    let world = match sitlog_sim::World::parse(&file.name, &file.text) {
        Ok(w) => w,
        Err(errors) => {
            for e in errors {
                sitlog_runtime::errln!("{e}");
            }
            return 2;
        }
    };
    let ros2 = assets
        .ros2
        .as_ref()
        .map(|f| (f.name.as_str(), f.text.as_str()));
    let iface = match Interface::load(ros2, Some(&world)) {
        Ok(i) => i,
        Err(e) => {
            sitlog_runtime::errln!("{e}");
            return 2;
        }
    };
    let domain = match link::domain_id() {
        Ok(d) => d,
        Err(e) => {
            sitlog_runtime::errln!("{e}");
            return 2;
        }
    };
    let interrupt = Interrupt::install();
    sitlog_runtime::errln!(
        "sitlogc sim: serving {} on ROS 2 domain {domain}{} (speech: {}); stop with Ctrl-C",
        file.name,
        if link::localhost_only() {
            ", this host only"
        } else {
            ""
        },
        if external {
            "external, on the heard topic"
        } else {
            "simulated"
        }
    );
    let options = Options {
        seed,
        speech_external: external,
        narrate: !quiet,
    };
    let mut note = |line: &str| sitlog_runtime::errln!("sitlogc sim: {line}");
    match serve(
        &world,
        &iface,
        &options,
        Box::new(std::io::stdout()),
        &mut note,
        &interrupt.flag,
    ) {
        Ok(()) => 0,
        Err(e) => {
            sitlog_runtime::errln!("{e}");
            2
        }
    }
}
