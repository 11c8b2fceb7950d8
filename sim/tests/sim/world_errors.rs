//! Bad world files: every error names file, line, column and the key or name
//! at fault (insta snapshots), and no input makes the reader panic
//! (proptest over random text, random bytes and mutated valid files).

use proptest::prelude::*;
use sitlog_sim::{Hand, Sim, World};

const BASE: &str = r#"[robot]
name = "Golem"
at = "a"
[user]
name = "Luis"
at = "a"
says = ["hi", "bring me noodles"]
[[place]]
name = "a"
x = 0
y = 0
[[place]]
name = "b"
x = 2
y = 0
[[shelf]]
name = "s"
at = "b"
[[object]]
name = "noodles"
on = "s"
"#;

fn with(extra: &str) -> String {
    format!("{BASE}{extra}")
}

fn replace(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "{from:?} is not in BASE");
    BASE.replacen(from, to, 1)
}

/// Each error, then the line it points at with a caret under the column.
fn report(text: &str) -> String {
    match World::parse("world.toml", text) {
        Ok(_) => "(no error)\n".into(),
        Err(errors) => {
            assert!(!errors.is_empty());
            let lines: Vec<&str> = text.lines().collect();
            let mut out = String::new();
            for e in errors {
                out.push_str(&format!("{e}\n"));
                if let Some(line) = lines.get(e.line.wrapping_sub(1)) {
                    out.push_str(&format!(
                        "    | {line}\n    | {}^\n",
                        " ".repeat(e.column - 1)
                    ));
                }
            }
            out
        }
    }
}

fn cases() -> Vec<(&'static str, String)> {
    vec![
        ("not TOML", replace("[user]", "[user")),
        ("not TOML: a value without quotes", replace("at = \"a\"", "at = a")),
        ("unknown key in [[object]]", with("colour = \"red\"\n")),
        ("unknown key at the top", format!("colour = 1\n{BASE}")),
        ("unknown key in [robot]", replace("name = \"Golem\"", "name = \"Golem\"\narms = 2")),
        ("unknown key in [[place]]", replace("x = 2", "x = 2\nz = 1")),
        (
            "unknown key in [[user.moves]]",
            with("[[user.moves]]\nafter_saying = 1\nto = \"b\"\nrun = true\n"),
        ),
        ("missing key in [[object]]", replace("name = \"noodles\"\n", "")),
        ("missing key in [robot]", replace("at = \"a\"\n[user]", "[user]")),
        ("missing key in [[place]]", replace("x = 2\n", "")),
        ("missing [robot] and [user]", {
            let start = BASE.find("[[place]]").unwrap();
            BASE[start..].to_string()
        }),
        ("wrong type: a string for a number", replace("x = 2", "x = \"two\"")),
        ("wrong type: a number for a name", replace("at = \"b\"", "at = 2")),
        ("wrong type: says is not an array", replace("says = [\"hi\", \"bring me noodles\"]", "says = \"hi\"")),
        ("wrong type: an utterance is not a string", replace("says = [\"hi\", \"bring me noodles\"]", "says = [\"hi\", 2]")),
        ("wrong type: place is not an array of tables", {
            let end = BASE.find("[[place]]").unwrap();
            format!("place = \"a\"\n{}", &BASE[..end])
        }),
        ("wrong type: size has two numbers", with("size = [0.1, 0.2]\n")),
        ("wrong type: seed is negative", format!("seed = -1\n{BASE}")),
        ("wrong type: seed is a float", format!("seed = 1.5\n{BASE}")),
        ("the robot at a place that is not defined", replace("at = \"a\"", "at = \"attic\"")),
        ("the user at a place that is not defined", replace("at = \"a\"\nsays", "at = \"garden\"\nsays")),
        ("the user moves to a place that is not defined", with("[[user.moves]]\nat_time = 5\nto = \"moon\"\n")),
        ("a route to a place that is not defined", with("[[route]]\nfrom = \"a\"\nto = \"c\"\n")),
        ("a shelf at a place that is not defined", replace("at = \"b\"", "at = \"c\"")),
        ("an object on a missing shelf", replace("on = \"s\"", "on = \"shelf_x\"")),
        ("a fault names an object that is not defined", with("[[fault]]\nkind = \"grasp_fails\"\nobject = \"malz\"\n")),
        ("misspelt names of a place, a shelf and an object: did you mean (session 16)", with("[[place]]\nname = \"kitchen\"\nx = 4\ny = 0\n[[shelf]]\nname = \"fridge\"\nat = \"kitchn\"\n[[object]]\nname = \"milk\"\non = \"nodles_shelf\"\n[[object]]\nname = \"juice\"\non = \"fridg\"\n[[fault]]\nkind = \"grasp_fails\"\nobject = \"noodels\"\n")),
        ("a fault blocks a route between places that are not defined", with("[[fault]]\nkind = \"route_blocked\"\nfrom = \"hall\"\nto = \"kitchen\"\n")),
        ("a fault blocks a route that is not there", with("[[place]]\nname = \"c\"\nx = 4\ny = 0\n[[route]]\nfrom = \"a\"\nto = \"b\"\n[[fault]]\nkind = \"route_blocked\"\nfrom = \"a\"\nto = \"c\"\n")),
        ("mishear of an utterance number that is not there", with("[[fault]]\nkind = \"mishear\"\nutterance = 3\n")),
        ("a huge utterance number", with("[[fault]]\nkind = \"mishear\"\nutterance = 99999999999999999999\n")),
        ("mishear of an utterance number 0", with("[[fault]]\nkind = \"mishear\"\nutterance = 0\n")),
        ("mishear of a text the user never says", with("[[fault]]\nkind = \"mishear\"\nutterance = \"hello\"\n")),
        ("after_saying beyond the utterances", with("[[user.moves]]\nafter_saying = 3\nto = \"b\"\n")),
        ("after_saying and at_time both", with("[[user.moves]]\nafter_saying = 1\nat_time = 3.0\nto = \"b\"\n")),
        ("neither after_saying nor at_time", with("[[user.moves]]\nto = \"b\"\n")),
        ("two places with one name", with("[[place]]\nname = \"a\"\nx = 5\ny = 5\n")),
        ("two shelves with one name", with("[[shelf]]\nname = \"s\"\nat = \"a\"\n")),
        ("two objects with one name", with("[[object]]\nname = \"noodles\"\non = \"s\"\n")),
        ("a fault of an unknown kind", with("[[fault]]\nkind = \"earthquake\"\n")),
        ("a key a fault of that kind does not have", with("[[fault]]\nkind = \"grasp_fails\"\nobject = \"noodles\"\nfrom = \"a\"\n")),
        ("a shelf at a place that has another shelf", with("[[shelf]]\nname = \"s2\"\nat = \"b\"\n")),
        ("a route to itself", with("[[route]]\nfrom = \"a\"\nto = \"a\"\n")),
        ("a fault blocks a route to itself", with("[[fault]]\nkind = \"route_blocked\"\nfrom = \"b\"\nto = \"b\"\n")),
        ("a negative size", with("size = [0.1, -0.2, 0.3]\n")),
        ("an infinite size", with("size = [0.1, inf, 0.3]\n")),
        ("a zero speed", replace("at = \"a\"\n[user]", "at = \"a\"\nspeed = 0\n[user]")),
        ("a negative speed", replace("at = \"a\"\n[user]", "at = \"a\"\nspeed = -0.5\n[user]")),
        ("a speed too slow to be physical", replace("at = \"a\"\n[user]", "at = \"a\"\nspeed = 1e-300\n[user]")),
        ("a speed too fast to be physical", replace("at = \"a\"\n[user]", "at = \"a\"\nspeed = 1e6\n[user]")),
        ("a speed that is not a number", replace("at = \"a\"\n[user]", "at = \"a\"\nspeed = nan\n[user]")),
        ("a coordinate too far away", replace("x = 2", "x = 1e9")),
        ("an empty name", replace("name = \"noodles\"", "name = \"\"")),
        ("objects that do not fit on their shelf", with("size = [0.5, 0.1, 0.1]\n[[object]]\nname = \"box\"\non = \"s\"\nsize = [0.5, 0.1, 0.1]\n")),
        ("objects that overlap", with("spot = [0.0, 0.0]\n[[object]]\nname = \"box\"\non = \"s\"\nspot = [0.03, 0.0]\n")),
        ("an object off the edge of its board", with("spot = [0.39, 0.0]\n")),
        ("a wall of no length", with("[[wall]]\nfrom = [1, 1]\nto = [1, 1]\n")),
        ("a wall with three coordinates", with("[[wall]]\nfrom = [1, 1, 0]\nto = [1, 2]\n")),
        ("many errors at once, in file order", {
            let mut t = replace("at = \"a\"", "at = \"attic\"");
            t = t.replacen("x = 2", "x = \"two\"", 1);
            t = t.replacen("on = \"s\"", "on = \"shelf_x\"\ncolour = \"red\"", 1);
            t.push_str("[[fault]]\nkind = \"earthquake\"\n");
            t
        }),
    ]
}

#[test]
fn the_base_world_is_valid() {
    let w = World::parse("world.toml", BASE).unwrap();
    assert_eq!(w.object_names(), ["noodles"]);
}

#[test]
fn every_error_names_file_line_column_and_key() {
    let mut out = String::new();
    for (name, text) in cases() {
        out.push_str(&format!("## {name}\n{}\n", report(&text)));
    }
    insta::assert_snapshot!(out);
}

#[test]
fn the_exact_messages_of_the_contract() {
    let e = World::parse("w.toml", &with("colour = \"red\"\n")).unwrap_err();
    assert_eq!(e.len(), 1);
    assert!(
        e[0].message
            .starts_with("unknown key `colour` in [[object]]"),
        "{}",
        e[0]
    );
    assert_eq!((e[0].line, e[0].column), (22, 1));
    let e = World::parse("w.toml", &replace("on = \"s\"", "on = \"shelf_x\"")).unwrap_err();
    assert_eq!(
        e[0].to_string(),
        "w.toml:21:6: error: object `noodles` is on shelf `shelf_x`, which is not defined"
    );
}

#[test]
fn text_that_is_not_utf8_is_an_error_at_its_first_bad_byte() {
    let e = World::text_of("w.toml", b"seed = 7\n# caf\xc3\xa9 \xff\n").unwrap_err();
    assert_eq!(
        e[0].to_string(),
        "w.toml:2:8: error: invalid UTF-8 (byte 0xFF): the file must be UTF-8 text"
    );
    let dir = std::env::temp_dir().join(format!("sitlog-sim-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, b"\xfe").unwrap();
    let e = World::load(&bad).unwrap_err();
    assert_eq!((e[0].line, e[0].column), (1, 1));
    let missing = dir.join("missing.toml");
    let e = World::load(&missing).unwrap_err();
    assert_eq!((e[0].line, e[0].column), (0, 0));
    assert!(
        e[0].to_string()
            .contains(": error: cannot read the world file"),
        "{}",
        e[0]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

fn home_text() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/worlds/home.toml"
    ))
    .unwrap()
}

/// A world that reads must also run: build it and try each action once.
fn exercise(world: &World) {
    let mut sim = Sim::new(world, 1);
    for p in world.place_names() {
        let _ = sim.navigate(p);
        let seen = sim.see();
        for (o, hand) in seen.objects.iter().zip(Hand::ALL) {
            let _ = sim.grasp(o, hand);
        }
        let _ = sim.hear();
    }
    for hand in Hand::ALL {
        let _ = sim.place(hand);
    }
    sim.wait_for_user(100.0);
    for e in sim.events() {
        let _ = e.to_string();
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn random_text_never_panics(text in "\\PC{0,300}") {
        let _ = World::parse("r.toml", &text);
    }

    #[test]
    fn random_toml_like_text_never_panics(
        text in "(\\[\\[?(robot|user|place|shelf|object|fault|route|wall|user\\.moves)\\]\\]?\n|(name|at|x|y|on|size|kind|says|seed|to|from) = (\"[a-z]{0,3}\"|-?[0-9]{1,3}(\\.[0-9])?|\\[[0-9., \"a-z]{0,12}\\]|inf|nan)\n){0,30}"
    ) {
        let _ = World::parse("r.toml", &text);
    }

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        if let Ok(text) = World::text_of("r.toml", &bytes) {
            let _ = World::parse("r.toml", text);
        }
        let _ = World::parse("r.toml", &String::from_utf8_lossy(&bytes));
    }
}

proptest! {
    // Mutated valid files may still be valid: then they are run too, which
    // steps the physics, so fewer cases.
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn mutated_valid_files_never_panic(
        edits in proptest::collection::vec((any::<prop::sample::Index>(), 0u8..4, "[a-z0-9=\\[\\]\"., \n-]{0,4}"), 1..4)
    ) {
        let mut text: Vec<char> = home_text().chars().collect();
        for (at, op, s) in edits {
            let i = at.index(text.len() + 1);
            match op {
                0 => { text.splice(i..i, s.chars()); }
                1 => { let j = (i + s.len().max(1)).min(text.len()); text.drain(i..j); }
                2 => { let j = (i + s.chars().count()).min(text.len()); text.splice(i..j, s.chars()); }
                _ => {
                    // Duplicate a line: names twice, tables twice.
                    let t: String = text.iter().collect();
                    let lines: Vec<&str> = t.lines().collect();
                    if !lines.is_empty() {
                        let l = i % lines.len();
                        let mut out = lines.clone();
                        out.insert(l, lines[l]);
                        text = out.join("\n").chars().collect();
                    }
                }
            }
        }
        let text: String = text.into_iter().collect();
        if let Ok(world) = World::parse("m.toml", &text) {
            exercise(&world);
        }
    }
}

/// A world of 20 000 shelves with an object each loads (issue 31: 100 000
/// took 79 s, every shelf scanning every object; a quadratic step would keep
/// this test running for hours). `benches/benches/world.rs` measures it.
#[test]
fn a_world_of_twenty_thousand_shelves_loads() {
    let text = sitlog_sim::world::example::grid(20_000);
    let w =
        World::parse("big.toml", &text).unwrap_or_else(|e| panic!("{:?}", &e[..e.len().min(3)]));
    assert_eq!(w.object_names().len(), 20_000);
    assert_eq!(w.shelf_names().len(), 20_000);
    assert_eq!(w.initial_shelf("o19999"), Some("s19999"));
}
