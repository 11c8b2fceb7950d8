//! `sitlogc new NAME [--robot]`: a new application that checks and runs at
//! once. Owns the templates (the files under `cli/templates/`, embedded in
//! the binary) and writing them; the invariant is that it never writes into
//! a directory that already exists.
//!
//! Two templates ([`Template`]):
//! - `speech` (`cli/templates/new/`): a DM `main` with a speech situation
//!   and a recursive situation calling the DM `ask_name(Name)`, the side
//!   files a program usually has (`global_vars.pl`, `basic_actions.pl`,
//!   `user_functions.pl`, `models`), a test-mode script and the golden
//!   output of running it (`expected.txt`);
//! - `robot` (`cli/templates/robot/`): a task on the simulated robot using
//!   the behaviour library by name (fetch an object the user asks for, with
//!   the library's recovery protocols at work): a world file with a small
//!   map, a KB, the DMs `main` and `fetch`, the side files, and the golden
//!   output of a run (`expected.txt`).
//!
//! Each has a README saying how to use its files.

use std::path::{Path, PathBuf};

/// Which application `sitlogc new` makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Template {
    /// Test mode: a speech task run from a script or the prompt.
    Speech,
    /// A task on the simulated robot, with a world, a KB and the library.
    Robot,
}

/// The files of the speech template: (file name, text). `{name}` in a
/// text is replaced by the application's name.
const SPEECH: &[(&str, &str)] = &[
    ("models", include_str!("../templates/new/models.in")),
    ("main.dm", include_str!("../templates/new/main.dm.in")),
    (
        "ask_name.dm",
        include_str!("../templates/new/ask_name.dm.in"),
    ),
    (
        "global_vars.pl",
        include_str!("../templates/new/global_vars.pl.in"),
    ),
    (
        "basic_actions.pl",
        include_str!("../templates/new/basic_actions.pl.in"),
    ),
    (
        "user_functions.pl",
        include_str!("../templates/new/user_functions.pl.in"),
    ),
    ("script.txt", include_str!("../templates/new/script.txt.in")),
    (
        "expected.txt",
        include_str!("../templates/new/expected.txt.in"),
    ),
    ("README.md", include_str!("../templates/new/README.md.in")),
];

/// The files of the robot template, as [`SPEECH`].
const ROBOT: &[(&str, &str)] = &[
    ("models", include_str!("../templates/robot/models.in")),
    ("main.dm", include_str!("../templates/robot/main.dm.in")),
    ("fetch.dm", include_str!("../templates/robot/fetch.dm.in")),
    (
        "world.toml",
        include_str!("../templates/robot/world.toml.in"),
    ),
    (
        "knowledge.kb",
        include_str!("../templates/robot/knowledge.kb.in"),
    ),
    (
        "global_vars.pl",
        include_str!("../templates/robot/global_vars.pl.in"),
    ),
    (
        "basic_actions.pl",
        include_str!("../templates/robot/basic_actions.pl.in"),
    ),
    (
        "user_functions.pl",
        include_str!("../templates/robot/user_functions.pl.in"),
    ),
    (
        "expected.txt",
        include_str!("../templates/robot/expected.txt.in"),
    ),
    (
        "tests/fetch_juice.toml",
        include_str!("../templates/robot/tests/fetch_juice.toml.in"),
    ),
    (
        "tests/juice_missing.toml",
        include_str!("../templates/robot/tests/juice_missing.toml.in"),
    ),
    ("README.md", include_str!("../templates/robot/README.md.in")),
];

impl Template {
    fn files(self) -> &'static [(&'static str, &'static str)] {
        match self {
            Template::Speech => SPEECH,
            Template::Robot => ROBOT,
        }
    }
}

/// Why an application could not be made (exit status 2 in the CLI).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Error(pub String);

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Error {}

/// The names of the files [`create`] writes for `template`, in order.
pub fn file_names(template: Template) -> impl Iterator<Item = &'static str> {
    template.files().iter().map(|(name, _)| *name)
}

/// Makes the application directory `dir` (its parents too) and writes
/// `template` into it; returns the files written. `dir` must not exist: an
/// existing file or directory (even an empty one) is refused untouched.
pub fn create(dir: &Path, template: Template) -> Result<Vec<PathBuf>, Error> {
    let shown = dir.display();
    if dir.as_os_str().is_empty() {
        return Err(Error("the application needs a name".to_owned()));
    }
    if dir.symlink_metadata().is_ok() {
        let what = if dir.is_dir() { "directory" } else { "file" };
        return Err(Error(format!(
            "`{shown}` already exists (a {what}); `sitlogc new` only makes a new directory: \
             choose another name, or remove it first"
        )));
    }
    let name = dir
        .file_name()
        .and_then(|n| n.to_str())
        .filter(|n| *n != "." && *n != "..")
        .ok_or_else(|| Error(format!("`{shown}` does not end in a directory name")))?
        .to_owned();
    if let Some(parent) = dir.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .map_err(|e| Error(format!("cannot create {}: {e}", parent.display())))?;
    }
    // create_dir (not _all): if something appeared meanwhile, refuse it too.
    std::fs::create_dir(dir).map_err(|e| match e.kind() {
        std::io::ErrorKind::AlreadyExists => Error(format!("`{shown}` already exists")),
        _ => Error(format!("cannot create {shown}: {e}")),
    })?;
    let mut written = Vec::new();
    for (file, text) in template.files() {
        let path = dir.join(file);
        if let Some(sub) = path.parent().filter(|p| *p != dir) {
            std::fs::create_dir_all(sub)
                .map_err(|e| Error(format!("cannot create {}: {e}", sub.display())))?;
        }
        std::fs::write(&path, text.replace("{name}", &name))
            .map_err(|e| Error(format!("cannot write {}: {e}", path.display())))?;
        written.push(path);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_an_existing_directory_untouched() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("keep.txt"), "mine").unwrap();
        let err = create(dir.path(), Template::Speech).unwrap_err();
        assert!(err.0.contains("already exists"), "{err}");
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(left.len(), 1);
    }

    #[test]
    fn writes_every_file_with_the_name() {
        let dir = tempfile::tempdir().unwrap();
        for (template, name) in [
            (Template::Speech, "hello_bot"),
            (Template::Robot, "fetch_bot"),
        ] {
            let app = dir.path().join("deep").join(name);
            let files = create(&app, template).unwrap();
            assert_eq!(files.len(), file_names(template).count());
            let readme = std::fs::read_to_string(app.join("README.md")).unwrap();
            assert!(readme.starts_with(&format!("# {name}\n")), "{readme}");
            assert!(!readme.contains("{name}"));
        }
    }
}
