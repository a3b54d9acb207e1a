//! Incremental insertion into a finished `hex-simple` mesh (paper 000 Sec. 1 and 9): added
//! points refine the hierarchy only around them, and the mesh keeps its bounds.

mod mesh_support;

use hexmesh::hex::IncrementalHexSimple;
use hexmesh::{Params, Point, Pslg};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

fn uniform(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..n)
        .map(|_| [rng.random::<f64>(), rng.random::<f64>()])
        .collect()
}

#[test]
fn added_points_become_vertices_and_the_simple_bounds_hold() {
    let first = uniform(200, 21);
    let mut inc = IncrementalHexSimple::new(&Pslg::from_points(first.clone()), &Params::default())
        .expect("meshes");
    // Points of the unit square lie inside the hexagon fitted to 200 points of it only if
    // they are not too close to its corners; keep the middle.
    let added: Vec<Point> = uniform(100, 22)
        .into_iter()
        .map(|p| [0.2 + 0.6 * p[0], 0.2 + 0.6 * p[1]])
        .collect();
    let ids = inc.insert(&added).expect("inserts");
    assert_eq!(ids, (200..300).collect::<Vec<u32>>());
    let all: Vec<Point> = first.iter().chain(&added).copied().collect();
    let mesh = inc.mesh();
    mesh_support::meets(&mesh, &all, "hex-simple").unwrap_or_else(|e| panic!("{e}"));
    inc.hierarchy().check_invariants().unwrap();
    inc.hierarchy().check_refined().unwrap();
    let bounds = hexmesh::registry::bounds("hex-simple").unwrap();
    let v = hexmesh::quality::verdict(&mesh, Some(&Pslg::from_points(all)), Some(&bounds));
    assert!(v.passed(), "{v}");
}

#[test]
fn one_added_point_refines_locally() {
    let first = uniform(2000, 23);
    let mut inc = IncrementalHexSimple::new(&Pslg::from_points(first.clone()), &Params::default())
        .expect("meshes");
    let before = inc.hierarchy().steps;
    // Close to an existing point, so that both must be separated by new, smaller hexagons.
    let p = first[1000];
    inc.insert(&[[p[0] + 1e-4, p[1] + 0.5e-4]])
        .expect("inserts");
    let added = inc.hierarchy().steps - before;
    assert!(added > 0, "the new point needed no hexagon split");
    assert!(
        added * 50 < before,
        "{added} splits for one point after {before} for 2000"
    );
}

#[test]
fn duplicates_and_points_outside_the_hexagon_are_refused() {
    let first = uniform(50, 24);
    let mut inc =
        IncrementalHexSimple::new(&Pslg::from_points(first.clone()), &Params::default()).unwrap();
    let err = inc.insert(&[first[7]]).unwrap_err();
    assert!(err.to_string().contains("duplicates point 7"), "{err}");
    assert!(inc.insert(&[[50.0, 50.0]]).is_err());
    assert!(inc.insert(&[[f64::NAN, 0.5]]).is_err());
    // The refused points left the mesh as it was.
    mesh_support::meets(&inc.mesh(), &first, "hex-simple").unwrap();
}
