//! The integer lattice behind the hexagon hierarchy (paper 000, Sußner & Greiner 2009,
//! Sec. 3.1): a hexagon of level k is the cell of lattice point (i, j)
//! with centre o + r_k·(i·u + j·v), r_k = r_0/2^k, u = (3/2, √3/2), v = (0, √3).
//!
//! Every coordinate the mesher constructs (centres and cell corners) goes through one formula
//! on a normalised integer key, so the same geometric point always gets the same f64 bits: two
//! cells sharing a corner share it bit for bit, and exact predicates on constructed corners then
//! see a tiling without gaps or overlaps.

use crate::geom::{lattice_coordinate, turned_point, Hexagon, Point, Turn, CORNER_X, CORNER_Y};

// The keys and the containers once kept here, re-exported so that their old paths keep
// working (the keys live in `key`, which the containers use without the lattice).
pub use crate::hex::fxhash::{FxBuild, FxHashMap, FxHashSet, FxHasher};
pub use crate::hex::key::{Key, Parents, DIRS, MAX_LEVEL};
pub use crate::hex::keylines::{ByteLine, IndexLine, KeyBytes, KeyIndex, KeyLines, Line};
pub use crate::hex::keyset::KeySet;

/// Positions of lattice points of a given root hexagon.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lattice {
    /// The root's centre o.
    pub origin: Point,
    /// The root's circumradius r_0 (level k has r_0/2^k).
    pub r0: f64,
    /// r_0·√3, rounded once, so that every y coordinate is one product and one sum.
    sqrt3_r0: f64,
    /// The root's rotation (`Hexagon::turn`); with one, positions are o + the turned axes
    /// (`Hexagon::axes`, `turned_point`) applied to (X, Y).
    pub turn: Turn,
    axes: [f64; 4],
}

impl Lattice {
    /// The lattice whose level-0 cell is `root`.
    pub fn new(root: Hexagon) -> Lattice {
        Lattice {
            origin: root.center,
            r0: root.circumradius,
            sqrt3_r0: root.circumradius * 3f64.sqrt(),
            turn: root.turn,
            axes: root.axes(),
        }
    }

    /// The level-0 hexagon (the one `new` was given).
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

#[cfg(test)]
mod tests {
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
