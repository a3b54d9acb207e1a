//! Bad input to every command: a clear error naming the file and line, exit 2, no panic.

use std::process::{Command, Output};

fn hexmesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hexmesh"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("hexmesh runs")
}

/// Each malformed input file with the `file:line` its error must name.
const BAD_INPUTS: &[(&str, &str)] = &[
    ("nan_coordinate.node", "nan_coordinate.node:4:"),
    ("inf_coordinate.node", "inf_coordinate.node:4:"),
    ("empty.node", "empty.node:1:"),
    ("short_rows.node", "short_rows.node:5:"),
    ("non_numeric.node", "non_numeric.node:3:"),
    ("missing_vertex.poly", "missing_vertex.poly:9:"),
    ("crossing_segments.poly", "crossing_segments.poly:9:"),
    ("duplicate_points.node", "duplicate_points.node:6:"),
    ("point_on_segment.poly", "point_on_segment.poly:6:"),
    (
        "outside_given_hexagon.node",
        "outside_given_hexagon.node:5:",
    ),
];

fn assert_refused(args: &[&str], needle: &str) {
    let out = hexmesh(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.contains(needle),
        "{args:?}: expected '{needle}' in: {err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn mesh_refuses_each_malformed_input_naming_file_and_line() {
    let mesher = hexmesh::mesher_names()
        .first()
        .copied()
        .unwrap_or("no-mesher-registered");
    for (file, needle) in BAD_INPUTS {
        let path = format!("tests/fixtures/io/{file}");
        assert_refused(
            &["mesh", &path, "--mesher", mesher, "-o", "/dev/null/x"],
            needle,
        );
    }
}

#[test]
fn verify_refuses_each_malformed_input_naming_file_and_line() {
    for (file, needle) in BAD_INPUTS {
        let path = format!("tests/fixtures/io/{file}");
        assert_refused(
            &[
                "verify",
                "tests/fixtures/broken/right_angle_exactly_90",
                "--input",
                &path,
            ],
            needle,
        );
    }
}

#[test]
fn an_unknown_mesher_or_format_is_a_usage_error() {
    assert_refused(
        &[
            "mesh",
            "datasets/plane-100.node",
            "--mesher",
            "nope",
            "-o",
            "/tmp/x",
        ],
        "unknown mesher 'nope'",
    );
    assert_refused(
        &["mesh", "close-pair", "--mesher", "nope", "-o", "/tmp/x"],
        "nope",
    );
    assert_refused(&["verify"], "<MESH>");
}

#[test]
fn a_mangled_mesh_file_is_refused_with_its_line() {
    assert_refused(
        &["verify", "tests/fixtures/io/missing_corner"],
        "missing_corner.ele:",
    );
}

#[test]
fn datasets_regenerates_the_committed_files_byte_for_byte() {
    let dir = std::env::temp_dir().join(format!("hexmesh-datasets-{}", std::process::id()));
    let out = hexmesh(&["datasets", "--out", dir.to_str().expect("utf-8 temp dir")]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let small = hexmesh::datasets::SMALL.iter();
    for name in small.chain(hexmesh::datasets::PSLG_EXAMPLES) {
        let file = hexmesh::datasets::file_name(name).expect("dataset file name");
        let fresh = std::fs::read(dir.join(&file)).expect("written");
        let committed = std::fs::read(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("datasets")
                .join(&file),
        )
        .expect("committed dataset");
        assert!(
            fresh == committed,
            "datasets/{file} differs from what `hexmesh datasets` writes"
        );
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn max_angle_refuses_each_malformed_input_naming_file_and_line() {
    for (file, needle) in BAD_INPUTS {
        let path = format!("tests/fixtures/io/{file}");
        assert_refused(&["max-angle", &path, "--mesher", "spade"], needle);
    }
}

#[test]
fn every_reference_refuses_each_malformed_input_before_it_runs() {
    for mesher in ["cgal", "cgal-conforming", "triangle", "spade"] {
        for (file, needle) in BAD_INPUTS {
            let path = format!("tests/fixtures/io/{file}");
            assert_refused(
                &["mesh", &path, "--mesher", mesher, "-o", "/dev/null/x"],
                needle,
            );
        }
    }
}

#[test]
fn report_fuzz_and_datasets_refuse_bad_arguments() {
    let out = std::env::temp_dir().join(format!("hexmesh-bad-args-{}", std::process::id()));
    let o = out.to_str().expect("utf-8 temp dir");
    assert_refused(
        &["report", "--datasets", "no-such-set", "--out", o],
        "unknown dataset 'no-such-set'",
    );
    assert_refused(
        &["report", "--meshers", "nope", "--out", o],
        "unknown mesher 'nope'",
    );
    assert_refused(&["report", "--runs", "0", "--out", o], "--runs");
    assert_refused(&["report", "--timeout", "0", "--out", o], "--timeout");
    assert!(!out.exists(), "a refused report created {o}");
    assert_refused(&["fuzz", "--mesher", "nope", "--cases", "1"], "nope");
    assert_refused(&["fuzz", "--mesher", "spade", "--cases", "0"], "--cases");
    // Triangle can end the process the campaign runs in.
    assert_refused(
        &["fuzz", "--mesher", "triangle", "--cases", "1"],
        "Triangle can exit",
    );
    // --out naming a file, not a directory.
    assert_refused(
        &["datasets", "--out", "tests/fixtures/io/empty.node"],
        "empty.node",
    );
    assert_refused(
        &[
            "max-angle",
            "close-pair",
            "--mesher",
            "spade",
            "--step",
            "0",
        ],
        "--step",
    );
    assert_refused(
        &[
            "mesh",
            "close-pair",
            "--mesher",
            "spade",
            "--min-angle",
            "NaN",
            "-o",
            o,
        ],
        "--min-angle",
    );
}
