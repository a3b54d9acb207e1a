//! Refinement meshers built on a Delaunay triangulation of the input:
//! - [`saalfeld`]: conforming Delaunay triangulation of a PSLG by iterated intersection of the
//!   segments with the Delaunay triangulation of a growing vertex set (Saalfeld, "Delaunay Edge
//!   Refinements", Sec. 6), and the constructive refinement of its Sec. 5 as an option.
//! - [`lsb`]: modified longest-side bisection (Stamm, Eidenbenz, Pajarola, Definition 3.2 and
//!   rule 4.1) with Rivara propagation, driven by a longest-edge heap (their Sec. 4).
//!
//! This file holds what both share: the domain a point set is meshed in, the triangles of a
//! spade triangulation, and the carved constrained Delaunay triangulation they start from
//! (`domain_cdt`, on the triangulation and the removal of triangles outside the domain or in
//! holes that `Pslg::check` decides the domain with: `crate::enclosed`).

pub mod lsb;
pub mod saalfeld;

pub use lsb::{family, family_min_ratio, lsb_descent_check, min_angle, Lsb, LsbRun, Target};
pub use saalfeld::{ConformingRun, Saalfeld};

use std::collections::HashSet;
use std::time::{Duration, Instant};

use spade::handles::FixedVertexHandle;
use spade::{InsertionError, Triangulation};

use crate::enclosed::{triangulate, CdtFailure};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::{Pslg, TriMesh};
use crate::mesher::{Budget, StopReason};

/// The domain a refinement mesher works in: a PSLG as given, a point set inside its bounding
/// hexagon with the hexagon's corners and edges added (`Pslg::reference_domain`), so that
/// these meshers mesh the same region as the reference meshers.
pub(crate) fn domain(input: &Pslg) -> Pslg {
    input.reference_domain()
}

pub(crate) use crate::enclosed::{carve, ekey, to_spade};

pub(crate) fn insertion_error(mesher: &str, e: InsertionError) -> Error {
    Error::mesher(mesher, format!("spade refused a vertex: {e:?}"))
}

/// The counter-clockwise inner triangles of a spade triangulation, as vertex indices
/// (spade's vertex handles count insertions from 0, so the index is the insertion order).
pub(crate) fn spade_triangles<T: Triangulation>(t: &T) -> Vec<[u32; 3]> {
    t.inner_faces()
        .map(|f| {
            let [a, b, c] = f.vertices();
            [idx(a.fix()), idx(b.fix()), idx(c.fix())]
        })
        .collect()
}

pub(crate) fn idx(h: FixedVertexHandle) -> u32 {
    h.index() as u32
}

/// The constrained Delaunay triangulation of the domain (a PSLG, or a point set in its bounding
/// hexagon: `Pslg::reference_domain`) without the triangles outside it or in holes (Triangle's
/// convention, [`carve`]), with the vertices no triangle uses dropped ([`compact`]). Returns the
/// mesh and the domain's segments renumbered to its vertices (those whose two endpoints
/// remain). Errors name `mesher`: a segment spade could not insert, two points that coincide
/// once tiny coordinates are flushed, segments that enclose no region.
pub fn domain_cdt(input: &Pslg, mesher: &str) -> Result<(TriMesh, Vec<[u32; 2]>)> {
    input.validate_input()?;
    let dom = domain(input);
    let triangles = triangulate(&dom.points, &dom.segments).map_err(|e| match e {
        CdtFailure::Insertion(e) => insertion_error(mesher, e),
        CdtFailure::Conflict([a, b]) => Error::mesher(
            mesher,
            format!("segment {a}-{b} conflicts with another segment in the triangulation"),
        ),
        CdtFailure::Coincide => Error::mesher(
            mesher,
            "two input points coincide after flushing tiny coordinates to zero",
        ),
    })?;
    let vertices: Vec<Point> = dom.points.clone();
    let barriers: HashSet<(u32, u32)> = dom.segments.iter().map(|s| ekey(s[0], s[1])).collect();
    let kept = carve(&vertices, &triangles, &barriers, &dom.holes);
    let (vertices, triangles, map) = compact(&vertices, &kept);
    if triangles.is_empty() {
        return Err(Error::mesher(
            mesher,
            "the segments enclose no region to mesh",
        ));
    }
    let segments = dom
        .segments
        .iter()
        .filter_map(|s| Some([map[s[0] as usize]?, map[s[1] as usize]?]))
        .collect();
    Ok((
        TriMesh {
            vertices,
            triangles,
        },
        segments,
    ))
}

/// Drops vertices no triangle uses (those outside the domain), keeping the order of the rest,
/// so that input points keep their indices whenever all of them lie in the domain.
/// Returns the new vertices, the renumbered triangles, and old index -> new index.
pub(crate) fn compact(
    vertices: &[Point],
    triangles: &[[u32; 3]],
) -> (Vec<Point>, Vec<[u32; 3]>, Vec<Option<u32>>) {
    let mut used = vec![false; vertices.len()];
    for t in triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let mut map = vec![None; vertices.len()];
    let mut out = Vec::new();
    for (i, &p) in vertices.iter().enumerate() {
        if used[i] {
            map[i] = Some(out.len() as u32);
            out.push(p);
        }
    }
    let tris = triangles
        .iter()
        .map(|t| t.map(|v| map[v as usize].unwrap_or(u32::MAX)))
        .collect();
    (out, tris, map)
}

/// The three budget limits, checked together; the reason names the limit that ran out.
pub(crate) struct Limits {
    budget: Budget,
    start: Instant,
}

impl Limits {
    pub(crate) fn new(budget: Budget) -> Limits {
        Limits {
            budget,
            start: Instant::now(),
        }
    }

    pub(crate) fn elapsed(&self) -> Duration {
        self.start.elapsed()
    }

    /// `Some(reason)` when `steps` reached its limit, `vertices` (the count a step would
    /// leave) exceeds its limit, or time ran out.
    pub(crate) fn exceeded(&self, steps: u64, vertices: usize) -> Option<StopReason> {
        if let Some(max) = self.budget.max_steps {
            if steps >= max {
                return Some(StopReason::Steps(max));
            }
        }
        if let Some(max) = self.budget.max_vertices {
            if vertices > max {
                return Some(StopReason::Vertices(max));
            }
        }
        if let Some(max) = self.budget.max_time {
            if self.start.elapsed() >= max {
                return Some(StopReason::Time(max));
            }
        }
        None
    }
}
