//! The broken invariants `validate` reports: one variant each, with a message that names the
//! indices and coordinates involved, and a short kind name for tables and tests.

use std::fmt;

use crate::geom::Point;
use crate::quality::show;

/// One broken invariant. Indices are 0-based; `points` are the coordinates of the named
/// vertices, so a message can be checked without opening the mesh.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(tag = "kind", rename_all = "snake_case"))]
pub enum Violation {
    /// The mesh has no triangles: it meshes nothing, so no bound may pass on it vacuously.
    NoTriangles {
        /// How many vertices the mesh has.
        vertices: usize,
    },
    /// A triangle names a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle naming the vertex.
        triangle: usize,
        /// Which of its three corners (0, 1 or 2) names it.
        corner: usize,
        /// The vertex index it names.
        vertex: u32,
        /// How many vertices the mesh has.
        vertices: usize,
    },
    /// A vertex has a NaN or infinite coordinate.
    NonFiniteVertex {
        /// The vertex.
        vertex: usize,
        /// Its coordinates.
        point: Point,
    },
    /// A triangle is clockwise (negative exact orientation).
    Clockwise {
        /// The triangle.
        triangle: usize,
        /// Its vertices, in its order.
        corners: [u32; 3],
        /// Their coordinates.
        points: [Point; 3],
    },
    /// A triangle has zero area: collinear corners, or a corner named twice.
    ZeroArea {
        /// The triangle.
        triangle: usize,
        /// Its vertices, in its order.
        corners: [u32; 3],
        /// Their coordinates.
        points: [Point; 3],
    },
    /// An undirected edge belongs to more than two triangles.
    EdgeOverused {
        /// The edge's vertices, lower index first.
        edge: [u32; 2],
        /// Their coordinates.
        points: [Point; 2],
        /// Every triangle using the edge, in index order.
        triangles: Vec<usize>,
    },
    /// Two triangles traverse their shared edge in the same direction (one is flipped).
    EdgeSameDirection {
        /// The edge, in the direction both triangles traverse it.
        edge: [u32; 2],
        /// Its endpoints' coordinates.
        points: [Point; 2],
        /// The two triangles.
        triangles: [usize; 2],
    },
    /// Two vertices have bit-equal coordinates (-0.0 and 0.0 count as equal).
    DuplicateVertex {
        /// The vertex of lowest index at these coordinates.
        first: usize,
        /// A later vertex at the same coordinates.
        second: usize,
        /// The shared coordinates (of `first`).
        point: Point,
    },
    /// A vertex belongs to no triangle.
    UnreferencedVertex {
        /// The vertex.
        vertex: usize,
        /// Its coordinates.
        point: Point,
    },
    /// The boundary edges at a vertex do not pair up into closed loops.
    OpenBoundary {
        /// The vertex.
        vertex: usize,
        /// Its coordinates.
        point: Point,
        /// How many boundary edges end at it.
        incoming: usize,
        /// How many boundary edges start at it.
        outgoing: usize,
    },
    /// Two boundary edges cross or overlap.
    BoundaryCrossing {
        /// One boundary edge, as its triangle traverses it.
        first: [u32; 2],
        /// The other boundary edge, as its triangle traverses it.
        second: [u32; 2],
        /// The coordinates of `first`'s endpoints.
        first_points: [Point; 2],
        /// The coordinates of `second`'s endpoints.
        second_points: [Point; 2],
    },
    /// The triangles around an interior vertex wind `winding` times around it instead of once
    /// (their angles do not sum to 360°).
    Fold {
        /// The interior vertex.
        vertex: usize,
        /// Its coordinates.
        point: Point,
        /// How many times its triangles wind around it.
        winding: i64,
    },
    /// Just inside boundary edge `edge` the mesh covers the plane `covering` times, not once:
    /// two parts of the mesh overlap.
    Overlap {
        /// The boundary edge, as its triangle traverses it (the mesh on its left).
        edge: [u32; 2],
        /// Its endpoints' coordinates.
        points: [Point; 2],
        /// How many times the mesh covers the plane just left of the edge's midpoint.
        covering: i64,
    },
    /// The triangle areas do not sum to the area the boundary loops enclose.
    AreaMismatch {
        /// The sum of the signed triangle areas.
        triangles: f64,
        /// The signed area the boundary loops enclose.
        enclosed: f64,
    },
    /// A mesh that must be one disc has several boundary loops (a hole, or pieces), or its
    /// boundary touches itself at a vertex (a hole reaching the boundary at a corner).
    HoleInMesh {
        /// How many boundary loops the mesh has.
        loops: usize,
        /// The first vertex of each loop.
        first_vertices: Vec<u32>,
        /// The vertices where the boundary touches itself (several boundary edges leave them).
        pinched_at: Vec<u32>,
    },
    /// An input point is not a mesh vertex (bit-exact comparison).
    MissingInputPoint {
        /// The input point's index.
        input: usize,
        /// Its coordinates.
        point: Point,
    },
    /// A hole seed of the input lies in triangle `triangle`: the hole is meshed.
    HoleCovered {
        /// The hole seed's index among the input's holes.
        hole: usize,
        /// Its coordinates.
        point: Point,
        /// The first triangle (by index) containing it.
        triangle: usize,
    },
    /// A boundary edge of the mesh lies on no input segment: the mesh of a PSLG ends where
    /// the input has no boundary (it spills beyond the segments, or leaves a gap inside).
    BoundaryOffSegments {
        /// The boundary edge, as its triangle traverses it.
        edge: [u32; 2],
        /// Its endpoints' coordinates.
        points: [Point; 2],
    },
    /// An input segment is not a chain of mesh edges along it: every vertex of the chain must
    /// lie on the segment's line within 2^-40 of the segment's coordinate scale (the rounding
    /// of constructed points such as midpoints and crossings, never a visible kink).
    SegmentNotConforming {
        /// The segment's index in the input.
        segment: usize,
        /// Its endpoints, as input point indices.
        endpoints: [u32; 2],
        /// The endpoints' coordinates.
        points: [Point; 2],
        /// The mesh vertex where the chain from the first endpoint breaks off, with its
        /// coordinates; `None` when an endpoint is not a mesh vertex.
        stuck_at: Option<(u32, Point)>,
    },
}

/// A point as `(x, y)`, each coordinate naming its f64 exactly.
fn pt(p: Point) -> String {
    format!("({}, {})", show(p[0]), show(p[1]))
}

/// A triangle's three corners as points.
fn tri(points: &[Point; 3]) -> String {
    format!("{} {} {}", pt(points[0]), pt(points[1]), pt(points[2]))
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Violation::NoTriangles { vertices } => {
                write!(f, "the mesh has no triangles ({vertices} vertices)")
            }
            Violation::IndexOutOfRange {
                triangle,
                corner,
                vertex,
                vertices,
            } => write!(
                f,
                "triangle {triangle} corner {corner} names vertex {vertex}, but there are only {vertices} vertices"
            ),
            Violation::NonFiniteVertex { vertex, point } => {
                write!(f, "vertex {vertex} has a non-finite coordinate {}", pt(*point))
            }
            Violation::Clockwise {
                triangle,
                corners,
                points,
            } => write!(
                f,
                "triangle {triangle} {corners:?} is clockwise: {}",
                tri(points)
            ),
            Violation::ZeroArea {
                triangle,
                corners,
                points,
            } => write!(
                f,
                "triangle {triangle} {corners:?} has zero area: {}",
                tri(points)
            ),
            Violation::EdgeOverused {
                edge,
                points,
                triangles,
            } => write!(
                f,
                "edge {edge:?} {}-{} is used by {} triangles {triangles:?}; at most two may share an edge",
                pt(points[0]),
                pt(points[1]),
                triangles.len()
            ),
            Violation::EdgeSameDirection {
                edge,
                points,
                triangles,
            } => write!(
                f,
                "triangles {} and {} traverse edge {edge:?} {}-{} in the same direction (one of them is flipped)",
                triangles[0],
                triangles[1],
                pt(points[0]),
                pt(points[1])
            ),
            Violation::DuplicateVertex {
                first,
                second,
                point,
            } => write!(
                f,
                "vertices {first} and {second} are duplicates, both at {}",
                pt(*point)
            ),
            Violation::UnreferencedVertex { vertex, point } => {
                write!(f, "vertex {vertex} at {} belongs to no triangle", pt(*point))
            }
            Violation::OpenBoundary {
                vertex,
                point,
                incoming,
                outgoing,
            } => write!(
                f,
                "the boundary is not closed at vertex {vertex} {}: {incoming} boundary edges come in, {outgoing} go out",
                pt(*point)
            ),
            Violation::BoundaryCrossing {
                first,
                second,
                first_points,
                second_points,
            } => write!(
                f,
                "boundary edges {first:?} {}-{} and {second:?} {}-{} cross",
                pt(first_points[0]),
                pt(first_points[1]),
                pt(second_points[0]),
                pt(second_points[1])
            ),
            Violation::Fold {
                vertex,
                point,
                winding,
            } => write!(
                f,
                "fold at interior vertex {vertex} {}: its triangles wind {winding} times around it (angle sum {}°, not 360°)",
                pt(*point),
                360 * winding
            ),
            Violation::Overlap {
                edge,
                points,
                covering,
            } => write!(
                f,
                "overlap: just inside boundary edge {edge:?} {}-{} the mesh covers the plane {covering} times, not once",
                pt(points[0]),
                pt(points[1])
            ),
            Violation::AreaMismatch {
                triangles,
                enclosed,
            } => write!(
                f,
                "the triangles cover an area of {}, but the boundary loops enclose {}",
                show(*triangles),
                show(*enclosed)
            ),
            Violation::HoleInMesh {
                loops,
                first_vertices,
                pinched_at,
            } => {
                write!(
                    f,
                    "hole in the mesh: {loops} boundary loops (starting at vertices {first_vertices:?})"
                )?;
                if !pinched_at.is_empty() {
                    write!(f, ", touching at vertices {pinched_at:?},")?;
                }
                write!(f, " where the mesh of a point set must be one disc")
            }
            Violation::MissingInputPoint { input, point } => {
                write!(f, "input point {input} {} is not a mesh vertex", pt(*point))
            }
            Violation::HoleCovered {
                hole,
                point,
                triangle,
            } => write!(
                f,
                "hole seed {hole} {} lies in triangle {triangle}: the hole is meshed",
                pt(*point)
            ),
            Violation::BoundaryOffSegments { edge, points } => write!(
                f,
                "boundary edge {edge:?} {}-{} lies on no input segment: the mesh does not end at the segments",
                pt(points[0]),
                pt(points[1])
            ),
            Violation::SegmentNotConforming {
                segment,
                endpoints,
                points,
                stuck_at,
            } => {
                write!(
                    f,
                    "input segment {segment} {endpoints:?} {}-{} is not a chain of mesh edges",
                    pt(points[0]),
                    pt(points[1])
                )?;
                match stuck_at {
                    Some((v, p)) => write!(f, ": the chain breaks off at vertex {v} {}", pt(*p)),
                    None => write!(f, ": an endpoint is not a mesh vertex"),
                }
            }
        }
    }
}

impl Violation {
    /// A short snake_case name of the kind of violation, for tables and tests.
    pub fn kind(&self) -> &'static str {
        match self {
            Violation::NoTriangles { .. } => "no_triangles",
            Violation::IndexOutOfRange { .. } => "index_out_of_range",
            Violation::NonFiniteVertex { .. } => "non_finite_vertex",
            Violation::Clockwise { .. } => "clockwise",
            Violation::ZeroArea { .. } => "zero_area",
            Violation::EdgeOverused { .. } => "edge_overused",
            Violation::EdgeSameDirection { .. } => "edge_same_direction",
            Violation::DuplicateVertex { .. } => "duplicate_vertex",
            Violation::UnreferencedVertex { .. } => "unreferenced_vertex",
            Violation::OpenBoundary { .. } => "open_boundary",
            Violation::BoundaryCrossing { .. } => "boundary_crossing",
            Violation::Fold { .. } => "fold",
            Violation::Overlap { .. } => "overlap",
            Violation::AreaMismatch { .. } => "area_mismatch",
            Violation::HoleInMesh { .. } => "hole_in_mesh",
            Violation::MissingInputPoint { .. } => "missing_input_point",
            Violation::HoleCovered { .. } => "hole_covered",
            Violation::BoundaryOffSegments { .. } => "boundary_off_segments",
            Violation::SegmentNotConforming { .. } => "segment_not_conforming",
        }
    }

    /// The mesh vertices and mesh triangles (0-based) the message names, in the order it
    /// names them, so that a caller can give them the numbers a file uses for them (a Gmsh
    /// file's node and element tags). Input points, segments and holes are not included.
    pub fn named(&self) -> (Vec<usize>, Vec<usize>) {
        let v = |i: &u32| *i as usize;
        match self {
            Violation::NoTriangles { .. }
            | Violation::AreaMismatch { .. }
            | Violation::MissingInputPoint { .. } => (vec![], vec![]),
            Violation::IndexOutOfRange { triangle, .. } => (vec![], vec![*triangle]),
            Violation::NonFiniteVertex { vertex, .. }
            | Violation::UnreferencedVertex { vertex, .. }
            | Violation::OpenBoundary { vertex, .. }
            | Violation::Fold { vertex, .. } => (vec![*vertex], vec![]),
            Violation::Clockwise {
                triangle, corners, ..
            }
            | Violation::ZeroArea {
                triangle, corners, ..
            } => (corners.iter().map(v).collect(), vec![*triangle]),
            Violation::EdgeOverused {
                edge, triangles, ..
            } => (edge.iter().map(v).collect(), triangles.clone()),
            Violation::EdgeSameDirection {
                edge, triangles, ..
            } => (edge.iter().map(v).collect(), triangles.to_vec()),
            Violation::DuplicateVertex { first, second, .. } => (vec![*first, *second], vec![]),
            Violation::BoundaryCrossing { first, second, .. } => {
                (first.iter().chain(second).map(v).collect(), vec![])
            }
            Violation::Overlap { edge, .. } | Violation::BoundaryOffSegments { edge, .. } => {
                (edge.iter().map(v).collect(), vec![])
            }
            Violation::HoleInMesh {
                first_vertices,
                pinched_at,
                ..
            } => (
                first_vertices.iter().chain(pinched_at).map(v).collect(),
                vec![],
            ),
            Violation::HoleCovered { triangle, .. } => (vec![], vec![*triangle]),
            // Its endpoints are input points; where the chain breaks off is a mesh vertex.
            Violation::SegmentNotConforming { stuck_at, .. } => {
                (stuck_at.iter().map(|(s, _)| v(s)).collect(), vec![])
            }
        }
    }
}
