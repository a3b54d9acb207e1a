//! The rounding contract (README "Checks"): our meshers mesh real coordinates and close pairs
//! and keep every bound up to the rounding allowance of `quality::rounding`; the allowance is
//! sound (moving each vertex by δv keeps the angles within it) and no loophole (a missed
//! bound at ordinary coordinates still fails); an input that would need more than
//! `--max-rounding` is refused, naming its two points.

use std::path::{Path, PathBuf};

use hexmesh::error::InputError;
use hexmesh::quality::rounding::{angle_allowance, delta, ANGLE_FLOOR_DEG};
use hexmesh::quality::{verdict, HEX};
use hexmesh::{Error, Params, Pslg, TriMesh};

fn fixtures() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/rounding");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("fixture directory")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "node"))
        .collect();
    files.sort();
    files
}

fn mesh(name: &str, input: &Pslg) -> TriMesh {
    let m = hexmesh::mesher(name).expect("registered");
    let run = m
        .mesh(input, &Params::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(run.complete, "{name}: {:?}", run.stop_reason);
    run.mesh
}

#[test]
fn real_coordinates_and_close_pairs_mesh_and_keep_every_bound() {
    let files = fixtures();
    assert_eq!(files.len(), 7, "{files:?}");
    for path in &files {
        let input = hexmesh::io::read_input(path).unwrap_or_else(|e| panic!("{e}"));
        for name in ["hex", "hex-simple", "rhomb"] {
            let mesh = mesh(name, &input);
            let bounds = hexmesh::registry::bounds(name).expect("bounds");
            let v = verdict(&mesh, Some(&input), Some(&bounds));
            assert!(v.passed(), "{} {name}:\n{v}", path.display());
            for c in &v.checks {
                assert!(
                    c.value.is_none_or(f64::is_finite),
                    "{} {name}: {} = {:?}",
                    path.display(),
                    c.what,
                    c.value
                );
                if let Some(r) = c.rounding {
                    assert!(
                        r.used <= 0.01,
                        "{} {name}: {} used {r:?}",
                        path.display(),
                        c.what
                    );
                }
            }
        }
    }
}

#[test]
fn the_allowance_is_sound_when_each_vertex_moves_by_its_delta() {
    // A hex mesh at 1e7, where the allowance is far above its floor: every vertex moved by
    // δv in each of eight directions, one vertex at a time and all together, keeps every angle
    // within the allowance (computed on the unmoved mesh) of the bounds.
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/rounding/unit-square-shifted-1e7.node");
    let input = hexmesh::io::read_input(&path).expect("fixture");
    let mesh = mesh("hex", &input);
    let angles =
        |c: [[f64; 2]; 3], m: usize| hexmesh::geom::angle_deg(c[m], c[(m + 1) % 3], c[(m + 2) % 3]);
    let mut largest_move: f64 = 0.0;
    let mut largest_allowance: f64 = 0.0;
    for dir in 0..8 {
        let a = std::f64::consts::FRAC_PI_4 * dir as f64;
        let moved: Vec<[f64; 2]> = mesh
            .vertices
            .iter()
            .enumerate()
            .map(|(i, p)| {
                // Alternate the direction between vertices so that neighbours move apart.
                let s = if i % 2 == 0 { 1.0 } else { -1.0 };
                let d = delta(*p);
                [p[0] + s * d * a.cos(), p[1] + s * d * a.sin()]
            })
            .collect();
        for t in 0..mesh.triangles.len() {
            let c = mesh.corners(t);
            let cm = mesh.triangles[t].map(|v| moved[v as usize]);
            for m in 0..3 {
                let allowance = angle_allowance(c[m], c[(m + 1) % 3], c[(m + 2) % 3]);
                let change = (angles(cm, m) - angles(c, m)).abs();
                largest_move = largest_move.max(change);
                largest_allowance = largest_allowance.max(allowance);
                // The first-order bound, less its floor, covers the move.
                assert!(
                    change <= allowance - ANGLE_FLOOR_DEG + 1e-9,
                    "triangle {t} corner {m}: moved {change:e}°, allowance {allowance:e}°"
                );
                let moved_angle = angles(cm, m);
                assert!(
                    moved_angle >= HEX.min_angle - allowance && moved_angle <= 90.0 + allowance,
                    "triangle {t} corner {m}: {moved_angle}° with allowance {allowance:e}°"
                );
            }
        }
    }
    // The test means something: the moves are far above the floor of the allowance.
    assert!(largest_move > 10.0 * ANGLE_FLOOR_DEG, "{largest_move:e}");
    assert!(
        largest_allowance > 10.0 * ANGLE_FLOOR_DEG,
        "{largest_allowance:e}"
    );
}

#[test]
fn an_angle_of_43_8978_degrees_near_unit_coordinates_still_fails() {
    // A right triangle with a 43.8978° angle (1e-4° below the bound), coordinates near 1.
    let tan = 43.8978f64.to_radians().tan();
    let mesh = TriMesh {
        vertices: vec![[0.25, 0.25], [1.25, 0.25], [1.25, 0.25 + tan]],
        triangles: vec![[0, 1, 2]],
    };
    let bounds = hexmesh::registry::bounds("hex").expect("hex");
    let v = verdict(&mesh, None, Some(&bounds));
    assert!(!v.passed(), "{v}");
    let min = v
        .checks
        .iter()
        .find(|c| c.what.starts_with("min angle"))
        .expect("min angle row");
    let r = min.rounding.expect("allowance");
    assert!(r.used > 8e-5 && r.allowance < 2e-6, "{r:?}");
}

#[test]
fn a_pair_too_close_for_its_coordinates_is_refused_naming_both_points() {
    // Two points 1e-14 apart at coordinates near 1: a mesh of them would use far more than
    // 0.01°.
    let input = Pslg::from_points(vec![[0.2, 0.3], [0.9, 0.8], [0.5, 0.5], [0.5 + 1e-14, 0.5]]);
    // rhomb runs out of rhomb levels (48) first; it names the pair all the same.
    for name in ["hex", "hex-simple", "rhomb"] {
        let m = hexmesh::mesher(name).expect("registered");
        match m.mesh(&input, &Params::default()) {
            Err(Error::Input {
                problem:
                    InputError::Rounding {
                        first,
                        second,
                        distance,
                        needed,
                        allowed,
                    },
                ..
            }) => {
                assert_eq!((first, second), (2, 3), "{name}");
                assert!((distance - 1e-14).abs() < 1e-16, "{name}: {distance}");
                assert!(needed > allowed && allowed == 0.01, "{name}: {needed}");
                let text = hexmesh::InputError::Rounding {
                    first,
                    second,
                    distance,
                    needed,
                    allowed,
                }
                .describe(1);
                assert!(text.contains("points 3 and 4"), "{text}");
            }
            other => panic!("{name}: expected a rounding refusal, got {other:?}"),
        }
    }
    // A larger allowance is the user's to give.
    let loose = Params::default().with_max_rounding(1e3);
    let m = hexmesh::mesher("hex-simple").expect("registered");
    assert!(m.mesh(&input, &loose).is_ok());
}

/// hex on a domain keeps the Sec. 6 bounds away from the segments, and the contract covers
/// them there too: a unit square at 1e7 with two interior points 1e-3 apart meshes, every
/// interior angle within 0.01° of its bound; 1e-5 apart (5,000 ulps) the pair would need
/// about 1° and is refused, naming it.
#[test]
fn hex_on_a_domain_keeps_its_interior_within_max_rounding_or_refuses_naming_the_pair() {
    let square = |gap: f64| Pslg {
        points: vec![
            [1e7, 1e7],
            [1e7 + 1.0, 1e7],
            [1e7 + 1.0, 1e7 + 1.0],
            [1e7, 1e7 + 1.0],
            [1e7 + 0.5, 1e7 + 0.5],
            [1e7 + 0.5 + gap, 1e7 + 0.5],
        ],
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
        ..Pslg::default()
    };
    let hex = hexmesh::mesher("hex").expect("registered");
    let input = square(1e-3);
    let run = hex.mesh(&input, &Params::default()).expect("meshes");
    let bounds = hexmesh::registry::bounds("hex").expect("bounds");
    let v = verdict(&run.mesh, Some(&input), Some(&bounds));
    assert!(v.passed(), "{v}");
    for c in v.checks.iter().filter(|c| c.what.contains("angle")) {
        assert!(c.rounding.is_none_or(|r| r.used <= 0.01), "{}", c.what);
    }
    match hex.mesh(&square(1e-5), &Params::default()) {
        Err(Error::Input {
            problem: InputError::Rounding { first, second, .. },
            ..
        }) => assert_eq!((first, second), (4, 5)),
        other => panic!("expected a rounding refusal, got {other:?}"),
    }
}

#[test]
fn the_command_line_names_the_two_points_by_their_lines() {
    let dir = std::env::temp_dir().join(format!("hexmesh-rounding-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let node = dir.join("close.node");
    std::fs::write(
        &node,
        "# two points 1e-14 apart\n4 2 0 0\n1 0.2 0.3\n2 0.9 0.8\n3 0.5 0.5\n4 0.50000000000001 0.5\n",
    )
    .expect("write");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_hexmesh"))
        .args(["mesh"])
        .arg(&node)
        .args(["--mesher", "hex", "-o"])
        .arg(dir.join("out"))
        .output()
        .expect("run hexmesh");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("close.node:6:")
            && err.contains("points 3 and 4")
            && err.contains("line 5")
            && err.contains("--max-rounding"),
        "{err}"
    );
    assert!(!dir.join("out.node").exists());
    std::fs::remove_dir_all(&dir).ok();
}
