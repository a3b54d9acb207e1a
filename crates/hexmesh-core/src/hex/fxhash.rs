//! A small multiplicative hasher for the integer keys of the hexagon lattice, and the hash
//! maps and sets built on it: engineering, not in paper 000.

use std::hash::{BuildHasherDefault, Hasher};

/// A small multiplicative hasher (the Fx hash of rustc) for integer keys: the default SipHash
/// costs more than the rest of a lookup. Hash order never reaches the output.
#[derive(Default, Clone, Copy)]
pub struct FxHasher(u64);

impl FxHasher {
    fn add(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

impl Hasher for FxHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.add(b as u64);
        }
    }

    fn write_u8(&mut self, n: u8) {
        self.add(n as u64);
    }

    fn write_u64(&mut self, n: u64) {
        self.add(n);
    }

    fn write_i64(&mut self, n: i64) {
        self.add(n as u64);
    }

    fn finish(&self) -> u64 {
        // The table indexes by the low bits, which a multiplication leaves poorly mixed.
        self.0.rotate_left(26)
    }
}

/// Builds `FxHasher`s for the standard collections.
pub type FxBuild = BuildHasherDefault<FxHasher>;
/// A `HashMap` hashed with `FxHasher`.
pub type FxHashMap<K, V> = std::collections::HashMap<K, V, FxBuild>;
/// A `HashSet` hashed with `FxHasher`.
pub type FxHashSet<K> = std::collections::HashSet<K, FxBuild>;
