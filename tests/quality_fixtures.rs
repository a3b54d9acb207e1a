//! The hand-written broken meshes of tests/fixtures/broken: each is caught with the right
//! violation or failed bound, and the two borderline good ones pass.

use std::path::PathBuf;

use hexmesh::quality::{validate, verdict, Status, ValidateOptions, Violation, HEX};
use hexmesh::{Pslg, TriMesh};

/// Rows of a Triangle file without comments and blank lines, split into words.
fn rows(path: &PathBuf) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .map(|l| l.split('#').next().unwrap_or(""))
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(str::to_string).collect())
        .collect()
}

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/broken")
        .join(name)
}

/// Test-only reader of a 1-based .node file (the io module owns the real one).
fn read_node(name: &str) -> Vec<[f64; 2]> {
    let r = rows(&fixture(name));
    let count: usize = r[0][0].parse().expect("vertex count");
    r[1..=count]
        .iter()
        .map(|w| [w[1].parse().expect("x"), w[2].parse().expect("y")])
        .collect()
}

fn read_mesh(prefix: &str) -> TriMesh {
    let r = rows(&fixture(&format!("{prefix}.ele")));
    let count: usize = r[0][0].parse().expect("triangle count");
    let triangles = r[1..=count]
        .iter()
        .map(|w| {
            let v = |k: usize| w[k].parse::<u32>().expect("vertex index") - 1;
            [v(1), v(2), v(3)]
        })
        .collect();
    TriMesh {
        vertices: read_node(&format!("{prefix}.node")),
        triangles,
    }
}

fn plain(mesh: &TriMesh) -> Vec<Violation> {
    validate(mesh, None, &ValidateOptions::default())
}

#[test]
fn clockwise_triangle_is_reported_as_clockwise() {
    let v = plain(&read_mesh("clockwise_triangle"));
    assert!(
        v.iter().any(|x| matches!(
            x,
            Violation::Clockwise {
                triangle: 1,
                corners: [0, 3, 2],
                ..
            }
        )),
        "{v:#?}"
    );
    assert!(!v.iter().any(|x| matches!(x, Violation::ZeroArea { .. })));
}

#[test]
fn zero_area_triangle_is_reported_as_zero_area_and_nothing_else() {
    let v = plain(&read_mesh("zero_area_triangle"));
    assert_eq!(v.len(), 1, "{v:#?}");
    assert!(
        matches!(v[0], Violation::ZeroArea { triangle: 2, .. }),
        "{v:#?}"
    );
}

#[test]
fn edge_used_three_times_names_the_edge_and_its_triangles() {
    let v = plain(&read_mesh("edge_used_three_times"));
    assert!(
        v.iter().any(|x| matches!(
            x,
            Violation::EdgeOverused { edge: [0, 1], triangles, .. } if triangles == &vec![0, 1, 2]
        )),
        "{v:#?}"
    );
}

#[test]
fn overlapping_triangles_fold_is_found_at_the_interior_vertex() {
    let mesh = read_mesh("overlapping_triangles");
    let v = plain(&mesh);
    assert!(
        v.iter().any(|x| matches!(
            x,
            Violation::Fold {
                vertex: 0,
                winding: 2,
                ..
            }
        )),
        "{v:#?}"
    );
    // Every triangle is counter-clockwise: the fold is not a flipped triangle.
    assert!(!v.iter().any(|x| matches!(x, Violation::Clockwise { .. })));
    assert!(v
        .iter()
        .any(|x| matches!(x, Violation::BoundaryCrossing { .. })));
}

#[test]
fn hole_in_point_set_mesh_breaks_the_one_disc_rule_only() {
    let mesh = read_mesh("hole_in_point_set_mesh");
    // A ring is a valid mesh of a domain with a hole...
    assert_eq!(plain(&mesh), vec![]);
    // ...but not of a point set.
    let one_disc = ValidateOptions {
        single_component: true,
        ..ValidateOptions::default()
    };
    let v = validate(&mesh, None, &one_disc);
    assert_eq!(v.len(), 1, "{v:#?}");
    assert!(
        matches!(v[0], Violation::HoleInMesh { loops: 2, .. }),
        "{v:#?}"
    );
    assert!(v[0].to_string().contains("hole in the mesh"));
}

#[test]
fn duplicate_vertex_names_both_copies() {
    let v = plain(&read_mesh("duplicate_vertex"));
    assert!(
        v.iter().any(|x| matches!(
            x,
            Violation::DuplicateVertex { first: 2, second: 4, point } if *point == [1.0, 1.0]
        )),
        "{v:#?}"
    );
}

#[test]
fn missing_input_point_names_the_input_index() {
    let mesh = read_mesh("missing_input_point");
    assert_eq!(plain(&mesh), vec![]);
    let input = Pslg::from_points(read_node("missing_input_point_input.node"));
    let v = validate(&mesh, Some(&input), &ValidateOptions::default());
    assert_eq!(
        v,
        vec![Violation::MissingInputPoint {
            input: 4,
            point: [0.5, 0.5]
        }]
    );
    assert!(!verdict(&mesh, Some(&input), None).passed());
}

#[test]
fn non_delaunay_edge_is_valid_but_fails_the_delaunay_bound() {
    let mesh = read_mesh("non_delaunay_edge");
    assert_eq!(plain(&mesh), vec![]);
    let bounds = hexmesh::registry::bounds("delaunay").expect("delaunay bounds");
    let out = verdict(&mesh, None, Some(&bounds));
    assert!(!out.passed(), "{out}");
    assert_eq!(out.metrics.delaunay_violations, 1);
    assert_eq!(out.metrics.delaunay_tolerance_violations, 1);
    let check = out
        .checks
        .iter()
        .find(|c| c.what.contains("Delaunay"))
        .expect("a Delaunay row");
    assert_eq!(check.status, Status::Fail);
    assert_eq!(check.worst.map(|w| w.triangle), Some(0));
    assert!(out.to_string().contains("FAIL"));
}

#[test]
fn cocircular_square_passes_delaunay_and_hex_with_either_diagonal() {
    for prefix in [
        "cocircular_square_either_diagonal_a",
        "cocircular_square_either_diagonal_b",
    ] {
        let mesh = read_mesh(prefix);
        for name in ["delaunay", "hex"] {
            let bounds = hexmesh::registry::bounds(name).expect("bounds");
            let out = verdict(&mesh, None, Some(&bounds));
            assert!(out.passed(), "{prefix} with {name}:\n{out}");
            assert_eq!(out.metrics.delaunay_violations, 0);
            assert_eq!(out.metrics.delaunay_tolerance_violations, 0);
        }
    }
}

#[test]
fn angle_43_8978_fails_the_hex_min_angle_at_its_triangle() {
    let mesh = read_mesh("angle_43_8978");
    assert_eq!(plain(&mesh), vec![]);
    let out = verdict(
        &mesh,
        None,
        Some(&hexmesh::registry::bounds("hex").expect("hex")),
    );
    assert!(!out.passed(), "{out}");
    let failed: Vec<_> = out
        .checks
        .iter()
        .filter(|c| c.status == Status::Fail)
        .collect();
    assert_eq!(failed.len(), 1, "{out}");
    assert_eq!(failed[0].what, "min angle (deg)");
    assert_eq!(failed[0].limit, HEX.min_angle);
    let worst = failed[0].worst.expect("worst triangle");
    assert_eq!(worst.triangle, 0);
    assert_eq!(worst.corners[0], [0.0, 0.0]);
    assert!((worst.value - 43.8978).abs() < 1e-9, "{}", worst.value);
    // Within the 1e-6° slack it would pass: 43.8978 is 8.6e-5° short.
    assert!(HEX.min_angle - worst.value > 1e-6);
}

#[test]
fn right_angle_exactly_90_passes_the_hex_bounds() {
    let mesh = read_mesh("right_angle_exactly_90");
    let out = verdict(
        &mesh,
        None,
        Some(&hexmesh::registry::bounds("hex").expect("hex")),
    );
    assert!(out.passed(), "{out}");
    assert_eq!(out.metrics.max_angle.map(|w| w.value), Some(90.0));
    assert_eq!(out.metrics.min_angle.map(|w| w.value), Some(45.0));
}

#[test]
fn every_fixture_is_readable_and_checked_without_panicking() {
    let dir = fixture("");
    let mut prefixes: Vec<String> = std::fs::read_dir(&dir)
        .expect("fixture dir")
        .filter_map(|e| e.ok())
        .filter_map(|e| {
            e.file_name()
                .to_str()?
                .strip_suffix(".ele")
                .map(str::to_string)
        })
        .collect();
    prefixes.sort();
    assert_eq!(prefixes.len(), 23, "{prefixes:?}");
    for p in prefixes {
        let mesh = read_mesh(&p);
        for name in ["hex", "valid"] {
            let b = hexmesh::registry::bounds(name).expect("bounds");
            let out = verdict(&mesh, None, Some(&b));
            let json = serde_json::to_string(&out).expect("verdict as JSON");
            assert!(json.contains("\"checks\""), "{p}: {json}");
        }
    }
}

#[test]
fn the_io_reader_reads_every_fixture_as_the_test_reader_does() {
    // `hexmesh verify` reads these files with the io module: it must see the same meshes.
    let dir = fixture("");
    let mut prefixes: Vec<String> = std::fs::read_dir(&dir)
        .expect("fixture dir")
        .filter_map(|e| e.ok())
        .filter_map(|e| {
            e.file_name()
                .to_str()?
                .strip_suffix(".ele")
                .map(str::to_string)
        })
        .collect();
    prefixes.sort();
    for p in prefixes {
        let by_io = hexmesh::io::read_mesh(&fixture(&p)).unwrap_or_else(|e| panic!("{p}: {e}"));
        assert_eq!(by_io, read_mesh(&p), "{p}");
    }
    let input = hexmesh::io::read_input(&fixture("missing_input_point_input.node"))
        .expect("the input of missing_input_point");
    assert_eq!(input.points, read_node("missing_input_point_input.node"));
}

#[test]
fn no_triangles_is_invalid_so_no_bound_passes_on_it() {
    let mesh = read_mesh("no_triangles");
    assert_eq!(
        plain(&mesh).first(),
        Some(&Violation::NoTriangles { vertices: 3 })
    );
    let out = verdict(
        &mesh,
        None,
        Some(&hexmesh::registry::bounds("hex").expect("hex")),
    );
    assert!(!out.passed(), "{out}");
}

#[test]
fn nested_triangle_overlap_is_covered_twice_without_crossing_edges() {
    let v = plain(&read_mesh("nested_triangle_overlap"));
    assert!(
        !v.iter()
            .any(|x| matches!(x, Violation::BoundaryCrossing { .. })),
        "{v:#?}"
    );
    assert!(
        v.iter()
            .any(|x| matches!(x, Violation::Overlap { covering: 2, .. })),
        "{v:#?}"
    );
}

#[test]
fn t_junction_is_caught_as_boundary_edges_overlapping() {
    let v = plain(&read_mesh("t_junction"));
    // Edge 1-2 (0-based [0, 1]) of the upper triangle runs along the two lower edges at 4.
    assert!(
        v.iter()
            .any(|x| matches!(x, Violation::BoundaryCrossing { first: [0, 1], .. })),
        "{v:#?}"
    );
}

#[test]
fn non_delaunay_by_a_hair_fails_only_the_exact_test() {
    let bad = read_mesh("non_delaunay_by_a_hair");
    assert_eq!(plain(&bad), vec![]);
    let out = verdict(
        &bad,
        None,
        Some(&hexmesh::registry::bounds("delaunay").expect("delaunay")),
    );
    assert!(!out.passed(), "{out}");
    assert_eq!(out.metrics.delaunay_violations, 1);
    // The angle-sum form with its 1e-7° slack cannot see 2^-52.
    assert_eq!(out.metrics.delaunay_tolerance_violations, 0);

    let good = read_mesh("delaunay_by_a_hair");
    let out = verdict(
        &good,
        None,
        Some(&hexmesh::registry::bounds("delaunay").expect("delaunay")),
    );
    assert!(out.passed(), "{out}");
}

#[test]
fn hole_meshed_is_caught_at_its_seed_and_the_mesh_is_otherwise_valid() {
    let mesh = read_mesh("hole_meshed");
    assert_eq!(plain(&mesh), vec![]);
    let input = hexmesh::io::read_input(&fixture("hole_meshed_input.poly")).expect("input");
    let v = validate(&mesh, Some(&input), &ValidateOptions::default());
    assert_eq!(
        v,
        vec![Violation::HoleCovered {
            hole: 0,
            point: [1.5, 1.5],
            triangle: 8
        }]
    );
    // The ring alone (triangles 0..8) is right.
    let ring = TriMesh {
        triangles: mesh.triangles[..8].to_vec(),
        ..mesh
    };
    assert_eq!(
        validate(&ring, Some(&input), &ValidateOptions::default()),
        vec![]
    );
}

#[test]
fn spills_past_segments_is_caught_when_conformity_is_asked_for() {
    let mesh = read_mesh("spills_past_segments");
    let input =
        hexmesh::io::read_input(&fixture("spills_past_segments_input.poly")).expect("input");
    let conforming = ValidateOptions {
        conforming: true,
        ..ValidateOptions::default()
    };
    let v = validate(&mesh, Some(&input), &conforming);
    assert_eq!(
        v,
        vec![Violation::BoundaryOffSegments {
            edge: [2, 4],
            points: [[2.0, 1.0], [1.0, 2.0]]
        }]
    );
    // Without the notch triangle the L is meshed exactly.
    let l = TriMesh {
        triangles: mesh.triangles[..4].to_vec(),
        ..mesh
    };
    assert_eq!(validate(&l, Some(&input), &conforming), vec![]);
}

/// `hex`'s verdict on a hand-made mesh of a domain, with its input.
fn hex_on_domain(prefix: &str, input: &str) -> hexmesh::quality::Verdict {
    let mesh = read_mesh(prefix);
    let input = hexmesh::io::read_input(&fixture(input)).expect("input");
    let hex = hexmesh::registry::bounds("hex").expect("hex");
    verdict(&mesh, Some(&input), Some(&hex))
}

/// The rows of a verdict that failed, by name.
fn failed_rows(v: &hexmesh::quality::Verdict) -> Vec<&str> {
    v.failed().map(|c| c.what.as_str()).collect()
}

#[test]
fn a_29_9_degree_angle_at_a_segment_fails_only_the_hex_near_segment_minimum() {
    let v = hex_on_domain("near_segment_29_9", "near_segment_29_9_input.poly");
    assert_eq!(failed_rows(&v), ["min angle near segments (deg)"], "{v}");
    let row = v
        .checks
        .iter()
        .find(|c| c.status == Status::Fail)
        .expect("row");
    let worst = row.worst.expect("worst");
    assert!((worst.value - 29.9).abs() < 1e-9, "{}", worst.value);
    assert_eq!(row.limit, 30.0);
}

#[test]
fn a_split_sharp_corner_fails_the_hex_near_segment_minimum_and_the_whole_corner_passes() {
    let split = hex_on_domain("sharp_corner_split", "sharp_corner_input.poly");
    assert_eq!(
        failed_rows(&split),
        ["min angle near segments (deg)"],
        "{split}"
    );
    let worst = split.checks.iter().find_map(|c| c.worst).expect("worst");
    assert!((worst.value - 5.0).abs() < 1e-6, "{}", worst.value);
    let whole = hex_on_domain("sharp_corner_whole", "sharp_corner_input.poly");
    assert!(whole.passed(), "{whole}");
    assert_eq!(whole.metrics.min_angle.map(|w| w.value.round()), Some(10.0));
}

#[test]
fn a_120_1_degree_angle_at_a_segment_fails_only_the_hex_near_segment_maximum() {
    let v = hex_on_domain("near_segment_120_1", "near_segment_120_1_input.poly");
    assert_eq!(failed_rows(&v), ["max angle near segments (deg)"], "{v}");
}
