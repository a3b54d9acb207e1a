//! `rhomb` on polygonal domains (paper 001 Sec. 3–5), through the command line and the
//! datasets: what the paper does not allow is refused naming the file and line of the
//! segment or point, and every permitted example gets through the steps implemented so far.

use std::process::{Command, Output};

use hexmesh::datasets::{by_name, PSLG_EXAMPLES};
use hexmesh::mesher::{Mesher, Params};
use hexmesh::rhomb::Rhomb;

fn hexmesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hexmesh"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("hexmesh runs")
}

/// Each input the paper does not allow, with the `file:line` and words its refusal must name.
const REFUSED: &[(&str, &str, &str)] = &[
    ("slit.poly", "slit.poly:16:", "segment 5 ends at point 5"),
    (
        "unseeded_inner_square.poly",
        "unseeded_inner_square.poly:17:",
        "segment 5 has the domain on both sides",
    ),
    (
        "touching_squares.poly",
        "touching_squares.poly:16:",
        "segment 5 is the third of 4 segments at point 3",
    ),
    (
        "point_in_hole.poly",
        "point_in_hole.poly:12:",
        "point 9 lies outside the domain",
    ),
];

#[test]
fn what_the_paper_does_not_allow_is_refused_naming_file_and_line() {
    for (file, at, words) in REFUSED {
        let path = format!("tests/fixtures/rhomb-domain/{file}");
        let out = hexmesh(&["mesh", &path, "--mesher", "rhomb", "-o", "/dev/null/x"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{file}: {err}");
        assert!(err.contains(at) && err.contains(words), "{file}: {err}");
    }
}

#[test]
fn every_example_but_the_slit_is_a_permitted_domain_whose_quad_tree_is_built() {
    let mut names: Vec<&str> = PSLG_EXAMPLES.to_vec();
    names.push("imr");
    for name in names {
        let input = by_name(name).unwrap();
        let err = Rhomb
            .mesh(&input, &Params::default())
            .unwrap_err()
            .to_string();
        if name == "pslg-slit" {
            assert!(err.contains("segment 4 ends at point 4"), "{name}: {err}");
        } else {
            assert!(err.contains("rhombs after steps 1-3"), "{name}: {err}");
        }
    }
}
