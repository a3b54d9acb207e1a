//! Structural validity of a triangle mesh: every violation of the invariants a mesh must
//! satisfy before any quality figure means anything. A valid mesh has every triangle
//! counter-clockwise with positive area, every edge used by one or two triangles in opposite
//! directions, no duplicate vertices, triangle areas that sum to the area inside the boundary
//! loops, every input point as a vertex (bit-exact) and, where the mesher promises conformity,
//! every input segment as a chain of mesh edges.
//!
//! Each invariant is decided with exact orientation signs (Shewchuk's predicates through
//! `geom::orient2d_scaled`, which scales the points by a power of two where `robust` would
//! under- or overflow, so the signs stay exact at any coordinate magnitude). Lengths and areas
//! are compared on coordinates scaled by powers of two for the same reason.
//!
//! Overlap is decided without area sums: with counter-clockwise triangles and paired interior
//! edges, the number of triangles covering a point equals the winding number of the boundary
//! edges around it (Stokes), so the mesh is one sheet exactly when that winding is 1 just
//! inside every boundary edge and the boundary edges do not cross.
//!
//! One check a file, run in this order by [`validate()`]:
//! - `violation`: the [`Violation`] enum, its messages and kind names;
//! - `topology`: the edges of the triangles grouped into boundary, interior, overused and
//!   same-direction edges;
//! - `vertices`: point hash keys and duplicate vertices;
//! - `boundary`: boundary loops, open boundaries and the one-disc check;
//! - `crossings`: boundary edges that cross or overlap;
//! - `winding`: overlaps just inside the boundary and folds around interior vertices;
//! - `area`: triangle areas against the area the boundary loops enclose;
//! - `chains`: the vertex of each input point and the chain of edges along each segment;
//! - `input`: input points as vertices, segments as chains of edges, the boundary on them;
//! - `holes`: hole seeds that a triangle covers;
//! - `regions`: the region of the input each triangle lies in (regional attributes and area
//!   limits), across the same chains.

mod area;
mod boundary;
pub(crate) mod chains;
mod crossings;
mod holes;
mod input;
mod regions;
mod topology;
pub(super) mod vertices;
mod violation;
mod winding;

pub(crate) use boundary::boundary_loops;
pub(crate) use regions::regions_across;
pub use regions::triangle_regions;
pub(crate) use topology::{topology, DirectedEdge, Topology};
pub use violation::{Numbering, Violation};

use crate::geom::orient2d_scaled;
use crate::mesh::{Pslg, TriMesh};

use area::area_balance;
use boundary::one_disc;
use crossings::boundary_crossings;
use holes::holes_covered;
use input::input_conformity;
use vertices::duplicate_vertices;
use winding::{folds, overlaps};

/// What `validate` checks beyond the invariants every mesh must meet.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct ValidateOptions {
    /// The mesh must be one disc: more than one boundary loop is a violation. True for meshes
    /// of point sets, whose domain is the bounding hexagon.
    pub single_component: bool,
    /// Every input segment must be a chain of collinear mesh edges.
    pub conforming: bool,
}

/// Checks every invariant and returns every violation found, in a fixed order: vertex
/// coordinates, triangles, edges, duplicates, unreferenced vertices, boundary, input; by
/// index within each. An empty result means the mesh is valid.
pub fn validate(mesh: &TriMesh, input: Option<&Pslg>, opts: &ValidateOptions) -> Vec<Violation> {
    validate_with(mesh, input, opts, &topology(mesh))
}

/// [`validate`] with the mesh's edge structure built already (`topology`), as the verdict
/// shares it with the figures (`metrics_with`).
pub(crate) fn validate_with(
    mesh: &TriMesh,
    input: Option<&Pslg>,
    opts: &ValidateOptions,
    topo: &Topology,
) -> Vec<Violation> {
    let mut out = Vec::new();
    let verts = &mesh.vertices;
    let n = verts.len();
    if mesh.triangles.is_empty() {
        out.push(Violation::NoTriangles { vertices: n });
    }
    let finite: Vec<bool> = verts
        .iter()
        .map(|p| p[0].is_finite() && p[1].is_finite())
        .collect();
    for (vertex, &p) in verts.iter().enumerate() {
        if !finite[vertex] {
            out.push(Violation::NonFiniteVertex { vertex, point: p });
        }
    }

    // Triangles whose geometry can be trusted: usable and with finite corners.
    let mut geometric = topo.usable.clone();
    let mut referenced = vec![false; n];
    for (t, corners) in mesh.triangles.iter().enumerate() {
        let mut in_range = true;
        for (corner, &v) in corners.iter().enumerate() {
            if (v as usize) < n {
                referenced[v as usize] = true;
            } else {
                in_range = false;
                out.push(Violation::IndexOutOfRange {
                    triangle: t,
                    corner,
                    vertex: v,
                    vertices: n,
                });
            }
        }
        if !in_range || corners.iter().any(|&v| !finite[v as usize]) {
            geometric[t] = false;
            continue;
        }
        let points = mesh.corners(t);
        let o = orient2d_scaled(points[0], points[1], points[2]);
        if o < 0.0 {
            out.push(Violation::Clockwise {
                triangle: t,
                corners: *corners,
                points,
            });
        } else if o == 0.0 {
            out.push(Violation::ZeroArea {
                triangle: t,
                corners: *corners,
                points,
            });
        }
    }

    let p = |v: u32| verts[v as usize];
    for (lo, hi, triangles) in &topo.overused {
        out.push(Violation::EdgeOverused {
            edge: [*lo, *hi],
            points: [p(*lo), p(*hi)],
            triangles: triangles.clone(),
        });
    }
    for &(u, v, t1, t2) in &topo.same_direction {
        out.push(Violation::EdgeSameDirection {
            edge: [u, v],
            points: [p(u), p(v)],
            triangles: [t1, t2],
        });
    }

    duplicate_vertices(verts, &mut out);
    for (vertex, &r) in referenced.iter().enumerate() {
        if !r {
            out.push(Violation::UnreferencedVertex {
                vertex,
                point: verts[vertex],
            });
        }
    }

    // Boundary edges with trustworthy geometry drive the loop, crossing and overlap checks.
    let boundary: Vec<DirectedEdge> = topo
        .boundary
        .iter()
        .copied()
        .filter(|e| geometric[e.triangle])
        .collect();
    let loops = boundary_loops(mesh, topo, &boundary, &mut out);
    boundary_crossings(verts, &boundary, &mut out);
    overlaps(verts, &boundary, &loops, &mut out);
    folds(mesh, topo, &geometric, &mut out);
    area_balance(mesh, &geometric, &boundary, &mut out);
    if opts.single_component {
        one_disc(&boundary, &loops, &mut out);
    }

    if let Some(input) = input {
        input_conformity(mesh, topo, &boundary, input, opts.conforming, &mut out);
        holes_covered(mesh, &geometric, input, &mut out);
    }
    out
}
