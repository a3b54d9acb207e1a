//! Structural validity of a triangle mesh (DESIGN.md "Checks", *valid*): every violation of
//! the invariants a mesh must satisfy before any quality figure means anything, each decided
//! with exact orientation signs (Shewchuk's predicates through `geom::orient2d_scaled`,
//! which scales the points by a power of two where `robust` would under- or overflow, so the
//! signs stay exact at any coordinate magnitude). Lengths and areas are compared on
//! coordinates scaled by powers of two for the same reason.
//!
//! Overlap is decided without area sums: with counter-clockwise triangles and paired interior
//! edges, the number of triangles covering a point equals the winding number of the boundary
//! edges around it (Stokes), so the mesh is one sheet exactly when that winding is 1 just
//! inside every boundary edge and the boundary edges do not cross.

use std::collections::HashMap;
use std::fmt;

use crate::geom::{dist, orient2d_scaled, scale2, scale_exponent, scale_point, Dist2, Point};
use crate::mesh::{Pslg, TriMesh};

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

/// One broken invariant. Indices are 0-based; `points` are the coordinates of the named
/// vertices, so a message can be checked without opening the mesh.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(tag = "kind", rename_all = "snake_case"))]
pub enum Violation {
    /// The mesh has no triangles: it meshes nothing, so no bound may pass on it vacuously.
    NoTriangles { vertices: usize },
    /// A triangle names a vertex that does not exist.
    IndexOutOfRange {
        triangle: usize,
        corner: usize,
        vertex: u32,
        vertices: usize,
    },
    /// A vertex has a NaN or infinite coordinate.
    NonFiniteVertex { vertex: usize, point: Point },
    /// A triangle is clockwise (negative exact orientation).
    Clockwise {
        triangle: usize,
        corners: [u32; 3],
        points: [Point; 3],
    },
    /// A triangle has zero area: collinear corners, or a corner named twice.
    ZeroArea {
        triangle: usize,
        corners: [u32; 3],
        points: [Point; 3],
    },
    /// An undirected edge belongs to more than two triangles.
    EdgeOverused {
        edge: [u32; 2],
        points: [Point; 2],
        triangles: Vec<usize>,
    },
    /// Two triangles traverse their shared edge in the same direction (one is flipped).
    EdgeSameDirection {
        edge: [u32; 2],
        points: [Point; 2],
        triangles: [usize; 2],
    },
    /// Two vertices have bit-equal coordinates (-0.0 and 0.0 count as equal).
    DuplicateVertex {
        first: usize,
        second: usize,
        point: Point,
    },
    /// A vertex belongs to no triangle.
    UnreferencedVertex { vertex: usize, point: Point },
    /// The boundary edges at a vertex do not pair up into closed loops.
    OpenBoundary {
        vertex: usize,
        point: Point,
        incoming: usize,
        outgoing: usize,
    },
    /// Two boundary edges cross or overlap.
    BoundaryCrossing {
        first: [u32; 2],
        second: [u32; 2],
        first_points: [Point; 2],
        second_points: [Point; 2],
    },
    /// The triangles around an interior vertex wind `winding` times around it instead of once
    /// (their angles do not sum to 360°).
    Fold {
        vertex: usize,
        point: Point,
        winding: i64,
    },
    /// Just inside boundary edge `edge` the mesh covers the plane `covering` times, not once:
    /// two parts of the mesh overlap.
    Overlap {
        edge: [u32; 2],
        points: [Point; 2],
        covering: i64,
    },
    /// The triangle areas do not sum to the area the boundary loops enclose.
    AreaMismatch { triangles: f64, enclosed: f64 },
    /// A mesh that must be one disc has several boundary loops (a hole, or pieces), or its
    /// boundary touches itself at a vertex (a hole reaching the boundary at a corner).
    HoleInMesh {
        loops: usize,
        first_vertices: Vec<u32>,
        pinched_at: Vec<u32>,
    },
    /// An input point is not a mesh vertex (bit-exact comparison).
    MissingInputPoint { input: usize, point: Point },
    /// A hole seed of the input lies in triangle `triangle`: the hole is meshed.
    HoleCovered {
        hole: usize,
        point: Point,
        triangle: usize,
    },
    /// A boundary edge of the mesh lies on no input segment: the mesh of a PSLG ends where
    /// the input has no boundary (it spills beyond the segments, or leaves a gap inside).
    BoundaryOffSegments { edge: [u32; 2], points: [Point; 2] },
    /// An input segment is not a chain of mesh edges along it (within rounding, see `check_input`); `stuck_at` is the mesh vertex
    /// where the chain from the first endpoint breaks off (none when an endpoint is missing).
    SegmentNotConforming {
        segment: usize,
        endpoints: [u32; 2],
        points: [Point; 2],
        stuck_at: Option<(u32, Point)>,
    },
}

fn pt(p: Point) -> String {
    format!("({}, {})", super::show(p[0]), super::show(p[1]))
}

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
                super::show(*triangles),
                super::show(*enclosed)
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
}

/// A hash key for a point: the bits of both coordinates, with -0.0 folded into 0.0 (adding
/// 0.0 does exactly that) so the two zeros, which compare equal, hash equal.
pub(crate) fn point_key(p: Point) -> (u64, u64) {
    ((p[0] + 0.0).to_bits(), (p[1] + 0.0).to_bits())
}

/// The edge structure of the usable triangles (indices in range, three distinct corners).
pub(crate) struct Topology {
    /// Triangles with in-range, distinct corners.
    pub usable: Vec<bool>,
    /// Edges used by exactly one triangle, directed as that triangle traverses them.
    pub boundary: Vec<DirectedEdge>,
    /// Edges shared by two triangles in opposite directions: (u, v, t1, t2), t1 traverses u→v.
    pub interior: Vec<(u32, u32, usize, usize)>,
    /// Edges used three or more times: (lo, hi, triangles).
    pub overused: Vec<(u32, u32, Vec<usize>)>,
    /// Edges two triangles traverse in the same direction: (u, v, t1, t2).
    pub same_direction: Vec<(u32, u32, usize, usize)>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct DirectedEdge {
    pub from: u32,
    pub to: u32,
    pub triangle: usize,
}

/// Groups the edges of the usable triangles, deterministically (sorted, no hash order).
pub(crate) fn topology(mesh: &TriMesh) -> Topology {
    let n = mesh.vertices.len();
    let usable: Vec<bool> = mesh
        .triangles
        .iter()
        .map(|t| {
            t.iter().all(|&v| (v as usize) < n) && t[0] != t[1] && t[1] != t[2] && t[0] != t[2]
        })
        .collect();
    // (lo, hi, triangle, forward): forward when the triangle goes lo→hi.
    let mut edges: Vec<(u32, u32, usize, bool)> = Vec::with_capacity(3 * mesh.triangles.len());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if !usable[t] {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b), t, a < b));
        }
    }
    edges.sort_unstable();
    let mut topo = Topology {
        usable,
        boundary: Vec::new(),
        interior: Vec::new(),
        overused: Vec::new(),
        same_direction: Vec::new(),
    };
    let mut i = 0;
    while i < edges.len() {
        let (lo, hi, _, _) = edges[i];
        let mut j = i;
        while j < edges.len() && edges[j].0 == lo && edges[j].1 == hi {
            j += 1;
        }
        let group = &edges[i..j];
        let directed = |e: &(u32, u32, usize, bool)| if e.3 { (lo, hi) } else { (hi, lo) };
        match group.len() {
            1 => {
                let (from, to) = directed(&group[0]);
                topo.boundary.push(DirectedEdge {
                    from,
                    to,
                    triangle: group[0].2,
                });
            }
            2 => {
                let (u, v) = directed(&group[0]);
                if group[0].3 == group[1].3 {
                    topo.same_direction.push((u, v, group[0].2, group[1].2));
                } else {
                    topo.interior.push((u, v, group[0].2, group[1].2));
                }
            }
            _ => topo
                .overused
                .push((lo, hi, group.iter().map(|e| e.2).collect())),
        }
        i = j;
    }
    topo.boundary.sort_unstable();
    topo
}

/// Checks every invariant and returns every violation found, in a fixed order: vertex
/// coordinates, triangles, edges, duplicates, unreferenced vertices, boundary, input; by
/// index within each. An empty result means the mesh is valid.
pub fn validate(mesh: &TriMesh, input: Option<&Pslg>, opts: &ValidateOptions) -> Vec<Violation> {
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

    let topo = topology(mesh);
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
    let loops = boundary_loops(mesh, &topo, &boundary, &mut out);
    boundary_crossings(verts, &boundary, &mut out);
    overlaps(verts, &boundary, &loops, &mut out);
    folds(mesh, &topo, &geometric, &mut out);
    area_balance(mesh, &geometric, &boundary, &mut out);
    if opts.single_component {
        // Several boundary edges leaving one vertex: the boundary touches itself there.
        let mut pinched_at: Vec<u32> = boundary
            .windows(2)
            .filter(|w| w[0].from == w[1].from)
            .map(|w| w[0].from)
            .collect();
        pinched_at.dedup();
        if loops.len() > 1 || !pinched_at.is_empty() {
            out.push(Violation::HoleInMesh {
                loops: loops.len(),
                first_vertices: loops.iter().map(|l| boundary[l.edges[0]].from).collect(),
                pinched_at,
            });
        }
    }

    if let Some(input) = input {
        input_conformity(mesh, &topo, &boundary, input, opts.conforming, &mut out);
        holes_covered(mesh, &geometric, input, &mut out);
    }
    out
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

/// A hole seed inside (or on an edge of) a triangle means the mesher meshed the hole; seeds
/// on an input segment decide nothing and are skipped. Triangles are matched to the seeds in
/// their x-range, found by binary search in the seeds sorted by x.
fn holes_covered(mesh: &TriMesh, geometric: &[bool], input: &Pslg, out: &mut Vec<Violation>) {
    let on_segment = |q: Point| {
        input.segments.iter().any(|s| {
            match (
                input.points.get(s[0] as usize),
                input.points.get(s[1] as usize),
            ) {
                (Some(&a), Some(&b)) => {
                    orient2d_scaled(a, b, q) == 0.0
                        && q[0] >= a[0].min(b[0])
                        && q[0] <= a[0].max(b[0])
                        && q[1] >= a[1].min(b[1])
                        && q[1] <= a[1].max(b[1])
                }
                _ => false,
            }
        })
    };
    let mut seeds: Vec<(usize, Point)> = input
        .holes
        .iter()
        .copied()
        .enumerate()
        .filter(|(_, h)| h[0].is_finite() && h[1].is_finite() && !on_segment(*h))
        .collect();
    if seeds.is_empty() {
        return;
    }
    seeds.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]).then(a.0.cmp(&b.0)));
    let mut first: Vec<Option<usize>> = vec![None; input.holes.len()];
    for (t, &g) in geometric.iter().enumerate() {
        if !g {
            continue;
        }
        let [a, b, c] = mesh.corners(t);
        let (lo, hi) = (a[0].min(b[0]).min(c[0]), a[0].max(b[0]).max(c[0]));
        let start = seeds.partition_point(|s| s.1[0] < lo);
        for &(h, q) in seeds[start..].iter().take_while(|s| s.1[0] <= hi) {
            let inside = orient2d_scaled(a, b, q) >= 0.0
                && orient2d_scaled(b, c, q) >= 0.0
                && orient2d_scaled(c, a, q) >= 0.0
                && orient2d_scaled(a, b, c) > 0.0;
            if inside && first[h].is_none() {
                first[h] = Some(t);
            }
        }
    }
    for (hole, t) in first.iter().enumerate() {
        if let Some(triangle) = *t {
            out.push(Violation::HoleCovered {
                hole,
                point: input.holes[hole],
                triangle,
            });
        }
    }
}

/// Sorting by coordinate bits puts equal points next to each other; each later copy is
/// reported against the first.
fn duplicate_vertices(verts: &[Point], out: &mut Vec<Violation>) {
    let mut order: Vec<usize> = (0..verts.len()).collect();
    order.sort_by_key(|&i| (point_key(verts[i]), i));
    let mut i = 0;
    while i < order.len() {
        let mut j = i + 1;
        while j < order.len() && point_key(verts[order[j]]) == point_key(verts[order[i]]) {
            out.push(Violation::DuplicateVertex {
                first: order[i],
                second: order[j],
                point: verts[order[i]],
            });
            j += 1;
        }
        i = j;
    }
}

/// A chain of boundary edges (indices into the boundary list), closed unless the boundary
/// is broken.
pub(crate) struct BoundaryLoop {
    pub edges: Vec<usize>,
    /// True when the loop passes through a vertex shared with another loop or itself.
    pub pinched: bool,
}

/// Splits the boundary edges into loops. Where several loops meet at a vertex, the incoming
/// edge is continued by the outgoing edge of the same fan of triangles (found by rotating
/// around the vertex through shared edges), so that two discs touching at a corner give two
/// loops rather than one figure eight.
fn boundary_loops(
    mesh: &TriMesh,
    topo: &Topology,
    boundary: &[DirectedEdge],
    out: &mut Vec<Violation>,
) -> Vec<BoundaryLoop> {
    let verts = &mesh.vertices;
    let mut incoming: HashMap<u32, usize> = HashMap::new();
    let mut outgoing: HashMap<u32, usize> = HashMap::new();
    for e in boundary {
        *outgoing.entry(e.from).or_default() += 1;
        *incoming.entry(e.to).or_default() += 1;
    }
    let mut touched: Vec<u32> = incoming.keys().chain(outgoing.keys()).copied().collect();
    touched.sort_unstable();
    touched.dedup();
    for &v in &touched {
        let (i, o) = (
            incoming.get(&v).copied().unwrap_or(0),
            outgoing.get(&v).copied().unwrap_or(0),
        );
        if i != o {
            out.push(Violation::OpenBoundary {
                vertex: v as usize,
                point: verts[v as usize],
                incoming: i,
                outgoing: o,
            });
        }
    }

    // Directed edge -> triangle, for the fan walk; boundary is sorted by (from, to).
    let mut directed: Vec<(u32, u32, usize)> = topo
        .interior
        .iter()
        .flat_map(|&(u, v, t1, t2)| [(u, v, t1), (v, u, t2)])
        .collect();
    directed.sort_unstable();
    let twin_triangle = |from: u32, to: u32| -> Option<usize> {
        directed
            .binary_search_by(|e| (e.0, e.1).cmp(&(from, to)))
            .ok()
            .map(|k| directed[k].2)
    };
    let boundary_index = |from: u32, to: u32| -> Option<usize> {
        let k = boundary.partition_point(|e| (e.from, e.to) < (from, to));
        (k < boundary.len() && boundary[k].from == from && boundary[k].to == to).then_some(k)
    };
    let next_corner = |t: usize, v: u32| -> Option<u32> {
        let tri = mesh.triangles[t];
        (0..3).find(|&k| tri[k] == v).map(|k| tri[(k + 1) % 3])
    };
    // The boundary edge leaving `v` in the fan that edge `e` (arriving at v) belongs to.
    let fan_successor = |e: &DirectedEdge| -> Option<usize> {
        let v = e.to;
        let mut t = e.triangle;
        // Each step is a bijection between the triangles at v (every directed interior
        // edge names one triangle), so the walk ends at a boundary edge or comes back.
        loop {
            let w = next_corner(t, v)?;
            if let Some(k) = boundary_index(v, w) {
                return Some(k);
            }
            t = twin_triangle(w, v)?;
            if t == e.triangle {
                return None;
            }
        }
    };

    let first_out = |v: u32| boundary.partition_point(|e| e.from < v);
    let mut used = vec![false; boundary.len()];
    let mut loops = Vec::new();
    for start in 0..boundary.len() {
        if used[start] {
            continue;
        }
        let mut edges = vec![start];
        used[start] = true;
        let mut cur = start;
        loop {
            let preferred = fan_successor(&boundary[cur]).filter(|&k| !used[k] || k == start);
            let next = preferred.or_else(|| {
                let v = boundary[cur].to;
                (first_out(v)..boundary.len())
                    .take_while(|&k| boundary[k].from == v)
                    .find(|&k| !used[k] || k == start)
            });
            match next {
                Some(k) if k == start => break,
                Some(k) => {
                    used[k] = true;
                    edges.push(k);
                    cur = k;
                }
                None => break,
            }
        }
        let pinched = edges
            .iter()
            .any(|&k| outgoing.get(&boundary[k].from).copied().unwrap_or(0) > 1);
        loops.push(BoundaryLoop { edges, pinched });
    }
    loops
}

/// True when the closed segments ab and cd meet anywhere other than at an endpoint they
/// share as vertices (`shared`), decided with exact orientation signs.
fn segments_meet(a: Point, b: Point, c: Point, d: Point, shared: usize) -> bool {
    let o1 = orient2d_scaled(a, b, c);
    let o2 = orient2d_scaled(a, b, d);
    let o3 = orient2d_scaled(c, d, a);
    let o4 = orient2d_scaled(c, d, b);
    let between = |p: Point, q: Point, x: Point| {
        x[0] >= p[0].min(q[0])
            && x[0] <= p[0].max(q[0])
            && x[1] >= p[1].min(q[1])
            && x[1] <= p[1].max(q[1])
            && x != p
            && x != q
    };
    if o1 == 0.0 && o2 == 0.0 {
        return between(a, b, c) || between(a, b, d) || between(c, d, a) || between(c, d, b);
    }
    if shared > 0 {
        // Sharing an endpoint and not collinear: they meet only there.
        return false;
    }
    let proper = ((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0))
        && ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0));
    proper
        || (o1 == 0.0 && between(a, b, c))
        || (o2 == 0.0 && between(a, b, d))
        || (o3 == 0.0 && between(c, d, a))
        || (o4 == 0.0 && between(c, d, b))
        || c == a
        || c == b
        || d == a
        || d == b
}

/// Sweep over the boundary edges by x-interval; each candidate pair gets the exact test.
fn boundary_crossings(verts: &[Point], boundary: &[DirectedEdge], out: &mut Vec<Violation>) {
    let p = |v: u32| verts[v as usize];
    let mut order: Vec<usize> = (0..boundary.len()).collect();
    let xmin = |k: usize| p(boundary[k].from)[0].min(p(boundary[k].to)[0]);
    let xmax = |k: usize| p(boundary[k].from)[0].max(p(boundary[k].to)[0]);
    order.sort_by(|&a, &b| xmin(a).total_cmp(&xmin(b)).then(a.cmp(&b)));
    let mut active: Vec<usize> = Vec::new();
    let mut found: Vec<(usize, usize)> = Vec::new();
    for &k in &order {
        let x = xmin(k);
        active.retain(|&j| xmax(j) >= x);
        let e = boundary[k];
        for &j in &active {
            let f = boundary[j];
            let shared = [e.from, e.to]
                .iter()
                .filter(|v| **v == f.from || **v == f.to)
                .count();
            if shared == 2 {
                // The same undirected edge twice cannot be a boundary edge; skip defensively.
                continue;
            }
            if segments_meet(p(e.from), p(e.to), p(f.from), p(f.to), shared) {
                found.push((j.min(k), j.max(k)));
            }
        }
        active.push(k);
    }
    found.sort_unstable();
    for (a, b) in found {
        let (e, f) = (boundary[a], boundary[b]);
        out.push(Violation::BoundaryCrossing {
            first: [e.from, e.to],
            second: [f.from, f.to],
            first_points: [p(e.from), p(e.to)],
            second_points: [p(f.from), p(f.to)],
        });
    }
}

/// Contribution of the directed segment a→b to the winding number around `p`, counted on
/// the ray from `p` through `q` (Sunday's crossing rule with exact signs: an endpoint on the
/// ray's line counts as right of it, so shared endpoints are counted once).
fn ray_crossing(p: Point, q: Point, a: Point, b: Point) -> i64 {
    let left_a = orient2d_scaled(p, q, a) > 0.0;
    let left_b = orient2d_scaled(p, q, b) > 0.0;
    if !left_a && left_b && orient2d_scaled(a, b, p) > 0.0 {
        1
    } else if left_a && !left_b && orient2d_scaled(a, b, p) < 0.0 {
        -1
    } else {
        0
    }
}

/// `ray_crossing` for the ray from `p` towards +x, where "left of the ray" is "above p":
/// a y comparison, so it needs no second point on the ray (which p.x + 1 may not give).
fn horizontal_crossing(p: Point, a: Point, b: Point) -> i64 {
    let (above_a, above_b) = (a[1] > p[1], b[1] > p[1]);
    if !above_a && above_b && orient2d_scaled(a, b, p) > 0.0 {
        1
    } else if above_a && !above_b && orient2d_scaled(a, b, p) < 0.0 {
        -1
    } else {
        0
    }
}

/// The covering number just left of each tested boundary edge must be 1. Along a loop that
/// touches no other loop, that side is one region, so its longest edge stands for all of it;
/// loops through a shared vertex are tested edge by edge.
fn overlaps(
    verts: &[Point],
    boundary: &[DirectedEdge],
    loops: &[BoundaryLoop],
    out: &mut Vec<Violation>,
) {
    let p = |v: u32| verts[v as usize];
    let len2 = |k: usize| Dist2::between(p(boundary[k].from), p(boundary[k].to));
    for l in loops {
        let tested: Vec<usize> = if l.pinched {
            l.edges.clone()
        } else {
            l.edges
                .iter()
                .copied()
                .max_by(|&a, &b| len2(a).cmp(&len2(b)).then(b.cmp(&a)))
                .into_iter()
                .collect()
        };
        for k in tested {
            let (a, b) = (p(boundary[k].from), p(boundary[k].to));
            let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            // A ray leaving the edge to its left, along the left normal, long enough that
            // adding it to m does not round away its direction.
            let normal = [-(b[1] - a[1]), b[0] - a[0]];
            let stretch =
                (m[0].abs().max(m[1].abs()) / normal[0].abs().max(normal[1].abs())).max(1.0);
            let q = [m[0] + stretch * normal[0], m[1] + stretch * normal[1]];
            if m == a || m == b || orient2d_scaled(a, b, q) <= 0.0 {
                continue; // too short or too large to place a probe; nothing to decide with
            }
            // m is within rounding of the edge; only a boundary edge passing within that
            // distance of the midpoint (boundaries touching to an ulp) could mislead the count.
            let covering: i64 = boundary
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != k)
                .map(|(_, f)| ray_crossing(m, q, p(f.from), p(f.to)))
                .sum();
            if covering != 1 {
                out.push(Violation::Overlap {
                    edge: [boundary[k].from, boundary[k].to],
                    points: [a, b],
                    covering,
                });
            }
        }
    }
}

/// Winding number of each interior vertex's link (the opposite edges of its triangles) around
/// it, counted on the horizontal ray; a fan that is one sheet winds exactly once.
fn folds(mesh: &TriMesh, topo: &Topology, geometric: &[bool], out: &mut Vec<Violation>) {
    let n = mesh.vertices.len();
    let mut interior = vec![true; n];
    for e in &topo.boundary {
        interior[e.from as usize] = false;
        interior[e.to as usize] = false;
    }
    for &(u, v, _, _) in &topo.same_direction {
        interior[u as usize] = false;
        interior[v as usize] = false;
    }
    for (u, v, _) in &topo.overused {
        interior[*u as usize] = false;
        interior[*v as usize] = false;
    }
    let mut winding = vec![0i64; n];
    let mut seen = vec![false; n];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if !geometric[t] {
            for &v in tri {
                if (v as usize) < n {
                    interior[v as usize] = false;
                }
            }
            continue;
        }
        for k in 0..3 {
            let v = tri[k] as usize;
            let (a, b) = (tri[(k + 1) % 3] as usize, tri[(k + 2) % 3] as usize);
            let c = mesh.vertices[v];
            seen[v] = true;
            winding[v] += horizontal_crossing(c, mesh.vertices[a], mesh.vertices[b]);
        }
    }
    for v in 0..n {
        if interior[v] && seen[v] && winding[v] != 1 {
            out.push(Violation::Fold {
                vertex: v,
                point: mesh.vertices[v],
                winding: winding[v],
            });
        }
    }
}

/// The signed triangle areas must add up to the signed area of the boundary loops (shoelace
/// about the centre of the bounding box, to keep the cancellation small). Both are summed on
/// the coordinates scaled by the power of two that brings the largest into [1, 2) (exact, and
/// the same bits as unscaled wherever those products stay normal), so that no product of two
/// coordinates overflows or underflows; a mismatch reports them scaled back.
fn area_balance(
    mesh: &TriMesh,
    geometric: &[bool],
    boundary: &[DirectedEdge],
    out: &mut Vec<Violation>,
) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for (t, &g) in geometric.iter().enumerate() {
        if g {
            for c in mesh.corners(t) {
                for d in 0..2 {
                    lo[d] = lo[d].min(c[d]);
                    hi[d] = hi[d].max(c[d]);
                }
            }
        }
    }
    if lo[0] > hi[0] {
        return; // no triangle to measure
    }
    let k = scale_exponent(&[lo[0], lo[1], hi[0], hi[1]]);
    let s = |p: Point| scale_point(p, -k);
    let (lo, hi) = (s(lo), s(hi));
    let o = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    let cross = |a: Point, b: Point| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let mut total = 0.0;
    let mut scale = 0.0;
    for (t, &g) in geometric.iter().enumerate() {
        if g {
            let [a, b, c] = mesh.corners(t).map(s);
            let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
            total += area;
            scale += area.abs();
        }
    }
    let enclosed: f64 = 0.5
        * boundary
            .iter()
            .map(|e| {
                cross(
                    s(mesh.vertices[e.from as usize]),
                    s(mesh.vertices[e.to as usize]),
                )
            })
            .sum::<f64>();
    if (total - enclosed).abs() > 1e-9 * scale.max(enclosed.abs()) {
        out.push(Violation::AreaMismatch {
            triangles: scale2(total, 2 * k),
            enclosed: scale2(enclosed, 2 * k),
        });
    }
}

/// Every input point must be a vertex (bit-exact); with `conforming`, every input segment a
/// chain of mesh edges whose vertices lie exactly on it, walked from one endpoint to the other.
fn input_conformity(
    mesh: &TriMesh,
    topo: &Topology,
    boundary: &[DirectedEdge],
    input: &Pslg,
    conforming: bool,
    out: &mut Vec<Violation>,
) {
    let mut index: HashMap<(u64, u64), u32> = HashMap::with_capacity(mesh.vertices.len());
    for (v, &p) in mesh.vertices.iter().enumerate().rev() {
        // Reverse order so that the first of duplicate vertices wins.
        index.insert(point_key(p), v as u32);
    }
    let vertex_of: Vec<Option<u32>> = input
        .points
        .iter()
        .map(|&p| index.get(&point_key(p)).copied())
        .collect();
    for (i, (&p, v)) in input.points.iter().zip(&vertex_of).enumerate() {
        if v.is_none() {
            out.push(Violation::MissingInputPoint { input: i, point: p });
        }
    }
    if !conforming || input.segments.is_empty() {
        return;
    }

    // Adjacency in compressed rows, from every edge of the usable triangles.
    let n = mesh.vertices.len();
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if topo.usable[t] {
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
    let neighbours = |v: u32| {
        pairs[start[v as usize]..start[v as usize + 1]]
            .iter()
            .map(|e| e.1)
    };

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
        // Progress along the dominant axis of the segment: exact for collinear points.
        let (axis, sign) = if (pb[0] - pa[0]).abs() >= (pb[1] - pa[1]).abs() {
            (0, (pb[0] - pa[0]).signum())
        } else {
            (1, (pb[1] - pa[1]).signum())
        };
        let progress = |v: u32| sign * mesh.vertices[v as usize][axis];
        // Meshers split segments at constructed points (midpoints, crossings) that f64 can only
        // round onto the segment's line; a vertex counts as on the segment when it is within
        // 2^-40 of the segment's coordinate scale of the line: rounding, never a visible kink.
        // Input endpoints still have to match bit-exactly (above). The test runs on the points
        // scaled by the power of two that brings the segment's largest coordinate into [1, 2)
        // (exact; every quantity below scales alike, so the decision is the unscaled one),
        // so that neither the length nor the orientation under- or overflows.
        let k = scale_exponent(&[pa[0], pa[1], pb[0], pb[1]]);
        let (sa, sb) = (scale_point(pa, -k), scale_point(pb, -k));
        let length = dist(sa, sb);
        let scale = [sa[0], sa[1], sb[0], sb[1]]
            .iter()
            .fold(length, |m, c| m.max(c.abs()));
        let tolerance = scale * (-40f64).exp2();
        let on_line = |pw: Point| {
            let o = orient2d_scaled(sa, sb, scale_point(pw, -k));
            o == 0.0 || o.abs() / length <= tolerance
        };
        let end = progress(vb);
        let mut u = va;
        while u != vb {
            let here = progress(u);
            let step = neighbours(u)
                .filter(|&w| {
                    let pw = mesh.vertices[w as usize];
                    on_line(pw) && progress(w) > here && progress(w) <= end
                })
                .min_by(|&x, &y| progress(x).total_cmp(&progress(y)).then(x.cmp(&y)));
            match step {
                Some(w) => {
                    on_segments.push((u.min(w), u.max(w)));
                    u = w;
                }
                None => {
                    out.push(not_conforming(Some((u, mesh.vertices[u as usize]))));
                    conforms = false;
                    break;
                }
            }
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
