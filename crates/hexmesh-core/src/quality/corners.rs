//! Input corners sharper than a mesher's smallest angle. The rhomboidal quad-tree (paper 001,
//! Sec. 1) promises every angle in [30°, 90°] except at the input's own corners sharper than
//! 30°: no mesh can do better there than the corner itself, and a good one leaves the corner
//! whole, one triangle at the corner with its two edges along the corner's two segments.
//! Quality references (Triangle, CGAL, spade) do the same: they cannot split a sharp input
//! angle into better ones. `quality::verdict` exempts exactly such angles from a minimum-angle
//! bound when the bounds say so (`Bounds::whole_sharp_corners`); a split corner is not
//! exempt, since each of its pieces is sharper still and one of its edges is not an input
//! segment.

use std::collections::HashMap;

use super::validate::vertices::point_key;
use crate::geom::Point;
use crate::mesh::Pslg;

/// The input segments leaving each input point, to tell whether a mesh angle at an input
/// point is a whole input corner.
pub(crate) struct InputCorners {
    /// For each input point (by its coordinate bits), the other endpoints of its segments.
    ends: HashMap<(u64, u64), Vec<Point>>,
    /// How far a vertex may lie off a segment and still be on it: the conformity check's
    /// tolerance (`metrics::on_segment_tolerance`), since meshers round split points.
    tolerance: f64,
}

impl InputCorners {
    /// The corners of `input`'s segments.
    pub(crate) fn new(input: &Pslg) -> InputCorners {
        let mut ends: HashMap<(u64, u64), Vec<Point>> = HashMap::new();
        for s in &input.segments {
            let (Some(&a), Some(&b)) = (
                input.points.get(s[0] as usize),
                input.points.get(s[1] as usize),
            ) else {
                continue;
            };
            ends.entry(point_key(a)).or_default().push(b);
            ends.entry(point_key(b)).or_default().push(a);
        }
        InputCorners {
            ends,
            tolerance: super::metrics::on_segment_tolerance(input),
        }
    }

    /// True when the angle at `a` of the triangle (a, b, c) is an input corner taken whole:
    /// `a` is an input point and both `b` and `c` lie on input segments leaving `a`.
    pub(crate) fn whole_at(&self, a: Point, b: Point, c: Point) -> bool {
        let Some(ends) = self.ends.get(&point_key(a)) else {
            return false;
        };
        let along = |p: Point| ends.iter().any(|&u| lies_along(a, u, p, self.tolerance));
        along(b) && along(c)
    }
}

/// True when `p` lies on the segment from `a` to `u`, beyond `a`, within `tolerance` of it.
fn lies_along(a: Point, u: Point, p: Point, tolerance: f64) -> bool {
    let (dx, dy) = (u[0] - a[0], u[1] - a[1]);
    let (wx, wy) = (p[0] - a[0], p[1] - a[1]);
    let len = dx.hypot(dy);
    if len == 0.0 {
        return false;
    }
    let along = (wx * dx + wy * dy) / len;
    let off = (dx * wy - dy * wx).abs() / len;
    along > 0.0 && along <= len + tolerance && off <= tolerance
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 10° corner at the origin between segments along the x-axis and at 10°.
    fn wedge() -> Pslg {
        let r = 10f64.to_radians();
        Pslg {
            points: vec![[0.0, 0.0], [1.0, 0.0], [r.cos(), r.sin()]],
            segments: vec![[0, 1], [1, 2], [2, 0]],
            ..Pslg::default()
        }
    }

    #[test]
    fn a_triangle_spanning_the_corner_takes_it_whole() {
        let input = wedge();
        let corners = InputCorners::new(&input);
        let r = 10f64.to_radians();
        // Edges to points part-way along both segments.
        let b = [0.5, 0.0];
        let c = [0.5 * r.cos(), 0.5 * r.sin()];
        assert!(corners.whole_at([0.0, 0.0], b, c));
        assert!(corners.whole_at([0.0, 0.0], c, b));
    }

    #[test]
    fn a_split_corner_and_a_point_off_the_segments_are_not_whole() {
        let input = wedge();
        let corners = InputCorners::new(&input);
        let mid = 5f64.to_radians();
        // An interior edge at 5°: each half has one edge along a segment only.
        assert!(!corners.whole_at([0.0, 0.0], [0.5, 0.0], [0.5 * mid.cos(), 0.5 * mid.sin()]));
        // A point beyond the segment's far end, and a vertex that is no input point.
        assert!(!corners.whole_at([0.0, 0.0], [1.5, 0.0], [0.5, 0.08]));
        assert!(!corners.whole_at([0.5, 0.0], [1.0, 0.0], [0.0, 0.0]));
    }
}
