//! Size control: `--max-area` and `--max-edge` are kept by our meshers (hex, hex-simple,
//! rhomb) by refining further, with every promised bound still verified; hex keeps an area
//! limit on a PSLG away from the segments; the references keep a maximum edge where they can
//! (cgal) and refuse it where they cannot (triangle), as a usage error; the verdict's edge
//! check fails a mesh with one edge too long.

use std::process::{Command, Output};

use hexmesh::quality::{verdict, Bounds, Check, Status, Verdict};
use hexmesh::{datasets, mesher, Params, Pslg, TriMesh};

fn hexmesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hexmesh"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("hexmesh runs")
}

fn text(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr)
}

fn row<'a>(v: &'a Verdict, what: &str) -> &'a Check {
    v.checks
        .iter()
        .find(|c| c.what == what)
        .unwrap_or_else(|| panic!("no check '{what}' in\n{v}"))
}

fn area(mesh: &TriMesh, t: usize) -> f64 {
    let [a, b, c] = mesh.corners(t);
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

fn longest_edge(mesh: &TriMesh, t: usize) -> f64 {
    let c = mesh.corners(t);
    (0..3)
        .map(|e| hexmesh::geom::dist(c[e], c[(e + 1) % 3]))
        .fold(0.0, f64::max)
}

/// Meshes `input` with `name` and `params`, checks the run against the mesher's promise for
/// those parameters and returns the mesh with its verdict.
fn mesh_and_verify(name: &str, input: &Pslg, params: &Params) -> (TriMesh, Verdict) {
    let m = mesher(name).expect(name);
    let run = m
        .mesh(input, params)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(run.complete, "{name}: {:?}", run.stop_reason);
    let promise = m.promise(params);
    assert_eq!(
        promise.max_area, params.max_area,
        "{name} promises the area"
    );
    assert_eq!(
        promise.max_edge, params.max_edge,
        "{name} promises the edge"
    );
    let v = verdict(&run.mesh, Some(input), Some(&promise));
    assert!(v.passed(), "{name}:\n{v}");
    (run.mesh, v)
}

#[test]
fn hex_hex_simple_and_rhomb_keep_a_maximum_area_on_plane_100_with_their_bounds() {
    let input = datasets::by_name("plane-100").unwrap();
    let limit = 1e-4;
    for name in ["hex", "hex-simple", "rhomb"] {
        let plain = mesher(name)
            .unwrap()
            .mesh(&input, &Params::default())
            .unwrap();
        let (mesh, v) = mesh_and_verify(name, &input, &Params::default().with_max_area(limit));
        let largest = (0..mesh.triangles.len())
            .map(|t| area(&mesh, t))
            .fold(0.0, f64::max);
        assert!(largest <= limit, "{name}: {largest} > {limit}");
        // The limit is checked, and it made the mesh finer than without it.
        assert_eq!(row(&v, "triangle area / its limit").status, Status::Ok);
        assert!(row(&v, "min angle (deg)").status == Status::Ok, "{name}");
        assert!(
            mesh.triangles.len() > plain.mesh.triangles.len(),
            "{name}: {} triangles with the limit, {} without",
            mesh.triangles.len(),
            plain.mesh.triangles.len()
        );
        eprintln!(
            "{name} plane-100 --max-area {limit}: {} triangles (without: {}), largest area {largest:e}",
            mesh.triangles.len(),
            plain.mesh.triangles.len()
        );
    }
}

#[test]
fn hex_hex_simple_and_rhomb_keep_a_maximum_edge_on_plane_100_with_their_bounds() {
    let input = datasets::by_name("plane-100").unwrap();
    let limit = 0.02;
    for name in ["hex", "hex-simple", "rhomb"] {
        let (mesh, v) = mesh_and_verify(name, &input, &Params::default().with_max_edge(limit));
        let longest = (0..mesh.triangles.len())
            .map(|t| longest_edge(&mesh, t))
            .fold(0.0, f64::max);
        assert!(longest <= limit, "{name}: {longest} > {limit}");
        assert_eq!(row(&v, "longest edge / its limit").status, Status::Ok);
        eprintln!(
            "{name} plane-100 --max-edge {limit}: {} triangles, longest edge {longest:e}",
            mesh.triangles.len()
        );
    }
}

#[test]
fn both_limits_together_are_kept_and_the_finer_one_decides() {
    let input = datasets::by_name("plane-100").unwrap();
    for name in ["hex", "hex-simple", "rhomb", "lsb"] {
        let params = Params::default().with_max_area(1e-3).with_max_edge(0.01);
        let (mesh, _) = mesh_and_verify(name, &input, &params);
        for t in 0..mesh.triangles.len() {
            assert!(
                area(&mesh, t) <= 1e-3 && longest_edge(&mesh, t) <= 0.01,
                "{name}"
            );
        }
    }
}

#[test]
fn a_regions_area_limit_on_a_point_set_is_kept_by_hex_and_hex_simple() {
    let mut input = datasets::by_name("plane-100").unwrap();
    input.labels.regions = vec![hexmesh::Region {
        point: input.points[0],
        attribute: 0.0,
        max_area: Some(3e-4),
    }];
    for name in ["hex", "hex-simple"] {
        let m = mesher(name).unwrap();
        let run = m.mesh(&input, &Params::default()).unwrap();
        let largest = (0..run.mesh.triangles.len())
            .map(|t| area(&run.mesh, t))
            .fold(0.0, f64::max);
        assert!(largest <= 3e-4, "{name}: {largest}");
        let v = verdict(
            &run.mesh,
            Some(&input),
            Some(&m.promise(&Params::default())),
        );
        assert!(v.passed(), "{name}:\n{v}");
    }
}

#[test]
fn hex_keeps_a_maximum_area_on_pslg_holes_away_from_the_segments_and_stays_conforming() {
    let input = datasets::by_name("pslg-holes").unwrap();
    let limit = 1e-3;
    let out = hexmesh::hex::pslg::mesh_pslg(&input, &Params::default().with_max_area(limit))
        .expect("meshes");
    let mesh = &out.mesh;
    let interior = |t: usize| {
        mesh.triangles[t]
            .iter()
            .all(|&v| !out.on_segment[v as usize])
    };
    let (mut inner, mut near, mut near_over) = (0.0f64, 0.0f64, 0usize);
    for t in 0..mesh.triangles.len() {
        let a = area(mesh, t);
        if interior(t) {
            inner = inner.max(a);
        } else {
            near = near.max(a);
            near_over += usize::from(a > limit);
        }
    }
    assert!(inner <= limit, "{inner} > {limit}");
    eprintln!(
        "hex pslg-holes --max-area {limit}: {} triangles, largest interior area {inner:e}, \
         largest near-segment area {near:e} ({near_over} near-segment triangles over)",
        mesh.triangles.len()
    );
    // Through the mesher: the same mesh, valid, conforming, its angles kept away from the
    // segments, and (the near-segment triangles keep it too here) every area within the limit.
    let params = Params::default().with_max_area(limit);
    let hex = mesher("hex").unwrap();
    let run = hex.mesh(&input, &params).expect("meshes");
    assert_eq!(&run.mesh, mesh);
    let v = verdict(mesh, Some(&input), Some(&hex.promise(&params)));
    assert!(v.passed(), "{v}");
    assert_eq!(near_over, 0);
    assert_eq!(row(&v, "triangle area / its limit").status, Status::Ok);
}

#[test]
fn without_limits_the_hex_meshes_are_the_same_as_before() {
    // The level of no limit is 0, and nothing else changes: counts recorded before size
    // control existed.
    let input = datasets::by_name("plane-100").unwrap();
    let count = |name: &str| {
        mesher(name)
            .unwrap()
            .mesh(&input, &Params::default())
            .unwrap()
            .mesh
            .triangles
            .len()
    };
    assert_eq!(count("hex"), 12509);
    assert_eq!(count("hex-simple"), 3566);
    assert_eq!(count("rhomb"), 15155);
}

#[test]
fn the_edge_check_fails_a_mesh_with_one_edge_too_long() {
    // Two triangles of the unit square: the diagonal is √2 long.
    let mesh = TriMesh {
        vertices: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    };
    let bounds = Bounds::validity("sized").with_size_limits(None, Some(1.4));
    let v = verdict(&mesh, None, Some(&bounds));
    let check = row(&v, "longest edge / its limit");
    assert_eq!(check.status, Status::Fail, "{v}");
    assert!(!v.passed());
    assert!((check.value.unwrap() - 2f64.sqrt() / 1.4).abs() < 1e-12);
    // At √2 (up to the slack) it passes.
    let ok = Bounds::validity("sized").with_size_limits(None, Some(2f64.sqrt()));
    let v = verdict(&mesh, None, Some(&ok));
    assert_eq!(
        row(&v, "longest edge / its limit").status,
        Status::Ok,
        "{v}"
    );
}

#[test]
fn max_edge_is_refused_by_triangle_with_exit_2_and_kept_by_cgal() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("size_control");
    std::fs::create_dir_all(&dir).unwrap();
    let prefix = dir.join("tri");
    let out = hexmesh(&[
        "mesh",
        "plane-100",
        "--mesher",
        "triangle",
        "--max-edge",
        "0.05",
        "-o",
        prefix.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    let said = text(&out);
    assert!(
        said.contains("triangle") && said.contains("--max-edge"),
        "{said}"
    );
    assert!(!dir.join("tri.ele").exists());
    if cfg!(feature = "cgal") {
        let prefix = dir.join("cgal");
        let out = hexmesh(&[
            "mesh",
            "plane-100",
            "--mesher",
            "cgal",
            "--max-edge",
            "0.05",
            "-o",
            prefix.to_str().unwrap(),
        ]);
        // `mesh` checks the promise, the edge limit among it: exit 0 means every edge kept it.
        assert_eq!(out.status.code(), Some(0), "{}", text(&out));
        let mesh = hexmesh::io::read_mesh(&prefix).expect("reads the mesh");
        let longest = (0..mesh.triangles.len())
            .map(|t| longest_edge(&mesh, t))
            .fold(0.0, f64::max);
        assert!(longest <= 0.05, "{longest}");
    }
}

#[test]
fn a_nonpositive_or_infinite_max_edge_is_a_usage_error() {
    for bad in ["0", "-1", "inf", "NaN"] {
        let option = format!("--max-edge={bad}");
        let out = hexmesh(&[
            "mesh",
            "plane-100",
            "--mesher",
            "hex",
            &option,
            "-o",
            "target/never",
        ]);
        assert_eq!(out.status.code(), Some(2), "{bad}: {}", text(&out));
        assert!(text(&out).contains("--max-edge"), "{bad}: {}", text(&out));
    }
    // And in the library, for the meshers that read it.
    let input = datasets::by_name("plane-100").unwrap();
    for name in ["hex", "hex-simple", "rhomb", "lsb"] {
        assert!(
            mesher(name)
                .unwrap()
                .mesh(&input, &Params::default().with_max_edge(-1.0))
                .is_err(),
            "{name}"
        );
    }
}

#[test]
fn meshers_without_an_edge_control_refuse_it_naming_themselves() {
    let input = datasets::by_name("plane-100").unwrap();
    let mut names = vec!["saalfeld", "spade"];
    if cfg!(feature = "cgal") {
        names.push("cgal-conforming");
    }
    for name in names {
        let err = mesher(name)
            .unwrap()
            .mesh(&input, &Params::default().with_max_edge(0.05))
            .expect_err(name)
            .to_string();
        assert!(err.contains(name) && err.contains("--max-edge"), "{err}");
    }
}
