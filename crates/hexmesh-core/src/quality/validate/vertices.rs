//! Vertices by their coordinate bits: the hash key of a point, and duplicate vertices.

use super::Violation;
use crate::geom::Point;

/// A hash key for a point: the bits of both coordinates, with -0.0 folded into 0.0 (adding
/// 0.0 does exactly that) so the two zeros, which compare equal, hash equal.
pub(crate) fn point_key(p: Point) -> (u64, u64) {
    ((p[0] + 0.0).to_bits(), (p[1] + 0.0).to_bits())
}

/// Sorting by coordinate bits puts equal points next to each other; each later copy is
/// reported against the first.
pub(super) fn duplicate_vertices(verts: &[Point], out: &mut Vec<Violation>) {
    let mut order: Vec<usize> = (0..verts.len()).collect();
    order.sort_by_key(|&i| (point_key(verts[i]), i));
    let mut i = 0;
    while i < order.len() {
        let mut j = i + 1;
        while j < order.len() && point_key(verts[order[j]]) == point_key(verts[order[i]]) {
            out.push(Violation::DuplicateVertex {
                first: order[i],
                second: order[j],
                point: verts[order[i]],
            });
            j += 1;
        }
        i = j;
    }
}
