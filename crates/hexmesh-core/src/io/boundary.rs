//! The boundary of an output mesh, derived from the mesh and its input, for the writers that
//! hand a finite-element user what Triangle's output files carry: every edge with its
//! boundary marker, every vertex with its marker and attributes, the boundary loops (outer
//! boundaries and holes) and every triangle's regional attribute.
//!
//! Conventions (Triangle 1.6 documentation, "Boundary markers", without `-B`):
//! - an edge on an input segment with a nonzero marker has that marker; else an edge on the
//!   boundary of the mesh (holes included) has 1; else 0;
//! - a vertex with a nonzero input marker keeps it; else a vertex on an input segment with a
//!   nonzero marker has that marker (the first such segment in input order); else a vertex on
//!   the boundary has 1; else 0.
//!
//! Position decides what an output item is: an input point is the mesh vertex with its exact
//! coordinates, and an input segment is the chain of mesh edges walked along it from one
//! endpoint to the other, as the conformity check walks it (`quality::validate`: a vertex on
//! the segment's line by its exact orientation, or within the 2^-40 relative rounding that
//! check allows for constructed points). A point set has no segments: its boundary is the
//! mesh's outer loop, marked 1.

use crate::geom::{orient2d_scaled, Point};
use crate::hex::fxhash::FxHashMap;
use crate::mesh::{Pslg, TriMesh};
use crate::quality::validate::chains::{input_vertices, walk_segments, Adjacency};
use crate::quality::validate::regions_across;
use crate::quality::validate::{boundary_loops, topology};

/// The edges of the usable triangles by their lower vertex, as (higher vertex, edge number):
/// room for each vertex's first `BUCKET` edges counted first, then filled as edges are met,
/// and a hash table for the edges beyond (a vertex with many edges, such as the hub of a fan,
/// would make the scans quadratic). Most vertices have a handful of edges, so a look-up scans
/// a few entries: a hash table of every edge was most of the time of writing a large mesh.
struct EdgeIndex {
    /// Vertex v's entries start at `start[v]`; `end[v]` is one past its last so far.
    start: Vec<usize>,
    end: Vec<usize>,
    slots: Vec<(u32, usize)>,
    /// The edges of a vertex beyond its first `BUCKET`, by (lower, higher) vertex.
    beyond: FxHashMap<(u32, u32), usize>,
}

/// The edges of a vertex kept in its bucket; the others go to `EdgeIndex::beyond`.
const BUCKET: usize = 16;

impl EdgeIndex {
    /// Empty, with room for the uses of an edge by a usable triangle (up to `BUCKET` a vertex).
    fn new(mesh: &TriMesh, usable: &[bool]) -> EdgeIndex {
        let n = mesh.vertices.len();
        let mut start = vec![0usize; n + 1];
        for (tri, _) in mesh.triangles.iter().zip(usable).filter(|(_, &u)| u) {
            for k in 0..3 {
                start[tri[k].min(tri[(k + 1) % 3]) as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] = start[v] + start[v + 1].min(BUCKET);
        }
        let end = start[..n].to_vec();
        let slots = vec![(0, 0); start[n]];
        EdgeIndex {
            start,
            end,
            slots,
            beyond: FxHashMap::default(),
        }
    }

    /// The number of edge {a, b}, if added.
    fn get(&self, a: u32, b: u32) -> Option<usize> {
        let (lo, hi) = (a.min(b) as usize, a.max(b));
        let (from, to) = (*self.start.get(lo)?, *self.end.get(lo)?);
        let found = self.slots[from..to].iter().find(|s| s.0 == hi).map(|s| s.1);
        match found {
            None if to - from == BUCKET => self.beyond.get(&(lo as u32, hi)).copied(),
            _ => found,
        }
    }

    /// Adds edge {a, b} (of a usable triangle, not added before) as number `e`.
    fn add(&mut self, a: u32, b: u32, e: usize) {
        let lo = a.min(b) as usize;
        if self.end[lo] - self.start[lo] < BUCKET {
            self.slots[self.end[lo]] = (a.max(b), e);
            self.end[lo] += 1;
        } else {
            self.beyond.insert((a.min(b), a.max(b)), e);
        }
    }
}

/// One edge of the mesh, with what the writers say about it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edge {
    /// The endpoints (0-based), directed as the first triangle using the edge traverses it:
    /// a boundary edge has the mesh on its left.
    pub vertices: [u32; 2],
    /// Used by exactly one triangle.
    pub boundary: bool,
    /// The first input segment (in input order) whose chain of edges contains this edge.
    pub segment: Option<u32>,
    /// The boundary marker, in Triangle's convention (see the module documentation).
    pub marker: i64,
}

impl Edge {
    /// A boundary edge or an edge on an input segment: what an output `.poly` file lists as a
    /// segment and Gmsh gets as a line element.
    pub fn is_marked(&self) -> bool {
        self.boundary || self.segment.is_some()
    }
}

/// Whether a boundary loop bounds the mesh from outside or a hole in it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoopKind {
    /// Counter-clockwise: the outer boundary of a part of the mesh.
    Outer,
    /// Clockwise: the boundary of a hole.
    Hole,
}

/// A connected cycle of boundary edges.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BoundaryLoop {
    /// The loop's edges in order (the mesh on their left), as indices into
    /// [`Boundary::edges`].
    pub edges: Vec<usize>,
    /// Outer boundary or hole, by the loop's orientation.
    pub kind: LoopKind,
}

/// What the writers carry to an output mesh beyond vertices and triangles.
#[derive(Debug, Clone, PartialEq)]
pub struct Boundary {
    /// Every edge of the mesh once, in the order the triangles first use them (triangle 0's
    /// edges 01, 12, 20, then triangle 1's new edges, and so on).
    pub edges: Vec<Edge>,
    /// The boundary marker of every vertex.
    pub vertex_markers: Vec<i64>,
    /// The attributes of every vertex, as many per vertex as the input points have: an input
    /// point's own; a Steiner point on an input segment gets them interpolated linearly between
    /// the segment's endpoints (by position along the segment); any other vertex gets zeros.
    /// Empty when the input has no point attributes.
    pub vertex_attributes: Vec<Vec<f64>>,
    /// The boundary loops, in the order of their first edge (`quality::validate`'s loops).
    pub loops: Vec<BoundaryLoop>,
    /// The regional attribute of every triangle: the attribute of the last input region whose
    /// point lies in the triangle's part of the domain (the triangles reachable without
    /// crossing an input segment), else 0.
    pub triangle_regions: Vec<f64>,
    /// True when the input has regions, so that the region attribute means something.
    pub has_regions: bool,
}

impl Boundary {
    /// The edges that are boundary edges or lie on input segments, in edge order.
    pub fn marked_edges(&self) -> impl Iterator<Item = &Edge> {
        self.edges.iter().filter(|e| e.is_marked())
    }
}

/// Derives the boundary of `mesh` from the mesh and, when given, its input (see the module
/// documentation for the conventions). Deterministic: no hash order reaches the result.
pub fn derive_boundary(mesh: &TriMesh, input: Option<&Pslg>) -> Boundary {
    derive(mesh, input, true)
}

/// `derive_boundary` with `edges` and `loops` left empty: the vertex markers and attributes
/// and the triangle regions, which the `.node`, `.ele`, VTK and VTU files carry, without the
/// list of every edge (32 bytes an edge; at 12 million triangles most of the time of writing
/// those files went into it).
pub(crate) fn derive_labels(mesh: &TriMesh, input: Option<&Pslg>) -> Boundary {
    derive(mesh, input, false)
}

/// `derive_boundary`, with the edges and loops only when `with_edges`.
fn derive(mesh: &TriMesh, input: Option<&Pslg>, with_edges: bool) -> Boundary {
    let n = mesh.vertices.len();
    let topo = topology(mesh);

    // Every edge of the usable triangles, in order of first use.
    let mut index = with_edges.then(|| EdgeIndex::new(mesh, &topo.usable));
    let mut edges: Vec<Edge> = Vec::new();
    let mut uses: Vec<u32> = Vec::new();
    let with_regions = input.is_some_and(|i| !i.labels.regions.is_empty());
    if let Some(index) = index.as_mut() {
        for (t, tri) in mesh.triangles.iter().enumerate() {
            if !topo.usable[t] {
                continue;
            }
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let e = index.get(a, b).unwrap_or_else(|| {
                    edges.push(Edge {
                        vertices: [a, b],
                        boundary: false,
                        segment: None,
                        marker: 0,
                    });
                    uses.push(0);
                    index.add(a, b, edges.len() - 1);
                    edges.len() - 1
                });
                uses[e] += 1;
            }
        }
    }
    for (edge, &u) in edges.iter_mut().zip(&uses) {
        edge.boundary = u == 1;
    }
    let edge_of = |a: u32, b: u32| index.as_ref().and_then(|i| i.get(a, b));

    // The chains of edges along the input segments; the first segment in input order wins.
    // Their edges as (lower, higher) vertex, sorted, for the regions.
    let mut on_segments: Vec<(u32, u32)> = Vec::new();
    let mut chain_vertices: Vec<(u32, u32)> = Vec::new(); // (vertex, segment)
    let labels = input.map(|i| &i.labels);
    let vertex_of = input.map_or_else(Vec::new, |i| input_vertices(mesh, i));
    if let Some(input) = input.filter(|i| i.has_segments()) {
        let adjacency = Adjacency::new(mesh, &topo.usable);
        for walked in walk_segments(mesh, input, &adjacency, &vertex_of) {
            let s = walked.segment as u32;
            for (u, w) in walked.edges {
                if let Some(e) = edge_of(u, w) {
                    edges[e].segment.get_or_insert(s);
                }
                on_segments.push((u.min(w), u.max(w)));
                chain_vertices.extend([(u, s), (w, s)]);
            }
            chain_vertices.extend(walked.ends.map(|v| (v, s)));
        }
    }
    let segment_marker = |s: u32| {
        labels
            .and_then(|l| l.segment_markers.as_ref())
            .and_then(|m| m.get(s as usize).copied())
            .unwrap_or(0)
    };
    for edge in &mut edges {
        edge.marker = match edge.segment.map(segment_marker) {
            Some(m) if m != 0 => m,
            _ => i64::from(edge.boundary),
        };
    }

    // Vertex markers: input marker, else the first marked segment through it, else boundary.
    chain_vertices.sort_unstable_by_key(|&(v, s)| (s, v));
    let mut vertex_markers = vec![0i64; n];
    // The ends of the edges used once (`edges`' boundary edges, when they are listed).
    for edge in &topo.boundary {
        vertex_markers[edge.from as usize] = 1;
        vertex_markers[edge.to as usize] = 1;
    }
    // Segments in reverse input order, so that the first one through a vertex writes last.
    for &(v, s) in chain_vertices.iter().rev() {
        let m = segment_marker(s);
        if m != 0 {
            vertex_markers[v as usize] = m;
        }
    }
    if let (Some(input), Some(markers)) = (input, labels.and_then(|l| l.point_markers.as_ref())) {
        for (i, &m) in markers.iter().enumerate().take(input.points.len()) {
            if let (Some(v), true) = (vertex_of[i], m != 0) {
                vertex_markers[v as usize] = m;
            }
        }
    }

    let vertex_attributes = match input {
        Some(input) if input.labels.attribute_count() > 0 => {
            vertex_attributes(mesh, input, &vertex_of, &chain_vertices)
        }
        _ => Vec::new(),
    };

    // Boundary loops, through the fan where loops touch, as the validity check splits them.
    let mut ignored = Vec::new();
    let found = match with_edges {
        true => boundary_loops(mesh, &topo, &topo.boundary, &mut ignored),
        false => Vec::new(),
    };
    let loops = found
        .into_iter()
        .map(|l| {
            let directed: Vec<[u32; 2]> = l
                .edges
                .iter()
                .map(|&k| [topo.boundary[k].from, topo.boundary[k].to])
                .collect();
            BoundaryLoop {
                edges: directed
                    .iter()
                    .filter_map(|&[a, b]| edge_of(a, b))
                    .collect(),
                kind: loop_kind(mesh, &directed),
            }
        })
        .collect();

    let (triangle_regions, has_regions) = match input {
        // The flood fill the area-limit check uses too (`quality::triangle_regions`).
        Some(input) if with_regions => {
            // The segments' edges are known here: no second walk along them.
            on_segments.sort_unstable();
            let on_segment =
                |u: u32, v: u32| on_segments.binary_search(&(u.min(v), u.max(v))).is_ok();
            let attributes = regions_across(mesh, input, &topo, on_segment)
                .into_iter()
                .map(|r| r.map_or(0.0, |k| input.labels.regions[k].attribute))
                .collect();
            (attributes, true)
        }
        _ => (vec![0.0; mesh.triangles.len()], false),
    };

    Boundary {
        edges,
        vertex_markers,
        vertex_attributes,
        loops,
        triangle_regions,
        has_regions,
    }
}

/// Outer or hole, by the exact orientation of the loop at its lexicographically smallest
/// vertex (a convex corner of a simple polygon); the shoelace sum decides only when that
/// corner is degenerate (a broken or self-touching loop).
fn loop_kind(mesh: &TriMesh, directed: &[[u32; 2]]) -> LoopKind {
    let p = |v: u32| mesh.vertices[v as usize];
    let lowest = (0..directed.len()).min_by(|&i, &j| {
        let (a, b) = (p(directed[i][0]), p(directed[j][0]));
        a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
    });
    let Some(j) = lowest else {
        return LoopKind::Outer;
    };
    let previous = directed[(j + directed.len() - 1) % directed.len()][0];
    let [v, next] = directed[j];
    let mut turn = orient2d_scaled(p(previous), p(v), p(next));
    if turn == 0.0 {
        let o = p(directed[0][0]);
        turn = directed
            .iter()
            .map(|&[a, b]| {
                let (a, b) = (p(a), p(b));
                (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
            })
            .sum();
    }
    if turn < 0.0 {
        LoopKind::Hole
    } else {
        LoopKind::Outer
    }
}

/// The attributes of every vertex: an input point's own; a vertex on an input segment's chain
/// interpolated between the endpoints along the segment's dominant axis (first segment in
/// input order); zeros elsewhere.
fn vertex_attributes(
    mesh: &TriMesh,
    input: &Pslg,
    vertex_of: &[Option<u32>],
    chain_vertices: &[(u32, u32)],
) -> Vec<Vec<f64>> {
    let width = input.labels.attribute_count();
    let rows = &input.labels.point_attributes;
    let mut out: Vec<Option<Vec<f64>>> = vec![None; mesh.vertices.len()];
    for (i, v) in vertex_of.iter().enumerate() {
        if let (Some(v), Some(row)) = (v, rows.get(i)) {
            out[*v as usize].get_or_insert_with(|| row.clone());
        }
    }
    // chain_vertices is sorted by segment: the first segment through a vertex sets it.
    for &(v, s) in chain_vertices {
        if out[v as usize].is_some() {
            continue;
        }
        let seg = input.segments[s as usize];
        let (pa, pb) = (input.points[seg[0] as usize], input.points[seg[1] as usize]);
        let (ra, rb) = (&rows[seg[0] as usize], &rows[seg[1] as usize]);
        let axis = usize::from((pb[0] - pa[0]).abs() < (pb[1] - pa[1]).abs());
        let q: Point = mesh.vertices[v as usize];
        let t = ((q[axis] - pa[axis]) / (pb[axis] - pa[axis])).clamp(0.0, 1.0);
        out[v as usize] = Some(ra.iter().zip(rb).map(|(a, b)| a + t * (b - a)).collect());
    }
    out.into_iter()
        .map(|r| r.unwrap_or_else(|| vec![0.0; width]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Labels, Region};

    /// A 3×3 square with a 1×1 square hole in the middle, eight triangles around the hole.
    fn ring() -> (TriMesh, Pslg) {
        let points = vec![
            [0.0, 0.0],
            [3.0, 0.0],
            [3.0, 3.0],
            [0.0, 3.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [2.0, 2.0],
            [1.0, 2.0],
        ];
        let mesh = TriMesh {
            vertices: points.clone(),
            triangles: vec![
                [0, 1, 5],
                [0, 5, 4],
                [1, 2, 6],
                [1, 6, 5],
                [2, 3, 7],
                [2, 7, 6],
                [3, 0, 4],
                [3, 4, 7],
            ],
        };
        let ring = |b: u32| (0..4).map(move |k| [b + k, b + (k + 1) % 4]);
        let input = Pslg {
            points,
            segments: ring(0).chain(ring(4)).collect(),
            holes: vec![[1.5, 1.5]],
            labels: Labels {
                point_markers: Some(vec![9, 0, 0, 0, 0, 0, 0, 0]),
                segment_markers: Some(vec![5, 5, 5, 5, 7, 7, 7, 0]),
                ..Labels::default()
            },
            ..Pslg::default()
        };
        (mesh, input)
    }

    /// `super::derive_boundary`, checking on the way that `derive_labels` gives the same
    /// labels without the edges and loops: every test here checks both.
    fn derive_boundary(mesh: &TriMesh, input: Option<&Pslg>) -> Boundary {
        let full = super::derive_boundary(mesh, input);
        let labels = derive_labels(mesh, input);
        let without_edges = Boundary {
            edges: Vec::new(),
            loops: Vec::new(),
            ..full.clone()
        };
        assert_eq!(
            labels, without_edges,
            "the labels derived without the edges"
        );
        full
    }

    fn marker_of(b: &Boundary, u: u32, v: u32) -> i64 {
        b.edges
            .iter()
            .find(|e| e.vertices == [u, v] || e.vertices == [v, u])
            .map(|e| e.marker)
            .expect("edge")
    }

    #[test]
    fn the_hub_of_a_fan_has_each_of_its_edges_once() {
        // Vertex 0 has 200 edges, beyond the bucket of `EdgeIndex`: a look-up there must find
        // the edges kept in its table, or they would be listed again.
        let m = 200u32;
        let mut vertices = vec![[0.0, 0.0]];
        vertices.extend((0..m).map(|i| {
            let a = std::f64::consts::PI * f64::from(i) / f64::from(m);
            [a.cos(), a.sin()]
        }));
        let mesh = TriMesh {
            vertices,
            triangles: (1..m).map(|i| [0, i, i + 1]).collect(),
        };
        let b = derive_boundary(&mesh, None);
        // m spokes and m - 1 rim edges; the rim and the two outer spokes are the boundary.
        assert_eq!(b.edges.len(), 2 * m as usize - 1);
        assert_eq!(
            b.edges.iter().filter(|e| e.boundary).count(),
            m as usize + 1
        );
        assert_eq!(b.loops.len(), 1);
        assert_eq!(b.loops[0].edges.len(), m as usize + 1);
        assert!(b.vertex_markers.iter().all(|&k| k == 1));
    }

    #[test]
    fn a_square_with_a_square_hole_has_an_outer_loop_and_a_hole_loop() {
        let (mesh, input) = ring();
        let b = derive_boundary(&mesh, Some(&input));
        assert_eq!(b.edges.len(), 16);
        assert_eq!(b.loops.len(), 2);
        let kinds: Vec<(LoopKind, usize)> =
            b.loops.iter().map(|l| (l.kind, l.edges.len())).collect();
        assert!(kinds.contains(&(LoopKind::Outer, 4)), "{kinds:?}");
        assert!(kinds.contains(&(LoopKind::Hole, 4)), "{kinds:?}");
        for l in &b.loops {
            let lowest = if l.kind == LoopKind::Outer { 0 } else { 4 };
            // Every edge of a loop lies on that loop's ring, the mesh on its left.
            for &e in &l.edges {
                let [u, v] = b.edges[e].vertices;
                assert!((lowest..lowest + 4).contains(&u) && (lowest..lowest + 4).contains(&v));
                assert!(b.edges[e].boundary);
            }
        }
        // Without an input the same mesh has the same loops, all marked 1.
        let plain = derive_boundary(&mesh, None);
        assert_eq!(plain.loops, b.loops);
        assert!(plain.marked_edges().all(|e| e.marker == 1 && e.boundary));
        assert_eq!(plain.vertex_markers, vec![1; 8]);
    }

    #[test]
    fn markers_follow_triangles_convention() {
        let (mesh, input) = ring();
        let b = derive_boundary(&mesh, Some(&input));
        // Input segment markers are kept; the hole's segment 7 (marker 0) falls back to 1.
        for (k, s) in input.segments.iter().enumerate() {
            let expected = [5, 5, 5, 5, 7, 7, 7, 1][k];
            assert_eq!(marker_of(&b, s[0], s[1]), expected, "segment {k}");
        }
        // The four interior edges between the rings are on no segment: 0.
        for (u, v) in [(0, 5), (1, 6), (2, 7), (3, 4)] {
            assert_eq!(marker_of(&b, u, v), 0);
        }
        assert_eq!(b.marked_edges().count(), 8);
        // Vertex 0 keeps its input marker 9; the others take their first marked segment's.
        assert_eq!(b.vertex_markers, vec![9, 5, 5, 5, 7, 7, 7, 7]);
        assert!(!b.has_regions && b.triangle_regions == vec![0.0; 8]);
        assert!(b.vertex_attributes.is_empty());
    }

    /// A 2×2 square cut in two by the segment from (1, 0) to (1, 2); Steiner-free.
    fn halves() -> (TriMesh, Pslg) {
        let points = vec![
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 2.0],
            [0.0, 2.0],
            [1.0, 0.0],
            [1.0, 2.0],
        ];
        let mesh = TriMesh {
            vertices: points.clone(),
            triangles: vec![[0, 4, 5], [0, 5, 3], [4, 1, 2], [4, 2, 5]],
        };
        let input = Pslg {
            points,
            segments: vec![[0, 4], [4, 1], [1, 2], [2, 5], [5, 3], [3, 0], [4, 5]],
            ..Pslg::default()
        };
        (mesh, input)
    }

    #[test]
    fn an_interior_segment_is_marked_zero_and_separates_regions() {
        let (mesh, mut input) = halves();
        let b = derive_boundary(&mesh, Some(&input));
        let inner = b
            .edges
            .iter()
            .find(|e| e.segment == Some(6))
            .expect("the interior segment's edge");
        assert_eq!((inner.boundary, inner.marker), (false, 0));
        assert_eq!(b.marked_edges().count(), 7);
        assert_eq!(b.loops.len(), 1);
        assert_eq!(b.loops[0].kind, LoopKind::Outer);
        assert_eq!(b.vertex_markers, vec![1; 6]);

        input.labels.segment_markers = Some(vec![0, 0, 0, 0, 0, 0, 4]);
        input.labels.regions = vec![
            Region {
                point: [0.5, 1.0],
                attribute: 1.5,
                max_area: None,
            },
            Region {
                point: [1.5, 1.0],
                attribute: 2.5,
                max_area: Some(0.1),
            },
        ];
        let b = derive_boundary(&mesh, Some(&input));
        assert_eq!(marker_of(&b, 4, 5), 4);
        assert_eq!(b.vertex_markers, vec![1, 1, 1, 1, 4, 4]);
        assert!(b.has_regions);
        assert_eq!(b.triangle_regions, vec![1.5, 1.5, 2.5, 2.5]);

        // Without the interior segment one part holds both points: the later region wins.
        input.segments.pop();
        input.labels.segment_markers = None;
        let b = derive_boundary(&mesh, Some(&input));
        assert_eq!(b.triangle_regions, vec![2.5; 4]);
        // A region point outside the mesh sets nothing.
        input.labels.regions.truncate(1);
        input.labels.regions[0].point = [5.0, 5.0];
        assert_eq!(
            derive_boundary(&mesh, Some(&input)).triangle_regions,
            vec![0.0; 4]
        );
    }

    #[test]
    fn steiner_points_on_a_segment_get_its_marker_and_interpolated_attributes() {
        let (mesh, _) = halves();
        // The input is the bare square: (1, 0) and (1, 2) are Steiner points of the mesh.
        let input = Pslg {
            points: mesh.vertices[..4].to_vec(),
            segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
            labels: Labels {
                point_attributes: vec![
                    vec![2.0, 1.0],
                    vec![6.0, 1.0],
                    vec![10.0, 1.0],
                    vec![20.0, 1.0],
                ],
                segment_markers: Some(vec![3, 0, 0, 0]),
                ..Labels::default()
            },
            ..Pslg::default()
        };
        let b = derive_boundary(&mesh, Some(&input));
        assert_eq!(b.vertex_markers, vec![3, 3, 1, 1, 3, 1]);
        assert_eq!(marker_of(&b, 0, 4), 3);
        assert_eq!(marker_of(&b, 4, 1), 3);
        assert_eq!(marker_of(&b, 2, 5), 1);
        assert_eq!(marker_of(&b, 4, 5), 0);
        assert_eq!(
            b.vertex_attributes,
            vec![
                vec![2.0, 1.0],
                vec![6.0, 1.0],
                vec![10.0, 1.0],
                vec![20.0, 1.0],
                vec![4.0, 1.0],
                vec![15.0, 1.0],
            ]
        );
    }

    #[test]
    fn a_steiner_point_rounded_off_its_segment_still_splits_it_as_the_conformity_check_says() {
        // q is a third of the way along ab, rounded to f64: not exactly on the line.
        let (a, b, c) = ([0.0, 0.0], [1.0, 0.1], [0.5, 1.0]);
        let q = [1.0 / 3.0, 0.1 / 3.0];
        assert_ne!(
            orient2d_scaled(a, b, q),
            0.0,
            "the test needs a rounded point"
        );
        let mesh = TriMesh {
            vertices: vec![a, q, b, c],
            triangles: vec![[0, 1, 3], [1, 2, 3]],
        };
        let input = Pslg {
            points: vec![a, b, c],
            segments: vec![[0, 1], [1, 2], [2, 0]],
            labels: Labels {
                segment_markers: Some(vec![4, 0, 0]),
                ..Labels::default()
            },
            ..Pslg::default()
        };
        let b = derive_boundary(&mesh, Some(&input));
        assert_eq!(marker_of(&b, 0, 1), 4);
        assert_eq!(marker_of(&b, 1, 2), 4);
        assert_eq!(marker_of(&b, 2, 3), 1);
        assert_eq!(b.vertex_markers, vec![4, 4, 4, 1]);
        let v = crate::quality::validate(
            &mesh,
            Some(&input),
            &crate::quality::ValidateOptions {
                conforming: true,
                ..Default::default()
            },
        );
        assert!(v.is_empty(), "{v:?}");
    }

    #[test]
    fn edges_come_in_the_order_the_triangles_first_use_them() {
        let (mesh, _) = halves();
        let b = derive_boundary(&mesh, None);
        let order: Vec<[u32; 2]> = b.edges.iter().map(|e| e.vertices).collect();
        assert_eq!(
            order,
            vec![
                [0, 4],
                [4, 5],
                [5, 0],
                [5, 3],
                [3, 0],
                [4, 1],
                [1, 2],
                [2, 4],
                [2, 5]
            ]
        );
    }
}
