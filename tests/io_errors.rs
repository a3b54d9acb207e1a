//! Every malformed input in tests/fixtures/io/ (named after its defect) is refused with the
//! right kind of error, the right file and the right line, never a panic.

use std::path::{Path, PathBuf};

use hexmesh::io::{read_input, read_mesh};
use hexmesh::{Error, InputError};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/io")
        .join(name)
}

/// The parse error's file name and line, and its message.
fn parse_error(e: Error) -> (String, usize, String) {
    match e {
        Error::Parse {
            path,
            line,
            message,
        } => (file_name(&path), line, message),
        other => panic!("expected Error::Parse, got {other:?}"),
    }
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn input_parse_error(name: &str) -> (String, usize, String) {
    parse_error(read_input(&fixture(name)).expect_err("malformed input accepted"))
}

#[test]
fn empty_file_is_a_parse_error_at_line_1() {
    let (file, line, message) = input_parse_error("empty.node");
    assert_eq!((file.as_str(), line), ("empty.node", 1));
    assert!(message.contains("empty"), "{message}");
}

#[test]
fn a_file_of_comments_only_is_empty() {
    let (_, line, message) = input_parse_error("only_comments.node");
    assert_eq!(line, 2);
    assert!(message.contains("empty"), "{message}");
}

#[test]
fn fewer_rows_than_the_header_says_fail_where_the_file_ends() {
    let (_, line, message) = input_parse_error("short_rows.node");
    assert_eq!(line, 5);
    assert!(message.contains("point 4 of the 4"), "{message}");
    assert!(message.contains("line 2"), "{message}");
}

#[test]
fn a_non_numeric_token_is_refused_at_its_line() {
    let (_, line, message) = input_parse_error("non_numeric.node");
    assert_eq!(line, 3);
    assert!(message.contains("'abc'"), "{message}");
}

#[test]
fn nan_and_infinite_coordinates_are_refused_at_their_lines() {
    let (_, line, message) = input_parse_error("nan_coordinate.node");
    assert_eq!(line, 4);
    assert!(message.contains("NaN and infinite"), "{message}");
    let (_, line, _) = input_parse_error("inf_coordinate.node");
    assert_eq!(line, 4);
}

#[test]
fn a_row_with_the_wrong_number_of_fields_is_refused() {
    let (_, line, message) = input_parse_error("wrong_token_count.node");
    assert_eq!(line, 3);
    assert!(message.contains("expected 3 fields"), "{message}");
}

#[test]
fn a_negative_count_is_refused() {
    let (_, line, message) = input_parse_error("negative_count.node");
    assert_eq!(line, 1);
    assert!(message.contains("negative"), "{message}");
}

#[test]
fn a_huge_header_count_is_a_short_file_not_an_allocation() {
    let (_, line, _) = input_parse_error("huge_count.node");
    assert_eq!(line, 3);
}

#[test]
fn numbering_must_start_at_0_or_1() {
    let (_, line, _) = input_parse_error("first_index_2.node");
    assert_eq!(line, 2);
}

#[test]
fn duplicate_points_are_refused_naming_both_lines() {
    let (file, line, message) = input_parse_error("duplicate_points.node");
    assert_eq!((file.as_str(), line), ("duplicate_points.node", 6));
    assert!(message.contains("line 3"), "{message}");
    assert!(message.contains("point 4 duplicates point 1"), "{message}");
}

#[test]
fn a_segment_naming_a_missing_vertex_fails_at_its_line() {
    let (_, line, message) = input_parse_error("missing_vertex.poly");
    assert_eq!(line, 9);
    assert!(message.contains("vertex 9"), "{message}");
}

#[test]
fn a_missing_segment_section_is_reported_at_the_end() {
    let (_, line, message) = input_parse_error("missing_segments.poly");
    assert_eq!(line, 5);
    assert!(message.contains("segment header"), "{message}");
}

#[test]
fn a_nan_hole_is_refused_at_its_line() {
    let (_, line, _) = input_parse_error("nan_hole.poly");
    assert_eq!(line, 10);
}

fn input_error(name: &str) -> (String, Option<usize>, InputError) {
    match read_input(&fixture(name)).expect_err("bad input accepted") {
        Error::Input {
            path,
            line,
            problem,
            ..
        } => (
            path.as_deref().map(file_name).unwrap_or_default(),
            line,
            problem,
        ),
        other => panic!("expected Error::Input, got {other:?}"),
    }
}

#[test]
fn crossing_segments_are_an_input_error_at_the_later_segment() {
    let (file, line, problem) = input_error("crossing_segments.poly");
    assert_eq!((file.as_str(), line), ("crossing_segments.poly", Some(9)));
    assert_eq!(
        problem,
        InputError::CrossingSegments {
            first: 0,
            second: 1
        }
    );
}

#[test]
fn a_segment_from_a_vertex_to_itself_is_refused_at_its_line() {
    let (_, line, problem) = input_error("degenerate_segment.poly");
    assert_eq!(line, Some(7));
    assert_eq!(problem, InputError::DegenerateSegment { segment: 1 });
}

#[test]
fn a_point_inside_a_segment_is_refused_at_the_segment() {
    let (_, line, problem) = input_error("point_on_segment.poly");
    assert_eq!(line, Some(6));
    assert_eq!(
        problem,
        InputError::PointOnSegment {
            point: 2,
            segment: 0
        }
    );
}

#[test]
fn an_unknown_extension_is_refused_by_name() {
    let (file, _, message) = input_parse_error("unknown_extension.txt");
    assert_eq!(file, "unknown_extension.txt");
    assert!(
        message.contains(".node") && message.contains(".poly"),
        "{message}"
    );
}

#[test]
fn a_missing_file_is_an_io_error_naming_it() {
    let e = read_input(&fixture("no_such_file.node")).expect_err("missing file");
    assert!(matches!(e, Error::Io { .. }), "{e:?}");
    assert!(e.to_string().contains("no_such_file.node"), "{e}");
}

#[test]
fn six_node_triangles_are_refused_with_a_clear_error() {
    let (file, line, message) =
        parse_error(read_mesh(&fixture("six_node")).expect_err("6-node triangles accepted"));
    assert_eq!((file.as_str(), line), ("six_node.ele", 1));
    assert!(message.contains("6-node"), "{message}");
}

#[test]
fn a_triangle_naming_a_missing_vertex_fails_at_its_ele_line() {
    let (file, line, message) =
        parse_error(read_mesh(&fixture("missing_corner")).expect_err("missing corner"));
    assert_eq!((file.as_str(), line), ("missing_corner.ele", 4));
    assert!(message.contains("vertex 5"), "{message}");
}

#[test]
fn display_names_the_file_and_the_line() {
    let e = read_input(&fixture("nan_coordinate.node")).expect_err("nan accepted");
    let text = e.to_string();
    assert!(text.contains("nan_coordinate.node:4:"), "{text}");
    let e = read_input(&fixture("crossing_segments.poly")).expect_err("crossing accepted");
    let text = e.to_string();
    assert!(text.contains("crossing_segments.poly:9:"), "{text}");
    assert!(text.contains("cross"), "{text}");
}

#[test]
fn a_header_with_no_points_is_an_empty_input() {
    let (file, line, problem) = input_error("no_points.node");
    assert_eq!((file.as_str(), line), ("no_points.node", None));
    assert_eq!(problem, InputError::Empty);
}

#[test]
fn coordinates_too_large_to_square_are_refused_at_their_line() {
    let (_, line, problem) = input_error("huge_coordinate.node");
    assert_eq!(line, Some(3));
    assert!(matches!(problem, InputError::Range { .. }), "{problem:?}");
}

#[test]
fn a_poly_without_points_and_without_a_node_file_says_where_it_looked() {
    let (file, _, message) = input_parse_error("orphan.poly");
    assert_eq!(file, "orphan.poly");
    assert!(message.contains("orphan.node"), "{message}");
}

mod never_panics {
    use super::*;
    use hexmesh::io::{parse_ele, parse_node, parse_poly};
    use proptest::prelude::*;

    /// Text made of the pieces Triangle files are made of, in any order: the parsers must
    /// answer every such file with a value or an error, never a panic.
    fn triangle_like_text() -> impl Strategy<Value = String> {
        let token = prop_oneof![
            Just("0".to_string()),
            Just("1".to_string()),
            Just("2".to_string()),
            Just("3".to_string()),
            Just("6".to_string()),
            Just("-1".to_string()),
            Just("4294967296".to_string()),
            Just("99999999999999999999".to_string()),
            Just("0.5".to_string()),
            Just("-0.0".to_string()),
            Just("nan".to_string()),
            Just("inf".to_string()),
            Just("1e400".to_string()),
            Just("x".to_string()),
            Just("#".to_string()),
            Just("# hexmesh: hexagon 0 0 1".to_string()),
            Just("\n".to_string()),
            Just("\r\n".to_string()),
            Just("\t".to_string()),
        ];
        prop::collection::vec(token, 0..60).prop_map(|t| t.join(" "))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        #[test]
        fn parsers_return_errors_instead_of_panicking(text in triangle_like_text()) {
            let _ = parse_node(Path::new("f.node"), &text);
            let _ = parse_poly(Path::new("f.poly"), &text);
            let _ = parse_ele(Path::new("f.ele"), &text);
        }

        #[test]
        fn parse_errors_carry_a_line_inside_the_file(text in triangle_like_text()) {
            let lines = text.lines().count().max(1);
            for result in [
                parse_node(Path::new("f.node"), &text).err(),
                parse_poly(Path::new("f.poly"), &text).err(),
                parse_ele(Path::new("f.ele"), &text).err(),
            ] {
                if let Some(Error::Parse { line, .. }) = result {
                    prop_assert!(line >= 1 && line <= lines, "line {} of {}", line, lines);
                }
            }
        }
    }
}

#[test]
fn input_errors_count_points_and_segments_as_the_file_does() {
    // crossing_segments.poly numbers from 1: its segments 1 and 2 cross.
    let text = read_input(&fixture("crossing_segments.poly"))
        .expect_err("crossing accepted")
        .to_string();
    assert!(text.contains("segments 1 and 2 cross"), "{text}");
    // The same square numbered from 0.
    let text = read_input(&fixture("crossing_segments_0_based.poly"))
        .expect_err("crossing accepted")
        .to_string();
    assert!(text.contains("crossing_segments_0_based.poly:9:"), "{text}");
    assert!(text.contains("segments 0 and 1 cross"), "{text}");
    // point_on_segment.poly: point 3 (1, 0) lies inside segment 1.
    let text = read_input(&fixture("point_on_segment.poly"))
        .expect_err("point on segment accepted")
        .to_string();
    assert!(
        text.contains("point 3 lies inside segment 1 without"),
        "{text}"
    );
    let text = read_input(&fixture("degenerate_segment.poly"))
        .expect_err("degenerate segment accepted")
        .to_string();
    assert!(
        text.contains("segment 2 joins a vertex to itself"),
        "{text}"
    );
}

#[test]
fn a_point_outside_the_given_hexagon_is_refused_at_its_line() {
    let (file, line, problem) = input_error("outside_given_hexagon.node");
    assert_eq!(
        (file.as_str(), line),
        ("outside_given_hexagon.node", Some(5))
    );
    assert!(
        matches!(
            problem,
            InputError::OutsideHexagon {
                index: 1,
                fitted: false,
                ..
            }
        ),
        "{problem:?}"
    );
    let text = read_input(&fixture("outside_given_hexagon.node"))
        .expect_err("outside accepted")
        .to_string();
    assert!(text.contains("point 2 (5.0, 5.0)"), "{text}");
}

/// Two points one ulp apart: once refused on reading (their fitted hexagon rounded onto them),
/// they now get a fitted hexagon (`Hexagon::fitted` grows it until its corners move), and
/// `hexmesh mesh` refuses them, naming both points by their lines.
#[test]
fn points_one_ulp_apart_are_refused_by_the_mesher_at_their_lines() {
    let path = fixture("points_one_ulp_apart.node");
    assert!(read_input(&path).is_ok());
    let dir = std::env::temp_dir().join(format!("hexmesh-ulp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    for mesher in ["hex", "hex-simple", "rhomb"] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_hexmesh"))
            .arg("mesh")
            .arg(&path)
            .args(["--mesher", mesher, "-o"])
            .arg(dir.join("out"))
            .output()
            .expect("run hexmesh");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{mesher}: {err}");
        assert!(
            err.contains("points_one_ulp_apart.node:5:")
                && err.contains("points 1 and 2")
                && err.contains("line 4"),
            "{mesher}: {err}"
        );
        assert!(!dir.join("out.node").exists(), "{mesher}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
