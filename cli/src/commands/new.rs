//! `sitlogc new NAME [--robot]`: a new application from a template
//! ([`crate::scaffold`]).

use crate::scaffold::Template;

/// `sitlogc new NAME [--robot]`.
pub fn new_app(dir: &std::path::Path, robot: bool) -> u8 {
    let template = if robot {
        Template::Robot
    } else {
        Template::Speech
    };
    match crate::scaffold::create(dir, template) {
        Ok(files) => {
            let d = dir.display();
            eprintln!("sitlogc: made the application {d} ({} files)", files.len());
            eprintln!("  check it:  sitlogc check {d}");
            if robot {
                eprintln!("  run it:    sitlogc run {d}");
                eprintln!("  test it:   sitlogc run {d} | diff {d}/expected.txt -");
            } else {
                eprintln!("  run it:    sitlogc run {d} --script {d}/script.txt");
                eprintln!("  talk to it: sitlogc run {d}");
            }
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            2
        }
    }
}
