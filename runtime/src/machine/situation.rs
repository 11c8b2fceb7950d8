//! How the machine names a program's parts: DM and situation indices,
//! the [`Kind`] of a situation, and the fields of a situation [`Instance`],
//! made fresh from the situation's template ([`Instance::fresh`], the one
//! way both back ends instantiate; a compiled program reads its templates
//! from text once, [`read_templates`]).

use crate::store::Store;
use crate::term::Term;
use sitlog_syntax::Atom;

/// Index of a DM in its program.
pub type DmIx = u32;
/// Index of a situation in its DM (0 is the initial situation).
pub type SitIx = u32;

/// What kind of situation, as its `type` says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Final,
    Recursive,
    /// Any other type: the name of a perceptual interpreter.
    Perceptual,
}

/// The fields of a situation instance, as [`DmProgram::instantiate`](super::DmProgram::instantiate) returns
/// them: fresh terms sharing variables with a fresh copy of the DM head.
#[derive(Clone, Copy, Debug)]
pub struct Instance {
    pub head: Term,
    pub id: Term,
    pub type_term: Term,
    pub in_arg: Option<Term>,
    pub out_arg: Option<Term>,
    pub prog: Option<Term>,
    pub embedded_dm: Option<Term>,
    pub diag_mod: Option<Term>,
    /// The arcs as a list of `'$arc'(Expectation, Action, Next)`.
    pub arcs: Term,
}

/// The atom a situation template has in place of an absent optional field
/// (`in_arg`, `out_arg`, `prog`, `embedded_dm`, `diag_mod`).
pub fn none_marker() -> Atom {
    Atom::intern("$none")
}

impl Instance {
    /// The instance whose fields are the nine arguments of `t`, a fresh copy
    /// of a situation template (head, id, type, in_arg, out_arg, prog,
    /// embedded_dm, diag_mod, arcs; [`none_marker`] for an absent one).
    pub fn of_template(store: &Store, t: Term) -> Instance {
        let a = store.args(t);
        let none = Term::atom(none_marker());
        let opt = |x: Term| (x != none).then_some(x);
        Instance {
            head: a[0],
            id: a[1],
            type_term: a[2],
            in_arg: opt(a[3]),
            out_arg: opt(a[4]),
            prog: opt(a[5]),
            embedded_dm: opt(a[6]),
            diag_mod: opt(a[7]),
            arcs: a[8],
        }
    }

    /// A fresh instance of `template` (D-7): a `copy_term` of it, as the
    /// interpreter makes one.
    pub fn fresh(store: &mut Store, template: Term) -> Instance {
        let t = store.copy_term(template);
        Instance::of_template(store, t)
    }
}

/// Reads the templates of a DM's situations (`None`: a situation that is
/// never instantiated) into `store`, the program's store before it is
/// frozen. The texts are `writeq` texts the compiler checked read back as
/// the template itself, so a text that does not read is the compiler's bug,
/// reported with the text.
pub fn read_templates(store: &mut Store, texts: &[Option<&str>]) -> Vec<Option<Term>> {
    texts
        .iter()
        .map(|text| {
            text.map(|text| match store.parse(text) {
                Ok((t, _)) if store.args(t).len() == 9 => t,
                Ok(_) => panic!("a generated situation template has not nine fields: {text}"),
                Err(e) => panic!("a generated situation template does not read: {e}: {text}"),
            })
        })
        .collect()
}
