//! Links between DMs (pipes, control links, recovery links, the
//! overview's calls) routed round the nodes in their way: where the curve
//! passes through a node's circle (with a margin), the route is a smooth
//! curve through waypoints beside the nodes in the way. A link that
//! crosses no node keeps its curve as it was. Deterministic (no
//! randomness, bounded work).

use super::geometry::{Cmd, Placed, P};

/// Clearance between a routed link and a node it passes.
const MARGIN: f64 = 10.0;

/// A node in the way: centre and radius (its shape's circumscribed circle).
#[derive(Clone, Copy, Debug)]
pub(super) struct Obstacle {
    pub center: P,
    pub radius: f64,
}

impl Obstacle {
    pub(super) fn of(n: &Placed) -> Obstacle {
        Obstacle {
            center: n.center,
            // a circle's own radius; a box's circumscribed circle
            radius: if n.w == n.h {
                n.w / 2.0
            } else {
                (n.w * n.w + n.h * n.h).sqrt() / 2.0
            },
        }
    }
}

fn cubic(a: P, b: P, c: P, d: P, t: f64) -> P {
    let u = 1.0 - t;
    a.scale(u * u * u)
        .plus(b.scale(3.0 * u * u * t))
        .plus(c.scale(3.0 * u * t * t))
        .plus(d.scale(t * t * t))
}

/// The points of `path` (one `M` then `C`s or `L`s), about every 16 units.
fn sample(path: &[Cmd]) -> Vec<P> {
    let mut out = Vec::new();
    let mut at = P::new(0.0, 0.0);
    for c in path {
        match *c {
            Cmd::M(a) => {
                at = a;
                out.push(a);
            }
            Cmd::L(b) => {
                let n = (b.minus(at).len() / 16.0).ceil().clamp(1.0, 400.0) as usize;
                out.extend((1..=n).map(|k| at.plus(b.minus(at).scale(k as f64 / n as f64))));
                at = b;
            }
            Cmd::C(c1, c2, b) => {
                let rough = c1.minus(at).len() + c2.minus(c1).len() + b.minus(c2).len();
                let n = (rough / 16.0).ceil().clamp(2.0, 400.0) as usize;
                out.extend((1..=n).map(|k| cubic(at, c1, c2, b, k as f64 / n as f64)));
                at = b;
            }
            Cmd::S(_, b) => {
                out.push(b);
                at = b;
            }
        }
    }
    out
}

fn inside(q: P, o: &Obstacle) -> bool {
    q.minus(o.center).len() < o.radius + MARGIN - 0.5
}

/// The distance from `c` to the segment `a`–`b`, and the closest point.
fn to_segment(a: P, b: P, c: P) -> (f64, P) {
    let ab = b.minus(a);
    let len2 = ab.x * ab.x + ab.y * ab.y;
    let t = if len2 < 1e-12 {
        0.0
    } else {
        (((c.x - a.x) * ab.x + (c.y - a.y) * ab.y) / len2).clamp(0.0, 1.0)
    };
    let q = a.plus(ab.scale(t));
    (q.minus(c).len(), q)
}

/// Waypoints from `s` to `t` that pass every obstacle at a distance: where
/// a leg passes through one, a waypoint beside it (on the side the leg
/// passes) is put in, the leg nearest its start first, a bounded number of
/// times.
fn waypoints(s: P, t: P, near: &[Obstacle]) -> Vec<P> {
    let mut pts = vec![s, t];
    for _ in 0..24 {
        let mut insert = None;
        'legs: for i in 0..pts.len() - 1 {
            let (a, b) = (pts[i], pts[i + 1]);
            // the obstacle the leg meets first
            let mut best: Option<(f64, P, &Obstacle)> = None;
            for o in near {
                // an end inside it: not its way round
                if inside(a, o) || inside(b, o) {
                    continue;
                }
                let (d, q) = to_segment(a, b, o.center);
                if d < o.radius + MARGIN {
                    let along = q.minus(a).len();
                    if best.is_none_or(|(x, _, _)| along < x) {
                        best = Some((along, q, o));
                    }
                }
            }
            if let Some((_, q, o)) = best {
                let side = q.minus(o.center);
                let dir = if side.len() > 1e-6 {
                    side.scale(1.0 / side.len())
                } else {
                    let ab = b.minus(a);
                    let l = ab.len().max(1e-6);
                    P::new(-ab.y / l, ab.x / l)
                };
                // beside it, and further out while that is inside another
                let mut w = o.center.plus(dir.scale(o.radius + MARGIN + 4.0));
                for _ in 0..40 {
                    if !near.iter().any(|x| inside(w, x)) {
                        break;
                    }
                    w = w.plus(dir.scale(12.0));
                }
                insert = Some((i + 1, w));
                break 'legs;
            }
        }
        match insert {
            Some((i, w)) => pts.insert(i, w),
            None => break,
        }
    }
    pts
}

/// `path` routed round `obstacles` (the link's own ends left out by the
/// caller): when it passes through one, a smooth curve from its start to
/// its end through waypoints beside them; `None` when it passes none.
pub(super) fn around(path: &[Cmd], obstacles: &[Obstacle]) -> Option<(Vec<Cmd>, P)> {
    let pts = sample(path);
    if pts.len() < 2 {
        return None;
    }
    let (s, t) = (pts[0], pts[pts.len() - 1]);
    // only the nodes near the curve matter
    let (mut lo, mut hi) = (pts[0], pts[0]);
    for q in &pts {
        lo = P::new(lo.x.min(q.x), lo.y.min(q.y));
        hi = P::new(hi.x.max(q.x), hi.y.max(q.y));
    }
    let reach = 400.0;
    let near: Vec<Obstacle> = obstacles
        .iter()
        .filter(|o| {
            o.center.x + o.radius > lo.x - reach
                && o.center.x - o.radius < hi.x + reach
                && o.center.y + o.radius > lo.y - reach
                && o.center.y - o.radius < hi.y + reach
        })
        .copied()
        .collect();
    let crosses = |pts: &[P]| {
        pts.iter().any(|q| {
            near.iter()
                .any(|o| inside(*q, o) && !inside(s, o) && !inside(t, o))
        })
    };
    if !crosses(&pts) {
        return None;
    }
    let way = waypoints(s, t, &near);
    let mut routed = through(&way);
    // a smooth curve may swing into a node a straight leg passes: then
    // straight legs
    if crosses(&sample(&routed)) {
        routed = std::iter::once(Cmd::M(way[0]))
            .chain(way[1..].iter().map(|&q| Cmd::L(q)))
            .collect();
    }
    // the label half way along the route
    let along = sample(&routed);
    let mid = along[along.len() / 2];
    Some((routed, mid))
}

/// A smooth curve through `pts` (Catmull-Rom as cubic Béziers).
fn through(pts: &[P]) -> Vec<Cmd> {
    let mut cmds = vec![Cmd::M(pts[0])];
    let n = pts.len();
    for i in 0..n - 1 {
        let p0 = pts[i.saturating_sub(1)];
        let (p1, p2) = (pts[i], pts[i + 1]);
        let p3 = pts[(i + 2).min(n - 1)];
        let c1 = p1.plus(p2.minus(p0).scale(1.0 / 6.0));
        let c2 = p2.minus(p3.minus(p1).scale(1.0 / 6.0));
        cmds.push(Cmd::C(c1, c2, p2));
    }
    cmds
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_through_a_circle_goes_round_it() {
        let path = [Cmd::M(P::new(0.0, 0.0)), Cmd::L(P::new(400.0, 0.0))];
        let o = Obstacle {
            center: P::new(200.0, 5.0),
            radius: 40.0,
        };
        let (routed, _) = around(&path, &[o]).expect("rerouted");
        for q in sample(&routed) {
            assert!(q.minus(o.center).len() > o.radius, "{q:?}");
        }
        // ends kept
        assert!(matches!(routed[0], Cmd::M(a) if a == P::new(0.0, 0.0)));
        let far = Obstacle {
            center: P::new(200.0, 300.0),
            radius: 40.0,
        };
        assert!(around(&path, &[far]).is_none());
    }
}
