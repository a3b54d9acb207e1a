//! `hex-simple` on the paper's datasets (DESIGN.md "Datasets"): a valid mesh, every input point
//! a vertex bit for bit, every angle in [30°, 120°] (paper 000 Sec. 4.3).

use hexmesh::hex::fuzz::check_mesh;
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
    let stats =
        check_mesh(&run.mesh, &input.points, Some((30.0, 120.0))).unwrap_or_else(|e| panic!("{e}"));
    assert!(stats.min_angle >= 30.0 - 1e-6 && stats.max_angle <= 120.0 + 1e-6);
    run
}

#[test]
fn close_pair_in_the_unit_hexagon_meets_the_simple_bounds() {
    let input = Pslg {
        points: vec![[-0.01, 0.0], [0.01, 0.0]],
        hexagon: Some(Hexagon {
            center: [0.0, 0.0],
            circumradius: 1.0,
        }),
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
