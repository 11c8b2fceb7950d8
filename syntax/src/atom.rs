//! Global atom interner: every atom of every program, KB and input term is a `u32`.
//!
//! Atoms are compared by id on the hot path; the text is only needed to print.
//! Interned strings are leaked and never collected (as in most Prolog systems
//! without atom GC); a long-running task reading unbounded distinct atoms from
//! input grows by their text.
//!
//! An atom's text is read without a lock, a thread-local or a hash
//! ([`Atom::as_str`], issue 37: a `say` writes a word per item): every name is
//! also published, once, in an append-only table of segments of doubling
//! size (`NAMES`), each slot set once. Invariant: an atom handed out by
//! [`Atom::intern`] has its name in the table (published under the
//! interner's write lock, before the lock is released, and so before any
//! other thread can learn its id); a slot not set yet (an atom of the
//! predefined table before the interner was first used) is read from the
//! interner.

use std::collections::HashMap;
use std::fmt;
use std::sync::{OnceLock, RwLock};

/// An interned atom (Prolog constant name or functor name).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Atom(u32);

struct Interner {
    names: Vec<&'static str>,
    ids: HashMap<&'static str, u32>,
}

fn interner() -> &'static RwLock<Interner> {
    static INTERNER: OnceLock<RwLock<Interner>> = OnceLock::new();
    INTERNER.get_or_init(|| {
        let mut interner = Interner {
            names: Vec::with_capacity(1024),
            ids: HashMap::with_capacity(1024),
        };
        for name in PREDEFINED {
            let id = interner.names.len() as u32;
            interner.names.push(name);
            interner.ids.insert(name, id);
            publish(id, name);
        }
        RwLock::new(interner)
    })
}

macro_rules! predefined_atoms {
    ($($konst:ident = $text:literal,)*) => {
        const PREDEFINED: &[&str] = &[$($text,)*];
        #[allow(dead_code, non_camel_case_types, clippy::upper_case_acronyms)]
        enum PredefinedIndex { $($konst,)* }
        /// Atoms with fixed ids, usable without touching the interner.
        pub mod atoms {
            use super::Atom;
            $(pub const $konst: Atom = Atom(super::PredefinedIndex::$konst as u32);)*
        }
    };
}

predefined_atoms! {
    NIL = "[]",
    DOT = ".",
    CURLY = "{}",
    COMMA = ",",
    BAR = "|",
    MINUS = "-",
    PLUS = "+",
    TRUE = "true",
    FALSE = "false",
    FAIL = "fail",
    EMPTY = "empty",
    NONE = "none",
    COLON = ":",
    ARROW = "=>",
    DOUBLE_ARROW = "==>",
    DEFAULT_ARROW = "=>>",
    IF_THEN = "->",
    SEMICOLON = ";",
    OTHERWISE = "otherwise",
    EQUALS = "=",
    IS = "is",
    APPLY = "apply",
    ASSIGN = "assign",
    GET = "get",
    SET = "set",
    INC = "inc",
    WHEN = "when",
    NOT = "not",
    DIAG_MOD = "diag_mod",
    ID = "id",
    TYPE = "type",
    ARCS = "arcs",
    PROG = "prog",
    IN_ARG = "in_arg",
    OUT_ARG = "out_arg",
    EMBEDDED_DM = "embedded_dm",
    NEUTRAL = "neutral",
    RECURSIVE = "recursive",
    FINAL = "final",
    END_OF_FILE = "end_of_file",
    UNKNOWN = "unknown",
    YES = "yes",
    NO = "no",
    TOP = "top",
    MAIN = "main",
    EQ_EQ = "==",
    NOT_EQ_EQ = "\\==",
    LESS = "<",
    GREATER = ">",
    LESS_EQ = "=<",
    GREATER_EQ = ">=",
    MEMBER = "member",
    NOT_MEMBER = "not_member",
    ERROR = "error",
    CUT = "!",
}

impl Atom {
    /// Interns `name`, returning its atom.
    pub fn intern(name: &str) -> Atom {
        // A small direct-mapped per-thread cache in front of the shared
        // table: readers intern the same few names over and over.
        let slot = cache_slot(name);
        let hit = INTERN_CACHE.with(|cache| {
            let cache = cache.borrow();
            match cache[slot] {
                Some((text, atom)) if text == name => Some(atom),
                _ => None,
            }
        });
        if let Some(atom) = hit {
            return atom;
        }
        let atom = Atom::intern_shared(name);
        INTERN_CACHE.with(|cache| {
            cache.borrow_mut()[slot] = Some((atom.as_str(), atom));
        });
        atom
    }

    fn intern_shared(name: &str) -> Atom {
        {
            let guard = interner().read().unwrap_or_else(|e| e.into_inner());
            if let Some(&id) = guard.ids.get(name) {
                return Atom(id);
            }
        }
        let mut guard = interner().write().unwrap_or_else(|e| e.into_inner());
        if let Some(&id) = guard.ids.get(name) {
            return Atom(id);
        }
        let leaked: &'static str = Box::leak(name.to_owned().into_boxed_str());
        let id = u32::try_from(guard.names.len()).expect("more than 2^32 atoms");
        guard.names.push(leaked);
        guard.ids.insert(leaked, id);
        publish(id, leaked);
        Atom(id)
    }

    /// The atom's text: a read of the published table (`NAMES`), no
    /// lock, no thread-local, no hash.
    #[inline]
    pub fn as_str(self) -> &'static str {
        match name_slot(self.0).and_then(OnceLock::get) {
            Some(name) => name,
            None => self.as_str_unpublished(),
        }
    }

    /// [`Atom::as_str`] of an atom whose name is not in the table yet: a
    /// predefined atom before the interner was first used (which
    /// publishes them all).
    #[cold]
    #[inline(never)]
    fn as_str_unpublished(self) -> &'static str {
        let guard = interner().read().unwrap_or_else(|e| e.into_inner());
        guard.names[self.0 as usize]
    }

    /// The interner index (stable for the life of the process).
    pub fn index(self) -> u32 {
        self.0
    }

    /// Rebuilds an atom from [`Atom::index`]; `None` if no such atom was interned.
    pub fn from_index(index: u32) -> Option<Atom> {
        let guard = interner().read().unwrap_or_else(|e| e.into_inner());
        ((index as usize) < guard.names.len()).then_some(Atom(index))
    }
}

const CACHE_SLOTS: usize = 512;

/// Slots in the table's first segment; segment `k` has `SEGMENT0 << k`.
const SEGMENT0: usize = 1024;
/// Segments: `SEGMENT0 * (2^SEGMENTS - 1)` slots, more than the `2^32`
/// atoms an id can name.
const SEGMENTS: usize = 23;

/// One segment of the table: a slot per atom, each set once.
type Segment = Box<[OnceLock<&'static str>]>;

/// Every interned name by id, append-only (module doc): segment `k` holds
/// ids `SEGMENT0 * (2^k - 1)` up to (not including) `SEGMENT0 * (2^(k+1) - 1)`,
/// allocated when its first id is published.
static NAMES: [OnceLock<Segment>; SEGMENTS] = [const { OnceLock::new() }; SEGMENTS];

/// The slot of id `i` in [`NAMES`], where its segment exists.
#[inline]
fn name_slot(i: u32) -> Option<&'static OnceLock<&'static str>> {
    let (k, at) = segment_of(i);
    NAMES.get(k)?.get()?.get(at)
}

/// The segment of id `i` and its place in it.
#[inline]
fn segment_of(i: u32) -> (usize, usize) {
    let j = (i as usize / SEGMENT0) + 1;
    let k = (usize::BITS - 1 - j.leading_zeros()) as usize;
    (k, i as usize - SEGMENT0 * ((1 << k) - 1))
}

/// Sets the slot of id `id` to `name` (the interner's write lock held, or
/// its initialisation), allocating its segment the first time.
fn publish(id: u32, name: &'static str) {
    let (k, at) = segment_of(id);
    let segment = NAMES[k].get_or_init(|| (0..SEGMENT0 << k).map(|_| OnceLock::new()).collect());
    let _ = segment[at].set(name);
}

thread_local! {
    static INTERN_CACHE: std::cell::RefCell<Vec<Option<(&'static str, Atom)>>> =
        std::cell::RefCell::new(vec![None; CACHE_SLOTS]);
}

/// FNV-1a over the text, folded to a cache slot.
fn cache_slot(name: &str) -> usize {
    let mut h: u32 = 0x811c_9dc5;
    for &b in name.as_bytes() {
        h = (h ^ u32::from(b)).wrapping_mul(0x0100_0193);
    }
    (h as usize ^ (h as usize >> 16)) % CACHE_SLOTS
}

impl fmt::Debug for Atom {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.as_str())
    }
}

impl fmt::Display for Atom {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl PartialOrd for Atom {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

/// Standard order of atoms is alphabetical by text, not by interning order.
impl Ord for Atom {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        if self.0 == other.0 {
            std::cmp::Ordering::Equal
        } else {
            self.as_str().cmp(other.as_str())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn predefined_atoms_have_their_text() {
        assert_eq!(atoms::NIL.as_str(), "[]");
        assert_eq!(atoms::ERROR.as_str(), "error");
        assert_eq!(Atom::intern("==>"), atoms::DOUBLE_ARROW);
    }

    #[test]
    fn segments_cover_the_ids() {
        assert_eq!(segment_of(0), (0, 0));
        assert_eq!(segment_of(1023), (0, 1023));
        assert_eq!(segment_of(1024), (1, 0));
        assert_eq!(segment_of(3071), (1, 2047));
        assert_eq!(segment_of(3072), (2, 0));
        assert_eq!(segment_of(7167), (2, 4095));
        assert_eq!(segment_of(7168), (3, 0));
        let (k, at) = segment_of(u32::MAX);
        assert!(k < SEGMENTS && at < SEGMENT0 << k);
    }

    #[test]
    fn names_past_the_first_segment_and_from_other_threads() {
        let atoms: Vec<Atom> = (0..3000)
            .map(|i| Atom::intern(&format!("atom_table_test_{i}")))
            .collect();
        let other = std::thread::spawn(move || {
            (0..3000).all(|i| atoms[i].as_str() == format!("atom_table_test_{i}"))
        });
        assert!(other.join().unwrap());
        let late = std::thread::spawn(|| Atom::intern("atom_made_on_another_thread"))
            .join()
            .unwrap();
        assert_eq!(late.as_str(), "atom_made_on_another_thread");
    }

    #[test]
    fn interning_is_idempotent() {
        let a = Atom::intern("some_new_atom");
        assert_eq!(a, Atom::intern("some_new_atom"));
        assert_eq!(a.as_str(), "some_new_atom");
        assert!(Atom::intern("abc") < Atom::intern("abd"));
    }
}
