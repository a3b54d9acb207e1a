//! `hex-simple` on the paper's datasets (`hexmesh::datasets`): a valid mesh, every input point
//! a vertex bit for bit, every angle in [30°, 120°] (paper 000 Sec. 4.3).

mod mesh_support;

use hexmesh::hex::HexSimple;
use hexmesh::{Hexagon, Mesher, Params, Point, Pslg};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

fn uniform(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..n)
        .map(|_| [rng.random::<f64>(), rng.random::<f64>()])
        .collect()
}

fn assert_simple_bounds(input: &Pslg) -> hexmesh::MeshRun {
    let run = HexSimple.mesh(input, &Params::default()).expect("meshes");
    assert!(run.complete);
    mesh_support::inputs_first(&run.mesh, &input.points).unwrap_or_else(|e| panic!("{e}"));
    let bounds = hexmesh::registry::bounds("hex-simple").unwrap();
    let v = hexmesh::quality::verdict(&run.mesh, Some(input), Some(&bounds));
    assert!(v.passed(), "{v}");
    run
}

#[test]
fn close_pair_in_the_unit_hexagon_meets_the_simple_bounds() {
    let input = Pslg {
        points: vec![[-0.01, 0.0], [0.01, 0.0]],
        hexagon: Some(Hexagon::new([0.0, 0.0], 1.0)),
        ..Pslg::default()
    };
    let run = assert_simple_bounds(&input);
    assert!(run.mesh.triangles.len() > 50);
}

#[test]
fn hundred_points_on_a_line_meet_the_simple_bounds() {
    let mut rng = Pcg64::seed_from_u64(7);
    let pts = (0..100)
        .map(|_| {
            let t = rng.random::<f64>();
            [t, 0.37 * t]
        })
        .collect();
    assert_simple_bounds(&Pslg::from_points(pts));
}

#[test]
fn uniform_plane_sets_meet_the_simple_bounds() {
    for (n, seed) in [(100, 1), (1000, 2), (2000, 3)] {
        assert_simple_bounds(&Pslg::from_points(uniform(n, seed)));
    }
}

#[test]
fn a_single_point_gives_a_ring_of_triangles() {
    let run = assert_simple_bounds(&Pslg::from_points(vec![[3.0, 4.0]]));
    assert!(run.mesh.triangles.len() >= 6);
}

#[test]
fn a_step_budget_stops_early_with_a_valid_plain_mesh() {
    let input = Pslg::from_points(uniform(500, 9));
    let budget = hexmesh::Budget {
        max_steps: Some(40),
        ..hexmesh::Budget::default()
    };
    let run = HexSimple
        .mesh(&input, &Params::default().with_budget(budget))
        .expect("a budget is not an error");
    assert!(!run.complete);
    assert_eq!(run.stop_reason, Some(hexmesh::StopReason::Steps(40)));
    assert!(run.steps <= 40);
    // Not every input point is a vertex yet, so check the mesh without the point mapping.
    mesh_support::meets(&run.mesh, &[], "hex-simple").unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_vertex_budget_stops_early() {
    let input = Pslg::from_points(uniform(500, 10));
    let budget = hexmesh::Budget {
        max_vertices: Some(300),
        ..hexmesh::Budget::default()
    };
    let run = HexSimple
        .mesh(&input, &Params::default().with_budget(budget))
        .expect("a budget is not an error");
    assert!(!run.complete);
    assert!(run.mesh.vertices.len() < 1000);
}

#[test]
fn segments_points_outside_the_hexagon_and_unresolvable_pairs_are_refused() {
    let seg = Pslg {
        points: vec![[0.0, 0.0], [1.0, 0.0]],
        segments: vec![[0, 1]],
        ..Pslg::default()
    };
    assert!(matches!(
        HexSimple.mesh(&seg, &Params::default()),
        Err(hexmesh::Error::Mesher { .. })
    ));
    let outside = Pslg {
        points: vec![[0.0, 0.0], [2.0, 0.0]],
        hexagon: Some(Hexagon::new([0.0, 0.0], 1.0)),
        ..Pslg::default()
    };
    let err = HexSimple.mesh(&outside, &Params::default()).unwrap_err();
    assert!(err.to_string().contains("point 1"), "{err}");
    // 1e-14 apart at 0.5: a mesh would use far more than the default 0.01° of rounding.
    let close = Pslg::from_points(vec![[0.5, 0.5], [0.5 + 1e-14, 0.5], [0.0, 0.0]]);
    assert!(matches!(
        HexSimple.mesh(&close, &Params::default()),
        Err(hexmesh::Error::Input {
            problem: hexmesh::InputError::Rounding {
                first: 0,
                second: 1,
                ..
            },
            ..
        })
    ));
    let nan = Pslg::from_points(vec![[f64::NAN, 0.0]]);
    assert!(HexSimple.mesh(&nan, &Params::default()).is_err());
}

#[test]
fn the_same_input_gives_the_same_mesh_bit_for_bit() {
    let input = Pslg::from_points(uniform(300, 11));
    let a = HexSimple.mesh(&input, &Params::default()).unwrap().mesh;
    let b = HexSimple.mesh(&input, &Params::default()).unwrap().mesh;
    assert_eq!(a, b);
}

#[test]
fn the_hexagon_picture_draws_cells_the_dual_and_the_points() {
    let input = Pslg {
        points: vec![[-0.01, 0.0], [0.01, 0.0]],
        hexagon: Some(Hexagon::new([0.0, 0.0], 1.0)),
        ..Pslg::default()
    };
    let dir = std::env::temp_dir().join(format!("hexmesh-picture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("close-pair.svg");
    hexmesh::hex::write_hexagons_svg(&input, &Params::default(), &path).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    let run = HexSimple.mesh(&input, &Params::default()).unwrap();
    assert!(svg.starts_with("<svg"));
    assert!(svg.contains("#f7b267"), "occupied hexagons are drawn");
    assert!(svg.contains("#cfe3f7"), "semi-hexagons are drawn");
    assert_eq!(svg.matches("<circle").count(), 2);
    // One polygon per triangle in the dual group, plus the cells and the root outline.
    assert!(svg.matches("<polygon").count() > run.mesh.triangles.len());
}

/// Two points 2e-7 apart in the unit hexagon, which the old worst-case precision level (a
/// fixed 1e-6° for every angle) refused in the hierarchy alone: under the rounding allowance
/// the hierarchy refines them and the mesher meshes them within the bounds (plane-1m needs
/// this).
#[test]
fn a_pair_below_the_old_worst_case_precision_level_is_meshed() {
    let input = Pslg {
        points: vec![[-1e-7, 0.0], [1e-7, 0.0]],
        hexagon: Some(Hexagon::new([0.0, 0.0], 1.0)),
        ..Pslg::default()
    };
    let (h, stop) =
        hexmesh::hex::mesh_with_hierarchy(&input, &Params::default()).expect("hierarchy");
    assert!(stop.is_none());
    assert!(h.deepest() > 22, "{}", h.deepest());
    assert_simple_bounds(&input);
}
