//! Every dataset is what `hexmesh::datasets` and the paper's Sec. 8 say it is: valid input,
//! the right counts, the right domain, points where they should be.

use hexmesh::datasets::{self, LINE_END, SCALING, SMALL};
use hexmesh::geom::orient2d;
use hexmesh::{Error, Hexagon, Pslg};

fn get(name: &str) -> Pslg {
    datasets::by_name(name).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn every_small_dataset_passes_the_input_check() {
    for &name in SMALL {
        assert_eq!(get(name).check(), Ok(()), "{name}");
    }
}

#[test]
fn every_scaling_dataset_passes_the_input_check() {
    for &name in SCALING {
        assert_eq!(get(name).check(), Ok(()), "{name}");
    }
}

#[test]
fn point_counts_match_the_names() {
    let expected = [
        ("close-pair", 2),
        ("line-100", 100),
        ("plane-100", 100),
        ("plane-1k", 1_000),
        ("plane-2k", 2_000),
        ("plane-10k", 10_000),
        ("plane-100k", 100_000),
        ("plane-1m", 1_000_000),
    ];
    for (name, n) in expected {
        let d = get(name);
        assert_eq!(d.points.len(), n, "{name}");
        assert!(d.segments.is_empty() && d.holes.is_empty(), "{name}");
    }
}

#[test]
fn close_pair_sits_in_the_unit_hexagon_which_is_not_fitted() {
    let d = get("close-pair");
    assert_eq!(d.points, vec![[-0.01, 0.0], [0.01, 0.0]]);
    let unit = Hexagon::new([0.0, 0.0], 1.0);
    assert_eq!(d.hexagon, Some(unit));
    assert_eq!(d.bounding_hexagon(), unit);
    assert!(d.points.iter().all(|&p| unit.contains_strictly(p)));
}

#[test]
fn random_point_sets_have_fitted_hexagons() {
    for name in ["line-100", "plane-100", "plane-1k", "plane-2k"] {
        assert_eq!(get(name).hexagon, None, "{name}");
    }
}

#[test]
fn line_points_lie_on_the_segment_up_to_one_rounding() {
    let d = get("line-100");
    for (i, p) in d.points.iter().enumerate() {
        // x is the parameter t itself and y its product with 0.37, rounded once.
        assert!((0.0..1.0).contains(&p[0]), "point {i}: {p:?}");
        assert_eq!(p[1], p[0] * LINE_END[1], "point {i}");
        // So the exact orientation against the segment is at most half an ulp of y times 1.
        let o = orient2d([0.0, 0.0], LINE_END, *p);
        assert!(o.abs() <= f64::EPSILON * p[1].abs(), "point {i}: {o:e}");
    }
}

#[test]
fn line_points_spread_over_the_whole_segment() {
    let d = get("line-100");
    let mut xs: Vec<f64> = d.points.iter().map(|p| p[0]).collect();
    xs.sort_by(f64::total_cmp);
    assert!(xs[0] < 0.1 && xs[99] > 0.9, "{} .. {}", xs[0], xs[99]);
}

#[test]
fn plane_points_lie_in_the_unit_square_and_fill_its_quadrants() {
    for name in ["plane-100", "plane-1k", "plane-2k", "plane-10k"] {
        let d = get(name);
        let n = d.points.len();
        let mut quadrant = [0usize; 4];
        for p in &d.points {
            assert!(
                (0.0..1.0).contains(&p[0]) && (0.0..1.0).contains(&p[1]),
                "{name} {p:?}"
            );
            quadrant[usize::from(p[0] >= 0.5) + 2 * usize::from(p[1] >= 0.5)] += 1;
        }
        // A fair quarter each, within five standard deviations of the binomial count.
        let sd = (n as f64 * 0.25 * 0.75).sqrt();
        for q in quadrant {
            assert!(
                (q as f64 - n as f64 / 4.0).abs() < 5.0 * sd,
                "{name} {quadrant:?}"
            );
        }
    }
}

#[test]
fn seeded_variants_differ_by_seed_and_repeat_by_seed() {
    for name in ["line-100", "plane-100", "plane-2k"] {
        let a = datasets::random_with_seed(name, 11).expect(name);
        let b = datasets::random_with_seed(name, 12).expect(name);
        assert_ne!(a.points, b.points, "{name}");
        assert_eq!(a, datasets::random_with_seed(name, 11).expect(name));
        assert_eq!(a.check(), Ok(()));
    }
}

#[test]
fn a_smaller_plane_set_is_a_prefix_of_a_larger_one_with_the_same_seed() {
    let small = datasets::random_with_seed("plane-1k", 99).expect("plane-1k");
    let large = datasets::random_with_seed("plane-2k", 99).expect("plane-2k");
    assert_eq!(small.points[..], large.points[..1_000]);
}

#[test]
fn unknown_and_non_random_names_are_usage_errors() {
    assert!(matches!(datasets::by_name("IMR"), Err(Error::Usage(_))));
    assert!(matches!(datasets::by_name(""), Err(Error::Usage(_))));
    assert!(matches!(
        datasets::random_with_seed("imr", 0),
        Err(Error::Usage(_))
    ));
    assert!(matches!(
        datasets::random_with_seed("nope", 0),
        Err(Error::Usage(_))
    ));
}
