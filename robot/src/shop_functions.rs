//! The daily-life inference cycle (`sitlog-infer`) as SitLog user
//! functions, with distances from the simulated robot's map. Terms in,
//! terms out; the inference itself knows nothing of terms.
//!
//! - `shop_shelves` → the shelves of the world, in file order;
//!   `shop_shelf_here` → the shelf in front of the robot, or `none`;
//!   `shop_place_here` → the robot's place.
//! - `shop_diagnose(Current, Observed, Believed, Missing)` → `diagnosis(Placed,
//!   RanOut, Actions)`: Observed and Believed are `[Shelf-[Object, ...], ...]`
//!   (Previous_Shelves and the KB's beliefs), Missing `[Object, ...]` (the
//!   object sought first); Placed `[Object-Shelf, ...]`, RanOut
//!   `[Object, ...]`, Actions the assistant's `move(Shelf)`/`place(Object)`.
//! - `shop_decide(Obligations, UserAt, RMax, Costs)` → `decision(Chosen, Left,
//!   Plan, Cost, Budget)`: Obligations `[fetch(Object, From) | put(Object,
//!   From, To), ...]` (the task obligation first; From `hand` when the robot
//!   holds it), Costs `costs(Take, Deliver, SearchUser, PMove, PTake,
//!   PDeliver, PSearch)` or `default`; Plan the behaviours `take(Object,
//!   Shelf)`, `place(Object, Shelf)`, `deliver(Object)`; Cost in seconds
//!   (one decimal); Budget `within` or `over` (the task obligation alone
//!   costs more than RMax).
//!
//! The robot's own place and hands come from the simulator (what the robot
//! knows of itself, read through [`SimAccess`]); every other input from the
//! task. Nothing here knows the robot itself: the simulated robot
//! registers these functions over its world.

use sitlog_infer::decision::decide;
use sitlog_infer::diagnosis::{diagnose, AssistantAction, Input};
use sitlog_infer::plan::{Behaviour, Costs, Obligation, Problem, Target};
use sitlog_infer::Distances;
use sitlog_runtime::functions::FnCall;
use sitlog_runtime::{Functions, Store, Term, Value};
use sitlog_sim::{Hand, Sim};

/// The simulated world the functions read, under the robot's lock (the
/// simulated robot's own, or what another robot believes of itself over
/// the world's map: sitlog-ros).
pub trait SimAccess: Clone + Send + Sync + 'static {
    /// `f` on the simulator; `Err` when the world is unusable (after an
    /// earlier panic).
    fn with_sim<R>(&self, f: impl FnOnce(&Sim) -> R) -> Result<R, String>;
}

fn atom_name(store: &Store, t: Term, what: &str) -> Result<String, String> {
    store
        .atom_of(t)
        .map(|a| a.as_str().to_owned())
        .ok_or_else(|| format!("{what} must be an atom, not `{}`", store.writeq(t)))
}

fn list(store: &Store, t: Term, what: &str) -> Result<Vec<Term>, String> {
    store
        .list_to_vec(t)
        .ok_or_else(|| format!("{what} must be a list, not `{}`", store.writeq(t)))
}

fn names(store: &Store, t: Term, what: &str) -> Result<Vec<String>, String> {
    list(store, t, what)?
        .into_iter()
        .map(|x| atom_name(store, x, what))
        .collect()
}

/// `[Shelf-[Object, ...], ...]`.
fn shelf_pairs(store: &Store, t: Term, what: &str) -> Result<Vec<(String, Vec<String>)>, String> {
    let mut out = Vec::new();
    for p in list(store, t, what)? {
        match store.value(p) {
            Value::Compound(f, a) if f.as_str() == "-" && a.len() == 2 => {
                out.push((atom_name(store, a[0], what)?, names(store, a[1], what)?));
            }
            _ => {
                return Err(format!(
                    "{what}: `{}` is not Shelf-[Objects]",
                    store.writeq(p)
                ))
            }
        }
    }
    Ok(out)
}

fn number(store: &Store, t: Term, what: &str) -> Result<f64, String> {
    match store.value(t) {
        Value::Int(i) => Ok(i as f64),
        Value::Float(f) => Ok(f),
        _ => Err(format!(
            "{what} must be a number, not `{}`",
            store.writeq(t)
        )),
    }
}

fn quoted(name: &str) -> String {
    let mut s = String::new();
    sitlog_syntax::write::write_atom(&mut s, sitlog_runtime::Atom::intern(name), true);
    s
}

fn parse(call: &mut FnCall<'_>, text: &str) -> Result<Term, String> {
    Ok(call.store.parse(text).map_err(|e| e.message)?.0)
}

/// Distances between `names` (places or shelves) along the robot's map.
fn distances(sim: &Sim, names: &[&str]) -> Result<Distances, String> {
    let mut d = Distances::new();
    for (i, a) in names.iter().enumerate() {
        d.add_place(a);
        for b in &names[i + 1..] {
            let r = sim
                .route(a, b)
                .ok_or_else(|| format!("no route between `{a}` and `{b}` on the map"))?;
            d.set(a, b, r.length);
        }
    }
    Ok(d)
}

/// The functions [`register`] registers, by name and arity: what a checker
/// must know besides the application's own functions when a task runs on
/// a world (the checker does not depend on this crate; its callers pass
/// this list).
pub(crate) const FUNCTIONS: &[(&str, usize)] = &[
    ("shop_shelves", 0),
    ("shop_shelf_here", 0),
    ("shop_place_here", 0),
    ("shop_diagnose", 4),
    ("shop_decide", 4),
];

/// Registers the functions of the module documentation.
pub fn register(functions: &mut Functions, world: impl SimAccess, seed: u64) {
    let w = world.clone();
    functions.register("shop_shelves", 0, move |call, _| {
        let shelves: Vec<String> =
            w.with_sim(|sim| sim.world().shelf_names().into_iter().map(quoted).collect())?;
        parse(call, &format!("[{}]", shelves.join(",")))
    });

    let w = world.clone();
    functions.register("shop_shelf_here", 0, move |call, _| {
        let shelf = w.with_sim(|sim| sim.shelf_at(sim.robot_at()).unwrap_or("none").to_owned())?;
        parse(call, &quoted(&shelf))
    });

    let w = world.clone();
    functions.register("shop_place_here", 0, move |call, _| {
        let here = w.with_sim(|sim| sim.robot_at().to_owned())?;
        parse(call, &quoted(&here))
    });

    let w = world.clone();
    functions.register("shop_diagnose", 4, move |call, args| {
        let store = &*call.store;
        let current = atom_name(store, args[0], "the current shelf")?;
        let observed = shelf_pairs(store, args[1], "the shelves observed")?;
        let believed = shelf_pairs(store, args[2], "the shelves believed")?;
        let missing = names(store, args[3], "the missing objects")?;
        let (shelves, d) = w.with_sim(|sim| {
            let shelves: Vec<String> = sim
                .world()
                .shelf_names()
                .into_iter()
                .map(str::to_owned)
                .collect();
            let mut refs: Vec<&str> = shelves.iter().map(String::as_str).collect();
            if !refs.contains(&current.as_str()) {
                refs.push(&current);
            }
            let d = distances(sim, &refs)?;
            Ok::<_, String>((shelves, d))
        })??;
        let input = Input {
            shelves,
            current,
            observed,
            believed,
            missing,
            seed,
        };
        let dg = diagnose(&input, &d).map_err(|e| format!("shop_diagnose: {e}"))?;
        let placed: Vec<String> = dg
            .placed
            .iter()
            .map(|(o, s)| format!("{}-{}", quoted(o), quoted(s)))
            .collect();
        let ran_out: Vec<String> = dg.ran_out.iter().map(|o| quoted(o)).collect();
        let actions: Vec<String> = dg
            .actions
            .iter()
            .map(|a| match a {
                AssistantAction::Move(s) => format!("move({})", quoted(s)),
                AssistantAction::Place(o) => format!("place({})", quoted(o)),
            })
            .collect();
        let text = format!(
            "diagnosis([{}],[{}],[{}])",
            placed.join(","),
            ran_out.join(","),
            actions.join(",")
        );
        parse(call, &text)
    });

    let w = world;
    functions.register("shop_decide", 4, move |call, args| {
        let store = &*call.store;
        let mut obligations = Vec::new();
        for o in list(store, args[0], "the obligations")? {
            let bad = || {
                format!(
                    "`{}` is not fetch(Object, From) or put(Object, From, To)",
                    store.writeq(o)
                )
            };
            let Value::Compound(f, a) = store.value(o) else {
                return Err(bad());
            };
            let from = |t: Term| -> Result<Option<String>, String> {
                let s = atom_name(store, t, "where an object is")?;
                Ok((s != "hand").then_some(s))
            };
            obligations.push(match (f.as_str(), a.len()) {
                ("fetch", 2) => Obligation {
                    object: atom_name(store, a[0], "an object")?,
                    from: from(a[1])?,
                    to: Target::User,
                },
                ("put", 3) => Obligation {
                    object: atom_name(store, a[0], "an object")?,
                    from: from(a[1])?,
                    to: Target::Shelf(atom_name(store, a[2], "a shelf")?),
                },
                _ => return Err(bad()),
            });
        }
        let user_at = atom_name(store, args[1], "where the customer is")?;
        let r_max = number(store, args[2], "r_max")?;
        let costs = match store.value(args[3]) {
            Value::Atom(a) if a.as_str() == "default" => Costs::default(),
            Value::Compound(f, a) if f.as_str() == "costs" && a.len() == 7 => {
                let n = |k: usize| number(store, a[k], "a cost");
                Costs {
                    take: n(0)?,
                    deliver: n(1)?,
                    search_user: n(2)?,
                    p_move: n(3)?,
                    p_take: n(4)?,
                    p_deliver: n(5)?,
                    p_search_user: n(6)?,
                    ..Costs::default()
                }
            }
            _ => {
                return Err(format!(
                    "the costs must be `default` or costs(Take, Deliver, SearchUser, PMove, PTake, PDeliver, PSearch), not `{}`",
                    store.writeq(args[3])
                ))
            }
        };
        let (problem, d) = w.with_sim(|sim| {
            let at = sim.robot_at().to_owned();
            let mut names: Vec<&str> = vec![at.as_str(), user_at.as_str()];
            for o in &obligations {
                if let Some(f) = &o.from {
                    names.push(f);
                }
                if let Target::Shelf(s) = &o.to {
                    names.push(s);
                }
            }
            names.sort_unstable();
            names.dedup();
            let d = distances(sim, &names)?;
            let problem = Problem {
                at: at.clone(),
                left: sim.holding(Hand::Left).map(str::to_owned),
                right: sim.holding(Hand::Right).map(str::to_owned),
                user_at: user_at.clone(),
                obligations,
                costs: Costs {
                    speed: sim.world().robot_speed(),
                    ..costs
                },
            };
            Ok::<_, String>((problem, d))
        })??;
        let dec = decide(&problem, r_max, &d).map_err(|e| format!("shop_decide: {e}"))?;
        let ob = |o: &Obligation| match (&o.to, &o.from) {
            (Target::User, f) => format!(
                "fetch({},{})",
                quoted(&o.object),
                quoted(f.as_deref().unwrap_or("hand"))
            ),
            (Target::Shelf(s), f) => format!(
                "put({},{},{})",
                quoted(&o.object),
                quoted(f.as_deref().unwrap_or("hand")),
                quoted(s)
            ),
        };
        let chosen: Vec<String> = dec.chosen.iter().map(ob).collect();
        let left: Vec<String> = dec.left.iter().map(ob).collect();
        let plan: Vec<String> = dec
            .plan
            .behaviours
            .iter()
            .map(|b| match b {
                Behaviour::Take { object, shelf } => {
                    format!("take({},{})", quoted(object), quoted(shelf))
                }
                Behaviour::Place { object, shelf } => {
                    format!("place({},{})", quoted(object), quoted(shelf))
                }
                Behaviour::Deliver { object } => format!("deliver({})", quoted(object)),
            })
            .collect();
        let text = format!(
            "decision([{}],[{}],[{}],{:.1},{})",
            chosen.join(","),
            left.join(","),
            plan.join(","),
            dec.plan.cost,
            if dec.over_budget { "over" } else { "within" }
        );
        parse(call, &text)
    });
}
