//! A .poly's regional area limits are kept or refused, never ignored: the meshers with size
//! control (triangle per region, cgal, spade, lsb and hex by the smallest limit everywhere;
//! hex-simple and rhomb too on point sets, tests/size_control.rs) keep
//! every region's limit and say so in their promise, which `verify` checks triangle by
//! triangle; the meshers without it refuse the input naming the region. The check itself
//! fails a triangle over its limit.

use hexmesh::quality::{verdict, Bounds, Status};
use hexmesh::{mesher, Params, Pslg, Region, TriMesh};

/// The rectangle [0, 2] × [0, 1] cut in two squares by a segment at x = 1; the left square
/// limits areas to 0.01, the right one to 0.1 (rows with an area field), or, with
/// `attribute_only`, the right one has a four-field row whose attribute Triangle reads as
/// its limit too.
fn two_squares(attribute_only: bool) -> Pslg {
    let mut p = Pslg {
        points: vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [0.0, 1.0],
        ],
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0], [1, 4]],
        ..Pslg::default()
    };
    p.labels.regions = vec![
        Region {
            point: [0.5, 0.5],
            attribute: 1.0,
            max_area: Some(0.01),
        },
        Region {
            point: [1.5, 0.5],
            attribute: 0.1,
            max_area: (!attribute_only).then_some(0.1),
        },
    ];
    p
}

fn area_row(v: &hexmesh::quality::Verdict) -> &hexmesh::quality::Check {
    v.checks
        .iter()
        .find(|c| c.what == "triangle area / its limit")
        .unwrap_or_else(|| panic!("no area check in\n{v}"))
}

#[test]
fn meshers_with_size_control_keep_every_regions_area_limit() {
    for name in ["triangle", "cgal", "spade", "lsb", "hex"] {
        for attribute_only in [false, true] {
            let input = two_squares(attribute_only);
            let m = mesher(name).expect(name);
            let params = Params::default();
            let run = m
                .mesh(&input, &params)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            let promise = m.promise(&params);
            assert!(promise.region_area_limits, "{name} promises the limits");
            let v = verdict(&run.mesh, Some(&input), Some(&promise));
            assert!(v.passed(), "{name}:\n{v}");
            let row = area_row(&v);
            assert_eq!(row.status, Status::Ok, "{name}");
            // The limit bites: the largest triangle is more than half of its limit (hex: more
            // than 1/20, its level is chosen by a bound 4.6 times a regular triangle's area,
            // hex::size, and a level quarters the areas).
            let bites = if name == "hex" { 0.05 } else { 0.5 };
            assert!(
                row.value.is_some_and(|r| r > bites && r <= 1.0),
                "{name}: {row:?}"
            );
        }
    }
}

#[test]
fn meshers_without_size_control_refuse_an_area_limit_naming_the_region() {
    let input = two_squares(false);
    for name in ["saalfeld", "cgal-conforming"] {
        let err = mesher(name)
            .expect(name)
            .mesh(&input, &Params::default())
            .expect_err(name)
            .to_string();
        assert!(
            err.contains("region 1 at (0.5, 0.5) limits triangle areas to 0.01"),
            "{name}: {err}"
        );
    }
    // rhomb on a domain has no size control yet either.
    let err = mesher("rhomb")
        .expect("rhomb")
        .mesh(&input, &Params::default())
        .expect_err("refused")
        .to_string();
    assert!(err.contains("area limit 0.01"), "{err}");
}

#[test]
fn the_area_check_fails_a_triangle_over_its_regions_limit() {
    let input = two_squares(false);
    // Four triangles: the right square in two halves of area 0.5 each, over its 0.1.
    let mesh = TriMesh {
        vertices: input.points.clone(),
        triangles: vec![[0, 1, 4], [0, 4, 5], [1, 2, 3], [1, 3, 4]],
    };
    let bounds = Bounds::validity("sized").with_area_limits(None);
    let v = verdict(&mesh, Some(&input), Some(&bounds));
    let row = area_row(&v);
    assert_eq!(row.status, Status::Fail, "{v}");
    // The worst is a left triangle: 0.5 against 0.01.
    assert_eq!(row.value, Some(50.0));
    assert!(!v.passed());
    // Without regions and with a global limit of 0.5 it passes, exactly at the limit.
    let plain = Pslg {
        labels: Default::default(),
        ..input
    };
    let v = verdict(
        &mesh,
        Some(&plain),
        Some(&Bounds::validity("sized").with_area_limits(Some(0.5))),
    );
    assert_eq!(area_row(&v).status, Status::Ok, "{v}");
    assert_eq!(area_row(&v).value, Some(1.0));
}
