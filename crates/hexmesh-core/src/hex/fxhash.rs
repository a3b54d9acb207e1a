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
    /// Eight bytes a word (the last word zero-padded): a byte at a time cost a multiplication
    /// each.
    fn write(&mut self, bytes: &[u8]) {
        let mut words = bytes.chunks_exact(8);
        for w in &mut words {
            self.add(u64::from_le_bytes(w.try_into().expect("eight bytes")));
        }
        let rest = words.remainder();
        if !rest.is_empty() {
            let mut last = [0u8; 8];
            last[..rest.len()].copy_from_slice(rest);
            self.add(u64::from_le_bytes(last));
        }
    }

    fn write_u8(&mut self, n: u8) {
        self.add(n as u64);
    }

    // Without these, the default methods hand the integer to `write` as bytes.
    fn write_u16(&mut self, n: u16) {
        self.add(n as u64);
    }

    fn write_u32(&mut self, n: u32) {
        self.add(n as u64);
    }

    fn write_usize(&mut self, n: usize) {
        self.add(n as u64);
    }

    fn write_i32(&mut self, n: i32) {
        self.add(n as u32 as u64);
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

#[cfg(test)]
mod tests {
    use super::*;

    fn hash(f: impl Fn(&mut FxHasher)) -> u64 {
        let mut h = FxHasher::default();
        f(&mut h);
        h.finish()
    }

    #[test]
    fn an_integer_key_is_one_word_and_a_byte_string_a_word_at_a_time() {
        let word = |n: u64| hash(|h| h.write_u64(n));
        assert_eq!(hash(|h| h.write_u32(0xdead_beef)), word(0xdead_beef));
        assert_eq!(hash(|h| h.write_usize(12_345)), word(12_345));
        assert_eq!(hash(|h| h.write_u16(7)), word(7));
        assert_eq!(hash(|h| h.write_i32(-1)), word(0xffff_ffff));
        // Twelve bytes: one whole word, then the last four zero-padded.
        let bytes: Vec<u8> = (1..=12).collect();
        let (a, b) = (
            u64::from_le_bytes(bytes[..8].try_into().unwrap()),
            u64::from_le_bytes([9, 10, 11, 12, 0, 0, 0, 0]),
        );
        let by_words = hash(|h| {
            h.write_u64(a);
            h.write_u64(b);
        });
        assert_eq!(hash(|h| h.write(&bytes)), by_words);
        // The tail counts: a last byte changed changes the hash.
        let mut other = bytes.clone();
        other[11] = 13;
        assert_ne!(hash(|h| h.write(&other)), by_words);
    }
}
