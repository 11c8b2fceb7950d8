//! `sitlog-syntax`: the term layer shared by every part of sitlog-rs.
//!
//! Reads Prolog text (SitLog's DMs, side files, KBs, scripted input) into
//! spanned terms using an operator table that is data ([`OpTable`]), and
//! writes terms back in `writeq` style ([`write`]). It knows nothing about
//! dialogue models: the compiler builds its SitLog layer on top, the runtime
//! converts read terms into its own heap terms, and the KB reads its files
//! with it.

pub mod atom;
pub mod decode;
mod lexer;
pub mod ops;
pub mod read;
pub mod term;
pub mod write;

pub use atom::{atoms, Atom};
pub use decode::{decode, decode_owned, DecodeError};
pub use ops::{OpDef, OpTable, OpType};
pub use read::{
    line_col, read_clauses, read_clauses_bytes, read_clauses_bytes_with, read_clauses_with,
    read_term, read_term_limited, read_term_with, source_from_bytes, ClauseReader, SyntaxError,
};
pub use term::{Clause, Node, Span, TermId, Terms, VarId, VarInfo};
pub use write::{write_term, writeq, TermSource, VarLabel, View, WriteOptions};
