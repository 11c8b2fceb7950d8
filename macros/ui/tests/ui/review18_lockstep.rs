// Helper `review18` (issue 37): two lists walked in step, a DM that checks
// and runs on the interpreter; its generated Rust must compile.
mod lockstep {
    sitlog_macros::include_dm!("../../tests/typed/review18/r18_d_lockstep");
}
mod lockstep_any {
    sitlog_macros::include_dm!("../../tests/typed/review18/r18_d_lockstep_any");
}

fn main() {
    let _ = (lockstep::program(), lockstep_any::program());
}
