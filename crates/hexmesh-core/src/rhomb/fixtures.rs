//! Inputs that found problems, named after what they showed (see mod.rs `rounding_check`).

use super::Rhomb;
use crate::mesh::Pslg;
use crate::mesher::{Mesher, Params};

/// (0, ±1): the fitted hexagon's top and bottom edges pass a relative 1e-9 from the points, so
/// the mesh needs edges of 2e-10; at the origin rounding stays within the slack.
#[test]
fn vertical_pair_touching_the_fitted_hexagon_meshes_at_the_origin() {
    let input = Pslg::from_points(vec![[0.0, 1.0], [0.0, -1.0]]);
    let run = Rhomb.mesh(&input, &Params::default()).unwrap();
    assert!(run.complete);
}

/// The same pair moved to x = 100: 2e-10 edges at coordinates 100 left angles about 2e-3°
/// out of bounds after rounding. The fitted hexagon's least margin (`geom::FIT_MARGIN`, 2^-34
/// of the coordinates: 5.9e-9 here) now keeps its edges farther, and rounding moves the angles
/// by 3e-5°. Within the rounding allowance (README "Checks") and below the default
/// `--max-rounding` of 0.01°, the mesh is given and passes `verify`; asked for at most 1e-5°,
/// the mesher refuses, naming the two points.
#[test]
fn vertical_pair_far_from_the_origin_meshes_within_its_rounding_allowance() {
    let input = Pslg::from_points(vec![[100.0, 1.0], [100.0, -1.0]]);
    within_allowance_or_refused(&input, 1e-5);
}

/// Meshes `input` under the default allowance, checks it, and sees it refused at `strict`°.
fn within_allowance_or_refused(input: &Pslg, strict: f64) {
    let run = Rhomb.mesh(input, &Params::default()).unwrap();
    let bounds = Rhomb.promise(&Params::default());
    let v = crate::quality::verdict(&run.mesh, Some(input), Some(&bounds));
    assert!(v.passed(), "{v}");
    let used = v
        .checks
        .iter()
        .filter_map(|c| c.rounding)
        .map(|r| r.used)
        .fold(0.0, f64::max);
    assert!(used > strict && used <= 0.01, "{used}");
    let err = Rhomb
        .mesh(input, &Params::default().with_max_rounding(strict))
        .unwrap_err();
    assert!(
        matches!(
            err,
            crate::Error::Input {
                problem: crate::InputError::Rounding {
                    first: 0,
                    second: 1,
                    ..
                },
                ..
            }
        ),
        "{err}"
    );
}

/// A proptest find: two points 1e-6 apart alone at x ≈ 0.85. The fitted hexagon is 1e-6 wide
/// and its edge passed a relative 1e-9 of it (5e-16, under an ulp) from a point, so rounding
/// moved the needed triangles' angles by more than 1e-6°; with the least margin of
/// `geom::FIT_MARGIN` (4.9e-11) by 6e-7°, still more than the floor and less than the
/// allowance and the default 0.01°, and asked for at most 1e-7° the mesher refuses.
#[test]
fn lone_near_duplicate_pair_meshes_within_its_rounding_allowance() {
    let a: f64 = 1.633_424_765_072_893_5;
    let input = Pslg::from_points(vec![
        [0.849_768_232_370_818_4, 0.0],
        [0.849_768_232_370_818_4 + 1e-6 * a.cos(), 1e-6 * a.sin()],
    ]);
    within_allowance_or_refused(&input, 1e-7);
}

/// Fuzz family "lattice" (seed 20261123, case 26): a corner of a level-5 hexagon on the unit
/// hexagon's edge, which rounding puts 7e-18 inside it. It was refused (no patch fits between
/// the point and the edge, and the tree reached its deepest level); it is the lattice's own
/// boundary vertex (u + v = 3 at level 5) bit for bit, and is meshed as that vertex
/// (`Frame::boundary_vertex`, `centring::Kind::Vertex`): the mesh is the lattice's, every angle
/// within its rounding allowance.
#[test]
fn a_point_rounding_left_just_inside_the_hexagon_edge_is_meshed_as_its_boundary_vertex() {
    let hex = crate::geom::Hexagon::new([0.0, 0.0], 1.0);
    let input = Pslg {
        points: vec![
            [-0.1875, 0.108_253_175_473_054_82],
            [0.71875, 0.487_139_289_628_746_7],
        ],
        hexagon: Some(hex),
        ..Pslg::default()
    };
    // On the edge from corner 0 to corner 1 up to rounding, but strictly inside in f64.
    let c = hex.corners();
    assert!(crate::geom::orient2d(c[0], c[1], input.points[1]) > 0.0);
    assert!(crate::geom::orient2d(c[0], c[1], input.points[1]) < 1e-16);
    let run = Rhomb.mesh(&input, &Params::default()).unwrap();
    assert!(run.complete);
    let bounds = Rhomb.promise(&Params::default());
    let v = crate::quality::verdict(&run.mesh, Some(&input), Some(&bounds));
    assert!(v.passed(), "{v}");
    assert!((run.mesh.area() - hex.area()).abs() < 1e-12);
    // Vertex 1 is the point, used by the triangles along the edge, and no lattice vertex
    // duplicates it.
    let p = input.points[1];
    assert_eq!(run.mesh.vertices[1], p);
    assert_eq!(run.mesh.vertices.iter().filter(|&&q| q == p).count(), 1);
    assert!(run.mesh.triangles.iter().any(|t| t.contains(&1)));
}
