//! The integer lattice behind the hexagon hierarchy (DESIGN.md "One way to see the hexagon
//! hierarchy"; paper 000 Sec. 3.1): a hexagon of level k is the cell of lattice point (i, j)
//! with centre o + r_k·(i·u + j·v), r_k = r_0/2^k, u = (3/2, √3/2), v = (0, √3).
//!
//! Every coordinate the mesher constructs (centres and cell corners) goes through one formula
//! on a normalised integer key, so the same geometric point always gets the same f64 bits: two
//! cells sharing a corner share it bit for bit, and exact predicates on constructed corners then
//! see a tiling without gaps or overlaps.

use std::hash::{BuildHasherDefault, Hasher};

use crate::geom::{lattice_coordinate, turned_point, Hexagon, Point, Turn, CORNER_X, CORNER_Y};

/// Deepest level the mesher constructs. Lattice coordinates of level k need k + 2 bits, and
/// they must stay exact in an f64 mantissa (53 bits) when a position is computed.
pub const MAX_LEVEL: u8 = 50;

/// The six lattice directions, counter-clockwise, starting at 30° (the neighbour across the
/// upper-right edge of a flat-topped hexagon).
pub const DIRS: [(i64, i64); 6] = [(1, 0), (0, 1), (-1, 1), (-1, 0), (0, -1), (1, -1)];

/// A lattice cell: the hexagon of level `k` centred at lattice point (i, j).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Key {
    pub k: u8,
    pub i: i64,
    pub j: i64,
}

impl Key {
    pub const ROOT: Key = Key { k: 0, i: 0, j: 0 };

    pub fn new(k: u8, i: i64, j: i64) -> Key {
        Key { k, i, j }
    }

    /// The key as one integer with the same order as `Ord` (k, then i, then j): sorting by it
    /// is much cheaper than comparing the fields. Lattice coordinates stay far below 2^55 in
    /// magnitude (level ≤ `MAX_LEVEL` + 1, a few cells beyond the root at most).
    pub fn packed(self) -> u128 {
        const OFF: i64 = 1 << 55;
        debug_assert!(
            self.i.abs() < OFF && self.j.abs() < OFF,
            "{self:?} out of range"
        );
        ((self.k as u128) << 112) | (((self.i + OFF) as u128) << 56) | ((self.j + OFF) as u128)
    }

    /// The same-level neighbour in direction `d` (an index into `DIRS`).
    pub fn neighbor(self, d: usize) -> Key {
        let (di, dj) = DIRS[d];
        Key::new(self.k, self.i + di, self.j + dj)
    }

    /// The central child: the hexagon scaled to half size (Sec. 3.1).
    pub fn central_child(self) -> Key {
        Key::new(self.k + 1, 2 * self.i, 2 * self.j)
    }

    /// The child cell at the midpoint of edge `d`: a semi-hexagon of this hexagon, or a full
    /// hexagon when the neighbour across that edge is subdivided too.
    pub fn edge_child(self, d: usize) -> Key {
        let (di, dj) = DIRS[d];
        Key::new(self.k + 1, 2 * self.i + di, 2 * self.j + dj)
    }

    /// The cells a subdivision of `self` creates: the central child, then the six edge
    /// children in direction order.
    pub fn children(self) -> [Key; 7] {
        let mut out = [self.central_child(); 7];
        for (d, slot) in out.iter_mut().skip(1).enumerate() {
            *slot = self.edge_child(d);
        }
        out
    }

    /// The hexagons whose subdivision creates this cell: one for a central child (both
    /// coordinates even), two for an edge child (the hexagons sharing the edge whose midpoint
    /// is this cell's centre), none for the root.
    pub fn parents(self) -> Parents {
        if self.k == 0 {
            return Parents::None;
        }
        let k = self.k - 1;
        let (ei, ej) = (self.i.rem_euclid(2), self.j.rem_euclid(2));
        if ei == 0 && ej == 0 {
            return Parents::Central(Key::new(k, self.i / 2, self.j / 2));
        }
        // The direction d with (i, j) - d even: parity (1,0) -> (1,0), (0,1) -> (0,1),
        // (1,1) -> (1,-1).
        let (di, dj) = match (ei, ej) {
            (1, 0) => (1, 0),
            (0, 1) => (0, 1),
            _ => (1, -1),
        };
        Parents::Edge(
            Key::new(k, (self.i - di) / 2, (self.j - dj) / 2),
            Key::new(k, (self.i + di) / 2, (self.j + dj) / 2),
        )
    }

    /// The key of the coarsest cell with the same centre: centres repeat down a chain of
    /// central children, and a dual vertex is identified by its position.
    pub fn canonical(self) -> Key {
        let mut key = self;
        while key.k > 0 && key.i % 2 == 0 && key.j % 2 == 0 {
            key = Key::new(key.k - 1, key.i / 2, key.j / 2);
        }
        key
    }

    /// The split counter of Sec. 3.2: how many times the hexagon that became this cell was
    /// scaled to half size since it was created by a join (or since the root). A cell created
    /// by joining two semi-hexagons has counter 0, and only such a cell may be broken again.
    pub fn split_counter(self) -> u32 {
        (self.k - self.canonical().k) as u32
    }

    /// True when the cell's centre lies in the closed bounding hexagon (the root). Exact: with
    /// X = 3i and Y = i + 2j the centre is o + r_0/2^(k+1)·(X, √3·Y), and the root is
    /// |Y| ≤ 2^k, |X| + |Y| ≤ 2^(k+1).
    pub fn inside(self) -> bool {
        // |i|, |j| < 2^55 (see `packed`) and k ≤ 51 keep every term below 2^59.
        let x = 3 * self.i;
        let y = self.i + 2 * self.j;
        let half = 1i64 << self.k;
        y.abs() <= half && x.abs() + y.abs() <= 2 * half
    }

    /// True when the centre lies on the boundary of the root: a boundary semi-hexagon that the
    /// paper treats as a virtual full hexagon (Fig. 1).
    pub fn on_boundary(self) -> bool {
        let x = 3 * self.i;
        let y = self.i + 2 * self.j;
        let half = 1i64 << self.k;
        self.inside() && (y.abs() == half || x.abs() + y.abs() == 2 * half)
    }
}

/// What `Key::parents` returns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Parents {
    None,
    Central(Key),
    Edge(Key, Key),
}

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

/// Positions of lattice points of a given root hexagon.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lattice {
    pub origin: Point,
    pub r0: f64,
    /// r_0·√3, rounded once, so that every y coordinate is one product and one sum.
    sqrt3_r0: f64,
    /// The root's rotation (`Hexagon::turn`); with one, positions are o + the turned axes
    /// (`Hexagon::axes`, `turned_point`) applied to (X, Y).
    pub turn: Turn,
    axes: [f64; 4],
}

impl Lattice {
    pub fn new(root: Hexagon) -> Lattice {
        Lattice {
            origin: root.center,
            r0: root.circumradius,
            sqrt3_r0: root.circumradius * 3f64.sqrt(),
            turn: root.turn,
            axes: root.axes(),
        }
    }

    pub fn root(&self) -> Hexagon {
        Hexagon {
            center: self.origin,
            circumradius: self.r0,
            turn: self.turn,
        }
    }

    /// Circumradius of level k.
    pub fn radius(&self, k: u8) -> f64 {
        self.r0 * pow2(-(k as i32))
    }

    /// The point o + r_0/2^(k+1)·(X, √3·Y). The key is first reduced to its coarsest level so
    /// that one geometric point always gives the same bits; the scaling by a power of two is
    /// exact, leaving one rounding per product and one per sum. Level 0 with (X, Y) = (2, 0),
    /// (1, 1), … reproduces `Hexagon::corners` bit for bit.
    pub fn grid_point(&self, k: u8, x: i64, y: i64) -> Point {
        let (mut k, mut x, mut y) = (k, x, y);
        while k > 0 && x % 2 == 0 && y % 2 == 0 {
            k -= 1;
            x /= 2;
            y /= 2;
        }
        let s = pow2(-(k as i32) - 1);
        if !self.turn.is_none() {
            return turned_point(self.origin, self.axes, x as f64, y as f64, s);
        }
        [
            lattice_coordinate(self.origin[0], self.r0 * s, x as f64),
            lattice_coordinate(self.origin[1], self.sqrt3_r0 * s, y as f64),
        ]
    }

    /// The centre of a cell.
    pub fn center(&self, key: Key) -> Point {
        self.grid_point(key.k, 3 * key.i, key.i + 2 * key.j)
    }

    /// Corner `m` (at angle 60°·m) of a cell.
    pub fn corner(&self, key: Key, m: usize) -> Point {
        self.grid_point(
            key.k,
            3 * key.i + CORNER_X[m],
            key.i + 2 * key.j + CORNER_Y[m],
        )
    }

    /// The six corners of a cell, counter-clockwise from angle 0.
    pub fn corners(&self, key: Key) -> [Point; 6] {
        std::array::from_fn(|m| self.corner(key, m))
    }

    /// The lattice point of level k nearest to `p` in floating point (cube rounding). A guess
    /// only: exact decisions are made on the constructed corners.
    pub fn nearest(&self, k: u8, p: Point) -> Key {
        let r = self.radius(k);
        let q = self
            .turn
            .undo([p[0] - self.origin[0], p[1] - self.origin[1]]);
        let qx = q[0] / r;
        let qy = q[1] / r;
        let fi = qx * (2.0 / 3.0);
        let fj = qy / 3f64.sqrt() - fi / 2.0;
        let fs = -fi - fj;
        let (mut ri, mut rj, rs) = (fi.round(), fj.round(), fs.round());
        let (di, dj, ds) = ((ri - fi).abs(), (rj - fj).abs(), (rs - fs).abs());
        if di > dj && di > ds {
            ri = -rj - rs;
        } else if dj > ds {
            rj = -ri - rs;
        }
        // Saturating float-to-int casts keep absurd inputs from wrapping; callers check.
        Key::new(k, ri as i64, rj as i64)
    }
}

/// 2^e for the exponents the lattice uses.
fn pow2(e: i32) -> f64 {
    f64::from_bits(((1023 + e) as u64) << 52)
}

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

pub type FxBuild = BuildHasherDefault<FxHasher>;
pub type FxHashMap<K, V> = std::collections::HashMap<K, V, FxBuild>;
pub type FxHashSet<K> = std::collections::HashSet<K, FxBuild>;

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

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The keys, in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = Key> + '_ {
        self.blocks().flat_map(|(b, w)| {
            (0..64)
                .filter(move |n| w & (1u64 << n) != 0)
                .map(move |n| KeySet::cell_in_block(b, n))
        })
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

/// One cache line of slots of a `KeyLines` map: the values of a square block of cells of
/// one level, `EMPTY` in the slots of cells that have none.
pub trait Line: Copy {
    type Value: Copy + Eq;
    /// The block is `1 << SHIFT` cells a side.
    const SHIFT: i64;
    /// Marks an empty slot: it is not a value.
    const EMPTY: Self::Value;
    /// A line of empty slots.
    const CLEAR: Self;
    fn slots(&self) -> &[Self::Value];
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

    pub fn len(&self) -> usize {
        self.len
    }

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

    #[test]
    fn packed_keys_sort_like_keys() {
        let mut keys = Vec::new();
        for k in [0u8, 1, 7, 50, 51] {
            for i in [-(1i64 << 52), -3, -1, 0, 1, 2, 1 << 52] {
                for j in [-(1i64 << 51), -2, 0, 5, 1 << 51] {
                    keys.push(Key::new(k, i, j));
                }
            }
        }
        let mut by_ord = keys.clone();
        by_ord.sort();
        let mut by_packed = keys;
        by_packed.sort_by_key(|k| k.packed());
        assert_eq!(by_ord, by_packed);
    }

    use super::*;

    fn unit() -> Lattice {
        Lattice::new(Hexagon::new([0.0, 0.0], 1.0))
    }

    /// A hexagon turned as `Hexagon::aligned` turns the one of points along (1, 0.37).
    fn turned(center: Point, r: f64) -> Hexagon {
        Hexagon {
            turn: crate::geom::principal_turn(&[[0.0, 0.0], [1.0, 0.37], [0.4, 0.148]]),
            ..Hexagon::new(center, r)
        }
    }

    #[test]
    fn root_corners_match_hexagon_corners_bit_for_bit() {
        for hex in [Hexagon::new([0.3, -7.1], 2.7), turned([0.3, -7.1], 2.7)] {
            let lat = Lattice::new(hex);
            assert_eq!(lat.corners(Key::ROOT), hex.corners());
            assert_eq!(lat.root(), hex);
        }
    }

    #[test]
    fn a_turned_lattice_is_the_flat_topped_one_turned_about_the_centre() {
        let (flat, turn) = (unit(), Lattice::new(turned([0.0, 0.0], 1.0)));
        for key in [Key::new(0, 0, 0), Key::new(3, 2, -1), Key::new(5, -7, 9)] {
            let want = flat.center(key);
            let got = turn.turn.undo(turn.center(key));
            assert!((got[0] - want[0]).abs() < 1e-15 && (got[1] - want[1]).abs() < 1e-15);
            assert_eq!(turn.nearest(key.k, turn.center(key)), key);
        }
    }

    #[test]
    fn a_shared_corner_has_the_same_bits_from_every_cell_and_level() {
        for lat in [
            Lattice::new(Hexagon::new([0.1, 0.2], 0.7)),
            Lattice::new(turned([0.1, 0.2], 0.7)),
        ] {
            shared_corners_agree(&lat);
        }
    }

    fn shared_corners_agree(lat: &Lattice) {
        // Corner 0 of (k, i, j) is corner 2 of its neighbour in direction 5 and corner 4 of its
        // neighbour in direction 0.
        let key = Key::new(3, 2, -1);
        assert_eq!(lat.corner(key, 0), lat.corner(key.neighbor(5), 2));
        assert_eq!(lat.corner(key, 0), lat.corner(key.neighbor(0), 4));
        // A corner of a level-k cell is a corner of its edge children at level k + 1.
        assert_eq!(lat.corner(key, 1), lat.corner(key.edge_child(0), 2));
        assert_eq!(lat.center(key), lat.center(key.central_child()));
    }

    #[test]
    fn parents_of_edge_children_are_the_two_hexagons_sharing_the_edge() {
        let key = Key::new(4, -3, 5);
        for d in 0..6 {
            match key.edge_child(d).parents() {
                Parents::Edge(a, b) => {
                    let mut got = [a, b];
                    got.sort();
                    let mut want = [key, key.neighbor(d)];
                    want.sort();
                    assert_eq!(got, want, "direction {d}");
                }
                other => panic!("edge child {d} has parents {other:?}"),
            }
        }
        assert_eq!(key.central_child().parents(), Parents::Central(key));
    }

    #[test]
    fn inside_is_the_closed_root_hexagon() {
        assert!(Key::ROOT.inside());
        assert!((0..6).all(|d| !Key::ROOT.neighbor(d).inside()));
        // Level 1: the six edge midpoints of the root lie on its boundary.
        for d in 0..6 {
            let c = Key::ROOT.edge_child(d);
            assert!(c.inside() && c.on_boundary(), "edge child {d}");
        }
        // Cross-check against the geometry on a fine level.
        let lat = unit();
        for i in -20..=20 {
            for j in -20..=20 {
                let key = Key::new(3, i, j);
                let c = lat.center(key);
                let far = c[1].abs() > 3f64.sqrt() / 2.0 + 1e-9
                    || 3f64.sqrt() * c[0].abs() + c[1].abs() > 3f64.sqrt() + 1e-9;
                let near = c[1].abs() < 3f64.sqrt() / 2.0 - 1e-9
                    && 3f64.sqrt() * c[0].abs() + c[1].abs() < 3f64.sqrt() - 1e-9;
                if far {
                    assert!(!key.inside(), "{key:?}");
                }
                if near {
                    assert!(key.inside() && !key.on_boundary(), "{key:?}");
                }
            }
        }
    }

    #[test]
    fn split_counter_counts_scalings_since_the_last_join() {
        assert_eq!(Key::ROOT.split_counter(), 0);
        assert_eq!(Key::new(2, 0, 0).split_counter(), 2);
        assert_eq!(Key::new(3, 2, 0).split_counter(), 1);
        assert_eq!(Key::new(3, 1, 0).split_counter(), 0);
    }

    #[test]
    fn nearest_finds_the_cell_of_its_own_centre() {
        let lat = unit();
        for i in -6..=6 {
            for j in -6..=6 {
                let key = Key::new(4, i, j);
                assert_eq!(lat.nearest(4, lat.center(key)), key);
            }
        }
    }
}
