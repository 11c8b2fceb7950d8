//! The planning problems of the crossover example and of the criterion
//! bench `benches/benches/plan.rs` (which includes this file by path).

use sitlog_infer::plan::{Costs, Obligation, Problem, Target};
use sitlog_infer::Distances;

const SHELVES: [(&str, f64, f64); 6] = [
    ("entrance", 0.0, 0.0),
    ("shelf_drinks", 6.0, 0.0),
    ("shelf_food", 6.0, 5.0),
    ("shelf_bread", 0.0, 5.0),
    ("shelf_snacks", 3.0, 8.0),
    ("shelf_fruit", 9.0, 8.0),
];

pub fn shop() -> Distances {
    let mut d = Distances::new();
    for (a, ax, ay) in SHELVES {
        for (b, bx, by) in SHELVES {
            d.set(a, b, ((ax - bx) * (ax - bx) + (ay - by) * (ay - by)).sqrt());
        }
    }
    d
}

/// A problem of `n` basic actions (4 per object to fetch, 2 per object in
/// a hand): the customer's object first, then misplaced ones.
pub fn problem(n: usize) -> Problem {
    let fetch = n / 4;
    let held = (n % 4) / 2;
    let mut obligations = Vec::new();
    for i in 0..fetch {
        let from = SHELVES[1 + (i * 2) % 5].0;
        obligations.push(Obligation {
            object: format!("o{i}"),
            from: Some(from.into()),
            to: if i == 0 {
                Target::User
            } else {
                Target::Shelf(SHELVES[1 + (i * 2 + 1) % 5].0.into())
            },
        });
    }
    let mut right = None;
    if held == 1 {
        obligations.push(Obligation {
            object: "h".into(),
            from: None,
            to: Target::Shelf("shelf_fruit".into()),
        });
        right = Some("h".into());
    }
    Problem {
        at: "shelf_drinks".into(),
        left: None,
        right,
        user_at: "entrance".into(),
        obligations,
        costs: Costs::default(),
    }
}
