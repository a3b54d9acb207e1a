//! Flips in the re-triangulated cavity (ours). The constrained Delaunay triangulation puts a
//! triangle of three fixed centres into a notch of the cavity boundary (30°/109°/41° on imr);
//! such a triangle touches no segment, counts as interior and breaks the bounds, and
//! subdividing it only moves the notch (on imr three rounds went from 46k to 660k triangles).
//! It is flipped instead with its neighbour that has a corner on the segment. Since `band`
//! repairs most such triangles by points on the segments, this runs last, on the few it
//! leaves (one on imr, one on a 15° wedge).

use crate::geom::{orient2d, Point};
use crate::hex::extended::check::breaks_bounds;
use crate::hex::lattice::FxHashMap;

/// A cavity triangle with no corner on a segment counts as interior and must keep the Sec. 6
/// bounds; the constrained Delaunay triangulation makes such triangles where the cavity
/// boundary has a notch (two fixed centres two apart around a third). Where one breaks the
/// bounds, its edge towards a triangle with a corner on a segment is flipped when the two
/// form a strictly convex quadrilateral, so that both new triangles touch the segment (they
/// are near-segment triangles of Sec. 7). Returns the number of flips.
pub(super) fn flip_interior_cavity_triangles(
    vertices: &[Point],
    tris: &mut [[u32; 3]],
    on_segment: &[bool],
) -> u64 {
    let corners = |t: [u32; 3]| t.map(|v| vertices[v as usize]);
    let mut by_edge: FxHashMap<(u32, u32), usize> = FxHashMap::default();
    for (t, tri) in tris.iter().enumerate() {
        for e in 0..3 {
            by_edge.insert((tri[e], tri[(e + 1) % 3]), t);
        }
    }
    let mut flips = 0;
    for t in 0..tris.len() {
        let tri = tris[t];
        if tri.iter().any(|&v| on_segment[v as usize]) || !breaks_bounds(&corners(tri)) {
            continue;
        }
        for e in 0..3 {
            let (u, v, w) = (tri[e], tri[(e + 1) % 3], tri[(e + 2) % 3]);
            let Some(&o) = by_edge.get(&(v, u)) else {
                continue;
            };
            let other = tris[o];
            let Some(&d) = other.iter().find(|&&x| x != u && x != v) else {
                continue;
            };
            if !on_segment[d as usize] {
                continue;
            }
            let (pu, pv, pw, pd) = (
                vertices[u as usize],
                vertices[v as usize],
                vertices[w as usize],
                vertices[d as usize],
            );
            if orient2d(pu, pd, pw) <= 0.0 || orient2d(pd, pv, pw) <= 0.0 {
                continue;
            }
            for (a, b) in [(u, v), (v, w), (w, u), (v, u), (u, d), (d, v)] {
                by_edge.remove(&(a, b));
            }
            tris[t] = [u, d, w];
            tris[o] = [d, v, w];
            for (a, b, x) in [
                (u, d, t),
                (d, w, t),
                (w, u, t),
                (d, v, o),
                (v, w, o),
                (w, d, o),
            ] {
                by_edge.insert((a, b), x);
            }
            flips += 1;
            break;
        }
    }
    flips
}
