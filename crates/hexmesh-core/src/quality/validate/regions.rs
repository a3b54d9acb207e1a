//! The region of every triangle, as Triangle assigns regional attributes and area limits
//! (Triangle 1.6 documentation, ".poly files"): the triangles reachable from a region's point
//! without crossing an input segment belong to it, and a later region of the input overrides
//! an earlier one. The segments are the chains of edges the conformity check walks
//! (`chains`), so a region ends exactly where `verify` sees the segment.

use std::collections::HashSet;

use super::chains::{input_vertices, segment_chain, Adjacency};
use super::topology;
use crate::geom::orient2d_scaled;
use crate::mesh::{Pslg, TriMesh};

/// The index (in `input.labels.regions`) of the region each triangle lies in; `None` for a
/// triangle no region reaches, or one with a corner that names no vertex.
pub fn triangle_regions(mesh: &TriMesh, input: &Pslg) -> Vec<Option<usize>> {
    let m = mesh.triangles.len();
    if input.labels.regions.is_empty() {
        return vec![None; m];
    }
    let topo = topology(mesh);
    let key = |a: u32, b: u32| (a.min(b), a.max(b));

    // The edges along the segments.
    let mut on_segment: HashSet<(u32, u32)> = HashSet::new();
    let vertex_of = input_vertices(mesh, input);
    let adjacency = Adjacency::new(mesh, &topo.usable);
    for seg in &input.segments {
        let (ia, ib) = (seg[0] as usize, seg[1] as usize);
        let (Some(&pa), Some(&pb)) = (input.points.get(ia), input.points.get(ib)) else {
            continue;
        };
        let (Some(va), Some(vb)) = (vertex_of[ia], vertex_of[ib]) else {
            continue;
        };
        let mut walked = segment_chain(mesh, &adjacency, [pa, pb], [va, vb]).edges;
        if walked.last().is_none_or(|e| e.1 != vb) {
            walked.extend(segment_chain(mesh, &adjacency, [pb, pa], [vb, va]).edges);
        }
        on_segment.extend(walked.into_iter().map(|(u, w)| key(u, w)));
    }

    // Triangles joined across interior edges on no segment (union-find, smaller root wins).
    let mut parent: Vec<usize> = (0..m).collect();
    fn root(parent: &mut [usize], mut t: usize) -> usize {
        while parent[t] != t {
            parent[t] = parent[parent[t]];
            t = parent[t];
        }
        t
    }
    for &(u, v, s, t) in &topo.interior {
        if on_segment.contains(&key(u, v)) {
            continue;
        }
        let (a, b) = (root(&mut parent, s), root(&mut parent, t));
        parent[a.max(b)] = a.min(b);
    }

    // Each region's point located in a triangle (on an edge: the first triangle in order).
    let p = |v: u32| mesh.vertices[v as usize];
    let mut region_of_root: Vec<Option<usize>> = vec![None; m];
    for (k, region) in input.labels.regions.iter().enumerate() {
        let q = region.point;
        let found = mesh.triangles.iter().enumerate().find(|(t, tri)| {
            topo.usable[*t]
                && (0..3).all(|i| orient2d_scaled(p(tri[i]), p(tri[(i + 1) % 3]), q) >= 0.0)
        });
        if let Some((t, _)) = found {
            let r = root(&mut parent, t);
            region_of_root[r] = Some(k);
        }
    }
    (0..m)
        .map(|t| {
            if !topo.usable[t] {
                return None;
            }
            let r = root(&mut parent, t);
            region_of_root[r]
        })
        .collect()
}
