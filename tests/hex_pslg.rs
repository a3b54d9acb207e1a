//! Planar straight-line graphs for mesher `hex` (paper 000 Sec. 7, src/hex/pslg.rs): every
//! PSLG meshes valid and conforming, the region the segments bound is covered, and the
//! triangles away from the segments keep the Sec. 6 bounds [43.8979°, 90°] with no exact
//! empty-circle violation.

use hexmesh::hex::pslg::{mesh_pslg, PslgRun};
use hexmesh::quality::{
    metrics_split, validate, verdict, Bounds, ValidateOptions, ANGLE_SLACK_DEG, HEX_MIN_ANGLE_DEG,
};
use hexmesh::{datasets, Error, InputError, Params, Point, Pslg};

/// The distance within which a vertex counts as on a segment in `quality::validate`'s
/// conformity check (2^-40 of the coordinate scale): a projected centre is rounded onto the
/// segment's line, never exactly on it.
fn on_line_band(input: &Pslg) -> f64 {
    let scale = input
        .points
        .iter()
        .flat_map(|p| [p[0].abs(), p[1].abs()])
        .fold(1e-300, f64::max);
    4.0 * scale * (-40f64).exp2()
}

/// Meshes `input`, checks validity and conformity, the interior bounds, and returns the run.
fn mesh_and_check(name: &str, input: &Pslg) -> PslgRun {
    let run = mesh_pslg(input, &Params::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
    let violations = validate(
        &run.mesh,
        Some(input),
        &ValidateOptions {
            single_component: false,
            conforming: true,
        },
    );
    assert!(
        violations.is_empty(),
        "{name}: {} violations, first {}",
        violations.len(),
        violations[0]
    );
    let split = metrics_split(&run.mesh, input, on_line_band(input));
    let interior = &split.interior;
    if interior.triangles > 0 {
        let lo = interior.min_angle.map(|w| w.value).unwrap_or(f64::NAN);
        let hi = interior.max_angle.map(|w| w.value).unwrap_or(f64::NAN);
        assert!(
            lo >= HEX_MIN_ANGLE_DEG - ANGLE_SLACK_DEG && hi <= 90.0 + ANGLE_SLACK_DEG,
            "{name}: interior angles {lo}..{hi}"
        );
        assert_eq!(interior.delaunay_violations, 0, "{name}: interior Delaunay");
    }
    let near = &split.near;
    println!(
        "{name}: {} triangles ({} near segments, {} interior), near angles {:.2}..{:.2}, \
         interior {:.4}..{:.4}, {:?}",
        run.mesh.triangles.len(),
        near.triangles,
        interior.triangles,
        near.min_angle.map_or(f64::NAN, |w| w.value),
        near.max_angle.map_or(f64::NAN, |w| w.value),
        interior.min_angle.map_or(f64::NAN, |w| w.value),
        interior.max_angle.map_or(f64::NAN, |w| w.value),
        run.stats
    );
    run
}

/// A closed polygon's vertices appended to `p`, with its segments.
fn add_loop(p: &mut Pslg, poly: &[Point]) {
    let base = p.points.len() as u32;
    let n = poly.len() as u32;
    p.points.extend_from_slice(poly);
    p.segments
        .extend((0..n).map(|i| [base + i, base + (i + 1) % n]));
}

fn square(c: Point, half: f64) -> Vec<Point> {
    vec![
        [c[0] - half, c[1] - half],
        [c[0] + half, c[1] - half],
        [c[0] + half, c[1] + half],
        [c[0] - half, c[1] + half],
    ]
}

fn area(mesh: &hexmesh::TriMesh) -> f64 {
    mesh.area()
}

#[test]
fn a_square_with_a_square_hole_covers_the_ring_between_them() {
    let mut p = Pslg::default();
    add_loop(&mut p, &square([0.0, 0.0], 1.0));
    add_loop(&mut p, &square([0.1, -0.05], 0.4));
    p.holes.push([0.1, -0.05]);
    let run = mesh_and_check("square-hole", &p);
    let want = 4.0 - 0.64;
    assert!((area(&run.mesh) - want).abs() < 1e-9, "{}", area(&run.mesh));
}

#[test]
#[ignore]
fn debug_levels() {
    let which = std::env::var("WHICH").unwrap_or_default();
    let mut p = Pslg::default();
    if which == "seg" {
        p.points = vec![[0.0, 0.0], [1.0, 0.1]];
        p.segments = vec![[0, 1]];
    } else if which == "tri" {
        add_loop(&mut p, &[[0.0, 0.0], [1.0, 0.1], [0.3, 0.8]]);
    } else {
        add_loop(&mut p, &square([0.0, 0.0], 1.0));
        add_loop(&mut p, &square([0.1, -0.05], 0.4));
        p.holes.push([0.1, -0.05]);
    }
    let mut params = Params::default();
    params.budget.max_steps = Some(
        std::env::var("STEPS")
            .map(|s| s.parse().unwrap())
            .unwrap_or(3000),
    );
    let (h, stop) = hexmesh::hex::pslg::refine_pslg(&p, &params).unwrap();
    let mut hist = std::collections::BTreeMap::new();
    for (k, _) in h.leaves() {
        *hist.entry(k.k).or_insert(0) += 1;
    }
    println!("{stop:?} steps {} levels {hist:?}", h.steps);
}
