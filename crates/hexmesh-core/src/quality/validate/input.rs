//! Conformity to the input: every input point is a mesh vertex, every input segment a chain
//! of mesh edges along it, and, where the segments bound a region, the mesh ends at them.

use std::collections::HashMap;

use super::vertices::point_key;
use super::{DirectedEdge, Topology, Violation};
use crate::geom::{dist, orient2d_scaled, scale_exponent, scale_point, Point};
use crate::mesh::{Pslg, TriMesh};

/// Every input point must be a vertex (bit-exact); with `conforming`, every input segment a
/// chain of mesh edges whose vertices lie on it (within rounding), walked from one endpoint to
/// the other.
pub(super) fn input_conformity(
    mesh: &TriMesh,
    topo: &Topology,
    boundary: &[DirectedEdge],
    input: &Pslg,
    conforming: bool,
    out: &mut Vec<Violation>,
) {
    let mut index: HashMap<(u64, u64), u32> = HashMap::with_capacity(mesh.vertices.len());
    for (v, &p) in mesh.vertices.iter().enumerate().rev() {
        // Reverse order so that the first of duplicate vertices wins.
        index.insert(point_key(p), v as u32);
    }
    let vertex_of: Vec<Option<u32>> = input
        .points
        .iter()
        .map(|&p| index.get(&point_key(p)).copied())
        .collect();
    for (i, (&p, v)) in input.points.iter().zip(&vertex_of).enumerate() {
        if v.is_none() {
            out.push(Violation::MissingInputPoint { input: i, point: p });
        }
    }
    if !conforming || input.segments.is_empty() {
        return;
    }

    // Adjacency in compressed rows, from every edge of the usable triangles.
    let n = mesh.vertices.len();
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if topo.usable[t] {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                pairs.push((a, b));
                pairs.push((b, a));
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    let mut start = vec![0usize; n + 1];
    for &(a, _) in &pairs {
        start[a as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let neighbours = |v: u32| {
        pairs[start[v as usize]..start[v as usize + 1]]
            .iter()
            .map(|e| e.1)
    };

    // The mesh edges the segment chains walk, as (low, high) vertex pairs.
    let mut on_segments: Vec<(u32, u32)> = Vec::new();
    let mut conforms = true;
    for (s, seg) in input.segments.iter().enumerate() {
        let (ia, ib) = (seg[0] as usize, seg[1] as usize);
        let (Some(&pa), Some(&pb)) = (input.points.get(ia), input.points.get(ib)) else {
            conforms = false;
            continue; // Pslg::check reports segments naming missing points
        };
        let not_conforming = |stuck_at| Violation::SegmentNotConforming {
            segment: s,
            endpoints: *seg,
            points: [pa, pb],
            stuck_at,
        };
        let (Some(va), Some(vb)) = (vertex_of[ia], vertex_of[ib]) else {
            out.push(not_conforming(None));
            conforms = false;
            continue;
        };
        // Progress along the dominant axis of the segment: exact for collinear points.
        let (axis, sign) = if (pb[0] - pa[0]).abs() >= (pb[1] - pa[1]).abs() {
            (0, (pb[0] - pa[0]).signum())
        } else {
            (1, (pb[1] - pa[1]).signum())
        };
        let progress = |v: u32| sign * mesh.vertices[v as usize][axis];
        // Meshers split segments at constructed points (midpoints, crossings) that f64 can only
        // round onto the segment's line; a vertex counts as on the segment when it is within
        // 2^-40 of the segment's coordinate scale of the line: rounding, never a visible kink.
        // Input endpoints still have to match bit-exactly (above). The test runs on the points
        // scaled by the power of two that brings the segment's largest coordinate into [1, 2)
        // (exact; every quantity below scales alike, so the decision is the unscaled one),
        // so that neither the length nor the orientation under- or overflows.
        let k = scale_exponent(&[pa[0], pa[1], pb[0], pb[1]]);
        let (sa, sb) = (scale_point(pa, -k), scale_point(pb, -k));
        let length = dist(sa, sb);
        let scale = [sa[0], sa[1], sb[0], sb[1]]
            .iter()
            .fold(length, |m, c| m.max(c.abs()));
        let tolerance = scale * (-40f64).exp2();
        let on_line = |pw: Point| {
            let o = orient2d_scaled(sa, sb, scale_point(pw, -k));
            o == 0.0 || o.abs() / length <= tolerance
        };
        let end = progress(vb);
        let mut u = va;
        while u != vb {
            let here = progress(u);
            let step = neighbours(u)
                .filter(|&w| {
                    let pw = mesh.vertices[w as usize];
                    on_line(pw) && progress(w) > here && progress(w) <= end
                })
                .min_by(|&x, &y| progress(x).total_cmp(&progress(y)).then(x.cmp(&y)));
            match step {
                Some(w) => {
                    on_segments.push((u.min(w), u.max(w)));
                    u = w;
                }
                None => {
                    out.push(not_conforming(Some((u, mesh.vertices[u as usize]))));
                    conforms = false;
                    break;
                }
            }
        }
    }

    // The domain of a PSLG is what its segments bound (Triangle's .poly semantics): once
    // every segment is a chain of edges, every boundary edge must be one of those chains'
    // edges. (A broken chain is reported above; its boundary edges would only repeat it.)
    // Segments that bound nothing leave the mesher its own domain (hex keeps the bounding
    // hexagon): then there is nothing to hold the boundary to.
    if conforms && segments_bound_a_region(input) {
        on_segments.sort_unstable();
        for e in boundary {
            let key = (e.from.min(e.to), e.from.max(e.to));
            if on_segments.binary_search(&key).is_err() {
                out.push(Violation::BoundaryOffSegments {
                    edge: [e.from, e.to],
                    points: [mesh.vertices[e.from as usize], mesh.vertices[e.to as usize]],
                });
            }
        }
    }
}

/// True when the segments close a cycle, so that they bound a region: they do not cross
/// (`Pslg::check`), so a cycle of them is a closed curve. Union-find over the endpoints.
fn segments_bound_a_region(input: &Pslg) -> bool {
    let mut parent: Vec<usize> = (0..input.points.len()).collect();
    fn root(parent: &mut [usize], mut v: usize) -> usize {
        while parent[v] != v {
            parent[v] = parent[parent[v]];
            v = parent[v];
        }
        v
    }
    for s in &input.segments {
        let (a, b) = (s[0] as usize, s[1] as usize);
        if a >= parent.len() || b >= parent.len() || a == b {
            continue;
        }
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        if ra == rb {
            return true;
        }
        parent[ra] = rb;
    }
    false
}
