//! Integer keys of the hexagon hierarchy (paper 000, Sußner & Greiner 2009, Sec. 3.1): a
//! hexagon of level k is lattice point (i, j) of that level. Keys, their children, parents and
//! neighbours are integer arithmetic only; `lattice` turns them into positions.

/// Deepest level the mesher constructs. Lattice coordinates of level k need k + 2 bits, and
/// they must stay exact in an f64 mantissa (53 bits) when a position is computed.
pub const MAX_LEVEL: u8 = 50;

/// The six lattice directions, counter-clockwise, starting at 30° (the neighbour across the
/// upper-right edge of a flat-topped hexagon).
pub const DIRS: [(i64, i64); 6] = [(1, 0), (0, 1), (-1, 1), (-1, 0), (0, -1), (1, -1)];

/// A lattice cell: the hexagon of level `k` centred at lattice point (i, j).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Key {
    /// The level: 0 for the root, circumradius r_0/2^k.
    pub k: u8,
    /// The coordinate along u = (3/2, √3/2), in units of r_k.
    pub i: i64,
    /// The coordinate along v = (0, √3), in units of r_k.
    pub j: i64,
}

impl Key {
    /// The root hexagon: level 0, centred at the origin o.
    pub const ROOT: Key = Key { k: 0, i: 0, j: 0 };

    /// The cell of level `k` at lattice point (`i`, `j`).
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
    /// The root has no parent.
    None,
    /// A central child: the one hexagon it is the centre of.
    Central(Key),
    /// An edge child: the two hexagons one level up that share the edge whose midpoint is its
    /// centre.
    Edge(Key, Key),
}
