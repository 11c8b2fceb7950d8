% Functions this example registers in Rust (channel_robot.rs).
describe/1.
