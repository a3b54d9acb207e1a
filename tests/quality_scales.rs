//! The quality figures at any coordinate scale from 1e-150 to 1e150 (issue 23): valid meshes
//! with every vertex multiplied by a factor keep finite figures equal to the unscaled ones
//! (bit for bit when the factor is a power of two, within rounding otherwise), and `validate`
//! still finds them valid.

use std::sync::OnceLock;

use hexmesh::quality::{closest_pair, metrics, verdict, Metrics, Status, HEX};
use hexmesh::{Params, Point, Pslg, TriMesh};
use proptest::prelude::*;

/// A 4 × 3 grid sheared by 0.37 per row and moved off the origin, two triangles a cell.
/// With `segments`, the four (sheared) sides are input segments from corner to corner, whose
/// inner vertices lie on them only within rounding.
fn sheared_grid(segments: bool) -> (TriMesh, Pslg) {
    let (nx, ny) = (4u32, 3u32);
    let vertices: Vec<Point> = (0..=ny)
        .flat_map(|j| (0..=nx).map(move |i| [2.0 + i as f64 + 0.37 * j as f64, 1.0 + j as f64]))
        .collect();
    let v = |i: u32, j: u32| j * (nx + 1) + i;
    let triangles = (0..ny)
        .flat_map(|j| {
            (0..nx).flat_map(move |i| {
                [
                    [v(i, j), v(i + 1, j), v(i + 1, j + 1)],
                    [v(i, j), v(i + 1, j + 1), v(i, j + 1)],
                ]
            })
        })
        .collect();
    let corners = [v(0, 0), v(nx, 0), v(nx, ny), v(0, ny)];
    let input = Pslg {
        points: vertices.clone(),
        segments: if segments {
            (0..4).map(|k| [corners[k], corners[(k + 1) % 4]]).collect()
        } else {
            Vec::new()
        },
        ..Pslg::default()
    };
    (
        TriMesh {
            vertices,
            triangles,
        },
        input,
    )
}

/// Eight points in the unit square, meshed by `hex`.
fn hex_mesh() -> (TriMesh, Pslg) {
    let input = Pslg::from_points(vec![
        [0.1, 0.2],
        [0.8, 0.15],
        [0.45, 0.5],
        [0.3, 0.85],
        [0.9, 0.7],
        [0.52, 0.51],
        [0.05, 0.6],
        [0.7, 0.95],
        [0.45 + 1e-7, 0.5 + 3e-8],
    ]);
    let mesh = hexmesh::mesher("hex")
        .expect("registered")
        .mesh(&input, &Params::default())
        .expect("meshes")
        .mesh;
    (mesh, input)
}

/// The test meshes with their inputs and unscaled figures, built once.
fn cases() -> &'static [(TriMesh, Pslg, Metrics)] {
    static CASES: OnceLock<Vec<(TriMesh, Pslg, Metrics)>> = OnceLock::new();
    CASES.get_or_init(|| {
        [sheared_grid(false), sheared_grid(true), hex_mesh()]
            .into_iter()
            .map(|(mesh, input)| {
                let v = verdict(
                    &mesh,
                    Some(&input),
                    Some(&hexmesh::registry::bounds("valid").unwrap()),
                );
                assert!(v.passed(), "unscaled: {v}");
                let m = metrics(&mesh, Some(&input));
                (mesh, input, m)
            })
            .collect()
    })
}

fn scale_mesh(mesh: &TriMesh, input: &Pslg, f: f64) -> (TriMesh, Pslg) {
    let s = |p: &Point| [p[0] * f, p[1] * f];
    (
        TriMesh {
            vertices: mesh.vertices.iter().map(s).collect(),
            triangles: mesh.triangles.clone(),
        },
        Pslg {
            points: input.points.iter().map(s).collect(),
            holes: input.holes.iter().map(s).collect(),
            ..input.clone()
        },
    )
}

/// Every figure of `m` is finite (no inf, no NaN).
fn assert_finite(m: &Metrics, what: &str) {
    let worst = [
        ("min angle", m.min_angle),
        ("max angle", m.max_angle),
        ("radius ratio max", m.radius_ratio_max),
        ("edge ratio max", m.edge_ratio_max),
        ("shortest edge", m.shortest_edge),
    ];
    for (name, w) in worst {
        let v = w.unwrap_or_else(|| panic!("{what}: no {name}")).value;
        assert!(v.is_finite(), "{what}: {name} = {v}");
    }
    for (name, v) in [
        ("radius ratio mean", m.radius_ratio_mean),
        ("d_min", m.d_min),
        ("shortest edge / d_min", m.shortest_edge_over_d_min),
        ("covered area", Some(m.covered_area)),
    ] {
        let v = v.unwrap_or_else(|| panic!("{what}: no {name}"));
        assert!(v.is_finite() && v > 0.0, "{what}: {name} = {v}");
    }
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

/// The figures of `m`, of the mesh scaled by `f`, against those of the unscaled mesh `u`:
/// equal bits for a power of two, else within a relative `rel` (ratios, lengths, areas) and
/// 1e-6° (angles).
fn assert_matches(m: &Metrics, u: &Metrics, f: f64, rel: f64, what: &str) {
    let exact = f.abs().log2().fract() == 0.0;
    assert_eq!(
        (m.vertices, m.triangles),
        (u.vertices, u.triangles),
        "{what}"
    );
    assert_eq!(m.interior_edges, u.interior_edges, "{what}");
    assert_eq!(
        m.delaunay_tolerance_violations, u.delaunay_tolerance_violations,
        "{what}"
    );
    let value = |w: Option<hexmesh::quality::Worst>| w.expect("figure").value;
    let angles = [
        (value(m.min_angle), value(u.min_angle)),
        (value(m.max_angle), value(u.max_angle)),
    ];
    let ratios = [
        (value(m.radius_ratio_max), value(u.radius_ratio_max)),
        (m.radius_ratio_mean.unwrap(), u.radius_ratio_mean.unwrap()),
        (value(m.edge_ratio_max), value(u.edge_ratio_max)),
        (
            m.shortest_edge_over_d_min.unwrap(),
            u.shortest_edge_over_d_min.unwrap(),
        ),
        // Lengths and areas, brought back to the unscaled size.
        (value(m.shortest_edge) / f, value(u.shortest_edge)),
        (m.d_min.unwrap() / f, u.d_min.unwrap()),
        (m.covered_area / f / f, u.covered_area),
    ];
    if exact {
        for (a, b) in angles.iter().chain(&ratios) {
            assert_eq!(a.to_bits(), b.to_bits(), "{what}: {a} vs {b}");
        }
        assert_eq!(m.angle_histogram, u.angle_histogram, "{what}");
        assert_eq!(m.delaunay_violations, u.delaunay_violations, "{what}");
        assert_eq!(m.delaunay_first, u.delaunay_first, "{what}");
    } else {
        for (a, b) in angles {
            assert!((a - b).abs() <= 1e-6, "{what}: angle {a} vs {b}");
        }
        for (a, b) in ratios {
            assert!(close(a, b, rel), "{what}: {a} vs {b} (within {rel:e})");
        }
    }
}

/// Scales case `k` by `f` and checks the figures of `metrics` and of `verdict` under the
/// validity bounds.
fn check(k: usize, f: f64) {
    let (mesh, input, unscaled) = &cases()[k];
    let what = format!("case {k} scaled by {f:e}");
    // Rounding the scaled coordinates moves a vertex by up to 2^-53 of its largest coordinate:
    // relative to the shortest edge, (largest coordinate / shortest edge) times that.
    let largest = mesh
        .vertices
        .iter()
        .flatten()
        .fold(0.0f64, |m, c| m.max(c.abs()));
    let conditioning = largest / unscaled.shortest_edge.expect("edges").value;
    let rel = 1e-9f64.max(4.0 * f64::EPSILON * conditioning);
    let (mesh, input) = scale_mesh(mesh, input, f);
    let m = metrics(&mesh, Some(&input));
    assert_finite(&m, &what);
    assert_matches(&m, unscaled, f, rel, &what);
    let v = verdict(
        &mesh,
        Some(&input),
        Some(&hexmesh::registry::bounds("valid").unwrap()),
    );
    assert!(v.violations.is_empty(), "{what}: {v}");
    assert!(v.passed(), "{what}: {v}");
    assert_eq!(v.metrics, m, "{what}");
    for c in &v.checks {
        assert!(c.value.is_none_or(f64::is_finite), "{what}: {c:?}");
    }
    if let Some(split) = &v.split {
        for part in [&split.near, &split.interior] {
            for w in [part.min_angle, part.max_angle, part.radius_ratio_max] {
                assert!(w.is_none_or(|w| w.value.is_finite()), "{what}: {part:?}");
            }
        }
        assert!(!split.near_triangles.is_empty(), "{what}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn figures_are_finite_and_unchanged_at_powers_of_ten(k in 0usize..3, s in -150i32..=150) {
        check(k, format!("1e{s}").parse().unwrap());
    }

    #[test]
    fn figures_are_bit_identical_at_powers_of_two(k in 0usize..3, e in -498i32..=497) {
        check(k, 2f64.powi(e));
    }

    #[test]
    fn figures_are_finite_and_unchanged_at_any_factor(
        k in 0usize..3,
        s in -150i32..=149,
        mantissa in 1.0f64..10.0,
    ) {
        let f: f64 = format!("1e{s}").parse::<f64>().unwrap() * mantissa;
        check(k, f);
    }
}

#[test]
fn a_hex_mesh_at_1e80_and_1e_minus_80_keeps_its_radius_ratio() {
    let (mesh, input, unscaled) = &cases()[2];
    let rr = unscaled.radius_ratio_max.expect("triangles").value;
    assert!((rr - 1.2078697).abs() < 1e-6, "unscaled {rr}");
    let hex = hexmesh::registry::bounds("hex").unwrap();
    for f in [1e80, 1e-80] {
        let (scaled, scaled_input) = scale_mesh(mesh, input, f);
        let v = verdict(&scaled, Some(&scaled_input), Some(&hex));
        let m = &v.metrics;
        assert_finite(m, &format!("{f:e}"));
        let r = m.radius_ratio_max.unwrap().value;
        assert!(
            (r - 1.2078697).abs() < 1e-6 && r <= HEX.max_radius_ratio,
            "{f:e}: {r}"
        );
        let row = v
            .checks
            .iter()
            .find(|c| c.what.starts_with("radius ratio"))
            .expect("the hex bounds check the radius ratio");
        assert_eq!(row.status, Status::Ok, "{f:e}: {v}");
        assert!(v.violations.is_empty(), "{f:e}: {v}");
        for c in &v.checks {
            assert!(c.value.is_none_or(f64::is_finite), "{f:e}: {c:?}");
        }
        assert!(!v.to_string().contains("inf"), "{f:e}: {v}");
    }
}

#[test]
fn d_min_is_exact_at_1e_minus_150_where_squares_underflow() {
    // Squared, 3e-160 is 9e-320: subnormal, with a third of its bits gone.
    let d = 3e-160;
    let pts = [[1e-150, 1e-150], [1e-150 + d, 1e-150], [0.0, 0.0]];
    let c = closest_pair(&pts).expect("three points");
    assert_eq!((c.first, c.second), (0, 1));
    let exact = pts[1][0] - pts[0][0];
    assert_eq!(c.distance, exact);
    // And pairs whose squares both underflow to zero are still told apart.
    let pts = [
        [0.0, 0.0],
        [3e-170, 0.0],
        [1.0, 1.0],
        [1.0, 1.5],
        [5.0, 0.0],
        [5.0, 1e-170],
    ];
    let c = closest_pair(&pts).expect("six points");
    assert_eq!((c.first, c.second, c.distance), (4, 5, 1e-170));
}

/// A parallelogram (0, 0), (4, 0), (5, 2), (1, 2) placed at `c` and scaled by `h` (powers of
/// two, so every coordinate is exact), split along its long diagonal (`long`: not Delaunay,
/// the opposite angles are 116.6°) or its short one.
fn parallelogram(c: f64, h: f64, long: bool) -> TriMesh {
    let unit = [[0.0, 0.0], [4.0, 0.0], [5.0, 2.0], [1.0, 2.0]];
    TriMesh {
        vertices: unit.iter().map(|p| [c + h * p[0], c + h * p[1]]).collect(),
        triangles: if long {
            vec![[0, 1, 2], [0, 2, 3]]
        } else {
            vec![[0, 1, 3], [1, 2, 3]]
        },
    }
}

#[test]
fn tiny_and_huge_triangles_keep_exact_signs_and_shapes() {
    // Near 1.5e-150 with edges of 2^-540 (3e-163), whose products underflow to zero, and near
    // 2e149 with edges of 2^480, whose incircle products overflow.
    for (c, h) in [
        (2f64.powi(-497), 2f64.powi(-540)),
        (2f64.powi(497), 2f64.powi(480)),
    ] {
        for long in [true, false] {
            let what = format!("c = {c:e}, h = {h:e}, long diagonal {long}");
            let unit = metrics(&parallelogram(0.0, 1.0, long), None);
            let mesh = parallelogram(c, h, long);
            let v = verdict(
                &mesh,
                None,
                Some(&hexmesh::registry::bounds("valid").unwrap()),
            );
            assert!(v.passed(), "{what}: {v}");
            let m = &v.metrics;
            assert_eq!(m.delaunay_violations, usize::from(long), "{what}");
            assert_eq!(m.delaunay_tolerance_violations, usize::from(long), "{what}");
            for (a, b) in [
                (m.min_angle, unit.min_angle),
                (m.max_angle, unit.max_angle),
                (m.radius_ratio_max, unit.radius_ratio_max),
                (m.edge_ratio_max, unit.edge_ratio_max),
            ] {
                assert_eq!(a.unwrap().value, b.unwrap().value, "{what}");
            }
            assert_eq!(m.radius_ratio_mean, unit.radius_ratio_mean, "{what}");
            let shortest = unit.shortest_edge.unwrap().value * h;
            assert_eq!(m.shortest_edge.unwrap().value, shortest, "{what}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The scaled predicates give the signs of the unscaled points at any power-of-two scale
    /// (scaling is exact, and orient2d and incircle are homogeneous), and the `robust` values
    /// themselves where the coordinates need no scaling.
    #[test]
    fn scaled_predicates_keep_their_signs_at_any_power_of_two(
        pts in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 4),
        k in -520i32..=520,
    ) {
        use hexmesh::geom::{incircle, incircle_scaled, orient2d, orient2d_scaled};
        let p: Vec<Point> = pts.iter().map(|&(x, y)| [x, y]).collect();
        let f = 2f64.powi(k);
        let q: Vec<Point> = p.iter().map(|a| [a[0] * f, a[1] * f]).collect();
        let o = orient2d(p[0], p[1], p[2]);
        let i = incircle(p[0], p[1], p[2], p[3]);
        prop_assert_eq!(orient2d_scaled(p[0], p[1], p[2]).to_bits(), o.to_bits());
        prop_assert_eq!(incircle_scaled(p[0], p[1], p[2], p[3]).to_bits(), i.to_bits());
        let (os, is) = (
            orient2d_scaled(q[0], q[1], q[2]),
            incircle_scaled(q[0], q[1], q[2], q[3]),
        );
        prop_assert_eq!(os.partial_cmp(&0.0), o.partial_cmp(&0.0));
        prop_assert_eq!(is.partial_cmp(&0.0), i.partial_cmp(&0.0));
    }

    /// `Dist2` orders like `dist2` and its root is `dist`, bit for bit, at ordinary scales,
    /// and it keeps that order where `dist2` underflows or overflows.
    #[test]
    fn dist2_keys_order_like_squares(
        pts in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 4),
        k in -520i32..=520,
    ) {
        use hexmesh::geom::{dist, dist2, dist_scaled, Dist2};
        let p: Vec<Point> = pts.iter().map(|&(x, y)| [x, y]).collect();
        let (a, b) = (Dist2::between(p[0], p[1]), Dist2::between(p[2], p[3]));
        let (da, db) = (dist2(p[0], p[1]), dist2(p[2], p[3]));
        prop_assert_eq!(a.cmp(&b), da.total_cmp(&db));
        prop_assert_eq!(a.sqrt().to_bits(), dist(p[0], p[1]).to_bits());
        prop_assert_eq!(dist_scaled(p[0], p[1]).to_bits(), dist(p[0], p[1]).to_bits());
        let f = 2f64.powi(k);
        let q: Vec<Point> = p.iter().map(|a| [a[0] * f, a[1] * f]).collect();
        let (qa, qb) = (Dist2::between(q[0], q[1]), Dist2::between(q[2], q[3]));
        prop_assert_eq!(qa.cmp(&qb), da.total_cmp(&db));
        prop_assert_eq!(qa.sqrt(), a.sqrt() * f);
        prop_assert_eq!(dist_scaled(q[0], q[1]), dist(p[0], p[1]) * f);
    }
}

#[test]
fn exponents_and_power_of_two_scaling_are_exact_down_to_subnormals() {
    use hexmesh::geom::{exponent, scale2};
    assert_eq!(exponent(1.0), 0);
    assert_eq!(exponent(-3.0), 1);
    assert_eq!(exponent(0.75), -1);
    assert_eq!(exponent(f64::MAX), 1023);
    assert_eq!(exponent(f64::MIN_POSITIVE), -1022);
    assert_eq!(exponent(f64::from_bits(1)), -1074);
    assert_eq!(exponent(f64::from_bits(3)), -1073);
    assert_eq!(scale2(1.0, -1074), f64::from_bits(1));
    assert_eq!(scale2(f64::from_bits(1), 1074), 1.0);
    assert_eq!(scale2(1.5, 1023), f64::from_bits(0x7fe8_0000_0000_0000));
    assert_eq!(scale2(1.0, 1024), f64::INFINITY);
    assert_eq!(scale2(-3.0, 2000), f64::NEG_INFINITY);
    assert_eq!(scale2(1.0, -1080), 0.0);
    assert_eq!(scale2(1e-300, 600), 1e-300 * 2f64.powi(600));
}
