//! The operator table: data, not grammar. `OpTable::sitlog()` is the table in
//! force when the original interpreter reads DMs (ISO core + SitLog's four
//! operators + SWI's infix `|`).

use crate::atom::Atom;
use std::collections::HashMap;

/// Operator type in ISO notation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OpType {
    Xfx,
    Xfy,
    Yfx,
    Fy,
    Fx,
    Xf,
    Yf,
}

impl OpType {
    pub fn parse(text: &str) -> Option<OpType> {
        Some(match text {
            "xfx" => OpType::Xfx,
            "xfy" => OpType::Xfy,
            "yfx" => OpType::Yfx,
            "fy" => OpType::Fy,
            "fx" => OpType::Fx,
            "xf" => OpType::Xf,
            "yf" => OpType::Yf,
            _ => return None,
        })
    }
    pub fn as_str(self) -> &'static str {
        match self {
            OpType::Xfx => "xfx",
            OpType::Xfy => "xfy",
            OpType::Yfx => "yfx",
            OpType::Fy => "fy",
            OpType::Fx => "fx",
            OpType::Xf => "xf",
            OpType::Yf => "yf",
        }
    }
}

/// One operator definition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OpDef {
    pub priority: u16,
    pub kind: OpType,
}

impl OpDef {
    /// Maximum priorities of (left, right) operands; `None` where there is no operand.
    pub fn arg_max(self) -> (Option<u16>, Option<u16>) {
        let p = self.priority;
        match self.kind {
            OpType::Xfx => (Some(p - 1), Some(p - 1)),
            OpType::Xfy => (Some(p - 1), Some(p)),
            OpType::Yfx => (Some(p), Some(p - 1)),
            OpType::Fy => (None, Some(p)),
            OpType::Fx => (None, Some(p - 1)),
            OpType::Xf => (Some(p - 1), None),
            OpType::Yf => (Some(p), None),
        }
    }
}

/// Hashes an [`Atom`] (a `u32`) with one multiplication: operator lookups
/// happen for every name token the reader sees.
#[derive(Clone, Copy, Debug, Default)]
pub struct AtomHasher(u64);

impl std::hash::Hasher for AtomHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(5) ^ u64::from(b)).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
        }
    }
    fn write_u32(&mut self, i: u32) {
        self.0 = (self.0.rotate_left(5) ^ u64::from(i)).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

type AtomMap<V> = HashMap<Atom, V, std::hash::BuildHasherDefault<AtomHasher>>;

/// Prefix, infix and postfix operators by name.
#[derive(Clone, Debug, Default)]
pub struct OpTable {
    prefix: AtomMap<OpDef>,
    infix: AtomMap<OpDef>,
    postfix: AtomMap<OpDef>,
}

const ISO: &[(u16, &str, &[&str])] = &[
    (1200, "xfx", &[":-", "-->"]),
    (1200, "fx", &[":-", "?-"]),
    (1100, "xfy", &[";"]),
    (1050, "xfy", &["->"]),
    (1000, "xfy", &[","]),
    (900, "fy", &["\\+"]),
    (
        700,
        "xfx",
        &[
            "=", "\\=", "==", "\\==", "@<", "@>", "@=<", "@>=", "=..", "is", "=:=", "=\\=", "<",
            ">", "=<", ">=",
        ],
    ),
    (500, "yfx", &["+", "-", "/\\", "\\/"]),
    (400, "yfx", &["*", "/", "//", "rem", "mod", "<<", ">>"]),
    (200, "xfx", &["**"]),
    (200, "xfy", &["^"]),
    (200, "fy", &["-", "+", "\\"]),
];

const SITLOG: &[(u16, &str, &[&str])] = &[
    (600, "xfx", &[":"]),
    (800, "xfx", &["=>"]),
    (850, "xfx", &["=>>"]),
    (900, "xfx", &["==>"]),
    (1105, "xfy", &["|"]),
];

/// SWI-Prolog 9's own operators beyond ISO core (in module `user`), except
/// `.` (dicts) and `=>` (SSU rules; SitLog redefines it), plus
/// `json_object` that the original interpreter imports.
const SWI_EXTRA: &[(u16, &str, &[&str])] = &[
    (1, "fx", &["$"]),
    (1050, "xfy", &["*->"]),
    (
        1150,
        "fx",
        &[
            "discontiguous",
            "dynamic",
            "initialization",
            "meta_predicate",
            "module_transparent",
            "multifile",
            "public",
            "table",
            "thread_initialization",
            "thread_local",
            "volatile",
            "json_object",
        ],
    ),
    (400, "yfx", &["div", "rdiv", "xor"]),
    (700, "xfx", &[":<", ">:<", "=@=", "\\=@=", "as"]),
    (800, "xfx", &[":="]),
];

impl OpTable {
    /// An empty table.
    pub fn empty() -> OpTable {
        OpTable::default()
    }

    /// The ISO core operator table.
    pub fn iso() -> OpTable {
        let mut table = OpTable::empty();
        table.add_all(ISO);
        table
    }

    /// ISO core plus SitLog's operators, as in force when the original reads DMs.
    pub fn sitlog() -> OpTable {
        let mut table = OpTable::iso();
        table.add_all(SITLOG);
        table
    }

    /// SWI-Prolog 9's full default table plus SitLog's operators: what the
    /// original interpreter has in force. `writeq` in SWI prints with it
    /// (e.g. `table(X)` as `(table X)`), so the conformance dump prints with
    /// it; reading DMs needs only [`OpTable::sitlog`].
    pub fn swi() -> OpTable {
        let mut table = OpTable::iso();
        table.add_all(SWI_EXTRA);
        table.add_all(SITLOG);
        table
    }

    /// A shared instance of [`OpTable::swi`].
    pub fn swi_shared() -> &'static OpTable {
        static TABLE: std::sync::OnceLock<OpTable> = std::sync::OnceLock::new();
        TABLE.get_or_init(OpTable::swi)
    }

    /// A shared instance of [`OpTable::sitlog`].
    pub fn sitlog_shared() -> &'static OpTable {
        static TABLE: std::sync::OnceLock<OpTable> = std::sync::OnceLock::new();
        TABLE.get_or_init(OpTable::sitlog)
    }

    fn add_all(&mut self, defs: &[(u16, &str, &[&str])]) {
        for (priority, kind, names) in defs {
            let kind = OpType::parse(kind).expect("valid operator type in built-in table");
            for name in *names {
                self.add(*priority, kind, Atom::intern(name));
            }
        }
    }

    /// Adds (or, with priority 0, removes) an operator, like `op/3`.
    pub fn add(&mut self, priority: u16, kind: OpType, name: Atom) {
        let map = match kind {
            OpType::Fy | OpType::Fx => &mut self.prefix,
            OpType::Xfx | OpType::Xfy | OpType::Yfx => &mut self.infix,
            OpType::Xf | OpType::Yf => &mut self.postfix,
        };
        if priority == 0 {
            map.remove(&name);
        } else {
            map.insert(name, OpDef { priority, kind });
        }
    }

    pub fn prefix(&self, name: Atom) -> Option<OpDef> {
        self.prefix.get(&name).copied()
    }
    pub fn infix(&self, name: Atom) -> Option<OpDef> {
        self.infix.get(&name).copied()
    }
    pub fn postfix(&self, name: Atom) -> Option<OpDef> {
        self.postfix.get(&name).copied()
    }
    /// Whether `name` is an operator of any kind.
    pub fn is_op(&self, name: Atom) -> bool {
        self.prefix.contains_key(&name)
            || self.infix.contains_key(&name)
            || self.postfix.contains_key(&name)
    }
    /// The highest priority of `name` as any operator (0 if none).
    pub fn max_priority(&self, name: Atom) -> u16 {
        [self.prefix(name), self.infix(name), self.postfix(name)]
            .iter()
            .flatten()
            .map(|d| d.priority)
            .max()
            .unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sitlog_colon_is_xfx_600() {
        let t = OpTable::sitlog();
        let colon = t.infix(Atom::intern(":")).unwrap();
        assert_eq!((colon.priority, colon.kind), (600, OpType::Xfx));
        assert_eq!(t.infix(Atom::intern("==>")).unwrap().priority, 900);
        assert!(t.prefix(Atom::intern("-")).is_some());
        assert!(t.infix(Atom::intern("-")).is_some());
    }
}
