//! The rhomb lattice of Neugebauer & Diekmann (paper 001, Sec. 3 "quad-tree"): cells are rhombs
//! with 60°/120° angles spanned by e1 = (1, 0) and e2 = (1/2, √3/2), split into four children.
//!
//! The root rhomb is c − R·e1 − R·e2 + [0, 2R]·e1 + [0, 2R]·e2 (c, R the bounding hexagon's centre
//! and circumradius). The flat-topped bounding hexagon is then made of lattice lines of every
//! level ≥ 1: in root units (u, v) ∈ [0, 2]² it is 0 ≤ u, v ≤ 2, 1 ≤ u + v ≤ 3, and u + v = const
//! is the direction of every cell's short diagonal (Sec. 4 step 10). So a point set needs no
//! boundary machinery: a cell half is either inside the hexagon or outside it.

use crate::geom::{Hexagon, Point};

/// Resolution of the global integer vertex keys: a key (I, J) is the lattice vertex
/// u = 2I/2^KEY_BITS, v = 2J/2^KEY_BITS. 2I + J stays below 2^53, so coordinates are exact
/// dyadic fractions before the one scaling by R.
pub const KEY_BITS: u32 = 50;

/// The finest cell level. Triangulation patterns use the midpoints of a cell's sides, one level
/// finer, and those must still have integer keys.
pub const MAX_LEVEL: u8 = (KEY_BITS - 2) as u8;

/// A lattice vertex at the global key resolution.
pub type VKey = (i64, i64);

/// A rhomb of the quad-tree: level k, corners (i, j), (i+1, j), (i+1, j+1), (i, j+1) in units of
/// the level-k side 2R/2^k.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Cell {
    pub level: u8,
    pub i: i64,
    pub j: i64,
}

/// The eight cells sharing a corner with a cell (the paper's first neighbours of equal size).
pub const AROUND: [(i64, i64); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// The four cells sharing a side: bottom, right, top, left.
pub const SIDES: [(i64, i64); 4] = [(0, -1), (1, 0), (0, 1), (-1, 0)];

impl Cell {
    pub const ROOT: Cell = Cell {
        level: 0,
        i: 0,
        j: 0,
    };

    pub fn new(level: u8, i: i64, j: i64) -> Cell {
        Cell { level, i, j }
    }

    pub fn offset(self, di: i64, dj: i64) -> Cell {
        Cell::new(self.level, self.i + di, self.j + dj)
    }

    pub fn parent(self) -> Cell {
        Cell::new(self.level - 1, self.i >> 1, self.j >> 1)
    }

    pub fn children(self) -> [Cell; 4] {
        let (l, i, j) = (self.level + 1, 2 * self.i, 2 * self.j);
        [
            Cell::new(l, i, j),
            Cell::new(l, i + 1, j),
            Cell::new(l, i, j + 1),
            Cell::new(l, i + 1, j + 1),
        ]
    }

    /// Inside the root rhomb.
    pub fn in_root(self) -> bool {
        let n = 1i64 << self.level;
        (0..n).contains(&self.i) && (0..n).contains(&self.j)
    }
}

/// The corners of half 0 ((i,j), (i+1,j), (i,j+1)) or half 1 ((i+1,j), (i+1,j+1), (i,j+1)) of a
/// rhomb, counter-clockwise; the short diagonal (i+1,j)–(i,j+1) separates them.
pub fn half_corners(c: Cell, half: u8) -> [(i64, i64); 3] {
    let (i, j) = (c.i, c.j);
    if half == 0 {
        [(i, j), (i + 1, j), (i, j + 1)]
    } else {
        [(i + 1, j), (i + 1, j + 1), (i, j + 1)]
    }
}

/// A rhomb half inside the closed bounding hexagon (for level ≥ 1 a half is inside or outside
/// as a whole).
pub fn half_in_hexagon(c: Cell, half: u8) -> bool {
    half_corners(c, half)
        .iter()
        .all(|&(i, j)| vertex_in_hexagon(c.level, i, j))
}

/// Level-k lattice vertex (i, j) inside the closed bounding hexagon: in root units
/// 0 ≤ u, v ≤ 2 and 1 ≤ u + v ≤ 3, with u = 2i/2^k.
pub fn vertex_in_hexagon(level: u8, i: i64, j: i64) -> bool {
    let n = 1i64 << level;
    (0..=n).contains(&i) && (0..=n).contains(&j) && n <= 2 * (i + j) && 2 * (i + j) <= 3 * n
}

/// Level-k lattice vertex (i, j) on the bounding hexagon's boundary: inside the closed hexagon
/// and on one of its six lines u = 0, v = 0, u = 2, v = 2, u + v = 1, u + v = 3.
pub fn vertex_on_boundary(level: u8, i: i64, j: i64) -> bool {
    let n = 1i64 << level;
    vertex_in_hexagon(level, i, j)
        && (i == 0 || j == 0 || i == n || j == n || 2 * (i + j) == n || 2 * (i + j) == 3 * n)
}

/// The global key of level-k lattice vertex (i, j).
pub fn key(level: u8, i: i64, j: i64) -> VKey {
    let shift = KEY_BITS - level as u32;
    (i << shift, j << shift)
}

/// The hexagon norm of a lattice vector (a, b) = a·e1 + b·e2: the circumradius, in lattice
/// steps, of the smallest flat-topped lattice hexagon around the origin holding it.
pub fn hexnorm(a: i64, b: i64) -> i64 {
    a.abs().max(b.abs()).max((a + b).abs())
}

/// Maps between the plane and the lattice of one bounding hexagon.
#[derive(Debug, Clone, Copy)]
pub struct Frame {
    hex: Hexagon,
    /// The hexagon's inradius, computed exactly as `Hexagon::corners` does.
    h: f64,
}

impl Frame {
    pub fn new(hex: Hexagon) -> Frame {
        Frame {
            hex,
            h: hex.circumradius * 3f64.sqrt() / 2.0,
        }
    }

    /// Root-normalised lattice coordinates (s, t) ∈ [0, 1]² of a point. Rounding here only
    /// decides which cell a point is sorted into; no sign of the mesh depends on it.
    pub fn locate(&self, p: Point) -> [f64; 2] {
        let [cx, cy] = self.hex.center;
        let [dx, dy] = self.hex.turn.undo([p[0] - cx, p[1] - cy]);
        let v = 1.0 + dy / self.h;
        let u = 1.0 + dx / self.hex.circumradius - (v - 1.0) / 2.0;
        [u / 2.0, v / 2.0]
    }

    /// The boundary lattice vertex whose f64 position (`point`) is `p` itself, at the coarsest
    /// level it has, if there is one; `st` is `locate(p)`. Rounding `point` can leave such a
    /// vertex a little inside the hexagon's edge, so that `p` passes the strict containment
    /// test although in real arithmetic it lies on the edge (the lattice points of the hex
    /// meshers of the same hexagon are built by the same formula, so bit-identical). Only the
    /// bit-for-bit equality decides; `st` merely proposes the candidate of each level.
    pub fn boundary_vertex(&self, p: Point, st: [f64; 2]) -> Option<(u8, i64, i64)> {
        // A cheap filter first: `locate` errs by a few ulps of 1, far below this.
        let near = |x: f64, line: f64| (x - line).abs() < 1e-9;
        let (s, t) = (st[0], st[1]);
        let near_edge = near(s, 0.0)
            || near(t, 0.0)
            || near(s, 1.0)
            || near(t, 1.0)
            || near(s + t, 0.5)
            || near(s + t, 1.5);
        if !near_edge {
            return None;
        }
        (1..=MAX_LEVEL).find_map(|level| {
            let n = (1i64 << level) as f64;
            let (i, j) = ((st[0] * n).round() as i64, (st[1] * n).round() as i64);
            let q = self.point(key(level, i, j));
            (vertex_on_boundary(level, i, j) && q[0] == p[0] && q[1] == p[1])
                .then_some((level, i, j))
        })
    }

    /// The plane coordinates of a lattice vertex. Written as c + R·a, c + h·b with the same h as
    /// `Hexagon::corners`, so the six hexagon corners come out bit-identical to it.
    pub fn point(&self, key: VKey) -> Point {
        let n = (1i64 << KEY_BITS) as f64;
        let a = (2 * key.0 + key.1 - 3 * (1i64 << (KEY_BITS - 1))) as f64 / n;
        let b = (2 * key.1 - (1i64 << KEY_BITS)) as f64 / n;
        let [cx, cy] = self.hex.center;
        // Each coordinate is rounded once, so its error is half an ulp of itself (README
        // "Checks"), as the hex lattice's are (`geom::turned_point`, `lattice_coordinate`).
        if !self.hex.turn.is_none() {
            // The turned hexagon's corners (`Hexagon::corners`): (A·X − B·Y)/2 with X = 2a,
            // Y = b.
            return crate::geom::turned_point(self.hex.center, self.hex.axes(), 2.0 * a, b, 0.5);
        }
        let x = if a == 0.0 {
            cx
        } else {
            crate::geom::lattice_coordinate(cx, self.hex.circumradius, a)
        };
        let y = if b == 0.0 {
            cy
        } else {
            crate::geom::lattice_coordinate(cy, self.h, b)
        };
        [x, y]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hexagon_corners_are_lattice_vertices_bit_exactly() {
        for hex in [
            Hexagon::new([0.0, 0.0], 1.0),
            Hexagon::new([0.3, -7.1], 0.0123),
            Hexagon::new([-0.0, -0.0], 1e3),
            Hexagon {
                turn: crate::geom::principal_turn(&[[0.0, 0.0], [1.0, 0.37], [0.4, 0.148]]),
                ..Hexagon::new([0.3, -7.1], 0.0123)
            },
        ] {
            let f = Frame::new(hex);
            // (u, v) = (2, 1), (1, 2), (0, 2), (0, 1), (1, 0), (2, 0) at level 1.
            let lattice = [(2, 1), (1, 2), (0, 2), (0, 1), (1, 0), (2, 0)];
            for (corner, &(i, j)) in hex.corners().iter().zip(&lattice) {
                let p = f.point(key(1, i, j));
                assert_eq!(p[0].to_bits(), corner[0].to_bits());
                assert_eq!(p[1].to_bits(), corner[1].to_bits());
                assert!(vertex_in_hexagon(1, i, j));
            }
        }
    }

    #[test]
    fn locate_inverts_point() {
        let flat = Hexagon::new([2.0, 3.0], 5.0);
        let turn = crate::geom::principal_turn(&[[0.0, 0.0], [1.0, 0.37], [0.4, 0.148]]);
        for hex in [flat, Hexagon { turn, ..flat }] {
            let f = Frame::new(hex);
            let k = key(4, 5, 9);
            let st = f.locate(f.point(k));
            assert!((st[0] - 5.0 / 16.0).abs() < 1e-14 && (st[1] - 9.0 / 16.0).abs() < 1e-14);
        }
    }

    #[test]
    fn hexagon_halves_are_whole_cells_halves() {
        // The root's corner triangles lie outside: vertex (0,0) and (2,2) in root units.
        assert!(!vertex_in_hexagon(1, 0, 0));
        assert!(!vertex_in_hexagon(1, 2, 2));
        assert!(half_in_hexagon(Cell::new(1, 1, 0), 0) && half_in_hexagon(Cell::new(1, 1, 0), 1));
        assert!(!half_in_hexagon(Cell::new(1, 0, 0), 0) && half_in_hexagon(Cell::new(1, 0, 0), 1));
    }
}
