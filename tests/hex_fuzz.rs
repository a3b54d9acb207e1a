//! The fuzz campaign of `hexmesh::fuzz` as a test: thousands of seeded random point sets
//! of every family, each meshed and checked against the promised bounds.

use hexmesh::fuzz::fuzz_campaign;

#[test]
fn hex_simple_survives_three_thousand_fuzz_cases() {
    let summary = fuzz_campaign("hex-simple", 0..3000, 20261123, None, |_| {});
    eprintln!("{summary:?}");
    assert_eq!(summary.failures, 0, "{:?}", summary.first_failure);
    // Every angle within its rounding allowance (the failures above), none more than the
    // default 0.01° beyond the bounds.
    assert!(summary.worst_min_angle >= 30.0 - 0.01);
    assert!(summary.worst_max_angle <= 120.0 + 0.01);
    assert_eq!(summary.rounding_used.last(), Some(&0));
    // Every finished mesh is in a bin (the verdict reported its angle checks).
    assert_eq!(
        summary.rounding_used.iter().sum::<u64>(),
        summary.cases - summary.refused
    );
}

#[test]
fn hex_in_tiles_of_sixteen_points_survives_five_hundred_fuzz_cases() {
    // `hex` tiles inputs of more than 2,048 points; `hex-tiled` tiles these sets of up to 80
    // points by 16, so that the join of the tiles (`hex::extended::tiles`) meets the
    // campaign's families, each checked against `hex`'s promise.
    let summary = fuzz_campaign("hex-tiled", 0..500, 20261123, None, |_| {});
    eprintln!("{summary:?}");
    assert_eq!(summary.failures, 0, "{:?}", summary.first_failure);
    assert!(summary.worst_min_angle >= 43.8979 - 0.01);
    assert!(summary.worst_max_angle <= 90.0 + 0.01);
    assert_eq!(
        summary.rounding_used.iter().sum::<u64>(),
        summary.cases - summary.refused
    );
}

#[test]
fn a_point_set_campaign_split_at_a_case_covers_the_same_cases_as_the_whole() {
    let run = |cases: std::ops::Range<u64>| fuzz_campaign("hex-simple", cases, 7, None, |_| {});
    let (whole, head, tail) = (run(0..60), run(0..45), run(45..60));
    assert_eq!((tail.first, tail.cases), (45, 15));
    assert_eq!(head.cases + tail.cases, whole.cases);
    assert_eq!(
        head.worst_min_angle.min(tail.worst_min_angle),
        whole.worst_min_angle
    );
    assert_eq!(
        head.max_triangles.max(tail.max_triangles),
        whole.max_triangles
    );
    for ((w, h), t) in whole
        .families
        .iter()
        .zip(&head.families)
        .zip(&tail.families)
    {
        assert_eq!(h.cases + t.cases, w.cases, "{}", w.family);
        assert_eq!(h.refused + t.refused, w.refused, "{}", w.family);
    }
}
