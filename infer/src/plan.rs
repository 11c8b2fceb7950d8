//! Planning (§8.3): the order of basic actions that carries out a set of
//! obligations at the least cost.
//!
//! Each obligation moves one object: to its right shelf
//! (`[move(From), take(O), move(To), deliver(O)]`) or to the customer
//! (`[move(From), take(O), search(user), deliver(O)]`); an object already in
//! a hand needs only the last two. All of them form the multiset B of basic
//! actions. The search goes depth first from the robot's state (place,
//! hands, obligations left, actions left, the plan so far) with the paper's
//! pruning rules:
//! 1. no two navigation steps (`move`, `search(user)`) in a row;
//! 2. (the paper's rule on useless observations: this planner has no
//!    separate `search(object)` step, `take` includes looking);
//! 3. `deliver(O)` only holding O (after `take(O)`), where O goes;
//! 4. `take` only with a free hand (the left one first), where O is.
//!
//! Children are tried cheapest first; a branch whose cost plus a lower
//! bound of what is left exceeds the best plan found is cut (branch and
//! bound), and a state reached before at no greater cost is not expanded
//! again. The plan found has minimal cost; ties go to the likelier plan,
//! then to the first in the order of [`Step`]. [`exhaustive`] is the
//! authors' method (every permutation of B, sorted by cost), for
//! comparison on small problems.
//!
//! Size: just over 800 lines, of which about 250 are its tests; the code
//! (about 560 lines) is one job, the search and the problem it searches,
//! and reads best whole.

use crate::{Distances, Error};
use std::collections::HashMap;

/// Where an obligation's object goes.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Target {
    /// Its right shelf (a task obligation: put it back).
    Shelf(String),
    /// The customer (a conversational obligation).
    User,
}

/// One object to move.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Obligation {
    pub object: String,
    /// The shelf where it is (known or assumed); `None` when a hand holds it.
    pub from: Option<String>,
    pub to: Target,
}

/// Time (seconds) and success probability of the basic actions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Costs {
    /// Metres per second when moving.
    pub speed: f64,
    pub take: f64,
    pub deliver: f64,
    /// Looking for the customer, on top of the way to them.
    pub search_user: f64,
    pub p_move: f64,
    pub p_take: f64,
    pub p_deliver: f64,
    pub p_search_user: f64,
}

impl Default for Costs {
    fn default() -> Self {
        Costs {
            speed: 0.5,
            take: 10.0,
            deliver: 5.0,
            search_user: 10.0,
            p_move: 0.95,
            p_take: 0.9,
            p_deliver: 0.99,
            p_search_user: 0.9,
        }
    }
}

/// A planning problem.
#[derive(Clone, Debug)]
pub struct Problem {
    /// Where the robot is (a place of the distance table).
    pub at: String,
    pub left: Option<String>,
    pub right: Option<String>,
    /// Where the customer is.
    pub user_at: String,
    pub obligations: Vec<Obligation>,
    pub costs: Costs,
}

/// A basic action of a plan.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Step {
    Move(String),
    SearchUser,
    Take(String),
    Deliver(String),
}

/// What the dispatcher runs: the plan in terms of behaviours.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Behaviour {
    /// Go to the shelf, look, take the object.
    Take { object: String, shelf: String },
    /// Take the held object to the shelf and put it there.
    Place { object: String, shelf: String },
    /// Find the customer and hand the object over.
    Deliver { object: String },
}

/// A plan: its steps, its cost (seconds) and its probability of success.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    pub steps: Vec<Step>,
    pub cost: f64,
    pub probability: f64,
    /// The steps as behaviours for the dispatcher.
    pub behaviours: Vec<Behaviour>,
}

/// At most this many basic actions (the search keeps them in a bit set).
pub const MAX_ACTIONS: usize = 64;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Move,
    Search,
    Take,
    Deliver,
}

#[derive(Clone, Copy, Debug)]
struct Action {
    kind: Kind,
    obligation: usize,
    /// The place moved to, taken at or delivered at.
    place: usize,
}

/// In a hand: an object of no obligation.
const OTHER: usize = usize::MAX;

/// The problem in indices.
struct Compiled<'a> {
    d: &'a Distances,
    costs: Costs,
    actions: Vec<Action>,
    objects: Vec<String>,
    at: usize,
    user: usize,
    hands: [Option<usize>; 2],
    steps: Vec<Step>,
}

fn compile<'a>(p: &Problem, d: &'a Distances) -> Result<Compiled<'a>, Error> {
    let at = d.index(&p.at)?;
    let user = d.index(&p.user_at)?;
    let c = p.costs;
    let ok = |x: f64| x.is_finite() && x >= 0.0;
    let prob = |x: f64| (0.0..=1.0).contains(&x);
    let valid = c.speed.is_finite()
        && c.speed > 0.0
        && ok(c.take)
        && ok(c.deliver)
        && ok(c.search_user)
        && [c.p_move, c.p_take, c.p_deliver, c.p_search_user]
            .into_iter()
            .all(prob);
    if !valid {
        return Err(Error(format!("bad costs: {c:?}")));
    }
    // A hand holding an object no obligation moves stays full.
    let mut hands = [
        p.left.as_ref().map(|_| OTHER),
        p.right.as_ref().map(|_| OTHER),
    ];
    let mut actions = Vec::new();
    let mut objects = Vec::new();
    let mut steps = Vec::new();
    for (i, o) in p.obligations.iter().enumerate() {
        if objects.contains(&o.object) {
            return Err(Error(format!("`{}` is in two obligations", o.object)));
        }
        objects.push(o.object.clone());
        let held = [&p.left, &p.right]
            .iter()
            .position(|h| h.as_deref() == Some(o.object.as_str()));
        match (&o.from, held) {
            (_, Some(h)) => hands[h] = Some(i),
            (Some(from), None) => {
                let place = d.index(from)?;
                actions.push(Action {
                    kind: Kind::Move,
                    obligation: i,
                    place,
                });
                steps.push(Step::Move(from.clone()));
                actions.push(Action {
                    kind: Kind::Take,
                    obligation: i,
                    place,
                });
                steps.push(Step::Take(o.object.clone()));
            }
            (None, None) => {
                return Err(Error(format!(
                    "`{}` is in no hand and on no shelf",
                    o.object
                )))
            }
        }
        match &o.to {
            Target::Shelf(s) => {
                let place = d.index(s)?;
                actions.push(Action {
                    kind: Kind::Move,
                    obligation: i,
                    place,
                });
                steps.push(Step::Move(s.clone()));
                actions.push(Action {
                    kind: Kind::Deliver,
                    obligation: i,
                    place,
                });
            }
            Target::User => {
                actions.push(Action {
                    kind: Kind::Search,
                    obligation: i,
                    place: user,
                });
                steps.push(Step::SearchUser);
                actions.push(Action {
                    kind: Kind::Deliver,
                    obligation: i,
                    place: user,
                });
            }
        }
        steps.push(Step::Deliver(o.object.clone()));
    }
    if actions.len() > MAX_ACTIONS {
        return Err(Error(format!(
            "{} basic actions: at most {MAX_ACTIONS} can be planned",
            actions.len()
        )));
    }
    // Every place used must be reachable from every other.
    let mut places: Vec<usize> = actions.iter().map(|a| a.place).collect();
    places.push(at);
    places.push(user);
    for &a in &places {
        for &b in &places {
            if !d.by_index(a, b).is_finite() {
                return Err(Error(format!(
                    "no route between `{}` and `{}`",
                    d.places()[a],
                    d.places()[b]
                )));
            }
        }
    }
    Ok(Compiled {
        d,
        costs: c,
        actions,
        objects,
        at,
        user,
        hands,
        steps,
    })
}

#[derive(Clone, Copy, PartialEq, Eq, Hash)]
struct State {
    at: usize,
    hands: [Option<usize>; 2],
    used: u64,
    done: u64,
    after_move: bool,
}

impl Compiled<'_> {
    /// The cost and probability of action `a` in state `s`, and the next
    /// state, if the rules allow it.
    fn apply(&self, s: &State, a: usize) -> Option<(f64, f64, State)> {
        if s.used & (1 << a) != 0 {
            return None;
        }
        let act = self.actions[a];
        let c = &self.costs;
        let mut n = *s;
        n.used |= 1 << a;
        n.after_move = false;
        let (cost, p) = match act.kind {
            Kind::Move | Kind::Search => {
                if s.after_move {
                    return None;
                }
                n.at = act.place;
                n.after_move = true;
                let way = self.d.by_index(s.at, act.place) / c.speed;
                if act.kind == Kind::Search {
                    (way + c.search_user, c.p_search_user)
                } else {
                    (way, c.p_move)
                }
            }
            Kind::Take => {
                if s.at != act.place {
                    return None;
                }
                let h = s.hands.iter().position(Option::is_none)?;
                n.hands[h] = Some(act.obligation);
                (c.take, c.p_take)
            }
            Kind::Deliver => {
                if s.at != act.place {
                    return None;
                }
                let h = s.hands.iter().position(|&x| x == Some(act.obligation))?;
                n.hands[h] = None;
                n.done |= 1 << act.obligation;
                (c.deliver, c.p_deliver)
            }
        };
        Some((cost, p, n))
    }

    fn start(&self) -> State {
        State {
            at: self.at,
            hands: self.hands,
            used: 0,
            done: 0,
            after_move: false,
        }
    }

    fn all_done(&self) -> u64 {
        if self.objects.len() >= 64 {
            u64::MAX
        } else {
            (1u64 << self.objects.len()) - 1
        }
    }

    /// Takes and deliveries still to make: a lower bound of the cost left.
    fn bound(&self, s: &State) -> f64 {
        let mut b = 0.0;
        for (i, a) in self.actions.iter().enumerate() {
            if s.used & (1 << i) == 0 && s.done & (1 << a.obligation) == 0 {
                match a.kind {
                    Kind::Take => b += self.costs.take,
                    Kind::Deliver => b += self.costs.deliver,
                    _ => {}
                }
            }
        }
        b
    }

    fn finish(&self, plan: &[usize], cost: f64, probability: f64) -> Plan {
        let steps: Vec<Step> = plan.iter().map(|&a| self.steps[a].clone()).collect();
        let mut behaviours = Vec::new();
        let mut at = self.at;
        for &a in plan {
            let act = self.actions[a];
            let object = self.objects[act.obligation].clone();
            match act.kind {
                Kind::Move | Kind::Search => at = act.place,
                Kind::Take => behaviours.push(Behaviour::Take {
                    object,
                    shelf: self.d.places()[at].clone(),
                }),
                Kind::Deliver if at == self.user && self.steps[a - 1] == Step::SearchUser => {
                    behaviours.push(Behaviour::Deliver { object })
                }
                Kind::Deliver => behaviours.push(Behaviour::Place {
                    object,
                    shelf: self.d.places()[at].clone(),
                }),
            }
        }
        Plan {
            steps,
            cost,
            probability,
            behaviours,
        }
    }
}

/// Whether plan `a` (cost, probability, steps) beats plan `b`.
fn better(a: (f64, f64, &[Step]), b: (f64, f64, &[Step])) -> bool {
    a.0.total_cmp(&b.0)
        .then(b.1.total_cmp(&a.1))
        .then_with(|| a.2.cmp(b.2))
        .is_lt()
}

/// The plan of least cost for `problem` (see the module documentation).
pub fn plan(problem: &Problem, distances: &Distances) -> Result<Plan, Error> {
    let c = compile(problem, distances)?;
    let goal = c.all_done();
    struct Frame {
        state: State,
        cost: f64,
        p: f64,
        /// Children not tried yet, the cheapest last.
        children: Vec<(f64, usize)>,
    }
    let children = |s: &State, cost: f64| -> Vec<(f64, usize)> {
        let mut v: Vec<(f64, usize)> = (0..c.actions.len())
            .filter_map(|a| c.apply(s, a).map(|(k, _, _)| (cost + k, a)))
            .collect();
        v.sort_by(|x, y| {
            y.0.total_cmp(&x.0)
                .then_with(|| c.steps[y.1].cmp(&c.steps[x.1]))
        });
        v
    };
    let mut best: Option<(f64, f64, Vec<usize>)> = None;
    let mut seen: HashMap<State, (f64, f64)> = HashMap::new();
    let s0 = c.start();
    if s0.done == goal {
        return Ok(c.finish(&[], 0.0, 1.0));
    }
    let mut path: Vec<usize> = Vec::new();
    let mut stack = vec![Frame {
        state: s0,
        cost: 0.0,
        p: 1.0,
        children: children(&s0, 0.0),
    }];
    while let Some(top) = stack.last_mut() {
        let Some((_, a)) = top.children.pop() else {
            stack.pop();
            path.pop();
            continue;
        };
        let (k, q, next) = c.apply(&top.state, a).expect("a child is allowed");
        let (cost, p) = (top.cost + k, top.p * q);
        if let Some((bc, bp, _)) = &best {
            if cost + c.bound(&next) > *bc || (cost == *bc && p < *bp) {
                continue;
            }
        }
        if let Some(&(sc, sp)) = seen.get(&next) {
            if sc < cost || (sc == cost && sp > p) {
                continue;
            }
        }
        seen.insert(next, (cost, p));
        path.push(a);
        if next.done == goal {
            let steps: Vec<Step> = path.iter().map(|&i| c.steps[i].clone()).collect();
            let replace = match &best {
                None => true,
                Some((bc, bp, bpath)) => {
                    let bsteps: Vec<Step> = bpath.iter().map(|&i| c.steps[i].clone()).collect();
                    better((cost, p, &steps), (*bc, *bp, &bsteps))
                }
            };
            if replace {
                best = Some((cost, p, path.clone()));
            }
            path.pop();
            continue;
        }
        let ch = children(&next, cost);
        stack.push(Frame {
            state: next,
            cost,
            p,
            children: ch,
        });
    }
    match best {
        Some((cost, p, path)) => Ok(c.finish(&path, cost, p)),
        None => Err(Error(
            "no plan carries out these obligations (hands full of other objects?)".into(),
        )),
    }
}

/// The authors' method: every permutation of the basic actions, each run
/// until the obligations are done (a permutation that breaks a rule of
/// the robot — taking with no free hand or away from the object,
/// delivering what it does not hold or elsewhere — is dropped), the
/// cheapest kept. `n!` permutations: for comparisons only (at most 12
/// actions).
pub fn exhaustive(problem: &Problem, distances: &Distances) -> Result<Plan, Error> {
    let c = compile(problem, distances)?;
    let n = c.actions.len();
    if n > 12 {
        return Err(Error(format!(
            "{n} basic actions: too many to try every order"
        )));
    }
    let goal = c.all_done();
    let s0 = c.start();
    if s0.done == goal {
        return Ok(c.finish(&[], 0.0, 1.0));
    }
    let mut best: Option<(f64, f64, Vec<Step>, Vec<usize>)> = None;
    let mut perm: Vec<usize> = (0..n).collect();
    let mut try_perm = |perm: &[usize]| {
        let mut s = s0;
        let (mut cost, mut p) = (0.0, 1.0);
        for (i, &a) in perm.iter().enumerate() {
            // Consecutive moves are allowed here: the rules of the search
            // are not the baseline's.
            let mut t = s;
            t.after_move = false;
            let Some((k, q, next)) = c.apply(&t, a) else {
                return;
            };
            cost += k;
            p *= q;
            s = next;
            if s.done == goal {
                let plan = &perm[..=i];
                let steps: Vec<Step> = plan.iter().map(|&x| c.steps[x].clone()).collect();
                let replace = match &best {
                    None => true,
                    Some((bc, bp, bs, _)) => better((cost, p, &steps), (*bc, *bp, bs)),
                };
                if replace {
                    best = Some((cost, p, steps, plan.to_vec()));
                }
                return;
            }
        }
    };
    // Heap's algorithm, iteratively.
    let mut counters = vec![0usize; n];
    try_perm(&perm);
    let mut i = 0;
    while i < n {
        if counters[i] < i {
            if i % 2 == 0 {
                perm.swap(0, i);
            } else {
                perm.swap(counters[i], i);
            }
            try_perm(&perm);
            counters[i] += 1;
            i = 0;
        } else {
            counters[i] = 0;
            i += 1;
        }
    }
    match best {
        Some((cost, p, _, plan)) => Ok(c.finish(&plan, cost, p)),
        None => Err(Error(
            "no plan carries out these obligations (hands full of other objects?)".into(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn shop() -> Distances {
        let mut d = Distances::new();
        let pts = [
            ("entrance", 0.0, 0.0),
            ("shelf_drinks", 6.0, 0.0),
            ("shelf_food", 6.0, 5.0),
            ("shelf_bread", 0.0, 5.0),
            ("shelf_snacks", 3.0, 8.0),
        ];
        for (a, ax, ay) in pts {
            for (b, bx, by) in pts {
                let dist: f64 = (ax - bx) * (ax - bx) + (ay - by) * (ay - by);
                d.set(a, b, dist.sqrt().round());
            }
        }
        d
    }

    fn to_shelf(o: &str, from: &str, to: &str) -> Obligation {
        Obligation {
            object: o.into(),
            from: Some(from.into()),
            to: Target::Shelf(to.into()),
        }
    }

    fn to_user(o: &str, from: &str) -> Obligation {
        Obligation {
            object: o.into(),
            from: Some(from.into()),
            to: Target::User,
        }
    }

    fn problem(obligations: Vec<Obligation>) -> Problem {
        Problem {
            at: "shelf_drinks".into(),
            left: None,
            right: None,
            user_at: "entrance".into(),
            obligations,
            costs: Costs::default(),
        }
    }

    #[test]
    fn one_fetch_goes_takes_searches_delivers() {
        let p = problem(vec![to_user("heineken", "shelf_food")]);
        let plan = plan(&p, &shop()).unwrap();
        assert_eq!(
            plan.steps,
            vec![
                Step::Move("shelf_food".into()),
                Step::Take("heineken".into()),
                Step::SearchUser,
                Step::Deliver("heineken".into()),
            ]
        );
        assert_eq!(
            plan.behaviours,
            vec![
                Behaviour::Take {
                    object: "heineken".into(),
                    shelf: "shelf_food".into()
                },
                Behaviour::Deliver {
                    object: "heineken".into()
                }
            ]
        );
        // 5 m + 8 m at 0.5 m/s, take 10, search 10, deliver 5.
        assert_eq!(plan.cost, 10.0 + 10.0 + 16.0 + 10.0 + 5.0);
    }

    #[test]
    fn a_misplaced_object_is_put_back_on_the_way() {
        // The noodles are on the drinks shelf, where the robot is; the
        // coke is on the food shelf, where the noodles go.
        let p = problem(vec![
            to_user("coke", "shelf_food"),
            to_shelf("noodles", "shelf_drinks", "shelf_food"),
        ]);
        let plan = plan(&p, &shop()).unwrap();
        assert_eq!(
            plan.behaviours,
            vec![
                Behaviour::Take {
                    object: "noodles".into(),
                    shelf: "shelf_drinks".into()
                },
                Behaviour::Take {
                    object: "coke".into(),
                    shelf: "shelf_food".into()
                },
                Behaviour::Place {
                    object: "noodles".into(),
                    shelf: "shelf_food".into()
                },
                Behaviour::Deliver {
                    object: "coke".into()
                },
            ]
        );
        let e = exhaustive(&p, &shop()).unwrap();
        assert_eq!(plan.cost, e.cost);
    }

    #[test]
    fn both_hands_full_deliver_first() {
        let p = problem(vec![
            to_user("coke", "shelf_food"),
            Obligation {
                object: "bagel".into(),
                from: None,
                to: Target::Shelf("shelf_bread".into()),
            },
            Obligation {
                object: "chips".into(),
                from: None,
                to: Target::Shelf("shelf_snacks".into()),
            },
        ])
        .with_hands(Some("bagel"), Some("chips"));
        let plan = plan(&p, &shop()).unwrap();
        let e = exhaustive(&p, &shop()).unwrap();
        assert_eq!(plan.cost, e.cost);
        assert_eq!(plan.behaviours.len(), 4);
        // A hand must be free before the coke is taken.
        assert!(matches!(plan.behaviours[0], Behaviour::Place { .. }));
    }

    #[test]
    fn objects_in_hand_need_no_take() {
        let mut p = problem(vec![to_user("malz", "shelf_drinks")]);
        p.obligations[0].from = None;
        p.right = Some("malz".into());
        let plan = plan(&p, &shop()).unwrap();
        assert_eq!(
            plan.steps,
            vec![Step::SearchUser, Step::Deliver("malz".into())]
        );
    }

    #[test]
    fn hands_full_of_other_objects_is_an_error() {
        let mut p = problem(vec![to_user("coke", "shelf_food")]);
        p.left = Some("x".into());
        p.right = Some("y".into());
        assert!(plan(&p, &shop()).unwrap_err().0.contains("no plan"));
    }

    #[test]
    fn a_route_blocked_mid_plan_gives_a_new_plan_from_where_the_robot_is() {
        let p = problem(vec![
            to_user("coke", "shelf_food"),
            to_shelf("bagel", "shelf_drinks", "shelf_bread"),
        ]);
        let before = plan(&p, &shop()).unwrap();
        // The robot took the bagel; then the way drinks-food closed: the
        // remaining obligations are planned again from its state, on the
        // map without that way (the detour through the entrance).
        let mut d = shop();
        d.set("shelf_drinks", "shelf_food", 6.0 + 8.0);
        let mut again = p.clone();
        again.obligations[1].from = None;
        again.left = Some("bagel".into());
        let after = plan(&again, &d).unwrap();
        assert!(after.cost > 0.0 && after.steps.len() < before.steps.len());
        assert_eq!(after.cost, exhaustive(&again, &d).unwrap().cost);
        assert!(after
            .behaviours
            .iter()
            .any(|b| matches!(b, Behaviour::Place { object, .. } if object == "bagel")));
    }

    #[test]
    fn nothing_to_do_is_the_empty_plan() {
        let plan = plan(&problem(vec![]), &shop()).unwrap();
        assert!(plan.steps.is_empty());
        assert_eq!(plan.cost, 0.0);
    }

    #[test]
    fn unknown_places_and_objects_are_named() {
        let p = problem(vec![to_user("coke", "shelf_toys")]);
        assert_eq!(
            plan(&p, &shop()).unwrap_err().0,
            "`shelf_toys` is not a place of the map"
        );
        let mut p = problem(vec![to_user("coke", "shelf_food")]);
        p.obligations[0].from = None;
        assert!(plan(&p, &shop()).unwrap_err().0.contains("`coke`"));
    }

    #[test]
    fn same_cost_as_every_permutation_on_small_problems() {
        let shelves = [
            "shelf_drinks",
            "shelf_food",
            "shelf_bread",
            "shelf_snacks",
            "entrance",
        ];
        let mut k = 0u32;
        for a in 0..4 {
            for b in 0..4 {
                for c in 0..5 {
                    k += 1;
                    // 8 basic actions: 40 320 orders for the baseline.
                    // Both hands full: a delivery must come first.
                    let p = problem(vec![
                        to_user("o1", shelves[a]),
                        Obligation {
                            object: "o2".into(),
                            from: None,
                            to: Target::Shelf(shelves[b].into()),
                        },
                        Obligation {
                            object: "o3".into(),
                            from: None,
                            to: Target::Shelf(shelves[c].into()),
                        },
                    ])
                    .with_hands(Some("o2"), Some("o3"));
                    let p = Problem {
                        user_at: shelves[(a + c) % 5].into(),
                        ..p
                    };
                    let x = plan(&p, &shop()).unwrap();
                    let y = exhaustive(&p, &shop()).unwrap();
                    assert!((x.cost - y.cost).abs() < 1e-9, "case {k}: {x:?} vs {y:?}");
                }
            }
        }
    }

    impl Problem {
        fn with_hands(mut self, left: Option<&str>, right: Option<&str>) -> Problem {
            self.left = left.map(str::to_owned);
            self.right = right.map(str::to_owned);
            self
        }
    }
}
