//! The area balance: the triangles' areas sum to the area their boundary loops enclose.

use super::{DirectedEdge, Violation};
use crate::geom::{scale2, scale_exponent, scale_point, Point};
use crate::mesh::TriMesh;

/// The signed triangle areas must add up to the signed area of the boundary loops (shoelace
/// about the centre of the bounding box, to keep the cancellation small). Both are summed on
/// the coordinates scaled by the power of two that brings the largest into [1, 2) (exact, and
/// the same bits as unscaled wherever those products stay normal), so that no product of two
/// coordinates overflows or underflows; a mismatch reports them scaled back.
pub(super) fn area_balance(
    mesh: &TriMesh,
    geometric: &[bool],
    boundary: &[DirectedEdge],
    out: &mut Vec<Violation>,
) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for (t, &g) in geometric.iter().enumerate() {
        if g {
            for c in mesh.corners(t) {
                for d in 0..2 {
                    lo[d] = lo[d].min(c[d]);
                    hi[d] = hi[d].max(c[d]);
                }
            }
        }
    }
    if lo[0] > hi[0] {
        return; // no triangle to measure
    }
    let k = scale_exponent(&[lo[0], lo[1], hi[0], hi[1]]);
    let s = |p: Point| scale_point(p, -k);
    let (lo, hi) = (s(lo), s(hi));
    let o = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    let cross = |a: Point, b: Point| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let mut total = 0.0;
    let mut scale = 0.0;
    for (t, &g) in geometric.iter().enumerate() {
        if g {
            let [a, b, c] = mesh.corners(t).map(s);
            let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
            total += area;
            scale += area.abs();
        }
    }
    let enclosed: f64 = 0.5
        * boundary
            .iter()
            .map(|e| {
                cross(
                    s(mesh.vertices[e.from as usize]),
                    s(mesh.vertices[e.to as usize]),
                )
            })
            .sum::<f64>();
    if (total - enclosed).abs() > 1e-9 * scale.max(enclosed.abs()) {
        out.push(Violation::AreaMismatch {
            triangles: scale2(total, 2 * k),
            enclosed: scale2(enclosed, 2 * k),
        });
    }
}
