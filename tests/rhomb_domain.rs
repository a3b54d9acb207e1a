//! `rhomb` on polygonal domains (paper 001 Sec. 3–5), through the command line and the
//! datasets: what the paper does not allow is refused naming the file and line of the
//! segment or point, and every permitted example (the PSLG examples and imr) is meshed within
//! the domain promise.

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
fn every_permitted_example_and_imr_are_meshed_within_the_domain_promise() {
    let bounds = hexmesh::registry::bounds("rhomb").unwrap();
    let mut names: Vec<&str> = PSLG_EXAMPLES.to_vec();
    names.push("imr");
    for name in names {
        let input = by_name(name).unwrap();
        let run = Rhomb.mesh(&input, &Params::default());
        if name == "pslg-slit" {
            let err = run.unwrap_err().to_string();
            assert!(err.contains("segment 4 ends at point 4"), "{name}: {err}");
            continue;
        }
        let run = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        // Valid, conforming, every angle in [30°, 90°] but at input corners sharper than
        // 30° taken whole (pslg-wedge-5's 5° corner), and input point i as vertex i.
        let verdict = hexmesh::quality::verdict(&run.mesh, Some(&input), Some(&bounds));
        assert!(verdict.passed(), "{name}: {verdict}");
        for (i, p) in input.points.iter().enumerate() {
            assert_eq!(run.mesh.vertices[i], *p, "{name}: input point {i}");
        }
    }
}
