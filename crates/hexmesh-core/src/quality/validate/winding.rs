//! One sheet, by winding numbers (Stokes): the mesh covers the plane once just inside each
//! boundary edge (no overlap), and the triangles around each interior vertex wind around it
//! once (no fold).

use super::boundary::BoundaryLoop;
use super::{DirectedEdge, Topology, Violation};
use crate::geom::{orient2d_scaled, Dist2, Point};
use crate::mesh::TriMesh;

/// Contribution of the directed segment a→b to the winding number around `p`, counted on
/// the ray from `p` through `q` (Sunday's crossing rule with exact signs: an endpoint on the
/// ray's line counts as right of it, so shared endpoints are counted once).
fn ray_crossing(p: Point, q: Point, a: Point, b: Point) -> i64 {
    let left_a = orient2d_scaled(p, q, a) > 0.0;
    let left_b = orient2d_scaled(p, q, b) > 0.0;
    if !left_a && left_b && orient2d_scaled(a, b, p) > 0.0 {
        1
    } else if left_a && !left_b && orient2d_scaled(a, b, p) < 0.0 {
        -1
    } else {
        0
    }
}

/// `ray_crossing` for the ray from `p` towards +x, where "left of the ray" is "above p":
/// a y comparison, so it needs no second point on the ray (which p.x + 1 may not give).
fn horizontal_crossing(p: Point, a: Point, b: Point) -> i64 {
    let (above_a, above_b) = (a[1] > p[1], b[1] > p[1]);
    if !above_a && above_b && orient2d_scaled(a, b, p) > 0.0 {
        1
    } else if above_a && !above_b && orient2d_scaled(a, b, p) < 0.0 {
        -1
    } else {
        0
    }
}

/// The covering number just left of each tested boundary edge must be 1. Along a loop that
/// touches no other loop, that side is one region, so its longest edge stands for all of it;
/// loops through a shared vertex are tested edge by edge.
pub(super) fn overlaps(
    verts: &[Point],
    boundary: &[DirectedEdge],
    loops: &[BoundaryLoop],
    out: &mut Vec<Violation>,
) {
    let p = |v: u32| verts[v as usize];
    let len2 = |k: usize| Dist2::between(p(boundary[k].from), p(boundary[k].to));
    for l in loops {
        let tested: Vec<usize> = if l.pinched {
            l.edges.clone()
        } else {
            l.edges
                .iter()
                .copied()
                .max_by(|&a, &b| len2(a).cmp(&len2(b)).then(b.cmp(&a)))
                .into_iter()
                .collect()
        };
        for k in tested {
            let (a, b) = (p(boundary[k].from), p(boundary[k].to));
            let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            // A ray leaving the edge to its left, along the left normal, long enough that
            // adding it to m does not round away its direction.
            let normal = [-(b[1] - a[1]), b[0] - a[0]];
            let stretch =
                (m[0].abs().max(m[1].abs()) / normal[0].abs().max(normal[1].abs())).max(1.0);
            let q = [m[0] + stretch * normal[0], m[1] + stretch * normal[1]];
            if m == a || m == b || orient2d_scaled(a, b, q) <= 0.0 {
                continue; // too short or too large to place a probe; nothing to decide with
            }
            // m is within rounding of the edge; only a boundary edge passing within that
            // distance of the midpoint (boundaries touching to an ulp) could mislead the count.
            let covering: i64 = boundary
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != k)
                .map(|(_, f)| ray_crossing(m, q, p(f.from), p(f.to)))
                .sum();
            if covering != 1 {
                out.push(Violation::Overlap {
                    edge: [boundary[k].from, boundary[k].to],
                    points: [a, b],
                    covering,
                });
            }
        }
    }
}

/// Winding number of each interior vertex's link (the opposite edges of its triangles) around
/// it, counted on the horizontal ray; a fan that is one sheet winds exactly once.
pub(super) fn folds(mesh: &TriMesh, topo: &Topology, geometric: &[bool], out: &mut Vec<Violation>) {
    let n = mesh.vertices.len();
    let mut interior = vec![true; n];
    for e in &topo.boundary {
        interior[e.from as usize] = false;
        interior[e.to as usize] = false;
    }
    for &(u, v, _, _) in &topo.same_direction {
        interior[u as usize] = false;
        interior[v as usize] = false;
    }
    for (u, v, _) in &topo.overused {
        interior[*u as usize] = false;
        interior[*v as usize] = false;
    }
    let mut winding = vec![0i64; n];
    let mut seen = vec![false; n];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if !geometric[t] {
            for &v in tri {
                if (v as usize) < n {
                    interior[v as usize] = false;
                }
            }
            continue;
        }
        for k in 0..3 {
            let v = tri[k] as usize;
            let (a, b) = (tri[(k + 1) % 3] as usize, tri[(k + 2) % 3] as usize);
            let c = mesh.vertices[v];
            seen[v] = true;
            winding[v] += horizontal_crossing(c, mesh.vertices[a], mesh.vertices[b]);
        }
    }
    for v in 0..n {
        if interior[v] && seen[v] && winding[v] != 1 {
            out.push(Violation::Fold {
                vertex: v,
                point: mesh.vertices[v],
                winding: winding[v],
            });
        }
    }
}
