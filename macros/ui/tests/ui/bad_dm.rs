mod app {
    sitlog_macros::include_dm!("tests/ui/bad_dm");
}

fn main() {}
