//! The figures of `metrics`: Verdict's radius ratio on the triangles the paper names, robust
//! angles, the histogram, shortest edge over d_min, the two Delaunay counts, and the
//! near-segment/interior split. Plus d_min against brute force (proptest).

use hexmesh::quality::{closest_pair, metrics, metrics_split, triangle_shape, HEX};
use hexmesh::{Pslg, TriMesh};
use proptest::prelude::*;

fn one(p: [[f64; 2]; 3]) -> TriMesh {
    TriMesh {
        vertices: p.to_vec(),
        triangles: vec![[0, 1, 2]],
    }
}

#[test]
fn radius_ratio_is_one_for_the_equilateral_triangle() {
    let s = triangle_shape([[0.0, 0.0], [1.0, 0.0], [0.5, 3f64.sqrt() / 2.0]]);
    assert!((s.radius_ratio - 1.0).abs() < 1e-12, "{}", s.radius_ratio);
    assert!((s.edge_ratio - 1.0).abs() < 1e-12);
    for a in s.angles {
        assert!((a - 60.0).abs() < 1e-12, "{a}");
    }
}

#[test]
fn radius_ratio_is_1_20787_for_the_43_9_46_1_90_triangle() {
    // tan α = 5/(3√3): legs 3√3 and 5 (paper Fig. 10, Sec. 6.2).
    let s = triangle_shape([[0.0, 0.0], [3.0 * 3f64.sqrt(), 0.0], [0.0, 5.0]]);
    assert!(
        (s.radius_ratio - 1.20787).abs() < 1e-5,
        "{}",
        s.radius_ratio
    );
    let mut angles = s.angles;
    angles.sort_by(f64::total_cmp);
    assert!((angles[0] - HEX.min_angle).abs() < 1e-9, "{angles:?}");
    assert!((angles[1] - 46.1021137).abs() < 1e-6, "{angles:?}");
    assert!((angles[2] - 90.0).abs() < 1e-12, "{angles:?}");
}

#[test]
fn radius_ratio_is_1_20711_for_the_right_isoceles_triangle() {
    let s = triangle_shape([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    assert!(
        (s.radius_ratio - 1.20711).abs() < 1e-5,
        "{}",
        s.radius_ratio
    );
    assert!((s.edge_ratio - 2f64.sqrt()).abs() < 1e-15);
}

#[test]
fn tiny_angles_are_accurate_where_acos_would_round_to_zero() {
    // The angle at the origin is atan(1e-9) ≈ 1e-9 rad; acos of its rounded cosine is 0.
    let a = hexmesh::geom::angle_deg([0.0, 0.0], [1.0, 0.0], [1.0, 1e-9]);
    let expected = 1e-9f64.atan().to_degrees();
    assert!((a - expected).abs() < 1e-12 * expected, "{a} vs {expected}");
    let cos = 1.0 / (1.0 + 1e-18f64).sqrt();
    assert_eq!(cos.acos(), 0.0);
}

#[test]
fn the_histogram_holds_every_angle_in_its_degree_bin() {
    let square = TriMesh {
        vertices: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    };
    let m = metrics(&square, None);
    assert_eq!(m.angle_histogram.len(), 180);
    assert_eq!(m.angle_histogram.iter().sum::<u64>(), 6);
    assert_eq!(m.angle_histogram[45], 4);
    assert_eq!(m.angle_histogram[90], 2);
    assert_eq!(m.covered_area, 1.0);
    assert_eq!((m.vertices, m.triangles, m.interior_edges), (4, 2, 1));
    // Cocircular: neither count may call the diagonal a violation.
    assert_eq!(m.delaunay_violations, 0);
    assert_eq!(m.delaunay_tolerance_violations, 0);
}

#[test]
fn shortest_edge_over_d_min_uses_the_input_points() {
    let m = one([[0.0, 0.0], [0.5, 0.0], [0.0, 2.0]]);
    let input = Pslg::from_points(vec![[0.0, 0.0], [0.0, 2.0], [3.0, 3.0]]);
    let q = metrics(&m, Some(&input));
    assert_eq!(q.shortest_edge.map(|w| w.value), Some(0.5));
    assert_eq!(q.d_min, Some(2.0));
    assert_eq!(q.shortest_edge_over_d_min, Some(0.25));
    assert_eq!(metrics(&m, None).shortest_edge_over_d_min, None);
}

#[test]
fn a_near_cocircular_pair_is_settled_by_the_exact_test() {
    // (3, -4) lies exactly on the circle x² + y² = 25 through the other three vertices.
    // One ulp towards the centre puts it strictly inside: the exact test must say so, while
    // the angle sum exceeds 180° by far less than the 1e-7° tolerance.
    let inward = f64::from_bits((-4.0f64).to_bits() - 1);
    let outward = f64::from_bits((-4.0f64).to_bits() + 1);
    assert!(inward > -4.0 && outward < -4.0);
    for (y, exact) in [(-4.0, 0), (inward, 1), (outward, 0)] {
        let m = TriMesh {
            vertices: vec![[-5.0, 0.0], [5.0, 0.0], [0.0, 5.0], [3.0, y]],
            triangles: vec![[0, 1, 2], [1, 0, 3]],
        };
        let q = metrics(&m, None);
        assert_eq!(q.interior_edges, 1);
        assert_eq!(q.delaunay_violations, exact, "y = {y}");
        assert_eq!(q.delaunay_tolerance_violations, 0, "y = {y}");
    }
}

#[test]
fn the_split_puts_triangles_touching_a_segment_apart() {
    // A strip of four triangles along x; the segment is the left edge x = 0.
    let m = TriMesh {
        vertices: vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [3.0, 0.0],
            [0.0, 1.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [3.0, 1.0],
        ],
        triangles: vec![
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
        ],
    };
    let input = Pslg {
        points: vec![[0.0, 0.0], [0.0, 1.0], [3.0, 0.0]],
        segments: vec![[0, 1]],
        ..Pslg::default()
    };
    let s = metrics_split(&m, &input, 0.0);
    assert_eq!(s.near_triangles, vec![0, 1]);
    assert_eq!((s.near.triangles, s.interior.triangles), (2, 4));
    assert_eq!(s.interior.vertices, 6);
    // A band of 1.5 reaches the second column (distance 1) but not the third (distance 2).
    let wide = metrics_split(&m, &input, 1.5);
    assert_eq!(wide.near_triangles, vec![0, 1, 2, 3]);
    // Worst triangles keep their whole-mesh indices.
    assert!(wide.interior.min_angle.is_some_and(|w| w.triangle >= 4));
}

fn brute_force(points: &[[f64; 2]]) -> f64 {
    let mut best = f64::INFINITY;
    for i in 0..points.len() {
        for j in i + 1..points.len() {
            best = best.min(hexmesh::geom::dist(points[i], points[j]));
        }
    }
    best
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn closest_pair_matches_brute_force(
        points in prop::collection::vec((-100i32..100, -100i32..100), 2..120),
        scale in prop::sample::select(vec![1e-9, 0.37, 1.0, 1e9]),
    ) {
        // Integer lattices make ties and duplicates common; the scales probe the arithmetic.
        let pts: Vec<[f64; 2]> = points
            .iter()
            .map(|&(x, y)| [x as f64 * scale, y as f64 * scale])
            .collect();
        let c = closest_pair(&pts).expect("two or more points");
        prop_assert_eq!(c.distance, brute_force(&pts));
        prop_assert!(c.first < c.second);
        prop_assert_eq!(hexmesh::geom::dist(pts[c.first], pts[c.second]), c.distance);
    }
}
