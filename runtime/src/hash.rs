//! The hasher of the runtime's small tables keyed by atoms (the function
//! registry, the plain functions, the evaluator's operator table): a
//! multiplication a word, where SipHash showed up on every call and every
//! `is`; and `native::memo`'s cells (store cell indices, addresses).
//! Invariant: only for keys the program itself names (atom indices,
//! arities) or the runtime makes, never for keys an adversary chooses.

use std::collections::HashMap;
use std::hash::BuildHasherDefault;

/// Hashes atom indices and small integers with a rotation and a
/// multiplication a word.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct AtomKeyHasher(u64);

impl std::hash::Hasher for AtomKeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u32(&mut self, i: u32) {
        self.write_u64(u64::from(i));
    }
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
}

/// A map hashed by [`AtomKeyHasher`].
pub(crate) type AtomKeyMap<K, V> = HashMap<K, V, BuildHasherDefault<AtomKeyHasher>>;
