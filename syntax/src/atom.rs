//! Global atom interner: every atom of every program, KB and input term is a `u32`.
//!
//! Atoms are compared by id on the hot path; the text is only needed to print.
//! Interned strings are leaked and never collected (as in most Prolog systems
//! without atom GC); a long-running task reading unbounded distinct atoms from
//! input grows by their text.

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
        Atom(id)
    }

    /// The atom's text.
    pub fn as_str(self) -> &'static str {
        // Names are leaked and never move: each thread keeps its own copy
        // of the table's prefix and takes the lock only for atoms newer
        // than its copy (the hot paths ask for the same few names).
        let i = self.0 as usize;
        NAMES_SEEN.with(|seen| {
            if let Some(&name) = seen.borrow().get(i) {
                return name;
            }
            let guard = interner().read().unwrap_or_else(|e| e.into_inner());
            let mut seen = seen.borrow_mut();
            let from = seen.len();
            seen.extend_from_slice(&guard.names[from..]);
            guard.names[i]
        })
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

thread_local! {
    /// This thread's copy of a prefix of the interner's names (see [`Atom::as_str`]).
    static NAMES_SEEN: std::cell::RefCell<Vec<&'static str>> = const { std::cell::RefCell::new(Vec::new()) };
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
    fn interning_is_idempotent() {
        let a = Atom::intern("some_new_atom");
        assert_eq!(a, Atom::intern("some_new_atom"));
        assert_eq!(a.as_str(), "some_new_atom");
        assert!(Atom::intern("abc") < Atom::intern("abd"));
    }
}
