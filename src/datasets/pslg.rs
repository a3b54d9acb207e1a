//! Small planar straight-line graphs that stress what a mesher of domains must get right
//! (paper 000 Sec. 7; issue 8): holes given by seeds as in Triangle's .poly, a small input
//! angle, a segment inside the domain, nested boundaries, short segments beside long ones.
//! `hexmesh report` meshes each with every mesher that keeps segments (`reports/pslg.csv`).
//!
//! Every coordinate but the wedge's is a dyadic rational (a multiple of 1/64), so the points,
//! the segment lengths and the domain areas are exact in f64. The wedge's third corner uses
//! `imr`'s Taylor `cos_sin`, the same bits on every machine.

use super::imr::{cos_sin, push_loop};
use crate::geom::Point;
use crate::mesh::Pslg;

/// The apex angle of `pslg-wedge-5`, degrees.
pub const WEDGE_DEG: f64 = 5.0;

/// Short segments along the top of `pslg-short-long` (32 teeth of two segments each).
pub const SHORT_PIECES: usize = 64;

/// The names of the PSLG examples, in report order.
pub const PSLG_EXAMPLES: &[&str] = &[
    "pslg-holes",
    "pslg-wedge-5",
    "pslg-slit",
    "pslg-nested",
    "pslg-short-long",
];

/// One PSLG example: the input, what it tests, and the area of the domain it bounds.
#[derive(Debug, Clone, PartialEq)]
pub struct PslgExample {
    pub name: &'static str,
    /// What the shape tests, one sentence (the report's README prints it).
    pub tests: &'static str,
    /// The area of the domain (Triangle's .poly semantics: inside the outer boundary, holes
    /// removed), from the construction; a mesh that covers the domain covers this much.
    pub area: f64,
    pub pslg: Pslg,
}

/// Every PSLG example, in the order of [`PSLG_EXAMPLES`].
pub fn pslg_examples() -> Vec<PslgExample> {
    vec![holes(), wedge(), slit(), nested(), short_long()]
}

/// The example called `name`, if there is one.
pub fn pslg_example(name: &str) -> Option<PslgExample> {
    pslg_examples().into_iter().find(|e| e.name == name)
}

/// An L-shaped polygon (a reflex corner) with a square hole in its foot and a triangular
/// hole in its stem, each emptied by a seed.
fn holes() -> PslgExample {
    let mut pslg = Pslg::default();
    push_loop(
        &mut pslg,
        &[
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 0.75],
            [0.875, 0.75],
            [0.875, 1.625],
            [0.0, 1.625],
        ],
    );
    let square = [
        [1.25, 0.1875],
        [1.625, 0.1875],
        [1.625, 0.5625],
        [1.25, 0.5625],
    ];
    push_loop(&mut pslg, &square);
    let triangle = [[0.25, 0.9375], [0.625, 1.0], [0.375, 1.375]];
    push_loop(&mut pslg, &triangle);
    pslg.holes.push([1.4375, 0.375]);
    pslg.holes.push(centroid(&triangle));
    // Segment markers for the writers' boundary conditions: the L is 1, the square hole 2,
    // the triangular hole 3.
    pslg.labels.segment_markers = Some(
        [(1, 6), (2, 4), (3, 3)]
            .iter()
            .flat_map(|&(m, k)| vec![m; k])
            .collect(),
    );
    // L: 2 × 0.75 + 0.875 × 0.875; square hole 0.375²; triangle hole 0.078125.
    let area = 1.5 + 0.765625 - 0.140625 - 0.078125;
    PslgExample {
        name: "pslg-holes",
        tests: "a non-convex polygon (an L) with a square and a triangular hole, each given by \
                a seed as in Triangle's .poly: the mesher must empty exactly the two seeded \
                regions and keep the reflex corner",
        area,
        pslg,
    }
}

/// A triangle with a 5° angle at the origin and 87.5° at the two far corners.
fn wedge() -> PslgExample {
    let (c, s) = cos_sin(WEDGE_DEG.to_radians());
    let mut pslg = Pslg::default();
    push_loop(&mut pslg, &[[0.0, 0.0], [1.0, 0.0], [c, s]]);
    PslgExample {
        name: "pslg-wedge-5",
        tests: "a thin wedge, the triangle with a 5° input angle at the origin: every mesh of \
                it has an angle of at most 5° in that corner, so a mesher must terminate \
                without meeting an angle request there (the references' rows fail the 30° \
                they are asked for by construction) and keep the triangles at the apex valid",
        area: 0.5 * s,
        pslg,
    }
}

/// The unit square with one segment inside it that touches nothing.
fn slit() -> PslgExample {
    let mut pslg = Pslg::default();
    push_loop(&mut pslg, &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    let base = pslg.points.len() as u32;
    pslg.points.extend([[0.25, 0.375], [0.75, 0.625]]);
    pslg.segments.push([base, base + 1]);
    PslgExample {
        name: "pslg-slit",
        tests: "an interior slit, a segment inside the unit square that touches no boundary: \
                it must become a chain of mesh edges with triangles on both sides, and the \
                domain stays the whole square",
        area: 1.0,
        pslg,
    }
}

/// Three squares, each inside the next; the ring between the middle and the inner one is a
/// hole, so the inner square is an island.
fn nested() -> PslgExample {
    let mut pslg = Pslg::default();
    push_loop(&mut pslg, &[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
    push_loop(&mut pslg, &[[0.5, 0.5], [1.5, 0.5], [1.5, 1.5], [0.5, 1.5]]);
    // Off centre: the gaps to the middle square are 0.3125 and 0.1875.
    push_loop(
        &mut pslg,
        &[
            [0.8125, 0.6875],
            [1.3125, 0.6875],
            [1.3125, 1.1875],
            [0.8125, 1.1875],
        ],
    );
    pslg.holes.push([0.625, 1.0]);
    PslgExample {
        name: "pslg-nested",
        tests: "nested boundaries, a square inside a square inside a square with a seed in the \
                middle ring: the ring must be empty while the outer ring and the island inside \
                it are meshed",
        area: 4.0 - 1.0 + 0.25,
        pslg,
    }
}

/// A 2 × 1 rectangle whose top side is a sawtooth of [`SHORT_PIECES`] segments, each about
/// 1/29 long, beside three single sides of lengths 2, 1 and 1.
fn short_long() -> PslgExample {
    let mut outline: Vec<Point> = vec![[0.0, 0.0], [2.0, 0.0]];
    let step = 2.0 / SHORT_PIECES as f64;
    let tooth = 1.0 / 64.0;
    for k in 0..=SHORT_PIECES {
        let y = if k % 2 == 1 { 1.0 + tooth } else { 1.0 };
        outline.push([2.0 - step * k as f64, y]);
    }
    let mut pslg = Pslg::default();
    push_loop(&mut pslg, &outline);
    // The rectangle, plus 32 teeth of base 2·step and height `tooth`.
    let teeth = (SHORT_PIECES / 2) as f64 * 0.5 * (2.0 * step) * tooth;
    PslgExample {
        name: "pslg-short-long",
        tests: "many short segments beside long ones: a 2 × 1 rectangle whose top is a \
                sawtooth of 64 segments 0.035 long, meeting sides 29 and 57 times longer, so \
                the mesh must grade from the teeth to the far side",
        area: 2.0 + teeth,
        pslg,
    }
}

fn centroid(points: &[Point]) -> Point {
    let n = points.len() as f64;
    let (x, y) = points
        .iter()
        .fold((0.0, 0.0), |(x, y), p| (x + p[0], y + p[1]));
    [x / n, y / n]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_examples_come_in_the_order_of_their_names() {
        let names: Vec<&str> = pslg_examples().iter().map(|e| e.name).collect();
        assert_eq!(names, PSLG_EXAMPLES);
        assert_eq!(pslg_example("pslg-slit").map(|e| e.name), Some("pslg-slit"));
        assert!(pslg_example("imr").is_none());
    }

    #[test]
    fn the_holes_example_marks_its_outer_boundary_1_and_its_holes_2_and_3() {
        let p = holes().pslg;
        let markers = p.labels.segment_markers.clone().expect("segment markers");
        assert_eq!(markers.len(), p.segments.len());
        // Segments come loop by loop: the L's six, the square's four, the triangle's three.
        assert_eq!(markers, [1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3]);
        assert_eq!(p.labels.check_fit(p.points.len(), p.segments.len()), Ok(()));
        // The other examples carry no labels.
        assert!(pslg_examples()[1..]
            .iter()
            .all(|e| e.pslg.labels.is_empty()));
    }

    #[test]
    fn the_sawtooth_pieces_are_one_29th_long() {
        let e = short_long();
        let len = (2.0f64 / 64.0).hypot(1.0 / 64.0);
        assert!((1.0 / len - 28.6).abs() < 0.1, "{}", 1.0 / len);
        assert_eq!(e.pslg.segments.len(), 2 + SHORT_PIECES + 1);
        assert_eq!(e.area, 2.0 + 1.0 / 64.0);
    }
}
