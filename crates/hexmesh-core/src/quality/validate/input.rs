//! Conformity to the input: every input point is a mesh vertex, every input segment a chain
//! of mesh edges along it, and, where the segments bound a region, the mesh ends at them.

use super::chains::{input_vertices, segment_chain, Adjacency};
use super::{DirectedEdge, Topology, Violation};
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
    let vertex_of = input_vertices(mesh, input);
    for (i, (&p, v)) in input.points.iter().zip(&vertex_of).enumerate() {
        if v.is_none() {
            out.push(Violation::MissingInputPoint { input: i, point: p });
        }
    }
    if !conforming || input.segments.is_empty() {
        return;
    }

    let adjacency = Adjacency::new(mesh, &topo.usable);
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
        let chain = segment_chain(mesh, &adjacency, [pa, pb], [va, vb]);
        on_segments.extend(chain.edges.iter().map(|&(u, w)| (u.min(w), u.max(w))));
        if let Some(u) = chain.stuck_at {
            out.push(not_conforming(Some((u, mesh.vertices[u as usize]))));
            conforms = false;
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
