//! `hexmesh verify` on meshes made elsewhere: Gmsh's `.msh` (4.1 binary, 2.2 ASCII, and the
//! other two encodings) and meshio's `.vtu` (binary, zlib-compressed), `.vtk` and `.msh` must
//! get the same verdict, the same counts and the same angles as the same mesh written as
//! Triangle's `.node`/`.ele` by the library: the whole `verify --json` output is compared.
//!
//! Gmsh comes from PATH (`make deps` installs Debian's `gmsh`); without it those tests print a
//! note and pass. Python with meshio comes from HEXMESH_PYTHON (set by the Makefile), else the
//! crate's `.venv`, as in tests/meshio.rs.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use hexmesh::io::{read_any_mesh, write_mesh, Format};

fn hexmesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hexmesh"))
        .args(args)
        .output()
        .expect("hexmesh runs")
}

/// A fresh directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("verify_foreign")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// `hexmesh verify PATH --json [extra]`: (exit code, stdout), after checking that it did not
/// fail on its input (exit 2).
fn verify_json(path: &Path, extra: &[&str]) -> (i32, String) {
    let mut args = vec!["verify", path.to_str().expect("utf-8 path"), "--json"];
    args.extend_from_slice(extra);
    let out = hexmesh(&args);
    let code = out.status.code().expect("exit code");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        code == 0 || code == 1,
        "verify {} exits {code}: {stderr}",
        path.display()
    );
    (code, String::from_utf8(out.stdout).expect("utf-8"))
}

/// A number from the JSON text: the first `"key": value` after `after`.
fn json_number(json: &str, after: &str, key: &str) -> f64 {
    let from = json
        .find(after)
        .unwrap_or_else(|| panic!("no {after} in {json}"));
    let rest = &json[from..];
    let at = rest.find(&format!("\"{key}\": ")).expect("key") + key.len() + 4;
    rest[at..]
        .split([',', '\n', '}'])
        .next()
        .expect("value")
        .trim()
        .parse()
        .expect("a number")
}

/// Verify on `foreign` and on the `.node`/`.ele` the library writes of what it reads from
/// `foreign` agree on everything, with no bounds and with two sets of bounds. Returns the
/// number of vertices and triangles read.
fn agrees_with_node_ele(foreign: &Path) -> (usize, usize) {
    let loaded = read_any_mesh(foreign).unwrap_or_else(|e| panic!("{e}"));
    let prefix = foreign.with_extension("");
    let prefix = prefix.with_file_name(format!(
        "{}-as-node",
        prefix.file_name().expect("name").to_string_lossy()
    ));
    write_mesh(&prefix, &loaded.mesh, &[Format::Triangle]).expect("write .node/.ele");
    for bounds in [
        &[][..],
        &["--bounds", "delaunay"],
        &["--bounds", "min-angle=30"],
    ] {
        let (code, json) = verify_json(foreign, bounds);
        let (node_code, node_json) = verify_json(&prefix, bounds);
        // Everything but how messages number: the .node file counts from 1, VTK from 0.
        let findings = |text: &str| {
            let mut v: serde_json::Value = serde_json::from_str(text).expect("JSON");
            v.as_object_mut().expect("an object").remove("numbering");
            v
        };
        assert_eq!(
            (code, findings(&json)),
            (node_code, findings(&node_json)),
            "{} and its .node/.ele disagree with {bounds:?}",
            foreign.display()
        );
        let (n, m) = (loaded.mesh.vertices.len(), loaded.mesh.triangles.len());
        assert_eq!(json_number(&json, "\"metrics\"", "vertices"), n as f64);
        assert_eq!(json_number(&json, "\"metrics\"", "triangles"), m as f64);
        let min = json_number(&json, "\"min_angle\"", "value");
        let max = json_number(&json, "\"max_angle\"", "value");
        assert!(
            0.0 < min && min <= 60.0 && (60.0..180.0).contains(&max),
            "{min} {max}"
        );
    }
    (loaded.mesh.vertices.len(), loaded.mesh.triangles.len())
}

/// The unit square with a square hole, in Gmsh's own geometry language.
const SQUARE_WITH_HOLE: &str = "lc = 0.2;\n\
    Point(1) = {0, 0, 0, lc}; Point(2) = {1, 0, 0, lc};\n\
    Point(3) = {1, 1, 0, lc}; Point(4) = {0, 1, 0, lc};\n\
    Point(5) = {0.4, 0.4, 0, lc}; Point(6) = {0.6, 0.4, 0, lc};\n\
    Point(7) = {0.6, 0.6, 0, lc}; Point(8) = {0.4, 0.6, 0, lc};\n\
    Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n\
    Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};\n\
    Curve Loop(1) = {1, 2, 3, 4}; Curve Loop(2) = {5, 6, 7, 8};\n\
    Plane Surface(1) = {1, 2};\n";

fn gmsh_available() -> bool {
    let found = Command::new("gmsh")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        println!("note: gmsh is not on PATH (make deps installs it); skipping the Gmsh checks");
    }
    found
}

#[test]
fn gmsh_meshes_in_every_msh_encoding_verify_as_their_node_ele_copy() {
    if !gmsh_available() {
        return;
    }
    let dir = scratch("gmsh");
    let geo = dir.join("square.geo");
    std::fs::write(&geo, SQUARE_WITH_HOLE).expect("write .geo");
    let variants: [(&str, &[&str]); 5] = [
        ("msh41-binary", &["-format", "msh41", "-bin"]),
        ("msh22-ascii", &["-format", "msh22"]),
        ("msh41-ascii", &["-format", "msh41"]),
        ("msh22-binary", &["-format", "msh22", "-bin"]),
        (
            "msh41-parametric",
            &["-format", "msh41", "-setnumber", "Mesh.SaveParametric", "1"],
        ),
    ];
    let mut counts = Vec::new();
    for (name, options) in variants {
        let out = dir.join(format!("{name}.msh"));
        let status = Command::new("gmsh")
            .arg("-2")
            .arg(&geo)
            .args(options)
            .arg("-o")
            .arg(&out)
            .args(["-v", "0"])
            .status()
            .expect("gmsh runs");
        assert!(status.success(), "gmsh {options:?} failed");
        let (n, m) = agrees_with_node_ele(&out);
        // Gmsh's mesh of the holed square is valid: verify passes it.
        assert_eq!(verify_json(&out, &[]).0, 0, "{name}");
        counts.push((n, m));
    }
    // Every encoding holds the same mesh.
    assert!(counts.windows(2).all(|w| w[0] == w[1]), "{counts:?}");
    assert!(counts[0].1 > 20, "{counts:?}");
}

/// A Gmsh 2.2 file with sparse node tags, a clockwise triangle and a node no triangle uses:
/// the text output names the vertices and the triangle by position (from 1, as Gmsh counts),
/// then by the file's tags.
#[test]
fn verify_names_the_gmsh_tags_of_what_it_finds_wrong() {
    let dir = scratch("tags");
    let path = dir.join("flipped.msh");
    std::fs::write(
        &path,
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n\
         70 0 0 0\n9 1 0 0\n33 1 1 0\n5 0 1 0\n$EndNodes\n\
         $Elements\n2\n1 15 0 5\n205 2 0 70 33 9\n$EndElements\n",
    )
    .expect("write");
    let out = hexmesh(&["verify", path.to_str().expect("utf-8")]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(text.contains("clockwise"), "{text}");
    let note = text
        .lines()
        .find(|l| l.starts_with("vertices and triangles above are numbered from 1"))
        .unwrap_or_else(|| panic!("no tag note in {text}"));
    assert!(
        text.contains("vertex 4 at (0, 1) belongs to no triangle"),
        "{text}"
    );
    assert!(note.contains("vertex 4 is node 5"), "{note}");
    assert!(note.contains("vertex 3 is node 33"), "{note}");
    assert!(note.ends_with("triangle 1 is element 205"), "{note}");
}

/// A quadrangle in a .msh, a .vtk or a .vtu is refused with exit 2, naming the file.
#[test]
fn verify_refuses_quadrangles_in_every_format_with_exit_2() {
    let dir = scratch("quads");
    let files = [
        (
            "q.msh",
            "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n\
             0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n$Elements\n1 1 1 1\n2 1 3 1\n1 1 2 3 4\n\
             $EndElements\n",
        ),
        (
            "q.vtk",
            "# vtk DataFile Version 4.2\nq\nASCII\nDATASET UNSTRUCTURED_GRID\n\
             POINTS 4 double\n0 0 0 1 0 0 1 1 0 0 1 0\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n9\n",
        ),
        (
            "q.vtu",
            "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid>\
             <Piece NumberOfPoints=\"4\" NumberOfCells=\"1\"><Points>\
             <DataArray type=\"Float64\" NumberOfComponents=\"3\">0 0 0 1 0 0 1 1 0 0 1 0\
             </DataArray></Points><Cells>\
             <DataArray type=\"Int32\" Name=\"connectivity\">0 1 2 3</DataArray>\
             <DataArray type=\"Int32\" Name=\"offsets\">4</DataArray>\
             <DataArray type=\"UInt8\" Name=\"types\">9</DataArray>\
             </Cells></Piece></UnstructuredGrid></VTKFile>\n",
        ),
    ];
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::write(&path, text).expect("write");
        let out = hexmesh(&["verify", path.to_str().expect("utf-8")]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        assert!(stderr.contains(name), "{stderr}");
        assert!(stderr.contains("quadrangle"), "{stderr}");
    }
}

fn python() -> PathBuf {
    let candidates = std::env::var_os("HEXMESH_PYTHON")
        .map(PathBuf::from)
        .into_iter()
        .chain([Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv/bin/python")]);
    for candidate in candidates {
        if candidate.exists() {
            return candidate;
        }
    }
    panic!("no Python with meshio: set HEXMESH_PYTHON or run `make venv`");
}

/// A `hex` mesh of 40 seeded points with awkward coordinates, written as Gmsh 4.1 by the
/// library; meshio reads that and writes `.vtu` (its default: binary, zlib), `.vtk` (5.1
/// binary and ASCII, 4.2 binary) and Gmsh `.msh` (4.1 and 2.2, binary). Each must hold the
/// mesh bit for bit and verify as the `.node`/`.ele` of what it holds.
#[test]
fn meshio_vtu_and_vtk_files_verify_as_their_node_ele_copy() {
    let dir = scratch("meshio");
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let points: Vec<[f64; 2]> = (0..40)
        .map(|_| {
            let mut next = || {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 11) as f64 / (1u64 << 53) as f64
            };
            [next() * 3.0 - 1.0, next() / 3.0 + 1e3]
        })
        .collect();
    let mesh = hexmesh_core::mesh(points).expect("hex meshes the points");
    let prefix = dir.join("hex");
    write_mesh(&prefix, &mesh, &[Format::Msh]).expect("write .msh");
    let script = "import sys, meshio\n\
                  m = meshio.read(sys.argv[1])\n\
                  meshio.write(sys.argv[2] + '.vtu', m)\n\
                  meshio.write(sys.argv[2] + '.vtk', m)\n\
                  meshio.write(sys.argv[2] + '-ascii.vtk', m, binary=False)\n\
                  meshio.write(sys.argv[2] + '-42.vtk', m, file_format='vtk42')\n\
                  t = meshio.Mesh(m.points, [c for c in m.cells if c.type == 'triangle'])\n\
                  meshio.write(sys.argv[2] + '-41.msh', t, file_format='gmsh')\n\
                  meshio.write(sys.argv[2] + '-22.msh', t, file_format='gmsh22')\n";
    let out = Command::new(python())
        .args(["-c", script])
        .arg(prefix.with_extension("msh"))
        .arg(dir.join("meshio"))
        .output()
        .expect("run python");
    assert!(
        out.status.success(),
        "meshio failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let vtu = std::fs::read_to_string(dir.join("meshio.vtu")).expect("meshio wrote .vtu");
    assert!(vtu.contains("vtkZLibDataCompressor"), "not compressed");
    let names = [
        "meshio.vtu",
        "meshio.vtk",
        "meshio-ascii.vtk",
        "meshio-42.vtk",
        "meshio-41.msh",
        "meshio-22.msh",
    ];
    for name in names {
        let path = dir.join(name);
        let read = read_any_mesh(&path).unwrap_or_else(|e| panic!("{e}"));
        // Bit for bit the mesh hexmesh made.
        assert_eq!(read.mesh, mesh, "{name}");
        let (n, m) = agrees_with_node_ele(&path);
        assert_eq!((n, m), (mesh.vertices.len(), mesh.triangles.len()));
        assert_eq!(verify_json(&path, &["--bounds", "hex"]).0, 0, "{name}");
    }
}
