//! What a task carries besides its DMs ([`Assets`]: its name, its world and
//! its KB, read from an application directory or embedded in a compiled
//! task), and the text files a run reads ([`TextFile`]: a file's name and
//! its UTF-8 text; [`FileError`] when it cannot be used).

use std::path::Path;

/// A text file a run uses (a world, a KB, a script): its name (for
/// messages) and its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextFile {
    pub name: String,
    pub text: String,
}

/// A file of a run that could not be used: the exit status (1 for bad
/// content, e.g. text that is not UTF-8; 2 for I/O) and the message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileError {
    pub status: u8,
    pub message: String,
}

impl std::fmt::Display for FileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl TextFile {
    /// Reads a text file: `what` names it in errors ("world", "script").
    /// Text that is not UTF-8 is an error at its first bad byte (status 1).
    pub fn read(path: &Path, what: &str) -> Result<TextFile, FileError> {
        let name = path.display().to_string();
        let bytes = sitlog_syntax::read_file(path).map_err(|e| FileError {
            status: 2,
            message: format!("error: cannot read {what} {name}: {e}"),
        })?;
        match sitlog_syntax::decode_owned(bytes) {
            Ok(text) => Ok(TextFile { name, text }),
            Err(e) => Err(FileError {
                status: 1,
                message: format!("{name}:{}:{}: error: {}", e.line, e.column, e.message),
            }),
        }
    }
}

/// What an application brings besides its DMs: its name, its world and its
/// KB. `sitlogc run` reads them from the application directory; a compiled
/// task embeds them.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Assets {
    pub app_name: String,
    /// `world.toml`.
    pub world: Option<TextFile>,
    /// `knowledge.kb`.
    pub kb: Option<TextFile>,
    /// The program's diagram as JSON (`sitlogc graph --format json`), for
    /// `--view`.
    pub diagram: Option<String>,
}

/// The world file of an application directory.
pub const WORLD_FILE: &str = "world.toml";
/// The KB file of an application directory.
pub const KB_FILE: &str = "knowledge.kb";

impl Assets {
    /// The assets of an application directory (or of the directory of a DM
    /// file): `world.toml` and `knowledge.kb` where present.
    pub fn from_app(app: &Path) -> Result<Assets, FileError> {
        let dir = if app.is_dir() {
            app.to_path_buf()
        } else {
            app.parent().map(Path::to_path_buf).unwrap_or_default()
        };
        let read = |file: &str, what: &str| -> Result<Option<TextFile>, FileError> {
            let path = dir.join(file);
            if !path.is_file() {
                return Ok(None);
            }
            TextFile::read(&path, what).map(Some)
        };
        Ok(Assets {
            app_name: app_name(app),
            world: read(WORLD_FILE, "world")?,
            kb: read(KB_FILE, "KB")?,
            diagram: None,
        })
    }
}

pub use sitlog_runtime::paths::app_name;
