//! The behaviour library as `sitlogc` ships it: the DMs and Prolog files of
//! `dms/behaviors/` embedded in the binary (`cli/build.rs`), versioned with
//! it, and the search order of library names ([`library`]): the
//! application's own copy first (the loader's rule), then each directory of
//! `$SITLOG_LIBRARY`, then the embedded files. An application names a
//! library file without a path (`'behaviors/say.dm'.` in `models`,
//! `:- consult('behaviors/language.pl').`), so it runs wherever it is.

use sitlog_compiler::load::{Library, LibraryFiles, LibraryRoot};
use std::sync::OnceLock;

include!(concat!(env!("OUT_DIR"), "/embedded_library.rs"));

/// The environment variable listing library directories searched before
/// the embedded library (separated as `PATH` is).
pub const LIBRARY_ENV: &str = "SITLOG_LIBRARY";

/// The library of this process: `$SITLOG_LIBRARY`'s directories (read
/// once), then the library built into `sitlogc`.
pub fn library() -> &'static Library {
    static LIBRARY: OnceLock<Library> = OnceLock::new();
    LIBRARY.get_or_init(|| {
        let mut roots: Vec<LibraryRoot> = std::env::var_os(LIBRARY_ENV)
            .map(|v| std::env::split_paths(&v).collect::<Vec<_>>())
            .unwrap_or_default()
            .into_iter()
            .filter(|d| !d.as_os_str().is_empty())
            .map(|dir| LibraryRoot {
                what: format!("${LIBRARY_ENV} directory {}", dir.display()),
                files: LibraryFiles::Dir(dir),
            })
            .collect();
        roots.push(embedded());
        Library { roots }
    })
}

/// The library built into this `sitlogc`.
pub fn embedded() -> LibraryRoot {
    LibraryRoot {
        what: format!(
            "the library built into sitlogc {}",
            env!("CARGO_PKG_VERSION")
        ),
        files: LibraryFiles::Embedded(LIBRARY_FILES),
    }
}

/// The names of the embedded library's files (`behaviors/say.dm`, ...).
pub fn names() -> impl Iterator<Item = &'static str> {
    LIBRARY_FILES.iter().map(|(name, _)| *name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_library_holds_the_behaviours_and_their_grammar() {
        let names: Vec<_> = names().collect();
        for name in [
            "behaviors/say.dm",
            "behaviors/ask.dm",
            "behaviors/language.pl",
            "behaviors/recovery/regrasp.dm",
        ] {
            assert!(names.contains(&name), "{name} not in {names:?}");
        }
        let found = library().find("behaviors/say.dm").expect("say.dm");
        assert_eq!(found.1, std::path::Path::new("library:/behaviors/say.dm"));
        assert!(library().find("../behaviors/say.dm").is_none());
    }
}
