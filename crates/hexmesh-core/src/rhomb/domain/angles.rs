//! The angle figures of a mesh of a domain, for the tests of rhomb's promise there (paper 001
//! Sec. 1: every angle in [30°, 90°] but input angles below 30°). Every angle of every
//! triangle is computed; the only ones exempt are at an input vertex whose two triangle edges
//! both lie on input segments through that vertex, so that the triangle's angle there is the
//! whole input corner (or a part of it bounded by segments on both sides). An edge lies on
//! segment (v, k) when it ends at k, or at a vertex within the conformity tolerance of the
//! segment strictly between its ends (a Steiner point rounded onto it).
//!
//! Angles are compared with [30°, 90°] widened by each angle's rounding allowance
//! (`quality::rounding::angle_allowance`), as `quality::verdict` does.

use crate::geom::{angle_deg, dist, orient2d, Point};
use crate::mesh::{Pslg, TriMesh};
use crate::quality::rounding::angle_allowance;

/// What the tests read: the extremes of the angles that count, split into the triangles
/// touching a segment and the others, and the angles out of bounds.
#[derive(Debug, Clone, PartialEq)]
pub struct AngleFigures {
    pub triangles: usize,
    /// Extremes over all counted angles, degrees.
    pub min: f64,
    pub max: f64,
    /// Extremes over triangles with a vertex on an input segment.
    pub near_min: f64,
    pub near_max: f64,
    /// Exempt angles: (triangle, corner, degrees).
    pub exempt: Vec<(usize, usize, f64)>,
    /// Counted angles beyond [lo − allowance, hi + allowance]: (triangle, corner, degrees).
    pub outside: Vec<(usize, usize, f64)>,
}

/// Whether mesh vertex `w` lies on input segment `s` away from its end `v`: it is the other
/// end, or within `tol` of the segment's line strictly between the ends.
fn along(mesh: &TriMesh, input: &Pslg, s: [u32; 2], v: u32, w: u32, tol: f64) -> bool {
    let k = if s[0] == v { s[1] } else { s[0] };
    if w == k {
        return true;
    }
    let (a, b, q) = (
        input.points[v as usize],
        input.points[k as usize],
        mesh.vertices[w as usize],
    );
    let len = dist(a, b);
    let off = orient2d(a, b, q).abs() / len;
    let t = ((q[0] - a[0]) * (b[0] - a[0]) + (q[1] - a[1]) * (b[1] - a[1])) / (len * len);
    off <= tol && t > 0.0 && t < 1.0
}

/// Whether vertex `w` lies on any input segment: an input point that ends one, or another
/// vertex within `tol` inside one.
fn on_some_segment(mesh: &TriMesh, input: &Pslg, w: u32, tol: f64) -> bool {
    if (w as usize) < input.points.len() {
        return input.segments.iter().any(|s| s.contains(&w));
    }
    input
        .segments
        .iter()
        .any(|&s| along(mesh, input, s, s[0], w, tol))
}

/// The figures of `mesh` against the bounds [lo, hi] (degrees), with input point i being
/// vertex i.
pub fn angle_figures(mesh: &TriMesh, input: &Pslg, lo: f64, hi: f64) -> AngleFigures {
    let tol = crate::quality::metrics::on_segment_tolerance(input);
    let n_in = input.points.len() as u32;
    let mut f = AngleFigures {
        triangles: mesh.triangles.len(),
        min: f64::INFINITY,
        max: f64::NEG_INFINITY,
        near_min: f64::INFINITY,
        near_max: f64::NEG_INFINITY,
        exempt: Vec::new(),
        outside: Vec::new(),
    };
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let near = tri.iter().any(|&w| on_some_segment(mesh, input, w, tol));
        for m in 0..3 {
            let (v, w1, w2) = (tri[m], tri[(m + 1) % 3], tri[(m + 2) % 3]);
            let p: [Point; 3] = [v, w1, w2].map(|x| mesh.vertices[x as usize]);
            let angle = angle_deg(p[0], p[1], p[2]);
            let bounded = |w: u32| {
                input
                    .segments
                    .iter()
                    .any(|&s| s.contains(&v) && along(mesh, input, s, v, w, tol))
            };
            if v < n_in && bounded(w1) && bounded(w2) {
                f.exempt.push((t, m, angle));
                continue;
            }
            f.min = f.min.min(angle);
            f.max = f.max.max(angle);
            if near {
                f.near_min = f.near_min.min(angle);
                f.near_max = f.near_max.max(angle);
            }
            let slack = angle_allowance(p[0], p[1], p[2]);
            if angle < lo - slack || angle > hi + slack {
                f.outside.push((t, m, angle));
            }
        }
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 5° wedge of `pslg-wedge-5`, cut into an apex triangle and the rest by a Steiner
    /// point on each long side.
    fn wedge() -> (Pslg, TriMesh) {
        let r = 5f64.to_radians();
        let input = Pslg {
            points: vec![[0.0, 0.0], [1.0, 0.0], [r.cos(), r.sin()]],
            segments: vec![[0, 1], [1, 2], [2, 0]],
            ..Pslg::default()
        };
        let mut vertices = input.points.clone();
        vertices.push([0.5, 0.0]);
        vertices.push([0.5 * r.cos(), 0.5 * r.sin()]);
        let mesh = TriMesh {
            vertices,
            triangles: vec![[0, 3, 4], [3, 1, 2], [3, 2, 4]],
        };
        (input, mesh)
    }

    #[test]
    fn the_whole_sharp_input_corner_is_exempt_and_nothing_else() {
        let (input, mesh) = wedge();
        let f = angle_figures(&mesh, &input, 30.0, 90.0);
        // Exempt: the apex (triangle 0, corner 0: edges to 3 and 4, on the two segments at
        // 0) and corner 1 of triangle 1 (edges to 2 and to 3, on the segments at 1).
        let exempt: Vec<(usize, usize)> = f.exempt.iter().map(|&(t, m, _)| (t, m)).collect();
        assert_eq!(exempt, vec![(0, 0), (1, 1)]);
        assert!((f.exempt[0].2 - 5.0).abs() < 1e-9);
        assert!((f.exempt[1].2 - 87.5).abs() < 1e-9);
        // Corner 2 of triangle 1 and corner 1 of triangle 2 split the input corner at 2 by an
        // inner edge: they count (82.54° and 4.96°), as do all angles at Steiner points.
        assert!((f.min - 4.962_281).abs() < 1e-6, "{f:?}");
        assert!((f.max - 92.5).abs() < 1e-9, "{f:?}");
        let outside: Vec<(usize, usize)> = f.outside.iter().map(|&(t, m, _)| (t, m)).collect();
        assert_eq!(outside, vec![(1, 0), (2, 1), (2, 2)]);
        assert_eq!(f.triangles, 3);
    }

    #[test]
    fn a_sharp_angle_at_an_input_vertex_with_an_inner_edge_counts() {
        let (input, mut mesh) = wedge();
        // Remove the segment: no angle is exempt, the 5° one is out of bounds.
        let free = Pslg {
            segments: Vec::new(),
            ..input.clone()
        };
        let f = angle_figures(&mesh, &free, 30.0, 90.0);
        assert!(f.exempt.is_empty());
        assert!(f
            .outside
            .iter()
            .any(|&(t, m, a)| (t, m) == (0, 0) && a < 5.1));
        // A vertex moved off the side (not on the segment) un-exempts the apex.
        mesh.vertices[4] = [0.5 * 0.996, 0.06];
        let f = angle_figures(&mesh, &input, 30.0, 90.0);
        assert!(f.exempt.iter().all(|&(t, m, _)| (t, m) != (0, 0)), "{f:?}");
        assert!(f
            .outside
            .iter()
            .any(|&(t, m, a)| (t, m) == (0, 0) && a < 7.0));
    }

    #[test]
    fn near_segment_figures_cover_triangles_touching_a_segment() {
        let (input, mesh) = wedge();
        let f = angle_figures(&mesh, &input, 30.0, 90.0);
        // Every triangle of the wedge touches a segment.
        assert_eq!(f.near_min, f.min);
        assert_eq!(f.near_max, f.max);
    }
}
