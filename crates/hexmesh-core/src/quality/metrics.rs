//! Quality figures of a triangle mesh: angles and their histogram, the
//! paper's "aspect ratio", which is Verdict's radius ratio R/(2r) (Sußner & Greiner 2009,
//! Sec. 6.2: 1.20787 for the 43.9°/46.1°/90° triangle), edge ratio, shortest edge over d_min
//! (Sec. 6.3), and the Delaunay property (Sec. 6.4) by the exact empty-circle test.
//! `metrics_split` reports the figures near input segments and away from them apart, since on
//! a PSLG the bounds hold only in the interior (Sec. 7).

use crate::geom::{
    angle_deg, dist_scaled, incircle_scaled, orient2d_scaled, scale2, scale_exponent, scale_point,
    vector_angle_deg, Point,
};
use crate::mesh::{Pslg, TriMesh};
use crate::quality::validate::{topology, Topology};

/// A figure and the triangle where it is reached.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Worst {
    /// The figure (angles in degrees).
    pub value: f64,
    /// The 0-based index of a triangle reaching it (the first, in triangle order).
    pub triangle: usize,
}

/// An interior edge that fails the exact empty-circle test.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct DelaunayEdge {
    /// The edge's two vertex indices (0-based).
    pub edge: [u32; 2],
    /// The two triangles sharing the edge; the first traverses `edge` in its order.
    pub triangles: [usize; 2],
}

/// Quality figures of a mesh. Angles are in degrees. Figures over an empty set are `None`.
/// Triangles naming vertices that do not exist are left out (`validate` reports them).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Metrics {
    /// Vertices of the mesh (for a part of a mesh: the vertices its triangles use).
    pub vertices: usize,
    /// Triangles of the mesh (or the part), those left out of the figures included.
    pub triangles: usize,
    /// The smallest angle of any triangle.
    pub min_angle: Option<Worst>,
    /// The largest angle of any triangle.
    pub max_angle: Option<Worst>,
    /// Counts of all triangle angles in 1° bins: bin k holds angles in [k°, k+1°), 180° in
    /// bin 179.
    pub angle_histogram: Vec<u64>,
    /// Verdict's radius ratio R/(2r): circumradius over incircle diameter, 1 for equilateral.
    pub radius_ratio_max: Option<Worst>,
    /// The mean radius ratio over the triangles.
    pub radius_ratio_mean: Option<f64>,
    /// Longest over shortest edge of a triangle.
    pub edge_ratio_max: Option<Worst>,
    /// The shortest edge of the mesh; `triangle` is one triangle having it.
    pub shortest_edge: Option<Worst>,
    /// The smallest distance between two input points; on an input with segments, between
    /// two input features that share no point (`quality::feature_gap`).
    pub d_min: Option<f64>,
    /// `shortest_edge` over `d_min`; the paper's bound for `hex` is √7/(12√3) ≈ 0.12729.
    pub shortest_edge_over_d_min: Option<f64>,
    /// Interior edges (shared by two triangles in opposite directions).
    pub interior_edges: usize,
    /// Interior edges whose opposite vertex lies strictly inside the other triangle's
    /// circumcircle (exact incircle; cocircular is not a violation).
    pub delaunay_violations: usize,
    /// The first such edge, in edge order.
    pub delaunay_first: Option<DelaunayEdge>,
    /// Interior edges whose two opposite angles sum to more than 180° + 1e-7°: violations
    /// that rounding of constructed vertices cannot explain.
    pub delaunay_tolerance_violations: usize,
    /// Sum of the signed triangle areas.
    pub covered_area: f64,
}

/// Slack of the angle-sum form of the Delaunay test, in degrees: an edge whose two opposite
/// angles sum to more than 180° plus this is a violation rounding cannot explain.
pub const DELAUNAY_ANGLE_SLACK_DEG: f64 = 1e-7;

/// Angles (degrees), radius ratio, edge ratio and edge lengths of one triangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangleShape {
    /// Angle at each corner, in degrees.
    pub angles: [f64; 3],
    /// R/(2r), 1 for equilateral; infinite when degenerate.
    pub radius_ratio: f64,
    /// Longest over shortest edge.
    pub edge_ratio: f64,
    /// The shortest edge's length.
    pub shortest_edge: f64,
}

/// The difference b − a.
fn sub(b: Point, a: Point) -> [f64; 2] {
    [b[0] - a[0], b[1] - a[1]]
}

/// The cross product u × v.
fn cross(u: [f64; 2], v: [f64; 2]) -> f64 {
    u[0] * v[1] - u[1] * v[0]
}

/// The shape figures of triangle (a, b, c). R/(2r) = abc·s / (8·A²) with s the semiperimeter
/// (R = abc/(4A), r = A/s); infinite for a degenerate triangle.
pub fn triangle_shape(p: [Point; 3]) -> TriangleShape {
    shape_and_area(p).0
}

/// `triangle_shape` and the signed area of the triangle. Every figure is computed on the
/// edge vectors scaled by the power of two 2^-e that brings their largest component into
/// [1, 2): exact, so angles and ratios are those of the unscaled vectors (bit for bit where
/// the unscaled products neither overflow nor underflow), and no product of four lengths
/// (the radius ratio) overflows or underflows at any coordinates. The shortest edge is
/// scaled back by 2^e and the area by 2^2e.
fn shape_and_area(p: [Point; 3]) -> (TriangleShape, f64) {
    let [a, b, c] = p;
    // The differences from each corner to the other two, as the unscaled formulas take them.
    let d = [
        sub(b, a),
        sub(c, a),
        sub(c, b),
        sub(a, b),
        sub(a, c),
        sub(b, c),
    ];
    // b − a, c − b and a − c hold every magnitude (the others are their negatives).
    let e = scale_exponent(&[d[0][0], d[0][1], d[2][0], d[2][1], d[4][0], d[4][1]]);
    let [ab, ac, bc, ba, ca, cb] = d.map(|v| scale_point(v, -e));
    let angles = [
        vector_angle_deg(ab, ac),
        vector_angle_deg(bc, ba),
        vector_angle_deg(ca, cb),
    ];
    // Edge k is opposite corner k.
    let length = |v: [f64; 2]| (v[0] * v[0] + v[1] * v[1]).sqrt();
    let l = [length(cb), length(ac), length(ba)];
    let shortest = l[0].min(l[1]).min(l[2]);
    let longest = l[0].max(l[1]).max(l[2]);
    let signed = 0.5 * cross(ab, ac);
    let area = signed.abs();
    let s = 0.5 * (l[0] + l[1] + l[2]);
    let radius_ratio = if area > 0.0 {
        l[0] * l[1] * l[2] * s / (8.0 * area * area)
    } else {
        f64::INFINITY
    };
    let shape = TriangleShape {
        angles,
        radius_ratio,
        edge_ratio: if shortest > 0.0 {
            longest / shortest
        } else {
            f64::INFINITY
        },
        shortest_edge: scale2(shortest, e),
    };
    (shape, scale2(signed, 2 * e))
}

/// Quality figures of the whole mesh; `input` supplies d_min.
pub fn metrics(mesh: &TriMesh, input: Option<&Pslg>) -> Metrics {
    metrics_with(mesh, input, &topology(mesh))
}

/// [`metrics`] with the mesh's edge structure built already (`topology`), as the verdict
/// shares it with the validity checks.
pub(crate) fn metrics_with(mesh: &TriMesh, input: Option<&Pslg>, topo: &Topology) -> Metrics {
    let all: Vec<usize> = (0..mesh.triangles.len()).collect();
    let mut m = metrics_of(mesh, &all, input, topo);
    m.vertices = mesh.vertices.len();
    m
}

fn keep_min(slot: &mut Option<Worst>, value: f64, triangle: usize) {
    if !value.is_nan() && slot.is_none_or(|w| value < w.value) {
        *slot = Some(Worst { value, triangle });
    }
}

fn keep_max(slot: &mut Option<Worst>, value: f64, triangle: usize) {
    if !value.is_nan() && slot.is_none_or(|w| value > w.value) {
        *slot = Some(Worst { value, triangle });
    }
}

/// Figures over the triangles `subset` (indices into the mesh, ascending). Interior edges
/// count only when both their triangles are in the subset.
fn metrics_of(mesh: &TriMesh, subset: &[usize], input: Option<&Pslg>, topo: &Topology) -> Metrics {
    let n = mesh.vertices.len();
    let in_range = |t: usize| mesh.triangles[t].iter().all(|&v| (v as usize) < n);
    let mut member = vec![false; mesh.triangles.len()];
    let mut used = vec![false; n];
    let mut m = Metrics {
        vertices: 0,
        triangles: 0,
        min_angle: None,
        max_angle: None,
        angle_histogram: vec![0; 180],
        radius_ratio_max: None,
        radius_ratio_mean: None,
        edge_ratio_max: None,
        shortest_edge: None,
        d_min: None,
        shortest_edge_over_d_min: None,
        interior_edges: 0,
        delaunay_violations: 0,
        delaunay_first: None,
        delaunay_tolerance_violations: 0,
        covered_area: 0.0,
    };
    let mut ratio_sum = 0.0;
    for &t in subset {
        m.triangles += 1;
        if !in_range(t) {
            continue;
        }
        member[t] = true;
        for &v in &mesh.triangles[t] {
            used[v as usize] = true;
        }
        let p = mesh.corners(t);
        let (shape, area) = shape_and_area(p);
        for &a in &shape.angles {
            keep_min(&mut m.min_angle, a, t);
            keep_max(&mut m.max_angle, a, t);
            if a.is_finite() {
                m.angle_histogram[(a.floor().max(0.0) as usize).min(179)] += 1;
            }
        }
        keep_max(&mut m.radius_ratio_max, shape.radius_ratio, t);
        ratio_sum += shape.radius_ratio;
        keep_max(&mut m.edge_ratio_max, shape.edge_ratio, t);
        keep_min(&mut m.shortest_edge, shape.shortest_edge, t);
        m.covered_area += area;
    }
    m.vertices = used.iter().filter(|&&u| u).count();
    let measured = member.iter().filter(|&&x| x).count();
    if measured > 0 {
        m.radius_ratio_mean = Some(ratio_sum / measured as f64);
    }

    let opposite = |t: usize, u: u32, v: u32| -> Option<u32> {
        mesh.triangles[t]
            .iter()
            .copied()
            .find(|&w| w != u && w != v)
    };
    for &(u, v, t1, t2) in &topo.interior {
        if !member[t1] || !member[t2] {
            continue;
        }
        m.interior_edges += 1;
        let (Some(w1), Some(w2)) = (opposite(t1, u, v), opposite(t2, u, v)) else {
            continue;
        };
        let p = |x: u32| mesh.vertices[x as usize];
        let (pu, pv, p1, p2) = (p(u), p(v), p(w1), p(w2));
        let Some(inside) = breaks_empty_circle(pu, pv, p1, p2) else {
            continue; // no circle to test; validate reports the coordinate
        };
        if inside {
            m.delaunay_violations += 1;
            if m.delaunay_first.is_none() {
                m.delaunay_first = Some(DelaunayEdge {
                    edge: [u, v],
                    triangles: [t1, t2],
                });
            }
        }
        if angle_deg(p1, pu, pv) + angle_deg(p2, pu, pv) > 180.0 + DELAUNAY_ANGLE_SLACK_DEG {
            m.delaunay_tolerance_violations += 1;
        }
    }

    if let Some(input) = input {
        // The closest pair of points, or on a domain of features (`feature_gap`).
        m.d_min = crate::quality::feature_gap(input).map(|c| c.distance);
    }
    if let (Some(d), Some(s)) = (m.d_min, m.shortest_edge) {
        if d > 0.0 {
            m.shortest_edge_over_d_min = Some(s.value / d);
        }
    }
    m
}

/// Whether `p2` lies strictly inside the circle through the edge (pu, pv) and `p1`, the
/// vertices opposite the edge on its two sides (the exact empty-circle test of the edge);
/// `None` when a coordinate is not finite. A flipped triangle is validate's business, but the
/// sign still means "inside". The scaled predicates give exact signs at any coordinate
/// magnitude (`robust` alone overflows in incircle from about 1e77 on and underflows below
/// about 1e-80).
fn breaks_empty_circle(pu: Point, pv: Point, p1: Point, p2: Point) -> Option<bool> {
    if [pu, pv, p1, p2]
        .iter()
        .any(|q| !q[0].is_finite() || !q[1].is_finite())
    {
        return None;
    }
    let o = orient2d_scaled(pu, pv, p1);
    Some(if o > 0.0 {
        incircle_scaled(pu, pv, p1, p2) > 0.0
    } else if o < 0.0 {
        incircle_scaled(pv, pu, p1, p2) > 0.0
    } else {
        false
    })
}

/// The edges shared by two triangles that fail the exact empty-circle test and do not lie on
/// an input segment (a constrained Delaunay mesh has none): how many, and the first. The
/// segments are the chains of edges the conformity check walks (`validate::chains`).
pub fn off_segment_delaunay_violations(
    mesh: &TriMesh,
    input: &Pslg,
) -> (usize, Option<DelaunayEdge>) {
    let topo = topology(mesh);
    let on_segment = crate::quality::validate::chains::segment_edges(mesh, input, &topo);
    let opposite = |t: usize, u: u32, v: u32| {
        mesh.triangles[t]
            .iter()
            .copied()
            .find(|&w| w != u && w != v)
    };
    let p = |x: u32| mesh.vertices[x as usize];
    let mut count = 0;
    let mut first = None;
    for (u, v, t1, t2) in topo.interior {
        if on_segment.contains(&(u.min(v), u.max(v))) {
            continue;
        }
        let (Some(w1), Some(w2)) = (opposite(t1, u, v), opposite(t2, u, v)) else {
            continue;
        };
        if breaks_empty_circle(p(u), p(v), p(w1), p(w2)) == Some(true) {
            count += 1;
            first.get_or_insert(DelaunayEdge {
                edge: [u, v],
                triangles: [t1, t2],
            });
        }
    }
    (count, first)
}

/// Figures of the triangles near the input segments and of the rest, apart.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct SplitMetrics {
    /// The distance from a segment within which a triangle counts as near.
    pub band: f64,
    /// Triangles that touch a segment or come within `band` of one.
    pub near: Metrics,
    /// The other triangles, where the interior bounds apply.
    pub interior: Metrics,
    /// Indices of the near triangles, ascending.
    pub near_triangles: Vec<usize>,
}

/// Splits the mesh into triangles touching an input segment (sharing a point with it, decided
/// exactly) or within distance `band` of one, and the rest, and gives the figures of each.
/// Worst-triangle indices refer to the whole mesh. Without segments every triangle is interior.
pub fn metrics_split(mesh: &TriMesh, input: &Pslg, band: f64) -> SplitMetrics {
    metrics_split_with(mesh, input, band, &topology(mesh))
}

/// [`metrics_split`] with the mesh's edge structure built already (`topology`).
pub(crate) fn metrics_split_with(
    mesh: &TriMesh,
    input: &Pslg,
    band: f64,
    topo: &Topology,
) -> SplitMetrics {
    let near_triangles = near_segment_triangles(mesh, input, band.max(0.0));
    let mut is_near = vec![false; mesh.triangles.len()];
    for &t in &near_triangles {
        is_near[t] = true;
    }
    let rest: Vec<usize> = (0..mesh.triangles.len()).filter(|&t| !is_near[t]).collect();
    SplitMetrics {
        band,
        near: metrics_of(mesh, &near_triangles, Some(input), topo),
        interior: metrics_of(mesh, &rest, Some(input), topo),
        near_triangles,
    }
}

/// The distance within which a vertex counts as lying on an input segment: the conformity
/// check's 2^-40 of the segments' coordinate scale (`validate`). A mesher that splits a
/// segment at a constructed point can only round it onto the line; the triangles at such a
/// point touch the segment, and count as near-segment triangles, not as interior ones.
pub fn on_segment_tolerance(input: &Pslg) -> f64 {
    let scale = input
        .segments
        .iter()
        .filter_map(|s| {
            Some((
                input.points.get(s[0] as usize)?,
                input.points.get(s[1] as usize)?,
            ))
        })
        .map(|(a, b)| {
            [a[0], a[1], b[0], b[1]]
                .iter()
                .fold(crate::geom::dist(*a, *b), |m, c| m.max(c.abs()))
        })
        .fold(0.0, f64::max);
    scale * (-40f64).exp2()
}

/// The triangles near a segment, found through a uniform grid of triangle bounding boxes so
/// that each segment tests only the triangles around it.
pub(crate) fn near_segment_triangles(mesh: &TriMesh, input: &Pslg, band: f64) -> Vec<usize> {
    let n = mesh.vertices.len();
    let segments: Vec<(Point, Point)> = input
        .segments
        .iter()
        .filter_map(|s| {
            Some((
                *input.points.get(s[0] as usize)?,
                *input.points.get(s[1] as usize)?,
            ))
        })
        .collect();
    let tris: Vec<usize> = (0..mesh.triangles.len())
        .filter(|&t| {
            mesh.triangles[t].iter().all(|&v| (v as usize) < n)
                && mesh
                    .corners(t)
                    .iter()
                    .all(|p| p[0].is_finite() && p[1].is_finite())
        })
        .collect();
    if segments.is_empty() || tris.is_empty() {
        return Vec::new();
    }
    let bbox = |ps: &[Point]| {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in ps {
            for d in 0..2 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
        (lo, hi)
    };
    let all: Vec<Point> = tris.iter().flat_map(|&t| mesh.corners(t)).collect();
    let (lo, hi) = bbox(&all);
    let side = (tris.len() as f64).sqrt().ceil().clamp(1.0, 512.0) as usize;
    let cell = [
        ((hi[0] - lo[0]) / side as f64).max(f64::MIN_POSITIVE),
        ((hi[1] - lo[1]) / side as f64).max(f64::MIN_POSITIVE),
    ];
    let cell_of = |x: f64, d: usize| -> usize {
        let k = ((x - lo[d]) / cell[d]).floor();
        if k.is_nan() || k < 0.0 {
            0
        } else {
            (k as usize).min(side - 1)
        }
    };
    let mut grid: Vec<Vec<usize>> = vec![Vec::new(); side * side];
    for &t in &tris {
        let (a, b) = bbox(&mesh.corners(t));
        for i in cell_of(a[0], 0)..=cell_of(b[0], 0) {
            for j in cell_of(a[1], 1)..=cell_of(b[1], 1) {
                grid[i * side + j].push(t);
            }
        }
    }
    let half_diagonal = 0.5 * cell[0].hypot(cell[1]);
    let mut near = vec![false; mesh.triangles.len()];
    for &(a, b) in &segments {
        let (slo, shi) = bbox(&[a, b]);
        for i in cell_of(slo[0] - band, 0)..=cell_of(shi[0] + band, 0) {
            for j in cell_of(slo[1] - band, 1)..=cell_of(shi[1] + band, 1) {
                // A triangle within `band` has a point in some cell it is filed under, and
                // that cell's centre is within half a diagonal of the point: skip cells
                // farther than that, so a long diagonal segment visits a strip, not its box.
                let centre = [
                    lo[0] + (i as f64 + 0.5) * cell[0],
                    lo[1] + (j as f64 + 0.5) * cell[1],
                ];
                if point_segment(centre, a, b) > (half_diagonal + band) * (1.0 + 1e-6) {
                    continue;
                }
                for &t in &grid[i * side + j] {
                    if !near[t] && triangle_near_segment(mesh.corners(t), a, b, band) {
                        near[t] = true;
                    }
                }
            }
        }
    }
    (0..mesh.triangles.len()).filter(|&t| near[t]).collect()
}

/// True when the closed triangle and the segment ab share a point (exact), or their distance
/// is at most `band` (rounded arithmetic).
fn triangle_near_segment(p: [Point; 3], a: Point, b: Point, band: f64) -> bool {
    let on_segment = |q: Point, a: Point, b: Point| {
        orient2d_scaled(a, b, q) == 0.0
            && q[0] >= a[0].min(b[0])
            && q[0] <= a[0].max(b[0])
            && q[1] >= a[1].min(b[1])
            && q[1] <= a[1].max(b[1])
    };
    let inside = |q: Point| {
        let o = [
            orient2d_scaled(p[0], p[1], q),
            orient2d_scaled(p[1], p[2], q),
            orient2d_scaled(p[2], p[0], q),
        ];
        o.iter().all(|&x| x >= 0.0) || o.iter().all(|&x| x <= 0.0)
    };
    let crosses = |c: Point, d: Point| {
        let o1 = orient2d_scaled(a, b, c);
        let o2 = orient2d_scaled(a, b, d);
        let o3 = orient2d_scaled(c, d, a);
        let o4 = orient2d_scaled(c, d, b);
        let opposite = |x: f64, y: f64| (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0);
        (opposite(o1, o2) && opposite(o3, o4))
            || on_segment(c, a, b)
            || on_segment(d, a, b)
            || on_segment(a, c, d)
            || on_segment(b, c, d)
    };
    if inside(a) || inside(b) || (0..3).any(|k| crosses(p[k], p[(k + 1) % 3])) {
        return true;
    }
    if band <= 0.0 {
        return false;
    }
    let d = (0..3)
        .map(|k| {
            point_segment(p[k], a, b)
                .min(point_segment(a, p[k], p[(k + 1) % 3]))
                .min(point_segment(b, p[k], p[(k + 1) % 3]))
        })
        .fold(f64::INFINITY, f64::min);
    d <= band
}

/// Distance from `q` to the segment ab (rounded arithmetic). The parameter of the nearest
/// point is computed on ab and aq scaled by one power of two (exact; the quotient does not
/// see it), and the distance by `dist_scaled`, so that no square overflows or underflows.
pub(crate) fn point_segment(q: Point, a: Point, b: Point) -> f64 {
    let ab = sub(b, a);
    let aq = sub(q, a);
    let e = scale_exponent(&[ab[0], ab[1], aq[0], aq[1]]);
    let (sab, saq) = (scale_point(ab, -e), scale_point(aq, -e));
    let l2 = sab[0] * sab[0] + sab[1] * sab[1];
    let t = if l2 > 0.0 {
        ((saq[0] * sab[0] + saq[1] * sab[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    dist_scaled(q, [a[0] + t * ab[0], a[1] + t * ab[1]])
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A k×k grid of unit squares, each split into two triangles.
    fn grid_mesh(k: u32) -> TriMesh {
        let vertices = (0..=k)
            .flat_map(|j| (0..=k).map(move |i| [i as f64, j as f64]))
            .collect();
        let id = |i: u32, j: u32| j * (k + 1) + i;
        let triangles = (0..k)
            .flat_map(|j| {
                (0..k).flat_map(move |i| {
                    [
                        [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                        [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
                    ]
                })
            })
            .collect();
        TriMesh {
            vertices,
            triangles,
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn the_grid_search_finds_exactly_the_near_triangles(
            k in 1u32..25,
            segs in prop::collection::vec(((-2.0..27.0f64, -2.0..27.0f64), (-2.0..27.0f64, -2.0..27.0f64)), 1..4),
            band in prop::sample::select(vec![0.0, 0.3, 1.0, 4.0]),
        ) {
            let mesh = grid_mesh(k);
            let mut input = Pslg::default();
            for ((ax, ay), (bx, by)) in segs {
                let n = input.points.len() as u32;
                input.points.extend([[ax, ay], [bx, by]]);
                input.segments.push([n, n + 1]);
            }
            let brute: Vec<usize> = (0..mesh.triangles.len())
                .filter(|&t| {
                    input.segments.iter().any(|s| {
                        let (a, b) = (input.points[s[0] as usize], input.points[s[1] as usize]);
                        triangle_near_segment(mesh.corners(t), a, b, band)
                    })
                })
                .collect();
            prop_assert_eq!(near_segment_triangles(&mesh, &input, band), brute);
        }
    }
}
