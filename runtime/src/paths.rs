//! File paths as the loaders compare them: lexically, without touching the
//! file system (a compiled task compares the names of embedded sources).

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
