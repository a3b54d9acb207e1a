//! `hexmesh mesh -o` loses no data: it refuses to write over an input file, however the path
//! is spelled, and its output files appear all together or not at all.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Five points in general position: `hex` meshes them in milliseconds.
const POINTS: &str = "# five points\n5 2 0 0\n1 0 0\n2 1 0\n3 0 1\n4 1 1\n5 0.4 0.6\n";

/// A fresh directory for one test under cargo's per-target scratch space.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("cli_outputs")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// Runs `hexmesh` in `dir`, so that relative paths are relative to it.
fn hexmesh(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hexmesh"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("hexmesh runs")
}

fn text(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr)
}

/// The names in `dir`, hidden ones included.
fn names(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .expect("list dir")
        .map(|e| {
            e.expect("dir entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect()
}

fn set(names: &[&str]) -> BTreeSet<String> {
    names.iter().map(|s| s.to_string()).collect()
}

fn write(path: &Path, text: &str) {
    std::fs::write(path, text).expect("write fixture");
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Asserts that `args` exit 2 naming `named`, and that `dir` still holds exactly `expected`
/// with `input` unchanged.
fn assert_refused(dir: &Path, args: &[&str], named: &str, expected: &BTreeSet<String>) {
    let out = hexmesh(dir, args);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {}", text(&out));
    let shown = text(&out);
    assert!(
        shown.contains("refusing to write") && shown.contains(named),
        "{args:?}: {shown}"
    );
    assert_eq!(&names(dir), expected, "{args:?}");
}

#[test]
fn mesh_refuses_an_output_prefix_naming_the_input_and_leaves_it_unchanged() {
    let dir = scratch("refuses_input");
    write(&dir.join("pts.node"), POINTS);
    let before = set(&["pts.node"]);
    assert_refused(
        &dir,
        &["mesh", "pts.node", "--mesher", "hex", "-o", "pts"],
        "pts.node",
        &before,
    );
    // The input is also protected among other formats, and as the --hexagons picture.
    let args = [
        "mesh", "pts.node", "--mesher", "hex", "-o", "pts", "--format", "vtk,node",
    ];
    assert_refused(&dir, &args, "pts.node", &before);
    let args = [
        "mesh",
        "pts.node",
        "--mesher",
        "hex",
        "-o",
        "m",
        "--hexagons",
        "pts.node",
    ];
    assert_refused(&dir, &args, "pts.node", &before);
    assert_eq!(read(&dir.join("pts.node")), POINTS);
}

#[test]
fn mesh_refuses_the_input_under_another_spelling_or_through_a_link() {
    let dir = scratch("refuses_spellings");
    write(&dir.join("pts.node"), POINTS);
    std::fs::create_dir(dir.join("sub")).expect("sub dir");
    std::os::unix::fs::symlink("pts.node", dir.join("soft.node")).expect("symlink");
    std::fs::hard_link(dir.join("pts.node"), dir.join("hard.node")).expect("hard link");
    let before = set(&["pts.node", "sub", "soft.node", "hard.node"]);
    let absolute = dir.join("pts").to_string_lossy().into_owned();
    for (input, prefix) in [
        ("./pts.node", "pts"),
        ("pts.node", "./pts"),
        ("pts.node", "sub/../pts"),
        ("sub/../pts.node", absolute.as_str()),
        ("pts.node", "soft"),
        ("soft.node", "pts"),
        ("pts.node", "hard"),
    ] {
        let named = format!("{prefix}.node");
        let args = ["mesh", input, "--mesher", "hex", "-o", prefix];
        assert_refused(&dir, &args, &named, &before);
    }
    assert_eq!(read(&dir.join("pts.node")), POINTS);
    let soft = std::fs::read_link(dir.join("soft.node")).expect("still a symlink");
    assert_eq!(soft, Path::new("pts.node"));
}

#[test]
fn mesh_refuses_the_node_file_a_poly_input_reads_its_points_from() {
    let dir = scratch("refuses_poly_node");
    let nodes = "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n";
    let poly = "0 2 0 0\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n";
    write(&dir.join("box.node"), nodes);
    write(&dir.join("box.poly"), poly);
    let before = set(&["box.node", "box.poly"]);
    let args = ["mesh", "box.poly", "--mesher", "hex", "-o", "box"];
    assert_refused(&dir, &args, "box.node", &before);
    assert_eq!(read(&dir.join("box.node")), nodes);
    assert_eq!(read(&dir.join("box.poly")), poly);
}

#[test]
fn a_poly_input_with_its_own_points_may_replace_the_node_file_beside_it() {
    let dir = scratch("poly_own_points");
    let poly = "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n";
    write(&dir.join("box.poly"), poly);
    write(&dir.join("box.node"), "an earlier run's output\n");
    let out = hexmesh(&dir, &["mesh", "box.poly", "--mesher", "hex", "-o", "box"]);
    assert!(out.status.success(), "{}", text(&out));
    assert_eq!(names(&dir), set(&["box.poly", "box.node", "box.ele"]));
    assert_eq!(read(&dir.join("box.poly")), poly);
    let mesh = hexmesh::io::read_mesh(&dir.join("box")).expect("the new mesh reads back");
    assert!(mesh.vertices.len() >= 4, "{mesh:?}");
}

#[test]
fn a_failing_later_format_creates_no_output_file_and_leaves_no_temporaries() {
    let dir = scratch("failing_format_fresh");
    write(&dir.join("pts.node"), POINTS);
    // A directory where the last file goes: every file is written, and its rename fails.
    std::fs::create_dir(dir.join("m.svg")).expect("dir in the way");
    let before = names(&dir);
    let args = ["mesh", "pts.node", "--mesher", "hex", "-o", "m"];
    let out = hexmesh(
        &dir,
        &[&args[..], &["--format", "node,vtk,msh,svg"]].concat(),
    );
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    assert!(text(&out).contains("m.svg"), "{}", text(&out));
    assert_eq!(names(&dir), before);
    assert!(
        out.stdout.is_empty(),
        "no file is listed as written: {}",
        text(&out)
    );
}

#[test]
fn a_failing_later_format_leaves_the_outputs_of_an_earlier_run_untouched() {
    let dir = scratch("failing_format_earlier_run");
    write(&dir.join("pts.node"), POINTS);
    let earlier = ["m.node", "m.ele", "m.vtk", "m.msh"];
    for name in earlier {
        write(&dir.join(name), &format!("earlier {name}\n"));
    }
    std::fs::create_dir(dir.join("m.svg")).expect("dir in the way");
    std::fs::hard_link(dir.join("m.node"), dir.join("other-link.node")).expect("hard link");
    let before = names(&dir);
    let args = ["mesh", "pts.node", "--mesher", "hex", "-o", "m"];
    let out = hexmesh(
        &dir,
        &[&args[..], &["--format", "node,vtk,msh,svg"]].concat(),
    );
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    assert!(text(&out).contains("m.svg"), "{}", text(&out));
    assert_eq!(names(&dir), before);
    for name in earlier {
        assert_eq!(read(&dir.join(name)), format!("earlier {name}\n"), "{name}");
    }
    assert_eq!(read(&dir.join("other-link.node")), "earlier m.node\n");
    assert_eq!(read(&dir.join("pts.node")), POINTS);
}

#[test]
fn a_normal_run_writes_every_requested_file_and_leaves_no_temporaries() {
    let dir = scratch("normal_run");
    write(&dir.join("pts.node"), POINTS);
    write(&dir.join("m.node"), "an earlier run's output\n");
    let args = ["mesh", "pts.node", "--mesher", "hex", "-o", "m", "--format"];
    let out = hexmesh(&dir, &[&args[..], &["node,vtk,msh,svg"]].concat());
    assert!(out.status.success(), "{}", text(&out));
    let files = ["m.node", "m.ele", "m.vtk", "m.msh", "m.svg"];
    let listed: Vec<String> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(String::from)
        .collect();
    assert_eq!(listed, files);
    assert_eq!(
        names(&dir),
        set(&[&["pts.node"][..], &files[..]].concat()),
        "exactly the input and the outputs"
    );
    assert_eq!(read(&dir.join("pts.node")), POINTS);
    assert!(read(&dir.join("m.vtk")).starts_with("# vtk DataFile"));
    assert!(read(&dir.join("m.msh")).starts_with("$MeshFormat"));
    assert!(read(&dir.join("m.svg")).contains("<svg"));
    let mesh = hexmesh::io::read_mesh(&dir.join("m")).expect("the mesh reads back");
    assert!(mesh.vertices.len() >= 5 && !mesh.triangles.is_empty());
    let out = hexmesh(
        &dir,
        &["verify", "m", "--input", "pts.node", "--bounds", "hex"],
    );
    assert!(out.status.success(), "{}", text(&out));
}

#[test]
fn mesh_refuses_a_poly_output_naming_the_poly_input() {
    let dir = scratch("refuses_poly_output");
    let square =
        "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 1\n1 1 2 5\n2 2 3 5\n3 3 4 5\n4 4 1 5\n0\n";
    write(&dir.join("sq.poly"), square);
    let before = set(&["sq.poly"]);
    // `-o sq` with node alone writes sq.node and sq.ele, which the input does not read; with
    // poly it would also write sq.poly, the input itself.
    let args = [
        "mesh", "sq.poly", "--mesher", "saalfeld", "-o", "sq", "--format", "vtu,poly",
    ];
    assert_refused(&dir, &args, "sq.poly", &before);
    assert_eq!(read(&dir.join("sq.poly")), square);
}

#[test]
fn poly_and_vtu_formats_write_their_files_with_the_inputs_markers() {
    let dir = scratch("poly_vtu");
    let square =
        "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 1\n1 1 2 5\n2 2 3 6\n3 3 4 0\n4 4 1 5\n0\n";
    write(&dir.join("sq.poly"), square);
    let args = [
        "mesh", "sq.poly", "--mesher", "saalfeld", "-o", "m", "--format", "poly,vtu",
    ];
    let out = hexmesh(&dir, &args);
    assert!(out.status.success(), "{}", text(&out));
    let files = ["m.node", "m.ele", "m.poly", "m.edge", "m.vtu"];
    let listed: Vec<String> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(String::from)
        .collect();
    assert_eq!(listed, files);
    assert_eq!(names(&dir), set(&[&["sq.poly"][..], &files[..]].concat()));
    assert!(read(&dir.join("m.node")).starts_with("4 2 0 1\n1 0.0 0.0 5\n"));
    // Saalfeld keeps the square as it is: the four sides with their markers, the third
    // (marker 0 in the input) on the boundary, so 1.
    let poly = read(&dir.join("m.poly"));
    assert!(poly.starts_with("0 2 0 1\n4 1\n"), "{poly}");
    let mut markers: Vec<&str> = poly
        .lines()
        .skip(2)
        .take(4)
        .map(|l| l.rsplit(' ').next().unwrap_or(""))
        .collect();
    markers.sort_unstable();
    assert_eq!(markers, ["1", "5", "5", "6"]);
    let vtu = std::fs::read(dir.join("m.vtu")).expect("vtu");
    assert!(vtu.starts_with(b"<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\""));
    // The output .poly and .node read back as a valid input.
    let back = hexmesh::io::read_input(&dir.join("m.poly")).expect("the output .poly reads");
    assert_eq!(back.segments.len(), 4);
    assert_eq!(
        back.labels.segment_markers.as_deref().map(<[i64]>::len),
        Some(4)
    );
}
