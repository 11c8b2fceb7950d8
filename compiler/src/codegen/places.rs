//! Each DM's places in generated code (issue 39): where its situations'
//! arcs and constructs of L are written, as the text the runtime's
//! `machine::places` reads (its module doc has the format) when a run-time
//! error is reported, so that a compiled task names the `file:line:col`
//! the interpreter names from the source. The texts are the program's
//! `PLACES` (by DM, given to its `SitTable`): static data, read only for
//! an error; the code of a situation names nothing of it.

use super::wrapped_literal;
use crate::ir::{Ir, IrDm};
use proc_macro2::Literal;
use sitlog_runtime::machine::places::{sit_places_text, Written};

/// The program's `PLACES`: each DM's places text as a literal (wrapped
/// like the constants').
pub(super) fn places(ir: &Ir) -> Vec<Literal> {
    ir.dms
        .iter()
        .map(|dm| {
            wrapped_literal(&dm_places(ir, dm), 88)
                .parse()
                .expect("a string literal")
        })
        .collect()
}

/// DM `dm`'s places text.
fn dm_places(ir: &Ir, dm: &IrDm) -> String {
    let entries: Vec<String> = dm
        .situations
        .iter()
        .map(|s| {
            let src = &s.source;
            let file = ir.sources.get(src.file);
            let at = |span: sitlog_syntax::Span| {
                let p = file.line_col(span.start);
                (p.line, p.column)
            };
            let arcs: Vec<_> = src.arcs.iter().map(|&span| at(span)).collect();
            let written = src.exprs.iter().map(|e| {
                let w = Written {
                    arc: e.arc,
                    functor: (e.functor.0.as_str(), e.functor.1),
                    inner: e.inner.map(|(n, a)| (n.as_str(), a)),
                };
                (w, at(e.span))
            });
            sit_places_text(&arcs, written)
        })
        .collect();
    entries.join("#")
}
