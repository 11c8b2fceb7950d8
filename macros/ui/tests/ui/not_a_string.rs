mod app {
    sitlog_macros::include_dm!(dms / app);
}

fn main() {}
