//! `KeySet`: a set of lattice keys (paper 000 Sec. 3.1's hexagons of one level, by lattice
//! point) kept as 8 × 8 blocks of bits. A container of ours, not in the paper.

use crate::hex::fxhash::FxHashMap;
use crate::hex::key::{Key, DIRS};

/// The bits of `next` seen one row of cells along i from `word` (`step` = 1: cell (i, j) gets
/// the bit of (i + 1, j); -1: of (i - 1, j)), where `next` is the block beyond, in the
/// 8 × 8 layout of `KeySet`.
fn shift_i(word: u64, next: u64, step: i64) -> u64 {
    if step > 0 {
        (word >> 8) | (next << 56)
    } else {
        (word << 8) | (next >> 56)
    }
}

/// As `shift_i`, along j (columns: bit `j & 7` of each row of eight).
fn shift_j(word: u64, next: u64, step: i64) -> u64 {
    const FIRST: u64 = 0x0101_0101_0101_0101;
    const LAST: u64 = FIRST << 7;
    if step > 0 {
        ((word >> 1) & !LAST) | ((next & FIRST) << 7)
    } else {
        ((word << 1) & !FIRST) | ((next & LAST) >> 7)
    }
}

/// A set of keys kept as blocks of 8 × 8 cells of one level, one bit each: neighbouring cells
/// share a block, so the table is several times smaller than a set of keys and the lookups
/// of a neighbourhood stay in cache (the hierarchy asks for the subdivided state of every
/// cell near the one it looks at). The blocks of a level that fills up move from the table
/// to an array over the whole level (`DenseLevel`). Iteration order depends on which levels
/// are dense; no caller's result depends on it.
#[derive(Debug, Clone, Default)]
pub struct KeySet {
    /// The blocks of the levels kept in a table, and of dense levels outside their array.
    sparse: FxHashMap<Key, u64>,
    /// Per level: how many blocks `sparse` holds, and the level's array once it is dense.
    levels: Vec<Level>,
    len: usize,
}

/// One level of a `KeySet`.
#[derive(Debug, Clone, Default)]
struct Level {
    sparse_blocks: usize,
    dense: Option<DenseLevel>,
}

/// The words of one level as an array over the blocks of a rectangle of lattice coordinates
/// that holds the bounding hexagon (with a margin): a look-up is an index computation and
/// one read instead of a hash, a probe and a key comparison. A level turns dense once it has
/// `MIN_BLOCKS` blocks and they would fill a 64th of the array (8 bytes a word against about
/// 38 a block in the table, so at most about 14 times the table's room when it switches).
/// Measured here: with an eighth, plane-1m's level 14 stayed in the table.
/// The array is laid out in tiles of 8 × 8 blocks (64 × 64 cells, 512 bytes), so that cells
/// near each other in the plane are near each other in memory.
#[derive(Debug, Clone)]
struct DenseLevel {
    /// Block coordinates of the first block of the first tile (multiples of 8).
    bi0: i64,
    bj0: i64,
    /// Tiles along i and along j.
    tiles_i: i64,
    tiles_j: i64,
    words: Vec<u64>,
}

impl DenseLevel {
    /// Cells beyond the bounding hexagon that a set may hold (neighbours, rings and discs
    /// around cells near the boundary) within this many cells stay in the array.
    const MARGIN: i64 = 16;
    /// Levels whose array would be larger than this many words stay in the table.
    const MAX_WORDS: i64 = 1 << 25;
    /// Levels with fewer blocks stay in the table (about 300 KB at most, which stays in
    /// cache), so that small sets (local checks, small inputs) do not allocate arrays of
    /// megabytes for a few blocks.
    const MIN_BLOCKS: usize = 8192;

    /// The rectangle of level `k`: the root is |i + 2j| ≤ 2^k, |3i| + |i + 2j| ≤ 2^(k+1)
    /// (`Key::inside`), so |i| ≤ 2^(k+1)/3 and |j| ≤ (2^k + |i|)/2 ≤ 5/6·2^k.
    fn shape(k: u8) -> Option<(i64, i64, i64, i64)> {
        // Level 15 already needs more than `MAX_WORDS`; deeper levels would overflow below.
        if k > 16 {
            return None;
        }
        let half = 1i64 << k;
        let ri = (2 * half) / 3 + 1 + Self::MARGIN;
        let rj = (5 * half) / 6 + 1 + Self::MARGIN;
        let (bi0, bj0) = ((-ri >> 3) & !7, (-rj >> 3) & !7);
        let tiles_i = ((ri >> 3) - bi0) / 8 + 1;
        let tiles_j = ((rj >> 3) - bj0) / 8 + 1;
        (tiles_i * tiles_j * 64 <= Self::MAX_WORDS).then_some((bi0, bj0, tiles_i, tiles_j))
    }

    fn new(k: u8) -> Option<DenseLevel> {
        let (bi0, bj0, tiles_i, tiles_j) = DenseLevel::shape(k)?;
        Some(DenseLevel {
            bi0,
            bj0,
            tiles_i,
            tiles_j,
            words: vec![0; (tiles_i * tiles_j * 64) as usize],
        })
    }

    /// The index of block (bi, bj) in `words`, if the rectangle holds it.
    #[inline]
    fn index(&self, bi: i64, bj: i64) -> Option<usize> {
        let (di, dj) = (bi - self.bi0, bj - self.bj0);
        let (ti, tj) = (di >> 3, dj >> 3);
        if di < 0 || dj < 0 || ti >= self.tiles_i || tj >= self.tiles_j {
            return None;
        }
        Some((((ti * self.tiles_j + tj) << 6) | ((di & 7) << 3) | (dj & 7)) as usize)
    }

    /// The block of index `x` (the inverse of `index`).
    fn block(&self, k: u8, x: usize) -> Key {
        let x = x as i64;
        let (tile, n) = (x >> 6, x & 63);
        let (ti, tj) = (tile / self.tiles_j, tile % self.tiles_j);
        Key::new(
            k,
            self.bi0 + (ti << 3) + (n >> 3),
            self.bj0 + (tj << 3) + (n & 7),
        )
    }
}

impl KeySet {
    /// A set for about `keys` keys. Levels that fill up turn dense, so only a share of the
    /// hint goes to the table at first.
    pub fn with_capacity(keys: usize) -> KeySet {
        KeySet {
            sparse: FxHashMap::with_capacity_and_hasher(
                (keys / 8).min(1 << 16) + 16,
                Default::default(),
            ),
            levels: Vec::new(),
            len: 0,
        }
    }

    /// The dense array of level `k` and the index of `block` in it, if it has one.
    #[inline]
    fn dense_slot(&self, block: Key) -> Option<(&DenseLevel, usize)> {
        let d = self.levels.get(block.k as usize)?.dense.as_ref()?;
        Some((d, d.index(block.i, block.j)?))
    }

    /// The word of `block`, created empty if missing.
    fn word_mut(&mut self, block: Key) -> &mut u64 {
        if let Some(x) = self.dense_slot(block).map(|(_, x)| x) {
            let d = self.levels[block.k as usize].dense.as_mut();
            return &mut d.expect("a dense level").words[x];
        }
        let k = block.k as usize;
        if self.levels.len() <= k {
            self.levels.resize_with(k + 1, Level::default);
        }
        match self.sparse.entry(block) {
            std::collections::hash_map::Entry::Occupied(e) => e.into_mut(),
            std::collections::hash_map::Entry::Vacant(e) => {
                self.levels[k].sparse_blocks += 1;
                e.insert(0)
            }
        }
    }

    /// Moves level `k` into an array once it has `DenseLevel::MIN_BLOCKS` blocks in the table
    /// and they would fill a 64th of it.
    fn maybe_densify(&mut self, k: u8) {
        let Some(level) = self.levels.get(k as usize) else {
            return;
        };
        if level.dense.is_some() || level.sparse_blocks < DenseLevel::MIN_BLOCKS {
            return;
        }
        let Some((_, _, ti, tj)) = DenseLevel::shape(k) else {
            return;
        };
        if (level.sparse_blocks as i64) * 64 < ti * tj * 64 {
            return;
        }
        let mut dense = DenseLevel::new(k).expect("the shape fits");
        let mut moved = 0;
        self.sparse.retain(|b, &mut w| {
            let x = if b.k == k {
                dense.index(b.i, b.j)
            } else {
                None
            };
            match x {
                Some(x) => {
                    dense.words[x] = w;
                    moved += 1;
                    false
                }
                None => true,
            }
        });
        let level = &mut self.levels[k as usize];
        level.sparse_blocks -= moved;
        level.dense = Some(dense);
    }

    /// The cell of bit `n` of block `block` (the inverse of `slot`).
    pub fn cell_in_block(block: Key, n: i64) -> Key {
        Key::new(block.k, (block.i << 3) | (n >> 3), (block.j << 3) | (n & 7))
    }

    /// The block of `key` and its bit there (`>>` and `&` floor negative coordinates).
    fn slot(key: Key) -> (Key, u64) {
        let block = Key::new(key.k, key.i >> 3, key.j >> 3);
        (block, 1u64 << (((key.i & 7) << 3) | (key.j & 7)))
    }

    /// Whether `key` is in the set.
    pub fn contains(&self, key: &Key) -> bool {
        let (block, bit) = KeySet::slot(*key);
        self.word(block) & bit != 0
    }

    /// Adds `key`; true when it was not there.
    pub fn insert(&mut self, key: Key) -> bool {
        let (block, bit) = KeySet::slot(key);
        let w = self.word_mut(block);
        let new = *w & bit == 0;
        *w |= bit;
        self.len += new as usize;
        self.maybe_densify(key.k);
        new
    }

    /// Removes `key`; true when it was there.
    pub fn remove(&mut self, key: &Key) -> bool {
        let (block, bit) = KeySet::slot(*key);
        let had = if let Some(x) = self.dense_slot(block).map(|(_, x)| x) {
            let d = self.levels[block.k as usize].dense.as_mut();
            let w = &mut d.expect("a dense level").words[x];
            let had = *w & bit != 0;
            *w &= !bit;
            had
        } else {
            let Some(w) = self.sparse.get_mut(&block) else {
                return false;
            };
            let had = *w & bit != 0;
            *w &= !bit;
            if *w == 0 {
                self.sparse.remove(&block);
                self.levels[block.k as usize].sparse_blocks -= 1;
            }
            had
        };
        self.len -= had as usize;
        had
    }

    /// The neighbours of `key` (same level, directions `DIRS`) that are in the set, as a bit
    /// mask (bit d: direction d), with bit 6 set when `key` itself is. The seven cells lie
    /// in a 3 × 3 window of one level, which meets one block for 36 of the 64 positions in a
    /// block and at most four otherwise: one table lookup per block met, where `contains` on
    /// each cell makes seven.
    pub fn neighbourhood(&self, key: Key) -> u8 {
        let (li, lj) = (key.i & 7, key.j & 7);
        if (1..=6).contains(&li) && (1..=6).contains(&lj) {
            let w = self.word(Key::new(key.k, key.i >> 3, key.j >> 3));
            if w == 0 {
                return 0;
            }
            let mut mask = (((w >> ((li << 3) | lj)) & 1) as u8) << 6;
            for (d, &(di, dj)) in DIRS.iter().enumerate() {
                let bit = ((li + di) << 3) | (lj + dj);
                mask |= (((w >> bit) & 1) as u8) << d;
            }
            return mask;
        }
        // Up to four blocks, each looked up once.
        const SEVEN: [(i64, i64); 7] =
            [DIRS[0], DIRS[1], DIRS[2], DIRS[3], DIRS[4], DIRS[5], (0, 0)];
        self.mask_at(key, &SEVEN) as u8
    }

    /// Which of the cells `key + offsets[n]` (same level) are in the set, as bit n. The
    /// offsets must lie within 8 cells of `key` along each axis (at most four blocks, each
    /// looked up once).
    pub fn mask_at(&self, key: Key, offsets: &[(i64, i64)]) -> u32 {
        let mut seen: [(i64, i64, u64); 4] = [(0, 0, 0); 4];
        let mut n_seen = 0;
        let mut mask = 0u32;
        for (n, &(di, dj)) in offsets.iter().enumerate() {
            let (i, j) = (key.i + di, key.j + dj);
            let (bi, bj) = (i >> 3, j >> 3);
            let w = match seen[..n_seen].iter().find(|e| e.0 == bi && e.1 == bj) {
                Some(e) => e.2,
                None => {
                    let w = self.word(Key::new(key.k, bi, bj));
                    debug_assert!(n_seen < 4, "offsets beyond one block of {key:?}");
                    seen[n_seen.min(3)] = (bi, bj, w);
                    n_seen += 1;
                    w
                }
            };
            mask |= (((w >> (((i & 7) << 3) | (j & 7))) & 1) as u32) << n;
        }
        mask
    }

    #[inline]
    fn word(&self, block: Key) -> u64 {
        if let Some((d, x)) = self.dense_slot(block) {
            return d.words[x];
        }
        self.sparse.get(&block).copied().unwrap_or(0)
    }

    /// For the 8 × 8 block `block` (a key whose i and j are block coordinates, `i >> 3` and
    /// `j >> 3` of its cells): its word, and the cells of the block with at least one of their
    /// six neighbours in the set, as a word of the same layout (bit `(i & 7) << 3 | (j & 7)`).
    /// Seven block lookups and shifts for 64 cells, where `neighbourhood` takes one or more
    /// lookups a cell.
    pub fn block_and_beside(&self, block: Key) -> (u64, u64) {
        let at = |di: i64, dj: i64| self.word(Key::new(block.k, block.i + di, block.j + dj));
        let c = at(0, 0);
        let (up, down, left, right) = (at(-1, 0), at(1, 0), at(0, -1), at(0, 1));
        let (up_right, down_left) = (at(-1, 1), at(1, -1));
        let mut beside = shift_i(c, down, 1) | shift_i(c, up, -1);
        beside |= shift_j(c, right, 1) | shift_j(c, left, -1);
        // The diagonal directions (-1, 1) and (1, -1): first along i in the two block columns
        // involved, then along j.
        beside |= shift_j(shift_i(c, up, -1), shift_i(right, up_right, -1), 1);
        beside |= shift_j(shift_i(c, down, 1), shift_i(left, down_left, 1), -1);
        (c, beside)
    }

    /// The occupied blocks with their words (bit `(i & 7) << 3 | (j & 7)` of block
    /// `(k, i >> 3, j >> 3)`), in no particular order.
    pub fn blocks(&self) -> impl Iterator<Item = (Key, u64)> + '_ {
        let dense = self.levels.iter().enumerate().flat_map(|(k, level)| {
            level.dense.iter().flat_map(move |d| {
                d.words
                    .iter()
                    .enumerate()
                    .filter(|(_, &w)| w != 0)
                    .map(move |(x, &w)| (d.block(k as u8, x), w))
            })
        });
        dense.chain(self.sparse.iter().map(|(b, &w)| (*b, w)))
    }

    /// Adds every cell within lattice distance `radius` of `c` (at its level), one table
    /// lookup per block the disc meets rather than one per cell.
    pub fn insert_disc(&mut self, c: Key, radius: i64) {
        // (block i, block j, bits), for the few blocks a disc meets.
        let mut acc: Vec<(i64, i64, u64)> = Vec::with_capacity(8);
        for di in -radius..=radius {
            let i = c.i + di;
            let lo = c.j + (-radius).max(-radius - di);
            let hi = c.j + radius.min(radius - di);
            let mut j = lo;
            while j <= hi {
                let (bi, bj) = (i >> 3, j >> 3);
                // The cells j..=end of this row that lie in block column bj.
                let end = hi.min((bj << 3) + 7);
                let row = (i & 7) << 3;
                let (a, b) = (j & 7, end & 7);
                let bits = ((u64::MAX >> (63 - (b - a))) << a) << row;
                match acc.iter_mut().find(|e| e.0 == bi && e.1 == bj) {
                    Some(e) => e.2 |= bits,
                    None => acc.push((bi, bj, bits)),
                }
                j = end + 1;
            }
        }
        for (bi, bj, bits) in acc {
            let w = self.word_mut(Key::new(c.k, bi, bj));
            let new = (bits & !*w).count_ones() as usize;
            *w |= bits;
            self.len += new;
        }
        self.maybe_densify(c.k);
    }

    /// How many keys the set holds.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the set holds no key.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The keys, in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = Key> + '_ {
        self.blocks().flat_map(|(b, w)| KeySet::keys_in_block(b, w))
    }

    /// The keys of block `block` whose bits `word` holds (as `blocks` gives them), in the
    /// order of `iter`.
    pub fn keys_in_block(block: Key, word: u64) -> impl Iterator<Item = Key> {
        (0..64)
            .filter(move |n| word & (1u64 << n) != 0)
            .map(move |n| KeySet::cell_in_block(block, n))
    }
}

impl FromIterator<Key> for KeySet {
    fn from_iter<I: IntoIterator<Item = Key>>(keys: I) -> KeySet {
        let keys = keys.into_iter();
        let mut set = KeySet::with_capacity(keys.size_hint().0);
        for key in keys {
            set.insert(key);
        }
        set
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_key_set_holds_exactly_what_was_inserted_and_not_removed() {
        let mut set = KeySet::default();
        let mut reference = std::collections::BTreeSet::new();
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for step in 0..4000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let key = Key::new(
                (x % 4) as u8,
                (x >> 8) as i64 % 40 - 20,
                (x >> 24) as i64 % 40 - 20,
            );
            if step % 3 == 2 {
                assert_eq!(set.remove(&key), reference.remove(&key), "{key:?}");
            } else {
                assert_eq!(set.insert(key), reference.insert(key), "{key:?}");
            }
            assert_eq!(set.len(), reference.len());
        }
        for k in 0..4u8 {
            for i in -21..21 {
                for j in -21..21 {
                    let key = Key::new(k, i, j);
                    assert_eq!(set.contains(&key), reference.contains(&key), "{key:?}");
                }
            }
        }
        let mut listed: Vec<Key> = set.iter().collect();
        listed.sort();
        assert_eq!(listed, reference.into_iter().collect::<Vec<_>>());
    }

    #[test]
    fn a_key_set_answers_the_same_before_and_after_a_level_turns_dense() {
        // Level 10: the array covers |i| <= 683 + 16 and |j| <= 853 + 16 (with the margin).
        // One key in each of 91 x 91 blocks turns it dense part way; random keys (some far
        // beyond the array, which stay in the table) are inserted and removed around them.
        let k = 10u8;
        let mut set = KeySet::default();
        let mut reference = std::collections::BTreeSet::new();
        let mut x: u64 = 0x0123_4567_89ab_cdef;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let mut was_dense = false;
        let mut step = 0;
        for bi in -45..46i64 {
            for bj in -45..46i64 {
                let r = next();
                let key = Key::new(k, 8 * bi + (r % 8) as i64, 8 * bj + (r >> 8) as i64 % 8);
                assert_eq!(set.insert(key), reference.insert(key), "{key:?}");
                for _ in 0..2 {
                    step += 1;
                    let r = next();
                    let far = if step % 50 == 0 { 5000 } else { 0 };
                    let key = Key::new(
                        k - (step % 7 == 0) as u8,
                        (r >> 8) as i64 % 800 - 400 + far,
                        (r >> 24) as i64 % 800 - 400 - far,
                    );
                    if step % 3 == 2 {
                        assert_eq!(set.remove(&key), reference.remove(&key), "{key:?}");
                    } else {
                        assert_eq!(set.insert(key), reference.insert(key), "{key:?}");
                    }
                }
                assert_eq!(set.len(), reference.len());
                was_dense |= set
                    .levels
                    .get(k as usize)
                    .is_some_and(|l| l.dense.is_some());
            }
        }
        assert!(was_dense, "level {k} never turned dense");
        for key in reference.iter() {
            assert!(set.contains(key), "{key:?}");
        }
        for i in -380..380 {
            for j in (-380..380).step_by(7) {
                let key = Key::new(k, i, j);
                assert_eq!(set.contains(&key), reference.contains(&key), "{key:?}");
            }
        }
        let mut listed: Vec<Key> = set.iter().collect();
        listed.sort();
        assert_eq!(listed, reference.iter().copied().collect::<Vec<_>>());
        let bits: u32 = set.blocks().map(|(_, w)| w.count_ones()).sum();
        assert_eq!(bits as usize, reference.len());
        for key in reference.clone() {
            assert!(set.remove(&key));
        }
        assert!(set.is_empty() && set.iter().next().is_none());
    }

    #[test]
    fn the_neighbourhood_mask_is_the_cells_looked_up_one_by_one() {
        let mut set = KeySet::default();
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..600 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            set.insert(Key::new(
                2,
                (x >> 8) as i64 % 24 - 12,
                (x >> 24) as i64 % 24 - 12,
            ));
        }
        for i in -14..14 {
            for j in -14..14 {
                let key = Key::new(2, i, j);
                let want = (0..6).fold(0u8, |m, d| {
                    m | ((set.contains(&key.neighbor(d)) as u8) << d)
                });
                let own = (set.contains(&key) as u8) << 6;
                assert_eq!(set.neighbourhood(key), want | own, "{key:?}");
            }
        }
    }

    #[test]
    fn the_cells_beside_a_block_are_the_cells_with_a_neighbour_looked_up_one_by_one() {
        let mut x: u64 = 0x51_7c_c1_b7_27_22_0a_95;
        for density in [3u64, 20, 60] {
            let mut set = KeySet::default();
            for _ in 0..400 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                if x % 64 < density {
                    set.insert(Key::new(
                        3,
                        (x >> 8) as i64 % 20 - 10,
                        (x >> 24) as i64 % 20 - 10,
                    ));
                }
            }
            for bi in -3..3 {
                for bj in -3..3 {
                    let (own, beside) = set.block_and_beside(Key::new(3, bi, bj));
                    for n in 0..64 {
                        let key = KeySet::cell_in_block(Key::new(3, bi, bj), n);
                        let mask = set.neighbourhood(key);
                        assert_eq!(own >> n & 1 == 1, mask & 0x40 != 0, "{key:?}");
                        assert_eq!(beside >> n & 1 == 1, mask & 0x3f != 0, "{key:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn a_disc_inserted_at_once_is_the_cells_inserted_one_by_one() {
        for (c, radius) in [
            (Key::new(3, 0, 0), 0),
            (Key::new(3, 5, -2), 1),
            (Key::new(7, -13, 22), 4),
            (Key::new(9, 100, -9), 11),
        ] {
            let mut at_once = KeySet::default();
            at_once.insert(Key::new(c.k, c.i + radius, c.j));
            at_once.insert_disc(c, radius);
            let mut one_by_one = KeySet::default();
            one_by_one.insert(Key::new(c.k, c.i + radius, c.j));
            for di in -radius..=radius {
                for dj in -radius..=radius {
                    if (di + dj).abs() <= radius {
                        one_by_one.insert(Key::new(c.k, c.i + di, c.j + dj));
                    }
                }
            }
            let mut a: Vec<Key> = at_once.iter().collect();
            let mut b: Vec<Key> = one_by_one.iter().collect();
            a.sort();
            b.sort();
            assert_eq!(a, b, "disc {c:?} radius {radius}");
            assert_eq!(at_once.len(), one_by_one.len());
        }
    }
}
