//! `sitlogc library [NAME]`: the behaviour library built into `sitlogc`
//! ([`crate::library`]): its files and where each is read from, or one
//! file's text (to start a copy of one's own).

use crate::output::write_stdout;

/// `sitlogc library [NAME]`.
pub fn library(name: Option<&str>) -> u8 {
    let library = crate::library::library();
    match name {
        None => {
            let mut text = String::new();
            for name in crate::library::names() {
                let from = library
                    .find(name)
                    .map(|(root, _, _)| library.roots[root].what.as_str())
                    .unwrap_or("?");
                text.push_str(&format!("{name}  ({from})\n"));
            }
            write_stdout(&text, "the library's files")
        }
        Some(name) => match library.find(name) {
            Some((_, _, bytes)) => {
                write_stdout(&String::from_utf8_lossy(&bytes), "the library file")
            }
            None => {
                sitlog_runtime::errln!(
                    "error: no file `{name}` in the library; `sitlogc library` lists its files"
                );
                2
            }
        },
    }
}
