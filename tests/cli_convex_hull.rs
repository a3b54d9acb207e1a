//! The domain of a .poly input is what its segments enclose (Triangle's semantics), for every
//! mesher alike: segments that enclose no region, and a segment outside the region, are
//! refused with exit 2 naming the file and line, by ours and the references, from the command
//! line and through the `Mesher` trait; `--convex-hull` (Triangle's -c) adds the hull's edges
//! as segments, split at the points on the hull, and every mesher then meshes the same domain,
//! valid and conforming to the file's segments and the hull (`verify --convex-hull`).

use std::path::PathBuf;
use std::process::{Command, Output};

use hexmesh::{Error, InputError, Params, Unenclosed};

/// The meshers that take segments, those of them this build registers (cgal needs its
/// feature).
fn segment_meshers() -> Vec<&'static str> {
    let registered = hexmesh::mesher_names();
    [
        "hex",
        "rhomb",
        "saalfeld",
        "lsb",
        "triangle",
        "cgal",
        "cgal-conforming",
        "spade",
        "gmsh",
    ]
    .into_iter()
    .filter(|m| registered.contains(m))
    .collect()
}

fn hexmesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hexmesh"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("hexmesh runs")
}

/// A clean scratch directory of this test binary under target/, one per test.
fn scratch(test: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("cli_convex_hull")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

const OPEN: &str = "tests/fixtures/io/open_polyline.poly";
const OUTSIDE: &str = "tests/fixtures/io/segment_outside_domain.poly";
const ON_HULL: &str = "tests/fixtures/io/open_chain_on_hull_points.poly";

fn assert_exit_2(out: &Output, what: &str, needles: &[&str]) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{what}: {err}");
    for needle in needles {
        assert!(
            err.contains(needle),
            "{what}: expected '{needle}' in: {err}"
        );
    }
    assert!(!err.contains("panicked"), "{what}: {err}");
}

#[test]
fn every_mesher_refuses_segments_enclosing_no_region_with_exit_2_naming_the_line() {
    let meshers = segment_meshers();
    assert!(meshers.len() >= 8, "{meshers:?}");
    for m in meshers {
        let out = hexmesh(&["mesh", OPEN, "--mesher", m, "-o", "/dev/null/x"]);
        assert_exit_2(
            &out,
            m,
            &[
                "open_polyline.poly:10: the segments enclose no region",
                "(1 to 2)",
                "--convex-hull",
            ],
        );
    }
}

#[test]
fn every_mesher_refuses_a_segment_outside_the_enclosed_region_naming_its_line() {
    for m in segment_meshers() {
        let out = hexmesh(&["mesh", OUTSIDE, "--mesher", m, "-o", "/dev/null/x"]);
        assert_exit_2(
            &out,
            m,
            &["segment_outside_domain.poly:15: segment 5 has no domain on either side"],
        );
    }
}

#[test]
fn every_mesher_refuses_segments_enclosing_no_region_through_its_trait() {
    let input = hexmesh::io::read_input_enclosed(std::path::Path::new(OPEN), true)
        .expect("with its hull the input reads")
        .0;
    let open = hexmesh::Pslg {
        segments: input.segments[..2].to_vec(),
        ..input
    };
    for name in segment_meshers() {
        let mesher = hexmesh::mesher(name).expect("registered");
        match mesher.mesh(&open, &Params::default()) {
            Err(Error::Input {
                problem:
                    InputError::NoEnclosedRegion {
                        segments: 2,
                        cause: Unenclosed::Open,
                    },
                ..
            }) => {}
            other => panic!(
                "{name}: expected the refusal, got {:?}",
                other.map(|r| r.mesh.triangles.len())
            ),
        }
    }
}

/// Meshes `input` with `--convex-hull` and every segment mesher (`rhomb` refuses with
/// `rhomb_refuses` when given: branching segments, which paper 001 does not permit), and
/// checks each mesh with `verify --convex-hull --bounds valid`: valid, every input point a
/// vertex, every segment (the file's and the hull's) a chain of edges and every boundary
/// edge on a segment. Without `--convex-hull`, `verify` refuses the input as `mesh` does.
fn mesh_in_hull_with_every_mesher(test: &str, input: &str, rhomb_refuses: Option<&str>) {
    let dir = scratch(test);
    for m in segment_meshers() {
        let prefix = dir.join(m);
        let prefix = prefix.to_str().expect("utf-8 path");
        let out = hexmesh(&[
            "mesh",
            input,
            "--convex-hull",
            "--mesher",
            m,
            "-o",
            prefix,
            "--no-check",
        ]);
        if let Some(says) = rhomb_refuses.filter(|_| m == "rhomb") {
            assert_exit_2(&out, m, &[says]);
            continue;
        }
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{m}: {err}");
        let out = hexmesh(&[
            "verify",
            prefix,
            "--input",
            input,
            "--convex-hull",
            "--bounds",
            "valid",
        ]);
        let text = String::from_utf8_lossy(&out.stdout);
        assert_eq!(out.status.code(), Some(0), "{m}: {text}");
        let out = hexmesh(&["verify", prefix, "--input", input, "--bounds", "valid"]);
        assert_exit_2(&out, m, &["the segments enclose no region"]);
    }
}

#[test]
fn with_convex_hull_every_mesher_meshes_an_open_polyline_valid_and_conforming() {
    mesh_in_hull_with_every_mesher(
        "open_polyline",
        OPEN,
        Some("segment 5 is the third of 3 segments at point 1"),
    );
}

#[test]
fn the_convex_hull_is_split_at_points_on_it_and_every_mesher_conforms_to_the_pieces() {
    let (hulled, _) = hexmesh::io::read_input_enclosed(std::path::Path::new(ON_HULL), true)
        .expect("the chain closed by its hull reads");
    // 0-based: the file's three sides, then the left side through (0, 2) and (0, 1).
    assert_eq!(
        hulled.segments,
        vec![[0, 1], [1, 2], [2, 3], [3, 4], [4, 6], [6, 0]]
    );
    mesh_in_hull_with_every_mesher("on_hull_points", ON_HULL, None);
}

#[test]
fn verify_convex_hull_needs_an_input() {
    let out = hexmesh(&["verify", "tests/fixtures/io/square.1", "--convex-hull"]);
    assert_exit_2(&out, "verify", &["--convex-hull", "--input"]);
}
