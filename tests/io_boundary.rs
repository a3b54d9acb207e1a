//! A finite-element user's boundary survives meshing: `pslg-holes` (segment markers 1 on the
//! L, 2 on the square hole, 3 on the triangular hole), meshed by the meshers that keep
//! segments, written as Triangle `.poly`/`.edge` and Gmsh `.msh`. Every boundary edge of the
//! mesh, found here from the triangles alone, carries the marker of the input segment it lies
//! on (found here by geometry), and each hole is its own physical group in the `.msh`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use hexmesh::io::{read_input, read_poly, write_mesh_with, Format};
use hexmesh::{datasets, Params, Point, Pslg, TriMesh};

fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("io_boundary")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

fn holes() -> Pslg {
    datasets::by_name("pslg-holes").expect("pslg-holes")
}

fn meshed(name: &str, input: &Pslg) -> TriMesh {
    let run = hexmesh::mesher(name)
        .expect("registered")
        .mesh(input, &Params::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(run.complete, "{name}");
    run.mesh
}

/// The edges used by one triangle, as sorted vertex pairs.
fn boundary_edges(mesh: &TriMesh) -> BTreeSet<(u32, u32)> {
    let mut count: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    count
        .into_iter()
        .filter(|&(_, c)| c == 1)
        .map(|(e, _)| e)
        .collect()
}

/// The input segment that the edge pq lies on: both ends within 1e-12 of the segment's length
/// of its line and inside its bounding box.
fn segment_under(input: &Pslg, p: Point, q: Point) -> Option<usize> {
    input.segments.iter().position(|s| {
        let (a, b) = (input.points[s[0] as usize], input.points[s[1] as usize]);
        let length = (b[0] - a[0]).hypot(b[1] - a[1]);
        let on = |r: Point| {
            let cross = (b[0] - a[0]) * (r[1] - a[1]) - (b[1] - a[1]) * (r[0] - a[0]);
            let inside = |k: usize| r[k] >= a[k].min(b[k]) && r[k] <= a[k].max(b[k]);
            cross.abs() <= 1e-12 * length * length && inside(0) && inside(1)
        };
        on(p) && on(q)
    })
}

#[test]
fn every_boundary_edge_of_pslg_holes_carries_its_segments_marker_in_the_poly_and_edge_files() {
    let input = holes();
    let markers = input.labels.segment_markers.clone().expect("markers");
    for name in ["saalfeld", "hex"] {
        let dir = scratch(name);
        let mesh = meshed(name, &input);
        let prefix = dir.join("holes");
        write_mesh_with(&prefix, &mesh, Some(&input), &[Format::Poly]).expect("write");

        let poly = read_poly(&dir.join("holes.poly")).expect("the .poly reads");
        assert!(
            poly.nodes.points.is_empty(),
            "{name}: points are in holes.node"
        );
        let poly_markers = poly.segment_markers.clone().expect("segment markers");
        let listed: BTreeMap<(u32, u32), i64> = poly
            .segments
            .iter()
            .zip(&poly_markers)
            .map(|(s, &m)| ((s[0].min(s[1]) - 1, s[0].max(s[1]) - 1), m))
            .collect();
        let boundary = boundary_edges(&mesh);
        // pslg-holes has no segment inside the domain: the .poly lists the boundary.
        assert_eq!(
            listed.keys().copied().collect::<BTreeSet<_>>(),
            boundary,
            "{name}"
        );
        for &(u, v) in &boundary {
            let (p, q) = (mesh.vertices[u as usize], mesh.vertices[v as usize]);
            let s = segment_under(&input, p, q)
                .unwrap_or_else(|| panic!("{name}: boundary edge {u}-{v} lies on no segment"));
            assert_eq!(
                listed[&(u, v)],
                markers[s],
                "{name}: edge {u}-{v} on segment {s}"
            );
        }
        // Every marker of the input appears; the holes are still holes.
        let seen: BTreeSet<i64> = listed.values().copied().collect();
        assert_eq!(seen, BTreeSet::from([1, 2, 3]), "{name}");
        assert_eq!(poly.holes, input.holes, "{name}");

        // The .edge file lists every edge once, the boundary ones with the same markers.
        let edge_text = std::fs::read_to_string(dir.join("holes.edge")).expect("edge");
        let mut rows = edge_text.lines();
        let header = rows.next().expect("header");
        let edges: Vec<Vec<i64>> = rows
            .map(|l| {
                l.split_whitespace()
                    .map(|t| t.parse().expect("int"))
                    .collect()
            })
            .collect();
        assert_eq!(header, format!("{} 1", edges.len()), "{name}");
        assert_eq!(
            2 * edges.len(),
            3 * mesh.triangles.len() + boundary.len(),
            "{name}: every edge once"
        );
        for (k, e) in edges.iter().enumerate() {
            assert_eq!(e[0], k as i64 + 1);
            let key = ((e[1].min(e[2]) - 1) as u32, (e[1].max(e[2]) - 1) as u32);
            assert_eq!(
                e[3],
                listed.get(&key).copied().unwrap_or(0),
                "{name}: edge {k}"
            );
        }

        // The output reads back as an input: its boundary is a valid PSLG with the markers.
        let back = read_input(&dir.join("holes.poly")).expect("the output .poly is an input");
        assert_eq!(back.points, mesh.vertices, "{name}");
        assert_eq!(back.segments.len(), boundary.len(), "{name}");
    }
}

/// The curve entities of each physical group of dimension 1, and the line elements of each
/// curve, from a Gmsh 4.1 ASCII file.
struct Msh {
    groups: BTreeMap<String, usize>,
    curves: Vec<(usize, Vec<usize>)>,
    lines: BTreeMap<usize, Vec<[u32; 2]>>,
}

fn read_msh(path: &Path) -> Msh {
    let text = std::fs::read_to_string(path).expect("msh");
    let section = |name: &str| -> Vec<&str> {
        let start = text.find(&format!("${name}\n")).expect(name) + name.len() + 2;
        let end = text.find(&format!("$End{name}")).expect(name);
        text[start..end].lines().collect()
    };
    let number = |t: &str| t.parse::<usize>().expect("number");
    let mut groups = BTreeMap::new();
    for row in &section("PhysicalNames")[1..] {
        let (head, name) = row.split_once(" \"").expect("name");
        let fields: Vec<usize> = head.split_whitespace().map(number).collect();
        if fields[0] == 1 {
            groups.insert(name.trim_end_matches('"').to_string(), fields[1]);
        }
    }
    let entities = section("Entities");
    let counts: Vec<usize> = entities[0].split_whitespace().map(number).collect();
    let mut curves = Vec::new();
    for row in &entities[1..=counts[1]] {
        let f: Vec<&str> = row.split_whitespace().collect();
        let physical = number(f[7]);
        curves.push((
            number(f[0]),
            f[8..8 + physical].iter().map(|t| number(t)).collect(),
        ));
    }
    let elements = section("Elements");
    let mut lines: BTreeMap<usize, Vec<[u32; 2]>> = BTreeMap::new();
    let mut k = 1;
    while k < elements.len() {
        let block: Vec<usize> = elements[k].split_whitespace().map(number).collect();
        let (dim, tag, count) = (block[0], block[1], block[3]);
        if dim == 1 {
            for row in &elements[k + 1..k + 1 + count] {
                let v: Vec<u32> = row
                    .split_whitespace()
                    .map(|t| t.parse().expect("tag"))
                    .collect();
                lines.entry(tag).or_default().push([v[1] - 1, v[2] - 1]);
            }
        }
        k += 1 + count;
    }
    Msh {
        groups,
        curves,
        lines,
    }
}

#[test]
fn each_hole_of_pslg_holes_is_its_own_physical_group_in_the_msh() {
    let input = holes();
    // The input's segments 6..10 are the square hole, 10..13 the triangular one.
    let hole_of_segment = |s: usize| match s {
        6..=9 => 1,
        10..=12 => 2,
        _ => 0,
    };
    for name in ["saalfeld", "hex"] {
        let dir = scratch(&format!("msh-{name}"));
        let mesh = meshed(name, &input);
        let written =
            write_mesh_with(&dir.join("holes"), &mesh, Some(&input), &[Format::Msh]).expect("msh");
        let msh = read_msh(&written[0]);
        let names: Vec<&str> = msh.groups.keys().map(String::as_str).collect();
        assert_eq!(
            names,
            [
                "hole 1",
                "hole 2",
                "marker 1",
                "marker 2",
                "marker 3",
                "outer boundary"
            ],
            "{name}"
        );
        let boundary = boundary_edges(&mesh);
        let mut covered = BTreeSet::new();
        let mut holes_seen = BTreeSet::new();
        for group in ["hole 1", "hole 2", "outer boundary"] {
            let tag = msh.groups[group];
            let edges: Vec<[u32; 2]> = msh
                .curves
                .iter()
                .filter(|(_, physical)| physical.contains(&tag))
                .flat_map(|(curve, _)| msh.lines[curve].clone())
                .collect();
            // All the group's lines lie on one ring of the input, and on no other group.
            let rings: BTreeSet<usize> = edges
                .iter()
                .map(|&[u, v]| {
                    let s =
                        segment_under(&input, mesh.vertices[u as usize], mesh.vertices[v as usize])
                            .expect("on a segment");
                    hole_of_segment(s)
                })
                .collect();
            assert_eq!(rings.len(), 1, "{name}: {group} spans rings {rings:?}");
            let ring = *rings.iter().next().expect("one ring");
            assert_eq!(ring == 0, group == "outer boundary", "{name}: {group}");
            holes_seen.insert(ring);
            for [u, v] in edges {
                assert!(
                    covered.insert((u.min(v), u.max(v))),
                    "{name}: edge in two loops"
                );
            }
        }
        assert_eq!(holes_seen, BTreeSet::from([0, 1, 2]), "{name}");
        // The three loop groups together are exactly the boundary.
        assert_eq!(covered, boundary, "{name}");
    }
}
