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

/// The same pair moved to x = 100: 2e-10 edges at coordinates 100 leave angles 2e-3° out of
/// bounds after rounding; the mesher refuses with the reason instead of returning them.
#[test]
fn vertical_pair_far_from_the_origin_is_refused_for_f64_rounding() {
    let input = Pslg::from_points(vec![[100.0, 1.0], [100.0, -1.0]]);
    let err = Rhomb.mesh(&input, &Params::default()).unwrap_err();
    assert!(err.to_string().contains("f64 rounding"), "{err}");
}

/// A proptest find: two points 1e-6 apart alone at x ≈ 0.85. The fitted hexagon is 1e-6 wide
/// and its edge passes 1e-9 from a point, so the needed triangles are below f64 resolution.
#[test]
fn lone_near_duplicate_pair_is_refused_for_f64_rounding() {
    let a: f64 = 1.633_424_765_072_893_5;
    let input = Pslg::from_points(vec![
        [0.849_768_232_370_818_4, 0.0],
        [0.849_768_232_370_818_4 + 1e-6 * a.cos(), 1e-6 * a.sin()],
    ]);
    let err = Rhomb.mesh(&input, &Params::default()).unwrap_err();
    assert!(err.to_string().contains("f64 rounding"), "{err}");
}
