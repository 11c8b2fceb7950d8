//! The interface of a robot over ROS 2 (`ros2.toml`, all keys optional):
//! topic, action and service names, QoS, frame ids, timeouts, the names of
//! the robot and the user, and the places a navigation goal can name.
//! Defaults are the guide's interface table; places come from the
//! application's world file (a place, or a shelf standing for the place in
//! front of it), then from `[places.NAME]`.
//!
//! Invariant: an [`Interface`] is complete (every name set, every timeout
//! finite and ≥ 0); any unknown key is an error; an error is one line,
//! `FILE:LINE:COL: error: ...` at the value that is wrong.

use serde::Deserialize;
use sitlog_sim::World;
use std::collections::BTreeMap;
use std::time::Duration;

/// Reliability, durability and depth of one topic.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Qos {
    /// `reliable` or `best_effort`.
    pub reliability: String,
    /// `transient_local` or `volatile`.
    pub durability: String,
    /// History: keep the last `depth` messages.
    pub depth: i32,
}

impl Qos {
    fn new(reliability: &str, durability: &str, depth: i32) -> Qos {
        Qos {
            reliability: reliability.into(),
            durability: durability.into(),
            depth,
        }
    }
}

macro_rules! section {
    ($(#[$m:meta])* $name:ident { $($(#[$fm:meta])* $field:ident : $ty:ty = $default:expr),* $(,)? }) => {
        $(#[$m])*
        #[derive(Clone, Debug, Deserialize, PartialEq)]
        #[serde(deny_unknown_fields, default)]
        pub struct $name { $($(#[$fm])* pub $field: $ty),* }
        impl Default for $name {
            fn default() -> $name { $name { $($field: $default.into()),* } }
        }
    };
}

section!(
    /// `[topics]`.
    Topics {
        say: String = "/sitlog/say",
        listening: String = "/sitlog/listening",
        heard: String = "/sitlog/heard",
        screen: String = "/sitlog/screen",
        message: String = "/sitlog/message",
        /// Task → robot: a run starts (its id, once, latched).
        run: String = "/sitlog/run",
        /// Robot → task: the robot cannot go on with this run (why).
        abort: String = "/sitlog/abort",
    }
);

section!(
    /// `[actions]`.
    ActionNames {
        navigate: String = "/navigate_to_pose",
        grasp: String = "/sitlog/grasp",
        place: String = "/sitlog/place",
        hand_over: String = "/sitlog/hand_over",
        wait_for_person: String = "/sitlog/wait_for_person",
    }
);

section!(
    /// `[services]`.
    Services {
        detect_objects: String = "/sitlog/detect_objects",
        hands: String = "/sitlog/hands",
    }
);

section!(
    /// `[frames]`: the frame of navigation goals, and the camera asked for
    /// detections (empty: the robot's default).
    Frames {
        map: String = "map",
        camera: String = "",
    }
);

section!(
    /// `[qos.TOPIC]`.
    TopicQos {
        say: Qos = Qos::new("reliable", "transient_local", 50),
        listening: Qos = Qos::new("reliable", "transient_local", 1),
        heard: Qos = Qos::new("reliable", "volatile", 10),
        screen: Qos = Qos::new("reliable", "transient_local", 10),
        message: Qos = Qos::new("reliable", "transient_local", 10),
        run: Qos = Qos::new("reliable", "transient_local", 1),
        abort: Qos = Qos::new("reliable", "volatile", 10),
    }
);

section!(
    /// `[timeouts]`, in seconds.
    Timeouts {
        /// To find the robot at start, and the server of an action or service.
        discovery: f64 = 5.0,
        /// For the robot to acknowledge a message or answer a request: past
        /// it, the robot is gone.
        answer: f64 = 5.0,
        /// For a navigation to end.
        navigate: f64 = 600.0,
        /// For any other action to end.
        action: f64 = 120.0,
        /// For an utterance while listening; 0: as long as it takes.
        speech: f64 = 0.0,
    }
);

/// `[places.NAME]`: a goal pose in the map frame.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PlacePose {
    pub x: f64,
    pub y: f64,
    /// Degrees anticlockwise from +x.
    #[serde(default)]
    pub yaw: f64,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct File {
    robot_name: Option<String>,
    user_name: Option<String>,
    topics: Topics,
    actions: ActionNames,
    services: Services,
    frames: Frames,
    qos: TopicQos,
    timeouts: Timeouts,
    places: BTreeMap<String, PlacePose>,
}

/// The whole interface of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Interface {
    pub robot_name: String,
    pub user_name: String,
    pub topics: Topics,
    pub actions: ActionNames,
    pub services: Services,
    pub frames: Frames,
    pub qos: TopicQos,
    pub timeouts: Timeouts,
    /// Goal poses by name: (x, y, yaw in radians).
    pub places: BTreeMap<String, (f64, f64, f64)>,
}

impl Interface {
    /// The interface of `ros2.toml` (`file`: its name and text, if there is
    /// one) over the places and names of `world`. `Err`: one line,
    /// `FILE:LINE:COL: error: ...` at the value (or text) that is wrong.
    pub fn load(file: Option<(&str, &str)>, world: Option<&World>) -> Result<Interface, String> {
        let (name, text) = file.unwrap_or(("ros2.toml", ""));
        let error = |path: &[&str], message: String| {
            let at = value_at(text, path);
            match at {
                Some(at) => {
                    let (line, column) = line_col(text, at);
                    format!("{name}:{line}:{column}: error: {message}")
                }
                None => format!("{name}: error: {message}"),
            }
        };
        let parsed: File = match file {
            Some(_) => toml::from_str(text).map_err(|e: toml::de::Error| {
                let message = e.message().trim().replace('\n', " ");
                match e.span() {
                    Some(span) => {
                        let (line, column) = line_col(text, span.start);
                        format!("{name}:{line}:{column}: error: {message}")
                    }
                    None => format!("{name}: error: {message}"),
                }
            })?,
            None => File::default(),
        };
        let t = &parsed.timeouts;
        for (key, v) in [
            ("discovery", t.discovery),
            ("answer", t.answer),
            ("navigate", t.navigate),
            ("action", t.action),
            ("speech", t.speech),
        ] {
            if !(v.is_finite() && (0.0..=1.0e6).contains(&v)) {
                return Err(error(
                    &["timeouts", key],
                    format!("timeouts.{key} must be a number of seconds between 0 and 1000000"),
                ));
            }
        }
        for (key, q) in [
            ("say", &parsed.qos.say),
            ("listening", &parsed.qos.listening),
            ("heard", &parsed.qos.heard),
            ("screen", &parsed.qos.screen),
            ("message", &parsed.qos.message),
            ("run", &parsed.qos.run),
            ("abort", &parsed.qos.abort),
        ] {
            let bad = if !matches!(q.reliability.as_str(), "reliable" | "best_effort") {
                Some("reliability")
            } else if !matches!(q.durability.as_str(), "transient_local" | "volatile") {
                Some("durability")
            } else if !(1..=10_000).contains(&q.depth) {
                Some("depth")
            } else {
                None
            };
            if let Some(field) = bad {
                return Err(error(
                    &["qos", key, field],
                    format!("qos.{key}: reliability `reliable` or `best_effort`, durability `transient_local` or `volatile`, depth 1 to 10000"),
                ));
            }
        }
        let mut places = BTreeMap::new();
        if let Some(w) = world {
            for n in w.place_names().into_iter().chain(w.shelf_names()) {
                if let Some((_, x, y, yaw)) = w.place_pose(n) {
                    places.insert(n.to_owned(), (x, y, yaw));
                }
            }
        }
        for (n, p) in &parsed.places {
            if let Some(field) = [("x", p.x), ("y", p.y), ("yaw", p.yaw)]
                .into_iter()
                .find_map(|(field, v)| (!v.is_finite()).then_some(field))
            {
                return Err(error(
                    &["places", n, field],
                    format!("places.{n}: x, y and yaw must be numbers"),
                ));
            }
            places.insert(n.clone(), (p.x, p.y, p.yaw.to_radians()));
        }
        Ok(Interface {
            robot_name: parsed
                .robot_name
                .or_else(|| world.map(|w| w.robot_name().to_owned()))
                .unwrap_or_else(|| "Robot".into()),
            user_name: parsed
                .user_name
                .or_else(|| world.map(|w| w.user_name().to_owned()))
                .unwrap_or_else(|| "User".into()),
            topics: parsed.topics,
            actions: parsed.actions,
            services: parsed.services,
            frames: parsed.frames,
            qos: parsed.qos,
            timeouts: parsed.timeouts,
            places,
        })
    }

    /// A timeout of `[timeouts]` as a duration.
    pub fn secs(seconds: f64) -> Duration {
        Duration::from_secs_f64(seconds.max(0.0))
    }
}

/// The byte offset of the value at `path` (`["timeouts", "answer"]`) in
/// `text`, read as TOML; `None` if there is none or the text does not read.
fn value_at(text: &str, path: &[&str]) -> Option<usize> {
    use toml::de::{DeTable, DeValue};
    let doc = DeTable::parse(text).ok()?;
    let (last, parents) = path.split_last()?;
    let mut table = doc.get_ref();
    for key in parents {
        match table.get(*key)?.get_ref() {
            DeValue::Table(t) => table = t,
            _ => return None,
        }
    }
    Some(table.get(*last)?.span().start)
}

/// 1-based line and column (in characters) of byte offset `at` in `text`.
fn line_col(text: &str, at: usize) -> (usize, usize) {
    let mut at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn defaults_and_overrides() {
        let i = Interface::load(None, None).unwrap();
        assert_eq!(i.topics.say, "/sitlog/say");
        assert_eq!(i.actions.navigate, "/navigate_to_pose");
        assert_eq!(i.qos.say, Qos::new("reliable", "transient_local", 50));
        assert_eq!(i.robot_name, "Robot");
        let text = "robot_name = \"Tiago\"\n[topics]\nsay = \"/tts\"\n[places.kitchen]\nx = 1.0\ny = 2.0\nyaw = 90.0\n";
        let i = Interface::load(Some(("ros2.toml", text)), None).unwrap();
        assert_eq!(i.robot_name, "Tiago");
        assert_eq!(i.topics.say, "/tts");
        assert_eq!(i.topics.heard, "/sitlog/heard");
        let (x, y, yaw) = i.places["kitchen"];
        assert_eq!((x, y), (1.0, 2.0));
        assert!((yaw - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }

    #[test]
    fn errors_name_the_file_and_the_place() {
        let e = Interface::load(Some(("r.toml", "[topics]\nsai = \"/x\"\n")), None).unwrap_err();
        assert!(
            e.starts_with("r.toml:2:1: error: unknown field `sai`"),
            "{e}"
        );
        assert!(!e.contains('\n'), "{e}");
        let e = Interface::load(Some(("r.toml", "[timeouts]\nanswer = -1.0\n")), None).unwrap_err();
        assert!(e.starts_with("r.toml:2:10: error: timeouts.answer"), "{e}");
        let text =
            "[qos.heard]\nreliability = \"reliable\"\ndurability = \"volatile\"\ndepth = 0\n";
        let e = Interface::load(Some(("r.toml", text)), None).unwrap_err();
        assert!(e.starts_with("r.toml:4:9: error: qos.heard:"), "{e}");
        let e =
            Interface::load(Some(("r.toml", "[places.k]\nx = 1\ny = nan\n")), None).unwrap_err();
        assert!(e.starts_with("r.toml:3:5: error: places.k:"), "{e}");
        let e = Interface::load(Some(("r.toml", "qos = 3\n")), None).unwrap_err();
        assert!(e.starts_with("r.toml:1:7: error: "), "{e}");
    }

    /// Pieces of text shaped like a `ros2.toml` (and like what it must refuse).
    const PIECES: &[&str] = &[
        "robot_name",
        "[topics]",
        "[actions]",
        "[services]",
        "[frames]",
        "[qos.say]",
        "[qos.heard]",
        "[timeouts]",
        "[places.kitchen]",
        "[places.\"a b\"]",
        "say",
        "navigate",
        "answer",
        "speech",
        "reliability",
        "durability",
        "depth",
        "x",
        "y",
        "yaw",
        " = ",
        "=",
        "\"reliable\"",
        "\"volatile\"",
        "\"/tts\"",
        "0",
        "-1",
        "5.0",
        "1e6",
        "1e7",
        "1e308",
        "inf",
        "-inf",
        "nan",
        "2147483648",
        "true",
        "\"",
        "'",
        "[",
        "]",
        "{",
        "}",
        ",",
        ".",
        "#",
        " ",
        "\n",
        "\r\n",
        "é",
        "\u{2028}",
    ];

    /// The home world of `sitlog-sim`'s tests (places and shelves to pose).
    fn home() -> World {
        let text = include_str!("../../sim/tests/worlds/home.toml");
        World::parse("home.toml", text).expect("the home world reads")
    }

    /// The invariant on `text`: one line `ros2.toml:LINE:COL: error: ...`
    /// whose place is in `text` (`ros2.toml: error: ...` without one), or a complete
    /// interface (every timeout finite and in range, every QoS valid,
    /// every place's pose finite).
    fn complete_or_refused(text: &str, world: Option<&World>) -> Result<(), TestCaseError> {
        match Interface::load(Some(("ros2.toml", text)), world) {
            Err(e) => {
                prop_assert!(!e.contains('\n'), "{e:?}");
                let rest = e.strip_prefix("ros2.toml:");
                prop_assert!(rest.is_some(), "{e:?}");
                let rest = rest.unwrap_or_default();
                if !rest.starts_with(" error: ") {
                    let mut parts = rest.splitn(3, ':');
                    let line: usize = parts.next().unwrap_or("").parse().unwrap_or(0);
                    let col: usize = parts.next().unwrap_or("").parse().unwrap_or(0);
                    prop_assert!(
                        parts.next().is_some_and(|m| m.starts_with(" error: ")),
                        "{e:?}"
                    );
                    let lines: Vec<&str> = text.split('\n').collect();
                    prop_assert!(line >= 1 && line <= lines.len(), "{e:?}");
                    let chars = lines[line - 1].chars().count();
                    prop_assert!(col >= 1 && col <= chars + 1, "{e:?}");
                }
            }
            Ok(i) => {
                let t = &i.timeouts;
                for v in [t.discovery, t.answer, t.navigate, t.action, t.speech] {
                    prop_assert!(v.is_finite() && (0.0..=1.0e6).contains(&v), "{t:?}");
                    Interface::secs(v);
                }
                let q = &i.qos;
                for q in [
                    &q.say,
                    &q.listening,
                    &q.heard,
                    &q.screen,
                    &q.message,
                    &q.run,
                    &q.abort,
                ] {
                    prop_assert!((1..=10_000).contains(&q.depth), "{q:?}");
                }
                for (x, y, yaw) in i.places.values() {
                    prop_assert!(
                        x.is_finite() && y.is_finite() && yaw.is_finite(),
                        "{:?}",
                        i.places
                    );
                }
            }
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn any_text_is_an_interface_or_an_error(text in any::<String>()) {
            complete_or_refused(&text, None)?;
        }

        #[test]
        fn interface_shaped_text_is_an_interface_or_an_error(
            parts in prop::collection::vec(prop::sample::select(PIECES), 0..32)
        ) {
            let text = parts.concat();
            complete_or_refused(&text, None)?;
            complete_or_refused(&text, Some(&home()))?;
        }
    }
}
