//! Reading each section of a world file into raw records: every key checked
//! for its type and range, unknown keys reported, names kept as written
//! (with their positions) for `resolve`. Walls have no names, so they come
//! out finished. A section that cannot be read is reported and left out;
//! reading goes on, to find every error in one pass.

use nalgebra::Point2;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

use super::error::Cx;
use super::model::{
    Trigger, WallSpec, DEFAULT_OBJECT_SIZE, DEFAULT_SHELF_SIZE, DEFAULT_SPEED, DEFAULT_WALL_HEIGHT,
    DEFAULT_WALL_THICKNESS, MAX_COORDINATE, MAX_SIZE, MAX_SPEED, MIN_SIZE, MIN_SPEED,
};
use super::value::{what, At, Tbl};

/// The whole file, read, names unresolved.
pub(super) struct Raw {
    pub seed: Option<u64>,
    pub robot: RawRobot,
    pub user: RawUser,
    pub places: Vec<RawPlace>,
    /// `None`: no `[[route]]` at all.
    pub routes: Option<Vec<RawRoute>>,
    pub walls: Vec<WallSpec>,
    pub shelves: Vec<RawShelf>,
    pub objects: Vec<RawObject>,
    pub faults: Vec<RawFault>,
}

/// `[robot]`: `name` and `at` are `None` when missing or bad (reported).
pub(super) struct RawRobot {
    pub name: Option<At<String>>,
    pub at: Option<At<String>>,
    pub speed: f64,
}

/// `[user]`: `name` and `at` are `None` when missing or bad (reported).
pub(super) struct RawUser {
    pub name: Option<At<String>>,
    pub at: Option<At<String>>,
    pub says: Vec<String>,
    pub moves: Vec<RawMove>,
}

pub(super) struct RawPlace {
    pub name: At<String>,
    pub x: Option<f64>,
    pub y: Option<f64>,
    pub room: Option<String>,
    pub heading: f64,
}

pub(super) struct RawRoute {
    pub at: usize,
    pub from: Option<At<String>>,
    pub to: Option<At<String>>,
    pub length: Option<f64>,
}

pub(super) struct RawShelf {
    pub name: At<String>,
    pub at: Option<At<String>>,
    pub size: [f64; 3],
}

pub(super) struct RawObject {
    pub name: At<String>,
    pub on: Option<At<String>>,
    pub size: [f64; 3],
    pub spot: Option<At<[f64; 2]>>,
}

pub(super) struct RawMove {
    pub trigger: Option<At<Trigger>>,
    pub delay: f64,
    pub to: Option<At<String>>,
}

pub(super) enum RawFault {
    GraspFails {
        object: At<String>,
        times: u32,
    },
    RouteBlocked {
        at: usize,
        from: At<String>,
        to: At<String>,
    },
    Mishear {
        utterance: At<Utterance>,
    },
}

pub(super) enum Utterance {
    Index(i64),
    Text(String),
}

/// Every key of the world file, by table (`""` for the top level; a fault's
/// keys by its kind, `[[fault]] KIND`): what the reader accepts, and what the
/// guide's reference lists (a test of this crate compares the two).
pub const KEYS: &[(&str, &[&str])] = &[
    (
        "",
        &[
            "seed", "robot", "user", "place", "route", "wall", "shelf", "object", "fault",
        ],
    ),
    ("[robot]", &["name", "at", "speed"]),
    ("[user]", &["name", "at", "says", "moves"]),
    (
        "[[user.moves]]",
        &["after_saying", "at_time", "delay", "to"],
    ),
    ("[[place]]", &["name", "x", "y", "room", "heading"]),
    ("[[route]]", &["from", "to", "length"]),
    ("[[wall]]", &["from", "to", "height", "thickness"]),
    ("[[shelf]]", &["name", "at", "size"]),
    ("[[object]]", &["name", "on", "size", "spot"]),
    ("[[fault]] grasp_fails", &["kind", "object", "times"]),
    ("[[fault]] route_blocked", &["kind", "from", "to"]),
    ("[[fault]] mishear", &["kind", "utterance"]),
];

/// The keys of `table` in [`KEYS`].
fn keys_of(table: &str) -> &'static [&'static str] {
    KEYS.iter()
        .find(|(t, _)| *t == table)
        .map(|(_, k)| *k)
        .unwrap_or(&[])
}

/// Reads every section of the file; what cannot be read is reported to `cx`.
pub(super) fn read_world(cx: &mut Cx<'_>, doc: &Spanned<DeTable<'_>>) -> Raw {
    let root = Tbl {
        t: doc.get_ref(),
        at: 0,
        label: "the world file".to_string(),
    };
    cx.keys(&root, keys_of(""));
    let seed = match Cx::get(&root, "seed") {
        Some(v) => cx.integer(&root, "seed", v, 0).map(|n| n.v as u64),
        None => None,
    };
    Raw {
        seed,
        robot: read_robot(cx, &root),
        user: read_user(cx, &root),
        places: read_places(cx, &root),
        routes: read_routes(cx, &root),
        walls: read_walls(cx, &root),
        shelves: read_shelves(cx, &root),
        objects: read_objects(cx, &root),
        faults: read_faults(cx, &root),
    }
}

/// `[robot]`.
fn read_robot(cx: &mut Cx<'_>, root: &Tbl<'_, '_>) -> RawRobot {
    let robot = cx.req(root, "robot").and_then(|v| cx.table(v, "[robot]"));
    let (mut name, mut at, mut speed) = (None, None, DEFAULT_SPEED);
    if let Some(t) = &robot {
        cx.keys(t, keys_of("[robot]"));
        name = cx.name(t, "name");
        at = cx.name(t, "at");
        if let Some(v) = Cx::get(t, "speed") {
            speed = cx
                .ranged(t, "speed", v, MIN_SPEED, MAX_SPEED, false)
                .unwrap_or(speed);
        }
    }
    RawRobot { name, at, speed }
}

/// `[user]` with its `[[user.moves]]`.
fn read_user(cx: &mut Cx<'_>, root: &Tbl<'_, '_>) -> RawUser {
    let user = cx.req(root, "user").and_then(|v| cx.table(v, "[user]"));
    let (mut name, mut at, mut says, mut moves) = (None, None, Vec::new(), Vec::new());
    if let Some(t) = &user {
        cx.keys(t, keys_of("[user]"));
        name = cx.name(t, "name");
        at = cx.name(t, "at");
        if let Some(v) = Cx::get(t, "says") {
            match v.get_ref() {
                DeValue::Array(items) => {
                    for item in items.iter() {
                        if let Some(s) = cx.string(t, "says", item) {
                            says.push(s.v);
                        }
                    }
                }
                other => cx.err(
                    v.span().start,
                    format!(
                        "`says` in [user] must be an array of strings, found {}",
                        what(other)
                    ),
                ),
            }
        }
        if let Some(v) = Cx::get(t, "moves") {
            for m in cx.tables(v, "[[user.moves]]") {
                moves.push(read_move(cx, &m));
            }
        }
    }
    RawUser {
        name,
        at,
        says,
        moves,
    }
}

/// `[[place]]`: a place without a usable name is left out.
fn read_places(cx: &mut Cx<'_>, root: &Tbl<'_, '_>) -> Vec<RawPlace> {
    let mut places = Vec::new();
    let Some(v) = Cx::get(root, "place") else {
        return places;
    };
    for t in cx.tables(v, "[[place]]") {
        cx.keys(&t, keys_of("[[place]]"));
        let name = cx.name(&t, "name");
        let x = cx.req(&t, "x").and_then(|v| cx.coordinate(&t, "x", v));
        let y = cx.req(&t, "y").and_then(|v| cx.coordinate(&t, "y", v));
        let room = Cx::get(&t, "room").and_then(|v| cx.string(&t, "room", v));
        if let Some(r) = &room {
            if r.v.trim().is_empty() {
                cx.err(r.at, "`room` in [[place]] must not be empty".into());
            }
        }
        let heading = Cx::get(&t, "heading")
            .and_then(|v| cx.ranged(&t, "heading", v, -3600.0, 3600.0, false))
            .unwrap_or(0.0);
        if let Some(name) = name {
            places.push(RawPlace {
                name,
                x,
                y,
                room: room.map(|r| r.v),
                heading,
            });
        }
    }
    places
}

/// `[[route]]`: `None` when the file has none at all.
fn read_routes(cx: &mut Cx<'_>, root: &Tbl<'_, '_>) -> Option<Vec<RawRoute>> {
    let v = Cx::get(root, "route")?;
    let mut list = Vec::new();
    for t in cx.tables(v, "[[route]]") {
        cx.keys(&t, keys_of("[[route]]"));
        let from = cx.name(&t, "from");
        let to = cx.name(&t, "to");
        let length = Cx::get(&t, "length").and_then(|v| cx.ranged(&t, "length", v, 0.0, 1e6, true));
        list.push(RawRoute {
            at: t.at,
            from,
            to,
            length,
        });
    }
    Some(list)
}

/// `[[wall]]`, finished: a wall with a bad end or no length is left out.
fn read_walls(cx: &mut Cx<'_>, root: &Tbl<'_, '_>) -> Vec<WallSpec> {
    let mut walls = Vec::new();
    let Some(v) = Cx::get(root, "wall") else {
        return walls;
    };
    for t in cx.tables(v, "[[wall]]") {
        cx.keys(&t, keys_of("[[wall]]"));
        let c = MAX_COORDINATE;
        let from = cx
            .req(&t, "from")
            .and_then(|v| cx.numbers::<2>(&t, "from", v, -c, c, false));
        let to = cx
            .req(&t, "to")
            .and_then(|v| cx.numbers::<2>(&t, "to", v, -c, c, false));
        let height = Cx::get(&t, "height")
            .and_then(|v| cx.ranged(&t, "height", v, MIN_SIZE, MAX_SIZE, false))
            .unwrap_or(DEFAULT_WALL_HEIGHT);
        let thickness = Cx::get(&t, "thickness")
            .and_then(|v| cx.ranged(&t, "thickness", v, MIN_SIZE, MAX_SIZE, false))
            .unwrap_or(DEFAULT_WALL_THICKNESS);
        if let (Some(from), Some(to)) = (from, to) {
            let (a, b) = (Point2::from(from), Point2::from(to));
            if (b - a).norm() < MIN_SIZE {
                cx.err(
                    t.at,
                    format!(
                        "[[wall]] from [{}, {}] to [{}, {}] has no length",
                        from[0], from[1], to[0], to[1]
                    ),
                );
            } else {
                walls.push(WallSpec {
                    from: a,
                    to: b,
                    height,
                    thickness,
                });
            }
        }
    }
    walls
}

/// `[[shelf]]`: a shelf without a usable name is left out.
fn read_shelves(cx: &mut Cx<'_>, root: &Tbl<'_, '_>) -> Vec<RawShelf> {
    let mut shelves = Vec::new();
    let Some(v) = Cx::get(root, "shelf") else {
        return shelves;
    };
    for t in cx.tables(v, "[[shelf]]") {
        cx.keys(&t, keys_of("[[shelf]]"));
        let name = cx.name(&t, "name");
        let at = cx.name(&t, "at");
        let size = match Cx::get(&t, "size") {
            Some(v) => cx.numbers::<3>(&t, "size", v, MIN_SIZE, MAX_SIZE, false),
            None => Some(DEFAULT_SHELF_SIZE),
        };
        // A bad size is reported; the shelf stays so that its objects
        // do not also read as "on a shelf that is not defined".
        if let Some(name) = name {
            let size = size.unwrap_or(DEFAULT_SHELF_SIZE);
            shelves.push(RawShelf { name, at, size });
        }
    }
    shelves
}

/// `[[object]]`: an object without a usable name is left out.
fn read_objects(cx: &mut Cx<'_>, root: &Tbl<'_, '_>) -> Vec<RawObject> {
    let mut objects = Vec::new();
    let Some(v) = Cx::get(root, "object") else {
        return objects;
    };
    for t in cx.tables(v, "[[object]]") {
        cx.keys(&t, keys_of("[[object]]"));
        let name = cx.name(&t, "name");
        let on = cx.name(&t, "on");
        let size = match Cx::get(&t, "size") {
            Some(v) => cx.numbers::<3>(&t, "size", v, MIN_SIZE, MAX_SIZE, false),
            None => Some(DEFAULT_OBJECT_SIZE),
        };
        let spot = Cx::get(&t, "spot").and_then(|v| {
            cx.numbers::<2>(&t, "spot", v, -MAX_SIZE, MAX_SIZE, false)
                .map(|s| At {
                    v: s,
                    at: v.span().start,
                })
        });
        if let Some(name) = name {
            let size = size.unwrap_or(DEFAULT_OBJECT_SIZE);
            objects.push(RawObject {
                name,
                on,
                size,
                spot,
            });
        }
    }
    objects
}

/// `[[fault]]`: a fault that cannot be read is left out.
fn read_faults(cx: &mut Cx<'_>, root: &Tbl<'_, '_>) -> Vec<RawFault> {
    let mut faults = Vec::new();
    if let Some(v) = Cx::get(root, "fault") {
        for t in cx.tables(v, "[[fault]]") {
            if let Some(f) = read_fault(cx, &t) {
                faults.push(f);
            }
        }
    }
    faults
}

fn read_move(cx: &mut Cx<'_>, t: &Tbl<'_, '_>) -> RawMove {
    cx.keys(t, keys_of("[[user.moves]]"));
    let to = cx.name(t, "to");
    let delay = Cx::get(t, "delay")
        .and_then(|v| cx.ranged(t, "delay", v, 0.0, 1e9, false))
        .unwrap_or(0.0);
    let after = Cx::get(t, "after_saying");
    let at_time = Cx::get(t, "at_time");
    let trigger = match (after, at_time) {
        (Some(_), Some(v)) => {
            cx.err(
                v.span().start,
                "[[user.moves]] has both `after_saying` and `at_time`; give one".into(),
            );
            None
        }
        (None, None) => {
            cx.err(
                t.at,
                "missing key `after_saying` or `at_time` in [[user.moves]]".into(),
            );
            None
        }
        (Some(v), None) => cx.integer(t, "after_saying", v, 1).map(|n| At {
            v: Trigger::AfterSaying(n.v as usize),
            at: n.at,
        }),
        (None, Some(v)) => cx.ranged(t, "at_time", v, 0.0, 1e9, false).map(|x| At {
            v: Trigger::AtTime(x),
            at: v.span().start,
        }),
    };
    RawMove { trigger, delay, to }
}

const FAULT_KINDS: &str = "grasp_fails, route_blocked, mishear";

fn read_fault(cx: &mut Cx<'_>, t: &Tbl<'_, '_>) -> Option<RawFault> {
    let kind = cx.name(t, "kind");
    let Some(kind) = kind else {
        // Without a kind the other keys cannot be checked.
        return None;
    };
    let mut t2 = Tbl {
        t: t.t,
        at: t.at,
        label: format!("[[fault]] of kind `{}`", kind.v),
    };
    match kind.v.as_str() {
        "grasp_fails" => {
            cx.keys(&t2, keys_of("[[fault]] grasp_fails"));
            let object = cx.name(&t2, "object");
            let times = match Cx::get(&t2, "times") {
                Some(v) => cx
                    .integer(&t2, "times", v, 1)
                    .map(|n| n.v.min(u32::MAX as i64) as u32),
                None => Some(1),
            };
            Some(RawFault::GraspFails {
                object: object?,
                times: times?,
            })
        }
        "route_blocked" => {
            cx.keys(&t2, keys_of("[[fault]] route_blocked"));
            let from = cx.name(&t2, "from");
            let to = cx.name(&t2, "to");
            Some(RawFault::RouteBlocked {
                at: t.at,
                from: from?,
                to: to?,
            })
        }
        "mishear" => {
            cx.keys(&t2, keys_of("[[fault]] mishear"));
            let v = cx.req(&t2, "utterance")?;
            let at = v.span().start;
            match v.get_ref() {
                DeValue::String(s) => Some(RawFault::Mishear {
                    utterance: At {
                        v: Utterance::Text(s.to_string()),
                        at,
                    },
                }),
                DeValue::Integer(_) => {
                    let n = cx.integer(&t2, "utterance", v, i64::MIN)?;
                    Some(RawFault::Mishear {
                        utterance: At {
                            v: Utterance::Index(n.v),
                            at,
                        },
                    })
                }
                other => {
                    cx.err(
                        at,
                        format!(
                            "`utterance` in {} must be an integer (counting from 1) or the utterance's text, found {}",
                            t2.label,
                            what(other)
                        ),
                    );
                    None
                }
            }
        }
        other => {
            t2.label = "[[fault]]".into();
            cx.err(
                kind.at,
                format!("unknown fault kind `{other}`; known kinds: {FAULT_KINDS}"),
            );
            None
        }
    }
}
