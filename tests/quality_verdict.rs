//! `verdict`: bounds per mesher applied to the right part of the mesh, the table `hexmesh
//! verify` prints, and its JSON.

use hexmesh::quality::{verdict, Status};
use hexmesh::{Pslg, TriMesh};

/// A strip of three unit-high columns; the first (next to the segment x = 0) is half as wide,
/// so its triangles have 26.6° angles while the others are 45°/45°/90°.
fn strip() -> (TriMesh, Vec<[f64; 2]>) {
    let xs = [0.0, 0.5, 1.5, 2.5];
    let mut vertices: Vec<[f64; 2]> = xs.iter().map(|&x| [x, 0.0]).collect();
    vertices.extend(xs.iter().map(|&x| [x, 1.0]));
    let triangles = (0..3u32)
        .flat_map(|c| [[c, c + 1, c + 5], [c, c + 5, c + 4]])
        .collect();
    let mesh = TriMesh {
        vertices: vertices.clone(),
        triangles,
    };
    (mesh, vertices)
}

/// A 3 × 3 grid of cells in the rectangle [0, 3] × [0, 3] framed by its four sides as segments
/// (Triangle's .poly semantics: the domain is what they bound). The first and last columns
/// are half as wide (x in [0, 0.5] and [2.5, 3]), so their triangles have 26.6° angles; the
/// others are 45°/45°/90°, and the two cells of the middle row away from the frame touch no
/// segment.
fn framed_grid() -> (TriMesh, Pslg) {
    framed_grid_with([0.0, 0.5, 1.5, 2.5, 3.0])
}

/// The framed 4 × 3 grid of cells with columns at `xs`.
fn framed_grid_with(xs: [f64; 5]) -> (TriMesh, Pslg) {
    let ys = [0.0, 1.0, 2.0, 3.0];
    let vertices: Vec<[f64; 2]> = ys
        .iter()
        .flat_map(|&y| xs.iter().map(move |&x| [x, y]))
        .collect();
    let v = |i: u32, j: u32| j * 5 + i;
    let mut triangles = Vec::new();
    for j in 0..3 {
        for i in 0..4 {
            triangles.push([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
            triangles.push([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    // The frame as a chain of segments through every boundary vertex.
    let ring: Vec<u32> = (0..4)
        .map(|i| v(i, 0))
        .chain((0..3).map(|j| v(4, j)))
        .chain((1..5).rev().map(|i| v(i, 3)))
        .chain((1..4).rev().map(|j| v(0, j)))
        .collect();
    let segments = (0..ring.len())
        .map(|k| [ring[k], ring[(k + 1) % ring.len()]])
        .collect();
    let pslg = Pslg {
        points: vertices.clone(),
        segments,
        ..Pslg::default()
    };
    (
        TriMesh {
            vertices,
            triangles,
        },
        pslg,
    )
}

/// The names of the rows of `v` that failed.
fn failed(v: &hexmesh::quality::Verdict) -> Vec<&str> {
    v.failed().map(|c| c.what.as_str()).collect()
}

#[test]
fn hex_holds_its_interior_bounds_away_from_segments_and_30_degrees_beside_them() {
    let (mesh, pslg) = framed_grid();
    let hex = hexmesh::registry::bounds("hex").expect("hex");
    let out = verdict(&mesh, Some(&pslg), Some(&hex));
    // The 26.6° triangles touch the frame: the interior rows pass, the near-segment row fails.
    assert_eq!(failed(&out), vec!["min angle near segments (deg)"], "{out}");
    // With columns of equal width every triangle is 45°/45°/90°: passed.
    let (square, square_input) = framed_grid_with([0.0, 1.0, 2.0, 3.0, 4.0]);
    let whole = verdict(&square, Some(&square_input), Some(&hex));
    assert!(whole.passed(), "{whole}");
    let split = out.split.as_ref().expect("a PSLG gets the split figures");
    // Cells (1, 1) and (2, 1) are the triangles 10, 11, 12, 13; everything else touches the frame.
    let near: Vec<usize> = (0..24).filter(|t| !(10..14).contains(t)).collect();
    assert_eq!(split.near_triangles, near);
    let near_min = split.near.min_angle.expect("near min angle").value;
    assert!((near_min - 26.565051177).abs() < 1e-6, "{near_min}");
    let text = out.to_string();
    assert!(
        text.contains("away from segments") && text.contains("near segments"),
        "{text}"
    );

    // The same mesh as the mesh of a point set must meet the bounds everywhere.
    let points_only = Pslg::from_points(pslg.points);
    let out = verdict(&mesh, Some(&points_only), Some(&hex));
    assert!(!out.passed());
    assert_eq!(
        failed(&out),
        vec!["min angle (deg)", "radius ratio R/(2r)"],
        "{out}"
    );
}

#[test]
fn shortest_edge_over_d_min_is_skipped_without_input_and_checked_with_it() {
    let (mesh, points) = strip();
    let hex = hexmesh::registry::bounds("hex").expect("hex");
    let without = verdict(&mesh, None, Some(&hex));
    let row = |v: &hexmesh::quality::Verdict| {
        v.checks
            .iter()
            .find(|c| c.what == "shortest edge / d_min")
            .map(|c| (c.status, c.value))
            .expect("an edge row")
    };
    assert_eq!(row(&without).0, Status::Skipped);
    // d_min 0.5 between (0,0) and (0.5,0), shortest edge 0.5: ratio 1.
    let with = verdict(&mesh, Some(&Pslg::from_points(points.clone())), Some(&hex));
    assert_eq!(row(&with), (Status::Ok, Some(1.0)));
    // Input points 5 apart but a mesh edge of 0.5: 0.1 is below √7/(12√3) ≈ 0.127.
    let sparse = Pslg::from_points(vec![[0.0, 0.0], [5.0, 0.0]]);
    let tight = verdict(&mesh, Some(&sparse), Some(&hex));
    assert_eq!(row(&tight), (Status::Fail, Some(0.1)));
}

#[test]
fn the_json_names_each_check_with_status_value_and_limit() {
    let (mesh, _) = strip();
    let out = verdict(
        &mesh,
        None,
        Some(&hexmesh::registry::bounds("min-angle=30").expect("bounds")),
    );
    let json: serde_json::Value = serde_json::to_value(&out).expect("json");
    let checks = json["checks"].as_array().expect("checks array");
    let min = checks
        .iter()
        .find(|c| c["what"] == "min angle (deg)")
        .expect("min angle row");
    assert_eq!(min["status"], "fail");
    assert_eq!(min["limit"], 30.0);
    // The worst triangle is the one that lies farthest beyond its rounding allowance.
    let fit = hexmesh::quality::rounding::angle_fit(
        (0..mesh.triangles.len()).map(|t| (t, mesh.corners(t))),
        30.0,
        180.0,
    )
    .expect("triangles");
    assert_eq!(min["worst"]["triangle"], fit.nearest.triangle);
    assert!(min["rounding"]["used"].as_f64().is_some_and(|u| u > 0.0));
    assert_eq!(
        json["metrics"]["angle_histogram"].as_array().map(Vec::len),
        Some(180)
    );
    assert_eq!(json["bounds"], "min-angle=30");
}

#[test]
fn without_bounds_only_validity_is_decided() {
    let (mesh, _) = strip();
    let out = verdict(&mesh, None, None);
    assert!(out.passed(), "{out}");
    assert_eq!(out.checks.len(), 1);
    assert!(out.to_string().contains("none (validity only)"));
}
