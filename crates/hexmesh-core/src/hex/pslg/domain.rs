//! The domain the segments bound (ours, following Triangle's .poly semantics; the paper
//! meshes "the interior of the bound region" but gives no rule for finding it): triangles
//! outside the outermost segments and inside holes are removed.

use super::NAME;
use crate::error::Error;
use crate::geom::{orient2d, Point};
use crate::hex::lattice::FxHashMap;
use crate::mesh::Pslg;

/// Which triangles lie in the domain (Triangle's .poly semantics without -c): triangles
/// reached from the mesh's outer boundary, or from a hole seed, without crossing a segment
/// edge are outside. Segments that enclose nothing are refused before meshing
/// (`Pslg::check`), so an outer flood that reaches every triangle is an internal error.
pub(super) fn carve(
    vertices: &[Point],
    triangles: &[[u32; 3]],
    input: &Pslg,
    on_segment_edge: impl Fn(u32, u32) -> bool,
) -> std::result::Result<Vec<bool>, Error> {
    let mut by_edge: FxHashMap<(u32, u32), usize> = FxHashMap::default();
    for (t, tri) in triangles.iter().enumerate() {
        for e in 0..3 {
            by_edge.insert((tri[e], tri[(e + 1) % 3]), t);
        }
    }
    let flood = |seeds: Vec<usize>| {
        let mut reached = vec![false; triangles.len()];
        let mut stack = seeds;
        while let Some(t) = stack.pop() {
            if reached[t] {
                continue;
            }
            reached[t] = true;
            let tri = triangles[t];
            for e in 0..3 {
                let (u, v) = (tri[e], tri[(e + 1) % 3]);
                if on_segment_edge(u, v) {
                    continue;
                }
                if let Some(&o) = by_edge.get(&(v, u)) {
                    stack.push(o);
                }
            }
        }
        reached
    };
    let outer_seeds: Vec<usize> = (0..triangles.len())
        .filter(|&t| {
            let tri = triangles[t];
            (0..3).any(|e| {
                let (u, v) = (tri[e], tri[(e + 1) % 3]);
                !by_edge.contains_key(&(v, u)) && !on_segment_edge(u, v)
            })
        })
        .collect();
    let outside = flood(outer_seeds);
    if outside.iter().all(|&o| o) {
        return Err(Error::mesher(
            NAME,
            "internal error: the segments enclose no triangle of the mesh, although the input \
             check found a region they enclose",
        ));
    }
    let contains = |t: usize, p: Point| {
        let [a, b, c] = triangles[t].map(|v| vertices[v as usize]);
        orient2d(a, b, p) >= 0.0 && orient2d(b, c, p) >= 0.0 && orient2d(c, a, p) >= 0.0
    };
    let hole_seeds: Vec<usize> = input
        .holes
        .iter()
        .filter_map(|&p| (0..triangles.len()).find(|&t| contains(t, p)))
        .collect();
    let holes = flood(hole_seeds);
    let keep: Vec<bool> = (0..triangles.len())
        .map(|t| !outside[t] && !holes[t])
        .collect();
    if !keep.iter().any(|&k| k) {
        return Err(Error::mesher(
            NAME,
            "the holes and the outside of the segments cover the whole domain",
        ));
    }
    Ok(keep)
}
