//! The cavity around the segments triangulated again (ours): a constrained Delaunay
//! triangulation (spade's CDT) of the cavity's boundary, the points inside and the projected
//! centres, with the cavity boundary and the segment pieces as constraints.

use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use super::NAME;
use crate::error::Error;
use crate::geom::Point;
use crate::hex::lattice::{FxHashMap, FxHashSet};
use crate::mesh::Pslg;

/// The cavity's triangles, and (vertex, segment) pairs for vertices a segment piece runs
/// through exactly.
type Filled = (Vec<[u32; 3]>, Vec<(u32, u32)>);

/// The constrained Delaunay triangulation of the cavity: `points` (indices into `vertices`),
/// the cavity `boundary` (directed, cavity on the left) and the segment `chains` as
/// constraints; the triangles reached from the boundary edges' inner side without crossing the
/// boundary.
pub(super) fn fill_cavity(
    vertices: &[Point],
    points: &[u32],
    boundary: &[(u32, u32)],
    chains: &[Vec<u32>],
    input: &Pslg,
) -> std::result::Result<Filled, Error> {
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::new();
    let mut handle: FxHashMap<u32, spade::handles::FixedVertexHandle> = FxHashMap::default();
    let mut back: FxHashMap<usize, u32> = FxHashMap::default();
    for &v in points {
        let p = vertices[v as usize];
        let fh = cdt.insert(Point2::new(p[0], p[1])).map_err(|e| {
            Error::mesher(
                NAME,
                format!("spade refused cavity vertex ({}, {}): {e:?}", p[0], p[1]),
            )
        })?;
        if back.insert(fh.index(), v).is_some() {
            return Err(Error::mesher(
                NAME,
                format!(
                    "internal error: two cavity vertices at ({}, {})",
                    p[0], p[1]
                ),
            ));
        }
        handle.insert(v, fh);
    }
    let get = |v: u32| {
        handle.get(&v).copied().ok_or_else(|| {
            Error::mesher(
                NAME,
                format!("internal error: vertex {v} not in the cavity"),
            )
        })
    };
    for &(u, v) in boundary {
        let added = cdt.try_add_constraint(get(u)?, get(v)?);
        if added.len() != 1 {
            return Err(Error::mesher(
                NAME,
                format!(
                    "internal error: the cavity boundary edge {:?}-{:?} is crossed or touched",
                    vertices[u as usize], vertices[v as usize]
                ),
            ));
        }
    }
    // Vertices a segment piece runs through exactly (spade splits the constraint there).
    let mut extra_on: Vec<(u32, u32)> = Vec::new();
    for (s, chain) in chains.iter().enumerate() {
        for w in chain.windows(2) {
            let added = cdt.try_add_constraint(get(w[0])?, get(w[1])?);
            for &e in &added {
                let edge = cdt.directed_edge(e);
                for v in [edge.from().fix().index(), edge.to().fix().index()] {
                    extra_on.push((back[&v], s as u32));
                }
            }
            if added.is_empty() {
                return Err(Error::mesher(
                    NAME,
                    format!(
                        "segment {s} ({:?}-{:?}) could not be inserted: its piece {:?}-{:?} \
                         meets another segment or the cavity boundary",
                        input.points[input.segments[s][0] as usize],
                        input.points[input.segments[s][1] as usize],
                        vertices[w[0] as usize],
                        vertices[w[1] as usize]
                    ),
                ));
            }
        }
    }
    let mut tris: Vec<[u32; 3]> = Vec::with_capacity(cdt.num_inner_faces());
    for f in cdt.inner_faces() {
        let vs = f.vertices().map(|v| back[&v.fix().index()]);
        tris.push(vs);
    }
    let mut by_edge: FxHashMap<(u32, u32), usize> = FxHashMap::default();
    for (t, tri) in tris.iter().enumerate() {
        for e in 0..3 {
            by_edge.insert((tri[e], tri[(e + 1) % 3]), t);
        }
    }
    let walls: FxHashSet<(u32, u32)> = boundary
        .iter()
        .flat_map(|&(u, v)| [(u, v), (v, u)])
        .collect();
    let mut inside = vec![false; tris.len()];
    let mut stack = Vec::new();
    for &(u, v) in boundary {
        let t = by_edge.get(&(u, v)).copied().ok_or_else(|| {
            Error::mesher(
                NAME,
                format!(
                    "internal error: no cavity triangle inside boundary edge {:?}-{:?}",
                    vertices[u as usize], vertices[v as usize]
                ),
            )
        })?;
        stack.push(t);
    }
    while let Some(t) = stack.pop() {
        if inside[t] {
            continue;
        }
        inside[t] = true;
        let tri = tris[t];
        for e in 0..3 {
            let (u, v) = (tri[e], tri[(e + 1) % 3]);
            if walls.contains(&(u, v)) {
                continue;
            }
            if let Some(&o) = by_edge.get(&(v, u)) {
                stack.push(o);
            }
        }
    }
    let filled = tris
        .into_iter()
        .zip(inside)
        .filter(|(_, i)| *i)
        .map(|(t, _)| t)
        .collect();
    Ok((filled, extra_on))
}
