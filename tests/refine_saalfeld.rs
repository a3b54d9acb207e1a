//! Saalfeld's conforming Delaunay refinement (paper 002): on point sets in their bounding
//! hexagon and on PSLGs, the output is valid, has zero exact Delaunay violations, keeps every
//! input point bit-exactly and every input segment as a chain of mesh edges along it.

mod refine_support;

use hexmesh::refine::{ConformingRun, Saalfeld};
use hexmesh::{Budget, Mesher, Params, Pslg, StopReason};
use proptest::prelude::*;
use refine_support::*;

/// How far (relative to the coordinates' magnitude) a constructed chain vertex may lie from
/// its segment: a few rounding errors per round.
const CHAIN_TOL: f64 = 1e-12;

fn run(input: &Pslg, constructive: bool) -> ConformingRun {
    input.check().expect("test input is valid");
    let s = Saalfeld {
        constructive,
        ..Saalfeld::default()
    };
    s.refine(input, &Params::default()).expect("saalfeld runs")
}

/// Everything `saalfeld` promises, asserted on one run.
fn assert_conforming_delaunay(input: &Pslg, r: &ConformingRun, expected_area: Option<f64>) {
    assert!(r.run.complete, "stopped: {:?}", r.run.stop_reason);
    let mesh = &r.run.mesh;
    validate(mesh).unwrap();
    assert_eq!(delaunay_violations(mesh), 0, "exact Delaunay violations");
    for &p in &input.points {
        assert!(
            vertex_of(mesh, p).is_some(),
            "input point {p:?} is not a vertex"
        );
    }
    assert_eq!(r.chains.len(), r.domain.segments.len());
    for (chain, s) in r.chains.iter().zip(&r.domain.segments) {
        let (a, b) = (
            r.domain.points[s[0] as usize],
            r.domain.points[s[1] as usize],
        );
        check_chain(mesh, chain, a, b, CHAIN_TOL).unwrap();
    }
    assert_eq!(
        r.added_points,
        mesh.vertices.len() - r.domain.points.len(),
        "added points are the vertices beyond the domain's"
    );
    assert_eq!(r.run.steps, r.added_points as u64);
    if let Some(area) = expected_area {
        assert!(
            (mesh.area() - area).abs() < 1e-9 * area,
            "area {} != {area}",
            mesh.area()
        );
    }
}

#[test]
fn point_set_is_meshed_in_its_bounding_hexagon_as_a_conforming_delaunay_triangulation() {
    let input = Pslg::from_points(random_points(300, 7));
    let r = run(&input, false);
    let hex = input.bounding_hexagon();
    assert_conforming_delaunay(&input, &r, Some(hex.area()));
    assert_eq!(r.domain.segments.len(), 6);
}

#[test]
fn close_pair_in_the_unit_hexagon_conforms() {
    let mut input = Pslg::from_points(vec![[-0.01, 0.0], [0.01, 0.0]]);
    input.hexagon = Some(hexmesh::Hexagon::new([0.0, 0.0], 1.0));
    let r = run(&input, false);
    assert_conforming_delaunay(&input, &r, Some(input.bounding_hexagon().area()));
}

#[test]
fn collinear_points_conform_in_their_hexagon() {
    let pts: Vec<_> = random_points(100, 3)
        .into_iter()
        .map(|p| [p[0], 0.37 * p[0]])
        .collect();
    let input = Pslg::from_points(pts);
    let r = run(&input, false);
    assert_conforming_delaunay(&input, &r, Some(input.bounding_hexagon().area()));
}

#[test]
fn square_with_hole_removes_the_hole_and_conforms() {
    let input = square_with_hole();
    let r = run(&input, false);
    assert_conforming_delaunay(&input, &r, Some(1.0 - 0.04));
}

#[test]
fn square_with_hole_and_inner_points_adds_crossing_points() {
    let mut input = square_with_hole();
    // Points near the boundary make the segments cross Delaunay edges.
    input
        .points
        .extend(random_points(60, 11).into_iter().map(|p| {
            let q = [0.02 + 0.96 * p[0], 0.02 + 0.96 * p[1]];
            if (0.38..0.62).contains(&q[0]) && (0.38..0.62).contains(&q[1]) {
                [q[0] * 0.3, q[1]]
            } else {
                q
            }
        }));
    let r = run(&input, false);
    assert!(
        r.added_points > 0,
        "these segments are not Delaunay edges at first"
    );
    assert_conforming_delaunay(&input, &r, Some(1.0 - 0.04));
}

#[test]
fn polygon_with_interior_slit_keeps_the_slit_as_a_chain() {
    let input = polygon_with_slit();
    let r = run(&input, false);
    assert_conforming_delaunay(&input, &r, Some(1.0));
    let slit = r.chains.last().unwrap();
    assert!(slit.len() >= 2);
}

#[test]
fn constructive_option_conforms_and_is_counted_apart() {
    for input in [square_with_hole(), polygon_with_slit()] {
        let r = run(&input, true);
        let area = if input.holes.is_empty() { 1.0 } else { 0.96 };
        assert_conforming_delaunay(&input, &r, Some(area));
        assert!(r.constructive_points >= 2 * input.segments.len());
        assert!(r.constructive_points <= r.added_points);
    }
}

#[test]
fn iterative_adds_fewer_points_than_constructive_on_a_square_with_hole() {
    let it = run(&square_with_hole(), false);
    let co = run(&square_with_hole(), true);
    assert!(
        it.added_points < co.added_points,
        "{} vs {}",
        it.added_points,
        co.added_points
    );
}

#[test]
fn constructive_refuses_a_piece_count_beyond_the_vertex_budget() {
    let s = Saalfeld {
        constructive: true,
        ..Saalfeld::default()
    };
    let params = Params::default().with_budget(Budget {
        max_vertices: Some(20),
        ..Budget::default()
    });
    let r = s.refine(&square_with_hole(), &params).unwrap();
    assert!(!r.run.complete);
    assert!(
        matches!(
            r.run.stop_reason,
            Some(StopReason::VertexLimit { needed, limit: 20 }) if needed > 20
        ),
        "{:?}",
        r.run.stop_reason
    );
}

#[test]
fn a_round_budget_stops_early_and_says_so() {
    let mut input = square_with_hole();
    input.points.extend(
        random_points(200, 5)
            .into_iter()
            .filter(|p| !((0.38..0.62).contains(&p[0]) && (0.38..0.62).contains(&p[1]))),
    );
    let s = Saalfeld {
        constructive: false,
        max_rounds: 0,
    };
    let r = s.refine(&input, &Params::default()).unwrap();
    assert!(!r.run.complete);
    assert_eq!(r.run.stop_reason, Some(StopReason::Rounds(0)));
}

#[test]
fn registered_under_its_name_and_supports_segments() {
    let m = hexmesh::mesher("saalfeld").unwrap();
    assert!(m.supports_segments());
    let run = m.mesh(&square_with_hole(), &Params::default()).unwrap();
    assert!(run.complete);
    assert!(Saalfeld::default()
        .settings(&Params::default())
        .contains("Sec. 6"));
}

/// Even-odd test, with points near the boundary counted as outside.
fn strictly_inside(poly: &[[f64; 2]], q: [f64; 2]) -> bool {
    let n = poly.len();
    let near = (0..n).any(|i| {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let len = hexmesh::geom::dist(a, b);
        hexmesh::geom::orient2d(a, b, q).abs() / len < 1e-6
            && (q[0] - a[0]) * (b[0] - a[0]) + (q[1] - a[1]) * (b[1] - a[1]) >= -1e-6
            && (q[0] - b[0]) * (a[0] - b[0]) + (q[1] - b[1]) * (a[1] - b[1]) >= -1e-6
    });
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a[1] > q[1]) != (b[1] > q[1])
            && q[0] < a[0] + (q[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
        {
            inside = !inside;
        }
    }
    inside && !near
}

/// A star-shaped simple polygon: sorted angles, random radii.
fn star_polygon() -> impl Strategy<Value = Pslg> {
    (5usize..40)
        .prop_flat_map(|n| {
            (
                proptest::collection::vec(0.0f64..1.0, n),
                proptest::collection::vec(0.2f64..1.0, n),
                proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 0..120),
            )
        })
        .prop_filter_map("degenerate polygon", |(mut ang, rad, inner)| {
            ang.sort_by(f64::total_cmp);
            ang.dedup_by(|a, b| (*a - *b).abs() < 1e-3);
            if ang.len() < 3 {
                return None;
            }
            let pts: Vec<_> = ang
                .iter()
                .zip(&rad)
                .map(|(&a, &r)| {
                    let t = a * std::f64::consts::TAU;
                    [r * t.cos(), r * t.sin()]
                })
                .collect();
            let mut p = Pslg::default();
            add_loop(&mut p, &pts);
            // Interior points only: those outside the domain are not meshed.
            p.points.extend(
                inner
                    .into_iter()
                    .map(|(x, y)| [x, y])
                    .filter(|&q| strictly_inside(&pts, q)),
            );
            p.check().ok().map(|_| p)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn random_simple_polygons_get_conforming_delaunay_meshes(input in star_polygon()) {
        let outline: Vec<_> = input.points[..input.segments.len()].to_vec();
        let area = polygon_area(&outline);
        prop_assume!(area > 1e-3);
        let r = run(&input, false);
        assert_conforming_delaunay(&input, &r, Some(area));
    }

    #[test]
    fn random_point_sets_get_conforming_delaunay_meshes(seed in 0u64..1000, n in 1usize..200) {
        let input = Pslg::from_points(random_points(n, seed));
        let r = run(&input, false);
        assert_conforming_delaunay(&input, &r, Some(input.bounding_hexagon().area()));
    }

}

/// Everything `verify --bounds saalfeld` checks, from the project's own checker.
fn assert_verdict_passes(input: &Pslg, mesh: &hexmesh::TriMesh) {
    let bounds = hexmesh::registry::bounds("saalfeld").unwrap();
    let v = hexmesh::quality::verdict(mesh, Some(input), Some(&bounds));
    assert!(v.passed(), "{v}");
}

#[test]
fn tiny_input_angles_down_to_1e_7_degrees_conform() {
    for k in [2, 3, 4] {
        for deg in [1.0, 1e-2, 1e-4, 1e-6, 1e-7] {
            let input = fan(k, deg);
            let r = run(&input, false);
            assert_conforming_delaunay(&input, &r, Some(4.0));
            assert_verdict_passes(&input, &r.run.mesh);
        }
    }
}

#[test]
fn a_sliver_between_segments_exhausts_the_round_budget() {
    // Found by the random-PSLG proptest (seed 632494, 24 points, with the hole): segments
    // 30-26 and 26-5 meet at 0.0007°, and 5-30 closes a sliver of them. Each round adds
    // about three crossing points along the sliver, so conformity needs tens of thousands of
    // rounds; the default budget of 1000 stops the run with its reason, and the mesh built so
    // far is still a valid Delaunay triangulation.
    let input = random_pslg(632494, 24, 72, true);
    assert!(smallest_segment_angle(&input) < 0.001);
    let r = Saalfeld::default()
        .refine(&input, &Params::default())
        .unwrap();
    assert!(!r.run.complete);
    assert_eq!(r.run.stop_reason, Some(StopReason::Rounds(1000)));
    assert!(r.added_points > 1000, "{} points added", r.added_points);
    validate(&r.run.mesh).unwrap();
    assert_eq!(delaunay_violations(&r.run.mesh), 0);
}

#[test]
fn a_crossing_below_f64_resolution_stops_with_a_reason_not_a_wrong_mesh() {
    // Four segments 1e-8° apart: a Delaunay edge between two endpoints crosses the segment
    // between them about 1e-20 from its end, which rounds onto the end itself.
    let input = fan(4, 1e-8);
    let r = Saalfeld::default()
        .refine(&input, &Params::default())
        .unwrap();
    assert!(!r.run.complete);
    assert!(
        matches!(r.run.stop_reason, Some(StopReason::Stalled(_))),
        "{:?}",
        r.run.stop_reason
    );
    let err = hexmesh::mesher("saalfeld")
        .unwrap()
        .mesh(&input, &Params::default())
        .map(|run| run.complete);
    assert_eq!(err.ok(), Some(false), "the mesher reports the stop");
}

#[test]
fn collinear_points_and_segments_on_one_line_conform() {
    let input = collinear_pslg(20);
    let r = run(&input, false);
    assert_conforming_delaunay(&input, &r, Some(1.0));
    assert_verdict_passes(&input, &r.run.mesh);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn random_pslgs_with_dangling_segments_and_holes_get_conforming_delaunay_meshes(
        seed in 0u64..1_000_000, n in 2usize..40, hole in any::<bool>()
    ) {
        let input = random_pslg(seed, n, 3 * n, hole);
        let area = if hole { 1.0 - 0.04 } else { 1.0 };
        input.check().expect("test input is valid");
        let r = Saalfeld::default().refine(&input, &Params::default()).unwrap();
        if !r.run.complete && smallest_feature(&input) < 1e-3 {
            // Near a feature that small (two segments meeting at under 0.06°, or a point
            // closer to a segment than 1/1000 of its length) the iteration adds a point or
            // two per round (`a_sliver_between_segments_exhausts_the_round_budget`): about 1
            // random PSLG in 1000 here needs more than the default 1000 rounds. The stop must
            // say so, and what was built is still a valid Delaunay triangulation.
            let why = r.run.stop_reason.clone();
            prop_assert!(matches!(why, Some(StopReason::Rounds(_))), "{:?}", why);
            validate(&r.run.mesh).unwrap();
            prop_assert_eq!(delaunay_violations(&r.run.mesh), 0);
        } else {
            assert_conforming_delaunay(&input, &r, Some(area));
            assert_verdict_passes(&input, &r.run.mesh);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn random_simple_polygons_conform_under_the_constructive_option(input in star_polygon()) {
        let outline: Vec<_> = input.points[..input.segments.len()].to_vec();
        let area = polygon_area(&outline);
        prop_assume!(area > 1e-3);
        let s = Saalfeld { constructive: true, ..Saalfeld::default() };
        let params = Params::default().with_budget(Budget { max_vertices: Some(50_000), ..Budget::default() });
        let r = s.refine(&input, &params).unwrap();
        // Tiny features can ask for more pieces than the budget or the construction's cap: that
        // is reported as a stop naming the piece count, never a silently partial mesh.
        if !r.run.complete {
            let why = r.run.stop_reason.clone();
            prop_assert!(
                matches!(why, Some(StopReason::VertexLimit { .. })),
                "an incomplete run must say it ran out of pieces: {:?}", why
            );
        }
        prop_assume!(r.run.complete);
        assert_conforming_delaunay(&input, &r, Some(area));
        prop_assert!(r.constructive_points >= 2 * input.segments.len());
    }
}
