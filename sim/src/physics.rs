//! The physical world: rapier3d bodies for the floor, walls, shelf boards and
//! objects, settling, and the camera's queries.
//!
//! Owns the rapier3d [`PhysicsWorld`] and the link between its colliders and
//! the world's shelves and objects. Invariant: an object is in the physics
//! world (one dynamic body, one cuboid collider whose `user_data` is its
//! index) exactly when it is not in a hand or with the user.
//!
//! Frame: metres, `z` up, the floor's top face at `z = 0`. A place's heading
//! θ gives the robot's forward direction `f = (cos θ, sin θ)` and its right
//! `r = (sin θ, −cos θ)`; a shelf's board is centred `SHELF_DISTANCE` in front
//! of its place, its width along `r`, its depth along `f`.
//!
//! rapier3d 0.36 speaks glam (`f32`, through parry's `glamx`), not nalgebra:
//! the rest of the crate keeps nalgebra `f64` geometry and converts here,
//! at the boundary, with [`to_glam`] and [`to_na`].

use nalgebra::{Point2, Point3, Vector2, Vector3};
use rapier3d::math::{Pose, Rotation, Vector};
use rapier3d::prelude::*;

use crate::world::World;

/// How far in front of its place a shelf's board is centred (m).
pub const SHELF_DISTANCE: f64 = 0.6;
/// Thickness of a shelf's board (m).
pub const BOARD_THICKNESS: f64 = 0.02;
/// Height of the robot's camera above the floor (m).
pub const CAMERA_HEIGHT: f64 = 1.2;
/// Height of the viewing volume above a shelf's board (m).
pub const VIEW_HEIGHT: f64 = 0.6;
/// Height of the robot's hand when it lets go of an object with no shelf
/// in front (m).
pub const HAND_HEIGHT: f64 = 0.8;
/// How far in front of the robot a hand puts things down (m).
pub const REACH: f64 = 0.5;
/// Bound on physics steps (at 60 Hz) for the bodies to fall asleep.
pub const MAX_SETTLE_STEPS: usize = 1200;
/// Gap kept between objects when the robot puts one down on a shelf (m).
pub const PLACE_GAP: f64 = 0.01;
/// Height above the board an object is let go from (m).
pub const DROP_HEIGHT: f64 = 0.005;

const TAG_FLOOR: u128 = 1 << 100;
const TAG_SHELF: u128 = 2 << 100;
const TAG_WALL: u128 = 3 << 100;

/// nalgebra `f64` point → rapier's glam `f32` vector.
pub fn to_glam(p: &Point3<f64>) -> Vector {
    Vector::new(p.x as f32, p.y as f32, p.z as f32)
}

/// rapier's glam `f32` vector → nalgebra `f64` point.
pub fn to_na(v: Vector) -> Point3<f64> {
    Point3::new(v.x as f64, v.y as f64, v.z as f64)
}

fn pose(centre: &Point3<f64>, yaw: f64) -> Pose {
    Pose::from_parts(to_glam(centre), Rotation::from_rotation_z(yaw as f32))
}

/// A shelf's board, in world coordinates.
#[derive(Clone, Debug)]
pub struct Board {
    /// Centre of the board's upper face.
    pub centre: Point3<f64>,
    pub heading: f64,
    pub width: f64,
    pub depth: f64,
}

impl Board {
    pub fn forward(&self) -> Vector2<f64> {
        Vector2::new(self.heading.cos(), self.heading.sin())
    }
    pub fn right(&self) -> Vector2<f64> {
        Vector2::new(self.heading.sin(), -self.heading.cos())
    }
    /// The point on the board's upper face at `across` (+ = right as the
    /// robot sees it) and `depth` (+ = away from the robot), raised by `up`.
    pub fn point(&self, across: f64, depth: f64, up: f64) -> Point3<f64> {
        let p = self.centre.xy() + self.right() * across + self.forward() * depth;
        Point3::new(p.x, p.y, self.centre.z + up)
    }
    /// `(across, depth, up)` of a world point in the board's frame.
    pub fn local(&self, p: &Point3<f64>) -> (f64, f64, f64) {
        let d = p.xy() - self.centre.xy();
        (
            d.dot(&self.right()),
            d.dot(&self.forward()),
            p.z - self.centre.z,
        )
    }
    /// Whether a world point lies above the board's face, within its extent.
    pub fn holds(&self, p: &Point3<f64>) -> bool {
        let (a, d, up) = self.local(p);
        a.abs() <= self.width / 2.0 && d.abs() <= self.depth / 2.0 && up > 0.0
    }
}

/// What a settle did.
#[derive(Clone, Debug, PartialEq)]
pub struct Settled {
    pub steps: usize,
    /// Objects still awake when the step bound was reached.
    pub awake: Vec<usize>,
}

pub struct Physics {
    world: PhysicsWorld,
    boards: Vec<Board>,
    /// Per object: its body and collider while it is in the physics world.
    objects: Vec<Option<(RigidBodyHandle, ColliderHandle)>>,
    sizes: Vec<Vector3<f64>>,
}

impl Physics {
    /// The fixed geometry of `world` and its objects on their shelves,
    /// not yet settled.
    pub fn new(world: &World) -> Physics {
        let mut pw = PhysicsWorld {
            gravity: Vector::new(0.0, 0.0, -9.81),
            ..PhysicsWorld::default()
        };

        // The floor: a slab under everything.
        let mut lo = Point2::new(0.0f64, 0.0);
        let mut hi = lo;
        let mut grow = |p: Point2<f64>| {
            lo = lo.inf(&p);
            hi = hi.sup(&p);
        };
        for p in &world.places {
            grow(p.pos);
        }
        for w in &world.walls {
            grow(w.from);
            grow(w.to);
        }
        let mid = nalgebra::center(&lo, &hi);
        let half = (hi - lo) / 2.0 + Vector2::new(50.0, 50.0);
        pw.insert_collider(
            ColliderBuilder::cuboid(half.x as f32, half.y as f32, 0.5)
                .translation(Vector::new(mid.x as f32, mid.y as f32, -0.5))
                .friction(0.8)
                .user_data(TAG_FLOOR),
            None,
        );

        // Walls.
        for (i, w) in world.walls.iter().enumerate() {
            let d = w.to - w.from;
            let c = nalgebra::center(&w.from, &w.to);
            let centre = Point3::new(c.x, c.y, w.height / 2.0);
            pw.insert_collider(
                ColliderBuilder::cuboid(
                    (d.norm() / 2.0) as f32,
                    (w.thickness / 2.0) as f32,
                    (w.height / 2.0) as f32,
                )
                .position(pose(&centre, d.y.atan2(d.x)))
                .user_data(TAG_WALL | i as u128),
                None,
            );
        }

        // Shelf boards.
        let mut boards = Vec::new();
        for (i, s) in world.shelves.iter().enumerate() {
            let place = &world.places[s.place];
            let f = Vector2::new(place.heading.cos(), place.heading.sin());
            let c = place.pos + f * SHELF_DISTANCE;
            let board = Board {
                centre: Point3::new(c.x, c.y, s.size.z),
                heading: place.heading,
                width: s.size.x,
                depth: s.size.y,
            };
            let centre = board.point(0.0, 0.0, -BOARD_THICKNESS / 2.0);
            pw.insert_collider(
                ColliderBuilder::cuboid(
                    (board.depth / 2.0) as f32,
                    (board.width / 2.0) as f32,
                    (BOARD_THICKNESS / 2.0) as f32,
                )
                .position(pose(&centre, board.heading))
                .friction(0.8)
                .user_data(TAG_SHELF | i as u128),
                None,
            );
            boards.push(board);
        }

        let mut physics = Physics {
            world: pw,
            boards,
            objects: vec![None; world.objects.len()],
            sizes: world.objects.iter().map(|o| o.size).collect(),
        };
        for (i, o) in world.objects.iter().enumerate() {
            let board = &physics.boards[o.shelf];
            let centre = board.point(o.spot.x, o.spot.y, o.size.z / 2.0 + DROP_HEIGHT);
            let yaw = board.heading;
            physics.spawn(i, &centre, yaw);
        }
        physics
    }

    pub fn boards(&self) -> &[Board] {
        &self.boards
    }

    /// Puts object `i` into the physics world as a dynamic box centred at
    /// `centre`, turned by `yaw` about `z`.
    pub fn spawn(&mut self, i: usize, centre: &Point3<f64>, yaw: f64) {
        let size = self.sizes[i];
        let body = RigidBodyBuilder::dynamic()
            .pose(pose(centre, yaw))
            .ccd_enabled(true)
            .build();
        let collider = ColliderBuilder::cuboid(
            (size.y / 2.0) as f32,
            (size.x / 2.0) as f32,
            (size.z / 2.0) as f32,
        )
        .density(300.0)
        .friction(0.8)
        .restitution(0.0)
        .user_data(i as u128)
        .build();
        let handles = self.world.insert(body, collider);
        self.objects[i] = Some(handles);
    }

    /// Takes object `i` out of the physics world (into a hand). Wakes what
    /// touched it.
    pub fn remove(&mut self, i: usize) {
        if let Some((body, _)) = self.objects[i].take() {
            self.world.remove_body(body);
        }
    }

    pub fn is_present(&self, i: usize) -> bool {
        self.objects[i].is_some()
    }

    /// Steps the pipeline until every object sleeps, at least once (so the
    /// query structures know of every change) and at most
    /// [`MAX_SETTLE_STEPS`] times.
    pub fn settle(&mut self) -> Settled {
        let mut steps = 0;
        loop {
            self.world.step();
            steps += 1;
            let awake = self.awake();
            if awake.is_empty() {
                return Settled { steps, awake };
            }
            if steps >= MAX_SETTLE_STEPS {
                return Settled { steps, awake };
            }
        }
    }

    /// The objects whose bodies are awake (still moving).
    pub fn awake(&self) -> Vec<usize> {
        (0..self.objects.len())
            .filter(|&i| match self.objects[i] {
                Some((b, _)) => self.world.bodies.get(b).is_some_and(|b| !b.is_sleeping()),
                None => false,
            })
            .collect()
    }

    /// Where object `i`'s centre is (if it is in the physics world).
    pub fn position(&self, i: usize) -> Option<Point3<f64>> {
        self.rest(i)
            .map(|r| Point3::new(r[0] as f64, r[1] as f64, r[2] as f64))
    }

    /// Object `i`'s centre exactly as rapier has it (`f32`).
    pub fn rest(&self, i: usize) -> Option<[f32; 3]> {
        let (b, _) = self.objects[i]?;
        let t = self.world.bodies.get(b)?.translation();
        Some([t.x, t.y, t.z])
    }

    /// The shelf whose board object `i` rests on (above its face, within
    /// its extent), if any.
    pub fn shelf_of(&self, i: usize) -> Option<usize> {
        let p = self.position(i)?;
        self.boards.iter().position(|b| b.holds(&p))
    }

    /// The objects the camera at `camera` sees on board `s`, left to right:
    /// those whose colliders intersect the box above the board (a
    /// shape-intersection query), each kept only when a ray from the camera
    /// to its centre hits it first.
    pub fn visible(&self, s: usize, camera: &Point3<f64>) -> Vec<usize> {
        let board = &self.boards[s];
        let volume = Cuboid::new(Vector::new(
            (board.depth / 2.0) as f32,
            (board.width / 2.0) as f32,
            (VIEW_HEIGHT / 2.0) as f32,
        ));
        let at = pose(&board.point(0.0, 0.0, VIEW_HEIGHT / 2.0), board.heading);
        let mut candidates: Vec<(usize, ColliderHandle)> = self
            .world
            .intersect_shape(at, &volume, QueryFilter::only_dynamic())
            .filter_map(|(h, c)| {
                let i = c.user_data as usize;
                (i < self.objects.len() && self.objects[i].is_some_and(|(_, ch)| ch == h))
                    .then_some((i, h))
            })
            .collect();
        candidates.sort_by_key(|c| c.0);
        candidates.dedup_by_key(|c| c.0);
        let origin = to_glam(camera);
        let mut seen: Vec<(f64, usize)> = Vec::new();
        for (i, h) in candidates {
            let Some(target) = self.world.colliders.get(h).map(|c| c.translation()) else {
                continue;
            };
            let d = target - origin;
            let dist = d.length();
            if dist.is_nan() || dist <= 1e-6 {
                continue;
            }
            let ray = Ray::new(origin, d / dist);
            let first = self
                .world
                .cast_ray(&ray, dist, true, QueryFilter::default())
                .map(|(hit, _)| hit);
            if first == Some(h) {
                let (across, _, _) = board.local(&to_na(target));
                seen.push((across, i));
            }
        }
        seen.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        seen.into_iter().map(|(_, i)| i).collect()
    }

    /// Where on board `s` (across, along its middle line) object `i` can be
    /// put down without touching the objects already there: the free spot
    /// nearest the middle. `None` when nothing is free.
    pub fn free_spot(&self, s: usize, i: usize) -> Option<f64> {
        let board = &self.boards[s];
        let w = self.sizes[i].x;
        let taken: Vec<(f64, f64)> = (0..self.objects.len())
            .filter(|&o| o != i && self.shelf_of(o) == Some(s))
            .filter_map(|o| {
                let (a, _, _) = board.local(&self.position(o)?);
                // Half the diagonal of the footprint: safe whatever the turn.
                let r = self.sizes[o].x.hypot(self.sizes[o].y) / 2.0;
                Some((a - r, a + r))
            })
            .collect();
        let limit = board.width / 2.0 - w / 2.0;
        if limit < 0.0 {
            return None;
        }
        let mut candidates = vec![0.0];
        for &(lo, hi) in &taken {
            candidates.push(hi + PLACE_GAP + w / 2.0);
            candidates.push(lo - PLACE_GAP - w / 2.0);
        }
        candidates.push(limit);
        candidates.push(-limit);
        candidates
            .into_iter()
            .filter(|c| c.abs() <= limit + 1e-12)
            .filter(|c| {
                taken.iter().all(|&(lo, hi)| {
                    c + w / 2.0 + PLACE_GAP <= lo + 1e-9 || c - w / 2.0 - PLACE_GAP >= hi - 1e-9
                })
            })
            .min_by(|a, b| a.abs().total_cmp(&b.abs()).then(a.total_cmp(b)))
    }

    pub fn size(&self, i: usize) -> Vector3<f64> {
        self.sizes[i]
    }
}
