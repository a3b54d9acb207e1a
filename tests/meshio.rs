//! Python users read our VTK and Gmsh files (`hexmesh mesh --format vtk,msh`) with meshio:
//! meshio must see our vertex and triangle counts, our exact coordinates and our triangles.
//! The interpreter comes from HEXMESH_PYTHON (set by the Makefile), else the crate's `.venv`.

use std::path::{Path, PathBuf};
use std::process::Command;

use hexmesh::io::{write_mesh, Format};
use hexmesh::TriMesh;

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

/// A small mesh with awkward coordinates: negative zero, a tiny value, thirds, a large x.
fn mesh() -> TriMesh {
    TriMesh {
        vertices: vec![
            [0.0, -0.0],
            [1.0, 0.0],
            [1.0 / 3.0, 0.9],
            [-0.5, 1e-12],
            [1.25e5, 2.0 / 3.0],
        ],
        triangles: vec![[0, 1, 2], [3, 0, 2], [1, 4, 2]],
    }
}

/// Runs meshio on `path`; returns (points, triangle count) as meshio sees them. Coordinates
/// travel as hex float bit patterns so the comparison is exact.
fn meshio_read(path: &Path) -> (Vec<[u64; 3]>, usize, Vec<[u32; 3]>) {
    let script = "import sys, struct, meshio\n\
                  m = meshio.read(sys.argv[1])\n\
                  print('counts', len(m.points), sum(len(c.data) for c in m.cells if c.type == 'triangle'))\n\
                  for p in m.points:\n\
                  \x20   print('point', ' '.join(struct.pack('>d', float(v)).hex() for v in p))\n\
                  for c in m.cells:\n\
                  \x20   for t in (c.data if c.type == 'triangle' else []):\n\
                  \x20       print('tri', *(int(v) for v in t))\n";
    let out = Command::new(python())
        .arg("-c")
        .arg(script)
        .arg(path)
        .output()
        .expect("run python");
    assert!(
        out.status.success(),
        "meshio failed on {}: {}",
        path.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    // meshio may print its own lines (a blank line before reading msh): keep only ours.
    let text = String::from_utf8(out.stdout).expect("utf-8");
    let counts: Vec<usize> = text
        .lines()
        .find_map(|l| l.strip_prefix("counts "))
        .expect("counts line")
        .split_whitespace()
        .map(|t| t.parse().expect("count"))
        .collect();
    let points: Vec<[u64; 3]> = text
        .lines()
        .filter_map(|l| l.strip_prefix("point "))
        .map(|l| {
            let v: Vec<u64> = l
                .split_whitespace()
                .map(|h| u64::from_str_radix(h, 16).expect("hex"))
                .collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    let triangles: Vec<[u32; 3]> = text
        .lines()
        .filter_map(|l| l.strip_prefix("tri "))
        .map(|l| {
            let v: Vec<u32> = l
                .split_whitespace()
                .map(|t| t.parse().expect("corner"))
                .collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    assert_eq!(counts[0], points.len());
    (points, counts[1], triangles)
}

fn check_format(format: Format, extension: &str) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("meshio");
    std::fs::create_dir_all(&dir).expect("dir");
    let mesh = mesh();
    let prefix = dir.join(format!("small-{extension}"));
    let written = write_mesh(&prefix, &mesh, &[format]).expect("write");
    assert_eq!(written.len(), 1);
    let (points, count, triangles) = meshio_read(&written[0]);
    assert_eq!(points.len(), mesh.vertices.len());
    assert_eq!(count, mesh.triangles.len());
    // meshio is 0-based: the 1-based Gmsh tags must come back as our indices.
    assert_eq!(triangles, mesh.triangles);
    for (ours, theirs) in mesh.vertices.iter().zip(&points) {
        // meshio turns "-0.0" into -0.0 too; z is 0.
        assert_eq!(
            [ours[0].to_bits(), ours[1].to_bits(), 0f64.to_bits()],
            *theirs
        );
    }
}

#[test]
fn meshio_reads_our_vtk_with_our_counts_coordinates_and_triangles() {
    check_format(Format::Vtk, "vtk");
}

#[test]
fn meshio_reads_our_msh_with_our_counts_coordinates_and_triangles() {
    check_format(Format::Msh, "msh");
}
