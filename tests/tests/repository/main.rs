//! The repository's own rules, checked on its files: the guide's links
//! ([`guide_links`]), its tables of diagnostic codes ([`guide_codes`]) and
//! the crate and module layout ([`layout`]).

mod guide_codes;
mod guide_links;
mod layout;
