//! `KeyLines` (`KeyIndex`, `KeyBytes`): maps from lattice keys to small values kept as
//! square blocks of cells, one cache line a block. A container of ours, not in paper 000.

use crate::hex::fxhash::FxHashMap;
use crate::hex::key::Key;

/// One cache line of slots of a `KeyLines` map: the values of a square block of cells of
/// one level, `EMPTY` in the slots of cells that have none.
pub trait Line: Copy {
    /// What a slot holds.
    type Value: Copy + Eq;
    /// The block is `1 << SHIFT` cells a side.
    const SHIFT: i64;
    /// Marks an empty slot: it is not a value.
    const EMPTY: Self::Value;
    /// A line of empty slots.
    const CLEAR: Self;
    /// The slots, `1 << (2 · SHIFT)` of them; cell (i, j) of the block is slot
    /// `i << SHIFT | j`, (i, j) taken modulo the block's side.
    fn slots(&self) -> &[Self::Value];
    /// The slots, to write.
    fn slots_mut(&mut self) -> &mut [Self::Value];
}

/// The line of a `KeyIndex`: 4 × 4 cells of `u32`.
#[derive(Debug, Clone, Copy)]
#[repr(align(64))]
pub struct IndexLine([u32; 16]);

impl Line for IndexLine {
    type Value = u32;
    const SHIFT: i64 = 2;
    const EMPTY: u32 = u32::MAX;
    const CLEAR: IndexLine = IndexLine([u32::MAX; 16]);
    #[inline]
    fn slots(&self) -> &[u32] {
        &self.0
    }
    #[inline]
    fn slots_mut(&mut self) -> &mut [u32] {
        &mut self.0
    }
}

/// The line of a `KeyBytes`: 8 × 8 cells of `u8`.
#[derive(Debug, Clone, Copy)]
#[repr(align(64))]
pub struct ByteLine([u8; 64]);

impl Line for ByteLine {
    type Value = u8;
    const SHIFT: i64 = 3;
    const EMPTY: u8 = u8::MAX;
    const CLEAR: ByteLine = ByteLine([u8::MAX; 64]);
    #[inline]
    fn slots(&self) -> &[u8] {
        &self.0
    }
    #[inline]
    fn slots_mut(&mut self) -> &mut [u8] {
        &mut self.0
    }
}

/// A map from keys to small values kept as square blocks of cells of one level, one cache
/// line a block, in the order the blocks were first used. Cells near each other in the plane
/// share a line, so the dual's recursion (which meets a vertex's neighbours next), a search
/// that walks the lattice, or look-ups made in the dual's order land in a block just used
/// instead of a random slot of a table of millions of entries, and the table of blocks is
/// several times smaller than a table of keys.
#[derive(Debug, Clone)]
pub struct KeyLines<L: Line> {
    blocks: FxHashMap<Key, u32>,
    lines: Vec<L>,
    len: usize,
}

/// Key → `u32` (vertex numbers of the dual); `u32::MAX` is not a value.
pub type KeyIndex = KeyLines<IndexLine>;

/// Key → `u8` (distances of a region, levels of the settled cells); `KeyBytes::NONE` is not
/// a value.
pub type KeyBytes = KeyLines<ByteLine>;

impl KeyBytes {
    /// The value no key can have: an empty slot (255).
    pub const NONE: u8 = ByteLine::EMPTY;
}

impl<L: Line> Default for KeyLines<L> {
    fn default() -> KeyLines<L> {
        KeyLines {
            blocks: FxHashMap::default(),
            lines: Vec::new(),
            len: 0,
        }
    }
}

impl<L: Line> KeyLines<L> {
    const MASK: i64 = (1 << L::SHIFT) - 1;

    /// Room for about `keys` keys, a quarter of them starting a block.
    pub fn with_capacity(keys: usize) -> KeyLines<L> {
        KeyLines {
            blocks: FxHashMap::with_capacity_and_hasher(keys / 4 + 16, Default::default()),
            lines: Vec::with_capacity(keys / 4 + 16),
            len: 0,
        }
    }

    /// The block of `key` and its slot there (`>>` and `&` floor negative coordinates).
    #[inline]
    fn slot(key: Key) -> (Key, usize) {
        let block = Key::new(key.k, key.i >> L::SHIFT, key.j >> L::SHIFT);
        let n = ((key.i & Self::MASK) << L::SHIFT) | (key.j & Self::MASK);
        (block, n as usize)
    }

    /// The cell of slot `n` of block `block` (the inverse of `slot`).
    fn cell(block: Key, n: usize) -> Key {
        let n = n as i64;
        Key::new(
            block.k,
            (block.i << L::SHIFT) | (n >> L::SHIFT),
            (block.j << L::SHIFT) | (n & Self::MASK),
        )
    }

    /// The value of `key`, if it has one.
    pub fn get(&self, key: &Key) -> Option<L::Value> {
        let (block, n) = Self::slot(*key);
        let b = *self.blocks.get(&block)?;
        let v = self.lines[b as usize].slots()[n];
        (v != L::EMPTY).then_some(v)
    }

    /// The slot of `key`, its block made when there is none yet.
    fn slot_mut(&mut self, key: Key) -> &mut L::Value {
        let (block, n) = Self::slot(key);
        let lines = &mut self.lines;
        let b = *self.blocks.entry(block).or_insert_with(|| {
            lines.push(L::CLEAR);
            (lines.len() - 1) as u32
        });
        &mut self.lines[b as usize].slots_mut()[n]
    }

    /// The value of `key`, inserting `value` first when there is none.
    pub fn get_or_insert(&mut self, key: Key, value: L::Value) -> L::Value {
        debug_assert!(value != L::EMPTY);
        let v = self.slot_mut(key);
        let new = *v == L::EMPTY;
        if new {
            *v = value;
        }
        let value = *v;
        self.len += new as usize;
        value
    }

    /// Sets `key` to `value` when it has no value yet; true when it had none.
    pub fn insert_new(&mut self, key: Key, value: L::Value) -> bool {
        debug_assert!(value != L::EMPTY);
        let v = self.slot_mut(key);
        let new = *v == L::EMPTY;
        if new {
            *v = value;
        }
        self.len += new as usize;
        new
    }

    /// Sets the value of `key`.
    pub fn insert(&mut self, key: Key, value: L::Value) {
        debug_assert!(value != L::EMPTY);
        let v = self.slot_mut(key);
        let new = *v == L::EMPTY;
        *v = value;
        self.len += new as usize;
    }

    /// How many keys have a value.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no key has a value.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Every key with its value, in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = (Key, L::Value)> + '_ {
        self.blocks.iter().flat_map(move |(b, &at)| {
            let slots = self.lines[at as usize].slots();
            (0..slots.len())
                .filter(move |&n| slots[n] != L::EMPTY)
                .map(move |n| (Self::cell(*b, n), slots[n]))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Inserts 5000 pseudo-random keys of three levels, by each of the three ways in turn
    /// (`insert_new`, `get_or_insert`, `insert`), into `map` and a `BTreeMap`, then checks that
    /// the two hold the same: `len`, `get` of every key and of keys never inserted, `iter`.
    fn check_key_lines<L: Line>(mut map: KeyLines<L>, side: i64, value: impl Fn(u64) -> L::Value)
    where
        L::Value: Ord + std::fmt::Debug,
    {
        let mut reference = std::collections::BTreeMap::new();
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..5000u32 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let key = Key::new(
                (x % 3) as u8,
                ((x >> 8) % side as u64) as i64 - side / 2,
                ((x >> 20) % side as u64) as i64 - side / 2,
            );
            let v = value(x >> 32);
            match (x >> 40) % 3 {
                0 => {
                    let new = !reference.contains_key(&key);
                    reference.entry(key).or_insert(v);
                    assert_eq!(map.insert_new(key, v), new, "{key:?}");
                }
                1 => {
                    let kept = *reference.entry(key).or_insert(v);
                    assert_eq!(map.get_or_insert(key, v), kept, "{key:?}");
                }
                _ => {
                    reference.insert(key, v);
                    map.insert(key, v);
                }
            }
        }
        assert_eq!(map.len(), reference.len());
        for (key, &v) in &reference {
            assert_eq!(map.get(key), Some(v), "{key:?}");
        }
        let mut listed: Vec<(Key, L::Value)> = map.iter().collect();
        listed.sort();
        let expected: Vec<(Key, L::Value)> = reference.into_iter().collect();
        assert_eq!(listed, expected);
        assert_eq!(map.get(&Key::new(0, 100, -100)), None);
        assert_eq!(map.get(&Key::new(2, -side / 2 - 1, 0)), None);
    }

    #[test]
    fn a_key_bytes_map_holds_exactly_what_was_inserted_with_the_first_or_last_value() {
        check_key_lines(KeyBytes::default(), 37, |x| (x % 255) as u8);
    }

    #[test]
    fn a_key_index_maps_exactly_what_was_inserted_with_the_first_or_last_value() {
        check_key_lines(KeyIndex::with_capacity(100), 23, |x| x as u32 % u32::MAX);
    }
}
