//! `hex-simple` on the committed datasets (`datasets/`) and on the regression
//! fixtures of tests/fixtures/hex, each named after what found it, read through `io`.

use std::path::{Path, PathBuf};

mod mesh_support;

use hexmesh::hex::HexSimple;
use hexmesh::{Mesher, Params};

fn check_file(path: &Path) {
    let input = hexmesh::io::read_input(path).unwrap_or_else(|e| panic!("{e}"));
    let run = HexSimple
        .mesh(&input, &Params::default())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    mesh_support::inputs_first(&run.mesh, &input.points)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let bounds = hexmesh::registry::bounds("hex-simple").unwrap();
    let v = hexmesh::quality::verdict(&run.mesh, Some(&input), Some(&bounds));
    assert!(v.passed(), "{}: {v}", path.display());
}

#[test]
fn the_committed_point_set_datasets_meet_the_simple_bounds() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("datasets");
    for name in [
        "close-pair.node",
        "line-100.node",
        "plane-100.node",
        "plane-1k.node",
        "plane-2k.node",
    ] {
        check_file(&dir.join(name));
    }
}

#[test]
fn every_hex_fixture_meets_the_simple_bounds() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/hex");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("fixture directory")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "node"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    for f in files {
        check_file(&f);
    }
}
