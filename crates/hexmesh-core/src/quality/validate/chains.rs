//! Input items found in a mesh: the vertex of each input point (bit-exact coordinates) and the
//! chain of mesh edges along each input segment. The conformity check (`input`) and the
//! boundary derivation of the writers (`io::boundary`) read the same chains, so that a mesh
//! `verify` calls conforming is labelled along exactly the edges it checked.

use std::collections::HashMap;

use super::vertices::point_key;
use crate::geom::{dist, orient2d_scaled, scale_exponent, scale_point, Point};
use crate::mesh::{Pslg, TriMesh};

/// The mesh vertex of each input point: the vertex with the same coordinate bits (-0.0 and
/// 0.0 count as one), the first of duplicate vertices; `None` when there is none.
pub(crate) fn input_vertices(mesh: &TriMesh, input: &Pslg) -> Vec<Option<u32>> {
    let mut index: HashMap<(u64, u64), u32> = HashMap::with_capacity(mesh.vertices.len());
    for (v, &p) in mesh.vertices.iter().enumerate().rev() {
        // Reverse order so that the first of duplicate vertices wins.
        index.insert(point_key(p), v as u32);
    }
    input
        .points
        .iter()
        .map(|&p| index.get(&point_key(p)).copied())
        .collect()
}

/// The neighbours of every vertex along the edges of the usable triangles, in compressed
/// rows sorted by vertex.
pub(crate) struct Adjacency {
    pairs: Vec<(u32, u32)>,
    start: Vec<usize>,
}

impl Adjacency {
    /// The adjacency of the triangles whose `usable` flag is set.
    pub(crate) fn new(mesh: &TriMesh, usable: &[bool]) -> Adjacency {
        let n = mesh.vertices.len();
        let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(6 * mesh.triangles.len());
        for (t, tri) in mesh.triangles.iter().enumerate() {
            if usable[t] {
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
        Adjacency { pairs, start }
    }

    /// The neighbours of `v`, ascending.
    pub(crate) fn neighbours(&self, v: u32) -> impl Iterator<Item = u32> + '_ {
        self.pairs[self.start[v as usize]..self.start[v as usize + 1]]
            .iter()
            .map(|e| e.1)
    }
}

/// The walk along one segment: the edges found, in order from the first endpoint, and the
/// vertex where the walk stopped short of the second endpoint (`None` when it arrived).
pub(crate) struct Chain {
    /// The edges walked, each directed along the segment (from `pa` towards `pb`).
    pub edges: Vec<(u32, u32)>,
    /// The vertex with no next step, when the chain does not reach the far endpoint.
    pub stuck_at: Option<u32>,
}

/// Walks from vertex `va` (at `pa`) to vertex `vb` (at `pb`) through mesh edges whose far
/// vertex lies on the segment's line and strictly nearer `pb`, taking the such neighbour
/// closest to the line each step (then the nearest along it). On a segment a few millionths
/// long at coordinates in the millions, the tolerance below is as wide as the segment is
/// long, and a mesh vertex beside the segment can count as on it; a split point, rounded
/// onto the line, is much closer to it (domain fuzz seed 20261123, case 4327).
///
/// A vertex counts as on the line when its exact orientation against the segment is zero, or
/// within 2^-40 of the segment's coordinate scale of the line: meshers split segments at
/// constructed points (midpoints, projections) that f64 can only round onto the line; this is
/// rounding, never a visible kink. Progress is measured along the segment's dominant axis,
/// which is exact for collinear points. The test runs on the points scaled by the power of two
/// that brings the segment's largest coordinate into [1, 2) (exact; every quantity scales
/// alike, so the decision is the unscaled one), so that neither the length nor the orientation
/// under- or overflows.
pub(crate) fn segment_chain(
    mesh: &TriMesh,
    adjacency: &Adjacency,
    [pa, pb]: [Point; 2],
    [va, vb]: [u32; 2],
) -> Chain {
    let (axis, sign) = if (pb[0] - pa[0]).abs() >= (pb[1] - pa[1]).abs() {
        (0, (pb[0] - pa[0]).signum())
    } else {
        (1, (pb[1] - pa[1]).signum())
    };
    let progress = |v: u32| sign * mesh.vertices[v as usize][axis];
    let k = scale_exponent(&[pa[0], pa[1], pb[0], pb[1]]);
    let (sa, sb) = (scale_point(pa, -k), scale_point(pb, -k));
    let length = dist(sa, sb);
    let scale = [sa[0], sa[1], sb[0], sb[1]]
        .iter()
        .fold(length, |m, c| m.max(c.abs()));
    let tolerance = scale * (-40f64).exp2();
    // The distance of a vertex from the line, when it counts as on it.
    let off_line = |pw: Point| {
        let o = orient2d_scaled(sa, sb, scale_point(pw, -k)).abs() / length;
        (o == 0.0 || o <= tolerance).then_some(o)
    };
    let end = progress(vb);
    let mut edges = Vec::new();
    let mut u = va;
    while u != vb {
        let here = progress(u);
        let step = adjacency
            .neighbours(u)
            .filter(|&w| progress(w) > here && progress(w) <= end)
            .filter_map(|w| Some((off_line(mesh.vertices[w as usize])?, w)))
            .min_by(|&(ox, x), &(oy, y)| {
                ox.total_cmp(&oy)
                    .then(progress(x).total_cmp(&progress(y)))
                    .then(x.cmp(&y))
            })
            .map(|(_, w)| w);
        match step {
            Some(w) => {
                edges.push((u, w));
                u = w;
            }
            None => {
                return Chain {
                    edges,
                    stuck_at: Some(u),
                }
            }
        }
    }
    Chain {
        edges,
        stuck_at: None,
    }
}

/// One input segment's edges in the mesh, as [`walk_segments`] finds them.
pub(crate) struct WalkedSegment {
    /// The segment's index in the input.
    pub segment: usize,
    /// The mesh vertices of its two endpoints.
    pub ends: [u32; 2],
    /// The edges walked along it, each directed along the walk that found it.
    pub edges: Vec<(u32, u32)>,
}

/// The edges along every input segment whose two endpoints are mesh vertices (`vertex_of`,
/// from [`input_vertices`]): the chain from the first endpoint and, where it breaks off short
/// of the second, also what can be walked back from the second, so that a broken chain still
/// gives all the edges that lie on it.
pub(crate) fn walk_segments(
    mesh: &TriMesh,
    input: &Pslg,
    adjacency: &Adjacency,
    vertex_of: &[Option<u32>],
) -> Vec<WalkedSegment> {
    let mut out = Vec::with_capacity(input.segments.len());
    for (s, seg) in input.segments.iter().enumerate() {
        let (ia, ib) = (seg[0] as usize, seg[1] as usize);
        let (Some(&pa), Some(&pb)) = (input.points.get(ia), input.points.get(ib)) else {
            continue;
        };
        let (Some(Some(va)), Some(Some(vb))) = (vertex_of.get(ia), vertex_of.get(ib)) else {
            continue;
        };
        let (va, vb) = (*va, *vb);
        let mut edges = segment_chain(mesh, adjacency, [pa, pb], [va, vb]).edges;
        if edges.last().is_none_or(|e| e.1 != vb) {
            edges.extend(segment_chain(mesh, adjacency, [pb, pa], [vb, va]).edges);
        }
        out.push(WalkedSegment {
            segment: s,
            ends: [va, vb],
            edges,
        });
    }
    out
}

/// The mesh edges (smaller vertex first) that lie on input segments, as [`walk_segments`]
/// finds them in a mesh of topology `topo`.
pub(crate) fn segment_edges(
    mesh: &TriMesh,
    input: &Pslg,
    topo: &super::Topology,
) -> std::collections::HashSet<(u32, u32)> {
    let adjacency = Adjacency::new(mesh, &topo.usable);
    let vertex_of = input_vertices(mesh, input);
    walk_segments(mesh, input, &adjacency, &vertex_of)
        .into_iter()
        .flat_map(|w| w.edges)
        .map(|(u, w)| (u.min(w), u.max(w)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Domain fuzz seed 20261123, case 4327: a segment 1.4e-5 long at coordinates in the
    /// millions, split at m; a vertex f beside it, 2e-6 off the line (within the tolerance)
    /// and before m along it, is a neighbour of the first endpoint too. The walk goes through
    /// m, the vertex on the line.
    #[test]
    fn the_walk_takes_the_split_point_not_a_vertex_beside_a_tiny_segment() {
        let pa: Point = [421257.6130264518, 5654694.737125214];
        let pb: Point = [421257.6130392821, 5654694.737129657];
        let along = |t: f64, off: f64| {
            let (dx, dy) = (pb[0] - pa[0], pb[1] - pa[1]);
            let l = dx.hypot(dy);
            [pa[0] + t * dx - off * dy / l, pa[1] + t * dy + off * dx / l]
        };
        let (m, f, q) = (along(0.33, 0.0), along(0.1, 2e-6), along(0.5, -5e-6));
        // 0 = pa, 1 = m, 2 = pb, 3 = f (left of the line), 4 = q (right of it).
        let mesh = TriMesh {
            vertices: vec![pa, m, pb, f, q],
            triangles: vec![[0, 1, 3], [1, 2, 3], [0, 4, 1], [1, 4, 2]],
        };
        let adjacency = Adjacency::new(&mesh, &[true; 4]);
        let chain = segment_chain(&mesh, &adjacency, [pa, pb], [0, 2]);
        assert_eq!(chain.stuck_at, None);
        assert_eq!(chain.edges, vec![(0, 1), (1, 2)]);
    }
}
