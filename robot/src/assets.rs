//! What a task carries besides its DMs ([`Assets`]: its name, its world and
//! its KB, read from an application directory or embedded in a compiled
//! task; [`Assets::problems`], what a run would refuse in them), and the
//! text files a run reads ([`TextFile`]: a file's name and its UTF-8 text;
//! [`FileError`] when it cannot be used).

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
    /// `ros2.toml`: the ROS 2 interface's names, QoS and places
    /// (`--robot ros2`, see sitlog-ros).
    pub ros2: Option<TextFile>,
    /// The program's diagram as JSON (`sitlogc graph --format json`), for
    /// `--view`.
    pub diagram: Option<String>,
}

/// The world file of an application directory.
pub const WORLD_FILE: &str = "world.toml";
/// The KB file of an application directory.
pub const KB_FILE: &str = "knowledge.kb";
/// The ROS 2 interface file of an application directory (`--robot ros2`).
pub const ROS2_FILE: &str = "ros2.toml";

impl Assets {
    /// The assets of an application directory (or of the directory of a DM
    /// file): `world.toml`, `knowledge.kb` and `ros2.toml` where present.
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
            ros2: read(ROS2_FILE, "ROS 2 interface")?,
            diagram: None,
        })
    }
}

/// A problem in a file of the application besides its DMs (its world, its
/// KB): the file, the 1-based line and column (0 and 0 when it has no
/// position) and what is wrong, as a run reports it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AssetError {
    pub file: String,
    pub line: usize,
    pub column: usize,
    pub message: String,
}

impl std::fmt::Display for AssetError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
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

impl Assets {
    /// What a run of these assets would refuse before it starts: every
    /// error of the world file (with feature `sim`) and the KB's first, each
    /// with the position and message the run gives (`sitlogc check` reports
    /// them). The ROS 2 interface file is sitlog-ros's to read.
    pub fn problems(&self) -> Vec<AssetError> {
        let mut out = Vec::new();
        #[cfg(feature = "sim")]
        if let Some(world) = &self.world {
            if let Err(errors) = sitlog_sim::World::parse(&world.name, &world.text) {
                out.extend(errors.into_iter().map(|e| AssetError {
                    file: e.file,
                    line: e.line,
                    column: e.column,
                    message: e.message,
                }));
            }
        }
        if let Some(kb) = &self.kb {
            if let Err(e) = sitlog_kb::Kb::parse(&kb.text, &kb.name) {
                let (line, column) = e.pos.unwrap_or((0, 0));
                out.push(AssetError {
                    file: e.path,
                    line,
                    column,
                    message: e.message,
                });
            }
        }
        out
    }
}

pub use sitlog_runtime::paths::app_name;
