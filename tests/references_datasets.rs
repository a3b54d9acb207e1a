//! Every reference mesher on every small dataset (issue 6): valid, every input point a vertex
//! bit-exactly, segments kept as chains of edges, and the minimum angle it was asked for;
//! cgal-conforming with zero exact Delaunay violations.

use hexmesh::quality::{verdict, Bounds};
use hexmesh::{datasets, mesher, Budget, Params};
use std::time::Duration;

/// Meshes `dataset` with `name` at `params` and checks the verdict of `bounds`.
fn check(name: &str, dataset: &str, params: &Params, bounds: &Bounds) {
    let input = datasets::by_name(dataset).expect("dataset");
    let run = mesher(name)
        .expect("registered")
        .mesh(&input, params)
        .unwrap_or_else(|e| panic!("{name} on {dataset}: {e}"));
    assert!(
        run.complete,
        "{name} on {dataset} stopped: {:?}",
        run.stop_reason
    );
    let v = verdict(&run.mesh, Some(&input), Some(bounds));
    assert!(v.passed(), "{name} on {dataset}:\n{v}");
}

fn budget() -> Budget {
    Budget {
        max_time: Some(Duration::from_secs(120)),
        ..Budget::default()
    }
}

#[test]
fn angle_refiners_meet_30_degrees_on_every_small_dataset() {
    let params = Params::default().with_min_angle(30.0).with_budget(budget());
    for name in ["cgal", "triangle", "spade"] {
        let bounds = hexmesh::registry::bounds(name)
            .and_then(|b| b.with_min_angle(30.0))
            .expect("bounds");
        for dataset in datasets::SMALL {
            check(name, dataset, &params, &bounds);
        }
    }
}

#[test]
fn cgal_conforming_is_exactly_delaunay_on_every_small_dataset() {
    let params = Params::default().with_budget(budget());
    let bounds = hexmesh::registry::bounds("cgal-conforming").expect("bounds");
    assert!(bounds.delaunay);
    for dataset in datasets::SMALL {
        check("cgal-conforming", dataset, &params, &bounds);
    }
}

#[test]
fn a_32_degree_request_is_met_where_all_three_terminate() {
    let params = Params::default().with_min_angle(32.0).with_budget(budget());
    for name in ["cgal", "triangle", "spade"] {
        let bounds = hexmesh::registry::bounds(name)
            .and_then(|b| b.with_min_angle(32.0))
            .expect("bounds");
        for dataset in ["close-pair", "plane-100", "imr"] {
            check(name, dataset, &params, &bounds);
        }
    }
}
