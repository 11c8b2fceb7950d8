//! The repository's own rules, checked on its files: the guide's links
//! ([`guide_links`]).

mod guide_links;
