//! The running simulation: the robot, the user, time, and the event log.
//!
//! Owns the state that changes as the robot acts: where the robot and the
//! user are, what each hand holds, the simulated clock, the faults still to
//! come, the routes known to be blocked, and the log. Invariants: the clock
//! never goes back and never reads the wall clock; events are logged in
//! time order; an object is in exactly one of: the physics world, a hand,
//! the user's hands; everything random comes from one ChaCha8 generator
//! seeded by the caller, so a world and a seed fix the whole run.

use std::collections::BTreeSet;
use std::sync::Arc;

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector2, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::map::{edge, Edge, Map};
use crate::physics::{Physics, CAMERA_HEIGHT, DROP_HEIGHT, HAND_HEIGHT, REACH};
use crate::types::*;
use crate::world::{Fault, Trigger, World};

/// Seconds one look of the camera takes.
pub const SEE_SECONDS: f64 = 1.0;
/// Seconds a grasp takes (failed or not).
pub const GRASP_SECONDS: f64 = 4.0;
/// Seconds putting an object down takes.
pub const PLACE_SECONDS: f64 = 4.0;
/// Seconds handing an object over takes.
pub const HAND_OVER_SECONDS: f64 = 3.0;
/// Seconds per word spoken, by the robot or the user.
pub const SECONDS_PER_WORD: f64 = 0.4;
/// Seconds the robot listens before it gives up when nobody speaks.
pub const LISTEN_SECONDS: f64 = 5.0;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Loc {
    World,
    Hand(Hand),
    User,
}

/// A simulated run of a [`World`].
pub struct Sim {
    world: World,
    robot: Arc<str>,
    user: Arc<str>,
    rng: ChaCha8Rng,
    now: f64,
    robot_at: usize,
    user_at: usize,
    hands: [Option<usize>; 2],
    loc: Vec<Loc>,
    /// Where an object fell when the robot let go of it with no shelf below.
    floor_place: Vec<Option<usize>>,
    grasp_faults: Vec<u32>,
    blocked: BTreeSet<Edge>,
    known_blocked: BTreeSet<Edge>,
    mishear: BTreeSet<usize>,
    next_utterance: usize,
    /// Per user move: when it happens, once its trigger has come.
    move_due: Vec<Option<f64>>,
    move_done: Vec<bool>,
    map: Map,
    physics: Physics,
    events: Vec<Event>,
}

fn words(text: &str) -> usize {
    text.split_whitespace().count().max(1)
}

impl Sim {
    /// Builds the physical world of `world`, settles its objects on their
    /// shelves, and starts the clock at 0. `seed` drives everything random.
    pub fn new(world: &World, seed: u64) -> Sim {
        let mut grasp_faults = vec![0u32; world.objects.len()];
        let mut blocked = BTreeSet::new();
        let mut mishear = BTreeSet::new();
        for f in &world.faults {
            match *f {
                Fault::GraspFails { object, times } => {
                    grasp_faults[object] = grasp_faults[object].saturating_add(times)
                }
                Fault::RouteBlocked { a, b } => {
                    blocked.insert(edge(a, b));
                }
                Fault::Mishear { utterance } => {
                    mishear.insert(utterance);
                }
            }
        }
        let move_due = world
            .user
            .moves
            .iter()
            .map(|m| match m.trigger {
                Trigger::AtTime(t) => Some(t + m.delay),
                Trigger::AfterSaying(_) => None,
            })
            .collect();
        let mut sim = Sim {
            robot: Arc::from(world.robot.name.as_str()),
            user: Arc::from(world.user.name.as_str()),
            rng: ChaCha8Rng::seed_from_u64(seed),
            now: 0.0,
            robot_at: world.robot.at,
            user_at: world.user.at,
            hands: [None, None],
            loc: vec![Loc::World; world.objects.len()],
            floor_place: vec![None; world.objects.len()],
            grasp_faults,
            blocked,
            known_blocked: BTreeSet::new(),
            mishear,
            next_utterance: 0,
            move_done: vec![false; world.user.moves.len()],
            move_due,
            map: Map::new(world),
            physics: Physics::new(world),
            events: Vec::new(),
            world: world.clone(),
        };
        sim.settle();
        sim.advance_to(0.0);
        sim
    }

    // ---- reading the state -------------------------------------------------

    /// The world this run simulates.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Simulated seconds since the start.
    pub fn now(&self) -> f64 {
        self.now
    }

    /// The place the robot is at.
    pub fn robot_at(&self) -> &str {
        &self.world.places[self.robot_at].name
    }

    /// The place the user is at.
    pub fn user_at(&self) -> &str {
        &self.world.places[self.user_at].name
    }

    /// The object a hand holds.
    pub fn holding(&self, hand: Hand) -> Option<&str> {
        self.hands[hand.index()].map(|o| self.world.objects[o].name.as_str())
    }

    /// The shelf in front of a place (the shelf whose `at` is that place).
    pub fn shelf_at(&self, place: &str) -> Option<&str> {
        let p = self.world.place_index(place)?;
        self.shelf_index_at(p)
            .map(|s| self.world.shelves[s].name.as_str())
    }

    fn shelf_index_at(&self, place: usize) -> Option<usize> {
        self.world.shelves.iter().position(|s| s.place == place)
    }

    /// The place in front of a shelf.
    pub fn shelf_place(&self, shelf: &str) -> Option<&str> {
        let s = self.world.shelf_index(shelf)?;
        Some(&self.world.places[self.world.shelves[s].place].name)
    }

    /// The room a place is in.
    pub fn room_of(&self, place: &str) -> Option<&str> {
        let p = self.world.place_index(place)?;
        Some(&self.world.places[p].room)
    }

    /// The routes the robot has found blocked, each as a pair of places.
    pub fn known_blocked(&self) -> Vec<(&str, &str)> {
        self.known_blocked
            .iter()
            .map(|&(a, b)| {
                (
                    self.world.places[a].name.as_str(),
                    self.world.places[b].name.as_str(),
                )
            })
            .collect()
    }

    /// The robot's base pose: at its place on the floor, turned to the
    /// place's heading.
    pub fn robot_pose(&self) -> Isometry3<f64> {
        let p = &self.world.places[self.robot_at];
        Isometry3::from_parts(
            Translation3::new(p.pos.x, p.pos.y, 0.0),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), p.heading),
        )
    }

    /// The camera's pose: above the base at [`CAMERA_HEIGHT`], looking
    /// along the robot's heading (its `x` axis).
    pub fn camera_pose(&self) -> Isometry3<f64> {
        let mut pose = self.robot_pose();
        pose.translation.vector.z = CAMERA_HEIGHT;
        pose
    }

    /// Where an object's centre is, if it is neither in a hand nor with the
    /// user.
    pub fn position(&self, object: &str) -> Option<Point3<f64>> {
        self.physics.position(self.world.object_index(object)?)
    }

    /// The board of a shelf, in world coordinates.
    pub fn shelf_board(&self, shelf: &str) -> Option<&crate::physics::Board> {
        Some(&self.physics.boards()[self.world.shelf_index(shelf)?])
    }

    /// The objects whose bodies have not come to rest (normally none: every
    /// action settles the physics).
    pub fn moving_objects(&self) -> Vec<&str> {
        self.physics
            .awake()
            .into_iter()
            .map(|o| self.world.objects[o].name.as_str())
            .collect()
    }

    /// How many of the user's utterances are still to be heard.
    pub fn utterances_left(&self) -> usize {
        self.world.user.says.len() - self.next_utterance
    }

    /// Where an object is.
    pub fn where_is(&self, object: &str) -> Option<Where> {
        let o = self.world.object_index(object)?;
        Some(match self.loc[o] {
            Loc::Hand(h) => Where::InHand(h),
            Loc::User => Where::WithUser,
            Loc::World => match self.physics.shelf_of(o) {
                Some(s) => Where::OnShelf(self.world.shelves[s].name.clone()),
                None => {
                    let place = self.floor_place[o].unwrap_or_else(|| self.nearest_place(o));
                    Where::Floor(self.world.places[place].name.clone())
                }
            },
        })
    }

    fn nearest_place(&self, o: usize) -> usize {
        let Some(p) = self.physics.position(o) else {
            return self.robot_at;
        };
        let xy = Vector2::new(p.x, p.y);
        (0..self.world.places.len())
            .min_by(|&a, &b| {
                let da = (self.world.places[a].pos.coords - xy).norm();
                let db = (self.world.places[b].pos.coords - xy).norm();
                da.total_cmp(&db).then(a.cmp(&b))
            })
            .unwrap_or(self.robot_at)
    }

    /// Everything that happened, in order.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    // ---- time and the user ---------------------------------------------------

    fn log(&mut self, kind: EventKind) {
        self.events.push(Event {
            time: self.now,
            kind,
            robot: self.robot.clone(),
            user: self.user.clone(),
        });
    }

    fn next_move(&self, until: f64) -> Option<usize> {
        (0..self.move_due.len())
            .filter(|&k| !self.move_done[k])
            .filter_map(|k| self.move_due[k].map(|d| (d, k)))
            .filter(|&(d, _)| d <= until)
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
            .map(|(_, k)| k)
    }

    /// Moves the clock to `t` (never back), carrying out the user's moves
    /// that fall due on the way.
    fn advance_to(&mut self, t: f64) {
        while let Some(k) = self.next_move(t) {
            self.move_done[k] = true;
            let due = self.move_due[k].unwrap_or(self.now);
            self.now = self.now.max(due);
            let from = self.user_at;
            let to = self.world.user.moves[k].to;
            if from != to {
                self.user_at = to;
                self.log(EventKind::UserMoved {
                    from: self.world.places[from].name.clone(),
                    to: self.world.places[to].name.clone(),
                });
            }
        }
        if t.is_finite() {
            self.now = self.now.max(t);
        }
    }

    fn advance(&mut self, seconds: f64) {
        self.advance_to(self.now + seconds);
    }

    fn settle(&mut self) {
        let settled = self.physics.settle();
        if !settled.awake.is_empty() {
            let moving = settled
                .awake
                .iter()
                .map(|&o| self.world.objects[o].name.clone())
                .collect();
            self.log(EventKind::NotSettled {
                steps: settled.steps,
                moving,
            });
        }
    }

    /// Lets `seconds` of simulated time pass (a negative or non-finite
    /// amount counts as 0).
    pub fn wait(&mut self, seconds: f64) {
        let seconds = if seconds.is_finite() && seconds > 0.0 {
            seconds
        } else {
            0.0
        };
        self.log(EventKind::Waited { seconds });
        self.advance(seconds);
    }

    /// Lets time pass until the user is at the robot's place (`true`) or
    /// `max_seconds` have passed (`false`). With an infinite `max_seconds`
    /// it waits through the user's scheduled moves only, and gives up
    /// (without more time passing) when none is left. A negative or NaN
    /// `max_seconds` counts as 0.
    pub fn wait_for_user(&mut self, max_seconds: f64) -> bool {
        let max = if max_seconds > 0.0 { max_seconds } else { 0.0 };
        let start = self.now;
        let limit = start + max;
        let came = loop {
            if self.user_at == self.robot_at {
                break true;
            }
            match self.next_move(limit) {
                Some(k) => {
                    let due = self.move_due[k].unwrap_or(self.now);
                    self.advance_to(due);
                }
                None => {
                    self.advance_to(limit);
                    break self.user_at == self.robot_at;
                }
            }
        };
        // Logged when the wait ends, after the user's moves it waited for;
        // not at all when the user was there already.
        let seconds = self.now - start;
        if came && seconds == 0.0 {
            return true;
        }
        self.events.push(Event {
            time: self.now,
            kind: EventKind::WaitedForUser { seconds, came },
            robot: self.robot.clone(),
            user: self.user.clone(),
        });
        came
    }

    // ---- moving ------------------------------------------------------------

    /// A place name, or a shelf name standing for its place.
    fn resolve(&self, name: &str) -> Option<usize> {
        self.world.place_index(name).or_else(|| {
            self.world
                .shelf_index(name)
                .map(|s| self.world.shelves[s].place)
        })
    }

    fn route_of(&self, path: &[usize], length: f64) -> Route {
        Route {
            places: path
                .iter()
                .map(|&p| self.world.places[p].name.clone())
                .collect(),
            length,
            seconds: length / self.world.robot.speed,
        }
    }

    /// The shortest route between two places (or shelves: their places),
    /// avoiding the routes the robot knows to be blocked.
    pub fn route(&self, from: &str, to: &str) -> Option<Route> {
        let (a, b) = (self.resolve(from)?, self.resolve(to)?);
        let (path, length) = self.map.plan(a, b, &self.known_blocked)?;
        Some(self.route_of(&path, length))
    }

    /// Drives the robot to a place, or to a shelf's place, along the
    /// shortest route it knows to be open. A blocked route is found only on
    /// trying it: the robot stops at its near end, the block is remembered
    /// (later plans avoid it) and `Blocked` is returned.
    pub fn navigate(&mut self, to: &str) -> Result<Route, NavError> {
        let Some(target) = self.resolve(to) else {
            return Err(NavError::UnknownPlace(to.to_string()));
        };
        let from = self.robot_at;
        let name = |s: &Self, p: usize| s.world.places[p].name.clone();
        let Some((path, length)) = self.map.plan(from, target, &self.known_blocked) else {
            let (f, t) = (name(self, from), name(self, target));
            self.log(EventKind::NoRoute {
                from: f.clone(),
                to: t.clone(),
            });
            return Err(NavError::NoRoute { from: f, to: t });
        };
        if path.len() == 1 {
            return Ok(self.route_of(&path, 0.0));
        }
        // Walk the route leg by leg until a blocked leg (if any).
        let mut walked = 0.0;
        for k in 0..path.len() - 1 {
            let leg = edge(path[k], path[k + 1]);
            if self.blocked.contains(&leg) {
                self.known_blocked.insert(leg);
                if k > 0 {
                    self.travel(&path[..=k], walked);
                }
                let (at, next) = (name(self, path[k]), name(self, path[k + 1]));
                self.log(EventKind::Blocked {
                    at: at.clone(),
                    from: at.clone(),
                    to: next.clone(),
                });
                return Err(NavError::Blocked {
                    at: at.clone(),
                    from: at,
                    to: next,
                });
            }
            walked += self.map.direct(path[k], path[k + 1]).unwrap_or(0.0);
        }
        self.travel(&path, length);
        Ok(self.route_of(&path, length))
    }

    fn travel(&mut self, path: &[usize], length: f64) {
        let route = self.route_of(path, length);
        let last = path.len() - 1;
        self.log(EventKind::Moved {
            from: route.places[0].clone(),
            to: route.places[last].clone(),
            via: route.places[1..last].to_vec(),
            metres: route.length,
            seconds: route.seconds,
        });
        self.advance(route.seconds);
        self.robot_at = path[last];
    }

    // ---- seeing and handling -------------------------------------------------

    fn camera(&self) -> Point3<f64> {
        let p = &self.world.places[self.robot_at];
        Point3::new(p.pos.x, p.pos.y, CAMERA_HEIGHT)
    }

    fn visible(&self) -> (Option<usize>, Vec<usize>) {
        match self.shelf_index_at(self.robot_at) {
            Some(s) => (Some(s), self.physics.visible(s, &self.camera())),
            None => (None, Vec::new()),
        }
    }

    /// Looks at the shelf in front of the robot: the objects whose colliders
    /// lie in the viewing volume above its board and that no wall or other
    /// object hides from the camera, left to right.
    pub fn see(&mut self) -> Seen {
        let (shelf, objects) = self.visible();
        let seen = Seen {
            shelf: shelf.map(|s| self.world.shelves[s].name.clone()),
            objects: objects
                .iter()
                .map(|&o| self.world.objects[o].name.clone())
                .collect(),
        };
        self.log(EventKind::Saw {
            shelf: seen.shelf.clone(),
            objects: seen.objects.clone(),
        });
        self.advance(SEE_SECONDS);
        seen
    }

    /// Takes an object from the shelf in front with a hand. The object must
    /// be visible there; a `grasp_fails` fault makes the attempt fail (the
    /// object stays).
    pub fn grasp(&mut self, object: &str, hand: Hand) -> Result<(), GraspError> {
        let Some(o) = self.world.object_index(object) else {
            return Err(GraspError::UnknownObject(object.to_string()));
        };
        if let Some(h) = self.hands[hand.index()] {
            return Err(GraspError::HandFull {
                hand,
                holding: self.world.objects[h].name.clone(),
            });
        }
        if self.loc[o] != Loc::World || !self.visible().1.contains(&o) {
            return Err(GraspError::NotInView {
                object: object.to_string(),
            });
        }
        if self.grasp_faults[o] > 0 {
            self.grasp_faults[o] -= 1;
            self.log(EventKind::GraspFailed {
                object: object.to_string(),
                hand,
            });
            self.advance(GRASP_SECONDS);
            return Err(GraspError::GraspFailed {
                object: object.to_string(),
            });
        }
        self.physics.remove(o);
        self.loc[o] = Loc::Hand(hand);
        self.floor_place[o] = None;
        self.hands[hand.index()] = Some(o);
        self.log(EventKind::Grasped {
            object: object.to_string(),
            hand,
        });
        self.settle();
        self.advance(GRASP_SECONDS);
        Ok(())
    }

    /// Puts down what a hand holds: on the shelf in front (at the free spot
    /// nearest the middle of its board), or, with no shelf in front, lets
    /// it go above the floor, where it falls. Says where it came to rest.
    pub fn place(&mut self, hand: Hand) -> Result<Placed, PlaceError> {
        let Some(o) = self.hands[hand.index()] else {
            return Err(PlaceError::EmptyHand(hand));
        };
        let size = self.physics.size(o);
        let here = &self.world.places[self.robot_at];
        let (centre, yaw) = match self.shelf_index_at(self.robot_at) {
            Some(s) => {
                let board = &self.physics.boards()[s];
                let across = self.physics.free_spot(s, o).unwrap_or(0.0);
                (
                    board.point(across, 0.0, size.z / 2.0 + DROP_HEIGHT),
                    board.heading,
                )
            }
            None => {
                let f = Vector2::new(here.heading.cos(), here.heading.sin());
                let p = here.pos + f * REACH;
                (
                    Point3::new(p.x, p.y, HAND_HEIGHT + size.z / 2.0),
                    here.heading,
                )
            }
        };
        self.physics.spawn(o, &centre, yaw);
        self.hands[hand.index()] = None;
        self.loc[o] = Loc::World;
        let settled = self.physics.settle();
        let rest = self.physics.rest(o).unwrap_or([f32::NAN; 3]);
        let object = self.world.objects[o].name.clone();
        let placed = match self.physics.shelf_of(o) {
            Some(s) => {
                let shelf = self.world.shelves[s].name.clone();
                self.log(EventKind::Placed {
                    object,
                    shelf: shelf.clone(),
                    rest,
                });
                Placed::OnShelf(shelf)
            }
            None => {
                self.floor_place[o] = Some(self.robot_at);
                let place = self.world.places[self.robot_at].name.clone();
                self.log(EventKind::FellToFloor {
                    object,
                    place: place.clone(),
                    rest,
                });
                Placed::Floor { place }
            }
        };
        if !settled.awake.is_empty() {
            let moving = settled
                .awake
                .iter()
                .map(|&o| self.world.objects[o].name.clone())
                .collect();
            self.log(EventKind::NotSettled {
                steps: settled.steps,
                moving,
            });
        }
        self.advance(PLACE_SECONDS);
        Ok(placed)
    }

    /// Hands what a hand holds to the user, who must be at the robot's
    /// place. Returns the object.
    pub fn hand_over(&mut self, hand: Hand) -> Result<String, HandOverError> {
        let Some(o) = self.hands[hand.index()] else {
            return Err(HandOverError::EmptyHand(hand));
        };
        if self.user_at != self.robot_at {
            return Err(HandOverError::NoUser {
                user_at: self.user_at().to_string(),
            });
        }
        self.hands[hand.index()] = None;
        self.loc[o] = Loc::User;
        let object = self.world.objects[o].name.clone();
        self.log(EventKind::HandedOver {
            object: object.clone(),
            hand,
        });
        self.advance(HAND_OVER_SECONDS);
        Ok(object)
    }

    // ---- talking -------------------------------------------------------------

    /// The robot says something (logged; takes [`SECONDS_PER_WORD`] a word).
    pub fn say(&mut self, text: &str) {
        self.log(EventKind::Said {
            text: text.to_string(),
        });
        self.advance(words(text) as f64 * SECONDS_PER_WORD);
    }

    /// Listens for the user's next utterance: heard only when the user is
    /// in the robot's room. A `mishear` fault garbles an utterance the first
    /// time; the user then says it again at the next `hear`.
    pub fn hear(&mut self) -> Heard {
        let room = |s: &Self, p: usize| s.world.places[p].room.clone();
        if room(self, self.user_at) != room(self, self.robot_at) {
            self.log(EventKind::NobodyHeard {
                user_at: self.user_at().to_string(),
            });
            self.advance(LISTEN_SECONDS);
            return Heard::Nobody;
        }
        let i = self.next_utterance;
        let Some(text) = self.world.user.says.get(i).cloned() else {
            self.log(EventKind::NothingMore);
            self.advance(LISTEN_SECONDS);
            return Heard::NothingMore;
        };
        let seconds = words(&text) as f64 * SECONDS_PER_WORD;
        if self.mishear.remove(&i) {
            let garbled = self.garble(&text);
            self.log(EventKind::Misheard {
                text,
                garbled: garbled.clone(),
            });
            self.advance(seconds);
            return Heard::Misheard(garbled);
        }
        self.next_utterance += 1;
        self.log(EventKind::Heard { text: text.clone() });
        for (k, m) in self.world.user.moves.iter().enumerate() {
            if matches!(m.trigger, Trigger::AfterSaying(n) if n == i + 1) {
                self.move_due[k] = Some(self.now + m.delay);
            }
        }
        self.advance(seconds);
        Heard::Said(text)
    }

    /// The user says `text`, words that come from outside the world file (a
    /// person, or a speech recogniser): heard as the world's next utterance
    /// would be, and counted with them (the user's `after_saying` moves
    /// follow it); the world's own `says` are not used.
    pub fn hear_from_outside(&mut self, text: &str) {
        let i = self.next_utterance;
        self.next_utterance += 1;
        self.log(EventKind::Heard {
            text: text.to_string(),
        });
        for (k, m) in self.world.user.moves.iter().enumerate() {
            if matches!(m.trigger, Trigger::AfterSaying(n) if n == i + 1) {
                self.move_due[k] = Some(self.now + m.delay);
            }
        }
        self.advance(words(text) as f64 * SECONDS_PER_WORD);
    }

    /// As many made-up words as `text` has, none of them a word of `text`.
    fn garble(&mut self, text: &str) -> String {
        const CONSONANTS: &[u8] = b"bdfgklmnprstvz";
        const VOWELS: &[u8] = b"aeiou";
        let originals: BTreeSet<String> =
            text.split_whitespace().map(|w| w.to_lowercase()).collect();
        let mut out = Vec::new();
        for _ in 0..words(text) {
            let mut word = String::new();
            for _ in 0..self.rng.random_range(1..=3) {
                word.push(CONSONANTS[self.rng.random_range(0..CONSONANTS.len())] as char);
                word.push(VOWELS[self.rng.random_range(0..VOWELS.len())] as char);
            }
            while originals.contains(&word) {
                word.push('m');
            }
            out.push(word);
        }
        out.join(" ")
    }
}
