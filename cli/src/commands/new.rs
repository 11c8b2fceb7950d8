//! `sitlogc new NAME`: a new application from the template ([`crate::scaffold`]).

/// `sitlogc new NAME`.
pub fn new_app(dir: &std::path::Path) -> u8 {
    match crate::scaffold::create(dir) {
        Ok(files) => {
            let d = dir.display();
            eprintln!("sitlogc: made the application {d} ({} files)", files.len());
            eprintln!("  check it:  sitlogc check {d}");
            eprintln!("  run it:    sitlogc run {d} --script {d}/script.txt");
            eprintln!("  talk to it: sitlogc run {d}");
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            2
        }
    }
}
