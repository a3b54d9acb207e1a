//! Incremental insertion into a finished `hex` mesh (paper 000 Sec. 1 and 9): added points
//! refine only around them, and the mesh keeps every Sec. 6 bound, like the mesh of all
//! points meshed at once.

mod mesh_support;

use hexmesh::hex::IncrementalHex;
use hexmesh::quality::verdict;
use hexmesh::{Params, Point, Pslg, TriMesh};
use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

fn uniform(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..n)
        .map(|_| [rng.random::<f64>(), rng.random::<f64>()])
        .collect()
}

/// Points of the unit square's middle, inside the hexagon fitted to any spread-out first set.
fn middle(points: Vec<Point>) -> Vec<Point> {
    points
        .into_iter()
        .map(|p| [0.3 + 0.4 * p[0], 0.3 + 0.4 * p[1]])
        .collect()
}

fn assert_hex_bounds(what: &str, mesh: &TriMesh, points: &[Point]) {
    mesh_support::inputs_first(mesh, points).unwrap_or_else(|e| panic!("{what}: {e}"));
    let bounds = hexmesh::registry::bounds("hex").unwrap();
    let v = verdict(
        mesh,
        Some(&Pslg::from_points(points.to_vec())),
        Some(&bounds),
    );
    assert!(v.passed(), "{what}: {v}");
}

/// A first set whose fitted hexagon holds the middle of the unit square: its four corners
/// and some uniform points.
fn first_set(n: usize, seed: u64) -> Vec<Point> {
    let mut v = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    v.extend(uniform(n, seed));
    v
}

#[test]
fn added_points_become_vertices_and_every_hex_bound_holds() {
    let first = first_set(60, 31);
    let mut inc =
        IncrementalHex::new(&Pslg::from_points(first.clone()), &Params::default()).expect("meshes");
    let added = middle(uniform(40, 32));
    let ids = inc.insert(&added).expect("inserts");
    assert_eq!(ids, (64..104).collect::<Vec<u32>>());
    let all: Vec<Point> = first.iter().chain(&added).copied().collect();
    let mesh = inc.mesh();
    for (i, p) in all.iter().enumerate() {
        assert_eq!(mesh.vertices[i], *p, "point {i} is vertex {i} bit-exactly");
    }
    assert_hex_bounds("incremental", &mesh, &all);
    inc.hierarchy().check_invariants().unwrap();
}

#[test]
fn one_added_point_is_checked_locally_not_over_the_whole_mesh() {
    let first = first_set(400, 33);
    let mut inc =
        IncrementalHex::new(&Pslg::from_points(first.clone()), &Params::default()).expect("meshes");
    let total = inc.mesh().triangles.len() as u64;
    let (steps, checked) = (inc.hierarchy().steps, inc.stats().checked_triangles);
    // Close to an existing point, so that both need new, smaller hexagons.
    let p = first[200];
    let q = [p[0] + 3e-4, p[1] + 1e-4];
    inc.insert(&[q]).expect("inserts");
    let splits = inc.hierarchy().steps - steps;
    let looked_at = inc.stats().checked_triangles - checked;
    assert!(splits > 0, "the new point needed no hexagon split");
    assert!(
        looked_at * 20 < total,
        "the self-check examined {looked_at} triangles of {total} for one point"
    );
    let all: Vec<Point> = first.iter().copied().chain([q]).collect();
    assert_hex_bounds("incremental", &inc.mesh(), &all);
}

#[test]
fn refused_points_leave_the_mesh_unchanged() {
    let first = first_set(30, 34);
    let mut inc =
        IncrementalHex::new(&Pslg::from_points(first.clone()), &Params::default()).expect("meshes");
    let before = inc.mesh();
    let good = [0.5, 0.5];
    for bad in [
        vec![good, first[7]],
        vec![good, [f64::NAN, 0.5]],
        vec![good, [1e6, 0.5]],
        vec![good, [0.4, 0.6], good],
    ] {
        let err = inc.insert(&bad).unwrap_err().to_string();
        assert!(err.contains("added point"), "{err}");
        assert_eq!(inc.mesh(), before, "{bad:?} changed the mesh");
    }
    inc.insert(&[good]).expect("a good point is still accepted");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Meshing some points and adding the rest keeps every bound, as meshing all at once does,
    /// with a triangle count of the same order.
    #[test]
    fn adding_points_keeps_every_bound_like_meshing_all_at_once(
        seed in 0u64..1_000_000,
        n_first in 1usize..30,
        n_added in 1usize..30,
    ) {
        let first = first_set(n_first, seed);
        let added = middle(uniform(n_added, seed ^ 0x9e37));
        let all: Vec<Point> = first.iter().chain(&added).copied().collect();
        let mut dedup = all.clone();
        dedup.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        dedup.dedup();
        prop_assume!(dedup.len() == all.len());

        let mut inc = IncrementalHex::new(&Pslg::from_points(first), &Params::default()).unwrap();
        inc.insert(&added).unwrap();
        let incremental = inc.mesh();
        assert_hex_bounds("incremental", &incremental, &all);

        let at_once = hexmesh::hex::extended::mesh_extended(
            &Pslg::from_points(all.clone()),
            &Params::default(),
        )
        .unwrap();
        assert_hex_bounds("all at once", &at_once.mesh, &all);
        let (a, b) = (incremental.triangles.len(), at_once.mesh.triangles.len());
        prop_assert!(a <= 3 * b && b <= 3 * a, "incremental {a} triangles, at once {b}");
    }
}
