//! Python users read our VTK, VTK XML and Gmsh files (`hexmesh mesh --format vtk,vtu,msh`)
//! with meshio: meshio must see our vertex and triangle counts, our exact coordinates and our
//! triangles, the Gmsh physical groups with every boundary and segment edge as a line, and the
//! VTK data arrays with our exact values. Gmsh itself must accept our `.msh` (`gmsh -check`)
//! when it is installed. The interpreter comes from HEXMESH_PYTHON (set by the Makefile),
//! else the crate's `.venv`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use hexmesh::io::{derive_boundary, write_mesh, write_mesh_with, Format};
use hexmesh::quality::triangle_shape;
use hexmesh::{Labels, Pslg, Region, TriMesh};

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

#[test]
fn meshio_reads_our_vtu_with_our_counts_coordinates_and_triangles() {
    check_format(Format::Vtu, "vtu");
}

/// A 3×3 square with a 1×1 square hole, eight triangles around it, its input with segment
/// markers (outer 5, hole 7 but one side 0) and one region.
fn ring() -> (TriMesh, Pslg) {
    let points = vec![
        [0.0, 0.0],
        [3.0, 0.0],
        [3.0, 3.0],
        [0.0, 3.0],
        [1.0, 1.0],
        [2.0, 1.0],
        [2.0, 2.0],
        [1.0, 2.0],
    ];
    let mesh = TriMesh {
        vertices: points.clone(),
        triangles: vec![
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
            [3, 0, 4],
            [3, 4, 7],
        ],
    };
    let ring = |b: u32| (0..4).map(move |k| [b + k, b + (k + 1) % 4]);
    let input = Pslg {
        points,
        segments: ring(0).chain(ring(4)).collect(),
        holes: vec![[1.5, 1.5]],
        labels: Labels {
            segment_markers: Some(vec![5, 5, 5, 5, 7, 7, 7, 0]),
            regions: vec![Region {
                point: [0.5, 0.5],
                attribute: 4.0,
                max_area: None,
            }],
            ..Labels::default()
        },
        ..Pslg::default()
    };
    (mesh, input)
}

/// What meshio sees in a file: its lines of `kind key rest…`, and what it printed on stderr.
fn meshio_report(path: &Path) -> (Vec<(String, String, String)>, String) {
    let script = "import sys, struct, meshio\n\
                  m = meshio.read(sys.argv[1])\n\
                  for name, (tag, dim) in m.field_data.items():\n\
                  \x20   print('group', name.replace(' ', '_'), dim)\n\
                  for name, sets in m.cell_sets.items():\n\
                  \x20   if name.startswith('gmsh:'): continue\n\
                  \x20   for block, idx in zip(m.cells, sets):\n\
                  \x20       print('set', name.replace(' ', '_') + '/' + block.type, 0 if idx is None else len(idx))\n\
                  for block in m.cells:\n\
                  \x20   print('block', block.type, len(block.data))\n\
                  for name, arrays in m.cell_data.items():\n\
                  \x20   for a in arrays:\n\
                  \x20       if name.startswith('gmsh:'): continue\n\
                  \x20       print('size', name, len(a), a.size)\n\
                  \x20       print('cell', name, ' '.join(struct.pack('>d', float(v)).hex() for v in a.ravel()))\n\
                  for name, a in m.point_data.items():\n\
                  \x20   if name.startswith('gmsh:'): continue\n\
                  \x20   print('size', name, len(a), a.size)\n\
                  \x20   print('point', name, ' '.join(str(int(v)) for v in a.ravel()))\n\
                  m.cell_sets_to_data()\n";
    let out = Command::new(python())
        .arg("-c")
        .arg(script)
        .arg(path)
        .output()
        .expect("run python");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        out.status.success(),
        "meshio failed on {}: {stderr}",
        path.display()
    );
    let lines = String::from_utf8(out.stdout)
        .expect("utf-8")
        .lines()
        .filter_map(|l| {
            let mut parts = l.splitn(3, ' ');
            let kind = parts.next()?;
            matches!(kind, "group" | "set" | "block" | "cell" | "point" | "size").then(|| {
                let key = parts.next().unwrap_or("").to_string();
                (
                    kind.to_string(),
                    key,
                    parts.next().unwrap_or("").to_string(),
                )
            })
        })
        .collect();
    (lines, stderr)
}

fn values(lines: &[(String, String, String)], kind: &str) -> BTreeMap<String, String> {
    lines
        .iter()
        .filter(|l| l.0 == kind)
        .map(|l| (l.1.clone(), l.2.clone()))
        .collect()
}

#[test]
fn meshio_reads_our_msh_physical_groups_with_every_boundary_and_segment_edge_as_a_line() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("meshio");
    std::fs::create_dir_all(&dir).expect("dir");
    let (mesh, input) = ring();
    let written =
        write_mesh_with(&dir.join("ring"), &mesh, Some(&input), &[Format::Msh]).expect("write");
    let (lines, stderr) = meshio_report(&written[0]);
    assert!(!stderr.contains("not part of any cell set"), "{stderr}");
    let groups = values(&lines, "group");
    let expected: BTreeMap<String, String> = [
        ("marker_1", "1"),
        ("marker_5", "1"),
        ("marker_7", "1"),
        ("outer_boundary", "1"),
        ("hole_1", "1"),
        ("domain", "2"),
        ("region_4", "2"),
    ]
    .iter()
    .map(|(k, v)| (k.to_string(), v.to_string()))
    .collect();
    assert_eq!(groups, expected);

    // Our count of boundary and segment edges is meshio's count of lines.
    let ours = derive_boundary(&mesh, Some(&input)).marked_edges().count();
    let lines_read: usize = lines
        .iter()
        .filter(|l| l.0 == "block" && l.1 == "line")
        .map(|l| l.2.parse::<usize>().expect("count"))
        .sum();
    assert_eq!((ours, lines_read), (8, 8));
    // Each group holds the cells it should, summed over meshio's blocks.
    let mut members: BTreeMap<String, usize> = BTreeMap::new();
    for l in lines.iter().filter(|l| l.0 == "set") {
        *members.entry(l.1.clone()).or_default() += l.2.parse::<usize>().expect("count");
    }
    for (set, count) in [
        ("marker_1/line", 1),
        ("marker_5/line", 4),
        ("marker_7/line", 3),
        ("outer_boundary/line", 4),
        ("hole_1/line", 4),
        ("domain/triangle", 8),
        ("region_4/triangle", 8),
        ("domain/line", 0),
        ("hole_1/triangle", 0),
    ] {
        assert_eq!(members.get(set).copied(), Some(count), "{set}: {members:?}");
    }
}

/// The bit patterns meshio printed for one array, as f64.
fn doubles(hex: &str) -> Vec<f64> {
    hex.split_whitespace()
        .map(|h| f64::from_bits(u64::from_str_radix(h, 16).expect("hex")))
        .collect()
}

#[test]
fn meshio_reads_our_vtk_and_vtu_cell_and_point_data_with_our_exact_values() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("meshio");
    std::fs::create_dir_all(&dir).expect("dir");
    let (mut mesh, mut input) = ring();
    // Awkward coordinates, so that the angles are not round numbers.
    mesh.vertices[5] = [2.0, 1.0 / 3.0 + 0.5];
    input.points[5] = mesh.vertices[5];
    input.labels.point_markers = Some(vec![0, 0, 0, 0, 0, -3_000_000_000, 0, 0]);
    let shapes: Vec<_> = mesh
        .triangles
        .iter()
        .map(|t| triangle_shape(t.map(|v| mesh.vertices[v as usize])))
        .collect();
    let min: Vec<f64> = shapes
        .iter()
        .map(|s| s.angles.iter().copied().fold(f64::INFINITY, f64::min))
        .collect();
    let max: Vec<f64> = shapes
        .iter()
        .map(|s| s.angles.iter().copied().fold(0.0, f64::max))
        .collect();
    let ratio: Vec<f64> = shapes.iter().map(|s| s.radius_ratio).collect();
    for format in [Format::Vtk, Format::Vtu] {
        let prefix = dir.join(format!("ring-data-{format}"));
        let written = write_mesh_with(&prefix, &mesh, Some(&input), &[format]).expect("write");
        let (lines, stderr) = meshio_report(&written[0]);
        // One value per triangle and per vertex (legacy SCALARS come back from meshio as
        // columns of shape (n, 1), XML arrays as vectors: both have n rows of one value).
        let sizes = values(&lines, "size");
        for array in ["min_angle", "max_angle", "radius_ratio", "region"] {
            assert_eq!(sizes[array], "8 8", "{format}: {array}");
        }
        assert_eq!(sizes["boundary_marker"], "8 8", "{format}");
        let cells = values(&lines, "cell");
        let names: Vec<&String> = cells.keys().collect();
        assert_eq!(
            names,
            ["max_angle", "min_angle", "radius_ratio", "region"],
            "{stderr}"
        );
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&doubles(&cells["min_angle"])), bits(&min), "{format}");
        assert_eq!(bits(&doubles(&cells["max_angle"])), bits(&max), "{format}");
        assert_eq!(
            bits(&doubles(&cells["radius_ratio"])),
            bits(&ratio),
            "{format}"
        );
        assert_eq!(doubles(&cells["region"]), vec![4.0; 8], "{format}");
        assert!(min
            .iter()
            .zip(&max)
            .all(|(a, b)| 0.0 < *a && a < b && *b < 180.0));
        // Vertex 5 keeps its input marker, which needs 64 bits; the outer ring is 5, the
        // hole's first corner 7 (its segments 4 and 7 are marked 7 and 0).
        let points = values(&lines, "point");
        assert_eq!(
            points["boundary_marker"], "5 5 5 5 7 -3000000000 7 7",
            "{format}"
        );
    }
}

/// `gmsh -check` reads our `.msh` without an error, when Gmsh is installed.
#[test]
fn gmsh_check_accepts_our_msh_with_groups_and_regions() {
    let found = std::env::var_os("PATH")
        .map(|p| std::env::split_paths(&p).any(|d| d.join("gmsh").is_file()))
        .unwrap_or(false);
    if !found {
        println!("note: gmsh is not on PATH; `gmsh -check` skipped (`make deps` installs it)");
        return;
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("meshio");
    std::fs::create_dir_all(&dir).expect("dir");
    let (mesh, input) = ring();
    for (name, input) in [("ring-gmsh", Some(&input)), ("plain-gmsh", None)] {
        let written =
            write_mesh_with(&dir.join(name), &mesh, input, &[Format::Msh]).expect("write");
        let out = Command::new("gmsh")
            .arg("-check")
            .arg(&written[0])
            .output()
            .expect("run gmsh");
        let shown = String::from_utf8_lossy(&out.stdout).to_string()
            + &String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "gmsh -check failed: {shown}");
        assert!(!shown.contains("Error"), "{shown}");
        assert!(
            shown.contains("16 elements"),
            "8 triangles and 8 lines: {shown}"
        );
    }
}
