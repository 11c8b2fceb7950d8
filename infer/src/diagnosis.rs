//! Diagnosis (§8.1): how did the shelves come to be as the robot saw them?
//!
//! The paper's assumptions: a human assistant filled every shelf in one
//! round, moving from shelf to shelf and placing objects; an object not on
//! the shelf where the robot believed it was misplaced by the assistant on
//! a shelf the robot has not seen yet. The diagnosis extends the believed
//! content of the unseen shelves with the missing objects: the first one
//! (the object sought) goes to the unseen shelf closest to the current one,
//! the others to unseen shelves chosen by the seed. With no unseen shelf
//! left, a missing object is nowhere: the shop ran out of it. The answer
//! is the state of every shelf, known (observed) or assumed, and the
//! assistant's assumed actions (`move(Shelf)`, `place(Object)`).

use crate::{Distances, Error};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeSet;

/// What the diagnosis is given.
#[derive(Clone, Debug, Default)]
pub struct Input {
    /// Every shelf of the shop (names in the distance table).
    pub shelves: Vec<String>,
    /// The shelf just observed (or the place where the robot is: any
    /// place of the distance table).
    pub current: String,
    /// Shelves observed so far in this cycle, with what was on them
    /// (Previous_Shelves, the current one included), oldest first.
    pub observed: Vec<(String, Vec<String>)>,
    /// What the KB believes each shelf holds.
    pub believed: Vec<(String, Vec<String>)>,
    /// Objects not where they were believed to be, whose place is unknown
    /// (Missing), the object sought first.
    pub missing: Vec<String>,
    pub seed: u64,
}

/// The state of one shelf in a diagnosis.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShelfState {
    pub shelf: String,
    pub objects: Vec<String>,
    /// Observed (`true`) or assumed (`false`).
    pub known: bool,
}

/// An action the assistant is assumed to have made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AssistantAction {
    Move(String),
    Place(String),
}

/// The diagnosis.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnosis {
    /// Every shelf: the observed ones in the order seen, then the unseen
    /// ones from the closest to the current shelf.
    pub states: Vec<ShelfState>,
    /// Where each missing object is assumed to be, in the order given.
    pub placed: Vec<(String, String)>,
    /// Missing objects with no unseen shelf left: the shop ran out.
    pub ran_out: Vec<String>,
    /// The assistant's round: `move` to each shelf, `place` its objects.
    pub actions: Vec<AssistantAction>,
}

impl Diagnosis {
    /// Where `object` is, known or assumed.
    pub fn shelf_of(&self, object: &str) -> Option<&str> {
        self.states
            .iter()
            .find(|s| s.objects.iter().any(|o| o == object))
            .map(|s| s.shelf.as_str())
    }
}

/// Runs the diagnosis.
pub fn diagnose(input: &Input, distances: &Distances) -> Result<Diagnosis, Error> {
    let shelves: BTreeSet<&str> = input.shelves.iter().map(String::as_str).collect();
    let known_shelf = |s: &str| -> Result<(), Error> {
        if shelves.contains(s) {
            Ok(())
        } else {
            Err(Error(format!("`{s}` is not a shelf of the shop")))
        }
    };
    distances.index(&input.current)?;
    for (s, _) in input.observed.iter().chain(&input.believed) {
        known_shelf(s)?;
    }
    for s in &input.shelves {
        distances.get(&input.current, s)?;
    }
    // The latest observation of a shelf is what it holds.
    let mut observed: Vec<(String, Vec<String>)> = Vec::new();
    for (s, objects) in &input.observed {
        observed.retain(|(t, _)| t != s);
        observed.push((s.clone(), objects.clone()));
    }
    let seen_objects: BTreeSet<&str> = observed
        .iter()
        .flat_map(|(_, os)| os.iter().map(String::as_str))
        .collect();
    let missing: Vec<&str> = {
        let mut v: Vec<&str> = Vec::new();
        for m in &input.missing {
            if !v.contains(&m.as_str()) && !seen_objects.contains(m.as_str()) {
                v.push(m);
            }
        }
        v
    };
    // Unseen shelves, closest to the current shelf first (ties by name).
    let mut unseen: Vec<(f64, &str)> = input
        .shelves
        .iter()
        .filter(|s| !observed.iter().any(|(t, _)| t == *s))
        .map(|s| Ok((distances.get(&input.current, s)?, s.as_str())))
        .collect::<Result<_, Error>>()?;
    unseen.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(b.1)));
    unseen.dedup_by(|a, b| a.1 == b.1);
    // Assumed states: believed content, less what is known to be elsewhere
    // and what is missing.
    let mut assumed: Vec<(String, Vec<String>)> = unseen
        .iter()
        .map(|&(_, s)| {
            let objects = input
                .believed
                .iter()
                .filter(|(t, _)| t == s)
                .flat_map(|(_, os)| os.iter())
                .filter(|o| !seen_objects.contains(o.as_str()) && !missing.contains(&o.as_str()))
                .cloned()
                .collect();
            (s.to_owned(), objects)
        })
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(input.seed);
    let mut placed = Vec::new();
    let mut ran_out = Vec::new();
    for (k, &m) in missing.iter().enumerate() {
        if assumed.is_empty() {
            ran_out.push(m.to_owned());
            continue;
        }
        let i = if k == 0 {
            0
        } else {
            rng.random_range(0..assumed.len())
        };
        assumed[i].1.push(m.to_owned());
        placed.push((m.to_owned(), assumed[i].0.clone()));
    }
    let mut states: Vec<ShelfState> = observed
        .into_iter()
        .map(|(shelf, objects)| ShelfState {
            shelf,
            objects,
            known: true,
        })
        .collect();
    states.extend(assumed.into_iter().map(|(shelf, objects)| ShelfState {
        shelf,
        objects,
        known: false,
    }));
    let mut actions = Vec::new();
    for s in &states {
        actions.push(AssistantAction::Move(s.shelf.clone()));
        actions.extend(s.objects.iter().cloned().map(AssistantAction::Place));
    }
    Ok(Diagnosis {
        states,
        placed,
        ran_out,
        actions,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shop() -> Distances {
        // drinks -- 5 -- food -- 4 -- bread; drinks -- 8 -- bread
        let mut d = Distances::new();
        d.set("shelf_drinks", "shelf_food", 5.0);
        d.set("shelf_food", "shelf_bread", 4.0);
        d.set("shelf_drinks", "shelf_bread", 8.0);
        d
    }

    fn s(v: &[&str]) -> Vec<String> {
        v.iter().map(|x| x.to_string()).collect()
    }

    fn input() -> Input {
        Input {
            shelves: s(&["shelf_drinks", "shelf_food", "shelf_bread"]),
            current: "shelf_drinks".into(),
            observed: vec![("shelf_drinks".into(), s(&["malz"]))],
            believed: vec![
                ("shelf_drinks".into(), s(&["heineken", "malz"])),
                ("shelf_food".into(), s(&["noodles"])),
                ("shelf_bread".into(), s(&["bagel"])),
            ],
            missing: s(&["heineken"]),
            seed: 1,
        }
    }

    #[test]
    fn the_sought_object_goes_to_the_closest_unseen_shelf() {
        let d = diagnose(&input(), &shop()).unwrap();
        assert_eq!(
            d.placed,
            vec![("heineken".to_owned(), "shelf_food".to_owned())]
        );
        assert_eq!(d.shelf_of("heineken"), Some("shelf_food"));
        assert!(d.ran_out.is_empty());
        assert!(d.states[0].known);
        assert_eq!(d.states[1].objects, s(&["noodles", "heineken"]));
        assert_eq!(
            d.actions[..3],
            [
                AssistantAction::Move("shelf_drinks".into()),
                AssistantAction::Place("malz".into()),
                AssistantAction::Move("shelf_food".into()),
            ]
        );
    }

    #[test]
    fn with_every_shelf_seen_the_shop_ran_out() {
        let mut i = input();
        i.current = "shelf_food".into();
        i.observed.push(("shelf_food".into(), s(&["noodles"])));
        i.observed.push(("shelf_bread".into(), s(&["bagel"])));
        let d = diagnose(&i, &shop()).unwrap();
        assert_eq!(d.ran_out, s(&["heineken"]));
        assert!(d.placed.is_empty());
        assert!(d.states.iter().all(|s| s.known));
    }

    #[test]
    fn nothing_missing_means_the_beliefs_stand() {
        let mut i = input();
        i.missing.clear();
        let d = diagnose(&i, &shop()).unwrap();
        assert!(d.placed.is_empty() && d.ran_out.is_empty());
        assert_eq!(d.shelf_of("bagel"), Some("shelf_bread"));
    }

    #[test]
    fn other_missing_objects_are_spread_by_the_seed_deterministically() {
        let mut i = input();
        i.missing = s(&["heineken", "coke", "water", "juice"]);
        let a = diagnose(&i, &shop()).unwrap();
        let b = diagnose(&i, &shop()).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.placed[0].1, "shelf_food");
        assert!(a.placed.iter().all(|(_, s)| s != "shelf_drinks"));
    }

    #[test]
    fn an_object_seen_elsewhere_is_not_assumed_missing() {
        let mut i = input();
        i.observed
            .push(("shelf_bread".into(), s(&["heineken", "bagel"])));
        let d = diagnose(&i, &shop()).unwrap();
        assert!(d.placed.is_empty());
        assert_eq!(d.shelf_of("heineken"), Some("shelf_bread"));
    }

    #[test]
    fn unknown_shelves_are_errors_naming_them() {
        let mut i = input();
        i.current = "shelf_toys".into();
        assert_eq!(
            diagnose(&i, &shop()).unwrap_err().0,
            "`shelf_toys` is not a place of the map"
        );
    }
}
