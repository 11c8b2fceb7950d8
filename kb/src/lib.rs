//! `sitlog-kb`: the robot's non-monotonic knowledge base. Never knows about DMs.
