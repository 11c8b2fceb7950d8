//! `sitlog-infer`: the daily-life inference cycle of the 2021 SitLog paper
//! (§7–§8, `000_80af30d55af63779.txt`): when what a service robot sees is
//! not what it believed, it *diagnoses* how the world came to be so,
//! *decides* what to do about it, and *plans* how to do it.
//!
//! This crate owns the three inferences and nothing else: it knows nothing
//! of SitLog, terms, the KB or the simulator. Places, shelves and objects
//! are names; distances come from a [`Distances`] table the caller fills
//! (the robot's map). Invariants:
//! - every function is deterministic: the same input (and seed) gives the
//!   same answer, bit for bit (ordered containers, one seeded ChaCha8);
//! - no input makes it panic or run without end: bad input (an unknown
//!   shelf, an object to take that is nowhere) is an [`Error`] naming it;
//! - [`plan::plan`] returns a plan of minimal cost (ties: the likelier,
//!   then the first in a fixed order of steps): the same plan as
//!   [`plan::exhaustive`], which tries every order of the basic actions,
//!   on every problem small enough for that.
//!
//! Modules: [`diagnosis`] (§8.1), [`decision`] (§8.2), [`plan`] (§8.3).
//! Each uses only [`Distances`] and [`Error`] (defined here), and
//! [`decision`] also [`plan`] (a set of obligations costs what its best plan
//! costs); nothing else uses another module.

pub mod decision;
pub mod diagnosis;
pub mod plan;

use std::collections::BTreeMap;
use std::fmt;

/// A problem with the input, naming the offending value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error(pub String);

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Error {}

/// Route lengths between named places (metres), symmetric; a place's
/// distance to itself is 0. Names not in the table are an [`Error`].
#[derive(Clone, Debug, Default)]
pub struct Distances {
    index: BTreeMap<String, usize>,
    names: Vec<String>,
    d: Vec<Vec<f64>>,
}

impl Distances {
    pub fn new() -> Distances {
        Distances::default()
    }

    /// Adds a place (no-op if known); its distances start unknown.
    pub fn add_place(&mut self, name: &str) -> usize {
        if let Some(&i) = self.index.get(name) {
            return i;
        }
        let i = self.names.len();
        self.index.insert(name.to_owned(), i);
        self.names.push(name.to_owned());
        for row in &mut self.d {
            row.push(f64::INFINITY);
        }
        let mut row = vec![f64::INFINITY; i + 1];
        row[i] = 0.0;
        self.d.push(row);
        i
    }

    /// Sets the distance between two places (both ways), adding them.
    pub fn set(&mut self, a: &str, b: &str, metres: f64) {
        let (i, j) = (self.add_place(a), self.add_place(b));
        if i != j {
            self.d[i][j] = metres;
            self.d[j][i] = metres;
        }
    }

    pub fn places(&self) -> &[String] {
        &self.names
    }

    pub fn index(&self, name: &str) -> Result<usize, Error> {
        self.index
            .get(name)
            .copied()
            .ok_or_else(|| Error(format!("`{name}` is not a place of the map")))
    }

    /// The distance between two known places, `Err` when unknown or
    /// unreachable.
    pub fn get(&self, a: &str, b: &str) -> Result<f64, Error> {
        let d = self.d[self.index(a)?][self.index(b)?];
        if d.is_finite() {
            Ok(d)
        } else {
            Err(Error(format!("no route between `{a}` and `{b}`")))
        }
    }

    fn by_index(&self, i: usize, j: usize) -> f64 {
        self.d[i][j]
    }
}
