//! The domain promise of `rhomb` (paper 001: every angle in [30°, 90°] but at input corners
//! sharper than 30°, which the mesh must keep whole), checked on hand-made meshes of one
//! domain: a 10° corner at the origin, a kite closed by a triangle on the far side.
//! `verify --bounds rhomb` runs the same verdict.

use hexmesh::quality::{verdict, Verdict};
use hexmesh::{Point, Pslg, TriMesh};

/// O = (0, 0) with its 10° corner, P on the x-axis, Q on the 10° ray, and R beyond PQ placed
/// so that the angle of triangle P R Q at P is `at_p` degrees and at Q is `at_q` degrees.
fn kite(at_p: f64, at_q: f64) -> (Pslg, [Point; 4]) {
    let r10 = 10f64.to_radians();
    let o = [0.0, 0.0];
    let p = [1.0, 0.0];
    let q = [r10.cos(), r10.sin()];
    // R from P: the direction of PQ turned clockwise by `at_p` (outward, away from O), at the
    // length the sine rule gives.
    let pq = [q[0] - p[0], q[1] - p[1]];
    let base = pq[0].hypot(pq[1]);
    let at_r = 180.0 - at_p - at_q;
    let len = base * at_q.to_radians().sin() / at_r.to_radians().sin();
    let turn = -at_p.to_radians();
    let dir = [
        (pq[0] * turn.cos() - pq[1] * turn.sin()) / base,
        (pq[0] * turn.sin() + pq[1] * turn.cos()) / base,
    ];
    let r = [p[0] + len * dir[0], p[1] + len * dir[1]];
    let input = Pslg {
        points: vec![o, p, r, q],
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
        ..Pslg::default()
    };
    (input, [o, p, r, q])
}

/// The kite meshed by its two triangles O P Q (the 10° corner whole) and P R Q.
fn two_triangles(at_p: f64, at_q: f64) -> (Pslg, TriMesh) {
    let (input, [o, p, r, q]) = kite(at_p, at_q);
    let mesh = TriMesh {
        vertices: vec![o, p, r, q],
        triangles: vec![[0, 1, 3], [1, 2, 3]],
    };
    (input, mesh)
}

fn rhomb_verdict(input: &Pslg, mesh: &TriMesh) -> Verdict {
    let bounds = hexmesh::registry::bounds("rhomb").expect("rhomb's promise");
    verdict(mesh, Some(input), Some(&bounds))
}

/// The verdict's row checking `what`.
fn check<'a>(v: &'a Verdict, what: &str) -> &'a hexmesh::quality::Check {
    v.checks
        .iter()
        .find(|c| c.what == what)
        .unwrap_or_else(|| panic!("no check '{what}' in\n{v}"))
}

fn failed(v: &Verdict) -> Vec<String> {
    v.checks
        .iter()
        .filter(|c| c.status == hexmesh::quality::Status::Fail)
        .map(|c| c.what.clone())
        .collect()
}

#[test]
fn a_sharp_input_corner_kept_whole_passes() {
    let (input, mesh) = two_triangles(60.0, 60.0);
    let v = rhomb_verdict(&input, &mesh);
    assert!(v.passed(), "{v}");
    let min = check(&v, "min angle (deg)");
    // The 10° corner is left out and said so; the smallest angle counted is the 60°.
    assert!((min.value.unwrap() - 60.0).abs() < 1e-9, "{v}");
    assert!(
        min.note
            .as_deref()
            .unwrap_or("")
            .contains("1 angle at input corners"),
        "{v}"
    );
}

#[test]
fn a_split_ten_degree_corner_fails() {
    let (input, whole) = two_triangles(60.0, 60.0);
    // M, the midpoint of P Q, joined to O: the corner becomes two 5° angles.
    let [p, q] = [whole.vertices[1], whole.vertices[3]];
    let mut mesh = whole.clone();
    mesh.vertices
        .push([(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0]);
    mesh.triangles = vec![[0, 1, 4], [0, 4, 3], [1, 2, 4], [4, 2, 3]];
    let v = rhomb_verdict(&input, &mesh);
    assert_eq!(failed(&v), ["min angle (deg)"], "{v}");
    let min = check(&v, "min angle (deg)");
    assert!((min.value.unwrap() - 5.0).abs() < 1e-9, "{v}");
}

#[test]
fn an_angle_of_90_01_degrees_beside_a_segment_fails() {
    // P R Q with 44.995° at P and Q: 90.01° at R, between the segments P R and R Q.
    let (input, mesh) = two_triangles(44.995, 44.995);
    let v = rhomb_verdict(&input, &mesh);
    assert_eq!(failed(&v), ["max angle (deg)"], "{v}");
    let max = check(&v, "max angle (deg)");
    assert!((max.value.unwrap() - 90.01).abs() < 1e-9, "{v}");
}

#[test]
fn an_angle_of_29_99_degrees_beside_a_segment_fails() {
    // 29.99° at P between the segment P R and the mesh edge P Q: not a whole input corner.
    let (input, mesh) = two_triangles(29.99, 75.0);
    let v = rhomb_verdict(&input, &mesh);
    assert_eq!(failed(&v), ["min angle (deg)"], "{v}");
    let min = check(&v, "min angle (deg)");
    assert!((min.value.unwrap() - 29.99).abs() < 1e-9, "{v}");
}

#[test]
fn the_same_meshes_pass_or_fail_through_verify() {
    let dir = std::env::temp_dir().join(format!("hexmesh-domain-bounds-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, (at_p, at_q), passes) in [
        ("whole", (60.0, 60.0), true),
        ("obtuse", (44.995, 44.995), false),
    ] {
        let (input, mesh) = two_triangles(at_p, at_q);
        let poly = dir.join(format!("{name}.poly"));
        hexmesh::io::write_pslg(&poly, &input).unwrap();
        let prefix = dir.join(name);
        hexmesh::io::write_mesh(&prefix, &mesh, &[hexmesh::io::Format::Triangle]).unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_hexmesh"))
            .args(["verify", prefix.to_str().unwrap(), "--input"])
            .arg(&poly)
            .args(["--bounds", "rhomb"])
            .output()
            .unwrap();
        assert_eq!(out.status.success(), passes, "{name}: {out:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn min_angle_bounds_leave_out_whole_sharp_corners_too() {
    // `min-angle=DEG` (and each reference's promise) keeps the same exception.
    let bounds = hexmesh::registry::bounds("min-angle=30").unwrap();
    let (input, whole) = two_triangles(60.0, 60.0);
    assert!(verdict(&whole, Some(&input), Some(&bounds)).passed());
    let (input, sharp) = two_triangles(29.99, 75.0);
    assert!(!verdict(&sharp, Some(&input), Some(&bounds)).passed());
}
