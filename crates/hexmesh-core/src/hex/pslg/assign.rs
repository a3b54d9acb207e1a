//! Segments assigned to hexagons, paper Sec. 7.1: a segment belongs to every leaf whose
//! closed constructed hexagon it meets, decided exactly (`hexagon_meets_segment`: `orient2d`
//! against the lattice's bit-shared corners). A segment that only touches a hexagon's edge or
//! corner is assigned to it too, so a segment on the common edge of two hexagons belongs to
//! both. A semi-hexagon is tested as the half of its cell inside its owner (four of the cell's
//! corners). The assignment is recomputed from the hierarchy after every batch of splits and
//! joins (`crossed_cells`), which gives the same sets as re-assigning to the children at each
//! split and join, as the paper does.

use std::collections::BTreeMap;

use crate::geom::{orient2d, Point};
use crate::hex::lattice::{FxHashSet, Key};
use crate::hex::subdivision::{Cell, Hierarchy};

/// True when the closed convex hexagon with counter-clockwise `corners` and the closed segment
/// ab share a point. Exact: no hexagon edge has both a and b strictly outside it, and the line
/// ab does not have all six corners strictly on one side (separating axes of two convex sets).
pub fn hexagon_meets_segment(corners: &[Point; 6], a: Point, b: Point) -> bool {
    polygon_meets_segment(corners, a, b)
}

/// `hexagon_meets_segment` for any closed convex polygon with counter-clockwise corners.
pub fn polygon_meets_segment(corners: &[Point], a: Point, b: Point) -> bool {
    let n = corners.len();
    for m in 0..n {
        let (p, q) = (corners[m], corners[(m + 1) % n]);
        if orient2d(p, q, a) < 0.0 && orient2d(p, q, b) < 0.0 {
            return false;
        }
    }
    let sides: Vec<f64> = corners.iter().map(|&c| orient2d(a, b, c)).collect();
    !(sides.iter().all(|&s| s > 0.0) || sides.iter().all(|&s| s < 0.0))
}

/// The leaves (full unsubdivided hexagons and semi-hexagons) each segment meets, with the
/// indices of the segments meeting them, sorted: the assignment of Sec. 7.1 by the rule of the
/// module docs, found by descending from the root through the hexagons the segment meets.
pub fn crossed_cells(h: &Hierarchy, segments: &[[Point; 2]]) -> BTreeMap<Key, Vec<u32>> {
    let mut out: BTreeMap<Key, Vec<u32>> = BTreeMap::new();
    for (s, &[a, b]) in segments.iter().enumerate() {
        let mut stack = vec![Key::ROOT];
        let mut seen: FxHashSet<Key> = FxHashSet::default();
        while let Some(key) = stack.pop() {
            if !key.inside() || !seen.insert(key) {
                continue;
            }
            let corners = h.lattice.corners(key);
            if !hexagon_meets_segment(&corners, a, b) {
                continue;
            }
            let cell = h.cell(key);
            // A semi-hexagon is the half of its cell inside its owner: the four corners of the
            // cell in the owner's closed hexagon (the two on the long edge are corners of both).
            if let Cell::Semi { owner, .. } = cell {
                let half: Vec<Point> = corners
                    .into_iter()
                    .filter(|&c| h.closed_contains(owner, c))
                    .collect();
                if !polygon_meets_segment(&half, a, b) {
                    continue;
                }
            }
            match cell {
                Cell::Full { subdivided: true } => stack.extend(key.children()),
                Cell::Full { subdivided: false } | Cell::Semi { .. } => {
                    out.entry(key).or_default().push(s as u32)
                }
                _ => {}
            }
        }
    }
    for v in out.values_mut() {
        v.sort_unstable();
        v.dedup();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_hexagon() -> [Point; 6] {
        std::array::from_fn(|m| {
            let a = (60.0 * m as f64).to_radians();
            [a.cos(), a.sin()]
        })
    }

    #[test]
    fn a_segment_through_the_hexagon_meets_it() {
        let c = unit_hexagon();
        assert!(hexagon_meets_segment(&c, [-2.0, 0.1], [2.0, -0.1]));
        assert!(hexagon_meets_segment(&c, [0.0, 0.0], [0.1, 0.1]));
    }

    #[test]
    fn a_segment_beside_the_hexagon_does_not_meet_it() {
        let c = unit_hexagon();
        assert!(!hexagon_meets_segment(&c, [-2.0, 1.0], [2.0, 1.0]));
        assert!(!hexagon_meets_segment(&c, [1.5, -3.0], [1.5, 3.0]));
        // The line meets the hexagon, the segment stops short of it.
        assert!(!hexagon_meets_segment(&c, [-3.0, 0.0], [-1.5, 0.0]));
    }

    #[test]
    fn a_segment_touching_a_corner_or_lying_on_an_edge_meets_the_closed_hexagon() {
        let c = unit_hexagon();
        assert!(hexagon_meets_segment(&c, [1.0, 0.0], [2.0, 0.0]));
        assert!(hexagon_meets_segment(&c, c[1], c[2]));
        assert!(hexagon_meets_segment(&c, [-2.0, c[1][1]], [2.0, c[1][1]]));
    }
}
