//! Boundary edges that cross or overlap, found by a sweep in x and decided with exact
//! orientation signs.

use super::{DirectedEdge, Violation};
use crate::geom::{orient2d_scaled, Point};

/// True when the closed segments ab and cd meet anywhere other than at an endpoint they
/// share as vertices (`shared`), decided with exact orientation signs.
fn segments_meet(a: Point, b: Point, c: Point, d: Point, shared: usize) -> bool {
    let o1 = orient2d_scaled(a, b, c);
    let o2 = orient2d_scaled(a, b, d);
    let o3 = orient2d_scaled(c, d, a);
    let o4 = orient2d_scaled(c, d, b);
    let between = |p: Point, q: Point, x: Point| {
        x[0] >= p[0].min(q[0])
            && x[0] <= p[0].max(q[0])
            && x[1] >= p[1].min(q[1])
            && x[1] <= p[1].max(q[1])
            && x != p
            && x != q
    };
    if o1 == 0.0 && o2 == 0.0 {
        return between(a, b, c) || between(a, b, d) || between(c, d, a) || between(c, d, b);
    }
    if shared > 0 {
        // Sharing an endpoint and not collinear: they meet only there.
        return false;
    }
    let proper = ((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0))
        && ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0));
    proper
        || (o1 == 0.0 && between(a, b, c))
        || (o2 == 0.0 && between(a, b, d))
        || (o3 == 0.0 && between(c, d, a))
        || (o4 == 0.0 && between(c, d, b))
        || c == a
        || c == b
        || d == a
        || d == b
}

/// Sweep over the boundary edges by x-interval; each candidate pair gets the exact test.
pub(super) fn boundary_crossings(
    verts: &[Point],
    boundary: &[DirectedEdge],
    out: &mut Vec<Violation>,
) {
    let p = |v: u32| verts[v as usize];
    let mut order: Vec<usize> = (0..boundary.len()).collect();
    let xmin = |k: usize| p(boundary[k].from)[0].min(p(boundary[k].to)[0]);
    let xmax = |k: usize| p(boundary[k].from)[0].max(p(boundary[k].to)[0]);
    order.sort_by(|&a, &b| xmin(a).total_cmp(&xmin(b)).then(a.cmp(&b)));
    let mut active: Vec<usize> = Vec::new();
    let mut found: Vec<(usize, usize)> = Vec::new();
    for &k in &order {
        let x = xmin(k);
        active.retain(|&j| xmax(j) >= x);
        let e = boundary[k];
        for &j in &active {
            let f = boundary[j];
            let shared = [e.from, e.to]
                .iter()
                .filter(|v| **v == f.from || **v == f.to)
                .count();
            if shared == 2 {
                // The same undirected edge twice cannot be a boundary edge; skip defensively.
                continue;
            }
            if segments_meet(p(e.from), p(e.to), p(f.from), p(f.to), shared) {
                found.push((j.min(k), j.max(k)));
            }
        }
        active.push(k);
    }
    found.sort_unstable();
    for (a, b) in found {
        let (e, f) = (boundary[a], boundary[b]);
        out.push(Violation::BoundaryCrossing {
            first: [e.from, e.to],
            second: [f.from, f.to],
            first_points: [p(e.from), p(e.to)],
            second_points: [p(f.from), p(f.to)],
        });
    }
}
