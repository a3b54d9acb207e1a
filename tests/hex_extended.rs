//! The extended refinement (paper 000 Sec. 5, mesher `hex`, not registered yet): on the inputs
//! it finishes quickly, the Sec. 6 promises hold: angles in [43.8979°, 90°], radius ratio at
//! most 1.20787, no exact Delaunay violation, shortest edge at least √7/(12√3)·d_min.

use hexmesh::geom::{dist, Point};
use hexmesh::hex::extended::{delaunay_violations, mesh_extended, min_angle_bound};
use hexmesh::hex::fuzz::check_mesh;
use hexmesh::{Hexagon, Params, Pslg, TriMesh};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

fn radius_ratio(t: [Point; 3]) -> f64 {
    let (a, b, c) = (dist(t[1], t[2]), dist(t[0], t[2]), dist(t[0], t[1]));
    let s = (a + b + c) / 2.0;
    let area = (s * (s - a) * (s - b) * (s - c)).max(0.0).sqrt();
    let circum = a * b * c / (4.0 * area);
    let inr = area / s;
    circum / (2.0 * inr)
}

fn assert_extended_bounds(input: &Pslg) -> TriMesh {
    let out = mesh_extended(input, &Params::default()).expect("meshes");
    assert!(out.stop.is_none());
    let mesh = out.mesh;
    check_mesh(&mesh, &input.points, Some((min_angle_bound(), 90.0)))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(delaunay_violations(&mesh).is_empty());
    let bounds = hexmesh::quality::Bounds::parse("hex").unwrap();
    let v = hexmesh::quality::verdict(&mesh, Some(input), Some(&bounds));
    assert!(v.passed(), "{v}");
    let worst = (0..mesh.triangles.len())
        .map(|t| radius_ratio(mesh.corners(t)))
        .fold(0.0, f64::max);
    assert!(worst <= 1.20787 + 1e-9, "radius ratio {worst}");
    let mut d_min = f64::INFINITY;
    for i in 0..input.points.len() {
        for j in 0..i {
            d_min = d_min.min(dist(input.points[i], input.points[j]));
        }
    }
    let shortest = mesh
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |e| (t[e], t[(e + 1) % 3])))
        .map(|(a, b)| dist(mesh.vertices[a as usize], mesh.vertices[b as usize]))
        .fold(f64::INFINITY, f64::min);
    if d_min.is_finite() {
        let bound = 7f64.sqrt() / (12.0 * 3f64.sqrt()) * d_min;
        assert!(shortest >= bound, "shortest edge {shortest} < {bound}");
    }
    mesh
}

#[test]
fn close_pair_meets_the_extended_bounds() {
    let input = Pslg {
        points: vec![[-0.01, 0.0], [0.01, 0.0]],
        hexagon: Some(Hexagon {
            center: [0.0, 0.0],
            circumradius: 1.0,
        }),
        ..Pslg::default()
    };
    let mesh = assert_extended_bounds(&input);
    assert!(mesh.triangles.len() > 300);
}

#[test]
fn a_single_point_meets_the_extended_bounds() {
    let mesh = assert_extended_bounds(&Pslg::from_points(vec![[0.3, 0.7]]));
    assert_eq!(mesh.triangles.len(), 6);
}

#[test]
fn ten_points_and_a_hundred_uniform_points_meet_the_extended_bounds() {
    let pts = (0..10)
        .map(|t| {
            let s = t as f64 * 0.618_033_988_749_895;
            [s.fract(), (s * 2.3).fract()]
        })
        .collect();
    assert_extended_bounds(&Pslg::from_points(pts));
    let mut rng = Pcg64::seed_from_u64(1);
    let pts = (0..100)
        .map(|_| [rng.random::<f64>(), rng.random::<f64>()])
        .collect();
    assert_extended_bounds(&Pslg::from_points(pts));
}
