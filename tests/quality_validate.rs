//! `validate` on meshes built in code: the invariants the fixtures do not cover (indices,
//! non-finite coordinates, overlaps without crossings, touching discs, conformity).

use hexmesh::quality::{metrics, validate, verdict, ValidateOptions, Violation};
use hexmesh::{Pslg, TriMesh};

fn mesh(vertices: &[[f64; 2]], triangles: &[[u32; 3]]) -> TriMesh {
    TriMesh {
        vertices: vertices.to_vec(),
        triangles: triangles.to_vec(),
    }
}

fn square() -> TriMesh {
    mesh(
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        &[[0, 1, 2], [0, 2, 3]],
    )
}

const ONE_DISC: ValidateOptions = ValidateOptions {
    single_component: true,
    conforming: true,
};

#[test]
fn a_valid_square_has_no_violations_under_every_option() {
    let input = Pslg {
        points: square().vertices,
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]],
        ..Pslg::default()
    };
    assert_eq!(validate(&square(), Some(&input), &ONE_DISC), vec![]);
}

#[test]
fn an_index_out_of_range_is_reported_and_nothing_panics() {
    let m = mesh(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], &[[0, 1, 7]]);
    let v = validate(&m, None, &ValidateOptions::default());
    assert!(
        v.contains(&Violation::IndexOutOfRange {
            triangle: 0,
            corner: 2,
            vertex: 7,
            vertices: 3
        }),
        "{v:#?}"
    );
    assert!(v.contains(&Violation::UnreferencedVertex {
        vertex: 2,
        point: [0.0, 1.0]
    }));
    // The figures and the verdict skip the broken triangle rather than panic.
    let m2 = metrics(&m, None);
    assert_eq!(m2.min_angle, None);
    assert!(!verdict(
        &m,
        None,
        Some(&hexmesh::registry::bounds("hex").expect("hex"))
    )
    .passed());
}

#[test]
fn a_nan_vertex_is_reported_by_index() {
    let mut m = square();
    m.vertices[2] = [f64::NAN, 1.0];
    let v = validate(&m, None, &ValidateOptions::default());
    assert!(
        v.iter()
            .any(|x| matches!(x, Violation::NonFiniteVertex { vertex: 2, .. })),
        "{v:#?}"
    );
}

#[test]
fn an_unreferenced_vertex_is_a_violation() {
    let mut m = square();
    m.vertices.push([5.0, 5.0]);
    assert_eq!(
        validate(&m, None, &ValidateOptions::default()),
        vec![Violation::UnreferencedVertex {
            vertex: 4,
            point: [5.0, 5.0]
        }]
    );
}

#[test]
fn a_triangle_lying_inside_another_is_an_overlap_without_crossings() {
    // Two separate components; the small one lies in the big one's interior, so no
    // boundary edges cross and no area sum can tell: only the covering number can.
    let m = mesh(
        &[
            [0.0, 0.0],
            [10.0, 0.0],
            [0.0, 10.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [1.0, 2.0],
        ],
        &[[0, 1, 2], [3, 4, 5]],
    );
    let v = validate(&m, None, &ValidateOptions::default());
    assert!(!v
        .iter()
        .any(|x| matches!(x, Violation::BoundaryCrossing { .. })));
    assert!(
        v.iter()
            .any(|x| matches!(x, Violation::Overlap { covering: 2, .. })),
        "{v:#?}"
    );
}

#[test]
fn two_triangles_touching_at_a_corner_are_valid_but_not_one_disc() {
    let m = mesh(
        &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]],
        &[[0, 1, 2], [0, 3, 4]],
    );
    assert_eq!(validate(&m, None, &ValidateOptions::default()), vec![]);
    let v = validate(&m, None, &ONE_DISC);
    assert!(
        matches!(v.as_slice(), [Violation::HoleInMesh { loops: 2, .. }]),
        "{v:#?}"
    );
}

#[test]
fn two_fans_touching_at_a_vertex_are_two_loops_not_a_figure_eight() {
    // Vertex 6 is the apex of two fans of two triangles each. The loop starting at edge 0-1
    // reaches 6 from the first fan; leaving by the lowest-numbered edge (6-2) would cross
    // into the other fan: only the walk around 6 through the shared edge 0-6 finds 6-4.
    let m = mesh(
        &[
            [1.0, 1.0],
            [0.0, 1.0],
            [-1.0, 0.0],
            [-1.0, -1.0],
            [1.0, 0.0],
            [0.0, -1.0],
            [0.0, 0.0],
        ],
        &[[6, 4, 0], [6, 0, 1], [6, 2, 3], [6, 3, 5]],
    );
    assert_eq!(validate(&m, None, &ValidateOptions::default()), vec![]);
    let v = validate(&m, None, &ONE_DISC);
    assert!(
        matches!(
            v.as_slice(),
            [Violation::HoleInMesh { loops: 2, pinched_at, .. }] if pinched_at == &[6]
        ),
        "{v:#?}"
    );
}

#[test]
fn two_triangles_crossing_at_a_shared_corner_overlap() {
    // Both triangles have corner 0; the second one's wedge reaches into the first one.
    let m = mesh(
        &[[0.0, 0.0], [4.0, 0.0], [0.0, 4.0], [4.0, 1.0], [1.0, 4.0]],
        &[[0, 1, 2], [0, 3, 4]],
    );
    let v = validate(&m, None, &ValidateOptions::default());
    assert!(
        v.iter()
            .any(|x| matches!(x, Violation::BoundaryCrossing { .. }))
            && v.iter().any(|x| matches!(x, Violation::Overlap { .. })),
        "{v:#?}"
    );
}

#[test]
fn a_segment_split_by_a_steiner_point_conforms() {
    // The bottom edge 0-1 of the input is split at (1, 0) in the mesh.
    let m = mesh(
        &[[0.0, 0.0], [2.0, 0.0], [1.0, 1.0], [1.0, 0.0]],
        &[[0, 3, 2], [3, 1, 2]],
    );
    let input = Pslg {
        points: vec![[0.0, 0.0], [2.0, 0.0], [1.0, 1.0]],
        segments: vec![[0, 1], [1, 2], [2, 0]],
        ..Pslg::default()
    };
    assert_eq!(validate(&m, Some(&input), &ONE_DISC), vec![]);
}

#[test]
fn a_segment_the_mesh_cuts_across_does_not_conform() {
    let input = Pslg {
        points: square().vertices,
        segments: vec![[1, 3]],
        ..Pslg::default()
    };
    let v = validate(&square(), Some(&input), &ONE_DISC);
    assert_eq!(v.len(), 1, "{v:#?}");
    assert!(
        matches!(
            v[0],
            Violation::SegmentNotConforming {
                segment: 0,
                endpoints: [1, 3],
                stuck_at: Some((1, [1.0, 0.0])),
                ..
            }
        ),
        "{v:#?}"
    );
    // Without the conforming option the segment is not checked.
    assert_eq!(
        validate(&square(), Some(&input), &ValidateOptions::default()),
        vec![]
    );
}

#[test]
fn an_input_point_matches_a_vertex_at_negative_zero() {
    let mut m = square();
    m.vertices[0] = [-0.0, 0.0];
    let input = Pslg::from_points(vec![[0.0, -0.0]]);
    assert_eq!(validate(&m, Some(&input), &ONE_DISC), vec![]);
}

#[test]
fn violations_read_with_indices_and_coordinates() {
    let m = mesh(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], &[[0, 2, 1]]);
    let v = validate(&m, None, &ValidateOptions::default());
    let text = v[0].to_string();
    assert_eq!(
        text,
        "triangle 0 [0, 2, 1] is clockwise: (0, 0) (0, 1) (1, 0)"
    );
    assert_eq!(v[0].kind(), "clockwise");
    let json = serde_json::to_string(&v[0]).expect("json");
    assert!(json.starts_with("{\"kind\":\"clockwise\""), "{json}");
}

#[test]
fn results_do_not_change_with_scale_or_a_far_offset() {
    // Powers of two keep every coordinate exact, so the answers must be the same.
    let fold = mesh(
        &[
            [0.0, 0.0],
            [10.0, 0.0],
            [-8.0, 6.0],
            [3.0, -9.0],
            [3.0, 9.0],
            [-8.0, -6.0],
        ],
        &[[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5], [0, 5, 1]],
    );
    let ring_and_square = mesh(
        &[
            [0.0, 0.0],
            [3.0, 0.0],
            [3.0, 3.0],
            [0.0, 3.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [2.0, 2.0],
            [1.0, 2.0],
        ],
        &[
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
            [3, 0, 4],
            [3, 4, 7],
            [4, 5, 6],
            [4, 6, 7],
        ],
    );
    for exp in [-40, 0, 40] {
        let s = 2f64.powi(exp);
        for offset in [0.0, 2f64.powi(50) * s] {
            let moved = |m: &TriMesh| TriMesh {
                vertices: m
                    .vertices
                    .iter()
                    .map(|p| [p[0] * s + offset, p[1] * s - offset])
                    .collect(),
                triangles: m.triangles.clone(),
            };
            let v = validate(&moved(&fold), None, &ONE_DISC);
            assert!(
                v.iter().any(|x| matches!(
                    x,
                    Violation::Fold {
                        vertex: 0,
                        winding: 2,
                        ..
                    }
                )),
                "scale 2^{exp}, offset {offset}: {v:#?}"
            );
            assert_eq!(
                validate(&moved(&ring_and_square), None, &ONE_DISC),
                vec![],
                "scale 2^{exp}, offset {offset}"
            );
        }
    }
}

#[test]
fn nan_and_infinite_coordinates_are_reported_without_panicking() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut m = mesh(
            &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]],
            &[[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
        );
        m.vertices[4] = [bad, 0.5];
        let input = Pslg {
            points: vec![[0.0, 0.0], [bad, 0.5], [1.0, 1.0]],
            segments: vec![[0, 1], [0, 2]],
            ..Pslg::default()
        };
        let v = validate(&m, Some(&input), &ONE_DISC);
        assert!(
            v.iter()
                .any(|x| matches!(x, Violation::NonFiniteVertex { vertex: 4, .. })),
            "{v:#?}"
        );
        let hex = hexmesh::registry::bounds("hex").expect("hex");
        let out = verdict(&m, Some(&input), Some(&hex));
        assert!(!out.passed());
        serde_json::to_string(&out).expect("non-finite numbers still serialize");
        let _ = out.to_string();
    }
}

/// A segment split at its constructed midpoint, which f64 rounds off the line by one ulp,
/// still conforms; a split point visibly off the line does not.
#[test]
fn a_rounded_split_point_conforms_but_a_kink_does_not() {
    let (a, b) = ([0.1, 0.2], [0.7, 0.9]);
    let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    assert_ne!(
        hexmesh::geom::orient2d(a, b, m),
        0.0,
        "the midpoint must be off the line"
    );
    let apex = [0.0, 1.0];
    // The triangle a, b, apex as a PSLG, whose side ab the mesh splits.
    let input = Pslg {
        points: vec![a, b, apex],
        segments: vec![[0, 1], [1, 2], [2, 0]],
        ..Pslg::default()
    };
    let split = |mid: [f64; 2]| mesh(&[a, b, apex, mid], &[[0, 3, 2], [3, 1, 2]]);
    assert_eq!(validate(&split(m), Some(&input), &ONE_DISC), vec![]);
    let kinked = [m[0], m[1] - 1e-9];
    let v = validate(&split(kinked), Some(&input), &ONE_DISC);
    assert!(
        v.iter()
            .any(|v| matches!(v, Violation::SegmentNotConforming { segment: 0, .. })),
        "{v:#?}"
    );
}

/// Segments that close no cycle bound nothing, so the mesher keeps its own domain (hex: the
/// bounding hexagon) and the boundary is not held to them; once they close a loop it is.
#[test]
fn the_boundary_is_held_to_the_segments_only_when_they_bound_a_region() {
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let m = mesh(&square, &[[0, 1, 2], [0, 2, 3]]);
    let options = ValidateOptions {
        conforming: true,
        ..ValidateOptions::default()
    };
    let open = Pslg {
        points: square.to_vec(),
        segments: vec![[0, 1], [1, 2]],
        ..Pslg::default()
    };
    assert_eq!(validate(&m, Some(&open), &options), vec![]);
    let closed = Pslg {
        segments: vec![[0, 1], [1, 2], [2, 0]],
        ..open
    };
    let v = validate(&m, Some(&closed), &options);
    assert_eq!(
        v.iter()
            .filter(|x| matches!(x, Violation::BoundaryOffSegments { .. }))
            .count(),
        2,
        "{v:#?}"
    );
}
