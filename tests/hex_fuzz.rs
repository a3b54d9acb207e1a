//! The fuzz campaign of `hexmesh::fuzz` as a test: thousands of seeded random point sets
//! of every family, each meshed and checked against the promised bounds.

use hexmesh::fuzz::fuzz_campaign;

#[test]
fn hex_simple_survives_three_thousand_fuzz_cases() {
    let summary = fuzz_campaign("hex-simple", 3000, 20261123, None, |_| {});
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
