//! Modified longest-side bisection (paper 003): Theorem 3.4's bound under uniform refinement
//! (every angle ≥ 2/3 of the smallest angle of the initial triangle it descends from; ≥ 1/2
//! for plain bisection), conformity (Rivara propagation), the adaptive heap targets, budgets.

mod refine_support;

use hexmesh::refine::{family, lsb_descent_check, Lsb, LsbRun, Target};
use hexmesh::{Budget, Mesher, Params, Pslg, TriMesh};
use proptest::prelude::*;
use refine_support::*;

const MODIFIED: Lsb = Lsb { plain: false };
const PLAIN: Lsb = Lsb { plain: true };

/// Angle ratios are computed in f64 from rounded midpoints.
const RATIO_TOL: f64 = 1e-9;

fn triangle(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> TriMesh {
    TriMesh {
        vertices: vec![a, b, c],
        triangles: vec![[0, 1, 2]],
    }
}

/// Valid, conforming (every interior edge shared by exactly two triangles: no hanging
/// vertex), covering the initial area, with a parent for every triangle.
fn assert_conforming_refinement(r: &LsbRun) {
    let mesh = &r.run.mesh;
    validate(mesh).unwrap();
    assert_eq!(r.parents.len(), mesh.triangles.len());
    let a0 = r.initial.area();
    assert!(
        (mesh.area() - a0).abs() <= 1e-9 * a0,
        "area {} != {a0}",
        mesh.area()
    );
    // No hanging vertex: a vertex lying inside a boundary edge of the union would make the
    // boundary longer than the initial one.
    let boundary = |m: &TriMesh| {
        let dir: std::collections::HashSet<(u32, u32)> = m
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
            .collect();
        dir.iter()
            .filter(|(a, b)| !dir.contains(&(*b, *a)))
            .map(|&(a, b)| hexmesh::geom::dist(m.vertices[a as usize], m.vertices[b as usize]))
            .sum::<f64>()
    };
    let (b0, b1) = (boundary(&r.initial), boundary(mesh));
    assert!(
        (b0 - b1).abs() <= 1e-9 * b0,
        "boundary length {b1} != {b0}: hanging vertices"
    );
    // Every triangle lies in the initial triangle it names (its centroid does).
    for (t, &p) in r.parents.iter().enumerate() {
        let c = mesh.corners(t);
        let g = [
            (c[0][0] + c[1][0] + c[2][0]) / 3.0,
            (c[0][1] + c[1][1] + c[2][1]) / 3.0,
        ];
        let [a, b, d] = r.initial.corners(p as usize);
        let o = hexmesh::geom::orient2d;
        assert!(
            o(a, b, g) > 0.0 && o(b, d, g) > 0.0 && o(d, a, g) > 0.0,
            "triangle {t} outside its parent"
        );
    }
}

#[test]
fn equilateral_triangle_is_split_into_similar_quarters() {
    let h = 3f64.sqrt() / 2.0;
    let m = triangle([0.0, 0.0], [1.0, 0.0], [0.5, h]);
    let r = MODIFIED.refine_uniform(&m, 4, Budget::default()).unwrap();
    assert_conforming_refinement(&r);
    assert_eq!(r.run.mesh.triangles.len(), 4usize.pow(4));
    assert!(
        (r.min_descent_ratio - 1.0).abs() < 1e-9,
        "ratio {}",
        r.min_descent_ratio
    );
    assert_eq!(r.quaternary_splits, 1 + 4 + 16 + 64);
}

#[test]
fn plain_bisection_of_the_equilateral_triangle_halves_the_angle() {
    // Plain bisection of an equilateral triangle makes 30° angles at once: the 1/2 bound is tight.
    let h = 3f64.sqrt() / 2.0;
    let m = triangle([0.0, 0.0], [1.0, 0.0], [0.5, h]);
    let r = PLAIN.refine_uniform(&m, 6, Budget::default()).unwrap();
    assert_conforming_refinement(&r);
    assert_eq!(r.quaternary_splits, 0);
    assert!(
        (r.min_descent_ratio - 0.5).abs() < 1e-9,
        "ratio {}",
        r.min_descent_ratio
    );
}

#[test]
fn descent_check_reports_the_ratio_to_the_parent_triangle() {
    let init = triangle([0.0, 0.0], [2.0, 0.0], [0.0, 2.0]); // 45° smallest
    let refined = TriMesh {
        vertices: vec![[0.0, 0.0], [2.0, 0.0], [0.0, 2.0], [1.0, 1.0]],
        triangles: vec![[0, 1, 3], [0, 3, 2]],
    };
    // Bisection of the right isosceles triangle gives two right isosceles ones: ratio 1.
    assert!((lsb_descent_check(&init, &refined, &[0, 0]) - 1.0).abs() < 1e-12);
    assert!(lsb_descent_check(&init, &refined, &[0, 7]).is_nan());
}

#[test]
fn adaptive_refinement_meets_the_edge_target_and_keeps_half_the_angle() {
    let (initial, segs) = Lsb::initial(&Pslg::from_points(random_points(40, 9))).unwrap();
    for lsb in [MODIFIED, PLAIN] {
        let r = lsb
            .refine_to(&initial, &segs, Target::MaxEdge(0.05), Budget::default())
            .unwrap();
        assert!(r.run.complete);
        assert_conforming_refinement(&r);
        for e in edges(&r.run.mesh) {
            let d = hexmesh::geom::dist(
                r.run.mesh.vertices[e.0 as usize],
                r.run.mesh.vertices[e.1 as usize],
            );
            assert!(d <= 0.05, "edge of length {d}");
        }
        assert!(
            r.min_descent_ratio >= 0.5 - RATIO_TOL,
            "ratio {}",
            r.min_descent_ratio
        );
    }
}

#[test]
fn adaptive_refinement_meets_the_area_target() {
    let input = square_with_hole();
    let params = Params::default().with_max_area(0.001);
    let r = MODIFIED.refine(&input, &params).unwrap();
    assert!(r.run.complete);
    assert_conforming_refinement(&r);
    let m = &r.run.mesh;
    assert!((0..m.triangles.len()).all(|t| m.corners(t).len() == 3));
    let max_area = (0..m.triangles.len())
        .map(|t| {
            let [a, b, c] = m.corners(t);
            0.5 * hexmesh::geom::orient2d(a, b, c)
        })
        .fold(0.0, f64::max);
    assert!(max_area <= 0.001, "max area {max_area}");
    assert!((m.area() - 0.96).abs() < 1e-9, "the hole is removed");
}

#[test]
fn rule_4_1_completes_quaternary_splits_during_adaptive_refinement() {
    let (initial, segs) = Lsb::initial(&Pslg::from_points(random_points(30, 2))).unwrap();
    let r = MODIFIED
        .refine_to(&initial, &segs, Target::MaxEdge(0.02), Budget::default())
        .unwrap();
    assert!(r.quaternary_splits > 0);
    let p = PLAIN
        .refine_to(&initial, &segs, Target::MaxEdge(0.02), Budget::default())
        .unwrap();
    assert_eq!(p.quaternary_splits, 0);
}

#[test]
fn segments_stay_chains_of_mesh_edges() {
    for input in [square_with_hole(), polygon_with_slit()] {
        let r = MODIFIED.refine(&input, &Params::default()).unwrap();
        assert!(r.run.complete);
        assert_conforming_refinement(&r);
        assert_eq!(r.chains.len(), input.segments.len());
        for (chain, s) in r.chains.iter().zip(&input.segments) {
            let (a, b) = (input.points[s[0] as usize], input.points[s[1] as usize]);
            check_chain(&r.run.mesh, chain, a, b, 1e-12).unwrap();
            assert!(chain.len() > 2, "long segments are bisected");
        }
        for &p in &input.points {
            assert!(vertex_of(&r.run.mesh, p).is_some());
        }
    }
}

#[test]
fn point_sets_are_refined_in_their_bounding_hexagon_to_a_twentieth_of_the_diagonal() {
    let input = Pslg::from_points(random_points(50, 4));
    let r = MODIFIED.refine(&input, &Params::default()).unwrap();
    assert!(r.run.complete);
    assert_conforming_refinement(&r);
    let hex = input.bounding_hexagon();
    assert!((r.run.mesh.area() - hex.area()).abs() < 1e-9 * hex.area());
    let Some(Target::MaxEdge(l)) = r.target else {
        panic!("default target is an edge length")
    };
    // The hexagon's bounding box: width 2R, height √3 R.
    let rr = hex.circumradius;
    let diag = ((2.0 * rr).powi(2) + (3f64.sqrt() * rr).powi(2)).sqrt();
    assert!((l - diag / 20.0).abs() < 1e-12 * diag);
    assert!(MODIFIED
        .settings(&Params::default())
        .contains("diagonal / 20"));
}

#[test]
fn budgets_stop_refinement_with_complete_false() {
    let input = Pslg::from_points(random_points(20, 1));
    for budget in [
        Budget {
            max_steps: Some(10),
            ..Budget::default()
        },
        Budget {
            max_vertices: Some(60),
            ..Budget::default()
        },
        Budget {
            max_time: Some(std::time::Duration::ZERO),
            ..Budget::default()
        },
    ] {
        let params = Params::default().with_budget(budget).with_max_area(1e-6);
        let r = MODIFIED.refine(&input, &params).unwrap();
        assert!(!r.run.complete);
        assert!(r.run.stop_reason.is_some());
        validate(&r.run.mesh).unwrap();
        if let Some(max) = budget.max_vertices {
            assert!(r.run.mesh.vertices.len() <= max);
        }
        if let Some(max) = budget.max_steps {
            assert!(r.run.steps <= max);
        }
    }
}

#[test]
fn a_non_positive_max_area_is_a_usage_error() {
    let input = Pslg::from_points(random_points(5, 1));
    assert!(MODIFIED
        .refine(&input, &Params::default().with_max_area(0.0))
        .is_err());
    assert!(MODIFIED
        .refine(&input, &Params::default().with_max_area(f64::NAN))
        .is_err());
}

#[test]
fn registered_under_its_name() {
    let m = hexmesh::mesher("lsb").unwrap();
    assert!(m.supports_segments());
    assert!(
        m.mesh(&polygon_with_slit(), &Params::default())
            .unwrap()
            .complete
    );
}

/// `verify --bounds lsb` on the run's mesh passes, and the checker's own ancestor search
/// (centroid location in the initial triangulation) agrees with the mesher's bookkeeping.
fn assert_lsb_verdict(input: &Pslg, r: &LsbRun) {
    let bounds = hexmesh::registry::bounds("lsb").unwrap();
    let v = hexmesh::quality::verdict(&r.run.mesh, Some(input), Some(&bounds));
    assert!(v.passed(), "{v}");
    let d = hexmesh::quality::descent(&r.initial, &r.run.mesh, 0.5);
    let located: Vec<u32> = d.parents.iter().map(|p| p.expect("located")).collect();
    assert_eq!(
        located, r.parents,
        "ancestors differ from the mesher's bookkeeping"
    );
    let (ratio, _) = d.min_ratio.unwrap();
    assert!(
        (ratio - r.min_descent_ratio).abs() <= 1e-9,
        "{ratio} vs {}",
        r.min_descent_ratio
    );
}

#[test]
fn tiny_input_angles_keep_half_of_them_and_conform() {
    for deg in [1.0, 1e-2, 1e-4, 1e-6] {
        let input = fan(4, deg);
        for lsb in [MODIFIED, PLAIN] {
            let r = lsb.refine(&input, &Params::default()).unwrap();
            assert!(r.run.complete, "{deg}: {:?}", r.run.stop_reason);
            assert_conforming_refinement(&r);
            assert_lsb_verdict(&input, &r);
        }
    }
}

#[test]
fn collinear_points_and_segments_keep_half_the_angle_and_conform() {
    let input = collinear_pslg(20);
    for lsb in [MODIFIED, PLAIN] {
        let r = lsb.refine(&input, &Params::default()).unwrap();
        assert!(r.run.complete);
        assert_conforming_refinement(&r);
        assert_lsb_verdict(&input, &r);
        for (chain, s) in r.chains.iter().zip(&input.segments) {
            let (a, b) = (input.points[s[0] as usize], input.points[s[1] as usize]);
            check_chain(&r.run.mesh, chain, a, b, 1e-12).unwrap();
        }
    }
}

#[test]
fn verify_fails_a_mesh_with_a_sliver_cut_into_a_fat_initial_triangle() {
    // The initial triangulation of this equilateral triangle is itself; a point just above
    // its base makes 2.3° angles, far below half of 60°.
    let h = 3f64.sqrt() / 2.0;
    let mut input = Pslg::default();
    add_loop(&mut input, &[[0.0, 0.0], [1.0, 0.0], [0.5, h]]);
    let mesh = TriMesh {
        vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.5, h], [0.5, 0.02]],
        triangles: vec![[0, 1, 3], [1, 2, 3], [2, 0, 3]],
    };
    let bounds = hexmesh::registry::bounds("lsb").unwrap();
    let v = hexmesh::quality::verdict(&mesh, Some(&input), Some(&bounds));
    assert!(!v.passed(), "{v}");
    let failed: Vec<&str> = v
        .checks
        .iter()
        .filter(|c| c.status == hexmesh::quality::Status::Fail)
        .map(|c| c.what.as_str())
        .collect();
    assert_eq!(failed, ["smallest angle / ancestor's (lsb descent)"]);
}

/// Random non-degenerate triangles with smallest angle at least `min_deg` degrees.
fn random_triangle(min_deg: f64) -> impl Strategy<Value = TriMesh> {
    (
        -1.0f64..1.0,
        -1.0f64..1.0,
        -1.0f64..1.0,
        -1.0f64..1.0,
        -1.0f64..1.0,
        -1.0f64..1.0,
    )
        .prop_filter_map("too thin", move |(ax, ay, bx, by, cx, cy)| {
            let (a, mut b, mut c) = ([ax, ay], [bx, by], [cx, cy]);
            if hexmesh::geom::orient2d(a, b, c) < 0.0 {
                std::mem::swap(&mut b, &mut c);
            }
            let m = triangle(a, b, c);
            (hexmesh::geom::orient2d(a, b, c) > 0.0
                && hexmesh::refine::min_angle(&m, 0) >= min_deg.to_radians())
            .then_some(m)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn theorem_3_4_the_family_of_a_triangle_keeps_two_thirds_of_its_smallest_angle(m in random_triangle(1.0), levels in 4u32..9) {
        let (soup, parents) = family(&m, levels, false);
        let r = lsb_descent_check(&m, &soup, &parents);
        prop_assert!(r >= 2.0 / 3.0 - RATIO_TOL, "ratio {}", r);
    }

    #[test]
    fn plain_bisection_family_keeps_half_the_smallest_angle(m in random_triangle(1.0), levels in 4u32..12) {
        let (soup, parents) = family(&m, levels, true);
        let r = lsb_descent_check(&m, &soup, &parents);
        prop_assert!(r >= 0.5 - RATIO_TOL, "ratio {}", r);
    }

    #[test]
    fn theorem_3_4_holds_for_every_triangle_of_a_triangulation(seed in 0u64..10_000, n in 1usize..25, levels in 3u32..7) {
        let (initial, _) = Lsb::initial(&Pslg::from_points(random_points(n, seed))).unwrap();
        let (soup, parents) = family(&initial, levels, false);
        let r = lsb_descent_check(&initial, &soup, &parents);
        prop_assert!(r >= 2.0 / 3.0 - RATIO_TOL, "ratio {}", r);
        let (soup, parents) = family(&initial, levels, true);
        let p = lsb_descent_check(&initial, &soup, &parents);
        prop_assert!(p >= 0.5 - RATIO_TOL, "ratio {}", p);
    }

    #[test]
    fn conforming_uniform_refinement_of_a_triangle_keeps_half_the_smallest_angle(m in random_triangle(3.0), levels in 3u32..7) {
        for lsb in [MODIFIED, PLAIN] {
            let r = lsb.refine_uniform(&m, levels, Budget::default()).unwrap();
            prop_assert!(r.run.complete);
            assert_conforming_refinement(&r);
            prop_assert!(r.min_descent_ratio >= 0.5 - RATIO_TOL, "ratio {}", r.min_descent_ratio);
        }
    }

    #[test]
    fn adaptive_refinement_of_random_pslgs_keeps_half_the_angle_and_conforms(
        seed in 0u64..1_000_000, n in 2usize..30, hole in any::<bool>(), plain in any::<bool>()
    ) {
        let input = random_pslg(seed, n, 3 * n, hole);
        let lsb = Lsb { plain };
        let r = lsb.refine(&input, &Params::default()).unwrap();
        prop_assert!(r.run.complete);
        assert_conforming_refinement(&r);
        assert_lsb_verdict(&input, &r);
        for (chain, s) in r.chains.iter().zip(&input.segments) {
            let (a, b) = (input.points[s[0] as usize], input.points[s[1] as usize]);
            check_chain(&r.run.mesh, chain, a, b, 1e-12).unwrap();
        }
    }

    #[test]
    fn conforming_uniform_refinement_of_a_triangulation_keeps_half_the_smallest_angle(seed in 0u64..10_000, n in 1usize..25, levels in 2u32..5) {
        let (initial, _) = Lsb::initial(&Pslg::from_points(random_points(n, seed))).unwrap();
        for lsb in [MODIFIED, PLAIN] {
            let r = lsb.refine_uniform(&initial, levels, Budget::default()).unwrap();
            prop_assert!(r.run.complete);
            assert_conforming_refinement(&r);
            prop_assert!(r.min_descent_ratio >= 0.5 - RATIO_TOL, "ratio {}", r.min_descent_ratio);
        }
    }
}
