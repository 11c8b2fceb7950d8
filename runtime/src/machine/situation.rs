//! How the machine names a program's parts: DM and situation indices,
//! the [`Kind`] of a situation, and the fields of a situation [`Instance`],
//! made fresh from the situation's template ([`Instance::fresh`], the one
//! way both back ends instantiate; a compiled program reads its templates
//! from text once, [`read_templates`]), and a compiled program's table of
//! its situations ([`SitRow`] per situation, [`SitTable`] for the program:
//! kind, id functor, whether it runs as code, where it is written), read by
//! the generic `DmProgram` methods instead of a `match` per DM.

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

/// Reads the templates of a DM's situations (`""`: a situation that is
/// never instantiated, `None` here) into `store`, the program's store
/// before it is frozen. The texts are `writeq` texts the compiler checked
/// read back as the template itself, so a text that does not read is the
/// compiler's bug, reported with the text.
pub fn read_templates(store: &mut Store, texts: &[&str]) -> Vec<Option<Term>> {
    texts
        .iter()
        .map(|&text| {
            (!text.is_empty()).then(|| match store.parse(text) {
                Ok((t, _)) if store.args(t).len() == 9 => t,
                Ok(_) => panic!("a generated situation template has not nine fields: {text}"),
                Err(e) => panic!("a generated situation template does not read: {e}: {text}"),
            })
        })
        .collect()
}

/// Reads the program's constants (ground terms its code names `k[i]`) from
/// their `writeq` texts into `store`, the program's store before it is
/// frozen. The compiler checked each text reads back as the constant (one
/// that does not is built by code after this, its text `[]`), so a text
/// that does not read is the compiler's bug, reported with the text.
pub fn read_consts<const N: usize>(store: &mut Store, texts: &[&str; N]) -> [Term; N] {
    texts.map(|text| match store.parse(text) {
        // A pattern (`Cx::fill`'s): marked so that filling it walks its
        // holes only.
        Ok((t, _)) if text.contains("$hole") => {
            super::cx::mark_pattern(store, t);
            t
        }
        Ok((t, _)) => t,
        Err(e) => panic!("a generated constant does not read: {e}: {text}"),
    })
}

/// How a compiled situation's id takes a value, as the interpreter's plan
/// of it does (`sitlog_compiler::mir`'s `select` / `pattern`).
#[derive(Clone, Copy, Debug)]
enum IdSelect {
    /// An atom id: the functor says it all.
    Name,
    /// Distinct variables and atomic constants: each constant unified with
    /// the value's argument there.
    Args,
    /// Any other compound: a fresh copy unified with the value.
    Pattern,
}

/// A compiled program's situation templates (each DM module's
/// `TEMPLATES`, read once into the program's store, [`read_templates`]),
/// by DM and situation, with how each id selects.
#[derive(Clone, Debug, Default)]
pub struct Templates {
    dms: Vec<Vec<Option<(Term, IdSelect)>>>,
}

impl Templates {
    /// Reads DM number `i`'s templates from `dms[i]` into `store`.
    pub fn read(store: &mut Store, dms: &[&[&str]]) -> Templates {
        let dms = dms
            .iter()
            .map(|texts| {
                read_templates(store, texts)
                    .into_iter()
                    .map(|t| t.map(|t| (t, id_select(store, store.args(t)[1]))))
                    .collect()
            })
            .collect();
        Templates { dms }
    }

    /// A fresh instance of situation `sit` of DM `dm` from its template
    /// (`None`: it has none).
    pub fn instance(&self, dm: DmIx, sit: SitIx, store: &mut Store) -> Option<Instance> {
        let (t, _) = self.dms[dm as usize][sit as usize]?;
        Some(Instance::fresh(store, t))
    }

    /// Whether compiled situation `sit` of DM `dm`, whose id has the
    /// principal functor of `value`, is selected by `value`
    /// ([`DmProgram::select_compiled`](super::DmProgram::select_compiled)),
    /// decided on its template's id as the interpreter decides on its plan:
    /// `Args` ids by their constants, other compound ids as a fresh copy
    /// unified with the value (bindings kept when it is taken). `None`: the
    /// situation has no template (the program's code decides).
    pub fn select(&self, dm: DmIx, sit: SitIx, value: Term, store: &mut Store) -> Option<bool> {
        let (t, how) = self.dms[dm as usize][sit as usize]?;
        let id = store.args(t)[1];
        Some(match how {
            IdSelect::Name => true,
            IdSelect::Args => {
                let n = store.args(id).len();
                (0..n).all(|i| {
                    let c = store.args(id)[i];
                    if matches!(store.value(c), crate::term::Value::Var(_)) {
                        return true;
                    }
                    let x = store.args(value)[i];
                    store.unify(x, c)
                })
            }
            IdSelect::Pattern => {
                let c = store.copy_term(id);
                store.unify(value, c)
            }
        })
    }
}

/// How the id `id` (a template's) selects: an atom, a simple compound
/// (distinct variables and atoms or numbers), another compound.
fn id_select(store: &Store, id: Term) -> IdSelect {
    use crate::term::Value;
    let Value::Compound(_, args) = store.value(id) else {
        return IdSelect::Name;
    };
    let mut seen = Vec::new();
    let simple = args.iter().all(|&a| match store.value(a) {
        Value::Var(v) if !seen.contains(&v) => {
            seen.push(v);
            true
        }
        Value::Atom(_) | Value::Int(_) | Value::Float(_) => true,
        _ => false,
    });
    if simple {
        IdSelect::Args
    } else {
        IdSelect::Pattern
    }
}

/// A situation's row in a compiled program's table (each DM module's
/// `SITUATIONS`, by situation index): what the machine asks of a situation
/// before it runs it.
#[derive(Clone, Copy, Debug)]
pub struct SitRow {
    pub kind: Kind,
    /// Its id's name and arity (`None`: the id is a variable).
    pub id: Option<(&'static str, usize)>,
    /// Whether it runs as code (its id is then `id`'s functor:
    /// [`DmProgram::compiled_id`](super::DmProgram::compiled_id)).
    pub code: bool,
    /// Where it is written: line and column in its DM's file.
    pub at: (u32, u32),
    /// Where its in_arg is written, when it has one ([`SitRow::in_arg`]).
    pub in_arg_at: Option<(u32, u32)>,
}

impl SitRow {
    /// This row, its in_arg written at `line`, `col` (the warning of an
    /// in_arg skipped points there: [`SitTable::in_arg_location`]).
    pub const fn in_arg(self, line: u32, col: u32) -> SitRow {
        SitRow {
            in_arg_at: Some((line, col)),
            ..self
        }
    }

    /// A situation that runs as code, its id named `name/arity`.
    pub const fn code(kind: Kind, name: &'static str, arity: usize, line: u32, col: u32) -> SitRow {
        SitRow {
            kind,
            id: Some((name, arity)),
            code: true,
            at: (line, col),
            in_arg_at: None,
        }
    }

    /// A situation the machine instantiates from its template.
    pub const fn template(
        kind: Kind,
        id: Option<(&'static str, usize)>,
        line: u32,
        col: u32,
    ) -> SitRow {
        SitRow {
            kind,
            id,
            code: false,
            at: (line, col),
            in_arg_at: None,
        }
    }
}

/// What a compiled program says of one of its DMs (a row of its `DMS`):
/// its name, the file it is written in, and its head's arity when the head
/// is the name alone or the name with distinct variables (`None`: another
/// head, made by the DM's own code). Read once into a [`SitTable`].
#[derive(Clone, Copy, Debug)]
pub struct DmRow {
    pub name: &'static str,
    pub file: &'static str,
    pub head: Option<usize>,
}

impl DmRow {
    /// DM `name`, written in `file`, its head `name(V1, .., Vn)` of `n`
    /// distinct variables (`Some(0)`: the atom `name`) or another (`None`).
    pub const fn new(name: &'static str, file: &'static str, head: Option<usize>) -> DmRow {
        DmRow { name, file, head }
    }
}

/// A compiled program's DMs read once when it is built: their situations'
/// table and templates (the program's `DMS`, and each DM's `SITUATIONS`
/// and `TEMPLATES`, in load order).
pub fn read_dms(
    store: &mut Store,
    dms: &[DmRow],
    tables: &[(&[SitRow], &[&str])],
) -> (Templates, SitTable) {
    let templates = tables.iter().map(|&(_, texts)| texts).collect::<Vec<_>>();
    let sits = dms
        .iter()
        .zip(tables)
        .map(|(dm, &(rows, _))| (dm, rows))
        .collect::<Vec<_>>();
    (Templates::read(store, &templates), SitTable::new(&sits))
}

/// One situation of a [`SitTable`], its id's name interned.
#[derive(Clone, Copy, Debug)]
struct SitEntry {
    kind: Kind,
    id: Option<(Atom, usize)>,
    code: bool,
    at: (u32, u32),
    in_arg_at: Option<(u32, u32)>,
}

/// Where a situation and its in_arg (when it has one) are written: line
/// and column ([`SitTable::positions`]).
pub(super) type SitPositions = ((u32, u32), Option<(u32, u32)>);

/// A compiled program's situations, by DM and situation index (the rows of
/// each DM's `SITUATIONS`, names interned once when the program is built).
#[derive(Clone, Debug, Default)]
pub struct SitTable {
    /// Per DM: its file, its situations.
    dms: Vec<(&'static str, Vec<SitEntry>)>,
    /// Per DM: where its arcs and constructs of L are written
    /// ([`SitTable::with_places`]).
    places: &'static [&'static str],
    /// Per DM: its name, interned, and its head's arity ([`DmRow::head`]).
    heads: Vec<(Atom, Option<usize>)>,
}

impl SitTable {
    /// The table of a program whose DM number `i` is `dms[i].0` and has
    /// the rows `dms[i].1`.
    pub fn new(dms: &[(&DmRow, &[SitRow])]) -> SitTable {
        let heads = dms
            .iter()
            .map(|(dm, _)| (Atom::intern(dm.name), dm.head))
            .collect();
        let dms = dms
            .iter()
            .map(|&(dm, rows)| {
                let rows = rows
                    .iter()
                    .map(|r| SitEntry {
                        kind: r.kind,
                        id: r.id.map(|(name, arity)| (Atom::intern(name), arity)),
                        code: r.code,
                        at: r.at,
                        in_arg_at: r.in_arg_at,
                    })
                    .collect();
                (dm.file, rows)
            })
            .collect();
        SitTable {
            dms,
            heads,
            places: &[],
        }
    }

    /// This table, DM `i`'s arcs and constructs of L written where
    /// `places[i]` says (the text `machine::places` reads, only when a
    /// run-time error is reported: its module doc).
    pub fn with_places(self, places: &'static [&'static str]) -> SitTable {
        SitTable { places, ..self }
    }

    /// DM `dm`'s file and places text ([`SitTable::with_places`]; empty
    /// when the program gave none); `None` for no such DM.
    pub(super) fn file_and_places(&self, dm: DmIx) -> Option<(&'static str, &'static str)> {
        let file = self.dms.get(dm as usize)?.0;
        Some((file, self.places.get(dm as usize).copied().unwrap_or("")))
    }

    /// Where situation `sit` of DM `dm` and its in_arg are written (line,
    /// column); `None` for no such situation.
    pub(super) fn positions(&self, dm: DmIx, sit: SitIx) -> Option<SitPositions> {
        let e = self.dms.get(dm as usize)?.1.get(sit as usize)?;
        Some((e.at, e.in_arg_at))
    }

    /// The name of DM `dm`.
    pub fn dm_name(&self, dm: DmIx) -> Atom {
        match self.heads.get(dm as usize) {
            Some(&(name, _)) => name,
            None => panic!("no DM number {dm}"),
        }
    }

    /// A fresh head of DM `dm`, when it is its name alone or its name with
    /// distinct variables (`None`: another head, [`DmRow::head`]).
    pub fn fresh_head(&self, dm: DmIx, store: &mut Store) -> Option<Term> {
        let (name, arity) = match self.heads.get(dm as usize) {
            Some(&(name, arity)) => (name, arity?),
            None => panic!("no DM number {dm}"),
        };
        let mut vars = [Term::NIL; 16];
        if arity <= vars.len() {
            for v in &mut vars[..arity] {
                *v = store.new_var();
            }
            Some(store.compound(name, &vars[..arity]))
        } else {
            let vars: Vec<Term> = (0..arity).map(|_| store.new_var()).collect();
            Some(store.compound(name, &vars))
        }
    }

    #[inline]
    fn entry(&self, dm: DmIx, sit: SitIx) -> &SitEntry {
        &self.dms[dm as usize].1[sit as usize]
    }

    /// How many situations DM `dm` has.
    pub fn count(&self, dm: DmIx) -> usize {
        self.dms[dm as usize].1.len()
    }

    pub fn kind(&self, dm: DmIx, sit: SitIx) -> Kind {
        self.entry(dm, sit).kind
    }

    /// Whether the situation's id may unify with a value of principal
    /// functor `functor` (D-21's cheap filter; a variable id: always).
    pub fn may_select(&self, dm: DmIx, sit: SitIx, functor: Option<(Atom, usize)>) -> bool {
        match self.entry(dm, sit).id {
            Some(id) => functor == Some(id),
            None => true,
        }
    }

    /// Where the situation is written (`file:line:col`).
    pub fn location(&self, dm: DmIx, sit: SitIx) -> String {
        let (line, col) = self.entry(dm, sit).at;
        format!("{}:{line}:{col}", self.dms[dm as usize].0)
    }

    /// Where the situation's in_arg is written (`file:line:col`), when
    /// its row says ([`SitRow::in_arg`]).
    pub fn in_arg_location(&self, dm: DmIx, sit: SitIx) -> Option<String> {
        let (line, col) = self.entry(dm, sit).in_arg_at?;
        Some(format!("{}:{line}:{col}", self.dms[dm as usize].0))
    }

    /// Its id's functor when it runs as code.
    #[inline]
    pub fn compiled_id(&self, dm: DmIx, sit: SitIx) -> Option<(Atom, usize)> {
        let e = self.entry(dm, sit);
        if e.code {
            e.id
        } else {
            None
        }
    }
}
