//! `sitlogc new NAME`: a new application from the template ([`crate::scaffold`]).

/// `sitlogc new NAME`.
pub fn new_app(dir: &std::path::Path) -> u8 {
    match crate::scaffold::create(dir) {
        Ok(files) => {
            let d = dir.display();
            sitlog_runtime::errln!("sitlogc: made the application {d} ({} files)", files.len());
            sitlog_runtime::errln!("  check it:  sitlogc check {d}");
            sitlog_runtime::errln!("  run it:    sitlogc run {d} --script {d}/script.txt");
            sitlog_runtime::errln!("  talk to it: sitlogc run {d}");
            0
        }
        Err(e) => {
            sitlog_runtime::errln!("error: {e}");
            2
        }
    }
}
