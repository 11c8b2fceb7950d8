//! `sitlog-sim`: a deterministic simulated home (or shop) for a service
//! robot. A robot with a camera and two hands, a user who talks and walks
//! about, places joined by routes, shelves with objects on them, walls, and
//! faults to test recovery. It knows nothing of SitLog: a bridge maps a
//! robot program's actions and perceptions onto [`Sim`].
//!
//! **Invariant:** no SitLog crate is among its dependencies (see its
//! `Cargo.toml`); its only input is the world file and the calls on [`Sim`].
//! Even the world file's bytes are turned into text here (with the same
//! rules and messages as the toolchain's other readers).
//!
//! What this crate owns and keeps:
//! - [`World`] (module `world`): the world file, read with every error
//!   reported at its line and column, never a panic. A `World` is always
//!   consistent.
//! - [`Sim`] (module `sim`): the running world. Same world and same seed ⇒
//!   the same run, bit for bit (the event log, rest positions included):
//!   rapier3d's `enhanced-determinism` feature, ordered containers only, and
//!   one seeded ChaCha8 generator for everything random (the words of a
//!   mishearing). The clock is simulated: nothing ever sleeps.
//! - Physics (module `physics`): rapier3d. Floor, walls and shelf boards are
//!   fixed colliders; objects are dynamic boxes, settled by stepping the
//!   pipeline until they sleep (at most [`physics::MAX_SETTLE_STEPS`]
//!   steps; beyond that the log says so and the run goes on). rapier3d
//!   0.36 speaks glam `f32` (through parry's `glamx`), so the crate keeps
//!   its own geometry in nalgebra `f64` and converts at that module's
//!   boundary.
//! - The map (module `map`): a petgraph graph of the places, shortest routes
//!   by Dijkstra; a route takes `length / speed` seconds.
//!
//! # The robot and its senses
//! The robot stands at a place, facing the place's `heading`. Its camera is
//! [`physics::CAMERA_HEIGHT`] above the floor. [`Sim::see`] looks at the
//! shelf whose `at` is the robot's place: it asks the physics world for the
//! dynamic colliders intersecting the box above the shelf's board (as wide
//! and deep as the board, [`physics::VIEW_HEIGHT`] high), then casts a ray
//! from the camera to each one's centre and keeps it only when the ray hits
//! it first (so nothing behind a wall, nothing hidden behind a bigger
//! object). Objects in hands are not in the physics world, so never seen.
//! The user is heard ([`Sim::hear`]) only when in the robot's room.
//!
//! Actions take simulated time: moving `length / speed`; looking
//! [`SEE_SECONDS`]; grasping [`GRASP_SECONDS`]; putting down
//! [`PLACE_SECONDS`]; handing over [`HAND_OVER_SECONDS`]; speaking (either
//! side) [`SECONDS_PER_WORD`] a word; listening in vain [`LISTEN_SECONDS`].
//! An action's event is logged when it starts; the user's moves that fall
//! due while it lasts follow it in the log.
//!
//! # The world file (`world.toml`)
//! Coordinates are metres on the floor plan (`x`, `y`; heights are `z`, up).
//! Every key is listed here; any other key is an error.
//!
//! ```toml
//! seed = 7                  # optional: default seed (integer ≥ 0)
//!
//! [robot]
//! name = "Golem"            # required
//! at = "living_room"        # required: a place
//! speed = 0.5               # optional, m/s, 0.01 to 20 (default 0.5)
//!
//! [user]
//! name = "Luis"             # required
//! at = "living_room"        # required: a place
//! says = ["hi golem", "i like noodles best"]  # optional: utterances, in order
//!
//! [[user.moves]]            # optional, any number
//! after_saying = 3          # trigger: once utterance 3 (from 1) has been heard
//! # at_time = 120.0         #   or: at this absolute simulated second (give one)
//! delay = 0.0               # optional: seconds after the trigger (default 0)
//! to = "outside"            # required: a place (the user is there at once)
//!
//! [[place]]                 # at least the robot's and the user's places
//! name = "living_room"      # required, unique among places
//! x = 0.0                   # required
//! y = 0.0                   # required
//! room = "living_room"      # optional (default: the place's name)
//! heading = 90.0            # optional, degrees anticlockwise from +x (default 0):
//!                           #   the way the robot standing here faces
//!
//! [[route]]                 # optional; with none at all, every two places
//! from = "a"                #   are joined at their Euclidean distance
//! to = "b"                  # required; undirected; not `from` itself
//! length = 4.0              # optional, m, > 0 (default: Euclidean distance)
//!
//! [[wall]]                  # optional: a straight wall, blocks sight
//! from = [1.0, -1.0]        # required: [x, y]
//! to = [1.0, 1.0]           # required: [x, y], not `from`
//! height = 2.5              # optional, m (default 2.5)
//! thickness = 0.1           # optional, m (default 0.1)
//!
//! [[shelf]]
//! name = "shelf_food"       # required, unique among shelves (the KB's name)
//! at = "kitchen_food"       # required: a place with no other shelf; the robot
//!                           #   standing there faces the shelf
//! size = [0.8, 0.4, 0.8]    # optional: width, depth of its top board and the
//!                           #   height of the board's upper face (m)
//!
//! [[object]]
//! name = "noodles"          # required, unique among objects (the KB's name)
//! on = "shelf_food"         # required: a shelf
//! size = [0.07, 0.07, 0.15] # optional: width, depth, height (m)
//! spot = [0.0, 0.1]         # optional: its centre on the board, metres from
//!                           #   the board's centre: across (+ = right as the
//!                           #   robot sees it), depth (+ = away from the robot)
//!
//! [[fault]]
//! kind = "grasp_fails"      # the first `times` grasps of `object` fail
//! object = "malz"           #   (the object stays where it is)
//! times = 1                 # optional, ≥ 1 (default 1)
//!
//! [[fault]]
//! kind = "route_blocked"    # the route between `from` and `to` is blocked both
//! from = "hall"             #   ways; the robot finds out on reaching either end
//! to = "kitchen"            #   and trying it (it must be a [[route]] if any given)
//!
//! [[fault]]
//! kind = "mishear"          # the first time the utterance is heard it comes
//! utterance = 2             #   out garbled (no word of it); the user says it
//!                           #   again at the next hear(). 1-based index into
//!                           #   `says`, or the utterance's exact text
//! ```
//!
//! Objects without a `spot` stand side by side across their shelf's board,
//! in file order (the first leftmost as the robot sees it), evenly spaced,
//! on the board's middle line. They are created a few millimetres above the
//! board and settled. The sizes of everything must lie between
//! [`world::MIN_SIZE`] and [`world::MAX_SIZE`] metres and coordinates within
//! [`world::MAX_COORDINATE`] of the origin.
//!
//! Errors, all found before anything runs, each as
//! `FILE:LINE:COL: error: MESSAGE`: text that is not TOML, an unknown key
//! (anywhere), a missing required key, a wrong type, a number out of range
//! (negative, zero or non-finite sizes and speeds), a name that is not
//! defined (place, shelf, object, utterance), a name defined twice, a shelf
//! at a place that already has one, a route or blocked route from a place to
//! itself, a fault of an unknown kind, objects that do not fit on their
//! shelf or overlap. A name that is both a place and a shelf means the place
//! where [`Sim::navigate`] is given it.

mod map;
pub mod physics;
mod sim;
mod types;
pub mod world;

pub use sim::{
    Sim, GRASP_SECONDS, HAND_OVER_SECONDS, LISTEN_SECONDS, PLACE_SECONDS, SECONDS_PER_WORD,
    SEE_SECONDS,
};
pub use types::{
    Event, EventKind, GraspError, Hand, HandOverError, Heard, NavError, NotAHand, PlaceError,
    Placed, Route, Seen, Where,
};
pub use world::{World, WorldError};
