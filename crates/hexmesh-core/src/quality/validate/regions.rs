//! The region of every triangle, as Triangle assigns regional attributes and area limits
//! (Triangle 1.6 documentation, ".poly files"): the triangles reachable from a region's point
//! without crossing an input segment belong to it, and a later region of the input overrides
//! an earlier one. The segments are the chains of edges the conformity check walks
//! (`chains`), so a region ends exactly where `verify` sees the segment.

use super::chains::segment_edges;
use super::{topology, Topology};
use crate::geom::orient2d_scaled;
use crate::mesh::{Pslg, TriMesh};

/// The index (in `input.labels.regions`) of the region each triangle lies in; `None` for a
/// triangle no region reaches, or one with a corner that names no vertex.
pub fn triangle_regions(mesh: &TriMesh, input: &Pslg) -> Vec<Option<usize>> {
    if input.labels.regions.is_empty() {
        return vec![None; mesh.triangles.len()];
    }
    let topo = topology(mesh);
    let on_segment = segment_edges(mesh, input, &topo);
    regions_across(mesh, input, &topo, |u, v| {
        on_segment.contains(&(u.min(v), u.max(v)))
    })
}

/// [`triangle_regions`] for a caller that has the mesh's topology and knows which edges lie
/// on segments (`on_segment(u, v)`, either direction), as `io::boundary` does.
pub(crate) fn regions_across(
    mesh: &TriMesh,
    input: &Pslg,
    topo: &Topology,
    on_segment: impl Fn(u32, u32) -> bool,
) -> Vec<Option<usize>> {
    let m = mesh.triangles.len();
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
        if on_segment(u, v) {
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
