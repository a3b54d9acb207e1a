//! The refine meshers judged by the project's own checker (`quality::verdict` with the
//! bounds DESIGN.md gives them) on the paper's datasets: `saalfeld` valid, conforming and
//! Delaunay; `lsb` valid and conforming, with its smallest angle not below half the initial
//! triangulation's (the plain-bisection bound that survives adaptive refinement).

use hexmesh::quality::{verdict, Bounds};
use hexmesh::refine::{min_angle, Lsb, Saalfeld};
use hexmesh::{datasets, Mesher, Params};

const DATASETS: &[&str] = &["close-pair", "line-100", "plane-100", "plane-1k", "imr"];

#[test]
fn saalfeld_meshes_pass_the_saalfeld_bounds_on_the_datasets() {
    let bounds = Bounds::parse("saalfeld").unwrap();
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
    let bounds = Bounds::parse("lsb").unwrap();
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
