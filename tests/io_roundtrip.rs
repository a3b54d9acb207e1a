//! Triangle's formats survive write → read bit for bit (every f64 compared by its bits, -0.0
//! and subnormals included), hand-written files survive read → write → read, and the
//! high-level API keeps numbering, prefixes and bounding hexagons straight.

use std::path::{Path, PathBuf};

use hexmesh::io::{
    read_ele, read_input, read_mesh, read_node, read_poly, write_ele, write_mesh, write_node,
    write_poly, write_pslg, EleFile, Format, NodeFile, PolyFile, Region,
};
use hexmesh::{Hexagon, Pslg, TriMesh};
use proptest::prelude::*;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/io")
        .join(name)
}

/// A fresh directory for one test under cargo's per-target scratch space.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("io_roundtrip")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|v| v.to_bits()).collect()
}

fn point_bits(points: &[[f64; 2]]) -> Vec<[u64; 2]> {
    points
        .iter()
        .map(|p| [p[0].to_bits(), p[1].to_bits()])
        .collect()
}

/// Everything a .node file carries, compared by bits (source lines excluded: they are where
/// the rows were, not what they say).
fn assert_nodes_identical(a: &NodeFile, b: &NodeFile) {
    assert_eq!(point_bits(&a.points), point_bits(&b.points));
    assert_eq!(a.attribute_count, b.attribute_count);
    let attr = |n: &NodeFile| n.attributes.iter().map(|r| bits(r)).collect::<Vec<_>>();
    assert_eq!(attr(a), attr(b));
    assert_eq!(a.markers, b.markers);
    assert_eq!(a.first_index, b.first_index);
    assert_eq!(
        a.hexagon
            .map(|h| bits(&[h.center[0], h.center[1], h.circumradius])),
        b.hexagon
            .map(|h| bits(&[h.center[0], h.center[1], h.circumradius]))
    );
}

fn assert_polys_identical(a: &PolyFile, b: &PolyFile) {
    assert_nodes_identical(&a.nodes, &b.nodes);
    assert_eq!(a.segments, b.segments);
    assert_eq!(a.segment_markers, b.segment_markers);
    assert_eq!(point_bits(&a.holes), point_bits(&b.holes));
    let regions = |p: &PolyFile| {
        p.regions.as_ref().map(|rs| {
            rs.iter()
                .map(|r| {
                    (
                        bits(&[r.point[0], r.point[1], r.attribute]),
                        r.max_area.map(f64::to_bits),
                    )
                })
                .collect::<Vec<_>>()
        })
    };
    assert_eq!(regions(a), regions(b));
}

/// Values that shortest round-trip formatting must get right.
const AWKWARD: [f64; 12] = [
    -0.0,
    0.0,
    1e-300,
    5e-324,
    2.2250738585072014e-308,
    1.7976931348623157e308,
    -1e150,
    0.1,
    1.0 / 3.0,
    std::f64::consts::PI,
    123456789012345680.0,
    -2.5e-7,
];

#[test]
fn node_write_read_is_bit_exact_for_awkward_floats() {
    let dir = scratch("node_awkward");
    let points: Vec<[f64; 2]> = AWKWARD
        .iter()
        .zip(AWKWARD.iter().rev())
        .map(|(&x, &y)| [x, y])
        .collect();
    let n = points.len();
    for first_index in [0, 1] {
        let nodes = NodeFile {
            points: points.clone(),
            attribute_count: 2,
            attributes: (0..n)
                .map(|k| vec![AWKWARD[k], AWKWARD[(k + 5) % n]])
                .collect(),
            markers: Some((0..n as i64).map(|k| k * 7 - 20).collect()),
            first_index,
            hexagon: Some(Hexagon::new([0.1, -0.0], 1.0 / 3.0)),
            lines: Vec::new(),
        };
        let path = dir.join(format!("awkward{first_index}.node"));
        write_node(&path, &nodes).expect("write");
        let back = read_node(&path).expect("read");
        assert_nodes_identical(&nodes, &back);
        assert_eq!(back.lines.len(), n);
    }
}

#[test]
fn poly_write_read_is_bit_exact_with_markers_holes_and_regions() {
    let dir = scratch("poly");
    let poly = PolyFile {
        nodes: NodeFile {
            markers: Some(vec![1, 1, 1, 0]),
            ..NodeFile::from_points(
                vec![[0.0, 0.0], [1e-300, 0.0], [0.5, 5e-324], [0.25, 0.1]],
                0,
            )
        },
        segments: vec![[0, 1], [1, 2], [2, 0]],
        segment_markers: Some(vec![3, -4, 5]),
        holes: vec![[-0.0, 1.0 / 3.0]],
        regions: Some(vec![
            Region {
                point: [0.2, 0.01],
                attribute: -1.5,
                max_area: Some(1e-9),
            },
            Region {
                point: [0.3, 0.02],
                attribute: 2.0,
                max_area: None,
            },
        ]),
        ..PolyFile::default()
    };
    let path = dir.join("p.poly");
    write_poly(&path, &poly).expect("write");
    let back = read_poly(&path).expect("read");
    assert_polys_identical(&poly, &back);
}

#[test]
fn poly_without_inline_nodes_keeps_its_empty_header() {
    let dir = scratch("poly_empty_nodes");
    let poly = read_poly(&fixture("sibling_nodes.poly")).expect("read");
    assert!(poly.nodes.points.is_empty());
    let path = dir.join("s.poly");
    write_poly(&path, &poly).expect("write");
    let text = std::fs::read_to_string(&path).expect("text");
    assert!(text.starts_with("0 2 0 0\n"), "{text}");
    assert_polys_identical(&poly, &read_poly(&path).expect("re-read"));
}

#[test]
fn ele_write_read_is_bit_exact_with_attributes() {
    let dir = scratch("ele");
    let ele = EleFile {
        triangles: vec![[1, 2, 3], [3, 2, 4]],
        attribute_count: 1,
        attributes: vec![vec![-0.0], vec![5e-324]],
        first_index: 1,
        lines: Vec::new(),
    };
    let path = dir.join("e.ele");
    write_ele(&path, &ele).expect("write");
    let back = read_ele(&path).expect("read");
    assert_eq!(back.triangles, ele.triangles);
    assert_eq!(back.first_index, 1);
    assert_eq!(
        back.attributes.iter().map(|r| bits(r)).collect::<Vec<_>>(),
        ele.attributes.iter().map(|r| bits(r)).collect::<Vec<_>>()
    );
}

#[test]
fn hand_written_files_survive_read_write_read() {
    let dir = scratch("hand_written");
    let node = read_node(&fixture("hand_written.node")).expect("node");
    assert_eq!((node.first_index, node.attribute_count), (1, 2));
    assert_eq!(node.points[1][0].to_bits(), (-0.0f64).to_bits());
    assert_eq!(node.lines, vec![3, 4, 5, 6, 7]);
    write_node(&dir.join("n.node"), &node).expect("write node");
    assert_nodes_identical(
        &node,
        &read_node(&dir.join("n.node")).expect("re-read node"),
    );

    let poly = read_poly(&fixture("hand_written.poly")).expect("poly");
    assert_eq!(poly.nodes.first_index, 0);
    assert_eq!(poly.nodes.markers.as_ref().map(Vec::len), Some(8));
    assert_eq!(poly.nodes.attributes[6][0].to_bits(), 5e-324f64.to_bits());
    assert_eq!(poly.segments.len(), 8);
    assert_eq!(poly.holes, vec![[0.5, 0.5]]);
    assert_eq!(poly.regions.as_ref().map(Vec::len), Some(2));
    write_poly(&dir.join("p.poly"), &poly).expect("write poly");
    assert_polys_identical(
        &poly,
        &read_poly(&dir.join("p.poly")).expect("re-read poly"),
    );
}

#[test]
fn read_input_shifts_a_0_based_poly_to_0_based_segments() {
    let pslg = read_input(&fixture("hand_written.poly")).expect("poly input");
    assert_eq!(pslg.points.len(), 8);
    assert_eq!(pslg.segments[0], [0, 1]);
    assert_eq!(pslg.segments[7], [7, 4]);
    assert_eq!(pslg.holes, vec![[0.5, 0.5]]);
}

#[test]
fn read_input_takes_points_from_the_sibling_node_file() {
    let pslg = read_input(&fixture("sibling_nodes.poly")).expect("sibling");
    assert_eq!(pslg.points, vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    // The .poly says 1 2, the .node numbers from 0: vertex 1 is the second point.
    assert_eq!(pslg.segments, vec![[1, 2], [2, 0], [0, 1]]);
}

#[test]
fn read_input_of_a_1_based_node_file_keeps_every_bit() {
    let pslg = read_input(&fixture("hand_written.node")).expect("node input");
    let node = read_node(&fixture("hand_written.node")).expect("node");
    assert_eq!(point_bits(&pslg.points), point_bits(&node.points));
    assert!(pslg.segments.is_empty() && pslg.hexagon.is_none());
}

#[test]
fn write_pslg_then_read_input_gives_the_same_pslg() {
    let dir = scratch("pslg");
    let points = Pslg {
        points: vec![[-0.01, 0.0], [0.01, 0.0]],
        hexagon: Some(Hexagon::new([0.0, 0.0], 1.0)),
        ..Pslg::default()
    };
    write_pslg(&dir.join("close-pair.node"), &points).expect("node");
    assert_eq!(
        read_input(&dir.join("close-pair.node")).expect("read"),
        points
    );

    let square = Pslg {
        points: vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.4, 0.4],
            [0.6, 0.4],
            [0.5, 0.6],
        ],
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 4]],
        holes: vec![[0.5, 0.45]],
        hexagon: None,
        ..Pslg::default()
    };
    assert_eq!(hexmesh::io::pslg_extension(&square), "poly");
    write_pslg(&dir.join("square.poly"), &square).expect("poly");
    assert_eq!(read_input(&dir.join("square.poly")).expect("read"), square);
    assert!(write_pslg(&dir.join("square.node"), &square).is_err());
}

#[test]
fn input_labels_are_read_into_the_pslg_and_written_back() {
    let dir = scratch("labels");
    let text = "4 2 1 1\n1 0 0 0.5 7\n2 1 0 1.5 0\n3 1 1 2.5 0\n4 0 1 3.5 8\n\
                4 1\n1 1 2 3\n2 2 3 0\n3 3 4 0\n4 4 1 2\n0\n2\n\
                1 0.25 0.25 10\n2 0.75 0.75 20 0.125\n";
    let path = dir.join("labelled.poly");
    std::fs::write(&path, text).expect("write fixture");
    let pslg = read_input(&path).expect("read");
    let labels = &pslg.labels;
    assert_eq!(labels.point_markers, Some(vec![7, 0, 0, 8]));
    assert_eq!(
        labels.point_attributes,
        vec![vec![0.5], vec![1.5], vec![2.5], vec![3.5]]
    );
    assert_eq!(labels.segment_markers, Some(vec![3, 0, 0, 2]));
    assert_eq!(
        labels.regions,
        vec![
            Region {
                point: [0.25, 0.25],
                attribute: 10.0,
                max_area: None
            },
            Region {
                point: [0.75, 0.75],
                attribute: 20.0,
                max_area: Some(0.125)
            },
        ]
    );
    write_pslg(&dir.join("again.poly"), &pslg).expect("write");
    assert_eq!(
        read_input(&dir.join("again.poly")).expect("read again"),
        pslg
    );
    // Labels that do not fit the points are refused, and nothing is written.
    let mut bad = pslg.clone();
    bad.labels.segment_markers = Some(vec![1]);
    assert!(write_pslg(&dir.join("bad.poly"), &bad).is_err());
    assert!(!dir.join("bad.poly").exists());
    // A .node file without markers or attributes gives no labels.
    std::fs::write(dir.join("bare.node"), "2 2 0 0\n1 0 0\n2 1 0\n").expect("bare");
    assert!(read_input(&dir.join("bare.node"))
        .expect("node")
        .labels
        .is_empty());
}

#[test]
fn read_mesh_accepts_the_prefix_with_or_without_an_extension() {
    let expected = TriMesh {
        vertices: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    };
    for name in ["square.1", "square.1.node", "square.1.ele"] {
        assert_eq!(read_mesh(&fixture(name)).expect(name), expected, "{name}");
    }
}

#[test]
fn read_mesh_keeps_clockwise_and_degenerate_triangles_for_verify() {
    let mesh = read_mesh(&fixture("clockwise")).expect("broken mesh must load");
    assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 0, 1]]);
    assert!(mesh.area() < 0.0);
}

#[test]
fn write_mesh_writes_1_based_triangle_files_that_read_back_exactly() {
    let dir = scratch("write_mesh");
    let mesh = TriMesh {
        vertices: vec![[0.0, -0.0], [1.0 / 3.0, 0.0], [0.0, 5e-324], [0.7, 0.9]],
        triangles: vec![[0, 1, 2], [1, 3, 2]],
    };
    let prefix = dir.join("m.1");
    let written = write_mesh(
        &prefix,
        &mesh,
        &[
            Format::Triangle,
            Format::Vtk,
            Format::Msh,
            Format::Svg,
            Format::Triangle,
        ],
    )
    .expect("write");
    let names: Vec<String> = written
        .iter()
        .map(|p| {
            p.file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    assert_eq!(
        names,
        ["m.1.node", "m.1.ele", "m.1.vtk", "m.1.msh", "m.1.svg"]
    );
    let ele_text = std::fs::read_to_string(dir.join("m.1.ele")).expect("ele");
    assert!(ele_text.starts_with("2 3 0\n1 1 2 3\n"), "{ele_text}");
    let back = read_mesh(&prefix).expect("read back");
    assert_eq!(back.triangles, mesh.triangles);
    assert_eq!(point_bits(&back.vertices), point_bits(&mesh.vertices));
}

#[test]
fn write_mesh_refuses_a_triangle_naming_a_missing_vertex() {
    let dir = scratch("bad_mesh");
    let mesh = TriMesh {
        vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        triangles: vec![[0, 1, 3]],
    };
    assert!(write_mesh(&dir.join("bad"), &mesh, &[Format::Triangle]).is_err());
    assert!(!dir.join("bad.node").exists());
}

#[test]
fn format_names_parse_and_unknown_ones_are_refused() {
    assert_eq!(Format::parse("node").ok(), Some(Format::Triangle));
    assert_eq!(Format::parse("Triangle").ok(), Some(Format::Triangle));
    assert_eq!(Format::parse("vtk").ok(), Some(Format::Vtk));
    assert_eq!(Format::parse("msh").ok(), Some(Format::Msh));
    assert_eq!(Format::parse("svg").ok(), Some(Format::Svg));
    assert_eq!(Format::parse("poly").ok(), Some(Format::Poly));
    assert_eq!(Format::parse("edge").ok(), Some(Format::Poly));
    assert_eq!(Format::parse("VTU").ok(), Some(Format::Vtu));
    for f in Format::ALL {
        assert_eq!(Format::parse(f.name()).ok(), Some(f));
    }
    let e = Format::parse("stl").expect_err("stl accepted");
    assert!(e.to_string().contains("stl"), "{e}");
}

#[test]
fn a_poly_output_brings_the_node_and_ele_files_its_points_are_in() {
    let names = |formats: &[Format]| -> Vec<String> {
        hexmesh::io::mesh_files(Path::new("d/m.1"), formats)
            .iter()
            .map(|p| p.display().to_string())
            .collect()
    };
    assert_eq!(
        names(&[Format::Vtu, Format::Poly]),
        [
            "d/m.1.vtu",
            "d/m.1.node",
            "d/m.1.ele",
            "d/m.1.poly",
            "d/m.1.edge"
        ]
    );
    assert_eq!(
        names(&[Format::Poly, Format::Triangle, Format::Poly]),
        ["d/m.1.node", "d/m.1.ele", "d/m.1.poly", "d/m.1.edge"]
    );
    assert_eq!(names(&[Format::Msh]), ["d/m.1.msh"]);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn any_finite_coordinates_round_trip_bit_exactly(
        coords in prop::collection::vec(
            (any::<f64>(), any::<f64>()).prop_filter("finite", |(x, y)| x.is_finite() && y.is_finite()),
            1..40,
        ),
        first_index in 0u32..2,
    ) {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("io_roundtrip").join("proptest");
        std::fs::create_dir_all(&dir).expect("dir");
        let path = dir.join(format!("p{}.node", std::process::id()));
        let nodes = NodeFile::from_points(coords.iter().map(|&(x, y)| [x, y]).collect(), first_index);
        write_node(&path, &nodes).expect("write");
        let back = read_node(&path).expect("read");
        prop_assert_eq!(point_bits(&back.points), point_bits(&nodes.points));
        prop_assert_eq!(back.first_index, first_index);
    }
}

#[test]
fn windows_line_endings_are_read() {
    let pslg = read_input(&fixture("crlf.node")).expect("crlf");
    assert_eq!(pslg.points, vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
}

#[test]
fn every_small_dataset_and_pslg_example_survives_write_pslg_and_read_input_bit_exactly() {
    let dir = scratch("datasets");
    let small = hexmesh::datasets::SMALL.iter();
    for &name in small.chain(hexmesh::datasets::PSLG_EXAMPLES) {
        let pslg = hexmesh::datasets::by_name(name).expect(name);
        let file = hexmesh::datasets::file_name(name).expect(name);
        let path = dir.join(&file);
        write_pslg(&path, &pslg).expect(name);
        let back = read_input(&path).expect(name);
        assert_eq!(point_bits(&back.points), point_bits(&pslg.points), "{name}");
        assert_eq!(back.segments, pslg.segments, "{name}");
        assert_eq!(point_bits(&back.holes), point_bits(&pslg.holes), "{name}");
        // close-pair's hexagon is given, not fitted: it must come back.
        assert_eq!(back.hexagon, pslg.hexagon, "{name}");
    }
}
