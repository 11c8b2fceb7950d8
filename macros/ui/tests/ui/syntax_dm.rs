mod app {
    sitlog_macros::include_dm!("tests/ui/syntax_dm.dm");
}

fn main() {}
