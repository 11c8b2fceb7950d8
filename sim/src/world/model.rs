//! The validated world: [`World`] and the records it is made of (places,
//! routes, walls, shelves, objects, the user's moves, faults), every name
//! already an index, with the defaults and limits of the world file's keys.
//! Invariant: only `resolve` builds a `World`, so one that exists is
//! consistent (see the parent module).

use nalgebra::{Point2, Vector2, Vector3};

/// Default robot speed (m/s).
pub const DEFAULT_SPEED: f64 = 0.5;
/// Slowest robot a world may have (m/s): 1 cm/s. Slower ones would narrate
/// trips of absurd length (a speed of 1e-300 m/s was once accepted).
pub const MIN_SPEED: f64 = 0.01;
/// Fastest robot a world may have (m/s): faster than any service robot.
pub const MAX_SPEED: f64 = 20.0;
/// Default shelf size: width, depth, height of its top board (m).
pub const DEFAULT_SHELF_SIZE: [f64; 3] = [0.8, 0.4, 0.8];
/// Default object size: width, depth, height (m).
pub const DEFAULT_OBJECT_SIZE: [f64; 3] = [0.07, 0.07, 0.15];
/// Default wall height (m).
pub const DEFAULT_WALL_HEIGHT: f64 = 2.5;
/// Default wall thickness (m).
pub const DEFAULT_WALL_THICKNESS: f64 = 0.1;
/// Coordinates must lie within this many metres of the origin.
pub const MAX_COORDINATE: f64 = 10_000.0;
/// Smallest size of anything (m).
pub const MIN_SIZE: f64 = 0.001;
/// Largest size of anything (m).
pub const MAX_SIZE: f64 = 100.0;

/// A parsed, validated world file (see the crate documentation for its keys).
#[derive(Clone, Debug)]
pub struct World {
    pub(crate) file: String,
    pub(crate) seed: Option<u64>,
    pub(crate) robot: RobotSpec,
    pub(crate) user: UserSpec,
    pub(crate) places: Vec<PlaceSpec>,
    /// `None`: no `[[route]]` at all, every pair of places is joined.
    pub(crate) routes: Option<Vec<RouteSpec>>,
    pub(crate) walls: Vec<WallSpec>,
    pub(crate) shelves: Vec<ShelfSpec>,
    pub(crate) objects: Vec<ObjectSpec>,
    pub(crate) faults: Vec<Fault>,
}

#[derive(Clone, Debug)]
pub(crate) struct RobotSpec {
    pub name: String,
    pub at: usize,
    pub speed: f64,
}

#[derive(Clone, Debug)]
pub(crate) struct UserSpec {
    pub name: String,
    pub at: usize,
    pub says: Vec<String>,
    pub moves: Vec<UserMove>,
}

#[derive(Clone, Debug)]
pub(crate) struct UserMove {
    pub trigger: Trigger,
    pub delay: f64,
    pub to: usize,
}

#[derive(Clone, Copy, Debug)]
pub(crate) enum Trigger {
    /// 1-based index of an utterance.
    AfterSaying(usize),
    /// Absolute simulated seconds.
    AtTime(f64),
}

#[derive(Clone, Debug)]
pub(crate) struct PlaceSpec {
    pub name: String,
    pub pos: Point2<f64>,
    pub room: String,
    /// Radians.
    pub heading: f64,
}

#[derive(Clone, Debug)]
pub(crate) struct RouteSpec {
    pub from: usize,
    pub to: usize,
    pub length: f64,
}

#[derive(Clone, Debug)]
pub(crate) struct WallSpec {
    pub from: Point2<f64>,
    pub to: Point2<f64>,
    pub height: f64,
    pub thickness: f64,
}

#[derive(Clone, Debug)]
pub(crate) struct ShelfSpec {
    pub name: String,
    pub place: usize,
    /// Width (across), depth, height of the top board's upper face.
    pub size: Vector3<f64>,
}

#[derive(Clone, Debug)]
pub(crate) struct ObjectSpec {
    pub name: String,
    pub shelf: usize,
    /// Width (across), depth, height.
    pub size: Vector3<f64>,
    /// Centre on the board: across (+ = the robot's right), depth (+ = away).
    pub spot: Vector2<f64>,
}

#[derive(Clone, Debug)]
pub(crate) enum Fault {
    GraspFails {
        object: usize,
        times: u32,
    },
    RouteBlocked {
        a: usize,
        b: usize,
    },
    /// 0-based utterance index.
    Mishear {
        utterance: usize,
    },
}

impl World {
    /// The file name the world was read under.
    pub fn file_name(&self) -> &str {
        &self.file
    }

    /// The file's `seed`, if it gives one.
    pub fn seed(&self) -> Option<u64> {
        self.seed
    }

    /// `[robot] name`.
    pub fn robot_name(&self) -> &str {
        &self.robot.name
    }

    /// `[user] name`.
    pub fn user_name(&self) -> &str {
        &self.user.name
    }

    /// The robot's speed (m/s).
    pub fn robot_speed(&self) -> f64 {
        self.robot.speed
    }

    /// What the user will say, in order.
    pub fn utterances(&self) -> Vec<&str> {
        self.user.says.iter().map(String::as_str).collect()
    }

    /// The places in file order.
    pub fn place_names(&self) -> Vec<&str> {
        self.places.iter().map(|p| p.name.as_str()).collect()
    }

    /// The rooms, each once, in order of first mention.
    pub fn room_names(&self) -> Vec<&str> {
        let mut rooms: Vec<&str> = Vec::new();
        for p in &self.places {
            if !rooms.contains(&p.room.as_str()) {
                rooms.push(&p.room);
            }
        }
        rooms
    }

    /// The shelves in file order.
    pub fn shelf_names(&self) -> Vec<&str> {
        self.shelves.iter().map(|s| s.name.as_str()).collect()
    }

    /// The objects in file order.
    pub fn object_names(&self) -> Vec<&str> {
        self.objects.iter().map(|o| o.name.as_str()).collect()
    }

    /// The shelf an object stands on when the world starts.
    pub fn initial_shelf(&self, object: &str) -> Option<&str> {
        self.objects
            .iter()
            .find(|o| o.name == object)
            .map(|o| self.shelves[o.shelf].name.as_str())
    }

    /// Where the robot stands to be at `name` (a place, or a shelf: the
    /// place in front of it, as [`crate::Sim::navigate`] resolves it): the
    /// place's name, `x`, `y` (m) and `heading` (radians anticlockwise from
    /// +x). A bridge turns it into a goal pose (sitlog-ros).
    pub fn place_pose(&self, name: &str) -> Option<(&str, f64, f64, f64)> {
        let i = self
            .place_index(name)
            .or_else(|| self.shelf_index(name).map(|s| self.shelves[s].place))?;
        let p = &self.places[i];
        Some((p.name.as_str(), p.pos.x, p.pos.y, p.heading))
    }

    pub(crate) fn place_index(&self, name: &str) -> Option<usize> {
        self.places.iter().position(|p| p.name == name)
    }

    pub(crate) fn shelf_index(&self, name: &str) -> Option<usize> {
        self.shelves.iter().position(|s| s.name == name)
    }

    pub(crate) fn object_index(&self, name: &str) -> Option<usize> {
        self.objects.iter().position(|o| o.name == name)
    }
}
