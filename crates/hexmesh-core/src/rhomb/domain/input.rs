//! Paper 001 Sec. 3, the permitted input {P, H, G}: a polygon P, holes H_i inside it, single
//! interior points G. The segments of a `Pslg` (already through `Pslg::check`: no crossing,
//! no point inside a segment) are read as closed polygons, and Triangle's hole seeds say which
//! of the regions they bound are empty.
//!
//! Reading (ours; the paper takes P and H as given): every vertex of a segment must have
//! exactly two segments, so that the segments fall into closed loops; a region is the inside
//! of a loop minus the loops directly inside it, and it is domain unless a hole seed lies in
//! it (the region outside every loop never is). Each loop must then have the domain on exactly
//! one side: it is an outer polygon (domain inside) or a hole (domain outside). The rest is
//! refused with an `InputError` naming a segment or point, which the command line turns into
//! the file and line it came from:
//! - a free segment end (`DanglingSegment`) or a vertex with three or more segments
//!   (`BranchingSegment`);
//! - a loop with the domain on both sides (`SegmentInsideDomain`: the paper's "segments lying
//!   completely within the area of triangulation are not allowed", Sec. 2 end), such as a
//!   polygon drawn inside the domain without a seed;
//! - a loop with the domain on neither side (`SegmentOutsideDomain`);
//! - a point on no segment outside the domain or in a hole (`PointOutsideDomain`, condition 3).
//!
//! Departure: several outer polygons are accepted (`imr`'s three letters, an island in a hole
//! as in `pslg-nested`). They are meshed together, in one quad-tree: elements of different
//! polygons are foreign, so close polygons separate each other as a polygon and its holes do.
//!
//! The paper's footnote to condition 1 (a polygon needs more than three corners, or a rhomb
//! might not split enough) is met by an extra corner: a triangle's longest side gets its
//! midpoint as a fourth corner, a Steiner point appended after the input points. The midpoint
//! is rounded to f64, so it lies on the side's line within the conformity tolerance only; the
//! corner it makes is flat (about 180°) and is treated as any corner of that angle.

use crate::error::InputError;
use crate::geom::{orient2d, Point};
use crate::mesh::Pslg;

/// One polygon of the domain.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon {
    /// Corner indices into `Domain::points`, in order, the domain on the left of every side
    /// (counter-clockwise for an outer polygon, clockwise for a hole).
    pub corners: Vec<u32>,
    /// `sides[k]`: the input segment that side corners[k] → corners[k + 1] lies on.
    pub sides: Vec<u32>,
    /// True for an outer polygon (domain inside), false for a hole (domain outside).
    pub outer: bool,
}

/// A permitted input: polygons and single points, with the footnote's extra corners.
#[derive(Debug, Clone, PartialEq)]
pub struct Domain {
    /// The input points, then one extra corner per triangular polygon.
    pub points: Vec<Point>,
    /// The polygons, in the order of their smallest segment index.
    pub polygons: Vec<Polygon>,
    /// The input points on no segment (the paper's single interior points), ascending.
    pub singles: Vec<u32>,
}

/// Reads `input` (already through `Pslg::check`) as a permitted input of paper 001 Sec. 3, or
/// names the first segment or point that makes it not one.
pub fn permitted(input: &Pslg) -> Result<Domain, InputError> {
    let points = &input.points;
    let incident = incidence(input)?;
    let loops = trace_loops(input, &incident);
    let rings: Vec<Vec<Point>> = loops
        .iter()
        .map(|l| l.corners.iter().map(|&c| points[c as usize]).collect())
        .collect();
    // A ring can hold a point only inside its bounding box: the exact test runs on few rings.
    let boxes: Vec<[f64; 4]> = rings.iter().map(|r| bbox(r)).collect();
    let holds = |b: usize, q: Point| {
        let [x0, y0, x1, y1] = boxes[b];
        x0 <= q[0] && q[0] <= x1 && y0 <= q[1] && q[1] <= y1 && inside(q, &rings[b])
    };
    // The loops containing each loop (by its first corner: loops do not cross, and a corner
    // lies on no other loop), its depth and its parent, the innermost of them.
    let containing: Vec<Vec<usize>> = (0..loops.len())
        .map(|a| {
            let q = points[loops[a].corners[0] as usize];
            (0..loops.len())
                .filter(|&b| b != a && holds(b, q))
                .collect()
        })
        .collect();
    let depth: Vec<usize> = containing.iter().map(Vec::len).collect();
    let innermost = |around: &[usize]| around.iter().copied().max_by_key(|&b| depth[b]);
    let parent: Vec<Option<usize>> = containing.iter().map(|c| innermost(c)).collect();
    let count = loops.len();
    let region_of = |q: Point| {
        let around: Vec<usize> = (0..count).filter(|&b| holds(b, q)).collect();
        innermost(&around)
    };
    // Region k is the inside of loop k minus its children; it is domain unless seeded.
    let mut domain = vec![true; loops.len()];
    for &seed in &input.holes {
        if let Some(k) = region_of(seed) {
            domain[k] = false;
        }
    }
    let is_domain = |region: Option<usize>| region.is_some_and(|k| domain[k]);
    let mut polygons = Vec::with_capacity(loops.len());
    for (k, l) in loops.into_iter().enumerate() {
        let (within, around) = (domain[k], is_domain(parent[k]));
        let segment = l.sides[0] as usize;
        let outer = match (within, around) {
            (true, false) => true,
            (false, true) => false,
            (true, true) => return Err(InputError::SegmentInsideDomain { segment }),
            (false, false) => return Err(InputError::SegmentOutsideDomain { segment }),
        };
        polygons.push(oriented(l, &rings[k], outer));
    }
    let singles: Vec<u32> = (0..points.len() as u32)
        .filter(|&p| incident[p as usize].is_empty())
        .collect();
    if let Some(&point) = singles
        .iter()
        .find(|&&p| !is_domain(region_of(points[p as usize])))
    {
        return Err(InputError::PointOutsideDomain {
            point: point as usize,
        });
    }
    let mut out = Domain {
        points: points.clone(),
        polygons,
        singles,
    };
    for k in 0..out.polygons.len() {
        if out.polygons[k].corners.len() == 3 {
            add_extra_corner(&mut out, k);
        }
    }
    Ok(out)
}

/// The segments at each point, by index; a point with one segment, or more than two, is
/// refused (the first such point by index).
fn incidence(input: &Pslg) -> Result<Vec<Vec<u32>>, InputError> {
    let mut incident = vec![Vec::new(); input.points.len()];
    for (s, seg) in input.segments.iter().enumerate() {
        for &v in seg {
            incident[v as usize].push(s as u32);
        }
    }
    for (vertex, at) in incident.iter().enumerate() {
        match at.len() {
            1 => {
                return Err(InputError::DanglingSegment {
                    segment: at[0] as usize,
                    vertex,
                })
            }
            count if count > 2 => {
                return Err(InputError::BranchingSegment {
                    segment: at[2] as usize,
                    vertex,
                    count,
                })
            }
            _ => {}
        }
    }
    Ok(incident)
}

/// The closed loops of segments (every vertex has two), each starting at its smallest
/// segment, in the order of those segments.
fn trace_loops(input: &Pslg, incident: &[Vec<u32>]) -> Vec<Polygon> {
    let mut seen = vec![false; input.segments.len()];
    let mut loops = Vec::new();
    for first in 0..input.segments.len() {
        if seen[first] {
            continue;
        }
        let (mut corners, mut sides) = (Vec::new(), Vec::new());
        let (mut s, mut at) = (first as u32, input.segments[first][0]);
        while !seen[s as usize] {
            seen[s as usize] = true;
            corners.push(at);
            sides.push(s);
            let [a, b] = input.segments[s as usize];
            at = if a == at { b } else { a };
            let pair = &incident[at as usize];
            s = if pair[0] == s { pair[1] } else { pair[0] };
        }
        loops.push(Polygon {
            corners,
            sides,
            outer: true,
        });
    }
    loops
}

/// `l` turned so that the domain lies on the left of its sides: counter-clockwise when
/// `outer`, clockwise otherwise. The orientation is the exact sign at the lexicographically
/// smallest corner, which is convex (its neighbours are not collinear with it: they would
/// overlap a segment, which `Pslg::check` refuses).
fn oriented(mut l: Polygon, ring: &[Point], outer: bool) -> Polygon {
    let n = ring.len();
    let low = (0..n)
        .min_by(|&a, &b| {
            ring[a][0]
                .total_cmp(&ring[b][0])
                .then(ring[a][1].total_cmp(&ring[b][1]))
        })
        .unwrap_or(0);
    let ccw = orient2d(ring[(low + n - 1) % n], ring[low], ring[(low + 1) % n]) > 0.0;
    if ccw != outer {
        l.corners[1..].reverse();
        l.sides.reverse();
    }
    l.outer = outer;
    l
}

/// The bounding box [x0, y0, x1, y1] of some points.
pub fn bbox(points: &[Point]) -> [f64; 4] {
    points.iter().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, p| {
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        },
    )
}

/// True when `q` lies inside the closed polygon `ring` (crossing count of the ray towards +x,
/// with exact orientation signs). A point on the ring counts as inside or outside, the same
/// each time; callers pass points on no side of it, except hole seeds placed on a segment.
pub fn inside(q: Point, ring: &[Point]) -> bool {
    let mut odd = false;
    for k in 0..ring.len() {
        let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
        if (a[1] > q[1]) != (b[1] > q[1]) {
            let o = orient2d(a, b, q);
            if (b[1] > a[1] && o > 0.0) || (b[1] < a[1] && o < 0.0) {
                odd = !odd;
            }
        }
    }
    odd
}

/// The footnote to Sec. 3 condition 1: triangle `k` gets the midpoint of its longest side
/// (the first of equal ones) as a fourth corner, on the same input segment.
fn add_extra_corner(domain: &mut Domain, k: usize) {
    let p = &domain.points;
    let poly = &domain.polygons[k];
    let length = |s: usize| {
        let (a, b) = (
            p[poly.corners[s] as usize],
            p[poly.corners[(s + 1) % 3] as usize],
        );
        crate::geom::Dist2::between(a, b)
    };
    let side = (0..3).fold(0, |best, s| if length(s) > length(best) { s } else { best });
    let (a, b) = (
        p[poly.corners[side] as usize],
        p[poly.corners[(side + 1) % 3] as usize],
    );
    let mid = [a[0] * 0.5 + b[0] * 0.5, a[1] * 0.5 + b[1] * 0.5];
    let index = domain.points.len() as u32;
    domain.points.push(mid);
    let poly = &mut domain.polygons[k];
    let segment = poly.sides[side];
    poly.corners.insert(side + 1, index);
    poly.sides.insert(side + 1, segment);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pslg(points: &[Point], loops: &[&[u32]], holes: &[Point]) -> Pslg {
        let mut segments = Vec::new();
        for l in loops {
            for k in 0..l.len() {
                segments.push([l[k], l[(k + 1) % l.len()]]);
            }
        }
        Pslg {
            points: points.to_vec(),
            segments,
            holes: holes.to_vec(),
            hexagon: None,
            ..Pslg::default()
        }
    }

    const SQUARE: [Point; 4] = [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];

    fn square_with(inner: &[Point], holes: &[Point]) -> Pslg {
        let mut points = SQUARE.to_vec();
        points.extend_from_slice(inner);
        let inner_loop: Vec<u32> = (4..4 + inner.len() as u32).collect();
        pslg(&points, &[&[0, 1, 2, 3], &inner_loop], holes)
    }

    const INNER: [Point; 4] = [[1.0, 1.0], [1.0, 3.0], [3.0, 3.0], [3.0, 1.0]];

    #[test]
    fn a_square_with_a_seeded_square_is_an_outer_polygon_and_a_clockwise_hole() {
        let d = permitted(&square_with(&INNER, &[[2.0, 2.0]])).unwrap();
        assert_eq!(d.polygons.len(), 2);
        let (outer, hole) = (&d.polygons[0], &d.polygons[1]);
        assert!(outer.outer && !hole.outer);
        assert_eq!(outer.corners, vec![0, 1, 2, 3]);
        assert_eq!(outer.sides, vec![0, 1, 2, 3]);
        // Given counter-clockwise as 4, 5, 6, 7 with 4 → 5 upwards (clockwise already).
        assert_eq!(hole.corners, vec![4, 5, 6, 7]);
        assert_eq!(hole.sides, vec![4, 5, 6, 7]);
        assert!(d.singles.is_empty());
    }

    #[test]
    fn a_counter_clockwise_hole_is_turned_round_with_its_sides() {
        let ccw = [[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0]];
        let d = permitted(&square_with(&ccw, &[[2.0, 2.0]])).unwrap();
        let hole = &d.polygons[1];
        assert_eq!(hole.corners, vec![4, 7, 6, 5]);
        // Side 4 → 7 is segment 7 (7–4), 7 → 6 is segment 6, and so on.
        assert_eq!(hole.sides, vec![7, 6, 5, 4]);
        let segments = square_with(&ccw, &[]).segments;
        for k in 0..4 {
            let [a, b] = segments[hole.sides[k] as usize];
            let (c, e) = (hole.corners[k], hole.corners[(k + 1) % 4]);
            assert!((a, b) == (c, e) || (a, b) == (e, c));
        }
    }

    #[test]
    fn an_unseeded_polygon_inside_the_domain_is_refused_by_its_first_segment() {
        let e = permitted(&square_with(&INNER, &[])).unwrap_err();
        assert_eq!(e, InputError::SegmentInsideDomain { segment: 4 });
        assert!(e
            .describe(1)
            .contains("segment 5 has the domain on both sides"));
    }

    #[test]
    fn a_slit_is_refused_as_dangling() {
        let mut input = pslg(&SQUARE, &[&[0, 1, 2, 3]], &[]);
        input.points.extend([[1.0, 1.5], [3.0, 2.5]]);
        input.segments.push([4, 5]);
        assert_eq!(
            permitted(&input),
            Err(InputError::DanglingSegment {
                segment: 4,
                vertex: 4
            })
        );
    }

    #[test]
    fn two_squares_sharing_a_corner_are_refused_as_branching() {
        let points = [
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [2.0, 1.0],
            [2.0, 2.0],
            [1.0, 2.0],
        ];
        let input = pslg(&points, &[&[0, 1, 2, 3], &[2, 4, 5, 6]], &[]);
        assert_eq!(
            permitted(&input),
            Err(InputError::BranchingSegment {
                segment: 4,
                vertex: 2,
                count: 4
            })
        );
    }

    #[test]
    fn an_island_in_a_seeded_ring_is_a_second_outer_polygon() {
        let mut points = SQUARE.to_vec();
        points.extend_from_slice(&INNER);
        points.extend([[1.5, 1.5], [2.5, 1.5], [2.5, 2.5], [1.5, 2.5], [0.5, 0.5]]);
        let input = pslg(
            &points,
            &[&[0, 1, 2, 3], &[4, 5, 6, 7], &[8, 9, 10, 11]],
            &[[1.25, 2.0]],
        );
        let d = permitted(&input).unwrap();
        let kinds: Vec<bool> = d.polygons.iter().map(|p| p.outer).collect();
        assert_eq!(kinds, vec![true, false, true]);
        assert_eq!(d.singles, vec![12]);
    }

    #[test]
    fn a_point_in_a_hole_or_outside_is_refused() {
        let mut input = square_with(&INNER, &[[2.0, 2.0]]);
        input.points.push([2.5, 2.0]);
        assert_eq!(
            permitted(&input),
            Err(InputError::PointOutsideDomain { point: 8 })
        );
        input.points[8] = [5.0, 2.0];
        assert_eq!(
            permitted(&input),
            Err(InputError::PointOutsideDomain { point: 8 })
        );
        input.points[8] = [0.5, 2.0];
        assert_eq!(permitted(&input).unwrap().singles, vec![8]);
    }

    #[test]
    fn a_polygon_with_its_inside_seeded_and_nothing_around_is_refused() {
        let input = pslg(&SQUARE, &[&[0, 1, 2, 3]], &[[1.0, 1.0]]);
        assert_eq!(
            permitted(&input),
            Err(InputError::SegmentOutsideDomain { segment: 0 })
        );
    }

    #[test]
    fn a_triangle_gets_the_midpoint_of_its_longest_side_as_a_fourth_corner() {
        let input = pslg(&[[0.0, 0.0], [4.0, 0.0], [0.0, 2.0]], &[&[0, 1, 2]], &[]);
        let d = permitted(&input).unwrap();
        assert_eq!(d.points.len(), 4);
        assert_eq!(d.points[3], [2.0, 1.0]);
        let poly = &d.polygons[0];
        // The hypotenuse 1 → 2 (segment 1) is the longest; the midpoint splits it.
        assert_eq!(poly.corners, vec![0, 1, 3, 2]);
        assert_eq!(poly.sides, vec![0, 1, 1, 2]);
        assert_eq!(orient2d(d.points[1], d.points[2], d.points[3]), 0.0);
    }

    #[test]
    fn a_square_with_a_grid_of_seeded_square_holes_reads_every_hole() {
        // 30 × 30 holes of side 1/2 at unit spacing inside a 32 × 32 square, and a single
        // point between four of them.
        let mut input = pslg(
            &[[0.0, 0.0], [32.0, 0.0], [32.0, 32.0], [0.0, 32.0]],
            &[&[0, 1, 2, 3]],
            &[],
        );
        for gy in 0..30 {
            for gx in 0..30 {
                let (x, y) = (1.25 + gx as f64, 1.25 + gy as f64);
                let base = input.points.len() as u32;
                input
                    .points
                    .extend([[x, y], [x + 0.5, y], [x + 0.5, y + 0.5], [x, y + 0.5]]);
                input
                    .segments
                    .extend((0..4).map(|k| [base + k, base + (k + 1) % 4]));
                input.holes.push([x + 0.25, y + 0.25]);
            }
        }
        input.points.push([2.0, 2.0]);
        let d = permitted(&input).unwrap();
        assert_eq!(d.polygons.len(), 901);
        assert!(d.polygons[1..].iter().all(|p| !p.outer));
        assert_eq!(d.singles, vec![3604]);
    }

    #[test]
    fn inside_counts_crossings_exactly_at_vertex_heights() {
        let ring = SQUARE.to_vec();
        assert!(inside([2.0, 2.0], &ring));
        assert!(!inside([5.0, 0.0], &ring));
        assert!(!inside([-1.0, 4.0], &ring));
        // A ray through a vertex of a diamond counts one crossing, not two.
        let diamond = vec![[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]];
        assert!(inside([0.0, 0.0], &diamond));
        assert!(!inside([-2.0, 0.0], &diamond));
    }
}
