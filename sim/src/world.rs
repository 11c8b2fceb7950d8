//! The world file: reading, checking and the validated [`World`].
//!
//! Owns the translation from `world.toml` text to a [`World`] whose every name
//! resolves. Invariant: a `World` that exists is consistent (every place, shelf,
//! object and utterance it names is defined, every number is finite and in
//! range, the objects of each shelf fit on its board without overlapping), so
//! [`crate::Sim`] never has to check it again. Reading never panics: TOML syntax
//! errors, unknown keys, wrong types and bad names all come back as
//! [`WorldError`]s, as many as can be found, sorted by position.
//!
//! The reader walks toml's span-keeping [`toml::de::DeTable`] by hand rather
//! than going through `serde::Deserialize`: serde stops at the first error,
//! and we want all of them, each at the line and column of the key or value
//! it is about.

use std::collections::BTreeMap;
use std::fmt;

use nalgebra::{Point2, Vector2, Vector3};
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// Default robot speed (m/s).
pub const DEFAULT_SPEED: f64 = 0.5;
/// Default shelf size: width, depth, height of its top board (m).
pub const DEFAULT_SHELF_SIZE: [f64; 3] = [0.8, 0.4, 0.8];
/// Default object size: width, depth, height (m).
pub const DEFAULT_OBJECT_SIZE: [f64; 3] = [0.07, 0.07, 0.15];
/// Default wall height (m).
pub const DEFAULT_WALL_HEIGHT: f64 = 2.5;
/// Default wall thickness (m).
pub const DEFAULT_WALL_THICKNESS: f64 = 0.1;
/// Coordinates must lie within this many metres of the origin.
pub const MAX_COORDINATE: f64 = 10_000.0;
/// Smallest size of anything (m).
pub const MIN_SIZE: f64 = 0.001;
/// Largest size of anything (m).
pub const MAX_SIZE: f64 = 100.0;

/// One problem in a world file: where it is and what is wrong.
///
/// `line` and `column` are 1-based (columns count characters). An error that
/// has no position in the text (the file cannot be read) has line and column
/// 0 and displays as `FILE: error: MESSAGE`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WorldError {
    pub file: String,
    pub line: usize,
    pub column: usize,
    pub message: String,
}

impl fmt::Display for WorldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}: error: {}", self.file, self.message)
        } else {
            write!(
                f,
                "{}:{}:{}: error: {}",
                self.file, self.line, self.column, self.message
            )
        }
    }
}

impl std::error::Error for WorldError {}

/// A parsed, validated world file (see the crate documentation for its keys).
#[derive(Clone, Debug)]
pub struct World {
    pub(crate) file: String,
    pub(crate) seed: Option<u64>,
    pub(crate) robot: RobotSpec,
    pub(crate) user: UserSpec,
    pub(crate) places: Vec<PlaceSpec>,
    /// `None`: no `[[route]]` at all, every pair of places is joined.
    pub(crate) routes: Option<Vec<RouteSpec>>,
    pub(crate) walls: Vec<WallSpec>,
    pub(crate) shelves: Vec<ShelfSpec>,
    pub(crate) objects: Vec<ObjectSpec>,
    pub(crate) faults: Vec<Fault>,
}

#[derive(Clone, Debug)]
pub(crate) struct RobotSpec {
    pub name: String,
    pub at: usize,
    pub speed: f64,
}

#[derive(Clone, Debug)]
pub(crate) struct UserSpec {
    pub name: String,
    pub at: usize,
    pub says: Vec<String>,
    pub moves: Vec<UserMove>,
}

#[derive(Clone, Debug)]
pub(crate) struct UserMove {
    pub trigger: Trigger,
    pub delay: f64,
    pub to: usize,
}

#[derive(Clone, Copy, Debug)]
pub(crate) enum Trigger {
    /// 1-based index of an utterance.
    AfterSaying(usize),
    /// Absolute simulated seconds.
    AtTime(f64),
}

#[derive(Clone, Debug)]
pub(crate) struct PlaceSpec {
    pub name: String,
    pub pos: Point2<f64>,
    pub room: String,
    /// Radians.
    pub heading: f64,
}

#[derive(Clone, Debug)]
pub(crate) struct RouteSpec {
    pub from: usize,
    pub to: usize,
    pub length: f64,
}

#[derive(Clone, Debug)]
pub(crate) struct WallSpec {
    pub from: Point2<f64>,
    pub to: Point2<f64>,
    pub height: f64,
    pub thickness: f64,
}

#[derive(Clone, Debug)]
pub(crate) struct ShelfSpec {
    pub name: String,
    pub place: usize,
    /// Width (across), depth, height of the top board's upper face.
    pub size: Vector3<f64>,
}

#[derive(Clone, Debug)]
pub(crate) struct ObjectSpec {
    pub name: String,
    pub shelf: usize,
    /// Width (across), depth, height.
    pub size: Vector3<f64>,
    /// Centre on the board: across (+ = the robot's right), depth (+ = away).
    pub spot: Vector2<f64>,
}

#[derive(Clone, Debug)]
pub(crate) enum Fault {
    GraspFails {
        object: usize,
        times: u32,
    },
    RouteBlocked {
        a: usize,
        b: usize,
    },
    /// 0-based utterance index.
    Mishear {
        utterance: usize,
    },
}

impl World {
    /// Reads and checks a world file's text. `file_name` only labels errors.
    pub fn parse(file_name: &str, text: &str) -> Result<World, Vec<WorldError>> {
        let mut cx = Cx::new(file_name, text);
        let (doc, syntax) = DeTable::parse_recoverable(text);
        // Only the first syntax error: the parser's recovery after it often
        // reports errors that are not there (a `duplicate key` further down).
        if let Some(e) = syntax.first() {
            let at = e.span().map(|s| s.start).unwrap_or(0);
            cx.err(at, format!("not valid TOML: {}", e.message()));
            return Err(cx.finish());
        }
        let world = read_world(&mut cx, &doc);
        match world {
            Some(w) if cx.errors.is_empty() => Ok(w),
            _ => Err(cx.finish()),
        }
    }

    /// Reads and checks a world file. A file that cannot be read is an error
    /// without position; text that is not UTF-8 is an error at the first bad
    /// byte.
    pub fn load(path: &std::path::Path) -> Result<World, Vec<WorldError>> {
        let file = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| {
            vec![WorldError {
                file: file.clone(),
                line: 0,
                column: 0,
                message: format!("cannot read the world file: {e}"),
            }]
        })?;
        let text = Self::text_of(&file, &bytes)?;
        Self::parse(&file, text)
    }

    /// The bytes of a world file as text, or an error at the first byte that
    /// is not UTF-8.
    pub fn text_of<'b>(file_name: &str, bytes: &'b [u8]) -> Result<&'b str, Vec<WorldError>> {
        sitlog_syntax::decode(bytes).map_err(|e| {
            vec![WorldError {
                file: file_name.to_string(),
                line: e.line,
                column: e.column,
                message: e.message,
            }]
        })
    }

    /// The file name the world was read under.
    pub fn file_name(&self) -> &str {
        &self.file
    }

    /// The file's `seed`, if it gives one.
    pub fn seed(&self) -> Option<u64> {
        self.seed
    }

    /// `[robot] name`.
    pub fn robot_name(&self) -> &str {
        &self.robot.name
    }

    /// `[user] name`.
    pub fn user_name(&self) -> &str {
        &self.user.name
    }

    /// The robot's speed (m/s).
    pub fn robot_speed(&self) -> f64 {
        self.robot.speed
    }

    /// What the user will say, in order.
    pub fn utterances(&self) -> Vec<&str> {
        self.user.says.iter().map(String::as_str).collect()
    }

    /// The places in file order.
    pub fn place_names(&self) -> Vec<&str> {
        self.places.iter().map(|p| p.name.as_str()).collect()
    }

    /// The rooms, each once, in order of first mention.
    pub fn room_names(&self) -> Vec<&str> {
        let mut rooms: Vec<&str> = Vec::new();
        for p in &self.places {
            if !rooms.contains(&p.room.as_str()) {
                rooms.push(&p.room);
            }
        }
        rooms
    }

    /// The shelves in file order.
    pub fn shelf_names(&self) -> Vec<&str> {
        self.shelves.iter().map(|s| s.name.as_str()).collect()
    }

    /// The objects in file order.
    pub fn object_names(&self) -> Vec<&str> {
        self.objects.iter().map(|o| o.name.as_str()).collect()
    }

    /// The shelf an object stands on when the world starts.
    pub fn initial_shelf(&self, object: &str) -> Option<&str> {
        self.objects
            .iter()
            .find(|o| o.name == object)
            .map(|o| self.shelves[o.shelf].name.as_str())
    }

    pub(crate) fn place_index(&self, name: &str) -> Option<usize> {
        self.places.iter().position(|p| p.name == name)
    }

    pub(crate) fn shelf_index(&self, name: &str) -> Option<usize> {
        self.shelves.iter().position(|s| s.name == name)
    }

    pub(crate) fn object_index(&self, name: &str) -> Option<usize> {
        self.objects.iter().position(|o| o.name == name)
    }
}

/// 1-based line and column (in characters) of byte offset `at` in `text`.
pub(crate) fn line_col(text: &str, at: usize) -> (usize, usize) {
    let mut at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map(|i| i + 1).unwrap_or(0);
    let column = before[start..].chars().count() + 1;
    (line, column)
}

/// The error collector.
struct Cx<'t> {
    file: String,
    text: &'t str,
    errors: Vec<(usize, String)>,
}

impl<'t> Cx<'t> {
    fn new(file: &str, text: &'t str) -> Self {
        Cx {
            file: file.to_string(),
            text,
            errors: Vec::new(),
        }
    }

    fn err(&mut self, at: usize, message: String) {
        self.errors.push((at, message));
    }

    fn pos(&self, at: usize) -> String {
        let (l, c) = line_col(self.text, at);
        format!("{l}:{c}")
    }

    fn finish(mut self) -> Vec<WorldError> {
        self.errors.sort();
        self.errors.dedup();
        self.errors
            .into_iter()
            .map(|(at, message)| {
                let (line, column) = line_col(self.text, at);
                WorldError {
                    file: self.file.clone(),
                    line,
                    column,
                    message,
                }
            })
            .collect()
    }
}

/// A value with the byte offset it starts at.
#[derive(Clone, Debug)]
struct At<T> {
    v: T,
    at: usize,
}

type Val<'i> = Spanned<DeValue<'i>>;

/// A table being read: its entries, where its header is, how to name it.
struct Tbl<'a, 'i> {
    t: &'a DeTable<'i>,
    at: usize,
    label: String,
}

fn what(v: &DeValue<'_>) -> &'static str {
    match v {
        DeValue::String(_) => "a string",
        DeValue::Integer(_) => "an integer",
        DeValue::Float(_) => "a float",
        DeValue::Boolean(_) => "a boolean",
        DeValue::Datetime(_) => "a date-time",
        DeValue::Array(_) => "an array",
        DeValue::Table(_) => "a table",
    }
}

fn int_of(v: &DeValue<'_>) -> Option<Option<i64>> {
    match v {
        DeValue::Integer(i) => Some(i64::from_str_radix(i.as_str(), i.radix()).ok()),
        _ => None,
    }
}

fn num_of(v: &DeValue<'_>) -> Option<f64> {
    match v {
        DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
            Ok(n) => Some(n as f64),
            // Too big for i64: as a float it is out of every range anyway.
            Err(_) => Some(f64::INFINITY),
        },
        DeValue::Float(x) => Some(x.as_str().parse::<f64>().unwrap_or(f64::NAN)),
        _ => None,
    }
}

impl<'t> Cx<'t> {
    fn table<'a, 'i>(&mut self, v: &'a Val<'i>, label: &str) -> Option<Tbl<'a, 'i>> {
        match v.get_ref() {
            DeValue::Table(t) => Some(Tbl {
                t,
                at: v.span().start,
                label: label.to_string(),
            }),
            other => {
                self.err(
                    v.span().start,
                    format!("{label} must be a table, found {}", what(other)),
                );
                None
            }
        }
    }

    /// The tables of an array of tables (`[[key]]`).
    fn tables<'a, 'i>(&mut self, v: &'a Val<'i>, label: &str) -> Vec<Tbl<'a, 'i>> {
        match v.get_ref() {
            DeValue::Array(items) => items
                .iter()
                .filter_map(|item| self.table(item, label))
                .collect(),
            other => {
                self.err(
                    v.span().start,
                    format!(
                        "{label} must be an array of tables (write `{label}` headers), found {}",
                        what(other)
                    ),
                );
                Vec::new()
            }
        }
    }

    fn keys(&mut self, t: &Tbl<'_, '_>, allowed: &[&str]) {
        for (k, _) in t.t.iter() {
            if !allowed.contains(&k.get_ref().as_ref()) {
                self.err(
                    k.span().start,
                    format!(
                        "unknown key `{}` in {}; known keys: {}",
                        k.get_ref(),
                        t.label,
                        allowed.join(", ")
                    ),
                );
            }
        }
    }

    fn get<'a, 'i>(t: &Tbl<'a, 'i>, key: &str) -> Option<&'a Val<'i>> {
        t.t.get(key)
    }

    fn req<'a, 'i>(&mut self, t: &Tbl<'a, 'i>, key: &str) -> Option<&'a Val<'i>> {
        let v = t.t.get(key);
        if v.is_none() {
            self.err(t.at, format!("missing key `{key}` in {}", t.label));
        }
        v
    }

    fn string(&mut self, t: &Tbl<'_, '_>, key: &str, v: &Val<'_>) -> Option<At<String>> {
        match v.get_ref() {
            DeValue::String(s) => Some(At {
                v: s.to_string(),
                at: v.span().start,
            }),
            other => {
                self.err(
                    v.span().start,
                    format!(
                        "`{key}` in {} must be a string, found {}",
                        t.label,
                        what(other)
                    ),
                );
                None
            }
        }
    }

    /// A required, non-empty name.
    fn name(&mut self, t: &Tbl<'_, '_>, key: &str) -> Option<At<String>> {
        let v = self.req(t, key)?;
        let s = self.string(t, key, v)?;
        if s.v.trim().is_empty() {
            self.err(s.at, format!("`{key}` in {} must not be empty", t.label));
            return None;
        }
        Some(s)
    }

    fn number(&mut self, t: &Tbl<'_, '_>, key: &str, v: &Val<'_>) -> Option<At<f64>> {
        match num_of(v.get_ref()) {
            Some(x) => Some(At {
                v: x,
                at: v.span().start,
            }),
            None => {
                self.err(
                    v.span().start,
                    format!(
                        "`{key}` in {} must be a number, found {}",
                        t.label,
                        what(v.get_ref())
                    ),
                );
                None
            }
        }
    }

    /// A number that must lie in `lo..=hi` (`lo` excluded when `open_lo`).
    fn ranged(
        &mut self,
        t: &Tbl<'_, '_>,
        key: &str,
        v: &Val<'_>,
        lo: f64,
        hi: f64,
        open_lo: bool,
    ) -> Option<f64> {
        let x = self.number(t, key, v)?;
        let ok = x.v.is_finite() && (if open_lo { x.v > lo } else { x.v >= lo }) && x.v <= hi;
        if ok {
            Some(x.v)
        } else {
            let lower = if open_lo {
                format!("greater than {lo}")
            } else {
                format!("at least {lo}")
            };
            self.err(
                x.at,
                format!(
                    "`{key}` in {} must be a finite number {lower} and at most {hi}, found {}",
                    t.label,
                    show_num(x.v)
                ),
            );
            None
        }
    }

    fn coordinate(&mut self, t: &Tbl<'_, '_>, key: &str, v: &Val<'_>) -> Option<f64> {
        self.ranged(t, key, v, -MAX_COORDINATE, MAX_COORDINATE, false)
    }

    fn integer(&mut self, t: &Tbl<'_, '_>, key: &str, v: &Val<'_>, lo: i64) -> Option<At<i64>> {
        match int_of(v.get_ref()) {
            Some(Some(n)) if n >= lo => Some(At {
                v: n,
                at: v.span().start,
            }),
            Some(n) => {
                let found = match n {
                    Some(n) => n.to_string(),
                    None => "a number too big".to_string(),
                };
                let least = if lo == i64::MIN {
                    String::new()
                } else {
                    format!(" of at least {lo}")
                };
                self.err(
                    v.span().start,
                    format!(
                        "`{key}` in {} must be an integer{least}, found {found}",
                        t.label
                    ),
                );
                None
            }
            None => {
                self.err(
                    v.span().start,
                    format!(
                        "`{key}` in {} must be an integer, found {}",
                        t.label,
                        what(v.get_ref())
                    ),
                );
                None
            }
        }
    }

    /// An array of exactly `N` numbers, each checked by `check`.
    fn numbers<const N: usize>(
        &mut self,
        t: &Tbl<'_, '_>,
        key: &str,
        v: &Val<'_>,
        lo: f64,
        hi: f64,
        open_lo: bool,
    ) -> Option<[f64; N]> {
        let bad = |cx: &mut Self, found: String| {
            cx.err(
                v.span().start,
                format!(
                    "`{key}` in {} must be an array of {N} numbers, found {found}",
                    t.label
                ),
            );
        };
        let DeValue::Array(items) = v.get_ref() else {
            bad(self, what(v.get_ref()).to_string());
            return None;
        };
        if items.len() != N {
            bad(self, format!("{} items", items.len()));
            return None;
        }
        let mut out = [0.0; N];
        let mut ok = true;
        for (i, item) in items.iter().enumerate() {
            match self.ranged(t, key, item, lo, hi, open_lo) {
                Some(x) => out[i] = x,
                None => ok = false,
            }
        }
        ok.then_some(out)
    }
}

fn show_num(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{x}")
    }
}

// ---------------------------------------------------------------------------
// The raw (unresolved) world, then resolution.

struct RawPlace {
    name: At<String>,
    x: Option<f64>,
    y: Option<f64>,
    room: Option<String>,
    heading: f64,
}

struct RawRoute {
    at: usize,
    from: Option<At<String>>,
    to: Option<At<String>>,
    length: Option<f64>,
}

struct RawShelf {
    name: At<String>,
    at: Option<At<String>>,
    size: [f64; 3],
}

struct RawObject {
    name: At<String>,
    on: Option<At<String>>,
    size: [f64; 3],
    spot: Option<At<[f64; 2]>>,
}

struct RawMove {
    trigger: Option<At<Trigger>>,
    delay: f64,
    to: Option<At<String>>,
}

enum RawFault {
    GraspFails {
        object: At<String>,
        times: u32,
    },
    RouteBlocked {
        at: usize,
        from: At<String>,
        to: At<String>,
    },
    Mishear {
        utterance: At<Utterance>,
    },
}

enum Utterance {
    Index(i64),
    Text(String),
}

const ROOT_KEYS: &[&str] = &[
    "seed", "robot", "user", "place", "route", "wall", "shelf", "object", "fault",
];

fn read_world(cx: &mut Cx<'_>, doc: &Spanned<DeTable<'_>>) -> Option<World> {
    let root = Tbl {
        t: doc.get_ref(),
        at: 0,
        label: "the world file".to_string(),
    };
    cx.keys(&root, ROOT_KEYS);

    let seed = match Cx::get(&root, "seed") {
        Some(v) => cx.integer(&root, "seed", v, 0).map(|n| n.v as u64),
        None => None,
    };

    // [robot]
    let robot = cx.req(&root, "robot").and_then(|v| cx.table(v, "[robot]"));
    let (mut robot_name, mut robot_at, mut speed) = (None, None, DEFAULT_SPEED);
    if let Some(t) = &robot {
        cx.keys(t, &["name", "at", "speed"]);
        robot_name = cx.name(t, "name");
        robot_at = cx.name(t, "at");
        if let Some(v) = Cx::get(t, "speed") {
            speed = cx
                .ranged(t, "speed", v, 0.0, MAX_SIZE, true)
                .unwrap_or(speed);
        }
    }

    // [user]
    let user = cx.req(&root, "user").and_then(|v| cx.table(v, "[user]"));
    let (mut user_name, mut user_at, mut says, mut raw_moves) =
        (None, None, Vec::new(), Vec::new());
    if let Some(t) = &user {
        cx.keys(t, &["name", "at", "says", "moves"]);
        user_name = cx.name(t, "name");
        user_at = cx.name(t, "at");
        if let Some(v) = Cx::get(t, "says") {
            match v.get_ref() {
                DeValue::Array(items) => {
                    for item in items.iter() {
                        if let Some(s) = cx.string(t, "says", item) {
                            says.push(s.v);
                        }
                    }
                }
                other => cx.err(
                    v.span().start,
                    format!(
                        "`says` in [user] must be an array of strings, found {}",
                        what(other)
                    ),
                ),
            }
        }
        if let Some(v) = Cx::get(t, "moves") {
            for m in cx.tables(v, "[[user.moves]]") {
                raw_moves.push(read_move(cx, &m));
            }
        }
    }

    // [[place]]
    let mut places: Vec<RawPlace> = Vec::new();
    if let Some(v) = Cx::get(&root, "place") {
        for t in cx.tables(v, "[[place]]") {
            cx.keys(&t, &["name", "x", "y", "room", "heading"]);
            let name = cx.name(&t, "name");
            let x = cx.req(&t, "x").and_then(|v| cx.coordinate(&t, "x", v));
            let y = cx.req(&t, "y").and_then(|v| cx.coordinate(&t, "y", v));
            let room = Cx::get(&t, "room").and_then(|v| cx.string(&t, "room", v));
            if let Some(r) = &room {
                if r.v.trim().is_empty() {
                    cx.err(r.at, "`room` in [[place]] must not be empty".into());
                }
            }
            let heading = Cx::get(&t, "heading")
                .and_then(|v| cx.ranged(&t, "heading", v, -3600.0, 3600.0, false))
                .unwrap_or(0.0);
            if let Some(name) = name {
                places.push(RawPlace {
                    name,
                    x,
                    y,
                    room: room.map(|r| r.v),
                    heading,
                });
            }
        }
    }

    // [[route]]
    let mut routes: Option<Vec<RawRoute>> = None;
    if let Some(v) = Cx::get(&root, "route") {
        let mut list = Vec::new();
        for t in cx.tables(v, "[[route]]") {
            cx.keys(&t, &["from", "to", "length"]);
            let from = cx.name(&t, "from");
            let to = cx.name(&t, "to");
            let length =
                Cx::get(&t, "length").and_then(|v| cx.ranged(&t, "length", v, 0.0, 1e6, true));
            list.push(RawRoute {
                at: t.at,
                from,
                to,
                length,
            });
        }
        routes = Some(list);
    }

    // [[wall]]
    let mut walls = Vec::new();
    if let Some(v) = Cx::get(&root, "wall") {
        for t in cx.tables(v, "[[wall]]") {
            cx.keys(&t, &["from", "to", "height", "thickness"]);
            let c = MAX_COORDINATE;
            let from = cx
                .req(&t, "from")
                .and_then(|v| cx.numbers::<2>(&t, "from", v, -c, c, false));
            let to = cx
                .req(&t, "to")
                .and_then(|v| cx.numbers::<2>(&t, "to", v, -c, c, false));
            let height = Cx::get(&t, "height")
                .and_then(|v| cx.ranged(&t, "height", v, MIN_SIZE, MAX_SIZE, false))
                .unwrap_or(DEFAULT_WALL_HEIGHT);
            let thickness = Cx::get(&t, "thickness")
                .and_then(|v| cx.ranged(&t, "thickness", v, MIN_SIZE, MAX_SIZE, false))
                .unwrap_or(DEFAULT_WALL_THICKNESS);
            if let (Some(from), Some(to)) = (from, to) {
                let (a, b) = (Point2::from(from), Point2::from(to));
                if (b - a).norm() < MIN_SIZE {
                    cx.err(
                        t.at,
                        format!(
                            "[[wall]] from [{}, {}] to [{}, {}] has no length",
                            from[0], from[1], to[0], to[1]
                        ),
                    );
                } else {
                    walls.push(WallSpec {
                        from: a,
                        to: b,
                        height,
                        thickness,
                    });
                }
            }
        }
    }

    // [[shelf]]
    let mut shelves: Vec<RawShelf> = Vec::new();
    if let Some(v) = Cx::get(&root, "shelf") {
        for t in cx.tables(v, "[[shelf]]") {
            cx.keys(&t, &["name", "at", "size"]);
            let name = cx.name(&t, "name");
            let at = cx.name(&t, "at");
            let size = match Cx::get(&t, "size") {
                Some(v) => cx.numbers::<3>(&t, "size", v, MIN_SIZE, MAX_SIZE, false),
                None => Some(DEFAULT_SHELF_SIZE),
            };
            // A bad size is reported; the shelf stays so that its objects
            // do not also read as "on a shelf that is not defined".
            if let Some(name) = name {
                let size = size.unwrap_or(DEFAULT_SHELF_SIZE);
                shelves.push(RawShelf { name, at, size });
            }
        }
    }

    // [[object]]
    let mut objects: Vec<RawObject> = Vec::new();
    if let Some(v) = Cx::get(&root, "object") {
        for t in cx.tables(v, "[[object]]") {
            cx.keys(&t, &["name", "on", "size", "spot"]);
            let name = cx.name(&t, "name");
            let on = cx.name(&t, "on");
            let size = match Cx::get(&t, "size") {
                Some(v) => cx.numbers::<3>(&t, "size", v, MIN_SIZE, MAX_SIZE, false),
                None => Some(DEFAULT_OBJECT_SIZE),
            };
            let spot = Cx::get(&t, "spot").and_then(|v| {
                cx.numbers::<2>(&t, "spot", v, -MAX_SIZE, MAX_SIZE, false)
                    .map(|s| At {
                        v: s,
                        at: v.span().start,
                    })
            });
            if let Some(name) = name {
                let size = size.unwrap_or(DEFAULT_OBJECT_SIZE);
                objects.push(RawObject {
                    name,
                    on,
                    size,
                    spot,
                });
            }
        }
    }

    // [[fault]]
    let mut faults = Vec::new();
    if let Some(v) = Cx::get(&root, "fault") {
        for t in cx.tables(v, "[[fault]]") {
            if let Some(f) = read_fault(cx, &t) {
                faults.push(f);
            }
        }
    }

    // ---- resolution -------------------------------------------------------
    let mut place_ix: BTreeMap<String, usize> = BTreeMap::new();
    let mut place_specs = Vec::new();
    let mut place_seen: BTreeMap<String, usize> = BTreeMap::new();
    for p in &places {
        if let Some(&first_at) = place_seen.get(&p.name.v) {
            let pos = cx.pos(first_at);
            cx.err(
                p.name.at,
                format!("place `{}` is defined twice (first at {pos})", p.name.v),
            );
            continue;
        }
        place_seen.insert(p.name.v.clone(), p.name.at);
        place_ix.insert(p.name.v.clone(), place_specs.len());
        place_specs.push(PlaceSpec {
            name: p.name.v.clone(),
            pos: Point2::new(p.x.unwrap_or(0.0), p.y.unwrap_or(0.0)),
            room: p.room.clone().unwrap_or_else(|| p.name.v.clone()),
            heading: p.heading.to_radians(),
        });
    }
    let place = |cx: &mut Cx<'_>, name: &At<String>, what: String| -> Option<usize> {
        match place_ix.get(&name.v) {
            Some(&i) => Some(i),
            None => {
                cx.err(
                    name.at,
                    format!("{what} place `{}`, which is not defined", name.v),
                );
                None
            }
        }
    };

    let robot_at = match (&robot_name, &robot_at) {
        (Some(n), Some(a)) => place(cx, a, format!("robot `{}` is at", n.v)),
        (None, Some(a)) => place(cx, a, "the robot is at".into()),
        _ => None,
    };
    let user_at = match (&user_name, &user_at) {
        (Some(n), Some(a)) => place(cx, a, format!("user `{}` is at", n.v)),
        (None, Some(a)) => place(cx, a, "the user is at".into()),
        _ => None,
    };
    let user_label = user_name
        .as_ref()
        .map(|n| format!("user `{}`", n.v))
        .unwrap_or_else(|| "the user".into());
    let mut moves = Vec::new();
    for m in &raw_moves {
        let to =
            m.to.as_ref()
                .and_then(|to| place(cx, to, format!("{user_label} moves to")));
        if let Some(At {
            v: Trigger::AfterSaying(n),
            at,
        }) = &m.trigger
        {
            if *n > says.len() {
                cx.err(
                    *at,
                    format!(
                        "`after_saying = {n}` in [[user.moves]], but {user_label} says only {} utterance{}",
                        says.len(),
                        if says.len() == 1 { "" } else { "s" }
                    ),
                );
                continue;
            }
        }
        if let (Some(trigger), Some(to)) = (&m.trigger, to) {
            moves.push(UserMove {
                trigger: trigger.v,
                delay: m.delay,
                to,
            });
        }
    }

    let mut route_specs = None;
    if let Some(list) = &routes {
        let mut specs = Vec::new();
        for r in list {
            let from = r
                .from
                .as_ref()
                .and_then(|n| place(cx, n, "[[route]] starts at".into()));
            let to =
                r.to.as_ref()
                    .and_then(|n| place(cx, n, "[[route]] goes to".into()));
            if let (Some(a), Some(b)) = (from, to) {
                if a == b {
                    cx.err(
                        r.at,
                        format!("[[route]] from `{}` to itself", place_specs[a].name),
                    );
                    continue;
                }
                let length = r
                    .length
                    .unwrap_or_else(|| (place_specs[a].pos - place_specs[b].pos).norm());
                if length <= 0.0 {
                    cx.err(
                        r.at,
                        format!(
                            "[[route]] from `{}` to `{}` has length 0 (the places coincide); give a `length`",
                            place_specs[a].name, place_specs[b].name
                        ),
                    );
                    continue;
                }
                specs.push(RouteSpec {
                    from: a,
                    to: b,
                    length,
                });
            }
        }
        route_specs = Some(specs);
    }

    let mut shelf_ix: BTreeMap<String, usize> = BTreeMap::new();
    let mut shelf_at_place: BTreeMap<usize, (String, usize)> = BTreeMap::new();
    let mut shelf_specs: Vec<ShelfSpec> = Vec::new();
    let mut shelf_seen: BTreeMap<String, usize> = BTreeMap::new();
    for s in &shelves {
        if let Some(&first_at) = shelf_seen.get(&s.name.v) {
            let pos = cx.pos(first_at);
            cx.err(
                s.name.at,
                format!("shelf `{}` is defined twice (first at {pos})", s.name.v),
            );
            continue;
        }
        shelf_seen.insert(s.name.v.clone(), s.name.at);
        let Some(at) = &s.at else { continue };
        let Some(p) = place(cx, at, format!("shelf `{}` is at", s.name.v)) else {
            continue;
        };
        if let Some((other, _)) = shelf_at_place.get(&p) {
            cx.err(
                at.at,
                format!(
                    "shelf `{}` is at place `{}`, which already has shelf `{other}`",
                    s.name.v, at.v
                ),
            );
            continue;
        }
        shelf_at_place.insert(p, (s.name.v.clone(), shelf_specs.len()));
        shelf_ix.insert(s.name.v.clone(), shelf_specs.len());
        shelf_specs.push(ShelfSpec {
            name: s.name.v.clone(),
            place: p,
            size: Vector3::from(s.size),
        });
    }
    let shelf_names_all: Vec<&str> = shelves.iter().map(|s| s.name.v.as_str()).collect();

    let mut object_ix: BTreeMap<String, usize> = BTreeMap::new();
    let mut object_specs: Vec<ObjectSpec> = Vec::new();
    let mut explicit: Vec<bool> = Vec::new();
    let mut object_at: Vec<usize> = Vec::new();
    let mut object_seen: BTreeMap<String, usize> = BTreeMap::new();
    for o in &objects {
        if let Some(&first_at) = object_seen.get(&o.name.v) {
            let pos = cx.pos(first_at);
            cx.err(
                o.name.at,
                format!("object `{}` is defined twice (first at {pos})", o.name.v),
            );
            continue;
        }
        object_seen.insert(o.name.v.clone(), o.name.at);
        let Some(on) = &o.on else { continue };
        let Some(&s) = shelf_ix.get(&on.v) else {
            // A shelf that was defined but dropped for another error is not
            // "not defined": say nothing more about it.
            if !shelf_names_all.contains(&on.v.as_str()) {
                cx.err(
                    on.at,
                    format!(
                        "object `{}` is on shelf `{}`, which is not defined",
                        o.name.v, on.v
                    ),
                );
            }
            continue;
        };
        object_ix.insert(o.name.v.clone(), object_specs.len());
        explicit.push(o.spot.is_some());
        object_at.push(o.spot.as_ref().map(|s| s.at).unwrap_or(o.name.at));
        object_specs.push(ObjectSpec {
            name: o.name.v.clone(),
            shelf: s,
            size: Vector3::from(o.size),
            spot: o
                .spot
                .as_ref()
                .map(|s| Vector2::from(s.v))
                .unwrap_or_else(Vector2::zeros),
        });
    }
    layout(cx, &shelf_specs, &mut object_specs, &explicit, &object_at);

    let mut fault_specs = Vec::new();
    for f in &faults {
        match f {
            RawFault::GraspFails { object, times } => match object_ix.get(&object.v) {
                Some(&o) => fault_specs.push(Fault::GraspFails {
                    object: o,
                    times: *times,
                }),
                None => {
                    if !objects.iter().any(|x| x.name.v == object.v) {
                        cx.err(
                            object.at,
                            format!(
                                "fault `grasp_fails` names object `{}`, which is not defined",
                                object.v
                            ),
                        )
                    }
                }
            },
            RawFault::RouteBlocked { at, from, to } => {
                let a = place(cx, from, "fault `route_blocked` starts at".into());
                let b = place(cx, to, "fault `route_blocked` goes to".into());
                if let (Some(a), Some(b)) = (a, b) {
                    if a == b {
                        cx.err(
                            *at,
                            format!(
                                "fault `route_blocked` from `{}` to itself",
                                place_specs[a].name
                            ),
                        );
                        continue;
                    }
                    if let Some(specs) = &route_specs {
                        let exists = specs
                            .iter()
                            .any(|r| (r.from, r.to) == (a, b) || (r.from, r.to) == (b, a));
                        if !exists {
                            cx.err(
                                *at,
                                format!(
                                    "fault `route_blocked`: there is no [[route]] between `{}` and `{}` to block",
                                    place_specs[a].name, place_specs[b].name
                                ),
                            );
                            continue;
                        }
                    }
                    fault_specs.push(Fault::RouteBlocked { a, b });
                }
            }
            RawFault::Mishear { utterance } => match &utterance.v {
                Utterance::Index(n) => {
                    if *n < 1 || *n as u64 > says.len() as u64 {
                        cx.err(
                            utterance.at,
                            format!(
                                "fault `mishear` names utterance {n}, but {user_label} says {} utterance{} (counting from 1)",
                                says.len(),
                                if says.len() == 1 { "" } else { "s" }
                            ),
                        );
                    } else {
                        fault_specs.push(Fault::Mishear {
                            utterance: *n as usize - 1,
                        });
                    }
                }
                Utterance::Text(text) => match says.iter().position(|s| s == text) {
                    Some(i) => fault_specs.push(Fault::Mishear { utterance: i }),
                    None => cx.err(
                        utterance.at,
                        format!(
                            "fault `mishear` names utterance {text:?}, which {user_label} never says"
                        ),
                    ),
                },
            },
        }
    }

    Some(World {
        file: cx.file.clone(),
        seed,
        robot: RobotSpec {
            name: robot_name?.v,
            at: robot_at?,
            speed,
        },
        user: UserSpec {
            name: user_name?.v,
            at: user_at?,
            says,
            moves,
        },
        places: place_specs,
        routes: route_specs,
        walls,
        shelves: shelf_specs,
        objects: object_specs,
        faults: fault_specs,
    })
}

fn read_move(cx: &mut Cx<'_>, t: &Tbl<'_, '_>) -> RawMove {
    cx.keys(t, &["after_saying", "at_time", "delay", "to"]);
    let to = cx.name(t, "to");
    let delay = Cx::get(t, "delay")
        .and_then(|v| cx.ranged(t, "delay", v, 0.0, 1e9, false))
        .unwrap_or(0.0);
    let after = Cx::get(t, "after_saying");
    let at_time = Cx::get(t, "at_time");
    let trigger = match (after, at_time) {
        (Some(_), Some(v)) => {
            cx.err(
                v.span().start,
                "[[user.moves]] has both `after_saying` and `at_time`; give one".into(),
            );
            None
        }
        (None, None) => {
            cx.err(
                t.at,
                "missing key `after_saying` or `at_time` in [[user.moves]]".into(),
            );
            None
        }
        (Some(v), None) => cx.integer(t, "after_saying", v, 1).map(|n| At {
            v: Trigger::AfterSaying(n.v as usize),
            at: n.at,
        }),
        (None, Some(v)) => cx.ranged(t, "at_time", v, 0.0, 1e9, false).map(|x| At {
            v: Trigger::AtTime(x),
            at: v.span().start,
        }),
    };
    RawMove { trigger, delay, to }
}

const FAULT_KINDS: &str = "grasp_fails, route_blocked, mishear";

fn read_fault(cx: &mut Cx<'_>, t: &Tbl<'_, '_>) -> Option<RawFault> {
    let kind = cx.name(t, "kind");
    let Some(kind) = kind else {
        // Without a kind the other keys cannot be checked.
        return None;
    };
    let mut t2 = Tbl {
        t: t.t,
        at: t.at,
        label: format!("[[fault]] of kind `{}`", kind.v),
    };
    match kind.v.as_str() {
        "grasp_fails" => {
            cx.keys(&t2, &["kind", "object", "times"]);
            let object = cx.name(&t2, "object");
            let times = match Cx::get(&t2, "times") {
                Some(v) => cx
                    .integer(&t2, "times", v, 1)
                    .map(|n| n.v.min(u32::MAX as i64) as u32),
                None => Some(1),
            };
            Some(RawFault::GraspFails {
                object: object?,
                times: times?,
            })
        }
        "route_blocked" => {
            cx.keys(&t2, &["kind", "from", "to"]);
            let from = cx.name(&t2, "from");
            let to = cx.name(&t2, "to");
            Some(RawFault::RouteBlocked {
                at: t.at,
                from: from?,
                to: to?,
            })
        }
        "mishear" => {
            cx.keys(&t2, &["kind", "utterance"]);
            let v = cx.req(&t2, "utterance")?;
            let at = v.span().start;
            match v.get_ref() {
                DeValue::String(s) => Some(RawFault::Mishear {
                    utterance: At {
                        v: Utterance::Text(s.to_string()),
                        at,
                    },
                }),
                DeValue::Integer(_) => {
                    let n = cx.integer(&t2, "utterance", v, i64::MIN)?;
                    Some(RawFault::Mishear {
                        utterance: At {
                            v: Utterance::Index(n.v),
                            at,
                        },
                    })
                }
                other => {
                    cx.err(
                        at,
                        format!(
                            "`utterance` in {} must be an integer (counting from 1) or the utterance's text, found {}",
                            t2.label,
                            what(other)
                        ),
                    );
                    None
                }
            }
        }
        other => {
            t2.label = "[[fault]]".into();
            cx.err(
                kind.at,
                format!("unknown fault kind `{other}`; known kinds: {FAULT_KINDS}"),
            );
            None
        }
    }
}

/// Puts the objects of each shelf on its board: those with a `spot` there,
/// the others side by side across the board's width in file order (first =
/// leftmost as the robot sees it), evenly spaced, on the board's middle line.
/// Errors when they do not fit or overlap.
fn layout(
    cx: &mut Cx<'_>,
    shelves: &[ShelfSpec],
    objects: &mut [ObjectSpec],
    explicit: &[bool],
    at: &[usize],
) {
    for (s, shelf) in shelves.iter().enumerate() {
        let (w, d) = (shelf.size.x, shelf.size.y);
        let auto: Vec<usize> = (0..objects.len())
            .filter(|&o| objects[o].shelf == s && !explicit[o])
            .collect();
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
        let on: Vec<usize> = (0..objects.len())
            .filter(|&o| objects[o].shelf == s)
            .collect();
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_counts_characters() {
        let t = "ab\nçd\nxyz";
        assert_eq!(line_col(t, 0), (1, 1));
        assert_eq!(line_col(t, 3), (2, 1));
        assert_eq!(line_col(t, 5), (2, 2));
        assert_eq!(line_col(t, 4), (2, 1)); // inside ç: back to its start
        assert_eq!(line_col(t, 999), (3, 4));
    }

    #[test]
    fn minimal_world() {
        let w = World::parse(
            "w.toml",
            "[robot]\nname = \"G\"\nat = \"a\"\n[user]\nname = \"L\"\nat = \"a\"\n[[place]]\nname = \"a\"\nx = 0\ny = 0\n",
        )
        .unwrap();
        assert_eq!(w.robot_name(), "G");
        assert_eq!(w.place_names(), ["a"]);
        assert_eq!(w.seed(), None);
        assert!(w.routes.is_none());
    }

    #[test]
    fn spread_in_file_order() {
        let w = World::parse(
            "w.toml",
            "[robot]\nname = \"G\"\nat = \"a\"\n[user]\nname = \"L\"\nat = \"a\"\n[[place]]\nname = \"a\"\nx = 0\ny = 0\n\
             [[shelf]]\nname = \"s\"\nat = \"a\"\nsize = [0.8, 0.4, 0.8]\n\
             [[object]]\nname = \"o1\"\non = \"s\"\nsize = [0.1, 0.1, 0.1]\n\
             [[object]]\nname = \"o2\"\non = \"s\"\nsize = [0.1, 0.1, 0.1]\n",
        )
        .unwrap();
        assert!((w.objects[0].spot.x + 0.2).abs() < 1e-12);
        assert!((w.objects[1].spot.x - 0.2).abs() < 1e-12);
    }
}
