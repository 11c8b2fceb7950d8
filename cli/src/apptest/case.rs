//! One test case of `sitlogc test`: a TOML file in the application's
//! `tests/` directory, read into a [`Case`] (the run's world or script, its
//! options, and what must hold afterwards). Every mistake in a test file is
//! an error at its `file:line:col` ([`CaseError`]); nothing here panics.
//!
//! The world of a test is the application's `world.toml` (or the file its
//! `[world] file` names) with the test's changes applied ([`world_text`]):
//! objects taken out (`missing`, with the faults that name them) or moved
//! (`moved`), the user's lines
//! (`says`), the seed, faults added (`[[world.fault]]`). A change that
//! names no object or shelf of that world is an error at the change.

use std::path::{Path, PathBuf};
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// A bad test file: `file:line:col: error: message`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CaseError {
    pub file: String,
    pub line: usize,
    pub column: usize,
    pub message: String,
}

impl std::fmt::Display for CaseError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}:{}:{}: error: {}",
            self.file, self.line, self.column, self.message
        )
    }
}

/// What a test runs on.
#[derive(Clone, Debug, PartialEq)]
pub enum Input {
    /// A world: the application's (or `[world] file`), with changes.
    World(WorldSpec),
    /// Test mode: the inputs, one term a line (`script`).
    Script { name: String, text: String },
}

/// The world of a test before its changes are applied.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WorldSpec {
    /// `[world] file`, relative to the test file (default: the app's world).
    pub file: Option<PathBuf>,
    pub seed: Option<i64>,
    pub says: Option<Vec<String>>,
    /// Objects taken out, with where the test names them.
    pub missing: Vec<(String, usize)>,
    /// Objects moved: (object, shelf, where).
    pub moved: Vec<(String, String, usize)>,
    /// `[[world.fault]]` tables, added to the world's faults.
    pub faults: Vec<toml::Table>,
}

impl WorldSpec {
    fn changes_nothing(&self) -> bool {
        self.seed.is_none()
            && self.says.is_none()
            && self.missing.is_empty()
            && self.moved.is_empty()
            && self.faults.is_empty()
    }
}

/// The status a test's run must end with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// The main DM reached a final situation (exit status 0).
    Ok,
    /// A run-time error stopped it (exit status 1).
    Error,
}

/// What must hold after the run (`[expect]`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Expect {
    pub status: Status,
    /// The main DM's final situation, as `writeq` writes it (`fs`, `error(E)`: its functor is compared when it has variables).
    pub final_situation: Option<Located>,
    pub out_arg: Option<Located>,
    /// Text that lines of the output must contain, in this order.
    pub lines: Vec<Located>,
    /// Text that no line of the output may contain.
    pub absent: Vec<Located>,
    pub max_transitions: Option<u64>,
    /// KB questions and their answers after the run: (query, answer).
    pub kb: Vec<(Located, Located)>,
    /// Text the error message must contain (with `status = "error"`).
    pub error: Option<Located>,
    /// A file the run's stdout must equal (what `sitlogc run APP > FILE` writes).
    pub golden: Option<(Located, PathBuf)>,
}

/// A value of the test file with its position (`line:col`), for failures.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Located {
    pub text: String,
    pub line: usize,
    pub column: usize,
}

/// One test.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// The file's name without `.toml`.
    pub name: String,
    pub path: PathBuf,
    pub about: Option<String>,
    pub input: Input,
    pub main: Option<String>,
    pub in_arg: Option<String>,
    pub expect: Expect,
}

const TOP_KEYS: &[&str] = &["about", "main", "in_arg", "script", "world", "expect"];
const WORLD_KEYS: &[&str] = &["file", "seed", "says", "missing", "moved", "fault"];
const EXPECT_KEYS: &[&str] = &[
    "status",
    "final",
    "out_arg",
    "lines",
    "absent",
    "max_transitions",
    "kb",
    "error",
    "golden",
];

struct Cx<'t> {
    file: String,
    text: &'t str,
    errors: Vec<CaseError>,
}

type Val<'i> = Spanned<DeValue<'i>>;

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

impl Cx<'_> {
    fn err(&mut self, at: usize, message: String) {
        let (line, column) = sitlog_syntax::line_col(self.text, at);
        self.errors.push(CaseError {
            file: self.file.clone(),
            line,
            column,
            message,
        });
    }

    fn located(&self, text: String, at: usize) -> Located {
        let (line, column) = sitlog_syntax::line_col(self.text, at);
        Located { text, line, column }
    }

    fn keys(&mut self, t: &DeTable<'_>, label: &str, allowed: &[&str]) {
        for (k, _) in t.iter() {
            if !allowed.contains(&k.get_ref().as_ref()) {
                self.err(
                    k.span().start,
                    format!(
                        "unknown key `{}` in {label}; known keys: {}",
                        k.get_ref(),
                        allowed.join(", ")
                    ),
                );
            }
        }
    }

    fn string(&mut self, v: &Val<'_>, label: &str) -> Option<Located> {
        match v.get_ref() {
            DeValue::String(s) => Some(self.located(s.to_string(), v.span().start)),
            other => {
                self.err(
                    v.span().start,
                    format!("{label} must be a string, found {}", what(other)),
                );
                None
            }
        }
    }

    fn strings(&mut self, v: &Val<'_>, label: &str) -> Vec<Located> {
        match v.get_ref() {
            DeValue::Array(items) => items
                .iter()
                .filter_map(|i| self.string(i, &format!("each of {label}")))
                .collect(),
            other => {
                self.err(
                    v.span().start,
                    format!("{label} must be an array of strings, found {}", what(other)),
                );
                Vec::new()
            }
        }
    }

    fn table<'a, 'i>(&mut self, v: &'a Val<'i>, label: &str) -> Option<&'a DeTable<'i>> {
        match v.get_ref() {
            DeValue::Table(t) => Some(t),
            other => {
                self.err(
                    v.span().start,
                    format!("{label} must be a table, found {}", what(other)),
                );
                None
            }
        }
    }

    fn integer(&mut self, v: &Val<'_>, label: &str, min: i64) -> Option<i64> {
        let n = match v.get_ref() {
            DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix()).ok(),
            _ => None,
        };
        match n {
            Some(n) if n >= min => Some(n),
            _ => {
                self.err(
                    v.span().start,
                    format!(
                        "{label} must be an integer of at least {min}, found {}",
                        match v.get_ref() {
                            DeValue::Integer(i) => format!("`{}`", i.as_str()),
                            other => what(other).to_owned(),
                        }
                    ),
                );
                None
            }
        }
    }
}

/// Reads the test file `path` (its text `text`).
pub fn parse(path: &Path, text: &str) -> Result<Case, Vec<CaseError>> {
    let mut cx = Cx {
        file: path.display().to_string(),
        text,
        errors: Vec::new(),
    };
    let (doc, syntax) = DeTable::parse_recoverable(text);
    if let Some(e) = syntax.first() {
        let at = e.span().map(|s| s.start).unwrap_or(0);
        cx.err(at, format!("not valid TOML: {}", e.message()));
        return Err(cx.errors);
    }
    let root = doc.get_ref();
    cx.keys(root, "a test file", TOP_KEYS);
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let about = root
        .get("about")
        .and_then(|v| cx.string(v, "`about`"))
        .map(|l| l.text);
    let main = root
        .get("main")
        .and_then(|v| cx.string(v, "`main`"))
        .map(|l| l.text);
    let in_arg = root
        .get("in_arg")
        .and_then(|v| cx.string(v, "`in_arg`"))
        .map(|l| l.text);

    // The world, or test mode with a script.
    let mut world = WorldSpec::default();
    if let Some(v) = root.get("world") {
        if let Some(t) = cx.table(v, "`world`") {
            read_world(&mut cx, t, &dir, &mut world);
        }
    }
    let input = match root.get("script") {
        Some(v) => {
            if root.get("world").is_some() {
                cx.err(
                    v.span().start,
                    "`script` runs the test in test mode, without a world: remove `[world]` or `script`".to_owned(),
                );
            }
            match v.get_ref() {
                DeValue::String(s) => {
                    let file = dir.join(s.as_ref());
                    match crate::apptest::read_text(&file) {
                        Ok(text) => Some(Input::Script {
                            name: file.display().to_string(),
                            text,
                        }),
                        Err(e) => {
                            cx.err(v.span().start, format!("cannot read the script: {e}"));
                            None
                        }
                    }
                }
                DeValue::Array(_) => {
                    let lines = cx.strings(v, "`script`");
                    let mut text = String::new();
                    for l in lines {
                        text.push_str(&l.text);
                        text.push('\n');
                    }
                    Some(Input::Script {
                        name: format!("{} (its script)", cx.file),
                        text,
                    })
                }
                other => {
                    cx.err(
                        v.span().start,
                        format!(
                            "`script` must be a file name or an array of inputs (one term each), found {}",
                            what(other)
                        ),
                    );
                    None
                }
            }
        }
        None => Some(Input::World(world)),
    };

    let expect = match root.get("expect") {
        Some(v) => match cx.table(v, "`expect`") {
            Some(t) => read_expect(&mut cx, t, &dir),
            None => None,
        },
        None => Some(empty_expect()),
    };
    match (input, expect) {
        (Some(input), Some(expect)) if cx.errors.is_empty() => Ok(Case {
            name: path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default(),
            path: path.to_path_buf(),
            about,
            input,
            main,
            in_arg,
            expect,
        }),
        _ => Err(cx.errors),
    }
}

fn empty_expect() -> Expect {
    Expect {
        status: Status::Ok,
        final_situation: None,
        out_arg: None,
        lines: Vec::new(),
        absent: Vec::new(),
        max_transitions: None,
        kb: Vec::new(),
        error: None,
        golden: None,
    }
}

fn read_world(cx: &mut Cx<'_>, t: &DeTable<'_>, dir: &Path, w: &mut WorldSpec) {
    cx.keys(t, "`[world]`", WORLD_KEYS);
    if let Some(v) = t.get("file") {
        w.file = cx.string(v, "`world.file`").map(|l| dir.join(l.text));
    }
    if let Some(v) = t.get("seed") {
        w.seed = cx.integer(v, "`world.seed`", 0);
    }
    if let Some(v) = t.get("says") {
        w.says = Some(
            cx.strings(v, "`world.says`")
                .into_iter()
                .map(|l| l.text)
                .collect(),
        );
    }
    if let Some(v) = t.get("missing") {
        let at = v.span().start;
        w.missing = cx
            .strings(v, "`world.missing`")
            .into_iter()
            .map(|l| (l.text, at))
            .collect();
        if let DeValue::Array(items) = v.get_ref() {
            for (m, item) in w.missing.iter_mut().zip(items) {
                m.1 = item.span().start;
            }
        }
    }
    if let Some(v) = t.get("moved") {
        if let Some(m) = cx.table(v, "`world.moved` (object = \"shelf\")") {
            for (k, s) in m.iter() {
                if let Some(shelf) = cx.string(s, &format!("`world.moved.{}`", k.get_ref())) {
                    w.moved
                        .push((k.get_ref().to_string(), shelf.text, k.span().start));
                }
            }
        }
    }
    if let Some(v) = t.get("fault") {
        match v.get_ref() {
            DeValue::Array(items) => {
                for item in items {
                    match item.get_ref() {
                        DeValue::Table(f) => w.faults.push(owned_table(f)),
                        other => cx.err(
                            item.span().start,
                            format!(
                                "each `[[world.fault]]` must be a table, found {}",
                                what(other)
                            ),
                        ),
                    }
                }
            }
            other => cx.err(
                v.span().start,
                format!(
                    "`world.fault` must be an array of tables (`[[world.fault]]`), found {}",
                    what(other)
                ),
            ),
        }
    }
}

/// A table of the test file as a plain TOML table (a fault to add).
fn owned_table(t: &DeTable<'_>) -> toml::Table {
    let mut out = toml::Table::new();
    for (k, v) in t.iter() {
        out.insert(k.get_ref().to_string(), owned(v.get_ref()));
    }
    out
}

fn owned(v: &DeValue<'_>) -> toml::Value {
    match v {
        DeValue::String(s) => toml::Value::String(s.to_string()),
        DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
            Ok(n) => toml::Value::Integer(n),
            Err(_) => toml::Value::String(i.as_str().to_owned()),
        },
        DeValue::Float(x) => toml::Value::Float(x.as_str().parse().unwrap_or(f64::NAN)),
        DeValue::Boolean(b) => toml::Value::Boolean(*b),
        DeValue::Datetime(d) => toml::Value::Datetime(*d),
        DeValue::Array(items) => {
            toml::Value::Array(items.iter().map(|i| owned(i.get_ref())).collect())
        }
        DeValue::Table(t) => toml::Value::Table(owned_table(t)),
    }
}

fn read_expect(cx: &mut Cx<'_>, t: &DeTable<'_>, dir: &Path) -> Option<Expect> {
    cx.keys(t, "`[expect]`", EXPECT_KEYS);
    let mut e = empty_expect();
    if let Some(v) = t.get("status") {
        if let Some(s) = cx.string(v, "`expect.status`") {
            match s.text.as_str() {
                "ok" => e.status = Status::Ok,
                "error" => e.status = Status::Error,
                other => cx.err(
                    v.span().start,
                    format!("`expect.status` is `ok` or `error`, not `{other}`"),
                ),
            }
        }
    }
    if let Some(v) = t.get("final") {
        e.final_situation = cx.string(v, "`expect.final`");
    }
    if let Some(v) = t.get("out_arg") {
        e.out_arg = cx.string(v, "`expect.out_arg`");
    }
    if let Some(v) = t.get("lines") {
        e.lines = cx.strings(v, "`expect.lines`");
    }
    if let Some(v) = t.get("absent") {
        e.absent = cx.strings(v, "`expect.absent`");
    }
    if let Some(v) = t.get("max_transitions") {
        e.max_transitions = cx
            .integer(v, "`expect.max_transitions`", 1)
            .map(|n| n as u64);
    }
    if let Some(v) = t.get("error") {
        e.error = cx.string(v, "`expect.error`");
        if e.status != Status::Error {
            cx.err(
                v.span().start,
                "`expect.error` needs `status = \"error\"`".to_owned(),
            );
        }
    }
    if let Some(v) = t.get("golden") {
        if let Some(l) = cx.string(v, "`expect.golden`") {
            let path = dir.join(&l.text);
            e.golden = Some((l, path));
        }
    }
    if let Some(v) = t.get("kb") {
        match v.get_ref() {
            DeValue::Table(q) => {
                // `[expect.kb]`: query = "answer"
                for (k, a) in q.iter() {
                    let query = cx.located(k.get_ref().to_string(), k.span().start);
                    if let Some(answer) = cx.string(a, &format!("the answer of `{}`", query.text))
                    {
                        e.kb.push((query, answer));
                    }
                }
            }
            other => cx.err(
                v.span().start,
                format!(
                    "`expect.kb` must be a table of questions and answers (`\"object_property_value(juice, loc, X)\" = \"fridge\"`), found {}",
                    what(other)
                ),
            ),
        }
    }
    Some(e)
}

/// The world text of a test: `base` (the world file `base_name`) with the
/// changes of `spec`; the test file `case` (its text `case_text`) names
/// the changes in errors. Without changes, `base` as it is (so the
/// simulator's errors name its lines).
pub fn world_text(
    spec: &WorldSpec,
    base_name: &str,
    base: &str,
    case: &Path,
    case_text: &str,
) -> Result<String, Vec<CaseError>> {
    if spec.changes_nothing() {
        return Ok(base.to_owned());
    }
    let mut cx = Cx {
        file: case.display().to_string(),
        text: case_text,
        errors: Vec::new(),
    };
    let mut world: toml::Table = match base.parse() {
        Ok(t) => t,
        Err(e) => {
            cx.err(
                0,
                format!("cannot change the world {base_name}: it is not valid TOML: {e}"),
            );
            return Err(cx.errors);
        }
    };
    if let Some(seed) = spec.seed {
        world.insert("seed".into(), toml::Value::Integer(seed));
    }
    if let Some(says) = &spec.says {
        match world.get_mut("user") {
            Some(toml::Value::Table(u)) => {
                u.insert(
                    "says".into(),
                    toml::Value::Array(says.iter().cloned().map(toml::Value::String).collect()),
                );
            }
            _ => cx.err(
                0,
                format!("`world.says`: the world {base_name} has no [user]"),
            ),
        }
    }
    let names = |world: &toml::Table, key: &str| -> Vec<String> {
        match world.get(key) {
            Some(toml::Value::Array(items)) => items
                .iter()
                .filter_map(|i| i.get("name").and_then(|n| n.as_str()).map(str::to_owned))
                .collect(),
            _ => Vec::new(),
        }
    };
    let objects = names(&world, "object");
    let shelves = names(&world, "shelf");
    let known = |list: &[String]| {
        if list.is_empty() {
            "none".to_owned()
        } else {
            list.join(", ")
        }
    };
    for (name, at) in &spec.missing {
        if !objects.contains(name) {
            cx.err(
                *at,
                format!(
                    "`world.missing`: no object `{name}` in {base_name} (its objects: {})",
                    known(&objects)
                ),
            );
        }
    }
    for (name, shelf, at) in &spec.moved {
        if !objects.contains(name) {
            cx.err(
                *at,
                format!(
                    "`world.moved`: no object `{name}` in {base_name} (its objects: {})",
                    known(&objects)
                ),
            );
        } else if !shelves.contains(shelf) {
            cx.err(
                *at,
                format!(
                    "`world.moved`: no shelf `{shelf}` in {base_name} to put `{name}` on (its shelves: {})",
                    known(&shelves)
                ),
            );
        }
    }
    if !cx.errors.is_empty() {
        return Err(cx.errors);
    }
    if let Some(toml::Value::Array(items)) = world.get_mut("object") {
        items.retain(|o| {
            let n = o.get("name").and_then(|n| n.as_str()).unwrap_or("");
            !spec.missing.iter().any(|(m, _)| m == n)
        });
        for o in items.iter_mut() {
            let n = o
                .get("name")
                .and_then(|n| n.as_str())
                .unwrap_or("")
                .to_owned();
            if let (Some((_, shelf, _)), toml::Value::Table(t)) =
                (spec.moved.iter().find(|(m, _, _)| *m == n), o)
            {
                t.insert("on".into(), toml::Value::String(shelf.clone()));
                t.remove("spot");
            }
        }
    }
    // the faults that name an object taken out go with it
    if !spec.missing.is_empty() {
        if let Some(toml::Value::Array(items)) = world.get_mut("fault") {
            items.retain(|f| {
                let o = f.get("object").and_then(|n| n.as_str()).unwrap_or("");
                !spec.missing.iter().any(|(m, _)| m == o)
            });
        }
    }
    if !spec.faults.is_empty() {
        let faults = world
            .entry("fault")
            .or_insert_with(|| toml::Value::Array(Vec::new()));
        if let toml::Value::Array(items) = faults {
            items.extend(spec.faults.iter().cloned().map(toml::Value::Table));
        }
    }
    toml::to_string(&world).map_err(|e| {
        cx.err(0, format!("cannot write the changed world: {e}"));
        cx.errors
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const WORLD: &str = "seed = 1\n[user]\nname = \"Ada\"\nsays = [\"hi\"]\n[[shelf]]\nname = \"fridge\"\n[[shelf]]\nname = \"table\"\n[[object]]\nname = \"juice\"\non = \"table\"\n[[object]]\nname = \"milk\"\non = \"fridge\"\n";

    fn case(text: &str) -> Result<Case, Vec<CaseError>> {
        parse(Path::new("tests/t.toml"), text)
    }

    #[test]
    fn a_full_test_file_reads() {
        let c = case(
            "about = \"x\"\n[world]\nseed = 3\nsays = [\"a\"]\nmissing = [\"milk\"]\nmoved = { juice = \"fridge\" }\n[[world.fault]]\nkind = \"grasp_fails\"\nobject = \"juice\"\n[expect]\nlines = [\"Golem: a\", \"Golem: b\"]\nabsent = [\"c\"]\nfinal = \"fs\"\nmax_transitions = 90\n[expect.kb]\n\"object_property_value(juice, loc, X)\" = \"fridge\"\n",
        )
        .unwrap();
        assert_eq!(c.name, "t");
        assert_eq!(c.expect.lines.len(), 2);
        assert_eq!(c.expect.lines[1].line, 11);
        assert_eq!(c.expect.kb.len(), 1);
        let Input::World(w) = &c.input else {
            panic!("a world")
        };
        let text = world_text(w, "world.toml", WORLD, &c.path, "").unwrap();
        let t: toml::Table = text.parse().unwrap();
        assert_eq!(t["seed"].as_integer(), Some(3));
        let objects = t["object"].as_array().unwrap();
        assert_eq!(objects.len(), 1);
        assert_eq!(objects[0]["on"].as_str(), Some("fridge"));
        assert_eq!(t["fault"].as_array().unwrap().len(), 1);
        assert_eq!(t["user"]["says"].as_array().unwrap().len(), 1);
    }

    #[test]
    fn mistakes_are_located() {
        let errs =
            case("about = 3\nwrold = 1\n[expect]\nstatus = \"fine\"\nlines = \"x\"\n").unwrap_err();
        let shown: Vec<String> = errs.iter().map(|e| e.to_string()).collect();
        assert_eq!(
            shown,
            [
                "tests/t.toml:2:1: error: unknown key `wrold` in a test file; known keys: about, main, in_arg, script, world, expect",
                "tests/t.toml:1:9: error: `about` must be a string, found an integer",
                "tests/t.toml:4:10: error: `expect.status` is `ok` or `error`, not `fine`",
                "tests/t.toml:5:9: error: `expect.lines` must be an array of strings, found a string",
            ]
        );
        let errs = case("[expect\n").unwrap_err();
        assert!(
            errs[0].to_string().starts_with("tests/t.toml:1:"),
            "{errs:?}"
        );
    }

    #[test]
    fn a_change_naming_nothing_of_the_world_is_located() {
        let text = "[world]\nmissing = [\"cola\"]\nmoved = { milk = \"roof\" }\n";
        let c = case(text).unwrap();
        let Input::World(w) = &c.input else {
            panic!("a world")
        };
        let errs = world_text(w, "w.toml", WORLD, &c.path, text).unwrap_err();
        let shown: Vec<String> = errs.iter().map(|e| e.to_string()).collect();
        assert_eq!(
            shown,
            [
                "tests/t.toml:2:12: error: `world.missing`: no object `cola` in w.toml (its objects: juice, milk)",
                "tests/t.toml:3:11: error: `world.moved`: no shelf `roof` in w.toml to put `milk` on (its shelves: fridge, table)",
            ]
        );
    }
}
