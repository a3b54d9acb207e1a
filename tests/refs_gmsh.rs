//! The `gmsh` reference (Debian's gmsh program, which `make deps` installs): on the paper's
//! small datasets and on every PSLG example, the mesh it gives back keeps its promise (valid,
//! conforming to the segments, every input point a vertex, first and in order, bit for bit),
//! the same mesh on every run, and a time budget stops it.

mod mesh_support;

use std::time::Duration;

use hexmesh::mesher::{Budget, StopReason};
use hexmesh::quality::verdict;
use hexmesh::reference::GmshMesher;
use hexmesh::{datasets, Mesher, Params, Pslg};

/// The gmsh program is there (CI runs `make deps` first); without it these tests cannot
/// say anything, and they fail rather than pass empty.
fn gmsh() -> GmshMesher {
    let version = GmshMesher.version();
    assert!(
        !version.contains("unavailable"),
        "{version}: run `make deps` to install Debian's gmsh"
    );
    GmshMesher
}

fn keeps_its_promise(name: &str, input: &Pslg) -> usize {
    let m = gmsh();
    let params = Params::default();
    let run = m
        .mesh(input, &params)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(run.complete, "{name}: {:?}", run.stop_reason);
    mesh_support::inputs_first(&run.mesh, &input.points).unwrap_or_else(|e| panic!("{name}: {e}"));
    let promise = m.promise(&params);
    assert!(promise.conforming, "gmsh promises a conforming mesh");
    let v = verdict(&run.mesh, Some(input), Some(&promise));
    assert!(v.passed(), "{name}:\n{v}");
    let again = m.mesh(input, &params).expect("second run");
    assert_eq!(
        again.mesh, run.mesh,
        "{name}: a second run gave another mesh"
    );
    run.mesh.triangles.len()
}

#[test]
fn gmsh_meshes_of_the_small_datasets_are_valid_keep_the_points_and_repeat() {
    for name in ["close-pair", "line-100", "plane-100", "plane-1k", "imr"] {
        let input = datasets::by_name(name).expect(name);
        let triangles = keeps_its_promise(name, &input);
        assert!(triangles > 0, "{name}");
    }
}

#[test]
fn gmsh_meshes_of_every_pslg_example_conform_to_its_segments() {
    for name in datasets::PSLG_EXAMPLES {
        let input = datasets::by_name(name).expect(name);
        keeps_its_promise(name, &input);
    }
}

#[test]
fn a_smaller_area_asks_gmsh_for_smaller_triangles() {
    let input = datasets::by_name("pslg-holes").expect("pslg-holes");
    let m = gmsh();
    let coarse = m.mesh(&input, &Params::default()).expect("coarse");
    let fine = m
        .mesh(&input, &Params::default().with_max_area(1e-3))
        .expect("fine");
    // Sizes are Gmsh's targets, not bounds: the request shows in the count, not per triangle.
    assert!(
        fine.mesh.triangles.len() > 4 * coarse.mesh.triangles.len(),
        "{} vs {}",
        fine.mesh.triangles.len(),
        coarse.mesh.triangles.len()
    );
    assert!(m
        .settings(&Params::default().with_max_area(1e-3))
        .contains("area 0.001"));
}

#[test]
fn a_time_budget_stops_gmsh_with_the_time_as_the_reason() {
    let input = datasets::by_name("plane-10k").expect("plane-10k");
    let limit = Duration::from_millis(1);
    let params = Params::default().with_budget(Budget {
        max_time: Some(limit),
        ..Budget::default()
    });
    let run = gmsh()
        .mesh(&input, &params)
        .expect("a stop is not an error");
    assert!(!run.complete);
    assert_eq!(run.stop_reason, Some(StopReason::Time(limit)));
}
