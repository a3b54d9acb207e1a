//! The extended refinement (paper 000 Sec. 5, mesher `hex`): on the inputs it finishes
//! quickly, the Sec. 6 promises hold: angles in [43.8979°, 90°], radius ratio at
//! most 1.20787, no exact Delaunay violation, shortest edge at least √7/(12√3)·d_min.

mod mesh_support;

use hexmesh::geom::{dist, Point};
use hexmesh::hex::extended::{delaunay_violations, mesh_extended};
use hexmesh::{Hexagon, Params, Pslg, TriMesh};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

fn radius_ratio(t: [Point; 3]) -> f64 {
    let (a, b, c) = (dist(t[1], t[2]), dist(t[0], t[2]), dist(t[0], t[1]));
    let s = (a + b + c) / 2.0;
    let area = (s * (s - a) * (s - b) * (s - c)).max(0.0).sqrt();
    let circum = a * b * c / (4.0 * area);
    let inr = area / s;
    circum / (2.0 * inr)
}

fn assert_extended_bounds(input: &Pslg) -> TriMesh {
    let out = mesh_extended(input, &Params::default()).expect("meshes");
    assert!(out.stop.is_none());
    let mesh = out.mesh;
    mesh_support::inputs_first(&mesh, &input.points).unwrap_or_else(|e| panic!("{e}"));
    assert!(delaunay_violations(&mesh).is_empty());
    let bounds = hexmesh::registry::bounds("hex").unwrap();
    let v = hexmesh::quality::verdict(&mesh, Some(input), Some(&bounds));
    assert!(v.passed(), "{v}");
    let worst = (0..mesh.triangles.len())
        .map(|t| radius_ratio(mesh.corners(t)))
        .fold(0.0, f64::max);
    assert!(worst <= 1.20787 + 1e-9, "radius ratio {worst}");
    let mut d_min = f64::INFINITY;
    for i in 0..input.points.len() {
        for j in 0..i {
            d_min = d_min.min(dist(input.points[i], input.points[j]));
        }
    }
    let shortest = mesh
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |e| (t[e], t[(e + 1) % 3])))
        .map(|(a, b)| dist(mesh.vertices[a as usize], mesh.vertices[b as usize]))
        .fold(f64::INFINITY, f64::min);
    if d_min.is_finite() {
        let bound = 7f64.sqrt() / (12.0 * 3f64.sqrt()) * d_min;
        assert!(shortest >= bound, "shortest edge {shortest} < {bound}");
    }
    mesh
}

#[test]
fn close_pair_meets_the_extended_bounds() {
    let input = Pslg {
        points: vec![[-0.01, 0.0], [0.01, 0.0]],
        hexagon: Some(Hexagon::new([0.0, 0.0], 1.0)),
        ..Pslg::default()
    };
    let mesh = assert_extended_bounds(&input);
    assert!(mesh.triangles.len() > 300);
}

#[test]
fn a_single_point_meets_the_extended_bounds() {
    let mesh = assert_extended_bounds(&Pslg::from_points(vec![[0.3, 0.7]]));
    assert_eq!(mesh.triangles.len(), 6);
}

#[test]
fn ten_points_and_a_hundred_uniform_points_meet_the_extended_bounds() {
    let pts = (0..10)
        .map(|t| {
            let s = t as f64 * 0.618_033_988_749_895;
            [s.fract(), (s * 2.3).fract()]
        })
        .collect();
    assert_extended_bounds(&Pslg::from_points(pts));
    let mut rng = Pcg64::seed_from_u64(1);
    let pts = (0..100)
        .map(|_| [rng.random::<f64>(), rng.random::<f64>()])
        .collect();
    assert_extended_bounds(&Pslg::from_points(pts));
}

/// The point-set datasets of paper 000 Table 1 against every Sec. 6 bound, with the triangle counts
/// and times of paper 000 Table 1 for comparison (close-pair 684, line-100 18,667, plane-100
/// 12,748, plane-1k 127,729, plane-2k 268,138 triangles).
#[test]
#[ignore = "about 20 s in a test build (plane-1k, plane-2k)"]
fn datasets_meet_the_extended_bounds() {
    for name in [
        "close-pair",
        "line-100",
        "plane-100",
        "plane-1k",
        "plane-2k",
    ] {
        let input = hexmesh::datasets::by_name(name).expect("dataset");
        let t = std::time::Instant::now();
        let mesh = assert_extended_bounds(&input);
        eprintln!(
            "{name}: {} triangles in {:?}",
            mesh.triangles.len(),
            t.elapsed()
        );
    }
}

fn fixture(name: &str) -> Pslg {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/hex")
        .join(name);
    hexmesh::io::read_input(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Cases 42 and 128 were open (shortest edge 0.115 and 0.113 d_min) until the contested ring
/// cells were placed by local search; 121 needs the second pass, which moves ring neighbours.
#[test]
fn conflicting_rings_three_cells_apart_keep_the_shortest_edge_bound() {
    for case in [42, 105, 121, 128] {
        let input = fixture(&format!("hex-shortest-edge-fuzz-seed7-case{case}.node"));
        // Since MOVED_CENTER_3 hexagons keep their own dual, cases 42 and 105 have a few
        // self-check splits away from the rings (corridors of moved hexagons, `mc3` docs);
        // what must hold is the shortest edge with every other bound.
        assert_extended_bounds(&input);
    }
}

/// Two OCCUPIED_2 points far apart on the far sides of hexagons three cells apart (neither
/// role of the contested cells works, and a split would break Sec. 6.3), and lattice-aligned
/// points with contested cells: both meet every bound without a self-check split.
#[test]
fn contested_ring_cells_placed_by_local_search_meet_every_bound() {
    for name in [
        "hex-contested-ring-far-pair-fuzz-seed20261123-case875.node",
        "hex-contested-ring-lattice-fuzz-seed7-case1371.node",
    ] {
        let input = fixture(name);
        let out = mesh_extended(&input, &Params::default()).expect("meshes");
        assert_eq!(out.stats.verify_splits, 0, "{name}: {:?}", out.stats);
        assert!(out.stats.settled > 0, "{name}: {:?}", out.stats);
        assert_extended_bounds(&input);
    }
}

/// Two OCCUPIED_2 points three hexagons apart whose shared ring cells no single move of
/// `settle_contested` could place: the self-check subdivided a ring cell, below the r_min of
/// Sec. 6.3, and an edge fell to 0.124·d_min (case 22172, translated by 1e7) and 0.120·d_min
/// (case 70276, scaled by 1e-6; the point lies near the border of two corners' regions). The
/// finer search of `polish_rings` and the second-corner shift of `switch_corner` now repair
/// them in place: no self-check split, every bound.
#[test]
fn rings_of_points_three_apart_are_repaired_without_going_below_r_min() {
    for (name, polished) in [
        (
            "hex-short-edge-below-r-min-translated-fuzz-seed20261123-case22172.node",
            true,
        ),
        (
            "hex-second-corner-scaled-fuzz-seed20261123-case70276.node",
            false,
        ),
    ] {
        let input = fixture(name);
        let out = mesh_extended(&input, &Params::default()).expect("meshes");
        assert_eq!(out.stats.verify_splits, 0, "{name}: {:?}", out.stats);
        assert!(out.stats.corner_switches > 0, "{name}: {:?}", out.stats);
        assert_eq!(out.stats.polished > 0, polished, "{name}: {:?}", out.stats);
        assert_extended_bounds(&input);
    }
}

/// A set translated to 1e7 whose hexagons go below the level f64 guarantees: there the
/// self-check once subdivided 358 times for triangles that rounding spoiled, down to
/// 0.035·d_min. Now such a rejection is refused as too close for f64, and the local placement
/// leaves none here: the mesh meets every bound.
#[test]
fn a_translated_set_below_the_guaranteed_level_meets_every_bound() {
    let input = fixture("hex-deep-self-check-fuzz-seed20261123-case1321.node");
    assert_extended_bounds(&input);
}

#[test]
fn a_step_budget_stops_hex_early_with_an_incomplete_valid_mesh() {
    use hexmesh::mesher::Budget;
    use hexmesh::Mesher;
    let mut rng = Pcg64::seed_from_u64(3);
    let pts: Vec<Point> = (0..200)
        .map(|_| [rng.random::<f64>(), rng.random::<f64>()])
        .collect();
    let input = Pslg::from_points(pts);
    let params = Params::default().with_budget(Budget {
        max_steps: Some(50),
        ..Budget::default()
    });
    let run = hexmesh::hex::extended::Hex
        .mesh(&input, &params)
        .expect("a budget is not an error");
    assert!(!run.complete);
    assert!(matches!(
        run.stop_reason,
        Some(hexmesh::StopReason::Steps(_))
    ));
    assert!(run.steps <= 50);
    // A partial hierarchy may still hold several points per hexagon: only validity holds.
    mesh_support::meets(&run.mesh, &[], "valid").unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_time_budget_stops_hex_promptly() {
    use hexmesh::mesher::Budget;
    use hexmesh::Mesher;
    let input = hexmesh::datasets::by_name("plane-1k").expect("dataset");
    let params = Params::default().with_budget(Budget {
        max_time: Some(std::time::Duration::from_millis(20)),
        ..Budget::default()
    });
    let t = std::time::Instant::now();
    let run = hexmesh::hex::extended::Hex
        .mesh(&input, &params)
        .expect("a budget is not an error");
    assert!(!run.complete);
    assert!(matches!(
        run.stop_reason,
        Some(hexmesh::StopReason::Time(_))
    ));
    assert!(
        t.elapsed() < std::time::Duration::from_secs(2),
        "{:?}",
        t.elapsed()
    );
}

#[test]
fn a_deep_clustered_set_finishes_within_a_few_seconds_and_meets_every_bound() {
    use hexmesh::mesher::Budget;
    // Case 8 of fuzz seed 7 (clustered, 74 points, 21 levels): over ten seconds while the leaf
    // walk visited deep subtrees once per path to them.
    let input = hexmesh::fuzz::generate_family_case(7, 8, "clustered");
    let params = Params::default().with_budget(Budget {
        max_time: Some(std::time::Duration::from_secs(5)),
        ..Budget::default()
    });
    let out = mesh_extended(&input, &params).expect("meshes");
    assert!(out.stop.is_none(), "{:?}", out.stop);
    assert_extended_bounds(&input);
}

/// An OCCUPIED_2 point on its hexagon's edge, a quarter of the edge from its nearest corner,
/// is (3√3/4)·r ≈ 1.299·r from the moved ring cell across that edge (Sec. 5.4 shift), not the
/// (√7/2)·r ≈ 1.323·r Sec. 6.3 takes as the shortest edge. A grid whose points 5.14·r apart
/// were split to hexagons within 2% of r_min had a shortest edge of 0.1262·d_min; such pairs
/// are now split only up to 5.10·r apart.
#[test]
fn an_occupied_2_point_on_its_hexagon_edge_keeps_the_shortest_edge_bound() {
    assert_extended_bounds(&fixture(
        "hex-shortest-edge-grid-fuzz-seed20261123-case26.node",
    ));
}
