//! Quad-tree corners near the boundary (paper 001 Sec. 5, first paragraph, and Sec. 5.2 case
//! 1): a corner p of the tree is the centre of a hexagon a_0..a_5 of side l; v_i is where the
//! boundary crosses side (p, a_i), and v_j the crossing nearest p. A corner of four rhombs of
//! one size is moved away from the boundary, to the midpoint of (p, a_{j+3}), when
//! dist(p, v_j) < l/2, and stays otherwise.
//!
//! Both decisions are exact: whether a boundary side crosses (p, a_i) is a pair of exact
//! orientation signs of the f64 positions; along side i the crossing lies at
//! t_i = o_p / (o_p − o_a) of the way from p (o_x the orientation of x against the boundary
//! side, computed exactly as an expansion), so t_i < t_k and t_i < 1/2 are signs of degree-4
//! polynomials (`exact`). The moved corner, the midpoint of two level-k lattice vertices, is a
//! lattice vertex of level k + 1: its position comes from its key like every other.
//!
//! The domain method uses `meets` (in `cut`); the hexagon crossing and the move are kept
//! for the tests of `boxes` and `fan`, which build their lattices with it. `cut` moves the
//! corners next to the boundary its own way (Sec. 5.2 case 1, generalised).

#[cfg(test)]
use super::exact::Exact;
use crate::geom::{orient2d, Point};

/// The six hexagon directions around a lattice vertex, counter-clockwise from e1: a_i is
/// p + DIRECTIONS[i] in lattice steps, a_{i+3} the opposite one.
#[cfg(test)]
pub const DIRECTIONS: [(i64, i64); 6] = [(1, 0), (0, 1), (-1, 1), (-1, 0), (0, -1), (1, -1)];

/// Where the boundary crosses the hexagon of a corner first.
#[cfg(test)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Nearest {
    /// j: the hexagon side (p, a_j) with the crossing nearest p.
    pub side: usize,
    /// dist(p, v_j) < l/2: Sec. 5.2 case 1 moves the corner.
    pub within_half: bool,
}

/// The exact orientation of c against the line ab, scaled by 2^k per coordinate difference.
#[cfg(test)]
fn orient(a: Point, b: Point, c: Point, k: i32) -> Exact {
    let d = |u: f64, v: f64| Exact::diff(u, v).scaled(k);
    let (bx, by) = (d(b[0], a[0]), d(b[1], a[1]));
    let (cx, cy) = (d(c[0], a[0]), d(c[1], a[1]));
    bx.mul(&cy).sub(&by.mul(&cx))
}

/// True when the closed segments pq and ab meet (exact signs).
pub fn meets(p: Point, q: Point, a: Point, b: Point) -> bool {
    let (o1, o2) = (orient2d(a, b, p), orient2d(a, b, q));
    let (o3, o4) = (orient2d(p, q, a), orient2d(p, q, b));
    let apart = |x: f64, y: f64| (x > 0.0 && y > 0.0) || (x < 0.0 && y < 0.0);
    if o1 == 0.0 && o2 == 0.0 {
        // Collinear: they meet when their extents along the line overlap.
        let axis = usize::from((p[0] - q[0]).abs() < (p[1] - q[1]).abs());
        let (lo, hi) = (p[axis].min(q[axis]), p[axis].max(q[axis]));
        return a[axis].max(b[axis]) >= lo && a[axis].min(b[axis]) <= hi;
    }
    !apart(o1, o2) && !apart(o3, o4)
}

/// A crossing of side (p, a) at t = num / den of the way from p (both exact, den > 0).
#[cfg(test)]
struct Crossing {
    num: Exact,
    den: Exact,
}

#[cfg(test)]
impl Crossing {
    /// The crossing of (p, a) by boundary side bc, if they meet; `k` scales the differences.
    fn of(p: Point, a: Point, b: Point, c: Point, k: i32) -> Option<Crossing> {
        if !meets(p, a, b, c) {
            return None;
        }
        let (op, oa) = (orient(b, c, p, k), orient(b, c, a, k));
        let den = op.sub(&oa);
        match den.sign() {
            0 => Some(Crossing {
                // bc runs along (p, a): it reaches p's side at its nearer end.
                num: Exact::of(0.0),
                den: Exact::of(1.0),
            }),
            s if s > 0 => Some(Crossing { num: op, den }),
            _ => Some(Crossing {
                num: op.neg(),
                den: den.neg(),
            }),
        }
    }

    /// self.t < other.t, exactly.
    fn before(&self, other: &Crossing) -> bool {
        self.num
            .mul(&other.den)
            .sub(&other.num.mul(&self.den))
            .sign()
            < 0
    }

    /// t < 1/2, exactly.
    fn within_half(&self) -> bool {
        self.num.add(&self.num).sub(&self.den).sign() < 0
    }
}

/// The nearest crossing of the hexagon sides (p, a_i) by the boundary sides `boundary`, if
/// any: the first side in counter-clockwise order among equally near ones. `scale` is the
/// exponent of the hexagon's side length (for the exact arithmetic's range).
#[cfg(test)]
pub fn nearest(
    p: Point,
    hexagon: &[Point; 6],
    boundary: &[[Point; 2]],
    scale: i32,
) -> Option<Nearest> {
    let mut best: Option<(usize, Crossing)> = None;
    for (i, &a) in hexagon.iter().enumerate() {
        for &[b, c] in boundary {
            if let Some(x) = Crossing::of(p, a, b, c, -scale) {
                if best.as_ref().is_none_or(|(_, y)| x.before(y)) {
                    best = Some((i, x));
                }
            }
        }
    }
    best.map(|(side, x)| Nearest {
        side,
        within_half: x.within_half(),
    })
}

/// Sec. 5.2 case 1: where level-`level` corner (i, j) of four equal rhombs goes, as a vertex
/// of level `level + 1`: itself, or the midpoint of (p, a_{j+3}) when the nearest crossing is
/// within half a side.
#[cfg(test)]
pub fn moved(level: u8, i: i64, j: i64, near: Nearest) -> (u8, i64, i64) {
    let (di, dj) = if near.within_half {
        DIRECTIONS[(near.side + 3) % 6]
    } else {
        (0, 0)
    };
    (level + 1, 2 * i + di, 2 * j + dj)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit hexagon around the origin, in the plane (e1 = (1, 0), e2 = (1/2, √3/2)).
    fn hexagon() -> [Point; 6] {
        let h = 3f64.sqrt() / 2.0;
        DIRECTIONS.map(|(a, b)| [a as f64 + b as f64 / 2.0, b as f64 * h])
    }

    #[test]
    fn a_boundary_a_third_of_a_side_to_the_right_moves_the_corner_left() {
        let wall = [[1.0 / 3.0, -5.0], [1.0 / 3.0, 5.0]];
        let near = nearest([0.0, 0.0], &hexagon(), &[wall], 0).unwrap();
        // Side 0 (towards e1) is crossed at 1/3; sides 1 and 5 (at ±60°) at 2/3.
        assert_eq!(
            near,
            Nearest {
                side: 0,
                within_half: true
            }
        );
        // Level 3 corner (4, 4) goes to the level-4 midpoint towards a_3 = (3, 4).
        assert_eq!(moved(3, 4, 4, near), (4, 7, 8));
    }

    #[test]
    fn a_boundary_beyond_half_a_side_leaves_the_corner() {
        let wall = [[0.6, -5.0], [0.6, 5.0]];
        let near = nearest([0.0, 0.0], &hexagon(), &[wall], 0).unwrap();
        assert_eq!(
            near,
            Nearest {
                side: 0,
                within_half: false
            }
        );
        assert_eq!(moved(3, 4, 4, near), (4, 8, 8));
        assert_eq!(
            nearest([0.0, 0.0], &hexagon(), &[[[2.0, 0.0], [2.0, 1.0]]], 0),
            None
        );
    }

    #[test]
    fn exactly_half_a_side_is_not_within_half() {
        // The wall through the midpoint of side 0, x = 1/2 exactly.
        let near = nearest([0.0, 0.0], &hexagon(), &[[[0.5, -1.0], [0.5, 1.0]]], 0).unwrap();
        assert!(!near.within_half);
        let closer = nearest(
            [0.0, 0.0],
            &hexagon(),
            &[[[0.5 - f64::EPSILON, -1.0], [0.5 - f64::EPSILON, 1.0]]],
            0,
        )
        .unwrap();
        assert!(closer.within_half);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2000))]

        /// Table 1, row BB_1: after the move of Sec. 5.2 case 1, a corner of four equal
        /// rhombs lies between √3/4·l = 0.433 l and l from a straight boundary crossing its
        /// hexagon (l_1, l_2 of the border-box). The nearest crossing is on the side most
        /// nearly perpendicular to the boundary, within 30° of its normal, so a corner left
        /// where it is (crossing at l/2 or more) is at least l/2 · sin 60° away, and a moved
        /// one gains l/2 · sin 60° or more on at most l/2.
        #[test]
        fn a_moved_corner_lies_between_0_433_and_1_side_from_the_boundary(
            normal in 0.0..std::f64::consts::TAU,
            offset in 0.0..1.0f64,
        ) {
            let n = [normal.cos(), normal.sin()];
            let (q, t) = ([offset * n[0], offset * n[1]], [-n[1], n[0]]);
            let wall = [
                [q[0] - 5.0 * t[0], q[1] - 5.0 * t[1]],
                [q[0] + 5.0 * t[0], q[1] + 5.0 * t[1]],
            ];
            if let Some(near) = nearest([0.0, 0.0], &hexagon(), &[wall], 0) {
                let (level, di, dj) = moved(0, 0, 0, near);
                proptest::prop_assert_eq!(level, 1);
                let h = 3f64.sqrt() / 2.0;
                let p = [(di as f64 + dj as f64 / 2.0) / 2.0, dj as f64 * h / 2.0];
                // Distance from the wall's line, on p's side (the origin's, away from it).
                let d = offset - (p[0] * n[0] + p[1] * n[1]);
                proptest::prop_assert!(
                    d >= 3f64.sqrt() / 4.0 - 1e-12 && d <= 1.0 + 1e-12,
                    "{:?} {} {}", near, offset, d
                );
            } else {
                // No side crossed: the wall is beyond the hexagon's inradius.
                proptest::prop_assert!(offset > 3f64.sqrt() / 2.0 - 1e-12);
            }
        }
    }

    #[test]
    fn the_nearest_of_two_boundary_sides_decides_the_direction() {
        // A corner of the boundary: one side crosses e2's side at 0.45, the other crosses
        // side 3 (towards −e1) at 0.4.
        let h = 3f64.sqrt() / 2.0;
        let upper = [[-2.0, 0.45 * h], [2.0, 0.45 * h]];
        let left = [[-0.4, -2.0], [-0.4, 2.0]];
        let near = nearest([0.0, 0.0], &hexagon(), &[upper, left], 0).unwrap();
        assert_eq!(near.side, 3);
        assert!(near.within_half);
        // Far from the origin and tiny, the same configuration decides the same way.
        let s = 2f64.powi(-20);
        let shift = |p: Point| [1.0 + p[0] * s, 3.0 + p[1] * s];
        let hex = hexagon().map(shift);
        let far = nearest(
            shift([0.0, 0.0]),
            &hex,
            &[upper.map(shift), left.map(shift)],
            -20,
        )
        .unwrap();
        assert_eq!(far.side, 3);
    }
}
