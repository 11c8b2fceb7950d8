//! From raw records to the [`World`]: every name looked up (places, shelves,
//! objects, utterances), names defined twice, a second shelf at a place,
//! routes and blocked routes from a place to itself, moves and faults that
//! name what is not there; then the objects laid out on their boards.
//! Invariant: it returns a `World` only when every name it holds resolved
//! (the caller also requires that no error was reported at all).

use std::collections::BTreeMap;

use nalgebra::{Point2, Vector2, Vector3};

use super::error::Cx;
use super::layout::layout;
use super::model::{
    Fault, ObjectSpec, PlaceSpec, RobotSpec, RouteSpec, ShelfSpec, Trigger, UserMove, UserSpec,
    World,
};
use super::read::{Raw, RawFault, RawMove, RawObject, RawPlace, RawRoute, RawShelf, Utterance};
use super::value::At;

/// The places, resolved: specs in file order and an index by name.
struct Places {
    specs: Vec<PlaceSpec>,
    ix: BTreeMap<String, usize>,
}

impl Places {
    /// The index of the place `name`, or an error `{what} place `name`, which
    /// is not defined`.
    fn find(&self, cx: &mut Cx<'_>, name: &At<String>, what: String) -> Option<usize> {
        match self.ix.get(&name.v) {
            Some(&i) => Some(i),
            None => {
                cx.err(
                    name.at,
                    format!(
                        "{what} place `{}`, which is not defined{}",
                        name.v,
                        did_you_mean(&name.v, self.ix.keys().map(String::as_str))
                    ),
                );
                None
            }
        }
    }

    fn name(&self, i: usize) -> &str {
        &self.specs[i].name
    }
}

/// `; did you mean `x`?` when one of `known` is close enough to `name` to
/// be a typo of it (at most a third of its length apart by edit distance,
/// at least one edit allowed; names of 3 characters or more), the closest
/// first; else nothing. The rule of the checker's *did you mean*.
fn did_you_mean<'a>(name: &str, known: impl Iterator<Item = &'a str>) -> String {
    fn distance(a: &str, b: &str) -> usize {
        let b: Vec<char> = b.chars().collect();
        let mut row: Vec<usize> = (0..=b.len()).collect();
        for (i, ca) in a.chars().enumerate() {
            let mut prev = row[0];
            row[0] = i + 1;
            for (j, &cb) in b.iter().enumerate() {
                let cur = row[j + 1];
                row[j + 1] = (prev + usize::from(ca != cb)).min(cur + 1).min(row[j] + 1);
                prev = cur;
            }
        }
        row[b.len()]
    }
    let len = name.chars().count();
    if len < 3 {
        return String::new();
    }
    let limit = (len / 3).max(1);
    known
        .filter(|k| *k != name)
        .map(|k| (distance(name, k), k))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map_or_else(String::new, |(_, k)| format!("; did you mean `{k}`?"))
}

/// The user as the checks of moves and faults name it.
struct Speaker<'a> {
    /// What the user says, in order.
    says: &'a [String],
    /// `user `NAME``, or `the user` when the name is missing.
    label: &'a str,
}

/// The world of `raw`, or `None` when something it needs did not resolve
/// (each such thing is reported to `cx`).
pub(super) fn resolve(cx: &mut Cx<'_>, raw: Raw) -> Option<World> {
    let places = places(cx, &raw.places);

    let robot_at = match (&raw.robot.name, &raw.robot.at) {
        (Some(n), Some(a)) => places.find(cx, a, format!("robot `{}` is at", n.v)),
        (None, Some(a)) => places.find(cx, a, "the robot is at".into()),
        _ => None,
    };
    let user_at = match (&raw.user.name, &raw.user.at) {
        (Some(n), Some(a)) => places.find(cx, a, format!("user `{}` is at", n.v)),
        (None, Some(a)) => places.find(cx, a, "the user is at".into()),
        _ => None,
    };
    let user_label = raw
        .user
        .name
        .as_ref()
        .map(|n| format!("user `{}`", n.v))
        .unwrap_or_else(|| "the user".into());
    let says = raw.user.says;
    let speaker = Speaker {
        says: &says,
        label: &user_label,
    };
    let moves = moves(cx, &places, &raw.user.moves, &speaker);
    let routes = raw.routes.as_deref().map(|list| routes(cx, &places, list));
    let (shelves, shelf_ix) = shelves(cx, &places, &raw.shelves);
    let (objects, object_ix) = objects(cx, &raw.shelves, &shelves, &shelf_ix, &raw.objects);
    let faults = faults(
        cx,
        &places,
        routes.as_deref(),
        &raw.objects,
        &object_ix,
        &speaker,
        &raw.faults,
    );

    Some(World {
        file: cx.file.clone(),
        seed: raw.seed,
        robot: RobotSpec {
            name: raw.robot.name?.v,
            at: robot_at?,
            speed: raw.robot.speed,
        },
        user: UserSpec {
            name: raw.user.name?.v,
            at: user_at?,
            says,
            moves,
        },
        places: places.specs,
        routes,
        walls: raw.walls,
        shelves,
        objects,
        faults,
    })
}

/// The places in file order; a name defined twice keeps its first place.
fn places(cx: &mut Cx<'_>, raw: &[RawPlace]) -> Places {
    let mut ix: BTreeMap<String, usize> = BTreeMap::new();
    let mut specs = Vec::new();
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    for p in raw {
        if let Some(&first_at) = seen.get(&p.name.v) {
            let pos = cx.pos(first_at);
            cx.err(
                p.name.at,
                format!("place `{}` is defined twice (first at {pos})", p.name.v),
            );
            continue;
        }
        seen.insert(p.name.v.clone(), p.name.at);
        ix.insert(p.name.v.clone(), specs.len());
        specs.push(PlaceSpec {
            name: p.name.v.clone(),
            pos: Point2::new(p.x.unwrap_or(0.0), p.y.unwrap_or(0.0)),
            room: p.room.clone().unwrap_or_else(|| p.name.v.clone()),
            heading: p.heading.to_radians(),
        });
    }
    Places { specs, ix }
}

/// `[[user.moves]]`: each to a place, each `after_saying` an utterance.
fn moves(cx: &mut Cx<'_>, places: &Places, raw: &[RawMove], user: &Speaker<'_>) -> Vec<UserMove> {
    let (says, user_label) = (user.says, user.label);
    let mut moves = Vec::new();
    for m in raw {
        let to =
            m.to.as_ref()
                .and_then(|to| places.find(cx, to, format!("{user_label} moves to")));
        if let Some(At {
            v: Trigger::AfterSaying(n),
            at,
        }) = &m.trigger
        {
            if *n > says.len() {
                cx.err(
                    *at,
                    format!(
                        "`after_saying = {n}` in [[user.moves]], but {user_label} says only {} utterance{}",
                        says.len(),
                        if says.len() == 1 { "" } else { "s" }
                    ),
                );
                continue;
            }
        }
        if let (Some(trigger), Some(to)) = (&m.trigger, to) {
            moves.push(UserMove {
                trigger: trigger.v,
                delay: m.delay,
                to,
            });
        }
    }
    moves
}

/// `[[route]]`: between two different places, of a length above 0.
fn routes(cx: &mut Cx<'_>, places: &Places, raw: &[RawRoute]) -> Vec<RouteSpec> {
    let mut specs = Vec::new();
    for r in raw {
        let from = r
            .from
            .as_ref()
            .and_then(|n| places.find(cx, n, "[[route]] starts at".into()));
        let to =
            r.to.as_ref()
                .and_then(|n| places.find(cx, n, "[[route]] goes to".into()));
        if let (Some(a), Some(b)) = (from, to) {
            if a == b {
                cx.err(
                    r.at,
                    format!("[[route]] from `{}` to itself", places.name(a)),
                );
                continue;
            }
            let length = r
                .length
                .unwrap_or_else(|| (places.specs[a].pos - places.specs[b].pos).norm());
            if length <= 0.0 {
                cx.err(
                    r.at,
                    format!(
                        "[[route]] from `{}` to `{}` has length 0 (the places coincide); give a `length`",
                        places.name(a), places.name(b)
                    ),
                );
                continue;
            }
            specs.push(RouteSpec {
                from: a,
                to: b,
                length,
            });
        }
    }
    specs
}

/// `[[shelf]]`: each at a place that has no other shelf. Also the index of
/// the shelves kept, by name.
fn shelves(
    cx: &mut Cx<'_>,
    places: &Places,
    raw: &[RawShelf],
) -> (Vec<ShelfSpec>, BTreeMap<String, usize>) {
    let mut shelf_ix: BTreeMap<String, usize> = BTreeMap::new();
    let mut shelf_at_place: BTreeMap<usize, (String, usize)> = BTreeMap::new();
    let mut specs: Vec<ShelfSpec> = Vec::new();
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    for s in raw {
        if let Some(&first_at) = seen.get(&s.name.v) {
            let pos = cx.pos(first_at);
            cx.err(
                s.name.at,
                format!("shelf `{}` is defined twice (first at {pos})", s.name.v),
            );
            continue;
        }
        seen.insert(s.name.v.clone(), s.name.at);
        let Some(at) = &s.at else { continue };
        let Some(p) = places.find(cx, at, format!("shelf `{}` is at", s.name.v)) else {
            continue;
        };
        if let Some((other, _)) = shelf_at_place.get(&p) {
            cx.err(
                at.at,
                format!(
                    "shelf `{}` is at place `{}`, which already has shelf `{other}`",
                    s.name.v, at.v
                ),
            );
            continue;
        }
        shelf_at_place.insert(p, (s.name.v.clone(), specs.len()));
        shelf_ix.insert(s.name.v.clone(), specs.len());
        specs.push(ShelfSpec {
            name: s.name.v.clone(),
            place: p,
            size: Vector3::from(s.size),
        });
    }
    (specs, shelf_ix)
}

/// `[[object]]`: each on a shelf, laid out on its board. Also the index of
/// the objects kept, by name.
fn objects(
    cx: &mut Cx<'_>,
    raw_shelves: &[RawShelf],
    shelves: &[ShelfSpec],
    shelf_ix: &BTreeMap<String, usize>,
    raw: &[RawObject],
) -> (Vec<ObjectSpec>, BTreeMap<String, usize>) {
    let shelf_names_all: std::collections::BTreeSet<&str> =
        raw_shelves.iter().map(|s| s.name.v.as_str()).collect();
    let mut object_ix: BTreeMap<String, usize> = BTreeMap::new();
    let mut specs: Vec<ObjectSpec> = Vec::new();
    let mut explicit: Vec<bool> = Vec::new();
    let mut object_at: Vec<usize> = Vec::new();
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    for o in raw {
        if let Some(&first_at) = seen.get(&o.name.v) {
            let pos = cx.pos(first_at);
            cx.err(
                o.name.at,
                format!("object `{}` is defined twice (first at {pos})", o.name.v),
            );
            continue;
        }
        seen.insert(o.name.v.clone(), o.name.at);
        let Some(on) = &o.on else { continue };
        let Some(&s) = shelf_ix.get(&on.v) else {
            // A shelf that was defined but dropped for another error is not
            // "not defined": say nothing more about it.
            if !shelf_names_all.contains(&on.v.as_str()) {
                cx.err(
                    on.at,
                    format!(
                        "object `{}` is on shelf `{}`, which is not defined{}",
                        o.name.v,
                        on.v,
                        did_you_mean(&on.v, shelf_names_all.iter().copied())
                    ),
                );
            }
            continue;
        };
        object_ix.insert(o.name.v.clone(), specs.len());
        explicit.push(o.spot.is_some());
        object_at.push(o.spot.as_ref().map(|s| s.at).unwrap_or(o.name.at));
        specs.push(ObjectSpec {
            name: o.name.v.clone(),
            shelf: s,
            size: Vector3::from(o.size),
            spot: o
                .spot
                .as_ref()
                .map(|s| Vector2::from(s.v))
                .unwrap_or_else(Vector2::zeros),
        });
    }
    layout(cx, shelves, &mut specs, &explicit, &object_at);
    (specs, object_ix)
}

/// `[[fault]]`: each naming an object, a route or an utterance that is there.
fn faults(
    cx: &mut Cx<'_>,
    places: &Places,
    routes: Option<&[RouteSpec]>,
    raw_objects: &[RawObject],
    object_ix: &BTreeMap<String, usize>,
    user: &Speaker<'_>,
    raw: &[RawFault],
) -> Vec<Fault> {
    let (says, user_label) = (user.says, user.label);
    let mut specs = Vec::new();
    for f in raw {
        match f {
            RawFault::GraspFails { object, times } => match object_ix.get(&object.v) {
                Some(&o) => specs.push(Fault::GraspFails {
                    object: o,
                    times: *times,
                }),
                None => {
                    if !raw_objects.iter().any(|x| x.name.v == object.v) {
                        cx.err(
                            object.at,
                            format!(
                                "fault `grasp_fails` names object `{}`, which is not defined{}",
                                object.v,
                                did_you_mean(&object.v, raw_objects.iter().map(|x| x.name.v.as_str()))
                            ),
                        )
                    }
                }
            },
            RawFault::RouteBlocked { at, from, to } => {
                let a = places.find(cx, from, "fault `route_blocked` starts at".into());
                let b = places.find(cx, to, "fault `route_blocked` goes to".into());
                if let (Some(a), Some(b)) = (a, b) {
                    if a == b {
                        cx.err(
                            *at,
                            format!(
                                "fault `route_blocked` from `{}` to itself",
                                places.name(a)
                            ),
                        );
                        continue;
                    }
                    if let Some(routes) = routes {
                        let exists = routes
                            .iter()
                            .any(|r| (r.from, r.to) == (a, b) || (r.from, r.to) == (b, a));
                        if !exists {
                            cx.err(
                                *at,
                                format!(
                                    "fault `route_blocked`: there is no [[route]] between `{}` and `{}` to block",
                                    places.name(a), places.name(b)
                                ),
                            );
                            continue;
                        }
                    }
                    specs.push(Fault::RouteBlocked { a, b });
                }
            }
            RawFault::Mishear { utterance } => match &utterance.v {
                Utterance::Index(n) => {
                    if *n < 1 || *n as u64 > says.len() as u64 {
                        cx.err(
                            utterance.at,
                            format!(
                                "fault `mishear` names utterance {n}, but {user_label} says {} utterance{} (counting from 1)",
                                says.len(),
                                if says.len() == 1 { "" } else { "s" }
                            ),
                        );
                    } else {
                        specs.push(Fault::Mishear {
                            utterance: *n as usize - 1,
                        });
                    }
                }
                Utterance::Text(text) => match says.iter().position(|s| s == text) {
                    Some(i) => specs.push(Fault::Mishear { utterance: i }),
                    None => cx.err(
                        utterance.at,
                        format!(
                            "fault `mishear` names utterance {text:?}, which {user_label} never says"
                        ),
                    ),
                },
            },
        }
    }
    specs
}
