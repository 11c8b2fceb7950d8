//! `sitlog-syntax`: the term layer shared by every part of sitlog-rs.
//!
//! Reads Prolog text (SitLog's DMs, side files, KBs, scripted input) into
//! spanned terms using an operator table that is data ([`OpTable`]), and
//! writes terms back in `writeq` style ([`mod@write`]). It knows nothing about
//! dialogue models: the compiler builds its SitLog layer on top, the runtime
//! converts read terms into its own heap terms, and the KB reads its files
//! with it.
//!
//! **Invariant:** it is the bottom of sitlog-rs: no other sitlog crate is
//! among its dependencies, and no input makes a reader panic or overflow
//! the stack (the parser is iterative and depth-limited). Modules, each
//! using only those listed before it: [`atom`], [`term`], [`mod@decode`],
//! `error` ([`SyntaxError`]), [`ops`], `lexer`, [`read`], [`write`](mod@write).

pub mod atom;
pub mod decode;
mod error;
mod lexer;
pub mod ops;
pub mod read;
pub mod term;
pub mod write;

pub use atom::{atoms, Atom};
pub use decode::{decode, decode_owned, read_file, DecodeError};
pub use error::{line_col, SyntaxError};
#[doc(hidden)]
pub use lexer::fast_path_disagreement;
pub use ops::{OpDef, OpTable, OpType};
pub use read::{
    read_clauses, read_clauses_bytes, read_clauses_bytes_with, read_clauses_with,
    read_prolog_clauses, read_term, read_term_limited, read_term_with, source_from_bytes,
    ClauseReader,
};
pub use term::{Clause, Node, Span, TermId, Terms, VarId, VarInfo};
pub use write::{write_term, writeq, TermSource, VarLabel, View, WriteOptions};
