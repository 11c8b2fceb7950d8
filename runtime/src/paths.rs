//! File paths as the loaders compare them: lexically, without touching the
//! file system (a compiled task compares the names of embedded sources);
//! and the name of an application ([`app_name`], the one function here that
//! asks the file system: for the real name of `.`).

use std::path::{Component, Path, PathBuf};

/// `path` with `.` and `dir/..` removed lexically (no file system access;
/// a leading `..` stays).
pub fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir
                if matches!(out.components().next_back(), Some(Component::Normal(_))) =>
            {
                out.pop();
            }
            c => out.push(c),
        }
    }
    out
}

/// The name of an application: its directory's real name (`.` and `..`
/// too), or a DM file's stem; `app` when it has none. The one name every
/// tool uses (the compiled task's default file name, the live view's title;
/// the generated code and diagrams take its Rust identifier form).
pub fn app_name(app: &Path) -> String {
    let app = std::fs::canonicalize(app).unwrap_or_else(|_| app.to_path_buf());
    let name = if app.is_dir() {
        app.file_name()
    } else {
        app.file_stem()
    };
    name.map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "app".to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lexical() {
        let n = |p: &str| normalize(Path::new(p));
        assert_eq!(n("a/b/../../c/./d.pl"), PathBuf::from("c/d.pl"));
        assert_eq!(n("../x/../y"), PathBuf::from("../y"));
        assert_eq!(n("/a/.."), PathBuf::from("/"));
    }
}
