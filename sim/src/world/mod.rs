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
//!
//! The steps, one module each, in the order they run (each uses only those
//! before it):
//! - `text`: the file's bytes as text (UTF-8 only);
//! - `error`: [`WorldError`], byte offsets to line and column, and the
//!   collector every later step reports to;
//! - `model`: the validated [`World`] and its defaults and limits;
//! - `value`: one TOML value or table read as what a key needs (a name, a
//!   number in range, an array of tables...), with its position;
//! - `read`: each section of the file into raw records, names not yet
//!   resolved;
//! - `layout`: the objects of each shelf put on its board;
//! - `resolve`: names to indexes, with the checks across sections, into the
//!   [`World`].

mod error;
pub mod example;
mod layout;
mod model;
mod read;
mod resolve;
mod text;
mod value;

pub use error::WorldError;
pub(crate) use model::{Fault, Trigger};
pub use model::{
    World, DEFAULT_OBJECT_SIZE, DEFAULT_SHELF_SIZE, DEFAULT_SPEED, DEFAULT_WALL_HEIGHT,
    DEFAULT_WALL_THICKNESS, MAX_COORDINATE, MAX_SIZE, MIN_SIZE,
};
pub use read::KEYS;

use error::Cx;
use toml::de::DeTable;

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
        let raw = read::read_world(&mut cx, &doc);
        let world = resolve::resolve(&mut cx, raw);
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
        let bytes = read_capped(path).map_err(|e| {
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
        text::decode(bytes).map_err(|e| {
            vec![WorldError {
                file: file_name.to_string(),
                line: e.line,
                column: e.column,
                message: e.message,
            }]
        })
    }
}

/// The largest world file [`World::load`] reads (256 MiB, the default of
/// `sitlogc --max-file-bytes`, which reads worlds itself).
pub const MAX_WORLD_BYTES: u64 = 256 * 1024 * 1024;

/// The bytes of `path`, at most [`MAX_WORLD_BYTES`].
fn read_capped(path: &std::path::Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(MAX_WORLD_BYTES + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_WORLD_BYTES {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("larger than the limit of {MAX_WORLD_BYTES} bytes"),
        ));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    /// The guide's reference of the world file's keys (docs/guide/robot.md,
    /// "Every key of the world file") lists exactly the keys the reader
    /// accepts ([`KEYS`]).
    #[test]
    fn the_guide_lists_every_key_of_the_world_file() {
        let page = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../docs/guide/robot.md"
        ))
        .expect("the guide's robot page");
        let section = page
            .split("### Every key of the world file")
            .nth(1)
            .expect("the section")
            .split("\n#")
            .next()
            .unwrap_or("");
        let mut listed: Vec<(String, String)> = section
            .lines()
            .filter(|l| l.starts_with("| ") && !l.starts_with("| table"))
            .map(|l| {
                let cells: Vec<&str> = l.split('|').map(str::trim).collect();
                let table = cells[1].trim_matches('`');
                let table = if table == "(top)" { "" } else { table };
                (table.to_owned(), cells[2].trim_matches('`').to_owned())
            })
            .collect();
        let mut accepted: Vec<(String, String)> = super::KEYS
            .iter()
            .flat_map(|(t, ks)| ks.iter().map(move |k| (t.to_string(), k.to_string())))
            .collect();
        listed.sort();
        accepted.sort();
        let missing: Vec<_> = accepted.iter().filter(|k| !listed.contains(k)).collect();
        let extra: Vec<_> = listed.iter().filter(|k| !accepted.contains(k)).collect();
        assert!(
            missing.is_empty() && extra.is_empty(),
            "the guide misses {missing:?} and lists keys the reader refuses: {extra:?}"
        );
    }

    use super::*;

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
