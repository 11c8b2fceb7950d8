//! The objects of each shelf put on its board: those with a `spot` there,
//! the others side by side across the board in file order. Invariant: after
//! it, without an error, no object hangs over its board's edge and no two
//! objects of a shelf overlap.

use nalgebra::Vector2;

use super::error::Cx;
use super::model::{ObjectSpec, ShelfSpec};

/// Puts the objects of each shelf on its board: those with a `spot` there,
/// the others side by side across the board's width in file order (first =
/// leftmost as the robot sees it), evenly spaced, on the board's middle line.
/// Errors when they do not fit or overlap.
pub(super) fn layout(
    cx: &mut Cx<'_>,
    shelves: &[ShelfSpec],
    objects: &mut [ObjectSpec],
    explicit: &[bool],
    at: &[usize],
) {
    // The objects of each shelf, in file order: one pass over the objects
    // (a scan of every object per shelf made 100 000 shelves take minutes).
    let mut by_shelf: Vec<Vec<usize>> = vec![Vec::new(); shelves.len()];
    for (o, object) in objects.iter().enumerate() {
        if let Some(list) = by_shelf.get_mut(object.shelf) {
            list.push(o);
        }
    }
    for (s, shelf) in shelves.iter().enumerate() {
        let (w, d) = (shelf.size.x, shelf.size.y);
        let on = std::mem::take(&mut by_shelf[s]);
        let auto: Vec<usize> = on.iter().copied().filter(|&o| !explicit[o]).collect();
        let total: f64 = auto.iter().map(|&o| objects[o].size.x).sum();
        if total > w + 1e-9 {
            let last = *auto.last().unwrap_or(&0);
            cx.err(
                at[last],
                format!(
                    "the objects on shelf `{}` do not fit side by side: together {} m wide, its board is {} m",
                    shelf.name,
                    round3(total),
                    round3(w)
                ),
            );
            continue;
        }
        let gap = if auto.is_empty() {
            0.0
        } else {
            (w - total) / auto.len() as f64
        };
        let mut cursor = -w / 2.0 + gap / 2.0;
        for &o in &auto {
            let ow = objects[o].size.x;
            objects[o].spot = Vector2::new(cursor + ow / 2.0, 0.0);
            cursor += ow + gap;
        }
        for &o in &on {
            let ob = &objects[o];
            if explicit[o]
                && (ob.spot.x.abs() + ob.size.x / 2.0 > w / 2.0 + 1e-9
                    || ob.spot.y.abs() + ob.size.y / 2.0 > d / 2.0 + 1e-9)
            {
                cx.err(
                    at[o],
                    format!(
                        "object `{}` at spot [{}, {}] does not lie on the {} × {} m board of shelf `{}`",
                        ob.name,
                        ob.spot.x,
                        ob.spot.y,
                        round3(w),
                        round3(d),
                        shelf.name
                    ),
                );
            }
        }
        for (i, &a) in on.iter().enumerate() {
            for &b in &on[i + 1..] {
                let (oa, ob) = (&objects[a], &objects[b]);
                let dx = (oa.spot.x - ob.spot.x).abs();
                let dy = (oa.spot.y - ob.spot.y).abs();
                if dx < (oa.size.x + ob.size.x) / 2.0 - 1e-9
                    && dy < (oa.size.y + ob.size.y) / 2.0 - 1e-9
                {
                    cx.err(
                        at[b],
                        format!(
                            "object `{}` overlaps object `{}` on shelf `{}`",
                            ob.name, oa.name, shelf.name
                        ),
                    );
                }
            }
        }
    }
}

fn round3(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}
