//! The values the simulator hands out: hands, routes, what was seen, heard
//! and where things are, the errors of the robot's actions (each with the
//! status atom the robot reports, [`NavError::code`] and the like), and the
//! event log with its one-sentence narration.
//!
//! Invariant: every error's `code()` is a short snake_case atom, stable
//! across releases (robot programs match on it).

use std::fmt;
use std::str::FromStr;
use std::sync::Arc;

use serde::Serialize;

/// One of the robot's two hands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Hand {
    Left,
    Right,
}

impl Hand {
    /// Both hands, left first.
    pub const ALL: [Hand; 2] = [Hand::Left, Hand::Right];

    pub(crate) fn index(self) -> usize {
        match self {
            Hand::Left => 0,
            Hand::Right => 1,
        }
    }

    /// `"left"` or `"right"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Hand::Left => "left",
            Hand::Right => "right",
        }
    }
}

impl fmt::Display for Hand {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The text was neither `left` nor `right`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NotAHand(pub String);

impl fmt::Display for NotAHand {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}` is not a hand (left or right)", self.0)
    }
}

impl std::error::Error for NotAHand {}

impl FromStr for Hand {
    type Err = NotAHand;
    fn from_str(s: &str) -> Result<Hand, NotAHand> {
        match s {
            "left" => Ok(Hand::Left),
            "right" => Ok(Hand::Right),
            _ => Err(NotAHand(s.to_string())),
        }
    }
}

/// A route over the map: its places in order (both ends included), its
/// length in metres and the seconds it takes at the robot's speed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Route {
    pub places: Vec<String>,
    pub length: f64,
    pub seconds: f64,
}

/// What the camera saw: the shelf in front (none if there is none) and the
/// objects on it it can see, left to right as the camera sees them.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Seen {
    pub shelf: Option<String>,
    pub objects: Vec<String>,
}

/// What the robot heard when it listened.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Heard {
    /// The user's next utterance, as the user said it.
    Said(String),
    /// The user spoke, but the robot understood only these (garbled) words;
    /// the user says it again at the next `hear`.
    Misheard(String),
    /// The user is not in the robot's room.
    Nobody,
    /// The user has said everything in the world file.
    NothingMore,
}

/// Where an object is.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Where {
    /// Resting on this shelf's board (or on something that rests on it).
    OnShelf(String),
    InHand(Hand),
    /// On the floor, at (near) this place.
    Floor(String),
    /// Handed over to the user.
    WithUser,
}

/// Where an object the robot put down came to rest.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Placed {
    OnShelf(String),
    Floor { place: String },
}

/// Why `navigate` failed.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum NavError {
    /// Neither a place nor a shelf of the world.
    UnknownPlace(String),
    /// The route from `from` to `to` turned out to be blocked when the robot
    /// tried it; the robot stopped at `at` (= `from`). Later plans avoid it.
    Blocked {
        at: String,
        from: String,
        to: String,
    },
    /// No route (avoiding the known blocks) joins the two places.
    NoRoute { from: String, to: String },
}

impl NavError {
    /// The status atom: `unknown_place`, `blocked`, `no_route`.
    pub fn code(&self) -> &'static str {
        match self {
            NavError::UnknownPlace(_) => "unknown_place",
            NavError::Blocked { .. } => "blocked",
            NavError::NoRoute { .. } => "no_route",
        }
    }
}

impl fmt::Display for NavError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NavError::UnknownPlace(p) => write!(f, "there is no place or shelf `{p}`"),
            NavError::Blocked { at, from, to } => write!(
                f,
                "the route from `{from}` to `{to}` is blocked; the robot stopped at `{at}`"
            ),
            NavError::NoRoute { from, to } => {
                write!(f, "there is no route from `{from}` to `{to}`")
            }
        }
    }
}

impl std::error::Error for NavError {}

/// Why `grasp` failed.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GraspError {
    UnknownObject(String),
    /// The object is not on the shelf in front of the robot, or the camera
    /// cannot see it there.
    NotInView {
        object: String,
    },
    HandFull {
        hand: Hand,
        holding: String,
    },
    /// The hand closed on nothing (a `grasp_fails` fault); the object stays
    /// where it was.
    GraspFailed {
        object: String,
    },
}

impl GraspError {
    /// The status atom: `unknown_object`, `not_in_view`, `hand_full`,
    /// `grasp_failed`.
    pub fn code(&self) -> &'static str {
        match self {
            GraspError::UnknownObject(_) => "unknown_object",
            GraspError::NotInView { .. } => "not_in_view",
            GraspError::HandFull { .. } => "hand_full",
            GraspError::GraspFailed { .. } => "grasp_failed",
        }
    }
}

impl fmt::Display for GraspError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GraspError::UnknownObject(o) => write!(f, "there is no object `{o}`"),
            GraspError::NotInView { object } => {
                write!(f, "`{object}` is not in view on the shelf in front")
            }
            GraspError::HandFull { hand, holding } => {
                write!(f, "the {hand} hand already holds `{holding}`")
            }
            GraspError::GraspFailed { object } => write!(f, "the grasp of `{object}` failed"),
        }
    }
}

impl std::error::Error for GraspError {}

/// Why `place` failed.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PlaceError {
    EmptyHand(Hand),
}

impl PlaceError {
    /// The status atom: `empty_hand`.
    pub fn code(&self) -> &'static str {
        match self {
            PlaceError::EmptyHand(_) => "empty_hand",
        }
    }
}

impl fmt::Display for PlaceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlaceError::EmptyHand(h) => write!(f, "the {h} hand holds nothing"),
        }
    }
}

impl std::error::Error for PlaceError {}

/// Why `hand_over` failed.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum HandOverError {
    EmptyHand(Hand),
    /// The user is not at the robot's place (they are at `user_at`).
    NoUser {
        user_at: String,
    },
}

impl HandOverError {
    /// The status atom: `empty_hand`, `no_user`.
    pub fn code(&self) -> &'static str {
        match self {
            HandOverError::EmptyHand(_) => "empty_hand",
            HandOverError::NoUser { .. } => "no_user",
        }
    }
}

impl fmt::Display for HandOverError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HandOverError::EmptyHand(h) => write!(f, "the {h} hand holds nothing"),
            HandOverError::NoUser { user_at } => {
                write!(f, "the user is not here (the user is at `{user_at}`)")
            }
        }
    }
}

impl std::error::Error for HandOverError {}

/// One thing that happened, at simulated time `time` (seconds since the
/// start). An action's event is logged when the action starts; the time the
/// action takes passes after it (and the user's moves in that time follow
/// it in the log), so times never decrease along the log.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Event {
    pub time: f64,
    pub kind: EventKind,
    /// The robot's name, for the narration.
    #[serde(skip)]
    pub robot: Arc<str>,
    /// The user's name, for the narration.
    #[serde(skip)]
    pub user: Arc<str>,
}

/// What happened.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "event")]
pub enum EventKind {
    /// The robot went from `from` to `to` through `via`.
    Moved {
        from: String,
        to: String,
        via: Vec<String>,
        metres: f64,
        seconds: f64,
    },
    /// The robot, at `at`, found the route from `from` to `to` blocked.
    Blocked {
        at: String,
        from: String,
        to: String,
    },
    /// No route from `from` to `to` (avoiding known blocks).
    NoRoute {
        from: String,
        to: String,
    },
    /// The camera looked at `shelf` (none in front: `None`) and saw these.
    Saw {
        shelf: Option<String>,
        objects: Vec<String>,
    },
    Grasped {
        object: String,
        hand: Hand,
    },
    GraspFailed {
        object: String,
        hand: Hand,
    },
    /// The object came to rest on `shelf`, its centre at `rest`.
    Placed {
        object: String,
        shelf: String,
        rest: [f32; 3],
    },
    /// The object fell to the floor at `place`, its centre at `rest`.
    FellToFloor {
        object: String,
        place: String,
        rest: [f32; 3],
    },
    HandedOver {
        object: String,
        hand: Hand,
    },
    Said {
        text: String,
    },
    Heard {
        text: String,
    },
    /// The user said utterance `text`, the robot understood `garbled`.
    Misheard {
        text: String,
        garbled: String,
    },
    /// The robot listened; the user is in another room.
    NobodyHeard {
        user_at: String,
    },
    /// The robot listened; the user has nothing more to say.
    NothingMore,
    UserMoved {
        from: String,
        to: String,
    },
    Waited {
        seconds: f64,
    },
    /// The robot waited for the user to come to its place.
    WaitedForUser {
        seconds: f64,
        came: bool,
    },
    /// The physics did not come to rest within the step bound: these
    /// objects were still moving (the run carries on).
    NotSettled {
        steps: usize,
        moving: Vec<String>,
    },
}

fn list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

impl fmt::Display for Event {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (robot, user) = (&*self.robot, &*self.user);
        match &self.kind {
            EventKind::Moved {
                from,
                to,
                via,
                metres,
                seconds,
            } => {
                write!(f, "{robot} goes from {from} to {to}")?;
                if !via.is_empty() {
                    write!(f, " via {}", list(via))?;
                }
                write!(f, " ({metres:.1} m, {seconds:.1} s)")
            }
            EventKind::Blocked { at, from, to } => write!(
                f,
                "{robot} finds the way from {from} to {to} blocked and stops at {at}"
            ),
            EventKind::NoRoute { from, to } => {
                write!(f, "{robot} finds no way from {from} to {to}")
            }
            EventKind::Saw { shelf: None, .. } => {
                write!(f, "{robot} looks, but there is no shelf in front of it")
            }
            EventKind::Saw {
                shelf: Some(s),
                objects,
            } => {
                if objects.is_empty() {
                    write!(f, "{robot} looks at {s} and sees nothing")
                } else {
                    write!(f, "{robot} looks at {s} and sees {}", list(objects))
                }
            }
            EventKind::Grasped { object, hand } => {
                write!(f, "{robot} takes {object} with its {hand} hand")
            }
            EventKind::GraspFailed { object, hand } => {
                write!(
                    f,
                    "{robot} tries to take {object} with its {hand} hand, but it slips"
                )
            }
            EventKind::Placed { object, shelf, .. } => {
                write!(f, "{robot} puts {object} on {shelf}")
            }
            EventKind::FellToFloor { object, place, .. } => {
                write!(
                    f,
                    "{robot} lets go of {object}, which falls to the floor at {place}"
                )
            }
            EventKind::HandedOver { object, .. } => {
                write!(f, "{robot} hands {object} to {user}")
            }
            EventKind::Said { text } => write!(f, "{robot} says: \"{text}\""),
            EventKind::Heard { text } => write!(f, "{user} says: \"{text}\""),
            EventKind::Misheard { garbled, .. } => {
                write!(
                    f,
                    "{robot} hears {user} say \"{garbled}\" and cannot make it out"
                )
            }
            EventKind::NobodyHeard { .. } => {
                write!(f, "{robot} listens, but {user} is not in the room")
            }
            EventKind::NothingMore => write!(f, "{robot} listens, but {user} says nothing more"),
            EventKind::UserMoved { from, to } => write!(f, "{user} goes from {from} to {to}"),
            EventKind::Waited { seconds } => write!(f, "{robot} waits {seconds:.1} s"),
            EventKind::WaitedForUser { seconds, came } => {
                if *came {
                    write!(f, "{robot} waits {seconds:.1} s for {user}, who comes")
                } else {
                    write!(
                        f,
                        "{robot} waits {seconds:.1} s for {user}, who does not come"
                    )
                }
            }
            EventKind::NotSettled { steps, moving } => write!(
                f,
                "after {steps} physics steps {} still {}",
                list(moving),
                if moving.len() == 1 { "moves" } else { "move" }
            ),
        }
    }
}
