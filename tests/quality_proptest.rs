//! `validate` accepts the Delaunay triangulation of random point sets (built with spade,
//! whose predicates are exact too) and rejects every single corruption of it.

use hexmesh::geom::orient2d;
use hexmesh::quality::{metrics, validate, ValidateOptions, Violation};
use hexmesh::{Pslg, TriMesh};
use proptest::prelude::*;
use spade::{DelaunayTriangulation, Point2, Triangulation};

const ONE_DISC: ValidateOptions = ValidateOptions {
    single_component: true,
    conforming: true,
};

/// The Delaunay triangulation of `points` as a TriMesh, `None` when it has no triangle
/// (fewer than three points, or all collinear).
fn delaunay(points: &[[f64; 2]]) -> Option<TriMesh> {
    let mut dt: DelaunayTriangulation<Point2<f64>> = DelaunayTriangulation::new();
    for p in points {
        dt.insert(Point2::new(p[0], p[1])).ok()?;
    }
    let vertices: Vec<[f64; 2]> = dt
        .vertices()
        .map(|v| [v.position().x, v.position().y])
        .collect();
    let triangles: Vec<[u32; 3]> = dt
        .inner_faces()
        .map(|f| f.vertices().map(|v| v.fix().index() as u32))
        .collect();
    (!triangles.is_empty()).then_some(TriMesh {
        vertices,
        triangles,
    })
}

/// Random points: uniform in the unit square, or on a small integer lattice where collinear
/// and cocircular quadruples are everywhere.
fn point_sets() -> impl Strategy<Value = Vec<[f64; 2]>> {
    prop_oneof![
        prop::collection::vec((0.0..1.0f64, 0.0..1.0f64), 3..80)
            .prop_map(|v| v.into_iter().map(|(x, y)| [x, y]).collect()),
        prop::collection::vec((0i32..12, 0i32..12), 3..80)
            .prop_map(|v| v.into_iter().map(|(x, y)| [x as f64, y as f64]).collect()),
    ]
}

#[derive(Debug, Clone, Copy)]
enum Corruption {
    FlipTriangle(usize),
    MoveVertexAcrossEdge(usize, usize),
    DuplicateTriangle(usize),
    DeleteInteriorTriangle(usize),
    DuplicateVertex(usize),
    WrongIndex(usize, usize, usize),
    NudgeVertexOneUlp(usize, bool),
}

fn corruptions() -> impl Strategy<Value = Corruption> {
    let i = any::<usize>;
    prop_oneof![
        i().prop_map(Corruption::FlipTriangle),
        (i(), 0..3usize).prop_map(|(t, k)| Corruption::MoveVertexAcrossEdge(t, k)),
        i().prop_map(Corruption::DuplicateTriangle),
        i().prop_map(Corruption::DeleteInteriorTriangle),
        i().prop_map(Corruption::DuplicateVertex),
        (i(), 0..3usize, i()).prop_map(|(t, k, w)| Corruption::WrongIndex(t, k, w)),
        (i(), any::<bool>()).prop_map(|(v, up)| Corruption::NudgeVertexOneUlp(v, up)),
    ]
}

fn has(v: &[Violation], pred: impl Fn(&Violation) -> bool) -> bool {
    v.iter().any(pred)
}

/// Triangles whose three edges are each shared with another triangle.
fn interior_triangles(mesh: &TriMesh) -> Vec<usize> {
    let mut edges: Vec<(u32, u32)> = mesh
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
        .collect();
    edges.sort_unstable();
    let shared = |a: u32, b: u32| {
        let e = (a.min(b), a.max(b));
        edges.partition_point(|x| *x < e) + 1 < edges.partition_point(|x| *x <= e)
    };
    (0..mesh.triangles.len())
        .filter(|&t| {
            let tri = mesh.triangles[t];
            (0..3).all(|k| shared(tri[k], tri[(k + 1) % 3]))
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn validate_accepts_the_delaunay_triangulation_of_random_points(points in point_sets()) {
        let Some(mesh) = delaunay(&points) else { return Ok(()) };
        let input = Pslg::from_points(points.clone());
        let v = validate(&mesh, Some(&input), &ONE_DISC);
        prop_assert!(v.is_empty(), "{:#?}", v);
        prop_assert_eq!(metrics(&mesh, Some(&input)).delaunay_violations, 0);
    }

    #[test]
    fn validate_rejects_each_single_corruption(points in point_sets(), c in corruptions()) {
        let Some(mut mesh) = delaunay(&points) else { return Ok(()) };
        let nt = mesh.triangles.len();
        let nv = mesh.vertices.len();
        match c {
            Corruption::FlipTriangle(t) => {
                let t = t % nt;
                mesh.triangles[t].swap(1, 2);
                let v = validate(&mesh, None, &ONE_DISC);
                prop_assert!(has(&v, |x| matches!(x, Violation::Clockwise { triangle, .. } if *triangle == t)), "{:#?}", v);
            }
            Corruption::MoveVertexAcrossEdge(t, k) => {
                let t = t % nt;
                let tri = mesh.triangles[t];
                let (v, a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize, tri[(k + 2) % 3] as usize);
                let (pa, pb, pv) = (mesh.vertices[a], mesh.vertices[b], mesh.vertices[v]);
                // Point reflection through the edge's midpoint: same distance, other side.
                let q = [pa[0] + pb[0] - pv[0], pa[1] + pb[1] - pv[1]];
                prop_assume!(orient2d(pa, pb, q) < 0.0);
                mesh.vertices[v] = q;
                let out = validate(&mesh, None, &ONE_DISC);
                prop_assert!(has(&out, |x| matches!(x, Violation::Clockwise { triangle, .. } if *triangle == t)), "{:#?}", out);
            }
            Corruption::DuplicateTriangle(t) => {
                let copy = mesh.triangles[t % nt];
                mesh.triangles.push(copy);
                let v = validate(&mesh, None, &ONE_DISC);
                prop_assert!(has(&v, |x| matches!(x, Violation::EdgeOverused { .. } | Violation::EdgeSameDirection { .. })), "{:#?}", v);
            }
            Corruption::DeleteInteriorTriangle(t) => {
                let inner = interior_triangles(&mesh);
                prop_assume!(!inner.is_empty());
                mesh.triangles.remove(inner[t % inner.len()]);
                let v = validate(&mesh, None, &ONE_DISC);
                prop_assert!(has(&v, |x| matches!(x, Violation::HoleInMesh { .. })), "{:#?}", v);
                // A hole is fine where the domain has one: only the one-disc rule catches it.
                let plain = validate(&mesh, None, &ValidateOptions::default());
                prop_assert!(plain.is_empty(), "{:#?}", plain);
            }
            Corruption::DuplicateVertex(t) => {
                // A copy of a corner of triangle t, which t now uses instead of the original.
                let t = t % nt;
                let v = mesh.triangles[t][0];
                mesh.vertices.push(mesh.vertices[v as usize]);
                mesh.triangles[t][0] = nv as u32;
                let out = validate(&mesh, None, &ONE_DISC);
                prop_assert!(has(&out, |x| matches!(x, Violation::DuplicateVertex { first, second, .. } if *first == v as usize && *second == nv)), "{:#?}", out);
            }
            Corruption::WrongIndex(t, k, w) => {
                let t = t % nt;
                let w = (w % nv) as u32;
                prop_assume!(!mesh.triangles[t].contains(&w));
                mesh.triangles[t][k] = w;
                let v = validate(&mesh, None, &ONE_DISC);
                prop_assert!(!v.is_empty(), "corner {} of triangle {} set to {} went unnoticed", k, t, w);
            }
            Corruption::NudgeVertexOneUlp(v, up) => {
                // One ulp is invisible to any tolerance; the input point must still be missed.
                let v = v % nv;
                let p = mesh.vertices[v];
                // Away from zero adds one to the bits, towards zero subtracts one; 0 goes to 5e-324.
                let x = if p[0] == 0.0 {
                    5e-324
                } else if up {
                    f64::from_bits(p[0].to_bits() + 1)
                } else {
                    f64::from_bits(p[0].to_bits() - 1)
                };
                mesh.vertices[v] = [x, p[1]];
                let input = Pslg::from_points(points.clone());
                let out = validate(&mesh, Some(&input), &ONE_DISC);
                prop_assert!(has(&out, |x| matches!(x, Violation::MissingInputPoint { point, .. } if *point == p)), "{:#?}", out);
            }
        }
    }
}
