//! Behaviour of the simulated world: physics rest, the camera, routes and
//! time, hands, the user, determinism; and, in `world_errors`, bad world
//! files. One binary (a test binary costs a link: issue 30).

mod world_errors;

use sitlog_sim::*;

fn home() -> World {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/worlds/home.toml");
    World::load(std::path::Path::new(path)).unwrap_or_else(|e| panic!("{e:#?}"))
}

/// A world from a robot/user head and the rest of the text.
fn world(rest: &str) -> World {
    let text = format!(
        "[robot]\nname = \"Golem\"\nat = \"a\"\n[user]\nname = \"Luis\"\nat = \"a\"\n{rest}"
    );
    World::parse("test.toml", &text).unwrap_or_else(|e| {
        panic!(
            "{}",
            e.iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("\n")
        )
    })
}

fn seen(sim: &mut Sim) -> Vec<String> {
    sim.see().objects
}

/// The object's centre lies over its shelf's board, just above it.
fn assert_rests_on(sim: &Sim, object: &str, shelf: &str, height: f64) {
    assert_eq!(sim.where_is(object), Some(Where::OnShelf(shelf.into())));
    let board = sim.shelf_board(shelf).unwrap();
    let p = sim.position(object).unwrap();
    let (across, depth, up) = board.local(&p);
    assert!(
        across.abs() <= board.width / 2.0,
        "{object}: across {across}"
    );
    assert!(depth.abs() <= board.depth / 2.0, "{object}: depth {depth}");
    assert!(
        (up - height / 2.0).abs() < 0.002,
        "{object}: {up} above the board, expected {}",
        height / 2.0
    );
}

// ---- physics ----------------------------------------------------------------

#[test]
fn objects_come_to_rest_on_their_shelves() {
    let w = home();
    let sim = Sim::new(&w, 1);
    assert_rests_on(&sim, "noodles", "shelf_food", 0.15);
    assert_rests_on(&sim, "biscuits", "shelf_food", 0.2);
    assert_rests_on(&sim, "soup", "shelf_food", 0.15);
    assert_rests_on(&sim, "malz", "shelf_drinks", 0.2);
    assert_rests_on(&sim, "coke", "shelf_drinks", 0.12);
    assert!(sim.moving_objects().is_empty());
    assert!(
        !sim.events()
            .iter()
            .any(|e| matches!(e.kind, EventKind::NotSettled { .. })),
        "{:?}",
        sim.events()
    );
}

#[test]
fn a_placed_object_rests_on_the_shelf_it_was_put_on() {
    let w = home();
    let mut sim = Sim::new(&w, 1);
    sim.navigate("shelf_food").unwrap();
    sim.grasp("noodles", Hand::Left).unwrap();
    sim.grasp("soup", Hand::Right).unwrap();
    sim.navigate("shelf_drinks").unwrap();
    assert_eq!(
        sim.place(Hand::Left),
        Ok(Placed::OnShelf("shelf_drinks".into()))
    );
    assert_eq!(
        sim.place(Hand::Right),
        Ok(Placed::OnShelf("shelf_drinks".into()))
    );
    for (o, h) in [
        ("malz", 0.2),
        ("coke", 0.12),
        ("noodles", 0.15),
        ("soup", 0.15),
    ] {
        assert_rests_on(&sim, o, "shelf_drinks", h);
    }
    assert!(sim.moving_objects().is_empty());
    // The camera finds the new ones among the old, left to right.
    assert_eq!(seen(&mut sim), ["malz", "noodles", "soup", "coke"]);
    let placed = sim
        .events()
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Placed { .. }))
        .map(|e| e.to_string())
        .collect::<Vec<_>>();
    assert_eq!(
        placed,
        [
            "Golem puts noodles on shelf_drinks",
            "Golem puts soup on shelf_drinks"
        ]
    );
}

#[test]
fn an_object_put_down_where_there_is_no_shelf_falls_to_the_floor() {
    let w = home();
    let mut sim = Sim::new(&w, 1);
    sim.navigate("shelf_food").unwrap();
    sim.grasp("biscuits", Hand::Right).unwrap();
    sim.navigate("hall").unwrap();
    assert_eq!(
        sim.place(Hand::Right),
        Ok(Placed::Floor {
            place: "hall".into()
        })
    );
    assert_eq!(sim.holding(Hand::Right), None);
    assert_eq!(sim.where_is("biscuits"), Some(Where::Floor("hall".into())));
    let p = sim.position("biscuits").unwrap();
    assert!(p.z < 0.1, "biscuits rest at {p}");
    let last = sim
        .events()
        .iter()
        .rev()
        .find(|e| matches!(e.kind, EventKind::FellToFloor { .. }))
        .unwrap();
    assert_eq!(
        last.to_string(),
        "Golem lets go of biscuits, which falls to the floor at hall"
    );
    // Nothing on the floor is seen or can be grasped.
    assert_eq!(
        sim.grasp("biscuits", Hand::Right).unwrap_err().code(),
        "not_in_view"
    );
}

#[test]
fn an_object_taken_and_put_back_rests_on_its_shelf_again() {
    let w = home();
    let mut sim = Sim::new(&w, 3);
    sim.navigate("shelf_food").unwrap();
    sim.grasp("biscuits", Hand::Left).unwrap();
    assert_eq!(seen(&mut sim), ["noodles", "soup"]);
    assert_eq!(
        sim.place(Hand::Left),
        Ok(Placed::OnShelf("shelf_food".into()))
    );
    assert_rests_on(&sim, "biscuits", "shelf_food", 0.2);
    assert_eq!(seen(&mut sim), ["noodles", "biscuits", "soup"]);
}

// ---- the camera ----------------------------------------------------------------

#[test]
fn see_finds_exactly_the_objects_on_the_shelf_in_front() {
    let w = home();
    let mut sim = Sim::new(&w, 1);
    let s = sim.see();
    assert_eq!(s.shelf, None);
    assert!(s.objects.is_empty());
    sim.navigate("kitchen_food").unwrap();
    assert_eq!(
        sim.see(),
        Seen {
            shelf: Some("shelf_food".into()),
            objects: vec!["noodles".into(), "biscuits".into(), "soup".into()]
        }
    );
    sim.navigate("kitchen_drinks").unwrap();
    assert_eq!(seen(&mut sim), ["malz", "coke"]);
}

const NEIGHBOURS: &str = r#"
[[place]]
name = "a"
x = 0
y = 0
[[place]]
name = "b"
x = 0
y = 0.9
[[shelf]]
name = "left_shelf"
at = "b"
size = [0.8, 0.4, 0.8]
[[shelf]]
name = "right_shelf"
at = "a"
size = [0.8, 0.4, 0.8]
[[object]]
name = "cup"
on = "right_shelf"
spot = [-0.35, 0]
[[object]]
name = "plate"
on = "left_shelf"
spot = [0.35, 0]
"#;

#[test]
fn see_finds_nothing_on_a_neighbouring_shelf() {
    let w = world(NEIGHBOURS);
    let mut sim = Sim::new(&w, 1);
    // cup and plate stand 0.2 m apart, on two boards 0.1 m apart.
    assert_eq!(seen(&mut sim), ["cup"]);
    sim.navigate("b").unwrap();
    assert_eq!(seen(&mut sim), ["plate"]);
}

#[test]
fn see_finds_nothing_behind_a_wall() {
    let w = world(
        r#"
[[place]]
name = "a"
x = 0
y = 0
[[place]]
name = "b"
x = 0
y = 5
[[wall]]
from = [0.25, -1]
to = [0.25, 1]
[[shelf]]
name = "s"
at = "a"
[[shelf]]
name = "open"
at = "b"
[[object]]
name = "cup"
on = "s"
[[object]]
name = "plate"
on = "open"
"#,
    );
    let mut sim = Sim::new(&w, 1);
    let s = sim.see();
    assert_eq!(s.shelf.as_deref(), Some("s"));
    assert!(s.objects.is_empty(), "{s:?}");
    assert_eq!(sim.where_is("cup"), Some(Where::OnShelf("s".into())));
    assert_eq!(
        sim.grasp("cup", Hand::Left).unwrap_err().code(),
        "not_in_view"
    );
    // The same shelf without a wall: seen.
    sim.navigate("b").unwrap();
    assert_eq!(seen(&mut sim), ["plate"]);
}

#[test]
fn see_does_not_report_objects_in_hands() {
    let w = home();
    let mut sim = Sim::new(&w, 1);
    sim.navigate("kitchen_food").unwrap();
    sim.grasp("soup", Hand::Right).unwrap();
    assert_eq!(seen(&mut sim), ["noodles", "biscuits"]);
    sim.grasp("noodles", Hand::Left).unwrap();
    assert_eq!(seen(&mut sim), ["biscuits"]);
}

#[test]
fn a_big_object_hides_a_small_one_behind_it() {
    let w = world(
        r#"
[[place]]
name = "a"
x = 0
y = 0
[[shelf]]
name = "s"
at = "a"
size = [0.8, 0.4, 0.8]
[[object]]
name = "cereal_box"
on = "s"
size = [0.2, 0.08, 0.4]
spot = [0.0, -0.1]
[[object]]
name = "sauce"
on = "s"
size = [0.05, 0.05, 0.08]
spot = [0.0, 0.12]
[[object]]
name = "beans"
on = "s"
size = [0.07, 0.07, 0.1]
spot = [0.3, 0.12]
"#,
    );
    let mut sim = Sim::new(&w, 1);
    assert_eq!(sim.where_is("sauce"), Some(Where::OnShelf("s".into())));
    assert_eq!(seen(&mut sim), ["cereal_box", "beans"]);
    assert_eq!(
        sim.grasp("sauce", Hand::Left).unwrap_err().code(),
        "not_in_view"
    );
    // Once the box is taken away the sauce is in view.
    sim.grasp("cereal_box", Hand::Left).unwrap();
    assert_eq!(seen(&mut sim), ["sauce", "beans"]);
    sim.grasp("sauce", Hand::Right).unwrap();
}

// ---- routes and time ------------------------------------------------------------

#[test]
fn shortest_routes_over_explicit_routes_and_their_times() {
    let w = home();
    let mut sim = Sim::new(&w, 1);
    let r = sim.route("living_room", "shelf_food").unwrap();
    assert_eq!(r.places, ["living_room", "hall", "kitchen", "kitchen_food"]);
    assert_eq!(r.length, 10.0);
    assert_eq!(r.seconds, 20.0);
    assert_eq!(sim.navigate("shelf_food"), Ok(r));
    assert_eq!(sim.now(), 20.0);
    assert_eq!(sim.robot_at(), "kitchen_food");
    assert_eq!(
        sim.events()[0].to_string(),
        "Golem goes from living_room to kitchen_food via hall and kitchen (10.0 m, 20.0 s)"
    );
    // Already there: nothing to do, no time.
    let r = sim.navigate("kitchen_food").unwrap();
    assert_eq!(r.places, ["kitchen_food"]);
    assert_eq!(sim.now(), 20.0);
}

#[test]
fn every_two_places_are_joined_when_no_route_is_given() {
    let w = world(
        "[[place]]\nname = \"a\"\nx = 0\ny = 0\n[[place]]\nname = \"b\"\nx = 3\ny = 4\n[[place]]\nname = \"c\"\nx = 6\ny = 0\n",
    );
    let mut sim = Sim::new(&w, 1);
    let r = sim.route("a", "c").unwrap();
    assert_eq!(r.places, ["a", "c"]);
    assert_eq!(r.length, 6.0);
    assert_eq!(sim.navigate("b").unwrap().length, 5.0);
    assert_eq!(sim.now(), 10.0);
    assert_eq!(sim.robot_at(), "b");
}

#[test]
fn a_blocked_route_is_found_on_trying_it_then_avoided() {
    let mut text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/worlds/home.toml"
    ))
    .unwrap();
    text.push_str("\n[[fault]]\nkind = \"route_blocked\"\nfrom = \"kitchen\"\nto = \"hall\"\n");
    let w = World::parse("home.toml", &text).unwrap();
    let mut sim = Sim::new(&w, 1);
    // Planned through the kitchen: the robot does not know yet.
    assert_eq!(
        sim.route("living_room", "shelf_food").unwrap().places,
        ["living_room", "hall", "kitchen", "kitchen_food"]
    );
    let e = sim.navigate("shelf_food").unwrap_err();
    assert_eq!(
        e,
        NavError::Blocked {
            at: "hall".into(),
            from: "hall".into(),
            to: "kitchen".into()
        }
    );
    assert_eq!(e.code(), "blocked");
    assert_eq!(sim.robot_at(), "hall");
    assert_eq!(sim.now(), 8.0);
    assert_eq!(sim.known_blocked(), [("hall", "kitchen")]);
    let r = sim.route("hall", "shelf_food").unwrap();
    assert_eq!(r.places, ["hall", "corridor", "kitchen_food"]);
    let expected = 4.0 + (16.0f64 + 4.0).sqrt();
    assert_eq!(r.length, expected);
    assert_eq!(sim.navigate("shelf_food"), Ok(r));
    assert_eq!(sim.now(), 8.0 + expected / 0.5);
    let narration: Vec<String> = sim.events().iter().map(|e| e.to_string()).collect();
    assert_eq!(
        narration,
        [
            "Golem goes from living_room to hall (4.0 m, 8.0 s)",
            "Golem finds the way from hall to kitchen blocked and stops at hall",
            "Golem goes from hall to kitchen_food via corridor (8.5 m, 16.9 s)",
        ]
    );
}

#[test]
fn no_route_and_unknown_places() {
    let w = world(
        r#"
[[place]]
name = "a"
x = 0
y = 0
[[place]]
name = "b"
x = 1
y = 0
[[place]]
name = "island"
x = 5
y = 5
[[route]]
from = "a"
to = "b"
[[fault]]
kind = "route_blocked"
from = "b"
to = "a"
"#,
    );
    let mut sim = Sim::new(&w, 1);
    let e = sim.navigate("island").unwrap_err();
    assert_eq!(e.code(), "no_route");
    assert_eq!(e.to_string(), "there is no route from `a` to `island`");
    assert_eq!(sim.route("a", "island"), None);
    let e = sim.navigate("atlantis").unwrap_err();
    assert_eq!(e, NavError::UnknownPlace("atlantis".into()));
    assert_eq!(e.code(), "unknown_place");
    // The only way to b is blocked: found out, then there is no route.
    assert_eq!(sim.navigate("b").unwrap_err().code(), "blocked");
    assert_eq!(sim.robot_at(), "a");
    assert_eq!(sim.navigate("b").unwrap_err().code(), "no_route");
    assert_eq!(sim.now(), 0.0);
}

// ---- hands ----------------------------------------------------------------------

#[test]
fn grasp_errors() {
    let w = home();
    let mut sim = Sim::new(&w, 1);
    assert_eq!(
        sim.grasp("unicorn", Hand::Left),
        Err(GraspError::UnknownObject("unicorn".into()))
    );
    assert_eq!(
        sim.grasp("noodles", Hand::Left).unwrap_err().code(),
        "not_in_view"
    );
    sim.navigate("shelf_food").unwrap();
    // Not on the shelf in front.
    assert_eq!(
        sim.grasp("malz", Hand::Left).unwrap_err().code(),
        "not_in_view"
    );
    sim.grasp("noodles", Hand::Left).unwrap();
    assert_eq!(sim.holding(Hand::Left), Some("noodles"));
    assert_eq!(sim.where_is("noodles"), Some(Where::InHand(Hand::Left)));
    let e = sim.grasp("soup", Hand::Left).unwrap_err();
    assert_eq!(
        e,
        GraspError::HandFull {
            hand: Hand::Left,
            holding: "noodles".into()
        }
    );
    assert_eq!(e.code(), "hand_full");
    // In the other hand already: not on the shelf.
    assert_eq!(
        sim.grasp("noodles", Hand::Right).unwrap_err().code(),
        "not_in_view"
    );
}

#[test]
fn a_grasp_fault_fails_then_the_retry_succeeds() {
    let mut text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/worlds/home.toml"
    ))
    .unwrap();
    text.push_str("\n[[fault]]\nkind = \"grasp_fails\"\nobject = \"malz\"\ntimes = 2\n");
    let w = World::parse("home.toml", &text).unwrap();
    let mut sim = Sim::new(&w, 1);
    sim.navigate("shelf_drinks").unwrap();
    let t = sim.now();
    for _ in 0..2 {
        let e = sim.grasp("malz", Hand::Right).unwrap_err();
        assert_eq!(e.code(), "grasp_failed");
        assert_eq!(sim.holding(Hand::Right), None);
        assert_eq!(
            sim.where_is("malz"),
            Some(Where::OnShelf("shelf_drinks".into()))
        );
    }
    assert_eq!(sim.now(), t + 2.0 * GRASP_SECONDS);
    sim.grasp("malz", Hand::Right).unwrap();
    assert_eq!(sim.holding(Hand::Right), Some("malz"));
    let failed: Vec<String> = sim
        .events()
        .iter()
        .filter(|e| matches!(e.kind, EventKind::GraspFailed { .. }))
        .map(|e| e.to_string())
        .collect();
    assert_eq!(
        failed,
        ["Golem tries to take malz with its right hand, but it slips"; 2]
    );
}

#[test]
fn hand_over_needs_the_user_here_and_something_in_hand() {
    let w = home();
    let mut sim = Sim::new(&w, 1);
    assert_eq!(
        sim.hand_over(Hand::Left),
        Err(HandOverError::EmptyHand(Hand::Left))
    );
    assert_eq!(sim.place(Hand::Left).unwrap_err().code(), "empty_hand");
    sim.navigate("shelf_drinks").unwrap();
    sim.grasp("malz", Hand::Left).unwrap();
    let e = sim.hand_over(Hand::Left).unwrap_err();
    assert_eq!(
        e,
        HandOverError::NoUser {
            user_at: "living_room".into()
        }
    );
    assert_eq!(e.code(), "no_user");
    sim.navigate("living_room").unwrap();
    assert_eq!(sim.hand_over(Hand::Left), Ok("malz".into()));
    assert_eq!(sim.holding(Hand::Left), None);
    assert_eq!(sim.where_is("malz"), Some(Where::WithUser));
    assert_eq!(
        sim.events().last().unwrap().to_string(),
        "Golem hands malz to Luis"
    );
}

#[test]
fn hands_parse_and_print() {
    assert_eq!("left".parse::<Hand>(), Ok(Hand::Left));
    assert_eq!("right".parse::<Hand>(), Ok(Hand::Right));
    assert!("middle".parse::<Hand>().is_err());
    assert_eq!(Hand::Right.to_string(), "right");
}

// ---- the user ---------------------------------------------------------------------

#[test]
fn the_user_talks_leaves_after_saying_and_comes_back_at_a_time() {
    let w = home();
    let mut sim = Sim::new(&w, 1);
    assert_eq!(sim.hear(), Heard::Said("hi golem i like malz".into()));
    sim.say("hello luis");
    assert_eq!(sim.hear(), Heard::Said("i like noodles best".into()));
    assert_eq!(sim.hear(), Heard::Said("i am going to work".into()));
    let said_at = sim.events().last().unwrap().time;
    // The move comes 10 s after the third utterance.
    assert_eq!(sim.user_at(), "living_room");
    sim.wait(10.0);
    assert_eq!(sim.user_at(), "outside");
    let moved = sim
        .events()
        .iter()
        .find(|e| matches!(e.kind, EventKind::UserMoved { .. }))
        .unwrap();
    assert_eq!(moved.time, said_at + 10.0);
    assert_eq!(moved.to_string(), "Luis goes from living_room to outside");
    // In another room: nobody to hear.
    assert_eq!(sim.hear(), Heard::Nobody);
    assert_eq!(sim.hand_over(Hand::Left).unwrap_err().code(), "empty_hand");
    // Back at 600 s.
    assert!(!sim.wait_for_user(100.0));
    assert_eq!(sim.user_at(), "outside");
    assert!(sim.wait_for_user(10_000.0));
    assert_eq!(sim.now(), 600.0);
    assert_eq!(sim.user_at(), "living_room");
    assert_eq!(sim.hear(), Heard::Said("i am back".into()));
    assert_eq!(sim.hear(), Heard::NothingMore);
    // Waiting without end for a user who has no more moves: gives up at once.
    sim.navigate("hall").unwrap();
    let t = sim.now();
    assert!(!sim.wait_for_user(f64::INFINITY));
    assert_eq!(sim.now(), t);
    // The robot's room, not its place, decides who is heard.
    assert_eq!(sim.hear(), Heard::Nobody);
    // Times never decrease along the log.
    assert!(sim.events().windows(2).all(|p| p[0].time <= p[1].time));
    let narration: Vec<String> = sim
        .events()
        .iter()
        .map(|e| format!("{:6.1} {e}", e.time))
        .collect();
    insta::assert_snapshot!(narration.join("\n"));
}

#[test]
fn mishearing_garbles_every_word_then_the_user_repeats() {
    let text = r#"
[robot]
name = "Golem"
at = "a"
[user]
name = "Luis"
at = "a"
says = ["bring me the noodles", "yes please"]
[[place]]
name = "a"
x = 0
y = 0
[[fault]]
kind = "mishear"
utterance = 1
[[fault]]
kind = "mishear"
utterance = "yes please"
"#;
    let w = World::parse("m.toml", text).unwrap();
    let mut sim = Sim::new(&w, 42);
    let Heard::Misheard(g) = sim.hear() else {
        panic!("expected a mishearing")
    };
    assert_eq!(g.split_whitespace().count(), 4);
    for word in g.split_whitespace() {
        assert!(!["bring", "me", "the", "noodles"].contains(&word), "{g}");
    }
    assert_eq!(sim.hear(), Heard::Said("bring me the noodles".into()));
    assert!(matches!(sim.hear(), Heard::Misheard(_)));
    assert_eq!(sim.hear(), Heard::Said("yes please".into()));
    assert_eq!(sim.hear(), Heard::NothingMore);
    // Another seed, other words.
    let mut other = Sim::new(&w, 43);
    assert_ne!(other.hear(), Heard::Misheard(g));
}

// ---- determinism ----------------------------------------------------------------------

fn script(world: &World, seed: u64) -> Sim {
    let mut sim = Sim::new(world, seed);
    let _ = sim.hear();
    sim.say("what shall i bring");
    let _ = sim.hear();
    sim.navigate("shelf_food").unwrap();
    sim.see();
    sim.grasp("noodles", Hand::Left).unwrap();
    sim.grasp("biscuits", Hand::Right).unwrap();
    sim.navigate("shelf_drinks").unwrap();
    sim.place(Hand::Right).unwrap();
    sim.see();
    sim.grasp("coke", Hand::Right).unwrap();
    sim.navigate("hall").unwrap();
    sim.place(Hand::Right).unwrap();
    sim.navigate("living_room").unwrap();
    sim.hand_over(Hand::Left).unwrap();
    let _ = sim.hear();
    sim.wait_for_user(1000.0);
    sim
}

fn rest_bits(sim: &Sim) -> Vec<[u32; 3]> {
    sim.events()
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Placed { rest, .. } | EventKind::FellToFloor { rest, .. } => {
                Some(rest.map(f32::to_bits))
            }
            _ => None,
        })
        .collect()
}

#[test]
fn the_same_world_and_seed_give_the_same_run_bit_for_bit() {
    let w = home();
    let a = script(&w, 7);
    let b = script(&w, 7);
    assert_eq!(format!("{:?}", a.events()), format!("{:?}", b.events()));
    assert_eq!(rest_bits(&a).len(), 2);
    assert_eq!(rest_bits(&a), rest_bits(&b));
    let times = |s: &Sim| {
        s.events()
            .iter()
            .map(|e| e.time.to_bits())
            .collect::<Vec<_>>()
    };
    assert_eq!(times(&a), times(&b));
    for o in w.object_names() {
        let bits = |s: &Sim| {
            s.position(o)
                .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
        };
        assert_eq!(bits(&a), bits(&b), "{o}");
    }
}
