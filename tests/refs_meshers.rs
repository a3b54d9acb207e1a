//! The spade and Triangle reference meshers at 30° on a point set (meshed inside its fitted
//! bounding hexagon) and on a square with a square hole: input points come back first and
//! bit-exact, triangles are counter-clockwise, the smallest angle meets the request, and
//! nothing is left inside the hole. `quality::validate` must find nothing wrong, segments
//! conforming included.

use hexmesh::geom::orient2d;
use hexmesh::quality::{metrics, validate, ValidateOptions};
use hexmesh::reference::triangle::triangle_switches;
use hexmesh::{mesher, MeshRun, Params, Pslg};

/// 40 points of two Weyl sequences in the unit square: spread out, deterministic.
fn point_set() -> Pslg {
    let pts = (1..=40)
        .map(|i| {
            let i = f64::from(i);
            [
                (i * 0.618_033_988_749_895).fract(),
                (i * 0.414_213_562_373_095).fract(),
            ]
        })
        .collect();
    Pslg::from_points(pts)
}

fn square_with_hole() -> Pslg {
    Pslg {
        points: vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.4, 0.4],
            [0.6, 0.4],
            [0.6, 0.6],
            [0.4, 0.6],
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

fn assert_good_mesh(name: &str, input: &Pslg, run: &MeshRun, min_angle: f64) {
    assert!(run.complete, "{name}: {:?}", run.stop_reason);
    assert!(!run.mesh.triangles.is_empty(), "{name}: no triangles");
    for (i, p) in input.points.iter().enumerate() {
        let v = run.mesh.vertices[i];
        assert_eq!(
            (v[0].to_bits(), v[1].to_bits()),
            (p[0].to_bits(), p[1].to_bits()),
            "{name}: input point {i} is not vertex {i} bit-exactly"
        );
    }
    for t in 0..run.mesh.triangles.len() {
        let [a, b, c] = run.mesh.corners(t);
        assert!(orient2d(a, b, c) > 0.0, "{name}: triangle {t} is not CCW");
    }
    let options = ValidateOptions {
        single_component: !input.has_segments(),
        conforming: true,
    };
    let violations = validate(&run.mesh, Some(input), &options);
    assert!(violations.is_empty(), "{name}: {}", violations[0]);
    let got = metrics(&run.mesh, Some(input)).min_angle.unwrap().value;
    assert!(
        got >= min_angle - 1e-6,
        "{name}: smallest angle {got}° < {min_angle}°"
    );
}

#[test]
fn both_references_mesh_a_point_set_inside_its_hexagon_at_30_degrees() {
    let input = point_set();
    let hexagon_area = input.bounding_hexagon().area();
    for name in ["spade", "triangle"] {
        let m = mesher(name).unwrap();
        let run = m
            .mesh(&input, &Params::default().with_min_angle(30.0))
            .unwrap();
        assert_good_mesh(name, &input, &run, 30.0);
        let area = run.mesh.area();
        assert!(
            (area - hexagon_area).abs() < 1e-9 * hexagon_area,
            "{name}: area {area} != hexagon {hexagon_area}"
        );
    }
}

#[test]
fn both_references_mesh_a_square_with_a_hole_at_30_degrees_and_leave_the_hole_empty() {
    let input = square_with_hole();
    for name in ["spade", "triangle"] {
        let m = mesher(name).unwrap();
        let run = m
            .mesh(&input, &Params::default().with_min_angle(30.0))
            .unwrap();
        assert_good_mesh(name, &input, &run, 30.0);
        for t in 0..run.mesh.triangles.len() {
            let [a, b, c] = run.mesh.corners(t);
            let g = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
            let inside_hole = g[0] > 0.4 && g[0] < 0.6 && g[1] > 0.4 && g[1] < 0.6;
            assert!(!inside_hole, "{name}: triangle {t} lies in the hole");
        }
        let area = run.mesh.area();
        assert!((area - 0.96).abs() < 1e-9, "{name}: area {area} != 0.96");
    }
}

#[test]
fn max_area_is_honoured_by_both_references() {
    let input = square_with_hole();
    for name in ["spade", "triangle"] {
        let m = mesher(name).unwrap();
        let params = Params::default().with_min_angle(25.0).with_max_area(0.01);
        let run = m.mesh(&input, &params).unwrap();
        assert_good_mesh(name, &input, &run, 25.0);
        for t in 0..run.mesh.triangles.len() {
            let [a, b, c] = run.mesh.corners(t);
            let area = 0.5 * orient2d(a, b, c);
            assert!(
                area <= 0.01 * (1.0 + 1e-9),
                "{name}: triangle {t} area {area}"
            );
        }
    }
}

#[test]
fn triangle_settings_spell_the_switches_sent() {
    let params = Params::default().with_min_angle(30.0);
    assert_eq!(triangle_switches(&params).unwrap(), "pzAQaq30");
    let settings = mesher("triangle").unwrap().settings(&params);
    assert_eq!(settings, "triangulate(\"pzAQaq30\")");
    let bare = mesher("triangle").unwrap().settings(&Params::default());
    assert!(
        bare.contains("\"pzAQaq\"") && bare.contains("20°"),
        "{bare}"
    );
    let user = mesher("triangle")
        .unwrap()
        .settings(&Params::default().with_switches("q25D"));
    assert_eq!(user, "triangulate(\"pzAQaq25D\")");
}

#[test]
fn spade_settings_spell_the_ratio_limit_and_the_vertex_budget() {
    let s = mesher("spade")
        .unwrap()
        .settings(&Params::default().with_min_angle(30.0));
    assert!(s.contains("from_deg(30)") && s.contains("1.000000"), "{s}");
    assert!(s.contains("max(10*initial vertices, 1000000)"), "{s}");
}

#[test]
fn spade_reports_an_exhausted_vertex_budget_as_incomplete() {
    let mut params = Params::default().with_min_angle(30.0);
    params.budget.max_steps = Some(3);
    let run = mesher("spade")
        .unwrap()
        .mesh(&point_set(), &params)
        .unwrap();
    assert!(!run.complete);
    assert_eq!(run.stop_reason, Some(hexmesh::StopReason::Steps(3)));
    assert_eq!(run.steps, 3);
}

#[test]
fn bad_input_is_an_error_not_a_crash() {
    let dup = Pslg::from_points(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]]);
    assert!(mesher("triangle")
        .unwrap()
        .mesh(&dup, &Params::default())
        .is_err());
    let p = Params::default().with_min_angle(61.0);
    assert!(mesher("spade").unwrap().mesh(&point_set(), &p).is_err());
    assert!(mesher("triangle").unwrap().mesh(&point_set(), &p).is_err());
}

#[test]
fn the_close_pair_and_collinear_points_mesh_at_30_degrees() {
    // As the close-pair dataset: the bounding hexagon is the given unit hexagon, not fitted.
    let close_pair = Pslg {
        points: vec![[-0.01, 0.0], [0.01, 0.0]],
        hexagon: Some(hexmesh::Hexagon::new([0.0, 0.0], 1.0)),
        ..Pslg::default()
    };
    let line = Pslg::from_points(
        (0..100)
            .map(|i| {
                let t = (f64::from(i) * 0.618_033_988_749_895).fract();
                [t, 0.37 * t]
            })
            .collect(),
    );
    for input in [close_pair, line] {
        let area = input.bounding_hexagon().area();
        for name in ["spade", "triangle"] {
            let run = mesher(name)
                .unwrap()
                .mesh(&input, &Params::default().with_min_angle(30.0))
                .unwrap();
            assert_good_mesh(name, &input, &run, 30.0);
            assert!((run.mesh.area() - area).abs() < 1e-9 * area, "{name}");
        }
    }
}

/// Found by the issue 3/6 audit: at 1e-80 and 1e80 CGAL returned 6.6° for 30° as complete,
/// and Triangle 2.3° for 25° at 1e-100 (fourth powers of lengths leave f64). Such domains are
/// now refused before the mesher runs; 1e-60 and 1e60 still mesh to the request.
#[test]
fn cgal_and_triangle_refuse_scales_whose_fourth_powers_leave_f64() {
    let scaled = |s: f64| {
        let mut p = point_set();
        for q in &mut p.points {
            *q = [q[0] * s, q[1] * s];
        }
        p
    };
    let names: &[&str] = if cfg!(feature = "cgal") {
        &["triangle", "cgal", "cgal-conforming"]
    } else {
        &["triangle"]
    };
    let params = Params::default().with_min_angle(30.0);
    for &name in names {
        let m = mesher(name).unwrap();
        for s in [1e-80, 1e80, 1e-100] {
            match m.mesh(&scaled(s), &params) {
                Err(hexmesh::Error::Input {
                    problem: hexmesh::InputError::Range { detail },
                    ..
                }) => assert!(detail.contains("scale the input"), "{name} {s}: {detail}"),
                other => panic!("{name} at {s}: expected a range error, got {other:?}"),
            }
        }
        for s in [1e-60, 1e60] {
            let input = scaled(s);
            let run = m.mesh(&input, &params).unwrap();
            if name != "cgal-conforming" {
                assert_good_mesh(name, &input, &run, 30.0);
            }
        }
    }
}
