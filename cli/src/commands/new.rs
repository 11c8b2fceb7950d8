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
            sitlog_runtime::errln!("sitlogc: made the application {d} ({} files)", files.len());
            sitlog_runtime::errln!("  check it:  sitlogc check {d}");
            if robot {
                sitlog_runtime::errln!("  run it:    sitlogc run {d}");
                sitlog_runtime::errln!("  test it:   sitlogc test {d} --coverage");
            } else {
                sitlog_runtime::errln!("  run it:    sitlogc run {d} --script {d}/script.txt");
                sitlog_runtime::errln!("  talk to it: sitlogc run {d}");
            }
            0
        }
        Err(e) => {
            sitlog_runtime::errln!("error: {e}");
            2
        }
    }
}
