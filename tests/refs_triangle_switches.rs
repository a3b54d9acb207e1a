//! The `triangle` reference mesher with a .poly's regions and the user's Triangle switches:
//! regional area bounds are applied by Triangle itself (and beside a global `--max-area`),
//! the switches travel to the isolated child and are named in the settings, and switches that
//! would break the harness, or switches for another mesher, are usage errors (exit 2).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Duration;

use hexmesh::geom::orient2d;
use hexmesh::isolate::run_isolated;
use hexmesh::mesh::{Labels, Region};
use hexmesh::quality::verdict;
use hexmesh::{mesher, MeshRun, Params, Pslg};

fn exe() -> &'static Path {
    Path::new(env!("CARGO_BIN_EXE_hexmesh"))
}

fn hexmesh(args: &[&str]) -> Output {
    Command::new(exe())
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("hexmesh runs")
}

/// A path in this test binary's own scratch directory under target/.
fn temp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("refs_triangle_switches");
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir.join(name)
}

fn text(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr)
}

/// The rectangle [0, 2] × [0, 1] cut in two squares by the segment x = 1, the left square
/// a region with area bound `left`, the right one with `right`.
fn two_squares(left: f64, right: f64) -> Pslg {
    Pslg {
        points: vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [0.0, 1.0],
        ],
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0], [1, 4]],
        labels: Labels {
            regions: vec![
                Region {
                    point: [0.5, 0.5],
                    attribute: 1.0,
                    max_area: Some(left),
                },
                Region {
                    point: [1.5, 0.5],
                    attribute: 2.0,
                    max_area: Some(right),
                },
            ],
            ..Labels::default()
        },
        ..Pslg::default()
    }
}

/// The largest triangle area left and right of x = 1 (by centroid), and the triangle counts.
fn largest_by_side(run: &MeshRun) -> ([f64; 2], [usize; 2]) {
    let mut largest = [0.0f64; 2];
    let mut count = [0usize; 2];
    for t in 0..run.mesh.triangles.len() {
        let [a, b, c] = run.mesh.corners(t);
        let side = usize::from((a[0] + b[0] + c[0]) / 3.0 > 1.0);
        largest[side] = largest[side].max(0.5 * orient2d(a, b, c));
        count[side] += 1;
    }
    (largest, count)
}

/// The mesh keeps the input points first and bit-exact and passes `verdict` with the mesher's
/// promise for `params` (valid, conforming, the angle).
fn assert_kept_promise(input: &Pslg, run: &MeshRun, params: &Params) {
    assert!(run.complete);
    for (i, p) in input.points.iter().enumerate() {
        let v = run.mesh.vertices[i];
        assert_eq!(
            (v[0].to_bits(), v[1].to_bits()),
            (p[0].to_bits(), p[1].to_bits()),
            "input point {i}"
        );
    }
    let promise = mesher("triangle").unwrap().promise(params);
    assert!(promise.conforming && promise.min_angle.is_some());
    let v = verdict(&run.mesh, Some(input), Some(&promise));
    assert!(v.passed(), "{v}");
}

#[test]
fn each_region_gets_its_own_area_bound_from_triangle() {
    let input = two_squares(0.01, 0.5);
    let params = Params::default();
    let run = mesher("triangle").unwrap().mesh(&input, &params).unwrap();
    assert_kept_promise(&input, &run, &params);
    let ([left, right], [n_left, _]) = largest_by_side(&run);
    assert!(left <= 0.01, "left region: a triangle of area {left}");
    assert!(right <= 0.5, "right region: a triangle of area {right}");
    // The bounds are the regions' own: the right square is not refined to the left's bound.
    assert!(
        right > 0.01,
        "right region refined like the left one: {right}"
    );
    assert!(
        n_left >= 100,
        "{n_left} triangles cannot cover 1 at 0.01 each"
    );
}

#[test]
fn a_global_max_area_applies_beside_the_regional_bounds() {
    let input = two_squares(0.01, 0.5);
    let params = Params::default().with_max_area(0.05);
    let run = mesher("triangle").unwrap().mesh(&input, &params).unwrap();
    assert_kept_promise(&input, &run, &params);
    let ([left, right], _) = largest_by_side(&run);
    assert!(left <= 0.01, "left region: a triangle of area {left}");
    assert!(right <= 0.05, "right region: a triangle of area {right}");
}

#[test]
fn the_isolated_child_gets_the_regions_and_the_switches() {
    let input = two_squares(0.01, 0.5);
    let params = Params::default().with_switches("q28D");
    let local = mesher("triangle").unwrap().mesh(&input, &params).unwrap();
    assert_kept_promise(&input, &local, &params);
    let iso = run_isolated(exe(), "triangle", &input, &params, Duration::from_secs(30)).unwrap();
    assert_eq!(iso.run.mesh, local.mesh);
    // The switches change the mesh: without them (bare q, 20°) it differs.
    let plain = mesher("triangle")
        .unwrap()
        .mesh(&input, &Params::default())
        .unwrap();
    assert_ne!(plain.mesh, local.mesh);
}

#[test]
fn other_meshers_refuse_switches() {
    // Without the regions: hex and saalfeld would refuse their area limits first.
    let mut input = two_squares(0.01, 0.5);
    input.labels.regions.clear();
    for name in ["spade", "hex", "saalfeld", "lsb"] {
        let e = mesher(name)
            .unwrap()
            .mesh(&input, &Params::default().with_switches("q25"))
            .unwrap_err()
            .to_string();
        assert!(e.contains(name) && e.contains("q25"), "{name}: {e}");
    }
}

const POLY: &str = "\
# the two squares of two_squares(0.01, 0.5)
6 2 0 0
1 0 0
2 1 0
3 2 0
4 2 1
5 1 1
6 0 1
7 0
1 1 2
2 2 3
3 3 4
4 4 5
5 5 6
6 6 1
7 2 5
0
2
1 0.5 0.5 1 0.01
2 1.5 0.5 2 0.5
";

fn poly_file() -> PathBuf {
    let path = temp("two-squares.poly");
    std::fs::write(&path, POLY).unwrap();
    path
}

#[test]
fn mesh_passes_the_switches_end_to_end_and_names_the_string_sent() {
    let poly = poly_file();
    let prefix = temp("two-squares-q25D");
    let out = hexmesh(&[
        "mesh",
        poly.to_str().unwrap(),
        "--mesher",
        "triangle",
        "--triangle-switches",
        "q25D",
        "-o",
        prefix.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    assert!(
        text(&out).contains("triangulate(\"pzAQaq25D\")"),
        "{}",
        text(&out)
    );
    // The written mesh (PREFIX.node + PREFIX.ele) keeps the regions' bounds.
    let mesh = hexmesh::io::read_any_mesh(&prefix).unwrap().mesh;
    let run = MeshRun {
        mesh,
        complete: true,
        stop_reason: None,
        steps: 0,
        elapsed: Duration::ZERO,
    };
    let ([left, right], _) = largest_by_side(&run);
    assert!(
        left <= 0.01 && right <= 0.5 && right > 0.01,
        "{left} {right}"
    );
}

#[test]
fn refused_switches_and_switches_for_another_mesher_exit_2_naming_them() {
    let poly = poly_file();
    let prefix = temp("two-squares-refused");
    let run = |mesher: &str, switches: &str| {
        hexmesh(&[
            "mesh",
            poly.to_str().unwrap(),
            "--mesher",
            mesher,
            "--triangle-switches",
            switches,
            "-o",
            prefix.to_str().unwrap(),
        ])
    };
    for switch in ["j", "r"] {
        let out = run("triangle", &format!("q25{switch}"));
        assert_eq!(out.status.code(), Some(2), "{}", text(&out));
        assert!(
            text(&out).contains(&format!("switch {switch} is refused")),
            "{}",
            text(&out)
        );
    }
    let out = run("spade", "q25");
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    assert!(
        text(&out).contains("--triangle-switches") && text(&out).contains("spade"),
        "{}",
        text(&out)
    );
    let clash = hexmesh(&[
        "mesh",
        poly.to_str().unwrap(),
        "--mesher",
        "triangle",
        "--min-angle",
        "30",
        "--triangle-switches",
        "q25",
        "-o",
        prefix.to_str().unwrap(),
    ]);
    assert_eq!(clash.status.code(), Some(2), "{}", text(&clash));
    assert!(text(&clash).contains("--min-angle"), "{}", text(&clash));
    assert!(
        !prefix.with_extension("ele").exists(),
        "a refused run wrote a mesh"
    );
}

#[test]
fn report_rows_of_triangle_record_the_switches_sent_and_other_rows_do_not() {
    std::env::set_var("HEXMESH_EXE", env!("CARGO_BIN_EXE_hexmesh"));
    let out = temp("report");
    let _ = std::fs::remove_dir_all(&out);
    let opts = hexmesh::report::ReportOptions {
        datasets: vec!["pslg-holes".to_string()],
        meshers: vec!["triangle".to_string(), "spade".to_string()],
        runs: 1,
        out: out.clone(),
        timeout: Duration::from_secs(60),
        max_angle: false,
        triangle_switches: Some("D".to_string()),
        ..hexmesh::report::ReportOptions::default()
    };
    hexmesh::report::run_report(&opts).unwrap();
    let mut rd = csv::Reader::from_path(out.join("pslg.csv")).unwrap();
    let header = rd.headers().unwrap().clone();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (mesher, settings, err) = (col("mesher"), col("settings"), col("err"));
    let rows: Vec<csv::StringRecord> = rd.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), 2);
    for r in &rows {
        assert_eq!(&r[err], "", "{r:?}");
        let sent = r[settings].contains("triangulate(\"pzAQaq30D\")");
        assert_eq!(sent, &r[mesher] == "triangle", "{r:?}");
    }
}
