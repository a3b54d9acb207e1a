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

/// How the numbers in a message count: the number of the first vertex and triangle of the
/// mesh, and of the first point, segment and hole of the input, as the files the user reads
/// number them. The library's own indices (in [`Violation`], [`crate::TriMesh`],
/// [`crate::Pslg`]) count from 0, and so does [`Numbering::default`]; the command line
/// numbers as the files it read, and from 1 ([`Numbering::FILES`]) for the files it writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Numbering {
    /// The number of the mesh's first vertex and first triangle (a `.node`/`.ele` file's
    /// first index).
    pub mesh: u32,
    /// The number of the input's first point, segment and hole.
    pub input: u32,
}

impl Numbering {
    /// Numbers from 1, as every file hexmesh writes (Triangle's default).
    pub const FILES: Numbering = Numbering { mesh: 1, input: 1 };

    /// A vertex or triangle index `i` of the mesh as the user's files number it.
    pub fn mesh_index(self, i: impl Into<u64>) -> u64 {
        i.into() + u64::from(self.mesh)
    }

    /// Input index `i` as the user's files number it.
    pub fn input_index(self, i: impl Into<u64>) -> u64 {
        i.into() + u64::from(self.input)
    }

    /// Mesh indices as `[a, b, ...]` in the user's numbering.
    pub fn mesh_list<T: Copy + Into<u64>>(self, list: &[T]) -> String {
        let items: Vec<String> = list
            .iter()
            .map(|&i| self.mesh_index(i).to_string())
            .collect();
        format!("[{}]", items.join(", "))
    }
}

/// A `usize` index as a `u64` (indices fit: they count items in memory).
fn n(i: usize) -> u64 {
    i as u64
}

impl fmt::Display for Violation {
    /// The message with the library's 0-based indices; see [`Violation::describe`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.describe(Numbering::default()))
    }
}

impl Violation {
    /// The message, with vertices, triangles, input points, segments and holes numbered as
    /// `numbering` says.
    pub fn describe(&self, numbering: Numbering) -> String {
        let m = |i: usize| numbering.mesh_index(n(i));
        let v = |i: u32| numbering.mesh_index(i);
        let list = |l: &[u32]| numbering.mesh_list(l);
        let triangles = |l: &[usize]| {
            let l: Vec<u64> = l.iter().map(|&t| n(t)).collect();
            numbering.mesh_list(&l)
        };
        let input = |i: usize| numbering.input_index(n(i));
        match self {
            Violation::NoTriangles { vertices } => {
                format!("the mesh has no triangles ({vertices} vertices)")
            }
            Violation::IndexOutOfRange {
                triangle,
                corner,
                vertex,
                vertices,
            } => format!(
                "triangle {} corner {} of 3 names vertex {}, but there are only {vertices} vertices",
                m(*triangle),
                corner + 1,
                v(*vertex)
            ),
            Violation::NonFiniteVertex { vertex, point } => {
                format!("vertex {} has a non-finite coordinate {}", m(*vertex), pt(*point))
            }
            Violation::Clockwise {
                triangle,
                corners,
                points,
            } => format!(
                "triangle {} {} is clockwise: {}",
                m(*triangle),
                list(corners),
                tri(points)
            ),
            Violation::ZeroArea {
                triangle,
                corners,
                points,
            } => format!(
                "triangle {} {} has zero area: {}",
                m(*triangle),
                list(corners),
                tri(points)
            ),
            Violation::EdgeOverused {
                edge,
                points,
                triangles: ts,
            } => format!(
                "edge {} {}-{} is used by {} triangles {}; at most two may share an edge",
                list(edge),
                pt(points[0]),
                pt(points[1]),
                ts.len(),
                triangles(ts)
            ),
            Violation::EdgeSameDirection {
                edge,
                points,
                triangles: ts,
            } => format!(
                "triangles {} and {} traverse edge {} {}-{} in the same direction (one of them is flipped)",
                m(ts[0]),
                m(ts[1]),
                list(edge),
                pt(points[0]),
                pt(points[1])
            ),
            Violation::DuplicateVertex {
                first,
                second,
                point,
            } => format!(
                "vertices {} and {} are duplicates, both at {}",
                m(*first),
                m(*second),
                pt(*point)
            ),
            Violation::UnreferencedVertex { vertex, point } => {
                format!("vertex {} at {} belongs to no triangle", m(*vertex), pt(*point))
            }
            Violation::OpenBoundary {
                vertex,
                point,
                incoming,
                outgoing,
            } => format!(
                "the boundary is not closed at vertex {} {}: {incoming} boundary edges come in, {outgoing} go out",
                m(*vertex),
                pt(*point)
            ),
            Violation::BoundaryCrossing {
                first,
                second,
                first_points,
                second_points,
            } => format!(
                "boundary edges {} {}-{} and {} {}-{} cross",
                list(first),
                pt(first_points[0]),
                pt(first_points[1]),
                list(second),
                pt(second_points[0]),
                pt(second_points[1])
            ),
            Violation::Fold {
                vertex,
                point,
                winding,
            } => format!(
                "fold at interior vertex {} {}: its triangles wind {winding} times around it (angle sum {}°, not 360°)",
                m(*vertex),
                pt(*point),
                360 * winding
            ),
            Violation::Overlap {
                edge,
                points,
                covering,
            } => format!(
                "overlap: just inside boundary edge {} {}-{} the mesh covers the plane {covering} times, not once",
                list(edge),
                pt(points[0]),
                pt(points[1])
            ),
            Violation::AreaMismatch {
                triangles,
                enclosed,
            } => format!(
                "the triangles cover an area of {}, but the boundary loops enclose {}",
                show(*triangles),
                show(*enclosed)
            ),
            Violation::HoleInMesh {
                loops,
                first_vertices,
                pinched_at,
            } => {
                let mut s = format!(
                    "hole in the mesh: {loops} boundary loops (starting at vertices {})",
                    list(first_vertices)
                );
                if !pinched_at.is_empty() {
                    s.push_str(&format!(", touching at vertices {},", list(pinched_at)));
                }
                s.push_str(" where the mesh of a point set must be one disc");
                s
            }
            Violation::MissingInputPoint { input: i, point } => {
                format!("input point {} {} is not a mesh vertex", input(*i), pt(*point))
            }
            Violation::HoleCovered {
                hole,
                point,
                triangle,
            } => format!(
                "hole seed {} {} lies in triangle {}: the hole is meshed",
                input(*hole),
                pt(*point),
                m(*triangle)
            ),
            Violation::BoundaryOffSegments { edge, points } => format!(
                "boundary edge {} {}-{} lies on no input segment: the mesh does not end at the segments",
                list(edge),
                pt(points[0]),
                pt(points[1])
            ),
            Violation::SegmentNotConforming {
                segment,
                endpoints,
                points,
                stuck_at,
            } => {
                let ends: Vec<u64> = endpoints.iter().map(|&e| numbering.input_index(e)).collect();
                let mut s = format!(
                    "input segment {} [{}, {}] {}-{} is not a chain of mesh edges",
                    input(*segment),
                    ends[0],
                    ends[1],
                    pt(points[0]),
                    pt(points[1])
                );
                match stuck_at {
                    Some((at, p)) => {
                        s.push_str(&format!(": the chain breaks off at vertex {} {}", v(*at), pt(*p)))
                    }
                    None => s.push_str(": an endpoint is not a mesh vertex"),
                }
                s
            }
        }
    }
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
