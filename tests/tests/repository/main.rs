//! The repository's own rules, checked on its files: the guide's links
//! ([`guide_links`]), its tables of diagnostic codes ([`guide_codes`]) and
//! the crate and module layout ([`layout`]), the library's finals
//! ([`library_finals`]).

mod guide_codes;
mod guide_links;
mod layout;
mod library_finals;
