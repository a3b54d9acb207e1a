//! `lsb.csv`'s figures (paper 003): the family of every initial triangle keeps Theorem 3.4's
//! 2/3 (1/2 plain), and the adaptive meshes, made in child processes like every report case,
//! keep the 1/2 that `verify --bounds lsb` checks.

use std::time::Duration;

use hexmesh::report::lsb::lsb_rows;

#[test]
fn the_family_meets_theorem_3_4_and_the_adaptive_meshes_keep_half_on_plane_100_and_imr() {
    std::env::set_var("HEXMESH_EXE", env!("CARGO_BIN_EXE_hexmesh"));
    let exe = hexmesh::isolate::find_exe().unwrap();
    let inputs: Vec<_> = ["plane-100", "imr"]
        .iter()
        .map(|n| (n.to_string(), hexmesh::datasets::by_name(n).unwrap()))
        .collect();
    let mut labels = Vec::new();
    let rows = lsb_rows(&exe, &inputs, Duration::from_secs(60), |l| {
        labels.push(l.to_string())
    });
    assert_eq!(
        labels,
        [
            "plane-100 × lsb: Theorem 3.4",
            "plane-100 × lsb-plain: Theorem 3.4",
            "imr × lsb: Theorem 3.4",
            "imr × lsb-plain: Theorem 3.4",
        ]
    );
    assert_eq!(rows.len(), 4);
    for r in &rows {
        assert!(r.err.is_empty(), "{}: {}", r.dataset, r.err);
        let family = r.family_min_ratio.unwrap();
        assert!(
            family >= r.bound - 1e-9,
            "{} {}: {family}",
            r.dataset,
            r.variant
        );
        let adaptive = r.adaptive_min_ratio.unwrap();
        assert!(
            adaptive >= r.adaptive_bound - 1e-9,
            "{} {}: {adaptive}",
            r.dataset,
            r.variant
        );
        assert!(r.adaptive_triangles.unwrap() > 0);
    }
    // The modified rule's bound is 2/3, the plain one's 1/2; both adaptive meshes are held to 1/2.
    assert!((rows[0].bound - 2.0 / 3.0).abs() < 1e-15 && rows[1].bound == 0.5);
    assert!(rows.iter().all(|r| r.adaptive_bound == 0.5));
}
