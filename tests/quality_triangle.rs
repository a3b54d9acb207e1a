//! `validate` and `verdict` on real meshes from Shewchuk's Triangle (through `tritet`): a
//! quality mesh of a PSLG with a hole, whose segments Triangle splits with Steiner points,
//! must come out valid, conforming, and within the angle it was asked for.

use hexmesh::quality::{validate, verdict, ValidateOptions};
use hexmesh::{Pslg, TriMesh};
use tritet::Trigen;

/// The 4×4 square with a 1×2 rectangular hole, as a PSLG.
fn square_with_hole() -> Pslg {
    Pslg {
        points: vec![
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 4.0],
            [0.0, 4.0],
            [1.5, 1.0],
            [2.5, 1.0],
            [2.5, 3.0],
            [1.5, 3.0],
        ],
        segments: vec![
            [0, 1],
            [1, 2],
            [2, 3],
            [3, 0],
            [4, 5],
            [5, 6],
            [6, 7],
            [7, 4],
        ],
        holes: vec![[2.0, 2.0]],
        hexagon: None,
        ..Pslg::default()
    }
}

fn triangle(input: &Pslg, max_area: f64, min_angle: f64) -> TriMesh {
    let mut g = Trigen::new(
        input.points.len(),
        Some(input.segments.len()),
        None,
        Some(input.holes.len()),
    )
    .expect("trigen");
    for (i, p) in input.points.iter().enumerate() {
        g.set_point(i, 0, p[0], p[1]).expect("point");
    }
    for (i, s) in input.segments.iter().enumerate() {
        g.set_segment(i, 0, s[0] as usize, s[1] as usize)
            .expect("segment");
    }
    for (i, h) in input.holes.iter().enumerate() {
        g.set_hole(i, h[0], h[1]).expect("hole");
    }
    g.generate_mesh(false, false, true, Some(max_area), Some(min_angle))
        .expect("mesh");
    TriMesh {
        vertices: (0..g.out_npoint())
            .map(|i| [g.out_point(i, 0), g.out_point(i, 1)])
            .collect(),
        triangles: (0..g.out_ncell())
            .map(|c| {
                [
                    g.out_cell_point(c, 0) as u32,
                    g.out_cell_point(c, 1) as u32,
                    g.out_cell_point(c, 2) as u32,
                ]
            })
            .collect(),
    }
}

// One test: Triangle is not thread-safe, so its calls must not run in parallel.
#[test]
fn triangle_quality_meshes_of_a_pslg_with_a_hole_are_valid_and_keep_their_angle() {
    let input = square_with_hole();
    for (max_area, min_angle) in [(0.5, 20.0), (0.01, 30.0), (0.001, 33.0)] {
        let mesh = triangle(&input, max_area, min_angle);
        let conforming = ValidateOptions {
            single_component: false,
            conforming: true,
        };
        let v = validate(&mesh, Some(&input), &conforming);
        assert!(v.is_empty(), "area {max_area}: {v:#?}");
        let bounds = hexmesh::registry::bounds(&format!("min-angle={min_angle}")).expect("bounds");
        let out = verdict(&mesh, Some(&input), Some(&bounds));
        assert!(out.passed(), "{out}");
        // The hole is not covered: 16 − 2.
        assert!((out.metrics.covered_area - 14.0).abs() < 1e-9, "{out}");
        // As the mesh of a point set (one disc), the hole must be caught.
        let one_disc = ValidateOptions {
            single_component: true,
            conforming: false,
        };
        assert!(!validate(&mesh, None, &one_disc).is_empty());
    }
}
