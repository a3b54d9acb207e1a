//! The refine meshers judged by the project's own checker (`quality::verdict` with the
//! bounds their `Mesher::promise` gives) on every dataset of the paper: `saalfeld` (both
//! variants) valid, conforming and Delaunay; `lsb` valid and conforming, every angle at least
//! half the smallest angle of its initial triangle (the bound that survives adaptive
//! refinement); and Theorem 3.4 itself, 2/3, on the family T(A, B, C) of every initial triangle.

use hexmesh::quality::verdict;
use hexmesh::quality::{descent, LSB_ADAPTIVE_RATIO, LSB_FAMILY_RATIO};
use hexmesh::refine::{family, lsb_descent_check, min_angle, Lsb, Saalfeld};
use hexmesh::Budget;
use hexmesh::{datasets, Mesher, Params};

/// Every dataset `hexmesh report` runs by default.
const DATASETS: &[&str] = hexmesh::datasets::SMALL;

#[test]
fn saalfeld_meshes_pass_the_saalfeld_bounds_on_the_datasets() {
    let bounds = hexmesh::registry::bounds("saalfeld").unwrap();
    for name in DATASETS {
        let input = datasets::by_name(name).unwrap();
        let r = Saalfeld::default()
            .refine(&input, &Params::default())
            .unwrap();
        assert!(r.run.complete, "{name}: {:?}", r.run.stop_reason);
        let v = verdict(&r.run.mesh, Some(&input), Some(&bounds));
        assert!(v.passed(), "{name}: {v:?}");
    }
}

#[test]
fn lsb_meshes_pass_the_lsb_bounds_and_keep_half_the_initial_angle() {
    let bounds = hexmesh::registry::bounds("lsb").unwrap();
    for name in DATASETS {
        let input = datasets::by_name(name).unwrap();
        for lsb in [Lsb { plain: false }, Lsb { plain: true }] {
            let r = lsb.refine(&input, &Params::default()).unwrap();
            assert!(r.run.complete, "{name}: {:?}", r.run.stop_reason);
            let v = verdict(&r.run.mesh, Some(&input), Some(&bounds));
            assert!(
                v.passed(),
                "{name} ({}): {v:?}",
                lsb.settings(&Params::default())
            );
            let smallest = |m: &hexmesh::TriMesh| {
                (0..m.triangles.len())
                    .map(|t| min_angle(m, t))
                    .fold(f64::INFINITY, f64::min)
            };
            assert!(smallest(&r.run.mesh) >= 0.5 * smallest(&r.initial) * (1.0 - 1e-12));
            assert!(
                r.min_descent_ratio >= 0.5 - 1e-9,
                "{name}: {}",
                r.min_descent_ratio
            );
        }
    }
}

#[test]
fn saalfeld_sec5_meshes_pass_the_saalfeld_bounds_or_stop_naming_the_point_count() {
    let sec5 = Saalfeld {
        constructive: true,
        ..Saalfeld::default()
    };
    let bounds = hexmesh::registry::bounds("saalfeld-sec5").unwrap();
    let mut complete = 0;
    for name in DATASETS {
        let input = datasets::by_name(name).unwrap();
        let r = sec5.refine(&input, &Params::default()).unwrap();
        if !r.run.complete {
            // line-100: two of its random points are 1e-5 apart, so δ asks for millions of
            // pieces on the hexagon's edges; the construction refuses instead of running out.
            let why = r.run.stop_reason;
            assert!(
                matches!(why, Some(hexmesh::StopReason::VertexLimit { .. })),
                "{name}: {why:?}"
            );
            continue;
        }
        complete += 1;
        let v = verdict(&r.run.mesh, Some(&input), Some(&bounds));
        assert!(v.passed(), "{name}: {v}");
        assert!(r.constructive_points > 0, "{name}");
    }
    assert!(complete >= DATASETS.len() - 1, "{complete} complete");
}

#[test]
fn theorem_3_4_holds_on_the_family_of_every_initial_triangle_of_every_dataset() {
    for name in DATASETS {
        let input = datasets::by_name(name).unwrap();
        let (initial, _) = Lsb::initial(&input).unwrap();
        let (soup, parents) = family(&initial, 4, false);
        let r = lsb_descent_check(&initial, &soup, &parents);
        assert!(r >= LSB_FAMILY_RATIO - 1e-9, "{name}: modified {r}");
        let (soup, parents) = family(&initial, 6, true);
        let r = lsb_descent_check(&initial, &soup, &parents);
        assert!(r >= LSB_ADAPTIVE_RATIO - 1e-9, "{name}: plain {r}");
    }
}

#[test]
fn conforming_uniform_refinement_of_every_dataset_keeps_half_the_angle_by_the_checker() {
    for name in DATASETS {
        let input = datasets::by_name(name).unwrap();
        let (initial, _) = Lsb::initial(&input).unwrap();
        for lsb in [Lsb { plain: false }, Lsb { plain: true }] {
            let r = lsb.refine_uniform(&initial, 3, Budget::default()).unwrap();
            assert!(r.run.complete, "{name}");
            let d = descent(&initial, &r.run.mesh, LSB_ADAPTIVE_RATIO);
            assert_eq!(d.first_unlocated, None, "{name}");
            let (margin, t) = d.min_margin.unwrap();
            assert!(margin >= -1e-6, "{name}: triangle {t} margin {margin}°");
            let (ratio, _) = d.min_ratio.unwrap();
            assert!((ratio - r.min_descent_ratio).abs() < 1e-9, "{name}");
        }
    }
}

#[test]
fn bad_input_is_an_error_not_a_panic_or_an_empty_mesh() {
    use hexmesh::Pslg;
    let open = Pslg {
        points: vec![[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]],
        segments: vec![[0, 1], [1, 2]],
        ..Pslg::default()
    };
    let missing = Pslg {
        points: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        segments: vec![[0, 1], [1, 7]],
        ..Pslg::default()
    };
    let nan = Pslg::from_points(vec![[0.0, 0.0], [f64::NAN, 1.0]]);
    let empty = Pslg::default();
    for input in [open, missing, nan, empty] {
        for m in [&Saalfeld::default() as &dyn Mesher, &Lsb::default()] {
            let e = m.mesh(&input, &Params::default());
            assert!(e.is_err(), "{} accepted {input:?}", m.name());
        }
    }
}
