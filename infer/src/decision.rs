//! Decision (§8.2): which pending obligations to carry out together with
//! the one that started the cycle.
//!
//! Potential decisions are the sets of obligations that hold the task
//! obligation TO (the first of the problem's obligations) and any of the
//! pending ones (the rest). Each set costs what its best plan costs
//! ([`crate::plan::plan`]); the decision is the set of maximal cost within
//! `r_max`, the time the customer can afford: as much tidying as fits.
//! Ties go to the set with more obligations, then to the first in the order
//! given. When even TO alone costs more than `r_max`, the decision is TO
//! alone (the customer comes first), marked `over_budget`.

use crate::plan::{plan, Obligation, Plan, Problem};
use crate::{Distances, Error};

/// At most this many pending obligations are weighed (2^n plans).
pub const MAX_PENDING: usize = 12;

/// The decision.
#[derive(Clone, Debug, PartialEq)]
pub struct Decision {
    /// The obligations chosen, TO first, the others in the order given.
    pub chosen: Vec<Obligation>,
    /// Pending obligations left for later.
    pub left: Vec<Obligation>,
    /// The plan of the chosen set.
    pub plan: Plan,
    /// Whether TO alone already costs more than `r_max`.
    pub over_budget: bool,
}

/// Decides (see the module documentation). `problem.obligations[0]` is TO.
pub fn decide(problem: &Problem, r_max: f64, distances: &Distances) -> Result<Decision, Error> {
    let Some(to) = problem.obligations.first() else {
        return Err(Error("no task obligation to decide about".into()));
    };
    if r_max.is_nan() {
        return Err(Error("r_max is not a number".into()));
    }
    let pending = &problem.obligations[1..];
    if pending.len() > MAX_PENDING {
        return Err(Error(format!(
            "{} pending obligations: at most {MAX_PENDING} are weighed",
            pending.len()
        )));
    }
    let mut best: Option<(u32, Plan)> = None;
    let mut alone: Option<Plan> = None;
    for mask in 0u32..(1 << pending.len()) {
        let mut obligations = vec![to.clone()];
        obligations.extend(
            pending
                .iter()
                .enumerate()
                .filter(|(i, _)| mask & (1 << i) != 0)
                .map(|(_, o)| o.clone()),
        );
        let sub = Problem {
            obligations,
            ..problem.clone()
        };
        let p = match plan(&sub, distances) {
            Ok(p) => p,
            // A set the hands cannot carry out is no decision; TO alone must be.
            Err(e) if mask != 0 && e.0.starts_with("no plan") => continue,
            Err(e) => return Err(e),
        };
        if mask == 0 {
            alone = Some(p.clone());
        }
        if p.cost > r_max {
            continue;
        }
        let better = match &best {
            None => true,
            Some((m, b)) => {
                p.cost > b.cost || (p.cost == b.cost && mask.count_ones() > m.count_ones())
            }
        };
        if better {
            best = Some((mask, p));
        }
    }
    let (mask, plan, over_budget) = match best {
        Some((m, p)) => (m, p, false),
        None => (0, alone.expect("TO alone was planned"), true),
    };
    let mut chosen = vec![to.clone()];
    let mut left = Vec::new();
    for (i, o) in pending.iter().enumerate() {
        if mask & (1 << i) != 0 {
            chosen.push(o.clone());
        } else {
            left.push(o.clone());
        }
    }
    Ok(Decision {
        chosen,
        left,
        plan,
        over_budget,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{Costs, Target};

    fn shop() -> Distances {
        let mut d = Distances::new();
        d.set("entrance", "shelf_drinks", 6.0);
        d.set("entrance", "shelf_food", 8.0);
        d.set("entrance", "shelf_bread", 5.0);
        d.set("shelf_drinks", "shelf_food", 5.0);
        d.set("shelf_drinks", "shelf_bread", 8.0);
        d.set("shelf_food", "shelf_bread", 6.0);
        d
    }

    fn problem() -> Problem {
        Problem {
            at: "shelf_drinks".into(),
            left: None,
            right: None,
            user_at: "entrance".into(),
            obligations: vec![
                Obligation {
                    object: "coke".into(),
                    from: Some("shelf_food".into()),
                    to: Target::User,
                },
                Obligation {
                    object: "noodles".into(),
                    from: Some("shelf_drinks".into()),
                    to: Target::Shelf("shelf_food".into()),
                },
                Obligation {
                    object: "bagel".into(),
                    from: Some("shelf_food".into()),
                    to: Target::Shelf("shelf_bread".into()),
                },
            ],
            costs: Costs::default(),
        }
    }

    #[test]
    fn enough_time_takes_every_pending_obligation() {
        let d = decide(&problem(), 1000.0, &shop()).unwrap();
        assert_eq!(d.chosen.len(), 3);
        assert!(d.left.is_empty() && !d.over_budget);
    }

    #[test]
    fn r_max_zero_serves_only_the_customer() {
        let d = decide(&problem(), 0.0, &shop()).unwrap();
        assert_eq!(d.chosen.len(), 1);
        assert_eq!(d.chosen[0].object, "coke");
        assert_eq!(d.left.len(), 2);
        assert!(d.over_budget);
    }

    #[test]
    fn the_most_that_fits_within_r_max() {
        let alone = decide(&problem(), 0.0, &shop()).unwrap().plan.cost;
        let all = decide(&problem(), 1000.0, &shop()).unwrap().plan.cost;
        let d = decide(&problem(), (alone + all) / 2.0, &shop()).unwrap();
        assert!(d.plan.cost <= (alone + all) / 2.0);
        assert!(d.chosen.len() == 2, "{d:?}");
    }

    #[test]
    fn no_task_obligation_is_an_error() {
        let mut p = problem();
        p.obligations.clear();
        assert!(decide(&p, 10.0, &shop()).is_err());
    }
}
