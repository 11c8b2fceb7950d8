//! The repository's own rules, checked on its files: the guide's links
//! ([`guide_links`]) and the crate and module layout ([`layout`]).

mod guide_links;
mod layout;
