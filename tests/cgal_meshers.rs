//! The CGAL meshers `cgal` and `cgal-conforming` keep their promises (`verify --bounds`):
//! input points kept bit-exactly, counter-clockwise triangles covering exactly the domain, the
//! requested smallest angle and area for `cgal`, the empty-circle property for
//! `cgal-conforming`; C++ exceptions and budgets come back as Rust values.
#![cfg(feature = "cgal")]

use std::collections::BTreeMap;
use std::time::Duration;

use hexmesh::geom::{incircle, orient2d};
use hexmesh::reference::cgal::{ffi, limits, Cgal, CgalConforming};
use hexmesh::{Budget, Error, InputError, MeshRun, Mesher, Params, Point, Pslg, TriMesh};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

/// The unit square around a hole [0.25, 0.75]², seeded at its centre: area 0.75.
fn square_with_hole() -> Pslg {
    Pslg {
        points: vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.25, 0.25],
            [0.75, 0.25],
            [0.75, 0.75],
            [0.25, 0.75],
        ],
        segments: vec![
            [0, 1],
            [1, 2],
            [2, 3],
            [3, 0],
            [4, 5],
            [5, 6],
            [6, 7],
            [7, 4],
        ],
        holes: vec![[0.5, 0.5]],
        hexagon: None,
        ..Pslg::default()
    }
}

/// Forty seeded random points in the unit square, in their reference domain (the fitted
/// bounding hexagon's corners and edges added).
fn point_set_domain() -> Pslg {
    let mut rng = Pcg64::seed_from_u64(20090603);
    let points: Vec<Point> = (0..40)
        .map(|_| [rng.random::<f64>(), rng.random::<f64>()])
        .collect();
    Pslg::from_points(points).reference_domain()
}

fn triangle_area(m: &TriMesh, t: usize) -> f64 {
    let [a, b, c] = m.corners(t);
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

/// Smallest interior angle of a triangle, in degrees.
fn min_angle_deg(m: &TriMesh, t: usize) -> f64 {
    let p = m.corners(t);
    (0..3)
        .map(|i| {
            let (a, b, c) = (p[i], p[(i + 1) % 3], p[(i + 2) % 3]);
            let u = [b[0] - a[0], b[1] - a[1]];
            let v = [c[0] - a[0], c[1] - a[1]];
            let cross = u[0] * v[1] - u[1] * v[0];
            let dot = u[0] * v[0] + u[1] * v[1];
            cross.abs().atan2(dot).to_degrees()
        })
        .fold(f64::INFINITY, f64::min)
}

/// What every CGAL mesh must satisfy: input point i is vertex i, bit for bit; every triangle
/// counter-clockwise with positive area (exact sign); every edge used once per direction at
/// most; the triangles cover `area`.
fn assert_valid(input: &Pslg, run: &MeshRun, area: f64) {
    let m = &run.mesh;
    assert!(m.vertices.len() >= input.points.len());
    for (i, p) in input.points.iter().enumerate() {
        let v = m.vertices[i];
        assert!(
            v[0].to_bits() == p[0].to_bits() && v[1].to_bits() == p[1].to_bits(),
            "input point {i} {p:?} became {v:?}"
        );
    }
    assert!(!m.triangles.is_empty());
    let mut directed = BTreeMap::new();
    for (t, tri) in m.triangles.iter().enumerate() {
        let [a, b, c] = m.corners(t);
        assert!(orient2d(a, b, c) > 0.0, "triangle {t} {tri:?} is not CCW");
        for k in 0..3 {
            let e = (tri[k], tri[(k + 1) % 3]);
            assert!(directed.insert(e, t).is_none(), "edge {e:?} used twice");
        }
    }
    let covered: f64 = (0..m.triangles.len()).map(|t| triangle_area(m, t)).sum();
    assert!(
        (covered - area).abs() <= 1e-12 * area,
        "triangles cover {covered}, the domain is {area}"
    );
}

/// Every input segment is a chain of mesh edges: the edges lying on it add up to its length.
/// Split points are constructed (midpoints), so "on it" allows a rounding-sized distance.
fn assert_segments_are_chains(input: &Pslg, m: &TriMesh) {
    let mut edges: Vec<(u32, u32)> = m
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    for &[s, t] in &input.segments {
        let (a, b) = (input.points[s as usize], input.points[t as usize]);
        let len2 = hexmesh::geom::dist2(a, b);
        let on = |p: Point| {
            let along = (p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1]);
            orient2d(a, b, p).abs() <= 1e-12 * len2
                && along >= -1e-12 * len2
                && along <= len2 * (1.0 + 1e-12)
        };
        let length: f64 = edges
            .iter()
            .map(|&(u, v)| (m.vertices[u as usize], m.vertices[v as usize]))
            .filter(|&(p, q)| on(p) && on(q))
            .map(|(p, q)| hexmesh::geom::dist(p, q))
            .sum();
        let want = len2.sqrt();
        assert!(
            (length - want).abs() <= 1e-9 * want,
            "segment {s}-{t}: mesh edges along it sum to {length}, not {want}"
        );
    }
}

/// Interior edges whose opposite vertex lies strictly inside the circumcircle (exact test).
fn delaunay_violations(m: &TriMesh) -> usize {
    let mut opposite = BTreeMap::new();
    for tri in &m.triangles {
        for k in 0..3 {
            opposite.insert((tri[k], tri[(k + 1) % 3]), tri[(k + 2) % 3]);
        }
    }
    let v = |i: u32| m.vertices[i as usize];
    opposite
        .iter()
        .filter(|&(&(a, b), &c)| {
            opposite
                .get(&(b, a))
                .is_some_and(|&d| incircle(v(a), v(b), v(c), v(d)) > 0.0)
        })
        .count()
}

#[test]
fn cgal_meshes_a_square_with_a_hole_at_30_degrees() {
    let input = square_with_hole();
    let run = Cgal
        .mesh(&input, &Params::default().with_min_angle(30.0))
        .expect("cgal meshes the square");
    assert!(run.complete, "{:?}", run.stop_reason);
    assert_valid(&input, &run, 0.75);
    assert_segments_are_chains(&input, &run.mesh);
    let worst = (0..run.mesh.triangles.len())
        .map(|t| min_angle_deg(&run.mesh, t))
        .fold(f64::INFINITY, f64::min);
    assert!(worst >= 30.0 - 1e-6, "smallest angle {worst}°");
}

#[test]
fn cgal_meshes_a_point_set_in_its_reference_domain_at_30_degrees() {
    let input = point_set_domain();
    let area = input.bounding_hexagon().area();
    let run = Cgal
        .mesh(&input, &Params::default().with_min_angle(30.0))
        .expect("cgal meshes the point set");
    assert!(run.complete, "{:?}", run.stop_reason);
    assert_valid(&input, &run, area);
    assert_segments_are_chains(&input, &run.mesh);
    let worst = (0..run.mesh.triangles.len())
        .map(|t| min_angle_deg(&run.mesh, t))
        .fold(f64::INFINITY, f64::min);
    assert!(worst >= 30.0 - 1e-6, "smallest angle {worst}°");
}

#[test]
fn a_bare_point_set_is_meshed_in_its_bounding_hexagon() {
    let domain = point_set_domain();
    let bare = Pslg::from_points(domain.points[..40].to_vec());
    let hexagon = bare.bounding_hexagon().area();
    for mesher in [&Cgal as &dyn Mesher, &CgalConforming] {
        let params = Params::default().with_min_angle(30.0);
        let run = mesher.mesh(&bare, &params).unwrap();
        assert!(run.complete, "{}", mesher.name());
        // The hexagon's corners follow the input points, as in the reference domain.
        assert_valid(&domain, &run, hexagon);
        assert_eq!(run.mesh, mesher.mesh(&domain, &params).unwrap().mesh);
    }
}

#[test]
fn cgal_max_area_bounds_every_triangle_at_30_degrees() {
    let input = square_with_hole();
    let params = Params::default().with_min_angle(30.0).with_max_area(0.002);
    let run = Cgal.mesh(&input, &params).expect("cgal meshes the square");
    assert!(run.complete);
    assert_valid(&input, &run, 0.75);
    assert_segments_are_chains(&input, &run.mesh);
    let m = &run.mesh;
    let biggest = (0..m.triangles.len())
        .map(|t| triangle_area(m, t))
        .fold(0.0, f64::max);
    assert!(biggest <= 0.002, "largest triangle {biggest}");
    assert!(m.triangles.len() >= 375, "{}", m.triangles.len());
    let worst = (0..m.triangles.len())
        .map(|t| min_angle_deg(m, t))
        .fold(f64::INFINITY, f64::min);
    assert!(worst >= 30.0 - 1e-6, "smallest angle {worst}°");
}

#[test]
fn cgal_conforming_on_a_square_with_a_hole_is_delaunay() {
    let input = square_with_hole();
    let run = CgalConforming
        .mesh(&input, &Params::default())
        .expect("cgal-conforming meshes the square");
    assert!(run.complete);
    assert_valid(&input, &run, 0.75);
    assert_segments_are_chains(&input, &run.mesh);
    assert_eq!(delaunay_violations(&run.mesh), 0);
}

#[test]
fn cgal_conforming_on_a_point_set_domain_is_delaunay() {
    let input = point_set_domain();
    let area = input.bounding_hexagon().area();
    let run = CgalConforming
        .mesh(&input, &Params::default())
        .expect("cgal-conforming meshes the point set");
    assert!(run.complete);
    assert_valid(&input, &run, area);
    assert_segments_are_chains(&input, &run.mesh);
    assert_eq!(delaunay_violations(&run.mesh), 0);
}

/// A 10 × 2 rectangle cut in two by the chord y = 1, with points hugging the chord from above:
/// the chord is not a Delaunay edge, so the conformer must split it. Both halves touch the
/// outside, so both are in the domain (area 20).
fn split_rectangle() -> Pslg {
    let mut points = vec![
        [0.0, 0.0],
        [10.0, 0.0],
        [10.0, 1.0],
        [10.0, 2.0],
        [0.0, 2.0],
        [0.0, 1.0],
    ];
    points.extend((0..10).map(|i| [0.5 + i as f64, 1.05]));
    Pslg {
        points,
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0], [5, 2]],
        ..Pslg::default()
    }
}

#[test]
fn cgal_conforming_splits_segments_until_delaunay() {
    let input = split_rectangle();
    let run = CgalConforming.mesh(&input, &Params::default()).unwrap();
    assert!(run.complete);
    assert!(run.steps >= 10, "only {} splits", run.steps);
    assert_eq!(run.mesh.vertices.len() as u64, 16 + run.steps);
    assert_valid(&input, &run, 20.0);
    assert_segments_are_chains(&input, &run.mesh);
    assert_eq!(delaunay_violations(&run.mesh), 0);
}

#[test]
fn cgal_conforming_domain_follows_nesting_parity() {
    // Three nested squares, no seeds: level 1 (outer ring) is in, level 2 out, level 3 in.
    let ring = |lo: f64, hi: f64, base: u32| {
        (
            vec![[lo, lo], [hi, lo], [hi, hi], [lo, hi]],
            (0..4).map(move |i| [base + i, base + (i + 1) % 4]),
        )
    };
    let mut input = Pslg::default();
    for (k, (lo, hi)) in [(0.0, 6.0), (1.0, 5.0), (2.0, 4.0)].into_iter().enumerate() {
        let (pts, segs) = ring(lo, hi, 4 * k as u32);
        input.points.extend(pts);
        input.segments.extend(segs);
    }
    let run = CgalConforming.mesh(&input, &Params::default()).unwrap();
    assert_valid(&input, &run, 36.0 - 16.0 + 4.0);
    assert_segments_are_chains(&input, &run.mesh);
    // A seed in the innermost square removes it too.
    input.holes.push([3.0, 3.0]);
    let run = CgalConforming.mesh(&input, &Params::default()).unwrap();
    assert_valid(&input, &run, 36.0 - 16.0);
}

#[test]
fn meshes_are_deterministic() {
    let input = point_set_domain();
    let params = Params::default().with_min_angle(28.0).with_max_area(0.01);
    let first = Cgal.mesh(&input, &params).unwrap();
    let second = Cgal.mesh(&input, &params).unwrap();
    assert_eq!(first.mesh, second.mesh);
    assert_eq!(first.steps, second.steps);
}

#[test]
fn crossing_segments_throw_in_cgal_and_are_refused_before_it_through_the_trait() {
    // The diagonals of a square cross: CGAL's constrained triangulation throws
    // Intersection_of_constraints_exception. Called straight through the bridge, nothing
    // on the Rust side filters the input first.
    let points = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    let segments = [0, 2, 1, 3];
    let unlimited = limits(&Budget::default());
    let err = ffi::mesh_delaunay(&points, &segments, &[], 0.125, 0.0, &unlimited)
        .expect_err("crossing constraints must throw");
    assert!(err.what().contains("intersection"), "{}", err.what());
    assert!(ffi::mesh_conforming(&points, &segments, &[], &unlimited).is_err());

    let input = Pslg {
        points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        segments: vec![[0, 2], [1, 3]],
        ..Pslg::default()
    };
    // Through the trait, the input check (`Pslg::check`, which every mesher runs) refuses
    // the crossing before CGAL sees it.
    for mesher in [&Cgal as &dyn Mesher, &CgalConforming] {
        match mesher.mesh(&input, &Params::default()) {
            Err(Error::Input {
                problem:
                    InputError::CrossingSegments {
                        first: 0,
                        second: 1,
                    },
                ..
            }) => {}
            other => panic!(
                "{}: expected the crossing refused, got {other:?}",
                mesher.name()
            ),
        }
    }
}

#[test]
fn malformed_plain_data_is_refused_by_the_shim() {
    let unlimited = limits(&Budget::default());
    let square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    let cases: [(&[f64], &[u32], &[f64]); 6] = [
        (&[0.0, 0.0, 1.0], &[], &[]),
        (&[0.0, 0.0, f64::NAN, 1.0, 1.0, 0.0], &[], &[]),
        (&square, &[0, 9], &[]),
        (&square, &[1, 1], &[]),
        (&[0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0], &[], &[]),
        (&square, &[], &[f64::INFINITY, 0.0]),
    ];
    for (points, segments, holes) in cases {
        let d = ffi::mesh_delaunay(points, segments, holes, 0.125, 0.0, &unlimited);
        assert!(d.is_err(), "{points:?} {segments:?} {holes:?}");
        let c = ffi::mesh_conforming(points, segments, holes, &unlimited);
        assert!(c.is_err(), "{points:?} {segments:?} {holes:?}");
    }
    let dup = ffi::mesh_delaunay(cases[4].0, &[], &[], 0.125, 0.0, &unlimited).unwrap_err();
    assert!(dup.what().contains("points 0 and 2"), "{}", dup.what());
}

#[test]
fn a_tiny_time_budget_stops_refinement_incomplete() {
    let input = square_with_hole();
    let budget = Budget {
        max_time: Some(Duration::from_nanos(1)),
        ..Budget::default()
    };
    let params = Params::default()
        .with_min_angle(30.0)
        .with_max_area(1e-5)
        .with_budget(budget);
    let run = Cgal.mesh(&input, &params).unwrap();
    assert!(!run.complete);
    let reason = run
        .stop_reason
        .as_ref()
        .map(|r| r.to_string())
        .unwrap_or_default();
    assert!(reason.contains("time budget"), "{reason}");
    // What was built so far is still a valid mesh of the domain.
    assert_valid(&input, &run, 0.75);
}

#[test]
fn step_and_vertex_budgets_stop_refinement_where_they_say() {
    let input = square_with_hole();
    let params = Params::default().with_min_angle(30.0).with_max_area(1e-4);
    let steps = Budget {
        max_steps: Some(25),
        ..Budget::default()
    };
    let run = Cgal
        .mesh(&input, &params.clone().with_budget(steps))
        .unwrap();
    assert!(!run.complete);
    assert_eq!(run.steps, 25);
    assert!(run.stop_reason.unwrap().to_string().contains("step budget"));

    let vertices = Budget {
        max_vertices: Some(100),
        ..Budget::default()
    };
    let run = Cgal.mesh(&input, &params.with_budget(vertices)).unwrap();
    assert!(!run.complete);
    assert!(run.mesh.vertices.len() <= 100);
    assert_eq!(run.steps, 100 - 8);
    assert_valid(&input, &run, 0.75);

    let few = Budget {
        max_steps: Some(3),
        ..Budget::default()
    };
    let run = CgalConforming
        .mesh(&split_rectangle(), &Params::default().with_budget(few))
        .unwrap();
    assert!(!run.complete);
    assert_eq!(run.steps, 3);
    assert_valid(&split_rectangle(), &run, 20.0);
}

#[test]
fn both_meshers_are_registered() {
    for name in ["cgal", "cgal-conforming"] {
        let m = hexmesh::mesher(name).expect("registered");
        assert_eq!(m.name(), name);
        assert!(m.version().starts_with("CGAL 5.5"), "{}", m.version());
        assert!(m.supports_segments());
    }
    let s = Cgal.settings(&Params::default().with_min_angle(30.0).with_max_area(0.5));
    assert!(s.contains("sin²(30°)") && s.contains("sqrt(4A/√3)"), "{s}");
}
