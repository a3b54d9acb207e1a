//! Property tests of `hex-simple` (paper 000 Sec. 4.3: every angle in [30°, 120°]) on the point
//! set families that stress it: uniform, clustered, collinear, near-duplicates, extreme scales,
//! far translations, and points exactly on hexagon centres, edges and corners. Every case
//! yields a valid mesh with every input point a vertex, or, only when the points are closer
//! than f64 can resolve at their coordinates, a clear `InputError::Range`.

mod mesh_support;

use hexmesh::fuzz::unit_hexagon;
use hexmesh::hex::lattice::{Key, Lattice};
use hexmesh::hex::{mesh_with_hierarchy, HexSimple};
use hexmesh::{Error, InputError, Mesher, Params, Point, Pslg};
use proptest::prelude::*;

fn dedup(mut pts: Vec<Point>) -> Vec<Point> {
    let mut seen: Vec<Point> = Vec::new();
    pts.retain(|p| {
        let k = [p[0] + 0.0, p[1] + 0.0];
        let new = !seen.contains(&k);
        seen.push(k);
        new
    });
    pts
}

fn d_min(pts: &[Point]) -> f64 {
    let mut best = f64::INFINITY;
    for i in 0..pts.len() {
        for j in 0..i {
            best = best.min(hexmesh::geom::dist(pts[i], pts[j]));
        }
    }
    best
}

/// Meshes and checks; a Range refusal is accepted only when the closest pair is closer than
/// `refusable` times the coordinate magnitude.
fn check(input: Pslg, refusable: f64) -> Result<(), TestCaseError> {
    match HexSimple.mesh(&input, &Params::default()) {
        Ok(run) => {
            prop_assert!(run.complete);
            mesh_support::inputs_first(&run.mesh, &input.points).map_err(TestCaseError::fail)?;
            let bounds = hexmesh::registry::bounds("hex-simple").expect("known bounds");
            let v = hexmesh::quality::verdict(&run.mesh, Some(&input), Some(&bounds));
            prop_assert!(v.passed(), "{}", v);
        }
        Err(Error::Input {
            problem: InputError::Range { detail },
            ..
        }) => {
            let hex = input.bounding_hexagon();
            let scale = hex.center[0].abs().max(hex.center[1].abs()) + hex.circumradius;
            prop_assert!(
                d_min(&input.points) < refusable * scale,
                "refused points {} apart at scale {scale}: {detail}",
                d_min(&input.points)
            );
        }
        Err(e) => return Err(TestCaseError::fail(e.to_string())),
    }
    Ok(())
}

fn unit_points(max: usize) -> impl Strategy<Value = Vec<Point>> {
    prop::collection::vec((0.0..1.0f64, 0.0..1.0f64).prop_map(|(x, y)| [x, y]), 1..max)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, ..ProptestConfig::default() })]

    #[test]
    fn uniform_sets_meet_the_simple_bounds(pts in unit_points(120)) {
        check(Pslg::from_points(dedup(pts)), 1e-5)?;
    }

    #[test]
    fn clustered_sets_meet_the_simple_bounds(
        centres in unit_points(4),
        offsets in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 1..80),
        spread_exp in 1.0..5.0f64,
    ) {
        let spread = 10f64.powf(-spread_exp);
        let pts = offsets.iter().enumerate().map(|(t, &(dx, dy))| {
            let c = centres[t % centres.len()];
            [c[0] + spread * dx, c[1] + spread * dy]
        }).collect();
        check(Pslg::from_points(dedup(pts)), 1e-5)?;
    }

    #[test]
    fn collinear_sets_meet_the_simple_bounds(
        a in (0.0..1.0f64, 0.0..1.0f64),
        dir in (-1.0..1.0f64, -1.0..1.0f64),
        ts in prop::collection::vec(0.0..1.0f64, 1..100),
        exact in any::<bool>(),
    ) {
        let pts = ts.iter().enumerate().map(|(n, &t)| {
            if exact { [n as f64, 0.37 * n as f64] } else { [a.0 + t * dir.0, a.1 + t * dir.1] }
        }).collect();
        check(Pslg::from_points(dedup(pts)), 1e-5)?;
    }

    #[test]
    fn near_duplicates_meet_the_simple_bounds_or_are_refused_as_too_close(
        base in unit_points(30),
        gap_exp in 2.0..9.0f64,
        angle in 0.0..std::f64::consts::TAU,
    ) {
        let gap = 10f64.powf(-gap_exp);
        let mut pts = Vec::new();
        for p in base {
            pts.push(p);
            pts.push([p[0] + gap * angle.cos(), p[1] + gap * angle.sin()]);
        }
        // Refusal is allowed below the documented precision floor (about 1e-6 here).
        check(Pslg::from_points(dedup(pts)), 2e-6)?;
    }

    #[test]
    fn scaled_sets_meet_the_simple_bounds(pts in unit_points(60), exp in -6.0..6.0f64) {
        let s = 10f64.powf(exp);
        let pts = pts.iter().map(|p| [p[0] * s, p[1] * s]).collect();
        check(Pslg::from_points(dedup(pts)), 1e-5)?;
    }

    #[test]
    fn sets_translated_by_1e7_meet_the_simple_bounds(pts in unit_points(60), exp in 2.0..6.0f64) {
        let s = 10f64.powf(exp);
        let pts = pts.iter().map(|p| [1e7 + p[0] * s, 1e7 + p[1] * s]).collect();
        check(Pslg::from_points(dedup(pts)), 1e-5)?;
    }

    #[test]
    fn points_on_hexagon_centres_edges_and_corners_meet_the_simple_bounds(
        picks in prop::collection::vec((1u8..=7, -128i64..=128, -128i64..=128, 0usize..3, 0usize..6), 1..60),
    ) {
        let lat = Lattice::new(unit_hexagon());
        let root = unit_hexagon();
        let pts: Vec<Point> = picks.iter().filter_map(|&(k, i, j, what, m)| {
            let span = 1i64 << k;
            let key = Key::new(k, i.rem_euclid(2 * span + 1) - span, j.rem_euclid(2 * span + 1) - span);
            let p = match what {
                0 => lat.center(key),
                1 => lat.corner(key, m),
                _ => lat.center(key.edge_child(m)),
            };
            root.contains_strictly(p).then_some(p)
        }).collect();
        let pts = dedup(pts);
        prop_assume!(!pts.is_empty());
        let input = Pslg { points: pts, hexagon: Some(root), ..Pslg::default() };
        let (h, stop) = mesh_with_hierarchy(&input, &Params::default())
            .map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert!(stop.is_none());
        h.check_invariants().map_err(TestCaseError::fail)?;
        h.check_refined().map_err(TestCaseError::fail)?;
        check(input, 0.0)?;
    }
}
