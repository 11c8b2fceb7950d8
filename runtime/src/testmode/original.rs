//! The original's test mode, by situation type, for `sitlogc run --legacy`:
//! which terms a situation reads from the script (or the prompt) and what it
//! is given, as the original's `src/in_communication.pl` does in test mode
//! (`communication_int/3`, one clause per situation type), then one more
//! term read for each variable of what it is given (the original's
//! `input_values/3`).
//!
//! [`ORIGINAL_TYPES`] is that table, read from the original (the probe
//! `tests/conformance/original/wrapping.pl` prints it from
//! `$SITLOG_HOME/src/in_communication.pl`; the test below compares).
//! [`OriginalTestMode`] applies it around a perception that reads as our
//! own test mode does (`said(T)` for `listening` and `nkeyboard`): it takes
//! the typed term back and gives it as the original would. Invariant: every
//! type in the table reads, builds and binds exactly as the original's
//! clause for it in test mode; a type the table lacks is an error, as the
//! original has no clause for it.

use crate::machine::{Perceived, Perception};
use crate::store::Store;
use crate::term::{Term, Value};
use sitlog_syntax::Atom;

/// What a situation of one type reads and is given, in the original's test
/// mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reading {
    /// One term read, given as it is.
    AsRead,
    /// One term read, given as `F(Term)`.
    Wrapped(&'static str),
    /// `N` terms read, given as `F(T1, ..., TN)`.
    Tuple(&'static str, usize),
    /// `N` terms read and dropped; an unbound variable is given (and then,
    /// like every variable of what is given, read).
    Unbound(usize),
    /// Nothing read; `F(_)` given.
    Open(&'static str),
    /// The first expectation `cam_to_nav(X,Y,Z,T,A,B,_)` gives the first six
    /// arguments, one term read the seventh.
    CamToNav,
    /// The first expectation `cmds2dms(I,_)` gives `I` (else unbound);
    /// nothing read; `cmds2dms(I,_)` given.
    Cmds2Dms,
    /// The single expectation is `F(.., _)` (arity `N`): one term read
    /// replaces its last argument, the others are kept.
    LastArg(&'static str, usize),
    /// The single expectation is `direction(_)`: one number read, given
    /// rounded to tenths as `direction(round(X*10)/10)`.
    Direction,
    /// Calls a robot service (ROS) even in test mode: the original stops
    /// with an error outside a robot.
    Ros,
}

/// What the original's clause needs of the expectations (its head's
/// pattern) before it reads; otherwise it fails.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Needs {
    Anything,
    /// At least `N` expectations.
    AtLeast(usize),
    /// Exactly one expectation, which unifies with `F(_, ..)` of arity `N`.
    Single(&'static str, usize),
    /// One of the expectations unifies with `F(_, ..)` of arity `N`.
    Member(&'static str, usize),
}

/// One situation type of the original's test mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OriginalType {
    pub name: &'static str,
    pub arity: usize,
    pub reading: Reading,
    pub needs: Needs,
}

const fn t(name: &'static str, arity: usize, reading: Reading) -> OriginalType {
    OriginalType {
        name,
        arity,
        reading,
        needs: Needs::Anything,
    }
}

const fn n(name: &'static str, arity: usize, reading: Reading, needs: Needs) -> OriginalType {
    OriginalType {
        name,
        arity,
        reading,
        needs,
    }
}

use Reading::*;

/// Every situation type of the original's test mode (the clauses of
/// `communication_int/3` in `src/in_communication.pl`, in its order).
/// `neutral` is not here: the machine runs neutral situations itself.
pub const ORIGINAL_TYPES: &[OriginalType] = &[
    t("keyboard", 0, AsRead),
    t("click", 0, AsRead),
    t("gfOrders", 0, Open("gfOrder")),
    t("get_dms", 0, Cmds2Dms),
    t("translating_nav", 0, CamToNav),
    t("speech", 0, AsRead),
    t("nkeyboard", 0, Wrapped("said")),
    t("nlistening", 1, Wrapped("said")),
    t("listening", 1, Wrapped("said")),
    t("listening", 0, AsRead),
    t("listening_softloud", 0, AsRead),
    t("doas", 0, Wrapped("doas")),
    t("speakerid", 0, Wrapped("speaker")),
    t("query_speakerid", 1, AsRead),
    t("seeing", 0, AsRead),
    t("vision", 0, AsRead),
    t("vision_simple", 0, AsRead),
    t("pulso", 0, AsRead),
    t("catching", 0, AsRead),
    t("detect_people", 0, AsRead),
    n("save_face", 0, AsRead, Needs::Member("save", 1)),
    t("learn_faces", 0, AsRead),
    t("recognized_face", 0, AsRead),
    t("object_analyzing", 3, AsRead),
    t("uobject_analyzing", 0, AsRead),
    t("plane_analyzing", 0, AsRead),
    t("yolo_object_detection", 2, AsRead),
    t("plane_recognition", 4, AsRead),
    t("following", 0, AsRead),
    t("waiting", 0, AsRead),
    t("person_detect", 0, AsRead),
    t("grasping", 0, AsRead),
    n("walking", 0, AsRead, Needs::AtLeast(3)),
    n("displacing", 0, AsRead, Needs::AtLeast(4)),
    n("position", 0, AsRead, Needs::AtLeast(3)),
    n(
        "directions",
        0,
        LastArg("directions", 1),
        Needs::Single("directions", 1),
    ),
    n(
        "directions_pre",
        0,
        LastArg("directions", 1),
        Needs::Single("directions", 1),
    ),
    n("direction", 0, Direction, Needs::Single("direction", 1)),
    n(
        "calculate_distance",
        0,
        LastArg("distance_to", 2),
        Needs::Single("distance_to", 2),
    ),
    n("positionxyz", 0, Tuple("pos", 3), Needs::Single("pos", 3)),
    t("turning", 0, Unbound(0)),
    t("taking", 0, AsRead),
    t("grasping_obj", 0, Unbound(1)),
    t("detect_head", 0, AsRead),
    t("detect_table", 0, AsRead),
    t("detect_face", 0, AsRead),
    t("recognize_face", 0, AsRead),
    t("detect_body", 1, Wrapped("detected")),
    t("memorize_body", 3, Wrapped("said")),
    t("recognize_body", 2, Wrapped("said")),
    t("detect_gesture", 2, Wrapped("detected")),
    t("detect_any_gesture", 1, Wrapped("detected")),
    t("analyzing_crowd", 1, Wrapped("detected")),
    t("detect_crowd", 1, Wrapped("detected")),
    t("describe_body", 2, Wrapped("said")),
    t("waiting_door", 0, AsRead),
    t("detect_polo", 0, AsRead),
    t("navigate_status", 0, AsRead),
    t("follow_status", 0, AsRead),
    t("qr_recognition", 0, AsRead),
    t("recognize_follow", 0, AsRead),
    t("find_follow", 0, AsRead),
    t("see_pointing_follow", 0, Tuple("pointing_coords", 3)),
    t("see_gesture_op", 1, AsRead),
    t("detect_face_cognitive", 1, AsRead),
    t("identify_face_cognitive", 2, AsRead),
    t("gesture_op", 0, AsRead),
    t("person_pose_op", 0, Ros),
    t("pointing_op", 0, AsRead),
    t("whereiam", 0, AsRead),
    t("whereiam_dummy", 0, AsRead),
];

/// The table's entry for a situation type (its name and arity).
pub fn original_type(store: &Store, ty: Term) -> Option<&'static OriginalType> {
    let (name, arity) = store.functor(ty)?;
    ORIGINAL_TYPES
        .iter()
        .find(|e| e.name == name.as_str() && e.arity == arity)
}

/// The term our own test mode read, from what it delivered for `ty`
/// (`said(T)` for `listening` and `nkeyboard`, see [`super::deliver_typed`]).
fn typed_term(store: &Store, ty: Term, delivered: Term) -> Term {
    if super::wraps_said(store, ty) {
        if let Some(args) = store.compound_args(delivered, Atom::intern("said"), 1) {
            return args[0];
        }
    }
    delivered
}

/// The unbound variables of `t`, left to right, each once (the order of
/// the original's `listPreds2list/4` with `filter_duplicates/3`).
pub fn variables(store: &Store, t: Term) -> Vec<Term> {
    let mut out: Vec<Term> = Vec::new();
    let mut stack = vec![t];
    while let Some(t) = stack.pop() {
        match store.value(t) {
            Value::Var(v) => {
                let v = Term::from(v);
                if !out.contains(&v) {
                    out.push(v);
                }
            }
            Value::Compound(_, args) => stack.extend(args.iter().rev()),
            _ => {}
        }
    }
    out
}

/// SWI-Prolog's `round(X*10)/10` (`direction`): `None` when `x` is not a
/// number.
fn tenths(store: &Store, x: Term) -> Option<Term> {
    let scaled = match store.value(x) {
        Value::Int(i) => i.checked_mul(10)?,
        Value::Float(f) => {
            let r = (f * 10.0).round();
            if !r.is_finite() || r.abs() >= 9.2e18 {
                return None;
            }
            r as i64
        }
        _ => return None,
    };
    Some(if scaled % 10 == 0 {
        Term::int(scaled / 10)
    } else {
        Term::float(scaled as f64 / 10.0)
    })
}

/// A fresh copy of the pattern `F(_, ..)` of arity `arity`.
fn pattern(store: &mut Store, name: &str, arity: usize) -> Term {
    let args: Vec<Term> = (0..arity).map(|_| store.new_var()).collect();
    if arity == 0 {
        Term::atom(Atom::intern(name))
    } else {
        store.compound(Atom::intern(name), &args)
    }
}

/// Whether `t` unifies with `F(_, ..)` (nothing stays bound).
fn fits(store: &mut Store, t: Term, name: &str, arity: usize) -> bool {
    let p = pattern(store, name, arity);
    let mark = store.mark();
    let ok = store.unify(t, p);
    store.undo_to(mark);
    ok
}

/// Whether the expectations meet what the type's clause needs.
fn needs_met(store: &mut Store, needs: Needs, expectations: &[Term]) -> bool {
    match needs {
        Needs::Anything => true,
        Needs::AtLeast(k) => expectations.len() >= k,
        Needs::Single(name, arity) => {
            expectations.len() == 1 && fits(store, expectations[0], name, arity)
        }
        Needs::Member(name, arity) => expectations.iter().any(|&e| fits(store, e, name, arity)),
    }
}

/// Why a reading stopped: what the inner perception said instead of a term
/// (end of input, again), or an error.
pub enum Stop {
    Perceived(Perceived),
    Error(String),
}

impl From<String> for Stop {
    fn from(e: String) -> Stop {
        Stop::Error(e)
    }
}

/// What a situation of type `ty` (the table's `entry`) is given, before the
/// variables of it are read: `read` gives the terms typed, in turn.
pub fn build(
    store: &mut Store,
    ty: Term,
    entry: &OriginalType,
    expectations: &[Term],
    read: &mut dyn FnMut(&mut Store) -> Result<Term, Stop>,
) -> Result<Term, Stop> {
    let named = |store: &Store, what: &str| {
        format!(
            "situation type `{}`: the original's test mode {what}",
            store.writeq(ty)
        )
    };
    if !needs_met(store, entry.needs, expectations) {
        let needs = match entry.needs {
            Needs::Anything => String::new(),
            Needs::AtLeast(k) => format!("at least {k} expectations"),
            Needs::Single(f, a) => format!("a single expectation {f}/{a}"),
            Needs::Member(f, a) => format!("an expectation {f}/{a}"),
        };
        let what = format!("needs {needs} (its clause of communication_int/3 fails)");
        return Err(Stop::Error(named(store, &what)));
    }
    // The arguments of the first expectation `F(..)`, when there is one.
    let args_of = |store: &mut Store, f: &str, arity: usize| -> Option<Vec<Term>> {
        let e = expectations
            .iter()
            .copied()
            .find(|&e| fits(store, e, f, arity))?;
        let e = store.deref(e);
        match store.value(e) {
            Value::Compound(_, args) => Some(args.to_vec()),
            _ => Some((0..arity).map(|_| store.new_var()).collect()),
        }
    };
    Ok(match entry.reading {
        AsRead => read(store)?,
        Wrapped(f) => {
            let x = read(store)?;
            store.compound(Atom::intern(f), &[x])
        }
        Tuple(f, k) => {
            let mut items = Vec::with_capacity(k);
            for _ in 0..k {
                items.push(read(store)?);
            }
            store.compound(Atom::intern(f), &items)
        }
        Unbound(k) => {
            for _ in 0..k {
                read(store)?;
            }
            store.new_var()
        }
        Open(f) => {
            let v = store.new_var();
            store.compound(Atom::intern(f), &[v])
        }
        CamToNav => {
            let Some(mut args) = args_of(store, "cam_to_nav", 7) else {
                return Err(Stop::Error(named(
                    store,
                    "needs an expectation cam_to_nav/7",
                )));
            };
            args[6] = read(store)?;
            store.compound(Atom::intern("cam_to_nav"), &args)
        }
        Cmds2Dms => {
            let input = match args_of(store, "cmds2dms", 2) {
                Some(args) => args[0],
                None => store.new_var(),
            };
            let dms = store.new_var();
            store.compound(Atom::intern("cmds2dms"), &[input, dms])
        }
        LastArg(f, k) => {
            let mut args = args_of(store, f, k).unwrap_or_default();
            args.resize_with(k, || Term::NIL);
            args[k - 1] = read(store)?;
            store.compound(Atom::intern(f), &args)
        }
        Direction => {
            let x = read(store)?;
            let Some(a) = tenths(store, x) else {
                let what = format!(
                    "computes round(X*10)/10 of the input, and `{}` is not a number",
                    store.writeq(x)
                );
                return Err(Stop::Error(named(store, &what)));
            };
            store.compound(Atom::intern("direction"), &[a])
        }
        Ros => {
            let what = "calls a ROS service for it (rosswipl_call_service/3), which needs a robot";
            return Err(Stop::Error(named(store, what)));
        }
    })
}

/// A perception that gives each situation what the original's test mode
/// would, from the terms `inner` reads (see the module doc).
pub struct OriginalTestMode {
    inner: Box<dyn Perception>,
}

impl OriginalTestMode {
    pub fn new(inner: Box<dyn Perception>) -> OriginalTestMode {
        OriginalTestMode { inner }
    }
}

impl Perception for OriginalTestMode {
    fn perceive(
        &mut self,
        store: &mut Store,
        ty: Term,
        expectations: &[Term],
    ) -> Result<Perceived, String> {
        let ty = store.deref(ty);
        let Some(entry) = original_type(store, ty) else {
            return Err(format!(
                "situation type `{}`: the original's test mode has no interpreter for it \
                 (no clause of communication_int/3 in src/in_communication.pl)",
                store.writeq(ty)
            ));
        };
        let inner = &mut self.inner;
        let mut read = |store: &mut Store| -> Result<Term, Stop> {
            match inner.perceive(store, ty, expectations)? {
                Perceived::Input(t) => Ok(typed_term(store, ty, t)),
                other => Err(Stop::Perceived(other)),
            }
        };
        let result = build(store, ty, entry, expectations, &mut read).and_then(|given| {
            // The original's input_values/3: one more term read for each
            // variable of what is given, left to right.
            for v in variables(store, given) {
                let x = read(store)?;
                store.bind(v, x);
            }
            Ok(given)
        });
        match result {
            Ok(given) => Ok(Perceived::Input(given)),
            Err(Stop::Perceived(p)) => Ok(p),
            Err(Stop::Error(e)) => Err(e),
        }
    }

    fn waiting_at(&mut self, store: &Store, dm: Term, situation: Term) {
        self.inner.waiting_at(store, dm, situation);
    }

    fn uses_waiting_at(&self) -> bool {
        self.inner.uses_waiting_at()
    }

    fn unmatched_is_news(&self) -> bool {
        self.inner.unmatched_is_news()
    }
}

#[cfg(test)]
mod tests;
